!> Benchmarks of the batch RK4 kernel (docs/sweep.md): printed figures, one per line
!> as `key: value unit`. Run in the release profile (dpend-bench is an fpm example):
!>   . scripts/flags.sh
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS" -- --batch
module bench_batch
   use, intrinsic :: iso_fortran_env, only: output_unit, compiler_options
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_pendulum, only: pendulum_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: new_model, model_spec
   use dpend_rk_explicit, only: rk4_t
   use dpend_lane_batch, only: batch_options_t, batch_result_t, lane_width, stop_end, &
      st_cannot_flip
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_sweep_settings, only: sweep_config_t, sweep_defaults, validate_sweep
   use dpend_sweep_gpu, only: resolve_device
   use dpend_sweep_setup, only: sweep_setup_t, build_setup
   use dpend_sweep_engine, only: compute_block
   use dpend_progress, only: wall_seconds
   implicit none
   private
   public :: run_batch_benchmarks, instruction_set, load_average

contains

   !> Print the benchmark figures of the batch kernel to `unit`.
   subroutine run_batch_benchmarks(unit)
      integer, intent(in) :: unit  !! where to print
      integer :: nthreads, width
      real(dp) :: ns1, nsn, single, c1, cn
      character(len=:), allocatable :: isa
      nthreads = omp_get_max_threads()
      write (unit, '(a, a)') 'load_average_1min_at_start: ', load_average()
      single = single_trajectory_ns()
      write (unit, '(a, f0.2, a)') 'rk4_ns_per_step: ', single, ' ns'
      write (unit, '(a, i0)') 'batch_lane_width: ', lane_width
      call instruction_set(isa, width)
      write (unit, '(a, a)') 'built_for_instruction_set: ', isa
      write (unit, '(a, i0, a)') 'kernel_vector_width: ', width, ' doubles'
      ! best of three: the machine may be shared
      call omp_set_num_threads(1)
      call best_of_3(8, ns1, c1)
      write (unit, '(a, f0.2, a)') 'batch_rk4_ns_per_traj_step_1thread: ', ns1, ' ns'
      call omp_set_num_threads(nthreads)
      call best_of_3(8*nthreads, nsn, cn)
      write (unit, '(a, f0.2, a)') 'batch_rk4_ns_per_traj_step_all_threads: ', nsn, ' ns'
      write (unit, '(a, i0)') 'threads: ', nthreads
      write (unit, '(a, f0.2, a)') 'batch_rk4_ns_per_traj_step_per_core: ', nsn*nthreads, ' ns'
      write (unit, '(a, f0.1, a)') 'batch_speedup_vs_single_trajectory: ', single/ns1, ' x'
      write (unit, '(a, f0.1, a)') 'parallel_efficiency: ', 100.0_dp*ns1/(nsn*nthreads), ' %'
      ! CPU time of the process: insensitive to other processes taking a core
      write (unit, '(a, f0.2, a)') 'batch_rk4_cpu_ns_per_traj_step_1thread: ', c1, ' ns'
      write (unit, '(a, f0.2, a)') 'batch_rk4_cpu_ns_per_traj_step_all_threads: ', cn, ' ns'
      write (unit, '(a, f0.1, a)') 'parallel_efficiency_cpu_time: ', 100.0_dp*c1/cn, ' %'
      call classic_map(unit)
      flush (unit)
   end subroutine run_batch_benchmarks

   !> The vector instruction set this program was compiled for, from the options
   !> gfortran records (`compiler_options`; -march=native is expanded there into
   !> -march=CPU -mavx2 -mno-avx512f ...), and the vector width of the batch kernel
   !> in doubles: the kernel's loops vectorize with any of them (-fopt-info-vec,
   !> docs/sweep.md); gfortran 12 uses 256-bit vectors on AVX-512 CPUs unless
   !> -mprefer-vector-width=512 is given.
   subroutine instruction_set(isa, width)
      character(len=:), allocatable, intent(out) :: isa  !! e.g. 'avx2 (-march=znver3)'
      integer, intent(out) :: width                      !! doubles per vector
      character(len=:), allocatable :: opts, march
      integer :: i, j
      opts = ' '//compiler_options()//' '
      march = 'x86-64'
      i = index(opts, ' -march=')
      if (i > 0) then
         j = index(opts(i + 1:), ' ')
         march = opts(i + 8:i + j - 1)
      end if
      if (has(' -mavx512f ') .or. index(march, 'avx512') > 0 .or. march == 'x86-64-v4') then
         isa = 'avx512'
         width = 4
         if (has(' -mprefer-vector-width=512 ')) width = 8
      else if (has(' -mavx2 ') .or. march == 'x86-64-v3' .or. march == 'haswell' .or. &
               index(march, 'znver') > 0 .or. index(march, 'lake') > 0) then
         isa = 'avx2'
         width = 4
      else if (has(' -mavx ')) then
         isa = 'avx'
         width = 4
      else
         isa = 'sse2'
         width = 2
      end if
      isa = isa//' (-march='//march//')'
   contains
      logical function has(flag)
         character(len=*), intent(in) :: flag
         has = index(opts, flag) > 0
      end function has
   end subroutine instruction_set

   !> The first field of /proc/loadavg ('?' if unreadable).
   function load_average() result(s)
      character(len=:), allocatable :: s
      character(len=64) :: line
      integer :: u, stat
      s = '?'
      open (newunit=u, file='/proc/loadavg', status='old', action='read', iostat=stat)
      if (stat /= 0) return
      read (u, '(a)', iostat=stat) line
      close (u)
      if (stat == 0) s = line(:index(line, ' ') - 1)
   end function load_average

   !> ns per step of the library's one-trajectory rk4_t (chapter parameters).
   real(dp) function single_trajectory_ns() result(ns)
      type(rk4_t) :: rk
      class(model_t), allocatable :: model  ! the chapter's pendulum (factory defaults)
      type(error_t), allocatable :: error
      real(dp) :: t, y(4), h, t0
      integer :: k, stat
      integer, parameter :: n = 2000000
      call new_model(model_spec('pendulum'), model, error)
      if (allocated(error)) error stop 'the factory refused the pendulum'
      y = [0.5_dp, -1.0_dp, 0.0_dp, 0.0_dp]
      t = 0.0_dp
      t0 = wall_seconds()
      do k = 1, n
         h = 1e-3_dp
         call rk%step(model, t, y, h, stat)
      end do
      ns = (wall_seconds() - t0)/real(n, dp)*1e9_dp
      if (.not. (abs(y(1)) < 1e30_dp)) ns = -1.0_dp   ! keep the result alive
   end function single_trajectory_ns

   !> Best (least) wall and CPU ns per trajectory-step of three runs of `batch_ns`.
   subroutine best_of_3(nblocks, wall, cpu)
      integer, intent(in) :: nblocks   !! blocks of work
      real(dp), intent(out) :: wall    !! wall ns per trajectory-step
      real(dp), intent(out) :: cpu     !! process CPU ns per trajectory-step
      real(dp) :: w, c
      integer :: k
      wall = huge(1.0_dp); cpu = huge(1.0_dp)
      do k = 1, 3
         w = batch_ns(nblocks, c)
         wall = min(wall, w); cpu = min(cpu, c)
      end do
   end subroutine best_of_3

   !> ns per trajectory-step of integrate_batch over `nblocks` blocks of 1024
   !> trajectories x 2000 steps run to the end (no early stop), OpenMP over blocks.
   real(dp) function batch_ns(nblocks, cpu_ns) result(ns)
      integer, intent(in) :: nblocks  !! blocks of work
      real(dp), intent(out) :: cpu_ns !! process CPU time per trajectory-step [ns]
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      integer, parameter :: nb = 1024, steps = 2000
      real(dp) :: t0, check, c0, c1
      integer :: b
      opt%h = 1e-3_dp
      opt%n_steps = steps
      opt%stop_rule = stop_end
      check = 0.0_dp
      call cpu_time(c0)
      t0 = wall_seconds()
      !$omp parallel do schedule(dynamic, 1) reduction(+:check)
      do b = 1, nblocks
         check = check + one_block(b)
      end do
      !$omp end parallel do
      ns = (wall_seconds() - t0)/(real(nblocks, dp)*nb*steps)*1e9_dp
      call cpu_time(c1)
      cpu_ns = (c1 - c0)/(real(nblocks, dp)*nb*steps)*1e9_dp
      if (.not. (check > -1e300_dp)) ns = -1.0_dp
   contains
      real(dp) function one_block(b) result(s)
         integer, intent(in) :: b
         type(batch_result_t) :: res
         real(dp) :: y0(4, nb)
         integer :: j
         do j = 1, nb   ! angles well above the flip bound: full-length chaotic runs
            y0(:, j) = [1.0_dp + 1e-3_dp*j, 1.5_dp + 1e-3_dp*b, 0.0_dp, 0.0_dp]
         end do
         call integrate_batch(par, opt, y0, res)
         s = sum(res%final(1, :))
      end function one_block
   end function batch_ns

   !> The classic flip map at 128 x 128 (theta1, theta2 in [-3, 3], rest, chapter
   !> parameters, t_end = 1000 sqrt(L/g), step 0.005 sqrt(L/g) as data/sweep_classic.nml),
   !> computed in memory on all threads. The rate counts the integrated trajectories
   !> only: the pixels below both flip energy bounds (status 3, st_cannot_flip) are
   !> never integrated and are reported apart (`classic_map_skipped_by_energy_bound`).
   subroutine classic_map(unit)
      integer, intent(in) :: unit
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(error_t), allocatable :: error
      real(dp) :: t0, secs
      integer(i8) :: steps
      integer :: b, skipped
      cfg = sweep_defaults()
      cfg%n1 = 128; cfg%n2 = 128
      cfg%run%t_end = 1000.0_dp
      cfg%run%dt = 0.005_dp
      cfg%stop_at = 'either'
      cfg%stats = .true.
      cfg%block = 512
      call validate_sweep(cfg, error)   ! builds the model (the factory)
      if (.not. allocated(error)) call resolve_device(cfg, error)
      if (.not. allocated(error)) call build_setup(cfg, setup, error)
      if (allocated(error)) then
         write (unit, '(a)') 'classic_map: '//error%message
         return
      end if
      steps = 0
      skipped = 0
      t0 = wall_seconds()
      !$omp parallel do schedule(dynamic, 1) reduction(+:steps, skipped)
      do b = 1, setup%nblocks
         call block_steps(b, steps, skipped)
      end do
      !$omp end parallel do
      secs = wall_seconds() - t0
      write (unit, '(a, f0.1, a)') 'classic_map_128_seconds: ', secs, ' s'
      ! the rate and the mean count integrated trajectories only (not the skipped ones)
      write (unit, '(a, i0, a, i0)') 'classic_map_skipped_by_energy_bound: ', skipped, &
         ' trajectories, not integrated, of ', setup%n
      write (unit, '(a, i0, a)') 'classic_map_integrated: ', setup%n - skipped, ' trajectories'
      write (unit, '(a, f0.1, a)') 'classic_map_trajectories_per_second: ', &
         real(setup%n - skipped, dp)/secs, ' 1/s'
      write (unit, '(a, f0.1, a)') 'classic_map_mean_steps_per_trajectory: ', &
         real(steps, dp)/real(max(setup%n - skipped, 1), dp), ' steps'
      write (unit, '(a, f0.1, a)') 'classic_map_1024_estimate: ', &
         secs*64.0_dp/60.0_dp, ' min'
   contains
      !> Block b: add its RK4 steps and its pixels skipped by the energy bound.
      subroutine block_steps(b, steps, skipped)
         integer, intent(in) :: b
         integer(i8), intent(inout) :: steps
         integer, intent(inout) :: skipped
         type(batch_result_t) :: res
         call compute_block(setup, b, res)
         steps = steps + sum(int(res%steps, i8))
         skipped = skipped + count(res%status == st_cannot_flip)
      end subroutine block_steps
   end subroutine classic_map

end module bench_batch
