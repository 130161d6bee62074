!> `dpend fit`: estimate the initial state (and the joint damping) of the
!> pendulum or chain from a measured series of angles or of the positions of the link
!> ends (a CSV file, `dpend_csv`), by
!> Levenberg–Marquardt with the sensitivities of the variational equations
!> (`dpend_estimate`); print the estimates with standard errors, correlations, the RMS
!> residual and the prediction horizon, and write them with the residual series to
!> HDF5 (group /fit, docs/hdf5-layout.md) through the one writer (`dpend_output`);
!> a fit that fails partway writes its settings and why it stopped (`status`).
!> The command line, the data and their checks: `dpend_fit_config`.
module dpend_fit_command
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use dpend_kinds, only: dp, pi, half_pi
   use dpend_error, only: error_t, run_failure, error_bad_input
   use dpend_cli, only: arg_t, real_str, to_str, pad
   use dpend_strings, only: with_uncertainty, interval_text
   use dpend_run_settings, only: time_text, span_text
   use dpend_csv, only: csv_format
   use dpend_estimate, only: fit_problem_t, fit_result_t, fit_series, set_fitted, n_fitted, &
                             observation_noise, misfit_suspects, misfit_factor, suspect_t, &
                             condition_text
   use dpend_model_factory, only: model_catalogue, find_model, model_info_t
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model
   use dpend_output, only: output_t
   use dpend_version, only: version
   use dpend_command_common, only: report_unit, take_quiet, with_quiet, summary_quiet, &
      refusal_line, error_line
   use dpend_fit_alternatives, only: weigh_alternatives
   use dpend_fit_config, only: fit_config_t, parse_fit, fit_help, fit_problem, state_names, &
      joined_names, &
                               coordinate_units
   implicit none
   private
   public :: fit_command, fit_config_t, parse_fit, run_fit, fit_help

