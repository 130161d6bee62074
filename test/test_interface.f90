!> The model interface with a second model: a damped harmonic oscillator
!> q̈ = −ω² q − 2ζω q̇ (one degree of freedom, not Hamiltonian, not conservative),
!> written as a test-only `model_t` in a few lines. The generic integrator paths
!> (state size 2, not the double pendulum's 4) are compared with the closed form
!>   q(t) = e^(−ζωt) (q0 cos ω_d t + (v0 + ζω q0)/ω_d sin ω_d t),  ω_d = ω √(1 − ζ²),
!> (rk4, dop853, and gauss6 on (q, q̇)), and a method that needs a Hamiltonian (verlet)
!> must refuse the model.
module test_interface
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_interface

   real(dp), parameter :: omega = 2.0_dp, zeta = 0.1_dp
   real(dp), parameter :: q0 = 0.3_dp, v0 = -0.5_dp

   type, extends(model_t) :: oscillator_t
   contains
      procedure :: n_dof => osc_n_dof
      procedure :: name => osc_name
      procedure :: field => osc_field
      procedure :: jacobian => osc_jacobian
      procedure :: energy => osc_energy
      procedure :: energy_scale => osc_energy_scale
      procedure :: potential_energy => osc_potential_energy
      procedure :: conservative => osc_false
   end type oscillator_t

contains

   subroutine collect_interface(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('hamiltonian_method_refuses_damped_model', test_refuse), &
               new_unittest('oscillator_closed_form_rk4_dop853_gauss6', test_closed_form), &
               new_unittest('oscillator_rk4_order_4', test_order)]
   end subroutine collect_interface

   pure integer function osc_n_dof(self)
      class(oscillator_t), intent(in) :: self
      osc_n_dof = 1
   end function osc_n_dof

   pure function osc_name(self) result(name)
      class(oscillator_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'damped oscillator'
   end function osc_name

   pure subroutine osc_field(self, t, y, f)
      class(oscillator_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      f(1) = y(2)
      f(2) = -omega**2*y(1) - 2.0_dp*zeta*omega*y(2)
   end subroutine osc_field

   pure subroutine osc_jacobian(self, t, y, jac)
      class(oscillator_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      jac = reshape([0.0_dp, -omega**2, 1.0_dp, -2.0_dp*zeta*omega], [2, 2])
   end subroutine osc_jacobian

   pure real(dp) function osc_energy(self, t, y)
      class(oscillator_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      osc_energy = 0.5_dp*(y(2)**2 + omega**2*y(1)**2)
   end function osc_energy

   pure real(dp) function osc_potential_energy(self, t, y)
      class(oscillator_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      osc_potential_energy = 0.5_dp*omega**2*y(1)**2
   end function osc_potential_energy

   pure real(dp) function osc_energy_scale(self, e0)
      class(oscillator_t), intent(in) :: self
      real(dp), intent(in) :: e0
      osc_energy_scale = abs(e0)
   end function osc_energy_scale

   pure logical function osc_false(self)
      class(oscillator_t), intent(in) :: self
      osc_false = .false.
   end function osc_false

   !> The closed form (q, q̇) at time t.
   pure function exact(t) result(y)
      real(dp), intent(in) :: t
      real(dp) :: y(2), wd, a, b, c, s
      wd = omega*sqrt(1.0_dp - zeta**2)
      a = q0; b = (v0 + zeta*omega*q0)/wd
      c = cos(wd*t); s = sin(wd*t)
      y(1) = exp(-zeta*omega*t)*(a*c + b*s)
      y(2) = exp(-zeta*omega*t)*(-zeta*omega*(a*c + b*s) + wd*(b*c - a*s))
   end function exact

   !> |(q, q̇/ω)(1 s) − exact| for `name` with fixed step h (0: adaptive at rtol 1e-12).
   real(dp) function error_at_1s(name, h) result(err)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: h
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: error
      type(oscillator_t) :: model
      real(dp) :: t, y(2), hh
      integer :: stat
      call new_integrator(name, integ, error, method_options_t(rtol=1e-12_dp, atol=1e-14_dp))
      t = 0.0_dp; y = [q0, v0]; hh = h
      call advance_to(integ, model, t, y, 1.0_dp, hh, stat)
      err = huge(1.0_dp)
      if (stat == stat_ok) err = norm2((y - exact(1.0_dp))*[1.0_dp, 1.0_dp/omega])
   end function error_at_1s

   subroutine test_refuse(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(oscillator_t) :: model
      call new_integrator('verlet', integ, err)
      call integ%check_model(model, err)
      call check_true(error, allocated(err), 'verlet accepted a damped model')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'verlet needs a Hamiltonian model') > 0, &
                      'message: '//err%message)
      if (allocated(error)) return
      deallocate (err)
      call new_integrator('rk4', integ, err)
      call integ%check_model(model, err)
      call check_true(error, .not. allocated(err), 'rk4 refused a damped model')
      if (allocated(error)) return
      call new_integrator('gauss6', integ, err)
      call integ%check_model(model, err)
      call check_true(error, .not. allocated(err), 'gauss6 refused a damped model')
   end subroutine test_refuse

   !> rk4 (h = 1e-3, error O(h⁴) ~ 1e-13), dop853 (rtol 1e-12) and gauss6 (h = 1e-2,
   !> on (q, q̇): the model has no Hamiltonian; error O(h⁶)) on the closed form.
   subroutine test_closed_form(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: e_rk4, e_853, e_g6
      e_rk4 = error_at_1s('rk4', 1e-3_dp)
      e_853 = error_at_1s('dop853', 0.0_dp)
      e_g6 = error_at_1s('gauss6', 1e-2_dp)
      call check_true(error, e_rk4 < 1e-11_dp, 'rk4 error '//real_str(e_rk4, 3))
      if (allocated(error)) return
      call check_true(error, e_853 < 1e-10_dp, 'dop853 error '//real_str(e_853, 3))
      if (allocated(error)) return
      call check_true(error, e_g6 < 1e-13_dp, 'gauss6 error '//real_str(e_g6, 3))
   end subroutine test_closed_form

   !> Halving h divides rk4's error by 2⁴: measured order within 0.2 of 4.
   subroutine test_order(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: e1, e2, order
      e1 = error_at_1s('rk4', 0.02_dp)
      e2 = error_at_1s('rk4', 0.01_dp)
      order = log(e1/e2)/log(2.0_dp)
      call check(error, order, 4.0_dp, 'measured rk4 order', abs=0.2_dp)
   end subroutine test_order

end module test_interface
