!> The chain of N uniform rods (dpend_chain) against independently known
!> values:
!> - N = 2 against the double pendulum (its own formulas, Cramer's rule);
!> - N = 1 against the compound pendulum's closed forms (pin reaction, period);
!> - N = 3, 5 against the descriptor system of the free-body diagrams (3N unknowns q̈
!>   and the reactions, solved at once by LAPACK dgesv), Lagrange's equations from the
!>   links' energies, the balance of every link, and
!>   the small-oscillation frequencies of K v = ω² M v (LAPACK dsygv) measured on
!>   simulated small oscillations;
!> - the analytic Jacobians and energy gradient against central differences;
!> - gauss6 keeps the energy of N = 3 and N = 5 bounded;
!> - the measured order of every method of the registry on N = 3.
!> Each test prints its measured figures on one line ('    chain: …').
module test_chain
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t, max_dof
   use dpend_chain, only: chain_t, chain_model
   use dpend_link_layout, only: n_link_out
   use dpend_pendulum, only: pendulum_t, double_pendulum_t, pendulum_model, reactions
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods
   use dpend_propagate, only: advance_to
   use dpend_events, only: event_t, angle_crossing_t, crossing_t, find_crossings
   use dpend_lapack, only: dgesv, dsygv
   use dpend_cli, only: real_str, to_str
   use test_integrators, only: slope
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_chain, measured_period, rel_diff

   real(dp), parameter :: pi = acos(-1.0_dp)

   !> Park–Miller minimal standard generator (exact in real(dp)), fixed seed.
   type :: rng_t
      real(dp) :: s = 20261123.0_dp
   end type rng_t

   !> Crossing of a modal coordinate η = wᵀ (q − q_eq) through zero.
   type, extends(event_t) :: mode_event_t
      integer :: n = 0
      real(dp) :: w(max_dof) = 0.0_dp
   contains
      procedure :: value => mode_value
   end type mode_event_t

contains

   subroutine collect_chain(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('refuses_bad_parameters', test_refuse), &
               new_unittest('n2_equals_double_pendulum', test_n2), &
               new_unittest('n1_pin_reaction_closed_form', test_n1_reaction), &
               new_unittest('n1_small_oscillation_period', test_n1_period), &
               new_unittest('n3_n5_descriptor_lagrange_balance', test_descriptor), &
               new_unittest('n3_n5_small_oscillation_frequencies', test_modes), &
               new_unittest('jacobians_finite_differences', test_jacobians), &
               new_unittest('n3_n5_gauss6_energy_bounded', test_energy), &
               new_unittest('n3_order_every_method', test_orders), &
               new_unittest('gauss6_tiny_oscillations', test_tiny)]
   end subroutine collect_chain

   !> Uniform number in [a, b).
   real(dp) function uniform(rng, a, b)
      type(rng_t), intent(inout) :: rng
      real(dp), intent(in) :: a, b
      rng%s = mod(16807.0_dp*rng%s, 2147483647.0_dp)
      uniform = a + (b - a)*rng%s/2147483647.0_dp
   end function uniform

   !> A random chain of n links: m in [0.2, 5] kg, l in [0.2, 3] m, g in [1, 20].
   subroutine random_chain(rng, n, model)
      type(rng_t), intent(inout) :: rng
      integer, intent(in) :: n
      type(chain_t), intent(out) :: model
      type(error_t), allocatable :: error
      real(dp) :: m(n), l(n), g
      integer :: i
      do i = 1, n
         m(i) = uniform(rng, 0.2_dp, 5.0_dp)
         l(i) = uniform(rng, 0.2_dp, 3.0_dp)
      end do
      g = uniform(rng, 1.0_dp, 20.0_dp)
      model = chain_model(m, l, g, error)
      if (allocated(error)) error stop 'random_chain: '//error%message
   end subroutine random_chain

   !> A random state: q in [−π, π], q̇ in [−5, 5].
   subroutine random_state(rng, n, y)
      type(rng_t), intent(inout) :: rng
      integer, intent(in) :: n
      real(dp), intent(out) :: y(2*n)
      integer :: i
      do i = 1, n
         y(i) = uniform(rng, -pi, pi)
         y(n + i) = uniform(rng, -5.0_dp, 5.0_dp)
      end do
   end subroutine random_state

   !> ‖a − b‖∞ / ‖b‖∞.
   pure real(dp) function rel_diff(a, b)
      real(dp), intent(in) :: a(:), b(:)
      rel_diff = maxval(abs(a - b))/max(maxval(abs(b)), tiny(1.0_dp))
   end function rel_diff

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    chain: '//text
   end subroutine report

   pure real(dp) function mode_value(self, model, t, q, qd)
      class(mode_event_t), intent(in) :: self
      class(model_t), intent(in) :: model
      real(dp), intent(in) :: t, q(:), qd(:)
      mode_value = dot_product(self%w(1:self%n), q(1:self%n) + 0.5_dp*pi)
   end function mode_value

   subroutine test_refuse(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: model
      model = chain_model([1.0_dp, 1.0_dp, 0.0_dp], [1.0_dp, 1.0_dp, 1.0_dp], 9.8_dp, err)
      call check_true(error, allocated(err), 'm3 = 0 accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'invalid m3: 0') == 1, err%message)
      if (allocated(error)) return
      model = chain_model([1.0_dp], [1.0_dp], -1.0_dp, err)
      call check_true(error, allocated(err), 'g = -1 accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'invalid g: -1') == 1, err%message)
      if (allocated(error)) return
      model = chain_model([1.0_dp, 2.0_dp], [1.0_dp], 9.8_dp, err)
      call check_true(error, allocated(err), 'l of the wrong size accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'invalid l: 1 lengths for 2 links') == 1, &
                      err%message)
      if (allocated(error)) return
      model = chain_model([real(dp) ::], [real(dp) ::], 9.8_dp, err)
      call check_true(error, allocated(err), 'no links accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'invalid links: 0 is outside [1, ') == 1, &
                      err%message)
      if (allocated(error)) return
      model = chain_model([1.0_dp], [1.0_dp], 0.0_dp, err)   ! the range table: g >= 1e-6
      call check_true(error, allocated(err), 'g = 0 accepted')
      if (allocated(error)) return
      model = chain_model([1.0_dp], [1.0_dp], 9.8_dp, err)
      call check_true(error, .not. allocated(err), 'g = 9.8 refused')
      if (allocated(error)) return
      call check_true(error, model%n_parameters() == 3 .and. model%n_outputs() == n_link_out, &
                      'parameter or output count')
   end subroutine test_refuse

   !> N = 2 against the double pendulum at 1000 random states and parameters: q̈, the
   !> reactions (F01, −F21), energy, momenta, the canonical field to 1e-13 relative.
   subroutine test_n2(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(chain_t) :: chain
      type(double_pendulum_t) :: pend
      type(pendulum_t) :: par
      real(dp) :: y(4), fc(4), fp(4), pc(2), pp(2), z(4), gc(4), gp(4), fj(2, 2)
      real(dp) :: f01(2), f21(2), d(9), out(48), outp(48), jc(4, 4), jp(4, 4)
      type(error_t), allocatable :: err
      integer :: k
      d = 0.0_dp
      do k = 1, 1000
         par%m1 = uniform(rng, 0.2_dp, 5.0_dp); par%m2 = uniform(rng, 0.2_dp, 5.0_dp)
         par%l1 = uniform(rng, 0.2_dp, 3.0_dp); par%l2 = uniform(rng, 0.2_dp, 3.0_dp)
         par%g = uniform(rng, 1.0_dp, 20.0_dp)
         pend = pendulum_model(par)
         chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err)
         if (allocated(err)) error stop err%message
         call random_state(rng, 2, y)
         call chain%field(0.0_dp, y, fc)
         call pend%field(0.0_dp, y, fp)
         d(1) = max(d(1), rel_diff(fc(3:4), fp(3:4)))
         call reactions(par, y(1:2), y(3:4), fp(3:4), f01, f21)
         call chain%reactions(y(1:2), y(3:4), fc(3:4), fj)
         d(2) = max(d(2), rel_diff([fj(:, 1), fj(:, 2)], [f01, -f21]))
         call chain%outputs(0.0_dp, y, fc, out)
         d(2) = max(d(2), rel_diff(out(1:4), [f01, -f21]))
         call pend%outputs(0.0_dp, y, fp, outp)   ! one layout: every dataset alike
         d(9) = max(d(9), rel_diff(out, outp))
         d(3) = max(d(3), rel_diff([chain%energy(0.0_dp, y)], [pend%energy(0.0_dp, y)]))
         call chain%momenta(0.0_dp, y, pc)
         call pend%momenta(0.0_dp, y, pp)
         d(4) = max(d(4), rel_diff(pc, pp))
         z = [y(1:2), pp]
         call chain%canonical_field(0.0_dp, z, gc)
         call pend%canonical_field(0.0_dp, z, gp)
         d(5) = max(d(5), rel_diff(gc, gp))
         d(6) = max(d(6), rel_diff([chain%hamiltonian_value(0.0_dp, z)], &
                                   [pend%hamiltonian_value(0.0_dp, z)]))
         call chain%jacobian(0.0_dp, y, jc)
         call pend%jacobian(0.0_dp, y, jp)
         d(7) = max(d(7), rel_diff(reshape(jc, [16]), reshape(jp, [16])))
         call chain%canonical_jacobian(0.0_dp, z, jc)
         call pend%canonical_jacobian(0.0_dp, z, jp)
         d(7) = max(d(7), rel_diff(reshape(jc, [16]), reshape(jp, [16])))
         call chain%energy_gradient(0.0_dp, y, gc)
         call pend%energy_gradient(0.0_dp, y, gp)
         d(8) = max(d(8), rel_diff(gc, gp))
      end do
      call sections(error)
      if (allocated(error)) return
      call report('N=2 vs double pendulum, max rel diff: qdd '//real_str(d(1), 2)// &
                  ', reactions '//real_str(d(2), 2)//', energy '//real_str(d(3), 2)// &
                  ', momenta '//real_str(d(4), 2)//', canonical field '//real_str(d(5), 2)// &
                  ', H '//real_str(d(6), 2)//', jacobians '//real_str(d(7), 2)// &
                  ', energy gradient '//real_str(d(8), 2)//', outputs '//real_str(d(9), 2))
      call check(error, maxval(d), 0.0_dp, 'N=2 vs double pendulum, max rel diff', &
                 abs=1e-13_dp)
      if (allocated(error)) return
      call same_layout(chain, pend, error)
      if (allocated(error)) return
      call same_trajectories(error)
   end subroutine test_n2

   !> One double pendulum: the two-link chain and the double pendulum's own
   !> formulation describe the same outputs (names, units, shapes, texts).
   subroutine same_layout(chain, pend, error)
      type(chain_t), intent(in) :: chain
      type(double_pendulum_t), intent(in) :: pend
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: n1, u1, t1, n2, u2, t2
      integer :: i, c1, c2, r1, r2
      call check_true(error, chain%n_outputs() == pend%n_outputs(), 'output counts')
      if (allocated(error)) return
      do i = 1, chain%n_outputs()
         call chain%output_info(i, n1, c1, u1, t1, r1)
         call pend%output_info(i, n2, c2, u2, t2, r2)
         call check_true(error, n1 == n2 .and. u1 == u2 .and. t1 == t2 .and. c1 == c2 &
                         .and. r1 == r2, 'output '//n1//' vs '//n2)
         if (allocated(error)) return
      end do
   end subroutine same_layout

   !> rk4, dop853 and gauss6 carry the two-link chain and the double pendulum along the
   !> same trajectory (1 s from q = (0.3, 1.2) at rest; the integrators' four-component
   !> paths): the states agree to 1e-10 (rounding of the fields ~1e-15, amplified by
   !> the divergence of nearby trajectories).
   subroutine same_trajectories(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      character(len=6), parameter :: names(3) = ['rk4   ', 'dop853', 'gauss6']
      type(chain_t) :: chain
      type(double_pendulum_t) :: pend
      class(integrator_t), allocatable :: integ
      real(dp) :: yc(4), yp(4), t, h, qc(2), wc(2), qp(2), wp(2), d
      integer :: i, stat
      chain = chain_model([1.0_dp, 0.6_dp], [1.0_dp, 0.8_dp], 9.81_dp, err)
      pend = pendulum_model(pendulum_t(m1=1.0_dp, m2=0.6_dp, l1=1.0_dp, l2=0.8_dp, g=9.81_dp))
      d = 0.0_dp
      do i = 1, 3
         call new_integrator(trim(names(i)), integ, err)
         yc = integ%to_internal(chain, [0.3_dp, 1.2_dp], [0.0_dp, 0.0_dp])
         t = 0.0_dp; h = 1e-3_dp
         call advance_to(integ, chain, t, yc, 1.0_dp, h, stat)
         call check_true(error, stat == stat_ok, trim(names(i))//' failed on the chain')
         if (allocated(error)) return
         call integ%to_physical(chain, yc, qc, wc)
         call new_integrator(trim(names(i)), integ, err)
         yp = integ%to_internal(pend, [0.3_dp, 1.2_dp], [0.0_dp, 0.0_dp])
         t = 0.0_dp; h = 1e-3_dp
         call advance_to(integ, pend, t, yp, 1.0_dp, h, stat)
         call integ%to_physical(pend, yp, qp, wp)
         d = max(d, rel_diff([qc, wc], [qp, wp]))
      end do
      call report('N=2 trajectories (rk4, dop853, gauss6; 1 s) vs double pendulum: '// &
                  'max rel diff '//real_str(d, 2))
      call check(error, d, 0.0_dp, 'N=2 trajectories vs double pendulum', abs=1e-10_dp)
   end subroutine same_trajectories

   !> N = 2 has energy-shell sections (N = 3 not): the states on the section have the
   !> requested energy (the chain's own `energy`) to 1e-12 of T + Σ G_i.
   subroutine sections(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(chain_t) :: chain
      real(dp) :: e, q(2), qd(2), pmax, d
      logical :: found
      integer :: k, link, n_found
      call random_chain(rng, 3, chain)
      call check_true(error, .not. chain%energy_sections(), 'N=3 claims energy sections')
      if (allocated(error)) return
      d = 0.0_dp; n_found = 0
      do k = 1, 200
         call random_chain(rng, 2, chain)
         call check_true(error, chain%energy_sections(), 'N=2 has no energy sections')
         if (allocated(error)) return
         link = 1 + mod(k, 2)
         e = uniform(rng, -0.5_dp, 2.0_dp)*sum(chain%gl)
         pmax = chain%section_p_max(e, link, -0.5_dp*pi)
         call chain%section_state(e, link, -0.5_dp*pi, 1, uniform(rng, -pi, pi), &
                                  uniform(rng, -1.0_dp, 1.0_dp)*pmax, q, qd, found)
         if (.not. found) cycle
         n_found = n_found + 1
         d = max(d, abs(chain%energy(0.0_dp, [q, qd]) - e) &
                 /(chain%energy(0.0_dp, [q, qd]) - chain%potential(q) + sum(chain%gl)))
      end do
      call report('N=2 sections: '//to_str(n_found)//' states on the shell, max rel '// &
                  'energy error '//real_str(d, 2))
      call check_true(error, n_found > 20, 'too few section states: '//to_str(n_found))
      call check(error, d, 0.0_dp, 'N=2 section state energy', abs=1e-12_dp)
   end subroutine sections

   !> N = 1: q̈ = −(3g/(2L)) cos q and F01 = m (a_C + g ĵ), a_C = (L/2)(q̈ n − q̇² u).
   subroutine test_n1_reaction(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(chain_t) :: chain
      real(dp) :: y(2), f(2), fj(2, 1), alpha, w, q, mass, len, fx, fy, d(2)
      integer :: k
      d = 0.0_dp
      do k = 1, 1000
         call random_chain(rng, 1, chain)
         call random_state(rng, 1, y)
         q = y(1); w = y(2); mass = chain%m(1); len = chain%l(1)
         call chain%field(0.0_dp, y, f)
         call chain%reactions(y(1:1), y(2:2), f(2:2), fj)
         alpha = -1.5_dp*chain%g/len*cos(q)
         fx = mass*0.5_dp*len*(-alpha*sin(q) - w**2*cos(q))
         fy = mass*(0.5_dp*len*(alpha*cos(q) - w**2*sin(q)) + chain%g)
         d(1) = max(d(1), rel_diff(f(2:2), [alpha]))
         d(2) = max(d(2), rel_diff(fj(:, 1), [fx, fy]))
      end do
      call report('N=1 closed form, max rel diff: qdd '//real_str(d(1), 2)// &
                  ', pin reaction '//real_str(d(2), 2))
      call check(error, maxval(d), 0.0_dp, 'N=1 closed form, max rel diff', abs=1e-13_dp)
   end subroutine test_n1_reaction

   !> Period of `event` crossings (rising) from ~n_periods periods of `method` with the
   !> step period/steps_per, starting from (q, q̇).
   real(dp) function measured_period(method, model, event, q, qd, period, n_periods, &
                                     steps_per) result(tp)
      character(len=*), intent(in) :: method
      class(model_t), intent(in) :: model
      class(event_t), intent(in) :: event
      real(dp), intent(in) :: q(:), qd(:), period
      integer, intent(in) :: n_periods, steps_per
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(crossing_t), allocatable :: hits(:)
      real(dp) :: t, y(2*size(q)), h
      integer :: stat, nh
      call new_integrator(method, integ, err)
      if (allocated(err)) error stop err%message
      y = integ%to_internal(model, q, qd)
      t = 0.0_dp; h = period/real(steps_per, dp)
      call find_crossings(event, integ, model, t, y, (real(n_periods, dp) + 0.6_dp)*period, &
                          h, hits, stat)
      nh = size(hits)
      tp = -1.0_dp
      if (stat == stat_ok .and. nh >= 2) tp = (hits(nh)%t - hits(1)%t)/real(nh - 1, dp)
   end function measured_period

   !> N = 1: period 2π √(2L/(3g)) of small oscillations (amplitude 1e-5 rad: the
   !> amplitude correction θ0²/16 is 6e-12) to 1e-9, by event location with gauss6.
   subroutine test_n1_period(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      type(angle_crossing_t) :: event
      real(dp) :: t0, tp
      chain = chain_model([0.7_dp], [1.3_dp], 9.81_dp, err)
      t0 = 2.0_dp*pi*sqrt(2.0_dp*1.3_dp/(3.0_dp*9.81_dp))
      event = angle_crossing_t(index=1, angle=-0.5_dp*pi, direction=1)
      tp = measured_period('gauss6', chain, event, [-0.5_dp*pi + 1e-5_dp], [0.0_dp], t0, 10, 200)
      call report('N=1 period '//real_str(tp, 15)//' s, closed form '//real_str(t0, 15)// &
                  ' s, rel diff '//real_str(abs(tp/t0 - 1.0_dp), 2))
      call check(error, tp, t0, 'N=1 small-oscillation period', rel=1e-9_dp)
   end subroutine test_n1_period

   !> Solve the free-body diagrams of all links at once: unknowns q̈ (n) and the
   !> reactions F_(i−1,i) (2n); per link m_i a_Ci = F_(i−1,i) − F_(i,i+1) + G_i and
   !> I_Ci q̈_i = −(L_i/2) u_i × (F_(i−1,i) + F_(i,i+1)). dgesv, LU with pivoting.
   subroutine descriptor(chain, y, qdd, f)
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: y(:)
      real(dp), intent(out) :: qdd(:), f(:, :)
      real(dp) :: a(3*chain%n, 3*chain%n), b(3*chain%n), c(chain%n), s(chain%n), cij, h
      integer :: n, i, j, r, ipiv(3*chain%n), info, fi, fn
      n = chain%n
      c = cos(y(1:n)); s = sin(y(1:n))
      a = 0.0_dp; b = 0.0_dp
      do i = 1, n
         r = 3*(i - 1)
         fi = n + 2*(i - 1)          ! F_(i−1,i) at fi+1, fi+2
         fn = n + 2*i                ! F_(i,i+1)
         h = 0.5_dp*chain%l(i)
         do j = 1, i
            cij = merge(h, chain%l(j), j == i)   ! a_Ci = Σ cij (q̈_j n_j − q̇_j² u_j)
            a(r + 1, j) = -chain%m(i)*cij*s(j)
            a(r + 2, j) = chain%m(i)*cij*c(j)
            b(r + 1) = b(r + 1) + chain%m(i)*cij*y(n + j)**2*c(j)
            b(r + 2) = b(r + 2) + chain%m(i)*cij*y(n + j)**2*s(j)
         end do
         b(r + 2) = b(r + 2) - chain%m(i)*chain%g
         a(r + 1, fi + 1) = -1.0_dp
         a(r + 2, fi + 2) = -1.0_dp
         a(r + 3, i) = chain%m(i)*chain%l(i)**2/12.0_dp
         a(r + 3, fi + 1) = -h*s(i)
         a(r + 3, fi + 2) = h*c(i)
         if (i < n) then
            a(r + 1, fn + 1) = 1.0_dp
            a(r + 2, fn + 2) = 1.0_dp
            a(r + 3, fn + 1) = -h*s(i)
            a(r + 3, fn + 2) = h*c(i)
         end if
      end do
      call dgesv(3*n, 1, a, 3*n, ipiv, b, 3*n, info)
      if (info /= 0) error stop 'descriptor: dgesv failed'
      qdd = b(1:n)
      f = reshape(b(n + 1:3*n), [2, n])
   end subroutine descriptor

   !> q̈ from Lagrange's equations M q̈ + Σ_jl Γ_ijl q̇_j q̇_l = −∂V/∂q_i, written from the
   !> energies of the links: v_Ck = Σ_j c_kj q̇_j n_j (c_kj = L_j for j < k, L_k/2 for
   !> j = k), T = Σ_k ½ m_k |v_Ck|² + ½ I_Ck q̇_k², so M_ij = Σ_k m_k c_ki c_kj n_i·n_j
   !> + δ_ij I_Ci, ∂M_ij/∂q_l = −Σ_k m_k c_ki c_kj (δ_il u_i·n_j + δ_jl n_i·u_j), Γ the
   !> Christoffel symbols of the first kind; V = Σ_k m_k g y_Ck. Solved by dgesv.
   subroutine lagrange(chain, y, qdd)
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: y(:)
      real(dp), intent(out) :: qdd(:)
      real(dp) :: u(2, chain%n), nv(2, chain%n), cc(chain%n, chain%n)
      real(dp) :: mm(chain%n, chain%n), dm(chain%n, chain%n, chain%n), b(chain%n)
      integer :: n, i, j, k, l, ipiv(chain%n), info
      n = chain%n
      cc = 0.0_dp
      do k = 1, n
         u(:, k) = [cos(y(k)), sin(y(k))]
         nv(:, k) = [-sin(y(k)), cos(y(k))]
         do j = 1, k - 1
            cc(k, j) = chain%l(j)
         end do
         cc(k, k) = 0.5_dp*chain%l(k)
      end do
      mm = 0.0_dp; dm = 0.0_dp
      do i = 1, n
         mm(i, i) = chain%m(i)*chain%l(i)**2/12.0_dp
         do j = 1, n
            do k = 1, n
               mm(i, j) = mm(i, j) + chain%m(k)*cc(k, i)*cc(k, j)*dot_product(nv(:, i), nv(:, j))
               dm(i, j, i) = dm(i, j, i) &
                             - chain%m(k)*cc(k, i)*cc(k, j)*dot_product(u(:, i), nv(:, j))
               dm(i, j, j) = dm(i, j, j) &
                             - chain%m(k)*cc(k, i)*cc(k, j)*dot_product(nv(:, i), u(:, j))
            end do
         end do
      end do
      do i = 1, n
         b(i) = 0.0_dp
         do k = 1, n
            b(i) = b(i) - chain%m(k)*chain%g*cc(k, i)*u(1, i)
         end do
         do j = 1, n
            do l = 1, n
               b(i) = b(i) - 0.5_dp*(dm(i, j, l) + dm(i, l, j) - dm(j, l, i))*y(n + j)*y(n + l)
            end do
         end do
      end do
      call dgesv(n, 1, mm, n, ipiv, b, n, info)
      if (info /= 0) error stop 'lagrange: dgesv failed'
      qdd = b
   end subroutine lagrange

   !> N = 3, 5: q̈ and the reactions of the model equal those of the descriptor system
   !> to 1e-12, q̈ that of Lagrange's equations to 1e-12; with the model's reactions
   !> every link's force and moment balance holds to 1e-12 of the largest term.
   subroutine test_descriptor(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(chain_t) :: chain
      real(dp) :: y(10), fy(10), qdd(5), fd(2, 5), fm(2, 5), d(5)
      real(dp) :: rc(2, 5), vc(2, 5), ac(2, 5), rj(2, 5), vj(2, 5), aj(2, 5), nxt(2), u(2)
      real(dp) :: res(3), scale(3), h
      integer :: k, n, i, nn
      integer, parameter :: ns(2) = [3, 5]
      d = 0.0_dp
      do nn = 1, 2
         n = ns(nn)
         do k = 1, 500
            call random_chain(rng, n, chain)
            call random_state(rng, n, y(1:2*n))
            call chain%field(0.0_dp, y(1:2*n), fy(1:2*n))
            call descriptor(chain, y(1:2*n), qdd(1:n), fd(:, 1:n))
            d(1) = max(d(1), rel_diff(fy(n + 1:2*n), qdd(1:n)))
            call lagrange(chain, y(1:2*n), qdd(1:n))
            d(5) = max(d(5), rel_diff(fy(n + 1:2*n), qdd(1:n)))
            call chain%reactions(y(1:n), y(n + 1:2*n), fy(n + 1:2*n), fm(:, 1:n))
            d(2) = max(d(2), rel_diff(reshape(fm(:, 1:n), [2*n]), reshape(fd(:, 1:n), [2*n])))
            call chain%kinematics(y(1:n), y(n + 1:2*n), fy(n + 1:2*n), rc(:, 1:n), &
                                  vc(:, 1:n), ac(:, 1:n), rj(:, 1:n), vj(:, 1:n), aj(:, 1:n))
            do i = 1, n
               nxt = 0.0_dp
               if (i < n) nxt = fm(:, i + 1)
               u = [cos(y(i)), sin(y(i))]
               h = 0.5_dp*chain%l(i)
               res(1:2) = chain%m(i)*ac(:, i) - (fm(:, i) - nxt + [0.0_dp, -chain%m(i)*chain%g])
               res(3) = chain%m(i)*chain%l(i)**2/12.0_dp*fy(n + i) &
                        + h*(u(1)*(fm(2, i) + nxt(2)) - u(2)*(fm(1, i) + nxt(1)))
               scale(1:2) = max(maxval(abs(chain%m(i)*ac(:, i))), maxval(abs(fm(:, i))), &
                                maxval(abs(nxt)), chain%m(i)*chain%g)
               scale(3) = max(abs(chain%m(i)*chain%l(i)**2/12.0_dp*fy(n + i)), &
                              h*maxval(abs(fm(:, i))), h*maxval(abs(nxt)))
               d(3) = max(d(3), maxval(abs(res(1:2))/scale(1:2)))
               d(4) = max(d(4), abs(res(3))/scale(3))
            end do
            ! the outputs hold the same reactions and kinematics
            block
               real(dp) :: out(72)
               call chain%outputs(0.0_dp, y(1:2*n), fy(1:2*n), out(1:14*n + 2))
               if (rel_diff(out(1:2*n), reshape(fm(:, 1:n), [2*n])) > 0.0_dp .or. &
                   rel_diff(out(6*n + 1:8*n), reshape(ac(:, 1:n), [2*n])) > 0.0_dp .or. &
                   rel_diff(out(8*n + 1:10*n), reshape(rj(:, 1:n), [2*n])) > 0.0_dp) &
                  error stop 'test_descriptor: outputs differ from reactions/kinematics'
            end block
         end do
      end do
      call report('N=3,5 vs descriptor system (dgesv), max rel diff: qdd '// &
                  real_str(d(1), 2)//', reactions '//real_str(d(2), 2)// &
                  '; vs Lagrange: qdd '//real_str(d(5), 2)// &
                  '; balance residuals: force '//real_str(d(3), 2)//', moment '// &
                  real_str(d(4), 2))
      call check(error, max(d(1), d(2)), 0.0_dp, 'N=3,5 vs descriptor, max rel diff', &
                 abs=1e-12_dp)
      call check(error, d(5), 0.0_dp, 'N=3,5 vs Lagrange, max rel diff', abs=1e-12_dp)
      call check(error, max(d(3), d(4)), 0.0_dp, 'N=3,5 link balance residual', abs=1e-12_dp)
   end subroutine test_descriptor

   !> N = 3, 5: ω_j² of diag(G) v = ω² M(−π/2) v (dsygv; V = Σ G_i sin q_i has
   !> ∂²V/∂q_i² = G_i at q_i = −π/2, M(−π/2) = K) against the period of the modal
   !> coordinate η_j = v_jᵀ M (q − q_eq) of rk4 runs (400 steps per period: phase
   !> error ~(ωh)⁴/120 = 5e-10) started at q_eq + ε v_j (|ε v_j| ≤ 1e-4 rad; the
   !> nonlinearities are cubic, frequency shifts O(ε²)), to 1e-6. (gauss6's fixed-point
   !> iteration stalls above its 1e3 ε tolerance at such amplitudes: the momenta are
   !> ~1e-4 of the rounding scale of q ≈ −π/2.)
   subroutine test_modes(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(error_t), allocatable :: err
      type(mode_event_t) :: event
      real(dp) :: mm(5, 5), a(5, 5), w2(5), work(200), qeq(5), tp, wm, d, amp
      real(dp), parameter :: m5(5) = [1.0_dp, 0.5_dp, 2.0_dp, 0.8_dp, 1.3_dp]
      real(dp), parameter :: l5(5) = [1.0_dp, 0.7_dp, 1.2_dp, 0.9_dp, 0.6_dp]
      integer :: n, nn, j, info, i
      integer, parameter :: ns(2) = [3, 5]
      character(len=:), allocatable :: text
      d = 0.0_dp
      text = ''
      do nn = 1, 2
         n = ns(nn)
         chain = chain_model(m5(1:n), l5(1:n), 9.81_dp, err)
         qeq(1:n) = -0.5_dp*pi
         mm(1:n, 1:n) = chain%mass_matrix(qeq(1:n))
         a = 0.0_dp
         do i = 1, n
            a(i, i) = chain%gl(i)
         end do
         call dsygv(1, 'V', 'U', n, a, 5, mm, 5, w2, work, size(work), info)
         call check_true(error, info == 0, 'dsygv info '//to_str(info))
         if (allocated(error)) return
         mm(1:n, 1:n) = chain%mass_matrix(qeq(1:n))
         text = text//' N='//to_str(n)//':'
         do j = 1, n
            event%n = n
            event%w(1:n) = matmul(mm(1:n, 1:n), a(1:n, j))
            event%direction = 1
            amp = 1e-4_dp/maxval(abs(a(1:n, j)))
            tp = measured_period('rk4', chain, event, qeq(1:n) + amp*a(1:n, j), &
                                 [(0.0_dp, i = 1, n)], 2.0_dp*pi/sqrt(w2(j)), 4, 400)
            wm = 2.0_dp*pi/tp
            d = max(d, abs(wm/sqrt(w2(j)) - 1.0_dp))
            text = text//' '//real_str(sqrt(w2(j)), 8)
         end do
      end do
      call report('small-oscillation omega [rad/s] (dsygv)'//text// &
                  '; max rel diff to measured '//real_str(d, 2))
      call check(error, d, 0.0_dp, 'N=3,5 modal frequencies, max rel diff', abs=1e-6_dp)
   end subroutine test_modes

   !> Analytic Jacobian, canonical Jacobian and energy gradient against central
   !> differences (step 1e-6 max(1, |y|)), relative to the largest entry, for N = 1, 2,
   !> 3, 5 at random states; velocities(momenta(y)) returns q̇ and H(q, p) = E.
   subroutine test_jacobians(error)
      type(error_t), allocatable, intent(out) :: error
      type(rng_t) :: rng
      type(chain_t) :: chain
      real(dp) :: y(10), z(10), yp(10), ym(10), fp(10), fm(10), jac(10, 10), jfd(10, 10)
      real(dp) :: g(10), gfd(10), p(5), qd(5), dx, d(6)
      integer :: nn, n, k, i, m
      integer, parameter :: ns(4) = [1, 2, 3, 5]
      d = 0.0_dp
      do nn = 1, 4
         n = ns(nn); m = 2*n
         do k = 1, 50
            call random_chain(rng, n, chain)
            call random_state(rng, n, y(1:m))
            call chain%jacobian(0.0_dp, y(1:m), jac(1:m, 1:m))
            call chain%energy_gradient(0.0_dp, y(1:m), g(1:m))
            call chain%momenta(0.0_dp, y(1:m), p(1:n))
            z(1:m) = [y(1:n), p(1:n)]
            do i = 1, m
               dx = 1e-6_dp*max(1.0_dp, abs(y(i)))
               yp(1:m) = y(1:m); ym(1:m) = y(1:m)
               yp(i) = y(i) + dx; ym(i) = y(i) - dx
               call chain%field(0.0_dp, yp(1:m), fp(1:m))
               call chain%field(0.0_dp, ym(1:m), fm(1:m))
               jfd(1:m, i) = (fp(1:m) - fm(1:m))/(2.0_dp*dx)
               gfd(i) = (chain%energy(0.0_dp, yp(1:m)) - chain%energy(0.0_dp, ym(1:m))) &
                        /(2.0_dp*dx)
            end do
            d(1) = max(d(1), maxval(abs(jac(1:m, 1:m) - jfd(1:m, 1:m))) &
                       /maxval(abs(jfd(1:m, 1:m))))
            d(3) = max(d(3), rel_diff(g(1:m), gfd(1:m)))
            call chain%canonical_jacobian(0.0_dp, z(1:m), jac(1:m, 1:m))
            do i = 1, m
               dx = 1e-6_dp*max(1.0_dp, abs(z(i)))
               yp(1:m) = z(1:m); ym(1:m) = z(1:m)
               yp(i) = z(i) + dx; ym(i) = z(i) - dx
               call chain%canonical_field(0.0_dp, yp(1:m), fp(1:m))
               call chain%canonical_field(0.0_dp, ym(1:m), fm(1:m))
               jfd(1:m, i) = (fp(1:m) - fm(1:m))/(2.0_dp*dx)
               ! −∂H/∂q from differences of H
               if (i <= n) gfd(i) = -(chain%hamiltonian_value(0.0_dp, yp(1:m)) &
                                      - chain%hamiltonian_value(0.0_dp, ym(1:m)))/(2.0_dp*dx)
            end do
            d(2) = max(d(2), maxval(abs(jac(1:m, 1:m) - jfd(1:m, 1:m))) &
                       /maxval(abs(jfd(1:m, 1:m))))
            call chain%canonical_field(0.0_dp, z(1:m), fp(1:m))
            d(4) = max(d(4), rel_diff(fp(n + 1:m), gfd(1:n)))
            call chain%velocities(0.0_dp, z(1:m), qd(1:n))
            d(5) = max(d(5), rel_diff(qd(1:n), y(n + 1:m)))
            ! relative to T + Σ G_i (E itself may vanish by cancellation)
            d(6) = max(d(6), abs(chain%hamiltonian_value(0.0_dp, z(1:m)) &
                                 - chain%energy(0.0_dp, y(1:m))) &
                       /(0.5_dp*dot_product(p(1:n), y(n + 1:m)) + sum(chain%gl)))
         end do
      end do
      call report('central differences, max rel diff: jacobian '//real_str(d(1), 2)// &
                  ', canonical jacobian '//real_str(d(2), 2)//', energy gradient '// &
                  real_str(d(3), 2)//', -dH/dq '//real_str(d(4), 2)// &
                  '; velocities(momenta) '//real_str(d(5), 2)//', H = E '//real_str(d(6), 2))
      call check(error, maxval(d(1:4)), 0.0_dp, 'derivatives vs central differences', &
                 abs=1e-7_dp)
      call check(error, maxval(d(5:6)), 0.0_dp, 'velocities(momenta), H = E', abs=1e-13_dp)
   end subroutine test_jacobians

   !> gauss6 on the chain of n unit links released horizontally (E0 = 0, so the unit
   !> is E_ref = Σ G_i), nsteps of h: the largest relative energy error in the first
   !> and in the second half of the run (`de`), and the status.
   subroutine gauss6_energy(n, h, nsteps, de, stat)
      integer, intent(in) :: n, nsteps
      real(dp), intent(in) :: h
      real(dp), intent(out) :: de(2)
      integer, intent(out) :: stat
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: y(2*n), t, hh, q(n), qd(n), e0, scale
      integer :: k
      chain = chain_model([(1.0_dp, k=1, n)], [(1.0_dp, k=1, n)], 9.8_dp, err)
      call new_integrator('gauss6', integ, err)
      q = 0.0_dp; qd = 0.0_dp
      e0 = chain%energy(0.0_dp, [q, qd])
      scale = chain%energy_scale(e0)
      y = integ%to_internal(chain, q, qd)
      t = 0.0_dp; de = 0.0_dp
      do k = 1, nsteps
         hh = h
         call integ%step(chain, t, y, hh, stat)
         if (stat /= stat_ok) return
         if (mod(k, 10) /= 0) cycle
         call integ%to_physical(chain, y, q, qd)
         de(1 + (2*k - 1)/nsteps) = max(de(1 + (2*k - 1)/nsteps), &
                                        abs(chain%energy(t, [q, qd]) - e0)/scale)
      end do
   end subroutine gauss6_energy

   !> gauss6, h = 1 ms, 2·10⁴ steps (20 s) of the chains of 3 and 5 unit links
   !> released horizontally (chaotic): the relative energy error stays below 1e-10
   !> and does not grow (the second half's maximum is below 10× the first half's).
   !> The 10⁶-step runs: `dpend-bench --chain-energy` (release).
   subroutine test_energy(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: de(2)
      integer :: n, stat
      character(len=:), allocatable :: line
      line = 'gauss6 h=1e-3, 2e4 steps, max rel. energy error (1st half, 2nd half):'
      do n = 3, 5, 2
         call gauss6_energy(n, 1e-3_dp, 20000, de, stat)
         call check_true(error, stat == stat_ok, 'N='//to_str(n)//' gauss6 failed')
         if (allocated(error)) return
         line = line//' N='//to_str(n)//' '//real_str(de(1), 2)//', '//real_str(de(2), 2)
         call check(error, maxval(de), 0.0_dp, 'N='//to_str(n)//' gauss6 energy error', &
                    abs=1e-10_dp)
         if (allocated(error)) return
         call check_true(error, de(2) < 10.0_dp*de(1), 'N='//to_str(n)// &
                         ' gauss6 energy error grows')
         if (allocated(error)) return
      end do
      call report(line)
   end subroutine test_energy

   !> The states of the chain at t = k Δ, k = 1 … size(ys, 2), from y0 (physical q, q̇)
   !> with `integ` at the fixed step h (0: adaptive), as physical (q, q̇); huge on
   !> failure.
   subroutine chain_samples(integ, chain, y0, dt, h, ys)
      class(integrator_t), intent(inout) :: integ
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: y0(:), dt, h
      real(dp), intent(out) :: ys(:, :)
      real(dp) :: z(size(y0)), t, hh
      integer :: n, stat, k
      n = size(y0)/2
      call integ%clear_step()
      z = integ%to_internal(chain, y0(1:n), y0(n + 1:))
      t = 0.0_dp; hh = h
      ys = huge(1.0_dp)
      do k = 1, size(ys, 2)
         call advance_to(integ, chain, t, z, dt*k, hh, stat)
         if (stat /= stat_ok) return
         call integ%to_physical(chain, z, ys(1:n, k), ys(n + 1:, k))
      end do
   end subroutine chain_samples

   !> The measured order of every method of the registry on the triple pendulum
   !> (unit links, g = 9.8) whirling from q_i = −π/2 + 0.1 i, q̇_i = 8 rad/s: the
   !> global error max over t = 0.25, 0.5, …, 2 s and over (q, q̇) at three fixed
   !> steps (the adaptive pairs in their fixed-step mode), against dop853 at
   !> rtol = 1e-14 (cross-checked with gauss8 at h = 1/1024 s); the least-squares
   !> slope of log error against log h is the nominal order ± 0.3. The steps
   !> (divisors of 0.25 s) keep each method in its asymptotic range and its errors
   !> far above the reference's (≤ 1e-12): the 8th-order methods from h = 1/64 s,
   !> where the 9th-order term no longer shows. They start from a guess by order and
   !> are halved (doubled) while an error is above 0.2 (below 5e-11), at most four
   !> times, so that a method added to the registry needs no entry here.
   subroutine test_orders(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      integer, parameter :: ns = 8
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: y0(6), yref(6, ns), ys(6, ns), e(3), h(3), d, p, worst
      integer :: m, k, moves
      character(len=:), allocatable :: name, line
      chain = chain_model([1.0_dp, 1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp, 1.0_dp], 9.8_dp, err)
      y0 = [-0.5_dp*pi + 0.1_dp, -0.5_dp*pi + 0.2_dp, -0.5_dp*pi + 0.3_dp, &
            8.0_dp, 8.0_dp, 8.0_dp]
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-14_dp, atol=1e-16_dp))
      call chain_samples(integ, chain, y0, 0.25_dp, 0.0_dp, yref)
      call new_integrator('gauss8', integ, err)
      call chain_samples(integ, chain, y0, 0.25_dp, 1.0_dp/1024, ys)
      d = maxval(abs(ys - yref))
      call check(error, d, 0.0_dp, 'reference dop853 vs gauss8', abs=1e-12_dp)
      if (allocated(error)) return
      line = 'N=3 measured orders (reference dop853 vs gauss8 '//real_str(d, 2)//'):'
      worst = 0.0_dp
      do m = 1, n_methods
         name = trim(method_table(m)%name)
         select case (method_table(m)%order)
         case (2)
            h = [256, 512, 1024]
         case (4)
            h = [128, 256, 512]
         case (5)
            h = [256, 512, 1024]
         case (6)
            h = [64, 128, 256]
         case (3)
            h = [128, 256, 512]
         case default   ! 7, 8, ...
            h = [64, 96, 128]
         end select
         h = 1.0_dp/h
         call new_integrator(name, integ, err, method_options_t(fixed_step=.true.))
         call check_true(error, .not. allocated(err), 'factory refused '//name)
         if (allocated(error)) return
         do moves = 0, 4
            do k = 1, 3
               call chain_samples(integ, chain, y0, 0.25_dp, h(k), ys)
               e(k) = maxval(abs(ys - yref))
            end do
            if (moves == 4) exit
            if (any(e >= 0.2_dp) .and. all(e > 5e-11_dp)) then
               h = 0.5_dp*h
            else if (any(e <= 5e-11_dp) .and. all(e < 0.2_dp) .and. h(1) < 0.125_dp) then
               h = 2.0_dp*h
            else
               exit   ! in the window, or no window: checked below
            end if
         end do
         call check_true(error, all(e > 5e-11_dp) .and. all(e < 0.2_dp), &
                         name//': errors '//real_str(e(1), 2)//' … '//real_str(e(3), 2)// &
                         ' outside [5e-11, 0.2]')
         if (allocated(error)) return
         p = slope(h, e)
         line = line//' '//name//' '//real_str(p, 3)
         worst = max(worst, abs(p - method_table(m)%order))
         call check(error, p, real(method_table(m)%order, dp), name//' measured order', &
                    abs=0.3_dp)
         if (allocated(error)) exit
      end do
      call report(line//'; max |measured - nominal| '//real_str(worst, 2))
   end subroutine test_orders

   !> gauss6 steps of `model` (n links) from rest at q_i = −π/2 ± amp (alternating
   !> signs): the steps done before a failure (of nsteps), the status and the
   !> fixed-point iterations per step.
   subroutine tiny_run(model, n, amp, h, nsteps, done, stat, iter)
      class(model_t), intent(in) :: model
      integer, intent(in) :: n, nsteps
      real(dp), intent(in) :: amp, h
      integer, intent(out) :: done, stat
      real(dp), intent(out) :: iter
      type(error_t), allocatable :: err
      class(integrator_t), allocatable :: integ
      real(dp) :: q(n), qd(n), y(2*n), t, hh
      integer :: i
      call new_integrator('gauss6', integ, err)
      do i = 1, n
         q(i) = -0.5_dp*pi + amp*merge(1.0_dp, -1.0_dp, mod(i, 2) == 1)
      end do
      qd = 0.0_dp
      y = integ%to_internal(model, q, qd)
      t = 0.0_dp
      stat = stat_ok
      done = 0
      do i = 1, nsteps
         hh = h
         call integ%step(model, t, y, hh, stat)
         if (stat /= stat_ok) exit
         done = i
      end do
      iter = real(integ%n_iter, dp)/max(1, done)
   end subroutine tiny_run

   !> gauss6 at h = 0.01 s, 2000 steps of tiny oscillations about the hanging
   !> equilibrium (amplitudes 1e-3 … 1e-9 rad) of the chains of 2 and 3 unit links:
   !> every step converges, and the fixed-point iteration count does not depend on
   !> the amplitude (the stage forces are computed relative to the offset from the
   !> step start, `field_near`), as for the double pendulum (N = 2: the same count).
   subroutine test_tiny(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      real(dp) :: amp, iter, iter_ref
      integer :: n, ia, done, stat
      character(len=:), allocatable :: line
      line = 'gauss6 h=0.01, 2000 steps from q=-pi/2+-amp: iterations per step'
      call tiny_run(pendulum_model(pendulum_t()), 2, 1e-5_dp, 0.01_dp, 2000, done, stat, &
                    iter_ref)
      line = line//'; double pendulum (amp 1e-5) '//real_str(iter_ref, 3)
      do n = 2, 3
         chain = chain_model([(1.0_dp, ia=1, n)], [(1.0_dp, ia=1, n)], 9.8_dp, err)
         line = line//'; N='//to_str(n)//':'
         do ia = 1, 4
            amp = 10.0_dp**(-1 - 2*ia)
            call tiny_run(chain, n, amp, 0.01_dp, 2000, done, stat, iter)
            line = line//' '//real_str(iter, 3)
            call check_true(error, stat == stat_ok, 'N='//to_str(n)//' amplitude '// &
                            real_str(amp, 2)//': gauss6 failed after '//to_str(done)// &
                            ' steps')
            if (allocated(error)) return
            if (ia == 1 .and. n == 3) iter_ref = iter
            call check(error, iter, iter_ref, 'N='//to_str(n)//' amplitude '// &
                       real_str(amp, 2)//': iterations per step', abs=0.5_dp)
            if (allocated(error)) return
         end do
      end do
      call report(line)
   end subroutine test_tiny
end module test_chain
