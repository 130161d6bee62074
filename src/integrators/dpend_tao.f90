!> Tao's explicit symplectic integrators for non-separable Hamiltonians in an
!> extended phase space (Molei Tao, "Explicit symplectic approximation of
!> nonseparable Hamiltonians: algorithm and long time performance",
!> Phys. Rev. E 94, 043303, 2016).
!>
!> Two copies (q, p) and (x, y) of phase space are bound together:
!>   H̄(q, p, x, y) = H(q, y) + H(x, p) + ω/2 (|q - x|² + |p - y|²).
!> The flows of H_A = H(q, y), H_B = H(x, p) and H_C = ω/2(…) are explicit:
!>   φ_A^δ: p ← p - δ ∂H/∂q(q, y),  x ← x + δ ∂H/∂p(q, y)
!>   φ_B^δ: q ← q + δ ∂H/∂p(x, p),  y ← y - δ ∂H/∂q(x, p)
!>   φ_C^δ: (q - x, p - y) rotated by the angle 2ωδ, (q + x, p + y) fixed,
!> and `tao2` = φ_A^{h/2} φ_B^{h/2} φ_C^h φ_B^{h/2} φ_A^{h/2} (order 2, symmetric,
!> 4 evaluations of the vector field); `tao4` is its triple jump
!> (`composition_t` with `triple_jump`).
!>
!> The state y(4) seen by the driver is the first copy (q, p), as in Tao's
!> paper; the second copy (x, y) lives in the object between steps and is set
!> to (q, p) when a new trajectory starts. The maps are symplectic in the
!> extended phase space (ℝ⁸), not exactly on (q, p): the reduced map's defect
!> is measured in the tests. The (q, p) update is summed with compensation
!> like the other methods (see `dpend_symplectic`: never compile with
!> reassociating flags such as -ffast-math); the copy (x, y) is updated plainly.
!>
!> The binding constant ω [1/s]: Tao's error bound O(T h^l ω) (l the order)
!> wants ω h^l small, while the copies stay bound only if ω is large compared
!> with the system's own frequencies (≈ 3 and 8 rad/s for the chapter's
!> pendulum near the hanging position) and the rotation angle 2ωh stays small.
!> The default ω = 20 /s with h ≈ 1e-3 s (2ωh = 0.04) follows Tao's examples.
module dpend_tao
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_state, max_dof
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite
   use dpend_symplectic, only: symplectic_t, accumulate, symplectic_reset, &
                               symplectic_configure
   use dpend_method_options, only: method_options_t
   implicit none
   private
   public :: tao_t

   !> Tao's second-order extended-phase-space method (`tao2`). Symplectic in the
   !> extended phase space (q, p, x, y) and symmetric.
   type, extends(symplectic_t) :: tao_t
      real(dp) :: omega = 20.0_dp  !! binding constant ω [1/s] (`--omega`)
      real(dp), private :: x(max_dof) = 0.0_dp   ! second copy of q [rad]
      real(dp), private :: w(max_dof) = 0.0_dp   ! second copy of p [kg m²/s]
      logical, private :: have_copy = .false.
   contains
      procedure :: advance => tao_advance
      procedure :: name => tao_name
      procedure :: order => tao_order
      procedure :: reset => tao_reset
      procedure :: configure => tao_configure
      procedure :: get_copy => tao_get_copy
      procedure :: set_copy => tao_set_copy
   end type tao_t

