!> Configuration of `dpend study`: the cases, the methods with their step and
!> tolerance ranges, the horizons, the roundoff (Brouwer) and Tao experiments,
!> read from the namelist group &study (plus &pendulum and &output) and from
!> the command line. The built-in defaults are the default study, written out
!> with comments in data/study.nml.
!>
!> Lists in &study are indexed arrays (`method(1) = 'rk4'`, `h_min(1) = 1e-3`).
!> A list that the file does not set keeps its default; a list that it sets
!> replaces the default list entirely, and a range left at 0 for a listed
!> method takes that method's default range.
module dpend_study_config
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_pendulum, only: finite_positive
   use dpend_model_factory, only: model_spec_t, model_spec, new_model, default_model
   use dpend_model, only: model_t, max_dof
   use dpend_cli, only: arg_t, next_option, parse_int, option_outcome, to_str
   use dpend_config, only: run_config_t, read_run_config, apply_run_flag, check_groups, &
                           namelist_error
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_method_registry, only: method_names, method_index, method_table, &
                                    field_method_names
   use dpend_kinds, only: i8
   use dpend_limits, only: in_range, check_range, check_count, sci, max_angle, &
                           max_angular_velocity, &
                           max_time, max_steps, min_rtol, min_atol, max_atol, max_omega, &
                           max_threads
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_cli, only: scan_help_config, printable
   implicit none
   private
   public :: study_config_t, study_case_t, study_method_t
   public :: study_defaults, parse_study, read_study_config, validate_study_config
   public :: apply_quick, study_help, study_namelist, case_index, default_ranges
   public :: balance_case
   public :: case_model, study_model_name, default_model_study
   public :: max_cases, max_methods, max_extra

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
      !> joint damping c_i [N m s], one per link (issue 13); not allocated: none
      real(dp), allocatable :: damping(:)
      real(dp) :: support_amplitude(2) = 0.0_dp  !! moving pin (a_x, a_y) [m]
      real(dp) :: support_frequency = 0.0_dp     !! its ω [rad/s]
      real(dp) :: support_phase(2) = 0.0_dp      !! its phases (φ_x, φ_y) [rad]
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

   ! ----------------------------------------------------------------- defaults

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

   !> Case ic is damped or driven (joint damping, a moving support): a balance case,
   !> whose energy error is the energy balance E(t) − E(0) + W_friction − W_support
   !> (dpend_work) and to which the drift verdicts are not applied.
   pure logical function balance_case(cfg, ic)
      type(study_config_t), intent(in) :: cfg  !! configuration
      integer, intent(in) :: ic                !! case index
      balance_case = any(cfg%cases(ic)%support_amplitude /= 0.0_dp)
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
         if (allocated(cfg%model_params%items)) then
            do i = 1, size(cfg%model_params%items)
               call spec%set(cfg%model_params%items(i)%name, cfg%model_params%items(i)%values)
            end do
         end if
         return
      end if
      spec = model_spec('pendulum')
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
      end associate
   end function case_spec

   !> The damping of a case of n links (0 when none is given).
   pure function case_damping(cs, n) result(c)
      type(study_case_t), intent(in) :: cs  !! the case
      integer, intent(in) :: n              !! its links
      real(dp) :: c(n)
      c = 0.0_dp
      if (allocated(cs%damping)) c = cs%damping(:n)
   end function case_damping

   ! -------------------------------------------------------------------- help

   !> Help text of `dpend study`.
   function study_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = 'usage: dpend study [options]'//nl//nl// &
          'The energy-conservation study: every method over a geometric range of steps'//nl// &
          '(tolerances for dopri5/dop853) on several initial conditions, to long times;'//nl// &
          'global errors against a reference, energy errors on a logarithmic time grid,'//nl// &
          "Brouwer's law of roundoff, Tao's binding constant. Writes one HDF5 file"//nl// &
          '(docs/study-hdf5.md), a Markdown summary next to it (FILE with .md), prints'//nl// &
          'the summary, and draws six figures with scripts/plot_study.sh (gnuplot).'//nl//nl// &
          'options:'//nl// &
          '  --config FILE     namelist file: &study, &pendulum, &output, &model (default:'//nl// &
          '                    data/study.nml, identical to the built-in defaults;'//nl// &
          '                    data/study_chain.nml: the triple pendulum, N-link chain;'//nl// &
          '                    data/study_damped.nml: damped and driven chains, whose'//nl// &
          '                    energy error is the energy balance, no drift verdict;'//nl// &
          '                    data/elastic_study.nml: the elastic pendulum, &model)'//nl// &
          '  --quick           smoke test, ~50x cheaper: long runs at 2 % of their steps,'//nl// &
          '                    4 roundoff runs of <= 1e5 steps, Tao runs at 1/10 horizon'//nl// &
          '  --methods LIST    only these methods (comma separated, from the config), also'//nl// &
          '                    in the roundoff and Tao experiments'//nl// &
          '  --cases LIST      only these cases (comma separated, from the config); a'//nl// &
          '                    verdict case left out becomes the first of them'//nl// &
          '  --threads N       OpenMP threads (default: OMP_NUM_THREADS or all cores)'//nl// &
          '  --output FILE     HDF5 file; default out/study/study.h5 (directory created)'//nl// &
          '  --force           overwrite an existing output file'//nl// &
          '  --no-figures      do not run scripts/plot_study.sh'//nl// &
          '  --m1, --m2 KG, --l1, --l2 M, --g M/S^2   pendulum parameters (default:'//nl// &
          "                    the chapter's 1 kg, 1 m, 9.8 m/s^2)"//nl// &
          '  --m LIST, --l LIST  per-link masses, lengths (comma separated) for cases of'//nl// &
          '                    N links (case_links in &study; N = 2: the double pendulum)'//nl// &
          '  -h, --help        this text'//nl//nl// &
          'Relative energy error: |H(t) - H(0)| / E_s with E_s = |H(0)|, or, when'//nl// &
          'H(0) ~ 0 (both links released horizontally), the potential energy with both'//nl// &
          'links upright, (m1/2 + m2) g l1 + (m2/2) g l2. A damped or driven case'//nl// &
          '(case_damping, case_support_* in &study) measures the energy balance'//nl// &
          '|E(t) - E(0) + W_friction - W_support| / E_s instead (methods that need a'//nl// &
          'Hamiltonian refuse such a case; no drift, roundoff or Tao runs on it).'
   end function study_help

   ! ------------------------------------------------------------ command line

   !> Build the study configuration from the defaults, --config and the flags.
   subroutine parse_study(args, cfg, help, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'study'
      type(study_config_t), intent(out) :: cfg          !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value, only_methods, only_cases, config
      type(run_config_t) :: rcfg
      logical :: matched, missing, methods_given, cases_given
      integer :: i
      cfg = study_defaults()
      help = .false.
      only_methods = ''
      only_cases = ''
      methods_given = .false.
      cases_given = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_study_config(config, cfg, error)
         if (allocated(error)) return
      end if
      rcfg%m = cfg%m; rcfg%l = cfg%l; rcfg%g = cfg%g; rcfg%list_size(1:2) = cfg%list_size
      i = 1
      do while (i <= size(args))
         select case (args(i)%s)
         case ('--force')
            cfg%force = .true.; i = i + 1; cycle
         case ('--quick')
            cfg%quick = .true.; i = i + 1; cycle
         case ('--no-figures')
            cfg%figures = .false.; i = i + 1; cycle
         end select
         if (args(i)%s(1:min(2, len(args(i)%s))) /= '--' .and. args(i)%s /= '-o') then
            call fatal_error(error, "unexpected argument '"//printable(args(i)%s)// &
                             "' (dpend study --help lists the options)")
            return
         end if
         call next_option(args, i, name, value, .true., error, missing)
         matched = .true.
         select case (name)
         case ('--config')
            cycle
         case ('--output', '-o')
            cfg%output = value
         case ('--threads')
            call parse_int(value, name, cfg%threads, error)
            if (.not. allocated(error) .and. .not. missing .and. cfg%threads < 1) &
               call fatal_error(error, 'invalid --threads: must be an integer >= 1')
         case ('--methods')
            only_methods = value
            methods_given = .true.
         case ('--cases')
            only_cases = value
            cases_given = .true.
         case ('--m1', '--m2', '--l1', '--l2', '--g', '--m', '--l')
            call apply_run_flag(rcfg, name, value, matched, error)
            cfg%m = rcfg%m; cfg%l = rcfg%l; cfg%g = rcfg%g
            cfg%list_size = rcfg%list_size(1:2)
         case default
            matched = .false.
         end select
         call option_outcome('study', name, matched, missing, [character(len=16) :: &
                             '--force', '--quick', '--no-figures'], error, study_help())
         if (allocated(error)) return
      end do
      if (methods_given) call select_methods(cfg, only_methods, error)
      if (allocated(error)) return
      if (cases_given) call select_cases(cfg, only_cases, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call apply_quick(cfg)
   end subroutine parse_study

   !> Keep only the methods named in the comma-separated `list`.
   subroutine select_methods(cfg, list, error)
      type(study_config_t), intent(inout) :: cfg         !! configuration
      character(len=*), intent(in) :: list               !! e.g. 'rk4,gauss6'
      type(error_t), allocatable, intent(out) :: error   !! a name not in the config
      character(len=:), allocatable :: names(:)
      logical :: keep(size(cfg%methods))
      integer :: i, j
      call split_list(list, '--methods', names, error)
      if (allocated(error)) return
      keep = .false.
      do j = 1, size(names)
         do i = 1, size(cfg%methods)
            if (cfg%methods(i)%name == trim(names(j))) keep(i) = .true.
         end do
         if (.not. any([(cfg%methods(i)%name == trim(names(j)), i=1, size(cfg%methods))])) then
            call fatal_error(error, "invalid --methods: '"//trim(names(j))// &
                             "' is not a method of the study (accepted: "//method_names()//")")
            return
         end if
      end do
      cfg%methods = pack(cfg%methods, keep)
      ! the roundoff and Tao experiments keep only the selected methods
      keep_ro: block
         logical :: sel(max(size(cfg%ro_methods), size(cfg%tao_methods)))
         do i = 1, size(cfg%ro_methods)
            sel(i) = any(names == cfg%ro_methods(i))
         end do
         cfg%ro_dt = pack(cfg%ro_dt, sel(:size(cfg%ro_methods)))
         cfg%ro_methods = pack(cfg%ro_methods, sel(:size(cfg%ro_methods)))
         do i = 1, size(cfg%tao_methods)
            sel(i) = any(names == cfg%tao_methods(i))
         end do
         cfg%tao_methods = pack(cfg%tao_methods, sel(:size(cfg%tao_methods)))
      end block keep_ro
   end subroutine select_methods

   !> Keep only the cases named in the comma-separated `list`.
   subroutine select_cases(cfg, list, error)
      type(study_config_t), intent(inout) :: cfg         !! configuration
      character(len=*), intent(in) :: list               !! e.g. 'small,mixed'
      type(error_t), allocatable, intent(out) :: error   !! a name not in the config
      character(len=:), allocatable :: names(:)
      logical :: keep(size(cfg%cases))
      integer :: i, j
      call split_list(list, '--cases', names, error)
      if (allocated(error)) return
      keep = .false.
      do j = 1, size(names)
         i = case_index(cfg, trim(names(j)))
         if (i == 0) then
            call fatal_error(error, "invalid --cases: '"//trim(names(j))// &
                             "' is not a case of the study (accepted: "//case_list(cfg)//")")
            return
         end if
         keep(i) = .true.
      end do
      cfg%cases = pack(cfg%cases, keep)
      ! the verdict and experiment cases fall back to the first selected case
      if (case_index(cfg, cfg%order_case) == 0) cfg%order_case = cfg%cases(1)%name
      if (case_index(cfg, cfg%drift_case) == 0) cfg%drift_case = cfg%cases(1)%name
      if (case_index(cfg, cfg%ro_case) == 0) cfg%ro_case = cfg%cases(1)%name
      if (case_index(cfg, cfg%tao_case) == 0) cfg%tao_case = cfg%cases(1)%name
   end subroutine select_cases

   ! ----------------------------------------------------------------- namelist

   !> Read &pendulum, &output and &study from `filename` into `cfg` (see the
   !> module header for how lists replace the defaults).
   subroutine read_study_config(filename, cfg, error)
      character(len=*), intent(in) :: filename           !! namelist file
      type(study_config_t), intent(inout) :: cfg         !! updated from the file
      type(error_t), allocatable, intent(out) :: error   !! unreadable or invalid
      character(len=32) :: case_name(max_cases), order_case, drift_case, ro_case, tao_case
      real(dp) :: case_q1(max_cases), case_q2(max_cases), case_w1(max_cases), &
                  case_w2(max_cases), case_long_steps(max_cases)
      integer :: case_links(max_cases)
      real(dp) :: case_q(max_dof, max_cases), case_w(max_dof, max_cases)
      real(dp) :: case_damping(max_dof, max_cases), case_support_amplitude(2, max_cases), &
                  case_support_frequency(max_cases), case_support_phase(2, max_cases)
      character(len=16) :: method(max_methods), ref_method, check_method
      real(dp) :: h_min(max_methods), h_max(max_methods), rtol_min(max_methods), &
                  rtol_max(max_methods)
      character(len=16) :: ro_method(max_extra), tao_method(max_extra)
      real(dp) :: ro_dt(max_extra)
      integer :: n_h, n_rtol, n_check, bins_per_decade, decades, ro_runs, n_omega
      real(dp) :: atol_ratio, t_short, drift_decades, ref_dt, check_rtol, wall_min, ro_steps, &
                  ro_perturb, ro_fit_t_min, tao_dt, tao_t_end, omega_min, omega_max
      logical :: quick
      integer :: unit, stat, i, n
      character(len=512) :: msg
      namelist /study/ case_name, case_q1, case_q2, case_w1, case_w2, case_long_steps, &
         case_links, case_q, case_w, case_damping, case_support_amplitude, &
         case_support_frequency, case_support_phase, &
         method, h_min, h_max, rtol_min, rtol_max, n_h, n_rtol, atol_ratio, t_short, &
         n_check, order_case, drift_case, drift_decades, bins_per_decade, decades, &
         ref_method, ref_dt, check_method, check_rtol, wall_min, ro_method, ro_dt, ro_steps, &
         ro_runs, ro_case, ro_perturb, ro_fit_t_min, tao_method, tao_dt, tao_t_end, &
         omega_min, omega_max, n_omega, tao_case, quick

      call read_study_groups(filename, cfg, error)
      if (allocated(error)) return

      ! lists start empty (a set list replaces the default); scalars start at the defaults
      case_name = ''; case_q1 = unset; case_q2 = unset; case_w1 = unset; case_w2 = unset
      case_long_steps = 0; case_links = 0; case_q = unset; case_w = unset
      case_damping = unset; case_support_amplitude = 0; case_support_frequency = 0
      case_support_phase = 0
      method = ''; h_min = 0; h_max = 0; rtol_min = 0; rtol_max = 0
      ro_method = ''; ro_dt = 0; tao_method = ''
      n_h = cfg%n_h; n_rtol = cfg%n_rtol; atol_ratio = cfg%atol_ratio; t_short = cfg%t_short
      n_check = cfg%n_check; order_case = cfg%order_case; drift_case = cfg%drift_case
      drift_decades = cfg%drift_decades; bins_per_decade = cfg%bins_per_decade
      decades = cfg%decades; ref_method = cfg%ref_method; ref_dt = cfg%ref_dt
      check_method = cfg%check_method; check_rtol = cfg%check_rtol; wall_min = cfg%wall_min
      ro_steps = cfg%ro_steps; ro_runs = cfg%ro_runs; ro_case = cfg%ro_case
      ro_perturb = cfg%ro_perturb; ro_fit_t_min = cfg%ro_fit_t_min; tao_dt = cfg%tao_dt
      tao_t_end = cfg%tao_t_end; omega_min = cfg%omega_min; omega_max = cfg%omega_max
      n_omega = cfg%n_omega; tao_case = cfg%tao_case; quick = cfg%quick

      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//printable(filename)//"'")
         return
      end if
      read (unit, nml=study, iostat=stat, iomsg=msg)
      close (unit)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'study', msg))
         return
      end if

      call set_cases(filename, case_name, case_q1, case_q2, case_w1, case_w2, case_long_steps, &
                     case_links, case_q, case_w, case_damping, case_support_amplitude, &
                     case_support_frequency, case_support_phase, cfg, error)
      if (allocated(error)) return
      call set_methods(filename, method, h_min, h_max, rtol_min, rtol_max, cfg, error)
      if (allocated(error)) return
      call check_list(filename, 'ro_method', ro_method, error)
      if (allocated(error)) return
      call check_list(filename, 'tao_method', tao_method, error)
      if (allocated(error)) return
      n = count(len_trim(ro_method) > 0)
      if (n == 0) n = size(cfg%ro_methods)   ! ro_dt(i) then sets the default method i's step
      do i = n + 1, max_extra
         if (ro_dt(i) /= 0.0_dp) then
            call fatal_error(error, 'invalid ro_dt('//to_str(i)//'): '//sci(ro_dt(i))// &
                             " in '"//printable(filename)//"', but there is no ro_method(" &
                             //to_str(i)//') (&study: one step per roundoff method, ' &
                             //'ro_method(1..'//to_str(n)//')'//default_ro()//')')
            return
         end if
      end do
      if (count(len_trim(ro_method) > 0) > 0) then
         cfg%ro_methods = ro_method(1:n)
         cfg%ro_dt = merge(ro_dt(1:n), 1.0e-3_dp, ro_dt(1:n) /= 0.0_dp)
      else
         do i = 1, min(size(cfg%ro_dt), max_extra)
            if (ro_dt(i) /= 0.0_dp) cfg%ro_dt(i) = ro_dt(i)
         end do
      end if
      n = count(len_trim(tao_method) > 0)
      if (n > 0) cfg%tao_methods = tao_method(1:n)

      cfg%n_h = n_h; cfg%n_rtol = n_rtol; cfg%atol_ratio = atol_ratio; cfg%t_short = t_short
      cfg%n_check = n_check; cfg%order_case = trim(order_case)
      cfg%drift_case = trim(drift_case); cfg%drift_decades = drift_decades
      cfg%bins_per_decade = bins_per_decade; cfg%decades = decades
      cfg%ref_method = trim(ref_method); cfg%ref_dt = ref_dt
      cfg%check_method = trim(check_method); cfg%check_rtol = check_rtol
      cfg%wall_min = wall_min; cfg%ro_steps = ro_steps; cfg%ro_runs = ro_runs
      cfg%ro_case = trim(ro_case); cfg%ro_perturb = ro_perturb
      cfg%ro_fit_t_min = ro_fit_t_min; cfg%tao_dt = tao_dt; cfg%tao_t_end = tao_t_end
      cfg%omega_min = omega_min; cfg%omega_max = omega_max; cfg%n_omega = n_omega
      cfg%tao_case = trim(tao_case); cfg%quick = quick
   contains
      !> ': the default methods A B' when &study sets no ro_method, else ''.
      function default_ro() result(t)
         character(len=:), allocatable :: t
         integer :: j
         t = ''
         if (count(len_trim(ro_method) > 0) > 0) return
         t = ': the default methods'
         do j = 1, size(cfg%ro_methods)
            t = t//' '//trim(cfg%ro_methods(j))
         end do
      end function default_ro
   end subroutine read_study_config

   !> &pendulum, &output and &model of the study's file (through read_run_config;
   !> the groups the study accepts are checked first).
   subroutine read_study_groups(filename, cfg, error)
      character(len=*), intent(in) :: filename           !! namelist file
      type(study_config_t), intent(inout) :: cfg         !! updated from the file
      type(error_t), allocatable, intent(out) :: error   !! unreadable or invalid
      type(run_config_t) :: rcfg
      call check_groups(filename, [character(len=16) :: 'pendulum', 'output', 'study', &
                                   'model'], error)
      if (allocated(error)) return
      rcfg%m = cfg%m; rcfg%l = cfg%l; rcfg%g = cfg%g; rcfg%list_size(1:2) = cfg%list_size
      rcfg%output = cfg%output
      rcfg%force = cfg%force
      call read_run_config(filename, rcfg, error, extra_groups=[character(len=16) :: 'study'])
      if (allocated(error)) return
      if (rcfg%links /= 2) then
         call fatal_error(error, "invalid links in '"//printable(filename)//"': "// &
                          to_str(rcfg%links)// &
                          ' (the cases of the study carry their links: case_links(i); ' &
                          //'&pendulum gives the lists m, l, one value per link)')
         return
      end if
      cfg%m = rcfg%m; cfg%l = rcfg%l; cfg%g = rcfg%g
      cfg%list_size = rcfg%list_size(1:2)
      if (allocated(rcfg%model_name)) cfg%model_name = rcfg%model_name
      cfg%model_params = rcfg%extra
      cfg%output = rcfg%output
      cfg%force = rcfg%force
   end subroutine read_study_groups

   !> The cases of &study (`case_*` arrays as read; entries not given are `unset`):
   !> a list set in the file replaces the default cases.
   subroutine set_cases(filename, case_name, case_q1, case_q2, case_w1, case_w2, &
                        case_long_steps, case_links, case_q, case_w, case_damping, &
                        case_support_amplitude, case_support_frequency, case_support_phase, &
                        cfg, error)
      character(len=*), intent(in) :: filename           !! namelist file (for messages)
      character(len=*), intent(in) :: case_name(:)       !! names ('' not given)
      real(dp), intent(in) :: case_q1(:), case_q2(:), case_w1(:), case_w2(:)
      real(dp), intent(in) :: case_long_steps(:)         !! 0: the default
      integer, intent(in) :: case_links(:)               !! 0: two
      real(dp), intent(in) :: case_q(:, :), case_w(:, :), case_damping(:, :)
      real(dp), intent(in) :: case_support_amplitude(:, :), case_support_frequency(:), &
                              case_support_phase(:, :)
      type(study_config_t), intent(inout) :: cfg         !! updated
      type(error_t), allocatable, intent(out) :: error   !! invalid
      integer :: i, n
      character(len=:), allocatable :: given
      call check_list(filename, 'case_name', case_name, error)
      if (allocated(error)) return
      n = count(len_trim(case_name) > 0)
      do i = n + 1, size(case_name)   ! a value of a case without a name: never ignored
         given = case_key(i)
         if (len(given) > 0) then
            call fatal_error(error, 'invalid case_name('//to_str(i)//"): '' in '"// &
                             printable(filename)//"', but "//given//' is given ' &
                             //'(&study: name every case, case_name(1..n) without gaps)')
            return
         end if
      end do
      if (n > 0) then
         deallocate (cfg%cases)
         allocate (cfg%cases(n))
         do i = 1, n
            cfg%cases(i)%name = trim(case_name(i))
            call case_values(i, 'case_q', case_q(:, i), case_q1(i), case_q2(i), &
                             cfg%cases(i)%q0)
            if (allocated(error)) return
            call case_values(i, 'case_w', case_w(:, i), case_w1(i), case_w2(i), &
                             cfg%cases(i)%w0)
            if (allocated(error)) return
            cfg%cases(i)%long_steps = merge(case_long_steps(i), 1.0e6_dp, &
                                            case_long_steps(i) /= 0.0_dp)
            call case_values(i, 'case_damping', case_damping(:, i), unset, unset, &
                             cfg%cases(i)%damping, none_given=.true.)
            if (allocated(error)) return
            cfg%cases(i)%support_amplitude = case_support_amplitude(:, i)
            cfg%cases(i)%support_frequency = case_support_frequency(i)
            cfg%cases(i)%support_phase = case_support_phase(:, i)
         end do
      end if
   contains
      !> A key of case i given (its value differs from the not-given mark), the first
      !> in the order case_q1, case_q2, ... of the namelist, e.g. 'case_q1(2)'; or ''.
      function case_key(i) result(key)
         integer, intent(in) :: i
         character(len=:), allocatable :: key
         character(len=:), allocatable :: a, b
         a = '('//to_str(i)//')'      ! a value per case
         b = '(:, '//to_str(i)//')'   ! a list per case
         key = ''
         if (any(case_support_phase(:, i) /= 0.0_dp)) key = 'case_support_phase'//b
         if (case_support_frequency(i) /= 0.0_dp) key = 'case_support_frequency'//a
         if (any(case_support_amplitude(:, i) /= 0.0_dp)) key = 'case_support_amplitude'//b
         if (any(case_damping(:, i) /= unset)) key = 'case_damping'//b
         if (any(case_w(:, i) /= unset)) key = 'case_w'//b
         if (any(case_q(:, i) /= unset)) key = 'case_q'//b
         if (case_links(i) /= 0) key = 'case_links'//a
         if (case_long_steps(i) /= 0.0_dp) key = 'case_long_steps'//a
         if (case_w2(i) /= unset) key = 'case_w2'//a
         if (case_w1(i) /= unset) key = 'case_w1'//a
         if (case_q2(i) /= unset) key = 'case_q2'//a
         if (case_q1(i) /= unset) key = 'case_q1'//a
      end function case_key

      !> The initial values of case i (N = case_links(i) links, 2 when not given): the
      !> list case_q(1:N, i) (`field` 'case_q' or 'case_w'), or for two links
      !> case_q1(i), case_q2(i); values not given are 0 (with `none_given`: `values`
      !> is left unallocated).
      subroutine case_values(i, field, list, v1, v2, values, none_given)
         integer, intent(in) :: i
         character(len=*), intent(in) :: field
         real(dp), intent(in) :: list(:), v1, v2
         real(dp), allocatable, intent(out) :: values(:)
         logical, intent(in), optional :: none_given
         integer :: links, k
         character(len=:), allocatable :: where
         links = merge(case_links(i), 2, case_links(i) /= 0)
         where = "in '"//printable(filename)//"' (case '"//printable(trim(case_name(i)))//"')"
         if (links < 1 .or. links > max_dof) then
            call fatal_error(error, 'invalid case_links('//to_str(i)//'): '//to_str(links)// &
                             ' is outside [1, '//to_str(max_dof)//'] '//where)
            return
         end if
         k = 0
         do while (k < size(list))
            if (list(k + 1) == unset) exit
            k = k + 1
         end do
         if (any(list(k + 1:) /= unset)) then   ! a value after a gap: never ignored
            call fatal_error(error, 'invalid '//field//'(:, '//to_str(i)//'): values '// &
                             'must be given for links 1 to '//to_str(links)// &
                             ' without gaps '//where)
            return
         end if
         if (k /= 0 .and. k /= links) then
            call fatal_error(error, 'invalid '//field//'(:, '//to_str(i)//'): '//to_str(k)// &
                             ' values for '//to_str(links)//' links (one per link) '//where)
            return
         end if
         if (links /= 2 .and. (v1 /= unset .or. v2 /= unset)) then
            call fatal_error(error, 'invalid '//field//'1, '//field//'2('//to_str(i)// &
                             '): only for two links; give '//field//'(1:'//to_str(links)// &
                             ', '//to_str(i)//') '//where)
            return
         end if
         if (present(none_given) .and. k == 0) return
         allocate (values(links))
         values = 0.0_dp
         if (k == links) then
            values = list(:links)
         else if (links == 2) then
            if (v1 /= unset) values(1) = v1
            if (v2 /= unset) values(2) = v2
         end if
      end subroutine case_values
   end subroutine set_cases

   !> Refuse a list of names `field` of &study set with gaps (names 1..n, the rest
   !> blank).
   subroutine check_list(filename, field, names, error)
      character(len=*), intent(in) :: filename           !! namelist file (for messages)
      character(len=*), intent(in) :: field              !! the list's key
      character(len=*), intent(in) :: names(:)           !! as read ('' not given)
      type(error_t), allocatable, intent(out) :: error   !! a gap
      integer :: n, k
      n = count(len_trim(names) > 0)
      do k = 1, n
         if (len_trim(names(k)) == 0) then
            call fatal_error(error, 'invalid '//field//'('//to_str(k)//"): '' in '"// &
                             printable(filename)//"', but later entries are given (&study: " &
                             //field//'(1..n) without gaps)')
            return
         end if
      end do
   end subroutine check_list

   !> The methods of &study (`method(i)` and their ranges as read): a list set in
   !> the file replaces the default list; a range left at 0 takes the method's default.
   subroutine set_methods(filename, method, h_min, h_max, rtol_min, rtol_max, cfg, error)
      character(len=*), intent(in) :: filename           !! namelist file (for messages)
      character(len=*), intent(in) :: method(:)          !! names ('' not given)
      real(dp), intent(in) :: h_min(:), h_max(:), rtol_min(:), rtol_max(:)  !! 0: default
      type(study_config_t), intent(inout) :: cfg         !! updated
      type(error_t), allocatable, intent(out) :: error   !! invalid
      integer :: i, n
      character(len=:), allocatable :: key
      call check_list(filename, 'method', method, error)
      if (allocated(error)) return
      n = count(len_trim(method) > 0)
      do i = n + 1, size(method)   ! a range without its method: never ignored
         key = ''
         if (rtol_max(i) /= 0.0_dp) key = 'rtol_max'   ! (the first given wins)
         if (rtol_min(i) /= 0.0_dp) key = 'rtol_min'
         if (h_max(i) /= 0.0_dp) key = 'h_max'
         if (h_min(i) /= 0.0_dp) key = 'h_min'
         if (len(key) > 0) then
            call fatal_error(error, 'invalid method('//to_str(i)//"): '' in '"// &
                             printable(filename)//"', but "//key//'('//to_str(i)// &
                             ') is given (&study: name every method, method(1..n) ' &
                             //'without gaps)')
            return
         end if
      end do
      if (n > 0) then
         deallocate (cfg%methods)
         allocate (cfg%methods(n))
         do i = 1, n
            cfg%methods(i)%name = trim(method(i))
            call default_ranges(trim(method(i)), cfg%methods(i)%h_min, cfg%methods(i)%h_max, &
                                cfg%methods(i)%rtol_min, cfg%methods(i)%rtol_max)
            if (h_min(i) /= 0.0_dp) cfg%methods(i)%h_min = h_min(i)
            if (h_max(i) /= 0.0_dp) cfg%methods(i)%h_max = h_max(i)
            if (rtol_min(i) /= 0.0_dp) cfg%methods(i)%rtol_min = rtol_min(i)
            if (rtol_max(i) /= 0.0_dp) cfg%methods(i)%rtol_max = rtol_max(i)
         end do
      end if
   end subroutine set_methods

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
   end function study_namelist

   ! --------------------------------------------------------------- validation

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
   end subroutine check_cases

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
      else if (.not. (finite_positive(cfg%check_rtol) .and. cfg%check_rtol < 1.0_dp)) then
         call fatal_error(error, 'invalid check_rtol: must be in (0, 1)')
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

   !> A method that needs a Hamiltonian model refuses a damped or driven case.
   subroutine check_accepts(cfg, field, method, error)
      type(study_config_t), intent(in) :: cfg           !! configuration
      character(len=*), intent(in) :: field             !! e.g. 'method(3)'
      class(integrator_t), intent(in) :: method         !! the method
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: ic
      if (.not. method%needs_hamiltonian()) return
      do ic = 1, size(cfg%cases)
         if (balance_case(cfg, ic)) then
            call fatal_error(error, 'invalid '//field//": '"//method%name()//"' needs a " &
                             //"Hamiltonian model; case '"//cfg%cases(ic)%name// &
                             "' is damped or driven (use "//field_method_names()//')')
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
      if (n > max_dof - 1) then
         call fatal_error(error, 'invalid case_links('//to_str(ic)//'): '//to_str(n)// &
                          ' with damping or a moving support is outside [1, '// &
                          to_str(max_dof - 1)//'] (the energy balance takes two state ' &
                          //'components)')
         return
      end if
      call new_model(case_spec(cfg, ic), model, error)
      if (allocated(error)) error%message = error%message//" (case '"// &
                                            cfg%cases(ic)%name//"': case_damping, " &
                                            //'case_support_*)'
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
      if (any(cfg%list_size /= 0) .or. any(cfg%m(:2) /= 1.0_dp) .or. &
          any(cfg%l(:2) /= 1.0_dp) .or. cfg%g /= 9.8_dp) then
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

   ! ------------------------------------------------------------------ helpers

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
end module dpend_study_config
