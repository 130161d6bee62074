!> The energy balance of a damped or driven chain: the chain with the work
!> of its joint friction and of its support as two extra quadrature components,
!> integrated along the solution by the same method, to its order.
!>
!> The chain's balance (dpend_chain's notes) is dE/dt = P_support + P_torque −
!> P_friction, so
!>   W_friction(t) = ∫₀ᵗ Σ c_i (q̇_i − q̇_(i−1))² dt,  W_support(t) = ∫₀ᵗ F_(0,1) · v_A dt,
!>   W_torque(t) = ∫₀ᵗ Σ τ_i (q̇_i − q̇_(i−1)) dt
!> make E(t) − E(0) + W_friction(t) − W_support(t) − W_torque(t) an error of the
!> integration alone.
!>
!> The augmented model has n = N + k "degrees of freedom" so that the integrators'
!> state layout y = (y(1:n), y(n+1:2n)) holds unchanged. Without applied torques k = 1:
!> y = (q, W_friction, q̇, W_support), f = (q̇, P_friction, q̈, P_support). With them
!> k = 2: y = (q, W_friction, W_torque, q̇, W_support, 0), f = (q̇, P_friction, P_torque,
!> q̈, P_support, 0) (the last slot pads the halves to equal length; its rate is zero,
!> so it stays 0). It is not Hamiltonian (the methods
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
   public :: work_model_t, needs_work, work_model, split_work, is_work_model, &
             augmented_state, balance_energy, n_works, work_slots

   !> The works each `split_work` returns: W_friction, W_support, W_torque [J].
   integer, parameter :: n_works = 3

   !> The chain and its work integrals (state 2N + 2k).
   type, extends(model_t) :: work_model_t
      type(chain_t) :: chain   !! the damped or driven chain
      integer :: k = 1         !! work slots per half: 1, or 2 with applied torques
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
         allocate (work, source=work_model_t(chain=model, k=merge(2, 1, model%torqued)))
      class default
         error stop 'internal error: work_model needs a chain'
      end select
   end subroutine work_model

   !> The work slots k per half of the state (n_dof = N + k) of a work model, or of a
   !> chain integrated with its works (`needs_work`): 1, or 2 with applied torques (its
   !> works include W_torque); 0 for any other model.
   pure integer function work_slots(model)
      class(model_t), intent(in) :: model   !! the system
      work_slots = 0
      select type (model)
      type is (work_model_t)
         work_slots = model%k
      type is (chain_t)
         if (needs_work(model)) work_slots = merge(2, 1, model%torqued)
      end select
   end function work_slots

   !> (q, q̇) and (W_friction, W_support, W_torque) from the augmented pair q_aug =
   !> (q, W_friction[, W_torque]), qd_aug = (q̇, W_support[, 0]) of size N + k each
   !> (W_torque = 0 for k = 1).
   pure subroutine split_work(q_aug, qd_aug, q, qd, w)
      real(dp), intent(in) :: q_aug(:), qd_aug(:)   !! augmented halves of the state
      real(dp), intent(out) :: q(:), qd(:)          !! angles [rad], rates [rad/s] (N)
      real(dp), intent(out) :: w(n_works)           !! W_friction, W_support, W_torque [J]
      integer :: n
      n = size(q)
      q = q_aug(1:n); qd = qd_aug(1:n)
      w = [q_aug(n + 1), qd_aug(n + 1), 0.0_dp]
      if (size(q_aug) > n + 1) w(3) = q_aug(n + 2)
   end subroutine split_work

   !> The augmented halves (q, 0 …), (q̇, 0 …) of size n_dof of a work model (the works
   !> start at 0), or (q, q̇) for any other model.
   pure subroutine augmented_state(model, q, qd, q_aug, qd_aug)
      class(model_t), intent(in) :: model                  !! the system
      real(dp), intent(in) :: q(:), qd(:)                  !! angles, rates (N)
      real(dp), allocatable, intent(out) :: q_aug(:), qd_aug(:)  !! (n_dof each)
      allocate (q_aug(model%n_dof()), qd_aug(model%n_dof()))
      q_aug = 0.0_dp; qd_aug = 0.0_dp
      q_aug(1:size(q)) = q; qd_aug(1:size(qd)) = qd
   end subroutine augmented_state

   !> E(t) + W_friction − W_support − W_torque at the internal state y = (q, q̇ with
   !> works) of a work model, whose change from t = 0 is the error of the energy
   !> balance; the energy for any other model.
   pure real(dp) function balance_energy(model, t, y) result(e)
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: y(:)         !! state (2 n_dof)
      integer :: n
      e = model%energy(t, y)
      select type (model)
      type is (work_model_t)
         n = model%chain%n
         e = e + y(n + 1) - y(2*n + model%k + 1)
         if (model%k > 1) e = e - y(n + 2)
      end select
   end function balance_energy

   pure integer function work_n_dof(self)
      class(work_model_t), intent(in) :: self
      work_n_dof = self%chain%n + self%k
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
      real(dp), intent(out) :: q(:)            !! (q, W_friction[, W_torque]) at rest
      call self%chain%rest_state(q(1:self%chain%n))
      q(self%chain%n + 1:) = 0.0_dp
   end subroutine work_rest_state

   !> The chain's state (q, q̇) of the augmented y.
   pure subroutine inner(n, k, y, yc)
      integer, intent(in) :: n           !! links N
      integer, intent(in) :: k           !! work slots per half
      real(dp), intent(in) :: y(*)       !! (q, W_friction[, W_torque], q̇, W_support[, 0])
      real(dp), intent(out) :: yc(2*n)   !! (q, q̇)
      yc(1:n) = y(1:n)
      yc(n + 1:2*n) = y(n + k + 1:2*n + k)
   end subroutine inner

   !> f = (q̇, P_friction[, P_torque], q̈, P_support[, 0]).
   pure subroutine work_field(self, t, y, f)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: yc(2*max_dof), fc(2*max_dof), pf, ps, pt
      integer :: n, k
      n = self%chain%n
      k = self%k
      call inner(n, k, y, yc)
      call self%chain%field(t, yc, fc)
      if (k == 1) then
         call self%chain%powers(t, yc, fc(n + 1:2*n), pf, ps)
      else
         call self%chain%powers(t, yc, fc(n + 1:2*n), pf, ps, pt)
         f(n + 2) = pt
         f(2*n + 4) = 0.0_dp
      end if
      f(1:n) = fc(1:n)
      f(n + 1) = pf
      f(n + k + 1:2*n + k) = fc(n + 1:2*n)
      f(2*n + k + 1) = ps
   end subroutine work_field

   !> ∂f/∂y: the chain's Jacobian, rows of the powers by central differences (the
   !> works themselves enter nothing: zero columns).
   pure subroutine work_jacobian(self, t, y, jac)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: yc(2*max_dof), jc(2*self%chain%n, 2*self%chain%n)
      real(dp) :: fp(2*max_dof + 4), fm(2*max_dof + 4), yp(size(y)), d
      integer :: n, k, j, jj, r
      integer :: map(2*self%chain%n), rows(3)
      n = self%chain%n
      k = self%k
      call inner(n, k, y, yc)
      call self%chain%jacobian(t, yc(1:2*n), jc)
      map = [(j, j = 1, n), (j, j = n + k + 1, 2*n + k)]
      rows = [n + 1, 2*n + k + 1, n + 2]   ! P_friction, P_support[, P_torque]
      jac = 0.0_dp
      jac(map, map) = jc
      do jj = 1, 2*n
         j = map(jj)
         d = 1e-6_dp*max(1.0_dp, abs(y(j)))
         yp = y; yp(j) = y(j) + d
         call self%field(t, yp, fp)
         yp(j) = y(j) - d
         call self%field(t, yp, fm)
         do r = 1, merge(3, 2, k > 1)
            jac(rows(r), j) = (fp(rows(r)) - fm(rows(r)))/(2.0_dp*d)
         end do
      end do
   end subroutine work_jacobian

   !> The chain's energy (the works are not part of it).
   pure real(dp) function work_energy(self, t, y)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yc(2*max_dof)
      integer :: n
      n = self%chain%n
      call inner(n, self%k, y, yc)
      work_energy = self%chain%energy(t, yc(1:2*n))
   end function work_energy

   !> The chain's potential energy (the works are not part of it).
   pure real(dp) function work_potential_energy(self, t, y)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yc(2*max_dof)
      integer :: n
      n = self%chain%n
      call inner(n, self%k, y, yc)
      work_potential_energy = self%chain%potential_energy(t, yc(1:2*n))
   end function work_potential_energy

   pure real(dp) function work_energy_scale(self, e0)
      class(work_model_t), intent(in) :: self
      real(dp), intent(in) :: e0
      work_energy_scale = self%chain%energy_scale(e0)
   end function work_energy_scale
end module dpend_work
