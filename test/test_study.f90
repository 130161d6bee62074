!> The energy-conservation study: its arithmetic (power-law fits, drift
!> exponents, grids) on synthetic data with known answers, the quadruple-
!> precision energy, a tiny study run in process, the default configuration
!> file, and the command's rejection of bad input.
module test_study
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, hamiltonian, dh_dq, dh_dp, hamiltonian_qp
   use dpend_fit, only: fit_t, loglog_fit, drift_exponent
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_study_settings, only: study_config_t, study_case_t, study_method_t, &
      study_defaults, validate_study_config, study_namelist, apply_quick, balance_case, &
      study_times_in_seconds
   use dpend_study_config, only: read_study_config
   use dpend_study, only: study_result_t, run_study, step_grid, time_bins
   use dpend_study_command, only: write_study_h5, study_summary
   use dpend_study_verdicts, only: study_verdicts, verdicts_t
   use test_cli, only: run_command, scratch_dir, read_text
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, tiny_study_config
   use dpend_cli, only: to_str
   use dpend_method_registry, only: method_table, field_method_names, method_index
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec, new_model
   use dpend_study_settings, only: case_model
   use dpend_limits, only: sci
   use dpend_joint_torque, only: torque_sines
   use dpend_study_settings, only: read_case_torques, check_case_torques
   implicit none
   private
   public :: collect_study

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_study(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('fit_exact_power_law', test_fit_exact), &
              new_unittest('fit_with_noise', test_fit_noise), &
              new_unittest('fit_window_floor_and_gaps', test_fit_window), &
              new_unittest('drift_exponents_known', test_drift), &
              new_unittest('grids', test_grids), &
              new_unittest('hamiltonian_quadruple', test_hamiltonian_qp), &
              new_unittest('tiny_study_orders', test_tiny_study), &
              new_unittest('tiny_chain_study', test_tiny_chain_study), &
              new_unittest('tiny_damped_study', test_tiny_damped_study), &
              new_unittest('tiny_torqued_study', test_tiny_torqued_study), &
              new_unittest('torque_file_cases', test_torque_config), &
              new_unittest('tiny_elastic_study', test_tiny_elastic_study), &
              new_unittest('quadruple_h_through_the_model', test_model_hamiltonian_qp), &
              new_unittest('damped_config_file', test_damped_config), &
              new_unittest('chain_config_file', test_chain_config), &
              new_unittest('default_config_file', test_default_config), &
              new_unittest('bad_input_rejected', test_bad_input), &
              new_unittest('time_unit_natural', test_time_unit)]
   end subroutine collect_study

   ! ----------------------------------------------------------------- helpers

   !> Deterministic standard normal numbers (Park–Miller generator + Box–Muller),
   !> reproducible on every compiler.
   subroutine normals(z)
      real(dp), intent(out) :: z(:)
      integer(i8) :: s
      real(dp) :: u1, u2
      integer :: i
      s = 12345_i8
      do i = 1, size(z)
         u1 = next()
         u2 = next()
         z(i) = sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
      end do
   contains
      real(dp) function next()
         s = modulo(16807_i8*s, 2147483647_i8)
         next = real(s, dp)/2147483647.0_dp
      end function next
   end subroutine normals

   subroutine write_file(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)') text
      close (unit)
   end subroutine write_file


   ! ------------------------------------------------------------------- fits

   !> y = 3 x^2.5 exactly: slope 2.5, intercept ln 3, no scatter.
   subroutine test_fit_exact(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: x(9), y(9)
      type(fit_t) :: fit
      integer :: i
      x = [(1.0e-3_dp*2.0_dp**(0.5_dp*i), i=0, 8)]
      y = 3.0_dp*x**2.5_dp
      fit = loglog_fit(x, y)
      call check_true(error, fit%ok .and. fit%n == 9, 'fit uses all 9 points')
      call check(error, fit%slope, 2.5_dp, 'slope', abs=1e-12_dp)
      call check(error, fit%intercept, log(3.0_dp), 'intercept', abs=1e-10_dp)
      call check(error, fit%stderr, 0.0_dp, 'standard error', abs=1e-10_dp)
      call check(error, fit%x_lo, x(1), 'x_lo', rel=1e-15_dp)
      call check(error, fit%x_hi, x(9), 'x_hi', rel=1e-15_dp)
      ! decreasing power (error against work)
      fit = loglog_fit(x, 7.0_dp*x**(-8))
      call check(error, fit%slope, -8.0_dp, 'slope -8', abs=1e-10_dp)
   end subroutine test_fit_exact

   !> y = 2 x^(-1.5) exp(σ z), z standard normal, σ = 0.1, 400 points over 3
   !> decades: the slope is -1.5 within 3 theoretical standard errors
   !> σ/(√n sd(ln x)), and the reported standard error is that value within 20 %.
   subroutine test_fit_noise(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: n = 400
      real(dp), parameter :: sigma = 0.1_dp
      real(dp) :: x(n), y(n), z(n), lx(n), sd, expected
      type(fit_t) :: fit
      integer :: i
      call normals(z)
      x = [(10.0_dp**(3.0_dp*(i - 1)/real(n - 1, dp)), i=1, n)]
      y = 2.0_dp*x**(-1.5_dp)*exp(sigma*z)
      lx = log(x)
      sd = sqrt(sum((lx - sum(lx)/n)**2)/n)
      expected = sigma/(sqrt(real(n, dp))*sd)
      fit = loglog_fit(x, y)
      call check(error, fit%slope, -1.5_dp, 'noisy slope', abs=3.0_dp*expected)
      call check(error, fit%stderr, expected, 'standard error of the slope', rel=0.2_dp)
      call check(error, fit%intercept, log(2.0_dp), 'noisy intercept', abs=0.05_dp)
   end subroutine test_fit_noise

   !> Window and floor select the points; NaN, zero and negative values are
   !> skipped; fewer than two usable points give no fit.
   subroutine test_fit_window(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: t(40), e(40), nan
      type(fit_t) :: fit
      integer :: i
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      ! bounded (1e-8) up to t = 10, then a linear drift 1e-9 t
      t = [(10.0_dp**(-1.0_dp + 0.15_dp*i), i=0, 39)]
      e = max(1.0e-8_dp, 1.0e-9_dp*t)
      fit = loglog_fit(t, e, x_min=20.0_dp, x_max=1.0e5_dp)
      call check(error, fit%slope, 1.0_dp, 'windowed drift', abs=1e-12_dp)
      fit = loglog_fit(t, e, x_max=9.0_dp)
      call check(error, fit%slope, 0.0_dp, 'windowed plateau', abs=1e-12_dp)
      ! a roundoff floor at 1e-8: only the drifting points count
      fit = loglog_fit(t, e, y_min=1.5e-8_dp)
      call check(error, fit%slope, 1.0_dp, 'floor removes the plateau', abs=1e-12_dp)
      ! gaps
      e(5) = nan; e(30) = 0.0_dp; e(31) = -1.0_dp
      fit = loglog_fit(t, e, x_min=20.0_dp)
      call check_true(error, fit%ok .and. fit%n == count(t >= 20.0_dp) - 2, &
                      'NaN, zero and negative values skipped, n = '//to_str(fit%n))
      call check(error, fit%slope, 1.0_dp, 'slope with gaps', abs=1e-12_dp)
      fit = loglog_fit([1.0_dp, 2.0_dp, 3.0_dp], [nan, 1.0_dp, 0.0_dp])
      call check_true(error, .not. fit%ok .and. fit%n == 1, 'one usable point: no fit')
      fit = loglog_fit([2.0_dp, 2.0_dp], [1.0_dp, 3.0_dp])
      call check_true(error, .not. fit%ok, 'equal x: no fit')
   end subroutine test_fit_window

   !> Drift exponents of known error histories kept as maxima in logarithmic
   !> time bins, as the study does: a bounded oscillation (0), a linear drift
   !> plus oscillation (1), and a √t envelope (1/2).
   subroutine test_drift(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: edges(50), b0(50), b1(50), bh(50), t, e
      integer :: j, i
      type(fit_t) :: fit
      edges = time_bins(1.0e4_dp, 5, 10)
      call check(error, edges(50), 1.0e4_dp, 'last bin edge', rel=1e-15_dp)
      call check(error, edges(1), 1.0e4_dp*10.0_dp**(-4.9_dp), 'first bin edge', rel=1e-12_dp)
      b0 = -1.0_dp; b1 = -1.0_dp; bh = -1.0_dp
      j = 1
      do i = 1, 1000000
         t = 0.01_dp*i
         do while (j < 50)
            if (t <= edges(j)) exit
            j = j + 1
         end do
         e = 1.0e-6_dp*abs(sin(2.7_dp*t))
         b0(j) = max(b0(j), e)
         b1(j) = max(b1(j), 1.0e-9_dp*t + 1.0e-10_dp*abs(sin(2.7_dp*t)))
         bh(j) = max(bh(j), 1.0e-12_dp*sqrt(t)*(1.0_dp + 0.1_dp*sin(t)))
      end do
      where (b0 < 0.0_dp) b0 = ieee_value(1.0_dp, ieee_quiet_nan)
      fit = drift_exponent(edges, b0, 100.0_dp, 1.0e4_dp)
      call check(error, fit%slope, 0.0_dp, 'bounded oscillation', abs=1e-3_dp)
      fit = drift_exponent(edges, b1, 100.0_dp, 1.0e4_dp)
      call check(error, fit%slope, 1.0_dp, 'linear drift', abs=0.01_dp)
      fit = drift_exponent(edges, bh, 100.0_dp, 1.0e4_dp)
      call check(error, fit%slope, 0.5_dp, 'square-root growth', abs=0.01_dp)
   end subroutine test_drift

   !> Step grids hit the checkpoints exactly and stay geometric.
   subroutine test_grids(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: h(7), target
      integer :: k
      h = step_grid(1.0e-3_dp, 4.0e-3_dp, 7, 0.25_dp)
      do k = 1, 7
         call check(error, 0.25_dp/h(k), real(nint(0.25_dp/h(k)), dp), 'steps per interval', &
                    abs=1e-9_dp)
         target = 4.0e-3_dp*(0.25_dp)**((k - 1)/6.0_dp)
         call check(error, h(k), target, 'close to the geometric target', rel=0.02_dp)
         if (k > 1) call check_true(error, h(k) < h(k - 1), 'strictly decreasing')
      end do
      ! coarse rounding still gives distinct steps
      h = step_grid(0.05_dp, 0.1_dp, 7, 0.25_dp)
      call check_true(error, all(h(2:) < h(:6)), 'distinct steps when rounding is coarse')
   end subroutine test_grids

   !> The quadruple-precision H agrees with the model's H, and its dependence
   !> on the compensation e is the gradient of H.
   subroutine test_hamiltonian_qp(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: y(4), e(4), grad(4), dh
      real(dp), parameter :: states(4, 3) = reshape([-1.2_dp, -1.7_dp, 0.3_dp, -0.2_dp, &
                                                     0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
                                                     2.0_dp, -3.0_dp, 4.0_dp, 1.0_dp], [4, 3])
      integer :: i
      par = pendulum_t(m1=1.3_dp, m2=0.7_dp, l1=0.9_dp, l2=1.4_dp, g=9.81_dp)
      do i = 1, 3
         y = states(:, i)
         call check(error, real(hamiltonian_qp(par, y, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]), dp), &
                    hamiltonian(par, y(1:2), y(3:4)), 'H in quad vs double', abs=1e-14_dp)
         e = 1.0e-12_dp*[1.0_dp, -2.0_dp, 0.5_dp, 3.0_dp]
         grad = [dh_dq(par, y(1:2), y(3:4)), dh_dp(par, y(1:2), y(3:4))]
         dh = real(hamiltonian_qp(par, y, e) - hamiltonian_qp(par, y, 0.0_dp*e), dp)
         call check(error, dh, dot_product(grad, e), 'dH = grad H . e', &
                    rel=1e-6_dp, abs=1e-24_dp)
      end do
   end subroutine test_hamiltonian_qp

   ! ------------------------------------------------------------------ study

   !> A tiny study in process: two cases, four methods, short long runs, two
   !> roundoff runs, two values of ω. The measured orders are the nominal ones
   !> (±0.3), the file holds the tables, the summary names every method.
   subroutine test_tiny_study(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(study_result_t) :: res, res1
      type(verdicts_t) :: v
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir, md, text
      real(dp), allocatable :: h(:), ge(:)
      real(dp) :: order
      integer :: s, drift_ok, roundoff_ok
      ! the shared tiny study, longer: four steps, three tolerances, 300 roundoff steps,
      ! Tao's runs over 0.5 s, two threads
      cfg = tiny_study_config(3000.0_dp, 300.0_dp)
      cfg%n_h = 4
      cfg%n_rtol = 3
      cfg%ro_steps = 300.0_dp
      cfg%tao_t_end = 0.5_dp
      cfg%threads = 2
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      call check_true(error, size(res%sweeps) == 2*5, 'sweeps: 2 cases x (4 + 1 tolerance)')
      ! the jobs share nothing: one thread gives bit for bit the same numbers
      cfg%threads = 1
      call run_study(cfg, res1, quiet=.true.)
      do s = 1, size(res%sweeps)
         call check_true(error, all(res1%sweeps(s)%global_error == res%sweeps(s)%global_error) &
                         .and. all(res1%sweeps(s)%energy_long == res%sweeps(s)%energy_long), &
                         res%sweeps(s)%method//': 1 and 2 threads agree')
      end do
      call check_true(error, all(res1%roundoff(1)%rms == res%roundoff(1)%rms) .and. &
                      all(res1%tao(1)%energy_max == res%tao(1)%energy_max), &
                      'roundoff and Tao runs: 1 and 2 threads agree')
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s))
            if (sw%mode /= 1 .or. sw%icase /= 1) cycle
            call check_true(error, all(sw%stat == 0), sw%method//': every run succeeded')
            call check_true(error, sw%fit_global%ok .and. sw%fit_energy%ok, sw%method//' fitted')
            if (allocated(error)) return
            call check(error, sw%fit_global%slope, real(sw%order, dp), &
                       sw%method//' order from the global error', abs=0.3_dp)
            call check(error, sw%fit_energy%slope, real(sw%order, dp), &
                       sw%method//' order from the energy error', abs=0.3_dp)
            call check_true(error, all(sw%long_steps > 0) .and. all(sw%short_rhs > 0), &
                            sw%method//' counters')
            call check_true(error, all(sw%wall_short > 0.0_dp), sw%method//' wall times')
            if (sw%method == 'gauss4' .or. sw%method == 'verlet') &
               call check_true(error, all(sw%short_iter > 0), sw%method//' inner iterations')
         end associate
      end do
      call check_true(error, res%refs(1)%check_difference < 1e-12_dp, &
                      'reference and check method agree')
      call check_true(error, res%refs(2)%e_scale > 19.0_dp, &
                      'horizontal release: E_s is the upright potential energy (19.6 J)')
      v = study_verdicts(cfg, res)
      call check_true(error, v%orders, 'order verdict: '//v%orders_text)
      if (allocated(error)) return   ! (the next call would reset error)
      dir = scratch_dir('study-tiny')
      call write_study_h5(cfg, res, dir//'/tiny.h5', error)
      if (allocated(error)) return
      call h5%open(dir//'/tiny.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/cases/small/gauss4/step/h', h, error)
      if (.not. allocated(error)) call h5%read('/cases/small/gauss4/step/global_error', ge, error)
      if (.not. allocated(error)) call h5%readattr('/cases/small/gauss4/step', 'order_global', &
                                                    order, error)
      if (.not. allocated(error)) call h5%readattr('/', 'methods', text, error)
      if (.not. allocated(error)) call h5%readattr('/summary', 'drift_ok', drift_ok, error)
      if (.not. allocated(error)) call h5%readattr('/summary', 'roundoff_ok', roundoff_ok, error)
      call h5%close()
      if (allocated(error)) return
      ! every long run here is far below drift_min_steps: the drift is not judged (-1),
      ! while the roundoff experiment ran (0 or 1)
      call check_true(error, drift_ok == -1 .and. .not. v%drift_judged, &
                      'drift_ok = -1 when no long run is long enough: '//to_str(drift_ok))
      ! the roundoff verdict recomputed here from the runs' errors: the RMS over the
      ! runs of the compensated (H - H0)/E_s, its least-squares slope in ln t against
      ! ln t over t >= ro_fit_t_min, Brouwer's law 0.5 ± 0.15 (brouwer_tol): roundoff_ok
      ! must be that verdict, not merely 0 or 1
      block
         use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
         real(dp), allocatable :: rms(:), lt(:), lr(:)
         logical, allocatable :: usable(:)
         real(dp) :: slope
         integer :: expected
         character(len=12) :: slope_text
         associate (ro => res%roundoff(1))
            rms = sqrt(sum(ro%err(:, :, 1)**2, dim=2)/real(size(ro%err, 2), dp))
            usable = ieee_is_finite(rms) .and. ro%t >= cfg%ro_fit_t_min
            usable = usable .and. merge(rms, 0.0_dp, usable) > 0.0_dp
            lt = log(pack(ro%t, usable)); lr = log(pack(rms, usable))
            lt = lt - sum(lt)/size(lt); lr = lr - sum(lr)/size(lr)
            slope = sum(lt*lr)/sum(lt**2)
            expected = merge(1, 0, abs(slope - 0.5_dp) <= 0.15_dp)
            call check_true(error, size(lt) >= 10, 'roundoff: usable samples '// &
                            to_str(size(lt)))
            call check(error, ro%fit(1)%slope, slope, 'roundoff exponent', abs=1e-12_dp)
         end associate
         write (slope_text, '(f12.4)') slope
         call check_true(error, roundoff_ok == expected, 'roundoff_ok '// &
                         to_str(roundoff_ok)//', the exponent '//trim(adjustl(slope_text))// &
                         ' gives '//to_str(expected))
      end block
      call check_true(error, size(h) == 4 .and. size(ge) == 4, 'sweep arrays of 4 points')
      call check(error, order, 4.0_dp, 'order attribute', abs=0.3_dp)
      call check_true(error, text == 'rk4 dopri5 gauss4 verlet', 'methods attribute: '//text)
      md = study_summary(cfg, res)
      call check_true(error, index(md, '| gauss4 | 4 |') > 0 .and. index(md, '| verlet |') > 0 &
                      .and. index(md, 'Roundoff') > 0 .and. index(md, 'tao2') > 0, &
                      'summary tables')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_tiny_study

   !> A tiny study of the triple pendulum (N-link chain, N = 3) in process: the
   !> orders of rk4 and gauss4 are the nominal ones (±0.3), H(0) is the chain's
   !> potential energy in closed form, the states have 2N = 6 components, and the
   !> roundoff experiment (the double pendulum's H in quadruple precision) reads
   !> "not run for the N-link chain" while the Tao runs are made.
   subroutine test_tiny_chain_study(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      type(verdicts_t) :: v
      character(len=:), allocatable :: md
      real(dp) :: v0
      integer :: s
      cfg = study_defaults()
      cfg%cases = [study_case_t('triple', [-0.5_dp*pi + 0.3_dp, -0.5_dp*pi - 0.2_dp, &
                                           -0.5_dp*pi + 0.1_dp], [0.0_dp, 0.0_dp, 0.0_dp], &
                                300.0_dp)]
      cfg%methods = [study_method_t('rk4', 1.0e-3_dp, 2.5e-3_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('gauss4', 1.0e-2_dp, 2.5e-2_dp, 0.0_dp, 0.0_dp)]
      cfg%n_h = 4
      cfg%order_case = 'triple'
      cfg%drift_case = 'triple'
      cfg%ro_case = 'triple'
      cfg%tao_case = 'triple'
      cfg%decades = 2
      cfg%wall_min = 0.0_dp
      cfg%ro_methods = [character(len=16) :: 'gauss4']
      cfg%ro_dt = [1.0e-2_dp]
      cfg%ro_steps = 300.0_dp
      cfg%ro_runs = 2
      cfg%tao_methods = [character(len=16) :: 'tao2']
      cfg%n_omega = 2
      cfg%tao_t_end = 0.5_dp
      cfg%tao_dt = 1.0e-2_dp
      cfg%threads = 2
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      ! V = sum_i G_i sin q_i, G = g l (m_i/2 + sum_(k>i) m_k) = 9.8 (2.5, 1.5, 0.5) J
      v0 = -9.8_dp*(2.5_dp*cos(0.3_dp) + 1.5_dp*cos(0.2_dp) + 0.5_dp*cos(0.1_dp))
      call check(error, res%refs(1)%e0, v0, 'H(0) of the triple pendulum at rest', &
                 rel=1e-13_dp)
      call check_true(error, size(res%refs(1)%y, 1) == 6 .and. &
                      size(res%sweeps(1)%y_check, 1) == 6, 'states of 2N = 6 components')
      call check_true(error, res%refs(1)%check_difference < 1e-12_dp, &
                      'reference and check method agree: '//sci(res%refs(1)%check_difference))
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s))
            call check_true(error, all(sw%stat == 0), sw%method//': every run succeeded')
            call check_true(error, sw%fit_global%ok .and. sw%fit_energy%ok, sw%method//' fitted')
            if (allocated(error)) return
            call check(error, sw%fit_global%slope, real(sw%order, dp), &
                       sw%method//' order from the global error (N = 3)', abs=0.3_dp)
            call check(error, sw%fit_energy%slope, real(sw%order, dp), &
                       sw%method//' order from the energy error (N = 3)', abs=0.3_dp)
         end associate
      end do
      call check_true(error, size(res%roundoff) == 0 .and. size(res%tao) == 1, &
                      'no roundoff runs on the chain, Tao runs made')
      call check_true(error, all(res%tao(1)%stat == 0), 'Tao runs succeeded')
      v = study_verdicts(cfg, res)
      call check_true(error, v%orders, 'order verdict: '//v%orders_text)
      call check_true(error, .not. v%roundoff_run .and. &
                      index(v%roundoff_text, 'not run for the N-link chain') > 0, &
                      'roundoff verdict: '//v%roundoff_text)
      md = study_summary(cfg, res)
      call check_true(error, index(md, 'roundoff: not run: not run for the N-link chain') > 0, &
                      'summary names the roundoff experiment not run')
   end subroutine test_tiny_chain_study

   !> A tiny study of the elastic pendulum from data/elastic_study.nml (&model): the
   !> file reads and reads back (study_namelist); reduced to one case and three
   !> methods (rk4 on (q, q̇), gauss4 on (q, p), verlet on the non-separable H), the
   !> orders from the global and the energy error are the registry's (±0.3); H(0) is
   !> the closed-form energy k/2 (r − l0)² + m g r sin φ of the bob at rest; the states
   !> have 4 components; the roundoff experiment reads "not run for model elastic"
   !> (no H in quadruple precision) while the Tao runs are made; the summary gives
   !> the units m, rad; a failed check or reference run is named in words in the
   !> summary (not the saturated difference 1.8E+308).
   subroutine test_tiny_elastic_study(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg, back
      type(study_result_t) :: res
      type(verdicts_t) :: v
      character(len=:), allocatable :: md, dir, text
      real(dp) :: e0, r, phi
      integer :: s
      cfg = study_defaults()
      call read_study_config('data/elastic_study.nml', cfg, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      dir = scratch_dir('study-elastic-config')
      text = study_namelist(cfg)
      call write_file(dir//'/back.nml', text)
      back = study_defaults()
      call read_study_config(dir//'/back.nml', back, error)
      if (allocated(error)) return
      call check_true(error, study_namelist(back) == text, 'elastic namelist reads back:'// &
                      new_line('a')//text)
      call execute_command_line('rm -rf '//dir)
      if (allocated(error)) return
      r = 1.3_dp; phi = -0.5_dp*pi + 0.2_dp
      cfg%cases = [study_case_t('small', [r, phi], [0.0_dp, 0.0_dp], 300.0_dp)]
      cfg%methods = [study_method_t('rk4', 1.0e-3_dp, 2.5e-3_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('gauss4', 5.0e-3_dp, 1.25e-2_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('verlet', 2.5e-3_dp, 1.0e-2_dp, 0.0_dp, 0.0_dp)]
      cfg%n_h = 4
      cfg%decades = 2
      cfg%wall_min = 0.0_dp
      cfg%ro_methods = [character(len=16) :: 'gauss4']
      cfg%ro_dt = [1.0e-2_dp]
      cfg%ro_steps = 300.0_dp
      cfg%ro_runs = 2
      cfg%tao_methods = [character(len=16) :: 'tao2']
      cfg%n_omega = 2
      cfg%tao_t_end = 0.5_dp
      cfg%tao_dt = 1.0e-2_dp
      cfg%threads = 2
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      ! m = 1 kg, k = 40 N/m, l0 = 1 m, g = 9.8 m/s² (the file's &model)
      e0 = 0.5_dp*40.0_dp*(r - 1.0_dp)**2 + 9.8_dp*r*sin(phi)
      call check(error, res%refs(1)%e0, e0, 'H(0) of the elastic pendulum at rest', &
                 rel=1e-13_dp)
      call check_true(error, size(res%refs(1)%y, 1) == 4, 'states of 4 components')
      call check_true(error, res%refs(1)%check_difference < 1e-11_dp, &
                      'reference and check method agree: '//sci(res%refs(1)%check_difference))
      if (allocated(error)) return
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s))
            call check_true(error, all(sw%stat == 0), sw%method//': every run succeeded')
            call check_true(error, sw%fit_global%ok .and. sw%fit_energy%ok, sw%method//' fitted')
            if (allocated(error)) return
            call check(error, sw%fit_global%slope, &
                       real(method_table(method_index(sw%method))%order, dp), &
                       sw%method//' order from the global error (elastic)', abs=0.3_dp)
            call check(error, sw%fit_energy%slope, &
                       real(method_table(method_index(sw%method))%order, dp), &
                       sw%method//' order from the energy error (elastic)', abs=0.3_dp)
         end associate
      end do
      call check_true(error, size(res%roundoff) == 0 .and. size(res%tao) == 1, &
                      'no roundoff runs on the elastic pendulum, Tao runs made')
      call check_true(error, all(res%tao(1)%stat == 0), 'Tao runs succeeded')
      v = study_verdicts(cfg, res)
      call check_true(error, v%orders, 'order verdict: '//v%orders_text)
      call check_true(error, .not. v%roundoff_run .and. &
                      index(v%roundoff_text, 'not run for model elastic') > 0, &
                      'roundoff verdict: '//v%roundoff_text)
      md = study_summary(cfg, res)
      call check_true(error, index(md, 'q = (r, phi) [m, rad]') > 0 .and. &
                      index(md, '1.8E+308') == 0 .and. index(md, 'links upright') == 0, &
                      'summary in the model''s units')
      ! a failed check run: the summary says so in words, not the saturated difference
      res%refs(1)%stat = 2; res%refs(1)%check_stat = 2
      res%refs(1)%check_difference = huge(1.0_dp)
      md = study_summary(cfg, res)
      call check_true(error, index(md, 'check run failed (state became non-finite') > 0 &
                      .and. index(md, 'E+308') == 0, 'failed check in words')
      res%refs(1)%check_stat = 0
      md = study_summary(cfg, res)
      call check_true(error, index(md, 'reference run failed (state became non-finite') > 0 &
                      .and. index(md, 'E+308') == 0, 'failed reference in words')
   end subroutine test_tiny_elastic_study

   !> The quadruple-precision H through the model: the double pendulum has it and
   !> agrees with `hamiltonian_qp` of its parameters; the elastic pendulum and the
   !> chain do not (the study makes no roundoff runs on them).
   subroutine test_model_hamiltonian_qp(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      class(model_t), allocatable :: model
      real(dp) :: y(4)
      cfg = study_defaults()
      call case_model(cfg, 1, model)
      call check_true(error, model%has_hamiltonian_qp(), 'double pendulum has H in qp')
      if (allocated(error)) return
      y = [0.3_dp, -1.1_dp, 0.7_dp, -0.2_dp]
      call check_true(error, model%hamiltonian_qp(y, 1e-17_dp*y) == &
                      hamiltonian_qp(pendulum_t(), y, 1e-17_dp*y), 'the same H as hamiltonian_qp')
      call new_model(model_spec('elastic'), model, error)
      if (allocated(error)) return
      call check_true(error, .not. model%has_hamiltonian_qp(), 'elastic: no H in qp')
      cfg%cases = [study_case_t('triple', [0.1_dp, 0.2_dp, 0.3_dp], [0.0_dp, 0.0_dp, 0.0_dp], &
                                300.0_dp)]
      call case_model(cfg, 1, model)
      call check_true(error, .not. model%has_hamiltonian_qp(), 'chain: no H in qp')
   end subroutine test_model_hamiltonian_qp

   !> A tiny study of a damped double pendulum on a moving support (a balance case) in
   !> process: rk4 and gauss6 (on (q, q̇): the model has no Hamiltonian) keep their
   !> orders in the global error and in the energy balance error; gauss6 at its
   !> smallest step balances to 1e-10; the case is not symplectic, the drift verdict is
   !> not applied, and neither roundoff nor Tao runs are made on it.
   subroutine test_tiny_damped_study(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      type(verdicts_t) :: v
      character(len=:), allocatable :: md
      cfg = study_defaults()
      cfg%cases = [study_case_t('shaken', [-0.5_dp*pi + 0.3_dp, -0.5_dp*pi - 0.2_dp], &
                                [0.0_dp, 0.0_dp], 300.0_dp)]
      cfg%cases(1)%damping = [0.05_dp, 0.03_dp]
      cfg%cases(1)%support_amplitude = [0.01_dp, 0.02_dp]
      cfg%cases(1)%support_frequency = 10.0_dp
      cfg%methods = [study_method_t('rk4', 1.0e-3_dp, 2.5e-3_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('gauss6', 6.0e-3_dp, 1.6e-2_dp, 0.0_dp, 0.0_dp)]
      cfg%n_h = 4
      cfg%order_case = 'shaken'; cfg%drift_case = 'shaken'
      cfg%ro_case = 'shaken'; cfg%tao_case = 'shaken'
      cfg%decades = 2
      cfg%wall_min = 0.0_dp
      cfg%threads = 2
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      call check_true(error, res%refs(1)%check_difference < 1e-12_dp, &
                      'reference (gauss8 on (q, qdot)) and dop853 agree: '// &
                      sci(res%refs(1)%check_difference))
      call check_balance_sweeps(res, 'damped, driven', error)
      if (allocated(error)) return
      call check_true(error, size(res%roundoff) == 0 .and. size(res%tao) == 0, &
                      'no roundoff or Tao runs on a damped case')
      v = study_verdicts(cfg, res)
      call check_true(error, v%orders, 'order verdict: '//v%orders_text)
      call check_true(error, .not. v%drift_judged .and. &
                      index(v%drift_text, 'is damped or driven') > 0, &
                      'drift verdict: '//v%drift_text)
      md = study_summary(cfg, res)
      call check_true(error, index(md, '- drift: not applied: case shaken is damped or ' &
                                   //'driven') > 0 .and. index(md, '## Energy balance') > 0, &
                      'summary: drift not applied, energy balance section')
   end subroutine test_tiny_damped_study

   !> The sweeps of a balance case (`what`: its forces): every run succeeded, none
   !> symplectic, each method's order (within 0.3) in the global error and in the
   !> energy balance error, gauss6's balance at its smallest step within 1e-10; the
   !> figures printed ('    study: …').
   subroutine check_balance_sweeps(res, what, error)
      type(study_result_t), intent(in) :: res
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: error
      integer :: s
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s))
            call check_true(error, all(sw%stat == 0) .and. .not. sw%symplectic, sw%method// &
                            ': every run succeeded, not symplectic ('//what//')')
            call check_true(error, sw%fit_global%ok .and. sw%fit_energy%ok, sw%method//' fitted')
            if (allocated(error)) return
            call check(error, sw%fit_global%slope, real(sw%order, dp), &
                       sw%method//' order from the global error ('//what//')', abs=0.3_dp)
            call check(error, sw%fit_energy%slope, real(sw%order, dp), &
                       sw%method//' order from the energy balance error ('//what//')', &
                       abs=0.3_dp)
            if (allocated(error)) return
            if (sw%method == 'gauss6') call check(error, sw%energy_long(size(sw%x)), 0.0_dp, &
                                                  'gauss6 balance error ('//what//') at h = '// &
                                                  sci(sw%x(size(sw%x))), abs=1e-10_dp)
            write (*, '(a, f6.3, a, f6.3, a, es9.2)') '    study: '//what//', '//sw%method// &
               ' order (global) ', sw%fit_global%slope, ', (balance) ', sw%fit_energy%slope, &
               ', longest balance error ', maxval(sw%energy_long)
         end associate
      end do
   end subroutine check_balance_sweeps

   !> A tiny study of a double pendulum driven by joint torques (the closed form
   !> τ1 = 0.3 + 0.4 sin(3 t), τ2 = −0.2 cos(5 t) with a little damping): a balance case
   !> whose energy balance includes W_torque; rk4 and gauss6 keep their orders in the
   !> global error and in the balance error, gauss6 balances to 1e-10, no drift verdict.
   subroutine test_tiny_torqued_study(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      type(verdicts_t) :: v
      cfg = study_defaults()
      cfg%cases = [study_case_t('torqued', [-0.5_dp*pi + 0.3_dp, -0.5_dp*pi - 0.2_dp], &
                                [0.0_dp, 0.0_dp], 300.0_dp)]
      cfg%cases(1)%damping = [0.02_dp, 0.01_dp]
      cfg%cases(1)%torque = torque_sines([0.3_dp, 0.0_dp], &
                                         reshape([0.4_dp, 0.0_dp, 0.0_dp, 0.2_dp], [2, 2]), &
                                         [3.0_dp, 5.0_dp], &
                                         reshape([0.0_dp, 0.0_dp, 0.0_dp, -0.5_dp*pi], &
                                                 [2, 2]), error)
      if (allocated(error)) return
      cfg%methods = [study_method_t('rk4', 1.0e-3_dp, 2.5e-3_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('gauss6', 6.0e-3_dp, 1.6e-2_dp, 0.0_dp, 0.0_dp)]
      cfg%n_h = 4
      cfg%order_case = 'torqued'; cfg%drift_case = 'torqued'
      cfg%ro_case = 'torqued'; cfg%tao_case = 'torqued'
      cfg%decades = 2
      cfg%wall_min = 0.0_dp
      cfg%threads = 2
      call check_true(error, balance_case(cfg, 1), 'a case with torques is a balance case')
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call check_case_torques(cfg, error)   ! a closed form covers every run
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      call check_balance_sweeps(res, 'torques', error)
      if (allocated(error)) return
      v = study_verdicts(cfg, res)
      call check_true(error, v%orders, 'order verdict: '//v%orders_text)
      call check_true(error, .not. v%drift_judged, 'no drift verdict with torques')
   end subroutine test_tiny_torqued_study

   !> case_torque_file in &study: read for the case's links, recorded in the namelist
   !> the file keeps, its span checked against the case's runs (refused in one line
   !> naming the key), refused for a model of &model.
   subroutine test_torque_config(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(error_t), allocatable :: err
      character(len=:), allocatable :: dir
      character(len=*), parameter :: cases = "order_case = 'driven', drift_case = " &
                                             //"'driven', ro_case = 'driven', tao_case = 'driven'"
      dir = scratch_dir('studytorque')
      call write_file(dir//'/tq.csv', 't,tau1,tau2'//new_line('a')//'0,0.5,-0.2'// &
                      new_line('a')//'1e6,0.4,0.1'//new_line('a'))
      call write_file(dir//'/short.csv', 't,tau1,tau2'//new_line('a')//'0,0.5,-0.2'// &
                      new_line('a')//'1,0.4,0.1'//new_line('a'))
      call write_file(dir//'/s.nml', "&study case_name(1) = 'driven', case_q1(1) = 0.3, " &
                      //"case_torque_file(1) = '"//dir//"/tq.csv', method(1) = 'rk4', "//cases//' /')
      cfg = study_defaults()
      call read_study_config(dir//'/s.nml', cfg, error)
      if (allocated(error)) return
      call read_case_torques(cfg, error)
      if (allocated(error)) return
      call check_true(error, cfg%cases(1)%torque%active() .and. balance_case(cfg, 1), &
                      'the case has its torques: a balance case')
      if (allocated(error)) return
      call validate_study_config(cfg, err)
      if (.not. allocated(err)) call check_case_torques(cfg, err)
      call check_true(error, .not. allocated(err), 'a series over [0, 1e6] s covers the runs')
      if (allocated(error)) return
      call check_true(error, index(study_namelist(cfg), "case_torque_file(1) = '"//dir// &
                                   "/tq.csv'") > 0, 'the namelist records the torque file')
      if (allocated(error)) return
      call write_file(dir//'/s.nml', "&study case_name(1) = 'driven', case_q1(1) = 0.3, " &
                      //"case_torque_file(1) = '"//dir//"/short.csv', method(1) = 'rk4', "//cases//' /')
      cfg = study_defaults()
      call read_study_config(dir//'/s.nml', cfg, error)
      if (.not. allocated(error)) call read_case_torques(cfg, error)
      if (allocated(error)) return
      call check_case_torques(cfg, err)
      call check_true(error, allocated(err), 'a series over [0, 1] s does not cover the runs')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'invalid case_torque_file(1)') == 1 .and. &
                      index(err%message, 'not extrapolated') > 0, 'refused: '//err%message)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_torque_config

   !> data/study_damped.nml: three balance cases (damped; driven; damped and driven, three
   !> links) that read back through study_namelist; a method that needs a Hamiltonian
   !> is refused with them in one line, as is a damping list of the wrong length.
   subroutine test_damped_config(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg, back
      character(len=:), allocatable :: dir, text
      integer :: s
      cfg = study_defaults()
      call read_study_config('data/study_damped.nml', cfg, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call check_true(error, size(cfg%cases) == 3 .and. all([(balance_case(cfg, s), &
                                                             s=1, 3)]), 'three balance cases')
      if (allocated(error)) return
      call check_true(error, all(cfg%cases(1)%damping == [0.05_dp, 0.03_dp]) .and. &
                      all(cfg%cases(2)%support_amplitude == [0.0_dp, 0.02_dp]) .and. &
                      cfg%cases(2)%support_frequency == 12.0_dp .and. &
                      size(cfg%cases(3)%damping) == 3 .and. cfg%cases(3)%support_phase(1) &
                      == 0.5_dp, 'damping and support read')
      if (allocated(error)) return
      dir = scratch_dir('study-damped-config')
      text = study_namelist(cfg)
      call write_file(dir//'/back.nml', text)
      back = study_defaults()
      call read_study_config(dir//'/back.nml', back, error)
      if (allocated(error)) return
      call check_true(error, study_namelist(back) == text, 'damped namelist reads back:'// &
                      new_line('a')//text)
      if (allocated(error)) return
      ! the first method of the registry that needs a Hamiltonian (verlet)
      s = findloc(method_table%hamiltonian, .true., dim=1)
      call check_true(error, s > 0, 'no method needs a Hamiltonian')
      if (allocated(error)) return
      cfg%methods(1)%name = trim(method_table(s)%name)
      call validate_study_config(cfg, error)
      call check_true(error, allocated(error), trim(method_table(s)%name)// &
                      ' accepted on damped cases')
      if (.not. allocated(error)) return
      text = error%message
      deallocate (error)
      call check_true(error, text == "invalid method(1): '"//trim(method_table(s)%name)// &
                      "' needs a Hamiltonian model; case 'damped' is damped or driven (use " &
                      //field_method_names()//")", 'message: '//text)
      if (allocated(error)) return
      call write_file(dir//'/bad.nml', "&study case_name(1) = 'd', case_damping(1:3, 1) = "// &
                      "0.1, 0.1, 0.1, order_case = 'd', drift_case = 'd', ro_case = 'd', "// &
                      "tao_case = 'd' /")
      cfg = study_defaults()
      call read_study_config(dir//'/bad.nml', cfg, error)
      call check_true(error, allocated(error), 'three damping values for two links accepted')
      if (.not. allocated(error)) return
      text = error%message
      deallocate (error)
      call check_true(error, index(text, 'invalid case_damping(:, 1): 3 values for 2 links') &
                      == 1, 'message: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_damped_config

   !> &integration time_unit = 'natural': the study's times in sqrt(l1/g), with l1 =
   !> 2.45 m, g = 9.8 m/s^2 exactly 0.5 s, converted to seconds once (t_short, the
   !> reference step, a method's steps, Tao's horizon); any other key of
   !> &integration is refused (the study's steps are in &study).
   subroutine test_time_unit(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg, given
      type(error_t), allocatable :: why
      character(len=:), allocatable :: dir
      dir = scratch_dir('study-time-unit')
      call write_file(dir//'/n.nml', "&pendulum l1 = 2.45, g = 9.8 /"//new_line('a')// &
                      "&integration time_unit = 'natural' /"//new_line('a')// &
                      '&study t_short = 2, tao_t_end = 40 /')
      cfg = study_defaults()
      call read_study_config(dir//'/n.nml', cfg, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      given = cfg
      call study_times_in_seconds(cfg)
      call study_times_in_seconds(cfg)   ! once: a second call changes nothing
      call check_true(error, cfg%time_scale == 0.5_dp .and. cfg%t_short == 1.0_dp .and. &
                      cfg%tao_t_end == 20.0_dp .and. cfg%ref_dt == 0.5_dp*given%ref_dt .and. &
                      cfg%methods(1)%h_max == 0.5_dp*given%methods(1)%h_max .and. &
                      trim(cfg%time_unit_name) == 'sqrt(l1/g)', 'times in s: t_short '// &
                      sci(cfg%t_short)//', tao_t_end '//sci(cfg%tao_t_end))
      if (allocated(error)) return
      call write_file(dir//'/d.nml', '&integration dt = 0.1 /')
      cfg = study_defaults()
      call read_study_config(dir//'/d.nml', cfg, why)
      call check_true(error, allocated(why), '&integration dt refused')
      if (allocated(error)) return
      call check_true(error, index(why%message, 'reads only time_unit') > 0, &
                      'the refusal says why: '//why%message)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_time_unit

   !> data/study_chain.nml: two triple-pendulum cases; the effective configuration
   !> written by study_namelist reads back to the same text (lists of links), also
   !> when a double-pendulum case and a chain case are mixed.
   subroutine test_chain_config(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg, back
      character(len=:), allocatable :: dir, text
      cfg = study_defaults()
      call read_study_config('data/study_chain.nml', cfg, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call check_true(error, size(cfg%cases) == 2, 'two cases')
      if (allocated(error)) return
      call check_true(error, size(cfg%cases(1)%q0) == 3 .and. size(cfg%cases(2)%w0) == 3, &
                      'three links each')
      call check(error, cfg%cases(1)%q0(3), -0.5_dp*pi + 0.1_dp, 'case_q(3, 1)', abs=1e-15_dp)
      call check_true(error, all(cfg%cases(2)%q0 == 0.0_dp), 'horizontal release')
      dir = scratch_dir('study-chain-config')
      text = study_namelist(cfg)
      call write_file(dir//'/back.nml', text)
      back = study_defaults()
      call read_study_config(dir//'/back.nml', back, error)
      if (allocated(error)) return
      call check_true(error, study_namelist(back) == text, 'chain namelist reads back:'// &
                      new_line('a')//text)
      ! a double-pendulum case next to a chain case of one link, with lists m, l
      call write_file(dir//'/mixed.nml', "&pendulum m = 1.5, 0.5, l = 0.8, 1.2 /"// &
                      new_line('a')//"&study case_name(1) = 'dp', case_q1(1) = 0.3, "// &
                      "case_name(2) = 'one', case_links(2) = 1, case_q(1, 2) = -1.0, "// &
                      "order_case = 'one', drift_case = 'dp', ro_case = 'dp', tao_case = 'one' /")
      cfg = study_defaults()
      call read_study_config(dir//'/mixed.nml', cfg, error)
      if (allocated(error)) return
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call check_true(error, size(cfg%cases(1)%q0) == 2 .and. size(cfg%cases(2)%q0) == 1, &
                      'links 2 and 1')
      call check_true(error, all(cfg%cases(1)%q0 == [0.3_dp, 0.0_dp]) .and. &
                      all(cfg%cases(2)%q0 == [-1.0_dp]) .and. cfg%m(2) == 0.5_dp .and. &
                      cfg%l(1) == 0.8_dp, 'values read')
      text = study_namelist(cfg)
      call write_file(dir//'/back2.nml', text)
      back = study_defaults()
      call read_study_config(dir//'/back2.nml', back, error)
      if (allocated(error)) return
      call check_true(error, study_namelist(back) == text, 'mixed namelist reads back:'// &
                      new_line('a')//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_chain_config

   !> data/study.nml is the default study, written out (but for the methods: it sets
   !> no method list, so the study takes every method of the registry with its
   !> default ranges): reading it gives the built-in defaults.
   subroutine test_default_config(error)
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: from_file, defaults
      character(len=:), allocatable :: text_file, text_defaults
      from_file = study_defaults()
      from_file%cases = [from_file%cases(1)]
      call read_study_config('data/study.nml', from_file, error)
      if (allocated(error)) return
      defaults = study_defaults()
      text_file = study_namelist(from_file)
      text_defaults = study_namelist(defaults)
      call check_true(error, text_file == text_defaults, &
                      'data/study.nml differs from the defaults:'//new_line('a')//text_file)
      call check_true(error, from_file%output == 'out/study/study.h5', 'output file')
      if (allocated(error)) return   ! (the next call would reset error)
      call validate_study_config(from_file, error)
      if (allocated(error)) return
      from_file%quick = .true.
      call apply_quick(from_file)
      call check(error, from_file%cases(1)%long_steps, 2.0e4_dp, 'quick long runs', rel=1e-12_dp)
   end subroutine test_default_config

   !> Bad input: exit status 2, one line on stderr naming the field, no file.
   subroutine test_bad_input(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('study-bad')
      call rejected('--threads 0', 'threads')
      call rejected('--methods rk4,nosuch', 'nosuch')
      call rejected('--cases tiny', 'tiny')
      call rejected('--dt 1e-3', 'unknown option')
      call rejected('--m1 -1', 'm1')
      call rejected('--config '//dir//'/missing.nml', 'config')
      call write_file(dir//'/range.nml', "&study method(1) = 'rk4', h_min(1) = 0.01, "// &
                      'h_max(1) = 0.001 /')
      call rejected('--config '//dir//'/range.nml', 'h_min')
      call write_file(dir//'/key.nml', '&study n_h = 5, bogus = 1 /')
      call rejected('--config '//dir//'/key.nml', 'bogus')
      call write_file(dir//'/group.nml', '&integration dt = 1 /')
      call rejected('--config '//dir//'/group.nml', 'integration')
      call write_file(dir//'/case.nml', "&study order_case = 'nowhere' /")
      call rejected('--config '//dir//'/case.nml', 'order_case')
      call write_file(dir//'/ro.nml', "&study ro_method(1) = 'rk4' /")
      call rejected('--config '//dir//'/ro.nml', 'ro_method')
      call write_file(dir//'/tao.nml', "&study tao_method(1) = 'gauss4' /")
      call rejected('--config '//dir//'/tao.nml', 'tao_method')
      call write_file(dir//'/tol.nml', "&study method(1) = 'rk4', rtol_min(1) = 1e-9, "// &
                      'rtol_max(1) = 1e-6 /')
      call rejected('--config '//dir//'/tol.nml', 'rtol')
      ! chain cases: a list of the wrong length, the two-link names, m too short
      call write_file(dir//'/links.nml', "&study case_name(1) = 'c', case_links(1) = 3, "// &
                      'case_q(1:2, 1) = 0.1, 0.2 /')
      call rejected('--config '//dir//'/links.nml', 'case_q(:, 1)')
      call write_file(dir//'/names.nml', "&study case_name(1) = 'c', case_links(1) = 3, "// &
                      'case_w2(1) = 0.1 /')
      call rejected('--config '//dir//'/names.nml', 'case_w1, case_w2(1)')
      call write_file(dir//'/mlist.nml', '&pendulum m = 1, 1 /'//new_line('a')// &
                      "&study case_name(1) = 'c', case_links(1) = 3 /")
      call rejected('--config '//dir//'/mlist.nml', 'invalid m: 2 values')
      call write_file(dir//'/toomany.nml', "&study case_name(1) = 'c', case_links(1) = 33 /")
      call rejected('--config '//dir//'/toomany.nml', 'case_links(1)')
      ! an existing output is kept
      call write_file(dir//'/out.h5', 'keep me')
      call rejected('--quick', 'exists')
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine rejected(args, needle)
         character(len=*), intent(in) :: args, needle
         character(len=:), allocatable :: text
         integer :: stat, n
         logical :: exists, kept
         if (allocated(error)) return
         stat = run_command(dir, 'study --no-figures --output '//dir//'/out.h5 '//args)
         call read_text(dir//'/stderr', text, n)
         inquire (file=dir//'/out.h5', exist=exists)
         kept = .true.
         if (exists) kept = .not. is_hdf5(dir//'/out.h5')
         call check_true(error, stat == 2, '['//args//'] exit status 2, got '//to_str(stat)// &
                         ': '//text)
         call check_true(error, n == 1, '['//args//'] one stderr line, got '//to_str(n)//': '//text)
         call check_true(error, index(text, needle) > 0, '['//args//'] message names "'// &
                         needle//'": '//text)
         call check_true(error, kept, '['//args//'] no HDF5 output written')
      end subroutine rejected
   end subroutine test_bad_input
end module test_study
