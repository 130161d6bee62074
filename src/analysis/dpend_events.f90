!> Events: scalar functions g(t, q, q̇) of the physical state whose sign changes
!> are located inside the integration steps to roundoff.
!>
!> After each accepted step, `locate_crossing` compares g at both ends of the
!> method's last step [t_old, t_new]. A sign change (g_old < 0 <= g_new rising,
!> g_old > 0 >= g_new falling, filtered by `direction`) is bracketed and the root
!> is found by Brent's method (Brent 1973, "Algorithms for Minimization without
!> Derivatives", ch. 4; the zeroin of Forsythe, Malcolm, Moler 1977) down to a
!> bracket of about 4 eps |t|. The state inside the step is
!>  * adaptive methods: the method's continuous extension (dopri5: order 4,
!>    dop853: order 7, both within the tolerance of the step);
!>  * fixed-step methods: the method's own numerical flow over a fractional step,
!>    i.e. `step` re-taken from (t_old, y_old) with s in (0, h) on a copy of the
!>    method. This is the exact discrete flow (no interpolation error, same order
!>    as the method, symplectic for symplectic methods), at the cost of about 10
!>    extra steps per event; the Hermite cubic would add an O(h⁴) error.
!> One root per step is found (steps are assumed not to contain two crossings).
!> A crossing exactly at t_new is reported in that step and not again in the next.
!>
!> New events: extend `event_t` and implement `value` (and optionally `accept`,
!> a filter applied to the located crossing).
module dpend_events
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_state
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_propagate, only: march_t, march_progress_t
   implicit none
   private
   public :: event_t, angle_crossing_t, crossing_t, locate_crossing, find_crossings

   real(dp), parameter :: pi = acos(-1.0_dp)

   !> An event g(t, q, q̇) = 0 with a crossing direction.
   type, abstract :: event_t
      integer :: direction = 0  !! +1 rising (g goes up through 0), -1 falling, 0 both
   contains
      procedure(value_i), deferred :: value
      procedure :: accept => accept_all
   end type event_t

   abstract interface
      !> The event function.
      pure real(dp) function value_i(self, model, t, q, qd)
         import :: event_t, model_t, dp
         class(event_t), intent(in) :: self  !! the event
         class(model_t), intent(in) :: model  !! the system
         real(dp), intent(in) :: t           !! time [s]
         real(dp), intent(in) :: q(:)        !! angles [rad]
         real(dp), intent(in) :: qd(:)       !! angular velocities [rad/s]
      end function value_i
   end interface

   !> Crossing of q(index) = angle, e.g. the Poincaré section q1 = -π/2 with
   !> q̇1 > 0: `angle_crossing_t(index=1, angle=-pi/2, direction=+1)`.
   !> With `wrap`, g = sin(q - angle) and only crossings with cos(q - angle) > 0
   !> are kept, so q ≡ angle (mod 2π) is detected on every turn.
   type, extends(event_t) :: angle_crossing_t
      integer :: index = 1                !! which angle, 1 or 2
      real(dp) :: angle = -0.5_dp*pi      !! crossing value [rad]
      logical :: wrap = .false.           !! detect angle modulo 2π
   contains
      procedure :: value => angle_value
      procedure :: accept => angle_accept
   end type angle_crossing_t

   !> A located crossing.
   type :: crossing_t
      real(dp) :: t = 0.0_dp       !! time [s]
      real(dp), allocatable :: q(:)    !! coordinates [rad]
      real(dp), allocatable :: qd(:)   !! their rates [rad/s]
      real(dp), allocatable :: y(:)    !! the method's internal state
      integer :: direction = 0     !! +1 rising, -1 falling
   end type crossing_t

