!> `dpend lyapunov`: the Lyapunov exponents of one trajectory (the numerics of
!> `dpend_lyapunov`: tangent vectors re-orthonormalised every tau), written to an
!> HDF5 file (group /lyapunov, docs/hdf5-layout.md) with a summary on standard
!> output whose last line is the result for scripts. The settings, their parsing
!> and the run around it are in `dpend_chaos_common`.
module dpend_lyapunov_command
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t, to_str
   use dpend_strings, only: with_uncertainty, real_str, distance_in_errors
   use dpend_run_settings, only: run_config_t, time_text
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_lyapunov, only: lyapunov_result_t, lyapunov_spectrum
   use dpend_propagate, only: march_progress_t
   use dpend_hdf5, only: h5file_t
   use dpend_chaos_common, only: chaos_config_t, write_common, run_status, stopped, &
                                 n_vectors, num, es, fixed
   use dpend_chaos_common, only: chaos_command
   implicit none
   private
   public :: lyapunov_command, run_lyapunov

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The entry point of `dpend lyapunov [options]` (app/main.f90): the arguments after
   !> the command, run through `chaos_command` with `run_lyapunov`; a refusal or a
   !> failed run comes back as `error`.
   subroutine lyapunov_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `lyapunov`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      call chaos_command('lyapunov', args, run_lyapunov, error)
   end subroutine lyapunov_command

   !> `dpend lyapunov`.
   subroutine run_lyapunov(cfg, ch, integ, filename, summary, error, failed)
      type(run_config_t), intent(in) :: cfg
      type(chaos_config_t), intent(in) :: ch
      class(integrator_t), intent(inout) :: integ
      character(len=*), intent(in) :: filename  !! the file to write
      character(len=:), allocatable, intent(inout) :: summary
      type(error_t), allocatable, intent(out) :: error
      logical, intent(inout) :: failed
      type(lyapunov_result_t) :: res
      type(h5file_t) :: h5
      character(len=:), allocatable :: status, line
      integer :: stat, i, k
      real(dp), allocatable :: defects(:)
      real(dp) :: u
      type(march_progress_t) :: prog   ! the report in model time
      call prog%begin('dpend lyapunov', cfg%t_end)
      call lyapunov_spectrum(integ, cfg%model, 0.0_dp, &
                             integ%to_internal(cfg%model, cfg%q0(), cfg%w0()), cfg%t_end, &
                             cfg%dt, ch%tau, n_vectors(ch, cfg), ch%batches, res, stat, prog)
      call prog%end()
      status = run_status(stat, res%t_reached)
      ! a Hamiltonian spectrum comes in pairs: lambda_i + lambda_(2N+1-i) = 0 (a damped
      ! or driven model has no such pairing: no defects are reported)
      k = res%k
      allocate (defects(0))
      if (k == cfg%model%n_state() .and. cfg%model%hamiltonian()) &
         defects = res%exponents(:k/2) + res%exponents(k:k/2 + 1:-1)
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call write_common(h5, cfg, integ, 'lyapunov', status)
      call h5%write('/lyapunov/t', res%t, units='s', description= &
         'times of the renormalisations (every tau, and t_end)')
      call h5%write('/lyapunov/running', res%running, units='1/s', description= &
         'running estimates lambda_i(t) = (1/t) sum ln R_ii, column i-1 for lambda_i')
      call h5%write('/lyapunov/exponents', res%exponents, units='1/s', description= &
         'Lyapunov exponents lambda_1 >= ... >= lambda_k at the end')
      call h5%write('/lyapunov/spread', res%spread, units='1/s', description= &
         'standard error of the mean of the batch exponents (NaN with one batch)')
      call h5%write('/lyapunov/batches', res%batches, units='1/s', description= &
         'exponents of the equal time segments')
      call h5%writeattr('/', 'tau', ch%tau)
      call h5%writeattr('/', 'vectors', k)
      call h5%writeattr('/', 'batches', size(res%batches, 2))
      call h5%writeattr('/', 't_reached', res%t_reached)
      call h5%writeattr('/', 'n_renormalisations', size(res%t))
      call h5%writeattr('/', 'n_tangent_substeps', res%n_sub)
      if (size(defects) > 0) then
         call h5%writeattr('/', 'pairing_defects', defects)
         call h5%writeattr('/', 'pairing_defect', defects(1))
         if (k == 4) call h5%writeattr('/', 'zero_pair_sum', defects(2))
      end if
      call h5%close(error)   ! reports the first failed write, if any
      if (allocated(error)) return
      summary = 'dpend lyapunov: '//integ%name()//', dt = '//time_text(cfg, cfg%dt)// &
                ', t = 0 .. '//time_text(cfg, res%t_reached)//', tau = ' &
                //time_text(cfg, ch%tau)//', ' &
                //to_str(size(res%t))//' renormalisations, '//to_str(integ%n_steps) &
                //' steps'//nl//'  i   lambda_i [1/s] +- its standard error (the spread of ' &
                //to_str(size(res%batches, 2))//' batch means: statistical only, not the ' &
                //'finite-time bias)'//nl
      do i = 1, res%k
         summary = summary//'  '//to_str(i)//'   '// &
                   with_uncertainty(res%exponents(i), res%spread(i))//nl
      end do
      do i = 1, size(defects)
         u = sqrt(res%spread(i)**2 + res%spread(k + 1 - i)**2)
         summary = summary//'pairing defect: lambda'//to_str(i)//' + lambda'// &
                   to_str(k + 1 - i)//' = '//with_uncertainty(defects(i), u)//' 1/s'// &
                   pct(defects(i), res%exponents(1))//'; '// &
                   distance_in_errors(defects(i), 0.0_dp, '0', u)//nl
      end do
      summary = summary//"dpend lyapunov: wrote '"//cfg%output//"'"
      if (stat /= stat_ok) then
         ! no scripting line: a failed run has no exponents to report
         call stopped(status, cfg%output, error, failed)
         return
      end if
      line = 'lyapunov:'
      do i = 1, res%k
         line = line//' '//es(res%exponents(i))
      end do
      summary = summary//nl//line
   end subroutine run_lyapunov

   !> " (x % of ref)" when ref /= 0.
   function pct(x, ref) result(s)
      real(dp), intent(in) :: x, ref
      character(len=:), allocatable :: s
      s = ''
      if (ref == 0.0_dp) return
      s = ' ('//real_str(100.0_dp*abs(x/ref), 2)//' % of |lambda1|)'
   end function pct

end module dpend_lyapunov_command
