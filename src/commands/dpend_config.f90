!> Run configuration shared by every command: a Fortran namelist file
!> (`--config FILE`, commented examples in data/) and command-line flags that
!> override it. Groups: &pendulum (links m l g, or m1 m2 l1 l2 for two links),
!> &initial (q w, or q1 q2 w1 w2), &integration (method dt t_end save_every rtol atol
!> output_dt omega), &output (file force). Commands with more settings read further
!> groups through `check_groups` and their own namelists.
!>
!> The system is built by the model factory (dpend_model_factory) from a
!> specification: the model --model names (default: the chapter's pendulum of `links`
!> uniform rods), its parameters from the fields above and those given by name
!> (--k 40 --l0 1 for the elastic pendulum). `validate_run_config` checks the fields
!> and builds `model`; before that, `model` is not allocated.
module dpend_config
   use dpend_kinds, only: dp, i8, half_pi
   use dpend_error, only: error_t, fatal_error
   use dpend_pendulum, only: pendulum_t, finite_positive, body_general
   use dpend_model_factory, only: model_spec_t, model_spec, model_info_t, new_model, &
                                  model_catalogue, find_model, default_model
   use dpend_model, only: model_t, max_dof
   use dpend_cli, only: arg_t, parse_real, parse_int, real_str, to_str, to_lower, printable, &
      quoted
   use dpend_parse, only: read_real, read_int
   use dpend_output, only: register_input
   use dpend_os, only: path_kind, path_missing, path_file, path_directory, &
      path_other, errno_text, directory_of
   use dpend_limits, only: in_range, check_range, check_count, max_angle, max_angular_velocity, &
                           max_time, max_dt, min_rtol, min_atol, max_atol, max_omega, &
                           max_steps, default_max_steps, sci, max_support_frequency
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator, method_names
   use dpend_strings, only: canonical_name
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: run_config_t, read_run_config, apply_run_flag, validate_run_config
   public :: check_groups, run_flags_help, namelist_error
   public :: check_regular_file, set_pendulum

   !> Largest configuration file read [bytes].
   integer(i8), parameter :: max_config_bytes = 1048576_i8

   !> The lists a user may give (--m --l --q --w, namelist m l q w), in this order.
   character(len=1), parameter :: list_names(4) = ['m', 'l', 'q', 'w']

   !> Pairs (list, scalar) of two forms of one quantity in a namelist group.
   character(len=2), parameter :: scan_forms(2, 8) = reshape([character(len=2) :: &
      'm', 'm1', 'm', 'm2', 'l', 'l1', 'l', 'l2', 'q', 'q1', 'q', 'q2', 'w', 'w1', 'w', 'w2'], &
      [2, 8])
   !> What ends a token of a namelist (besides quotes, '!' and '%').
   character(len=*), parameter :: scan_delims = ' ,=/'//achar(9)//achar(10)//achar(13)
   character(len=*), parameter :: printable_ascii = ' !"#$%&''()*+,-./0123456789:;<=>?@' &
      //'ABCDEFGHIJKLMNOPQRSTUVWXYZ[\]^_`abcdefghijklmnopqrstuvwxyz{|}~'
   !> Keys of one group compared for repeats (more: not compared).
   integer, parameter :: max_scan_keys = 1024

   !> Where the strict scan of a namelist file stands (`check_number_tokens`).
   type :: nml_scan_t
      character(len=:), allocatable :: pre    !! message prefix
      character(len=:), allocatable :: group  !! the current group, lower case
      character(len=:), allocatable :: key    !! the current key, without blanks
      integer :: line = 1                     !! the current line
      logical :: inside = .false.             !! within a group
      logical :: wants_value = .false.        !! a key was read, its value not yet
      integer :: n_values = 0                 !! values of the current key so far
      integer :: n_keys = 0                   !! keys of the current group so far
      character(len=64) :: keys(max_scan_keys) = ''   !! them
      integer :: key_lines(max_scan_keys) = 0         !! and their lines
   end type nml_scan_t

   !> Everything a single run needs (SI units, angles in rad from the horizontal x axis).
   !> Per-link values are kept for max_dof links; the first `links` are used.
   type :: run_config_t
      integer :: links = 2                     !! number of links N
      real(dp) :: m(max_dof) = 1.0_dp          !! link masses [kg]
      real(dp) :: l(max_dof) = 1.0_dp          !! link lengths [m]
      real(dp) :: g = 9.8_dp                   !! gravitational acceleration [m/s²]
      real(dp) :: q(max_dof) = 0.0_dp          !! initial angles [rad]
      real(dp) :: w(max_dof) = 0.0_dp          !! initial angular velocities [rad/s]
      !> Lengths of the lists given for m, l, q, w (0: none given); each must be N.
      integer :: list_size(4) = 0
      !> Joint damping c_i [N m s] (issue 13) and the number of values given (0: none).
      real(dp) :: damping(max_dof) = 0.0_dp
      integer :: damping_size = 0
      !> The support's motion x_A = a_x cos(ω t + φ_x), y_A = a_y cos(ω t + φ_y):
      !> amplitudes (a_x, a_y) [m], ω [rad/s], phases (φ_x, φ_y) [rad]; zero: fixed pin.
      real(dp) :: support_amplitude(2) = 0.0_dp
      real(dp) :: support_frequency = 0.0_dp
      real(dp) :: support_phase(2) = 0.0_dp
      class(model_t), allocatable :: model     !! the system, built by validate_run_config
      character(len=:), allocatable :: method  !! integrator name
      real(dp) :: dt = 1e-3_dp                 !! step (initial step for adaptive) [s]
      real(dp) :: t_end = 10.0_dp              !! end time [s]
      integer :: save_every = 10               !! keep every N-th step
      real(dp) :: rtol = 1e-9_dp               !! relative tolerance (adaptive methods)
      real(dp) :: atol = 1e-12_dp              !! absolute tolerance (adaptive methods)
      real(dp) :: output_dt = 0.0_dp           !! sample at k·output_dt (0: every save_every steps) [s]
      real(dp) :: omega = 20.0_dp              !! Tao's binding constant [1/s]
      integer(i8) :: max_steps = default_max_steps !! most accepted steps of one
                                               !! integration (adaptive methods)
      character(len=:), allocatable :: output  !! output file
      logical :: force = .false.               !! overwrite an existing output file
      !> The per-link flags given so far (' --m1 --q '), so that two forms of one
      !> quantity on the command line are refused (`apply_run_flag`).
      character(len=:), allocatable :: flags_seen
      !> The model (--model; unset: the factory's default, the chapter's pendulum),
      !> the parameters of models other than the pendulum given by name (--k 40), and
      !> the specification the model was built from (validate_run_config).
      character(len=:), allocatable :: model_name
      type(model_spec_t) :: extra
      type(model_spec_t) :: spec
      !> Issue 25 (front end): the scalar keys a namelist file gave (' q1 save_every '),
      !> so that a command refuses a fixed value it sweeps or two forms of one setting.
      character(len=:), allocatable :: nml_given
      !> The links' body (issue 26): '' (not given: uniform rods unless --com or
      !> --inertia), 'rod' or 'point' (--body / &pendulum body)
      character(len=:), allocatable :: body
   contains
      !> Initial angles q(1:N) [rad].
      procedure :: q0 => run_q0
      !> Initial angular velocities w(1:N) [rad/s].
      procedure :: w0 => run_w0
      !> The double pendulum's parameters (links 1 and 2, g).
      procedure :: pendulum => run_pendulum
   end type run_config_t

