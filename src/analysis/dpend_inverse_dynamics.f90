!> Inverse dynamics of the N-link chain by Newton–Euler: the joint torques and
!> reactions that a motion (q, q̇, q̈) at time t requires.
!>
!> The forces come from the tip (the chain's own recursion, `reactions`):
!>   F_(i−1,i) = F_(i,i+1) + m_i (a_Ci + g ĵ),  F_(N,N+1) = 0,
!> and the moments about each centre of mass C_i give the torques, again from the tip.
!> Body i (unit vector u_i along it, C_i at d_i from joint i, inertia I_i about C_i)
!> feels F_(i−1,i) at joint i (−d_i u_i from C_i), −F_(i,i+1) at joint i + 1
!> ((L_i − d_i) u_i from C_i), the motor couples τ_i and −τ_(i+1), and the joints'
!> friction couples −φ_i and +φ_(i+1), φ_i = c_i ω_i + c_f,i tanh(ω_i/v_s) with
!> ω_i = q̇_i − q̇_(i−1) (q̇_0 = 0). Its moment equation
!>   I_i q̈_i = −d_i u_i × F_(i−1,i) − (L_i − d_i) u_i × F_(i,i+1)
!>             + (τ_i − φ_i) − (τ_(i+1) − φ_(i+1))
!> gives, with τ_(N+1) − φ_(N+1) = 0,
!>   τ_i = φ_i + (τ_(i+1) − φ_(i+1)) + I_i q̈_i + d_i u_i × F_(i−1,i)
!>         + (L_i − d_i) u_i × F_(i,i+1),
!> where a × b = a_x b_y − a_y b_x. A motor at joint i (the chain's reflected rotor
!> inertia Im_i = g_r,i² I_r,i) needs Im_i ω̇_i more to turn its rotor:
!>   τ_i ← τ_i + Im_i (q̈_i − q̈_(i−1))
!> (the couple on the links is unchanged, the forces too). A moving support enters
!> through the accelerations of the recursion (the chain's `kinematics` at t). This
!> is the forward model's
!> equation read backwards: for the q̈ of the chain's field under torques τ(t), it
!> returns τ(t) (test_inverse_dynamics, to rounding).
module dpend_inverse_dynamics
   use dpend_kinds, only: dp
   use dpend_model, only: max_dof
   use dpend_chain, only: chain_t
   implicit none
   private
   public :: joint_torques, torque_gain

contains

   !> The joint torques τ (N) [N m] and reactions F_(i−1,i) (2, N) [N] of the motion
   !> (q, q̇, q̈) of `chain` at time t (module's notes).
   pure subroutine joint_torques(chain, t, q, qd, qdd, tau, f)
      type(chain_t), intent(in) :: chain   !! the model (its torques, if any, unused)
      real(dp), intent(in) :: t            !! time [s] (the support's motion)
      real(dp), intent(in) :: q(:), qd(:), qdd(:)  !! angles, rates, accelerations (N)
      real(dp), intent(out) :: tau(:)      !! joint torques τ_1 .. τ_N [N m]
      real(dp), intent(out) :: f(:, :)     !! reactions F_(i−1,i) (2, N) [N]
      real(dp) :: u(2), next_f(2), next_s, s, d, l, w
      real(dp) :: phi(max_dof)
      integer :: i, n
      n = chain%n
      call chain%reactions(q, qd, qdd, f, t)
      do i = 1, n
         w = qd(i)
         if (i > 1) w = w - qd(i - 1)
         phi(i) = 0.0_dp
         if (chain%damped) phi(i) = chain%c(i)*w
         if (chain%coulomb) phi(i) = phi(i) + chain%cf(i)*tanh(w/chain%vs)
      end do
      next_f = 0.0_dp
      next_s = 0.0_dp   ! τ_(i+1) − φ_(i+1)
      do i = n, 1, -1
         u = [cos(q(i)), sin(q(i))]
         d = chain%d(i)
         l = chain%l(i)
         s = next_s + chain%ic(i)*qdd(i) + d*cross(u, f(:, i)) + (l - d)*cross(u, next_f)
         tau(i) = s + phi(i)
         if (chain%motors) then
            tau(i) = tau(i) + chain%im(i)*qdd(i)
            if (i > 1) tau(i) = tau(i) - chain%im(i)*qdd(i - 1)
         end if
         next_s = s
         next_f = f(:, i)
      end do
   end subroutine joint_torques

   !> The gain A (N, N) [kg m²] of the torques on the accelerations at q: τ changes
   !> by A δq̈ for a change δq̈ (the mass matrix summed from the tip: A_ij =
   !> Σ_(k>=i) M_kj, the rotors' Im_i on ω̇_i included), so that white errors of
   !> standard deviation σ_j in q̈_j give τ_i errors of standard deviation
   !> (Σ_j A_ij² σ_j²)^(1/2).
   pure subroutine torque_gain(chain, q, a)
      type(chain_t), intent(in) :: chain  !! the model
      real(dp), intent(in) :: q(:)        !! angles (N)
      real(dp), intent(out) :: a(:, :)    !! the gain (N, N)
      integer :: i, n
      n = chain%n
      a = chain%mass_matrix(q)
      do i = n - 1, 1, -1
         a(i, :) = a(i, :) + a(i + 1, :)
      end do
   end subroutine torque_gain

   pure real(dp) function cross(a, b)
      real(dp), intent(in) :: a(2), b(2)
      cross = a(1)*b(2) - a(2)*b(1)
   end function cross

end module dpend_inverse_dynamics
