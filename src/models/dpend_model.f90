!> The abstract model: what every integrator, analysis and writer may ask of a
!> mechanical system with n degrees of freedom (docs/architecture.md).
!>
!> The state is y = (q, q̇), size 2n: generalized coordinates q [rad for the chain
!> models] and their rates. Every procedure takes the time t, so that a model may be
!> time-dependent (a moving support); an autonomous model ignores it.
!>
!> Structure a model may have, and says it has:
!> - `hamiltonian()`: canonical variables z = (q, p) with p = ∂L/∂q̇, H(q, p), the
!>   Hamiltonian vector field (∂H/∂p, −∂H/∂q) and its Jacobian. Methods on (q, p)
!>   use it; Störmer–Verlet, its compositions and Tao's need it and refuse a model
!>   without it (`check_model`), the Gauss methods then run on (q, q̇). A damped
!>   model is not Hamiltonian.
!> - `conservative()`: the energy is a constant of motion, so that energy-error
!>   verdicts apply (false for damping or a moving support).
!> - fast paths: `cache_size() > 0` means the model keeps quantities of the step start
!>   (for the double pendulum: sin and cos of the angles) in a cache that
!>   `field_near` / `canonical_field_near` update for states near the start by angle
!>   addition. Integrators call these hooks without knowing what the cache holds;
!>   the defaults ignore the cache and evaluate the field.
!>
!> Models describe themselves: `coordinate` names each q_i with its units (and the
!> units of its momentum), `coordinates_text` says what q, q̇ and q̈ are, and
!> `figure` names the outputs a figure or the animation draws (the anchor, the
!> chain of points, the style, the forces), so that no consumer infers them.
!>
!> Writers ask for `n_outputs` named quantities per sample (kinematics, joint
!> reactions, …, with units) and the model's named parameters, so that a writer never
!> names a model's fields.
!>
!> The hot procedures (`field`, `canonical_field`, `fill_cache`, `field_near`,
!> `canonical_field_near`) take assumed-size arrays of the model's own size (2n, n,
!> `cache_size()`): no array descriptors on the integrators' inner loop.
!>
!> Procedures for structure a model lacks have default bodies that are never reached:
!> the factory refuses such a method before any step (they `error stop` as an internal
!> check, with a message naming the model and the procedure).
module dpend_model
   use, intrinsic :: iso_fortran_env, only: real128
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, error_bad_input
   use dpend_limits, only: check_range, max_angle, max_angular_velocity
   implicit none
   private
   public :: model_t, max_dof, max_state
   public :: model_check_parameter_rates  ! the refusal models extend

   !> Most degrees of freedom of any model: integrators keep their stage vectors on
   !> the stack in arrays of this size (no allocation per step).
   integer, parameter :: max_dof = 32
   !> Most state components, 2 max_dof.
   integer, parameter :: max_state = 2*max_dof

   type, abstract :: model_t
   contains
      procedure(n_dof_i), deferred :: n_dof
      procedure(name_i), deferred :: name
      procedure(field_i), deferred :: field
      procedure(jacobian_i), deferred :: jacobian
      procedure(energy_i), deferred :: energy
      procedure(energy_scale_i), deferred :: energy_scale
      !> The energy split E = T + V: the potential part V(t, y), and the kinetic part
      !> T (default E − V; a model with its own formula for T overrides it).
      procedure(energy_i), deferred :: potential_energy
      procedure :: kinetic_energy => model_kinetic_energy
      !> Size 2n of the state vector.
      procedure, non_overridable :: n_state
      procedure :: hamiltonian => model_false
      procedure :: conservative => model_true
      procedure :: autonomous => model_true
      ! the Hamiltonian structure (models with hamiltonian() true override all five)
      procedure :: momenta => model_momenta
      procedure :: velocities => model_velocities
      procedure :: hamiltonian_value => model_hamiltonian_value
      procedure :: canonical_field => model_canonical_field
      procedure :: canonical_jacobian => model_canonical_jacobian
      ! gradient of the energy in (q, q̇) (the divergence's energy-shell projection)
      procedure :: energy_gradient => model_energy_gradient
      ! energy-shell sections of a two-degree-of-freedom Hamiltonian (Poincaré maps)
      procedure :: energy_sections => model_false
      procedure :: section_state => model_section_state
      procedure :: section_p_max => model_section_p_max
      ! fast-path hooks
      procedure :: cache_size => model_cache_size
      procedure :: fill_cache => model_fill_cache
      procedure :: fill_cache_field => model_fill_cache_field
      procedure :: field_near => model_field_near
      procedure :: canonical_field_near => model_canonical_field_near
      ! what writers need
      procedure :: n_outputs => model_none
      procedure :: output_info => model_output_info
      procedure :: outputs => model_outputs
      procedure :: n_parameters => model_none
      procedure :: parameter => model_parameter
      ! what writers, figures and the animation need to know of the coordinates
      procedure :: coordinate => model_coordinate
      procedure :: coordinates_text => model_coordinates_text
      procedure :: energy_text => model_energy_text
      procedure :: figure => model_figure
      ! an initial state within the model (before any step)
      procedure :: check_state => model_check_state
      ! H in quadruple precision for the study's roundoff runs (default: none)
      procedure :: has_hamiltonian_qp => model_false
      procedure :: hamiltonian_qp => model_hamiltonian_qp
      ! the sensitivities of the motion to a model parameter (dpend fit)
      procedure :: check_parameter_rates => model_check_parameter_rates
      procedure :: parameter_rates => model_parameter_rates
      ! sweep (one construction site): G_i of V = Σ G_i sin q_i, if V has that form
      procedure :: potential_weights => model_potential_weights
      ! the chain lanes: K_ij of M_ij = K_ij cos(q_i − q_j), if T has that form
      procedure :: mass_weights => model_mass_weights
      ! the links' mass distribution for files and summaries
      procedure :: body_description => model_body_description
      ! the natural time unit of the motion (sweeps and summaries count time in it)
      procedure :: time_unit => model_time_unit
      ! the period of the slowest small oscillation about rest (the fit's hold window)
      procedure :: swing_period => model_swing_period
      ! the state of rest (hanging): where a tiny run or a test may start near
      procedure :: rest_state => model_rest_state
   end type model_t

   abstract interface
      !> Degrees of freedom n (the state has 2n components).
      pure integer function n_dof_i(self)
         import :: model_t
         class(model_t), intent(in) :: self
      end function n_dof_i
      !> Short name, e.g. 'double pendulum'.
      pure function name_i(self) result(name)
         import :: model_t
         class(model_t), intent(in) :: self
         character(len=:), allocatable :: name
      end function name_i
      !> The vector field f(t, y) = (q̇, q̈) for y = (q, q̇).
      pure subroutine field_i(self, t, y, f)
         import :: model_t, dp
         class(model_t), intent(in) :: self
         real(dp), intent(in) :: t       !! time [s]
         real(dp), intent(in) :: y(*)    !! state (q, q̇), size 2n
         real(dp), intent(out) :: f(*)   !! (q̇, q̈), size 2n
      end subroutine field_i
      !> The Jacobian ∂f/∂y of `field`, (2n, 2n).
      pure subroutine jacobian_i(self, t, y, jac)
         import :: model_t, dp
         class(model_t), intent(in) :: self
         real(dp), intent(in) :: t          !! time [s]
         real(dp), intent(in) :: y(:)       !! state (q, q̇)
         real(dp), intent(out) :: jac(:, :) !! ∂f/∂y
      end subroutine jacobian_i
      !> Mechanical energy E(t, y) = T + V [J].
      pure real(dp) function energy_i(self, t, y)
         import :: model_t, dp
         class(model_t), intent(in) :: self
         real(dp), intent(in) :: t      !! time [s]
         real(dp), intent(in) :: y(:)   !! state (q, q̇)
      end function energy_i
      !> The unit of relative energy errors for a run starting with energy e0 [J].
      pure real(dp) function energy_scale_i(self, e0)
         import :: model_t, dp
         class(model_t), intent(in) :: self
         real(dp), intent(in) :: e0     !! initial energy [J]
      end function energy_scale_i
   end interface

contains

   pure integer function n_state(self)
      class(model_t), intent(in) :: self  !! the model
      n_state = 2*self%n_dof()
   end function n_state

   !> Default of a structure query: false.
   pure logical function model_false(self)
      class(model_t), intent(in) :: self  !! the model
      model_false = .false.
   end function model_false

   !> Default of a structure query: true.
   pure logical function model_true(self)
      class(model_t), intent(in) :: self  !! the model
      model_true = .true.
   end function model_true

   !> Unreachable default (the caller checks `hamiltonian()` first).
   pure subroutine lacks(what)
      character(len=*), intent(in) :: what  !! the missing procedure
      error stop 'internal error: the model has no '//what
   end subroutine lacks

   !> Canonical momenta p(t, q, q̇) [kg m²/s for angles].
   pure subroutine model_momenta(self, t, y, p)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t        !! time [s]
      real(dp), intent(in) :: y(:)     !! state (q, q̇)
      real(dp), intent(out) :: p(:)    !! momenta, size n
      p = 0.0_dp
      call lacks('momenta (not a Hamiltonian model)')
   end subroutine model_momenta

   !> Rates q̇ = ∂H/∂p from z = (q, p).
   pure subroutine model_velocities(self, t, z, qd)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t        !! time [s]
      real(dp), intent(in) :: z(:)     !! canonical state (q, p)
      real(dp), intent(out) :: qd(:)   !! q̇, size n
      qd = 0.0_dp
      call lacks('velocities (not a Hamiltonian model)')
   end subroutine model_velocities

   !> H(t, z) [J].
   pure real(dp) function model_hamiltonian_value(self, t, z) result(h)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t        !! time [s]
      real(dp), intent(in) :: z(:)     !! canonical state (q, p)
      h = 0.0_dp
      call lacks('Hamiltonian')
   end function model_hamiltonian_value

   !> The Hamiltonian vector field (∂H/∂p, −∂H/∂q) at z = (q, p).
   pure subroutine model_canonical_field(self, t, z, f)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t        !! time [s]
      real(dp), intent(in) :: z(*)     !! canonical state (q, p)
      real(dp), intent(out) :: f(*)    !! (∂H/∂p, −∂H/∂q)
      f(:self%n_state()) = 0.0_dp
      call lacks('Hamiltonian vector field')
   end subroutine model_canonical_field

   !> Jacobian of `canonical_field`.
   pure subroutine model_canonical_jacobian(self, t, z, jac)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t          !! time [s]
      real(dp), intent(in) :: z(:)       !! canonical state (q, p)
      real(dp), intent(out) :: jac(:, :) !! ∂f/∂z
      jac = 0.0_dp
      call lacks('Jacobian of the Hamiltonian vector field')
   end subroutine model_canonical_jacobian

   !> ∂E/∂y at y = (q, q̇). Default: central differences with steps scaled to each
   !> component (relative accuracy ~1e-10); models override it with the exact form.
   pure subroutine model_energy_gradient(self, t, y, g)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t        !! time [s]
      real(dp), intent(in) :: y(:)     !! state (q, q̇)
      real(dp), intent(out) :: g(:)    !! ∂E/∂y
      real(dp) :: yp(size(y)), ym(size(y)), d
      integer :: i
      do i = 1, size(y)
         d = 1e-5_dp*max(1.0_dp, abs(y(i)))
         yp = y; ym = y
         yp(i) = y(i) + d; ym(i) = y(i) - d
         g(i) = (self%energy(t, yp) - self%energy(t, ym))/(2.0_dp*d)
      end do
   end subroutine model_energy_gradient

   !> The state on the section q_link = angle with the other coordinate q_o, its
   !> momentum p_o and energy e (models with `energy_sections()`; dpend_poincare).
   pure subroutine model_section_state(self, e, link, angle, direction, q_o, p_o, q, qd, &
                                       found)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: e, angle, q_o, p_o   !! energy [J], section, other q and p
      integer, intent(in) :: link, direction       !! section coordinate, sign of its rate
      real(dp), intent(out) :: q(:), qd(:)         !! the state
      logical, intent(out) :: found                !! (q_o, p_o) is inside the shell
      q = 0.0_dp; qd = 0.0_dp; found = .false.
      call lacks('energy-shell sections')
   end subroutine model_section_state

   !> Largest |p_o| on the energy shell of the section (see `section_state`).
   pure real(dp) function model_section_p_max(self, e, link, angle) result(p)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: e, angle   !! energy [J], section angle [rad]
      integer, intent(in) :: link        !! section coordinate
      p = 0.0_dp
      call lacks('energy-shell sections')
   end function model_section_p_max

   !> No fast path by default.
   pure integer function model_cache_size(self)
      class(model_t), intent(in) :: self
      model_cache_size = 0
   end function model_cache_size

   !> Fill the step-start cache from the coordinates q (nothing by default).
   pure subroutine model_fill_cache(self, q, cache)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: q(*)         !! coordinates at the step start
      real(dp), intent(inout) :: cache(*)  !! the model's cache, size cache_size()
   end subroutine model_fill_cache

   !> `fill_cache` from the coordinates of y, and `field` at y (an explicit step's
   !> first stage: one call where two would sit on the step's critical path).
   pure subroutine model_fill_cache_field(self, t, y, cache, f)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: y(*)         !! state (q, q̇) at the step start
      real(dp), intent(inout) :: cache(*)  !! the model's cache, filled
      real(dp), intent(out) :: f(*)        !! (q̇, q̈) at y
      call self%fill_cache(y, cache)
      call self%field(t, y, f)
   end subroutine model_fill_cache_field

   !> `field` at y, whose coordinates are those of the cache plus d (|d| small);
   !> the default ignores the cache.
   pure subroutine model_field_near(self, t, y, d, cache, f)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t          !! time [s]
      real(dp), intent(in) :: y(*)       !! state (q, q̇)
      real(dp), intent(in) :: d(*)       !! q minus the coordinates of the cache
      real(dp), intent(in) :: cache(*)   !! from `fill_cache`
      real(dp), intent(out) :: f(*)      !! (q̇, q̈)
      call self%field(t, y, f)
   end subroutine model_field_near

   !> `canonical_field` at z with the step-start cache (see `field_near`).
   pure subroutine model_canonical_field_near(self, t, z, d, cache, f)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t          !! time [s]
      real(dp), intent(in) :: z(*)       !! canonical state (q, p)
      real(dp), intent(in) :: d(*)       !! q minus the coordinates of the cache
      real(dp), intent(in) :: cache(*)   !! from `fill_cache`
      real(dp), intent(out) :: f(*)      !! (∂H/∂p, −∂H/∂q)
      call self%canonical_field(t, z, f)
   end subroutine model_canonical_field_near

   !> Default count of named outputs and of named parameters: none.
   pure integer function model_none(self)
      class(model_t), intent(in) :: self
      model_none = 0
   end function model_none

   !> Name, number of components, units and description of output i; `rows` > 0 says
   !> that the n_comp values of a sample are `rows` vectors of n_comp/rows components
   !> (e.g. (x, y) per joint), written with shape (samples, rows, n_comp/rows) as
   !> h5py shows it; 0 (the default) writes (samples, n_comp).
   subroutine model_output_info(self, i, name, n_comp, units, description, rows)
      class(model_t), intent(in) :: self
      integer, intent(in) :: i                                   !! 1 … n_outputs()
      character(len=:), allocatable, intent(out) :: name         !! dataset name
      integer, intent(out) :: n_comp                             !! components per sample
      character(len=:), allocatable, intent(out) :: units        !! SI units
      character(len=:), allocatable, intent(out) :: description  !! one line
      integer, intent(out), optional :: rows                     !! vectors per sample
      name = ''; n_comp = 0; units = ''; description = ''
      if (present(rows)) rows = 0
      call lacks('outputs')
   end subroutine model_output_info

   !> All outputs of one sample, concatenated in the order of `output_info`, from the
   !> state y = (q, q̇) and its rate f = (q̇, q̈) at time t.
   pure subroutine model_outputs(self, t, y, f, values)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t          !! time [s]
      real(dp), intent(in) :: y(:)       !! state (q, q̇)
      real(dp), intent(in) :: f(:)       !! field at y
      real(dp), intent(out) :: values(:) !! Σ n_comp values
      values = 0.0_dp
   end subroutine model_outputs

   !> Name, value and units of parameter i (1 … n_parameters()).
   subroutine model_parameter(self, i, name, value, units)
      class(model_t), intent(in) :: self
      integer, intent(in) :: i                              !! parameter index
      character(len=:), allocatable, intent(out) :: name    !! attribute name
      real(dp), intent(out) :: value                        !! its value
      character(len=:), allocatable, intent(out) :: units   !! SI units
      name = ''; value = 0.0_dp; units = ''
      call lacks('parameters')
   end subroutine model_parameter

   !> Coordinate i: its name, its units and the units of its momentum. The default:
   !> q_i [1] with momentum [J s]; every concrete model says what its q are.
   subroutine model_coordinate(self, i, name, units, momentum_units)
      class(model_t), intent(in) :: self
      integer, intent(in) :: i                                     !! 1..n
      character(len=:), allocatable, intent(out) :: name           !! e.g. 'q1', 'r'
      character(len=:), allocatable, intent(out) :: units          !! e.g. 'rad', 'm'
      character(len=:), allocatable, intent(out) :: momentum_units !! of p_i = dL/dq̇_i
      character(len=12) :: digits
      write (digits, '(i0)') i
      name = 'q'//trim(digits); units = '1'; momentum_units = 'J s'
   end subroutine model_coordinate

   !> What the datasets of q (order 0), q̇ (1) and q̈ (2) hold, one line each.
   function model_coordinates_text(self, order) result(text)
      class(model_t), intent(in) :: self
      integer, intent(in) :: order                  !! 0: q, 1: q̇, 2: q̈
      character(len=:), allocatable :: text
      select case (order)
      case (0); text = 'generalized coordinates q'
      case (1); text = 'their rates qdot'
      case default; text = 'their second derivatives qddot'
      end select
   end function model_coordinates_text

   !> What a figure draws, by output name: `anchor` (a point (x, y), the support),
   !> `points` (a chain of points (rows, 2) drawn from the anchor on), `style`
   !> ('rods': straight segments; 'spring': a coil from the anchor to each point) and
   !> `forces` (one (x, y) per segment, acting at its start). Empty names: nothing to
   !> draw (the default).
   subroutine model_figure(self, anchor, points, style, forces)
      class(model_t), intent(in) :: self
      character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      anchor = ''; points = ''; style = ''; forces = ''
   end subroutine model_figure

   !> Refuse an initial state (q, q̇) outside what the model accepts, in one line
   !> naming the component (q1, w2, ...), its value and the range. The default: every
   !> q_i an angle within ±1e6 rad (beyond, its rounding exceeds 1e-10 rad), every q̇_i
   !> within ±1e6 rad/s (energies and momenta stay finite).
   subroutine model_check_state(self, q, qd, error)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: q(:)                      !! coordinates
      real(dp), intent(in) :: qd(:)                     !! their rates
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      character(len=12) :: digits
      integer :: i
      do i = 1, size(q)
         write (digits, '(i0)') i
         call check_range('q'//trim(digits), q(i), -max_angle, max_angle, 'rad', error, &
                          'beyond, the rounding of the angle exceeds 1e-10 rad')
         if (allocated(error)) return
      end do
      do i = 1, size(qd)
         write (digits, '(i0)') i
         call check_range('w'//trim(digits), qd(i), -max_angular_velocity, &
                          max_angular_velocity, 'rad/s', error, &
                          'keeps energies and momenta finite')
         if (allocated(error)) return
      end do
   end subroutine model_check_state

   !> The kinetic energy T = E − V [J] (models with their own formula override it).
   pure real(dp) function model_kinetic_energy(self, t, y)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t      !! time [s]
      real(dp), intent(in) :: y(:)   !! state (q, q̇)
      model_kinetic_energy = self%energy(t, y) - self%potential_energy(t, y)
   end function model_kinetic_energy

   !> What the energy dataset holds: T + V and where V = 0 (the default: the chain of
   !> rods' zero, every link horizontal, the pin at its mean height).
   function model_energy_text(self) result(text)
      class(model_t), intent(in) :: self
      character(len=:), allocatable :: text
      if (self%autonomous()) then
         text = 'total energy T + V (V = 0 with every link horizontal)'
      else
         text = 'total energy T + V in the fixed frame (V = 0 at y = 0, the mean height of ' &
                //'the pin A)'
      end if
   end function model_energy_text

   !> H(z + e) in quadruple precision at the compensated canonical state [J], for
   !> energy errors below the double-precision rounding of H (the study's roundoff
   !> runs). Models with `has_hamiltonian_qp()` override it; the study makes no
   !> roundoff runs on the others, so this default is never reached.
   pure function model_hamiltonian_qp(self, z, e) result(h)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: z(:)     !! canonical state (q, p)
      real(dp), intent(in) :: e(:)     !! its compensation (0 without)
      real(real128) :: h
      h = 0.0_real128
      call lacks('Hamiltonian in quadruple precision')
   end function model_hamiltonian_qp

   ! the sensitivities of the motion to a model parameter (dpend fit)

   !> Refuse a fit of parameter `name` when the model cannot give `parameter_rates`
   !> for it (the default: no parameter; a refusal of kind bad input).
   subroutine model_check_parameter_rates(self, name, error)
      class(model_t), intent(in) :: self
      character(len=*), intent(in) :: name              !! parameter name, e.g. 'damping'
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      call fatal_error(error, 'invalid fit parameter: '//name//' (model '//self%name()// &
                       ' gives no sensitivity of its motion to it)', error_bad_input)
   end subroutine model_check_parameter_rates

   !> ∂q̈/∂θ_j at y = (q, q̇) for the components θ_j of parameter `name` (column j
   !> of `d`, size (n, components)), the other parameters and q, q̇ held. Reached only
   !> for a parameter `check_parameter_rates` accepted; the default gives zeros.
   pure subroutine model_parameter_rates(self, t, y, name, d)
      class(model_t), intent(in) :: self
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: y(:)         !! state (q, q̇)
      character(len=*), intent(in) :: name !! parameter name
      real(dp), intent(out) :: d(:, :)     !! ∂q̈/∂θ (n, components)
      d = 0.0_dp
   end subroutine model_parameter_rates

   !> The weights G_i [J] of a potential V = Σ G_i sin q_i (rods' angles q_i): the
   !> sweep's flip energy bounds and energy-error unit. Default: none (size 0), the
   !> potential has another form.
   pure function model_potential_weights(self) result(gl)
      class(model_t), intent(in) :: self  !! the model
      real(dp), allocatable :: gl(:)
      allocate (gl(0))
   end function model_potential_weights

   !> The weights K_ij [kg m²] of a mass matrix M_ij = K_ij cos(q_i − q_j) (rods'
   !> angles q_i, a fixed pin): with `potential_weights`, the constants of the chain
   !> lanes' equations of motion. Default: none (size 0 × 0), the kinetic energy has
   !> another form or the lanes do not serve the model.
   pure function model_mass_weights(self) result(k)
      class(model_t), intent(in) :: self  !! the model
      real(dp), allocatable :: k(:, :)
      allocate (k(0, 0))
   end function model_mass_weights

   !> The links' mass distribution in words with units, for the 'body' attribute of
   !> output files and the summaries; '' (the default) for uniform rods and
   !> models without links.
   function model_body_description(self) result(text)
      class(model_t), intent(in) :: self  !! the model
      character(len=:), allocatable :: text
      text = ''
   end function model_body_description

   !> The natural time unit of the motion [s] and its name, e.g. 'sqrt(l1/g)': sweeps
   !> count time in it (`--time-unit natural`) and summaries quote it. Default: the
   !> second, named 's', for a model that states no natural unit.
   !> The period of the slowest small oscillation about the state of rest [s]: while a
   !> fit's window is shorter, its model parameters are held at their guess. Default:
   !> none (huge: never held).
   pure real(dp) function model_swing_period(self) result(period)
      class(model_t), intent(in) :: self  !! the model
      period = huge(1.0_dp)
   end function model_swing_period

   pure subroutine model_time_unit(self, seconds, name)
      class(model_t), intent(in) :: self                  !! the model
      real(dp), intent(out) :: seconds                    !! the unit [s]
      character(len=:), allocatable, intent(out) :: name  !! its name
      seconds = 1.0_dp
      name = 's'
   end subroutine model_time_unit

   !> The coordinates q of the model at rest (its stable equilibrium, q̇ = 0).
   !> Default: q = 0, for a model that states none.
   pure subroutine model_rest_state(self, q)
      class(model_t), intent(in) :: self  !! the model
      real(dp), intent(out) :: q(:)       !! coordinates at rest (n_dof)
      q = 0.0_dp
   end subroutine model_rest_state
end module dpend_model
