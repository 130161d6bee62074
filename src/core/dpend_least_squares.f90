!> Linear least squares and the singular value decomposition, pure, no state:
!> - `jacobi_svd`: the singular values and right singular vectors of a real matrix by
!>   one-sided Jacobi rotations (Hestenes): accurate for the small singular values,
!>   which the normal matrix AᵀA would square below the rounding unit;
!> - `qr_least_squares`: min ‖A x − b‖ by the QR factorisation of A (Gram–Schmidt,
!>   each column orthogonalised twice: as accurate as Householder for a few columns),
!>   with R, so that (AᵀA)⁻¹ = R⁻¹ R⁻ᵀ gives the covariance of x.
module dpend_least_squares
   use dpend_kinds, only: dp
   implicit none
   private
   public :: jacobi_svd, qr_least_squares, r_inverse

contains

   !> A = U Σ Vᵀ: the singular values sv (P, largest first) and the right singular
   !> vectors v (P, P, column j for sv(j)) of a (m, P).
   pure subroutine jacobi_svd(a, sv, v)
      real(dp), intent(in) :: a(:, :)                   !! the matrix (m, P)
      real(dp), allocatable, intent(out) :: sv(:)       !! singular values (P)
      real(dp), allocatable, intent(out) :: v(:, :)     !! right singular vectors (P, P)
      real(dp), allocatable :: u(:, :), col(:)
      real(dp) :: alpha, beta, gamma, zeta, tt, cs, sn
      integer :: np, i, j, sweep, order(size(a, 2))
      logical :: rotated
      np = size(a, 2)
      u = a
      allocate (v(np, np))
      v = 0.0_dp
      do j = 1, np
         v(j, j) = 1.0_dp
      end do
      do sweep = 1, 60
         rotated = .false.
         do i = 1, np - 1
            do j = i + 1, np
               alpha = sum(u(:, i)**2)
               beta = sum(u(:, j)**2)
               gamma = sum(u(:, i)*u(:, j))
               if (abs(gamma) <= 1e-15_dp*sqrt(alpha*beta) .or. gamma == 0.0_dp) cycle
               rotated = .true.
               zeta = (beta - alpha)/(2.0_dp*gamma)
               tt = sign(1.0_dp, zeta)/(abs(zeta) + sqrt(1.0_dp + zeta**2))
               cs = 1.0_dp/sqrt(1.0_dp + tt**2)
               sn = cs*tt
               col = u(:, i)
               u(:, i) = cs*col - sn*u(:, j)
               u(:, j) = sn*col + cs*u(:, j)
               col = v(:, i)
               v(:, i) = cs*col - sn*v(:, j)
               v(:, j) = sn*col + cs*v(:, j)
            end do
         end do
         if (.not. rotated) exit
      end do
      allocate (sv(np))
      do j = 1, np
         sv(j) = sqrt(sum(u(:, j)**2))
      end do
      do i = 1, np   ! largest first
         order(i) = maxloc(sv, dim=1)
         sv(order(i)) = -sv(order(i)) - 1.0_dp
      end do
      sv = -sv - 1.0_dp
      sv = sv(order)
      v = v(:, order)
   end subroutine jacobi_svd

   !> x = argmin ‖A x − b‖ for A (m, P) of full column rank (m >= P), and the
   !> triangular factor r (P, P) of A = Q R. `ok` false when a column is (numerically)
   !> a combination of the previous ones (R_jj <= 1e-13 ‖A_j‖).
   pure subroutine qr_least_squares(a, b, x, r, ok)
      real(dp), intent(in) :: a(:, :)                !! the matrix (m, P)
      real(dp), intent(in) :: b(:)                   !! the right-hand side (m)
      real(dp), intent(out) :: x(:)                  !! the solution (P)
      real(dp), intent(out) :: r(:, :)               !! R (P, P)
      logical, intent(out) :: ok                     !! full column rank
      real(dp), allocatable :: q(:, :), bb(:)
      real(dp) :: qb(size(a, 2)), s, w
      integer :: c, i, pass, np
      np = size(a, 2)
      allocate (q(size(a, 1), np))
      r = 0.0_dp
      ok = .true.
      do c = 1, np
         q(:, c) = a(:, c)
         w = norm2(a(:, c))
         do pass = 1, 2
            do i = 1, c - 1
               s = dot_product(q(:, i), q(:, c))
               r(i, c) = r(i, c) + s
               q(:, c) = q(:, c) - s*q(:, i)
            end do
         end do
         r(c, c) = norm2(q(:, c))
         if (.not. (r(c, c) > 1e-13_dp*w)) then
            ok = .false.
            x = 0.0_dp
            return
         end if
         q(:, c) = q(:, c)/r(c, c)
      end do
      bb = b   ! Qᵀ b as b's own orthogonalisation (twice), as accurate as the columns'
      qb = 0.0_dp
      do pass = 1, 2
         do i = 1, np
            s = dot_product(q(:, i), bb)
            qb(i) = qb(i) + s
            bb = bb - s*q(:, i)
         end do
      end do
      do c = np, 1, -1
         x(c) = (qb(c) - dot_product(r(c, c + 1:np), x(c + 1:np)))/r(c, c)
      end do
   end subroutine qr_least_squares

   !> R⁻¹ of an upper triangular R with a nonzero diagonal.
   pure function r_inverse(r) result(ri)
      real(dp), intent(in) :: r(:, :)
      real(dp) :: ri(size(r, 1), size(r, 1))
      integer :: i, j, n
      n = size(r, 1)
      ri = 0.0_dp
      do j = 1, n
         ri(j, j) = 1.0_dp/r(j, j)
         do i = j - 1, 1, -1
            ri(i, j) = -dot_product(r(i, i + 1:j), ri(i + 1:j, j))/r(i, i)
         end do
      end do
   end function r_inverse

end module dpend_least_squares
