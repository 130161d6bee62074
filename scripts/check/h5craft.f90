!> h5craft: edit an HDF5 file into a hostile one, for the reliability suite's
!> fixtures (test/reliability/cases/external_files.sh, io_coordinates.sh). Not part of
!> dpend.
!> Build: h5fc -o h5craft scripts/check/h5craft.f90 (h5fc comes with libhdf5-dev).
!>
!> usage: h5craft FILE OP ARGS...   (FILE must exist; shapes in h5py order)
!>   del PATH                      delete the link PATH
!>   huge PATH D1 [D2]             a chunked float64 dataset of that shape (chunk 1 x D2),
!>                                 nothing written (a few kB declare any size)
!>   real PATH VALUE D1 [D2]       a float64 dataset filled with VALUE (nan, inf allowed)
!>   ramp PATH D1                  a float64 dataset 0, 1, ..., D1-1
!>   int PATH VALUE D1 [D2]        an int32 dataset filled with VALUE
!>   set PATH INDEX VALUE          set element INDEX (1-based, in storage order) of
!>                                 the float64 dataset PATH to VALUE
!>   attr-int OBJ NAME D1          an int32 attribute array 1..D1 of OBJ
!>   attr-i0 OBJ NAME VALUE        a scalar int32 attribute of OBJ
!>   attr-real OBJ NAME VALUE      a scalar float64 attribute of OBJ
!>   attr-sub OBJ NAME OLD NEW     replace OLD by NEW in the string attribute NAME
!>   attr-del OBJ NAME             delete the attribute NAME of OBJ
!> A dataset or attribute that exists is replaced.
program h5craft
   use hdf5
   use, intrinsic :: iso_c_binding, only: c_loc, c_ptr, c_char, c_null_char, c_f_pointer, &
      c_associated
   implicit none
   integer, parameter :: dp = kind(1.0d0)
   character(len=4096) :: file, op, a(6)
   integer(hid_t) :: fid
   integer :: ierr, i, nargs
   nargs = command_argument_count()
   if (nargs < 3) call die('usage: h5craft FILE OP ARGS... (see the source)')
   call get_command_argument(1, file)
   call get_command_argument(2, op)
   a = ''
   do i = 3, min(nargs, 8)
      call get_command_argument(i, a(i - 2))
   end do
   call h5open_f(ierr)
   call h5eset_auto_f(0, ierr)
   call h5fopen_f(trim(file), H5F_ACC_RDWR_F, fid, ierr)
   if (ierr /= 0) call die('cannot open '//trim(file))
   select case (trim(op))
   case ('del')
      call h5ldelete_f(fid, trim(a(1)), ierr)
   case ('huge')
      call make_real(a(1), shape_of(a(2:3)), .true., 0.0_dp)
   case ('real')
      call make_real(a(1), shape_of(a(3:4)), .false., real_of(a(2)))
   case ('ramp')
      call make_real(a(1), shape_of(a(2:2)), .false., -1.0_dp, ramp=.true.)
   case ('int')
      call make_int(a(1), shape_of(a(3:4)), int(real_of(a(2))))
   case ('set')
      call set_one(a(1), int(real_of(a(2))), real_of(a(3)))
   case ('attr-int')
      call attr_int(a(1), a(2), int(real_of(a(3))))
   case ('attr-i0')
      call attr_int(a(1), a(2), int(real_of(a(3))), scalar=.true.)
   case ('attr-real')
      call attr_real(a(1), a(2), real_of(a(3)))
   case ('attr-sub')
      call attr_sub(a(1), a(2), a(3), a(4))
   case ('attr-del')
      call h5adelete_by_name_f(fid, trim(a(1)), trim(a(2)), ierr)
   case default
      call die('unknown op '//trim(op))
   end select
   if (ierr /= 0) call die(trim(op)//' failed')
   call h5fclose_f(fid, ierr)
   call h5close_f(ierr)
contains
   subroutine die(msg)
      character(len=*), intent(in) :: msg
      write (0, '(a)') 'h5craft: '//msg
      error stop 1
   end subroutine die
   !> Fortran-order shape from h5py-order words (blank words left out).
   function shape_of(w) result(d)
      character(len=*), intent(in) :: w(:)
      integer(hsize_t), allocatable :: d(:)
      integer :: k, n
      n = count(len_trim(w) > 0)
      allocate (d(n))
      do k = 1, n
         read (w(k), *) d(n - k + 1)
      end do
   end function shape_of
   real(dp) function real_of(w)
      character(len=*), intent(in) :: w
      read (w, *) real_of
   end function real_of
   subroutine replace(path)
      character(len=*), intent(in) :: path
      logical :: found
      integer :: e
      call h5lexists_f(fid, trim(path), found, e)
      if (found) call h5ldelete_f(fid, trim(path), e)
   end subroutine replace
   subroutine make_real(path, d, chunked, value, ramp)
      character(len=*), intent(in) :: path
      integer(hsize_t), intent(in) :: d(:)
      logical, intent(in) :: chunked
      real(dp), intent(in) :: value
      logical, intent(in), optional :: ramp
      integer(hid_t) :: space, dset, dcpl
      integer(hsize_t), allocatable :: chunk(:)
      real(dp), allocatable, target :: buf(:)
      integer(hsize_t) :: k
      call replace(path)
      call h5screate_simple_f(size(d), d, space, ierr)
      call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, ierr)
      if (chunked) then
         chunk = d
         chunk(size(d)) = 1
         call h5pset_chunk_f(dcpl, size(d), chunk, ierr)
      end if
      call h5dcreate_f(fid, trim(path), H5T_IEEE_F64LE, space, dset, ierr, dcpl)
      if (ierr /= 0) call die('cannot create '//trim(path))
      if (.not. chunked) then
         allocate (buf(product(d)))
         buf = value
         if (present(ramp)) buf = [(real(k - 1, dp), k=1, size(buf, kind=hsize_t))]
         call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, c_loc(buf), ierr)
      end if
      call h5dclose_f(dset, ierr)
      call h5pclose_f(dcpl, ierr)
      call h5sclose_f(space, ierr)
   end subroutine make_real
   subroutine make_int(path, d, value)
      character(len=*), intent(in) :: path
      integer(hsize_t), intent(in) :: d(:)
      integer, intent(in) :: value
      integer(hid_t) :: space, dset
      integer, allocatable, target :: buf(:)
      call replace(path)
      call h5screate_simple_f(size(d), d, space, ierr)
      call h5dcreate_f(fid, trim(path), H5T_STD_I32LE, space, dset, ierr)
      allocate (buf(product(d)))
      buf = value
      call h5dwrite_f(dset, H5T_NATIVE_INTEGER, c_loc(buf), ierr)
      call h5dclose_f(dset, ierr)
      call h5sclose_f(space, ierr)
   end subroutine make_int
   subroutine set_one(path, idx, value)
      character(len=*), intent(in) :: path
      integer, intent(in) :: idx
      real(dp), intent(in) :: value
      integer(hid_t) :: dset, space
      integer :: rank
      integer(hsize_t) :: d(8), md(8)
      real(dp), allocatable, target :: buf(:)
      type(c_ptr) :: p
      call h5dopen_f(fid, trim(path), dset, ierr)
      if (ierr /= 0) call die('no dataset '//trim(path))
      call h5dget_space_f(dset, space, ierr)
      call h5sget_simple_extent_ndims_f(space, rank, ierr)
      call h5sget_simple_extent_dims_f(space, d(1:rank), md(1:rank), ierr)
      allocate (buf(product(d(1:rank))))
      p = c_loc(buf)
      call h5dread_f(dset, H5T_NATIVE_DOUBLE, p, ierr)
      buf(idx) = value
      call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, p, ierr)
      call h5sclose_f(space, ierr)
      call h5dclose_f(dset, ierr)
   end subroutine set_one
   subroutine open_obj(path, obj, name)
      character(len=*), intent(in) :: path, name
      integer(hid_t), intent(out) :: obj
      logical :: found
      integer :: e
      call h5oopen_f(fid, trim(path), obj, ierr)
      if (ierr /= 0) call die('no object '//trim(path))
      call h5aexists_f(obj, trim(name), found, e)
      if (found) call h5adelete_f(obj, trim(name), e)
   end subroutine open_obj
   subroutine attr_int(path, name, n, scalar)
      character(len=*), intent(in) :: path, name
      integer, intent(in) :: n
      logical, intent(in), optional :: scalar
      integer(hid_t) :: obj, space, attr
      integer, allocatable, target :: buf(:)
      integer :: k
      call open_obj(path, obj, name)
      if (present(scalar)) then
         buf = [n]
         call h5screate_f(H5S_SCALAR_F, space, ierr)
      else
         buf = [(k, k=1, n)]
         call h5screate_simple_f(1, [int(n, hsize_t)], space, ierr)
      end if
      call h5acreate_f(obj, trim(name), H5T_STD_I32LE, space, attr, ierr)
      call h5awrite_f(attr, H5T_NATIVE_INTEGER, c_loc(buf), ierr)
      call h5aclose_f(attr, ierr)
      call h5sclose_f(space, ierr)
      call h5oclose_f(obj, ierr)
   end subroutine attr_int
   subroutine attr_real(path, name, value)
      character(len=*), intent(in) :: path, name
      real(dp), intent(in) :: value
      integer(hid_t) :: obj, space, attr
      real(dp), target :: buf
      call open_obj(path, obj, name)
      buf = value
      call h5screate_f(H5S_SCALAR_F, space, ierr)
      call h5acreate_f(obj, trim(name), H5T_IEEE_F64LE, space, attr, ierr)
      call h5awrite_f(attr, H5T_NATIVE_DOUBLE, c_loc(buf), ierr)
      call h5aclose_f(attr, ierr)
      call h5sclose_f(space, ierr)
      call h5oclose_f(obj, ierr)
   end subroutine attr_real
   !> Read the variable-length string attribute, substitute, write it back.
   subroutine attr_sub(path, name, old, new)
      character(len=*), intent(in) :: path, name, old, new
      integer(hid_t) :: obj, space, attr, stype
      type(c_ptr), target :: text
      character(kind=c_char), pointer :: chars(:)
      character(len=:), allocatable, target :: s
      character(len=:), allocatable, target :: z
      type(c_ptr) :: p
      integer :: k, n, at
      call h5oopen_f(fid, trim(path), obj, ierr)
      if (ierr /= 0) call die('no object '//trim(path))
      call h5tcopy_f(H5T_STRING, stype, ierr)
      call h5tset_cset_f(stype, H5T_CSET_UTF8_F, ierr)
      call h5aopen_f(obj, trim(name), attr, ierr)
      if (ierr /= 0) call die('no attribute '//trim(name))
      p = c_loc(text)
      call h5aread_f(attr, stype, p, ierr)
      call h5aclose_f(attr, ierr)
      n = 0
      call c_f_pointer(text, chars, [1000000])
      do while (chars(n + 1) /= c_null_char)
         n = n + 1
      end do
      allocate (character(len=n) :: s)
      do k = 1, n
         s(k:k) = chars(k)
      end do
      at = index(s, trim(old))
      if (at == 0) call die('text not found: '//trim(old))
      s = s(1:at - 1)//trim(new)//s(at + len_trim(old):)
      z = s//c_null_char
      text = c_loc(z)
      call h5adelete_f(obj, trim(name), ierr)
      call h5screate_f(H5S_SCALAR_F, space, ierr)
      call h5acreate_f(obj, trim(name), stype, space, attr, ierr)
      p = c_loc(text)
      call h5awrite_f(attr, stype, p, ierr)
      call h5aclose_f(attr, ierr)
      call h5sclose_f(space, ierr)
      call h5oclose_f(obj, ierr)
   end subroutine attr_sub
end program h5craft
