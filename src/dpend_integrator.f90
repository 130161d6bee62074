!> The one abstract integrator type of dpend, its step status codes and the state
!> conventions shared by every method.
!>
!> A method advances an internal state y(4): (q1, q2, q̇1, q̇2) for the explicit
!> Runge–Kutta methods, (q1, q2, p1, p2) for the symplectic ones (`canonical()`).
!> Drivers convert with `to_internal` / `to_physical` once at the start and when
!> sampling; the methods never convert inside a step.
module dpend_integrator
   use dpend_kinds, only: dp, i8
   use dpend_model, only: pendulum_t, rhs_qqdot, rhs_qp, momenta, velocities
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: integrator_t
   public :: stat_ok, stat_no_convergence, stat_nonfinite, stat_step_too_small
   public :: status_message, state_ok, diverged_bound

   integer, parameter :: stat_ok = 0              !! the step was taken
   integer, parameter :: stat_no_convergence = 1  !! implicit stages did not converge
   integer, parameter :: stat_nonfinite = 2       !! the state became NaN or Inf
   integer, parameter :: stat_step_too_small = 3  !! adaptive step fell below roundoff

   !> A state component beyond this magnitude counts as diverged: no physical state of
   !> the pendulum comes near it, and stopping there keeps every intermediate stage of
   !> the next step below overflow (which would trap under -ffpe-trap=overflow).
   real(dp), parameter :: diverged_bound = 1e30_dp

   !> Common state and counters of every method.
   type, abstract :: integrator_t
      integer(i8) :: n_rhs = 0       !! right-hand-side evaluations
      integer(i8) :: n_steps = 0     !! accepted steps
      integer(i8) :: n_rejected = 0  !! rejected steps (adaptive methods)
      integer(i8) :: n_iter = 0      !! inner iterations (implicit methods)
   contains
      procedure(step_i), deferred :: step
      procedure(name_i), deferred :: name
      procedure(order_i), deferred :: order
      procedure :: symplectic => false_property
      procedure :: symmetric => false_property
      procedure :: adaptive => false_property
      procedure :: canonical => false_property
      procedure :: reset_counters
      procedure :: rhs
      procedure :: to_internal
      procedure :: to_physical
   end type integrator_t

   abstract interface
      !> Advance (t, y) by one step. Fixed-step methods take exactly h; adaptive
      !> methods take one accepted step of at most h (retrying internally) and
      !> return in h the step size proposed for the next step. On failure t and
      !> y are left unchanged and `stat` says why.
      subroutine step_i(self, par, t, y, h, stat)
         import :: integrator_t, pendulum_t, dp
         class(integrator_t), intent(inout) :: self  !! the method and its counters
         type(pendulum_t), intent(in) :: par         !! parameters
         real(dp), intent(inout) :: t                !! time [s]
         real(dp), intent(inout) :: y(4)             !! internal state
         real(dp), intent(inout) :: h                !! step [s]
         integer, intent(out) :: stat                !! stat_ok or a failure code
      end subroutine step_i
      !> Name as given to --method.
      pure function name_i(self) result(name)
         import :: integrator_t
         class(integrator_t), intent(in) :: self
         character(len=:), allocatable :: name
      end function name_i
      !> Classical order of convergence.
      pure integer function order_i(self)
         import :: integrator_t
         class(integrator_t), intent(in) :: self
      end function order_i
   end interface

contains

   !> Default for the properties: false.
   pure logical function false_property(self)
      class(integrator_t), intent(in) :: self  !! the method
      false_property = .false.
   end function false_property

   !> Zero the counters.
   subroutine reset_counters(self)
      class(integrator_t), intent(inout) :: self  !! the method
      self%n_rhs = 0; self%n_steps = 0; self%n_rejected = 0; self%n_iter = 0
   end subroutine reset_counters

   !> The vector field in the method's own variables, counted in `n_rhs`.
   function rhs(self, par, y) result(f)
      class(integrator_t), intent(inout) :: self  !! the method
      type(pendulum_t), intent(in) :: par         !! parameters
      real(dp), intent(in) :: y(4)                !! internal state
      real(dp) :: f(4)
      self%n_rhs = self%n_rhs + 1
      if (self%canonical()) then
         f = rhs_qp(par, y)
      else
         f = rhs_qqdot(par, y)
      end if
   end function rhs

   !> Internal state from angles and angular velocities.
   pure function to_internal(self, par, q, qd) result(y)
      class(integrator_t), intent(in) :: self  !! the method
      type(pendulum_t), intent(in) :: par      !! parameters
      real(dp), intent(in) :: q(2)             !! angles [rad]
      real(dp), intent(in) :: qd(2)            !! angular velocities [rad/s]
      real(dp) :: y(4)
      y(1:2) = q
      if (self%canonical()) then
         y(3:4) = momenta(par, q, qd)
      else
         y(3:4) = qd
      end if
   end function to_internal

   !> Angles and angular velocities from the internal state.
   pure subroutine to_physical(self, par, y, q, qd)
      class(integrator_t), intent(in) :: self  !! the method
      type(pendulum_t), intent(in) :: par      !! parameters
      real(dp), intent(in) :: y(4)             !! internal state
      real(dp), intent(out) :: q(2)            !! angles [rad]
      real(dp), intent(out) :: qd(2)           !! angular velocities [rad/s]
      q = y(1:2)
      if (self%canonical()) then
         qd = velocities(par, y(1:2), y(3:4))
      else
         qd = y(3:4)
      end if
   end subroutine to_physical

   !> The state is finite and below `diverged_bound`.
   pure logical function state_ok(y)
      real(dp), intent(in) :: y(:)  !! any state vector
      state_ok = all(ieee_is_finite(y))
      if (state_ok) state_ok = maxval(abs(y)) < diverged_bound
   end function state_ok

   !> One-line description of a step status.
   pure function status_message(stat) result(msg)
      integer, intent(in) :: stat  !! a stat_* code
      character(len=:), allocatable :: msg
      select case (stat)
      case (stat_ok); msg = 'ok'
      case (stat_no_convergence); msg = 'implicit stage iteration did not converge'
      case (stat_nonfinite); msg = 'state became non-finite (NaN, Inf or |y| > 1e30)'
      case (stat_step_too_small); msg = 'adaptive step size fell below roundoff'
      case default; msg = 'unknown status'
      end select
   end function status_message
end module dpend_integrator
