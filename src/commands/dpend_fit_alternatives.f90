!> When a fit stalls far above the noise (`fit_series` with prob%stall_check: the
!> model does not describe the data), the alternatives a user can choose are fitted
!> on the window where it stalled and compared by their RMS residuals: the other
!> named bodies (--body rod, point), the joint damping fitted too, and a shorter fit
!> window (the longest the model described). `weigh_alternatives` says which fits,
!> whether another body is what the data need, and
!> whether one is clearly better: its RMS a third or less of the stalled fit's and of
!> the configured model's fitted afresh on that window (a continuation stuck in a
!> local minimum is not the model's fault). Each alternative may do at most twice the
!> stalled fit's work, the fresh configured fit at most half the best alternative's:
!> the weighing costs about what the stalled fit did.
module dpend_fit_alternatives
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_strings, only: real_str
   use dpend_model_factory, only: body_names, has_parameter
   use dpend_run_settings, only: validate_run_config
   use dpend_estimate, only: fit_problem_t, fit_result_t, fit_series, misfit_factor
   use dpend_fit_config, only: fit_config_t, fit_problem, joined_names
   implicit none
   private
   public :: weigh_alternatives

   !> An alternative is clearly better when its RMS is at most this fraction of the
   !> stalled fit's on the same window.
   real(dp), parameter :: better_fraction = 1.0_dp/3.0_dp
   !> The least work an alternative may do [step-equivalents]
   real(dp), parameter :: min_work = 1e5_dp

contains

   !> Fit the alternatives on the stalled window (samples 1 .. res%stall_k) and say
   !> what they give: `text` lists them with their RMS ('--body point: RMS 0.00098 m,
   !> 1 times the noise'), `advice` the best one if clearly better ('' if none),
   !> `better` whether one is.
   subroutine weigh_alternatives(fc, res, unit, text, advice, better, work, body)
      type(fit_config_t), intent(in) :: fc           !! the fit as configured
      type(fit_result_t), intent(in) :: res          !! the stalled fit (stall_k set)
      character(len=*), intent(in) :: unit           !! of the residuals ('m', 'rad')
      character(len=:), allocatable, intent(out) :: text, advice
      logical, intent(out) :: better
      real(dp), intent(out) :: work                  !! their work [step-equivalents]
      !> the clearly better alternative is another body (the configured one cannot
      !> describe the data: a fit with it runs long and ends far off)
      logical, intent(out) :: body
      type(fit_config_t) :: alt
      type(error_t), allocatable :: err
      character(len=:), allocatable :: current, chosen
      real(dp) :: best, best_work, cap, last_rms
      integer :: i
      text = ''
      advice = ''
      better = .false.
      body = .false.
      work = 0.0_dp
      best = huge(1.0_dp)
      best_work = 0.0_dp
      cap = max(2.0_dp*res%work, min_work)
      current = 'rod'
      if (allocated(fc%run%body)) current = fc%run%body
      if (fc%run%spec%find('com') > 0 .and. .not. allocated(fc%run%body)) current = 'general'
      do i = 1, size(body_names)   ! the other named bodies
         if (trim(body_names(i)) == current .or. current == 'general') cycle
         alt = fc
         alt%run%body = trim(body_names(i))
         call validate_run_config(alt%run, err)
         if (allocated(err)) cycle
         call try(alt, '--body '//trim(body_names(i)))
      end do
      if (has_parameter(fc%run%spec%model_name(), 'damping') .and. &
          .not. any(fc%fit_names == 'damping')) then   ! the damping fitted too
         alt = fc
         alt%fit_names = [character(len=32) :: fc%fit_names, 'damping']
         call try(alt, '--fit-param '//joined_names(alt%fit_names))
      end if
      if (better) then
         ! the fit as configured, afresh on that window, at most half the best
         ! alternative's work: a continuation stuck on its way (a local minimum) fits it
         ! here too, and the alternative is then no better
         chosen = advice
         cap = max(0.5_dp*best_work, min_work)
         call try(fc, 'as configured, afresh on that window')
         if (.not. (best <= better_fraction*last_rms)) then
            better = .false.
            body = .false.
            advice = ''
         else
            advice = chosen
            body = index(chosen, 'give --body ') == 1
         end if
      end if
      if (res%good_k > 0 .and. res%good_k < res%stall_k) then   ! a shorter window
         if (len(text) > 0) text = text//'; '
         text = text//'--fit-window '//real_str(fc%series%t(res%good_k), 4)//': the model ' &
                //'described the data up to there (RMS within '//real_str(misfit_factor)// &
                ' times the noise)'
      end if
      if (better) return
      if (res%good_k > 0 .and. res%good_k < res%stall_k) &
         advice = 'fit --fit-window '//real_str(fc%series%t(res%good_k), 4)// &
                  ' (what the model describes), or find what the model lacks'
   contains
      !> Fit `a` on the stalled window; its RMS into the text, the best kept.
      subroutine try(a, what)
         type(fit_config_t), intent(in) :: a
         character(len=*), intent(in) :: what
         type(fit_problem_t) :: prob
         type(fit_result_t) :: r
         type(error_t), allocatable :: e
         integer :: k
         k = res%stall_k
         last_rms = huge(1.0_dp)
         call fit_problem(a, prob, e)
         if (allocated(e)) return
         prob%stall_check = .false.
         prob%work_limit = cap
         call fit_series(prob, a%series%t(:k), a%series%q(:, :k), a%series%t(k), &
                         a%tolerance, r, e)
         work = work + r%work
         if (len(text) > 0) text = text//'; '
         if (allocated(e)) then
            text = text//what//': failed ('//e%message//')'
            return
         end if
         last_rms = r%rms
         text = text//what//': RMS '//real_str(r%rms, 3)//' '//unit//', '// &
                real_str(r%rms/max(res%noise, tiny(1.0_dp)), 2)//' times the noise'
         if (r%rms < best .and. r%rms <= better_fraction*res%stall_rms) then
            best = r%rms
            best_work = r%work
            better = .true.
            body = index(what, '--body ') == 1
            advice = 'give '//what
         end if
      end subroutine try
   end subroutine weigh_alternatives
end module dpend_fit_alternatives
