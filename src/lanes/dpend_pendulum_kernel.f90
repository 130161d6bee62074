!> The double pendulum's lane kernel: one RK4 step of `lane_width` double pendulums
!> at once (`rk4_lanes`), their accelerations and energies, for the sweeps' maps
!> (docs/sweep.md; the driver and results: dpend_pendulum_lanes; the tangent and
!> indicator steps: dpend_pendulum_tangent_lanes).
!>
!> Layout: structure of arrays over `lane_width` lanes (q1(W), q2(W), w1(W), w2(W)),
!> every loop runs over all W lanes so that gfortran vectorizes it. W = 16 is a
!> multiple of every vector width (2 doubles with SSE2, the default of fpm's release
!> profile; 4 with AVX2; 8 with AVX-512), so no loop has a remainder.
!>
!> Trigonometry: `rk4_lanes` and `rk4_tangent_fused_lanes` (the indicators' step)
!> carry sin and cos of both angles from step to step
!> (`lane_trig_t`); the RK4 stages and the new state take theirs from the step
!> start's by the addition formulas (as the scalar `sin_cos_near`), so a step
!> computes no sin/cos. Exact values, set when a lane is loaded and every
!> `resync_steps` steps, come from `sincos_lanes` / `sincos_exact` (our own
!> polynomial, no libm call, so it vectorizes without libmvec or -fno-math-errno).
!>
!> Reproducibility: every trajectory goes through exactly the same operations in
!> the same order whatever its lane, its block or the thread: lanes never mix,
!> every loop runs the full width (no scalar remainder), idle lanes hold a
!> harmless dummy state. Results are therefore bitwise independent of the number
!> of threads, the block size and the order in which lanes are refilled.
!>
!> The right-hand side is Lagrange's form of the equations of motion
!> (docs/physics.md) with d = q1 - q2, cos d and sin d built from sin q and cos q:
!>   M11 q̈1 + M12 q̈2 = -A cos q1 - k sin d q̇2²,
!>   M12 q̈1 + M22 q̈2 = -B cos q2 + k sin d q̇1²,
!> M11 = (m1/3 + m2) L1², M22 = m2 L2²/3, M12 = k cos d, k = m2 L1 L2/2,
!> A = (m1/2 + m2) g L1, B = (m2/2) g L2.

module dpend_pendulum_kernel
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, body_rod, body_constants
   use dpend_lane_batch, only: lane_width
   implicit none
   private
   public :: batch_coef_t, batch_coef, flip_energy_bounds, potential_range
   public :: lane_coef_t, lane_coef, set_lane_coef, lane_trig_t, set_lane_trig
   public :: rk4_lanes, energy_lanes, accel_lanes, accel_trig_lanes
   public :: sincos_lanes, sincos_near_lanes, sincos_exact_max, sincos_exact, sincos_stage_lanes
   ! the constants of the shared lane arithmetic (dpend_pendulum_lane_math.inc)
   public :: pi, half_pi, two_pi, inv_two_pi, two_over_pi, round_magic, pio2_1, pio2_2, pio2_2t
   public :: sin_p1, sin_p2, sin_p3, sin_p4, sin_p5, sin_p6
   public :: cos_p1, cos_p2, cos_p3, cos_p4, cos_p5, cos_p6, lane_bound, d_max

   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
   real(dp), parameter :: half_pi = 0.5_dp*pi, two_pi = 2.0_dp*pi, inv_two_pi = 1.0_dp/two_pi
   !> |x| up to which `sincos_lanes` reduces exactly enough (2^20 π/2 rad)
   real(dp), parameter :: sincos_exact_max = 1048576.0_dp*half_pi
   ! constants of `sincos_poly`
   real(dp), parameter :: two_over_pi = 6.36619772367581382433e-01_dp
   real(dp), parameter :: round_magic = 6755399441055744.0_dp  ! 1.5·2^52
   real(dp), parameter :: pio2_1 = 1.57079632673412561417e+00_dp   ! first 33 bits
   real(dp), parameter :: pio2_2 = 6.07710050630396597660e-11_dp   ! next 33 bits
   real(dp), parameter :: pio2_2t = 2.02226624879595063154e-21_dp  ! π/2 - pio2_1 - pio2_2
   real(dp), parameter :: sin_p1 = -1.66666666666666324348e-01_dp, &
                          sin_p2 = 8.33333333332248946124e-03_dp, &
                          sin_p3 = -1.98412698298579493134e-04_dp, &
                          sin_p4 = 2.75573137070700676789e-06_dp, &
                          sin_p5 = -2.50507602534068634195e-08_dp, &
                          sin_p6 = 1.58969099521155010221e-10_dp
   real(dp), parameter :: cos_p1 = 4.16666666666666019037e-02_dp, &
                          cos_p2 = -1.38888888888741095749e-03_dp, &
                          cos_p3 = 2.48015872894767294178e-05_dp, &
                          cos_p4 = -2.75573143513906633035e-07_dp, &
                          cos_p5 = 2.08757232129817482790e-09_dp, &
                          cos_p6 = -1.13596475577881948265e-11_dp
   !> A lane whose |q1| + |q2| + |q̇1| + |q̇2| exceeds this has run away: it ends with
   !> st_nonfinite, and the accelerations take the squares of the velocities clamped
   !> to its square (`wsq`), so that no step of the kernel overflows (accepted inputs
   !> stay below 1e9; the scalar integrators' bound, diverged_bound = 1e30, would let
   !> one RK4 step overflow here)
   real(dp), parameter :: lane_bound = 1.0e15_dp
   !> |d| up to which `sincos_near_lanes` uses the addition formulas [rad]
   real(dp), parameter :: d_max = 0.0625_dp

   !> Constants of the right-hand side, from `pendulum_t` [SI].
   type :: batch_coef_t
      real(dp) :: m11 = 0  !! (m1/3 + m2) L1² [kg m²]
      real(dp) :: m22 = 0  !! m2 L2²/3 [kg m²]
      real(dp) :: k = 0    !! m2 L1 L2/2 [kg m²]
      real(dp) :: ga = 0   !! A = (m1/2 + m2) g L1 [J]
      real(dp) :: gb = 0   !! B = (m2/2) g L2 [J]
      ! the same divided by k (`accel_trig`'s form: M12/k = cos d, no product by k)
      real(dp) :: m11k = 0  !! M11/k [1]
      real(dp) :: m22k = 0  !! M22/k [1]
      real(dp) :: detk = 0  !! M11 M22/k² [1]
      real(dp) :: gak = 0   !! A/k [1/s²]
      real(dp) :: gbk = 0   !! B/k [1/s²]
   end type batch_coef_t

   !> The constants of `batch_coef_t` lane by lane (structure of arrays):
   !> every lane its own pendulum, so that a sweep over parameters fills all lanes.
   !> The kernels take this form; those of `batch_coef_t` copy it into every lane.
   type :: lane_coef_t
      real(dp) :: m11(lane_width)   !! (m1/3 + m2) L1² [kg m²]
      real(dp) :: m22(lane_width)   !! m2 L2²/3 [kg m²]
      real(dp) :: k(lane_width)     !! m2 L1 L2/2 [kg m²]
      real(dp) :: ga(lane_width)    !! A [J]
      real(dp) :: gb(lane_width)    !! B [J]
      real(dp) :: m11k(lane_width)  !! M11/k [1]
      real(dp) :: m22k(lane_width)  !! M22/k [1]
      real(dp) :: detk(lane_width)  !! M11 M22/k² [1]
      real(dp) :: gak(lane_width)   !! A/k [1/s²]
      real(dp) :: gbk(lane_width)   !! B/k [1/s²]
   end type lane_coef_t

   !> sin and cos of both angles of every lane, carried by `rk4_lanes` and
   !> `rk4_tangent_fused_lanes` from step to step [1].
   type :: lane_trig_t
      real(dp) :: s1(lane_width) = 0  !! sin q1
      real(dp) :: c1(lane_width) = 1  !! cos q1
      real(dp) :: s2(lane_width) = 0  !! sin q2
      real(dp) :: c2(lane_width) = 1  !! cos q2
   end type lane_trig_t

   ! The kernels with each lane's own constants (`lane_coef_t`) or one pendulum in
   ! every lane (`batch_coef_t`, copied into the lanes: for the tests and callers of
   ! one pendulum)
   interface rk4_lanes
      module procedure rk4_lanes_lc, rk4_lanes_one
   end interface rk4_lanes
   interface accel_lanes
      module procedure accel_lanes_lc, accel_lanes_one
   end interface accel_lanes
   interface accel_trig_lanes
      module procedure accel_trig_lanes_lc, accel_trig_lanes_one
   end interface accel_trig_lanes
   interface energy_lanes
      module procedure energy_lanes_lc, energy_lanes_one
   end interface energy_lanes

contains

   !> The constants of the right-hand side.
   pure function batch_coef(par) result(c)
      type(pendulum_t), intent(in) :: par  !! parameters
      type(batch_coef_t) :: c
      real(dp) :: b(5)
      if (par%body == body_rod) then
         c%m11 = (par%m1/3.0_dp + par%m2)*par%l1**2
         c%m22 = par%m2*par%l2**2/3.0_dp
         c%k = 0.5_dp*par%m2*par%l1*par%l2
         c%ga = (0.5_dp*par%m1 + par%m2)*par%g*par%l1
         c%gb = 0.5_dp*par%m2*par%g*par%l2
      else   ! links of any mass distribution: the same kernels, other constants
         b = body_constants(par)
         c%m11 = b(1); c%m22 = b(2); c%k = b(3); c%ga = b(4); c%gb = b(5)
      end if
      ! the form divided by k needs k > 0: every accepted pendulum (dpend_limits:
      ! masses and lengths >= 1e-6)
      if (.not. (c%k > 0.0_dp)) error stop 'internal error: batch_coef needs m2 L1 L2 > 0'
      c%m11k = c%m11/c%k
      c%m22k = c%m22/c%k
      c%detk = c%m11k*c%m22k
      c%gak = c%ga/c%k
      c%gbk = c%gb/c%k
   end function batch_coef

   !> Least energy with which link 1, resp. link 2, can reach the upward vertical [J]
   !> (docs/sweep.md): with V = A sin q1 + B sin q2 and T >= 0, link 1 at the top
   !> needs E >= min over q2 of V(π/2, q2) = A - B, link 2 needs E >= B - A.
   pure function flip_energy_bounds(par) result(e)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp) :: e(2)
      type(batch_coef_t) :: c
      c = batch_coef(par)
      e = [c%ga - c%gb, c%gb - c%ga]
   end function flip_energy_bounds

   !> The range of the potential energy, V_max - V_min = 2 (A + B) [J]: the unit of
   !> the sweep's relative energy error (one unit for every initial condition of a
   !> sweep; not `dpend_pendulum`'s `energy_scale`, which depends on E(0)).
   pure real(dp) function potential_range(par)
      type(pendulum_t), intent(in) :: par  !! parameters
      type(batch_coef_t) :: c
      c = batch_coef(par)
      potential_range = 2.0_dp*(c%ga + c%gb)
   end function potential_range

   !> The constants `c` in every lane.
   pure function lane_coef(c) result(lc)
      type(batch_coef_t), intent(in) :: c  !! constants
      type(lane_coef_t) :: lc
      integer :: l
      do l = 1, lane_width
         call set_lane_coef(lc, l, c)
      end do
   end function lane_coef

   !> Set lane l's constants to `c`.
   pure subroutine set_lane_coef(lc, l, c)
      type(lane_coef_t), intent(inout) :: lc  !! the lanes' constants
      integer, intent(in) :: l                !! lane
      type(batch_coef_t), intent(in) :: c     !! its constants
      lc%m11(l) = c%m11; lc%m22(l) = c%m22; lc%k(l) = c%k; lc%ga(l) = c%ga; lc%gb(l) = c%gb
      lc%m11k(l) = c%m11k; lc%m22k(l) = c%m22k; lc%detk(l) = c%detk
      lc%gak(l) = c%gak; lc%gbk(l) = c%gbk
   end subroutine set_lane_coef

   !> `rk4_lanes` with the constants `c` in every lane.
   pure subroutine rk4_lanes_one(c, h, q1, q2, w1, w2, e, tr)
      type(batch_coef_t), intent(in) :: c                        !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      call rk4_lanes_lc(lane_coef(c), h, q1, q2, w1, w2, e, tr)
   end subroutine rk4_lanes_one

   !> `accel_lanes` with the constants `c` in every lane.
   pure subroutine accel_lanes_one(c, q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
      type(batch_coef_t), intent(in) :: c                       !! constants
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)    !! angles [rad]
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      real(dp), intent(out) :: a1(lane_width), a2(lane_width)   !! accelerations [rad/s²]
      real(dp), intent(out) :: s1(lane_width), c1(lane_width)   !! sin q1, cos q1
      real(dp), intent(out) :: s2(lane_width), c2(lane_width)   !! sin q2, cos q2
      call accel_lanes_lc(lane_coef(c), q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
   end subroutine accel_lanes_one

   !> `accel_trig_lanes` with the constants `c` in every lane.
   pure subroutine accel_trig_lanes_one(c, s1, c1, s2, c2, w1, w2, a1, a2)
      type(batch_coef_t), intent(in) :: c                       !! constants
      real(dp), intent(in) :: s1(lane_width), c1(lane_width)    !! sin q1, cos q1
      real(dp), intent(in) :: s2(lane_width), c2(lane_width)    !! sin q2, cos q2
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      real(dp), intent(out) :: a1(lane_width), a2(lane_width)   !! accelerations [rad/s²]
      call accel_trig_lanes_lc(lane_coef(c), s1, c1, s2, c2, w1, w2, a1, a2)
   end subroutine accel_trig_lanes_one

   !> `energy_lanes` with the constants `c` in every lane.
   pure subroutine energy_lanes_one(c, q1, q2, w1, w2, e)
      type(batch_coef_t), intent(in) :: c                     !! constants
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                  !! energy [J]
      call energy_lanes_lc(lane_coef(c), q1, q2, w1, w2, e)
   end subroutine energy_lanes_one

   !> The carried sin and cos of `rk4_lanes` set exactly (`sincos_lanes`).
   pure subroutine set_lane_trig(q1, q2, tr)
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      type(lane_trig_t), intent(out) :: tr                    !! sin, cos of q1, q2
      call trig_lanes(q1, q2, tr%s1, tr%c1, tr%s2, tr%c2)
   end subroutine set_lane_trig

   !> `sincos_add_stage` over the lanes (for the tests: the elemental procedure
   !> stays private, so that gcc inlines it into `rk4_lanes`' loop; a public one
   !> compiled with -fPIC is not inlined, and a call stops the vectorizer).
   pure subroutine sincos_stage_lanes(s0, c0, d, s, c)
      real(dp), intent(in) :: s0(lane_width), c0(lane_width)  !! sin x0, cos x0
      real(dp), intent(in) :: d(lane_width)                   !! offsets [rad], |d| <= d_max
      real(dp), intent(out) :: s(lane_width), c(lane_width)   !! sin(x0 + d), cos(x0 + d)
      integer :: i
      do i = 1, lane_width
         call sincos_add_stage(s0(i), c0(i), d(i), s(i), c(i))
      end do
   end subroutine sincos_stage_lanes

   !> Copy of `energy` (dpend_pendulum) for speed: SIMD over the lanes, through
   !> `energy_formula`, also used by the RK4 steps; test/test_copies.f90 compares them.
   !> Energy T + V of each lane [J].
   pure subroutine energy_lanes_lc(c, q1, q2, w1, w2, e)
      type(lane_coef_t), intent(in) :: c                      !! constants
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                  !! energy [J]
      real(dp) :: s1(lane_width), c1(lane_width), s2(lane_width), c2(lane_width)
      integer :: i
      call trig_lanes(q1, q2, s1, c1, s2, c2)
      do i = 1, lane_width
         e(i) = energy_formula(c, i, s1(i), c1(i), s2(i), c2(i), w1(i), w2(i))
      end do
   end subroutine energy_lanes_lc

   !> One classical RK4 step of size h on every lane; `e` is the energy of the state
   !> before the step [J] (it costs no extra sin/cos).
   !>
   !> Trigonometry: `tr` holds sin and cos of both angles of the state on entry, and
   !> of the new state on return, so that a step needs no sin/cos of its own: the
   !> three later stages' (`sincos_add_stage`) and the new state's (`sincos_add`)
   !> come from the step start's by the addition formulas. The caller sets `tr` exactly
   !> (`set_lane_trig`, or `sincos_exact` lane by lane) when it loads a lane, and again
   !> every so often (`integrate_batch`: every `resync_steps` steps of the lane; a lane
   !> on the fallback starts from exact values anyway): each carried step
   !> adds about one ulp of rounding, a random walk (test sweep/carried_trig_drift).
   !>
   !> The whole step of a lane is one loop body (the stages' values stay in vector
   !> registers; no lane array passes through memory between the stages): the
   !> stages' sines and cosines by `sincos_add_stage`, the accelerations by
   !> `accel_trig`.
   !> A lane outside that path's range (an offset |d| > `d_max` of a stage or of the
   !> new state from the step start) takes instead the result of `rk4_lanes_ref`, the
   !> same step through the lane routines with their exact fallbacks. Which path a
   !> lane takes depends on its own values only, so the results stay bitwise
   !> independent of the other lanes. On entry |q̇| <= `lane_bound` (`wsq`:
   !> `integrate_batch` ends a lane beyond).
   pure subroutine rk4_lanes_lc(c, h, q1, q2, w1, w2, e, tr)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      integer, parameter :: half = lane_width/2
      real(dp), dimension(lane_width) :: p1, p2, pw1, pw2, off
      real(dp) :: s1a_1, c1a_1, s2a_1, c2a_1, s1_1, c1_1, s2_1, c2_1, d1_1, d2_1, dc1_1, dc2_1
      real(dp) :: s1a_2, c1a_2, s2a_2, c2a_2, s1_2, c1_2, s2_2, c2_2, d1_2, d2_2, dc1_2, dc2_2
      real(dp) :: ka1_1, ka2_1, kb1_1, kb2_1, kc1_1, kc2_1, kd1_1, kd2_1, sk1_1, sk2_1
      real(dp) :: ka1_2, ka2_2, kb1_2, kb2_2, kc1_2, kc2_2, kd1_2, kd2_2, sk1_2, sk2_2
      real(dp) :: vb1_1, vb2_1, vc1_1, vc2_1, vd1_1, vd2_1, sv1_1, sv2_1
      real(dp) :: vb1_2, vb2_2, vc1_2, vc2_2, vd1_2, vd2_2, sv1_2, sv2_2
      real(dp) :: hh, h6, n_off
      integer :: i, j
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      n_off = 0
      ! (the offsets are clamped to d_max and the velocities' squares to lane_bound²: a lane
      ! beyond takes the reference step or ends, and its discarded values here stay
      ! bounded; off counts |d - clamped d|, > 0 or NaN for a lane beyond)
      ! lanes i and i + half side by side: two independent chains of stages in each
      ! vector iteration, so that one's divisions overlap the other's work
      do i = 1, half
         j = i + half
         ! stage a: the step start
         p1(i) = q1(i); p2(i) = q2(i); pw1(i) = w1(i); pw2(i) = w2(i)
         s1a_1 = tr%s1(i); c1a_1 = tr%c1(i); s2a_1 = tr%s2(i); c2a_1 = tr%c2(i)
         call accel_trig(c, i, s1a_1, c1a_1, s2a_1, c2a_1, wsq(w1(i)), wsq(w2(i)), ka1_1, ka2_1)
         e(i) = energy_formula(c, i, s1a_1, c1a_1, s2a_1, c2a_1, w1(i), w2(i))
         d1_1 = (q1(i) + hh*w1(i)) - q1(i); d2_1 = (q2(i) + hh*w2(i)) - q2(i)
         vb1_1 = w1(i) + hh*ka1_1; vb2_1 = w2(i) + hh*ka2_1
         p1(j) = q1(j); p2(j) = q2(j); pw1(j) = w1(j); pw2(j) = w2(j)
         s1a_2 = tr%s1(j); c1a_2 = tr%c1(j); s2a_2 = tr%s2(j); c2a_2 = tr%c2(j)
         call accel_trig(c, j, s1a_2, c1a_2, s2a_2, c2a_2, wsq(w1(j)), wsq(w2(j)), ka1_2, ka2_2)
         e(j) = energy_formula(c, j, s1a_2, c1a_2, s2a_2, c2a_2, w1(j), w2(j))
         d1_2 = (q1(j) + hh*w1(j)) - q1(j); d2_2 = (q2(j) + hh*w2(j)) - q2(j)
         vb1_2 = w1(j) + hh*ka1_2; vb2_2 = w2(j) + hh*ka2_2
         ! stage b
         dc1_1 = dclamp(d1_1); dc2_1 = dclamp(d2_1)
         off(i) = abs(d1_1 - dc1_1) + abs(d2_1 - dc2_1)
         call sincos_add_stage(s1a_1, c1a_1, dc1_1, s1_1, c1_1)
         call sincos_add_stage(s2a_1, c2a_1, dc2_1, s2_1, c2_1)
         call accel_trig(c, i, s1_1, c1_1, s2_1, c2_1, wsq(vb1_1), wsq(vb2_1), kb1_1, kb2_1)
         d1_1 = (q1(i) + hh*vb1_1) - q1(i); d2_1 = (q2(i) + hh*vb2_1) - q2(i)
         vc1_1 = w1(i) + hh*kb1_1; vc2_1 = w2(i) + hh*kb2_1
         sv1_1 = vb1_1 + vc1_1; sv2_1 = vb2_1 + vc2_1
         dc1_2 = dclamp(d1_2); dc2_2 = dclamp(d2_2)
         off(j) = abs(d1_2 - dc1_2) + abs(d2_2 - dc2_2)
         call sincos_add_stage(s1a_2, c1a_2, dc1_2, s1_2, c1_2)
         call sincos_add_stage(s2a_2, c2a_2, dc2_2, s2_2, c2_2)
         call accel_trig(c, j, s1_2, c1_2, s2_2, c2_2, wsq(vb1_2), wsq(vb2_2), kb1_2, kb2_2)
         d1_2 = (q1(j) + hh*vb1_2) - q1(j); d2_2 = (q2(j) + hh*vb2_2) - q2(j)
         vc1_2 = w1(j) + hh*kb1_2; vc2_2 = w2(j) + hh*kb2_2
         sv1_2 = vb1_2 + vc1_2; sv2_2 = vb2_2 + vc2_2
         ! stage c
         dc1_1 = dclamp(d1_1); dc2_1 = dclamp(d2_1)
         off(i) = off(i) + (abs(d1_1 - dc1_1) + abs(d2_1 - dc2_1))
         call sincos_add_stage(s1a_1, c1a_1, dc1_1, s1_1, c1_1)
         call sincos_add_stage(s2a_1, c2a_1, dc2_1, s2_1, c2_1)
         call accel_trig(c, i, s1_1, c1_1, s2_1, c2_1, wsq(vc1_1), wsq(vc2_1), kc1_1, kc2_1)
         d1_1 = (q1(i) + h*vc1_1) - q1(i); d2_1 = (q2(i) + h*vc2_1) - q2(i)
         vd1_1 = w1(i) + h*kc1_1; vd2_1 = w2(i) + h*kc2_1
         sk1_1 = kb1_1 + kc1_1; sk2_1 = kb2_1 + kc2_1
         sv1_1 = (w1(i) + 2.0_dp*sv1_1) + vd1_1; sv2_1 = (w2(i) + 2.0_dp*sv2_1) + vd2_1
         dc1_2 = dclamp(d1_2); dc2_2 = dclamp(d2_2)
         off(j) = off(j) + (abs(d1_2 - dc1_2) + abs(d2_2 - dc2_2))
         call sincos_add_stage(s1a_2, c1a_2, dc1_2, s1_2, c1_2)
         call sincos_add_stage(s2a_2, c2a_2, dc2_2, s2_2, c2_2)
         call accel_trig(c, j, s1_2, c1_2, s2_2, c2_2, wsq(vc1_2), wsq(vc2_2), kc1_2, kc2_2)
         d1_2 = (q1(j) + h*vc1_2) - q1(j); d2_2 = (q2(j) + h*vc2_2) - q2(j)
         vd1_2 = w1(j) + h*kc1_2; vd2_2 = w2(j) + h*kc2_2
         sk1_2 = kb1_2 + kc1_2; sk2_2 = kb2_2 + kc2_2
         sv1_2 = (w1(j) + 2.0_dp*sv1_2) + vd1_2; sv2_2 = (w2(j) + 2.0_dp*sv2_2) + vd2_2
         ! stage d
         dc1_1 = dclamp(d1_1); dc2_1 = dclamp(d2_1)
         off(i) = off(i) + (abs(d1_1 - dc1_1) + abs(d2_1 - dc2_1))
         call sincos_add_stage(s1a_1, c1a_1, dc1_1, s1_1, c1_1)
         call sincos_add_stage(s2a_1, c2a_1, dc2_1, s2_1, c2_1)
         call accel_trig(c, i, s1_1, c1_1, s2_1, c2_1, wsq(vd1_1), wsq(vd2_1), kd1_1, kd2_1)
         d1_1 = h6*sv1_1; d2_1 = h6*sv2_1
         w1(i) = w1(i) + h6*((ka1_1 + 2.0_dp*sk1_1) + kd1_1)
         w2(i) = w2(i) + h6*((ka2_1 + 2.0_dp*sk2_1) + kd2_1)
         dc1_2 = dclamp(d1_2); dc2_2 = dclamp(d2_2)
         off(j) = off(j) + (abs(d1_2 - dc1_2) + abs(d2_2 - dc2_2))
         call sincos_add_stage(s1a_2, c1a_2, dc1_2, s1_2, c1_2)
         call sincos_add_stage(s2a_2, c2a_2, dc2_2, s2_2, c2_2)
         call accel_trig(c, j, s1_2, c1_2, s2_2, c2_2, wsq(vd1_2), wsq(vd2_2), kd1_2, kd2_2)
         d1_2 = h6*sv1_2; d2_2 = h6*sv2_2
         w1(j) = w1(j) + h6*((ka1_2 + 2.0_dp*sk1_2) + kd1_2)
         w2(j) = w2(j) + h6*((ka2_2 + 2.0_dp*sk2_2) + kd2_2)
         ! the new state and its sines and cosines
         sv1_1 = q1(i) + d1_1; sv2_1 = q2(i) + d2_1
         d1_1 = sv1_1 - q1(i); d2_1 = sv2_1 - q2(i)
         q1(i) = sv1_1; q2(i) = sv2_1
         dc1_1 = dclamp(d1_1); dc2_1 = dclamp(d2_1)
         off(i) = off(i) + (abs(d1_1 - dc1_1) + abs(d2_1 - dc2_1))
         call sincos_add(s1a_1, c1a_1, dc1_1, tr%s1(i), tr%c1(i))
         call sincos_add(s2a_1, c2a_1, dc2_1, tr%s2(i), tr%c2(i))
         sv1_2 = q1(j) + d1_2; sv2_2 = q2(j) + d2_2
         d1_2 = sv1_2 - q1(j); d2_2 = sv2_2 - q2(j)
         q1(j) = sv1_2; q2(j) = sv2_2
         dc1_2 = dclamp(d1_2); dc2_2 = dclamp(d2_2)
         off(j) = off(j) + (abs(d1_2 - dc1_2) + abs(d2_2 - dc2_2))
         call sincos_add(s1a_2, c1a_2, dc1_2, tr%s1(j), tr%c1(j))
         call sincos_add(s2a_2, c2a_2, dc2_2, tr%s2(j), tr%c2(j))
         n_off = n_off + (off(i) + off(j))
      end do
      if (n_off == 0.0_dp) return   ! (a NaN offset fails its check)
      call rk4_lanes_fallback(c, h, off, p1, p2, pw1, pw2, q1, q2, w1, w2, e, tr)
   end subroutine rk4_lanes_lc

   !> The lanes of `rk4_lanes` with off /= 0 take the step of `rk4_lanes_ref` from
   !> (p1, p2, pw1, pw2), starting from exact sin and cos; the other lanes keep their
   !> values. (Its own procedure: its locals are set up only when a lane needs it.)
   pure subroutine rk4_lanes_fallback(c, h, off, p1, p2, pw1, pw2, q1, q2, w1, w2, e, tr)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(in) :: off(lane_width)                    !! 0: the lane's step holds
      real(dp), intent(in) :: p1(lane_width), p2(lane_width)     !! step start [rad]
      real(dp), intent(in) :: pw1(lane_width), pw2(lane_width)   !! step start [rad/s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! new angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! new velocities [rad/s]
      real(dp), intent(inout) :: e(lane_width)                   !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      real(dp), dimension(lane_width) :: r1, r2, rw1, rw2, re
      type(lane_trig_t) :: rtr
      integer :: i
      r1 = p1; r2 = p2; rw1 = pw1; rw2 = pw2
      call set_lane_trig(r1, r2, rtr)
      call rk4_lanes_ref(c, h, r1, r2, rw1, rw2, re, rtr)
      do i = 1, lane_width
         if (.not. (off(i) == 0.0_dp)) then
            q1(i) = r1(i); q2(i) = r2(i); w1(i) = rw1(i); w2(i) = rw2(i); e(i) = re(i)
            tr%s1(i) = rtr%s1(i); tr%c1(i) = rtr%c1(i)
            tr%s2(i) = rtr%s2(i); tr%c2(i) = rtr%c2(i)
         end if
      end do
   end subroutine rk4_lanes_fallback

   !> The RK4 step of `rk4_lanes` through the lane routines, stage by stage, with the
   !> exact fallbacks of `sincos_near_lanes` (a lane whose offset exceeds `d_max`
   !> takes the exact sin and cos of that angle): the path of the lanes that
   !> `rk4_lanes`' fused loop does not cover. `tr` as in `rk4_lanes`.
   pure subroutine rk4_lanes_ref(c, h, q1, q2, w1, w2, e, tr)
      type(lane_coef_t), intent(in) :: c                         !! constants
      real(dp), intent(in) :: h                                  !! step [s]
      real(dp), intent(inout) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(inout) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                     !! energy before [J]
      type(lane_trig_t), intent(inout) :: tr                     !! sin, cos of q1, q2
      real(dp), dimension(lane_width) :: s1, c1, s2, c2, x1, x2, y1, y2
      real(dp), dimension(lane_width) :: ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2
      real(dp), dimension(lane_width) :: vb1, vb2, vc1, vc2, vd1, vd2
      real(dp) :: hh, h6
      integer :: i
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      call accel_trig_lanes(c, tr%s1, tr%c1, tr%s2, tr%c2, w1, w2, ka1, ka2)
      do i = 1, lane_width
         e(i) = energy_formula(c, i, tr%s1(i), tr%c1(i), tr%s2(i), tr%c2(i), w1(i), w2(i))
         x1(i) = q1(i) + hh*w1(i); x2(i) = q2(i) + hh*w2(i)
         vb1(i) = w1(i) + hh*ka1(i); vb2(i) = w2(i) + hh*ka2(i)
      end do
      call stage_trig_lanes(q1, q2, tr, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vb1, vb2, kb1, kb2)
      do i = 1, lane_width
         x1(i) = q1(i) + hh*vb1(i); x2(i) = q2(i) + hh*vb2(i)
         vc1(i) = w1(i) + hh*kb1(i); vc2(i) = w2(i) + hh*kb2(i)
      end do
      call stage_trig_lanes(q1, q2, tr, x1, x2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vc1, vc2, kc1, kc2)
      do i = 1, lane_width
         y1(i) = q1(i) + h*vc1(i); y2(i) = q2(i) + h*vc2(i)
         vd1(i) = w1(i) + h*kc1(i); vd2(i) = w2(i) + h*kc2(i)
      end do
      call stage_trig_lanes(q1, q2, tr, y1, y2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, vd1, vd2, kd1, kd2)
      do i = 1, lane_width
         y1(i) = q1(i) + h6*(w1(i) + 2.0_dp*(vb1(i) + vc1(i)) + vd1(i))
         y2(i) = q2(i) + h6*(w2(i) + 2.0_dp*(vb2(i) + vc2(i)) + vd2(i))
         w1(i) = w1(i) + h6*(ka1(i) + 2.0_dp*(kb1(i) + kc1(i)) + kd1(i))
         w2(i) = w2(i) + h6*(ka2(i) + 2.0_dp*(kb2(i) + kc2(i)) + kd2(i))
      end do
      call stage_trig_lanes(q1, q2, tr, y1, y2, s1, c1, s2, c2)
      q1 = y1; q2 = y2
      tr%s1 = s1; tr%c1 = c1; tr%s2 = s2; tr%c2 = c2
   end subroutine rk4_lanes_ref

   !> sin x and cos x of one lane as `sincos_lanes` gives them: `sincos_poly` for
   !> |x| <= `sincos_exact_max`, the intrinsic beyond (and for NaN).
   pure elemental subroutine sincos_exact(x, s, c)
      real(dp), intent(in) :: x   !! angle [rad]
      real(dp), intent(out) :: s  !! sin x
      real(dp), intent(out) :: c  !! cos x
      if (abs(x) <= sincos_exact_max) then
         call sincos_poly(x, s, c)
      else
         s = sin(x)
         c = cos(x)
      end if
   end subroutine sincos_exact

   include 'dpend_pendulum_lane_math.inc'
end module dpend_pendulum_kernel
