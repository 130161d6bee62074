!> `dpend export`: datasets of an HDF5 file as whitespace-separated text columns,
!> for gnuplot, or as CSV with a header line of names and units. A 1-D dataset (n)
!> gives one column, a 2-D one (n, k as h5py sees it) gives k columns; all must
!> have the same n. `export_matrix` prints one 2-D dataset as a gnuplot
!> "nonuniform matrix" (for `plot ... with image`); `export_list` lists the
!> datasets of a file with shapes and units. A dataset name without a leading '/'
!> is relative to the command's group ('t' is '/trajectory/t' in a simulate file):
!> it names the one dataset '/NAME' or '/GROUP/NAME' of the file.
module dpend_export
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_hdf5, only: h5file_t
   use dpend_output, only: check_regular_file
   use dpend_limits, only: sci
   use dpend_resources, only: check_memory
   use dpend_cli, only: to_str
   use dpend_strings, only: printable, replace_char
   use dpend_angle_convention, only: to_relative, to_absolute, rates_to_relative, rates_to_absolute
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: export_columns, export_matrix, export_list, max_export_values, print_csv

   !> At most 1e9 values (columns x rows) in one export: the table is indexed with
   !> default integers and printed as text of about 25 bytes a value (25 GB).
   integer(i8), parameter :: max_export_values = 1000000000_i8
   !> At most 32 characters in a coordinate's name read from a file (`column_scheme`).
   integer, parameter :: max_coordinate_len = 32

   !> Text appended piece by piece into one buffer that doubles when full.
   type :: text_buffer_t
      character(len=:), allocatable :: text  !! the buffer (its first n characters used)
      integer :: n = 0                       !! characters used
   contains
      procedure :: add => buffer_add
   end type text_buffer_t

