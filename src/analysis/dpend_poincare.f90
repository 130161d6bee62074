!> Poincaré sections at fixed energy.
!>
!> The section is an event of `dpend_events`: the angle q_s of link s (1 or 2)
!> crosses a value, modulo 2π, in a given direction; the default is q1 = −π/2
!> crossed with q̇1 > 0 (link 1 swinging counter-clockwise through the bottom).
!> Each crossing is located to roundoff by `find_crossings` and recorded as the
!> other link's angle q_o (wrapped to (−π, π]) and canonical momentum p_o.
!>
!> Energy-shell sampling. On the section q_s is fixed, so a point (q_o, p_o)
!> and the energy E leave one unknown, p_s. With M⁻¹ = [A B; B C] in the (s, o)
!> ordering, H = E is quadratic in p_s and q̇_s = A p_s + B p_o satisfies
!>   q̇_s² = 2 A (E − V(q)) − det(M⁻¹) p_o²,
!> so the sign of q̇_s is that of the crossing direction and a point belongs to
!> the energy shell iff the right-hand side is positive. Points (q_o, p_o) are
!> drawn from the Halton sequence in bases 2 and 3 (evenly spread, reproducible)
!> over q_o ∈ [−π, π) and |p_o| ≤ p_max, the largest |p_o| of the shell, and
!> those outside the shell are skipped.
!>
!> The orbits are independent and run in parallel (OpenMP), each on its own
!> copy of the method; results do not depend on the number of threads.
module dpend_poincare
   use dpend_kinds, only: dp, i8, pi
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_events, only: angle_crossing_t, crossing_t, find_crossings
   use dpend_propagate, only: march_progress_t
   implicit none
   private
   public :: shell_samples, halton
   public :: poincare_result_t, section_orbit, poincare_sections


   !> Section points of many orbits, concatenated in orbit order.
   type :: poincare_result_t
      real(dp), allocatable :: q(:)       !! other link's angle, wrapped to (−π, π] [rad]
      real(dp), allocatable :: p(:)       !! other link's canonical momentum [kg m²/s]
      real(dp), allocatable :: t(:)       !! crossing times [s]
      real(dp), allocatable :: energy(:)  !! energy at the crossing [J]
      integer, allocatable :: orbit(:)    !! orbit number of each point (1-based)
      integer, allocatable :: count(:)    !! points of each orbit
      integer, allocatable :: status(:)   !! stat_ok or the failure code of each orbit
      integer(i8) :: n_steps = 0          !! accepted steps over all orbits
   end type poincare_result_t

