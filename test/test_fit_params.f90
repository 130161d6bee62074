!> `dpend fit` of physical parameters, against independently known values:
!> - the central-difference sensitivities (a model without `parameter_rates` for the
!>   parameter) against the models' analytic rates (the chain's damping, the elastic
!>   pendulum's k and l0), and those of l2 and g against central differences of the
!>   residuals;
!> - the reference case: series simulated in-process (dop853, rtol 1e-12, a run
!>   independent of the fit's) with m2 = 0.5 kg and l2 = 0.7 m: noise-free, the fit of
!>   m2, l2 from the defaults recovers them to 1e-7; with seeded Gaussian noise
!>   σ = 0.01 rad the 95 % intervals cover the truth and the scatter of the estimates
!>   matches their standard errors;
!> - the file data/fit_mass_length.csv (the same system, noise 0.01 rad): the default
!>   fit's RMS residual is above 3 times the noise estimated from the data (which is
!>   0.01 within 20 %) and the parameters ranked as suspects include l2; the fit of m2,
!>   l2 covers the truth;
!> - sets the data cannot determine refused: every mass (the mass scale), m with k for
!>   the elastic pendulum, a parameter with no effect (support phase without motion),
!>   the lengths with g (only g/l matters);
!> - CSV columns in degrees converted by π/180;
!> - the coverage fit: a two-link pendulum with bobs, d2, I2, g, c1, c2 from
!>   angles (noise-free to 1e-7; the coverage of the 95 % intervals over seeded noisy
!>   series, 50 with scripts/check/fit_coverage.sh);
!> - a fitted length placing observed tip positions (Jacobian against differences of
!>   the residuals), point masses whose fitted length moves the mass, the sets bodies
!>   leave undetermined, and a wrong fixed length's misfit warning.
module test_fit_params
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_model_factory, only: model_spec, new_model, model_spec_t, spec_values, &
                                  derived_default
   use dpend_estimate, only: set_fitted, fit_problem_t, fit_result_t, fit_series, &
                             evaluate_fit, noise_estimate, misfit_suspects, suspect_t, &
                             misfit_factor
   use dpend_csv, only: series_t, parse_series, read_series
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str, to_str
   use dpend_model, only: model_t
   use testing, only: unittest_t, new_unittest, check, check_true
   use test_estimate, only: gaussian
   implicit none
   private
   public :: collect_fit_params

   real(dp), parameter :: pi = acos(-1.0_dp)
   !> the reference pendulum: m = (1, 0.5) kg, l = (1, 0.7) m, released at rest from
   !> theta = (1.0, 0.6) rad; 300 samples over 5.98 s
   real(dp), parameter :: true_m(2) = [1.0_dp, 0.5_dp], true_l(2) = [1.0_dp, 0.7_dp]
   real(dp), parameter :: theta0(2) = [1.0_dp, 0.6_dp]
   integer, parameter :: samples = 300

