!> `dpend fit` (issue 13): estimate the initial state (and the joint damping) of the
!> pendulum or chain from a measured series of angles or of the positions of the link
!> ends (a CSV file, `dpend_csv`), by
!> Levenberg–Marquardt with the sensitivities of the variational equations
!> (`dpend_estimate`); print the estimates with standard errors, correlations, the RMS
!> residual and the prediction horizon, and write them with the residual series to
!> HDF5 (group /fit, docs/hdf5-layout.md) through the one writer (`dpend_output`).
module dpend_fit_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_cli, only: arg_t, next_option, option_outcome, scan_help_config, parse_real, &
                        parse_int, real_str, to_str, pad, printable
   use dpend_config, only: run_config_t, read_run_config, apply_run_flag, &
                           validate_run_config, run_flags_help
   use dpend_model, only: max_dof
   use dpend_csv, only: series_t, read_series, csv_format
   use dpend_estimate, only: fit_problem_t, fit_result_t, fit_series, fit_work_t, &
                             estimate_fit_work, set_fitted
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_hdf5, only: h5file_t
   use dpend_output, only: output_t, check_output_path, register_input
   use dpend_version, only: version
   use dpend_limits, only: check_range, sci, max_time, max_fit_work
   use dpend_resources, only: check_memory
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: fit_config_t, parse_fit, run_fit, fit_help

   !> Most starting points of the first stage (--starts).
   integer, parameter :: max_starts = 1000
   !> Largest horizon tolerance for positions [m].
   real(dp), parameter :: max_position_tol = 1e6_dp

   !> Everything `dpend fit` needs.
   type :: fit_config_t
      type(run_config_t) :: run                  !! model, method, tolerances, output
      character(len=:), allocatable :: input     !! the CSV file
      type(series_t) :: series                   !! its samples
      logical :: fit_damping = .false.           !! estimate c_i too
      real(dp) :: fit_window = huge(1.0_dp)      !! fit t <= T [s] (default: all)
      logical :: window_given = .false.
      real(dp) :: tolerance = 0.1_dp             !! horizon tolerance [rad]
      integer :: starts = 1                      !! first-stage starting points
   end type fit_config_t

   !> The run flags that make sense for a fit (the initial state comes from the data).
   character(len=20), parameter :: run_flags(19) = [character(len=20) :: '--links', '--m', &
      '--l', '--g', '--m1', '--m2', '--l1', '--l2', '--damping', '--support-amplitude', &
      '--support-frequency', '--support-phase', '--method', '--dt', '--rtol', '--atol', &
      '--max-steps', '--output', '-o']

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
          nl//'                          units in brackets allowed (t [s], theta1 [rad]);'//nl// &
          '                          other columns are ignored, lines starting with # and'// &
          nl//'                          blank lines skipped. N = the number of angle columns.'// &
          nl//'  t,x1,y1[,x2,y2,...]     or (no angle columns) the positions of the far ends of'// &
          nl//'                          the links (joint i+1, the tip for i = N), origin at'// &
          nl//'                          the pin, y up; units [m], [cm], [mm] (none: m);'// &
          nl//'                          residuals and --horizon-tolerance are then in m.'// &
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
          '  --fit-window T    fit only the samples with t <= T (s); the rest measures the'// &
          nl//'                    prediction horizon; default: all samples'//nl// &
          '  --horizon-tolerance R  the horizon ends at the first sample after T where an'// &
          nl//'                    angle differs from the model by more than R (rad, in'//nl// &
          '                    (0, pi]; positions: m, in (0, 1e6]); default '// &
          real_str(fc%tolerance)//nl// &
          '  --starts K        first-stage starting points (1 to '//to_str(max_starts)// &
          '): the guess and'//nl// &
          '                    K-1 others spread over the rates (sparse samples of a chaotic'// &
          nl//'                    motion); default '//to_str(fc%starts)//nl// &
          '  --output FILE     HDF5 file to write; default '//fc%run%output//nl// &
          '  --force           overwrite an existing output file'//nl//nl// &
          'model and integration (the initial state comes from the data; the links from'// &
          nl//'its angle columns; --method: a method on (q, qdot): rk4, dopri5, dop853):'// &
          nl//'  --config, --links, --m, --l, --g, --m1, --m2, --l1, --l2, --damping,'//nl// &
          '  --support-amplitude, --support-frequency, --support-phase, --method (default '// &
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
      character(len=:), allocatable :: name, value, config
      class(integrator_t), allocatable :: integ
      logical :: matched, missing, links_given
      integer :: i, np, k_fit
      real(dp) :: x
      fc = fit_defaults()
      help = .false.
      links_given = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_run_config(config, fc%run, error)
         if (allocated(error)) return
      end if
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
         if (args(i)%s(1:min(2, len(args(i)%s))) /= '--' .and. args(i)%s /= '-o') then
            if (len(fc%input) > 0) then
               call fatal_error(error, "unexpected argument '"//printable(args(i)%s)// &
                                "' (one data file; dpend fit --help)")
               return
            end if
            fc%input = args(i)%s
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
         case ('--starts')
            call parse_int(value, name, fc%starts, error)
         case default
            if (any(run_flags == name)) then
               if (name == '--links') links_given = .true.
               call apply_run_flag(fc%run, name, value, matched, error)
            else
               matched = .false.
            end if
         end select
         call option_outcome('fit', name, matched, missing, &
                             [character(len=16) :: '--force', '--fit-damping'], error)
         if (allocated(error)) return
      end do
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
      call register_input(fc%input)   ! the output never replaces the data file
      call check_output_path(fc%run%output, fc%run%force, error)
      if (allocated(error)) return
      call read_series(fc%input, fc%series, error)
      if (allocated(error)) return
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
         if (links_given .and. fc%run%links /= s%n) then
            call fatal_error(error, 'invalid links: '//to_str(fc%run%links)//" given, the " &
                             //"data file '"//printable(fc%input)//"' has "//to_str(s%n)// &
                             ' angle columns (N is the number of angle columns) [--links]')
            return
         end if
         fc%run%links = s%n
         call validate_run_config(fc%run, error)
         if (allocated(error)) return
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
         np = merge(3*s%n, 2*s%n, fc%fit_damping)
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
      call check_work(fc, error)
   end subroutine parse_fit

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
                          to_str(1 + merge(3, 2, fc%fit_damping)*fc%series%n)// &
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
      if (fc%fit_damping) then
         call set_fitted(prob, [character(len=8) :: 'damping'], error)
         if (allocated(error)) return
         if (fc%run%g > 0.0_dp) prob%hold_period = 2.0_dp*pi*sqrt(sum(fc%run%l(:n))/fc%run%g)
      end if
      prob%positions = fc%series%positions
      prob%l = fc%run%l(:n)
      prob%sup_a = fc%run%support_amplitude
      prob%sup_w = fc%run%support_frequency
      prob%sup_phi = fc%run%support_phase
      prob%method = fc%run%method
      prob%rtol = fc%run%rtol
      prob%atol = fc%run%atol
      prob%dt = fc%run%dt
      prob%starts = fc%starts
      prob%max_steps = fc%run%max_steps
   end subroutine fit_problem

   !> Run the fit and write its report and file.
   !> The error's kind says whether the input was refused (nothing written) or
   !> the run started and failed (exit status 1).
   subroutine run_fit(fc, error)
      type(fit_config_t), intent(in) :: fc              !! validated configuration
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical :: failed
      call run_fit_body(fc, error, failed)
      if (allocated(error) .and. failed) call run_failure(error)
   end subroutine run_fit

   !> Fit, print the report, write the HDF5 file.
   subroutine run_fit_body(fc, error, failed)
      type(fit_config_t), intent(in) :: fc              !! validated configuration
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical, intent(out) :: failed                    !! the fit started and failed
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      type(output_t) :: out
      type(error_t), allocatable :: werr
      failed = .false.
      call fit_problem(fc, prob, error)
      if (allocated(error)) return
      call out%begin(fc%run%output, fc%run%force, error)
      if (allocated(error)) return
      call fit_series(prob, fc%series%t, fc%series%q, fc%fit_window, fc%tolerance, res, &
                      error, progress=.true.)
      if (allocated(error)) then
         call out%discard()
         failed = .true.
         return
      end if
      call print_report(fc, res)
      call write_fit(out%temp, fc, res, werr)
      if (.not. allocated(werr)) call out%commit(werr)
      call out%explain(werr)
      call out%discard()
      if (allocated(werr)) then
         failed = .true.
         call move_alloc(werr, error)
         return
      end if
      write (output_unit, '(a)') "dpend fit: wrote '"//fc%run%output//"'"
   end subroutine run_fit_body

   !> Names and units of the parameters.
   subroutine parameter_names(n, damping, names, units)
      integer, intent(in) :: n
      logical, intent(in) :: damping
      character(len=16), allocatable, intent(out) :: names(:), units(:)
      integer :: i, np
      np = merge(3*n, 2*n, damping)
      allocate (names(np), units(np))
      do i = 1, n
         names(i) = 'q'//to_str(i)//'(t1)'
         units(i) = 'rad'
         names(n + i) = 'qdot'//to_str(i)//'(t1)'
         units(n + i) = 'rad/s'
         if (damping) then
            names(2*n + i) = 'c'//to_str(i)
            units(2*n + i) = 'N m s'
         end if
      end do
   end subroutine parameter_names

   subroutine print_report(fc, res)
      type(fit_config_t), intent(in) :: fc
      type(fit_result_t), intent(in) :: res
      character(len=16), allocatable :: names(:), units(:)
      character(len=:), allocatable :: line, ou
      integer :: i, j, np
      ou = trim(merge('m  ', 'rad', fc%series%positions))
      associate (s => fc%series)
         write (output_unit, '(a)') "dpend fit: '"//fc%input//"': "//to_str(s%n)// &
            merge(' link ', ' links', s%n == 1)//', '//to_str(s%k)//' samples, t1 = '// &
            real_str(s%t(1))//' s to '//real_str(s%t(s%k))//' s; fit window t <= '// &
            real_str(res%t_window)//' s ('//to_str(res%k_fit)//' samples); '// &
            fc%run%method//' rtol '//real_str(fc%run%rtol)
         if (len(csv_format(s)) > 0) write (output_unit, '(a)') '  csv: '//csv_format(s)
         if (s%theta) write (output_unit, '(a)') '  (the file gives theta from the hanging ' &
            //'position; estimates are q = theta - pi/2 from the horizontal x axis)'
         if (s%positions) write (output_unit, '(a)') '  (the file gives the positions of ' &
            //'the link ends: residuals and tolerance in m)'
      end associate
      call parameter_names(res%n, fc%fit_damping, names, units)
      np = res%np
      write (output_unit, '(a)') '  parameter    estimate                     standard error' &
         //'   95 % interval'
      do i = 1, np
         write (output_unit, '(a)') '  '//pad(names(i), 13)//pad(real_str(res%p(i), 12)// &
            ' '//trim(units(i)), 29)//pad(real_str(res%se(i), 3), 17)//'['// &
            real_str(res%p(i) - res%t95*res%se(i), 6)//', '// &
            real_str(res%p(i) + res%t95*res%se(i), 6)//']'
      end do
      write (output_unit, '(a)') '  correlation matrix (rows and columns in the order above):'
      do i = 1, np
         line = '   '
         do j = 1, np
            line = line//' '//fixed(res%corr(i, j))
         end do
         write (output_unit, '(a)') line
      end do
      write (output_unit, '(a)') '  RMS residual '//real_str(res%rms, 3)//' '//ou// &
         ' (sigma '//real_str(res%sigma, 3)//' '//ou//', '//to_str(res%dof)// &
         ' degrees of freedom, t = '//real_str(res%t95, 4)//'); '// &
         to_str(res%iterations)//' iterations in '//to_str(res%stages)//' stages, '// &
         trim(merge('converged    ', 'not converged', res%converged))
      if (res%has_after) then
         if (res%horizon_censored) then
            write (output_unit, '(a)') '  prediction horizon after t = '// &
               real_str(res%t_window)//' s: at least '//real_str(res%horizon, 4)// &
               ' s (within '//real_str(res%tolerance)//' '//ou//' up to the last sample)'
         else
            write (output_unit, '(a)') '  prediction horizon after t = '// &
               real_str(res%t_window)//' s: '//real_str(res%horizon, 4)//' s (tolerance ' &
               //real_str(res%tolerance)//' '//ou//')'
         end if
      else
         write (output_unit, '(a)') '  prediction horizon: none (no samples after the fit ' &
            //'window; give --fit-window T)'
      end if
   contains
      function fixed(x) result(t)
         real(dp), intent(in) :: x
         character(len=:), allocatable :: t
         character(len=8) :: buf
         write (buf, '(f7.3)') x
         t = buf(:7)
      end function fixed
   end subroutine print_report

   !> The /fit group and the root attributes.
   subroutine write_fit(filename, fc, res, error)
      character(len=*), intent(in) :: filename
      type(fit_config_t), intent(in) :: fc
      type(fit_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=16), allocatable :: names(:), units(:)
      character(len=:), allocatable :: joined, units_text
      real(dp), allocatable :: interval(:, :)
      integer :: i, np, n
      integer, allocatable :: window(:)
      np = res%np
      n = res%n
      call parameter_names(n, fc%fit_damping, names, units)
      joined = trim(names(1))
      do i = 2, np
         joined = joined//','//trim(names(i))
      end do
      ! by blocks of components (docs/hdf5-layout.md)
      units_text = 'rad, rad/s'
      if (fc%fit_damping) units_text = units_text//', N m s'
      allocate (interval(2, np))
      interval(1, :) = res%p - res%t95*res%se
      interval(2, :) = res%p + res%t95*res%se
      window = merge(1, 0, fc%series%t <= res%t_window)
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call h5%write('/fit/t', fc%series%t, units='s', description='sample times of the data')
      if (fc%series%positions) then
         call h5%write('/fit/xy_data', fc%series%q, units='m', description='measured ' &
                       //'positions x_i, y_i of the far ends of the links (origin: the pin)')
         call h5%write('/fit/xy_model', res%q_model, units='m', description='positions ' &
                       //'of the fitted model at the sample times')
         call h5%write('/fit/residual', res%resid, units='m', description='data minus ' &
                       //'model (x_1, y_1, ..., x_N, y_N)')
      else
         call h5%write('/fit/q_data', fc%series%q, units='rad', description='measured ' &
                       //'angles q_i from the horizontal x axis (theta - pi/2 for theta ' &
                       //'columns)')
         call h5%write('/fit/q_model', res%q_model, units='rad', description='angles of ' &
                       //'the fitted model at the sample times')
         call h5%write('/fit/residual', res%resid, units='rad', description='data minus ' &
                       //'model, wrapped to [-pi, pi)')
      end if
      call h5%write('/fit/in_window', window, units='1', description='1 for the samples ' &
                    //'of the fit window (t <= T), 0 after it')
      call h5%write('/fit/estimate', res%p, units=units_text, description='estimates of '// &
                    joined)
      call h5%write('/fit/guess', res%guess, units=units_text, description='the first ' &
                    //'guess (angles of the first sample, rates by finite differences)')
      call h5%write('/fit/standard_error', res%se, units=units_text, description= &
                    'standard errors: sqrt of the diagonal of sigma^2 (J^T J)^-1')
      call h5%write('/fit/interval95', interval, units=units_text, description='95 % ' &
                    //'intervals estimate -/+ t(0.975, dof) standard error (lower, upper)')
      call h5%write('/fit/covariance', res%cov, units=units_text//' (row unit times ' &
                    //'column unit)', &
                    description='covariance sigma^2 (J^T J)^-1 of the estimates')
      call h5%write('/fit/correlation', res%corr, units='1', description='correlation ' &
                    //'matrix of the estimates')
      call h5%write('/fit/horizon', [res%horizon], units='s', description='prediction ' &
                    //'horizon: time after the fit window until the model leaves the ' &
                    //'tolerance (0 without samples after the window)')
      call h5%write('/fit/t_window', [res%t_window], units='s', description='end T of ' &
                    //'the fit window (its last sample time)')
      call h5%writeattr('/fit', 'parameters', joined)
      call h5%writeattr('/fit', 'rms_residual', res%rms)
      call h5%writeattr('/fit', 'sigma', res%sigma)
      call h5%writeattr('/fit', 'dof', res%dof)
      call h5%writeattr('/fit', 't95', res%t95)
      call h5%writeattr('/fit', 'iterations', res%iterations)
      call h5%writeattr('/fit', 'stages', res%stages)
      call h5%writeattr('/fit', 'converged', merge(1, 0, res%converged))
      call h5%writeattr('/fit', 'horizon_tolerance', res%tolerance)
      call h5%writeattr('/fit', 'horizon_censored', merge(1, 0, res%horizon_censored))
      call h5%writeattr('/fit', 'has_after', merge(1, 0, res%has_after))
      call h5%writeattr('/fit', 'input', fc%input)
      if (fc%series%positions) then
         call h5%writeattr('/fit', 'observations', 'positions')
      else
         call h5%writeattr('/fit', 'observations', 'angles')
         call h5%writeattr('/fit', 'angle_columns', trim(merge('theta', 'q    ', &
                           fc%series%theta)))
      end if
      call h5%writeattr('/', 'command', 'fit')
      call h5%writeattr('/', 'version', version)
      call h5%writeattr('/', 'method', fc%run%method)
      call h5%writeattr('/', 'rtol', fc%run%rtol)
      call h5%writeattr('/', 'atol', fc%run%atol)
      call h5%writeattr('/', 'links', n)
      call h5%writeattr('/', 'm', fc%run%m(:n))
      call h5%writeattr('/', 'l', fc%run%l(:n))
      call h5%writeattr('/', 'g', fc%run%g)
      call h5%writeattr('/', 'damping', fc%run%damping(:n))
      call h5%writeattr('/', 'fit_damping', merge(1, 0, fc%fit_damping))
      call h5%close(error)
   end subroutine write_fit
end module dpend_fit_command
