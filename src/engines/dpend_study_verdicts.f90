!> The verdicts of `dpend study` (the engine's judgement of its results): the
!> measured orders against the registry's, the drift exponents (bounded for the
!> symplectic methods, linear for the others) and Brouwer's law of the roundoff
!> runs, each with its one-line text. Used by the summary and the HDF5 file of the
!> front end (dpend_study_command).
module dpend_study_verdicts
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_kinds, only: dp, i8
   use dpend_fit, only: fit_t
   use dpend_study_settings, only: study_config_t, case_index, balance_case, &
      study_model_name
   use dpend_study, only: study_result_t, sweep_t, mode_step
   use dpend_integrator, only: stat_ok
   use dpend_cli, only: to_str
   implicit none
   private
   public :: verdicts_t, study_verdicts, sweep_index, order_ok, drift_ok, drift_judged, drift_failed
   public :: order_tolerance, bounded_max, linear_tol, brouwer_tol, drift_min_steps, fmt

   !> Measured orders must lie within this of the nominal order.
   real(dp), parameter :: order_tolerance = 0.3_dp
   !> Drift exponents: symplectic below `bounded_max`, explicit within `linear_tol` of 1.
   real(dp), parameter :: bounded_max = 0.1_dp, linear_tol = 0.2_dp
   !> Brouwer's law: exponent 0.5 within this.
   real(dp), parameter :: brouwer_tol = 0.15_dp
   !> The drift exponent is judged only when the long run at the middle step has at
   !> least this many steps. The exponent is fitted over the last `drift_decades`
   !> (default 2) decades of t, so a shorter run starts its fit window within its
   !> first 1000 steps: for the study's steps (1e-3 to 4e-2 s) within the first
   !> period or so of the motion (about 2 s for small oscillations), where the energy
   !> error of a non-symplectic method still oscillates within each period instead
   !> of growing secularly (rk4 on case small: exponent 0.51 with the 2e4 steps of
   !> --quick, 1 expected). Shorter runs read "too short to judge", neither ✓ nor ✗.
   integer(i8), parameter :: drift_min_steps = 100000_i8

   !> The done-when checks of the study.
   type :: verdicts_t
      logical :: orders = .false.      !! every method's orders within ±0.3 (order case)
      logical :: drift = .false.       !! bounded symplectic, linear explicit (drift case)
      logical :: roundoff = .false.    !! compensated exponents 0.5 ± 0.15
      logical :: drift_judged = .false.  !! some method's long run was long enough
      logical :: roundoff_run = .false.  !! the study made roundoff runs
      character(len=:), allocatable :: orders_text, drift_text, roundoff_text
   end type verdicts_t

