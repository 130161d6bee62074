!> The local order of the continuous extensions of dopri5 and dop853, measured by
!> h-scaling: one fixed step of size h from a generic large-amplitude state,
!> the dense output at θ = 1/4, 1/2, 3/4 of the step against the solution through the same start
!> (dop853 at rtol = 1e-14 to each interior time: step ends only, no interpolation).
!> The local error of an extension of order p scales as h^(p+1); the fitted slope of
!> log(error) against log(h) must lie within ±0.5 of it: 5 for dopri5's 4th-order
!> extension (Hairer, Nørsett & Wanner I, II.6), 8 for dop853's 7th-order one (ibid.,
!> and DOP853 of Hairer & Wanner). A wrong digit in one dense-output coefficient makes
!> the error O(h) for small h and collapses the slope (a mutant that survived the
!> earlier suite).
!> Measured: dopri5 slope 4.61 over h = 0.1 … 0.00625 (consecutive 4.2, 4.5, 4.8, 4.9);
!> dop853 slope 7.52 over h = 0.2 … 0.025 (7.9, 7.1, 7.6). d413 of dop853 changed in its
!> 8th digit: slope 5.6, the last halving 1.3 (fails both windows).
!> Each test prints the measured errors and slope ('    dense: …').
module test_dense
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_pendulum, only: pendulum_t, pendulum_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use test_integrators, only: slope
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_dense

   real(dp), parameter :: pi = acos(-1.0_dp)
   !> A generic large-amplitude state (not at rest: at rest the odd time derivatives of
   !> q vanish and the leading error terms are not the generic ones).
   real(dp), parameter :: y_start(4) = [-0.5_dp*pi + 1.0_dp, -0.5_dp*pi + 0.5_dp, 1.3_dp, -0.7_dp]

contains

   subroutine collect_dense(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('dopri5_local_order', test_dopri5), &
               new_unittest('dop853_local_order', test_dop853)]
   end subroutine collect_dense

   !> A method by name: fixed steps, or dop853 at tight tolerances (reference).
   subroutine make(name, integ, reference)
      character(len=*), intent(in) :: name               !! method name
      class(integrator_t), allocatable, intent(out) :: integ  !! the method
      logical, intent(in) :: reference                   !! tight adaptive reference
      type(error_t), allocatable :: error
      type(method_options_t) :: options
      if (reference) then
         options%rtol = 1.0e-14_dp; options%atol = 1.0e-16_dp
      else
         options%fixed_step = .true.
      end if
      call new_integrator(name, integ, error, options)
   end subroutine make

   !> Largest error of the dense output of `name` at θ = 1/4, 1/2, 3/4 of one step of
   !> size h from (t0, y0), against the reference solution.
   real(dp) function dense_error(name, t0, y0, h, error) result(worst)
      character(len=*), intent(in) :: name          !! method name
      real(dp), intent(in) :: t0                    !! start time [s]
      real(dp), intent(in) :: y0(4)                 !! start state (q [rad], q̇ [rad/s])
      real(dp), intent(in) :: h                     !! step [s]
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      class(integrator_t), allocatable :: integ, ref
      real(dp) :: t, y(4), hh, te, yi(4), ye(4), tr, hr
      integer :: stat, j
      worst = 0.0_dp
      call make(name, integ, .false.)
      call make('dop853', ref, .true.)
      t = t0; y = y0; hh = h
      call integ%step(pendulum_model(pendulum_t()), t, y, hh, stat)
      call check_true(error, stat == stat_ok .and. integ%has_step(), name//': step failed')
      if (allocated(error)) return
      call check(error, integ%t_new - integ%t_old, h, name//': fixed step size', abs=1.0e-15_dp)
      if (allocated(error)) return
      do j = 1, 3
         te = t0 + real(j, dp)/4.0_dp*h
         yi = 0.0_dp
         call integ%interpolate(pendulum_model(pendulum_t()), te, yi)
         call ref%clear_step()
         tr = t0; ye = y0; hr = 0.0_dp
         call advance_to(ref, pendulum_model(pendulum_t()), tr, ye, te, hr, stat)
         call check_true(error, stat == stat_ok, 'reference run failed')
         if (allocated(error)) return
         worst = max(worst, maxval(abs(yi - ye)))
      end do
   end function dense_error

   !> Measured slope of the local dense error over hs against `nominal` ± 0.5, every
   !> error above 100× the reference's accuracy (so that the slope is the method's).
   subroutine local_order(name, hs, nominal, error)
      character(len=*), intent(in) :: name          !! method name
      real(dp), intent(in) :: hs(:)                 !! step sizes [s]
      real(dp), intent(in) :: nominal               !! expected slope p + 1
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      real(dp) :: e(size(hs)), s
      integer :: i
      character(len=400) :: line
      do i = 1, size(hs)
         e(i) = dense_error(name, 0.3_dp, y_start, hs(i), error)
         if (allocated(error)) return
      end do
      s = slope(hs, e)
      write (line, '(a, " errors", *(es9.2))') name, e
      write (output_unit, '(a, "; slope ", f5.2)') '    dense: '//trim(line), s
      call check_true(error, minval(e) > 1.0e-13_dp, name//': errors too small to measure')
      call check(error, s, nominal, name//' local order of the dense output (slope)', abs=0.5_dp)
      ! each halving of h on its own (a wrong coefficient shows at the smallest h first)
      do i = 2, size(hs)
         call check(error, log(e(i - 1)/e(i))/log(hs(i - 1)/hs(i)), nominal, &
                    name//' slope between consecutive h', abs=1.0_dp)
      end do
   end subroutine local_order

   !> dopri5: the 4th-order extension, local error O(h⁵).
   subroutine test_dopri5(error)
      type(error_t), allocatable, intent(out) :: error
      call local_order('dopri5', [0.1_dp, 0.05_dp, 0.025_dp, 0.0125_dp, 0.00625_dp], 5.0_dp, error)
   end subroutine test_dopri5

   !> dop853: the 7th-order extension, local error O(h⁸).
   subroutine test_dop853(error)
      type(error_t), allocatable, intent(out) :: error
      call local_order('dop853', [0.2_dp, 0.1_dp, 0.05_dp, 0.025_dp], 8.0_dp, error)
   end subroutine test_dop853

end module test_dense
