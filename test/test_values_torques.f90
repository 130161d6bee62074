!> The values of `dpend torques` files against independent computations:
!> - a motion of known torques: `dpend simulate` of two damped rods with Coulomb
!>   friction under smooth applied torques (a torque file of sines at 1 ms, written
!>   here), its angles and torques exported at 500 Hz and read back by `dpend
!>   torques` with the same model: tau against the applied torques, q, qdot, qddot
!>   and F_joint against the simulate file's (the forward model at the integrated
!>   states), tau_measured against the CSV, residual recomputed, and the --csv file
!>   against the HDF5 datasets;
!> - the same angles quantised as a 16384-count encoder reads them: the RMS torque
!>   error against the filter's predicted error (noise and bias combined);
!> - `dpend identify` of the noise-free run: the base parameters against the rods'
!>   closed forms (J = m l²/3, h = m l/2, J1 + l1² m2, h1 + l1 m2) and the known
!>   frictions, the names and units in words, the intervals and standard errors
!>   recomputed from the covariance and t95, the singular values against the
!>   condition number, the rows' times against the CSV, sigma_joint from the residual.
module test_values_torques
   use, intrinsic :: iso_fortran_env, only: output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   use dpend_cli, only: real_str
   use test_cli, only: run_command, scratch_dir
   use test_values_fit, only: read_csv
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_values_torques

   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
   character(len=*), parameter :: model = '--m 1,0.7 --l 0.8,0.6 --damping 0.02,0.01 ' &
                                          //'--coulomb 0.05,0.03 --coulomb-speed 0.5'

