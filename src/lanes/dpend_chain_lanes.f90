!> The chain lanes: the sweep's flip maps of the conservative chain of
!> N = 3 … `max_lane_links` links (`dpend_chain`: uniform rods or general bodies),
!> `lane_width` trajectories at a time in structure-of-arrays form, every loop over the
!> lanes innermost so that gfortran vectorizes it. Each lane assembles and solves its
!> own N × N mass-matrix system at every RK4 stage.
!>
!> Physics: the chain model's own constants K_ij and G_i (`chain_t`'s k and gl, built
!> once by `chain_model`: one source for the mass distribution), with the written-out
!> form of its equations of motion (dpend_chain's module notes)
!>   M_ij = K_ij cos(q_i − q_j),  f_i = −Σ_j K_ij sin(q_i − q_j) q̇_j² − G_i cos q_i,
!>   M q̈ = f,  E = ½ q̇ᵀ M q̇ + Σ G_i sin q_i.
!> The model evaluates f by its Newton–Euler recursion and solves by Cholesky; this is a
!> copy for speed (LDLᵀ without square roots, cos and sin of q_i − q_j by the
!> subtraction formulas), which test chain_lanes/accelerations_match_model compares with
!> `chain_t%accelerations` and `chain_t%energy`.
!>
!> The results are those of the per-trajectory path (`dpend_trajectory_batch`): the
!> first flip of every link (crossing of q_i = π/2 + 2π k, interpolated linearly in q_i
!> within the step), the same flip energy bounds (`link_flip_bounds`, `bound_margin`),
!> stop rules, energy error (max |E(t_k) − E(0)| / 2 Σ G_i), final state, steps and
!> statuses; E(0) and the final state's energy come from the model itself. Within a
!> step the lanes differ from the registry's rk4 only by rounding: the stages' sin and
!> cos come from the step start's by the addition formulas (`sincos_near_lanes`, exact
!> beyond its offset), and the carried sin and cos are set exactly every
!> `resync_steps` steps (as the two-link kernel). A step whose result is not finite or
!> not below the integrators' bound (Σ |y_i| < 1e30, `state_ok`) is not taken: the
!> lane ends with st_nonfinite, its final state the last one before (the
!> per-trajectory path's rule).
!>
!> Served: maps over initial values of the undamped, undriven chain (the sweep refuses
!> the others): the flip map and the indicators MEGNO, FLI (one deviation vector), SALI
!> and GALI_2 (two). Parameter maps stay on the per-trajectory path (and the sweep
!> refuses a Lyapunov exponent for chains).
!>
!> Indicators: the definitions, vectors, renormalisation and sample of the
!> per-trajectory path (`integrate_trajectories` → `chaos_indicators`: vectors 1 and 2
!> of `initial_vectors(2N)`, renormalised to length 1 after every step, `megno_step`
!> on vector 1, one sample at t_end; every trajectory runs to t_end, those below the
!> flip bounds too). The vectors step in the lanes with the state: the derivative of
!> the lanes' RK4 step (`chain_rk4_lanes` with vectors: RK4 on the variational
!> equation M δq̈ = r, each stage's Jacobian–vector product `chain_tangent_lanes`
!> from the stage's own factors of M), where the path integrates the variational
!> equation along the step's cubic Hermite interpolant with ⌈hω/θ⌉ substeps
!> (`tangent_t%propagate`). Both are fourth-order approximations of the same
!> tangent flow: the maps differ by less than the path's own change from dt to dt/2
!> (docs/sweep.md, "Chain lanes"; test chain_lanes/indicators_match_per_trajectory).
!> Only the vectors the indicator needs are carried (the path carries 2N). A
!> trajectory whose state runs away, whose step turns a link by more than
!> `max_tangent_turn`, or whose vector's length leaves (0, `diverged_bound`) has NaN
!> indicators (the path: its state runs away, its tangent needs more than
!> `max_tangent_substeps` substeps, or a vector leaves its bounds).
!> DPEND_SWEEP_KERNEL=trajectory in the environment sends every chain to the
!> per-trajectory path (`chain_kernel_choice`); two links are not affected.
!>
!> Reproducibility: lanes never mix and every loop runs the full width (idle lanes
!> hang at rest), so results are bitwise independent of threads and blocks.
module dpend_chain_lanes
   use dpend_kinds, only: dp, i8, pi, half_pi
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: diverged_bound, max_tangent_substeps
   use dpend_strings, only: printable
   use dpend_model, only: model_t
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t, lane_kernel_t, &
      refill_lanes, resync_steps, stop_both, stop_either, st_end, st_flipped, st_cannot_flip, &
      st_nonfinite, link_flip_bounds, first_flips, bound_margin
   use dpend_pendulum_kernel, only: sincos_near_lanes, sincos_exact
   use dpend_pendulum_tangent_lanes, only: log_lanes, megno_step_lanes
   use dpend_indicator_math, only: initial_vectors, sali, gali
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private
   public :: max_lane_links, chain_coef_t, chain_coef, chain_lanes_serve, chain_kernel_choice
   public :: chain_accel_lanes, chain_rk4_lanes, integrate_chain_lanes, chain_tangent_lanes

   integer, parameter :: min_lane_links = 3  !! fewest links of the chain lanes
   integer, parameter :: max_lane_links = 8  !! most links of the chain lanes
   integer, parameter :: w = lane_width
   integer, parameter :: nm = max_lane_links
   real(dp), parameter :: two_pi = 2.0_dp*pi, inv_two_pi = 1.0_dp/two_pi
   !> A lane whose Σ |q_i| + |q̇_i| is not below this has run away (st_nonfinite): the
   !> integrators' bound (`state_ok`), so that the lanes end a trajectory where the
   !> per-trajectory path does. The forces take the velocities' squares clamped to its
   !> square (1e60), so that no stage of a step that starts below it overflows
   real(dp), parameter :: chain_lane_bound = diverged_bound
   !> Margin of the angle windows [rad] (as the two-link kernel's)
   real(dp), parameter :: window_margin = 1.0e-6_dp
   !> Largest turn h max |q̇_i| of a step with indicators [rad]: beyond it the
   !> per-trajectory path's tangent would need more than `max_tangent_substeps`
   !> substeps of θ = 0.1 (its ω is at least about max |q̇_i|), and the lanes' tangent
   !> step is no approximation of the tangent flow: the trajectory has no indicators
   real(dp), parameter :: max_tangent_turn = 0.1_dp*real(max_tangent_substeps, dp)

   !> The chain's constants for the lanes [SI].
   type :: chain_coef_t
      integer :: n = 0                     !! links N
      real(dp) :: k(nm, nm) = 0.0_dp       !! K_ij of M_ij = K_ij cos(q_i − q_j) [kg m²]
      real(dp) :: gl(nm) = 0.0_dp          !! G_i of V = Σ G_i sin q_i [J]
   end type chain_coef_t

   !> The chain's system at a state of every lane, solved and kept for the tangent's
   !> Jacobian–vector products (`solve_system`, `system_jvp`).
   type :: lane_system_t
      real(dp), dimension(w, nm, nm) :: mm      !! L of M = L D Lᵀ (below the diagonal)
      real(dp), dimension(w, nm, nm) :: kc, sk  !! K_ij cos, K_ij sin of q_i − q_j (i > j)
      real(dp), dimension(w, nm) :: a           !! q̈ [rad/s²]
      real(dp), dimension(w, nm) :: dinv        !! D⁻¹
      real(dp), dimension(w, nm) :: wq          !! q̇², clamped [rad²/s²]
      real(dp), dimension(w, nm) :: s, qd       !! sin q, q̇ [rad/s]
   end type lane_system_t

   !> The lanes of a batch of chains: the batch, its results, and every lane's
   !> state, flips and indicator sums (structure of arrays).
   type, extends(lane_kernel_t) :: chain_lanes_t
      ! the lanes' arrays first (multiples of 64 bytes from the start of the object:
      ! aligned wherever the object is, as the kernel's vector loads want them)
      real(dp), dimension(w, nm) :: q, qd, ts, tc, p, pd, lo, hi, nk, tf
      real(dp), dimension(w, nm, 2) :: dq, dw        !! deviation vectors (δq, δq̇)
      real(dp), dimension(w) :: e, e0, err, active, fresh, left, sync
      real(dp), dimension(w) :: lg, ig, yy, sy, vok
      integer(i8) :: ks(w)                           !! steps taken
      type(chain_coef_t) :: cf                       !! the chain's constants
      integer :: lane_ic(w)                          !! trajectory held, 0: none
      logical :: lane_can(w, nm)
      logical :: ind_ok(w)
      class(model_t), allocatable :: model           !! the chain
      integer :: nl = 0                              !! links N
      type(batch_options_t) :: opt                   !! step, length, stop rule
      real(dp), allocatable :: y0(:, :)              !! (2N, n) initial states
      logical, allocatable :: can(:, :)              !! (N, n) links that can flip
      type(batch_result_t) :: res                    !! the results
      real(dp) :: escale = 1.0_dp                    !! unit of the energy error [J]
      real(dp) :: nan
      ! the indicators (opt%vectors 1 or 2): vectors dq, dw, running sums of vector 1
      ! (lg, ig, yy, sy; dpend_indicators), vok = 1 where a lane's indicators hold
      integer :: nv = 0
      real(dp), allocatable :: v0(:, :)   !! the initial vectors (2N, 2N)
   contains
      procedure :: step => chain_step
      procedure :: load => chain_load
      procedure :: check => chain_check
      procedure :: finish => chain_finish
   end type chain_lanes_t

contains

   !> The lanes' constants of a chain of at most `max_lane_links` links (served:
   !> `chain_lanes_serve`): the model's own K_ij and G_i (`mass_weights`,
   !> `potential_weights`).
   pure function chain_coef(model) result(cf)
      class(model_t), intent(in) :: model  !! the chain
      type(chain_coef_t) :: cf
      real(dp), allocatable :: k(:, :), gl(:)
      k = model%mass_weights()
      gl = model%potential_weights()
      cf%n = size(gl)
      cf%k(1:cf%n, 1:cf%n) = k
      cf%gl(1:cf%n) = gl
   end function chain_coef

   !> Whether the chain lanes can serve a sweep of `model` with options `opt`: a
   !> conservative model of 3 to `max_lane_links` links whose equations have the
   !> chain's form (`mass_weights` and `potential_weights` given: M_ij = K_ij cos(q_i −
   !> q_j), V = Σ G_i sin q_i), a flip map or indicators (no Lyapunov exponent).
   pure logical function chain_lanes_serve(model, opt) result(ok)
      class(model_t), intent(in) :: model         !! the run's model
      type(batch_options_t), intent(in) :: opt    !! the sweep's kernel options
      integer :: n
      real(dp), allocatable :: k(:, :), gl(:)
      n = model%n_dof()
      k = model%mass_weights()
      gl = model%potential_weights()
      ok = n >= min_lane_links .and. n <= max_lane_links .and. size(gl) == n .and. &
           size(k, 1) == n .and. size(k, 2) == n .and. model%hamiltonian() .and. &
           opt%vectors >= 0 .and. opt%vectors <= 2 .and. .not. opt%lyapunov
   end function chain_lanes_serve

   !> The chain lanes serve the sweep (`chain_lanes_serve`) unless the environment
   !> variable DPEND_SWEEP_KERNEL is 'trajectory' (unset, empty or 'lanes': the lanes).
   !> Any other value is refused, naming the variable, its value and the accepted ones.
   subroutine chain_kernel_choice(model, opt, lanes, error)
      class(model_t), intent(in) :: model               !! the run's model
      type(batch_options_t), intent(in) :: opt          !! the sweep's kernel options
      logical, intent(out) :: lanes                     !! integrate with the chain lanes
      type(error_t), allocatable, intent(out) :: error  !! refused value
      character(len=32) :: value
      integer :: length, stat
      lanes = chain_lanes_serve(model, opt)
      call get_environment_variable('DPEND_SWEEP_KERNEL', value, length, stat)
      if (stat == 1 .or. length == 0) return   ! unset or empty
      if (stat /= 0 .or. length > len(value)) then
         call fatal_error(error, 'invalid DPEND_SWEEP_KERNEL: a value of '// &
                          'more than 32 characters (accepted: lanes, trajectory)')
         return
      end if
      ! the whole value, no blanks around it
      if (length == len('trajectory') .and. value(1:length) == 'trajectory') then
         lanes = .false.
      else if (.not. (length == len('lanes') .and. value(1:length) == 'lanes')) then
         call fatal_error(error, "invalid DPEND_SWEEP_KERNEL: '"//printable(value(1:length)) &
                          //"' (accepted: lanes, trajectory)")
      end if
   end subroutine chain_kernel_choice

   !> q̈ [rad/s²] of every lane at (q, q̇) from s = sin q, c = cos q; with `e`, also the
   !> energy E = ½ q̇ᵀ M q̇ + Σ G_i sin q_i [J]. The velocities' squares are clamped to
   !> `chain_lane_bound`² (a lane beyond has run away; its values stay finite).
   pure subroutine chain_accel_lanes(cf, s, c, qd, a, e)
      type(chain_coef_t), intent(in) :: cf          !! constants
      real(dp), intent(in) :: s(w, nm), c(w, nm)    !! sin q_i, cos q_i
      real(dp), intent(in) :: qd(w, nm)             !! q̇ [rad/s]
      real(dp), intent(out) :: a(w, nm)             !! q̈ [rad/s²]
      real(dp), intent(out), optional :: e(w)       !! energy [J]
      logical, parameter :: keep = .false.
      real(dp) :: mm(w, nm, nm), u(w, nm, nm), wq(w, nm), dinv(w, nm), t(w)
      real(dp) :: kc(w, nm, nm), sk(w, nm, nm)      !! (not kept)
      real(dp) :: kij, sij
      integer :: n, i, j, k, l
      include 'dpend_chain_system.inc'
   end subroutine chain_accel_lanes

   !> The chain's system M q̈ = f of every lane at (q, q̇) (s = sin q, c = cos q), solved:
   !> q̈ in `a`, M = L D Lᵀ in `mm` (L unit lower, below the diagonal) and `dinv` (D⁻¹),
   !> the clamped squares of the rates in `wq`, and K_ij cos(q_i − q_j) and
   !> K_ij sin(q_i − q_j) for i > j in kc and sk (the tangent's terms, `system_jvp`);
   !> with `e`, the energy [J]. The arithmetic of `chain_accel_lanes`, bit for bit
   !> (dpend_chain_system.inc).
   pure subroutine chain_system_lanes(cf, s, c, qd, a, mm, dinv, wq, kc, sk, e)
      type(chain_coef_t), intent(in) :: cf               !! constants
      real(dp), intent(in) :: s(w, nm), c(w, nm)         !! sin q_i, cos q_i
      real(dp), intent(in) :: qd(w, nm)                  !! q̇ [rad/s]
      real(dp), intent(out) :: a(w, nm)                  !! q̈ [rad/s²]
      real(dp), intent(out) :: mm(w, nm, nm), dinv(w, nm)  !! L, D⁻¹
      real(dp), intent(out) :: wq(w, nm)                 !! q̇², clamped
      real(dp), intent(inout) :: kc(w, nm, nm), sk(w, nm, nm)  !! K cos, K sin (i > j)
      real(dp), intent(out), optional :: e(w)            !! energy [J]
      logical, parameter :: keep = .true.
      real(dp) :: u(w, nm, nm), t(w)
      real(dp) :: kij, sij
      integer :: n, i, j, k, l
      include 'dpend_chain_system.inc'
   end subroutine chain_system_lanes

   !> Solve L D Lᵀ x = b of every lane in place (x: b in, the solution out): L z = b,
   !> then Lᵀ x = D⁻¹ z.
   pure subroutine ldl_solve_lanes(n, mm, dinv, x)
      integer, intent(in) :: n                            !! links N
      real(dp), intent(in) :: mm(w, nm, nm), dinv(w, nm)  !! L (below the diagonal), D⁻¹
      real(dp), intent(inout) :: x(w, nm)                 !! b in, x out
      integer :: i, k, l
      do i = 2, n
         do k = 1, i - 1
            do l = 1, w
               x(l, i) = x(l, i) - mm(l, i, k)*x(l, k)
            end do
         end do
      end do
      do i = n, 1, -1
         do l = 1, w
            x(l, i) = x(l, i)*dinv(l, i)
         end do
         do k = i + 1, n
            do l = 1, w
               x(l, i) = x(l, i) - mm(l, k, i)*x(l, k)
            end do
         end do
      end do
   end subroutine ldl_solve_lanes

   !> The chain's system of every lane at (q, q̇) (s = sin q, c = cos q), solved and
   !> kept for Jacobian–vector products (`system_jvp`).
   pure subroutine solve_system(cf, s, c, qd, sys, e)
      type(chain_coef_t), intent(in) :: cf          !! constants
      real(dp), intent(in) :: s(w, nm), c(w, nm)    !! sin q_i, cos q_i
      real(dp), intent(in) :: qd(w, nm)             !! q̇ [rad/s]
      type(lane_system_t), intent(inout) :: sys     !! the system there
      real(dp), intent(out), optional :: e(w)       !! energy [J]
      sys%s = s
      sys%qd = qd
      call chain_system_lanes(cf, s, c, qd, sys%a, sys%mm, sys%dinv, sys%wq, sys%kc, &
                              sys%sk, e)
   end subroutine solve_system

   !> δq̈ of every lane's nv deviation vectors (xq, xw) = (δq, δq̇) at the state of the
   !> solved system `sys`: the variational equation M δq̈ = r of M q̈ = f, with the
   !> state's own factors of M,
   !>   r_i = G_i sin q_i δq_i − Σ_{j≠i} [ (K_ij cos(q_i − q_j) q̇_j² − K_ij sin(q_i − q_j) q̈_j)
   !>         (δq_i − δq_j) + 2 K_ij sin(q_i − q_j) q̇_j δq̇_j ]
   !> (q̇_j² clamped as in the forces): the lower half of the Jacobian J of
   !> (q̇, q̈)(q, q̇) times the vector. Test chain_lanes/tangent_matches_differences
   !> compares it with central differences of `chain_accel_lanes`.
   pure subroutine system_jvp(cf, sys, nv, xq, xw, b)
      type(chain_coef_t), intent(in) :: cf                !! constants
      type(lane_system_t), intent(in) :: sys              !! the solved system
      integer, intent(in) :: nv                           !! vectors, 1 or 2
      real(dp), intent(in) :: xq(w, nm, 2), xw(w, nm, 2)  !! δq, δq̇ (vectors 1:nv)
      real(dp), intent(out) :: b(w, nm, 2)                !! δq̈ (vectors 1:nv)
      real(dp) :: pj(w, nm), dd
      integer :: n, i, j, k, l
      n = cf%n
      do k = 1, nv
         do i = 1, n
            do l = 1, w
               b(l, i, k) = cf%gl(i)*sys%s(l, i)*xq(l, i, k)
               pj(l, i) = 2.0_dp*sys%qd(l, i)*xw(l, i, k)
            end do
         end do
         do j = 1, n
            do i = j + 1, n
               do l = 1, w
                  dd = xq(l, i, k) - xq(l, j, k)
                  b(l, i, k) = b(l, i, k) - ((sys%kc(l, i, j)*sys%wq(l, j) &
                               - sys%sk(l, i, j)*sys%a(l, j))*dd + sys%sk(l, i, j)*pj(l, j))
                  b(l, j, k) = b(l, j, k) + ((sys%kc(l, i, j)*sys%wq(l, i) &
                               + sys%sk(l, i, j)*sys%a(l, i))*dd + sys%sk(l, i, j)*pj(l, i))
               end do
            end do
         end do
         call ldl_solve_lanes(n, sys%mm, sys%dinv, b(:, :, k))
      end do
   end subroutine system_jvp

   !> q̈ of every lane at (q, q̇) (as `chain_accel_lanes`, energy `e`) and δq̈ of its nv
   !> deviation vectors (xq, xw) = (δq, δq̇) there (`system_jvp`).
   pure subroutine chain_tangent_lanes(cf, s, c, qd, a, nv, xq, xw, b, e)
      type(chain_coef_t), intent(in) :: cf                !! constants
      real(dp), intent(in) :: s(w, nm), c(w, nm)          !! sin q_i, cos q_i
      real(dp), intent(in) :: qd(w, nm)                   !! q̇ [rad/s]
      real(dp), intent(out) :: a(w, nm)                   !! q̈ [rad/s²]
      integer, intent(in) :: nv                           !! vectors, 1 or 2
      real(dp), intent(in) :: xq(w, nm, 2), xw(w, nm, 2)  !! δq, δq̇ (vectors 1:nv)
      real(dp), intent(out) :: b(w, nm, 2)                !! δq̈ (vectors 1:nv)
      real(dp), intent(out), optional :: e(w)             !! energy [J]
      type(lane_system_t) :: sys
      call solve_system(cf, s, c, qd, sys, e)
      a = sys%a
      call system_jvp(cf, sys, nv, xq, xw, b)
   end subroutine chain_tangent_lanes

   !> One classical RK4 step of size h on every lane; `e` is the energy of the state
   !> before the step [J]. `ts`, `tc` hold sin and cos of the angles on entry and of
   !> the new angles on return (the stages' and the new state's from the step start's
   !> by `sincos_near_lanes`, exact for a lane whose offset exceeds its range).
   !> With nv > 0, the deviation vectors (dq, dw) = (δq, δq̇) 1:nv step with it: the
   !> derivative of the step (the discrete tangent), RK4 on the variational equation
   !> with each stage's Jacobian (`chain_tangent_lanes`) at the stage's own state. The
   !> state's values are the same with and without the vectors.
   pure subroutine chain_rk4_lanes(cf, h, q, qd, e, ts, tc, nv, dq, dw)
      type(chain_coef_t), intent(in) :: cf           !! constants
      real(dp), intent(in) :: h                      !! step [s]
      real(dp), intent(inout) :: q(w, nm)            !! angles [rad]
      real(dp), intent(inout) :: qd(w, nm)           !! rates [rad/s]
      real(dp), intent(out) :: e(w)                  !! energy before the step [J]
      real(dp), intent(inout) :: ts(w, nm), tc(w, nm)  !! sin q, cos q
      integer, intent(in), optional :: nv            !! deviation vectors, 0 … 2
      real(dp), intent(inout), optional :: dq(w, nm, 2), dw(w, nm, 2)  !! δq, δq̇
      real(dp), dimension(w, nm) :: ka, kb, kc, kd, vb, vc, vd, x, d, s, c
      real(dp), dimension(w, nm, 2) :: xq, xb, xc, xd, ba, bb, bc, bd
      real(dp) :: hh, h6
      integer :: n, i, l, m, k
      n = cf%n
      m = 0
      if (present(nv)) m = nv
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      if (m > 0) then
         call chain_tangent_lanes(cf, ts, tc, qd, ka, m, dq, dw, ba, e)
      else
         call chain_accel_lanes(cf, ts, tc, qd, ka, e)
      end if
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + hh*qd(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vb(l, i) = qd(l, i) + hh*ka(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      if (m > 0) then
         call offset_vectors(n, m, hh, dq, dw, dw, ba, xq, xb)
         call chain_tangent_lanes(cf, s, c, vb, kb, m, xq, xb, bb)
      else
         call chain_accel_lanes(cf, s, c, vb, kb)
      end if
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + hh*vb(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vc(l, i) = qd(l, i) + hh*kb(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      if (m > 0) then
         call offset_vectors(n, m, hh, dq, dw, xb, bb, xq, xc)
         call chain_tangent_lanes(cf, s, c, vc, kc, m, xq, xc, bc)
      else
         call chain_accel_lanes(cf, s, c, vc, kc)
      end if
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + h*vc(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vd(l, i) = qd(l, i) + h*kc(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      if (m > 0) then
         call offset_vectors(n, m, h, dq, dw, xc, bc, xq, xd)
         call chain_tangent_lanes(cf, s, c, vd, kd, m, xq, xd, bd)
      else
         call chain_accel_lanes(cf, s, c, vd, kd)
      end if
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + h6*((qd(l, i) + 2.0_dp*(vb(l, i) + vc(l, i))) + vd(l, i))
            d(l, i) = x(l, i) - q(l, i)
            qd(l, i) = qd(l, i) + h6*((ka(l, i) + 2.0_dp*(kb(l, i) + kc(l, i))) + kd(l, i))
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      do i = 1, n
         do l = 1, w
            q(l, i) = x(l, i)
            ts(l, i) = s(l, i)
            tc(l, i) = c(l, i)
         end do
      end do
      do k = 1, m
         do i = 1, n
            do l = 1, w
               dq(l, i, k) = dq(l, i, k) + h6*((dw(l, i, k) + 2.0_dp*(xb(l, i, k) &
                             + xc(l, i, k))) + xd(l, i, k))
               dw(l, i, k) = dw(l, i, k) + h6*((ba(l, i, k) + 2.0_dp*(bb(l, i, k) &
                             + bc(l, i, k))) + bd(l, i, k))
            end do
         end do
      end do
   end subroutine chain_rk4_lanes


   !> s, c of the angles x = q + d of links 1 … n from the step start's (ts, tc).
   pure subroutine stage_trig(n, ts, tc, x, d, s, c)
      integer, intent(in) :: n                        !! links
      real(dp), intent(in) :: ts(w, nm), tc(w, nm)    !! sin q, cos q
      real(dp), intent(in) :: x(w, nm), d(w, nm)      !! angles, offsets [rad]
      real(dp), intent(inout) :: s(w, nm), c(w, nm)   !! sin x, cos x
      real(dp) :: dc(w)
      integer :: j, l
      do j = 1, n
         ! d clamped to ±1: the same values (an offset beyond 1/16 takes sin x, cos x
         ! themselves), and no overflow in the Taylor terms of a lane that runs away
         do l = 1, w
            dc(l) = min(max(d(l, j), -1.0_dp), 1.0_dp)
         end do
         call sincos_near_lanes(ts(:, j), tc(:, j), x(:, j), dc, s(:, j), c(:, j))
      end do
   end subroutine stage_trig

   !> Integrate the initial conditions y0(:, j) = (q, q̇) of the chain `model` (served:
   !> `chain_lanes_serve`) with RK4 of step opt%h for at most opt%n_steps steps each,
   !> with the stop rule opt%stop_rule, `lane_width` at a time, a lane refilled as soon as
   !> its trajectory ends. Results as `integrate_trajectories` (dpend_trajectory_batch).
   subroutine integrate_chain_lanes(model, opt, y0, res)
      class(model_t), intent(in) :: model            !! the chain
      type(batch_options_t), intent(in) :: opt       !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)               !! (2N, n) initial states
      type(batch_result_t), intent(out) :: res       !! results
      type(chain_lanes_t) :: k
      logical :: todo(size(y0, 2))
      real(dp) :: bounds(model%n_dof()), margin
      integer :: n, nl, i, j
      if (.not. chain_lanes_serve(model, opt)) &
         error stop 'internal error: integrate_chain_lanes needs a chain it serves'
      allocate (k%model, source=model)
      k%cf = chain_coef(model)
      nl = k%cf%n
      n = size(y0, 2)
      k%nl = nl
      k%opt = opt
      k%nan = ieee_value(k%nan, ieee_quiet_nan)
      bounds = link_flip_bounds(k%cf%gl(1:nl))
      margin = bound_margin*sum(k%cf%gl(1:nl))
      k%escale = 2.0_dp*sum(k%cf%gl(1:nl))
      k%nv = opt%vectors
      k%dq = 0.0_dp
      k%dw = 0.0_dp
      k%vok = 0.0_dp
      if (k%nv > 0) k%v0 = initial_vectors(2*nl)
      allocate (k%can(nl, n))
      associate (res => k%res)
         res%n = n
         allocate (res%t_flip1(n), res%t_flip2(n), res%t_flip(n), res%t_flip_link(nl, n), &
                   res%energy0(n), res%energy_error(n), res%t_stop(n), res%final(2*nl, n), &
                   res%lyapunov(n), res%status(n), res%steps(n))
         allocate (res%megno(n), res%megno_y(n), res%fli(n), res%sali(n), res%gali2(n))
         res%lyapunov = k%nan
         res%megno = k%nan; res%megno_y = k%nan; res%fli = k%nan; res%sali = k%nan
         res%gali2 = k%nan
         do j = 1, n   ! as integrate_trajectories
            res%energy0(j) = model%energy(0.0_dp, y0(:, j))
            do i = 1, nl
               k%can(i, j) = .not. (res%energy0(j) < bounds(i) - margin)
            end do
            res%final(:, j) = y0(:, j)
            res%t_stop(j) = 0.0_dp
            res%steps(j) = 0
            res%energy_error(j) = 0.0_dp
            res%t_flip_link(:, j) = -1.0_dp
            res%status(j) = merge(st_end, st_cannot_flip, any(k%can(1:nl, j)))
            todo(j) = opt%n_steps >= 1
            if (opt%n_steps < 1) then
               res%status(j) = st_end
            else if (.not. (any(k%can(1:nl, j)) .or. .not. opt%skip_cannot_flip .or. &
                            k%nv > 0)) then
               res%energy_error(j) = k%nan
               todo(j) = .false.
            end if
         end do
      end associate
      k%y0 = y0
      call refill_lanes(k, todo)
      call first_flips(k%res, nl)
      res = k%res
   end subroutine integrate_chain_lanes

   !> One RK4 step of every lane (and of the indicators' vectors), then a vectorized
   !> count of the lanes with a possible event: an angle out of its window, the last
   !> step, a state not finite or beyond the bound, carried sin and cos due, a fresh
   !> lane.
   subroutine chain_step(self, events)
      class(chain_lanes_t), intent(inout) :: self  !! the lanes
      logical, intent(out) :: events               !! some lane may hold an event
      real(dp) :: n_events
      self%p = self%q
      self%pd = self%qd
      if (self%nv > 0) then
         call tangent_guard(self)
         call chain_rk4_lanes(self%cf, self%opt%h, self%q, self%qd, self%e, self%ts, &
                              self%tc, self%nv, self%dq, self%dw)
         call vectors_update(self)
      else
         call chain_rk4_lanes(self%cf, self%opt%h, self%q, self%qd, self%e, self%ts, self%tc)
      end if
      call count_events(self%nl, self%q, self%qd, self%e, self%e0, self%active, self%fresh, &
                        self%lo, self%hi, self%err, self%ks, self%left, self%sync, n_events)
      events = .not. (n_events == 0.0_dp)   ! true for NaN
   end subroutine chain_step

   !> After a step: each lane's largest energy error, step count and steps left, and
   !> a count of the lanes with a possible event: an angle out of its window, the last
   !> step, a state not finite or beyond half the bound, carried sin and cos due, a
   !> fresh lane (arrays of the lanes as arguments, so that gcc sees that they do not
   !> overlap and vectorizes the loops).
   pure subroutine count_events(nl, q, qd, e, e0, active, fresh, lo, hi, err, ks, left, &
                                sync, n_events)
      integer, intent(in) :: nl                               !! links N
      real(dp), intent(in), dimension(w, nm) :: q, qd         !! state [rad, rad/s]
      real(dp), intent(in), dimension(w) :: e, e0             !! energy before the step, E(0) [J]
      real(dp), intent(in), dimension(w) :: active, fresh     !! 1: holds a trajectory; just loaded
      real(dp), intent(in), dimension(w, nm) :: lo, hi        !! the angles' windows [rad]
      real(dp), intent(inout) :: err(w)                       !! largest |E - E(0)| [J]
      integer(i8), intent(inout) :: ks(w)                     !! steps taken
      real(dp), intent(inout) :: left(w), sync(w)             !! steps left, to the next resync
      real(dp), intent(out) :: n_events                       !! > 0 or NaN: some event
      real(dp) :: tot(w)
      integer :: i, l
      n_events = 0.0_dp
      do l = 1, w
         err(l) = max(err(l), abs(e(l) - e0(l)))
         ks(l) = ks(l) + 1
         left(l) = left(l) - 1.0_dp
         sync(l) = sync(l) - 1.0_dp
         n_events = n_events + active(l)*(0.5_dp*(1.0_dp - sign(1.0_dp, left(l) - 0.5_dp)) &
                                          + max(0.0_dp, 0.5_dp - sync(l)) + fresh(l))
      end do
      do l = 1, w
         tot(l) = 0.0_dp
      end do
      do i = 1, nl
         do l = 1, w
            tot(l) = tot(l) + (abs(q(l, i)) + abs(qd(l, i)))
            n_events = n_events + active(l)*(max(0.0_dp, lo(l, i) - q(l, i)) &
                                             + max(0.0_dp, q(l, i) - hi(l, i)))
         end do
      end do
      do l = 1, w   ! (half the bound: the rare path decides exactly)
         n_events = n_events + active(l)*(abs(tot(l) - tot(l)) &
                                          + max(0.0_dp, tot(l) - 0.5_dp*chain_lane_bound))
      end do
   end subroutine count_events

   !> The vectors of an RK4 stage: xq = δq + hs δq̇', xw = δq̇ + hs δq̈' from the
   !> previous stage's slopes (pw = its δq̇, pb = its δq̈), vectors 1:nv.
   pure subroutine offset_vectors(n, nv, hs, dq, dw, pw, pb, xq, xw)
      integer, intent(in) :: n, nv                        !! links, vectors
      real(dp), intent(in) :: hs                          !! the stage's offset [s]
      real(dp), intent(in) :: dq(w, nm, 2), dw(w, nm, 2)  !! vectors at the step start
      real(dp), intent(in) :: pw(w, nm, 2), pb(w, nm, 2)  !! previous stage's slopes
      real(dp), intent(out) :: xq(w, nm, 2), xw(w, nm, 2) !! the stage's vectors
      integer :: i, k, l
      do k = 1, nv
         do i = 1, n
            do l = 1, w
               xq(l, i, k) = dq(l, i, k) + hs*pw(l, i, k)
               xw(l, i, k) = dw(l, i, k) + hs*pb(l, i, k)
            end do
         end do
      end do
   end subroutine offset_vectors

   !> Before a step with vectors: a lane whose step turns a link by more than
   !> `max_tangent_turn` (h max |q̇_i|) gets no indicators; its vectors are set to zero,
   !> so that the step's arithmetic on them stays finite.
   subroutine tangent_guard(self)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      real(dp) :: over, g(w)
      integer :: i, l
      do l = 1, w
         g(l) = 0.0_dp
      end do
      do i = 1, self%nl
         do l = 1, w
            g(l) = max(g(l), abs(self%qd(l, i)))
         end do
      end do
      over = 0.0_dp
      do l = 1, w
         over = over + self%vok(l)*max(0.0_dp, self%opt%h*g(l) - max_tangent_turn)
      end do
      if (over == 0.0_dp) return
      do l = 1, w
         if (self%vok(l) > 0.0_dp .and. self%opt%h*g(l) > max_tangent_turn) &
            call vectors_fail(self, l)
      end do
   end subroutine tangent_guard

   !> After a step: every vector of a lane with indicators renormalised to length 1,
   !> and ln of vector 1's growth into the MEGNO sums of the step [ks h, (ks + 1) h]
   !> (`megno_step`, as `chaos_indicators` does with vector 1). A lane whose vector's
   !> |δ|² is not a positive normal number below `diverged_bound`² gets no indicators.
   !> Lanes without indicators keep their vectors (idle lanes: bounded; failed: zero).
   subroutine vectors_update(self)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      real(dp), dimension(w) :: n2, sc, lnn2, dl, ta, tb
      real(dp) :: bad
      integer :: i, k, l, nl
      nl = self%nl
      do k = 1, self%nv
         do l = 1, w
            n2(l) = 0.0_dp
         end do
         do i = 1, nl
            do l = 1, w
               n2(l) = n2(l) + (self%dq(l, i, k)**2 + self%dw(l, i, k)**2)
            end do
         end do
         bad = 0.0_dp
         do l = 1, w
            bad = bad + self%vok(l)*norm_outside(n2(l))
         end do
         if (bad > 0.0_dp) then   ! rare: a vector collapsed, overflowed or ran away
            do l = 1, w
               if (self%vok(l) > 0.0_dp .and. norm_outside(n2(l)) > 0.0_dp) then
                  call vectors_fail(self, l)
                  n2(l) = 1.0_dp
               end if
            end do
         end if
         do l = 1, w   ! (lanes without indicators: |δ|² taken as 1)
            n2(l) = self%vok(l)*n2(l) + (1.0_dp - self%vok(l))
            sc(l) = 1.0_dp/sqrt(n2(l))
         end do
         do i = 1, nl
            do l = 1, w
               self%dq(l, i, k) = self%dq(l, i, k)*sc(l)
               self%dw(l, i, k) = self%dw(l, i, k)*sc(l)
            end do
         end do
         if (k == 1) then
            call log_lanes(n2, lnn2)
            do l = 1, w
               dl(l) = 0.5_dp*lnn2(l)
               ta(l) = real(self%ks(l), dp)*self%opt%h
               tb(l) = real(self%ks(l) + 1, dp)*self%opt%h
            end do
            call megno_step_lanes(dl, ta, tb, self%lg, self%ig, self%yy, self%sy)
         end if
      end do
   end subroutine vectors_update

   !> 1 where |δ|² = x is not a positive normal number below `diverged_bound`² (0,
   !> subnormal, negative, too large, Inf, NaN), else 0: from the bits (positive
   !> doubles order as their bit patterns; no floating-point compare on NaN).
   pure elemental real(dp) function norm_outside(x)
      real(dp), intent(in) :: x  !! |δ|²
      integer(i8), parameter :: lo = transfer(tiny(1.0_dp), 0_i8)
      integer(i8), parameter :: hi = transfer(diverged_bound*diverged_bound, 0_i8)
      integer(i8) :: ix
      ix = transfer(x, 0_i8)
      norm_outside = merge(0.0_dp, 1.0_dp, ix >= lo .and. ix < hi)
   end function norm_outside

   !> Lane ll's indicators fail (NaN at its end): its vectors are set to zero.
   subroutine vectors_fail(self, ll)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: ll                   !! lane
      self%ind_ok(ll) = .false.
      self%vok(ll) = 0.0_dp
      self%dq(ll, :, :) = 0.0_dp
      self%dw(ll, :, :) = 0.0_dp
   end subroutine vectors_fail

   !> Every lane's events, decided exactly (`chain_check_lane`).
   subroutine chain_check(self, ended)
      class(chain_lanes_t), intent(inout) :: self  !! the lanes
      logical, intent(out) :: ended(w)    !! each lane's trajectory is done
      integer :: l
      do l = 1, w
         call chain_check_lane(self, l, ended(l))
      end do
   end subroutine chain_check

   !> Lane l's events, decided exactly: a runaway state, a due resync, the flips of
   !> its links (interpolated within the step), the stop rule. An idle lane has none.
   subroutine chain_check_lane(self, l, ended)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                     !! lane
      logical, intent(out) :: ended                !! its trajectory is done
      real(dp) :: mk, qc
      integer :: i, nl
      ended = .false.
      if (self%lane_ic(l) == 0) return
      nl = self%nl
      self%fresh(l) = 0.0_dp
      if (runaway(self, l)) then
         ended = .true.
         return
      end if
      if (self%sync(l) < 0.5_dp) call resync(self, l)
      do i = 1, nl
         mk = turn(self%q(l, i))
         if (mk /= self%nk(l, i)) then
            if (self%tf(l, i) < 0.0_dp) then
               qc = half_pi + two_pi*max(mk, self%nk(l, i))
               self%tf(l, i) = (real(self%ks(l) - 1, dp) + (qc - self%p(l, i)) &
                                /(self%q(l, i) - self%p(l, i)))*self%opt%h
            end if
            self%nk(l, i) = mk
            call set_window(self, l, i)
         end if
      end do
      ended = self%ks(l) >= self%opt%n_steps
      select case (self%opt%stop_rule)
      case (stop_both)
         ended = ended .or. all(self%tf(l, 1:nl) >= 0.0_dp .or. .not. self%lane_can(l, 1:nl))
      case (stop_either)
         ended = ended .or. any(self%tf(l, 1:nl) >= 0.0_dp)
      end select
   end subroutine chain_check_lane

   !> Put initial condition j into lane l, or the idle state (j = 0).
   subroutine chain_load(self, l, j)
      class(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                    !! lane
      integer, intent(in) :: j                     !! initial condition, 0: none
      integer :: ii, nl
      nl = self%nl
      self%ks(l) = 0
      self%left(l) = real(self%opt%n_steps, dp)
      self%err(l) = 0.0_dp
      self%tf(l, :) = -1.0_dp
      self%lane_ic(l) = j
      if (j > 0) then
         self%q(l, 1:nl) = self%y0(1:nl, j)
         self%qd(l, 1:nl) = self%y0(nl + 1:2*nl, j)
         self%e0(l) = self%res%energy0(j)
         self%lane_can(l, 1:nl) = self%can(1:nl, j)
         self%active(l) = 1.0_dp
         self%fresh(l) = 1.0_dp
      else
         self%q(l, :) = -half_pi
         self%qd(l, :) = 0.0_dp
         self%e0(l) = 0.0_dp
         self%lane_can(l, :) = .false.
         self%active(l) = 0.0_dp
         self%fresh(l) = 0.0_dp
      end if
      do ii = 1, nl
         self%nk(l, ii) = turn(self%q(l, ii))
         call set_window(self, l, ii)
      end do
      call resync(self, l)
      if (self%nv > 0) then
         do ii = 1, self%nv
            self%dq(l, 1:nl, ii) = self%v0(1:nl, ii)
            self%dw(l, 1:nl, ii) = self%v0(nl + 1:2*nl, ii)
         end do
         self%lg(l) = 0.0_dp; self%ig(l) = 0.0_dp; self%yy(l) = 0.0_dp; self%sy(l) = 0.0_dp
         self%ind_ok(l) = .true.
         self%vok(l) = self%active(l)
      end if
   end subroutine chain_load

   !> Set the carried sines and cosines of lane ll exactly.
   subroutine resync(self, ll)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: ll                   !! lane
      integer :: ii
      do ii = 1, self%nl
         call sincos_exact(self%q(ll, ii), self%ts(ll, ii), self%tc(ll, ii))
      end do
      self%sync(ll) = real(resync_steps, dp)
   end subroutine resync

   !> The window of link ii's angle in lane ll: between two upward verticals, shrunk
   !> by window_margin so that rounding never hides a crossing.
   subroutine set_window(self, ll, ii)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: ll, ii               !! lane, link
      self%lo(ll, ii) = half_pi + two_pi*self%nk(ll, ii) + window_margin
      self%hi(ll, ii) = half_pi + two_pi*(self%nk(ll, ii) + 1.0_dp) - window_margin
   end subroutine set_window

   !> The index k of the last upward vertical π/2 + 2π k at or below the angle x
   !> [rad], as a real (the per-trajectory path's floor, clamped to ±2^52 so that no
   !> conversion to integer overflows for a state near the runaway bound).
   pure real(dp) function turn(x)
      real(dp), intent(in) :: x  !! angle [rad]
      real(dp), parameter :: big = 4503599627370496.0_dp   ! 2^52
      turn = real(floor(min(max((x - half_pi)*inv_two_pi, -big), big), i8), dp)
   end function turn

   !> Lane ll's state is not finite or not below `chain_lane_bound` (the
   !> integrators' `state_ok`; no ordered comparison on NaN).
   logical function runaway(self, ll)
      type(chain_lanes_t), intent(in) :: self  !! the lanes
      integer, intent(in) :: ll                !! lane
      real(dp) :: ss
      ss = sum(abs(self%q(ll, 1:self%nl))) + sum(abs(self%qd(ll, 1:self%nl)))
      runaway = .true.
      if (ss - ss == 0.0_dp) runaway = .not. (ss < chain_lane_bound)
   end function runaway

   !> Store the results of the trajectory in lane l as those of initial condition j.
   subroutine chain_finish(self, l, j)
      class(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                    !! lane
      integer, intent(in) :: j                    !! its initial condition
      integer(i8) :: kk
      real(dp) :: y(2*self%nl)
      integer :: nl
      nl = self%nl
      kk = self%ks(l)
      associate (res => self%res)
         if (runaway(self, l)) then   ! the step is not taken: the last state before it
            kk = kk - 1
            res%final(1:nl, j) = self%p(l, 1:nl)
            res%final(nl + 1:2*nl, j) = self%pd(l, 1:nl)
            res%status(j) = st_nonfinite
            res%energy_error(j) = self%nan
         else
            res%final(1:nl, j) = self%q(l, 1:nl)
            res%final(nl + 1:2*nl, j) = self%qd(l, 1:nl)
            y = res%final(:, j)
            self%err(l) = max(self%err(l), &
                               abs(self%model%energy(real(kk, dp)*self%opt%h, y) - self%e0(l)))
            res%energy_error(j) = self%err(l)/self%escale
            if (kk < self%opt%n_steps) res%status(j) = st_flipped
         end if
         res%t_stop(j) = real(kk, dp)*self%opt%h
         res%steps(j) = int(kk)
         res%t_flip_link(:, j) = self%tf(l, 1:nl)
         if (self%nv > 0 .and. res%status(j) /= st_nonfinite .and. kk >= 1) then
            if (self%ind_ok(l)) call finish_indicators(self, j, l, res%t_stop(j))
         end if
      end associate
   end subroutine chain_finish

   !> The indicators of trajectory jj from lane ll at its end time t_b [s]
   !> (`integrate_trajectories`' choice of `chaos_indicators`' sample).
   subroutine finish_indicators(self, jj, ll, t_b)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: jj, ll               !! trajectory, lane
      real(dp), intent(in) :: t_b                 !! end time [s]
      real(dp) :: v(2*self%nl, 2)
      integer :: info, k, nl
      self%res%fli(jj) = self%lg(ll)
      self%res%megno_y(jj) = self%yy(ll)
      self%res%megno(jj) = self%sy(ll)/t_b
      if (self%nv < 2) return
      nl = self%nl
      do k = 1, 2
         v(1:nl, k) = self%dq(ll, 1:nl, k)
         v(nl + 1:, k) = self%dw(ll, 1:nl, k)
      end do
      self%res%sali(jj) = sali(v(:, 1), v(:, 2))
      call gali(v, self%res%gali2(jj), info)
      if (info /= 0) self%res%gali2(jj) = self%nan
   end subroutine finish_indicators

end module dpend_chain_lanes
