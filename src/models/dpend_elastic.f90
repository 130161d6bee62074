!> The elastic (spring) pendulum (docs/elastic.md): a point mass m on
!> a massless spring of stiffness k and rest length l0, hung from the pin A at the
!> origin, gravity g along −y (the chapter's conventions: y up, SI units).
!>
!> Coordinates q = (r, φ): r the spring's length [m], φ its angle from the horizontal x
!> axis, counter-clockwise [rad], so that hanging is φ = −π/2. The bob C is at
!> r u, u = (cos φ, sin φ); n = (−sin φ, cos φ) is u turned by +90°. The state is
!> y = (r, φ, ṙ, φ̇) [m, rad, m/s, rad/s].
!>
!> Lagrangian (V = 0 with the bob at A's height and the spring at its rest length):
!>   L = m/2 (ṙ² + r² φ̇²) − k/2 (r − l0)² − m g r sin φ,
!> Lagrange's equations:
!>   r̈ = r φ̇² − (k/m)(r − l0) − g sin φ,
!>   φ̈ = −(2 ṙ φ̇ + g cos φ)/r,
!> energy E = m/2 (ṙ² + r² φ̇²) + k/2 (r − l0)² + m g r sin φ [J].
!> Hamiltonian form: p_r = m ṙ [kg m/s], p_φ = m r² φ̇ [kg m²/s],
!>   H = p_r²/(2m) + p_φ²/(2 m r²) + k/2 (r − l0)² + m g r sin φ,
!>   ṗ_r = p_φ²/(m r³) − k (r − l0) − m g sin φ,  ṗ_φ = −m g r cos φ.
!> The mass matrix diag(m, m r²) depends on r: H is not separable.
!>
!> Hanging equilibrium: r_eq = l0 + m g/k, φ = −π/2; small oscillations about it have
!> the radial frequency √(k/m) (exactly: along φ = −π/2 the motion is linear) and the
!> swing frequency √(g/r_eq); at k/m = 4 g/r_eq (2:1 resonance) energy swaps between
!> the two modes (test/test_elastic.f90 measures all three).
!>
!> Forces (the chapter's "F01 is the ground on link 1 at A"): body 0 is the ground,
!> body 1 the spring with its bob. The spring's tension is T = k (r − l0) [N]
!> (positive when stretched). F01 = −T u is the force of the ground on the spring at
!> A; the spring is massless, so it passes the same force on to the bob:
!> m a_C = F01 − m g ĵ, i.e. F01 = m (a_C + g ĵ) (the chain's F_(0,1)).
!>
!> The collapsed spring: the field divides by r (φ̈, φ̇ = p_φ/(m r²)), and the model is
!> unphysical for r ≤ 0 (the spring's length would be |r|). A state with
!> r < r_min = 1e-6 l0, or with a component beyond `diverged_bound`, is outside the
!> model: there `field` and `canonical_field` return `saturated_field` = 1e60 in every
!> component instead of the dynamics — the chain's mechanism for runaway states
!> (dpend_chain `saturate`), with a value large enough that the step that meets such a
!> state (any step above 1e-29 s) ends beyond `diverged_bound`, where the integrators
!> stop the run with a failure status (stat_nonfinite; an adaptive method may first
!> shrink its step to stat_step_too_small). A saturation at diverged_bound itself
!> would leave states of ~1e27 that integrate on as nonsense. The Jacobians saturate at
!> diverged_bound (the tangent equations multiply three of them in one substep), and
!> `velocities` and `hamiltonian_value` return diverged_bound. Nothing divides by
!> r < r_min or overflows, so the debug profile never traps; `check_state` refuses
!> such an initial state in one line before any work.
!>
!> Methods (dpend_method_registry): all 13 apply. The model is Hamiltonian and
!> conservative, so the methods that need a Hamiltonian (`hamiltonian` in the
!> registry: verlet, yoshida4, comp6, comp8, tao2, tao4) accept it, and no method of
!> the registry needs a separable H: the generalized Störmer–Verlet and its
!> compositions solve the non-separable H implicitly (GNI §VI.3), Tao's methods
!> are written for non-separable H, the Gauss methods run on (q, p), the explicit
!> Runge–Kutta methods (rk4, dopri5, dop853) on (q, q̇). `check_model` refuses none
!> (the `methods_follow_registry` test asks the registry and checks this).
!>
!> Not provided: the fast-path cache (cache_size() = 0: the field is cheap), the
!> energy-shell sections of Poincaré maps (energy_sections() false), damping and a
!> moving support. What the abstract interface lacks for this model (coordinate names
!> and units, drawable points and forces, parameter ranges, a state-domain check) is
!> listed in docs/elastic.md.
module dpend_elastic
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_strings, only: to_str
   use dpend_limits, only: check_parameter, parameter_mass, parameter_length, &
                           parameter_gravity, check_range, min_mass, max_mass, min_length, max_length, max_g, &
                           diverged_bound, max_angle, max_angular_velocity
   use dpend_model, only: model_t, model_check_parameter_rates
   implicit none
   private
   public :: elastic_t, elastic_model, check_state, min_stiffness, max_stiffness
   public :: r_min_ratio, saturated_field

   !> Smallest and largest stiffness k [N/m]: as the masses and lengths (dpend_limits,
   !> [1e-6, 1e6]), so that every product of the model stays far from overflow
   !> (k r² ≤ 1e6 · 1e60 for r below the divergence bound).
   real(dp), parameter :: min_stiffness = 1e-6_dp
   real(dp), parameter :: max_stiffness = 1e6_dp
   !> The spring counts as collapsed onto the pin at r < r_min_ratio · l0: there 1/r is
   !> at most 1e12 /m (l0 ≥ 1e-6 m), and the largest term of the Jacobians,
   !> 3 p_φ²/(m r⁴) with p_φ ≤ 1e30, m ≥ 1e-6, stays below 1e120.
   real(dp), parameter :: r_min_ratio = 1e-6_dp
   !> The fields of a state outside the model (see the module header): diverged_bound²,
   !> so that h · saturated_field > diverged_bound for every step h > 1e-29 s, while
   !> the squares of the adaptive methods' scaled errors stay below 1e300.
   real(dp), parameter :: saturated_field = diverged_bound**2

   !> The elastic pendulum (SI units); build it with `elastic_model`. The defaults are
   !> those of the reference example (`--m 1 --k 40 --l0 1 --g 9.8`).
   type, extends(model_t) :: elastic_t
      real(dp) :: m = 1.0_dp       !! mass of the bob [kg]
      real(dp) :: k = 40.0_dp      !! stiffness of the spring [N/m]
      real(dp) :: l0 = 1.0_dp      !! rest length of the spring [m]
      real(dp) :: g = 9.8_dp       !! gravitational acceleration [m/s²]
      real(dp) :: r_min = 1e-6_dp  !! collapsed spring: r < r_min = r_min_ratio l0 [m]
   contains
      procedure :: n_dof => el_n_dof
      procedure :: name => el_name
      procedure :: field => el_field
      procedure :: jacobian => el_jacobian
      procedure :: energy => el_energy
      procedure :: energy_scale => el_energy_scale
      procedure :: potential_energy => el_potential_energy
      procedure :: kinetic_energy => el_kinetic_energy
      procedure :: hamiltonian => el_true
      procedure :: momenta => el_momenta
      procedure :: velocities => el_velocities
      procedure :: hamiltonian_value => el_hamiltonian_value
      procedure :: canonical_field => el_canonical_field
      procedure :: canonical_jacobian => el_canonical_jacobian
      procedure :: energy_gradient => el_energy_gradient
      procedure :: n_outputs => el_n_outputs
      procedure :: output_info => el_output_info
      procedure :: outputs => el_outputs
      procedure :: n_parameters => el_n_parameters
      procedure :: parameter => el_parameter
      procedure :: coordinate => el_coordinate
      procedure :: coordinates_text => el_coordinates_text
      procedure :: figure => el_figure
      procedure :: time_unit => el_time_unit
      procedure :: swing_period => el_swing_period
      procedure :: rest_state => el_rest_state
      procedure :: energy_text => el_energy_text
      procedure :: check_state => el_check_state
      !> Hanging equilibrium length r_eq = l0 + m g/k [m].
      procedure :: r_eq => el_r_eq
      !> Whether a state is outside the model's domain (see the module header).
      procedure :: collapsed => el_collapsed
      ! the sensitivities of the motion to k and l0 (dpend fit)
      procedure :: check_parameter_rates => el_check_parameter_rates
      procedure :: parameter_rates => el_parameter_rates
   end type elastic_t

   !> The writer's per-sample outputs, in the chain's layout where the meaning is the
   !> same (body 1 = the spring with its bob, one row per body).
   integer, parameter :: n_out = 7
   character(len=13), parameter :: out_names(n_out) = [character(len=13) :: &
      'rC', 'vC', 'aC', 'F_joint', 'tension', 'spring_length', 'rA']
   character(len=5), parameter :: out_units(n_out) = &
      [character(len=5) :: 'm', 'm/s', 'm/s^2', 'N', 'N', 'm', 'm']
   integer, parameter :: out_comp(n_out) = [2, 2, 2, 2, 1, 1, 2]
   integer, parameter :: out_rows(n_out) = [1, 1, 1, 1, 0, 0, 0]
   character(len=96), parameter :: out_text(n_out) = [character(len=96) :: &
      'position of the bob C (x, y)', &
      'velocity of the bob C (x, y)', &
      'acceleration of the bob C (x, y)', &
      'force of the ground on the spring at A (x, y): F01 = -k (r - l0) u, also on the bob', &
      'spring tension k (r - l0), positive when stretched', &
      'spring length r (the distance from the pin A to the bob)', &
      'position of the pin A, the support (x, y)']

contains

   !> The elastic pendulum with mass m [kg], stiffness k [N/m], rest length l0 [m] and
   !> g [m/s²], checked: m in [min_mass, max_mass], k in [min_stiffness,
   !> max_stiffness], l0 in [min_length, max_length], g in [0, max_g] (dpend_limits).
   !> The error names the parameter, its value and the accepted range.
   function elastic_model(m, k, l0, g, error) result(model)
      real(dp), intent(in) :: m                         !! mass of the bob [kg]
      real(dp), intent(in) :: k                         !! stiffness [N/m]
      real(dp), intent(in) :: l0                        !! rest length [m]
      real(dp), intent(in) :: g                         !! gravitational acceleration [m/s²]
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      type(elastic_t) :: model                          !! the model (defaults when refused)
      character(len=*), parameter :: reason = 'keeps every product of the model finite'
      call check_parameter(parameter_mass, 'm', m, error)
      if (allocated(error)) return
      call check_range('k', k, min_stiffness, max_stiffness, 'N/m', error, reason)
      if (allocated(error)) return
      call check_parameter(parameter_length, 'l0', l0, error)
      if (allocated(error)) return
      call check_parameter(parameter_gravity, 'g', g, error)
      if (allocated(error)) return
      model%m = m; model%k = k; model%l0 = l0; model%g = g
      model%r_min = r_min_ratio*l0
   end function elastic_model

   !> Check an initial state (q, q̇) = ((r, φ), (ṙ, φ̇)) in one line naming the field as
   !> the commands do (q1, q2, w1, w2): r in [r_min, max_length] m (above r_min: the
   !> spring has not collapsed onto the pin), |φ| ≤ max_angle rad, |ṙ| ≤
   !> max_angular_velocity m/s, |φ̇| ≤ max_angular_velocity rad/s.
   subroutine check_state(model, q, qd, error)
      type(elastic_t), intent(in) :: model              !! the model
      real(dp), intent(in) :: q(:)                      !! (r [m], φ [rad])
      real(dp), intent(in) :: qd(:)                     !! (ṙ [m/s], φ̇ [rad/s])
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      if (size(q) /= 2 .or. size(qd) /= 2) then
         call fatal_error(error, 'invalid q: '//to_str(size(q))//' coordinates and ' &
                          //to_str(size(qd))//' rates given; the elastic pendulum has 2 ' &
                          //'of each (r, phi)')
         return
      end if
      call check_range('q1', q(1), model%r_min, max_length, 'm', error, &
                       'the spring length r; below 1e-6 l0 it has collapsed onto the pin')
      if (allocated(error)) return
      call check_range('q2', q(2), -max_angle, max_angle, 'rad', error, &
                       'beyond, the rounding of the angle exceeds 1e-10 rad')
      if (allocated(error)) return
      call check_range('w1', qd(1), -max_angular_velocity, max_angular_velocity, 'm/s', &
                       error, 'keeps energies and momenta finite')
      if (allocated(error)) return
      call check_range('w2', qd(2), -max_angular_velocity, max_angular_velocity, 'rad/s', &
                       error, 'keeps energies and momenta finite')
   end subroutine check_state

   !> The swing's small-oscillation period about the hanging equilibrium, 2 π √(r_eq/g)
   !> [s] (the spring's own period is shorter for every k/m > g/r_eq).
   pure real(dp) function el_swing_period(self) result(period)
      class(elastic_t), intent(in) :: self  !! the elastic pendulum
      period = 2.0_dp*pi*sqrt(self%r_eq()/self%g)
   end function el_swing_period

   pure real(dp) function el_r_eq(self)
      class(elastic_t), intent(in) :: self
      el_r_eq = self%l0 + self%m*self%g/self%k
   end function el_r_eq

   !> r < r_min (the spring collapsed onto the pin, or a negative length) or a component
   !> beyond diverged_bound (tested without an ordered comparison on NaN: none reaches
   !> here, the integrators stop at non-finite states).
   pure logical function el_collapsed(self, y)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: y(*)   !! state (r, φ, ·, ·), 4 values
      el_collapsed = .not. (y(1) >= self%r_min) .or. abs(y(1)) > diverged_bound &
                     .or. abs(y(2)) > diverged_bound .or. abs(y(3)) > diverged_bound &
                     .or. abs(y(4)) > diverged_bound
   end function el_collapsed

   pure integer function el_n_dof(self)
      class(elastic_t), intent(in) :: self
      el_n_dof = 2
   end function el_n_dof

   pure function el_name(self) result(name)
      class(elastic_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'elastic pendulum'
   end function el_name

   pure logical function el_true(self)
      class(elastic_t), intent(in) :: self
      el_true = .true.
   end function el_true

   !> (ṙ, φ̇, r̈, φ̈) from Lagrange's equations (module header); saturated when collapsed.
   pure subroutine el_field(self, t, y, f)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: s, c
      if (self%collapsed(y)) then
         f(1:4) = saturated_field
         return
      end if
      s = sin(y(2)); c = cos(y(2))
      f(1) = y(3)
      f(2) = y(4)
      f(3) = y(1)*y(4)**2 - (self%k/self%m)*(y(1) - self%l0) - self%g*s
      f(4) = -(2.0_dp*y(3)*y(4) + self%g*c)/y(1)
   end subroutine el_field

   !> ∂f/∂y of `field`: with N = 2 ṙ φ̇ + g cos φ,
   !>   ∂r̈/∂(r, φ, ṙ, φ̇) = (φ̇² − k/m, −g cos φ, 0, 2 r φ̇),
   !>   ∂φ̈/∂(r, φ, ṙ, φ̇) = (N/r², g sin φ/r, −2 φ̇/r, −2 ṙ/r).
   pure subroutine el_jacobian(self, t, y, jac)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: s, c, r
      if (self%collapsed(y)) then
         jac(1:4, 1:4) = diverged_bound
         return
      end if
      s = sin(y(2)); c = cos(y(2)); r = y(1)
      jac(1:4, 1:4) = 0.0_dp
      jac(1, 3) = 1.0_dp
      jac(2, 4) = 1.0_dp
      jac(3, :) = [y(4)**2 - self%k/self%m, -self%g*c, 0.0_dp, 2.0_dp*r*y(4)]
      jac(4, :) = [(2.0_dp*y(3)*y(4) + self%g*c)/r**2, self%g*s/r, -2.0_dp*y(4)/r, &
                   -2.0_dp*y(3)/r]
   end subroutine el_jacobian

   !> E = m/2 (ṙ² + r² φ̇²) + k/2 (r − l0)² + m g r sin φ [J] (no division: defined for
   !> every finite state).
   pure real(dp) function el_energy(self, t, y)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      el_energy = 0.5_dp*self%m*(y(3)**2 + (y(1)*y(4))**2) &
                  + 0.5_dp*self%k*(y(1) - self%l0)**2 + self%m*self%g*y(1)*sin(y(2))
   end function el_energy

   !> V = k/2 (r − l0)² + m g r sin φ: the spring's and gravity's [J].
   pure real(dp) function el_potential_energy(self, t, y)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      el_potential_energy = 0.5_dp*self%k*(y(1) - self%l0)**2 + self%m*self%g*y(1)*sin(y(2))
   end function el_potential_energy

   !> T = m/2 (ṙ² + r² φ̇²) [J].
   pure real(dp) function el_kinetic_energy(self, t, y)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      el_kinetic_energy = 0.5_dp*self%m*(y(3)**2 + (y(1)*y(4))**2)
   end function el_kinetic_energy

   !> Energy unit for relative energy errors [J]: |E0| when it is at least 1e-3 of
   !> E_ref = m g l0 + k l0²/2 (the bob lifted by l0, plus the spring compressed to
   !> zero length; positive for every accepted parameter, g = 0 included), E_ref
   !> itself when E0 ≈ 0 — the rule of the double pendulum and the chain.
   pure real(dp) function el_energy_scale(self, e0)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: e0
      real(dp) :: e_ref
      e_ref = self%m*self%g*self%l0 + 0.5_dp*self%k*self%l0**2
      el_energy_scale = merge(abs(e0), e_ref, abs(e0) >= 1e-3_dp*e_ref)
   end function el_energy_scale

   !> p = (m ṙ, m r² φ̇) [kg m/s, kg m²/s].
   pure subroutine el_momenta(self, t, y, p)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: p(:)
      p(1) = self%m*y(3)
      p(2) = self%m*y(1)**2*y(4)
   end subroutine el_momenta

   !> q̇ = ∂H/∂p = (p_r/m, p_φ/(m r²)) [m/s, rad/s]; saturated when collapsed.
   pure subroutine el_velocities(self, t, z, qd)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: qd(:)
      if (self%collapsed(z)) then
         qd(1:2) = diverged_bound
         return
      end if
      qd(1) = z(3)/self%m
      qd(2) = z(4)/(self%m*z(1)**2)
   end subroutine el_velocities

   !> H(q, p) [J]; diverged_bound when collapsed.
   pure real(dp) function el_hamiltonian_value(self, t, z) result(h)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      if (self%collapsed(z)) then
         h = diverged_bound
         return
      end if
      h = 0.5_dp*(z(3)**2 + (z(4)/z(1))**2)/self%m + 0.5_dp*self%k*(z(1) - self%l0)**2 &
          + self%m*self%g*z(1)*sin(z(2))
   end function el_hamiltonian_value

   !> (∂H/∂p, −∂H/∂q) = (p_r/m, p_φ/(m r²), p_φ²/(m r³) − k (r − l0) − m g sin φ,
   !> −m g r cos φ); saturated when collapsed.
   pure subroutine el_canonical_field(self, t, z, f)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: w
      if (self%collapsed(z)) then
         f(1:4) = saturated_field
         return
      end if
      w = z(4)/(self%m*z(1)**2)           ! φ̇
      f(1) = z(3)/self%m
      f(2) = w
      f(3) = z(4)*w/z(1) - self%k*(z(1) - self%l0) - self%m*self%g*sin(z(2))
      f(4) = -self%m*self%g*z(1)*cos(z(2))
   end subroutine el_canonical_field

   !> ∂f/∂z of `canonical_field`, z = (r, φ, p_r, p_φ):
   !>   ṙ:   (0, 0, 1/m, 0)
   !>   φ̇:   (−2 p_φ/(m r³), 0, 0, 1/(m r²))
   !>   ṗ_r: (−3 p_φ²/(m r⁴) − k, −m g cos φ, 0, 2 p_φ/(m r³))
   !>   ṗ_φ: (−m g cos φ, m g r sin φ, 0, 0).
   pure subroutine el_canonical_jacobian(self, t, z, jac)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: r, w, mg, s, c
      if (self%collapsed(z)) then
         jac(1:4, 1:4) = diverged_bound
         return
      end if
      r = z(1)
      w = z(4)/(self%m*r**2)              ! φ̇
      mg = self%m*self%g
      s = sin(z(2)); c = cos(z(2))
      jac(1:4, 1:4) = 0.0_dp
      jac(1, 3) = 1.0_dp/self%m
      jac(2, :) = [-2.0_dp*w/r, 0.0_dp, 0.0_dp, 1.0_dp/(self%m*r**2)]
      jac(3, :) = [-3.0_dp*z(4)*w/r**2 - self%k, -mg*c, 0.0_dp, 2.0_dp*w/r]
      jac(4, :) = [-mg*c, mg*r*s, 0.0_dp, 0.0_dp]
   end subroutine el_canonical_jacobian

   !> ∂E/∂y = (m r φ̇² + k (r − l0) + m g sin φ, m g r cos φ, m ṙ, m r² φ̇).
   pure subroutine el_energy_gradient(self, t, y, g)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: g(:)
      g(1) = self%m*y(1)*y(4)**2 + self%k*(y(1) - self%l0) + self%m*self%g*sin(y(2))
      g(2) = self%m*self%g*y(1)*cos(y(2))
      g(3) = self%m*y(3)
      g(4) = self%m*y(1)**2*y(4)
   end subroutine el_energy_gradient

   pure integer function el_n_outputs(self)
      class(elastic_t), intent(in) :: self
      el_n_outputs = n_out
   end function el_n_outputs

   !> rC, vC, aC, F_joint: (samples, 1, 2) as h5py shows them (the chain's layout with
   !> one body); tension, spring_length: (samples).
   subroutine el_output_info(self, i, name, n_comp, units, description, rows)
      class(elastic_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, description
      integer, intent(out) :: n_comp
      integer, intent(out), optional :: rows
      name = trim(out_names(i)); n_comp = out_comp(i)
      if (present(rows)) rows = out_rows(i)
      units = trim(out_units(i)); description = trim(out_text(i))
   end subroutine el_output_info

   !> The outputs of one sample (10 values) from y and f = (q̇, q̈):
   !> r_C = r u, v_C = ṙ u + r φ̇ n, a_C = (r̈ − r φ̇²) u + (r φ̈ + 2 ṙ φ̇) n,
   !> F01 = −k (r − l0) u, T = k (r − l0), r.
   pure subroutine el_outputs(self, t, y, f, values)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:), f(:)
      real(dp), intent(out) :: values(:)
      real(dp) :: u(2), nv(2), tension
      u = [cos(y(2)), sin(y(2))]
      nv = [-u(2), u(1)]
      tension = self%k*(y(1) - self%l0)
      values(1:2) = y(1)*u
      values(3:4) = y(3)*u + y(1)*y(4)*nv
      values(5:6) = (f(3) - y(1)*y(4)**2)*u + (y(1)*f(4) + 2.0_dp*y(3)*y(4))*nv
      values(7:8) = -tension*u
      values(9) = tension
      values(10) = y(1)
      values(11:12) = 0.0_dp
   end subroutine el_outputs

   pure integer function el_n_parameters(self)
      class(elastic_t), intent(in) :: self
      el_n_parameters = 4
   end function el_n_parameters

   !> m [kg], k [N/m], l0 [m], g [m/s²], in that order.
   subroutine el_parameter(self, i, name, value, units)
      class(elastic_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units
      real(dp), intent(out) :: value
      select case (i)
      case (1); name = 'm'; value = self%m; units = 'kg'
      case (2); name = 'k'; value = self%k; units = 'N/m'
      case (3); name = 'l0'; value = self%l0; units = 'm'
      case default; name = 'g'; value = self%g; units = 'm/s^2'
      end select
   end subroutine el_parameter

   !> q1 = r [m] (momentum m ṙ [kg m/s]), q2 = φ [rad] (momentum m r² φ̇ [kg m²/s]).
   subroutine el_coordinate(self, i, name, units, momentum_units)
      class(elastic_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, momentum_units
      if (i == 1) then
         name = 'r'; units = 'm'; momentum_units = 'kg m/s'
      else
         name = 'phi'; units = 'rad'; momentum_units = 'kg m^2/s'
      end if
   end subroutine el_coordinate

   function el_coordinates_text(self, order) result(text)
      class(elastic_t), intent(in) :: self
      integer, intent(in) :: order
      character(len=:), allocatable :: text
      select case (order)
      case (0)
         text = 'r, the spring length, and phi, its angle from the horizontal x axis, ' &
                //'counter-clockwise, unwrapped (hanging: phi = -pi/2)'
      case (1); text = 'rdot [m/s], phidot [rad/s]'
      case default; text = 'rddot [m/s^2], phiddot [rad/s^2]'
      end select
   end function el_coordinates_text

   !> A spring from the pin A to the bob C; the force of the ground on it at A.
   subroutine el_figure(self, anchor, points, style, forces)
      class(elastic_t), intent(in) :: self
      character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      anchor = 'rA'; points = 'rC'; style = 'spring'; forces = 'F_joint'
   end subroutine el_figure

   !> The natural time unit sqrt(l0/g) of the spring's rest length [s].
   pure subroutine el_time_unit(self, seconds, name)
      class(elastic_t), intent(in) :: self                !! the model
      real(dp), intent(out) :: seconds                    !! the unit [s]
      character(len=:), allocatable, intent(out) :: name  !! 'sqrt(l0/g)'
      seconds = sqrt(self%l0/self%g)
      name = 'sqrt(l0/g)'
   end subroutine el_time_unit

   !> Hanging at the stretched length: r = l0 + m g/k, φ = −π/2.
   pure subroutine el_rest_state(self, q)
      class(elastic_t), intent(in) :: self  !! the model
      real(dp), intent(out) :: q(:)         !! (r [m], φ [rad]) at rest
      q = [self%l0 + self%m*self%g/self%k, -0.5_dp*acos(-1.0_dp)]
   end subroutine el_rest_state

   !> The model's check of an initial state (`check_state`): r above the collapse.
   subroutine el_check_state(self, q, qd, error)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: q(:), qd(:)
      type(error_t), allocatable, intent(out) :: error
      call check_state(self, q, qd, error)
   end subroutine el_check_state

   function el_energy_text(self) result(text)
      class(elastic_t), intent(in) :: self
      character(len=:), allocatable :: text
      text = 'total energy T + V (V = 0 with the bob at the pin''s height and the spring at ' &
             //'its rest length)'
   end function el_energy_text

   ! the sensitivities of the motion to k and l0 (dpend fit)

   !> The elastic pendulum gives the sensitivities to k and l0 (with g known, the
   !> motion depends on k/m and l0 only: m is held, k is fitted at the given m).
   subroutine el_check_parameter_rates(self, name, error)
      class(elastic_t), intent(in) :: self
      character(len=*), intent(in) :: name              !! parameter name
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      if (name /= 'k' .and. name /= 'l0') call model_check_parameter_rates(self, name, error)
   end subroutine el_check_parameter_rates

   !> ∂r̈/∂k = −(r − l0)/m, ∂r̈/∂l0 = k/m; φ̈ depends on neither (zeros where the
   !> spring has collapsed: the field is saturated there).
   pure subroutine el_parameter_rates(self, t, y, name, d)
      class(elastic_t), intent(in) :: self
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: y(:)         !! state (r, φ, ṙ, φ̇)
      character(len=*), intent(in) :: name !! 'k' or 'l0'
      real(dp), intent(out) :: d(:, :)     !! (∂r̈/∂θ, ∂φ̈/∂θ), (2, 1)
      d = 0.0_dp
      if (self%collapsed(y)) return
      select case (name)
      case ('k'); d(1, 1) = -(y(1) - self%l0)/self%m
      case ('l0'); d(1, 1) = self%k/self%m
      end select
   end subroutine el_parameter_rates
end module dpend_elastic
