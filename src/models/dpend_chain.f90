!> The chain of N uniform rods on pin joints: the chapter's Newton–Euler
!> method for any number of links, with every joint's reaction.
!>
!> Link i (1 … N) has mass m_i, length L_i, centre of mass C_i at its middle and
!> I_Ci = m_i L_i²/12. Link 1 turns about the pin A at the origin; link i + 1 is pinned
!> to the far end of link i. Angles q_i are absolute, from the horizontal x axis,
!> counter-clockwise, y up (the chapter's convention); hanging at rest: q_i = −π/2.
!> N = 2 is the chapter's double pendulum (`dpend_pendulum`).
!>
!> Notation: u_i = (cos q_i, sin q_i) along link i, n_i = (−sin q_i, cos q_i),
!> h_i = L_i/2, P_0 = A = 0 and P_i = P_(i−1) + L_i u_i the far end of link i (joint
!> i + 1, the tip for i = N), C_i = P_(i−1) + h_i u_i. A point at distance s along link
!> i moves with a = a_P(i−1) + s (q̈_i n_i − q̇_i² u_i). F_(i−1,i) is the force of body
!> i − 1 on body i at joint i (body 0 the ground), F_(N,N+1) = 0; 2-D cross product
!> a × b = a_x b_y − a_y b_x.
!>
!> Newton–Euler, per link (the chapter's free-body diagrams):
!>   m_i a_Ci = F_(i−1,i) − F_(i,i+1) + G_i,                   G_i = (0, −m_i g),
!>   I_Ci q̈_i = (P_(i−1) − C_i) × F_(i−1,i) + (P_i − C_i) × (−F_(i,i+1))
!>            = −h_i u_i × (F_(i−1,i) + F_(i,i+1)).
!> The force equations, summed from the tip, give every reaction:
!>   F_(i−1,i) = F_(i,i+1) + m_i (a_Ci + g ĵ) = Σ_(k≥i) m_k (a_Ck + g ĵ).
!> Substituted into the moment equations (eliminating the reactions), with
!> a_Ck = Σ_(j<k) L_j (q̈_j n_j − q̇_j² u_j) + h_k (q̈_k n_k − q̇_k² u_k),
!> u_i × n_j = cos(q_i − q_j) and u_i × u_j = sin(q_j − q_i), they become
!>   M(q) q̈ = f(q, q̇),  M_ij = K_ij cos(q_i − q_j),
!>   f_i = −h_i u_i × (F⁰_(i−1,i) + F⁰_(i,i+1)),
!> where F⁰ are the reactions of the same recursion with q̈ = 0 (centripetal terms and
!> gravity only), and the coefficient of q̈_j in the moment equation of link i is
!>   K_ii = (m_i/3 + Σ_(k>i) m_k) L_i²,  K_ij = (m_l/2 + Σ_(k>l) m_k) L_i L_j,
!>   l = max(i, j) (i ≠ j),
!> symmetric, so that M is the mass matrix of Lagrange's equations (positive
!> definite: ½ q̇ᵀ M q̇ is the kinetic energy). Written out,
!>   f_i = −Σ_j K_ij sin(q_i − q_j) q̇_j² − G_i cos q_i,  G_i = g L_i (m_i/2 + Σ_(k>i) m_k),
!> with V = Σ_i G_i sin q_i (zero with every link horizontal). The field evaluates f by
!> the recursion (O(N)) and solves M q̈ = f by a Cholesky factorization (`cholesky`).
!>
!> Cholesky: a small pure routine of this module rather than LAPACK's dpotrf/dpotrs:
!> the model interface's procedures are `pure` (LAPACK routines are external, not
!> pure, and report errors through xerbla), and for N ≤ max_dof = 32 the inlined loops
!> cost less than the calls (no blocking pays at this size). Locals are fixed-size
!> arrays of max_dof (gfortran allocates automatic arrays on the heap), so the hot path
!> does not allocate.
!>
!> Hamiltonian form: p = M(q) q̇, H = ½ pᵀ M⁻¹ p + V, ∂H/∂p = q̇ and
!>   ∂H/∂q_i = −τ_i + G_i cos q_i,  τ_i = ∂T/∂q_i|_q̇ = −q̇_i Σ_j K_ij sin(q_i − q_j) q̇_j.
!>
!> Joint damping and a moving support, both off by default (the
!> conservative chain above, its arithmetic unchanged):
!> - joint i exerts the viscous torque −c_i (q̇_i − q̇_(i−1)) on body i and its
!>   opposite on body i − 1 (q̇_0 = 0, joint 1 the pin A). The moment equation of link
!>   i is Lagrange's equation of q_i (the absolute angles), so the torques enter f as
!>   the generalized forces Q = −C q̇, C_ii = c_i + c_(i+1), C_(i,i+1) = −c_(i+1);
!> - the pin A moves: x_A = a_x cos(ω t + φ_x), y_A = a_y cos(ω t + φ_y). Its
!>   acceleration a_A starts the recursion of accelerations (a⁰ of the near end of link
!>   1), so that f gains −μ_i u_i × a_A, μ_i = L_i (m_i/2 + Σ_(k>i) m_k) (gravity g ĵ
!>   becomes g ĵ + a_A); kinematics and reactions include the motion of A.
!> - Coulomb joint friction, smoothed: joint i exerts −c_f,i tanh(ω_i/v_s) on body i and
!>   its opposite on body i − 1 (ω_i = q̇_i − q̇_(i−1)), a torque of magnitude c_f,i
!>   once |ω_i| ≫ v_s and a steep viscous one of slope c_f,i/v_s near rest (a link held
!>   by a torque τ < c_f,i creeps at v_s atanh(τ/c_f,i) < v_s (τ/c_f,i ≤ 0.76) rather
!>   than sticking); its power c_f,i tanh(ω_i/v_s) ω_i ≥ 0 joins P_friction;
!> - applied joint torques τ_i(t) (dpend_joint_torque): joint i's motor exerts τ_i on
!>   body i and −τ_i on body i − 1, so that f gains the generalized forces
!>   Q_i = τ_i − τ_(i+1) (τ_(N+1) = 0); they are couples, so the reactions of the
!>   recursion (given q̈) are unchanged.
!> - a motor at joint i (rotor inertia I_r,i, gear ratio g_r,i; stator on body i − 1,
!>   the gear's output on body i): the rotor spins at g_r,i ω_i and adds
!>   ½ g_r,i² I_r,i ω_i² to T (the rotor's own rotation with body i − 1 and its mass
!>   neglected: the usual reflected-inertia model), so M gains the constant
!>   Dᵀ diag(g_r² I_r) D, D q̇ = ω (`fill_mass`); a constant part of M changes neither
!>   f, ∂M/∂q nor the Hamiltonian form's ∂H/∂q, and its couples
!>   −g_r,i² I_r,i ω̇_i on body i (the opposite on body i − 1) leave the reactions
!>   unchanged. The motion stays conservative; the chain lanes (which assemble
!>   M = K cos) do not serve it (`mass_weights` of size 0).
!> With any of these, the model is neither Hamiltonian nor conservative (the support
!> and the torques also make it non-autonomous). The energy is then the inertial one,
!>   E = T + V with T = Σ ½ m_k |v_Ck|² + ½ I_Ck q̇_k², V = Σ m_k g y_Ck,
!>     = ½ q̇ᵀ M q̇ + Σ G_i sin q_i + v_A · Σ μ_i q̇_i n_i + ½ m |v_A|² + m g y_A
!> (m the total mass), and its balance is dE/dt = P_support + P_torque − P_friction with
!>   P_friction = Σ c_i ω_i² + c_f,i tanh(ω_i/v_s) ω_i ≥ 0,  P_torque = Σ τ_i ω_i,
!>   P_support = F_(0,1) · v_A,  F_(0,1) = m (a_A + g ĵ) + Σ μ_i (q̈_i n_i − q̇_i² u_i)
!> (`powers`; `dpend_work` integrates both along the solution).
!>
!> Links of any mass distribution: link i may carry its centre of mass at
!> d_i from joint i along the link and have the inertia I_i about it (`chain_model`'s
!> com and inertia; a point mass at the end of a massless rod: d_i = L_i, I_i = 0).
!> The recursion places C_i at d_i, the moment equation about C_i becomes
!>   I_i q̈_i = −d_i u_i × F_(i−1,i) − (L_i − d_i) u_i × F_(i,i+1)
!> (F_(i−1,i) at distance d_i behind C_i, F_(i,i+1) at L_i − d_i ahead), and
!>   K_ii = I_i + m_i d_i² + L_i² Σ_(k>i) m_k,
!>   K_ij = L_i (m_j d_j + L_j Σ_(k>j) m_k) (i < j),
!>   G_i = g (m_i d_i + L_i Σ_(k>i) m_k),  μ_i = m_i d_i + L_i Σ_(k>i) m_k,
!> which are the rod's for d_i = L_i/2, I_i = m_i L_i²/12. Without com and inertia the
!> chain is of uniform rods and keeps the rod's arithmetic (results bit for bit).
module dpend_chain
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_limits, only: diverged_bound
   use dpend_model, only: model_t, max_dof
   use dpend_joint_torque, only: joint_torque_t
   implicit none
   private
   public :: chain_t, chain_model

   !> The chain of N uniform rods (SI units); build it with `chain_model`.
   type, extends(model_t) :: chain_t
      integer :: n = 0                       !! number of links N
      real(dp), allocatable :: m(:)          !! masses m_i [kg] (N)
      real(dp), allocatable :: l(:)          !! lengths L_i [m] (N)
      real(dp) :: g = 9.8_dp                 !! gravitational acceleration [m/s²]
      real(dp), allocatable :: k(:, :)       !! K_ij of M_ij = K_ij cos(q_i − q_j) [kg m²]
      real(dp), allocatable :: gl(:)         !! G_i of V = Σ G_i sin q_i [J]
      real(dp), allocatable :: mu(:)         !! μ_i = L_i (m_i/2 + Σ_(k>i) m_k) [kg m]
      real(dp), allocatable :: c(:)          !! joint damping c_i [N m s] (N)
      !> uniform rods (d_i = L_i/2, I_i = m_i L_i²/12, the rod's arithmetic) or not
      logical :: rod = .true.
      real(dp), allocatable :: d(:)          !! joint i to the centre of mass C_i [m] (N)
      real(dp), allocatable :: ic(:)         !! inertia of link i about C_i [kg m²] (N)
      logical :: damped = .false.            !! some c_i > 0
      logical :: driven = .false.            !! the support moves
      real(dp) :: sup_a(2) = 0.0_dp          !! support amplitudes (a_x, a_y) [m]
      real(dp) :: sup_w = 0.0_dp             !! support angular frequency ω [rad/s]
      real(dp) :: sup_phi(2) = 0.0_dp        !! support phases (φ_x, φ_y) [rad]
      logical :: coulomb = .false.           !! some joint has Coulomb friction c_f,i > 0
      real(dp), allocatable :: cf(:)         !! Coulomb friction torques c_f,i [N m] (N)
      real(dp) :: vs = 1e-3_dp               !! its smoothing speed v_s [rad/s]
      logical :: motors = .false.            !! some joint has a rotor: g_r,i² I_r,i > 0
      real(dp), allocatable :: ir(:)         !! rotor inertias I_r,i [kg m²] (N)
      real(dp), allocatable :: gr(:)         !! gear ratios g_r,i (N)
      !> reflected rotor inertias g_r,i² I_r,i [kg m²] (N): the rotor of joint i spins at
      !> g_r,i ω_i (ω_i = q̇_i − q̇_(i−1)), kinetic energy ½ g_r,i² I_r,i ω_i²
      real(dp), allocatable :: im(:)
      logical :: torqued = .false.           !! joint torques are applied
      type(joint_torque_t) :: torque         !! the applied joint torques τ_i(t)
   contains
      procedure :: n_dof => chain_n_dof
      procedure :: name => chain_name
      procedure :: field => chain_field
      procedure :: jacobian => chain_jacobian
      procedure :: energy => chain_energy
      procedure :: energy_scale => chain_energy_scale
      procedure :: potential_energy => chain_potential_energy
      procedure :: hamiltonian => chain_hamiltonian
      procedure :: conservative => chain_hamiltonian
      procedure :: autonomous => chain_autonomous
      procedure :: momenta => chain_momenta
      procedure :: velocities => chain_velocities
      procedure :: hamiltonian_value => chain_hamiltonian_value
      procedure :: canonical_field => chain_canonical_field
      procedure :: canonical_jacobian => chain_canonical_jacobian
      procedure :: energy_gradient => chain_energy_gradient
      procedure :: energy_sections => chain_energy_sections
      procedure :: section_state => chain_section_state
      procedure :: section_p_max => chain_section_p_max
      procedure :: n_outputs => chain_n_outputs
      procedure :: output_info => chain_output_info
      procedure :: outputs => chain_outputs
      procedure :: n_parameters => chain_n_parameters
      procedure :: parameter => chain_parameter
      procedure :: coordinate => chain_coordinate
      procedure :: coordinates_text => chain_coordinates_text
      procedure :: figure => chain_figure
      procedure :: cache_size => chain_cache_size
      procedure :: fill_cache => chain_fill_cache
      procedure :: fill_cache_field => chain_fill_cache_field
      procedure :: field_near => chain_field_near
      procedure :: canonical_field_near => chain_canonical_field_near
      !> Mass matrix M(q) (n, n) [kg m²].
      procedure :: mass_matrix => chain_mass_matrix
      !> Accelerations q̈ by Newton–Euler [rad/s²].
      procedure :: accelerations => chain_accelerations
      !> Every joint reaction F_(i−1,i) [N] from q, q̇, q̈ (recursion from the tip).
      procedure :: reactions => chain_reactions
      !> Positions, velocities, accelerations of the centres and link ends.
      procedure :: kinematics => chain_kinematics
      !> Potential energy V(q) [J].
      procedure :: potential => chain_potential
      !> Position, velocity and acceleration of the pin A at time t.
      procedure :: support => chain_support
      !> Power dissipated by the joints and delivered by the support [W].
      procedure :: powers => chain_powers
      ! the sensitivities of the motion to the damping (dpend fit --fit-damping)
      procedure :: check_parameter_rates => chain_check_parameter_rates
      procedure :: parameter_rates => chain_parameter_rates
      ! sweep (one construction site): the G_i of its potential
      procedure :: potential_weights => chain_potential_weights
      procedure :: mass_weights => chain_mass_weights
      ! the links' mass distribution
      procedure :: body_description => chain_body_description
      procedure :: time_unit => chain_time_unit
      procedure :: rest_state => chain_rest_state
   end type chain_t

   ! The cold procedures, implemented by the submodules dpend_chain_build (the
   ! constructor and its checks) and dpend_chain_outputs (outputs, force recovery,
   ! sections, descriptions, parameter listing), where the type-bound ones are
   ! described. No procedure below `contains` (the hot path) calls them.
   interface
      !> The chain with masses m [kg], lengths l [m] (one per link) and g [m/s²],
      !> checked: 1 ≤ N ≤ max_dof links, m and l of the same size, each within
      !> dpend_limits' range table (`check_parameter`: masses, lengths and g each in
      !> [1e-6, 1e6]).
      !> The error names the field (m3, l2, g, links), its value and the accepted range.
      !> Optional: joint damping c [N m s] (one per link, each in
      !> [0, max_damping]) and the support motion: amplitudes (a_x, a_y) [m] (each in
      !> [−max_support_amplitude, max_support_amplitude]), angular frequency ω [rad/s]
      !> (in [0, max_support_frequency]), phases (φ_x, φ_y) [rad] (|φ| ≤ max_angle).
      !> All zero (the default) is the conservative chain.
      !> Optional: the mass distribution, com d_i [m] and inertia I_i [kg m²]
      !> (one per link, both or neither; `check_bodies` checks them); absent: uniform rods.
      module function chain_model(m, l, g, error, damping, amplitude, frequency, phase, com, &
                                  inertia, torque, coulomb, coulomb_speed, rotor_inertia, &
                                  gear_ratio) result(model)
         real(dp), intent(in) :: m(:)                      !! masses [kg]
         real(dp), intent(in) :: l(:)                      !! lengths [m]
         real(dp), intent(in) :: g                         !! gravitational acceleration [m/s²]
         type(error_t), allocatable, intent(out) :: error  !! set when refused
         real(dp), intent(in), optional :: damping(:)      !! c_i [N m s]
         real(dp), intent(in), optional :: amplitude(2)    !! (a_x, a_y) [m]
         real(dp), intent(in), optional :: frequency       !! ω [rad/s]
         real(dp), intent(in), optional :: phase(2)        !! (φ_x, φ_y) [rad]
         real(dp), intent(in), optional :: com(:)          !! d_i [m] (N)
         real(dp), intent(in), optional :: inertia(:)      !! I_i [kg m²] (N)
         type(joint_torque_t), intent(in), optional :: torque  !! τ_i(t) (N joints)
         real(dp), intent(in), optional :: coulomb(:)      !! c_f,i [N m] (N)
         real(dp), intent(in), optional :: coulomb_speed   !! v_s [rad/s]
         real(dp), intent(in), optional :: rotor_inertia(:) !! I_r,i [kg m²] (N)
         real(dp), intent(in), optional :: gear_ratio(:)   !! g_r,i (N)
         type(chain_t) :: model                            !! the chain (n = 0 when refused)
      end function chain_model

      ! dpend_chain_outputs: the outputs of a sample, the force recovery, the energy scale
      pure module subroutine chain_kinematics(self, q, qd, qdd, rc, vc, ac, rj, vj, aj, t)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: q(:), qd(:), qdd(:)         !! q [rad], q̇ [rad/s], q̈ [rad/s²]
         real(dp), intent(out) :: rc(:, :), vc(:, :), ac(:, :) !! of C_i (2, n)
         real(dp), intent(out) :: rj(:, :), vj(:, :), aj(:, :) !! of P_i (2, n)
         real(dp), intent(in), optional :: t                 !! time [s]
      end subroutine chain_kinematics
      pure module subroutine chain_reactions(self, q, qd, qdd, f, t)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: q(:), qd(:), qdd(:)   !! q [rad], q̇ [rad/s], q̈ [rad/s²]
         real(dp), intent(out) :: f(:, :)              !! reactions (2, n) [N]
         real(dp), intent(in), optional :: t           !! time [s] (default 0)
      end subroutine chain_reactions
      pure module subroutine chain_powers(self, t, y, qdd, p_friction, p_support, p_torque)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: t            !! time [s]
         real(dp), intent(in) :: y(*)         !! state (q, q̇)
         real(dp), intent(in) :: qdd(*)       !! q̈ [rad/s²]
         real(dp), intent(out) :: p_friction  !! power dissipated in the joints [W]
         real(dp), intent(out) :: p_support   !! power delivered by the support [W]
         !> power delivered by the applied joint torques [W]
         real(dp), intent(out), optional :: p_torque
      end subroutine chain_powers
      pure real(dp) module function chain_potential_energy(self, t, y)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: t, y(:)
      end function chain_potential_energy
      pure real(dp) module function chain_energy_scale(self, e0)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: e0
      end function chain_energy_scale
      pure integer module function chain_n_outputs(self)
         class(chain_t), intent(in) :: self
      end function chain_n_outputs
      module subroutine chain_output_info(self, i, name, n_comp, units, description, rows)
         class(chain_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units, description
         integer, intent(out) :: n_comp
         integer, intent(out), optional :: rows
      end subroutine chain_output_info
      pure module subroutine chain_outputs(self, t, y, f, values)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: t, y(:), f(:)
         real(dp), intent(out) :: values(:)
      end subroutine chain_outputs

      ! dpend_chain_outputs: the Poincaré sections (two links: the double pendulum's)
      pure logical module function chain_energy_sections(self)
         class(chain_t), intent(in) :: self
      end function chain_energy_sections
      pure module subroutine chain_section_state(self, e, link, angle, direction, q_o, p_o, q, qd, &
                                                 found)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: e, angle, q_o, p_o
         integer, intent(in) :: link, direction
         real(dp), intent(out) :: q(:), qd(:)
         logical, intent(out) :: found
      end subroutine chain_section_state
      pure real(dp) module function chain_section_p_max(self, e, link, angle) result(p)
         class(chain_t), intent(in) :: self
         real(dp), intent(in) :: e, angle
         integer, intent(in) :: link
      end function chain_section_p_max

      ! dpend_chain_outputs: descriptions, the parameter listing
      pure module function chain_name(self) result(name)
         class(chain_t), intent(in) :: self
         character(len=:), allocatable :: name
      end function chain_name
      pure integer module function chain_n_parameters(self)
         class(chain_t), intent(in) :: self
      end function chain_n_parameters
      module subroutine chain_parameter(self, i, name, value, units)
         class(chain_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units
         real(dp), intent(out) :: value
      end subroutine chain_parameter
      module subroutine chain_coordinate(self, i, name, units, momentum_units)
         class(chain_t), intent(in) :: self
         integer, intent(in) :: i
         character(len=:), allocatable, intent(out) :: name, units, momentum_units
      end subroutine chain_coordinate
      module function chain_coordinates_text(self, order) result(text)
         class(chain_t), intent(in) :: self
         integer, intent(in) :: order
         character(len=:), allocatable :: text
      end function chain_coordinates_text
      module subroutine chain_figure(self, anchor, points, style, forces)
         class(chain_t), intent(in) :: self
         character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      end subroutine chain_figure
      module subroutine chain_check_parameter_rates(self, name, error)
         class(chain_t), intent(in) :: self
         character(len=*), intent(in) :: name              !! parameter name
         type(error_t), allocatable, intent(out) :: error  !! set when refused
      end subroutine chain_check_parameter_rates
      pure module subroutine chain_time_unit(self, seconds, name)
         class(chain_t), intent(in) :: self                  !! the model
         real(dp), intent(out) :: seconds                    !! the unit [s]
         character(len=:), allocatable, intent(out) :: name  !! 'sqrt(l1/g)'
      end subroutine chain_time_unit
      pure module subroutine chain_rest_state(self, q)
         class(chain_t), intent(in) :: self  !! the model
         real(dp), intent(out) :: q(:)       !! angles at rest [rad]
      end subroutine chain_rest_state
      module function chain_body_description(self) result(text)
         class(chain_t), intent(in) :: self  !! the chain
         character(len=:), allocatable :: text
      end function chain_body_description
      pure module function chain_potential_weights(self) result(gl)
         class(chain_t), intent(in) :: self  !! the chain
         real(dp), allocatable :: gl(:)
      end function chain_potential_weights
      pure module function chain_mass_weights(self) result(k)
         class(chain_t), intent(in) :: self  !! the chain
         real(dp), allocatable :: k(:, :)
      end function chain_mass_weights
   end interface

contains

   ! ---------------------------------------------------------------- linear algebra

   !> In-place Cholesky factorization A = L Lᵀ of the leading n×n block of a
   !> (lower triangle used and overwritten by L). M is positive definite for every
   !> accepted parameter; a non-positive pivot (not reachable) gives a NaN-free
   !> result by clamping at tiny, so that the debug profile never traps.
   pure subroutine cholesky(n, a)
      integer, intent(in) :: n                       !! order
      real(dp), intent(inout) :: a(max_dof, max_dof) !! matrix, then L (lower)
      integer :: i, j, k
      real(dp) :: s
      do j = 1, n
         s = a(j, j)
         do k = 1, j - 1
            s = s - a(j, k)**2
         end do
         a(j, j) = sqrt(max(s, tiny(1.0_dp)))
         do i = j + 1, n
            s = a(i, j)
            do k = 1, j - 1
               s = s - a(i, k)*a(j, k)
            end do
            a(i, j) = s/a(j, j)
         end do
      end do
   end subroutine cholesky

   !> Solve L Lᵀ x = b in place for the factor of `cholesky`.
   pure subroutine cholesky_solve(n, a, b)
      integer, intent(in) :: n                       !! order
      real(dp), intent(in) :: a(max_dof, max_dof)    !! L (lower)
      real(dp), intent(inout) :: b(max_dof)          !! right-hand side, then x
      integer :: i, k
      real(dp) :: s
      do i = 1, n
         s = b(i)
         do k = 1, i - 1
            s = s - a(i, k)*b(k)
         end do
         b(i) = s/a(i, i)
      end do
      do i = n, 1, -1
         s = b(i)
         do k = i + 1, n
            s = s - a(k, i)*b(k)
         end do
         b(i) = s/a(i, i)
      end do
   end subroutine cholesky_solve

   !> cos and sin of the angles.
   pure subroutine trig(n, q, c, s)
      integer, intent(in) :: n            !! links
      real(dp), intent(in) :: q(*)        !! angles [rad]
      real(dp), intent(out) :: c(max_dof) !! cos q_i
      real(dp), intent(out) :: s(max_dof) !! sin q_i
      integer :: i
      do i = 1, n
         c(i) = cos(q(i))
         s(i) = sin(q(i))
      end do
   end subroutine trig

   !> M(q) = K_ij cos(q_i − q_j) into the leading block of a, from cos and sin; with
   !> motors plus the constant Dᵀ diag(g_r² I_r) D of the rotors (D q̇ = ω, the joints'
   !> relative rates): g_r,i² I_r,i + g_r,(i+1)² I_r,(i+1) on the diagonal,
   !> −g_r,(i+1)² I_r,(i+1) beside it.
   pure subroutine fill_mass(self, c, s, a)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), intent(out) :: a(max_dof, max_dof)    !! M in a(1:n, 1:n)
      integer :: i, j
      do j = 1, self%n
         a(j, j) = self%k(j, j)
         do i = j + 1, self%n
            a(i, j) = self%k(i, j)*(c(i)*c(j) + s(i)*s(j))
            a(j, i) = a(i, j)
         end do
      end do
      if (.not. self%motors) return
      do i = 1, self%n
         a(i, i) = a(i, i) + self%im(i)
         if (i > 1) then
            a(i - 1, i - 1) = a(i - 1, i - 1) + self%im(i)
            a(i, i - 1) = a(i, i - 1) - self%im(i)
            a(i - 1, i) = a(i, i - 1)
         end if
      end do
   end subroutine fill_mass

   !> f(q, q̇) of M q̈ = f by the Newton–Euler recursion with q̈ = 0: centripetal
   !> accelerations a⁰ from the pin outwards, the reactions F⁰ from the tip inwards,
   !> f_i = −h_i u_i × (F⁰_(i−1,i) + F⁰_(i,i+1)).
   pure subroutine rhs_newton_euler(self, c, s, qd, a0, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), intent(in) :: qd(*)                   !! q̇ [rad/s]
      real(dp), intent(in) :: a0(2)                   !! acceleration of A [m/s²]
      real(dp), intent(out) :: f(max_dof)             !! f [N m]
      real(dp) :: acx(max_dof), acy(max_dof), px, py, w2, h, fx, fy, gx, gy
      integer :: i, n
      n = self%n
      px = a0(1); py = a0(2)              ! a⁰ of the near end of link i
      do i = 1, n
         w2 = qd(i)**2
         h = self%d(i)          ! L_i/2 for rods (chain_model: 0.5 L_i, the same bits)
         acx(i) = px - h*w2*c(i)
         acy(i) = py - h*w2*s(i)
         px = px - self%l(i)*w2*c(i)
         py = py - self%l(i)*w2*s(i)
      end do
      fx = 0.0_dp; fy = 0.0_dp            ! F⁰_(i,i+1), zero beyond the tip
      if (.not. self%rod) then   ! −d_i u_i × F⁰_(i−1,i) − (L_i − d_i) u_i × F⁰_(i,i+1)
         do i = n, 1, -1
            gx = fx + self%m(i)*acx(i)
            gy = fy + self%m(i)*(acy(i) + self%g)
            f(i) = -(self%d(i)*(c(i)*gy - s(i)*gx) &
                     + (self%l(i) - self%d(i))*(c(i)*fy - s(i)*fx))
            fx = gx; fy = gy
         end do
         return
      end if
      do i = n, 1, -1
         gx = fx + self%m(i)*acx(i)                 ! F⁰_(i−1,i)
         gy = fy + self%m(i)*(acy(i) + self%g)      ! and gravity
         f(i) = -0.5_dp*self%l(i)*(c(i)*(gy + fy) - s(i)*(gx + fx))
         fx = gx; fy = gy
      end do
   end subroutine rhs_newton_euler

   !> q̈ (leading n of qdd) and the Cholesky factor of M at (q, q̇).
   pure subroutine solve_qdd(self, t, q, qd, qdd, a, c, s)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t                      !! time [s]
      real(dp), intent(in) :: q(*), qd(*)            !! angles [rad], rates [rad/s]
      real(dp), intent(out) :: qdd(max_dof)          !! q̈ [rad/s²]
      real(dp), intent(out) :: a(max_dof, max_dof)   !! Cholesky factor of M
      real(dp), intent(out) :: c(max_dof), s(max_dof) !! cos q, sin q
      call trig(self%n, q, c, s)
      call solve_qdd_trig(self, t, c, s, qd, qdd, a)
   end subroutine solve_qdd

   !> q̈ (leading n of qdd) and the Cholesky factor of M from cos q, sin q.
   pure subroutine solve_qdd_trig(self, t, c, s, qd, qdd, a)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t                       !! time [s]
      real(dp), intent(in) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), intent(in) :: qd(*)                   !! rates [rad/s]
      real(dp), intent(out) :: qdd(max_dof)           !! q̈ [rad/s²]
      real(dp), intent(out) :: a(max_dof, max_dof)    !! Cholesky factor of M
      real(dp) :: ra(2), va(2), aa(2), tau(max_dof), w
      integer :: i
      aa = 0.0_dp
      if (self%driven) call self%support(t, ra, va, aa)
      call fill_mass(self, c, s, a)
      call cholesky(self%n, a)
      call rhs_newton_euler(self, c, s, qd, aa, qdd)
      if (self%damped) then   ! Q = −C q̇
         do i = 1, self%n
            qdd(i) = qdd(i) - self%c(i)*(qd(i) - merge(qd(max(i - 1, 1)), 0.0_dp, i > 1))
            if (i < self%n) qdd(i) = qdd(i) + self%c(i + 1)*(qd(i + 1) - qd(i))
         end do
      end if
      if (self%coulomb) then   ! Q_i = −c_f,i tanh(ω_i/v_s) + c_f,(i+1) tanh(ω_(i+1)/v_s)
         do i = 1, self%n
            w = self%cf(i)*tanh((qd(i) - merge(qd(max(i - 1, 1)), 0.0_dp, i > 1))/self%vs)
            qdd(i) = qdd(i) - w
            if (i > 1) qdd(i - 1) = qdd(i - 1) + w
         end do
      end if
      if (self%torqued) then   ! Q_i = τ_i − τ_(i+1)
         call self%torque%values(t, tau(1:self%n))
         do i = 1, self%n
            qdd(i) = qdd(i) + tau(i)
            if (i < self%n) qdd(i) = qdd(i) - tau(i + 1)
         end do
      end if
      call cholesky_solve(self%n, a, qdd)
   end subroutine solve_qdd_trig

   !> x_A = a_x cos(ω t + φ_x), y_A = a_y cos(ω t + φ_y) and its derivatives.
   pure subroutine chain_support(self, t, r, v, a)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t              !! time [s]
      real(dp), intent(out) :: r(2)          !! position of A [m]
      real(dp), intent(out) :: v(2)          !! velocity of A [m/s]
      real(dp), intent(out) :: a(2)          !! acceleration of A [m/s²]
      real(dp) :: ph(2)
      ph = self%sup_w*t + self%sup_phi
      r = self%sup_a*cos(ph)
      v = -self%sup_w*self%sup_a*sin(ph)
      a = -self%sup_w**2*r
   end subroutine chain_support

   !> q̇ = M⁻¹ p (leading n of qd) and the Cholesky factor of M.
   pure subroutine solve_qd(self, q, p, qd, a, c, s)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(*), p(*)             !! angles [rad], momenta [kg m²/s]
      real(dp), intent(out) :: qd(max_dof)           !! q̇ [rad/s]
      real(dp), intent(out) :: a(max_dof, max_dof)   !! Cholesky factor of M
      real(dp), intent(out) :: c(max_dof), s(max_dof) !! cos q, sin q
      call trig(self%n, q, c, s)
      call solve_qd_trig(self, c, s, p, qd, a)
   end subroutine solve_qd

   !> q̇ = M⁻¹ p (leading n of qd) and the Cholesky factor of M from cos q, sin q.
   pure subroutine solve_qd_trig(self, c, s, p, qd, a)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), intent(in) :: p(*)                    !! momenta [kg m²/s]
      real(dp), intent(out) :: qd(max_dof)            !! q̇ [rad/s]
      real(dp), intent(out) :: a(max_dof, max_dof)    !! Cholesky factor of M
      integer :: n
      n = self%n
      call fill_mass(self, c, s, a)
      call cholesky(n, a)
      qd(1:n) = p(1:n)
      call cholesky_solve(n, a, qd)
   end subroutine solve_qd_trig

   !> cos and sin of q = q0 + d from those of q0 (c0, s0), for small d: the
   !> angle-addition formulas with sin d and cos d − 1 from their Taylor series (as
   !> `sin_cos_near` of dpend_pendulum: remainder below 1e-17 for |d| ≤ 0.25 rad;
   !> beyond, cos q and sin q directly). Unlike cos(q0 + d), which sees the rounding
   !> of q0 + d (ulp(q)/2 absolute), this is accurate relative to d: the forces of
   !> a state near equilibrium come out smooth in d, so that the fixed-point
   !> iterations of the implicit methods converge to their roundoff test.
   pure subroutine trig_near(n, c0, s0, q, d, c, s)
      integer, intent(in) :: n                         !! links
      real(dp), intent(in) :: c0(*), s0(*)             !! cos q0, sin q0
      real(dp), intent(in) :: q(*), d(*)               !! q [rad], d = q − q0 [rad]
      real(dp), intent(out) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), parameter :: d_max = 0.25_dp
      real(dp) :: d2, sd, cm1
      integer :: i
      do i = 1, n
         if (abs(d(i)) > d_max) then
            c(i) = cos(q(i))
            s(i) = sin(q(i))
         else
            d2 = d(i)*d(i)
            sd = d(i)*(1.0_dp + d2*(-1.0_dp/6.0_dp + d2*(1.0_dp/120.0_dp &
                 + d2*(-1.0_dp/5040.0_dp + d2*(1.0_dp/362880.0_dp &
                 + d2*(-1.0_dp/39916800.0_dp))))))
            cm1 = d2*(-0.5_dp + d2*(1.0_dp/24.0_dp + d2*(-1.0_dp/720.0_dp &
                  + d2*(1.0_dp/40320.0_dp + d2*(-1.0_dp/3628800.0_dp &
                  + d2*(1.0_dp/479001600.0_dp))))))
            s(i) = s0(i) + (s0(i)*cm1 + c0(i)*sd)
            c(i) = c0(i) + (c0(i)*cm1 - s0(i)*sd)
         end if
      end do
   end subroutine trig_near

   ! ---------------------------------------------------------------- model bindings

   pure integer function chain_n_dof(self)
      class(chain_t), intent(in) :: self
      chain_n_dof = self%n
   end function chain_n_dof

   !> Hamiltonian and conservative without damping, friction, support motion and torques
   !> (motors keep it so: their inertia is kinetic energy).
   pure logical function chain_hamiltonian(self)
      class(chain_t), intent(in) :: self
      chain_hamiltonian = .not. (self%damped .or. self%driven .or. self%torqued .or. &
                                 self%coulomb)
   end function chain_hamiltonian

   !> Autonomous unless the support moves or torques are applied.
   pure logical function chain_autonomous(self)
      class(chain_t), intent(in) :: self
      chain_autonomous = .not. (self%driven .or. self%torqued)
   end function chain_autonomous

   !> (q̇, q̈) with q̈ from Newton–Euler and a Cholesky solve.
   pure subroutine chain_field(self, t, y, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: c(max_dof), s(max_dof)
      integer :: n
      logical :: runaway
      n = self%n
      call saturate(2*n, y, f, runaway)
      if (runaway) return
      call trig(n, y, c, s)
      call field_trig(self, t, c, s, y, f)
   end subroutine chain_field

   !> f = (q̇, q̈) at y = (q, q̇) from the cos and sin of q: the tail of `field`,
   !> `fill_cache_field` and `field_near`.
   pure subroutine field_trig(self, t, c, s, y, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t                       !! time [s]
      real(dp), intent(in) :: c(max_dof), s(max_dof)  !! cos q, sin q
      real(dp), intent(in) :: y(*)                    !! state (q, q̇)
      real(dp), intent(out) :: f(*)                   !! (q̇, q̈)
      real(dp) :: qdd(max_dof), a(max_dof, max_dof)
      integer :: n
      n = self%n
      call solve_qdd_trig(self, t, c, s, y(n + 1:2*n), qdd, a)
      f(1:n) = y(n + 1:2*n)
      f(n + 1:2*n) = qdd(1:n)
   end subroutine field_trig

   !> The accelerations q̈ [rad/s²] (n) at (q, q̇) and time t (default 0).
   pure function chain_accelerations(self, q, qd, t) result(qdd)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(:), qd(:)   !! angles [rad], rates [rad/s]
      real(dp), intent(in), optional :: t   !! time [s]
      real(dp) :: qdd(self%n)
      real(dp) :: w(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof), tt
      tt = 0.0_dp
      if (present(t)) tt = t
      call solve_qdd(self, tt, q, qd, w, a, c, s)
      qdd = w(1:self%n)
   end function chain_accelerations

   !> M(q) [kg m²].
   pure function chain_mass_matrix(self, q) result(mm)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(:)          !! angles [rad]
      real(dp) :: mm(self%n, self%n)
      real(dp) :: a(max_dof, max_dof), c(max_dof), s(max_dof)
      call trig(self%n, q, c, s)
      call fill_mass(self, c, s, a)
      mm = a(1:self%n, 1:self%n)
   end function chain_mass_matrix

   !> ∂f/∂y of `field`: with q̈ = M⁻¹ f,
   !>   ∂q̈/∂q_k = M⁻¹ (∂f/∂q_k − (∂M/∂q_k) q̈),  ∂q̈/∂q̇_k = M⁻¹ ∂f/∂q̇_k, where
   !>   ∂f_i/∂q_i = G_i sin q_i − Σ_(j≠i) K_ij cos(q_i − q_j) q̇_j²,
   !>   ∂f_i/∂q_k = K_ik cos(q_i − q_k) q̇_k² (k ≠ i),  ∂f_i/∂q̇_k = −2 K_ik sin(q_i − q_k) q̇_k,
   !>   ((∂M/∂q_k) x)_i = −δ_ik Σ_j K_ij sin(q_i − q_j) x_j + K_ik sin(q_i − q_k) x_k.
   pure subroutine chain_jacobian(self, t, y, jac)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: qdd(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof), col(max_dof)
      real(dp) :: cij, sij, qd(max_dof), ra(2), va(2), aa(2), ce(max_dof), th
      integer :: n, i, k
      n = self%n
      qd(1:n) = y(n + 1:2*n)
      ! the joints' viscous slopes: c_i, plus c_f,i (1 − tanh²(ω_i/v_s))/v_s with friction
      if (self%damped) ce(1:n) = self%c
      if (self%coulomb) then
         if (.not. self%damped) ce(1:n) = 0.0_dp
         do i = 1, n
            th = tanh((qd(i) - merge(qd(max(i - 1, 1)), 0.0_dp, i > 1))/self%vs)
            ce(i) = ce(i) + self%cf(i)*(1.0_dp - th*th)/self%vs
         end do
      end if
      call solve_qdd(self, t, y(1:n), qd, qdd, a, c, s)
      if (self%driven) call self%support(t, ra, va, aa)
      jac = 0.0_dp
      do i = 1, n
         jac(i, n + i) = 1.0_dp
      end do
      do k = 1, n
         ! column ∂/∂q_k
         col(1:n) = 0.0_dp
         do i = 1, n
            if (i == k) cycle
            cij = c(i)*c(k) + s(i)*s(k)
            sij = s(i)*c(k) - c(i)*s(k)
            col(i) = self%k(i, k)*(cij*qd(k)**2 - sij*qdd(k))
            col(k) = col(k) - self%k(k, i)*(cij*qd(i)**2 + sij*qdd(i))
         end do
         col(k) = col(k) + self%gl(k)*s(k)
         ! ∂(−μ_k u_k × a_A)/∂q_k
         if (self%driven) col(k) = col(k) + self%mu(k)*(s(k)*aa(2) + c(k)*aa(1))
         call cholesky_solve(n, a, col)
         jac(n + 1:2*n, k) = col(1:n)
         ! column ∂/∂q̇_k
         do i = 1, n
            sij = s(i)*c(k) - c(i)*s(k)
            col(i) = -2.0_dp*self%k(i, k)*sij*qd(k)
         end do
         if (self%damped .or. self%coulomb) then   ! −C e_k
            col(k) = col(k) - ce(k)
            if (k > 1) col(k - 1) = col(k - 1) + ce(k)
            if (k < n) then
               col(k) = col(k) - ce(k + 1)
               col(k + 1) = col(k + 1) + ce(k + 1)
            end if
         end if
         call cholesky_solve(n, a, col)
         jac(n + 1:2*n, n + k) = col(1:n)
      end do
   end subroutine chain_jacobian

   !> V(q) = Σ G_i sin q_i, zero with every link horizontal [J].
   pure real(dp) function chain_potential(self, q) result(v)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(:)          !! angles [rad]
      integer :: i
      v = 0.0_dp
      do i = 1, self%n
         v = v + self%gl(i)*sin(q(i))
      end do
   end function chain_potential

   !> ½ q̇ᵀ M q̇ + V [J].
   !> On a moving support, the inertial energy (module notes): plus
   !> v_A · Σ μ_i q̇_i n_i + ½ m |v_A|² + m g y_A.
   pure real(dp) function chain_energy(self, t, y)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp) :: p(max_dof), ra(2), va(2), aa(2), mt
      integer :: n, i
      n = self%n
      call momenta_of(self, y(1:n), y(n + 1:2*n), p)
      chain_energy = 0.5_dp*dot_product(p(1:n), y(n + 1:2*n)) + self%potential(y(1:n))
      if (self%driven) then
         call self%support(t, ra, va, aa)
         mt = sum(self%m)
         chain_energy = chain_energy + 0.5_dp*mt*dot_product(va, va) + mt*self%g*ra(2)
         do i = 1, n
            chain_energy = chain_energy + self%mu(i)*y(n + i)* &
                           (-sin(y(i))*va(1) + cos(y(i))*va(2))
         end do
      end if
   end function chain_energy

   !> p = M(q) q̇ into the leading n of p.
   pure subroutine momenta_of(self, q, qd, p)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(*), qd(*)   !! angles [rad], rates [rad/s]
      real(dp), intent(out) :: p(max_dof)   !! momenta [kg m²/s]
      real(dp) :: a(max_dof, max_dof), c(max_dof), s(max_dof)
      integer :: i, n
      n = self%n
      call trig(n, q, c, s)
      call fill_mass(self, c, s, a)
      do i = 1, n
         p(i) = dot_product(a(i, 1:n), qd(1:n))
      end do
   end subroutine momenta_of

   pure subroutine chain_momenta(self, t, y, p)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: p(:)
      real(dp) :: w(max_dof)
      integer :: n
      n = self%n
      call momenta_of(self, y(1:n), y(n + 1:2*n), w)
      p(1:n) = w(1:n)
   end subroutine chain_momenta

   pure subroutine chain_velocities(self, t, z, qd)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: qd(:)
      real(dp) :: w(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof)
      integer :: n
      n = self%n
      call solve_qd(self, z(1:n), z(n + 1:2*n), w, a, c, s)
      qd(1:n) = w(1:n)
   end subroutine chain_velocities

   !> H = ½ pᵀ M⁻¹ p + V [J].
   pure real(dp) function chain_hamiltonian_value(self, t, z) result(h)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp) :: w(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof)
      integer :: n
      n = self%n
      call solve_qd(self, z(1:n), z(n + 1:2*n), w, a, c, s)
      h = 0.5_dp*dot_product(z(n + 1:2*n), w(1:n)) + self%potential(z(1:n))
   end function chain_hamiltonian_value

   !> σ_i = Σ_j K_ij sin(q_i − q_j) x_j.
   pure subroutine sigma(self, c, s, x, sg)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: c(max_dof), s(max_dof), x(max_dof)
      real(dp), intent(out) :: sg(max_dof)
      integer :: i, j
      do i = 1, self%n
         sg(i) = 0.0_dp
         do j = 1, self%n
            if (j == i) cycle
            sg(i) = sg(i) + self%k(i, j)*(s(i)*c(j) - c(i)*s(j))*x(j)
         end do
      end do
   end subroutine sigma

   !> The step-start cache: (cos q_1 … cos q_n, sin q_1 … sin q_n).
   pure integer function chain_cache_size(self)
      class(chain_t), intent(in) :: self
      chain_cache_size = 2*self%n
   end function chain_cache_size

   pure subroutine chain_fill_cache(self, q, cache)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: q(*)
      real(dp), intent(inout) :: cache(*)
      real(dp) :: c(max_dof), s(max_dof)
      integer :: n
      n = self%n
      call trig(n, q, c, s)
      cache(1:n) = c(1:n)
      cache(n + 1:2*n) = s(1:n)
   end subroutine chain_fill_cache

   !> The cache at the angles of y and `field` at y from it (rk4's first stage: the
   !> sines and cosines once, not once for the cache and once for the field).
   pure subroutine chain_fill_cache_field(self, t, y, cache, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(inout) :: cache(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: c(max_dof), s(max_dof)
      integer :: n
      logical :: runaway
      n = self%n
      call trig(n, y, c, s)
      cache(1:n) = c(1:n)
      cache(n + 1:2*n) = s(1:n)
      call saturate(2*n, y, f, runaway)
      if (runaway) return
      call field_trig(self, t, c, s, y, f)
   end subroutine chain_fill_cache_field

   !> `field` at y = (q0 + d, q̇) with the cos and sin of q0 from the cache.
   pure subroutine chain_field_near(self, t, y, d, cache, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*), d(*), cache(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: c(max_dof), s(max_dof)
      integer :: n
      logical :: runaway
      n = self%n
      call saturate(2*n, y, f, runaway)
      if (runaway) return
      call trig_near(n, cache(1:n), cache(n + 1:2*n), y(1:n), d(1:n), c, s)
      call field_trig(self, t, c, s, y, f)
   end subroutine chain_field_near

   !> `canonical_field` at z = (q0 + d, p) with the cos and sin of q0 from the cache.
   pure subroutine chain_canonical_field_near(self, t, z, d, cache, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*), d(*), cache(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: qd(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof)
      integer :: n
      logical :: runaway
      n = self%n
      call saturate(2*n, z, f, runaway)
      if (runaway) return
      call trig_near(n, cache(1:n), cache(n + 1:2*n), z(1:n), d(1:n), c, s)
      call solve_qd_trig(self, c, s, z(n + 1:2*n), qd, a)
      call canonical_tail(self, c, s, qd, f)
   end subroutine chain_canonical_field_near

   !> (q̇, τ − G cos q) from q̇ and the trigonometric values (see canonical_field).
   pure subroutine canonical_tail(self, c, s, qd, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: c(max_dof), s(max_dof), qd(max_dof)
      real(dp), intent(out) :: f(*)
      real(dp) :: sg(max_dof)
      integer :: n, i
      n = self%n
      call sigma(self, c, s, qd, sg)
      f(1:n) = qd(1:n)
      do i = 1, n
         f(n + i) = -qd(i)*sg(i) - self%gl(i)*c(i)
      end do
   end subroutine canonical_tail

   !> (∂H/∂p, −∂H/∂q) = (q̇, τ − G cos q), τ_i = −q̇_i σ_i(q̇).
   pure subroutine chain_canonical_field(self, t, z, f)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*)
      real(dp), intent(out) :: f(*)
      real(dp) :: qd(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof)
      integer :: n
      logical :: runaway
      n = self%n
      call saturate(2*n, z, f, runaway)
      if (runaway) return
      call solve_qd(self, z(1:n), z(n + 1:2*n), qd, a, c, s)
      call canonical_tail(self, c, s, qd, f)
   end subroutine chain_canonical_field

   !> A state with a component beyond `diverged_bound` (where the integrators stop
   !> the run) gets the field f = diverged_bound in every component instead of the
   !> dynamics: the accelerations grow like q̇², so the stages of one step that blows
   !> up would otherwise overflow (a trap under -ffpe-trap=overflow) before the
   !> step's end check sees the divergence.
   pure subroutine saturate(m, y, f, runaway)
      integer, intent(in) :: m           !! state size 2N
      real(dp), intent(in) :: y(*)       !! state
      real(dp), intent(inout) :: f(*)    !! set when runaway
      logical, intent(out) :: runaway    !! a component is beyond diverged_bound
      integer :: i
      runaway = .false.
      do i = 1, m
         if (abs(y(i)) > diverged_bound) runaway = .true.
      end do
      if (runaway) f(1:m) = diverged_bound
   end subroutine saturate

   !> ∂f/∂z of `canonical_field`, z = (q, p): ∂q̇/∂p = M⁻¹, ∂q̇/∂q_k = −M⁻¹ (∂M/∂q_k) q̇,
   !> and for f_p,i = −q̇_i σ_i − G_i cos q_i:
   !>   ∂f_p,i/∂x = −(∂q̇_i/∂x) σ_i − q̇_i Σ_j K_ij sin(q_i − q_j) ∂q̇_j/∂x
   !>               − q̇_i ∂σ_i/∂q_k|_q̇ + δ_ik G_i sin q_i  (last two for x = q_k),
   !>   ∂σ_i/∂q_k|_q̇ = δ_ik Σ_j K_ij cos(q_i − q_j) q̇_j − K_ik cos(q_i − q_k) q̇_k (k ≠ i).
   pure subroutine chain_canonical_jacobian(self, t, z, jac)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: jac(:, :)
      real(dp) :: qd(max_dof), a(max_dof, max_dof), c(max_dof), s(max_dof), sg(max_dof)
      real(dp) :: col(max_dof), dsg(max_dof), cik, sik
      integer :: n, i, k, j
      n = self%n
      call solve_qd(self, z(1:n), z(n + 1:2*n), qd, a, c, s)
      call sigma(self, c, s, qd, sg)
      do k = 1, 2*n
         ! ∂q̇/∂z_k
         col(1:n) = 0.0_dp
         if (k <= n) then
            do i = 1, n
               if (i == k) cycle
               sik = s(i)*c(k) - c(i)*s(k)
               ! −(∂M/∂q_k) q̇: entry i ≠ k is −K_ik sin(q_i − q_k) q̇_k, entry k is
               ! Σ_j K_kj sin(q_k − q_j) q̇_j
               col(i) = -self%k(i, k)*sik*qd(k)
               col(k) = col(k) - self%k(k, i)*sik*qd(i)
            end do
         else
            col(k - n) = 1.0_dp
         end if
         call cholesky_solve(n, a, col)
         jac(1:n, k) = col(1:n)
         call sigma(self, c, s, col, dsg)
         do i = 1, n
            jac(n + i, k) = -col(i)*sg(i) - qd(i)*dsg(i)
         end do
         if (k <= n) then
            do i = 1, n
               if (i == k) then
                  do j = 1, n
                     if (j == i) cycle
                     jac(n + i, k) = jac(n + i, k) &
                                     - qd(i)*self%k(i, j)*(c(i)*c(j) + s(i)*s(j))*qd(j)
                  end do
                  jac(n + i, k) = jac(n + i, k) + self%gl(i)*s(i)
               else
                  cik = c(i)*c(k) + s(i)*s(k)
                  jac(n + i, k) = jac(n + i, k) + qd(i)*self%k(i, k)*cik*qd(k)
               end if
            end do
         end if
      end do
   end subroutine chain_canonical_jacobian

   !> ∂E/∂y: ∂E/∂q_i = τ_i + G_i cos q_i (τ_i = −q̇_i σ_i(q̇)), ∂E/∂q̇ = p.
   pure subroutine chain_energy_gradient(self, t, y, g)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: g(:)
      real(dp) :: c(max_dof), s(max_dof), qd(max_dof), sg(max_dof), p(max_dof)
      integer :: n, i
      n = self%n
      qd(1:n) = y(n + 1:2*n)
      call trig(n, y, c, s)
      call sigma(self, c, s, qd, sg)
      call momenta_of(self, y(1:n), qd, p)
      do i = 1, n
         g(i) = -qd(i)*sg(i) + self%gl(i)*c(i)
      end do
      g(n + 1:2*n) = p(1:n)
      if (self%driven) then   ! ∂/∂y of v_A · Σ μ_i q̇_i n_i
         block
            real(dp) :: ra(2), va(2), aa(2)
            call self%support(t, ra, va, aa)
            do i = 1, n
               g(i) = g(i) - self%mu(i)*qd(i)*(c(i)*va(1) + s(i)*va(2))
               g(n + i) = g(n + i) + self%mu(i)*(-s(i)*va(1) + c(i)*va(2))
            end do
         end block
      end if
   end subroutine chain_energy_gradient

   ! the sensitivities of the motion to the damping (dpend fit --fit-damping)

   !> ∂q̈/∂c_i = M⁻¹ ∂Q/∂c_i with ∂Q/∂c_i = −w_i e_i + w_i e_(i−1),
   !> w_i = q̇_i − q̇_(i−1) (q̇_0 = 0): one column per joint.
   pure subroutine chain_parameter_rates(self, t, y, name, d)
      class(chain_t), intent(in) :: self
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: y(:)         !! state (q, q̇)
      character(len=*), intent(in) :: name !! 'damping'
      real(dp), intent(out) :: d(:, :)     !! ∂q̈/∂c (n, n)
      real(dp) :: a(max_dof, max_dof), c(max_dof), sn(max_dof), b(max_dof), w
      integer :: i, n
      n = self%n
      d = 0.0_dp
      if (name /= 'damping') return
      call trig(n, y(1:n), c, sn)
      call fill_mass(self, c, sn, a)
      call cholesky(n, a)
      do i = 1, n
         w = y(n + i)
         if (i > 1) w = w - y(n + i - 1)
         b = 0.0_dp
         b(i) = -w
         if (i > 1) b(i - 1) = w
         call cholesky_solve(n, a, b)
         d(:, i) = b(1:n)
      end do
   end subroutine chain_parameter_rates
end module dpend_chain
