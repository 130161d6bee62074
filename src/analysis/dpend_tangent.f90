!> Tangent (variational) dynamics along the trajectory of any integrator.
!>
!> The tangent vectors v obey the variational equation v' = J(y(t)) v, with J the
!> analytic Jacobian of the vector field in the method's own variables
!> (`jacobian_qp` for canonical methods, (q, p); `jacobian_qqdot` otherwise,
!> (q, q̇)). After every accepted step of the method, `tangent_t%propagate`
!> integrates it over that step [t_old, t_new] with the classical fourth-order
!> Runge–Kutta method for linear non-autonomous systems, J evaluated at the
!> substep ends and midpoints on the method's own continuous extension
!> (`integrator_t%interpolate`: dop853 order 7, dopri5 order 4, the cubic
!> Hermite interpolant of the step for fixed-step methods).
!>
!> Design. Of the two possible designs — each method supplying the exact
!> linearisation of its own step map, or one tangent integrator driven by every
!> method's dense output — this module is the second: it needs nothing from a
!> method beyond the base interface (step memory, `interpolate`, `canonical`), so
!> one mechanism serves explicit, adaptive, implicit and composition methods
!> alike, and new methods get Lyapunov exponents for free. What it computes is
!> the linearisation of the exact flow along the numerical trajectory, which is
!> what Lyapunov exponents measure; its accuracy is set here, not by the method:
!>  * each step is split into n = ⌈|h| ω / θ⌉ substeps, ω = ‖J²‖∞^½ being the
!>    local frequency of the linear flow (scale-free: for an oscillator ω is its
!>    angular frequency whatever the units of q and p). With θ = 0.1 the RK4
!>    amplitude error is (ωh)⁶/144 ≈ 7e-9 per substep, i.e. below 1e-6 s⁻¹ on an
!>    exponent for ω ≲ 30 rad/s; rk4 with dt = 1e-3 s takes one substep;
!>  * the interpolation error of y (O(h⁴) to O(h⁸)) enters J only, so it
!>    perturbs the tangent map at the level of the method's own error.
!> The Jacobian at the end of a step is kept for the start of the next one.
module dpend_tangent
   use dpend_kinds, only: dp, i8
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t
   use dpend_limits, only: max_tangent_substeps
   implicit none
   private
   public :: tangent_t, internal_jacobian
   ! the chain lanes' indicators: the tangent step of dpend_chain_lanes
   public :: mat_mul

   !> Tangent vectors carried along a trajectory, and the substep control.
   !> Largest magnitude of a tangent vector's component: far above any renormalized
   !> use (Lyapunov, indicators renormalize at O(1)) and far below overflow.
   real(dp), parameter, public :: max_tangent_size = 1e100_dp

   type :: tangent_t
      !> tangent vectors (4, k) in the method's internal variables
      real(dp), allocatable :: v(:, :)
      !> largest ω·h per RK4 substep (ω = ‖J²‖∞^½, the local frequency) [1]
      real(dp) :: theta = 0.1_dp
      integer(i8) :: n_jac = 0   !! Jacobian evaluations
      integer(i8) :: n_sub = 0   !! RK4 substeps taken
      !> most substeps of one step (at most `max_tangent_substeps`)
      integer :: max_substeps = max_tangent_substeps
      !> the last step needed more than `max_substeps` substeps: the vectors were not
      !> propagated (the step is far too long for the local frequency)
      logical :: too_stiff = .false.
      !> a component of the vectors passed `max_tangent_size` (or is not finite): they
      !> were not propagated further. Callers that renormalize (Lyapunov, indicators)
      !> never meet it; the fit's sensitivities over a long chaotic window do, before
      !> their growth could overflow (a trap in the debug build)
      logical :: too_large = .false.
      logical :: cached = .false.         !! j_cache holds J(y_cache)
      real(dp), allocatable :: y_cache(:)     !! state of the cached Jacobian
      real(dp), allocatable :: j_cache(:, :)  !! cached Jacobian
   contains
      procedure :: init => tangent_init
      procedure :: propagate => tangent_propagate
   end type tangent_t

