!> The lane family's common ground: what a batch of trajectories is asked (the
!> options, the stop rules) and answers (the results, the status codes), the flip
!> rules shared by every path (the flip energy bounds, the first flip of any link),
!> and the one refill driver of the lane kernels.
!>
!> A lane kernel (`lane_kernel_t`) steps `lane_width` trajectories together in
!> structure-of-arrays form; `refill_lanes` fills its lanes with the trajectories to
!> integrate, steps them, lets the kernel decide the lanes whose step may hold an
!> event (a flip, the last step, a runaway state, a due resync), stores the ended
!> trajectories' results and refills their lanes, until every trajectory is done.
!> The kernels: the double pendulum's (dpend_pendulum_lanes) and the chain's
!> (dpend_chain_lanes); the per-trajectory path of any model
!> (dpend_trajectory_batch) answers with the same records.
!>
!> Reproducibility: the driver never mixes lanes, and every lane's trajectory goes
!> through the same operations whatever its lane, its block or its thread, so that
!> the results are bitwise independent of the number of threads, the block size and
!> the order in which lanes are refilled.
module dpend_lane_batch
   use dpend_kinds, only: dp, i8
   use dpend_stop_request, only: stop_requested
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private
   public :: lane_width, resync_steps, bound_margin
   public :: batch_options_t, batch_result_t
   public :: stop_both, stop_either, stop_end
   public :: st_missing, st_end, st_flipped, st_cannot_flip, st_nonfinite
   public :: link_flip_bounds, first_flips
   public :: lane_kernel_t, refill_lanes

   integer, parameter :: lane_width = 16  !! trajectories per lane set (two AVX-512 vectors)
   !> Steps of a lane after which the lane kernels set its carried sin and cos exactly
   !> again: the carried values' rounding, a random walk of about one ulp per step,
   !> stays near sqrt(1024) ulp
   integer, parameter :: resync_steps = 1024
   !> Margin of the flip energy bounds, relative to Σ G_i (rounding of E(0)).
   real(dp), parameter :: bound_margin = 1e-12_dp

   ! stop rules: when a trajectory ends before t_end
   integer, parameter :: stop_both = 1    !! when every link that can flip has flipped
   integer, parameter :: stop_either = 2  !! at the first flip of either link
   integer, parameter :: stop_end = 3     !! never: always run to t_end

   ! status of an initial condition (0 is the fill value of the files: not computed)
   integer, parameter :: st_missing = 0      !! not computed yet
   integer, parameter :: st_end = 1          !! integrated to t_end
   integer, parameter :: st_flipped = 2      !! stopped early by the stop rule after a flip
   integer, parameter :: st_cannot_flip = 3  !! energy below the flip bound (not integrated
                                             !! unless the Lyapunov exponent is wanted)
   integer, parameter :: st_nonfinite = 4    !! the state became NaN or Inf

   !> How to integrate a batch.
   type :: batch_options_t
      real(dp) :: h = 1e-3_dp          !! step [s]
      integer(i8) :: n_steps = 0       !! steps from t = 0 to t_end (t_end = n_steps h)
      integer :: stop_rule = stop_both !! stop_both, stop_either or stop_end
      logical :: lyapunov = .false.    !! also the largest Lyapunov exponent (runs to t_end)
      logical :: skip_cannot_flip = .true.  !! leave out initial conditions below the
                                            !! flip energy bounds (always integrated with
                                            !! the Lyapunov exponent)
      !> Deviation vectors of the fast indicators (dpend_indicator_math); runs to
      !> t_end like the Lyapunov exponent (exclusive with it): 0 none, 1 MEGNO and
      !> FLI, 2 also SALI and GALI_2
      integer :: vectors = 0
   end type batch_options_t

   !> Reduced results per initial condition (arrays of size n). NaN marks "none".
   type :: batch_result_t
      integer :: n = 0                          !! number of initial conditions
      real(dp), allocatable :: t_flip1(:)       !! first flip of link 1 [s], NaN: none
      real(dp), allocatable :: t_flip2(:)       !! first flip of link 2 [s], NaN: none
      real(dp), allocatable :: t_flip(:)        !! first flip of either link [s], NaN: none
      !> (N, n) first flip of every link [s], NaN: none; only from the per-trajectory
      !> path of N links (dpend_trajectory_batch), where t_flip1 and t_flip2 are unused
      real(dp), allocatable :: t_flip_link(:, :)
      real(dp), allocatable :: energy0(:)       !! initial energy E(0) [J]
      real(dp), allocatable :: energy_error(:)  !! max |E(t) - E(0)| / potential_range [1]
      real(dp), allocatable :: t_stop(:)        !! time integrated to [s]
      real(dp), allocatable :: final(:, :)      !! (2N, n) state at t_stop [rad, rad/s]
      real(dp), allocatable :: lyapunov(:)      !! largest Lyapunov exponent [1/s], NaN: off
      integer, allocatable :: status(:)         !! st_* code
      integer, allocatable :: steps(:)          !! RK4 steps taken (4 evaluations each)
      !> Fast indicators at t_stop (NaN: not computed) of deviation vector 1: <Y> the
      !> running mean of MEGNO, Y itself, FLI = ln |δ|; of vectors 1 and 2: SALI,
      !> GALI_2 [1]
      real(dp), allocatable :: megno(:), megno_y(:), fli(:), sali(:), gali2(:)
   end type batch_result_t

   !> A lane kernel: `lane_width` trajectories in lanes, stepped together. The
   !> kernel holds its lanes' states and the batch's results; `refill_lanes` decides
   !> which trajectory each lane holds.
   type, abstract :: lane_kernel_t
   contains
      !> One step of every lane; `events` false when no lane can hold an event (a
      !> vectorized count: the common case, no lane needs `check`).
      procedure(kernel_step_i), deferred :: step
      !> Put trajectory j into lane l (j = 0: the lane idles at a harmless state).
      procedure(kernel_load_i), deferred :: load
      !> Decide every lane's possible events exactly; `ended(l)`: lane l's
      !> trajectory (if any) is done.
      procedure(kernel_check_i), deferred :: check
      !> Store lane l's results as those of trajectory j.
      procedure(kernel_load_i), deferred :: finish
   end type lane_kernel_t

   abstract interface
      subroutine kernel_step_i(self, events)
         import :: lane_kernel_t
         class(lane_kernel_t), intent(inout) :: self  !! the kernel
         logical, intent(out) :: events               !! some lane may hold an event
      end subroutine kernel_step_i
      subroutine kernel_load_i(self, l, j)
         import :: lane_kernel_t
         class(lane_kernel_t), intent(inout) :: self  !! the kernel
         integer, intent(in) :: l                     !! lane
         integer, intent(in) :: j                     !! trajectory (0: none)
      end subroutine kernel_load_i
      subroutine kernel_check_i(self, ended)
         import :: lane_kernel_t, lane_width
         class(lane_kernel_t), intent(inout) :: self  !! the kernel
         logical, intent(out) :: ended(lane_width)    !! each lane's trajectory is done
      end subroutine kernel_check_i
   end interface

