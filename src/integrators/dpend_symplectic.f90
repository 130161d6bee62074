!> Symplectic and symmetric one-step methods on the canonical variables
!> y = (q1, q2, p1, p2) of the non-separable H(q, p) = ½ pᵀM(q)⁻¹p + V(q):
!>
!> | name       | scheme                                           | order |
!> |------------|--------------------------------------------------|-------|
!> | `midpoint` | implicit midpoint rule = 1-stage Gauss           | 2     |
!> | `gauss4/6/8` | Gauss–Legendre collocation, s = 2, 3, 4 stages | 2s    |
!> | `verlet`   | generalized Störmer–Verlet (non-separable H)     | 2     |
!> | `yoshida4` | triple jump of `verlet`                          | 4     |
!> | `comp6`    | Kahan–Li s9odr6a, 9 substeps of `verlet`         | 6     |
!> | `comp8`    | Kahan–Li s17odr8a, 17 substeps of `verlet`       | 8     |
!>
!> and Tao's explicit extended-phase-space methods in `dpend_tao`. The Gauss methods
!> also accept models without a Hamiltonian (damped, driven): they collocate the
!> first-order field on (q, q̇) instead (`gauss_advance_field`); the others refuse them.
!>
!> All of them derive from `symplectic_t`, which owns the driver-facing `step`:
!> it detects the start of a new trajectory, calls the method's `advance`, and
!> commits (t, y) only on success. A method binds `advance` (one step of its
!> scheme, applied to y in place through `accumulate`) and its properties.
!>
!> **Implicit stages are solved to roundoff** by fixed-point iteration from a
!> good starting guess (Gauss: the previous step's collocation polynomial,
!> GNI §VIII.6.1; Verlet: the previous step's force). Following GNI §VIII.6.2
!> the iteration runs until the scaled increment Δ_k vanishes or stops
!> decreasing; because the iteration error of a mechanical system hops between
!> the q and p blocks at every iteration (∂q̇/∂p and ∂ṗ/∂q dominate f'), "stops
!> decreasing" is judged over two iterations, Δ_k ≥ Δ_{k-2}, which is immune
!> to the resulting zig-zag of Δ_k. Stopped there, the iteration has converged
!> if Δ_k ≤ `iter_tol` (10³ ε, relative to the size of the state: roundoff),
!> and has failed otherwise (a growing increment: divergence, caught two
!> iterations after it starts, long before anything can overflow); after
!> `max_iter` = 50 iterations it has converged only if Δ_k ≤ `iter_tol`. A
!> failed step returns `stat_no_convergence` and leaves t, y unchanged. The
!> pendulum is not stiff, so the fixed-point iteration converges at every
!> step size of practical interest (contraction factor ≈ h ρ(A) ‖f'‖) and
!> needs neither a Jacobian nor an LU factorization of the 4s×4s system of a
!> simplified Newton iteration (gauss6 at h = 0.01 s: 8 iterations, 24
!> evaluations of f, ≈ 5–6 rk4 steps of time). Strong joint damping is stiff: on
!> (q, q̇) the Gauss methods then fall back to a simplified Newton iteration with the
!> model's Jacobian (`gauss_field_newton`).
!>
!> **Compensated summation** (Kahan; GNI §VIII.5) of
!> y_{n+1} = y_n + δ_n keeps the rounding error of the update in `comp(4)`;
!> switch it off with `compensated = .false.` (the roundoff study). The
!> compensation is reset whenever a new trajectory starts (`reset`, called
!> automatically when the state passed to `step` is not the one it returned
!> last). The summation relies on IEEE semantics and on parentheses being
!> honoured: never compile this module with -ffast-math, -Ofast,
!> -fassociative-math or -fno-protect-parens (FMA contraction is harmless: the
!> compensated update has no products).
!>
!> References: E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration,
!> 2nd ed., Springer 2006 (GNI).
module dpend_symplectic
   use, intrinsic :: iso_fortran_env, only: qp => real128
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_state, max_dof
   use dpend_integrator, only: integrator_t, stat_ok, stat_no_convergence, stat_nonfinite, &
                               integrator_configure
   use dpend_method_options, only: method_options_t
   use dpend_lapack, only: dgetrf, dgetrs
   implicit none
   private
   public :: symplectic_t, gauss_t, verlet_t, composition_t
   public :: gauss, composition, gauss_tableau, accumulate, symplectic_reset
   public :: symplectic_configure
   public :: triple_jump, kahan_li_6, kahan_li_8
   public :: max_iter, iter_tol

   integer, parameter :: max_iter = 50  !! cap on fixed-point iterations per implicit solve
   !> An increment at or below this (relative to the state) is roundoff.
   real(dp), parameter :: iter_tol = 1.0e3_dp*epsilon(1.0_dp)
   integer, parameter :: it_continue = 0   !! verdict: iterate again
   integer, parameter :: it_converged = 1  !! verdict: converged to roundoff
   integer, parameter :: it_failed = 2     !! verdict: diverging, stagnating or capped

   !> Common part of the canonical (q, p) methods: compensated summation and
   !> detection of a new trajectory. Symplectic, symmetric and canonical.
   type, extends(integrator_t), abstract :: symplectic_t
      !> Kahan-compensated update y_{n+1} = y_n + δ (GNI §VIII.5); set to .false.
      !> to see the uncompensated roundoff.
      logical :: compensated = .true.
      real(dp) :: comp(max_state) = 0.0_dp  !! compensation: the part of y lost to rounding
      real(dp), private :: y_last(max_state) = 0.0_dp  ! the state returned by the last step
      logical, private :: started = .false.    ! y_last is valid
   contains
      procedure(advance_i), deferred :: advance
      procedure :: step => symplectic_step
      procedure :: symplectic => true_property
      procedure :: symmetric => true_property
      procedure :: canonical => true_property
      procedure :: reset => symplectic_reset
      procedure :: configure => symplectic_configure
   end type symplectic_t

   abstract interface
      !> One step of the scheme from y by h, applied in place with
      !> `accumulate(y, e, δ, self%compensated)`. On failure `stat` /= stat_ok
      !> and the caller discards y and e.
      subroutine advance_i(self, model, t, y, e, h, stat)
         import :: symplectic_t, model_t, dp
         class(symplectic_t), intent(inout) :: self  !! the method
         class(model_t), intent(in) :: model         !! the system (Hamiltonian)
         real(dp), intent(in) :: t                   !! time at the start [s]
         real(dp), intent(inout) :: y(:)             !! state (q, p)
         real(dp), intent(inout) :: e(:)             !! compensation of y
         real(dp), intent(in) :: h                   !! step [s]
         integer, intent(out) :: stat                !! stat_ok or a failure code
      end subroutine advance_i
   end interface

   !> Gauss–Legendre collocation with s = 1..4 stages, order 2s (GNI §II.1.3,
   !> Table II.1.1; implementation GNI §VIII.6). s = 1 is the implicit midpoint
   !> rule. Stage increments Z_i = h Σ_j a_ij f(y + Z_j) are iterated; the update
   !> is δ = Σ_j d_j Z_j with dᵀ = bᵀA⁻¹ (GNI eq. VIII.6.5), which needs no
   !> further evaluation of f. The tableau is computed in quadruple precision,
   !> and A and d are applied as unevaluated sums of two doubles (a + a_lo,
   !> d + d_lo): with A and d merely rounded, the method is symplectic and
   !> symmetric only to O(ε), which shows as a linear energy drift in the
   !> roundoff regime (≈1e-14 after 10⁶ steps of gauss8 at h = 0.01 s, even with
   !> compensated summation; cf. Hairer, McLachlan, Razakarivony, "Achieving
   !> Brouwer's law with implicit Runge–Kutta methods", BIT 48, 231–243, 2008).
   !> The extra products cost a few flops per stage, nothing next to f.
   !>
   !> A model without a Hamiltonian (damped, driven: `hamiltonian()` false) is
   !> integrated by the same collocation on its first-order field y' = f(t, y),
   !> y = (q, q̇) (`gauss_advance_field`): order 2s, A-stable and symmetric, no
   !> longer symplectic (there is no symplectic structure to keep); the work
   !> integrals of `dpend_work` are then collocated with the state, to the same order.
   type, extends(symplectic_t) :: gauss_t
      integer :: s = 2             !! number of stages, 1..4
      real(dp) :: a(4, 4) = 0.0_dp !! Runge–Kutta matrix (leading s×s block)
      real(dp) :: b(4) = 0.0_dp    !! weights
      real(dp) :: c(4) = 0.0_dp    !! nodes, ascending
      real(dp) :: d(4) = 0.0_dp    !! dᵀ = bᵀA⁻¹
      real(dp), private :: a_lo(4, 4) = 0.0_dp  ! a + a_lo: A to twice double precision
      real(dp), private :: d_lo(4) = 0.0_dp     ! d + d_lo: d to twice double precision
      logical, private :: ready = .false.        ! the tableau is set up for s
      real(dp), private :: z_old(max_state, 4) = 0.0_dp  ! stage increments of the last step
      real(dp), private :: h_old = 0.0_dp        ! its step size
      logical, private :: have_z = .false.       ! z_old belongs to this trajectory
      real(dp), private :: w(4, 4) = 0.0_dp      ! extrapolation weights for ratio r_w
      real(dp), private :: r_w = 0.0_dp
      logical, private :: have_w = .false.
   contains
      procedure :: advance => gauss_advance
      procedure :: name => gauss_name
      procedure :: order => gauss_order
      procedure :: implicit => gauss_implicit
      procedure :: reset => gauss_reset
      procedure :: needs_hamiltonian => gauss_needs_hamiltonian
   end type gauss_t

   !> Generalized Störmer–Verlet method for non-separable H (GNI §VI.3, eq. 3.4),
   !> order 2, symmetric and symplectic:
   !>   p_{n+½} = p_n - h/2 ∂H/∂q(q_n, p_{n+½})                      (implicit in p)
   !>   q_{n+1} = q_n + h/2 [∂H/∂p(q_n, p_{n+½}) + ∂H/∂p(q_{n+1}, p_{n+½})]  (in q)
   !>   p_{n+1} = p_{n+½} - h/2 ∂H/∂q(q_{n+1}, p_{n+½})              (explicit)
   !> Both implicit equations are 2-dimensional fixed-point problems.
   type, extends(symplectic_t) :: verlet_t
      real(dp), private :: force(max_dof) = 0.0_dp  ! -∂H/∂q(q_{n}, p_{n-½}): first guess
      logical, private :: have_force = .false.
   contains
      procedure :: advance => verlet_advance
      procedure :: name => verlet_name
      procedure :: order => verlet_order
      procedure :: implicit => verlet_implicit
      procedure :: reset => verlet_reset
   end type verlet_t

   !> Symmetric composition Ψ_h = Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h} of a symmetric
   !> second-order base method Φ (GNI §II.4, §V.3.2). Every substep's update is
   !> summed with the composition's compensation, so roundoff does not grow with
   !> the number of substeps. The coefficients are `triple_jump`, `kahan_li_6`,
   !> `kahan_li_8`; the base is `verlet_t` for `yoshida4`, `comp6`, `comp8` (the
   !> base these coefficients are classically used with; measured on the test
   !> trajectory it gives 7× and 1.6× smaller errors than the midpoint base
   !> for orders 4 and 6, 4× larger for order 8, at 40–55 % more evaluations
   !> of f, 15–20 % more time) and `tao_t` for `tao4`.
   type, extends(symplectic_t) :: composition_t
      class(symplectic_t), allocatable :: base  !! the symmetric base method
      real(dp), allocatable :: gamma(:)         !! substep fractions, Σ γ_i = 1
      integer :: p = 0                          !! order of the composition
      character(len=:), allocatable :: label    !! name
   contains
      procedure :: advance => composition_advance
      procedure :: name => composition_name
      procedure :: order => composition_order
      procedure :: implicit => composition_implicit
      procedure :: reset => composition_reset
      procedure :: configure => composition_configure
   end type composition_t

contains

   ! ---------------------------------------------------------------- base

   pure logical function true_property(self)
      class(symplectic_t), intent(in) :: self  !! the method
      true_property = .true.
   end function true_property

   !> Start a new trajectory: zero the compensation and forget everything kept
   !> from earlier steps. Called by `step` when the state it is given is not
   !> the one it returned last.
   subroutine symplectic_reset(self)
      class(symplectic_t), intent(inout) :: self  !! the method
      self%comp = 0.0_dp
      self%started = .false.
   end subroutine symplectic_reset

   !> Options of the (q, p) methods: `compensated`, and those of every method.
   subroutine symplectic_configure(self, options)
      class(symplectic_t), intent(inout) :: self      !! the method
      type(method_options_t), intent(in) :: options   !! its options
      call integrator_configure(self, options)
      self%compensated = options%compensated
   end subroutine symplectic_configure

   !> One step of the method (see `integrator_t`); t and y change only on success.
   subroutine symplectic_step(self, model, t, y, h, stat)
      class(symplectic_t), intent(inout) :: self  !! the method and its counters
      class(model_t), intent(in) :: model         !! the system (Hamiltonian)
      real(dp), intent(inout) :: t                !! time [s]
      real(dp), intent(inout) :: y(:)             !! state (q [rad], p [kg m²/s])
      real(dp), intent(inout) :: h                !! step [s]
      integer, intent(out) :: stat                !! stat_ok or a failure code
      real(dp) :: ynew_(max_state), enew_(max_state)
      integer :: n
      logical :: ok
      n = size(y)
      if (self%started) then
         if (any(y /= self%y_last(:n))) call self%reset()
      else
         call self%reset()
      end if
      associate (ynew => ynew_(:n), enew => enew_(:n))
      ynew = y
      enew = self%comp(:n)
      call self%advance(model, t, ynew, enew, h, stat)
      if (stat /= stat_ok) return
      call self%record_finite_step(n, t, y, t + h, ynew, ok)
      if (.not. ok) then
         call self%reset()
         stat = stat_nonfinite
         return
      end if
      y = ynew
      self%comp(:n) = enew
      end associate
      t = t + h
      self%n_steps = self%n_steps + 1
      self%y_last(:n) = y
      self%started = .true.
   end subroutine symplectic_step

   !> y ← y + δ, with Kahan's compensated summation if `compensated`
   !> (GNI §VIII.5): e carries the rounding error of y.
   pure subroutine accumulate(y, e, delta, compensated)
      real(dp), intent(inout) :: y(:)      !! the sum
      real(dp), intent(inout) :: e(:)      !! its compensation
      real(dp), intent(in) :: delta(:)     !! the increment
      logical, intent(in) :: compensated   !! use the compensation
      real(dp) :: a(size(y)), ynew(size(y))
      if (compensated) then
         a = delta + e
         ynew = y + a
         e = (y - ynew) + a
         y = ynew
      else
         y = y + delta
      end if
   end subroutine accumulate

   !> Stopping rule of the fixed-point iterations (GNI §VIII.6.2, judged over two
   !> iterations; see the module doc): stop when the increment vanishes or is no
   !> smaller than two iterations before; that is convergence if it is at
   !> roundoff level (≤ `iter_tol`), failure otherwise. After `max_iter`
   !> iterations, converged only if at roundoff level.
   pure integer function iteration_verdict(dnew, dold, k) result(verdict)
      real(dp), intent(in) :: dnew  !! scaled increment Δ_k of iteration k
      real(dp), intent(in) :: dold  !! Δ_{k-2} (huge for k <= 2)
      integer, intent(in) :: k      !! iteration number
      if (.not. (dnew <= huge(dnew))) then
         verdict = it_failed
      else if (dnew == 0.0_dp) then
         verdict = it_converged
      else if (dnew >= dold .or. k >= max_iter) then
         if (dnew <= iter_tol) then
            verdict = it_converged
         else
            verdict = it_failed
         end if
      else
         verdict = it_continue
      end if
   end function iteration_verdict

   !> Stopping rule of the Gauss iteration on (q, q̇) (`gauss_advance_field`): the
   !> iteration error of a damped or driven system rotates between the components
   !> over several iterations (complex eigenvalues of h A ⊗ f'), so that Δ_k is not
   !> monotone over two iterations as `iteration_verdict` assumes. Progress is
   !> judged by the smallest increment so far, Δ_min (updated here): iterate while
   !> Δ_k sets a new minimum or did within the last `field_patience` iterations;
   !> converged when Δ_k vanishes, or is at roundoff level (≤ `iter_tol`) and no
   !> longer decreases; failed when no new minimum came for `field_patience`
   !> iterations above roundoff (divergence, stagnation) or after `max_iter`.
   pure subroutine field_verdict(dnew, dmin, k_min, k, verdict)
      real(dp), intent(in) :: dnew       !! scaled increment Δ_k of iteration k
      real(dp), intent(inout) :: dmin    !! smallest Δ so far (huge before the first)
      integer, intent(inout) :: k_min    !! the iteration of dmin
      integer, intent(in) :: k           !! iteration number
      integer, intent(out) :: verdict    !! it_continue, it_converged or it_failed
      integer, parameter :: field_patience = 4
      logical :: improved
      if (.not. (dnew <= huge(dnew))) then
         verdict = it_failed
         return
      end if
      improved = dnew < dmin
      if (improved) then
         dmin = dnew
         k_min = k
      end if
      if (dnew == 0.0_dp .or. (dnew <= iter_tol .and. .not. improved)) then
         verdict = it_converged
      else if (k >= max_iter .or. k - k_min >= field_patience) then
         if (dnew <= iter_tol) then
            verdict = it_converged
         else
            verdict = it_failed
         end if
      else
         verdict = it_continue
      end if
   end subroutine field_verdict

   !> Reciprocal scale of an increment of x: 1/(max|x| + max|dx|), 1 if both vanish.
   pure real(dp) function inv_scale(x, dx)
      real(dp), intent(in) :: x(:)   !! the variable
      real(dp), intent(in) :: dx(:)  !! a typical increment
      real(dp) :: sc
      sc = maxval(abs(x)) + maxval(abs(dx))
      if (sc > 0.0_dp) then
         inv_scale = 1.0_dp/sc
      else
         inv_scale = 1.0_dp
      end if
   end function inv_scale

   ! ---------------------------------------------------------------- Gauss

   !> The s-stage Gauss method (s = 1: `midpoint`, 2, 3, 4: `gauss4/6/8`).
   function gauss(s) result(g)
      integer, intent(in) :: s  !! number of stages, 1..4
      type(gauss_t) :: g
      g%s = s
      call gauss_setup(g)
   end function gauss

   !> Compute the tableau for `self%s` (clamped to 1..4).
   subroutine gauss_setup(self)
      class(gauss_t), intent(inout) :: self  !! the method
      real(dp) :: a(4, 4), b(4), c(4), d(4), a_lo(4, 4), d_lo(4)
      integer :: s
      s = max(1, min(4, self%s))
      call gauss_tableau(s, a, b, c, d, a_lo, d_lo)
      self%a_lo = 0.0_dp; self%d_lo = 0.0_dp
      self%a_lo(1:s, 1:s) = a_lo(1:s, 1:s); self%d_lo(1:s) = d_lo(1:s)
      self%s = s
      self%a = 0.0_dp; self%b = 0.0_dp; self%c = 0.0_dp; self%d = 0.0_dp
      self%a(1:s, 1:s) = a(1:s, 1:s)
      self%b(1:s) = b(1:s); self%c(1:s) = c(1:s); self%d(1:s) = d(1:s)
      self%ready = .true.
      self%have_z = .false.
      self%have_w = .false.
   end subroutine gauss_setup

   !> Butcher tableau of the s-stage Gauss–Legendre method (GNI §II.1.3), rounded
   !> from quadruple precision: nodes c_i = (1 + t_i)/2 with t_i the roots of the
   !> Legendre polynomial P_s (Newton's method); b and A from the simplifying
   !> conditions B(s) and C(s), Σ_j b_j c_j^{k-1} = 1/k and
   !> Σ_j a_ij c_j^{k-1} = c_i^k/k (k = 1..s), i.e. a_ij = ∫_0^{c_i} ℓ_j;
   !> d solves Aᵀd = b.
   pure subroutine gauss_tableau(s, a, b, c, d, a_lo, d_lo)
      integer, intent(in) :: s            !! number of stages
      real(dp), intent(out) :: a(:, :)    !! Runge–Kutta matrix in a(1:s, 1:s)
      real(dp), intent(out) :: b(:)       !! weights in b(1:s)
      real(dp), intent(out) :: c(:)       !! nodes in c(1:s)
      real(dp), intent(out) :: d(:)       !! bᵀA⁻¹ in d(1:s)
      real(dp), intent(out), optional :: a_lo(:, :)  !! rounding error of a: a + a_lo ≈ A
      real(dp), intent(out), optional :: d_lo(:)     !! rounding error of d
      real(qp), parameter :: pi_q = acos(-1.0_qp)
      real(qp) :: t, p0, p1, p2, dpdt, dt, cq(s), v(s, s), r(s, s + 1), at(s, s), dq(s, 1)
      integer :: i, j, k, n, it
      do i = 1, s
         t = cos(pi_q*(i - 0.25_qp)/(s + 0.5_qp))
         do it = 1, 100
            p0 = 1.0_qp; p1 = t
            do n = 2, s
               p2 = ((2*n - 1)*t*p1 - (n - 1)*p0)/n
               p0 = p1; p1 = p2
            end do
            dpdt = s*(t*p1 - p0)/(t*t - 1.0_qp)
            dt = p1/dpdt
            t = t - dt
            if (abs(dt) <= 2*epsilon(t)) exit
         end do
         cq(s + 1 - i) = (1.0_qp + t)/2
      end do
      do k = 1, s
         do j = 1, s
            v(k, j) = cq(j)**(k - 1)
         end do
         r(k, 1) = 1.0_qp/k
         do i = 1, s
            r(k, 1 + i) = cq(i)**k/k
         end do
      end do
      call solve_qp(v, r)
      do i = 1, s
         at(:, i) = r(:, 1 + i)   ! column i of Aᵀ is row i of A
      end do
      dq(:, 1) = r(:, 1)
      call solve_qp(at, dq)
      c(1:s) = real(cq, dp)
      b(1:s) = real(r(:, 1), dp)
      a(1:s, 1:s) = transpose(real(at, dp))
      d(1:s) = real(dq(:, 1), dp)
      if (present(a_lo)) a_lo(1:s, 1:s) = real(transpose(at) - real(a(1:s, 1:s), qp), dp)
      if (present(d_lo)) d_lo(1:s) = real(dq(:, 1) - real(d(1:s), qp), dp)
   end subroutine gauss_tableau

   !> Solve m x = r in quadruple precision (Gaussian elimination, partial
   !> pivoting); x overwrites r.
   pure subroutine solve_qp(m, r)
      real(qp), intent(in) :: m(:, :)     !! n×n matrix
      real(qp), intent(inout) :: r(:, :)  !! right-hand sides, then solutions
      real(qp) :: a(size(m, 1), size(m, 2)), row(size(m, 2)), rr(size(r, 2)), f
      integer :: n, i, k, piv
      a = m
      n = size(m, 1)
      do k = 1, n
         piv = k - 1 + maxloc(abs(a(k:n, k)), 1)
         row = a(k, :); a(k, :) = a(piv, :); a(piv, :) = row
         rr = r(k, :); r(k, :) = r(piv, :); r(piv, :) = rr
         do i = k + 1, n
            f = a(i, k)/a(k, k)
            a(i, k:n) = a(i, k:n) - f*a(k, k:n)
            r(i, :) = r(i, :) - f*r(k, :)
         end do
      end do
      do k = n, 1, -1
         r(k, :) = (r(k, :) - matmul(a(k, k + 1:n), r(k + 1:n, :)))/a(k, k)
      end do
   end subroutine solve_qp

   !> Weights w(i, j) = ℓ_j(1 + r c_i) - ℓ_j(1) such that Σ_j w(i, j) Z_j extrapolates
   !> the last step's collocation polynomial to the stages of the next step of
   !> size r h (GNI §VIII.6.1); ℓ_j are the Lagrange polynomials on the nodes
   !> {0, c_1, …, c_s}, and ℓ_j(1) removes y_{n+1} - y_n = u(t_n + h) - y_n.
   pure function extrapolation_weights(s, c, r) result(w)
      integer, intent(in) :: s      !! number of stages
      real(dp), intent(in) :: c(4)  !! nodes
      real(dp), intent(in) :: r     !! ratio of the new step to the old one
      real(dp) :: w(4, 4)
      integer :: i, j
      w = 0.0_dp
      do i = 1, s
         do j = 1, s
            w(i, j) = lagrange(j, 1.0_dp + r*c(i)) - lagrange(j, 1.0_dp)
         end do
      end do
   contains
      pure real(dp) function lagrange(j, x)
         integer, intent(in) :: j
         real(dp), intent(in) :: x
         integer :: m
         lagrange = x/c(j)   ! the factor of the node 0
         do m = 1, s
            if (m /= j) lagrange = lagrange*(x - c(m))/(c(j) - c(m))
         end do
      end function lagrange
   end function extrapolation_weights

   subroutine gauss_reset(self)
      class(gauss_t), intent(inout) :: self  !! the method
      call symplectic_reset(self)
      self%have_z = .false.
   end subroutine gauss_reset

   !> One Gauss step; states of four components take the same statements compiled
   !> with fixed sizes (dpend_gauss_body.inc), others the generic ones; a model
   !> without a Hamiltonian takes `gauss_advance_field` on (q, q̇).
   subroutine gauss_advance(self, model, t, y, e, h, stat)
      class(gauss_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model    !! the system (Hamiltonian)
      real(dp), intent(in) :: t              !! time at the start [s]
      real(dp), intent(inout) :: y(:)        !! state (q, p)
      real(dp), intent(inout) :: e(:)        !! compensation of y
      real(dp), intent(in) :: h              !! step [s]
      integer, intent(out) :: stat           !! status
      if (.not. model%hamiltonian()) then
         call gauss_advance_field(self, model, t, y, e, h, stat)
      else if (size(y) == 4) then
         call gauss_advance_4(self, model, t, y, e, h, stat)
      else
         call gauss_advance_n(self, model, t, y, e, h, stat)
      end if
   end subroutine gauss_advance

   subroutine gauss_advance_4(self, model, t, y, e, h, stat)
      class(gauss_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model    !! the system (Hamiltonian)
      real(dp), intent(in) :: t              !! time at the start [s]
      real(dp), intent(inout) :: y(4)        !! state (q, p)
      real(dp), intent(inout) :: e(4)        !! compensation of y
      real(dp), intent(in) :: h              !! step [s]
      integer, intent(out) :: stat           !! status
      integer, parameter :: n = 4, m = 2
      real(dp) :: z(n, 4), f(n, 4), zi(n), zl(n), f0(n), delta(n), yj(n), cache(2*max_state)
      real(dp) :: wq, wp, dnew, dm1, dm2, z4(4, 4), d4(4), l4(4)
      integer :: s, i, j, k, verdict, nb
      if (.not. self%ready) call gauss_setup(self)
      s = self%s
      associate (sc0 => cache(:model%cache_size()))
      include 'dpend_gauss_body.inc'
      end associate
   end subroutine gauss_advance_4

   subroutine gauss_advance_n(self, model, t, y, e, h, stat)
      class(gauss_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model    !! the system (Hamiltonian)
      real(dp), intent(in) :: t              !! time at the start [s]
      real(dp), intent(inout) :: y(:)        !! state (q, p)
      real(dp), intent(inout) :: e(:)        !! compensation of y
      real(dp), intent(in) :: h              !! step [s]
      integer, intent(out) :: stat           !! status
      real(dp) :: z_(max_state, 4), f_(max_state, 4), zi_(max_state), zl_(max_state)
      real(dp) :: f0_(max_state), delta_(max_state), yj_(max_state), cache(2*max_state)
      real(dp) :: wq, wp, dnew, dm1, dm2, z4(4, 4), d4(4), l4(4)
      integer :: s, i, j, k, verdict, n, m, nb
      if (.not. self%ready) call gauss_setup(self)
      s = self%s
      n = size(y); m = n/2
      associate (z => z_(:n, :), f => f_(:n, :), zi => zi_(:n), zl => zl_(:n), f0 => f0_(:n), &
                 delta => delta_(:n), yj => yj_(:n), sc0 => cache(:model%cache_size()))
      include 'dpend_gauss_body.inc'
      end associate
   end subroutine gauss_advance_n

   !> One Gauss step on the first-order field y' = f(t, y), y = (q, q̇), of a model
   !> without a Hamiltonian: the statements of dpend_gauss_body.inc with `field` at
   !> the stage times t + c_j h in place of the canonical field (same starting guess,
   !> fixed-point iteration and compensated update; stopping rule `field_verdict`).
   !> Strong damping makes the problem stiff (h c/(m l²) of order 1 and more), where
   !> the fixed-point iteration diverges: the step is then solved again from the same
   !> starting guess by a simplified Newton iteration (`gauss_field_newton`).
   subroutine gauss_advance_field(self, model, t, y, e, h, stat)
      class(gauss_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model    !! the system (damped, driven)
      real(dp), intent(in) :: t              !! time at the start [s]
      real(dp), intent(inout) :: y(:)        !! state (q, q̇)
      real(dp), intent(inout) :: e(:)        !! compensation of y
      real(dp), intent(in) :: h              !! step [s]
      integer, intent(out) :: stat           !! status
      real(dp) :: z_(max_state, 4), f_(max_state, 4), zi_(max_state), zl_(max_state)
      real(dp) :: f0_(max_state), delta_(max_state), yj_(max_state), z0_(max_state, 4)
      real(dp) :: wq, wv, dnew, dmin
      integer :: s, i, j, k, verdict, n, m, k_min
      if (.not. self%ready) call gauss_setup(self)
      s = self%s
      n = size(y); m = n/2
      associate (z => z_(:n, :s), f => f_(:n, :s), zi => zi_(:n), zl => zl_(:n), &
                 f0 => f0_(:n), delta => delta_(:n), yj => yj_(:n), z0 => z0_(:n, :s))
      ! starting guess: the last collocation polynomial, or c_i h f(t, y_n)
      z = 0.0_dp
      if (self%have_z .and. self%h_old /= 0.0_dp) then
         if (.not. (self%have_w .and. self%r_w == h/self%h_old)) then
            self%r_w = h/self%h_old
            self%w = extrapolation_weights(s, self%c, self%r_w)
            self%have_w = .true.
         end if
         do i = 1, s
            do j = 1, s
               z(:, i) = z(:, i) + self%w(i, j)*self%z_old(:n, j)
            end do
         end do
      else
         call model%field(t, y, f0)
         self%n_rhs = self%n_rhs + 1
         do i = 1, s
            z(:, i) = (self%c(i)*h)*f0
         end do
      end if
      wq = inv_scale(y(1:m), [maxval(abs(z(1:m, :)))])
      wv = inv_scale(y(m + 1:n), [maxval(abs(z(m + 1:n, :)))])
      ! a damped chain comes to rest: its rates vanish, and their increments are the
      ! roundoff of accelerations whose terms are set by the angles; so the scale of
      ! the rates is at least min(1, that of the angles)
      wv = min(wv, max(1.0_dp, wq))
      z0 = z
      dmin = huge(1.0_dp)
      k_min = 0
      stat = stat_no_convergence
      do k = 1, max_iter
         do j = 1, s
            yj = y + z(:, j)
            call model%field(t + self%c(j)*h, yj, f(:, j))
         end do
         self%n_rhs = self%n_rhs + s
         self%n_iter = self%n_iter + 1
         dnew = 0.0_dp
         do i = 1, s
            zi = 0.0_dp
            zl = 0.0_dp
            do j = 1, s
               zi = zi + self%a(i, j)*f(:, j)
               zl = zl + self%a_lo(i, j)*f(:, j)
            end do
            zi = h*(zi + zl)
            dnew = max(dnew, wq*maxval(abs(zi(1:m) - z(1:m, i))), &
                       wv*maxval(abs(zi(m + 1:n) - z(m + 1:n, i))))
            z(:, i) = zi
         end do
         call field_verdict(dnew, dmin, k_min, k, verdict)
         if (verdict == it_converged) stat = stat_ok
         if (verdict /= it_continue) exit
      end do
      if (stat /= stat_ok) then   ! stiff: simplified Newton from the same guess
         z = z0
         call gauss_field_newton(self, model, t, y, h, wq, wv, z, stat)
      end if
      if (stat /= stat_ok) return   ! (leaves the associate block)
      delta = 0.0_dp
      zl = 0.0_dp
      do j = 1, s
         delta = delta + self%d(j)*z(:, j)
         zl = zl + self%d_lo(j)*z(:, j)
      end do
      delta = delta + zl
      if (.not. all(ieee_is_finite(delta))) then
         stat = stat_nonfinite
         return
      end if
      self%z_old(:n, :s) = z
      self%h_old = h
      self%have_z = .true.
      call accumulate(y, e, delta, self%compensated)
      end associate
   end subroutine gauss_advance_field

   !> The stage increments Z (n, s) of a Gauss step on the field by a simplified
   !> Newton iteration (Hairer, Wanner, Solving ODEs II, §IV.8): with J = ∂f/∂y at
   !> (t, y) (the model's `jacobian`), factor I − h A ⊗ J once (LAPACK dgetrf) and
   !> solve (I − h A ⊗ J) ΔZ = h (A ⊗ I) F(Z) − Z (dgetrs) until `field_verdict`
   !> stops it; wq, wv scale the increments as in the fixed-point iteration. For
   !> stiff damping, where the fixed-point iteration diverges.
   subroutine gauss_field_newton(self, model, t, y, h, wq, wv, z, stat)
      class(gauss_t), intent(inout) :: self  !! the method and its counters
      class(model_t), intent(in) :: model    !! the system (damped, driven)
      real(dp), intent(in) :: t              !! time at the start [s]
      real(dp), intent(in) :: y(:)           !! state (q, q̇) at the start
      real(dp), intent(in) :: h              !! step [s]
      real(dp), intent(in) :: wq, wv         !! scales of the increments of q and q̇
      real(dp), intent(inout) :: z(:, :)     !! (n, s): starting guess, then the solution
      integer, intent(out) :: stat           !! stat_ok or stat_no_convergence
      real(dp) :: jac(size(y), size(y)), mat(size(z), size(z)), g(size(z), 1)
      real(dp) :: f(size(y), size(z, 2)), yj(size(y)), zi(size(y)), zl(size(y)), dnew, dmin
      integer :: ipiv(size(z)), n, s, m, i, j, k, info, verdict, k_min, r
      n = size(y); s = size(z, 2); m = n/2
      stat = stat_no_convergence
      call model%jacobian(t, y, jac)
      do j = 1, s
         do i = 1, s
            mat((i - 1)*n + 1:i*n, (j - 1)*n + 1:j*n) = (-h*(self%a(i, j) + &
                                                             self%a_lo(i, j)))*jac
         end do
      end do
      do i = 1, s*n
         mat(i, i) = mat(i, i) + 1.0_dp
      end do
      call dgetrf(s*n, s*n, mat, s*n, ipiv, info)
      if (info /= 0) return
      dmin = huge(1.0_dp)
      k_min = 0
      do k = 1, max_iter
         do j = 1, s
            yj = y + z(:, j)
            call model%field(t + self%c(j)*h, yj, f(:, j))
         end do
         self%n_rhs = self%n_rhs + s
         self%n_iter = self%n_iter + 1
         do i = 1, s
            zi = 0.0_dp
            zl = 0.0_dp
            do j = 1, s
               zi = zi + self%a(i, j)*f(:, j)
               zl = zl + self%a_lo(i, j)*f(:, j)
            end do
            g((i - 1)*n + 1:i*n, 1) = h*(zi + zl) - z(:, i)
         end do
         if (.not. all(ieee_is_finite(g))) return
         call dgetrs('N', s*n, 1, mat, s*n, ipiv, g, s*n, info)
         if (info /= 0) return
         dnew = 0.0_dp
         do i = 1, s
            r = (i - 1)*n
            dnew = max(dnew, wq*maxval(abs(g(r + 1:r + m, 1))), &
                       wv*maxval(abs(g(r + m + 1:r + n, 1))))
            z(:, i) = z(:, i) + g(r + 1:r + n, 1)
         end do
         call field_verdict(dnew, dmin, k_min, k, verdict)
         if (verdict == it_converged) stat = stat_ok
         if (verdict /= it_continue) exit
      end do
   end subroutine gauss_field_newton

   !> The Gauss methods run on (q, q̇) when the model has no Hamiltonian.
   pure logical function gauss_needs_hamiltonian(self)
      class(gauss_t), intent(in) :: self
      gauss_needs_hamiltonian = .false.
   end function gauss_needs_hamiltonian

   pure function gauss_name(self) result(name)
      class(gauss_t), intent(in) :: self
      character(len=:), allocatable :: name
      character(len=8) :: buf
      if (self%s == 1) then
         name = 'midpoint'
      else
         write (buf, '(a, i0)') 'gauss', 2*self%s
         name = trim(buf)
      end if
   end function gauss_name

   pure integer function gauss_order(self)
      class(gauss_t), intent(in) :: self
      gauss_order = 2*max(self%s, 1)
   end function gauss_order

   ! ---------------------------------------------------------------- Verlet

   subroutine verlet_reset(self)
      class(verlet_t), intent(inout) :: self  !! the method
      call symplectic_reset(self)
      self%have_force = .false.
   end subroutine verlet_reset

   subroutine verlet_advance(self, model, t, y, e, h, stat)
      class(verlet_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system (Hamiltonian)
      real(dp), intent(in) :: t               !! time at the start [s]
      real(dp), intent(inout) :: y(:)         !! state (q, p)
      real(dp), intent(inout) :: e(:)         !! compensation of y
      real(dp), intent(in) :: h               !! step [s]
      integer, intent(out) :: stat            !! status
      real(dp) :: f_(max_state), g_(max_state), z_(max_state), cache(2*max_state)
      real(dp) :: dp_half_(max_dof), dpn_(max_dof), dq_(max_dof), dqn_(max_dof)
      real(dp) :: v0_(max_dof), ph_(max_dof), w, dnew, dm1, dm2
      integer :: k, verdict, n, m
      n = size(y); m = n/2
      associate (f => f_(:n), g => g_(:n), z => z_(:n), dp_half => dp_half_(:m), &
                 dpn => dpn_(:m), dq => dq_(:m), dqn => dqn_(:m), v0 => v0_(:m), &
                 ph => ph_(:m), sc0 => cache(:model%cache_size()))
      ! p_{n+½} = p_n + Δp, Δp = h/2 F(q_n, p_n + Δp), F = -∂H/∂q
      if (self%have_force) then
         dp_half = (0.5_dp*h)*self%force(:m)
      else
         call model%canonical_field(t, y, f)
         self%n_rhs = self%n_rhs + 1
         dp_half = (0.5_dp*h)*f(m + 1:n)
      end if
      w = inv_scale(y(m + 1:n), dp_half)
      dm1 = huge(1.0_dp)
      dm2 = huge(1.0_dp)
      stat = stat_no_convergence
      do k = 1, max_iter
         z(1:m) = y(1:m)
         z(m + 1:n) = y(m + 1:n) + dp_half
         call model%canonical_field(t, z, f)
         self%n_rhs = self%n_rhs + 1
         self%n_iter = self%n_iter + 1
         dpn = (0.5_dp*h)*f(m + 1:n)
         dnew = w*maxval(abs(dpn - dp_half))
         dp_half = dpn
         verdict = iteration_verdict(dnew, dm2, k)
         if (verdict == it_converged) stat = stat_ok
         if (verdict /= it_continue) exit
         dm2 = dm1
         dm1 = dnew
      end do
      if (stat /= stat_ok) return
      v0 = f(1:m)                  ! ∂H/∂p(q_n, p_{n+½})
      ph = y(m + 1:n) + dp_half
      ! q_{n+1} = q_n + Δq, Δq = h/2 [v0 + ∂H/∂p(q_n + Δq, p_{n+½})]
      dq = h*v0
      w = inv_scale(y(1:m), dq)
      dm1 = huge(1.0_dp)
      dm2 = huge(1.0_dp)
      stat = stat_no_convergence
      call model%fill_cache(y(1:m), sc0)   ! q_n + Δq is near q_n
      z(m + 1:n) = ph
      do k = 1, max_iter
         z(1:m) = y(1:m) + dq
         call model%canonical_field_near(t + h, z, dq, sc0, g)
         self%n_rhs = self%n_rhs + 1
         self%n_iter = self%n_iter + 1
         dqn = (0.5_dp*h)*(v0 + g(1:m))
         dnew = w*maxval(abs(dqn - dq))
         dq = dqn
         verdict = iteration_verdict(dnew, dm2, k)
         if (verdict == it_converged) stat = stat_ok
         if (verdict /= it_continue) exit
         dm2 = dm1
         dm1 = dnew
      end do
      if (stat /= stat_ok) return
      ! p_{n+1} = p_{n+½} + h/2 F(q_{n+1}, p_{n+½})
      f(1:m) = dq
      f(m + 1:n) = dp_half + (0.5_dp*h)*g(m + 1:n)
      if (.not. all(ieee_is_finite(f))) then
         stat = stat_nonfinite
         return
      end if
      self%force(:m) = g(m + 1:n)
      self%have_force = .true.
      call accumulate(y, e, f, self%compensated)
      end associate
   end subroutine verlet_advance

   pure function verlet_name(self) result(name)
      class(verlet_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'verlet'
   end function verlet_name

   pure integer function verlet_order(self)
      class(verlet_t), intent(in) :: self
      verlet_order = 2
   end function verlet_order

   ! ---------------------------------------------------------------- composition

   !> A composition method named `label` of order `order`.
   function composition(base, gamma, order, label) result(cm)
      class(symplectic_t), intent(in) :: base  !! symmetric second-order base method
      real(dp), intent(in) :: gamma(:)         !! substep fractions
      integer, intent(in) :: order             !! resulting order
      character(len=*), intent(in) :: label    !! name
      type(composition_t) :: cm
      allocate (cm%base, source=base)
      cm%gamma = gamma
      cm%p = order
      cm%label = label
   end function composition

   !> Triple jump γ = (γ1, 1 - 2γ1, γ1), γ1 = 1/(2 - 2^{1/3}): order 4 from a
   !> symmetric order-2 method (Yoshida, Phys. Lett. A 150, 262, 1990; Suzuki,
   !> Phys. Lett. A 146, 319, 1990; GNI §II.4).
   pure function triple_jump() result(gamma)
      real(dp) :: gamma(3)
      real(dp), parameter :: g1 = 1.0_dp/(2.0_dp - 2.0_dp**(1.0_dp/3.0_dp))
      gamma = [g1, 1.0_dp - 2.0_dp*g1, g1]
   end function triple_jump

   !> Kahan & Li, "Composition constants for raising the orders of
   !> unconventional schemes for ordinary differential equations", Math. Comp.
   !> 66, 1089–1099 (1997), method s9odr6a: order 6, 9 substeps (GNI §V.3.2).
   pure function kahan_li_6() result(gamma)
      real(dp) :: gamma(9)
      real(dp), parameter :: g(5) = [ &
                             0.39216144400731413927925056_dp, &
                             0.33259913678935943859974864_dp, &
                             -0.70624617255763935980996482_dp, &
                             0.08221359629355080023149045_dp, &
                             0.79854399093482996339895035_dp]
      gamma = [g, g(4:1:-1)]
   end function kahan_li_6

   !> Kahan & Li (1997), method s17odr8a: order 8, 17 substeps (GNI §V.3.2).
   pure function kahan_li_8() result(gamma)
      real(dp) :: gamma(17)
      real(dp), parameter :: g(9) = [ &
                             0.13020248308889008087881763_dp, &
                             0.56116298177510838456196441_dp, &
                             -0.38947496264484728640807860_dp, &
                             0.15884190655515560089621075_dp, &
                             -0.39590389413323757733623154_dp, &
                             0.18453964097831570709183254_dp, &
                             0.25837438768632204729397911_dp, &
                             0.29501172360931029887096624_dp, &
                             -0.60550853383003451169892108_dp]
      gamma = [g, g(8:1:-1)]
   end function kahan_li_8

   subroutine composition_reset(self)
      class(composition_t), intent(inout) :: self  !! the method
      call symplectic_reset(self)
      if (allocated(self%base)) call self%base%reset()
   end subroutine composition_reset

   !> Options of a composition: its own, and its base method's (e.g. Tao's ω).
   subroutine composition_configure(self, options)
      class(composition_t), intent(inout) :: self     !! the method
      type(method_options_t), intent(in) :: options   !! its options
      call symplectic_configure(self, options)
      if (allocated(self%base)) call self%base%configure(options)
   end subroutine composition_configure

   subroutine composition_advance(self, model, t, y, e, h, stat)
      class(composition_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model          !! the system (Hamiltonian)
      real(dp), intent(in) :: t                    !! time at the start [s]
      real(dp), intent(inout) :: y(:)              !! state (q, p)
      real(dp), intent(inout) :: e(:)              !! compensation of y
      real(dp), intent(in) :: h                    !! step [s]
      integer, intent(out) :: stat                 !! status
      real(dp) :: ts
      integer :: k
      self%base%compensated = self%compensated
      stat = stat_ok
      ts = t
      do k = 1, size(self%gamma)
         call self%base%advance(model, ts, y, e, self%gamma(k)*h, stat)
         if (stat /= stat_ok) exit
         ts = ts + self%gamma(k)*h
      end do
      self%n_rhs = self%n_rhs + self%base%n_rhs
      self%n_iter = self%n_iter + self%base%n_iter
      call self%base%reset_counters()
      ! a failed substep leaves the base's memory ahead of y: forget it
      if (stat /= stat_ok) call self%base%reset()
   end subroutine composition_advance

   pure function composition_name(self) result(name)
      class(composition_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = self%label
   end function composition_name

   pure integer function composition_order(self)
      class(composition_t), intent(in) :: self
      composition_order = self%p
   end function composition_order

   !> Gauss collocation solves its stage equations by fixed-point iteration.
   pure logical function gauss_implicit(self)
      class(gauss_t), intent(in) :: self
      gauss_implicit = .true.
   end function gauss_implicit

   !> The generalised leapfrog is implicit in p and in q (non-separable H).
   pure logical function verlet_implicit(self)
      class(verlet_t), intent(in) :: self
      verlet_implicit = .true.
   end function verlet_implicit

   !> A composition is implicit when its base method is.
   pure logical function composition_implicit(self)
      class(composition_t), intent(in) :: self
      composition_implicit = self%base%implicit()
   end function composition_implicit
end module dpend_symplectic