contains

   !> Default filter: keep every located crossing.
   pure logical function accept_all(self, model, t, q, qd)
      class(event_t), intent(in) :: self  !! the event
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t           !! time [s]
      real(dp), intent(in) :: q(:)        !! angles [rad]
      real(dp), intent(in) :: qd(:)       !! angular velocities [rad/s]
      accept_all = .true.
   end function accept_all

   !> g = q(index) - angle, or sin(q(index) - angle) with `wrap` [rad or 1].
   pure real(dp) function angle_value(self, model, t, q, qd)
      class(angle_crossing_t), intent(in) :: self  !! the event
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t                    !! time [s]
      real(dp), intent(in) :: q(:)                 !! angles [rad]
      real(dp), intent(in) :: qd(:)                !! angular velocities [rad/s]
      if (self%wrap) then
         angle_value = sin(q(self%index) - self%angle)
      else
         angle_value = q(self%index) - self%angle
      end if
   end function angle_value

   !> With `wrap`, reject the crossings of sin at angle + π.
   pure logical function angle_accept(self, model, t, q, qd)
      class(angle_crossing_t), intent(in) :: self  !! the event
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t                    !! time [s]
      real(dp), intent(in) :: q(:)                 !! angles [rad]
      real(dp), intent(in) :: qd(:)                !! angular velocities [rad/s]
      angle_accept = .true.
      if (self%wrap) angle_accept = cos(q(self%index) - self%angle) > 0.0_dp
   end function angle_accept

   !> Look for a crossing of `event` in the last step of `integ` and locate it
   !> (see the module header). `found` is false when there is no step, no sign
   !> change in the requested direction, or the crossing is not accepted.
   !> `stat` reports a failure of the fractional steps (fixed-step methods).
   subroutine locate_crossing(event, integ, model, found, hit, stat)
      class(event_t), intent(in) :: event          !! the event
      class(integrator_t), intent(inout) :: integ  !! the method, after a step
      class(model_t), intent(in) :: model  !! the system
      logical, intent(out) :: found                !! a crossing was located
      type(crossing_t), intent(out) :: hit         !! the crossing, when found
      integer, intent(out) :: stat                 !! stat_ok or a step failure code
      class(integrator_t), allocatable :: work
      real(dp) :: ga, gb, gc, a, b, c, d, e, tol1, xm, p, q, r, s, yb(max_state)
      integer :: dir, it, n
      found = .false.
      stat = stat_ok
      if (.not. integ%has_step()) return
      n = integ%n_rec
      a = integ%t_old; b = integ%t_new
      ga = g_of(integ%y_old(:n), a)
      gb = g_of(integ%y_new(:n), b)
      if (ga < 0.0_dp .and. gb >= 0.0_dp) then
         dir = 1
      else if (ga > 0.0_dp .and. gb <= 0.0_dp) then
         dir = -1
      else
         return
      end if
      if (event%direction /= 0 .and. event%direction /= dir) return
      if (.not. integ%adaptive()) allocate (work, source=integ)
      ! Brent's zeroin on [a, b]; b is the best estimate, [b, c] the bracket
      c = a; gc = ga; d = b - a; e = d
      do it = 1, 200
         if ((gb > 0.0_dp .and. gc > 0.0_dp) .or. (gb < 0.0_dp .and. gc < 0.0_dp)) then
            c = a; gc = ga; d = b - a; e = d
         end if
         if (abs(gc) < abs(gb)) then
            a = b; b = c; c = a
            ga = gb; gb = gc; gc = ga
         end if
         tol1 = 2.0_dp*epsilon(1.0_dp)*max(abs(b), abs(integ%t_new - integ%t_old))
         xm = 0.5_dp*(c - b)
         if (abs(xm) <= tol1 .or. gb == 0.0_dp) exit
         if (abs(e) >= tol1 .and. abs(ga) > abs(gb)) then
            s = gb/ga
            if (a == c) then
               p = 2.0_dp*xm*s                       ! secant
               q = 1.0_dp - s
            else
               q = ga/gc; r = gb/gc                  ! inverse quadratic interpolation
               p = s*(2.0_dp*xm*q*(q - r) - (b - a)*(r - 1.0_dp))
               q = (q - 1.0_dp)*(r - 1.0_dp)*(s - 1.0_dp)
            end if
            if (p > 0.0_dp) then
               q = -q
            else
               p = -p
            end if
            if (2.0_dp*p < min(3.0_dp*xm*q - abs(tol1*q), abs(e*q))) then
               e = d; d = p/q
            else
               d = xm; e = d
            end if
         else
            d = xm; e = d                            ! bisection
         end if
         a = b; ga = gb
         if (abs(d) > tol1) then
            b = b + d
         else
            b = b + sign(tol1, xm)
         end if
         call state_at(b, yb(:n))
         gb = g_of(yb(:n), b)
         if (stat /= stat_ok) exit
      end do
      call state_at(b, yb(:n))
      if (allocated(work)) integ%n_rhs = work%n_rhs  ! the copy started from integ's count
      if (stat /= stat_ok) return
      hit%t = b
      hit%y = yb(:n)
      hit%direction = dir
      allocate (hit%q(n/2), hit%qd(n/2))
      call integ%to_physical(model, yb(:n), hit%q, hit%qd)
      found = event%accept(model, b, hit%q, hit%qd)
   contains
      !> g at internal state ys and time ts.
      real(dp) function g_of(ys, ts)
         real(dp), intent(in) :: ys(:), ts
         real(dp) :: qq(max_state), qqd(max_state)
         integer :: m
         m = size(ys)/2
         call integ%to_physical(model, ys, qq(:m), qqd(:m))
         g_of = event%value(model, ts, qq(:m), qqd(:m))
      end function g_of

      !> Internal state at ts inside the last step.
      subroutine state_at(ts, ys)
         real(dp), intent(in) :: ts
         real(dp), intent(out) :: ys(:)
         real(dp) :: tt, hs
         if (ts == integ%t_new) then
            ys = integ%y_new(:n)
         else if (ts == integ%t_old) then
            ys = integ%y_old(:n)
         else if (allocated(work)) then
            tt = integ%t_old; ys = integ%y_old(:n); hs = ts - integ%t_old
            call work%step(model, tt, ys, hs, stat)
         else
            ys = integ%y_new(:n)
            call integ%interpolate(model, ts, ys)
         end if
      end subroutine state_at
   end subroutine locate_crossing

   !> Integrate from (t, y) to t_end (rules of `march_t`) and collect the
   !> crossings of `event`, at most `max_hits` of them if given: the integration
   !> then stops at the end of the step holding the last one, and (t, y) is that
   !> step end, so that a further call continues the same discrete trajectory.
   !> h: fixed step or initial proposal (0: auto), returned as the next proposal.
   !> The method's step memory is cleared first.
   subroutine find_crossings(event, integ, model, t, y, t_end, h, hits, stat, max_hits, progress)
      class(event_t), intent(in) :: event               !! the event
      class(integrator_t), intent(inout) :: integ       !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t                      !! start, then stop time [s]
      real(dp), intent(inout) :: y(:)                   !! internal state at t
      real(dp), intent(in) :: t_end                     !! end time [s]
      real(dp), intent(inout) :: h                      !! step or proposal [s]
      type(crossing_t), allocatable, intent(out) :: hits(:) !! the crossings, in order
      integer, intent(out) :: stat                      !! stat_ok or a failure code
      integer, intent(in), optional :: max_hits         !! stop after this many
      !> the command's progress, which the march adds to
      type(march_progress_t), intent(inout), target, optional :: progress
      type(march_t) :: march
      type(crossing_t) :: hit
      type(crossing_t), allocatable :: tmp(:)
      logical :: found
      integer :: n, limit
      limit = huge(1)
      if (present(max_hits)) limit = max_hits
      allocate (hits(16))
      n = 0
      stat = stat_ok
      call integ%clear_step()
      if (present(progress)) march%progress => progress
      call march%start(integ, t, t_end, h)
      do while (.not. march%finished .and. n < limit)
         call march%next(integ, model, t, y, h, stat)
         if (stat /= stat_ok) exit
         call locate_crossing(event, integ, model, found, hit, stat)
         if (stat /= stat_ok) exit
         if (.not. found) cycle
         if (n == size(hits)) then
            allocate (tmp(2*n))
            tmp(1:n) = hits
            call move_alloc(tmp, hits)
         end if
         n = n + 1
         hits(n) = hit
      end do
      ! stopped early at its crossings: the steps since the march's last report count
      if (associated(march%progress) .and. .not. march%finished) &
         call march%progress%advance(abs(t - march%t_reported))
      hits = hits(1:n)
   end subroutine find_crossings
end module dpend_events
