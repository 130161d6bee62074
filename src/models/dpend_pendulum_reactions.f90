!> Joint reactions from the Newton–Euler equations (chapter 6.16–6.26, corrected):
!> F21 is the force of link 2 on link 1 at B, F01 the force of the ground on link 1
!> at A, both in newtons, (x, y) with y up.
module dpend_pendulum_reactions
   use dpend_kinds, only: dp
   use dpend_pendulum, only: pendulum_t
   use dpend_pendulum_kinematics, only: kinematics_t, kinematics
   implicit none
   private
   public :: reactions

contains

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
end module dpend_pendulum_reactions
