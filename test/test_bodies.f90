!> Links of any mass distribution against independently known values:
!> - the point-mass double pendulum (`--body point`) against the textbook equations
!>   written out here (matplotlib's double-pendulum example, angles from the downward
!>   vertical, converted to the chapter's convention q = theta − π/2): accelerations at
!>   random states, and a 10 s trajectory;
!> - general bodies (unequal d_i, I_i), the two-link model and the chain of 2 and 3
!>   links, against the descriptor system of the free-body diagrams written here (3N
!>   unknowns: q̈ and every joint reaction, solved at once by LAPACK dgesv);
!> - the rod's default against the general formulas at rod values and the closed form
!>   of the horizontal release (docs/physics.md);
!> - the energy of a point-mass and a general-body pendulum kept by gauss6;
!> - the balance m a_C = ΣF and I q̈ = ΣM of each body with the model's reactions;
!> - the two-link model and the 2-link chain (`general`) agree for general bodies;
!> - the SIMD lanes' constants for a point-mass pendulum against the scalar model;
!> - the power balance dE/dt = P_support − P_friction of a damped, driven chain of bodies;
!> - the general two-link Jacobians and energy gradient against central differences;
!> - refusals of invalid bodies;
!> - Poincaré sections (q1 = −π/2 crossed with q̇1 > 0) of a point-mass and a general
!>   two-link pendulum against crossings located here on a classical RK4 integration
!>   of the textbook equations (point masses) or of the descriptor system (general),
!>   with the momentum p2 from its closed form.
module test_bodies
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t, body_general, body_rod, qddot, reactions, &
                             kinematics, kinematics_t, energy, pendulum_model, check_bodies, &
                             double_pendulum_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_model_factory, only: model_spec_t, model_spec, new_model
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t, stop_end
   use dpend_pendulum_kernel, only: batch_coef, accel_lanes
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_fixed
   use dpend_lapack, only: dgesv
   use dpend_events, only: angle_crossing_t
   use dpend_poincare, only: section_orbit
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_bodies

   real(dp), parameter :: pi = acos(-1.0_dp)

   !> Park–Miller minimal standard generator (exact in real(dp)), fixed seed.
   type :: rng_t
      real(dp) :: s = 20261127.0_dp
   end type rng_t

contains

   subroutine collect_bodies(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('point_mass_textbook_accelerations', test_point_accel), &
               new_unittest('point_mass_textbook_trajectory', test_point_trajectory), &
               new_unittest('general_descriptor_system', test_descriptor), &
               new_unittest('rod_default_unchanged', test_rod_default), &
               new_unittest('energy_kept_by_gauss6', test_energy), &
               new_unittest('joint_forces_balance', test_balance), &
               new_unittest('two_link_equals_chain', test_two_link_chain), &
               new_unittest('lanes_point_mass', test_lanes), &
               new_unittest('damped_driven_power_balance', test_power), &
               new_unittest('general_jacobians_finite_differences', test_jacobians), &
               new_unittest('refuses_bad_bodies', test_refuse), &
               new_unittest('poincare_independent', test_poincare)]
   end subroutine collect_bodies

   real(dp) function uniform(rng, a, b)
      type(rng_t), intent(inout) :: rng
      real(dp), intent(in) :: a, b
      rng%s = mod(16807.0_dp*rng%s, 2147483647.0_dp)
      uniform = a + (b - a)*rng%s/2147483647.0_dp
   end function uniform

   !> A point-mass pendulum: d_i = l_i, I_i = 0.
   pure function point_pendulum(m1, m2, l1, l2, g) result(par)
      real(dp), intent(in) :: m1, m2, l1, l2, g
      type(pendulum_t) :: par
      par = pendulum_t(m1=m1, m2=m2, l1=l1, l2=l2, g=g)
      par%body = body_general
      par%d1 = l1; par%d2 = l2; par%i1 = 0.0_dp; par%i2 = 0.0_dp
   end function point_pendulum

   !> The textbook point-mass equations (matplotlib's double_pendulum example,
   !> `derivs`): state (θ1, ω1, θ2, ω2), θ from the downward vertical, x = L sin θ,
   !> y = −L cos θ.
   pure function textbook(m1, m2, l1, l2, g, s) result(dydx)
      real(dp), intent(in) :: m1, m2, l1, l2, g, s(4)
      real(dp) :: dydx(4), delta, den1, den2
      dydx(1) = s(2)
      delta = s(3) - s(1)
      den1 = (m1 + m2)*l1 - m2*l1*cos(delta)*cos(delta)
      dydx(2) = (m2*l1*s(2)*s(2)*sin(delta)*cos(delta) + m2*g*sin(s(3))*cos(delta) &
                 + m2*l2*s(4)*s(4)*sin(delta) - (m1 + m2)*g*sin(s(1)))/den1
      dydx(3) = s(4)
      den2 = (l2/l1)*den1
      dydx(4) = (-m2*l2*s(4)*s(4)*sin(delta)*cos(delta) + (m1 + m2)*g*sin(s(1))*cos(delta) &
                 - (m1 + m2)*l1*s(2)*s(2)*sin(delta) - (m1 + m2)*g*sin(s(3)))/den2
   end function textbook

   !> q̈ of the model against the textbook's θ̈ (θ = q + π/2) at 500 random states
   !> and parameters, relative to max(|θ̈|, g/l_min): 1e-13.
   subroutine test_point_accel(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(pendulum_t) :: par
      real(dp) :: q(2), w(2), a(2), t(4), d, scale
      integer :: k
      d = 0.0_dp
      do k = 1, 500
         par = point_pendulum(uniform(rng, 0.2_dp, 5.0_dp), uniform(rng, 0.2_dp, 5.0_dp), &
                              uniform(rng, 0.2_dp, 3.0_dp), uniform(rng, 0.2_dp, 3.0_dp), &
                              uniform(rng, 1.0_dp, 20.0_dp))
         q = [uniform(rng, -pi, pi), uniform(rng, -pi, pi)]
         w = [uniform(rng, -5.0_dp, 5.0_dp), uniform(rng, -5.0_dp, 5.0_dp)]
         a = qddot(par, q, w)
         t = textbook(par%m1, par%m2, par%l1, par%l2, par%g, &
                      [q(1) + 0.5_dp*pi, w(1), q(2) + 0.5_dp*pi, w(2)])
         scale = max(maxval(abs(t([2, 4]))), par%g/min(par%l1, par%l2), &
                     maxval(w**2))
         d = max(d, maxval(abs(a - t([2, 4])))/scale)
      end do
      write (*, '(a, es9.2)') '    bodies: point mass vs textbook, max rel diff of qdd ', d
      call check(error, d, 0.0_dp, 'point mass vs textbook accelerations', abs=1e-13_dp)
   end subroutine test_point_accel

   !> 10 s from θ = (2.0, 0.5) rad (chaotic energy) and from (0.4, −0.3) (regular), by
   !> dpend's rk4 on the model and by a classical RK4 written here on the textbook
   !> field, both h = 1e-3 s: the same method on two formulations of one field, so that
   !> they differ by the rounding of the fields only (regular: to 1e-12 rad; the
   !> chaotic release to 1e-8 rad, its rounding grown by the Lyapunov exponent).
   subroutine test_point_trajectory(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(pendulum_t) :: par
      real(dp) :: y(4), s(4), k1(4), k2(4), k3(4), k4(4), t, h, d(2)
      real(dp), parameter :: th0(2, 2) = reshape([0.4_dp, -0.3_dp, 2.0_dp, 0.5_dp], [2, 2])
      integer :: i, run, stat
      par = point_pendulum(1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 9.8_dp)
      do run = 1, 2
         call new_integrator('rk4', integ, err)
         y = [th0(1, run) - 0.5_dp*pi, th0(2, run) - 0.5_dp*pi, 0.0_dp, 0.0_dp]
         s = [th0(1, run), 0.0_dp, th0(2, run), 0.0_dp]
         t = 0.0_dp; h = 1e-3_dp
         call advance_fixed(integ, pendulum_model(par), t, y, h, 10000_i8, stat)
         call check_true(error, stat == stat_ok, 'rk4 run')
         do i = 1, 10000
            k1 = tb(s)
            k2 = tb(s + 0.5e-3_dp*k1)
            k3 = tb(s + 0.5e-3_dp*k2)
            k4 = tb(s + 1e-3_dp*k3)
            s = s + 1e-3_dp/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
         end do
         d(run) = maxval(abs([y(1) + 0.5_dp*pi - s(1), y(2) + 0.5_dp*pi - s(3), &
                              y(3) - s(2), y(4) - s(4)]))
      end do
      write (*, '(a, 2es9.2)') '    bodies: point mass 10 s rk4 vs textbook rk4, max diff ' &
         //'(regular, chaotic) ', d
      call check(error, d(1), 0.0_dp, 'regular release after 10 s', abs=1e-12_dp)
      call check(error, d(2), 0.0_dp, 'chaotic release after 10 s', abs=1e-8_dp)
   contains
      function tb(x) result(f)
         real(dp), intent(in) :: x(4)
         real(dp) :: f(4)
         f = textbook(par%m1, par%m2, par%l1, par%l2, par%g, x)
      end function tb
   end subroutine test_point_trajectory

   !> The descriptor system of N links with centres of mass at d_i and inertias I_i
   !> about them: per link m_i a_Ci = F_(i−1,i) − F_(i,i+1) + G_i and
   !> I_i q̈_i = (P_(i−1) − C_i) × F_(i−1,i) + (P_i − C_i) × (−F_(i,i+1)), with
   !> a_Ci = Σ_(j<i) L_j (q̈_j n_j − q̇_j² u_j) + d_i (q̈_i n_i − q̇_i² u_i): 3N linear
   !> equations in q̈ and the reactions F_(i−1,i), solved by dgesv.
   subroutine descriptor(n, m, l, d, ic, g, y, qdd, f)
      integer, intent(in) :: n
      real(dp), intent(in) :: m(n), l(n), d(n), ic(n), g, y(2*n)
      real(dp), intent(out) :: qdd(n), f(2, n)
      real(dp) :: a(3*n, 3*n), b(3*n), c(n), s(n), cij
      integer :: i, j, r, ipiv(3*n), info, fi, fn
      c = cos(y(1:n)); s = sin(y(1:n))
      a = 0.0_dp; b = 0.0_dp
      do i = 1, n
         r = 3*(i - 1)
         fi = n + 2*(i - 1)
         fn = n + 2*i
         do j = 1, i
            cij = merge(d(i), l(j), j == i)
            a(r + 1, j) = -m(i)*cij*s(j)
            a(r + 2, j) = m(i)*cij*c(j)
            b(r + 1) = b(r + 1) + m(i)*cij*y(n + j)**2*c(j)
            b(r + 2) = b(r + 2) + m(i)*cij*y(n + j)**2*s(j)
         end do
         b(r + 2) = b(r + 2) - m(i)*g
         a(r + 1, fi + 1) = -1.0_dp
         a(r + 2, fi + 2) = -1.0_dp
         ! I q̈ + d u × F_(i−1,i) + (L − d) u × F_(i,i+1) = 0, u × F = c F_y − s F_x
         a(r + 3, i) = ic(i)
         a(r + 3, fi + 1) = -d(i)*s(i)
         a(r + 3, fi + 2) = d(i)*c(i)
         if (i < n) then
            a(r + 1, fn + 1) = 1.0_dp
            a(r + 2, fn + 2) = 1.0_dp
            a(r + 3, fn + 1) = -(l(i) - d(i))*s(i)
            a(r + 3, fn + 2) = (l(i) - d(i))*c(i)
         end if
      end do
      call dgesv(3*n, 1, a, 3*n, ipiv, b, 3*n, info)
      if (info /= 0) error stop 'descriptor: dgesv failed'
      qdd = b(1:n)
      f = reshape(b(n + 1:3*n), [2, n])
   end subroutine descriptor

   !> Random bodies: m in [0.2, 5] kg, l in [0.2, 3] m, d in [0, 1.5 l] (a bob beyond
   !> the pin included), I in [0, m l²/6]; every third link a point mass.
   subroutine random_bodies(rng, n, m, l, d, ic, g)
      type(rng_t), intent(inout) :: rng
      integer, intent(in) :: n
      real(dp), intent(out) :: m(n), l(n), d(n), ic(n), g
      integer :: i
      do i = 1, n
         m(i) = uniform(rng, 0.2_dp, 5.0_dp)
         l(i) = uniform(rng, 0.2_dp, 3.0_dp)
         d(i) = uniform(rng, 0.05_dp, 1.5_dp)*l(i)
         ic(i) = uniform(rng, 0.0_dp, 1.0_dp/6.0_dp)*m(i)*l(i)**2
         if (mod(i, 3) == 0) then
            d(i) = l(i); ic(i) = 0.0_dp
         end if
      end do
      g = uniform(rng, 1.0_dp, 20.0_dp)
   end subroutine random_bodies

   !> |a − b| / max(|b|) (0 when both vanish).
   pure real(dp) function rel_diff(a, b)
      real(dp), intent(in) :: a(:), b(:)
      rel_diff = maxval(abs(a - b))/max(maxval(abs(b)), tiny(1.0_dp))
   end function rel_diff

   !> The two-link model and the chain of 2 and 3 links with general bodies: q̈ and
   !> every joint reaction against the descriptor system, 300 random states each, to
   !> 1e-10 (relative to the largest).
   subroutine test_descriptor(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(rng_t) :: rng
      type(chain_t) :: chain
      type(pendulum_t) :: par
      real(dp) :: m(3), l(3), d(3), ic(3), g, y(6), fy(6), qdd(3), fd(2, 3), fm(2, 3)
      real(dp) :: f01(2), f21(2), dq(2), dr(2)
      integer :: k, n
      dq = 0.0_dp; dr = 0.0_dp
      do k = 1, 300
         do n = 2, 3
            call random_bodies(rng, n, m(1:n), l(1:n), d(1:n), ic(1:n), g)
            call random_state(rng, n, y(1:2*n))
            chain = chain_model(m(1:n), l(1:n), g, err, com=d(1:n), inertia=ic(1:n))
            call check_true(error, .not. allocated(err), 'chain of general bodies built')
            if (allocated(error)) return
            call chain%field(0.0_dp, y(1:2*n), fy(1:2*n))
            call descriptor(n, m(1:n), l(1:n), d(1:n), ic(1:n), g, y(1:2*n), qdd(1:n), &
                            fd(:, 1:n))
            dq(1) = max(dq(1), rel_diff(fy(n + 1:2*n), qdd(1:n)))
            call chain%reactions(y(1:n), y(n + 1:2*n), fy(n + 1:2*n), fm(:, 1:n))
            dr(1) = max(dr(1), rel_diff(reshape(fm(:, 1:n), [2*n]), &
                                        reshape(fd(:, 1:n), [2*n])))
            if (n == 2) then
               par = pendulum_t(m1=m(1), m2=m(2), l1=l(1), l2=l(2), g=g)
               par%body = body_general
               par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
               fy(3:4) = qddot(par, y(1:2), y(3:4))
               dq(2) = max(dq(2), rel_diff(fy(3:4), qdd(1:2)))
               call reactions(par, y(1:2), y(3:4), fy(3:4), f01, f21)
               ! F01 = F_(0,1); F21 (link 2 on link 1) = −F_(1,2)
               dr(2) = max(dr(2), rel_diff([f01, -f21], reshape(fd(:, 1:2), [4])))
            end if
         end do
      end do
      write (*, '(a, 4es9.2)') '    bodies: vs descriptor system, max rel diff qdd (chain, ' &
         //'two-link), reactions (chain, two-link) ', dq, dr
      call check(error, maxval(dq), 0.0_dp, 'general bodies qdd vs descriptor', abs=1e-10_dp)
      call check(error, maxval(dr), 0.0_dp, 'general bodies reactions vs descriptor', &
                 abs=1e-10_dp)
   end subroutine test_descriptor

   subroutine random_state(rng, n, y)
      type(rng_t), intent(inout) :: rng
      integer, intent(in) :: n
      real(dp), intent(out) :: y(2*n)
      integer :: i
      do i = 1, n
         y(i) = uniform(rng, -pi, pi)
         y(n + i) = uniform(rng, -4.0_dp, 4.0_dp)
      end do
   end subroutine random_state

   !> The default body is the uniform rod: the factory builds it without com and
   !> inertia (5 parameters, the name unchanged); its accelerations equal the general
   !> formulas at d = l/2, I = m l²/12 to 1e-13, and the horizontal release gives the
   !> closed form q̈ = (−9g/7, 3g/7) of docs/physics.md.
   subroutine test_rod_default(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(rng_t) :: rng
      type(pendulum_t) :: rod, gen
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      real(dp) :: q(2), w(2), d, a(2)
      integer :: k
      rod = pendulum_t()
      call check_true(error, rod%body == body_rod, 'the default body is the rod')
      spec = model_spec('pendulum')
      call new_model(spec, model, err)
      call check_true(error, .not. allocated(err), 'default model built')
      if (allocated(error)) return
      call check_true(error, model%n_parameters() == 5 .and. model%name() == &
                      'double pendulum', 'the default: 5 parameters, named double pendulum')
      call check_true(error, len(model%body_description()) == 0, 'no body text for rods')
      call spec%set('links', [3.0_dp])
      call spec%set('com', [1.0_dp, 1.0_dp, 1.0_dp])
      call spec%set('inertia', [0.0_dp, 0.0_dp, 0.0_dp])
      call new_model(spec, model, err)
      call check_true(error, .not. allocated(err), 'point-mass chain of 3 built')
      if (allocated(error)) return
      call check_true(error, index(model%body_description(), 'point masses') == 1 .and. &
                      index(model%name(), 'point masses') > 0, 'point masses named')
      d = 0.0_dp
      do k = 1, 300
         rod = pendulum_t(m1=uniform(rng, 0.2_dp, 5.0_dp), m2=uniform(rng, 0.2_dp, 5.0_dp), &
                          l1=uniform(rng, 0.2_dp, 3.0_dp), l2=uniform(rng, 0.2_dp, 3.0_dp), &
                          g=uniform(rng, 1.0_dp, 20.0_dp))
         gen = rod
         gen%body = body_general
         gen%d1 = 0.5_dp*rod%l1; gen%d2 = 0.5_dp*rod%l2
         gen%i1 = rod%m1*rod%l1**2/12.0_dp; gen%i2 = rod%m2*rod%l2**2/12.0_dp
         q = [uniform(rng, -pi, pi), uniform(rng, -pi, pi)]
         w = [uniform(rng, -4.0_dp, 4.0_dp), uniform(rng, -4.0_dp, 4.0_dp)]
         d = max(d, rel_diff(qddot(gen, q, w), qddot(rod, q, w)))
         d = max(d, abs(energy(gen, q, w) - energy(rod, q, w))/max(1.0_dp, &
                                                                  abs(energy(rod, q, w))))
      end do
      call check(error, d, 0.0_dp, 'rod vs general at rod values', abs=1e-13_dp)
      a = qddot(pendulum_t(), [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp])
      call check(error, a(1), -9.0_dp*9.8_dp/7.0_dp, 'horizontal release qdd1', abs=1e-13_dp)
      call check(error, a(2), 3.0_dp*9.8_dp/7.0_dp, 'horizontal release qdd2', abs=1e-13_dp)
   end subroutine test_rod_default

   !> gauss6 (symplectic) keeps the energy of a point-mass pendulum (a chaotic
   !> release) and of a general-body chain of 3 links (0.5 rad from hanging) over 10 s,
   !> h = 2.5 ms, within 1e-10 of the energy scale: no drift.
   subroutine test_energy(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      class(integrator_t), allocatable :: integ
      type(chain_t) :: chain
      class(model_t), allocatable :: model
      real(dp) :: y(6), t, h, e0, e1, de(2), q(3), w(3)
      integer :: stat, run, n
      do run = 1, 2
         if (run == 1) then
            n = 2
            allocate (model, source=pendulum_model(point_pendulum(1.0_dp, 0.7_dp, 1.0_dp, &
                                                                  0.8_dp, 9.8_dp)))
         else
            n = 3
            chain = chain_model([1.0_dp, 0.6_dp, 0.9_dp], [1.0_dp, 0.8_dp, 0.7_dp], 9.8_dp, &
                                err, com=[0.3_dp, 0.8_dp, 0.9_dp], &
                                inertia=[0.05_dp, 0.0_dp, 0.02_dp])
            allocate (model, source=chain)
         end if
         q = [-0.9_dp, -0.6_dp, -1.2_dp]
         if (n == 2) q(1:2) = [0.3_dp, 1.4_dp]
         w(1:n) = 0.0_dp
         e0 = model%energy(0.0_dp, [q(1:n), w(1:n)])
         call new_integrator('gauss6', integ, err)
         y(1:2*n) = integ%to_internal(model, q(1:n), w(1:n))
         t = 0.0_dp; h = 0.0025_dp
         call advance_fixed(integ, model, t, y(1:2*n), h, 4000_i8, stat)
         call check_true(error, stat == stat_ok, 'gauss6 run')
         call integ%to_physical(model, y(1:2*n), q(1:n), w(1:n))
         e1 = model%energy(t, [q(1:n), w(1:n)])
         de(run) = abs(e1 - e0)/model%energy_scale(e0)
         deallocate (model)
      end do
      write (*, '(a, 2es9.2)') '    bodies: gauss6 10 s relative energy error (point, ' &
         //'3 general links) ', de
      call check(error, maxval(de), 0.0_dp, 'gauss6 energy error', abs=1e-10_dp)
   end subroutine test_energy

   !> With the model's reactions each body of a general two-link pendulum balances:
   !> m1 a_C1 = F01 + F21 + G1, m2 a_C2 = −F21 + G2, and about the centres
   !> I1 q̈1 = (A − C1) × F01 + (B − C1) × F21, I2 q̈2 = (B − C2) × (−F21), to 1e-12 of
   !> the largest term.
   subroutine test_balance(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(pendulum_t) :: par
      type(kinematics_t) :: kin
      real(dp) :: m(2), l(2), d(2), ic(2), g, y(4), a(2), f01(2), f21(2), res(6), sc(6)
      integer :: k
      real(dp) :: worst
      worst = 0.0_dp
      do k = 1, 300
         call random_bodies(rng, 2, m, l, d, ic, g)
         par = pendulum_t(m1=m(1), m2=m(2), l1=l(1), l2=l(2), g=g)
         par%body = body_general
         par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
         call random_state(rng, 2, y)
         a = qddot(par, y(1:2), y(3:4))
         call reactions(par, y(1:2), y(3:4), a, f01, f21)
         kin = kinematics(par, y(1:2), y(3:4), a)
         res(1:2) = m(1)*kin%ac1 - (f01 + f21 + [0.0_dp, -m(1)*g])
         res(3:4) = m(2)*kin%ac2 - (-f21 + [0.0_dp, -m(2)*g])
         res(5) = ic(1)*a(1) - (cross(-kin%rc1, f01) + cross(kin%rb - kin%rc1, f21))
         res(6) = ic(2)*a(2) - cross(kin%rb - kin%rc2, -f21)
         sc(1:4) = max(maxval(abs(f01)), maxval(abs(f21)), maxval(m)*g, &
                       maxval(abs(m(1)*kin%ac1)), maxval(abs(m(2)*kin%ac2)))
         sc(5:6) = maxval(l)*(sc(1) + 1.0_dp) + maxval(ic*abs(a))
         worst = max(worst, maxval(abs(res)/sc))
         ! the model's rC is at d_i along the link
         worst = max(worst, abs(norm2(kin%rc1) - d(1))/l(1), &
                     abs(norm2(kin%rc2 - kin%rb) - d(2))/l(2))
      end do
      write (*, '(a, es9.2)') '    bodies: force and moment balance, max residual ', worst
      call check(error, worst, 0.0_dp, 'balance of each body', abs=1e-12_dp)
   contains
      pure real(dp) function cross(u, v)
         real(dp), intent(in) :: u(2), v(2)
         cross = u(1)*v(2) - u(2)*v(1)
      end function cross
   end subroutine test_balance

   !> The factory's two-link model and its 2-link chain (`general`) for a general
   !> body: the same field, energy, parameters and reactions (outputs) to 1e-13.
   subroutine test_two_link_chain(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(rng_t) :: rng
      type(model_spec_t) :: spec
      class(model_t), allocatable :: two, chain
      real(dp) :: y(4), f2(4), fc(4), o2(48), oc(48), d
      integer :: k
      character(len=:), allocatable :: n2, nc, u2, uc
      real(dp) :: v2, vc
      spec = model_spec('pendulum')
      call spec%set('m', [1.3_dp, 0.6_dp])
      call spec%set('l', [0.9_dp, 1.2_dp])
      call spec%set('com', [0.7_dp, 1.2_dp])
      call spec%set('inertia', [0.04_dp, 0.0_dp])
      call new_model(spec, two, err)
      call check_true(error, .not. allocated(err), 'two-link general body built')
      spec%general = .true.
      call new_model(spec, chain, err)
      call check_true(error, .not. allocated(err), '2-link chain general body built')
      if (allocated(error)) return
      call check_true(error, two%n_parameters() == 9 .and. chain%n_parameters() == 9, &
                      'm, l, g, com and inertia recorded (9 parameters)')
      do k = 1, two%n_parameters()
         call two%parameter(k, n2, v2, u2)
         call chain%parameter(k, nc, vc, uc)
         call check_true(error, n2 == nc .and. v2 == vc .and. u2 == uc, &
                         'parameter '//n2//' the same in both forms')
      end do
      call check_true(error, index(two%name(), 'general bodies') > 0, 'name says the body')
      ! the 'body' attribute and summary text: d_i, I_i with units, the same in both forms
      call check_true(error, two%body_description() == 'general bodies: com = 0.7, 1.2 m; ' &
                      //'inertia = 0.04, 0 kg m^2', 'body text: '//two%body_description())
      call check_true(error, chain%body_description() == two%body_description(), &
                      'body text of the chain: '//chain%body_description())
      d = 0.0_dp
      do k = 1, 200
         call random_state(rng, 2, y)
         call two%field(0.0_dp, y, f2)
         call chain%field(0.0_dp, y, fc)
         d = max(d, rel_diff(f2, fc))
         d = max(d, abs(two%energy(0.0_dp, y) - chain%energy(0.0_dp, y))/ &
                 max(1.0_dp, abs(chain%energy(0.0_dp, y))))
         call two%outputs(0.0_dp, y, f2, o2)
         call chain%outputs(0.0_dp, y, fc, oc)
         d = max(d, rel_diff(o2, oc))
      end do
      write (*, '(a, es9.2)') '    bodies: two-link vs 2-link chain, max rel diff ', d
      call check(error, d, 0.0_dp, 'two-link vs chain for a general body', abs=1e-13_dp)
   end subroutine test_two_link_chain

   !> The SIMD lanes with a point-mass pendulum's constants: accelerations against
   !> the scalar model to 1e-13, and a 2 s batch against single rk4 runs to 1e-10 rad.
   subroutine test_lanes(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(rng_t) :: rng
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(batch_options_t) :: opt
      type(batch_result_t) :: res
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, a1, a2, s1, c1, s2, c2
      real(dp) :: d, dt, y0(4, 5), y(4), t, h
      integer :: i, stat
      par = point_pendulum(1.2_dp, 0.8_dp, 0.9_dp, 1.1_dp, 9.81_dp)
      do i = 1, lane_width
         q1(i) = uniform(rng, -pi, pi); q2(i) = uniform(rng, -pi, pi)
         w1(i) = uniform(rng, -4.0_dp, 4.0_dp); w2(i) = uniform(rng, -4.0_dp, 4.0_dp)
      end do
      call accel_lanes(batch_coef(par), q1, q2, w1, w2, a1, a2, s1, c1, s2, c2)
      d = 0.0_dp
      do i = 1, lane_width
         d = max(d, rel_diff([a1(i), a2(i)], qddot(par, [q1(i), q2(i)], [w1(i), w2(i)])))
      end do
      call check(error, d, 0.0_dp, 'lane accelerations of a point-mass pendulum', &
                 abs=1e-13_dp)
      do i = 1, 5
         y0(:, i) = [-0.5_dp*pi + 0.2_dp*i, -0.5_dp*pi - 0.15_dp*i, 0.0_dp, 0.0_dp]
      end do
      opt%h = 1e-3_dp
      opt%n_steps = 2000
      opt%stop_rule = stop_end
      opt%skip_cannot_flip = .false.
      call integrate_batch(par, opt, y0, res)
      dt = 0.0_dp
      do i = 1, 5
         call new_integrator('rk4', integ, err)
         y = y0(:, i); t = 0.0_dp; h = 1e-3_dp
         call advance_fixed(integ, pendulum_model(par), t, y, h, 2000_i8, stat)
         dt = max(dt, maxval(abs(res%final(:, i) - y)))
      end do
      write (*, '(a, 2es9.2)') '    bodies: lanes of a point-mass pendulum: qdd rel diff, ' &
         //'2 s batch vs single rk4 ', d, dt
      call check(error, dt, 0.0_dp, 'point-mass batch vs single rk4 runs', abs=1e-10_dp)
   end subroutine test_lanes

   !> A damped chain of general bodies on a moving support: along the motion
   !> dE/dt = P_support − P_friction (module notes of dpend_chain), dE/dt from the
   !> energy's gradient in y times the field plus its partial derivative in t (central
   !> difference, step 1e-5 s), at 200 random states of 2- and 3-link chains, to 1e-6
   !> of the largest power.
   subroutine test_power(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(rng_t) :: rng
      type(chain_t) :: chain
      real(dp) :: m(3), l(3), d(3), ic(3), c(3), g, y(6), f(6), gr(6), t, dedt, pf, ps
      real(dp) :: worst
      real(dp), parameter :: dt = 1e-5_dp
      integer :: k, n, i
      worst = 0.0_dp
      do k = 1, 200
         n = 2 + mod(k, 2)
         call random_bodies(rng, n, m(1:n), l(1:n), d(1:n), ic(1:n), g)
         do i = 1, n
            c(i) = uniform(rng, 0.0_dp, 0.5_dp)
         end do
         chain = chain_model(m(1:n), l(1:n), g, err, c(1:n), [0.05_dp, 0.08_dp], 6.0_dp, &
                             [0.3_dp, -0.7_dp], d(1:n), ic(1:n))
         call check_true(error, .not. allocated(err), 'damped driven chain of bodies built')
         if (allocated(error)) return
         call random_state(rng, n, y(1:2*n))
         t = uniform(rng, 0.0_dp, 2.0_dp)
         call chain%field(t, y(1:2*n), f(1:2*n))
         call chain%energy_gradient(t, y(1:2*n), gr(1:2*n))
         dedt = dot_product(gr(1:2*n), f(1:2*n)) + (chain%energy(t + dt, y(1:2*n)) &
                                                    - chain%energy(t - dt, y(1:2*n)))/(2*dt)
         call chain%powers(t, y(1:2*n), f(n + 1:2*n), pf, ps)
         worst = max(worst, abs(dedt - (ps - pf))/max(abs(ps), abs(pf), 1.0_dp))
      end do
      write (*, '(a, es9.2)') '    bodies: damped driven chain, dE/dt vs P_support - ' &
         //'P_friction, max rel diff ', worst
      call check(error, worst, 0.0_dp, 'power balance of general bodies', abs=1e-6_dp)
   end subroutine test_power

   !> The two-link model of general bodies: its Jacobians of (q, q̇) and of the
   !> canonical (q, p) field and its energy gradient against central differences
   !> (step 1e-6), relative to the largest entry, at 100 random states: 1e-7.
   subroutine test_jacobians(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(pendulum_t) :: par
      type(double_pendulum_t) :: model
      real(dp) :: m(2), l(2), d(2), ic(2), g, y(4), yp(4), ym(4), fp(4), fm(4)
      real(dp) :: jac(4, 4), jfd(4, 4), cj(4, 4), cfd(4, 4), gr(4), gfd(4), worst
      real(dp), parameter :: h = 1e-6_dp
      integer :: k, j
      worst = 0.0_dp
      do k = 1, 100
         call random_bodies(rng, 2, m, l, d, ic, g)
         par = pendulum_t(m1=m(1), m2=m(2), l1=l(1), l2=l(2), g=g)
         par%body = body_general
         par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
         model = pendulum_model(par)
         call random_state(rng, 2, y)
         call model%jacobian(0.0_dp, y, jac)
         call model%canonical_jacobian(0.0_dp, y, cj)
         call model%energy_gradient(0.0_dp, y, gr)
         do j = 1, 4
            yp = y; ym = y
            yp(j) = y(j) + h; ym(j) = y(j) - h
            call model%field(0.0_dp, yp, fp)
            call model%field(0.0_dp, ym, fm)
            jfd(:, j) = (fp - fm)/(2*h)
            call model%canonical_field(0.0_dp, yp, fp)
            call model%canonical_field(0.0_dp, ym, fm)
            cfd(:, j) = (fp - fm)/(2*h)
            gfd(j) = (model%energy(0.0_dp, yp) - model%energy(0.0_dp, ym))/(2*h)
         end do
         worst = max(worst, maxval(abs(jac - jfd))/maxval(abs(jfd)), &
                     maxval(abs(cj - cfd))/maxval(abs(cfd)), maxval(abs(gr - gfd))/maxval(abs(gfd)))
      end do
      write (*, '(a, es9.2)') '    bodies: general Jacobians and energy gradient vs central ' &
         //'differences, max rel diff ', worst
      call check(error, worst, 0.0_dp, 'general Jacobians vs differences', abs=1e-7_dp)
   end subroutine test_jacobians

   !> Invalid bodies are refused with the field named: d < 0, I < 0, a link
   !> without inertia about its joint (d = 0, I = 0), a wrong count; valid point
   !> masses and d > l are accepted.
   subroutine test_refuse(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      call check_bodies([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], [-0.1_dp, 0.5_dp], &
                        [0.0_dp, 0.0_dp], err)
      call expect('invalid com1: -0.1 m is outside')
      call check_bodies([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], [0.5_dp, 0.5_dp], &
                        [0.0_dp, -1.0_dp], err)
      call expect('invalid inertia2: -1 kg m^2 is outside')
      call check_bodies([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], [0.5_dp, 0.0_dp], &
                        [0.0_dp, 0.0_dp], err)
      call expect('invalid com2, inertia2:')
      call check_bodies([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], [1.0_dp, 2.5_dp], &
                        [0.0_dp, 0.0_dp], err)
      call check_true(error, .not. allocated(err), 'point masses, d2 > l2 accepted')
      chain = chain_model([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], 9.8_dp, err, &
                          com=[0.5_dp], inertia=[0.1_dp, 0.1_dp])
      call expect('invalid com: 1 values for 2 links')
      chain = chain_model([1.0_dp, 1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp, 1.0_dp], 9.8_dp, err, &
                          com=[0.5_dp, 0.0_dp, 1.0_dp], inertia=[0.1_dp, 0.0_dp, 0.0_dp])
      call expect('invalid com2, inertia2:')
   contains
      subroutine expect(start)
         character(len=*), intent(in) :: start
         call check_true(error, allocated(err), 'refused: '//start)
         if (allocated(error)) return
         call check_true(error, index(err%message, start) == 1, 'message starts '''//start// &
                         ''': '//err%message)
         deallocate (err)
      end subroutine expect
   end subroutine test_refuse
   !> The Poincaré section q1 = −π/2 (mod 2π) crossed with q̇1 > 0 of the models that
   !> `dpend poincare` builds (the factory, 2 links): `section_orbit` with dop853 at
   !> rtol 1e-12, 8 points, against crossings located here: a classical RK4 at
   !> h = 2.5e-4 s on the textbook point-mass equations (case 1) or on the descriptor
   !> system (case 2: d = (0.55, 0.8) m, I = (0.05, 0.02) kg m²), each crossing found
   !> inside its step by the secant method on the RK4 step's length. The other link's
   !> angle q2 and the crossing times agree to 1e-9 (measured: 4e-13 rad, 5e-12 s); the
   !> momentum p2 = (m2 d2² + I2) q̇2 + m2 l1 d2 cos(q1 − q2) q̇1 to 1e-9 relative.
   subroutine test_poincare(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      real(dp), parameter :: m(2) = [1.3_dp, 0.6_dp], l(2) = [0.9_dp, 1.2_dp], g = 9.8_dp
      real(dp), parameter :: h = 2.5e-4_dp
      integer, parameter :: points = 8
      real(dp) :: d(2), ic(2), th0(2), y(4), yp(4), yc(4), t, tc, worst(3)
      real(dp) :: qx(points), px(points), tx(points)
      real(dp), allocatable :: qo(:), po(:), ts(:), e(:)
      type(model_spec_t) :: spec
      type(angle_crossing_t) :: section
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      integer :: c, k, stat
      character(len=*), parameter :: what(2) = [character(len=13) :: 'point masses', &
                                                 'general body']
      section = angle_crossing_t(index=1, angle=-0.5_dp*pi, wrap=.true.)
      section%direction = 1
      do c = 1, 2
         if (c == 1) then
            d = l; ic = 0.0_dp; th0 = [0.4_dp, -0.3_dp]
         else
            d = [0.55_dp, 0.8_dp]; ic = [0.05_dp, 0.02_dp]; th0 = [0.5_dp, -0.4_dp]
         end if
         spec = model_spec('pendulum')
         call spec%set('m', m)
         call spec%set('l', l)
         call spec%set('g', [g])
         call spec%set('com', d)
         call spec%set('inertia', ic)
         call new_model(spec, model, err)
         call check_true(error, .not. allocated(err), what(c)//': model built')
         if (allocated(error)) return
         call new_integrator('dop853', integ, err, method_options_t(rtol=1e-12_dp, &
                             atol=1e-14_dp))
         call section_orbit(integ, model, section, th0 - 0.5_dp*pi, [0.0_dp, 0.0_dp], &
                            30.0_dp, 1e-3_dp, points, qo, po, ts, e, stat)
         call check_true(error, stat == stat_ok .and. size(qo) == points, what(c)// &
                         ': '//'8 section points')
         if (allocated(error)) return
         ! the crossings of the independent integration
         y = [th0 - 0.5_dp*pi, 0.0_dp, 0.0_dp]
         t = 0.0_dp
         k = 0
         do while (k < points .and. t < 30.0_dp)
            yp = y
            y = rk4_step(yp, h)
            t = t + h
            if (sin(yp(1) + 0.5_dp*pi) < 0.0_dp .and. sin(y(1) + 0.5_dp*pi) >= 0.0_dp .and. &
                cos(y(1) + 0.5_dp*pi) > 0.0_dp .and. y(3) > 0.0_dp) then
               call locate(yp, tc, yc)
               k = k + 1
               qx(k) = yc(2) - 2.0_dp*pi*anint(yc(2)/(2.0_dp*pi))
               px(k) = (m(2)*d(2)**2 + ic(2))*yc(4) + m(2)*l(1)*d(2)*cos(yc(1) - yc(2))*yc(3)
               tx(k) = t - h + tc
            end if
         end do
         call check_true(error, k == points, what(c)//': 8 crossings found here')
         if (allocated(error)) return
         worst = [maxval(abs(qo - qx)), maxval(abs(ts - tx)), &
                  maxval(abs(po - px))/maxval(abs(px))]
         write (*, '(a, 3es9.2)') '    bodies: Poincare section of '//trim(what(c))// &
            ' vs independent RK4, max diff of q2, t, p2 (rel) ', worst
         call check(error, qo, qx, what(c)//': section q2', abs=1e-9_dp)
         if (allocated(error)) return
         call check(error, ts, tx, what(c)//': crossing times', abs=1e-9_dp)
         if (allocated(error)) return
         call check(error, po, px, what(c)//': section p2', abs=1e-9_dp*maxval(abs(px)))
         if (allocated(error)) return
      end do
   contains
      !> q̈ of the independent formulation: the textbook (θ = q + π/2) or the
      !> descriptor system.
      function accel(x) result(f)
         real(dp), intent(in) :: x(4)
         real(dp) :: f(4), qdd(2), fr(2, 2), tb(4)
         if (c == 1) then
            tb = textbook(m(1), m(2), l(1), l(2), g, [x(1) + 0.5_dp*pi, x(3), &
                                                      x(2) + 0.5_dp*pi, x(4)])
            qdd = tb([2, 4])
         else
            call descriptor(2, m, l, d, ic, g, x, qdd, fr)
         end if
         f = [x(3:4), qdd]
      end function accel
      !> One classical RK4 step of length dt.
      function rk4_step(x, dt) result(xn)
         real(dp), intent(in) :: x(4), dt
         real(dp) :: xn(4), k1(4), k2(4), k3(4), k4(4)
         k1 = accel(x)
         k2 = accel(x + 0.5_dp*dt*k1)
         k3 = accel(x + 0.5_dp*dt*k2)
         k4 = accel(x + dt*k3)
         xn = x + dt/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
      end function rk4_step
      !> The step length tau in (0, h] whose RK4 step from x lands on the section
      !> (secant iterations on sin(q1 + π/2), bracketed), and that state.
      subroutine locate(x, tau, xc)
         real(dp), intent(in) :: x(4)
         real(dp), intent(out) :: tau, xc(4)
         real(dp) :: a, b, ga, gb, gm
         integer :: it
         a = 0.0_dp; b = h
         ga = sin(x(1) + 0.5_dp*pi)
         xc = rk4_step(x, b)
         gb = sin(xc(1) + 0.5_dp*pi)
         tau = b
         do it = 1, 60
            tau = b - gb*(b - a)/(gb - ga)
            tau = min(max(tau, a), b)
            xc = rk4_step(x, tau)
            gm = sin(xc(1) + 0.5_dp*pi)
            if (abs(gm) < 1e-15_dp) exit
            if (sign(1.0_dp, gm) == sign(1.0_dp, ga)) then
               a = tau; ga = gm
            else
               b = tau; gb = gm
            end if
         end do
      end subroutine locate
   end subroutine test_poincare
end module test_bodies
