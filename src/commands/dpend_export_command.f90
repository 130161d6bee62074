!> `dpend export FILE [--csv] DATASET...`, `FILE --matrix DATASET [XAXIS YAXIS
!> [SCALE]]` or `FILE --list`: the entry point `export_command` reads the command line
!> (options may stand anywhere) and prints through the printers of `dpend_export`.
!> Every failure is a refusal: one line, exit 2.
module dpend_export_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, is_long_option, parse_real, real_str, unknown_option_text, &
                        printable
   use dpend_export, only: export_columns, export_matrix, export_list
   use dpend_command_common, only: take_quiet, data_quiet, refusal_line
   implicit none
   private
   public :: export_command, export_help

   character(len=*), parameter :: nl = new_line('a')

contains

   !> Help text of `dpend export`.
   function export_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend export FILE.h5 [--csv] DATASET [DATASET ...]'//nl// &
          '       dpend export FILE.h5 --matrix DATASET [XAXIS YAXIS [SCALE]]'//nl// &
          '       dpend export FILE.h5 --list'//nl// &
          'Print datasets as whitespace-separated columns: a (n) dataset gives one'//nl// &
          'column, an (n, k) dataset (h5py order) gives k; all must share n.'//nl// &
          'A DATASET is a full path (/trajectory/q) or a name relative to the'//nl// &
          "command's group (q, energy; final/q1 in a sweep file)."//nl// &
          '  --csv     comma-separated, after a header line of names and units'//nl// &
          '            ("t [s],q1 [rad],q2 [rad]"; numpy.genfromtxt(names=True) and'//nl// &
          '            pandas.read_csv read it as written)'//nl// &
          '  --angles relative|absolute  the link angles (and their rates) in this'//nl// &
          '            convention: relative (robotics: phi_1 from the hanging position,'//nl// &
          '            phi_i of link i against link i-1; columns phi1.., phidot1..) or'//nl// &
          '            absolute (from the horizontal x axis); default: as stored (each'//nl// &
          "            dataset's attribute 'angles' says which); other datasets as stored"//nl// &
          '  --list    the datasets of the file: path, shape (h5py order), units'//nl// &
          "            ('1': dimensionless) and description"//nl// &
          '  --matrix  a 2-D dataset (ny, nx) as a gnuplot nonuniform matrix, with'//nl// &
          '            the 1-D datasets XAXIS (nx) and YAXIS (ny) as coordinates,'//nl// &
          '            values / SCALE (SCALE > 0, at least '// &
          real_str(tiny(1.0_dp))//')'//nl// &
          '  -h, --help  this text'//nl//data_quiet
   end function export_help

   !> The entry point of `dpend export` (app/main.f90): parse → the printer of the
   !> form asked for, onto standard output. A failure comes back as `error`, a
   !> refusal whose message is the one line 'dpend export: ...'.
   subroutine export_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `export`
      type(error_t), allocatable, intent(out) :: error  !! the refusal
      type(arg_t), allocatable :: rest(:), pos(:)
      logical :: matrix, csv, list
      character(len=:), allocatable :: angles
      integer :: i
      call take_quiet(args, rest)
      if (any([(rest(i)%s == '--help' .or. rest(i)%s == '-h', i=1, size(rest))])) then
         write (output_unit, '(a)') export_help()
         return
      end if
      call parse_export(rest, pos, matrix, csv, list, angles, error)
      if (.not. allocated(error)) then
         if (len(angles) > 0 .and. (list .or. matrix)) then
            call fatal_error(error, '--angles applies to columns and CSV (not with --list ' &
                             //'or --matrix)')
         else if (list) then
            call print_list(pos, error)
         else if (matrix) then
            call print_matrix(pos, error)
         else
            call print_columns(pos, csv, angles, error)
         end if
      end if
      if (allocated(error)) call refusal_line(error, 'export')
   end subroutine export_command

   !> The options of `dpend export` (anywhere; without --help and --quiet) and its
   !> positional arguments (the file, then the datasets and numbers).
   subroutine parse_export(args, pos, matrix, csv, list, angles, error)
      type(arg_t), intent(in) :: args(:)                 !! the arguments after `export`
      type(arg_t), allocatable, intent(out) :: pos(:)    !! the positional arguments
      logical, intent(out) :: matrix, csv, list          !! --matrix, --csv, --list
      character(len=:), allocatable, intent(out) :: angles  !! --angles ('' not given)
      type(error_t), allocatable, intent(out) :: error   !! invalid input
      integer :: i
      logical :: value_next
      matrix = .false.
      csv = .false.
      list = .false.
      angles = ''
      value_next = .false.
      allocate (pos(0))
      do i = 1, size(args)
         if (value_next) then
            value_next = .false.
            if (args(i)%s /= 'relative' .and. args(i)%s /= 'absolute') then
               call fatal_error(error, "invalid angles: '"//printable(args(i)%s)// &
                                "' (accepted: relative, absolute) [--angles]")
               return
            end if
            angles = args(i)%s
            cycle
         end if
         if (args(i)%s == '--angles') then
            if (len(angles) > 0) then
               call fatal_error(error, 'option --angles given twice')
               return
            end if
            value_next = .true.
            if (i == size(args)) call fatal_error(error, 'option --angles needs a value')
         else if (args(i)%s == '--matrix') then
            matrix = .true.
         else if (args(i)%s == '--csv') then
            csv = .true.
         else if (args(i)%s == '--list') then
            list = .true.
         else if (index(args(i)%s, '--matrix=') == 1) then
            call fatal_error(error, 'option --matrix takes no value')
         else if (index(args(i)%s, '--csv=') == 1) then
            call fatal_error(error, 'option --csv takes no value')
         else if (index(args(i)%s, '--list=') == 1) then
            call fatal_error(error, 'option --list takes no value')
         else if (is_long_option(args(i)%s)) then
            call fatal_error(error, unknown_option_text('export', args(i)%s, &
                                                        '--matrix --csv --list --angles --help'))
         else
            pos = [pos, args(i)]
         end if
         if (allocated(error)) return
      end do
      if (count([matrix, csv, list]) > 1) call fatal_error(error, '--csv, --list and '// &
         '--matrix exclude each other (give one)')
   end subroutine parse_export

   !> `FILE --list`: the datasets of the file.
   subroutine print_list(pos, error)
      type(arg_t), intent(in) :: pos(:)                  !! the positional arguments
      type(error_t), allocatable, intent(out) :: error   !! refused or unreadable
      if (size(pos) /= 1) then
         call fatal_error(error, '--list takes the file alone (dpend export FILE.h5 --list)')
         return
      end if
      call export_list(pos(1)%s, output_unit, error)
   end subroutine print_list

   !> `FILE --matrix DATASET [XAXIS YAXIS [SCALE]]`: one 2-D dataset as a matrix.
   subroutine print_matrix(pos, error)
      type(arg_t), intent(in) :: pos(:)                  !! the positional arguments
      type(error_t), allocatable, intent(out) :: error   !! refused or unreadable
      real(dp) :: scale
      select case (size(pos))
      case (0:1)
         call no_dataset(error)
      case (2)
         call export_matrix(pos(1)%s, pos(2)%s, output_unit, error)
      case (4)
         call export_matrix(pos(1)%s, pos(2)%s, output_unit, error, pos(3)%s, pos(4)%s)
      case (5)
         call parse_real(pos(5)%s, 'SCALE', scale, error)
         if (allocated(error)) return
         if (.not. (scale >= tiny(1.0_dp))) then
            call fatal_error(error, 'invalid SCALE: '//pos(5)%s//' (accepted: a number >= ' &
                             //real_str(tiny(1.0_dp))//')')
            return
         end if
         call export_matrix(pos(1)%s, pos(2)%s, output_unit, error, pos(3)%s, &
                            pos(4)%s, scale)
      case default
         call fatal_error(error, '--matrix takes FILE DATASET [XAXIS YAXIS [SCALE]]')
      end select
   end subroutine print_matrix

   !> `FILE [--csv] DATASET...`: datasets as columns (CSV with a header line).
   subroutine print_columns(pos, csv, angles, error)
      type(arg_t), intent(in) :: pos(:)                  !! the positional arguments
      logical, intent(in) :: csv                         !! --csv
      character(len=*), intent(in) :: angles             !! --angles ('' as stored)
      type(error_t), allocatable, intent(out) :: error   !! refused or unreadable
      character(len=:), allocatable :: paths(:)
      integer :: i, n, width
      n = size(pos)
      if (n < 2) then
         call no_dataset(error)
         return
      end if
      width = 1
      do i = 2, n
         width = max(width, len(pos(i)%s))
      end do
      allocate (character(len=width) :: paths(n - 1))
      do i = 2, n
         paths(i - 1) = pos(i)%s
      end do
      call export_columns(pos(1)%s, paths, output_unit, error, csv, angles)
   end subroutine print_columns

   !> The refusal of a command line without a file and a dataset.
   subroutine no_dataset(error)
      type(error_t), allocatable, intent(out) :: error   !! the refusal
      call fatal_error(error, 'needs a file and at least one dataset (dpend export --help)')
   end subroutine no_dataset
end module dpend_export_command
