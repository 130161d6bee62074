!> The energy balance of a damped or driven chain: the chain with the work
!> of its joint friction and of its support as two extra quadrature components,
!> integrated along the solution by the same method, to its order.
!>
!> The chain's balance (dpend_chain's notes) is dE/dt = P_support − P_friction, so
!>   W_friction(t) = ∫₀ᵗ Σ c_i (q̇_i − q̇_(i−1))² dt,  W_support(t) = ∫₀ᵗ F_(0,1) · v_A dt
!> make E(t) − E(0) + W_friction(t) − W_support(t) an error of the integration alone.
!>
!> The augmented model has n = N + 1 "degrees of freedom" so that the integrators'
!> state layout y = (y(1:n), y(n+1:2n)) holds unchanged: y = (q, W_friction, q̇,
!> W_support), f = (q̇, P_friction, q̈, P_support). It is not Hamiltonian (the methods
!> that need one refuse it, as they refuse the damped chain itself); the explicit
!> Runge–Kutta methods integrate it, their dense output interpolating the works too,
!> and the Gauss methods collocate it on (q, q̇) (the works to the same order). The work
!> components take part in the adaptive error control (joules, with the run's rtol
!> and atol), so the steps differ slightly from those of the chain alone.
module dpend_work
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_dof
   use dpend_chain, only: chain_t
   implicit none
   private
   public :: work_model_t, needs_work, work_model, split_work, is_work_model

   !> The chain and its two work integrals (state 2N + 2).
   type, extends(model_t) :: work_model_t
      type(chain_t) :: chain   !! the damped or driven chain
   contains
      procedure :: n_dof => work_n_dof
      procedure :: name => work_name
      procedure :: field => work_field
      procedure :: jacobian => work_jacobian
      procedure :: energy => work_energy
      procedure :: energy_scale => work_energy_scale
      procedure :: potential_energy => work_potential_energy
      procedure :: conservative => work_false
      procedure :: autonomous => work_autonomous
      procedure :: time_unit => work_time_unit
      procedure :: rest_state => work_rest_state
   end type work_model_t

