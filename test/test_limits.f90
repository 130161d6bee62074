!> Limits before work (dpend_limits): counts compared before dividing, ranges that
!> keep the model finite, --max-steps of the adaptive methods, the bounded tangent
!> substeps, and the Lyapunov exponents sorted descending with their spreads.
module test_limits
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_limits, only: in_range, check_count, check_range, max_steps, sci
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_pendulum, only: pendulum_t
   use dpend_pendulum, only: pendulum_model
   use dpend_integrator, only: integrator_t, stat_ok, stat_max_steps, stat_count_limit
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: march_t, integrate_sampled
   use dpend_lyapunov, only: lyapunov_result_t, lyapunov_spectrum, sort_descending
   use testing, only: unittest_t, new_unittest, check, check_true
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private
   public :: collect_limits

contains

   subroutine collect_limits(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('in_range_nan_safe', test_in_range), &
              new_unittest('count_compared_before_dividing', test_count), &
              new_unittest('run_config_ranges', test_run_config), &
              new_unittest('max_steps_stops_adaptive_march', test_max_steps), &
              new_unittest('fixed_step_count_limit', test_fixed_limit), &
              new_unittest('sampled_count_limit', test_sampled_limit), &
              new_unittest('lyapunov_sorted_descending', test_sort), &
              new_unittest('lyapunov_tau_below_adaptive_step', test_short_tau) &
              ]
   end subroutine collect_limits

   subroutine test_in_range(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: nan
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      call check_true(error, .not. in_range(nan, 0.0_dp, 1.0_dp), 'NaN is not in range')
      call check_true(error, in_range(1.0_dp, 0.0_dp, 1.0_dp), 'upper bound is inclusive')
      call check_true(error, .not. in_range(huge(1.0_dp), 0.0_dp, 1.0_dp), 'huge is out')
   end subroutine test_in_range

   !> 1e9 s over a step of 5e-324 s (1e332 steps) is refused without overflow, and
   !> the message gives the count; 1e12 steps exactly is accepted.
   subroutine test_count(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: e
      call check_count('dt', 5e-324_dp, 1e9_dp, 't_end', max_steps, 'steps', 'hint', e)
      call check_true(error, allocated(e), 'dt = 5e-324 refused')
      if (allocated(error)) return
      call check_true(error, index(e%message, 'invalid dt: ') == 1 .and. &
                      index(e%message, 'e332 steps') > 0, 'message: '//e%message)
      call check_count('dt', 1e-3_dp, 1e9_dp, 't_end', max_steps, 'steps', 'hint', e)
      call check_true(error, .not. allocated(e), '1e12 steps accepted')
      call check_range('m1', 1e308_dp, 1e-6_dp, 1e6_dp, 'kg', e)
      call check_true(error, allocated(e), 'm1 = 1e308 refused')
      call check_true(error, sci(1e-19_dp) == '1e-19' .and. sci(0.5_dp) == '0.5', &
                      'sci: '//sci(1e-19_dp)//' '//sci(0.5_dp))
   end subroutine test_count

   !> Extreme values are refused by validation (no trap), values on the boundary pass.
   subroutine test_run_config(error)
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: base, c
      base%method = 'rk4'
      base%output = 'x.h5'
      c = base
      call expect(c, .true., 'defaults')
      c = base; c%m(1) = 1e308_dp; call expect(c, .false., 'm1 = 1e308')
      c = base; c%l(1) = 1e-300_dp; call expect(c, .false., 'l1 = 1e-300')
      c = base; c%w(2) = 1e150_dp; call expect(c, .false., 'w2 = 1e150')
      c = base; c%t_end = 1.0_dp; c%dt = 1e-19_dp; call expect(c, .false., 'dt = 1e-19')
      c = base; c%dt = 5e-324_dp; call expect(c, .false., 'dt = 5e-324')
      c = base; c%method = 'dopri5'; c%rtol = 1e-300_dp; call expect(c, .false., 'rtol')
      c = base; c%method = 'dopri5'; c%atol = 1e-300_dp; call expect(c, .false., 'atol')
      c = base; c%max_steps = 0; call expect(c, .false., 'max_steps = 0')
      c = base; c%m(1:2) = [1e6_dp, 1e-6_dp]; c%l(1:2) = [1e6_dp, 1e-6_dp]; c%g = 1e6_dp
      c%w(1:2) = [1e6_dp, -1e6_dp]; c%q(1:2) = [1e6_dp, -1e6_dp]
      call expect(c, .true., 'every value on its boundary')
      c = base; c%t_end = 1.0_dp; c%dt = 1e-12_dp; call expect(c, .true., '1e12 steps')
   contains
      subroutine expect(cfg, ok, what)
         type(run_config_t), intent(inout) :: cfg
         logical, intent(in) :: ok
         character(len=*), intent(in) :: what
         type(error_t), allocatable :: e
         call validate_run_config(cfg, e)
         call check_true(error, allocated(e) .neqv. ok, what//merge(' accepted', ' refused ', &
                         ok))
      end subroutine expect
   end subroutine test_run_config

   !> dopri5 with max_steps = 5 over a long interval stops after 5 accepted steps
   !> with stat_max_steps, before t_end.
   subroutine test_max_steps(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(march_t) :: march
      real(dp) :: t, h, y(4)
      integer :: stat
      call new_integrator('dopri5', integ, error, method_options_t(rtol=1e-10_dp, &
                          atol=1e-12_dp, max_steps=5_i8))
      if (allocated(error)) return
      t = 0.0_dp; h = 1e-3_dp; y = [1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp]
      call march%start(integ, t, 100.0_dp, h)
      stat = stat_ok
      do while (.not. march%finished)
         call march%next(integ, pendulum_model(pendulum_t()), t, y, h, stat)
         if (stat /= stat_ok) exit
      end do
      call check_true(error, stat == stat_max_steps, 'stat_max_steps')
      call check_true(error, integ%n_steps == 5_i8, 'five steps taken')
      call check_true(error, t < 100.0_dp, 'stopped before t_end')
   end subroutine test_max_steps

   !> A fixed step of 1e-19 s over 1 s (1e19 steps, beyond integer(8)) is refused by
   !> the march with stat_count_limit, without a step and without a trap.
   subroutine test_fixed_limit(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(march_t) :: march
      real(dp) :: t, h, y(4)
      integer :: stat
      call new_integrator('rk4', integ, error)
      if (allocated(error)) return
      t = 0.0_dp; h = 1e-19_dp; y = [1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp]
      call march%start(integ, t, 1.0_dp, h)
      call march%next(integ, pendulum_model(pendulum_t()), t, y, h, stat)
      call check_true(error, stat == stat_count_limit, 'stat_count_limit')
      call check_true(error, integ%n_steps == 0_i8 .and. t == 0.0_dp, 'no step taken')
   end subroutine test_fixed_limit

   !> Sampling every 1e-300 s is refused by integrate_sampled before allocating.
   subroutine test_sampled_limit(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: times(:), states(:, :)
      integer :: stat
      call new_integrator('rk4', integ, error)
      if (allocated(error)) return
      call integrate_sampled(integ, pendulum_model(pendulum_t()), 0.0_dp, [1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp], &
                             1.0_dp, 1e-3_dp, 1e-300_dp, times, states, stat)
      call check_true(error, stat == stat_count_limit, 'stat_count_limit')
      call check_true(error, size(times) == 1, 'only the initial sample')
   end subroutine test_sampled_limit

   !> sort_descending orders the exponents and carries spreads, batches and running
   !> estimates along.
   subroutine test_sort(error)
      type(error_t), allocatable, intent(out) :: error
      type(lyapunov_result_t) :: r
      integer :: i
      r%k = 4
      r%exponents = [0.1_dp, 1.2_dp, -0.05_dp, -1.3_dp]
      r%spread = [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp]
      allocate (r%batches(4, 3), r%running(4, 2))
      do i = 1, 4
         r%batches(i, :) = 10.0_dp*i
         r%running(i, :) = 100.0_dp*i
      end do
      call sort_descending(r)
      call check(error, r%exponents, [1.2_dp, 0.1_dp, -0.05_dp, -1.3_dp], 'exponents', &
                 abs=0.0_dp)
      call check(error, r%spread, [2.0_dp, 1.0_dp, 3.0_dp, 4.0_dp], 'spreads', abs=0.0_dp)
      call check(error, r%batches(:, 3), [20.0_dp, 10.0_dp, 30.0_dp, 40.0_dp], 'batches', &
                 abs=0.0_dp)
      call check(error, r%running(:, 1), [200.0_dp, 100.0_dp, 300.0_dp, 400.0_dp], &
                 'running', abs=0.0_dp)
   end subroutine test_sort

   !> tau far below the steps of an adaptive method: one renormalisation per step,
   !> the run ends (the next multiple of tau is found directly) and the exponents
   !> come out descending.
   subroutine test_short_tau(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(lyapunov_result_t) :: res
      integer :: stat, i
      call new_integrator('dopri5', integ, error, method_options_t(rtol=1e-8_dp, atol=1e-10_dp))
      if (allocated(error)) return
      call lyapunov_spectrum(integ, pendulum_model(pendulum_t()), 0.0_dp, [1.0_dp, 0.5_dp, 0.0_dp, 0.0_dp], &
                             1.0_dp, 1e-3_dp, 1e-12_dp, 4, 5, res, stat)
      call check_true(error, stat == stat_ok, 'run completed')
      call check_true(error, size(res%t) <= integ%n_steps + 1, &
                      'at most one renormalisation per step')
      call check_true(error, all([(res%exponents(i) >= res%exponents(i + 1), i=1, 3)]), &
                      'descending')
   end subroutine test_short_tau
end module test_limits
