!> The N-link chain's procedures that its own hot path never calls (interfaces in
!> dpend_chain): the outputs of a sample (kinematics, joint reactions, the potential
!> energy and the scale of energy errors), the powers of the energy balance (called by
!> the field of dpend_work, another module, so out of line wherever they live), the
!> Poincaré sections of two links (the double pendulum's formulas), the descriptions
!> and the parameter listing. None of dpend_chain's own procedures calls these.
submodule (dpend_chain) dpend_chain_outputs
   use dpend_strings, only: to_str
   use dpend_model, only: model_check_parameter_rates
   use dpend_link_layout, only: n_link_out, link_out_name, link_out_units, link_out_text, &
                                link_out_rows, rod_coordinate, rod_coordinates_text, rod_figure, &
                                n_alias_out, alias_out_name, alias_out_units, &
                                alias_out_text, two_link_aliases, body_text, link_output_info
   use dpend_pendulum, only: pendulum_t, shell_state, shell_p_max, body_general
   implicit none

contains

   ! ---------------------------------------------------------------- kinematics, reactions

   !> Positions [m], velocities [m/s], accelerations [m/s²] of every centre of mass C_i
   !> and far end P_i, as (2, n) arrays (x, y per link), at time t (default 0; the
   !> support's motion included).
   module procedure chain_kinematics
      real(dp) :: u(2), nv(2), r0(2), v0(2), a0(2), h
      integer :: i
      r0 = 0.0_dp; v0 = 0.0_dp; a0 = 0.0_dp
      if (self%driven) then
         h = 0.0_dp
         if (present(t)) h = t
         call self%support(h, r0, v0, a0)
      end if
      do i = 1, self%n
         u = [cos(q(i)), sin(q(i))]
         nv = [-u(2), u(1)]
         h = self%d(i)          ! L_i/2 for rods (the same bits as 0.5 L_i)
         rc(:, i) = r0 + h*u
         vc(:, i) = v0 + h*qd(i)*nv
         ac(:, i) = a0 + h*(qdd(i)*nv - qd(i)**2*u)
         rj(:, i) = r0 + self%l(i)*u
         vj(:, i) = v0 + self%l(i)*qd(i)*nv
         aj(:, i) = a0 + self%l(i)*(qdd(i)*nv - qd(i)**2*u)
         r0 = rj(:, i); v0 = vj(:, i); a0 = aj(:, i)
      end do
   end procedure chain_kinematics

   !> F_(i−1,i) [N] (2, n), the force of body i − 1 on body i at joint i, from the tip:
   !> F_(i−1,i) = F_(i,i+1) + m_i (a_Ci + g ĵ), F_(N,N+1) = 0.
   module procedure chain_reactions
      real(dp) :: rc(2, max_dof), vc(2, max_dof), ac(2, max_dof)
      real(dp) :: rj(2, max_dof), vj(2, max_dof), aj(2, max_dof), nxt(2)
      integer :: i, n
      n = self%n
      call self%kinematics(q, qd, qdd, rc(:, 1:n), vc(:, 1:n), ac(:, 1:n), &
                           rj(:, 1:n), vj(:, 1:n), aj(:, 1:n), t)
      nxt = 0.0_dp
      do i = n, 1, -1
         f(1, i) = nxt(1) + self%m(i)*ac(1, i)
         f(2, i) = nxt(2) + self%m(i)*(ac(2, i) + self%g)
         nxt = f(:, i)
      end do
   end procedure chain_reactions

   !> P_friction = Σ c_i (q̇_i − q̇_(i−1))², P_support = F_(0,1) · v_A and
   !> P_torque = Σ τ_i (q̇_i − q̇_(i−1)) [W] at (t, q, q̇) with the accelerations q̈ (see
   !> the module's notes).
   module procedure chain_powers
      real(dp) :: ra(2), va(2), aa(2), f(2), w, ci, si, tau(max_dof)
      integer :: i, n
      n = self%n
      p_friction = 0.0_dp
      p_support = 0.0_dp
      if (self%damped) then
         do i = 1, n
            w = y(n + i)
            if (i > 1) w = w - y(n + i - 1)
            p_friction = p_friction + self%c(i)*w**2
         end do
      end if
      if (self%coulomb) then
         do i = 1, n
            w = y(n + i)
            if (i > 1) w = w - y(n + i - 1)
            p_friction = p_friction + self%cf(i)*tanh(w/self%vs)*w
         end do
      end if
      if (self%driven) then
         call self%support(t, ra, va, aa)
         f = sum(self%m)*(aa + [0.0_dp, self%g])
         do i = 1, n
            ci = cos(y(i)); si = sin(y(i))
            f = f + self%mu(i)*(qdd(i)*[-si, ci] - y(n + i)**2*[ci, si])
         end do
         p_support = dot_product(f, va)
      end if
      if (present(p_torque)) then
         p_torque = 0.0_dp
         if (self%torqued) then
            call self%torque%values(t, tau(1:n))
            do i = 1, n
               w = y(n + i)
               if (i > 1) w = w - y(n + i - 1)
               p_torque = p_torque + tau(i)*w
            end do
         end if
      end if
   end procedure chain_powers

   ! ---------------------------------------------------------------- outputs, energies

   module procedure chain_n_outputs
      chain_n_outputs = n_link_out
      if (self%n == 2) chain_n_outputs = n_link_out + n_alias_out
      if (self%torqued) chain_n_outputs = chain_n_outputs + 1   ! tau, the last
   end procedure chain_n_outputs

   !> The pendulum layout of dpend_link_layout: F_joint rC vC aC rJ vJ aJ (N rows)
   !> and rA; for two links also the chapter's F01 F21 rC1 vC1 aC1 rC2 vC2 aC2 rB;
   !> last, with applied torques, tau (N).
   module procedure chain_output_info
      if (self%torqued .and. i == self%n_outputs()) then
         name = 'tau'
         n_comp = self%n
         units = 'N m'
         description = 'applied joint torques tau_1 .. tau_N: joint i''s motor on link i ' &
                       //'(its reaction on link i - 1), '//self%torque%text()
         if (present(rows)) rows = 0
         return
      end if
      call link_output_info(i, self%n, name, n_comp, units, description, rows)
   end procedure chain_output_info

   !> The outputs of one sample (14 N + 2 values, 20 more for two links), q̈ taken
   !> from f = (q̇, q̈).
   module procedure chain_outputs
      real(dp) :: w(2, max_dof, n_link_out - 1), v(2), a(2)
      integer :: n, k
      n = self%n
      associate (q => y(1:n), qd => y(n + 1:2*n), qdd => f(n + 1:2*n))
         call self%reactions(q, qd, qdd, w(:, 1:n, 1), t)
         call self%kinematics(q, qd, qdd, w(:, 1:n, 2), w(:, 1:n, 3), w(:, 1:n, 4), &
                              w(:, 1:n, 5), w(:, 1:n, 6), w(:, 1:n, 7), t)
      end associate
      do k = 1, n_link_out - 1
         values(2*n*(k - 1) + 1:2*n*k) = reshape(w(:, 1:n, k), [2*n])
      end do
      call self%support(t, values(14*n + 1:14*n + 2), v, a)
      if (n == 2) call two_link_aliases(w(:, 1:2, :), values(31:48))
      if (self%torqued) then   ! after rA (and the two links' aliases)
         k = 14*n + 2 + merge(18, 0, n == 2)
         call self%torque%values(t, values(k + 1:k + n))
      end if
   end procedure chain_outputs

   !> V = Σ G_i sin q_i, and with a moving support the height of the whole mass at
   !> the pin, M g y_A(t) [J] (the potential part of `chain_energy`).
   module procedure chain_potential_energy
      real(dp) :: ra(2), va(2), aa(2)
      chain_potential_energy = self%potential(y(1:self%n))
      if (self%driven) then
         call self%support(t, ra, va, aa)
         chain_potential_energy = chain_potential_energy + sum(self%m)*self%g*ra(2)
      end if
   end procedure chain_potential_energy

   !> The unit of relative energy errors [J], as for the double pendulum: |E0| when it is
   !> at least 1e-3 of E_ref = V(π/2, …, π/2) = Σ G_i (every link upright), E_ref itself
   !> when E0 ≈ 0 (e.g. released horizontally); 1 J when both vanish (g = 0 at rest),
   !> so that the relative error is then the error in joules.
   module procedure chain_energy_scale
      real(dp) :: e_ref
      e_ref = sum(self%gl)
      chain_energy_scale = merge(abs(e0), e_ref, abs(e0) >= 1e-3_dp*e_ref)
      if (.not. chain_energy_scale > 0.0_dp) chain_energy_scale = 1.0_dp
   end procedure chain_energy_scale

   ! ---------------------------------------------------------------- Poincaré sections

   !> Energy-shell sections exist for two links only (a two-degree-of-freedom
   !> Hamiltonian); there the chain is the double pendulum, whose formulas are used.
   module procedure chain_energy_sections
      ! (the double pendulum's shell, `as_pendulum`: no rotors)
      chain_energy_sections = self%n == 2 .and. self%hamiltonian() .and. .not. self%motors
   end procedure chain_energy_sections

   !> The double pendulum of a two-link chain.
   pure function as_pendulum(self) result(par)
      class(chain_t), intent(in) :: self
      type(pendulum_t) :: par
      par = pendulum_t(m1=self%m(1), m2=self%m(2), l1=self%l(1), l2=self%l(2), g=self%g)
      if (.not. self%rod) then
         par%body = body_general
         par%d1 = self%d(1); par%d2 = self%d(2); par%i1 = self%ic(1); par%i2 = self%ic(2)
      end if
   end function as_pendulum

   !> N = 2 only (`energy_sections`): the double pendulum's `shell_state`.
   module procedure chain_section_state
      if (self%n /= 2) error stop 'internal error: the chain has sections for N = 2 only'
      call shell_state(as_pendulum(self), e, link, angle, direction, q_o, p_o, q, qd, found)
   end procedure chain_section_state

   !> N = 2 only (`energy_sections`): the double pendulum's `shell_p_max`.
   module procedure chain_section_p_max
      if (self%n /= 2) error stop 'internal error: the chain has sections for N = 2 only'
      p = shell_p_max(as_pendulum(self), e, link, angle)
   end procedure chain_section_p_max

   ! ---------------------------------------------------------------- descriptions

   module procedure chain_name
      name = 'chain of '//to_str(self%n)//' links'
      if (.not. self%rod) then
         if (all(self%d(1:self%n) == self%l(1:self%n)) .and. all(self%ic(1:self%n) == 0.0_dp)) &
            then
            name = name//' of point masses on massless rods'
         else
            name = name//' of general bodies (com d_i, inertia I_i)'
         end if
      end if
      if (self%damped) name = 'damped '//name
      if (self%coulomb) name = name//' with Coulomb joint friction'
      if (self%motors) name = name//' with motors (rotor inertia)'
      if (self%driven) name = name//' on a moving support'
      if (self%torqued) name = name//' with applied joint torques'
   end procedure chain_name

   module procedure chain_n_parameters
      chain_n_parameters = 2*self%n + 1
      if (self%damped) chain_n_parameters = chain_n_parameters + self%n
      if (self%coulomb) chain_n_parameters = chain_n_parameters + self%n + 1
      if (self%motors) chain_n_parameters = chain_n_parameters + 2*self%n
      if (self%driven) chain_n_parameters = chain_n_parameters + 5
      if (.not. self%rod) chain_n_parameters = chain_n_parameters + 2*self%n
   end procedure chain_n_parameters

   !> m1 … mN [kg], l1 … lN [m], g [m/s²], in that order; then, when present, the
   !> damping c1 … cN [N m s], the Coulomb friction coulomb1 … coulombN [N m] and
   !> coulomb_speed [rad/s], the motors' rotor_inertia1 … rotor_inertiaN [kg m^2] and
   !> gear_ratio1 … gear_ratioN, and the support's a_x, a_y [m], ω [rad/s], φ_x, φ_y [rad];
   !> last, for links other than uniform rods, com1 … comN [m] and inertia1 … inertiaN
   !> [kg m^2].
   module procedure chain_parameter
      integer :: j
      character(len=*), parameter :: sup_names(5) = &
         [character(len=17) :: 'support_ax', 'support_ay', 'support_frequency', &
          'support_phase_x', 'support_phase_y']
      character(len=*), parameter :: sup_units(5) = &
         [character(len=5) :: 'm', 'm', 'rad/s', 'rad', 'rad']
      j = i - (2*self%n + 1)
      if (j > 0 .and. .not. self%rod) then   ! the last: com1 … comN, inertia1 … inertiaN
         j = i - (chain_n_parameters(self) - 2*self%n)
         if (j > 0) then
            if (j <= self%n) then
               name = 'com'//to_str(j); value = self%d(j); units = 'm'
            else
               name = 'inertia'//to_str(j - self%n); value = self%ic(j - self%n)
               units = 'kg m^2'
            end if
            return
         end if
         j = i - (2*self%n + 1)
      end if
      if (j > 0 .and. self%damped) then
         if (j <= self%n) then
            name = 'c'//to_str(j); value = self%c(j); units = 'N m s'
            return
         end if
         j = j - self%n
      end if
      if (j > 0 .and. self%coulomb) then
         if (j <= self%n) then
            name = 'coulomb'//to_str(j); value = self%cf(j); units = 'N m'
            return
         else if (j == self%n + 1) then
            name = 'coulomb_speed'; value = self%vs; units = 'rad/s'
            return
         end if
         j = j - self%n - 1
      end if
      if (j > 0 .and. self%motors) then
         if (j <= self%n) then
            name = 'rotor_inertia'//to_str(j); value = self%ir(j); units = 'kg m^2'
            return
         else if (j <= 2*self%n) then
            name = 'gear_ratio'//to_str(j - self%n); value = self%gr(j - self%n); units = ''
            return
         end if
         j = j - 2*self%n
      end if
      if (j > 0) then
         name = trim(sup_names(j)); units = trim(sup_units(j))
         select case (j)
         case (1, 2); value = self%sup_a(j)
         case (3); value = self%sup_w
         case default; value = self%sup_phi(j - 3)
         end select
         return
      end if
      if (i <= self%n) then
         name = 'm'//to_str(i); value = self%m(i); units = 'kg'
      else if (i <= 2*self%n) then
         name = 'l'//to_str(i - self%n); value = self%l(i - self%n); units = 'm'
      else
         name = 'g'; value = self%g; units = 'm/s^2'
      end if
   end procedure chain_parameter

   module procedure chain_coordinate
      call rod_coordinate(i, name, units, momentum_units)
   end procedure chain_coordinate

   module procedure chain_coordinates_text
      text = rod_coordinates_text(self%n, order)
   end procedure chain_coordinates_text

   module procedure chain_figure
      call rod_figure(anchor, points, style, forces)
   end procedure chain_figure

   !> The natural time unit sqrt(l1/g) of the first link [s].
   module procedure chain_time_unit
      seconds = sqrt(self%l(1)/self%g)
      name = 'sqrt(l1/g)'
   end procedure chain_time_unit

   !> Every link hanging: q_i = −π/2 (the support's mean position if it moves).
   module procedure chain_rest_state
      q = -0.5_dp*acos(-1.0_dp)
   end procedure chain_rest_state

   !> The links' mass distribution with units ('' for uniform rods).
   module procedure chain_body_description
      text = body_text(self%rod, self%l, self%d, self%ic)
   end procedure chain_body_description

   !> G_i of V = Σ G_i sin q_i [J] (n).
   module procedure chain_potential_weights
      gl = self%gl
   end procedure chain_potential_weights

   !> K_ij of M_ij = K_ij cos(q_i − q_j) [kg m²] (n × n); none (0 × 0) when the
   !> support moves (the mass matrix is that, but the forces have more terms) or
   !> motors add their constant part to M.
   module procedure chain_mass_weights
      if (self%driven .or. self%motors) then
         allocate (k(0, 0))
      else
         k = self%k
      end if
   end procedure chain_mass_weights

   ! the sensitivities of the motion to the damping (dpend fit --fit-damping)

   !> The chain gives the sensitivities to its joint damping.
   module procedure chain_check_parameter_rates
      if (name /= 'damping') call model_check_parameter_rates(self, name, error)
   end procedure chain_check_parameter_rates
end submodule dpend_chain_outputs
