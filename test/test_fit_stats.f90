!> The statistics that a fit reports (`fit_series`: σ, the RMS, the degrees of freedom,
!> the covariance and the standard errors) against an independent computation from
!> the definitions (mutation stage: a residual scale divided by the number
!> of observations instead of the degrees of freedom, or a covariance scaled by σ
!> instead of σ², passed every other test):
!>   σ² = Σ r²/(m − P),  RMS² = Σ r²/m,  C = σ² (JᵀJ)⁻¹,  SE_i = sqrt(C_ii),
!> with r the residuals at the estimate (`evaluate_fit`) and J their Jacobian by
!> central differences of `evaluate_fit` (not the fitter's tangent propagation), JᵀJ
!> inverted by LAPACK's dgesv. The data: the damped compound pendulum (N = 1,
!> m = 1 kg, L = 1 m, g = 9.8 m/s², c = 0.06 N m s) over 3 s, 61 samples, with a
!> deterministic disturbance of 0.01 rad, so that the residuals are not small.
!> Measured: σ, RMS equal; covariance entries within 5e-8 (relative to the
!> largest), the tolerance 1e-6; printed on one line ('    fit_stats: …').
!> Also the fit's input: angles given from the hanging position (theta1, theta2) reach
!> the fit as q = θ − π/2, angles q1, q2 unchanged (a conversion with the wrong sign
!> passed every other test).
module test_fit_stats
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_chain, only: chain_t, chain_model
   use dpend_estimate, only: fit_problem_t, fit_result_t, fit_series, evaluate_fit, set_fitted
   use dpend_model_factory, only: model_spec
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_lapack, only: dgesv
   use dpend_csv, only: series_t, parse_series
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_fit_stats

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_fit_stats(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('sigma_covariance_from_definitions', test_statistics), &
               new_unittest('csv_theta_to_q', test_csv_angles)]
   end subroutine collect_fit_stats

   subroutine test_statistics(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer, parameter :: k = 61, np = 3
      real(dp), parameter :: truth(np) = [-0.5_dp*pi + 0.8_dp, 0.5_dp, 0.06_dp]
      type(fit_problem_t) :: prob
      type(fit_result_t) :: res
      real(dp) :: t(k), q(1, k), r(k), rp(k), rm(k), jac(k, np), a(np, np), cov(np, np)
      real(dp) :: p(np), d, sigma, rms, worst
      integer :: j, ipiv(np), info
      t = [(0.05_dp*j, j=0, k - 1)]
      call simulate(truth, t, q, error)
      if (allocated(error)) return
      do j = 1, k
         q(1, j) = q(1, j) + 0.01_dp*sin(37.0_dp*j)
      end do
      ! one rod (1 kg, 1 m, g = 9.8), its damping fitted from the guess 0 and held
      ! while the window is shorter than a swing, as `dpend fit --fit-damping`
      prob%spec = model_spec('pendulum')
      call prob%spec%set('links', [1.0_dp])
      call prob%spec%set('m', [1.0_dp])
      call prob%spec%set('l', [1.0_dp])
      call prob%spec%set('g', [9.8_dp])
      call set_fitted(prob, [character(len=8) :: 'damping'], error)
      if (allocated(error)) return
      prob%hold_period = 2.0_dp*pi*sqrt(1.0_dp/9.8_dp)
      prob%l = [1.0_dp]
      prob%method = 'dop853'; prob%rtol = 1e-12_dp; prob%atol = 1e-14_dp
      call fit_series(prob, t, q, huge(1.0_dp), 0.1_dp, res, error)
      if (allocated(error)) return
      call check_true(error, res%converged .and. res%k_fit == k .and. res%np == np, &
                      'the fit converged over every sample')
      if (allocated(error)) return
      ! the residuals and their Jacobian at the estimate, by central differences
      p = res%p
      call evaluate_fit(prob, p, t, q, k, r, error)
      if (allocated(error)) return
      do j = 1, np
         d = 1e-5_dp*max(1.0_dp, abs(p(j)))
         p(j) = res%p(j) + d
         call evaluate_fit(prob, p, t, q, k, rp, error)
         if (allocated(error)) return
         p(j) = res%p(j) - d
         call evaluate_fit(prob, p, t, q, k, rm, error)
         if (allocated(error)) return
         p(j) = res%p(j)
         jac(:, j) = (rp - rm)/(2.0_dp*d)
      end do
      sigma = sqrt(sum(r**2)/real(k - np, dp))
      rms = sqrt(sum(r**2)/real(k, dp))
      a = matmul(transpose(jac), jac)
      cov = 0.0_dp
      do j = 1, np
         cov(j, j) = 1.0_dp
      end do
      call dgesv(np, np, a, np, ipiv, cov, np, info)
      call check_true(error, info == 0, 'JᵀJ is regular')
      if (allocated(error)) return
      cov = sigma**2*cov
      worst = maxval(abs(res%cov - cov))/maxval(abs(cov))
      write (output_unit, '(a, 3(es9.2, a))') '    fit_stats: sigma ', sigma, &
         ' rad; relative differences: sigma ', abs(res%sigma - sigma)/sigma, &
         ', covariance ', worst, ' (of its largest entry)'
      call check_true(error, res%dof == k - np, 'degrees of freedom m - P')
      call check(error, res%sigma, sigma, 'sigma = sqrt(sum r^2/(m - P)) [rad]', rel=1e-10_dp)
      call check(error, res%rms, rms, 'RMS = sqrt(sum r^2/m) [rad]', rel=1e-10_dp)
      call check(error, reshape(res%cov, [np*np]), reshape(cov, [np*np]), &
                 'covariance sigma^2 (J^T J)^-1', abs=1e-6_dp*maxval(abs(cov)))
      call check(error, res%se, [(sqrt(cov(j, j)), j=1, np)], 'standard errors', rel=1e-6_dp)
   end subroutine test_statistics

   !> theta columns are converted to q = θ − π/2, q columns kept, times as written.
   subroutine test_csv_angles(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=1), parameter :: lf = achar(10)
      type(series_t) :: s
      call parse_series('t,theta1,theta2'//lf//'0,0.1,-0.2'//lf//'0.5,3,1e-3'//lf, s, error)
      if (allocated(error)) return
      call check_true(error, s%n == 2 .and. s%k == 2 .and. s%theta, 'theta: 2 links, 2 rows')
      if (allocated(error)) return
      call check(error, s%t, [0.0_dp, 0.5_dp], 'times [s]', abs=0.0_dp)
      call check(error, reshape(s%q, [4]), [0.1_dp, -0.2_dp, 3.0_dp, 1e-3_dp] - 0.5_dp*pi, &
                 'q = theta - pi/2 [rad]', abs=4.0_dp*epsilon(1.0_dp))
      if (allocated(error)) return
      call parse_series('t,q1,q2'//lf//'0,0.1,-0.2'//lf//'0.5,3,1e-3'//lf, s, error)
      if (allocated(error)) return
      call check_true(error, s%n == 2 .and. s%k == 2 .and. .not. s%theta, 'q: 2 links, 2 rows')
      if (allocated(error)) return
      call check(error, reshape(s%q, [4]), [0.1_dp, -0.2_dp, 3.0_dp, 1e-3_dp], 'q [rad]', &
                 abs=0.0_dp)
   end subroutine test_csv_angles

   !> Angles of the damped compound pendulum from the state (q0, q̇0) and damping c at
   !> the times t (dop853 at rtol 1e-13).
   subroutine simulate(p, t, q, error)
      real(dp), intent(in) :: p(3)                      !! q0 [rad], q̇0 [rad/s], c [N m s]
      real(dp), intent(in) :: t(:)                      !! sample times [s]
      real(dp), intent(out) :: q(:, :)                  !! angles (1, K) [rad]
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: y(2), tt, h
      integer :: j, stat
      chain = chain_model([1.0_dp], [1.0_dp], 9.8_dp, error, damping=[p(3)])
      if (allocated(error)) return
      call new_integrator('dop853', integ, error, method_options_t(rtol=1e-13_dp, &
                          atol=1e-15_dp))
      if (allocated(error)) return
      y = p(1:2); tt = t(1); h = 1e-3_dp
      q(1, 1) = y(1)
      do j = 2, size(t)
         call advance_to(integ, chain, tt, y, t(j), h, stat)
         call check_true(error, stat == stat_ok, 'reference integration')
         if (allocated(error)) return
         q(1, j) = y(1)
      end do
   end subroutine simulate

end module test_fit_stats
