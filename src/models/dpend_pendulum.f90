!> The compound double pendulum of the chapter (docs/physics.md#reference): two uniform
!> rods on pin joints, angles q1, q2 measured from the horizontal x axis,
!> counter-clockwise positive, y up, SI units.
!>
!> The equations of motion come from the corrected Newton–Euler equations
!> (docs/errata.md); Lagrange's equations are derived independently and kept as
!> a cross-check; the Hamiltonian form H(q, p) serves the symplectic methods.
!>
!> With k = m2 L1 L2 / 2 and d = q1 - q2 the mass matrix is
!>   M11 = (m1/3 + m2) L1²,  M12 = k cos d,  M22 = m2 L2²/3,
!> and the potential energy V = (m1/2 + m2) g L1 sin q1 + m2 g (L2/2) sin q2.
!>
!> The module holds, once, every formula of the double pendulum (equations of motion,
!> energy, Hamiltonian form, Jacobians, kinematics, joint reactions, energy shells)
!> and `double_pendulum_t`, which binds the model interface (`dpend_model`) to them:
!> one translation unit, so that the bindings inline the formulas.
module dpend_pendulum
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: check_parameter, parameter_mass, parameter_length, &
                           parameter_gravity, check_range, max_length, max_mass, &
                           finite_positive
   use dpend_model, only: model_t
   use dpend_strings, only: real_str
   use dpend_link_layout, only: n_link_out, link_out_name, link_out_units, link_out_text, &
                                link_out_rows, rod_coordinate, rod_coordinates_text, rod_figure, &
                                n_alias_out, alias_out_name, alias_out_units, &
                                alias_out_text, chain_from_aliases, body_text
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: qp => real128
   implicit none
   private
   public :: pendulum_t, validate, mass_matrix, generalized_forces
   public :: qddot_newton_euler, qddot_lagrange, qddot
   public :: kinetic_energy, potential_energy, energy
   public :: momenta, velocities, hamiltonian, dh_dq, dh_dp
   public :: rhs_qqdot, rhs_qp, energy_scale, jacobian_qqdot, jacobian_qp
   public :: qddot_trig, rhs_qp_trig, sin_cos, sin_cos_near, energy_gradient
   public :: shell_state, shell_p_max, energy_limit
   public :: kinematics_t, kinematics, tip_position, reactions
   public :: double_pendulum_t, pendulum_model
   public :: hamiltonian_qp
   ! links of any mass distribution
   public :: body_rod, body_general, check_bodies, body_constants, body_kind_name
   public :: rhs_qp_trig_general

   !> The body kind of `pendulum_t`: uniform rods (the chapter's; d_i = l_i/2,
   !> I_i = m_i l_i²/12, the fields d1 … i2 unused) or links of any mass distribution
   !> (d1, d2, i1, i2 given). The rod's formulas keep their own arithmetic (results
   !> bit for bit unchanged by the general bodies); the general ones reduce to them for rod values
   !> (test/test_bodies.f90 compares them).
   integer, parameter :: body_rod = 0
   integer, parameter :: body_general = 1

   !> Physical parameters (SI units). Defaults are the chapter's numerical application.
   type :: pendulum_t
      real(dp) :: m1 = 1.0_dp   !! mass of link 1 [kg]
      real(dp) :: m2 = 1.0_dp   !! mass of link 2 [kg]
      real(dp) :: l1 = 1.0_dp   !! length of link 1 [m]
      real(dp) :: l2 = 1.0_dp   !! length of link 2 [m]
      real(dp) :: g = 9.8_dp    !! gravitational acceleration [m/s²]
      integer :: body = body_rod   !! body_rod (uniform rods) or body_general
      real(dp) :: d1 = 0.5_dp   !! joint A to the centre of mass C1 (body_general) [m]
      real(dp) :: d2 = 0.5_dp   !! joint B to the centre of mass C2 (body_general) [m]
      real(dp) :: i1 = 1.0_dp/12.0_dp  !! inertia of link 1 about C1 (body_general) [kg m²]
      real(dp) :: i2 = 1.0_dp/12.0_dp  !! inertia of link 2 about C2 (body_general) [kg m²]
   end type pendulum_t

   !> Positions [m], velocities [m/s] and accelerations [m/s²] of C1, C2 and B.
   type :: kinematics_t
      real(dp) :: rc1(2) !! position of C1 [m] (6.2)
      real(dp) :: vc1(2) !! velocity of C1 [m/s] (6.6)
      real(dp) :: ac1(2) !! acceleration of C1 [m/s²] (6.10)
      real(dp) :: rc2(2) !! position of C2 [m] (6.4)
      real(dp) :: vc2(2) !! velocity of C2 [m/s] (6.8)
      real(dp) :: ac2(2) !! acceleration of C2 [m/s²] (6.12)
      real(dp) :: rb(2)  !! position of the joint B [m]
      real(dp) :: vb(2)  !! velocity of B [m/s]
      real(dp) :: ab(2)  !! acceleration of B [m/s²]
   end type kinematics_t

   !> The double pendulum with its parameters (SI units).
   type, extends(model_t) :: double_pendulum_t
      type(pendulum_t) :: par   !! masses, lengths, g
   contains
      procedure :: n_dof => dp_n_dof
      procedure :: name => dp_name
      procedure :: field => dp_field
      procedure :: jacobian => dp_jacobian
      procedure :: energy => dp_energy
      procedure :: energy_scale => dp_energy_scale
      procedure :: potential_energy => dp_potential_energy
      procedure :: kinetic_energy => dp_kinetic_energy
      procedure :: hamiltonian => dp_true
      procedure :: momenta => dp_momenta
      procedure :: velocities => dp_velocities
      procedure :: hamiltonian_value => dp_hamiltonian_value
      procedure :: canonical_field => dp_canonical_field
      procedure :: canonical_jacobian => dp_canonical_jacobian
      procedure :: energy_gradient => dp_energy_gradient
      procedure :: energy_sections => dp_true
      procedure :: section_state => dp_section_state
      procedure :: section_p_max => dp_section_p_max
      procedure :: cache_size => dp_cache_size
      procedure :: fill_cache => dp_fill_cache
      procedure :: fill_cache_field => dp_fill_cache_field
      procedure :: field_near => dp_field_near
      procedure :: canonical_field_near => dp_canonical_field_near
      procedure :: n_outputs => dp_n_outputs
      procedure :: output_info => dp_output_info
      procedure :: outputs => dp_outputs
      procedure :: n_parameters => dp_n_parameters
      procedure :: parameter => dp_parameter
      procedure :: coordinate => dp_coordinate
      procedure :: coordinates_text => dp_coordinates_text
      procedure :: figure => dp_figure
      ! H in quadruple precision for the study's roundoff runs
      procedure :: has_hamiltonian_qp => dp_true
      procedure :: hamiltonian_qp => dp_hamiltonian_qp
      ! sweep (one construction site): the G_i of its potential
      procedure :: potential_weights => dp_potential_weights
      ! the links' mass distribution
      procedure :: body_description => dp_body_description
      procedure :: time_unit => dp_time_unit
      procedure :: rest_state => dp_rest_state
   end type double_pendulum_t

