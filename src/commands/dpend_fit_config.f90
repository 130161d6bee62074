!> The command line and the data of `dpend fit`: the settings record `fit_config_t`
!> and its defaults, the parsing of the arguments, the reading of the measured series
!> (`dpend_csv`) and its checks against the model, the work limit, the `--help` text,
!> and the estimation problem (`fit_problem`) the command runs (`dpend_fit_command`).
module dpend_fit_config
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, take_data_file, next_option, option_outcome, scan_help_config, parse_real, &
                        parse_int, real_str, to_str, printable
   use dpend_run_settings, only: run_config_t, validate_run_config, time_unit_option_help
   use dpend_namelist, only: read_run_config
   use dpend_run_flags, only: apply_run_flag, is_model_flag, take_torque_file
   use dpend_model, only: max_dof
   use dpend_csv, only: series_t, read_series
   use dpend_estimate, only: fit_problem_t, fit_work_t, estimate_fit_work, set_fitted, n_fitted
   use dpend_model_factory, only: default_model, body_list
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_output, only: check_output_path, register_input
   use dpend_limits, only: check_range, sci, max_time, max_fit_work
   use dpend_resources, only: check_memory
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: fit_config_t, parse_fit, fit_help, fit_problem, state_names, coordinate_units, &
      joined_names

   !> Most starting points of the first stage (--starts).
   integer, parameter :: max_starts = 1000
   !> Largest horizon tolerance for positions [m].
   real(dp), parameter :: max_position_tol = 1e6_dp
   !> The default horizon tolerance of positions as a fraction of the pendulum's total
   !> length (the angles' default 0.1 rad moves a tip by about 0.1 of its distance
   !> from the pin).
   real(dp), parameter :: default_length_fraction = 0.1_dp

   !> Everything `dpend fit` needs.
   type :: fit_config_t
      type(run_config_t) :: run                  !! model, method, tolerances, output
      character(len=:), allocatable :: input     !! the CSV file
      type(series_t) :: series                   !! its samples
      logical :: fit_damping = .false.           !! estimate c_i too
      real(dp) :: fit_window = huge(1.0_dp)      !! fit t <= T [s] (default: all)
      logical :: window_given = .false.
      real(dp) :: tolerance = 0.1_dp             !! horizon tolerance [rad or m]
      logical :: tolerance_given = .false.       !! --horizon-tolerance given
      !> how the tolerance was chosen, for the report ('given', or the default's rule)
      character(len=:), allocatable :: tolerance_rule
      integer :: starts = 1                      !! first-stage starting points
      !> model parameters fitted by name (--fit-parameters; --fit-damping: damping)
      character(len=32), allocatable :: fit_names(:)
      !> a model other than the pendulum: the CSV columns are its coordinates
      logical :: model_coords = .false.
      !> the noise of the observations given (--sigma) [rad or m]; 0: estimated from
      !> the data (`noise_estimate`)
      real(dp) :: sigma = 0.0_dp
   end type fit_config_t

   !> The run flags that make sense for a fit (the initial state comes from the data).
   character(len=20), parameter :: run_flags(21) = [character(len=20) :: '--links', '--m', &
      '--l', '--g', '--m1', '--m2', '--l1', '--l2', '--damping', '--support-amplitude', &
      '--support-frequency', '--support-phase', '--method', '--dt', '--rtol', '--atol', &
      '--max-steps', '--output', '-o', '--body', '--time-unit']

contains

   !> Defaults: dop853 at rtol 1e-10, atol 1e-12; output fit.h5.
   function fit_defaults() result(fc)
      type(fit_config_t) :: fc
      fc%run%method = 'dop853'
      fc%run%rtol = 1e-10_dp
      fc%run%atol = 1e-12_dp
      fc%run%dt = 1e-3_dp
      fc%run%output = 'fit.h5'
      fc%input = ''
      allocate (fc%fit_names(0))
   end function fit_defaults

   !> Help text of `dpend fit`.
   function fit_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(fit_config_t) :: fc
      fc = fit_defaults()
      s = 'usage: dpend fit DATA.csv [options]'//nl//nl// &
          'Estimate the initial state (q, qdot at the first sample time) of the pendulum or'//nl// &
          'chain, and with --fit-damping the joint damping c_i, from measured angles, by'//nl// &
          'Levenberg-Marquardt with the sensitivities of the variational equations. Prints'// &
          nl//'the estimates with standard errors and 95 % intervals, the correlation matrix,'// &
          nl//'the RMS residual and the prediction horizon; writes them and the residual'//nl// &
          'series to HDF5 (group /fit; figures: scripts/plot_fit.sh).'//nl//nl// &
          'DATA.csv: a header line, then one row per sample (README, data/fit_example.csv):'// &
          nl//'  t,theta1,theta2[,...]   t in s; angles in rad from the hanging position'//nl// &
          '                          (counter-clockwise; as --theta1), or q1,q2,... from'//nl// &
          "                          the horizontal x axis (as dpend export --csv writes);"// &
          nl//'                          units in brackets allowed (t [s], theta1 [rad],'// &
          nl//'                          theta1 [deg]: converted by pi/180);'//nl// &
          '                          other columns are ignored, lines starting with # and'// &
          nl//'                          blank lines skipped. N = the number of angle columns.'// &
          nl//'  t,x1,y1[,x2,y2,...]     or (no angle columns) the positions of the far ends of'// &
          nl//'                          the links (joint i+1, the tip for i = N), origin at'// &
          nl//'                          the pin, y up; units [m], [cm], [mm] (none: m);'// &
          nl//'                          residuals and --horizon-tolerance are then in m.'// &
          nl//'                          Some points may be missing (t,x2,y2: the tip'// &
          nl//'                          only; N = the last point): each missing point'// &
          nl//'                          between two known ones, placed by the lengths and'// &
          nl//'                          the dynamics (both mirror places tried).'// &
          nl//'  t,r,phi                 with --model elastic: the model''s coordinates'// &
          nl//'                          (dpend models), r in m, phi in rad from the'// &
          nl//'                          horizontal x axis (units [m], [rad], [deg], none).'// &
          nl//'  Separated by , or ; or tabs (detected from the header), a UTF-8 BOM and'// &
          nl//'  quoted names and fields allowed (as spreadsheets write them).'// &
          nl//'  Refused with the line number: missing columns, a wrong number of fields,'//nl// &
          '  numbers that do not parse, NaN or Inf, times that do not increase, fewer'//nl// &
          '  samples in the fit window than the parameters need; a fit whose estimated'//nl// &
          '  work exceeds '//sci(max_fit_work)//' integration steps (sensitivities counted).' &
          //nl//nl// &
          'fit options:'//nl// &
          '  --fit-damping     estimate c_1..c_N too (N m s; the --damping values are the'// &
          nl//'                    first guess, default 0)'//nl// &
          '  --fit-param NAMES fit these model parameters too (also --fit-parameters),'// &
          nl//'                    comma-separated, any the model describes (dpend'// &
          nl//'                    models): m, l, g, damping, support_amplitude, ... (all'// &
          nl//'                    components) or one component: m2, l1, c2 (damping 2);'// &
          nl//'                    the elastic pendulum: k, l0, m, g. First guess: the'// &
          nl//'                    values given (--m2, --l2, --k). A set the data cannot'// &
          nl//'                    determine is refused naming the combination (angles'// &
          nl//'                    never fix the absolute mass scale: fit m2, not m1,m2)'// &
          nl//'  --sigma S         the noise of the observations (rad or m): a fit whose RMS'// &
          nl//'                    residual exceeds 3 S warns and names the parameters'// &
          nl//'                    that may be wrong; default: estimated from the data'//nl// &
          '  --fit-window T    fit only the samples with t <= T (in --time-unit); the rest'// &
          nl//'                    measures the prediction horizon; default: all samples'//nl// &
          time_unit_option_help('s')//nl// &
          '                    (the data keep the unit of their t column; the natural'//nl// &
          '                    unit is that of the configured model, not the fitted one)'//nl// &
          '  --torque-file F   apply joint torques (a CSV of t [s], tau1 .. tauN [N m],'// &
          nl//'                    linear between samples, covering the data''s times; the'// &
          nl//'                    data file itself when it has tau columns): a fit of the'// &
          nl//'                    motion a robot''s measured torques drove'//nl// &
          '  --horizon-tolerance R  the horizon ends at the first sample after T where an'// &
          nl//'                    angle differs from the model by more than R (rad, in'//nl// &
          '                    (0, pi]; positions: m, in (0, 1e6]); default '// &
          real_str(fc%tolerance)//' rad,'//nl// &
          '                    positions: '//real_str(default_length_fraction)// &
          ' of the total length (the sum of l_i)'//nl// &
          '  --starts K        first-stage starting points (1 to '//to_str(max_starts)// &
          '): the guess and'//nl// &
          '                    K-1 others spread over the rates (sparse samples of a chaotic'// &
          nl//'                    motion); default '//to_str(fc%starts)//nl// &
          '  --output FILE     HDF5 file to write; default '//fc%run%output//nl// &
          '  --force           overwrite an existing output file'//nl//nl// &
          'model and integration (the initial state comes from the data; the links from'// &
          nl//'its angle columns; --method: a method on (q, qdot): rk4, dopri5, dop853):'// &
          nl//'  --config, --links, --m, --l, --g, --m1, --m2, --l1, --l2, --damping,'//nl// &
          '  --coulomb, --coulomb-speed (Coulomb joint friction), --rotor-inertia,'//nl// &
          '  --gear-ratio (motors),'//nl// &
          '  --support-amplitude, --support-frequency, --support-phase,'//nl// &
          '  --body '//body_list('|')//', --com LIST, --inertia LIST (links of any mass distribution),'// &
          nl// &
          '  --model and its parameters (--model elastic --m --k --l0), --method (default '// &
          fc%run%method//'),'//nl//'  --dt, --rtol (default '//real_str(fc%run%rtol)// &
          '), --atol (default '//real_str(fc%run%atol)//'), --max-steps'//nl// &
          '  as for dpend simulate (dpend simulate --help).'//nl// &
          '  -h, --help        this text'
   end function fit_help

   !> Build the configuration and read the data; every refusal is one line.
   subroutine parse_fit(args, fc, help, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'fit'
      type(fit_config_t), intent(out) :: fc             !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: config
      logical :: links_given
      fc = fit_defaults()
      help = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_run_config(config, fc%run, error)
         if (allocated(error)) return
      end if
      call parse_fit_args(args, fc, links_given, error)
      if (allocated(error)) return
      if (len(fc%input) == 0) then
         call fatal_error(error, 'no data file given (usage: dpend fit DATA.csv [options]; ' &
                          //'dpend fit --help)')
         return
      end if
      if (fc%starts < 1 .or. fc%starts > max_starts) then
         call fatal_error(error, 'invalid starts: '//to_str(fc%starts)//' is outside [1, ' &
                          //to_str(max_starts)//'] [--starts]')
         return
      end if
      if (fc%fit_damping .and. .not. any(fc%fit_names == 'damping')) &
         fc%fit_names = [character(len=32) :: fc%fit_names, 'damping']
      fc%fit_damping = any(fc%fit_names == 'damping')
      call register_input(fc%input)   ! the output never replaces the data file
      call check_output_path(fc%run%output, fc%run%force, error)
      if (allocated(error)) return
      if (allocated(fc%run%model_name)) fc%model_coords = fc%run%model_name /= default_model
      if (fc%model_coords) then
         call read_model_series(fc, error)
      else
         call read_series(fc%input, fc%series, error)
      end if
      if (allocated(error)) return
      call check_fit_data(fc, links_given, error)
      if (allocated(error)) return
      call check_work(fc, error)
   end subroutine parse_fit

   !> The arguments: the data file, the fit's options and the run's flags.
   subroutine parse_fit_args(args, fc, links_given, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'fit'
      type(fit_config_t), intent(inout) :: fc           !! the configuration
      logical, intent(out) :: links_given               !! --links was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value
      logical :: matched, missing
      integer :: i
      links_given = .false.
      i = 1
      do while (i <= size(args))
         if (args(i)%s == '--force') then
            fc%run%force = .true.
            i = i + 1
            cycle
         end if
         if (args(i)%s == '--fit-damping') then
            fc%fit_damping = .true.
            i = i + 1
            cycle
         end if
         if (take_data_file(args(i)%s, fc%input, 'fit', error)) then
            if (allocated(error)) return
            i = i + 1
            cycle
         end if
         call next_option(args, i, name, value, .true., error, missing)
         if (name == '--config') cycle
         matched = .true.
         select case (name)
         case ('--fit-window')
            call parse_real(value, name, fc%fit_window, error)
            fc%window_given = .true.
         case ('--horizon-tolerance')
            call parse_real(value, name, fc%tolerance, error)
            fc%tolerance_given = .true.
         case ('--starts')
            call parse_int(value, name, fc%starts, error)
         case ('--torque-file')
            if (.not. (missing .or. allocated(error))) call take_torque_file(fc%run, value, &
                                                                             error)
         case ('--fit-parameters', '--fit-param')
            call parse_names(value, fc%fit_names, error)
         case ('--sigma')
            call parse_real(value, name, fc%sigma, error)
            if (.not. allocated(error)) call check_range('sigma', fc%sigma, 1e-12_dp, &
                                                         max_position_tol, '', error, &
                                                         'the noise of the observations')
         case default
            if (any(run_flags == name) .or. is_model_flag(name)) then
               if (name == '--links') links_given = .true.
               call apply_run_flag(fc%run, name, value, matched, error)
            else
               matched = .false.
            end if
         end select
         call option_outcome('fit', name, matched, missing, &
                             [character(len=16) :: '--force', '--fit-damping'], error, fit_help())
         if (allocated(error)) return
      end do
   end subroutine parse_fit_args

   !> The configuration against the data read: the tolerance's units, the links, the
   !> model, the method, the fit window and the samples it holds.
   subroutine check_fit_data(fc, links_given, error)
      type(fit_config_t), intent(inout) :: fc           !! configuration; model built
      logical, intent(in) :: links_given                !! --links was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      class(integrator_t), allocatable :: integ
      type(fit_problem_t) :: prob
      integer :: np, k_fit
      real(dp) :: x
      associate (s => fc%series)
         if (s%positions) then
            if (.not. (fc%tolerance > 0.0_dp .and. fc%tolerance <= max_position_tol)) then
               call fatal_error(error, 'invalid horizon-tolerance: '// &
                                real_str(fc%tolerance)//' m (the data are positions) is ' &
                                //'outside (0, '//real_str(max_position_tol)// &
                                '] [--horizon-tolerance]')
               return
            end if
         else if (.not. (fc%tolerance > 0.0_dp .and. fc%tolerance <= pi)) then
            call fatal_error(error, 'invalid horizon-tolerance: '//real_str(fc%tolerance)// &
                             ' rad is outside (0, pi] [--horizon-tolerance]')
            return
         end if
         if (links_given .and. s%positions .and. fc%run%links > s%n) then
            call fatal_error(error, 'invalid links: '//to_str(fc%run%links)//" given, the " &
                             //"data file '"//printable(fc%input)//"' ends at point "// &
                             to_str(s%n)//': the angles of links '//to_str(s%n + 1)// &
                             ' to '//to_str(fc%run%links)//' are not observed (give x'// &
                             to_str(fc%run%links)//',y'//to_str(fc%run%links)// &
                             ', the tip) [--links]')
            return
         else if (links_given .and. fc%run%links /= s%n) then
            call fatal_error(error, 'invalid links: '//to_str(fc%run%links)//" given, the " &
                             //"data file '"//printable(fc%input)//"' has "//to_str(s%n)// &
                             trim(merge(' angle columns', ' points       ', .not. s%positions)) &
                             //' (N is the number of '//trim(merge('angle columns  ', &
                             'the last point ', .not. s%positions))//') [--links]')
            return
         end if
         if (s%positions) then
            call check_observed_points(s, error)
            if (allocated(error)) return
         end if
         fc%run%torque_span = [s%t(1), s%t(s%k)]   ! the torques must cover the data
         if (.not. fc%model_coords) then
            fc%run%links = s%n
            call validate_run_config(fc%run, error)
            if (allocated(error)) return
            call default_tolerance(fc)
            call check_body_fit(fc, error)
            if (allocated(error)) return
         end if
         call new_integrator(fc%run%method, integ, error)
         if (allocated(error)) return
         if (integ%canonical()) then
            call fatal_error(error, 'invalid method: '//fc%run%method//' integrates (q, p); ' &
                             //'dpend fit needs a method on (q, qdot): rk4, dopri5, dop853 ' &
                             //'[--method]')
            return
         end if
         if (fc%fit_damping .and. s%n > max_dof/2) then
            call fatal_error(error, 'invalid links: '//to_str(s%n)//' with --fit-damping is ' &
                             //'outside [1, '//to_str(max_dof/2)//'] (the damping takes N ' &
                             //'state components of the sensitivity system)')
            return
         end if
         if (fc%window_given) then
            fc%fit_window = fc%run%seconds(fc%fit_window)   ! given in the run's unit
            x = fc%fit_window
            call check_range('fit-window', x, -max_time, max_time, 's', error, &
                             'times are at most 1e9 s')
            if (allocated(error)) return
            if (.not. (ieee_is_finite(x) .and. x >= s%t(1))) then
               call fatal_error(error, 'invalid fit-window: '//real_str(x)//' s is before ' &
                                //'the first sample (t = '//real_str(s%t(1))// &
                                ' s) [--fit-window]')
               return
            end if
         end if
         call fit_problem(fc, prob, error)
         if (allocated(error)) return
         np = 2*s%n + n_fitted(prob)
         k_fit = count(s%t <= fc%fit_window)
         if (s%n_obs*k_fit <= np) then
            call fatal_error(error, "invalid data file '"//printable(fc%input)//"': "// &
                             to_str(k_fit)// &
                             ' samples in the fit window give '//to_str(s%n_obs*k_fit)// &
                             ' residuals for '//to_str(np)//' parameters: at least '// &
                             to_str(np/s%n_obs + 1)//' samples are needed (lines '// &
                             to_str(s%line(1))//' to '//to_str(s%line(k_fit))//')')
            return
         end if
      end associate
   end subroutine check_fit_data

   !> Positions of some points only: each point not observed must lie between two
   !> known ones (the pin or observed points), which place it up to its mirror image;
   !> two missing in a row leave a link pair's angles undetermined by the geometry and
   !> are refused, naming the points to add.
   subroutine check_observed_points(s, error)
      type(series_t), intent(in) :: s                   !! the series (positions)
      type(error_t), allocatable, intent(out) :: error  !! undetermined
      integer :: i
      do i = 1, s%n - 1
         if (any(s%points == i) .or. any(s%points == i + 1)) cycle
         call fatal_error(error, "invalid data file: points "//to_str(i)//' and '// &
                          to_str(i + 1)//' are both missing (a missing point must lie ' &
                          //'between two known ones, the pin or observed points: give x'// &
                          to_str(i)//',y'//to_str(i)//' or x'//to_str(i + 1)//',y'// &
                          to_str(i + 1)//')')
         return
      end do
   end subroutine check_observed_points

   !> The horizon tolerance when none is given: for positions a fraction of the
   !> pendulum's total length (its configured lengths), for angles 0.1 rad; the rule in
   !> `tolerance_rule` for the report.
   subroutine default_tolerance(fc)
      type(fit_config_t), intent(inout) :: fc  !! the configuration, links set
      real(dp) :: total
      if (fc%tolerance_given) then
         fc%tolerance_rule = 'given'
      else if (fc%series%positions) then
         total = sum(fc%run%l(1:fc%run%links))
         fc%tolerance = default_length_fraction*total
         fc%tolerance_rule = real_str(default_length_fraction)//' of the total length '// &
                             real_str(total)//' m'
      else
         fc%tolerance_rule = 'the default for angles'
      end if
   end subroutine default_tolerance

   !> A body named by --body fixes every link's com and inertia ('point': com_i = l_i,
   !> inertia_i = 0; 'rod': com_i = l_i/2, inertia_i = m_i l_i^2/12): fitting one of them
   !> would fit a model the body contradicts (simulate refuses the same pair).
   subroutine check_body_fit(fc, error)
      type(fit_config_t), intent(in) :: fc              !! configuration
      type(error_t), allocatable, intent(out) :: error  !! a fixed quantity fitted
      character(len=:), allocatable :: name, sets
      integer :: i
      if (.not. allocated(fc%run%body)) return
      if (fc%run%body == 'rod') then
         sets = 'com_i = l_i/2 and inertia_i = m_i l_i^2/12'
      else
         sets = 'com_i = l_i and inertia_i = 0'
      end if
      do i = 1, size(fc%fit_names)
         name = trim(fc%fit_names(i))
         if (index(name, 'com') /= 1 .and. index(name, 'inertia') /= 1) cycle
         call fatal_error(error, 'invalid fit-param: '//name//' is fixed by --body '// &
                          fc%run%body//' ('//sets//'); to fit it give --com and --inertia ' &
                          //'(their first guesses) instead of --body [--fit-param --body]')
         return
      end do
   end subroutine check_body_fit

   !> Refuse a fit whose work or memory (`estimate_fit_work`) is beyond the limits:
   !> at most `max_fit_work` step-equivalents, and the memory available.
   subroutine check_work(fc, error)
      type(fit_config_t), intent(in) :: fc              !! the configuration
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      type(fit_problem_t) :: prob
      type(fit_work_t) :: work
      call fit_problem(fc, prob, error)
      if (allocated(error)) return
      call estimate_fit_work(prob, fc%series%t, fc%series%q, fc%fit_window, work, error)
      if (allocated(error)) return
      if (work%work > max_fit_work) then
         call fatal_error(error, 'invalid fit work: up to '//sci(work%work, 3)// &
                          ' integration steps ('//sci(work%steps, 3)//' per integration ' &
                          //'over the fit window of '//sci(fc%series%t(count(fc%series%t <= &
                          fc%fit_window)) - fc%series%t(1), 4)//' s, x'// &
                          to_str(1 + 2*fc%series%n + n_fitted(prob))// &
                          ' with sensitivities, up to '//sci(work%evaluations, 3)// &
                          ' integrations in '//to_str(work%stages)//' stages); at most '// &
                          sci(max_fit_work)//' (a shorter --fit-window or series, a ' &
                          //'larger --dt for rk4, a looser --rtol)')
         return
      end if
      call check_memory('fit work', work%bytes, 'the residuals and Jacobians of the ' &
                        //'fit window', 'shorten the fit window: --fit-window', error)
   end subroutine check_work

   !> The estimation problem of the configuration: the run's model and its
   !> specification, the model parameters fitted (the damping with --fit-damping,
   !> held at its guess while the window is shorter than 2 pi sqrt(sum l / g)).
   subroutine fit_problem(fc, prob, error)
      type(fit_config_t), intent(in) :: fc              !! validated configuration
      type(fit_problem_t), intent(out) :: prob          !! the problem
      type(error_t), allocatable, intent(out) :: error  !! a parameter not fittable
      integer :: n
      n = fc%series%n
      allocate (prob%model, source=fc%run%model)
      prob%spec = fc%run%spec
      ! --body point: the mass at the tip, a fitted length moves it
      if (allocated(fc%run%body)) prob%com_at_tip = fc%run%body == 'point'
      if (size(fc%fit_names) > 0) then
         call set_fitted(prob, fc%fit_names, error)
         if (allocated(error)) return
         prob%hold_period = hold_period(fc)
      end if
      prob%swing = hold_period(fc)
      if (fc%model_coords) prob%angular = coordinate_units(fc, 0) == 'rad'
      block
         character(len=16), allocatable :: names(:), units(:)
         call state_names(fc, names, units)
         prob%labels = [character(len=24) :: names]
         if (n_fitted(prob) > 0) prob%labels = [character(len=24) :: prob%labels, &
                                                prob%comp_labels]
      end block
      prob%positions = fc%series%positions
      if (prob%positions) then   ! some points only: which
         if (size(fc%series%points) < n) prob%points = fc%series%points
      end if
      prob%l = fc%run%l(:n)
      prob%sup_a = fc%run%support_amplitude
      prob%sup_w = fc%run%support_frequency
      prob%sup_phi = fc%run%support_phase
      prob%method = fc%run%method
      prob%rtol = fc%run%rtol
      prob%atol = fc%run%atol
      prob%dt = fc%run%dt
      prob%starts = fc%starts
      prob%noise = fc%sigma
      prob%max_steps = fc%run%max_steps
   end subroutine fit_problem

   !> Names and units of the state at t1: q_i(t1), qdot_i(t1) for the pendulum, the
   !> model's coordinates and their rates otherwise.
   subroutine state_names(fc, names, units)
      type(fit_config_t), intent(in) :: fc
      character(len=16), allocatable, intent(out) :: names(:), units(:)
      character(len=16), allocatable :: cn(:), cu(:), ru(:)
      integer :: i, n
      n = fc%series%n
      allocate (names(2*n), units(2*n))
      if (fc%model_coords) then
         cn = coordinate_units(fc, -1)
         cu = coordinate_units(fc, 0)
         ru = coordinate_units(fc, 1)
         do i = 1, n
            names(i) = trim(cn(i))//'(t1)'
            units(i) = cu(i)
            names(n + i) = trim(cn(i))//'dot(t1)'
            units(n + i) = ru(i)
         end do
      else
         do i = 1, n
            names(i) = 'q'//to_str(i)//'(t1)'
            units(i) = 'rad'
            names(n + i) = 'qdot'//to_str(i)//'(t1)'
            units(n + i) = 'rad/s'
         end do
      end if
   end subroutine state_names

   ! ------------------------------------------------ models other than the pendulum

   !> The fitted model parameters are held at their guess while the fit window is
   !> shorter than the slowest small oscillation: 2 pi sqrt(sum l / g) for the
   !> pendulum's rods, the model's own `swing_period` for another model.
   real(dp) function hold_period(fc) result(period)
      type(fit_config_t), intent(in) :: fc  !! validated configuration
      period = huge(1.0_dp)
      if (.not. fc%model_coords) then
         if (fc%run%g > 0.0_dp) period = 2.0_dp*pi*sqrt(sum(fc%run%l(:fc%series%n))/fc%run%g)
      else
         period = fc%run%model%swing_period()
      end if
   end function hold_period

   !> The model of a fit with --model (built before the data: the CSV columns are
   !> named after its coordinates, e.g. t, r [m], phi [rad]) and the series.
   subroutine read_model_series(fc, error)
      type(fit_config_t), intent(inout) :: fc           !! configuration; series read
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=16), allocatable :: names(:), units(:)
      ! the initial state comes from the data: a state every model accepts meanwhile
      fc%run%q = 0.0_dp
      fc%run%q(1) = 1.0_dp
      fc%run%w = 0.0_dp
      call validate_run_config(fc%run, error)
      if (allocated(error)) return
      names = coordinate_units(fc, -1)
      units = coordinate_units(fc, 0)
      call read_series(fc%input, fc%series, error, names, units)
      if (allocated(error)) return
      call check_model_states(fc, error)
   end subroutine read_model_series

   !> Every sample's coordinates a state the model accepts (at rest: `check_state`,
   !> e.g. the elastic pendulum's r above its collapse), refused with its line: the fit
   !> starts from the first sample and passes near the others, so a sample no state
   !> of the model can reach is an error in the data, not a fit to attempt.
   subroutine check_model_states(fc, error)
      type(fit_config_t), intent(in) :: fc              !! configuration; series read
      type(error_t), allocatable, intent(out) :: error  !! refused
      real(dp), allocatable :: rest(:)
      integer :: k, nd
      nd = fc%run%model%n_dof()
      allocate (rest(nd))
      rest = 0.0_dp
      do k = 1, fc%series%k
         call fc%run%model%check_state(fc%series%q(:nd, k), rest, error)
         if (.not. allocated(error)) cycle
         error%message = "invalid data file '"//printable(fc%input)//"' line "// &
                         to_str(fc%series%line(k))//': not a state of model '// &
                         fc%run%model_name//' ('//error%message//')'
         return
      end do
   end subroutine check_model_states

   !> The model's coordinate names (order -1) or the units of its coordinates
   !> (order 0) or of their rates (order 1).
   function coordinate_units(fc, order) result(u)
      type(fit_config_t), intent(in) :: fc  !! configuration with the model built
      integer, intent(in) :: order          !! -1: names, 0: units, 1: rate units
      character(len=16), allocatable :: u(:)
      character(len=:), allocatable :: name, units, momentum_units
      integer :: i
      allocate (u(fc%run%model%n_dof()))
      do i = 1, size(u)
         call fc%run%model%coordinate(i, name, units, momentum_units)
         select case (order)
         case (-1); u(i) = name
         case (0); u(i) = units
         case default; u(i) = units//'/s'
         end select
      end do
   end function coordinate_units

   !> A comma-separated list of parameter names (--fit-parameters k,l0), appended.
   subroutine parse_names(value, names, error)
      character(len=*), intent(in) :: value                   !! the list
      character(len=32), allocatable, intent(inout) :: names(:) !! names so far
      type(error_t), allocatable, intent(out) :: error        !! an empty or long name
      integer :: start, comma
      character(len=:), allocatable :: item
      start = 1
      do
         comma = index(value(start:), ',')
         if (comma == 0) then
            item = value(start:)
         else
            item = value(start:start + comma - 2)
         end if
         if (len(item) == 0 .or. len(item) > 32 .or. verify(item, &
             'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) then
            call fatal_error(error, "invalid fit-parameters: '"//printable(value)// &
                             "' (parameter names separated by commas, e.g. k,l0; dpend " &
                             //'models lists them) [--fit-parameters]')
            return
         end if
         if (any(names == item)) then
            call fatal_error(error, "invalid fit-parameters: '"//item//"' given twice " &
                             //'[--fit-parameters]')
            return
         end if
         names = [character(len=32) :: names, item]
         if (comma == 0) exit
         start = start + comma
      end do
   end subroutine parse_names

   !> 'k,l0': fitted parameter names joined by commas.
   function joined_names(names) result(s)
      character(len=32), intent(in) :: names(:)  !! names
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(names)
         if (i > 1) s = s//','
         s = s//trim(names(i))
      end do
   end function joined_names
end module dpend_fit_config
