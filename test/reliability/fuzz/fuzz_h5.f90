!> The HDF5 mutator of the fuzzing stage (test/reliability/fuzz/fuzz.sh): copies a
!> valid dpend file and applies one structural change to the copy, so that the
!> readers of `export`, `animate` and `sweep-compare` meet files from elsewhere.
!>
!>     dpend-fuzz-h5 IN OUT OP ARGS...
!>
!> OP (dataset shapes DIMS are comma-separated, in h5py order, "" for a scalar):
!>   delete PATH                     remove a link (dataset or group)
!>   delete-attr OBJ NAME            remove an attribute
!>   attr-int OBJ NAME DIMS V        replace (or add) an attribute: int32 filled with V
!>   attr-real OBJ NAME DIMS V       ... float64 filled with V (nan, inf, -inf allowed)
!>   attr-str OBJ NAME TEXT          ... a fixed-length string
!>   fill PATH V                     every element of a numeric dataset set to V
!>   poke PATH K V                   element K (flat, modulo the size) set to V
!>   replace PATH TYPE DIMS V        the dataset replaced by one of TYPE (f64 f32 i32
!>                                   str) and shape DIMS, contiguous, filled with V
!>   chunked PATH DIMS               the dataset replaced by a chunked float64 one of
!>                                   shape DIMS (may be huge: no data is written)
!>   group PATH                      the object replaced by an empty group
!>   softlink PATH TARGET            the object replaced by a soft link to TARGET
!>
!> Exit status 0 done, 3 the operation failed (a bug of the fuzzer's plan).
!> A test tool, not part of dpend: it talks to the HDF5 Fortran API directly.
program fuzz_h5
   use, intrinsic :: iso_c_binding, only: c_loc, c_ptr
   use, intrinsic :: ieee_exceptions, only: ieee_all, ieee_set_halting_mode
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use, intrinsic :: iso_fortran_env, only: error_unit, int64, real64
   use hdf5
   implicit none
   character(len=:), allocatable :: args(:)
   integer :: nargs, i, err
   integer(hid_t) :: file

   ! HDF5 converts NaN or Inf into an integer dataset by its own rules: no trap
   ! (the debug profile halts on invalid, zero and overflow)
   call ieee_set_halting_mode(ieee_all, .false.)
   nargs = command_argument_count()
   if (nargs < 4) call die('usage: dpend-fuzz-h5 IN OUT OP ARGS...')
   allocate (character(len=4096) :: args(nargs))
   do i = 1, nargs
      call get_command_argument(i, args(i))
   end do
   call copy_file(trim(args(1)), trim(args(2)))
   call h5open_f(err)
   call check(err, 'h5open')
   call h5eset_auto_f(0, err)
   call h5fopen_f(trim(args(2)), H5F_ACC_RDWR_F, file, err)
   call check(err, 'open '//trim(args(2)))
   select case (trim(args(3)))
   case ('delete')
      call need(4)
      call h5ldelete_f(file, trim(args(4)), err)
      call check(err, 'delete')
   case ('delete-attr')
      call need(5)
      call h5adelete_by_name_f(file, trim(args(4)), trim(args(5)), err)
      call check(err, 'delete-attr')
   case ('attr-int', 'attr-real')
      call need(7)
      call put_attr(file, trim(args(4)), trim(args(5)), trim(args(3)), trim(args(6)), &
                    to_real(args(7)), '')
   case ('attr-str')
      call need(6)
      call put_attr(file, trim(args(4)), trim(args(5)), 'attr-str', '', 0.0_real64, &
                    trim(args(6)))
   case ('fill', 'poke')
      call need(5)
      if (trim(args(3)) == 'fill') then
         call change_values(file, trim(args(4)), 0_int64, to_real(args(5)), .true.)
      else
         call need(6)
         call change_values(file, trim(args(4)), to_int(args(5)), to_real(args(6)), .false.)
      end if
   case ('replace')
      call need(7)
      call h5ldelete_f(file, trim(args(4)), err)
      call check(err, 'replace: delete')
      call new_dataset(file, trim(args(4)), trim(args(5)), trim(args(6)), &
                       to_real(args(7)), .false.)
   case ('chunked')
      call need(5)
      call h5ldelete_f(file, trim(args(4)), err)
      call check(err, 'chunked: delete')
      call new_dataset(file, trim(args(4)), 'f64', trim(args(5)), 0.0_real64, .true.)
   case ('group')
      call need(4)
      call replace_by_group(file, trim(args(4)))
   case ('softlink')
      call need(5)
      call h5ldelete_f(file, trim(args(4)), err)
      call check(err, 'softlink: delete')
      call h5lcreate_soft_f(trim(args(5)), file, trim(args(4)), err)
      call check(err, 'softlink')
   case default
      call die('unknown operation '//trim(args(3)))
   end select
   call h5fclose_f(file, err)
   call check(err, 'close')
   call h5close_f(err)

contains

   !> Stops with status 3 and MESSAGE.
   subroutine die(message)
      character(len=*), intent(in) :: message  !! what failed
      write (error_unit, '(a)') 'dpend-fuzz-h5: '//message
      error stop 3
   end subroutine die

   !> Stops when an HDF5 call failed.
   subroutine check(status, what)
      integer, intent(in) :: status            !! HDF5 status
      character(len=*), intent(in) :: what     !! the step
      if (status < 0) call die(what//' failed')
   end subroutine check

   !> Stops unless the operation has at least N arguments in all.
   subroutine need(n)
      integer, intent(in) :: n                 !! arguments needed
      if (nargs < n) call die('too few arguments for '//trim(args(3)))
   end subroutine need

   !> The value of a real argument (nan, inf, -inf as Fortran reads them).
   real(real64) function to_real(text) result(v)
      character(len=*), intent(in) :: text     !! the argument
      integer :: ios
      read (text, *, iostat=ios) v
      if (ios /= 0) call die('not a number: '//trim(text))
   end function to_real

   !> The value of an integer argument.
   integer(int64) function to_int(text) result(k)
      character(len=*), intent(in) :: text     !! the argument
      integer :: ios
      read (text, *, iostat=ios) k
      if (ios /= 0) call die('not an integer: '//trim(text))
   end function to_int

   !> Byte copy of IN to OUT.
   subroutine copy_file(from, to)
      character(len=*), intent(in) :: from     !! source path
      character(len=*), intent(in) :: to       !! destination path (replaced)
      integer :: u, n, ios
      character(len=:), allocatable :: bytes
      open (newunit=u, file=from, access='stream', form='unformatted', status='old', &
            action='read', iostat=ios)
      if (ios /= 0) call die('cannot open '//from)
      inquire (unit=u, size=n)
      allocate (character(len=n) :: bytes)
      read (u, iostat=ios) bytes
      if (ios /= 0) call die('cannot read '//from)
      close (u)
      open (newunit=u, file=to, access='stream', form='unformatted', status='replace', &
            action='write', iostat=ios)
      if (ios /= 0) call die('cannot create '//to)
      write (u) bytes
      close (u)
   end subroutine copy_file

   !> Shape DIMS (h5py order, comma-separated) in HDF5's Fortran order; rank 0: scalar.
   subroutine parse_dims(text, dims, rank)
      character(len=*), intent(in) :: text                !! e.g. "101,2"
      integer(hsize_t), intent(out) :: dims(7)            !! Fortran order
      integer, intent(out) :: rank                        !! 0 for a scalar
      integer :: p, q, ios
      integer(hsize_t) :: h5py(7)
      rank = 0
      p = 1
      do while (p <= len(text))
         q = index(text(p:), ',')
         if (q == 0) then
            q = len(text) + 1
         else
            q = p + q - 1
         end if
         rank = rank + 1
         if (rank > 7) call die('rank over 7: '//text)
         read (text(p:q - 1), *, iostat=ios) h5py(rank)
         if (ios /= 0) call die('bad dims: '//text)
         p = q + 1
      end do
      dims(1:rank) = h5py(rank:1:-1)
   end subroutine parse_dims

   !> Dataspace of shape DIMS (scalar for rank 0).
   integer(hid_t) function new_space(dims, rank, maxdims) result(space)
      integer(hsize_t), intent(in) :: dims(7)             !! Fortran order
      integer, intent(in) :: rank                         !! rank
      integer(hsize_t), intent(in), optional :: maxdims(7) !! largest extent
      integer :: e
      if (rank == 0) then
         call h5screate_f(H5S_SCALAR_F, space, e)
      else if (present(maxdims)) then
         call h5screate_simple_f(rank, dims(1:rank), space, e, maxdims(1:rank))
      else
         call h5screate_simple_f(rank, dims(1:rank), space, e)
      end if
      call check(e, 'dataspace')
   end function new_space

   !> Replaces (or adds) the attribute NAME of OBJ: int32 or float64 of shape DIMS
   !> filled with V, or the string TEXT.
   subroutine put_attr(loc, obj, name, kind, dims_text, v, text)
      integer(hid_t), intent(in) :: loc        !! the file
      character(len=*), intent(in) :: obj      !! object path
      character(len=*), intent(in) :: name     !! attribute name
      character(len=*), intent(in) :: kind     !! attr-int, attr-real or attr-str
      character(len=*), intent(in) :: dims_text !! shape (numeric kinds)
      real(real64), intent(in) :: v            !! value (numeric kinds)
      character(len=*), intent(in) :: text     !! value (attr-str)
      integer(hid_t) :: o, space, attr, stype
      integer(hsize_t) :: dims(7)
      integer :: rank, e, n
      logical :: exists
      real(real64), allocatable, target :: rbuf(:)
      integer, allocatable, target :: ibuf(:)
      character(len=max(1, len(text))), target :: sbuf
      call h5oopen_f(loc, obj, o, e)
      call check(e, 'open '//obj)
      call h5aexists_f(o, name, exists, e)
      call check(e, 'attribute exists')
      if (exists) then
         call h5adelete_f(o, name, e)
         call check(e, 'attribute delete')
      end if
      select case (kind)
      case ('attr-str')
         sbuf = text
         space = new_space(dims, 0)
         call h5tcopy_f(H5T_FORTRAN_S1, stype, e)
         call h5tset_size_f(stype, int(len(sbuf), size_t), e)
         call h5acreate_f(o, name, stype, space, attr, e)
         call check(e, 'attribute create')
         call h5awrite_f(attr, stype, c_loc(sbuf), e)
         call h5tclose_f(stype, e)
      case default
         call parse_dims(dims_text, dims, rank)
         n = int(product(dims(1:rank)))
         space = new_space(dims, rank)
         if (kind == 'attr-int') then
            allocate (ibuf(max(1, n)))
            ibuf = clamp_int(v)
            call h5acreate_f(o, name, H5T_NATIVE_INTEGER, space, attr, e)
            call check(e, 'attribute create')
            call h5awrite_f(attr, H5T_NATIVE_INTEGER, c_loc(ibuf), e)
         else
            allocate (rbuf(max(1, n)))
            rbuf = v
            call h5acreate_f(o, name, H5T_NATIVE_DOUBLE, space, attr, e)
            call check(e, 'attribute create')
            call h5awrite_f(attr, H5T_NATIVE_DOUBLE, c_loc(rbuf), e)
         end if
      end select
      call check(e, 'attribute write')
      call h5aclose_f(attr, e)
      call h5sclose_f(space, e)
      call h5oclose_f(o, e)
   end subroutine put_attr

   !> V as an int32 (NaN: 0; clamped to the int32 range).
   elemental integer function clamp_int(v)
      real(real64), intent(in) :: v            !! value
      if (ieee_is_nan(v)) then
         clamp_int = 0
      else
         clamp_int = int(max(-2147483648.0_real64, min(2147483647.0_real64, v)))
      end if
   end function clamp_int

   !> ALL: every element of PATH set to V; else element K (modulo the size).
   subroutine change_values(loc, path, k, v, all)
      integer(hid_t), intent(in) :: loc        !! the file
      character(len=*), intent(in) :: path     !! dataset path
      integer(int64), intent(in) :: k          !! flat element index (poke)
      real(real64), intent(in) :: v            !! the value
      logical, intent(in) :: all               !! fill every element
      integer(hid_t) :: dset, space
      integer(hssize_t) :: n
      integer :: e
      real(real64), allocatable, target :: buf(:)
      integer, allocatable, target :: ibuf(:)
      integer(hid_t) :: dtype
      integer :: tclass
      type(c_ptr) :: p
      call h5dopen_f(loc, path, dset, e)
      call check(e, 'open '//path)
      call h5dget_space_f(dset, space, e)
      call h5sget_simple_extent_npoints_f(space, n, e)
      call check(e, 'extent')
      if (n < 1 .or. n > 10000000) call die('size out of range: '//path)
      allocate (buf(n))
      p = c_loc(buf)
      call h5dread_f(dset, H5T_NATIVE_DOUBLE, p, e)
      call check(e, 'read '//path)
      if (all) then
         buf = v
      else
         buf(modulo(k, int(n, int64)) + 1) = v
      end if
      call h5dget_type_f(dset, dtype, e)
      call h5tget_class_f(dtype, tclass, e)
      call h5tclose_f(dtype, e)
      if (tclass == H5T_INTEGER_F) then  ! converted here: NaN -> 0, clamped
         ibuf = clamp_int(buf)
         call h5dwrite_f(dset, H5T_NATIVE_INTEGER, c_loc(ibuf), e)
      else
         call h5dwrite_f(dset, H5T_NATIVE_DOUBLE, c_loc(buf), e)
      end if
      call check(e, 'write '//path)
      call h5sclose_f(space, e)
      call h5dclose_f(dset, e)
   end subroutine change_values

   !> A new dataset PATH of TYPE and shape DIMS_TEXT filled with V, or (chunked) a
   !> chunked float64 one with no data written.
   subroutine new_dataset(loc, path, type, dims_text, v, chunked)
      integer(hid_t), intent(in) :: loc        !! the file
      character(len=*), intent(in) :: path     !! dataset path
      character(len=*), intent(in) :: type     !! f64, f32, i32 or str
      character(len=*), intent(in) :: dims_text !! shape, h5py order
      real(real64), intent(in) :: v            !! value
      logical, intent(in) :: chunked           !! chunked, nothing written
      integer(hid_t) :: space, dset, ftype, mtype, dcpl
      integer(hsize_t) :: dims(7), chunk(7)
      integer :: rank, e, n
      real(real64), allocatable, target :: rbuf(:)
      integer, allocatable, target :: ibuf(:)
      character(len=8), allocatable, target :: sbuf(:)
      call parse_dims(dims_text, dims, rank)
      if (chunked) then
         if (rank == 0) call die('chunked needs a rank')
         space = new_space(dims, rank, dims)
         chunk(1:rank) = max(1_hsize_t, min(dims(1:rank), 64_hsize_t))
         call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, e)
         call h5pset_chunk_f(dcpl, rank, chunk(1:rank), e)
         call check(e, 'chunk')
         call h5dcreate_f(loc, path, H5T_NATIVE_DOUBLE, space, dset, e, dcpl_id=dcpl)
         call check(e, 'create '//path)
         call h5pclose_f(dcpl, e)
      else
         if (product(dims(1:rank)) > 20000000_hsize_t) call die('too large to write')
         n = max(1, int(product(dims(1:rank))))
         space = new_space(dims, rank)
         select case (type)
         case ('f64', 'f32')
            ftype = merge(H5T_NATIVE_DOUBLE, H5T_NATIVE_REAL, type == 'f64')
            mtype = H5T_NATIVE_DOUBLE
            allocate (rbuf(n))
            rbuf = v
         case ('i32')
            ftype = H5T_NATIVE_INTEGER
            mtype = H5T_NATIVE_INTEGER
            allocate (ibuf(n))
            ibuf = clamp_int(v)
         case ('str')
            call h5tcopy_f(H5T_FORTRAN_S1, ftype, e)
            call h5tset_size_f(ftype, 8_size_t, e)
            mtype = ftype
            allocate (sbuf(n))
            sbuf = 'fuzz'
         case default
            call die('unknown type '//type)
         end select
         call h5dcreate_f(loc, path, ftype, space, dset, e)
         call check(e, 'create '//path)
         select case (type)
         case ('f64', 'f32')
            call h5dwrite_f(dset, mtype, c_loc(rbuf), e)
         case ('i32')
            call h5dwrite_f(dset, mtype, c_loc(ibuf), e)
         case default
            call h5dwrite_f(dset, mtype, c_loc(sbuf), e)
         end select
         call check(e, 'write '//path)
      end if
      call h5dclose_f(dset, e)
      call h5sclose_f(space, e)
   end subroutine new_dataset

   !> The object PATH replaced by an empty group.
   subroutine replace_by_group(loc, path)
      integer(hid_t), intent(in) :: loc        !! the file
      character(len=*), intent(in) :: path     !! object path
      integer(hid_t) :: g
      integer :: e
      call h5ldelete_f(loc, path, e)
      call check(e, 'group: delete')
      call h5gcreate_f(loc, path, g, e)
      call check(e, 'group create')
      call h5gclose_f(g, e)
   end subroutine replace_by_group

end program fuzz_h5
