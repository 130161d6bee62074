!> Explicit Runge–Kutta methods on (q, q̇).
module dpend_rk_explicit
   use dpend_kinds, only: dp
   use dpend_model, only: pendulum_t
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite, state_ok
   implicit none
   private
   public :: rk4_t

   !> The classical fourth-order Runge–Kutta method (Kutta 1901; Hairer, Nørsett,
   !> Wanner, Solving ODEs I, Table II.1.2).
   type, extends(integrator_t) :: rk4_t
   contains
      procedure :: step => rk4_step
      procedure :: name => rk4_name
      procedure :: order => rk4_order
   end type rk4_t

contains

   subroutine rk4_step(self, par, t, y, h, stat)
      class(rk4_t), intent(inout) :: self  !! the method
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(inout) :: t         !! time [s]
      real(dp), intent(inout) :: y(4)      !! state (q, q̇)
      real(dp), intent(inout) :: h         !! step [s]
      integer, intent(out) :: stat         !! status
      real(dp) :: k1(4), k2(4), k3(4), k4(4), ynew(4)
      k1 = self%rhs(par, y)
      k2 = self%rhs(par, y + 0.5_dp*h*k1)
      k3 = self%rhs(par, y + 0.5_dp*h*k2)
      k4 = self%rhs(par, y + h*k3)
      ynew = y + (h/6.0_dp)*(k1 + 2.0_dp*(k2 + k3) + k4)
      if (.not. state_ok(ynew)) then
         stat = stat_nonfinite
         return
      end if
      y = ynew
      t = t + h
      self%n_steps = self%n_steps + 1
      stat = stat_ok
   end subroutine rk4_step

   pure function rk4_name(self) result(name)
      class(rk4_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'rk4'
   end function rk4_name

   pure integer function rk4_order(self)
      class(rk4_t), intent(in) :: self
      rk4_order = 4
   end function rk4_order
end module dpend_rk_explicit
