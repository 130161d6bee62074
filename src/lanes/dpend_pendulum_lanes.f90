!> The double pendulum's lanes: many trajectories of the double pendulum at once
!> (`integrate_batch`), for the sweeps' maps over initial conditions and parameters
!> (docs/sweep.md), on the lane family's refill driver (dpend_lane_batch) with the
!> RK4 kernel (dpend_pendulum_kernel) or the tangent kernels
!> (dpend_pendulum_tangent_lanes). A lane's trajectory is watched for the flips of
!> both links (an angle leaving its window between two upward verticals), the last
!> step and a runaway state; the check is a vectorized count after every step, and
!> only lanes with a possible event are decided one by one (`pendulum_check`).
module dpend_pendulum_lanes
   use dpend_kinds, only: dp, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
   use dpend_pendulum, only: pendulum_t
   use dpend_indicator_math, only: initial_vectors, sali, gali
   use dpend_lane_batch, only: lane_width, resync_steps, batch_options_t, batch_result_t, &
      lane_kernel_t, refill_lanes, stop_both, stop_either, stop_end, st_end, st_flipped, &
      st_cannot_flip, st_nonfinite
   use dpend_pendulum_kernel, only: batch_coef_t, batch_coef, lane_coef_t, lane_coef, &
      set_lane_coef, lane_trig_t, rk4_lanes, energy_lanes, sincos_exact, flip_energy_bounds, &
      potential_range, half_pi, two_pi, inv_two_pi, lane_bound
   use dpend_pendulum_tangent_lanes, only: lyapunov_step_lanes, indicator_step_lanes
   implicit none
   private
   public :: integrate_batch

   integer, parameter :: w = lane_width
   !> Margin of the sweep's angle windows [rad]: far above the rounding of
   !> (q - π/2)/(2π) at the largest accepted angles (1e6 rad: ~1e-10)
   real(dp), parameter :: window_margin = 1.0e-6_dp

   !> The lanes of a batch of double pendulums: the batch, its results, and every
   !> lane's state, flips and sums (structure of arrays).
   type, extends(lane_kernel_t) :: pendulum_lanes_t
      ! the lanes' arrays first (multiples of 64 bytes from the start of the object:
      ! aligned wherever the object is, as the kernels' vector loads want them)
      real(dp), dimension(w) :: q1, q2, w1, w2, u1, u2, v1, v2, e, e0, err, tf1, tf2
      real(dp), dimension(w) :: p1, p2, n1, n2, lacc
      !> the angles between lo and hi cannot have crossed an upward vertical since the
      !> last check: (π/2 + 2π n, π/2 + 2π (n + 1)) shrunk by window_margin
      real(dp), dimension(w) :: lo1, hi1, lo2, hi2
      real(dp), dimension(w) :: active, fresh  !! 1: lane holds an initial condition; just loaded
      real(dp), dimension(w) :: left           !! steps left to n_steps
      real(dp), dimension(w) :: sync           !! steps left to the next exact sin/cos
      type(lane_trig_t) :: tr                  !! sin, cos of the angles (rk4_lanes)
      type(lane_coef_t) :: c                   !! the constants of each lane's trajectory
      integer(i8) :: ks(w)                     !! steps taken
      real(dp) :: dv(w, 4, 2), acc(w, 5), v0(4, 4)   !! indicators' vectors and sums
      integer :: lane_ic(w)                    !! trajectory held, 0: none
      logical :: can1(w), can2(w)              !! its links can flip
      type(batch_options_t) :: opt                 !! step, length, stop rule
      integer :: rule = stop_both                  !! the stop rule applied
      type(batch_coef_t), allocatable :: coefs(:)  !! (1), or (n) one per trajectory
      real(dp), allocatable :: y0(:, :)            !! (4, n) initial states
      logical, allocatable :: can_flip1(:), can_flip2(:)  !! (n) links that can flip
      type(batch_result_t) :: res                  !! the results
      real(dp) :: nan
   contains
      procedure :: step => pendulum_step
      procedure :: load => pendulum_load
      procedure :: check => pendulum_check
      procedure :: finish => pendulum_finish
   end type pendulum_lanes_t

