!> Output of `dpend study`: the HDF5 file (layout in docs/study-hdf5.md), the
!> verdicts, the Markdown summary, and the command that runs it all and draws
!> the figures with scripts/plot_study.sh.
module dpend_study_command
   use, intrinsic :: iso_fortran_env, only: output_unit, compiler_version, compiler_options
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model
   use dpend_version, only: version
   use dpend_fit, only: fit_t
   use dpend_output, only: output_t, check_output_path
   use dpend_integrator, only: stat_ok
   use dpend_os, only: host_name, cpu_model, executable_path, make_directories, &
                           find_script, &
                           directory_of, run_program, io_failure_reason, path_kind, &
                           path_missing, base_name, make_temp_file, remove_file, echo_to_stderr
   use dpend_study_settings, only: study_config_t, case_index, study_namelist, balance_case
   use dpend_study_settings, only: study_model_name, default_model_study, case_model
   use dpend_model, only: model_t
   use dpend_integrator, only: status_message
   use dpend_study, only: study_result_t, sweep_t, run_study, mode_step, mode_tol, reference_t
   use dpend_study, only: roundoff_t, tao_sweep_t
   use dpend_cli, only: to_str, arg_t
   use dpend_study_verdicts, only: verdicts_t, study_verdicts, sweep_index, order_ok, &
                                   drift_ok, drift_judged, drift_failed, brouwer_tol, fmt
   implicit none
   private
   public :: run_study_command, write_study_h5, study_summary
   public :: summary_path

