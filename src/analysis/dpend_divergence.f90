!> Divergence of nearby trajectories: two trajectories started δ0 apart, the
!> distance |δ(t)| between them sampled on a uniform grid, and a straight-line
!> fit of log10 |δ| against t over the exponential phase, whose slope (times
!> ln 10) estimates the largest Lyapunov exponent.
!>
!> Distance: the Euclidean norm in (q1, q2, q̇1, q̇2) with the angle differences
!> wrapped to (-π, π], so that it saturates at the size of the accessible
!> region instead of growing when one pendulum turns over and the other does
!> not. The initial displacement is δ0 (1, 1, 1, 1)/2 in (q, q̇); on request it
!> is first projected onto the tangent plane of the energy surface
!> E(q, q̇) = E0 and then corrected by Newton steps along ∇E, so that both
!> trajectories have the same energy (to roundoff) and |δ(0)| = δ0 (to O(δ0²)).
!>
!> Ensembles: with n_pairs > 1 the pairs start at the states of the reference
!> orbit at t = 0, s, 2s, … (s the spacing) and the curve is the mean of
!> log10 |δ| over the pairs (the average of the logarithm, as for the Lyapunov
!> exponent itself), which removes much of the finite-time scatter of one pair.
!> Pair 1 always starts at the given initial state. A driven system (a moving
!> support, applied torques: not `autonomous`) runs pair p from its start time
!> t_p = (p − 1) s on, so that both of its trajectories see the forcing of the orbit
!> they left; an autonomous one from t = 0 (its motion does not depend on the start
!> time; the results stay bitwise those of every earlier version).
!>
!> Both trajectories are sampled through the method's continuous extension
!> (`integrate_sampled`). Fixed-step methods take the same steps on both, so the
!> difference of their truncation errors is O(h^p δ); adaptive methods choose
!> different steps for each, and their tolerances must be far below δ0.
module dpend_divergence
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp
   use dpend_sorting, only: median
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_propagate, only: integrate_sampled, march_progress_t
   implicit none
   private
   public :: perturbed_state, phase_distance, angle_coordinates
   public :: divergence_result_t, divergence_pairs, line_fit_t, fit_exponential_phase

   real(dp), parameter :: pi = acos(-1.0_dp)

   !> Sampled divergence of one or more pairs.
   type :: divergence_result_t
      real(dp), allocatable :: t(:)             !! sample times from each pair's start (n) [s]
      real(dp), allocatable :: log10_pairs(:, :) !! log10 |δ| of each pair (n_pairs, n)
      real(dp), allocatable :: log10_mean(:)    !! mean over the pairs of log10 |δ| (n)
      real(dp), allocatable :: start(:, :)      !! (q1, q2, q̇1, q̇2) of each pair's reference
      real(dp), allocatable :: delta_start(:)   !! actual |δ(0)| of each pair
      real(dp), allocatable :: energy_diff(:)   !! E_b - E_a at t = 0 of each pair [J]
   end type divergence_result_t

   !> A straight line fitted to log10 |δ| against t.
   type :: line_fit_t
      real(dp) :: slope = 0.0_dp        !! d ln|δ|/dt [1/s] (natural log)
      real(dp) :: slope_stderr = 0.0_dp !! its least-squares standard error [1/s]
      real(dp) :: intercept = 0.0_dp    !! log10 |δ| of the line at t = 0
      real(dp) :: t_start = 0.0_dp      !! fit window start [s]
      real(dp) :: t_end = 0.0_dp        !! fit window end [s]
      integer :: n_points = 0           !! samples in the window
      real(dp) :: saturation = 0.0_dp   !! log10 |δ| level of saturation
      logical :: saturated = .false.    !! the curve reached saturation
      logical :: ok = .false.           !! at least 3 points were fitted
   end type line_fit_t

