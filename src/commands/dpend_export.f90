!> `dpend export`: datasets of an HDF5 file as whitespace-separated text columns,
!> for gnuplot. A 1-D dataset (n) gives one column, a 2-D one (n, k as h5py sees
!> it) gives k columns; all must have the same n. `export_matrix` prints one 2-D
!> dataset as a gnuplot "nonuniform matrix" (for `plot ... with image`).
module dpend_export
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_hdf5, only: h5file_t
   use dpend_config, only: check_regular_file
   use dpend_limits, only: sci
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: export_columns, export_matrix

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
      call check_regular_file(filename, "invalid FILE '"//filename//"': ", error)
      if (allocated(error)) return
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

   !> Write the 2-D dataset `path` of `filename` (h5py shape (ny, nx)) to `unit` as a
   !> gnuplot nonuniform matrix: a first line "nx x(1) ... x(nx)", then one line
   !> "y(j) v(1, j) ... v(nx, j)" per row. x and y come from the 1-D datasets
   !> `xpath` and `ypath` if given, else they are the indices 1, 2, ... Values are
   !> divided by `scale` if given; NaN is printed as NaN (gnuplot leaves it out).
   subroutine export_matrix(filename, path, unit, error, xpath, ypath, scale)
      character(len=*), intent(in) :: filename          !! HDF5 file
      character(len=*), intent(in) :: path              !! 2-D dataset
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      character(len=*), intent(in), optional :: xpath   !! 1-D dataset of x values
      character(len=*), intent(in), optional :: ypath   !! 1-D dataset of y values
      real(dp), intent(in), optional :: scale           !! divide the values by it
      type(h5file_t) :: h5
      real(dp), allocatable :: v(:, :), x(:), y(:), row(:)
      real(dp) :: big
      integer :: i, j
      character(len=*), parameter :: fmt = '(*(es15.7e3, :, " "))'
      call check_regular_file(filename, "invalid FILE '"//filename//"': ", error)
      if (allocated(error)) return
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      call h5%read(trim(path), v, error)
      if (.not. allocated(error)) then
         if (present(xpath)) then
            call h5%read(trim(xpath), x, error)
         else
            x = [(real(i, dp), i=1, size(v, 1))]
         end if
      end if
      if (.not. allocated(error)) then
         if (present(ypath)) then
            call h5%read(trim(ypath), y, error)
         else
            y = [(real(j, dp), j=1, size(v, 2))]
         end if
      end if
      call h5%close()
      if (allocated(error)) return
      if (size(x) /= size(v, 1) .or. size(y) /= size(v, 2)) then
         call fatal_error(error, "export: the axes do not match the shape of '"// &
                          trim(path)//"'")
         return
      end if
      if (present(scale)) then
         if (.not. (scale > 0.0_dp .and. ieee_is_finite(scale))) then
            call fatal_error(error, 'invalid SCALE: must be finite and > 0')
            return
         end if
         ! refuse quotients beyond the largest real (the division would overflow)
         ! (element by element: an ordered comparison with NaN would trap)
         big = 0.0_dp
         do j = 1, size(v, 2)
            do i = 1, size(v, 1)
               if (ieee_is_finite(v(i, j))) big = max(big, abs(v(i, j)))
            end do
         end do
         ! (nested, not `.and.`: Fortran may evaluate both operands, and huge*scale
         ! overflows for scale > 1)
         if (scale < 1.0_dp) then
            if (big > huge(1.0_dp)*scale) then
               call fatal_error(error, 'invalid SCALE: '//sci(scale)//" makes the values "// &
                                "of '"//trim(path)//"' exceed the largest real (largest "// &
                                '|value| '//sci(big)//'; SCALE must be >= '// &
                                sci(big/huge(1.0_dp))//')')
               return
            end if
         end if
         where (ieee_is_finite(v)) v = v/scale   ! NaN and Inf stay, without arithmetic
      end if
      allocate (row(size(x) + 1))
      row(1) = real(size(x), dp)
      row(2:) = x
      write (unit, fmt) row
      do j = 1, size(y)
         row(1) = y(j)
         row(2:) = v(:, j)
         write (unit, fmt) row
      end do
   end subroutine export_matrix
end module dpend_export
