!> The chain lanes (dpend_chain_lanes), compared with their sources:
!> - `chain_accel_lanes` is a copy of the chain model's equations of motion (M q̈ = f
!>   from K_ij and G_i, LDLᵀ) and of its energy: compared with `chain_t%accelerations`
!>   (Newton–Euler recursion and Cholesky) and `chain_t%energy` at random states of
!>   chains of 3 to 8 uniform rods and general bodies;
!> - `chain_rk4_lanes` step by step against the registry's rk4 on the chain model;
!> - `integrate_chain_lanes` against the per-trajectory path (`integrate_trajectories`)
!>   for every stop rule: the same statuses and steps, flip times, final states and
!>   energy errors within rounding, and bitwise independent of the lanes' order;
!> - the sweep's dispatch: which sweeps the lanes serve, and the kernel in the config;
!> - `chain_tangent_lanes` (the tangent's Jacobian–vector product) against central
!>   differences, and the indicators against the per-trajectory path's.
module test_chain_lanes
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t, stop_both, &
      stop_either, stop_end
   use dpend_pendulum_kernel, only: sincos_exact
   use dpend_chain_lanes, only: chain_coef_t, chain_coef, chain_accel_lanes, chain_rk4_lanes, &
      integrate_chain_lanes, max_lane_links, chain_tangent_lanes
   use dpend_trajectory_batch, only: integrate_trajectories
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep
   use dpend_sweep_setup, only: sweep_setup_t, build_setup
   use dpend_sweep_engine, only: compute_block
   use dpend_cli, only: arg_t
   use testing, only: unittest_t, new_unittest, check, check_true, fatal_error, check_same_time
   implicit none
   private
   public :: collect_chain_lanes

   integer, parameter :: w = lane_width, nm = max_lane_links

contains

   subroutine collect_chain_lanes(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('accelerations_match_model', test_accelerations), &
               new_unittest('steps_match_rk4', test_steps), &
               new_unittest('lanes_match_per_trajectory', test_paths), &
               new_unittest('independent_of_lane_order', test_order), &
               new_unittest('sweep_dispatch', test_dispatch), &
               new_unittest('tangent_matches_differences', test_tangent_accel), &
               new_unittest('indicators_match_per_trajectory', test_indicators), &
               new_unittest('runaway_to_t_end', test_runaway)]
   end subroutine collect_chain_lanes

   !> A fixed seed: the same draws on every run (each test starts from it).
   subroutine seed()
      integer :: n, i
      call random_seed(size=n)
      call random_seed(put=[(2718281 + 173*i, i=1, n)])
   end subroutine seed

   !> A chain of n links, uniform rods (body = .false.) or general bodies, with
   !> masses and lengths from the generator (log-uniform in [0.5, 2]).
   subroutine draw_chain(n, body, chain)
      integer, intent(in) :: n
      logical, intent(in) :: body
      type(chain_t), intent(out) :: chain
      real(dp) :: m(n), l(n), r(4*n)
      type(error_t), allocatable :: err
      call random_number(r)
      m = 2.0_dp**(2.0_dp*r(1:n) - 1.0_dp)
      l = 2.0_dp**(2.0_dp*r(n + 1:2*n) - 1.0_dp)
      if (body) then   ! centre of mass in [0.3, 0.9] L, inertia from 1/4 to 1 of a rod's
         chain = chain_model(m, l, 9.8_dp, err, com=(0.3_dp + 0.6_dp*r(2*n + 1:3*n))*l, &
                             inertia=m*l**2*(1.0_dp + 3.0_dp*r(3*n + 1:4*n))/48.0_dp)
      else
         chain = chain_model(m, l, 9.8_dp, err)
      end if
      if (allocated(err)) error stop 'test_chain_lanes: chain refused'
   end subroutine draw_chain

   !> q̈ and E of the lanes against the model at 16 random states of each of 24 chains
   !> (N = 3 … 8, rods and bodies). Error unit: the forces' scale
   !> (Σ_j |K_ij| q̇_j² + G_i) over the least diagonal entry of M (the solve's scale),
   !> and |T| + Σ G_i for the energy; measured maxima ~1e-15.
   subroutine test_accelerations(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(chain_coef_t) :: cf
      real(dp), dimension(w, nm) :: q, qd, s, c, a
      real(dp) :: e(w), r(w, nm, 2), qdd(nm), scale, dmax, emax, y(2*nm)
      integer :: n, l, i, rep
      call seed()
      dmax = 0.0_dp; emax = 0.0_dp
      q = 0.0_dp; qd = 0.0_dp
      do rep = 1, 4
         do n = 3, nm
            call draw_chain(n, mod(rep, 2) == 0, chain)
            cf = chain_coef(chain)
            call random_number(r)
            q(:, 1:n) = pi*(2.0_dp*r(:, 1:n, 1) - 1.0_dp)
            if (rep > 2) q(:, 1:n) = q(:, 1:n)*300.0_dp   ! large angles too
            qd(:, 1:n) = 10.0_dp*(2.0_dp*r(:, 1:n, 2) - 1.0_dp)
            do i = 1, n
               call sincos_exact(q(:, i), s(:, i), c(:, i))
            end do
            call chain_accel_lanes(cf, s, c, qd, a, e)
            do l = 1, w
               y(1:n) = q(l, 1:n); y(n + 1:2*n) = qd(l, 1:n)
               qdd(1:n) = chain%accelerations(y(1:n), y(n + 1:2*n))
               scale = 0.0_dp
               do i = 1, n
                  scale = max(scale, sum(abs(chain%k(i, 1:n))*qd(l, 1:n)**2) + chain%gl(i))
               end do
               scale = scale/minval([(chain%k(i, i), i=1, n)])
               dmax = max(dmax, maxval(abs(a(l, 1:n) - qdd(1:n)))/scale)
               scale = abs(chain%energy(0.0_dp, y(1:2*n))) + sum(chain%gl)
               emax = max(emax, abs(e(l) - chain%energy(0.0_dp, y(1:2*n)))/scale)
            end do
         end do
      end do
      print '(a, es9.2, a, es9.2)', '    max q̈ error ', dmax, ', max energy error ', emax
      call check_true(error, dmax < 1e-12_dp, 'chain_accel_lanes q̈ within 1e-12 of the model')
      call check_true(error, emax < 1e-13_dp, 'chain_accel_lanes E within 1e-13 of the model')
   end subroutine test_accelerations

   !> 400 steps of h = 1e-3 s of 16 lanes (N = 3, 5, 8; rods and bodies) against the
   !> registry's rk4 on the model, step by step (each rk4 step from the lanes' state
   !> before it, so that the chaos does not amplify the rounding): within 1e-12 (1 + |y|);
   !> measured ~1e-13 (the carried sin and cos drift by about an ulp per step).
   subroutine test_steps(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(chain_coef_t) :: cf
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      real(dp), dimension(w, nm) :: q, qd, ts, tc
      real(dp) :: e(w), r(w, nm, 2), y(2*nm, w), t, h, dmax
      integer :: links(3), k, n, l, i, step, stat
      call seed()
      links = [3, 5, 8]
      h = 1e-3_dp
      dmax = 0.0_dp
      call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, 'rk4: '//err%message)
         return
      end if
      q = 0.0_dp; qd = 0.0_dp
      do k = 1, 6
         n = links(mod(k - 1, 3) + 1)
         call draw_chain(n, k > 3, chain)
         cf = chain_coef(chain)
         call random_number(r)
         q(:, 1:n) = pi*(2.0_dp*r(:, 1:n, 1) - 1.0_dp)
         qd(:, 1:n) = 5.0_dp*(2.0_dp*r(:, 1:n, 2) - 1.0_dp)
         do i = 1, n
            call sincos_exact(q(:, i), ts(:, i), tc(:, i))
         end do
         do step = 1, 400
            do l = 1, w   ! rk4 from the lanes' state: each step compared on its own
               y(1:n, l) = q(l, 1:n); y(n + 1:2*n, l) = qd(l, 1:n)
            end do
            call chain_rk4_lanes(cf, h, q, qd, e, ts, tc)
            do l = 1, w
               t = real(step - 1, dp)*h
               call integ%step(chain, t, y(1:2*n, l), h, stat)
               if (stat /= stat_ok) then
                  call fatal_error(error, 'rk4 step failed')
                  return
               end if
               dmax = max(dmax, maxval(abs(q(l, 1:n) - y(1:n, l))/(1.0_dp + abs(y(1:n, l)))), &
                          maxval(abs(qd(l, 1:n) - y(n + 1:2*n, l))/(1.0_dp + abs(y(n + 1:2*n, l)))))
            end do
         end do
      end do
      print '(a, es9.2)', '    max state difference ', dmax
      call check_true(error, dmax < 1e-12_dp, 'chain lanes step by step within 1e-12 of rk4')
   end subroutine test_steps

   !> 40 initial states of a chain (some below every flip bound, some flipping fast).
   subroutine draw_states(n, y0)
      integer, intent(in) :: n
      real(dp), allocatable, intent(out) :: y0(:, :)
      real(dp) :: r(2*n, 40)
      integer :: j
      call random_number(r)
      allocate (y0(2*n, 40))
      do j = 1, 40
         y0(1:n, j) = -0.5_dp*pi + 3.0_dp*(2.0_dp*r(1:n, j) - 1.0_dp)*real(j, dp)/40.0_dp
         y0(n + 1:2*n, j) = 4.0_dp*(2.0_dp*r(n + 1:2*n, j) - 1.0_dp)*real(j, dp)/40.0_dp
      end do
   end subroutine draw_states

   !> The chain lanes against the per-trajectory path: N = 3 rods and N = 4 bodies,
   !> stop rules both, either and end, 300 steps of 0.01 s.
   subroutine test_paths(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(batch_options_t) :: opt
      type(batch_result_t) :: a, b
      real(dp), allocatable :: y0(:, :)
      integer :: rule, k, n, j, i, nflip, nskip
      call seed()
      call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, 'rk4: '//err%message)
         return
      end if
      opt%h = 0.01_dp
      opt%n_steps = 200
      nflip = 0; nskip = 0
      do k = 1, 2
         n = 2 + k
         call draw_chain(n, k == 2, chain)
         call draw_states(n, y0)
         do rule = stop_both, stop_end
            opt%stop_rule = rule
            call integrate_chain_lanes(chain, opt, y0, a)
            call integrate_trajectories(chain, integ, chain%gl, opt, y0, b)
            do j = 1, size(y0, 2)
               call check_true(error, a%status(j) == b%status(j) .and. &
                               a%steps(j) == b%steps(j), 'same status and steps')
               call check(error, a%energy0(j), b%energy0(j), 'energy0', abs=0.0_dp)
               do i = 1, n
                  call check_same_time(error, a%t_flip_link(i, j), b%t_flip_link(i, j), 't_flip_link', 1e-7_dp)
               end do
               call check_same_time(error, a%t_flip(j), b%t_flip(j), 't_flip', 1e-7_dp)
               call check_same_time(error, a%t_flip1(j), b%t_flip1(j), 't_flip1', 1e-7_dp)
               call check_same_time(error, a%t_flip2(j), b%t_flip2(j), 't_flip2', 1e-7_dp)
               call check(error, a%t_stop(j), b%t_stop(j), 't_stop', abs=0.0_dp)
               ! the rounding of the two paths, ~1e-15 a step (steps_match_rk4), grows
               ! in the chaotic trajectories (up to ~1e-5 after 2 s for some seeds);
               ! a wrong lane, step or state in the bookkeeping differs by O(1)
               call check(error, a%final(:, j), b%final(:, j), 'final state', rel=1e-3_dp, &
                          abs=1e-3_dp)
               if (ieee_is_nan(b%energy_error(j))) then
                  call check_true(error, ieee_is_nan(a%energy_error(j)), 'energy_error NaN')
                  nskip = nskip + 1
               else
                  call check(error, a%energy_error(j), b%energy_error(j), 'energy_error', &
                             abs=1e-13_dp, rel=1e-3_dp)
               end if
               call check_true(error, ieee_is_nan(a%lyapunov(j)) .and. ieee_is_nan(a%megno(j)), &
                               'no Lyapunov exponent, no indicators')
               if (.not. ieee_is_nan(b%t_flip(j))) nflip = nflip + 1
               if (allocated(error)) return
            end do
         end do
      end do
      call check_true(error, nflip > 20 .and. nskip > 0, 'some flip, some below the bounds')
   end subroutine test_paths

   !> The same states in reverse order (other lanes, other neighbours): bitwise the
   !> same results, flip map and indicators.
   subroutine test_order(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(batch_options_t) :: opt
      type(batch_result_t) :: a, b
      real(dp), allocatable :: y0(:, :)
      integer :: j, m, k, nv
      call seed()
      call draw_chain(5, .true., chain)
      call draw_states(5, y0)
      opt%h = 0.01_dp
      opt%n_steps = 200
      opt%stop_rule = stop_either
      m = size(y0, 2)
      do nv = 0, 2, 2   ! the flip map, and the indicators with two vectors
         opt%vectors = nv
         call integrate_chain_lanes(chain, opt, y0, a)
         call integrate_chain_lanes(chain, opt, y0(:, m:1:-1), b)
         do j = 1, m
            k = m + 1 - j
            call check_true(error, all(a%final(:, j) == b%final(:, k)) .and. &
                            a%steps(j) == b%steps(k) .and. a%status(j) == b%status(k) .and. &
                            same(a%energy_error(j), b%energy_error(k)) .and. &
                            all(same(a%t_flip_link(:, j), b%t_flip_link(:, k))) .and. &
                            same(a%megno(j), b%megno(k)) .and. same(a%fli(j), b%fli(k)) .and. &
                            same(a%sali(j), b%sali(k)) .and. same(a%gali2(j), b%gali2(k)), &
                            'results independent of the lane')
         end do
      end do
   contains
      elemental logical function same(x, y)
         real(dp), intent(in) :: x, y
         same = x == y .or. (ieee_is_nan(x) .and. ieee_is_nan(y))
      end function same
   end subroutine test_order

   !> Which sweeps the chain lanes serve (flip maps of 3 to 8 links over initial
   !> values), the kernel named in the configuration, and a block through the sweep's
   !> dispatch equal to the lanes' own results.
   subroutine test_dispatch(error)
      type(error_t), allocatable, intent(out) :: error
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: a, b
      integer :: j
      call setup_of([character(len=16) :: '--links', '3'], setup, error)
      if (allocated(error)) return
      call check_true(error, setup%chain_lanes, 'N = 3 flip map: chain lanes')
      call check_true(error, index(setup%config, 'kernel = chain lanes') > 0, &
                      'config names the chain lanes')
      ! a block through the dispatch: the lanes' results (the per-trajectory path's
      ! within rounding: lanes_match_per_trajectory)
      call compute_block(setup, 1, a)
      setup%chain_lanes = .false.
      call compute_block(setup, 1, b)
      do j = 1, a%n
         call check_true(error, a%status(j) == b%status(j) .and. a%steps(j) == b%steps(j), &
                         'dispatch: same status and steps as the per-trajectory path')
         call check(error, a%final(:, j), b%final(:, j), 'dispatch: final', abs=1e-9_dp)
      end do
      call setup_of([character(len=16) :: '--links', '8'], setup, error)
      call check_true(error, setup%chain_lanes, 'N = 8: chain lanes')
      call setup_of([character(len=16) :: '--links', '9'], setup, error)
      call check_true(error, .not. setup%chain_lanes .and. &
                      index(setup%config, 'kernel = per trajectory') > 0, 'N = 9: per trajectory')
      call setup_of([character(len=16) :: '--links', '2'], setup, error)
      call check_true(error, .not. setup%chain_lanes, 'N = 2: the two-link kernel')
      call setup_of([character(len=16) :: '--links', '3', '--indicator', 'megno'], setup, error)
      call check_true(error, setup%chain_lanes, 'MEGNO: chain lanes')
      call setup_of([character(len=16) :: '--links', '4', '--indicator', 'gali2'], setup, error)
      call check_true(error, setup%chain_lanes, 'GALI_2: chain lanes')
      call setup_of([character(len=16) :: '--links', '3', '--axis1', 'm1', '--min1', '0.5', &
                     '--max1', '2'], setup, error)
      call check_true(error, .not. setup%chain_lanes, 'parameter maps: per trajectory')
   end subroutine test_dispatch

   !> The Jacobian–vector product of `chain_tangent_lanes` against central differences
   !> of `chain_accel_lanes` (ε = 1e-6 along each vector): 16 lanes at random states of
   !> each of 24 chains (N = 3 … 8, rods and bodies), two vectors. Error unit: 1 + the
   !> largest |δq̈| of the lane; the differences' own error is about ε² |q̈'''| +
   !> 1e-16 |q̈|/ε, ~1e-9 here (measured maximum printed). Its q̈ is that of
   !> `chain_accel_lanes` bit for bit.
   subroutine test_tangent_accel(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(chain_coef_t) :: cf
      real(dp), dimension(w, nm) :: q, qd, s, c, a, at, ap, am, qp, wp
      real(dp) :: xq(w, nm, 2), xw(w, nm, 2), b(w, nm, 2), e(w), r(w, nm, 4)
      real(dp) :: fd(w, nm), dmax, unit
      real(dp), parameter :: eps = 1e-6_dp
      integer :: n, l, i, k, rep
      call seed()
      dmax = 0.0_dp
      q = 0.0_dp; qd = 0.0_dp; xq = 0.0_dp; xw = 0.0_dp
      do rep = 1, 4
         do n = 3, nm
            call draw_chain(n, mod(rep, 2) == 0, chain)
            cf = chain_coef(chain)
            call random_number(r)
            q(:, 1:n) = pi*(2.0_dp*r(:, 1:n, 1) - 1.0_dp)
            qd(:, 1:n) = 5.0_dp*(2.0_dp*r(:, 1:n, 2) - 1.0_dp)
            xq(:, 1:n, 1) = 2.0_dp*r(:, 1:n, 3) - 1.0_dp
            xw(:, 1:n, 1) = 2.0_dp*r(:, 1:n, 4) - 1.0_dp
            xq(:, 1:n, 2) = xw(:, 1:n, 1)
            xw(:, 1:n, 2) = -xq(:, 1:n, 1)
            call trig(q, s, c)
            call chain_accel_lanes(cf, s, c, qd, a, e)
            call chain_tangent_lanes(cf, s, c, qd, at, 2, xq, xw, b)
            call check_true(error, all(at(:, 1:n) == a(:, 1:n)), &
                            'chain_tangent_lanes: q̈ as chain_accel_lanes')
            do k = 1, 2
               qp = q + eps*xq(:, :, k); wp = qd + eps*xw(:, :, k)
               call trig(qp, s, c)
               call chain_accel_lanes(cf, s, c, wp, ap)
               qp = q - eps*xq(:, :, k); wp = qd - eps*xw(:, :, k)
               call trig(qp, s, c)
               call chain_accel_lanes(cf, s, c, wp, am)
               fd = (ap - am)/(2.0_dp*eps)
               do l = 1, w
                  unit = 1.0_dp + maxval(abs(b(l, 1:n, k)))
                  dmax = max(dmax, maxval(abs(b(l, 1:n, k) - fd(l, 1:n)))/unit)
               end do
            end do
            if (allocated(error)) return
         end do
      end do
      print '(a, es9.2)', '    max difference from central differences ', dmax
      call check_true(error, dmax < 1e-7_dp, 'δq̈ within 1e-7 of central differences')
   contains
      subroutine trig(x, sx, cx)
         real(dp), intent(in) :: x(w, nm)
         real(dp), intent(out) :: sx(w, nm), cx(w, nm)
         do i = 1, nm
            call sincos_exact(x(:, i), sx(:, i), cx(:, i))
         end do
      end subroutine trig
   end subroutine test_tangent_accel

   !> The indicators of the chain lanes against the per-trajectory path
   !> (`integrate_trajectories`, `chaos_indicators`): N = 3 rods and N = 5 bodies,
   !> 1 and 2 vectors, 40 states, 100 and 600 steps of 0.001 s. The lanes' tangent step
   !> (the derivative of their RK4 step) and the path's (RK4 on the variational
   !> equation along the step's interpolant, in substeps) are different fourth-order
   !> approximations of the same tangent flow: the same statuses, steps and NaN
   !> indicators; MEGNO ⟨Y⟩ nearer to the path's than the path at dt/2 is in at least
   !> 95 % of the trajectories; every indicator within 1e-7 (100 steps) and 1e-4 (600
   !> steps, chaotic growth) of max(1, |path's|) (measured maxima printed: 6e-9, 2e-5).
   subroutine test_indicators(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(batch_options_t) :: opt, half
      type(batch_result_t) :: a, b, c
      real(dp), allocatable :: y0(:, :)
      real(dp) :: tol, dmax(5)
      integer :: k, n, j, nv, il, nearer, finite
      call seed()
      call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, 'rk4: '//err%message)
         return
      end if
      opt%h = 0.001_dp
      opt%stop_rule = stop_end
      do k = 1, 2
         n = merge(3, 5, k == 1)
         call draw_chain(n, k == 2, chain)
         call draw_states(n, y0)
         do il = 1, 2
            opt%n_steps = merge(100, 600, il == 1)
            tol = merge(1e-7_dp, 1e-4_dp, il == 1)
            do nv = 1, 2
               opt%vectors = nv
               half = opt
               half%h = 0.5_dp*opt%h
               half%n_steps = 2*opt%n_steps
               call integrate_chain_lanes(chain, opt, y0, a)
               call integrate_trajectories(chain, integ, chain%gl, opt, y0, b)
               call integrate_trajectories(chain, integ, chain%gl, half, y0, c)
               dmax = 0.0_dp
               nearer = 0; finite = 0
               do j = 1, size(y0, 2)
                  call check_true(error, a%status(j) == b%status(j) .and. &
                                  a%steps(j) == b%steps(j), 'indicators: same status, steps')
                  call near(a%megno(j), b%megno(j), 1)
                  call near(a%megno_y(j), b%megno_y(j), 2)
                  call near(a%fli(j), b%fli(j), 3)
                  if (nv == 2) then
                     call near(a%sali(j), b%sali(j), 4)
                     call near(a%gali2(j), b%gali2(j), 5)
                  else
                     call check_true(error, ieee_is_nan(a%sali(j)) .and. &
                                     ieee_is_nan(a%gali2(j)), 'one vector: no SALI, GALI_2')
                  end if
                  if (allocated(error)) return
                  if (ieee_is_nan(b%megno(j))) cycle
                  finite = finite + 1
                  if (abs(a%megno(j) - b%megno(j)) <= abs(c%megno(j) - b%megno(j))) &
                     nearer = nearer + 1
               end do
               print '(a, i0, a, i0, a, i0, a, 5es9.2, a, i0, a, i0)', '    N = ', n, ', ', &
                  opt%n_steps, ' steps, ', nv, ' vectors: max rel. difference ', dmax, &
                  '; MEGNO nearer than dt/2 ', nearer, ' of ', finite
               call check_true(error, real(nearer, dp) >= 0.95_dp*real(finite, dp), &
                               'MEGNO of the lanes nearer to the path than dt/2, 95 %')
               if (allocated(error)) return
            end do
         end do
      end do
   contains
      !> x against the path's y within tol relative (to max(1, |y|)), NaN in both.
      subroutine near(x, y, slot)
         real(dp), intent(in) :: x, y
         integer, intent(in) :: slot
         if (ieee_is_nan(y)) then
            call check_true(error, ieee_is_nan(x), 'indicator NaN in both')
            return
         end if
         call check_true(error, .not. ieee_is_nan(x), 'indicator finite in both')
         if (allocated(error)) return
         dmax(slot) = max(dmax(slot), abs(x - y)/max(1.0_dp, abs(y)))
         call check(error, x, y, 'indicator', abs=tol*max(1.0_dp, abs(y)))
      end subroutine near
   end subroutine test_indicators

   !> Rates of 1e3 rad/s run away within a few steps (the velocities' squares reach the
   !> lanes' clamp, the stages' offsets far beyond 1): run to t_end without a trap in
   !> the debug build, for the flip map and the indicators, the same statuses, steps
   !> and NaN indicators as the per-trajectory path.
   subroutine test_runaway(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(batch_options_t) :: opt
      type(batch_result_t) :: a, b
      real(dp) :: y0(6, 20)
      integer :: j, nv
      call seed()
      call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, 'rk4: '//err%message)
         return
      end if
      call draw_chain(3, .false., chain)
      do j = 1, 20
         y0(:, j) = [0.1_dp*j, -0.2_dp*j, 0.3_dp, 1e3_dp, -1e3_dp*j, 1e3_dp]
      end do
      opt%h = 0.01_dp
      opt%n_steps = 200
      opt%stop_rule = stop_end
      do nv = 0, 2
         opt%vectors = nv
         call integrate_chain_lanes(chain, opt, y0, a)
         call integrate_trajectories(chain, integ, chain%gl, opt, y0, b)
         do j = 1, 20
            call check_true(error, a%status(j) == b%status(j) .and. a%steps(j) == b%steps(j) &
                            .and. a%steps(j) < 200, 'runaway: same status and steps')
            call check_true(error, ieee_is_nan(a%megno(j)) .and. ieee_is_nan(a%sali(j)), &
                            'runaway: NaN indicators')
            if (allocated(error)) return
         end do
      end do
   end subroutine test_runaway

   !> The setup of `dpend sweep` on a small grid with the given extra words.
   subroutine setup_of(extra, setup, error)
      character(len=*), intent(in) :: extra(:)
      type(sweep_setup_t), intent(out) :: setup
      type(error_t), allocatable, intent(inout) :: error
      character(len=16), parameter :: words(11) = [character(len=16) :: '--n', '4', &
         '--t-end', '1', '--time-unit', 's', '--dt', '0.01', '--quiet', '--block', '16']
      type(arg_t), allocatable :: args(:)
      type(sweep_config_t) :: cfg
      type(error_t), allocatable :: err
      logical :: help
      integer :: j
      if (allocated(error)) return
      allocate (args(size(words) + size(extra)))
      do j = 1, size(words)
         args(j)%s = trim(words(j))
      end do
      do j = 1, size(extra)
         args(size(words) + j)%s = trim(extra(j))
      end do
      call parse_sweep(args, cfg, help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      if (allocated(err)) call fatal_error(error, 'setup: '//err%message)
   end subroutine setup_of

end module test_chain_lanes
