!> Run configuration shared by every command: a Fortran namelist file
!> (`--config FILE`, commented examples in data/) and command-line flags that
!> override it. Groups: &pendulum (m1 m2 l1 l2 g), &initial (q1 q2 w1 w2),
!> &integration (method dt t_end save_every rtol atol output_dt omega),
!> &output (file force). Commands with more settings read further groups
!> through `check_groups` and their own namelists.
module dpend_config
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: pendulum_t, validate, finite_positive
   use dpend_cli, only: arg_t, parse_real, parse_int, real_str
   use dpend_kinds, only: i8
   use dpend_limits, only: in_range, check_range, check_count, max_angle, max_angular_velocity, &
                           max_time, max_dt, min_rtol, min_atol, max_atol, max_omega, &
                           max_steps, default_max_steps, sci
   use dpend_integrator, only: integrator_t
   use dpend_integrators, only: new_integrator
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: run_config_t, read_run_config, apply_run_flag, validate_run_config
   public :: check_groups, run_flags_help, check_output_file, namelist_error


   !> Everything a single run needs (SI units, angles in rad from the horizontal x axis).
   type :: run_config_t
      type(pendulum_t) :: par                  !! physical parameters
      real(dp) :: q0(2) = [0.0_dp, 0.0_dp]     !! initial angles [rad]
      real(dp) :: w0(2) = [0.0_dp, 0.0_dp]     !! initial angular velocities [rad/s]
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
   end type run_config_t

