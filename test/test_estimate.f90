!> `dpend fit`: reading a measured series and estimating the initial state
!> and the joint damping, against independently known values:
!> - the 40-digit reference table data/reference/release_horizontal.txt (mpmath) read
!>   as measured angles: the fit recovers the initial state q(0) = q̇(0) = 0 (rows
!>   t = 0..5) and the state (q, q̇)(1) of the table (rows t = 1..5) to 1e-8;
!> - the sensitivities of the variational equations (initial state: tangent
!>   propagation; damping: the augmented system) against central differences;
!> - 50 synthetic damped series (N = 1, known q0, q̇0, c, Gaussian noise of known σ,
!>   fixed seed): the reported 95 % intervals contain the true values in at least 90 %
!>   of the sets, for each parameter;
!> - malformed CSV files refused with their line numbers, by the reader and by the
!>   command (exit 2, one line, no output file).
!> Each test prints its measured figures on one line ('    estimate: …').
module test_estimate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_pendulum, only: pendulum_t, pendulum_model
   use dpend_model_factory, only: model_spec, model_spec_t, new_model
   use dpend_estimate, only: set_fitted, fit_problem_t, fit_result_t, fit_series, evaluate_fit, &
                             student_t95, fit_work_t, estimate_fit_work
   use dpend_limits, only: max_fit_work
   use dpend_csv, only: series_t, parse_series, csv_format
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str, to_str
   use test_cli, only: run_command, scratch_dir, read_text
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_estimate
   public :: gaussian   ! also test_fit_params

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_estimate(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('reference_initial_state', test_reference), &
               new_unittest('sensitivities_finite_differences', test_sensitivities), &
               new_unittest('coverage_95', test_coverage), &
               new_unittest('student_t_quantile', test_student), &
               new_unittest('positions_driven_damped', test_positions), &
               new_unittest('csv_refusals', test_csv_refusals), &
               new_unittest('command_refusals', test_command_refusals), &
               new_unittest('work_bound', test_work), &
               new_unittest('csv_spreadsheet_forms', test_csv_forms), &
               new_unittest('command_csv_forms', test_command_csv_forms), &
               new_unittest('command_writes_report', test_command), &
               new_unittest('elastic_spring', test_elastic), &
               new_unittest('elastic_columns', test_elastic_columns)]
   end subroutine collect_estimate

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    estimate: '//text
   end subroutine report

   !> The reference table (t, q1, q2, q̇1, q̇2 at t = 1..5).
   subroutine read_reference(ref, error)
      real(dp), intent(out) :: ref(5, 5)
      type(error_t), allocatable, intent(inout) :: error
      integer :: unit, stat, i
      character(len=256) :: line
      ref = 0.0_dp
      open (newunit=unit, file='data/reference/release_horizontal.txt', status='old', &
            action='read', iostat=stat)
      call check_true(error, stat == 0, 'reference table readable')
      if (allocated(error)) return
      i = 0
      do while (i < 5)
         read (unit, '(a)') line
         if (line(1:1) == '#') cycle
         i = i + 1
         read (line, *) ref(:, i)
      end do
      close (unit)
   end subroutine read_reference

   function reference_problem() result(prob)
      type(fit_problem_t) :: prob
      allocate (prob%model, source=pendulum_model(pendulum_t(m1=1.0_dp, m2=1.0_dp, &
                l1=1.0_dp, l2=1.0_dp, g=9.8_dp)))
      prob%method = 'dop853'
      prob%rtol = 1e-13_dp
      prob%atol = 1e-15_dp
      prob%starts = 25
   end function reference_problem

   !> (a) The table as measured data: rows t = 0 (q = 0, the table's initial state)
   !> and t = 1..5: the fit recovers q(0) = q̇(0) = 0; rows t = 1..5 only: it recovers
   !> the table's (q, q̇)(1). Both to 1e-8.
   subroutine test_reference(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp) :: ref(5, 5), t(6), q(2, 6), err0, err1
      call read_reference(ref, error)
      if (allocated(error)) return
      prob = reference_problem()
      t(1) = 0.0_dp
      q(:, 1) = 0.0_dp
      t(2:6) = ref(1, :)
      q(:, 2:6) = ref(2:3, :)
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      err0 = maxval(abs(res%p))
      call report('reference rows t = 0..5: |state(0) - 0| = '//real_str(err0, 2)// &
                  ', rms '//real_str(res%rms, 2)//' rad, '//to_str(res%iterations)// &
                  ' iterations in '//to_str(res%stages)//' stages, guess q̇ = ('// &
                  real_str(res%guess(3), 3)//', '//real_str(res%guess(4), 3)//')')
      call check(error, res%p, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], 'state(0)', abs=1e-8_dp)
      if (allocated(error)) return
      call fit_series(prob, t(2:6), q(:, 2:6), huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      err1 = maxval(abs(res%p - [ref(2:5, 1)]))
      call report('reference rows t = 1..5: |state(1) - table| = '//real_str(err1, 2)// &
                  ', '//to_str(res%iterations)//' iterations')
      call check(error, res%p, ref(2:5, 1), 'state(1)', abs=1e-8_dp)
   end subroutine test_reference

   !> The Jacobian of the residuals (tangent propagation for the state, the augmented
   !> system for the damping) against central differences of the residuals, for the
   !> damped chain of N = 2 and N = 3 fitted with its damping.
   subroutine test_sensitivities(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      real(dp), allocatable :: p(:), t(:), q(:, :), r(:), rp(:), rm(:), jac(:, :), fd(:, :)
      real(dp) :: d, worst
      integer :: n, k, j, np, i
      worst = 0.0_dp
      do n = 2, 3
         call damping_problem(prob, [(1.0_dp + 0.2_dp*i, i=1, n)], &
                              [(1.0_dp - 0.1_dp*i, i=1, n)], error)
         if (allocated(error)) return
         prob%method = 'dop853'
         prob%rtol = 1e-13_dp
         prob%atol = 1e-15_dp
         k = 21
         t = [(0.1_dp*j, j=0, k - 1)]
         allocate (q(n, k))
         q = 0.0_dp
         np = 3*n
         p = [(-1.2_dp + 0.3_dp*i, i=1, n), (0.5_dp - 0.4_dp*i, i=1, n), &
              (0.05_dp*i, i=1, n)]
         allocate (r(n*k), rp(n*k), rm(n*k), jac(n*k, np), fd(n*k, np))
         call evaluate_fit(prob, p, t, q, k, r, error, jac)
         if (allocated(error)) return
         do j = 1, np
            d = 1e-6_dp*max(1.0_dp, abs(p(j)))
            p(j) = p(j) + d
            call evaluate_fit(prob, p, t, q, k, rp, error)
            if (allocated(error)) return
            p(j) = p(j) - 2.0_dp*d
            call evaluate_fit(prob, p, t, q, k, rm, error)
            if (allocated(error)) return
            p(j) = p(j) + d
            fd(:, j) = (rp - rm)/(2.0_dp*d)
         end do
         worst = max(worst, maxval(abs(jac - fd))/maxval(abs(fd)))
         call check(error, reshape(jac, [n*k*np]), reshape(fd, [n*k*np]), &
                    'N='//to_str(n)//' dr/dp', abs=1e-6_dp*maxval(abs(fd)))
         if (allocated(error)) return
         deallocate (q, r, rp, rm, jac, fd)
      end do
      call report('sensitivities vs central differences (N = 2, 3, state and damping, '// &
                  '2 s): largest difference '//real_str(worst, 2)//' of the largest entry')
   end subroutine test_sensitivities

   !> (b) 50 synthetic series of the damped compound pendulum (N = 1, m = 1 kg,
   !> L = 1 m, g = 9.8), true (q0, q̇0, c) varied per set, 61 samples over 3 s with
   !> Gaussian noise σ = 0.01 rad (Park–Miller generator, fixed seed, Box–Muller): the
   !> 95 % intervals p ± t SE contain the true value in at least 45 of 50 sets, for
   !> each of the three parameters.
   subroutine test_coverage(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      integer, parameter :: n_sets = 50, k = 61
      real(dp), parameter :: sigma = 0.01_dp
      real(dp) :: t(k), q(1, k), truth(3), z
      integer(8) :: seed
      integer :: s, j, hits(3), all_hits
      seed = 20261123_8
      hits = 0
      all_hits = 0
      t = [(0.05_dp*j, j=0, k - 1)]
      call damping_problem(prob, [1.0_dp], [1.0_dp], error)
      if (allocated(error)) return
      prob%method = 'dop853'
      prob%rtol = 1e-10_dp
      prob%atol = 1e-12_dp
      do s = 1, n_sets
         truth = [-pi/2 + 0.8_dp + 0.01_dp*s, 0.5_dp - 0.02_dp*s, 0.05_dp + 0.002_dp*s]
         call simulate_chain(truth, t, q, error)
         if (allocated(error)) return
         do j = 1, k
            call gaussian(seed, z)
            q(1, j) = q(1, j) + sigma*z
         end do
         call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
         if (allocated(error)) then
            error%message = 'set '//to_str(s)//': '//error%message
            return
         end if
         do j = 1, 3
            if (abs(res%p(j) - truth(j)) <= res%t95*res%se(j)) hits(j) = hits(j) + 1
         end do
         if (all(abs(res%p - truth) <= res%t95*res%se)) all_hits = all_hits + 1
      end do
      call report('coverage of the 95 % intervals over 50 damped sets (N = 1, sigma 0.01 '// &
                  'rad): q0 '//to_str(hits(1))//'/50, qdot0 '//to_str(hits(2))// &
                  '/50, c '//to_str(hits(3))//'/50, all three '//to_str(all_hits)//'/50')
      do j = 1, 3
         call check_true(error, hits(j) >= 45, 'coverage of parameter '//to_str(j)//': '// &
                         to_str(hits(j))//'/50 below 90 %')
      end do
   end subroutine test_coverage

   !> Positions of the link ends (cm in the file) of a damped chain (N = 2, unequal
   !> links) on a moving support, exact (dop853 at rtol 1e-12): the fit of the state
   !> and the damping recovers them to 1e-7.
   subroutine test_positions(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      type(series_t) :: s
      type(error_t), allocatable :: err
      integer, parameter :: k = 101
      real(dp) :: truth(6), y(4), tt, h, ra(2), va(2), aa(2), pos(2), xy(4, k), t(k)
      character(len=:), allocatable :: text
      character(len=160) :: buf
      integer :: j, i, stat
      truth = [-1.2_dp, -0.6_dp, 0.8_dp, -0.5_dp, 0.04_dp, 0.02_dp]
      chain = chain_model([1.0_dp, 0.5_dp], [1.0_dp, 0.8_dp], 9.8_dp, error, &
                          damping=truth(5:6), amplitude=[0.0_dp, 0.01_dp], frequency=5.0_dp, &
                          phase=[0.0_dp, 0.3_dp])
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      if (allocated(error)) return
      y = truth(1:4)
      tt = 0.0_dp
      h = 1e-3_dp
      text = 't [s],x1 [cm],y1 [cm],x2 [cm],y2 [cm]'//achar(10)
      do j = 1, k
         t(j) = 0.02_dp*(j - 1)
         if (j > 1) call advance_to(integ, chain, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok .or. j == 1, 'synthetic run')
         if (allocated(error)) return
         call chain%support(t(j), ra, va, aa)
         pos = ra
         do i = 1, 2
            pos = pos + chain%l(i)*[cos(y(i)), sin(y(i))]
            xy(2*i - 1:2*i, j) = pos
         end do
         write (buf, '(f0.2, 4(",", es24.16))') t(j), 100.0_dp*xy(:, j)
         text = text//trim(buf)//achar(10)
      end do
      call parse_series(text, s, err)
      call check_true(error, .not. allocated(err), 'positions file accepted')
      if (allocated(error)) return
      call check_true(error, s%positions .and. s%n == 2 .and. s%n_obs == 4, 'positions read')
      call check(error, s%q(:, k), xy(:, k), 'cm -> m', rel=1e-15_dp)
      if (allocated(error)) return
      call damping_problem(prob, chain%m, chain%l, error, [0.0_dp, 0.01_dp], 5.0_dp, &
                           [0.0_dp, 0.3_dp])
      if (allocated(error)) return
      prob%positions = .true.
      prob%sup_a = [0.0_dp, 0.01_dp]
      prob%sup_w = 5.0_dp
      prob%sup_phi = [0.0_dp, 0.3_dp]
      prob%method = 'dop853'
      prob%rtol = 1e-12_dp
      prob%atol = 1e-14_dp
      call fit_series(prob, s%t, s%q, huge(1.0_dp), 0.01_dp, res, error)
      if (allocated(error)) return
      call report('positions (cm) of a damped chain on a moving support, 2 s: |p - truth| = ' &
                  //real_str(maxval(abs(res%p - truth)), 2)//', rms '//real_str(res%rms, 2) &
                  //' m, '//to_str(res%iterations)//' iterations')
      call check(error, res%p, truth, 'state and damping', abs=1e-7_dp)
   end subroutine test_positions

   !> The elastic pendulum (m = 1 kg, g = 9.8 m/s²) sampled in (r, φ) every 0.05 s
   !> over 3 s from a run of known (r0, φ0, ṙ0, φ̇0, k, l0) (dop853 at rtol 1e-12, an
   !> integration independent of the fit's), fitted with k and l0 from the guess
   !> k = 35 N/m, l0 = 1.1 m: noise-free, the fit recovers every value to 1e-6; with
   !> Gaussian noise σ = 0.002 (m and rad), over 20 sets the 95 % intervals contain the
   !> true value in at least 16 of 20 for each parameter.
   subroutine test_elastic(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      integer, parameter :: k = 61, n_sets = 20
      real(dp), parameter :: truth(6) = [1.2_dp, -1.0_dp, 0.3_dp, 0.5_dp, 40.0_dp, 1.0_dp]
      real(dp), parameter :: sigma = 0.002_dp
      real(dp) :: t(k), q(2, k), qn(2, k), z
      integer(8) :: seed
      integer :: j, s, hits(6)
      t = [(0.05_dp*j, j=0, k - 1)]
      call simulate_elastic(truth, t, q, error)
      if (allocated(error)) return
      prob%spec = model_spec('elastic')
      call prob%spec%set('k', [35.0_dp])
      call prob%spec%set('l0', [1.1_dp])
      call set_fitted(prob, [character(len=2) :: 'k', 'l0'], error)
      if (allocated(error)) return
      call check_true(error, size(prob%theta0) == 2, 'two fitted components')
      if (allocated(error)) return
      call check(error, prob%theta0, [35.0_dp, 1.1_dp], 'guess from the spec', rel=0.0_dp)
      if (allocated(error)) return
      prob%angular = [.false., .true.]
      prob%hold_period = 2.0_dp*pi*sqrt((1.1_dp + 9.8_dp/35.0_dp)/9.8_dp)
      prob%method = 'dop853'
      prob%rtol = 1e-12_dp
      prob%atol = 1e-14_dp
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call report('elastic, noise-free, 3 s: |p - truth| = '// &
                  real_str(maxval(abs(res%p - truth)), 2)//', '//to_str(res%iterations)// &
                  ' iterations')
      call check(error, res%p, truth, 'r0, phi0, rdot0, phidot0, k, l0', abs=1e-6_dp)
      if (allocated(error)) return
      prob%rtol = 1e-10_dp
      prob%atol = 1e-12_dp
      seed = 20261127_8
      hits = 0
      do s = 1, n_sets
         do j = 1, k
            call gaussian(seed, z)
            qn(1, j) = q(1, j) + sigma*z
            call gaussian(seed, z)
            qn(2, j) = q(2, j) + sigma*z
         end do
         call fit_series(prob, t, qn, huge(1.0_dp), 0.1_dp, res, error)
         if (allocated(error)) then
            error%message = 'set '//to_str(s)//': '//error%message
            return
         end if
         where (abs(res%p - truth) <= res%t95*res%se) hits = hits + 1
      end do
      call report('elastic, sigma 0.002, 20 sets: 95 % intervals containing the truth: '// &
                  to_str(hits(1))//', '//to_str(hits(2))//', '//to_str(hits(3))//', '// &
                  to_str(hits(4))//', k '//to_str(hits(5))//', l0 '//to_str(hits(6)))
      do j = 1, 6
         call check_true(error, hits(j) >= 16, 'coverage of parameter '//to_str(j)//': '// &
                         to_str(hits(j))//'/20')
         if (allocated(error)) return
      end do
   end subroutine test_elastic

   !> (r, φ) of the elastic pendulum (m = 1 kg, g = 9.8) from truth = (r0, φ0, ṙ0,
   !> φ̇0, k, l0) at times t, by dop853 at rtol 1e-12.
   subroutine simulate_elastic(truth, t, q, error)
      real(dp), intent(in) :: truth(6), t(:)
      real(dp), intent(out) :: q(:, :)
      type(error_t), allocatable, intent(inout) :: error
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      real(dp) :: tt, y(4), h
      integer :: j, stat
      spec = model_spec('elastic')
      call spec%set('k', truth(5:5))
      call spec%set('l0', truth(6:6))
      call new_model(spec, model, error)
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      if (allocated(error)) return
      y = truth(1:4)
      tt = t(1)
      h = 1e-3_dp
      q(:, 1) = y(1:2)
      do j = 2, size(t)
         call advance_to(integ, model, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok, 'synthetic run')
         if (allocated(error)) return
         q(:, j) = y(1:2)
      end do
   end subroutine simulate_elastic

   !> The reader takes a model's coordinates as columns (r [m], phi [rad]) and refuses
   !> a missing one, a wrong unit, and theta columns (the pendulum's).
   subroutine test_elastic_columns(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: lf = achar(10)
      character(len=3), parameter :: names(2) = ['r  ', 'phi'], units(2) = ['m  ', 'rad']
      type(series_t) :: s
      type(error_t), allocatable :: err
      call parse_series('t [s],phi [rad],r [m]'//lf//'0,-1,1.2'//lf//'0.1,-1.1,1.3'//lf, s, &
                        err, names, units)
      call check_true(error, .not. allocated(err), 'r, phi accepted')
      if (allocated(error)) return
      call check(error, s%q(:, 2), [1.3_dp, -1.1_dp], 'columns in the model''s order', &
                 rel=0.0_dp)
      if (allocated(error)) return
      call parse_series('t,r'//lf//'0,1'//lf, s, err, names, units)
      call check_true(error, allocated(err), 'phi missing refused')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'missing column phi') > 0, err%message)
      if (allocated(error)) return
      call parse_series('t,r [cm],phi'//lf//'0,1,2'//lf, s, err, names, units)
      call check_true(error, allocated(err), 'unit refused')
      if (allocated(error)) return
      call check_true(error, index(err%message, "accepted: [m] or none") > 0, err%message)
      if (allocated(error)) return
      call parse_series('t,theta1,theta2'//lf//'0,1,2'//lf, s, err, names, units)
      call check_true(error, allocated(err), 'theta columns refused for the model')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'no columns r [m], phi [rad]') > 0, &
                      err%message)
   end subroutine test_elastic_columns

   !> A fit of the state and the joint damping (first guess 0) of the chain of these
   !> masses and lengths (g = 9.8 m/s²), the support moving as given; the damping
   !> held while the window is shorter than 2 pi sqrt(sum l / g), as in dpend fit.
   subroutine damping_problem(prob, m, l, error, amplitude, frequency, phase)
      type(fit_problem_t), intent(out) :: prob
      real(dp), intent(in) :: m(:), l(:)
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: amplitude(2), frequency, phase(2)
      prob%spec = model_spec('pendulum')
      call prob%spec%set('links', [real(size(m), dp)])
      call prob%spec%set('m', m)
      call prob%spec%set('l', l)
      call prob%spec%set('g', [9.8_dp])
      if (present(amplitude)) call prob%spec%set('support_amplitude', amplitude)
      if (present(frequency)) call prob%spec%set('support_frequency', [frequency])
      if (present(phase)) call prob%spec%set('support_phase', phase)
      call set_fitted(prob, [character(len=8) :: 'damping'], error)
      prob%hold_period = 2.0_dp*pi*sqrt(sum(l)/9.8_dp)
      prob%l = l
   end subroutine damping_problem

   !> t_(0.975, ν) against tabulated values (R's qt(0.975, ν), 10 digits).
   subroutine test_student(error)
      type(error_t), allocatable, intent(out) :: error
      call check(error, student_t95(1), 12.70620474_dp, 't(1)', rel=1e-9_dp)
      call check(error, student_t95(8), 2.306004135_dp, 't(8)', rel=1e-9_dp)
      call check(error, student_t95(9), 2.262157163_dp, 't(9)', rel=1e-5_dp)
      call check(error, student_t95(10), 2.228138852_dp, 't(10)', rel=1e-5_dp)
      call check(error, student_t95(30), 2.042272456_dp, 't(30)', rel=1e-6_dp)
      call check(error, student_t95(1000), 1.962339081_dp, 't(1000)', rel=1e-8_dp)
   end subroutine test_student

   !> Angles of the damped compound pendulum (q0, q̇0, c) = truth at times t, by
   !> dop853 at rtol 1e-12 (an integration independent of the fit's).
   subroutine simulate_chain(truth, t, q, error)
      real(dp), intent(in) :: truth(3), t(:)
      real(dp), intent(out) :: q(:, :)
      type(error_t), allocatable, intent(inout) :: error
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: tt, y(2), h
      integer :: j, stat
      chain = chain_model([1.0_dp], [1.0_dp], 9.8_dp, error, damping=[truth(3)])
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      if (allocated(error)) return
      y = truth(1:2)
      tt = t(1)
      h = 1e-3_dp
      q(1, 1) = y(1)
      do j = 2, size(t)
         call advance_to(integ, chain, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok, 'synthetic run')
         if (allocated(error)) return
         q(1, j) = y(1)
      end do
   end subroutine simulate_chain

   !> A standard normal deviate (Box–Muller on the Park–Miller minimal standard).
   subroutine gaussian(seed, z)
      integer(8), intent(inout) :: seed
      real(dp), intent(out) :: z
      real(dp) :: u1, u2
      seed = mod(16807_8*seed, 2147483647_8)
      u1 = real(seed, dp)/2147483647.0_dp
      seed = mod(16807_8*seed, 2147483647_8)
      u2 = real(seed, dp)/2147483647.0_dp
      z = sqrt(-2.0_dp*log(u1))*cos(2.0_dp*pi*u2)
   end subroutine gaussian

   !> (c) Malformed series refused by the reader, the message naming the line.
   subroutine test_csv_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: lf = achar(10)
      type(series_t) :: s
      type(error_t), allocatable :: err
      call csv_refused(error, &
                       't,theta1'//lf//'0,0.1'//lf//'0.1,abc'//lf, 'line 3, column theta1: ' &
                       //"'abc' is not a number")
      call csv_refused(error, &
                       't,theta1'//lf//'0,0.1'//lf//'0.1,nan'//lf, 'line 3, column theta1: ' &
                       //"'nan' is not finite")
      call csv_refused(error, 't,theta1'//lf//'0,0.1'//lf//'0.1,Inf'//lf, "'Inf' is not finite")
      call csv_refused(error, &
                       '# a comment'//lf//'t,theta1,theta2'//lf//'0,0.1,0.2'//lf//'0.1,0.2'//lf, &
                       'line 4: 2 fields, the header has 3')
      call csv_refused(error, 't,theta1'//lf//'0,0.1'//lf//'0.2,0.1'//lf//'0.2,0.3'//lf, &
                       'line 4: t = 0.2 s is not after t = 0.2 s of line 3')
      call csv_refused(error, 't,theta1'//lf//'0,0.1'//lf//'0.2,0.1'//lf//lf//'0.1,0.3'//lf, &
                       'line 5: t = 0.1 s is not after')
      call csv_refused(error, 'time,theta1'//lf//'0,0.1'//lf, "line 1 (header): no column 't'")
      call csv_refused(error, 't,z1'//lf//'0,0.1'//lf, 'line 1 (header): no angle columns')
      call csv_refused(error, 't,theta1,theta3'//lf//'0,0.1,0.2'//lf, 'missing column theta2')
      call csv_refused(error, 't,theta1,q2'//lf//'0,0.1,0.2'//lf, "column 'q2' mixes theta and q")
      call csv_refused(error, 't [ms],theta1'//lf//'0,0.1'//lf, "column 't' has the unit '[ms]'")
      call csv_refused(error, 't,theta1'//lf, 'has no data rows')
      call csv_refused(error, '# only a comment'//lf, 'has no header line')
      call csv_refused(error, 't,x1,y1,x2'//lf//'0,1,0,2'//lf, 'missing column y2')
      call csv_refused(error, 't,x1 [in],y1'//lf//'0,1,0'//lf, "column 'x1' has the unit '[in]'")
      call csv_refused(error, 't,x1,y1'//lf//'0,1,0'//lf//'1,1,zz'//lf, "line 3, column y1: 'zz'")
      ! accepted: CRLF, blanks, units, comments, q columns, ignored columns
      call parse_series('# c'//lf//' t [s] , q1 [rad], qdot1 '//achar(13)//lf// &
                        '0, -1.5, 9'//achar(13)//lf//'0.5,-1.4,x'//lf, s, err)
      call check_true(error, .not. allocated(err), 'accepted file')
      if (allocated(error)) return
      call check_true(error, s%n == 1 .and. s%k == 2 .and. all(s%line == [3, 4]) .and. &
                      .not. s%theta, 'series shape')
      call check(error, s%q(1, :), [-1.5_dp, -1.4_dp], 'q', abs=0.0_dp)
      call parse_series('t,theta2,theta1'//lf//'1,0.5,0.25'//lf, s, err)
      call check_true(error, .not. allocated(err) .and. s%theta, 'theta columns accepted')
      call check(error, s%q(:, 1), [0.25_dp - pi/2, 0.5_dp - pi/2], 'theta -> q', &
                 abs=1e-15_dp)
   end subroutine test_csv_refusals

   !> The command refuses bad files and too few samples: exit 2, one line, no output.
   subroutine test_command_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('fitbad')
      call write_file(dir//'/bad.csv', 't,theta1,theta2'//achar(10)//'0,0,0'//achar(10)// &
                      '0.1,0.1,oops')
      call expect_refused(dir//'/bad.csv', '', "line 3, column theta2: 'oops' is not a number")
      call write_file(dir//'/few.csv', 't,theta1'//achar(10)//'0,0'//achar(10)//'0.1,0.1')
      call expect_refused(dir//'/few.csv', '', '2 samples in the fit window give 2 residuals')
      call write_file(dir//'/ok.csv', 't,theta1'//achar(10)//'0,0'//achar(10)//'0.1,0.1'// &
                      achar(10)//'0.2,0.1'//achar(10)//'0.3,0.1')
      call expect_refused(dir//'/ok.csv', '--links 2', 'links')
      call expect_refused(dir//'/ok.csv', '--fit-window -1', 'invalid fit-window')
      call expect_refused(dir//'/ok.csv', '--fit-window 0', '1 samples in the fit window')
      call expect_refused(dir//'/ok.csv', '--starts 0', 'invalid starts')
      call expect_refused(dir//'/ok.csv', '--horizon-tolerance -1', 'horizon-tolerance')
      call expect_refused(dir//'/ok.csv', '--method leapfrog', 'method')
      call expect_refused(dir//'/ok.csv', '--fit-window 1e300', &
                          'invalid fit-window: 1e300 s is outside [-1e9, 1e9]')
      ! four samples 1e8 s apart, refused before any work
      call write_file(dir//'/far.csv', 't,theta1'//achar(10)//'0,0'//achar(10)//'1e8,0.1'// &
                      achar(10)//'2e8,0.1'//achar(10)//'3e8,0.1')
      call expect_refused(dir//'/far.csv', '', 'invalid fit work: up to ')
      call expect_refused(dir//'/missing.csv', '', 'no such file')
      call expect_refused(dir, '', 'is a directory')
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine expect_refused(file, options, needle)
         character(len=*), intent(in) :: file, options, needle
         integer :: stat, n
         logical :: exists
         character(len=:), allocatable :: text
         if (allocated(error)) return
         stat = run_command(dir, 'fit '//file//' --output '//dir//'/out.h5 '//options)
         call read_text(dir//'/stderr', text, n)
         inquire (file=dir//'/out.h5', exist=exists)
         call check_true(error, stat == 2 .and. n == 1 .and. index(text, needle) > 0 .and. &
                         .not. exists, '[fit '//options//'] exit 2, one line naming "'// &
                         needle//'", no output; got '//to_str(stat)//': '//text)
      end subroutine expect_refused
   end subroutine test_command_refusals

   !> The command on a small damped series: exit 0, the report printed, the HDF5 file
   !> with the estimates, standard errors, correlations, residuals and the horizon.
   subroutine test_command(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: stat, n
      dir = scratch_dir('fitrun')
      stat = run_command(dir, 'fit data/fit_example.csv --fit-damping --fit-window 4 ' &
                         //'--output '//dir//'/fit.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'fit exits 0; stdout: '//text)
      if (allocated(error)) return
      call check_true(error, index(text, 'standard error') > 0 .and. &
                      index(text, 'horizon') > 0 .and. index(text, 'correlation') > 0, &
                      'report printed: '//text)
      stat = run_command(dir, 'export '//dir//'/fit.h5 --list')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, '/fit/estimate') > 0 .and. &
                      index(text, '/fit/standard_error') > 0 .and. &
                      index(text, '/fit/correlation') > 0 .and. &
                      index(text, '/fit/residual') > 0, 'datasets listed: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_command

   !> The work bound. rk4 with dt = 0.01 s over 11 samples 0.1 s apart: the
   !> probe measures exactly 100 steps per second, one integration over the window
   !> takes 100 steps plus one per sample interval (110), and the continuation from 3
   !> samples growing by max(1, k/4) has the 8 stages 3, 4, 5, 6, 7, 8, 10, 11
   !> (2 × 200 + 31 integrations each, one more between stages, 2 at the end).
   !> Samples 1e8 s apart are beyond `max_fit_work`. A fit given a smaller work limit
   !> than it needs stops with an error naming the limit; with the default it succeeds.
   subroutine test_work(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(fit_problem_t) :: prob
      type(fit_work_t) :: work
      type(fit_result_t) :: res
      type(chain_t) :: chain
      real(dp) :: t(11), q(1, 11)
      integer :: j
      chain = chain_model([1.0_dp], [1.0_dp], 9.8_dp, error)
      if (allocated(error)) return
      allocate (prob%model, source=chain)
      prob%method = 'rk4'
      prob%dt = 0.01_dp
      do j = 1, 11
         t(j) = 0.1_dp*real(j - 1, dp)
         q(1, j) = -pi/2 + 0.1_dp*cos(sqrt(9.8_dp)*t(j))
      end do
      call estimate_fit_work(prob, t, q, huge(1.0_dp), work, error)
      if (allocated(error)) return
      call report('rk4 dt 0.01 s over 1 s: '//real_str(work%rate)//' steps/s, '// &
                  real_str(work%steps)//' steps, '//to_str(work%stages)//' stages, '// &
                  real_str(work%evaluations)//' integrations, work '//real_str(work%work, 3))
      call check(error, work%rate, 100.0_dp, 'probe rate', rel=1e-12_dp)
      if (allocated(error)) return
      call check(error, work%steps, 110.0_dp, 'steps over the window', rel=1e-12_dp)
      if (allocated(error)) return
      call check_true(error, work%stages == 8, 'stages: '//to_str(work%stages))
      if (allocated(error)) return
      call check(error, work%evaluations, 8.0_dp*431.0_dp + 7.0_dp + 2.0_dp, &
                 'integrations', abs=0.0_dp)
      if (allocated(error)) return
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, err)
      call check_true(error, .not. allocated(err), 'fit within the default limit')
      if (allocated(error)) return
      prob%work_limit = 500.0_dp
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, err)
      call check_true(error, allocated(err), 'fit beyond its work limit refused')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'work limit') > 0 .and. &
                      index(err%message, 'at most 500') > 0, 'message: '//err%message)
      if (allocated(error)) return
      ! the reproducer: 4 samples 1e8 s apart, dop853
      prob%method = 'dop853'
      prob%rtol = 1e-10_dp
      prob%atol = 1e-12_dp
      prob%dt = 1e-3_dp
      prob%work_limit = max_fit_work
      call estimate_fit_work(prob, [0.0_dp, 1e8_dp, 2e8_dp, 3e8_dp], q(:, :4), &
                             huge(1.0_dp), work, error)
      if (allocated(error)) return
      call report('samples 1e8 s apart: work '//real_str(work%work, 3))
      call check_true(error, work%work > max_fit_work, 'beyond max_fit_work')
   end subroutine test_work

   !> CSV as spreadsheets write it: a UTF-8 BOM, quoted names and fields,
   !> ';' or tab separators, CRLF, are read into exactly the series of the plain comma
   !> file (abs 0), and say what they detected; a broken header is refused naming the
   !> real cause, with control characters escaped.
   subroutine test_csv_forms(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: lf = achar(10), tab = achar(9), cr = achar(13)
      character(len=*), parameter :: bom = char(239)//char(187)//char(191)
      type(series_t) :: plain
      type(error_t), allocatable :: err
      call parse_series('t,theta1,theta2'//lf//'0,0.1,0.2'//lf//'0.5,-0.25,1e-3'//lf, plain, &
                        err)
      call check_true(error, .not. allocated(err) .and. csv_format(plain) == '', 'plain file')
      if (allocated(error)) return
      call same(bom//'t,theta1,theta2'//lf//'0,0.1,0.2'//lf//'0.5,-0.25,1e-3'//lf, &
                'BOM removed')
      call same('"t","theta1","theta2"'//lf//'0,0.1,0.2'//lf//'0.5,-0.25,1e-3'//lf, &
                'quoted names')
      call same('t'//tab//'theta1'//tab//'theta2'//lf//'0'//tab//'0.1'//tab//'0.2'//lf// &
                '0.5'//tab//'-0.25'//tab//'1e-3'//lf, 'separator tab')
      call same('t;theta1;theta2'//lf//'0;0.1;0.2'//lf//'0.5;-0.25;1e-3'//lf, &
                "separator ';'")
      call same(bom//'"t [s]";"theta1 [rad]"; "theta2"'//cr//lf//'# comment'//cr//lf// &
                '0;"0.1";0.2'//cr//lf//'0.5 ; -0.25;"1e-3"'//cr//lf, &
                "separator ';', BOM removed, quoted names")
      call same('"t","theta1","the ""other""","theta2"'//lf//'0,0.1,"a,b",0.2'//lf// &
                '0.5,-0.25,x,1e-3'//lf, 'quoted names')
      call csv_refused(error, 't theta1'//lf//'0 0.1'//lf, &
                       "line 1 (header): 1 field ('t theta1'); separators tried: , ; tab")
      call csv_refused(error, &
                       bom//'time;theta1'//lf//'0;0.1'//lf, "line 1 (header): no column 't' " &
                       //"among the 2 fields 'time', 'theta1' (separator ';'")
      call csv_refused(error, &
                       '"t,theta1'//lf//'0,0.1'//lf, 'line 1 (header): the quote opened at ' &
                       //'character 1 is not closed')
      call csv_refused(error, '"t"x,theta1'//lf//'0,0.1'//lf, 'text after the quote closed at ' &
                       //'character 3')
      call csv_refused(error, char(255)//char(254)//'t'//achar(0), 'is UTF-16 text')
      call csv_refused(error, &
                       't;theta1'//lf//'0;0,1'//lf, "line 2, column theta1: '0,1' is not a " &
                       //'number (a decimal comma?')
      call csv_refused(error, 't,theta1'//lf//'0,"0.'//tab//'1"'//lf, &
                       "line 2, column theta1: '0.\t1' is not a number")
      call csv_refused(error, 't,theta1 [r'//lf//'ad]'//lf//'0,1'//lf, "unit '[r'")
      call csv_refused(error, 't,theta1 [r'//achar(1)//'ad]'//lf//'0,1'//lf, "unit '[r\x01ad]'")
   contains
      subroutine same(text, format)
         character(len=*), intent(in) :: text, format
         type(series_t) :: ss
         type(error_t), allocatable :: e
         if (allocated(error)) return
         call parse_series(text, ss, e)
         if (allocated(e)) then
            call check_true(error, .false., 'accepted ('//format//'): '//e%message)
            return
         end if
         call check_true(error, csv_format(ss) == format .and. ss%k == plain%k .and. &
                         ss%n == plain%n .and. all(ss%line == plain%line .or. &
                         index(text, '# comment') > 0), 'format "'//csv_format(ss)// &
                         '" is "'//format//'"')
         if (allocated(error)) return
         call check(error, ss%t, plain%t, 't ('//format//')', abs=0.0_dp)
         if (allocated(error)) return
         call check(error, reshape(ss%q, [size(ss%q)]), reshape(plain%q, [size(plain%q)]), &
                    'q ('//format//')', abs=0.0_dp)
      end subroutine same
   end subroutine test_csv_forms

   !> The command on the same samples as a comma file and as a spreadsheet's file (BOM,
   !> ';', quoted names, CRLF): the same report, but for the file's name and the line
   !> stating the format.
   subroutine test_command_csv_forms(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: lf = achar(10), crlf = achar(13)//achar(10)
      character(len=:), allocatable :: dir, plain, sheet, fmt
      integer :: stat, n
      dir = scratch_dir('fitforms')
      call write_bytes(dir//'/plain.csv', 't,theta1'//lf//'0,0.1'//lf//'0.1,0.09'//lf// &
                       '0.2,0.06'//lf//'0.3,0.02'//lf//'0.4,-0.03'//lf)
      call write_bytes(dir//'/sheet.csv', char(239)//char(187)//char(191)// &
                       '"t";"theta1"'//crlf//'0;0.1'//crlf//'0.1;0.09'//crlf//'0.2;0.06'// &
                       crlf//'0.3;0.02'//crlf//'0.4;-0.03'//crlf)
      stat = run_command(dir, 'fit '//dir//'/plain.csv --output '//dir//'/plain.h5')
      call read_text(dir//'/stdout', plain, n)
      call check_true(error, stat == 0, 'plain file fitted: '//plain)
      if (allocated(error)) return
      stat = run_command(dir, 'fit '//dir//'/sheet.csv --output '//dir//'/sheet.h5')
      call read_text(dir//'/stdout', sheet, n)
      call check_true(error, stat == 0, 'spreadsheet file fitted: '//sheet)
      if (allocated(error)) return
      fmt = "  csv: separator ';', BOM removed, quoted names"//lf
      call check_true(error, index(sheet, fmt) > 0, 'format stated: '//sheet)
      if (allocated(error)) return
      plain = plain(index(plain, lf) + 1:)
      sheet = sheet(index(sheet, lf) + 1:)
      sheet = sheet(:index(sheet, fmt) - 1)//sheet(index(sheet, fmt) + len(fmt):)
      plain = plain(:index(plain, "wrote '") - 1)
      sheet = sheet(:index(sheet, "wrote '") - 1)
      call check_true(error, plain == sheet, 'same report:'//lf//plain//lf//'and'//lf//sheet)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_command_csv_forms

   !> `text` as a series file is refused, the one-line message containing `needle` and
   !> only printable ASCII.
   subroutine csv_refused(error, text, needle)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: text, needle
      type(series_t) :: ss
      type(error_t), allocatable :: e
      integer :: i
      if (allocated(error)) return
      call parse_series(text, ss, e)
      call check_true(error, allocated(e), 'refused: '//needle)
      if (allocated(error)) return
      call check_true(error, index(e%message, needle) > 0, 'message "'//e%message// &
                      '" names "'//needle//'"')
      do i = 1, len(e%message)
         if (allocated(error)) return
         call check_true(error, iachar(e%message(i:i)) >= 32 .and. &
                         iachar(e%message(i:i)) < 127, 'message printable: '//needle)
      end do
   end subroutine csv_refused

   !> Write the bytes of `text` (no record marker, no added new line).
   subroutine write_bytes(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write', access='stream', &
            form='unformatted')
      write (unit) text
      close (unit)
   end subroutine write_bytes

   subroutine write_file(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)') text
      close (unit)
   end subroutine write_file
end module test_estimate
