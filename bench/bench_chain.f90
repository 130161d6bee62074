!> Benchmarks of the chain lanes (issue 27, dpend_chain_lanes): ns per trajectory-step
!> of the flip-map kernel of the chain of N = 3, 5 and 8 unit rods, on one thread, and
!> as ratios to the two-link batch kernel (dpend_pendulum_lanes) timed in the same run
!> (the machine may be shared: ratios of one run are the comparable figures); the
!> per-trajectory path (the registry's rk4, dpend_trajectory_batch) of N = 3 for
!> reference. One figure a line as `key: value unit`. Run in the release profile:
!>   . scripts/flags.sh
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS"
module bench_chain
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_pendulum, only: pendulum_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_pendulum_lanes, only: batch_options_t, batch_result_t, integrate_batch, stop_end
   use dpend_chain_lanes, only: integrate_chain_lanes
   use dpend_trajectory_batch, only: integrate_trajectories
   use dpend_methods, only: new_integrator
   use dpend_integrator, only: integrator_t
   use dpend_progress, only: wall_seconds
   implicit none
   private
   public :: run_chain_lane_benchmarks

   real(dp), parameter :: pi = acos(-1.0_dp)
   integer, parameter :: steps = 1000   !! steps per trajectory (run to the end)
   integer, parameter :: nb = 512       !! trajectories per timed batch

contains

   !> Print the chain lanes' figures to `unit`.
   subroutine run_chain_lane_benchmarks(unit)
      integer, intent(in) :: unit  !! where to print
      integer, parameter :: links(3) = [3, 5, 8]
      real(dp) :: two, ns
      integer :: nthreads, k
      nthreads = omp_get_max_threads()
      call omp_set_num_threads(1)
      two = best(two_link_ns)
      write (unit, '(a, f0.2, a)') 'chain_lanes_two_link_kernel_ns_per_traj_step: ', two, ' ns'
      do k = 1, size(links)
         ns = best(chain_ns, links(k))
         write (unit, '(a, i0, a, f0.2, a)') 'chain_lanes_n', links(k), &
            '_ns_per_traj_step: ', ns, ' ns'
         write (unit, '(a, i0, a, f0.2, a)') 'chain_lanes_n', links(k), &
            '_over_two_link_kernel: ', ns/two, ' x'
      end do
      ns = trajectory_ns(3)
      write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_ns_per_traj_step: ', ns, ' ns'
      write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_over_two_link_kernel: ', &
         ns/two, ' x'
      call omp_set_num_threads(nthreads)
      flush (unit)
   end subroutine run_chain_lane_benchmarks

   !> The least of three timings of f (one thread).
   real(dp) function best(f, n) result(ns)
      interface
         real(dp) function f(n)
            import :: dp
            integer, intent(in), optional :: n
         end function f
      end interface
      integer, intent(in), optional :: n  !! links
      integer :: k
      ns = huge(1.0_dp)
      do k = 1, 3
         ns = min(ns, f(n))
      end do
   end function best

   !> The run's options: `steps` steps of 1e-3 s, no early stop.
   pure function options() result(opt)
      type(batch_options_t) :: opt
      opt%h = 1e-3_dp
      opt%n_steps = steps
      opt%stop_rule = stop_end
   end function options

   !> ns per trajectory-step of the two-link kernel (chapter parameters).
   real(dp) function two_link_ns(n) result(ns)
      integer, intent(in), optional :: n  !! unused (two links)
      type(pendulum_t) :: par
      type(batch_result_t) :: res
      real(dp) :: y0(4, nb), t0
      integer :: j
      do j = 1, nb   ! above the flip bounds: full-length chaotic runs
         y0(:, j) = [1.0_dp + 1e-3_dp*j, 1.5_dp, 0.0_dp, 0.0_dp]
      end do
      t0 = wall_seconds()
      call integrate_batch(par, options(), y0, res)
      ns = (wall_seconds() - t0)/(real(nb, dp)*steps)*1e9_dp
      if (.not. (sum(res%final(1, :)) > -1e300_dp)) ns = -1.0_dp
   end function two_link_ns

   !> The chain of n unit rods and nb initial states released at rest, far above
   !> every flip bound.
   subroutine chain_start(n, chain, y0)
      integer, intent(in) :: n                      !! links
      type(chain_t), intent(out) :: chain           !! the chain
      real(dp), allocatable, intent(out) :: y0(:, :) !! (2n, nb)
      type(error_t), allocatable :: error
      integer :: i, j
      chain = chain_model([(1.0_dp, i=1, n)], [(1.0_dp, i=1, n)], 9.8_dp, error)
      if (allocated(error)) error stop 'bench_chain: the chain was refused'
      allocate (y0(2*n, nb))
      do j = 1, nb
         do i = 1, n
            y0(i, j) = 1.0_dp + 1e-3_dp*j + 0.1_dp*i
         end do
         y0(n + 1:2*n, j) = 0.0_dp
      end do
   end subroutine chain_start

   !> ns per trajectory-step of the chain lanes, n links.
   real(dp) function chain_ns(n) result(ns)
      integer, intent(in), optional :: n  !! links
      type(chain_t) :: chain
      type(batch_result_t) :: res
      real(dp), allocatable :: y0(:, :)
      real(dp) :: t0
      call chain_start(n, chain, y0)
      t0 = wall_seconds()
      call integrate_chain_lanes(chain, options(), y0, res)
      ns = (wall_seconds() - t0)/(real(nb, dp)*steps)*1e9_dp
      if (.not. (sum(res%final(1, :)) > -1e300_dp)) ns = -1.0_dp
   end function chain_ns

   !> ns per trajectory-step of the per-trajectory path (rk4), n links, nb/16
   !> trajectories (it is slow).
   real(dp) function trajectory_ns(n) result(ns)
      integer, intent(in) :: n  !! links
      type(chain_t) :: chain
      type(batch_result_t) :: res
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      real(dp), allocatable :: y0(:, :)
      real(dp) :: t0
      integer :: m
      call chain_start(n, chain, y0)
      call new_integrator('rk4', integ, error)
      if (allocated(error)) error stop 'bench_chain: no rk4'
      m = nb/16
      t0 = wall_seconds()
      call integrate_trajectories(chain, integ, chain%gl, options(), y0(:, 1:m), res)
      ns = (wall_seconds() - t0)/(real(m, dp)*steps)*1e9_dp
      if (.not. (sum(res%final(1, :)) > -1e300_dp)) ns = -1.0_dp
   end function trajectory_ns

end module bench_chain
