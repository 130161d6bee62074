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
   use dpend_run_flags, only: set_time_unit
   use dpend_namelist_scan, only: check_groups, read_config_bytes, stripped, &
      without_comments
   implicit none
   private
   public :: read_run_config, check_groups, namelist_error

   !> Marks a value of the run groups the file did not give.
   real(dp), parameter :: unset = -huge(1.0_dp)

   !> The groups &pendulum, &initial, &integration and &output as read
   !> (`read_run_groups`), for the steps that resolve them into the run settings.
   type :: run_groups_t
      integer :: links = 0, save_every = 0
      integer(i8) :: max_steps = 0
      real(dp) :: m1 = 0, m2 = 0, l1 = 0, l2 = 0, g = 0, q1 = 0, q2 = 0, w1 = 0, w2 = 0
      real(dp) :: dt = 0, t_end = 0, rtol = 0, atol = 0, output_dt = 0, omega = 0
      real(dp) :: m(max_dof) = 0, l(max_dof) = 0, q(max_dof) = 0, w(max_dof) = 0
      real(dp) :: damping(max_dof) = 0, com(max_dof) = 0, inertia(max_dof) = 0
      real(dp) :: support_amplitude(2) = 0, support_frequency = 0, support_phase(2) = 0
      character(len=16) :: body = ''
      character(len=64) :: method = ''
      character(len=16) :: time_unit = ''
      character(len=1024) :: file = ''
      logical :: force = .false.
   end type run_groups_t

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
      type(run_groups_t) :: r
      character(len=16), allocatable :: known(:)
      integer :: i, n_extra
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
      call read_run_groups(filename, cfg, r, error)
      if (allocated(error)) return
      call check_two_groups(filename, r, cfg, error)
      if (allocated(error)) return
      call note_pendulum_given(r, cfg)
      call take_run_groups(filename, r, cfg, error)
      if (allocated(error)) return
      call take_model_fields(cfg)
   end subroutine read_run_config

   !> The groups &pendulum, &initial, &integration and &output of `filename`, as read:
   !> the scalars whose giving matters (links, m1 … w2, g, output_dt, save_every, the
   !> support's motion) and every list entry `unset` where the file gave none, the
   !> others the current values of `cfg`.
   subroutine read_run_groups(filename, cfg, r, error)
      character(len=*), intent(in) :: filename          !! namelist file
      type(run_config_t), intent(in) :: cfg             !! the current values
      type(run_groups_t), intent(out) :: r              !! the groups as read
      type(error_t), allocatable, intent(out) :: error  !! unreadable or invalid
      real(dp) :: m1, m2, l1, l2, g, q1, q2, w1, w2, dt, t_end, rtol, atol, output_dt, omega
      real(dp) :: m(max_dof), l(max_dof), q(max_dof), w(max_dof), damping(max_dof)
      real(dp) :: support_amplitude(2), support_frequency, support_phase(2)
      real(dp) :: com(max_dof), inertia(max_dof)
      character(len=16) :: body
      integer :: save_every, unit, stat, links
      integer(i8) :: max_steps
      character(len=64) :: method
      character(len=16) :: time_unit
      character(len=1024) :: file
      character(len=512) :: msg
      character(len=16) :: group
      logical :: force
      namelist /pendulum/ links, m, l, m1, m2, l1, l2, g, damping, support_amplitude, &
         support_frequency, support_phase, body, com, inertia
      namelist /initial/ q, w, q1, q2, w1, w2
      namelist /integration/ method, dt, t_end, save_every, rtol, atol, output_dt, omega, &
         max_steps, time_unit
      namelist /output/ file, force
      m = unset; l = unset; q = unset; w = unset; damping = unset
      com = unset; inertia = unset; body = ''
      method = ''
      if (allocated(cfg%method)) method = cfg%method
      time_unit = ''
      dt = cfg%dt; t_end = cfg%t_end
      rtol = cfg%rtol; atol = cfg%atol; omega = cfg%omega
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
      group = 'pendulum'
      read (unit, nml=pendulum, iostat=stat, iomsg=msg)
      if (stat <= 0) then
         group = 'initial'
         rewind (unit)
         read (unit, nml=initial, iostat=stat, iomsg=msg)
      end if
      if (stat <= 0) then
         group = 'integration'
         rewind (unit)
         read (unit, nml=integration, iostat=stat, iomsg=msg)
      end if
      if (stat <= 0) then
         group = 'output'
         rewind (unit)
         read (unit, nml=output, iostat=stat, iomsg=msg)
      end if
      close (unit)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, trim(group), msg))
         return
      end if
      r%links = links; r%save_every = save_every; r%max_steps = max_steps
      r%m1 = m1; r%m2 = m2; r%l1 = l1; r%l2 = l2; r%g = g
      r%q1 = q1; r%q2 = q2; r%w1 = w1; r%w2 = w2
      r%dt = dt; r%t_end = t_end; r%rtol = rtol; r%atol = atol
      r%output_dt = output_dt; r%omega = omega
      r%m = m; r%l = l; r%q = q; r%w = w; r%damping = damping
      r%support_amplitude = support_amplitude; r%support_frequency = support_frequency
      r%support_phase = support_phase
      r%com = com; r%inertia = inertia; r%body = body
      r%method = method; r%file = file; r%force = force; r%time_unit = time_unit
   end subroutine read_run_groups

   !> A quantity given in &model and in &pendulum (m and m1, g and g, com and com)
   !> is refused naming both: which one holds would depend on a rule of the reader.
   subroutine check_two_groups(filename, r, cfg, error)
      character(len=*), intent(in) :: filename          !! namelist file
      type(run_groups_t), intent(in) :: r               !! &pendulum as read
      type(run_config_t), intent(in) :: cfg             !! cfg%extra: &model's
      type(error_t), allocatable, intent(out) :: error  !! a quantity given twice
      character(len=:), allocatable :: key, also
      integer :: k
      if (.not. allocated(cfg%extra%items)) return
      do k = 1, size(cfg%extra%items)
         key = cfg%extra%items(k)%name
         also = ''
         select case (key)
         case ('links'); if (r%links /= -huge(1)) also = 'links'
         case ('m'); also = list_or_pair('m', r%m, r%m1, r%m2)
         case ('l'); also = list_or_pair('l', r%l, r%l1, r%l2)
         case ('g'); if (r%g /= unset) also = 'g'
         case ('damping'); if (any(r%damping /= unset)) also = 'damping'
         case ('support_amplitude')
            if (any(r%support_amplitude /= unset)) also = key
         case ('support_frequency'); if (r%support_frequency /= unset) also = key
         case ('support_phase'); if (any(r%support_phase /= unset)) also = key
         case ('com'); if (any(r%com /= unset)) also = 'com'
         case ('inertia'); if (any(r%inertia /= unset)) also = 'inertia'
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
   !> `unset` scalars of those not given take the current values.
   subroutine note_pendulum_given(r, cfg)
      type(run_groups_t), intent(inout) :: r   !! the groups as read
      type(run_config_t), intent(inout) :: cfg !! cfg%given updated
      integer :: k
      if (r%links == -huge(1)) then
         r%links = cfg%links
      else
         call mark_given(cfg, 'links')
      end if
      if (r%g == unset) then
         r%g = cfg%g
      else
         call mark_given(cfg, 'g')
      end if
      if (r%support_frequency == unset) then
         r%support_frequency = cfg%support_frequency
      else
         call mark_given(cfg, 'support_frequency')
      end if
      if (any(r%support_amplitude /= unset)) call mark_given(cfg, 'support_amplitude')
      where (r%support_amplitude == unset) r%support_amplitude = cfg%support_amplitude
      if (any(r%support_phase /= unset)) call mark_given(cfg, 'support_phase')
      where (r%support_phase == unset) r%support_phase = cfg%support_phase
      if (r%m1 /= unset) call mark_given(cfg, 'm1')
      if (r%m2 /= unset) call mark_given(cfg, 'm2')
      if (r%l1 /= unset) call mark_given(cfg, 'l1')
      if (r%l2 /= unset) call mark_given(cfg, 'l2')
      if (r%q1 /= unset) call mark_given(cfg, 'q1')
      if (r%q2 /= unset) call mark_given(cfg, 'q2')
      if (r%w1 /= unset) call mark_given(cfg, 'w1')
      if (r%w2 /= unset) call mark_given(cfg, 'w2')
      do k = 1, 4
         if (any(list_of(r, k) /= unset)) call mark_given(cfg, list_names(k))
      end do
      if (any(r%damping /= unset)) call mark_given(cfg, 'damping')
   end subroutine note_pendulum_given

   !> The namelist list of `list_names(k)` (m, l, q, w).
   function list_of(r, k) result(v)
      type(run_groups_t), intent(in) :: r
      integer, intent(in) :: k
      real(dp) :: v(max_dof)
      select case (k)
      case (1); v = r%m
      case (2); v = r%l
      case (3); v = r%q
      case default; v = r%w
      end select
   end function list_of

   !> The groups as read into the run settings: the scalars the file did not give keep
   !> their values (those it gave are recorded in cfg%nml_given); the lists, where
   !> given, override the two-link names; the body, the method, the output.
   subroutine take_run_groups(filename, r, cfg, error)
      character(len=*), intent(in) :: filename          !! namelist file
      type(run_groups_t), intent(inout) :: r            !! the groups as read
      type(run_config_t), intent(inout) :: cfg          !! updated
      type(error_t), allocatable, intent(out) :: error  !! a list with a gap
      if (.not. allocated(cfg%nml_given)) cfg%nml_given = ' '
      call note_given(cfg, 'm1', r%m1, cfg%m(1)); call note_given(cfg, 'm2', r%m2, cfg%m(2))
      call note_given(cfg, 'l1', r%l1, cfg%l(1)); call note_given(cfg, 'l2', r%l2, cfg%l(2))
      call note_given(cfg, 'q1', r%q1, cfg%q(1)); call note_given(cfg, 'q2', r%q2, cfg%q(2))
      call note_given(cfg, 'w1', r%w1, cfg%w(1)); call note_given(cfg, 'w2', r%w2, cfg%w(2))
      call note_given(cfg, 'output_dt', r%output_dt, cfg%output_dt)
      if (r%save_every == -huge(1)) then
         r%save_every = cfg%save_every
      else
         cfg%nml_given = cfg%nml_given//'save_every '
      end if
      cfg%links = r%links
      cfg%m(1:2) = [r%m1, r%m2]; cfg%l(1:2) = [r%l1, r%l2]; cfg%g = r%g
      cfg%q(1:2) = [r%q1, r%q2]; cfg%w(1:2) = [r%w1, r%w2]
      ! the lists, where given, override the two-link names
      call take_list(filename, cfg, 1, 'm', r%m, cfg%m, error)
      if (.not. allocated(error)) call take_list(filename, cfg, 2, 'l', r%l, cfg%l, error)
      if (.not. allocated(error)) call take_list(filename, cfg, 3, 'q', r%q, cfg%q, error)
      if (.not. allocated(error)) call take_list(filename, cfg, 4, 'w', r%w, cfg%w, error)
      if (.not. allocated(error)) call take_list(filename, cfg, 0, 'damping', r%damping, &
                                                 cfg%damping, error)
      if (.not. allocated(error)) call take_body(filename, cfg, r%body, r%com, r%inertia, &
                                                 error)
      if (allocated(error)) return
      cfg%support_amplitude = r%support_amplitude; cfg%support_frequency = r%support_frequency
      cfg%support_phase = r%support_phase
      if (len_trim(r%method) > 0) cfg%method = canonical_name(trim(r%method), method_names())
      cfg%dt = r%dt; cfg%t_end = r%t_end; cfg%save_every = r%save_every
      cfg%rtol = r%rtol; cfg%atol = r%atol; cfg%output_dt = r%output_dt; cfg%omega = r%omega
      cfg%max_steps = r%max_steps
      if (len_trim(r%time_unit) > 0) then
         call set_time_unit(cfg, trim(r%time_unit), "namelist &integration time_unit in '" &
                            //printable(filename)//"'", error)
         if (allocated(error)) return
         call mark_given(cfg, 'time_unit')
      end if
      if (len_trim(r%file) > 0) cfg%output = trim(r%file)
      cfg%force = r%force
   end subroutine take_run_groups

   !> The parameters &model gives that the run holds as fields (links, m, l, g,
   !> damping, the support's motion) go into those fields, as &pendulum's do, so
   !> that a flag overrides either the same way (flags over the file) and the file
   !> records the values the run used. A value of the wrong count or kind stays a
   !> named parameter, for the factory's refusal.
   subroutine take_model_fields(cfg)
      type(run_config_t), intent(inout) :: cfg  !! cfg%extra: &model's parameters
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
   subroutine note_given(cfg, key, x, current)
      type(run_config_t), intent(inout) :: cfg
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
   subroutine take_body(filename, cfg, kind, d, ic, error)
      character(len=*), intent(in) :: filename
      type(run_config_t), intent(inout) :: cfg
      character(len=*), intent(in) :: kind
      real(dp), intent(in) :: d(:), ic(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: n
      if (len_trim(kind) > 0) call set_body(cfg, trim(kind), error)
      if (allocated(error)) return
      n = count_given(filename, 'com', d, error)
      if (allocated(error)) return
      if (n > 0) call cfg%extra%set('com', d(:n))
      n = count_given(filename, 'inertia', ic, error)
      if (allocated(error)) return
      if (n > 0) call cfg%extra%set('inertia', ic(:n))
   end subroutine take_body

   !> The leading entries given of the list `key`; an entry given after one that
   !> is not (`m(2) = 3` without m(1)) is refused, never ignored.
   integer function count_given(filename, key, given, error) result(n)
      character(len=*), intent(in) :: filename, key
      real(dp), intent(in) :: given(:)
      type(error_t), allocatable, intent(inout) :: error
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
   subroutine take_list(filename, cfg, k, key, given, values, error)
      character(len=*), intent(in) :: filename
      type(run_config_t), intent(inout) :: cfg
      integer, intent(in) :: k
      character(len=*), intent(in) :: key
      real(dp), intent(in) :: given(:)
      real(dp), intent(inout) :: values(:)
      type(error_t), allocatable, intent(inout) :: error
      integer :: n
      n = count_given(filename, key, given, error)
      if (allocated(error)) return
      if (n == 0) return
      values(:n) = given(:n)
      if (k > 0) then
         cfg%list_size(k) = n
      else
         cfg%damping_size = n
      end if
   end subroutine take_list

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
