!> The double pendulum's force recovery for the files: the kinematics of the centres
!> of mass C1, C2 and the joint B (chapter 6.2–6.12), the free end of link 2, and the
!> joint reactions F01, F21 (6.16–6.26, corrected: docs/errata.md) for a state and
!> its accelerations. Evaluated per output sample, never within an integrator step.
!>
!> dpend_pendulum passes every public name of this module on; use it from there.
module dpend_pendulum_forces
   use dpend_kinds, only: dp
   use dpend_pendulum_params, only: pendulum_t, body_rod
   implicit none
   private
   public :: kinematics_t, kinematics, tip_position, reactions

   !> Positions [m], velocities [m/s] and accelerations [m/s²] of C1, C2 and B.
   type :: kinematics_t
      real(dp) :: rc1(2) !! position of C1 [m] (6.2)
      real(dp) :: vc1(2) !! velocity of C1 [m/s] (6.6)
      real(dp) :: ac1(2) !! acceleration of C1 [m/s²] (6.10)
      real(dp) :: rc2(2) !! position of C2 [m] (6.4)
      real(dp) :: vc2(2) !! velocity of C2 [m/s] (6.8)
      real(dp) :: ac2(2) !! acceleration of C2 [m/s²] (6.12)
      real(dp) :: rb(2)  !! position of the joint B [m]
      real(dp) :: vb(2)  !! velocity of B [m/s]
      real(dp) :: ab(2)  !! acceleration of B [m/s²]
   end type kinematics_t

contains

   !> Kinematics of C1, C2 and B for given q, q̇, q̈.
   pure function kinematics(par, q, qd, qdd) result(k)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp), intent(in) :: qdd(2)       !! angular accelerations [rad/s²]
      type(kinematics_t) :: k
      real(dp) :: u1(2), u2(2), n1(2), n2(2)
      u1 = [cos(q(1)), sin(q(1))]     ! unit vector along link 1
      u2 = [cos(q(2)), sin(q(2))]     ! unit vector along link 2
      n1 = [-u1(2), u1(1)]            ! u1 turned by +90°
      n2 = [-u2(2), u2(1)]
      ! a point at distance s along a link: r = s u, v = s q̇ n, a = s (q̈ n - q̇² u)
      k%rb = par%l1*u1
      k%vb = par%l1*qd(1)*n1
      k%ab = par%l1*(qdd(1)*n1 - qd(1)**2*u1)
      if (par%body /= body_rod) then   ! C_i at d_i along link i
         k%rc1 = par%d1*u1
         k%vc1 = par%d1*qd(1)*n1
         k%ac1 = par%d1*(qdd(1)*n1 - qd(1)**2*u1)
         k%rc2 = k%rb + par%d2*u2
         k%vc2 = k%vb + par%d2*qd(2)*n2
         k%ac2 = k%ab + par%d2*(qdd(2)*n2 - qd(2)**2*u2)
         return
      end if
      k%rc1 = 0.5_dp*k%rb
      k%vc1 = 0.5_dp*k%vb
      k%ac1 = 0.5_dp*k%ab
      k%rc2 = k%rb + 0.5_dp*par%l2*u2
      k%vc2 = k%vb + 0.5_dp*par%l2*qd(2)*n2
      k%ac2 = k%ab + 0.5_dp*par%l2*(qdd(2)*n2 - qd(2)**2*u2)
   end function kinematics

   !> Position of the free end of link 2 [m].
   pure function tip_position(par, q) result(r)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp) :: r(2)
      r = par%l1*[cos(q(1)), sin(q(1))] + par%l2*[cos(q(2)), sin(q(2))]
   end function tip_position

   !> F01 and F21 [N] for a state and its accelerations.
   !>
   !> Link 2 (6.22, 6.23): m2 a_C2 = -F21 + G2, so F21 = -m2 (a_C2 + g j)
   !> (the chapter's 6.26 prints + m2 g; the sign is corrected here, docs/errata.md).
   !> Link 1 (6.16): m1 a_C1 = F01 + F21 + G1, so F01 = m1 (a_C1 + g j) - F21.
   pure subroutine reactions(par, q, qd, qdd, f01, f21)
      type(pendulum_t), intent(in) :: par  !! parameters
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! angular velocities [rad/s]
      real(dp), intent(in) :: qdd(2)       !! angular accelerations [rad/s²]
      real(dp), intent(out) :: f01(2)      !! ground on link 1 at A [N]
      real(dp), intent(out) :: f21(2)      !! link 2 on link 1 at B [N]
      type(kinematics_t) :: k
      k = kinematics(par, q, qd, qdd)
      f21 = -par%m2*(k%ac2 + [0.0_dp, par%g])
      f01 = par%m1*(k%ac1 + [0.0_dp, par%g]) - f21
   end subroutine reactions
end module dpend_pendulum_forces
