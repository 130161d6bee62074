!> Benchmarks of the sweep's per-pixel indicators (figures in docs/performance.md): the
!> cost per trajectory-step of the batch kernel with each indicator against the flip
!> time alone, one thread, and of a sweep over parameters (m2/m1, l2/l1: each pixel
!> its own constants, `lane_coef_t`) against one over initial values (theta1,
!> theta2), flip maps on one thread and on all threads, MEGNO maps on one thread.
!> The indicator figures are the least of twelve interleaved rounds (flip, λ1, MEGNO,
!> FLI, SALI, GALI_2, then again), so that a slow spell of a shared machine does not
!> fall on one indicator only; then the same on all threads at once (each its own
!> batch; six rounds), `..._all_threads`.
!> Printed one per line as `key: value unit`, with the CPU and the load average.
!> Run in the release profile:
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS" -- --indicators
module bench_indicators
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_pendulum, only: pendulum_t
   use dpend_lane_batch, only: batch_options_t, batch_result_t, stop_end
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_sweep_settings, only: sweep_config_t, sweep_defaults, validate_sweep
   use dpend_sweep_gpu, only: resolve_device
   use dpend_sweep_setup, only: sweep_setup_t, build_setup
   use dpend_sweep_engine, only: compute_block
   use dpend_progress, only: wall_seconds
   use bench_batch, only: load_average
   implicit none
   private
   public :: run_indicator_benchmarks

   !> least wall time of one timed run [s]: the work doubles until a run takes it
   real(dp), parameter :: min_seconds = 0.3_dp
   !> least wall time of one run of an indicator figure [s] (twelve interleaved rounds)
   real(dp), parameter :: round_seconds = 0.1_dp
   !> trajectories of the indicator figures' batch
   integer, parameter :: batch_size = 256

