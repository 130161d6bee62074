!> `dpend indicators`: the fast chaos indicators of one trajectory (the numerics
!> of `dpend_indicators`: MEGNO, FLI, SALI and GALI_k against time), written to an
!> HDF5 file (group /indicators, docs/hdf5-layout.md) with a summary on standard
!> output, the verdict regular, chaotic or undecided (`indicator_verdict`), and a
!> last line that is the result for scripts. The settings, their parsing and the
!> run around it are in `dpend_chaos_common`.
module dpend_indicators_command
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t, to_str, real_str
   use dpend_run_settings, only: run_config_t, time_text, natural_time, natural_unit_name
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_indicators, only: indicators_result_t, chaos_indicators
   use dpend_propagate, only: march_progress_t
   use dpend_hdf5, only: h5file_t
   use dpend_chaos_common, only: chaos_config_t, write_common, run_status, stopped, num, es
   use dpend_chaos_common, only: chaos_command
   implicit none
   private
   public :: indicators_command, run_indicators, indicator_verdict

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The entry point of `dpend indicators [options]` (app/main.f90): the arguments after
   !> the command, run through `chaos_command` with `run_indicators`; a refusal or a
   !> failed run comes back as `error`.
   subroutine indicators_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `indicators`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      call chaos_command('indicators', args, run_indicators, error)
   end subroutine indicators_command

   !> `dpend indicators`.
   subroutine run_indicators(cfg, ch, integ, filename, summary, error, failed)
      type(run_config_t), intent(in) :: cfg
      type(chaos_config_t), intent(in) :: ch
      class(integrator_t), intent(inout) :: integ
      character(len=:), allocatable, intent(inout) :: summary
      character(len=*), intent(in) :: filename  !! the file to write
      type(error_t), allocatable, intent(out) :: error
      logical, intent(inout) :: failed
      type(indicators_result_t) :: res
      type(h5file_t) :: h5
      character(len=:), allocatable :: status, line, unit
      real(dp) :: tn
      integer :: stat, j, n
      type(march_progress_t) :: prog   ! the report in model time
      call prog%begin('dpend indicators', cfg%t_end)
      call chaos_indicators(integ, cfg%model, 0.0_dp, &
                            integ%to_internal(cfg%model, cfg%q0(), cfg%w0()), cfg%t_end, &
                            cfg%dt, ch%tau, res, stat, prog)
      call prog%end()
      status = run_status(stat, res%t_reached)
      n = res%n
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call write_common(h5, cfg, integ, 'indicators', status)
      if (n > 0) call write_series()   ! a run that failed before its first sample: the
      ! file holds its status and settings, no series (as lyapunov's and divergence's)
      call h5%writeattr('/', 'tau', ch%tau)
      call h5%writeattr('/', 'vectors', res%k)
      call h5%writeattr('/', 't_reached', res%t_reached)
      call h5%writeattr('/', 'n_samples', n)
      call h5%writeattr('/', 'n_tangent_substeps', res%n_sub)
      if (n > 0) then
         call h5%writeattr('/', 'megno_mean_final', res%mean_all(1, n))
         call h5%writeattr('/', 'fli_final', res%fli(n))
         call h5%writeattr('/', 'sali_final', res%sali(n))
         call h5%writeattr('/', 'gali_final', res%gali(:, n))
      end if
      call h5%close(error)   ! reports the first failed write, if any
      if (allocated(error)) return
      summary = 'dpend indicators: '//integ%name()//', dt = '//time_text(cfg, cfg%dt)// &
                ', t = 0 .. '//time_text(cfg, res%t_reached)//', tau = ' &
                //time_text(cfg, ch%tau)//', '//to_str(n) &
                //' samples, '//to_str(integ%n_steps)//' steps, '//to_str(res%k) &
                //' deviation vectors'//nl
      if (n > 0) then
         summary = summary//'MEGNO <Y> = '//es(res%mean_all(1, n))//' (Y = '// &
                   es(res%megno_all(1, n))//'; 2: regular, ~ lambda1 t/2: chaotic)'//nl// &
                   'FLI = '//es(res%fli(n))//' (ln(t/s) = '//es(log(res%t(n)))// &
                   ': regular ~ ln t + c)'//nl//'SALI = '//es(res%sali(n))//nl
         do j = 2, res%k
            summary = summary//'GALI_'//to_str(j)//' = '//es(res%gali(j - 1, n))//nl
         end do
      end if
      summary = summary//"dpend indicators: wrote '"//cfg%output//"'"
      if (n > 0) then
         tn = natural_time(cfg)
         unit = natural_unit_name(cfg)
         summary = summary//nl//indicator_verdict(res%mean_all(1, n), res%sali(n), res%t(n), &
                                                  tn, unit, trim(cfg%time_unit) == 'natural')
      end if
      if (stat /= stat_ok .or. n == 0) then
         call stopped(status, cfg%output, error, failed)
         return
      end if
      line = 'indicators: '//es(res%mean_all(1, n))//' '//es(res%fli(n))//' '//es(res%sali(n))
      do j = 1, res%k - 1
         line = line//' '//es(res%gali(j, n))
      end do
      summary = summary//nl//line
   contains
      !> The sampled series of the indicators.
      subroutine write_series()
         call h5%write('/indicators/t', res%t, units='s', description= &
            'sample times (every tau, at step ends, and t_end)')
         call h5%write('/indicators/megno', res%megno(), units='1', description= &
            'MEGNO Y(t) = (2/t) int_0^t s (d ln|delta_1|/ds) ds of deviation vector 1')
         call h5%write('/indicators/megno_mean', res%megno_mean(), units='1', description= &
            'running mean <Y>(t) = (1/t) int_0^t Y ds of vector 1: 2 regular, lambda1 t/2 chaotic')
         call h5%write('/indicators/fli', res%fli, units='1', description= &
            'fast Lyapunov indicator FLI(t) = max_i ln|delta_i(t)|, |delta_i(0)| = 1')
         call h5%write('/indicators/sali', res%sali, units='1', description= &
            'SALI = min(|u1 + u2|, |u1 - u2|) of the unit deviation vectors 1 and 2')
         call h5%write('/indicators/gali', res%gali, units='1', description= &
            'GALI_k(t), column k-2 for k = 2 .. 2N: volume spanned by unit vectors 1 .. k')
         call h5%write('/indicators/log_norm', res%log_norm, units='1', description= &
            'ln|delta_i(t)| of each deviation vector, column i-1 for vector i')
         call h5%write('/indicators/megno_vectors', res%megno_all, units='1', description= &
            'MEGNO Y(t) of each deviation vector, column i-1 for vector i')
         call h5%write('/indicators/megno_mean_vectors', res%mean_all, units='1', description= &
            'running mean <Y>(t) of each deviation vector, column i-1 for vector i')
      end subroutine write_series
   end subroutine run_indicators

   !> The verdict of `dpend indicators` (docs/chaos.md, "Verdict"):
   !> 'verdict: chaotic' when MEGNO's mean <Y> > 4 (twice the regular limit 2; it
   !> grows as lambda1 t/2) and SALI < 1e-4 (it falls as exp(-(lambda1 - lambda2) t));
   !> 'verdict: regular' when <Y> <= 2.1 (2 with shear, 0 without), SALI >= 1e-4
   !> and the run lasted at least 100 natural time units (before, a chaotic orbit
   !> can still look regular); 'verdict: undecided' otherwise. The line names the
   !> criterion and the values.
   function indicator_verdict(mean_y, sali, t, t_nat, unit, natural_first) result(s)
      real(dp), intent(in) :: mean_y  !! MEGNO's running mean <Y> at the end
      real(dp), intent(in) :: sali    !! SALI at the end
      real(dp), intent(in) :: t       !! the time reached [s]
      real(dp), intent(in) :: t_nat   !! the natural time unit [s] (sqrt(l1/g))
      character(len=*), intent(in) :: unit  !! its name: 'sqrt(l1/g)' or 'sqrt(l0/g)'
      !> t in the natural unit first (--time-unit natural; default: seconds first)
      logical, intent(in), optional :: natural_first
      character(len=:), allocatable :: s
      character(len=:), allocatable :: values, tt
      tt = real_str(t, 4)//' s = '//real_str(t/t_nat, 4)//' '//unit
      if (present(natural_first)) then
         if (natural_first) tt = real_str(t/t_nat, 4)//' '//unit//' = '//real_str(t, 4)//' s'
      end if
      values = 'MEGNO <Y> = '//real_str(mean_y, 4)//', SALI = '//real_str(sali, 3)
      if (.not. (mean_y == mean_y .and. sali == sali)) then
         s = 'verdict: undecided ('//values//': not finite)'
      else if (mean_y > 4.0_dp .and. sali < 1e-4_dp) then
         s = 'verdict: chaotic ('//values//'; criterion: <Y> > 4 and SALI < 1e-4)'
      else if (mean_y <= 2.1_dp .and. sali >= 1e-4_dp .and. t >= 100.0_dp*t_nat) then
         s = 'verdict: regular ('//values//' at t = '//tt//'; criterion: ' &
             //'<Y> <= 2.1 and SALI >= 1e-4 after at least 100 '//unit//' = '// &
             real_str(100.0_dp*t_nat, 4)//' s)'
      else if (mean_y <= 2.1_dp .and. sali >= 1e-4_dp) then
         s = 'verdict: undecided ('//values//' look regular, but t = '//tt// &
             ' is below 100 '//unit//' = '//real_str(100.0_dp*t_nat, 4)// &
             ' s; criterion: chaotic <Y> > 4 and SALI < 1e-4, regular <Y> <= 2.1 and ' &
             //'SALI >= 1e-4 after 100 '//unit//'; a longer --t-end)'
      else
         s = 'verdict: undecided ('//values//'; criterion: chaotic <Y> > 4 and SALI < ' &
             //'1e-4, regular <Y> <= 2.1 and SALI >= 1e-4 after 100 '//unit//'; a ' &
             //'longer --t-end)'
      end if
   end function indicator_verdict

end module dpend_indicators_command
