!> The formulas of the double pendulum built on its mass matrix M(q) and potential
!> V(q): the generalized forces and Lagrange's accelerations (the cross-check of the
!> Newton–Euler ones of dpend_pendulum), the energies with their scale and gradient,
!> the momenta and velocities, H and its derivatives, the Jacobians of both forms, the
!> energy shells of the Poincaré sections and H in quadruple precision (the roundoff
!> runs); each for uniform rods and, through its `*_general` variant, for links of any
!> mass distribution. The model bindings of dpend_pendulum call them (energies,
!> Jacobians, sections); the equations of motion of the integrators' steps do not.
!>
!> dpend_pendulum passes every public name of this module on; use it from there.
module dpend_pendulum_lagrange
   use dpend_kinds, only: dp, pi
   use dpend_pendulum_params, only: pendulum_t, body_rod, body_constants
   use, intrinsic :: iso_fortran_env, only: qp => real128
   implicit none
   private
   public :: mass_matrix, generalized_forces, qddot_lagrange, kinetic_energy, &
             potential_energy, energy, energy_scale, momenta, velocities, hamiltonian, &
             dh_dp, dh_dq, shell_state, shell_p_max, energy_limit, energy_gradient, &
             jacobian_qqdot, jacobian_qp, hamiltonian_qp

contains

   !> Constant i of `body_constants` (M11, M22, k, ga, gb).
   !> A copy of dpend_pendulum's, whose `rhs_qp_trig_general` inlines it there: a
   !> private procedure is inlined within its own module only; keep the two alike.
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
end module dpend_pendulum_lagrange
