!> A thin layer over the HDF5 Fortran API in the spirit of h5fortran.
!>
!> `h5file_t` opens one file and reads or writes whole datasets, attributes and
!> hyperslabs of chunked, compressed datasets. Paths are absolute ('/a/b/c');
!> intermediate groups are created on write. Shapes are stored in Fortran order
!> as the HDF5 Fortran API does: `q(2, n)` is seen by h5py and h5dump as (n, 2).
!> String datasets are fixed-length, null-padded, ASCII; string attributes are
!> variable-length UTF-8 (h5py reads them as `str`), and both forms are read.
!> `write` and `create_dataset` take optional `units` and `description`, stored
!> as attributes of the dataset (see `describe`). Trailing blanks of paths, names
!> and file names are ignored. Every failure comes back as an `error_t` naming the
!> file and the path; HDF5's own error printing is off. A write (`write`,
!> `write_slab`, `writeattr`) called without `error` keeps its failure in the file
!> object instead: the first failure is kept, later writes without `error` do
!> nothing, and `close(error)` or `take_error` hands it over, so that a writer
!> writes plainly and checks once at the end.
!> `write_slab(..., whole_chunks=.true.)` writes a block made of whole chunks of a
!> fixed-size chunked dataset (the last ones cut at its edge; anything else is
!> refused): every value of those chunks is replaced, so the old contents HDF5
!> reads to rewrite a partial edge chunk are not checked against their checksum,
!> and a chunk torn by a kill during an earlier write is simply rewritten.
!> `read_slab(..., check_sums=.false.)` reads a block without verifying checksums
!> (the chunk index is still read): for blocks that will be rewritten so.
!> `write`, `write_slab` and `writeattr` take real(dp), default-integer and
!> integer(i8) values of any rank (a scalar too); `read` and `read_slab` fill
!> allocatable arrays of rank 1 to 3 (one body, dpend_hdf5_read.inc and
!> dpend_hdf5_slabread.inc, included by each reader), and one-element scalars.
!> HDF5 here is the serial library (the parallel one in the MPI build, mpi/): use
!> an `h5file_t` from one thread at a time.
module dpend_hdf5
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char, c_null_ptr, &
      c_associated, c_f_pointer, c_size_t
   use, intrinsic :: iso_fortran_env, only: real64, int32
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use hdf5
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_os, only: io_failure_reason
   use dpend_limits, only: sci
   use dpend_resources, only: check_memory
   use dpend_strings, only: to_str
   implicit none
   private
   public :: h5file_t, is_hdf5, max_read_values, max_string_bytes

   !> At most 2^31 − 1 values in one read of a whole dataset or attribute: arrays are
   !> indexed with default integers. A file from elsewhere may declare any shape
   !> (a few kB can declare 2^40 × 2 chunked values); it is refused before anything
   !> is allocated, as is a read that would not fit the available memory.
   integer(i8), parameter :: max_read_values = int(huge(1), i8)
   !> At most 64 MiB in one fixed-length string (dataset or attribute).
   integer(i8), parameter :: max_string_bytes = 67108864_i8

   !> What a read accepts in the file: anything, numbers, integers, a string.
   integer, parameter :: want_any = 0, want_real = 1, want_int = 2, want_str = 3

   logical, save :: library_ready = .false.  !! h5open_f has been called
   !> HDF5's error printing is off in this thread. The library is thread-safe, so
   !> the setting is per thread: every OpenMP thread that calls HDF5 turns it off.
   logical, save :: thread_quiet = .false.
   !$omp threadprivate(thread_quiet)

   !> One open HDF5 file. Do not copy an open `h5file_t`: the copy shares the id.
   type :: h5file_t
      private
      character(len=:), allocatable :: filename  !! name given to `open`
      integer(hid_t) :: id = -1                  !! HDF5 file id, -1 when closed
      logical :: readonly = .false.              !! opened with mode 'r'
      !> first failure of a write called without `error` (see `take_error`)
      type(error_t), allocatable :: error
   contains
      procedure :: open => file_open
      procedure :: close => file_close
      procedure :: is_open => file_is_open
      procedure :: flush => file_flush
      procedure :: take_error => file_take_error
      procedure :: exists => file_exists
      procedure :: attr_exists => file_attr_exists
      procedure :: shape => file_shape
      procedure :: filters => file_filters
      procedure :: create_dataset => file_create_dataset
      procedure :: describe => file_describe
      procedure :: datasets => file_datasets
      procedure, private :: write_real, write_int, write_i64, write_str
      generic :: write => write_real, write_int, write_i64, write_str
      procedure, private :: slab_real, slab_int
      generic :: write_slab => slab_real, slab_int
      procedure, private :: slabread_real_rank1, slabread_real_rank2, &
         slabread_int_rank1, slabread_int_rank2
      generic :: read_slab => slabread_real_rank1, slabread_real_rank2, &
         slabread_int_rank1, slabread_int_rank2
      procedure, private :: read_real_rank0, read_real_rank1, read_real_rank2, read_real_rank3
      procedure, private :: read_int_rank0, read_int_rank1, read_int_rank2, read_i64_rank1, &
         read_str
      generic :: read => read_real_rank0, read_real_rank1, read_real_rank2, read_real_rank3, &
         read_int_rank0, read_int_rank1, read_int_rank2, read_i64_rank1, read_str
      procedure, private :: writeattr_real, writeattr_int, writeattr_i64, writeattr_str
      generic :: writeattr => writeattr_real, writeattr_int, writeattr_i64, writeattr_str
      procedure, private :: readattr_real_rank0, readattr_real_rank1, readattr_int_rank0, &
         readattr_str
      generic :: readattr => readattr_real_rank0, readattr_real_rank1, readattr_int_rank0, &
         readattr_str
      final :: file_finalize
   end type h5file_t

   !> The element type of a reader's array (dpend_hdf5_read.inc, ..._slabread.inc).
   interface element
      module procedure element_real, element_int, element_i64
   end interface element