contains

   ! ---- public entry points of the hot formulas; the bodies (`*_impl`) are private,
   ! so that the model bindings in this module can inline them (a public procedure
   ! compiled with -fPIC could be interposed, and gcc does not inline it)
   pure function sin_cos(q) result(sc)
      real(dp), intent(in) :: q(2)  !! angles [rad]
      real(dp) :: sc(4)
      sc = sin_cos_impl(q)
   end function sin_cos

   pure function sin_cos_near(sc0, q, d) result(sc)
      real(dp), intent(in) :: sc0(4)  !! sin_cos(q - d)
      real(dp), intent(in) :: q(2)    !! the angles [rad]
      real(dp), intent(in) :: d(2)    !! their offset from the angles of sc0 [rad]
      real(dp) :: sc(4)
      sc = sin_cos_near_impl(sc0, q, d)
   end function sin_cos_near

   pure function qddot_trig(par, sc, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      real(dp) :: c1, s1, c2, s2, h2, m2l1, m2h2, a0x, a0y, a11, a12, a22, b1, b2, rdet
      include 'dpend_qddot_trig_body.inc'
   end function qddot_trig

   pure function rhs_qp_trig(par, sc, z) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: z(4)         !! canonical state
      real(dp) :: f(4)
      if (par%body /= body_rod) then   ! links of any mass distribution
         f = rhs_qp_trig_general(par, sc, z)
         return
      end if
      f = rhs_qp_trig_impl(par, sc, z)
   end function rhs_qp_trig

   pure function rhs_qqdot(par, y) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: y(4)         !! state [rad, rad, rad/s, rad/s]
      real(dp) :: f(4)
      f = rhs_qqdot_impl(par, y)
   end function rhs_qqdot

   pure function rhs_qp(par, z) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: z(4)         !! canonical state
      real(dp) :: f(4)
      f = rhs_qp_trig(par, sin_cos(z(1:2)), z)
   end function rhs_qp

   !> Check that every parameter is finite and within its accepted range
   !> (`dpend_limits`: [1e-6, 1e6] each, so that no product of the model overflows).
   subroutine validate(par, error)
      type(pendulum_t), intent(in) :: par               !! parameters to check
      type(error_t), allocatable, intent(out) :: error  !! set if a value is invalid
      character(len=*), parameter :: names(5) = ['m1', 'm2', 'l1', 'l2', 'g ']
      integer, parameter :: rows(5) = [parameter_mass, parameter_mass, parameter_length, &
                                       parameter_length, parameter_gravity]
      real(dp) :: x(5)
      integer :: i
      x = [par%m1, par%m2, par%l1, par%l2, par%g]
      do i = 1, 5
         call check_parameter(rows(i), trim(names(i)), x(i), error)
         if (allocated(error)) return
      end do
      if (par%body /= body_rod) call check_bodies([par%m1, par%m2], [par%l1, par%l2], &
                                                  [par%d1, par%d2], [par%i1, par%i2], error)
   end subroutine validate

   !> Check the mass distribution of links with masses m and lengths l (checked
   !> before): d_i (joint i to the centre of mass C_i, along the link) in
   !> [0, max_length] m, I_i (about C_i) in [0, max_mass max_length²] kg m², and each
   !> link's inertia about its own joint, I_i + m_i d_i², at least 1e-12 m_i l_i²:
   !> without it the link (a point mass on its own pin) has no inertia to turn, and
   !> the mass matrix is singular (for the last link everywhere, for another where the
   !> links align). d_i > l_i is accepted (a bob beyond the next pin or the tip);
   !> d_i < 0 (a counterweight behind the pin) is not: d is measured from the joint
   !> towards the link's far end.
   subroutine check_bodies(m, l, d, inertia, error)
      real(dp), intent(in) :: m(:)                      !! masses [kg]
      real(dp), intent(in) :: l(:)                      !! lengths [m]
      real(dp), intent(in) :: d(:)                      !! joint to centre of mass [m]
      real(dp), intent(in) :: inertia(:)                !! inertia about C_i [kg m²]
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      character(len=20) :: k
      integer :: i
      do i = 1, size(m)
         write (k, '(i0)') i
         call check_range('com'//trim(k), d(i), 0.0_dp, max_length, 'm', error, &
                          'the distance from joint '//trim(k)//' to the centre of mass ' &
                          //'of link '//trim(k)//' along the link')
         if (allocated(error)) return
         call check_range('inertia'//trim(k), inertia(i), 0.0_dp, max_mass*max_length**2, &
                          'kg m^2', error, 'the moment of inertia of link '//trim(k) &
                          //' about its centre of mass')
         if (allocated(error)) return
         if (.not. inertia(i) + m(i)*d(i)**2 >= 1e-12_dp*m(i)*l(i)**2) then
            call fatal_error(error, 'invalid com'//trim(k)//', inertia'//trim(k)//': com' &
                             //trim(k)//' = '//real_str(d(i))//' m with inertia'//trim(k)//' = ' &
                             //real_str(inertia(i))//' kg m^2 leaves link '//trim(k) &
                             //' no inertia about its joint (inertia + m com^2 must be at ' &
                             //'least 1e-12 m l^2, else the mass matrix is singular)')
            return
         end if
      end do
   end subroutine check_bodies

   !> The constants of a general two-link body (`body_general`): M11 = I1 + m1 d1² +
   !> m2 l1², M22 = I2 + m2 d2² [kg m²], k = m2 l1 d2 (M12 = k cos(q1 − q2)) [kg m²],
   !> and V = ga sin q1 + gb sin q2 with ga = g (m1 d1 + m2 l1), gb = g m2 d2 [J].
   !> The rod's formulas keep their own arithmetic; for rod values these agree with
   !> them to rounding.
   pure function body_constants(par) result(c)
      type(pendulum_t), intent(in) :: par  !! parameters (any body kind: d, I used)
      real(dp) :: c(5)                     !! (M11, M22, k, ga, gb)
      c(1) = par%i1 + par%m1*par%d1**2 + par%m2*par%l1**2
      c(2) = par%i2 + par%m2*par%d2**2
      c(3) = par%m2*par%l1*par%d2
      c(4) = par%g*(par%m1*par%d1 + par%m2*par%l1)
      c(5) = par%g*par%m2*par%d2
   end function body_constants

   !> 'rod', 'point' (d_i = l_i, I_i = 0) or 'general': the body of a parameter set.
   pure function body_kind_name(par) result(name)
      type(pendulum_t), intent(in) :: par  !! parameters
      character(len=:), allocatable :: name
      if (par%body == body_rod) then
         name = 'rod'
      else if (par%d1 == par%l1 .and. par%d2 == par%l2 .and. par%i1 == 0.0_dp &
               .and. par%i2 == 0.0_dp) then
         name = 'point'
      else
         name = 'general'
      end if
   end function body_kind_name

   !> Constant i of `body_constants` (M11, M22, k, ga, gb).
   pure real(dp) function body_constant(par, i) result(x)
      type(pendulum_t), intent(in) :: par  !! parameters
      integer, intent(in) :: i             !! which
      real(dp) :: c(5)
      c = body_constants(par)
      x = c(i)
   end function body_constant

   !> `mass_matrix` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function mass_matrix_general(par, q) result(m)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: m(2, 2)
      m(1, 1) = body_constant(par, 1)
      m(1, 2) = body_constant(par, 3)*cos(q(1) - q(2))
      m(2, 1) = m(1, 2)
      m(2, 2) = body_constant(par, 2)
   end function mass_matrix_general

   !> `generalized_forces` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function generalized_forces_general(par, q) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: f(2)
      f(1) = -body_constant(par, 4)*cos(q(1))
      f(2) = -body_constant(par, 5)*cos(q(2))
   end function generalized_forces_general

   !> `qddot_lagrange` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function qddot_lagrange_general(par, q, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      real(dp) :: m(2, 2), r(2), k, sd, det
      m = mass_matrix(par, q)
      k = body_constant(par, 3)
      sd = sin(q(1) - q(2))
      r = generalized_forces(par, q) - [k*sd*qd(2)**2, -k*sd*qd(1)**2]
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      qdd(1) = (m(2, 2)*r(1) - m(1, 2)*r(2))/det
      qdd(2) = (m(1, 1)*r(2) - m(1, 2)*r(1))/det
   end function qddot_lagrange_general

   !> `potential_energy` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure real(dp) function potential_energy_general(par, q)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      potential_energy_general = body_constant(par, 4)*sin(q(1)) + body_constant(par, 5)*sin(q(2))
   end function potential_energy_general

   !> `energy_scale` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure real(dp) function energy_scale_general(par, e0)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: e0           !! initial energy [J]
      real(dp) :: e_ref
      e_ref = body_constant(par, 4) + body_constant(par, 5)
      energy_scale_general = merge(abs(e0), e_ref, abs(e0) >= 1e-3_dp*e_ref)
   end function energy_scale_general

   !> `dh_dq` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function dh_dq_general(par, q, p) result(g)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: p(2)         !! canonical momenta [kg m²/s]
      real(dp) :: g(2)
      real(dp) :: qd(2), t
      qd = velocities(par, q, p)
      t = body_constant(par, 3)*sin(q(1) - q(2))*qd(1)*qd(2)
      g = [t, -t] - generalized_forces(par, q)
   end function dh_dq_general

   !> `energy_limit` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure real(dp) function energy_limit_general(par, w_max)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: w_max        !! angular velocity [rad/s]
      real(dp) :: m11, m22, k
      m11 = body_constant(par, 1)
      m22 = body_constant(par, 2)
      k = body_constant(par, 3)
      energy_limit_general = body_constant(par, 4) + body_constant(par, 5) &
                     + 0.5_dp*w_max**2*(m11 + m22 + 2.0_dp*k)
   end function energy_limit_general

   !> `energy_gradient` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function energy_gradient_general(par, q, qd) result(g)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: g(4)
      real(dp) :: t
      t = body_constant(par, 3)*sin(q(1) - q(2))*qd(1)*qd(2)
      g(1:2) = -generalized_forces(par, q) + [-t, t]
      g(3:4) = momenta(par, q, qd)
   end function energy_gradient_general

   !> `rhs_qp_trig_impl` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`. Public, so that gcc (-fPIC) keeps it out of
   !> line: the canonical field bindings branch to it before the rods' inlined formula.
   pure function rhs_qp_trig_general(par, sc, z) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: z(4)         !! canonical state [rad, rad, kg m²/s, kg m²/s]
      real(dp) :: f(4)
      real(dp) :: k, cd, sd, m11, m12, m22, rdet, t
      k = body_constant(par, 3)
      cd = sc(3)*sc(4) + sc(1)*sc(2)
      sd = sc(1)*sc(4) - sc(3)*sc(2)
      m11 = body_constant(par, 1)
      m12 = k*cd
      m22 = body_constant(par, 2)
      rdet = 1.0_dp/(m11*m22 - m12*m12)
      f(1) = (m22*z(3) - m12*z(4))*rdet
      f(2) = (m11*z(4) - m12*z(3))*rdet
      t = k*sd*f(1)*f(2)
      f(3) = -body_constant(par, 4)*sc(3) - t
      f(4) = -body_constant(par, 5)*sc(4) + t
   end function rhs_qp_trig_general

   !> `jacobian_qqdot` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function jacobian_qqdot_general(par, y) result(jac)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: y(4)         !! state (q, q̇)
      real(dp) :: jac(4, 4)
      real(dp) :: m(2, 2), minv(2, 2), a(2), k, sd, cd, dr(2, 4), dma(2, 4), det
      m = mass_matrix(par, y(1:2))
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      minv = reshape([m(2, 2), -m(1, 2), -m(1, 2), m(1, 1)], [2, 2])/det
      a = qddot_lagrange(par, y(1:2), y(3:4))
      k = body_constant(par, 3)
      sd = sin(y(1) - y(2)); cd = cos(y(1) - y(2))
      ! ∂r/∂(q1, q2, q̇1, q̇2)
      dr(1, :) = [body_constant(par, 4)*sin(y(1)) - k*cd*y(4)**2, &
                  k*cd*y(4)**2, 0.0_dp, -2.0_dp*k*sd*y(4)]
      dr(2, :) = [k*cd*y(3)**2, body_constant(par, 5)*sin(y(2)) - k*cd*y(3)**2, &
                  2.0_dp*k*sd*y(3), 0.0_dp]
      ! (∂M/∂x) q̈: only M12 = k cos(q1 - q2) depends on q
      dma = 0.0_dp
      dma(:, 1) = -k*sd*[a(2), a(1)]
      dma(:, 2) = k*sd*[a(2), a(1)]
      jac = 0.0_dp
      jac(1, 3) = 1.0_dp
      jac(2, 4) = 1.0_dp
      jac(3:4, :) = matmul(minv, dr - dma)
   end function jacobian_qqdot_general

   !> `jacobian_qp` for links of any mass distribution: the same formula
   !> with the constants of `body_constants`.
   pure function jacobian_qp_general(par, z) result(jac)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: z(4)         !! canonical state (q, p)
      real(dp) :: jac(4, 4)
      real(dp) :: m(2, 2), minv(2, 2), qd(2), k, sd, cd, det, dqd(2, 4), dphi(4)
      m = mass_matrix(par, z(1:2))
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      minv = reshape([m(2, 2), -m(1, 2), -m(1, 2), m(1, 1)], [2, 2])/det
      qd = matmul(minv, z(3:4))
      k = body_constant(par, 3)
      sd = sin(z(1) - z(2)); cd = cos(z(1) - z(2))
      ! ∂q̇/∂(q1, q2, p1, p2); (∂M/∂q1) q̇ = -k sd (q̇2, q̇1), (∂M/∂q2) q̇ = +k sd (q̇2, q̇1)
      dqd(:, 1) = matmul(minv, k*sd*[qd(2), qd(1)])
      dqd(:, 2) = -dqd(:, 1)
      dqd(:, 3:4) = minv
      dphi = k*sd*(dqd(1, :)*qd(2) + qd(1)*dqd(2, :))
      dphi(1) = dphi(1) + k*cd*qd(1)*qd(2)
      dphi(2) = dphi(2) - k*cd*qd(1)*qd(2)
      jac(1:2, :) = dqd
      jac(3, :) = -dphi
      jac(4, :) = dphi
      jac(3, 1) = jac(3, 1) + body_constant(par, 4)*sin(z(1))
      jac(4, 2) = jac(4, 2) + body_constant(par, 5)*sin(z(2))
   end function jacobian_qp_general

   !> Mass matrix M(q) of Lagrange's equations [kg m²].
   pure function mass_matrix(par, q) result(m)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: m(2, 2)
      if (par%body /= body_rod) then   ! links of any mass distribution
         m = mass_matrix_general(par, q)
         return
      end if
      m(1, 1) = (par%m1/3.0_dp + par%m2)*par%l1**2
      m(1, 2) = 0.5_dp*par%m2*par%l1*par%l2*cos(q(1) - q(2))
      m(2, 1) = m(1, 2)
      m(2, 2) = par%m2*par%l2**2/3.0_dp
   end function mass_matrix


   !> Generalized gravity forces Q = -dV/dq [N m].
   pure function generalized_forces(par, q) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: f(2)
      if (par%body /= body_rod) then   ! links of any mass distribution
         f = generalized_forces_general(par, q)
         return
      end if
      f(1) = -(0.5_dp*par%m1 + par%m2)*par%g*par%l1*cos(q(1))
      f(2) = -0.5_dp*par%m2*par%g*par%l2*cos(q(2))
   end function generalized_forces

   !> Angular accelerations from the corrected Newton–Euler equations [rad/s²].
   !>
   !> Unknowns q̈1, q̈2 with the joint reaction F21 eliminated through
   !> (6.22) F21x = -m2 ẍC2 and (6.23, corrected 6.26) F21y = -m2 (ÿC2 + g), where
   !> a_C2 = a0 + q̈1 L1 (-sin q1, cos q1) + q̈2 (L2/2)(-sin q2, cos q2) and a0 holds the
   !> centripetal terms. Substituted into (6.19) and the corrected (6.24)
   !>   I_A q̈1  = -m1 g (L1/2) cos q1 + L1 (F21y cos q1 - F21x sin q1)
   !>   I_C2 q̈2 = (L2/2)(F21y cos q2 - F21x sin q2)
   !> they give a 2×2 linear system solved by Cramer's rule.
   pure function qddot_newton_euler(par, q, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      qdd = qddot_trig_impl(par, sin_cos_impl(q), qd)
   end function qddot_newton_euler

   !> The corrected Newton–Euler accelerations (see `qddot_newton_euler`) from the
   !> sines and cosines of the angles, sc = (sin q1, sin q2, cos q1, cos q2), so that
   !> a caller who has them (rk4's stages, via `sin_cos_near`) need not recompute them.
   pure function qddot_trig_impl(par, sc, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      real(dp) :: c1, s1, c2, s2, h2, m2l1, m2h2, a0x, a0y, a11, a12, a22, b1, b2, rdet
      include 'dpend_qddot_trig_body.inc'
   end function qddot_trig_impl

   !> `qddot_trig_impl` for links of any mass distribution: the same
   !> corrected Newton–Euler equations with C_i at d_i along link i and I_Ci = I_i,
   !>   I_A1 q̈1 = −m1 g d1 cos q1 + L1 (F21y cos q1 − F21x sin q1),  I_A1 = I1 + m1 d1²,
   !>   I2 q̈2 = d2 (F21y cos q2 − F21x sin q2),  F21 = −m2 (a_C2 + g j),
   !> a_C2 = a0 + q̈1 L1 n1 + q̈2 d2 n2 (a0 the centripetal part), solved by Cramer's rule.
   pure function qddot_trig_general(par, sc, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters (body_general)
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      real(dp) :: c1, s1, c2, s2, m2l1, m2d2, a0x, a0y, a11, a12, a22, b1, b2, rdet
      s1 = sc(1); s2 = sc(2); c1 = sc(3); c2 = sc(4)
      m2l1 = par%m2*par%l1
      m2d2 = par%m2*par%d2
      a0x = -par%l1*qd(1)**2*c1 - par%d2*qd(2)**2*c2
      a0y = -par%l1*qd(1)**2*s1 - par%d2*qd(2)**2*s2
      a11 = par%i1 + par%m1*par%d1**2 + m2l1*par%l1
      a12 = m2l1*par%d2*(c1*c2 + s1*s2)
      b1 = -par%m1*par%g*par%d1*c1 - m2l1*((a0y + par%g)*c1 - a0x*s1)
      a22 = par%i2 + m2d2*par%d2
      b2 = -m2d2*((a0y + par%g)*c2 - a0x*s2)
      rdet = 1.0_dp/(a11*a22 - a12*a12)
      qdd(1) = (b1*a22 - a12*b2)*rdet
      qdd(2) = (a11*b2 - a12*b1)*rdet
   end function qddot_trig_general

   !> (sin q1, sin q2, cos q1, cos q2) as one 4-wide sine, cos q = sin(q + π/2), so that
   !> the release build calls glibc's vector sine (libmvec) once instead of two scalar
   !> sincos (19 ns → 7 ns on AVX-512). The rounding of q + π/2 adds at most
   !> ulp(q)/2 absolute to cos q: the size of the rounding already carried by q.
   pure function sin_cos_impl(q) result(sc)
      real(dp), intent(in) :: q(2)  !! angles [rad]
      real(dp) :: sc(4)
      real(dp), parameter :: half_pi = 0.5_dp*acos(-1.0_dp)
      real(dp) :: x(4)
      integer :: i
      x = [q(1), q(2), q(1) + half_pi, q(2) + half_pi]
      do i = 1, 4
         sc(i) = sin(x(i))
      end do
   end function sin_cos_impl

   !> (sin, cos) of the angles q = q0 + d from sc0 = sin_cos_impl(q0), for small d: the
   !> angle-addition formulas with sin d and cos d - 1 from their Taylor series,
   !> truncated where the remainder is below 1e-17 for |d| ≤ 0.25 rad (13th and 14th
   !> powers). Agrees with sin_cos_impl(q) to a few ulp; the rounding of q0 + d, which
   !> sin_cos_impl(q) would see, is ulp(q)/2 as in `sin_cos`. For |d| > 0.25 it calls
   !> sin_cos_impl(q). Explicit Runge–Kutta stages differ from the step start by
   !> d = h Σ a_ij q̇_j, so rk4 evaluates the sine once per step instead of 4 times.
   pure function sin_cos_near_impl(sc0, q, d) result(sc)
      real(dp), intent(in) :: sc0(4)  !! sin_cos_impl(q - d)
      real(dp), intent(in) :: q(2)    !! the angles [rad]
      real(dp), intent(in) :: d(2)    !! their offset from the angles of sc0 [rad]
      real(dp) :: sc(4)
      real(dp), parameter :: d_max = 0.25_dp
      real(dp) :: d2(2), sd(2), cm1(2)
      if (abs(d(1)) > d_max .or. abs(d(2)) > d_max) then
         sc = sin_cos_impl(q)
         return
      end if
      d2 = d*d
      sd = d*(1.0_dp + d2*(-1.0_dp/6.0_dp + d2*(1.0_dp/120.0_dp + d2*(-1.0_dp/5040.0_dp &
           + d2*(1.0_dp/362880.0_dp + d2*(-1.0_dp/39916800.0_dp))))))
      cm1 = d2*(-0.5_dp + d2*(1.0_dp/24.0_dp + d2*(-1.0_dp/720.0_dp + d2*(1.0_dp/40320.0_dp &
            + d2*(-1.0_dp/3628800.0_dp + d2*(1.0_dp/479001600.0_dp))))))
      sc(1:2) = sc0(1:2) + (sc0(1:2)*cm1 + sc0(3:4)*sd)
      sc(3:4) = sc0(3:4) + (sc0(3:4)*cm1 - sc0(1:2)*sd)
   end function sin_cos_near_impl


   !> Angular accelerations from Lagrange's equations M(q) q̈ = Q(q) - c(q, q̇) [rad/s²],
   !> with c1 = k sin(q1-q2) q̇2², c2 = -k sin(q1-q2) q̇1², k = m2 L1 L2/2.
   pure function qddot_lagrange(par, q, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      real(dp) :: m(2, 2), r(2), k, sd, det
      if (par%body /= body_rod) then   ! links of any mass distribution
         qdd = qddot_lagrange_general(par, q, qd)
         return
      end if
      m = mass_matrix(par, q)
      k = 0.5_dp*par%m2*par%l1*par%l2
      sd = sin(q(1) - q(2))
      r = generalized_forces(par, q) - [k*sd*qd(2)**2, -k*sd*qd(1)**2]
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      qdd(1) = (m(2, 2)*r(1) - m(1, 2)*r(2))/det
      qdd(2) = (m(1, 1)*r(2) - m(1, 2)*r(1))/det
   end function qddot_lagrange

   !> The accelerations used by the integrators: the corrected Newton–Euler form.
   pure function qddot(par, q, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      qdd = qddot_newton_euler(par, q, qd)
   end function qddot

   !> Kinetic energy ½ q̇ᵀ M(q) q̇ [J].
   pure real(dp) function kinetic_energy(par, q, qd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: m(2, 2)
      m = mass_matrix(par, q)
      kinetic_energy = 0.5_dp*(m(1, 1)*qd(1)**2 + 2.0_dp*m(1, 2)*qd(1)*qd(2) &
                               + m(2, 2)*qd(2)**2)
   end function kinetic_energy


   !> Potential energy V(q), zero with both links horizontal (y = 0 at the pin A) [J].
   pure real(dp) function potential_energy(par, q)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      if (par%body /= body_rod) then   ! links of any mass distribution
         potential_energy = potential_energy_general(par, q)
         return
      end if
      potential_energy = (0.5_dp*par%m1 + par%m2)*par%g*par%l1*sin(q(1)) &
                         + 0.5_dp*par%m2*par%g*par%l2*sin(q(2))
   end function potential_energy

   !> Total mechanical energy T + V [J].
   pure real(dp) function energy(par, q, qd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      energy = kinetic_energy(par, q, qd) + potential_energy(par, q)
   end function energy


   !> Energy unit for relative energy errors [J]: |E0| when it is at least 1e-3 of
   !> E_ref = V(π/2, π/2) = (m1/2 + m2) g L1 + (m2/2) g L2 (both links upright),
   !> and E_ref itself when E0 ≈ 0 (e.g. both links released horizontally).
   pure real(dp) function energy_scale(par, e0)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: e0           !! initial energy [J]
      real(dp) :: e_ref
      if (par%body /= body_rod) then   ! links of any mass distribution
         energy_scale = energy_scale_general(par, e0)
         return
      end if
      e_ref = (0.5_dp*par%m1 + par%m2)*par%g*par%l1 + 0.5_dp*par%m2*par%g*par%l2
      energy_scale = merge(abs(e0), e_ref, abs(e0) >= 1e-3_dp*e_ref)
   end function energy_scale

   !> Canonical momenta p = M(q) q̇ [kg m²/s].
   pure function momenta(par, q, qd) result(p)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: p(2)
      p = matmul(mass_matrix(par, q), qd)
   end function momenta

   !> Angular velocities q̇ = M(q)⁻¹ p = ∂H/∂p [rad/s].
   pure function velocities(par, q, p) result(qd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: p(2)         !! canonical momenta [kg m²/s]
      real(dp) :: qd(2)
      real(dp) :: m(2, 2), det
      m = mass_matrix(par, q)
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      qd(1) = (m(2, 2)*p(1) - m(1, 2)*p(2))/det
      qd(2) = (m(1, 1)*p(2) - m(1, 2)*p(1))/det
   end function velocities

   !> Hamiltonian H(q, p) = ½ pᵀ M(q)⁻¹ p + V(q) [J].
   pure real(dp) function hamiltonian(par, q, p)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: p(2)         !! canonical momenta [kg m²/s]
      real(dp) :: qd(2)
      qd = velocities(par, q, p)
      hamiltonian = 0.5_dp*(p(1)*qd(1) + p(2)*qd(2)) + potential_energy(par, q)
   end function hamiltonian

   !> ∂H/∂p = M(q)⁻¹ p [rad/s].
   pure function dh_dp(par, q, p) result(g)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: p(2)         !! canonical momenta [kg m²/s]
      real(dp) :: g(2)
      g = velocities(par, q, p)
   end function dh_dp


   !> ∂H/∂q [J/rad]. Only M12 depends on q (through d = q1 - q2):
   !> ∂/∂d (½ pᵀM⁻¹p) = -½ q̇ᵀ (∂M/∂d) q̇ = k sin d q̇1 q̇2.
   pure function dh_dq(par, q, p) result(g)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: p(2)         !! canonical momenta [kg m²/s]
      real(dp) :: g(2)
      real(dp) :: qd(2), t
      if (par%body /= body_rod) then   ! links of any mass distribution
         g = dh_dq_general(par, q, p)
         return
      end if
      qd = velocities(par, q, p)
      t = 0.5_dp*par%m2*par%l1*par%l2*sin(q(1) - q(2))*qd(1)*qd(2)
      g = [t, -t] - generalized_forces(par, q)   ! dH/dq of the rods
   end function dh_dq

   !> The state on the section with q_s = angle, q_o, p_o given and H = E (see dpend_poincare); `found` is false outside the energy shell. direction: sign
   !> of q̇_s (−1 negative, otherwise positive).
   pure subroutine shell_state(par, e, link, angle, direction, q_o, p_o, q, qd, found)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: e            !! energy [J]
      integer, intent(in) :: link          !! section link s (1 or 2)
      real(dp), intent(in) :: angle        !! section angle [rad]
      integer, intent(in) :: direction     !! crossing direction
      real(dp), intent(in) :: q_o          !! other link's angle [rad]
      real(dp), intent(in) :: p_o          !! other link's momentum [kg m²/s]
      real(dp), intent(out) :: q(2)        !! angles [rad]
      real(dp), intent(out) :: qd(2)       !! angular velocities [rad/s]
      logical, intent(out) :: found        !! (q_o, p_o) lies inside the shell
      integer :: o
      real(dp) :: a, b, det_inv, disc, qd_s, p(2), m(2, 2)
      o = 3 - link
      q(link) = angle; q(o) = q_o
      m = mass_matrix(par, q)
      det_inv = 1.0_dp/(m(1, 1)*m(2, 2) - m(1, 2)**2)
      a = m(o, o)*det_inv            ! (M⁻¹)_ss
      b = -m(1, 2)*det_inv           ! (M⁻¹)_so
      disc = 2.0_dp*a*(e - potential_energy(par, q)) - det_inv*p_o**2
      found = disc > 0.0_dp
      qd = 0.0_dp
      if (.not. found) return
      qd_s = sqrt(disc)
      if (direction < 0) qd_s = -qd_s
      p(o) = p_o
      p(link) = (qd_s - b*p_o)/a
      qd = velocities(par, q, p)
   end subroutine shell_state

   !> Largest |p_o| on the energy shell of the section (0 if the shell is empty),
   !> from q̇_s² ≥ 0 maximised over a grid of 1441 values of q_o, plus 2 %.
   pure real(dp) function shell_p_max(par, e, link, angle)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: e            !! energy [J]
      integer, intent(in) :: link          !! section link (1 or 2)
      real(dp), intent(in) :: angle        !! section angle [rad]
      real(dp) :: q(2), m(2, 2), det_inv, a, x
      integer :: i
      shell_p_max = 0.0_dp
      q(link) = angle
      do i = 0, 1440
         q(3 - link) = -pi + 2.0_dp*pi*real(i, dp)/1440.0_dp
         m = mass_matrix(par, q)
         det_inv = 1.0_dp/(m(1, 1)*m(2, 2) - m(1, 2)**2)
         a = m(3 - link, 3 - link)*det_inv
         x = 2.0_dp*a*(e - potential_energy(par, q))/det_inv
         if (x > 0.0_dp) shell_p_max = max(shell_p_max, sqrt(x))
      end do
      shell_p_max = 1.02_dp*shell_p_max
   end function shell_p_max


   !> Largest |energy| accepted for a Poincaré section: both links upright plus the
   !> kinetic energy of angular velocities w_max [J].
   pure real(dp) function energy_limit(par, w_max)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: w_max        !! angular velocity [rad/s]
      real(dp) :: m11, m22, k
      if (par%body /= body_rod) then   ! links of any mass distribution
         energy_limit = energy_limit_general(par, w_max)
         return
      end if
      m11 = (par%m1/3.0_dp + par%m2)*par%l1**2
      m22 = par%m2*par%l2**2/3.0_dp
      k = 0.5_dp*par%m2*par%l1*par%l2
      energy_limit = (0.5_dp*par%m1 + par%m2)*par%g*par%l1 + 0.5_dp*par%m2*par%g*par%l2 &
                     + 0.5_dp*w_max**2*(m11 + m22 + 2.0_dp*k)
   end function energy_limit


   !> Gradient of the energy in (q, q̇): ∂E/∂q = -Q(q) + ∂T/∂q with
   !> ∂T/∂q1 = -k sin(q1 - q2) q̇1 q̇2 = -∂T/∂q2, and ∂E/∂q̇ = M(q) q̇ = p.
   pure function energy_gradient(par, q, qd) result(g)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: g(4)
      real(dp) :: t
      if (par%body /= body_rod) then   ! links of any mass distribution
         g = energy_gradient_general(par, q, qd)
         return
      end if
      t = 0.5_dp*par%m2*par%l1*par%l2*sin(q(1) - q(2))*qd(1)*qd(2)
      g(1:2) = -generalized_forces(par, q) + [-t, t]
      g(3:4) = momenta(par, q, qd)
   end function energy_gradient

   !> First-order right-hand side for y = (q1, q2, q̇1, q̇2): (q̇, q̈).
   pure function rhs_qqdot_impl(par, y) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: y(4)         !! state [rad, rad, rad/s, rad/s]
      real(dp) :: f(4)
      f(1:2) = y(3:4)
      f(3:4) = qddot(par, y(1:2), y(3:4))
   end function rhs_qqdot_impl

   !> `rhs_qp` from sc = (sin q1, sin q2, cos q1, cos q2), for callers that have them
   !> (the implicit stages of the symplectic methods, via `sin_cos_near`):
   !> cos(q1 - q2) and sin(q1 - q2) by the subtraction formulas. Uniform rods only: its
   !> callers (`rhs_qp_trig`, `dp_canonical_field`, `dp_canonical_field_near`) send other
   !> bodies to `rhs_qp_trig_general` first. Kept to these three call sites and free of
   !> that branch so that gcc inlines it into the two bindings, the implicit methods' hot
   !> path (a branch here kept gcc from it: implicit midpoint 519 → 610 ns per
   !> step; docs/performance.md).
   pure function rhs_qp_trig_impl(par, sc, z) result(f)
      type(pendulum_t), intent(in) :: par  !! parameters (body_rod)
      real(dp), intent(in) :: sc(4)        !! (sin q1, sin q2, cos q1, cos q2)
      real(dp), intent(in) :: z(4)         !! canonical state [rad, rad, kg m²/s, kg m²/s]
      real(dp) :: f(4)
      real(dp) :: k, cd, sd, m11, m12, m22, rdet, t
      k = 0.5_dp*par%m2*par%l1*par%l2
      cd = sc(3)*sc(4) + sc(1)*sc(2)
      sd = sc(1)*sc(4) - sc(3)*sc(2)
      m11 = (par%m1/3.0_dp + par%m2)*par%l1**2
      m12 = k*cd
      m22 = par%m2*par%l2**2/3.0_dp
      rdet = 1.0_dp/(m11*m22 - m12*m12)
      f(1) = (m22*z(3) - m12*z(4))*rdet
      f(2) = (m11*z(4) - m12*z(3))*rdet
      t = k*sd*f(1)*f(2)
      f(3) = -(0.5_dp*par%m1 + par%m2)*par%g*par%l1*sc(3) - t
      f(4) = -0.5_dp*par%m2*par%g*par%l2*sc(4) + t
   end function rhs_qp_trig_impl


   !> Jacobian ∂f/∂y of `rhs_qqdot` for y = (q, q̇), written analytically:
   !> with q̈ = M⁻¹ r, r = Q(q) - c(q, q̇), ∂q̈/∂x = M⁻¹ (∂r/∂x - (∂M/∂x) q̈).
   pure function jacobian_qqdot(par, y) result(jac)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: y(4)         !! state (q, q̇)
      real(dp) :: jac(4, 4)
      real(dp) :: m(2, 2), minv(2, 2), a(2), k, sd, cd, dr(2, 4), dma(2, 4), det
      if (par%body /= body_rod) then   ! links of any mass distribution
         jac = jacobian_qqdot_general(par, y)
         return
      end if
      m = mass_matrix(par, y(1:2))
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      minv = reshape([m(2, 2), -m(1, 2), -m(1, 2), m(1, 1)], [2, 2])/det
      a = qddot_lagrange(par, y(1:2), y(3:4))
      k = 0.5_dp*par%m2*par%l1*par%l2
      sd = sin(y(1) - y(2)); cd = cos(y(1) - y(2))
      ! ∂r/∂(q1, q2, q̇1, q̇2)
      dr(1, :) = [(0.5_dp*par%m1 + par%m2)*par%g*par%l1*sin(y(1)) - k*cd*y(4)**2, &
                  k*cd*y(4)**2, 0.0_dp, -2.0_dp*k*sd*y(4)]
      dr(2, :) = [k*cd*y(3)**2, 0.5_dp*par%m2*par%g*par%l2*sin(y(2)) - k*cd*y(3)**2, &
                  2.0_dp*k*sd*y(3), 0.0_dp]
      ! (∂M/∂x) q̈: only M12 = k cos(q1 - q2) depends on q
      dma = 0.0_dp
      dma(:, 1) = -k*sd*[a(2), a(1)]
      dma(:, 2) = k*sd*[a(2), a(1)]
      jac = 0.0_dp
      jac(1, 3) = 1.0_dp
      jac(2, 4) = 1.0_dp
      jac(3:4, :) = matmul(minv, dr - dma)
   end function jacobian_qqdot


   !> Jacobian ∂f/∂z of `rhs_qp` for z = (q, p), written analytically:
   !> f = (q̇, -∂H/∂q) with q̇ = M⁻¹p, ∂q̇/∂q_j = -M⁻¹ (∂M/∂q_j) q̇, ∂q̇/∂p = M⁻¹, and
   !> -∂H/∂q = (-φ - V_1, φ - V_2), φ = k sin(q1 - q2) q̇1 q̇2.
   pure function jacobian_qp(par, z) result(jac)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: z(4)         !! canonical state (q, p)
      real(dp) :: jac(4, 4)
      real(dp) :: m(2, 2), minv(2, 2), qd(2), k, sd, cd, det, dqd(2, 4), dphi(4)
      if (par%body /= body_rod) then   ! links of any mass distribution
         jac = jacobian_qp_general(par, z)
         return
      end if
      m = mass_matrix(par, z(1:2))
      det = m(1, 1)*m(2, 2) - m(1, 2)**2
      minv = reshape([m(2, 2), -m(1, 2), -m(1, 2), m(1, 1)], [2, 2])/det
      qd = matmul(minv, z(3:4))
      k = 0.5_dp*par%m2*par%l1*par%l2
      sd = sin(z(1) - z(2)); cd = cos(z(1) - z(2))
      ! ∂q̇/∂(q1, q2, p1, p2); (∂M/∂q1) q̇ = -k sd (q̇2, q̇1), (∂M/∂q2) q̇ = +k sd (q̇2, q̇1)
      dqd(:, 1) = matmul(minv, k*sd*[qd(2), qd(1)])
      dqd(:, 2) = -dqd(:, 1)
      dqd(:, 3:4) = minv
      dphi = k*sd*(dqd(1, :)*qd(2) + qd(1)*dqd(2, :))
      dphi(1) = dphi(1) + k*cd*qd(1)*qd(2)
      dphi(2) = dphi(2) - k*cd*qd(1)*qd(2)
      jac(1:2, :) = dqd
      jac(3, :) = -dphi
      jac(4, :) = dphi
      jac(3, 1) = jac(3, 1) + (0.5_dp*par%m1 + par%m2)*par%g*par%l1*sin(z(1))
      jac(4, 2) = jac(4, 2) + 0.5_dp*par%m2*par%g*par%l2*sin(z(2))
   end function jacobian_qp

   ! ---------------------------------------------------------------- kinematics

   !> Kinematics of C1, C2 and B for given q, q̇, q̈.
   pure function kinematics(par, q, qd, qdd) result(k)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp), intent(in) :: qdd(2)       !! angular accelerations [rad/s²]
      type(kinematics_t) :: k
      real(dp) :: u1(2), u2(2), n1(2), n2(2)
      u1 = [cos(q(1)), sin(q(1))]     ! unit vector along link 1
      u2 = [cos(q(2)), sin(q(2))]     ! unit vector along link 2
      n1 = [-u1(2), u1(1)]            ! u1 turned by +90°
      n2 = [-u2(2), u2(1)]
      ! a point at distance s along a link: r = s u, v = s q̇ n, a = s (q̈ n - q̇² u)
      k%rb = par%l1*u1
      k%vb = par%l1*qd(1)*n1
      k%ab = par%l1*(qdd(1)*n1 - qd(1)**2*u1)
      if (par%body /= body_rod) then   ! C_i at d_i along link i
         k%rc1 = par%d1*u1
         k%vc1 = par%d1*qd(1)*n1
         k%ac1 = par%d1*(qdd(1)*n1 - qd(1)**2*u1)
         k%rc2 = k%rb + par%d2*u2
         k%vc2 = k%vb + par%d2*qd(2)*n2
         k%ac2 = k%ab + par%d2*(qdd(2)*n2 - qd(2)**2*u2)
         return
      end if
      k%rc1 = 0.5_dp*k%rb
      k%vc1 = 0.5_dp*k%vb
      k%ac1 = 0.5_dp*k%ab
      k%rc2 = k%rb + 0.5_dp*par%l2*u2
      k%vc2 = k%vb + 0.5_dp*par%l2*qd(2)*n2
      k%ac2 = k%ab + 0.5_dp*par%l2*(qdd(2)*n2 - qd(2)**2*u2)
   end function kinematics

   !> Position of the free end of link 2 [m].
   pure function tip_position(par, q) result(r)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: r(2)
      r = par%l1*[cos(q(1)), sin(q(1))] + par%l2*[cos(q(2)), sin(q(2))]
   end function tip_position

   ! ---------------------------------------------------------------- reactions

   !> F01 and F21 [N] for a state and its accelerations.
   !>
   !> Link 2 (6.22, 6.23): m2 a_C2 = -F21 + G2, so F21 = -m2 (a_C2 + g j)
   !> (the chapter's 6.26 prints + m2 g; the sign is corrected here, docs/errata.md).
   !> Link 1 (6.16): m1 a_C1 = F01 + F21 + G1, so F01 = m1 (a_C1 + g j) - F21.
   pure subroutine reactions(par, q, qd, qdd, f01, f21)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp), intent(in) :: qdd(2)       !! angular accelerations [rad/s²]
      real(dp), intent(out) :: f01(2)      !! ground on link 1 at A [N]
      real(dp), intent(out) :: f21(2)      !! link 2 on link 1 at B [N]
      type(kinematics_t) :: k
      k = kinematics(par, q, qd, qdd)
      f21 = -par%m2*(k%ac2 + [0.0_dp, par%g])
      f01 = par%m1*(k%ac1 + [0.0_dp, par%g]) - f21
   end subroutine reactions

   ! ------------------------------------------------ the model interface bindings

   !> The model with parameters `par` (validated by the caller: `validate`).
   pure function pendulum_model(par) result(model)
      type(pendulum_t), intent(in) :: par  !! parameters
      type(double_pendulum_t) :: model
      model%par = par
   end function pendulum_model

   pure integer function dp_n_dof(self)
      class(double_pendulum_t), intent(in) :: self
      dp_n_dof = 2
   end function dp_n_dof

   pure function dp_name(self) result(name)
      class(double_pendulum_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'double pendulum'
      if (self%par%body /= body_rod) name = name//' of '//body_name_text(self%par)
   end function dp_name

   !> The natural time unit sqrt(l1/g) [s].
   pure subroutine dp_time_unit(self, seconds, name)
      class(double_pendulum_t), intent(in) :: self        !! the model
      real(dp), intent(out) :: seconds                    !! the unit [s]
      character(len=:), allocatable, intent(out) :: name  !! 'sqrt(l1/g)'
      seconds = sqrt(self%par%l1/self%par%g)
      name = 'sqrt(l1/g)'
   end subroutine dp_time_unit

   !> Both links hanging: q = (−π/2, −π/2).
   pure subroutine dp_rest_state(self, q)
      class(double_pendulum_t), intent(in) :: self  !! the model
      real(dp), intent(out) :: q(:)                 !! angles at rest [rad]
      q = -0.5_dp*acos(-1.0_dp)
   end subroutine dp_rest_state

   !> The links' mass distribution with units ('' for uniform rods).
   function dp_body_description(self) result(text)
      class(double_pendulum_t), intent(in) :: self  !! the model
      character(len=:), allocatable :: text
      associate (p => self%par)
         text = body_text(p%body == body_rod, [p%l1, p%l2], [p%d1, p%d2], [p%i1, p%i2])
      end associate
   end function dp_body_description

   !> 'point masses on massless rods' or 'general bodies (d, I given)': the body of a
   !> non-rod parameter set, for names and summaries.
   pure function body_name_text(par) result(s)
      type(pendulum_t), intent(in) :: par  !! parameters
      character(len=:), allocatable :: s
      if (body_kind_name(par) == 'point') then
         s = 'point masses on massless rods'
      else
         s = 'general bodies (com d_i, inertia I_i)'
      end if
   end function body_name_text

   pure logical function dp_true(self)
      class(double_pendulum_t), intent(in) :: self
      dp_true = .true.
   end function dp_true

   pure subroutine dp_field(self, t, y, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      f(1:4) = rhs_qqdot_impl(self%par, y(1:4))
   end subroutine dp_field

   pure subroutine dp_jacobian(self, t, y, jac)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      jac = jacobian_qqdot(self%par, y)
   end subroutine dp_jacobian

   pure real(dp) function dp_energy(self, t, y)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      dp_energy = energy(self%par, y(1:2), y(3:4))
   end function dp_energy

   !> V = (m1/2 + m2) g L1 sin q1 + m2 g (L2/2) sin q2 (rods; any body: the same form
   !> with the centres of mass) [J].
   pure real(dp) function dp_potential_energy(self, t, y)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      dp_potential_energy = potential_energy(self%par, y(1:2))
   end function dp_potential_energy

   !> T = ½ q̇ᵀ M(q) q̇ [J].
   pure real(dp) function dp_kinetic_energy(self, t, y)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      dp_kinetic_energy = kinetic_energy(self%par, y(1:2), y(3:4))
   end function dp_kinetic_energy

   pure real(dp) function dp_energy_scale(self, e0)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: e0
      dp_energy_scale = energy_scale(self%par, e0)
   end function dp_energy_scale

   pure subroutine dp_momenta(self, t, y, p)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: p(:)
      p = momenta(self%par, y(1:2), y(3:4))
   end subroutine dp_momenta

   pure subroutine dp_velocities(self, t, z, qd)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: qd(:)
      qd = velocities(self%par, z(1:2), z(3:4))
   end subroutine dp_velocities

   pure real(dp) function dp_hamiltonian_value(self, t, z) result(h)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      h = hamiltonian(self%par, z(1:2), z(3:4))
   end function dp_hamiltonian_value

   pure subroutine dp_canonical_field(self, t, z, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*)
      real(dp), intent(out) :: f(*)
      if (self%par%body /= body_rod) then   ! links of any mass distribution
         f(1:4) = rhs_qp_trig_general(self%par, sin_cos(z(1:2)), z(1:4))
         return
      end if
      f(1:4) = rhs_qp_trig_impl(self%par, sin_cos_impl(z(1:2)), z(1:4))
   end subroutine dp_canonical_field

   pure subroutine dp_canonical_jacobian(self, t, z, jac)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: jac(:, :)
      jac = jacobian_qp(self%par, z)
   end subroutine dp_canonical_jacobian

   pure subroutine dp_energy_gradient(self, t, y, g)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: g(:)
      g = energy_gradient(self%par, y(1:2), y(3:4))
   end subroutine dp_energy_gradient

   pure subroutine dp_section_state(self, e, link, angle, direction, q_o, p_o, q, qd, found)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: e, angle, q_o, p_o
      integer, intent(in) :: link, direction
      real(dp), intent(out) :: q(:), qd(:)
      logical, intent(out) :: found
      call shell_state(self%par, e, link, angle, direction, q_o, p_o, q, qd, found)
   end subroutine dp_section_state

   pure real(dp) function dp_section_p_max(self, e, link, angle) result(p)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: e, angle
      integer, intent(in) :: link
      p = shell_p_max(self%par, e, link, angle)
   end function dp_section_p_max

   !> The cache: (sin q1, sin q2, cos q1, cos q2) of the step start.
   pure integer function dp_cache_size(self)
      class(double_pendulum_t), intent(in) :: self
      dp_cache_size = 4
   end function dp_cache_size

   pure subroutine dp_fill_cache(self, q, cache)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: q(*)
      real(dp), intent(inout) :: cache(*)
      cache(1:4) = sin_cos_impl(q(1:2))
   end subroutine dp_fill_cache

   !> (q̇, q̈) with the sines of q = q_start + d by angle addition.
   pure subroutine dp_field_near(self, t, y, d, cache, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*), d(*), cache(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: sc(4)
      if (d(1) == 0.0_dp .and. d(2) == 0.0_dp) then
         sc = cache(1:4)          ! at the cache's own angles (a state at rest)
      else
         sc = sin_cos_near_impl(cache(1:4), y(1:2), d(1:2))
      end if
      f(1:2) = y(3:4)
      f(3:4) = qddot_trig(self%par, sc, y(3:4))
   end subroutine dp_field_near

   !> The cache at the angles of y, and (q̇, q̈) there with its sines and cosines.
   pure subroutine dp_fill_cache_field(self, t, y, cache, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(inout) :: cache(*)
      real(dp), intent(out) :: f(*)
      cache(1:4) = sin_cos_impl(y(1:2))
      f(1:2) = y(3:4)
      f(3:4) = qddot_trig(self%par, cache(1:4), y(3:4))
   end subroutine dp_fill_cache_field

   !> (∂H/∂p, −∂H/∂q) with the sines of q = q_start + d by angle addition.
   pure subroutine dp_canonical_field_near(self, t, z, d, cache, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*), d(*), cache(*)
      real(dp), intent(out) :: f(*)
      if (self%par%body /= body_rod) then   ! links of any mass distribution
         f(1:4) = rhs_qp_trig_general(self%par, sin_cos_near(cache(1:4), z(1:2), d(1:2)), &
                                      z(1:4))
         return
      end if
      f(1:4) = rhs_qp_trig_impl(self%par, sin_cos_near_impl(cache(1:4), z(1:2), d(1:2)), z(1:4))
   end subroutine dp_canonical_field_near

   pure integer function dp_n_outputs(self)
      class(double_pendulum_t), intent(in) :: self
      dp_n_outputs = n_link_out + n_alias_out
   end function dp_n_outputs

   !> The pendulum layout of dpend_link_layout: F_joint rC vC aC rJ vJ aJ (2 rows)
   !> and rA, then the chapter's F01 F21 rC1 vC1 aC1 rC2 vC2 aC2 rB.
   subroutine dp_output_info(self, i, name, n_comp, units, description, rows)
      class(double_pendulum_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, description
      integer, intent(out) :: n_comp
      integer, intent(out), optional :: rows
      integer :: r
      if (i <= n_link_out) then
         name = trim(link_out_name(i)); units = trim(link_out_units(i))
         description = trim(link_out_text(i))
         r = merge(2, 0, link_out_rows(i))
      else
         name = trim(alias_out_name(i - n_link_out))
         units = trim(alias_out_units(i - n_link_out))
         description = trim(alias_out_text(i - n_link_out))
         r = 0
      end if
      n_comp = 2*max(1, r)
      if (present(rows)) rows = r
   end subroutine dp_output_info

   !> The outputs of one sample (48 values): the reactions (chapter 6.16–6.26,
   !> corrected) and kinematics (6.2–6.12) in the chapter's names, and from them the
   !> per-link layout (the pin A fixed at the origin).
   pure subroutine dp_outputs(self, t, y, f, values)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:), f(:)
      real(dp), intent(out) :: values(:)
      type(kinematics_t) :: k
      real(dp) :: alias(18)
      call reactions(self%par, y(1:2), y(3:4), f(3:4), alias(1:2), alias(3:4))
      k = kinematics(self%par, y(1:2), y(3:4), f(3:4))
      alias(5:6) = k%rc1; alias(7:8) = k%vc1; alias(9:10) = k%ac1
      alias(11:12) = k%rc2; alias(13:14) = k%vc2; alias(15:16) = k%ac2
      alias(17:18) = k%rb
      call chain_from_aliases(alias, k%vb, k%ab, values(1:28))
      if (self%par%body /= body_rod) then   ! the tip is not 2 C2 − B: at l2 along link 2
         associate (u2 => [cos(y(2)), sin(y(2))], n2 => [-sin(y(2)), cos(y(2))])
            values(19:20) = k%rb + self%par%l2*u2
            values(23:24) = k%vb + self%par%l2*y(4)*n2
            values(27:28) = k%ab + self%par%l2*(f(4)*n2 - y(4)**2*u2)
         end associate
      end if
      values(29:30) = 0.0_dp
      values(31:48) = alias
   end subroutine dp_outputs

   pure integer function dp_n_parameters(self)
      class(double_pendulum_t), intent(in) :: self
      dp_n_parameters = 5
      if (self%par%body /= body_rod) dp_n_parameters = 9
   end function dp_n_parameters

   !> m1, m2 [kg], l1, l2 [m], g [m/s²], in that order; for a body other than the
   !> uniform rod also com1, com2 [m] (d_i) and inertia1, inertia2 [kg m^2] (I_i).
   subroutine dp_parameter(self, i, name, value, units)
      class(double_pendulum_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units
      real(dp), intent(out) :: value
      select case (i)
      case (1); name = 'm1'; value = self%par%m1; units = 'kg'
      case (2); name = 'm2'; value = self%par%m2; units = 'kg'
      case (3); name = 'l1'; value = self%par%l1; units = 'm'
      case (4); name = 'l2'; value = self%par%l2; units = 'm'
      case (6); name = 'com1'; value = self%par%d1; units = 'm'
      case (7); name = 'com2'; value = self%par%d2; units = 'm'
      case (8); name = 'inertia1'; value = self%par%i1; units = 'kg m^2'
      case (9); name = 'inertia2'; value = self%par%i2; units = 'kg m^2'
      case default; name = 'g'; value = self%par%g; units = 'm/s^2'
      end select
   end subroutine dp_parameter

   subroutine dp_coordinate(self, i, name, units, momentum_units)
      class(double_pendulum_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, momentum_units
      call rod_coordinate(i, name, units, momentum_units)
   end subroutine dp_coordinate

   function dp_coordinates_text(self, order) result(text)
      class(double_pendulum_t), intent(in) :: self
      integer, intent(in) :: order
      character(len=:), allocatable :: text
      text = rod_coordinates_text(2, order)
   end function dp_coordinates_text

   subroutine dp_figure(self, anchor, points, style, forces)
      class(double_pendulum_t), intent(in) :: self
      character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      call rod_figure(anchor, points, style, forces)
   end subroutine dp_figure

   ! ---- the Hamiltonian in quadruple precision (the roundoff runs)

   !> Copy of `hamiltonian` for precision: quadruple precision;
   !> test/test_copies.f90 compares them.
   !> H(q, p) in quadruple precision at the compensated state y + e (canonical
   !> variables), for errors below the double-precision rounding of H [J].
   pure function hamiltonian_qp(par, y, e) result(h)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: y(4)         !! state (q1, q2, p1, p2)
      real(dp), intent(in) :: e(4)         !! its compensation (0 without)
      real(qp) :: h
      real(qp) :: z(4), m11, m12, m22, det, qd1, qd2, m1, m2, l1, l2, g, d1, d2
      z = real(y, qp) + real(e, qp)
      m1 = real(par%m1, qp); m2 = real(par%m2, qp); l1 = real(par%l1, qp)
      l2 = real(par%l2, qp); g = real(par%g, qp)
      if (par%body /= body_rod) then   ! links of any mass distribution
         d1 = real(par%d1, qp); d2 = real(par%d2, qp)
         m11 = real(par%i1, qp) + m1*d1**2 + m2*l1**2
         m12 = m2*l1*d2*cos(z(1) - z(2))
         m22 = real(par%i2, qp) + m2*d2**2
         det = m11*m22 - m12**2
         qd1 = (m22*z(3) - m12*z(4))/det
         qd2 = (m11*z(4) - m12*z(3))/det
         h = 0.5_qp*(z(3)*qd1 + z(4)*qd2) + g*(m1*d1 + m2*l1)*sin(z(1)) + g*m2*d2*sin(z(2))
         return
      end if
      m11 = (m1/3.0_qp + m2)*l1**2
      m12 = 0.5_qp*m2*l1*l2*cos(z(1) - z(2))
      m22 = m2*l2**2/3.0_qp
      det = m11*m22 - m12**2
      qd1 = (m22*z(3) - m12*z(4))/det
      qd2 = (m11*z(4) - m12*z(3))/det
      h = 0.5_qp*(z(3)*qd1 + z(4)*qd2) + (0.5_qp*m1 + m2)*g*l1*sin(z(1)) &
          + 0.5_qp*m2*g*l2*sin(z(2))
   end function hamiltonian_qp

   !> H(z + e) in quadruple precision [J] (`hamiltonian_qp`).
   pure function dp_hamiltonian_qp(self, z, e) result(h)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: z(:)     !! canonical state (q1, q2, p1, p2)
      real(dp), intent(in) :: e(:)     !! its compensation (0 without)
      real(qp) :: h
      h = hamiltonian_qp(self%par, z(1:4), e(1:4))
   end function dp_hamiltonian_qp

   !> G_i of V = G_1 sin q1 + G_2 sin q2 [J]: G_i = g l_i (m_i/2 + Σ_(k>i) m_k), the
   !> expressions (and roundings) of the N-link chain's (dpend_chain).
   pure function dp_potential_weights(self) result(gl)
      class(double_pendulum_t), intent(in) :: self  !! the double pendulum
      real(dp), allocatable :: gl(:)
      real(dp) :: tail
      associate (p => self%par)
         if (p%body /= body_rod) then   ! G_i = g (m_i d_i + l_i Σ_(k>i) m_k), as the chain's
            gl = [p%g*(p%m1*p%d1 + p%l1*p%m2), p%g*(p%m2*p%d2)]
            return
         end if
         tail = 0.0_dp
         allocate (gl(2))
         gl(2) = p%g*p%l2*(0.5_dp*p%m2 + tail)
         tail = tail + p%m2
         gl(1) = p%g*p%l1*(0.5_dp*p%m1 + tail)
      end associate
   end function dp_potential_weights
end module dpend_pendulum
