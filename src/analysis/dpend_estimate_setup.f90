!> Setting up a fit of `dpend fit`: the model parameters fitted besides the initial
!> state (`set_fitted`: a parameter or one of its components by name, 'damping', 'm2',
!> with its first guess, range and the source of its sensitivities; a set that leaves
!> the mass scale free is refused), and the most work the fit can do, known before it
!> starts (`estimate_fit_work`).
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
module dpend_estimate_setup
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, error_bad_input
   use dpend_model, only: model_t, max_dof
   use dpend_model_factory, only: model_spec_t, new_model, model_catalogue, find_model, &
                                  spec_values, derived_default, model_info_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_propagate, only: march_t
   use dpend_strings, only: to_str
   use dpend_estimate_sensitivity, only: sens_model_t
   use dpend_estimate_problem, only: fit_problem_t, n_fitted, start_model, initial_guess, &
      problem_links
   implicit none
   private
   public :: set_fitted, component_label, fit_work_t, estimate_fit_work

   !> Most steps of the probe integration that measures the steps per second of model
   !> time (`estimate_fit_work`): a few milliseconds.
   integer, parameter :: probe_steps = 4096
   !> Integrations of one Levenberg–Marquardt call beyond 2 per iteration (the first
   !> evaluation and the 30 rejected trials that end a call).
   integer, parameter :: lm_extra_evaluations = 31

   !> What a fit costs at most (`estimate_fit_work`), known before it starts.
   type :: fit_work_t
      real(dp) :: rate = 0.0_dp         !! integration steps per second of model time [1/s]
      real(dp) :: steps = 0.0_dp        !! steps of one integration over the fit window
      real(dp) :: evaluations = 0.0_dp  !! integrations of the model, at most
      integer :: stages = 0             !! continuation stages, at most
      real(dp) :: work = 0.0_dp         !! step-equivalents in all (steps × (1 + P))
      real(dp) :: bytes = 0.0_dp        !! memory of residuals and Jacobians [B]
   end type fit_work_t

contains

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
         ! the model as the fit builds it, with the parameter set at its start: a
         ! model that refuses it so (a gear ratio without a rotor) is refused now
         call spec%set(base, spec_values(spec, base, cnt))
      end do
      call new_model(spec, model, no_rates)
      if (allocated(no_rates)) then   ! (its own error variable: fatal_error resets error)
         call fatal_error(error, 'invalid fit parameters: '//no_rates%message, error_bad_input)
         return
      end if
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
   !> fitted in all its components or zero (a damping of 0 fixes no scale); a rotor
   !> inertia whose gear ratio is fitted scales through it (g_r² I_r), and applied
   !> joint torques (their size given) fix the scale.
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
      if (prob%spec%torque%active()) return
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
               else if (par%name == 'rotor_inertia' .and. any(prob%comp_names == &
                        'gear_ratio' .and. prob%comp_index == i)) then
                  cycle   ! its gear ratio, fitted, carries the scale (listed there)
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

   !> Index of parameter `name` in the description `info` (0: none).
   pure integer function param_index(info, name) result(j)
      type(model_info_t), intent(in) :: info  !! a model's description
      character(len=*), intent(in) :: name    !! parameter name
      do j = 1, size(info%params)
         if (info%params(j)%name == trim(name)) return
      end do
      j = 0
   end function param_index

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
      n = problem_links(prob, no)
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
end module dpend_estimate_setup
