!> The chapter's compound double pendulum as a `model_t` (docs/physics.md): state
!> y = (q1, q2, q̇1, q̇2), angles from the horizontal x axis, counter-clockwise, y up.
!>
!> This module only binds the model interface to the formulas, which live once in
!> `dpend_pendulum` (equations of motion, energy, Hamiltonian form, Jacobians),
!> `dpend_pendulum_kinematics` and `dpend_pendulum_reactions`. It provides the fast
!> path of the integrators: its cache holds (sin q1, sin q2, cos q1, cos q2) of the
!> step start, and stages near it take their sines by angle addition
!> (`sin_cos_near`), so that rk4, Gauss and Verlet evaluate the sine once per step.
module dpend_double_pendulum
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t, validate, rhs_qqdot, jacobian_qqdot, energy, &
                             energy_scale, momenta, velocities, hamiltonian, rhs_qp, &
                             jacobian_qp, energy_gradient, qddot_trig, rhs_qp_trig, &
                             sin_cos, sin_cos_near, shell_state, shell_p_max
   use dpend_pendulum_kinematics, only: kinematics_t, kinematics
   use dpend_pendulum_reactions, only: reactions
   implicit none
   private
   public :: double_pendulum_t, double_pendulum, pendulum_model

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
      procedure :: field_near => dp_field_near
      procedure :: canonical_field_near => dp_canonical_field_near
      procedure :: n_outputs => dp_n_outputs
      procedure :: output_info => dp_output_info
      procedure :: outputs => dp_outputs
      procedure :: n_parameters => dp_n_parameters
      procedure :: parameter => dp_parameter
   end type double_pendulum_t

   !> The writer's per-sample outputs: joint reactions (chapter 6.16–6.26, corrected)
   !> and kinematics (6.2–6.12), two components (x, y) each.
   integer, parameter :: n_out = 9
   character(len=3), parameter :: out_names(n_out) = &
      [character(len=3) :: 'F01', 'F21', 'rC1', 'vC1', 'aC1', 'rC2', 'vC2', 'aC2', 'rB']
   character(len=5), parameter :: out_units(n_out) = &
      [character(len=5) :: 'N', 'N', 'm', 'm/s', 'm/s^2', 'm', 'm/s', 'm/s^2', 'm']
   character(len=48), parameter :: out_text(n_out) = [character(len=48) :: &
      'force of the ground on link 1 at A (x, y)', &
      'force of link 2 on link 1 at B (x, y)', &
      'position of the centre of mass C1 (x, y)', &
      'velocity of C1 (x, y)', 'acceleration of C1 (x, y)', &
      'position of the centre of mass C2 (x, y)', &
      'velocity of C2 (x, y)', 'acceleration of C2 (x, y)', &
      'position of the joint B (x, y)']

contains

   !> The model with parameters `par`, checked (`validate`).
   subroutine double_pendulum(par, model, error)
      type(pendulum_t), intent(in) :: par               !! parameters
      type(double_pendulum_t), intent(out) :: model     !! the model
      type(error_t), allocatable, intent(out) :: error  !! a parameter out of range
      call validate(par, error)
      model%par = par
   end subroutine double_pendulum

   !> The model with parameters `par`, unchecked (tests and callers that validated).
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
   end function dp_name

   pure logical function dp_true(self)
      class(double_pendulum_t), intent(in) :: self
      dp_true = .true.
   end function dp_true

   pure subroutine dp_field(self, t, y, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: f(:)
      f = rhs_qqdot(self%par, y)
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
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: f(:)
      f = rhs_qp(self%par, z)
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
      real(dp), intent(in) :: q(:)
      real(dp), intent(inout) :: cache(:)
      cache(1:4) = sin_cos(q(1:2))
   end subroutine dp_fill_cache

   !> (q̇, q̈) with the sines of q = q_start + d by angle addition.
   pure subroutine dp_field_near(self, t, y, d, cache, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:), d(:), cache(:)
      real(dp), intent(out) :: f(:)
      f(1:2) = y(3:4)
      f(3:4) = qddot_trig(self%par, sin_cos_near(cache(1:4), y(1:2), d(1:2)), y(3:4))
   end subroutine dp_field_near

   !> (∂H/∂p, −∂H/∂q) with the sines of q = q_start + d by angle addition.
   pure subroutine dp_canonical_field_near(self, t, z, d, cache, f)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:), d(:), cache(:)
      real(dp), intent(out) :: f(:)
      f = rhs_qp_trig(self%par, sin_cos_near(cache(1:4), z(1:2), d(1:2)), z)
   end subroutine dp_canonical_field_near

   pure integer function dp_n_outputs(self)
      class(double_pendulum_t), intent(in) :: self
      dp_n_outputs = n_out
   end function dp_n_outputs

   subroutine dp_output_info(self, i, name, n_comp, units, description)
      class(double_pendulum_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, description
      integer, intent(out) :: n_comp
      name = trim(out_names(i)); n_comp = 2
      units = trim(out_units(i)); description = trim(out_text(i))
   end subroutine dp_output_info

   !> F01, F21, rC1, vC1, aC1, rC2, vC2, aC2, rB of one sample (18 values).
   pure subroutine dp_outputs(self, t, y, f, values)
      class(double_pendulum_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:), f(:)
      real(dp), intent(out) :: values(:)
      type(kinematics_t) :: k
      call reactions(self%par, y(1:2), y(3:4), f(3:4), values(1:2), values(3:4))
      k = kinematics(self%par, y(1:2), y(3:4), f(3:4))
      values(5:6) = k%rc1; values(7:8) = k%vc1; values(9:10) = k%ac1
      values(11:12) = k%rc2; values(13:14) = k%vc2; values(15:16) = k%ac2
      values(17:18) = k%rb
   end subroutine dp_outputs

   pure integer function dp_n_parameters(self)
      class(double_pendulum_t), intent(in) :: self
      dp_n_parameters = 5
   end function dp_n_parameters

   !> m1, m2 [kg], l1, l2 [m], g [m/s²], in that order.
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
      case default; name = 'g'; value = self%par%g; units = 'm/s^2'
      end select
   end subroutine dp_parameter
end module dpend_double_pendulum
