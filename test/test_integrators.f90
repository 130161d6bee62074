!> Integrators, dense output, propagation drivers and events against independent
!> references: measured orders of convergence, tolerance proportionality,
!> continuous extensions against local exact solutions, event times against the
!> analytic normal-mode period of the linearized pendulum, counter bookkeeping.
module test_integrators
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, mass_matrix, energy
   use dpend_pendulum, only: pendulum_model
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite, stat_step_too_small
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_fixed, advance_to, integrate_sampled
   use dpend_events, only: angle_crossing_t, crossing_t, locate_crossing, find_crossings
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_integrators, slope

   real(dp), parameter :: pi = acos(-1.0_dp)
   !> Small oscillation about the hanging equilibrium (regular, two modes).
   real(dp), parameter :: y_small(4) = [-0.5_dp*pi + 0.1_dp, -0.5_dp*pi - 0.05_dp, 0.0_dp, 0.0_dp]
   !> Large swing released at rest (regular over 10 s, strongly nonlinear).
   real(dp), parameter :: y_swing(4) = [-0.5_dp*pi + 1.0_dp, -0.5_dp*pi + 1.0_dp, 0.0_dp, 0.0_dp]
   !> Both links whirling from the bottom (rotation, regular over 2 s).
   real(dp), parameter :: y_whirl(4) = [-0.5_dp*pi, -0.5_dp*pi, 8.0_dp, 8.0_dp]

