!> Benchmarks of the chain lanes (dpend_chain_lanes): process CPU ns per
!> trajectory-step of the flip-map kernel of the chain of N = 3, 5 and 8 unit rods, on
!> one thread, and as ratios to the two-link batch kernel (dpend_pendulum_lanes) timed
!> in the same rounds (the machine may be shared: ratios of one run are the comparable
!> figures); the per-trajectory path (the registry's rk4, dpend_trajectory_batch) of
!> N = 3 for reference; the triple pendulum's indicator maps (MEGNO: one deviation
!> vector, SALI: two) in the lanes and on the per-trajectory path, and their ratios to
!> the lanes' flip map and to each other. One figure a line as `key: value unit`. Run in the release profile:
!>   . scripts/flags.sh
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS" -- --batch
module bench_chain
   use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_pendulum, only: pendulum_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_lane_batch, only: batch_options_t, batch_result_t, stop_end
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_chain_lanes, only: integrate_chain_lanes
   use dpend_trajectory_batch, only: integrate_trajectories
   use dpend_methods, only: new_integrator
   use dpend_integrator, only: integrator_t
   implicit none
   private
   public :: run_chain_lane_benchmarks

   real(dp), parameter :: pi = acos(-1.0_dp)
   integer, parameter :: steps = 1000   !! steps per trajectory (run to the end)
   integer, parameter :: nb = 512       !! trajectories per timed batch

