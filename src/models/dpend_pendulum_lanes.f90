!> Batch RK4 kernel: many trajectories of the double pendulum at once, for sweeps
!> over initial conditions (docs/sweep.md).
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
module dpend_pendulum_lanes
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, body_rod, body_constants
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   use dpend_indicator_math, only: initial_vectors, sali, gali
   implicit none
   private
   public :: lane_width, batch_coef_t, batch_coef, flip_energy_bounds, potential_range
   public :: lane_coef_t, lane_coef, set_lane_coef, rk4_tangent2_lanes, rk4_tangent_fused_lanes
   public :: rk4_lanes, rk4_tangent_lanes, energy_lanes, indicator_step_lanes, megno_step_lanes
   public :: accel_lanes, tangent_accel_lanes, accel_trig_lanes
   public :: sincos_lanes, sincos_near_lanes, sincos_exact_max, sincos_exact, log_lanes
   public :: lane_trig_t, set_lane_trig, resync_steps, sincos_stage_lanes
   public :: batch_options_t, batch_result_t, integrate_batch
   public :: stop_both, stop_either, stop_end
   public :: st_missing, st_end, st_flipped, st_cannot_flip, st_nonfinite

   integer, parameter :: lane_width = 16  !! trajectories per lane set (two AVX-512 vectors)

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
   !> Margin of the sweep's angle windows [rad]: far above the rounding of
   !> (q - π/2)/(2π) at the largest accepted angles (1e6 rad: ~1e-10)
   real(dp), parameter :: window_margin = 1.0e-6_dp
   !> |d| up to which `sincos_near_lanes` uses the addition formulas [rad]
   real(dp), parameter :: d_max = 0.0625_dp
   !> Steps of a lane after which `integrate_batch` sets its carried sin and cos
   !> (`rk4_lanes`, `rk4_tangent_fused_lanes`) exactly again: the carried values'
   !> rounding, a random walk of about one ulp per step, stays near sqrt(1024) ulp
   integer, parameter :: resync_steps = 1024

   ! stop rules: when a trajectory ends before t_end
   integer, parameter :: stop_both = 1    !! when every link that can flip has flipped
   integer, parameter :: stop_either = 2  !! at the first flip of either link
   integer, parameter :: stop_end = 3     !! never: always run to t_end

   ! status of an initial condition (0 is the fill value of the files: not computed)
   integer, parameter :: st_missing = 0      !! not computed yet
   integer, parameter :: st_end = 1          !! integrated to t_end
   integer, parameter :: st_flipped = 2      !! stopped early by the stop rule after a flip
   integer, parameter :: st_cannot_flip = 3  !! energy below the flip bound (not integrated
                                             !! unless the Lyapunov exponent is wanted)
   integer, parameter :: st_nonfinite = 4    !! the state became NaN or Inf

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

   !> How to integrate a batch.
   type :: batch_options_t
      real(dp) :: h = 1e-3_dp          !! step [s]
      integer(i8) :: n_steps = 0       !! steps from t = 0 to t_end (t_end = n_steps h)
      integer :: stop_rule = stop_both !! stop_both, stop_either or stop_end
      logical :: lyapunov = .false.    !! also the largest Lyapunov exponent (runs to t_end)
      logical :: skip_cannot_flip = .true.  !! leave out initial conditions below the
                                            !! flip energy bounds (always integrated with
                                            !! the Lyapunov exponent)
      !> Deviation vectors of the fast indicators (dpend_indicator_math); runs to
      !> t_end like the Lyapunov exponent (exclusive with it): 0 none, 1 MEGNO and
      !> FLI, 2 also SALI and GALI_2
      integer :: vectors = 0
   end type batch_options_t

   !> Reduced results per initial condition (arrays of size n). NaN marks "none".
   type :: batch_result_t
      integer :: n = 0                          !! number of initial conditions
      real(dp), allocatable :: t_flip1(:)       !! first flip of link 1 [s], NaN: none
      real(dp), allocatable :: t_flip2(:)       !! first flip of link 2 [s], NaN: none
      real(dp), allocatable :: t_flip(:)        !! first flip of either link [s], NaN: none
      !> (N, n) first flip of every link [s], NaN: none; only from the per-trajectory
      !> path of N links (dpend_trajectory_batch), where t_flip1 and t_flip2 are unused
      real(dp), allocatable :: t_flip_link(:, :)
      real(dp), allocatable :: energy0(:)       !! initial energy E(0) [J]
      real(dp), allocatable :: energy_error(:)  !! max |E(t) - E(0)| / potential_range [1]
      real(dp), allocatable :: t_stop(:)        !! time integrated to [s]
      real(dp), allocatable :: final(:, :)      !! (2N, n) state at t_stop [rad, rad/s]
      real(dp), allocatable :: lyapunov(:)      !! largest Lyapunov exponent [1/s], NaN: off
      integer, allocatable :: status(:)         !! st_* code
      integer, allocatable :: steps(:)          !! RK4 steps taken (4 evaluations each)
      !> Fast indicators at t_stop (NaN: not computed) of deviation vector 1: <Y> the
      !> running mean of MEGNO, Y itself, FLI = ln |δ|; of vectors 1 and 2: SALI,
      !> GALI_2 [1]
      real(dp), allocatable :: megno(:), megno_y(:), fli(:), sali(:), gali2(:)
   end type batch_result_t

   ! The kernels with each lane's own constants (`lane_coef_t`) or one pendulum in
   ! every lane (`batch_coef_t`, copied into the lanes: for the tests and callers of
   ! one pendulum)
   interface rk4_lanes
      module procedure rk4_lanes_lc, rk4_lanes_one
   end interface rk4_lanes
   interface rk4_tangent_lanes
      module procedure rk4_tangent_lanes_lc, rk4_tangent_lanes_one
   end interface rk4_tangent_lanes
   interface indicator_step_lanes
      module procedure indicator_step_lanes_lc, indicator_step_lanes_one
   end interface indicator_step_lanes
   interface accel_lanes
      module procedure accel_lanes_lc, accel_lanes_one
   end interface accel_lanes
   interface accel_trig_lanes
      module procedure accel_trig_lanes_lc, accel_trig_lanes_one
   end interface accel_trig_lanes
   interface tangent_accel_lanes
      module procedure tangent_accel_lanes_lc, tangent_accel_lanes_one
   end interface tangent_accel_lanes
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

   !> `energy_lanes` with the constants `c` in every lane.
   pure subroutine energy_lanes_one(c, q1, q2, w1, w2, e)
      type(batch_coef_t), intent(in) :: c                     !! constants
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)  !! velocities [rad/s]
      real(dp), intent(out) :: e(lane_width)                  !! energy [J]
      call energy_lanes_lc(lane_coef(c), q1, q2, w1, w2, e)
   end subroutine energy_lanes_one

   !> sin and cos of both angles (`sincos_lanes`).
   pure subroutine trig_lanes(q1, q2, s1, c1, s2, c2)
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)   !! angles [rad]
      real(dp), intent(out) :: s1(lane_width), c1(lane_width)  !! sin q1, cos q1
      real(dp), intent(out) :: s2(lane_width), c2(lane_width)  !! sin q2, cos q2
      call sincos_lanes(q1, s1, c1)
      call sincos_lanes(q2, s2, c2)
   end subroutine trig_lanes

   !> sin x and cos x of every lane, our own vectorizable implementation (no libm
   !> call in the loop, so that any build vectorizes it, with or without libmvec
   !> and -fno-math-errno). Argument reduction x = n π/2 + r, |r| <= π/4, by
   !> Cody–Waite with π/2 in three parts (33 + 33 + 53 bits: n p1 and n p2 exact for
   !> |n| < 2^20), the nearest integer n by the 1.5·2^52 rounding trick; then fdlibm's
   !> minimax polynomials of sin and cos on [-π/4, π/4] (error < 2^-58) and the
   !> quadrant n mod 4 by exact arithmetic. Accurate to 2-3 ulp for |x| <= `sincos_exact_max`
   !> (= 2^20 π/2, above dpend_limits' max_angle = 1e6 rad; test/test_sweep.f90
   !> checks it against the intrinsic); lanes beyond it (and NaN/Inf) take the
   !> intrinsic sin and cos, lane by lane.
   pure subroutine sincos_lanes(x, s, c)
      real(dp), intent(in) :: x(lane_width)   !! angles [rad]
      real(dp), intent(out) :: s(lane_width)  !! sin x
      real(dp), intent(out) :: c(lane_width)  !! cos x
      real(dp) :: n_near
      integer :: i
      do i = 1, lane_width
         call sincos_poly(x(i), s(i), c(i))
      end do
      n_near = 0   ! a count, not a logical .or.: this form vectorizes
      do i = 1, lane_width
         n_near = n_near + merge(1.0_dp, 0.0_dp, abs(x(i)) <= sincos_exact_max)
      end do
      if (n_near == lane_width) return
      do i = 1, lane_width
         if (.not. (abs(x(i)) <= sincos_exact_max)) then
            s(i) = sin(x(i))
            c(i) = cos(x(i))
         end if
      end do
   end subroutine sincos_lanes

   !> One lane of `sincos_lanes` for |x| <= `sincos_exact_max` (clamped beyond): the
   !> reduction and polynomials described there. Elemental and private, so that gcc
   !> inlines it into the vectorized loop of `sincos_lanes`.
   pure elemental subroutine sincos_poly(x, s, c)
      real(dp), intent(in) :: x   !! angle [rad]
      real(dp), intent(out) :: s  !! sin x
      real(dp), intent(out) :: c  !! cos x
      real(dp) :: xi, fn, fq, fo, fh, r, z, sr, cr, hz, wc, sa, ca
      xi = min(max(x, -sincos_exact_max), sincos_exact_max)  ! far lanes: below
      fn = (xi*two_over_pi + round_magic) - round_magic        ! nearest integer
      r = ((xi - fn*pio2_1) - fn*pio2_2) - fn*pio2_2t          ! x - n π/2
      ! quadrant by exact arithmetic, no compare (compares and merges would stop the
      ! vectorizer without -fno-trapping-math): j = n mod 4, odd = j mod 2, hi = j >= 2
      fq = fn - 4.0_dp*((0.25_dp*(fn - 1.5_dp) + round_magic) - round_magic)
      fo = fq - 2.0_dp*((0.5_dp*(fq - 0.5_dp) + round_magic) - round_magic)
      fh = 0.5_dp*(fq - fo)
      z = r*r
      sr = r + r*z*(sin_p1 + z*(sin_p2 + z*(sin_p3 + z*(sin_p4 + z*(sin_p5 + z*sin_p6)))))
      hz = 0.5_dp*z
      wc = 1.0_dp - hz
      cr = wc + (((1.0_dp - wc) - hz) &
                 + z*z*(cos_p1 + z*(cos_p2 + z*(cos_p3 + z*(cos_p4 + z*(cos_p5 + z*cos_p6))))))
      ! j = 0: (sr, cr); 1: (cr, -sr); 2: (-sr, -cr); 3: (-cr, sr); exact products
      sa = fo*cr + (1.0_dp - fo)*sr
      ca = fo*sr + (1.0_dp - fo)*cr
      s = (1.0_dp - 2.0_dp*fh)*sa
      c = (1.0_dp - 2.0_dp*(fh - fo)**2)*ca
   end subroutine sincos_poly

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

   !> The carried sin and cos of `rk4_lanes` set exactly (`sincos_lanes`).
   pure subroutine set_lane_trig(q1, q2, tr)
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)  !! angles [rad]
      type(lane_trig_t), intent(out) :: tr                    !! sin, cos of q1, q2
      call trig_lanes(q1, q2, tr%s1, tr%c1, tr%s2, tr%c2)
   end subroutine set_lane_trig

   !> The lanes' form of `sin_cos_near_impl` (dpend_pendulum), SIMD over the lanes:
   !> sin and cos of x = x0 + d from those of x0 by the addition formulas, with the
   !> Taylor polynomials of sin d (to d⁹) and cos d - 1 (to d⁸), whose remainders are
   !> below 1e-21 and 3e-19 for |d| <= 1/16 (RK4 stages of the classic map have
   !> |d| <= h |q̇| ~ 0.04 at most). A lane with |d| > 1/16 takes `sincos_lanes(x)`
   !> instead (only its own value: the lanes never mix).
   pure subroutine sincos_near_lanes(s0, c0, x, d, s, c)
      real(dp), intent(in) :: s0(lane_width), c0(lane_width)  !! sin x0, cos x0
      real(dp), intent(in) :: x(lane_width)                   !! angles [rad]
      real(dp), intent(in) :: d(lane_width)                   !! x - x0 [rad]
      real(dp), intent(out) :: s(lane_width), c(lane_width)   !! sin x, cos x
      real(dp) :: sf(lane_width), cf(lane_width), n_near
      integer :: i
      do i = 1, lane_width
         call sincos_add(s0(i), c0(i), d(i), s(i), c(i))
      end do
      n_near = 0
      do i = 1, lane_width
         n_near = n_near + merge(1.0_dp, 0.0_dp, abs(d(i)) <= d_max)
      end do
      if (n_near == lane_width) return
      call sincos_lanes(x, sf, cf)
      do i = 1, lane_width
         if (.not. (abs(d(i)) <= d_max)) then
            s(i) = sf(i)
            c(i) = cf(i)
         end if
      end do
   end subroutine sincos_near_lanes

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

   !> `sincos_add` with shorter polynomials, for the RK4 stages of `rk4_lanes`, whose
   !> values are not carried to the next step: sin d to d⁷ and cos d - 1 to d⁶,
   !> Chebyshev-economized on |d| <= 1/16 (scripts/reference/stage_poly.py), within 1.3e-18
   !> and 1.8e-16 of sin d and cos d - 1 there (sincos_add: 3e-21 and 3e-19).
   pure elemental subroutine sincos_add_stage(s0, c0, d, s, c)
      real(dp), intent(in) :: s0, c0  !! sin x0, cos x0
      real(dp), intent(in) :: d       !! offset [rad], |d| <= `d_max`
      real(dp), intent(out) :: s, c   !! sin(x0 + d), cos(x0 + d)
      real(dp), parameter :: a3 = -1.66666666666661522633e-01_dp, &
                             a5 = 8.33333330968069607714e-03_dp, &
                             a7 = -1.98396551545965599316e-04_dp, &
                             b2 = -4.99999999999953814722e-01_dp, &
                             b4 = 4.16666664537929387624e-02_dp, &
                             b6 = -1.38874356708829365011e-03_dp
      real(dp) :: d2, sd, cm1
      d2 = d*d
      sd = d + d*d2*(a3 + d2*(a5 + d2*a7))
      cm1 = d2*(b2 + d2*(b4 + d2*b6))
      s = s0 + (s0*cm1 + c0*sd)
      c = c0 + (c0*cm1 - s0*sd)
   end subroutine sincos_add_stage

   !> One lane of `sincos_near_lanes` without its check of |d|: sin and cos of x0 + d
   !> from s0 = sin x0, c0 = cos x0 by the addition formulas and the Taylor
   !> polynomials of sin d and cos d - 1 (accurate for |d| <= `d_max`).
   pure elemental subroutine sincos_add(s0, c0, d, s, c)
      real(dp), intent(in) :: s0, c0  !! sin x0, cos x0
      real(dp), intent(in) :: d       !! offset [rad]
      real(dp), intent(out) :: s, c   !! sin(x0 + d), cos(x0 + d)
      real(dp) :: d2, sd, cm1
      d2 = d*d
      sd = d*(1.0_dp + d2*(-1.0_dp/6.0_dp + d2*(1.0_dp/120.0_dp + d2*(-1.0_dp/5040.0_dp &
           + d2*(1.0_dp/362880.0_dp)))))
      cm1 = d2*(-0.5_dp + d2*(1.0_dp/24.0_dp + d2*(-1.0_dp/720.0_dp + d2*(1.0_dp/40320.0_dp))))
      s = s0 + (s0*cm1 + c0*sd)
      c = c0 + (c0*cm1 - s0*sd)
   end subroutine sincos_add

   !> sin and cos of the stage angles (x1, x2) from those of the step start (q1, q2)
   !> (`sincos_near_lanes`).
   pure subroutine stage_trig_lanes(q1, q2, tr, x1, x2, s1, c1, s2, c2)
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)    !! step start [rad]
      type(lane_trig_t), intent(in) :: tr                       !! sin, cos of q1, q2
      real(dp), intent(in) :: x1(lane_width), x2(lane_width)    !! stage angles [rad]
      real(dp), intent(out) :: s1(lane_width), c1(lane_width)   !! sin x1, cos x1
      real(dp), intent(out) :: s2(lane_width), c2(lane_width)   !! sin x2, cos x2
      real(dp) :: d1(lane_width), d2(lane_width)
      integer :: i
      do i = 1, lane_width
         d1(i) = x1(i) - q1(i)
         d2(i) = x2(i) - q2(i)
      end do
      call sincos_near_lanes(tr%s1, tr%c1, x1, d1, s1, c1)
      call sincos_near_lanes(tr%s2, tr%c2, x2, d2, s2, c2)
   end subroutine stage_trig_lanes

   !> Copy of `qddot_lagrange` (dpend_pendulum) for speed: SIMD over the lanes, with
   !> cos and sin of q1 - q2 by the subtraction formulas; test/test_copies.f90
   !> compares them.
   !> Angular accelerations at (q, q̇) and the trigonometric values used [rad/s²].
   pure subroutine accel_lanes_lc(c, q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
      type(lane_coef_t), intent(in) :: c                        !! constants
      real(dp), intent(in) :: q1(lane_width), q2(lane_width)    !! angles [rad]
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      real(dp), intent(out) :: a1(lane_width), a2(lane_width)   !! accelerations [rad/s²]
      real(dp), intent(out) :: s1(lane_width), c1(lane_width)   !! sin q1, cos q1
      real(dp), intent(out) :: s2(lane_width), c2(lane_width)   !! sin q2, cos q2
      call trig_lanes(q1, q2, s1, c1, s2, c2)
      call accel_trig_lanes(c, s1, c1, s2, c2, w1, w2, a1, a2)
   end subroutine accel_lanes_lc

   !> The accelerations of `accel_lanes` from given sin and cos of the angles.
   pure subroutine accel_trig_lanes_lc(c, s1, c1, s2, c2, w1, w2, a1, a2)
      type(lane_coef_t), intent(in) :: c                        !! constants
      real(dp), intent(in) :: s1(lane_width), c1(lane_width)    !! sin q1, cos q1
      real(dp), intent(in) :: s2(lane_width), c2(lane_width)    !! sin q2, cos q2
      real(dp), intent(in) :: w1(lane_width), w2(lane_width)    !! velocities [rad/s]
      real(dp), intent(out) :: a1(lane_width), a2(lane_width)   !! accelerations [rad/s²]
      integer :: i
      do i = 1, lane_width
         call accel_trig(c, i, s1(i), c1(i), s2(i), c2(i), wsq(w1(i)), wsq(w2(i)), a1(i), a2(i))
      end do
   end subroutine accel_trig_lanes_lc

   !> Lane l of `accel_trig_lanes`, from the squares of the velocities (`wsq`).
   pure subroutine accel_trig(c, l, s1, c1, s2, c2, w1sq, w2sq, a1, a2)
      type(lane_coef_t), intent(in) :: c         !! constants
      integer, intent(in) :: l                   !! lane
      real(dp), intent(in) :: s1, c1, s2, c2     !! sin q1, cos q1, sin q2, cos q2
      real(dp), intent(in) :: w1sq, w2sq         !! q̇1², q̇2² [rad²/s²]
      real(dp), intent(out) :: a1, a2            !! accelerations [rad/s²]
      real(dp) :: cd, sd, r1, r2, rdet
      ! the equations divided by k: M12/k = cos d
      cd = c1*c2 + s1*s2
      sd = s1*c2 - c1*s2
      r1 = -c%gak(l)*c1 - sd*w2sq
      r2 = -c%gbk(l)*c2 + sd*w1sq
      rdet = 1.0_dp/(c%detk(l) - cd*cd)
      a1 = (c%m22k(l)*r1 - cd*r2)*rdet
      a2 = (c%m11k(l)*r2 - cd*r1)*rdet
   end subroutine accel_trig

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

   !> T + V of lane l from the trigonometric values [J].
   pure real(dp) function energy_formula(c, l, s1, c1, s2, c2, w1, w2) result(e)
      type(lane_coef_t), intent(in) :: c          !! constants
      integer, intent(in) :: l                    !! lane
      real(dp), intent(in) :: s1, c1, s2, c2      !! sin q1, cos q1, sin q2, cos q2
      real(dp), intent(in) :: w1, w2              !! velocities [rad/s]
      e = 0.5_dp*(c%m11(l)*w1*w1 + 2.0_dp*c%k(l)*(c1*c2 + s1*s2)*w1*w2 + c%m22(l)*w2*w2) &
          + (c%ga(l)*s1 + c%gb(l)*s2)
   end function energy_formula

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

   !> Integrate the initial conditions y0(:, j) = (q1, q2, q̇1, q̇2) with RK4 of step
   !> opt%h up to opt%n_steps steps, lanes refilled with the next initial condition as
   !> soon as a trajectory ends. Initial conditions whose energy is below both flip
   !> bounds are not integrated (status st_cannot_flip) unless opt%lyapunov.
   !> With `pars`, initial condition j has the pendulum pars(j) (a sweep over
   !> parameters): each lane takes the constants of the trajectory it
   !> holds (`lane_coef_t`), so that its results are those of a call with par =
   !> pars(j) bit for bit, and the lanes fill whatever the parameters.
   subroutine integrate_batch(par, opt, y0, res, pars)
      type(pendulum_t), intent(in) :: par             !! parameters (of all, without pars)
      type(batch_options_t), intent(in) :: opt        !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)                !! (4, n) initial states
      type(batch_result_t), intent(out) :: res        !! results
      type(pendulum_t), intent(in), optional :: pars(:)  !! (n) each one's own parameters
      integer, parameter :: w = lane_width
      type(lane_coef_t) :: c                   ! the constants of each lane's trajectory
      type(batch_coef_t), allocatable :: coefs(:)  ! (1), or (n) with pars
      real(dp), allocatable :: bounds(:, :), escale(:)  ! (2, size(coefs)), (size(coefs))
      real(dp), dimension(w) :: q1, q2, w1, w2, u1, u2, v1, v2, e, e0, err, tf1, tf2
      real(dp), dimension(w) :: p1, p2, n1, n2, lacc, nrm, lnrm
      ! the angles between lo and hi cannot have crossed an upward vertical since the last
      ! check: (π/2 + 2π n, π/2 + 2π (n + 1)) shrunk by window_margin
      real(dp), dimension(w) :: lo1, hi1, lo2, hi2
      real(dp), dimension(w) :: active, fresh  ! 1: lane holds an initial condition; just loaded
      real(dp), dimension(w) :: left           ! steps left to n_steps
      real(dp), dimension(w) :: sync           ! steps left to the next exact sin/cos
      type(lane_trig_t) :: tr                  ! sin, cos of the angles (rk4_lanes)
      integer(i8) :: ks(w)
      integer :: lane_ic(w)
      logical :: can1(w), can2(w), ended(w)
      logical, allocatable :: can_flip1(:), can_flip2(:), todo(:)
      real(dp) :: nan, m, qc, s, n_events
      real(dp) :: dv(w, 4, 2), acc(w, 5), v0(4, 4)   ! indicators' vectors and sums
      integer :: n, i, next, n_active, rule
      logical :: any_ended

      n = size(y0, 2)
      if (present(pars)) then
         if (size(pars) /= n) error stop 'internal error: integrate_batch needs size(pars) = n'
         coefs = [(batch_coef(pars(i)), i=1, n)]
         escale = [(potential_range(pars(i)), i=1, n)]
         allocate (bounds(2, n))
         do i = 1, n
            bounds(:, i) = flip_energy_bounds(pars(i))
         end do
      else
         coefs = [batch_coef(par)]
         escale = [potential_range(par)]
         bounds = reshape(flip_energy_bounds(par), [2, 1])
      end if
      c = lane_coef(batch_coef(par))   ! idle lanes keep valid constants
      nan = ieee_value(nan, ieee_quiet_nan)
      rule = opt%stop_rule
      if (opt%lyapunov .or. opt%vectors > 0) rule = stop_end
      v0 = initial_vectors(4)
      dv = 1.0_dp; acc = 0.0_dp
      allocate (can_flip1(n), can_flip2(n), todo(n))
      call start_results(coefs, bounds, opt, y0, res, can_flip1, can_flip2, todo)
      if (opt%n_steps < 1) return   ! t_end = 0: nothing to integrate

      ! fill the lanes
      next = 1
      n_active = 0
      do i = 1, w
         call load(i)
      end do

      do while (n_active > 0)
         p1 = q1
         p2 = q2
         if (opt%vectors > 0) then
            call indicator_step_lanes(c, opt%h, ks, q1, q2, w1, w2, opt%vectors, dv, acc, e, tr)
         else if (opt%lyapunov) then
            call rk4_tangent_lanes(c, opt%h, q1, q2, w1, w2, u1, u2, v1, v2, e)
            do i = 1, w
               nrm(i) = sqrt(u1(i)**2 + u2(i)**2 + v1(i)**2 + v2(i)**2)
               s = 1.0_dp/nrm(i)
               u1(i) = u1(i)*s; u2(i) = u2(i)*s; v1(i) = v1(i)*s; v2(i) = v2(i)*s
            end do
            call log_lanes(nrm, lnrm)
            lacc = lacc + lnrm
         else
            call rk4_lanes(c, opt%h, q1, q2, w1, w2, e, tr)
         end if
         ! vectorized: error, step count, and a count of the lanes with a possible
         ! event (an angle out of its window, the last step, a non-finite state, a fresh
         ! lane, carried sin and cos due to be set exactly); the rare path below decides
         ! each one exactly
         n_events = 0
         do i = 1, w
            err(i) = max(err(i), abs(e(i) - e0(i)))
            ks(i) = ks(i) + 1
            s = abs(q1(i)) + abs(q2(i)) + abs(w1(i)) + abs(w2(i))
            left(i) = left(i) - 1.0_dp
            sync(i) = sync(i) - 1.0_dp
            ! no compare (it would stop the vectorizer without -fno-trapping-math):
            ! every term >= 0, > 0 for an event; NaN (also an event) if s is not finite
            n_events = n_events + active(i)*(max(0.0_dp, lo1(i) - q1(i)) &
                                             + max(0.0_dp, q1(i) - hi1(i)) &
                                             + max(0.0_dp, lo2(i) - q2(i)) &
                                             + max(0.0_dp, q2(i) - hi2(i)) &
                                             + 0.5_dp*(1.0_dp - sign(1.0_dp, left(i) - 0.5_dp)) &
                                             + abs(s - s) + max(0.0_dp, s - lane_bound) &
                                             + max(0.0_dp, 0.5_dp - sync(i)) + fresh(i))
         end do
         if (n_events == 0.0_dp) cycle   ! false for NaN
         ! rare: flip times and the stop rule, lane by lane
         do i = 1, w
            fresh(i) = 0.0_dp
            if (sync(i) < 0.5_dp) call resync(i)
            ! the index of the last upward vertical below each angle (π/2 + 2π n)
            m = floor_real((q1(i) - half_pi)*inv_two_pi)
            if (m /= n1(i)) then
               if (tf1(i) < 0.0_dp) then
                  qc = half_pi + two_pi*max(m, n1(i))
                  tf1(i) = (real(ks(i) - 1, dp) + (qc - p1(i))/(q1(i) - p1(i)))*opt%h
               end if
               n1(i) = m
               call set_windows(i)
            end if
            m = floor_real((q2(i) - half_pi)*inv_two_pi)
            if (m /= n2(i)) then
               if (tf2(i) < 0.0_dp) then
                  qc = half_pi + two_pi*max(m, n2(i))
                  tf2(i) = (real(ks(i) - 1, dp) + (qc - p2(i))/(q2(i) - p2(i)))*opt%h
               end if
               n2(i) = m
               call set_windows(i)
            end if
            ended(i) = ks(i) >= opt%n_steps .or. runaway(q1(i), q2(i), w1(i), w2(i))
            select case (rule)
            case (stop_both)
               ended(i) = ended(i) .or. ((tf1(i) >= 0.0_dp .or. .not. can1(i)) .and. &
                                         (tf2(i) >= 0.0_dp .or. .not. can2(i)))
            case (stop_either)
               ended(i) = ended(i) .or. tf1(i) >= 0.0_dp .or. tf2(i) >= 0.0_dp
            end select
            ended(i) = ended(i) .and. lane_ic(i) > 0
         end do
         any_ended = .false.
         do i = 1, w
            any_ended = any_ended .or. ended(i)
         end do
         if (.not. any_ended) cycle
         do i = 1, w
            if (.not. ended(i)) cycle
            call finish(i)
            call load(i)
         end do
      end do

      call close_results(coefs, escale, opt, y0, todo, res)

   contains

      !> Put the next initial condition to integrate into lane l, or the idle state.
      subroutine load(l)
         integer, intent(in) :: l
         do while (next <= n)
            if (todo(next)) exit
            next = next + 1
         end do
         ks(l) = 0
         left(l) = real(opt%n_steps, dp)
         err(l) = 0.0_dp
         tf1(l) = -1.0_dp; tf2(l) = -1.0_dp
         lacc(l) = 0.0_dp
         u1(l) = 0.5_dp; u2(l) = 0.5_dp; v1(l) = 0.5_dp; v2(l) = 0.5_dp
         dv(l, :, 1) = v0(:, 1); dv(l, :, 2) = v0(:, 2); acc(l, :) = 0.0_dp
         if (next <= n) then
            lane_ic(l) = next
            if (size(coefs) > 1) call set_lane_coef(c, l, coefs(next))
            q1(l) = y0(1, next); q2(l) = y0(2, next)
            w1(l) = y0(3, next); w2(l) = y0(4, next)
            e0(l) = res%energy0(next)
            can1(l) = can_flip1(next); can2(l) = can_flip2(next)
            next = next + 1
            n_active = n_active + 1
            active(l) = 1.0_dp
            fresh(l) = 1.0_dp
         else
            lane_ic(l) = 0
            q1(l) = -half_pi; q2(l) = -half_pi; w1(l) = 0.0_dp; w2(l) = 0.0_dp
            e0(l) = 0.0_dp
            can1(l) = .false.; can2(l) = .false.
            active(l) = 0.0_dp
            fresh(l) = 0.0_dp
         end if
         n1(l) = floor_real((q1(l) - half_pi)*inv_two_pi)
         n2(l) = floor_real((q2(l) - half_pi)*inv_two_pi)
         call set_windows(l)
         call resync(l)
      end subroutine load

      !> Set the sines and cosines that rk4_lanes and rk4_tangent_fused_lanes carry,
      !> for lane l, exactly.
      subroutine resync(l)
         integer, intent(in) :: l
         call sincos_exact(q1(l), tr%s1(l), tr%c1(l))
         call sincos_exact(q2(l), tr%s2(l), tr%c2(l))
         sync(l) = real(resync_steps, dp)
         ! (the Lyapunov kernel, `rk4_tangent_lanes`, computes its own sin and cos)
         if (opt%lyapunov .and. opt%vectors == 0) sync(l) = huge(1.0_dp)
      end subroutine resync

      !> The windows of lane l's angles from n1, n2: between two upward verticals,
      !> shrunk by window_margin so that rounding never hides a crossing.
      subroutine set_windows(l)
         integer, intent(in) :: l
         lo1(l) = half_pi + two_pi*n1(l) + window_margin
         hi1(l) = half_pi + two_pi*(n1(l) + 1.0_dp) - window_margin
         lo2(l) = half_pi + two_pi*n2(l) + window_margin
         hi2(l) = half_pi + two_pi*(n2(l) + 1.0_dp) - window_margin
      end subroutine set_windows

      !> Store the results of the trajectory in lane l.
      subroutine finish(l)
         integer, intent(in) :: l
         integer :: jj
         jj = lane_ic(l)
         res%t_stop(jj) = real(ks(l), dp)*opt%h
         res%final(:, jj) = [q1(l), q2(l), w1(l), w2(l)]
         res%t_flip1(jj) = tf1(l); res%t_flip2(jj) = tf2(l)
         res%energy_error(jj) = err(l)
         res%steps(jj) = int(ks(l))
         if (opt%lyapunov) res%lyapunov(jj) = lacc(l)/res%t_stop(jj)
         if (opt%vectors > 0) call finish_indicators(jj, l)
         if (runaway(q1(l), q2(l), w1(l), w2(l))) then
            res%status(jj) = st_nonfinite
         else if (ks(l) < opt%n_steps) then
            res%status(jj) = st_flipped
         end if
         n_active = n_active - 1
      end subroutine finish

      !> The fast indicators of trajectory jj from the vectors and sums of lane l.
      subroutine finish_indicators(jj, l)
         integer, intent(in) :: jj, l
         real(dp) :: d(4, 2), a(4)
         integer :: info
         d = dv(l, :, :); a = acc(l, 1:4)
         if (.not. (all(ieee_is_finite(d(:, 1:opt%vectors))) .and. &
                    all(ieee_is_finite(a)))) return   ! NaN: not finite
         res%fli(jj) = a(1)
         res%megno_y(jj) = a(3)
         res%megno(jj) = a(4)/res%t_stop(jj)
         if (opt%vectors < 2) return
         res%sali(jj) = sali(d(:, 1), d(:, 2))
         call gali(d, res%gali2(jj), info)
         if (info /= 0) res%gali2(jj) = nan
      end subroutine finish_indicators
   end subroutine integrate_batch

   !> The batch kernel's set-up (outside the step loop): allocate the results of the
   !> n initial conditions y0, their initial energies and which of them can flip
   !> (energy at or above a link's flip bound) or must be integrated anyway (`todo`);
   !> with opt%n_steps < 1 (t_end = 0) the results are final here. Constants and
   !> bounds: one column for all, or column j for initial condition j.
   subroutine start_results(c, bounds, opt, y0, res, can_flip1, can_flip2, todo)
      type(batch_coef_t), intent(in) :: c(:)              !! constants (1 or n)
      real(dp), intent(in) :: bounds(:, :)                !! (2, 1 or n) flip bounds [J]
      type(batch_options_t), intent(in) :: opt            !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)                    !! (4, n) initial states
      type(batch_result_t), intent(inout) :: res          !! results (allocated here)
      logical, intent(out) :: can_flip1(:), can_flip2(:), todo(:)  !! (n)
      real(dp) :: nan
      integer :: n, j, jc
      n = size(y0, 2)
      nan = ieee_value(nan, ieee_quiet_nan)
      allocate (res%megno(n), res%megno_y(n), res%fli(n), res%sali(n), res%gali2(n))
      res%megno = nan; res%megno_y = nan; res%fli = nan; res%sali = nan; res%gali2 = nan
      res%n = n
      allocate (res%t_flip1(n), res%t_flip2(n), res%t_flip(n), res%energy0(n), &
                res%energy_error(n), res%t_stop(n), res%final(4, n), res%lyapunov(n), &
                res%status(n), res%steps(n))
      if (opt%n_steps < 1) then   ! t_end = 0: nothing to integrate
         call energies(c, y0, res%energy0)
         res%t_flip1 = nan; res%t_flip2 = nan; res%t_flip = nan; res%lyapunov = nan
         res%energy_error = 0.0_dp; res%t_stop = 0.0_dp; res%final = y0
         res%status = st_end; res%steps = 0
         return
      end if

      ! initial energies, W at a time (padding lanes hold the hanging state)
      call energies(c, y0, res%energy0)
      do j = 1, n
         jc = min(j, size(bounds, 2))
         can_flip1(j) = .not. (res%energy0(j) < bounds(1, jc))
         can_flip2(j) = .not. (res%energy0(j) < bounds(2, jc))
         todo(j) = can_flip1(j) .or. can_flip2(j) .or. opt%lyapunov .or. &
                   .not. opt%skip_cannot_flip .or. opt%vectors > 0
         res%t_flip1(j) = -1.0_dp; res%t_flip2(j) = -1.0_dp
         res%energy_error(j) = 0.0_dp
         res%t_stop(j) = 0.0_dp
         res%final(:, j) = y0(:, j)
         res%lyapunov(j) = 0.0_dp
         res%steps(j) = 0
         res%status(j) = merge(st_end, st_cannot_flip, can_flip1(j) .or. can_flip2(j))
      end do
   end subroutine start_results

   !> The batch kernel's closing pass: the largest energy error (the final states'
   !> energies included) relative to the potential's range `escale`, the first flip
   !> of either link, NaN for what was not computed, and the initial state as the
   !> final one of a condition that was not integrated.
   subroutine close_results(c, escale, opt, y0, todo, res)
      type(batch_coef_t), intent(in) :: c(:)              !! constants (1 or n)
      real(dp), intent(in) :: escale(:)                   !! V_max - V_min (1 or n) [J]
      type(batch_options_t), intent(in) :: opt            !! options
      real(dp), intent(in) :: y0(:, :)                    !! (4, n) initial states
      logical, intent(in) :: todo(:)                      !! integrated (n)
      type(batch_result_t), intent(inout) :: res          !! results
      real(dp) :: nan
      integer :: n, j
      n = size(y0, 2)
      nan = ieee_value(nan, ieee_quiet_nan)
      ! the energy of the final states enters the maximum error
      call energies(c, res%final, e_final=res%t_flip)   ! t_flip used as scratch
      do j = 1, n
         if (todo(j) .and. res%status(j) /= st_nonfinite) then
            res%energy_error(j) = max(res%energy_error(j), abs(res%t_flip(j) - res%energy0(j)))
            res%energy_error(j) = res%energy_error(j)/escale(min(j, size(escale)))
         else
            res%energy_error(j) = nan
         end if
      end do
      do j = 1, n
         if (res%t_flip1(j) >= 0.0_dp .and. res%t_flip2(j) >= 0.0_dp) then
            res%t_flip(j) = min(res%t_flip1(j), res%t_flip2(j))
         else if (res%t_flip1(j) >= 0.0_dp) then
            res%t_flip(j) = res%t_flip1(j)
         else if (res%t_flip2(j) >= 0.0_dp) then
            res%t_flip(j) = res%t_flip2(j)
         else
            res%t_flip(j) = nan
         end if
         if (.not. (res%t_flip1(j) >= 0.0_dp)) res%t_flip1(j) = nan
         if (.not. (res%t_flip2(j) >= 0.0_dp)) res%t_flip2(j) = nan
         if (.not. opt%lyapunov .or. .not. todo(j)) res%lyapunov(j) = nan
         if (.not. todo(j)) res%final(:, j) = y0(:, j)
      end do
   end subroutine close_results

   !> An angle offset clamped to ±`d_max` [rad]: itself on `rk4_lanes`' fast path.
   pure elemental real(dp) function dclamp(d)
      real(dp), intent(in) :: d  !! offset [rad]
      dclamp = min(max(d, -d_max), d_max)
   end function dclamp

   !> The square of a velocity clamped to `lane_bound`² [rad²/s²]: w² unless the lane
   !> runs away. (w² itself must not overflow: |w| < 1e154. A step that starts below
   !> `lane_bound` keeps its stage velocities far below that, and `integrate_batch`
   !> ends a lane beyond `lane_bound` before its next step.)
   pure elemental real(dp) function wsq(w)
      real(dp), intent(in) :: w  !! velocity [rad/s]
      wsq = min(w*w, lane_bound*lane_bound)
   end function wsq

   !> The lane's state is not finite or beyond `lane_bound` (no ordered comparison
   !> on NaN, which would raise IEEE invalid).
   pure elemental logical function runaway(q1, q2, w1, w2)
      real(dp), intent(in) :: q1, q2, w1, w2  !! state [rad, rad/s]
      real(dp) :: s
      s = abs(q1) + abs(q2) + abs(w1) + abs(w2)
      runaway = .true.
      if (s - s == 0.0_dp) runaway = s > lane_bound
   end function runaway

   !> floor(y) as a real, vectorizable (no conversion to integer): y rounded to an
   !> integer by the 1.5·2^52 trick, minus 1 where that rounded up (yc - f < 0; for
   !> yc = f, yc - f = +0); exact for
   !> |y| < 2^50 (beyond, y is clamped to ±2^50: angles above 7e15 rad).
   pure elemental real(dp) function floor_real(y) result(f)
      real(dp), intent(in) :: y  !! value
      real(dp), parameter :: round_magic = 6755399441055744.0_dp  ! 1.5·2^52
      real(dp), parameter :: big = 1125899906842624.0_dp           ! 2^50
      real(dp) :: yc
      yc = min(max(y, -big), big)
      f = (yc + round_magic) - round_magic
      f = f - 0.5_dp*(1.0_dp - sign(1.0_dp, yc - f))   ! - 1 if f > yc, without a compare
   end function floor_real

   !> Energies of the states y(:, j), computed W at a time with the lane kernel, with
   !> the constants c(1) for all, or c(j) for state j.
   subroutine energies(c, y, e_final)
      type(batch_coef_t), intent(in) :: c(:)  !! constants (1 or n)
      real(dp), intent(in) :: y(:, :)         !! (4, n) states
      real(dp), intent(out) :: e_final(:)     !! (n) energies [J]
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, e
      type(lane_coef_t) :: lc
      integer :: j0, i, n, m
      n = size(y, 2)
      if (n < 1) return
      lc = lane_coef(c(1))
      do j0 = 1, n, lane_width
         m = min(lane_width, n - j0 + 1)
         q1 = -half_pi; q2 = -half_pi; w1 = 0.0_dp; w2 = 0.0_dp
         if (size(c) > 1) then
            do i = 1, m
               call set_lane_coef(lc, i, c(j0 + i - 1))
            end do
         end if
         do i = 1, m
            q1(i) = y(1, j0 + i - 1); q2(i) = y(2, j0 + i - 1)
            w1(i) = y(3, j0 + i - 1); w2(i) = y(4, j0 + i - 1)
         end do
         call energy_lanes(lc, q1, q2, w1, w2, e)
         e_final(j0:j0 + m - 1) = e(:m)
      end do
   end subroutine energies
end module dpend_pendulum_lanes
