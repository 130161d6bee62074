!> Inverse dynamics (dpend_inverse_dynamics) and the smoothing filter
!> (dpend_smoothing), against independently known values:
!> - Newton–Euler read backwards against the forward chain: for the q̈ of the chain's
!>   field under known torques τ(t) (N = 1, 2, 3, 5; damping, Coulomb friction, a
!>   moving support, general bodies), the inverse returns τ(t) to rounding;
!> - the double pendulum against a second formulation: Lagrange's equations in
!>   absolute angles give Q = M (q̈ − q̈_free) and τ2 = Q2, τ1 = Q1 + Q2, for any q̈;
!> - the filter: a polynomial of the filter's degree is reproduced exactly (value,
!>   slope, curvature, at irregular times and at the ends); the 5-point quadratic
!>   Savitzky–Golay second derivative has the weights (2, −1, −2, −1, 2)/(7 h²);
!> - the noise estimate of white noise on a smooth signal within 5 %;
!> - torques from sampled noise-free motion (dop853, 500 Hz and 1000 Hz): the error
!>   falls with the step as the filter's order says (degree 4: h⁴).
!> Each test prints its measured figures on one line ('    inverse_dynamics: …').
module test_inverse_dynamics
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_joint_torque, only: joint_torque_t, torque_sines
   use dpend_chain, only: chain_t, chain_model
   use dpend_pendulum, only: pendulum_t, qddot_lagrange, mass_matrix
   use dpend_inverse_dynamics, only: joint_torques, torque_gain
   use dpend_smoothing, only: derivative_weights, smooth_derivatives, noise_sigma, &
                              choose_half_width
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str, to_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_inverse_dynamics

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_inverse_dynamics(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('newton_euler_vs_forward_chain', test_forward), &
               new_unittest('double_pendulum_vs_lagrange', test_lagrange), &
               new_unittest('filter_polynomials_and_weights', test_filter), &
               new_unittest('noise_estimate', test_noise), &
               new_unittest('torques_from_samples_order', test_samples)]
   end subroutine collect_inverse_dynamics

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    inverse_dynamics: '//text
   end subroutine report

   !> A pseudo-random number in [0, 1) (a fixed sequence).
   real(dp) function next(s)
      real(dp), intent(inout) :: s
      s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
      next = s
   end function next

   !> Forward under known torques, then backwards: τ back to rounding.
   subroutine test_forward(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      integer, parameter :: sizes(4) = [1, 2, 3, 5]
      real(dp), allocatable :: y(:), f(:), tau(:), back(:), fj(:, :), m(:), l(:)
      real(dp) :: s, t, worst
      integer :: c, n, k, i, variant
      worst = 0.0_dp
      s = 0.41_dp
      do c = 1, size(sizes)
         n = sizes(c)
         do variant = 1, 2
            tq = torque_sines([(0.2_dp*i, i = 1, n)], reshape([(1.0_dp/i, i = 1, 2*n)], &
                              [n, 2]), [1.7_dp, 3.1_dp], reshape([(0.3_dp*i, i = 1, 2*n)], &
                              [n, 2]), err)
            m = [(0.5_dp + 0.3_dp*i, i = 1, n)]
            l = [(1.1_dp - 0.1_dp*i, i = 1, n)]
            if (variant == 1) then
               chain = chain_model(m, l, 9.81_dp, err, torque=tq)
            else
               chain = chain_model(m, l, 9.81_dp, err, damping=[(0.05_dp*i, i = 1, n)], &
                                   amplitude=[0.02_dp, 0.01_dp], frequency=4.0_dp, &
                                   phase=[0.3_dp, 0.1_dp], com=0.4_dp*l, &
                                   inertia=[(0.02_dp*i, i = 1, n)], torque=tq, &
                                   coulomb=[(0.1_dp*i, i = 1, n)], coulomb_speed=0.3_dp, &
                                   rotor_inertia=[(1e-3_dp*i, i = 1, n)], &
                                   gear_ratio=[(12.0_dp - i, i = 1, n)])
            end if
            call check_true(error, .not. allocated(err), 'chain refused')
            if (allocated(error)) return
            allocate (y(2*n), f(2*n), tau(n), back(n), fj(2, n))
            do k = 1, 40
               y(1:n) = [(6.0_dp*next(s) - 3.0_dp, i = 1, n)]
               y(n + 1:) = [(8.0_dp*next(s) - 4.0_dp, i = 1, n)]
               t = 0.37_dp*k
               call chain%field(t, y, f)
               call tq%values(t, tau)
               call joint_torques(chain, t, y(1:n), y(n + 1:), f(n + 1:), back, fj)
               worst = max(worst, maxval(abs(back - tau))/max(1.0_dp, maxval(abs(f))))
            end do
            deallocate (y, f, tau, back, fj)
         end do
      end do
      call report('forward chain under known torques, then Newton-Euler backwards, '// &
                  'N = 1,2,3,5, plain and damped/Coulomb/driven/bodies/motors, 320 states: max '// &
                  '|tau back - tau| / max(1, |f|) '//real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'inverse of the forward chain', abs=1e-12_dp)
   end subroutine test_forward

   !> τ of Newton–Euler against Lagrange's Q = M (q̈ − q̈_free) for arbitrary q̈.
   subroutine test_lagrange(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), qdd(2), qm(2), tau(2), fj(2, 2), mm(2, 2), gain(2, 2), s, &
                  worst, worst_gain
      integer :: k
      par = pendulum_t(m1=1.2_dp, m2=0.7_dp, l1=0.9_dp, l2=1.3_dp, g=9.81_dp)
      chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err)
      call check_true(error, .not. allocated(err), 'chain refused')
      if (allocated(error)) return
      worst = 0.0_dp
      worst_gain = 0.0_dp
      s = 0.23_dp
      do k = 1, 200
         q = [6.0_dp*next(s) - 3.0_dp, 6.0_dp*next(s) - 3.0_dp]
         qd = [8.0_dp*next(s) - 4.0_dp, 8.0_dp*next(s) - 4.0_dp]
         qdd = [40.0_dp*next(s) - 20.0_dp, 40.0_dp*next(s) - 20.0_dp]
         mm = mass_matrix(par, q)
         qm = matmul(mm, qdd - qddot_lagrange(par, q, qd))
         call joint_torques(chain, 0.0_dp, q, qd, qdd, tau, fj)
         worst = max(worst, maxval(abs(tau - [qm(1) + qm(2), qm(2)]))/ &
                     max(1.0_dp, maxval(abs(qm))))
         call torque_gain(chain, q, gain)
         worst_gain = max(worst_gain, maxval(abs(gain - reshape([mm(1, 1) + mm(2, 1), &
                          mm(2, 1), mm(1, 2) + mm(2, 2), mm(2, 2)], [2, 2]))))
      end do
      call report('double pendulum, 200 states and accelerations: max |tau NE - tau '// &
                  'Lagrange| / max(1, |Q|) '//real_str(worst, 2)//'; gain vs summed M '// &
                  real_str(worst_gain, 2))
      call check(error, worst, 0.0_dp, 'Newton-Euler against Lagrange', abs=1e-12_dp)
      if (allocated(error)) return
      call check(error, worst_gain, 0.0_dp, 'torque gain', abs=1e-13_dp)
   end subroutine test_lagrange

   !> Polynomials of the filter's degree exactly; the textbook 5-point weights.
   subroutine test_filter(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: t(30), y(1, 30), ys(0:2, 1, 30), w(0:2, 5), expect(0:2), s, worst, x
      integer :: j, p, lo, k
      s = 0.61_dp
      t(1) = 0.3_dp
      do j = 2, size(t)
         t(j) = t(j - 1) + 0.01_dp + 0.02_dp*next(s)
      end do
      worst = 0.0_dp
      do p = 2, 6
         do k = p/2 + 1, 6
            y(1, :) = poly(t, p, 0)
            call smooth_derivatives(t, y, k, p, ys)
            do j = 1, size(t)
               expect = [poly([t(j)], p, 0), poly([t(j)], p, 1), poly([t(j)], p, 2)]
               worst = max(worst, maxval(abs(ys(:, 1, j) - expect)/ &
                           max(1.0_dp, abs(expect))))
            end do
         end do
      end do
      call report('polynomials of degree 2..6 through the filter of that degree, '// &
                  'irregular times, every sample (ends too): max rel error '// &
                  real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'polynomial reproduced', abs=1e-8_dp)
      if (allocated(error)) return
      t = [(0.002_dp*j, j = 1, size(t))]
      call derivative_weights(t, 10, 2, 2, lo, w)
      x = maxval(abs(w(2, :) - [2.0_dp, -1.0_dp, -2.0_dp, -1.0_dp, 2.0_dp]/(7*0.002_dp**2)))
      call report('5-point quadratic second-derivative weights vs (2,-1,-2,-1,2)/(7h^2): '// &
                  real_str(x*0.002_dp**2, 2)//' (in units of 1/h^2)')
      call check(error, x*0.002_dp**2, 0.0_dp, 'Savitzky-Golay weights', abs=1e-12_dp)
   contains
      !> Derivative d of the polynomial Σ_(i<=p) (1 + 0.3 i) (x − 0.5)^i.
      function poly(x, p, d) result(v)
         real(dp), intent(in) :: x(:)
         integer, intent(in) :: p, d
         real(dp) :: v(size(x))
         integer :: i, r
         real(dp) :: c
         v = 0.0_dp
         do i = d, p
            c = (1.0_dp + 0.3_dp*i)*product([(real(i - r, dp), r = 0, d - 1)])
            v = v + c*(x - 0.5_dp)**(i - d)
         end do
      end function poly
   end subroutine test_filter

   !> σ of white noise on a sine from the fourth differences.
   subroutine test_noise(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: n = 20000
      real(dp) :: t(n), y(n), u(2), z, sd
      integer :: j
      real(dp), parameter :: sigma = 1e-3_dp
      integer, allocatable :: seed(:)
      call random_seed(size=j)
      allocate (seed(j))
      seed = 20261130
      call random_seed(put=seed)
      do j = 1, n
         t(j) = 0.002_dp*j
         call random_number(u)
         z = sqrt(-2*log(1.0_dp - u(1)))*cos(2*pi*u(2))   ! Box-Muller
         y(j) = sin(3.0_dp*t(j)) + sigma*z
      end do
      sd = noise_sigma(y)
      call report('white noise sigma 1e-3 on sin(3t) at 500 Hz: estimated '// &
                  real_str(sd, 4))
      call check(error, sd, sigma, 'noise estimate', rel=0.05_dp)
   end subroutine test_noise

   !> Two damped rods under sine torques, dop853 at rtol 1e-13 sampled at 500 and
   !> 1000 Hz for 4 s, noise-free; the filter of degree 4 with a fixed half-width of 4
   !> samples: the interior torque error falls by about 2⁴ when h halves.
   subroutine test_samples(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: ts(:), qs(:, :), ys(:, :, :)
      real(dp) :: y(4), t, h, tau(2), back(2), fj(2, 2), rms(2), sig(2), first(2)
      integer :: run, k, n_s, stat, kk
      character(len=:), allocatable :: text
      tq = torque_sines([0.1_dp, 0.05_dp], reshape([0.4_dp, 0.2_dp, 0.2_dp, -0.1_dp], [2, 2]), &
                        [2.3_dp, 5.1_dp], reshape([0.1_dp, 0.4_dp, 0.9_dp, 0.2_dp], [2, 2]), err)
      chain = chain_model([1.0_dp, 0.6_dp], [0.5_dp, 0.4_dp], 9.81_dp, err, &
                          damping=[0.02_dp, 0.01_dp], torque=tq)
      call check_true(error, .not. allocated(err), 'chain refused')
      if (allocated(error)) return
      text = ''
      do run = 1, 2
         n_s = 2000*run + 1
         allocate (ts(n_s), qs(2, n_s), ys(0:2, 2, n_s))
         call new_integrator('dop853', integ, err, method_options_t(rtol=1e-13_dp, &
                             atol=1e-15_dp))
         y = [-1.2_dp, -1.0_dp, 0.5_dp, -0.3_dp]
         t = 0.0_dp; h = 0.0_dp
         do k = 1, n_s
            ts(k) = 4.0_dp*(k - 1)/(n_s - 1)
            if (k > 1) call advance_to(integ, chain, t, y, ts(k), h, stat)
            qs(:, k) = y(1:2)
         end do
         call smooth_derivatives(ts, qs, 4, 4, ys)
         rms = 0.0_dp
         do k = 21, n_s - 20
            call joint_torques(chain, ts(k), ys(0, :, k), ys(1, :, k), ys(2, :, k), back, fj)
            call tq%values(ts(k), tau)
            rms = rms + (back - tau)**2
         end do
         rms = sqrt(rms/(n_s - 40))
         sig = [noise_sigma(qs(1, :)), noise_sigma(qs(2, :))]
         kk = choose_half_width(ts, qs, sig, 4)
         text = text//' h = '//real_str(ts(2) - ts(1), 3)//' s: RMS '//real_str(rms(1), 2)// &
                ', '//real_str(rms(2), 2)//' N m (plug-in half-width '//to_str(kk)//');'
         if (run == 1) first = rms
         deallocate (ts, qs, ys)
      end do
      call report('two damped rods under sine torques, noise-free samples over 4 s, '// &
                  'degree 4, half-width 4:'//text//' ratio '// &
                  real_str(minval(first/rms), 3))
      call check_true(error, minval(first/rms) > 12.0_dp .and. maxval(rms) < 1e-5_dp, &
                      'torque error does not fall as h^4')
   end subroutine test_samples

end module test_inverse_dynamics