contains

   !> Print the chain lanes' figures to `unit`: the least process CPU time of five
   !> rounds, each timing the two-link kernel and the chain lanes one after the other
   !> (on a shared machine the CPU time is far steadier than the wall time; the
   !> rounds interleave the kernels so that a change of load hits them alike).
   subroutine run_chain_lane_benchmarks(unit)
      integer, intent(in) :: unit  !! where to print
      integer, parameter :: links(3) = [3, 5, 8], rounds = 5
      real(dp) :: two, ns(size(links)), traj, ind_lanes(2), ind_traj(2)
      character(len=5), parameter :: ind_name(2) = ['megno', 'sali ']
      integer :: nthreads, k, r
      nthreads = omp_get_max_threads()
      call omp_set_num_threads(1)
      two = huge(1.0_dp); ns = huge(1.0_dp)
      do r = 1, rounds
         two = min(two, two_link_ns())
         do k = 1, size(links)
            ns(k) = min(ns(k), chain_ns(links(k)))
         end do
      end do
      traj = trajectory_ns(3)
      ind_lanes = huge(1.0_dp)
      do r = 1, 3
         do k = 1, 2
            ind_lanes(k) = min(ind_lanes(k), indicator_ns(3, k, .true.))
         end do
      end do
      do k = 1, 2
         ind_traj(k) = indicator_ns(3, k, .false.)
      end do
      write (unit, '(a, f0.2, a)') 'chain_lanes_two_link_kernel_cpu_ns_per_traj_step: ', two, &
         ' ns'
      do k = 1, size(links)
         write (unit, '(a, i0, a, f0.2, a)') 'chain_lanes_n', links(k), &
            '_cpu_ns_per_traj_step: ', ns(k), ' ns'
         write (unit, '(a, i0, a, f0.2, a)') 'chain_lanes_n', links(k), &
            '_over_two_link_kernel: ', ns(k)/two, ' x'
      end do
      write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_cpu_ns_per_traj_step: ', traj, ' ns'
      write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_over_two_link_kernel: ', &
         traj/two, ' x'
      do k = 1, 2
         write (unit, '(a, f0.2, a)') 'chain_lanes_n3_'//trim(ind_name(k))// &
            '_cpu_ns_per_traj_step: ', ind_lanes(k), ' ns'
         write (unit, '(a, f0.2, a)') 'chain_lanes_n3_'//trim(ind_name(k))// &
            '_over_lanes_flip: ', ind_lanes(k)/ns(1), ' x'
         write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_'//trim(ind_name(k))// &
            '_cpu_ns_per_traj_step: ', ind_traj(k), ' ns'
         write (unit, '(a, f0.2, a)') 'chain_per_trajectory_n3_'//trim(ind_name(k))// &
            '_over_lanes: ', ind_traj(k)/ind_lanes(k), ' x'
      end do
      call omp_set_num_threads(nthreads)
      flush (unit)
   end subroutine run_chain_lane_benchmarks

   !> The run's options: `steps` steps of 1e-3 s, no early stop.
   pure function options() result(opt)
      type(batch_options_t) :: opt
      opt%h = 1e-3_dp
      opt%n_steps = steps
      opt%stop_rule = stop_end
   end function options

   !> CPU ns per trajectory-step of the two-link kernel (chapter parameters).
   real(dp) function two_link_ns() result(ns)
      type(pendulum_t) :: par
      type(batch_result_t) :: res
      real(dp) :: y0(4, nb), t0, t1
      integer :: j
      do j = 1, nb   ! above the flip bounds: full-length chaotic runs
         y0(:, j) = [1.0_dp + 1e-3_dp*j, 1.5_dp, 0.0_dp, 0.0_dp]
      end do
      call cpu_time(t0)
      call integrate_batch(par, options(), y0, res)
      call cpu_time(t1)
      ns = (t1 - t0)/(real(nb, dp)*steps)*1e9_dp
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

   !> CPU ns per trajectory-step of the chain lanes, n links.
   real(dp) function chain_ns(n) result(ns)
      integer, intent(in) :: n  !! links
      type(chain_t) :: chain
      type(batch_result_t) :: res
      real(dp), allocatable :: y0(:, :)
      real(dp) :: t0, t1
      call chain_start(n, chain, y0)
      call cpu_time(t0)
      call integrate_chain_lanes(chain, options(), y0, res)
      call cpu_time(t1)
      ns = (t1 - t0)/(real(nb, dp)*steps)*1e9_dp
      if (.not. (sum(res%final(1, :)) > -1e300_dp)) ns = -1.0_dp
   end function chain_ns

   !> CPU ns per trajectory-step of the per-trajectory path (rk4), n links, nb/16
   !> trajectories (it is slow).
   real(dp) function trajectory_ns(n) result(ns)
      integer, intent(in) :: n  !! links
      type(chain_t) :: chain
      type(batch_result_t) :: res
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      real(dp), allocatable :: y0(:, :)
      real(dp) :: t0, t1
      integer :: m
      call chain_start(n, chain, y0)
      call new_integrator('rk4', integ, error)
      if (allocated(error)) error stop 'bench_chain: no rk4'
      m = nb/16
      call cpu_time(t0)
      call integrate_trajectories(chain, integ, chain%gl, options(), y0(:, 1:m), res)
      call cpu_time(t1)
      ns = (t1 - t0)/(real(m, dp)*steps)*1e9_dp
      if (.not. (sum(res%final(1, :)) > -1e300_dp)) ns = -1.0_dp
   end function trajectory_ns

   !> CPU ns per trajectory-step of an indicator map (nv deviation vectors: 1 MEGNO,
   !> 2 SALI) of the chain of n unit rods, in the chain lanes (nb trajectories) or on
   !> the per-trajectory path (nb/16: it is slow; it integrates each trajectory twice,
   !> the second time with its 2n vectors).
   real(dp) function indicator_ns(n, nv, lanes) result(ns)
      integer, intent(in) :: n      !! links
      integer, intent(in) :: nv     !! deviation vectors, 1 or 2
      logical, intent(in) :: lanes  !! the chain lanes (else the per-trajectory path)
      type(chain_t) :: chain
      type(batch_result_t) :: res
      type(batch_options_t) :: opt
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      real(dp), allocatable :: y0(:, :)
      real(dp) :: t0, t1
      integer :: m
      call chain_start(n, chain, y0)
      opt = options()
      opt%vectors = nv
      m = merge(nb, nb/16, lanes)
      call cpu_time(t0)
      if (lanes) then
         call integrate_chain_lanes(chain, opt, y0(:, 1:m), res)
      else
         call new_integrator('rk4', integ, error)
         if (allocated(error)) error stop 'bench_chain: no rk4'
         call integrate_trajectories(chain, integ, chain%gl, opt, y0(:, 1:m), res)
      end if
      call cpu_time(t1)
      ns = (t1 - t0)/(real(m, dp)*steps)*1e9_dp
      if (.not. (sum(res%megno) > -1e300_dp)) ns = -1.0_dp
   end function indicator_ns

end module bench_chain
