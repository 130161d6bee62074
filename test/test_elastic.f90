!> The elastic (spring) pendulum (dpend_elastic) against independently
!> known values:
!> - the field against Newton's law for the bob in Cartesian coordinates and against
!>   Lagrange's equations evaluated by finite differences of the Lagrangian;
!> - the Jacobians and the energy gradient against central differences, the canonical
!>   field against the (q, q̇) field through momenta and velocities, H = E;
!> - the outputs against differences along the flow and Newton's law for the bob;
!> - the small-oscillation frequencies √(k/m) and √(g/r_eq), measured on simulations;
!> - the energy exchange between the radial and the swing mode at the 2:1 resonance
!>   k/m = 4 g/r_eq, and its absence off resonance;
!> - for every method of the registry that accepts the model: the measured order of
!>   the state error and of the energy error; for the symplectic ones a bounded energy
!>   error, for the fixed-step explicit ones a drift;
!> - the methods refuse the model exactly where the registry says they need structure
!>   it lacks; a spring collapsing onto the pin ends every method's run with a failure
!>   status (no trap in the debug profile).
!> Each test prints its measured figures on one line ('    elastic: …').
module test_elastic
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp, pi, half_pi
   use dpend_error, only: error_t
   use dpend_model, only: model_t, max_state
   use dpend_elastic, only: elastic_t, elastic_model, check_state, saturated_field
   use dpend_limits, only: diverged_bound
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods
   use dpend_propagate, only: advance_to
   use dpend_events, only: event_t
   use dpend_cli, only: real_str, to_str
   use test_integrators, only: slope
   use test_chain, only: measured_period, rel_diff
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_elastic

   !> Crossing of coordinate `index` through `level` (r = r_eq, or φ = −π/2).
   type, extends(event_t) :: level_event_t
      integer :: index = 1
      real(dp) :: level = 0.0_dp
   contains
      procedure :: value => level_value
   end type level_event_t