contains

   !> Options of Tao's method: ω (0 keeps the default), and those of the (q, p)
   !> methods. tao4 reaches it through its composition.
   subroutine tao_configure(self, options)
      class(tao_t), intent(inout) :: self             !! the method
      type(method_options_t), intent(in) :: options   !! its options
      call symplectic_configure(self, options)
      if (options%omega > 0.0_dp) self%omega = options%omega
   end subroutine tao_configure

   !> The second copy (x, y) carried between steps, e.g. to monitor how far the
   !> copies drift apart (|q - x|, |p - y|); `have` is false before the first step
   !> of a trajectory.
   pure subroutine tao_get_copy(self, x, y, have)
      class(tao_t), intent(in) :: self  !! the method
      real(dp), intent(out) :: x(:)     !! second copy of q [rad]
      real(dp), intent(out) :: y(:)     !! second copy of p [kg m²/s]
      logical, intent(out) :: have      !! the copy belongs to the current trajectory
      x = self%x(:size(x))
      y = self%w(:size(y))
      have = self%have_copy
   end subroutine tao_get_copy

   !> Impose the second copy (x, y) for the next call of `advance` (the
   !> extended-phase-space map; `step` resets it when a new trajectory starts).
   pure subroutine tao_set_copy(self, x, y)
      class(tao_t), intent(inout) :: self  !! the method
      real(dp), intent(in) :: x(:)         !! second copy of q [rad]
      real(dp), intent(in) :: y(:)         !! second copy of p [kg m²/s]
      self%x(:size(x)) = x
      self%w(:size(y)) = y
      self%have_copy = .true.
   end subroutine tao_set_copy

   subroutine tao_reset(self)
      class(tao_t), intent(inout) :: self  !! the method
      call symplectic_reset(self)
      self%have_copy = .false.
   end subroutine tao_reset

   !> One step of Tao's method. Four-component states take the statements of
   !> dpend_tao_body.inc compiled with constant sizes, others the generic ones.
   subroutine tao_advance(self, model, t, y, e, h, stat)
      class(tao_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system (Hamiltonian)
      real(dp), intent(in) :: t            !! time at the start [s]
      real(dp), intent(inout) :: y(:)      !! state (q, p), the first copy
      real(dp), intent(inout) :: e(:)      !! compensation of y
      real(dp), intent(in) :: h            !! step [s]
      integer, intent(out) :: stat         !! status
      if (size(y) == 4) then
         call tao_advance_4(self, model, t, y, e, h, stat)
      else
         call tao_advance_n(self, model, t, y, e, h, stat)
      end if
   end subroutine tao_advance

   subroutine tao_advance_4(self, model, t, y, e, h, stat)
      class(tao_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system (Hamiltonian)
      real(dp), intent(in) :: t            !! time at the start [s]
      real(dp), intent(inout) :: y(:)      !! state (q, p), the first copy
      real(dp), intent(inout) :: e(:)      !! compensation of y
      real(dp), intent(in) :: h            !! step [s]
      integer, intent(out) :: stat         !! status
      integer, parameter :: n = 4, m = 2
      ! x_, w_, dq_, dp__ are read and updated by the flows (dpend_tao_body.inc)
      real(dp) :: x_(m), w_(m), dq_(m), dp__(m), u_(m), v_(m), ru_(m), rv_(m)
      real(dp) :: delta_(n), f_(n), z_(n), cs, sn
      include 'dpend_tao_body.inc'
   end subroutine tao_advance_4

   subroutine tao_advance_n(self, model, t, y, e, h, stat)
      class(tao_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system (Hamiltonian)
      real(dp), intent(in) :: t            !! time at the start [s]
      real(dp), intent(inout) :: y(:)      !! state (q, p), the first copy
      real(dp), intent(inout) :: e(:)      !! compensation of y
      real(dp), intent(in) :: h            !! step [s]
      integer, intent(out) :: stat         !! status
      ! x_, w_, dq_, dp__ are read and updated by the flows (dpend_tao_body.inc)
      real(dp) :: x_(max_dof), w_(max_dof), dq_(max_dof), dp__(max_dof), u_(max_dof)
      real(dp) :: v_(max_dof), ru_(max_dof), rv_(max_dof), delta_(max_state), cs, sn
      real(dp) :: f_(max_state), z_(max_state)
      integer :: n, m
      n = size(y); m = n/2
      include 'dpend_tao_body.inc'
   end subroutine tao_advance_n

   pure function tao_name(self) result(name)
      class(tao_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'tao2'
   end function tao_name

   pure integer function tao_order(self)
      class(tao_t), intent(in) :: self
      tao_order = 2
   end function tao_order
end module dpend_tao
