!> Identification (dpend_identify) against independently known values:
!> - Newton–Euler in the standard parameters against the chain's own inverse
!>   dynamics (J = I_C + m d², h = m d) for N = 1, 2, 3, 5 with friction, a moving
!>   support and general bodies;
!> - the base parameters of 2 and 3 links against the closed form of planar chains:
!>   J_i + L_i² Σ_(k>i) m_k, h_i + L_i Σ_(k>i) m_k, m_1 absent;
!> - exact states (the integrator's q, q̇ and the field's q̈) of two links under sine
!>   torques: the base parameters recovered to rounding; the same run's noise-free
!>   angles at 500 Hz and 1 kHz through the filter: to 1e-6 relative;
!> - a rotation at constant rate: viscous and Coulomb friction not separated, the
!>   refusal naming the combination;
!> - 50 seeds of noisy runs (angles with white noise 1e-5 rad, torques with 0.01 N m)
!>   through the filter (the torques through the same filter, rows every window, as
!>   `dpend identify` does): each base parameter inside its 95 % interval in >= 45 of
!>   50.
!> Each test prints its measured figures on one line ('    identify: …').
module test_identify
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_joint_torque, only: joint_torque_t, torque_sines
   use dpend_chain, only: chain_t, chain_model
   use dpend_inverse_dynamics, only: joint_torques
   use dpend_identify, only: n_kinds, parameter_torques, base_t, base_parameters, &
                             identify_result_t, identify_parameters, standard_values
   use dpend_smoothing, only: smooth_derivatives, noise_sigma, choose_half_width, noise_factors
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str, to_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_identify, true_base, robot_run

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_identify(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('standard_parameters_vs_chain', test_standard), &
               new_unittest('base_parameters_closed_form', test_base), &
               new_unittest('exact_states_recovered', test_exact), &
               new_unittest('rotor_inertia_recovered', test_rotors), &
               new_unittest('noise_free_through_filter', test_noise_free), &
               new_unittest('constant_rate_not_separated', test_constant_rate), &
               new_unittest('coverage_50_seeds', test_coverage)]
   end subroutine collect_identify

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    identify: '//text
   end subroutine report

   real(dp) function next(s)
      real(dp), intent(inout) :: s
      s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
      next = s
   end function next

   !> The true base parameters of θ (flattened) for `base`: θ_k + Σ β_kj θ_j.
   function true_base(base, theta) result(b)
      type(base_t), intent(in) :: base
      real(dp), intent(in) :: theta(:)
      real(dp) :: b(size(base%kept))
      b = theta(base%kept) + matmul(base%beta, theta(base%dropped))
   end function true_base

   subroutine test_standard(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      integer, parameter :: sizes(4) = [1, 2, 3, 5]
      real(dp), allocatable :: q(:), qd(:), qdd(:), tau(:), back(:), f(:, :), l(:)
      real(dp) :: s, worst
      integer :: c, n, k, i
      worst = 0.0_dp
      s = 0.31_dp
      do c = 1, size(sizes)
         n = sizes(c)
         l = [(1.0_dp - 0.1_dp*i, i = 1, n)]
         chain = chain_model([(0.4_dp + 0.2_dp*i, i = 1, n)], l, 9.81_dp, err, &
                             damping=[(0.03_dp*i, i = 1, n)], amplitude=[0.02_dp, 0.01_dp], &
                             frequency=3.0_dp, phase=[0.2_dp, 0.4_dp], com=0.45_dp*l, &
                             inertia=[(0.01_dp*i, i = 1, n)], &
                             coulomb=[(0.02_dp*i, i = 1, n)], coulomb_speed=0.2_dp)
         call check_true(error, .not. allocated(err), 'chain refused')
         if (allocated(error)) return
         allocate (q(n), qd(n), qdd(n), tau(n), back(n), f(2, n))
         do k = 1, 50
            q = [(6*next(s) - 3, i = 1, n)]
            qd = [(8*next(s) - 4, i = 1, n)]
            qdd = [(30*next(s) - 15, i = 1, n)]
            call joint_torques(chain, 0.3_dp*k, q, qd, qdd, tau, f)
            call parameter_torques(chain, 0.3_dp*k, q, qd, qdd, standard_values(chain), back)
            worst = max(worst, maxval(abs(back - tau))/max(1.0_dp, maxval(abs(tau))))
         end do
         deallocate (q, qd, qdd, tau, back, f)
      end do
      call report('standard-parameter Newton-Euler vs the chain''s, N = 1,2,3,5, bodies, '// &
                  'friction, support, 200 states: max rel '//real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'standard parameters', abs=1e-13_dp)
   end subroutine test_standard

   subroutine test_base(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      type(base_t) :: base
      real(dp), parameter :: l(3) = [0.8_dp, 0.6_dp, 0.5_dp]
      real(dp) :: worst
      integer :: n, i, k
      worst = 0.0_dp
      do n = 2, 3
         chain = chain_model([(1.0_dp, i = 1, n)], l(:n), 9.8_dp, err)
         call base_parameters(chain, without_rotors(n), base)
         ! kept: J h c cf of every link (4N); dropped: the masses
         call check_true(error, size(base%kept) == 4*n .and. size(base%dropped) == n .and. &
                         base%absent(1), 'base of '//to_str(n)//' links: '// &
                         to_str(size(base%kept))//' kept')
         if (allocated(error)) return
         do k = 2, n   ! m_k: beta on J_i = L_i^2, on h_i = L_i for every i < k
            do i = 1, k - 1
               worst = max(worst, abs(base%beta(4*(i - 1) + 1, k) - l(i)**2), &
                           abs(base%beta(4*(i - 1) + 2, k) - l(i)))
            end do
            worst = max(worst, maxval(abs(base%beta(4*(k - 1) + 1:, k))))
         end do
         if (n == 2) call report('base of two links: '//trim(base%names(1))//'; '// &
                                 trim(base%names(2))//'; m1 absent')
      end do
      call report('base parameters vs J_i + L_i^2 sum m_k, h_i + L_i sum m_k: max '// &
                  real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'base coefficients', abs=1e-10_dp)
   end subroutine test_base

   !> Two rods under sine torques, with friction: 20 s sampled at 100 Hz from dop853
   !> at rtol 1e-13, q̈ from the field; every sample used.
   !> With `rotor`, motors at both joints: rotor inertias `rotor` and gear ratios 10, 8.
   subroutine robot_run(chain, t, q, qd, qdd, tau, error, t_end, hz, rotor)
      type(chain_t), intent(out) :: chain
      real(dp), allocatable, intent(out) :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :)
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(in) :: t_end, hz
      real(dp), intent(in), optional :: rotor(2)
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      class(integrator_t), allocatable :: integ
      real(dp) :: y(4), f(4), tt, h
      integer :: k, ns, stat
      tq = torque_sines([0.1_dp, 0.05_dp], reshape([0.8_dp, 0.3_dp, 0.4_dp, -0.25_dp], &
                        [2, 2]), [1.3_dp, 3.7_dp], reshape([0.0_dp, 0.4_dp, 1.0_dp, 0.2_dp], &
                        [2, 2]), err)
      chain = chain_model([1.0_dp, 0.7_dp], [0.8_dp, 0.6_dp], 9.8_dp, err, &
                          damping=[0.02_dp, 0.01_dp], coulomb=[0.05_dp, 0.03_dp], &
                          coulomb_speed=0.5_dp, com=[0.35_dp, 0.32_dp], &
                          inertia=[0.06_dp, 0.025_dp], torque=tq)
      if (present(rotor)) chain = chain_model([1.0_dp, 0.7_dp], [0.8_dp, 0.6_dp], 9.8_dp, &
                                              err, damping=[0.02_dp, 0.01_dp], &
                                              coulomb=[0.05_dp, 0.03_dp], coulomb_speed=0.5_dp, &
                                              com=[0.35_dp, 0.32_dp], inertia=[0.06_dp, 0.025_dp], &
                                              torque=tq, rotor_inertia=rotor, &
                                              gear_ratio=[10.0_dp, 8.0_dp])
      call check_true(error, .not. allocated(err), 'chain refused')
      if (allocated(error)) return
      ns = nint(t_end*hz) + 1
      allocate (t(ns), q(2, ns), qd(2, ns), qdd(2, ns), tau(2, ns))
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-13_dp, atol=1e-15_dp))
      y = [-1.2_dp, -1.0_dp, 0.0_dp, 0.0_dp]
      tt = 0.0_dp; h = 0.0_dp
      do k = 1, ns
         t(k) = (k - 1)/hz
         if (k > 1) call advance_to(integ, chain, tt, y, t(k), h, stat)
         call chain%field(t(k), y, f)
         q(:, k) = y(1:2); qd(:, k) = y(3:4); qdd(:, k) = f(3:4)
         call tq%values(t(k), tau(:, k))
      end do
   end subroutine robot_run

   subroutine test_exact(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(base_t) :: base
      type(identify_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :), truth(:)
      real(dp) :: worst
      integer :: i
      call robot_run(chain, t, q, qd, qdd, tau, error, 20.0_dp, 100.0_dp)
      if (allocated(error)) return
      call base_parameters(chain, without_rotors(2), base)
      call identify_parameters(chain, base, t, q, qd, qdd, tau, [(0.0_dp, i = 1, 2*n_kinds)], &
                               res, error)
      if (allocated(error)) return
      truth = true_base(base, pack(standard_values(chain), .true.))
      worst = maxval(abs(res%estimate - truth)/abs(truth))
      call report('exact states of a 20 s run at 100 Hz: max rel error of the 8 base '// &
                  'parameters '//real_str(worst, 2)//', condition '// &
                  real_str(res%condition, 3))
      call check(error, worst, 0.0_dp, 'exact recovery', abs=1e-9_dp)
   end subroutine test_exact

   !> Motors at both joints (reflected inertias 100 × 2e-4 = 0.02 and 64 × 1e-4 =
   !> 0.0064 kg m²), every parameter free: Im1 shows only within J1 + Im1 (joint 1's
   !> relative rate is q̇1), Im2 on its own; exact states recover the base to rounding.
   subroutine test_rotors(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(base_t) :: base
      type(identify_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :), truth(:)
      real(dp) :: worst
      integer :: i, i2
      call robot_run(chain, t, q, qd, qdd, tau, error, 20.0_dp, 100.0_dp, [2e-4_dp, 1e-4_dp])
      if (allocated(error)) return
      call base_parameters(chain, [(.true., i = 1, 2*n_kinds)], base)
      call report('base with motors: '//trim(base%names(1))//'; '//trim(base%names(5))// &
                  '; '//trim(base%names(size(base%kept))))
      call check_true(error, base%names(1) == 'J1 + Im1 + 0.64 m2' .and. &
                      any(base%names == 'Im2') .and. .not. any(base%names == 'Im1'), &
                      'Im1 within J1, Im2 alone: '//trim(base%names(1)))
      if (allocated(error)) return
      call identify_parameters(chain, base, t, q, qd, qdd, tau, [(0.0_dp, i = 1, 2*n_kinds)], &
                               res, error)
      if (allocated(error)) return
      truth = true_base(base, pack(standard_values(chain), .true.))
      worst = maxval(abs(res%estimate - truth)/abs(truth))
      i2 = 0   ! (findloc on a deferred-length character array: gfortran 12 faults)
      do i = 1, size(base%kept)
         if (base%names(i) == 'Im2') i2 = i
      end do
      call report('motors, exact states, 20 s at 100 Hz: max rel error of the '// &
                  to_str(size(truth))//' base parameters '//real_str(worst, 2)// &
                  ', Im2 = '//real_str(res%estimate(i2), 10)// &
                  ' (0.0064)')
      call check(error, worst, 0.0_dp, 'exact recovery with motors', abs=1e-9_dp)
   end subroutine test_rotors

   !> The free mask of every standard parameter but the rotors' (n links).
   pure function without_rotors(n) result(free)
      integer, intent(in) :: n
      logical :: free(n_kinds*n)
      free = .true.
      free(6::n_kinds) = .false.
   end function without_rotors

   !> Noise-free angles sampled at 500 Hz and 1 kHz through the command's pipeline
   !> (filter of degree 6, the plug-in window, torques through the same filter, rows
   !> every window, compensation with the estimated noise).
   subroutine test_noise_free(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(base_t) :: base
      type(identify_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :), truth(:), &
                               ys(:, :, :), ts(:, :, :)
      integer, allocatable :: rows(:)
      real(dp) :: nf(0:2), nv(2, 2), worst(2), hz
      integer :: i, k, kw, run
      do run = 1, 2
         hz = 500.0_dp*run
         call robot_run(chain, t, q, qd, qdd, tau, error, 20.0_dp, hz)
         if (allocated(error)) return
         call base_parameters(chain, without_rotors(2), base)
         truth = true_base(base, pack(standard_values(chain), .true.))
         kw = choose_half_width(t, q, [noise_sigma(q(1, :)), noise_sigma(q(2, :))], 6)
         allocate (ys(0:2, 2, size(t)), ts(0:2, 2, size(t)))
         call smooth_derivatives(t, q, kw, 6, ys)
         call smooth_derivatives(t, tau, kw, 6, ts)
         rows = [(k, k = kw + 1, size(t) - kw, 2*kw + 1)]
         nf = noise_factors(t, kw, 6)
         do i = 1, 2
            nv(:, i) = (noise_sigma(q(i, :))*nf(1:2))**2
         end do
         call identify_parameters(chain, base, t(rows), ys(0, :, rows), ys(1, :, rows), &
                                  ys(2, :, rows), ts(0, :, rows), &
                                  [(0.0_dp, i = 1, 2*n_kinds)], res, &
                                  error, noise_var=nv)
         if (allocated(error)) return
         worst(run) = maxval(abs(res%estimate - truth)/abs(truth))
         deallocate (ys, ts)
      end do
      call report('noise-free angles through the filter (degree 6, plug-in window), '// &
                  'max rel error of the 8 base parameters: 500 Hz '//real_str(worst(1), 2)// &
                  ', 1 kHz '//real_str(worst(2), 2))
      call check(error, maxval(worst), 0.0_dp, 'noise-free recovery', abs=1e-6_dp)
   end subroutine test_noise_free

   !> One rod turning at 5 rad/s: q̈ = 0 and ω constant: c1 ω and cf1 tanh(ω/v_s)
   !> are the same column.
   subroutine test_constant_rate(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      type(base_t) :: base
      type(identify_result_t) :: res
      real(dp) :: t(200), q(1, 200), qd(1, 200), qdd(1, 200), tau(1, 200)
      integer :: k
      chain = chain_model([1.0_dp], [0.5_dp], 9.8_dp, err, damping=[0.1_dp], &
                          coulomb=[0.2_dp], coulomb_speed=0.1_dp)
      do k = 1, 200
         t(k) = 0.01_dp*k
         q(1, k) = -1.0_dp + 5.0_dp*t(k)
         qd(1, k) = 5.0_dp
         qdd(1, k) = 0.0_dp
         call parameter_torques(chain, t(k), q(:, k), qd(:, k), qdd(:, k), &
                                standard_values(chain), tau(:, k))
      end do
      call base_parameters(chain, without_rotors(1), base)
      call identify_parameters(chain, base, t, q, qd, qdd, tau, [(0.0_dp, k = 1, n_kinds)], &
                               res, err)
      call check_true(error, allocated(err), 'a constant rate was not refused')
      if (allocated(error)) return
      call report('constant rate: '//err%message)
      call check_true(error, index(err%message, 'c1') > 0 .and. &
                      index(err%message, 'cf1') > 0 .and. index(err%message, 'J1') > 0, &
                      'the refusal names J1 and c1 with cf1')
   end subroutine test_constant_rate

   !> 50 seeds: noise on the angles (1e-5 rad) and the torques (0.01 N m), 500 Hz
   !> for 20 s; the filter of degree 4 with the plug-in window; rows every window.
   subroutine test_coverage(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(base_t) :: base
      type(identify_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :), truth(:), &
                               qn(:, :), tn(:, :), ys(:, :, :), ts(:, :, :), z(:, :)
      integer, allocatable :: covered(:), seed(:), rows(:)
      real(dp), allocatable :: zsum(:), z2sum(:)
      real(dp) :: nf(0:2), nv(2, 2)
      integer :: s, i, k, ns, kw, nseed
      character(len=:), allocatable :: text
      call robot_run(chain, t, q, qd, qdd, tau, error, 20.0_dp, 500.0_dp)
      if (allocated(error)) return
      call base_parameters(chain, without_rotors(2), base)
      truth = true_base(base, pack(standard_values(chain), .true.))
      ns = size(t)
      allocate (covered(size(truth)), qn(2, ns), tn(2, ns), ys(0:2, 2, ns), ts(0:2, 2, ns), &
                z(2, ns))
      covered = 0
      allocate (zsum(size(truth)), z2sum(size(truth)))
      zsum = 0; z2sum = 0
      call random_seed(size=nseed)
      allocate (seed(nseed))
      do s = 1, 50
         seed = 1000 + s
         call random_seed(put=seed)
         call gauss(z)
         qn = q + 1e-5_dp*z
         call gauss(z)
         tn = tau + 0.01_dp*z
         kw = choose_half_width(t, qn, [noise_sigma(qn(1, :)), noise_sigma(qn(2, :))], 4)
         call smooth_derivatives(t, qn, kw, 4, ys)
         call smooth_derivatives(t, tn, kw, 4, ts)   ! the torques through the same filter
         rows = [(k, k = kw + 1, ns - kw, 2*kw + 1)]
         nf = noise_factors(t, kw, 4)
         do i = 1, 2
            nv(:, i) = (noise_sigma(qn(i, :))*nf(1:2))**2
         end do
         call identify_parameters(chain, base, t(rows), ys(0, :, rows), ys(1, :, rows), &
                                  ys(2, :, rows), ts(0, :, rows), &
                                  [(0.0_dp, i = 1, 2*n_kinds)], res, &
                                  error, noise_var=nv)
         if (allocated(error)) return
         where (abs(res%estimate - truth) <= res%t95*res%std_error) covered = covered + 1
         zsum = zsum + (res%estimate - truth)/res%std_error
         z2sum = z2sum + ((res%estimate - truth)/res%std_error)**2
      end do
      text = ''
      do i = 1, size(truth)
         text = text//' '//trim(base%names(i))//' '//to_str(covered(i))//';'
      end do
      call report('compensated for the filter''s noise in the regressor: '// &
                  trim(merge('yes', 'no ', res%compensated)))
      call report('50 seeds (angles 1e-5 rad, torques 0.01 N m, 500 Hz, 20 s; last: window '// &
                  to_str(2*kw + 1)//', '//to_str(size(rows))//' rows): covered'//text)
      text = ''
      do i = 1, size(truth)
         text = text//' '//real_str(zsum(i)/50, 2)//'/'//real_str(sqrt(z2sum(i)/50), 3)
      end do
      call report('(estimate - truth)/std_error over the seeds, mean/RMS:'//text)
      call check_true(error, all(covered >= 45), 'coverage below 45 of 50')
   contains
      subroutine gauss(x)
         real(dp), intent(out) :: x(:, :)
         real(dp) :: u(2)
         integer :: a, b
         do b = 1, size(x, 2)
            do a = 1, size(x, 1)
               call random_number(u)
               x(a, b) = sqrt(-2*log(1.0_dp - u(1)))*cos(2*pi*u(2))
            end do
         end do
      end subroutine gauss
   end subroutine test_coverage

end module test_identify
