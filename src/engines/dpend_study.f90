!> The energy-conservation study: cases × methods × step sizes (tolerances for
!> the adaptive methods), the roundoff (Brouwer) runs and Tao's binding constant,
!> run as one list of independent jobs over OpenMP threads, then fitted.
!>
!> Each point of a sweep is two runs from the case's initial condition:
!>
!> * the **short run** to t_short, through `n_check` checkpoints k·t_short/n_check
!>   that fixed steps hit exactly (h = (t_short/n_check)/m, m an integer) and the
!>   adaptive methods reach exactly (their last step is capped). It gives the
!>   global error, the largest deviation max(|Δq_i|, |Δq̇_i|) over the links [rad,
!>   rad/s] from the reference over the checkpoints; the largest relative energy
!>   error over every step up to t_short; the counters; and the wall time of the
!>   same run without monitoring, repeated until it lasts `wall_min`.
!> * the **long run** to t_long = long_steps × h_mid (h_mid: the sweep's middle
!>   step), the same for every point of the sweep, with the relative energy error
!>   |H(t) − H(0)| / E_s evaluated after every step and kept as its maximum within
!>   logarithmic time bins (upper edges t_long·10^(−j/bins_per_decade)); the
!>   drift exponent is the slope of ln(bin maximum) against ln t over the last
!>   `drift_decades` decades.
!>
!> E_s = the model's `energy_scale(H(0))`: |H(0)|, or the potential energy with
!> every link upright when H(0) ≈ 0 (the horizontal release). H is the Hamiltonian
!> of the canonical methods' (q, p) and the energy T + V of the others' (q, q̇).
!>
!> A case of N links runs the double pendulum for N = 2 and the N-link chain
!> otherwise (`case_model`), through the model interface; states have 2N values.
!> A damped or driven case (a balance case) is the chain with its damping
!> and moving support; its sweeps integrate it with its work integrals (dpend_work)
!> and monitor the energy balance E(t) − E(0) + W_friction − W_support in place of
!> the energy error (same fields, same bins and fits); its methods are not
!> symplectic on it, and the roundoff and Tao experiments are not run on it.
!> Only the roundoff runs need H in quadruple precision (`has_hamiltonian_qp`, the
!> double pendulum's alone): for a `ro_case` of any other model they are not run.
!>
!> The adaptive methods are swept twice: at fixed steps with the error control
!> off (`fixed_step`: the order of the underlying formula) and over tolerances
!> (atol = atol_ratio × rtol), where the abscissa of the fits is the mean
!> accepted step t/n_steps.
!>
!> The reference of each case is `ref_method` at `ref_dt` (by default gauss8 at
!> 2.5e-4 s, the highest order at 60× below its sweep's smallest step), checked
!> against `check_method` at `check_rtol` (dop853 at 1e-14); the difference is
!> recorded, and errors below ten times it are left out of the fits.
!>
!> The roundoff runs integrate `ro_runs` perturbed copies of `ro_case` for
!> `ro_steps` steps with and without compensated summation, and evaluate the
!> energy error at logarithmically spaced steps in quadruple precision from the
!> compensated state y + comp (the model's `hamiltonian_qp`, where it has one:
!> `has_hamiltonian_qp`, the double pendulum), so that the error of the
!> numerical solution is seen below the double-precision rounding of H itself.
!>
!> Jobs share nothing mutable: each creates its own integrator from the factory
!> and writes only its own elements of the result arrays; progress is updated in
!> a named critical section.
module dpend_study
   use, intrinsic :: iso_fortran_env, only: error_unit, qp => real128
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_model, only: model_t, max_dof
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_index, method_table
   use dpend_symplectic, only: symplectic_t
   use dpend_propagate, only: march_t
   use dpend_fit, only: fit_t, loglog_fit, drift_exponent
   use dpend_os, only: wall_clock
   use dpend_progress, only: progress_silenced, progress_t
   use dpend_study_settings, only: study_config_t, case_index, case_model, balance_case, &
      step_grid
   use dpend_work, only: needs_work, work_model, is_work_model, augmented_state, &
                         balance_energy
   !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   implicit none
   private
   public :: study_result_t, reference_t, sweep_t, roundoff_t, tao_sweep_t
   public :: run_study, step_grid, time_bins, fit_sweeps
   public :: mode_step, mode_tol, global_floor, energy_floor, long_floor

   integer, parameter :: mode_step = 1  !! sweep over fixed steps
   integer, parameter :: mode_tol = 2   !! sweep over tolerances (adaptive methods)
   !> Energy errors at or below this are roundoff of the evaluation of H: left out of fits.
   real(dp), parameter :: energy_floor = 1.0e-14_dp
   !> Global errors at or below this are left out of fits (with 10× the reference check).
   real(dp), parameter :: global_floor = 1.0e-14_dp
   !> Maxima over the long runs at or below this are left out of fits: after 10⁶
   !> steps the accumulated roundoff of the state adds ~1e-14 (see the roundoff runs).
   real(dp), parameter :: long_floor = 1.0e-13_dp

   !> Reference solution of one case at the checkpoints.
   type :: reference_t
      real(dp), allocatable :: t(:)      !! checkpoint times (n_check) [s]
      real(dp), allocatable :: y(:, :)   !! (q1 … qN, q̇1 … q̇N) at them, (2N, n_check)
      real(dp) :: check_difference = 0.0_dp  !! max deviation of the check method
      real(dp) :: e0 = 0.0_dp            !! initial energy [J]
      real(dp) :: e_scale = 1.0_dp       !! energy unit E_s [J]
      integer :: stat = stat_ok          !! status of the reference run
      !> status of the check run alone (stat: the reference's own, else this)
      integer :: check_stat = stat_ok
   end type reference_t

   !> One sweep: a method on a case, over steps or tolerances; arrays over points.
   type :: sweep_t
      integer :: icase = 0                 !! case index
      integer :: imethod = 0               !! method index in the configuration
      integer :: mode = mode_step          !! mode_step or mode_tol
      character(len=:), allocatable :: method  !! method name
      integer :: order = 0                 !! nominal order
      logical :: symplectic = .false.      !! the method is symplectic
      integer :: mid = 1                   !! index of the middle point
      real(dp) :: t_long = 0.0_dp          !! horizon of the long runs [s]
      real(dp), allocatable :: x(:)        !! step [s] (mode_step) or rtol (mode_tol)
      real(dp), allocatable :: t_bins(:)   !! upper edges of the time bins [s]
      real(dp), allocatable :: h_mean_short(:)  !! t_short / accepted steps [s]
      real(dp), allocatable :: h_mean_long(:)   !! t_long / accepted steps [s]
      real(dp), allocatable :: y_check(:, :, :) !! states at the checkpoints (2N, n_check, n)
      real(dp), allocatable :: global_error(:)  !! max deviation from the reference
      real(dp), allocatable :: energy_short(:)  !! max relative energy error up to t_short
      real(dp), allocatable :: energy_long(:)   !! max relative energy error up to t_long
      real(dp), allocatable :: energy_final(:)  !! relative energy error at t_long
      real(dp), allocatable :: bins(:, :)       !! bin maxima (n, n_bins); NaN: empty bin
      real(dp), allocatable :: drift(:)         !! fitted drift exponent
      real(dp), allocatable :: drift_stderr(:)  !! its standard error
      integer(i8), allocatable :: short_steps(:), short_rhs(:), short_iter(:), short_rejected(:)
      integer(i8), allocatable :: long_steps(:), long_rhs(:), long_iter(:), long_rejected(:)
      real(dp), allocatable :: wall_short(:)    !! wall time of one short run [s]
      real(dp), allocatable :: wall_long(:)     !! wall time of the long run [s]
      integer, allocatable :: stat(:)           !! stat_ok or the first failure
      type(fit_t) :: fit_global       !! global error against step (mean step)
      type(fit_t) :: fit_energy       !! energy error up to t_short against step
      type(fit_t) :: fit_energy_long  !! energy error up to t_long against step
      type(fit_t) :: fit_tolerance    !! global error against rtol (mode_tol)
   end type sweep_t

   !> Roundoff runs of one method: signed energy errors at sample steps.
   type :: roundoff_t
      character(len=:), allocatable :: method  !! method name
      real(dp) :: dt = 0.0_dp                  !! step [s]
      integer(i8), allocatable :: steps(:)     !! sample steps
      real(dp), allocatable :: t(:)            !! sample times [s]
      !> (H - H0)/E_s, (n_samples, runs, 2): 1 compensated, 2 plain
      real(dp), allocatable :: err(:, :, :)
      real(dp), allocatable :: rms(:, :)       !! RMS over the runs, (n_samples, 2)
      integer, allocatable :: stat(:, :)       !! (runs, 2)
      real(dp), allocatable :: wall(:, :)      !! wall time per run (runs, 2) [s]
      type(fit_t) :: fit(2)                    !! exponent of the RMS in t
   end type roundoff_t

   !> Tao runs of one method over ω.
   type :: tao_sweep_t
      character(len=:), allocatable :: method  !! tao2 or tao4
      real(dp), allocatable :: omega(:)        !! binding constants [1/s]
      real(dp), allocatable :: energy_max(:)   !! max relative energy error
      real(dp), allocatable :: energy_final(:) !! relative energy error at the end
      real(dp), allocatable :: global_error(:) !! deviation from the reference at t_short
      integer, allocatable :: stat(:)          !! status
   end type tao_sweep_t

   !> Everything the study computed.
   type :: study_result_t
      type(reference_t), allocatable :: refs(:)       !! per case
      type(sweep_t), allocatable :: sweeps(:)         !! cases × methods × modes
      type(roundoff_t), allocatable :: roundoff(:)    !! per roundoff method
      type(tao_sweep_t), allocatable :: tao(:)        !! per Tao method
      integer :: threads = 1                          !! OpenMP threads used
      real(dp) :: wall_total = 0.0_dp                 !! elapsed time [s]
   end type study_result_t

   integer, parameter :: job_ref = 0, job_sweep = 1, job_roundoff = 2, job_tao = 3

   !> One unit of work.
   type :: job_t
      integer :: kind = job_sweep  !! job_sweep, job_roundoff, job_tao
      integer :: i = 0             !! sweep, roundoff or Tao index
      integer :: k = 0             !! point, run or ω index
      integer :: c = 1             !! roundoff: 1 compensated, 2 plain
      real(dp) :: cost = 0.0_dp    !! estimated seconds
   end type job_t

contains

   ! ================================================================ grids

   !> Upper edges of the logarithmic time bins below t_end: t_end·10^(−j/b),
   !> j = n_bins − 1 … 0, n_bins = decades·b; bin 1 starts at 0.
   pure function time_bins(t_end, decades, per_decade) result(edges)
      real(dp), intent(in) :: t_end       !! end of the run [s]
      integer, intent(in) :: decades      !! decades covered
      integer, intent(in) :: per_decade   !! bins per decade
      real(dp) :: edges(decades*per_decade)
      integer :: j, nb
      nb = decades*per_decade
      do j = 1, nb
         edges(j) = t_end*10.0_dp**(-real(nb - j, dp)/real(per_decade, dp))
      end do
      edges(nb) = t_end
   end function time_bins

   !> Geometric values from a to b (n >= 1).
   pure function geometric(a, b, n) result(x)
      real(dp), intent(in) :: a, b
      integer, intent(in) :: n
      real(dp) :: x(n)
      integer :: k
      if (n == 1) then
         x = sqrt(a*b)
         return
      end if
      do k = 1, n
         x(k) = a*(b/a)**(real(k - 1, dp)/real(n - 1, dp))
      end do
   end function geometric

   ! ================================================================ energy

   !> Energy of the internal state: H(q, p) for canonical methods, T + V else [J].
   function energy_of(integ, model, y) result(e)
      class(integrator_t), intent(in) :: integ  !! the method
      class(model_t), intent(in) :: model       !! the system
      real(dp), intent(in) :: y(:)              !! internal state
      real(dp) :: e
      if (integ%canonical_on(model)) then
         e = model%hamiltonian_value(0.0_dp, y)
      else
         e = model%energy(0.0_dp, y)
      end if
   end function energy_of

   !> The energy monitored by the sweeps: `energy_of` (H or T + V), and for a damped
   !> or driven chain with its works (dpend_work) E(t) + W_friction − W_support
   !> (− W_torque), whose change from t = 0 is the error of the energy balance.
   function monitored_energy(integ, model, t, y) result(e)
      class(integrator_t), intent(in) :: integ  !! the method
      class(model_t), intent(in) :: model       !! the system
      real(dp), intent(in) :: t                 !! time [s]
      real(dp), intent(in) :: y(:)              !! internal state
      real(dp) :: e
      if (is_work_model(model)) then   ! y = (q, W_friction, q̇, W_support), (q, q̇) inside
         e = balance_energy(model, t, y)
      else
         e = energy_of(integ, model, y)
      end if
   end function monitored_energy

   ! ================================================================ driver

   !> Run the whole study described by `cfg` (validated). Progress goes to stderr
   !> unless `quiet`.
   subroutine run_study(cfg, res, quiet)
      type(study_config_t), intent(in) :: cfg        !! configuration
      type(study_result_t), intent(out) :: res       !! everything computed
      logical, intent(in), optional :: quiet         !! no progress display
      type(job_t), allocatable :: jobs(:)
      integer, allocatable :: order(:)
      real(dp) :: start
      integer :: j
      logical :: show
      type(progress_t) :: bar
      show = .not. progress_silenced()   ! --quiet
      if (present(quiet)) show = .not. quiet
      start = wall_clock()
      res%threads = 1
      !$ if (cfg%threads > 0) call omp_set_num_threads(cfg%threads)
      !$ res%threads = omp_get_max_threads()
      call compute_references(cfg, res)
      call plan(cfg, res, jobs)
      order = sort_by_cost(jobs)
      if (show) then
         write (error_unit, '(a, i0, a, i0, a)') 'dpend study: ', size(jobs), ' runs on ', &
            res%threads, trim(merge(' thread ', ' threads', res%threads == 1))
         flush (error_unit)
      end if
      ! the one progress report: a bar on a terminal, else a line at most
      ! every 10 s
      call bar%start('dpend study', int(size(jobs), i8), 0_i8, .not. show, what='runs')
      !$omp parallel do schedule(dynamic, 1) default(shared) private(j)
      do j = 1, size(jobs)
         call run_job(cfg, res, jobs(order(j)))
         !$omp critical (study_progress)
         call bar%update(1_i8)
         !$omp end critical (study_progress)
      end do
      !$omp end parallel do
      call bar%finish()
      call time_short_runs(cfg, res, show)
      call fit_sweeps(res)
      call fit_roundoff(cfg, res)
      res%wall_total = wall_clock() - start
   end subroutine run_study

   !> Seconds with two decimals, e.g. '0.04'.
   function seconds(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(f0.2)') x
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0'//s
   end function seconds

   ! ============================================================= references

   !> The reference of every case at the checkpoints, and its check.
   subroutine compute_references(cfg, res)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(inout) :: res
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      type(error_t), allocatable :: error
      real(dp), allocatable :: yc(:, :)
      real(dp) :: interval
      integer :: ic, k
      interval = cfg%t_short/cfg%n_check
      allocate (res%refs(size(cfg%cases)))
      do ic = 1, size(cfg%cases)
         associate (ref => res%refs(ic), cs => cfg%cases(ic))
            call case_model(cfg, ic, model)
            ref%t = [(k*interval, k=1, cfg%n_check)]
            allocate (ref%y(2*size(cs%q0), cfg%n_check), yc(2*size(cs%q0), cfg%n_check))
            ref%e0 = model%energy(0.0_dp, [cs%q0, cs%w0])
            ref%e_scale = model%energy_scale(ref%e0)
            call new_integrator(cfg%ref_method, integ, error)
            call checkpoints(integ, model, cs%q0, cs%w0, ref%t, &
                             interval/real(max(1, nint(interval/cfg%ref_dt)), dp), ref%y, ref%stat)
            call new_integrator(cfg%check_method, integ, error, method_options_t( &
                                rtol=cfg%check_rtol, atol=1.0e-2_dp*cfg%check_rtol))
            call checkpoints(integ, model, cs%q0, cs%w0, ref%t, 0.0_dp, yc, k)
            ref%check_stat = k
            if (k == stat_ok .and. ref%stat == stat_ok) then
               ref%check_difference = maxval(abs(yc - ref%y))
            else
               ref%check_difference = huge(1.0_dp)
               if (ref%stat == stat_ok) ref%stat = k
            end if
            deallocate (yc)
         end associate
      end do
   end subroutine compute_references

   !> Physical states (q, q̇) at the times `times` (increasing, > 0) from (q0, w0):
   !> fixed step h (exactly hitting each time) or, for adaptive methods, h = 0.
   subroutine checkpoints(integ, par, q0, w0, times, h, ys, stat)
      class(integrator_t), intent(inout) :: integ
      class(model_t), intent(in) :: par
      real(dp), intent(in) :: q0(:), w0(:), times(:), h
      real(dp), intent(out) :: ys(:, :)
      integer, intent(out) :: stat
      type(march_t) :: march
      real(dp) :: t, hh
      real(dp), allocatable :: y(:)
      integer :: k, n
      n = size(q0)
      y = integ%to_internal(par, q0, w0)
      t = 0.0_dp
      hh = h
      ys = 0.0_dp
      stat = stat_ok
      do k = 1, size(times)
         if (.not. integ%adaptive()) hh = h
         call march%start(integ, t, times(k), hh)
         do while (.not. march%finished)
            call march%next(integ, par, t, y, hh, stat)
            if (stat /= stat_ok) return
         end do
         call integ%to_physical(par, y, ys(1:n, k), ys(n + 1:2*n, k))
      end do
   end subroutine checkpoints

   ! ================================================================ planning

   !> Allocate the results and list the jobs with their estimated costs.
   subroutine plan(cfg, res, jobs)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(inout) :: res
      type(job_t), allocatable, intent(out) :: jobs(:)
      type(job_t), allocatable :: list(:)
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      class(model_t), allocatable :: ro_model
      integer :: ic, im, mode, n, k, s, nb, i, ns, c
      real(dp) :: interval, h_mid, nan, cps
      integer(i8) :: n_ro
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      interval = cfg%t_short/cfg%n_check
      nb = cfg%decades*cfg%bins_per_decade
      ! sweeps
      n = 0
      do im = 1, size(cfg%methods)
         n = n + 1
         if (cfg%methods(im)%rtol_min > 0.0_dp) n = n + 1
      end do
      allocate (res%sweeps(n*size(cfg%cases)))
      allocate (list(0))
      s = 0
      do ic = 1, size(cfg%cases)
         do im = 1, size(cfg%methods)
            do mode = mode_step, mode_tol
               if (mode == mode_tol .and. .not. cfg%methods(im)%rtol_min > 0.0_dp) cycle
               s = s + 1
               associate (sw => res%sweeps(s), me => cfg%methods(im))
                  sw%icase = ic
                  sw%imethod = im
                  sw%mode = mode
                  sw%method = me%name
                  call new_integrator(me%name, integ, error)
                  sw%order = integ%order()
                  ! (not symplectic on a damped or driven case)
                  sw%symplectic = integ%symplectic() .and. .not. balance_case(cfg, ic)
                  if (mode == mode_step) then
                     n = cfg%n_h
                     sw%x = step_grid(me%h_min, me%h_max, n, interval)
                  else
                     n = cfg%n_rtol
                     sw%x = geometric(me%rtol_max, me%rtol_min, n)
                  end if
                  sw%mid = (n + 1)/2
                  call allocate_sweep(sw, n, 2*size(cfg%cases(ic)%q0), cfg%n_check, nb, nan)
                  ! the long horizon: long_steps steps of the fixed-step sweep's middle step
                  block
                     real(dp) :: hs(cfg%n_h)
                     hs = step_grid(me%h_min, me%h_max, cfg%n_h, interval)
                     h_mid = hs((cfg%n_h + 1)/2)
                  end block
                  sw%t_long = cfg%cases(ic)%long_steps*h_mid
                  sw%t_bins = time_bins(sw%t_long, cfg%decades, cfg%bins_per_decade)
                  cps = cost_per_step(me%name)
                  do k = 1, n
                     if (mode == mode_step) then
                        list = [list, job_t(job_sweep, s, k, 1, &
                                            cps*(sw%t_long + cfg%t_short)/sw%x(k))]
                     else
                        list = [list, job_t(job_sweep, s, k, 1, cps*sw%t_long/ &
                                            adaptive_step_guess(me%name, sw%x(k)))]
                     end if
                  end do
               end associate
            end do
         end do
      end do
      ! roundoff: only on a model with H in quadruple precision (the double pendulum;
      ! not a chain of other than two links, nor a damped or driven case: the verdict
      ! says so)
      n_ro = nint(cfg%ro_steps, i8)
      call case_model(cfg, case_index(cfg, cfg%ro_case), ro_model)
      if (ro_model%has_hamiltonian_qp()) then
         allocate (res%roundoff(size(cfg%ro_methods)))
      else
         allocate (res%roundoff(0))
      end if
      do i = 1, size(res%roundoff)
         associate (ro => res%roundoff(i))
            ro%method = trim(cfg%ro_methods(i))
            ro%dt = cfg%ro_dt(i)
            ro%steps = sample_steps(n_ro, cfg%bins_per_decade)
            ns = size(ro%steps)
            ro%t = real(ro%steps, dp)*ro%dt
            allocate (ro%err(ns, cfg%ro_runs, 2), ro%rms(ns, 2), ro%stat(cfg%ro_runs, 2), &
                      ro%wall(cfg%ro_runs, 2))
            ro%err = nan; ro%rms = nan; ro%stat = stat_ok; ro%wall = 0.0_dp
            do c = 1, 2
               do k = 1, cfg%ro_runs
                  list = [list, job_t(job_roundoff, i, k, c, &
                                      cost_per_step(ro%method)*real(n_ro, dp)*0.7_dp)]
               end do
            end do
         end associate
      end do
      ! Tao: on a Hamiltonian case only
      if (balance_case(cfg, case_index(cfg, cfg%tao_case))) then
         allocate (res%tao(0))
      else
         allocate (res%tao(size(cfg%tao_methods)))
      end if
      do i = 1, size(res%tao)
         associate (ts => res%tao(i))
            ts%method = trim(cfg%tao_methods(i))
            ts%omega = geometric(cfg%omega_min, cfg%omega_max, cfg%n_omega)
            allocate (ts%energy_max(cfg%n_omega), ts%energy_final(cfg%n_omega), &
                      ts%global_error(cfg%n_omega), ts%stat(cfg%n_omega))
            ts%energy_max = nan; ts%energy_final = nan; ts%global_error = nan
            ts%stat = stat_ok
            do k = 1, cfg%n_omega
               list = [list, job_t(job_tao, i, k, 1, cost_per_step(ts%method)* &
                                   (cfg%tao_t_end + cfg%t_short)/cfg%tao_dt)]
            end do
         end associate
      end do
      call move_alloc(list, jobs)
   end subroutine plan

   subroutine allocate_sweep(sw, n, n_state, n_check, nb, nan)
      type(sweep_t), intent(inout) :: sw
      integer, intent(in) :: n, n_state, n_check, nb
      real(dp), intent(in) :: nan
      allocate (sw%h_mean_short(n), sw%h_mean_long(n), sw%y_check(n_state, n_check, n), &
                sw%global_error(n), sw%energy_short(n), sw%energy_long(n), &
                sw%energy_final(n), sw%bins(n, nb), sw%drift(n), sw%drift_stderr(n), &
                sw%short_steps(n), sw%short_rhs(n), sw%short_iter(n), sw%short_rejected(n), &
                sw%long_steps(n), sw%long_rhs(n), sw%long_iter(n), sw%long_rejected(n), &
                sw%wall_short(n), sw%wall_long(n), sw%stat(n))
      sw%h_mean_short = nan; sw%h_mean_long = nan; sw%y_check = nan
      sw%global_error = nan; sw%energy_short = nan; sw%energy_long = nan
      sw%energy_final = nan; sw%bins = nan; sw%drift = nan; sw%drift_stderr = nan
      sw%short_steps = 0; sw%short_rhs = 0; sw%short_iter = 0; sw%short_rejected = 0
      sw%long_steps = 0; sw%long_rhs = 0; sw%long_iter = 0; sw%long_rejected = 0
      sw%wall_short = 0.0_dp; sw%wall_long = 0.0_dp; sw%stat = stat_ok
   end subroutine allocate_sweep

   !> Sample steps 1 … n, about `per_decade` per decade, distinct, ending on n.
   pure function sample_steps(n, per_decade) result(steps)
      integer(i8), intent(in) :: n
      integer, intent(in) :: per_decade
      integer(i8), allocatable :: steps(:)
      integer(i8) :: buf(2000), s
      integer :: j, m
      m = 0
      do j = 0, 1999
         s = nint(10.0_dp**(real(j, dp)/real(per_decade, dp)), i8)
         if (s >= n) exit
         if (m > 0) then
            if (s <= buf(m)) cycle
         end if
         m = m + 1
         buf(m) = s
      end do
      m = m + 1
      buf(m) = n
      steps = buf(1:m)
   end function sample_steps

   !> Rough cost of one step with energy monitoring [s] (release build, one core),
   !> from the method registry (`dpend methods`); used only to schedule the longest
   !> jobs first and for the ETA.
   pure real(dp) function cost_per_step(name) result(c)
      character(len=*), intent(in) :: name
      integer :: i
      i = method_index(name)
      c = 2.0e-6_dp
      if (i > 0) c = method_table(i)%cost
   end function cost_per_step

   !> Rough mean step of an adaptive method at tolerance rtol [s] (for the ETA).
   pure real(dp) function adaptive_step_guess(name, rtol) result(h)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: rtol
      if (name == 'dop853') then
         h = 0.05_dp*(rtol/1.0e-9_dp)**(1.0_dp/8.0_dp)
      else
         h = 0.02_dp*(rtol/1.0e-9_dp)**(1.0_dp/5.0_dp)
      end if
   end function adaptive_step_guess

   !> Job order: most expensive first (so the last jobs to finish are short).
   function sort_by_cost(jobs) result(order)
      type(job_t), intent(in) :: jobs(:)
      integer :: order(size(jobs))
      integer :: i, j, tmp
      order = [(i, i=1, size(jobs))]
      ! insertion sort, descending (a few hundred jobs)
      do i = 2, size(jobs)
         tmp = order(i)
         j = i - 1
         do while (j >= 1)
            if (jobs(order(j))%cost >= jobs(tmp)%cost) exit
            order(j + 1) = order(j)
            j = j - 1
         end do
         order(j + 1) = tmp
      end do
   end function sort_by_cost

   ! ================================================================== jobs

   subroutine run_job(cfg, res, job)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(inout) :: res
      type(job_t), intent(in) :: job
      select case (job%kind)
      case (job_sweep)
         call sweep_point(cfg, res%refs(res%sweeps(job%i)%icase), res%sweeps(job%i), job%k)
      case (job_roundoff)
         call roundoff_run(cfg, res%roundoff(job%i), job%k, job%c)
      case (job_tao)
         call tao_run(cfg, res%refs(case_index(cfg, cfg%tao_case)), res%tao(job%i), job%k)
      end select
   end subroutine run_job

   !> A new integrator for point k of the sweep (error control off in mode_step), and
   !> with `model` the model of the sweep's case.
   subroutine make_method(cfg, sw, k, integ, model)
      type(study_config_t), intent(in) :: cfg
      type(sweep_t), intent(in) :: sw
      integer, intent(in) :: k
      class(integrator_t), allocatable, intent(out) :: integ
      class(model_t), allocatable, intent(out), optional :: model
      if (sw%mode == mode_tol) then
         call build_in_turn(cfg, sw%method, method_options_t(rtol=sw%x(k), &
                            atol=cfg%atol_ratio*sw%x(k)), integ, sw%icase, model)
      else
         call build_in_turn(cfg, sw%method, method_options_t(fixed_step=.true.), integ, &
                            sw%icase, model)
      end if
   end subroutine make_method

   !> The method `name` with `options` and, with `ic` and `model`, the model of case ic, for a
   !> job run by one of the study's threads: built by one thread at a time (the
   !> critical section dpend_build), because the factories are not reentrant under
   !> gfortran 12, which keeps the length of a deferred-length character function
   !> result in a static variable (docs/architecture.md, "Threads"). A validated
   !> study names only methods that build.
   subroutine build_in_turn(cfg, name, options, integ, ic, model)
      type(study_config_t), intent(in) :: cfg                      !! configuration
      character(len=*), intent(in) :: name                         !! method name
      type(method_options_t), intent(in) :: options                !! its options
      class(integrator_t), allocatable, intent(out) :: integ       !! the method
      integer, intent(in), optional :: ic                          !! case index (with model)
      class(model_t), allocatable, intent(out), optional :: model  !! case ic's model
      type(error_t), allocatable :: error
      if (present(model) .and. .not. present(ic)) error stop 'internal error: ' &
         //'build_in_turn builds the model from a case index'
      !$omp critical (dpend_build)
      call new_integrator(name, integ, error, options)
      if (present(model)) call case_model(cfg, ic, model)
      !$omp end critical (dpend_build)
      if (allocated(error)) error stop 'internal error: a validated study method: ' &
         //error%message
   end subroutine build_in_turn

   !> Short and long run of point k of sweep sw.
   subroutine sweep_point(cfg, ref, sw, k)
      type(study_config_t), intent(in) :: cfg
      type(reference_t), intent(in) :: ref
      type(sweep_t), intent(inout) :: sw
      integer, intent(in) :: k
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      type(march_t) :: march
      real(dp) :: t, hh, h0, e, e0, es, start, qa(max_dof + 1), qda(max_dof + 1)
      real(dp), allocatable :: y(:), y0(:)
      real(dp) :: bins(size(sw%t_bins))
      integer :: stat, kc, jb, nb, n
      type(fit_t) :: fit
      logical :: works
      associate (cs => cfg%cases(sw%icase))
         call make_method(cfg, sw, k, integ, model)
         n = size(cs%q0)
         ! a damped or driven case: the chain with its works, the energy balance
         works = needs_work(model)
         if (works) then
            block
               class(model_t), allocatable :: chain
               call move_alloc(model, chain)
               call work_model(chain, model)
            end block
            block
               real(dp), allocatable :: q_aug(:), qd_aug(:)
               call augmented_state(model, cs%q0, cs%w0, q_aug, qd_aug)
               y0 = integ%to_internal(model, q_aug, qd_aug)
            end block
         else
            y0 = integ%to_internal(model, cs%q0, cs%w0)
         end if
         e0 = monitored_energy(integ, model, 0.0_dp, y0)
         es = model%energy_scale(e0)
         h0 = merge(sw%x(k), 0.0_dp, sw%mode == mode_step)
         ! ---- short run with monitoring
         y = y0; t = 0.0_dp; hh = h0
         sw%energy_short(k) = 0.0_dp
         stat = stat_ok
         do kc = 1, cfg%n_check
            if (sw%mode == mode_step) hh = h0
            call march%start(integ, t, ref%t(kc), hh)
            do while (.not. march%finished)
               call march%next(integ, model, t, y, hh, stat)
               if (stat /= stat_ok) exit
               sw%energy_short(k) = max(sw%energy_short(k), &
                                        abs(monitored_energy(integ, model, t, y) - e0)/es)
            end do
            if (stat /= stat_ok) exit
            if (works) then   ! (q, W_friction …), (q̇, W_support …)
               call integ%to_physical(model, y, qa(:model%n_dof()), qda(:model%n_dof()), t)
               sw%y_check(1:n, kc, k) = qa(:n)
               sw%y_check(n + 1:2*n, kc, k) = qda(:n)
            else
               call integ%to_physical(model, y, sw%y_check(1:n, kc, k), &
                                      sw%y_check(n + 1:2*n, kc, k))
            end if
         end do
         sw%short_steps(k) = integ%n_steps; sw%short_rhs(k) = integ%n_rhs
         sw%short_iter(k) = integ%n_iter; sw%short_rejected(k) = integ%n_rejected
         sw%stat(k) = stat
         if (stat == stat_ok) then
            sw%global_error(k) = maxval(abs(sw%y_check(:, :, k) - ref%y))
            sw%h_mean_short(k) = cfg%t_short/real(max(integ%n_steps, 1_i8), dp)
         else
            sw%energy_short(k) = ieee_value(1.0_dp, ieee_quiet_nan)
            return
         end if
         ! ---- long run with the energy error in logarithmic bins
         call make_method(cfg, sw, k, integ)
         y = y0; t = 0.0_dp; hh = h0
         nb = size(sw%t_bins)
         bins = -1.0_dp
         jb = 1
         sw%energy_long(k) = 0.0_dp
         e = 0.0_dp
         start = wall_clock()
         call march%start(integ, t, sw%t_long, hh)
         do while (.not. march%finished)
            call march%next(integ, model, t, y, hh, stat)
            if (stat /= stat_ok) exit
            e = abs(monitored_energy(integ, model, t, y) - e0)/es
            do while (jb < nb)
               if (t <= sw%t_bins(jb)) exit
               jb = jb + 1
            end do
            bins(jb) = max(bins(jb), e)
            sw%energy_long(k) = max(sw%energy_long(k), e)
         end do
         sw%wall_long(k) = wall_clock() - start
         sw%energy_final(k) = e
         sw%long_steps(k) = integ%n_steps; sw%long_rhs(k) = integ%n_rhs
         sw%long_iter(k) = integ%n_iter; sw%long_rejected(k) = integ%n_rejected
         sw%h_mean_long(k) = t/real(max(integ%n_steps, 1_i8), dp)
         where (bins < 0.0_dp) bins = ieee_value(1.0_dp, ieee_quiet_nan)
         sw%bins(k, :) = bins
         sw%stat(k) = stat
         if (stat /= stat_ok) return
         fit = drift_exponent(sw%t_bins, bins, sw%t_long*10.0_dp**(-cfg%drift_decades), &
                              sw%t_long)
         if (fit%ok) then
            sw%drift(k) = fit%slope
            sw%drift_stderr(k) = fit%stderr
         end if
      end associate
   end subroutine sweep_point

   !> Wall times of the short runs, on one thread after the parallel phase so that
   !> the runs timed do not compete with each other for the cores.
   subroutine time_short_runs(cfg, res, show)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(inout) :: res
      logical, intent(in) :: show
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      real(dp) :: start
      real(dp), allocatable :: y0(:)
      integer :: s, k, n
      start = wall_clock()
      n = 0
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s), cs => cfg%cases(res%sweeps(s)%icase))
            call case_model(cfg, sw%icase, model)
            do k = 1, size(sw%x)
               if (sw%stat(k) /= stat_ok) cycle
               call make_method(cfg, sw, k, integ)
               y0 = integ%to_internal(model, cs%q0, cs%w0)
               sw%wall_short(k) = time_short_run(integ, model, cfg, res%refs(sw%icase), y0, &
                                                 merge(sw%x(k), 0.0_dp, sw%mode == mode_step), &
                                                 sw%mode)
               n = n + 1
            end do
         end associate
      end do
      if (show) then
         write (error_unit, '(a, i0, a, a, a)') 'dpend study: timed ', n, &
            ' short runs on one thread in ', seconds(wall_clock() - start), ' s'
         flush (error_unit)
      end if
   end subroutine time_short_runs

   !> Wall time of one short run without monitoring [s]: the count of repetitions
   !> doubles until a batch lasts wall_min/5; the time per run is the minimum over
   !> five such batches (robust against preemption on a shared machine).
   real(dp) function time_short_run(integ, model, cfg, ref, y0, h0, mode) result(seconds)
      class(integrator_t), intent(inout) :: integ
      class(model_t), intent(in) :: model
      type(study_config_t), intent(in) :: cfg
      type(reference_t), intent(in) :: ref
      real(dp), intent(in) :: y0(:), h0
      integer, intent(in) :: mode
      type(march_t) :: march
      real(dp) :: y(size(y0)), t, hh, start, elapsed, best
      integer :: reps, r, kc, stat, batch
      real(dp) :: sink
      reps = 1
      best = huge(1.0_dp)
      sink = 0.0_dp
      batch = 0
      do
         start = wall_clock()
         do r = 1, reps
            call integ%clear_step()
            y = y0; t = 0.0_dp; hh = h0
            do kc = 1, cfg%n_check
               if (mode == mode_step) hh = h0
               call march%start(integ, t, ref%t(kc), hh)
               do while (.not. march%finished)
                  call march%next(integ, model, t, y, hh, stat)
                  if (stat /= stat_ok) exit
               end do
            end do
            sink = sink + y(1)
         end do
         elapsed = wall_clock() - start
         if (elapsed >= 0.2_dp*cfg%wall_min .or. reps >= 2**24) then
            best = min(best, elapsed/real(reps, dp))
            batch = batch + 1
            if (batch == 5 .or. cfg%wall_min == 0.0_dp) exit
         else
            reps = 2*reps
         end if
      end do
      seconds = best
      if (.not. ieee_is_finite(sink)) seconds = huge(1.0_dp)   ! keeps the loop alive
   end function time_short_run

   !> One roundoff run: method i, run number r, compensated (c = 1) or plain (2).
   subroutine roundoff_run(cfg, ro, r, c)
      type(study_config_t), intent(in) :: cfg
      type(roundoff_t), intent(inout) :: ro
      integer, intent(in) :: r, c
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      real(dp) :: y(4), t, h, q0(2), es, comp(4), start
      real(qp) :: h0
      integer(i8) :: n
      integer :: stat, j
      ! `plan` makes roundoff jobs only for a model with H in quadruple precision
      ! (`has_hamiltonian_qp`: the double pendulum)
      call build_in_turn(cfg, ro%method, method_options_t(compensated=c == 1), integ, &
                         case_index(cfg, cfg%ro_case), model)
      if (.not. model%has_hamiltonian_qp()) return
      associate (cs => cfg%cases(case_index(cfg, cfg%ro_case)))
         q0 = cs%q0 + cfg%ro_perturb*real(r - 1, dp)*[1.0_dp, -0.7_dp]
         y = integ%to_internal(model, q0, cs%w0)
         h0 = model%hamiltonian_qp(y, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
         es = model%energy_scale(real(h0, dp))
         t = 0.0_dp
         j = 1
         start = wall_clock()
         do n = 1, ro%steps(size(ro%steps))
            h = ro%dt
            call integ%step(model, t, y, h, stat)
            if (stat /= stat_ok) exit
            t = real(n, dp)*ro%dt
            if (n == ro%steps(j)) then
               comp = 0.0_dp
               select type (integ)
               class is (symplectic_t)
                  comp = integ%comp(:4)
               end select
               ro%err(j, r, c) = real((model%hamiltonian_qp(y, comp) - h0)/real(es, qp), dp)
               j = j + 1
            end if
         end do
         ro%wall(r, c) = wall_clock() - start
         ro%stat(r, c) = stat
      end associate
   end subroutine roundoff_run

   !> One Tao run: method i at ω(k) with step tao_dt to tao_t_end.
   subroutine tao_run(cfg, ref, ts, k)
      type(study_config_t), intent(in) :: cfg
      type(reference_t), intent(in) :: ref
      type(tao_sweep_t), intent(inout) :: ts
      integer, intent(in) :: k
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      type(march_t) :: march
      real(dp) :: t, hh, e0, es, e
      real(dp), allocatable :: y(:), yc(:, :)
      integer :: stat
      associate (cs => cfg%cases(case_index(cfg, cfg%tao_case)))
         call build_in_turn(cfg, ts%method, method_options_t(omega=ts%omega(k)), integ, &
                            case_index(cfg, cfg%tao_case), model)
         allocate (yc(2*size(cs%q0), cfg%n_check))
         call checkpoints(integ, model, cs%q0, cs%w0, ref%t, cfg%tao_dt, yc, stat)
         if (stat == stat_ok) ts%global_error(k) = maxval(abs(yc - ref%y))
         call build_in_turn(cfg, ts%method, method_options_t(omega=ts%omega(k)), integ)
         y = integ%to_internal(model, cs%q0, cs%w0)
         e0 = energy_of(integ, model, y)
         es = model%energy_scale(e0)
         t = 0.0_dp
         hh = cfg%tao_dt
         e = 0.0_dp
         ts%energy_max(k) = 0.0_dp
         call march%start(integ, t, cfg%tao_t_end, hh)
         do while (.not. march%finished)
            call march%next(integ, model, t, y, hh, stat)
            if (stat /= stat_ok) exit
            e = abs(energy_of(integ, model, y) - e0)/es
            ts%energy_max(k) = max(ts%energy_max(k), e)
         end do
         ts%energy_final(k) = e
         ts%stat(k) = stat
         if (stat /= stat_ok) then
            ts%energy_max(k) = ieee_value(1.0_dp, ieee_quiet_nan)
            ts%energy_final(k) = ieee_value(1.0_dp, ieee_quiet_nan)
         end if
      end associate
   end subroutine tao_run

   ! ================================================================== fits

   !> Fit orders for every sweep: global error and short-run energy error against
   !> the step (mode_step) or the mean accepted step (mode_tol), the long-run
   !> energy error against the step, and the global error against rtol.
   subroutine fit_sweeps(res)
      type(study_result_t), intent(inout) :: res
      integer :: s
      real(dp) :: gfloor
      do s = 1, size(res%sweeps)
         associate (sw => res%sweeps(s))
            ! a failed check run leaves check_difference = huge: the floor saturates
            ! (10*huge would overflow, a trap in the debug build)
            gfloor = max(global_floor, 10.0_dp*min(res%refs(sw%icase)%check_difference, &
                                                   huge(1.0_dp)/10.0_dp))
            if (sw%mode == mode_step) then
               sw%fit_global = loglog_fit(sw%x, ok_only(sw%global_error, sw%stat), y_min=gfloor)
               sw%fit_energy = loglog_fit(sw%x, ok_only(sw%energy_short, sw%stat), &
                                          y_min=energy_floor)
               sw%fit_energy_long = loglog_fit(sw%x, ok_only(sw%energy_long, sw%stat), &
                                               y_min=long_floor)
            else
               sw%fit_global = loglog_fit(sw%h_mean_short, ok_only(sw%global_error, sw%stat), &
                                          y_min=gfloor)
               sw%fit_energy = loglog_fit(sw%h_mean_short, ok_only(sw%energy_short, sw%stat), &
                                          y_min=energy_floor)
               sw%fit_energy_long = loglog_fit(sw%h_mean_long, ok_only(sw%energy_long, &
                                                                       sw%stat), &
                                               y_min=long_floor)
               sw%fit_tolerance = loglog_fit(sw%x, ok_only(sw%global_error, sw%stat), &
                                             y_min=gfloor)
            end if
         end associate
      end do
   end subroutine fit_sweeps

   !> Values of successful runs, NaN for the others.
   pure function ok_only(v, stat) result(w)
      real(dp), intent(in) :: v(:)
      integer, intent(in) :: stat(:)
      real(dp) :: w(size(v))
      w = v
      where (stat /= stat_ok) w = ieee_value(1.0_dp, ieee_quiet_nan)
   end function ok_only

   !> RMS over the successful roundoff runs and its exponent in t from ro_fit_t_min.
   subroutine fit_roundoff(cfg, res)
      type(study_config_t), intent(in) :: cfg
      type(study_result_t), intent(inout) :: res
      integer :: i, c, j, r, n
      real(dp) :: s2
      do i = 1, size(res%roundoff)
         associate (ro => res%roundoff(i))
            do c = 1, 2
               do j = 1, size(ro%steps)
                  s2 = 0.0_dp
                  n = 0
                  do r = 1, cfg%ro_runs
                     if (ro%stat(r, c) /= stat_ok) cycle
                     if (.not. ieee_is_finite(ro%err(j, r, c))) cycle
                     s2 = s2 + ro%err(j, r, c)**2
                     n = n + 1
                  end do
                  if (n > 0) ro%rms(j, c) = sqrt(s2/real(n, dp))
               end do
               ro%fit(c) = drift_exponent(ro%t, ro%rms(:, c), cfg%ro_fit_t_min, huge(1.0_dp))
            end do
         end associate
      end do
   end subroutine fit_roundoff
end module dpend_study