contains

   !> Radical inverse of i in base b: the i-th element of van der Corput's
   !> sequence, the coordinates of the Halton sequence (Halton 1960).
   pure real(dp) function halton(i, b)
      integer, intent(in) :: i  !! index (≥ 1)
      integer, intent(in) :: b  !! prime base
      integer :: n
      real(dp) :: f
      halton = 0.0_dp
      f = 1.0_dp
      n = i
      do while (n > 0)
         f = f/real(b, dp)
         halton = halton + f*real(mod(n, b), dp)
         n = n/b
      end do
   end function halton

   !> Up to n initial states on the section at energy e, from the Halton points
   !> (see the module header); at most 1000 n + 1000 points are tried. n_found
   !> < n when the shell is empty or very thin.
   pure subroutine shell_samples(model, e, link, angle, direction, n, q, qd, n_found)
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: e            !! energy [J]
      integer, intent(in) :: link          !! section link (1 or 2)
      real(dp), intent(in) :: angle        !! section angle [rad]
      integer, intent(in) :: direction     !! crossing direction (sign of q̇_s)
      integer, intent(in) :: n             !! samples wanted
      real(dp), intent(out) :: q(2, n)     !! angles [rad]
      real(dp), intent(out) :: qd(2, n)    !! angular velocities [rad/s]
      integer, intent(out) :: n_found      !! samples found
      real(dp) :: pmax, q_o, p_o
      integer :: i
      logical :: found
      q = 0.0_dp; qd = 0.0_dp
      n_found = 0
      pmax = model%section_p_max(e, link, angle)
      if (pmax <= 0.0_dp) return
      do i = 1, 1000*n + 1000
         q_o = -pi + 2.0_dp*pi*halton(i, 2)
         p_o = pmax*(2.0_dp*halton(i, 3) - 1.0_dp)
         call model%section_state(e, link, angle, direction, q_o, p_o, &
                          q(:, n_found + 1), qd(:, n_found + 1), found)
         if (found) n_found = n_found + 1
         if (n_found == n) return
      end do
   end subroutine shell_samples

   !> Section points of one orbit from (q0, q̇0): the initial state itself when
   !> it lies on the section (first point, t = 0), then up to `max_points`
   !> crossings of `section` before t_end, located by `find_crossings`.
   !> h: fixed step or initial proposal. Returns the points found before a failure.
   subroutine section_orbit(integ, model, section, q0, qd0, t_end, h, max_points, &
                            qo, po, t, e, stat, progress)
      class(integrator_t), intent(inout) :: integ        !! the method
      class(model_t), intent(in) :: model  !! the system
      type(angle_crossing_t), intent(in) :: section      !! the section
      real(dp), intent(in) :: q0(:)                      !! initial angles [rad]
      real(dp), intent(in) :: qd0(:)                     !! initial angular velocities [rad/s]
      real(dp), intent(in) :: t_end                      !! longest integration [s]
      real(dp), intent(in) :: h                          !! step or proposal [s]
      integer, intent(in) :: max_points                  !! most points of the orbit
      real(dp), allocatable, intent(out) :: qo(:)        !! other angle, wrapped [rad]
      real(dp), allocatable, intent(out) :: po(:)        !! other momentum [kg m²/s]
      real(dp), allocatable, intent(out) :: t(:)         !! times [s]
      real(dp), allocatable, intent(out) :: e(:)         !! energies [J]
      integer, intent(out) :: stat                       !! stat_ok or a failure code
      !> the command's progress (this orbit's share: t_end, all of it counted when the
      !> orbit ends early at max_points or a failure)
      type(march_progress_t), intent(inout), optional :: progress
      type(crossing_t), allocatable :: hits(:)
      real(dp) :: y(2*size(q0)), tt, hh, p(size(q0))
      integer :: o, i, n0, n
      logical :: on_section
      o = 3 - section%index
      on_section = abs(sin(q0(section%index) - section%angle)) <= 4.0_dp*epsilon(1.0_dp) &
                   .and. cos(q0(section%index) - section%angle) > 0.0_dp &
                   .and. (section%direction == 0 .or. &
                          section%direction*qd0(section%index) > 0.0_dp)
      n0 = merge(1, 0, on_section)
      y = integ%to_internal(model, q0, qd0)
      tt = 0.0_dp; hh = h
      call find_crossings(section, integ, model, tt, y, t_end, hh, hits, stat, &
                          max_hits=max(max_points - n0, 0), progress=progress)
      if (present(progress)) call progress%advance(abs(t_end - tt))
      n = n0 + size(hits)
      allocate (qo(n), po(n), t(n), e(n))
      if (on_section) then
         call model%momenta(0.0_dp, [q0, qd0], p)
         qo(1) = wrap(q0(o)); po(1) = p(o); t(1) = 0.0_dp
         e(1) = model%energy(0.0_dp, [q0, qd0])
      end if
      do i = 1, size(hits)
         call model%momenta(hits(i)%t, [hits(i)%q, hits(i)%qd], p)
         qo(n0 + i) = wrap(hits(i)%q(o))
         po(n0 + i) = p(o)
         t(n0 + i) = hits(i)%t
         e(n0 + i) = model%energy(hits(i)%t, [hits(i)%q, hits(i)%qd])
      end do
   contains
      pure real(dp) function wrap(x)
         real(dp), intent(in) :: x
         wrap = x - 2.0_dp*pi*anint(x/(2.0_dp*pi))
      end function wrap
   end subroutine section_orbit

   !> Section points of the orbits from q0(:, j), q̇0(:, j), each integrated by
   !> its own copy of `proto` (in parallel), concatenated in orbit order.
   subroutine poincare_sections(proto, model, section, q0, qd0, t_end, h, max_points, res, &
                                progress)
      class(integrator_t), intent(in) :: proto           !! the method (copied per orbit)
      class(model_t), intent(in) :: model  !! the system
      type(angle_crossing_t), intent(in) :: section      !! the section
      real(dp), intent(in) :: q0(:, :)                   !! initial angles (2, n) [rad]
      real(dp), intent(in) :: qd0(:, :)                  !! initial velocities (2, n) [rad/s]
      real(dp), intent(in) :: t_end                      !! longest integration per orbit [s]
      real(dp), intent(in) :: h                          !! step or proposal [s]
      integer, intent(in) :: max_points                  !! most points per orbit
      type(poincare_result_t), intent(out) :: res        !! the points
      !> the command's progress (span: the orbits × t_end)
      type(march_progress_t), intent(inout), optional :: progress
      type :: orbit_points_t
         real(dp), allocatable :: qo(:), po(:), t(:), e(:)
      end type orbit_points_t
      type(orbit_points_t), allocatable :: orb(:)
      integer(i8), allocatable :: steps(:)
      integer :: j, n_orb, k, m
      n_orb = size(q0, 2)
      allocate (orb(n_orb), steps(n_orb), res%count(n_orb), res%status(n_orb))
      !$omp parallel do schedule(dynamic, 1)
      do j = 1, n_orb
         call one_orbit(j)
      end do
      !$omp end parallel do
      m = sum(res%count)
      allocate (res%q(m), res%p(m), res%t(m), res%energy(m), res%orbit(m))
      k = 0
      do j = 1, n_orb
         m = res%count(j)
         res%q(k + 1:k + m) = orb(j)%qo
         res%p(k + 1:k + m) = orb(j)%po
         res%t(k + 1:k + m) = orb(j)%t
         res%energy(k + 1:k + m) = orb(j)%e
         res%orbit(k + 1:k + m) = j
         k = k + m
      end do
      res%n_steps = sum(steps)
   contains
      subroutine one_orbit(jj)
         integer, intent(in) :: jj
         class(integrator_t), allocatable :: work
         allocate (work, source=proto)
         call work%reset_counters()
         call section_orbit(work, model, section, q0(:, jj), qd0(:, jj), t_end, h, max_points, &
                            orb(jj)%qo, orb(jj)%po, orb(jj)%t, orb(jj)%e, res%status(jj), &
                            progress)
         res%count(jj) = size(orb(jj)%qo)
         steps(jj) = work%n_steps
      end subroutine one_orbit
   end subroutine poincare_sections
end module dpend_poincare