contains

   pure function run_q0(self) result(q)
      class(run_config_t), intent(in) :: self  !! configuration
      real(dp), allocatable :: q(:)
      q = self%q(:self%links)
   end function run_q0

   pure function run_w0(self) result(w)
      class(run_config_t), intent(in) :: self  !! configuration
      real(dp), allocatable :: w(:)
      w = self%w(:self%links)
   end function run_w0

   pure function run_pendulum(self) result(par)
      class(run_config_t), intent(in) :: self  !! configuration
      type(pendulum_t) :: par
      par = pendulum_t(m1=self%m(1), m2=self%m(2), l1=self%l(1), l2=self%l(2), g=self%g)
      ! links other than uniform rods (issue 26): com and inertia as the model was built
      if (self%spec%find('com') > 0 .or. self%spec%find('inertia') > 0) then
         block
            real(dp), allocatable :: d(:), ic(:)
            d = 0.5_dp*self%l(1:2)
            if (self%spec%find('com') > 0) d = self%spec%get('com', d)
            ic = [0.0_dp, 0.0_dp]
            if (self%spec%find('inertia') > 0) then
               ic = self%spec%get('inertia', ic)
            else   ! the model was built: l is within its range, m l²/12 finite
               ic = self%m(1:2)*self%l(1:2)**2/12.0_dp
            end if
            if (size(d) == 2 .and. size(ic) == 2) then
               par%body = body_general
               par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
            end if
         end block
      end if
   end function run_pendulum

   !> Set the parameters of the double pendulum (two links) from `par`.
   pure subroutine set_pendulum(cfg, par)
      type(run_config_t), intent(inout) :: cfg  !! configuration
      type(pendulum_t), intent(in) :: par       !! parameters
      cfg%m(1:2) = [par%m1, par%m2]; cfg%l(1:2) = [par%l1, par%l2]; cfg%g = par%g
   end subroutine set_pendulum

   !> Check that `filename` is a namelist file made only of the groups `known`
   !> (names without '&'), each at most once, and nothing outside them but blanks
   !> and '!' comments. Refused, with one line naming the file and the problem: a
   !> missing, unreadable or too large file, a directory, a FIFO or device (never
   !> opened, so nothing blocks), a binary file (NUL, control bytes, not UTF-8),
   !> text outside a group (e.g. a key before any group), an unknown, repeated or
   !> unclosed group, and a file without any group. Bytes of the file are never
   !> echoed except as printable ASCII.
   subroutine check_groups(filename, known, error)
      character(len=*), intent(in) :: filename          !! the namelist file
      character(len=*), intent(in) :: known(:)          !! accepted group names
      type(error_t), allocatable, intent(out) :: error  !! why the file is refused
      character(len=:), allocatable :: pre, text
      pre = "invalid --config '"//printable(filename)//"': "
      call check_regular_file(filename, pre, error)
      if (allocated(error)) return
      call read_config_bytes(filename, pre, text, error)
      if (allocated(error)) return
      call check_text_bytes(text, pre, error)
      if (allocated(error)) return
      call check_group_structure(text, known, pre, error)
      if (allocated(error)) return
      call check_number_tokens(text, pre, error)
   end subroutine check_groups

   !> The group &model of a namelist file (checked by `check_groups`): `name = 'elastic'`
   !> and the model's parameters by name (`k = 40, l0 = 1`), read by name since every
   !> model has its own: the name into `cfg%model_name`, the parameters into
   !> `cfg%extra` (the pendulum's keep their groups: &pendulum). The factory checks
   !> them against the model (validate_run_config).
   subroutine read_model_group(filename, cfg, error)
      character(len=*), intent(in) :: filename          !! the namelist file
      type(run_config_t), intent(inout) :: cfg          !! updated
      type(error_t), allocatable, intent(out) :: error  !! unreadable or invalid
      character(len=:), allocatable :: text, body, key, pre
      integer :: i, j, k, eq
      pre = "invalid --config '"//printable(filename)//"': &model: "
      call read_config_bytes(filename, pre, text, error)
      if (allocated(error)) return
      text = without_comments(text)
      i = index(to_lower(text), '&model')
      if (i == 0) return
      j = index(text(i:), '/')
      if (j == 0) return          ! check_groups refused an open group
      body = text(i + 6:i + j - 2)
      do   ! key = value[, value ...], up to the next key or the end
         eq = index(body, '=')
         if (eq == 0) exit
         key = to_lower(stripped(body(:eq - 1)))
         body = body(eq + 1:)
         k = next_key(body)
         if (key == 'name') then
            cfg%model_name = canonical_name(unquoted(body(:k - 1)), model_names())
         else if (is_model_parameter(key)) then
            call parse_values(key, body(:k - 1))
            if (allocated(error)) return
         else
            call fatal_error(error, pre//"'"//printable(key)//"' is not a key (accepted: " &
                             //'name and the parameters of the models: dpend models)')
            return
         end if
         body = body(k:)
      end do
   contains
      !> Where the next `key =` starts in `s` (len(s) + 1 if none).
      integer function next_key(s)
         character(len=*), intent(in) :: s
         integer :: e, b
         next_key = len(s) + 1
         e = index(s, '=')
         if (e == 0) return
         b = e - 1
         do while (b > 0)
            if (s(b:b) /= ' ' .and. s(b:b) /= achar(9) .and. s(b:b) /= achar(10) .and. &
                s(b:b) /= achar(13)) exit
            b = b - 1
         end do
         do while (b > 0)
            if (index(' ,'//achar(9)//achar(10)//achar(13), s(b:b)) > 0) exit
            b = b - 1
         end do
         next_key = b + 1
      end function next_key
      !> Text between quotes (or the trimmed text).
      function unquoted(s) result(t)
         character(len=*), intent(in) :: s
         character(len=:), allocatable :: t
         t = stripped(s)
         if (len(t) > 0) then
            if (t(len(t):len(t)) == ',') t = stripped(t(:len(t) - 1))
         end if
         if (len(t) >= 2) then
            if (index('''"', t(1:1)) > 0 .and. t(len(t):len(t)) == t(1:1)) t = t(2:len(t) - 1)
         end if
      end function unquoted
      !> Numbers separated by commas or blanks, through the strict parser.
      subroutine parse_values(name, s)
         character(len=*), intent(in) :: name, s
         real(dp) :: v(max_dof)
         integer :: n, a, b
         character(len=*), parameter :: seps = ' ,'//achar(9)//achar(10)//achar(13)
         n = 0
         a = 1
         do
            do while (a <= len(s))
               if (index(seps, s(a:a)) == 0) exit
               a = a + 1
            end do
            if (a > len(s)) exit
            b = a
            do while (b <= len(s))
               if (index(seps, s(b:b)) > 0) exit
               b = b + 1
            end do
            if (n == max_dof) then
               call fatal_error(error, pre//name//': more than '//to_str(max_dof)//' values')
               return
            end if
            n = n + 1
            call parse_real(s(a:b - 1), '&model '//name, v(n), error)
            if (allocated(error)) then
               error%message = pre(:len(pre) - 8)//error%message
               return
            end if
            a = b
         end do
         call cfg%extra%set(name, v(:n))
      end subroutine parse_values
   end subroutine read_model_group

   !> `s` without leading and trailing blanks, tabs and line ends.
   pure function stripped(s) result(t)
      character(len=*), intent(in) :: s  !! text
      character(len=:), allocatable :: t
      character(len=*), parameter :: white = ' '//achar(9)//achar(10)//achar(13)
      integer :: a, b
      a = verify(s, white)
      b = verify(s, white, back=.true.)
      if (a == 0) then
         t = ''
      else
         t = s(a:b)
      end if
   end function stripped

   !> `text` with every '!' comment outside quotes removed (to the line end).
   pure function without_comments(text) result(t)
      character(len=*), intent(in) :: text  !! namelist text
      character(len=:), allocatable :: t
      character :: quote
      integer :: i
      t = ''
      quote = ' '
      i = 1
      do while (i <= len(text))
         if (quote /= ' ') then
            if (text(i:i) == quote) quote = ' '
         else if (text(i:i) == "'" .or. text(i:i) == '"') then
            quote = text(i:i)
         else if (text(i:i) == '!') then
            do while (i <= len(text))
               if (text(i:i) == achar(10)) exit
               i = i + 1
            end do
            cycle
         end if
         t = t//text(i:i)
         i = i + 1
      end do
   end function without_comments

   !> Read the keys and values of every group strictly, before the namelist read
   !> (which resolves conflicts silently): refused, in one line naming the line, are
   !> the component syntax '%' (`&pendulum%m1 = 2 /` is otherwise ignored), a key
   !> given twice in one group (the last would win), two forms of one quantity in one
   !> group (`m` with `m1`/`m2`, `l`, `q`, `w` alike: the list would win), and a value
   !> that starts like a number but is not one of the strict grammar (`dpend_parse`:
   !> '1;2', a 1,000-digit mantissa beyond the largest double, 'nan'; a repeat count
   !> `r*value` is checked on both sides), and a second value for a key that takes one
   !> (`dt = 0.001 0.002`: the read would keep the first silently; `is_array_key`).
   !> A word (or '.word.') for a key that is not a text must be a whole logical
   !> (`logical_word`: 'false.' would read as .false.). Names and quoted strings are
   !> left to the namelist read.
   subroutine check_number_tokens(text, pre, error)
      character(len=*), intent(in) :: text              !! the file (its groups checked)
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! the first problem
      type(nml_scan_t) :: s
      integer :: i, j
      s%pre = pre
      s%group = ''
      s%key = ''
      i = 1
      do while (i <= len(text))
         select case (text(i:i))
         case (achar(10))
            s%line = s%line + 1
            i = i + 1
         case ("'", '"')                       ! a string: skip to its closing quote
            call scan_string(s, text, i, error)
            if (allocated(error)) return
         case ('!')                            ! a comment: skip to the line end
            j = index(text(i:), achar(10))
            if (j == 0) exit
            i = i + j - 1
         case ('&', '$')
            j = i + 1
            do while (j <= len(text))
               if (index(scan_delims//'%!', text(j:j)) > 0) exit
               j = j + 1
            end do
            s%group = to_lower(text(i + 1:j - 1))
            s%inside = s%group /= 'end'
            s%n_keys = 0
            s%n_values = 0
            i = j
         case ('%')
            call scan_refuse(s, "'%' (component syntax, as in &pendulum%m1) is not " &
                             //'accepted; write the keys inside the group: &pendulum m1 = 2 /', &
                             error)
            return
         case ('/')
            if (s%inside .and. s%wants_value) then
               call scan_refuse(s, scan_key_text(s)//'no value (a key needs one: the ' &
                                //'namelist read would keep the default silently)', error)
               return
            end if
            s%inside = .false.
            i = i + 1
         case default
            if (index(scan_delims, text(i:i)) > 0 .or. .not. s%inside) then
               i = i + 1
               cycle
            end if
            call scan_token(s, text, i, error)
            if (allocated(error)) return
         end select
      end do
   end subroutine check_number_tokens

   !> The quoted string at text(i:) (`check_number_tokens`): not longer than its key's
   !> variable (the read would cut it short silently), one value of the key; `i` moves
   !> past its closing quote.
   subroutine scan_string(s, text, i, error)
      type(nml_scan_t), intent(inout) :: s              !! scan state
      character(len=*), intent(in) :: text              !! the file
      integer, intent(inout) :: i                       !! the opening quote; then past
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: j
      j = index(text(i + 1:), text(i:i))
      if (j == 0) j = len(text) - i + 1
      ! longer than the key's variable: the namelist read would cut it short
      ! silently (a warning of the runtime at most)
      if (s%inside .and. j - 1 > string_length(s%group, s%key)) then
         call scan_refuse(s, scan_key_text(s)//'a text of '//to_str(j - 1)// &
                          ' characters; at most '//to_str(string_length(s%group, s%key)), error)
         return
      end if
      ! a quoted value for a key that takes a number or a logical: gfortran reads
      ! block = "1" as 1; the whole token must be the value
      if (s%inside .and. len(s%key) > 0) then
         if (.not. is_string_key(s%key)) then
            call scan_refuse(s, scan_key_text(s)//'a quoted text (' &
                             //printable(text(i:min(i + j, i + 40, len(text)))) &
                             //') for a key that takes a number or a logical (remove the ' &
                             //'quotes)', error)
            return
         end if
      end if
      if (s%inside) call scan_count_values(s, 1, error)
      if (allocated(error)) return
      s%wants_value = .false.
      s%line = s%line + count_lf(text(i:i + j))
      i = i + j + 1
   end subroutine scan_string

   !> The token at text(i:) inside a group (`check_number_tokens`): a key (followed
   !> by '=') or a value of the current key; `i` moves past it.
   subroutine scan_token(s, text, i, error)
      type(nml_scan_t), intent(inout) :: s              !! scan state
      character(len=*), intent(in) :: text              !! the file
      integer, intent(inout) :: i                       !! the token's start; then past
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: tok
      integer :: j, k, depth
      ! a token: up to a delimiter outside parentheses (subscripts 'q(1:3, 1)')
      j = i
      depth = 0
      do while (j <= len(text))
         if (text(j:j) == '(') depth = depth + 1
         if (text(j:j) == ')') depth = depth - 1
         if (depth <= 0 .and. index(scan_delims//"!'"//'"%', text(j:j)) > 0) exit
         if (text(j:j) == achar(10)) exit
         j = j + 1
      end do
      tok = text(i:j - 1)
      i = j
      ! a key when the next character that is not a blank is '='
      k = verify(text(j:), ' '//achar(9)//achar(13)//achar(10))
      if (k > 0) k = j + k - 1
      if (k > 0) then
         if (text(k:k) == '=') then
            if (s%wants_value) then
               call scan_refuse(s, scan_key_text(s)//'no value (a key needs one: the ' &
                                //'namelist read would keep the default silently)', error)
               return
            end if
            call scan_add_key(s, to_lower(tok), error)
            if (allocated(error)) return
            s%wants_value = .true.
            return
         end if
      end if
      s%wants_value = .false.
      if (verify(tok, printable_ascii) /= 0) then
         call scan_refuse(s, scan_key_text(s)//quoted(tok)//' holds a byte that is not ' &
                          //'printable ASCII (quote a text; a number is ASCII digits)', error)
         return
      end if
      if (len(tok) > string_length(s%group, s%key) .and. is_string_key(s%key)) then
         call scan_refuse(s, scan_key_text(s)//'a text of '//to_str(len(tok))// &
                          ' characters; at most '//to_str(string_length(s%group, s%key)), error)
         return
      end if
      call scan_check_value(s, tok, error)
   end subroutine scan_token

   !> Record key `k` of the current group; refuse a repeat or a second form of one
   !> quantity (`scan_forms`).
   subroutine scan_add_key(s, k, error)
      type(nml_scan_t), intent(inout) :: s              !! scan state
      character(len=*), intent(in) :: k                 !! the key, lower case
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: n, p
      character(len=:), allocatable :: b, base
      s%key = ''
      s%n_values = 0
      do n = 1, len(k)            ! without blanks: 'q (1:3, 1)' is 'q(1:3,1)'
         if (index(' '//achar(9), k(n:n)) == 0) s%key = s%key//k(n:n)
      end do
      p = index(s%key, '(')
      base = s%key
      if (p > 0) base = s%key(:p - 1)
      do n = 1, s%n_keys
         b = trim(s%keys(n))
         if (index(b, '(') > 0) b = b(:index(b, '(') - 1)
         if (trim(s%keys(n)) == s%key .or. (b == base .and. (p == 0 .or. &
                                                           index(s%keys(n), '(') == 0))) then
            call scan_refuse(s, "key '"//printable(s%key)//"' of &"//printable(s%group)// &
                             ' is given twice (also at line '//to_str(s%key_lines(n))// &
                             '); give each key once', error)
            return
         end if
         do p = 1, size(scan_forms, 2)
            if ((b == trim(scan_forms(1, p)) .and. base == trim(scan_forms(2, p))) .or. &
                (b == trim(scan_forms(2, p)) .and. base == trim(scan_forms(1, p)))) then
               call scan_refuse(s, "'"//trim(scan_forms(1, p))//"' (one value per link) and '" &
                                //trim(scan_forms(2, p))//"' are two forms of one quantity " &
                                //'in &'//printable(s%group)//' (the other at line '// &
                                to_str(s%key_lines(n))//'); give one of them', error)
               return
            end if
         end do
      end do
      if (s%n_keys == max_scan_keys) return
      s%n_keys = s%n_keys + 1
      s%keys(s%n_keys) = s%key
      s%key_lines(s%n_keys) = s%line
   end subroutine scan_add_key

   !> Refuse a value that starts like a number but is not one (also r*value), or a
   !> word that is not a logical for a key that is not a text.
   subroutine scan_check_value(s, t, error)
      type(nml_scan_t), intent(inout) :: s              !! scan state
      character(len=*), intent(in) :: t                 !! the value's token
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: why, v
      integer :: star, r
      real(dp) :: x
      logical :: word
      v = t
      star = index(t, '*')
      if (star > 0) then
         call read_int(t(:star - 1), r, why)
         if (len(why) == 0 .and. r < 1) why = 'is not a repeat count >= 1'
         if (len(why) > 0) then
            call scan_refuse(s, scan_key_text(s)//quoted(t(:star - 1))//' (repeat count of ' &
                             //quoted(t)//') '//why, error)
            return
         end if
         v = t(star + 1:)
         call scan_count_values(s, r, error)
      else
         call scan_count_values(s, 1, error)
      end if
      if (allocated(error)) return
      if (len(v) == 0) return                      ! 'r*': r null values
      ! a word (also '.word.') for a key that is not a text: a logical, the whole token
      ! (t, f, .true., false, ...; 'false.' or '.tx' would read as a logical too)
      word = index('0123456789+-.', v(1:1)) == 0 .and. .not. non_finite(v)
      if (len(v) >= 2) word = word .or. (v(1:1) == '.' .and. index('0123456789', v(2:2)) == 0)
      if (word) then
         if (.not. is_string_key(s%key) .and. .not. logical_word(v)) &
            call scan_refuse(s, scan_key_text(s)//quoted(v)//' is not a number or a ' &
                             //'logical (t, f, true, false, .t., .f., .true., .false.; ' &
                             //'quote a text)', error)
         return
      end if
      call read_real(v, x, why)
      if (len(why) > 0) call scan_refuse(s, scan_key_text(s)//quoted(v)//' '//why, error)
   end subroutine scan_check_value

   !> Count `r` more values of the current key; refuse a second one for a key that
   !> takes one value (a scalar: the namelist read would keep the first silently).
   subroutine scan_count_values(s, r, error)
      type(nml_scan_t), intent(inout) :: s              !! scan state
      integer, intent(in) :: r                          !! values
      type(error_t), allocatable, intent(out) :: error  !! a second value for a scalar
      if (len(s%key) == 0) return
      s%n_values = s%n_values + r
      if (s%n_values > 1 .and. .not. is_array_key(s%group, s%key)) &
         call scan_refuse(s, scan_key_text(s)//to_str(s%n_values)//' values for a key that ' &
                          //'takes one (the namelist read would keep the first silently); ' &
                          //'give one value', error)
   end subroutine scan_count_values

   !> "key 'dt': " for the current key ('' before the first key).
   function scan_key_text(s) result(t)
      type(nml_scan_t), intent(in) :: s  !! scan state
      character(len=:), allocatable :: t
      t = ''
      if (len(s%key) > 0) t = "key '"//printable(s%key)//"': "
   end function scan_key_text

   !> The refusal: the file, the line, `msg`.
   subroutine scan_refuse(s, msg, error)
      type(nml_scan_t), intent(in) :: s                 !! scan state
      character(len=*), intent(in) :: msg               !! what is wrong
      type(error_t), allocatable, intent(out) :: error  !! the refusal
      call fatal_error(error, s%pre//'line '//to_str(s%line)//': '//msg)
   end subroutine scan_refuse

   !> The length of the text variable read for `k` of group `g` (the namelists of
   !> dpend_config, dpend_sweep_config, dpend_study_config; names 16 characters,
   !> case names 32, method 64 in &integration, file names 1024).
   pure integer function string_length(g, k) result(n)
      character(len=*), intent(in) :: g  !! group
      character(len=*), intent(in) :: k  !! key
      character(len=:), allocatable :: b
      b = k
      if (index(b, '(') > 0) b = b(:index(b, '(') - 1)
      select case (b)
      case ('file', 'ic_file', 'ic_dataset'); n = 1024
      case ('name'); n = 1024                         ! &model: read by dpend itself
      case ('case_name', 'order_case', 'drift_case', 'ro_case', 'tao_case'); n = 32
      case ('method')
         n = merge(64, 16, g == 'integration')
      case default; n = 16
      end select
   end function string_length

   !> A logical of a namelist, the whole word: t, f, true, false, or one of them between
   !> two periods (.t., .false.; any case). 'false.' or '.true' is not one.
   pure logical function logical_word(w)
      character(len=*), intent(in) :: w  !! a word
      character(len=:), allocatable :: u
      u = to_lower(w)
      if (len(u) >= 3) then
         if (u(1:1) == '.' .and. u(len(u):len(u)) == '.') u = u(2:len(u) - 1)
      end if
      logical_word = u == 't' .or. u == 'f' .or. u == 'true' .or. u == 'false'
   end function logical_word

   !> Whether `k` is read into a text variable (string_length applies).
   pure logical function is_string_key(k)
      character(len=*), intent(in) :: k  !! key
      character(len=:), allocatable :: b
      b = k
      if (index(b, '(') > 0) b = b(:index(b, '(') - 1)
      select case (b)
      case ('file', 'ic_file', 'ic_dataset', 'name', 'case_name', 'order_case', &
            'drift_case', 'ro_case', 'tao_case', 'method', 'ref_method', 'check_method', &
            'ro_method', 'tao_method', 'axis1', 'axis2', 'ic_angles', 'time_unit', &
            'stop_at', 'indicator', 'device', 'body')
         is_string_key = .true.
      case default
         is_string_key = .false.
      end select
   end function is_string_key

   !> inf, infinity, nan (any case, signed): a word the number check still reads.
   pure logical function non_finite(t)
      character(len=*), intent(in) :: t  !! a token
      character(len=:), allocatable :: u
      u = to_lower(t)
      if (u(1:1) == '+' .or. u(1:1) == '-') u = u(2:)
      non_finite = u == 'inf' .or. u == 'infinity' .or. u == 'nan'
   end function non_finite

   !> Line ends in `t`.
   pure integer function count_lf(t)
      character(len=*), intent(in) :: t  !! text
      integer :: n
      count_lf = 0
      do n = 1, len(t)
         if (t(n:n) == achar(10)) count_lf = count_lf + 1
      end do
   end function count_lf

   !> Whether key `k` of namelist group `g` takes several values: an array of the
   !> namelists of dpend_config (&pendulum m l damping support_amplitude support_phase,
   !> &initial q w), dpend_study_config (&study case_* and the method lists) or an
   !> element with a subscript ('q(2) = 1 2' fills q(2) and q(3)). The parameters of
   !> &model are checked by the factory (one value for a scalar parameter).
   pure logical function is_array_key(g, k)
      character(len=*), intent(in) :: g  !! group name, lower case
      character(len=*), intent(in) :: k  !! key, lower case, without blanks
      if (index(k, '(') > 0 .or. g == 'model') then
         is_array_key = .true.
         return
      end if
      select case (g)
      case ('pendulum')
         select case (k)
         case ('m', 'l', 'damping', 'support_amplitude', 'support_phase', 'com', 'inertia')
            is_array_key = .true.
         case default
            is_array_key = .false.
         end select
      case ('initial')
         is_array_key = k == 'q' .or. k == 'w'
      case ('study')
         select case (k)
         case ('method', 'h_min', 'h_max', 'rtol_min', 'rtol_max', 'ro_method', 'ro_dt', &
               'tao_method')
            is_array_key = .true.
         case default
            is_array_key = index(k, 'case_') == 1
         end select
      case default
         is_array_key = .false.
      end select
   end function is_array_key

   !> Refuse an input path that is not (a link to) a regular file, before anything
   !> opens it (a FIFO would block the open); messages start with `pre`.
   subroutine check_regular_file(filename, pre, error)
      character(len=*), intent(in) :: filename          !! the path
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! not a regular file
      integer :: kind
      if (len_trim(filename) == 0) then
         call fatal_error(error, pre//'empty file name')
         return
      end if
      kind = path_kind(filename, follow=.true.)
      select case (kind)
      case (path_file)
         call register_input(filename)   ! an output never replaces it (dpend_output)
      case (path_missing)
         call fatal_error(error, pre//'no such file')
      case (path_directory)
         call fatal_error(error, pre//'is a directory, not a file')
      case (path_other)
         call fatal_error(error, pre//'is not a regular file (a FIFO, socket or device)')
      case default
         call fatal_error(error, pre//'cannot be examined: '//errno_text(-kind))
      end select
   end subroutine check_regular_file

   !> The whole file as one string (at most max_config_bytes).
   subroutine read_config_bytes(filename, pre, text, error)
      character(len=*), intent(in) :: filename               !! a regular file
      character(len=*), intent(in) :: pre                    !! message prefix
      character(len=:), allocatable, intent(out) :: text     !! its bytes
      type(error_t), allocatable, intent(out) :: error       !! unreadable or too large
      integer :: unit, stat
      integer(i8) :: bytes
      character(len=256) :: msg
      text = ''
      open (newunit=unit, file=filename, status='old', action='read', access='stream', &
            form='unformatted', iostat=stat, iomsg=msg)
      if (stat /= 0) then
         call fatal_error(error, pre//'cannot be read ('//reason(msg)//')')
         return
      end if
      inquire (unit=unit, size=bytes)
      if (bytes > max_config_bytes) then
         call fatal_error(error, pre//'is '//to_str(bytes)//' bytes; a namelist file '// &
                          'has at most '//to_str(max_config_bytes)//' bytes')
      else if (bytes > 0) then
         deallocate (text)
         allocate (character(len=int(bytes)) :: text)
         read (unit, iostat=stat, iomsg=msg) text
         if (stat /= 0) call fatal_error(error, pre//'cannot be read ('//reason(msg)//')')
      end if
      close (unit)
   contains
      function reason(m) result(r)
         character(len=*), intent(in) :: m
         character(len=:), allocatable :: r
         integer :: colon
         ! the runtime's message ends with the system's reason after the last ': '
         colon = index(m, ': ', back=.true.)
         r = printable(trim(m(colon + 1:)))
         if (colon > 0) r = printable(trim(m(colon + 2:)))
         if (len(r) == 0) r = 'I/O error'
      end function reason
   end subroutine read_config_bytes

   !> Refuse bytes that are not text: NUL, control bytes other than blanks and line
   !> ends, and anything that is not UTF-8.
   subroutine check_text_bytes(text, pre, error)
      character(len=*), intent(in) :: text              !! the file
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! the first non-text byte
      integer :: i, c, follow, k, line
      character(len=*), parameter :: hdf5_signature = char(137)//'HDF'//achar(13)//achar(10)
      if (len(text) >= len(hdf5_signature)) then
         if (text(:len(hdf5_signature)) == hdf5_signature) then
            call fatal_error(error, pre//'is an HDF5 file, not a namelist text file '// &
                             '(binary data)')
            return
         end if
      end if
      i = 1
      line = 1
      do while (i <= len(text))
         c = iachar(text(i:i))
         if (c == 10) line = line + 1
         follow = -1
         if (c >= 32 .and. c < 127) then
            follow = 0
         else if (c == 9 .or. c == 10 .or. c == 11 .or. c == 12 .or. c == 13) then
            follow = 0
         else if (c >= 194 .and. c <= 223) then
            follow = 1
         else if (c >= 224 .and. c <= 239) then
            follow = 2
         else if (c >= 240 .and. c <= 244) then
            follow = 3
         end if
         if (follow > 0) then
            if (i + follow > len(text)) then
               follow = -1
            else
               do k = i + 1, i + follow
                  if (iachar(text(k:k)) < 128 .or. iachar(text(k:k)) > 191) follow = -1
               end do
            end if
         end if
         if (follow < 0) then
            call fatal_error(error, pre//'not a text file (binary data: byte '// &
                             hex(c)//' at line '//to_str(line)//')')
            return
         end if
         i = i + 1 + follow
      end do
   contains
      function hex(byte) result(s)
         integer, intent(in) :: byte
         character(len=:), allocatable :: s
         character(len=2) :: buf
         write (buf, '(z2.2)') byte
         s = '0x'//buf
      end function hex
   end subroutine check_text_bytes

   !> Refuse text outside the groups, unknown, repeated and unclosed groups, and a
   !> file without a group. Knows namelist syntax: quoted strings, '!' comments,
   !> groups '&name ... /' (or '&end', and '$' for '&').
   subroutine check_group_structure(text, known, pre, error)
      character(len=*), intent(in) :: text              !! the file (checked bytes)
      character(len=*), intent(in) :: known(:)          !! accepted group names
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! the first problem
      character(len=32) :: seen(size(known))   ! each group at most once, all known
      character(len=:), allocatable :: group, name
      character(len=1) :: c, quote
      character(len=1), parameter :: lf = achar(10)
      integer :: i, j, line, group_line, n_seen
      logical :: inside
      n_seen = 0
      inside = .false.
      quote = ' '
      group = ''
      group_line = 0
      line = 1
      i = 1
      do while (i <= len(text))
         c = text(i:i)
         if (c == lf) line = line + 1
         if (inside .and. quote /= ' ') then
            if (c == quote) quote = ' '
            i = i + 1
            cycle
         end if
         if (c == '!') then        ! a comment, to the end of the line
            j = index(text(i:), lf)
            if (j == 0) exit
            i = i + j - 1
            cycle
         end if
         if (c == '&' .or. c == '$') then
            j = i + 1
            do while (j <= len(text))
               if (.not. is_name_char(text(j:j))) exit
               j = j + 1
            end do
            name = to_lower(text(i + 1:j - 1))
            if (inside) then
               if (name /= 'end') then
                  call fatal_error(error, pre//'group &'//group//' (line '// &
                                   to_str(group_line)//") is not closed with '/' before "// &
                                   c//printable(name)//' (line '//to_str(line)//')')
                  return
               end if
               inside = .false.
            else if (len(name) == 0) then
               call fatal_error(error, pre//"'"//c//"' without a group name at line "// &
                                to_str(line))
               return
            else if (name == 'end') then
               call fatal_error(error, pre//c//'end at line '//to_str(line)// &
                                ' closes no group')
               return
            else if (.not. any(known == name)) then
               call fatal_error(error, pre//'unknown namelist group &'//printable(name)// &
                                ' at line '//to_str(line)//' (accepted: &'//join(known)//')')
               return
            else if (any(seen(:n_seen) == name)) then
               call fatal_error(error, pre//'group &'//name//' appears twice (again at line '// &
                                to_str(line)//'); give each group once')
               return
            else
               n_seen = n_seen + 1
               seen(n_seen) = name
               group = name
               group_line = line
               inside = .true.
            end if
            i = j
            cycle
         end if
         if (inside) then
            if (c == "'" .or. c == '"') quote = c
            if (c == '/') inside = .false.
         else if (.not. is_blank(c)) then
            j = i
            do while (j <= len(text))
               if (is_blank(text(j:j))) exit
               j = j + 1
            end do
            call fatal_error(error, pre//"'"//printable(text(i:min(j - 1, i + 23)))// &
                             "' at line "//to_str(line)//' is outside any namelist group '// &
                             '(keys go between &group and /)')
            return
         end if
         i = i + 1
      end do
      if (inside) then
         call fatal_error(error, pre//'group &'//group//' (line '//to_str(group_line)// &
                          ") is not closed with '/'")
      else if (n_seen == 0) then
         call fatal_error(error, pre//'holds no namelist group (accepted: &'//join(known)//')')
      end if
   contains
      pure logical function is_name_char(ch)
         character(len=1), intent(in) :: ch
         is_name_char = (ch >= 'a' .and. ch <= 'z') .or. (ch >= 'A' .and. ch <= 'Z') .or. &
                        (ch >= '0' .and. ch <= '9') .or. ch == '_'
      end function is_name_char
      pure logical function is_blank(ch)
         character(len=1), intent(in) :: ch
         is_blank = ch == ' ' .or. (iachar(ch) >= 9 .and. iachar(ch) <= 13)
      end function is_blank
      pure function join(list) result(s)
         character(len=*), intent(in) :: list(:)
         character(len=:), allocatable :: s
         integer :: k
         s = trim(list(1))
         do k = 2, size(list)
            s = s//' &'//trim(list(k))
         end do
      end function join
   end subroutine check_group_structure

   !> The message for a failed namelist read, naming the group and the offending key.
   function namelist_error(filename, group, iomsg) result(msg)
      character(len=*), intent(in) :: filename  !! file
      character(len=*), intent(in) :: group     !! group name
      character(len=*), intent(in) :: iomsg     !! the runtime's message
      character(len=:), allocatable :: msg
      msg = "invalid config '"//printable(filename)//"' in &"//group//': '//trim(iomsg)
   end function namelist_error

   !> Read the groups of a run configuration present in `filename` into `cfg`.
   subroutine read_run_config(filename, cfg, error, extra_groups)
      character(len=*), intent(in) :: filename               !! namelist file
      type(run_config_t), intent(inout) :: cfg               !! updated from the file
      type(error_t), allocatable, intent(out) :: error       !! unreadable or invalid
      character(len=*), intent(in), optional :: extra_groups(:) !! groups of the command
      real(dp) :: m1, m2, l1, l2, g, q1, q2, w1, w2, dt, t_end, rtol, atol, output_dt, omega
      real(dp) :: m(max_dof), l(max_dof), q(max_dof), w(max_dof), damping(max_dof)
      real(dp) :: support_amplitude(2), support_frequency, support_phase(2)
      real(dp) :: com(max_dof), inertia(max_dof)
      character(len=16) :: body
      real(dp), parameter :: unset = -huge(1.0_dp)   ! marks list entries not given
      integer :: save_every, unit, stat, n_extra, i, links
      integer(i8) :: max_steps
      character(len=64) :: method
      character(len=1024) :: file
      character(len=512) :: msg
      logical :: force
      character(len=16), allocatable :: known(:)
      namelist /pendulum/ links, m, l, m1, m2, l1, l2, g, damping, support_amplitude, &
         support_frequency, support_phase, body, com, inertia
      namelist /initial/ q, w, q1, q2, w1, w2
      namelist /integration/ method, dt, t_end, save_every, rtol, atol, output_dt, omega, &
         max_steps
      namelist /output/ file, force

      n_extra = 0
      if (present(extra_groups)) n_extra = size(extra_groups)
      allocate (known(5 + n_extra))
      known(1:5) = [character(len=16) :: 'pendulum', 'initial', 'integration', 'output', &
                    'model']
      ! element by element: gfortran's -fcheck=all rejects a typed array constructor
      ! over an array of another character length
      do i = 1, n_extra
         known(5 + i) = extra_groups(i)
      end do
      call check_groups(filename, known, error)
      if (allocated(error)) return
      call read_model_group(filename, cfg, error)
      if (allocated(error)) return

      links = cfg%links
      m1 = cfg%m(1); m2 = cfg%m(2); l1 = cfg%l(1); l2 = cfg%l(2); g = cfg%g
      q1 = cfg%q(1); q2 = cfg%q(2); w1 = cfg%w(1); w2 = cfg%w(2)
      m = unset; l = unset; q = unset; w = unset; damping = unset
      com = unset; inertia = unset; body = ''
      support_amplitude = cfg%support_amplitude; support_frequency = cfg%support_frequency
      support_phase = cfg%support_phase
      method = ''
      if (allocated(cfg%method)) method = cfg%method
      dt = cfg%dt; t_end = cfg%t_end; save_every = cfg%save_every
      rtol = cfg%rtol; atol = cfg%atol; output_dt = cfg%output_dt; omega = cfg%omega
      max_steps = cfg%max_steps
      file = ''
      if (allocated(cfg%output)) file = cfg%output
      force = cfg%force
      ! issue 25: these scalars start unset so that the file's own are known (nml_given)
      m1 = unset; m2 = unset; l1 = unset; l2 = unset
      q1 = unset; q2 = unset; w1 = unset; w2 = unset
      output_dt = unset; save_every = -huge(1)

      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//printable(filename)//"'")
         return
      end if
      read (unit, nml=pendulum, iostat=stat, iomsg=msg)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'pendulum', msg)); close (unit); return
      end if
      rewind (unit)
      read (unit, nml=initial, iostat=stat, iomsg=msg)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'initial', msg)); close (unit); return
      end if
      rewind (unit)
      read (unit, nml=integration, iostat=stat, iomsg=msg)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'integration', msg)); close (unit)
         return
      end if
      rewind (unit)
      read (unit, nml=output, iostat=stat, iomsg=msg)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'output', msg)); close (unit); return
      end if
      close (unit)
      if (.not. allocated(cfg%nml_given)) cfg%nml_given = ' '
      call note_given('m1', m1, cfg%m(1)); call note_given('m2', m2, cfg%m(2))
      call note_given('l1', l1, cfg%l(1)); call note_given('l2', l2, cfg%l(2))
      call note_given('q1', q1, cfg%q(1)); call note_given('q2', q2, cfg%q(2))
      call note_given('w1', w1, cfg%w(1)); call note_given('w2', w2, cfg%w(2))
      call note_given('output_dt', output_dt, cfg%output_dt)
      if (save_every == -huge(1)) then
         save_every = cfg%save_every
      else
         cfg%nml_given = cfg%nml_given//'save_every '
      end if

      cfg%links = links
      cfg%m(1:2) = [m1, m2]; cfg%l(1:2) = [l1, l2]; cfg%g = g
      cfg%q(1:2) = [q1, q2]; cfg%w(1:2) = [w1, w2]
      ! the lists, where given, override the two-link names
      call take_list(1, 'm', m, cfg%m)
      if (.not. allocated(error)) call take_list(2, 'l', l, cfg%l)
      if (.not. allocated(error)) call take_list(3, 'q', q, cfg%q)
      if (.not. allocated(error)) call take_list(4, 'w', w, cfg%w)
      if (.not. allocated(error)) call take_list(0, 'damping', damping, cfg%damping)
      if (.not. allocated(error)) call take_body(body, com, inertia)
      if (allocated(error)) return
      cfg%support_amplitude = support_amplitude; cfg%support_frequency = support_frequency
      cfg%support_phase = support_phase
      if (len_trim(method) > 0) cfg%method = canonical_name(trim(method), method_names())
      cfg%dt = dt; cfg%t_end = t_end; cfg%save_every = save_every
      cfg%rtol = rtol; cfg%atol = atol; cfg%output_dt = output_dt; cfg%omega = omega
      cfg%max_steps = max_steps
      if (len_trim(file) > 0) cfg%output = trim(file)
      cfg%force = force
   contains
      !> A scalar the file did not give takes its current value; one it gave is
      !> recorded in cfg%nml_given.
      subroutine note_given(key, x, current)
         character(len=*), intent(in) :: key
         real(dp), intent(inout) :: x
         real(dp), intent(in) :: current
         if (x == unset) then
            x = current
         else
            cfg%nml_given = cfg%nml_given//key//' '
         end if
      end subroutine note_given
      !> The mass distribution of &pendulum (issue 26): body = 'rod' | 'point', the lists
      !> com and inertia (as --com and --inertia: checked by the factory).
      subroutine take_body(kind, d, ic)
         character(len=*), intent(in) :: kind
         real(dp), intent(in) :: d(:), ic(:)
         integer :: n
         if (len_trim(kind) > 0) call set_body(cfg, trim(kind), error)
         if (allocated(error)) return
         n = count_given('com', d)
         if (allocated(error)) return
         if (n > 0) call cfg%extra%set('com', d(:n))
         n = count_given('inertia', ic)
         if (allocated(error)) return
         if (n > 0) call cfg%extra%set('inertia', ic(:n))
      end subroutine take_body
      !> The leading entries given of the list `key`; an entry given after one that
      !> is not (`m(2) = 3` without m(1)) is refused, never ignored.
      integer function count_given(key, given) result(n)
         character(len=*), intent(in) :: key
         real(dp), intent(in) :: given(:)
         integer :: k
         n = 0
         do while (n < size(given))
            if (given(n + 1) == unset) exit
            n = n + 1
         end do
         do k = n + 2, size(given)
            if (given(k) /= unset) then
               call fatal_error(error, 'invalid '//key//'('//to_str(k)//'): '// &
                                real_str(given(k))//" in '"//printable(filename)// &
                                "' is given without "//key//'('//to_str(n + 1)// &
                                ') (a list is given from its first entry, without gaps)')
               return
            end if
         end do
      end function count_given
      !> Keep the given leading entries of a namelist list (its size is checked
      !> against the number of links by validate_run_config).
      subroutine take_list(k, key, given, values)
         integer, intent(in) :: k
         character(len=*), intent(in) :: key
         real(dp), intent(in) :: given(:)
         real(dp), intent(inout) :: values(:)
         integer :: n
         n = count_given(key, given)
         if (allocated(error)) return
         if (n == 0) return
         values(:n) = given(:n)
         if (k > 0) then
            cfg%list_size(k) = n
         else
            cfg%damping_size = n
         end if
      end subroutine take_list
   end subroutine read_run_config

   !> Apply one of the common flags; `matched` is false if `name` is not one of them.
   subroutine apply_run_flag(cfg, name, value, matched, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration to update
      character(len=*), intent(in) :: name              !! option, e.g. '--dt'
      character(len=*), intent(in) :: value             !! its value
      logical, intent(out) :: matched                   !! whether it was a common flag
      type(error_t), allocatable, intent(out) :: error  !! invalid value
      matched = .true.
      call check_flag_forms(cfg, name, error)
      if (allocated(error)) return
      select case (name)
      case ('--links'); call parse_int(value, name, cfg%links, error)
      case ('--m'); call set_list(cfg, 1, name, value, error)
      case ('--l'); call set_list(cfg, 2, name, value, error)
      case ('--q'); call set_list(cfg, 3, name, value, error)
      case ('--w'); call set_list(cfg, 4, name, value, error)
      case ('--q1'); call parse_real(value, name, cfg%q(1), error)
      case ('--q2'); call parse_real(value, name, cfg%q(2), error)
      case ('--theta1', '--theta2')   ! from the hanging position, as the sweep's axes
         call set_theta(cfg, merge(1, 2, name == '--theta1'), name, value, error)
      case ('--w1'); call parse_real(value, name, cfg%w(1), error)
      case ('--w2'); call parse_real(value, name, cfg%w(2), error)
      case ('--m1'); call parse_real(value, name, cfg%m(1), error)
      case ('--m2'); call parse_real(value, name, cfg%m(2), error)
      case ('--l1'); call parse_real(value, name, cfg%l(1), error)
      case ('--l2'); call parse_real(value, name, cfg%l(2), error)
      case ('--g'); call parse_real(value, name, cfg%g, error)
      case ('--method'); cfg%method = canonical_name(value, method_names())
      case ('--dt'); call parse_real(value, name, cfg%dt, error)
      case ('--t-end'); call parse_real(value, name, cfg%t_end, error)
      case ('--save-every'); call parse_int(value, name, cfg%save_every, error)
      case ('--rtol'); call parse_real(value, name, cfg%rtol, error)
      case ('--atol'); call parse_real(value, name, cfg%atol, error)
      case ('--output-dt'); call parse_real(value, name, cfg%output_dt, error)
      case ('--omega'); call parse_real(value, name, cfg%omega, error)
      case ('--max-steps'); call parse_int(value, name, cfg%max_steps, error)
      case ('--damping'); call set_list(cfg, 0, name, value, error)
      case ('--support-amplitude')
         call parse_pair(name, value, cfg%support_amplitude, 'a_x,a_y (m)', error)
      case ('--support-frequency'); call parse_real(value, name, cfg%support_frequency, error)
      case ('--support-phase')
         call parse_pair(name, value, cfg%support_phase, 'phi_x,phi_y (rad)', error)
      case ('--output', '-o'); cfg%output = value
      case ('--model'); cfg%model_name = canonical_name(value, model_names())
      case ('--body'); call set_body(cfg, value, error)
      case default
         matched = .false.
         ! a parameter of another model, by name (--k 40 --l0 1 for the elastic pendulum)
         if (len(name) > 2) then
            if (is_model_parameter(name(3:))) then
               matched = .true.
               call set_named(cfg, name(3:), name, value, error)
            end if
         end if
      end select
   end subroutine apply_run_flag

   !> Refuse a second form of one quantity on the command line (`--m 1,2 --m1 3`,
   !> `--q1` with `--theta1`): which one wins would depend on their order. The
   !> same flag twice is the same form (refused by check_repeated_options). Records
   !> `name` in cfg%flags_seen.
   subroutine check_flag_forms(cfg, name, error)
      type(run_config_t), intent(inout) :: cfg          !! flags_seen updated
      character(len=*), intent(in) :: name              !! the option
      type(error_t), allocatable, intent(out) :: error  !! a second form
      character(len=:), allocatable :: others
      integer :: k
      select case (name)
      case ('--m', '--l', '--w')
         others = name//'1 '//name//'2'
      case ('--q')
         others = '--q1 --q2 --theta1 --theta2'
      case ('--m1', '--m2', '--l1', '--l2', '--w1', '--w2')
         others = name(:3)
      case ('--q1', '--q2')
         others = '--q --theta'//name(4:4)
      case ('--theta1', '--theta2')
         others = '--q --q'//name(8:8)
      case default
         return
      end select
      if (.not. allocated(cfg%flags_seen)) cfg%flags_seen = ' '
      others = ' '//others//' '
      do k = 1, len(others) - 1
         if (others(k:k) /= ' ' .or. others(k + 1:k + 1) == ' ') cycle
         if (index(cfg%flags_seen, ' '//first_word(others(k + 1:))//' ') > 0) then
            call fatal_error(error, 'invalid '//name//': '//first_word(others(k + 1:))// &
                             ' was given too; they are two forms of one quantity ' &
                             //'(--m, --l, --q, --w: one value per link; --m1 ... for ' &
                             //'two links); give one of them')
            return
         end if
      end do
      if (index(cfg%flags_seen, ' '//name//' ') == 0) &
         cfg%flags_seen = cfg%flags_seen//name//' '
   end subroutine check_flag_forms

   !> The first blank-separated word of `t`.
   pure function first_word(t) result(w)
      character(len=*), intent(in) :: t  !! text
      character(len=:), allocatable :: w
      w = t(:index(t//' ', ' ') - 1)
   end function first_word

   !> q_k = θ_k − π/2 from --theta1/--theta2 (θ from the hanging position,
   !> counter-clockwise) [rad].
   subroutine set_theta(cfg, k, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! q(k) set
      integer, intent(in) :: k                          !! the link, 1 or 2
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not a number, out of range
      real(dp) :: theta
      call parse_real(value, name, theta, error)
      if (allocated(error)) return
      if (.not. in_range(theta, -max_angle, max_angle)) then
         call fatal_error(error, 'invalid '//name//': '//real_str(theta)// &
                          ' rad is outside [-1e6, 1e6]')
         return
      end if
      cfg%q(k) = theta - half_pi
   end subroutine set_theta

   !> A comma-separated list of at most max_dof numbers, one per link: list k of
   !> `list_names` (m, l, q, w), or the damping for k = 0.
   subroutine set_list(cfg, k, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! the list and its size set
      integer, intent(in) :: k                          !! which list
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      integer :: n
      select case (k)
      case (0); call parse_real_list(value, name, cfg%damping, n, error)
      case (1); call parse_real_list(value, name, cfg%m, n, error)
      case (2); call parse_real_list(value, name, cfg%l, n, error)
      case (3); call parse_real_list(value, name, cfg%q, n, error)
      case default; call parse_real_list(value, name, cfg%w, n, error)
      end select
      if (allocated(error)) return
      if (k > 0) then
         cfg%list_size(k) = n
      else
         cfg%damping_size = n
      end if
   end subroutine set_list

   !> A comma-separated list of numbers for the model parameter `key` (--k 40).
   subroutine set_named(cfg, key, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%extra updated
      character(len=*), intent(in) :: key               !! the parameter
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      real(dp) :: values(max_dof)
      integer :: n
      call parse_real_list(value, name, values, n, error)
      if (.not. allocated(error)) call cfg%extra%set(key, values(:n))
   end subroutine set_named

   !> Two comma-separated numbers (`what` names them in the message).
   subroutine parse_pair(name, value, values, what, error)
      character(len=*), intent(in) :: name, value       !! the option and its value
      real(dp), intent(inout) :: values(2)              !! the numbers
      character(len=*), intent(in) :: what              !! e.g. 'a_x,a_y (m)'
      type(error_t), allocatable, intent(out) :: error  !! not two numbers
      integer :: comma
      comma = index(value, ',')
      if (comma == 0 .or. index(value(comma + 1:), ',') > 0) then
         call fatal_error(error, 'invalid '//name//": '"//printable(value)//"' must be two " &
                          //'comma-separated numbers '//what)
         return
      end if
      call parse_real(value(:comma - 1), name, values(1), error)
      if (allocated(error)) return
      call parse_real(value(comma + 1:), name, values(2), error)
   end subroutine parse_pair

   !> Check the whole configuration; messages name the field and the accepted range
   !> (the limits and their reasons are in `dpend_limits`). For a fixed-step method
   !> the number of steps t_end/dt is at most `max_steps`; an adaptive method stops
   !> after `max_steps` accepted steps instead (`--max-steps`).
   !> Builds `cfg%model` (the double pendulum for two links, the chain otherwise).
   subroutine validate_run_config(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      class(integrator_t), allocatable :: integ
      integer :: i, n
      if (allocated(cfg%model)) deallocate (cfg%model)
      call check_range('links', real(cfg%links, dp), 1.0_dp, real(max_dof, dp), '', error)
      if (allocated(error)) return
      n = cfg%links
      do i = 1, merge(2, 0, model_has(cfg, 'links'))   ! m and l: one per link
         if (cfg%list_size(i) /= 0 .and. cfg%list_size(i) /= n) then
            call fatal_error(error, 'invalid '//list_names(i)//': '// &
                             to_str(cfg%list_size(i))//' values for '//to_str(n)// &
                             ' links (one per link; --links N sets N) [--'//list_names(i)// &
                             ' / namelist '//list_names(i)//']')
            return
         end if
      end do
      if (cfg%damping_size /= 0 .and. cfg%damping_size /= n) then
         call fatal_error(error, 'invalid damping: '//to_str(cfg%damping_size)// &
                          ' values for '//to_str(n)//' links (one per joint; --links N ' &
                          //'sets N) [--damping / namelist damping]')
         return
      end if
      call check_range('support_frequency', cfg%support_frequency, 0.0_dp, &
                       max_support_frequency, 'rad/s', error)
      if (allocated(error)) return
      do i = 1, 2
         call check_range('support_phase '//merge('phi_x', 'phi_y', i == 1), &
                          cfg%support_phase(i), -max_angle, max_angle, 'rad', error)
         if (allocated(error)) return
      end do
      call build_model(cfg, error)
      if (allocated(error)) return
      call check_initial_state(cfg, error)
      if (allocated(error)) return
      if (.not. allocated(cfg%method)) then
         call fatal_error(error, 'invalid method: none given')
         return
      end if
      call new_integrator(cfg%method, integ, error)
      if (allocated(error)) return
      call integ%check_model(cfg%model, error)   ! e.g. a canonical method, no Hamiltonian
      if (allocated(error)) return
      if (.not. finite_positive(cfg%dt)) then
         call fatal_error(error, 'invalid dt: must be finite and > 0, at most '//sci(max_dt) &
                          //' s')
         return
      end if
      call check_range('dt', cfg%dt, 0.0_dp, max_dt, 's', error)
      if (allocated(error)) return
      call check_range('t_end', cfg%t_end, 0.0_dp, max_time, 's', error)
      if (allocated(error)) return
      if (.not. integ%adaptive()) then
         call check_count('dt', cfg%dt, cfg%t_end, 't_end', max_steps, 'steps', &
                          'use a larger --dt or a shorter --t-end', error)
         if (allocated(error)) return
      end if
      if (cfg%save_every < 1) then
         call fatal_error(error, 'invalid save_every: '//sci(real(cfg%save_every, dp))// &
                          ' must be an integer >= 1')
      else if (.not. finite_positive(cfg%rtol) .or. .not. finite_positive(1.0_dp - cfg%rtol)) &
         then
         call fatal_error(error, 'invalid rtol: must be in ['//sci(min_rtol)//', 1)')
      else if (cfg%rtol < min_rtol) then
         call fatal_error(error, 'invalid rtol: '//sci(cfg%rtol)//' is below '//sci(min_rtol) &
                          //' (double precision cannot honour it: the error estimate is '// &
                          'dominated by rounding and the step shrinks until it stalls)')
      else if (.not. in_range(cfg%atol, min_atol, max_atol)) then
         call fatal_error(error, 'invalid atol: must be in ['//sci(min_atol)//', ' &
                          //sci(max_atol)//'] (rad, rad/s)')
      else if (.not. (finite_positive(cfg%output_dt) .or. cfg%output_dt == 0.0_dp)) then
         call fatal_error(error, 'invalid output_dt: must be finite and >= 0 (s; 0 = off)')
      else if (cfg%output_dt > max_time) then
         call fatal_error(error, 'invalid output_dt: '//sci(cfg%output_dt)//' s is above ' &
                          //sci(max_time)//' s')
      else if (.not. (finite_positive(cfg%omega) .and. in_range(cfg%omega, 0.0_dp, max_omega))) &
         then
         call fatal_error(error, 'invalid omega: must be in (0, '//sci(max_omega)//'] (1/s)')
      else if (cfg%max_steps < 1 .or. cfg%max_steps > max_steps) then
         call fatal_error(error, 'invalid max_steps: must be an integer from 1 to ' &
                          //sci(real(max_steps, dp))//' (steps)')
      end if
   end subroutine validate_run_config

   !> A comma-separated list of at most size(values) numbers (one per link for the
   !> per-link fields), each through the strict parser; `n` values read.
   subroutine parse_real_list(text, name, values, n, error)
      character(len=*), intent(in) :: text              !! the flag's value
      character(len=*), intent(in) :: name              !! the flag, for messages
      real(dp), intent(inout) :: values(:)              !! the numbers
      integer, intent(out) :: n                         !! how many
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      integer :: start, comma
      n = 0
      start = 1
      do
         comma = index(text(start:), ',')
         if (n == size(values)) then
            call fatal_error(error, 'invalid '//name//': more than '//to_str(size(values))// &
                             ' values (at most '//to_str(size(values))//' links)')
            return
         end if
         n = n + 1
         if (comma == 0) then
            call parse_real(text(start:), name, values(n), error)
            exit
         end if
         call parse_real(text(start:start + comma - 2), name, values(n), error)
         if (allocated(error)) return
         start = start + comma
      end do
   end subroutine parse_real_list

   !> Whether the model `cfg` asks for has the parameter `name` (the factory's
   !> catalogue; an unknown model: none).
   logical function model_has(cfg, name)
      type(run_config_t), intent(in) :: cfg  !! configuration
      character(len=*), intent(in) :: name   !! parameter name
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      k = find_model(models, model_asked(cfg))
      model_has = .false.
      if (k == 0) return
      model_has = any([(models(k)%params(i)%name == name, i=1, size(models(k)%params))])
   end function model_has

   !> The model name --model gave (or &model name), else the factory's default.
   pure function model_asked(cfg) result(name)
      type(run_config_t), intent(in) :: cfg  !! configuration
      character(len=:), allocatable :: name
      if (allocated(cfg%model_name)) then
         name = cfg%model_name
      else
         name = default_model
      end if
   end function model_asked

   !> The names of the factory's models, blank-separated (for `canonical_name`).
   function model_names() result(s)
      character(len=:), allocatable :: s
      type(model_info_t), allocatable :: models(:)
      integer :: k
      models = model_catalogue()
      s = ''
      do k = 1, size(models)
         s = s//' '//models(k)%name
      end do
   end function model_names

   !> Whether `name` is a parameter of any model of the catalogue (a flag --NAME).
   logical function is_model_parameter(name)
      character(len=*), intent(in) :: name  !! parameter name
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      is_model_parameter = .false.
      do k = 1, size(models)
         do i = 1, size(models(k)%params)
            if (models(k)%params(i)%name == name) is_model_parameter = .true.
         end do
      end do
   end function is_model_parameter

   !> Build `cfg%model` through the factory (the one place a model is built): the
   !> specification holds the model's parameters from the run's fields (links, m, l,
   !> g, damping, support_*) and those given by name (--k); a field set for a model
   !> that has no such parameter is refused.
   subroutine build_model(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      type(model_info_t), allocatable :: models(:)
      integer :: k, i, n
      character(len=:), allocatable :: given
      models = model_catalogue()
      cfg%spec = model_spec(model_asked(cfg))
      k = find_model(models, model_asked(cfg))
      if (k > 0) then
         n = cfg%links
         do i = 1, size(models(k)%params)
            associate (p => models(k)%params(i))
               select case (p%name)
               case ('links'); call cfg%spec%set('links', [real(cfg%links, dp)])
               case ('m'); call cfg%spec%set('m', per_link(cfg%m, 1))
               case ('l'); call cfg%spec%set('l', per_link(cfg%l, 2))
               case ('g'); call cfg%spec%set('g', [cfg%g])
               case ('damping'); call cfg%spec%set('damping', cfg%damping(:n))
               case ('support_amplitude')
                  call cfg%spec%set('support_amplitude', cfg%support_amplitude)
               case ('support_frequency')
                  call cfg%spec%set('support_frequency', [cfg%support_frequency])
               case ('support_phase'); call cfg%spec%set('support_phase', cfg%support_phase)
               end select
            end associate
         end do
         ! the pendulum's fields given to a model without them
         given = ''
         if (cfg%links /= 2) given = 'links'
         if (cfg%list_size(2) > 0) given = 'l'
         if (cfg%damping_size > 0) given = 'damping'
         if (any(cfg%support_amplitude /= 0.0_dp)) given = 'support_amplitude'
         if (len(given) > 0 .and. .not. model_has(cfg, given)) then
            call fatal_error(error, 'invalid '//given//': not a parameter of model ' &
                             //model_asked(cfg)//' (dpend models lists its parameters)')
            return
         end if
      end if
      if (allocated(cfg%extra%items)) then
         do i = 1, size(cfg%extra%items)
            call cfg%spec%set(cfg%extra%items(i)%name, cfg%extra%items(i)%values)
         end do
      end if
      call apply_body(cfg, error)
      if (allocated(error)) return
      call new_model(cfg%spec, cfg%model, error)
      if (allocated(error)) error%message = error%message//hint(error%message)
   contains
      !> The first n values of a per-link field, or its first value for a scalar
      !> parameter (refused later by the factory if a list was given).
      function per_link(values, list) result(v)
         real(dp), intent(in) :: values(:)
         integer, intent(in) :: list
         real(dp), allocatable :: v(:)
         if (model_has(cfg, 'links')) then
            v = values(:n)
         else
            v = values(:max(1, cfg%list_size(list)))
         end if
      end function per_link
      !> Where a refused parameter is set: its flags and namelist group.
      function hint(message) result(s)
         character(len=*), intent(in) :: message
         character(len=:), allocatable :: s
         if (index(message, 'invalid model') == 1 .or. &
             index(message, 'not a parameter of model') > 0) then
            s = ''
         else if (.not. model_has(cfg, 'links')) then
            s = ' [dpend models lists the parameters of '//model_asked(cfg)//']'
         else if (index(message, 'invalid damping') == 1) then
            s = ' [--damping / &pendulum damping]'
         else if (index(message, 'invalid com') == 1 .or. index(message, 'invalid inertia') &
                  == 1) then
            s = ' [--com --inertia --body / &pendulum com inertia body]'
         else if (index(message, 'invalid support') == 1) then
            s = ' [--support-amplitude --support-frequency --support-phase / &pendulum]'
         else if (n == 2) then
            s = ' [--m1 --m2 --l1 --l2 --g / &pendulum]'
         else
            s = ' [--m --l --g / &pendulum]'
         end if
      end function hint
   end subroutine build_model

   !> The initial state: as many q and w as the model has coordinates, within what
   !> the model accepts (`check_state`: angles and angular velocities within 1e6 for
   !> the pendulum; the elastic pendulum's r above its collapse).
   subroutine check_initial_state(cfg, error)
      type(run_config_t), intent(in) :: cfg             !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: i, nd
      nd = cfg%model%n_dof()
      do i = 3, 4
         if (cfg%list_size(i) /= 0 .and. cfg%list_size(i) /= nd) then
            if (model_has(cfg, 'links')) then
               call fatal_error(error, 'invalid '//list_names(i)//': '// &
                                to_str(cfg%list_size(i))//' values for '//to_str(nd)// &
                                ' links (one per link; --links N sets N) [--'// &
                                list_names(i)//' / namelist '//list_names(i)//']')
            else
               call fatal_error(error, 'invalid '//list_names(i)//': '// &
                                to_str(cfg%list_size(i))//' values for the '//to_str(nd)// &
                                ' coordinates of model '//model_asked(cfg)//' [--' &
                                //list_names(i)//' / namelist '//list_names(i)//']')
            end if
            return
         end if
      end do
      call cfg%model%check_state(cfg%q(:nd), cfg%w(:nd), error)
   end subroutine check_initial_state

   !> Help lines for the common flags, with units and the defaults of `cfg`.
   function run_flags_help(cfg, t_end_text) result(s)
      type(run_config_t), intent(in) :: cfg  !! defaults to show
      character(len=*), intent(in), optional :: t_end_text  !! what --t-end means, if not
                                                            !! 'end time'
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      character(len=:), allocatable :: t_end_line
      t_end_line = 'end time'
      if (present(t_end_text)) t_end_line = t_end_text
      s = '  --config FILE     Fortran namelist file (groups &model &pendulum &initial' &
          //nl//'                    &integration &output; see data/*.nml); flags below' &
          //nl//'                    override it'//nl// &
          '  --model NAME      the model (dpend models lists them, with their parameters);'//nl// &
          '                    default pendulum. Parameters of other models by name, e.g.' &
          //nl//'                    --model elastic --m 1 --k 40 --l0 1 --q 1.2,-1.0'//nl// &
          '  --links N         number of links (uniform rods), 1 to '//to_str(max_dof)// &
          '; default '//to_str(cfg%links)//nl// &
          '                    (2: the double pendulum; 3: the triple pendulum, ...)'//nl// &
          '  --m, --l, --q, --w LIST  one value per link, comma-separated: masses (kg),'//nl// &
          '                    lengths (m), initial angles (rad), angular velocities (rad/s),'// &
          nl//'                    e.g. --links 3 --m 1,1,1 --q 0,0.5,-1; defaults 1 kg, 1 m, 0, 0' &
          //nl// &
          '  --q1, --q2 RAD    initial angles from the horizontal x axis, counter-clockwise' &
          //nl//'                    (hanging: -pi/2); default '//real_str(cfg%q(1))//', ' &
          //real_str(cfg%q(2))//nl// &
          '  --theta1, --theta2 RAD  the same angles from the hanging position, as the'//nl// &
          "                    sweep's axes: q = theta - pi/2"//nl// &
          '  --w1, --w2 RAD/S  initial angular velocities; default '//real_str(cfg%w(1))//', ' &
          //real_str(cfg%w(2))//nl// &
          '  --m1, --m2 KG     link masses (m1 m2 l1 l2 g: each in [1e-6, 1e6]); default ' &
          //real_str(cfg%m(1))//', ' &
          //real_str(cfg%m(2))//nl// &
          '  --l1, --l2 M      link lengths; default '//real_str(cfg%l(1))//', ' &
          //real_str(cfg%l(2))//nl// &
          '  --g M/S^2         gravitational acceleration; default '//real_str(cfg%g)//nl// &
          '  --body rod|point  the links: uniform rods (default; com l_i/2, inertia'//nl// &
          '                    m_i l_i^2/12) or point masses on massless rods (com l_i,'//nl// &
          '                    inertia 0: the textbook double pendulum)'//nl// &
          '  --com LIST        joint i to the centre of mass of link i along the link (m,'//nl// &
          '                    one per link, >= 0; default l_i/2)'//nl// &
          '  --inertia LIST    moment of inertia of link i about its centre of mass'//nl// &
          '                    (kg m^2, one per link, >= 0; default m_i l_i^2/12)'//nl// &
          '  --damping LIST    joint damping c_i (N m s, one per joint, each in [0, 1e6]):'//nl// &
          '                    torque -c_i (qdot_i - qdot_(i-1)) at joint i; default 0'//nl// &
          '  --support-amplitude AX,AY  moving pin: x_A = AX cos(w t + PX),'//nl// &
          '                    y_A = AY cos(w t + PY) (m, each in [-1e6, 1e6]); default 0,0'//nl// &
          '  --support-frequency W  w (rad/s, in [0, 1e6]); default 0'//nl// &
          '  --support-phase PX,PY  phases (rad); default 0,0. Damping or a moving support'//nl// &
          '                    makes the model the (damped, driven) chain, also for two'//nl// &
          '                    links: rk4, dopri5, dop853, midpoint, gauss4/6/8 only;'//nl// &
          '                    simulate writes the energy balance (W_friction,'//nl// &
          '                    W_support, balance_error)'//nl// &
          '  --method NAME     integrator (dpend methods lists them); default '//cfg%method//nl// &
          '  --dt S            step (first trial step for adaptive methods); default ' &
          //real_str(cfg%dt)//nl// &
          '  --t-end S         '//t_end_line//'; default '//real_str(cfg%t_end)//nl// &
          '  --rtol, --atol    tolerances of the adaptive methods; default '//real_str(cfg%rtol) &
          //', '//real_str(cfg%atol)//nl// &
          "  --omega 1/S       binding constant of Tao's methods; default "//real_str(cfg%omega)// &
          nl//'  --max-steps N     most accepted steps of one integration of an adaptive'//nl// &
          '                    method (steps); reaching it stops the run; default ' &
          //to_str(cfg%max_steps)
   end function run_flags_help

   ! ---- links of any mass distribution (issue 26): --body, &pendulum body

   !> `--body NAME` / `&pendulum body = 'NAME'`: rod or point, else refused.
   subroutine set_body(cfg, value, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%body set
      character(len=*), intent(in) :: value             !! the name given
      type(error_t), allocatable, intent(out) :: error  !! not a body
      select case (to_lower(value))
      case ('rod', 'point')
         cfg%body = to_lower(value)
      case default
         call fatal_error(error, "invalid body: '"//printable(value)//"' is not a body " &
                          //'(accepted: rod, point; --com and --inertia give any other) ' &
                          //'[--body / &pendulum body]')
      end select
   end subroutine set_body

   !> The body asked for into cfg%spec: 'point' sets com = l and inertia = 0, 'rod'
   !> leaves the rod's defaults; either is refused beside com or inertia (the two
   !> would contradict each other), and for a model without links' bodies.
   subroutine apply_body(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%spec updated
      type(error_t), allocatable, intent(out) :: error  !! a contradiction
      real(dp), allocatable :: l(:)
      character(len=:), allocatable :: given, sets
      if (.not. allocated(cfg%body)) return
      if (.not. model_has(cfg, 'com')) then
         call fatal_error(error, 'invalid body: not a parameter of model '//model_asked(cfg) &
                          //' (dpend models lists its parameters)')
         return
      end if
      given = ''
      if (cfg%spec%find('com') > 0) given = 'com'
      if (cfg%spec%find('inertia') > 0) then
         if (len(given) > 0) given = given//' and '
         given = given//'inertia'
      end if
      if (len(given) > 0) then
         if (cfg%body == 'rod') then
            sets = 'com = l_i/2 and inertia = m_i l_i^2/12'
         else
            sets = 'com = l_i and inertia = 0'
         end if
         call fatal_error(error, 'invalid body: '//cfg%body//' contradicts the '//given &
                          //' given (--body '//cfg%body//' sets '//sets//'; give either ' &
                          //'the body or com and inertia) [--body --com --inertia / &pendulum]')
         return
      end if
      if (cfg%body == 'point') then
         l = cfg%spec%get('l', [1.0_dp])
         call cfg%spec%set('com', l)
         call cfg%spec%set('inertia', spread(0.0_dp, 1, size(l)))
      end if
   end subroutine apply_body

end module dpend_config
