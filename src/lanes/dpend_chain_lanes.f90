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
!> flip bounds too). The state steps in the lanes; each lane's vectors step by
!> `chain_tangent_lane`, the per-trajectory path's tangent step (`tangent_t%propagate`:
!> the chain model's own Jacobian on the step's cubic Hermite interpolant, ⌈hω/θ⌉
!> substeps of RK4), which test chain_lanes/tangent_matches_model compares with it.
!> Only the vectors the indicator needs are carried (the path carries 2N): a
!> trajectory whose state runs away, or whose vectors fail (not finite, too many
!> substeps), has NaN indicators, as on the path (the path also fails when one of its
!> other vectors does: not met in practice, all grow at most like vector 1).
!> DPEND_SWEEP_KERNEL=trajectory in the environment sends every chain to the
!> per-trajectory path (`chain_kernel_choice`); two links are not affected.
!>
!> Reproducibility: lanes never mix and every loop runs the full width (idle lanes
!> hang at rest), so results are bitwise independent of threads and blocks.
module dpend_chain_lanes
   use dpend_kinds, only: dp, i8, pi, half_pi
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: diverged_bound
   use dpend_strings, only: printable
   use dpend_model, only: model_t
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t, lane_kernel_t, &
      refill_lanes, resync_steps, stop_both, stop_either, st_end, st_flipped, st_cannot_flip, &
      st_nonfinite, link_flip_bounds, first_flips, bound_margin
   use dpend_pendulum_kernel, only: sincos_near_lanes, sincos_exact
   use dpend_limits, only: max_tangent_substeps
   use dpend_indicator_math, only: initial_vectors, sali, gali, megno_step
   use dpend_tangent, only: max_tangent_size, mat_mul
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   implicit none
   private
   public :: max_lane_links, chain_coef_t, chain_coef, chain_lanes_serve, chain_kernel_choice
   public :: chain_accel_lanes, chain_rk4_lanes, integrate_chain_lanes, chain_tangent_lane

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
   !> Largest ω·h per tangent substep [1] (`tangent_t`'s theta, dpend_tangent)
   real(dp), parameter :: tangent_theta = 0.1_dp

   !> The chain's constants for the lanes [SI].
   type :: chain_coef_t
      integer :: n = 0                     !! links N
      real(dp) :: k(nm, nm) = 0.0_dp       !! K_ij of M_ij = K_ij cos(q_i − q_j) [kg m²]
      real(dp) :: gl(nm) = 0.0_dp          !! G_i of V = Σ G_i sin q_i [J]
   end type chain_coef_t

   !> The lanes of a batch of chains: the batch, its results, and every lane's
   !> state, flips and indicator sums (structure of arrays).
   type, extends(lane_kernel_t) :: chain_lanes_t
      ! the lanes' arrays first (multiples of 64 bytes from the start of the object:
      ! aligned wherever the object is, as the kernel's vector loads want them)
      real(dp), dimension(w, nm) :: q, qd, ts, tc, p, pd, lo, hi, nk, tf
      real(dp), dimension(w, nm) :: fa, fb
      real(dp), dimension(w) :: e, e0, err, active, fresh, left, sync
      real(dp), dimension(w) :: lg, ig, yy, sy
      integer(i8) :: ks(w)                           !! steps taken
      type(chain_coef_t) :: cf                       !! the chain's constants
      integer :: lane_ic(w)                          !! trajectory held, 0: none
      logical :: lane_can(w, nm)
      logical :: ind_ok(w), jfresh(w)
      class(model_t), allocatable :: model           !! the chain
      integer :: nl = 0                              !! links N
      type(batch_options_t) :: opt                   !! step, length, stop rule
      real(dp), allocatable :: y0(:, :)              !! (2N, n) initial states
      logical, allocatable :: can(:, :)              !! (N, n) links that can flip
      type(batch_result_t) :: res                    !! the results
      real(dp) :: escale = 1.0_dp                    !! unit of the energy error [J]
      real(dp) :: nan
      ! the indicators (opt%vectors 1 or 2): vectors, Jacobians at the step start,
      ! vector fields at the step ends (fa, fb), running sums of vector 1 (lg, ig, yy,
      ! sy; dpend_indicators)
      integer :: nv = 0
      real(dp), allocatable :: dv(:, :, :), jl(:, :, :), v0(:, :)
      logical :: stale = .true.   !! f at the step start to be computed anew
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
      real(dp) :: mm(w, nm, nm), u(w, nm, nm), wq(w, nm), dinv(w, nm), t(w)
      real(dp) :: kij, sij
      integer :: n, i, j, k, l
      n = cf%n
      do i = 1, n
         do l = 1, w
            wq(l, i) = min(qd(l, i)*qd(l, i), chain_lane_bound*chain_lane_bound)
            a(l, i) = -cf%gl(i)*c(l, i)
         end do
      end do
      ! M below the diagonal and f: sin(q_i − q_j) enters f_i and f_j with opposite signs
      do j = 1, n
         do i = j + 1, n
            kij = cf%k(i, j)
            do l = 1, w
               mm(l, i, j) = kij*(c(l, i)*c(l, j) + s(l, i)*s(l, j))
               sij = kij*(s(l, i)*c(l, j) - c(l, i)*s(l, j))
               a(l, i) = a(l, i) - sij*wq(l, j)
               a(l, j) = a(l, j) + sij*wq(l, i)
            end do
         end do
      end do
      if (present(e)) then
         do l = 1, w
            e(l) = 0.0_dp
         end do
         do i = 1, n
            do l = 1, w
               t(l) = 0.5_dp*cf%k(i, i)*qd(l, i)
            end do
            do j = 1, i - 1
               do l = 1, w
                  t(l) = t(l) + mm(l, i, j)*qd(l, j)
               end do
            end do
            do l = 1, w
               e(l) = e(l) + (t(l)*qd(l, i) + cf%gl(i)*s(l, i))
            end do
         end do
      end if
      ! M = L D Lᵀ (L unit lower, in mm below the diagonal; u_ik = L_ik D_k): D_j ≥ the
      ! least eigenvalue of M > 0 (clamped at tiny, as dpend_chain's cholesky)
      do j = 1, n
         do l = 1, w
            t(l) = cf%k(j, j)
         end do
         do k = 1, j - 1
            do l = 1, w
               t(l) = t(l) - mm(l, j, k)*u(l, j, k)
            end do
         end do
         do l = 1, w
            dinv(l, j) = 1.0_dp/max(t(l), tiny(1.0_dp))
         end do
         do i = j + 1, n
            do k = 1, j - 1
               do l = 1, w
                  mm(l, i, j) = mm(l, i, j) - mm(l, i, k)*u(l, j, k)
               end do
            end do
            do l = 1, w
               u(l, i, j) = mm(l, i, j)
               mm(l, i, j) = mm(l, i, j)*dinv(l, j)
            end do
         end do
      end do
      ! L z = f, then Lᵀ q̈ = D⁻¹ z
      do i = 2, n
         do k = 1, i - 1
            do l = 1, w
               a(l, i) = a(l, i) - mm(l, i, k)*a(l, k)
            end do
         end do
      end do
      do i = n, 1, -1
         do l = 1, w
            a(l, i) = a(l, i)*dinv(l, i)
         end do
         do k = i + 1, n
            do l = 1, w
               a(l, i) = a(l, i) - mm(l, k, i)*a(l, k)
            end do
         end do
      end do
   end subroutine chain_accel_lanes

   !> One classical RK4 step of size h on every lane; `e` is the energy of the state
   !> before the step [J]. `ts`, `tc` hold sin and cos of the angles on entry and of
   !> the new angles on return (the stages' and the new state's from the step start's
   !> by `sincos_near_lanes`, exact for a lane whose offset exceeds its range).
   pure subroutine chain_rk4_lanes(cf, h, q, qd, e, ts, tc)
      type(chain_coef_t), intent(in) :: cf           !! constants
      real(dp), intent(in) :: h                      !! step [s]
      real(dp), intent(inout) :: q(w, nm)            !! angles [rad]
      real(dp), intent(inout) :: qd(w, nm)           !! rates [rad/s]
      real(dp), intent(out) :: e(w)                  !! energy before the step [J]
      real(dp), intent(inout) :: ts(w, nm), tc(w, nm)  !! sin q, cos q
      real(dp), dimension(w, nm) :: ka, kb, kc, kd, vb, vc, vd, x, d, s, c
      real(dp) :: hh, h6
      integer :: n, i, l
      n = cf%n
      hh = 0.5_dp*h
      h6 = h/6.0_dp
      call chain_accel_lanes(cf, ts, tc, qd, ka, e)
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + hh*qd(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vb(l, i) = qd(l, i) + hh*ka(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      call chain_accel_lanes(cf, s, c, vb, kb)
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + hh*vb(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vc(l, i) = qd(l, i) + hh*kb(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      call chain_accel_lanes(cf, s, c, vc, kc)
      do i = 1, n
         do l = 1, w
            x(l, i) = q(l, i) + h*vc(l, i)
            d(l, i) = x(l, i) - q(l, i)
            vd(l, i) = qd(l, i) + h*kc(l, i)
         end do
      end do
      call stage_trig(n, ts, tc, x, d, s, c)
      call chain_accel_lanes(cf, s, c, vd, kd)
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

   !> One lane's tangent step: the vectors v (2N, nv) carried over the RK4 step [t_a,
   !> t_a + h] from state yo to yn (vector fields fo, fn at its ends) as
   !> `tangent_t%propagate` (dpend_tangent) does for the per-trajectory path: the chain
   !> model's own Jacobian (`chain_t%jacobian`) at the substep ends and midpoints on the
   !> cubic Hermite interpolant of the step (`integrator_t%interpolate`), n = ⌈h ω/θ⌉
   !> substeps (ω = ‖J²‖∞^½, θ = 0.1), classical RK4 for the linear system. ja holds J
   !> at yo on entry, J at yn on return. stiff: more than `max_tangent_substeps`
   !> substeps were needed (v is left unchanged), or a component of v passed
   !> `max_tangent_size` (v is not propagated further).
   subroutine chain_tangent_lane(model, t_a, h, yo, yn, fo, fn, ja, v, stiff)
      class(model_t), intent(in) :: model            !! the chain, N links
      real(dp), intent(in) :: t_a                    !! start of the step [s]
      real(dp), intent(in) :: h                      !! step [s]
      real(dp), intent(in) :: yo(:), yn(:)           !! states (q, q̇) at the ends (2N)
      real(dp), intent(in) :: fo(:), fn(:)           !! vector fields there (2N)
      real(dp), intent(inout) :: ja(:, :)            !! Jacobian at yo in, at yn out
      real(dp), intent(inout) :: v(:, :)             !! tangent vectors (2N, nv)
      logical, intent(out) :: stiff                  !! too many substeps
      real(dp), dimension(size(yo), size(yo)) :: jm, jb, ja2
      real(dp), dimension(size(yo)) :: ym, dy
      real(dp), dimension(size(yo), size(v, 2)) :: k1, k2, k3, k4
      real(dp) :: hs, ta, omega, th
      integer :: n, i
      call mat_mul(ja, ja, ja2)
      omega = sqrt(maxval(sum(abs(ja2), dim=2)))
      stiff = .not. (abs(h)*omega <= tangent_theta*real(max_tangent_substeps, dp))
      if (stiff) return
      n = max(1, ceiling(abs(h)*omega/tangent_theta))
      hs = h/real(n, dp)
      dy = yn - yo
      do i = 1, n
         ta = t_a + real(i - 1, dp)*hs
         th = ((ta + 0.5_dp*hs) - t_a)/h
         ym = (1.0_dp - th)*yo + th*yn + th*(th - 1.0_dp)*((1.0_dp - 2.0_dp*th)*dy &
              + (th - 1.0_dp)*h*fo + th*h*fn)
         call model%jacobian(ta + 0.5_dp*hs, ym, jm)
         if (i == n) then
            call model%jacobian(ta + hs, yn, jb)
         else
            th = ((ta + hs) - t_a)/h
            ym = (1.0_dp - th)*yo + th*yn + th*(th - 1.0_dp)*((1.0_dp - 2.0_dp*th)*dy &
                 + (th - 1.0_dp)*h*fo + th*h*fn)
            call model%jacobian(ta + hs, ym, jb)
         end if
         call mat_mul(ja, v, k1)
         call mat_mul(jm, v + (0.5_dp*hs)*k1, k2)
         call mat_mul(jm, v + (0.5_dp*hs)*k2, k3)
         call mat_mul(jb, v + hs*k3, k4)
         v = v + (hs/6.0_dp)*(k1 + 2.0_dp*(k2 + k3) + k4)
         ! as `tangent_propagate`: a substep grows v by about e^θ at most, so checking
         ! each one keeps the next far from overflow (the lane's indicators fail)
         if (.not. all(abs(v) <= max_tangent_size)) then
            stiff = .true.
            return
         end if
         ja = jb
      end do
   end subroutine chain_tangent_lane

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
      if (k%nv > 0) then
         allocate (k%dv(2*nl, k%nv, w), k%jl(2*nl, 2*nl, w))
         k%v0 = initial_vectors(2*nl)
         k%fa = 0.0_dp
         k%fb = 0.0_dp
      end if
      k%stale = .true.
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
      if (self%nv > 0 .and. self%stale) then   ! a lane loaded or resynced: f at the start anew
         call chain_accel_lanes(self%cf, self%ts, self%tc, self%qd, self%fa)
         self%stale = .false.
      end if
      call chain_rk4_lanes(self%cf, self%opt%h, self%q, self%qd, self%e, self%ts, self%tc)
      if (self%nv > 0) call tangent_step(self)
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

   !> The indicators' step of every lane with a trajectory (after the state's): the
   !> vectors by `chain_tangent_lane`, renormalised to length 1, the running sums
   !> by `megno_step` (as `chaos_indicators`, vector 1). A lane whose state ran away
   !> or whose vectors fail is left to the rare path (indicators NaN).
   subroutine tangent_step(self)
      type(chain_lanes_t), intent(inout) :: self  !! the lanes
      real(dp) :: yo(2*self%nl), yn(2*self%nl), fo(2*self%nl), fn(2*self%nl)
      real(dp) :: nrm, dl(self%nv), t_b, t_a
      logical :: stiff
      integer :: ll, kv, nl
      nl = self%nl
      call chain_accel_lanes(self%cf, self%ts, self%tc, self%qd, self%fb)
      do ll = 1, w
         if (self%lane_ic(ll) == 0 .or. .not. self%ind_ok(ll)) cycle
         if (runaway(self, ll)) cycle
         yo(1:nl) = self%p(ll, 1:nl); yo(nl + 1:) = self%pd(ll, 1:nl)
         yn(1:nl) = self%q(ll, 1:nl); yn(nl + 1:) = self%qd(ll, 1:nl)
         fo(1:nl) = self%pd(ll, 1:nl); fo(nl + 1:) = self%fa(ll, 1:nl)
         fn(1:nl) = self%qd(ll, 1:nl); fn(nl + 1:) = self%fb(ll, 1:nl)
         t_a = real(self%ks(ll), dp)*self%opt%h   ! (ks counts the step just after)
         t_b = real(self%ks(ll) + 1, dp)*self%opt%h
         if (self%jfresh(ll)) then
            call self%model%jacobian(t_a, yo, self%jl(:, :, ll))
            self%jfresh(ll) = .false.
         end if
         call chain_tangent_lane(self%model, t_a, self%opt%h, yo, yn, fo, fn, &
                                 self%jl(:, :, ll), self%dv(:, :, ll), stiff)
         if (stiff .or. .not. all(ieee_is_finite(self%dv(:, :, ll)))) then
            self%ind_ok(ll) = .false.
            cycle
         end if
         do kv = 1, self%nv
            nrm = norm2(self%dv(:, kv, ll))
            if (.not. (nrm > 0.0_dp .and. nrm < diverged_bound)) then
               self%ind_ok(ll) = .false.
               exit
            end if
            self%dv(:, kv, ll) = self%dv(:, kv, ll)/nrm
            dl(kv) = log(nrm)
         end do
         if (.not. self%ind_ok(ll)) cycle
         call megno_step(dl(1), t_a, t_b, 0.0_dp, self%lg(ll), self%ig(ll), self%yy(ll), &
                         self%sy(ll))
      end do
      self%fa = self%fb
   end subroutine tangent_step

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
         self%dv(:, :, l) = self%v0(:, 1:self%nv)
         self%lg(l) = 0.0_dp; self%ig(l) = 0.0_dp; self%yy(l) = 0.0_dp; self%sy(l) = 0.0_dp
         self%ind_ok(l) = .true.
         self%jfresh(l) = .true.
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
      self%stale = .true.
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
      integer :: info
      self%res%fli(jj) = self%lg(ll)
      self%res%megno_y(jj) = self%yy(ll)
      self%res%megno(jj) = self%sy(ll)/t_b
      if (self%nv < 2) return
      self%res%sali(jj) = sali(self%dv(:, 1, ll), self%dv(:, 2, ll))
      call gali(self%dv(:, 1:2, ll), self%res%gali2(jj), info)
      if (info /= 0) self%res%gali2(jj) = self%nan
   end subroutine finish_indicators

end module dpend_chain_lanes