contains

   !> Index of the fixed-step sweep of method `name` on case ic (0 if none).
   pure integer function sweep_index(res, ic, name, mode) result(s)
      type(study_result_t), intent(in) :: res
      integer, intent(in) :: ic, mode
      character(len=*), intent(in) :: name
      integer :: i
      s = 0
      do i = 1, size(res%sweeps)
         if (res%sweeps(i)%icase == ic .and. res%sweeps(i)%method == name .and. &
             res%sweeps(i)%mode == mode) then
            s = i
            return
         end if
      end do
   end function sweep_index

   !> |fitted - nominal| <= tol for a successful fit.
   pure logical function order_ok(fit, nominal)
      type(fit_t), intent(in) :: fit
      integer, intent(in) :: nominal
      order_ok = .false.
      if (fit%ok) order_ok = abs(fit%slope - nominal) <= order_tolerance
   end function order_ok

   !> The drift exponent of the middle point is as expected: below 0.1 for
   !> symplectic methods, within 0.2 of 1 for the others.
   pure logical function drift_ok(sw)
      type(sweep_t), intent(in) :: sw
      drift_ok = .false.
      if (.not. ieee_is_finite(sw%drift(sw%mid))) return
      if (sw%symplectic) then
         drift_ok = sw%drift(sw%mid) < bounded_max
      else
         drift_ok = abs(sw%drift(sw%mid) - 1.0_dp) <= linear_tol
      end if
   end function drift_ok

   !> The long run of `sw` at its middle step is long enough to judge its drift
   !> exponent (at least `drift_min_steps` steps).
   pure logical function drift_judged(sw)
      type(sweep_t), intent(in) :: sw
      drift_judged = sw%long_steps(sw%mid) >= drift_min_steps .and. .not. drift_failed(sw)
   end function drift_judged

   !> The long run at the middle step failed (a step failure, non-finite values):
   !> its drift is not judged, and says so rather than "too short".
   pure logical function drift_failed(sw)
      type(sweep_t), intent(in) :: sw
      drift_failed = .false.
      if (allocated(sw%stat)) drift_failed = sw%stat(sw%mid) /= stat_ok
   end function drift_failed

   !> Evaluate the done-when checks. An experiment that was not run reads "not run";
   !> a drift exponent from too short a run reads "too short to judge"; neither is a
   !> failure.
   function study_verdicts(cfg, res) result(v)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(in) :: res
      type(verdicts_t) :: v
      integer :: im, s, io, id, i
      character(len=:), allocatable :: bad, short, failed
      io = case_index(cfg, cfg%order_case)
      id = case_index(cfg, cfg%drift_case)
      bad = ''
      do im = 1, size(cfg%methods)
         s = sweep_index(res, io, cfg%methods(im)%name, mode_step)
         if (s == 0) cycle
         if (.not. (order_ok(res%sweeps(s)%fit_global, res%sweeps(s)%order) .and. &
                    order_ok(res%sweeps(s)%fit_energy, res%sweeps(s)%order))) &
            bad = bad//' '//cfg%methods(im)%name
      end do
      v%orders = len(bad) == 0
      if (v%orders) then
         v%orders_text = 'every method within ±'//fmt(order_tolerance, 'f0.1')// &
                         ' of its nominal order (case '//cfg%order_case//')'
      else
         v%orders_text = 'outside ±'//fmt(order_tolerance, 'f0.1')//' (case '// &
                         cfg%order_case//'):'//bad
      end if
      bad = ''
      short = ''
      failed = ''
      do im = 1, size(cfg%methods)
         s = sweep_index(res, id, cfg%methods(im)%name, mode_step)
         if (s == 0) cycle
         if (balance_case(cfg, id)) cycle   ! no conserved energy: no drift verdict
         if (drift_failed(res%sweeps(s))) then
            failed = failed//' '//cfg%methods(im)%name
         else if (.not. drift_judged(res%sweeps(s))) then
            short = short//' '//cfg%methods(im)%name
         else
            v%drift_judged = .true.
            if (.not. drift_ok(res%sweeps(s))) bad = bad//' '//cfg%methods(im)%name
         end if
      end do
      v%drift = len(bad) == 0 .and. v%drift_judged
      if (balance_case(cfg, id)) then
         v%drift_text = 'case '//cfg%drift_case//' is damped or driven (its ' &
                        //'energy balance error is shown instead; no conserved energy)'
      else if (.not. v%drift_judged .and. len(short) == 0 .and. len(failed) > 0) then
         v%drift_text = 'every long run at the middle step failed (case '// &
                        cfg%drift_case//'; the file has each run''s status):'//failed
      else if (.not. v%drift_judged) then
         v%drift_text = 'every long run has fewer than '//to_str(drift_min_steps)// &
                        ' steps at the middle step (case '//cfg%drift_case//'):'//short
         if (len(failed) > 0) v%drift_text = v%drift_text//'; failed:'//failed
      else
         if (v%drift) then
            v%drift_text = 'symplectic methods bounded (exponent < '// &
                           fmt(bounded_max, 'f0.1')//'), the others linear (1 ± '// &
                           fmt(linear_tol, 'f0.1')//') (case '//cfg%drift_case//', middle step)'
         else
            v%drift_text = 'unexpected drift exponent (case '//cfg%drift_case//'):'//bad
         end if
         if (len(short) > 0) v%drift_text = v%drift_text//'; too short to judge (fewer than '// &
                                            to_str(drift_min_steps)//' steps):'//short
         if (len(failed) > 0) v%drift_text = v%drift_text//'; the long run failed:'//failed
      end if
      bad = ''
      do i = 1, size(res%roundoff)
         associate (ro => res%roundoff(i))
            if (.not. ro%fit(1)%ok) then
               bad = bad//' '//ro%method
            else if (abs(ro%fit(1)%slope - 0.5_dp) > brouwer_tol) then
               bad = bad//' '//ro%method
            end if
         end associate
      end do
      v%roundoff_run = size(res%roundoff) > 0
      v%roundoff = len(bad) == 0 .and. v%roundoff_run
      i = case_index(cfg, cfg%ro_case)
      if (.not. v%roundoff_run .and. size(cfg%ro_methods) > 0 .and. &
          balance_case(cfg, max(i, 1))) then
         v%roundoff_text = 'case '//cfg%ro_case//' is damped or driven (no ' &
                           //'conserved H)'
      else if (.not. v%roundoff_run .and. size(cfg%ro_methods) > 0 .and. &
               size(cfg%cases(max(i, 1))%q0) /= 2) then
         v%roundoff_text = 'not run for the N-link chain (case '//cfg%ro_case//', '// &
                           to_str(size(cfg%cases(max(i, 1))%q0))//' links): H in quadruple '// &
                           'precision is the double pendulum''s'
      else if (.not. v%roundoff_run .and. size(cfg%ro_methods) > 0) then
         v%roundoff_text = 'not run for model '//study_model_name(cfg)//' (case '// &
                           cfg%ro_case//'): it has no Hamiltonian in quadruple precision ' &
                           //'(the double pendulum''s alone)'
      else if (.not. v%roundoff_run) then
         v%roundoff_text = 'no roundoff method among the methods of this study'
      else if (v%roundoff) then
         v%roundoff_text = "Brouwer's law: compensated exponents within 0.5 ± " &
                           //fmt(brouwer_tol, 'f0.2')
      else
         v%roundoff_text = 'compensated exponent outside 0.5 ± '//fmt(brouwer_tol, 'f0.2')// &
                           ':'//bad
      end if
   end function study_verdicts

   !> x in the Fortran edit descriptor f, without blanks, with a leading 0 before the
   !> decimal point (0.5, −0.5).
   function fmt(x, f) result(s)
      real(dp), intent(in) :: x
      character(len=*), intent(in) :: f
      character(len=:), allocatable :: s
      character(len=64) :: buf
      write (buf, '('//f//')') x
      s = trim(adjustl(buf))
      if (len(s) > 1) then
         if (s(1:1) == '.') s = '0'//s
         if (s(1:2) == '-.') s = '-0'//s(2:)
      end if
   end function fmt
end module dpend_study_verdicts
