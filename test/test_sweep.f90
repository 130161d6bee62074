!> Sweeps over initial conditions: the batch kernel against the library's
!> one-trajectory RK4, its tangent map against finite differences, flip times
!> against a quadrature, the flip energy bound against brute force, and the
!> `dpend sweep` command as a process: bitwise independence of threads, blocks and
!> lane positions, resume after kill -9, refusal of another configuration, bad input.
module test_sweep
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t, energy, potential_energy
   use dpend_pendulum, only: pendulum_model
   use dpend_rk_explicit, only: rk4_t
   use dpend_lane_batch, only: batch_options_t, batch_result_t, lane_width, resync_steps, &
      stop_either, stop_end, st_cannot_flip, st_nonfinite
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_pendulum_kernel, only: batch_coef_t, batch_coef, rk4_lanes, lane_trig_t, &
      set_lane_trig, sincos_exact, flip_energy_bounds
   use dpend_pendulum_tangent_lanes, only: rk4_tangent_lanes
   use dpend_hdf5, only: h5file_t, is_hdf5
   use test_cli, only: dpend_binary, run_command, scratch_dir, read_text, expect_rejected, &
      args_of
   use dpend_cli, only: arg_t, to_str
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep
   use dpend_sweep_setup, only: block_share_note
   use dpend_sweep_setup, only: block_initial_conditions, sweep_setup_t, build_setup, block_range, &
      block_parameters, parameter_names
   use dpend_sweep_engine, only: compute_block
   use dpend_sweep_resume, only: open_output
   use dpend_sweep_layout, only: write_block
   use dpend_lane_batch, only: link_flip_bounds
   use dpend_chain, only: chain_t, chain_model
   use dpend_indicators, only: indicators_result_t, chaos_indicators
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, model_spec, new_model
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error, check_same_time
   implicit none
   private
   public :: collect_sweep

   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
   real(dp), parameter :: half_pi = 0.5_dp*pi

   !> Result datasets compared bit for bit.
   character(len=*), parameter :: real_sets(10) = [character(len=20) :: '/sweep/t_flip', &
      '/sweep/t_flip1', '/sweep/t_flip2', '/sweep/energy0', '/sweep/energy_error', &
      '/sweep/t_stop', '/sweep/final/q1', '/sweep/final/q2', '/sweep/final/w1', &
      '/sweep/final/w2']

