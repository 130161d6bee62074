!> Sorting and the median of real arrays (pure, no state): a bottom-up merge sort,
!> O(n log n), stable.
module dpend_sorting
   use dpend_kinds, only: dp
   implicit none
   private
   public :: sort, median

contains

   !> The median of x (of a sorted copy); 0 for an empty x.
   pure real(dp) function median(x)
      real(dp), intent(in) :: x(:)  !! the values
      real(dp), allocatable :: s(:)
      integer :: n
      n = size(x)
      median = 0.0_dp
      if (n == 0) return
      s = x
      call sort(s)
      if (mod(n, 2) == 1) then
         median = s((n + 1)/2)
      else
         median = 0.5_dp*(s(n/2) + s(n/2 + 1))
      end if
   end function median

   !> Sort x in increasing order, in place (bottom-up merge sort).
   pure subroutine sort(x)
      real(dp), intent(inout) :: x(:)  !! the values
      real(dp), allocatable :: b(:)
      integer :: n, width, lo, mid, hi, i, j, o
      n = size(x)
      allocate (b(n))
      width = 1
      do while (width < n)
         lo = 1
         do while (lo <= n)
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo; j = mid + 1; o = lo
            do while (i <= mid .and. j <= hi)
               if (x(i) <= x(j)) then
                  b(o) = x(i); i = i + 1
               else
                  b(o) = x(j); j = j + 1
               end if
               o = o + 1
            end do
            b(o:o + mid - i) = x(i:mid)
            o = o + mid - i + 1
            b(o:o + hi - j) = x(j:hi)
            lo = lo + 2*width
         end do
         x = b
         width = 2*width
      end do
   end subroutine sort

end module dpend_sorting
