!> Files that explain themselves: every dataset of a simulate and a
!> sweep file (grid and list) carries `units` and `description`, string attributes
!> are variable-length UTF-8 and the old fixed-length ones still read, and
!> `dpend export` gives CSV with a header of names and units, lists the datasets
!> and takes names relative to the command's group.
module test_files
   use, intrinsic :: iso_c_binding, only: c_char, c_loc
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_output, only: track_inputs, register_input, check_output_path
   use hdf5, only: hid_t, size_t, H5F_ACC_RDWR_F, H5T_NATIVE_CHARACTER, H5S_SCALAR_F, &
      H5T_STR_NULLPAD_F, h5open_f, h5fopen_f, h5fclose_f, h5tcopy_f, h5tset_size_f, &
      h5tset_strpad_f, h5tclose_f, h5screate_f, h5sclose_f, h5acreate_f, h5awrite_f, &
      h5aclose_f
   use dpend_cli, only: to_str
   use test_cli, only: run_command, scratch_dir, read_text
   use testing, only: unittest_t, new_unittest, check_true, error_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, model_spec, new_model, default_model
   implicit none
   private
   public :: collect_files

contains

   !> The files test suite.
   subroutine collect_files(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
         new_unittest('describe_and_list', test_describe_and_list), &
         new_unittest('fixed_length_attributes_read', test_fixed_length), &
         new_unittest('simulate_units', test_simulate_units), &
         new_unittest('sweep_units', test_sweep_units), &
         new_unittest('export_csv', test_export_csv), &
         new_unittest('export_list_and_names', test_export_list), &
         new_unittest('export_wide_csv', test_export_wide_csv), &
         new_unittest('output_never_an_input', test_output_not_input)]
   end subroutine collect_files

   !> Fail unless every dataset of `filename` has the string attributes `units` and
   !> `description`, and there are `n_expected` datasets.
   subroutine check_all_described(error, filename, n_expected)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      character(len=*), intent(in) :: filename            !! HDF5 file
      integer, intent(in) :: n_expected                   !! datasets it must hold
      type(h5file_t) :: h5
      character(len=:), allocatable :: paths(:), s
      integer :: i
      if (allocated(error)) return
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      call h5%datasets('/', paths, error)
      if (allocated(error)) return
      call check_true(error, size(paths) == n_expected, filename//': '// &
                      to_str(n_expected)//' datasets, found '//to_str(size(paths)))
      do i = 1, size(paths)
         if (allocated(error)) exit
         call h5%readattr(trim(paths(i)), 'units', s, error)
         if (allocated(error)) exit
         call h5%readattr(trim(paths(i)), 'description', s, error)
         if (allocated(error)) exit
         call check_true(error, len(s) > 0, trim(paths(i))//': empty description')
      end do
      call h5%close()
   end subroutine check_all_described

   !> Fail unless the string attribute `name` of `path` reads as `expected`.
   subroutine check_attr(error, h5, path, name, expected)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      type(h5file_t), intent(inout) :: h5                 !! open file
      character(len=*), intent(in) :: path, name, expected
      character(len=:), allocatable :: s
      if (allocated(error)) return
      call h5%readattr(path, name, s, error)
      if (allocated(error)) return
      call check_true(error, s == expected, path//'@'//name//": expected '"//expected// &
                      "', got '"//s//"'")
   end subroutine check_attr

   !> `write` with units and description, `describe`, `create_dataset` with units;
   !> `datasets` lists every dataset below a group in name order.
   subroutine test_describe_and_list(error)
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir, paths(:)
      dir = scratch_dir('filesdesc')
      call h5%open(dir//'/a.h5', 'w', error)
      if (allocated(error)) return
      call h5%write('/g/t', [0.0_dp, 1.0_dp], error, units='s', description='times')
      if (.not. allocated(error)) call h5%write('/g/sub/n', [1, 2], error, units='1', &
                                                description='counts')
      if (.not. allocated(error)) call h5%write('/top', 2.0_dp, error)
      if (.not. allocated(error)) call h5%describe('/top', 'J', 'energy θ', error)
      if (.not. allocated(error)) call h5%create_dataset('/g/c', 'real64', [4], [2], error, &
                                                         units='rad', description='chunked')
      if (.not. allocated(error)) call h5%writeattr('/', 'method', 'rk4', error)
      call h5%close()
      if (allocated(error)) return
      call h5%open(dir//'/a.h5', 'r', error)
      if (allocated(error)) return
      call check_attr(error, h5, '/g/t', 'units', 's')
      call check_attr(error, h5, '/g/t', 'description', 'times')
      call check_attr(error, h5, '/g/sub/n', 'units', '1')
      call check_attr(error, h5, '/top', 'units', 'J')
      call check_attr(error, h5, '/top', 'description', 'energy θ')
      call check_attr(error, h5, '/g/c', 'units', 'rad')
      call check_attr(error, h5, '/', 'method', 'rk4')
      if (allocated(error)) return
      call h5%datasets('/', paths, error)
      if (allocated(error)) return
      call check_true(error, size(paths) == 4, 'four datasets, got '//to_str(size(paths)))
      if (allocated(error)) return
      call check_true(error, paths(1) == '/g/c' .and. paths(2) == '/g/sub/n' .and. &
                      paths(3) == '/g/t' .and. paths(4) == '/top', 'name order: '// &
                      paths(1)//' '//paths(2)//' '//paths(3)//' '//paths(4))
      call h5%datasets('/g/sub', paths, error)
      if (allocated(error)) return
      call check_true(error, size(paths) == 1, 'one dataset below /g/sub')
      call h5%close()
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_describe_and_list

   !> A fixed-length, null-padded string attribute (as dpend wrote them before)
   !> still reads, next to the variable-length ones written now.
   subroutine test_fixed_length(error)
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir
      character(kind=c_char), target :: buf(8)
      integer(hid_t) :: fid, stype, space, attr
      integer :: ierr
      dir = scratch_dir('filesfixed')
      call h5%open(dir//'/old.h5', 'w', error)
      if (.not. allocated(error)) call h5%write('/x', [1.0_dp], error)
      if (.not. allocated(error)) call h5%writeattr('/', 'new', 'vlen', error)
      call h5%close()
      if (allocated(error)) return
      buf = char(0)
      buf(1:3) = ['r', 'k', '4']
      call h5open_f(ierr)
      call h5fopen_f(dir//'/old.h5', H5F_ACC_RDWR_F, fid, ierr)
      call h5tcopy_f(H5T_NATIVE_CHARACTER, stype, ierr)
      call h5tset_size_f(stype, int(size(buf), size_t), ierr)
      call h5tset_strpad_f(stype, H5T_STR_NULLPAD_F, ierr)
      call h5screate_f(H5S_SCALAR_F, space, ierr)
      call h5acreate_f(fid, 'method', stype, space, attr, ierr)
      call h5awrite_f(attr, stype, c_loc(buf), ierr)
      call h5aclose_f(attr, ierr)
      call h5sclose_f(space, ierr)
      call h5tclose_f(stype, ierr)
      call h5fclose_f(fid, ierr)
      call check_true(error, ierr == 0, 'fixed-length attribute written')
      if (allocated(error)) return
      call h5%open(dir//'/old.h5', 'r', error)
      if (allocated(error)) return
      call check_attr(error, h5, '/', 'method', 'rk4')
      call check_attr(error, h5, '/', 'new', 'vlen')
      call h5%close()
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_fixed_length

   !> Every dataset of a simulate file has units and description; spot values.
   subroutine test_simulate_units(error)
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir
      integer :: stat
      dir = scratch_dir('filessim')
      stat = run_command(dir, 'simulate --t-end 0.2 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      ! t q qdot qddot p energy kinetic potential and the default model's outputs
      ! (F_joint among them)
      call check_all_described(error, dir//'/sim.h5', 8 + default_outputs())
      if (allocated(error)) return
      call h5%open(dir//'/sim.h5', 'r', error)
      if (allocated(error)) return
      call check_attr(error, h5, '/trajectory/t', 'units', 's')
      call check_attr(error, h5, '/trajectory/q', 'units', 'rad')
      call check_attr(error, h5, '/trajectory/qdot', 'units', 'rad/s')
      call check_attr(error, h5, '/trajectory/p', 'units', 'kg m^2/s')
      call check_attr(error, h5, '/trajectory/energy', 'units', 'J')
      call check_attr(error, h5, '/trajectory/kinetic', 'units', 'J')
      call check_attr(error, h5, '/trajectory/potential', 'units', 'J')
      call check_attr(error, h5, '/trajectory/F01', 'units', 'N')
      call check_attr(error, h5, '/trajectory/aC2', 'units', 'm/s^2')
      call check_attr(error, h5, '/', 'method', 'rk4')
      call h5%close()
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_simulate_units

   !> Every dataset of a grid and a list sweep file has units and description.
   subroutine test_sweep_units(error)
      type(error_t), allocatable, intent(out) :: error
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir
      integer :: stat, unit
      dir = scratch_dir('filessweep')
      stat = run_command(dir, 'sweep --quiet --n1 3 --n2 2 --t-end 1 --axis2 w2 '// &
                         '--threads 1 --output '//dir//'/grid.h5')
      call check_true(error, stat == 0, 'grid sweep exits 0')
      ! 10 reals, status, done, axis1, axis2
      call check_all_described(error, dir//'/grid.h5', 14)
      if (allocated(error)) return
      call h5%open(dir//'/grid.h5', 'r', error)
      if (allocated(error)) return
      call check_attr(error, h5, '/sweep/axis1', 'units', 'rad')
      call check_attr(error, h5, '/sweep/axis2', 'units', 'rad/s')
      call check_attr(error, h5, '/sweep/t_flip', 'units', 's')
      call check_attr(error, h5, '/sweep/energy_error', 'units', '1')
      call check_attr(error, h5, '/sweep/final/w1', 'units', 'rad/s')
      call h5%close()
      if (allocated(error)) return
      open (newunit=unit, file=dir//'/list.txt', status='replace', action='write')
      write (unit, '(a)') '0 0 0 0', '1 1.2 0 0'
      close (unit)
      stat = run_command(dir, 'sweep --quiet --ic-file '//dir//'/list.txt --t-end 1 '// &
                         '--stats --threads 1 --output '//dir//'/list.h5')
      call check_true(error, stat == 0, 'list sweep exits 0')
      ! 10 reals, status, steps, done, initial
      call check_all_described(error, dir//'/list.h5', 14)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_sweep_units

   !> `export --csv` with relative names: a header of names and units, then one
   !> line per sample with as many comma-separated fields as columns.
   subroutine test_export_csv(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, line
      character(len=2048) :: buf
      integer :: stat, n, unit, ios, k, lines
      dir = scratch_dir('filescsv')
      ! 0.1 s in steps of 0.01 saved every step: 11 samples
      stat = run_command(dir, 'simulate --t-end 0.1 --dt 0.01 --save-every 1 --output '// &
                         dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      stat = run_command(dir, 'export '//dir//'/sim.h5 --csv t q energy F01')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 12, 'header and 11 lines, got '// &
                      to_str(n)//': '//text)
      if (allocated(error)) return
      open (newunit=unit, file=dir//'/stdout', status='old', action='read')
      lines = 0
      do
         read (unit, '(a)', iostat=ios) buf
         if (ios /= 0) exit
         lines = lines + 1
         line = trim(buf)
         if (lines == 1) then
            call check_true(error, line == 't [s],q1 [rad],q2 [rad],energy [J],'// &
                            'F01_x [N],F01_y [N]', 'header: '//line)
         else
            k = count([(line(stat:stat) == ',', stat=1, len(line))])
            call check_true(error, k == 5, 'six fields in line '//to_str(lines)//': '//line)
            if (lines == 2) call check_true(error, line(1:24) == &
               '0.0000000000000000E+000,', 'first time 0: '//line)
         end if
         if (allocated(error)) exit
      end do
      close (unit)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_export_csv

   !> `export --csv` of a (2, 3000) dataset (h5py order): a header of 3000 names
   !> w1 [m] … w3000 [m] and two lines of 3000 fields (built in one buffer each).
   subroutine test_export_wide_csv(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, line
      character(len=200000) :: buf
      type(h5file_t) :: h5
      real(dp) :: w(3000, 2)
      integer :: stat, unit, ios, lines, i
      dir = scratch_dir('fileswide')
      w(:, 1) = [(real(i, dp), i=1, 3000)]
      w(:, 2) = -w(:, 1)
      call h5%open(dir//'/wide.h5', 'w', error)
      if (allocated(error)) return
      call h5%write('/data/w', w, error, units='m', description='wide')
      call h5%close()
      if (allocated(error)) return
      stat = run_command(dir, 'export '//dir//'/wide.h5 --csv w')
      call check_true(error, stat == 0, 'export exits 0')
      if (allocated(error)) return
      open (newunit=unit, file=dir//'/stdout', status='old', action='read')
      lines = 0
      do
         read (unit, '(a)', iostat=ios) buf
         if (ios /= 0) exit
         lines = lines + 1
         line = trim(buf)
         call check_true(error, count([(line(i:i) == ',', i=1, len(line))]) == 2999, &
                         '3000 fields in line '//to_str(lines))
         if (lines == 1) call check_true(error, line(1:16) == 'w1 [m],w2 [m],w3' .and. &
            line(len(line) - 15:) == 'w2999 [m],w3000 [m]'(4:), 'header: '//line(1:40))
         if (lines == 3) call check_true(error, line(1:24) == &
            '-1.0000000000000000E+000', 'second row: '//line(1:30))
         if (allocated(error)) exit
      end do
      close (unit)
      if (.not. allocated(error)) call check_true(error, lines == 3, 'three lines')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_export_wide_csv

   !> An output never replaces an input: through the registry (library) and the
   !> command line (animate onto its own trajectory, with --force), the file
   !> unchanged.
   subroutine test_output_not_input(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      character(len=:), allocatable :: dir, text
      integer :: stat, n
      dir = scratch_dir('filesinput')
      stat = run_command(dir, 'simulate --t-end 0.1 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      if (allocated(error)) return
      call check_output_path(dir//'/sim.h5', .true., err)
      call check_true(error, .not. allocated(err), 'not tracked: replacing is allowed')
      call track_inputs(.true.)
      call register_input(dir//'/sim.h5')
      call check_output_path(dir//'/./sim.h5', .true., err)
      call track_inputs(.false.)
      call check_true(error, allocated(err), 'a registered input is refused')
      if (allocated(error)) return
      call check_true(error, index(err%message, 'is the input') > 0 .and. &
                      index(err%message, '--output') > 0, err%message)
      call check_output_path(dir//'/sim.h5', .true., err)
      call check_true(error, .not. allocated(err), 'tracking off: the registry is empty')
      stat = run_command(dir, 'animate '//dir//'/sim.h5 --output '//dir// &
                         '/sim.h5 --force --fps 5 --size 64x64')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. n == 1 .and. index(text, 'is the input') > 0, &
                      'animate onto its input: exit 2, one line, got '//to_str(stat)//': '// &
                      text)
      call check_true(error, is_hdf5(dir//'/sim.h5'), 'the trajectory is unchanged')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_output_not_input

   !> `export --list` lists every dataset with shape and units; an unknown name,
   !> --list with a dataset and two modes are refused with one line, exit 2.
   subroutine test_export_list(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: stat, n
      dir = scratch_dir('fileslist')
      stat = run_command(dir, 'simulate --t-end 0.1 --dt 0.01 --save-every 1 --output '// &
                         dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      stat = run_command(dir, 'export '//dir//'/sim.h5 --list')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 9 + default_outputs(), 'a header and ' &
                      //to_str(8 + default_outputs())//' datasets, got '//to_str(n)//': '//text)
      call check_true(error, index(text, '/trajectory/q ') > 0 .and. &
                      index(text, '(11, 2)') > 0 .and. index(text, ' rad/s ') > 0, &
                      'path, shape (h5py order) and units: '//text)
      call refused('export '//dir//'/sim.h5 nope', "invalid DATASET 'nope'")
      call refused('export '//dir//'/sim.h5 --list t', '--list takes the file alone')
      call refused('export '//dir//'/sim.h5 --csv --matrix q', 'exclude each other')
      call refused('export '//dir//'/sim.h5 --csv=1 t', '--csv takes no value')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> `dpend args` exits 2 with one stderr line containing `needle`.
      subroutine refused(args, needle)
         character(len=*), intent(in) :: args, needle
         if (allocated(error)) return
         stat = run_command(dir, args)
         call read_text(dir//'/stderr', text, n)
         call check_true(error, stat == 2 .and. n == 1 .and. index(text, needle) > 0, &
                         args//': exit 2 and one line with "'//needle//'", got '// &
                         to_str(stat)//': '//text)
      end subroutine refused
   end subroutine test_export_list

   !> The outputs a simulate file of the default model holds, asked of the factory.
   integer function default_outputs() result(n)
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      type(error_t), allocatable :: err
      spec = model_spec(default_model)
      call new_model(spec, model, err)
      if (allocated(err)) error stop err%message
      n = model%n_outputs()
   end function default_outputs
end module test_files
