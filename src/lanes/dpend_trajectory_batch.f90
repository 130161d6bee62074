!> The sweep's per-trajectory path: initial conditions of any model with
!> n degrees of freedom integrated one at a time by a fixed-step method of the
!> registry (the sweep uses rk4), each reduced to what the batch kernel
!> (`dpend_pendulum_lanes`, the double pendulum; `dpend_chain_lanes`, chains) computes: the first flip of
!> every link, the initial energy, the largest energy error, the final state and a
!> status (the kernel's st_* codes and stop rules). `dpend sweep` calls it for every
!> number of links other than 2, one block per call, so that the blocks of a sweep
!> run in parallel over the OpenMP threads with one integrator per block in flight.
!>
!> Definitions, as the kernel's (docs/sweep.md):
!> - a flip of link i is a crossing of its upward vertical, q_i = π/2 + 2π k (θ_i = q_i
!>   + π/2 leaves (−π, π]); its time is interpolated linearly in q_i within the step;
!>   t_flip is the first flip of any link;
!> - the energy error is max over the steps of |E(t_k) − E(0)|, divided by the range of
!>   the potential V_max − V_min = 2 Σ G_i (V = Σ G_i sin q_i);
!> - flip energy bound of link i: with T ≥ 0 and sin q_j ≥ −1, link i upright needs
!>   E ≥ G_i − Σ_(j≠i) G_j. An initial condition whose energy is below every link's
!>   bound (less a margin of 1e-12 Σ G_i for the rounding of E(0)) cannot flip and is
!>   not integrated (st_cannot_flip), unless opt%skip_cannot_flip is false.
!>
!> A model whose potential is not of that form (no G_i: `potential_weights` of size 0,
!> e.g. the elastic pendulum, whose coordinates are not rod angles) has no flips and no
!> flip bound: every initial condition is integrated to t_end (t_flip NaN, status
!> st_end or st_nonfinite), and its energy error is divided by the model's own
!> `energy_scale(E(0))`.
!>
!> Difference from the kernel: a step whose result is not finite (or beyond the
!> integrators' `diverged_bound`) is not taken; the trajectory ends there with
!> st_nonfinite, its final state the last finite one and t_stop the time reached.
!>
!> A damped or driven chain (damping, Coulomb friction, a moving support, applied joint
!> torques: `needs_work`) is integrated with its work integrals (dpend_work), and its
!> accuracy figure is the error of the energy balance, max over the steps of
!> |E(t_k) − E(0) + W_friction − W_support − W_torque|, in the same unit. Its flip bounds
!> hold while the energy cannot grow: with damping and friction alone (an autonomous
!> chain, dE/dt = −P_friction ≤ 0); a moving support or torques can feed any energy, so
!> every initial condition is integrated.
module dpend_trajectory_batch
   use dpend_kinds, only: dp, i8, pi, half_pi
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_lane_batch, only: batch_options_t, batch_result_t, stop_both, stop_either, &
      stop_end, st_end, st_flipped, st_cannot_flip, st_nonfinite, link_flip_bounds, &
      first_flips, bound_margin
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_indicators, only: indicators_result_t, chaos_indicators
   use dpend_work, only: needs_work, work_model, augmented_state, balance_energy
   implicit none
   private
   public :: integrate_trajectories

   real(dp), parameter :: two_pi = 2.0_dp*pi, inv_two_pi = 1.0_dp/two_pi

contains

   !> Integrate the initial conditions y0(:, j) = (q, q̇) of `model` with `integ`
   !> (a fixed-step method) of step opt%h for at most opt%n_steps steps each, with
   !> the stop rule opt%stop_rule; results as the kernel's, plus res%t_flip_link
   !> (N, n). res%t_flip1 and res%t_flip2 hold links 1 and 2 (NaN if absent);
   !> res%lyapunov is NaN (not computed on this path). With opt%vectors > 0 every
   !> trajectory runs to t_end and its fast indicators come from `chaos_indicators`
   !> (dpend_indicators, the 2N vectors of `initial_vectors`, one sample at t_end),
   !> vector 1 for MEGNO and FLI, vectors 1 and 2 for SALI and GALI_2, as the kernel.
   !> `gl` of size 0: a model without flips (see the module header).
   subroutine integrate_trajectories(model, integ, gl, opt, y0, res)
      class(model_t), intent(in) :: model            !! the system, N degrees of freedom
      class(integrator_t), intent(inout) :: integ    !! fixed-step method (rk4)
      real(dp), intent(in) :: gl(:)                  !! G_i of V = Σ G_i sin q_i [J] (N or 0)
      type(batch_options_t), intent(in) :: opt       !! step, length, stop rule
      real(dp), intent(in) :: y0(:, :)               !! (2N, n) initial states
      type(batch_result_t), intent(out) :: res       !! results
      real(dp), allocatable :: y(:), qa(:), qda(:)
      real(dp) :: bounds(size(y0, 1)/2), tf(size(y0, 1)/2)
      real(dp) :: escale, nan, margin, err
      logical :: can(size(y0, 1)/2), flips, nonfinite, works
      class(model_t), allocatable :: wm
      integer(i8) :: ks
      integer :: n, nl, j, i, stat, na

      nl = size(y0, 1)/2
      n = size(y0, 2)
      flips = size(gl) == nl
      nan = ieee_value(nan, ieee_quiet_nan)
      bounds = 0.0_dp
      if (flips) bounds = link_flip_bounds(gl)
      ! a damped or driven chain: integrated with its works (the balance's terms)
      works = needs_work(model)
      if (works) then
         call work_model(model, wm)
      else
         allocate (wm, source=model)
      end if
      ! energy can enter (support, torques): no flip bound holds
      if (.not. model%autonomous()) bounds = -huge(1.0_dp)
      na = wm%n_dof()
      margin = bound_margin*sum(gl)
      escale = 2.0_dp*sum(gl)
      res%n = n
      allocate (res%t_flip1(n), res%t_flip2(n), res%t_flip(n), res%t_flip_link(nl, n), &
                res%energy0(n), res%energy_error(n), res%t_stop(n), res%final(2*nl, n), &
                res%lyapunov(n), res%status(n), res%steps(n))
      allocate (y(2*na))
      res%lyapunov = nan
      allocate (res%megno(n), res%megno_y(n), res%fli(n), res%sali(n), res%gali2(n))
      res%megno = nan; res%megno_y = nan; res%fli = nan; res%sali = nan; res%gali2 = nan
      do j = 1, n
         res%energy0(j) = model%energy(0.0_dp, y0(:, j))   ! the chain's E(0), works 0
         do i = 1, nl
            can(i) = .not. (res%energy0(j) < bounds(i) - margin)
         end do
         if (.not. flips) then   ! no flips: integrated in full, the model's energy unit
            can = .true.
            escale = model%energy_scale(res%energy0(j))
         end if
         res%final(:, j) = y0(:, j)
         res%t_stop(j) = 0.0_dp
         res%steps(j) = 0
         res%energy_error(j) = 0.0_dp
         res%t_flip_link(:, j) = -1.0_dp   ! NaN at the end (no ordered test on NaN)
         res%status(j) = merge(st_end, st_cannot_flip, any(can))
         if (opt%n_steps < 1) then   ! t_end = 0: nothing to integrate
            res%status(j) = st_end
            cycle
         end if
         if (.not. (any(can) .or. .not. opt%skip_cannot_flip .or. opt%vectors > 0)) then
            res%energy_error(j) = nan
            cycle
         end if
         call augmented_state(wm, y0(1:nl, j), y0(nl + 1:, j), qa, qda)
         y = [qa, qda]
         call march(wm, integ, opt, flips, can, res%energy0(j), y, ks, tf, err, nonfinite)
         if (nonfinite) res%status(j) = st_nonfinite
         res%final(:, j) = [y(1:nl), y(na + 1:na + nl)]
         res%t_stop(j) = real(ks, dp)*opt%h
         res%steps(j) = int(ks)
         res%t_flip_link(:, j) = tf
         if (res%status(j) == st_nonfinite) then
            res%energy_error(j) = nan
         else
            res%energy_error(j) = err/escale
            if (ks < opt%n_steps) res%status(j) = st_flipped
         end if
         if (opt%vectors > 0) call indicators(j)
      end do
      call first_flips(res, nl)
   contains

      !> The fast indicators of trajectory j, integrated again with its tangents.
      subroutine indicators(j)
         integer, intent(in) :: j
         type(indicators_result_t) :: ind
         real(dp) :: t_end
         integer :: m
         t_end = real(opt%n_steps, dp)*opt%h
         call chaos_indicators(integ, model, 0.0_dp, y0(:, j), t_end, opt%h, t_end, ind, stat)
         if (stat /= stat_ok .or. ind%n < 1) return
         m = ind%n
         res%fli(j) = ind%log_norm(1, m)
         res%megno_y(j) = ind%megno_all(1, m)
         res%megno(j) = ind%mean_all(1, m)
         res%sali(j) = ind%sali(m)
         res%gali2(j) = ind%gali(1, m)
      end subroutine indicators
   end subroutine integrate_trajectories

   !> One trajectory from y at t = 0 by steps of opt%h: at most opt%n_steps, ended by
   !> the stop rule; the first flip time of every link (`flips` true: its q_i passes
   !> π/2 + 2π k, interpolated linearly in q_i within the step; -1 if none) and the
   !> largest |E(t_k) − E(0)| (a chain with its works: of the balance, `balance_energy`).
   !> A step that fails (not finite) is not taken.
   subroutine march(model, integ, opt, flips, can, e0, y, ks, tf, err, nonfinite)
      class(model_t), intent(in) :: model            !! the system, N degrees of freedom
      class(integrator_t), intent(inout) :: integ    !! fixed-step method (rk4)
      type(batch_options_t), intent(in) :: opt       !! step, length, stop rule
      logical, intent(in) :: flips                   !! the model's links flip
      logical, intent(in) :: can(:)                  !! link i can flip (by energy), N
      real(dp), intent(in) :: e0                     !! E(0) [J]
      real(dp), intent(inout) :: y(:)                !! state (q, q̇): initial, then final
      integer(i8), intent(out) :: ks                 !! steps taken
      real(dp), intent(out) :: tf(:)                 !! first flip of each link [s], -1: none
      real(dp), intent(out) :: err                   !! max |E(t_k) − E(0)| [J]
      logical, intent(out) :: nonfinite              !! a step was not finite
      real(dp) :: p(size(tf)), nk(size(tf)), t, hs, mk, qc
      logical :: ended
      integer :: i, nl, stat
      nl = size(tf)
      nonfinite = .false.
      t = 0.0_dp
      ks = 0
      err = 0.0_dp
      tf = -1.0_dp
      do i = 1, nl
         nk(i) = real(floor((y(i) - half_pi)*inv_two_pi, i8), dp)
      end do
      call integ%clear_step()
      do
         p = y(1:nl)
         hs = opt%h
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) then
            nonfinite = .true.
            exit
         end if
         ks = ks + 1
         t = real(ks, dp)*opt%h
         err = max(err, abs(balance_energy(model, t, y) - e0))
         ! link i: index of the last upward vertical below q_i, π/2 + 2π k
         do i = 1, merge(nl, 0, flips)
            mk = real(floor((y(i) - half_pi)*inv_two_pi, i8), dp)
            if (mk /= nk(i)) then
               if (tf(i) < 0.0_dp) then
                  qc = half_pi + two_pi*max(mk, nk(i))
                  tf(i) = (real(ks - 1, dp) + (qc - p(i))/(y(i) - p(i)))*opt%h
               end if
               nk(i) = mk
            end if
         end do
         ended = ks >= opt%n_steps
         select case (opt%stop_rule)
         case (stop_both)
            ended = ended .or. all(tf >= 0.0_dp .or. .not. can)
         case (stop_either)
            ended = ended .or. any(tf >= 0.0_dp)
         case (stop_end)
         end select
         if (ended) exit
      end do
   end subroutine march
end module dpend_trajectory_batch