contains

   subroutine collect_values_torques(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('known_torques_every_dataset', test_known), &
               new_unittest('encoder_error_predicted', test_encoder), &
               new_unittest('identify_every_dataset', test_identify)]
   end subroutine collect_values_torques

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    values_torques: '//text
   end subroutine report

   !> The applied torques of the test at time t [N m].
   pure function applied(t) result(tau)
      real(dp), intent(in) :: t
      real(dp) :: tau(2)
      tau = [0.4_dp*sin(1.3_dp*t) + 0.2_dp*sin(3.1_dp*t + 0.4_dp), &
             0.15_dp*sin(2.2_dp*t + 1.0_dp) + 0.05_dp]
   end function applied

   !> Simulate the run of known torques in dir (s.h5) and write its angles and torques
   !> at 500 Hz to dir/data.csv (quantised to `counts` per turn when counts > 0).
   subroutine make_data(dir, counts, t, q, qd, qdd, f, tau, error)
      character(len=*), intent(in) :: dir
      integer, intent(in) :: counts
      real(dp), allocatable, intent(out) :: t(:), q(:, :), qd(:, :), qdd(:, :), f(:, :, :), &
                                            tau(:, :)
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      real(dp) :: x(2), step
      integer :: unit, k, stat
      open (newunit=unit, file=dir//'/tq.csv', status='replace', action='write')
      write (unit, '(a)') 't [s],tau1 [N m],tau2 [N m]'
      do k = 0, 6000
         write (unit, '(es24.16e3, 2(",", es24.16e3))') 0.001_dp*k, applied(0.001_dp*k)
      end do
      close (unit)
      stat = run_command(dir, 'simulate '//model//' --torque-file '//dir//'/tq.csv ' &
                         //'--q1 -1.2 --q2 -1.0 --method dop853 --rtol 1e-12 --atol 1e-14 ' &
                         //'--t-end 6 --output-dt 0.002 --output '//dir//'/s.h5 --force')
      call check_true(error, stat == 0, 'simulate exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qddot', qdd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/F_joint', f, error)
      if (.not. allocated(error)) call h5%read('/trajectory/tau', tau, error)
      call h5%close()
      if (allocated(error)) return
      step = 2*pi/max(counts, 1)
      open (newunit=unit, file=dir//'/data.csv', status='replace', action='write')
      write (unit, '(a)') 't [s],q1 [rad],q2 [rad],tau1 [N m],tau2 [N m]'
      do k = 1, size(t)
         x = q(:, k)
         if (counts > 0) x = nint(x/step)*step
         write (unit, '(es24.16e3, 4(",", es24.16e3))') t(k), x, tau(:, k)
      end do
      close (unit)
   end subroutine make_data

   !> Noise-free: every dataset against the simulate file and the applied torques.
   subroutine test_known(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), f(:, :, :), tau_sim(:, :)
      real(dp), allocatable :: tt(:), tq(:, :), tqd(:, :), tqdd(:, :), tf(:, :, :), tau(:, :), &
                               measured(:, :), residual(:, :), rows(:, :)
      real(dp) :: e_tau, e_q, e_qd, e_qdd, e_f, e_res
      integer :: stat, k, lo, hi, window
      dir = scratch_dir('torques')
      call execute_command_line('mkdir -p '//dir)
      call make_data(dir, 0, t, q, qd, qdd, f, tau_sim, error)
      if (allocated(error)) return
      stat = run_command(dir, 'torques '//dir//'/data.csv '//model//' --output '//dir// &
                         '/t.h5 --csv '//dir//'/t.csv')
      call check_true(error, stat == 0, 'torques exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/t.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/torques/t', tt, error)
      if (.not. allocated(error)) call h5%read('/torques/q', tq, error)
      if (.not. allocated(error)) call h5%read('/torques/qdot', tqd, error)
      if (.not. allocated(error)) call h5%read('/torques/qddot', tqdd, error)
      if (.not. allocated(error)) call h5%read('/torques/F_joint', tf, error)
      if (.not. allocated(error)) call h5%read('/torques/tau', tau, error)
      if (.not. allocated(error)) call h5%read('/torques/tau_measured', measured, error)
      if (.not. allocated(error)) call h5%read('/torques/residual', residual, error)
      if (.not. allocated(error)) call h5%readattr('/', 'window', window, error)
      call h5%close()
      if (allocated(error)) return
      call check(error, tt, t, 't: the CSV times', abs=0.0_dp)
      if (allocated(error)) return
      ! the interior (centred windows)
      lo = window/2 + 1
      hi = size(t) - window/2
      e_tau = 0.0_dp; e_q = 0.0_dp; e_qd = 0.0_dp; e_qdd = 0.0_dp; e_f = 0.0_dp
      do k = lo, hi
         e_tau = max(e_tau, maxval(abs(tau(:, k) - applied(t(k)))))
         e_q = max(e_q, maxval(abs(tq(:, k) - q(:, k))))
         e_qd = max(e_qd, maxval(abs(tqd(:, k) - qd(:, k))))
         e_qdd = max(e_qdd, maxval(abs(tqdd(:, k) - qdd(:, k))))
         e_f = max(e_f, maxval(abs(tf(:, :, k) - f(:, :, k))))
      end do
      e_res = maxval(abs(residual - (measured - tau)))
      call report('noise-free 500 Hz, window '//real_str(real(window, dp))// &
                  ': max |tau - applied| '//real_str(e_tau, 2)//' N m, |q - simulate| '// &
                  real_str(e_q, 2)//' rad, qdot '//real_str(e_qd, 2)//' rad/s, qddot '// &
                  real_str(e_qdd, 2)//' rad/s^2, F_joint '//real_str(e_f, 2)//' N')
      call check(error, e_tau, 0.0_dp, 'tau against the applied torques', abs=5e-6_dp)
      if (allocated(error)) return
      call check(error, e_q, 0.0_dp, 'q against simulate', abs=1e-9_dp)
      if (allocated(error)) return
      call check(error, e_qd, 0.0_dp, 'qdot against simulate', abs=1e-5_dp)
      if (allocated(error)) return
      call check(error, e_qdd, 0.0_dp, 'qddot against simulate', abs=1e-4_dp)
      if (allocated(error)) return
      call check(error, e_f, 0.0_dp, 'F_joint against simulate', abs=1e-5_dp)
      if (allocated(error)) return
      call check(error, pack(measured, .true.), pack(tau_sim, .true.), &
                 'tau_measured: the CSV torques', rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, e_res, 0.0_dp, 'residual = tau_measured - tau', abs=1e-15_dp)
      if (allocated(error)) return
      call read_csv(dir//'/t.csv', 7, rows, error)
      if (allocated(error)) return
      call check(error, pack(rows(2:3, :), .true.), pack(tau, .true.), 'CSV tau', &
                 rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, pack(rows(6:7, :), .true.), pack(residual, .true.), 'CSV residual', &
                 abs=1e-18_dp)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_known

   !> 16384 counts per turn: the RMS torque error within a factor 2 of the predicted.
   subroutine test_encoder(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), f(:, :, :), tau_sim(:, :)
      real(dp), allocatable :: tau(:, :), noise(:), bias(:), rms(:)
      integer :: stat, k, lo, hi, window
      dir = scratch_dir('torques-encoder')
      call execute_command_line('mkdir -p '//dir)
      call make_data(dir, 16384, t, q, qd, qdd, f, tau_sim, error)
      if (allocated(error)) return
      stat = run_command(dir, 'torques '//dir//'/data.csv '//model//' --output '//dir//'/t.h5')
      call check_true(error, stat == 0, 'torques exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/t.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/torques/tau', tau, error)
      if (.not. allocated(error)) call h5%readattr('/', 'window', window, error)
      if (.not. allocated(error)) call h5%readattr('/', 'predicted_tau_noise', noise, error)
      if (.not. allocated(error)) call h5%readattr('/', 'predicted_tau_bias', bias, error)
      call h5%close()
      if (allocated(error)) return
      lo = window/2 + 1
      hi = size(t) - window/2
      allocate (rms(2))
      rms = 0.0_dp
      do k = lo, hi
         rms = rms + (tau(:, k) - applied(t(k)))**2
      end do
      rms = sqrt(rms/(hi - lo + 1))
      call report('16384-count encoder at 500 Hz, window '//real_str(real(window, dp))// &
                  ': RMS tau error '//real_str(rms(1), 3)//', '//real_str(rms(2), 3)// &
                  ' N m; predicted (noise, bias) '//real_str(noise(1), 2)//', '// &
                  real_str(bias(1), 2)//'; '//real_str(noise(2), 2)//', '// &
                  real_str(bias(2), 2)//' N m')
      call check_true(error, all(rms < 2*sqrt(noise**2 + bias**2)) .and. &
                      all(rms > 0.25_dp*sqrt(noise**2 + bias**2)), &
                      'RMS torque error not within [1/4, 2] of the predicted')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_encoder

   subroutine test_identify(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, names, units
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), f(:, :, :), tau_sim(:, :)
      real(dp), allocatable :: estimate(:), std_error(:), interval95(:, :), covariance(:, :), &
                               singular(:), tt(:), residual(:, :), sigma_joint(:), &
                               physical(:, :), truth(:), phys_truth(:, :)
      real(dp) :: t95, condition, worst, e_phys
      integer :: stat, window, i, np
      dir = scratch_dir('identify')
      call execute_command_line('mkdir -p '//dir)
      call make_data(dir, 0, t, q, qd, qdd, f, tau_sim, error)
      if (allocated(error)) return
      stat = run_command(dir, 'identify '//dir//'/data.csv --m 1,0.7 --l 0.8,0.6 ' &
                         //'--coulomb-speed 0.5 --output '//dir//'/i.h5')
      call check_true(error, stat == 0, 'identify exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/i.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/identify/names', names, error)
      if (.not. allocated(error)) call h5%read('/identify/units', units, error)
      if (.not. allocated(error)) call h5%read('/identify/estimate', estimate, error)
      if (.not. allocated(error)) call h5%read('/identify/std_error', std_error, error)
      if (.not. allocated(error)) call h5%read('/identify/interval95', interval95, error)
      if (.not. allocated(error)) call h5%read('/identify/covariance', covariance, error)
      if (.not. allocated(error)) call h5%read('/identify/singular', singular, error)
      if (.not. allocated(error)) call h5%read('/identify/t', tt, error)
      if (.not. allocated(error)) call h5%read('/identify/residual', residual, error)
      if (.not. allocated(error)) call h5%read('/identify/sigma_joint', sigma_joint, error)
      if (.not. allocated(error)) call h5%read('/identify/physical', physical, error)
      if (.not. allocated(error)) call h5%readattr('/', 't95', t95, error)
      if (.not. allocated(error)) call h5%readattr('/', 'condition', condition, error)
      if (.not. allocated(error)) call h5%readattr('/', 'window', window, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, names == 'J1 + 0.64 m2; h1 + 0.8 m2; c1; cf1; J2; h2; c2; cf2' &
                      .and. units == 'kg m^2; kg m; N m s; N m; kg m^2; kg m; N m s; N m', &
                      'names and units: '//names//' / '//units)
      if (allocated(error)) return
      ! rods: J = m l^2/3, h = m l/2; the frictions of the model
      truth = [1.0_dp*0.8_dp**2/3 + 0.64_dp*0.7_dp, 1.0_dp*0.4_dp + 0.8_dp*0.7_dp, 0.02_dp, &
               0.05_dp, 0.7_dp*0.6_dp**2/3, 0.7_dp*0.3_dp, 0.01_dp, 0.03_dp]
      worst = maxval(abs(estimate - truth)/abs(truth))
      phys_truth = reshape([0.8_dp**2/3, 0.4_dp, 1.0_dp, 0.02_dp, 0.05_dp, &
                            0.7_dp*0.6_dp**2/3, 0.21_dp, 0.7_dp, 0.01_dp, 0.03_dp], [5, 2])
      ! (row 6, the rotors' Im: not estimated, NaN)
      call check_true(error, size(physical, 1) == 6 .and. all(ieee_is_nan(physical(6, :))), &
                      'physical: Im not determined without --rotors estimate')
      if (allocated(error)) return
      e_phys = maxval(abs(physical(1:5, :) - phys_truth)/phys_truth)
      call report('identify of the noise-free run (window '//real_str(real(window, dp))// &
                  ', '//real_str(real(size(tt), dp))//' rows): max rel error of the base '// &
                  'parameters '//real_str(worst, 2)//', of J, h, c, cf per link with the '// &
                  'masses given '//real_str(e_phys, 2))
      call check(error, worst, 0.0_dp, 'estimate against the closed forms', abs=1e-4_dp)
      if (allocated(error)) return
      call check(error, e_phys, 0.0_dp, 'physical against the rods', abs=1e-4_dp)
      if (allocated(error)) return
      np = size(estimate)
      call check(error, std_error, [(sqrt(covariance(i, i)), i = 1, np)], &
                 'std_error = sqrt(diag covariance)', rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, interval95(1, :), estimate - t95*std_error, 'interval95 low', &
                 rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, interval95(2, :), estimate + t95*std_error, 'interval95 high', &
                 rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, pack(covariance, .true.), pack(transpose(covariance), .true.), &
                 'covariance symmetric', rel=1e-12_dp)
      if (allocated(error)) return
      call check_true(error, all(singular(1:np - 1) >= singular(2:np)), 'singular sorted')
      if (allocated(error)) return
      call check(error, singular(1)/singular(np), condition, 'singular: the condition', &
                 rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, tt, t(window/2 + 1:size(t) - window/2:window), &
                 't: every window-th CSV time', abs=0.0_dp)
      if (allocated(error)) return
      call check(error, sigma_joint, sqrt(sum(residual**2, dim=2)/(size(tt) - &
                 real(np, dp)/2)), 'sigma_joint from the residual', rel=1e-12_dp)
      if (allocated(error)) return
      call check_true(error, maxval(abs(residual)) < 1e-5_dp, 'residual of noise-free ' &
                      //'data: '//real_str(maxval(abs(residual)), 2))
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_identify

end module test_values_torques
