!> Tests of `dpend_hdf5`: round trips of every written type and shape, attributes,
!> slab writes, overwrites, `exists`, a given file access list, the errors of
!> missing files and datasets, and the failure kept by writes made without `error`.
module test_hdf5
   use dpend_kinds, only: dp, i8
   use dpend_hdf5, only: h5file_t, is_hdf5
   use hdf5, only: hid_t, size_t, H5P_FILE_ACCESS_F, h5open_f, h5pcreate_f, h5pclose_f, &
      h5pset_fapl_core_f, hsize_t, H5F_ACC_TRUNC_F, H5P_DATASET_CREATE_F, H5T_IEEE_F64LE, &
      H5T_STD_I32LE, H5T_NATIVE_INTEGER, h5fcreate_f, h5fclose_f, h5screate_simple_f, &
      h5sclose_f, h5pset_chunk_f, h5dcreate_f, h5dclose_f, h5acreate_f, h5awrite_f, &
      h5aclose_f, h5fopen_f, H5F_ACC_RDONLY_F, h5dopen_f, h5dget_storage_size_f
   use, intrinsic :: iso_c_binding, only: c_loc, c_ptr
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
   use dpend_strings, only: to_str
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error
   use test_cli, only: run_command, scratch_dir
   use dpend_export, only: export_columns
   implicit none
   private
   public :: collect_hdf5

