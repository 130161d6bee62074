!> `dpend torques`: inverse dynamics of a measured motion. The angles (and rates,
!> when the file has them) are smoothed and differentiated by a local polynomial
!> (`dpend_smoothing`, its window from the noise of the data by the plug-in rule or
!> given); Newton–Euler (`dpend_inverse_dynamics`) gives the joint torques and
!> reactions at every sample; with measured torques, their residual. The report
!> states the filter and the errors it predicts; the file (group /torques,
!> docs/hdf5-layout.md) is written through the one writer, and with --csv a CSV too.
!> The command line and the data: `dpend_torques_config`.
module dpend_torques_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_cli, only: arg_t, real_str, to_str, printable
   use dpend_csv, only: csv_format
   use dpend_export, only: print_csv
   use dpend_smoothing, only: smooth_derivatives, noise_sigma, choose_half_width, &
                              predicted_errors
   use dpend_inverse_dynamics, only: joint_torques, torque_gain
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model
   use dpend_output, only: output_t
   use dpend_version, only: version
   use dpend_limits, only: sci
   use dpend_command_common, only: report_unit, take_quiet, with_quiet, summary_quiet, &
      refusal_line, error_line
   use dpend_torques_config, only: torques_config_t, parse_torques, torques_help, &
      filter_work, max_filter_work
   implicit none
   private
   public :: torques_command, torques_result_t, compute_torques, filter_motion

   character(len=*), parameter :: nl = new_line('a')

   !> What the command computes.
   type :: torques_result_t
      integer :: half_width = 0                  !! k: the window is 2k + 1 samples
      character(len=:), allocatable :: window_rule   !! 'given' or the plug-in rule
      real(dp), allocatable :: sigma(:)          !! noise of each angle [rad] (N)
      character(len=:), allocatable :: sigma_rule    !! 'given' or 'estimated ...'
      real(dp), allocatable :: qdd_noise(:), qdd_bias(:)  !! predicted RMS errors of q̈ (N)
      real(dp), allocatable :: tau_noise(:), tau_bias(:)  !! … and of τ [N m] (N)
      real(dp), allocatable :: q(:, :), qd(:, :), qdd(:, :)  !! filtered (N, K)
      real(dp), allocatable :: tau(:, :)         !! joint torques (N, K) [N m]
      real(dp), allocatable :: f(:, :, :)        !! reactions F_(i−1,i) (2, N, K) [N]
      real(dp), allocatable :: residual(:, :)    !! measured − computed (N, K), if measured
      real(dp), allocatable :: rms_tau(:)        !! RMS of τ_i over the interior (N)
      real(dp), allocatable :: rms_residual(:)   !! RMS of the residual, interior (N)
   end type torques_result_t

