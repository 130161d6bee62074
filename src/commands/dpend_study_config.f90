!> The command line of `dpend study`: its flags, the namelist group &study (plus
!> &model, &pendulum and &output) and its help, read into the study's settings
!> (dpend_study_settings, which describes the keys).
!>
!> Lists in &study are indexed arrays (`method(1) = 'rk4'`, `h_min(1) = 1e-3`).
!> A list that the file does not set keeps its default; a list that it sets
!> replaces the default list entirely, and a range left at 0 for a listed
!> method takes that method's default range.
!>
!> The entry point of the command, `study_command`, reads the command line here and
!> hands the settings to the run of `dpend_study_command`.
module dpend_study_config
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: max_dof
   use dpend_cli, only: arg_t, next_option, parse_int, option_outcome, to_str, &
      scan_help_config, printable
   use dpend_method_registry, only: method_names
   use dpend_limits, only: sci
   use dpend_run_settings, only: run_config_t, unused_setting
   use dpend_model_factory, only: default_model
   use dpend_namelist, only: read_run_config, check_groups, namelist_error
   use dpend_run_flags, only: apply_run_flag
   use dpend_study_settings, only: read_case_torques, check_case_torques
   use dpend_study_settings, only: study_config_t, study_defaults, validate_study_config, &
      apply_quick, study_times_in_seconds, case_index, default_ranges, max_cases, max_methods, max_extra, &
      case_list, split_list, unset
   use dpend_study_command, only: run_study_command
   use dpend_command_common, only: take_quiet, with_quiet, summary_quiet, refusal_line, &
      error_line
   implicit none
   private
   public :: study_command
   public :: parse_study, read_study_config, study_help

