!> The writers of dpend_hdf5: `write`, `create_dataset`, `write_slab`, `writeattr`
!> and `describe` of an `h5file_t`. The interfaces, with the arguments'
!> documentation, are in dpend_hdf5.
!>
!> One writer per element type; the value may have any rank (a scalar too), and
!> goes to the rank-agnostic cores (`write_raw`, `slab_raw`, `writeattr_raw`) as
!> its address, HDF5 type and shape.
submodule (dpend_hdf5) dpend_hdf5_write
   implicit none

   ! dpend_chunk_codec.c, and HDF5's direct chunk write (C API, HDF5 1.10.3 on)
   interface
      integer(c_int64_t) function c_chunk_bound(nbytes) bind(C, name='dpend_chunk_bound')
         import :: c_int64_t
         integer(c_int64_t), value :: nbytes
      end function c_chunk_bound
      integer(c_int) function c_chunk_encode(base, n1, n2, i0, j0, c1, c2, esize, level, &
                                             by_plane, sum, work, dst, cap, len) &
         bind(C, name='dpend_chunk_encode')
         import :: c_int, c_int64_t, c_ptr, c_int8_t
         type(c_ptr), value :: base
         integer(c_int64_t), value :: n1, n2, i0, j0, c1, c2
         integer(c_int), value :: esize, level, by_plane, sum
         integer(c_int8_t), intent(inout) :: work(*)
         integer(c_int8_t), intent(out) :: dst(*)
         integer(c_int64_t), value :: cap
         integer(c_int64_t), intent(out) :: len
      end function c_chunk_encode
      integer(c_int) function c_h5dwrite_chunk(dset, dxpl, filters, offset, size, buf) &
         bind(C, name='H5Dwrite_chunk')
         import :: c_int, c_int32_t, c_int64_t, c_size_t, c_ptr
         integer(c_int64_t), value :: dset, dxpl   ! hid_t: int64_t since HDF5 1.10
         integer(c_int32_t), value :: filters
         integer(c_int64_t), intent(in) :: offset(*)   ! hsize_t
         integer(c_size_t), value :: size
         type(c_ptr), value :: buf
      end function c_h5dwrite_chunk
   end interface

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

      call forget_stored(self)   ! a dataset may be replaced
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
         if (filter_available(H5Z_FILTER_DEFLATE_F)) &
            call h5pset_deflate_f(dcpl, deflate_level, ierr)
      end if
      ! last in the pipeline: the checksum covers the bytes as stored
      if (summed .and. filter_available(H5Z_FILTER_FLETCHER32_F)) &
         call h5pset_fletcher32_f(dcpl, ierr)
      if (early) then   ! allocated, not written (with a checksum: at its filtered size)
         call h5pset_alloc_time_f(dcpl, H5D_ALLOC_TIME_EARLY_F, ierr)
         call h5pset_fill_time_f(dcpl, H5D_FILL_TIME_NEVER_F, ierr)
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

   module procedure chunked_real
      call chunked_raw(self, path, real_type(), int(shape(array), hsize_t), c_loc(array), &
         int(storage_size(1.0_dp)/8), error)
   end procedure chunked_real

   module procedure chunked_int
      call chunked_raw(self, path, int_type(), int(shape(array), hsize_t), c_loc(array), &
         int(storage_size(1)/8), error)
   end procedure chunked_int

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

   !> `write_chunked` for the public writers: the chunks encoded here when the
   !> dataset's filters allow (`chunked_now`), else `slab_now`; failures handled as
   !> by `write_raw`.
   subroutine chunked_raw(self, path, mem_type, mem_dims, buf, esize, error)
      class(h5file_t), intent(inout) :: self                      !! the file object
      character(len=*), intent(in) :: path                        !! dataset path
      integer(hid_t), intent(in) :: mem_type                      !! type of `buf`
      integer(hsize_t), intent(in) :: mem_dims(:)                 !! shape of the array
      type(c_ptr), intent(in) :: buf                              !! address of the array
      integer, intent(in) :: esize                                !! bytes per element
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      type(error_t), allocatable :: err
      logical :: written
      if (.not. present(error) .and. allocated(self%error)) return
      written = .false.
      if (.not. allocated(self%record)) &
         call chunked_now(self, path, mem_type, mem_dims, buf, esize, written, err)
      if (.not. written .and. .not. allocated(err)) &
         call slab_now(self, path, mem_type, mem_dims, spread(1, 1, size(mem_dims)), buf, err)
      call settle(self, err, error)
   end subroutine chunked_raw

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
      call forget_stored(self)   ! a dataset may be replaced
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
      logical :: whole, written
      character(len=:), allocatable :: why
      whole = .false.
      if (present(whole_chunks)) whole = whole_chunks
      if (whole .and. self%direct) then
         call stored_chunks(self, path, mem_type, mem_dims, start, buf, written, hdferr)
         if (hdferr < 0) call fail(error, 'write a slab of', self, quoted(path), &
                                   'HDF5 write failed')
         if (written .or. hdferr < 0) return
      end if
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

   !> Write the block at `buf` (shape `mem_dims`, from 1-based `start`) chunk by chunk
   !> as stored (H5Dwrite_chunk), when it is whole chunks of a fixed-size dataset of
   !> rank 1 or 2 without filters, of the memory type (`written`); an edge chunk is
   !> padded with zeros, which HDF5 never shows. Else nothing is done and `write_slab`
   !> goes its usual way. The dataset stays open, with what is checked
   !> (`stored_dataset`). `hdferr` < 0: a write failed.
   subroutine stored_chunks(self, path, mem_type, mem_dims, start, buf, written, hdferr)
      class(h5file_t), intent(inout) :: self           !! the file object
      character(len=*), intent(in) :: path             !! dataset path
      integer(hid_t), intent(in) :: mem_type           !! type of `buf`
      integer(hsize_t), intent(in) :: mem_dims(:)      !! shape of the block
      integer, intent(in) :: start(:)                  !! its first index
      type(c_ptr), intent(in) :: buf                   !! the block
      logical, intent(out) :: written                  !! written here
      integer, intent(out) :: hdferr                   !! < 0: failed
      integer(i8) :: c(2), b(2), s(2), d(2), nch(2), i, j, k, col, rows, cols, bytes, e
      integer(c_int8_t), pointer :: block(:)
      integer(c_int8_t), allocatable, target :: padded(:)
      integer(c_int64_t) :: offset(2)
      integer :: slot, ierr
      logical :: same
      written = .false.
      hdferr = 0
      slot = stored_dataset(self, path)
      if (slot == 0) return
      associate (ds => self%stored(slot))
         if (ds%dset < 0 .or. size(start) /= ds%rank .or. size(mem_dims) > ds%rank) return
         c = int(ds%chunk, i8); d = int(ds%dims, i8)
         b = 1; s = 1
         b(1:size(mem_dims)) = int(mem_dims, i8)
         s(1:ds%rank) = int(start, i8)
         if (any(s < 1) .or. any(s - 1 + b > d) .or. product(b) == 0) return
         if (any(mod(s - 1, c) /= 0) .or. any(mod(b, c) /= 0 .and. s - 1 + b /= d)) return
         call h5tequal_f(ds%dtype, mem_type, same, ierr)
         if (.not. same .or. ierr /= 0) return
         e = int(ds%esize, i8)
         nch = (b + c - 1)/c
         bytes = c(1)*c(2)*e
         call c_f_pointer(buf, block, [b(1)*b(2)*e])
         do k = 0, nch(1)*nch(2) - 1
            i = mod(k, nch(1))*c(1)   ! the chunk's origin in the block, 0-based
            j = (k/nch(1))*c(2)
            rows = min(c(1), b(1) - i)
            cols = min(c(2), b(2) - j)
            offset = [s(2) - 1 + j, s(1) - 1 + i]   ! C order: the last index first
            if (ds%rank == 1) offset(1) = s(1) - 1 + i
            if (rows == c(1) .and. cols == c(2) .and. (ds%rank == 1 .or. b(1) == c(1))) then
               ! the chunk is a contiguous part of the block
               hdferr = c_h5dwrite_chunk(int(ds%dset, c_int64_t), &
                                         int(H5P_DEFAULT_F, c_int64_t), 0_c_int32_t, offset, &
                                         int(bytes, c_size_t), c_loc(block((j*b(1) + i)*e + 1)))
            else
               if (.not. allocated(padded)) allocate (padded(bytes))
               padded = 0
               do col = 0, cols - 1
                  padded(col*c(1)*e + 1:(col*c(1) + rows)*e) = &
                     block(((j + col)*b(1) + i)*e + 1:((j + col)*b(1) + i + rows)*e)
               end do
               hdferr = c_h5dwrite_chunk(int(ds%dset, c_int64_t), &
                                         int(H5P_DEFAULT_F, c_int64_t), 0_c_int32_t, offset, &
                                         int(bytes, c_size_t), c_loc(padded))
            end if
            if (hdferr < 0) return
         end do
      end associate
      written = .true.
   end subroutine stored_chunks

   !> The slot of `path` among the datasets kept for `stored_chunks`, opened and
   !> examined on its first write: eligible (`dset` >= 0) when it is a fixed-size
   !> chunked dataset of rank 1 or 2 without filters. 0: no such dataset.
   integer function stored_dataset(self, path) result(slot)
      class(h5file_t), intent(inout) :: self  !! the file object
      character(len=*), intent(in) :: path    !! dataset path
      type(stored_dataset_t) :: ds
      type(error_t), allocatable :: err
      integer(hid_t) :: dcpl, space
      integer(hsize_t), allocatable :: dims(:), maxdims(:)
      integer :: layout, nfilters, ierr
      if (allocated(self%stored)) then
         do slot = 1, size(self%stored)
            if (self%stored(slot)%path == trim(path)) return
         end do
      end if
      slot = 0
      call open_for_write(self, path, ds%dset, err)
      if (allocated(err) .or. ds%dset < 0) return
      ds%path = trim(path)
      call h5dget_space_f(ds%dset, space, ierr)
      call space_dims(space, dims, maxdims)
      call close_id(space)
      ds%rank = size(dims)
      nfilters = -1
      layout = -1
      if (ds%rank == 1 .or. ds%rank == 2) then
         if (all(maxdims == dims)) then
            ds%dims(1:ds%rank) = dims
            call h5dget_create_plist_f(ds%dset, dcpl, ierr)
            call h5pget_layout_f(dcpl, layout, ierr)
            if (layout == H5D_CHUNKED_F) then
               call h5pget_chunk_f(dcpl, ds%rank, ds%chunk, ierr)
               call h5pget_nfilters_f(dcpl, nfilters, ierr)
            end if
            call close_id(dcpl)
         end if
      end if
      if (nfilters == 0 .and. all(ds%chunk >= 1)) then
         call h5dget_type_f(ds%dset, ds%dtype, ierr)
         call h5tget_size_f(ds%dtype, ds%esize, ierr)
      else
         call close_id(ds%dset)   ! kept as not eligible
         ds%dset = -1
      end if
      if (.not. allocated(self%stored)) allocate (self%stored(0))
      self%stored = [self%stored, ds]
      slot = size(self%stored)
   end function stored_dataset


   !> Write the whole dataset `path` from `buf` (shape `mem_dims`, `esize` bytes per
   !> element) by encoding its chunks here, when the dataset is fixed-size, chunked,
   !> of rank 1 or 2, of the memory type, and stored with shuffle, deflate and
   !> optionally Fletcher-32, in that order (`written` true); else nothing is done
   !> (`written` false, no error). The chunks are encoded in groups, each group on
   !> every OpenMP thread, then written as stored in this thread.
   subroutine chunked_now(self, path, mem_type, mem_dims, buf, esize, written, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer(hid_t), intent(in) :: mem_type            !! type of `buf`
      integer(hsize_t), intent(in) :: mem_dims(:)       !! shape of the array
      type(c_ptr), intent(in) :: buf                    !! address of the array
      integer, intent(in) :: esize                      !! bytes per element
      logical, intent(out) :: written                   !! encoded and written here
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      !> bytes of encoded chunks held at once
      integer(i8), parameter :: group_bytes = 33554432_i8
      integer(c_int8_t), allocatable, target :: out(:, :)
      integer(c_int8_t), allocatable :: work(:)   ! a chunk, shuffled (one per thread)
      integer(i8), allocatable :: lens(:)
      integer, allocatable :: codes(:)
      integer(hid_t) :: dset
      integer(hsize_t) :: chunk(2)
      integer(c_int64_t) :: offset(2)
      integer(i8) :: n(2), c(2), nc(2), cap, nch, g0, k, i0, j0
      integer :: level, rank, hdferr, ng
      logical :: summed, usable
      written = .false.
      call open_for_write(self, path, dset, error)
      if (allocated(error)) return
      if (dset < 0) then
         call fail(error, 'write', self, quoted(path), 'no such dataset')
         return
      end if
      rank = size(mem_dims)
      call encodable(dset, mem_type, mem_dims, chunk, level, summed, usable)
      if (.not. usable) then
         call close_id(dset)
         return
      end if
      n = 1; c = 1
      n(1:rank) = int(mem_dims, i8)
      c(1:rank) = int(chunk(1:rank), i8)
      nc = (n + c - 1)/c
      nch = nc(1)*nc(2)
      cap = c_chunk_bound(c(1)*c(2)*esize)
      ng = int(max(1_i8, min(nch, group_bytes/cap)))
      allocate (out(cap, ng), lens(ng), codes(ng))
      hdferr = 0
      do g0 = 0, nch - 1, ng
         !$omp parallel default(shared) private(i0, j0, work)
         allocate (work(c(1)*c(2)*esize))
         !$omp do schedule(dynamic)
         do k = 1, min(int(ng, i8), nch - g0)
            call chunk_origin(g0 + k - 1, i0, j0)
            codes(k) = c_chunk_encode(buf, n(1), n(2), i0, j0, c(1), c(2), int(esize, c_int), &
                                      int(level, c_int), 1_c_int, &
                                      merge(1_c_int, 0_c_int, summed), work, &
                                      out(:, k), cap, lens(k))
         end do
         !$omp end do
         deallocate (work)
         !$omp end parallel
         do k = 1, min(int(ng, i8), nch - g0)
            if (codes(k) /= 0) then
               call close_id(dset)
               call fail(error, 'write', self, quoted(path), 'could not encode chunk '// &
                         to_str(g0 + k)//trim(merge(' (out of memory)     ', &
                                                    ' (compression failed)', codes(k) == 1)))
               return
            end if
            call chunk_origin(g0 + k - 1, i0, j0)
            offset = int([j0, i0], c_int64_t)   ! C order: the last Fortran index first
            if (rank == 1) offset(1) = int(i0, c_int64_t)
            hdferr = c_h5dwrite_chunk(int(dset, c_int64_t), int(H5P_DEFAULT_F, c_int64_t), &
                                      0_c_int32_t, offset, &
                                      int(lens(k), c_size_t), c_loc(out(1, k)))
            if (hdferr < 0) exit
         end do
         if (hdferr < 0) exit
      end do
      call close_id(dset)
      if (hdferr < 0) then
         call fail(error, 'write', self, quoted(path), 'HDF5 write failed')
      else
         written = .true.
      end if
   contains
      !> 0-based first element (i0, j0) of chunk `ch` (0-based, the first index fastest)
      subroutine chunk_origin(ch, i0, j0)
         integer(i8), intent(in) :: ch
         integer(i8), intent(out) :: i0, j0
         i0 = mod(ch, nc(1))*c(1)
         j0 = (ch/nc(1))*c(2)
      end subroutine chunk_origin
   end subroutine chunked_now

   !> Whether the open dataset `dset` can have its chunks encoded by
   !> dpend_chunk_codec.c for a write of the whole of it from memory of type
   !> `mem_type` and shape `mem_dims`; if so, its chunk shape (Fortran order), deflate
   !> level and whether it carries a checksum.
   subroutine encodable(dset, mem_type, mem_dims, chunk, level, summed, usable)
      integer(hid_t), intent(in) :: dset               !! open dataset
      integer(hid_t), intent(in) :: mem_type           !! type in memory
      integer(hsize_t), intent(in) :: mem_dims(:)      !! shape in memory
      integer(hsize_t), intent(out) :: chunk(2)        !! chunk shape
      integer, intent(out) :: level                    !! deflate level
      logical, intent(out) :: summed                   !! Fletcher-32 last
      logical, intent(out) :: usable                   !! all of the above hold
      integer(hid_t) :: space, dtype, dcpl
      integer(hsize_t), allocatable :: dims(:), maxdims(:)
      integer :: layout, nfilters, ierr, rank, f, flags, id
      integer(size_t) :: nelmts
      integer :: values(8)
      character(len=32) :: name
      logical :: same
      chunk = 1; level = 0; summed = .false.
      rank = size(mem_dims)
      call h5dget_space_f(dset, space, ierr)
      call space_dims(space, dims, maxdims)
      call close_id(space)
      call h5dget_type_f(dset, dtype, ierr)
      call h5tequal_f(dtype, mem_type, same, ierr)
      call close_id(dtype)
      usable = same .and. ierr == 0 .and. (rank == 1 .or. rank == 2) .and. size(dims) == rank
      if (usable) usable = all(dims == mem_dims) .and. all(maxdims == dims) .and. &
                           product(dims) > 0
      if (.not. usable) return
      call h5dget_create_plist_f(dset, dcpl, ierr)
      call h5pget_layout_f(dcpl, layout, ierr)
      usable = layout == H5D_CHUNKED_F
      if (usable) call h5pget_chunk_f(dcpl, rank, chunk, ierr)
      if (usable) usable = ierr >= 0 .and. all(chunk(1:rank) >= 1)
      nfilters = 0
      if (usable) call h5pget_nfilters_f(dcpl, nfilters, ierr)
      usable = usable .and. (nfilters == 2 .or. nfilters == 3)
      do f = 0, nfilters - 1
         if (.not. usable) exit
         nelmts = size(values, kind=size_t)
         values = 0
         call h5pget_filter_f(dcpl, f, flags, nelmts, values, int(len(name), size_t), name, &
                              id, ierr)
         select case (f)
         case (0); usable = ierr >= 0 .and. id == H5Z_FILTER_SHUFFLE_F
         case (1)
            usable = ierr >= 0 .and. id == H5Z_FILTER_DEFLATE_F .and. nelmts >= 1
            if (usable) level = values(1)
            usable = usable .and. level >= 0 .and. level <= 9
         case (2)
            usable = ierr >= 0 .and. id == H5Z_FILTER_FLETCHER32_F
            summed = usable
         end select
      end do
      call close_id(dcpl)
   end subroutine encodable

end submodule dpend_hdf5_write
