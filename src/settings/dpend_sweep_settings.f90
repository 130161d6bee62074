!> The settings of a sweep (`dpend sweep`, the MPI front end, library callers): the
!> run settings (&pendulum,
!> &initial for the values that are not swept, &integration for dt and t_end,
!> &output) plus those of &sweep below, their validation (`validate_sweep`) and what follows
!> from them: the time unit, the stop rule, the axes and a pixel's model.
!>
!> &sweep keys (docs/sweep.md):
!>   axis1, axis2   swept initial values: 'theta1' 'theta2' (angles from the hanging
!>                  position, θ = q + π/2), 'q1' 'q2' (from the horizontal x axis),
!>                  'w1' 'w2' (angular velocities) [rad, rad/s]; for N links any of
!>                  theta1..thetaN, q1..qN, w1..wN; or a parameter (grids of 2 or
!>                  more links): 'm1' 'm2' [kg], 'l1' 'l2' [m] of links 1 and 2, or the
!>                  ratios 'm2/m1' (m2 = value m1), 'l2/l1' (l2 = value l1) [1] (rods
!>                  and point masses); the natural time unit stays √(l1/g) of the
!>                  configured l1; any other real parameter of the pendulum by name
!>                  (`pendulum_axis`: g, m3.., l3.., com1.., inertia1..; not damping
!>                  or support_*), each pixel its own model on the per-trajectory
!>                  path; a model without flips: its real scalar parameters
!>                  by name (`model_axis`: the elastic pendulum's m, k, l0, g)
!>   n1, n2         points per axis (>= 1); min1, max1, min2, max2 the axis ranges
!>   ic_file        a list of initial conditions instead of a grid: a text file of
!>                  rows "q1 q2 w1 w2" or an HDF5 file (dataset ic_dataset, (n, 4));
!>                  for N links rows "q1 .. qN w1 .. wN", (n, 2N)
!>   ic_dataset     dataset of an HDF5 list, default '/initial'
!>   ic_angles      angles of a list: 'q' (from horizontal, default) or 'theta'
!>   time_unit      unit of dt and t_end: 's' or 'natural' (√(L1/g))
!>   stop_at        'both' (every link that can flip has flipped), 'either', 'end'
!>   block          initial conditions per block (unit of parallel work, output
!>                  chunks and resume); whole rows of axis 1 in a grid
!>   lyapunov       also the largest Lyapunov exponent (runs every trajectory to t_end)
!>   indicator      per-pixel chaos indicator beside the flip time: 'flip' (none),
!>                  'lambda1' (= lyapunov), 'megno', 'fli', 'sali', 'gali2' (every
!>                  trajectory to t_end)
!>   stats          also the number of steps of every trajectory
!>   threads        OpenMP threads (0: all; not part of the stored configuration)
module dpend_sweep_settings
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: real_str, to_str, printable
   use dpend_lane_batch, only: stop_both, stop_either, stop_end
   use dpend_limits, only: sci, max_threads, max_axis_points, max_sweep_points, max_angle, &
      max_angular_velocity, max_time, check_parameter, parameter_mass, parameter_length
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t
   use dpend_model_factory, only: model_spec_t, new_model, model_info_t, model_catalogue, &
      find_model, spec_values
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_strings, only: to_lower, did_you_mean
   use dpend_run_settings, only: run_config_t, validate_run_config
   implicit none
   private
   public :: sweep_config_t, sweep_defaults, validate_sweep, axis_names, time_scale, &
      stop_rule, grid_mode, axis_variable, indicator_names, indicator_vectors, &
      axis_parameter, param_axis_names, pixel_parameters, pixel_model, flip_model, &
      sweep_variable, natural_time, horizon_text
   public :: model_axis, model_axis_names, pixel_model_named, pixel_pendulum, pixel_pendulums
   public :: pendulum_axis, pendulum_param_names, pendulum_param_values, pixel_model_axes, &
      named_axis_units, coded_axes

   !> Names accepted for axis1 and axis2 (two links; `accepted_axes` for N).
   character(len=*), parameter :: axis_names = 'theta1 theta2 q1 q2 w1 w2'

   !> Parameters accepted as axes (grids of two or more links).
   character(len=*), parameter :: param_axis_names = 'm1 m2 l1 l2 m2/m1 l2/l1'

   !> Parameters of the pendulum's catalogue row that are not axes: the sweep
   !> integrates the conservative chain only (damping and the support's motion 0),
   !> and the support's amplitudes and phases are pairs.
   character(len=*), parameter :: unswept_parameters = &
      ' links damping support_amplitude support_frequency support_phase '

   !> Names accepted for the per-pixel indicator.
   character(len=*), parameter :: indicator_names = 'flip lambda1 megno fli sali gali2'

   !> Everything `dpend sweep` needs.
   type :: sweep_config_t
      type(run_config_t) :: run                    !! parameters, fixed initial values,
                                                   !! dt, t_end, output, force
      character(len=:), allocatable :: axis1       !! first swept value (fastest index)
      character(len=:), allocatable :: axis2       !! second swept value
      integer :: n1 = 256                          !! points on axis 1
      integer :: n2 = 256                          !! points on axis 2
      real(dp) :: min1 = -3.0_dp                   !! axis 1 from [rad or rad/s]
      real(dp) :: max1 = 3.0_dp                    !! axis 1 to
      real(dp) :: min2 = -3.0_dp                   !! axis 2 from
      real(dp) :: max2 = 3.0_dp                    !! axis 2 to
      character(len=:), allocatable :: ic_file     !! list of initial conditions ('' = grid)
      character(len=:), allocatable :: ic_dataset  !! dataset of an HDF5 list
      character(len=:), allocatable :: ic_angles   !! 'q' or 'theta'
      !> Whether ic_dataset, ic_angles were given (flag or namelist): both describe the
      !> list of --ic-file and are refused without it.
      logical :: ic_dataset_given = .false., ic_angles_given = .false.
      character(len=:), allocatable :: time_unit   !! 's' or 'natural'
      character(len=:), allocatable :: stop_at     !! 'both', 'either' or 'end'
      integer :: block = 4096                      !! initial conditions per block
      logical :: lyapunov = .false.                !! largest Lyapunov exponent
      character(len=:), allocatable :: indicator   !! 'flip', 'lambda1', 'megno', 'fli',
                                                   !! 'sali' or 'gali2'
      logical :: stats = .false.                   !! steps per trajectory
      integer :: threads = 0                       !! OpenMP threads, 0: all
      logical :: quiet = .false.                   !! no progress report
      !> The grid's axes and ranges given (' --axis1 min1 ': flags, namelist keys), refused
      !> with a list (--ic-file) that they would not describe (`check_sweep_forms`).
      character(len=:), allocatable :: grid_given
      !> The stop rule as given ('' if not given): refused with an indicator or the
      !> Lyapunov exponent, which integrate every trajectory to t_end.
      character(len=:), allocatable :: stop_at_given
      ! the device (docs/gpu.md); not part of the stored configuration
      character(len=:), allocatable :: device       !! 'cpu', 'gpu', 'auto' ('auto' resolved)
      character(len=:), allocatable :: device_name  !! the GPU's name when device = 'gpu'
      character(len=:), allocatable :: device_note  !! one line for stderr ('' : none)
      integer :: gpu_repack = 2048                  !! GPU: steps per launch, 0: one launch
      logical :: block_given = .false.              !! --block or block given
   end type sweep_config_t

contains

   !> Defaults: the classic flip map at 256 x 256 over θ1, θ2 in [-3, 3] rad from rest,
   !> the chapter's parameters, 100 √(L1/g), step 0.01 √(L1/g).
   function sweep_defaults() result(cfg)
      type(sweep_config_t) :: cfg
      cfg%run%method = 'rk4'
      cfg%run%dt = 0.01_dp
      cfg%run%t_end = 100.0_dp
      cfg%run%output = 'sweep.h5'
      cfg%run%q = 0.0_dp
      cfg%run%w = 0.0_dp
      cfg%axis1 = 'theta1'
      cfg%axis2 = 'theta2'
      cfg%ic_file = ''
      cfg%ic_dataset = '/initial'
      cfg%ic_angles = 'q'
      cfg%time_unit = 'natural'
      cfg%stop_at = 'both'
      cfg%indicator = 'flip'
      cfg%grid_given = ' '
      cfg%stop_at_given = ''
      cfg%device = 'cpu'; cfg%device_name = ''; cfg%device_note = ''
   end function sweep_defaults

   !> Deviation vectors of the batch kernel for the indicator: 0 (flip, lambda1: the
   !> Lyapunov exponent has its own), 1 (megno, fli), 2 (sali, gali2).
   pure integer function indicator_vectors(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      select case (cfg%indicator)
      case ('megno', 'fli'); indicator_vectors = 1
      case ('sali', 'gali2'); indicator_vectors = 2
      case default; indicator_vectors = 0
      end select
   end function indicator_vectors

   !> True for a grid, false for a list of initial conditions.
   pure logical function grid_mode(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      grid_mode = len_trim(cfg%ic_file) == 0
   end function grid_mode

   !> Seconds per unit of dt and t_end: 1 or the natural unit (`natural_time`).
   real(dp) function time_scale(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      time_scale = 1.0_dp
      if (cfg%time_unit == 'natural') time_scale = natural_time(cfg)
   end function time_scale

   !> The natural time unit [s] of the run's model (`time_unit`: √(l1/g) of the
   !> configured l1 for the pendulum of any N, √(l0/g) for the elastic pendulum);
   !> parameter sweeps keep the unit of the configured model.
   real(dp) function natural_time(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: name
      call cfg%run%model%time_unit(natural_time, name)
   end function natural_time

   !> The name of the natural time unit of the run's model, e.g. 'sqrt(l1/g)'.
   function natural_name(cfg) result(name)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: name
      real(dp) :: seconds
      call cfg%run%model%time_unit(seconds, name)
   end function natural_name

   !> True if the run's model has rods that flip (a potential V = Σ G_i sin q_i of
   !> its angles: the pendulum of any N): the flip map, its stop rules, t_flip and the
   !> flip energy bounds apply. False for the elastic pendulum.
   logical function flip_model(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      flip_model = size(cfg%run%model%potential_weights()) == cfg%run%model%n_dof()
   end function flip_model

   !> Index in the state (q, q̇) of the initial value an axis sweeps, 0 for an unknown
   !> name: `axis_variable` for the pendulum; for another model qk and wk, or its
   !> coordinate names (k) and those names followed by 'dot' (n + k).
   integer function sweep_variable(cfg, name) result(var)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: name     !! axis name
      character(len=:), allocatable :: cname, units, punits
      integer :: k, n
      if (flip_model(cfg)) then
         var = axis_variable(name, cfg%run%links)
         return
      end if
      n = cfg%run%model%n_dof()
      var = 0
      if (index(name, 'theta') /= 1) var = axis_variable(name, n)
      do k = 1, n
         call cfg%run%model%coordinate(k, cname, units, punits)
         if (name == cname) var = k
         if (name == cname//'dot') var = n + k
      end do
   end function sweep_variable

   !> The stop rule of the kernel (stop_end with the Lyapunov exponent).
   pure integer function stop_rule(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      select case (cfg%stop_at)
      case ('either'); stop_rule = stop_either
      case ('end'); stop_rule = stop_end
      case default; stop_rule = stop_both
      end select
      if (cfg%lyapunov .or. indicator_vectors(cfg) > 0) stop_rule = stop_end
   end function stop_rule

   !> The parameter an axis sweeps: 1 m1, 2 m2, 3 l1, 4 l2, 5 m2/m1, 6 l2/l1; 0 for
   !> an initial value or an unknown name.
   pure integer function axis_parameter(name)
      character(len=*), intent(in) :: name  !! axis name
      select case (name)
      case ('m1'); axis_parameter = 1
      case ('m2'); axis_parameter = 2
      case ('l1'); axis_parameter = 3
      case ('l2'); axis_parameter = 4
      case ('m2/m1'); axis_parameter = 5
      case ('l2/l1'); axis_parameter = 6
      case default; axis_parameter = 0
      end select
   end function axis_parameter

   !> (m1, m2, l1, l2) of a pixel: the configured ones with the values x1, x2 of the
   !> parameter axes p1, p2 (axis_parameter codes, 0: an initial value), the masses
   !> and lengths first, then the ratios (m2 = r m1 with m1 possibly swept).
   pure function pixel_parameters(cfg, p1, x1, p2, x2) result(p)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      integer, intent(in) :: p1, p2            !! axis_parameter of axis 1 and 2
      real(dp), intent(in) :: x1, x2           !! the pixel's axis values
      real(dp) :: p(4)
      p = [cfg%run%m(1), cfg%run%m(2), cfg%run%l(1), cfg%run%l(2)]
      if (p1 >= 1 .and. p1 <= 4) p(p1) = x1
      if (p2 >= 1 .and. p2 <= 4) p(p2) = x2
      if (p1 == 5) p(2) = x1*p(1)
      if (p2 == 5) p(2) = x2*p(1)
      if (p1 == 6) p(4) = x1*p(3)
      if (p2 == 6) p(4) = x2*p(3)
   end function pixel_parameters

   !> The model of a pixel of a parameter sweep, from the factory: a copy of the run's
   !> specification (`cfg%run%spec`) with the masses and lengths of links 1 and 2 set
   !> by name to p = (m1, m2, l1, l2) of `pixel_parameters`.
   subroutine pixel_model(cfg, p, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      real(dp), intent(in) :: p(4)                       !! (m1, m2, l1, l2) [kg, kg, m, m]
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      spec = cfg%run%spec
      call coded_spec(cfg, p, spec)
      call new_model(spec, model, error)
   end subroutine pixel_model

   !> Set the masses and lengths of links 1 and 2 of `spec` to p = (m1, m2, l1, l2)
   !> of `pixel_parameters` (point masses: com and inertia follow the lengths).
   subroutine coded_spec(cfg, p, spec)
      type(sweep_config_t), intent(in) :: cfg     !! configuration, model built
      real(dp), intent(in) :: p(4)                !! (m1, m2, l1, l2) [kg, kg, m, m]
      type(model_spec_t), intent(inout) :: spec   !! the pixel's specification
      real(dp), allocatable :: m(:), l(:)
      m = spec%get('m', cfg%run%m(:cfg%run%links))
      l = spec%get('l', cfg%run%l(:cfg%run%links))
      m(1:2) = p(1:2); l(1:2) = p(3:4)
      call spec%set('m', m)
      call spec%set('l', l)
      if (point_masses(cfg)) then   ! the body follows the pixel's lengths
         call spec%set('com', l)
         call spec%set('inertia', spread(0.0_dp, 1, size(l)))
      end if
   end subroutine coded_spec

   !> True if an axis of the grid is a coded parameter axis (m1 m2 l1 l2 m2/m1 l2/l1).
   pure logical function coded_axes(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      coded_axes = axis_parameter(cfg%axis1) > 0 .or. axis_parameter(cfg%axis2) > 0
   end function coded_axes

   !> Whether `axis` sweeps a parameter of the pendulum by name, beside the coded
   !> axes (`axis_parameter`): a real scalar of its catalogue row (g) or component k
   !> of a per-link list, k = 1 .. N (m3, l3, com1, inertia2, ...). Not the
   !> parameters of `unswept_parameters`.
   logical function pendulum_axis(cfg, axis)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      character(len=:), allocatable :: base
      integer :: k
      pendulum_axis = .false.
      if (.not. flip_model(cfg)) return
      if (axis_parameter(axis) > 0 .or. axis_variable(axis, cfg%run%links) > 0) return
      call split_axis(cfg, axis, base, k)
      pendulum_axis = len(base) > 0
   end function pendulum_axis

   !> The catalogue parameter `base` of a named pendulum axis and its link k (0 for a
   !> scalar); base = '' if `axis` is none.
   subroutine split_axis(cfg, axis, base, k)
      type(sweep_config_t), intent(in) :: cfg             !! configuration, model built
      character(len=*), intent(in) :: axis                !! axis name
      character(len=:), allocatable, intent(out) :: base  !! catalogue name or ''
      integer, intent(out) :: k                           !! link, 0: a scalar
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, d, stat
      base = ''; k = 0
      models = model_catalogue()
      m = find_model(models, cfg%run%spec%model_name())
      if (m == 0 .or. len_trim(axis) == 0) return
      do i = 1, size(models(m)%params)
         associate (p => models(m)%params(i))
            if (p%integer_valued .or. index(unswept_parameters, ' '//p%name//' ') > 0) cycle
            if (p%count == 1 .and. axis == p%name) then
               base = p%name; k = 0
               return
            else if (p%count == -1 .and. index(axis, p%name) == 1 .and. &
                     len(axis) > len(p%name) .and. len(axis) <= len(p%name) + 3) then
               d = len(p%name) + 1
               if (verify(axis(d:), '0123456789') /= 0 .or. axis(d:d) == '0') cycle
               read (axis(d:), *, iostat=stat) k
               if (stat /= 0 .or. k < 1 .or. k > cfg%run%links) then
                  k = 0
                  cycle
               end if
               base = p%name
               return
            end if
         end associate
      end do
   end subroutine split_axis

   !> The units of a named pendulum axis (its catalogue parameter's), '' if none.
   function named_axis_units(cfg, axis) result(units)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      character(len=:), allocatable :: units, base
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, k
      units = ''
      call split_axis(cfg, axis, base, k)
      if (len(base) == 0) return
      models = model_catalogue()
      m = find_model(models, cfg%run%spec%model_name())
      do i = 1, size(models(m)%params)
         if (models(m)%params(i)%name == base) units = models(m)%params(i)%units
      end do
   end function named_axis_units

   !> The named pendulum axes of N links for messages: ' m3..mN l3..lN g com1..comN
   !> inertia1..inertiaN' (the per-link lists beyond the coded m1 m2 l1 l2).
   function pendulum_axis_text(links) result(s)
      integer, intent(in) :: links  !! number of links N
      character(len=:), allocatable :: s
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, first
      s = ''
      models = model_catalogue()
      m = find_model(models, 'pendulum')
      do i = 1, size(models(m)%params)
         associate (p => models(m)%params(i))
            if (p%integer_valued .or. index(unswept_parameters, ' '//p%name//' ') > 0) cycle
            if (p%count == 1) then
               s = s//' '//p%name
            else if (p%count == -1) then
               first = 1
               if (p%name == 'm' .or. p%name == 'l') first = 3   ! m1 m2 l1 l2: coded
               if (links < first) cycle
               if (links == first) then
                  s = s//' '//p%name//to_str(first)
               else if (links == first + 1) then
                  s = s//' '//p%name//to_str(first)//' '//p%name//to_str(links)
               else
                  s = s//' '//p%name//to_str(first)//'..'//p%name//to_str(links)
               end if
            end if
         end associate
      end do
   end function pendulum_axis_text

   !> The parameters recorded per pixel of a pendulum map with a named axis
   !> (`pendulum_axis`): m1 m2 l1 l2 with a coded axis, then each named axis.
   function pendulum_param_names(cfg) result(names)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=32), allocatable :: names(:)
      character(len=32) :: all(6)
      integer :: n
      n = 0
      if (coded_axes(cfg)) then
         all(1:4) = [character(len=32) :: 'm1', 'm2', 'l1', 'l2']
         n = 4
      end if
      if (pendulum_axis(cfg, cfg%axis1)) then
         n = n + 1
         all(n) = cfg%axis1
      end if
      if (pendulum_axis(cfg, cfg%axis2)) then
         n = n + 1
         all(n) = cfg%axis2
      end if
      names = all(:n)
   end function pendulum_param_names

   !> The values of `pendulum_param_names` of the pixel at axis values (x1, x2).
   function pendulum_param_values(cfg, x1, x2) result(p)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: x1, x2           !! the pixel's axis values
      real(dp), allocatable :: p(:)
      real(dp) :: all(6)
      integer :: n
      n = 0
      if (coded_axes(cfg)) then
         all(1:4) = pixel_parameters(cfg, axis_parameter(cfg%axis1), x1, &
                                     axis_parameter(cfg%axis2), x2)
         n = 4
      end if
      if (pendulum_axis(cfg, cfg%axis1)) then
         n = n + 1
         all(n) = x1
      end if
      if (pendulum_axis(cfg, cfg%axis2)) then
         n = n + 1
         all(n) = x2
      end if
      p = all(:n)
   end function pendulum_param_values

   !> The model of a pixel of a pendulum map with a named axis, from the factory: a
   !> copy of the run's specification with (m1, m2, l1, l2) = x(1:4) as
   !> `pixel_model` when names(1:4) are those of a coded axis, then each named
   !> parameter (`pendulum_param_names`) set by name: a scalar to x(k), a per-link
   !> list's component to x(k), its other components those the run's model uses
   !> (`spec_values`: com and inertia of rods follow the pixel's m and l).
   subroutine pixel_model_axes(cfg, names, x, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      character(len=*), intent(in) :: names(:)           !! `pendulum_param_names`
      real(dp), intent(in) :: x(:)                       !! the pixel's values of names
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      character(len=:), allocatable :: base
      real(dp), allocatable :: v(:)
      integer :: j, k, first
      spec = cfg%run%spec
      first = 1
      if (size(names) >= 4) then
         if (names(1) == 'm1' .and. names(4) == 'l2') then   ! a coded axis
            call coded_spec(cfg, x(1:4), spec)
            first = 5
         end if
      end if
      do j = first, size(names)
         call split_axis(cfg, trim(names(j)), base, k)
         if (len(base) == 0) error stop 'internal error: not a pendulum axis: '//trim(names(j))
         if (k == 0) then
            call spec%set(base, [x(j)])
         else
            v = spec_values(spec, base, cfg%run%links)
            v(k) = x(j)
            call spec%set(base, v)
         end if
      end do
      call new_model(spec, model, error)
   end subroutine pixel_model_axes

   !> The double pendulum's constant records of the pixels p(:, j) of a parameter
   !> sweep (`pixel_pendulum` of each).
   pure function pixel_pendulums(cfg, p) result(pars)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: p(:, :)          !! (4, n) (m1, m2, l1, l2) [kg, kg, m, m]
      type(pendulum_t) :: pars(size(p, 2))
      integer :: j
      do j = 1, size(p, 2)
         pars(j) = pixel_pendulum(cfg, p(:, j))
      end do
   end function pixel_pendulums

   !> The double pendulum's constant record of a pixel of a parameter sweep (the lane
   !> kernel's parameters, not a model): the run's with (m1, m2, l1, l2) = p; point
   !> masses sit at the pixel's link ends.
   pure function pixel_pendulum(cfg, p) result(par)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: p(4)             !! (m1, m2, l1, l2) [kg, kg, m, m]
      type(pendulum_t) :: par
      par = cfg%run%pendulum()
      par%m1 = p(1); par%m2 = p(2); par%l1 = p(3); par%l2 = p(4)
      if (point_masses(cfg)) then
         par%d1 = p(3); par%d2 = p(4)
      end if
   end function pixel_pendulum

   !> The links are point masses (--body point): their centres follow a swept length.
   pure logical function point_masses(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      point_masses = .false.
      if (allocated(cfg%run%body)) point_masses = cfg%run%body == 'point'
   end function point_masses

   !> Whether `axis` sweeps a parameter by name: of a model without flips a real
   !> scalar parameter of its catalogue row (the elastic pendulum's m, k, l0, g); of
   !> the pendulum those of `pendulum_axis` (not the coded axes).
   logical function model_axis(cfg, axis)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      model_axis = .false.
      if (flip_model(cfg)) then   ! the pendulum's parameters by name
         model_axis = pendulum_axis(cfg, axis)
         return
      end if
      model_axis = index(' '//model_axis_names(cfg)//' ', ' '//axis//' ') > 0 .and. &
                   len_trim(axis) > 0
   end function model_axis

   !> The parameters a map of a model without flips may sweep, blank-separated: the
   !> real scalar parameters of its catalogue row.
   function model_axis_names(cfg) result(names)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: names
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      names = ''
      models = model_catalogue()
      k = find_model(models, cfg%run%spec%model_name())
      if (k == 0) return
      do i = 1, size(models(k)%params)
         associate (p => models(k)%params(i))
            if (p%count == 1 .and. .not. p%integer_valued) then
               if (len(names) > 0) names = names//' '
               names = names//p%name
            end if
         end associate
      end do
   end function model_axis_names

   !> The model of a pixel of a map of a model without flips whose axes sweep its
   !> parameters: a copy of the run's specification with each parameter names(k)
   !> set to x(k) ('': axis k sweeps an initial value).
   subroutine pixel_model_named(cfg, names, x, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      character(len=*), intent(in) :: names(2)           !! the axes' parameters or ''
      real(dp), intent(in) :: x(2)                       !! the pixel's axis values
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      integer :: k
      spec = cfg%run%spec
      do k = 1, 2
         if (len_trim(names(k)) > 0) call spec%set(trim(names(k)), [x(k)])
      end do
      call new_model(spec, model, error)
   end subroutine pixel_model_named

   !> Check the configuration; messages name the field and the accepted range.
   subroutine validate_sweep(cfg, error)
      type(sweep_config_t), intent(inout) :: cfg        !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      character(len=:), allocatable :: field
      call validate_run_config(cfg%run, error, initial_state=grid_mode(cfg))
      if (allocated(error)) return
      if (.not. cfg%run%model%conservative()) then   ! the sweep's kernels are conservative
         call fatal_error(error, 'invalid damping/support: dpend sweep integrates the ' &
                          //'conservative chain only (--damping and --support-amplitude ' &
                          //'must be 0; dpend simulate takes them)')
         return
      end if
      cfg%indicator = to_lower(cfg%indicator); cfg%axis1 = to_lower(cfg%axis1)
      cfg%axis2 = to_lower(cfg%axis2)   ! names without regard to case
      select case (cfg%indicator)
      case ('flip', 'lambda1', 'megno', 'fli', 'sali', 'gali2')
      case default
         call fatal_error(error, "invalid indicator: '"//cfg%indicator//"' (accepted: "// &
                          indicator_names//')'//did_you_mean(cfg%indicator, indicator_names, '; '))
         return
      end select
      if (cfg%indicator == 'lambda1') cfg%lyapunov = .true.
      if (.not. flip_model(cfg)) then
         call check_model_sweep(cfg, error)
         if (allocated(error)) return
      end if
      if (cfg%lyapunov .and. indicator_vectors(cfg) > 0) then
         call fatal_error(error, "invalid indicator: '"//cfg%indicator//"' with lyapunov "// &
                          '= true (one indicator per sweep; lambda1 is the Lyapunov exponent)')
         return
      end if
      if (cfg%run%links /= 2 .and. cfg%lyapunov) then
         field = 'lyapunov: true'
         if (cfg%indicator == 'lambda1') field = 'indicator: lambda1'
         call fatal_error(error, 'invalid '//field//' with '//to_str(cfg%run%links)// &
                          ' links (dpend sweep computes it for links = 2 only; '// &
                          'dpend lyapunov computes it for any N)')
         return
      end if
      if (cfg%run%method /= 'rk4') then
         call fatal_error(error, "invalid method: '"//cfg%run%method// &
                          "' (dpend sweep accepts: rk4)")
      else if (.not. (cfg%run%t_end > 0.0_dp)) then
         call fatal_error(error, 'invalid t_end: must be finite and > 0')
      else if (cfg%time_unit /= 's' .and. cfg%time_unit /= 'natural') then
         call fatal_error(error, "invalid time_unit: '"//cfg%time_unit// &
                          "' (accepted: s, natural)")
      else if (cfg%stop_at /= 'both' .and. cfg%stop_at /= 'either' .and. &
               cfg%stop_at /= 'end') then
         call fatal_error(error, "invalid stop_at: '"//cfg%stop_at// &
                          "' (accepted: both, either, end)")
      else if (cfg%block < 1 .or. cfg%block > max_sweep_points) then
         call fatal_error(error, 'invalid block: must be an integer from 1 to '// &
                          to_str(max_sweep_points))
      else if (cfg%threads < 0 .or. cfg%threads > max_threads) then
         call fatal_error(error, 'invalid threads: '//to_str(cfg%threads)// &
                          ' must be an integer from 0 (all) to '//to_str(max_threads))
      else if (cfg%run%t_end*time_scale(cfg) > max_time) then
         ! both factors are bounded (t_end <= 1e9, sqrt(l1/g) <= 1e6): no overflow
         call fatal_error(error, 'invalid t_end: '//sci(cfg%run%t_end)//' '// &
                          trim(unit_name(cfg))//' is '//sci(cfg%run%t_end*time_scale(cfg))// &
                          ' s, above '//sci(max_time)//' s')
      else if (.not. (cfg%run%t_end*time_scale(cfg) >= tiny(1.0_dp))) then
         ! (4.9e-324 in natural units is 0 s: a step of 0 s, MEGNO's 2 ∫/t divided by 0)
         call fatal_error(error, 'invalid t_end: '//sci(cfg%run%t_end)//' '// &
                          trim(unit_name(cfg))//' is '//sci(cfg%run%t_end*time_scale(cfg))// &
                          ' s, below '//sci(tiny(1.0_dp))//' s (the smallest normal double)')
      end if
      if (allocated(error)) return
      if (grid_mode(cfg) .and. (cfg%ic_angles_given .or. cfg%ic_dataset_given)) then
         call fatal_error(error, 'invalid '//trim(merge('ic_angles ', 'ic_dataset', &
                          cfg%ic_angles_given))//': given without ic_file (it describes ' &
                          //'the list of --ic-file; a grid sweep has none) [--ic-file / &sweep]')
         return
      end if
      if (grid_mode(cfg) .and. .not. flip_model(cfg)) then
         call check_model_axes(cfg, error)
      else if (grid_mode(cfg)) then
         call check_axis(cfg%axis1, 1, cfg%n1, cfg%min1, cfg%max1, cfg%run%links, error, &
                         pendulum_axis(cfg, cfg%axis1))
         if (allocated(error)) return
         call check_axis(cfg%axis2, 2, cfg%n2, cfg%min2, cfg%max2, cfg%run%links, error, &
                         pendulum_axis(cfg, cfg%axis2))
         if (allocated(error)) return
         if (merge(cfg%axis1 == cfg%axis2, same_value(cfg%axis1, cfg%axis2, cfg%run%links), &
                   pendulum_axis(cfg, cfg%axis1) .or. pendulum_axis(cfg, cfg%axis2))) then
            call fatal_error(error, "invalid axis2: '"//cfg%axis2//"' sweeps the same "// &
                             trim(merge('value        ', 'initial value', &
                                        pendulum_axis(cfg, cfg%axis2)))// &
                             " as axis1 '"//cfg%axis1//"'")
         else if (real(cfg%n1, dp)*real(cfg%n2, dp) > real(max_sweep_points, dp)) then
            call fatal_error(error, 'invalid n1, n2: n1*n2 = '// &
                             sci(real(cfg%n1, dp)*real(cfg%n2, dp))//' points, at most '// &
                             sci(real(max_sweep_points, dp))//' (fewer points)')
         else
            call check_pixel_parameters(cfg, error)
         end if
      else if (cfg%ic_angles /= 'q' .and. cfg%ic_angles /= 'theta') then
         call fatal_error(error, "invalid ic_angles: '"//cfg%ic_angles// &
                          "' (accepted: q, theta)")
      end if
      if (.not. allocated(error)) call check_sweep_forms(cfg, error)
      if (allocated(error)) return
      ! the device's name and the GPU's repacking (the GPU itself: resolve_device)
      cfg%device = to_lower(cfg%device)
      if (cfg%device /= 'cpu' .and. cfg%device /= 'gpu' .and. cfg%device /= 'auto') then
         call fatal_error(error, "invalid device: '"//printable(cfg%device)// &
                          "' (accepted: cpu, gpu, auto)")
      else if (cfg%gpu_repack < 0) then
         call fatal_error(error, 'invalid gpu_repack: '//to_str(cfg%gpu_repack)// &
                          ' must be an integer from 0 (one launch) to '//to_str(huge(1)))
      end if
   end subroutine validate_sweep

   !> Refuse two settings of one quantity, from flags or the namelist
   !> file: a fixed initial value or parameter and a grid axis that sweeps it (q1 or
   !> theta1 with axis theta1 or q1, m2 with axis m2/m1, ...); the grid's axes and
   !> ranges or fixed initial values with a list (ic_file), which gives every
   !> initial state; a stop rule with an indicator or the Lyapunov exponent, which
   !> integrate every trajectory to t_end. Lists (--q, --m) may hold the swept entry:
   !> of more than two links they are the only way to fix the others.
   subroutine check_sweep_forms(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, validated
      type(error_t), allocatable, intent(out) :: error  !! two forms of one quantity
      character(len=:), allocatable :: axis, fixed, c
      character(len=*), parameter :: initial = 'q1 q2 w1 w2'
      integer :: k
      if (len_trim(cfg%stop_at_given) > 0 .and. cfg%stop_at /= 'end' .and. &
          (cfg%lyapunov .or. indicator_vectors(cfg) > 0)) then
         fixed = 'lyapunov'
         if (cfg%indicator /= 'flip') fixed = "indicator '"//cfg%indicator//"'"
         call fatal_error(error, 'invalid '//cfg%stop_at_given//": '"//cfg%stop_at// &
                          "' given with "//fixed//' (it integrates every trajectory to ' &
                          //'t_end: stop_at end); give one of them')
         return
      end if
      if (.not. grid_mode(cfg)) then
         if (len_trim(cfg%grid_given) > 0) then
            fixed = first_word(adjustl(cfg%grid_given))
            call fatal_error(error, 'invalid '//fixed//': given with ic_file (a list ' &
                             //'sweep integrates the initial states of --ic-file; axes and ' &
                             //'ranges describe a grid); give one of them')
            return
         end if
         do k = 1, 4
            fixed = given_form(word(initial, k))
            if (len(fixed) > 0) then
               call fatal_error(error, 'invalid '//fixed//': given with ic_file (the ' &
                                //'list gives every initial state; ' &
                                //'the fixed value would be ignored); give one of them')
               return
            end if
         end do
         do k = 3, 4   ! the lists q and w (--q, --w, namelist q w) likewise
            if (cfg%run%list_size(k) == 0) cycle
            call fatal_error(error, 'invalid '//trim(merge('q', 'w', k == 3))//': given ' &
                             //'with ic_file (the list gives every initial state; the ' &
                             //'fixed values would be ignored); give one of them')
            return
         end do
         return
      end if
      do k = 1, 2
         axis = cfg%axis1
         if (k == 2) axis = cfg%axis2
         c = achar(iachar('0') + k)
         fixed = given_form(fixed_key(axis))
         if (len(fixed) == 0 .and. model_axis(cfg, axis)) then   ! a parameter by name
            if (allocated(cfg%run%given)) then
               ! the name, or the first link's form of a mass (m1 for m)
               if (index(cfg%run%given, ' '//axis//' ') > 0 .or. &
                   index(cfg%run%given, ' '//axis//'1 ') > 0) fixed = axis
            end if
         end if
         if (len(fixed) > 0) then
            call fatal_error(error, 'invalid '//fixed//": axis"//c//" '"//axis// &
                             "' sweeps the value it fixes (the axis would replace it); " &
                             //'give one of them')
            return
         end if
      end do
   contains
      !> The scalar key (q1 q2 w1 w2 m1 m2 l1 l2) whose value `axis` sweeps, '' if none.
      function fixed_key(axis) result(key)
         character(len=*), intent(in) :: axis
         character(len=:), allocatable :: key
         integer :: var, n
         key = ''
         select case (axis_parameter(axis))
         case (1); key = 'm1'
         case (2, 5); key = 'm2'
         case (3); key = 'l1'
         case (4, 6); key = 'l2'
         case default
            n = cfg%run%links
            if (.not. flip_model(cfg)) n = cfg%run%model%n_dof()
            var = sweep_variable(cfg, axis)
            if (var == 1 .or. var == 2) key = 'q'//achar(iachar('0') + var)
            if (var == n + 1 .or. var == n + 2) key = 'w'//achar(iachar('0') + var - n)
         end select
      end function fixed_key
      !> How `key` was given: '--q1' or '--theta1' (flags), 'q1 [&initial]' (the
      !> file), '' if not given.
      function given_form(key) result(form)
         character(len=*), intent(in) :: key
         character(len=:), allocatable :: form
         character(len=:), allocatable :: seen
         form = ''
         if (len(key) == 0) return
         seen = ' '
         if (allocated(cfg%run%flags_seen)) seen = cfg%run%flags_seen
         if (index(seen, ' --'//key//' ') > 0) then
            form = '--'//key
         else if (key(1:1) == 'q' .and. index(seen, ' --theta'//key(2:2)//' ') > 0) then
            form = '--theta'//key(2:2)
         else if (allocated(cfg%run%nml_given)) then
            if (index(cfg%run%nml_given, ' '//key//' ') > 0) then
               form = key//' [&initial]'
               if (key(1:1) == 'm' .or. key(1:1) == 'l') form = key//' [&pendulum]'
            end if
         end if
      end function given_form
      !> The k-th blank-separated word of `t`.
      function word(t, k) result(w)
         character(len=*), intent(in) :: t
         integer, intent(in) :: k
         character(len=:), allocatable :: w
         integer :: j
         w = adjustl(t)
         do j = 2, k
            w = adjustl(w(index(w, ' ') + 1:))
         end do
         w = first_word(w)
      end function word
      pure function first_word(t) result(w)
         character(len=*), intent(in) :: t
         character(len=:), allocatable :: w
         w = t(:index(t//' ', ' ') - 1)
      end function first_word
   end subroutine check_sweep_forms

   !> What a sweep of a model without flips (the elastic pendulum) refuses: the flip
   !> map (indicator flip, the default), the Lyapunov exponent of the batch kernel and
   !> angles of a list measured as theta.
   subroutine check_model_sweep(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: name
      name = cfg%run%spec%model_name()
      if (cfg%indicator == 'flip') then
         call fatal_error(error, "invalid indicator: 'flip' does not apply to model " &
                          //name//' (no rods to flip: no flip stop rules, t_flip or flip ' &
                          //'energy bound; use --indicator megno, fli, sali or gali2)')
      else if (cfg%lyapunov) then
         call fatal_error(error, 'invalid '//trim(merge('indicator: lambda1', &
                          'lyapunov: true    ', cfg%indicator == 'lambda1'))// &
                          ' with model '//name//' (dpend sweep computes it for the ' &
                          //'pendulum only; use --indicator megno, fli, sali or gali2, ' &
                          //'or dpend lyapunov)')
      else if (cfg%ic_angles_given .and. cfg%ic_angles /= 'q') then
         call fatal_error(error, "invalid ic_angles: '"//printable(cfg%ic_angles)// &
                          "' with model "//name//' (accepted: q; a list holds its ' &
                          //'coordinates and rates)')
      end if
   end subroutine check_model_sweep

   !> The axes of a model without flips: known names (`sweep_variable`), two
   !> different values, n and the range as every axis, and the grid's four corners
   !> (the extremes of each swept value) within the model (`check_state`).
   subroutine check_model_axes(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: names
      real(dp), allocatable :: y(:)
      integer :: k, i, j, var(2), n(2)
      real(dp) :: lo(2), hi(2), x1, x2
      character(len=1) :: c
      character(len=:), allocatable :: axis
      character(len=32) :: pnames(2)   ! the parameter of each parameter axis, else ''
      class(model_t), allocatable :: model
      var = [sweep_variable(cfg, cfg%axis1), sweep_variable(cfg, cfg%axis2)]
      n = [cfg%n1, cfg%n2]; lo = [cfg%min1, cfg%min2]; hi = [cfg%max1, cfg%max2]
      names = 'q1..q'//to_str(cfg%run%model%n_dof())//', w1..w'// &
              to_str(cfg%run%model%n_dof())//', '//coordinate_names()//', '// &
              model_axis_names(cfg)
      do k = 1, 2
         c = achar(iachar('0') + k)
         axis = cfg%axis1
         if (k == 2) axis = cfg%axis2
         if (var(k) == 0 .and. model_axis(cfg, axis)) var(k) = -k   ! a parameter axis
         if (var(k) == 0) then
            ! theta1, theta2 are also the defaults: the pendulum's, no ranges to keep
            call fatal_error(error, 'invalid axis'//c//": '"//printable(axis)// &
                             "' (accepted for model "//cfg%run%spec%model_name()//': '// &
                             names//'; it has no default axes: give --axis1 --axis2 and ' &
                             //'their ranges)')
         else if (n(k) < 1 .or. n(k) > max_axis_points) then
            call fatal_error(error, 'invalid n'//c//': '//to_str(n(k))//' must be an ' &
                             //'integer from 1 to '//to_str(max_axis_points)// &
                             ' (points on axis '//c//')')
         else if (.not. (ieee_is_finite(lo(k)) .and. ieee_is_finite(hi(k)))) then
            call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
         else
            call check_grid_range(axis, c, n(k), lo(k), hi(k), error)
         end if
         if (allocated(error)) return
      end do
      if (var(1) == var(2) .or. cfg%axis1 == cfg%axis2) then
         call fatal_error(error, "invalid axis2: '"//cfg%axis2//"' sweeps the same "// &
                          "value as axis1 '"//cfg%axis1//"'")
         return
      else if (real(cfg%n1, dp)*real(cfg%n2, dp) > real(max_sweep_points, dp)) then
         call fatal_error(error, 'invalid n1, n2: n1*n2 = '// &
                          sci(real(cfg%n1, dp)*real(cfg%n2, dp))//' points, at most '// &
                          sci(real(max_sweep_points, dp))//' (fewer points)')
         return
      end if
      pnames = ''
      if (var(1) < 0) pnames(1) = cfg%axis1
      if (var(2) < 0) pnames(2) = cfg%axis2
      do j = 1, 2
         do i = 1, 2
            x1 = merge(lo(1), hi(1), i == 1); x2 = merge(lo(2), hi(2), j == 1)
            y = [cfg%run%q0(), cfg%run%w0()]
            if (var(1) > 0) y(var(1)) = x1
            if (var(2) > 0) y(var(2)) = x2
            if (any(var < 0)) then   ! the pixel's model (the parameters' ranges)
               call pixel_model_named(cfg, pnames, [x1, x2], model, error)
               if (.not. allocated(error)) &
                  call model%check_state(y(:size(y)/2), y(size(y)/2 + 1:), error)
            else
               call cfg%run%model%check_state(y(:size(y)/2), y(size(y)/2 + 1:), error)
            end if
            if (allocated(error)) then
               error%message = 'invalid min1, max1, min2, max2: the pixel at ('// &
                               real_str(x1)//', '//real_str(x2)//') is refused: '// &
                               error%message
               return
            end if
         end do
      end do
   contains
      !> 'r phi rdot phidot'.
      function coordinate_names() result(t)
         character(len=:), allocatable :: t, cname, units, punits
         integer :: i
         t = ''
         do i = 1, cfg%run%model%n_dof()
            call cfg%run%model%coordinate(i, cname, units, punits)
            t = t//cname//' '
         end do
         do i = 1, cfg%run%model%n_dof()
            call cfg%run%model%coordinate(i, cname, units, punits)
            t = t//cname//'dot '
         end do
         t = trim(t)
      end function coordinate_names
   end subroutine check_model_axes

   !> True if two axes set the same value: the same initial value, the same
   !> parameter, or m2 and m2/m1, l2 and l2/l1.
   pure logical function same_value(a1, a2, links)
      character(len=*), intent(in) :: a1, a2  !! axis names
      integer, intent(in) :: links            !! number of links N
      integer :: p1, p2
      p1 = axis_parameter(a1); p2 = axis_parameter(a2)
      same_value = axis_variable(a1, links) == axis_variable(a2, links) .and. p1 == p2
      if (min(p1, p2) == 2 .and. max(p1, p2) == 5) same_value = .true.
      if (min(p1, p2) == 4 .and. max(p1, p2) == 6) same_value = .true.
   end function same_value

   !> The parameters of the pixels at the four corners of a grid (the extremes: each
   !> is monotonic in either axis value) within the limits of every command, and,
   !> for N links, a chain the model accepts.
   subroutine check_pixel_parameters(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, axes checked
      type(error_t), allocatable, intent(out) :: error  !! a corner out of range
      integer :: p1, p2, i, j
      real(dp) :: p(4), x1, x2
      character(len=*), parameter :: what = 'min1, max1, min2, max2'
      class(model_t), allocatable :: model
      logical :: named
      p1 = axis_parameter(cfg%axis1); p2 = axis_parameter(cfg%axis2)
      named = pendulum_axis(cfg, cfg%axis1) .or. pendulum_axis(cfg, cfg%axis2)
      if (p1 == 0 .and. p2 == 0 .and. .not. named) return
      ! the com and inertia given would not follow a swept mass or length (the
      ! bodies --body rod and point do)
      if ((p1 > 0 .or. p2 > 0) .and. &
          (cfg%run%extra%find('com') > 0 .or. cfg%run%extra%find('inertia') > 0)) then
         call fatal_error(error, 'invalid axis1, axis2: a mass or length axis sweeps ' &
                          //'uniform rods or point masses only (the com and inertia ' &
                          //'given would not follow it); sweep the initial values instead')
         return
      end if
      do j = 1, 2
         do i = 1, 2
            x1 = merge(cfg%min1, cfg%max1, i == 1)
            x2 = merge(cfg%min2, cfg%max2, j == 1)
            if (named) then   ! every parameter's range from the catalogue (the factory)
               call pixel_model_axes(cfg, pendulum_param_names(cfg), &
                                     pendulum_param_values(cfg, x1, x2), model, error)
               if (allocated(error)) then
                  error%message = 'invalid '//what//': the pixel at ('//real_str(x1)//', ' &
                                  //real_str(x2)//') is refused: '//error%message
                  return
               end if
               if (p1 == 0 .and. p2 == 0) cycle
            end if
            p = pixel_parameters(cfg, p1, x1, p2, x2)
            call check_parameter(parameter_mass, what//' (m1 of a pixel)', p(1), error)
            if (.not. allocated(error)) call check_parameter(parameter_mass, &
                                                             what//' (m2 of a pixel)', p(2), error)
            if (.not. allocated(error)) call check_parameter(parameter_length, &
                                                             what//' (l1 of a pixel)', p(3), error)
            if (.not. allocated(error)) call check_parameter(parameter_length, &
                                                             what//' (l2 of a pixel)', p(4), error)
            if (allocated(error)) return
            call pixel_model(cfg, p, model, error)
            if (allocated(error)) then
               error%message = 'invalid '//what//': the pixel at ('//real_str(x1)//', '// &
                               real_str(x2)//') is refused: '//error%message
               return
            end if
         end do
      end do
   end subroutine check_pixel_parameters

   !> Check one axis: a known name, n >= 1, finite min <= max (min < max if n > 1).
   subroutine check_axis(name, k, n, lo, hi, links, error, named)
      character(len=*), intent(in) :: name              !! axis name
      integer, intent(in) :: k                          !! 1 or 2
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      integer, intent(in) :: links                      !! number of links N
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      !> a parameter by name (`pendulum_axis`): n and the range as any axis; its
      !> values' range from the catalogue (`check_pixel_parameters`)
      logical, intent(in) :: named
      character(len=1) :: c
      character(len=5) :: unit
      real(dp) :: bound
      integer :: var
      c = achar(iachar('0') + k)
      var = axis_variable(name, links)
      if (var == 0 .and. axis_parameter(name) > 0) then
         call check_param_axis(name, k, n, lo, hi, links, error)
         return
      end if
      if (named) then
         if (n < 1 .or. n > max_axis_points) then
            call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer ' &
                             //'from 1 to '//to_str(max_axis_points)//' (points on axis '//c//')')
         else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
            call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
         else
            call check_grid_range(name, c, n, lo, hi, error)
         end if
         return
      end if
      ! the angles' and angular velocities' ranges of every command (dpend_limits)
      bound = max_angle
      unit = 'rad'
      if (var > links) then
         bound = max_angular_velocity
         unit = 'rad/s'
      end if
      if (var == 0 .and. (index(name, 'damping') == 1 .or. index(name, 'support') == 1)) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: " &
                          //accepted_axes(links)//'; damping and the support''s motion are ' &
                          //'not axes: dpend sweep integrates the conservative chain only)')
      else if (var == 0) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: " &
                          //accepted_axes(links)//')'//did_you_mean(name, accepted_axes(2), '; '))
      else if (n < 1 .or. n > max_axis_points) then
         call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer from 1' &
                          //' to '//to_str(max_axis_points)//' (points on axis '//c//')')
      else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
      else if (max(abs(lo), abs(hi)) > bound) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': '//sci(lo)//' .. ' &
                          //sci(hi)//' is outside ['//sci(-bound)//', '//sci(bound)// &
                          '] ('//trim(unit)//')')
      else
         call check_grid_range(name, c, n, lo, hi, error)
      end if
   end subroutine check_axis

   !> Check a parameter axis: two or more links, n as any axis, finite 0 < min <= max
   !> (min < max if n > 1); the pixels' parameters are checked by
   !> `check_pixel_parameters`.
   subroutine check_param_axis(name, k, n, lo, hi, links, error)
      character(len=*), intent(in) :: name              !! axis name
      integer, intent(in) :: k                          !! 1 or 2
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      integer, intent(in) :: links                      !! number of links N
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      character(len=1) :: c
      c = achar(iachar('0') + k)
      if (links < 2) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: "// &
                          accepted_axes(links)//'; parameter axes need 2 or more links)')
      else if (n < 1 .or. n > max_axis_points) then
         call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer from 1' &
                          //' to '//to_str(max_axis_points)//' (points on axis '//c//')')
      else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
      else if (.not. (lo > 0.0_dp)) then
         call fatal_error(error, 'invalid min'//c//': '//sci(lo)//' must be > 0 (axis '// &
                          name//')')
      else
         call check_grid_range(name, c, n, lo, hi, error)
      end if
   end subroutine check_param_axis

   !> The checks that every axis shares once its own range holds: max at most 1e12
   !> (the pixels' own limits are checked later; this bound keeps their products,
   !> ratio times mass or length, far from overflow), min <= max, and a non-empty
   !> grid.
   subroutine check_grid_range(name, c, n, lo, hi, error)
      character(len=*), intent(in) :: name              !! axis name
      character(len=1), intent(in) :: c                 !! '1' or '2'
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      if (hi > 1e12_dp) then
         call fatal_error(error, 'invalid max'//c//': '//sci(hi)//' must be at most 1e12 '// &
                          '(axis '//name//')')
      else if (lo > hi) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': min'//c//' = ' &
                          //real_str(lo)//' > max'//c//' = '//real_str(hi))
      else if (n > 1 .and. .not. (lo < hi)) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': the grid is empty, need min' &
                          //c//' < max'//c//' when n'//c//' > 1')
      end if
   end subroutine check_grid_range

   !> The horizon and the step in both units: 't_end = 100 sqrt(l1/g) =
   !> 31.94 s, dt = 0.01 sqrt(l1/g) = 0.003194 s' (time_unit natural) or 't_end =
   !> 30 s = 93.91 sqrt(l1/g), ...' (s); with an l1 axis the natural unit is the
   !> configured l1's.
   function horizon_text(cfg) result(s)
      type(sweep_config_t), intent(in) :: cfg  !! validated configuration
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nat
      real(dp) :: tn
      tn = natural_time(cfg)
      nat = natural_name(cfg)
      s = 't_end = '//both(cfg%run%t_end)//', dt = '//both(cfg%run%dt)
      if (axis_parameter(cfg%axis1) == 3 .or. axis_parameter(cfg%axis2) == 3) &
         s = s//' ('//nat//' of the configured l1 = '//real_str(cfg%run%l(1))// &
             ' m; l1 is swept)'
   contains
      function both(t) result(b)
         real(dp), intent(in) :: t
         character(len=:), allocatable :: b
         if (cfg%time_unit == 'natural') then
            b = real_str(t)//' '//nat//' = '//real_str(t*tn, 4)//' s'
         else
            b = real_str(t)//' s = '//real_str(t/tn, 4)//' '//nat
         end if
      end function both
   end function horizon_text

   !> The unit of dt and t_end: 's' or the name of the natural unit.
   function unit_name(cfg) result(u)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: u
      u = 's'
      if (cfg%time_unit == 'natural') u = natural_name(cfg)
   end function unit_name

   !> Index in the state (q1 .. qN, w1 .. wN) of the initial value an axis sweeps:
   !> k for thetak and qk, N + k for wk (k = 1 .. N), 0 for an unknown name. Two links:
   !> 1 q1, 2 q2, 3 w1, 4 w2.
   pure integer function axis_variable(name, links)
      character(len=*), intent(in) :: name   !! axis name
      integer, intent(in) :: links           !! number of links N
      integer :: k, start, stat
      axis_variable = 0
      if (index(name, 'theta') == 1) then
         start = 6
      else if (index(name, 'q') == 1 .or. index(name, 'w') == 1) then
         start = 2
      else
         return
      end if
      if (len(name) < start .or. len(name) > start + 3) return
      if (verify(name(start:), '0123456789') /= 0 .or. name(start:start) == '0') return
      read (name(start:), *, iostat=stat) k
      if (stat /= 0 .or. k < 1 .or. k > links) return
      axis_variable = k
      if (name(1:1) == 'w') axis_variable = links + k
   end function axis_variable

   !> The accepted axis names for N links, for messages.
   function accepted_axes(links) result(s)
      integer, intent(in) :: links  !! number of links N
      character(len=:), allocatable :: s
      character(len=:), allocatable :: n
      n = to_str(links)
      select case (links)
      case (1); s = 'theta1 q1 w1'//pendulum_axis_text(1)//' for 1 link'
      case (2); s = axis_names//' '//param_axis_names//pendulum_axis_text(2)
      case default
         s = 'theta1..theta'//n//' q1..q'//n//' w1..w'//n//' '//param_axis_names// &
             pendulum_axis_text(links)//' for '//n//' links'
      end select
   end function accepted_axes

end module dpend_sweep_settings