contains

   !> The hdf5 test suite.
   subroutine collect_hdf5(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
         new_unittest('hdf5_real_roundtrip', test_real_roundtrip), &
         new_unittest('hdf5_int_roundtrip', test_int_roundtrip), &
         new_unittest('hdf5_string_roundtrip', test_string_roundtrip), &
         new_unittest('hdf5_attributes', test_attributes), &
         new_unittest('hdf5_slabs', test_slabs), &
         new_unittest('hdf5_chunks_encoded_here', test_chunks_encoded_here), &
         new_unittest('hdf5_extendible', test_extendible), &
         new_unittest('hdf5_overwrite', test_overwrite), &
         new_unittest('hdf5_exists', test_exists), &
         new_unittest('hdf5_missing_file', test_missing_file), &
         new_unittest('hdf5_missing_dataset', test_missing_dataset), &
         new_unittest('hdf5_modes', test_modes), &
         new_unittest('hdf5_kept_error', test_kept_error), &
         new_unittest('hdf5_is_hdf5', test_is_hdf5), &
         new_unittest('hdf5_finalizer', test_finalizer), &
         new_unittest('hdf5_access_list', test_access_list), &
         new_unittest('hdf5_declared_sizes', test_declared_sizes), &
         new_unittest('hdf5_attribute_types', test_attribute_types), &
         new_unittest('export_coordinate_names', test_export_coordinate_names), &
         new_unittest('export_coordinates_refused', test_export_coordinates_refused) &
         ]
   end subroutine collect_hdf5

   !> Write a file as a hostile program could: a chunked dataset /big declared
   !> (2^40, 2) in h5py order (nothing written: a few kB), a 1-D /small (3) with an
   !> int32 array attribute 'units' (3 values) and a string 'description'.
   subroutine craft_hostile(name, error)
      character(len=*), intent(in) :: name              !! file to create
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer(hid_t) :: fid, space, dcpl, dset, attr
      integer, target :: units(3) = [1, 2, 3]
      type(c_ptr) :: ptr
      integer :: ierr, bad
      call h5open_f(ierr)
      call h5fcreate_f(name, H5F_ACC_TRUNC_F, fid, ierr)
      bad = ierr
      call h5screate_simple_f(2, [2_hsize_t, 2_hsize_t**40], space, ierr)
      call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, ierr)
      call h5pset_chunk_f(dcpl, 2, [2_hsize_t, 1_hsize_t], ierr)
      call h5dcreate_f(fid, 'big', H5T_IEEE_F64LE, space, dset, ierr, dcpl)
      bad = bad + abs(ierr)
      call h5dclose_f(dset, ierr)
      call h5pclose_f(dcpl, ierr)
      call h5sclose_f(space, ierr)
      call h5screate_simple_f(1, [3_hsize_t], space, ierr)
      call h5dcreate_f(fid, 'small', H5T_IEEE_F64LE, space, dset, ierr)
      bad = bad + abs(ierr)
      call h5acreate_f(dset, 'units', H5T_STD_I32LE, space, attr, ierr)
      ptr = c_loc(units)
      call h5awrite_f(attr, H5T_NATIVE_INTEGER, ptr, ierr)
      bad = bad + abs(ierr)
      call h5aclose_f(attr, ierr)
      call h5dclose_f(dset, ierr)
      call h5sclose_f(space, ierr)
      call h5fclose_f(fid, ierr)
      if (bad /= 0) call fatal_error(error, 'could not craft '//name)
   end subroutine craft_hostile

   !> A size declared by the file is refused before anything is allocated, in
   !> one line naming the file and the dataset; a small dataset still reads.
   subroutine test_declared_sizes(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      real(dp), allocatable :: v2(:, :), v1(:)
      integer, allocatable :: dims(:)
      name = temp_name('hostile')
      call craft_hostile(name, error)
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%read('/big', v2, err)
      call check_true(error, allocated(err), 'reading a 2^41-value dataset must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, "'/big'") > 0 .and. &
                      index(err%message, name) > 0 .and. &
                      index(err%message, '2199023255552 values') > 0 .and. &
                      index(err%message, new_line('a')) == 0, 'message: '//err%message)
      call check_true(error, .not. allocated(v2), 'nothing allocated')
      if (allocated(error)) return
      call h5%shape('/big', dims, err)
      call check_true(error, allocated(err), 'shape beyond a default integer must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, '1099511627776') > 0, 'shape: '//err%message)
      call h5%read('/big', v1, err)
      call check_true(error, allocated(err), 'a rank-2 dataset read as 1-D must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'rank 2, expected 1') > 0, err%message)
      call h5%read('/small', v1, error)
      if (.not. allocated(error)) call check_true(error, size(v1) == 3, 'small read')
      call h5%close()
      call delete_file(name)
   end subroutine test_declared_sizes

   !> An attribute of another type than the one read (an int32 array as 'units'):
   !> refused in one line naming it, the string result is '' (no crash).
   subroutine test_attribute_types(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name, s
      real(dp) :: x
      name = temp_name('attrtype')
      call craft_hostile(name, error)
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%readattr('/small', 'units', s, err)
      call check_true(error, allocated(err), 'an int array read as a string must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, "attribute 'units' of '/small'") > 0 .and. &
                      index(err%message, 'does not hold a string') > 0, err%message)
      call check_true(error, allocated(s), 'the string is allocated')
      if (.not. allocated(error)) call check_true(error, len(s) == 0, 'the string is empty')
      call h5%readattr('/small', 'units', x, err)
      call check_true(error, allocated(err), 'a 3-value attribute read as a scalar must fail')
      if (.not. allocated(error)) call check_true(error, index(err%message, 'not a scalar') &
                                                  > 0, err%message)
      call h5%close()
      call delete_file(name)
   end subroutine test_attribute_types

   !> A file name in /tmp unique to this run and `tag`.
   function temp_name(tag) result(name)
      character(len=*), intent(in) :: tag  !! distinguishes files of one run
      character(len=:), allocatable :: name
      integer(i8) :: clock
      real(dp) :: r
      character(len=64) :: buf
      call system_clock(clock)
      call random_number(r)
      write (buf, '(i0, "_", i0)') clock, int(r*1.0e9_dp)
      name = '/tmp/dpend_test_hdf5_'//trim(buf)//'_'//tag//'.h5'
   end function temp_name

   !> Delete `name` if it exists.
   subroutine delete_file(name)
      character(len=*), intent(in) :: name  !! file to remove
      integer :: unit, ios
      logical :: there
      inquire (file=name, exist=there)
      if (.not. there) return
      open (newunit=unit, file=name, status='old', iostat=ios)
      if (ios == 0) close (unit, status='delete')
   end subroutine delete_file

   !> Fail unless `actual` and `expected` have the same shape and integer values.
   subroutine check_ints(error, actual, expected, what)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      integer, intent(in) :: actual(:)                    !! values read
      integer, intent(in) :: expected(:)                  !! values written
      character(len=*), intent(in) :: what                !! what is compared
      call check_true(error, size(actual) == size(expected), what//': size differs')
      if (allocated(error)) return
      call check_true(error, all(actual == expected), what//': values differ')
   end subroutine check_ints

   !> Real scalars and 1-D, 2-D, 3-D arrays come back with equal shape and values.
   subroutine test_real_roundtrip(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      real(dp) :: x0, y0, x1(5), x2(2, 7), x3(3, 4, 2)
      real(dp), allocatable :: y1(:), y2(:, :), y3(:, :, :), empty(:)
      integer, allocatable :: dims(:)
      integer :: i
      name = temp_name('real')
      x0 = -1.25e-300_dp
      x1 = [(real(i, dp)/3.0_dp, i=1, 5)]
      x2 = reshape([(sin(real(i, dp)), i=1, 14)], [2, 7])
      x3 = reshape([(real(i, dp)**1.5_dp, i=1, 24)], [3, 4, 2])
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/scalar', x0, error)
      if (.not. allocated(error)) call h5%write('/trajectory/x1', x1, error)
      if (.not. allocated(error)) call h5%write('/trajectory/q', x2, error)
      if (.not. allocated(error)) call h5%write('/deep/er/x3', x3, error)
      if (.not. allocated(error)) call h5%write('/empty', x1(1:0), error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, .not. h5%is_open(), 'is_open after close')

      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call check_true(error, h5%is_open(), 'is_open after open')
      call h5%read('/scalar', y0, error)
      call check(error, y0, x0, 'scalar')
      if (.not. allocated(error)) call h5%read('/trajectory/x1', y1, error)
      if (.not. allocated(error)) call check(error, y1, x1, 'x1')
      if (.not. allocated(error)) call h5%read('/trajectory/q', y2, error)
      if (.not. allocated(error)) call check_true(error, all(shape(y2) == [2, 7]), 'q shape')
      if (.not. allocated(error)) call check(error, pack(y2, .true.), pack(x2, .true.), 'q')
      if (.not. allocated(error)) call h5%read('/deep/er/x3', y3, error)
      if (.not. allocated(error)) call check_true(error, all(shape(y3) == [3, 4, 2]), 'x3 shape')
      if (.not. allocated(error)) call check(error, pack(y3, .true.), pack(x3, .true.), 'x3')
      if (.not. allocated(error)) call h5%read('/empty', empty, error)
      if (.not. allocated(error)) call check_true(error, size(empty) == 0, 'empty size')
      if (.not. allocated(error)) call h5%shape('/trajectory/q', dims, error)
      if (.not. allocated(error)) call check_ints(error, dims, [2, 7], 'shape of q')
      if (.not. allocated(error)) call h5%shape('/scalar', dims, error)
      if (.not. allocated(error)) call check_true(error, size(dims) == 0, 'scalar has rank 0')
      call h5%close()
      call delete_file(name)
   end subroutine test_real_roundtrip

   !> Integer scalars, 1-D, 2-D and integer(i8) 1-D arrays round-trip exactly.
   subroutine test_int_roundtrip(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      integer :: n0, m0, n1(4), n2(3, 2), i
      integer, allocatable :: m1(:), m2(:, :)
      integer(i8) :: l1(3)
      integer(i8), allocatable :: k1(:)
      real(dp), allocatable :: as_real(:)
      name = temp_name('int')
      n0 = -huge(0)
      n1 = [1, -2, 3, huge(0)]
      n2 = reshape([(i*i - 4, i=1, 6)], [3, 2])
      l1 = [-huge(0_i8), 0_i8, 2_i8**40 + 7_i8]
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/n0', n0, error)
      if (.not. allocated(error)) call h5%write('/ints/n1', n1, error)
      if (.not. allocated(error)) call h5%write('/ints/n2', n2, error)
      if (.not. allocated(error)) call h5%write('/ints/l1', l1, error)
      call h5%close()
      if (allocated(error)) return

      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%read('/n0', m0, error)
      if (.not. allocated(error)) call check_true(error, m0 == n0, 'n0 differs')
      if (.not. allocated(error)) call h5%read('/ints/n1', m1, error)
      if (.not. allocated(error)) call check_ints(error, m1, n1, 'n1')
      if (.not. allocated(error)) call h5%read('/ints/n2', m2, error)
      if (.not. allocated(error)) call check_true(error, all(shape(m2) == [3, 2]), 'n2 shape')
      if (.not. allocated(error)) call check_true(error, all(m2 == n2), 'n2 values')
      if (.not. allocated(error)) call h5%read('/ints/l1', k1, error)
      if (.not. allocated(error)) call check_true(error, size(k1) == 3, 'l1 size')
      if (.not. allocated(error)) call check_true(error, all(k1 == l1), 'l1 values')
      ! integers read as reals are converted; reals never read as integers
      if (.not. allocated(error)) call h5%read('/ints/n1', as_real, error)
      if (.not. allocated(error)) call check(error, as_real, real(n1, dp), 'n1 as real')
      call h5%close()
      call delete_file(name)
   end subroutine test_int_roundtrip

   !> Strings, including empty ones and trailing blanks, round-trip exactly.
   subroutine test_string_roundtrip(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name, s
      integer, allocatable :: dims(:)
      real(dp) :: x
      name = temp_name('str')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/meta/integrator', 'rk4 (fixed step)', error)
      if (.not. allocated(error)) call h5%write('/meta/empty', '', error)
      if (.not. allocated(error)) call h5%write('/meta/padded', 'ab  ', error)
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%read('/meta/integrator', s, error)
      if (.not. allocated(error)) call check_true(error, s == 'rk4 (fixed step)' .and. &
         len(s) == 16, 'integrator string differs: "'//s//'"')
      if (.not. allocated(error)) call h5%read('/meta/empty', s, error)
      if (.not. allocated(error)) call check_true(error, len(s) == 0, 'empty string')
      if (.not. allocated(error)) call h5%read('/meta/padded', s, error)
      if (.not. allocated(error)) call check_true(error, len(s) == 4, 'trailing blanks')
      if (.not. allocated(error)) call h5%shape('/meta/integrator', dims, error)
      if (.not. allocated(error)) call check_true(error, size(dims) == 0, 'string is scalar')
      if (allocated(error)) return
      call h5%read('/meta/integrator', x, err)
      call check_true(error, allocated(err), 'string read as real must fail')
      call h5%close()
      call delete_file(name)
   end subroutine test_string_roundtrip

   !> Attributes on the root, a group and a dataset round-trip and can be replaced.
   subroutine test_attributes(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name, s
      real(dp) :: x
      real(dp), allocatable :: v(:)
      integer :: n
      name = temp_name('attr')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/run/theta', [1.0_dp, 2.0_dp], error)
      if (.not. allocated(error)) call h5%writeattr('/', 'version', '0.1.0', error)
      if (.not. allocated(error)) call h5%writeattr('/', 'seed', 42, error)
      if (.not. allocated(error)) call h5%writeattr('/run', 'dt', 1.0e-3_dp, error)
      if (.not. allocated(error)) call h5%writeattr('/run', 'dt', 2.5e-3_dp, error)
      if (.not. allocated(error)) call h5%writeattr('/run/theta', 'units', 'rad', error)
      if (.not. allocated(error)) call h5%writeattr('/run/theta', 'range', &
         [-3.0_dp, 3.0_dp, 0.5_dp], error)
      call h5%close()
      if (allocated(error)) return

      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call check_true(error, h5%attr_exists('/', 'version'), 'root attr exists')
      call check_true(error, h5%attr_exists('/run/theta', 'units'), 'dataset attr exists')
      call check_true(error, .not. h5%attr_exists('/run', 'units'), 'no such attr')
      call check_true(error, .not. h5%attr_exists('/nope', 'units'), 'no such object')
      if (allocated(error)) return
      call h5%readattr('/', 'version', s, error)
      if (.not. allocated(error)) call check_true(error, s == '0.1.0', 'version: '//s)
      if (.not. allocated(error)) call h5%readattr('/', 'seed', n, error)
      if (.not. allocated(error)) call check_true(error, n == 42, 'seed')
      if (.not. allocated(error)) call h5%readattr('/run', 'dt', x, error)
      if (.not. allocated(error)) call check(error, x, 2.5e-3_dp, 'dt replaced')
      if (.not. allocated(error)) call h5%readattr('/run/theta', 'units', s, error)
      if (.not. allocated(error)) call check_true(error, s == 'rad', 'units: '//s)
      if (.not. allocated(error)) call h5%readattr('/run/theta', 'range', v, error)
      if (.not. allocated(error)) call check_true(error, size(v) == 3, 'range size')
      if (.not. allocated(error)) call check(error, v, [-3.0_dp, 3.0_dp, 0.5_dp], 'range')
      if (allocated(error)) return
      call h5%readattr('/run', 'missing', x, err)
      call check_true(error, allocated(err), 'missing attribute must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, "'missing'") > 0, &
         'message names the attribute: '//err%message)
      call h5%close()
      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%writeattr('/', 'x', 1, err)
      call check_true(error, allocated(err), 'writing a read-only file must fail')
      call h5%close()
      call delete_file(name)
   end subroutine test_attributes

   !> Columns and blocks written with write_slab reassemble the full array.
   subroutine test_slabs(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      real(dp) :: full(4, 10), half(2, 3)
      real(dp), allocatable :: back(:, :), vback(:)
      integer :: counts(3, 5), j
      integer, allocatable :: nback(:, :)
      name = temp_name('slab')
      full = reshape([(real(j, dp)*0.1_dp - 1.0_dp, j=1, 40)], [4, 10])
      counts = reshape([(j, j=1, 15)], [3, 5])
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%create_dataset('/sweep/grid', 'real64', [4, 10], [4, 3], error, fill=-7.0_dp)
      if (allocated(error)) return
      do j = 1, 6   ! columns one at a time, 1-D into 2-D
         call h5%write_slab('/sweep/grid', full(:, j), [1, j], error)
         if (allocated(error)) return
      end do
      call h5%write_slab('/sweep/grid', full(:, 7:10), [1, 7], error)
      if (allocated(error)) return
      call h5%create_dataset('/sweep/count', 'int32', [3, 5], [2, 2], error, fill=0.0_dp)
      if (allocated(error)) return
      call h5%write_slab('/sweep/count', counts(:, 1:2), [1, 1], error)
      if (.not. allocated(error)) call h5%write_slab('/sweep/count', counts(:, 3:5), &
         [1, 3], error)
      if (.not. allocated(error)) call h5%create_dataset('/sweep/unwritten', 'real64', &
         [2, 3], [2, 1], error, fill=-7.0_dp)
      if (.not. allocated(error)) call h5%write_slab('/sweep/unwritten', [1.0_dp], [2, 3], error)
      if (allocated(error)) return
      call h5%write_slab('/sweep/grid', full(:, 1:2), [1, 10], err)
      call check_true(error, allocated(err), 'slab outside the dataset must fail')
      ! whole chunks ([4, 3] chunks of [4, 10]): columns 4-6, and 10 (the edge chunk),
      ! with new values (read back below)
      full(:, 4:6) = -full(:, 4:6)
      full(:, 10) = -full(:, 10)
      call h5%write_slab('/sweep/grid', full(:, 4:6), [1, 4], error, whole_chunks=.true.)
      if (.not. allocated(error)) call h5%write_slab('/sweep/grid', full(:, 10:10), &
         [1, 10], error, whole_chunks=.true.)
      if (allocated(error)) return
      call h5%write_slab('/sweep/grid', full(:, 4:5), [1, 4], err, whole_chunks=.true.)
      call check_true(error, allocated(err), 'whole_chunks: part of a chunk must fail')
      call h5%write_slab('/sweep/grid', full(:, 2:4), [1, 2], err, whole_chunks=.true.)
      call check_true(error, allocated(err), 'whole_chunks: a block across chunks must fail')
      half = full(1:2, 4:6)   ! contiguous: no array temporary for the call
      call h5%write_slab('/sweep/grid', half, [1, 4], err, whole_chunks=.true.)
      call check_true(error, allocated(err), 'whole_chunks: half the rows must fail')
      call h5%create_dataset('/sweep/grows', 'real64', [4, 3], [4, 3], error, &
         extendible=.true.)
      if (allocated(error)) return
      call h5%write_slab('/sweep/grows', full(:, 1:3), [1, 1], err, whole_chunks=.true.)
      call check_true(error, allocated(err), 'whole_chunks: an extendible dataset must fail')
      if (allocated(error)) return
      call h5%flush()
      call h5%close()

      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call h5%read('/sweep/grid', back, error)
      if (.not. allocated(error)) call check_true(error, all(shape(back) == [4, 10]), 'shape')
      if (.not. allocated(error)) call check(error, pack(back, .true.), pack(full, .true.), 'grid')
      if (.not. allocated(error)) call h5%read('/sweep/count', nback, error)
      if (.not. allocated(error)) call check_true(error, all(nback == counts), 'counts')
      if (.not. allocated(error)) call h5%read('/sweep/unwritten', back, error)
      if (.not. allocated(error)) call check(error, pack(back, .true.), &
         [-7.0_dp, -7.0_dp, -7.0_dp, -7.0_dp, -7.0_dp, 1.0_dp], 'fill value and one element')
      ! slab reads: blocks of both kinds, then a block outside and a wrong rank
      if (.not. allocated(error)) call h5%read_slab('/sweep/grid', [2, 3], [2, 5], back, error, &
         check_sums=.false.)
      if (.not. allocated(error)) call check(error, pack(back, .true.), &
         pack(full(2:3, 3:7), .true.), 'read_slab of a real block')
      if (.not. allocated(error)) call h5%read_slab('/sweep/count', [1, 4], [3, 2], nback, error)
      if (.not. allocated(error)) call check_true(error, all(nback == counts(:, 4:5)), &
         'read_slab of an integer block')
      if (.not. allocated(error)) call h5%read_slab('/sweep/grid', [1, 10], [4, 0], back, error)
      if (.not. allocated(error)) call check_true(error, size(back, 2) == 0, 'empty slab')
      if (allocated(error)) return
      call h5%read_slab('/sweep/grid', [1, 10], [4, 2], back, err)
      call check_true(error, allocated(err), 'read_slab outside the dataset must fail')
      call h5%read_slab('/sweep/grid', [1], [4], vback, err)
      call check_true(error, allocated(err), 'read_slab of another rank must fail')
      call h5%close()
      call delete_file(name)
   end subroutine test_slabs

   !> `write_chunked` encodes the chunks itself (shuffle, deflate by plane, Fletcher-32)
   !> and HDF5 reads them back through its own filters, checksums checked: the same
   !> values, bit for bit, as written through HDF5's filters (`write_slab`), for real
   !> and integer data of rank 1 and 2 with edge chunks, with and without checksums,
   !> NaN, infinities and -0 among them; a plane of random bytes is stored, a
   !> constant one shrinks. A dataset without those filters goes through HDF5; whole
   !> chunks of an unfiltered dataset (`write_slab` with `whole_chunks`) are written
   !> as stored, and read back as written.
   subroutine test_chunks_encoded_here(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      real(dp) :: grid(37, 23), line(1000), noise(4096)
      integer :: counts(37, 23), j, n, noise_bytes, zero_bytes
      integer(i8) :: state
      real(dp), allocatable :: back2(:, :), via2(:, :), back1(:)
      integer, allocatable :: iback(:, :)
      logical :: summed
      name = temp_name('chunked')
      do j = 1, 23
         grid(:, j) = [(sin(0.1_dp*real(j*37 + n, dp)), n=1, 37)]
         counts(:, j) = [(mod(j*n, 5) - 2, n=1, 37)]
      end do
      grid(1, 1) = ieee_value(1.0_dp, ieee_quiet_nan)
      grid(2, 1) = ieee_value(1.0_dp, ieee_positive_inf)
      grid(3, 1) = -0.0_dp
      line = [(real(j, dp)/7.0_dp, j=1, 1000)]
      state = 88172645463325252_i8   ! xorshift64: bytes with no pattern
      do j = 1, size(noise)
         state = ieor(state, ishft(state, 13))
         state = ieor(state, ishft(state, -7))
         state = ieor(state, ishft(state, 17))
         noise(j) = transfer(state, 1.0_dp)
      end do
      do n = 1, 2
         summed = n == 1
         call h5%open(name, 'w', error)
         if (allocated(error)) return
         call h5%create_dataset('/grid', 'real64', [37, 23], [37, 5], error, checksum=summed)
         if (.not. allocated(error)) call h5%write_chunked('/grid', grid, error)
         if (.not. allocated(error)) call h5%create_dataset('/via', 'real64', [37, 23], &
            [37, 5], error, checksum=summed)
         if (.not. allocated(error)) call h5%write_slab('/via', grid, [1, 1], error)
         if (.not. allocated(error)) call h5%create_dataset('/counts', 'int32', [37, 23], &
            [10, 4], error, checksum=summed)
         if (.not. allocated(error)) call h5%write_chunked('/counts', counts, error)
         if (.not. allocated(error)) call h5%create_dataset('/line', 'real64', [1000], &
            [300], error, checksum=summed)
         if (.not. allocated(error)) call h5%write_chunked('/line', line, error)
         if (.not. allocated(error)) call h5%create_dataset('/plain', 'real64', [1000], &
            [300], error, compress=.false.)
         if (.not. allocated(error)) call h5%write_chunked('/plain', line, error)
         if (.not. allocated(error)) call h5%create_dataset('/noise', 'real64', [4096], &
            [4096], error)
         if (.not. allocated(error)) call h5%write_chunked('/noise', noise, error)
         if (.not. allocated(error)) call h5%create_dataset('/zeros', 'real64', [4096], &
            [4096], error)
         if (.not. allocated(error)) call h5%write_chunked('/zeros', 0*noise, error)
         call h5%close()
         if (allocated(error)) return
         call h5%open(name, 'r', error)
         if (.not. allocated(error)) call h5%read('/grid', back2, error)
         if (.not. allocated(error)) call h5%read('/via', via2, error)
         if (allocated(error)) return
         call check_true(error, all(transfer(back2, [0_i8]) == transfer(grid, [0_i8])) .and. &
                         all(transfer(via2, [0_i8]) == transfer(grid, [0_i8])), &
                         'real grid back bit for bit, both ways')
         if (.not. allocated(error)) call h5%read('/counts', iback, error)
         if (.not. allocated(error)) call check_true(error, all(iback == counts), &
                                                     'integers back')
         if (.not. allocated(error)) call h5%read('/line', back1, error)
         if (.not. allocated(error)) call check_true(error, all(back1 == line), 'rank 1 back')
         if (.not. allocated(error)) call h5%read('/plain', back1, error)
         if (.not. allocated(error)) call check_true(error, all(back1 == line), &
                                                     'unfiltered dataset back')
         if (.not. allocated(error)) call h5%read('/noise', back1, error)
         if (.not. allocated(error)) call check_true(error, &
            all(transfer(back1, [0_i8]) == transfer(noise, [0_i8])), 'random bytes back')
         call h5%close()
         if (allocated(error)) return
      end do
      noise_bytes = stored_size(name, '/noise')
      zero_bytes = stored_size(name, '/zeros')
      ! whole chunks of datasets without filters, written as stored (H5Dwrite_chunk):
      ! blocks of one and of several chunks, edge chunks, chunks cut in both dimensions
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%create_dataset('/rows', 'real64', [37, 23], [37, 5], error, compress=.false., &
                             alloc_early=.true.)
      if (.not. allocated(error)) call h5%write_slab('/rows', grid(:, 1:5), [1, 1], error, &
         whole_chunks=.true.)
      if (.not. allocated(error)) call h5%write_slab('/rows', grid(:, 6:15), [1, 6], error, &
         whole_chunks=.true.)
      if (.not. allocated(error)) call h5%write_slab('/rows', grid(:, 16:23), [1, 16], error, &
         whole_chunks=.true.)
      if (.not. allocated(error)) call h5%create_dataset('/tiles', 'int32', [37, 23], [10, 4], &
         error, compress=.false.)
      if (.not. allocated(error)) call h5%write_slab('/tiles', counts, [1, 1], error, &
         whole_chunks=.true.)
      if (.not. allocated(error)) call h5%create_dataset('/list', 'real64', [1000], [300], &
         error, compress=.false., alloc_early=.true.)
      if (.not. allocated(error)) call h5%write_slab('/list', line(1:600), [1], error, &
         whole_chunks=.true.)
      if (.not. allocated(error)) call h5%write_slab('/list', line(601:1000), [601], error, &
         whole_chunks=.true.)
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (.not. allocated(error)) call h5%read('/rows', back2, error)
      if (.not. allocated(error)) call check_true(error, &
         all(transfer(back2, [0_i8]) == transfer(grid, [0_i8])), 'whole chunks as stored, 2-D')
      if (.not. allocated(error)) call h5%read('/tiles', iback, error)
      if (.not. allocated(error)) call check_true(error, all(iback == counts), &
                                                  'chunks cut in both dimensions')
      if (.not. allocated(error)) call h5%read('/list', back1, error)
      if (.not. allocated(error)) call check_true(error, all(back1 == line), &
                                                  'whole chunks as stored, 1-D')
      call h5%close()
      if (allocated(error)) return
      call check_true(error, noise_bytes > 32768 .and. noise_bytes < 33200 .and. &
                      zero_bytes < 1500, 'random planes stored ('//to_str(noise_bytes)// &
                      ' B for 32768), zeros shrink ('//to_str(zero_bytes)//' B)')
      call delete_file(name)
   contains
      !> Bytes the dataset takes in the file (its chunks as stored)
      integer function stored_size(file, path) result(bytes)
         character(len=*), intent(in) :: file, path
         integer(hid_t) :: fid, did
         integer(hsize_t) :: nbytes
         integer :: ierr
         bytes = -1
         call h5fopen_f(file, H5F_ACC_RDONLY_F, fid, ierr)
         if (ierr /= 0) return
         call h5dopen_f(fid, path, did, ierr)
         if (ierr == 0) then
            call h5dget_storage_size_f(did, nbytes, ierr)
            if (ierr == 0) bytes = int(nbytes)
            call h5dclose_f(did, ierr)
         end if
         call h5fclose_f(fid, ierr)
      end function stored_size
   end subroutine test_chunks_encoded_here

   !> An extendible dataset grows along its last dimension as columns are written.
   subroutine test_extendible(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      real(dp) :: cols(3, 5)
      real(dp), allocatable :: back(:, :)
      integer, allocatable :: dims(:)
      integer :: j
      name = temp_name('ext')
      cols = reshape([(real(j, dp), j=1, 15)], [3, 5])
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%create_dataset('/log', 'real64', [3, 0], [3, 4], error, extendible=.true.)
      if (allocated(error)) return
      do j = 1, 5
         call h5%write_slab('/log', cols(:, j), [1, j], error)
         if (allocated(error)) return
      end do
      call h5%shape('/log', dims, error)
      if (.not. allocated(error)) call check_ints(error, dims, [3, 5], 'grown shape')
      if (.not. allocated(error)) call h5%read('/log', back, error)
      if (.not. allocated(error)) call check(error, pack(back, .true.), pack(cols, .true.), 'grown')
      call h5%close()
      call delete_file(name)
   end subroutine test_extendible

   !> Rewriting a dataset works with the same shape, another shape and another type.
   subroutine test_overwrite(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name, s
      real(dp), allocatable :: back(:)
      integer, allocatable :: nback(:)
      name = temp_name('over')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/a', [1.0_dp, 2.0_dp, 3.0_dp], error)
      if (.not. allocated(error)) call h5%writeattr('/a', 'units', 'm', error)
      if (.not. allocated(error)) call h5%write('/a', [4.0_dp, 5.0_dp, 6.0_dp], error)
      if (.not. allocated(error)) call check_true(error, h5%attr_exists('/a', 'units'), &
         'same shape: dataset reused, attribute kept')
      if (.not. allocated(error)) call h5%write('/b', [1.0_dp, 2.0_dp], error)
      if (.not. allocated(error)) call h5%write('/b', [7.0_dp, 8.0_dp, 9.0_dp, 10.0_dp], error)
      if (.not. allocated(error)) call h5%write('/c', [1.0_dp], error)
      if (.not. allocated(error)) call h5%write('/c', [3, 4], error)
      if (.not. allocated(error)) call h5%write('/s', 'short', error)
      if (.not. allocated(error)) call h5%write('/s', 'much longer text', error)
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'rw', error)
      if (allocated(error)) return
      call h5%write('/a', [0.5_dp, 0.25_dp, 0.125_dp], error)   ! again after reopening
      if (.not. allocated(error)) call h5%read('/a', back, error)
      if (.not. allocated(error)) call check(error, back, [0.5_dp, 0.25_dp, 0.125_dp], 'a')
      if (.not. allocated(error)) call h5%read('/b', back, error)
      if (.not. allocated(error)) call check_true(error, size(back) == 4, 'b resized')
      if (.not. allocated(error)) call check_true(error, h5%attr_exists('/a', 'units'), &
         'attribute kept after reopening')
      if (.not. allocated(error)) call check(error, back, [7.0_dp, 8.0_dp, 9.0_dp, 10.0_dp], 'b')
      if (.not. allocated(error)) call h5%read('/c', nback, error)
      if (.not. allocated(error)) call check_ints(error, nback, [3, 4], 'c')
      if (.not. allocated(error)) call h5%read('/s', s, error)
      if (.not. allocated(error)) call check_true(error, s == 'much longer text', 's: '//s)
      call h5%close()
      call delete_file(name)
   end subroutine test_overwrite

   !> `exists` is true for the root, groups and datasets and false otherwise.
   subroutine test_exists(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      character(len=16) :: padded
      name = temp_name('exists')
      call check_true(error, .not. h5%exists('/'), 'nothing exists in a closed file')
      if (allocated(error)) return
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/a/b/x', 1.0_dp, error)
      if (allocated(error)) return
      call check_true(error, h5%exists('/'), '/')
      call check_true(error, h5%exists('/a'), '/a')
      call check_true(error, h5%exists('/a/b'), '/a/b')
      call check_true(error, h5%exists('/a/b/x'), '/a/b/x')
      call check_true(error, h5%exists('a/b/x'), 'a/b/x')
      call check_true(error, .not. h5%exists('/nope'), '/nope')
      call check_true(error, .not. h5%exists('/a/nope/x'), '/a/nope/x')
      call check_true(error, .not. h5%exists('/a/b/x/y'), '/a/b/x/y below a dataset')
      call check_true(error, .not. h5%exists(''), 'empty path')
      padded = '/a/p'
      call h5%write(padded, 2, error)
      call check_true(error, h5%exists('/a/p'), 'trailing blanks of a path are ignored')
      call h5%close()
      call delete_file(name)
   end subroutine test_exists

   !> Opening a missing file for reading fails with a message naming the file.
   subroutine test_missing_file(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      real(dp) :: x
      name = temp_name('missing')
      call h5%open(name, 'r', err)
      call check_true(error, allocated(err), 'opening a missing file must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, name) > 0, 'message names the file')
      call check_true(error, .not. h5%is_open(), 'not open after failure')
      call h5%read('/x', x, err)
      call check_true(error, allocated(err), 'reading with no open file must fail')
      call h5%open(name, 'q', err)
      call check_true(error, allocated(err), 'mode q must fail')
      call h5%open('/nonexistent_dir_dpend/x.h5', 'w', err)
      call check_true(error, allocated(err), 'creating in a missing directory must fail')
   end subroutine test_missing_file

   !> Reading a missing dataset, or one of the wrong rank, fails with a clear message.
   subroutine test_missing_dataset(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      real(dp), allocatable :: v(:), m(:, :)
      integer :: n
      name = temp_name('nodset')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/v', [1.0_dp, 2.0_dp], error)
      if (allocated(error)) return
      call h5%read('/absent/v', v, err)
      call check_true(error, allocated(err), 'missing dataset must fail')
      if (allocated(error)) return
      call check_true(error, index(err%message, '/absent/v') > 0 .and. &
         index(err%message, name) > 0, 'message names path and file: '//err%message)
      call h5%read('/v', m, err)
      call check_true(error, allocated(err), 'rank mismatch must fail')
      call h5%read('/v', n, err)
      call check_true(error, allocated(err), 'reals read as integer must fail')
      call h5%read('/', v, err)
      call check_true(error, allocated(err), 'a group is not a dataset')
      call h5%close()
      call delete_file(name)
   end subroutine test_missing_dataset

   !> 'x' refuses an existing file, 'rw' keeps data, 'w' truncates.
   subroutine test_modes(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      real(dp) :: x
      name = temp_name('modes')
      call h5%open(name, 'x', error)
      if (allocated(error)) return
      call h5%write('/x', 3.0_dp, error)
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'x', err)
      call check_true(error, allocated(err), "mode 'x' must refuse an existing file")
      call check_true(error, .not. h5%is_open(), "not open after refused 'x'")
      if (allocated(error)) return
      call h5%open(name, 'rw', error)
      if (allocated(error)) return
      call h5%read('/x', x, error)
      if (.not. allocated(error)) call check(error, x, 3.0_dp, "'rw' keeps data")
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call check_true(error, .not. h5%exists('/x'), "'w' truncates")
      call h5%close()
      call delete_file(name)
      call h5%open(name, 'rw', error)
      if (allocated(error)) return
      call check_true(error, h5%is_open(), "'rw' creates a missing file")
      call h5%close()
      call delete_file(name)
   end subroutine test_modes

   !> Writes without `error`: the first failure is kept, later such writes do
   !> nothing, a write with `error` still works and reports its own, and
   !> `take_error` / `close(error)` hand the kept failure over.
   subroutine test_kept_error(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      name = temp_name('kept')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%write('/a', 1.0_dp)
      call h5%writeattr('/missing', 'x', 2.0_dp)   ! fails: no such object
      call h5%write('/b', [1, 2])                  ! skipped
      call h5%writeattr('/', 's', 'text')          ! skipped
      call h5%write('/c', 3.0_dp, err)             ! with error: done
      call check_true(error, .not. allocated(err), 'a write with error must still work')
      if (allocated(error)) return
      call h5%take_error(err)
      call check_true(error, allocated(err), 'take_error must return the kept failure')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'missing') > 0, &
                      'the kept failure names the first failed path: '//err%message)
      if (allocated(error)) return
      call h5%take_error(err)
      call check_true(error, .not. allocated(err), 'take_error hands the failure over once')
      if (allocated(error)) return
      call h5%write('/d', 4.0_dp)                  ! works again
      call h5%writeattr('/nothing', 'y', 1)        ! fails, kept
      call h5%close(err)
      call check_true(error, allocated(err), 'close(error) must return the kept failure')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'nothing') > 0, &
                      'close returns the kept failure: '//err%message)
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (allocated(error)) return
      call check_true(error, h5%exists('/a') .and. h5%exists('/c') .and. h5%exists('/d'), &
                      'the writes before and after the failure are in the file')
      if (.not. allocated(error)) call check_true(error, .not. h5%exists('/b') .and. &
                                                  .not. h5%attr_exists('/', 's'), &
                                                  'the writes after a kept failure are skipped')
      call h5%close(err)
      if (.not. allocated(error)) call check_true(error, .not. allocated(err), &
                                                  'a clean close reports nothing')
      call delete_file(name)
   end subroutine test_kept_error

   !> is_hdf5 accepts our files and rejects text files and missing files.
   subroutine test_is_hdf5(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name, text
      integer :: unit
      name = temp_name('ish5')
      text = temp_name('text')
      call check_true(error, .not. is_hdf5(name), 'missing file is not HDF5')
      call h5%open(name, 'w', error)
      if (allocated(error)) return
      call h5%close()
      call check_true(error, is_hdf5(name), 'our file is HDF5')
      open (newunit=unit, file=text, status='replace', action='write')
      write (unit, '(a)') 'not hdf5'
      close (unit)
      call check_true(error, .not. is_hdf5(text), 'text file is not HDF5')
      call h5%open(text, 'r', err)
      call check_true(error, allocated(err), 'opening a text file must fail')
      call delete_file(name)
      call delete_file(text)
   end subroutine test_is_hdf5

   !> A file left open is closed when its h5file_t goes away, so it can be recreated.
   subroutine test_finalizer(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      real(dp) :: x
      name = temp_name('final')
      call leave_open(name, error)
      if (allocated(error)) return
      call h5%open(name, 'r', error)
      if (.not. allocated(error)) call h5%read('/x', x, error)
      if (.not. allocated(error)) call check(error, x, 5.0_dp, 'forgotten file')
      call h5%close()
      if (allocated(error)) return
      call h5%open(name, 'w', error)   ! truncating fails while another handle is open
      call h5%close()
      call delete_file(name)
   end subroutine test_finalizer

   !> `open` with a file access list uses it (the MPI build passes an MPI-IO list):
   !> with the in-memory driver and no backing store, nothing reaches the disk; the
   !> caller's list stays valid.
   subroutine test_access_list(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: name
      integer(hid_t) :: fapl
      integer :: hdferr
      real(dp) :: x
      logical :: there
      name = temp_name('core')
      call h5open_f(hdferr)
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, hdferr)
      call h5pset_fapl_core_f(fapl, int(65536, size_t), .false., hdferr)
      call h5%open(name, 'w', error, access=fapl)
      if (.not. allocated(error)) call h5%write('/x', 7.0_dp, error)
      if (.not. allocated(error)) call h5%read('/x', x, error)
      if (.not. allocated(error)) call check(error, x, 7.0_dp, 'read back in memory')
      call h5%close()
      call h5pclose_f(fapl, hdferr)
      if (allocated(error)) return
      call check_true(error, hdferr == 0, 'the caller''s access list is still valid')
      if (allocated(error)) return
      inquire (file=name, exist=there)
      call check_true(error, .not. there, 'in-memory file not written to disk')
      call delete_file(name)
   end subroutine test_access_list

   !> Write to `name` and return without closing.
   subroutine leave_open(name, error)
      character(len=*), intent(in) :: name              !! file to write
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      call h5%open(name, 'w', error)
      if (.not. allocated(error)) call h5%write('/x', 5.0_dp, error)
   end subroutine leave_open

   !> `export --csv` names the columns of q, qdot, qddot and p from the file's
   !> `coordinates` (the elastic pendulum: r, phi; the double pendulum keeps q1, qdot1,
   !> …) and the vectors NAME_x, NAME_y; every value equals the file's (read here).
   subroutine test_export_coordinate_names(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      integer :: stat
      dir = scratch_dir('hdf5names')
      stat = run_command(dir, 'simulate --model elastic --m 1 --k 40 --l0 1 --g 9.8 '// &
                         '--q 1.2,-1.0 --w 0.3,0.5 --t-end 0.1 --dt 0.01 --output '// &
                         dir//'/elastic.h5')
      call check_true(error, stat == 0, 'simulate --model elastic exits 0')
      if (allocated(error)) return
      call check_export(dir//'/elastic.h5', 'rA', 't [s],r [m],phi [rad],rdot [m/s],'// &
                        'phidot [rad/s],rddot [m/s^2],phiddot [rad/s^2],p_r [kg m/s],'// &
                        'p_phi [kg m^2/s],rA_x [m],rA_y [m]', error)
      if (allocated(error)) return
      stat = run_command(dir, 'simulate --t-end 0.1 --dt 0.01 --w 1,-2 --output '// &
                         dir//'/pendulum.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      if (allocated(error)) return
      call check_export(dir//'/pendulum.h5', 'rC2', 't [s],q1 [rad],q2 [rad],'// &
                        'qdot1 [rad/s],qdot2 [rad/s],qddot1 [rad/s^2],qddot2 [rad/s^2],'// &
                        'p1 [kg m^2/s],p2 [kg m^2/s],rC2_x [m],rC2_y [m]', error)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_export_coordinate_names

   !> Export t q qdot qddot p VECTOR of `file` as CSV: the header is `header`, and
   !> every line holds the values of the file (read here with h5file_t), exactly.
   subroutine check_export(file, vector, header, error)
      character(len=*), intent(in) :: file    !! a simulate file
      character(len=*), intent(in) :: vector  !! a 2-D (x, y) dataset of /trajectory
      character(len=*), intent(in) :: header  !! the header expected
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), p(:, :), r(:, :), row(:)
      real(dp), allocatable :: want(:)
      character(len=4096) :: line
      integer :: unit, i, ios
      call h5%open(file, 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qddot', qdd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/p', p, error)
      if (.not. allocated(error)) call h5%read('/trajectory/'//vector, r, error)
      call h5%close()
      if (allocated(error)) return
      open (newunit=unit, file=file//'.csv', status='replace', action='readwrite')
      call export_columns(file, [character(len=8) :: 't', 'q', 'qdot', 'qddot', 'p', &
                          vector], unit, error, csv=.true.)
      if (allocated(error)) then
         close (unit)
         return
      end if
      rewind (unit)
      read (unit, '(a)') line
      call check_true(error, trim(line) == header, 'header: '//trim(line))
      allocate (row(1 + 4*size(q, 1) + 2))
      do i = 1, size(t)
         if (allocated(error)) exit
         read (unit, '(a)', iostat=ios) line
         if (ios == 0) read (line, *, iostat=ios) row
         call check_true(error, ios == 0, 'line '//trim(line))
         if (allocated(error)) exit
         want = [t(i), q(:, i), qd(:, i), qdd(:, i), p(:, i), r(:, i)]
         call check_true(error, all(row == want), 'values of sample '//trim(line))
      end do
      if (.not. allocated(error)) then
         read (unit, '(a)', iostat=ios) line
         call check_true(error, is_iostat_end(ios), 'one line a sample, no more')
      end if
      close (unit)
   end subroutine check_export

   !> A `coordinates` attribute that is not one name a column (a comma, a count
   !> that differs from the columns of q) is refused naming the attribute; a file
   !> without it keeps the names q1, q2, ….
   subroutine test_export_coordinates_refused(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: file = 'test_export_coordinates.h5'
      character(len=*), parameter :: bad(3) = [character(len=8) :: 'r,phi', 'r', 'r phi z']
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=256) :: line
      integer :: unit, i
      do i = 0, size(bad)
         call h5%open(file, 'w', error)
         if (allocated(error)) return
         call h5%write('/trajectory/q', reshape([1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp], [2, 2]), &
                       units='m, rad')
         if (i > 0) call h5%writeattr('/', 'coordinates', trim(bad(i)))
         call h5%close(error)
         if (allocated(error)) return
         open (newunit=unit, status='scratch', action='readwrite')
         call export_columns(file, ['q'], unit, err, csv=.true.)
         if (i == 0) then
            call check_true(error, .not. allocated(err), 'no coordinates: exported')
            if (allocated(error)) exit
            rewind (unit)
            read (unit, '(a)') line
            call check_true(error, trim(line) == 'q1 [m],q2 [rad]', 'old names: '//trim(line))
         else
            call check_true(error, allocated(err), "refused: '"//trim(bad(i))//"'")
            if (allocated(error)) exit
            call check_true(error, index(err%message, "'coordinates'") > 0 .and. &
                            index(err%message, trim(bad(i))) > 0, 'names it: '//err%message)
         end if
         close (unit)
         if (allocated(error)) exit
      end do
      open (newunit=unit, file=file)
      close (unit, status='delete')
   end subroutine test_export_coordinates_refused

end module test_hdf5
