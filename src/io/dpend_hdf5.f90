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
!> and a chunk torn by a kill during an earlier write is simply rewritten. Chunks
!> of a dataset without filters, in a file opened without an access list, are
!> written as stored (H5Dwrite_chunk, in place): no selection, copy or cache.
!> `read_slab(..., check_sums=.false.)` reads a block without verifying checksums
!> (the chunk index is still read): for blocks that will be rewritten so.
!> `write`, `write_slab` and `writeattr` take real(dp), default-integer and
!> integer(i8) values of any rank (a scalar too); `read` and `read_slab` fill
!> allocatable arrays of rank 1 to 3 (one body, dpend_hdf5_read.inc and
!> dpend_hdf5_slabread.inc, included by each reader), and one-element scalars.
!> HDF5 here is the serial library (the parallel one in the MPI build, mpi/): use
!> an `h5file_t` from one thread at a time.
!>
!> This module holds the type, the interfaces of the procedures its submodules
!> implement and a few small procedures; the submodules hold the rest:
!> dpend_hdf5_file (open, close, flush; exists, attr_exists, shape, filters,
!> chunks, datasets), dpend_hdf5_write (write, create_dataset, write_slab, write_chunked,
!> writeattr, describe), dpend_hdf5_read (read, read_slab, readattr) and dpend_hdf5_common
!> (the helpers they share). A helper shared by submodules has its interface here
!> and its body in a submodule: gfortran gives a private procedure of the module
!> itself internal linkage, so a submodule could not call it.
module dpend_hdf5
   ! the submodules have these names too, by host association
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char, c_null_ptr, &
      c_associated, c_f_pointer, c_size_t
   use, intrinsic :: iso_fortran_env, only: real64, int32, int64, int8
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use hdf5
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_os, only: io_failure_reason, capturing_outputs, capture_buffer
   use dpend_output_record, only: record_t, recording_outputs, keep_record, item_real, &
      item_integer, item_string, item_text
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
   !> The deflate level of compressed datasets (`create_dataset`), chosen by
   !> measurement (docs/performance.md, "A map's file"): level 1 against level 4 on
   !> a sweep's results, files 1 to 2 % larger, compression a fifth faster.
   integer, parameter :: deflate_level = 1

   !> What a read accepts in the file: anything, numbers, integers, a string.
   integer, parameter :: want_any = 0, want_real = 1, want_int = 2, want_str = 3

   !> A dataset whose whole chunks `write_slab` writes as stored, kept open with
   !> what the writes check: its type, shape and chunk shape (rank 1 or 2).
   type :: stored_dataset_t
      character(len=:), allocatable :: path      !! its path
      integer(hid_t) :: dset = -1                !! open dataset, -1: not eligible
      integer(hid_t) :: dtype = -1               !! its type, open
      integer :: rank = 0                        !! 1 or 2
      integer(hsize_t) :: dims(2) = 1            !! its fixed shape
      integer(hsize_t) :: chunk(2) = 1           !! its chunk shape
      integer(size_t) :: esize = 0               !! bytes per element
   end type stored_dataset_t

   !> One open HDF5 file. Do not copy an open `h5file_t`: the copy shares the id.
   type :: h5file_t
      private
      character(len=:), allocatable :: filename  !! name given to `open`
      integer(hid_t) :: id = -1                  !! HDF5 file id, -1 when closed
      logical :: readonly = .false.              !! opened with mode 'r'
      !> created in memory (a captured output, `capture_outputs`): its image is kept
      !> when it is closed
      logical :: memory = .false.
      !> recorded, not written (`record_outputs`): whole datasets and attributes only;
      !> the record is kept when the file is closed
      type(record_t), allocatable :: record
      !> first failure of a write called without `error` (see `take_error`)
      type(error_t), allocatable :: error
      !> a file on disk opened with the default access (not MPI-IO): whole unfiltered
      !> chunks are written as stored (`write_slab` with `whole_chunks`)
      logical :: direct = .false.
      !> the datasets so written, kept open until a dataset is created or replaced,
      !> or the file closed (`forget_stored`)
      type(stored_dataset_t), allocatable :: stored(:)
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
      procedure :: chunks => file_chunks
      procedure :: create_dataset => file_create_dataset
      procedure :: describe => file_describe
      procedure :: datasets => file_datasets
      procedure :: replay => file_replay
      procedure :: to_record => file_record
      procedure, private :: write_real, write_int, write_i64, write_str
      generic :: write => write_real, write_int, write_i64, write_str
      procedure, private :: slab_real, slab_int
      generic :: write_slab => slab_real, slab_int
      procedure, private :: chunked_real, chunked_int
      generic :: write_chunked => chunked_real, chunked_int
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

   ! dpend_hdf5_file: open, close, flush, and what the file holds.
   interface
      !> Open `filename`: 'r' read only, 'w' create or truncate, 'rw' read-write
      !> (created if missing), 'x' create and fail if it exists. An open file is
      !> closed first. `access` is a file access property list to start from (e.g.
      !> one set up for MPI-IO by a parallel HDF5 program; then open and close are
      !> collective); it is copied, not kept.
      module subroutine file_open(self, filename, mode, error, access)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: filename          !! path on disk
         character(len=*), intent(in) :: mode              !! 'r', 'w', 'rw' or 'x'
         type(error_t), allocatable, intent(out) :: error  !! set on failure
         integer(hid_t), intent(in), optional :: access    !! file access property list
      end subroutine file_open

      !> Close the file if it is open (this also flushes it). With `error`: the kept
      !> failure of a write (see `take_error`), else a failed close (e.g. a full disk
      !> while flushing). Without, a kept failure is dropped.
      module subroutine file_close(self, error)
         class(h5file_t), intent(inout) :: self                      !! the file object
         type(error_t), allocatable, intent(out), optional :: error  !! a write or the close failed
      end subroutine file_close

      !> Flush everything written so far to disk (whole file).
      module subroutine file_flush(self)
         class(h5file_t), intent(inout) :: self  !! the file object
      end subroutine file_flush

      !> True if the group or dataset `path` exists: every component is checked.
      logical module function file_exists(self, path) result(found)
         class(h5file_t), intent(in) :: self   !! the file object
         character(len=*), intent(in) :: path  !! e.g. '/trajectory/q', '/' for the root
      end function file_exists

      !> True if the group or dataset `path` carries an attribute `name`.
      logical module function file_attr_exists(self, path, name) result(found)
         class(h5file_t), intent(in) :: self   !! the file object
         character(len=*), intent(in) :: path  !! group or dataset, '/' for the root
         character(len=*), intent(in) :: name  !! attribute name
      end function file_attr_exists

      !> Shape of dataset `path` in Fortran order (size 0 for a scalar). A dimension
      !> beyond a default integer (a file from elsewhere may declare 2^40) is refused.
      module subroutine file_shape(self, path, dims, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         integer, allocatable, intent(out) :: dims(:)      !! its shape
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine file_shape

      !> Number of filters (compression, shuffle, checksum) in the pipeline of dataset
      !> `path` (0 for a contiguous or unfiltered chunked dataset).
      module subroutine file_filters(self, path, n, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         integer, intent(out) :: n                         !! its filters
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine file_filters

      !> Number of chunks stored (allocated) for dataset `path`, its chunk index read
      !> whole (0 for a contiguous dataset).
      module subroutine file_chunks(self, path, n, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         integer(i8), intent(out) :: n                     !! its chunks
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine file_chunks

      !> Paths of all datasets in the group `group` and the groups below it, in name
      !> order (groups before the datasets they hold come in their place).
      module subroutine file_datasets(self, group, paths, error)
         class(h5file_t), intent(inout) :: self                       !! the file object
         character(len=*), intent(in) :: group                        !! e.g. '/' or '/sweep'
         character(len=:), allocatable, intent(out) :: paths(:)      !! dataset paths
         type(error_t), allocatable, intent(out) :: error             !! set on failure
      end subroutine file_datasets
   end interface

   ! dpend_hdf5_write: datasets, blocks and attributes written.
   interface
      !> Write a real(dp) dataset of the value's shape (a scalar: a scalar dataset).
      module subroutine write_real(self, path, value, error, units, description)
         class(h5file_t), intent(inout) :: self                       !! the file object
         character(len=*), intent(in) :: path                         !! dataset path
         real(dp), intent(in), target, contiguous :: value(..)        !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         character(len=*), intent(in), optional :: units        !! 'units' attribute
         character(len=*), intent(in), optional :: description  !! 'description' attribute
      end subroutine write_real

      !> Write a default-integer dataset of the value's shape.
      module subroutine write_int(self, path, value, error, units, description)
         class(h5file_t), intent(inout) :: self                       !! the file object
         character(len=*), intent(in) :: path                         !! dataset path
         integer, intent(in), target, contiguous :: value(..)         !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         character(len=*), intent(in), optional :: units        !! 'units' attribute
         character(len=*), intent(in), optional :: description  !! 'description' attribute
      end subroutine write_int

      !> Write an integer(i8) dataset of the value's shape (stored as 64-bit integers).
      module subroutine write_i64(self, path, value, error, units, description)
         class(h5file_t), intent(inout) :: self                       !! the file object
         character(len=*), intent(in) :: path                         !! dataset path
         integer(i8), intent(in), target, contiguous :: value(..)     !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         character(len=*), intent(in), optional :: units        !! 'units' attribute
         character(len=*), intent(in), optional :: description  !! 'description' attribute
      end subroutine write_i64

      !> Write a scalar fixed-length string dataset (stored exactly, trailing blanks kept).
      module subroutine write_str(self, path, value, error, units, description)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         character(len=*), intent(in) :: value             !! text to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         character(len=*), intent(in), optional :: units        !! 'units' attribute
         character(len=*), intent(in), optional :: description  !! 'description' attribute
      end subroutine write_str

      !> Create a chunked dataset of shape `dims` for partial writes with `write_slab`,
      !> compressed with shuffle + deflate (`deflate_level`) when the filters are available.
      !> An existing dataset at `path` is replaced. Unwritten elements read as `fill`
      !> (default 0; rounded with `nint` for 'int32'). With `extendible`, the
      !> last dimension is unlimited and `write_slab` grows it as needed. With
      !> `compress` false no filter is set; with `alloc_early` every chunk is allocated
      !> now, so that later writes change no metadata (crash-safe updates), and not
      !> written: until written, its elements read as what the file holds there (a
      !> sparse file's zeros, whose checksum does not match), not as `fill`.
      !> With `checksum`, every chunk carries a Fletcher-32 checksum (filter applied
      !> last, size fixed: a rewrite stays in place), and reading a damaged chunk fails.
      module subroutine file_create_dataset(self, path, dtype, dims, chunk, error, fill, &
                                            extendible, compress, alloc_early, checksum, units, &
                                            description)
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
      end subroutine file_create_dataset

      !> Write a real(dp) block (any rank, that of the dataset) into dataset `path`
      !> from index `start`.
      module subroutine slab_real(self, path, array, start, error, whole_chunks)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         real(dp), intent(in), target, contiguous :: array(..)  !! block to write
         integer, intent(in) :: start(:)                        !! 1-based first index
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         logical, intent(in), optional :: whole_chunks  !! see the module's header
      end subroutine slab_real

      !> `slab_real` for a default-integer block.
      module subroutine slab_int(self, path, array, start, error, whole_chunks)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         integer, intent(in), target, contiguous :: array(..)   !! block to write
         integer, intent(in) :: start(:)                        !! 1-based first index
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
         logical, intent(in), optional :: whole_chunks  !! see the module's header
      end subroutine slab_int

      !> Write the whole of the fixed-size chunked dataset `path` (rank 1 or 2) from
      !> `array`, of its shape. A dataset stored with the filters `create_dataset`
      !> sets (shuffle, deflate, and a Fletcher-32 checksum or not) has its chunks
      !> encoded here, on every OpenMP thread (dpend_chunk_codec.c: the bytes HDF5's
      !> filters would store), and written as stored (H5Dwrite_chunk); any other
      !> dataset, and a recorded file, is written through HDF5's filters in one
      !> thread (`write_slab`). Either way the file reads back the same values.
      module subroutine chunked_real(self, path, array, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         real(dp), intent(in), target, contiguous :: array(..)  !! its whole contents
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine chunked_real

      !> `chunked_real` for a default-integer dataset.
      module subroutine chunked_int(self, path, array, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         integer, intent(in), target, contiguous :: array(..)   !! its whole contents
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine chunked_int

      !> Write a real(dp) attribute of the value's shape on the group or dataset `path`.
      module subroutine writeattr_real(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! object path, '/' for the root
         character(len=*), intent(in) :: name                   !! attribute name
         real(dp), intent(in), target, contiguous :: value(..)  !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine writeattr_real

      !> Write a default-integer attribute of the value's shape on `path`.
      module subroutine writeattr_int(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! object path, '/' for the root
         character(len=*), intent(in) :: name                   !! attribute name
         integer, intent(in), target, contiguous :: value(..)   !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine writeattr_int

      !> Write a 64-bit integer attribute (counts that may pass 2^31 - 1) on `path`.
      module subroutine writeattr_i64(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self                     !! the file object
         character(len=*), intent(in) :: path                       !! object path, '/' for the root
         character(len=*), intent(in) :: name                       !! attribute name
         integer(i8), intent(in), target, contiguous :: value(..)   !! value(s) to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine writeattr_i64

      !> Write a string attribute on the group or dataset `path`: a variable-length
      !> UTF-8 string (h5py reads it as `str`).
      module subroutine writeattr_str(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! object path, '/' for the root
         character(len=*), intent(in) :: name              !! attribute name
         character(len=*), intent(in) :: value             !! text to store
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine writeattr_str

      !> The record of this open file, every dataset and attribute in HDF5's name
      !> order, depth first: the root's attributes, then each child (a group's
      !> attributes and its children; a dataset, then its attributes). Sizes are
      !> checked before anything is read.
      module subroutine file_record(self, record, error)
         class(h5file_t), intent(inout) :: self               !! the file object
         type(record_t), allocatable, intent(out) :: record   !! what it holds
         type(error_t), allocatable, intent(out) :: error     !! unreadable or too big
      end subroutine file_record

      !> Write the items of `record` (a recorded file's writes, in order) into this
      !> open file: the file the recorded writes would have made.
      module subroutine file_replay(self, record, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         type(record_t), intent(in), target :: record      !! what was recorded
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine file_replay

      !> Write the attributes `units` and `description` (variable-length UTF-8 strings)
      !> of the dataset `path`; either may be left out. Dimensionless quantities have
      !> units '1'.
      module subroutine file_describe(self, path, units, description, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset (or group) path
         character(len=*), intent(in), optional :: units        !! e.g. 'rad/s', '1'
         character(len=*), intent(in), optional :: description  !! one line of text
         type(error_t), allocatable, intent(out), optional :: error  !! see `take_error`
      end subroutine file_describe
   end interface

   ! dpend_hdf5_read: datasets, blocks and attributes read; `open_read` also
   ! serves `shape` and `filters`.
   interface
      !> Read a scalar (or one-element) numeric dataset as real(dp).
      module subroutine read_real_rank0(self, path, value, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         real(dp), intent(out), target :: value            !! value read
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine read_real_rank0

      !> Read a 1-D numeric dataset as real(dp); `value` takes the dataset's shape.
      module subroutine read_real_rank1(self, path, value, error)
         class(h5file_t), intent(inout) :: self                  !! the file object
         character(len=*), intent(in) :: path                    !! dataset path
         real(dp), allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error        !! set on failure
      end subroutine read_real_rank1

      !> Read a 2-D numeric dataset as real(dp); `value` takes the dataset's shape.
      module subroutine read_real_rank2(self, path, value, error)
         class(h5file_t), intent(inout) :: self                     !! the file object
         character(len=*), intent(in) :: path                       !! dataset path
         real(dp), allocatable, intent(out), target :: value(:, :)  !! values read
         type(error_t), allocatable, intent(out) :: error           !! set on failure
      end subroutine read_real_rank2

      !> Read a 3-D numeric dataset as real(dp); `value` takes the dataset's shape.
      module subroutine read_real_rank3(self, path, value, error)
         class(h5file_t), intent(inout) :: self                        !! the file object
         character(len=*), intent(in) :: path                          !! dataset path
         real(dp), allocatable, intent(out), target :: value(:, :, :)  !! values read
         type(error_t), allocatable, intent(out) :: error              !! set on failure
      end subroutine read_real_rank3

      !> Read a scalar (or one-element) integer dataset.
      module subroutine read_int_rank0(self, path, value, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! dataset path
         integer, intent(out), target :: value             !! value read
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine read_int_rank0

      !> Read a 1-D integer dataset; `value` takes the dataset's shape.
      module subroutine read_int_rank1(self, path, value, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         integer, allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error       !! set on failure
      end subroutine read_int_rank1

      !> Read a 2-D integer dataset; `value` takes the dataset's shape.
      module subroutine read_int_rank2(self, path, value, error)
         class(h5file_t), intent(inout) :: self                    !! the file object
         character(len=*), intent(in) :: path                      !! dataset path
         integer, allocatable, intent(out), target :: value(:, :)  !! values read
         type(error_t), allocatable, intent(out) :: error          !! set on failure
      end subroutine read_int_rank2

      !> Read a 1-D integer dataset as integer(i8); `value` takes the dataset's shape.
      module subroutine read_i64_rank1(self, path, value, error)
         class(h5file_t), intent(inout) :: self                     !! the file object
         character(len=*), intent(in) :: path                       !! dataset path
         integer(i8), allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error           !! set on failure
      end subroutine read_i64_rank1

      !> Read a scalar fixed-length string dataset (up to the first null byte).
      module subroutine read_str(self, path, value, error)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         character(len=:), allocatable, intent(out) :: value    !! text read
         type(error_t), allocatable, intent(out) :: error       !! set on failure
      end subroutine read_str

      !> Read the block of `count` values from index `start` (1-based) of the 1-D
      !> numeric dataset `path` as real(dp). Only the chunks holding the block are
      !> read (and their checksums checked).
      module subroutine slabread_real_rank1(self, path, start, count, value, error, check_sums)
         class(h5file_t), intent(inout) :: self                  !! the file object
         character(len=*), intent(in) :: path                    !! dataset path
         integer, intent(in) :: start(:)                         !! 1-based first index
         integer, intent(in) :: count(:)                         !! shape of the block
         real(dp), allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error        !! set on failure
         logical, intent(in), optional :: check_sums             !! see the module's header
      end subroutine slabread_real_rank1

      !> `slabread_real_rank1` for a 2-D numeric dataset.
      module subroutine slabread_real_rank2(self, path, start, count, value, error, check_sums)
         class(h5file_t), intent(inout) :: self                     !! the file object
         character(len=*), intent(in) :: path                       !! dataset path
         integer, intent(in) :: start(:)                            !! 1-based first index
         integer, intent(in) :: count(:)                            !! shape of the block
         real(dp), allocatable, intent(out), target :: value(:, :)  !! values read
         type(error_t), allocatable, intent(out) :: error           !! set on failure
         logical, intent(in), optional :: check_sums                !! see the module's header
      end subroutine slabread_real_rank2

      !> `slabread_real_rank1` for a 1-D integer dataset.
      module subroutine slabread_int_rank1(self, path, start, count, value, error, check_sums)
         class(h5file_t), intent(inout) :: self                 !! the file object
         character(len=*), intent(in) :: path                   !! dataset path
         integer, intent(in) :: start(:)                        !! 1-based first index
         integer, intent(in) :: count(:)                        !! shape of the block
         integer, allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error       !! set on failure
         logical, intent(in), optional :: check_sums            !! see the module's header
      end subroutine slabread_int_rank1

      !> `slabread_real_rank1` for a 2-D integer dataset.
      module subroutine slabread_int_rank2(self, path, start, count, value, error, check_sums)
         class(h5file_t), intent(inout) :: self                    !! the file object
         character(len=*), intent(in) :: path                      !! dataset path
         integer, intent(in) :: start(:)                           !! 1-based first index
         integer, intent(in) :: count(:)                           !! shape of the block
         integer, allocatable, intent(out), target :: value(:, :)  !! values read
         type(error_t), allocatable, intent(out) :: error          !! set on failure
         logical, intent(in), optional :: check_sums               !! see the module's header
      end subroutine slabread_int_rank2

      !> Read a real(dp) scalar attribute of the group or dataset `path`.
      module subroutine readattr_real_rank0(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! object path, '/' for the root
         character(len=*), intent(in) :: name              !! attribute name
         real(dp), intent(out), target :: value            !! value read
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine readattr_real_rank0

      !> Read a real(dp) 1-D attribute of the group or dataset `path`.
      module subroutine readattr_real_rank1(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self                  !! the file object
         character(len=*), intent(in) :: path                    !! object path, '/' for the root
         character(len=*), intent(in) :: name                    !! attribute name
         real(dp), allocatable, intent(out), target :: value(:)  !! values read
         type(error_t), allocatable, intent(out) :: error        !! set on failure
      end subroutine readattr_real_rank1

      !> Read an integer scalar attribute of the group or dataset `path`.
      module subroutine readattr_int_rank0(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self            !! the file object
         character(len=*), intent(in) :: path              !! object path, '/' for the root
         character(len=*), intent(in) :: name              !! attribute name
         integer, intent(out), target :: value             !! value read
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine readattr_int_rank0

      !> Read a string attribute (fixed- or variable-length, scalar) of the group or
      !> dataset `path`; on failure (e.g. an attribute of another type) `value` is ''.
      module subroutine readattr_str(self, path, name, value, error)
         class(h5file_t), intent(inout) :: self               !! the file object
         character(len=*), intent(in) :: path                 !! object path, '/' for the root
         character(len=*), intent(in) :: name                 !! attribute name
         character(len=:), allocatable, intent(out) :: value  !! text read
         type(error_t), allocatable, intent(out) :: error     !! set on failure
      end subroutine readattr_str

      !> Open dataset `path`, or with `name` its attribute, for reading; check that it
      !> holds what `want` asks for, with rank `rank` (0: one element, -1: any), and,
      !> unless `whole` is false (a block read: the caller sizes the block), that
      !> reading all of it fits the limits before anything is allocated: at most
      !> `max_read_values` values (`max_string_bytes` bytes for a string), in the
      !> machine's available memory (`check_read_size`).
      module subroutine open_read(self, path, rank, want, obj, dims, error, name, length, &
                                  variable, whole)
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
      end subroutine open_read
   end interface

   ! dpend_hdf5_common: the helpers the submodules share.
   interface
      !> Start the HDF5 library once and silence its error-stack printing.
      module subroutine init_library(error)
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine init_library

      !> Turn off HDF5's error printing in the calling thread (once per thread), so
      !> that its error stack never reaches the user: failures come back as error_t.
      module subroutine quiet_thread()
      end subroutine quiet_thread

      !> Memory and file type of real(dp).
      integer(hid_t) module function real_type()
      end function real_type

      !> Memory and file type of default integers.
      integer(hid_t) module function int_type()
      end function int_type

      !> Memory and file type of integer(i8).
      integer(hid_t) module function i64_type()
      end function i64_type

      !> A new fixed-length, null-padded ASCII string type of `length` bytes (>= 1).
      integer(hid_t) module function string_type(length) result(stype)
         integer, intent(in) :: length  !! bytes per string
      end function string_type

      !> A new variable-length, null-terminated UTF-8 string type.
      integer(hid_t) module function vlen_string_type() result(stype)
      end function vlen_string_type

      !> Close any HDF5 identifier we own and set it to -1.
      !> Close the datasets kept open for `write_slab`'s writes as stored.
      module subroutine forget_stored(self)
         class(h5file_t), intent(inout) :: self  !! the file object
      end subroutine forget_stored

      module subroutine close_id(id)
         integer(hid_t), intent(inout) :: id  !! dataset, space, type, attribute or plist
      end subroutine close_id

      !> `text` in single quotes.
      pure module function quoted(text) result(q)
         character(len=*), intent(in) :: text  !! e.g. a path
         character(len=:), allocatable :: q
      end function quoted

      !> "attribute 'name' of 'path'", used in messages.
      pure module function attr_label(path, name) result(text)
         character(len=*), intent(in) :: path  !! object path
         character(len=*), intent(in) :: name  !! attribute name
         character(len=:), allocatable :: text
      end function attr_label

      !> `attr_label(path, name)` if `name` is present, else `quoted(path)`.
      pure module function label(path, name) result(text)
         character(len=*), intent(in) :: path            !! object path
         character(len=*), intent(in), optional :: name  !! attribute name
         character(len=:), allocatable :: text
      end function label

      !> Set `error` to "cannot <verb> <what> in '<file>': <why>".
      module subroutine fail(error, verb, self, what, why)
         type(error_t), allocatable, intent(out) :: error  !! the error to create
         character(len=*), intent(in) :: verb              !! e.g. 'read'
         class(h5file_t), intent(in) :: self               !! the file object
         character(len=*), intent(in) :: what              !! quoted path or attr_label
         character(len=*), intent(in) :: why               !! the reason
      end subroutine fail

      !> Fail unless a file is open (and writable when `write` is true).
      module subroutine require_open(self, path, write, error)
         class(h5file_t), intent(in) :: self               !! the file object
         character(len=*), intent(in) :: path              !! path, for the message
         logical, intent(in) :: write                      !! writing is intended
         type(error_t), allocatable, intent(out) :: error  !! set on failure
      end subroutine require_open

      !> Shape (Fortran order) and optionally maximum shape of dataspace `space`.
      module subroutine space_dims(space, dims, maxdims)
         integer(hid_t), intent(in) :: space                                !! dataspace id
         integer(hsize_t), allocatable, intent(out) :: dims(:)              !! shape
         integer(hsize_t), allocatable, intent(out), optional :: maxdims(:) !! maximum shape
      end subroutine space_dims
   end interface

contains

   ! ---------------------------------------------------------------- file ---

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
      is_open = self%id >= 0 .or. allocated(self%record)
   end function file_is_open

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
end module dpend_hdf5