contains

   !> The model dissipates or is driven, so that simulate integrates its works: a
   !> chain with damping or a moving support.
   pure logical function needs_work(model)
      class(model_t), intent(in) :: model   !! the system
      needs_work = .false.
      select type (model)
      type is (chain_t)
         needs_work = .not. model%conservative()
      end select
   end function needs_work

   !> The model is a chain with its works (`work_model_t`).
   pure logical function is_work_model(model)
      class(model_t), intent(in) :: model   !! the system
      is_work_model = .false.
      select type (model)
      type is (work_model_t)
         is_work_model = .true.
      end select
   end function is_work_model

   !> The augmented model of a chain (`needs_work` true), in `work`.
   subroutine work_model(model, work)
      class(model_t), intent(in) :: model                   !! a chain_t
      class(model_t), allocatable, intent(out) :: work      !! its work_model_t
      select type (model)
      type is (chain_t)
         allocate (work, source=work_model_t(chain=model))
      class default
         error stop 'internal error: work_model needs a chain'
      end select
   end subroutine work_model

   !> (q, q̇) and (W_friction, W_support) from the augmented pair q_aug = (q, W_friction),
   !> qd_aug = (q̇, W_support) of size N + 1 each.
   pure subroutine split_work(q_aug, qd_aug, q, qd, w)
      real(dp), intent(in) :: q_aug(:), qd_aug(:)   !! augmented halves of the state
      real(dp), intent(out) :: q(:), qd(:)          !! angles [rad], rates [rad/s] (N)
      real(dp), intent(out) :: w(2)                 !! W_friction, W_support [J]
      integer :: n
      n = size(q)
      q = q_aug(1:n); qd = qd_aug(1:n)
      w = [q_aug(n + 1), qd_aug(n + 1)]
   end subroutine split_work

   pure integer function work_n_dof(self)
      class(work_model_t), intent(in) :: self
      work_n_dof = self%chain%n + 1
   end function work_n_dof

   pure function work_name(self) result(name)
      class(work_model_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = self%chain%name()//' with its work integrals'
   end function work_name

   pure logical function work_false(self)
      class(work_model_t), intent(in) :: self
      work_false = .false.
   end function work_false

   pure logical function work_autonomous(self)
      class(work_model_t), intent(in) :: self
      work_autonomous = self%chain%autonomous()
   end function work_autonomous

   !> The chain's natural time unit.
   pure subroutine work_time_unit(self, seconds, name)
      class(work_model_t), intent(in) :: self             !! the model
      real(dp), intent(out) :: seconds                    !! the unit [s]
      character(len=:), allocatable, intent(out) :: name  !! 'sqrt(l1/g)'
      call self%chain%time_unit(seconds, name)
   end subroutine work_time_unit

   !> The chain's rest state, with no work done.
   pure subroutine work_rest_state(self, q)
      class(work_model_t), intent(in) :: self  !! the model
      real(dp), intent(out) :: q(:)            !! (q, W_friction) at rest
      call self%chain%rest_state(q(1:self%chain%n))
      q(self%chain%n + 1:) = 0.0_dp
   end subroutine work_rest_state

   !> The chain's state (q, q̇) of the augmented y.
   pure subroutine inner(n, y, yc)
      integer, intent(in) :: n           !! links N
      real(dp), intent(in) :: y(*)       !! (q, W_friction, q̇, W_support)
      real(dp), intent(out) :: yc(2*n)   !! (q, q̇)
      yc(1:n) = y(1:n)
      yc(n + 1:2*n) = y(n + 2:2*n + 1)
   end subroutine inner

   !> f = (q̇, P_friction, q̈, P_support).
   pure subroutine work_field(self, t, y, f)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: yc(2*max_dof), fc(2*max_dof), pf, ps
      integer :: n
      n = self%chain%n
      call inner(n, y, yc)
      call self%chain%field(t, yc, fc)
      call self%chain%powers(t, yc, fc(n + 1:2*n), pf, ps)
      f(1:n) = fc(1:n)
      f(n + 1) = pf
      f(n + 2:2*n + 1) = fc(n + 1:2*n)
      f(2*n + 2) = ps
   end subroutine work_field

   !> ∂f/∂y: the chain's Jacobian, rows of the powers by central differences (the
   !> works themselves enter nothing: zero columns).
   pure subroutine work_jacobian(self, t, y, jac)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: yc(2*max_dof), jc(2*self%chain%n, 2*self%chain%n)
      real(dp) :: fp(2*max_dof + 2), fm(2*max_dof + 2), yp(size(y)), d
      integer :: n, m, j, jj
      integer :: map(2*self%chain%n)
      n = self%chain%n
      m = 2*n + 2
      call inner(n, y, yc)
      call self%chain%jacobian(t, yc(1:2*n), jc)
      map = [(j, j = 1, n), (j, j = n + 2, 2*n + 1)]
      jac = 0.0_dp
      jac(map, map) = jc
      do jj = 1, 2*n
         j = map(jj)
         d = 1e-6_dp*max(1.0_dp, abs(y(j)))
         yp = y; yp(j) = y(j) + d
         call self%field(t, yp, fp)
         yp(j) = y(j) - d
         call self%field(t, yp, fm)
         jac(n + 1, j) = (fp(n + 1) - fm(n + 1))/(2.0_dp*d)
         jac(m, j) = (fp(m) - fm(m))/(2.0_dp*d)
      end do
   end subroutine work_jacobian

   !> The chain's energy (the works are not part of it).
   pure real(dp) function work_energy(self, t, y)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yc(2*max_dof)
      integer :: n
      n = self%chain%n
      call inner(n, y, yc)
      work_energy = self%chain%energy(t, yc(1:2*n))
   end function work_energy

   !> The chain's potential energy (the works are not part of it).
   pure real(dp) function work_potential_energy(self, t, y)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yc(2*max_dof)
      integer :: n
      n = self%chain%n
      call inner(n, y, yc)
      work_potential_energy = self%chain%potential_energy(t, yc(1:2*n))
   end function work_potential_energy

   pure real(dp) function work_energy_scale(self, e0)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: e0
      work_energy_scale = self%chain%energy_scale(e0)
   end function work_energy_scale
end module dpend_work
