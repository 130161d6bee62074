!> The double pendulum's tangent lane kernels: one RK4 step of `lane_width` double
!> pendulums with one or two deviation vectors each, for the sweeps' Lyapunov
!> exponent (`rk4_tangent_lanes`) and fast indicators (`rk4_tangent_fused_lanes`,
!> `indicator_step_lanes`: MEGNO, FLI, SALI, GALI_2; definitions in
!> dpend_indicator_math), with the vectorized logarithm and MEGNO sums they need.
!> The state's arithmetic is the RK4 kernel's (dpend_pendulum_kernel; the shared
!> procedures are compiled into both from dpend_pendulum_lane_math.inc), so that a
!> lane's state steps alike in both. Layout, trigonometry and reproducibility as
!> there.
module dpend_pendulum_tangent_lanes
   use dpend_kinds, only: dp, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   use dpend_lane_batch, only: lane_width
   use dpend_pendulum_kernel, only: batch_coef_t, lane_coef_t, lane_trig_t, lane_coef, &
      pi, half_pi, two_pi, inv_two_pi, two_over_pi, round_magic, pio2_1, pio2_2, pio2_2t, &
      sin_p1, sin_p2, sin_p3, sin_p4, sin_p5, sin_p6, &
      cos_p1, cos_p2, cos_p3, cos_p4, cos_p5, cos_p6, lane_bound, d_max, sincos_exact_max, &
      sincos_exact
   implicit none
   private
   public :: rk4_tangent_lanes, rk4_tangent2_lanes, rk4_tangent_fused_lanes
   public :: indicator_step_lanes, tangent_accel_lanes, megno_step_lanes, log_lanes
   public :: lyapunov_step_lanes

   ! The kernels with each lane's own constants (`lane_coef_t`) or one pendulum in
   ! every lane (`batch_coef_t`)
   interface rk4_tangent_lanes
      module procedure rk4_tangent_lanes_lc, rk4_tangent_lanes_one
   end interface rk4_tangent_lanes
   interface indicator_step_lanes
      module procedure indicator_step_lanes_lc, indicator_step_lanes_one
   end interface indicator_step_lanes
   interface tangent_accel_lanes
      module procedure tangent_accel_lanes_lc, tangent_accel_lanes_one
   end interface tangent_accel_lanes
   ! this module's own copies of the shared arithmetic (dpend_pendulum_lane_math.inc)
   interface accel_lanes
      module procedure accel_lanes_lc
   end interface accel_lanes
   interface accel_trig_lanes
      module procedure accel_trig_lanes_lc
   end interface accel_trig_lanes

