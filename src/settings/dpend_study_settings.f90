!> The settings of an energy study (`dpend study`, library callers): the cases, the methods with their step and
!> tolerance ranges, the horizons, the roundoff (Brouwer) and Tao experiments,
!> their validation (`validate_study_config`) and the namelist that records
!> them (`study_namelist`); dpend_study_config reads them from &study and the flags. The built-in defaults are the default study, written out
!> with comments in data/study.nml.
!>
!> Lists in &study are indexed arrays (`method(1) = 'rk4'`, `h_min(1) = 1e-3`).
!> A list that the file does not set keeps its default; a list that it sets
!> replaces the default list entirely, and a range left at 0 for a listed
!> method takes that method's default range.
module dpend_study_settings
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: finite_positive
   use dpend_model_factory, only: model_spec_t, model_spec, new_model, default_model, &
      has_parameter
   use dpend_model, only: model_t, max_dof
   use dpend_joint_torque, only: joint_torque_t
   use dpend_run_settings, only: read_torque_file
   use dpend_cli, only: to_str, printable
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_method_registry, only: method_names, method_index, method_table, &
      field_method_names
   use dpend_limits, only: in_range, check_count, sci, max_angle, max_angular_velocity, &
      max_time, max_steps, min_rtol, min_atol, max_atol, max_omega, max_threads
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: study_config_t, study_case_t, study_method_t, study_defaults, &
      validate_study_config, apply_quick, study_times_in_seconds, study_namelist, case_index, default_ranges, &
      balance_case, case_model, study_model_name, default_model_study, max_cases, &
      max_methods, max_extra, case_damping, case_list, split_list, unset, read_case_torques, &
      check_case_torques, step_grid

   integer, parameter :: max_cases = 8      !! most cases in &study
   integer, parameter :: max_methods = 16   !! most methods in &study
   integer, parameter :: max_extra = 4      !! most roundoff / Tao methods
   real(dp), parameter :: pi = acos(-1.0_dp)
   !> Marks the entries of the &study lists that the file does not give.
   real(dp), parameter :: unset = -huge(1.0_dp)

   !> One initial condition (SI units, angles from the horizontal x axis) of the
   !> chain of N = size(q0) links: N = 2 is the double pendulum, any other N the
   !> N-link chain (`case_model`).
   type :: study_case_t
      character(len=:), allocatable :: name  !! label, e.g. 'small'
      real(dp), allocatable :: q0(:)         !! initial angles [rad], one per link
      real(dp), allocatable :: w0(:)         !! initial angular velocities [rad/s]
      !> steps of the long runs at each method's mid-range step: the long runs of a
      !> method reach t_long = long_steps × h_mid [s] (every step size of the sweep)
      real(dp) :: long_steps = 1.0e6_dp
      !> joint damping c_i [N m s], one per link; not allocated: none
      real(dp), allocatable :: damping(:)
      real(dp) :: support_amplitude(2) = 0.0_dp  !! moving pin (a_x, a_y) [m]
      real(dp) :: support_frequency = 0.0_dp     !! its ω [rad/s]
      real(dp) :: support_phase(2) = 0.0_dp      !! its phases (φ_x, φ_y) [rad]
      !> applied joint torques: the file (columns t, tau1 … tauN; '' none), read by
      !> `read_case_torques` into `torque`
      character(len=:), allocatable :: torque_file
      type(joint_torque_t) :: torque
   end type study_case_t

   !> One method and its sweeps.
   type :: study_method_t
      character(len=:), allocatable :: name  !! as in `dpend methods`
      real(dp) :: h_min = 0.0_dp     !! smallest step of the fixed-step sweep [s]
      real(dp) :: h_max = 0.0_dp     !! largest step of the fixed-step sweep [s]
      real(dp) :: rtol_min = 0.0_dp  !! tolerance sweep of adaptive methods (0: none)
      real(dp) :: rtol_max = 0.0_dp  !! largest relative tolerance
   end type study_method_t

   !> The whole study.
   type :: study_config_t
      !> link parameters: a case of N links uses m(1:N), l(1:N) and g (links 1 and 2
      !> are the double pendulum's m1, m2, l1, l2)
      real(dp) :: m(max_dof) = 1.0_dp   !! link masses [kg]
      real(dp) :: l(max_dof) = 1.0_dp   !! link lengths [m]
      real(dp) :: g = 9.8_dp            !! gravitational acceleration [m/s²]
      !> links given by the lists m, l of &pendulum or --m, --l (0: none given)
      integer :: list_size(2) = 0
      type(study_case_t), allocatable :: cases(:)     !! initial conditions
      type(study_method_t), allocatable :: methods(:) !! methods and ranges
      integer :: n_h = 7            !! steps per fixed-step sweep (geometric)
      integer :: n_rtol = 7         !! tolerances per tolerance sweep (geometric)
      real(dp) :: atol_ratio = 1.0_dp  !! atol = atol_ratio × rtol
      real(dp) :: t_short = 1.0_dp  !! horizon of the global error [s]
      integer :: n_check = 4        !! checkpoints k t_short / n_check, k = 1..n_check
      character(len=:), allocatable :: order_case  !! case of the order verdicts
      character(len=:), allocatable :: drift_case  !! case of the drift verdicts
      real(dp) :: drift_decades = 2.0_dp  !! drift fit over [t_long 10^-d, t_long]
      integer :: bins_per_decade = 10     !! logarithmic time bins per decade
      integer :: decades = 5              !! decades of the time grid below t_long
      character(len=:), allocatable :: ref_method    !! reference solution
      real(dp) :: ref_dt = 2.5e-4_dp                 !! its step [s]
      character(len=:), allocatable :: check_method  !! second method checking it
      real(dp) :: check_rtol = 1.0e-14_dp            !! its tolerance
      real(dp) :: wall_min = 0.05_dp  !! time each short run for at least this [s]
      ! roundoff (Brouwer's law)
      character(len=16), allocatable :: ro_methods(:)  !! symplectic methods
      real(dp), allocatable :: ro_dt(:)                !! their steps [s]
      real(dp) :: ro_steps = 1.0e6_dp     !! steps per run
      integer :: ro_runs = 32             !! runs (perturbed initial conditions)
      character(len=:), allocatable :: ro_case  !! case perturbed
      real(dp) :: ro_perturb = 2.0e-3_dp  !! perturbation of q per run [rad]
      real(dp) :: ro_fit_t_min = 10.0_dp  !! fit of the exponent from this time [s]
      ! Tao's binding constant
      character(len=16), allocatable :: tao_methods(:)  !! tao2, tao4
      real(dp) :: tao_dt = 2.0e-3_dp       !! step [s]
      real(dp) :: tao_t_end = 500.0_dp     !! horizon [s]
      real(dp) :: omega_min = 1.0_dp       !! smallest ω [1/s]
      real(dp) :: omega_max = 1.0e4_dp     !! largest ω [1/s]
      integer :: n_omega = 41              !! values of ω (geometric)
      character(len=:), allocatable :: tao_case  !! case
      ! run control
      !> the unit of the times given (t_short, ref_dt, h_min, h_max, ro_dt,
      !> ro_fit_t_min, tao_dt, tao_t_end): 's' or 'natural' (the first case's model's
      !> √(l1/g), `study_times_in_seconds`; --time-unit, &integration time_unit)
      character(len=7) :: time_unit = 's'
      real(dp) :: time_scale = 1.0_dp      !! seconds per unit of those times
      character(len=16) :: time_unit_name = 's'  !! its name, e.g. 'sqrt(l1/g)'
      logical :: quick = .false.           !! reduced long runs (smoke test, CI)
      integer :: threads = 0               !! OpenMP threads (0: the default)
      logical :: figures = .true.          !! run scripts/plot_study.sh at the end
      character(len=:), allocatable :: output  !! HDF5 file
      logical :: force = .false.               !! overwrite it
      !> the model of every case: &model name (unallocated: the factory's default, the
      !> pendulum of the case's links from m, l, g) and its parameters by name
      character(len=:), allocatable :: model_name
      type(model_spec_t) :: model_params
   end type study_config_t

contains

   !> Default step range [s] and tolerance range of method `name`, from the method
   !> registry (`dpend methods`); 0 when unknown.
   subroutine default_ranges(name, h_min, h_max, rtol_min, rtol_max)
      character(len=*), intent(in) :: name  !! method
      real(dp), intent(out) :: h_min        !! smallest step [s]
      real(dp), intent(out) :: h_max        !! largest step [s]
      real(dp), intent(out) :: rtol_min     !! smallest tolerance (0: none)
      real(dp), intent(out) :: rtol_max     !! largest tolerance
      integer :: i
      h_min = 0.0_dp; h_max = 0.0_dp; rtol_min = 0.0_dp; rtol_max = 0.0_dp
      i = method_index(name)
      if (i == 0) return
      h_min = method_table(i)%h_min
      h_max = method_table(i)%h_max
      rtol_min = method_table(i)%rtol_min
      rtol_max = method_table(i)%rtol_max
   end subroutine default_ranges

   !> The default study: three cases, every method, Brouwer and Tao experiments.
   function study_defaults() result(cfg)
      type(study_config_t) :: cfg
      character(len=16), allocatable :: names(:)
      integer :: i
      cfg%cases = [ &
                  study_case_t('small', [-0.5_dp*pi + 0.3_dp, -0.5_dp*pi - 0.2_dp], &
                               [0.0_dp, 0.0_dp], 1.0e6_dp), &
                  study_case_t('mixed', [-0.5_dp*pi + 0.75_dp, -0.5_dp*pi + 1.5_dp], &
                               [0.0_dp, 0.0_dp], 1.0e5_dp), &
                  study_case_t('horizontal', [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], 1.0e5_dp)]
      call split_words(method_names(), names)
      allocate (cfg%methods(size(names)))
      do i = 1, size(names)
         cfg%methods(i)%name = trim(names(i))
         call default_ranges(trim(names(i)), cfg%methods(i)%h_min, cfg%methods(i)%h_max, &
                             cfg%methods(i)%rtol_min, cfg%methods(i)%rtol_max)
      end do
      cfg%order_case = 'mixed'
      cfg%drift_case = 'small'
      cfg%ref_method = 'gauss8'
      cfg%check_method = 'dop853'
      cfg%ro_methods = [character(len=16) :: 'gauss6', 'gauss8']
      cfg%ro_dt = [1.0e-3_dp, 1.0e-3_dp]
      cfg%ro_case = 'small'
      cfg%tao_methods = [character(len=16) :: 'tao2', 'tao4']
      cfg%tao_case = 'small'
      cfg%output = 'out/study/study.h5'
   end function study_defaults

   !> With time_unit natural, the study's times given in the natural unit of the first
   !> case's model (√(l1/g) of the study's l1, √(l0/g) of an elastic &model) into
   !> seconds, once (validated before and after: the model must be built first).
   subroutine study_times_in_seconds(cfg)
      type(study_config_t), intent(inout) :: cfg  !! validated configuration
      class(model_t), allocatable :: model
      character(len=:), allocatable :: name
      integer :: i
      if (trim(cfg%time_unit) /= 'natural' .or. cfg%time_scale /= 1.0_dp) return
      call case_model(cfg, 1, model)
      call model%time_unit(cfg%time_scale, name)
      cfg%time_unit_name = name
      cfg%t_short = cfg%t_short*cfg%time_scale
      cfg%ref_dt = cfg%ref_dt*cfg%time_scale
      do i = 1, size(cfg%methods)
         cfg%methods(i)%h_min = cfg%methods(i)%h_min*cfg%time_scale
         cfg%methods(i)%h_max = cfg%methods(i)%h_max*cfg%time_scale
      end do
      cfg%ro_dt = cfg%ro_dt*cfg%time_scale
      cfg%ro_fit_t_min = cfg%ro_fit_t_min*cfg%time_scale
      cfg%tao_dt = cfg%tao_dt*cfg%time_scale
      cfg%tao_t_end = cfg%tao_t_end*cfg%time_scale
   end subroutine study_times_in_seconds

   !> Reduce the study to a smoke test (`--quick`, about 50× cheaper): long runs
   !> of 2 % of their steps, 4 roundoff runs of at most 10⁵ steps, Tao runs of a
   !> tenth of their horizon, short runs timed for 2 ms.
   subroutine apply_quick(cfg)
      type(study_config_t), intent(inout) :: cfg  !! configuration to reduce
      integer :: i
      if (.not. cfg%quick) return
      do i = 1, size(cfg%cases)
         cfg%cases(i)%long_steps = max(1.0e3_dp, 0.02_dp*cfg%cases(i)%long_steps)
      end do
      cfg%ro_steps = min(cfg%ro_steps, 1.0e5_dp)
      cfg%ro_runs = min(cfg%ro_runs, 4)
      cfg%ro_fit_t_min = min(cfg%ro_fit_t_min, 1.0_dp)
      cfg%tao_t_end = 0.1_dp*cfg%tao_t_end
      cfg%wall_min = min(cfg%wall_min, 0.002_dp)
   end subroutine apply_quick

   !> Index of the case called `name` in cfg%cases, 0 if none.
   pure integer function case_index(cfg, name)
      type(study_config_t), intent(in) :: cfg  !! configuration
      character(len=*), intent(in) :: name     !! case name
      integer :: i
      case_index = 0
      do i = 1, size(cfg%cases)
         if (cfg%cases(i)%name == trim(name)) then
            case_index = i
            return
         end if
      end do
   end function case_index

   !> The model of the study's cases (`&model name`, else the factory's default).
   pure function study_model_name(cfg) result(name)
      type(study_config_t), intent(in) :: cfg  !! configuration
      character(len=:), allocatable :: name
      if (allocated(cfg%model_name)) then
         name = cfg%model_name
      else
         name = default_model
      end if
   end function study_model_name

   !> The cases are the factory's default model (the pendulum of their links).
   pure logical function default_model_study(cfg)
      type(study_config_t), intent(in) :: cfg  !! configuration
      default_model_study = study_model_name(cfg) == default_model
   end function default_model_study

   !> Case ic is damped or driven (joint damping, a moving support, applied joint
   !> torques): a balance case, whose energy error is the energy balance E(t) − E(0) +
   !> W_friction − W_support − W_torque (dpend_work) and to which the drift verdicts
   !> are not applied.
   pure logical function balance_case(cfg, ic)
      type(study_config_t), intent(in) :: cfg  !! configuration
      integer, intent(in) :: ic                !! case index
      balance_case = any(cfg%cases(ic)%support_amplitude /= 0.0_dp) .or. &
                     cfg%cases(ic)%torque%active()
      if (allocated(cfg%cases(ic)%damping)) balance_case = balance_case .or. &
                                                          any(cfg%cases(ic)%damping /= 0.0_dp)
   end function balance_case

   !> The system of case ic (validated): the double pendulum for two links, the
   !> N-link chain of m(1:N), l(1:N), g otherwise, with the case's damping and
   !> moving support (then also for two links).
   subroutine case_model(cfg, ic, model)
      type(study_config_t), intent(in) :: cfg             !! configuration (validated)
      integer, intent(in) :: ic                           !! case index
      class(model_t), allocatable, intent(out) :: model   !! its system
      type(error_t), allocatable :: error
      call new_model(case_spec(cfg, ic), model, error)
      if (allocated(error)) error stop 'internal error: a validated study case: ' &
         //error%message
   end subroutine case_model

   !> The factory's specification of case ic: the pendulum of the case's links with
   !> the study's masses, lengths and g and the case's damping and support motion
   !> (the factory gives the double pendulum's own form to two conservative links).
   function case_spec(cfg, ic, conservative) result(spec)
      type(study_config_t), intent(in) :: cfg        !! configuration
      integer, intent(in) :: ic                      !! case index
      logical, intent(in), optional :: conservative  !! without damping and support
      type(model_spec_t) :: spec
      integer :: n, i
      n = size(cfg%cases(ic)%q0)
      if (.not. default_model_study(cfg)) then   ! &model: its parameters by name
         spec = model_spec(study_model_name(cfg))
         ! the masses and g the study holds, where the model has them (as a run's)
         if (model_takes(cfg, 'm')) call spec%set('m', cfg%m(:max(1, cfg%list_size(1))))
         if (model_takes(cfg, 'g')) call spec%set('g', [cfg%g])
         if (allocated(cfg%model_params%items)) then
            do i = 1, size(cfg%model_params%items)
               call spec%set(cfg%model_params%items(i)%name, cfg%model_params%items(i)%values)
            end do
         end if
         return
      end if
      spec = model_spec(default_model)
      call spec%set('links', [real(n, dp)])
      call spec%set('m', cfg%m(:n))
      call spec%set('l', cfg%l(:n))
      call spec%set('g', [cfg%g])
      if (present(conservative)) then
         if (conservative) return
      end if
      associate (cs => cfg%cases(ic))
         call spec%set('damping', case_damping(cs, n))
         call spec%set('support_amplitude', cs%support_amplitude)
         call spec%set('support_frequency', [cs%support_frequency])
         call spec%set('support_phase', cs%support_phase)
         spec%torque = cs%torque
      end associate
   end function case_spec

   !> Whether the study's model has the parameter `name` (its catalogue row).
   logical function model_takes(cfg, name)
      type(study_config_t), intent(in) :: cfg  !! configuration
      character(len=*), intent(in) :: name     !! parameter name
      model_takes = has_parameter(study_model_name(cfg), name)
   end function model_takes

   !> The damping of a case of n links (0 when none is given).
   pure function case_damping(cs, n) result(c)
      type(study_case_t), intent(in) :: cs  !! the case
      integer, intent(in) :: n              !! its links
      real(dp) :: c(n)
      c = 0.0_dp
      if (allocated(cs%damping)) c = cs%damping(:n)
   end function case_damping

   !> The effective configuration as &pendulum and &study namelists (one string
   !> with new lines), for the output file: reading it back reproduces the study
   !> (with --quick already applied, so it is written with quick = .false.).
   function study_namelist(cfg) result(text)
      type(study_config_t), intent(in) :: cfg  !! configuration
      character(len=:), allocatable :: text
      character(len=*), parameter :: nl = new_line('a')
      character(len=64) :: b
      integer :: i, n
      ! the lists m, l when a case has other than two links (as many values as the
      ! longest case, at least two), else the double pendulum's names
      n = 2
      do i = 1, size(cfg%cases)
         n = max(n, size(cfg%cases(i)%q0))
      end do
      if (.not. default_model_study(cfg)) then   ! &model: the parameters given by name
         text = "&model name = '"//study_model_name(cfg)//"'"
         if (model_takes(cfg, 'm')) text = text//', m = '//list(cfg%m(:max(1, cfg%list_size(1))))
         if (model_takes(cfg, 'g')) text = text//', g = '//g(cfg%g)
         if (allocated(cfg%model_params%items)) then
            do i = 1, size(cfg%model_params%items)
               text = text//', '//cfg%model_params%items(i)%name//' = '// &
                      list(cfg%model_params%items(i)%values)
            end do
         end if
         text = text//' /'//nl
      else if (all([(size(cfg%cases(i)%q0) == 2, i=1, size(cfg%cases))])) then
         text = '&pendulum m1 = '//g(cfg%m(1))//', m2 = '//g(cfg%m(2))//', l1 = ' &
                //g(cfg%l(1))//', l2 = '//g(cfg%l(2))//', g = '//g(cfg%g)//' /'//nl
      else
         text = '&pendulum m = '//list(cfg%m(:n))//', l = '//list(cfg%l(:n))//', g = ' &
                //g(cfg%g)//' /'//nl
      end if
      text = text//'&study'//nl
      do i = 1, size(cfg%cases)
         write (b, '(i0)') i
         if (size(cfg%cases(i)%q0) == 2) then
            text = text//'  case_name('//trim(b)//") = '"//cfg%cases(i)%name//"', case_q1(" &
                   //trim(b)//') = '//g(cfg%cases(i)%q0(1))//', case_q2('//trim(b)//') = ' &
                   //g(cfg%cases(i)%q0(2))//', case_w1('//trim(b)//') = ' &
                   //g(cfg%cases(i)%w0(1))//', case_w2('//trim(b)//') = ' &
                   //g(cfg%cases(i)%w0(2))//', case_long_steps('//trim(b)//') = ' &
                   //g(cfg%cases(i)%long_steps)//nl
         else
            n = size(cfg%cases(i)%q0)
            text = text//'  case_name('//trim(b)//") = '"//cfg%cases(i)%name// &
                   "', case_links("//trim(b)//') = '//i_(n)//', case_q(1:'//i_(n)//', ' &
                   //trim(b)//') = '//list(cfg%cases(i)%q0)//', case_w(1:'//i_(n)//', ' &
                   //trim(b)//') = '//list(cfg%cases(i)%w0)//', case_long_steps(' &
                   //trim(b)//') = '//g(cfg%cases(i)%long_steps)//nl
         end if
         if (balance_case(cfg, i)) then
            associate (cs => cfg%cases(i))
               n = size(cs%q0)
               text = text//'  case_damping(1:'//i_(n)//', '//trim(b)//') = '// &
                      list(case_damping(cs, n))//nl//'  case_support_amplitude(1:2, '// &
                      trim(b)//') = '//list(cs%support_amplitude)// &
                      ', case_support_frequency('//trim(b)//') = '// &
                      g(cs%support_frequency)//', case_support_phase(1:2, '//trim(b)// &
                      ') = '//list(cs%support_phase)//nl
               if (cs%torque%active()) text = text//'  case_torque_file('//trim(b)// &
                  ") = '"//quoted_path(cs%torque_file)//"'"//nl
            end associate
         end if
      end do
      do i = 1, size(cfg%methods)
         write (b, '(i0)') i
         text = text//'  method('//trim(b)//") = '"//cfg%methods(i)%name//"', h_min(" &
                //trim(b)//') = '//g(cfg%methods(i)%h_min)//', h_max('//trim(b)//') = ' &
                //g(cfg%methods(i)%h_max)
         if (cfg%methods(i)%rtol_min > 0.0_dp) text = text//', rtol_min('//trim(b)//') = ' &
                                                      //g(cfg%methods(i)%rtol_min)// &
                                                      ', rtol_max('//trim(b)//') = ' &
                                                      //g(cfg%methods(i)%rtol_max)
         text = text//nl
      end do
      text = text//'  n_h = '//i_(cfg%n_h)//', n_rtol = '//i_(cfg%n_rtol)//', atol_ratio = ' &
             //g(cfg%atol_ratio)//nl// &
             '  t_short = '//g(cfg%t_short)//', n_check = '//i_(cfg%n_check)//nl// &
             "  order_case = '"//cfg%order_case//"', drift_case = '"//cfg%drift_case// &
             "', drift_decades = "//g(cfg%drift_decades)//nl// &
             '  bins_per_decade = '//i_(cfg%bins_per_decade)//', decades = ' &
             //i_(cfg%decades)//nl// &
             "  ref_method = '"//cfg%ref_method//"', ref_dt = "//g(cfg%ref_dt)// &
             ", check_method = '"//cfg%check_method//"', check_rtol = "//g(cfg%check_rtol)//nl// &
             '  wall_min = '//g(cfg%wall_min)//nl
      do i = 1, size(cfg%ro_methods)
         write (b, '(i0)') i
         text = text//'  ro_method('//trim(b)//") = '"//trim(cfg%ro_methods(i))// &
                "', ro_dt("//trim(b)//') = '//g(cfg%ro_dt(i))//nl
      end do
      text = text//'  ro_steps = '//g(cfg%ro_steps)//', ro_runs = '//i_(cfg%ro_runs)// &
             ", ro_case = '"//cfg%ro_case//"', ro_perturb = "//g(cfg%ro_perturb)// &
             ', ro_fit_t_min = '//g(cfg%ro_fit_t_min)//nl
      do i = 1, size(cfg%tao_methods)
         write (b, '(i0)') i
         text = text//'  tao_method('//trim(b)//") = '"//trim(cfg%tao_methods(i))//"'"//nl
      end do
      text = text//'  tao_dt = '//g(cfg%tao_dt)//', tao_t_end = '//g(cfg%tao_t_end)// &
             ', omega_min = '//g(cfg%omega_min)//', omega_max = '//g(cfg%omega_max)// &
             ', n_omega = '//i_(cfg%n_omega)//", tao_case = '"//cfg%tao_case//"'"//nl
      ! the values above are the effective ones: --quick is already applied
      if (cfg%quick) text = text//'  ! reduced by --quick'//nl
      text = text//'  quick = .false.'//nl//'/'
   contains
      function g(x) result(s)
         real(dp), intent(in) :: x
         character(len=:), allocatable :: s
         s = sci(x)   ! the shortest text that reads back exactly
      end function g
      function i_(k) result(s)
         integer, intent(in) :: k
         character(len=:), allocatable :: s
         character(len=16) :: buf
         write (buf, '(i0)') k
         s = trim(buf)
      end function i_
      function list(x) result(s)
         real(dp), intent(in) :: x(:)
         character(len=:), allocatable :: s
         integer :: k
         s = g(x(1))
         do k = 2, size(x)
            s = s//', '//g(x(k))
         end do
      end function list
      !> A path in a namelist string: each ' doubled.
      function quoted_path(path) result(s)
         character(len=*), intent(in) :: path
         character(len=:), allocatable :: s
         integer :: k
         s = ''
         do k = 1, len(path)
            s = s//path(k:k)
            if (path(k:k) == "'") s = s//"'"
         end do
      end function quoted_path
   end function study_namelist

   !> Read the torque file of every case that names one (`case_torque_file`) into its
   !> `torque` (the columns tau1 … tauN of its N links): the pendulum's cases only (a
   !> model of &model has no joints), refusals naming the case's key, the file and the
   !> line.
   subroutine read_case_torques(cfg, error)
      type(study_config_t), intent(inout) :: cfg        !! configuration; torques set
      type(error_t), allocatable, intent(out) :: error  !! unreadable, refused
      integer :: i
      do i = 1, size(cfg%cases)
         if (.not. allocated(cfg%cases(i)%torque_file)) cycle
         if (len(cfg%cases(i)%torque_file) == 0) cycle
         if (.not. default_model_study(cfg)) then
            call fatal_error(error, 'invalid case_torque_file('//to_str(i)//'): model ' &
                             //study_model_name(cfg)//' has no joints to apply torques ' &
                             //'to (the pendulum of &pendulum takes them)')
            return
         end if
         call read_torque_file(cfg%cases(i)%torque_file, size(cfg%cases(i)%q0), &
                               cfg%cases(i)%torque, error)
         if (allocated(error)) then
            error%message = error%message//" (case_torque_file("//to_str(i)//"), case '" &
                            //cfg%cases(i)%name//"')"
            return
         end if
      end do
   end subroutine read_case_torques

   !> The torques of a case cover every run of it (a series is not extrapolated): the
   !> short runs and the reference to t_short, the long runs of each method to
   !> case_long_steps × the middle step of its fixed-step sweep (`step_grid`). Times in
   !> seconds, after --quick (whose long runs are shorter).
   subroutine check_case_torques(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! validated, times in seconds
      type(error_t), allocatable, intent(out) :: error  !! a span not covered
      real(dp) :: t_end, hs(cfg%n_h)
      integer :: i, im
      do i = 1, size(cfg%cases)
         if (.not. cfg%cases(i)%torque%active()) cycle
         t_end = cfg%t_short
         do im = 1, size(cfg%methods)
            hs = step_grid(cfg%methods(im)%h_min, cfg%methods(im)%h_max, cfg%n_h, &
                           cfg%t_short/real(cfg%n_check, dp))
            t_end = max(t_end, cfg%cases(i)%long_steps*hs((cfg%n_h + 1)/2))
         end do
         if (cfg%cases(i)%torque%covers(0.0_dp, t_end)) cycle
         call fatal_error(error, 'invalid case_torque_file('//to_str(i)//"): the runs of " &
                          //"case '"//cfg%cases(i)%name//"' span [0, "//sci(t_end, 6)// &
                          '] s (t_short and case_long_steps times the middle step of each ' &
                          //"method's sweep), the torques are "//cfg%cases(i)%torque%text()// &
                          ' (a series is not extrapolated: fewer case_long_steps, or samples' &
                          //' over the whole span)')
         return
      end do
   end subroutine check_case_torques

   !> Steps of a fixed-step sweep: n values from h_max down to h_min, geometric,
   !> each rounded to (t_short/n_check)/m with m an integer so that the steps hit
   !> the checkpoints; m is made strictly increasing.
   pure function step_grid(h_min, h_max, n, interval) result(h)
      real(dp), intent(in) :: h_min     !! smallest step [s]
      real(dp), intent(in) :: h_max     !! largest step [s]
      integer, intent(in) :: n          !! number of steps (>= 1)
      real(dp), intent(in) :: interval  !! checkpoint interval t_short/n_check [s]
      real(dp) :: h(n)
      integer :: m(n), k
      real(dp) :: hk
      do k = 1, n
         if (n == 1) then
            hk = sqrt(h_min*h_max)
         else
            hk = h_max*(h_min/h_max)**(real(k - 1, dp)/real(n - 1, dp))
         end if
         m(k) = max(1, nint(interval/hk))
         if (k > 1) m(k) = max(m(k), m(k - 1) + 1)
         h(k) = interval/real(m(k), dp)
      end do
   end function step_grid

   !> Check the whole configuration; messages name the field and the accepted range.
   !> The order of the checks is the order of the first refusal: the cases' systems,
   !> the horizon, the cases' values, the methods, the settings, the experiments.
   subroutine validate_study_config(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      integer :: i
      if (size(cfg%cases) == 0) then
         call fatal_error(error, 'invalid case_name: at least one case is needed')
         return
      end if
      ! the parameters of every case's system
      do i = 1, size(cfg%cases)
         call check_system(cfg, i, error)
         if (allocated(error)) return
      end do
      ! the scalars that later checks divide by, first (limits: dpend_limits)
      if (.not. (finite_positive(cfg%t_short) .and. in_range(cfg%t_short, 0.0_dp, max_time))) &
         then
         call fatal_error(error, 'invalid t_short: must be in (0, '//sci(max_time)//'] (s)')
         return
      else if (cfg%n_check < 1 .or. cfg%n_check > 1000) then
         call fatal_error(error, 'invalid n_check: must be an integer in 1..1000')
         return
      end if
      call check_cases(cfg, error)
      if (allocated(error)) return
      call check_methods(cfg, error)
      if (allocated(error)) return
      call check_settings(cfg, error)
      if (allocated(error)) return
      call check_experiments(cfg, error)
   end subroutine validate_study_config

   !> The initial values, long-run steps and names of the cases.
   subroutine check_cases(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      integer :: i, j
      character(len=16) :: idx
      do i = 1, size(cfg%cases)
         write (idx, '("(", i0, ")")') i
         if (.not. all(ieee_is_finite([cfg%cases(i)%q0, cfg%cases(i)%w0]))) then
            call fatal_error(error, 'invalid case_q1, case_q2, case_w1, case_w2'//trim(idx)// &
                             ' (case_q, case_w): must be finite (rad, rad/s)')
            return
         end if
         if (maxval(abs(cfg%cases(i)%q0)) > max_angle) then
            call fatal_error(error, 'invalid case_q1, case_q2'//trim(idx)//' (case_q): must ' &
                             //'be within [-'//sci(max_angle)//', '//sci(max_angle)//'] (rad)')
            return
         end if
         if (maxval(abs(cfg%cases(i)%w0)) > max_angular_velocity) then
            call fatal_error(error, 'invalid case_w1, case_w2'//trim(idx)//' (case_w): must ' &
                             //'be within ' &
                             //'[-'//sci(max_angular_velocity)//', ' &
                             //sci(max_angular_velocity)//'] (rad/s)')
            return
         end if
         if (.not. finite_positive(cfg%cases(i)%long_steps - 0.5_dp) .or. &
             cfg%cases(i)%long_steps > real(max_steps, dp)) then
            call fatal_error(error, 'invalid case_long_steps'//trim(idx)//': must be in 1..' &
                             //sci(real(max_steps, dp)))
            return
         end if
         if (verify(cfg%cases(i)%name, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ' &
                    //'0123456789_-') /= 0) then
            call fatal_error(error, "invalid case_name"//trim(idx)//": '"//cfg%cases(i)%name// &
                             "' (letters, digits, '_' and '-' only)")
            return
         end if
         do j = 1, i - 1
            if (cfg%cases(j)%name == cfg%cases(i)%name) then
               call fatal_error(error, "invalid case_name: '"//cfg%cases(i)%name// &
                                "' appears twice")
               return
            end if
         end do
      end do
      call check_lists_used(cfg, error)
   end subroutine check_cases

   !> A list m or l serves the cases of up to as many links as it has values (a
   !> case of n links takes the first n); values beyond the most links of any case
   !> would be dropped without a word: refused.
   subroutine check_lists_used(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! a list longer than used
      character(len=1), parameter :: names(2) = ['m', 'l']
      integer :: k, most, i
      if (.not. default_model_study(cfg)) return   ! the factory checks a model's lists
      most = 0
      do i = 1, size(cfg%cases)
         most = max(most, size(cfg%cases(i)%q0))
      end do
      do k = 1, 2
         if (cfg%list_size(k) <= most) cycle
         call fatal_error(error, 'invalid '//names(k)//': '//to_str(cfg%list_size(k))// &
                          ' values, but the cases have at most '//to_str(most)//' links ' &
                          //'(a case of n links takes the first n values) [--'//names(k)// &
                          ' / &pendulum '//names(k)//']')
         return
      end do
   end subroutine check_lists_used

   !> The methods: known, once each, suited to every case, their step and tolerance
   !> ranges.
   subroutine check_methods(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      class(integrator_t), allocatable :: integ
      integer :: i, j
      character(len=16) :: idx
      if (size(cfg%methods) == 0) then
         call fatal_error(error, 'invalid method: at least one method is needed')
         return
      end if
      do i = 1, size(cfg%methods)
         write (idx, '("(", i0, ")")') i
         call new_integrator(cfg%methods(i)%name, integ, error)
         if (allocated(error)) then
            error%message = 'in &study method'//trim(idx)//': '//error%message
            return
         end if
         do j = 1, i - 1
            if (cfg%methods(j)%name == cfg%methods(i)%name) then
               call fatal_error(error, "invalid method: '"//printable(cfg%methods(i)%name)// &
                                "' appears twice")
               return
            end if
         end do
         call check_accepts(cfg, 'method'//trim(idx), integ, error)
         if (allocated(error)) return
         associate (m => cfg%methods(i))
            if (.not. (finite_positive(m%h_min) .and. finite_positive(m%h_max))) then
               call fatal_error(error, 'invalid h_min, h_max'//trim(idx)//' ('//m%name// &
                                '): must be finite and > 0 (s)')
            else if (m%h_min > m%h_max) then
               call fatal_error(error, 'invalid h_min'//trim(idx)//' ('//m%name// &
                                '): must be <= h_max (s)')
            else if (m%h_max > cfg%t_short/cfg%n_check) then
               call fatal_error(error, 'invalid h_max'//trim(idx)//' ('//m%name// &
                                '): must be <= t_short/n_check (s)')
            else if (m%h_min*real(max_steps, dp) < cfg%t_short) then
               call check_count('h_min'//trim(idx), m%h_min, cfg%t_short, 't_short', &
                                max_steps, 'steps', 'use a larger h_min', error)
            else if (m%rtol_min /= 0.0_dp .or. m%rtol_max /= 0.0_dp) then
               if (.not. integ%adaptive()) then
                  call fatal_error(error, 'invalid rtol_min, rtol_max'//trim(idx)//' ('// &
                                   m%name//'): only for the adaptive methods dopri5, dop853')
               else if (.not. (finite_positive(m%rtol_min) .and. m%rtol_min <= m%rtol_max &
                               .and. m%rtol_max < 1.0_dp)) then
                  call fatal_error(error, 'invalid rtol_min, rtol_max'//trim(idx)//' ('// &
                                   m%name//'): need 0 < rtol_min <= rtol_max < 1')
               else if (m%rtol_min < min_rtol) then
                  call fatal_error(error, 'invalid rtol_min'//trim(idx)//' ('//m%name// &
                                   '): '//sci(m%rtol_min)//' is below '//sci(min_rtol)// &
                                   ' (double precision cannot honour it)')
               else if (.not. (finite_positive(cfg%atol_ratio) .and. &
                                in_range(cfg%atol_ratio, 0.0_dp, 1e6_dp))) then
                  call fatal_error(error, 'invalid atol_ratio: must be in (0, 1e6]')
               else if (cfg%atol_ratio*m%rtol_min < min_atol .or. &
                        cfg%atol_ratio*m%rtol_max > max_atol) then
                  call fatal_error(error, 'invalid atol_ratio: atol = atol_ratio * rtol ' &
                                   //'must stay in ['//sci(min_atol)//', '//sci(max_atol)// &
                                   '] for rtol in ['//sci(m%rtol_min)//', '// &
                                   sci(m%rtol_max)//']')
               end if
            end if
         end associate
         if (allocated(error)) return
      end do
   end subroutine check_methods

   !> The scalar settings: grids, horizons, the reference, the roundoff and Tao runs.
   subroutine check_settings(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      if (cfg%n_h < 2 .or. cfg%n_h > 64) then
         call fatal_error(error, 'invalid n_h: must be an integer in 2..64')
      else if (.not. (finite_positive(cfg%drift_decades) .and. &
                      in_range(cfg%drift_decades, 0.0_dp, 100.0_dp))) then
         call fatal_error(error, 'invalid drift_decades: must be in (0, 100]')
      else if (cfg%threads > max_threads) then
         call fatal_error(error, 'invalid threads: '//sci(real(cfg%threads, dp))// &
                          ' must be an integer from 0 (default) to '//sci(real(max_threads, dp)))
      else if (.not. (in_range(cfg%wall_min, 0.0_dp, max_time) .and. &
                      in_range(cfg%ro_fit_t_min, 0.0_dp, max_time) .and. &
                      in_range(cfg%tao_t_end, 0.0_dp, max_time) .and. &
                      in_range(cfg%ro_perturb, 0.0_dp, 1.0_dp))) then
         call fatal_error(error, 'invalid wall_min, ro_fit_t_min, tao_t_end: must be in [0, ' &
                          //sci(max_time)//'] s; ro_perturb in [0, 1] rad')
      else if (.not. in_range(cfg%omega_max, -huge(1.0_dp), max_omega)) then
         call fatal_error(error, 'invalid omega_max: must be at most '//sci(max_omega)//' 1/s')
      else if (cfg%n_rtol < 2 .or. cfg%n_rtol > 64) then
         call fatal_error(error, 'invalid n_rtol: must be an integer in 2..64')
      else if (.not. finite_positive(cfg%atol_ratio)) then
         call fatal_error(error, 'invalid atol_ratio: must be finite and > 0')
      else if (.not. finite_positive(cfg%t_short)) then
         call fatal_error(error, 'invalid t_short: must be finite and > 0 (s)')
      else if (cfg%n_check < 1 .or. cfg%n_check > 1000) then
         call fatal_error(error, 'invalid n_check: must be an integer in 1..1000')
      else if (.not. finite_positive(cfg%drift_decades)) then
         call fatal_error(error, 'invalid drift_decades: must be finite and > 0')
      else if (cfg%bins_per_decade < 1 .or. cfg%bins_per_decade > 100) then
         call fatal_error(error, 'invalid bins_per_decade: must be an integer in 1..100')
      else if (cfg%decades < 1 .or. cfg%decades > 12) then
         call fatal_error(error, 'invalid decades: must be an integer in 1..12')
      else if (.not. finite_positive(cfg%ref_dt) .or. cfg%ref_dt > cfg%t_short/cfg%n_check) &
         then
         call fatal_error(error, 'invalid ref_dt: must be in (0, t_short/n_check] (s)')
      else if (.not. (in_range(cfg%check_rtol, min_rtol, 1.0_dp) .and. cfg%check_rtol < 1.0_dp)) &
         then   ! (below min_rtol the step of the check shrinks until it traps)
         call fatal_error(error, 'invalid check_rtol: must be in ['//sci(min_rtol)//', 1) ' &
                          //'(double precision cannot honour a smaller tolerance)')
      else if (.not. (finite_positive(cfg%wall_min) .or. cfg%wall_min == 0.0_dp)) then
         call fatal_error(error, 'invalid wall_min: must be finite and >= 0 (s)')
      else if (.not. finite_positive(cfg%ro_steps - 0.5_dp) .or. cfg%ro_steps > 1e10_dp) then
         call fatal_error(error, 'invalid ro_steps: must be in 1..1e10')
      else if (cfg%ro_runs < 1 .or. cfg%ro_runs > 10000) then
         call fatal_error(error, 'invalid ro_runs: must be an integer in 1..10000')
      else if (.not. (finite_positive(cfg%ro_perturb) .or. cfg%ro_perturb == 0.0_dp)) then
         call fatal_error(error, 'invalid ro_perturb: must be finite and >= 0 (rad)')
      else if (.not. (finite_positive(cfg%ro_fit_t_min))) then
         call fatal_error(error, 'invalid ro_fit_t_min: must be finite and > 0 (s)')
      else if (.not. (finite_positive(cfg%tao_dt) .and. finite_positive(cfg%tao_t_end))) then
         call fatal_error(error, 'invalid tao_dt, tao_t_end: must be finite and > 0 (s)')
      else if (.not. (finite_positive(cfg%omega_min) .and. finite_positive(cfg%omega_max))) &
         then
         call fatal_error(error, 'invalid omega_min, omega_max: must be finite and > 0 (1/s)')
      else if (cfg%omega_min > cfg%omega_max) then
         call fatal_error(error, 'invalid omega_min: must be <= omega_max (1/s)')
      else if (cfg%n_omega < 1 .or. cfg%n_omega > 200) then
         call fatal_error(error, 'invalid n_omega: must be an integer in 1..200')
      else if (cfg%ref_dt*real(max_steps, dp) < cfg%t_short) then
         call fatal_error(error, 'invalid ref_dt: '//sci(cfg%ref_dt)//' s gives more than ' &
                          //sci(real(max_steps, dp))//' steps over t_short')
      else if (cfg%tao_dt*real(max_steps, dp) < cfg%tao_t_end + cfg%t_short) then
         call fatal_error(error, 'invalid tao_dt: '//sci(cfg%tao_dt)//' s gives more than ' &
                          //sci(real(max_steps, dp))//' steps over tao_t_end + t_short')
      else if (cfg%threads < 0) then
         call fatal_error(error, 'invalid --threads: must be an integer >= 1')
      end if
   end subroutine check_settings

   !> The cases named by the verdicts and experiments, the reference and check
   !> methods, the roundoff and the Tao methods.
   subroutine check_experiments(cfg, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      class(integrator_t), allocatable :: integ
      integer :: i
      character(len=16) :: idx
      call check_case_name(cfg, 'order_case', cfg%order_case, error)
      if (.not. allocated(error)) call check_case_name(cfg, 'drift_case', cfg%drift_case, error)
      if (.not. allocated(error)) call check_case_name(cfg, 'ro_case', cfg%ro_case, error)
      if (.not. allocated(error)) call check_case_name(cfg, 'tao_case', cfg%tao_case, error)
      if (allocated(error)) return
      call new_integrator(cfg%ref_method, integ, error)
      if (allocated(error)) then
         error%message = 'in &study ref_method: '//error%message
         return
      end if
      if (integ%adaptive()) then
         call fatal_error(error, "invalid ref_method: '"//cfg%ref_method// &
                          "' must be a fixed-step method (e.g. gauss8)")
         return
      end if
      call check_accepts(cfg, 'ref_method', integ, error)
      if (allocated(error)) return
      call new_integrator(cfg%check_method, integ, error)
      if (allocated(error)) then
         error%message = 'in &study check_method: '//error%message
         return
      end if
      call check_accepts(cfg, 'check_method', integ, error)
      if (allocated(error)) return
      do i = 1, size(cfg%ro_methods)
         write (idx, '("(", i0, ")")') i
         call new_integrator(trim(cfg%ro_methods(i)), integ, error)
         if (allocated(error)) then
            error%message = 'in &study ro_method'//trim(idx)//': '//error%message
            return
         end if
         if (.not. method_table(method_index(trim(cfg%ro_methods(i))))%compensated) then
            call fatal_error(error, "invalid ro_method"//trim(idx)//": '"// &
                             trim(cfg%ro_methods(i))//"' has no compensated summation (use "// &
                             "midpoint gauss4 gauss6 gauss8 verlet yoshida4 comp6 comp8)")
            return
         end if
         if (.not. finite_positive(cfg%ro_dt(i)) .or. cfg%ro_dt(i) > 1.0_dp) then
            call fatal_error(error, 'invalid ro_dt'//trim(idx)//': must be in (0, 1] (s)')
            return
         end if
      end do
      do i = 1, size(cfg%tao_methods)
         write (idx, '("(", i0, ")")') i
         call new_integrator(trim(cfg%tao_methods(i)), integ, error)
         if (allocated(error)) then
            error%message = 'in &study tao_method'//trim(idx)//': '//error%message
            return
         end if
         if (.not. method_table(method_index(trim(cfg%tao_methods(i))))%omega) then
            call fatal_error(error, "invalid tao_method"//trim(idx)//": '"// &
                             trim(cfg%tao_methods(i))//"' (accepted: tao2 tao4)")
            return
         end if
      end do
   end subroutine check_experiments

   !> A method refuses a case whose model it cannot run: the method is asked of each
   !> case's model (`check_model`; a damped or driven case is named as such).
   subroutine check_accepts(cfg, field, method, error)
      type(study_config_t), intent(in) :: cfg           !! configuration, cases checked
      character(len=*), intent(in) :: field             !! e.g. 'method(3)'
      class(integrator_t), intent(in) :: method         !! the method
      type(error_t), allocatable, intent(out) :: error  !! refused
      class(model_t), allocatable :: model
      type(error_t), allocatable :: refused
      character(len=*), parameter :: prefix = 'invalid method: '
      integer :: ic
      do ic = 1, size(cfg%cases)
         if (method%needs_hamiltonian() .and. balance_case(cfg, ic)) then
            call fatal_error(error, 'invalid '//field//": '"//method%name()//"' needs a " &
                             //"Hamiltonian model; case '"//cfg%cases(ic)%name// &
                             "' is damped or driven (use "//field_method_names()//')')
            return
         end if
         call case_model(cfg, ic, model)   ! the method asked of the case's own model
         call method%check_model(model, refused)
         if (allocated(refused)) then
            if (index(refused%message, prefix) == 1) &
               refused%message = refused%message(len(prefix) + 1:)
            call fatal_error(error, 'invalid '//field//": '"//method%name()//"' cannot run " &
                             //"case '"//cfg%cases(ic)%name//"': "//refused%message)
            return
         end if
      end do
   end subroutine check_accepts

   !> The system of case ic: the double pendulum's parameters for two links, the
   !> chain's otherwise; given lists m, l cover the case's links; the damping and
   !> the moving support of a balance case (a chain of at most max_dof − 1 links).
   subroutine check_system(cfg, ic, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      integer, intent(in) :: ic                         !! case index
      type(error_t), allocatable, intent(out) :: error  !! refused
      class(model_t), allocatable :: model
      integer :: n, k
      character(len=1), parameter :: names(2) = ['m', 'l']
      n = size(cfg%cases(ic)%q0)
      if (.not. default_model_study(cfg)) then
         call check_model_case(cfg, ic, error)
         return
      end if
      if (n < 1 .or. n > max_dof .or. size(cfg%cases(ic)%w0) /= n) then
         call fatal_error(error, 'invalid case_links('//to_str(ic)//'): '//to_str(n)// &
                          ' links, '//to_str(size(cfg%cases(ic)%w0))//' angular velocities' &
                          //' (1 to '//to_str(max_dof)//' links, one value per link)')
         return
      end if
      do k = 1, 2
         if (cfg%list_size(k) /= 0 .and. cfg%list_size(k) < n) then
            call fatal_error(error, 'invalid '//names(k)//': '//to_str(cfg%list_size(k))// &
                             ' values for the '//to_str(n)//" links of case '"// &
                             cfg%cases(ic)%name//"' (one per link) [--"//names(k)// &
                             ' / &pendulum '//names(k)//']')
            return
         end if
      end do
      call new_model(case_spec(cfg, ic, conservative=.true.), model, error)
      if (allocated(error)) then
         if (n == 2) then
            error%message = error%message//' [--m1 --m2 --l1 --l2 --g / &pendulum]'
         else
            error%message = error%message//" (case '"//cfg%cases(ic)%name//"', "// &
                            to_str(n)//' links) [--m --l --g / &pendulum]'
         end if
      end if
      if (allocated(error) .or. .not. balance_case(cfg, ic)) return
      k = merge(2, 1, cfg%cases(ic)%torque%active())   ! the works' state slots
      if (n > max_dof - k) then
         call fatal_error(error, 'invalid case_links('//to_str(ic)//'): '//to_str(n)// &
                          ' with damping, a moving support or torques is outside [1, '// &
                          to_str(max_dof - k)//'] (the energy balance takes '// &
                          to_str(2*k)//' state components)')
         return
      end if
      call new_model(case_spec(cfg, ic), model, error)
      if (allocated(error)) error%message = error%message//" (case '"// &
                                            cfg%cases(ic)%name//"': case_damping, " &
                                            //'case_support_*, case_torque_file)'
   end subroutine check_system

   !> Case ic of a model given by &model (not the pendulum of m, l, g): the factory
   !> builds it from the parameters by name; the case has its n_dof coordinates and
   !> rates, a state the model accepts (`check_state`), no damping or moving support,
   !> and no &pendulum or --m1 ... flags are given (they would be ignored).
   subroutine check_model_case(cfg, ic, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      integer, intent(in) :: ic                         !! case index
      type(error_t), allocatable, intent(out) :: error  !! refused
      class(model_t), allocatable :: model
      character(len=:), allocatable :: where
      where = " (case '"//cfg%cases(ic)%name//"', model "//study_model_name(cfg)//')'
      call new_model(case_spec(cfg, ic), model, error)
      if (allocated(error)) then
         error%message = error%message//' [&model]'
         return
      end if
      if (unread()) then
         call fatal_error(error, 'invalid &pendulum (or --m1, --m2, --l1, --l2, --g, --m, ' &
                          //'--l): not read for model '//study_model_name(cfg)// &
                          '; give its parameters by name in &model (dpend models)')
      else if (size(cfg%cases(ic)%q0) /= model%n_dof() .or. &
               size(cfg%cases(ic)%w0) /= model%n_dof()) then
         call fatal_error(error, 'invalid case_links('//to_str(ic)//'): '// &
                          to_str(size(cfg%cases(ic)%q0))//' coordinates, '// &
                          to_str(size(cfg%cases(ic)%w0))//' rates; model '// &
                          study_model_name(cfg)//' has '//to_str(model%n_dof())// &
                          ' of each (case_q1, case_q2, case_w1, case_w2 for two)'//where)
      else if (balance_case(cfg, ic)) then
         call fatal_error(error, 'invalid case_damping, case_support_amplitude('// &
                          to_str(ic)//'): model '//study_model_name(cfg)//' has no ' &
                          //'damping or moving support'//where)
      else
         call model%check_state(cfg%cases(ic)%q0, cfg%cases(ic)%w0, error)
         if (allocated(error)) error%message = error%message//where// &
                                               ' [case_q1, case_q2, case_w1, case_w2]'
      end if
   contains
      !> The study holds masses, lengths or g that the model has no parameter for
      !> (the masses and g it has are read: `case_spec`).
      logical function unread()
         logical :: per_link
         per_link = model_takes(cfg, 'links')
         unread = .false.
         if (.not. model_takes(cfg, 'l')) unread = cfg%list_size(2) /= 0 .or. &
                                                   any(cfg%l(:2) /= 1.0_dp)
         if (.not. model_takes(cfg, 'm')) then
            unread = unread .or. cfg%list_size(1) /= 0 .or. any(cfg%m(:2) /= 1.0_dp)
         else if (.not. per_link) then
            unread = unread .or. cfg%list_size(1) > 1 .or. cfg%m(2) /= 1.0_dp
         end if
         if (.not. model_takes(cfg, 'g')) unread = unread .or. cfg%g /= 9.8_dp
      end function unread
   end subroutine check_model_case

   !> `name` (of the setting `field`) is a case of the study.
   subroutine check_case_name(cfg, field, name, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      character(len=*), intent(in) :: field, name       !! e.g. 'ro_case', 'small'
      type(error_t), allocatable, intent(out) :: error  !! refused
      if (case_index(cfg, name) == 0) call fatal_error(error, 'invalid '//field//": '"// &
                                                       name//"' is not a case (accepted: " &
                                                       //case_list(cfg)//')')
   end subroutine check_case_name

   !> The case names, space separated.
   function case_list(cfg) result(s)
      type(study_config_t), intent(in) :: cfg
      character(len=:), allocatable :: s
      integer :: i
      s = cfg%cases(1)%name
      do i = 2, size(cfg%cases)
         s = s//' '//cfg%cases(i)%name
      end do
   end function case_list

   !> The names of a list given to option `field`: items separated by commas
   !> and/or blanks ('rk4,gauss6' or 'rk4, gauss6'). An empty list or an empty
   !> item (',', 'rk4,,gauss6', 'rk4,') is refused, naming the field.
   subroutine split_list(list, field, names, error)
      character(len=*), intent(in) :: list                  !! the option's value
      character(len=*), intent(in) :: field                 !! e.g. '--cases'
      character(len=:), allocatable, intent(out) :: names(:) !! the items
      type(error_t), allocatable, intent(out) :: error      !! empty list or item
      integer :: first(len(list) + 1), last(len(list) + 1)
      integer :: i, n, k
      logical :: in_word, item_empty
      character(len=len(list)) :: shown
      n = 0
      in_word = .false.
      item_empty = .true.
      do i = 1, len(list) + 1
         if (i > len(list)) then
            if (in_word) last(n) = i - 1
            if (item_empty) exit
         else if (list(i:i) == ',') then
            if (in_word) last(n) = i - 1
            in_word = .false.
            if (item_empty) exit
            item_empty = .true.
         else if (list(i:i) == ' ') then
            if (in_word) last(n) = i - 1
            in_word = .false.
         else if (.not. in_word) then
            n = n + 1
            first(n) = i
            in_word = .true.
            item_empty = .false.
         end if
      end do
      if (item_empty) then
         shown = list
         do k = 1, len(list)
            if (iachar(list(k:k)) < 32 .or. iachar(list(k:k)) > 126) shown(k:k) = '?'
         end do
         if (len_trim(list) == 0) then
            call fatal_error(error, 'invalid '//field//': empty list (give names '// &
                             'separated by commas)')
         else
            call fatal_error(error, 'invalid '//field//": '"//shown// &
                             "' has an empty item (give names separated by commas)")
         end if
         allocate (character(len=1) :: names(0))
         return
      end if
      allocate (character(len=maxval(last(:n) - first(:n) + 1)) :: names(n))
      do k = 1, n
         names(k) = list(first(k):last(k))
      end do
   end subroutine split_list

   !> The blank-separated words of `s`.
   pure subroutine split_words(s, words)
      character(len=*), intent(in) :: s
      character(len=16), allocatable, intent(out) :: words(:)
      integer :: i, n, start
      character(len=16) :: buf(64)
      n = 0
      i = 1
      do while (i <= len(s))
         if (s(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         start = i
         do while (i <= len(s))
            if (s(i:i) == ' ') exit
            i = i + 1
         end do
         if (n < size(buf)) then
            n = n + 1
            buf(n) = s(start:i - 1)
         end if
      end do
      words = buf(1:n)
   end subroutine split_words

end module dpend_study_settings
