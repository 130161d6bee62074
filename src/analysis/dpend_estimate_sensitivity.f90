!> The model whose tangents are the sensitivities of `dpend fit`: a model with its
!> fitted parameters carried as constant state components (`sens_model_t`).
!>
!> Sensitivities. The model is integrated by one of the explicit Runge–Kutta methods
!> (default dop853) landing exactly on every sample time (no interpolation of the
!> data's instants), and the tangent propagation of `dpend_tangent` carries
!> ∂y/∂p along each step. For the damping it is the augmented system: the
!> coefficients are carried as constant state components (`sens_model_t`:
!> y' = (q, c, q̇, 0) with rates (q̇, 0, q̈, 0)), so that the variational equation of
!> the augmented field, whose Jacobian has the column block ∂q̈/∂c = M⁻¹ ∂Q/∂c
!> (Q = −C q̇ the damping torques), gives the parameter sensitivities
!> s' = J s + ∂f/∂c with the same RK4 substeps as those of the state — no finite
!> differences (the test suite compares them with central differences).
module dpend_estimate_sensitivity
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_dof
   implicit none
   private
   public :: sens_model_t

   !> A model held by an array element (the finite-difference models).
   type :: model_box_t
      class(model_t), allocatable :: m
   end type model_box_t

   !> A model with its damping carried as constant state components (see the notes).
   type, extends(model_t) :: sens_model_t
      class(model_t), allocatable :: base   !! the system
      integer :: n = 0                      !! its degrees of freedom N
      integer :: nc = 0                     !! fitted parameter components
      !> per component: its parameter's name, that parameter's components, which one
      character(len=32), allocatable :: names(:)
      integer, allocatable :: counts(:), index(:)
      !> per component: central differences of the field (no `parameter_rates`), the
      !> two models of its stencil and the weights of base, fd(1), fd(2) [1/unit]
      logical, allocatable :: generic(:)
      type(model_box_t), allocatable :: fd(:, :)
      real(dp), allocatable :: fw(:, :)
   contains
      procedure :: n_dof => sens_n_dof
      procedure :: name => sens_name
      procedure :: field => sens_field
      procedure :: jacobian => sens_jacobian
      procedure :: energy => sens_energy
      procedure :: energy_scale => sens_energy_scale
      procedure :: potential_energy => sens_potential_energy
      procedure :: conservative => sens_false
      procedure :: autonomous => sens_autonomous
   end type sens_model_t

contains

   pure integer function sens_n_dof(self)
      class(sens_model_t), intent(in) :: self
      sens_n_dof = self%n + self%nc
   end function sens_n_dof

   pure function sens_name(self) result(name)
      class(sens_model_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = self%base%name()//' with its parameters'
   end function sens_name

   pure logical function sens_false(self)
      class(sens_model_t), intent(in) :: self
      sens_false = .false.
   end function sens_false

   pure logical function sens_autonomous(self)
      class(sens_model_t), intent(in) :: self
      sens_autonomous = self%base%autonomous()
   end function sens_autonomous

   !> (q, q̇) of the augmented y = (q, c, q̇, z).
   pure subroutine inner(n, nc, y, yb)
      integer, intent(in) :: n, nc
      real(dp), intent(in) :: y(*)
      real(dp), intent(out) :: yb(2*n)
      yb(1:n) = y(1:n)
      yb(n + 1:2*n) = y(n + nc + 1:2*n + nc)
   end subroutine inner

   pure subroutine sens_field(self, t, y, f)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: yb(2*max_dof), fb(2*max_dof)
      integer :: n, nc
      n = self%n
      nc = self%nc
      call inner(n, nc, y, yb)
      call self%base%field(t, yb, fb)
      f(1:n) = fb(1:n)
      f(n + 1:n + nc) = 0.0_dp
      f(n + nc + 1:2*n + nc) = fb(n + 1:2*n)
      f(2*n + nc + 1:2*n + 2*nc) = 0.0_dp
   end subroutine sens_field

   !> The base Jacobian and, for the fitted parameters θ, ∂q̈/∂θ from the model
   !> (`parameter_rates`).
   !> A component without `parameter_rates` (`generic`): the weighted field of the
   !> stencil's models, w_1 (f(θ + h_1) − f(θ)) + w_2 (f(θ + h_2) − f(θ)) (central
   !> differences, or one-sided of second order at an end of the parameter's range).
   pure subroutine sens_jacobian(self, t, y, jac)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: yb(2*self%n), jb(2*self%n, 2*self%n), d(self%n, self%nc)
      real(dp) :: dall(self%n, max_dof), f0(2*max_dof), f1(2*max_dof), f2(2*max_dof)
      integer :: n, nc, j, c
      integer :: map(2*self%n)
      logical :: have_f0
      n = self%n
      nc = self%nc
      call inner(n, nc, y, yb)
      call self%base%jacobian(t, yb, jb)
      map = [(j, j=1, n), (j, j=n + nc + 1, 2*n + nc)]
      jac = 0.0_dp
      jac(map, map) = jb
      if (nc == 0) return
      have_f0 = .false.
      do c = 1, nc
         if (self%generic(c)) then
            if (.not. have_f0) call self%base%field(t, yb, f0)
            have_f0 = .true.
            call self%fd(1, c)%m%field(t, yb, f1)
            call self%fd(2, c)%m%field(t, yb, f2)
            ! the weights sum to 0: differences first, so that a parameter without
            ! effect gives exactly 0 (whatever the compiler contracts into FMAs)
            d(:, c) = self%fw(2, c)*(f1(n + 1:2*n) - f0(n + 1:2*n)) + &
                      self%fw(3, c)*(f2(n + 1:2*n) - f0(n + 1:2*n))
         else
            ! the model's rates of the whole parameter, once per parameter
            if (c == 1) then
               call self%base%parameter_rates(t, yb, trim(self%names(c)), &
                                              dall(:, :self%counts(c)))
            else if (self%names(c) /= self%names(c - 1) .or. self%generic(c - 1)) then
               call self%base%parameter_rates(t, yb, trim(self%names(c)), &
                                              dall(:, :self%counts(c)))
            end if
            d(:, c) = dall(:, self%index(c))
         end if
      end do
      jac(n + nc + 1:2*n + nc, n + 1:n + nc) = d
   end subroutine sens_jacobian

   pure real(dp) function sens_energy(self, t, y)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yb(2*self%n)
      call inner(self%n, self%nc, y, yb)
      sens_energy = self%base%energy(t, yb)
   end function sens_energy

   pure real(dp) function sens_potential_energy(self, t, y)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: yb(2*self%n)
      call inner(self%n, self%nc, y, yb)
      sens_potential_energy = self%base%potential_energy(t, yb)
   end function sens_potential_energy

   pure real(dp) function sens_energy_scale(self, e0)
      class(sens_model_t), intent(in) :: self
      real(dp), intent(in) :: e0
      sens_energy_scale = self%base%energy_scale(e0)
   end function sens_energy_scale
end module dpend_estimate_sensitivity