contains

   !> `rk4_tangent_lanes` with the constants `c` in every lane.
   pure subroutine rk4_tangent_lanes_one(c, h, q1, q2, w1, w2, u1, u2, v1, v2, e)
      type(batch_coef_t), intent(in) :: c                        !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(inout) :: u1(lane_width), u2(lane_width)  !! tangent, angles
      real(dp), intent(inout) :: v1(lane_width), v2(lane_width)  !! tangent, velocities
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      call rk4_tangent_lanes_lc(lane_coef(c), h, q1, q2, w1, w2, u1, u2, v1, v2, e)
   end subroutine rk4_tangent_lanes_one

   !> `indicator_step_lanes` with the constants `c` in every lane.
   pure subroutine indicator_step_lanes_one(c, h, ks, q1, q2, w1, w2, nv, d, acc, e, tr)
      type(batch_coef_t), intent(in) :: c                          !! constants
      real(dp), intent(in) :: h                                    !! step [s]
      integer(i8), intent(in) :: ks(lane_width)                    !! steps done before
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)    !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      integer, intent(in) :: nv                                    !! vectors, 1 or 2
      real(dp), intent(inout) :: d(lane_width, 4, 2)               !! deviation vectors
      real(dp), intent(inout) :: acc(lane_width, 5)                !! vector 1's sums, ln |d|
      real(dp), intent(out) :: e(lane_width)                       !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                       !! sin, cos of q1, q2
      call indicator_step_lanes_lc(lane_coef(c), h, ks, q1, q2, w1, w2, nv, d, acc, e, tr)
   end subroutine indicator_step_lanes_one

   !> `tangent_accel_lanes` with the constants `c` in every lane.
   pure subroutine tangent_accel_lanes_one(c, w1, w2, a1, a2, s1, c1, s2, c2, u1, u2, v1, v2, &
                                           b1, b2)
      type(batch_coef_t), intent(in) :: c                      !! constants
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)   !! velocities [rad/s]
      real(dp), intent(in) :: a1(lane_width), a2(lane_width)   !! accelerations there
      real(dp), intent(in) :: s1(lane_width), c1(lane_width)   !! sin q1, cos q1
      real(dp), intent(in) :: s2(lane_width), c2(lane_width)   !! sin q2, cos q2
      real(dp), intent(in) :: u1(lane_width), u2(lane_width)   !! angle perturbation
      real(dp), intent(in) :: v1(lane_width), v2(lane_width)   !! velocity perturbation
      real(dp), intent(out) :: b1(lane_width), b2(lane_width)  !! derivative of (a1, a2)
      call tangent_accel_lanes_lc(lane_coef(c), w1, w2, a1, a2, s1, c1, s2, c2, u1, u2, v1, v2, &
                                  b1, b2)
   end subroutine tangent_accel_lanes_one

   !> Copy of `jacobian_qqdot` (dpend_pendulum, rows of q̈, applied to a vector) for
   !> speed: SIMD over the lanes, reusing the values of `accel_lanes`;
   !> test/test_copies.f90 compares them.
   !> Directional derivative of the accelerations at (q, q̇) along (u, v) [rad/s²],
   !> from the values of `accel_lanes` at the same point (no further sin/cos).
   pure subroutine tangent_accel_lanes_lc(c, w1, w2, a1, a2, s1, c1, s2, c2, u1, u2, v1, v2, &
                                          b1, b2)
      type(lane_coef_t), intent(in) :: c                       !! constants
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)   !! velocities [rad/s]
      real(dp), intent(in) :: a1(lane_width), a2(lane_width)   !! accelerations there
      real(dp), intent(in) :: s1(lane_width), c1(lane_width)   !! sin q1, cos q1
      real(dp), intent(in) :: s2(lane_width), c2(lane_width)   !! sin q2, cos q2
      real(dp), intent(in) :: u1(lane_width), u2(lane_width)   !! angle perturbation
      real(dp), intent(in) :: v1(lane_width), v2(lane_width)   !! velocity perturbation
      real(dp), intent(out) :: b1(lane_width), b2(lane_width)  !! derivative of (a1, a2)
      real(dp) :: cd, sd, rdet, w1sq, w2sq
      integer :: i
      do i = 1, lane_width
         call tangent_shared(c, i, w1(i), w2(i), s1(i), c1(i), s2(i), c2(i), cd, sd, w1sq, w2sq, &
                             rdet)
         call tangent_vector(c, i, a1(i), a2(i), s1(i), s2(i), cd, sd, w1(i), w2(i), w1sq, &
                             w2sq, rdet, u1(i), u2(i), v1(i), v2(i), b1(i), b2(i))
      end do
   end subroutine tangent_accel_lanes_lc

   !> `tangent_accel_lanes` for the two deviation vectors x(:, :, 1) and x(:, :, 2)
   !> = (u1, u2, v1, v2) of SALI and GALI_2 at once: the terms that do not
   !> depend on the vector (the Jacobian's: cos d, sin d, 1/det(M/k)) once per lane,
   !> then each vector by the same operations as `tangent_accel_lanes`, so that
   !> each result equals that of `tangent_accel_lanes` bit for bit.
   pure subroutine tangent_accel2_lanes(c, w1, w2, a1, a2, s1, c1, s2, c2, x, b)
      type(lane_coef_t), intent(in) :: c                       !! constants
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)   !! velocities [rad/s]
      real(dp), intent(in) :: a1(lane_width), a2(lane_width)   !! accelerations there
      real(dp), intent(in) :: s1(lane_width), c1(lane_width)   !! sin q1, cos q1
      real(dp), intent(in) :: s2(lane_width), c2(lane_width)   !! sin q2, cos q2
      real(dp), intent(in) :: x(lane_width, 4, 2)              !! the vectors (u1, u2, v1, v2)
      real(dp), intent(out) :: b(lane_width, 2, 2)             !! their derivatives of (a1, a2)
      real(dp) :: cd, sd, rdet, w1sq, w2sq
      integer :: i
      do i = 1, lane_width
         call tangent_shared(c, i, w1(i), w2(i), s1(i), c1(i), s2(i), c2(i), cd, sd, w1sq, w2sq, &
                             rdet)
         call tangent_vector(c, i, a1(i), a2(i), s1(i), s2(i), cd, sd, w1(i), w2(i), w1sq, &
                             w2sq, rdet, x(i, 1, 1), x(i, 2, 1), x(i, 3, 1), x(i, 4, 1), &
                             b(i, 1, 1), b(i, 2, 1))
         call tangent_vector(c, i, a1(i), a2(i), s1(i), s2(i), cd, sd, w1(i), w2(i), w1sq, &
                             w2sq, rdet, x(i, 1, 2), x(i, 2, 2), x(i, 3, 2), x(i, 4, 2), &
                             b(i, 1, 2), b(i, 2, 2))
      end do
   end subroutine tangent_accel2_lanes

   !> The terms of lane l's tangent accelerations that do not depend on the vector:
   !> cos d, sin d (d = q1 - q2), the squared velocities as `accel_trig` takes them
   !> (`wsq`) and 1/det(M/k), the same expression as `accel_trig`'s (in a fused step
   !> gcc computes both once).
   pure subroutine tangent_shared(c, l, w1, w2, s1, c1, s2, c2, cd, sd, w1sq, w2sq, rdet)
      type(lane_coef_t), intent(in) :: c       !! constants
      integer, intent(in) :: l                 !! lane
      real(dp), intent(in) :: w1, w2           !! velocities [rad/s]
      real(dp), intent(in) :: s1, c1, s2, c2   !! sin q1, cos q1, sin q2, cos q2
      real(dp), intent(out) :: cd, sd          !! cos d, sin d
      real(dp), intent(out) :: w1sq, w2sq      !! `wsq` of the velocities [rad²/s²]
      real(dp), intent(out) :: rdet            !! 1/det(M/k) [1]
      cd = c1*c2 + s1*s2
      sd = s1*c2 - c1*s2
      w1sq = wsq(w1)
      w2sq = wsq(w2)
      rdet = 1.0_dp/(c%detk(l) - cd*cd)
   end subroutine tangent_shared

   !> Lane l's derivative (b1, b2) of the accelerations (a1, a2) along (u1, u2, v1,
   !> v2), from the terms of `tangent_shared` [rad/s²]: the equations divided by k,
   !> as in `accel_trig` (M/k = [m11k, cos d; cos d, m22k], r/k), differentiated:
   !> (M/k) δa = δr/k - δ(M/k) a, δ(M/k) = [0, δcos d; δcos d, 0]. (A lane beyond
   !> `lane_bound`, which `integrate_batch` ends, keeps its values finite: the
   !> squares are `wsq`'s, the velocities themselves stay far below 1e100.)
   pure subroutine tangent_vector(c, l, a1, a2, s1, s2, cd, sd, w1, w2, w1sq, w2sq, rdet, &
                                  u1, u2, v1, v2, b1, b2)
      type(lane_coef_t), intent(in) :: c        !! constants
      integer, intent(in) :: l                  !! lane
      real(dp), intent(in) :: a1, a2            !! accelerations [rad/s²]
      real(dp), intent(in) :: s1, s2            !! sin q1, sin q2
      real(dp), intent(in) :: cd, sd, w1sq, w2sq, rdet  !! from `tangent_shared`
      real(dp), intent(in) :: w1, w2            !! velocities [rad/s]
      real(dp), intent(in) :: u1, u2, v1, v2    !! the vector [rad, rad/s]
      real(dp), intent(out) :: b1, b2           !! derivative of (a1, a2) [rad/s²]
      real(dp) :: ud, dcd, dsd, e1, e2
      ud = u1 - u2
      dcd = -sd*ud
      dsd = cd*ud
      e1 = c%gak(l)*s1*u1 - (dsd*w2sq + 2.0_dp*sd*w2*v2) - dcd*a2
      e2 = c%gbk(l)*s2*u2 + (dsd*w1sq + 2.0_dp*sd*w1*v1) - dcd*a1
      b1 = (c%m22k(l)*e1 - cd*e2)*rdet
      b2 = (c%m11k(l)*e2 - cd*e1)*rdet
   end subroutine tangent_vector

   !> One RK4 step of the state and of a tangent vector (u, v) of the variational
   !> equations, the same RK4 applied to the extended system; `e` as in `rk4_lanes`.
   pure subroutine rk4_tangent_lanes_lc(c, h, q1, q2, w1, w2, u1, u2, v1, v2, e)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(inout) :: u1(lane_width), u2(lane_width)  !! tangent, angles
      real(dp), intent(inout) :: v1(lane_width), v2(lane_width)  !! tangent, velocities
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      real(dp), dimension(lane_width) :: s1, c1, s2, c2, x1, x2, y1, y2
      real(dp), dimension(lane_width) :: s1a, c1a, s2a, c2a
      type(lane_trig_t) :: ta
      real(dp), dimension(lane_width) :: ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2
      real(dp), dimension(lane_width) :: vb1, vb2, vc1, vc2, vd1, vd2
      real(dp), dimension(lane_width) :: xu1, xu2, ub1, ub2, uc1, uc2, ud1, ud2
      real(dp), dimension(lane_width) :: la1, la2, lb1, lb2, lc1, lc2, ld1, ld2
      real(dp) :: hh, h6
      integer :: i
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      call accel_lanes(c, q1, q2, w1, w2, ka1, ka2, s1a, c1a, s2a, c2a)
      call tangent_accel_lanes(c, w1, w2, ka1, ka2, s1a, c1a, s2a, c2a, u1, u2, v1, v2, la1, la2)
      ta = lane_trig_t(s1a, c1a, s2a, c2a)
      do i = 1, lane_width
         e(i) = energy_formula(c, i, s1a(i), c1a(i), s2a(i), c2a(i), w1(i), w2(i))
         x1(i) = q1(i) + hh*w1(i); x2(i) = q2(i) + hh*w2(i)
         vb1(i) = w1(i) + hh*ka1(i); vb2(i) = w2(i) + hh*ka2(i)
         xu1(i) = u1(i) + hh*v1(i); xu2(i) = u2(i) + hh*v2(i)
         ub1(i) = v1(i) + hh*la1(i); ub2(i) = v2(i) + hh*la2(i)
      end do
      call stage_trig_lanes(q1, q2, ta, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vb1, vb2, kb1, kb2)
      call tangent_accel_lanes(c, vb1, vb2, kb1, kb2, s1, c1, s2, c2, xu1, xu2, ub1, ub2, &
                               lb1, lb2)
      do i = 1, lane_width
         x1(i) = q1(i) + hh*vb1(i); x2(i) = q2(i) + hh*vb2(i)
         vc1(i) = w1(i) + hh*kb1(i); vc2(i) = w2(i) + hh*kb2(i)
         xu1(i) = u1(i) + hh*ub1(i); xu2(i) = u2(i) + hh*ub2(i)
         uc1(i) = v1(i) + hh*lb1(i); uc2(i) = v2(i) + hh*lb2(i)
      end do
      call stage_trig_lanes(q1, q2, ta, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vc1, vc2, kc1, kc2)
      call tangent_accel_lanes(c, vc1, vc2, kc1, kc2, s1, c1, s2, c2, xu1, xu2, uc1, uc2, &
                               lc1, lc2)
      do i = 1, lane_width
         y1(i) = q1(i) + h*vc1(i); y2(i) = q2(i) + h*vc2(i)
         vd1(i) = w1(i) + h*kc1(i); vd2(i) = w2(i) + h*kc2(i)
         xu1(i) = u1(i) + h*uc1(i); xu2(i) = u2(i) + h*uc2(i)
         ud1(i) = v1(i) + h*lc1(i); ud2(i) = v2(i) + h*lc2(i)
      end do
      call stage_trig_lanes(q1, q2, ta, y1, y2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vd1, vd2, kd1, kd2)
      call tangent_accel_lanes(c, vd1, vd2, kd1, kd2, s1, c1, s2, c2, xu1, xu2, ud1, ud2, &
                               ld1, ld2)
      do i = 1, lane_width
         q1(i) = q1(i) + h6*(w1(i) + 2.0_dp*(vb1(i) + vc1(i)) + vd1(i))
         q2(i) = q2(i) + h6*(w2(i) + 2.0_dp*(vb2(i) + vc2(i)) + vd2(i))
         w1(i) = w1(i) + h6*(ka1(i) + 2.0_dp*(kb1(i) + kc1(i)) + kd1(i))
         w2(i) = w2(i) + h6*(ka2(i) + 2.0_dp*(kb2(i) + kc2(i)) + kd2(i))
         u1(i) = u1(i) + h6*(v1(i) + 2.0_dp*(ub1(i) + uc1(i)) + ud1(i))
         u2(i) = u2(i) + h6*(v2(i) + 2.0_dp*(ub2(i) + uc2(i)) + ud2(i))
         v1(i) = v1(i) + h6*(la1(i) + 2.0_dp*(lb1(i) + lc1(i)) + ld1(i))
         v2(i) = v2(i) + h6*(la2(i) + 2.0_dp*(lb2(i) + lc2(i)) + ld2(i))
      end do
   end subroutine rk4_tangent_lanes_lc

   !> `rk4_tangent_lanes` with two tangent vectors d(:, :, 1) and d(:, :, 2) = (u1, u2,
   !> v1, v2) (SALI, GALI_2): the state's stages, sines and cosines once, one
   !> Jacobian per stage for both vectors (`tangent_accel2_lanes`). Every value (state,
   !> each vector, `e`) equals that of `rk4_tangent_lanes` on that vector bit for bit
   !> (the same operations; test lanes/tangent2_matches_tangent).
   pure subroutine rk4_tangent2_lanes(c, h, q1, q2, w1, w2, d, e)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(inout) :: d(lane_width, 4, 2)             !! tangent vectors
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      real(dp), dimension(lane_width) :: s1, c1, s2, c2, x1, x2, y1, y2
      real(dp), dimension(lane_width) :: s1a, c1a, s2a, c2a
      type(lane_trig_t) :: ta
      real(dp), dimension(lane_width) :: ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2
      real(dp), dimension(lane_width) :: vb1, vb2, vc1, vc2, vd1, vd2
      ! the vectors at stages b, c, d (δq1, δq2, δq̇1, δq̇2) and their δq̈ at stages a to d
      real(dp), dimension(lane_width, 4, 2) :: xb, xc, xd
      real(dp), dimension(lane_width, 2, 2) :: la, lb, lc, ld
      real(dp) :: hh, h6
      integer :: i, k
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      call accel_lanes(c, q1, q2, w1, w2, ka1, ka2, s1a, c1a, s2a, c2a)
      call tangent_accel2_lanes(c, w1, w2, ka1, ka2, s1a, c1a, s2a, c2a, d, la)
      ta = lane_trig_t(s1a, c1a, s2a, c2a)
      do i = 1, lane_width
         e(i) = energy_formula(c, i, s1a(i), c1a(i), s2a(i), c2a(i), w1(i), w2(i))
         x1(i) = q1(i) + hh*w1(i); x2(i) = q2(i) + hh*w2(i)
         vb1(i) = w1(i) + hh*ka1(i); vb2(i) = w2(i) + hh*ka2(i)
      end do
      do k = 1, 2
         do i = 1, lane_width
            xb(i, 1, k) = d(i, 1, k) + hh*d(i, 3, k); xb(i, 2, k) = d(i, 2, k) + hh*d(i, 4, k)
            xb(i, 3, k) = d(i, 3, k) + hh*la(i, 1, k); xb(i, 4, k) = d(i, 4, k) + hh*la(i, 2, k)
         end do
      end do
      call stage_trig_lanes(q1, q2, ta, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vb1, vb2, kb1, kb2)
      call tangent_accel2_lanes(c, vb1, vb2, kb1, kb2, s1, c1, s2, c2, xb, lb)
      do i = 1, lane_width
         x1(i) = q1(i) + hh*vb1(i); x2(i) = q2(i) + hh*vb2(i)
         vc1(i) = w1(i) + hh*kb1(i); vc2(i) = w2(i) + hh*kb2(i)
      end do
      do k = 1, 2
         do i = 1, lane_width
            xc(i, 1, k) = d(i, 1, k) + hh*xb(i, 3, k); xc(i, 2, k) = d(i, 2, k) + hh*xb(i, 4, k)
            xc(i, 3, k) = d(i, 3, k) + hh*lb(i, 1, k); xc(i, 4, k) = d(i, 4, k) + hh*lb(i, 2, k)
         end do
      end do
      call stage_trig_lanes(q1, q2, ta, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vc1, vc2, kc1, kc2)
      call tangent_accel2_lanes(c, vc1, vc2, kc1, kc2, s1, c1, s2, c2, xc, lc)
      do i = 1, lane_width
         y1(i) = q1(i) + h*vc1(i); y2(i) = q2(i) + h*vc2(i)
         vd1(i) = w1(i) + h*kc1(i); vd2(i) = w2(i) + h*kc2(i)
      end do
      do k = 1, 2
         do i = 1, lane_width
            xd(i, 1, k) = d(i, 1, k) + h*xc(i, 3, k); xd(i, 2, k) = d(i, 2, k) + h*xc(i, 4, k)
            xd(i, 3, k) = d(i, 3, k) + h*lc(i, 1, k); xd(i, 4, k) = d(i, 4, k) + h*lc(i, 2, k)
         end do
      end do
      call stage_trig_lanes(q1, q2, ta, y1, y2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vd1, vd2, kd1, kd2)
      call tangent_accel2_lanes(c, vd1, vd2, kd1, kd2, s1, c1, s2, c2, xd, ld)
      do i = 1, lane_width
         q1(i) = q1(i) + h6*(w1(i) + 2.0_dp*(vb1(i) + vc1(i)) + vd1(i))
         q2(i) = q2(i) + h6*(w2(i) + 2.0_dp*(vb2(i) + vc2(i)) + vd2(i))
         w1(i) = w1(i) + h6*(ka1(i) + 2.0_dp*(kb1(i) + kc1(i)) + kd1(i))
         w2(i) = w2(i) + h6*(ka2(i) + 2.0_dp*(kb2(i) + kc2(i)) + kd2(i))
      end do
      do k = 1, 2
         do i = 1, lane_width
            d(i, 1, k) = d(i, 1, k) + h6*(d(i, 3, k) + 2.0_dp*(xb(i, 3, k) + xc(i, 3, k)) &
                                          + xd(i, 3, k))
            d(i, 2, k) = d(i, 2, k) + h6*(d(i, 4, k) + 2.0_dp*(xb(i, 4, k) + xc(i, 4, k)) &
                                          + xd(i, 4, k))
            d(i, 3, k) = d(i, 3, k) + h6*(la(i, 1, k) + 2.0_dp*(lb(i, 1, k) + lc(i, 1, k)) &
                                          + ld(i, 1, k))
            d(i, 4, k) = d(i, 4, k) + h6*(la(i, 2, k) + 2.0_dp*(lb(i, 2, k) + lc(i, 2, k)) &
                                          + ld(i, 2, k))
         end do
      end do
   end subroutine rk4_tangent2_lanes

   !> One RK4 step of the state and of nv (1 or 2) deviation vectors d(:, :, k) = (u1,
   !> u2, v1, v2): `rk4_tangent_lanes` (nv = 1) or `rk4_tangent2_lanes`
   !> (nv = 2) fused the way `rk4_lanes` is, the whole step of a lane one loop body
   !> (`tangent_lane_step`: the stages' values stay in registers, the Jacobian's
   !> terms once per stage for both vectors, one division per stage for the state
   !> and the vectors). `tr` as in `rk4_lanes`: the sines and cosines of the step
   !> start on entry, of the new state on return, carried by the addition formulas
   !> (the caller sets them exactly every so often). The values equal those of
   !> `rk4_tangent_lanes` and `rk4_tangent2_lanes` to rounding: those take exact sin
   !> and cos at each step start and the longer polynomials at the stages (test
   !> lanes/tangent_fused_matches).
   !> A lane outside the fused path's range (an offset |d| > `d_max` of a stage or of
   !> the new state from the step start, where those routines take exact sin and cos)
   !> takes their step from the saved start
   !> (`tangent_fallback`: that lane only, so that the lanes never mix), and exact sin
   !> and cos of its new state.
   pure subroutine rk4_tangent_fused_lanes(c, h, q1, q2, w1, w2, nv, d, e, tr)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      integer, intent(in) :: nv                                  !! vectors, 1 or 2
      real(dp), intent(inout) :: d(lane_width, 4, 2)             !! tangent vectors
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      real(dp), dimension(lane_width) :: p1, p2, pw1, pw2
      real(dp) :: pd(lane_width, 4, 2), off(lane_width), n_off
      integer :: i
      p1 = q1; p2 = q2; pw1 = w1; pw2 = w2
      pd(:, :, 1:nv) = d(:, :, 1:nv)   ! (the vectors in use only: a copy every step)
      n_off = 0
      ! (one call: gcc inlines it, then vectorizes the loop)
      do i = 1, lane_width
         call tangent_lane_step(c, i, h, nv, tr%s1(i), tr%c1(i), tr%s2(i), tr%c2(i), &
                                q1(i), q2(i), w1(i), w2(i), &
                                d(i, 1, 1), d(i, 2, 1), d(i, 3, 1), d(i, 4, 1), &
                                d(i, 1, 2), d(i, 2, 2), d(i, 3, 2), d(i, 4, 2), e(i), off(i))
         n_off = n_off + off(i)
      end do
      if (n_off == 0.0_dp) return   ! (a NaN offset fails its check)
      call tangent_fallback(c, h, nv, off, p1, p2, pw1, pw2, pd, q1, q2, w1, w2, d, e, tr)
   end subroutine rk4_tangent_fused_lanes

   !> The lanes of `rk4_tangent_fused_lanes` with off /= 0 take the step of
   !> `rk4_tangent_lanes` (nv = 1) or `rk4_tangent2_lanes` (nv = 2) from the saved
   !> start (p1, p2, pw1, pw2, pd); the other lanes keep their fused values, so that
   !> each lane's result depends on its own values only (the two paths may differ by
   !> rounding: FMA contraction in the release profile); their carried sines and
   !> cosines are set exactly (`sincos_exact`), as in `rk4_lanes_fallback`.
   pure subroutine tangent_fallback(c, h, nv, off, p1, p2, pw1, pw2, pd, q1, q2, w1, w2, d, e, &
                                    tr)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      integer, intent(in) :: nv                                  !! vectors, 1 or 2
      real(dp), intent(in) :: off(lane_width)                    !! 0: the lane's step holds
      real(dp), intent(in) :: p1(lane_width), p2(lane_width)     !! step start [rad]
      real(dp), intent(in) :: pw1(lane_width), pw2(lane_width)   !! step start [rad/s]
      real(dp), intent(in) :: pd(lane_width, 4, 2)               !! vectors at the start (1:nv)
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! new angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! new velocities [rad/s]
      real(dp), intent(inout) :: d(lane_width, 4, 2)             !! new vectors
      real(dp), intent(inout) :: e(lane_width)                   !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      real(dp), dimension(lane_width) :: r1, r2, rw1, rw2, re
      real(dp) :: rd(lane_width, 4, 2)
      integer :: i
      r1 = p1; r2 = p2; rw1 = pw1; rw2 = pw2
      rd = 0
      rd(:, :, 1:nv) = pd(:, :, 1:nv)
      if (nv > 1) then
         call rk4_tangent2_lanes(c, h, r1, r2, rw1, rw2, rd, re)
      else
         call rk4_tangent_lanes_lc(c, h, r1, r2, rw1, rw2, rd(:, 1, 1), rd(:, 2, 1), &
                                   rd(:, 3, 1), rd(:, 4, 1), re)
      end if
      do i = 1, lane_width
         if (.not. (off(i) == 0.0_dp)) then
            q1(i) = r1(i); q2(i) = r2(i); w1(i) = rw1(i); w2(i) = rw2(i); e(i) = re(i)
            d(i, :, 1:nv) = rd(i, :, 1:nv)
            call sincos_exact(q1(i), tr%s1(i), tr%c1(i))
            call sincos_exact(q2(i), tr%s2(i), tr%c2(i))
         end if
      end do
   end subroutine tangent_fallback

   !> Lane l's step of `rk4_tangent_fused_lanes` with nv vectors (x1 .. x4: vector 1,
   !> y1 .. y4: vector 2, untouched for nv = 1), from the carried sin and cos of the
   !> step start (s1 .. c2; on return those of the new state, by `sincos_add`);
   !> off > 0 (or NaN) where the lane leaves the fused path (its values are then
   !> discarded, but stay bounded). The vectors' δq̈ are `tangent_vector`'s formula,
   !> written out for each stage and vector (GCC 12 does not inline eight calls of it
   !> into one loop body, and a call stops the vectorizer); test
   !> lanes/tangent_fused_matches compares them. The stages' sines and cosines are
   !> `sincos_add_stage`'s, as in `rk4_lanes`.
   pure subroutine tangent_lane_step(c, l, h, nv, s1a, c1a, s2a, c2a, q1, q2, w1, w2, &
                                     x1, x2, x3, x4, y1, y2, y3, y4, e, off)
      type(lane_coef_t), intent(in) :: c             !! constants
      integer, intent(in) :: l                       !! lane
      real(dp), intent(in) :: h                      !! step [s]
      integer, intent(in) :: nv                      !! vectors, 1 or 2
      real(dp), intent(inout) :: s1a, c1a, s2a, c2a  !! sin q1, cos q1, sin q2, cos q2
      real(dp), intent(inout) :: q1, q2              !! angles [rad]
      real(dp), intent(inout) :: w1, w2              !! velocities [rad/s]
      real(dp), intent(inout) :: x1, x2, x3, x4      !! vector 1 (u1, u2, v1, v2)
      real(dp), intent(inout) :: y1, y2, y3, y4      !! vector 2
      real(dp), intent(out) :: e                     !! energy before [J]
      real(dp), intent(out) :: off                   !! 0 on the fused path
      real(dp) :: hh, h6, s1, c1, s2, c2, o1, o2
      real(dp) :: ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2, vb1, vb2, vc1, vc2, vd1, vd2
      real(dp) :: sa1, sa2, sb1, sb2, sc1, sc2, sd1, sd2
      real(dp) :: cd, sd, w1sq, w2sq, rdet, ud, dcd, dsd, e1, e2
      ! vector 1 (x) and 2 (y) at stages b, c, d and their δq̈ at stages a to d
      real(dp) :: xb1, xb2, xb3, xb4, xc1, xc2, xc3, xc4, xd1, xd2, xd3, xd4
      real(dp) :: la1, la2, lb1, lb2, lc1, lc2, ld1, ld2
      real(dp) :: yb1, yb2, yb3, yb4, yc1, yc2, yc3, yc4, yd1, yd2, yd3, yd4
      real(dp) :: ma1, ma2, mb1, mb2, mc1, mc2, md1, md2
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      ! stage a: the carried sin and cos of the step start
      off = 0
      call accel_trig(c, l, s1a, c1a, s2a, c2a, wsq(w1), wsq(w2), ka1, ka2)
      call tangent_shared(c, l, w1, w2, s1a, c1a, s2a, c2a, cd, sd, w1sq, w2sq, rdet)
      ud = x1 - x2
      dcd = -sd*ud
      dsd = cd*ud
      e1 = c%gak(l)*s1a*x1 - (dsd*w2sq + 2.0_dp*sd*w2*x4) - dcd*ka2
      e2 = c%gbk(l)*s2a*x2 + (dsd*w1sq + 2.0_dp*sd*w1*x3) - dcd*ka1
      la1 = (c%m22k(l)*e1 - cd*e2)*rdet
      la2 = (c%m11k(l)*e2 - cd*e1)*rdet
      if (nv > 1) then
         ud = y1 - y2
         dcd = -sd*ud
         dsd = cd*ud
         e1 = c%gak(l)*s1a*y1 - (dsd*w2sq + 2.0_dp*sd*w2*y4) - dcd*ka2
         e2 = c%gbk(l)*s2a*y2 + (dsd*w1sq + 2.0_dp*sd*w1*y3) - dcd*ka1
         ma1 = (c%m22k(l)*e1 - cd*e2)*rdet
         ma2 = (c%m11k(l)*e2 - cd*e1)*rdet
      end if
      e = energy_formula(c, l, s1a, c1a, s2a, c2a, w1, w2)
      sa1 = q1 + hh*w1; sa2 = q2 + hh*w2
      vb1 = w1 + hh*ka1; vb2 = w2 + hh*ka2
      xb1 = x1 + hh*x3; xb2 = x2 + hh*x4; xb3 = x3 + hh*la1; xb4 = x4 + hh*la2
      if (nv > 1) then
         yb1 = y1 + hh*y3; yb2 = y2 + hh*y4; yb3 = y3 + hh*ma1; yb4 = y4 + hh*ma2
      end if
      ! stage b
      sb1 = sa1 - q1; sb2 = sa2 - q2
      o1 = dclamp(sb1); o2 = dclamp(sb2)
      off = off + (abs(sb1 - o1) + abs(sb2 - o2))
      call sincos_add_stage(s1a, c1a, o1, s1, c1)
      call sincos_add_stage(s2a, c2a, o2, s2, c2)
      call accel_trig(c, l, s1, c1, s2, c2, wsq(vb1), wsq(vb2), kb1, kb2)
      call tangent_shared(c, l, vb1, vb2, s1, c1, s2, c2, cd, sd, w1sq, w2sq, rdet)
      ud = xb1 - xb2
      dcd = -sd*ud
      dsd = cd*ud
      e1 = c%gak(l)*s1*xb1 - (dsd*w2sq + 2.0_dp*sd*vb2*xb4) - dcd*kb2
      e2 = c%gbk(l)*s2*xb2 + (dsd*w1sq + 2.0_dp*sd*vb1*xb3) - dcd*kb1
      lb1 = (c%m22k(l)*e1 - cd*e2)*rdet
      lb2 = (c%m11k(l)*e2 - cd*e1)*rdet
      if (nv > 1) then
         ud = yb1 - yb2
         dcd = -sd*ud
         dsd = cd*ud
         e1 = c%gak(l)*s1*yb1 - (dsd*w2sq + 2.0_dp*sd*vb2*yb4) - dcd*kb2
         e2 = c%gbk(l)*s2*yb2 + (dsd*w1sq + 2.0_dp*sd*vb1*yb3) - dcd*kb1
         mb1 = (c%m22k(l)*e1 - cd*e2)*rdet
         mb2 = (c%m11k(l)*e2 - cd*e1)*rdet
      end if
      sa1 = q1 + hh*vb1; sa2 = q2 + hh*vb2
      vc1 = w1 + hh*kb1; vc2 = w2 + hh*kb2
      xc1 = x1 + hh*xb3; xc2 = x2 + hh*xb4; xc3 = x3 + hh*lb1; xc4 = x4 + hh*lb2
      if (nv > 1) then
         yc1 = y1 + hh*yb3; yc2 = y2 + hh*yb4; yc3 = y3 + hh*mb1; yc4 = y4 + hh*mb2
      end if
      ! stage c
      sc1 = sa1 - q1; sc2 = sa2 - q2
      o1 = dclamp(sc1); o2 = dclamp(sc2)
      off = off + (abs(sc1 - o1) + abs(sc2 - o2))
      call sincos_add_stage(s1a, c1a, o1, s1, c1)
      call sincos_add_stage(s2a, c2a, o2, s2, c2)
      call accel_trig(c, l, s1, c1, s2, c2, wsq(vc1), wsq(vc2), kc1, kc2)
      call tangent_shared(c, l, vc1, vc2, s1, c1, s2, c2, cd, sd, w1sq, w2sq, rdet)
      ud = xc1 - xc2
      dcd = -sd*ud
      dsd = cd*ud
      e1 = c%gak(l)*s1*xc1 - (dsd*w2sq + 2.0_dp*sd*vc2*xc4) - dcd*kc2
      e2 = c%gbk(l)*s2*xc2 + (dsd*w1sq + 2.0_dp*sd*vc1*xc3) - dcd*kc1
      lc1 = (c%m22k(l)*e1 - cd*e2)*rdet
      lc2 = (c%m11k(l)*e2 - cd*e1)*rdet
      if (nv > 1) then
         ud = yc1 - yc2
         dcd = -sd*ud
         dsd = cd*ud
         e1 = c%gak(l)*s1*yc1 - (dsd*w2sq + 2.0_dp*sd*vc2*yc4) - dcd*kc2
         e2 = c%gbk(l)*s2*yc2 + (dsd*w1sq + 2.0_dp*sd*vc1*yc3) - dcd*kc1
         mc1 = (c%m22k(l)*e1 - cd*e2)*rdet
         mc2 = (c%m11k(l)*e2 - cd*e1)*rdet
      end if
      sa1 = q1 + h*vc1; sa2 = q2 + h*vc2
      vd1 = w1 + h*kc1; vd2 = w2 + h*kc2
      xd1 = x1 + h*xc3; xd2 = x2 + h*xc4; xd3 = x3 + h*lc1; xd4 = x4 + h*lc2
      if (nv > 1) then
         yd1 = y1 + h*yc3; yd2 = y2 + h*yc4; yd3 = y3 + h*mc1; yd4 = y4 + h*mc2
      end if
      ! stage d
      sd1 = sa1 - q1; sd2 = sa2 - q2
      o1 = dclamp(sd1); o2 = dclamp(sd2)
      off = off + (abs(sd1 - o1) + abs(sd2 - o2))
      call sincos_add_stage(s1a, c1a, o1, s1, c1)
      call sincos_add_stage(s2a, c2a, o2, s2, c2)
      call accel_trig(c, l, s1, c1, s2, c2, wsq(vd1), wsq(vd2), kd1, kd2)
      call tangent_shared(c, l, vd1, vd2, s1, c1, s2, c2, cd, sd, w1sq, w2sq, rdet)
      ud = xd1 - xd2
      dcd = -sd*ud
      dsd = cd*ud
      e1 = c%gak(l)*s1*xd1 - (dsd*w2sq + 2.0_dp*sd*vd2*xd4) - dcd*kd2
      e2 = c%gbk(l)*s2*xd2 + (dsd*w1sq + 2.0_dp*sd*vd1*xd3) - dcd*kd1
      ld1 = (c%m22k(l)*e1 - cd*e2)*rdet
      ld2 = (c%m11k(l)*e2 - cd*e1)*rdet
      if (nv > 1) then
         ud = yd1 - yd2
         dcd = -sd*ud
         dsd = cd*ud
         e1 = c%gak(l)*s1*yd1 - (dsd*w2sq + 2.0_dp*sd*vd2*yd4) - dcd*kd2
         e2 = c%gbk(l)*s2*yd2 + (dsd*w1sq + 2.0_dp*sd*vd1*yd3) - dcd*kd1
         md1 = (c%m22k(l)*e1 - cd*e2)*rdet
         md2 = (c%m11k(l)*e2 - cd*e1)*rdet
      end if
      ! the new state and vectors (the sums as in `rk4_tangent_lanes`), and the new
      ! state's sin and cos from the step start's
      sa1 = q1 + h6*(w1 + 2.0_dp*(vb1 + vc1) + vd1)
      sa2 = q2 + h6*(w2 + 2.0_dp*(vb2 + vc2) + vd2)
      w1 = w1 + h6*(ka1 + 2.0_dp*(kb1 + kc1) + kd1)
      w2 = w2 + h6*(ka2 + 2.0_dp*(kb2 + kc2) + kd2)
      x1 = x1 + h6*(x3 + 2.0_dp*(xb3 + xc3) + xd3)
      x2 = x2 + h6*(x4 + 2.0_dp*(xb4 + xc4) + xd4)
      x3 = x3 + h6*(la1 + 2.0_dp*(lb1 + lc1) + ld1)
      x4 = x4 + h6*(la2 + 2.0_dp*(lb2 + lc2) + ld2)
      if (nv > 1) then
         y1 = y1 + h6*(y3 + 2.0_dp*(yb3 + yc3) + yd3)
         y2 = y2 + h6*(y4 + 2.0_dp*(yb4 + yc4) + yd4)
         y3 = y3 + h6*(ma1 + 2.0_dp*(mb1 + mc1) + md1)
         y4 = y4 + h6*(ma2 + 2.0_dp*(mb2 + mc2) + md2)
      end if
      sb1 = sa1 - q1; sb2 = sa2 - q2
      q1 = sa1; q2 = sa2
      o1 = dclamp(sb1); o2 = dclamp(sb2)
      off = off + (abs(sb1 - o1) + abs(sb2 - o2))
      call sincos_add(s1a, c1a, o1, s1, c1)
      call sincos_add(s2a, c2a, o2, s2, c2)
      s1a = s1; c1a = c1; s2a = s2; c2a = c2
   end subroutine tangent_lane_step

   !> One RK4 step of the state with nv (1 or 2) deviation vectors d(:, :, k) =
   !> (u1, u2, v1, v2) of the fast indicators (dpend_indicator_math) through
   !> `rk4_tangent_fused_lanes` (the state's stages once; the operations of
   !> `rk4_tangent_lanes` and `rk4_tangent2_lanes`). Vector 1's growth enters the
   !> sums acc(:, 1:4) = (ln |δ|, MEGNO's integral, Y, ∫ Y ds) of the step
   !> [ks h, (ks + 1) h] (`megno_step`, t0 = 0, `megno_lane`): ln |δ| after the
   !> step is ln(|d|²)/2 (`log_poly`), less acc(:, 5) = ln |d| before it; a lane
   !> whose |d|² is not a positive normal number gets NaN sums. Each vector is
   !> then scaled by the power of two 2^-m that brings |d|² into [1, 4)
   !> (`pow2_scale`: exact, so directions and ratios are untouched, with no square
   !> root or division; SALI and GALI_2 normalise the vectors themselves), and
   !> acc(:, 5) = ln |d| - m ln 2. `e` and `tr` as in `rk4_lanes`.
   pure subroutine indicator_step_lanes_lc(c, h, ks, q1, q2, w1, w2, nv, d, acc, e, tr)
      type(lane_coef_t), intent(in) :: c                           !! constants
      real(dp), intent(in) :: h                                    !! step [s]
      integer(i8), intent(in) :: ks(lane_width)                    !! steps done before
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)    !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      integer, intent(in) :: nv                                    !! vectors, 1 or 2
      real(dp), intent(inout) :: d(lane_width, 4, 2)               !! deviation vectors
      real(dp), intent(inout) :: acc(lane_width, 5)                !! vector 1's sums, ln |d|
      real(dp), intent(out) :: e(lane_width)                       !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                       !! sin, cos of q1, q2
      real(dp), dimension(lane_width) :: n2
      real(dp) :: sc, dm
      integer(i8) :: bad
      integer :: i, j
      call rk4_tangent_fused_lanes(c, h, q1, q2, w1, w2, nv, d, e, tr)
      bad = 0
      do i = 1, lane_width
         n2(i) = d(i, 1, 1)**2 + d(i, 2, 1)**2 + d(i, 3, 1)**2 + d(i, 4, 1)**2
         bad = bad + not_normal(n2(i))
      end do
      do i = 1, lane_width
         call vector1_update(h, ks(i), n2(i), log_poly(n2(i)), d(i, 1, 1), d(i, 2, 1), &
                             d(i, 3, 1), d(i, 4, 1), acc(i, 1), acc(i, 2), acc(i, 3), &
                             acc(i, 4), acc(i, 5))
      end do
      ! rare: a lane whose |d|² is 0, subnormal, Inf or NaN (a vector collapsed or
      ! overflowed in one step: its indicators have no meaning) gets NaN sums, so
      ! that its pixel has none (`integrate_batch` stores NaN for a non-finite sum)
      if (bad > 0) then
         do i = 1, lane_width
            if (not_normal(n2(i)) > 0) acc(i, :) = ieee_value(1.0_dp, ieee_quiet_nan)
         end do
      end if
      if (nv < 2) return
      do i = 1, lane_width
         n2(i) = d(i, 1, 2)**2 + d(i, 2, 2)**2 + d(i, 3, 2)**2 + d(i, 4, 2)**2
         call pow2_scale(n2(i), sc, dm)
         do j = 1, 4
            d(i, j, 2) = d(i, j, 2)*sc
         end do
      end do
   end subroutine indicator_step_lanes_lc

   !> One lane's update of vector 1 after a step (`indicator_step_lanes`): from
   !> n2 = |d|² and lnn2 = ln n2, MEGNO's sums of the step [ks h, (ks + 1) h] and
   !> ln |d| (lg, ig, yy, sy, ld = acc(:, 1:5)); d scaled by `pow2_scale`.
   pure elemental subroutine vector1_update(h, ks, n2, lnn2, d1, d2, d3, d4, lg, ig, yy, &
                                            sy, ld)
      real(dp), intent(in) :: h                    !! step [s]
      integer(i8), intent(in) :: ks                !! steps done before
      real(dp), intent(in) :: n2, lnn2             !! |d|², ln |d|²
      real(dp), intent(inout) :: d1, d2, d3, d4    !! vector 1
      real(dp), intent(inout) :: lg, ig, yy, sy    !! MEGNO's sums (`megno_lane`)
      real(dp), intent(inout) :: ld                !! ln |d| of the carried vector
      real(dp), parameter :: ln2 = log(2.0_dp)
      real(dp) :: sc, dm, dl
      call pow2_scale(n2, sc, dm)
      d1 = d1*sc; d2 = d2*sc; d3 = d3*sc; d4 = d4*sc
      dl = 0.5_dp*lnn2 - ld
      ld = 0.5_dp*lnn2 - dm*ln2
      call megno_lane(dl, real(ks, dp)*h, real(ks + 1, dp)*h, lg, ig, yy, sy)
   end subroutine vector1_update

   !> The power of two sc = 2^-m, m = floor(e/2) for the exponent e of x (x = |d|²):
   !> x sc² lies in [1, 4) for a positive normal x; m as a real in dm. From the bits
   !> of x, without a compare (NaN and Inf give some power of two within range).
   pure elemental subroutine pow2_scale(x, sc, dm)
      real(dp), intent(in) :: x    !! |d|²
      real(dp), intent(out) :: sc  !! 2^-m
      real(dp), intent(out) :: dm  !! m
      integer(i8) :: m
      m = shifta(shiftr(transfer(x, 0_i8), 52) - 1023_i8, 1)   ! floor((e + 1023 - 1023)/2)
      m = min(max(m, -511_i8), 511_i8)
      sc = transfer(shiftl(1023_i8 - m, 52), 1.0_dp)
      dm = real(m, dp)
   end subroutine pow2_scale

   !> ln x of every lane, our own vectorizable implementation (gfortran calls libm's
   !> log lane by lane, which stops the vectorizer): fdlibm's e_log.c. x = 2^k (1 + f)
   !> with sqrt(2)/2 <= 1 + f < sqrt(2) from the bits of x, s = f/(2 + f), ln(1 + f) =
   !> f - s (f - R(s²)) with fdlibm's minimax R (error < 2^-58), + k ln 2 in two parts.
   !> Within 1 ulp of the intrinsic log (test lanes/log_lanes_vs_intrinsic). Lanes
   !> outside the positive normal numbers (0, subnormal, negative, Inf, NaN) take the
   !> intrinsic log, lane by lane.
   pure subroutine log_lanes(x, r)
      real(dp), intent(in) :: x(lane_width)   !! argument
      real(dp), intent(out) :: r(lane_width)  !! ln x
      integer(i8) :: bad
      integer :: i
      bad = 0
      do i = 1, lane_width
         r(i) = log_poly(x(i))
         bad = bad + not_normal(x(i))
      end do
      if (bad == 0) return
      do i = 1, lane_width
         if (not_normal(x(i)) > 0) r(i) = log(x(i))
      end do
   end subroutine log_lanes

   !> 1 if x is not a positive normal finite number (0, subnormal, negative, Inf, NaN),
   !> else 0: from the sign and exponent bits (no floating-point compare, which would
   !> raise IEEE invalid on NaN).
   pure elemental integer(i8) function not_normal(x)
      real(dp), intent(in) :: x  !! argument
      integer(i8) :: ex
      ex = shiftr(transfer(x, 0_i8), 52)   ! sign and exponent: 1 .. 2046 for those
      not_normal = min(1_i8, max(0_i8, 1_i8 - ex) + max(0_i8, ex - 2046_i8))
   end function not_normal

   !> One lane of `log_lanes` for a positive normal finite x (other x give a finite
   !> value of no meaning). Elemental and private, so that gcc inlines it into the
   !> vectorized loop.
   pure elemental real(dp) function log_poly(x) result(r)
      real(dp), intent(in) :: x  !! argument
      real(dp), parameter :: ln2_hi = 6.93147180369123816490e-01_dp   ! 0x3fe62e42fee00000
      real(dp), parameter :: ln2_lo = 1.90821492927058770002e-10_dp   ! 0x3dea39ef35793c76
      real(dp), parameter :: lg1 = 6.666666666666735130e-01_dp, lg2 = 3.999999999940941908e-01_dp, &
                             lg3 = 2.857142874366239149e-01_dp, lg4 = 2.222219843214978396e-01_dp, &
                             lg5 = 1.818357216161805012e-01_dp, lg6 = 1.531383769920937332e-01_dp, &
                             lg7 = 1.479819860511658591e-01_dp
      ! the high word of sqrt(2)/2, and the mantissa and exponent masks of a double
      integer(i8), parameter :: rt2_hi = int(z'3FE6A09E00000000', i8)
      integer(i8), parameter :: one_hi = int(z'3FF0000000000000', i8)
      integer(i8), parameter :: mant = int(z'000FFFFFFFFFFFFF', i8)
      integer(i8) :: ix, k
      real(dp) :: f, s, z, w, t1, t2, hfsq, dk
      ! shift x's bits so that the exponent field steps up where the mantissa passes
      ! that of sqrt(2)/2: then 1 + f = the mantissa with the exponent of sqrt(2)/2 or 1
      ! (the bits clamped to those of huge: NaN's would overflow the integer sum)
      ix = min(transfer(x, 0_i8), int(z'7FEFFFFFFFFFFFFF', i8)) + (one_hi - rt2_hi)
      k = shiftr(ix, 52) - 1023
      f = transfer(iand(ix, mant) + rt2_hi, 1.0_dp) - 1.0_dp
      dk = real(k, dp)
      hfsq = 0.5_dp*f*f
      s = f/(2.0_dp + f)
      z = s*s
      w = z*z
      t1 = w*(lg2 + w*(lg4 + w*lg6))
      t2 = z*(lg1 + w*(lg3 + w*(lg5 + w*lg7)))
      r = s*(hfsq + (t2 + t1)) + dk*ln2_lo - hfsq + f + dk*ln2_hi
   end function log_poly

   !> Copy of `megno_step` (dpend_indicator_math) for speed, t0 = 0: SIMD over the
   !> lanes (a call of the elemental in another module would not be inlined);
   !> test/test_copies.f90 compares them. The kernel calls `megno_lane` itself
   !> (`vector1_update`); this loop is the test's entry, so that `megno_lane` stays
   !> private: made public, gcc 12 no longer inlined it into the kernel and MEGNO
   !> cost 2.6x the flip map instead of 1.7x (measured 2026-11-27).
   pure subroutine megno_step_lanes(dl, t_prev, t, lg, ig, yy, sy)
      real(dp), intent(in) :: dl(lane_width)                  !! ln of the growth of |δ|
      real(dp), intent(in) :: t_prev(lane_width), t(lane_width)  !! step start, end [s]
      real(dp), intent(inout) :: lg(lane_width)               !! ln |δ(t)| [1]
      real(dp), intent(inout) :: ig(lane_width)               !! ∫ s d ln|δ| [s]
      real(dp), intent(inout) :: yy(lane_width)               !! Y(t_prev) in, Y(t) out [1]
      real(dp), intent(inout) :: sy(lane_width)               !! ∫ Y ds [s]
      integer :: i
      do i = 1, lane_width
         call megno_lane(dl(i), t_prev(i), t(i), lg(i), ig(i), yy(i), sy(i))
      end do
   end subroutine megno_step_lanes

   !> One lane of `megno_step_lanes`.
   pure elemental subroutine megno_lane(dl, t_prev, t, lg, ig, yy, sy)
      real(dp), intent(in) :: dl           !! ln of the growth of |δ|
      real(dp), intent(in) :: t_prev, t    !! step start, end [s]
      real(dp), intent(inout) :: lg        !! ln |δ(t)| [1]
      real(dp), intent(inout) :: ig        !! ∫ s d ln|δ| [s]
      real(dp), intent(inout) :: yy        !! Y(t_prev) in, Y(t) out [1]
      real(dp), intent(inout) :: sy        !! ∫ Y ds [s]
      real(dp) :: y_new
      lg = lg + dl
      ig = ig + (0.5_dp*(t_prev + t))*dl   ! s - t0 = s exactly
      y_new = 2.0_dp*ig/t
      sy = sy + 0.5_dp*(t - t_prev)*(yy + y_new)
      yy = y_new
   end subroutine megno_lane

   !> One step of the largest Lyapunov exponent's kernel: `rk4_tangent_lanes` on the
   !> state and the deviation vector (u1, u2, v1, v2), the vector renormalised to
   !> length 1 and ln of its growth added to each lane's sum `lacc`; `e` the energy
   !> before the step [J].
   pure subroutine lyapunov_step_lanes(c, h, q1, q2, w1, w2, u1, u2, v1, v2, e, lacc)
      type(lane_coef_t), intent(in) :: c                       !! constants
      real(dp), intent(in) :: h                                !! step [s]
      real(dp), dimension(lane_width), intent(inout) :: q1, q2, w1, w2  !! state
      real(dp), dimension(lane_width), intent(inout) :: u1, u2, v1, v2  !! deviation
      real(dp), intent(out) :: e(lane_width)                   !! energy [J]
      real(dp), intent(inout) :: lacc(lane_width)              !! sum of ln growth [1]
      real(dp), dimension(lane_width) :: nrm, lnrm
      real(dp) :: s
      integer :: i
      call rk4_tangent_lanes_lc(c, h, q1, q2, w1, w2, u1, u2, v1, v2, e)
      do i = 1, lane_width
         nrm(i) = sqrt(u1(i)**2 + u2(i)**2 + v1(i)**2 + v2(i)**2)
         s = 1.0_dp/nrm(i)
         u1(i) = u1(i)*s; u2(i) = u2(i)*s; v1(i) = v1(i)*s; v2(i) = v2(i)*s
      end do
      call log_lanes(nrm, lnrm)
      lacc = lacc + lnrm
   end subroutine lyapunov_step_lanes

   include 'dpend_pendulum_lane_math.inc'
end module dpend_pendulum_tangent_lanes
