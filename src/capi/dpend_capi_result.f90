!> The results of the C interface (dpend.h): a run's file as named arrays and as an
!> HDF5 file image.
!>
!> A run records its file (`record_outputs`, src/io/dpend_output_record.f90): its
!> items are the file's datasets and attributes in the order written, each with its
!> path, name, type, shape and bytes, handed to the caller without HDF5
!> (`dpend_result_item*`: the address, or a copy into the caller's buffer). The
!> file's image is made from the record the first time it is asked for
!> (`dpend_result_bytes`, `_data`, `_copy`), by replaying the writes into a file in
!> memory: the file the command writes. A sweep writes its file on disk (its
!> working file) and its result holds that file's image only (no items).
module dpend_capi_result
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_ptr, c_null_ptr, c_null_char, &
      c_associated, c_f_pointer, c_loc, c_size_t, c_long_long
   use dpend_error, only: error_t
   use dpend_os, only: capture_outputs, take_capture
   use dpend_output_record, only: record_t, record_outputs
   use dpend_hdf5, only: h5file_t
   implicit none
   private
   public :: result_t, new_result, library_lock, library_unlock, c_free, c_memcpy, c_string
   public :: dpend_result_bytes, dpend_result_copy, dpend_result_data, dpend_result_free
   public :: dpend_result_items, dpend_result_item, dpend_result_item_bytes, &
      dpend_result_item_data, dpend_result_item_copy, dpend_result_find

   !> The most dimensions an item's shape is given with (dpend's datasets have 3).
   integer, parameter :: max_rank = 8

   integer(c_int), parameter :: kind_ok = 0, kind_refused = 2

   !> A run's result: the record of the file the command wrote, and its image once
   !> made (C memory, freed by `dpend_result_free`); a sweep's: the image only.
   type :: result_t
      type(record_t), allocatable :: record
      type(c_ptr) :: image = c_null_ptr
      integer(c_size_t) :: bytes = 0
   end type result_t

   interface
      !> One library call at a time (dpend_posix.c: the command code keeps string
      !> lengths in static storage, gfortran 12; HDF5 is built without threads)
      subroutine library_lock() bind(C, name='dpend_library_lock')
      end subroutine library_lock
      subroutine library_unlock() bind(C, name='dpend_library_unlock')
      end subroutine library_unlock
      subroutine c_free(p) bind(C, name='free')
         import :: c_ptr
         type(c_ptr), value :: p
      end subroutine c_free
      type(c_ptr) function c_memcpy(dst, src, n) bind(C, name='memcpy')
         import :: c_ptr, c_size_t
         type(c_ptr), value :: dst, src
         integer(c_size_t), value :: n
      end function c_memcpy
   end interface

