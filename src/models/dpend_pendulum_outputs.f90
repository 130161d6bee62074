!> The double pendulum's procedures for the files and the descriptions (interfaces in
!> dpend_pendulum): its name, the outputs of a sample (the joint reactions and
!> kinematics of dpend_pendulum_forces in the layout of dpend_link_layout), the
!> parameter listing, coordinates, figure, time unit, state of rest, mass
!> distribution and the weights G_i of the sweep. Evaluated per sample or once per
!> run, never within an integrator step.
submodule (dpend_pendulum) dpend_pendulum_outputs
   use dpend_link_layout, only: n_link_out, link_out_name, link_out_units, link_out_text, &
                                link_out_rows, rod_coordinate, rod_coordinates_text, rod_figure, &
                                n_alias_out, alias_out_name, alias_out_units, &
                                alias_out_text, chain_from_aliases, body_text, link_output_info
   implicit none

contains

   module procedure dp_name
      name = 'double pendulum'
      if (self%par%body /= body_rod) name = name//' of '//body_name_text(self%par)
   contains

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
   end procedure dp_name

   !> The natural time unit sqrt(l1/g) [s].
   module procedure dp_time_unit
      seconds = sqrt(self%par%l1/self%par%g)
      name = 'sqrt(l1/g)'
   end procedure dp_time_unit

   !> Both links hanging: q = (−π/2, −π/2).
   module procedure dp_rest_state
      q = -0.5_dp*acos(-1.0_dp)
   end procedure dp_rest_state

   !> The links' mass distribution with units ('' for uniform rods).
   module procedure dp_body_description
      associate (p => self%par)
         text = body_text(p%body == body_rod, [p%l1, p%l2], [p%d1, p%d2], [p%i1, p%i2])
      end associate
   end procedure dp_body_description

   module procedure dp_n_outputs
      dp_n_outputs = n_link_out + n_alias_out
   end procedure dp_n_outputs

   !> The pendulum layout of dpend_link_layout: F_joint rC vC aC rJ vJ aJ (2 rows)
   !> and rA, then the chapter's F01 F21 rC1 vC1 aC1 rC2 vC2 aC2 rB.
   module procedure dp_output_info
      call link_output_info(i, 2, name, n_comp, units, description, rows)
   end procedure dp_output_info

   !> The outputs of one sample (48 values): the reactions (chapter 6.16–6.26,
   !> corrected) and kinematics (6.2–6.12) in the chapter's names, and from them the
   !> per-link layout (the pin A fixed at the origin).
   module procedure dp_outputs
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
   end procedure dp_outputs

   module procedure dp_n_parameters
      dp_n_parameters = 5
      if (self%par%body /= body_rod) dp_n_parameters = 9
   end procedure dp_n_parameters

   !> m1, m2 [kg], l1, l2 [m], g [m/s²], in that order; for a body other than the
   !> uniform rod also com1, com2 [m] (d_i) and inertia1, inertia2 [kg m^2] (I_i).
   module procedure dp_parameter
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
   end procedure dp_parameter

   module procedure dp_coordinate
      call rod_coordinate(i, name, units, momentum_units)
   end procedure dp_coordinate

   module procedure dp_coordinates_text
      text = rod_coordinates_text(2, order)
   end procedure dp_coordinates_text

   module procedure dp_figure
      call rod_figure(anchor, points, style, forces)
   end procedure dp_figure

   !> G_i of V = G_1 sin q1 + G_2 sin q2 [J]: G_i = g l_i (m_i/2 + Σ_(k>i) m_k), the
   !> expressions (and roundings) of the N-link chain's (dpend_chain).
   module procedure dp_potential_weights
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
   end procedure dp_potential_weights
end submodule dpend_pendulum_outputs