contains

   subroutine collect_fit_params(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('generic_rates_analytic', test_generic_rates), &
               new_unittest('generic_rates_differences', test_generic_differences), &
               new_unittest('recover_mass_length', test_recover), &
               new_unittest('data_file_misfit', test_data_file), &
               new_unittest('undetermined_refused', test_undetermined), &
               new_unittest('csv_degrees', test_degrees), &
               new_unittest('body_values_follow_rods', test_body_values), &
               new_unittest('bob_coverage', test_bob_coverage), &
               new_unittest('positions_fitted_length', test_positions_length), &
               new_unittest('bodies_determined', test_bodies_determined), &
               new_unittest('wrong_fixed_length', test_wrong_length)]
   end subroutine collect_fit_params

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    fit_params: '//text
   end subroutine report

   !> `error` was set and holds `needle`: cleared; else set to a failure. Reports the
   !> message.
   subroutine expect_refused(error, what, needle)
      type(error_t), allocatable, intent(inout) :: error  !! the refusal expected
      character(len=*), intent(in) :: what                !! the case, for messages
      character(len=*), intent(in) :: needle              !! text the message holds
      character(len=:), allocatable :: message
      if (.not. allocated(error)) then
         call check_true(error, .false., what//' was accepted, expected refused')
         return
      end if
      message = error%message
      deallocate (error)
      call report(what//': '//message)
      call check_true(error, index(message, needle) > 0, what//': "'//needle// &
                      '" not in: '//message)
   end subroutine expect_refused

   !> A pendulum problem of these masses and lengths (g = 9.8 m/s²) fitting `names`.
   subroutine pendulum_problem(prob, m, l, names, error, damping)
      type(fit_problem_t), intent(out) :: prob
      real(dp), intent(in) :: m(:), l(:)
      character(len=*), intent(in) :: names(:)
      type(error_t), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: damping(:)
      prob%spec = model_spec('pendulum')
      call prob%spec%set('links', [real(size(m), dp)])
      call prob%spec%set('m', m)
      call prob%spec%set('l', l)
      call prob%spec%set('g', [9.8_dp])
      if (present(damping)) call prob%spec%set('damping', damping)
      prob%method = 'dop853'
      call set_fitted(prob, names, error)
      prob%hold_period = 2.0_dp*pi*sqrt(sum(l)/9.8_dp)
      prob%l = l
   end subroutine pendulum_problem

   !> The Jacobian of the residuals with the central-difference rates of the field
   !> (`comp_generic` forced) against the same with the models' analytic rates: the
   !> chain's damping (inside its range and at its lower end 0: one-sided differences)
   !> and the elastic pendulum's k and l0.
   subroutine test_generic_rates(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob, generic
      real(dp), allocatable :: p(:), t(:), q(:, :), r(:), ja(:, :), jg(:, :)
      real(dp) :: worst
      integer :: k, j, c
      character(len=*), parameter :: what(3) = [character(len=16) :: 'damping', &
                                                 'damping at 0', 'elastic k, l0']
      worst = 0.0_dp
      k = 31
      t = [(0.05_dp*j, j=0, k - 1)]
      do c = 1, 3
         select case (c)
         case (1)
            call pendulum_problem(prob, [1.0_dp, 1.3_dp], [1.0_dp, 0.8_dp], &
                                  [character(len=8) :: 'damping'], error, &
                                  damping=[0.05_dp, 0.1_dp])
            p = [-0.3_dp, -1.1_dp, 0.4_dp, -0.7_dp, 0.05_dp, 0.1_dp]
         case (2)
            call pendulum_problem(prob, [1.0_dp, 1.3_dp], [1.0_dp, 0.8_dp], &
                                  [character(len=8) :: 'damping'], error)
            p = [-0.3_dp, -1.1_dp, 0.4_dp, -0.7_dp, 0.0_dp, 0.0_dp]
         case (3)
            prob%spec = model_spec('elastic')
            call prob%spec%set('k', [35.0_dp])
            call prob%spec%set('l0', [1.1_dp])
            call set_fitted(prob, [character(len=2) :: 'k', 'l0'], error)
            prob%angular = [.false., .true.]
            p = [1.2_dp, -1.0_dp, 0.3_dp, 0.5_dp, 35.0_dp, 1.1_dp]
         end select
         if (allocated(error)) return
         call check_true(error, .not. any(prob%comp_generic), trim(what(c))// &
                         ': analytic rates')
         if (allocated(error)) return
         prob%method = 'dop853'
         prob%rtol = 1e-13_dp
         prob%atol = 1e-15_dp
         generic = prob
         generic%comp_generic = .true.
         allocate (q(2, k), r(2*k), ja(2*k, 6), jg(2*k, 6))
         q = 0.0_dp
         call evaluate_fit(prob, p, t, q, k, r, error, ja)
         if (allocated(error)) return
         call evaluate_fit(generic, p, t, q, k, r, error, jg)
         if (allocated(error)) return
         worst = max(worst, maxval(abs(jg(:, 5:6) - ja(:, 5:6)))/maxval(abs(ja(:, 5:6))))
         call check(error, reshape(jg(:, 5:6), [4*k]), reshape(ja(:, 5:6), [4*k]), &
                    trim(what(c))//': generic against analytic dr/dtheta', &
                    abs=1e-7_dp*maxval(abs(ja(:, 5:6))))
         if (allocated(error)) return
         call check(error, reshape(jg(:, :4), [8*k]), reshape(ja(:, :4), [8*k]), &
                    trim(what(c))//': state columns unchanged', rel=0.0_dp)
         if (allocated(error)) return
         deallocate (q, r, ja, jg)
      end do
      call report('generic (central-difference) rates against analytic ones (damping, '// &
                  'damping at 0, elastic k and l0): largest difference '// &
                  real_str(worst, 2)//' of the largest entry')
   end subroutine test_generic_rates

   !> The sensitivities to l2, g and m2 (central differences of the field inside the
   !> variational system) against central differences of the residuals.
   subroutine test_generic_differences(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      real(dp), allocatable :: p(:), t(:), q(:, :), r(:), jac(:, :), fd(:, :)
      real(dp) :: worst
      integer :: k, j, np
      call pendulum_problem(prob, [1.0_dp, 0.6_dp], [1.0_dp, 0.8_dp], &
                            [character(len=2) :: 'l2', 'g', 'm2'], error)
      if (allocated(error)) return
      call check_true(error, all(prob%comp_generic), 'l2, g, m2 by differences')
      if (allocated(error)) return
      call check_true(error, all(prob%comp_labels == ['l2', 'g ', 'm2']), 'labels')
      if (allocated(error)) return
      prob%method = 'dop853'
      prob%rtol = 1e-13_dp
      prob%atol = 1e-15_dp
      k = 41
      t = [(0.05_dp*j, j=0, k - 1)]
      allocate (q(2, k))
      q = 0.0_dp
      p = [-0.4_dp, -1.2_dp, 0.3_dp, -0.5_dp, 0.8_dp, 9.8_dp, 0.6_dp]
      np = size(p)
      allocate (r(2*k), jac(2*k, np), fd(2*k, np - 4))
      call evaluate_fit(prob, p, t, q, k, r, error, jac)
      if (allocated(error)) return
      call residual_differences(prob, p, t, q, k, 5, fd, error)
      if (allocated(error)) return
      worst = maxval(abs(jac(:, 5:) - fd))/maxval(abs(fd))
      call check(error, reshape(jac(:, 5:), [2*k*3]), reshape(fd, [2*k*3]), &
                 'dr/d(l2, g, m2)', abs=1e-6_dp*maxval(abs(fd)))
      if (allocated(error)) return
      call report('sensitivities to l2, g, m2 against differences of the residuals: '// &
                  'largest difference '//real_str(worst, 2)//' of the largest entry')
   end subroutine test_generic_differences

   !> The reference case simulated in-process: noise-free, the fit of m2 and l2 from the
   !> defaults (1 kg, 1 m) recovers 0.5 kg and 0.7 m to 1e-7; with Gaussian noise
   !> σ = 0.01 rad on 6 series (fixed seed) the 95 % intervals of m2 and l2 contain the
   !> truth in at least 5 of 6, and the RMS of (estimate − truth)/SE over the 12
   !> estimates lies in [0.45, 1.6] (1 for standard errors that match the scatter;
   !> the 95 % range of sqrt(χ²₁₂/12) is [0.56, 1.39]).
   subroutine test_recover(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :)
      real(dp) :: z2s(2), z
      integer :: j, cover(2)
      t = [(0.02_dp*j, j=0, samples - 1)]
      call simulate(true_m, true_l, t, q, error)
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=2) :: 'm2', 'l2'], error)
      if (allocated(error)) return
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call check(error, res%p(5:6), [true_m(2), true_l(2)], 'noise-free m2, l2', &
                 abs=1e-7_dp)
      if (allocated(error)) return
      call report('noise-free: m2 = '//real_str(res%p(5), 12)//', l2 = '// &
                  real_str(res%p(6), 12)//' (truth 0.5, 0.7); condition number '// &
                  real_str(res%condition, 3))
      call noisy_coverage(prob, t, q, [true_m(2), true_l(2)], 6, cover, z2s, error)
      if (allocated(error)) return
      z = sqrt(sum(z2s)/12.0_dp)
      call report('6 noisy series: 95 % intervals cover m2 in '//to_str(cover(1))// &
                  ', l2 in '//to_str(cover(2))//' of 6; RMS (estimate - truth)/SE = '// &
                  real_str(z, 3))
      call check_true(error, all(cover >= 5), 'coverage of m2, l2 in 6 noisy series')
      if (allocated(error)) return
      call check_true(error, z >= 0.45_dp .and. z <= 1.6_dp, 'standard errors match ' &
                      //'the scatter: RMS z = '//real_str(z, 3))
   end subroutine test_recover

   !> data/fit_mass_length.csv (m2 = 0.5 kg, l2 = 0.7 m, noise 0.01 rad): the noise
   !> estimated from the data is 0.01 within 20 %; the fit with the default parameters
   !> leaves an RMS residual above misfit_factor times it, and the suspects include l2,
   !> each predicting a lower RMS; the fit of m2, l2 covers the truth with an RMS
   !> residual within 20 % of 0.01.
   subroutine test_data_file(error)
      type(error_t), allocatable, intent(out) :: error
      type(series_t) :: s
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      type(suspect_t), allocatable :: sus(:)
      real(dp) :: noise
      character(len=:), allocatable :: listing
      integer :: i
      call read_series('data/fit_mass_length.csv', s, error)
      if (allocated(error)) return
      call check_true(error, s%k == samples .and. s%n == 2, 'the file has 300 samples')
      if (allocated(error)) return
      prob%spec = model_spec('pendulum')
      prob%method = 'dop853'
      call new_model(prob%spec, prob%model, error)
      if (allocated(error)) return
      prob%hold_period = 2.0_dp*pi*sqrt(2.0_dp/9.8_dp)
      call fit_series(prob, s%t, s%q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      noise = noise_estimate(prob, s%q, res%k_fit)
      call check(error, noise, 0.01_dp, 'noise estimated from the data', rel=0.2_dp)
      if (allocated(error)) return
      call check_true(error, res%rms > misfit_factor*noise, 'the default fit is far ' &
                      //'above the noise: RMS '//real_str(res%rms, 3))
      if (allocated(error)) return
      call misfit_suspects(prob, s%t, s%q, res, sus, error)
      if (allocated(error)) return
      listing = ''
      do i = 1, size(sus)
         listing = listing//' '//trim(sus(i)%label)//' '//real_str(sus(i)%rms, 3)
      end do
      call report('default fit: RMS '//real_str(res%rms, 3)//' rad, noise estimate '// &
                  real_str(noise, 3)//' rad; suspects:'//listing)
      ! link 2's geometry: l2, or com2, which for a rod is l2/2 and moves with it
      ! (ranked l1 0.118, g 0.128, l2 0.185, m1 0.285: com and inertia of rods are not
      ! candidates, they follow l and m)
      call check_true(error, any(sus(:min(4, size(sus)))%label == 'l2' .or. &
                                 sus(:min(4, size(sus)))%label == 'com2'), &
                      'l2 or com2 among the first four suspects')
      if (allocated(error)) return
      call check_true(error, all(sus%rms < res%rms), 'each suspect lowers the RMS')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=2) :: 'm2', 'l2'], error)
      if (allocated(error)) return
      call fit_series(prob, s%t, s%q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call report('fit of m2, l2: '//real_str(res%p(5), 6)//' +- '//real_str(res%se(5), 2) &
                  //' kg, '//real_str(res%p(6), 6)//' +- '//real_str(res%se(6), 2)// &
                  ' m; RMS '//real_str(res%rms, 3))
      call check_true(error, abs(res%p(5) - true_m(2)) <= res%t95*res%se(5) .and. &
                      abs(res%p(6) - true_l(2)) <= res%t95*res%se(6), &
                      'the 95 % intervals of m2 and l2 cover 0.5 kg and 0.7 m')
      if (allocated(error)) return
      call check(error, res%rms, 0.01_dp, 'RMS residual at the noise', rel=0.2_dp)
   end subroutine test_data_file

   !> Sets the data cannot determine: every mass of the pendulum (also with the
   !> damping fitted, or zero), m with k of the elastic pendulum: refused before any
   !> work naming the mass scale; a fixed nonzero damping fixes the scale (accepted);
   !> names that are no parameter or component; the support's phase without support
   !> motion: refused at the statistics naming it.
   subroutine test_undetermined(error)
      type(error_t), allocatable, intent(out) :: error
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :)
      integer :: j
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=1) :: 'm'], error)
      call expect_refused(error, 'm', 'm1,m2 together are not determined')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=7) :: 'm1', 'damping', 'm2'], error, &
                            damping=[0.1_dp, 0.2_dp])
      call expect_refused(error, 'm1,damping,m2', 'the absolute mass scale')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=1) :: 'm'], error, damping=[0.1_dp, 0.0_dp])
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=2) :: 'm2', 'c2'], error)
      if (allocated(error)) return
      prob = fit_problem_t()
      prob%spec = model_spec('elastic')
      call set_fitted(prob, [character(len=1) :: 'k', 'm'], error)
      call expect_refused(error, 'elastic k,m', 'm,k together are not determined')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=5) :: 'links'], error)
      call expect_refused(error, 'links', 'invalid fit parameter: links')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=2) :: 'm3'], error)
      call expect_refused(error, 'm3', 'outside [1, 2]')
      if (allocated(error)) return
      call pendulum_problem(prob, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], &
                            [character(len=2) :: 'l2', 'l2'], error)
      call expect_refused(error, 'l2 twice', 'given already')
      if (allocated(error)) return
      ! no support motion: its phase has no effect on the motion
      t = [(0.02_dp*j, j=0, 99)]
      call simulate(true_m, true_l, t, q, error)
      if (allocated(error)) return
      call pendulum_problem(prob, true_m, true_l, [character(len=16) :: &
                            'support_phase2'], error)
      if (allocated(error)) return
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'support_phase2', 'support_phase2 is not determined')
      if (allocated(error)) return
      ! lengths and g together: the angles depend on g/l only (uniform rods)
      call pendulum_problem(prob, true_m, [1.0_dp, 1.0_dp], [character(len=1) :: 'l', &
                            'g'], error)
      if (allocated(error)) return
      call fit_series(prob, t(:60), q(:, :60), huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'l,g', 'l1,l2,g together are not determined by the ' &
                          //'data: their common scale')
      if (allocated(error)) return
      ! at rest in the hanging position no parameter acts: each column of
      ! sensitivities is rounding error, judged against the noise before any scaling
      ! (scaled to unit length it once gave m2 = 1 ± 0.27 kg, condition number 2.7)
      q = spread([-0.5_dp*pi, -0.5_dp*pi], 2, 21)
      call pendulum_problem(prob, true_m, true_l, [character(len=2) :: 'm2', 'g', 'l2'], &
                            error)
      if (allocated(error)) return
      call fit_series(prob, t(:21), q, huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'at rest m2,g,l2', 'm2, g, l2 are not determined by the ' &
                          //'data: changing m2 by')
      if (allocated(error)) return
      ! the same with a given noise of 0.01 rad: named as given
      prob%noise = 0.01_dp
      call fit_series(prob, t(:21), q, huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'at rest, sigma 0.01', 'less than the noise 0.01 rad ' &
                          //'(given by --sigma)')
   end subroutine test_undetermined

   !> Columns in degrees: theta [deg] (q = θ π/180 − π/2), q [deg] (q = value π/180),
   !> the elastic pendulum's phi [deg]; a unit that is neither refused naming [deg].
   subroutine test_degrees(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(series_t) :: s
      character(len=*), parameter :: nl = new_line('a')
      call parse_series('t [s],theta1 [deg],theta2 [rad],thetadot1 [deg/s]'//nl// &
                        '0,90,1,5'//nl//'1,-45,0,5'//nl//'2,180,2,5'//nl, s, error)
      if (allocated(error)) return
      call check(error, [s%q(1, :), s%q(2, :)], [0.0_dp, -0.75_dp*pi, 0.5_dp*pi, &
                 1.0_dp - 0.5_dp*pi, -0.5_dp*pi, 2.0_dp - 0.5_dp*pi], 'theta in deg, rad', &
                 abs=4e-16_dp)
      if (allocated(error)) return
      call check_true(error, s%degrees, 'degrees noted')
      if (allocated(error)) return
      call parse_series('t,q1 [deg],q2 [deg]'//nl//'0,57.29577951308232,-30'//nl// &
                        '1,0,720'//nl, s, error)
      if (allocated(error)) return
      call check(error, [s%q(1, :), s%q(2, :)], [1.0_dp, 0.0_dp, -pi/6.0_dp, 4.0_dp*pi], &
                 'q in deg', rel=2e-16_dp)
      if (allocated(error)) return
      call parse_series('t,r [m],phi [deg]'//nl//'0,1.2,-90'//nl//'1,1.1,45'//nl, s, &
                        error, [character(len=3) :: 'r', 'phi'], [character(len=3) :: &
                        'm', 'rad'])
      if (allocated(error)) return
      call check(error, [s%q(1, :), s%q(2, :)], [1.2_dp, 1.1_dp, -0.5_dp*pi, 0.25_dp*pi], &
                 'elastic phi in deg', rel=2e-16_dp)
      if (allocated(error)) return
      call parse_series('t,theta1 [grad]'//nl//'0,1'//nl//'1,2'//nl, s, err)
      call check_true(error, allocated(err), 'grad refused')
      if (allocated(error)) return
      call check_true(error, index(err%message, '[deg]') > 0, 'the refusal names [deg]: ' &
                      //err%message)
      if (allocated(error)) return
      call parse_series('t,r [deg],phi [rad]'//nl//'0,1,0'//nl//'1,2,0'//nl, s, err, &
                        [character(len=3) :: 'r', 'phi'], [character(len=3) :: 'm', 'rad'])
      call check_true(error, allocated(err), 'r in deg refused')
   end subroutine test_degrees

   !> Angles q of the two-link chain of masses m and lengths l (g = 9.8) released at
   !> rest from theta0, at times t: dop853 at rtol 1e-12.
   subroutine simulate(m, l, t, q, error)
      real(dp), intent(in) :: m(2), l(2), t(:)
      real(dp), allocatable, intent(out) :: q(:, :)
      type(error_t), allocatable, intent(inout) :: error
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: tt, y(4), h
      integer :: j, stat
      chain = chain_model(m, l, 9.8_dp, error)
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      if (allocated(error)) return
      allocate (q(2, size(t)))
      y = [theta0 - 0.5_dp*pi, 0.0_dp, 0.0_dp]
      tt = t(1)
      h = 1e-3_dp
      q(:, 1) = y(1:2)
      do j = 2, size(t)
         call advance_to(integ, chain, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok, 'synthetic run')
         if (allocated(error)) return
         q(:, j) = y(1:2)
      end do
   end subroutine simulate
   !> The values a fit starts from and edits are the ones the model uses: a rod's
   !> com = l_i/2 and inertia = m_i l_i²/12 (not the catalogue's 0.5 and 1/12), until
   !> the spec gives them.
   subroutine test_body_values(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(model_spec_t) :: spec
      real(dp), allocatable :: v(:)
      spec = model_spec('pendulum')
      call spec%set('m', [2.0_dp, 0.5_dp])
      call spec%set('l', [0.7_dp, 1.2_dp])
      call check_true(error, derived_default(spec, 'com') .and. &
                      derived_default(spec, 'inertia'), 'com, inertia follow the rods')
      if (allocated(error)) return
      v = spec_values(spec, 'com', 2)
      call check(error, v(1), 0.35_dp, 'com1 = l1/2', rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, v(2), 0.6_dp, 'com2 = l2/2', rel=1e-15_dp)
      if (allocated(error)) return
      v = spec_values(spec, 'inertia', 2)
      call check(error, v(1), 2.0_dp*0.49_dp/12.0_dp, 'inertia1 = m1 l1^2/12', rel=1e-15_dp)
      if (allocated(error)) return
      call check(error, v(2), 0.5_dp*1.44_dp/12.0_dp, 'inertia2 = m2 l2^2/12', rel=1e-15_dp)
      if (allocated(error)) return
      call spec%set('com', [0.3_dp, 0.9_dp])
      call check_true(error, .not. derived_default(spec, 'com'), 'com given: its own')
      if (allocated(error)) return
      v = spec_values(spec, 'com', 2)
      call check(error, v(2), 0.9_dp, 'com2 as given', rel=0.0_dp)
   end subroutine test_body_values

   !> The coverage fit: a two-link pendulum with bobs (general bodies, the
   !> lab pendulum of data/bob_pendulum.nml: m = (1.2, 0.8) kg, l = (1, 0.7) m,
   !> d = (0.62, 0.55) m, I = (0.06, 0.02) kg m², g = 9.81 m/s², damping
   !> c = (0.05, 0.02) N m s), released at rest from q = (−0.6, −1.1) rad, 300 samples
   !> over 5.98 s simulated in-process (dop853, rtol 1e-12). Fitted: d2, I2, g, c1, c2
   !> (l2 does not enter the motion once d2 and I2 are given: it only places the tip;
   !> the masses fix the scale), from the guess d2 = 0.45, I2 = 0.03, g = 9.6,
   !> c = (0.01, 0.01). Noise-free: every parameter within 1e-7 of the truth. With
   !> Gaussian noise σ = 0.01 rad on `series` seeded series (DPEND_FIT_SERIES, default
   !> 1; scripts/check/fit_coverage.sh runs 50): the coverage of the 95 % intervals per
   !> parameter, at least 90 % when series ≥ 20; and the RMS over the series of
   !> (estimate − truth)/SE within [0.5, 1.6] per parameter (≥ 20 series) or over all
   !> estimates (fewer).
   subroutine test_bob_coverage(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=8), parameter :: names(5) = [character(len=8) :: 'com2', 'inertia2', &
                                                  'g', 'c1', 'c2']
      real(dp), parameter :: truth(5) = [0.55_dp, 0.02_dp, 9.81_dp, 0.05_dp, 0.02_dp]
      type(model_spec_t) :: spec
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :)
      real(dp) :: z, z2(5), worst
      integer(8) :: c0, c1, rate
      integer :: series, i, j, cover(5)
      character(len=32) :: value
      call get_environment_variable('DPEND_FIT_SERIES', value, status=i)
      series = 1
      if (i == 0) then
         read (value, *, iostat=i) series
      else
         i = 0   ! unset: the default
      end if
      call check_true(error, i == 0 .and. series >= 1 .and. series <= 1000, &
                      'DPEND_FIT_SERIES: '//trim(value)//' is not a count in [1, 1000]')
      if (allocated(error)) return
      call system_clock(c0, rate)
      spec = model_spec('pendulum')
      call spec%set('m', [1.2_dp, 0.8_dp])
      call spec%set('l', [1.0_dp, 0.7_dp])
      call spec%set('com', [0.62_dp, truth(1)])
      call spec%set('inertia', [0.06_dp, truth(2)])
      call spec%set('g', [truth(3)])
      call spec%set('damping', truth(4:5))
      t = [(0.02_dp*j, j=0, samples - 1)]
      call simulate_spec(spec, [-0.6_dp, -1.1_dp], t, q, error)
      if (allocated(error)) return
      ! the fit starts from other values of the fitted parameters
      call spec%set('com', [0.62_dp, 0.45_dp])
      call spec%set('inertia', [0.06_dp, 0.03_dp])
      call spec%set('g', [9.6_dp])
      call spec%set('damping', [0.01_dp, 0.01_dp])
      prob%spec = spec
      prob%method = 'dop853'
      call set_fitted(prob, names, error)
      if (allocated(error)) return
      prob%hold_period = 2.0_dp*pi*sqrt(1.7_dp/9.6_dp)
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      worst = maxval(abs(res%p(5:9) - truth))
      call report('bobs, noise-free: d2, I2, g, c1, c2 = '//values(res%p(5:9))// &
                  '; largest error '//real_str(worst, 2)//'; condition number '// &
                  real_str(res%condition, 3))
      call check(error, res%p(5:9), truth, 'bobs, noise-free d2, I2, g, c1, c2', abs=1e-7_dp)
      if (allocated(error)) return
      call noisy_coverage(prob, t, q, truth, series, cover, z2, error)
      if (allocated(error)) return
      call system_clock(c1)
      call report('bobs, '//to_str(series)//' noisy series (sigma 0.01 rad): 95 % intervals ' &
                  //'cover d2 '//to_str(cover(1))//', I2 '//to_str(cover(2))//', g '// &
                  to_str(cover(3))//', c1 '//to_str(cover(4))//', c2 '//to_str(cover(5))// &
                  ' times; RMS (estimate - truth)/SE '//values(sqrt(z2/real(series, dp)))// &
                  '; '//real_str(real(c1 - c0, dp)/real(rate, dp), 3)//' s')
      if (series >= 20) then
         do i = 1, 5
            call check_true(error, real(cover(i), dp) >= 0.9_dp*real(series, dp), &
                            trim(names(i))//': coverage '//to_str(cover(i))//' of '// &
                            to_str(series)//' < 90 %')
            if (allocated(error)) return
            z = sqrt(z2(i)/real(series, dp))
            call check_true(error, z >= 0.5_dp .and. z <= 1.6_dp, trim(names(i))// &
                            ': RMS (estimate - truth)/SE = '//real_str(z, 3))
            if (allocated(error)) return
         end do
      else
         z = sqrt(sum(z2)/real(5*series, dp))
         call check_true(error, z >= 0.3_dp .and. z <= 2.0_dp, 'RMS (estimate - ' &
                         //'truth)/SE over all estimates = '//real_str(z, 3))
      end if
   contains
      !> The values, blank-separated.
      function values(v) result(text)
         real(dp), intent(in) :: v(:)
         character(len=:), allocatable :: text
         integer :: k
         text = real_str(v(1), 10)
         do k = 2, size(v)
            text = text//' '//real_str(v(k), 10)
         end do
      end function values
   end subroutine test_bob_coverage

   !> Positions with a fitted length (the lab pendulum of data/fit_bob.csv: one link
   !> with a bob, m = 1 kg, l = 0.8 m, d = 0.65 m, I = 0.01 kg m², c = 0.02 N m s,
   !> released at rest from theta = 1.2 rad, the tip's positions observed): the fitted
   !> l places the observed tip, so ∂r/∂l holds ∂P/∂l besides the motion's change
   !> (here none: d and I are given). The Jacobian of l, com and damping against
   !> central differences of the residuals; noise-free, l, d and c recovered to 1e-7
   !> from l = 0.75, d = 0.5, c = 0.
   subroutine test_positions_length(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      real(dp), parameter :: truth(3) = [0.8_dp, 0.65_dp, 0.02_dp]
      type(model_spec_t) :: spec
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :), xy(:, :), p(:), r(:), jac(:, :), fd(:, :)
      real(dp) :: worst
      integer :: j, k
      spec = model_spec('pendulum')
      call spec%set('links', [1.0_dp])
      call spec%set('m', [1.0_dp])
      call spec%set('l', [truth(1)])
      call spec%set('com', [truth(2)])
      call spec%set('inertia', [0.01_dp])
      call spec%set('damping', [truth(3)])
      k = 200
      t = [(0.02_dp*j, j=0, k - 1)]
      call simulate_spec(spec, [1.2_dp - 0.5_dp*pi], t, q, error)
      if (allocated(error)) return
      xy = reshape([(truth(1)*[cos(q(1, j)), sin(q(1, j))], j=1, k)], [2, k])
      call spec%set('l', [0.75_dp])
      call spec%set('com', [0.5_dp])
      call spec%set('damping', [0.0_dp])
      prob%spec = spec
      prob%method = 'dop853'
      prob%positions = .true.
      prob%l = [0.75_dp]
      call set_fitted(prob, [character(len=7) :: 'l', 'com', 'damping'], error)
      if (allocated(error)) return
      prob%hold_period = 2.0_dp*pi*sqrt(0.75_dp/9.8_dp)
      ! the Jacobian against differences of the residuals, inside the ranges
      p = [-0.3_dp, 0.2_dp, 0.78_dp, 0.6_dp, 0.03_dp]
      allocate (r(2*k), jac(2*k, 5), fd(2*k, 3))
      call evaluate_fit(prob, p, t, xy, k, r, error, jac)
      if (allocated(error)) return
      call residual_differences(prob, p, t, xy, k, 3, fd, error)
      if (allocated(error)) return
      worst = maxval(abs(jac(:, 3:) - fd))/maxval(abs(fd))
      call report('positions: dr/d(l, com, c1) against differences of the residuals: ' &
                  //'largest difference '//real_str(worst, 2)//' of the largest entry')
      call check(error, reshape(jac(:, 3:), [6*k]), reshape(fd, [6*k]), &
                 'dr/d(l, com, c1) from positions', abs=1e-6_dp*maxval(abs(fd)))
      if (allocated(error)) return
      call fit_series(prob, t, xy, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call report('positions, noise-free: l, com, c1 = '//real_str(res%p(3), 12)//', '// &
                  real_str(res%p(4), 12)//', '//real_str(res%p(5), 12))
      call check(error, res%p(3:5), truth, 'noise-free l, com, c1 from positions', &
                 abs=1e-7_dp)
   end subroutine test_positions_length

   !> What the data determine for links that are not rods: point masses (`--body point`:
   !> com = l, inertia = 0) fitting m1, m2 refused naming the mass scale (no inertia
   !> fixes it); their l2 fitted moves the mass at the tip with it (`com_at_tip`):
   !> m2 = 0.5 kg, l2 = 0.7 m recovered to 1e-7 from 1 kg, 1 m, noise-free; without
   !> it the fitted l2 would only place the tip, which angles do not see: refused naming
   !> l2. Bobs (com and inertia given): l2 from angles refused naming l2.
   subroutine test_bodies_determined(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(model_spec_t) :: spec
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp), allocatable :: t(:), q(:, :)
      integer :: j
      spec = model_spec('pendulum')
      call spec%set('m', true_m)
      call spec%set('l', true_l)
      call spec%set('com', true_l)
      call spec%set('inertia', [0.0_dp, 0.0_dp])
      call spec%set('g', [9.8_dp])
      t = [(0.02_dp*j, j=0, 149)]
      call simulate_spec(spec, theta0 - 0.5_dp*pi, t, q, error)
      if (allocated(error)) return
      call spec%set('m', [1.0_dp, 1.0_dp])
      call spec%set('l', [1.0_dp, 1.0_dp])
      call spec%set('com', [1.0_dp, 1.0_dp])
      prob%spec = spec
      prob%method = 'dop853'
      prob%com_at_tip = .true.
      prob%hold_period = 2.0_dp*pi*sqrt(2.0_dp/9.8_dp)
      call set_fitted(prob, [character(len=2) :: 'm1', 'm2'], error)
      call expect_refused(error, 'point m1,m2', 'm1,m2 together are not determined by ' &
                          //'the data: the absolute mass scale')
      if (allocated(error)) return
      call set_fitted(prob, [character(len=2) :: 'm2', 'l2'], error)
      if (allocated(error)) return
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call report('point masses, noise-free: m2 = '//real_str(res%p(5), 12)//', l2 = '// &
                  real_str(res%p(6), 12))
      call check(error, res%p(5:6), [true_m(2), true_l(2)], 'point masses: m2, l2', &
                 abs=1e-7_dp)
      if (allocated(error)) return
      prob%com_at_tip = .false.
      call fit_series(prob, t(:60), q(:, :60), huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'point l2 not moving the mass', 'l2 is not determined')
      if (allocated(error)) return
      call prob%spec%set('com', [0.62_dp, 0.55_dp])
      call prob%spec%set('inertia', [0.06_dp, 0.02_dp])
      call set_fitted(prob, [character(len=2) :: 'l2'], error)
      if (allocated(error)) return
      call fit_series(prob, t(:60), q(:, :60), huge(1.0_dp), 0.1_dp, res, error)
      call expect_refused(error, 'bobs l2 from angles', 'l2 is not determined')
   end subroutine test_bodies_determined

   !> A wrong fixed length: the tip positions of data/fit_bob.csv's pendulum
   !> (l = 0.8 m; Gaussian noise 0.002 m, seeded) fitted for com and damping with
   !> l fixed at 0.7 m: the RMS residual exceeds misfit_factor times the noise
   !> estimated from the data (which is 0.002 within 20 %), and l is the first suspect,
   !> its predicted RMS within 20 % of the noise; the same data with l = 0.8 m leave
   !> the RMS at the noise (no warning).
   subroutine test_wrong_length(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(model_spec_t) :: spec
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      type(suspect_t), allocatable :: sus(:)
      real(dp), allocatable :: t(:), q(:, :), xy(:, :)
      real(dp) :: noise, z
      integer(8) :: seed
      integer :: j, i, k
      spec = model_spec('pendulum')
      call spec%set('links', [1.0_dp])
      call spec%set('m', [1.0_dp])
      call spec%set('l', [0.8_dp])
      call spec%set('com', [0.65_dp])
      call spec%set('inertia', [0.01_dp])
      call spec%set('damping', [0.02_dp])
      k = 300
      t = [(0.02_dp*j, j=0, k - 1)]
      call simulate_spec(spec, [1.2_dp - 0.5_dp*pi], t, q, error)
      if (allocated(error)) return
      seed = 26_8
      allocate (xy(2, k))
      do j = 1, k
         xy(:, j) = 0.8_dp*[cos(q(1, j)), sin(q(1, j))]
         do i = 1, 2
            call gaussian(seed, z)
            xy(i, j) = xy(i, j) + 0.002_dp*z
         end do
      end do
      do i = 1, 2
         call spec%set('l', [merge(0.7_dp, 0.8_dp, i == 1)])
         call spec%set('com', [0.5_dp])
         call spec%set('damping', [0.0_dp])
         prob%spec = spec
         prob%method = 'dop853'
         prob%positions = .true.
         prob%l = [merge(0.7_dp, 0.8_dp, i == 1)]
         call set_fitted(prob, [character(len=7) :: 'com', 'damping'], error)
         if (allocated(error)) return
         prob%hold_period = 2.0_dp*pi*sqrt(0.7_dp/9.8_dp)
         call fit_series(prob, t, xy, huge(1.0_dp), 0.1_dp, res, error)
         if (allocated(error)) return
         noise = noise_estimate(prob, xy, res%k_fit)
         if (i == 2) exit
         call check(error, noise, 0.002_dp, 'noise estimated from the positions', rel=0.2_dp)
         if (allocated(error)) return
         call misfit_suspects(prob, t, xy, res, sus, error)
         if (allocated(error)) return
         call report('l fixed at 0.7 m (truth 0.8): RMS '//real_str(res%rms, 3)// &
                     ' m, noise estimate '//real_str(noise, 3)//' m; first suspect '// &
                     trim(sus(1)%label)//' ('//real_str(sus(1)%rms, 3)//' m)')
         call check_true(error, res%rms > misfit_factor*noise, 'a wrong l: RMS '// &
                         real_str(res%rms, 3)//' not above '//real_str(misfit_factor)// &
                         ' times the noise '//real_str(noise, 3))
         if (allocated(error)) return
         call check_true(error, sus(1)%label == 'l', 'first suspect l, not '//sus(1)%label)
         if (allocated(error)) return
         call check(error, sus(1)%rms, 0.002_dp, 'RMS predicted with l fitted', rel=0.2_dp)
         if (allocated(error)) return
      end do
      call report('l at 0.8 m: RMS '//real_str(res%rms, 3)//' m')
      call check_true(error, res%rms <= misfit_factor*noise, 'the right l: RMS '// &
                      real_str(res%rms, 3)//' at the noise '//real_str(noise, 3))
   end subroutine test_wrong_length

   !> Fit `series` noisy copies of the angles q (Gaussian noise 0.01 rad, the seeded
   !> generator from 20261127) and count, per fitted model parameter, the 95 %
   !> intervals that contain `truth` (cover) and the sum of (estimate − truth)²/SE² (z2).
   subroutine noisy_coverage(prob, t, q, truth, series, cover, z2, error)
      type(fit_problem_t), intent(in) :: prob           !! the problem
      real(dp), intent(in) :: t(:), q(:, :)             !! times [s], angles (N, K) [rad]
      real(dp), intent(in) :: truth(:)                  !! the fitted parameters' truth
      integer, intent(in) :: series                     !! noisy series
      integer, intent(out) :: cover(size(truth))        !! intervals containing it
      real(dp), intent(out) :: z2(size(truth))          !! sums of squared z
      type(error_t), allocatable, intent(inout) :: error  !! a fit failed
      type(fit_result_t) :: res
      real(dp) :: qn(size(q, 1), size(q, 2)), z
      integer(8) :: seed
      integer :: s, i, j, off
      seed = 20261127_8
      cover = 0
      z2 = 0.0_dp
      off = 2*size(q, 1)
      do s = 1, series
         do j = 1, size(q, 2)
            do i = 1, size(q, 1)
               call gaussian(seed, z)
               qn(i, j) = q(i, j) + 0.01_dp*z
            end do
         end do
         call fit_series(prob, t, qn, huge(1.0_dp), 0.1_dp, res, error)
         if (allocated(error)) then
            error%message = 'noisy series '//to_str(s)//': '//error%message
            return
         end if
         do i = 1, size(truth)
            z = (res%p(off + i) - truth(i))/res%se(off + i)
            z2(i) = z2(i) + z**2
            if (abs(z) <= res%t95) cover(i) = cover(i) + 1
         end do
      end do
   end subroutine noisy_coverage

   !> Central differences of the residuals of the first k samples in the parameters
   !> p(first:) (steps 1e-5 |p_j|): column j − first + 1 of fd.
   subroutine residual_differences(prob, p, t, obs, k, first, fd, error)
      type(fit_problem_t), intent(in) :: prob             !! the problem
      real(dp), intent(in) :: p(:)                        !! parameters
      real(dp), intent(in) :: t(:), obs(:, :)             !! times [s], observations
      integer, intent(in) :: k                            !! samples used
      integer, intent(in) :: first                        !! first parameter differenced
      real(dp), intent(out) :: fd(:, :)                   !! ∂r/∂p_j (rows, columns)
      type(error_t), allocatable, intent(inout) :: error  !! an integration failed
      real(dp) :: pp(size(p)), rp(size(fd, 1)), rm(size(fd, 1)), d
      integer :: j
      do j = first, size(p)
         pp = p
         d = 1e-5_dp*abs(p(j))
         pp(j) = p(j) + d
         call evaluate_fit(prob, pp, t, obs, k, rp, error)
         if (allocated(error)) return
         pp(j) = p(j) - d
         call evaluate_fit(prob, pp, t, obs, k, rm, error)
         if (allocated(error)) return
         fd(:, j - first + 1) = (rp - rm)/(2.0_dp*d)
      end do
   end subroutine residual_differences

   !> Angles q of the model of `spec` released at rest from q0 [rad], at times t:
   !> dop853 at rtol 1e-12.
   subroutine simulate_spec(spec, q0, t, q, error)
      type(model_spec_t), intent(in) :: spec            !! the model
      real(dp), intent(in) :: q0(:)                     !! initial angles [rad]
      real(dp), intent(in) :: t(:)                      !! sample times [s]
      real(dp), allocatable, intent(out) :: q(:, :)     !! angles (N, K) [rad]
      type(error_t), allocatable, intent(inout) :: error
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: y(:)
      real(dp) :: tt, h
      integer :: j, n, stat
      call new_model(spec, model, error)
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      if (allocated(error)) return
      n = size(q0)
      allocate (q(n, size(t)))
      y = integ%to_internal(model, q0, 0.0_dp*q0, t(1))
      tt = t(1)
      h = 1e-3_dp
      q(:, 1) = q0
      do j = 2, size(t)
         call advance_to(integ, model, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok, 'synthetic run')
         if (allocated(error)) return
         q(:, j) = y(1:n)
      end do
   end subroutine simulate_spec
end module test_fit_params
