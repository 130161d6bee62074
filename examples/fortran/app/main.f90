!> dpend as a Fortran library: the chapter's double pendulum built by the model
!> factory, integrated by dop853 from the method registry to t = 10 s, sampled every
!> 0.5 s in memory (no file), with the relative energy error of each sample.
program dpend_example
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, new_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: integrate_sampled
   implicit none
   type(model_spec_t) :: spec
   class(model_t), allocatable :: model
   class(integrator_t), allocatable :: integ
   type(error_t), allocatable :: error
   real(dp), allocatable :: times(:), states(:, :)
   real(dp) :: y0(4), e0
   integer :: k, stat

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
end program dpend_example
