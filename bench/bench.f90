!> dpend-bench: cost of the integrators on the chapter's pendulum, one figure a line
!> as `key: value unit`. Each figure is timed (wall clock, system_clock int64) over
!> at least 0.3 s; a checksum of the final states defeats dead-code elimination.
!> Run in release (dpend-bench is an fpm example; flags from scripts/flags.sh):
!>   . scripts/flags.sh
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS"
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS" -- --batch
!> The methods come from the registry (dpend_method_registry): every fixed-step
!> method is timed at h = 0.01 s, every method enters the work-precision table.
!> The batch kernel of the sweep (and the single-trajectory rk4_ns_per_step) is timed
!> by `bench_batch`. The chain of N unit rods (dpend_chain) is timed with rk4 and
!> gauss6 for N = 3, 5, 10, 20 (`chainN_METHOD_ns_per_step`), so that the cost's
!> growth with N shows.
!> `dpend-bench --chain-energy` prints instead only the energy figures of gauss6 over
!> 10⁶ steps of the chains of 3 and 5 links (some seconds each, release);
!> `dpend-bench --batch` only the figures of the batch kernel (`bench_batch`) and of
!> the chain lanes of N = 3, 5, 8 links (`bench_chain`);
!> `dpend-bench --indicators` only the cost of the sweep's per-pixel indicators and
!> parameter axes (`bench_indicators`);
!> `dpend-bench --map-file` only the cost of a map's file (`bench_map_file`).
program bench
   use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options, int64, &
                                            output_unit, error_unit
   use bench_batch, only: run_batch_benchmarks
   use bench_indicators, only: run_indicator_benchmarks
   use bench_map_file, only: run_map_file_benchmarks
   use bench_chain, only: run_chain_lane_benchmarks
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, rhs_qqdot
   use dpend_model, only: model_t
   use dpend_model_factory, only: new_model, model_spec, model_spec_t
   use dpend_cli, only: to_str
   use dpend_error, only: error_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods
   implicit none

   real(dp), parameter :: pi = acos(-1.0_dp)
   real(dp), parameter :: min_seconds = 0.3_dp
   !> a large regular swing released at rest
   real(dp), parameter :: y0(4) = [-0.5_dp*pi + 1.0_dp, -0.5_dp*pi + 1.0_dp, 0.0_dp, 0.0_dp]
   !> links of the timed chains
   integer, parameter :: chain_links(4) = [3, 5, 10, 20]
   real(dp) :: checksum, ns, rhs_per_step, rk4_ns
   integer :: i, j
   character(len=:), allocatable :: name
   character(len=32) :: arg

   checksum = 0.0_dp
   if (command_argument_count() > 0) then
      call get_command_argument(1, arg)
      if ((trim(arg) /= '--chain-energy' .and. trim(arg) /= '--batch' .and. &
           trim(arg) /= '--indicators' .and. trim(arg) /= '--map-file') .or. &
          command_argument_count() > 1) then
         write (error_unit, '(a)') 'dpend-bench: argument "'//trim(arg)// &
            '" refused; accepted: none, --chain-energy, --batch, --indicators or --map-file'
         stop 2, quiet=.true.
      end if
      if (trim(arg) == '--map-file') then
         write (*, '(a)') 'compiler: '//compiler_version()
         write (*, '(a)') 'flags: '//compiler_options()
         call run_map_file_benchmarks(output_unit)
         stop
      end if
      if (trim(arg) == '--indicators') then
         write (*, '(a)') 'compiler: '//compiler_version()
         write (*, '(a)') 'flags: '//compiler_options()
         call run_indicator_benchmarks(output_unit)
         stop
      end if
      if (trim(arg) == '--batch') then
         write (*, '(a)') 'compiler: '//compiler_version()
         write (*, '(a)') 'flags: '//compiler_options()
         call run_batch_benchmarks(output_unit)
         call run_chain_lane_benchmarks(output_unit)   ! the chain lanes
         stop
      end if
      call chain_energy(3)
      call chain_energy(5)
      write (*, '(a, es24.16)') 'checksum: ', checksum
      stop
   end if
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
   do i = 1, size(chain_links)
      do j = 1, 2
         name = trim(merge('rk4   ', 'gauss6', j == 1))
         ns = time_chain(name, chain_links(i), 1.0e-3_dp, rhs_per_step)
         call report('chain'//to_str(chain_links(i))//'_'//name//'_ns_per_step', ns, 'ns')
         if (j == 2) call report('chain'//to_str(chain_links(i))//'_'//name// &
                                 '_rhs_per_step', rhs_per_step, '')
      end do
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
      class(model_t), allocatable :: model  ! the chapter's pendulum (factory defaults)
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
      call new_model(model_spec('pendulum'), model, error)
      if (allocated(error)) error stop 'the factory refused the pendulum'
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
      class(model_t), allocatable :: model  ! the chapter's pendulum (factory defaults)
      real(dp) :: t, y(4), hh, start, elapsed
      integer(i8) :: nsteps, i
      integer :: stat
      call new_model(model_spec('pendulum'), model, error)
      if (allocated(error)) error stop 'the factory refused the pendulum'
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

   !> The chain of n unit rods (1 kg, 1 m, g = 9.8) from a fixed generic state: the
   !> links at q_i = −π/2 + 0.8 sin(1.7 i) (rad) with q̇_i = 0.5 cos(2.3 i) (rad/s).
   subroutine chain_start(n, chain, q, qd)
      integer, intent(in) :: n                       !! links
      class(model_t), allocatable, intent(out) :: chain  !! the chain (from the factory)
      real(dp), intent(out) :: q(n), qd(n)           !! its initial angles, rates
      type(error_t), allocatable :: error
      type(model_spec_t) :: spec
      integer :: i
      spec = model_spec('pendulum')
      call spec%set('links', [real(n, dp)])
      call spec%set('m', [(1.0_dp, i=1, n)])
      call spec%set('l', [(1.0_dp, i=1, n)])
      call spec%set('g', [9.8_dp])
      spec%general = .true.   ! the chain's formulation for every n (also 2)
      call new_model(spec, chain, error)
      if (allocated(error)) error stop 'the factory refused the bench chain'
      do i = 1, n
         q(i) = -0.5_dp*pi + 0.8_dp*sin(1.7_dp*i)
         qd(i) = 0.5_dp*cos(2.3_dp*i)
      end do
   end subroutine chain_start

   !> ns per step of method `name` (fixed step h) on the chain of n links from
   !> `chain_start`; the number of steps doubles until the run lasts 0.2 s.
   !> Also returns the right-hand-side evaluations per step.
   real(dp) function time_chain(name, n, h, n_rhs_per_step) result(ns_per_step)
      character(len=*), intent(in) :: name
      integer, intent(in) :: n
      real(dp), intent(in) :: h
      real(dp), intent(out) :: n_rhs_per_step
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      class(model_t), allocatable :: chain
      real(dp) :: t, y(2*n), y0(2*n), q(n), qd(n), hh, start, elapsed
      integer(i8) :: nsteps, i
      integer :: stat
      call new_integrator(name, integ, error)
      if (allocated(error)) error stop 'unknown method'
      call chain_start(n, chain, q, qd)
      y0 = integ%to_internal(chain, q, qd)
      nsteps = 100
      do
         call integ%reset_counters()
         call integ%clear_step()
         t = 0.0_dp; y = y0
         start = now()
         do i = 1, nsteps
            hh = h
            call integ%step(chain, t, y, hh, stat)
            if (stat /= stat_ok) error stop 'chain step failed'
         end do
         elapsed = now() - start
         checksum = checksum + sum(y)
         if (elapsed >= 0.2_dp) exit
         nsteps = 2*nsteps
      end do
      ns_per_step = 1.0e9_dp*elapsed/real(integ%n_steps, dp)
      n_rhs_per_step = real(integ%n_rhs, dp)/real(integ%n_steps, dp)
   end function time_chain

   !> gauss6 at h = 1 ms over 10⁶ steps (1000 s) of the chain of n unit links
   !> released horizontally (q_i = 0, q̇_i = 0; E0 = 0, so the unit is the model's
   !> energy scale Σ G_i): the largest relative energy error over the first 10⁵
   !> steps, over all 10⁶, over the last 10⁵, and the error at the end, sampled
   !> every 10 steps.
   subroutine chain_energy(n)
      integer, intent(in) :: n  !! links
      integer, parameter :: nsteps = 1000000, part = nsteps/10
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      class(model_t), allocatable :: chain
      real(dp) :: t, y(2*n), q(n), qd(n), hh, e0, scale, de, de_first, de_all, de_last, &
                  start
      integer :: k, stat
      character(len=:), allocatable :: key
      call new_integrator('gauss6', integ, error)
      call chain_start(n, chain, q, qd)
      q = 0.0_dp; qd = 0.0_dp
      e0 = chain%energy(0.0_dp, [q, qd])
      scale = chain%energy_scale(e0)
      y = integ%to_internal(chain, q, qd)
      t = 0.0_dp; de_first = 0.0_dp; de_all = 0.0_dp; de_last = 0.0_dp; de = 0.0_dp
      start = now()
      do k = 1, nsteps
         hh = 1.0e-3_dp
         call integ%step(chain, t, y, hh, stat)
         if (stat /= stat_ok) then
            write (*, '(a)') 'chain'//to_str(n)//'_gauss6_energy_1e6: failed at step '// &
               to_str(k)
            return
         end if
         if (mod(k, 10) /= 0) cycle
         call integ%to_physical(chain, y, q, qd)
         de = abs(chain%energy(t, [q, qd]) - e0)/scale
         de_all = max(de_all, de)
         if (k <= part) de_first = max(de_first, de)
         if (k > nsteps - part) de_last = max(de_last, de)
      end do
      checksum = checksum + sum(y)
      key = 'chain'//to_str(n)//'_gauss6_h1e-3_'
      write (*, '(a, es9.2)') key//'max_rel_energy_error_first_1e5: ', de_first
      write (*, '(a, es9.2)') key//'max_rel_energy_error_last_1e5: ', de_last
      write (*, '(a, es9.2)') key//'max_rel_energy_error_1e6: ', de_all
      write (*, '(a, es9.2)') key//'rel_energy_error_at_1e6: ', de
      write (*, '(a, f0.1, a)') key//'seconds_1e6: ', now() - start, ' s'
   end subroutine chain_energy

   !> ns per evaluation of rhs_qqdot along a slowly varying state.
   real(dp) function time_rhs() result(ns)
      type(pendulum_t) :: par
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