contains

   !> The entry point of `dpend fit DATA.csv [options]` (app/main.f90): parse → `run_fit`;
   !> a refusal or a failed run comes back as `error`, its one line 'dpend fit: ...'.
   subroutine fit_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `fit`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(fit_config_t) :: fc
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_fit(rest, fc, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'fit')
      else if (help) then
         write (output_unit, '(a)') with_quiet(fit_help(), summary_quiet)
      else
         call run_fit(fc, error, quiet)
         if (allocated(error)) call error_line(error, 'fit')
      end if
   end subroutine fit_command

   !> Run the fit and write its report and file; `quiet`: of the report only its last
   !> line (the file written), and any warning.
   !> The error's kind says whether the input was refused (nothing written) or
   !> the run started and failed (exit status 1).
   subroutine run_fit(fc, error, quiet)
      type(fit_config_t), intent(in) :: fc              !! validated configuration
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical, intent(in) :: quiet                      !! --quiet
      logical :: failed
      call run_fit_body(fc, quiet, error, failed)
      if (allocated(error) .and. failed) call run_failure(error)
   end subroutine run_fit

   !> Fit, print the report, write the HDF5 file. A fit that fails partway (any
   !> error but refused input, `error_bad_input`) still writes its file, holding the
   !> settings and the failure as its status (`write_fit_failure`).
   subroutine run_fit_body(fc, quiet, error, failed)
      type(fit_config_t), intent(in) :: fc              !! validated configuration
      logical, intent(in) :: quiet                      !! only the report's last line
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical, intent(out) :: failed                    !! the fit started and failed
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      type(output_t) :: out
      type(error_t), allocatable :: werr
      character(len=:), allocatable :: note
      failed = .false.
      note = ''
      call fit_problem(fc, prob, error)
      if (allocated(error)) return
      call out%begin(fc%run%output, fc%run%force, error)
      if (allocated(error)) return
      ! a fit that stalls far above the noise stops early: the alternatives a user
      ! can choose are weighed on its window; none clearly better, it goes on
      prob%stall_check = .true.
      call fit_series(prob, fc%series%t, fc%series%q, fc%fit_window, fc%tolerance, res, &
                      error, progress=.true.)
      if (allocated(error) .and. res%stalled) then
         call stalled_fit(fc, res, quiet, error, note)
         if (.not. allocated(error)) then
            prob%stall_check = .false.
            call fit_series(prob, fc%series%t, fc%series%q, fc%fit_window, fc%tolerance, &
                            res, error, progress=.true.)
         end if
      end if
      if (allocated(error)) then
         if (error%kind /= error_bad_input) call write_fit_failure(out, fc, error, res%work)
         call out%discard()
         failed = .true.
         return
      end if
      if (.not. quiet) call print_report(fc, res)
      ! --quiet: the warning on stderr, the closing line alone on stdout
      ! (a stall the continued fit got past, ending at the noise, is not mentioned)
      call misfit_warning(fc, prob, res, merge(error_unit, report_unit(), quiet), note)
      call write_fit(out%temp, fc, res, werr)
      if (.not. allocated(werr)) call out%commit(werr)
      call out%explain(werr)
      call out%discard()
      if (allocated(werr)) then
         failed = .true.
         call move_alloc(werr, error)
         return
      end if
      write (report_unit(), '(a)') "dpend fit: wrote '"//fc%run%output//"'"
   end subroutine run_fit_body

   !> A fit that stalled (`res%stalled`): the alternatives weighed on its window
   !> (`weigh_alternatives`). Another body clearly better: the fit stops, `error`
   !> naming it ('... give --body point'); otherwise `error` is cleared and the caller
   !> fits on as configured (as before: a model lacking a setting ends with its misfit
   !> warning), `note` saying what fitted better for stderr (unless --quiet), shown
   !> if the continued fit does not reach the noise either.
   subroutine stalled_fit(fc, res, quiet, error, note)
      type(fit_config_t), intent(in) :: fc                !! the configuration
      logical, intent(in) :: quiet                        !! --quiet: no note
      type(fit_result_t), intent(inout) :: res            !! the stalled fit; its work
                                                          !! adds the alternatives'
      type(error_t), allocatable, intent(inout) :: error  !! its stall; kept or cleared
      character(len=:), allocatable, intent(out) :: note  !! the note ('' : none)
      character(len=:), allocatable :: text, advice, ou
      logical :: better, body
      real(dp) :: work
      note = ''
      ou = trim(merge('m  ', 'rad', fc%series%positions))
      if (fc%model_coords) ou = '(units)'
      call weigh_alternatives(fc, res, ou, text, advice, better, work, body)
      res%work = res%work + work
      if (better .and. body) then   ! the body cannot describe the data: stop
         error%message = error%message//' with '//setting_text(fc)// &
                         '; on that window '//text//': '//advice
         return
      end if
      ! another setting (the damping fitted, a shorter window) or none fits better:
      ! the fit goes on as configured, its misfit warning at the end
      if (.not. quiet) then
         if (better) then
            note = 'dpend fit: note: '//error%message//' with '// &
               setting_text(fc)//'; on that window '//text//': '//advice// &
               ' (the fit goes on as configured)'
         else
            if (len(text) > 0) text = ' ('//text//')'
            note = 'dpend fit: note: '//error%message//' with '// &
               setting_text(fc)//'; no alternative fits that window clearly better'// &
               text//': the fit goes on'
         end if
      end if
      deallocate (error)
   end subroutine stalled_fit

   !> The body and fitted parameters of a fit, in words: 'rods (--body rod), fitting
   !> m2,l,damping'.
   function setting_text(fc) result(s)
      type(fit_config_t), intent(in) :: fc
      character(len=:), allocatable :: s
      s = 'uniform rods (the default body)'
      if (allocated(fc%run%body)) then
         if (fc%run%body == 'point') s = 'point masses (--body point)'
         if (fc%run%body == 'rod') s = 'uniform rods (--body rod)'
      else if (fc%run%spec%find('com') > 0) then
         s = 'the links of --com and --inertia'
      end if
      if (fc%model_coords) s = 'model '//fc%run%model_name
      if (size(fc%fit_names) > 0) s = s//', fitting '//joined_names(fc%fit_names)
   end function setting_text

   !> The file of a fit that failed partway: the root attributes of the settings and
   !> `status` = the failure's message, no /fit group; `error` then names the file
   !> too (or, when the file could not be written, why not).
   subroutine write_fit_failure(out, fc, error, work)
      type(output_t), intent(inout) :: out                !! the output, begun
      type(fit_config_t), intent(in) :: fc                !! validated configuration
      type(error_t), allocatable, intent(inout) :: error  !! the fit's failure
      real(dp), intent(in) :: work                        !! the work done [step-eq.]
      type(error_t), allocatable :: werr
      type(h5file_t) :: h5
      call h5%open(out%temp, 'w', werr)
      if (.not. allocated(werr)) then
         call write_fit_root(h5, fc, error%message)
         call h5%writeattr('/', 'input', fc%input)
         if (fc%run%torque%active()) then
            call h5%writeattr('/', 'torque', fc%run%torque%text())
            if (allocated(fc%run%torque_file)) &
               call h5%writeattr('/', 'torque_file', fc%run%torque_file)
         end if
         call h5%writeattr('/', 'work', work)
         call h5%close(werr)
      end if
      if (.not. allocated(werr)) call out%commit(werr)
      call out%explain(werr)
      if (allocated(werr)) then
         error%message = error%message//'; its file was not written: '//werr%message
      else
         error%message = error%message//"; '"//fc%run%output// &
                         "' holds the settings and this status"
      end if
   end subroutine write_fit_failure

   !> A fit whose RMS residual exceeds `misfit_factor` times the noise (--sigma, or
   !> estimated from the data's third differences) says so on `unit` (the report's,
   !> stderr with --quiet) and names the unfitted parameters whose fit would lower it
   !> most (`misfit_suspects`).
   subroutine misfit_warning(fc, prob, res, unit, note)
      type(fit_config_t), intent(in) :: fc      !! configuration
      type(fit_problem_t), intent(in) :: prob   !! the problem fitted
      type(fit_result_t), intent(in) :: res     !! the fit
      integer, intent(in) :: unit               !! where the warning goes
      character(len=*), intent(in) :: note      !! a stall's note for stderr ('' : none)
      type(suspect_t), allocatable :: sus(:)
      type(error_t), allocatable :: error
      character(len=:), allocatable :: ou, how, line
      real(dp) :: noise
      integer :: i
      ou = trim(merge('m  ', 'rad', fc%series%positions))
      if (fc%model_coords) ou = '(in the coordinates'' units)'
      noise = observation_noise(prob, fc%series%q, res%k_fit, how)
      if (.not. (res%rms > misfit_factor*noise)) return
      if (len(note) > 0) write (error_unit, '(a)') note
      write (unit, '(a)') '  warning: the RMS residual '//real_str(res%rms, 3)//' ' &
         //ou//' is '//real_str(res%rms/max(noise, tiny(1.0_dp)), 3)//' times the noise ' &
         //real_str(noise, 3)//' '//ou//' ('//how//'), more than '//real_str(misfit_factor)// &
         ': the model does not describe the data (the residuals are model error: a ' &
         //'fixed parameter is wrong, or the model is not the system)'
      call misfit_suspects(prob, fc%series%t, fc%series%q, res, sus, error)
      if (allocated(error)) then
         write (unit, '(a)') '  (the parameters that may be wrong could not be ' &
            //'ranked: '//error%message//')'
         return
      end if
      if (size(sus) == 0) return
      line = ''
      do i = 1, min(size(sus), 4)
         if (i > 1) line = line//', '
         line = line//trim(sus(i)%label)//' ('//real_str(sus(i)%rms, 3)//')'
      end do
      how = 'fit them with --fit-param '//trim(sus(1)%label)
      ! a com or inertia that --body fixes is fitted by giving them instead of the body
      if (allocated(fc%run%body)) then
         if (any([(index(sus(i)%label, 'com') == 1 .or. index(sus(i)%label, 'inertia') == 1, &
                   i=1, min(size(sus), 4))])) &
            how = how//' (com and inertia are fixed by --body '//fc%run%body//': to fit ' &
                  //'them give --com and --inertia, their first guesses, instead)'
      end if
      write (unit, '(a)') '  parameters that may be wrong, by the RMS residual ' &
         //'fitting each too would leave (linearized): '//line//'; '//how
   end subroutine misfit_warning

   !> Names and units of the parameters: the state at t1 (q_i, qdot_i for the
   !> pendulum; the model's coordinates and their rates otherwise), then the fitted
   !> model parameters' components (c_i for the damping, m2, g, ...).
   subroutine parameter_names(fc, names, units)
      type(fit_config_t), intent(in) :: fc
      character(len=16), allocatable, intent(out) :: names(:), units(:)
      type(model_info_t), allocatable :: models(:)
      type(fit_problem_t) :: prob
      type(error_t), allocatable :: error
      integer :: i, j, k
      call state_names(fc, names, units)
      if (size(fc%fit_names) == 0) return
      prob%spec = fc%run%spec
      call set_fitted(prob, fc%fit_names, error)   ! accepted by check_fit_data
      if (allocated(error)) return
      models = model_catalogue()
      k = find_model(models, fc%run%spec%model_name())
      do i = 1, n_fitted(prob)
         names = [character(len=16) :: names, prob%comp_labels(i)]
         do j = 1, size(models(k)%params)
            if (models(k)%params(j)%name == trim(prob%comp_names(i))) &
               units = [character(len=16) :: units, models(k)%params(j)%units]
         end do
      end do
   end subroutine parameter_names

   !> The units of the parameters by blocks ('rad, rad/s, N m s'; a block of
   !> mixed units lists each: 'm rad, m/s rad/s, N/m m').
   function units_blocks(fc, units) result(s)
      type(fit_config_t), intent(in) :: fc
      character(len=16), intent(in) :: units(:)
      character(len=:), allocatable :: s
      integer :: n
      n = fc%series%n
      s = block(units(1:n))//', '//block(units(n + 1:2*n))
      if (size(units) > 2*n) s = s//', '//block(units(2*n + 1:))
   contains
      function block(u) result(b)
         character(len=16), intent(in) :: u(:)
         character(len=:), allocatable :: b
         integer :: i
         b = trim(u(1))
         if (all(u == u(1))) return
         do i = 2, size(u)
            b = b//' '//trim(u(i))
         end do
      end function block
   end function units_blocks

   !> The report on stdout: the data, the estimates with their standard errors and
   !> intervals, the correlations, the residual, the identifiability, the horizon.
   subroutine print_report(fc, res)
      type(fit_config_t), intent(in) :: fc
      type(fit_result_t), intent(in) :: res
      character(len=16), allocatable :: names(:), units(:)
      character(len=:), allocatable :: line, ou, rule
      integer :: i, j, np
      ou = trim(merge('m  ', 'rad', fc%series%positions))
      call parameter_names(fc, names, units)
      if (fc%model_coords) ou = '('//coordinates_joined(fc, ' in ', ', ')//')'
      associate (s => fc%series)
         write (report_unit(), '(a)') "dpend fit: '"//fc%input//"': "//model_text(fc)// &
            ', '//to_str(s%k)//' samples, t = '//span_text(fc%run, s%t(1), s%t(s%k))// &
            '; fit window t <= '// &
            time_text(fc%run, res%t_window)//' ('//to_str(res%k_fit)//' samples); '// &
            fc%run%method//' rtol '//real_str(fc%run%rtol)
         if (len(csv_format(s)) > 0) write (report_unit(), '(a)') '  csv: '//csv_format(s)
         if (s%theta) write (report_unit(), '(a)') '  (the file gives theta from the hanging ' &
            //'position; estimates are q = theta - pi/2 from the horizontal x axis)'
         if (s%positions) then   ! (nested: Fortran's .and. may evaluate both sides)
            if (size(s%points) == s%n) then
               write (report_unit(), '(a)') '  (the file gives the positions of the link ' &
                  //'ends: residuals and tolerance in m)'
            else
               write (report_unit(), '(a)') '  (the file gives the positions of '// &
                  xy_names(s%points)//' only, of the '//to_str(s%n)//' link ends; the ' &
                  //'others are placed by the lengths and the dynamics: residuals and ' &
                  //'tolerance in m)'
            end if
         end if
      end associate
      call parameter_names(fc, names, units)
      np = res%np
      write (report_unit(), '(a)') '  parameter    estimate +- standard error (to its digits)' &
         //'   95 % interval (Student t)'
      do i = 1, np
         write (report_unit(), '(a)') '  '//pad(names(i), 13)//pad(with_uncertainty(res%p(i), &
            res%se(i))//' '//trim(units(i)), 41)// &
            interval_text(res%p(i) - res%t95*res%se(i), res%p(i) + res%t95*res%se(i), &
                          res%se(i))
      end do
      if (.not. fc%model_coords .and. (fc%series%theta .or. fc%series%degrees)) &
         write (report_unit(), '(a)') '  in the data''s convention: '//data_convention(fc, res)
      write (report_unit(), '(a)') '  (standard errors from the residuals at the optimum: ' &
         //'the noise only, not a wrong model; every digit in /fit/estimate and /fit/standard_error)'
      write (report_unit(), '(a)') '  correlation matrix (rows and columns in the order above):'
      do i = 1, np
         line = '   '
         do j = 1, np
            line = line//' '//fixed(res%corr(i, j))
         end do
         write (report_unit(), '(a)') line
      end do
      write (report_unit(), '(a)') '  RMS residual '//real_str(res%rms, 3)//' '//ou// &
         ' (sigma '//real_str(res%sigma, 3)//' '//ou//', '//to_str(res%dof)// &
         ' degrees of freedom, t = '//real_str(res%t95, 4)//'); '// &
         to_str(res%iterations)//' iterations in '//to_str(res%stages)//' stages, '// &
         trim(merge('converged    ', 'not converged', res%converged))
      line = ''
      do i = 1, size(res%singular)
         if (i > 1) line = line//', '
         line = line//real_str(res%singular(i), 3)
      end do
      if (allocated(res%mirror)) write (report_unit(), '(a)') '  '//res%mirror
      write (report_unit(), '(a)') '  identifiability: singular values of the sensitivities ' &
         //'(columns scaled to 1) '//line//'; condition number '// &
         condition_text(res%condition)
      rule = ''
      if (allocated(fc%tolerance_rule)) then
         if (fc%tolerance_rule /= 'given') rule = ': '//fc%tolerance_rule
      end if
      if (res%has_after) then
         if (res%horizon_censored) then
            write (report_unit(), '(a)') '  prediction horizon after t = '// &
               time_text(fc%run, res%t_window)//': at least '// &
               time_text(fc%run, res%horizon)//' (within '//real_str(res%tolerance, 6)// &
               ' '//ou//rule//' up to the last sample)'
         else
            write (report_unit(), '(a)') '  prediction horizon after t = '// &
               time_text(fc%run, res%t_window)//': '//time_text(fc%run, res%horizon)// &
               ' (tolerance ' &
               //real_str(res%tolerance, 6)//' '//ou//rule//')'
         end if
      else
         write (report_unit(), '(a)') '  prediction horizon: none (no samples after the fit ' &
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

   !> The initial state in the convention and unit of the data (theta from the
   !> hanging position, theta = q + pi/2, and/or degrees), each with its standard
   !> error: 'theta1(t1) = 103.14 +- 0.09 deg, ..., thetadot1(t1) = ... deg/s'.
   function data_convention(fc, res) result(s)
      type(fit_config_t), intent(in) :: fc       !! the data's convention
      type(fit_result_t), intent(in) :: res      !! the estimates (q, qdot first)
      character(len=:), allocatable :: s, name, unit
      real(dp) :: scale, offset
      integer :: i, n
      n = res%n
      name = trim(merge('theta', 'q    ', fc%series%theta))
      offset = merge(half_pi, 0.0_dp, fc%series%theta)
      scale = merge(180.0_dp/pi, 1.0_dp, fc%series%degrees)
      unit = trim(merge('deg', 'rad', fc%series%degrees))
      s = ''
      do i = 1, n
         if (i > 1) s = s//', '
         s = s//name//to_str(i)//'(t1) = '//with_uncertainty(scale*(res%p(i) + offset), &
             scale*res%se(i))//' '//unit
      end do
      do i = 1, n
         s = s//', '//name//'dot'//to_str(i)//'(t1) = '// &
             with_uncertainty(scale*res%p(n + i), scale*res%se(n + i))//' '//unit//'/s'
      end do
   end function data_convention

   !> The columns of the observed points: 'x1, y1, x2, y2', 'x2, y2'.
   function xy_names(points) result(s)
      integer, intent(in) :: points(:)
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(points)
         if (i > 1) s = s//', '
         s = s//'x'//to_str(points(i))//', y'//to_str(points(i))
      end do
   end function xy_names

   !> The observed points as text: '1 2', '2'.
   function points_text(points) result(s)
      integer, intent(in) :: points(:)
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(points)
         if (i > 1) s = s//' '
         s = s//to_str(points(i))
      end do
   end function points_text

   !> The /fit group and the root attributes.
   subroutine write_fit(filename, fc, res, error)
      character(len=*), intent(in) :: filename
      type(fit_config_t), intent(in) :: fc
      type(fit_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=16), allocatable :: names(:), units(:)
      character(len=:), allocatable :: joined, units_text, coord_text, coord_names
      real(dp), allocatable :: interval(:, :)
      integer :: i, np, n
      integer, allocatable :: window(:)
      np = res%np
      n = res%n
      call parameter_names(fc, names, units)
      joined = trim(names(1))
      do i = 2, np
         joined = joined//','//trim(names(i))
      end do
      ! by blocks of components (docs/hdf5-layout.md)
      units_text = units_blocks(fc, units)
      allocate (interval(2, np))
      interval(1, :) = res%p - res%t95*res%se
      interval(2, :) = res%p + res%t95*res%se
      window = merge(1, 0, fc%series%t <= res%t_window)
      coord_text = units_blocks(fc, units)
      coord_text = coord_text(:index(coord_text, ',') - 1)
      coord_names = ''
      if (fc%model_coords) coord_names = model_text(fc)
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call h5%write('/fit/t', fc%series%t, units='s', description='sample times of the data')
      if (fc%model_coords) then
         call h5%write('/fit/q_data', fc%series%q, units=coord_text, description='measured ' &
                       //'coordinates '//coord_names//' of the model '//fc%run%model_name)
         call h5%write('/fit/q_model', res%q_model, units=coord_text, description= &
                       'coordinates of the fitted model at the sample times')
         call h5%write('/fit/residual', res%resid, units=coord_text, description='data ' &
                       //'minus model (angles wrapped to [-pi, pi))')
      else if (fc%series%positions) then
         call h5%write('/fit/xy_data', fc%series%q, units='m', description='measured ' &
                       //'positions '//xy_names(fc%series%points)//' of the far ends of ' &
                       //'the links observed (origin: the pin)')
         call h5%write('/fit/xy_model', res%q_model, units='m', description='positions ' &
                       //'of the fitted model at the sample times')
         call h5%write('/fit/residual', res%resid, units='m', description='data minus ' &
                       //'model ('//xy_names(fc%series%points)//')')
      else if (fc%series%relative) then   ! the data as read: the round trip is exact
         call h5%write('/fit/q_data', fc%series%raw, units='rad', description='measured ' &
                       //'relative angles phi_i as read (phi_1 from the hanging position, ' &
                       //'phi_i of link i against link i - 1)')
         call h5%writeattr('/fit/q_data', 'angles', 'relative')
         call h5%write('/fit/q_model', res%q_model, units='rad', description='angles of ' &
                       //'the fitted model at the sample times, from the horizontal x axis')
         call h5%writeattr('/fit/q_model', 'angles', 'absolute')
         call h5%write('/fit/residual', res%resid, units='rad', description='data minus ' &
                       //'model in absolute angles, wrapped to [-pi, pi)')
      else
         call h5%write('/fit/q_data', fc%series%q, units='rad', description='measured ' &
                       //'angles q_i from the horizontal x axis (theta - pi/2 for theta ' &
                       //'columns)')
         call h5%writeattr('/fit/q_data', 'angles', 'absolute')
         call h5%write('/fit/q_model', res%q_model, units='rad', description='angles of ' &
                       //'the fitted model at the sample times')
         call h5%writeattr('/fit/q_model', 'angles', 'absolute')
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
      call write_fit_attributes(h5, fc, res, joined)
      call h5%close(error)
   end subroutine write_fit

   !> The attributes of /fit and of the root: the fit's statistics, the model.
   subroutine write_fit_attributes(h5, fc, res, joined)
      type(h5file_t), intent(inout) :: h5           !! the open file
      type(fit_config_t), intent(in) :: fc          !! configuration
      type(fit_result_t), intent(in) :: res         !! estimates and statistics
      character(len=*), intent(in) :: joined        !! the parameters' names
      integer :: n
      n = res%n
      call h5%writeattr('/fit', 'parameters', joined)
      call h5%writeattr('/fit', 'rms_residual', res%rms)
      call h5%writeattr('/fit', 'sigma', res%sigma)
      call h5%writeattr('/fit', 'dof', res%dof)
      call h5%writeattr('/fit', 't95', res%t95)
      call h5%writeattr('/fit', 'iterations', res%iterations)
      call h5%writeattr('/fit', 'stages', res%stages)
      call h5%writeattr('/fit', 'converged', merge(1, 0, res%converged))
      call h5%writeattr('/fit', 'horizon_tolerance', res%tolerance)
      call h5%writeattr('/fit', 'work', res%work)
      if (allocated(fc%tolerance_rule)) &
         call h5%writeattr('/fit', 'horizon_tolerance_rule', fc%tolerance_rule)
      call h5%writeattr('/fit', 'horizon_censored', merge(1, 0, res%horizon_censored))
      call h5%writeattr('/fit', 'has_after', merge(1, 0, res%has_after))
      call h5%writeattr('/fit', 'input', fc%input)
      if (fc%run%torque%active()) then   ! the joint torques applied to the model
         call h5%writeattr('/', 'torque', fc%run%torque%text())
         if (allocated(fc%run%torque_file)) &
            call h5%writeattr('/', 'torque_file', fc%run%torque_file)
      end if
      if (fc%model_coords) then
         call h5%writeattr('/fit', 'observations', 'coordinates')
         call h5%writeattr('/fit', 'n_coordinates', fc%series%n)
         call h5%writeattr('/fit', 'coordinate_labels', coordinates_joined(fc, ':', ' '))
      else if (fc%series%positions) then
         call h5%writeattr('/fit', 'observations', 'positions')
         ! the points of xy_data, xy_model and residual, in their order ('1 2'; '2': the
         ! tip of two links only)
         call h5%writeattr('/fit', 'observed_points', points_text(fc%series%points))
         if (allocated(res%mirror)) call h5%writeattr('/fit', 'mirror', res%mirror)
      else
         call h5%writeattr('/fit', 'observations', 'angles')
         if (fc%series%relative) then
            call h5%writeattr('/fit', 'angle_columns', 'phi')
         else
            call h5%writeattr('/fit', 'angle_columns', trim(merge('theta', 'q    ', &
                              fc%series%theta)))
         end if
         if (fc%series%theta .or. fc%series%degrees) &
            call h5%writeattr('/fit', 'estimate_in_data_convention', data_convention(fc, res))
      end if
      call write_fit_root(h5, fc, 'completed')
      if (fc%model_coords) then
         call h5%writeattr('/', 'fit_parameters', joined_names(fc%fit_names))
      else
         call h5%writeattr('/', 'links', n)
         call h5%writeattr('/', 'm', fc%run%m(:n))
         call h5%writeattr('/', 'l', fc%run%l(:n))
         call h5%writeattr('/', 'damping', fc%run%damping(:n))
         call h5%writeattr('/', 'fit_damping', merge(1, 0, fc%fit_damping))
      end if
   end subroutine write_fit_attributes

   !> The root attributes of every fit file: the command, the version, the method
   !> and its tolerances, the model with its parameters and body, and `status`
   !> ('completed', or why the fit stopped).
   subroutine write_fit_root(h5, fc, status)
      type(h5file_t), intent(inout) :: h5           !! the open file
      type(fit_config_t), intent(in) :: fc          !! configuration
      character(len=*), intent(in) :: status        !! 'completed' or the failure
      call h5%writeattr('/', 'command', 'fit')
      call h5%writeattr('/', 'version', version)
      call h5%writeattr('/', 'method', fc%run%method)
      call h5%writeattr('/', 'rtol', fc%run%rtol)
      call h5%writeattr('/', 'atol', fc%run%atol)
      ! the model with its fixed values (the fitted ones at their first guess; a
      ! completed fit's estimates are in /fit/estimate)
      call h5%writeattr('/', 'model', fc%run%spec%model_name())
      call record_model(h5, fc%run%model)
      call h5%writeattr('/', 'status', status)
   end subroutine write_fit_root

   !> '2 links' for the pendulum, 'model elastic (r, phi)' for others.
   function model_text(fc) result(s)
      type(fit_config_t), intent(in) :: fc  !! configuration with the model built
      character(len=:), allocatable :: s
      character(len=16), allocatable :: cn(:)
      integer :: i
      if (.not. fc%model_coords) then
         s = to_str(fc%series%n)//trim(merge(' link ', ' links', fc%series%n == 1))
         return
      end if
      cn = coordinate_units(fc, -1)
      s = 'model '//fc%run%model_name//' ('//trim(cn(1))
      do i = 2, size(cn)
         s = s//', '//trim(cn(i))
      end do
      s = s//')'
   end function model_text

   !> The model's coordinates with their units: 'r:m phi:rad' with (':', ' ') (the
   !> labels of scripts/plot_fit.sh), 'r in m, phi in rad' with (' in ', ', ').
   function coordinates_joined(fc, between, sep) result(s)
      type(fit_config_t), intent(in) :: fc  !! configuration with the model built
      character(len=*), intent(in) :: between, sep  !! name-unit, coordinate separators
      character(len=:), allocatable :: s
      character(len=16), allocatable :: cn(:), cu(:)
      integer :: i
      cn = coordinate_units(fc, -1)
      cu = coordinate_units(fc, 0)
      s = ''
      do i = 1, size(cn)
         if (i > 1) s = s//sep
         s = s//trim(cn(i))//between//trim(cu(i))
      end do
   end function coordinates_joined
end module dpend_fit_command
