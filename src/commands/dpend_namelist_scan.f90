!> The strict checks of a namelist file before Fortran's namelist read sees it
!> (`check_groups`): a regular text file of at most 1 MiB, only known groups, each
!> once and closed, nothing outside them, and every value the whole token (a number
!> for a number key, a logical word for a logical, a quoted text for a text key),
!> no key twice and no two forms of one quantity in a group.
module dpend_namelist_scan
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: to_str, to_lower, printable, quoted
   use dpend_parse, only: read_real, read_int
   use dpend_output, only: check_regular_file
   implicit none
   private
   public :: check_groups, read_config_bytes, stripped, without_comments
   !> Largest configuration file read [bytes].
   integer(i8), parameter :: max_config_bytes = 1048576_i8

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

contains

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
         if (is_string_key(s%key)) return
         if (.not. logical_word(v)) then
            call scan_refuse(s, scan_key_text(s)//quoted(v)//' is not a number or a ' &
                             //'logical (t, f, true, false, .t., .f., .true., .false.; ' &
                             //'quote a text)', error)
         else if (.not. is_logical_key(s%key)) then   ! a number's key given a logical
            call scan_refuse(s, scan_key_text(s)//quoted(v)//' is a logical; this key ' &
                             //'takes a number', error)
         end if
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
      case ('file', 'ic_file', 'ic_dataset', 'case_torque_file'); n = 1024
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

   !> Whether `k` is read into a logical variable (force, quick, lyapunov, stats,
   !> quiet, same_energy): the only keys a logical word may be given to.
   pure logical function is_logical_key(k)
      character(len=*), intent(in) :: k  !! key
      select case (k)
      case ('force', 'quick', 'lyapunov', 'stats', 'quiet', 'same_energy')
         is_logical_key = .true.
      case default
         is_logical_key = .false.
      end select
   end function is_logical_key

   !> Whether `k` is read into a text variable (string_length applies).
   pure logical function is_string_key(k)
      character(len=*), intent(in) :: k  !! key
      character(len=:), allocatable :: b
      b = k
      if (index(b, '(') > 0) b = b(:index(b, '(') - 1)
      select case (b)
      case ('file', 'ic_file', 'ic_dataset', 'name', 'case_name', 'order_case', &
            'case_torque_file', 'drift_case', 'ro_case', 'tao_case', 'method', 'ref_method', 'check_method', &
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

end module dpend_namelist_scan