contains

   !> Write the datasets `names` of `filename` as columns to `unit`: separated by
   !> blanks, or with `csv` by commas after a header line "name [units],...".
   !> The table's size is bounded before anything is read (`max_export_values`
   !> values, in the available memory), and every line is built in one buffer of
   !> its final length, so the time is linear in the number of values.
   subroutine export_columns(filename, names, unit, error, csv, angles)
      character(len=*), intent(in) :: filename          !! HDF5 file
      character(len=*), intent(in) :: names(:)          !! dataset paths or relative names
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      logical, intent(in), optional :: csv              !! CSV with a header line
      !> the link angles in this convention, 'relative' or 'absolute' (absent or '':
      !> as stored); the datasets say theirs (attribute `angles`)
      character(len=*), intent(in), optional :: angles
      type(h5file_t) :: h5
      real(dp), allocatable :: table(:, :)
      character(len=:), allocatable :: paths(:)
      type(text_buffer_t) :: header
      real(dp) :: cols, largest
      integer :: j, n
      integer, allocatable :: plan(:)
      logical :: as_csv
      as_csv = .false.
      if (present(csv)) as_csv = csv
      call check_regular_file(filename, "invalid FILE '"//filename//"': ", error)
      if (allocated(error)) return
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      call resolve_all(h5, split_commas(names), paths, error)
      if (.not. allocated(error) .and. as_csv) then
         ! a sweep's maps (n2, n1) in long form: one row per pixel
         if (grid_maps(h5, paths)) then
            call export_long(h5, filename, paths, unit, error)
            call h5%close()
            return
         end if
      end if
      if (.not. allocated(error)) call table_shape(h5, paths, cols, n, largest, error)
      ! the work and memory, before anything is allocated: the table and the
      ! largest dataset read into it
      if (.not. allocated(error)) then
         if (cols*real(max(n, 0), dp) > real(max_export_values, dp)) then
            call fatal_error(error, "invalid DATASET: export of '"//filename//"' would "// &
                             'print '//sci(cols)//' columns x '//to_str(max(n, 0))// &
                             ' rows, at most '//sci(real(max_export_values, dp))// &
                             ' values (export fewer datasets)')
         else
            call check_memory('DATASET', 8.0_dp*(cols*real(max(n, 0), dp) + largest), &
                              "the export of '"//filename//"'", 'export fewer datasets', error)
         end if
      end if
      if (allocated(error)) then
         call h5%close()
         return
      end if
      allocate (table(nint(cols), max(n, 0)))
      if (present(angles)) then
         if (len(angles) > 0) call angle_plan(h5, filename, paths, angles, plan, error)
      end if
      if (.not. allocated(plan)) allocate (plan(size(paths)), source=0)
      if (as_csv .and. .not. allocated(error)) &
         call csv_headers(h5, filename, paths, header, error, plan)
      if (.not. allocated(error)) call read_table(h5, paths, table, error, plan)
      call h5%close()
      if (allocated(error)) return
      if (as_csv) then
         write (unit, '(a)') header%text(1:header%n)
         call print_csv(unit, table)
         return
      end if
      do j = 1, n
         write (unit, '(*(es24.16e3, :, " "))') table(:, j)
      end do
   end subroutine export_columns

   !> The names of `names`, those given as 'a,b' split at the commas (`--csv
   !> t_flip,energy_error`); empty parts are dropped.
   function split_commas(names) result(out)
      character(len=*), intent(in) :: names(:)  !! names as given
      character(len=:), allocatable :: out(:)
      integer :: i, k, n, start, pass
      if (all(index(names, ',') == 0)) then
         out = names   ! as given
         return
      end if
      n = 0
      do pass = 1, 2   ! count the parts, then store them
         if (pass == 2) allocate (character(len=len(names)) :: out(max(n, 1)))
         if (pass == 2 .and. n == 0) out(1) = ''   ! refused by resolve_all, as before
         n = 0
         do i = 1, size(names)
            start = 1
            do k = 1, len_trim(names(i)) + 1
               if (k <= len_trim(names(i))) then
                  if (names(i)(k:k) /= ',') cycle
               end if
               if (k > start) then
                  n = n + 1
                  if (pass == 2) out(n) = names(i)(start:k - 1)
               end if
               start = k + 1
            end do
         end do
      end do
   end function split_commas

   !> True if every dataset of `paths` is a map of a grid sweep: 2-D (n2, n1) in h5py
   !> order, with /sweep/axis1 (n1) and /sweep/axis2 (n2) in the file.
   logical function grid_maps(h5, paths)
      type(h5file_t), intent(inout) :: h5       !! open file
      character(len=*), intent(in) :: paths(:)  !! dataset paths
      integer, allocatable :: dims(:), d1(:), d2(:)
      type(error_t), allocatable :: err
      integer :: i
      grid_maps = .false.
      if (.not. (h5%exists('/sweep/axis1') .and. h5%exists('/sweep/axis2'))) return
      call h5%shape('/sweep/axis1', d1, err)
      if (.not. allocated(err)) call h5%shape('/sweep/axis2', d2, err)
      if (allocated(err)) return
      if (size(d1) /= 1 .or. size(d2) /= 1) return
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, err)
         if (allocated(err)) return
         if (size(dims) /= 2) return
         if (dims(1) /= d1(1) .or. dims(2) /= d2(1)) return
      end do
      grid_maps = .true.
   end function grid_maps

   !> A sweep's maps `paths` as CSV in long form: a header of the axes,
   !> named by the file's /sweep attributes axis1, axis2 ('theta1 [rad]'), and one
   !> column per map ('t_flip [s]'), then one row per pixel, axis 1 fastest. The
   !> axis names are checked (letters, digits, '_', '/'; at most 32 characters), and
   !> the table's size and memory before anything is read.
   subroutine export_long(h5, filename, paths, unit, error)
      type(h5file_t), intent(inout) :: h5               !! open file
      character(len=*), intent(in) :: filename          !! its name, for messages
      character(len=*), intent(in) :: paths(:)          !! the maps (`grid_maps`)
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! refused or unreadable
      type(text_buffer_t) :: header
      real(dp), allocatable :: table(:, :), a1(:), a2(:), v2(:, :)
      integer, allocatable :: dims(:)
      real(dp) :: values
      integer :: i, j1, j2, n1, n2
      call h5%shape(trim(paths(1)), dims, error)
      if (allocated(error)) return
      n1 = dims(1); n2 = dims(2)
      values = real(2 + size(paths), dp)*real(n1, dp)*real(n2, dp)
      if (values > real(max_export_values, dp)) then
         call fatal_error(error, "invalid DATASET: export of '"//filename//"' would print "// &
                          sci(values)//' values, at most '// &
                          sci(real(max_export_values, dp))//' (export fewer datasets)')
         return
      end if
      call check_memory('DATASET', 8.0_dp*(values + real(n1, dp)*real(n2, dp)), &
                        "the export of '"//filename//"'", 'export fewer datasets', error)
      if (allocated(error)) return
      do i = 1, 2
         if (i > 1) call header%add(',')
         call axis_header(i)
         if (allocated(error)) return
      end do
      do i = 1, size(paths)
         call header%add(',')
         call csv_header(h5, filename, trim(paths(i)), 0, header, error)
         if (allocated(error)) return
      end do
      call h5%read('/sweep/axis1', a1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', a2, error)
      if (allocated(error)) return
      allocate (table(2 + size(paths), n1*n2))
      do j2 = 1, n2
         do j1 = 1, n1
            table(1, j1 + (j2 - 1)*n1) = a1(j1)
            table(2, j1 + (j2 - 1)*n1) = a2(j2)
         end do
      end do
      do i = 1, size(paths)
         call h5%read(trim(paths(i)), v2, error)
         if (allocated(error)) return
         table(2 + i, :) = reshape(v2, [n1*n2])
      end do
      write (unit, '(a)') header%text(1:header%n)
      call print_csv(unit, table)
   contains
      !> 'theta1 [rad]': the axis name from the /sweep attribute, the units of the
      !> axis dataset ('axis1' when the attribute is missing).
      subroutine axis_header(k)
         integer, intent(in) :: k
         character(len=:), allocatable :: name, units
         character(len=*), parameter :: allowed = 'abcdefghijklmnopqrstuvwxyz'// &
            'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_/'
         character(len=5) :: key
         key = 'axis'//achar(iachar('0') + k)
         name = key
         if (h5%attr_exists('/sweep', key)) call h5%readattr('/sweep', key, name, error)
         if (allocated(error)) return
         if (len(name) == 0 .or. len(name) > 32 .or. verify(name, allowed) > 0) then
            call fatal_error(error, "invalid FILE '"//filename//"': the /sweep attribute "// &
                             key//" ('"//printable(name(1:min(len(name), 40)))//"') is not "// &
                             "an axis name (letters, digits, '_', '/'; 1 to 32 characters)")
            return
         end if
         units = ''
         if (h5%attr_exists('/sweep/'//key, 'units')) &
            call h5%readattr('/sweep/'//key, 'units', units, error)
         if (allocated(error)) return
         if (index(units, ',') > 0) units = ''   ! a CSV field holds no comma
         if (len_trim(units) > 0) then
            call header%add(name//' ['//trim(units)//']')
         else
            call header%add(name)
         end if
      end subroutine axis_header
   end subroutine export_long

   !> The columns (`cols`, counted in real(dp): no overflow) and rows `n` of the
   !> datasets `paths`, and the values of the largest: one column for a 1-D
   !> dataset, k for a 2-D (n, k) one, N k for a 3-D (n, N, k) one (h5py order).
   !> A dataset of another rank, or of another length n, is refused.
   subroutine table_shape(h5, paths, cols, n, largest, error)
      type(h5file_t), intent(inout) :: h5               !! open file
      character(len=*), intent(in) :: paths(:)          !! dataset paths
      real(dp), intent(out) :: cols                     !! columns of the table
      integer, intent(out) :: n                         !! rows (-1: no dataset)
      real(dp), intent(out) :: largest                  !! values of the largest dataset
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer, allocatable :: dims(:)
      integer :: i
      cols = 0.0_dp
      largest = 0.0_dp
      n = -1
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, error)
         if (allocated(error)) exit
         if (size(dims) == 1) then
            cols = cols + 1.0_dp
         else if (size(dims) == 2) then
            cols = cols + real(dims(1), dp)
         else if (size(dims) == 3) then   ! (samples, N, 2): one column per component
            cols = cols + real(dims(1), dp)*real(dims(2), dp)
         else
            call fatal_error(error, "export: '"//trim(paths(i))//"' is not 1-D, 2-D or 3-D")
            exit
         end if
         largest = max(largest, product(real(dims, dp)))
         if (n >= 0 .and. dims(size(dims)) /= n) then
            call fatal_error(error, "export: '"//trim(paths(i))//"' has another length")
            exit
         end if
         n = dims(size(dims))
      end do
   end subroutine table_shape

   !> The CSV header line of the datasets `paths` (`csv_header` for each).
   subroutine csv_headers(h5, filename, paths, header, error, plan)
      type(h5file_t), intent(inout) :: h5               !! open file
      character(len=*), intent(in) :: filename          !! its name, for messages
      character(len=*), intent(in) :: paths(:)          !! dataset paths
      type(text_buffer_t), intent(inout) :: header      !! the header line
      type(error_t), allocatable, intent(out) :: error  !! an attribute refused
      integer, intent(in) :: plan(:)                    !! the angle conversions (angle_plan)
      integer, allocatable :: dims(:)
      integer :: i
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, error)
         if (allocated(error)) exit
         if (i > 1) call header%add(',')
         if (size(dims) == 3) then
            call csv_header(h5, filename, trim(paths(i)), dims(1)*dims(2), header, error, &
                            dims(1))
         else if (plan(i) /= 0) then
            call csv_header(h5, filename, trim(paths(i)), merge(dims(1), 0, &
                            size(dims) == 2), header, error, &
                            label=converted_name(trim(paths(i)), plan(i)))
         else
            call csv_header(h5, filename, trim(paths(i)), merge(dims(1), 0, &
                            size(dims) == 2), header, error)
         end if
         if (allocated(error)) exit
      end do
   end subroutine csv_headers

   !> The conversion of each dataset to the angle convention asked for: 0 none, 1 to
   !> relative angles, 2 to relative rates, 3 to absolute angles, 4 to absolute rates
   !> (dpend_angle_convention), from the dataset's attribute `angles` ('absolute',
   !> 'absolute rates', 'relative', 'relative rates'). Refused when no dataset holds
   !> link angles (the option would do nothing).
   subroutine angle_plan(h5, filename, paths, angles, plan, error)
      type(h5file_t), intent(inout) :: h5               !! open file
      character(len=*), intent(in) :: filename          !! its name, for messages
      character(len=*), intent(in) :: paths(:)          !! dataset paths
      character(len=*), intent(in) :: angles            !! 'relative' or 'absolute'
      integer, allocatable, intent(out) :: plan(:)      !! per dataset
      type(error_t), allocatable, intent(out) :: error  !! no link angles
      character(len=:), allocatable :: conv
      integer :: i
      logical :: any_angles
      allocate (plan(size(paths)), source=0)
      any_angles = .false.
      do i = 1, size(paths)
         if (.not. h5%attr_exists(trim(paths(i)), 'angles')) cycle
         call h5%readattr(trim(paths(i)), 'angles', conv, error)
         if (allocated(error)) return
         any_angles = .true.
         select case (angles//' '//conv)
         case ('relative absolute'); plan(i) = 1
         case ('relative absolute rates'); plan(i) = 2
         case ('absolute relative'); plan(i) = 3
         case ('absolute relative rates'); plan(i) = 4
         end select
      end do
      if (.not. any_angles) call fatal_error(error, "invalid angles: none of the datasets " &
         //"of '"//printable(filename)//"' asked for holds link angles (their attribute " &
         //"'angles'), so --angles "//angles//' would change nothing')
   end subroutine angle_plan

   !> The name of a converted dataset's columns: q → phi, qdot → phidot, qddot →
   !> phiddot; other names get '_rel' (to relative) or '_abs' (to absolute).
   pure function converted_name(path, how) result(name)
      character(len=*), intent(in) :: path
      integer, intent(in) :: how
      character(len=:), allocatable :: name
      name = path(index(path, '/', back=.true.) + 1:)
      if (how <= 2) then
         select case (name)
         case ('q'); name = 'phi'
         case ('qdot'); name = 'phidot'
         case ('qddot'); name = 'phiddot'
         case default; name = name//'_rel'
         end select
      else
         name = name//'_abs'
      end if
   end function converted_name

   !> Read the datasets `paths` into the columns of `table` (its shape from
   !> `table_shape`), each dataset's columns after the previous one's.
   subroutine read_table(h5, paths, table, error, plan)
      type(h5file_t), intent(inout) :: h5               !! open file
      character(len=*), intent(in) :: paths(:)          !! dataset paths
      real(dp), intent(inout) :: table(:, :)            !! (columns, rows)
      type(error_t), allocatable, intent(out) :: error  !! a read failed
      !> the angle conversion of each dataset (`angle_plan`; absent: none)
      integer, intent(in), optional :: plan(:)
      real(dp), allocatable :: v1(:), v2(:, :), v3(:, :, :)
      integer, allocatable :: dims(:)
      integer :: i, col
      col = 0
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, error)
         if (allocated(error)) exit
         if (size(dims) == 1) then
            call h5%read(trim(paths(i)), v1, error)
            if (allocated(error)) exit
            table(col + 1, :) = v1
            col = col + 1
         else if (size(dims) == 2) then
            call h5%read(trim(paths(i)), v2, error)
            if (allocated(error)) exit
            if (present(plan)) then
               select case (plan(i))
               case (1); v2 = to_relative(v2)
               case (2); v2 = rates_to_relative(v2)
               case (3); v2 = to_absolute(v2)
               case (4); v2 = rates_to_absolute(v2)
               end select
            end if
            table(col + 1:col + dims(1), :) = v2
            col = col + dims(1)
         else
            call h5%read(trim(paths(i)), v3, error)
            if (allocated(error)) exit
            table(col + 1:col + dims(1)*dims(2), :) = &
               reshape(v3, [dims(1)*dims(2), dims(3)])
            col = col + dims(1)*dims(2)
         end if
      end do
   end subroutine read_table

   !> Print the rows of `table` as comma-separated lines, each built in one buffer
   !> of its final length (the time is linear in the number of values).
   subroutine print_csv(unit, table, stat)
      integer, intent(in) :: unit           !! output unit
      real(dp), intent(in) :: table(:, :)   !! (columns, rows)
      !> the status of the writes (0, or the first failure's, the rest not written);
      !> absent: a failed write stops the program
      integer, intent(out), optional :: stat
      character(len=:), allocatable :: line
      character(len=32) :: field
      integer :: i, j, pos, ios
      allocate (character(len=25*max(size(table, 1), 1)) :: line)
      if (present(stat)) stat = 0
      do j = 1, size(table, 2)
         pos = 0
         do i = 1, size(table, 1)
            write (field, '(es24.16e3)') table(i, j)
            if (i > 1) then
               line(pos + 1:pos + 1) = ','
               pos = pos + 1
            end if
            field = adjustl(field)
            line(pos + 1:pos + len_trim(field)) = trim(field)
            pos = pos + len_trim(field)
         end do
         if (present(stat)) then
            write (unit, '(a)', iostat=ios) line(1:pos)
            stat = ios
            if (ios /= 0) return
         else
            write (unit, '(a)') line(1:pos)
         end if
      end do
   end subroutine print_csv

   !> Append `piece` to the buffer, doubling its capacity when full (linear time
   !> over all appends).
   subroutine buffer_add(self, piece)
      class(text_buffer_t), intent(inout) :: self  !! the buffer
      character(len=*), intent(in) :: piece        !! text to append
      character(len=:), allocatable :: bigger
      if (.not. allocated(self%text)) allocate (character(len=max(256, 2*len(piece))) :: &
         self%text)
      if (self%n + len(piece) > len(self%text)) then
         allocate (character(len=max(2*len(self%text), self%n + len(piece))) :: bigger)
         bigger(1:self%n) = self%text(1:self%n)
         call move_alloc(bigger, self%text)
      end if
      self%text(self%n + 1:self%n + len(piece)) = piece
      self%n = self%n + len(piece)
   end subroutine buffer_add

   !> Append the CSV column names of dataset `path` with their units, comma-separated,
   !> to `header`: "t [s]" for a 1-D dataset, "q1 [rad],q2 [rad]" for k = 2 columns
   !> (names from `column_name`). Units listed per block of columns ('rad, rad/s'
   !> for 4 columns: rad, rad, rad/s, rad/s) are spread over them; other commas
   !> become ';'. A dataset without units gets no brackets; a `units` attribute
   !> that is not one string is refused.
   subroutine csv_header(h5, filename, path, k, header, error, inner, label)
      type(h5file_t), intent(inout) :: h5   !! open file
      character(len=*), intent(in) :: filename  !! its name, for messages
      character(len=*), intent(in) :: path  !! dataset path
      integer, intent(in) :: k              !! columns, 0 for a 1-D dataset
      type(text_buffer_t), intent(inout) :: header      !! the header line so far
      type(error_t), allocatable, intent(out) :: error  !! units not a string
      !> For a 3-D dataset (samples, N, inner): columns NAME_i_x, NAME_i_y (inner = 2)
      !> or NAME_i_j, i = 1 … N.
      integer, intent(in), optional :: inner
      !> the columns' name instead of the dataset's (converted angles: phi1, phi2)
      character(len=*), intent(in), optional :: label
      character(len=:), allocatable :: name, units, unit_j
      character(len=64), allocatable :: parts(:)
      character(len=max_coordinate_len), allocatable :: coords(:)
      logical :: vector
      integer :: j, m, pos
      name = path(index(path, '/', back=.true.) + 1:)
      if (present(label)) name = label
      units = ''
      if (h5%attr_exists(path, 'units')) call h5%readattr(path, 'units', units, error)
      if (allocated(error)) return
      ! split 'a, b, c' into its m parts
      m = 1 + count_commas(units)
      allocate (parts(m))
      block
         character(len=:), allocatable :: rest
         rest = units
         do j = 1, m
            pos = index(rest, ',')
            if (pos == 0) then
               parts(j) = adjustl(rest)
            else
               parts(j) = adjustl(rest(1:pos - 1))
               rest = rest(pos + 1:)
            end if
         end do
      end block
      if (k == 0) then
         call header%add(name//bracket(replace_char(units, ',', ';')))
         return
      end if
      vector = .false.
      if (.not. present(inner) .and. .not. present(label)) then
         call column_scheme(h5, filename, path, name, k, vector, coords, error)
         if (allocated(error)) return
      end if
      do j = 1, k
         if (m > 1 .and. mod(k, m) == 0) then
            unit_j = trim(parts((j - 1)/(k/m) + 1))
         else
            unit_j = replace_char(units, ',', ';')
         end if
         if (j > 1) call header%add(',')
         if (present(inner)) then
            call header%add(name//'_'//to_str((j - 1)/inner + 1)//'_'// &
                            component(mod(j - 1, inner) + 1, inner)//bracket(unit_j))
         else
            call header%add(column_name(name, j, vector, coords)//bracket(unit_j))
         end if
      end do
   contains
      !> 'x', 'y' for pairs, else the index.
      pure function component(c, n_c) result(t)
         integer, intent(in) :: c, n_c
         character(len=:), allocatable :: t
         if (n_c == 2) then
            t = merge('x', 'y', c == 1)
         else
            t = to_str(c)
         end if
      end function component
      !> Number of commas in `text`.
      pure integer function count_commas(text) result(c)
         character(len=*), intent(in) :: text
         integer :: i
         c = 0
         do i = 1, len(text)
            if (text(i:i) == ',') c = c + 1
         end do
      end function count_commas
      !> ' [u]', or nothing for blank units.
      pure function bracket(u) result(t)
         character(len=*), intent(in) :: u
         character(len=:), allocatable :: t
         if (len_trim(u) == 0) then
            t = ''
         else
            t = ' ['//trim(u)//']'
         end if
      end function bracket
   end subroutine csv_header

   !> How the k columns of the 2-D dataset `path` (last name `name`) are named. A
   !> vector, a dataset whose description ends in "(x, y)" (k = 2): NAME_x, NAME_y.
   !> The coordinates q, qdot, qddot, p of a file with the root attribute
   !> `coordinates` (k names, as simulate writes it): `coords`, the names given
   !> there. Else neither (NAME1 … NAMEk, NAME_1 … when NAME ends in a digit). A
   !> `description` or `coordinates` attribute that is not one string is refused, as
   !> are coordinates that are not k names of letters, digits and '_' (a file from
   !> elsewhere puts nothing else into a CSV header).
   subroutine column_scheme(h5, filename, path, name, k, vector, coords, error)
      type(h5file_t), intent(inout) :: h5     !! open file
      character(len=*), intent(in) :: filename  !! its name, for messages
      character(len=*), intent(in) :: path    !! dataset path
      character(len=*), intent(in) :: name    !! its last name
      integer, intent(in) :: k                !! its columns
      logical, intent(out) :: vector          !! an (x, y) vector
      !> the coordinates' names (allocated for q, qdot, qddot, p with `coordinates`)
      character(len=max_coordinate_len), allocatable, intent(out) :: coords(:)
      type(error_t), allocatable, intent(out) :: error  !! an attribute refused
      character(len=:), allocatable :: text
      character(len=*), parameter :: word = 'abcdefghijklmnopqrstuvwxyz'// &
         'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
      integer :: i, n, pos
      vector = .false.
      text = ''
      if (k == 2 .and. h5%attr_exists(path, 'description')) &
         call h5%readattr(path, 'description', text, error)
      if (allocated(error)) return
      vector = k == 2 .and. len_trim(text) >= 6
      if (vector) vector = text(len_trim(text) - 5:len_trim(text)) == '(x, y)'
      if (vector) return
      if (all(name /= [character(len=5) :: 'q', 'qdot', 'qddot', 'p'])) return
      if (.not. h5%attr_exists('/', 'coordinates')) return
      call h5%readattr('/', 'coordinates', text, error)
      if (allocated(error)) return
      allocate (coords(k))
      n = 0
      pos = 1
      do while (pos <= len(text))
         if (text(pos:pos) == ' ') then
            pos = pos + 1
            cycle
         end if
         i = scan(text(pos:), ' ')
         if (i == 0) i = len(text) - pos + 2
         n = n + 1
         if (n > k .or. i - 1 > max_coordinate_len .or. &
             verify(text(pos:pos + i - 2), word) > 0) exit
         coords(n) = text(pos:pos + i - 2)
         pos = pos + i
      end do
      if (n /= k .or. pos <= len(text)) call fatal_error(error, "invalid FILE '"// &
         filename//"': the root attribute 'coordinates' ('"//printable(text(1:min(len(text), &
         80)))//"') is not "//to_str(k)//" names of letters, digits and '_' (one per "// &
         "column of '"//path//"')")
   end subroutine column_scheme

   !> The name of column j of a 2-D dataset NAME (`column_scheme`): NAME_x, NAME_y of
   !> a vector; of a coordinate dataset, the coordinate's name c (q), c//'dot'
   !> (qdot), c//'ddot' (qddot), 'p_'//c (p), or today's q1, qdot1, qddot1, p1 when
   !> c is 'q' and the column number (the rods' angles); else NAMEj, or NAME_j when
   !> NAME ends in a digit.
   pure function column_name(name, j, vector, coords) result(t)
      character(len=*), intent(in) :: name  !! the dataset's last name
      integer, intent(in) :: j              !! the column
      logical, intent(in) :: vector         !! an (x, y) vector
      !> the coordinates' names, or unallocated
      character(len=max_coordinate_len), allocatable, intent(in) :: coords(:)
      character(len=:), allocatable :: t, c
      if (vector) then
         t = name//'_'//merge('x', 'y', j == 1)
         return
      end if
      if (allocated(coords)) then
         c = trim(coords(j))
         if (c /= 'q'//to_str(j)) then
            select case (name)
            case ('q')
               t = c
            case ('qdot')
               t = c//'dot'
            case ('qddot')
               t = c//'ddot'
            case default
               t = 'p_'//c
            end select
            return
         end if
      end if
      if (scan(name(len(name):len(name)), '0123456789') > 0) then
         t = name//'_'//to_str(j)
      else
         t = name//to_str(j)
      end if
   end function column_name

   !> Write one line per dataset of `filename` to `unit`: path, shape as h5py shows
   !> it, units ('?' if none) and description.
   subroutine export_list(filename, unit, error)
      character(len=*), intent(in) :: filename          !! HDF5 file
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! unreadable
      type(h5file_t) :: h5
      character(len=:), allocatable :: paths(:), units, text, shape_text
      character(len=40), allocatable :: shapes(:), unit_list(:)
      character(len=:), allocatable :: texts(:)
      type(error_t), allocatable :: err
      integer, allocatable :: dims(:)
      integer :: i, j, wp, ws, wu, wt
      call check_regular_file(filename, "invalid FILE '"//filename//"': ", error)
      if (allocated(error)) return
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      call h5%datasets('/', paths, error)
      if (allocated(error)) then
         call h5%close()
         return
      end if
      allocate (shapes(size(paths)), unit_list(size(paths)))
      allocate (character(len=200) :: texts(size(paths)))
      do i = 1, size(paths)
         call h5%shape(trim(paths(i)), dims, err)
         shape_text = '('
         if (.not. allocated(err)) then
            do j = size(dims), 1, -1   ! h5py order
               shape_text = shape_text//to_str(dims(j))
               if (j > 1 .or. size(dims) == 1) shape_text = shape_text//','
               if (j > 1) shape_text = shape_text//' '
            end do
         end if
         shapes(i) = shape_text//')'
         if (allocated(err)) shapes(i) = '(too large to read)'   ! a dimension > 2^31 - 1
         units = '?'
         if (h5%attr_exists(trim(paths(i)), 'units')) &
            call h5%readattr(trim(paths(i)), 'units', units, error)
         if (allocated(error)) exit
         if (len(units) == 0) units = "''"
         unit_list(i) = units
         text = ''
         if (h5%attr_exists(trim(paths(i)), 'description')) &
            call h5%readattr(trim(paths(i)), 'description', text, error)
         if (allocated(error)) exit
         texts(i) = text
      end do
      call h5%close()
      if (allocated(error)) return
      wp = 4; ws = 5; wu = 5; wt = 0
      do i = 1, size(paths)
         wp = max(wp, len_trim(paths(i)))
         ws = max(ws, len_trim(shapes(i)))
         wu = max(wu, len_trim(unit_list(i)))
      end do
      write (unit, '(a)') padded('path', wp)//'  '//padded('shape', ws)//'  '// &
         padded('units', wu)//'  description'
      do i = 1, size(paths)
         write (unit, '(a)') padded(paths(i), wp)//'  '//padded(shapes(i), ws)//'  '// &
            padded(unit_list(i), wu)//'  '//trim(texts(i))
      end do
   end subroutine export_list

   !> `text` without trailing blanks, padded to `width` columns.
   pure function padded(text, width) result(t)
      character(len=*), intent(in) :: text  !! text
      integer, intent(in) :: width          !! columns
      character(len=:), allocatable :: t
      t = trim(text)//repeat(' ', max(0, width - len_trim(text)))
   end function padded

   !> Full paths of the datasets `names` of the open file (see `resolve`).
   subroutine resolve_all(h5, names, paths, error)
      type(h5file_t), intent(inout) :: h5                      !! open file
      character(len=*), intent(in) :: names(:)                 !! paths or relative names
      character(len=:), allocatable, intent(out) :: paths(:)   !! full paths
      type(error_t), allocatable, intent(out) :: error         !! unknown or ambiguous
      character(len=:), allocatable :: full(:), path
      integer :: i, width
      allocate (character(len=1024) :: full(size(names)))
      width = 1
      do i = 1, size(names)
         call resolve(h5, trim(names(i)), path, error)
         if (allocated(error)) return
         full(i) = path
         width = max(width, len(path))
      end do
      allocate (character(len=width) :: paths(size(names)))
      do i = 1, size(names)
         paths(i) = full(i)
      end do
   end subroutine resolve_all

   !> The full path of the dataset `name` of the open file: `name` itself if it
   !> starts with '/', else the one dataset '/name' or '/GROUP/name'.
   subroutine resolve(h5, name, path, error)
      type(h5file_t), intent(inout) :: h5                   !! open file
      character(len=*), intent(in) :: name                  !! path or relative name
      character(len=:), allocatable, intent(out) :: path    !! full path
      type(error_t), allocatable, intent(out) :: error      !! unknown or ambiguous
      character(len=:), allocatable :: all(:), tail
      integer :: i, n, slash
      path = name
      if (len(name) == 0) then
         call fatal_error(error, "invalid DATASET '': give a name (dpend export FILE --list "// &
            "lists them)")
         return
      end if
      if (name(1:1) == '/') return
      call h5%datasets('/', all, error)
      if (allocated(error)) return
      n = 0
      do i = 1, size(all)
         slash = index(all(i)(2:), '/')   ! end of the first component
         tail = trim(all(i)(2:))
         if (slash > 0) tail = trim(all(i)(slash + 2:))
         if (tail == name .or. trim(all(i)) == '/'//name) then
            n = n + 1
            if (n == 1) then
               path = trim(all(i))
            else
               call fatal_error(error, "invalid DATASET '"//name//"': ambiguous ('"//path// &
                  "', '"//trim(all(i))//"'); give the full path")
               return
            end if
         end if
      end do
      if (n == 0) call fatal_error(error, "invalid DATASET '"//name//"': no such dataset "// &
         "(dpend export FILE --list lists them)")
   end subroutine resolve

   !> Write the 2-D dataset `path` of `filename` (h5py shape (ny, nx)) to `unit` as a
   !> gnuplot nonuniform matrix: a first line "nx x(1) ... x(nx)", then one line
   !> "y(j) v(1, j) ... v(nx, j)" per row. x and y come from the 1-D datasets
   !> `xpath` and `ypath` if given, else they are the indices 1, 2, ... Values are
   !> divided by `scale` if given; NaN is printed as NaN (gnuplot leaves it out).
   subroutine export_matrix(filename, path, unit, error, xpath, ypath, scale)
      character(len=*), intent(in) :: filename          !! HDF5 file
      character(len=*), intent(in) :: path              !! 2-D dataset
      integer, intent(in) :: unit                       !! output unit
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      character(len=*), intent(in), optional :: xpath   !! 1-D dataset of x values
      character(len=*), intent(in), optional :: ypath   !! 1-D dataset of y values
      real(dp), intent(in), optional :: scale           !! divide the values by it
      type(h5file_t) :: h5
      real(dp), allocatable :: v(:, :), x(:), y(:), row(:)
      real(dp) :: big
      integer :: i, j
      character(len=*), parameter :: fmt = '(*(es15.7e3, :, " "))'
      character(len=:), allocatable :: full
      call check_regular_file(filename, "invalid FILE '"//filename//"': ", error)
      if (allocated(error)) return
      call h5%open(filename, 'r', error)
      if (allocated(error)) return
      call resolve(h5, trim(path), full, error)
      if (.not. allocated(error)) call h5%read(full, v, error)
      if (.not. allocated(error)) then
         if (present(xpath)) then
            call resolve(h5, trim(xpath), full, error)
            if (.not. allocated(error)) call h5%read(full, x, error)
         else
            x = [(real(i, dp), i=1, size(v, 1))]
         end if
      end if
      if (.not. allocated(error)) then
         if (present(ypath)) then
            call resolve(h5, trim(ypath), full, error)
            if (.not. allocated(error)) call h5%read(full, y, error)
         else
            y = [(real(j, dp), j=1, size(v, 2))]
         end if
      end if
      call h5%close()
      if (allocated(error)) return
      if (size(x) /= size(v, 1) .or. size(y) /= size(v, 2)) then
         call fatal_error(error, "export: the axes do not match the shape of '"// &
                          trim(path)//"'")
         return
      end if
      if (present(scale)) then
         if (.not. (scale > 0.0_dp .and. ieee_is_finite(scale))) then
            call fatal_error(error, 'invalid SCALE: must be finite and > 0')
            return
         end if
         ! refuse quotients beyond the largest real (the division would overflow)
         ! (element by element: an ordered comparison with NaN would trap)
         big = 0.0_dp
         do j = 1, size(v, 2)
            do i = 1, size(v, 1)
               if (ieee_is_finite(v(i, j))) big = max(big, abs(v(i, j)))
            end do
         end do
         ! (nested, not `.and.`: Fortran may evaluate both operands, and huge*scale
         ! overflows for scale > 1)
         if (scale < 1.0_dp) then
            if (big > huge(1.0_dp)*scale) then
               call fatal_error(error, 'invalid SCALE: '//sci(scale)//" makes the values "// &
                                "of '"//trim(path)//"' exceed the largest real (largest "// &
                                '|value| '//sci(big)//'; SCALE must be >= '// &
                                sci(big/huge(1.0_dp))//')')
               return
            end if
         end if
         where (ieee_is_finite(v)) v = v/scale   ! NaN and Inf stay, without arithmetic
      end if
      allocate (row(size(x) + 1))
      row(1) = real(size(x), dp)
      row(2:) = x
      write (unit, fmt) row
      do j = 1, size(y)
         row(1) = y(j)
         row(2:) = v(:, j)
         write (unit, fmt) row
      end do
   end subroutine export_matrix
end module dpend_export