contains

   subroutine collect_elastic(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('refuses_bad_parameters_and_states', test_refuse), &
               new_unittest('field_newton_and_lagrange', test_field), &
               new_unittest('jacobians_and_canonical_form', test_jacobians), &
               new_unittest('outputs_kinematics_and_forces', test_outputs), &
               new_unittest('small_oscillation_frequencies', test_frequencies), &
               new_unittest('resonance_energy_exchange', test_resonance), &
               new_unittest('methods_follow_registry', test_registry), &
               new_unittest('orders_every_method', test_orders), &
               new_unittest('energy_long_run_every_method', test_long_run), &
               new_unittest('collapsed_spring_no_trap', test_collapse)]
   end subroutine collect_elastic

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    elastic: '//text
   end subroutine report

   pure real(dp) function level_value(self, model, t, q, qd)
      class(level_event_t), intent(in) :: self
      class(model_t), intent(in) :: model
      real(dp), intent(in) :: t, q(:), qd(:)
      level_value = q(self%index) - self%level
   end function level_value

   !> The fractional part of k α (a low-discrepancy sequence in [0, 1)).
   pure real(dp) function seq(k, alpha)
      integer, intent(in) :: k
      real(dp), intent(in) :: alpha
      seq = modulo(real(k, dp)*alpha, 1.0_dp)
   end function seq

   !> Test model k of a family spread over the accepted ranges' useful part:
   !> m in [0.2, 5] kg, k in [2, 200] N/m, l0 in [0.3, 3] m, g in [1, 20] m/s².
   function sample_model(k) result(model)
      integer, intent(in) :: k
      type(elastic_t) :: model
      type(error_t), allocatable :: err
      model = elastic_model(0.2_dp + 4.8_dp*seq(k, 0.6180339887_dp), &
                            2.0_dp*100.0_dp**seq(k, 0.4142135624_dp), &
                            0.3_dp + 2.7_dp*seq(k, 0.7320508076_dp), &
                            1.0_dp + 19.0_dp*seq(k, 0.2360679775_dp), err)
      if (allocated(err)) error stop 'sample_model: '//err%message
   end function sample_model

   !> Test state k: r in [0.3, 3] l0, φ in [−π, π], ṙ in [−3, 3] m/s, φ̇ in [−5, 5] rad/s.
   pure function sample_state(model, k) result(y)
      type(elastic_t), intent(in) :: model
      integer, intent(in) :: k
      real(dp) :: y(4)
      y = [model%l0*(0.3_dp + 2.7_dp*seq(k, 0.5497004779_dp)), &
           pi*(2.0_dp*seq(k, 0.3027756377_dp) - 1.0_dp), &
           3.0_dp*(2.0_dp*seq(k, 0.8284271247_dp) - 1.0_dp), &
           5.0_dp*(2.0_dp*seq(k, 0.1622776602_dp) - 1.0_dp)]
   end function sample_state

   !> Every x_i is exactly `value`.
   pure logical function is_all(x, value)
      real(dp), intent(in) :: x(:), value
      is_all = maxval(abs(x - value)) <= 0.0_dp
   end function is_all

   !> The default model of the reference example: m = 1, k = 40, l0 = 1, g = 9.8.
   function default_model() result(model)
      type(elastic_t) :: model
      type(error_t), allocatable :: err
      model = elastic_model(1.0_dp, 40.0_dp, 1.0_dp, 9.8_dp, err)
      if (allocated(err)) error stop 'default_model: '//err%message
   end function default_model

   ! ------------------------------------------------------------------ parameters

   subroutine expect_refusal(error, err, prefix)
      type(error_t), allocatable, intent(inout) :: error
      type(error_t), allocatable, intent(in) :: err
      character(len=*), intent(in) :: prefix
      if (allocated(error)) return
      call check_true(error, allocated(err), "'"//prefix//"' accepted")
      if (allocated(error)) return
      call check_true(error, index(err%message, prefix) == 1, 'expected "'//prefix// &
                      '…", got "'//err%message//'"')
   end subroutine expect_refusal

   !> Out-of-range parameters and initial states are refused in one line naming the
   !> field and its value; the named parameters are m, k, l0, g with their units.
   subroutine test_refuse(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(elastic_t) :: model
      real(dp) :: value
      real(dp), parameter :: values(4) = [1.0_dp, 40.0_dp, 1.0_dp, 9.8_dp]
      character(len=:), allocatable :: name, units
      character(len=*), parameter :: names(4) = ['m ', 'k ', 'l0', 'g ']
      character(len=*), parameter :: unit_list(4) = ['kg   ', 'N/m  ', 'm    ', 'm/s^2']
      integer :: i
      model = elastic_model(0.0_dp, 40.0_dp, 1.0_dp, 9.8_dp, err)
      call expect_refusal(error, err, 'invalid m: 0 kg is outside [')
      model = elastic_model(1.0_dp, -1.0_dp, 1.0_dp, 9.8_dp, err)
      call expect_refusal(error, err, 'invalid k: -1 N/m is outside [')
      model = elastic_model(1.0_dp, 40.0_dp, huge(1.0_dp), 9.8_dp, err)
      call expect_refusal(error, err, 'invalid l0: ')
      model = elastic_model(1.0_dp, 40.0_dp, 1.0_dp, -9.8_dp, err)
      call expect_refusal(error, err, 'invalid g: -9.8 m/s^2 is outside [')
      if (allocated(error)) return
      model = elastic_model(1.0_dp, 40.0_dp, 2.0_dp, 0.0_dp, err)   ! one range for g
      call expect_refusal(error, err, 'invalid g: 0 m/s^2 is outside [1e-6, 1e6]')
      if (allocated(error)) return
      call check_state(model, [0.0_dp, -1.0_dp], [0.0_dp, 0.0_dp], err)
      call expect_refusal(error, err, 'invalid q1: 0 m is outside [')
      call check_state(model, [-0.5_dp, -1.0_dp], [0.0_dp, 0.0_dp], err)
      call expect_refusal(error, err, 'invalid q1: -0.5 m is outside [')
      call check_state(model, [1.0_dp, 2e6_dp], [0.0_dp, 0.0_dp], err)
      call expect_refusal(error, err, 'invalid q2: ')
      call check_state(model, [1.0_dp, -1.0_dp], [2e6_dp, 0.0_dp], err)
      call expect_refusal(error, err, 'invalid w1: ')
      call check_state(model, [1.0_dp, -1.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], err)
      call expect_refusal(error, err, 'invalid q: 3 coordinates')
      if (allocated(error)) return
      call check_state(model, [1.2_dp, -1.0_dp], [0.0_dp, 0.0_dp], err)
      call check_true(error, .not. allocated(err), 'the reference state (1.2, -1) refused')
      if (allocated(error)) return
      model = default_model()
      call check_true(error, model%n_parameters() == 4 .and. model%n_dof() == 2 .and. &
                      model%hamiltonian() .and. model%conservative() .and. &
                      model%autonomous() .and. .not. model%energy_sections(), &
                      'structure queries')
      if (allocated(error)) return
      do i = 1, 4
         call model%parameter(i, name, value, units)
         call check_true(error, name == trim(names(i)) .and. units == trim(unit_list(i)), &
                         'parameter '//to_str(i)//': '//name//' ['//units//']')
         if (allocated(error)) return
         call check(error, value, values(i), 'value of '//name, abs=0.0_dp)
         if (allocated(error)) return
      end do
      call report('refusals: m = 0, k = -1, l0 = huge, g = -9.8, r0 = 0, r0 = -0.5, '// &
                  'phi0 = 2e6, rdot0 = 2e6, 3 coordinates; parameters m k l0 g')
   end subroutine test_refuse

   ! ------------------------------------------------------------------ equations

   !> The Lagrangian m/2 (ṙ² + r² φ̇²) − k/2 (r − l0)² − m g r sin φ [J], written here
   !> from the model's statement (not taken from the module).
   pure real(dp) function lagrangian(model, q, qd)
      type(elastic_t), intent(in) :: model
      real(dp), intent(in) :: q(2), qd(2)
      lagrangian = 0.5_dp*model%m*(qd(1)**2 + q(1)**2*qd(2)**2) &
                   - 0.5_dp*model%k*(q(1) - model%l0)**2 - model%m*model%g*q(1)*sin(q(2))
   end function lagrangian

   !> q̈ of Lagrange's equations d/dt ∂L/∂q̇ = ∂L/∂q from finite differences of L:
   !> M q̈ = ∂L/∂q − B q̇, M = ∂²L/∂q̇², B = ∂²L/∂q̇∂q (L is quadratic in q̇, so the
   !> differences in q̇ are exact but for rounding; steps 1e-5 in q, 1 in q̇).
   pure function lagrange_fd(model, q, qd) result(qdd)
      type(elastic_t), intent(in) :: model
      real(dp), intent(in) :: q(2), qd(2)
      real(dp) :: qdd(2)
      real(dp) :: mm(2, 2), b(2, 2), dl(2), rhs(2), e(2, 2), hq(2), hv, det
      integer :: i, j
      e = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
      hv = 1.0_dp
      hq = 1e-5_dp*max(1.0_dp, abs(q))
      do i = 1, 2
         dl(i) = (lagrangian(model, q + hq(i)*e(:, i), qd) &
                  - lagrangian(model, q - hq(i)*e(:, i), qd))/(2.0_dp*hq(i))
         do j = 1, 2
            mm(i, j) = (lagrangian(model, q, qd + hv*(e(:, i) + e(:, j))) &
                        - lagrangian(model, q, qd + hv*(e(:, i) - e(:, j))) &
                        - lagrangian(model, q, qd - hv*(e(:, i) - e(:, j))) &
                        + lagrangian(model, q, qd - hv*(e(:, i) + e(:, j))))/(4.0_dp*hv*hv)
            b(i, j) = (lagrangian(model, q + hq(j)*e(:, j), qd + hv*e(:, i)) &
                       - lagrangian(model, q + hq(j)*e(:, j), qd - hv*e(:, i)) &
                       - lagrangian(model, q - hq(j)*e(:, j), qd + hv*e(:, i)) &
                       + lagrangian(model, q - hq(j)*e(:, j), qd - hv*e(:, i))) &
                      /(4.0_dp*hv*hq(j))
         end do
      end do
      rhs = dl - matmul(b, qd)
      det = mm(1, 1)*mm(2, 2) - mm(1, 2)*mm(2, 1)
      qdd(1) = (mm(2, 2)*rhs(1) - mm(1, 2)*rhs(2))/det
      qdd(2) = (mm(1, 1)*rhs(2) - mm(2, 1)*rhs(1))/det
   end function lagrange_fd

   !> The field against (a) Newton's law for the bob in Cartesian coordinates,
   !> m a = −k (r − l0) u − m g ĵ, with a = (r̈ − r φ̇²) u + (r φ̈ + 2 ṙ φ̇) n from the
   !> field's (r̈, φ̈), to 1e-13 of the largest force term; (b) Lagrange's equations
   !> from finite differences of the Lagrangian (`lagrange_fd`), to 1e-6; at 200
   !> states of 200 models; and the hanging equilibrium (r_eq, −π/2) is at rest.
   subroutine test_field(error)
      type(error_t), allocatable, intent(out) :: error
      type(elastic_t) :: model
      real(dp) :: y(4), f(4), u(2), nv(2), a(2), an(2), scale, d(3), qdd(2)
      integer :: k
      d = 0.0_dp
      do k = 1, 200
         model = sample_model(k)
         y = sample_state(model, k)
         call model%field(0.0_dp, y, f)
         u = [cos(y(2)), sin(y(2))]
         nv = [-u(2), u(1)]
         a = (f(3) - y(1)*y(4)**2)*u + (y(1)*f(4) + 2.0_dp*y(3)*y(4))*nv
         an = -(model%k/model%m)*(y(1) - model%l0)*u - [0.0_dp, model%g]
         scale = abs(model%k/model%m*(y(1) - model%l0)) + model%g + y(1)*y(4)**2 &
                 + 2.0_dp*abs(y(3)*y(4))
         d(1) = max(d(1), maxval(abs(a - an))/scale)
         qdd = lagrange_fd(model, y(1:2), y(3:4))
         d(2) = max(d(2), rel_diff(f(3:4), qdd))
         d(2) = max(d(2), rel_diff(f(1:2), y(3:4)))
         ! at rest at the hanging equilibrium
         call model%field(0.0_dp, [model%r_eq(), -half_pi, 0.0_dp, 0.0_dp], f)
         d(3) = max(d(3), maxval(abs(f))/model%g)
      end do
      call report('field vs Newton (Cartesian) '//real_str(d(1), 2)// &
                  ', vs Lagrange by finite differences of L '//real_str(d(2), 2)// &
                  ', |f|/g at (r_eq, -pi/2) '//real_str(d(3), 2))
      call check(error, d(1), 0.0_dp, 'field vs Newton, max rel diff', abs=1e-13_dp)
      call check(error, d(2), 0.0_dp, 'field vs Lagrange (finite differences)', abs=1e-6_dp)
      call check(error, d(3), 0.0_dp, 'field at the hanging equilibrium', abs=1e-13_dp)
   end subroutine test_field

   !> Central differences (step 1e-6 max(1, |x_i|)) at x of the (q, q̇) field and the
   !> energy, or (canonical) of the Hamiltonian field and −H: their Jacobian jfd and
   !> gradient gfd.
   subroutine central_differences(model, canonical, x, jfd, gfd)
      type(elastic_t), intent(in) :: model
      logical, intent(in) :: canonical
      real(dp), intent(in) :: x(4)
      real(dp), intent(out) :: jfd(4, 4), gfd(4)
      real(dp) :: xp(4), xm(4), fp(4), fm(4), dx
      integer :: i
      do i = 1, 4
         dx = 1e-6_dp*max(1.0_dp, abs(x(i)))
         xp = x; xm = x
         xp(i) = x(i) + dx; xm(i) = x(i) - dx
         if (canonical) then
            call model%canonical_field(0.0_dp, xp, fp)
            call model%canonical_field(0.0_dp, xm, fm)
            gfd(i) = -(model%hamiltonian_value(0.0_dp, xp) &
                       - model%hamiltonian_value(0.0_dp, xm))/(2.0_dp*dx)
         else
            call model%field(0.0_dp, xp, fp)
            call model%field(0.0_dp, xm, fm)
            gfd(i) = (model%energy(0.0_dp, xp) - model%energy(0.0_dp, xm))/(2.0_dp*dx)
         end if
         jfd(:, i) = (fp - fm)/(2.0_dp*dx)
      end do
   end subroutine central_differences

   !> The analytic Jacobian, canonical Jacobian and energy gradient against central
   !> differences (`central_differences`), relative to the largest entry; −∂H/∂q of the
   !> canonical field against differences of H; and, exactly, velocities(momenta(y)) =
   !> q̇, H(q, p(y)) = E(y), the canonical field against the (q, q̇) field through the
   !> momenta: (ṙ, φ̇) equal, ṗ = (m r̈, m (2 r ṙ φ̇ + r² φ̈)).
   subroutine test_jacobians(error)
      type(error_t), allocatable, intent(out) :: error
      type(elastic_t) :: model
      real(dp) :: y(4), z(4), jac(4, 4), jfd(4, 4), g(4), gfd(4), p(2), qd(2), f(4), fz(4)
      real(dp) :: pdot(2), d(7)
      integer :: k
      d = 0.0_dp
      do k = 1, 200
         model = sample_model(k)
         y = sample_state(model, k)
         call model%jacobian(0.0_dp, y, jac)
         call model%energy_gradient(0.0_dp, y, g)
         call central_differences(model, .false., y, jfd, gfd)
         d(1) = max(d(1), maxval(abs(jac - jfd))/maxval(abs(jfd)))
         d(3) = max(d(3), rel_diff(g, gfd))
         call model%momenta(0.0_dp, y, p)
         z = [y(1:2), p]
         call model%canonical_jacobian(0.0_dp, z, jac)
         call central_differences(model, .true., z, jfd, gfd)
         d(2) = max(d(2), maxval(abs(jac - jfd))/maxval(abs(jfd)))
         call model%canonical_field(0.0_dp, z, fz)
         d(4) = max(d(4), rel_diff(fz(3:4), gfd(1:2)))
         call model%velocities(0.0_dp, z, qd)
         d(5) = max(d(5), rel_diff(qd, y(3:4)))
         ! relative to T + |V| term by term (E may vanish by cancellation)
         d(6) = max(d(6), abs(model%hamiltonian_value(0.0_dp, z) - model%energy(0.0_dp, y)) &
                    /(0.5_dp*dot_product(p, y(3:4)) + 0.5_dp*model%k*(y(1) - model%l0)**2 &
                      + model%m*model%g*y(1)))
         call model%field(0.0_dp, y, f)
         pdot = [model%m*f(3), model%m*(2.0_dp*y(1)*y(3)*y(4) + y(1)**2*f(4))]
         d(7) = max(d(7), rel_diff(fz(1:2), f(1:2)), &
                    maxval(abs(fz(3:4) - pdot)/(abs(pdot) + model%m*model%g*y(1) &
                                                + model%k*abs(y(1) - model%l0))))
      end do
      call report('central differences, max rel diff: jacobian '//real_str(d(1), 2)// &
                  ', canonical jacobian '//real_str(d(2), 2)//', energy gradient '// &
                  real_str(d(3), 2)//', -dH/dq '//real_str(d(4), 2)// &
                  '; velocities(momenta) '//real_str(d(5), 2)//', H = E '// &
                  real_str(d(6), 2)//', canonical vs (q, qdot) field '//real_str(d(7), 2))
      call check(error, maxval(d(1:4)), 0.0_dp, 'derivatives vs central differences', &
                 abs=1e-7_dp)
      call check(error, maxval(d(5:7)), 0.0_dp, 'velocities(momenta), H = E, canonical ' &
                 //'field', abs=1e-13_dp)
   end subroutine test_jacobians

   !> output_info describes 10 values (rC, vC, aC, F_joint as one row of (x, y);
   !> tension, spring_length); vC and aC against central differences of rC and vC along
   !> the flow (∂/∂y · f, step 1e-5: O(1e-10)); F_joint against Newton's law for the bob,
   !> F01 = m (a_C + g ĵ), and the tension is |F01| signed by r − l0, both to 1e-12 of
   !> k r + m (g + |a_C|); the spring length is |rC| = r.
   subroutine test_outputs(error)
      type(error_t), allocatable, intent(out) :: error
      type(elastic_t) :: model
      character(len=:), allocatable :: name, units, text, names
      real(dp) :: y(4), f(4), v(12), vp(12), vm(12), d(4), dt, fn(2), scale
      integer :: i, k, n_comp, rows, total
      model = default_model()
      total = 0
      names = ''
      do i = 1, model%n_outputs()
         call model%output_info(i, name, n_comp, units, text, rows)
         total = total + n_comp
         names = names//' '//name//' ['//units//']'
         call check_true(error, len(text) > 0 .and. (rows == 0 .or. rows == 1), &
                         name//': description or rows')
         if (allocated(error)) return
      end do
      call check_true(error, total == 12 .and. names == ' rC [m] vC [m/s] aC [m/s^2] ' &
                      //'F_joint [N] tension [N] spring_length [m] rA [m]', 'outputs:'//names)
      if (allocated(error)) return
      d = 0.0_dp
      do k = 1, 100
         model = sample_model(k)
         y = sample_state(model, k)
         call model%field(0.0_dp, y, f)
         call model%outputs(0.0_dp, y, f, v)
         dt = 1e-5_dp
         call model%outputs(0.0_dp, y + dt*f, f, vp)   ! rC, vC of y ± dt f
         call model%outputs(0.0_dp, y - dt*f, f, vm)
         d(1) = max(d(1), rel_diff((vp(1:4) - vm(1:4))/(2.0_dp*dt), v(3:6)))
         fn = model%m*(v(5:6) + [0.0_dp, model%g])
         ! relative to the size of the terms of m (a + g j)
         scale = model%k*y(1) + model%m*(model%g + norm2(v(5:6)))
         d(2) = max(d(2), maxval(abs(v(7:8) - fn))/scale)
         d(3) = max(d(3), abs(v(9) - sign(norm2(fn), y(1) - model%l0))/scale)
         d(4) = max(d(4), abs(v(10) - norm2(v(1:2)))/v(10), abs(v(10) - y(1))/y(1))
      end do
      call report('outputs'//names//'; max rel diff: vC, aC vs differences '// &
                  real_str(d(1), 2)//', F_joint vs m (aC + g j) '//real_str(d(2), 2)// &
                  ', tension '//real_str(d(3), 2)//', spring length '//real_str(d(4), 2))
      call check(error, d(1), 0.0_dp, 'vC, aC vs differences along the flow', abs=1e-8_dp)
      call check(error, maxval(d(2:4)), 0.0_dp, 'F_joint, tension, spring length', &
                 abs=1e-12_dp)
   end subroutine test_outputs

   ! ------------------------------------------------------------------ dynamics

   !> Small oscillations about (r_eq, −π/2), r_eq = l0 + m g/k, of the reference model
   !> (m 1, k 40, l0 1, g 9.8) and of a sample model: the radial period from r − r_eq =
   !> 1e-3 r_eq (the motion along φ = −π/2 is linear: exact at any amplitude) and the
   !> swing period from φ + π/2 = 1e-4 rad (frequency shifts O(1e-8)), by event location
   !> on rk4 runs with 400 steps per period (phase error ≈ (2π/400)⁴/120 = 5e-10) over
   !> 10 periods, against 2π/√(k/m) and 2π/√(g/r_eq), to 1e-7.
   subroutine test_frequencies(error)
      type(error_t), allocatable, intent(out) :: error
      type(elastic_t) :: model
      real(dp) :: req, w_r, w_s, tp, d(2), wm(2)
      integer :: j
      character(len=:), allocatable :: line
      d = 0.0_dp
      line = 'omega radial, swing [rad/s] measured (closed form):'
      do j = 1, 2
         if (j == 1) then
            model = default_model()
         else
            model = sample_model(7)
         end if
         req = model%r_eq()
         w_r = sqrt(model%k/model%m)
         w_s = sqrt(model%g/req)
         tp = measured_period('rk4', model, level_event_t(index=1, level=req, direction=1), &
                              [1.001_dp*req, -half_pi], [0.0_dp, 0.0_dp], 2.0_dp*pi/w_r, 10, 400)
         wm(1) = 2.0_dp*pi/tp
         tp = measured_period('rk4', model, level_event_t(index=2, level=-half_pi, &
                                                          direction=1), &
                              [req, -half_pi + 1e-4_dp], [0.0_dp, 0.0_dp], 2.0_dp*pi/w_s, 10, 400)
         wm(2) = 2.0_dp*pi/tp
         d(1) = max(d(1), abs(wm(1)/w_r - 1.0_dp))
         d(2) = max(d(2), abs(wm(2)/w_s - 1.0_dp))
         line = line//' '//real_str(wm(1), 10)//' ('//real_str(w_r, 10)//'), '// &
                real_str(wm(2), 10)//' ('//real_str(w_s, 10)//');'
      end do
      call report(line//' max rel diff radial '//real_str(d(1), 2)//', swing '// &
                  real_str(d(2), 2))
      call check(error, d(1), 0.0_dp, 'radial frequency sqrt(k/m), rel diff', abs=1e-7_dp)
      call check(error, d(2), 0.0_dp, 'swing frequency sqrt(g/r_eq), rel diff', abs=1e-7_dp)
   end subroutine test_frequencies

   !> Fractions of the linearised mode energies E_s/(E_r + E_s) at t = 0, 0.05, … t_end
   !> (dop853, rtol 1e-11) from r = r_eq (1 + a), φ = −π/2 + θ0, at rest:
   !> E_r = m ṙ²/2 + k (r − r_eq)²/2, E_s = m r_eq² φ̇²/2 + m g r_eq (φ + π/2)²/2.
   subroutine swing_fraction(model, a, theta0, t_end, frac, stat)
      type(elastic_t), intent(in) :: model
      real(dp), intent(in) :: a, theta0, t_end
      real(dp), allocatable, intent(out) :: frac(:)
      integer, intent(out) :: stat
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      real(dp) :: y(4), q(2), qd(2), t, h, req, er, es
      integer :: i, n
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-11_dp, atol=1e-13_dp))
      req = model%r_eq()
      n = nint(t_end/0.05_dp)
      allocate (frac(0:n))
      stat = stat_ok
      y = integ%to_internal(model, [req*(1.0_dp + a), -half_pi + theta0], [0.0_dp, 0.0_dp])
      t = 0.0_dp; h = 0.0_dp
      do i = 0, n
         if (i > 0) call advance_to(integ, model, t, y, 0.05_dp*i, h, stat)
         if (stat /= stat_ok) return
         call integ%to_physical(model, y, q, qd)
         er = 0.5_dp*model%m*qd(1)**2 + 0.5_dp*model%k*(q(1) - req)**2
         es = 0.5_dp*model%m*(req*qd(2))**2 + 0.5_dp*model%m*model%g*req*(q(2) + half_pi)**2
         frac(i) = es/(er + es)
      end do
      stat = stat_ok
   end subroutine swing_fraction

   !> The 2:1 resonance: m = 1, l0 = 1, g = 9.8, k = 3 m g/l0 = 29.4 N/m, so that
   !> r_eq = 4/3 m and k/m = 4 g/r_eq. Started in the radial mode (a = 5 % of r_eq) with
   !> a swing seed θ0 = 0.01 rad (swing fraction 0.6 %), the swing takes over more than
   !> half of the energy, then gives it back (below 10 % after the maximum), within
   !> 80 s. Off resonance (k = 60 N/m, ω_r/ω_s = 2.67) the same start keeps the swing
   !> fraction below 5 %.
   subroutine test_resonance(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(elastic_t) :: model
      real(dp), allocatable :: frac(:)
      real(dp) :: f_max, f_back, f_off, t_max, t_back
      integer :: stat, i_max, i_back
      model = elastic_model(1.0_dp, 3.0_dp*9.8_dp, 1.0_dp, 9.8_dp, err)
      call check(error, model%k/model%m, 4.0_dp*model%g/model%r_eq(), 'k/m = 4 g/r_eq', &
                 rel=1e-14_dp)
      if (allocated(error)) return
      call swing_fraction(model, 0.05_dp, 0.01_dp, 80.0_dp, frac, stat)
      call check_true(error, stat == stat_ok, 'dop853 failed: '//status_message(stat))
      if (allocated(error)) return
      i_max = maxloc(frac, 1) - 1
      f_max = frac(i_max); t_max = 0.05_dp*i_max
      i_back = minloc(frac(i_max:), 1) - 1 + i_max
      f_back = frac(i_back); t_back = 0.05_dp*i_back
      model = elastic_model(1.0_dp, 60.0_dp, 1.0_dp, 9.8_dp, err)
      call swing_fraction(model, 0.05_dp, 0.01_dp, 80.0_dp, frac, stat)
      call check_true(error, stat == stat_ok, 'dop853 failed off resonance')
      if (allocated(error)) return
      f_off = maxval(frac)
      call report('2:1 resonance: swing fraction '//real_str(frac(0), 3)// &
                  ' at t = 0, max '//real_str(f_max, 3)//' at t = '//real_str(t_max, 4)// &
                  ' s, back to '//real_str(f_back, 3)//' at t = '//real_str(t_back, 4)// &
                  ' s; off resonance (k = 60) max '//real_str(f_off, 3))
      call check_true(error, f_max > 0.5_dp, 'the swing takes less than half the energy: ' &
                      //real_str(f_max, 3))
      call check_true(error, f_back < 0.1_dp, 'the swing does not give the energy back: ' &
                      //real_str(f_back, 3))
      call check_true(error, f_off < 0.05_dp, 'off resonance the swing takes ' &
                      //real_str(f_off, 3))
   end subroutine test_resonance

   ! ------------------------------------------------------------------ methods

   !> Every method of the registry is built and asked `check_model`: it refuses the
   !> elastic pendulum exactly when the registry says it needs structure the model
   !> lacks (a Hamiltonian: `hamiltonian` in the table), with a one-line 'invalid
   !> method: …' error; the others accept it. (The model is Hamiltonian, so the
   !> registry predicts no refusal; the test follows the registry if that changes.)
   subroutine test_registry(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(elastic_t) :: model
      class(integrator_t), allocatable :: integ
      integer :: i, n_refused
      logical :: expect
      character(len=:), allocatable :: name
      model = default_model()
      n_refused = 0
      do i = 1, n_methods
         name = trim(method_table(i)%name)
         call new_integrator(name, integ, err)
         call check_true(error, .not. allocated(err), 'factory refused '//name)
         if (allocated(error)) return
         expect = (method_table(i)%hamiltonian .and. .not. model%hamiltonian()) &
                  .or. model%n_state() > max_state
         call integ%check_model(model, err)
         call check_true(error, allocated(err) .eqv. expect, name//': check_model ' &
                         //merge('accepted', 'refused ', expect))
         if (allocated(error)) return
         if (expect) then
            n_refused = n_refused + 1
            call check_true(error, index(err%message, 'invalid method: '//name) == 1, &
                            err%message)
            if (allocated(error)) return
         end if
      end do
      call report(to_str(n_methods - n_refused)//' of '//to_str(n_methods)// &
                  ' methods accept the elastic pendulum, '//to_str(n_refused)// &
                  ' refuse it, as the registry says')
   end subroutine test_registry

   !> States (r, φ, ṙ, φ̇) at t = k Δ, k = 1 … size(ys, 2), from y0 with `integ` at the
   !> fixed step h (0: adaptive); `ok` false (and ys huge) after a failure.
   subroutine samples(integ, model, y0, dt, h, ys, ok)
      class(integrator_t), intent(inout) :: integ
      type(elastic_t), intent(in) :: model
      real(dp), intent(in) :: y0(4), dt, h
      real(dp), intent(out) :: ys(:, :)
      logical, intent(out) :: ok
      real(dp) :: z(4), t, hh
      integer :: stat, k
      call integ%clear_step()
      z = integ%to_internal(model, y0(1:2), y0(3:4))
      t = 0.0_dp; hh = h
      ys = huge(1.0_dp)
      ok = .false.
      do k = 1, size(ys, 2)
         call advance_to(integ, model, t, z, dt*k, hh, stat)
         if (stat /= stat_ok) return
         call integ%to_physical(model, z, ys(1:2, k), ys(3:4, k))
      end do
      ok = .true.
   end subroutine samples

   !> The global error (max over the samples and the components) of `integ` at the
   !> fixed step h against yref, and the largest relative energy error of the samples
   !> against E(y0); both huge when the run fails.
   subroutine run_errors(integ, model, y0, dt, h, yref, e, ee)
      class(integrator_t), intent(inout) :: integ
      type(elastic_t), intent(in) :: model
      real(dp), intent(in) :: y0(4), dt, h, yref(:, :)
      real(dp), intent(out) :: e, ee
      real(dp) :: ys(4, size(yref, 2)), e0
      logical :: ok
      integer :: k
      call samples(integ, model, y0, dt, h, ys, ok)
      e = huge(1.0_dp); ee = huge(1.0_dp)
      if (.not. ok) return
      e = maxval(abs(ys - yref))
      e0 = model%energy(0.0_dp, y0)
      ee = 0.0_dp
      do k = 1, size(ys, 2)
         ee = max(ee, abs(model%energy(0.0_dp, ys(:, k)) - e0))
      end do
      ee = ee/model%energy_scale(e0)
   end subroutine run_errors

   !> The ladder of step divisors 2, 3, 4, 6, 8, 12, …: ×3/2 after a power of 2, else ×4/3.
   pure integer function next_n(n)
      integer, intent(in) :: n
      if (iand(n, n - 1) == 0) then
         next_n = 3*n/2
      else
         next_n = 4*n/3
      end if
   end function next_n

   !> The measured order of every method of the registry that accepts the model, on a
   !> large swing with a stretching spring (m 1, k 40, l0 1, g 9.8, from r = 1.3 m,
   !> φ = −π/2 + 0.8, ṙ = 0.5 m/s, φ̇ = 1 rad/s): the global error (max over t = 0.5,
   !> 1, 1.5, 2 s and over (r, φ, ṙ, φ̇)) at three fixed steps (the adaptive pairs in
   !> their fixed-step mode), against dop853 at rtol 1e-14 (cross-checked with gauss8
   !> at h = 1/1024 s), and the relative energy error at the same samples; the slopes
   !> of log error against log h are the nominal order ± 0.3 (state) and at least the
   !> nominal order − 0.3 (energy). The steps: of 0.5 s/n, n = 2, 3, 4, 6, 8, 12, …, the
   !> first whose error is below min(1e-5, 10^-order) (the asymptotic range: the
   !> 8th-order methods show their 9th-order term above 1e-8) and the next two (half of
   !> it in all); the errors must stay above 1e-12 (100 × the difference of the two
   !> references).
   subroutine test_orders(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      integer, parameter :: ns = 4
      real(dp), parameter :: dt = 0.5_dp
      type(elastic_t) :: model
      class(integrator_t), allocatable :: integ
      real(dp) :: y0(4), yref(4, ns), ys(4, ns), e(3), ee(3), h(3), d, p, pe, worst
      integer :: m, k, order, nn
      logical :: ok
      character(len=:), allocatable :: name, line
      model = default_model()
      y0 = [1.3_dp, -half_pi + 0.8_dp, 0.5_dp, 1.0_dp]
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-14_dp, atol=1e-16_dp))
      call samples(integ, model, y0, dt, 0.0_dp, yref, ok)
      call check_true(error, ok, 'reference dop853 failed')
      if (allocated(error)) return
      call new_integrator('gauss8', integ, err)
      call samples(integ, model, y0, dt, 1.0_dp/1024, ys, ok)
      d = maxval(abs(ys - yref))
      call check(error, d, 0.0_dp, 'reference dop853 vs gauss8', abs=1e-12_dp)
      if (allocated(error)) return
      line = 'measured orders state/energy (reference dop853 vs gauss8 '// &
             real_str(d, 2)//'):'
      worst = 0.0_dp
      do m = 1, n_methods
         name = trim(method_table(m)%name)
         order = method_table(m)%order
         call new_integrator(name, integ, err, method_options_t(fixed_step=.true.))
         call integ%check_model(model, err)
         if (allocated(err)) cycle      ! refused: `methods_follow_registry`
         ! steps Δ/n, n = 2, 3, 4, 6, 8, 12, … (ratios 3/2 and 4/3): the first with an
         ! error below min(1e-5, 10^-order), and the next two (n up to 24576: a second-
         ! order method such as Heun's needs n = 2048 here)
         nn = 2
         do k = 1, 28
            call run_errors(integ, model, y0, dt, dt/nn, yref, e(1), ee(1))
            if (e(1) < min(1e-5_dp, 10.0_dp**(-order))) exit
            nn = next_n(nn)
         end do
         ! the ladder exhausted: e(1) is the error of the step before nn, not of dt/nn
         call check_true(error, e(1) < min(1e-5_dp, 10.0_dp**(-order)), name// &
                         ': no step dt/n, n < '//to_str(nn)//', has an error below ' &
                         //real_str(min(1e-5_dp, 10.0_dp**(-order)), 2))
         if (allocated(error)) exit
         h(1) = dt/nn
         do k = 2, 3
            nn = next_n(nn)
            h(k) = dt/nn
            call run_errors(integ, model, y0, dt, h(k), yref, e(k), ee(k))
         end do
         call check_true(error, all(e > 1e-12_dp) .and. all(e < 0.2_dp), &
                         name//': errors '//real_str(e(1), 2)//' … '//real_str(e(3), 2)// &
                         ' outside [1e-12, 0.2]')
         if (allocated(error)) exit
         p = slope(h, e)
         pe = slope(h, max(ee, 1e-300_dp))
         line = line//' '//name//' '//real_str(p, 3)//'/'//real_str(pe, 3)// &
                ' (h '//real_str(h(1), 3)//')'
         worst = max(worst, abs(p - order))
         call check(error, p, real(order, dp), name//' measured order', abs=0.3_dp)
         call check_true(error, pe > order - 0.3_dp .and. all(ee > 1e-15_dp), name// &
                         ': energy errors '//real_str(ee(1), 2)//' … '//real_str(ee(3), 2)// &
                         ', measured order '//real_str(pe, 3))
         if (allocated(error)) exit
      end do
      call report(line//'; max |measured - nominal| '//real_str(worst, 2))
   end subroutine test_orders

   !> Long runs (200 s, from the large swing of `test_orders`) of every fixed-step
   !> method of the registry that accepts the model, at the registry's largest study
   !> step h_max: the largest relative energy error in the first and in the second half.
   !> The symplectic methods keep it bounded (second half < 2 × first half, and
   !> below 1e-3); the others (rk4) drift (second half > 1.5 × first half).
   subroutine test_long_run(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(elastic_t) :: model
      class(integrator_t), allocatable :: integ
      real(dp) :: y0(4), z(4), q(2), qd(2), t, h, hh, e0, scale, de(2), t_end
      integer :: m, stat, half, k, nsteps
      character(len=:), allocatable :: name, line
      model = default_model()
      y0 = [1.3_dp, -half_pi + 0.8_dp, 0.5_dp, 1.0_dp]
      e0 = model%energy(0.0_dp, y0)
      scale = model%energy_scale(e0)
      t_end = 200.0_dp
      line = 'energy error over 200 s at h_max (1st half, 2nd half):'
      do m = 1, n_methods
         if (method_table(m)%adaptive) cycle
         name = trim(method_table(m)%name)
         call new_integrator(name, integ, err)
         call integ%check_model(model, err)
         if (allocated(err)) cycle
         h = method_table(m)%h_max
         nsteps = nint(t_end/h)
         z = integ%to_internal(model, y0(1:2), y0(3:4))
         t = 0.0_dp; de = 0.0_dp
         do k = 1, nsteps
            hh = h
            call integ%step(model, t, z, hh, stat)
            if (stat /= stat_ok) exit
            call integ%to_physical(model, z, q, qd)
            half = merge(1, 2, 2*k <= nsteps)
            de(half) = max(de(half), abs(model%energy(t, [q, qd]) - e0)/scale)
         end do
         call check_true(error, stat == stat_ok, name//' failed: '//status_message(stat))
         if (allocated(error)) return
         line = line//' '//name//' '//real_str(de(1), 2)//', '//real_str(de(2), 2)//';'
         if (method_table(m)%symplectic) then
            call check_true(error, de(2) < 2.0_dp*de(1) .and. de(2) < 1e-3_dp, name// &
                            ': energy error not bounded: '//real_str(de(1), 2)//', '// &
                            real_str(de(2), 2))
         else
            call check_true(error, de(2) > 1.5_dp*de(1), name//': no energy drift: '// &
                            real_str(de(1), 2)//', '//real_str(de(2), 2))
         end if
         if (allocated(error)) exit
      end do
      call report(line)
   end subroutine test_long_run

   ! ------------------------------------------------------------------ the collapse

   !> The saturation at r < r_min and beyond diverged_bound (the fields return
   !> saturated_field, the Jacobians, velocities and H diverged_bound, the energy stays
   !> finite), and a radial fall
   !> onto the pin (r0 = 0.2 m, ṙ0 = −6 m/s, along φ = −π/2: r(t) = r_eq + (r0 − r_eq)
   !> cos ωt + (ṙ0/ω) sin ωt reaches 0 at t_hit) with every method that accepts the
   !> model (fixed steps of 1 ms, the adaptive ones at their default tolerances): the
   !> run ends with a failure status within 20 ms of t_hit, not later and not a trap.
   subroutine test_collapse(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(elastic_t) :: model
      class(integrator_t), allocatable :: integ
      real(dp) :: y(4), f(4), jac(4, 4), qd(2), z(4), t, h, w, req, t_hit, a, b, worst
      real(dp), parameter :: bad(4, 4) = reshape([0.0_dp, -1.0_dp, 0.1_dp, 0.1_dp, &
                                                  -0.3_dp, 1.0_dp, 1.0_dp, 1.0_dp, &
                                                  1e-7_dp, -1.0_dp, 0.0_dp, 0.0_dp, &
                                                  1.0_dp, -1.0_dp, 2e30_dp, 0.0_dp], [4, 4])
      integer :: i, stat
      character(len=:), allocatable :: name, line
      model = default_model()
      do i = 1, 4
         y = bad(:, i)
         call model%field(0.0_dp, y, f)
         call check_true(error, is_all(f, saturated_field), 'field not saturated at state ' &
                         //to_str(i))
         call model%canonical_field(0.0_dp, y, f)
         call check_true(error, is_all(f, saturated_field), 'canonical field not saturated')
         call model%jacobian(0.0_dp, y, jac)
         call check_true(error, is_all(reshape(jac, [16]), diverged_bound), &
                         'jacobian not saturated')
         call model%canonical_jacobian(0.0_dp, y, jac)
         call check_true(error, is_all(reshape(jac, [16]), diverged_bound), &
                         'canonical jacobian not saturated')
         call model%velocities(0.0_dp, y, qd)
         call check_true(error, is_all(qd, diverged_bound), 'velocities not saturated')
         call check_true(error, is_all([model%hamiltonian_value(0.0_dp, y)], diverged_bound), &
                         'H not saturated')
         call check_true(error, abs(model%energy(0.0_dp, y)) < huge(1.0_dp), 'E not finite')
         if (allocated(error)) return
      end do
      ! the radial fall: r − r_eq = a cos ωt + b sin ωt = 0 − r_eq first at t_hit
      req = model%r_eq(); w = sqrt(model%k/model%m)
      a = 0.2_dp - req; b = -6.0_dp/w
      ! a cos ωt + b sin ωt = √(a² + b²) cos(ωt − δ), δ = atan2(b, a): the first of
      ! ωt = δ ± acos(−r_eq/√(a² + b²)) (mod 2π)
      t_hit = min(modulo(atan2(b, a) + acos(-req/hypot(a, b)), 2.0_dp*pi), &
                  modulo(atan2(b, a) - acos(-req/hypot(a, b)), 2.0_dp*pi))/w
      line = 'radial fall onto the pin at t_hit = '//real_str(t_hit, 6)//' s; runs end at:'
      worst = 0.0_dp
      do i = 1, n_methods
         name = trim(method_table(i)%name)
         call new_integrator(name, integ, err)
         call integ%check_model(model, err)
         if (allocated(err)) cycle
         z = integ%to_internal(model, [0.2_dp, -half_pi], [-6.0_dp, 0.0_dp])
         t = 0.0_dp
         h = merge(0.0_dp, 1e-3_dp, method_table(i)%adaptive)
         call advance_to(integ, model, t, z, 1.0_dp, h, stat)
         line = line//' '//name//' '//real_str(t, 4)
         worst = max(worst, abs(t - t_hit))
         call check_true(error, stat /= stat_ok, name//' went through the pin')
         call check_true(error, abs(t - t_hit) < 0.02_dp, name//' stopped at t = '// &
                         real_str(t, 6)//' s: '//status_message(stat))
         if (allocated(error)) return
      end do
      call report(line//'; max |t - t_hit| '//real_str(worst, 2)//' s')
   end subroutine test_collapse
end module test_elastic