contains

   ! ================================================================ command

   !> Run the study, write the file and summary, draw the figures; `quiet`: print of
   !> the summary only its last line (the files written).
   !> The error's kind says whether the input was refused (nothing written) or
   !> the run started and failed (exit status 1).
   subroutine run_study_command(cfg, quiet, error)
      type(study_config_t), intent(in) :: cfg           !! validated configuration
      logical, intent(in) :: quiet                      !! --quiet
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical :: failed
      call run_study_command_body(cfg, quiet, error, failed)
      if (allocated(error) .and. failed) call run_failure(error)
   end subroutine run_study_command

   !> Run the study of `cfg` (validated): write the HDF5 file and the summary,
   !> print the summary, draw the figures. `error` with `failed` false: invalid
   !> output (nothing written); with `failed` true: the study ran but a later
   !> stage (writing, figures) failed.
   subroutine run_study_command_body(cfg, quiet, error, failed)
      type(study_config_t), intent(in) :: cfg           !! validated configuration
      logical, intent(in) :: quiet                      !! the summary's last line only
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical, intent(out) :: failed                    !! the study ran, then failed
      type(study_result_t) :: res
      type(output_t) :: h5_out, md_out
      character(len=:), allocatable :: text, md, script, fig_dir, exe, errlog
      integer :: gone
      type(arg_t) :: argv(7)
      integer :: unit, stat
      character(len=512) :: msg
      failed = .false.
      ! every output path is checked, and its temporary file created, before the study
      if (len_trim(cfg%output) == 0) then
         call fatal_error(error, 'invalid --output: empty file name')
         return
      end if
      md = summary_path(cfg%output)
      call check_output_path(cfg%output, cfg%force, error)
      if (.not. allocated(error)) call check_output_path(md, cfg%force, error, &
                                                          '--output (its summary)')
      ! refused only because the directory is missing: the study makes it (out/study by
      ! default)
      if (allocated(error) .and. len(base_name(cfg%output)) > 0 .and. &
          path_kind(directory_of(cfg%output), .true.) == path_missing) then
         deallocate (error)
         call make_directories(directory_of(cfg%output), error)
         if (allocated(error)) then
            error%message = 'invalid --output: '//error%message
            return
         end if
      end if
      if (allocated(error)) return
      call h5_out%begin(cfg%output, cfg%force, error)
      if (.not. allocated(error)) call md_out%begin(md, cfg%force, error, &
                                                     '--output (its summary)')
      if (allocated(error)) then
         call h5_out%discard()
         return
      end if

      call run_study(cfg, res)
      failed = .true.
      text = study_summary(cfg, res)
      call write_study_h5(cfg, res, h5_out%temp, error)
      if (.not. allocated(error)) then
         open (newunit=unit, file=md_out%temp, status='replace', action='write', &
               iostat=stat, iomsg=msg)
         if (stat == 0) write (unit, '(a)', iostat=stat, iomsg=msg) text
         if (stat == 0) then
            close (unit, iostat=stat, iomsg=msg)
         else
            close (unit)
         end if
         if (stat /= 0) call fatal_error(error, "cannot write the summary '"//md//"': "// &
                                         io_failure_reason(md_out%temp, trim(msg)))
      end if
      if (.not. allocated(error)) call h5_out%commit(error)
      if (.not. allocated(error)) call md_out%commit(error)
      call h5_out%explain(error)
      call md_out%explain(error)
      call h5_out%discard()
      call md_out%discard()
      if (allocated(error)) return
      if (.not. quiet) write (output_unit, '(a)') text
      if (.not. cfg%figures) then
         write (output_unit, '(a)') "dpend study: wrote '"//cfg%output//"' and '"//md//"'"
         failed = .false.
         return
      end if
      script = find_script('plot_study.sh')
      fig_dir = directory_of(cfg%output)
      if (len(script) == 0) then
         call fatal_error(error, 'figures not drawn: scripts/plot_study.sh not found (set '// &
                          'DPEND_ROOT to the dpend source tree); the .h5 and summary are written')
         return
      end if
      ! an argument vector, no shell: names are passed as they are
      exe = executable_path()
      ! component by component (gfortran 12 mangles an array constructor of
      ! structure constructors with deferred-length components)
      argv(1)%s = 'env'; argv(2)%s = 'DPEND='//exe
      argv(3)%s = 'DPEND_PLOT_QUIET='//trim(merge('1', '0', quiet)); argv(4)%s = 'bash'
      argv(5)%s = script; argv(6)%s = cfg%output; argv(7)%s = fig_dir
      ! gnuplot's messages go to a file, shown only when the figures fail
      if (make_temp_file(fig_dir//'/.'//base_name(cfg%output)//'.plot-', errlog) /= 0) &
         errlog = ''
      if (len(errlog) > 0) then
         call run_program(argv, stat, error, stderr_path=errlog)
         if (stat /= 0) call echo_to_stderr(errlog, 65536)
         gone = remove_file(errlog)
      else
         call run_program(argv, stat, error)
      end if
      if (allocated(error)) return
      if (stat /= 0) then
         call fatal_error(error, 'figures failed ('//script//', exit status '//to_str(stat)// &
                          '); the .h5 and summary are written: rerun scripts/plot_study.sh '// &
                          'with the file and the figure directory')
         return
      end if
      ! the closing line last (--quiet: the only one)
      write (output_unit, '(a)') "dpend study: wrote '"//cfg%output//"' and '"//md// &
         "', figures in '"//fig_dir//"'"
      failed = .false.
   end subroutine run_study_command_body

   !> The summary file next to the HDF5 file: FILE.h5 → FILE.md.
   pure function summary_path(output) result(path)
      character(len=*), intent(in) :: output  !! HDF5 file name
      character(len=:), allocatable :: path
      integer :: n
      n = len_trim(output)
      if (n > 3) then
         if (output(n - 2:n) == '.h5') then
            path = output(:n - 3)//'.md'
            return
         end if
      end if
      path = trim(output)//'.md'
   end function summary_path

   ! ================================================================ summary

   !> The Markdown summary: verdicts and tables.
   function study_summary(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      md = summary_head(cfg, res)//summary_methods(cfg, res)//summary_orders(cfg, res)// &
           summary_adaptive(cfg, res)//summary_roundoff(cfg, res)//summary_tao(cfg, res)// &
           summary_cases(cfg, res)
   end function study_summary

   !> The summary's title line, what the errors are, and the verdicts.
   function summary_head(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      type(verdicts_t) :: v
      integer :: ic, id
      character(len=8) :: date
      character(len=10) :: time
      character(len=:), allocatable :: upright, unjudged
      v = study_verdicts(cfg, res)
      id = case_index(cfg, cfg%drift_case)
      call date_and_time(date, time)
      md = '# dpend energy-conservation study'//nl//nl// &
           'dpend '//version//', '//date(1:4)//'-'//date(5:6)//'-'//date(7:8)//' '// &
           time(1:2)//':'//time(3:4)//', host '//host_name()//', '//cpu_model()//', '// &
           to_str(res%threads)//trim(merge(' thread ', ' threads', res%threads == 1))//', '// &
           fmt(res%wall_total, 'f0.1')//' s'
      if (cfg%quick) md = md//' (**--quick**: shortened long runs)'
      upright = 'both links'
      if (any([(size(cfg%cases(ic)%q0) /= 2, ic=1, size(cfg%cases))])) upright = 'every link'
      if (default_model_study(cfg)) then
         upright = 'the potential energy with '//upright//' upright'
      else
         upright = 'the energy unit of model '//study_model_name(cfg)//' (its energy_scale)'
      end if
      md = md//nl//nl
      if (.not. default_model_study(cfg)) md = md//'Model '//study_model_name(cfg)// &
         ': q = ('//state_units(cfg, 'names')//') ['//state_units(cfg, 'q')//'], q̇ ['// &
         state_units(cfg, 'qdot')//']. '
      md = md// &
           'Relative energy error |H(t) − H(0)| / E_s with E_s = |H(0)|, or, when H(0) ≈ 0, '// &
           upright//' (see the cases). Global error: '// &
           'max |Δq|, |Δq̇| ['//state_units(cfg, 'both')//'] over '//to_str(cfg%n_check)// &
           ' checkpoints up to '// &
           't = '//pretty(cfg%t_short)//' s against '//cfg%ref_method//' at h = '// &
           fmt(cfg%ref_dt, 'es8.2')//' s.'
      ! the unit: the times here are in s; with --time-unit natural also the unit's value
      md = md//' Times in s'
      if (trim(cfg%time_unit) == 'natural') then
         md = md//' (given in '//trim(cfg%time_unit_name)//' = '//pretty(cfg%time_scale)// &
              ' s: t_short = '//pretty(cfg%t_short/cfg%time_scale)//' '// &
              trim(cfg%time_unit_name)//')'
      else
         md = md//' (as given)'
      end if
      md = md//'.'
      if (any([(balance_case(cfg, ic), ic=1, size(cfg%cases))])) md = md//' In a damped or '// &
         'driven case the energy error is that of the energy balance, |E(t) − E(0) + '// &
         'W_friction − W_support| / E_s, the works integrated along the solution by the '// &
         'same method (section Energy balance); the drift verdict is not applied to it.'
      md = md//nl//nl
      unjudged = 'too short to judge:'
      if (balance_case(cfg, id)) unjudged = 'not applied:'
      if (index(v%drift_text, 'failed (case') > 0) unjudged = 'not judged:'
      md = md//'## Verdicts'//nl//nl// &
           '- orders: '//mark(v%orders)//' '//v%orders_text//nl// &
           '- drift: '//verdict(v%drift, v%drift_judged, unjudged)// &
           ' '//v%drift_text//nl// &
           '- roundoff: '//verdict(v%roundoff, v%roundoff_run, 'not run:')//' '// &
           v%roundoff_text//nl//nl
   end function summary_head

   !> The main table: orders on the order case, drift and cost on the drift case.
   function summary_methods(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: im, io, id, s, so, k
      real(dp) :: per_step
      io = case_index(cfg, cfg%order_case)
      id = case_index(cfg, cfg%drift_case)
      ! ---- main table
      md = '## Methods'//nl//nl// &
           'Orders: slopes of the global error and of the maximum energy error up to '// &
           't_short against the step, fixed steps (dopri5, dop853 with the error control off), '// &
           'case `'//cfg%order_case//'`. Drift: exponent of the energy error in t over the '// &
           'last '//fmt(cfg%drift_decades, 'f0.1')//' decades of the long run at the middle '// &
           'step, case `'//cfg%drift_case//'`; long-run slope: maximum energy error over the '// &
           'long run against the step; cost: the long run at the middle step.'//nl//nl// &
           '| method | p | order (global) | order (energy) | drift exponent | long-run slope |'// &
           ' h_mid [s] | steps | max energy error | rhs/step | iter/step | µs/step | |'//nl// &
           '|---|---|---|---|---|---|---|---|---|---|---|---|---|'//nl
      do im = 1, size(cfg%methods)
         so = sweep_index(res, io, cfg%methods(im)%name, mode_step)
         s = sweep_index(res, id, cfg%methods(im)%name, mode_step)
         if (so == 0 .or. s == 0) cycle
         associate (o => res%sweeps(so), d => res%sweeps(s))
            k = d%mid
            per_step = d%wall_long(k)/real(max(d%long_steps(k), 1_i8), dp)
            md = md//'| '//d%method//' | '//to_str(d%order)//' | '//slope(o%fit_global)//' | ' &
                 //slope(o%fit_energy)//' | '//num(d%drift(k), 'f0.2') &
                 //trim(merge('                     ', ' (too short to judge)', drift_judged(d) &
                              .or. drift_failed(d) .or. balance_case(cfg, id))) &
                 //trim(merge(' (the run failed)', '                 ', drift_failed(d))) &
                 //trim(merge(' (not applied)', '              ', balance_case(cfg, id))) &
                 //' | ' &
                 //slope(d%fit_energy_long)//' | '//num(d%x(k), 'es8.2')//' | ' &
                 //to_str(d%long_steps(k))//' | '//num(d%energy_long(k), 'es8.2')//' | ' &
                 //ratio(d%long_rhs(k), d%long_steps(k))//' | ' &
                 //ratio(d%long_iter(k), d%long_steps(k))//' | ' &
                 //num(1.0e6_dp*per_step, 'f0.2')//' | ' &
                 //mark(order_ok(o%fit_global, o%order) .and. order_ok(o%fit_energy, o%order) &
                        .and. (drift_ok(d) .or. .not. drift_judged(d) .or. &
                               balance_case(cfg, id)))//' |'//nl
         end associate
      end do
   end function summary_methods

   !> The orders of every method in every case, and the energy balance of the damped
   !> and driven cases (when there are any).
   function summary_orders(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: im, ic, s
      md = ''
      md = md//nl//'## Orders in every case'//nl//nl// &
           'global / energy (fixed steps, t ≤ '//pretty(cfg%t_short)//' s); drift exponent '// &
           'at the middle step'//nl//nl//'| method | p |'
      do ic = 1, size(cfg%cases)
         md = md//' '//cfg%cases(ic)%name//' |'
      end do
      md = md//nl//'|---|---|'//repeat('---|', size(cfg%cases))//nl
      do im = 1, size(cfg%methods)
         s = sweep_index(res, 1, cfg%methods(im)%name, mode_step)
         if (s == 0) cycle
         md = md//'| '//cfg%methods(im)%name//' | '//to_str(res%sweeps(s)%order)//' |'
         do ic = 1, size(cfg%cases)
            s = sweep_index(res, ic, cfg%methods(im)%name, mode_step)
            associate (w => res%sweeps(s))
               md = md//' '//slope(w%fit_global)//' / '//slope(w%fit_energy)//'; '// &
                    num(w%drift(w%mid), 'f0.2')//' |'
            end associate
         end do
         md = md//nl
      end do
      ! ---- the energy balance of the damped and driven cases
      if (any([(balance_case(cfg, ic), ic=1, size(cfg%cases))])) then
         md = md//nl//'## Energy balance'//nl//nl// &
              'Damped and driven cases: |E(t) − E(0) + W_friction − W_support| / E_s. Slope '// &
              'of its maximum up to t_short against the step (fixed steps), and its maximum '// &
              'over the long run at the middle step.'//nl//nl//'| method | p |'
         do ic = 1, size(cfg%cases)
            if (balance_case(cfg, ic)) md = md//' '//cfg%cases(ic)%name//' |'
         end do
         md = md//nl//'|---|---|'//repeat('---|', count([(balance_case(cfg, ic), &
                                                         ic=1, size(cfg%cases))]))//nl
         do im = 1, size(cfg%methods)
            s = sweep_index(res, 1, cfg%methods(im)%name, mode_step)
            if (s == 0) cycle
            md = md//'| '//cfg%methods(im)%name//' | '//to_str(res%sweeps(s)%order)//' |'
            do ic = 1, size(cfg%cases)
               if (.not. balance_case(cfg, ic)) cycle
               s = sweep_index(res, ic, cfg%methods(im)%name, mode_step)
               associate (w => res%sweeps(s))
                  md = md//' '//slope(w%fit_energy)//'; '//num(w%energy_long(w%mid), &
                                                               'es8.2')//' |'
               end associate
            end do
            md = md//nl
         end do
      end if
   end function summary_orders

   !> The tolerance sweeps of the adaptive methods (when there are any).
   function summary_adaptive(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: s
      md = ''
      if (any(res%sweeps%mode == mode_tol)) then
         md = md//nl//'## Adaptive methods over tolerances'//nl//nl// &
              'atol = '//pretty(cfg%atol_ratio)//' rtol. Order against the mean accepted '// &
              'step t_short/n_steps (global error) and slope of the global error against rtol '// &
              '(tolerance proportionality: 1 is ideal); drift at the middle tolerance.'//nl//nl// &
              '| method | case | rtol | order vs mean step | error vs rtol | drift exponent |'// &
              ' rejected/accepted |'//nl//'|---|---|---|---|---|---|---|'//nl
         do s = 1, size(res%sweeps)
            associate (w => res%sweeps(s))
               if (w%mode /= mode_tol) cycle
               md = md//'| '//w%method//' | '//cfg%cases(w%icase)%name//' | '// &
                    num(minval(w%x), 'es7.1')//' … '//num(maxval(w%x), 'es7.1')//' | '// &
                    slope(w%fit_global)//' | '//slope(w%fit_tolerance)//' | '// &
                    num(w%drift(w%mid), 'f0.2')//' | '// &
                    num(real(sum(w%long_rejected), dp)/real(max(sum(w%long_steps), 1_i8), dp), &
                        'f0.3')//' |'//nl
            end associate
         end do
      end if
   end function summary_adaptive

   !> The roundoff runs (Brouwer's law; when made).
   function summary_roundoff(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: i, k
      md = ''
      if (size(res%roundoff) > 0) then
         md = md//nl//"## Roundoff (Brouwer's law)"//nl//nl// &
              'RMS over '//to_str(cfg%ro_runs)//' runs (case `'//cfg%ro_case// &
              '`, q0 perturbed by '// &
              'multiples of '//fmt(cfg%ro_perturb, 'es8.2')//' rad) of (H − H0)/E_s, H in '// &
              'quadruple precision at the compensated state; exponent fitted in t ≥ '// &
              pretty(cfg%ro_fit_t_min)//' s.'//nl//nl// &
              '| method | h [s] | steps | exponent, compensated | exponent, plain |'// &
              ' RMS at the end, compensated | plain | |'//nl// &
              '|---|---|---|---|---|---|---|---|'//nl
         do i = 1, size(res%roundoff)
            associate (ro => res%roundoff(i))
               k = size(ro%steps)
               md = md//'| '//ro%method//' | '//num(ro%dt, 'es8.2')//' | '// &
                    to_str(ro%steps(k))//' | '//slope(ro%fit(1))//' | '//slope(ro%fit(2))// &
                    ' | '//num(ro%rms(k, 1), 'es8.2')//' | '//num(ro%rms(k, 2), 'es8.2')// &
                    ' | '//mark(ro%fit(1)%ok .and. abs(ro%fit(1)%slope - 0.5_dp) <= brouwer_tol) &
                    //' |'//nl
            end associate
         end do
      end if
   end function summary_roundoff

   !> Tao's binding constant (when run).
   function summary_tao(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: i, k
      md = ''
      if (size(res%tao) > 0) then
         md = md//nl//"## Tao's binding constant"//nl//nl// &
              'h = '//fmt(cfg%tao_dt, 'es8.2')//' s to t = '//pretty(cfg%tao_t_end)// &
              ' s, case `'//cfg%tao_case//'`.'//nl//nl// &
              '| method | ω range [1/s] | best ω | its max energy error | ω ≈ 20/s: '// &
              'max energy error | global error | failed runs |'//nl// &
              '|---|---|---|---|---|---|---|'//nl
         do i = 1, size(res%tao)
            associate (ts => res%tao(i))
               k = best_index(ts%energy_max)
               md = md//'| '//ts%method//' | '//pretty(ts%omega(1))//' … '// &
                    pretty(ts%omega(size(ts%omega)))//' | '
               if (k > 0) then
                  md = md//pretty(ts%omega(k))//' | '//num(ts%energy_max(k), 'es8.2')
               else
                  md = md//'– | –'
               end if
               k = minloc(abs(log(ts%omega/20.0_dp)), 1)
               md = md//' | '//pretty(ts%omega(k))//': '//num(ts%energy_max(k), 'es8.2')// &
                    ' | '//num(ts%global_error(k), 'es8.2')// &
                    ' | '//to_str(count(ts%stat /= stat_ok))//' |'//nl
            end associate
         end do
      end if
   end function summary_tao

   !> The cases: initial state, energy, its unit and the reference check.
   function summary_cases(cfg, res) result(md)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: md
      character(len=*), parameter :: nl = new_line('a')
      integer :: ic
      md = ''
      md = md//nl//'## Cases'//nl//nl// &
           '| case | q0 ['//state_units(cfg, 'q')//'] | q̇0 ['//state_units(cfg, 'qdot')// &
           '] | H(0) [J] | E_s [J] | reference check |'//nl// &
           '|---|---|---|---|---|---|'//nl
      do ic = 1, size(cfg%cases)
         associate (cs => cfg%cases(ic), ref => res%refs(ic))
            md = md//'| '//cs%name//trim(merge(' (damped or driven)', '                   ', &
                                               balance_case(cfg, ic)))//' | '// &
                 nums(cs%q0, 'f0.4')//' | '// &
                 nums(cs%w0, 'f0.3')//' | '//num(ref%e0, 'f0.4')//' | '// &
                 num(ref%e_scale, 'f0.4')
            if (abs(abs(ref%e0) - ref%e_scale) <= 1e-12_dp*ref%e_scale) then
               md = md//' = \|H(0)\|'
            else if (default_model_study(cfg)) then
               md = md//' (V, links upright)'
            else
               md = md//' (energy_scale)'
            end if
            md = md//' | '//cfg%check_method//': '//check_text(ref)//' |'//nl
         end associate
      end do
   end function summary_cases

   !> The reference check of a case in words: the largest deviation of the check
   !> method from the reference, or which of the two runs failed and why.
   function check_text(ref) result(s)
      type(reference_t), intent(in) :: ref  !! the case's reference
      character(len=:), allocatable :: s
      if (ref%stat == stat_ok) then
         s = num(ref%check_difference, 'es8.2')
      else if (ref%check_stat /= stat_ok .and. ref%stat == ref%check_stat) then
         s = 'check run failed ('//status_message(ref%check_stat)//')'
      else
         s = 'reference run failed ('//status_message(ref%stat)//')'
      end if
   end function check_text

   !> Units of the study's states, for the texts: 'q' (those of q, comma separated),
   !> 'qdot', 'both' ('q, qdot') or 'names' (the coordinates' names); the double
   !> pendulum's and the chain's: rad, rad/s.
   function state_units(cfg, which) result(s)
      type(study_config_t), intent(in) :: cfg  !! configuration
      character(len=*), intent(in) :: which    !! 'q', 'qdot', 'both' or 'names'
      character(len=:), allocatable :: s
      class(model_t), allocatable :: model
      character(len=:), allocatable :: name, units, p_units, q, qd, names
      integer :: i
      if (default_model_study(cfg)) then
         q = 'rad'; qd = 'rad/s'; names = 'q1, q2'
      else
         call case_model(cfg, 1, model)
         q = ''; qd = ''; names = ''
         do i = 1, model%n_dof()
            call model%coordinate(i, name, units, p_units)
            if (i > 1) then
               q = q//', '; qd = qd//', '; names = names//', '
            end if
            q = q//units; qd = qd//units//'/s'; names = names//name
         end do
      end if
      select case (which)
      case ('q'); s = q
      case ('qdot'); s = qd
      case ('names'); s = names
      case default; s = q//', '//qd
      end select
   end function state_units

   pure integer function best_index(v) result(k)
      real(dp), intent(in) :: v(:)
      integer :: i
      k = 0
      do i = 1, size(v)
         if (.not. ieee_is_finite(v(i))) cycle
         if (k == 0) then
            k = i
         else if (v(i) < v(k)) then
            k = i
         end if
      end do
   end function best_index

   !> ✓ or ✗ for an experiment that ran (`ran`), else `other` ("not run:", ...).
   function verdict(ok, ran, other) result(s)
      logical, intent(in) :: ok         !! the check passed
      logical, intent(in) :: ran        !! there was something to check
      character(len=*), intent(in) :: other  !! the text instead of a mark
      character(len=:), allocatable :: s
      if (ran) then
         s = mark(ok)
      else
         s = other
      end if
   end function verdict

   function mark(ok) result(s)
      logical, intent(in) :: ok
      character(len=:), allocatable :: s
      if (ok) then
         s = '✓'
      else
         s = '✗'
      end if
   end function mark

   function slope(fit) result(s)
      type(fit_t), intent(in) :: fit
      character(len=:), allocatable :: s
      if (fit%ok) then
         s = fmt(fit%slope, 'f0.2')
      else
         s = '–'
      end if
   end function slope

   !> The values of x, comma separated.
   function nums(x, f) result(s)
      real(dp), intent(in) :: x(:)
      character(len=*), intent(in) :: f
      character(len=:), allocatable :: s
      integer :: k
      s = num(x(1), f)
      do k = 2, size(x)
         s = s//', '//num(x(k), f)
      end do
   end function nums

   function num(x, f) result(s)
      real(dp), intent(in) :: x
      character(len=*), intent(in) :: f
      character(len=:), allocatable :: s
      if (ieee_is_finite(x)) then
         s = fmt(x, f)
      else
         s = '–'
      end if
   end function num

   !> Up to 4 significant digits without trailing zeros (1e-3 ≤ |x| < 1e5),
   !> else scientific notation.
   function pretty(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      integer :: d
      if (.not. ieee_is_finite(x)) then
         s = '–'
      else if (x == 0.0_dp) then
         s = '0'
      else if (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e5_dp) then
         d = max(0, 3 - floor(log10(abs(x))))
         write (buf, '(f0.'//to_str(d)//')') x
         s = trim(adjustl(buf))
         if (index(s, '.') > 0) then
            do while (s(len(s):len(s)) == '0')
               s = s(:len(s) - 1)
            end do
            if (s(len(s):len(s)) == '.') s = s(:len(s) - 1)
         end if
         if (s(1:1) == '.') s = '0'//s
         if (len(s) > 1) then
            if (s(1:2) == '-.') s = '-0'//s(2:)
         end if
      else
         s = fmt(x, 'es9.2')
      end if
   end function pretty

   function ratio(a, b) result(s)
      integer(i8), intent(in) :: a, b
      character(len=:), allocatable :: s
      if (b > 0) then
         s = fmt(real(a, dp)/real(b, dp), 'f0.1')
      else
         s = '–'
      end if
   end function ratio



   ! ================================================================== HDF5

   !> Write everything to `filename` (layout: docs/study-hdf5.md).
   subroutine write_study_h5(cfg, res, filename, error)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=*), intent(in) :: filename
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      integer :: ic, s, i
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      ! the writes below pass no `error`: h5 keeps the first failure, the later
      ! writes do nothing, and close hands it over
      call write_h5_config(h5, cfg)
      call write_h5_root(h5, cfg, res)
      do ic = 1, size(cfg%cases)
         call write_h5_case(h5, cfg, res, ic)
      end do
      do s = 1, size(res%sweeps)
         call write_sweep(h5, cfg, res%sweeps(s))
      end do
      do i = 1, size(res%roundoff)
         call write_h5_roundoff(h5, cfg, res%roundoff(i))
      end do
      do i = 1, size(res%tao)
         call write_h5_tao(h5, cfg, res%tao(i))
      end do
      call write_h5_summary(h5, cfg, res)
      call h5%close(error)
   end subroutine write_study_h5

   !> /config: the effective namelist, the model's parameters, the study's settings.
   subroutine write_h5_config(h5, cfg)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      integer :: ic, n
      call h5%write('/config/namelist', study_namelist(cfg), units='', description= &
         'the effective configuration as &pendulum and &study namelists')
      if (default_model_study(cfg)) then
         call h5%writeattr('/config', 'm1', cfg%m(1))
         call h5%writeattr('/config', 'm2', cfg%m(2))
         call h5%writeattr('/config', 'l1', cfg%l(1))
         call h5%writeattr('/config', 'l2', cfg%l(2))
         call h5%writeattr('/config', 'g', cfg%g)
      else   ! the model of the cases (&model) and its parameters, named by the model
         call h5%writeattr('/config', 'model', study_model_name(cfg))
         call write_model_parameters()
      end if
      ! the per-link parameters when a case is a chain of other than two links
      n = 2
      do ic = 1, size(cfg%cases)
         n = max(n, size(cfg%cases(ic)%q0))
      end do
      if (any([(size(cfg%cases(ic)%q0) /= 2, ic=1, size(cfg%cases))])) then
         call h5%writeattr('/config', 'm', cfg%m(:n))
         call h5%writeattr('/config', 'l', cfg%l(:n))
      end if
      call h5%writeattr('/config', 't_short', cfg%t_short)
      call h5%writeattr('/config', 'n_check', cfg%n_check)
      call h5%writeattr('/config', 'order_case', cfg%order_case)
      call h5%writeattr('/config', 'drift_case', cfg%drift_case)
      call h5%writeattr('/config', 'ro_case', cfg%ro_case)
      call h5%writeattr('/config', 'tao_case', cfg%tao_case)
      call h5%writeattr('/config', 'drift_decades', cfg%drift_decades)
      call h5%writeattr('/config', 'ref_method', cfg%ref_method)
      call h5%writeattr('/config', 'ref_dt', cfg%ref_dt)
      call h5%writeattr('/config', 'check_method', cfg%check_method)
      call h5%writeattr('/config', 'check_rtol', cfg%check_rtol)
      call h5%writeattr('/config', 'atol_ratio', cfg%atol_ratio)
      call h5%writeattr('/config', 'quick', merge(1, 0, cfg%quick))
   contains
      !> The model's parameters as attributes of /config (model of case 1: every
      !> case has the same).
      subroutine write_model_parameters()
         class(model_t), allocatable :: model
         call case_model(cfg, 1, model)
         call record_model(h5, model, '/config')
      end subroutine write_model_parameters
   end subroutine write_h5_config

   !> Attributes of /: provenance, what the errors are, and the lists the plot
   !> script needs.
   subroutine write_h5_root(h5, cfg, res)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      character(len=:), allocatable :: names
      character(len=8) :: date
      character(len=10) :: time
      integer :: ic, i
      call date_and_time(date, time)
      call h5%writeattr('/', 'program', 'dpend study')
      call h5%writeattr('/', 'version', version)
      call h5%writeattr('/', 'created', date(1:4)//'-'//date(5:6)//'-'//date(7:8)//'T'// &
                time(1:2)//':'//time(3:4)//':'//time(5:6))
      call h5%writeattr('/', 'host', host_name())
      call h5%writeattr('/', 'cpu', cpu_model())
      call h5%writeattr('/', 'compiler', compiler_version())
      call h5%writeattr('/', 'compiler_options', compiler_options())
      call h5%writeattr('/', 'threads', res%threads)
      call h5%writeattr('/', 'wall_time', res%wall_total)
      call h5%writeattr('/', 'energy_error', '|H(t) - H(0)| / E_s, E_s = |H(0)|, or when '// &
                        'H(0) ~ 0 the potential energy with both links upright (per case: '// &
                        'energy_scale); in a damped or driven case (balance = 1) the energy '// &
                        'balance |E(t) - E(0) + W_friction - W_support| / E_s')
      call h5%writeattr('/', 'global_error', 'max over the checkpoints of max(|dq1|, '// &
                        '|dq2|, |dqdot1|, |dqdot2|) ['//state_units(cfg, 'both')// &
                        '] against the reference')
      names = cfg%cases(1)%name
      do ic = 2, size(cfg%cases)
         names = names//' '//cfg%cases(ic)%name
      end do
      call h5%writeattr('/', 'cases', names)
      names = ''
      do ic = 1, size(cfg%cases)
         if (.not. balance_case(cfg, ic)) cycle
         if (len(names) > 0) names = names//' '
         names = names//cfg%cases(ic)%name
      end do
      if (len(names) == 0) names = 'none'
      call h5%writeattr('/', 'balance_cases', names)
      names = cfg%methods(1)%name
      do i = 2, size(cfg%methods)
         names = names//' '//cfg%methods(i)%name
      end do
      call h5%writeattr('/', 'methods', names)
      call h5%writeattr('/', 'order_case', cfg%order_case)
      call h5%writeattr('/', 'drift_case', cfg%drift_case)
      names = ''
      do i = 1, size(res%roundoff)
         if (i > 1) names = names//' '
         names = names//res%roundoff(i)%method
      end do
      if (len(names) == 0) names = 'none'
      call h5%writeattr('/', 'roundoff_methods', names)
      names = ''
      do i = 1, size(res%tao)
         if (i > 1) names = names//' '
         names = names//res%tao(i)%method
      end do
      if (len(names) == 0) names = 'none'
      call h5%writeattr('/', 'tao_methods', names)
   end subroutine write_h5_root

   !> /cases/<case>: the reference at the checkpoints, the initial state and energy.
   subroutine write_h5_case(h5, cfg, res, ic)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      integer, intent(in) :: ic   !! case index
      character(len=:), allocatable :: g
      integer :: n, i
      g = '/cases/'//cfg%cases(ic)%name
      associate (ref => res%refs(ic), cs => cfg%cases(ic))
         call h5%write(g//'/reference/t', ref%t, units='s', &
            description='checkpoint times k t_short/K')
         n = size(cs%q0)
         if (n == 2) then
            call h5%write(g//'/reference/state', ref%y, units=state_units(cfg, 'both'), &
               description='q1, q2, qdot1, qdot2 of the reference at the checkpoints')
         else
            call h5%write(g//'/reference/state', ref%y, units=state_units(cfg, 'both'), &
               description='q1 .. q'//to_str(n)//', qdot1 .. qdot'//to_str(n)// &
               ' of the reference at the checkpoints')
            call h5%writeattr(g, 'links', n)
         end if
         call h5%writeattr(g//'/reference', 'method', cfg%ref_method)
         call h5%writeattr(g//'/reference', 'dt', cfg%ref_dt)
         call h5%writeattr(g//'/reference', 'check_method', cfg%check_method)
         call h5%writeattr(g//'/reference', 'check_rtol', cfg%check_rtol)
         call h5%writeattr(g//'/reference', 'check_difference', ref%check_difference)
         call h5%writeattr(g, 'q0', cs%q0)
         call h5%writeattr(g, 'qdot0', cs%w0)
         call h5%writeattr(g, 'energy0', ref%e0)
         call h5%writeattr(g, 'energy_scale', ref%e_scale)
         if (abs(abs(ref%e0) - ref%e_scale) <= 1e-12_dp*ref%e_scale) then
            call h5%writeattr(g, 'energy_scale_definition', '|H(0)|')
         else if (.not. default_model_study(cfg)) then
            call h5%writeattr(g, 'energy_scale_definition', &
                              'energy_scale of model '//study_model_name(cfg))
         else if (n == 2) then
            call h5%writeattr(g, 'energy_scale_definition', &
                              'potential energy, both links upright')
         else
            call h5%writeattr(g, 'energy_scale_definition', &
                              'potential energy, every link upright')
         end if
         call h5%writeattr(g, 'long_steps', cs%long_steps)
         call h5%writeattr(g, 'balance', merge(1, 0, balance_case(cfg, ic)))
         if (balance_case(cfg, ic)) then
            if (allocated(cs%damping)) then
               call h5%writeattr(g, 'damping', cs%damping)
            else
               call h5%writeattr(g, 'damping', [(0.0_dp, i=1, n)])
            end if
            call h5%writeattr(g, 'support_amplitude', cs%support_amplitude)
            call h5%writeattr(g, 'support_frequency', cs%support_frequency)
            call h5%writeattr(g, 'support_phase', cs%support_phase)
            if (cs%torque%active()) then   ! the torques applied, exactly
               call h5%writeattr(g, 'torque', cs%torque%text())
               call h5%writeattr(g, 'torque_file', cs%torque_file)
               call h5%write(g//'/torque/sample_t', cs%torque%t, units='s', description= &
                             'sample times of the applied joint torques (linear between ' &
                             //'samples)')
               call h5%write(g//'/torque/sample_tau', cs%torque%tau, units='N m', &
                             description='applied joint torques tau_1 .. tau_N at the ' &
                             //'sample times')
            end if
         end if
      end associate
   end subroutine write_h5_case

   !> /roundoff/<method>: the roundoff runs of one method.
   subroutine write_h5_roundoff(h5, cfg, ro)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(roundoff_t), intent(in) :: ro
      real(dp), allocatable :: table(:, :)  ! a transposed copy (no array temporary)
      character(len=:), allocatable :: g
      g = '/roundoff/'//ro%method
      call h5%write(g//'/steps', ro%steps, units='1', &
         description='sample steps (logarithmic)')
      call h5%write(g//'/t', ro%t, units='s', description='times of the sample steps')
      call h5%write(g//'/rms_compensated', ro%rms(:, 1), units='1', description= &
         'RMS over the runs of (H - H(0))/E_s, compensated summation')
      call h5%write(g//'/rms_plain', ro%rms(:, 2), units='1', description= &
         'RMS over the runs of (H - H(0))/E_s, plain summation')
      table = transpose(ro%err(:, :, 1))
      call h5%write(g//'/error_compensated', table, units='1', description= &
         '(H - H(0))/E_s of every run, compensated summation')
      table = transpose(ro%err(:, :, 2))
      call h5%write(g//'/error_plain', table, units='1', description= &
         '(H - H(0))/E_s of every run, plain summation')
      call h5%write(g//'/status_compensated', ro%stat(:, 1), units='1', &
         description='status of every run (0 ok), compensated summation')
      call h5%write(g//'/status_plain', ro%stat(:, 2), units='1', &
         description='status of every run (0 ok), plain summation')
      call h5%write(g//'/wall_compensated', ro%wall(:, 1), units='s', &
         description='wall time of every run, compensated summation')
      call h5%write(g//'/wall_plain', ro%wall(:, 2), units='s', &
         description='wall time of every run, plain summation')
      call h5%writeattr(g, 'dt', ro%dt)
      call h5%writeattr(g, 'runs', cfg%ro_runs)
      call h5%writeattr(g, 'case', cfg%ro_case)
      call h5%writeattr(g, 'perturbation', cfg%ro_perturb)
      call h5%writeattr(g, 'fit_t_min', cfg%ro_fit_t_min)
      call fit_attrs(h5, g, 'exponent_compensated', ro%fit(1))
      call fit_attrs(h5, g, 'exponent_plain', ro%fit(2))
   end subroutine write_h5_roundoff

   !> /tao/<method>: the Tao runs of one method over ω.
   subroutine write_h5_tao(h5, cfg, ts)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(tao_sweep_t), intent(in) :: ts
      character(len=:), allocatable :: g
      g = '/tao/'//ts%method
      call h5%write(g//'/omega', ts%omega, units='1/s', &
         description='binding constants (geometric)')
      call h5%write(g//'/energy_max', ts%energy_max, units='1', &
         description='largest relative energy error up to t_end')
      call h5%write(g//'/energy_final', ts%energy_final, units='1', &
         description='relative energy error at t_end')
      call h5%write(g//'/global_error', ts%global_error, units=state_units(cfg, 'both'), &
         description='global error up to t_short')
      call h5%write(g//'/status', ts%stat, units='1', &
         description='0 ok, else the failure code')
      call h5%writeattr(g, 'dt', cfg%tao_dt)
      call h5%writeattr(g, 't_end', cfg%tao_t_end)
      call h5%writeattr(g, 'case', cfg%tao_case)
   end subroutine write_h5_tao

   !> /summary: the Markdown summary and the verdicts.
   subroutine write_h5_summary(h5, cfg, res)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      type(verdicts_t) :: v
      v = study_verdicts(cfg, res)
      call h5%write('/summary/markdown', study_summary(cfg, res), units='', &
         description='the Markdown summary')
      call h5%writeattr('/summary', 'orders_ok', merge(1, 0, v%orders))
      call h5%writeattr('/summary', 'orders', v%orders_text)
      ! -1: not judged (every long run too short) or not run, as the text says
      call h5%writeattr('/summary', 'drift_ok', merge(merge(1, 0, v%drift), -1, v%drift_judged))
      call h5%writeattr('/summary', 'drift', v%drift_text)
      call h5%writeattr('/summary', 'roundoff_ok', &
                        merge(merge(1, 0, v%roundoff), -1, v%roundoff_run))
      call h5%writeattr('/summary', 'roundoff', v%roundoff_text)
   end subroutine write_h5_summary

   !> One sweep under /cases/<case>/<method>/step or …/tol.
   subroutine write_sweep(h5, cfg, sw)
      type(h5file_t), intent(inout) :: h5
      type(study_config_t), intent(in) :: cfg
      type(sweep_t), intent(in) :: sw
      character(len=:), allocatable :: g
      g = '/cases/'//cfg%cases(sw%icase)%name//'/'//sw%method//'/'// &
          trim(merge('step', 'tol ', sw%mode == mode_step))
      if (sw%mode == mode_step) then
         call h5%write(g//'/h', sw%x, units='s', description='step')
      else
         call h5%write(g//'/rtol', sw%x, units='1', description='relative tolerance')
         call h5%write(g//'/atol', cfg%atol_ratio*sw%x, units=state_units(cfg, 'both'), &
            description='absolute tolerance')
      end if
      call h5%write(g//'/mean_step_short', sw%h_mean_short, units='s', &
         description='t_short / accepted steps of the short run')
      call h5%write(g//'/mean_step_long', sw%h_mean_long, units='s', &
         description='t_long / accepted steps of the long run')
      call h5%write(g//'/global_error', sw%global_error, units=state_units(cfg, 'both'), &
         description='global error up to t_short')
      call h5%write(g//'/energy_max_short', sw%energy_short, units='1', &
         description='largest relative energy error up to t_short')
      call h5%write(g//'/energy_max_long', sw%energy_long, units='1', &
         description='largest relative energy error over the long run')
      call h5%write(g//'/energy_final', sw%energy_final, units='1', &
         description='relative energy error at t_long')
      call h5%write(g//'/drift_exponent', sw%drift, units='1', &
         description='slope of ln(bin maximum) against ln t')
      call h5%write(g//'/drift_stderr', sw%drift_stderr, units='1', &
         description='standard error of drift_exponent')
      call h5%write(g//'/short_steps', sw%short_steps, units='1', &
         description='accepted steps of the short run')
      call h5%write(g//'/short_rhs', sw%short_rhs, units='1', &
         description='vector-field evaluations of the short run')
      call h5%write(g//'/short_iterations', sw%short_iter, units='1', &
         description='inner iterations of the short run (implicit methods)')
      call h5%write(g//'/short_rejected', sw%short_rejected, units='1', &
         description='rejected steps of the short run')
      call h5%write(g//'/long_steps', sw%long_steps, units='1', &
         description='accepted steps of the long run')
      call h5%write(g//'/long_rhs', sw%long_rhs, units='1', &
         description='vector-field evaluations of the long run')
      call h5%write(g//'/long_iterations', sw%long_iter, units='1', &
         description='inner iterations of the long run (implicit methods)')
      call h5%write(g//'/long_rejected', sw%long_rejected, units='1', &
         description='rejected steps of the long run')
      call h5%write(g//'/wall_short', sw%wall_short, units='s', &
         description='wall time of one short run (fastest of 5 batches)')
      call h5%write(g//'/wall_long', sw%wall_long, units='s', &
         description='wall time of the long run')
      call h5%write(g//'/status', sw%stat, units='1', &
         description='0 ok, 1 implicit iteration failed, 2 non-finite state, 3 step too small')
      call h5%write(g//'/t_bins', sw%t_bins, units='s', &
         description='upper edges of the logarithmic time bins')
      call h5%write(g//'/energy_bins', sw%bins, units='1', &
         description='largest relative energy error of each step size within each bin')
      call h5%writeattr(g, 'order', sw%order)
      call h5%writeattr(g, 'symplectic', merge(1, 0, sw%symplectic))
      call h5%writeattr(g, 'mid', sw%mid - 1)
      call h5%writeattr(g, 't_long', sw%t_long)
      call h5%writeattr(g, 't_short', cfg%t_short)
      call fit_attrs(h5, g, 'order_global', sw%fit_global)
      call fit_attrs(h5, g, 'order_energy', sw%fit_energy)
      call fit_attrs(h5, g, 'order_energy_long', sw%fit_energy_long)
      if (sw%mode == mode_tol) call fit_attrs(h5, g, 'slope_vs_rtol', sw%fit_tolerance)
   end subroutine write_sweep

   !> A fit as attributes NAME (slope, NaN if no fit), NAME_stderr, NAME_points.
   subroutine fit_attrs(h5, path, name, fit)
      type(h5file_t), intent(inout) :: h5
      character(len=*), intent(in) :: path, name
      type(fit_t), intent(in) :: fit
      if (fit%ok) then
         call h5%writeattr(path, name, fit%slope)
      else
         call h5%writeattr(path, name, ieee_value(1.0_dp, ieee_quiet_nan))
      end if
      call h5%writeattr(path, name//'_stderr', fit%stderr)
      call h5%writeattr(path, name//'_points', fit%n)
   end subroutine fit_attrs
end module dpend_study_command
