!> The one abstract integrator type of dpend, its step status codes and the state
!> conventions shared by every method.
!>
!> A method advances an internal state y(2n) of a `model_t` with n degrees of freedom:
!> (q, q̇) for the explicit Runge–Kutta methods, (q, p) for the methods on canonical
!> variables (`canonical()`) on a Hamiltonian model (`canonical_on(model)`). Most of
!> them need the Hamiltonian (`needs_hamiltonian()`); the Gauss methods run on (q, q̇)
!> when the model has none (damped, driven). No method names a model:
!> it calls the model's vector field and, where it has them, its fast-path hooks.
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
   use dpend_model, only: model_t, max_state
   use dpend_limits, only: default_max_steps, diverged_bound
   use dpend_error, only: error_t, fatal_error
   use dpend_method_options, only: method_options_t
   use dpend_method_registry, only: field_method_names
   implicit none
   private
   public :: integrator_t, integrator_configure
   public :: stat_ok, stat_no_convergence, stat_nonfinite, stat_step_too_small
   public :: stat_max_steps, stat_count_limit, stat_tangent_substeps, stat_stopped
   public :: status_message, state_ok, diverged_bound

   integer, parameter :: stat_ok = 0              !! the step was taken
   integer, parameter :: stat_no_convergence = 1  !! implicit stages did not converge
   integer, parameter :: stat_nonfinite = 2       !! the state became NaN or Inf
   integer, parameter :: stat_step_too_small = 3  !! adaptive step fell below roundoff
   integer, parameter :: stat_max_steps = 4       !! the integration reached max_steps
   integer, parameter :: stat_count_limit = 5     !! a step or sample count above its limit
   integer, parameter :: stat_tangent_substeps = 6 !! tangent equations need too many substeps
   integer, parameter :: stat_stopped = 7         !! stopped on request (dpend_cancel)


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
      integer :: n_rec = 0           !! size of the recorded states (2n)
      real(dp) :: y_old(max_state) = 0.0_dp  !! internal state at t_old (first n_rec)
      real(dp) :: y_new(max_state) = 0.0_dp  !! internal state at t_new
      real(dp) :: f_old(max_state) = 0.0_dp  !! vector field at y_old (if known_f_old)
      real(dp) :: f_new(max_state) = 0.0_dp  !! vector field at y_new (if known_f_new)
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
      !> Whether the method needs a Hamiltonian model (default: `canonical()`).
      procedure :: needs_hamiltonian => canonical_property
      procedure, non_overridable :: canonical_on
      !> Set the options a method has from one record (`dpend_method_options`);
      !> methods with more options override it and call `integrator_configure`.
      procedure :: configure => integrator_configure
      procedure :: reset_counters
      procedure :: rhs
      procedure :: to_internal
      procedure :: to_physical
      procedure, non_overridable :: record_step
      procedure, non_overridable :: record_finite_step
      procedure, non_overridable :: check_model
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
      !> `self%record_step(n, t, y, t_new, y_new)` before overwriting t and y, and
      !> increments `n_steps`. On failure t and y are left unchanged and `stat`
      !> says why (stat_nonfinite, stat_step_too_small, stat_no_convergence).
      subroutine step_i(self, model, t, y, h, stat)
         import :: integrator_t, model_t, dp
         class(integrator_t), intent(inout) :: self  !! the method and its counters
         class(model_t), intent(in) :: model         !! the system
         real(dp), intent(inout) :: t                !! time [s]
         real(dp), intent(inout) :: y(:)             !! internal state, size 2n
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

   !> Default of `needs_hamiltonian`: the methods on canonical variables.
   pure logical function canonical_property(self)
      class(integrator_t), intent(in) :: self  !! the method
      canonical_property = self%canonical()
   end function canonical_property

   !> Whether the internal state on `model` is (q, p): a canonical method on a
   !> Hamiltonian model; (q, q̇) otherwise.
   pure logical function canonical_on(self, model)
      class(integrator_t), intent(in) :: self  !! the method
      class(model_t), intent(in) :: model      !! the system
      canonical_on = self%canonical()
      if (canonical_on) canonical_on = model%hamiltonian()
   end function canonical_on

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
   subroutine rhs(self, model, t, y, f)
      class(integrator_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model         !! the system
      real(dp), intent(in) :: t                   !! time [s]
      real(dp), intent(in) :: y(:)                !! internal state
      real(dp), intent(out) :: f(:)               !! its rate
      self%n_rhs = self%n_rhs + 1
      if (self%canonical_on(model)) then
         call model%canonical_field(t, y, f)
      else
         call model%field(t, y, f)
      end if
   end subroutine rhs

   !> Internal state from angles and angular velocities.
   pure function to_internal(self, model, q, qd, t) result(y)
      class(integrator_t), intent(in) :: self  !! the method
      class(model_t), intent(in) :: model      !! the system
      real(dp), intent(in) :: q(:)             !! coordinates [rad]
      real(dp), intent(in) :: qd(:)            !! their rates [rad/s]
      real(dp), intent(in), optional :: t      !! time [s] (default 0)
      real(dp) :: y(2*size(q))
      real(dp) :: tt
      integer :: n
      n = size(q)
      tt = 0.0_dp
      if (present(t)) tt = t
      y(1:n) = q
      if (self%canonical_on(model)) then
         call model%momenta(tt, [q, qd], y(n + 1:))
      else
         y(n + 1:) = qd
      end if
   end function to_internal

   !> Angles and angular velocities from the internal state.
   pure subroutine to_physical(self, model, y, q, qd, t)
      class(integrator_t), intent(in) :: self  !! the method
      class(model_t), intent(in) :: model      !! the system
      real(dp), intent(in) :: y(:)             !! internal state
      real(dp), intent(out) :: q(:)            !! coordinates [rad]
      real(dp), intent(out) :: qd(:)           !! their rates [rad/s]
      real(dp), intent(in), optional :: t      !! time [s] (default 0)
      real(dp) :: tt
      integer :: n
      n = size(q)
      tt = 0.0_dp
      if (present(t)) tt = t
      q = y(1:n)
      if (self%canonical_on(model)) then
         call model%velocities(tt, y, qd)
      else
         qd = y(n + 1:2*n)
      end if
   end subroutine to_physical

   !> The state is finite and below `diverged_bound`: one comparison of Σ|y_i|, which
   !> is NaN or Inf if any component is (a NaN compares false). Under
   !> -ffpe-trap=invalid,overflow a NaN or Inf traps where it is made, before this.
   pure logical function state_ok(n, y)
      integer, intent(in) :: n      !! its size
      real(dp), intent(in) :: y(n)  !! any state vector
      if (n == 4) then   ! constant size: no loop set-up between two steps
         state_ok = sum(abs(y(1:4))) < diverged_bound
      else
         state_ok = sum(abs(y)) < diverged_bound
      end if
   end function state_ok

   !> Refuse a model that lacks structure the method needs (one line, e.g.
   !> "invalid method: verlet needs a Hamiltonian model; the damped chain of 2 links is
   !> not (use rk4, dopri5, dop853, midpoint, gauss4, gauss6 or gauss8)").
   subroutine check_model(self, model, error)
      class(integrator_t), intent(in) :: self           !! the method
      class(model_t), intent(in) :: model               !! the system
      type(error_t), allocatable, intent(out) :: error  !! set if the method cannot run it
      if (self%needs_hamiltonian() .and. .not. model%hamiltonian()) then
         call fatal_error(error, 'invalid method: '//self%name()//' needs a Hamiltonian ' &
                          //'model; the '//model%name()//' is not (use '// &
                          field_method_names()//')')
      else if (model%n_state() > max_state) then
         call fatal_error(error, 'invalid model: the '//model%name()//' has too many degrees ' &
                          //'of freedom for the integrators (at most 32)')
      end if
   end subroutine check_model

   !> Remember the accepted step from (t0, y0) to (t1, y1) for `interpolate` and the
   !> event locator. Every `step` calls it once per accepted step, before it
   !> overwrites t and y. A method that has the vector field at either end for free
   !> passes it (f0 = f(y0), f1 = f(y1), internal variables) so that the Hermite
   !> interpolant need not evaluate it; otherwise it is evaluated lazily, only when
   !> `interpolate` is called.
   subroutine record_step(self, n, t0, y0, t1, y1, f0, f1)
      class(integrator_t), intent(inout) :: self  !! the method
      integer, intent(in) :: n                    !! size of the states (2n)
      real(dp), intent(in) :: t0                  !! start of the step [s]
      real(dp), intent(in) :: y0(n)               !! internal state at t0
      real(dp), intent(in) :: t1                  !! end of the step [s]
      real(dp), intent(in) :: y1(n)               !! internal state at t1
      real(dp), intent(in), optional :: f0(n)     !! vector field at y0, if known
      real(dp), intent(in), optional :: f1(n)     !! vector field at y1, if known
      ! explicit sizes: the step's tail stays short (it runs between the steps)
      self%stepped = .true.
      self%n_rec = n
      self%t_old = t0
      self%t_new = t1
      self%known_f_old = present(f0)
      self%known_f_new = present(f1)
      if (n == 4) then   ! constant-size copies, inline (a run-time size calls memcpy,
         ! three calls per step: rk4 was 8 % slower for it)
         self%y_old(1:4) = y0(1:4)
         self%y_new(1:4) = y1(1:4)
         if (present(f0)) self%f_old(1:4) = f0(1:4)
         if (present(f1)) self%f_new(1:4) = f1(1:4)
      else
         self%y_old(:n) = y0
         self%y_new(:n) = y1
         if (present(f0)) self%f_old(:n) = f0
         if (present(f1)) self%f_new(:n) = f1
      end if
   end subroutine record_step

   !> `state_ok(n, y1)` and, when it holds, `record_step`: one call for the tail of a
   !> step (a call between two steps costs the short explicit methods a few % each).
   subroutine record_finite_step(self, n, t0, y0, t1, y1, ok, f0)
      class(integrator_t), intent(inout) :: self  !! the method
      integer, intent(in) :: n                    !! size of the states (2n)
      real(dp), intent(in) :: t0                  !! start of the step [s]
      real(dp), intent(in) :: y0(n)               !! internal state at t0
      real(dp), intent(in) :: t1                  !! end of the step [s]
      real(dp), intent(in) :: y1(n)               !! internal state at t1
      logical, intent(out) :: ok                  !! y1 is finite and below diverged_bound
      real(dp), intent(in), optional :: f0(n)     !! vector field at y0, if known
      ok = state_ok(n, y1)
      if (ok) call self%record_step(n, t0, y0, t1, y1, f0=f0)
   end subroutine record_finite_step

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
   subroutine interpolate(self, model, t_eval, y_eval)
      class(integrator_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model         !! the system
      real(dp), intent(in) :: t_eval              !! time [s]
      real(dp), intent(inout) :: y_eval(:)        !! internal state at t_eval
      real(dp) :: h, th, dy(max_state), yl(max_state), fl(max_state)
      integer :: n
      if (.not. self%stepped) return
      n = self%n_rec
      h = self%t_new - self%t_old
      if (t_eval == self%t_new .or. h == 0.0_dp) then
         y_eval = self%y_new(:n)
         return
      else if (t_eval == self%t_old) then
         y_eval = self%y_old(:n)
         return
      end if
      ! (through locals: self is also the counter's owner)
      if (.not. self%known_f_old) then
         yl(:n) = self%y_old(:n)
         call self%rhs(model, self%t_old, yl(:n), fl(:n))
         self%f_old(:n) = fl(:n)
         self%known_f_old = .true.
      end if
      if (.not. self%known_f_new) then
         yl(:n) = self%y_new(:n)
         call self%rhs(model, self%t_new, yl(:n), fl(:n))
         self%f_new(:n) = fl(:n)
         self%known_f_new = .true.
      end if
      th = (t_eval - self%t_old)/h
      dy(:n) = self%y_new(:n) - self%y_old(:n)
      y_eval = (1.0_dp - th)*self%y_old(:n) + th*self%y_new(:n) &
               + th*(th - 1.0_dp)*((1.0_dp - 2.0_dp*th)*dy(:n) &
                                   + (th - 1.0_dp)*h*self%f_old(:n) + th*h*self%f_new(:n))
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
      case (stat_stopped); msg = 'stopped on request (dpend_cancel)'
      case default; msg = 'unknown status'
      end select
   end function status_message
end module dpend_integrator
