!> The readers of dpend_hdf5: `read`, `read_slab` and `readattr` of an `h5file_t`,
!> and `open_read`, which checks what a dataset or attribute holds and its size
!> before anything is read. The interfaces, with the arguments' documentation, are
!> in dpend_hdf5.
!>
!> The array readers include one body each, dpend_hdf5_read.inc (a whole dataset)
!> or dpend_hdf5_slabread.inc (a block): the element type and rank come from the
!> declaration of `value` (`element`).
submodule (dpend_hdf5) dpend_hdf5_read
   implicit none

   !> The element type of a reader's array (dpend_hdf5_read.inc, ..._slabread.inc).
   interface element
      module procedure element_real, element_int, element_i64
   end interface element

contains

   module procedure read_real_rank0
      call read_one(self, path, want_real, real_type(), c_loc(value), error)
   end procedure read_real_rank0

   module procedure read_real_rank1
      include 'dpend_hdf5_read.inc'
   end procedure read_real_rank1

   module procedure read_real_rank2
      include 'dpend_hdf5_read.inc'
   end procedure read_real_rank2

   module procedure read_real_rank3
      include 'dpend_hdf5_read.inc'
   end procedure read_real_rank3

   module procedure read_int_rank0
      call read_one(self, path, want_int, int_type(), c_loc(value), error)
   end procedure read_int_rank0

   module procedure read_int_rank1
      include 'dpend_hdf5_read.inc'
   end procedure read_int_rank1

   module procedure read_int_rank2
      include 'dpend_hdf5_read.inc'
   end procedure read_int_rank2

   module procedure read_i64_rank1
      include 'dpend_hdf5_read.inc'
   end procedure read_i64_rank1

   module procedure read_str
      call read_string(self, path, value, error)
   end procedure read_str

   module procedure slabread_real_rank1
      include 'dpend_hdf5_slabread.inc'
   end procedure slabread_real_rank1

   module procedure slabread_real_rank2
      include 'dpend_hdf5_slabread.inc'
   end procedure slabread_real_rank2

   module procedure slabread_int_rank1
      include 'dpend_hdf5_slabread.inc'
   end procedure slabread_int_rank1

   module procedure slabread_int_rank2
      include 'dpend_hdf5_slabread.inc'
   end procedure slabread_int_rank2

   module procedure readattr_real_rank0
      call read_one(self, path, want_real, real_type(), c_loc(value), error, name)
   end procedure readattr_real_rank0

   module procedure readattr_real_rank1
      integer(hid_t) :: obj
      integer(hsize_t), allocatable :: dims(:)
      call open_read(self, path, 1, want_real, obj, dims, error, name=name)
      if (allocated(error)) return
      allocate (value(dims(1)))
      call read_obj(self, attr_label(path, name), obj, real_type(), c_loc(value), &
         size(value), error)
   end procedure readattr_real_rank1

   module procedure readattr_int_rank0
      call read_one(self, path, want_int, int_type(), c_loc(value), error, name)
   end procedure readattr_int_rank0

   module procedure readattr_str
      call read_string(self, path, value, error, name)
   end procedure readattr_str

   ! ----------------------------------------------------------- the cores ---

   !> The HDF5 memory type of real(dp) values and what a read accepts in the file
   !> (numbers); with `dims`, `value` (rank 1 to 3, as the readers declare it) is
   !> allocated to that shape.
   subroutine element_real(value, mem_type, want, dims)
      real(dp), allocatable, intent(inout) :: value(..)  !! the reader's array
      integer(hid_t), intent(out) :: mem_type            !! HDF5 memory type
      integer, intent(out) :: want                       !! want_real
      integer(hsize_t), intent(in), optional :: dims(:)  !! shape to allocate
      mem_type = real_type()
      want = want_real
      include 'dpend_hdf5_allocate.inc'
   end subroutine element_real

   !> `element_real` for default integers (the file holds integers).
   subroutine element_int(value, mem_type, want, dims)
      integer, allocatable, intent(inout) :: value(..)   !! the reader's array
      integer(hid_t), intent(out) :: mem_type            !! HDF5 memory type
      integer, intent(out) :: want                       !! want_int
      integer(hsize_t), intent(in), optional :: dims(:)  !! shape to allocate
      mem_type = int_type()
      want = want_int
      include 'dpend_hdf5_allocate.inc'
   end subroutine element_int

   !> `element_real` for integer(i8) (the file holds integers).
   subroutine element_i64(value, mem_type, want, dims)
      integer(i8), allocatable, intent(inout) :: value(..)  !! the reader's array
      integer(hid_t), intent(out) :: mem_type               !! HDF5 memory type
      integer, intent(out) :: want                          !! want_int
      integer(hsize_t), intent(in), optional :: dims(:)     !! shape to allocate
      mem_type = i64_type()
      want = want_int
      include 'dpend_hdf5_allocate.inc'
   end subroutine element_i64

   ! Declared in dpend_hdf5: `shape` and `filters` (dpend_hdf5_file) use it too.
   module procedure open_read
      character(len=*), parameter :: wanted(0:3) = [character(len=8) :: '', 'numbers', &
         'integers', 'a string']
      integer(hid_t) :: dtype, space
      integer(size_t) :: tsize
      integer :: tclass, ierr
      logical :: ok, vlen
      character(len=:), allocatable :: what
      character(len=40) :: msg
      obj = -1
      what = label(path, name)
      call require_open(self, path, .false., error)
      if (allocated(error)) return
      ierr = -1
      if (present(name)) then
         if (self%attr_exists(path, name)) &
            call h5aopen_by_name_f(self%id, trim(path), trim(name), obj, ierr)
         if (ierr == 0) call h5aget_type_f(obj, dtype, ierr)
         if (ierr == 0) call h5aget_space_f(obj, space, ierr)
      else
         if (self%exists(path)) call h5dopen_f(self%id, trim(path), obj, ierr)
         if (ierr == 0) call h5dget_type_f(obj, dtype, ierr)
         if (ierr == 0) call h5dget_space_f(obj, space, ierr)
      end if
      if (ierr /= 0) then
         call close_id(obj)
         if (present(name)) then
            call fail(error, 'read', self, what, 'no such attribute')
         else if (self%exists(path)) then
            call fail(error, 'read', self, what, 'not a dataset')
         else
            call fail(error, 'read', self, what, 'no such dataset')
         end if
         return
      end if
      call space_dims(space, dims)
      call close_id(space)
      call h5tget_class_f(dtype, tclass, ierr)
      call h5tget_size_f(dtype, tsize, ierr)
      vlen = .false.
      if (tclass == H5T_STRING_F) call h5tis_variable_str_f(dtype, vlen, ierr)
      call close_id(dtype)
      if (present(length)) length = int(tsize)
      if (present(variable)) variable = vlen
      select case (want)
      case (want_real)
         ok = tclass == H5T_FLOAT_F .or. tclass == H5T_INTEGER_F
      case (want_int)
         ok = tclass == H5T_INTEGER_F
      case (want_str)
         ok = tclass == H5T_STRING_F
      case default
         ok = .true.
      end select
      if (.not. ok) then
         call fail(error, 'read', self, what, 'it does not hold '//trim(wanted(want)))
      else if (rank == 0 .and. product(dims) /= 1) then
         call fail(error, 'read', self, what, 'it is not a scalar')
      else if (rank > 0 .and. size(dims) /= rank) then
         write (msg, '("it has rank ", i0, ", expected ", i0)') size(dims), rank
         call fail(error, 'read', self, what, trim(msg))
      else if (want /= want_any .and. .not. present_false(whole)) then
         if (tclass == H5T_STRING_F .and. .not. vlen) then
            call check_read_size(self, what, [integer(hsize_t) :: 1], int(tsize, i8), error)
         else
            call check_read_size(self, what, dims, 8_i8, error)
         end if
      end if
      if (allocated(error)) call close_id(obj)
   end procedure open_read

   !> Refuse to read `what` (a quoted path or attribute label) of shape `dims` with
   !> `bytes` bytes per value when it holds more than `max_read_values` values (a
   !> string more than `max_string_bytes` bytes) or needs more memory than the
   !> machine has available: a size declared by a file from elsewhere is checked
   !> before anything is allocated. Counts are formed in real(dp) (no overflow).
   subroutine check_read_size(self, what, dims, bytes, error)
      class(h5file_t), intent(in) :: self               !! the file object
      character(len=*), intent(in) :: what              !! quoted path or attr_label
      integer(hsize_t), intent(in) :: dims(:)           !! shape (Fortran order)
      integer(i8), intent(in) :: bytes                  !! bytes per value
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      type(error_t), allocatable :: mem
      real(dp) :: values, limit
      integer :: i
      character(len=:), allocatable :: shape_text
      values = 1.0_dp
      shape_text = ''
      do i = size(dims), 1, -1   ! h5py order
         values = values*real(dims(i), dp)
         shape_text = shape_text//to_str(int(dims(i), i8))
         if (i > 1) shape_text = shape_text//' x '
      end do
      if (bytes > 8) then
         limit = real(max_string_bytes, dp)
         if (real(bytes, dp) > limit) then
            call fail(error, 'read', self, what, 'its strings of '//to_str(bytes)// &
                      ' bytes exceed '//to_str(max_string_bytes)// &
                      ' bytes (a size declared by the file is checked before reading)')
            return
         end if
      else if (values > real(max_read_values, dp)) then
         call fail(error, 'read', self, what, 'its shape ('//shape_text//') holds '// &
                   sci(values)//' values, at most '//sci(real(max_read_values, dp))// &
                   ' are read at once (a size declared by the file is checked before reading)')
         return
      end if
      call check_memory('FILE', values*real(bytes, dp), 'reading '//what//' of '// &
                        quoted(self%filename), 'a size declared by the file', mem)
      if (allocated(mem)) call fatal_error(error, mem%message)
   end subroutine check_read_size

   !> `flag` is present and false.
   pure logical function present_false(flag)
      logical, intent(in), optional :: flag  !! an optional switch
      present_false = .false.
      if (present(flag)) present_false = .not. flag
   end function present_false

   !> The shape a slab read allocates: `count` (negative counts as 0); a rank that
   !> does not match gives an empty array, and `read_slab_raw` the error.
   pure function slab_shape(count, rank) result(n)
      integer, intent(in) :: count(:)  !! the requested shape
      integer, intent(in) :: rank      !! the rank of the array read into
      integer :: n(rank)
      n = 0
      if (size(count) == rank) n = max(count, 0)
   end function slab_shape

   !> Read the block of shape `count` from `start` of the dataset `path` of rank
   !> `rank` into `buf`, checking that the block lies inside it. With `check_sums`
   !> false the chunks' checksums are not verified (the chunk index is still read):
   !> for blocks whose values will be rewritten, which a kill may have torn.
   subroutine read_slab_raw(self, path, rank, want, mem_type, start, count, buf, error, &
                            check_sums)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer, intent(in) :: rank                       !! rank of the dataset and of `buf`
      integer, intent(in) :: want                       !! want_real or want_int
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      integer, intent(in) :: start(:)                   !! 1-based first index
      integer, intent(in) :: count(:)                   !! shape of the block
      type(c_ptr), intent(in) :: buf                    !! where to put the values
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      logical, intent(in), optional :: check_sums       !! verify checksums (default true)
      integer(hid_t) :: obj, fspace, mspace, dxpl
      integer(hsize_t), allocatable :: dims(:)
      type(c_ptr) :: ptr  ! the HDF5 interfaces take buf as intent(inout)
      integer :: hdferr, ierr
      logical :: verify
      verify = .true.
      if (present(check_sums)) verify = check_sums
      call open_read(self, path, rank, want, obj, dims, error, whole=.false.)
      if (allocated(error)) return
      if (size(start) /= rank .or. size(count) /= rank) then
         call fail(error, 'read', self, quoted(path), 'start or count rank does not match '// &
                   'the dataset')
      else if (any(start < 1) .or. any(count < 0)) then
         call fail(error, 'read', self, quoted(path), 'block lies outside the dataset')
      else if (any(int(start, hsize_t) - 1 + int(count, hsize_t) > dims)) then
         call fail(error, 'read', self, quoted(path), 'block lies outside the dataset')
      end if
      if (allocated(error) .or. product(count) == 0) then
         call close_id(obj)
         return
      end if
      ptr = buf
      call h5dget_space_f(obj, fspace, ierr)
      call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, int(start - 1, hsize_t), &
         int(count, hsize_t), hdferr)
      call h5screate_simple_f(size(count), int(count, hsize_t), mspace, ierr)
      call h5pcreate_f(H5P_DATASET_XFER_F, dxpl, ierr)
      if (.not. verify) call h5pset_edc_check_f(dxpl, H5Z_DISABLE_EDC_F, ierr)
      if (hdferr == 0) call h5dread_f(obj, mem_type, ptr, hdferr, mem_space_id=mspace, &
         file_space_id=fspace, xfer_prp=dxpl)
      call close_id(dxpl)
      call close_id(mspace)
      call close_id(fspace)
      call close_id(obj)
      if (hdferr /= 0) call fail(error, 'read', self, quoted(path), 'HDF5 read failed')
   end subroutine read_slab_raw

   !> Read all of the open dataset or attribute `obj` into `buf`, then close it.
   subroutine read_obj(self, what, obj, mem_type, buf, n, error)
      class(h5file_t), intent(in) :: self               !! the file object
      character(len=*), intent(in) :: what              !! quoted path or attr_label
      integer(hid_t), intent(inout) :: obj              !! open dataset or attribute
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      type(c_ptr), intent(in) :: buf                    !! where to put the data
      integer, intent(in) :: n                          !! number of elements
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(c_ptr) :: ptr  ! the HDF5 interfaces take buf as intent(inout)
      integer :: id_type, hdferr
      hdferr = 0
      ptr = buf
      if (n > 0) then
         call h5iget_type_f(obj, id_type, hdferr)
         if (id_type == H5I_ATTR_F) then
            call h5aread_f(obj, mem_type, ptr, hdferr)
         else
            call h5dread_f(obj, mem_type, ptr, hdferr)
         end if
      end if
      call close_id(obj)
      if (hdferr /= 0) call fail(error, 'read', self, what, 'HDF5 read failed')
   end subroutine read_obj

   !> Read a one-element dataset `path`, or its attribute `name`, into `buf`.
   subroutine read_one(self, path, want, mem_type, buf, error, name)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset or object path
      integer, intent(in) :: want                       !! want_real or want_int
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      type(c_ptr), intent(in) :: buf                    !! where to put the value
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), intent(in), optional :: name    !! attribute name
      integer(hid_t) :: obj
      integer(hsize_t), allocatable :: dims(:)
      call open_read(self, path, 0, want, obj, dims, error, name)
      if (allocated(error)) return
      call read_obj(self, label(path, name), obj, mem_type, buf, 1, error)
   end subroutine read_one

   !> Read a string dataset `path`, or its attribute `name`, fixed-length (up to the
   !> first null byte) or variable-length.
   subroutine read_string(self, path, value, error, name)
      class(h5file_t), intent(inout) :: self               !! the file object
      character(len=*), intent(in) :: path                 !! dataset or object path
      character(len=:), allocatable, intent(out) :: value  !! text read
      type(error_t), allocatable, intent(out) :: error     !! set on failure
      character(len=*), intent(in), optional :: name       !! attribute name
      character(kind=c_char), allocatable, target :: buf(:)
      integer(hid_t) :: obj, stype
      integer(hsize_t), allocatable :: dims(:)
      integer :: i, n, length
      logical :: variable
      value = ''   ! allocated even when the read fails
      call open_read(self, path, 0, want_str, obj, dims, error, name, length, variable)
      if (allocated(error)) return
      if (variable) then
         call read_vlen(self, label(path, name), obj, value, error)
         return
      end if
      allocate (buf(max(1, length)))
      buf = c_null_char
      stype = string_type(size(buf))
      call read_obj(self, label(path, name), obj, stype, c_loc(buf), 1, error)
      call close_id(stype)
      if (allocated(error)) return
      n = size(buf)
      do i = 1, size(buf)
         if (buf(i) == c_null_char) then
            n = i - 1
            exit
         end if
      end do
      deallocate (value)
      allocate (character(len=n) :: value)
      do i = 1, n
         value(i:i) = buf(i)
      end do
   end subroutine read_string

   !> Read the open scalar variable-length string dataset or attribute `obj`, then
   !> close it.
   subroutine read_vlen(self, what, obj, value, error)
      class(h5file_t), intent(in) :: self                  !! the file object
      character(len=*), intent(in) :: what                 !! quoted path or attr_label
      integer(hid_t), intent(inout) :: obj                 !! open dataset or attribute
      character(len=:), allocatable, intent(out) :: value  !! text read
      type(error_t), allocatable, intent(out) :: error     !! set on failure
      interface
         !> Free memory that the HDF5 library allocated (the string read).
         subroutine h5free_memory(mem) bind(c, name='H5free_memory')
            import :: c_ptr
            type(c_ptr), value :: mem  !! the block
         end subroutine h5free_memory
         !> Length of a null-terminated C string.
         function c_strlen(str) bind(c, name='strlen') result(n)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: str  !! the string
            integer(c_size_t) :: n
         end function c_strlen
      end interface
      type(c_ptr), target :: text
      character(kind=c_char), pointer :: chars(:)
      integer(hid_t) :: stype
      integer :: i
      text = c_null_ptr
      stype = vlen_string_type()
      call read_obj(self, what, obj, stype, c_loc(text), 1, error)
      call close_id(stype)
      if (allocated(error)) return
      if (.not. c_associated(text)) then
         value = ''
         return
      end if
      call c_f_pointer(text, chars, [c_strlen(text)])
      allocate (character(len=size(chars)) :: value)
      do i = 1, size(chars)
         value(i:i) = chars(i)
      end do
      call h5free_memory(text)
   end subroutine read_vlen

   ! ---------------------------------------------------------- the record ---

   module procedure file_record
      allocate (record)
      call require_open(self, '/', .false., error)
      if (.not. allocated(error)) call record_attributes(self, '/', record, error)
      if (.not. allocated(error)) call visit('/')
   contains
      !> The children of group `g`, in name order.
      recursive subroutine visit(g)
         character(len=*), intent(in) :: g
         character(len=1024) :: name
         character(len=:), allocatable :: child
         integer(hid_t) :: obj
         integer(size_t) :: name_len
         integer :: storage, nlinks, max_corder, ierr, id_type, k
         call h5gget_info_by_name_f(self%id, g, storage, nlinks, max_corder, ierr)
         if (ierr /= 0) then
            call fail(error, 'record', self, quoted(g), 'not a group')
            return
         end if
         do k = 0, nlinks - 1
            name = ''
            call h5lget_name_by_idx_f(self%id, g, H5_INDEX_NAME_F, H5_ITER_INC_F, &
               int(k, hsize_t), name, ierr, name_len)
            if (ierr /= 0 .or. name_len > len(name)) then
               call fail(error, 'record', self, quoted(g), 'a name of its is unreadable')
               return
            end if
            if (g == '/') then
               child = '/'//name(1:name_len)
            else
               child = g//'/'//name(1:name_len)
            end if
            call h5oopen_f(self%id, child, obj, ierr)
            id_type = -1
            if (ierr == 0) call h5iget_type_f(obj, id_type, ierr)
            if (ierr == 0) call h5oclose_f(obj, ierr)
            if (id_type == H5I_GROUP_F) then
               call record_attributes(self, child, record, error)
               if (.not. allocated(error)) call visit(child)
            else if (id_type == H5I_DATASET_F) then
               call record_dataset(self, child, record, error)
               if (.not. allocated(error)) call record_attributes(self, child, record, error)
            else
               call fail(error, 'record', self, quoted(child), 'not a group or dataset')
            end if
            if (allocated(error)) return
         end do
      end subroutine visit
   end procedure file_record

   !> The memory type, record type and element size of the HDF5 type `ftype`:
   !> floats read as double, integers as 4 or 8 bytes, strings as they are; `kind`
   !> 0 for a type a record cannot hold.
   subroutine record_type(ftype, mem_type, kind, itemsize)
      integer(hid_t), intent(in) :: ftype
      integer(hid_t), intent(out) :: mem_type      !! close it when kind is item_string
      integer, intent(out) :: kind
      integer(i8), intent(out) :: itemsize
      integer(size_t) :: bytes
      integer :: class, ierr
      logical :: vlen
      kind = 0
      mem_type = -1
      itemsize = 0
      call h5tget_class_f(ftype, class, ierr)
      if (ierr == 0) call h5tget_size_f(ftype, bytes, ierr)
      if (ierr /= 0) return
      if (class == H5T_FLOAT_F) then
         kind = item_real
         mem_type = real_type()
         itemsize = 8
      else if (class == H5T_INTEGER_F) then
         kind = item_integer
         itemsize = merge(4_i8, 8_i8, bytes <= 4)
         mem_type = merge(int_type(), i64_type(), bytes <= 4)
      else if (class == H5T_STRING_F) then
         call h5tis_variable_str_f(ftype, vlen, ierr)
         if (ierr /= 0) return
         if (vlen) then
            kind = item_text
         else
            kind = item_string
            itemsize = int(bytes, i8)
            mem_type = string_type(int(bytes))
         end if
      end if
   end subroutine record_type

   !> Record the dataset `path` (not a variable-length string).
   subroutine record_dataset(self, path, record, error)
      class(h5file_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(record_t), intent(inout) :: record
      type(error_t), allocatable, intent(out) :: error
      integer(hid_t) :: dset, ftype, space, mem_type
      integer(hsize_t), allocatable :: dims(:)
      integer(int8), allocatable, target :: bytes(:)
      integer(i8) :: itemsize
      integer :: kind, ierr
      call h5dopen_f(self%id, path, dset, ierr)
      if (ierr /= 0) then
         call fail(error, 'record', self, quoted(path), 'it cannot be opened')
         return
      end if
      call h5dget_type_f(dset, ftype, ierr)
      call record_type(ftype, mem_type, kind, itemsize)
      call close_id(ftype)
      call h5dget_space_f(dset, space, ierr)
      call space_dims(space, dims)
      call close_id(space)
      if (kind == 0 .or. kind == item_text) then
         call close_id(dset)
         call fail(error, 'record', self, quoted(path), 'a type a record cannot hold')
         return
      end if
      call check_read_size(self, quoted(path), dims, itemsize, error)
      if (.not. allocated(error)) then
         allocate (bytes(product(int(dims, i8))*itemsize))
         call read_obj(self, quoted(path), dset, mem_type, c_loc(bytes), &
                       int(product(int(dims, i8))), error)
      else
         call close_id(dset)
      end if
      if (kind == item_string) call close_id(mem_type)
      if (allocated(error)) return
      call record%add(path, '', kind, itemsize, int(dims, i8), c_loc(bytes), &
                      size(bytes, kind=i8))
   end subroutine record_dataset

   !> Record the attributes of the object `path`, in name order.
   subroutine record_attributes(self, path, record, error)
      class(h5file_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(record_t), intent(inout) :: record
      type(error_t), allocatable, intent(out) :: error
      integer(hid_t) :: obj, attr, ftype, space, mem_type
      integer(hsize_t), allocatable :: dims(:)
      integer(int8), allocatable, target :: bytes(:)
      character(len=1024) :: name
      character(len=:), allocatable :: what, text
      integer(i8) :: itemsize
      integer :: kind, ierr, nattrs, k, name_len
      logical :: unreadable
      unreadable = .false.
      call h5oopen_f(self%id, path, obj, ierr)
      if (ierr /= 0) then
         call fail(error, 'record', self, quoted(path), 'it cannot be opened')
         return
      end if
      call h5aget_num_attrs_f(obj, nattrs, ierr)
      do k = 0, nattrs - 1
         call h5aopen_by_idx_f(obj, '.', H5_INDEX_NAME_F, H5_ITER_INC_F, int(k, hsize_t), &
                               attr, ierr)
         unreadable = ierr /= 0
         if (unreadable) exit
         name = ''
         call h5aget_name_f(attr, int(len(name), size_t), name, name_len)
         if (name_len < 0 .or. name_len >= len(name)) then
            call close_id(attr)
            unreadable = .true.
            exit
         end if
         what = attr_label(path, name(:name_len))
         call h5aget_type_f(attr, ftype, ierr)
         call record_type(ftype, mem_type, kind, itemsize)
         call close_id(ftype)
         call h5aget_space_f(attr, space, ierr)
         call space_dims(space, dims)
         call close_id(space)
         if (kind == item_text) then
            call read_vlen(self, what, attr, text, error)
            if (allocated(error)) exit
            bytes = transfer(text, [0_int8], len(text))
            call record%add(path, name(:name_len), item_text, int(len(text), i8), &
                            [integer(i8) ::], c_loc(bytes), int(len(text), i8))
            cycle
         end if
         if (kind == 0) then
            call close_id(attr)
            call fail(error, 'record', self, what, 'a type a record cannot hold')
            exit
         end if
         call check_read_size(self, what, dims, itemsize, error)
         if (allocated(error)) then
            call close_id(attr)
            exit
         end if
         if (allocated(bytes)) deallocate (bytes)
         allocate (bytes(product(int(dims, i8))*itemsize))
         call read_obj(self, what, attr, mem_type, c_loc(bytes), &
                       int(product(int(dims, i8))), error)
         if (kind == item_string) call close_id(mem_type)
         if (allocated(error)) exit
         call record%add(path, name(:name_len), kind, itemsize, int(dims, i8), c_loc(bytes), &
                         size(bytes, kind=i8))
      end do
      call h5oclose_f(obj, ierr)
      if (unreadable .and. .not. allocated(error)) &
         call fail(error, 'record', self, quoted(path), 'its attributes are unreadable')
   end subroutine record_attributes
end submodule dpend_hdf5_read
