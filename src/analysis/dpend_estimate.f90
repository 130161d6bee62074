!> Estimating the initial state and, on request, the joint damping of a chain from a
!> measured series of angles (`dpend fit`): nonlinear least squares by
!> Levenberg–Marquardt with the sensitivities from the variational equations.
!>
!> Parameters p = (q(t₁), q̇(t₁)[, c]) (2N or 3N): the state at the first sample time t₁
!> and the damping coefficients c_i [N m s]. Residuals: r = q_model(t_k) − q_data(t_k)
!> for every angle of every sample k of the fit window, each wrapped into [−π, π) (so
!> that data given modulo 2π fit as well); or, with `positions`, the positions of the
!> link ends P_i = A(t) + Σ_(j≤i) L_j (cos q_j, sin q_j) minus the measured ones [m]
!> (A the pin, moving with the support), their sensitivities ∂P/∂q · ∂q/∂p.
!>
!> Sensitivities. The model is integrated by one of the explicit Runge–Kutta methods
!> (default dop853) landing exactly on every sample time (no interpolation of the
!> data's instants), and the tangent propagation of `dpend_tangent` carries
!> ∂y/∂p along each step. For the damping it is the augmented system: the
!> coefficients are carried as constant state components (`sens_model_t`:
!> y' = (q, c, q̇, 0) with rates (q̇, 0, q̈, 0)), so that the variational equation of
!> the augmented field, whose Jacobian has the column block ∂q̈/∂c = M⁻¹ ∂Q/∂c
!> (Q = −C q̇ the damping torques), gives the parameter sensitivities
!> s' = J s + ∂f/∂c with the same RK4 substeps as those of the state — no finite
!> differences (the test suite compares them with central differences).
!>
!> The iteration: LM with Marquardt's scaling D = diag(JᵀJ),
!> (JᵀJ + λ D) δ = −Jᵀ r, λ divided by 10 after a successful step and multiplied by 10
!> after a failed one. A chaotic series is fitted by continuation: the window grows from
!> the fewest samples that determine p, each stage started from the previous estimate
!> (a good guess at the start of the series is a poor one over a long window): the next
!> window ends at the sample before the stage's model leaves the data by more than
!> max(10 × its RMS residual, 0.01 rad), and is at least 1.25 times longer. The damping
!> is held at its guess while the window is shorter than 2π sqrt(Σ L_i / g) (a fraction
!> of a swing barely determines it, and a runaway value makes the model stiff), and kept
!> ≥ 0 (projected). Optionally (`starts` > 1) the first stage is started from several
!> rates, the lowest cost kept: samples far apart on a chaotic motion (the reference
!> table, one per second) leave the finite-difference rates far from the basin.
!>
!> Statistics at the solution: σ² = Σ r²/(m − P) with m residuals and P parameters, the
!> covariance σ² (JᵀJ)⁻¹, standard errors its diagonal's square roots, the correlation
!> matrix, and 95 % intervals p ± t_(0.975, m−P) SE (Student's t). The prediction
!> horizon: with the model of the fit window t ≤ T integrated over the whole series,
!> the time after T until the first sample where some angle differs from the data by
!> more than the tolerance.
!>
!> Bounded work. `estimate_fit_work` bounds, before any fitting, what
!> `fit_series` can do: the integration steps over each span (the steps per second of
!> model time measured by a short probe integration of the first guess, at most
!> `probe_steps` steps, extrapolated to the span, plus one step per sample for landing
!> on the sample times) × (1 + P) with the sensitivities (each of the P tangent
!> columns costs about one more integration) × the integrations of the
!> Levenberg–Marquardt calls (1 + 2 `max_iter` + 30 each: an accepted trial per
!> iteration, at most as many rejected ones as accepted ones plus the 30 that end a
!> call) × the continuation stages (the window growing by the least allowed, k/4) and
!> the starts; and the memory of the residuals and Jacobians. `fit_series` counts the
!> steps it really takes and stops with an error when they exceed `work_limit`, so the
!> bound holds even where the probe's rate was too low (a chaotic series speeding
!> up).
module dpend_estimate
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error, error_bad_input
   use dpend_model, only: model_t, max_dof, max_state
   use dpend_model_factory, only: model_spec_t, new_model, model_catalogue, find_model, &
                                  spec_values, derived_default, &
                                  model_info_t
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: march_t
   use dpend_tangent, only: tangent_t
   use dpend_lapack, only: dpotrf, dpotrs
   use dpend_limits, only: max_fit_work, default_max_steps
   use dpend_strings, only: real_str, to_str
   use dpend_kinds, only: i8
   use dpend_progress, only: progress_t
   implicit none
   private
   public :: fit_problem_t, fit_result_t, fit_series, evaluate_fit, sens_model_t
   public :: initial_guess, student_t95, fit_work_t, estimate_fit_work, set_fitted, n_fitted
   public :: noise_estimate, observation_noise, misfit_suspects, misfit_factor, suspect_t, condition_text

   !> Most steps of the probe integration that measures the steps per second of model
   !> time (`estimate_fit_work`): a few milliseconds.
   integer, parameter :: probe_steps = 4096
   !> Integrations of one Levenberg–Marquardt call beyond 2 per iteration (the first
   !> evaluation and the 30 rejected trials that end a call).
   integer, parameter :: lm_extra_evaluations = 31
   !> Largest condition number of the sensitivity matrix with unit columns that a fit
   !> accepts: beyond, some combination of the parameters is not determined (its
   !> standard error would exceed 1e8 times the others').
   real(dp), parameter :: max_condition = 1e8_dp

   !> What is fitted and how the model is integrated.
   type :: fit_problem_t
      !> the model with fixed parameters (used when no model parameter is fitted)
      class(model_t), allocatable :: model
      !> the model's specification: a fit of model parameters builds the model from it
      !> (`new_model`, the general form) with the fitted values set by name
      type(model_spec_t) :: spec
      !> the model parameters fitted (`set_fitted`), e.g. 'damping': their names, the
      !> components of each, and per component the first guess and the accepted range
      character(len=32), allocatable :: fit_names(:)
      integer, allocatable :: fit_counts(:)
      real(dp), allocatable :: theta0(:), theta_lower(:), theta_upper(:)
      !> per fitted component: its parameter's name, which of its `comp_count`
      !> components it is, its label ('c1', 'm2', 'g'), the scale of its
      !> finite-difference step, and whether its sensitivity comes from central
      !> differences of the field (`comp_generic`: the model gives no `parameter_rates`)
      character(len=32), allocatable :: comp_names(:)
      integer, allocatable :: comp_index(:), comp_count(:)
      character(len=24), allocatable :: comp_labels(:)
      character(len=16), allocatable :: comp_units(:)   !! each component's units
      real(dp), allocatable :: comp_scale(:)
      logical, allocatable :: comp_generic(:)
      !> labels of all P parameters (the state's, then the components'), for messages;
      !> unallocated: p1, p2, ...
      character(len=24), allocatable :: labels(:)
      !> the fitted model parameters are held at their guess while the window is
      !> shorter than this [s] (a fraction of a swing barely determines them)
      real(dp) :: hold_period = huge(1.0_dp)
      !> which observed coordinates are angles (residuals wrapped into [−π, π));
      !> unallocated: all
      logical, allocatable :: angular(:)
      !> the geometry of observed positions: link lengths [m] and the support's motion
      real(dp), allocatable :: l(:)           !! lengths [m]
      real(dp) :: sup_a(2) = 0.0_dp           !! support amplitudes [m]
      real(dp) :: sup_w = 0.0_dp              !! support angular frequency [rad/s]
      real(dp) :: sup_phi(2) = 0.0_dp         !! support phases [rad]
      character(len=:), allocatable :: method !! explicit method (default dop853)
      real(dp) :: rtol = 1e-12_dp             !! its tolerances
      real(dp) :: atol = 1e-14_dp
      real(dp) :: dt = 1e-3_dp                !! first trial step [s]
      integer :: max_iter = 200               !! LM iterations per stage
      !> the observations are the positions x_i, y_i of the link ends [m] (lengths `l`,
      !> the support's motion from sup_*), not the angles
      logical :: positions = .false.
      !> first-stage starts: the guess and starts-1 others whose rates spread over
      !> guess ± max(|guess rates|, 1 rad/s) (a Halton sequence); the lowest cost wins
      integer :: starts = 1
      !> most accepted steps of one adaptive integration between two samples
      integer(i8) :: max_steps = default_max_steps
      !> the links are point masses at their ends (`--body point`): a fitted
      !> length l_i moves the centre of mass com_i = l_i with it
      logical :: com_at_tip = .false.
      !> most step-equivalents (steps × (1 + P) with sensitivities) of the whole fit;
      !> `fit_series` stops with an error beyond
      real(dp) :: work_limit = max_fit_work
      !> the noise of the observations [rad or m] (`--sigma`); 0: estimated from the
      !> data (`observation_noise`)
      real(dp) :: noise = 0.0_dp
   end type fit_problem_t

   !> What a fit costs at most (`estimate_fit_work`), known before it starts.
   type :: fit_work_t
      real(dp) :: rate = 0.0_dp         !! integration steps per second of model time [1/s]
      real(dp) :: steps = 0.0_dp        !! steps of one integration over the fit window
      real(dp) :: evaluations = 0.0_dp  !! integrations of the model, at most
      integer :: stages = 0             !! continuation stages, at most
      real(dp) :: work = 0.0_dp         !! step-equivalents in all (steps × (1 + P))
      real(dp) :: bytes = 0.0_dp        !! memory of residuals and Jacobians [B]
   end type fit_work_t

   !> The work a running fit has done, against its limit, and its progress report.
   type :: fit_counter_t
      real(dp) :: used = 0.0_dp            !! step-equivalents so far
      real(dp) :: limit = huge(1.0_dp)     !! most step-equivalents
      logical :: exceeded = .false.        !! `used` went beyond `limit`
      logical :: show = .false.            !! report progress on stderr
      type(progress_t) :: progress         !! integrations done of the bound
   end type fit_counter_t

   !> The estimates and their statistics.
   type :: fit_result_t
      integer :: n = 0                      !! links N
      integer :: np = 0                     !! parameters P
      integer :: k_fit = 0                  !! samples in the fit window
      integer :: dof = 0                    !! m − P
      integer :: iterations = 0             !! LM iterations, all stages
      integer :: stages = 0                 !! continuation stages
      logical :: converged = .false.        !! the last stage met its criterion
      real(dp), allocatable :: p(:)         !! estimates (P)
      real(dp), allocatable :: guess(:)     !! the first guess (P)
      real(dp), allocatable :: se(:)        !! standard errors (P)
      real(dp), allocatable :: cov(:, :)    !! covariance (P, P)
      real(dp), allocatable :: corr(:, :)   !! correlations (P, P)
      real(dp) :: t95 = 0.0_dp              !! Student t quantile of the 95 % intervals
      real(dp) :: rms = 0.0_dp              !! RMS residual of the fit window [rad]
      real(dp) :: sigma = 0.0_dp            !! σ = sqrt(Σ r²/(m − P)) [rad]
      real(dp), allocatable :: q_model(:, :)   !! model angles at every sample (N, K)
      real(dp), allocatable :: resid(:, :)     !! data − model, wrapped (N, K) [rad]
      real(dp) :: t_window = 0.0_dp         !! end T of the fit window [s]
      logical :: has_after = .false.        !! samples after T exist
      real(dp) :: horizon = 0.0_dp          !! prediction horizon after T [s]
      logical :: horizon_censored = .false. !! never left the tolerance (a lower bound)
      real(dp) :: tolerance = 0.1_dp        !! its tolerance [rad]
      !> singular values of the sensitivity matrix with unit columns, largest first
      real(dp), allocatable :: singular(:)
      real(dp) :: condition = 0.0_dp        !! their ratio largest / smallest
      !> right singular vectors (P, P), columns in the order of `singular` (scaled
      !> parameters: each parameter in units of its column's norm)
      real(dp), allocatable :: directions(:, :)
   end type fit_result_t

   !> An unfitted parameter component that may be wrong (`misfit_suspects`).
   type :: suspect_t
      character(len=24) :: label = ''   !! e.g. 'l2'
      real(dp) :: rms = 0.0_dp          !! RMS residual with it fitted too (linearized)
   end type suspect_t

   !> A fit whose RMS residual exceeds this factor times the noise (given or estimated)
   !> does not describe the data (`misfit_suspects`).
   real(dp), parameter :: misfit_factor = 3.0_dp

   !> A model held by an array element (the finite-difference models).
   type :: model_box_t
      class(model_t), allocatable :: m
   end type model_box_t

   !> A model with its damping carried as constant state components (see the notes).
   type, extends(model_t) :: sens_model_t
      class(model_t), allocatable :: base   !! the system
      integer :: n = 0                      !! its degrees of freedom N
      integer :: nc = 0                     !! fitted parameter components
      !> per component: its parameter's name, that parameter's components, which one
      character(len=32), allocatable :: names(:)
      integer, allocatable :: counts(:), index(:)
      !> per component: central differences of the field (no `parameter_rates`), the
      !> two models of its stencil and the weights of base, fd(1), fd(2) [1/unit]
      logical, allocatable :: generic(:)
      type(model_box_t), allocatable :: fd(:, :)
      real(dp), allocatable :: fw(:, :)
   contains
      procedure :: n_dof => sens_n_dof
      procedure :: name => sens_name
      procedure :: field => sens_field
      procedure :: jacobian => sens_jacobian
      procedure :: energy => sens_energy
      procedure :: energy_scale => sens_energy_scale
      procedure :: potential_energy => sens_potential_energy
      procedure :: conservative => sens_false
      procedure :: autonomous => sens_autonomous
   end type sens_model_t

contains

   ! ------------------------------------------------------------ the augmented model

   pure integer function sens_n_dof(self)
      class(sens_model_t), intent(in) :: self
      sens_n_dof = self%n + self%nc
   end function sens_n_dof

   pure function sens_name(self) result(name)
      class(sens_model_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = self%base%name()//' with its parameters'
   end function sens_name

   pure logical function sens_false(self)
      class(sens_model_t), intent(in) :: self
      sens_false = .false.
   end function sens_false

   pure logical function sens_autonomous(self)
      class(sens_model_t), intent(in) :: self
      sens_autonomous = self%base%autonomous()
   end function sens_autonomous

   !> (q, q̇) of the augmented y = (q, c, q̇, z).
   pure subroutine inner(n, nc, y, yb)
      integer, intent(in) :: n, nc
      real(dp), intent(in) :: y(*)
      real(dp), intent(out) :: yb(2*n)
      yb(1:n) = y(1:n)
      yb(n + 1:2*n) = y(n + nc + 1:2*n + nc)
   end subroutine inner

   pure subroutine sens_field(self, t, y, f)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: yb(2*max_dof), fb(2*max_dof)
      integer :: n, nc
      n = self%n
      nc = self%nc
      call inner(n, nc, y, yb)
      call self%base%field(t, yb, fb)
      f(1:n) = fb(1:n)
      f(n + 1:n + nc) = 0.0_dp
      f(n + nc + 1:2*n + nc) = fb(n + 1:2*n)
      f(2*n + nc + 1:2*n + 2*nc) = 0.0_dp
   end subroutine sens_field

   !> The base Jacobian and, for the fitted parameters θ, ∂q̈/∂θ from the model
   !> (`parameter_rates`).
   !> A component without `parameter_rates` (`generic`): the weighted field of the
   !> stencil's models, w_1 (f(θ + h_1) − f(θ)) + w_2 (f(θ + h_2) − f(θ)) (central
   !> differences, or one-sided of second order at an end of the parameter's range).
   pure subroutine sens_jacobian(self, t, y, jac)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: yb(2*self%n), jb(2*self%n, 2*self%n), d(self%n, self%nc)
      real(dp) :: dall(self%n, max_dof), f0(2*max_dof), f1(2*max_dof), f2(2*max_dof)
      integer :: n, nc, j, c
      integer :: map(2*self%n)
      logical :: have_f0
      n = self%n
      nc = self%nc
      call inner(n, nc, y, yb)
      call self%base%jacobian(t, yb, jb)
      map = [(j, j=1, n), (j, j=n + nc + 1, 2*n + nc)]
      jac = 0.0_dp
      jac(map, map) = jb
      if (nc == 0) return
      have_f0 = .false.
      do c = 1, nc
         if (self%generic(c)) then
            if (.not. have_f0) call self%base%field(t, yb, f0)
            have_f0 = .true.
            call self%fd(1, c)%m%field(t, yb, f1)
            call self%fd(2, c)%m%field(t, yb, f2)
            ! the weights sum to 0: differences first, so that a parameter without
            ! effect gives exactly 0 (whatever the compiler contracts into FMAs)
            d(:, c) = self%fw(2, c)*(f1(n + 1:2*n) - f0(n + 1:2*n)) + &
                      self%fw(3, c)*(f2(n + 1:2*n) - f0(n + 1:2*n))
         else
            ! the model's rates of the whole parameter, once per parameter
            if (c == 1) then
               call self%base%parameter_rates(t, yb, trim(self%names(c)), &
                                              dall(:, :self%counts(c)))
            else if (self%names(c) /= self%names(c - 1) .or. self%generic(c - 1)) then
               call self%base%parameter_rates(t, yb, trim(self%names(c)), &
                                              dall(:, :self%counts(c)))
            end if
            d(:, c) = dall(:, self%index(c))
         end if
      end do
      jac(n + nc + 1:2*n + nc, n + 1:n + nc) = d
   end subroutine sens_jacobian

   pure real(dp) function sens_energy(self, t, y)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yb(2*self%n)
      call inner(self%n, self%nc, y, yb)
      sens_energy = self%base%energy(t, yb)
   end function sens_energy

   pure real(dp) function sens_potential_energy(self, t, y)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yb(2*self%n)
      call inner(self%n, self%nc, y, yb)
      sens_potential_energy = self%base%potential_energy(t, yb)
   end function sens_potential_energy

   pure real(dp) function sens_energy_scale(self, e0)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: e0
      sens_energy_scale = self%base%energy_scale(e0)
   end function sens_energy_scale

   ! ------------------------------------------------------------ residuals, Jacobian

   !> Residuals r (N k) of the first k samples for the parameters p and, if `jac` is
   !> present, their Jacobian ∂r/∂p (N k, P). Residual (i, j) is r(i + N (j − 1)).
   subroutine evaluate_fit(prob, p, t, q, k, r, error, jac, steps, budget)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: p(:)                      !! parameters
      real(dp), intent(in) :: t(:)                      !! sample times [s]
      real(dp), intent(in) :: q(:, :)                   !! measured angles (N, K) [rad]
                                                        !! or positions (2N, K) [m]
      integer, intent(in) :: k                          !! samples used
      real(dp), intent(out) :: r(:)                     !! residuals (N k) [rad]
      type(error_t), allocatable, intent(out) :: error  !! the integration failed
      real(dp), intent(out), optional :: jac(:, :)      !! ∂r/∂p (N k, P)
      integer(i8), intent(out), optional :: steps       !! integration steps taken
      !> with `steps`: stop with an error once more steps than this are taken
      real(dp), intent(in), optional :: budget
      type(sens_model_t) :: sm
      class(integrator_t), allocatable :: integ
      type(tangent_t) :: tan
      type(march_t) :: march
      real(dp), allocatable :: y(:), v0(:, :), o(:), d(:, :), lv(:), dl(:, :)
      integer, allocatable :: lc(:)
      real(dp) :: tt, h
      integer :: n, nc, np, ns, j, stat, no
      no = size(q, 1)
      n = merge(no/2, no, prob%positions)
      np = size(p)
      if (present(steps)) steps = 0
      allocate (o(no), d(no, n), dl(no, n))
      call observed_lengths(prob, p, n, lv, lc)
      call start_model(prob, p, t(1), sm, integ, y, error)
      if (allocated(error)) return
      nc = sm%nc
      ns = 2*(n + nc)
      if (present(jac)) then
         allocate (v0(ns, np))
         v0 = 0.0_dp
         do j = 1, n
            v0(j, j) = 1.0_dp
            v0(n + nc + j, n + j) = 1.0_dp
         end do
         do j = 1, nc
            v0(n + j, 2*n + j) = 1.0_dp
         end do
         call tan%init(v0)
         tan%theta = 0.05_dp
      end if
      call observe(prob, t(1), p(1:n), o, d, lv, dl)
      r(1:no) = residual(prob, o, q(:, 1))
      if (present(jac)) then
         jac(1:no, :) = matmul(d, v0(1:n, :))
         call add_length_columns(1)
      end if
      tt = t(1)
      h = prob%dt
      call integ%clear_step()
      do j = 2, k
         call march%start(integ, tt, t(j), h)
         do while (.not. march%finished)
            call march%next(integ, sm, tt, y, h, stat)
            if (present(steps)) then
               steps = steps + 1
               if (present(budget)) then
                  if (real(steps, dp) > budget) then
                     call fatal_error(error, 'the integration took more than '// &
                                      real_str(budget, 3)//' steps')
                     return
                  end if
               end if
            end if
            if (stat /= stat_ok) then
               call fatal_error(error, 'the model''s integration failed: '// &
                                status_message(stat)//' after t = '//real_str(tt)//' s')
               return
            end if
            if (present(jac)) then
               call tan%propagate(integ, sm)
               if (tan%too_stiff) then
                  call fatal_error(error, 'the sensitivities could not be propagated ' &
                                   //'(a step too long for the local frequency) after t = ' &
                                   //real_str(tt)//' s')
                  return
               end if
               if (tan%too_large) then
                  call fatal_error(error, 'the sensitivities grew beyond 1e100 by t = ' &
                                   //real_str(tt)//' s: the trajectory is chaotic over ' &
                                   //'the fit window (fit a shorter --fit-window or series)')
                  return
               end if
            end if
         end do
         call observe(prob, tt, y(1:n), o, d, lv, dl)
         r(no*(j - 1) + 1:no*j) = residual(prob, o, q(:, j))
         if (present(jac)) then
            jac(no*(j - 1) + 1:no*j, :) = matmul(d, tan%v(1:n, :))
            call add_length_columns(j)
         end if
      end do
   contains
      !> Positions with fitted lengths: ∂P/∂l_i added to the columns of the lengths
      !> (besides their effect on the motion, carried by the tangents), sample jj.
      subroutine add_length_columns(jj)
         integer, intent(in) :: jj
         integer :: i
         do i = 1, size(lc)
            if (lc(i) > 0) jac(no*(jj - 1) + 1:no*jj, 2*n + lc(i)) = &
               jac(no*(jj - 1) + 1:no*jj, 2*n + lc(i)) + dl(:, i)
         end do
      end subroutine add_length_columns
   end subroutine evaluate_fit

   !> The link lengths that place observed positions: `prob%l`, with the
   !> fitted components of `l` at their values in p (kept in range, as the model
   !> takes them); lc(i) the fitted component that is l_i (0: fixed). No positions:
   !> empty.
   pure subroutine observed_lengths(prob, p, n, lv, lc)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:)                    !! parameters
      integer, intent(in) :: n                        !! links
      real(dp), allocatable, intent(out) :: lv(:)     !! lengths [m]
      integer, allocatable, intent(out) :: lc(:)      !! fitted component per link
      integer :: c
      if (.not. prob%positions) then
         allocate (lv(0), lc(0))
         return
      end if
      lv = prob%l(:n)
      allocate (lc(n))
      lc = 0
      do c = 1, n_fitted(prob)
         if (prob%comp_names(c) /= 'l') cycle
         lc(prob%comp_index(c)) = c
         lv(prob%comp_index(c)) = min(max(p(2*n + c), prob%theta_lower(c)), &
                                      prob%theta_upper(c))
      end do
   end subroutine observed_lengths

   !> The augmented model for the parameters p, the integrator (`prob%method`, its
   !> tolerances and `max_steps`) and its internal state y at t1.
   subroutine start_model(prob, p, t1, sm, integ, y, error)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:)                             !! parameters
      real(dp), intent(in) :: t1                               !! first sample time [s]
      type(sens_model_t), intent(out) :: sm
      class(integrator_t), allocatable, intent(out) :: integ
      real(dp), allocatable, intent(out) :: y(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: n, nc, ns
      call model_for(prob, p, sm, error)
      if (allocated(error)) return
      n = sm%n
      nc = sm%nc
      ns = 2*(n + nc)
      call new_integrator(prob%method, integ, error, method_options_t(rtol=prob%rtol, &
                          atol=prob%atol, max_steps=prob%max_steps))
      if (allocated(error)) return
      call integ%check_model(sm, error)
      if (allocated(error)) return
      allocate (y(ns))
      y = 0.0_dp
      y(1:n) = p(1:n)
      y(n + nc + 1:2*n + nc) = p(n + 1:2*n)
      if (nc > 0) y(n + 1:n + nc) = p(2*n + 1:2*n + nc)
      y = integ%to_internal(sm, y(1:n + nc), y(n + nc + 1:ns), t1)
   end subroutine start_model

   !> The augmented model for the parameters p: with fitted model parameters, the
   !> model of the specification with their values (kept in range) set by name.
   subroutine model_for(prob, p, sm, error)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:)
      type(sens_model_t), intent(out) :: sm
      type(error_t), allocatable, intent(out) :: error
      type(model_spec_t) :: spec
      real(dp), allocatable :: theta(:)
      integer :: n, nc, c
      nc = n_fitted(prob)
      if (nc > 0) then
         n = (size(p) - nc)/2
         theta = min(max(p(2*n + 1:), prob%theta_lower), prob%theta_upper)
         spec = spec_with(prob, theta)
         call new_model(spec, sm%base, error)
         if (allocated(error)) return
         sm%n = n
         sm%nc = nc
         sm%names = prob%comp_names
         sm%counts = prob%comp_count
         sm%index = prob%comp_index
         sm%generic = prob%comp_generic
         allocate (sm%fd(2, nc), sm%fw(3, nc))
         sm%fw = 0.0_dp
         do c = 1, nc
            if (prob%comp_generic(c)) call stencil(c)
            if (allocated(error)) return
         end do
      else
         allocate (sm%base, source=prob%model)
         sm%n = prob%model%n_dof()
         sm%nc = 0
      end if
   contains
      !> The stencil of component c: steps h = 6e-6 max(|θ|, scale) (about the cube root
      !> of the rounding unit, relative), central where θ ± h lie in the range, else
      !> one-sided of second order (θ, θ ± h, θ ± 2h).
      subroutine stencil(c)
         integer, intent(in) :: c
         real(dp) :: h
         integer :: sg
         h = 6e-6_dp*max(abs(theta(c)), prob%comp_scale(c))
         if (theta(c) - h >= prob%theta_lower(c) .and. theta(c) + h <= prob%theta_upper(c)) &
            then
            sm%fw(:, c) = [0.0_dp, 0.5_dp/h, -0.5_dp/h]
            call build_fd(c, [h, -h])
         else
            sg = merge(1, -1, theta(c) + 2.0_dp*h <= prob%theta_upper(c))
            sm%fw(:, c) = [-1.5_dp, 2.0_dp, -0.5_dp]/(real(sg, dp)*h)
            call build_fd(c, [real(sg, dp)*h, real(2*sg, dp)*h])
         end if
      end subroutine stencil
      !> The two models of component c's stencil, θ_c + steps(k).
      subroutine build_fd(c, steps)
         integer, intent(in) :: c
         real(dp), intent(in) :: steps(2)
         real(dp) :: th(size(theta))
         integer :: k
         do k = 1, 2
            th = theta
            th(c) = theta(c) + steps(k)
            call new_model(spec_with(prob, th), sm%fd(k, c)%m, error)
            if (allocated(error)) return
         end do
      end subroutine build_fd
   end subroutine model_for

   !> The problem's specification, general form, with the fitted components set to
   !> theta (by name; a component replaces its value in the parameter's list).
   function spec_with(prob, theta) result(spec)
      type(fit_problem_t), intent(in) :: prob   !! the problem
      real(dp), intent(in) :: theta(:)          !! values of the fitted components
      type(model_spec_t) :: spec
      real(dp), allocatable :: v(:)
      integer :: c
      spec = prob%spec
      spec%general = .true.
      do c = 1, size(theta)
         v = spec_values(spec, trim(prob%comp_names(c)), prob%comp_count(c))
         v(prob%comp_index(c)) = theta(c)
         call spec%set(trim(prob%comp_names(c)), v)
         if (prob%com_at_tip .and. prob%comp_names(c) == 'l') then
            v = spec_values(spec, 'com', prob%comp_count(c))
            v(prob%comp_index(c)) = theta(c)
            call spec%set('com', v)
         end if
      end do
   end function spec_with

   !> Index of parameter `name` in the description `info` (0: none).
   pure integer function param_index(info, name) result(j)
      type(model_info_t), intent(in) :: info  !! a model's description
      character(len=*), intent(in) :: name    !! parameter name
      do j = 1, size(info%params)
         if (info%params(j)%name == trim(name)) return
      end do
      j = 0
   end function param_index

   !> The observations o at time t for the angles q, and ∂o/∂q: the angles themselves,
   !> or the positions of the link ends P_i = A(t) + Σ_(j≤i) L_j (cos q_j, sin q_j)
   !> (lengths lv), and then ∂o/∂L (dl).
   pure subroutine observe(prob, t, q, o, d, lv, dl)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: t, q(:)
      real(dp), intent(out) :: o(:), d(:, :)
      real(dp), intent(in) :: lv(:)          !! lengths [m] (positions)
      real(dp), intent(out) :: dl(:, :)      !! ∂o/∂L (positions)
      real(dp) :: pos(2)
      integer :: i, j, n
      n = size(q)
      d = 0.0_dp
      dl = 0.0_dp
      if (.not. prob%positions) then
         o = q
         do i = 1, n
            d(i, i) = 1.0_dp
         end do
         return
      end if
      pos = prob%sup_a*cos(prob%sup_w*t + prob%sup_phi)
      do i = 1, n
         pos = pos + lv(i)*[cos(q(i)), sin(q(i))]
         o(2*i - 1:2*i) = pos
         do j = 1, i
            d(2*i - 1, j) = -lv(j)*sin(q(j))
            d(2*i, j) = lv(j)*cos(q(j))
            dl(2*i - 1:2*i, j) = [cos(q(j)), sin(q(j))]
         end do
      end do
   end subroutine observe

   !> Model minus data: angles wrapped into [−π, π), positions as they are.
   pure function residual(prob, o, data) result(r)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: o(:), data(:)
      real(dp) :: r(size(o))
      if (prob%positions) then
         r = o - data
      else
         r = wrap_angles(prob, o - data)
      end if
   end function residual

   !> The components of x that are angles (`prob%angular`; all if unset) wrapped into
   !> [−π, π), the others as they are.
   pure function wrap_angles(prob, x) result(w)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: x(:)
      real(dp) :: w(size(x))
      if (allocated(prob%angular)) then
         w = merge(wrap(x), x, prob%angular)
      else
         w = wrap(x)
      end if
   end function wrap_angles

   !> The angles of the link ends' positions xy (2N, K) at times t.
   pure function angles_of(prob, t, xy) result(q)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: t(:), xy(:, :)
      real(dp) :: q(size(xy, 1)/2, size(t))
      real(dp) :: prev(2)
      integer :: i, j
      do j = 1, size(t)
         prev = prob%sup_a*cos(prob%sup_w*t(j) + prob%sup_phi)
         do i = 1, size(q, 1)
            q(i, j) = atan2(xy(2*i, j) - prev(2), xy(2*i - 1, j) - prev(1))
            prev = xy(2*i - 1:2*i, j)
         end do
      end do
   end function angles_of

   !> x wrapped into [−π, π).
   elemental real(dp) function wrap(x)
      real(dp), intent(in) :: x
      wrap = modulo(x + pi, 2.0_dp*pi) - pi
   end function wrap

   ! ------------------------------------------------------------ the fit

   !> The first guess: angles of the first sample, rates from the three-point
   !> (two-point for two samples) difference of the first samples; the fitted model
   !> parameters at `theta0`.
   function initial_guess(prob, t, obs) result(p)
      type(fit_problem_t), intent(in) :: prob   !! the problem
      real(dp), intent(in) :: t(:)              !! sample times [s]
      real(dp), intent(in) :: obs(:, :)         !! angles (N, K) [rad] or positions
      real(dp), allocatable :: p(:)
      real(dp), allocatable :: q(:, :)
      integer :: n
      real(dp) :: h1, h2
      if (prob%positions) then
         q = angles_of(prob, t(:min(3, size(t))), obs(:, :min(3, size(t))))
      else
         q = obs(:, :min(3, size(t)))
      end if
      n = size(q, 1)
      allocate (p(2*n + n_fitted(prob)))
      p(1:n) = q(:, 1)
      if (size(t) >= 3) then
         ! derivative at t1 of the parabola through the first three samples
         h1 = t(2) - t(1)
         h2 = t(3) - t(1)
         p(n + 1:2*n) = wrap_angles(prob, q(:, 2) - q(:, 1))*h2/(h1*(h2 - h1)) - &
                        wrap_angles(prob, q(:, 3) - q(:, 1))*h1/(h2*(h2 - h1))
      else
         p(n + 1:2*n) = wrap_angles(prob, q(:, 2) - q(:, 1))/(t(2) - t(1))
      end if
      if (n_fitted(prob) > 0) p(2*n + 1:) = prob%theta0
   end function initial_guess

   !> The most work `fit_series` can do on these samples (see the module's notes):
   !> integration steps, integrations, stages, step-equivalents and memory. Costs a
   !> probe integration of at most `probe_steps` steps.
   subroutine estimate_fit_work(prob, t, q, t_window, work, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      real(dp), intent(in) :: t_window                  !! end T of the fit window [s]
      type(fit_work_t), intent(out) :: work             !! the bounds
      type(error_t), allocatable, intent(out) :: error  !! too few samples
      real(dp), allocatable :: p(:)
      real(dp) :: lm, quick_lm, fac, m
      integer :: no, n, np, k_fit, kmax, k, k_min
      no = size(q, 1)
      n = merge(no/2, no, prob%positions)
      np = 2*n + n_fitted(prob)
      kmax = size(t)
      k_fit = count(t <= t_window)
      if (no*k_fit <= np) then
         call fatal_error(error, to_str(k_fit)//' samples in the fit window give ' &
                          //to_str(no*k_fit)//' residuals for '//to_str(np)// &
                          ' parameters: at least '//to_str(np/no + 1)//' samples are needed')
         return
      end if
      p = initial_guess(prob, t(:k_fit), q(:, :k_fit))
      work%rate = probe_rate(prob, p, t(1), t(kmax))
      work%steps = steps_to(k_fit)
      fac = real(1 + np, dp)
      lm = real(2*prob%max_iter + lm_extra_evaluations, dp)
      quick_lm = real(2*min(prob%max_iter, 30) + lm_extra_evaluations, dp)
      k_min = min(k_fit, max(3, np/no + 1))
      work%evaluations = 0.0_dp
      work%work = 0.0_dp
      if (prob%starts > 1) then   ! the quick first stages and their costs
         call add(real(prob%starts, dp)*quick_lm, fac, k_min)
         call add(real(prob%starts, dp), 1.0_dp, k_min)
      end if
      k = k_min
      work%stages = 0
      do   ! the stages, the window growing by the least the continuation allows
         call add(lm, fac, k)
         work%stages = work%stages + 1
         if (k == k_fit) exit
         call add(1.0_dp, 1.0_dp, k_fit)
         k = min(k_fit, k + max(1, k/4))
      end do
      call add(1.0_dp, fac, k_fit)   ! the statistics
      call add(1.0_dp, 1.0_dp, kmax) ! the prediction of the whole series
      ! residuals and Jacobians of the fit window (r, rn, jac, jn and the temporaries
      ! of JᵀJ), the model and residual series (K), the normal equations
      m = real(no, dp)*real(k_fit, dp)
      work%bytes = 8.0_dp*(5.0_dp*m*real(np, dp) + 4.0_dp*m + &
                           4.0_dp*real(no, dp)*real(kmax, dp) + 4.0_dp*real(np, dp)**2)
   contains
      !> Steps of one integration over the first k samples.
      real(dp) function steps_to(k) result(st)
         integer, intent(in) :: k
         st = work%rate*(t(k) - t(1)) + real(k - 1, dp)
      end function steps_to
      !> `count` integrations over the first k samples, each step costing `cost`.
      subroutine add(count, cost, k)
         real(dp), intent(in) :: count, cost
         integer, intent(in) :: k
         work%evaluations = work%evaluations + count
         work%work = work%work + count*cost*steps_to(k)
      end subroutine add
   end subroutine estimate_fit_work

   !> Integration steps per second of model time [1/s] of the motion from p at t1,
   !> measured over at most `probe_steps` steps towards t_end (an integration that
   !> fails at once: 0, the fit itself then reports it). At most 1e100.
   real(dp) function probe_rate(prob, p, t1, t_end) result(rate)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:)        !! parameters
      real(dp), intent(in) :: t1, t_end   !! the span [s]
      type(sens_model_t) :: sm
      class(integrator_t), allocatable :: integ
      type(march_t) :: march
      type(error_t), allocatable :: error
      real(dp), allocatable :: y(:)
      real(dp) :: tt, h
      integer :: steps, stat
      rate = 0.0_dp
      call start_model(prob, p, t1, sm, integ, y, error)
      if (allocated(error)) return
      tt = t1
      h = prob%dt
      call integ%clear_step()
      call march%start(integ, tt, t_end, h)
      steps = 0
      do while (.not. march%finished .and. steps < probe_steps)
         call march%next(integ, sm, tt, y, h, stat)
         if (stat /= stat_ok) exit
         steps = steps + 1
      end do
      if (.not. (tt - t1 > 1e-100_dp*real(steps, dp))) then
         if (steps > 0) rate = 1e100_dp
         return
      end if
      rate = min(real(steps, dp)/(tt - t1), 1e100_dp)
   end function probe_rate

   !> Fit the samples with t ≤ t_window (all when t_window ≥ the last time), then
   !> predict the whole series and measure the horizon with `tolerance` [rad]. The
   !> integration steps are counted: beyond `prob%work_limit` step-equivalents the fit
   !> stops with an error. With `progress`, long fits report on stderr the integrations
   !> done of the bound of `estimate_fit_work` (the time left is then an upper bound).
   subroutine fit_series(prob, t, q, t_window, tolerance, res, error, guess, progress)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! angles (N, K) [rad], or
                                                        !! positions (2N, K) [m]
      real(dp), intent(in) :: t_window                  !! end T of the fit window [s]
      real(dp), intent(in) :: tolerance                 !! horizon tolerance [rad or m]
      type(fit_result_t), intent(out) :: res            !! estimates and statistics
      type(error_t), allocatable, intent(out) :: error  !! too few samples, failed runs
      real(dp), intent(in), optional :: guess(:)        !! first guess (default:
                                                        !! `initial_guess`)
      logical, intent(in), optional :: progress         !! report progress on stderr
      type(fit_counter_t) :: counter
      type(fit_work_t) :: work
      counter%limit = prob%work_limit
      if (present(progress)) counter%show = progress
      if (counter%show) then
         call estimate_fit_work(prob, t, q, t_window, work, error)
         if (allocated(error)) return
         call counter%progress%start('dpend fit (integrations of at most '// &
                                     real_str(work%evaluations)//')', &
                                     int(min(work%evaluations, 1e15_dp), i8), 0_i8, .false.)
         ! a line only once the fit has run for a while (none for a quick fit)
         counter%progress%t_last = counter%progress%t_start
         counter%progress%reported = 0
      end if
      call fit_stages(prob, t, q, t_window, tolerance, res, counter, error, guess)
      if (counter%show .and. counter%progress%reported > 0) call counter%progress%finish()
   end subroutine fit_series

   !> `fit_series` with its work counter: the continuation stages, the statistics of
   !> the fit window, the prediction of the whole series.
   subroutine fit_stages(prob, t, q, t_window, tolerance, res, counter, error, guess)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      real(dp), intent(in) :: t_window                  !! end T of the fit window [s]
      real(dp), intent(in) :: tolerance                 !! horizon tolerance [rad or m]
      type(fit_result_t), intent(out) :: res            !! estimates and statistics
      type(fit_counter_t), intent(inout) :: counter     !! work done, its limit
      type(error_t), allocatable, intent(out) :: error  !! too few samples, failed runs
      real(dp), intent(in), optional :: guess(:)        !! first guess
      integer :: n, np, no
      no = size(q, 1)
      n = merge(no/2, no, prob%positions)
      res%n = n
      np = 2*n + n_fitted(prob)
      res%np = np
      res%tolerance = tolerance
      res%k_fit = count(t <= t_window)
      if (no*res%k_fit <= np) then
         call fatal_error(error, to_str(res%k_fit)//' samples in the fit window give ' &
                          //to_str(no*res%k_fit)//' residuals for '//to_str(np)// &
                          ' parameters: at least '//to_str(np/no + 1)//' samples are needed')
         return
      end if
      res%t_window = t(res%k_fit)
      if (present(guess)) then
         res%guess = guess
      else
         res%guess = initial_guess(prob, t(:res%k_fit), q(:, :res%k_fit))
      end if
      res%p = res%guess
      call continuation(prob, t, q, res, counter, error)
      if (allocated(error)) return
      call window_statistics(prob, t, q, res, counter, error)
      if (allocated(error)) return
      call predict_series(prob, t, q, tolerance, res, counter, error)
   end subroutine fit_stages

   !> The continuation stages: the window grows from the fewest samples that determine
   !> p to the fit window (see the module's notes); res%p, iterations, stages and
   !> converged updated.
   subroutine continuation(prob, t, q, res, counter, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      type(fit_result_t), intent(inout) :: res          !! p from the guess, k_fit set
      type(fit_counter_t), intent(inout) :: counter     !! work done, its limit
      type(error_t), allocatable, intent(out) :: error  !! failed runs
      real(dp), allocatable :: r(:)
      real(dp) :: period, thr
      integer :: np, k_min, k_stage, it, j, no
      logical :: conv
      no = size(q, 1)
      np = res%np
      ! continuation: the window grows from the fewest samples that determine p
      k_min = min(res%k_fit, max(3, np/no + 1))
      k_stage = k_min
      res%iterations = 0
      res%stages = 0
      if (prob%starts > 1) then
         call best_start(prob, t, q, k_stage, res%p, it, counter, error)
         res%iterations = it
         if (allocated(error)) return
      end if
      period = prob%hold_period
      allocate (r(no*res%k_fit))
      do
         ! the damping is held at its guess while the window is shorter than a swing
         ! (a fraction of a swing barely determines it, and large values make the
         ! model stiff)
         call levenberg_marquardt(prob, t, q, k_stage, res%p, it, conv, counter, error, &
                                  hold_damping=t(k_stage) - t(1) < period .and. &
                                  k_stage < res%k_fit)
         res%iterations = res%iterations + it
         res%stages = res%stages + 1
         if (allocated(error)) return
         if (k_stage == res%k_fit) exit
         ! the next window: up to the sample before the stage's model leaves the data
         ! by max(10 RMS, 0.01 rad or 0.01 Σ L_i), at least 1.25 times longer
         call counted_fit(prob, res%p, t, q, res%k_fit, r, counter, error)
         if (allocated(error)) return
         thr = 0.01_dp   ! (rad; m per metre of chain for positions)
         if (prob%positions) thr = 0.01_dp*sum(prob%l)
         thr = max(10.0_dp*sqrt(sum(r(:no*k_stage)**2)/real(no*k_stage, dp)), thr)
         j = k_stage + 1
         do while (j <= res%k_fit)
            if (maxval(abs(r(no*(j - 1) + 1:no*j))) > thr) exit
            j = j + 1
         end do
         k_stage = min(res%k_fit, max(j - 1, k_stage + max(1, k_stage/4)))
      end do
      res%converged = conv
   end subroutine continuation

   !> The statistics of the fit window at res%p: RMS, σ, the covariance σ² (JᵀJ)⁻¹,
   !> standard errors, correlations and Student's t; refused when JᵀJ is singular.
   subroutine window_statistics(prob, t, q, res, counter, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      type(fit_result_t), intent(inout) :: res          !! estimates; statistics set
      type(fit_counter_t), intent(inout) :: counter     !! work done, its limit
      type(error_t), allocatable, intent(out) :: error  !! failed run, singular JᵀJ
      real(dp), allocatable :: r(:), jac(:, :), a(:, :), ds(:)
      integer :: np, kk, info, i, j, no
      no = size(q, 1)
      np = res%np
      kk = res%k_fit
      allocate (r(no*kk), jac(no*kk, np))
      call counted_fit(prob, res%p, t, q, kk, r, counter, error, jac)
      if (allocated(error)) return
      res%dof = no*kk - np
      res%rms = sqrt(sum(r**2)/real(no*kk, dp))
      res%sigma = sqrt(sum(r**2)/real(res%dof, dp))
      a = matmul(transpose(jac), jac)
      allocate (res%cov(np, np), res%corr(np, np), res%se(np))
      ! JᵀJ scaled to a unit diagonal (its condition then measures the parameters'
      ! dependence, not their units); nearly singular means not determined
      allocate (ds(np))
      do i = 1, np
         ds(i) = 0.0_dp
         if (a(i, i) > tiny(1.0_dp)) ds(i) = 1.0_dp/sqrt(a(i, i))
      end do
      call check_visible(prob, q, res, jac, error)
      if (allocated(error)) return
      call identifiability(jac, ds, res)
      info = 0
      if (any(.not. (ds > 0.0_dp))) then
         info = minloc(ds, dim=1)
      else
         do j = 1, np
            a(:, j) = a(:, j)*ds*ds(j)
         end do
         call dpotrf('L', np, a, np, info)
         if (info == 0) then
            do i = 1, np   ! a pivot below 1e-7: condition number above about 1e14
               if (.not. (a(i, i) > 1e-7_dp)) info = i
               if (info /= 0) exit
            end do
         end if
      end if
      if (info /= 0 .or. res%condition > max_condition) then
         call fatal_error(error, 'invalid fit parameters: '//undetermined(prob, res, ds)// &
                          ' (singular values of the scaled sensitivities '// &
                          singular_text(res)//'; condition number '// &
                          condition_text(res%condition)//' > '//real_str(max_condition)// &
                          ')', &
                          error_bad_input)
         return
      end if
      res%cov = 0.0_dp
      do i = 1, np
         res%cov(i, i) = 1.0_dp
      end do
      call dpotrs('L', np, np, a, np, res%cov, np, info)
      do j = 1, np
         res%cov(:, j) = res%cov(:, j)*ds*ds(j)
      end do
      res%cov = res%sigma**2*res%cov
      do i = 1, np
         res%se(i) = sqrt(max(res%cov(i, i), 0.0_dp))
      end do
      do j = 1, np
         do i = 1, np
            res%corr(i, j) = res%cov(i, j)/max(res%se(i)*res%se(j), tiny(1.0_dp))
         end do
      end do
      res%t95 = student_t95(res%dof)
   end subroutine window_statistics

   !> Refuse a fitted model parameter the data cannot see, judged before any
   !> normalisation: fitted alone, its standard error would be σ/‖J_j‖ (σ the noise of
   !> the observations, `observation_noise`; J_j its column of sensitivities); when that
   !> exceeds the parameter's own scale s_j (the value given, or the model's default),
   !> changing it by s_j moves the predicted series by less than the noise, and no
   !> interval the fit could give would mean anything. A parameter at 0 (no damping,
   !> no support motion) has no scale of its own: it is refused only when its column,
   !> times 0.01 in its units, stays below what the fit resolves. (Scaling the
   !> columns to unit length first, as `identifiability` does, hides this: a column of
   !> rounding errors scales to 1 like any other.)
   subroutine check_visible(prob, q, res, jac, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      type(fit_result_t), intent(in) :: res             !! the fit (np, k_fit, p)
      real(dp), intent(in) :: jac(:, :)                 !! ∂r/∂p over the fit window
      type(error_t), allocatable, intent(out) :: error  !! a parameter not seen
      character(len=:), allocatable :: how, names, detail, ou, against
      real(dp) :: sigma, scale, norm, floor, level
      integer :: c, j, n_state
      if (n_fitted(prob) == 0) return
      ou = 'rad'
      if (prob%positions) ou = 'm'
      if (allocated(prob%angular)) then
         if (.not. all(prob%angular)) ou = '(in the observations'' units)'
      end if
      sigma = observation_noise(prob, q, res%k_fit, how, floor)
      n_state = res%np - n_fitted(prob)
      names = ''
      detail = ''
      do c = 1, n_fitted(prob)
         j = n_state + c
         norm = sqrt(sum(jac(:, j)**2))
         ! its own scale: the value given (or the model's default); a parameter at 0
         ! (no damping, no support motion) has none, and is judged only on whether the
         ! data see it at all: its column above the fit's resolution
         scale = abs(prob%theta0(c))
         level = sigma
         if (.not. (scale > 0.0_dp)) then
            scale = prob%comp_scale(c)
            level = floor
         end if
         if (norm*scale > level) cycle
         if (len(names) > 0) names = names//', '
         names = names//trim(prob%comp_labels(c))
         if (len(detail) == 0) then
            detail = trim(prob%comp_labels(c))//' by '// &
               real_str(scale, 3)//' '//trim(prob%comp_units(c))//' moves the fitted series '// &
               'by '//real_str(norm*scale, 3)//' '//ou//' (root sum of squares over the window)'
            against = 'the noise '//real_str(sigma, 3)//' '//ou//' ('//how//')'
            if (level < sigma) against = 'what the fit resolves, '//real_str(level, 3)//' '// &
                                         ou//' (10 rtol times the largest observation)'
         end if
      end do
      if (len(names) == 0) return
      call fatal_error(error, 'invalid fit parameters: '//names//trim(merge(' is ', ' are', &
                       index(names, ',') == 0))//' not determined by the data: changing ' &
                       //detail//', less than '//against// &
                       '; fix each at a known value, or fit data in which it acts', &
                       error_bad_input)
   end subroutine check_visible

   !> The noise of the observations of the first k samples: the value given (`noise`,
   !> --sigma), else `noise_estimate`; never below what the fit can resolve, 10 × rtol
   !> × the observations' magnitude (data at rest, or exact, would otherwise have
   !> noise 0 and make rounding errors look significant). `how` says which.
   function observation_noise(prob, q, k, how, resolution) result(sigma)
      type(fit_problem_t), intent(in) :: prob            !! the problem
      real(dp), intent(in) :: q(:, :)                    !! observations (N or 2N, K)
      integer, intent(in) :: k                           !! samples used
      character(len=:), allocatable, intent(out) :: how  !! where σ comes from
      real(dp), intent(out), optional :: resolution      !! the floor alone
      real(dp) :: sigma
      real(dp) :: floor
      floor = 10.0_dp*max(prob%rtol, epsilon(1.0_dp))*max(maxval(abs(q(:, :k))), &
                                                          tiny(1.0_dp))
      if (prob%noise > 0.0_dp) then
         sigma = prob%noise
         how = 'given by --sigma'
      else
         sigma = noise_estimate(prob, q, k)
         how = 'estimated from the third differences of the data; --sigma gives it'
      end if
      if (present(resolution)) resolution = floor
      if (sigma < floor) then
         sigma = floor
         how = 'the resolution of the fit, 10 rtol times the largest observation: '// &
               'the data show less noise'
      end if
   end function observation_noise

   !> The singular values and right singular vectors of the sensitivity matrix J with
   !> its columns scaled to unit norm (`ds`: 1/norm, 0 for a zero column), by one-sided
   !> Jacobi rotations (Hestenes; accurate for the small singular values, which JᵀJ
   !> would square below the rounding unit).
   subroutine identifiability(jac, ds, res)
      real(dp), intent(in) :: jac(:, :)        !! ∂r/∂p (m, P)
      real(dp), intent(in) :: ds(:)            !! column scales (P)
      type(fit_result_t), intent(inout) :: res !! singular, condition, directions set
      real(dp), allocatable :: u(:, :), v(:, :), sv(:), col(:)
      real(dp) :: alpha, beta, gamma, zeta, tt, cs, sn
      integer :: np, i, j, sweep, order(size(ds))
      logical :: rotated
      np = size(ds)
      u = jac
      do j = 1, np
         u(:, j) = u(:, j)*ds(j)
      end do
      allocate (v(np, np))
      v = 0.0_dp
      do j = 1, np
         v(j, j) = 1.0_dp
      end do
      do sweep = 1, 60
         rotated = .false.
         do i = 1, np - 1
            do j = i + 1, np
               alpha = sum(u(:, i)**2)
               beta = sum(u(:, j)**2)
               gamma = sum(u(:, i)*u(:, j))
               if (abs(gamma) <= 1e-15_dp*sqrt(alpha*beta) .or. gamma == 0.0_dp) cycle
               rotated = .true.
               zeta = (beta - alpha)/(2.0_dp*gamma)
               tt = sign(1.0_dp, zeta)/(abs(zeta) + sqrt(1.0_dp + zeta**2))
               cs = 1.0_dp/sqrt(1.0_dp + tt**2)
               sn = cs*tt
               col = u(:, i)
               u(:, i) = cs*col - sn*u(:, j)
               u(:, j) = sn*col + cs*u(:, j)
               col = v(:, i)
               v(:, i) = cs*col - sn*v(:, j)
               v(:, j) = sn*col + cs*v(:, j)
            end do
         end do
         if (.not. rotated) exit
      end do
      allocate (sv(np))
      do j = 1, np
         sv(j) = sqrt(sum(u(:, j)**2))
      end do
      do i = 1, np   ! largest first
         order(i) = maxloc(sv, dim=1)
         sv(order(i)) = -sv(order(i)) - 1.0_dp
      end do
      sv = -sv - 1.0_dp
      res%singular = sv(order)
      res%directions = v(:, order)
      if (res%singular(np) > 0.0_dp) then
         res%condition = res%singular(1)/res%singular(np)
      else
         res%condition = huge(1.0_dp)
      end if
   end subroutine identifiability

   !> A condition number, 3 digits ('infinite' for a zero singular value).
   function condition_text(x) result(s)
      real(dp), intent(in) :: x  !! condition number
      character(len=:), allocatable :: s
      if (x >= huge(1.0_dp)) then
         s = 'infinite'
      else
         s = real_str(x, 3)
      end if
   end function condition_text

   !> The singular values, 3 digits each, comma-separated.
   function singular_text(res) result(s)
      type(fit_result_t), intent(in) :: res  !! with singular set
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(res%singular)
         if (i > 1) s = s//', '
         s = s//real_str(res%singular(i), 3)
      end do
   end function singular_text

   !> Label of parameter i (`prob%labels`; else the component's label for a model
   !> parameter, 'state <i>' for the state).
   function label_of(prob, i, np) result(s)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      integer, intent(in) :: i                 !! parameter
      integer, intent(in) :: np                !! parameters P
      character(len=:), allocatable :: s
      integer :: c
      s = 'state '//to_str(i)
      c = i - (np - n_fitted(prob))
      if (allocated(prob%labels)) then
         if (i <= size(prob%labels)) s = trim(prob%labels(i))
      else if (c >= 1) then
         s = trim(prob%comp_labels(c))
      end if
   end function label_of

   !> The combination the data do not determine: the right singular vector of the
   !> smallest singular value, its components above 0.05 named. When they are all
   !> fitted masses (and damping) changed by one common factor, it is the absolute
   !> mass scale; otherwise the combination in scaled parameters.
   function undetermined(prob, res, ds) result(s)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      type(fit_result_t), intent(in) :: res    !! with directions set
      real(dp), intent(in) :: ds(:)            !! the columns' scales (1/norm)
      character(len=:), allocatable :: s, names, comb
      real(dp), allocatable :: v(:), rel(:)
      integer :: i, np, n, c
      logical :: scale_only
      np = size(res%singular)
      v = res%directions(:, np)
      if (maxval(abs(v)) > 0.0_dp) v = v/v(maxloc(abs(v), dim=1))
      n = (np - n_fitted(prob))/2
      names = ''
      comb = ''
      scale_only = n_fitted(prob) > 0
      allocate (rel(0))
      do i = 1, np
         if (abs(v(i)) <= 0.05_dp) cycle
         if (len(names) > 0) names = names//','
         names = names//label_of(prob, i, np)
         if (len(comb) > 0) comb = comb//merge(' + ', ' - ', v(i) > 0.0_dp)
         if (len(comb) == 0 .and. v(i) < 0.0_dp) comb = '-'
         comb = comb//real_str(abs(v(i)), 3)//' '//label_of(prob, i, np)
         c = i - 2*n
         if (c < 1) then
            scale_only = .false.
         else if (res%p(i) == 0.0_dp) then
            scale_only = .false.
         else
            rel = [rel, ds(i)*v(i)/res%p(i)]   ! δθ_i = ds_i v_i ∝ θ_i for a scale
         end if
      end do
      if (scale_only .and. size(rel) > 1) &
         scale_only = maxval(rel) - minval(rel) <= 1e-3_dp*maxval(abs(rel))
      if (scale_only .and. size(rel) > 1) then
         s = names//' together are not determined by the data: their common scale ' &
             //'(multiplying them all by one factor leaves the motion unchanged: the ' &
             //'absolute mass scale for masses, g/l for lengths with g; only their ratios ' &
             //'are determined: fit all but one, e.g. '//names(index(names, ',') + 1:)//')'
      else
         s = names//trim(merge(' is ', ' are', index(names, ',') == 0))//' not determined ' &
             //'by the data: the combination '//comb//' (each parameter in units of its ' &
             //'sensitivity) leaves the residuals unchanged'
      end if
   end function undetermined

   !> The noise of the observations of the first k samples, estimated from the data
   !> alone: third differences of a smooth signal sampled densely are small, those of
   !> independent noise of standard deviation σ have variance 20 σ², so
   !> σ ≈ sqrt(Σ (Δ³x)² / (20 count)) over all coordinates (angle steps wrapped into
   !> [−π, π)). An upper bound where the motion is fast against the sampling; 0 for
   !> fewer than 4 samples.
   function noise_estimate(prob, q, k) result(sigma)
      type(fit_problem_t), intent(in) :: prob  !! the problem (which coordinates wrap)
      real(dp), intent(in) :: q(:, :)          !! observations (N or 2N, K)
      integer, intent(in) :: k                 !! samples used
      real(dp) :: sigma
      real(dp), allocatable :: d1(:, :), d3(:, :)
      integer :: j
      sigma = 0.0_dp
      if (k < 4) return
      allocate (d1(size(q, 1), k - 1))
      do j = 1, k - 1
         if (prob%positions) then
            d1(:, j) = q(:, j + 1) - q(:, j)
         else
            d1(:, j) = wrap_angles(prob, q(:, j + 1) - q(:, j))
         end if
      end do
      d3 = d1(:, 3:) - 2.0_dp*d1(:, 2:k - 2) + d1(:, 1:k - 3)
      sigma = sqrt(sum(d3**2)/(20.0_dp*real(size(d3), dp)))
   end function noise_estimate

   !> The unfitted parameter components that may be wrong when the fit at res%p leaves
   !> residuals far above the noise: every continuous parameter of the model's
   !> description not fitted, each component ranked by the score test (the cost
   !> reduction a step in it alone would give once the fitted parameters are
   !> re-adjusted, to first order): with the fitted sensitivities' columns Q
   !> orthonormal and J_j the candidate's, c = J_j − Q Qᵀ J_j, the cost falls by
   !> (cᵀ r)²/(cᵀ c). Returned by predicted RMS, lowest first (components the data do
   !> not see left out).
   subroutine misfit_suspects(prob, t, q, res, suspects, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem as fitted
      real(dp), intent(in) :: t(:), q(:, :)             !! the series
      type(fit_result_t), intent(in) :: res             !! the fit
      type(suspect_t), allocatable, intent(out) :: suspects(:)  !! ranked
      type(error_t), allocatable, intent(out) :: error  !! an integration failed
      type(fit_problem_t) :: ext
      type(model_info_t), allocatable :: models(:)
      character(len=32), allocatable :: names(:)
      real(dp), allocatable :: r(:), jac(:, :), qm(:, :), p(:), c(:), pred(:), effect(:)
      real(dp) :: cost, cc, nq
      integer :: k, j, i, m, np, nfit, n, free, ncand, o, idx
      allocate (suspects(0))
      models = model_catalogue()
      k = find_model(models, prob%spec%model_name())
      n = (res%np - n_fitted(prob))/2
      free = max_dof - n - n_fitted(prob)
      allocate (names(0))
      if (allocated(prob%fit_names)) names = prob%fit_names
      ext = prob
      ! every component of every continuous parameter, the fitted ones first
      do j = 1, size(models(k)%params)
         associate (par => models(k)%params(j))
            if (par%integer_valued) cycle
            ! a rod's com and inertia follow its l and m, candidates already (as
            ! candidates too they cost the ranking 15 times the fit: 25 s against
            ! 1.6 s in the debug build, differences through the factory every step)
            if (derived_default(prob%spec, par%name)) cycle
            if (no_effect(par%name)) cycle
            if (par%count < 0) then
               idx = n
            else
               idx = par%count
            end if
            do i = 1, idx
               if (fitted(par%name, i)) cycle
               if (free <= 0) exit
               names = [character(len=32) :: names, component_label(par%name, i, idx)]
               free = free - 1
            end do
         end associate
      end do
      ! one at a time with the fitted ones: a scale all of them leave free is no matter
      call set_fitted(ext, names, error, scale_check=.false.)
      if (allocated(error)) return
      ext%labels = [character(len=24) :: ext%comp_labels]
      nfit = res%np
      np = 2*n + n_fitted(ext)
      ncand = np - nfit
      if (ncand == 0) return
      p = [res%p, ext%theta0(n_fitted(prob) + 1:)]
      m = size(q, 1)*res%k_fit
      allocate (r(m), jac(m, np))
      ! the fitted columns as the fit has them; the candidates' by differences of the
      ! residuals (two plain runs each: their sensitivities through the factory at
      ! every step cost 15 times the fit, 25 s against 1.6 s in the debug build)
      call evaluate_fit(prob, res%p, t, q, res%k_fit, r, error, jac(:, :nfit))
      if (allocated(error)) return
      do j = nfit + 1, np
         call candidate_column(j)
         if (allocated(error)) return
      end do
      ! Q: the fitted columns orthonormalized (modified Gram–Schmidt, twice)
      allocate (qm(m, nfit))
      o = 0
      do j = 1, nfit
         c = jac(:, j)
         nq = sqrt(sum(c**2))
         do i = 1, o
            c = c - qm(:, i)*sum(qm(:, i)*c)
         end do
         do i = 1, o
            c = c - qm(:, i)*sum(qm(:, i)*c)
         end do
         if (.not. (sqrt(sum(c**2)) > 1e-10_dp*nq)) cycle
         o = o + 1
         qm(:, o) = c/sqrt(sum(c**2))
      end do
      cost = sum(r**2)
      allocate (pred(ncand), effect(ncand))
      ! a candidate's effect: the residuals' change for a change of it by its size
      do j = 1, ncand
         effect(j) = sqrt(sum(jac(:, nfit + j)**2))*max(abs(p(nfit + j)), &
                                                         ext%comp_scale(n_fitted(prob) + j))
      end do
      do j = 1, ncand
         c = jac(:, nfit + j)
         nq = sqrt(sum(c**2))
         if (.not. (effect(j) > 1e-6_dp*maxval(effect))) nq = 0.0_dp   ! none (rounding)
         do i = 1, o
            c = c - qm(:, i)*sum(qm(:, i)*c)
         end do
         cc = sum(c**2)
         if (.not. (sqrt(cc) > 1e-8_dp*max(nq, tiny(1.0_dp))) .or. nq == 0.0_dp) then
            pred(j) = huge(1.0_dp)   ! the data do not see it
         else
            pred(j) = sqrt(max(cost - sum(c*r)**2/cc, 0.0_dp)/real(m, dp))
         end if
      end do
      do i = 1, ncand
         j = minloc(pred, dim=1)
         if (pred(j) == huge(1.0_dp)) exit
         suspects = [suspects, suspect_t(ext%comp_labels(n_fitted(prob) + j), pred(j))]
         pred(j) = huge(1.0_dp)
      end do
   contains
      !> Column j of jac: central differences of the residuals in p(j) (forward at
      !> the lower end of its range), step 6e-6 of its size.
      subroutine candidate_column(j)
         integer, intent(in) :: j
         real(dp), allocatable :: pp(:), rp(:), rm(:)
         real(dp) :: h
         integer :: c
         c = n_fitted(prob) + j - nfit
         h = 6e-6_dp*max(abs(p(j)), ext%comp_scale(c))
         allocate (rp(m), rm(m))
         pp = p
         pp(j) = p(j) + h
         call evaluate_fit(ext, pp, t, q, res%k_fit, rp, error)
         if (allocated(error)) return
         if (p(j) - h >= ext%theta_lower(c)) then
            pp(j) = p(j) - h
            call evaluate_fit(ext, pp, t, q, res%k_fit, rm, error)
            if (allocated(error)) return
            jac(:, j) = (rp - rm)/(2.0_dp*h)
         else
            jac(:, j) = (rp - r)/h
         end if
      end subroutine candidate_column

      !> A support parameter that cannot move the pendulum: the frequency and phases
      !> with every amplitude zero, the amplitudes with the frequency zero (their
      !> columns would be rounding noise of the differences).
      logical function no_effect(name)
         character(len=*), intent(in) :: name
         real(dp), allocatable :: a(:), w(:)
         no_effect = .false.
         if (index(name, 'support_') /= 1) return   ! (a model that has the support)
         a = spec_values(prob%spec, 'support_amplitude', 2)
         w = spec_values(prob%spec, 'support_frequency', 1)
         if (name == 'support_amplitude') then
            no_effect = w(1) == 0.0_dp .and. .not. fitted('support_frequency', 1)
         else
            no_effect = all(a == 0.0_dp) .and. .not. fitted('support_amplitude', 1) .and. &
                        .not. fitted('support_amplitude', 2)
         end if
      end function no_effect

      !> Component i of parameter `name` is fitted already.
      logical function fitted(name, i)
         character(len=*), intent(in) :: name
         integer, intent(in) :: i
         fitted = .false.
         if (n_fitted(prob) == 0) return
         fitted = any(prob%comp_names == name .and. prob%comp_index == i)
      end function fitted
   end subroutine misfit_suspects

   !> The whole series with the fitted model: the model's values and the residuals at
   !> every sample, and the prediction horizon after the fit window.
   subroutine predict_series(prob, t, q, tolerance, res, counter, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:)                      !! sample times (K) [s]
      real(dp), intent(in) :: q(:, :)                   !! observations (N or 2N, K)
      real(dp), intent(in) :: tolerance                 !! horizon tolerance [rad or m]
      type(fit_result_t), intent(inout) :: res          !! estimates; series, horizon set
      type(fit_counter_t), intent(inout) :: counter     !! work done, its limit
      type(error_t), allocatable, intent(out) :: error  !! the integration failed
      real(dp), allocatable :: r(:)
      integer :: j, kmax, kk, no
      no = size(q, 1)
      kmax = size(t)
      kk = res%k_fit
      allocate (r(no*kmax))
      call counted_fit(prob, res%p, t, q, kmax, r, counter, error)
      if (allocated(error)) return
      res%resid = -reshape(r, [no, kmax])
      res%q_model = q - res%resid
      res%has_after = kmax > kk
      res%horizon = 0.0_dp
      res%horizon_censored = .false.
      if (res%has_after) then
         res%horizon_censored = .true.
         res%horizon = t(kmax) - t(kk)
         do j = kk + 1, kmax
            if (maxval(abs(res%resid(:, j))) > tolerance) then
               res%horizon = t(j) - t(kk)
               res%horizon_censored = .false.
               exit
            end if
         end do
      end if
   end subroutine predict_series

   !> The first stage from `prob%starts` starting points (see `fit_problem_t`): p is
   !> replaced by the estimate of lowest cost.
   subroutine best_start(prob, t, q, k, p, iterations, counter, error)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: t(:), q(:, :)
      integer, intent(in) :: k
      real(dp), intent(inout) :: p(:)
      integer, intent(out) :: iterations
      type(fit_counter_t), intent(inout) :: counter
      type(error_t), allocatable, intent(out) :: error
      real(dp), allocatable :: ps(:), best(:), r(:)
      type(error_t), allocatable :: err
      type(fit_problem_t) :: quick
      real(dp) :: spread, cost, best_cost
      integer :: s, i, n, it
      logical :: conv
      integer, parameter :: primes(max_dof) = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, &
         41, 43, 47, 53, 59, 61, 67, 71, 73, 79, 83, 89, 97, 101, 103, 107, 109, 113, 127, 131]
      n = (size(p) - n_fitted(prob))/2
      allocate (r(size(q, 1)*k))
      ! the starts only have to find the basin: looser tolerances, fewer iterations
      quick = prob
      quick%rtol = max(prob%rtol, 1e-8_dp)
      quick%atol = max(prob%atol, 1e-10_dp)
      quick%max_iter = min(prob%max_iter, 30)
      spread = max(maxval(abs(p(n + 1:2*n))), 1.0_dp)
      best = p
      best_cost = huge(1.0_dp)
      iterations = 0
      do s = 1, prob%starts
         ps = p
         do i = 1, n
            ps(n + i) = p(n + i) + spread*(2.0_dp*halton(s - 1, primes(i)) - 1.0_dp)
         end do
         if (s == 1) ps = p
         call levenberg_marquardt(quick, t, q, k, ps, it, conv, counter, err, &
                                  hold_damping=.true.)
         iterations = iterations + it
         if (allocated(err)) then
            if (counter%exceeded) then
               call move_alloc(err, error)
               return
            end if
            deallocate (err)
            cycle
         end if
         call counted_fit(quick, ps, t, q, k, r, counter, err)
         if (allocated(err)) then
            if (counter%exceeded) then
               call move_alloc(err, error)
               return
            end if
            deallocate (err)
            cycle
         end if
         cost = sum(r**2)
         if (cost < best_cost) then
            best_cost = cost
            best = ps
         end if
      end do
      if (best_cost == huge(1.0_dp)) then
         call fatal_error(error, 'no starting point of the first stage could be integrated')
         return
      end if
      p = best
   end subroutine best_start

   !> `evaluate_fit` with its steps added to the counter (× (1 + P) with the
   !> Jacobian); an error when the fit's work goes beyond the counter's limit.
   subroutine counted_fit(prob, p, t, q, k, r, counter, error, jac)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:), t(:), q(:, :)
      integer, intent(in) :: k
      real(dp), intent(out) :: r(:)
      type(fit_counter_t), intent(inout) :: counter
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(out), optional :: jac(:, :)
      integer(i8) :: steps
      real(dp) :: factor
      real(dp) :: budget
      factor = 1.0_dp
      if (present(jac)) factor = real(1 + size(p), dp)
      ! the steps left (an integration stops once beyond them)
      budget = max(counter%limit - counter%used, 0.0_dp)/factor
      if (present(jac)) then
         call evaluate_fit(prob, p, t, q, k, r, error, jac, steps=steps, budget=budget)
      else
         call evaluate_fit(prob, p, t, q, k, r, error, steps=steps, budget=budget)
      end if
      counter%used = counter%used + factor*real(steps, dp)
      if (counter%show) call counter%progress%update(1_i8)
      if (counter%used > counter%limit) then
         counter%exceeded = .true.
         if (allocated(error)) deallocate (error)
         call fatal_error(error, 'the fit stopped at its work limit: '// &
                          real_str(counter%used, 3)//' integration steps (sensitivities ' &
                          //'counted x(1 + P)) done, at most '//real_str(counter%limit)// &
                          ' (the motion needed more steps than its first guess; shorten ' &
                          //'the fit window)')
      end if
   end subroutine counted_fit

   !> Element i of the van der Corput sequence in base b (Halton's coordinates).
   pure real(dp) function halton(i, b) result(x)
      integer, intent(in) :: i, b
      integer :: j
      real(dp) :: f
      x = 0.0_dp
      f = 1.0_dp
      j = i
      do while (j > 0)
         f = f/real(b, dp)
         x = x + f*real(mod(j, b), dp)
         j = j/b
      end do
   end function halton

   !> Levenberg–Marquardt on the first k samples, from p (updated).
   !> With `hold_damping` the damping stays at its value (its rows and columns of the
   !> normal equations are replaced by the identity's, its step is zero).
   subroutine levenberg_marquardt(prob, t, q, k, p, iterations, converged, counter, error, &
                                  hold_damping)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: t(:), q(:, :)
      integer, intent(in) :: k
      real(dp), intent(inout) :: p(:)
      integer, intent(out) :: iterations
      logical, intent(out) :: converged
      type(fit_counter_t), intent(inout) :: counter
      type(error_t), allocatable, intent(out) :: error
      logical, intent(in), optional :: hold_damping
      real(dp), allocatable :: r(:), jac(:, :), rn(:), jn(:, :), a(:, :), g(:), d(:)
      real(dp), allocatable :: pn(:), b(:, :)
      type(error_t), allocatable :: trial_error
      real(dp) :: cost, cost_n, lambda
      integer :: m, np, it, tries, info, i, n
      n = (size(p) - n_fitted(prob))/2
      m = size(q, 1)*k
      np = size(p)
      allocate (r(m), jac(m, np), rn(m), jn(m, np), g(np), d(np), pn(np), b(np, 1))
      converged = .false.
      iterations = 0
      call counted_fit(prob, p, t, q, k, r, counter, error, jac)
      if (allocated(error)) return
      cost = 0.5_dp*sum(r**2)
      lambda = 1e-3_dp
      converged = .false.
      iterations = 0
      do it = 1, prob%max_iter
         iterations = it
         a = matmul(transpose(jac), jac)
         g = matmul(transpose(jac), r)
         if (present(hold_damping) .and. n_fitted(prob) > 0) then
            if (hold_damping) then
               a(2*n + 1:, :) = 0.0_dp
               a(:, 2*n + 1:) = 0.0_dp
               do i = 2*n + 1, np
                  a(i, i) = 1.0_dp
               end do
               g(2*n + 1:) = 0.0_dp
            end if
         end if
         do i = 1, np
            d(i) = a(i, i)
         end do
         d = max(d, 1e-12_dp*maxval(d), tiny(1.0_dp))
         if (cost == 0.0_dp) then
            converged = .true.
            return
         end if
         do tries = 1, 30
            b(:, 1) = -g
            block
               real(dp) :: am(np, np)
               am = a
               do i = 1, np
                  am(i, i) = am(i, i) + lambda*d(i)
               end do
               call dpotrf('L', np, am, np, info)
               if (info == 0) call dpotrs('L', np, 1, am, np, b, np, info)
            end block
            if (info /= 0) then
               lambda = lambda*10.0_dp
               cycle
            end if
            pn = p + b(:, 1)
            if (n_fitted(prob) > 0) pn(2*n + 1:) = min(max(pn(2*n + 1:), &
                                                           prob%theta_lower), prob%theta_upper)
            call counted_fit(prob, pn, t, q, k, rn, counter, trial_error, jn)
            if (allocated(trial_error)) then
               if (counter%exceeded) then
                  call move_alloc(trial_error, error)
                  return
               end if
               deallocate (trial_error)
               lambda = lambda*10.0_dp
               cycle
            end if
            cost_n = 0.5_dp*sum(rn**2)
            if (cost_n < cost) exit
            lambda = lambda*10.0_dp
         end do
         if (tries > 30) then   ! no step lowers the cost: at the minimum's noise floor
            converged = .true.
            return
         end if
         converged = all(abs(pn - p) <= 1e-12_dp*(abs(p) + 1e-3_dp)) .or. &
                     cost - cost_n <= 1e-14_dp*cost
         p = pn
         r = rn
         jac = jn
         cost = cost_n
         lambda = max(lambda/10.0_dp, 1e-15_dp)
         if (converged) return
      end do
   end subroutine levenberg_marquardt

   !> Student's t quantile t_(0.975, ν): table values for ν ≤ 8, beyond the
   !> Cornish–Fisher expansion about the normal quantile (relative error below 1e-5).
   pure real(dp) function student_t95(nu) result(tq)
      integer, intent(in) :: nu   !! degrees of freedom
      real(dp), parameter :: z = 1.959963984540054_dp
      real(dp), parameter :: small(8) = [12.70620473617471_dp, 4.302652729911275_dp, &
                                         3.182446305284263_dp, 2.776445105197799_dp, &
                                         2.570581835636314_dp, 2.446911851144969_dp, &
                                         2.364624251592785_dp, 2.306004135204166_dp]
      real(dp) :: v
      if (nu <= 0) then
         tq = huge(1.0_dp)
      else if (nu <= 8) then
         tq = small(nu)
      else
         v = real(nu, dp)
         tq = z + (z**3 + z)/(4.0_dp*v) + (5.0_dp*z**5 + 16.0_dp*z**3 + 3.0_dp*z)/ &
              (96.0_dp*v**2) + (3.0_dp*z**7 + 19.0_dp*z**5 + 17.0_dp*z**3 - 15.0_dp*z)/ &
              (384.0_dp*v**3) + (79.0_dp*z**9 + 776.0_dp*z**7 + 1482.0_dp*z**5 - &
              1920.0_dp*z**3 - 945.0_dp*z)/(92160.0_dp*v**4)
      end if
   end function student_t95

   !> Components of the fitted model parameters (0: only the state is fitted).
   pure integer function n_fitted(prob)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      n_fitted = 0
      if (allocated(prob%theta0)) n_fitted = size(prob%theta0)
   end function n_fitted

   !> Fit the model parameters `names` of `prob%spec` too: each is a
   !> parameter of the model's description (all its components: 'damping', 'm') or one
   !> component of a parameter of several, the name followed by its number ('m2', 'l1',
   !> 'support_amplitude1'); not a count ('links'). Their sensitivities: the model's
   !> `parameter_rates` where `check_parameter_rates` accepts the name, central
   !> differences of the field otherwise. The first guess is the value of the
   !> specification (or the default), the range the description's.
   subroutine set_fitted(prob, names, error, scale_check)
      type(fit_problem_t), intent(inout) :: prob        !! the problem (spec set)
      character(len=*), intent(in) :: names(:)          !! parameter names
      type(error_t), allocatable, intent(out) :: error  !! refused
      !> refuse a set that leaves the mass scale free (`mass_scale`; default: yes)
      logical, intent(in), optional :: scale_check
      type(model_info_t), allocatable :: models(:)
      class(model_t), allocatable :: model
      type(model_spec_t) :: spec
      type(error_t), allocatable :: no_rates
      real(dp), allocatable :: v(:)
      integer :: i, j, k, cnt, first, last, c
      character(len=:), allocatable :: base
      spec = prob%spec
      spec%general = .true.
      call new_model(spec, model, error)
      if (allocated(error)) return
      models = model_catalogue()
      k = find_model(models, spec%model_name())
      if (allocated(prob%fit_names)) deallocate (prob%fit_names, prob%fit_counts, &
         prob%theta0, prob%theta_lower, prob%theta_upper, prob%comp_names, &
         prob%comp_index, prob%comp_count, prob%comp_labels, prob%comp_scale, &
         prob%comp_generic, prob%comp_units)
      allocate (prob%fit_names(size(names)), prob%fit_counts(size(names)))
      allocate (prob%theta0(0), prob%theta_lower(0), prob%theta_upper(0))
      allocate (prob%comp_names(0), prob%comp_index(0), prob%comp_count(0), &
                prob%comp_labels(0), prob%comp_scale(0), prob%comp_generic(0), &
                prob%comp_units(0))
      do i = 1, size(names)
         call parse_component(models(k), model%n_dof(), trim(names(i)), j, first, last, error)
         if (allocated(error)) return
         associate (par => models(k)%params(j))
            base = par%name
            cnt = par%count
            if (cnt < 0) cnt = model%n_dof()
            call model%check_parameter_rates(base, no_rates)
            v = spec_values(spec, base, cnt)
            if (size(v) /= cnt) then
               call fatal_error(error, 'invalid fit parameter: '//trim(names(i))//' (the ' &
                                //'model has '//to_str(size(v))//' values of '//base// &
                                ' for '//to_str(cnt)//' components)', error_bad_input)
               return
            end if
            do c = first, last
               if (any(prob%comp_names == base .and. prob%comp_index == c)) then
                  call fatal_error(error, 'invalid fit parameters: '//trim(names(i))// &
                                   ' names a component given already (' &
                                   //component_label(base, c, cnt)//')', error_bad_input)
                  return
               end if
               prob%theta0 = [prob%theta0, v(c)]
               prob%theta_lower = [prob%theta_lower, par%lower]
               prob%theta_upper = [prob%theta_upper, par%upper]
               prob%comp_names = [character(len=32) :: prob%comp_names, base]
               prob%comp_index = [prob%comp_index, c]
               prob%comp_count = [prob%comp_count, cnt]
               prob%comp_labels = [character(len=24) :: prob%comp_labels, &
                                   component_label(base, c, cnt)]
               prob%comp_scale = [prob%comp_scale, max(abs(par%default), 1e-2_dp)]
               prob%comp_units = [character(len=16) :: prob%comp_units, par%units]
               prob%comp_generic = [prob%comp_generic, allocated(no_rates)]
            end do
         end associate
         prob%fit_names(i) = names(i)
         prob%fit_counts(i) = last - first + 1
      end do
      if (.not. present(scale_check)) then
         call mass_scale(prob, models(k), model%n_dof(), error)
      else if (scale_check) then
         call mass_scale(prob, models(k), model%n_dof(), error)
      end if
      if (allocated(error)) return
      if (model%n_dof() + size(prob%theta0) > max_dof) then
         call fatal_error(error, 'invalid fit parameters: '//to_str(model%n_dof())// &
                          ' coordinates and '//to_str(size(prob%theta0))//' fitted ' &
                          //'components are more than the '//to_str(max_dof)//' the ' &
                          //'sensitivity system holds', error_bad_input)
      end if
   end subroutine set_fitted

   !> Refuse, before any work, a fit of every parameter that carries mass: the
   !> equations of motion are homogeneous of degree 1 in the masses, the inertias, the
   !> damping and the stiffnesses (every parameter whose units hold kg or N), so
   !> multiplying them all by one factor leaves the motion, hence the observed
   !> coordinates, unchanged. The symmetry holds when every such parameter is either
   !> fitted in all its components or zero (a damping of 0 fixes no scale).
   subroutine mass_scale(prob, info, n_dof, error)
      type(fit_problem_t), intent(in) :: prob           !! components set
      type(model_info_t), intent(in) :: info            !! the model's description
      integer, intent(in) :: n_dof                      !! its degrees of freedom
      type(error_t), allocatable, intent(out) :: error  !! the scale is not determined
      real(dp), allocatable :: v(:)
      character(len=:), allocatable :: names, rest
      integer :: j, i, cnt
      logical :: any_fitted
      any_fitted = .false.
      names = ''
      do j = 1, size(info%params)
         associate (par => info%params(j))
            if (index(par%units, 'kg') == 0 .and. index(par%units, 'N') == 0) cycle
            ! a rod's inertia m l²/12 follows its mass: it scales with the masses
            if (derived_default(prob%spec, par%name) .and. .not. any(prob%comp_names == &
                par%name)) cycle
            cnt = par%count
            if (cnt < 0) cnt = n_dof
            v = spec_values(prob%spec, par%name, cnt)
            do i = 1, min(size(v), cnt)
               if (any(prob%comp_names == par%name .and. prob%comp_index == i)) then
                  any_fitted = .true.
                  if (len(names) > 0) names = names//','
                  names = names//component_label(par%name, i, cnt)
               else if (v(i) /= 0.0_dp) then
                  return   ! a fixed nonzero mass, inertia or stiffness sets the scale
               end if
            end do
         end associate
      end do
      if (.not. any_fitted) return
      rest = names(index(names, ',') + 1:)
      call fatal_error(error, 'invalid fit parameters: '//names//' together are not ' &
                       //'determined by the data: the absolute mass scale (multiplying them ' &
                       //'all by one factor leaves the motion unchanged: only their ratios ' &
                       //'are determined; fit all but one, e.g. '//rest//')', error_bad_input)
   end subroutine mass_scale

   !> The label of component c of parameter `name` with `cnt` components: 'c2' for the
   !> damping, 'm2' for a parameter of several, the name for a scalar.
   pure function component_label(name, c, cnt) result(label)
      character(len=*), intent(in) :: name  !! parameter name
      integer, intent(in) :: c, cnt         !! the component, the parameter's components
      character(len=:), allocatable :: label
      if (name == 'damping') then
         label = 'c'//to_str(c)
      else if (cnt > 1) then
         label = name//to_str(c)
      else
         label = name
      end if
   end function component_label

   !> The parameter j of the description `info` named by `name` and its components
   !> first..last: the parameter's name (all), or the name and a component number
   !> ('m2'; 'c2' for the damping), or a refusal naming the model's parameters.
   subroutine parse_component(info, n_dof, name, j, first, last, error)
      type(model_info_t), intent(in) :: info            !! the model's description
      integer, intent(in) :: n_dof                      !! its degrees of freedom
      character(len=*), intent(in) :: name              !! as given
      integer, intent(out) :: j, first, last            !! parameter, components
      type(error_t), allocatable, intent(out) :: error  !! not a parameter
      integer :: digits, cnt, idx, stat
      character(len=:), allocatable :: base, known
      j = param_index(info, name)
      first = 1
      last = 0
      if (j == 0) then
         digits = len(name) + 1
         do while (digits > 1)
            if (verify(name(digits - 1:digits - 1), '0123456789') /= 0) exit
            digits = digits - 1
         end do
         if (digits > 1 .and. digits <= len(name)) then
            base = name(:digits - 1)
            if (base == 'c') base = 'damping'
            j = param_index(info, base)
            idx = 0
            read (name(digits:), *, iostat=stat) idx
            if (stat /= 0) idx = 0
            if (j > 0) then
               cnt = info%params(j)%count
               if (cnt < 0) cnt = n_dof
               if (cnt == 1) then
                  j = 0
               else if (idx < 1 .or. idx > cnt) then
                  call fatal_error(error, 'invalid fit parameter: '//name//' (component ' &
                                   //to_str(idx)//' of '//info%params(j)%name// &
                                   ' is outside [1, '//to_str(cnt)//'])', error_bad_input)
                  return
               end if
               first = idx
               last = idx
            end if
         end if
      end if
      if (j > 0) then
         if (info%params(j)%integer_valued) j = 0
      end if
      if (j == 0) then
         known = ''
         do idx = 1, size(info%params)
            if (info%params(idx)%integer_valued) cycle
            if (len(known) > 0) known = known//', '
            known = known//info%params(idx)%name
         end do
         call fatal_error(error, 'invalid fit parameter: '//name//' (model '//info%name// &
                          ' fits '//known//'; a component as m2, l1, c1)', error_bad_input)
         return
      end if
      if (last == 0) then
         cnt = info%params(j)%count
         if (cnt < 0) cnt = n_dof
         last = cnt
      end if
   end subroutine parse_component
end module dpend_estimate