contains

   !> The handle of a result holding `record` (moved) or the `image` of `bytes` bytes
   !> (taken over); c_null_ptr when there is neither.
   function new_result(record, image, bytes) result(handle)
      type(record_t), allocatable, intent(inout) :: record
      type(c_ptr), intent(in) :: image
      integer(c_size_t), intent(in) :: bytes
      type(c_ptr) :: handle
      type(result_t), pointer :: res
      handle = c_null_ptr
      if (.not. allocated(record) .and. .not. c_associated(image)) return
      allocate (res)
      if (allocated(record)) call move_alloc(record, res%record)
      res%image = image
      res%bytes = bytes
      handle = c_loc(res)
   end function new_result

   !> The result of a handle, its image made if it has none yet (null: no handle, or
   !> the image could not be made).
   function with_image(handle) result(res)
      type(c_ptr), intent(in) :: handle
      type(result_t), pointer :: res
      type(h5file_t) :: h5
      type(error_t), allocatable :: error
      res => null()
      if (.not. c_associated(handle)) return
      call c_f_pointer(handle, res)
      if (c_associated(res%image) .or. .not. allocated(res%record)) return
      call library_lock()   ! HDF5 and the capture: one library call at a time
      call record_outputs(.false.)
      call capture_outputs(.true.)
      call h5%open('result.h5', 'w', error)
      if (.not. allocated(error)) call h5%replay(res%record, error)
      call h5%close()
      res%image = take_capture(res%bytes)
      call capture_outputs(.false.)
      call library_unlock()
      if (allocated(error) .and. c_associated(res%image)) then
         call c_free(res%image)
         res%image = c_null_ptr
         res%bytes = 0
      end if
   end function with_image

   !> Bytes of the result's file image (0 for a null handle, or when it cannot be made).
   integer(c_long_long) function dpend_result_bytes(result) bind(C, name='dpend_result_bytes')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      type(result_t), pointer :: res
      dpend_result_bytes = 0
      res => with_image(result)
      if (associated(res)) dpend_result_bytes = int(res%bytes, c_long_long)
   end function dpend_result_bytes

   !> Copy the image into `buf` of n bytes; 0 on success, 2 when n is too small or a
   !> pointer is null.
   integer(c_int) function dpend_result_copy(result, buf, n) bind(C, name='dpend_result_copy')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      type(c_ptr), value :: buf     !! the destination
      integer(c_long_long), value :: n  !! its size [B]
      type(result_t), pointer :: res
      type(c_ptr) :: dst
      dpend_result_copy = kind_refused
      if (.not. c_associated(buf)) return
      res => with_image(result)
      if (.not. associated(res)) return
      if (n < int(res%bytes, c_long_long)) return
      if (res%bytes > 0) dst = c_memcpy(buf, res%image, res%bytes)
      dpend_result_copy = kind_ok
   end function dpend_result_copy

   !> The address of the result's image (dpend_result_bytes bytes, valid until
   !> `dpend_result_free`); NULL for a null handle.
   type(c_ptr) function dpend_result_data(result) bind(C, name='dpend_result_data')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      type(result_t), pointer :: res
      dpend_result_data = c_null_ptr
      res => with_image(result)
      if (associated(res)) dpend_result_data = res%image
   end function dpend_result_data

   !> Release a result (a null handle is ignored).
   subroutine dpend_result_free(result) bind(C, name='dpend_result_free')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      type(result_t), pointer :: res
      if (.not. c_associated(result)) return
      call c_f_pointer(result, res)
      call c_free(res%image)
      deallocate (res)
   end subroutine dpend_result_free

   !> The number of items (datasets and attributes) of a result; 0 for a null handle
   !> or a sweep's (its image only).
   integer(c_int) function dpend_result_items(result) bind(C, name='dpend_result_items')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      type(result_t), pointer :: res
      dpend_result_items = 0
      if (.not. c_associated(result)) return
      call c_f_pointer(result, res)
      if (allocated(res%record)) dpend_result_items = int(res%record%n, c_int)
   end function dpend_result_items

   !> Item `i` (from 0) of a result: its path and name ('' a dataset), type (1 real,
   !> 2 signed integer, 3 fixed-length string, 4 text), bytes per element (text: in
   !> all), rank and shape (C order, as the file and h5py give it; at most 8). 0, or 2
   !> for no such item, a null pointer or a name that does not fit with its NUL.
   integer(c_int) function dpend_result_item(result, i, path, path_len, name, name_len, &
                                             type, itemsize, rank, dims) &
      bind(C, name='dpend_result_item')
      type(c_ptr), value :: result               !! the handle of `dpend_run`
      integer(c_int), value :: i                 !! the item, from 0
      type(c_ptr), value :: path, name           !! char * buffers
      integer(c_int), value :: path_len, name_len  !! their sizes [B]
      integer(c_int), intent(out) :: type, rank
      integer(c_long_long), intent(out) :: itemsize
      integer(c_long_long), intent(out) :: dims(max_rank)
      type(result_t), pointer :: res
      integer :: r
      dpend_result_item = kind_refused
      type = 0
      rank = 0
      itemsize = 0
      dims = 0
      res => item_owner(result, i)
      if (.not. associated(res)) return
      associate (item => res%record%items(i + 1))
         r = size(item%dims)
         if (r > max_rank .or. len(item%path) >= path_len .or. &
             len(item%name) >= name_len) return
         if (.not. put(item%path, path, path_len) .or. .not. put(item%name, name, name_len)) &
            return
         type = int(item%type, c_int)
         itemsize = int(item%itemsize, c_long_long)
         rank = int(r, c_int)
         dims(1:r) = int(item%dims(r:1:-1), c_long_long)
      end associate
      dpend_result_item = kind_ok
   end function dpend_result_item

   !> Bytes of item `i`'s values (0 for no such item).
   integer(c_long_long) function dpend_result_item_bytes(result, i) &
      bind(C, name='dpend_result_item_bytes')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      integer(c_int), value :: i    !! the item, from 0
      type(result_t), pointer :: res
      dpend_result_item_bytes = 0
      res => item_owner(result, i)
      if (associated(res)) dpend_result_item_bytes = size(res%record%items(i + 1)%bytes, &
                                                          kind=c_long_long)
   end function dpend_result_item_bytes

   !> The address of item `i`'s values (C order; valid until `dpend_result_free`);
   !> NULL for no such item or no values.
   type(c_ptr) function dpend_result_item_data(result, i) bind(C, name='dpend_result_item_data')
      type(c_ptr), value :: result  !! the handle of `dpend_run`
      integer(c_int), value :: i    !! the item, from 0
      type(result_t), pointer :: res
      dpend_result_item_data = c_null_ptr
      res => item_owner(result, i)
      if (.not. associated(res)) return
      if (size(res%record%items(i + 1)%bytes) > 0) &
         dpend_result_item_data = c_loc(res%record%items(i + 1)%bytes)
   end function dpend_result_item_data

   !> Copy item `i`'s values into `buf` of n bytes: 0, or 2 for no such item, a null
   !> buffer or n too small.
   integer(c_int) function dpend_result_item_copy(result, i, buf, n) &
      bind(C, name='dpend_result_item_copy')
      type(c_ptr), value :: result      !! the handle of `dpend_run`
      integer(c_int), value :: i        !! the item, from 0
      type(c_ptr), value :: buf         !! the destination
      integer(c_long_long), value :: n  !! its size [B]
      type(result_t), pointer :: res
      type(c_ptr) :: dst
      integer(c_size_t) :: bytes
      dpend_result_item_copy = kind_refused
      res => item_owner(result, i)
      if (.not. associated(res) .or. .not. c_associated(buf)) return
      bytes = size(res%record%items(i + 1)%bytes, kind=c_size_t)
      if (n < int(bytes, c_long_long)) return
      if (bytes > 0) dst = c_memcpy(buf, c_loc(res%record%items(i + 1)%bytes), bytes)
      dpend_result_item_copy = kind_ok
   end function dpend_result_item_copy

   !> The index (from 0) of the item `path`, `name` ('' or NULL: the dataset); -1 if
   !> there is none.
   integer(c_int) function dpend_result_find(result, path, name) bind(C, name='dpend_result_find')
      type(c_ptr), value :: result       !! the handle of `dpend_run`
      type(c_ptr), value :: path, name   !! const char *
      type(result_t), pointer :: res
      dpend_result_find = -1
      if (.not. c_associated(result) .or. .not. c_associated(path)) return
      call c_f_pointer(result, res)
      if (.not. allocated(res%record)) return
      dpend_result_find = int(res%record%find(c_string(path), c_string(name)), c_int) - 1
   end function dpend_result_find

   !> The result of `handle` when it has an item `i` (from 0), else null.
   function item_owner(handle, i) result(res)
      type(c_ptr), intent(in) :: handle
      integer(c_int), intent(in) :: i
      type(result_t), pointer :: res
      res => null()
      if (.not. c_associated(handle) .or. i < 0) return
      call c_f_pointer(handle, res)
      if (.not. allocated(res%record)) then
         res => null()
      else if (i >= res%record%n) then
         res => null()
      end if
   end function item_owner

   !> `text` into the C buffer `p` of n bytes with its NUL; false when it does not fit.
   logical function put(text, p, n)
      character(len=*), intent(in) :: text
      type(c_ptr), intent(in) :: p
      integer(c_int), intent(in) :: n
      character(kind=c_char), pointer :: chars(:)
      integer :: k
      put = c_associated(p) .and. len(text) < n
      if (.not. put) return
      call c_f_pointer(p, chars, [n])
      do k = 1, len(text)
         chars(k) = text(k:k)
      end do
      chars(len(text) + 1) = c_null_char
   end function put

   !> The text of a NUL-terminated C string ('' for NULL).
   function c_string(p) result(s)
      type(c_ptr), intent(in) :: p
      character(len=:), allocatable :: s
      character(kind=c_char), pointer :: chars(:)
      integer :: n, k
      if (.not. c_associated(p)) then
         s = ''
         return
      end if
      call c_f_pointer(p, chars, [huge(1)])
      n = 0
      do while (chars(n + 1) /= c_null_char)
         n = n + 1
      end do
      allocate (character(len=n) :: s)
      do k = 1, n
         s(k:k) = chars(k)
      end do
   end function c_string
end module dpend_capi_result
