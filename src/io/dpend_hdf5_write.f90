!> The writers of dpend_hdf5: `write`, `create_dataset`, `write_slab`, `writeattr`
!> and `describe` of an `h5file_t`. The interfaces, with the arguments'
!> documentation, are in dpend_hdf5.
!>
!> One writer per element type; the value may have any rank (a scalar too), and
!> goes to the rank-agnostic cores (`write_raw`, `slab_raw`, `writeattr_raw`) as
!> its address, HDF5 type and shape.
submodule (dpend_hdf5) dpend_hdf5_write
   implicit none

contains

   module procedure write_real
      call write_raw(self, path, real_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end procedure write_real

   module procedure write_int
      call write_raw(self, path, int_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end procedure write_int

   module procedure write_i64
      call write_raw(self, path, i64_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end procedure write_i64

   module procedure write_str
      character(kind=c_char), allocatable, target :: buf(:)
      integer(hid_t) :: stype
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call require_open(self, path, .true., err)
      if (.not. allocated(err)) then
         call string_buffer(value, buf, stype)
         call write_now(self, path, stype, [integer(hsize_t) ::], c_loc(buf), err)
         call close_id(stype)
         if (.not. allocated(err)) call describe_now(self, path, err, units, description)
      end if
      call settle(self, err, error)
   end procedure write_str

   module procedure file_create_dataset
      integer(hid_t) :: type_id, dcpl, space, lcpl, dset
      integer(hsize_t) :: maxdims(size(dims)), hchunk(size(dims))
      integer :: rank, hdferr, ierr
      logical :: grows, packed, early, summed

      call open_for_write(self, path, dset, error)
      if (allocated(error)) return
      call close_id(dset)
      rank = size(dims)
      grows = .false.
      if (present(extendible)) grows = extendible
      packed = .true.
      if (present(compress)) packed = compress
      early = .false.
      if (present(alloc_early)) early = alloc_early
      summed = .false.
      if (present(checksum)) summed = checksum
      if (dtype /= 'real64' .and. dtype /= 'int32') then
         call fail(error, 'create', self, quoted(path), "dtype is not 'real64' or 'int32'")
      else if (rank < 1 .or. size(chunk) /= rank .or. any(dims < 0) .or. any(chunk < 1)) then
         call fail(error, 'create', self, quoted(path), 'bad dims or chunk')
      else if (present(fill) .and. dtype == 'int32') then
         if (.not. ieee_is_finite(fill)) then
            call fail(error, 'create', self, quoted(path), 'int32 fill out of range')
         else if (abs(fill) > real(huge(0_int32), dp)) then
            call fail(error, 'create', self, quoted(path), 'int32 fill out of range')
         end if
      end if
      if (allocated(error)) return
      type_id = merge(real_type(), h5kind_to_type(int32, H5_INTEGER_KIND), dtype == 'real64')
      maxdims = int(dims, hsize_t)
      hchunk = int(min(chunk, max(dims, 1)), hsize_t)
      if (grows) then
         maxdims(rank) = H5S_UNLIMITED_F
         hchunk(rank) = int(chunk(rank), hsize_t)
      end if
      if (self%exists(path)) call h5ldelete_f(self%id, trim(path), ierr)   ! a dataset, see above

      call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, ierr)
      call h5pset_chunk_f(dcpl, rank, hchunk, ierr)
      if (packed) then
         if (filter_available(H5Z_FILTER_SHUFFLE_F)) call h5pset_shuffle_f(dcpl, ierr)
         if (filter_available(H5Z_FILTER_DEFLATE_F)) call h5pset_deflate_f(dcpl, 4, ierr)
      end if
      ! last in the pipeline: the checksum covers the bytes as stored
      if (summed .and. filter_available(H5Z_FILTER_FLETCHER32_F)) &
         call h5pset_fletcher32_f(dcpl, ierr)
      if (early) then
         call h5pset_alloc_time_f(dcpl, H5D_ALLOC_TIME_EARLY_F, ierr)
         call h5pset_fill_time_f(dcpl, H5D_FILL_TIME_ALLOC_F, ierr)
      end if
      if (present(fill)) then
         if (dtype == 'int32') then
            call h5pset_fill_value_f(dcpl, type_id, nint(fill), ierr)
         else
            call h5pset_fill_value_f(dcpl, type_id, fill, ierr)
         end if
      end if
      call h5screate_simple_f(rank, int(dims, hsize_t), space, ierr, maxdims)
      lcpl = link_plist()
      call h5dcreate_f(self%id, trim(path), type_id, space, dset, hdferr, dcpl_id=dcpl, &
         lcpl_id=lcpl)
      call close_id(dset)
      call close_id(lcpl)
      call close_id(space)
      call close_id(dcpl)
      if (hdferr /= 0) then
         call fail(error, 'create', self, quoted(path), 'HDF5 refused it')
         return
      end if
      call describe_now(self, path, error, units, description)
   end procedure file_create_dataset

   module procedure slab_real
      call slab_raw(self, path, real_type(), int(shape(array), hsize_t), start, &
         c_loc(array), error, whole_chunks)
   end procedure slab_real

   module procedure slab_int
      call slab_raw(self, path, int_type(), int(shape(array), hsize_t), start, &
         c_loc(array), error, whole_chunks)
   end procedure slab_int

   module procedure writeattr_real
      call writeattr_raw(self, path, name, real_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end procedure writeattr_real

   module procedure writeattr_int
      call writeattr_raw(self, path, name, int_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end procedure writeattr_int

   module procedure writeattr_i64
      call writeattr_raw(self, path, name, i64_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end procedure writeattr_i64

   module procedure writeattr_str
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call require_open(self, path, .true., err)
      if (.not. allocated(err)) call writeattr_vlen(self, path, name, value, err)
      call settle(self, err, error)
   end procedure writeattr_str

   module procedure file_describe
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call require_open(self, path, .true., err)
      if (.not. allocated(err)) call describe_now(self, path, err, units, description)
      call settle(self, err, error)
   end procedure file_describe

   ! ----------------------------------------------------------- the cores ---

   !> `units` and `description` attributes of `path`, those present.
   subroutine describe_now(self, path, error, units, description)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! object path
      type(error_t), allocatable, intent(inout) :: error     !! set on failure
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
      if (allocated(error)) return
      if (present(units)) call writeattr_vlen(self, path, 'units', units, error)
      if (allocated(error)) return
      if (present(description)) &
         call writeattr_vlen(self, path, 'description', description, error)
   end subroutine describe_now

   !> Write `value` as a scalar variable-length UTF-8 string attribute.
   subroutine writeattr_vlen(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! object path
      character(len=*), intent(in) :: name              !! attribute name
      character(len=*), intent(in) :: value             !! text to store
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(kind=c_char), allocatable, target :: buf(:)
      type(c_ptr), target :: ptr
      integer(hid_t) :: stype
      integer :: i
      allocate (buf(len(value) + 1))
      do i = 1, len(value)
         buf(i) = value(i:i)
      end do
      buf(len(value) + 1) = c_null_char
      if (allocated(self%record)) then   ! the text, without its NUL
         call record_item(self, path, name, item_text, int(len(value), int64), &
                          [integer(int64) ::], c_loc(buf), int(len(value), int64), error)
         return
      end if
      ptr = c_loc(buf)
      stype = vlen_string_type()
      call writeattr_now(self, path, name, stype, [integer(hsize_t) ::], c_loc(ptr), error)
      call close_id(stype)
   end subroutine writeattr_vlen

   !> `value` as C characters (an empty string is one null byte) and its string type.
   subroutine string_buffer(value, buf, stype)
      character(len=*), intent(in) :: value                       !! Fortran text
      character(kind=c_char), allocatable, intent(out) :: buf(:)  !! bytes to store
      integer(hid_t), intent(out) :: stype                        !! type to close after use
      integer :: i
      allocate (buf(max(1, len(value))))
      buf = c_null_char
      do i = 1, len(value)
         buf(i) = value(i:i)
      end do
      stype = string_type(size(buf))
   end subroutine string_buffer

   !> A link-creation property list that creates missing intermediate groups.
   integer(hid_t) function link_plist() result(lcpl)
      integer :: ierr
      call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ierr)
      call h5pset_create_inter_group_f(lcpl, 1, ierr)
   end function link_plist

   !> True if the HDF5 filter `filter` can be used.
   logical function filter_available(filter) result(avail)
      integer, intent(in) :: filter  !! e.g. H5Z_FILTER_DEFLATE_F
      integer :: ierr
      call h5zfilter_avail_f(filter, avail, ierr)
      if (ierr /= 0) avail = .false.
   end function filter_available

   !> Open dataset `path` for writing, or give `dset` = -1 if there is none.
   subroutine open_for_write(self, path, dset, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer(hid_t), intent(out) :: dset               !! dataset id or -1
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer :: hdferr
      dset = -1
      call require_open(self, path, .true., error)
      if (allocated(error) .or. .not. self%exists(path)) return
      call h5dopen_f(self%id, trim(path), dset, hdferr)
      if (hdferr /= 0) then
         dset = -1
         call fail(error, 'write', self, quoted(path), 'it exists and is not a dataset')
      end if
   end subroutine open_for_write

   !> `write_now` for the public writers: with `error`, the failure goes there;
   !> without, it is kept in the file and later writes without `error` do nothing.
   subroutine write_raw(self, path, mem_type, dims, buf, error, units, description)
      class(h5file_t), intent(inout) :: self                      !! the file object
      character(len=*), intent(in) :: path                        !! dataset path
      integer(hid_t), intent(in) :: mem_type                      !! type of `buf`
      integer(hsize_t), intent(in) :: dims(:)                     !! shape
      type(c_ptr), intent(in) :: buf                              !! address of the data
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call write_now(self, path, mem_type, dims, buf, err)
      if (.not. allocated(err)) call describe_now(self, path, err, units, description)
      call settle(self, err, error)
   end subroutine write_raw

   !> `slab_now` for the public writers, failures handled as by `write_raw`.
   subroutine slab_raw(self, path, mem_type, mem_dims, start, buf, error, whole_chunks)
      class(h5file_t), intent(inout) :: self                      !! the file object
      character(len=*), intent(in) :: path                        !! dataset path
      integer(hid_t), intent(in) :: mem_type                      !! type of `buf`
      integer(hsize_t), intent(in) :: mem_dims(:)                 !! shape of the block
      integer, intent(in) :: start(:)                             !! 1-based first index
      type(c_ptr), intent(in) :: buf                              !! address of the block
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      logical, intent(in), optional :: whole_chunks               !! see the module's header
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call slab_now(self, path, mem_type, mem_dims, start, buf, err, whole_chunks)
      call settle(self, err, error)
   end subroutine slab_raw

   !> `writeattr_now` for the public writers, failures handled as by `write_raw`.
   subroutine writeattr_raw(self, path, name, mem_type, dims, buf, error)
      class(h5file_t), intent(inout) :: self                      !! the file object
      character(len=*), intent(in) :: path                        !! object path
      character(len=*), intent(in) :: name                        !! attribute name
      integer(hid_t), intent(in) :: mem_type                      !! type of `buf`
      integer(hsize_t), intent(in) :: dims(:)                     !! shape
      type(c_ptr), intent(in) :: buf                              !! address of the data
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call writeattr_now(self, path, name, mem_type, dims, buf, err)
      call settle(self, err, error)
   end subroutine writeattr_raw

   !> The failure `err` of one write goes to `error` when the caller passed it, else
   !> it becomes the file's kept error (the first one; later ones do not happen).
   subroutine settle(self, err, error)
      class(h5file_t), intent(inout) :: self                      !! the file object
      type(error_t), allocatable, intent(inout) :: err            !! failure of the write
      type(error_t), allocatable, intent(out), optional :: error  !! the caller's error
      if (present(error)) then
         call move_alloc(err, error)
      else if (allocated(err)) then
         call move_alloc(err, self%error)
      end if
   end subroutine settle

   !> Write a whole dataset from `buf`, reusing an existing dataset of equal type
   !> and shape (so its attributes and chunking stay), and replacing any other.
   subroutine write_now(self, path, mem_type, dims, buf, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`, also stored
      integer(hsize_t), intent(in) :: dims(:)           !! shape, size 0 for a scalar
      type(c_ptr), intent(in) :: buf                    !! address of the data
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t) :: dset, space, dtype, lcpl
      integer(hsize_t), allocatable :: old_dims(:)
      integer :: hdferr, ierr
      logical :: same
      if (allocated(self%record)) then
         call record_typed(self, path, '', mem_type, dims, buf, error)
         return
      end if
      call open_for_write(self, path, dset, error)
      if (allocated(error)) return
      if (dset >= 0) then
         call h5dget_space_f(dset, space, ierr)
         call space_dims(space, old_dims)
         call close_id(space)
         call h5dget_type_f(dset, dtype, ierr)
         call h5tequal_f(dtype, mem_type, same, ierr)   ! also tells vlen from fixed strings
         call close_id(dtype)
         same = same .and. ierr == 0 .and. size(old_dims) == size(dims)
         if (same) same = all(old_dims == dims)
         if (.not. same) then
            call close_id(dset)
            call h5ldelete_f(self%id, trim(path), ierr)
         end if
      end if
      if (dset < 0) then
         if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, space, ierr)
         else
            call h5screate_simple_f(size(dims), dims, space, ierr)
         end if
         lcpl = link_plist()
         call h5dcreate_f(self%id, trim(path), mem_type, space, dset, hdferr, lcpl_id=lcpl)
         call close_id(lcpl)
         call close_id(space)
         if (hdferr /= 0) then
            call fail(error, 'create', self, quoted(path), 'bad path or a name clash')
            return
         end if
      end if
      hdferr = 0
      if (product(dims) > 0) call h5dwrite_f(dset, mem_type, buf, hdferr)
      call close_id(dset)
      if (hdferr /= 0) call fail(error, 'write', self, quoted(path), 'HDF5 write failed')
   end subroutine write_now

   !> Write `buf` (shape `mem_dims`) into dataset `path` from 1-based `start`. Missing
   !> trailing dimensions of `mem_dims` count as 1, so a column goes in as 1-D.
   subroutine slab_now(self, path, mem_type, mem_dims, start, buf, error, whole_chunks)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      integer(hsize_t), intent(in) :: mem_dims(:)       !! shape of the block
      integer, intent(in) :: start(:)                   !! 1-based first index
      type(c_ptr), intent(in) :: buf                    !! address of the block
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      logical, intent(in), optional :: whole_chunks     !! see the module's header
      integer(hid_t) :: dset, fspace, mspace, dxpl
      integer(hsize_t), allocatable :: dims(:), maxdims(:), cnt(:), last(:)
      integer :: rank, hdferr, ierr
      logical :: whole
      character(len=:), allocatable :: why
      whole = .false.
      if (present(whole_chunks)) whole = whole_chunks
      call open_for_write(self, path, dset, error)
      if (allocated(error)) return
      if (dset < 0) then
         call fail(error, 'write a slab of', self, quoted(path), 'no such dataset')
         return
      end if
      call h5dget_space_f(dset, fspace, ierr)
      call space_dims(fspace, dims, maxdims)
      rank = size(dims)
      allocate (cnt(rank), last(rank))
      hdferr = 0
      if (size(start) /= rank .or. size(mem_dims) > rank) then
         why = 'start or block rank does not match the dataset'
         hdferr = -1
      else
         cnt = 1
         cnt(1:size(mem_dims)) = mem_dims
         last = int(start, hsize_t) - 1 + cnt
         if (any(start < 1) .or. any(last > maxdims .and. maxdims /= H5S_UNLIMITED_F)) then
            why = 'block lies outside the dataset'
            hdferr = -1
         else if (whole .and. .not. covers_chunks(dset, start, cnt, dims, maxdims)) then
            why = 'block does not cover whole chunks'
            hdferr = -1
         else if (any(last > dims)) then
            why = 'cannot extend the dataset'
            call close_id(fspace)
            call h5dset_extent_f(dset, max(dims, last), hdferr)
            call h5dget_space_f(dset, fspace, ierr)
         end if
      end if
      if (hdferr == 0) then
         if (product(cnt) > 0) then
            why = 'HDF5 write failed'
            call h5pcreate_f(H5P_DATASET_XFER_F, dxpl, ierr)
            if (whole) call h5pset_edc_check_f(dxpl, H5Z_DISABLE_EDC_F, ierr)
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, int(start - 1, hsize_t), &
               cnt, hdferr)
            call h5screate_simple_f(size(mem_dims), mem_dims, mspace, ierr)
            if (hdferr == 0) call h5dwrite_f(dset, mem_type, buf, hdferr, &
               mem_space_id=mspace, file_space_id=fspace, xfer_prp=dxpl)
            call close_id(mspace)
            call close_id(dxpl)
         end if
      end if
      call close_id(fspace)
      call close_id(dset)
      if (hdferr /= 0) call fail(error, 'write a slab of', self, quoted(path), why)
   contains
      !> The block from `start` of shape `cnt` is a union of whole chunks of the
      !> chunked, fixed-size dataset `dset` (of shape `dims`), the last ones cut at
      !> its edge.
      logical function covers_chunks(dset, start, cnt, dims, maxdims) result(ok)
         integer(hid_t), intent(in) :: dset
         integer, intent(in) :: start(:)
         integer(hsize_t), intent(in) :: cnt(:), dims(:), maxdims(:)
         integer(hid_t) :: dcpl
         integer(hsize_t) :: chunk(size(dims))
         integer :: layout, n, ierr
         ok = .false.
         call h5dget_create_plist_f(dset, dcpl, ierr)
         if (ierr /= 0) return
         call h5pget_layout_f(dcpl, layout, ierr)
         n = -1
         if (ierr == 0 .and. layout == H5D_CHUNKED_F) &
            call h5pget_chunk_f(dcpl, size(dims), chunk, n)
         call close_id(dcpl)
         if (n /= size(dims)) return
         ok = all(mod(int(start - 1, hsize_t), chunk) == 0 .and. &
                  (mod(cnt, chunk) == 0 .or. int(start - 1, hsize_t) + cnt == dims)) .and. &
              all(maxdims == dims)   ! fixed size: no padding of an edge chunk shows later
      end function covers_chunks
   end subroutine slab_now

   !> Write attribute `name` on object `path`, replacing an existing one.
   subroutine writeattr_now(self, path, name, mem_type, dims, buf, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! object path, '/' for the root
      character(len=*), intent(in) :: name              !! attribute name
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`, also stored
      integer(hsize_t), intent(in) :: dims(:)           !! shape, size 0 for a scalar
      type(c_ptr), intent(in) :: buf                    !! address of the data
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t) :: obj, space, attr
      integer :: hdferr, ierr
      logical :: found
      call require_open(self, path, .true., error)
      if (allocated(error)) return
      if (allocated(self%record)) then
         call record_typed(self, path, name, mem_type, dims, buf, error)
         return
      end if
      hdferr = -1
      if (self%exists(path)) call h5oopen_f(self%id, trim(path), obj, hdferr)
      if (hdferr /= 0) then
         call fail(error, 'write', self, attr_label(path, name), 'no such group or dataset')
         return
      end if
      call h5aexists_f(obj, trim(name), found, ierr)
      if (ierr == 0 .and. found) call h5adelete_f(obj, trim(name), ierr)
      if (size(dims) == 0) then
         call h5screate_f(H5S_SCALAR_F, space, ierr)
      else
         call h5screate_simple_f(size(dims), dims, space, ierr)
      end if
      call h5acreate_f(obj, trim(name), mem_type, space, attr, hdferr)
      if (hdferr == 0 .and. product(dims) > 0) call h5awrite_f(attr, mem_type, buf, hdferr)
      call close_id(attr)
      call close_id(space)
      call h5oclose_f(obj, ierr)
      if (hdferr /= 0) call fail(error, 'write', self, attr_label(path, name), &
         'HDF5 write failed')
   end subroutine writeattr_now

   ! -------------------------------------------------------- the record ---

   module procedure file_replay
      integer :: k
      integer(hid_t) :: mem_type
      character(len=:), allocatable :: text
      do k = 1, record%n
         associate (item => record%items(k))
            if (item%type == item_text) then
               allocate (character(len=size(item%bytes)) :: text)
               if (size(item%bytes) > 0) text = transfer(item%bytes, text)
               call writeattr_vlen(self, item%path, item%name, text, error)
               deallocate (text)
            else
               select case (item%type)
               case (item_real)
                  mem_type = real_type()
               case (item_integer)
                  mem_type = merge(i64_type(), int_type(), item%itemsize == 8)
               case default
                  mem_type = string_type(int(item%itemsize))
               end select
               if (len(item%name) == 0) then
                  call write_now(self, item%path, mem_type, int(item%dims, hsize_t), &
                                 c_loc(item%bytes), error)
               else
                  call writeattr_now(self, item%path, item%name, mem_type, &
                                     int(item%dims, hsize_t), c_loc(item%bytes), error)
               end if
               if (item%type == item_string) call close_id(mem_type)
            end if
         end associate
         if (allocated(error)) return
      end do
   end procedure file_replay

   !> Record a dataset (`name` '') or an attribute of HDF5 memory type `mem_type`: a
   !> float, a signed integer or a fixed-length string.
   subroutine record_typed(self, path, name, mem_type, dims, buf, error)
      class(h5file_t), intent(inout) :: self            !! the recorded file
      character(len=*), intent(in) :: path, name        !! the item
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      integer(hsize_t), intent(in) :: dims(:)           !! shape, size 0 for a scalar
      type(c_ptr), intent(in) :: buf                    !! address of the data
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(size_t) :: bytes
      integer :: class, ierr, kind
      logical :: vlen
      call h5tget_class_f(mem_type, class, ierr)
      if (ierr == 0) call h5tget_size_f(mem_type, bytes, ierr)
      vlen = .false.
      if (ierr == 0 .and. class == H5T_STRING_F) call h5tis_variable_str_f(mem_type, vlen, ierr)
      kind = 0
      if (class == H5T_FLOAT_F) kind = item_real
      if (class == H5T_INTEGER_F) kind = item_integer
      if (class == H5T_STRING_F .and. .not. vlen) kind = item_string
      if (ierr /= 0 .or. kind == 0) then
         if (len(name) == 0) then
            call fail(error, 'write', self, quoted(path), 'a type a record cannot hold')
         else
            call fail(error, 'write', self, attr_label(path, name), &
                      'a type a record cannot hold')
         end if
         return
      end if
      call record_item(self, path, name, kind, int(bytes, int64), int(dims, int64), buf, &
                       product(int(dims, int64))*int(bytes, int64), error)
   end subroutine record_typed

   !> Add an item to the record; an attribute's object must be there, as in a file.
   subroutine record_item(self, path, name, kind, itemsize, dims, buf, nbytes, error)
      class(h5file_t), intent(inout) :: self            !! the recorded file
      character(len=*), intent(in) :: path, name        !! the item
      integer, intent(in) :: kind                       !! item_real .. item_text
      integer(int64), intent(in) :: itemsize, dims(:), nbytes
      type(c_ptr), intent(in) :: buf                    !! address of the data
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      if (len(name) > 0 .and. .not. self%record%has_object(path)) then
         call fail(error, 'write', self, attr_label(path, name), 'no such group or dataset')
         return
      end if
      call self%record%add(path, name, kind, itemsize, dims, buf, nbytes)
   end subroutine record_item
end submodule dpend_hdf5_write