contains

   !> The entry point of `dpend study [options]` (app/main.f90): parse → settings →
   !> the run of `run_study_command` (engine, file, summary, figures). A refusal or a
   !> failed run comes back as `error`, its message the one line 'dpend study: ...'.
   subroutine study_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `study`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(study_config_t) :: cfg
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_study(rest, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'study')
      else if (help) then
         write (output_unit, '(a)') with_quiet(study_help(), summary_quiet)
      else
         call run_study_command(cfg, quiet, error)
         if (allocated(error)) call error_line(error, 'study')
      end if
   end subroutine study_command

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
          '  --time-unit U     unit of the times given (t_short, ref_dt, h_min, h_max,'//nl// &
          '                    ro_dt, ro_fit_t_min, tao_dt, tao_t_end): s or natural'//nl// &
          '                    (sqrt(l1/g) of the first case, sqrt(l0/g) for the elastic'//nl// &
          '                    pendulum); default s. The report and the file are in s'//nl// &
          '                    and say what was given'//nl// &
          '  -h, --help        this text'//nl//nl// &
          'Relative energy error: |H(t) - H(0)| / E_s with E_s = |H(0)|, or, when'//nl// &
          'H(0) ~ 0 (both links released horizontally), the potential energy with both'//nl// &
          'links upright, (m1/2 + m2) g l1 + (m2/2) g l2. A damped or driven case'//nl// &
          '(case_damping, case_support_*, case_torque_file in &study: a CSV of t [s],'//nl// &
          'tau1 .. tauN [N m] covering every run of the case, docs/robot.md) measures'//nl// &
          'the energy balance |E(t) - E(0) + W_friction - W_support - W_torque| / E_s'//nl// &
          'instead (methods that need a Hamiltonian refuse such a case; no drift,'//nl// &
          'roundoff or Tao runs on it).'
   end function study_help

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
         case ('--time-unit')
            call apply_run_flag(rcfg, name, value, matched, error)
            cfg%time_unit = rcfg%time_unit
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
      call read_case_torques(cfg, error)   ! the cases' torque files, once
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      if (trim(cfg%time_unit) == 'natural') then   ! its times in seconds, checked again
         call study_times_in_seconds(cfg)
         call validate_study_config(cfg, error)
         if (allocated(error)) return
      end if
      call apply_quick(cfg)
      call check_case_torques(cfg, error)   ! over the runs, in seconds, after --quick
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
      character(len=1024) :: case_torque_file(max_cases)
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
         case_support_frequency, case_support_phase, case_torque_file, &
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
      case_support_phase = 0; case_torque_file = ''
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
                     case_support_frequency, case_support_phase, case_torque_file, cfg, error)
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
                                   'model', 'integration'], error)
      if (allocated(error)) return
      call read_time_unit(error)
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
      call refuse_unused(error)
      if (allocated(error)) return
      cfg%m = rcfg%m; cfg%l = rcfg%l; cfg%g = rcfg%g
      cfg%list_size = rcfg%list_size(1:2)
      if (allocated(rcfg%model_name)) cfg%model_name = rcfg%model_name
      cfg%model_params = rcfg%extra
      cfg%output = rcfg%output
      cfg%force = rcfg%force
      cfg%time_unit = rcfg%time_unit
   contains
      !> &integration holds only time_unit for the study (its steps and horizons are
      !> in &study): any other key of it is refused by this namelist's read.
      subroutine read_time_unit(error)
         type(error_t), allocatable, intent(out) :: error
         character(len=16) :: time_unit
         character(len=512) :: msg
         integer :: unit, stat
         namelist /integration/ time_unit
         time_unit = ''
         open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
         if (stat /= 0) then
            call fatal_error(error, "invalid --config: cannot read '"//printable(filename)// &
                             "'")
            return
         end if
         read (unit, nml=integration, iostat=stat, iomsg=msg)
         close (unit)
         if (stat > 0) call fatal_error(error, namelist_error(filename, 'integration', msg)// &
                                        ' (dpend study reads only time_unit there; its ' &
                                        //'steps and horizons are keys of &study)')
      end subroutine read_time_unit
      !> The settings of a run the study has no use for are refused, never dropped:
      !> the links' body (its cases are uniform rods, or the &model's), the damping and
      !> the support's motion (each case carries its own: case_damping,
      !> case_support_*), and a named parameter of the pendulum other than m, l, g.
      subroutine refuse_unused(error)
         type(error_t), allocatable, intent(out) :: error
         character(len=*), parameter :: per_case(4) = [character(len=17) :: 'damping', &
            'support_amplitude', 'support_frequency', 'support_phase']
         character(len=:), allocatable :: pre, unused
         integer :: k
         pre = "invalid --config '"//printable(filename)//"': "
         if (allocated(rcfg%body)) then
            call fatal_error(error, pre//'body is not a setting of dpend study (its cases ' &
                             //'are the uniform rods of &pendulum m, l, g, or the model ' &
                             //'of &model)')
            return
         end if
         do k = 1, size(per_case)
            if (.not. allocated(rcfg%given)) exit
            if (index(rcfg%given, ' '//trim(per_case(k))//' ') == 0) cycle
            call fatal_error(error, pre//trim(per_case(k))//' is not a setting of &pendulum ' &
                             //'in dpend study: each case carries its own (case_'// &
                             trim(per_case(k))//'(i) in &study)')
            return
         end do
         unused = unused_setting(rcfg)
         if (len(unused) > 0) then
            call fatal_error(error, pre//unused//' is not a parameter of ' &
                             //'model '//rcfg%model_name//' (dpend models lists its ' &
                             //'parameters)')
            return
         end if
         if (.not. allocated(rcfg%extra%items)) return
         if (allocated(rcfg%model_name)) then
            if (rcfg%model_name /= default_model) return
         end if
         if (size(rcfg%extra%items) > 0) then
            call fatal_error(error, pre//rcfg%extra%items(1)%name//' is not a setting of ' &
                             //"dpend study's pendulum (its cases are uniform rods of m, l, g)")
         end if
      end subroutine refuse_unused
   end subroutine read_study_groups

   !> The cases of &study (`case_*` arrays as read; entries not given are `unset`):
   !> a list set in the file replaces the default cases.
   subroutine set_cases(filename, case_name, case_q1, case_q2, case_w1, case_w2, &
                        case_long_steps, case_links, case_q, case_w, case_damping, &
                        case_support_amplitude, case_support_frequency, case_support_phase, &
                        case_torque_file, cfg, error)
      character(len=*), intent(in) :: filename           !! namelist file (for messages)
      character(len=*), intent(in) :: case_name(:)       !! names ('' not given)
      real(dp), intent(in) :: case_q1(:), case_q2(:), case_w1(:), case_w2(:)
      real(dp), intent(in) :: case_long_steps(:)         !! 0: the default
      integer, intent(in) :: case_links(:)               !! 0: two
      real(dp), intent(in) :: case_q(:, :), case_w(:, :), case_damping(:, :)
      real(dp), intent(in) :: case_support_amplitude(:, :), case_support_frequency(:), &
                              case_support_phase(:, :)
      character(len=*), intent(in) :: case_torque_file(:)  !! '' none
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
            cfg%cases(i)%torque_file = trim(case_torque_file(i))
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
         if (len_trim(case_torque_file(i)) > 0) key = 'case_torque_file'//a
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

end module dpend_study_config