contains

   !> Start with the vectors `v0` (4, k), e.g. the first k columns of the identity.
   subroutine tangent_init(self, v0)
      class(tangent_t), intent(inout) :: self  !! the tangent state
      real(dp), intent(in) :: v0(:, :)         !! initial tangent vectors (2n, k)
      self%v = v0
      self%cached = .false.
      self%too_stiff = .false.
      self%too_large = .false.
      self%n_jac = 0
      self%n_sub = 0
   end subroutine tangent_init

   !> The Jacobian of the method's vector field at its internal state y:
   !> ∂f/∂(q, p) for canonical methods, ∂f/∂(q, q̇) otherwise.
   pure function internal_jacobian(integ, model, t, y) result(jac)
      class(integrator_t), intent(in) :: integ  !! the method (decides the variables)
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: y(:)              !! internal state
      real(dp) :: jac(size(y), size(y))
      if (integ%canonical_on(model)) then
         call model%canonical_jacobian(t, y, jac)
      else
         call model%jacobian(t, y, jac)
      end if
   end function internal_jacobian

   !> Propagate the tangent vectors over the last accepted step of `integ`
   !> (see the module header). Call once after every accepted step. Without a
   !> recorded step, or for a step of zero length, nothing happens.
   subroutine tangent_propagate(self, integ, model)
      class(tangent_t), intent(inout) :: self      !! the tangent state
      class(integrator_t), intent(inout) :: integ  !! the method, after a step
      class(model_t), intent(in) :: model  !! the system
      real(dp) :: h, hs, ta, omega
      real(dp), dimension(integ%n_rec, integ%n_rec) :: ja, jm, jb, ja2
      real(dp), dimension(integ%n_rec) :: ym, yb
      real(dp), dimension(integ%n_rec, size(self%v, 2)) :: k1, k2, k3, k4
      integer :: n, i, ns
      logical :: hit
      if (.not. integ%has_step()) return
      h = integ%t_new - integ%t_old
      if (h == 0.0_dp) return
      ns = integ%n_rec
      ! (nested: y_cache is unallocated until the first step is cached)
      hit = .false.
      if (self%cached) hit = all(self%y_cache == integ%y_old(:ns))
      if (hit) then
         ja = self%j_cache
      else
         ja = jacobian(integ%t_old, integ%y_old(:ns))
      end if
      call mat_mul(ja, ja, ja2)
      omega = sqrt(maxval(sum(abs(ja2), dim=2)))
      ! compared before converting: the substep count must fit an integer
      self%too_stiff = .not. (abs(h)*omega <= self%theta*real(self%max_substeps, dp))
      if (self%too_stiff) return
      n = max(1, ceiling(abs(h)*omega/self%theta))
      hs = h/real(n, dp)
      do i = 1, n
         ta = integ%t_old + real(i - 1, dp)*hs
         ym = integ%y_new(:ns)
         call integ%interpolate(model, ta + 0.5_dp*hs, ym)
         jm = jacobian(ta + 0.5_dp*hs, ym)
         if (i == n) then
            yb = integ%y_new(:ns)
         else
            yb = integ%y_new(:ns)
            call integ%interpolate(model, ta + hs, yb)
         end if
         jb = jacobian(ta + hs, yb)
         associate (v => self%v)
            call mat_mul(ja, v, k1)
            call mat_mul(jm, v + (0.5_dp*hs)*k1, k2)
            call mat_mul(jm, v + (0.5_dp*hs)*k2, k3)
            call mat_mul(jb, v + hs*k3, k4)
            v = v + (hs/6.0_dp)*(k1 + 2.0_dp*(k2 + k3) + k4)
            ! one substep grows v by at most about e^theta: checking each one keeps
            ! every stage of the next far from overflow
            self%too_large = .not. all(abs(v) <= max_tangent_size)
         end associate
         if (self%too_large) return
         ja = jb
      end do
      self%n_sub = self%n_sub + n
      self%cached = .true.
      self%y_cache = integ%y_new(:ns)
      self%j_cache = jb
   contains
      function jacobian(tt, y) result(jac)
         real(dp), intent(in) :: tt, y(:)
         real(dp) :: jac(size(y), size(y))
         jac = internal_jacobian(integ, model, tt, y)
         self%n_jac = self%n_jac + 1
      end function jacobian
   end subroutine tangent_propagate

   !> c = a b by the plain triple loop, summing over l in ascending order: the same
   !> operations as gfortran's inlined `matmul` of small fixed-size arrays, whatever
   !> the size (the library `matmul` used for run-time sizes sums differently).
   pure subroutine mat_mul(a, b, c)
      real(dp), intent(in) :: a(:, :)   !! (m, k)
      real(dp), intent(in) :: b(:, :)   !! (k, p)
      real(dp), intent(out) :: c(:, :)  !! (m, p)
      integer :: i, j, l
      c = 0.0_dp
      do j = 1, size(b, 2)
         do l = 1, size(a, 2)
            do i = 1, size(a, 1)
               c(i, j) = c(i, j) + a(i, l)*b(l, j)
            end do
         end do
      end do
   end subroutine mat_mul
end module dpend_tangent
