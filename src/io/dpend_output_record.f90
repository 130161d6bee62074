!> An output file recorded in memory instead of written: the whole datasets and the
!> attributes of an `h5file_t` in the order they were written, each with its path,
!> type, shape and bytes (a library call's result, src/capi: its arrays are handed
!> to the caller without HDF5, and the file is made from the record only when asked
!> for, by replaying the writes: `h5file_t%replay`).
!>
!> While `record_outputs(.true.)` is in force, a file that `capture_outputs` would
!> write in memory is recorded instead, and the record of the last one closed is
!> kept for `take_record`. Library calls run one at a time (src/capi's lock), so the
!> switch and the kept record are the process's, not a thread's.
module dpend_output_record
   use, intrinsic :: iso_c_binding, only: c_ptr, c_f_pointer, c_associated
   use, intrinsic :: iso_fortran_env, only: int8, int64
   implicit none
   private
   public :: record_t, record_item_t, record_outputs, recording_outputs, keep_record, &
      take_record
   public :: item_real, item_integer, item_string, item_text

   !> The types of an item: IEEE binary floating point, signed little-endian integer,
   !> fixed-length string (NUL-padded), variable-length UTF-8 text (a scalar).
   integer, parameter :: item_real = 1, item_integer = 2, item_string = 3, item_text = 4

   !> One dataset (`name` '') or one attribute `name` of the object `path`.
   type :: record_item_t
      character(len=:), allocatable :: path       !! the dataset, or the attribute's object
      character(len=:), allocatable :: name       !! '' for a dataset, else the attribute
      integer :: type = 0                         !! item_real .. item_text
      integer(int64) :: itemsize = 0              !! bytes of one element (text: all)
      integer(int64), allocatable :: dims(:)      !! shape, Fortran order; () a scalar
      integer(int8), allocatable :: bytes(:)      !! the values, Fortran order
   end type record_item_t

   !> The items written, in order (a rewritten item keeps its place).
   type :: record_t
      type(record_item_t), allocatable :: items(:)
      integer :: n = 0                            !! items in use
   contains
      procedure :: add => record_add
      procedure :: find => record_find
      procedure :: has_object => record_has_object
   end type record_t

   logical, save :: recording = .false.
   type(record_t), allocatable, save :: kept

contains

   !> Record the captured outputs from now on (or stop); a kept record is dropped.
   subroutine record_outputs(on)
      logical, intent(in) :: on  !! record from now on, or stop
      recording = on
      if (allocated(kept)) deallocate (kept)
   end subroutine record_outputs

   !> Whether outputs are recorded (`record_outputs`).
   logical function recording_outputs()
      recording_outputs = recording
   end function recording_outputs

   !> Keep `record` (moved) as the last one closed, for `take_record`.
   subroutine keep_record(record)
      type(record_t), allocatable, intent(inout) :: record  !! the closed file's record
      if (allocated(kept)) deallocate (kept)
      call move_alloc(record, kept)
   end subroutine keep_record

   !> The record of the last recorded file closed, handed over (unallocated: none).
   subroutine take_record(record)
      type(record_t), allocatable, intent(out) :: record  !! the record, if any
      if (allocated(kept)) call move_alloc(kept, record)
   end subroutine take_record

   !> Add the item (`name` '' a dataset) whose `nbytes` bytes are at `buf`; an item
   !> of the same path and name is replaced where it stands.
   subroutine record_add(self, path, name, type, itemsize, dims, buf, nbytes)
      class(record_t), intent(inout) :: self   !! the record
      character(len=*), intent(in) :: path     !! the dataset or the attribute's object
      character(len=*), intent(in) :: name     !! '' or the attribute's name
      integer, intent(in) :: type              !! item_real .. item_text
      integer(int64), intent(in) :: itemsize   !! bytes of one element
      integer(int64), intent(in) :: dims(:)    !! shape, Fortran order
      type(c_ptr), intent(in) :: buf           !! the values
      integer(int64), intent(in) :: nbytes     !! their size [B]
      type(record_item_t), allocatable :: grown(:)
      integer(int8), pointer :: src(:)
      integer :: k
      k = self%find(path, name)
      if (k == 0) then   ! new
         if (.not. allocated(self%items)) allocate (self%items(64))
         if (self%n == size(self%items)) then
            allocate (grown(2*size(self%items)))
            grown(:self%n) = self%items(:self%n)
            call move_alloc(grown, self%items)
         end if
         self%n = self%n + 1
         k = self%n
      end if
      associate (item => self%items(k))
         item%path = trim(path)
         item%name = name
         item%type = type
         item%itemsize = itemsize
         item%dims = dims
         allocate (item%bytes(nbytes))
         if (nbytes > 0 .and. c_associated(buf)) then
            call c_f_pointer(buf, src, [nbytes])
            item%bytes = src
         end if
      end associate
   end subroutine record_add

   !> The index of the item `path`, `name` ('' a dataset), 0 if there is none.
   integer function record_find(self, path, name) result(k)
      class(record_t), intent(in) :: self  !! the record
      character(len=*), intent(in) :: path, name
      do k = self%n, 1, -1
         if (self%items(k)%path == path .and. self%items(k)%name == name) then
            if (len(self%items(k)%path) == len_trim(path) .and. &
                len(self%items(k)%name) == len(name)) return
         end if
      end do
      k = 0
   end function record_find

   !> Whether the file would hold the object `path`: the root, a dataset written, or
   !> a group above one (HDF5 makes the groups of a dataset's path).
   logical function record_has_object(self, path) result(found)
      class(record_t), intent(in) :: self  !! the record
      character(len=*), intent(in) :: path !! e.g. '/', '/trajectory', '/trajectory/t'
      character(len=:), allocatable :: p
      integer :: k
      p = trim(path)
      found = p == '/' .or. len(p) == 0
      if (found) return
      if (p(len(p):) == '/') p = p(:len(p) - 1)
      do k = 1, self%n
         if (len(self%items(k)%name) > 0) cycle
         associate (d => self%items(k)%path)
            if (d == p .and. len(d) == len(p)) found = .true.
            if (len(d) > len(p)) found = found .or. (d(:len(p) + 1) == p//'/')
         end associate
         if (found) return
      end do
   end function record_has_object
end module dpend_output_record
