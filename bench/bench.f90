!> dpend-bench: cost of the integrators on the chapter's pendulum, one figure a line
!> as `key: value unit`. Each figure is timed (wall clock, system_clock int64) over
!> at least 0.3 s; a checksum of the final states defeats dead-code elimination.
!> Run in release: fpm run dpend-bench --profile release --flag "-O3 -march=native"
!> The methods come from the registry (dpend_method_registry): every fixed-step
!> method is timed at h = 0.01 s, every method enters the work-precision table.
!> The batch kernel of the sweep (and the single-trajectory rk4_ns_per_step) is timed
!> by `bench_batch`.
program bench
   use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options, int64, &
                                            output_unit
   use bench_batch, only: run_batch_benchmarks
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, rhs_qqdot
   use dpend_pendulum, only: double_pendulum_t
   use dpend_error, only: error_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods
   implicit none

   real(dp), parameter :: pi = acos(-1.0_dp)
   real(dp), parameter :: min_seconds = 0.3_dp
   !> a large regular swing released at rest
   real(dp), parameter :: y0(4) = [-0.5_dp*pi + 1.0_dp, -0.5_dp*pi + 1.0_dp, 0.0_dp, 0.0_dp]
   real(dp) :: checksum, ns, rhs_per_step, rk4_ns
   integer :: i
   character(len=:), allocatable :: name

   checksum = 0.0_dp
   write (*, '(a)') 'compiler: '//compiler_version()
   write (*, '(a)') 'flags: '//compiler_options()
   call report('rhs_ns', time_rhs(), 'ns')
   call run_batch_benchmarks(output_unit)
   call report('dopri5_ns_per_step', time_method('dopri5', 0.0_dp), 'ns')
   ns = time_method('dop853', 0.0_dp, n_rhs_per_step=rhs_per_step)
   call report('dop853_ns_per_accepted_step', ns, 'ns')
   call report('dop853_ns_per_rhs', ns/rhs_per_step, 'ns')
   rk4_ns = time_method('rk4', 1.0e-2_dp)   ! same step as the implicit methods below
   ! every fixed-step method of the registry but rk4 (timed above and by bench_batch)
   do i = 1, n_methods
      name = trim(method_table(i)%name)
      if (method_table(i)%adaptive .or. name == 'rk4') cycle
      ns = time_method(name, 1.0e-2_dp, n_rhs_per_step=rhs_per_step)
      call report(name//'_ns_per_step', ns, 'ns')
      call report(name//'_rhs_per_step', rhs_per_step, '')
      if (name == 'gauss6') call report('gauss6_over_rk4_step_cost', ns/rk4_ns, '')
   end do
   call work_precision()
   write (*, '(a, es24.16)') 'checksum: ', checksum

contains

   subroutine report(key, value, unit)
      character(len=*), intent(in) :: key, unit
      real(dp), intent(in) :: value
      if (abs(value) >= 10.0_dp) then
         write (*, '(a, ": ", f0.1, " ", a)') key, value, unit
      else
         write (*, '(a, ": ", f0.3, " ", a)') key, value, unit
      end if
   end subroutine report

   !> Work–precision table: the error at t = 1 s of the horizontal release against
   !> the 40-digit reference of data/reference/release_horizontal.txt, against the
   !> right-hand-side evaluations and the wall time, for every method at three steps
   !> (tolerances for the adaptive ones). Lines: `wp: method h_or_rtol error n_rhs us`.
   subroutine work_precision()
      use dpend_propagate, only: advance_to
      real(dp), parameter :: steps(3) = [1.0e-2_dp, 3.0e-3_dp, 1.0e-3_dp]
      real(dp), parameter :: tols(3) = [1.0e-6_dp, 1.0e-9_dp, 1.0e-12_dp]
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      type(pendulum_t) :: par
      type(double_pendulum_t) :: model
      real(dp) :: ref(4), t, y(4), h, q(2), qd(2), err, start, elapsed
      integer :: m, j, stat, unit, reps, r
      character(len=256) :: line
      open (newunit=unit, file='data/reference/release_horizontal.txt', status='old', &
            action='read', iostat=stat)
      if (stat /= 0) then
         write (*, '(a)') 'wp: skipped (run from the project root to read the reference)'
         return
      end if
      do
         read (unit, '(a)') line
         if (line(1:1) /= '#') exit
      end do
      read (line, *) t, ref
      close (unit)
      write (*, '(a)') 'wp: method step_or_rtol error_at_1s n_rhs microseconds'
      do m = 1, n_methods
         do j = 1, 3
            ! tolerances reach only the adaptive methods
            call new_integrator(trim(method_table(m)%name), integ, error, &
                                method_options_t(rtol=tols(j), atol=tols(j)*1.0e-3_dp))
            reps = 0
            start = now()
            do r = 1, 1000
               call integ%reset_counters()
               call integ%clear_step()
               h = merge(0.0_dp, steps(j), integ%adaptive())
               t = 0.0_dp
               y = integ%to_internal(model, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp])
               call advance_to(integ, model, t, y, 1.0_dp, h, stat)
               reps = reps + 1
               if (now() - start > 0.05_dp) exit
            end do
            elapsed = (now() - start)/real(reps, dp)
            call integ%to_physical(model, y, q, qd)
            err = maxval(abs([q, qd] - ref))
            checksum = checksum + err
            if (integ%adaptive()) then
               write (*, '("wp: ", a8, " rtol=", es8.1, es10.2, i9, f12.1)') &
                  method_table(m)%name(1:8), &
                  tols(j), err, integ%n_rhs, 1.0e6_dp*elapsed
            else
               write (*, '("wp: ", a8, " h=   ", es8.1, es10.2, i9, f12.1)') &
                  method_table(m)%name(1:8), &
                  steps(j), err, integ%n_rhs, 1.0e6_dp*elapsed
            end if
         end do
      end do
   end subroutine work_precision

   !> Seconds since an arbitrary origin.
   real(dp) function now()
      integer(int64) :: count, rate
      call system_clock(count, rate)
      now = real(count, dp)/real(rate, dp)
   end function now

   !> ns per accepted step of method `name` from the factory, stepping the swing
   !> with h (fixed-step methods) or from h = 0 at default tolerances (adaptive
   !> ones); the number of steps doubles until the run lasts min_seconds.
   !> Optionally returns the right-hand-side evaluations per accepted step.
   real(dp) function time_method(name, h, n_rhs_per_step) result(ns_per_step)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: h
      real(dp), intent(out), optional :: n_rhs_per_step
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      type(pendulum_t) :: par
      type(double_pendulum_t) :: model
      real(dp) :: t, y(4), hh, start, elapsed
      integer(i8) :: nsteps, i
      integer :: stat
      call new_integrator(name, integ, error)
      if (allocated(error)) error stop 'unknown method'
      nsteps = 1000
      do
         call integ%reset_counters()
         call integ%clear_step()
         t = 0.0_dp; y = y0; hh = h
         start = now()
         do i = 1, nsteps
            call integ%step(model, t, y, hh, stat)
            if (stat /= stat_ok) error stop 'step failed'
         end do
         elapsed = now() - start
         checksum = checksum + sum(y)
         if (elapsed >= min_seconds) exit
         nsteps = 2*nsteps
      end do
      ns_per_step = 1.0e9_dp*elapsed/real(integ%n_steps, dp)
      if (present(n_rhs_per_step)) &
         n_rhs_per_step = real(integ%n_rhs, dp)/real(integ%n_steps, dp)
   end function time_method

   !> ns per evaluation of rhs_qqdot along a slowly varying state.
   real(dp) function time_rhs() result(ns)
      type(pendulum_t) :: par
      type(double_pendulum_t) :: model
      real(dp) :: y(4), f(4), start, elapsed
      integer(i8) :: n, i
      n = 100000
      do
         y = y0
         start = now()
         do i = 1, n
            f = rhs_qqdot(par, y)
            y = y + 1.0e-7_dp*f
         end do
         elapsed = now() - start
         checksum = checksum + sum(y)
         if (elapsed >= min_seconds) exit
         n = 2*n
      end do
      ns = 1.0e9_dp*elapsed/real(n, dp)
   end function time_rhs
end program bench
