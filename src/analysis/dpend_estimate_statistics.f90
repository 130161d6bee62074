!> The statistics of a fit of `dpend fit` at its solution (`window_statistics`): the
!> covariance, standard errors, correlations and 95 % intervals over the fit window, with
!> a refusal of parameters the data do not determine (`check_visible`, and
!> `identifiability`: the singular values of the scaled sensitivities); the noise of the
!> observations (`observation_noise`, `noise_estimate`); the unfitted parameters that may
!> explain a misfit (`misfit_suspects`); and the whole series predicted with its horizon
!> (`predict_series`).
!>
!> Statistics at the solution: σ² = Σ r²/(m − P) with m residuals and P parameters, the
!> covariance σ² (JᵀJ)⁻¹, standard errors its diagonal's square roots, the correlation
!> matrix, and 95 % intervals p ± t_(0.975, m−P) SE (Student's t). The prediction
!> horizon: with the model of the fit window t ≤ T integrated over the whole series,
!> the time after T until the first sample where some angle differs from the data by
!> more than the tolerance.
module dpend_estimate_statistics
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, error_bad_input
   use dpend_model, only: max_dof
   use dpend_model_factory, only: model_catalogue, find_model, spec_values, derived_default, &
                                  model_info_t
   use dpend_lapack, only: dpotrf, dpotrs
   use dpend_least_squares, only: jacobi_svd
   use dpend_strings, only: real_str, to_str
   use dpend_estimate_problem, only: fit_problem_t, fit_result_t, fit_counter_t, n_fitted, &
                                     evaluate_fit, counted_fit, wrap_angles
   use dpend_estimate_setup, only: set_fitted, component_label
   implicit none
   private
   public :: window_statistics, predict_series, student_t95, noise_estimate, observation_noise
   public :: misfit_suspects, misfit_factor, suspect_t, condition_text

   !> Largest condition number of the sensitivity matrix with unit columns that a fit
   !> accepts: beyond, some combination of the parameters is not determined (its
   !> standard error would exceed 1e8 times the others').
   real(dp), parameter :: max_condition = 1e8_dp

   !> An unfitted parameter component that may be wrong (`misfit_suspects`).
   type :: suspect_t
      character(len=24) :: label = ''   !! e.g. 'l2'
      real(dp) :: rms = 0.0_dp          !! RMS residual with it fitted too (linearized)
   end type suspect_t

   !> A fit whose RMS residual exceeds this factor times the noise (given or estimated)
   !> does not describe the data (`misfit_suspects`).
   real(dp), parameter :: misfit_factor = 3.0_dp

contains

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
      real(dp), allocatable :: u(:, :)
      integer :: np, j
      np = size(ds)
      u = jac
      do j = 1, np
         u(:, j) = u(:, j)*ds(j)
      end do
      call jacobi_svd(u, res%singular, res%directions)
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
      real(dp), allocatable :: r(:), jac(:, :), p(:), pred(:)
      integer :: k, j, i, m, np, nfit, n, free, ncand, idx
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
      pred = predicted_rms(jac, r, nfit, p(nfit + 1:), ext%comp_scale(n_fitted(prob) + 1:))
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
         if (name == 'gear_ratio') then   ! it only scales a rotor inertia (none: refused)
            a = spec_values(prob%spec, 'rotor_inertia', n)
            no_effect = all(a == 0.0_dp)
            return
         end if
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

   !> The RMS residual each candidate would leave fitted too, to first order (the score
   !> test of `misfit_suspects`): jac holds the nfit fitted columns, then the
   !> candidates'; huge for a candidate the data do not see.
   function predicted_rms(jac, r, nfit, value, scale) result(pred)
      real(dp), intent(in) :: jac(:, :)  !! ∂r/∂p, the fitted columns first (m, P)
      real(dp), intent(in) :: r(:)       !! residuals at the fit (m)
      integer, intent(in) :: nfit        !! fitted parameters
      real(dp), intent(in) :: value(:)   !! the candidates' values
      real(dp), intent(in) :: scale(:)   !! their scales (a candidate's size: the larger)
      real(dp), allocatable :: pred(:)
      real(dp), allocatable :: qm(:, :), c(:), effect(:)
      real(dp) :: cost, cc, nq
      integer :: m, ncand, o, i, j
      m = size(r)
      ncand = size(jac, 2) - nfit
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
         effect(j) = sqrt(sum(jac(:, nfit + j)**2))*max(abs(value(j)), scale(j))
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
   end function predicted_rms

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
end module dpend_estimate_statistics
