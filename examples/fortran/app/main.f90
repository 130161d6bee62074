!> dpend as a Fortran library, every result in memory (no file):
!> 1. the chapter's double pendulum built by the model factory, integrated by dop853
!>    from the method registry to t = 10 s, sampled every 0.5 s, with the relative
!>    energy error of each sample;
!> 2. its Lyapunov spectrum (the chaos analysis of `dpend lyapunov`) to t = 200 s;
!> 3. the first flip times of a row of releases (the vectorized RK4 lanes of
!>    `dpend sweep`), theta1 from 1 to 3 rad from the hanging position, theta2 = 0;
!> 4. the initial state fitted (the engine of `dpend fit`) to the angles of 1. in the
!>    first 2 s, with 1 mrad of alternating "noise" added.
program dpend_example
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, new_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: integrate_sampled
   use dpend_lyapunov, only: lyapunov_result_t, lyapunov_spectrum
   use dpend_pendulum, only: pendulum_t
   use dpend_lane_batch, only: batch_options_t, batch_result_t, stop_either
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_estimate, only: fit_problem_t, fit_result_t, fit_series
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp)
   type(model_spec_t) :: spec
   class(model_t), allocatable :: model
   class(integrator_t), allocatable :: integ
   type(error_t), allocatable :: error
   real(dp), allocatable :: times(:), states(:, :), releases(:, :)
   real(dp) :: y0(4), e0
   integer :: k, stat
   type(lyapunov_result_t) :: lyap
   type(batch_options_t) :: opt
   type(batch_result_t) :: flips
   type(fit_problem_t) :: prob
   type(fit_result_t) :: fit
   real(dp), allocatable :: q_data(:, :)

   call spec%set('m', [1.0_dp, 1.0_dp])   ! the chapter's rods [kg], [m]
   call spec%set('l', [1.0_dp, 1.0_dp])
   call new_model(spec, model, error)
   if (allocated(error)) error stop 'model: '//error%message
   call new_integrator('dop853', integ, error, method_options_t(rtol=1e-10_dp, atol=1e-12_dp))
   if (allocated(error)) error stop 'method: '//error%message
   ! both links horizontal at rest (angles from the horizontal x axis)
   y0 = integ%to_internal(model, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], 0.0_dp)
   call integrate_sampled(integ, model, 0.0_dp, y0, 10.0_dp, 1e-3_dp, 0.5_dp, times, &
                          states, stat)
   if (stat /= stat_ok) error stop 'the integration failed'
   e0 = model%energy(0.0_dp, states(:, 1))
   write (*, '(a)') '   t [s]      q1 [rad]      q2 [rad]   relative energy error'
   do k = 1, size(times)
      write (*, '(f8.2, 2f14.8, es18.3)') times(k), states(1:2, k), &
         (model%energy(times(k), states(:, k)) - e0)/model%energy_scale(e0)
   end do

   ! the Lyapunov spectrum: 4 exponents, renormalised every 0.5 s, 10 batches
   call lyapunov_spectrum(integ, model, 0.0_dp, y0, 200.0_dp, 1e-2_dp, 0.5_dp, 4, 10, &
                          lyap, stat)
   if (stat /= stat_ok) error stop 'the Lyapunov spectrum failed'
   write (*, '(/, a)') 'Lyapunov exponents [1/s] to t = 200 s (standard error):'
   do k = 1, lyap%k
      write (*, '(f10.4, " (", f7.4, ")")') lyap%exponents(k), lyap%spread(k)
   end do

   ! the first flip of either link of 9 releases: RK4 lanes, h = 1 ms, to t = 20 s
   allocate (releases(4, 9))
   releases = 0.0_dp
   do k = 1, 9
      releases(1, k) = 1.0_dp + 0.25_dp*(k - 1) - pi/2   ! q = theta - pi/2
      releases(2, k) = -pi/2
   end do
   opt%h = 1e-3_dp
   opt%n_steps = 20000
   opt%stop_rule = stop_either
   call integrate_batch(pendulum_t(), opt, releases, flips)
   write (*, '(/, a)') ' theta1 [rad]   first flip [s] (NaN: none by t = 20 s)'
   do k = 1, 9
      write (*, '(f13.2, f17.4)') releases(1, k) + pi/2, flips%t_flip(k)
   end do

   ! the initial state (q1, q2, qdot1, qdot2) fitted to the angles sampled in 1.,
   ! within 0.5 s (the window's samples: t = 0, 0.5, ..., 2 s) and predicted after
   allocate (prob%model, source=model)
   prob%method = 'dop853'
   prob%l = [1.0_dp, 1.0_dp]
   q_data = states(1:2, :)
   do k = 1, size(times)
      q_data(:, k) = q_data(:, k) + 1e-3_dp*(-1.0_dp)**k
   end do
   call fit_series(prob, times, q_data, 2.0_dp, 0.1_dp, fit, error)
   if (allocated(error)) error stop 'fit: '//error%message
   write (*, '(/, a, i0, a, es9.2, a)') 'the release fitted to ', fit%k_fit, &
      ' samples (RMS residual ', fit%rms, ' rad); true values 0, 0, 0, 0:'
   do k = 1, fit%np
      write (*, '(f12.6, " +- ", f9.6)') fit%p(k), fit%se(k)
   end do
end program dpend_example