contains

   !> Integrate the trajectories j with todo(j) by `kernel`, `lane_width` at a time,
   !> in the order of j, a lane refilled as soon as its trajectory ends.
   subroutine refill_lanes(kernel, todo)
      class(lane_kernel_t), intent(inout) :: kernel  !! the kernel (its results filled)
      logical, intent(in) :: todo(:)                 !! (n) trajectories to integrate
      integer :: lane_ic(lane_width), next, n_active, l
      logical :: ended(lane_width), events, any_ended
      next = 1
      n_active = 0
      do l = 1, lane_width
         call take_next(l)
      end do
      do while (n_active > 0)
         call kernel%step(events)
         if (.not. events) cycle
         call kernel%check(ended)   ! rare: lane by lane
         do l = 1, lane_width
            ended(l) = ended(l) .and. lane_ic(l) > 0
         end do
         any_ended = .false.
         do l = 1, lane_width
            any_ended = any_ended .or. ended(l)
         end do
         if (.not. any_ended) cycle
         do l = 1, lane_width
            if (.not. ended(l)) cycle
            call kernel%finish(l, lane_ic(l))
            n_active = n_active - 1
            call take_next(l)
         end do
      end do

   contains

      !> Lane l takes the next trajectory to integrate, or idles (all lanes do once a
      !> stop is requested: the block is then cut short, and not written).
      subroutine take_next(l)
         integer, intent(in) :: l
         if (stop_requested()) next = size(todo) + 1
         do while (next <= size(todo))
            if (todo(next)) exit
            next = next + 1
         end do
         lane_ic(l) = 0
         if (next <= size(todo)) then
            lane_ic(l) = next
            next = next + 1
            n_active = n_active + 1
         end if
         call kernel%load(l, lane_ic(l))
      end subroutine take_next
   end subroutine refill_lanes

   !> Least energy with which link i can reach the upward vertical [J], for a
   !> potential V = Σ G_i sin q_i with G_i ≥ 0: G_i − Σ_(j≠i) G_j (for two links the
   !> kernel's `flip_energy_bounds`, A − B and B − A).
   pure function link_flip_bounds(gl) result(e)
      real(dp), intent(in) :: gl(:)  !! G_i [J]
      real(dp) :: e(size(gl))
      real(dp) :: others
      integer :: i, j
      do i = 1, size(gl)
         others = 0.0_dp
         do j = 1, size(gl)
            if (j /= i) others = others + gl(j)
         end do
         e(i) = gl(i) - others
      end do
   end function link_flip_bounds

   !> res%t_flip (the first flip of any link), NaN for every link that did not flip,
   !> and t_flip1, t_flip2 (links 1 and 2; NaN if absent) from res%t_flip_link (-1: none).
   subroutine first_flips(res, nl)
      type(batch_result_t), intent(inout) :: res   !! results, t_flip_link set
      integer, intent(in) :: nl                    !! links N
      real(dp) :: nan
      integer :: i, j
      nan = ieee_value(nan, ieee_quiet_nan)
      do j = 1, res%n
         if (any(res%t_flip_link(:, j) >= 0.0_dp)) then
            res%t_flip(j) = minval(res%t_flip_link(:, j), mask=res%t_flip_link(:, j) >= 0.0_dp)
         else
            res%t_flip(j) = nan
         end if
         do i = 1, nl
            if (.not. (res%t_flip_link(i, j) >= 0.0_dp)) res%t_flip_link(i, j) = nan
         end do
         res%t_flip1(j) = res%t_flip_link(1, j)
         res%t_flip2(j) = nan
         if (nl >= 2) res%t_flip2(j) = res%t_flip_link(2, j)
      end do
   end subroutine first_flips
end module dpend_lane_batch
