!> The copies of the double pendulum's formulas that remain for speed or precision,
!> each compared with its source of truth in `dpend_pendulum` at 1000 random states
!> and parameters (where a copy must remain, a test names each copy and compares it
!> with the source):
!>
!> | copy                                        | source                               |
!> |---------------------------------------------|--------------------------------------|
!> | `accel_lanes` (dpend_pendulum_lanes)         | `qddot_trig` and `qddot_lagrange`    |
!> | `tangent_accel_lanes` (dpend_pendulum_lanes) | `jacobian_qqdot` times (u, v)        |
!> | `energy_lanes` (dpend_pendulum_lanes)        | `energy`                             |
!> | `sincos_lanes` (dpend_pendulum_lanes)        | the intrinsic `sin`, `cos`           |
!> | `sincos_near_lanes` (dpend_pendulum_lanes)   | `sin_cos_near`                       |
!> | `megno_step_lanes` (dpend_pendulum_lanes)    | `megno_step` (dpend_indicator_math)  |
!> | `hamiltonian_qp` (dpend_pendulum), quadruple | `hamiltonian`, and with compensation |
!> |                                             | e: `dh_dq`, `dh_dp` (first order)    |
!> | src/gpu/dpend_gpu_step.h (the CUDA kernel's  | `qddot_trig`, `qddot_lagrange`,      |
!> | accelerations and energy)                    | `energy`                             |
!>
!> Draws: masses and lengths log-uniform in [0.1, 10], g in [1, 20], velocities in
!> [-10, 10] rad/s; angles in [-π, π], and in every fifth state in [-1000, 1000] rad.
!>
!> Error measure. Each compared value is a sum of terms t_k (products of rounded
!> factors), divided by det M = M11 M22 - M12², so its rounding error is a few ulps
!> of S = Σ |t_k| / det M, not of the value, which may be a near-cancellation. The
!> tests divide the difference by that S (`lane_scale`, `tangent_scale`,
!> `energy_abs`) and by (1 + |q1| + |q2|): the copies build cos(q1 - q2) and
!> sin(q1 - q2) from sin q and cos q by the subtraction formulas, the Lagrange
!> source from the rounded difference q1 - q2, whose absolute error is up to
!> eps |q|. det M needs no factor: M11 M22 >= 4/3 · M12² (1/3 ≥ 1/4 · 4/3), so the
!> determinant loses at most a factor 4 of its relative accuracy. A few tens of
!> roundings of eps = 2.2e-16 each, times that factor 4, stay below 1e-14;
!> `tol_double` = 1e-13 leaves a margin of 10 over that, and is still far below
!> any formula error (a wrong sign or factor gives O(1)). The maxima measured are
!> printed by each test (and noted in the commit that added this file).
module test_copies
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp, pi
   use dpend_pendulum, only: pendulum_t, qddot_trig, qddot_lagrange, sin_cos, energy, &
                             sin_cos_near, &
                             momenta, hamiltonian, dh_dq, dh_dp, jacobian_qqdot, &
                             velocities
   use dpend_pendulum_tangent_lanes, only: megno_step_lanes
   use dpend_lane_batch, only: lane_width
   use dpend_pendulum_kernel, only: batch_coef_t, batch_coef, accel_lanes, energy_lanes, &
      sincos_lanes, sincos_near_lanes, sincos_exact_max, sincos_stage_lanes
   use dpend_pendulum_tangent_lanes, only: tangent_accel_lanes
   use dpend_pendulum, only: hamiltonian_qp
   use dpend_indicator_math, only: megno_step
   use testing, only: unittest_t, new_unittest, check_true, error_t
   use dpend_cli, only: real_str
   implicit none
   private
   public :: collect_copies

   integer, parameter :: n_draws = 1000          !! random states and parameters per test
   real(dp), parameter :: tol_double = 1e-13_dp  !! see the module comment
   !> The first-order term of the compensated quadruple-precision Hamiltonian: the
   !> gradient is taken in double precision and its components are themselves sums
   !> that may cancel (∂H/∂q1 = k sin d q̇1 q̇2 + V_1), so its error is measured in
   !> ulps of those terms, not of Σ|∂H/∂y_i e_i| (measured up to ~1e-11); the
   !> second-order remainder is ~|e|/|y| ~ 1e-16 of the first-order term.
   real(dp), parameter :: tol_first_order = 1e-10_dp