contains

   subroutine collect_integrators(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('factory_names', test_factory), &
               new_unittest('order_rk4', test_order_rk4), &
               new_unittest('order_dopri5', test_order_dopri5), &
               new_unittest('order_dop853', test_order_dop853), &
               new_unittest('rk4_energy_error_dt4', test_rk4_energy), &
               new_unittest('tolerance_proportionality_dop853', test_tolerance), &
               new_unittest('dense_output_dopri5_local', test_dense_dopri5), &
               new_unittest('dense_output_dop853_local', test_dense_dop853), &
               new_unittest('dense_output_sampled_global', test_dense_global), &
               new_unittest('hermite_rk4_order4', test_hermite_rk4), &
               new_unittest('interpolate_without_step', test_no_step), &
               new_unittest('advance_to_exact_end', test_advance_to), &
               new_unittest('sampled_grid_times', test_sampled_grid), &
               new_unittest('counters_rk4', test_counters_rk4), &
               new_unittest('counters_dopri5_fsal', test_counters_dopri5), &
               new_unittest('counters_dop853', test_counters_dop853), &
               new_unittest('status_nonfinite_and_too_small', test_status), &
               new_unittest('events_normal_mode_period', test_events_period), &
               new_unittest('events_fixed_step_on_flow', test_events_fixed), &
               new_unittest('events_wrapped_angle', test_events_wrap)]
   end subroutine collect_integrators

   ! ------------------------------------------------------------------ helpers

   !> A method by name, with tolerances (adaptive pairs) or fixed steps.
   subroutine make(name, integ, rtol, atol, fixed)
      character(len=*), intent(in) :: name
      class(integrator_t), allocatable, intent(out) :: integ
      real(dp), intent(in), optional :: rtol, atol
      logical, intent(in), optional :: fixed
      type(error_t), allocatable :: error
      type(method_options_t) :: options
      if (present(rtol)) options%rtol = rtol
      if (present(atol)) options%atol = atol
      if (present(fixed)) options%fixed_step = fixed
      call new_integrator(name, integ, error, options)
   end subroutine make

   !> State at t_end from (0, y0): fixed step h, or adaptive with h = 0.
   function solve(integ, y0, t_end, h) result(y)
      class(integrator_t), intent(inout) :: integ
      real(dp), intent(in) :: y0(4), t_end, h
      real(dp) :: y(4), t, hh
      integer :: stat
      call integ%clear_step()
      t = 0.0_dp; y = y0; hh = h
      call advance_to(integ, pendulum_model(pendulum_t()), t, y, t_end, hh, stat)
      if (stat /= stat_ok) y = huge(1.0_dp)
   end function solve

   !> Least-squares slope of log(e) against log(x).
   pure real(dp) function slope(x, e)
      real(dp), intent(in) :: x(:), e(:)
      real(dp) :: lx(size(x)), le(size(x))
      lx = log(x); le = log(e)
      slope = sum((lx - sum(lx)/size(x))*(le - sum(le)/size(x))) &
              /sum((lx - sum(lx)/size(x))**2)
   end function slope

   !> Reference state at t_end: dop853 at rtol = 1e-14, cross-checked against rk4
   !> at h = 1e-4 with Richardson extrapolation from h = 2e-4 (an independent
   !> method); fails if they differ by more than `agree`.
   subroutine reference(y0, t_end, yref, agree, error)
      real(dp), intent(in) :: y0(4), t_end, agree
      real(dp), intent(out) :: yref(4)
      type(error_t), allocatable, intent(inout) :: error
      class(integrator_t), allocatable :: integ
      real(dp) :: y1(4), y2(4)
      call make('dop853', integ, rtol=1.0e-14_dp, atol=1.0e-16_dp)
      yref = solve(integ, y0, t_end, 0.0_dp)
      call make('rk4', integ)
      y1 = solve(integ, y0, t_end, 1.0e-4_dp)
      y2 = solve(integ, y0, t_end, 2.0e-4_dp)
      call check(error, y1 + (y1 - y2)/15.0_dp, yref, 'reference dop853 vs rk4', abs=agree)
   end subroutine reference

   !> Measured order of `name` at fixed steps hs on [0, t_end] from y0.
   subroutine measured_order(name, y0, t_end, hs, nominal, error)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: y0(4), t_end, hs(:)
      integer, intent(in) :: nominal
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      real(dp) :: yref(4), e(size(hs))
      integer :: i
      call reference(y0, t_end, yref, 1.0e-12_dp, error)
      if (allocated(error)) return
      call make(name, integ, fixed=.true.)
      do i = 1, size(hs)
         e(i) = maxval(abs(solve(integ, y0, t_end, hs(i)) - yref))
         ! the reference must be far more accurate than the measured errors
         call check_true(error, e(i) > 1.0e-12_dp, name//': error too close to the reference')
      end do
      call check(error, slope(hs, e), real(nominal, dp), name//' fitted order', abs=0.2_dp)
   end subroutine measured_order

   ! -------------------------------------------------------------------- tests

   subroutine test_factory(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      character(len=6), parameter :: names(3) = ['rk4   ', 'dopri5', 'dop853']
      integer, parameter :: orders(3) = [4, 5, 8]
      integer :: i
      do i = 1, 3
         call new_integrator(trim(names(i)), integ, err)
         call check_true(error, .not. allocated(err), 'factory rejects '//trim(names(i)))
         if (allocated(error)) return
         call check_true(error, integ%name() == trim(names(i)), 'name of '//trim(names(i)))
         call check_true(error, integ%order() == orders(i), 'order of '//trim(names(i)))
         call check_true(error, integ%adaptive() .eqv. (i > 1), 'adaptive() of '//names(i))
         call check_true(error, .not. integ%canonical(), 'canonical() of '//names(i))
         call check_true(error, .not. integ%symplectic(), 'symplectic() of '//names(i))
      end do
      call new_integrator('dopri', integ, err)
      call check_true(error, allocated(err), 'unknown method accepted')
   end subroutine test_factory

   !> rk4 on the small oscillation, T = 2 s, h = 0.025 … 0.00625 (errors 1e-5 … 5e-8).
   subroutine test_order_rk4(error)
      type(error_t), allocatable, intent(out) :: error
      call measured_order('rk4', y_small, 2.0_dp, [0.025_dp, 0.0125_dp, 0.00625_dp], 4, error)
   end subroutine test_order_rk4

   !> dopri5 at fixed steps on the small oscillation, T = 2 s, h = 0.05 … 0.00625.
   subroutine test_order_dopri5(error)
      type(error_t), allocatable, intent(out) :: error
      call measured_order('dopri5', y_small, 2.0_dp, &
                          [0.05_dp, 0.025_dp, 0.0125_dp, 0.00625_dp], 5, error)
   end subroutine test_order_dopri5

   !> dop853 at fixed steps on the whirling trajectory, T = 2 s, h = 0.05 … 0.0125
   !> (errors 4e-7 … 6e-12). On the small oscillation DOP853's 9th-order error
   !> term, which its coefficients make small (the z⁹ coefficient of the stability
   !> function is 2 % off e^z), dominates at every step size whose error is above
   !> roundoff: the apparent order there is 8.5.
   subroutine test_order_dop853(error)
      type(error_t), allocatable, intent(out) :: error
      call measured_order('dop853', y_whirl, 2.0_dp, [0.05_dp, 0.025_dp, 0.0125_dp], 8, error)
   end subroutine test_order_dop853

   !> The rk4 energy error at T = 2 s on the whirling trajectory shrinks as dt⁴
   !> (dt = 5e-3, 2.5e-3, 1.25e-3; measured slope 4.08). The error is a bounded
   !> O(dt⁴) oscillation plus a part that grows with t and is O(dt⁵) (for a linear
   !> oscillator |R(iωh)|² = 1 - (ωh)⁶/72 + …): on the oscillating trajectories of
   !> the tests the second part dominates after a few periods, slopes 4.5–5.
   subroutine test_rk4_energy(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp) :: dts(3), e(3), y(4), e0
      integer :: i
      dts = [0.005_dp, 0.0025_dp, 0.00125_dp]
      e0 = energy(par, y_whirl(1:2), y_whirl(3:4))
      call make('rk4', integ)
      do i = 1, 3
         y = solve(integ, y_whirl, 2.0_dp, dts(i))
         e(i) = abs(energy(par, y(1:2), y(3:4)) - e0)
      end do
      call check(error, slope(dts, e), 4.0_dp, 'rk4 energy error slope', abs=0.3_dp)
   end subroutine test_rk4_energy

   !> dop853 with atol = 1e-3 rtol: the global error at t = 10 s on the large swing
   !> stays below 100 rtol for rtol = 1e-6 … 1e-13 and its log-log slope against
   !> rtol is 0.7 … 1.3. Reference: rtol = 1e-15, checked against rk4 (h = 1e-4,
   !> Richardson) to 1e-11.
   subroutine test_tolerance(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      real(dp) :: yref(4), y1(4), y2(4), rt(8), e(8)
      integer :: i
      call make('dop853', integ, rtol=1.0e-15_dp, atol=1.0e-18_dp)
      yref = solve(integ, y_swing, 10.0_dp, 0.0_dp)
      call make('rk4', integ)
      y1 = solve(integ, y_swing, 10.0_dp, 1.0e-4_dp)
      y2 = solve(integ, y_swing, 10.0_dp, 2.0e-4_dp)
      call check(error, y1 + (y1 - y2)/15.0_dp, yref, 'reference vs rk4', abs=1.0e-11_dp)
      if (allocated(error)) return
      do i = 1, 8
         rt(i) = 10.0_dp**(-5 - i)
         call make('dop853', integ, rtol=rt(i), atol=1.0e-3_dp*rt(i))
         e(i) = maxval(abs(solve(integ, y_swing, 10.0_dp, 0.0_dp) - yref))
         call check(error, e(i), 0.0_dp, 'global error at rtol', abs=100.0_dp*rt(i))
      end do
      call check(error, slope(rt, e), 1.0_dp, 'slope of error vs rtol', abs=0.3_dp)
   end subroutine test_tolerance

   !> After every step of an adaptive run at rtol = 1e-8 over 3 s, the continuous
   !> extension at 7 interior points is compared with the local exact solution
   !> through (t_old, y_old) (rk4, h ≈ 1e-5, independent of the method). Its error
   !> in the controller's norm, RMS of e_i/(atol + rtol max(|y_old,i|, |y_new,i|)),
   !> must be below 20, i.e. of the size of the tolerance (measured: dopri5 9.5, its
   !> 4th-order extension being less accurate than the 5th-order step; dop853 4.1).
   !> (Separately: local dense errors scale as h⁵ for dopri5 and h⁸ for dop853.)
   subroutine dense_local(name, error)
      character(len=*), intent(in) :: name
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ, exact
      type(pendulum_t) :: par
      real(dp), parameter :: rtol = 1.0e-8_dp, atol = 1.0e-11_dp
      real(dp) :: t, y(4), h, ye(4), yi(4), te, he, worst, sk(4)
      integer :: stat, j, n
      call make(name, integ, rtol=rtol, atol=atol)
      call make('rk4', exact)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      worst = 0.0_dp
      n = 0
      do while (t < 3.0_dp)
         call integ%step(pendulum_model(par), t, y, h, stat)
         call check_true(error, stat == stat_ok, name//': step failed')
         if (allocated(error)) return
         n = n + 1
         do j = 1, 7
            te = integ%t_old + real(j, dp)/8.0_dp*(integ%t_new - integ%t_old)
            yi = 0.0_dp
            call integ%interpolate(pendulum_model(par), te, yi)
            ! local exact solution: rk4 with ~1e-5 steps from (t_old, y_old)
            ye = integ%y_old(:4)
            he = (te - integ%t_old)/real(max(1, nint((te - integ%t_old)/1.0e-5_dp)), dp)
            call advance_exact(ye, te - integ%t_old, he)
            sk = atol + rtol*max(abs(integ%y_old(:4)), abs(integ%y_new(:4)))
            worst = max(worst, sqrt(sum(((yi - ye)/sk)**2)/4.0_dp))
         end do
      end do
      call check_true(error, n > 20, name//': too few steps to be a test')
      call check(error, worst, 0.0_dp, name//' dense output error / scale', abs=20.0_dp)
   contains
      subroutine advance_exact(ys, span, hs)
         real(dp), intent(inout) :: ys(4)
         real(dp), intent(in) :: span, hs
         real(dp) :: tt, hh
         integer :: st
         tt = 0.0_dp; hh = hs
         call exact%clear_step()
         call advance_to(exact, pendulum_model(par), tt, ys, span, hh, st)
      end subroutine advance_exact
   end subroutine dense_local

   subroutine test_dense_dopri5(error)
      type(error_t), allocatable, intent(out) :: error
      call dense_local('dopri5', error)
   end subroutine test_dense_dopri5

   subroutine test_dense_dop853(error)
      type(error_t), allocatable, intent(out) :: error
      call dense_local('dop853', error)
   end subroutine test_dense_dop853

   !> `integrate_sampled` at rtol = 1e-8 with output every 0.01 s over 5 s agrees
   !> with rk4 at h = 1e-4 (its samples are step ends, no interpolation) within
   !> 100 rtol, i.e. the global error; the times are the same grid.
   subroutine test_dense_global(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp), allocatable :: tr(:), sr(:, :), ts(:), ss(:, :)
      character(len=6), parameter :: names(2) = ['dopri5', 'dop853']
      integer :: stat, i
      call make('rk4', integ)
      call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 5.0_dp, 1.0e-4_dp, 0.01_dp, tr, sr, stat)
      call check_true(error, stat == stat_ok .and. size(tr) == 501, 'reference run')
      if (allocated(error)) return
      do i = 1, 2
         call make(names(i), integ, rtol=1.0e-8_dp, atol=1.0e-11_dp)
         call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 5.0_dp, 0.0_dp, 0.01_dp, &
                                ts, ss, stat)
         call check_true(error, stat == stat_ok .and. size(ts) == 501, names(i)//' run')
         if (allocated(error)) return
         call check(error, maxval(abs(ts - tr)), 0.0_dp, names(i)//' sample times', abs=0.0_dp)
         call check(error, maxval(abs(ss - sr)), 0.0_dp, names(i)//' samples', abs=1.0e-6_dp)
      end do
   end subroutine test_dense_global

   !> The Hermite default of rk4, sampled every 0.007 s (mostly inside steps), is
   !> O(h⁴): fitted order over h = 0.02, 0.01, 0.005 within 4 ± 0.3.
   subroutine test_hermite_rk4(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp), allocatable :: tr(:), sr(:, :), ts(:), ss(:, :)
      real(dp) :: hs(3), e(3)
      integer :: stat, i
      call make('rk4', integ)
      call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 5.0_dp, 1.0e-4_dp, 0.007_dp, tr, sr, stat)
      hs = [0.02_dp, 0.01_dp, 0.005_dp]
      do i = 1, 3
         call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 5.0_dp, hs(i), 0.007_dp, ts, ss, stat)
         call check_true(error, stat == stat_ok .and. size(ts) == size(tr), 'rk4 sampled run')
         if (allocated(error)) return
         e(i) = maxval(abs(ss - sr))
      end do
      call check(error, slope(hs, e), 4.0_dp, 'rk4 + Hermite sampled order', abs=0.3_dp)
   end subroutine test_hermite_rk4

   !> Before any step `interpolate` leaves its argument alone and has_step() is false.
   subroutine test_no_step(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      character(len=6), parameter :: names(3) = ['rk4   ', 'dopri5', 'dop853']
      real(dp) :: y(4)
      integer :: i
      do i = 1, 3
         call make(trim(names(i)), integ)
         y = [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp]
         call check_true(error, .not. integ%has_step(), 'has_step before a step')
         call integ%interpolate(pendulum_model(pendulum_t()), 0.5_dp, y)
         call check(error, y, [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp], 'untouched', abs=0.0_dp)
         call check_true(error, integ%n_rhs == 0, 'no evaluation')
      end do
   end subroutine test_no_step

   !> advance_to ends exactly on t_target: fixed steps 0.03 to t = 1 take 33 whole
   !> steps and one of 0.01 (same as doing it by hand); 0.025 divides 1 exactly;
   !> an adaptive run ends on t_target as well.
   subroutine test_advance_to(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp) :: t, y(4), h, t2, y2(4), h2
      integer :: stat
      call make('rk4', integ)
      t = 0.0_dp; y = y_swing; h = 0.03_dp
      call advance_to(integ, pendulum_model(par), t, y, 1.0_dp, h, stat)
      call check_true(error, stat == stat_ok .and. t == 1.0_dp, 'rk4 reaches t = 1 exactly')
      call check_true(error, integ%n_steps == 34, 'rk4: 33 whole steps + 1 shortened')
      t2 = 0.0_dp; y2 = y_swing; h2 = 0.03_dp
      call advance_fixed(integ, pendulum_model(par), t2, y2, h2, 33_i8, stat)
      h2 = 1.0_dp - t2
      call integ%step(pendulum_model(par), t2, y2, h2, stat)
      call check(error, y, y2, 'same as by hand', abs=1.0e-15_dp)
      call integ%reset_counters()
      t = 0.0_dp; y = y_swing; h = 0.025_dp
      call advance_to(integ, pendulum_model(par), t, y, 1.0_dp, h, stat)
      call check_true(error, t == 1.0_dp .and. integ%n_steps == 40, 'rk4: 40 whole steps')
      call make('dop853', integ, rtol=1.0e-10_dp, atol=1.0e-13_dp)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      call advance_to(integ, pendulum_model(par), t, y, 0.3_dp, h, stat)
      call check_true(error, stat == stat_ok .and. t == 0.3_dp, 'dop853 reaches t = 0.3')
      call check_true(error, h > 0.0_dp, 'dop853 returns a proposal')
      ! continuing to 1 equals going to 1 at once up to the tolerance
      call advance_to(integ, pendulum_model(par), t, y, 1.0_dp, h, stat)
      y2 = solve(integ, y_swing, 1.0_dp, 0.0_dp)
      call check(error, y, y2, 'dop853 0→0.3→1 vs 0→1', abs=1.0e-8_dp)
      ! an interval shorter than the automatic first step (HINIT gives 1.3e-4 here)
      call make('dop853', integ)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      call advance_to(integ, pendulum_model(par), t, y, 1.0e-5_dp, h, stat)
      call check_true(error, stat == stat_ok .and. t == 1.0e-5_dp, 'dop853 reaches t = 1e-5')
      call check_true(error, integ%t_new <= 1.0e-5_dp, 'dop853 did not step past t = 1e-5')
      y2 = solve(integ, y_swing, 1.0e-5_dp, 1.0e-5_dp)
      call check(error, y, y2, 'dop853 short interval', abs=1.0e-15_dp)
      ! backward: rk4 from 1 back to 0 returns to the start
      call make('rk4', integ)
      t = 0.0_dp; y = y_swing; h = 0.01_dp
      call advance_to(integ, pendulum_model(par), t, y, 1.0_dp, h, stat)
      call advance_to(integ, pendulum_model(par), t, y, 0.0_dp, h, stat)
      call check_true(error, t == 0.0_dp, 'backward to 0')
      call check(error, y, y_swing, 'rk4 forth and back', abs=1.0e-6_dp)
   end subroutine test_advance_to

   !> Sample times are t0 + k D plus t_end, for fixed-step and adaptive methods.
   subroutine test_sampled_grid(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp), allocatable :: ts(:), ss(:, :)
      integer :: stat, k
      call make('rk4', integ)
      call integrate_sampled(integ, pendulum_model(par), 1.0_dp, y_swing, 2.05_dp, 0.003_dp, 0.1_dp, ts, ss, stat)
      call check_true(error, size(ts) == 12, 'rk4: 11 grid times + t_end')
      if (allocated(error)) return
      do k = 0, 10
         call check(error, ts(k + 1), 1.0_dp + real(k, dp)*0.1_dp, 'grid time', abs=0.0_dp)
      end do
      call check(error, ts(12), 2.05_dp, 'last sample at t_end', abs=0.0_dp)
      call check(error, ss(:, 1), y_swing, 'first sample is y0', abs=0.0_dp)
      call make('dopri5', integ)
      call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 1.0_dp, 0.0_dp, 0.1_dp, ts, ss, stat)
      call check_true(error, size(ts) == 11, 'dopri5: t_end on the grid is not repeated')
      call check(error, ts(11), 1.0_dp, 'dopri5 last time', abs=0.0_dp)
      call integ%reset_counters()
      call integrate_sampled(integ, pendulum_model(par), 0.0_dp, y_swing, 1.0_dp, 0.0_dp, 0.0_dp, ts, ss, stat)
      call check_true(error, size(ts) == integ%n_steps + 1, 'every step: n_steps + 1 samples')
      call check(error, ts(size(ts)), 1.0_dp, 'every step: ends at t_end', abs=0.0_dp)
   end subroutine test_sampled_grid

   subroutine test_counters_rk4(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      real(dp) :: t, y(4), h
      integer :: stat
      call make('rk4', integ)
      t = 0.0_dp; y = y_swing; h = 0.01_dp
      call advance_fixed(integ, pendulum_model(pendulum_t()), t, y, h, 100_i8, stat)
      call check_true(error, integ%n_steps == 100, 'rk4 n_steps')
      call check_true(error, integ%n_rhs == 4*integ%n_steps, 'rk4 n_rhs = 4 n_steps')
      call check(error, t, 1.0_dp, 't after 100 steps of 0.01', abs=0.0_dp)
   end subroutine test_counters_rk4

   !> DOPRI5: 1 (first stage) + 1 (HINIT) + 6 per attempted step (FSAL); a state
   !> changed between calls costs one more evaluation; dense output costs none.
   subroutine test_counters_dopri5(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp) :: t, y(4), h, yi(4)
      integer :: stat, i
      call make('dopri5', integ, rtol=1.0e-6_dp, atol=1.0e-9_dp)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      do i = 1, 50
         call integ%step(pendulum_model(par), t, y, h, stat)
         call integ%interpolate(pendulum_model(par), t - 0.5_dp*h, yi)
      end do
      call check_true(error, integ%n_steps == 50, 'dopri5 n_steps')
      call check_true(error, integ%n_rhs == 2 + 6*(integ%n_steps + integ%n_rejected), &
                      'dopri5 n_rhs = 2 + 6 (accepted + rejected)')
      ! a large first step is rejected and counted
      call make('dopri5', integ, rtol=1.0e-6_dp, atol=1.0e-9_dp)
      t = 0.0_dp; y = y_swing; h = 1.0_dp
      call integ%step(pendulum_model(par), t, y, h, stat)
      call check_true(error, integ%n_rejected >= 1 .and. integ%n_steps == 1, 'rejections')
      call check_true(error, integ%n_rhs == 1 + 6*(1 + integ%n_rejected), 'n_rhs with rejections')
      y(3) = y(3) + 1.0e-3_dp       ! not the state of the last step: no FSAL reuse
      call integ%step(pendulum_model(par), t, y, h, stat)
      call check_true(error, integ%n_rhs == 2 + 6*(2 + integ%n_rejected), 'FSAL only on y_new')
   end subroutine test_counters_dopri5

   !> DOP853: 1 + 1 (HINIT) + 11 per attempt + 1 per accepted step, + 3 per step
   !> whose dense output is used.
   subroutine test_counters_dop853(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp) :: t, y(4), h, yi(4)
      integer :: stat, i
      call make('dop853', integ, rtol=1.0e-6_dp, atol=1.0e-9_dp)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      do i = 1, 40
         call integ%step(pendulum_model(par), t, y, h, stat)
         if (i > 20) then
            call integ%interpolate(pendulum_model(par), t - 0.5_dp*h, yi)
            call integ%interpolate(pendulum_model(par), t - 0.25_dp*h, yi)
         end if
      end do
      call check_true(error, integ%n_steps == 40, 'dop853 n_steps')
      call check_true(error, integ%n_rhs == 2 + 11*(integ%n_steps + integ%n_rejected) &
                      + integ%n_steps + 3*20, 'dop853 n_rhs = 2 + 11 attempts + accepted + 3 dense')
   end subroutine test_counters_dop853

   subroutine test_status(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      real(dp) :: t, y(4), h
      integer :: stat
      call make('dop853', integ)
      t = 0.0_dp; y = y_swing; h = 0.01_dp
      y(2) = ieee_value(1.0_dp, ieee_quiet_nan)
      call integ%step(pendulum_model(par), t, y, h, stat)
      call check_true(error, stat == stat_nonfinite, 'NaN state: stat_nonfinite')
      call check_true(error, t == 0.0_dp .and. integ%n_steps == 0, 'nothing done')
      call make('rk4', integ)
      t = 0.0_dp; y = y_swing; h = 0.0_dp
      call advance_to(integ, pendulum_model(par), t, y, 1.0_dp, h, stat)
      call check_true(error, stat == stat_step_too_small .and. t == 0.0_dp, 'rk4 with h = 0')
      call make('dopri5', integ)
      t = 1.0e20_dp; y = y_swing; h = 1.0_dp
      call integ%step(pendulum_model(par), t, y, h, stat)
      call check_true(error, stat == stat_step_too_small, 'h < 16 eps |t|')
      call check(error, y, y_swing, 'state unchanged', abs=0.0_dp)
   end subroutine test_status

   !> Linearized about q = (-π/2, -π/2): M ẍ + K x = 0, M the mass matrix there,
   !> K = diag((m1/2 + m2) g L1, m2 g L2/2). Start on one normal mode v with
   !> amplitude 1e-5 (nonlinear period shift ~1e-11) at rest: q1 = -π/2 upward
   !> crossings occur at (3/4 + k) 2π/ω. Checked for dop853 (rtol = 1e-13, dense
   !> output) and rk4 (h = 1e-3, fractional steps), to 1e-9 relative.
   subroutine test_events_period(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      type(angle_crossing_t) :: ev
      type(crossing_t), allocatable :: hits(:)
      real(dp) :: m(2, 2), k1, k2, a, b, c, lam, v(2), y(4), t, h, period
      integer :: mode, im, stat, j
      character(len=6), parameter :: names(2) = ['dop853', 'rk4   ']
      par = pendulum_t(m1=1.0_dp, m2=1.0_dp, l1=1.0_dp, l2=1.0_dp, g=9.8_dp)
      m = mass_matrix(par, [-0.5_dp*pi, -0.5_dp*pi])
      k1 = (0.5_dp*par%m1 + par%m2)*par%g*par%l1
      k2 = 0.5_dp*par%m2*par%g*par%l2
      ! det(K - λM) = 0: a λ² + b λ + c = 0
      a = m(1, 1)*m(2, 2) - m(1, 2)**2
      b = -(k1*m(2, 2) + k2*m(1, 1))
      c = k1*k2
      ev = angle_crossing_t(index=1, angle=-0.5_dp*pi, direction=1)
      do mode = 1, 2
         lam = (-b + merge(-1.0_dp, 1.0_dp, mode == 1)*sqrt(b*b - 4.0_dp*a*c))/(2.0_dp*a)
         period = 2.0_dp*pi/sqrt(lam)
         v = [k2 - lam*m(2, 2), lam*m(1, 2)]      ! second row of (K - λM) v = 0
         v = v/maxval(abs(v))
         if (v(1) < 0.0_dp) v = -v
         do im = 1, 2
            call make(trim(names(im)), integ, rtol=1.0e-13_dp, atol=1.0e-16_dp)
            y = [-0.5_dp*pi + 1.0e-5_dp*v(1), -0.5_dp*pi + 1.0e-5_dp*v(2), 0.0_dp, 0.0_dp]
            t = 0.0_dp
            h = merge(0.0_dp, 1.0e-3_dp, im == 1)
            call find_crossings(ev, integ, pendulum_model(par), t, y, 8.0_dp, h, hits, stat)
            call check_true(error, stat == stat_ok .and. size(hits) >= 2, 'crossings found')
            if (allocated(error)) return
            call check(error, hits(1)%t, 0.75_dp*period, trim(names(im))//' first crossing', &
                       rel=1.0e-9_dp)
            do j = 2, size(hits)
               call check(error, hits(j)%t - hits(j - 1)%t, period, &
                          trim(names(im))//' crossing interval', rel=1.0e-9_dp)
               call check_true(error, hits(j)%direction == 1 .and. hits(j)%qd(1) > 0.0_dp, &
                               'upward crossing')
            end do
            call check(error, hits(1)%q(1), -0.5_dp*pi, 'q1 at the crossing', abs=1.0e-15_dp)
         end do
      end do
   end subroutine test_events_period

   !> Fixed-step location is on the method's own flow: re-integrating from the step
   !> start with s = t_event - t_old lands on the section to roundoff, and the
   !> counted evaluations include the fractional steps.
   subroutine test_events_fixed(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      type(angle_crossing_t) :: ev
      type(crossing_t) :: hit
      real(dp) :: t, y(4), h, t1, y1(4), s
      integer(i8) :: before
      integer :: stat, i
      logical :: found
      ev = angle_crossing_t(index=1, angle=-0.5_dp*pi, direction=0)
      call make('rk4', integ)
      t = 0.0_dp; y = y_swing; h = 0.05_dp
      found = .false.
      do i = 1, 200
         call integ%step(pendulum_model(par), t, y, h, stat)
         before = integ%n_rhs
         call locate_crossing(ev, integ, pendulum_model(par), found, hit, stat)
         if (found) exit
      end do
      call check_true(error, found .and. stat == stat_ok, 'a crossing of q1 = -pi/2')
      if (allocated(error)) return
      call check_true(error, hit%direction == -1, 'first crossing is downward')
      call check_true(error, integ%n_rhs > before, 'fractional steps are counted')
      call check(error, hit%q(1), -0.5_dp*pi, 'q1 at the event', abs=4.0e-16_dp)
      t1 = integ%t_old; y1 = integ%y_old(:4); s = hit%t - integ%t_old
      call integ%step(pendulum_model(par), t1, y1, s, stat)
      call check(error, y1, hit%y, 'event state is the fractional step', abs=0.0_dp)
   end subroutine test_events_fixed

   !> With `wrap`, q2 ≡ 0 (mod 2π) is found on every turn of the whirling motion,
   !> and never at q2 ≡ π; the crossing times agree between rk4 and dop853.
   subroutine test_events_wrap(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      type(angle_crossing_t) :: ev
      type(crossing_t), allocatable :: h1(:), h2(:)
      real(dp) :: t, y(4), h
      integer :: stat, j
      ev = angle_crossing_t(index=2, angle=0.0_dp, direction=1, wrap=.true.)
      call make('dop853', integ, rtol=1.0e-12_dp, atol=1.0e-14_dp)
      t = 0.0_dp; y = y_whirl; h = 0.0_dp
      call find_crossings(ev, integ, pendulum_model(par), t, y, 2.0_dp, h, h1, stat)
      call make('rk4', integ)
      t = 0.0_dp; y = y_whirl; h = 1.0e-3_dp
      call find_crossings(ev, integ, pendulum_model(par), t, y, 2.0_dp, h, h2, stat, max_hits=2)
      call check_true(error, size(h1) >= 2 .and. size(h2) == 2, 'crossings on each turn')
      if (allocated(error)) return
      call check_true(error, t >= h2(2)%t .and. t - h2(2)%t <= 1.0e-3_dp .and. &
                      abs(integ%t_new - t) <= 1.0e-15_dp, &
                      'max_hits stops at the end of the step of the last hit')
      do j = 1, size(h1)
         call check(error, modulo(h1(j)%q(2) + pi, 2.0_dp*pi) - pi, 0.0_dp, 'q2 = 0 mod 2 pi', &
                    abs=1.0e-12_dp)
         if (j > 1) call check_true(error, h1(j)%q(2) > h1(j - 1)%q(2) + 6.0_dp, 'one a turn')
      end do
      call check(error, h2(1)%t, h1(1)%t, 'rk4 vs dop853 crossing time', abs=1.0e-9_dp)
   end subroutine test_events_wrap
end module test_integrators
