!> `dpend divergence`: the divergence of nearby trajectories (the numerics of
!> `dpend_divergence`: pairs started delta0 apart, log10|delta(t)| averaged over
!> them, a straight-line fit over the exponential phase) with the largest Lyapunov
!> exponent of the same initial state beside it, written to an HDF5 file (group
!> /divergence, docs/hdf5-layout.md) with a summary on standard output whose last
!> line is the result for scripts. The settings, their parsing and the run around
!> it are in `dpend_chaos_common`.
module dpend_divergence_command
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t, to_str
   use dpend_strings, only: with_uncertainty, real_str, distance_in_errors
   use dpend_run_settings, only: run_config_t, time_text, span_text
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_lyapunov, only: lyapunov_result_t, lyapunov_spectrum
   use dpend_propagate, only: march_progress_t
   use dpend_divergence, only: divergence_result_t, divergence_pairs, line_fit_t, &
                               fit_exponential_phase
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: coordinate_labels
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
   use dpend_chaos_common, only: chaos_config_t, write_common, run_status, stopped, num, &
                                 es, fixed
   use dpend_chaos_common, only: chaos_command
   implicit none
   private
   public :: divergence_command, run_divergence

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The entry point of `dpend divergence [options]` (app/main.f90): the arguments after
   !> the command, run through `chaos_command` with `run_divergence`; a refusal or a
   !> failed run comes back as `error`.
   subroutine divergence_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `divergence`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      call chaos_command('divergence', args, run_divergence, error)
   end subroutine divergence_command

   !> `dpend divergence`.
   subroutine run_divergence(cfg, ch, integ, filename, summary, error, failed)
      type(run_config_t), intent(in) :: cfg
      type(chaos_config_t), intent(in) :: ch
      class(integrator_t), intent(inout) :: integ
      character(len=*), intent(in) :: filename  !! the file to write
      character(len=:), allocatable, intent(inout) :: summary
      type(error_t), allocatable, intent(out) :: error
      logical, intent(inout) :: failed
      type(divergence_result_t) :: res
      type(lyapunov_result_t) :: lres
      type(line_fit_t) :: fit
      type(h5file_t) :: h5
      character(len=:), allocatable :: status
      character(len=:), allocatable :: names, q_units, rate_units, acc_units, p_units
      integer :: stat, lstat
      real(dp) :: lam, lam_spread
      type(march_progress_t) :: prog   ! the report in model time
      ! the pairs' reference orbit, the pairs, the Benettin run beside
      call prog%begin('dpend divergence', real(ch%pairs - 1, dp)*ch%pair_spacing + &
                      2.0_dp*real(ch%pairs, dp)*cfg%t_end + max(ch%lyapunov_t, 0.0_dp))
      call divergence_pairs(integ, cfg%model, cfg%q0(), cfg%w0(), cfg%t_end, cfg%output_dt, &
                            ch%delta0, ch%same_energy, ch%pairs, ch%pair_spacing, cfg%dt, &
                            res, stat, prog)
      status = run_status(stat, -1.0_dp)
      call fit_exponential_phase(res%t, res%log10_mean, ch%fit_start, ch%fit_end, fit)
      if (.not. fit%ok) then   ! no exponential phase to fit: no slope
         fit%slope = ieee_value(1.0_dp, ieee_quiet_nan)
         fit%slope_stderr = fit%slope
      end if
      lam = 0.0_dp; lam_spread = 0.0_dp; lstat = stat_ok
      if (ch%lyapunov_t > 0.0_dp .and. stat == stat_ok) then
         call lyapunov_spectrum(integ, cfg%model, 0.0_dp, &
                                integ%to_internal(cfg%model, cfg%q0(), cfg%w0()), ch%lyapunov_t, &
                                cfg%dt, 0.5_dp, 1, 10, lres, lstat, prog)
         lam = lres%exponents(1); lam_spread = lres%spread(1)
         if (lstat /= stat_ok) status = run_status(lstat, lres%t_reached)
      end if
      call prog%end()
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call write_common(h5, cfg, integ, 'divergence', status)
      call h5%write('/divergence/t', res%t, units='s', description= &
         "sample times from each pair's start")
      call h5%write('/divergence/log10_delta', res%log10_mean, units='1', description= &
         'mean over the pairs of log10 |delta(t)| (|delta| in the units of the state)')
      call h5%write('/divergence/log10_delta_pairs', res%log10_pairs, units='1', &
         description='log10 |delta(t)| of each pair')
      call coordinate_labels(cfg%model, names, q_units, rate_units, acc_units, p_units)
      call h5%write('/divergence/start', res%start, units=q_units//', '//rate_units, &
         description='('//state_names(names)//") of each pair's reference at its start")
      call h5%write('/divergence/delta_start', res%delta_start, units='1', description= &
         '|delta(0)| of each pair (norm in ('//state_names(names)//'), '//q_units// &
         ' and '//rate_units//')')
      call h5%write('/divergence/energy_difference', res%energy_diff, units='J', &
         description='E(partner) - E(reference) at the start')
      call h5%writeattr('/', 'delta0', ch%delta0)
      call h5%writeattr('/', 'same_energy', merge(1, 0, ch%same_energy))
      call h5%writeattr('/', 'pairs', size(res%delta_start))
      call h5%writeattr('/', 'pair_spacing', ch%pair_spacing)
      call h5%writeattr('/', 'output_dt', cfg%output_dt)
      call h5%writeattr('/', 'slope', fit%slope)
      call h5%writeattr('/', 'slope_stderr', fit%slope_stderr)
      call h5%writeattr('/', 'fit_intercept', fit%intercept)
      call h5%writeattr('/', 'fit_start', fit%t_start)
      call h5%writeattr('/', 'fit_end', fit%t_end)
      call h5%writeattr('/', 'fit_points', fit%n_points)
      call h5%writeattr('/', 'saturation', fit%saturation)
      call h5%writeattr('/', 'saturated', merge(1, 0, fit%saturated))
      call h5%writeattr('/', 'lyapunov_t', ch%lyapunov_t)
      if (ch%lyapunov_t > 0.0_dp) then
         call h5%writeattr('/', 'lyapunov', lam)
         call h5%writeattr('/', 'lyapunov_spread', lam_spread)
      end if
      call h5%close(error)   ! reports the first failed write, if any
      if (allocated(error)) return
      summary = 'dpend divergence: '//integ%name()//', dt = '//time_text(cfg, cfg%dt)// &
                ', '//to_str(size(res%delta_start))//' pair(s) over '// &
                time_text(cfg, cfg%t_end)//', delta0 = '//num(ch%delta0)//pick(ch%same_energy, &
                                                               ' on the energy surface', '')//nl
      if (fit%ok) then
         summary = summary//'fit window: '//span_text(cfg, fit%t_start, fit%t_end)//' (' &
                   //to_str(fit%n_points)//' samples); saturation at log10|delta| = ' &
                   //fixed(fit%saturation)//pick(fit%saturated, '', ' (not saturated)')//nl// &
                   'slope: '//with_uncertainty(fit%slope, fit%slope_stderr)//' 1/s (the ' &
                   //'standard error of the straight line fitted in the window: statistical ' &
                   //'only, not the choice of the window)'//nl
      else
         summary = summary//'fit: fewer than 3 samples in the window (no rise of one decade'// &
                   ' above delta0?)'//nl
      end if
      if (ch%lyapunov_t > 0.0_dp .and. lstat == stat_ok .and. stat == stat_ok) then
         summary = summary//'Benettin lambda1 over t = 0 .. '//time_text(cfg, ch%lyapunov_t)//': ' &
                   //with_uncertainty(lam, lam_spread)//' 1/s (the standard error of its ' &
                   //'batch means)'
         if (lam > 0.0_dp .and. fit%ok) summary = summary//'; slope / lambda1 = '// &
                                                  ratio_text(fit%slope, fit%slope_stderr, &
                                                             lam, lam_spread)
         summary = summary//nl
      end if
      summary = summary//"dpend divergence: wrote '"//cfg%output//"'"
      if (stat /= stat_ok .or. lstat /= stat_ok) then
         call stopped(status, cfg%output, error, failed)
         return
      end if
      if (fit%ok) then
         summary = summary//nl//'divergence slope: '//es(fit%slope)
      else if (ch%fit_end > ch%fit_start) then
         summary = summary//nl//'divergence slope: none (fewer than 3 samples in the fit ' &
                   //'window '//span_text(cfg, ch%fit_start, ch%fit_end)//'; widen ' &
                   //'--fit-start/--fit-end or lower --output-dt)'
      else
         summary = summary//nl//'divergence slope: none (no exponential phase: log10|delta| ' &
                   //'did not rise one decade above its start within '// &
                   time_text(cfg, cfg%t_end)//'; a regular orbit, or try a longer --t-end)'
      end if
   contains
      !> 'q1, q2, qdot1, qdot2' or 'r, phi, rdot, phidot': the state's components.
      function state_names(blank_separated) result(t)
         character(len=*), intent(in) :: blank_separated
         character(len=:), allocatable :: t, rest, w, rates
         integer :: b
         t = ''; rates = ''
         rest = trim(adjustl(blank_separated))
         do while (len(rest) > 0)
            b = index(rest, ' ')
            if (b == 0) b = len(rest) + 1
            w = rest(:b - 1)
            rest = trim(adjustl(rest(min(b, len(rest)) + 1:)))
            if (b > len(rest) + len(w)) rest = ''
            if (len(t) > 0) then
               t = t//', '; rates = rates//', '
            end if
            t = t//w
            if (w(1:1) == 'q' .and. len(w) > 1 .and. verify(w(2:), '0123456789') == 0) then
               rates = rates//'qdot'//w(2:)   ! the generalised coordinates' q̇_i
            else
               rates = rates//w//'dot'
            end if
         end do
         t = t//', '//rates
      end function state_names
   end subroutine run_divergence

   !> `a` when `cond`, else `b`.
   pure function pick(cond, a, b) result(s)
      logical, intent(in) :: cond
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: s
      if (cond) then
         s = a
      else
         s = b
      end if
   end function pick

   !> a/b with its standard error (from those of a and b, taken independent) and how
   !> far 1 lies from it in standard errors: '0.975 +- 0.037 (1 within 1 standard
   !> error)'.
   function ratio_text(a, ua, b, ub) result(s)
      real(dp), intent(in) :: a, ua   !! the numerator and its standard error
      real(dp), intent(in) :: b, ub   !! the denominator (> 0) and its standard error
      character(len=:), allocatable :: s
      real(dp) :: r, ur
      r = a/b
      ur = sqrt((ua/b)**2 + (a*ub/b**2)**2)   ! |r| sqrt((ua/a)^2 + (ub/b)^2), a = 0 too
      s = with_uncertainty(r, ur)
      if (ieee_is_nan(ur) .or. ieee_is_nan(r)) return   ! (an ordered test with NaN traps)
      if (ur > 0.0_dp) s = s//' ('//distance_in_errors(r, 1.0_dp, '1', ur)//')'
   end function ratio_text

end module dpend_divergence_command
