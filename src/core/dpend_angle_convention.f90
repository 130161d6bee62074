!> The two conventions of link angles (docs/robot.md, "Angle conventions"):
!> - absolute (the chapter's, dpend's own): q_i from the horizontal x axis,
!>   counter-clockwise, the hanging position q_i = −π/2;
!> - relative (robotics): φ_1 = q_1 + π/2 (link 1 from the hanging position), φ_i =
!>   q_i − q_(i−1) (link i against link i − 1), zero hanging straight down;
!>   rates and accelerations by the same differences (φ̇_1 = q̇_1).
!> Pure, no state.
module dpend_angle_convention
   use dpend_kinds, only: dp, half_pi
   implicit none
   private
   public :: to_relative, to_absolute, rates_to_relative, rates_to_absolute

contains

   !> φ (N, K) of the absolute angles q (N, K).
   pure function to_relative(q) result(phi)
      real(dp), intent(in) :: q(:, :)
      real(dp) :: phi(size(q, 1), size(q, 2))
      phi = rates_to_relative(q)
      phi(1, :) = q(1, :) + half_pi
   end function to_relative

   !> q (N, K) of the relative angles φ (N, K): q_1 = φ_1 − π/2, q_i = q_(i−1) + φ_i.
   pure function to_absolute(phi) result(q)
      real(dp), intent(in) :: phi(:, :)
      real(dp) :: q(size(phi, 1), size(phi, 2))
      q = phi
      q(1, :) = phi(1, :) - half_pi
      q = rates_to_absolute(q)
   end function to_absolute

   !> Relative rates (N, K) of absolute ones: differences of neighbouring links.
   pure function rates_to_relative(w) result(r)
      real(dp), intent(in) :: w(:, :)
      real(dp) :: r(size(w, 1), size(w, 2))
      integer :: i
      r = w
      do i = 2, size(w, 1)
         r(i, :) = w(i, :) - w(i - 1, :)
      end do
   end function rates_to_relative

   !> Absolute rates (N, K) of relative ones: running sums from link 1.
   pure function rates_to_absolute(r) result(w)
      real(dp), intent(in) :: r(:, :)
      real(dp) :: w(size(r, 1), size(r, 2))
      integer :: i
      w = r
      do i = 2, size(r, 1)
         w(i, :) = w(i - 1, :) + r(i, :)
      end do
   end function rates_to_absolute

end module dpend_angle_convention