contains

   ! ---------------------------------------------------------------- file ---

   !> Open `filename`: 'r' read only, 'w' create or truncate, 'rw' read-write
   !> (created if missing), 'x' create and fail if it exists. An open file is
   !> closed first. `access` is a file access property list to start from (e.g.
   !> one set up for MPI-IO by a parallel HDF5 program; then open and close are
   !> collective); it is copied, not kept.
   subroutine file_open(self, filename, mode, error, access)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: filename          !! path on disk
      character(len=*), intent(in) :: mode              !! 'r', 'w', 'rw' or 'x'
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t), intent(in), optional :: access    !! file access property list
      integer(hid_t) :: fapl, fid
      integer :: hdferr, ierr
      logical :: on_disk
      character(len=:), allocatable :: why

      call self%close()
      if (allocated(self%error)) deallocate (self%error)
      call init_library(error)
      if (allocated(error)) return
      inquire (file=filename, exist=on_disk)
      if (present(access)) then
         call h5pcopy_f(access, fapl, ierr)
      else
         call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, ierr)
      end if
      call h5pset_fclose_degree_f(fapl, H5F_CLOSE_STRONG_F, ierr)
      hdferr = -1
      why = io_failure_reason(filename, 'cannot create it')
      select case (mode)
      case ('r', 'rw')
         if (on_disk) then
            why = 'not an HDF5 file or not '//merge('readable', 'writable', mode == 'r')
            call h5fopen_f(trim(filename), merge(H5F_ACC_RDONLY_F, H5F_ACC_RDWR_F, mode == 'r'), &
               fid, hdferr, access_prp=fapl)
         else if (mode == 'r') then
            why = 'no such file'
         else
            call h5fcreate_f(trim(filename), H5F_ACC_EXCL_F, fid, hdferr, access_prp=fapl)
         end if
      case ('w', 'x')
         if (mode == 'x' .and. on_disk) then
            why = 'file exists'
         else
            call h5fcreate_f(trim(filename), merge(H5F_ACC_TRUNC_F, H5F_ACC_EXCL_F, mode == 'w'), &
               fid, hdferr, access_prp=fapl)
         end if
      case default
         why = "invalid mode '"//mode//"' (use 'r', 'w', 'rw' or 'x')"
      end select
      call h5pclose_f(fapl, ierr)
      if (hdferr /= 0) then
         call fatal_error(error, 'cannot open '//quoted(filename)//': '//why)
         return
      end if
      self%id = fid
      self%filename = trim(filename)
      self%readonly = mode == 'r'
   end subroutine file_open

   !> Close the file if it is open (this also flushes it). With `error`: the kept
   !> failure of a write (see `take_error`), else a failed close (e.g. a full disk
   !> while flushing). Without, a kept failure is dropped.
   subroutine file_close(self, error)
      class(h5file_t), intent(inout) :: self                      !! the file object
      type(error_t), allocatable, intent(out), optional :: error  !! a write or the close failed
      integer :: ierr
      logical :: valid
      if (present(error)) call self%take_error(error)
      if (allocated(self%error)) deallocate (self%error)
      if (self%id < 0) return
      call quiet_thread()
      ierr = 0
      call h5iis_valid_f(self%id, valid, ierr)
      if (valid .and. ierr == 0) call h5fclose_f(self%id, ierr)
      if (ierr /= 0 .and. present(error)) then
         if (.not. allocated(error)) call fatal_error(error, 'cannot close '// &
            quoted(self%filename)//': '//io_failure_reason(self%filename, &
            'HDF5 could not flush it'))
      end if
      self%id = -1
      self%readonly = .false.
   end subroutine file_close

   !> Hand over the first failure of the writes called without `error` since the
   !> file was opened or the last `take_error` (unallocated: none failed), and
   !> let such writes work again.
   subroutine file_take_error(self, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      type(error_t), allocatable, intent(out) :: error  !! the kept failure, if any
      if (allocated(self%error)) call move_alloc(self%error, error)
   end subroutine file_take_error

   !> Finaliser: close a file that was left open.
   subroutine file_finalize(self)
      type(h5file_t), intent(inout) :: self  !! the file object going away
      call file_close(self)
   end subroutine file_finalize

   !> True while a file is open.
   logical function file_is_open(self) result(is_open)
      class(h5file_t), intent(in) :: self  !! the file object
      is_open = self%id >= 0
   end function file_is_open

   !> Flush everything written so far to disk (whole file).
   subroutine file_flush(self)
      class(h5file_t), intent(inout) :: self  !! the file object
      integer :: ierr
      if (.not. self%is_open()) return
      call quiet_thread()
      call h5fflush_f(self%id, H5F_SCOPE_GLOBAL_F, ierr)
   end subroutine file_flush

   !> True if the group or dataset `path` exists: every component is checked.
   logical function file_exists(self, path) result(found)
      class(h5file_t), intent(in) :: self   !! the file object
      character(len=*), intent(in) :: path  !! e.g. '/trajectory/q', '/' for the root
      integer :: i, n, ierr
      found = .false.
      if (.not. self%is_open() .or. len_trim(path) == 0) return
      found = .true.
      n = len_trim(path)
      do i = 2, n + 1   ! check path(1:i-1) at every component end
         if (i <= n) then
            if (path(i:i) /= '/') cycle
         end if
         if (path(i - 1:i - 1) == '/') cycle
         call h5lexists_f(self%id, path(1:i - 1), found, ierr)
         if (ierr /= 0) found = .false.
         if (.not. found) return
      end do
   end function file_exists

   !> True if the group or dataset `path` carries an attribute `name`.
   logical function file_attr_exists(self, path, name) result(found)
      class(h5file_t), intent(in) :: self   !! the file object
      character(len=*), intent(in) :: path  !! group or dataset, '/' for the root
      character(len=*), intent(in) :: name  !! attribute name
      integer :: ierr
      found = .false.
      if (.not. self%exists(path)) return
      call h5aexists_by_name_f(self%id, trim(path), trim(name), found, ierr)
      if (ierr /= 0) found = .false.
   end function file_attr_exists

   !> Shape of dataset `path` in Fortran order (size 0 for a scalar). A dimension
   !> beyond a default integer (a file from elsewhere may declare 2^40) is refused.
   subroutine file_shape(self, path, dims, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer, allocatable, intent(out) :: dims(:)      !! its shape
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t) :: dset
      integer(hsize_t), allocatable :: hdims(:)
      call open_read(self, path, -1, want_any, dset, hdims, error)
      call close_id(dset)
      if (allocated(error)) return
      if (any(hdims > int(huge(1), hsize_t))) then
         call fail(error, 'read', self, quoted(path), 'a dimension of '// &
                   to_str(int(maxval(hdims), i8))//' exceeds '//to_str(max_read_values)// &
                   ' (a size declared by the file is checked before reading)')
         return
      end if
      dims = int(hdims)
   end subroutine file_shape

   !> Number of filters (compression, shuffle, checksum) in the pipeline of dataset
   !> `path` (0 for a contiguous or unfiltered chunked dataset).
   subroutine file_filters(self, path, n, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer, intent(out) :: n                         !! its filters
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t) :: dset, dcpl
      integer(hsize_t), allocatable :: hdims(:)
      integer :: ierr
      n = 0
      call open_read(self, path, -1, want_any, dset, hdims, error)
      if (allocated(error)) return
      call h5dget_create_plist_f(dset, dcpl, ierr)
      if (ierr == 0) then
         call h5pget_nfilters_f(dcpl, n, ierr)
         call h5pclose_f(dcpl, ierr)
      end if
      call close_id(dset)
   end subroutine file_filters

   !> True if `filename` exists and is an HDF5 file.
   logical function is_hdf5(filename)
      character(len=*), intent(in) :: filename  !! path on disk
      type(error_t), allocatable :: error
      logical :: on_disk, status
      integer :: ierr
      is_hdf5 = .false.
      inquire (file=filename, exist=on_disk)
      if (.not. on_disk) return
      call init_library(error)
      if (allocated(error)) return
      call h5fis_hdf5_f(trim(filename), status, ierr)
      is_hdf5 = ierr == 0 .and. status
   end function is_hdf5

   ! ------------------------------------------------------------- writing ---
   ! One writer per element type; the value may have any rank (a scalar too), and
   ! goes to the rank-agnostic cores (`write_raw`, `slab_raw`, `writeattr_raw`) as
   ! its address, HDF5 type and shape.

   !> Write a real(dp) dataset of the value's shape (a scalar: a scalar dataset).
   subroutine write_real(self, path, value, error, units, description)
      class(h5file_t), intent(inout) :: self                       !! the file object
      character(len=*), intent(in) :: path                         !! dataset path
      real(dp), intent(in), target, contiguous :: value(..)        !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
      call write_raw(self, path, real_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end subroutine write_real

   !> Write a default-integer dataset of the value's shape.
   subroutine write_int(self, path, value, error, units, description)
      class(h5file_t), intent(inout) :: self                       !! the file object
      character(len=*), intent(in) :: path                         !! dataset path
      integer, intent(in), target, contiguous :: value(..)         !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
      call write_raw(self, path, int_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end subroutine write_int

   !> Write an integer(i8) dataset of the value's shape (stored as 64-bit integers).
   subroutine write_i64(self, path, value, error, units, description)
      class(h5file_t), intent(inout) :: self                       !! the file object
      character(len=*), intent(in) :: path                         !! dataset path
      integer(i8), intent(in), target, contiguous :: value(..)     !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
      call write_raw(self, path, i64_type(), int(shape(value), hsize_t), c_loc(value), error, &
         units, description)
   end subroutine write_i64

   !> Write a scalar fixed-length string dataset (stored exactly, trailing blanks kept).
   subroutine write_str(self, path, value, error, units, description)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      character(len=*), intent(in) :: value             !! text to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
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
   end subroutine write_str

   !> Create a chunked dataset of shape `dims` for partial writes with `write_slab`,
   !> compressed with shuffle + deflate level 4 when the filters are available.
   !> An existing dataset at `path` is replaced. Unwritten elements read as `fill`
   !> (default 0; rounded with `nint` for 'int32'). With `extendible`, the
   !> last dimension is unlimited and `write_slab` grows it as needed. With
   !> `compress` false no filter is set; with `alloc_early` every chunk is allocated
   !> (and filled) now, so that later writes change no metadata (crash-safe updates).
   !> With `checksum`, every chunk carries a Fletcher-32 checksum (filter applied
   !> last, size fixed: a rewrite stays in place), and reading a damaged chunk fails.
   subroutine file_create_dataset(self, path, dtype, dims, chunk, error, fill, extendible, &
                                  compress, alloc_early, checksum, units, description)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      character(len=*), intent(in) :: dtype             !! 'real64' or 'int32'
      integer, intent(in) :: dims(:)                    !! full shape, Fortran order
      integer, intent(in) :: chunk(:)                   !! chunk shape, same rank
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      real(dp), intent(in), optional :: fill            !! value of unwritten elements
      logical, intent(in), optional :: extendible       !! last dimension unlimited
      logical, intent(in), optional :: compress         !! shuffle + deflate (default true)
      logical, intent(in), optional :: alloc_early      !! allocate all chunks at creation
      logical, intent(in), optional :: checksum         !! Fletcher-32 checksum per chunk
      character(len=*), intent(in), optional :: units        !! 'units' attribute
      character(len=*), intent(in), optional :: description  !! 'description' attribute
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
   end subroutine file_create_dataset

   !> Write a real(dp) block (any rank, that of the dataset) into dataset `path`
   !> from index `start`.
   subroutine slab_real(self, path, array, start, error, whole_chunks)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset path
      real(dp), intent(in), target, contiguous :: array(..)  !! block to write
      integer, intent(in) :: start(:)                        !! 1-based first index
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      logical, intent(in), optional :: whole_chunks  !! see the module's header
      call slab_raw(self, path, real_type(), int(shape(array), hsize_t), start, &
         c_loc(array), error, whole_chunks)
   end subroutine slab_real

   !> `slab_real` for a default-integer block.
   subroutine slab_int(self, path, array, start, error, whole_chunks)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset path
      integer, intent(in), target, contiguous :: array(..)   !! block to write
      integer, intent(in) :: start(:)                        !! 1-based first index
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      logical, intent(in), optional :: whole_chunks  !! see the module's header
      call slab_raw(self, path, int_type(), int(shape(array), hsize_t), start, &
         c_loc(array), error, whole_chunks)
   end subroutine slab_int

   !> Write a real(dp) attribute of the value's shape on the group or dataset `path`.
   subroutine writeattr_real(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! object path, '/' for the root
      character(len=*), intent(in) :: name                   !! attribute name
      real(dp), intent(in), target, contiguous :: value(..)  !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      call writeattr_raw(self, path, name, real_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end subroutine writeattr_real

   !> Write a default-integer attribute of the value's shape on `path`.
   subroutine writeattr_int(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! object path, '/' for the root
      character(len=*), intent(in) :: name                   !! attribute name
      integer, intent(in), target, contiguous :: value(..)   !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      call writeattr_raw(self, path, name, int_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end subroutine writeattr_int

   !> Write a 64-bit integer attribute (counts that may pass 2^31 - 1) on `path`.
   subroutine writeattr_i64(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self                     !! the file object
      character(len=*), intent(in) :: path                       !! object path, '/' for the root
      character(len=*), intent(in) :: name                       !! attribute name
      integer(i8), intent(in), target, contiguous :: value(..)   !! value(s) to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      call writeattr_raw(self, path, name, i64_type(), int(shape(value), hsize_t), &
         c_loc(value), error)
   end subroutine writeattr_i64

   !> Write a string attribute on the group or dataset `path`: a variable-length
   !> UTF-8 string (h5py reads it as `str`).
   subroutine writeattr_str(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! object path, '/' for the root
      character(len=*), intent(in) :: name              !! attribute name
      character(len=*), intent(in) :: value             !! text to store
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call require_open(self, path, .true., err)
      if (.not. allocated(err)) call writeattr_vlen(self, path, name, value, err)
      call settle(self, err, error)
   end subroutine writeattr_str

   !> Write the attributes `units` and `description` (variable-length UTF-8 strings)
   !> of the dataset `path`; either may be left out. Dimensionless quantities have
   !> units '1'.
   subroutine file_describe(self, path, units, description, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset (or group) path
      character(len=*), intent(in), optional :: units        !! e.g. 'rad/s', '1'
      character(len=*), intent(in), optional :: description  !! one line of text
      type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      type(error_t), allocatable :: err
      if (.not. present(error) .and. allocated(self%error)) return
      call require_open(self, path, .true., err)
      if (.not. allocated(err)) call describe_now(self, path, err, units, description)
      call settle(self, err, error)
   end subroutine file_describe

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
      ptr = c_loc(buf)
      stype = vlen_string_type()
      call writeattr_now(self, path, name, stype, [integer(hsize_t) ::], c_loc(ptr), error)
      call close_id(stype)
   end subroutine writeattr_vlen

   ! ------------------------------------------------------------- reading ---
   ! The array readers declare their arguments and include one body each,
   ! dpend_hdf5_read.inc (a whole dataset) or dpend_hdf5_slabread.inc (a block):
   ! the element type and rank come from the declaration of `value` (`element`).

   !> Read a scalar (or one-element) numeric dataset as real(dp).
   subroutine read_real_rank0(self, path, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      real(dp), intent(out), target :: value            !! value read
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call read_one(self, path, want_real, real_type(), c_loc(value), error)
   end subroutine read_real_rank0

   !> Read a 1-D numeric dataset as real(dp); `value` takes the dataset's shape.
   subroutine read_real_rank1(self, path, value, error)
      class(h5file_t), intent(inout) :: self                  !! the file object
      character(len=*), intent(in) :: path                    !! dataset path
      real(dp), allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error        !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_real_rank1

   !> Read a 2-D numeric dataset as real(dp); `value` takes the dataset's shape.
   subroutine read_real_rank2(self, path, value, error)
      class(h5file_t), intent(inout) :: self                     !! the file object
      character(len=*), intent(in) :: path                       !! dataset path
      real(dp), allocatable, intent(out), target :: value(:, :)  !! values read
      type(error_t), allocatable, intent(out) :: error           !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_real_rank2

   !> Read a 3-D numeric dataset as real(dp); `value` takes the dataset's shape.
   subroutine read_real_rank3(self, path, value, error)
      class(h5file_t), intent(inout) :: self                        !! the file object
      character(len=*), intent(in) :: path                          !! dataset path
      real(dp), allocatable, intent(out), target :: value(:, :, :)  !! values read
      type(error_t), allocatable, intent(out) :: error              !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_real_rank3

   !> Read a scalar (or one-element) integer dataset.
   subroutine read_int_rank0(self, path, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! dataset path
      integer, intent(out), target :: value             !! value read
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call read_one(self, path, want_int, int_type(), c_loc(value), error)
   end subroutine read_int_rank0

   !> Read a 1-D integer dataset; `value` takes the dataset's shape.
   subroutine read_int_rank1(self, path, value, error)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset path
      integer, allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error       !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_int_rank1

   !> Read a 2-D integer dataset; `value` takes the dataset's shape.
   subroutine read_int_rank2(self, path, value, error)
      class(h5file_t), intent(inout) :: self                    !! the file object
      character(len=*), intent(in) :: path                      !! dataset path
      integer, allocatable, intent(out), target :: value(:, :)  !! values read
      type(error_t), allocatable, intent(out) :: error          !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_int_rank2

   !> Read a 1-D integer dataset as integer(i8); `value` takes the dataset's shape.
   subroutine read_i64_rank1(self, path, value, error)
      class(h5file_t), intent(inout) :: self                     !! the file object
      character(len=*), intent(in) :: path                       !! dataset path
      integer(i8), allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error           !! set on failure
      include 'dpend_hdf5_read.inc'
   end subroutine read_i64_rank1

   !> Read a scalar fixed-length string dataset (up to the first null byte).
   subroutine read_str(self, path, value, error)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset path
      character(len=:), allocatable, intent(out) :: value    !! text read
      type(error_t), allocatable, intent(out) :: error       !! set on failure
      call read_string(self, path, value, error)
   end subroutine read_str

   !> Read the block of `count` values from index `start` (1-based) of the 1-D
   !> numeric dataset `path` as real(dp). Only the chunks holding the block are
   !> read (and their checksums checked).
   subroutine slabread_real_rank1(self, path, start, count, value, error, check_sums)
      class(h5file_t), intent(inout) :: self                  !! the file object
      character(len=*), intent(in) :: path                    !! dataset path
      integer, intent(in) :: start(:)                         !! 1-based first index
      integer, intent(in) :: count(:)                         !! shape of the block
      real(dp), allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error        !! set on failure
      logical, intent(in), optional :: check_sums             !! see the module's header
      include 'dpend_hdf5_slabread.inc'
   end subroutine slabread_real_rank1

   !> `slabread_real_rank1` for a 2-D numeric dataset.
   subroutine slabread_real_rank2(self, path, start, count, value, error, check_sums)
      class(h5file_t), intent(inout) :: self                     !! the file object
      character(len=*), intent(in) :: path                       !! dataset path
      integer, intent(in) :: start(:)                            !! 1-based first index
      integer, intent(in) :: count(:)                            !! shape of the block
      real(dp), allocatable, intent(out), target :: value(:, :)  !! values read
      type(error_t), allocatable, intent(out) :: error           !! set on failure
      logical, intent(in), optional :: check_sums                !! see the module's header
      include 'dpend_hdf5_slabread.inc'
   end subroutine slabread_real_rank2

   !> `slabread_real_rank1` for a 1-D integer dataset.
   subroutine slabread_int_rank1(self, path, start, count, value, error, check_sums)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset path
      integer, intent(in) :: start(:)                        !! 1-based first index
      integer, intent(in) :: count(:)                        !! shape of the block
      integer, allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error       !! set on failure
      logical, intent(in), optional :: check_sums            !! see the module's header
      include 'dpend_hdf5_slabread.inc'
   end subroutine slabread_int_rank1

   !> `slabread_real_rank1` for a 2-D integer dataset.
   subroutine slabread_int_rank2(self, path, start, count, value, error, check_sums)
      class(h5file_t), intent(inout) :: self                    !! the file object
      character(len=*), intent(in) :: path                      !! dataset path
      integer, intent(in) :: start(:)                           !! 1-based first index
      integer, intent(in) :: count(:)                           !! shape of the block
      integer, allocatable, intent(out), target :: value(:, :)  !! values read
      type(error_t), allocatable, intent(out) :: error          !! set on failure
      logical, intent(in), optional :: check_sums               !! see the module's header
      include 'dpend_hdf5_slabread.inc'
   end subroutine slabread_int_rank2

   !> Read a real(dp) scalar attribute of the group or dataset `path`.
   subroutine readattr_real_rank0(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! object path, '/' for the root
      character(len=*), intent(in) :: name              !! attribute name
      real(dp), intent(out), target :: value            !! value read
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call read_one(self, path, want_real, real_type(), c_loc(value), error, name)
   end subroutine readattr_real_rank0

   !> Read a real(dp) 1-D attribute of the group or dataset `path`.
   subroutine readattr_real_rank1(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self                  !! the file object
      character(len=*), intent(in) :: path                    !! object path, '/' for the root
      character(len=*), intent(in) :: name                    !! attribute name
      real(dp), allocatable, intent(out), target :: value(:)  !! values read
      type(error_t), allocatable, intent(out) :: error        !! set on failure
      integer(hid_t) :: obj
      integer(hsize_t), allocatable :: dims(:)
      call open_read(self, path, 1, want_real, obj, dims, error, name=name)
      if (allocated(error)) return
      allocate (value(dims(1)))
      call read_obj(self, attr_label(path, name), obj, real_type(), c_loc(value), &
         size(value), error)
   end subroutine readattr_real_rank1

   !> Read an integer scalar attribute of the group or dataset `path`.
   subroutine readattr_int_rank0(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self            !! the file object
      character(len=*), intent(in) :: path              !! object path, '/' for the root
      character(len=*), intent(in) :: name              !! attribute name
      integer, intent(out), target :: value             !! value read
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call read_one(self, path, want_int, int_type(), c_loc(value), error, name)
   end subroutine readattr_int_rank0

   !> Read a string attribute (fixed- or variable-length, scalar) of the group or
   !> dataset `path`; on failure (e.g. an attribute of another type) `value` is ''.
   subroutine readattr_str(self, path, name, value, error)
      class(h5file_t), intent(inout) :: self               !! the file object
      character(len=*), intent(in) :: path                 !! object path, '/' for the root
      character(len=*), intent(in) :: name                 !! attribute name
      character(len=:), allocatable, intent(out) :: value  !! text read
      type(error_t), allocatable, intent(out) :: error     !! set on failure
      call read_string(self, path, value, error, name)
   end subroutine readattr_str

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

   ! ------------------------------------------------------------- helpers ---

   !> Start the HDF5 library once and silence its error-stack printing.
   subroutine init_library(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer :: hdferr
      hdferr = 0
      !$omp critical (dpend_hdf5_init)
      if (.not. library_ready) then
         call h5open_f(hdferr)
         library_ready = hdferr == 0
      end if
      !$omp end critical (dpend_hdf5_init)
      if (hdferr /= 0) then
         call fatal_error(error, 'cannot initialise the HDF5 library')
         return
      end if
      call quiet_thread()
   end subroutine init_library

   !> Turn off HDF5's error printing in the calling thread (once per thread), so
   !> that its error stack never reaches the user: failures come back as error_t.
   subroutine quiet_thread()
      integer :: ierr
      if (thread_quiet .or. .not. library_ready) return
      call h5eset_auto_f(0, ierr)
      thread_quiet = ierr == 0
   end subroutine quiet_thread

   !> Memory and file type of real(dp).
   integer(hid_t) function real_type()
      real_type = h5kind_to_type(real64, H5_REAL_KIND)
   end function real_type

   !> Memory and file type of default integers.
   integer(hid_t) function int_type()
      int_type = h5kind_to_type(kind(0), H5_INTEGER_KIND)
   end function int_type

   !> Memory and file type of integer(i8).
   integer(hid_t) function i64_type()
      i64_type = h5kind_to_type(i8, H5_INTEGER_KIND)
   end function i64_type

   !> A new fixed-length, null-padded ASCII string type of `length` bytes (>= 1).
   integer(hid_t) function string_type(length) result(stype)
      integer, intent(in) :: length  !! bytes per string
      integer :: ierr
      call h5tcopy_f(H5T_NATIVE_CHARACTER, stype, ierr)
      call h5tset_size_f(stype, int(max(1, length), size_t), ierr)
      call h5tset_strpad_f(stype, H5T_STR_NULLPAD_F, ierr)
   end function string_type

   !> A new variable-length, null-terminated UTF-8 string type.
   integer(hid_t) function vlen_string_type() result(stype)
      integer :: ierr
      call h5tcopy_f(H5T_STRING, stype, ierr)
      call h5tset_cset_f(stype, H5T_CSET_UTF8_F, ierr)
   end function vlen_string_type

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

   !> Close any HDF5 identifier we own and set it to -1.
   subroutine close_id(id)
      integer(hid_t), intent(inout) :: id  !! dataset, space, type, attribute or plist
      integer :: id_type, ierr
      if (id < 0) return
      call h5iget_type_f(id, id_type, ierr)
      if (ierr /= 0) id_type = H5I_BADID_F
      if (id_type == H5I_DATASET_F) call h5dclose_f(id, ierr)
      if (id_type == H5I_DATASPACE_F) call h5sclose_f(id, ierr)
      if (id_type == H5I_DATATYPE_F) call h5tclose_f(id, ierr)
      if (id_type == H5I_ATTR_F) call h5aclose_f(id, ierr)
      if (id_type == H5I_GROUP_F) call h5gclose_f(id, ierr)
      if (id_type == H5I_GENPROP_LST_F) call h5pclose_f(id, ierr)
      id = -1
   end subroutine close_id

   !> `text` in single quotes.
   pure function quoted(text) result(q)
      character(len=*), intent(in) :: text  !! e.g. a path
      character(len=:), allocatable :: q
      q = "'"//trim(text)//"'"
   end function quoted

   !> "attribute 'name' of 'path'", used in messages.
   pure function attr_label(path, name) result(text)
      character(len=*), intent(in) :: path  !! object path
      character(len=*), intent(in) :: name  !! attribute name
      character(len=:), allocatable :: text
      text = "attribute '"//trim(name)//"' of '"//trim(path)//"'"
   end function attr_label

   !> `attr_label(path, name)` if `name` is present, else `quoted(path)`.
   pure function label(path, name) result(text)
      character(len=*), intent(in) :: path            !! object path
      character(len=*), intent(in), optional :: name  !! attribute name
      character(len=:), allocatable :: text
      if (present(name)) then
         text = attr_label(path, name)
      else
         text = quoted(path)
      end if
   end function label

   !> Set `error` to "cannot <verb> <what> in '<file>': <why>".
   subroutine fail(error, verb, self, what, why)
      type(error_t), allocatable, intent(out) :: error  !! the error to create
      character(len=*), intent(in) :: verb              !! e.g. 'read'
      class(h5file_t), intent(in) :: self               !! the file object
      character(len=*), intent(in) :: what              !! quoted path or attr_label
      character(len=*), intent(in) :: why               !! the reason
      if (allocated(self%filename)) then
         if (verb == 'write' .or. verb == 'create') then
            call fatal_error(error, 'cannot '//verb//' '//what//' in '//quoted(self%filename) &
               //': '//io_failure_reason(self%filename, why))
         else
            call fatal_error(error, 'cannot '//verb//' '//what//' in '//quoted(self%filename) &
               //': '//why)
         end if
      else
         call fatal_error(error, 'cannot '//verb//' '//what//': '//why)
      end if
   end subroutine fail

   !> Fail unless a file is open (and writable when `write` is true).
   subroutine require_open(self, path, write, error)
      class(h5file_t), intent(in) :: self               !! the file object
      character(len=*), intent(in) :: path              !! path, for the message
      logical, intent(in) :: write                      !! writing is intended
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      if (self%is_open()) call quiet_thread()
      if (.not. self%is_open()) then
         call fatal_error(error, 'cannot access '//quoted(path)//': no HDF5 file is open')
      else if (write .and. self%readonly) then
         call fail(error, 'write', self, quoted(path), 'file is open read-only')
      end if
   end subroutine require_open

   !> Shape (Fortran order) and optionally maximum shape of dataspace `space`.
   subroutine space_dims(space, dims, maxdims)
      integer(hid_t), intent(in) :: space                                !! dataspace id
      integer(hsize_t), allocatable, intent(out) :: dims(:)              !! shape
      integer(hsize_t), allocatable, intent(out), optional :: maxdims(:) !! maximum shape
      integer(hsize_t), allocatable :: maxd(:)
      integer :: rank, ierr
      call h5sget_simple_extent_ndims_f(space, rank, ierr)
      allocate (dims(max(rank, 0)), maxd(max(rank, 0)))
      if (rank > 0) call h5sget_simple_extent_dims_f(space, dims, maxd, ierr)
      if (present(maxdims)) maxdims = maxd
   end subroutine space_dims

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

   !> Open dataset `path`, or with `name` its attribute, for reading; check that it
   !> holds what `want` asks for, with rank `rank` (0: one element, -1: any), and,
   !> unless `whole` is false (a block read: the caller sizes the block), that
   !> reading all of it fits the limits before anything is allocated: at most
   !> `max_read_values` values (`max_string_bytes` bytes for a string), in the
   !> machine's available memory (`check_read_size`).
   subroutine open_read(self, path, rank, want, obj, dims, error, name, length, variable, &
                        whole)
      class(h5file_t), intent(inout) :: self                 !! the file object
      character(len=*), intent(in) :: path                   !! dataset or object path
      integer, intent(in) :: rank                            !! expected rank
      integer, intent(in) :: want                            !! want_any/_real/_int/_str
      integer(hid_t), intent(out) :: obj                     !! open dataset or attribute
      integer(hsize_t), allocatable, intent(out) :: dims(:)  !! its shape
      type(error_t), allocatable, intent(out) :: error       !! set on failure
      character(len=*), intent(in), optional :: name         !! attribute name
      integer, intent(out), optional :: length               !! string size in bytes
      logical, intent(out), optional :: variable             !! a variable-length string
      logical, intent(in), optional :: whole                 !! all of it is read (default)
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
   end subroutine open_read

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

   !> Paths of all datasets in the group `group` and the groups below it, in name
   !> order (groups before the datasets they hold come in their place).
   subroutine file_datasets(self, group, paths, error)
      class(h5file_t), intent(inout) :: self                       !! the file object
      character(len=*), intent(in) :: group                        !! e.g. '/' or '/sweep'
      character(len=:), allocatable, intent(out) :: paths(:)      !! dataset paths
      type(error_t), allocatable, intent(out) :: error             !! set on failure
      character(len=1024), allocatable :: found(:)
      integer :: n, i, width
      allocate (found(16))
      n = 0
      call require_open(self, group, .false., error)
      if (allocated(error)) return
      if (.not. self%exists(group)) then
         call fail(error, 'list', self, quoted(group), 'no such group')
         return
      end if
      call visit(trim(group))
      if (allocated(error)) return
      width = 1
      do i = 1, n
         width = max(width, len_trim(found(i)))
      end do
      allocate (character(len=width) :: paths(n))
      do i = 1, n
         paths(i) = found(i)
      end do
   contains
      !> Append the datasets of group `g` and of the groups below it.
      recursive subroutine visit(g)
         character(len=*), intent(in) :: g
         character(len=1024) :: name
         character(len=:), allocatable :: child
         character(len=1024), allocatable :: more(:)
         integer(hid_t) :: obj
         integer(size_t) :: name_len
         integer :: storage, nlinks, max_corder, ierr, id_type, k
         call h5gget_info_by_name_f(self%id, g, storage, nlinks, max_corder, ierr)
         if (ierr /= 0) then
            call fail(error, 'list', self, quoted(g), 'not a group')
            return
         end if
         do k = 0, nlinks - 1
            name = ''
            call h5lget_name_by_idx_f(self%id, g, H5_INDEX_NAME_F, H5_ITER_INC_F, &
               int(k, hsize_t), name, ierr, name_len)
            if (ierr /= 0) cycle
            if (g == '/') then
               child = '/'//name(1:min(int(name_len), len(name)))
            else
               child = g//'/'//name(1:min(int(name_len), len(name)))
            end if
            call h5oopen_f(self%id, child, obj, ierr)
            if (ierr /= 0) cycle
            call h5iget_type_f(obj, id_type, ierr)
            call h5oclose_f(obj, ierr)
            if (id_type == H5I_GROUP_F) then
               call visit(child)
               if (allocated(error)) return
            else if (id_type == H5I_DATASET_F) then
               if (n == size(found)) then
                  allocate (more(2*n))
                  more(1:n) = found
                  call move_alloc(more, found)
               end if
               n = n + 1
               found(n) = child
            end if
         end do
      end subroutine visit
   end subroutine file_datasets
end module dpend_hdf5