contains

   !> The copies suite.
   subroutine collect_copies(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
         new_unittest('accel_lanes_vs_qddot', test_accel), &
         new_unittest('tangent_accel_lanes_vs_jacobian_qqdot', test_tangent), &
         new_unittest('energy_lanes_vs_energy', test_energy), &
         new_unittest('sincos_lanes_vs_intrinsic', test_sincos), &
         new_unittest('sincos_near_lanes_vs_sin_cos_near', test_sincos_near), &
         new_unittest('sincos_add_stage_vs_sincos_lanes', test_sincos_stage), &
         new_unittest('megno_step_lanes_vs_megno_step', test_megno_step), &
         new_unittest('hamiltonian_qp_vs_hamiltonian', test_hamiltonian_qp), &
         new_unittest('hamiltonian_qp_compensation_vs_gradient', test_compensation), &
         new_unittest('gpu_header_vs_qddot_energy', test_gpu_header) &
         ]
   end subroutine collect_copies

   !> A fixed seed: the same draws on every run.
   subroutine seed()
      integer :: n, i
      call random_seed(size=n)
      call random_seed(put=[(7654321 + 131*i, i=1, n)])
   end subroutine seed

   !> Parameters: masses and lengths log-uniform in [0.1, 10], g uniform in [1, 20].
   function random_pendulum() result(par)
      type(pendulum_t) :: par
      real(dp) :: r(5)
      call random_number(r)
      par = pendulum_t(m1=10.0_dp**(2*r(1) - 1), m2=10.0_dp**(2*r(2) - 1), &
                       l1=10.0_dp**(2*r(3) - 1), l2=10.0_dp**(2*r(4) - 1), &
                       g=1.0_dp + 19.0_dp*r(5))
   end function random_pendulum

   !> State number `i`: angles in [-π, π] (in [-1000, 1000] when i is a multiple of
   !> 5), velocities in [-10, 10] rad/s.
   subroutine random_state(i, q, qd)
      integer, intent(in) :: i        !! draw number
      real(dp), intent(out) :: q(2)   !! angles [rad]
      real(dp), intent(out) :: qd(2)  !! velocities [rad/s]
      call random_number(q); call random_number(qd)
      if (mod(i, 5) == 0) then
         q = 2000.0_dp*(q - 0.5_dp)
      else
         q = 2.0_dp*pi*(q - 0.5_dp)
      end if
      qd = 20.0_dp*(qd - 0.5_dp)
   end subroutine random_state

   !> Lanes filled with random states; every lane its own draw, one parameter set.
   subroutine fill_lanes(i0, q1, q2, w1, w2)
      integer, intent(in) :: i0  !! number of the first draw
      real(dp), intent(out) :: q1(lane_width), q2(lane_width), w1(lane_width), w2(lane_width)
      real(dp) :: q(2), qd(2)
      integer :: l
      do l = 1, lane_width
         call random_state(i0 + l, q, qd)
         q1(l) = q(1); q2(l) = q(2); w1(l) = qd(1); w2(l) = qd(2)
      end do
   end subroutine fill_lanes

   !> Σ|terms| / det M of the two accelerations (the scale of their rounding error).
   pure function lane_scale(c, q, qd) result(s)
      type(batch_coef_t), intent(in) :: c
      real(dp), intent(in) :: q(2), qd(2)
      real(dp) :: s(2)
      real(dp) :: cd, sd, r1, r2, m12, det
      cd = cos(q(1) - q(2)); sd = sin(q(1) - q(2))
      r1 = abs(c%ga*cos(q(1))) + abs(c%k*sd)*qd(2)**2
      r2 = abs(c%gb*cos(q(2))) + abs(c%k*sd)*qd(1)**2
      m12 = abs(c%k*cd)
      det = c%m11*c%m22 - m12*m12
      s = [(c%m22*r1 + m12*r2)/det, (c%m11*r2 + m12*r1)/det]
   end function lane_scale

   !> Scale of the rounding error of the tangent accelerations: Σ_j |J_ij x_j|, plus
   !> the accelerations' own scale times |x| (J's entries are built from the
   !> accelerations and from k sin d, k cos d times M⁻¹).
   pure function tangent_scale(c, jac, q, qd, x) result(s)
      type(batch_coef_t), intent(in) :: c
      real(dp), intent(in) :: jac(4, 4), q(2), qd(2), x(4)
      real(dp) :: s(2)
      real(dp) :: a(2), k2, det
      a = lane_scale(c, q, qd)
      det = c%m11*c%m22 - (c%k*cos(q(1) - q(2)))**2
      k2 = c%k*(c%m11 + c%m22)/det   ! |M⁻¹| |∂M/∂q| bound
      s(1) = sum(abs(jac(3, :)*x)) + (k2*(a(1) + a(2)) + a(1))*(abs(x(1)) + abs(x(2))) &
             + a(1)*(abs(x(3)) + abs(x(4)))
      s(2) = sum(abs(jac(4, :)*x)) + (k2*(a(1) + a(2)) + a(2))*(abs(x(1)) + abs(x(2))) &
             + a(2)*(abs(x(3)) + abs(x(4)))
   end function tangent_scale

   !> Σ|terms| of the energy T + V [J].
   pure real(dp) function energy_abs(c, q, qd)
      type(batch_coef_t), intent(in) :: c
      real(dp), intent(in) :: q(2), qd(2)
      energy_abs = 0.5_dp*(c%m11*qd(1)**2 + 2.0_dp*abs(c%k*cos(q(1) - q(2))*qd(1)*qd(2)) &
                           + c%m22*qd(2)**2) + abs(c%ga*sin(q(1))) + abs(c%gb*sin(q(2)))
   end function energy_abs

   !> The factor of the angle reduction: 1 + |q1| + |q2|.
   pure real(dp) function angle_factor(q)
      real(dp), intent(in) :: q(2)
      angle_factor = 1.0_dp + abs(q(1)) + abs(q(2))
   end function angle_factor

   !> Record the error `raw` (difference / Σ|terms|) of draw `i` at angles `q`:
   !> worst(1) the largest raw error at |q| <= π, worst(2) the largest raw error
   !> divided by the angle factor (what is tested) over all draws; true if the
   !> latter is within `tol_double`.
   logical function within(worst, raw, i, q)
      real(dp), intent(inout) :: worst(2)
      real(dp), intent(in) :: raw, q(2)
      integer, intent(in) :: i
      if (mod(i, 5) /= 0) worst(1) = max(worst(1), raw)
      worst(2) = max(worst(2), raw/angle_factor(q))
      within = raw/angle_factor(q) <= tol_double
   end function within

   !> Print the largest errors seen by a test.
   subroutine report(what, worst)
      character(len=*), intent(in) :: what
      real(dp), intent(in) :: worst(2)
      write (output_unit, '(a, es8.2, a, es8.2, a, es7.1)') '       '//what//': max error ', &
         worst(1), ' (|q| <= pi), ', worst(2), ' / (1 + |q1| + |q2|) (all); tolerance ', &
         tol_double
   end subroutine report

   !> Copy `accel_lanes` against the sources `qddot_trig` (the integrators'
   !> Newton–Euler form) and `qddot_lagrange` (the same Lagrange form).
   subroutine test_accel(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, a1, a2, s1, c1, s2, c2
      real(dp) :: q(2), qd(2), ne(2), lg(2), s(2), worst_ne(2), worst_lg(2)
      logical :: ok_ne, ok_lg
      integer :: i, l
      call seed()
      worst_ne = 0; worst_lg = 0
      do i = 0, n_draws - 1, lane_width
         par = random_pendulum()
         c = batch_coef(par)
         call fill_lanes(i, q1, q2, w1, w2)
         call accel_lanes(c, q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
         do l = 1, lane_width
            q = [q1(l), q2(l)]; qd = [w1(l), w2(l)]
            ne = qddot_trig(par, sin_cos(q), qd)
            lg = qddot_lagrange(par, q, qd)
            s = lane_scale(c, q, qd)
            ok_ne = within(worst_ne, maxval(abs([a1(l), a2(l)] - ne)/s), i + l, q)
            ok_lg = within(worst_lg, maxval(abs([a1(l), a2(l)] - lg)/s), i + l, q)
            call check_true(error, ok_ne .and. ok_lg, &
                            'accel_lanes differs from qddot_trig / qddot_lagrange')
            if (allocated(error)) return
         end do
      end do
      call report('accel_lanes vs qddot_trig', worst_ne)
      call report('accel_lanes vs qddot_lagrange', worst_lg)
   end subroutine test_accel

   !> Copy `tangent_accel_lanes` against rows 3 and 4 of `jacobian_qqdot` applied to
   !> the tangent vector (u, v).
   subroutine test_tangent(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, a1, a2, s1, c1, s2, c2
      real(dp), dimension(lane_width) :: u1, u2, v1, v2, b1, b2
      real(dp) :: q(2), qd(2), x(4), jac(4, 4), ref(2), s(2), worst(2)
      integer :: i, l
      call seed()
      worst = 0
      do i = 0, n_draws - 1, lane_width
         par = random_pendulum()
         c = batch_coef(par)
         call fill_lanes(i, q1, q2, w1, w2)
         call random_number(u1); call random_number(u2)
         call random_number(v1); call random_number(v2)
         u1 = 2*u1 - 1; u2 = 2*u2 - 1; v1 = 2*v1 - 1; v2 = 2*v2 - 1
         call accel_lanes(c, q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
         call tangent_accel_lanes(c, w1, w2, a1, a2, s1, c1, s2, c2, u1, u2, v1, v2, b1, b2)
         do l = 1, lane_width
            q = [q1(l), q2(l)]; qd = [w1(l), w2(l)]
            x = [u1(l), u2(l), v1(l), v2(l)]
            jac = jacobian_qqdot(par, [q, qd])
            ref = matmul(jac(3:4, :), x)
            s = tangent_scale(c, jac, q, qd, x)
            call check_true(error, within(worst, maxval(abs([b1(l), b2(l)] - ref)/s), i + l, q), &
                            'tangent_accel_lanes differs from jacobian_qqdot (u, v)')
            if (allocated(error)) return
         end do
      end do
      call report('tangent_accel_lanes vs jacobian_qqdot', worst)
   end subroutine test_tangent

   !> Copy `energy_lanes` against the source `energy`.
   subroutine test_energy(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, e
      real(dp) :: q(2), qd(2), worst(2)
      integer :: i, l
      call seed()
      worst = 0
      do i = 0, n_draws - 1, lane_width
         par = random_pendulum()
         c = batch_coef(par)
         call fill_lanes(i, q1, q2, w1, w2)
         call energy_lanes(c, q1, q2, w1, w2, e)
         do l = 1, lane_width
            q = [q1(l), q2(l)]; qd = [w1(l), w2(l)]
            call check_true(error, within(worst, abs(e(l) - energy(par, q, qd)) &
                                          /energy_abs(c, q, qd), i + l, q), &
                            'energy_lanes differs from energy')
            if (allocated(error)) return
         end do
      end do
      call report('energy_lanes vs energy', worst)
   end subroutine test_energy

   !> `sincos_lanes` (own argument reduction and polynomials) against the intrinsic
   !> sin and cos, in ulps of the intrinsic's value, over the whole accepted range of
   !> angles (dpend_limits' max_angle = 1e6 rad) and beyond: |x| log-uniform in
   !> [1e-9, 1.6e6], uniform in [-1e6, 1e6], the doubles nearest to k π/2 (up to
   !> k = 2^20, where the reduction cancels most), and far lanes (> 2^20 π/2) that
   !> take the intrinsic. Tolerance 4 ulp (measured maximum printed).
   subroutine test_sincos(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: n_sets = 20000
      real(dp), dimension(lane_width) :: x, s, c
      real(dp) :: r(lane_width), worst, u
      integer :: i, l, kind
      call seed()
      worst = 0
      do i = 1, n_sets
         call random_number(r)
         kind = mod(i, 4)
         select case (kind)
         case (0)
            x = sign(10.0_dp**(-9.0_dp + 15.2_dp*r), r - 0.5_dp)
         case (1)
            x = 2e6_dp*(r - 0.5_dp)
         case (2)
            x = real(nint(r*1048576.0_dp), dp)*(0.5_dp*pi)
            x(1:4) = [0.5_dp*pi, pi, 1.5_dp*pi, 2.0_dp*pi]
         case default
            x = r*1e6_dp
            x(1:3) = [2.0_dp*sincos_exact_max, 1e300_dp, -1e22_dp]
         end select
         call sincos_lanes(x, s, c)
         do l = 1, lane_width
            u = max(abs(s(l) - sin(x(l)))/spacing(sin(x(l))), &
                    abs(c(l) - cos(x(l)))/spacing(cos(x(l))))
            worst = max(worst, u)
            call check_true(error, u <= 4.0_dp, 'sincos_lanes differs from sin, cos at x = ' &
                            //real_str(x(l)))
            if (allocated(error)) return
         end do
      end do
      write (output_unit, '(a, f0.2, a)') '    sincos_lanes vs sin, cos: max ', worst, ' ulp'
   end subroutine test_sincos

   !> `sincos_near_lanes` against its source `sin_cos_near` (Taylor formulas, the
   !> lanes' truncated for |d| <= 1/16, beyond which they take `sincos_lanes`; the
   !> source's for |d| <= 0.25), from the intrinsic's sin and cos at x0: equal to a
   !> few ulps of 1, and close to sin x, cos x (scalar intrinsic) for every d.
   subroutine test_sincos_near(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), dimension(lane_width) :: x0, d, x, s0, c0, s, c
      real(dp) :: r(lane_width), sc(4), worst(2)
      integer :: i, l
      call seed()
      worst = 0
      do i = 1, 200
         call random_number(r)
         x0 = 2000.0_dp*(r - 0.5_dp)
         call random_number(r)
         d = 0.6_dp*(r - 0.5_dp)    ! a fifth of the lanes beyond 0.25
         x = x0 + d
         d = x - x0
         ! the step start's sine and cosine from the kernel's own sincos_lanes (tested
         ! against the scalar intrinsic above): the release build would evaluate
         ! sin(x0) of a whole array with libmvec, whose vector sine is off by up to
         ! ulp(x)/2 absolute (5.7e-14 at |x| ~ 800)
         call sincos_lanes(x0, s0, c0)
         call sincos_near_lanes(s0, c0, x, d, s, c)
         do l = 1, lane_width
            sc = sin_cos_near([s0(l), s0(l), c0(l), c0(l)], [x(l), x(l)], [d(l), d(l)])
            if (abs(d(l)) <= 0.25_dp) &   ! beyond: sin_cos_near's cos is sin(x + π/2)
               worst(1) = max(worst(1), abs(s(l) - sc(1)), abs(c(l) - sc(3)))
            worst(2) = max(worst(2), abs(s(l) - sin(x(l))), abs(c(l) - cos(x(l))))
         end do
      end do
      call check_true(error, worst(1) <= 4.0_dp*epsilon(1.0_dp) .and. &
                      worst(2) <= 8.0_dp*epsilon(1.0_dp), 'sincos_near_lanes differs')
      write (output_unit, '(a, es9.2, a, es9.2)') '    sincos_near_lanes vs sin_cos_near: ', &
         worst(1), ', vs sin, cos: ', worst(2)
   end subroutine test_sincos_near

   !> `sincos_stage_lanes` (the RK4 stages of `rk4_lanes`: economized polynomials,
   !> within 1.8e-16 of cos d - 1 by scripts/reference/stage_poly.py) against `sincos_lanes`
   !> at x = x0 + d, |x0| <= 1000, |d| <= 1/16, from `sincos_lanes`' values at x0.
   subroutine test_sincos_stage(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), dimension(lane_width) :: x0, d, x, s0, c0, s, c, r, sx, cx
      real(dp) :: worst
      integer :: i
      call seed()
      worst = 0
      do i = 1, 2000
         call random_number(r)
         x0 = 2000.0_dp*(r - 0.5_dp)
         call random_number(r)
         d = 0.125_dp*(r - 0.5_dp)
         x = x0 + d
         d = x - x0
         call sincos_lanes(x0, s0, c0)
         call sincos_stage_lanes(s0, c0, d, s, c)
         ! the reference at x also from sincos_lanes (within 3 ulp of the scalar
         ! intrinsic, test above): the release build would take sin(x) of the array
         ! from libmvec, off by up to ulp(x)/2 absolute (5.7e-14 at |x| ~ 800)
         call sincos_lanes(x, sx, cx)
         worst = max(worst, maxval(abs(s - sx)), maxval(abs(c - cx)))
      end do
      call check_true(error, worst <= 8.0_dp*epsilon(1.0_dp), 'sincos_add_stage differs')
      write (output_unit, '(a, es9.2)') '    sincos_add_stage vs sincos_lanes (|d| <= 1/16): ', worst
   end subroutine test_sincos_stage

   !> Copy `hamiltonian_qp` (no compensation), rounded to double, against the
   !> source `hamiltonian` at (q, p = M(q) q̇).
   !> `megno_step_lanes` against `megno_step` (t0 = 0) over 200 steps of random
   !> growths dl in [-1, 1] and steps in [1e-3, 1] s: equal to a few ulps (the same
   !> operations; only a compiler's contraction into fused multiply-adds may differ).
   subroutine test_megno_step(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), dimension(lane_width) :: dl, ta, tb, h, a1, a2, a3, a4
      real(dp) :: b(lane_width, 4), worst
      integer :: k, i
      a1 = 0; a2 = 0; a3 = 0; a4 = 0; b = 0; tb = 0; worst = 0
      do k = 1, 200
         call random_number(dl)
         call random_number(h)
         dl = 2.0_dp*dl - 1.0_dp
         ta = tb
         tb = ta + 1e-3_dp + h
         call megno_step_lanes(dl, ta, tb, a1, a2, a3, a4)
         do i = 1, lane_width
            call megno_step(dl(i), ta(i), tb(i), 0.0_dp, b(i, 1), b(i, 2), b(i, 3), b(i, 4))
         end do
         worst = max(worst, maxval(abs(a1 - b(:, 1))/(1 + abs(b(:, 1)))), &
                     maxval(abs(a2 - b(:, 2))/(1 + abs(b(:, 2)))), &
                     maxval(abs(a3 - b(:, 3))/(1 + abs(b(:, 3)))), &
                     maxval(abs(a4 - b(:, 4))/(1 + abs(b(:, 4)))))
      end do
      call check_true(error, worst < 1e-13_dp, 'megno_step_lanes equals megno_step')
   end subroutine test_megno_step

   subroutine test_hamiltonian_qp(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      real(dp) :: q(2), qd(2), p(2), v(2), h, hq, s, worst(2)
      integer :: i
      call seed()
      worst = 0
      do i = 1, n_draws
         par = random_pendulum()
         c = batch_coef(par)
         call random_state(i, q, qd)
         p = momenta(par, q, qd)
         h = hamiltonian(par, q, p)
         hq = real(hamiltonian_qp(par, [q, p], [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]), dp)
         ! Σ|terms|: ½ (|p1 q̇1| + |p2 q̇2|) + |A sin q1| + |B sin q2|
         v = velocities(par, q, p)
         s = 0.5_dp*(abs(p(1)*v(1)) + abs(p(2)*v(2))) + abs(c%ga*sin(q(1))) &
             + abs(c%gb*sin(q(2)))
         call check_true(error, within(worst, abs(hq - h)/s, i, q), &
                         'hamiltonian_qp differs from hamiltonian')
         if (allocated(error)) return
      end do
      call report('hamiltonian_qp vs hamiltonian', worst)
   end subroutine test_hamiltonian_qp

   !> The compensation e of `hamiltonian_qp`: H(y + e) - H(y) in quadruple
   !> precision against the first-order term ∇H · e, ∇H = (`dh_dq`, `dh_dp`), for
   !> e of relative size ~1e-16 (what compensated summation carries).
   subroutine test_compensation(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), p(2), e(4), grad(4), dh, lin, err, worst
      real(dp), parameter :: zero(4) = 0.0_dp
      integer :: i
      call seed()
      worst = 0
      do i = 1, n_draws
         par = random_pendulum()
         call random_state(i, q, qd)
         p = momenta(par, q, qd)
         call random_number(e)
         e = (2*e - 1)*1e-16_dp*abs([q, p])
         grad = [dh_dq(par, q, p), dh_dp(par, q, p)]
         dh = real(hamiltonian_qp(par, [q, p], e) - hamiltonian_qp(par, [q, p], zero), dp)
         lin = sum(grad*e)
         err = abs(dh - lin)/max(sum(abs(grad*e)), tiny(1.0_dp))
         worst = max(worst, err)
         call check_true(error, err <= tol_first_order, &
                         'hamiltonian_qp(y, e) - hamiltonian_qp(y, 0) differs from ∇H · e')
         if (allocated(error)) return
      end do
      write (output_unit, '(a, es9.2, a, es8.1, a)') &
         '       hamiltonian_qp compensation vs dh_dq, dh_dp: max error ', worst, &
         ' (tolerance ', tol_first_order, ')'
   end subroutine test_compensation

   !> Copy src/gpu/dpend_gpu_step.h (the per-trajectory formulas of the CUDA kernel,
   !> compiled for the host by src/gpu/dpend_gpu_host.c) against the sources
   !> `qddot_trig`, `qddot_lagrange` and `energy`, as `test_accel` and `test_energy`.
   subroutine test_gpu_header(error)
      type(error_t), allocatable, intent(out) :: error
      interface
         subroutine host_accel(coef, y, a, e) bind(C, name='dpend_gpu_host_accel')
            use, intrinsic :: iso_c_binding, only: c_double
            real(c_double), intent(in) :: coef(*), y(*)
            real(c_double), intent(out) :: a(*), e
         end subroutine host_accel
      end interface
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      real(dp) :: q(2), qd(2), a(2), e, s(2), worst_ne(2), worst_lg(2), worst_e(2)
      logical :: ok
      integer :: i
      call seed()
      worst_ne = 0; worst_lg = 0; worst_e = 0
      do i = 0, n_draws - 1
         if (mod(i, lane_width) == 0) par = random_pendulum()
         c = batch_coef(par)
         call random_state(i + 1, q, qd)
         call host_accel([c%m11, c%m22, c%k, c%ga, c%gb, c%m11k, c%m22k, c%detk, c%gak, &
                          c%gbk], [q, qd], a, e)
         s = lane_scale(c, q, qd)
         ok = within(worst_ne, maxval(abs(a - qddot_trig(par, sin_cos(q), qd))/s), i + 1, q)
         ok = within(worst_lg, maxval(abs(a - qddot_lagrange(par, q, qd))/s), i + 1, q) .and. ok
         ok = within(worst_e, abs(e - energy(par, q, qd))/energy_abs(c, q, qd), i + 1, q) .and. ok
         call check_true(error, ok, 'src/gpu/dpend_gpu_step.h differs from qddot_trig / ' &
                         //'qddot_lagrange / energy')
         if (allocated(error)) return
      end do
      call report('dpend_gpu_step.h accelerations vs qddot_trig', worst_ne)
      call report('dpend_gpu_step.h accelerations vs qddot_lagrange', worst_lg)
      call report('dpend_gpu_step.h energy vs energy', worst_e)
   end subroutine test_gpu_header
end module test_copies