contains

   subroutine collect_sweep(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('batch_matches_rk4', test_batch_matches_rk4), &
               new_unittest('tangent_matches_finite_differences', test_tangent), &
               new_unittest('fallback_lanes_bitwise_and_accurate', test_fallback_lanes), &
               new_unittest('carried_trig_drift', test_carried_trig), &
               new_unittest('runaway_lanes_end_without_overflow', test_runaway), &
               new_unittest('flip_time_single_link', test_flip_time), &
               new_unittest('energy_bound_brute_force', test_energy_bound), &
               new_unittest('energy_bound_no_flip_below', test_bound_dynamics), &
               new_unittest('help', test_help), &
               new_unittest('threads_and_blocks_bitwise', test_threads_blocks), &
               new_unittest('list_matches_grid', test_list_matches_grid), &
               new_unittest('resume_after_kill', test_resume_after_kill), &
               new_unittest('resume_after_kill_parameters', test_resume_parameters), &
               new_unittest('resume_torn_blocks', test_torn_blocks), &
               new_unittest('parameter_axes', test_parameter_axes), &
               new_unittest('agreement_megno_lambda1', test_agreement), &
               new_unittest('compare_indicator_values', test_compare_indicator), &
               new_unittest('block_share_note', test_block_share_note), &
               new_unittest('config_mismatch_refused', test_mismatch), &
               new_unittest('bad_input_rejected', test_bad_input), &
               new_unittest('export_matrix_and_compare', test_export_compare), &
               new_unittest('links3_matches_simulate', test_links3_simulate), &
               new_unittest('per_trajectory_matches_kernel', test_per_trajectory_n2), &
               new_unittest('links_axes_refused', test_links_refused), &
               new_unittest('links_bound_brute_force', test_links_bound), &
               new_unittest('links3_list_matches_grid', test_links3_list), &
               new_unittest('indicators_kernel_match_one_orbit', test_indicators_kernel), &
               new_unittest('indicators_per_trajectory_match_kernel', test_indicators_paths), &
               new_unittest('elastic_pixels_match_single_runs', test_elastic_pixels), &
               new_unittest('parameter_maps_of_other_bodies', test_parameter_bodies), &
               new_unittest('named_axes_g_theta1_pixels_match_direct_runs', test_named_g), &
               new_unittest('named_axes_bodies_pixels_match_direct_runs', test_named_bodies), &
               new_unittest('named_axis_out_of_range_refused', test_named_refused)]
   end subroutine collect_sweep

   ! ------------------------------------------------------------ kernel ---

   !> The batch kernel (Lagrange form, SoA lanes) and the library's rk4_t on the
   !> corrected Newton–Euler form agree after 2000 steps on regular trajectories.
   subroutine test_batch_matches_rk4(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      type(rk4_t) :: rk
      real(dp) :: y0(4, 5), y(4), t, h
      integer :: j, k, stat
      y0(:, 1) = [-half_pi + 0.1_dp, -half_pi - 0.2_dp, 0.0_dp, 0.0_dp]
      y0(:, 2) = [-half_pi + 0.5_dp, -half_pi + 0.3_dp, 0.2_dp, -0.1_dp]
      y0(:, 3) = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      y0(:, 4) = [-1.0_dp, -2.0_dp, 1.0_dp, 2.0_dp]
      y0(:, 5) = [-half_pi, -half_pi, 0.0_dp, 0.0_dp]
      par = pendulum_t(m1=1.3_dp, m2=0.7_dp, l1=0.9_dp, l2=1.2_dp, g=9.81_dp)
      opt%h = 1e-3_dp
      opt%n_steps = 2000
      opt%stop_rule = stop_end
      opt%skip_cannot_flip = .false.
      call integrate_batch(par, opt, y0, res)
      do j = 1, size(y0, 2)
         y = y0(:, j)
         t = 0.0_dp
         do k = 1, 2000
            h = 1e-3_dp
            call rk%step(pendulum_model(par), t, y, h, stat)
         end do
         call check(error, res%final(:, j), y, 'final state', abs=1e-11_dp)
         call check(error, res%energy0(j), energy(par, y0(1:2, j), y0(3:4, j)), 'E(0)', &
                    abs=1e-12_dp)
         call check(error, res%t_stop(j), 2.0_dp, 't_stop', abs=1e-12_dp)
         call check_true(error, res%steps(j) == 2000, 'steps')
      end do
   end subroutine test_batch_matches_rk4

   !> The kernel's fallback path: lanes with a stage offset |d| > 1/16 rad (fast
   !> spin) take `rk4_lanes`' reference step; a lane at an angle beyond
   !> `sincos_exact_max` (sin and cos set by the intrinsic) stays on the fast path.
   !> Each lane's result is bitwise the same whatever the other lanes hold and
   !> whichever position it has (alone among ordinary lanes, or every lane holding
   !> the same special state), and it agrees with the library's rk4_t.
   subroutine test_fallback_lanes(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: w = lane_width, n_special = 3
      type(batch_coef_t) :: c
      type(pendulum_t) :: par
      type(rk4_t) :: rk
      real(dp), dimension(w) :: q1, q2, w1, w2, e, r1, r2, rw1, rw2, q1x, q2x, w1x, w2x
      real(dp) :: special(4, n_special), plain(4, w), y(4), t, hh, worst
      type(lane_trig_t) :: tr
      real(dp), parameter :: h = 1e-3_dp
      integer :: i, j, k, pos, stat
      logical :: same
      par = pendulum_t(m1=1.3_dp, m2=0.7_dp, l1=0.9_dp, l2=1.2_dp, g=9.81_dp)
      c = batch_coef(par)
      ! ordinary lanes, two that need the fallback: a fast spin of link 2
      ! (h/2 |q̇2| = 0.1 > 1/16) and of link 1 in the fourth stage only (h |q̇1| = 0.07);
      ! and one on the fast path at an angle beyond sincos_exact_max (2^20 π/2 = 1.6e6 rad)
      do i = 1, w
         plain(:, i) = [-1.0_dp + 0.1_dp*i, 0.5_dp - 0.07_dp*i, 0.3_dp*sin(real(i, dp)), &
                        -0.2_dp*cos(real(i, dp))]
      end do
      special(:, 1) = [0.3_dp, -0.4_dp, 1.0_dp, 200.0_dp]
      special(:, 2) = [-0.2_dp, 1.1_dp, 70.0_dp, 0.5_dp]
      special(:, 3) = [2.0e6_dp, -0.7_dp, 0.4_dp, -0.3_dp]
      ! reference: the ordinary lanes alone, and each special lane on every lane
      q1 = plain(1, :); q2 = plain(2, :); w1 = plain(3, :); w2 = plain(4, :)
      call set_lane_trig(q1, q2, tr)
      do k = 1, 10
         call rk4_lanes(c, h, q1, q2, w1, w2, e, tr)
      end do
      r1 = q1; r2 = q2; rw1 = w1; rw2 = w2
      worst = 0
      do j = 1, n_special
         q1 = special(1, j); q2 = special(2, j); w1 = special(3, j); w2 = special(4, j)
         call set_lane_trig(q1, q2, tr)
         do k = 1, 10
            call rk4_lanes(c, h, q1, q2, w1, w2, e, tr)
         end do
         ! the same special lane at three positions among ordinary lanes
         do pos = 1, w, 7
            call load_mixed(j, pos)
            call set_lane_trig(q1x, q2x, tr)
            do k = 1, 10
               call rk4_lanes(c, h, q1x, q2x, w1x, w2x, e, tr)
            end do
            same = q1x(pos) == q1(1) .and. q2x(pos) == q2(1) .and. w1x(pos) == w1(1) &
                   .and. w2x(pos) == w2(1)
            do i = 1, w
               if (i /= pos) same = same .and. q1x(i) == r1(i) .and. q2x(i) == r2(i) &
                                    .and. w1x(i) == rw1(i) .and. w2x(i) == rw2(i)
            end do
            call check_true(error, same, 'fallback lane or its neighbours changed with position')
            if (allocated(error)) return
         end do
         ! against the library's rk4 (Newton–Euler form, intrinsic sin and cos)
         y = special(:, j); t = 0.0_dp
         do k = 1, 10
            hh = h
            call rk%step(pendulum_model(par), t, y, hh, stat)
         end do
         worst = max(worst, maxval(abs([q1(1), q2(1), w1(1), w2(1)] - y) &
                                   /max(1.0_dp, abs(y))))
      end do
      ! (two formulations: Lagrange's in the kernel, Newton–Euler in rk4_t; at 200 rad/s
      ! the accelerations reach 4e4 rad/s² and rounding differs at ~1e-11)
      call check_true(error, worst <= 1e-10_dp, 'fallback lanes differ from rk4_t')
      write (*, '(a, es9.2)') '    fallback lanes vs rk4_t (max relative, 10 steps): ', worst
   contains
      subroutine load_mixed(jj, p)
         integer, intent(in) :: jj, p
         q1x = plain(1, :); q2x = plain(2, :); w1x = plain(3, :); w2x = plain(4, :)
         q1x(p) = special(1, jj); q2x(p) = special(2, jj)
         w1x(p) = special(3, jj); w2x(p) = special(4, jj)
      end subroutine load_mixed
   end subroutine test_fallback_lanes

   !> `rk4_lanes` carries sin and cos of the angles from step to step: after
   !> `resync_steps` steps (when integrate_batch sets them exactly again) of 16
   !> chaotic and rotating trajectories, all on the fast path (h |q̇| <= 3/64 at every
   !> step, 3/4 of the fallback's 1/16, with a margin for the stage velocities: no
   !> fallback restarts them from exact values), they are still within 1e-14
   !> of sin and cos of the angles reached (`sincos_exact`, within 3 ulp of the
   !> intrinsic), and s² + c² within 1e-14 of 1.
   subroutine test_carried_trig(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: w = lane_width
      type(batch_coef_t) :: c
      type(lane_trig_t) :: tr
      real(dp), dimension(w) :: q1, q2, w1, w2, e, s1, c1, s2, c2
      real(dp) :: worst, worst_norm, fastest
      real(dp), parameter :: h = 2e-3_dp
      integer :: i, k
      c = batch_coef(pendulum_t())
      do i = 1, w
         q1(i) = -3.0_dp + 0.37_dp*i; q2(i) = 2.5_dp - 0.29_dp*i
         w1(i) = 2.0_dp*sin(real(3*i, dp)); w2(i) = 4.0_dp*cos(real(i, dp))
      end do
      call set_lane_trig(q1, q2, tr)
      fastest = 0
      do k = 1, resync_steps
         call rk4_lanes(c, h, q1, q2, w1, w2, e, tr)
         fastest = max(fastest, maxval(abs(w1)), maxval(abs(w2)))
      end do
      call sincos_exact(q1, s1, c1)
      call sincos_exact(q2, s2, c2)
      worst = max(maxval(abs(tr%s1 - s1)), maxval(abs(tr%c1 - c1)), &
                  maxval(abs(tr%s2 - s2)), maxval(abs(tr%c2 - c2)))
      worst_norm = max(maxval(abs(tr%s1**2 + tr%c1**2 - 1.0_dp)), &
                       maxval(abs(tr%s2**2 + tr%c2**2 - 1.0_dp)))
      write (*, '(a, i0, a, es9.2, a, es9.2, a, f0.1, a, f0.4)') '    after ', resync_steps, &
         ' carried steps: |sin, cos - exact| <= ', worst, ', |s² + c² - 1| <= ', &
         worst_norm, ' (max |q| ', max(maxval(abs(q1)), maxval(abs(q2))), &
         ' rad, max h |q̇| ', h*fastest
      call check_true(error, h*fastest <= 3.0_dp/64.0_dp, 'a lane left the fast path')
      if (allocated(error)) return
      call check_true(error, worst <= 1e-14_dp .and. worst_norm <= 1e-14_dp, &
                      'carried sin and cos drifted')
   end subroutine test_carried_trig

   !> An unstable step (0.5 s at 1e4 rad/s) makes every trajectory run away: each
   !> lane ends as st_nonfinite, with and without the tangent (λ1), and no step
   !> overflows (the debug profile traps on overflow and invalid).
   subroutine test_runaway(error)
      type(error_t), allocatable, intent(out) :: error
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      real(dp) :: y0(4, 20)
      integer :: j, pass
      do j = 1, size(y0, 2)
         y0(:, j) = [0.1_dp*j, -0.2_dp*j, 1e4_dp*cos(real(j, dp)), -1e4_dp*sin(real(j, dp))]
      end do
      opt%h = 0.5_dp
      opt%n_steps = 20
      opt%stop_rule = stop_end
      do pass = 1, 2
         opt%lyapunov = pass == 2
         call integrate_batch(pendulum_t(), opt, y0, res)
         call check_true(error, all(res%status == st_nonfinite), 'runaway lanes not ended')
         if (allocated(error)) return
         call check_true(error, all(res%steps < opt%n_steps), 'runaway lanes ran to the end')
         if (allocated(error)) return
      end do
   end subroutine test_runaway

   !> The tangent RK4 map against central differences of the RK4 map.
   subroutine test_tangent(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: w = lane_width
      type(batch_coef_t) :: c
      real(dp), dimension(w) :: q1, q2, w1, w2, u1, u2, v1, v2, e
      real(dp), dimension(w) :: p1, p2, pw1, pw2, m1, m2, mw1, mw2
      real(dp), parameter :: eps = 1e-6_dp, h = 2e-3_dp
      type(lane_trig_t) :: trp, trm
      integer :: i, k
      c = batch_coef(pendulum_t())
      do i = 1, w
         q1(i) = -1.0_dp + 0.15_dp*i; q2(i) = 0.5_dp - 0.1_dp*i
         w1(i) = 0.3_dp*sin(real(i, dp)); w2(i) = -0.2_dp*cos(real(i, dp))
         u1(i) = 1.0_dp; u2(i) = -0.5_dp; v1(i) = 0.25_dp*i; v2(i) = 0.1_dp
      end do
      p1 = q1 + eps*u1; p2 = q2 + eps*u2; pw1 = w1 + eps*v1; pw2 = w2 + eps*v2
      m1 = q1 - eps*u1; m2 = q2 - eps*u2; mw1 = w1 - eps*v1; mw2 = w2 - eps*v2
      call set_lane_trig(p1, p2, trp)
      call set_lane_trig(m1, m2, trm)
      do k = 1, 100
         call rk4_tangent_lanes(c, h, q1, q2, w1, w2, u1, u2, v1, v2, e)
         call rk4_lanes(c, h, p1, p2, pw1, pw2, e, trp)
         call rk4_lanes(c, h, m1, m2, mw1, mw2, e, trm)
      end do
      do i = 1, w
         call check(error, (p1(i) - m1(i))/(2*eps), u1(i), 'du1', abs=1e-6_dp, rel=1e-6_dp)
         call check(error, (p2(i) - m2(i))/(2*eps), u2(i), 'du2', abs=1e-6_dp, rel=1e-6_dp)
         call check(error, (pw1(i) - mw1(i))/(2*eps), v1(i), 'dv1', abs=1e-6_dp, rel=1e-6_dp)
         call check(error, (pw2(i) - mw2(i))/(2*eps), v2(i), 'dv2', abs=1e-6_dp, rel=1e-6_dp)
      end do
   end subroutine test_tangent

   !> With m2 negligible, link 1 is a compound pendulum: launched from the bottom
   !> with w0 it reaches the top after t = ∫ dq / sqrt(w0² - (3g/L1)(1 + sin q))
   !> over [-π/2, π/2] (quadrature). Both senses of rotation.
   subroutine test_flip_time(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      real(dp) :: y0(4, 2), expected, q, dq, w0
      integer :: i
      integer, parameter :: n = 20000
      par = pendulum_t(m1=1.0_dp, m2=1e-10_dp, l1=1.0_dp, l2=1.0_dp, g=9.8_dp)
      w0 = 9.0_dp
      ! composite Simpson
      dq = pi/n
      expected = 0.0_dp
      do i = 0, n
         q = -half_pi + i*dq
         expected = expected + merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), &
                                     i == 0 .or. i == n)/sqrt(w0**2 - 3.0_dp*par%g/par%l1 &
                                                              *(1.0_dp + sin(q)))
      end do
      expected = expected*dq/3.0_dp
      y0(:, 1) = [-half_pi, -half_pi, w0, 0.0_dp]
      y0(:, 2) = [-half_pi, -half_pi, -w0, 0.0_dp]
      opt%h = 1e-3_dp
      opt%n_steps = 1000
      opt%stop_rule = stop_end
      call integrate_batch(par, opt, y0, res)
      call check(error, res%t_flip1(1), expected, 'counter-clockwise flip time', abs=1e-6_dp)
      call check(error, res%t_flip1(2), expected, 'clockwise flip time', abs=1e-6_dp)
      if (allocated(error)) return
      ! the light link 2 is whipped over first; stop_either ends at that step
      call check_true(error, .not. ieee_is_nan(res%t_flip2(1)), 'link 2 flips')
      if (allocated(error)) return
      call check(error, res%t_flip(1), min(res%t_flip1(1), res%t_flip2(1)), 'first of both')
      opt%stop_rule = stop_either
      call integrate_batch(par, opt, y0, res)
      call check_true(error, res%steps(1) == ceiling(res%t_flip(1)/opt%h), &
                      'stop_either: stopped at the step of the first flip')
   end subroutine test_flip_time

   !> The least energy to bring each link to the top, against a brute-force
   !> minimum of V over the other angle, and the classic criterion
   !> 3 cos θ1 + cos θ2 > 2 for equal uniform rods.
   subroutine test_energy_bound(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: pars(3), par
      real(dp) :: bounds(2), vmin1, vmin2, x, th1, th2, e0, lhs
      integer :: k, i, j
      integer, parameter :: n = 200000
      pars(1) = pendulum_t()
      pars(2) = pendulum_t(m1=0.5_dp, m2=2.0_dp, l1=0.6_dp, l2=1.5_dp, g=9.81_dp)
      pars(3) = pendulum_t(m1=3.0_dp, m2=0.2_dp, l1=0.3_dp, l2=2.5_dp, g=1.62_dp)
      do k = 1, 3
         bounds = flip_energy_bounds(pars(k))
         vmin1 = huge(1.0_dp); vmin2 = huge(1.0_dp)
         do i = 0, n - 1
            x = 2*pi*i/n
            vmin1 = min(vmin1, potential_energy(pars(k), [half_pi, x]))
            vmin2 = min(vmin2, potential_energy(pars(k), [x, half_pi]))
         end do
         call check(error, bounds(1), vmin1, 'link 1 bound', abs=1e-8_dp)
         call check(error, bounds(2), vmin2, 'link 2 bound', abs=1e-8_dp)
      end do
      par = pendulum_t()
      bounds = flip_energy_bounds(par)
      do i = -60, 60
         do j = -60, 60
            th1 = 0.05_dp*i; th2 = 0.05_dp*j
            lhs = 3*cos(th1) + cos(th2)
            if (abs(lhs - 2) < 1e-9_dp) cycle
            e0 = energy(par, [th1 - half_pi, th2 - half_pi], [0.0_dp, 0.0_dp])
            call check_true(error, (e0 < minval(bounds)) .eqv. (lhs > 2), &
                            'cannot flip <=> 3 cos th1 + cos th2 > 2')
         end do
      end do
   end subroutine test_energy_bound

   !> Below the bound nothing is integrated; forced through the integrator (the
   !> Lyapunov option integrates everything) no such trajectory flips in 30 s.
   subroutine test_bound_dynamics(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      real(dp) :: y0(4, 40), th1, th2
      integer :: j
      do j = 1, 40   ! just inside 3 cos θ1 + cos θ2 = 2, from rest
         th2 = -pi + 2*pi*(j - 0.5_dp)/40
         th1 = acos((2.0_dp - cos(th2))/3.0_dp) - 1e-3_dp
         y0(:, j) = [th1 - half_pi, th2 - half_pi, 0.0_dp, 0.0_dp]
      end do
      opt%h = 0.01_dp
      opt%n_steps = 100
      call integrate_batch(par, opt, y0, res)
      call check_true(error, all(res%status == st_cannot_flip), 'status cannot flip')
      call check_true(error, all(res%steps == 0), 'not integrated')
      call check_true(error, all(ieee_is_nan(res%t_flip)), 'no flip time')
      opt%n_steps = 3000
      opt%lyapunov = .true.
      call integrate_batch(par, opt, y0, res)
      call check_true(error, all(res%steps == 3000), 'integrated with lyapunov')
      call check_true(error, all(ieee_is_nan(res%t_flip)), 'no flip below the bound')
   end subroutine test_bound_dynamics

   ! ----------------------------------------------------------- command ---

   subroutine test_help(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat, i
      character(len=12), parameter :: opts(18) = [character(len=12) :: '--axis1', '--n1', &
         '--min1', '--max2', '--ic-file', '--time-unit', '--dt', '--t-end', '--stop-at', &
         '--lyapunov', '--block', '--threads', '--quiet', '--force', '--output', 'theta1', &
         '--indicator', 'm2/m1']
      dir = scratch_dir('sweephelp')
      stat = run_command(dir, 'sweep --help')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'sweep --help exits 0')
      do i = 1, size(opts)
         call check_true(error, index(text, trim(opts(i))) > 0, 'help mentions '//trim(opts(i)))
      end do
      call execute_command_line('rm -rf '//dir)
   end subroutine test_help

   !> Threads 1 and 2, blocks of 1, 3 and all rows, give bitwise equal results.
   subroutine test_threads_blocks(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, common
      integer :: stat
      dir = scratch_dir('sweepthr')
      common = 'sweep --quiet --n 16 --t-end 30 --dt 0.02 --stats --output '
      stat = run_command(dir, common//dir//'/a.h5 --threads 1 --block 16')
      call check_true(error, stat == 0, 'run a exits 0')
      stat = run_command(dir, common//dir//'/b.h5 --threads 2 --block 48')
      call check_true(error, stat == 0, 'run b exits 0')
      stat = run_command(dir, common//dir//'/c.h5 --threads 2 --block 100000')
      call check_true(error, stat == 0, 'run c exits 0')
      if (allocated(error)) return
      call same_results(error, dir//'/a.h5', dir//'/b.h5', .true.)
      call same_results(error, dir//'/a.h5', dir//'/c.h5', .true.)
      ! with the Lyapunov exponent (every trajectory to t_end)
      common = 'sweep --quiet --n 8 --t-end 10 --dt 0.02 --lyapunov --output '
      stat = run_command(dir, common//dir//'/d.h5 --threads 1 --block 8')
      call check_true(error, stat == 0, 'run d exits 0')
      stat = run_command(dir, common//dir//'/e.h5 --threads 2 --block 1000')
      call check_true(error, stat == 0, 'run e exits 0')
      if (allocated(error)) return
      call same_results(error, dir//'/d.h5', dir//'/e.h5', .false.)
      call same_dataset(error, dir//'/d.h5', dir//'/e.h5', '/sweep/lyapunov')
      ! with the fast indicators (one and two deviation vectors per lane)
      common = 'sweep --quiet --n 8 --t-end 10 --dt 0.02 --output '
      stat = run_command(dir, common//dir//'/f.h5 --threads 1 --block 8 --indicator megno')
      call check_true(error, stat == 0, 'run f exits 0')
      stat = run_command(dir, common//dir//'/g.h5 --threads 2 --block 1000 --indicator megno')
      call check_true(error, stat == 0, 'run g exits 0')
      stat = run_command(dir, common//dir//'/h.h5 --threads 1 --block 24 --indicator gali2')
      call check_true(error, stat == 0, 'run h exits 0')
      stat = run_command(dir, common//dir//'/i.h5 --threads 2 --block 8 --indicator gali2')
      call check_true(error, stat == 0, 'run i exits 0')
      if (allocated(error)) return
      call same_results(error, dir//'/f.h5', dir//'/g.h5', .false.)
      call same_dataset(error, dir//'/f.h5', dir//'/g.h5', '/sweep/megno')
      call same_dataset(error, dir//'/f.h5', dir//'/g.h5', '/sweep/megno_y')
      call same_results(error, dir//'/h.h5', dir//'/i.h5', .false.)
      call same_dataset(error, dir//'/h.h5', dir//'/i.h5', '/sweep/gali2')
      ! the state of a pixel does not depend on the number of vectors it carries
      call same_dataset(error, dir//'/f.h5', dir//'/h.h5', '/sweep/final/q1')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_threads_blocks

   !> A list of grid points, shuffled, in text and HDF5 form, gives the grid's
   !> results bit for bit (other lanes, other blocks, other neighbours).
   subroutine test_list_matches_grid(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, common
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), tg(:, :), tl(:), ql(:), qg(:, :), ics(:, :)
      integer, allocatable :: sg(:, :), sl(:)
      integer :: stat, unit, k
      integer, parameter :: pick(2, 7) = reshape([3, 5, 16, 1, 8, 8, 1, 16, 12, 2, 7, 13, &
                                                  15, 15], [2, 7])
      character(len=2) :: kind
      dir = scratch_dir('sweeplist')
      common = ' --quiet --t-end 30 --dt 0.02 --threads 2 '
      stat = run_command(dir, 'sweep --n 16 --output '//dir//'/grid.h5'//common)
      call check_true(error, stat == 0, 'grid run exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/grid.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/t_flip', tg, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/q1', qg, error)
      if (.not. allocated(error)) call h5%read('/sweep/status', sg, error)
      call h5%close()
      if (allocated(error)) return
      allocate (ics(4, size(pick, 2)))
      do k = 1, size(pick, 2)
         ics(:, k) = [ax1(pick(1, k)) - half_pi, ax2(pick(2, k)) - half_pi, 0.0_dp, 0.0_dp]
      end do
      open (newunit=unit, file=dir//'/ics.txt', status='replace', action='write')
      write (unit, '(a)') '# q1 q2 w1 w2'
      do k = 1, size(pick, 2)
         write (unit, '(4es26.17e3)') ics(:, k)
      end do
      close (unit)
      call h5%open(dir//'/ics.h5', 'w', error)
      if (.not. allocated(error)) call h5%write('/initial', ics, error)
      call h5%close()
      if (allocated(error)) return
      stat = run_command(dir, 'sweep --ic-file '//dir//'/ics.txt --block 3 --output '// &
                         dir//'/tx.h5'//common)
      call check_true(error, stat == 0, 'text list run exits 0')
      stat = run_command(dir, 'sweep --ic-file '//dir//'/ics.h5 --output '// &
                         dir//'/h5.h5'//common)
      call check_true(error, stat == 0, 'HDF5 list run exits 0')
      if (allocated(error)) return
      do stat = 1, 2
         kind = merge('tx', 'h5', stat == 1)
         call h5%open(dir//'/'//kind//'.h5', 'r', error)
         if (.not. allocated(error)) call h5%read('/sweep/t_flip', tl, error)
         if (.not. allocated(error)) call h5%read('/sweep/final/q1', ql, error)
         if (.not. allocated(error)) call h5%read('/sweep/status', sl, error)
         call h5%close()
         if (allocated(error)) return
         do k = 1, size(pick, 2)
            call check_true(error, bits(tl(k)) == bits(tg(pick(1, k), pick(2, k))) .and. &
                            bits(ql(k)) == bits(qg(pick(1, k), pick(2, k))) .and. &
                            sl(k) == sg(pick(1, k), pick(2, k)), &
                            kind//' list entry equals its grid pixel bit for bit')
         end do
      end do
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_list_matches_grid

   !> kill -9 three times at moments spread over the run, then resume: the file
   !> equals an uninterrupted run's, and a finished file is left as it is.
   subroutine test_resume_after_kill(error)
      type(error_t), allocatable, intent(out) :: error
      call resume_case(error, 'sweepkill', '', .false.)
   end subroutine test_resume_after_kill

   !> The same for a MEGNO map over (theta1, m2/m1): per-pixel parameters and
   !> indicators resume bit for bit.
   subroutine test_resume_parameters(error)
      type(error_t), allocatable, intent(out) :: error
      call resume_case(error, 'sweepkillp', '--axis2 m2/m1 --min2 0.5 --max2 2 ' &
                       //'--indicator megno ', .true.)
   end subroutine test_resume_parameters

   !> kill -9 and resume a sweep with the extra arguments `extra`.
   subroutine resume_case(error, name, extra, indicators)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), intent(in) :: name, extra
      logical, intent(in) :: indicators
      character(len=:), allocatable :: dir, args, text
      integer :: stat, k, n, count_start, count_end, rate
      real(dp) :: secs, t_end
      integer, allocatable :: done(:)
      type(h5file_t) :: h5
      character(len=16) :: delay
      logical :: partial
      dir = scratch_dir(name)
      ! a run long enough (>= ~1 s, whatever the build profile) to be killed midway
      t_end = 60.0_dp
      do k = 1, 3
         write (delay, '(f0.1)') t_end
         args = 'sweep --quiet --n 32 --t-end '//trim(delay)//' --dt 0.02 --block 32 ' &
                //'--stats --threads 2 '//extra//' --force --output '
         call system_clock(count_start, rate)
         stat = run_command(dir, args//dir//'/ref.h5')
         call system_clock(count_end)
         call check_true(error, stat == 0, 'uninterrupted run exits 0')
         if (allocated(error)) return
         secs = real(count_end - count_start, dp)/rate
         if (secs >= 1.0_dp) exit
         t_end = t_end*min(20.0_dp, 1.5_dp/max(secs, 0.05_dp))
      end do
      args = args(:index(args, '--force') - 1)//'--output '
      partial = .false.
      do k = 1, 3
         write (delay, '(f0.3)') secs*(0.15_dp + 0.05_dp*k)
         call execute_command_line(dpend_binary()//' '//args//dir// &
            '/run.h5 > /dev/null 2>&1 & pid=$!; sleep '//trim(delay)// &
            '; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null; true', exitstat=stat)
         ! the working file run.h5.part holds the blocks done so far
         if (.not. is_hdf5(dir//'/run.h5.part')) cycle   ! killed before the file existed
         call h5%open(dir//'/run.h5.part', 'r', error)
         if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
         call h5%close()
         call check_true(error, .not. allocated(error), 'file valid after kill -9')
         if (allocated(error)) return
         if (any(done == 0)) partial = .true.
      end do
      call check_true(error, partial, 'a kill hit a run in progress')
      stat = run_command(dir, args//dir//'/run.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'resumed run exits 0: '//text)
      if (allocated(error)) return
      call same_results(error, dir//'/ref.h5', dir//'/run.h5', .true.)
      if (indicators) then
         call same_dataset(error, dir//'/ref.h5', dir//'/run.h5', '/sweep/megno')
         call same_dataset(error, dir//'/ref.h5', dir//'/run.h5', '/sweep/param/m2')
      end if
      call same_dataset_i(error, dir//'/ref.h5', dir//'/run.h5', '/sweep/done')
      call same_attr(error, dir//'/ref.h5', dir//'/run.h5', 'config')
      stat = run_command(dir, args//dir//'/run.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'complete') > 0, &
                      'rerun of a complete file: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine resume_case

   !> A kill -9 during the write of a block's chunk leaves it torn: part new data,
   !> part old, under a checksum that no longer matches (Linux lets a fatal signal
   !> cut a write between pages). The block is not flagged done, so the resume
   !> rewrites it: a working file with two such blocks (one of them the grid's last,
   !> partial chunk) resumes to the uninterrupted run's result bit for bit. A torn
   !> block flagged done (damage, not a kill) is refused.
   subroutine test_torn_blocks(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=16), parameter :: words(14) = [character(len=16) :: 'sweep', '--quiet', &
         '--n1', '10', '--n2', '7', '--block', '20', '--t-end', '3', '--stats', &
         '--threads', '1', '--output']
      type(arg_t), allocatable :: args(:)
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: res
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: dir, line, text
      integer, allocatable :: done(:)
      integer :: j, b, complete, stat, n
      logical :: help
      integer, parameter :: torn(2) = [2, 4]
      real(dp), allocatable :: e(:, :)
      dir = scratch_dir('sweeptorn')
      line = ''
      do j = 1, size(words)
         line = line//trim(words(j))//' '
      end do
      stat = run_command(dir, line//dir//'/ref.h5')
      call check_true(error, stat == 0, 'uninterrupted run exits 0')
      if (allocated(error)) return
      ! the working file of run.h5 with every block written and flagged done
      allocate (args(size(words)))
      do j = 2, size(words)
         args(j - 1)%s = trim(words(j))
      end do
      args(size(words))%s = dir//'/run.h5'
      call parse_sweep(args, cfg, help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      if (.not. allocated(err)) call open_output(setup, h5, done, complete, err)
      call check_true(error, .not. allocated(err) .and. setup%nblocks == 4, &
                      'working file created, 4 blocks')
      if (allocated(error)) return
      do b = 1, setup%nblocks
         call compute_block(setup, b, res)
         if (.not. allocated(err)) call write_block(h5, setup, b, res, err)
      end do
      call h5%close()
      call check_true(error, .not. allocated(err), 'blocks written')
      if (allocated(error)) return
      ! tear blocks 2 and 4 (row 7 of 7: a partial chunk) in final/q2 (energy0 is
      ! symmetric in theta2 = -pi, pi: rows 1 and 7 hold the same values)
      call h5%open(dir//'/run.h5.part', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/final/q2', e, error)
      call h5%close()
      if (allocated(error)) return
      ! a copy in which block 3, torn, is still flagged done: refused, naming it
      call execute_command_line('cp '//dir//'/run.h5.part '//dir//'/bad.h5.part')
      call tear(dir//'/bad.h5.part', setup, 3, flagged=.true.)
      if (allocated(error)) return
      stat = run_command(dir, line//dir//'/bad.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'damaged') > 0 .and. &
                      index(text, '/sweep/final/q2 does not read back in block 3') > 0, &
                      'a torn block flagged done is refused in one line: '//text)
      if (allocated(error)) return
      do j = 1, size(torn)
         call tear(dir//'/run.h5.part', setup, torn(j))
         if (allocated(error)) return
      end do
      stat = run_command(dir, line//dir//'/run.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'resume over torn blocks exits 0: '//text)
      if (allocated(error)) return
      call same_results(error, dir//'/ref.h5', dir//'/run.h5', .true.)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> Flip a byte in the middle of block b's final/q2 chunk (uncompressed: found
      !> in the file by its values) and flag the block not done, unless `flagged`.
      subroutine tear(path, setup, b, flagged)
         character(len=*), intent(in) :: path
         type(sweep_setup_t), intent(in) :: setup
         integer, intent(in) :: b
         logical, intent(in), optional :: flagged
         real(dp), allocatable :: v(:)
         character(len=:), allocatable :: bytes, pattern
         integer :: j0, nb, at, u, size_bytes
         if (.not. present(flagged)) then
            call h5%open(path, 'rw', error)
            if (.not. allocated(error)) call h5%write_slab('/sweep/done', [0], [b], error)
            call h5%close()
            if (allocated(error)) return
         end if
         call block_range(setup, b, j0, nb)
         v = reshape(e, [size(e)])
         v = v(j0:j0 + nb - 1)
         pattern = transfer(v, repeat(' ', 8*nb))
         open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
               action='readwrite')
         inquire (unit=u, size=size_bytes)
         allocate (character(len=size_bytes) :: bytes)
         read (u) bytes
         at = index(bytes, pattern)
         call check_true(error, at > 0 .and. index(bytes, pattern, back=.true.) == at, &
                         'block '//to_str(b)//' found once in the file')
         if (.not. allocated(error)) then
            at = at + 8*nb/2 + 3
            bytes(at:at) = achar(ieor(iachar(bytes(at:at)), 16))
            write (u, pos=1) bytes
         end if
         close (u)
      end subroutine tear
   end subroutine test_torn_blocks

   !> Another configuration against an existing file: exit 2, one line, file kept;
   !> --force overwrites.
   subroutine test_mismatch(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, args, config
      type(h5file_t) :: h5
      integer :: stat, n
      dir = scratch_dir('sweepcfg')
      args = 'sweep --quiet --n 8 --output '//dir//'/s.h5'
      stat = run_command(dir, args//' --t-end 5')
      call check_true(error, stat == 0, 'first run exits 0')
      stat = run_command(dir, args//' --t-end 6')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2, 'another t_end: exit 2')
      call check_true(error, n == 1 .and. index(text, 'another configuration') > 0 .and. &
                      index(text, 't_end') > 0 .and. index(text, '--force') > 0, &
                      'one line naming t_end and --force: '//text)
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'config', config, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, index(config, 't_end = 5.0') > 0, 'file kept')
      stat = run_command(dir, args//' --t-end 6 --force')
      call check_true(error, stat == 0, '--force overwrites')
      call write_file(dir//'/junk.h5', 'not hdf5')
      stat = run_command(dir, 'sweep --quiet --n 4 --t-end 1 --output '//dir//'/junk.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. index(text, 'not an HDF5') > 0, &
                      'a foreign file is refused: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_mismatch

   subroutine test_bad_input(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('sweepbad')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--n 0', 'n1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--n2 -3', 'n2')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--min1 2 --max1 1', 'min1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--min2 1 --max2 1', 'empty')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--max1 nan', '--max1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--min2 inf', '--min2')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--axis1 q3', 'axis1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--axis1 q1 --axis2 theta1', 'axis2')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--t-end 0', 't_end')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--dt -1', 'dt')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--block 0', 'block')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--threads -1', 'threads')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--time-unit h', 'time_unit')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--stop-at never', 'stop_at')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--indicator gali3', &
                           'indicator')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', &
                           '--indicator megno --lyapunov', 'indicator')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1 --min1 0.5 --max1 2', &
                           '--axis1 m2 --axis2 m2/m1 --min2 0.5 --max2 2', 'axis2')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', &
                           '--axis1 m2/m1 --min1 0 --max1 2', 'min1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', &
                           '--axis1 m2/m1 --min1 1 --max1 1e7', 'm2 of a pixel')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', &
                           '--links 1 --axis1 l1 --min1 1 --max1 2 --axis2 q1', 'axis1')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--method verlet', 'method')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--save-every 3', 'unknown option')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--bogus 1', 'unknown option')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--m2 0', 'm2')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--ic-file '//dir//'/none.txt', 'ic_file')
      call write_file(dir//'/bad.txt', '0 0 0 0'//new_line('a')//'1 2 three 4')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--ic-file '//dir//'/bad.txt', 'line 2')
      call write_file(dir//'/short.txt', '0 0 0')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--ic-file '//dir//'/short.txt', 'line 1')
      call write_file(dir//'/empty.txt', '# nothing')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--ic-file '//dir//'/empty.txt', 'no initial')
      call write_file(dir//'/n.nml', '&sweep min1 = 2, max1 = 1 /')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--config '//dir//'/n.nml', 'min1')
      call write_file(dir//'/k.nml', '&sweep n3 = 4 /')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--config '//dir//'/k.nml', 'sweep')
      call write_file(dir//'/g.nml', '&grid n1 = 4 /')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--config '//dir//'/g.nml', 'unknown namelist group')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--output '//dir//'/no/dir/s.h5', 'directory')
      call expect_rejected(error, dir, 'sweep --quiet --n 4 --t-end 1', '--output /proc/dpend-sweep.h5', 'not writable')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_bad_input

   !> `dpend export --matrix` gives a gnuplot nonuniform matrix; a sweep compared
   !> with itself changes no pixel.
   subroutine test_export_compare(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: stat, n
      dir = scratch_dir('sweepexp')
      stat = run_command(dir, 'sweep --quiet --n1 6 --n2 4 --t-end 5 --output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'run exits 0')
      stat = run_command(dir, 'export '//dir//'/s.h5 --matrix /sweep/t_flip /sweep/axis1 '// &
                         '/sweep/axis2 0.5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 5, 'matrix: 1 + n2 lines, got: '//text)
      call check_true(error, index(text, '6.0000000E+000') == 3 .or. &
                      index(text, '6.0000000E+000') == 2, 'first field is n1: '//text)
      stat = run_command(dir, 'sweep-compare '//dir//'/s.h5 '//dir//'/s.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'changed_fraction: 0 %') > 0, &
                      'self comparison: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_export_compare

   ! ----------------------------------------------------------- helpers ---

   !> Expect exit status 2, exactly one stderr line containing `needle`, no file.

   !> Every result dataset of two sweep files equal bit for bit.
   subroutine same_results(error, a, b, with_steps)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: a, b
      logical, intent(in) :: with_steps
      integer :: k
      do k = 1, size(real_sets)
         call same_dataset(error, a, b, trim(real_sets(k)))
      end do
      call same_dataset_i(error, a, b, '/sweep/status')
      if (with_steps) call same_dataset_i(error, a, b, '/sweep/steps')
   end subroutine same_results

   subroutine same_dataset(error, a, b, path)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: a, b, path
      real(dp), allocatable :: x(:, :), y(:, :)
      call read2(a, x)
      call read2(b, y)
      if (allocated(error)) return
      call check_true(error, all(shape(x) == shape(y)), path//' same shape')
      if (allocated(error)) return
      call check_true(error, all(bits(x) == bits(y)), path//' bitwise equal in '//a//' and '//b)
   contains
      subroutine read2(file, v)
         character(len=*), intent(in) :: file
         real(dp), allocatable, intent(out) :: v(:, :)
         type(h5file_t) :: h5
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (.not. allocated(error)) call h5%read(path, v, error)
         call h5%close()
      end subroutine read2
   end subroutine same_dataset

   subroutine same_dataset_i(error, a, b, path)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: a, b, path
      integer, allocatable :: x(:), y(:), x2(:, :), y2(:, :)
      integer, allocatable :: dims(:)
      type(h5file_t) :: h5
      if (allocated(error)) return
      call h5%open(a, 'r', error)
      if (.not. allocated(error)) call h5%shape(path, dims, error)
      call h5%close()
      if (allocated(error)) return
      if (size(dims) == 1) then
         call readi1(a, x); call readi1(b, y)
         if (allocated(error)) return
         call check_true(error, size(x) == size(y), path//' same size')
         if (allocated(error)) return
         call check_true(error, all(x == y), path//' equal')
      else
         call readi2(a, x2); call readi2(b, y2)
         if (allocated(error)) return
         call check_true(error, all(shape(x2) == shape(y2)), path//' same shape')
         if (allocated(error)) return
         call check_true(error, all(x2 == y2), path//' equal')
      end if
   contains
      subroutine readi1(file, v)
         character(len=*), intent(in) :: file
         integer, allocatable, intent(out) :: v(:)
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (.not. allocated(error)) call h5%read(path, v, error)
         call h5%close()
      end subroutine readi1
      subroutine readi2(file, v)
         character(len=*), intent(in) :: file
         integer, allocatable, intent(out) :: v(:, :)
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (.not. allocated(error)) call h5%read(path, v, error)
         call h5%close()
      end subroutine readi2
   end subroutine same_dataset_i

   subroutine same_attr(error, a, b, name)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: a, b, name
      character(len=:), allocatable :: x, y
      type(h5file_t) :: h5
      if (allocated(error)) return
      call h5%open(a, 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', name, x, error)
      call h5%close()
      if (allocated(error)) return
      call h5%open(b, 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', name, y, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, x == y, 'attribute '//name//' equal')
   end subroutine same_attr

   !> Bit pattern of a real (NaN-safe comparison without arithmetic).
   elemental integer(i8) function bits(x)
      real(dp), intent(in) :: x
      bits = transfer(x, 0_i8)
   end function bits

   subroutine write_file(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)') text
      close (unit)
   end subroutine write_file
   ! ------------------------------------------------------------ N links ---

   !> A 3-link sweep (the per-trajectory path) against `dpend simulate --links 3` of
   !> two of its pixels with the same rk4 and step, sampled at every step: the final
   !> state is identical and the flip times, found in the simulated angles by the
   !> sweep's own rule (linear interpolation of the crossing of q = π/2 + 2π k), are
   !> identical too.
   subroutine test_links3_simulate(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: par = '--links 3 --m 1,0.8,1.2 --l 1,0.7,0.9 --g 9.81'
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), tf(:, :, :), fin(:, :, :), q(:, :), tq(:)
      real(dp), allocatable :: t_any(:, :)
      real(dp) :: h, tl(3), q0(3), m, m0
      real(dp), parameter :: inv_two_pi = 1.0_dp/(2.0_dp*pi)
      character(len=80) :: qs
      integer :: stat, k, i, pix(2, 2), ks, i1, i2
      real(dp) :: tmax
      character(len=1) :: c
      dir = scratch_dir('sweepn3')
      ! the per-trajectory path (three links go through the chain lanes unless
      ! DPEND_SWEEP_KERNEL=trajectory; the lanes are compared in suite chain_lanes)
      call execute_command_line('DPEND_SWEEP_KERNEL=trajectory '//dpend_binary()// &
                                ' sweep --quiet '//par//' --n 8 --min1 -3 --max1 3 --min2 -3 '// &
                                '--max2 3 --q 0,0,0.4 --time-unit s --dt 0.01 --t-end 3 '// &
                                '--stop-at end --output '//dir//'/s.h5 > '//dir//'/stdout 2> ' &
                                //dir//'/stderr', exitstat=stat)
      call check_true(error, stat == 0, 'sweep --links 3 exits 0')
      if (allocated(error)) return
      allocate (tf(8, 8, 3), fin(8, 8, 6))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/t_flip', t_any, error)
      do k = 1, 3
         c = achar(iachar('0') + k)
         if (.not. allocated(error)) call read2('/sweep/t_flip'//c, tf(:, :, k))
         if (.not. allocated(error)) call read2('/sweep/final/q'//c, fin(:, :, k))
         if (.not. allocated(error)) call read2('/sweep/final/w'//c, fin(:, :, 3 + k))
      end do
      call h5%close()
      if (allocated(error)) return
      ! two pixels: the first that flips, and the one whose flip comes last
      pix = 0
      tmax = -1.0_dp
      do i2 = 1, 8
         do i1 = 1, 8
            if (ieee_is_nan(t_any(i1, i2))) cycle
            if (pix(1, 1) == 0) pix(:, 1) = [i1, i2]
            if (t_any(i1, i2) > tmax) then
               tmax = t_any(i1, i2)
               pix(:, 2) = [i1, i2]
            end if
         end do
      end do
      call check_true(error, pix(1, 1) > 0 .and. any(pix(:, 1) /= pix(:, 2)), &
                      'two pixels flip')
      if (allocated(error)) return
      h = 0.01_dp
      do i = 1, 2
         q0 = [ax1(pix(1, i)) - half_pi, ax2(pix(2, i)) - half_pi, 0.4_dp]
         write (qs, '(3(es25.16e3, :, ","))') q0
         qs = squeeze(qs)
         stat = run_command(dir, 'simulate '//par//' --q '//trim(qs)// &
                            ' --w 0,0,0 --method rk4 --dt 0.01 --t-end 3 --save-every 1 '// &
                            '--output '//dir//'/p.h5 --force')
         call check_true(error, stat == 0, 'simulate --links 3 exits 0')
         if (allocated(error)) return
         call h5%open(dir//'/p.h5', 'r', error)
         if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
         if (.not. allocated(error)) call h5%read('/trajectory/t', tq, error)
         call h5%close()
         if (allocated(error)) return
         call check_true(error, size(q, 2) == 301, 'every step sampled')
         if (allocated(error)) return
         do k = 1, 3
            tl(k) = -1.0_dp
            m0 = real(floor((q(k, 1) - half_pi)*inv_two_pi, i8), dp)
            do ks = 1, 300
               m = real(floor((q(k, ks + 1) - half_pi)*inv_two_pi, i8), dp)
               if (m /= m0) then
                  tl(k) = (real(ks - 1, dp) + (half_pi + 2.0_dp*pi*max(m, m0) - q(k, ks))/ &
                           (q(k, ks + 1) - q(k, ks)))*h
                  exit
               end if
            end do
            if (tl(k) < 0.0_dp) then
               call check_true(error, ieee_is_nan(tf(pix(1, i), pix(2, i), k)), 'no flip')
            else
               call check_true(error, bits(tf(pix(1, i), pix(2, i), k)) == bits(tl(k)), &
                               'flip time of link '//achar(iachar('0') + k)//' identical')
            end if
            call check_true(error, bits(fin(pix(1, i), pix(2, i), k)) == bits(q(k, 301)), &
                            'final angle identical')
         end do
      end do
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> The text without blanks.
      function squeeze(t) result(u)
         character(len=*), intent(in) :: t
         character(len=len(t)) :: u
         integer :: j, n
         u = ' '
         n = 0
         do j = 1, len_trim(t)
            if (t(j:j) == ' ') cycle
            n = n + 1
            u(n:n) = t(j:j)
         end do
      end function squeeze
      subroutine read2(name, a)
         character(len=*), intent(in) :: name
         real(dp), intent(out) :: a(:, :)
         real(dp), allocatable :: t2(:, :)
         call h5%read(name, t2, error)
         if (.not. allocated(error)) a = t2
      end subroutine read2
   end subroutine test_links3_simulate

   !> The per-trajectory path forced on two links (the double pendulum model through
   !> the registry's rk4) against the batch kernel: the same statuses and steps, flip
   !> times and final states within 1e-9 (relative) over 3 s of an 8 x 8 map, where the
   !> two right-hand sides (Lagrange's form in lanes, Newton–Euler) differ by rounding.
   subroutine test_per_trajectory_n2(error)
      type(error_t), allocatable, intent(out) :: error
      type(arg_t), allocatable :: args(:)
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: a, b
      type(error_t), allocatable :: err
      logical :: help
      integer :: blk, j, nflip
      character(len=16), parameter :: words(15) = [character(len=16) :: '--n', '8', &
         '--t-end', '3', '--time-unit', 's', '--dt', '0.01', '--m1', '1.3', '--l2', '0.8', &
         '--quiet', '--block', '16']
      allocate (args(size(words)))
      do j = 1, size(words)
         args(j)%s = trim(words(j))
      end do
      call parse_sweep(args, cfg, help, err)
      if (allocated(err)) then
         call fatal_error(error, 'parse_sweep: '//err%message)
         return
      end if
      call build_setup(cfg, setup, err)
      if (allocated(err)) then
         call fatal_error(error, 'build_setup: '//err%message)
         return
      end if
      nflip = 0
      do blk = 1, setup%nblocks
         setup%per_trajectory = .false.
         call compute_block(setup, blk, a)
         setup%per_trajectory = .true.
         call compute_block(setup, blk, b)
         do j = 1, a%n
            call check_true(error, a%status(j) == b%status(j) .and. a%steps(j) == b%steps(j), &
                            'same status and steps')
            call check(error, b%energy0(j), a%energy0(j), 'energy0', rel=1e-13_dp, &
                       abs=1e-13_dp)
            call check_same_time(error, b%t_flip(j), a%t_flip(j), 't_flip', 1e-9_dp)
            call check_same_time(error, b%t_flip1(j), a%t_flip1(j), 't_flip1', 1e-9_dp)
            call check_same_time(error, b%t_flip2(j), a%t_flip2(j), 't_flip2', 1e-9_dp)
            call check(error, b%final(:, j), a%final(:, j), 'final state', rel=1e-9_dp, &
                       abs=1e-9_dp)
            if (.not. ieee_is_nan(a%t_flip(j))) nflip = nflip + 1
            if (allocated(error)) return
         end do
      end do
      call check_true(error, nflip > 10, 'some pixels flip')
   end subroutine test_per_trajectory_n2

   !> Axes and options that do not exist for N links are refused naming the field and
   !> the accepted names.
   subroutine test_links_refused(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      character(len=*), parameter :: base = 'sweep --quiet --n 4 --t-end 1'
      dir = scratch_dir('sweeplinks')
      call expect_rejected(error, dir, base//' --links 3', '--axis1 theta4', &
                           "axis1: 'theta4' (accepted: theta1..theta3 q1..q3 w1..w3 m1 m2 l1 l2 m2/m1 "// &
                           "l2/l1 m3 l3 g com1..com3 inertia1..inertia3 for 3 links)")
      call expect_rejected(error, dir, base//' --links 3', '--axis2 w0', "axis2: 'w0'")
      call expect_rejected(error, dir, base//' --links 1', '--axis1 theta1 --axis2 w2', &
                           "axis2: 'w2' (accepted: theta1 q1 w1 g com1 inertia1 for 1 link)")
      call expect_rejected(error, dir, base//' --links 4', '--axis1 q3 --axis2 theta3', &
                           'invalid axis2')
      call expect_rejected(error, dir, base//' --links 3', '--lyapunov', 'invalid lyapunov')
      call write_file(dir//'/four.txt', '0 0 0 0')
      call expect_rejected(error, dir, base//' --links 3', '--ic-file '//dir//'/four.txt', &
                           'is not 6 numbers "q1 .. q3 w1 .. w3"')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_links_refused

   !> The flip energy bounds of N links against brute force: with link i upright,
   !> the chain's potential over 20 000 random configurations of the other links never
   !> goes below E_i, and equals E_i with every other link hanging (N = 1, 3, 5).
   subroutine test_links_bound(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(error_t), allocatable :: err
      real(dp), allocatable :: m(:), l(:), q(:), e(:)
      real(dp) :: vmin, r
      integer :: n, i, k, trial
      integer, parameter :: sizes(3) = [1, 3, 5]
      call random_seed(put=[(12345 + k, k=1, 64)])
      do trial = 1, size(sizes)
         n = sizes(trial)
         allocate (m(n), l(n), q(n))
         do k = 1, n
            call random_number(r); m(k) = 0.2_dp + 2*r
            call random_number(r); l(k) = 0.3_dp + 1.5_dp*r
         end do
         chain = chain_model(m, l, 9.81_dp, err)
         if (allocated(err)) then
            call fatal_error(error, err%message)
            return
         end if
         e = link_flip_bounds(chain%gl)
         do i = 1, n
            q = -half_pi
            q(i) = half_pi
            call check(error, chain%potential(q), e(i), 'bound attained, link ' // &
                       achar(iachar('0') + i), rel=1e-14_dp, abs=1e-14_dp)
            vmin = huge(1.0_dp)
            do k = 1, 20000
               call random_number(q)
               q = (2*q - 1)*pi
               q(i) = half_pi + 2*pi*mod(k, 3)
               vmin = min(vmin, chain%potential(q))
            end do
            call check_true(error, vmin >= e(i) - 1e-12_dp*sum(chain%gl), 'no V below E_i')
            call check_true(error, vmin - e(i) < 0.05_dp*sum(chain%gl) .or. n > 3, &
                            'brute force comes near E_i')
         end do
         deallocate (m, l, q)
         if (allocated(error)) return
      end do
   end subroutine test_links_bound

   !> Pixels of a 3-link grid given as a list (text, 6 columns, angles as theta) give
   !> the same bits.
   subroutine test_links3_list(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      character(len=*), parameter :: common = '--quiet --links 3 --q 0,0,-1.5 --w 0,0.5,0 '// &
                                             '--t-end 4 --stats'
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), tg(:, :), fg(:, :), tl(:), fl(:)
      integer, allocatable :: sg(:, :), sl(:)
      character(len=200) :: line
      integer :: stat, unit, k
      integer, parameter :: pick(2, 3) = reshape([2, 3, 5, 1, 4, 4], [2, 3])
      dir = scratch_dir('sweepn3l')
      stat = run_command(dir, 'sweep '//common//' --n 5 --output '//dir//'/grid.h5')
      call check_true(error, stat == 0, 'grid run exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/grid.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/t_flip3', tg, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/w2', fg, error)
      if (.not. allocated(error)) call h5%read('/sweep/steps', sg, error)
      call h5%close()
      if (allocated(error)) return
      open (newunit=unit, file=dir//'/ics.txt', status='replace', action='write')
      write (unit, '(a)') '# theta1 theta2 theta3 w1 w2 w3'
      do k = 1, 3
         write (line, '(6(es25.16e3, 1x))') ax1(pick(1, k)), ax2(pick(2, k)), &
            -1.5_dp + half_pi, 0.0_dp, 0.5_dp, 0.0_dp
         write (unit, '(a)') trim(line)
      end do
      close (unit)
      ! the list gives every state: no --q, --w beside it
      stat = run_command(dir, 'sweep --quiet --links 3 --t-end 4 --stats --ic-file '//dir// &
                         '/ics.txt --ic-angles theta --output '//dir//'/list.h5')
      call check_true(error, stat == 0, 'list run exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/list.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/t_flip3', tl, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/w2', fl, error)
      if (.not. allocated(error)) call h5%read('/sweep/steps', sl, error)
      call h5%close()
      if (allocated(error)) return
      do k = 1, 3
         call check_true(error, sl(k) == sg(pick(1, k), pick(2, k)), 'same steps')
         call check_true(error, bits(fl(k)) == bits(fg(pick(1, k), pick(2, k))), &
                         'same final w2')
         if (ieee_is_nan(tg(pick(1, k), pick(2, k)))) then
            call check_true(error, ieee_is_nan(tl(k)), 'no flip of link 3 in both')
         else
            call check_true(error, bits(tl(k)) == bits(tg(pick(1, k), pick(2, k))), &
                            'same t_flip3')
         end if
      end do
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_links3_list


   ! -------------------------------------------------------- indicators ---

   !> The batch kernel's per-pixel indicators (two deviation vectors) against
   !> `chaos_indicators` (dpend_indicators) along the same orbits with the library's
   !> rk4 and h = 0.01 s: a regular orbit (both links 1 rad from hanging, at rest)
   !> over 60 s and the chaotic horizontal release over 5 s agree within 1e-3
   !> relative (observed <= 2e-4: dpend_tangent integrates the linear flow by RK4 on
   !> the step's Hermite interpolant, the kernel RK4 of the extended system, an
   !> O(h^4) difference). Known behaviours: <Y> of the regular orbit between 1 and
   !> the classification threshold 2.5 (it tends to 2), GALI_2 away from 0; the
   !> horizontal release over 30 s: <Y> far above 2, SALI and GALI_2 near 0.
   subroutine test_indicators_kernel(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      type(indicators_result_t) :: r
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      real(dp) :: y0(4, 1), t_end(3)
      integer :: k, stat, m
      character(len=8) :: which
      t_end = [60.0_dp, 5.0_dp, 30.0_dp]
      call new_integrator('rk4', integ, err)
      do k = 1, 3
         which = merge('regular ', 'chaotic ', k == 1)
         if (k == 1) then
            y0(:, 1) = [-half_pi + 1.0_dp, -half_pi + 1.0_dp, 0.0_dp, 0.0_dp]
         else
            y0(:, 1) = 0.0_dp
         end if
         opt%h = 0.01_dp
         opt%n_steps = nint(t_end(k)/opt%h, i8)
         opt%stop_rule = stop_end
         opt%vectors = 2
         call integrate_batch(par, opt, y0, res)
         write (*, '(4x, a, f5.1, a, 5es11.3)') which//' t = ', t_end(k), &
            ' s: <Y>, Y, FLI, SALI, GALI_2 = ', res%megno(1), res%megno_y(1), res%fli(1), &
            res%sali(1), res%gali2(1)
         if (k == 3) then
            call check_true(error, res%megno(1) > 5.0_dp, 'chaotic <Y> far above 2')
            call check_true(error, res%sali(1) < 1e-6_dp .and. res%gali2(1) < 1e-6_dp, &
                            'chaotic SALI and GALI_2 near 0')
            return
         end if
         call chaos_indicators(integ, pendulum_model(par), 0.0_dp, y0(:, 1), t_end(k), &
                               opt%h, t_end(k), r, stat)
         call check_true(error, stat == stat_ok .and. r%n >= 1, 'chaos_indicators runs')
         if (allocated(error)) return
         m = r%n
         call check(error, r%t(m), res%t_stop(1), trim(which)//' t_stop', rel=1e-12_dp)
         call check(error, res%megno(1), r%mean_all(1, m), trim(which)//' <Y>', rel=1e-3_dp)
         call check(error, res%megno_y(1), r%megno_all(1, m), trim(which)//' Y', rel=1e-3_dp)
         call check(error, res%fli(1), r%log_norm(1, m), trim(which)//' FLI', rel=1e-3_dp)
         call check(error, res%sali(1), r%sali(m), trim(which)//' SALI', rel=1e-3_dp)
         call check(error, res%gali2(1), r%gali(1, m), trim(which)//' GALI_2', rel=1e-3_dp)
         if (k == 1) then
            call check_true(error, res%megno(1) > 1.0_dp .and. res%megno(1) < 2.5_dp, &
                            'regular <Y> between 1 and 2.5')
            call check_true(error, res%gali2(1) > 1e-2_dp, 'regular GALI_2 away from 0')
         end if
         if (allocated(error)) return
      end do
   end subroutine test_indicators_kernel

   !> The per-trajectory path forced on two links against the kernel, for the
   !> indicators of a 4 x 4 map over 2 s: equal statuses; the indicators differ by
   !> the tangents' O(h^4) difference (test_indicators_kernel): the largest
   !> difference of each (<Y>, Y, FLI, SALI, GALI_2) shrinks by more than 8 from
   !> dt = 0.01 s to 0.005 s (16 expected), and is below 1e-3 relative at 0.005 s.
   subroutine test_indicators_paths(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: d1(5), d2(5), r1(5), r2(5)
      integer :: k
      call path_differences('0.01', d1, r1)
      if (allocated(error)) return
      call path_differences('0.005', d2, r2)
      if (allocated(error)) return
      write (*, '(4x, a, 5es10.2)') 'largest |difference| at dt = 0.01 s:  ', d1
      write (*, '(4x, a, 5es10.2)') 'largest |difference| at dt = 0.005 s: ', d2
      do k = 1, 5
         call check_true(error, d2(k) < d1(k)/8.0_dp, 'difference shrinks like h^4')
         call check_true(error, r2(k) < 1e-3_dp, 'relative difference below 1e-3')
      end do
   contains
      !> Largest absolute and relative differences between the paths at step dt.
      subroutine path_differences(dt, dmax, rmax)
         character(len=*), intent(in) :: dt
         real(dp), intent(out) :: dmax(5), rmax(5)
         type(arg_t), allocatable :: args(:)
         type(sweep_config_t) :: cfg
         type(sweep_setup_t) :: setup
         type(batch_result_t) :: a, b
         type(error_t), allocatable :: err
         logical :: help
         integer :: blk, j
         real(dp) :: x(5), y(5)
         character(len=16), parameter :: words(10) = [character(len=16) :: '--n', '4', &
            '--t-end', '2', '--time-unit', 's', '--quiet', '--indicator', 'sali', '--dt']
         allocate (args(size(words) + 1))
         do j = 1, size(words)
            args(j)%s = trim(words(j))
         end do
         args(size(words) + 1)%s = dt
         dmax = 0; rmax = 0
         call parse_sweep(args, cfg, help, err)
         if (.not. allocated(err)) call build_setup(cfg, setup, err)
         if (allocated(err)) then
            call fatal_error(error, err%message)
            return
         end if
         do blk = 1, setup%nblocks
            setup%per_trajectory = .false.
            call compute_block(setup, blk, a)
            setup%per_trajectory = .true.
            call compute_block(setup, blk, b)
            do j = 1, a%n
               call check_true(error, a%status(j) == b%status(j) .and. &
                               a%steps(j) == b%steps(j), 'same status and steps')
               x = [a%megno(j), a%megno_y(j), a%fli(j), a%sali(j), a%gali2(j)]
               y = [b%megno(j), b%megno_y(j), b%fli(j), b%sali(j), b%gali2(j)]
               call check_true(error, all(x == x) .and. all(y == y), 'finite indicators')
               if (allocated(error)) return
               dmax = max(dmax, abs(y - x))
               rmax = max(rmax, abs(y - x)/abs(x))
            end do
         end do
      end subroutine path_differences
   end subroutine test_indicators_paths

   ! --------------------------------------------------------- parameters ---

   !> Sweeps over parameters. A flip and MEGNO map over (theta1, m2/m1) at m2/m1 =
   !> 0.5 and 2 equals, row for row and bit for bit, the maps over theta1 with the
   !> parameters given as --m2; it stores the pixels' parameters; the map with its
   !> axes swapped (the parameter on axis 1: groups across a block's rows) is its
   !> transpose bit for bit; it and a map over (m2/m1, l2/l1) (groups of one pixel)
   !> are bitwise independent of threads and block size; a chain of three links
   !> takes parameter axes too.
   subroutine test_parameter_axes(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, common, pmap
      real(dp), allocatable :: a(:, :), b(:, :)
      integer :: stat, k, row
      character(len=16), parameter :: sets(4) = [character(len=16) :: '/sweep/t_flip', &
         '/sweep/megno', '/sweep/final/q1', '/sweep/energy0']
      dir = scratch_dir('sweeppar')
      common = 'sweep --quiet --t-end 20 --dt 0.02 --stats --indicator megno --q2 -1 '
      pmap = common//'--n1 8 --n2 2 --axis1 theta1 --axis2 m2/m1 --min2 0.5 --max2 2 '
      stat = run_command(dir, pmap//'--threads 2 --block 8 --output '//dir//'/p.h5')
      call check_true(error, stat == 0, 'parameter map exits 0')
      stat = run_command(dir, pmap//'--threads 1 --block 100 --output '//dir//'/p2.h5')
      call check_true(error, stat == 0, 'parameter map, other blocks, exits 0')
      do k = 1, 2
         ! q2 = -1 from the one-point axis (a fixed --q2 with axis q2 is refused)
         stat = run_command(dir, common(:index(common, '--q2') - 1)//'--n1 8 --n2 1 ' &
                            //'--axis1 theta1 --axis2 q2 ' &
                            //'--min2 -1 --max2 -1 --threads 1 --m2 '// &
                            trim(merge('0.5', '2  ', k == 1))//' --output '//dir//'/r'// &
                            achar(iachar('0') + k)//'.h5')
         call check_true(error, stat == 0, 'map at fixed parameters exits 0')
      end do
      if (allocated(error)) return
      call same_results(error, dir//'/p.h5', dir//'/p2.h5', .true.)
      call same_dataset(error, dir//'/p.h5', dir//'/p2.h5', '/sweep/megno')
      do k = 1, size(sets)
         do row = 1, 2
            call read_map(error, dir//'/p.h5', trim(sets(k)), a)
            call read_map(error, dir//'/r'//achar(iachar('0') + row)//'.h5', trim(sets(k)), b)
            if (allocated(error)) return
            call check_true(error, all(bits(a(:, row)) == bits(b(:, 1))), &
                            trim(sets(k))//': row of the parameter map equals the fixed map')
         end do
      end do
      ! the parameter on axis 1 (groups across the rows of a block): the transpose
      stat = run_command(dir, common//'--n1 2 --n2 8 --axis2 theta1 --axis1 m2/m1 ' &
                         //'--min1 0.5 --max1 2 --threads 2 --block 8 --output '//dir//'/t.h5')
      call check_true(error, stat == 0, 'transposed parameter map exits 0')
      do k = 1, size(sets)
         call read_map(error, dir//'/p.h5', trim(sets(k)), a)
         call read_map(error, dir//'/t.h5', trim(sets(k)), b)
         if (allocated(error)) return
         call check_true(error, all(bits(transpose(a)) == bits(b)), &
                         trim(sets(k))//': the transposed map is the transpose')
      end do
      call read_map(error, dir//'/p.h5', '/sweep/param/m2', a)
      call read_map(error, dir//'/p.h5', '/sweep/param/m1', b)
      if (allocated(error)) return
      call check_true(error, all(a(:, 1) == 0.5_dp) .and. all(a(:, 2) == 2.0_dp) .and. &
                      all(b == 1.0_dp), 'per-pixel masses stored')
      ! both axes parameters: runs of one pixel
      common = 'sweep --quiet --t-end 5 --dt 0.02 --q1 0 --q2 0 --n 4 --axis1 m2/m1 ' &
               //'--axis2 l2/l1 --min1 0.5 --max1 3 --min2 0.5 --max2 3 --indicator sali '
      stat = run_command(dir, common//'--threads 1 --block 4 --output '//dir//'/m.h5')
      call check_true(error, stat == 0, 'map over (m2/m1, l2/l1) exits 0')
      stat = run_command(dir, common//'--threads 2 --block 16 --output '//dir//'/m2.h5')
      call check_true(error, stat == 0, 'map over (m2/m1, l2/l1), other blocks, exits 0')
      if (allocated(error)) return
      call same_results(error, dir//'/m.h5', dir//'/m2.h5', .false.)
      call same_dataset(error, dir//'/m.h5', dir//'/m2.h5', '/sweep/sali')
      call same_dataset(error, dir//'/m.h5', dir//'/m2.h5', '/sweep/param/l2')
      ! a map of one pixel (its lanes hold that pixel's constants, not the configured
      ! pendulum's) equals that pixel of the whole map (m2/m1 = l2/l1 = 3: the last)
      stat = run_command(dir, common(:index(common, '--n 4') - 1)//'--n 1 --axis1 m2/m1 ' &
                         //'--axis2 l2/l1 --min1 3 --max1 3 --min2 3 --max2 3 ' &
                         //'--indicator sali --output '//dir//'/one.h5')
      call check_true(error, stat == 0, 'map of one pixel over (m2/m1, l2/l1) exits 0')
      call read_map(error, dir//'/m.h5', '/sweep/sali', a)
      call read_map(error, dir//'/one.h5', '/sweep/sali', b)
      if (allocated(error)) return
      call check_true(error, all(bits(a(4:4, 4)) == bits(b(:, 1))), &
                      'a map of one pixel equals its pixel of the whole map')
      ! three links: the per-trajectory path with a chain per pixel
      stat = run_command(dir, 'sweep --quiet --links 3 --n 3 --t-end 2 --dt 0.02 ' &
                         //'--axis1 theta1 --axis2 l2/l1 --min2 0.5 --max2 2 --indicator fli ' &
                         //'--output '//dir//'/c.h5')
      call check_true(error, stat == 0, 'three links over (theta1, l2/l1) exits 0')
      call read_map(error, dir//'/c.h5', '/sweep/param/l2', a)
      call read_map(error, dir//'/c.h5', '/sweep/fli', b)
      if (allocated(error)) return
      call check_true(error, all(a(:, 1) == 0.5_dp) .and. all(a(:, 3) == 2.0_dp), &
                      'three links: per-pixel l2 stored')
      call check_true(error, all(b == b), 'three links: FLI of every pixel')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_parameter_axes

   !> `sweep-compare --agreement` of a MEGNO map (t_end 20) and a lambda1 map
   !> (t_end 200) of the same 6 x 6 pixels: exit 0, both times and the agreement
   !> printed; the stored classes are the thresholds applied to the maps by hand
   !> (MEGNO > 2.5, lambda1 sqrt(l1/g) > 0.05), the stored agreement their match;
   !> other pixels, a sweep without an indicator, FLI without a threshold, an
   !> existing output without --force, and the same pixels of other bodies (point
   !> masses against rods: also by the flip-time comparison) are refused.
   subroutine test_agreement(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, common
      type(h5file_t) :: h5
      real(dp), allocatable :: megno(:, :), lam(:, :)
      integer, allocatable :: ca(:, :), cb(:, :)
      real(dp) :: tau, stored
      integer :: stat, n, i, j
      dir = scratch_dir('sweepagree')
      common = 'sweep --quiet --n 6 --dt 0.02 --threads 2 '
      stat = run_command(dir, common//'--t-end 20 --indicator megno --output '//dir//'/m.h5')
      call check_true(error, stat == 0, 'MEGNO map exits 0')
      stat = run_command(dir, common//'--t-end 200 --indicator lambda1 --output '//dir//'/l.h5')
      call check_true(error, stat == 0, 'lambda1 map exits 0')
      stat = run_command(dir, common//'--t-end 20 --output '//dir//'/f.h5')
      call check_true(error, stat == 0, 'flip map exits 0')
      stat = run_command(dir, 'sweep --quiet --n 5 --t-end 20 --indicator megno --output '// &
                         dir//'/m5.h5')
      call check_true(error, stat == 0, '5 x 5 MEGNO map exits 0')
      if (allocated(error)) return
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/l.h5 --agreement '// &
                         '--output '//dir//'/a.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'agreement exits 0: '//text)
      call check_true(error, index(text, 'agreement: ') > 0 .and. &
                      index(text, 't_end_a: 20 sqrt(l1/g) = 6.38877 s') > 0 .and. &
                      index(text, 't_end_b: 200 sqrt(l1/g) = 63.8877 s') > 0, &
                      'agreement and both times printed: '//text)
      call h5%open(dir//'/m.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/megno', megno, error)
      call h5%close()
      if (.not. allocated(error)) call h5%open(dir//'/l.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/lyapunov', lam, error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'sqrt_l1_over_g', tau, error)
      call h5%close()
      if (.not. allocated(error)) call h5%open(dir//'/a.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/agreement/class_a', ca, error)
      if (.not. allocated(error)) call h5%read('/agreement/class_b', cb, error)
      if (.not. allocated(error)) call h5%readattr('/agreement', 'agreement', stored, error)
      call h5%close()
      if (allocated(error)) return
      do j = 1, 6
         do i = 1, 6
            call check_true(error, ca(i, j) == merge(1, 0, megno(i, j) > 2.5_dp) .and. &
                            cb(i, j) == merge(1, 0, lam(i, j)*tau > 0.05_dp), &
                            'stored classes are the thresholds applied by hand')
         end do
      end do
      call check(error, stored, real(count(ca == cb), dp)/36.0_dp, 'stored agreement')
      call check_true(error, count(ca == 1) > 0 .and. count(ca == 0) > 0, &
                      'both classes present')
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/l.h5 --agreement '// &
                         '--output '//dir//'/a.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1, 'existing output refused: '//text)
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/m5.h5 --agreement '// &
                         '--output '//dir//'/b.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'n1') > 0, &
                      'other pixels refused: '//text)
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/f.h5 --agreement '// &
                         '--output '//dir//'/b.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'no indicator') > 0, &
                      'a sweep without an indicator refused: '//text)
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/l.h5 --agreement '// &
                         '--threshold-a nan --output '//dir//'/b.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'threshold-a') > 0, &
                      'a NaN threshold refused: '//text)
      call check_true(error, .not. is_hdf5(dir//'/b.h5'), 'no file after a refusal')
      if (allocated(error)) return
      ! the same pixels of point masses: other bodies, refused by both comparisons
      stat = run_command(dir, common//'--t-end 20 --indicator megno --body point --output '// &
                         dir//'/mp.h5')
      call check_true(error, stat == 0, 'point-mass MEGNO map exits 0')
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/mp.h5 --agreement '// &
                         '--output '//dir//'/b.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'com1 = ') > 0, &
                      'rods against point masses refused (agreement): '//text)
      stat = run_command(dir, 'sweep-compare '//dir//'/m.h5 '//dir//'/mp.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'com1 = ') > 0, &
                      'rods against point masses refused (flip times): '//text)
      call check_true(error, .not. is_hdf5(dir//'/b.h5'), 'no file after a refusal')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_agreement

   !> `sweep-compare` of two MEGNO maps of the same 6 x 6 pixels (steps 0.04 and
   !> 0.02 sqrt(l1/g), t_end 20) compares MEGNO, not flip times: the changed pixels
   !> are those counted by hand from the two files' /sweep/megno (|b - a| > 0.01 |a|),
   !> the classes those of <Y> > 2.5; nothing is written (no agreement.h5 in the
   !> working directory, with --agreement too, unless --output); a MEGNO map against
   !> a flip map, another indicator or another t_end is refused in one line.
   subroutine test_compare_indicator(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, common, want
      type(h5file_t) :: h5
      real(dp), allocatable :: ma(:, :), mb(:, :)
      integer :: stat, n, n_changed, n_only_a
      logical :: existed, exists
      dir = scratch_dir('sweepcmpind')
      inquire (file='agreement.h5', exist=existed)
      common = 'sweep --quiet --n 6 --threads 2 --t-end 20 '
      stat = run_command(dir, common//'--dt 0.04 --indicator megno --output '//dir//'/a.h5')
      stat = stat + run_command(dir, common//'--dt 0.02 --indicator megno --output '// &
                                dir//'/b.h5')
      stat = stat + run_command(dir, common//'--dt 0.02 --indicator sali --output '// &
                                dir//'/s.h5')
      stat = stat + run_command(dir, common//'--dt 0.02 --output '//dir//'/f.h5')
      stat = stat + run_command(dir, 'sweep --quiet --n 6 --threads 2 --t-end 10 --dt 0.02 '// &
                                '--indicator megno --output '//dir//'/t.h5')
      call check_true(error, stat == 0, 'five maps exit 0')
      if (allocated(error)) return
      call h5%open(dir//'/a.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/megno', ma, error)
      call h5%close()
      if (.not. allocated(error)) call h5%open(dir//'/b.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/megno', mb, error)
      call h5%close()
      if (allocated(error)) return
      n_changed = count(abs(mb - ma) > 0.01_dp*abs(ma))
      n_only_a = count(ma > 2.5_dp .and. mb <= 2.5_dp)
      stat = run_command(dir, 'sweep-compare '//dir//'/a.h5 '//dir//'/b.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'two MEGNO maps compared: '//text)
      want = 'pixels_changed: '//to_str(n_changed)//new_line('a')
      call check_true(error, index(text, 'indicator: megno') > 0 .and. &
                      index(text, want) > 0 .and. index(text, 'pixels_flipping') == 0, &
                      'MEGNO values compared ('//want//'): '//text)
      call check_true(error, n_changed > 0 .and. n_changed < 36, &
                      'some pixels change, not all: '//to_str(n_changed))
      call check_true(error, index(text, 'pixels_classified: 36') > 0 .and. &
                      index(text, 'both_regular: '//to_str(count(ma <= 2.5_dp .and. &
                      mb <= 2.5_dp))) > 0 .and. index(text, 'chaotic_only_a: '// &
                      to_str(n_only_a)) > 0, 'classes by <Y> > 2.5: '//text)
      call check_true(error, index(text, 'the regular/chaotic classes agree on') > 0, &
                      'the summary line names the classes')
      stat = run_command(dir, 'sweep-compare '//dir//'/a.h5 '//dir//'/b.h5 --agreement')
      call check_true(error, stat == 0, '--agreement without --output exits 0')
      inquire (file='agreement.h5', exist=exists)
      call check_true(error, existed .or. .not. exists, 'no agreement.h5 written unasked')
      call refused(dir//'/a.h5 '//dir//'/f.h5', 'flip times')
      call refused(dir//'/a.h5 '//dir//'/s.h5', 'maps sali')
      call refused(dir//'/b.h5 '//dir//'/t.h5', 't_end')
      call refused(dir//'/a.h5 '//dir//'/b.h5 --agreement --force', '--force')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine refused(files, needle)
         character(len=*), intent(in) :: files, needle
         integer :: st, lines
         character(len=:), allocatable :: msg
         st = run_command(dir, 'sweep-compare '//files)
         call read_text(dir//'/stderr', msg, lines)
         call check_true(error, st == 2 .and. lines == 1 .and. index(msg, needle) > 0, &
                         'refused, naming '//needle//': '//msg)
      end subroutine refused
   end subroutine test_compare_indicator

   !> Fewer blocks than MPI ranks are said, with why the blocks stay and what would
   !> share them: a 16 x 16 map in the default 4096-pixel blocks is one block of 16
   !> rows (256 pixels) for 4 ranks, 3 idle; --block 16 (one row) makes 16 blocks.
   !> The same with block = 4096 given says "as given"; a map of 3 rows for 4 ranks
   !> says that at most 3 can work; 256 x 256 (16 blocks) for 4 ranks, and any map
   !> on one rank, say nothing.
   subroutine test_block_share_note(error)
      type(error_t), allocatable, intent(out) :: error
      call expect('--n 16', 4, '1 block of 256 pixels for 4 ranks: 3 ranks get no work')
      call expect('--n 16', 2, '1 block of 256 pixels for 2 ranks: 1 rank gets no work')
      call expect('--n 16', 4, 'so it stays as default; --block 16 makes 16 blocks')
      call expect('--n 16 --block 4096', 4, 'so it stays as given; --block 16 makes 16')
      call expect('--n1 16 --n2 3', 4, 'the map has 3 rows of axis 1: at most that many')
      call expect('--n 256', 4, '')
      call expect('--n 16', 1, '')
   contains
      subroutine expect(line, workers, want)
         character(len=*), intent(in) :: line, want
         integer, intent(in) :: workers
         type(sweep_config_t) :: cfg
         type(sweep_setup_t) :: setup
         type(error_t), allocatable :: err
         character(len=:), allocatable :: note
         logical :: help
         if (allocated(error)) return
         call parse_sweep(args_of(line//' --quiet'), cfg, help, err)
         if (.not. allocated(err)) call build_setup(cfg, setup, err)
         if (allocated(err)) then
            call check_true(error, .false., line//': refused: '//err%message)
            return
         end if
         note = block_share_note(setup, workers)
         if (len(want) == 0) then
            call check_true(error, len(note) == 0, line//': no note, got '//note)
         else
            call check_true(error, index(note, want) > 0, line//': '//note)
         end if
      end subroutine expect
   end subroutine test_block_share_note

   !> The elastic pendulum in the sweep: an indicator map over
   !> (r, phi) computed in process; four pixels against separate runs of the same
   !> initial conditions (a model from the factory, rk4 of the registry stepped by
   !> hand, the energy error in the model's energy_scale, MEGNO from
   !> chaos_indicators); the pixel at the hanging equilibrium r_eq = l0 + m g/k stays
   !> there.
   subroutine test_elastic_pixels(error)
      type(error_t), allocatable, intent(out) :: error
      type(arg_t), allocatable :: args(:)
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: res
      type(error_t), allocatable :: err
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(indicators_result_t) :: ind
      real(dp), allocatable :: y0(:, :)
      real(dp) :: y(4), t, hs, e0, emax, r_eq, t_end
      integer :: j, k, stat, jj(4)
      integer(i8) :: ks
      logical :: help
      character(len=24), parameter :: words(33) = [character(len=24) :: '--model', &
         'elastic', '--k', '50', '--m', '1.2', '--q', '1.3,-1.2', '--axis1', 'r', '--axis2', &
         'phi', '--n1', '3', '--n2', '2', '--min1', '1.0', '--max1', '1.2352', '--min2', &
         '-1.5707963267948966', '--max2', '-0.9', '--indicator', 'megno', '--t-end', '4', &
         '--time-unit', 's', '--quiet', '--dt', '0.01']
      allocate (args(size(words)))
      do j = 1, size(words)
         args(j)%s = trim(words(j))
      end do
      call parse_sweep(args, cfg, help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      if (allocated(err)) then
         call fatal_error(error, 'elastic sweep refused: '//err%message)
         return
      end if
      call check_true(error, setup%per_trajectory .and. .not. setup%flips .and. &
                      setup%nblocks == 1 .and. setup%n == 6, 'per-trajectory, no flips')
      if (allocated(error)) return
      call compute_block(setup, 1, res)
      call block_initial_conditions(setup, 1, y0)
      spec = model_spec('elastic')
      call spec%set('m', [1.2_dp]); call spec%set('k', [50.0_dp])
      call new_model(spec, model, err)
      if (.not. allocated(err)) call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, err%message)
         return
      end if
      r_eq = 1.0_dp + 1.2_dp*9.8_dp/50.0_dp   ! 1.2352 m, axis 1's last value
      t_end = real(setup%opt%n_steps, dp)*setup%opt%h
      call check(error, t_end, 4.0_dp, 't_end in s', rel=1e-14_dp)
      jj = [1, 3, 4, 6]   ! (r, phi) = (1, -pi/2), (r_eq, -pi/2), (1, -0.9), (r_eq, -0.9)
      do k = 1, size(jj)
         j = jj(k)
         call check_true(error, res%status(j) == 1 .and. res%steps(j) == setup%opt%n_steps &
                         .and. ieee_is_nan(res%t_flip(j)), 'runs to t_end, no flip')
         if (allocated(error)) return
         y = y0(:, j)
         e0 = model%energy(0.0_dp, y)
         emax = 0.0_dp
         t = 0.0_dp
         call integ%clear_step()
         do ks = 1, setup%opt%n_steps
            hs = setup%opt%h
            call integ%step(model, t, y, hs, stat)
            t = real(ks, dp)*setup%opt%h
            emax = max(emax, abs(model%energy(t, y) - e0))
         end do
         call check(error, res%final(:, j), y, 'final state as a single run', rel=0.0_dp, &
                    abs=0.0_dp)
         call check(error, res%energy0(j), e0, 'energy0', rel=0.0_dp, abs=0.0_dp)
         call check(error, res%energy_error(j), emax/model%energy_scale(e0), &
                    'energy error in the model''s energy_scale', rel=0.0_dp, abs=0.0_dp)
         call chaos_indicators(integ, model, 0.0_dp, y0(:, j), t_end, setup%opt%h, t_end, &
                               ind, stat)
         call check_true(error, stat == stat_ok, 'indicators of a single run')
         if (allocated(error)) return
         call check(error, res%megno(j), ind%mean_all(1, ind%n), 'MEGNO as a single run', &
                    rel=0.0_dp, abs=0.0_dp)
         call check_true(error, res%energy_error(j) < 1e-6_dp, 'rk4 conserves E to 1e-6')
         if (allocated(error)) return
      end do
      ! the hanging equilibrium (pixel 3) does not move
      call check(error, res%final(:, 3), [r_eq, -half_pi, 0.0_dp, 0.0_dp], &
                 'equilibrium stays', abs=1e-12_dp)
   end subroutine test_elastic_pixels

   !> Parameter axes beyond the uniform rods: point masses over (m2/m1, l2/l1) (the
   !> lane kernel, the bodies' centres following the swept lengths) and the elastic
   !> pendulum over its own parameters (k, l0) and over (r, k): every pixel equals, bit
   !> for bit, a one-pixel map of the same initial state run with its parameters given.
   subroutine test_parameter_bodies(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, common
      character(len=16), parameter :: lane_sets(4) = [character(len=16) :: 't_flip', &
         'sali', 'energy0', 'final/q1']
      character(len=16), parameter :: elastic_sets(4) = [character(len=16) :: 'megno', &
         'megno_y', 'energy0', 'final/q1']
      dir = scratch_dir('sweepbodies')
      ! point masses: m2/m1 in {0.5, 2}, l2/l1 in {0.5, 2}
      common = 'sweep --quiet --body point --t-end 5 --dt 0.01 --time-unit s ' &
               //'--indicator sali '
      call map_and_pixels(common//'--q1 0.3 --q2 -0.2 --axis1 m2/m1 --axis2 l2/l1 ' &
                          //'--min1 0.5 --max1 2 --min2 0.5 --max2 2 --n 2', &
                          [character(len=8) :: '0.5', '2'], [character(len=8) :: '0.5', '2'], &
                          common//'--axis1 q1 --axis2 q2 --min1 0.3 --max1 0.3 --min2 -0.2 ' &
                          //'--max2 -0.2 --n 1 --m2 X1 --l2 X2', lane_sets, 'point')
      if (allocated(error)) return
      ! the elastic pendulum over (k, l0), then over (r, k)
      common = 'sweep --quiet --model elastic --t-end 3 --dt 0.01 --time-unit s ' &
               //'--indicator megno --q 1.2,-1 '
      call map_and_pixels(common//'--axis1 k --axis2 l0 --min1 20 --max1 60 --min2 0.5 ' &
                          //'--max2 1.5 --n1 3 --n2 2 --threads 2 --block 2', &
                          [character(len=8) :: '20', '40', '60'], &
                          [character(len=8) :: '0.5', '1.5'], common//'--axis1 r --axis2 ' &
                          //'phi --min1 1.2 --max1 1.2 --min2 -1 --max2 -1 --n 1 --k X1 ' &
                          //'--l0 X2', elastic_sets, 'elastic')
      if (allocated(error)) return
      call map_and_pixels(common//'--axis1 r --axis2 k --min1 1 --max1 1.5 --min2 30 ' &
                          //'--max2 50 --n 2', [character(len=8) :: '1', '1.5'], &
                          [character(len=8) :: '30', '50'], common//'--axis1 r --axis2 ' &
                          //'phi --min1 X1 --max1 X1 --min2 -1 --max2 -1 --n 1 --k X2', &
                          elastic_sets, 'elastic (r, k)')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> The map `map_args`, then for each pixel (x1(i), x2(j)) the one-pixel map
      !> `template` with X1 and X2 replaced by them; the datasets `sets` agree bit for
      !> bit.
      subroutine map_and_pixels(map_args, x1, x2, template, sets, what)
         character(len=*), intent(in) :: map_args, x1(:), x2(:), template, sets(:), what
         real(dp), allocatable :: a(:, :), b(:, :)
         character(len=:), allocatable :: pixel
         integer :: i, j, k, stat
         stat = run_command(dir, map_args//' --force --output '//dir//'/map.h5')
         call check_true(error, stat == 0, what//': the parameter map exits 0')
         if (allocated(error)) return
         do j = 1, size(x2)
            do i = 1, size(x1)
               pixel = replaced(replaced(template, 'X1', trim(x1(i))), 'X2', trim(x2(j)))
               stat = run_command(dir, pixel//' --force --output '//dir//'/px.h5')
               call check_true(error, stat == 0, what//': the one-pixel map exits 0')
               do k = 1, size(sets)
                  if (allocated(error)) return
                  call read_map(error, dir//'/map.h5', '/sweep/'//trim(sets(k)), a)
                  call read_map(error, dir//'/px.h5', '/sweep/'//trim(sets(k)), b)
                  if (allocated(error)) return
                  call check_true(error, bits(a(i, j)) == bits(b(1, 1)), what//': '// &
                                  trim(sets(k))//' of pixel ('//trim(x1(i))//', '// &
                                  trim(x2(j))//') equals the direct run')
               end do
            end do
         end do
      end subroutine map_and_pixels
      !> `s` with every `key` replaced by `value`.
      function replaced(s, key, value) result(r)
         character(len=*), intent(in) :: s, key, value
         character(len=:), allocatable :: r
         integer :: k
         r = s
         do
            k = index(r, key)
            if (k == 0) exit
            r = r(:k - 1)//value//r(k + len(key):)
         end do
      end function replaced
   end subroutine test_parameter_bodies

   !> The 2-D dataset `path` of `file` (nothing if `error` is set already).
   subroutine read_map(error, file, path, v)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: file, path
      real(dp), allocatable, intent(out) :: v(:, :)
      type(h5file_t) :: h5
      if (allocated(error)) return
      call h5%open(file, 'r', error)
      if (.not. allocated(error)) call h5%read(path, v, error)
      call h5%close()
   end subroutine read_map

   !> The pendulum's parameters by name on the per-trajectory path: g beside θ1
   !> (rods), g beside θ2 (point masses), g beside the coded m2/m1, and m3 beside w1
   !> (three links). Every pixel equals, bit for bit, a one-pixel sweep of its initial
   !> state with its parameters given as fixed values on the per-trajectory path
   !> (the factory's model of that specification); /sweep/param holds the values.
   subroutine test_named_g(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: common = '--quiet --t-end 3 --dt 0.01 --time-unit s '
      call named_map_matches(error, common//'--q2 -0.4 --axis1 g --min1 1 --max1 12 ' &
                             //'--n1 3 --axis2 theta1 --min2 -2.5 --max2 2.9 --n2 2 --block 3', &
                             [character(len=8) :: '1', '6.5', '12'], &
                             [character(len=8) :: '-2.5', '2.9'], &
                             common//'--q2 -0.4 --g X1 --axis1 theta1 --min1 X2 --max1 X2 ' &
                             //'--axis2 w2 --min2 0 --max2 0 --n 1', ['g'], 'g x theta1')
      if (allocated(error)) return
      call named_map_matches(error, common//'--body point --q1 2.5 --axis1 theta2 ' &
                             //'--min1 -2 --max1 2 --n1 2 --axis2 g --min2 2 --max2 20 --n2 2', &
                             [character(len=8) :: '-2', '2'], [character(len=8) :: '2', '20'], &
                             common//'--body point --q1 2.5 --g X2 --axis1 theta2 --min1 X1 ' &
                             //'--max1 X1 --axis2 w2 --min2 0 --max2 0 --n 1', ['g'], &
                             'point masses theta2 x g')
      if (allocated(error)) return
      call named_map_matches(error, common//'--q1 1.2 --axis1 m2/m1 --min1 0.5 --max1 2 ' &
                             //'--n1 2 --axis2 g --min2 4 --max2 16 --n2 2', &
                             [character(len=8) :: '0.5', '2'], [character(len=8) :: '4', '16'], &
                             common//'--q1 1.2 --m2 X1 --g X2 --axis1 q2 --min1 0 ' &
                             //'--max1 0 --axis2 w2 --min2 0 --max2 0 --n 1', &
                             [character(len=2) :: 'm1', 'm2', 'l1', 'l2', 'g'], 'm2/m1 x g')
      if (allocated(error)) return
      call named_map_matches(error, common//'--links 3 --q 0.5,-0.3,0.2 --axis1 m3 ' &
                             //'--min1 0.5 --max1 3 --n1 2 --axis2 w1 --min2 -1 --max2 2 --n2 2', &
                             [character(len=8) :: '0.5', '3'], [character(len=8) :: '-1', '2'], &
                             common//'--links 3 --q 0.5,-0.3,0.2 --m 1,1,X1 --axis1 w1 ' &
                             //'--min1 X2 --max1 X2 --axis2 w2 --min2 0 --max2 0 --n 1', ['m3'], &
                             'three links m3 x w1')
   end subroutine test_named_g

   !> Bodies by name: com1 x inertia2 of general bodies (--com, --inertia given), and
   !> com2 x inertia1 of rods (their com and inertia not given: the other values are
   !> the rod's, l_i/2 and m_i l_i^2/12); every pixel as a direct run.
   subroutine test_named_bodies(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: common = '--quiet --t-end 3 --dt 0.01 --time-unit s ' &
                                      //'--q1 1.0 '
      call named_map_matches(error, common//'--com 0.4,0.6 --inertia 0.1,0.05 --axis1 com1 ' &
                             //'--min1 0.25 --max1 1.5 --n1 3 --axis2 inertia2 --min2 0 ' &
                             //'--max2 0.5 --n2 2 --stats', &
                             [character(len=8) :: '0.25', '0.875', '1.5'], &
                             [character(len=8) :: '0', '0.5'], &
                             common//'--com X1,0.6 --inertia 0.1,X2 --axis1 q2 --min1 0 ' &
                             //'--max1 0 --axis2 w2 --min2 0 --max2 0 --n 1 --stats', &
                             [character(len=8) :: 'com1', 'inertia2'], 'com1 x inertia2')
      if (allocated(error)) return
      call named_map_matches(error, common//'--axis1 com2 --min1 0.25 --max1 1 --n1 2 ' &
                             //'--axis2 inertia1 --min2 0 --max2 0.25 --n2 2', &
                             [character(len=8) :: '0.25', '1'], [character(len=8) :: '0', '0.25'], &
                             common//'--com 0.5,X1 --inertia X2,0.083333333333333329 ' &
                             //'--axis1 q2 --min1 0 --max1 0 --axis2 w2 --min2 0 --max2 0 ' &
                             //'--n 1', [character(len=8) :: 'com2', 'inertia1'], &
                             'rods com2 x inertia1')
   end subroutine test_named_bodies

   !> A named axis's values out of the catalogue's range are refused naming the
   !> pixel, the parameter, its value and the range; damping is not an axis.
   subroutine test_named_refused(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      character(len=*), parameter :: base = 'sweep --quiet --n 4 --t-end 1'
      dir = scratch_dir('sweepnamed')
      call expect_rejected(error, dir, base, '--axis1 g --min1 0 --max1 10', &
                           'invalid min1, max1, min2, max2: the pixel at (0, -3) is refused: ' &
                           //'invalid g: 0 m/s^2 is outside [1e-6, 1e6]')
      call expect_rejected(error, dir, base, '--axis2 inertia2 --min2 -1 --max2 1', &
                           'invalid inertia2: -1 kg m^2 is outside [0, 1e18]')
      call expect_rejected(error, dir, base//' --links 3', '--axis1 com3 --min1 -0.5 --max1 1', &
                           'invalid com3: -0.5 m is outside')
      call expect_rejected(error, dir, base, '--axis1 damping1', &
                           "invalid axis1: 'damping1' (accepted: theta1 theta2 q1 q2 w1 w2 m1 m2 " &
                           //'l1 l2 m2/m1 l2/l1 g com1 com2 inertia1 inertia2; damping')
      call expect_rejected(error, dir, base, '--axis1 coulomb2', &
                           "invalid axis1: 'coulomb2' (accepted: theta1 theta2 q1 q2 w1 w2 m1 m2 " &
                           //'l1 l2 m2/m1 l2/l1 g com1 com2 inertia1 inertia2; damping, friction')
      call expect_rejected(error, dir, base, '--axis2 coulomb_speed', "invalid axis2: " &
                           //"'coulomb_speed' (accepted:")
      call expect_rejected(error, dir, base, '--axis1 m3', "invalid axis1: 'm3'")
      call expect_rejected(error, dir, base//' --g 3', '--axis1 g --min1 1 --max1 2', &
                           "invalid g: axis1 'g' sweeps the value it fixes")
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_named_refused

   !> The map `map_line` (in process) against, for each pixel (x1(i), x2(j)), the
   !> one-pixel sweep `template` (X1, X2 replaced) on the per-trajectory path: every
   !> result bit for bit; /sweep/param's names and values those of the axes.
   subroutine named_map_matches(error, map_line, x1, x2, template, pnames, what)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: map_line, x1(:), x2(:), template, pnames(:), what
      type(sweep_config_t) :: cfg, cfg1
      type(sweep_setup_t) :: setup, setup1
      type(batch_result_t) :: res, one
      type(error_t), allocatable :: err
      real(dp), allocatable :: p(:, :)
      character(len=32), allocatable :: names(:)
      character(len=:), allocatable :: line
      logical :: help
      integer :: i, j, jj, b, j0, nb, k
      call parse_sweep(args_of(map_line), cfg, help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      if (allocated(err)) then
         call fatal_error(error, what//': map refused: '//err%message)
         return
      end if
      call check_true(error, setup%per_trajectory, what//': the per-trajectory path')
      if (allocated(error)) return
      names = parameter_names(setup)
      call check_true(error, size(names) == size(pnames), what//': parameters recorded')
      if (allocated(error)) return
      do k = 1, size(names)
         call check_true(error, trim(names(k)) == trim(pnames(k)), what//': /sweep/param/'// &
                         trim(pnames(k)))
         if (allocated(error)) return
      end do
      line = ''
      do b = 1, setup%nblocks
         call compute_block(setup, b, res)
         call block_parameters(setup, b, p)
         call block_range(setup, b, j0, nb)
         do jj = 1, nb
            i = mod(j0 + jj - 2, size(x1)) + 1
            j = (j0 + jj - 2)/size(x1) + 1
            ! the named axes' values recorded per pixel (the last row: axis 2 if named)
            if (names(size(names)) == cfg%axis1) call check(error, p(size(names), jj), &
               setup%axis1(i), what//': param of axis 1', rel=0.0_dp, abs=0.0_dp)
            if (names(size(names)) == cfg%axis2) call check(error, p(size(names), jj), &
               setup%axis2(j), what//': param of axis 2', rel=0.0_dp, abs=0.0_dp)
            if (allocated(error)) return
            line = replace(replace(template, 'X1', trim(x1(i))), 'X2', trim(x2(j)))
            call parse_sweep(args_of(line), cfg1, help, err)
            if (.not. allocated(err)) call build_setup(cfg1, setup1, err)
            if (allocated(err)) then
               call fatal_error(error, what//": pixel '"//line//"' refused: "//err%message)
               return
            end if
            setup1%per_trajectory = .true.; setup1%chain_lanes = .false.
            call compute_block(setup1, 1, one)
            call same_bits(res%t_flip(jj), one%t_flip(1), 't_flip')
            call same_bits(res%t_flip1(jj), one%t_flip1(1), 't_flip1')
            call same_bits(res%t_flip2(jj), one%t_flip2(1), 't_flip2')
            call same_bits(res%energy0(jj), one%energy0(1), 'energy0')
            call same_bits(res%energy_error(jj), one%energy_error(1), 'energy_error')
            call same_bits(res%t_stop(jj), one%t_stop(1), 't_stop')
            do k = 1, size(res%final, 1)
               call same_bits(res%final(k, jj), one%final(k, 1), 'final state')
            end do
            if (allocated(error)) return
            if (res%status(jj) /= one%status(1) .or. res%steps(jj) /= one%steps(1)) &
               call fatal_error(error, what//": status or steps differ at '"//line//"'")
            if (allocated(error)) return
         end do
      end do
   contains
      subroutine same_bits(a, c, name)
         real(dp), intent(in) :: a, c
         character(len=*), intent(in) :: name
         if (allocated(error)) return
         if (transfer(a, 1_i8) /= transfer(c, 1_i8)) call fatal_error(error, what//': '// &
            name//" differs from the direct run '"//line//"'")
      end subroutine same_bits
      function replace(t, key, val) result(r)
         character(len=*), intent(in) :: t, key, val
         character(len=:), allocatable :: r
         integer :: k
         r = t
         k = index(r, key)
         do while (k > 0)
            r = r(:k - 1)//val//r(k + len(key):)
            k = index(r, key)
         end do
      end function replace
   end subroutine named_map_matches

end module test_sweep
