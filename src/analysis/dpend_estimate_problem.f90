!> The problem and the result of `dpend fit` (`fit_problem_t`, `fit_result_t`), the
!> residuals of a parameter vector and their Jacobian (`evaluate_fit`), counted against
!> the fit's work limit (`counted_fit`), and the first guess (`initial_guess`).
!>
!> Parameters p = (q(t₁), q̇(t₁)[, c]) (2N or 3N): the state at the first sample time t₁
!> and the damping coefficients c_i [N m s]. Residuals: r = q_model(t_k) − q_data(t_k)
!> for every angle of every sample k of the fit window, each wrapped into [−π, π) (so
!> that data given modulo 2π fit as well); or, with `positions`, the positions of the
!> link ends P_i = A(t) + Σ_(j≤i) L_j (cos q_j, sin q_j) minus the measured ones [m]
!> (A the pin, moving with the support), their sensitivities ∂P/∂q · ∂q/∂p.
!>
!> The Jacobian: the tangents of the augmented model of `dpend_estimate_sensitivity`
!> (see its notes), propagated along the integration to every sample time.
module dpend_estimate_problem
   use dpend_kinds, only: dp, pi, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, new_model, spec_values
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: march_t
   use dpend_tangent, only: tangent_t
   use dpend_limits, only: max_fit_work, default_max_steps
   use dpend_strings, only: real_str
   use dpend_progress, only: progress_t
   use dpend_estimate_sensitivity, only: sens_model_t
   implicit none
   private
   public :: fit_problem_t, fit_result_t, fit_counter_t, n_fitted, evaluate_fit, counted_fit
   public :: start_model, initial_guess, wrap_angles, problem_links, unobserved_points

   !> Most substeps of the sensitivities over one step of the motion: a step whose
   !> local frequency needs more is far too long for the tangents (trial parameters
   !> that made the motion stiff), and its evaluation fails.
   integer, parameter :: fit_max_substeps = 4096

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
      !> with positions: the points observed, in order (link ends; the last is the
      !> tip N); unallocated: every point 1..N. A point missing between two observed
      !> ones (or the pin) is placed by the two lengths, on the side `branch` says
      !> (+1: counter-clockwise of the chord from the point before to the point after,
      !> -1: clockwise; the two mirror solutions, both tried by `fit_series`)
      integer, allocatable :: points(:)
      integer, allocatable :: branch(:)
      !> first-stage starts: the guess and starts-1 others whose rates spread over
      !> guess ± max(|guess rates|, 1 rad/s) (a Halton sequence); the lowest cost wins
      integer :: starts = 1
      !> most accepted steps of one adaptive integration between two samples
      integer(i8) :: max_steps = default_max_steps
      !> the links are point masses at their ends (`--body point`): a fitted
      !> length l_i moves the centre of mass com_i = l_i with it
      logical :: com_at_tip = .false.
      !> most step-equivalents (a step, and P per substep of the sensitivities) of the
      !> whole fit; `fit_series` stops with an error beyond (or beyond 4 times the
      !> bound of `estimate_fit_work`)
      real(dp) :: work_limit = max_fit_work
      !> the noise of the observations [rad or m] (`--sigma`); 0: estimated from the
      !> data (`observation_noise`)
      real(dp) :: noise = 0.0_dp
      !> stop the continuation when the residuals stall far above the noise (two
      !> stages in a row, the second no better, above `stall_factor` times it): the
      !> result says where (`stalled`), for the caller to weigh the alternatives
      logical :: stall_check = .false.
      !> the swing period of the configured pendulum [s] (2π √(Σ l_i / g)): a stall is
      !> judged on windows of at least half of it (a shorter one barely determines
      !> the fitted parameters, whatever the body)
      real(dp) :: swing = 0.0_dp
   end type fit_problem_t

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
      !> points not observed: which mirror place was kept, and the others' RMS ('': none)
      character(len=:), allocatable :: mirror
      !> the continuation stopped stalling (prob%stall_check): over the first
      !> `stall_k` samples the RMS residual `stall_rms` stays above stall_factor times
      !> the noise `noise`; the longest window the model described (RMS within
      !> misfit_factor noise) ended at sample `good_k` (0: none)
      logical :: stalled = .false.
      integer :: stall_k = 0, good_k = 0
      !> the work the fit did, in step-equivalents (each step, and P per substep of the
      !> sensitivities): its cost, the same on every machine
      real(dp) :: work = 0.0_dp
      real(dp) :: stall_rms = 0.0_dp, noise = 0.0_dp
      !> singular values of the sensitivity matrix with unit columns, largest first
      real(dp), allocatable :: singular(:)
      real(dp) :: condition = 0.0_dp        !! their ratio largest / smallest
      !> right singular vectors (P, P), columns in the order of `singular` (scaled
      !> parameters: each parameter in units of its column's norm)
      real(dp), allocatable :: directions(:, :)
   end type fit_result_t

contains

   !> Components of the fitted model parameters (0: only the state is fitted).
   pure integer function n_fitted(prob)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      n_fitted = 0
      if (allocated(prob%theta0)) n_fitted = size(prob%theta0)
   end function n_fitted

   !> Residuals r (N k) of the first k samples for the parameters p and, if `jac` is
   !> present, their Jacobian ∂r/∂p (N k, P). Residual (i, j) is r(i + N (j − 1)).
   !> With `counter`, the work is added to it as it is done, in step-equivalents: one
   !> per integration step, and with `jac` P more per substep of the tangents (one
   !> substep per step where the step is short for the local frequency, many where
   !> the trial parameters make the motion stiff); the progress is reported during the
   !> integration, and beyond the counter's limit the integration stops with an error.
   subroutine evaluate_fit(prob, p, t, q, k, r, error, jac, counter)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: p(:)                      !! parameters
      real(dp), intent(in) :: t(:)                      !! sample times [s]
      real(dp), intent(in) :: q(:, :)                   !! measured angles (N, K) [rad]
                                                        !! or positions (2N, K) [m]
      integer, intent(in) :: k                          !! samples used
      real(dp), intent(out) :: r(:)                     !! residuals (N k) [rad]
      type(error_t), allocatable, intent(out) :: error  !! the integration failed
      real(dp), intent(out), optional :: jac(:, :)      !! ∂r/∂p (N k, P)
      type(fit_counter_t), intent(inout), optional :: counter  !! work done, its limit
      type(sens_model_t) :: sm
      class(integrator_t), allocatable :: integ
      integer(i8) :: nstep
      real(dp) :: counted
      type(tangent_t) :: tan
      type(march_t) :: march
      real(dp), allocatable :: y(:), v0(:, :), o(:), d(:, :), lv(:), dl(:, :)
      integer, allocatable :: lc(:)
      real(dp) :: tt, h
      integer :: n, nc, np, ns, j, stat, no
      no = size(q, 1)
      n = problem_links(prob, no)
      np = size(p)
      nstep = 0
      counted = 0.0_dp
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
         ! a trial needing more substeps is rejected (too stiff): the fit's progress
         ! then advances every few seconds even in the debug build
         tan%max_substeps = fit_max_substeps
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
            nstep = nstep + 1
            if (stat /= stat_ok) then
               call fatal_error(error, 'the model''s integration failed: '// &
                                status_message(stat)//' after t = '//real_str(tt)//' s')
               if (present(counter)) call count_work()
               return
            end if
            if (present(jac)) then
               call tan%propagate(integ, sm)
               if (tan%too_stiff) then
                  call fatal_error(error, 'the sensitivities could not be propagated ' &
                                   //'(a step too long for the local frequency) after t = ' &
                                   //real_str(tt)//' s')
                  if (present(counter)) call count_work()
                  return
               end if
               if (tan%too_large) then
                  call fatal_error(error, 'the sensitivities grew beyond 1e100 by t = ' &
                                   //real_str(tt)//' s: the trajectory is chaotic over ' &
                                   //'the fit window (fit a shorter --fit-window or series)')
                  if (present(counter)) call count_work()
                  return
               end if
            end if
            if (present(counter)) then   ! counted every 1024 step-equivalents
               if (work_done() - counted >= 1024.0_dp) call count_work()
               if (counter%exceeded) return
            end if
         end do
         call observe(prob, tt, y(1:n), o, d, lv, dl)
         r(no*(j - 1) + 1:no*j) = residual(prob, o, q(:, j))
         if (present(jac)) then
            jac(no*(j - 1) + 1:no*j, :) = matmul(d, tan%v(1:n, :))
            call add_length_columns(j)
         end if
      end do
      if (present(counter)) call count_work()
   contains
      !> The step-equivalents done since the last count added to the counter; beyond
      !> its limit, an error.
      subroutine count_work()
         real(dp) :: work
         work = work_done()
         counter%used = counter%used + (work - counted)
         if (counter%show) call counter%progress%update(int(work - counted, i8))
         counted = work
         if (counter%used > counter%limit) then
            counter%exceeded = .true.
            if (allocated(error)) deallocate (error)
            call fatal_error(error, 'the fit stopped at its work limit: '// &
                             real_str(counter%used, 3)//' step-equivalents (each step, ' &
                             //'and P per substep of the sensitivities) done, at most '// &
                             real_str(counter%limit, 3)//' (the trial motions needed far ' &
                             //'more steps than the first guess''s; check the guesses and ' &
                             //'--body, or shorten the fit window)')
         end if
      end subroutine count_work
      !> The step-equivalents of this evaluation so far.
      real(dp) function work_done()
         work_done = real(nstep, dp)
         if (present(jac)) work_done = work_done + real(np, dp)*real(tan%n_sub, dp)
      end function work_done
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

   !> `evaluate_fit` with its step-equivalents added to the counter; an error when the
   !> fit's work goes beyond the counter's limit (`counter%exceeded`).
   subroutine counted_fit(prob, p, t, q, k, r, counter, error, jac)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: p(:), t(:), q(:, :)
      integer, intent(in) :: k
      real(dp), intent(out) :: r(:)
      type(fit_counter_t), intent(inout) :: counter
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(out), optional :: jac(:, :)
      if (present(jac)) then
         call evaluate_fit(prob, p, t, q, k, r, error, jac, counter)
      else
         call evaluate_fit(prob, p, t, q, k, r, error, counter=counter)
      end if
   end subroutine counted_fit

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
      integer :: i, j, n, k, pt
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
      ! the observed points only (all, or those of prob%points, in order)
      k = 0
      pos = prob%sup_a*cos(prob%sup_w*t + prob%sup_phi)
      do i = 1, n
         pos = pos + lv(i)*[cos(q(i)), sin(q(i))]
         pt = i
         if (allocated(prob%points)) then
            if (.not. any(prob%points == i)) cycle
         end if
         k = k + 1
         o(2*k - 1:2*k) = pos
         do j = 1, pt
            d(2*k - 1, j) = -lv(j)*sin(q(j))
            d(2*k, j) = lv(j)*cos(q(j))
            dl(2*k - 1:2*k, j) = [cos(q(j)), sin(q(j))]
         end do
      end do
   end subroutine observe

   !> The links N of a problem whose observations have `no` rows: the angles N, all
   !> points (2N), or the last observed point (the tip) of `points`.
   pure integer function problem_links(prob, no) result(n)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      integer, intent(in) :: no                !! observations per sample
      if (.not. prob%positions) then
         n = no
      else if (allocated(prob%points)) then
         n = prob%points(size(prob%points))
      else
         n = no/2
      end if
   end function problem_links

   !> The points 1..n not observed (none without `prob%points`).
   pure function unobserved_points(prob, n) result(u)
      type(fit_problem_t), intent(in) :: prob  !! the problem
      integer, intent(in) :: n                 !! links
      integer, allocatable :: u(:)
      integer :: i
      allocate (u(0))
      if (.not. allocated(prob%points)) return
      do i = 1, n
         if (.not. any(prob%points == i)) u = [u, i]
      end do
   end function unobserved_points

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

   !> The angles of the link ends' positions xy (the observed points, K) at times t.
   !> A point not observed lies between two known ones (the pin or observed points):
   !> it is placed at the lengths l_i, l_(i+1) from them, on the side prob%branch(i)
   !> says (the chord too long or too short for the two lengths: on the chord).
   pure function angles_of(prob, t, xy) result(q)
      type(fit_problem_t), intent(in) :: prob
      real(dp), intent(in) :: t(:), xy(:, :)
      real(dp), allocatable :: q(:, :)
      real(dp), allocatable :: pts(:, :)
      logical, allocatable :: known(:)
      real(dp) :: u(2), d, a, h, side
      integer :: i, j, k, n
      n = problem_links(prob, size(xy, 1))
      allocate (q(n, size(t)), pts(2, 0:n), known(0:n))
      do j = 1, size(t)
         pts(:, 0) = prob%sup_a*cos(prob%sup_w*t(j) + prob%sup_phi)
         known = .false.
         known(0) = .true.
         do k = 1, size(xy, 1)/2
            i = k
            if (allocated(prob%points)) i = prob%points(k)
            pts(:, i) = xy(2*k - 1:2*k, j)
            known(i) = .true.
         end do
         do i = 1, n - 1   ! a missing point between two known ones
            if (known(i) .or. .not. (known(i - 1) .and. known(i + 1))) cycle
            u = pts(:, i + 1) - pts(:, i - 1)
            d = max(norm2(u), tiny(1.0_dp))
            u = u/d
            d = min(max(d, abs(prob%l(i) - prob%l(i + 1))), prob%l(i) + prob%l(i + 1))
            a = (prob%l(i)**2 - prob%l(i + 1)**2 + d**2)/(2*d)
            h = sqrt(max(prob%l(i)**2 - a**2, 0.0_dp))
            side = 1.0_dp
            if (allocated(prob%branch)) side = real(prob%branch(i), dp)
            pts(:, i) = pts(:, i - 1) + a*u + side*h*[-u(2), u(1)]
         end do
         do i = 1, n
            q(i, j) = atan2(pts(2, i) - pts(2, i - 1), pts(1, i) - pts(1, i - 1))
         end do
      end do
   end function angles_of

   !> x wrapped into [−π, π).
   elemental real(dp) function wrap(x)
      real(dp), intent(in) :: x
      wrap = modulo(x + pi, 2.0_dp*pi) - pi
   end function wrap

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
end module dpend_estimate_problem
