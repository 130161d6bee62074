!> The settings record of a sweep (`dpend sweep`, the MPI front end, library
!> callers; validated by dpend_sweep_settings): the run settings (&pendulum,
!> &initial for the values that are not swept, &integration for dt, t_end and their
!> time_unit (the sweep keeps them in it: default natural, √(L1/g)),
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
!>   stop_at        'both' (every link that can flip has flipped), 'either', 'end'
!>   block          initial conditions per block (unit of parallel work, output
!>                  chunks and resume); whole rows of axis 1 in a grid
!>   lyapunov       also the largest Lyapunov exponent (runs every trajectory to t_end)
!>   indicator      per-pixel chaos indicator beside the flip time: 'flip' (none),
!>                  'lambda1' (= lyapunov), 'megno', 'fli', 'sali', 'gali2' (every
!>                  trajectory to t_end)
!>   stats          also the number of steps of every trajectory
!>   threads        OpenMP threads (0: all; not part of the stored configuration)
module dpend_sweep_record
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: real_str, to_str, printable
   use dpend_lane_batch, only: stop_both, stop_either, stop_end
   use dpend_limits, only: sci, max_threads, max_axis_points, max_sweep_points, max_angle, &
      max_angular_velocity, max_time, check_parameter, parameter_mass, parameter_length
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t, double_pendulum_t
   use dpend_model_factory, only: model_spec_t, new_model, model_info_t, model_catalogue, &
      find_model, spec_values
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_strings, only: to_lower, did_you_mean
   use dpend_run_settings, only: run_config_t, validate_run_config, natural_unit_name, &
      run_natural_time => natural_time
   implicit none
   private
   public :: axis_names, param_axis_names, indicator_names, &
      sweep_config_t, sweep_defaults, indicator_vectors, grid_mode, time_scale, &
      natural_time, natural_name, flip_model, sweep_variable, stop_rule, axis_variable, &
      kernel_pendulum


   !> Names accepted for axis1 and axis2 (two links; `accepted_axes` for N).
   character(len=*), parameter :: axis_names = 'theta1 theta2 q1 q2 w1 w2'

   !> Parameters accepted as axes (grids of two or more links).
   character(len=*), parameter :: param_axis_names = 'm1 m2 l1 l2 m2/m1 l2/l1'

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
      cfg%run%time_unit = 'natural'
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
      if (trim(cfg%run%time_unit) == 'natural') time_scale = natural_time(cfg)
   end function time_scale

   !> The natural time unit [s] of the run's model (dpend_run_settings' one rule:
   !> √(l1/g) of the configured l1, √(l0/g) for the elastic pendulum); parameter sweeps
   !> keep the unit of the configured model.
   real(dp) function natural_time(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      natural_time = run_natural_time(cfg%run)
   end function natural_time

   !> The name of the natural time unit of the run's model, e.g. 'sqrt(l1/g)'.
   function natural_name(cfg) result(name)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: name
      name = natural_unit_name(cfg%run)
   end function natural_name

   !> True if the run's model has rods that flip (a potential V = Σ G_i sin q_i of
   !> its angles: the pendulum of any N): the flip map, its stop rules, t_flip and the
   !> flip energy bounds apply. False for the elastic pendulum.
   logical function flip_model(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      flip_model = size(cfg%run%model%potential_weights()) == cfg%run%model%n_dof()
   end function flip_model

   !> The two-link kernels (the batch lanes, the GPU) serve the run's model: the
   !> double pendulum's own formulation (`double_pendulum_t`; a chain of two links with
   !> motors is not: its mass matrix has the rotors' part, so it goes per trajectory).
   logical function kernel_pendulum(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      select type (m => cfg%run%model)
      type is (double_pendulum_t)
         kernel_pendulum = .true.
      class default
         kernel_pendulum = .false.
      end select
   end function kernel_pendulum

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

end module dpend_sweep_record
