!> Kinematics of the chapter (eqs 6.1–6.14): position, velocity and acceleration of
!> the centres of mass C1, C2 and of the joint B, as (x, y) pairs in metres,
!> m/s and m/s², with the pin A at the origin and y up.
module dpend_pendulum_kinematics
   use dpend_kinds, only: dp
   use dpend_pendulum, only: pendulum_t
   implicit none
   private
   public :: kinematics_t, kinematics, tip_position

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
end module dpend_pendulum_kinematics