contains

   !> Integrate the initial conditions y0(:, j) = (q1, q2, q̇1, q̇2) with RK4 of step
   !> opt%h up to opt%n_steps steps, lanes refilled with the next initial condition as
   !> soon as a trajectory ends. Initial conditions whose energy is below both flip
   !> bounds are not integrated (status st_cannot_flip) unless opt%lyapunov.
   !> With `pars`, initial condition j has the pendulum pars(j) (a sweep over
   !> parameters): each lane takes the constants of the trajectory it
   !> holds (`lane_coef_t`), so that its results are those of a call with par =
   !> pars(j) bit for bit, and the lanes fill whatever the parameters.
   subroutine integrate_batch(par, opt, y0, res, pars)
      type(pendulum_t), intent(in) :: par             !! parameters (of all, without pars)
      type(batch_options_t), intent(in) :: opt        !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)                !! (4, n) initial states
      type(batch_result_t), intent(out) :: res        !! results
      type(pendulum_t), intent(in), optional :: pars(:)  !! (n) each one's own parameters
      type(pendulum_lanes_t) :: k
      real(dp), allocatable :: bounds(:, :), escale(:)  ! (2, size(coefs)), (size(coefs))
      logical, allocatable :: todo(:)
      integer :: n, i

      n = size(y0, 2)
      if (present(pars)) then
         if (size(pars) /= n) error stop 'internal error: integrate_batch needs size(pars) = n'
         k%coefs = [(batch_coef(pars(i)), i=1, n)]
         escale = [(potential_range(pars(i)), i=1, n)]
         allocate (bounds(2, n))
         do i = 1, n
            bounds(:, i) = flip_energy_bounds(pars(i))
         end do
      else
         k%coefs = [batch_coef(par)]
         escale = [potential_range(par)]
         bounds = reshape(flip_energy_bounds(par), [2, 1])
      end if
      ! every lane starts with the first trajectory's constants (idle lanes keep valid
      ! ones); with one trajectory per call (a parameter block of one pixel) no lane
      ! is set again (`size(coefs) > 1` in the refill), so these must be its own
      k%c = lane_coef(k%coefs(1))
      k%nan = ieee_value(k%nan, ieee_quiet_nan)
      k%opt = opt
      k%rule = opt%stop_rule
      if (opt%lyapunov .or. opt%vectors > 0) k%rule = stop_end
      k%v0 = initial_vectors(4)
      k%dv = 1.0_dp; k%acc = 0.0_dp
      allocate (k%can_flip1(n), k%can_flip2(n), todo(n))
      call start_results(k%coefs, bounds, opt, y0, k%res, k%can_flip1, k%can_flip2, todo)
      if (opt%n_steps >= 1) then   ! t_end = 0: nothing to integrate
         k%y0 = y0
         call refill_lanes(k, todo)
         call close_results(k%coefs, escale, opt, y0, todo, k%res)
      end if
      res = k%res
   end subroutine integrate_batch

   !> One step of every lane (RK4, with the tangent vectors of the Lyapunov exponent
   !> or of the indicators), then a vectorized count of the lanes with a possible
   !> event (`count_events`).
   subroutine pendulum_step(self, events)
      class(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      logical, intent(out) :: events                  !! some lane may hold an event
      real(dp) :: n_events
      self%p1 = self%q1
      self%p2 = self%q2
      if (self%opt%vectors > 0) then
         call indicator_step_lanes(self%c, self%opt%h, self%ks, self%q1, self%q2, self%w1, &
                                   self%w2, self%opt%vectors, self%dv, self%acc, self%e, self%tr)
      else if (self%opt%lyapunov) then
         call lyapunov_step_lanes(self%c, self%opt%h, self%q1, self%q2, self%w1, self%w2, &
                                  self%u1, self%u2, self%v1, self%v2, self%e, self%lacc)
      else
         call rk4_lanes(self%c, self%opt%h, self%q1, self%q2, self%w1, self%w2, self%e, self%tr)
      end if
      call count_events(self%q1, self%q2, self%w1, self%w2, self%e, self%e0, self%active, &
                        self%fresh, self%lo1, self%hi1, self%lo2, self%hi2, self%err, &
                        self%ks, self%left, self%sync, n_events)
      events = .not. (n_events == 0.0_dp)   ! true for NaN
   end subroutine pendulum_step

   !> After a step: each lane's largest energy error, step count and steps left, and
   !> a count of the lanes with a possible event: an angle out of its window, the
   !> last step, a non-finite state, a fresh lane, carried sin and cos due to be set
   !> exactly (arrays of the lanes as arguments, so that gcc sees that they do not
   !> overlap and vectorizes the loop).
   pure subroutine count_events(q1, q2, w1, w2, e, e0, active, fresh, lo1, hi1, lo2, hi2, &
                                err, ks, left, sync, n_events)
      real(dp), intent(in), dimension(w) :: q1, q2, w1, w2   !! state [rad, rad/s]
      real(dp), intent(in), dimension(w) :: e, e0            !! energy before the step, E(0) [J]
      real(dp), intent(in), dimension(w) :: active, fresh    !! 1: holds a trajectory; just loaded
      real(dp), intent(in), dimension(w) :: lo1, hi1, lo2, hi2  !! the angles' windows [rad]
      real(dp), intent(inout) :: err(w)                      !! largest |E - E(0)| [J]
      integer(i8), intent(inout) :: ks(w)                    !! steps taken
      real(dp), intent(inout) :: left(w), sync(w)            !! steps left, to the next resync
      real(dp), intent(out) :: n_events                      !! > 0 or NaN: some event
      real(dp) :: s
      integer :: i
      n_events = 0
      do i = 1, w
         err(i) = max(err(i), abs(e(i) - e0(i)))
         ks(i) = ks(i) + 1
         s = abs(q1(i)) + abs(q2(i)) + abs(w1(i)) + abs(w2(i))
         left(i) = left(i) - 1.0_dp
         sync(i) = sync(i) - 1.0_dp
         ! no compare (it would stop the vectorizer without -fno-trapping-math):
         ! every term >= 0, > 0 for an event; NaN (also an event) if s is not finite
         n_events = n_events + active(i)*(max(0.0_dp, lo1(i) - q1(i)) &
                                          + max(0.0_dp, q1(i) - hi1(i)) &
                                          + max(0.0_dp, lo2(i) - q2(i)) &
                                          + max(0.0_dp, q2(i) - hi2(i)) &
                                          + 0.5_dp*(1.0_dp - sign(1.0_dp, left(i) - 0.5_dp)) &
                                          + abs(s - s) + max(0.0_dp, s - lane_bound) &
                                          + max(0.0_dp, 0.5_dp - sync(i)) + fresh(i))
      end do
   end subroutine count_events

   !> Every lane's events, decided exactly (`pendulum_check_lane`).
   subroutine pendulum_check(self, ended)
      class(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      logical, intent(out) :: ended(w)    !! each lane's trajectory is done
      integer :: l
      do l = 1, w
         call pendulum_check_lane(self, l, ended(l))
      end do
   end subroutine pendulum_check

   !> Lane l's events, decided exactly: the flip times (the index of the last upward
   !> vertical below each angle, π/2 + 2π n, interpolated within the step), a due
   !> resync, and the stop rule.
   subroutine pendulum_check_lane(self, l, ended)
      type(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                        !! lane
      logical, intent(out) :: ended                   !! its trajectory is done
      real(dp) :: m, qc
      self%fresh(l) = 0.0_dp
      if (self%sync(l) < 0.5_dp) call resync(self, l)
      m = floor_real((self%q1(l) - half_pi)*inv_two_pi)
      if (m /= self%n1(l)) then
         if (self%tf1(l) < 0.0_dp) then
            qc = half_pi + two_pi*max(m, self%n1(l))
            self%tf1(l) = (real(self%ks(l) - 1, dp) + (qc - self%p1(l))/(self%q1(l) - self%p1(l))) &
                          *self%opt%h
         end if
         self%n1(l) = m
         call set_windows(self, l)
      end if
      m = floor_real((self%q2(l) - half_pi)*inv_two_pi)
      if (m /= self%n2(l)) then
         if (self%tf2(l) < 0.0_dp) then
            qc = half_pi + two_pi*max(m, self%n2(l))
            self%tf2(l) = (real(self%ks(l) - 1, dp) + (qc - self%p2(l))/(self%q2(l) - self%p2(l))) &
                          *self%opt%h
         end if
         self%n2(l) = m
         call set_windows(self, l)
      end if
      ended = self%ks(l) >= self%opt%n_steps .or. &
              runaway(self%q1(l), self%q2(l), self%w1(l), self%w2(l))
      select case (self%rule)
      case (stop_both)
         ended = ended .or. ((self%tf1(l) >= 0.0_dp .or. .not. self%can1(l)) .and. &
                             (self%tf2(l) >= 0.0_dp .or. .not. self%can2(l)))
      case (stop_either)
         ended = ended .or. self%tf1(l) >= 0.0_dp .or. self%tf2(l) >= 0.0_dp
      end select
   end subroutine pendulum_check_lane

   !> Put initial condition j into lane l, or the idle state (j = 0).
   subroutine pendulum_load(self, l, j)
      class(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                        !! lane
      integer, intent(in) :: j                        !! initial condition, 0: none
      self%ks(l) = 0
      self%left(l) = real(self%opt%n_steps, dp)
      self%err(l) = 0.0_dp
      self%tf1(l) = -1.0_dp; self%tf2(l) = -1.0_dp
      self%lacc(l) = 0.0_dp
      self%u1(l) = 0.5_dp; self%u2(l) = 0.5_dp; self%v1(l) = 0.5_dp; self%v2(l) = 0.5_dp
      self%dv(l, :, 1) = self%v0(:, 1); self%dv(l, :, 2) = self%v0(:, 2)
      self%acc(l, :) = 0.0_dp
      self%lane_ic(l) = j
      if (j > 0) then
         if (size(self%coefs) > 1) call set_lane_coef(self%c, l, self%coefs(j))
         self%q1(l) = self%y0(1, j); self%q2(l) = self%y0(2, j)
         self%w1(l) = self%y0(3, j); self%w2(l) = self%y0(4, j)
         self%e0(l) = self%res%energy0(j)
         self%can1(l) = self%can_flip1(j); self%can2(l) = self%can_flip2(j)
         self%active(l) = 1.0_dp
         self%fresh(l) = 1.0_dp
      else
         self%q1(l) = -half_pi; self%q2(l) = -half_pi; self%w1(l) = 0.0_dp; self%w2(l) = 0.0_dp
         self%e0(l) = 0.0_dp
         self%can1(l) = .false.; self%can2(l) = .false.
         self%active(l) = 0.0_dp
         self%fresh(l) = 0.0_dp
      end if
      self%n1(l) = floor_real((self%q1(l) - half_pi)*inv_two_pi)
      self%n2(l) = floor_real((self%q2(l) - half_pi)*inv_two_pi)
      call set_windows(self, l)
      call resync(self, l)
   end subroutine pendulum_load

   !> Set the sines and cosines that rk4_lanes and rk4_tangent_fused_lanes carry,
   !> for lane l, exactly.
   subroutine resync(self, l)
      type(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                       !! lane
      call sincos_exact(self%q1(l), self%tr%s1(l), self%tr%c1(l))
      call sincos_exact(self%q2(l), self%tr%s2(l), self%tr%c2(l))
      self%sync(l) = real(resync_steps, dp)
      ! (the Lyapunov kernel, `rk4_tangent_lanes`, computes its own sin and cos)
      if (self%opt%lyapunov .and. self%opt%vectors == 0) self%sync(l) = huge(1.0_dp)
   end subroutine resync

   !> The windows of lane l's angles from n1, n2: between two upward verticals,
   !> shrunk by window_margin so that rounding never hides a crossing.
   subroutine set_windows(self, l)
      type(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                       !! lane
      self%lo1(l) = half_pi + two_pi*self%n1(l) + window_margin
      self%hi1(l) = half_pi + two_pi*(self%n1(l) + 1.0_dp) - window_margin
      self%lo2(l) = half_pi + two_pi*self%n2(l) + window_margin
      self%hi2(l) = half_pi + two_pi*(self%n2(l) + 1.0_dp) - window_margin
   end subroutine set_windows

   !> Store the results of the trajectory in lane l as those of initial condition jj.
   subroutine pendulum_finish(self, l, j)
      class(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: l                        !! lane
      integer, intent(in) :: j                        !! its initial condition
      associate (res => self%res, opt => self%opt)
         res%t_stop(j) = real(self%ks(l), dp)*opt%h
         res%final(:, j) = [self%q1(l), self%q2(l), self%w1(l), self%w2(l)]
         res%t_flip1(j) = self%tf1(l); res%t_flip2(j) = self%tf2(l)
         res%energy_error(j) = self%err(l)
         res%steps(j) = int(self%ks(l))
         if (opt%lyapunov) res%lyapunov(j) = self%lacc(l)/res%t_stop(j)
         if (opt%vectors > 0) call finish_indicators(self, j, l)
         if (runaway(self%q1(l), self%q2(l), self%w1(l), self%w2(l))) then
            res%status(j) = st_nonfinite
         else if (self%ks(l) < opt%n_steps) then
            res%status(j) = st_flipped
         end if
      end associate
   end subroutine pendulum_finish

   !> The fast indicators of trajectory jj from the vectors and sums of lane l.
   subroutine finish_indicators(self, jj, l)
      type(pendulum_lanes_t), intent(inout) :: self  !! the lanes
      integer, intent(in) :: jj, l                   !! trajectory, lane
      real(dp) :: d(4, 2), a(4)
      integer :: info
      d = self%dv(l, :, :); a = self%acc(l, 1:4)
      if (.not. (all(ieee_is_finite(d(:, 1:self%opt%vectors))) .and. &
                 all(ieee_is_finite(a)))) return   ! NaN: not finite
      self%res%fli(jj) = a(1)
      self%res%megno_y(jj) = a(3)
      self%res%megno(jj) = a(4)/self%res%t_stop(jj)
      if (self%opt%vectors < 2) return
      self%res%sali(jj) = sali(d(:, 1), d(:, 2))
      call gali(d, self%res%gali2(jj), info)
      if (info /= 0) self%res%gali2(jj) = self%nan
   end subroutine finish_indicators

   !> The batch kernel's set-up (outside the step loop): allocate the results of the
   !> n initial conditions y0, their initial energies and which of them can flip
   !> (energy at or above a link's flip bound) or must be integrated anyway (`todo`);
   !> with opt%n_steps < 1 (t_end = 0) the results are final here. Constants and
   !> bounds: one column for all, or column j for initial condition j.
   subroutine start_results(c, bounds, opt, y0, res, can_flip1, can_flip2, todo)
      type(batch_coef_t), intent(in) :: c(:)              !! constants (1 or n)
      real(dp), intent(in) :: bounds(:, :)                !! (2, 1 or n) flip bounds [J]
      type(batch_options_t), intent(in) :: opt            !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)                    !! (4, n) initial states
      type(batch_result_t), intent(inout) :: res          !! results (allocated here)
      logical, intent(out) :: can_flip1(:), can_flip2(:), todo(:)  !! (n)
      real(dp) :: nan
      integer :: n, j, jc
      n = size(y0, 2)
      nan = ieee_value(nan, ieee_quiet_nan)
      allocate (res%megno(n), res%megno_y(n), res%fli(n), res%sali(n), res%gali2(n))
      res%megno = nan; res%megno_y = nan; res%fli = nan; res%sali = nan; res%gali2 = nan
      res%n = n
      allocate (res%t_flip1(n), res%t_flip2(n), res%t_flip(n), res%energy0(n), &
                res%energy_error(n), res%t_stop(n), res%final(4, n), res%lyapunov(n), &
                res%status(n), res%steps(n))
      if (opt%n_steps < 1) then   ! t_end = 0: nothing to integrate
         call energies(c, y0, res%energy0)
         res%t_flip1 = nan; res%t_flip2 = nan; res%t_flip = nan; res%lyapunov = nan
         res%energy_error = 0.0_dp; res%t_stop = 0.0_dp; res%final = y0
         res%status = st_end; res%steps = 0
         return
      end if

      ! initial energies, W at a time (padding lanes hold the hanging state)
      call energies(c, y0, res%energy0)
      do j = 1, n
         jc = min(j, size(bounds, 2))
         can_flip1(j) = .not. (res%energy0(j) < bounds(1, jc))
         can_flip2(j) = .not. (res%energy0(j) < bounds(2, jc))
         todo(j) = can_flip1(j) .or. can_flip2(j) .or. opt%lyapunov .or. &
                   .not. opt%skip_cannot_flip .or. opt%vectors > 0
         res%t_flip1(j) = -1.0_dp; res%t_flip2(j) = -1.0_dp
         res%energy_error(j) = 0.0_dp
         res%t_stop(j) = 0.0_dp
         res%final(:, j) = y0(:, j)
         res%lyapunov(j) = 0.0_dp
         res%steps(j) = 0
         res%status(j) = merge(st_end, st_cannot_flip, can_flip1(j) .or. can_flip2(j))
      end do
   end subroutine start_results

   !> The batch kernel's closing pass: the largest energy error (the final states'
   !> energies included) relative to the potential's range `escale`, the first flip
   !> of either link, NaN for what was not computed, and the initial state as the
   !> final one of a condition that was not integrated.
   subroutine close_results(c, escale, opt, y0, todo, res)
      type(batch_coef_t), intent(in) :: c(:)              !! constants (1 or n)
      real(dp), intent(in) :: escale(:)                   !! V_max - V_min (1 or n) [J]
      type(batch_options_t), intent(in) :: opt            !! options
      real(dp), intent(in) :: y0(:, :)                    !! (4, n) initial states
      logical, intent(in) :: todo(:)                      !! integrated (n)
      type(batch_result_t), intent(inout) :: res          !! results
      real(dp) :: nan
      integer :: n, j
      n = size(y0, 2)
      nan = ieee_value(nan, ieee_quiet_nan)
      ! the energy of the final states enters the maximum error
      call energies(c, res%final, e_final=res%t_flip)   ! t_flip used as scratch
      do j = 1, n
         if (todo(j) .and. res%status(j) /= st_nonfinite) then
            res%energy_error(j) = max(res%energy_error(j), abs(res%t_flip(j) - res%energy0(j)))
            res%energy_error(j) = res%energy_error(j)/escale(min(j, size(escale)))
         else
            res%energy_error(j) = nan
         end if
      end do
      do j = 1, n
         if (res%t_flip1(j) >= 0.0_dp .and. res%t_flip2(j) >= 0.0_dp) then
            res%t_flip(j) = min(res%t_flip1(j), res%t_flip2(j))
         else if (res%t_flip1(j) >= 0.0_dp) then
            res%t_flip(j) = res%t_flip1(j)
         else if (res%t_flip2(j) >= 0.0_dp) then
            res%t_flip(j) = res%t_flip2(j)
         else
            res%t_flip(j) = nan
         end if
         if (.not. (res%t_flip1(j) >= 0.0_dp)) res%t_flip1(j) = nan
         if (.not. (res%t_flip2(j) >= 0.0_dp)) res%t_flip2(j) = nan
         if (.not. opt%lyapunov .or. .not. todo(j)) res%lyapunov(j) = nan
         if (.not. todo(j)) res%final(:, j) = y0(:, j)
      end do
   end subroutine close_results

   !> The lane's state is not finite or beyond `lane_bound` (no ordered comparison
   !> on NaN, which would raise IEEE invalid).
   pure elemental logical function runaway(q1, q2, w1, w2)
      real(dp), intent(in) :: q1, q2, w1, w2  !! state [rad, rad/s]
      real(dp) :: s
      s = abs(q1) + abs(q2) + abs(w1) + abs(w2)
      runaway = .true.
      if (s - s == 0.0_dp) runaway = s > lane_bound
   end function runaway

   !> floor(y) as a real, vectorizable (no conversion to integer): y rounded to an
   !> integer by the 1.5·2^52 trick, minus 1 where that rounded up (yc - f < 0; for
   !> yc = f, yc - f = +0); exact for
   !> |y| < 2^50 (beyond, y is clamped to ±2^50: angles above 7e15 rad).
   pure elemental real(dp) function floor_real(y) result(f)
      real(dp), intent(in) :: y  !! value
      real(dp), parameter :: round_magic = 6755399441055744.0_dp  ! 1.5·2^52
      real(dp), parameter :: big = 1125899906842624.0_dp           ! 2^50
      real(dp) :: yc
      yc = min(max(y, -big), big)
      f = (yc + round_magic) - round_magic
      f = f - 0.5_dp*(1.0_dp - sign(1.0_dp, yc - f))   ! - 1 if f > yc, without a compare
   end function floor_real

   !> Energies of the states y(:, j), computed W at a time with the lane kernel, with
   !> the constants c(1) for all, or c(j) for state j.
   subroutine energies(c, y, e_final)
      type(batch_coef_t), intent(in) :: c(:)  !! constants (1 or n)
      real(dp), intent(in) :: y(:, :)         !! (4, n) states
      real(dp), intent(out) :: e_final(:)     !! (n) energies [J]
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, e
      type(lane_coef_t) :: lc
      integer :: j0, i, n, m
      n = size(y, 2)
      if (n < 1) return
      lc = lane_coef(c(1))
      do j0 = 1, n, lane_width
         m = min(lane_width, n - j0 + 1)
         q1 = -half_pi; q2 = -half_pi; w1 = 0.0_dp; w2 = 0.0_dp
         if (size(c) > 1) then
            do i = 1, m
               call set_lane_coef(lc, i, c(j0 + i - 1))
            end do
         end if
         do i = 1, m
            q1(i) = y(1, j0 + i - 1); q2(i) = y(2, j0 + i - 1)
            w1(i) = y(3, j0 + i - 1); w2(i) = y(4, j0 + i - 1)
         end do
         call energy_lanes(lc, q1, q2, w1, w2, e)
         e_final(j0:j0 + m - 1) = e(:m)
      end do
   end subroutine energies
end module dpend_pendulum_lanes
