!> The one abstract integrator type of dpend, its step status codes and the state
!> conventions shared by every method.
!>
!> A method advances an internal state y(4): (q1, q2, q̇1, q̇2) for the explicit
!> Runge–Kutta methods, (q1, q2, p1, p2) for the symplectic ones (`canonical()`).
!> Drivers convert with `to_internal` / `to_physical` once at the start and when
!> sampling; the methods never convert inside a step.
!>
!> Every method remembers its last accepted step [t_old, t_new] so that drivers can
!> sample it (dense output) and locate events inside it: each `step` calls
!> `record_step` once, after the step is accepted and before it overwrites (t, y).
!> `interpolate` then evaluates a continuous extension on that step; the default is
!> the cubic Hermite interpolant of the internal state (order 3 locally, O(h⁴)),
!> which methods with a better continuous extension (dopri5, dop853) override.
module dpend_integrator
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, rhs_qqdot, rhs_qp, momenta, velocities
   use dpend_limits, only: default_max_steps
   use dpend_method_options, only: method_options_t
   implicit none
   private
   public :: integrator_t, integrator_configure
   public :: stat_ok, stat_no_convergence, stat_nonfinite, stat_step_too_small
   public :: stat_max_steps, stat_count_limit, stat_tangent_substeps
   public :: status_message, state_ok, diverged_bound

   integer, parameter :: stat_ok = 0              !! the step was taken
   integer, parameter :: stat_no_convergence = 1  !! implicit stages did not converge
   integer, parameter :: stat_nonfinite = 2       !! the state became NaN or Inf
   integer, parameter :: stat_step_too_small = 3  !! adaptive step fell below roundoff
   integer, parameter :: stat_max_steps = 4       !! the integration reached max_steps
   integer, parameter :: stat_count_limit = 5     !! a step or sample count above its limit
   integer, parameter :: stat_tangent_substeps = 6 !! tangent equations need too many substeps

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
      !> Most accepted steps of one integration (one `march_t`) of an adaptive method
      !> (`--max-steps`); reaching it ends the march with stat_max_steps.
      integer(i8) :: max_steps = default_max_steps
      ! The last accepted step, written by `record_step` only; read-only elsewhere.
      logical :: stepped = .false.   !! a step has been recorded since `clear_step`
      real(dp) :: t_old = 0.0_dp     !! start of the last step [s]
      real(dp) :: t_new = 0.0_dp     !! end of the last step [s]
      real(dp) :: y_old(4) = 0.0_dp  !! internal state at t_old
      real(dp) :: y_new(4) = 0.0_dp  !! internal state at t_new
      real(dp) :: f_old(4) = 0.0_dp  !! vector field at y_old (valid if known_f_old)
      real(dp) :: f_new(4) = 0.0_dp  !! vector field at y_new (valid if known_f_new)
      logical :: known_f_old = .false.  !! f_old holds f(y_old)
      logical :: known_f_new = .false.  !! f_new holds f(y_new)
   contains
      procedure(step_i), deferred :: step
      procedure(name_i), deferred :: name
      procedure(order_i), deferred :: order
      procedure :: symplectic => false_property
      procedure :: symmetric => false_property
      procedure :: adaptive => false_property
      !> Whether a step solves equations (fixed-point iterations, counted in n_iter).
      procedure :: implicit => false_property
      procedure :: canonical => false_property
      !> Set the options a method has from one record (`dpend_method_options`);
      !> methods with more options override it and call `integrator_configure`.
      procedure :: configure => integrator_configure
      procedure :: reset_counters
      procedure :: rhs
      procedure :: to_internal
      procedure :: to_physical
      procedure, non_overridable :: record_step
      procedure, non_overridable :: has_step
      procedure, non_overridable :: clear_step
      procedure :: interpolate
   end type integrator_t

   abstract interface
      !> Advance (t, y) by one step. Fixed-step methods take exactly h (h < 0
      !> integrates backward). Adaptive methods take ONE accepted step of size at
      !> most |h| in the direction of h, retrying internally after rejections
      !> (counted in `n_rejected`), and return in h the step size proposed for the
      !> next step; h = 0 asks the method to choose the first step itself (forward).
      !> Drivers cap h so as not to pass their end time. Every successful step calls
      !> `self%record_step(t, y, t_new, y_new)` before overwriting t and y, and
      !> increments `n_steps`. On failure t and y are left unchanged and `stat`
      !> says why (stat_nonfinite, stat_step_too_small, stat_no_convergence).
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

   !> The options every method has: `max_steps` (0 keeps the default).
   subroutine integrator_configure(self, options)
      class(integrator_t), intent(inout) :: self       !! the method
      type(method_options_t), intent(in) :: options    !! its options
      if (options%max_steps > 0) self%max_steps = options%max_steps
   end subroutine integrator_configure

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

   !> The state is finite and below `diverged_bound`: one comparison of Σ|y_i|, which
   !> is NaN or Inf if any component is (a NaN compares false). Under
   !> -ffpe-trap=invalid,overflow a NaN or Inf traps where it is made, before this.
   pure logical function state_ok(y)
      real(dp), intent(in) :: y(:)  !! any state vector
      state_ok = sum(abs(y)) < diverged_bound
   end function state_ok

   !> Remember the accepted step from (t0, y0) to (t1, y1) for `interpolate` and the
   !> event locator. Every `step` calls it once per accepted step, before it
   !> overwrites t and y. A method that has the vector field at either end for free
   !> passes it (f0 = f(y0), f1 = f(y1), internal variables) so that the Hermite
   !> interpolant need not evaluate it; otherwise it is evaluated lazily, only when
   !> `interpolate` is called.
   subroutine record_step(self, t0, y0, t1, y1, f0, f1)
      class(integrator_t), intent(inout) :: self  !! the method
      real(dp), intent(in) :: t0                  !! start of the step [s]
      real(dp), intent(in) :: y0(4)               !! internal state at t0
      real(dp), intent(in) :: t1                  !! end of the step [s]
      real(dp), intent(in) :: y1(4)               !! internal state at t1
      real(dp), intent(in), optional :: f0(4)     !! vector field at y0, if known
      real(dp), intent(in), optional :: f1(4)     !! vector field at y1, if known
      self%stepped = .true.
      self%t_old = t0; self%y_old = y0
      self%t_new = t1; self%y_new = y1
      self%known_f_old = present(f0)
      if (present(f0)) self%f_old = f0
      self%known_f_new = present(f1)
      if (present(f1)) self%f_new = f1
   end subroutine record_step

   !> True once a step has been recorded (and not cleared): `interpolate` and the
   !> event locator have a step [t_old, t_new] to work on.
   pure logical function has_step(self)
      class(integrator_t), intent(in) :: self  !! the method
      has_step = self%stepped
   end function has_step

   !> Forget the last step (call before starting an unrelated trajectory).
   !> Methods with more memory (e.g. a step-size controller) reset it when they
   !> step without a recorded step.
   subroutine clear_step(self)
      class(integrator_t), intent(inout) :: self  !! the method
      self%stepped = .false.
      self%known_f_old = .false.
      self%known_f_new = .false.
   end subroutine clear_step

   !> Internal state at t_eval from the continuous extension of the last step.
   !> Default: cubic Hermite interpolation of y on [t_old, t_new] using y and f at
   !> both ends (Hairer, Nørsett, Wanner, Solving ODEs I, eq. II.6.7); f is
   !> evaluated (and counted in `n_rhs`) only on the first call within a step and
   !> only where the step did not provide it. Local error O(h⁴) for any method of
   !> order ≥ 3. t_eval should lie in [t_old, t_new] (otherwise the cubic is
   !> extrapolated). Without a recorded step y_eval is left unchanged.
   subroutine interpolate(self, par, t_eval, y_eval)
      class(integrator_t), intent(inout) :: self  !! the method
      type(pendulum_t), intent(in) :: par         !! parameters
      real(dp), intent(in) :: t_eval              !! time [s]
      real(dp), intent(inout) :: y_eval(4)        !! internal state at t_eval
      real(dp) :: h, th, dy(4)
      if (.not. self%stepped) return
      h = self%t_new - self%t_old
      if (t_eval == self%t_new .or. h == 0.0_dp) then
         y_eval = self%y_new
         return
      else if (t_eval == self%t_old) then
         y_eval = self%y_old
         return
      end if
      if (.not. self%known_f_old) then
         self%f_old = self%rhs(par, self%y_old)
         self%known_f_old = .true.
      end if
      if (.not. self%known_f_new) then
         self%f_new = self%rhs(par, self%y_new)
         self%known_f_new = .true.
      end if
      th = (t_eval - self%t_old)/h
      dy = self%y_new - self%y_old
      y_eval = (1.0_dp - th)*self%y_old + th*self%y_new &
               + th*(th - 1.0_dp)*((1.0_dp - 2.0_dp*th)*dy &
                                   + (th - 1.0_dp)*h*self%f_old + th*h*self%f_new)
   end subroutine interpolate

   !> One-line description of a step status.
   pure function status_message(stat) result(msg)
      integer, intent(in) :: stat  !! a stat_* code
      character(len=:), allocatable :: msg
      select case (stat)
      case (stat_ok); msg = 'ok'
      case (stat_no_convergence); msg = 'implicit stage iteration did not converge'
      case (stat_nonfinite); msg = 'state became non-finite (NaN, Inf or |y| > 1e30)'
      case (stat_step_too_small); msg = 'adaptive step size fell below roundoff'
      case (stat_max_steps); msg = 'maximum number of steps reached (--max-steps)'
      case (stat_count_limit); msg = 'step or sample count above its limit (1e12 steps, ' &
                                     //'1e9 samples)'
      case (stat_tangent_substeps); msg = 'tangent equations need more than 1e6 substeps ' &
                                          //'in one step (use a smaller --dt)'
      case default; msg = 'unknown status'
      end select
   end function status_message
end module dpend_integrator
