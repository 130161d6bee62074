!> `dpend export`: datasets of an HDF5 file as whitespace-separated text columns,
!> for gnuplot. A 1-D dataset (n) gives one column, a 2-D one (n, k as h5py sees
!> it) gives k columns; all must have the same n.
module dpend_export
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_hdf5, only: h5file_t
   implicit none
   private
   public :: export_columns

contains

   !> Write the datasets `paths` of `filename` as columns to `unit`.
   subroutine export_columns(filename, paths, unit, error)
      character(len=*), intent(in) :: filename          !! HDF5 file
      character(len=*), intent(in) :: paths(:)          !! dataset paths
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      type(h5file_t) :: h5
      real(dp), allocatable :: table(:, :), v1(:), v2(:, :)
      integer, allocatable :: dims(:)
      integer :: i, j, n, ncol, col
      character(len=:), allocatable :: fmt
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      ncol = 0
      n = -1
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, error)
         if (allocated(error)) exit
         if (size(dims) == 1) then
            ncol = ncol + 1
         else if (size(dims) == 2) then
            ncol = ncol + dims(1)
         else
            call fatal_error(error, "export: '"//trim(paths(i))//"' is not 1-D or 2-D")
            exit
         end if
         if (n >= 0 .and. dims(size(dims)) /= n) then
            call fatal_error(error, "export: '"//trim(paths(i))//"' has another length")
            exit
         end if
         n = dims(size(dims))
      end do
      if (allocated(error)) then
         call h5%close()
         return
      end if
      allocate (table(ncol, max(n, 0)))
      col = 0
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, error)
         if (size(dims) == 1) then
            call h5%read(trim(paths(i)), v1, error)
            if (allocated(error)) exit
            table(col + 1, :) = v1
            col = col + 1
         else
            call h5%read(trim(paths(i)), v2, error)
            if (allocated(error)) exit
            table(col + 1:col + dims(1), :) = v2
            col = col + dims(1)
         end if
      end do
      call h5%close()
      if (allocated(error)) return
      fmt = '(*(es24.16e3, :, " "))'
      do j = 1, n
         write (unit, fmt) table(:, j)
      end do
   end subroutine export_columns
end module dpend_export