contains

   !> The partner of (q, q̇): displaced by δ0 (1, 1, 1, 1)/2, or with `same_energy`
   !> by δ0 along the projection of that direction on the energy surface, then
   !> put back on E = E(q, q̇) by Newton steps along ∇E (see the module header).
   pure subroutine perturbed_state(model, q, qd, delta0, same_energy, qb, qdb, t)
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: q(:)          !! angles [rad]
      real(dp), intent(in) :: qd(:)         !! angular velocities [rad/s]
      real(dp), intent(in) :: delta0        !! displacement [mixed: rad, rad/s]
      logical, intent(in) :: same_energy    !! keep the energy
      real(dp), intent(out) :: qb(:)        !! displaced angles [rad]
      real(dp), intent(out) :: qdb(:)       !! displaced angular velocities [rad/s]
      real(dp), intent(in), optional :: t   !! the time of the state [s] (default 0)
      real(dp) :: u(2*size(q)), n(2*size(q)), z(2*size(q)), e0, nn, t0
      integer :: it, m
      m = size(q)
      t0 = 0.0_dp
      if (present(t)) t0 = t
      u = 0.5_dp
      if (same_energy) then
         call model%energy_gradient(t0, [q, qd], n)
         nn = dot_product(n, n)
         if (nn > 0.0_dp) u = u - (dot_product(u, n)/nn)*n
         u = u/norm2(u)
      end if
      z = [q, qd] + delta0*u
      if (same_energy) then
         e0 = model%energy(t0, [q, qd])
         do it = 1, 3
            call model%energy_gradient(t0, z, n)
            nn = dot_product(n, n)
            if (nn == 0.0_dp) exit
            z = z - ((model%energy(t0, z) - e0)/nn)*n
         end do
      end if
      qb = z(1:m); qdb = z(m + 1:)
   end subroutine perturbed_state

   !> Distance in (q, q̇) with angle differences wrapped to (-π, π] [mixed units]:
   !> every coordinate is an angle, or those `angle` marks (the model's coordinates
   !> in rad: `angle_coordinates`).
   pure real(dp) function phase_distance(qa, qda, qb, qdb, angle)
      real(dp), intent(in) :: qa(:), qda(:)  !! first state [rad, rad/s]
      real(dp), intent(in) :: qb(:), qdb(:)  !! second state [rad, rad/s]
      logical, intent(in), optional :: angle(:)  !! which coordinates are angles
      real(dp) :: dq(size(qa))
      dq = qb - qa
      if (present(angle)) then
         where (angle) dq = dq - 2.0_dp*pi*anint(dq/(2.0_dp*pi))
      else
         dq = dq - 2.0_dp*pi*anint(dq/(2.0_dp*pi))
      end if
      phase_distance = sqrt(sum(dq**2) + sum((qdb - qda)**2))
   end function phase_distance

   !> Divergence of `n_pairs` pairs over [0, t_span], sampled every sample_dt
   !> (see the module header). h: fixed step or initial proposal of `integ`.
   !> On failure `stat` says why and `res` holds the pairs completed before.
   subroutine divergence_pairs(integ, model, q0, qd0, t_span, sample_dt, delta0, same_energy, &
                               n_pairs, spacing, h, res, stat, progress)
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: q0(:)                !! initial angles [rad]
      real(dp), intent(in) :: qd0(:)               !! initial angular velocities [rad/s]
      real(dp), intent(in) :: t_span               !! duration of each pair [s]
      real(dp), intent(in) :: sample_dt            !! sampling interval [s]
      real(dp), intent(in) :: delta0               !! initial distance
      logical, intent(in) :: same_energy           !! partner on the same energy surface
      integer, intent(in) :: n_pairs               !! pairs (≥ 1)
      real(dp), intent(in) :: spacing              !! time between pair starts on the orbit [s]
      real(dp), intent(in) :: h                    !! step or proposal [s]
      type(divergence_result_t), intent(out) :: res !! curves
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      !> the command's progress (span: (n_pairs − 1) spacing + 2 n_pairs t_span)
      type(march_progress_t), intent(inout), optional :: progress
      real(dp), allocatable :: times(:), sa(:, :), sb(:, :), tref(:), sref(:, :)
      real(dp), dimension(size(q0)) :: qa, qda, qb, qdb
      real(dp) :: ya(2*size(q0)), yb(2*size(q0)), tp
      logical :: angle(size(q0))
      integer :: p, i, n_done
      angle = angle_coordinates(model)
      allocate (res%start(2*size(q0), n_pairs), res%delta_start(n_pairs), &
                res%energy_diff(n_pairs))
      ! a pair the run does not reach (it failed before) has no start: NaN, never
      ! the memory's leftovers
      res%start = ieee_value(1.0_dp, ieee_quiet_nan)
      res%delta_start = res%start(1, 1)
      res%energy_diff = res%start(1, 1)
      ya = integ%to_internal(model, q0, qd0)
      if (n_pairs > 1) then
         call integrate_sampled(integ, model, 0.0_dp, ya, real(n_pairs - 1, dp)*spacing, h, &
                                spacing, tref, sref, stat, progress)
         if (stat /= stat_ok) then
            allocate (res%t(0), res%log10_pairs(0, 0), res%log10_mean(0))
            return
         end if
      else
         tref = [0.0_dp]
         sref = reshape(ya, [size(ya), 1])
      end if
      n_done = 0
      do p = 1, n_pairs
         ! the pair's start time: its place on the orbit for a driven system
         tp = 0.0_dp
         if (.not. model%autonomous()) tp = tref(p)
         call integ%to_physical(model, sref(:, p), qa, qda, tp)
         call perturbed_state(model, qa, qda, delta0, same_energy, qb, qdb, tp)
         res%start(:, p) = [qa, qda]
         res%delta_start(p) = phase_distance(qa, qda, qb, qdb, angle)
         res%energy_diff(p) = model%energy(tp, [qb, qdb]) - model%energy(tp, [qa, qda])
         ya = integ%to_internal(model, qa, qda, tp)
         yb = integ%to_internal(model, qb, qdb, tp)
         call integrate_sampled(integ, model, tp, ya, tp + t_span, h, sample_dt, times, sa, &
                                stat, progress)
         if (stat /= stat_ok) exit
         call integrate_sampled(integ, model, tp, yb, tp + t_span, h, sample_dt, times, sb, &
                                stat, progress)
         if (stat /= stat_ok) exit
         if (p == 1) then
            res%t = times   ! from the pair's start (pair 1 starts at 0)
            allocate (res%log10_pairs(n_pairs, size(times)))
         else if (size(times) /= size(res%t)) then   ! (the grid's tolerance keeps them)
            error stop 'internal error: divergence pairs sampled at different counts'
         end if
         do i = 1, size(times)
            call integ%to_physical(model, sa(:, i), qa, qda, times(i))
            call integ%to_physical(model, sb(:, i), qb, qdb, times(i))
            res%log10_pairs(p, i) = log10(max(phase_distance(qa, qda, qb, qdb, angle), &
                                              tiny(1.0_dp)))
         end do
         n_done = p
      end do
      if (.not. allocated(res%t)) then
         allocate (res%t(0), res%log10_pairs(0, 0))
      end if
      res%log10_pairs = res%log10_pairs(1:n_done, :)
      if (n_done > 0) then
         res%log10_mean = sum(res%log10_pairs, dim=1)/real(n_done, dp)
      else
         allocate (res%log10_mean(size(res%t)))
         res%log10_mean = 0.0_dp
      end if
   end subroutine divergence_pairs

   !> Least-squares line through (t, y = log10 |δ|) over the exponential phase.
   !> Window: [t_fit0, t_fit1] when t_fit1 > t_fit0; otherwise automatic, from
   !> the first sample `low` decades above y(1) to the first sample `high`
   !> decades below the saturation level (the median of y over the last quarter
   !> of the samples). The curve counts as saturated when that level lies at
   !> least low + high + 1 decades above y(1) and is approached before the last
   !> quarter; otherwise the window runs to the end and `saturated` is false.
   pure subroutine fit_exponential_phase(t, y, t_fit0, t_fit1, fit, low, high)
      real(dp), intent(in) :: t(:)              !! sample times [s]
      real(dp), intent(in) :: y(:)              !! log10 |δ|
      real(dp), intent(in) :: t_fit0            !! window start [s] (if t_fit1 > t_fit0)
      real(dp), intent(in) :: t_fit1            !! window end [s]; <= t_fit0: automatic
      type(line_fit_t), intent(out) :: fit      !! the fitted line
      real(dp), intent(in), optional :: low     !! decades above y(1); default 1
      real(dp), intent(in), optional :: high    !! decades below saturation; default 1.5
      real(dp) :: lo, hi, tq, sx, sy, sxx, sxy, d, resid
      real(dp), allocatable :: tail(:)
      integer :: n, i, i0, i1, m
      n = size(t)
      if (n < 3) return
      lo = 1.0_dp; if (present(low)) lo = low
      hi = 1.5_dp; if (present(high)) hi = high
      tq = t(1) + 0.75_dp*(t(n) - t(1))
      tail = pack(y, t >= tq)
      fit%saturation = median(tail)
      if (t_fit1 > t_fit0) then
         i0 = n + 1; i1 = 0
         do i = 1, n
            if (t(i) >= t_fit0 .and. t(i) <= t_fit1) then
               i0 = min(i0, i); i1 = max(i1, i)
            end if
         end do
         fit%saturated = fit%saturation >= y(1) + lo + hi + 1.0_dp
      else
         i0 = first_above(y(1) + lo)
         i1 = first_above(fit%saturation - hi)
         fit%saturated = fit%saturation >= y(1) + lo + hi + 1.0_dp .and. i1 <= n
         if (i1 <= n) fit%saturated = fit%saturated .and. t(i1) < tq
         if (.not. fit%saturated) i1 = n
         if (i0 > n) i0 = n
      end if
      m = i1 - i0 + 1
      fit%n_points = max(m, 0)
      if (m < 3) return
      fit%t_start = t(i0); fit%t_end = t(i1)
      sx = sum(t(i0:i1)); sy = sum(y(i0:i1))
      sxx = sum((t(i0:i1) - sx/m)**2)
      sxy = sum((t(i0:i1) - sx/m)*(y(i0:i1) - sy/m))
      if (sxx <= 0.0_dp) return
      d = sxy/sxx
      fit%intercept = sy/m - d*sx/m
      resid = sum((y(i0:i1) - fit%intercept - d*t(i0:i1))**2)
      fit%slope = d*log(10.0_dp)
      fit%slope_stderr = sqrt(resid/max(m - 2, 1)/sxx)*log(10.0_dp)
      fit%ok = .true.
   contains
      pure integer function first_above(level)
         real(dp), intent(in) :: level
         integer :: j
         first_above = n + 1
         do j = 1, n
            if (y(j) >= level) then
               first_above = j
               return
            end if
         end do
      end function first_above
   end subroutine fit_exponential_phase

   !> Which coordinates of `model` are angles (in rad, wrapped by 2π in distances).
   function angle_coordinates(model) result(angle)
      class(model_t), intent(in) :: model  !! the system
      logical, allocatable :: angle(:)
      character(len=:), allocatable :: name, units, p_units
      integer :: i
      allocate (angle(model%n_dof()))
      do i = 1, model%n_dof()
         call model%coordinate(i, name, units, p_units)
         angle(i) = units == 'rad'
      end do
   end function angle_coordinates
end module dpend_divergence
