!> Estimating the initial state and, on request, the joint damping of a chain from a
!> measured series of angles (`dpend fit`): nonlinear least squares by
!> Levenberg–Marquardt with the sensitivities from the variational equations.
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
!> The fit's modules, each using only those before it: `dpend_estimate_sensitivity`
!> (the augmented model whose tangents are the sensitivities), `dpend_estimate_problem`
!> (the problem and result, the residuals and their Jacobian, the first guess),
!> `dpend_estimate_setup` (the fitted model parameters, the work bound),
!> `dpend_estimate_statistics` (the statistics at the solution, identifiability, the
!> noise, misfit suspects, the prediction of the whole series) and this one (the
!> stages and the iteration), which passes on every public name its callers use.
module dpend_estimate
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: max_dof
   use dpend_lapack, only: dpotrf, dpotrs
   use dpend_strings, only: real_str, to_str
   use dpend_progress, only: progress_listened
   use dpend_estimate_sensitivity, only: sens_model_t
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_estimate_problem, only: fit_problem_t, fit_result_t, fit_counter_t, n_fitted, &
                                     evaluate_fit, counted_fit, initial_guess, problem_links, &
                                     unobserved_points
   use dpend_estimate_setup, only: fit_work_t, estimate_fit_work, set_fitted
   use dpend_estimate_statistics, only: window_statistics, predict_series, student_t95, &
                                        noise_estimate, observation_noise, misfit_suspects, &
                                        misfit_factor, suspect_t, condition_text
   implicit none
   private
   public :: fit_problem_t, fit_result_t, fit_series, evaluate_fit, sens_model_t
   public :: initial_guess, student_t95, fit_work_t, estimate_fit_work, set_fitted, n_fitted
   public :: noise_estimate, observation_noise, misfit_suspects, misfit_factor, suspect_t, condition_text

   !> The fit stops beyond this many times the step-equivalents of `estimate_fit_work`
   !> (its worst case of integrations, each at the first guess's rate of steps): a fit
   !> doing every iteration it may can still afford trial motions `work_margin` times
   !> costlier than the first guess's; one whose trial parameters make the motion stiff
   !> (a link of kilometres, a damping driven to its bound) ends with an error instead
   !> of running hours.
   real(dp), parameter :: work_margin = 4.0_dp
   !> The least limit of step-equivalents (a first guess whose probe integration
   !> failed at once gives a bound of 0; the fit then reports the failure itself).
   real(dp), parameter :: min_work_limit = 1e6_dp

   !> A stage whose RMS residual stays above this many times the noise, after one
   !> that did too and was no worse, stalls (prob%stall_check): the model does not
   !> describe the data (a right model's continuation passes such a stage once, then
   !> falls back to the noise)
   real(dp), parameter, public :: stall_factor = 10.0_dp

contains

   !> Fit the samples with t ≤ t_window (all when t_window ≥ the last time), then
   !> predict the whole series and measure the horizon with `tolerance` [rad]. The
   !> integration steps are counted: beyond `work_margin` times the bound of
   !> `estimate_fit_work` (at most `prob%work_limit`) step-equivalents the fit stops
   !> with an error, so a fit whose trial parameters make the motion far costlier than
   !> its first guess's ends in about the time announced. With `progress`, long fits
   !> report on stderr the step-equivalents done of that limit.
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
      call estimate_fit_work(prob, t, q, t_window, work, error)
      if (allocated(error)) return
      counter%limit = min(prob%work_limit, max(work_margin*work%work, min_work_limit))
      if (present(progress)) counter%show = progress
      if (counter%show) then
         call counter%progress%start('dpend fit (step-equivalents of at most '// &
                                     real_str(counter%limit, 3)//', up to '// &
                                     real_str(work%evaluations)//' integrations)', &
                                     int(min(counter%limit, 1e15_dp), i8), 0_i8, .false., &
                                     what='steps')
         ! a line only once the fit has run for a while (none for a quick fit)
         counter%progress%t_last = counter%progress%t_start
         counter%progress%reported = 0
      end if
      if (.not. present(guess) .and. size(unobserved_points(prob, &
                                          problem_links(prob, size(q, 1)))) > 0) then
         call fit_mirrors(prob, t, q, t_window, tolerance, res, counter, error)
      else
         call fit_stages(prob, t, q, t_window, tolerance, res, counter, error, guess)
      end if
      res%work = counter%used
      if (counter%show .and. (counter%progress%reported > 0 .or. progress_listened())) &
         call counter%progress%finish()
   end subroutine fit_series

   !> Points not observed (the elbow of a tip-only series) have two mirror places for
   !> each observed configuration: the fit starts from every combination of sides
   !> (at most 2^4) and keeps the one of lowest RMS residual in the window; res%mirror
   !> says which, with the others' RMS. A start that fails is passed over unless all
   !> fail (its error then).
   subroutine fit_mirrors(prob, t, q, t_window, tolerance, res, counter, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem, points given
      real(dp), intent(in) :: t(:), q(:, :)             !! the samples
      real(dp), intent(in) :: t_window, tolerance       !! as fit_series
      type(fit_result_t), intent(out) :: res            !! the best start's fit
      type(fit_counter_t), intent(inout) :: counter     !! work done, its limit
      type(error_t), allocatable, intent(out) :: error  !! every start failed
      type(fit_problem_t) :: trial
      type(fit_result_t) :: one, failed
      type(error_t), allocatable :: err
      integer, allocatable :: gaps(:)
      integer :: n, combo, g, same, distinct
      character(len=:), allocatable :: others, kept
      logical :: found, close_by
      n = problem_links(prob, size(q, 1))
      gaps = unobserved_points(prob, n)
      if (size(gaps) > 4) then
         call fatal_error(error, to_str(size(gaps))//' points are not observed: at most 4 ' &
                          //'(each doubles the starts: the mirror places of its link pair)')
         return
      end if
      trial = prob
      allocate (trial%branch(n))
      found = .false.
      others = ''
      same = 0
      distinct = 0
      do combo = 0, 2**size(gaps) - 1
         trial%branch = 1
         do g = 1, size(gaps)
            if (btest(combo, g - 1)) trial%branch(gaps(g)) = -1
         end do
         call fit_stages(trial, t, q, t_window, tolerance, one, counter, err)
         if (counter%exceeded) then
            call move_alloc(err, error)
            return
         end if
         if (allocated(err) .and. one%stalled) then   ! the model, not the start: stop
            call move_alloc(err, error)
            res = one
            return
         end if
         if (allocated(err)) then
            if (.not. found .and. .not. allocated(error)) then
               call move_alloc(err, error)
               failed = one   ! (stalled: where, for the caller)
            end if
            if (allocated(err)) deallocate (err)
            others = others//'; '//sides(trial%branch)//': failed'
            cycle
         end if
         if (.not. found) then
            res = one
            kept = sides(trial%branch)
            found = .true.
            cycle
         end if
         ! the same estimates (within 3 standard errors): the dynamics chose the place
         if (all(ieee_is_finite(res%se)) .and. all(ieee_is_finite(one%se)) .and. &
             all(ieee_is_finite(one%p)) .and. all(ieee_is_finite(res%p))) then
            close_by = all(abs(one%p - res%p) <= 3*max(res%se, one%se))
         else
            close_by = .false.
         end if
         if (close_by) then
            same = same + 1
         else
            distinct = distinct + 1
         end if
         if (one%rms < res%rms) then
            others = others//'; '//kept//': RMS '//real_str(res%rms, 3)
            res = one
            kept = sides(trial%branch)
         else
            others = others//'; '//sides(trial%branch)//': RMS '//real_str(one%rms, 3)
         end if
      end do
      if (.not. found) then
         res = failed
         return
      end if
      if (allocated(error)) deallocate (error)
      if (distinct == 0 .and. same > 0) then
         res%mirror = 'the unobserved '//trim(merge('point: ', 'points:', size(gaps) == 1))// &
                      ' the fit started from every mirror place and each reached the same ' &
                      //'estimates (within 3 standard errors; RMS '//real_str(res%rms, 3)// &
                      '): the motion decides the place'
      else
         res%mirror = 'the unobserved '//trim(merge('point: ', 'points:', size(gaps) == 1))// &
                      ' the mirror places give different fits; kept '//kept//' (RMS '// &
                      real_str(res%rms, 3)//others//')'
      end if
   contains
      !> 'point 1 counter-clockwise of the chord' for each gap.
      function sides(branch) result(txt)
         integer, intent(in) :: branch(:)
         character(len=:), allocatable :: txt
         integer :: gg
         txt = ''
         do gg = 1, size(gaps)
            if (gg > 1) txt = txt//', '
            txt = txt//'point '//to_str(gaps(gg))//trim(merge(' left ', ' right', &
                  branch(gaps(gg)) > 0))//' of the chord'
         end do
      end function sides
   end subroutine fit_mirrors

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
      n = problem_links(prob, no)
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
      real(dp) :: period, thr, rms_stage, rms_before
      integer :: np, k_min, k_stage, it, j, no
      logical :: conv
      character(len=:), allocatable :: how, ou
      no = size(q, 1)
      np = res%np
      res%noise = observation_noise(prob, q, res%k_fit, how)
      rms_before = 0.0_dp
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
         rms_stage = sqrt(sum(r(:no*k_stage)**2)/real(no*k_stage, dp))
         if (rms_stage <= misfit_factor*res%noise) res%good_k = k_stage
         if (prob%stall_check .and. rms_stage > stall_factor*res%noise .and. &
             rms_before > stall_factor*res%noise .and. rms_stage >= rms_before .and. &
             t(k_stage) - t(1) >= 0.5_dp*prob%swing) then
            res%stalled = .true.
            res%stall_k = k_stage
            res%stall_rms = rms_stage
            ou = ''   ! the residuals' unit (a model's own coordinates: their own)
            if (prob%positions) then
               ou = ' m'
            else if (.not. allocated(prob%angular)) then
               ou = ' rad'
            end if
            call fatal_error(error, 'the fit stalls far above the noise: over the first '// &
                             real_str(t(k_stage) - t(1), 3)//' s the model stays '// &
                             real_str(rms_stage, 3)//ou//' (RMS) from the data, '// &
                             real_str(rms_stage/res%noise, 2)//' times the noise '// &
                             real_str(res%noise, 2)//ou)
            return
         end if
         rms_before = rms_stage
         thr = 0.01_dp   ! (rad; m per metre of chain for positions)
         if (prob%positions) thr = 0.01_dp*sum(prob%l)
         thr = max(10.0_dp*rms_stage, thr)
         j = k_stage + 1
         do while (j <= res%k_fit)
            if (maxval(abs(r(no*(j - 1) + 1:no*j))) > thr) exit
            j = j + 1
         end do
         k_stage = min(res%k_fit, max(j - 1, k_stage + max(1, k_stage/4)))
      end do
      res%converged = conv
   end subroutine continuation

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
end module dpend_estimate