contains

   !> Print the figures to `unit`: each as wall-clock ns and as process CPU ns (which
   !> other processes on a shared machine do not inflate), ratios from both.
   subroutine run_indicator_benchmarks(unit)
      integer, intent(in) :: unit  !! where to print
      character(len=8), parameter :: names(6) = [character(len=8) :: 'flip', 'lambda1', &
                                                 'megno', 'fli', 'sali', 'gali2']
      !> interleaved rounds of the indicator figures
      integer, parameter :: rounds = 12
      real(dp) :: base(2), ns(2), ic(2), par(2)
      real(dp), allocatable :: best(:, :)
      integer, allocatable :: steps(:)
      integer :: k, nthreads, t, r
      character(len=:), allocatable :: tag
      nthreads = omp_get_max_threads()
      write (unit, '(a, a)') 'cpu: ', cpu_model()
      write (unit, '(a, a)') 'load_average_1min_at_start: ', load_average()
      call omp_set_num_threads(1)
      ! interleaved rounds, the least time of each: a slow spell of a shared machine
      ! falls on every indicator alike instead of on one of them
      allocate (steps(size(names)), best(2, size(names)))
      do k = 1, size(names)
         steps(k) = calibrated_steps(trim(names(k)))
      end do
      best = huge(1.0_dp)
      do r = 1, rounds
         do k = 1, size(names)
            best(:, k) = min(best(:, k), indicator_ns(trim(names(k)), steps(k)))
         end do
      end do
      base = best(:, 1)
      do k = 1, size(names)
         ns = best(:, k)
         call put('indicator_'//trim(names(k)), '_ns_per_traj_step_1thread', ns, ' ns')
         if (k > 1) call put('indicator_'//trim(names(k)), '_cost_vs_flip', ns/base, ' x')
      end do
      ! the same on all threads at once, each its own batch (rounds interleaved too):
      ! ns per trajectory-step of the threads together, ratios to flip on as many
      if (nthreads > 1) then
         call omp_set_num_threads(nthreads)
         best = huge(1.0_dp)
         do r = 1, rounds/2
            do k = 1, size(names)
               best(:, k) = min(best(:, k), indicator_ns_all(trim(names(k)), steps(k)))
            end do
         end do
         base = best(:, 1)
         do k = 1, size(names)
            ns = best(:, k)
            call put('indicator_'//trim(names(k)), '_ns_per_traj_step_all_threads', ns, ' ns')
            if (k > 1) call put('indicator_'//trim(names(k)), '_cost_vs_flip_all_threads', &
                                ns/base, ' x')
         end do
         call omp_set_num_threads(1)
      end if
      ! flip maps (run to t_end) over initial values and over (m2/m1, l2/l1), where
      ! every pixel has its own parameters: one thread, then all threads
      do t = 1, 2
         call omp_set_num_threads(merge(1, nthreads, t == 1))
         tag = trim(merge('1thread    ', 'all_threads', t == 1))
         ic = map_ns('theta1', 'theta2', 'flip')
         par = map_ns('m2/m1', 'l2/l1', 'flip')
         call put('flip_map_initial_values', '_ns_per_traj_step_'//tag, ic, ' ns')
         call put('flip_map_parameters', '_ns_per_traj_step_'//tag, par, ' ns')
         call put('flip_map_parameters', '_cost_vs_initial_values_'//tag, par/ic, ' x')
      end do
      write (unit, '(a, i0)') 'threads: ', nthreads
      call omp_set_num_threads(1)
      ! the same with MEGNO, one thread
      ic = map_ns('theta1', 'theta2', 'megno')
      par = map_ns('m2/m1', 'l2/l1', 'megno')
      call put('megno_map_initial_values', '_ns_per_traj_step_1thread', ic, ' ns')
      call put('megno_map_parameters', '_ns_per_traj_step_1thread', par, ' ns')
      call put('megno_map_parameters', '_cost_vs_initial_values', par/ic, ' x')
      call omp_set_num_threads(nthreads)
   contains
      !> Print `key` + `tail` with the wall figure v(1), then `key`_cpu + `tail` with
      !> the CPU figure v(2).
      subroutine put(key, tail, v, unit_name)
         character(len=*), intent(in) :: key, tail, unit_name
         real(dp), intent(in) :: v(2)
         write (unit, '(a, f0.2, a)') key//tail//': ', v(1), unit_name
         write (unit, '(a, f0.2, a)') key//'_cpu'//tail//': ', v(2), unit_name
      end subroutine put
   end subroutine run_indicator_benchmarks

   !> The steps per run for the indicator `name`: doubled from 250 until a run of
   !> `indicator_ns` takes round_seconds.
   integer function calibrated_steps(name) result(n_steps)
      character(len=*), intent(in) :: name  !! flip, lambda1, megno, fli, sali, gali2
      real(dp) :: ns(2)
      n_steps = 250
      do
         ns = indicator_ns(name, n_steps)
         if (.not. (ns(1) > 0.0_dp)) exit   ! results not finite: -1 ns (printed)
         if (ns(1)*1e-9_dp*real(n_steps, dp)*real(batch_size, dp) >= round_seconds) exit
         n_steps = 2*n_steps
      end do
   end function calibrated_steps

   !> ns per trajectory-step of one run of integrate_batch with the indicator
   !> `name` (batch_size chaotic trajectories run to the end, step 1e-3 s, n_steps
   !> steps): (wall clock, process CPU time).
   function indicator_ns(name, n_steps) result(ns)
      character(len=*), intent(in) :: name  !! flip, lambda1, megno, fli, sali, gali2
      integer, intent(in) :: n_steps        !! steps per trajectory
      real(dp) :: ns(2), t0, c0, c1
      call cpu_time(c0)
      t0 = wall_seconds()
      if (.not. (one_batch(name, n_steps) > -1e300_dp)) then   ! keep the results alive
         ns = -1.0_dp
         return
      end if
      ns(1) = wall_seconds() - t0
      call cpu_time(c1)
      ns(2) = c1 - c0
      ns = ns/(real(batch_size, dp)*real(n_steps, dp))*1e9_dp
   end function indicator_ns

   !> `indicator_ns` with every thread running its own batch at once: ns per
   !> trajectory-step of all the threads' trajectories together (wall clock), and
   !> the process CPU time per trajectory-step.
   function indicator_ns_all(name, n_steps) result(ns)
      character(len=*), intent(in) :: name  !! flip, lambda1, megno, fli, sali, gali2
      integer, intent(in) :: n_steps        !! steps per trajectory
      real(dp) :: ns(2), t0, c0, c1, check
      integer :: nt
      nt = omp_get_max_threads()
      check = 0
      call cpu_time(c0)
      t0 = wall_seconds()
      !$omp parallel reduction(+:check)
      check = one_batch(name, n_steps)
      !$omp end parallel
      ns(1) = wall_seconds() - t0
      call cpu_time(c1)
      ns(2) = c1 - c0
      ns = ns/(real(nt, dp)*real(batch_size, dp)*real(n_steps, dp))*1e9_dp
      if (.not. (check > -1e300_dp)) ns = -1.0_dp   ! keep the results alive
   end function indicator_ns_all

   !> One run of integrate_batch with the indicator `name` (batch_size chaotic
   !> trajectories run to the end, step 1e-3 s, n_steps steps): the sum of the final
   !> angles (NaN if a result is not finite).
   real(dp) function one_batch(name, n_steps) result(check)
      character(len=*), intent(in) :: name  !! flip, lambda1, megno, fli, sali, gali2
      integer, intent(in) :: n_steps        !! steps per trajectory
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      real(dp) :: y0(4, batch_size)
      integer :: j
      do j = 1, batch_size   ! angles well above the flip bound: full-length chaotic runs
         y0(:, j) = [1.0_dp + 1e-3_dp*j, 1.5_dp, 0.0_dp, 0.0_dp]
      end do
      opt%h = 1e-3_dp
      opt%stop_rule = stop_end
      opt%lyapunov = name == 'lambda1'
      select case (name)
      case ('megno', 'fli'); opt%vectors = 1
      case ('sali', 'gali2'); opt%vectors = 2
      end select
      opt%n_steps = n_steps
      call integrate_batch(par, opt, y0, res)
      check = sum(res%final(1, :))
   end function one_batch

   !> ns per trajectory-step of a 32 x 32 map of `indicator` (flip or megno) over the
   !> axes ax1, ax2 computed in memory, blocks of 64 over the threads (runs to t_end;
   !> the time doubled until it takes min_seconds; the steps counted are those the
   !> trajectories took, `res%steps`): least of three runs, (wall clock, process CPU
   !> time summed over the threads).
   function map_ns(ax1, ax2, indicator) result(ns)
      character(len=*), intent(in) :: ax1, ax2   !! axes
      character(len=*), intent(in) :: indicator  !! flip or megno
      real(dp) :: ns(2)
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(error_t), allocatable :: error
      real(dp) :: t(2)
      integer(i8) :: steps
      integer :: k
      cfg = sweep_defaults()
      cfg%n1 = 32; cfg%n2 = 32
      cfg%axis1 = ax1; cfg%axis2 = ax2
      cfg%stop_at = 'end'
      if (ax1 == 'm2/m1') then
         cfg%min1 = 0.2_dp; cfg%max1 = 4.0_dp; cfg%min2 = 0.2_dp; cfg%max2 = 4.0_dp
         cfg%run%q(1:2) = 0.0_dp
      end if
      cfg%indicator = indicator
      cfg%run%dt = 0.01_dp
      cfg%run%t_end = 1.0_dp
      cfg%block = 64
      ns = -1.0_dp
      call validate_sweep(cfg, error)   ! builds the model (the factory)
      if (.not. allocated(error)) call resolve_device(cfg, error)
      if (allocated(error)) return
      do
         call build_setup(cfg, setup, error)
         if (allocated(error)) return
         t = timed_map()
         if (t(1) >= min_seconds) exit
         cfg%run%t_end = 2.0_dp*cfg%run%t_end
      end do
      ns = t
      do k = 1, 2
         ns = min(ns, timed_map())
      end do
      ns = ns/real(max(steps, 1_i8), dp)*1e9_dp
   contains
      !> One run of the map: (wall, CPU) seconds; its steps in `steps`.
      function timed_map() result(tt)
         real(dp) :: tt(2), t0, c0, c1
         integer :: b
         steps = 0
         call cpu_time(c0)
         t0 = wall_seconds()
         !$omp parallel do schedule(dynamic, 1) reduction(+:steps)
         do b = 1, setup%nblocks
            steps = steps + block_steps(b)
         end do
         !$omp end parallel do
         tt(1) = wall_seconds() - t0
         call cpu_time(c1)
         tt(2) = c1 - c0
      end function timed_map

      !> The RK4 steps of block b's trajectories.
      integer(i8) function block_steps(b)
         integer, intent(in) :: b
         type(batch_result_t) :: res
         call compute_block(setup, b, res)
         block_steps = sum(int(res%steps, i8))
      end function block_steps
   end function map_ns

   !> The CPU's model name from /proc/cpuinfo ('?' if unreadable).
   function cpu_model() result(s)
      character(len=:), allocatable :: s
      character(len=256) :: line
      integer :: u, stat
      s = '?'
      open (newunit=u, file='/proc/cpuinfo', status='old', action='read', iostat=stat)
      if (stat /= 0) return
      do
         read (u, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (index(line, 'model name') == 1) then
            s = trim(adjustl(line(index(line, ':') + 1:)))
            exit
         end if
      end do
      close (u)
   end function cpu_model
end module bench_indicators