contains

   !> The entry point of `dpend torques DATA.csv [options]` (app/main.f90).
   subroutine torques_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `torques`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(torques_config_t) :: tc
      type(torques_result_t) :: res
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_torques(rest, tc, help, error, 'torques')
      if (allocated(error)) then
         call refusal_line(error, 'torques')
         return
      else if (help) then
         write (output_unit, '(a)') with_quiet(torques_help(), summary_quiet)
         return
      end if
      call compute_torques(tc, res, error)
      if (allocated(error)) then
         call refusal_line(error, 'torques')
         return
      end if
      call write_outputs(tc, res, error)
      if (allocated(error)) then
         call run_failure(error)
         call error_line(error, 'torques')
         return
      end if
      call print_report(tc, res, quiet)
   end subroutine torques_command

   !> The filter: the noise of the angles (given or estimated), the window (given or
   !> by the plug-in rule), its predicted errors, and the smoothed q, q̇, q̈ (from the
   !> measured rates when the file has them). `error` (a refusal): the window the
   !> plug-in rule chose needs more work than allowed.
   subroutine filter_motion(tc, res, error)
      type(torques_config_t), intent(in) :: tc          !! validated configuration
      type(torques_result_t), intent(out) :: res        !! the filter's results set
      type(error_t), allocatable, intent(out) :: error  !! too much work
      real(dp), allocatable :: ys(:, :, :)
      integer :: n, k, c, p
      n = tc%angles%n
      k = tc%angles%k
      p = tc%degree
      associate (t => tc%angles%t, q => tc%angles%q)
         if (tc%sigma > 0.0_dp) then
            res%sigma = [(tc%sigma, c = 1, n)]
            res%sigma_rule = 'given'
         else
            res%sigma = [(noise_sigma(q(c, :)), c = 1, n)]
            res%sigma_rule = 'estimated from the fourth differences'
         end if
         if (tc%window > 0) then
            res%half_width = (tc%window - 1)/2
            res%window_rule = 'given'
         else
            res%half_width = choose_half_width(t, q, res%sigma, p)
            res%window_rule = 'plug-in rule (least predicted error of qddot)'
            if (filter_work(k, 2*res%half_width + 1, p, n) > max_filter_work) then
               call fatal_error(error, 'invalid window: the plug-in rule chose '// &
                                to_str(2*res%half_width + 1)//' samples, which on '// &
                                to_str(k)//' samples needs more than '// &
                                sci(max_filter_work)//' operations (give --window) [--window]')
               return
            end if
         end if
         call predicted_errors(t, q, res%sigma, res%half_width, p, res%qdd_noise, &
                               res%qdd_bias)
         allocate (ys(0:2, n, k))
         call smooth_derivatives(t, q, res%half_width, p, ys)
         res%q = ys(0, :, :)
         res%qd = ys(1, :, :)
         res%qdd = ys(2, :, :)
         if (tc%rates%coords_found) then   ! q̇ and q̈ from the measured rates
            call smooth_derivatives(t, tc%rates%q, res%half_width, p, ys)
            res%qd = ys(0, :, :)
            res%qdd = ys(1, :, :)
         end if
      end associate
   end subroutine filter_motion

   !> Filter, then Newton–Euler at every sample. `error` (a refusal): the window the
   !> plug-in rule chose needs more work than allowed.
   subroutine compute_torques(tc, res, error)
      type(torques_config_t), intent(in) :: tc          !! validated configuration
      type(torques_result_t), intent(out) :: res        !! the results
      type(error_t), allocatable, intent(out) :: error  !! too much work
      real(dp), allocatable :: gain(:, :)
      integer :: n, k, c, j, lo, hi
      call filter_motion(tc, res, error)
      if (allocated(error)) return
      n = tc%angles%n
      k = tc%angles%k
      associate (t => tc%angles%t)
         allocate (res%tau(n, k), res%f(2, n, k), gain(n, n))
         res%tau_noise = [(0.0_dp, c = 1, n)]
         res%tau_bias = res%tau_noise
         do j = 1, k
            call joint_torques(tc%chain, t(j), res%q(:, j), res%qd(:, j), res%qdd(:, j), &
                               res%tau(:, j), res%f(:, :, j))
            call torque_gain(tc%chain, res%q(:, j), gain)
            res%tau_noise = res%tau_noise + matmul(gain**2, res%qdd_noise**2)
            res%tau_bias = res%tau_bias + matmul(gain**2, res%qdd_bias**2)
         end do
         res%tau_noise = sqrt(res%tau_noise/k)
         res%tau_bias = sqrt(res%tau_bias/k)
         ! RMS over the interior: the samples whose window is centred
         lo = min(res%half_width + 1, k)
         hi = max(k - res%half_width, lo)
         res%rms_tau = sqrt(sum(res%tau(:, lo:hi)**2, dim=2)/(hi - lo + 1))
         if (tc%measured%coords_found) then
            res%residual = tc%measured%q - res%tau
            res%rms_residual = sqrt(sum(res%residual(:, lo:hi)**2, dim=2)/(hi - lo + 1))
         end if
      end associate
   end subroutine compute_torques

   !> The HDF5 file and, with --csv, the CSV file, each through the one writer.
   subroutine write_outputs(tc, res, error)
      type(torques_config_t), intent(in) :: tc          !! configuration
      type(torques_result_t), intent(in) :: res         !! results
      type(error_t), allocatable, intent(out) :: error  !! a failed write
      type(output_t) :: out, csv_out
      type(error_t), allocatable :: werr
      call out%begin(tc%run%output, tc%run%force, error)
      if (allocated(error)) return
      if (len(tc%csv) > 0) then
         call csv_out%begin(tc%csv, tc%run%force, error, '--csv')
         if (allocated(error)) then
            call out%discard()
            return
         end if
         call write_csv(csv_out%temp, tc, res, werr)
      end if
      if (.not. allocated(werr)) call write_h5(out%temp, tc, res, werr)
      if (.not. allocated(werr)) call out%commit(werr)
      if (.not. allocated(werr) .and. len(tc%csv) > 0) call csv_out%commit(werr)
      call out%explain(werr)
      call out%discard()
      if (len(tc%csv) > 0) then
         call csv_out%explain(werr)
         call csv_out%discard()
      end if
      if (allocated(werr)) call move_alloc(werr, error)
   end subroutine write_outputs

   !> Group /torques and the settings as attributes of the root.
   subroutine write_h5(filename, tc, res, error)
      character(len=*), intent(in) :: filename          !! the temporary file
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      integer :: n, k
      n = tc%angles%n
      k = tc%angles%k
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      call h5%writeattr('/', 'command', 'torques')
      call record_model(h5, tc%chain)
      call h5%writeattr('/', 'links', n)
      call h5%writeattr('/', 'data_file', tc%input)
      call h5%writeattr('/', 'data_format', csv_format(tc%angles))
      call h5%writeattr('/', 'angles', 'absolute: q_i from the horizontal x axis, ' &
                        //'counter-clockwise (the data''s theta converted: q = theta - pi/2)')
      call h5%writeattr('/', 'rates_measured', merge(1, 0, tc%rates%coords_found))
      call h5%writeattr('/', 'filter', 'local polynomial (Savitzky-Golay) of degree '// &
                        to_str(tc%degree)//' on '//to_str(2*res%half_width + 1)// &
                        ' samples, centred (the first and last '//to_str(res%half_width)// &
                        ' samples: the first or last window)')
      call h5%writeattr('/', 'degree', tc%degree)
      call h5%writeattr('/', 'window', 2*res%half_width + 1)
      call h5%writeattr('/', 'window_rule', res%window_rule)
      call h5%writeattr('/', 'sigma', res%sigma)
      call h5%writeattr('/', 'sigma_rule', res%sigma_rule)
      call h5%writeattr('/', 'predicted_qddot_noise', res%qdd_noise)
      call h5%writeattr('/', 'predicted_qddot_bias', res%qdd_bias)
      call h5%writeattr('/', 'predicted_tau_noise', res%tau_noise)
      call h5%writeattr('/', 'predicted_tau_bias', res%tau_bias)
      call h5%writeattr('/', 'rms_tau', res%rms_tau)
      call h5%writeattr('/', 'version', version)
      call h5%writeattr('/', 'status', 'completed')
      call h5%write('/torques/t', tc%angles%t, units='s', description='sample times')
      call h5%write('/torques/q', res%q, units='rad', description='smoothed angles from ' &
                    //'the horizontal x axis (q1 .. qN, one column per link)')
      call h5%write('/torques/qdot', res%qd, units='rad/s', description='angular ' &
                    //'velocities of the filter'//trim(merge(' (from the measured rates)', &
                                                              '                          ', &
                                                              tc%rates%coords_found)))
      call h5%write('/torques/qddot', res%qdd, units='rad/s^2', description='angular ' &
                    //'accelerations of the filter')
      call h5%writeattr('/torques/q', 'angles', 'absolute')
      call h5%writeattr('/torques/qdot', 'angles', 'absolute rates')
      call h5%writeattr('/torques/qddot', 'angles', 'absolute rates')
      call h5%write('/torques/tau', res%tau, units='N m', description='joint torques ' &
                    //'tau_1 .. tau_N the motion requires (Newton-Euler): joint i''s motor ' &
                    //'on link i, its reaction on link i - 1')
      call h5%write('/torques/F_joint', res%f, units='N', &
                    description='force of body i-1 on body i at joint i (x, y), i = 1..N, ' &
                    //'body 0 the ground')
      if (tc%measured%coords_found) then
         call h5%write('/torques/tau_measured', tc%measured%q, units='N m', description= &
                       'the measured joint torques of the data file')
         call h5%write('/torques/residual', res%residual, units='N m', description= &
                       'measured minus computed joint torques')
         call h5%writeattr('/', 'rms_residual', res%rms_residual)
      end if
      call h5%close(error)
   end subroutine write_h5

   !> t, tau1..N [, tau_measured1..N, residual1..N] with a header of names and units.
   subroutine write_csv(filename, tc, res, error)
      character(len=*), intent(in) :: filename          !! the temporary file
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(in) :: res
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: header
      character(len=256) :: msg
      real(dp), allocatable :: table(:, :)
      integer :: unit, stat, i, n
      logical :: measured
      n = tc%angles%n
      measured = tc%measured%coords_found
      header = 't [s]'
      do i = 1, n
         header = header//',tau'//to_str(i)//' [N m]'
      end do
      if (measured) then
         do i = 1, n
            header = header//',tau_measured'//to_str(i)//' [N m]'
         end do
         do i = 1, n
            header = header//',residual'//to_str(i)//' [N m]'
         end do
      end if
      open (newunit=unit, file=filename, status='replace', action='write', iostat=stat, &
            iomsg=msg)
      if (stat /= 0) then
         call fatal_error(error, "cannot write '"//printable(tc%csv)//"' ("//trim(msg)//')')
         return
      end if
      write (unit, '(a)', iostat=stat, iomsg=msg) header
      allocate (table(merge(1 + 3*n, 1 + n, measured), tc%angles%k))
      table(1, :) = tc%angles%t
      table(2:n + 1, :) = res%tau
      if (measured) then
         table(n + 2:2*n + 1, :) = tc%measured%q
         table(2*n + 2:3*n + 1, :) = res%residual
      end if
      if (stat == 0) call print_csv(unit, table, stat)
      if (stat == 0) then
         close (unit, iostat=stat, iomsg=msg)
      else
         close (unit)
      end if
      if (stat /= 0) call fatal_error(error, "cannot write '"//printable(tc%csv)//"' (" &
                                      //trim(msg)//')')
   end subroutine write_csv

   !> The report: data, filter, predicted errors, torques, residuals; its last line
   !> names the files written (--quiet: that line only).
   subroutine print_report(tc, res, quiet)
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(in) :: res
      logical, intent(in) :: quiet
      character(len=:), allocatable :: s
      integer :: i, n
      real(dp) :: h
      n = tc%angles%n
      h = (tc%angles%t(tc%angles%k) - tc%angles%t(1))/max(tc%angles%k - 1, 1)
      s = "dpend torques: '"//printable(tc%input)//"', "//to_str(tc%angles%k)// &
          ' samples, t = '//real_str(tc%angles%t(1))//' .. '// &
          real_str(tc%angles%t(tc%angles%k))//' s (mean step '//real_str(h, 4)//' s), '// &
          to_str(n)//' links'//trim(merge(', measured rates  ', '                  ', &
                                          tc%rates%coords_found))//nl// &
          'filter: local polynomial of degree '//to_str(tc%degree)//', window '// &
          to_str(2*res%half_width + 1)//' samples ('//real_str(2*res%half_width*h, 3)// &
          ' s; '//res%window_rule//')'//nl// &
          'noise of the angles ('//res%sigma_rule//'):'
      do i = 1, n
         s = s//' '//real_str(res%sigma(i), 3)
      end do
      s = s//' rad'//nl//'  joint  RMS tau [N m]  predicted error of tau: noise, bias [N m]'
      if (tc%measured%coords_found) s = s//'  RMS residual [N m]'
      do i = 1, n
         s = s//nl//'  '//to_str(i)//'      '//real_str(res%rms_tau(i), 4)//'       '// &
             real_str(res%tau_noise(i), 2)//', '//real_str(res%tau_bias(i), 2)
         if (tc%measured%coords_found) s = s//'      '//real_str(res%rms_residual(i), 3)
      end do
      s = s//nl//'(RMS over the '//to_str(max(tc%angles%k - 2*res%half_width, 1))// &
          ' samples whose window is centred)'//nl//"dpend torques: wrote '"// &
          printable(tc%run%output)//"'"
      if (len(tc%csv) > 0) s = s//" and '"//printable(tc%csv)//"'"
      if (quiet) then
         write (report_unit(), '(a)') s(index(s, nl, back=.true.) + 1:)
      else
         write (report_unit(), '(a)') s
      end if
   end subroutine print_report

end module dpend_torques_command
