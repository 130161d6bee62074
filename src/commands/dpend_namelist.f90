!> The namelist reader of every command (`--config FILE`, commented examples in
!> data/): after the strict checks of dpend_namelist_scan, the groups of a run,
!> &model (name and parameters by name), &pendulum (links m l g, or m1 m2 l1 l2 for
!> two links), &initial (q w, or q1 q2 w1 w2), &integration (method dt t_end
!> save_every rtol atol output_dt omega) and &output (file force), read into the run
!> settings (dpend_run_settings). Commands with more settings read further groups
!> through `check_groups` and their own namelists.
module dpend_namelist
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: max_dof
   use dpend_model_factory, only: spec_item_t, default_model, has_parameter
   use dpend_cli, only: parse_real, real_str, to_str, to_lower, printable
   use dpend_methods, only: method_names
   use dpend_strings, only: canonical_name
   use dpend_run_settings, only: run_config_t, set_body, model_names, is_model_parameter, &
      mark_given, list_names
   use dpend_namelist_scan, only: check_groups, read_config_bytes, stripped, &
      without_comments
   implicit none
   private
   public :: read_run_config, check_groups, namelist_error

contains

   !> The message for a failed namelist read, naming the group and the offending key.
   function namelist_error(filename, group, iomsg) result(msg)
      character(len=*), intent(in) :: filename  !! file
      character(len=*), intent(in) :: group     !! group name
      character(len=*), intent(in) :: iomsg     !! the runtime's message
      character(len=:), allocatable :: msg
      character(len=*), parameter :: unmatched = 'Cannot match namelist object name '
      character(len=:), allocatable :: text, tok, key
      type(error_t), allocatable :: err
      integer :: at
      msg = "invalid config '"//printable(filename)//"' in &"//group//': '//trim(iomsg)
      ! the runtime reads '1.5' for a whole-number key as 1 and then '.5' as a key:
      ! name the key whose value it was, and say what it takes
      at = index(iomsg, unmatched)
      if (at == 0) return
      tok = trim(iomsg(at + len(unmatched):))
      if (len(tok) == 0) return
      if (scan(tok(1:1), '.eEdD0123456789') == 0) return
      call read_config_bytes(filename, '', text, err)
      if (allocated(err)) return
      key = key_before(without_comments(text), tok)
      if (len(key) == 0) return
      msg = "invalid config '"//printable(filename)//"' in &"//group//': invalid '//key// &
            ": its value ends in '"//printable(tok)//"', which is not part of a whole " &
            //'number ('//key//' takes an integer: no fraction, no exponent)'
   contains
      !> The key of the assignment in `t` whose value is directly followed by `tk`
      !> (e.g. 'gpu_repack' in 'gpu_repack = 1.5' for '.5'); '' if not found.
      function key_before(t, tk) result(k)
         character(len=*), intent(in) :: t, tk
         character(len=:), allocatable :: k
         integer :: p, e, b, q
         k = ''
         p = index(t, tk)
         do while (p > 1)
            if (scan(t(p - 1:p - 1), '0123456789') /= 0) exit
            q = index(t(p + 1:), tk)
            if (q == 0) return
            p = p + q
         end do
         if (p <= 1) return
         e = index(t(:p - 1), '=', back=.true.)
         if (e <= 1) return
         b = verify(t(:e - 1), ' '//achar(9)//achar(10)//achar(13), back=.true.)
         if (b == 0) return
         q = scan(t(:b), ' '//achar(9)//achar(10)//achar(13)//',/&', back=.true.)
         k = to_lower(t(q + 1:b))
      end function key_before
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
      ! these scalars start unset so that the file's own are known (nml_given, given)
      m1 = unset; m2 = unset; l1 = unset; l2 = unset
      q1 = unset; q2 = unset; w1 = unset; w2 = unset
      output_dt = unset; save_every = -huge(1)
      links = -huge(1); g = unset
      support_amplitude = unset; support_frequency = unset; support_phase = unset

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
      call check_two_groups()
      if (allocated(error)) return
      call note_pendulum_given()
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
      call take_model_fields()
   contains
      !> A quantity given in &model and in &pendulum (m and m1, g and g, com and com)
      !> is refused naming both: which one holds would depend on a rule of the reader.
      subroutine check_two_groups()
         character(len=:), allocatable :: key, also
         integer :: k
         if (.not. allocated(cfg%extra%items)) return
         do k = 1, size(cfg%extra%items)
            key = cfg%extra%items(k)%name
            also = ''
            select case (key)
            case ('links'); if (links /= -huge(1)) also = 'links'
            case ('m'); also = list_or_pair('m', m, m1, m2)
            case ('l'); also = list_or_pair('l', l, l1, l2)
            case ('g'); if (g /= unset) also = 'g'
            case ('damping'); if (any(damping /= unset)) also = 'damping'
            case ('support_amplitude')
               if (any(support_amplitude /= unset)) also = key
            case ('support_frequency'); if (support_frequency /= unset) also = key
            case ('support_phase'); if (any(support_phase /= unset)) also = key
            case ('com'); if (any(com /= unset)) also = 'com'
            case ('inertia'); if (any(inertia /= unset)) also = 'inertia'
            end select
            if (len(also) > 0) then
               call fatal_error(error, "invalid --config '"//printable(filename)//"': "// &
                                key//' is given in &model and as '//also//' in &pendulum; ' &
                                //'give it in one group')
               return
            end if
         end do
      end subroutine check_two_groups
      !> Which form of a per-link quantity &pendulum gave ('' for none).
      function list_or_pair(key, list, x1, x2) result(form)
         character(len=*), intent(in) :: key
         real(dp), intent(in) :: list(:), x1, x2
         character(len=:), allocatable :: form
         form = ''
         if (x2 /= unset) form = key//'2'
         if (x1 /= unset) form = key//'1'
         if (any(list /= unset)) form = key
      end function list_or_pair
      !> The settings of &pendulum and &initial the file gave, into cfg%given; the
      !> sentinels of those not given take the current values.
      subroutine note_pendulum_given()
         integer :: k
         if (links == -huge(1)) then
            links = cfg%links
         else
            call mark_given(cfg, 'links')
         end if
         if (g == unset) then
            g = cfg%g
         else
            call mark_given(cfg, 'g')
         end if
         if (support_frequency == unset) then
            support_frequency = cfg%support_frequency
         else
            call mark_given(cfg, 'support_frequency')
         end if
         if (any(support_amplitude /= unset)) call mark_given(cfg, 'support_amplitude')
         where (support_amplitude == unset) support_amplitude = cfg%support_amplitude
         if (any(support_phase /= unset)) call mark_given(cfg, 'support_phase')
         where (support_phase == unset) support_phase = cfg%support_phase
         if (m1 /= unset) call mark_given(cfg, 'm1')
         if (m2 /= unset) call mark_given(cfg, 'm2')
         if (l1 /= unset) call mark_given(cfg, 'l1')
         if (l2 /= unset) call mark_given(cfg, 'l2')
         if (q1 /= unset) call mark_given(cfg, 'q1')
         if (q2 /= unset) call mark_given(cfg, 'q2')
         if (w1 /= unset) call mark_given(cfg, 'w1')
         if (w2 /= unset) call mark_given(cfg, 'w2')
         do k = 1, 4
            if (any(lists(k) /= unset)) call mark_given(cfg, list_names(k))
         end do
         if (any(damping /= unset)) call mark_given(cfg, 'damping')
      end subroutine note_pendulum_given
      !> The namelist list of `list_names(k)` (m, l, q, w).
      function lists(k) result(v)
         integer, intent(in) :: k
         real(dp) :: v(max_dof)
         select case (k)
         case (1); v = m
         case (2); v = l
         case (3); v = q
         case default; v = w
         end select
      end function lists
      !> The parameters &model gives that the run holds as fields (links, m, l, g,
      !> damping, the support's motion) go into those fields, as &pendulum's do, so
      !> that a flag overrides either the same way (flags over the file) and the file
      !> records the values the run used. A value of the wrong count or kind stays a
      !> named parameter, for the factory's refusal.
      subroutine take_model_fields()
         type(spec_item_t), allocatable :: kept(:)
         character(len=:), allocatable :: model
         logical :: moved
         integer :: k, n
         if (.not. allocated(cfg%extra%items)) return
         model = default_model
         if (allocated(cfg%model_name)) model = cfg%model_name
         allocate (kept(0))
         do k = 1, size(cfg%extra%items)
            associate (v => cfg%extra%items(k)%values, key => cfg%extra%items(k)%name)
               n = size(v)
               ! a parameter the model has, with one value or one per link
               moved = has_parameter(model, key) .and. &
                       (n == 1 .or. has_parameter(model, 'links'))
               if (moved) then
                  select case (key)
                  case ('links')
                     moved = n == 1 .and. v(1) == aint(v(1)) .and. abs(v(1)) <= real(max_dof, dp)
                     if (moved) cfg%links = nint(v(1))
                  case ('m'); cfg%m(:n) = v; cfg%list_size(1) = n
                  case ('l'); cfg%l(:n) = v; cfg%list_size(2) = n
                  case ('g')
                     moved = n == 1
                     if (moved) cfg%g = v(1)
                  case ('damping'); cfg%damping(:n) = v; cfg%damping_size = n
                  case ('support_amplitude')
                     moved = n == 2
                     if (moved) cfg%support_amplitude = v
                  case ('support_frequency')
                     moved = n == 1
                     if (moved) cfg%support_frequency = v(1)
                  case ('support_phase')
                     moved = n == 2
                     if (moved) cfg%support_phase = v
                  case default
                     moved = .false.
                  end select
               end if
               call mark_given(cfg, key)
               if (.not. moved) kept = [kept, cfg%extra%items(k)]
            end associate
         end do
         call move_alloc(kept, cfg%extra%items)
      end subroutine take_model_fields
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
      !> The mass distribution of &pendulum: body = 'rod' | 'point', the lists
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

end module dpend_namelist