contains

   !> Fail if `filename` holds a namelist group not in `known` (names without '&').
   subroutine check_groups(filename, known, error)
      character(len=*), intent(in) :: filename          !! the namelist file
      character(len=*), intent(in) :: known(:)          !! accepted group names
      type(error_t), allocatable, intent(out) :: error  !! unknown group or unreadable
      integer :: unit, stat, amp, bang, e
      character(len=1024) :: line
      character(len=:), allocatable :: group
      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//filename//"'")
         return
      end if
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         bang = index(line, '!')
         if (bang > 0) line(bang:) = ' '
         amp = index(line, '&')
         if (amp == 0) cycle
         e = scan(line(amp + 1:), ' ,/') + amp
         if (e == amp) e = len_trim(line) + 1
         group = to_lower(line(amp + 1:e - 1))
         if (len(group) == 0 .or. group == 'end') cycle
         if (.not. any(known == group)) then
            call fatal_error(error, "invalid config '"//filename//"': unknown namelist group &" &
                             //group//' (accepted: &'//join(known)//')')
            exit
         end if
      end do
      close (unit)
   contains
      pure function join(list) result(s)
         character(len=*), intent(in) :: list(:)
         character(len=:), allocatable :: s
         integer :: k
         s = trim(list(1))
         do k = 2, size(list)
            s = s//' &'//trim(list(k))
         end do
      end function join
   end subroutine check_groups

   !> The message for a failed namelist read, naming the group and the offending key.
   function namelist_error(filename, group, iomsg) result(msg)
      character(len=*), intent(in) :: filename  !! file
      character(len=*), intent(in) :: group     !! group name
      character(len=*), intent(in) :: iomsg     !! the runtime's message
      character(len=:), allocatable :: msg
      msg = "invalid config '"//filename//"' in &"//group//': '//trim(iomsg)
   end function namelist_error

   !> Read the groups of a run configuration present in `filename` into `cfg`.
   subroutine read_run_config(filename, cfg, error, extra_groups)
      character(len=*), intent(in) :: filename               !! namelist file
      type(run_config_t), intent(inout) :: cfg               !! updated from the file
      type(error_t), allocatable, intent(out) :: error       !! unreadable or invalid
      character(len=*), intent(in), optional :: extra_groups(:) !! groups of the command
      real(dp) :: m1, m2, l1, l2, g, q1, q2, w1, w2, dt, t_end, rtol, atol, output_dt, omega
      integer :: save_every, unit, stat, n_extra, i
      integer(i8) :: max_steps
      character(len=64) :: method
      character(len=1024) :: file
      character(len=512) :: msg
      logical :: force
      character(len=16), allocatable :: known(:)
      namelist /pendulum/ m1, m2, l1, l2, g
      namelist /initial/ q1, q2, w1, w2
      namelist /integration/ method, dt, t_end, save_every, rtol, atol, output_dt, omega, &
         max_steps
      namelist /output/ file, force

      n_extra = 0
      if (present(extra_groups)) n_extra = size(extra_groups)
      allocate (known(4 + n_extra))
      known(1:4) = [character(len=16) :: 'pendulum', 'initial', 'integration', 'output']
      ! element by element: gfortran's -fcheck=all rejects a typed array constructor
      ! over an array of another character length
      do i = 1, n_extra
         known(4 + i) = extra_groups(i)
      end do
      call check_groups(filename, known, error)
      if (allocated(error)) return

      m1 = cfg%par%m1; m2 = cfg%par%m2; l1 = cfg%par%l1; l2 = cfg%par%l2; g = cfg%par%g
      q1 = cfg%q0(1); q2 = cfg%q0(2); w1 = cfg%w0(1); w2 = cfg%w0(2)
      method = ''
      if (allocated(cfg%method)) method = cfg%method
      dt = cfg%dt; t_end = cfg%t_end; save_every = cfg%save_every
      rtol = cfg%rtol; atol = cfg%atol; output_dt = cfg%output_dt; omega = cfg%omega
      max_steps = cfg%max_steps
      file = ''
      if (allocated(cfg%output)) file = cfg%output
      force = cfg%force

      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//filename//"'")
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

      cfg%par = pendulum_t(m1=m1, m2=m2, l1=l1, l2=l2, g=g)
      cfg%q0 = [q1, q2]; cfg%w0 = [w1, w2]
      if (len_trim(method) > 0) cfg%method = trim(method)
      cfg%dt = dt; cfg%t_end = t_end; cfg%save_every = save_every
      cfg%rtol = rtol; cfg%atol = atol; cfg%output_dt = output_dt; cfg%omega = omega
      cfg%max_steps = max_steps
      if (len_trim(file) > 0) cfg%output = trim(file)
      cfg%force = force
   end subroutine read_run_config

   !> Apply one of the common flags; `matched` is false if `name` is not one of them.
   subroutine apply_run_flag(cfg, name, value, matched, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration to update
      character(len=*), intent(in) :: name              !! option, e.g. '--dt'
      character(len=*), intent(in) :: value             !! its value
      logical, intent(out) :: matched                   !! whether it was a common flag
      type(error_t), allocatable, intent(out) :: error  !! invalid value
      matched = .true.
      select case (name)
      case ('--q1'); call parse_real(value, name, cfg%q0(1), error)
      case ('--q2'); call parse_real(value, name, cfg%q0(2), error)
      case ('--w1'); call parse_real(value, name, cfg%w0(1), error)
      case ('--w2'); call parse_real(value, name, cfg%w0(2), error)
      case ('--m1'); call parse_real(value, name, cfg%par%m1, error)
      case ('--m2'); call parse_real(value, name, cfg%par%m2, error)
      case ('--l1'); call parse_real(value, name, cfg%par%l1, error)
      case ('--l2'); call parse_real(value, name, cfg%par%l2, error)
      case ('--g'); call parse_real(value, name, cfg%par%g, error)
      case ('--method'); cfg%method = value
      case ('--dt'); call parse_real(value, name, cfg%dt, error)
      case ('--t-end'); call parse_real(value, name, cfg%t_end, error)
      case ('--save-every'); call parse_int(value, name, cfg%save_every, error)
      case ('--rtol'); call parse_real(value, name, cfg%rtol, error)
      case ('--atol'); call parse_real(value, name, cfg%atol, error)
      case ('--output-dt'); call parse_real(value, name, cfg%output_dt, error)
      case ('--omega'); call parse_real(value, name, cfg%omega, error)
      case ('--max-steps'); call parse_i8(value, name, cfg%max_steps, error)
      case ('--output', '-o'); cfg%output = value
      case default
         matched = .false.
      end select
   end subroutine apply_run_flag

   !> Check the whole configuration; messages name the field and the accepted range
   !> (the limits and their reasons are in `dpend_limits`). For a fixed-step method
   !> the number of steps t_end/dt is at most `max_steps`; an adaptive method stops
   !> after `max_steps` accepted steps instead (`--max-steps`).
   subroutine validate_run_config(cfg, error)
      type(run_config_t), intent(in) :: cfg             !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      character(len=*), parameter :: qn(2) = ['q1', 'q2'], wn(2) = ['w1', 'w2']
      class(integrator_t), allocatable :: integ
      integer :: i
      call validate(cfg%par, error)
      if (allocated(error)) then
         error%message = error%message//' [--m1 --m2 --l1 --l2 --g / &pendulum]'
         return
      end if
      do i = 1, 2
         call check_range(qn(i), cfg%q0(i), -max_angle, max_angle, 'rad', error, &
                          'beyond, the rounding of the angle exceeds 1e-10 rad')
         if (allocated(error)) return
      end do
      do i = 1, 2
         call check_range(wn(i), cfg%w0(i), -max_angular_velocity, max_angular_velocity, &
                          'rad/s', error, 'keeps energies and momenta finite')
         if (allocated(error)) return
      end do
      if (.not. allocated(cfg%method)) then
         call fatal_error(error, 'invalid method: none given')
         return
      end if
      call new_integrator(cfg%method, integ, error)
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

   !> Parse a 64-bit integer for field `name`.
   subroutine parse_i8(text, name, n, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      integer(i8), intent(out) :: n                     !! the value
      type(error_t), allocatable, intent(out) :: error  !! not an integer
      integer :: stat
      n = 0
      if (len_trim(text) == 0 .or. len_trim(text) > 19 .or. &
          verify(trim(text), '0123456789+-') /= 0) then
         call fatal_error(error, 'invalid '//name//": '"//trim(text)//"' is not an integer")
         return
      end if
      read (text, *, iostat=stat) n
      if (stat /= 0) call fatal_error(error, 'invalid '//name//": '"//trim(text)// &
                                      "' is not an integer")
   end subroutine parse_i8

   !> Refuse an output path whose directory is missing or unwritable, or that exists
   !> without `force`. Creates and removes nothing.
   subroutine check_output_file(filename, force, error)
      character(len=*), intent(in) :: filename          !! output path
      logical, intent(in) :: force                      !! overwrite allowed
      type(error_t), allocatable, intent(out) :: error  !! why it cannot be written
      logical :: exists
      character(len=:), allocatable :: dir
      integer :: slash, stat, unit
      if (len_trim(filename) == 0) then
         call fatal_error(error, 'invalid --output: empty file name')
         return
      end if
      inquire (file=filename, exist=exists)
      if (exists .and. .not. force) then
         call fatal_error(error, "invalid --output: '"//filename// &
                          "' exists (use --force to overwrite)")
         return
      end if
      slash = index(filename, '/', back=.true.)
      dir = '.'
      if (slash == 1) dir = '/'
      if (slash > 1) dir = filename(:slash - 1)
      inquire (file=dir//'/.', exist=exists)
      if (.not. exists) then
         call fatal_error(error, "invalid --output: directory '"//dir//"' does not exist")
         return
      end if
      ! probe with a scratch file of another name: the output itself is not touched
      open (newunit=unit, file=dir//'/.dpend-write-probe', status='replace', &
            action='write', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --output: directory '"//dir//"' is not writable")
         return
      end if
      close (unit, status='delete')
   end subroutine check_output_file

   !> Help lines for the common flags, with units and the defaults of `cfg`.
   function run_flags_help(cfg) result(s)
      type(run_config_t), intent(in) :: cfg  !! defaults to show
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = '  --config FILE     Fortran namelist file (groups &pendulum &initial &integration' &
          //nl//'                    &output; see data/*.nml); flags below override it'//nl// &
          '  --q1, --q2 RAD    initial angles from the horizontal x axis, counter-clockwise' &
          //nl//'                    (hanging: -1.5707963); default '//real_str(cfg%q0(1))//', ' &
          //real_str(cfg%q0(2))//nl// &
          '  --w1, --w2 RAD/S  initial angular velocities; default '//real_str(cfg%w0(1))//', ' &
          //real_str(cfg%w0(2))//nl// &
          '  --m1, --m2 KG     link masses (m1 m2 l1 l2 g: each in [1e-6, 1e6]); default ' &
          //real_str(cfg%par%m1)//', ' &
          //real_str(cfg%par%m2)//nl// &
          '  --l1, --l2 M      link lengths; default '//real_str(cfg%par%l1)//', ' &
          //real_str(cfg%par%l2)//nl// &
          '  --g M/S^2         gravitational acceleration; default '//real_str(cfg%par%g)//nl// &
          '  --method NAME     integrator (dpend methods lists them); default '//cfg%method//nl// &
          '  --dt S            step (first trial step for adaptive methods); default ' &
          //real_str(cfg%dt)//nl// &
          '  --t-end S         end time; default '//real_str(cfg%t_end)//nl// &
          '  --rtol, --atol    tolerances of the adaptive methods; default '//real_str(cfg%rtol) &
          //', '//real_str(cfg%atol)//nl// &
          "  --omega 1/S       binding constant of Tao's methods; default "//real_str(cfg%omega)// &
          nl//'  --max-steps N     most accepted steps of one integration of an adaptive'//nl// &
          '                    method (steps); reaching it stops the run; default ' &
          //int8_text(cfg%max_steps)
   end function run_flags_help

   pure function int8_text(n) result(s)
      integer(i8), intent(in) :: n
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') n
      s = trim(buf)
   end function int8_text

   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: i
      t = s
      do i = 1, len(s)
         if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
      end do
   end function to_lower
end module dpend_config
