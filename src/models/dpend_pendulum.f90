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
!> This module holds, once, the formulas of the equations of motion that the
!> integrators evaluate in every step (the corrected Newton–Euler accelerations, the
!> canonical field of Hamilton's equations) and `double_pendulum_t`, which binds the
!> model interface (`dpend_model`) to the formulas: one translation unit, so that the
!> bindings inline them. The other formulas are in modules below it, whose public
!> names it passes on (use them from here): `pendulum_t`, the body kinds, the checks
!> and the body constants (dpend_pendulum_params); Lagrange's form, the energies, the
!> Hamiltonian, the Jacobians, the energy shells and H in quadruple precision
!> (dpend_pendulum_lagrange); the kinematics and joint reactions
!> (dpend_pendulum_forces). The submodule dpend_pendulum_outputs implements the
!> bindings for the files and descriptions (the interfaces below).
module dpend_pendulum
   use dpend_kinds, only: dp
   use dpend_model, only: model_t
   use dpend_pendulum_params, only: pendulum_t, body_rod, body_general, validate, &
                                    check_bodies, body_constants, body_kind_name
   use dpend_pendulum_lagrange, only: mass_matrix, generalized_forces, qddot_lagrange, &
                                      kinetic_energy, potential_energy, energy, &
                                      energy_scale, momenta, velocities, hamiltonian, dh_dp, &
                                      dh_dq, shell_state, shell_p_max, energy_limit, &
                                      energy_gradient, jacobian_qqdot, jacobian_qp, &
                                      hamiltonian_qp
   use dpend_pendulum_forces, only: kinematics_t, kinematics, tip_position, reactions
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

   ! dpend_pendulum_outputs implements these: the outputs of a sample, the descriptions,
   ! the parameter listing (described at their bodies). No procedure below `contains`
   ! calls them.
   interface
      pure module function dp_name(self) result(name)
         class(double_pendulum_t), intent(in) :: self
         character(len=:), allocatable :: name
      end function dp_name
      pure module subroutine dp_time_unit(self, seconds, name)
         class(double_pendulum_t), intent(in) :: self        !! the model
         real(dp), intent(out) :: seconds                    !! the unit [s]
         character(len=:), allocatable, intent(out) :: name  !! 'sqrt(l1/g)'
      end subroutine dp_time_unit
      pure module subroutine dp_rest_state(self, q)
         class(double_pendulum_t), intent(in) :: self  !! the model
         real(dp), intent(out) :: q(:)                 !! angles at rest [rad]
      end subroutine dp_rest_state
      module function dp_body_description(self) result(text)
         class(double_pendulum_t), intent(in) :: self  !! the model
         character(len=:), allocatable :: text
      end function dp_body_description
      pure integer module function dp_n_outputs(self)
         class(double_pendulum_t), intent(in) :: self
      end function dp_n_outputs
      module subroutine dp_output_info(self, i, name, n_comp, units, description, rows)
         class(double_pendulum_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units, description
         integer, intent(out) :: n_comp
         integer, intent(out), optional :: rows
      end subroutine dp_output_info
      pure module subroutine dp_outputs(self, t, y, f, values)
         class(double_pendulum_t), intent(in) :: self
         real(dp), intent(in) :: t, y(:), f(:)
         real(dp), intent(out) :: values(:)
      end subroutine dp_outputs
      pure integer module function dp_n_parameters(self)
         class(double_pendulum_t), intent(in) :: self
      end function dp_n_parameters
      module subroutine dp_parameter(self, i, name, value, units)
         class(double_pendulum_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units
         real(dp), intent(out) :: value
      end subroutine dp_parameter
      module subroutine dp_coordinate(self, i, name, units, momentum_units)
         class(double_pendulum_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units, momentum_units
      end subroutine dp_coordinate
      module function dp_coordinates_text(self, order) result(text)
         class(double_pendulum_t), intent(in) :: self
         integer, intent(in) :: order
         character(len=:), allocatable :: text
      end function dp_coordinates_text
      module subroutine dp_figure(self, anchor, points, style, forces)
         class(double_pendulum_t), intent(in) :: self
         character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      end subroutine dp_figure
      pure module function dp_potential_weights(self) result(gl)
         class(double_pendulum_t), intent(in) :: self  !! the double pendulum
         real(dp), allocatable :: gl(:)
      end function dp_potential_weights
   end interface

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

   !> Constant i of `body_constants` (M11, M22, k, ga, gb).
   !> dpend_pendulum_lagrange has a copy, which its `*_general` formulas inline: a
   !> private procedure is inlined within its own module only; keep the two alike.
   pure real(dp) function body_constant(par, i) result(x)
      type(pendulum_t), intent(in) :: par  !! parameters
      integer, intent(in) :: i             !! which
      real(dp) :: c(5)
      c = body_constants(par)
      x = c(i)
   end function body_constant

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

   !> The accelerations used by the integrators: the corrected Newton–Euler form.
   pure function qddot(par, q, qd) result(qdd)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp) :: qdd(2)
      qdd = qddot_newton_euler(par, q, qd)
   end function qddot

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

   !> H(z + e) in quadruple precision [J] (`hamiltonian_qp`).
   pure function dp_hamiltonian_qp(self, z, e) result(h)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: z(:)     !! canonical state (q1, q2, p1, p2)
      real(dp), intent(in) :: e(:)     !! its compensation (0 without)
      real(qp) :: h
      h = hamiltonian_qp(self%par, z(1:4), e(1:4))
   end function dp_hamiltonian_qp

end module dpend_pendulum
