!> Reading a measured series for `dpend fit`: a CSV text file with a
!> header line of column names, then one row of numbers per sample.
!>
!> Format (docs in README, example data/fit_example.csv):
!> - lines whose first non-blank character is '#' and blank lines are skipped;
!> - the file may start with a UTF-8 byte order mark (removed; what spreadsheets
!>   write); UTF-16 is refused naming it;
!> - the first other line is the header: names separated by ',', ';' or a tab (the
!>   separator is the one of these that occurs most often in the header, outside
!>   quotes; ties in that order; it is the separator of every row), blanks around a
!>   name ignored, case-insensitive, each optionally followed by a unit in brackets that
!>   must be the expected one ('t [s]', 'theta1 [rad]');
!> - any field, of the header or of a row, may be quoted ("t", "theta1 [rad]", "0.5"):
!>   the quotes are removed, "" inside stands for one quote, and a separator inside
!>   quotes belongs to the field;
!> - the column `t` (s) and the angles of links 1 … N, either `theta1 … thetaN` (from
!>   the hanging position, counter-clockwise, as --theta1: q = θ − π/2), `q1 … qN`
!>   (the project's angles from the horizontal x axis, as `dpend export --csv`
!>   writes them) or `phi1 … phiN` (robotics: relative to the previous link, zero
!>   hanging down, as `dpend export --angles relative` writes them; converted by
!>   dpend_angle_convention, the values as read kept in `raw`); N is the number of
!>   angle columns. Columns with other names are
!>   allowed and ignored (e.g. qdot1);
!> - or, without angle columns, the positions of the far ends of the links (joint i + 1,
!>   the tip for i = N) in the project's frame (origin at the pin A, x to the right, y
!>   up): `x1,y1, …, xN,yN`, each with a length unit [m], [cm] or [mm] (none: m),
!>   converted to m;
!> - every data row has as many fields as the header; t and the observed values are
!>   finite numbers, and the times increase strictly.
!> Everything else is refused with one line that names the file, the line number and
!> the problem; a header with one field names the separators tried. Text of the file
!> echoed in a message has its control characters replaced (`printable`). Numbers
!> are read by the one strict parser (dpend_parse `read_real`).
module dpend_csv
   use dpend_kinds, only: dp, i8, half_pi, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_strings, only: to_str, real_str, to_lower, printable
   use dpend_parse, only: read_real, quote_text => quoted
   use dpend_model, only: max_dof
   use dpend_limits, only: max_time
   use dpend_angle_convention, only: to_absolute
   use dpend_os, only: path_kind, path_missing, path_file, path_directory
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: series_t, read_series, parse_series, csv_format

   !> The separators tried, in the order that breaks ties.
   character(len=1), parameter :: separators(3) = [',', ';', achar(9)]
   !> The UTF-8 byte order mark.
   character(len=3), parameter :: utf8_bom = char(239)//char(187)//char(191)

   !> Largest accepted magnitude of a sample value (angle [rad] or position)
   real(dp), parameter :: max_sample_value = 1e6_dp

   !> Largest series file read [bytes].
   integer(i8), parameter :: max_csv_bytes = 268435456_i8

   !> A measured series of angles, converted to the project's angles q.
   type :: series_t
      integer :: n = 0                    !! links N (angle columns)
      integer :: k = 0                    !! samples (data rows)
      real(dp), allocatable :: t(:)       !! times (k) [s]
      !> the observations (n_obs, k): angles from the horizontal x axis [rad] (n_obs = n),
      !> or the positions x1, y1, …, xN, yN of the link ends [m] (n_obs = 2n)
      real(dp), allocatable :: q(:, :)
      integer :: n_obs = 0                !! observations per sample
      logical :: positions = .false.      !! the file gave positions, not angles
      !> with positions: the points observed (link ends i with both x_i and y_i, in
      !> order; n_obs = 2 size(points)); N = the last one (the tip), the others may be
      !> missing (the elbow of a tip-only series)
      integer, allocatable :: points(:)
      integer, allocatable :: line(:)     !! line number of each row in the file (k)
      logical :: theta = .false.          !! the file gave θ (from hanging), not q
      !> the file gave the relative angles φ1 … φN (robotics: link 1 from hanging,
      !> link i against link i − 1): q holds them converted, `raw` as read [rad]
      logical :: relative = .false.
      real(dp), allocatable :: raw(:, :)
      character(len=1) :: separator = ',' !! field separator: ',', ';' or a tab
      logical :: bom = .false.            !! a UTF-8 byte order mark was removed
      logical :: quoted = .false.         !! some header names were quoted
      !> a model's own coordinates as columns (`coords` of `read_series`): their names
      !> and units, in the model's order; `coords_found` when the file gave them
      character(len=16), allocatable :: coord_names(:), coord_units(:)
      logical :: coords_found = .false.
      !> some angle columns were in degrees ([deg]), converted to rad (× π/180)
      logical :: degrees = .false.
      !> what the named columns (`coords`) are, for messages ('the joint torques'); set:
      !> those columns only, no angles or positions (default: a model's coordinates)
      character(len=:), allocatable :: what
      !> the named columns (`coords`) may be absent altogether (`optional_columns`)
      logical :: optional = .false.
   end type series_t

   !> Radians per degree: a column in [deg] is converted by this factor.
   real(dp), parameter :: rad_per_deg = pi/180.0_dp

contains

   !> Read and check the series file `filename` (see the module's notes).
   subroutine read_series(filename, series, error, coords, units, what, optional_columns)
      character(len=*), intent(in) :: filename          !! the CSV file
      type(series_t), intent(out) :: series             !! the samples
      type(error_t), allocatable, intent(out) :: error  !! the first problem, one line
      !> a model's coordinates (names, units): columns of these names are its q
      !> (instead of theta or q columns), e.g. r [m], phi [rad]
      character(len=*), intent(in), optional :: coords(:), units(:)
      !> what the `coords` columns are, e.g. 'the joint torques' (messages); default:
      !> the model's coordinates
      character(len=*), intent(in), optional :: what
      !> the `coords` columns may be absent altogether: then n = n_obs = 0 and
      !> coords_found false (the rows are still read and checked)
      logical, intent(in), optional :: optional_columns
      character(len=:), allocatable :: text, pre
      integer :: unit, stat
      integer(i8) :: bytes
      character(len=256) :: msg
      pre = "invalid data file '"//printable(filename)//"': "
      select case (path_kind(filename, follow=.true.))
      case (path_file)
      case (path_missing)
         call fatal_error(error, pre//'no such file')
      case (path_directory)
         call fatal_error(error, pre//'is a directory, not a file')
      case default
         call fatal_error(error, pre//'is not a regular file (a FIFO, socket or device)')
      end select
      if (allocated(error)) return
      open (newunit=unit, file=filename, status='old', action='read', access='stream', &
            form='unformatted', iostat=stat, iomsg=msg)
      if (stat /= 0) then
         call fatal_error(error, pre//'cannot be read ('//trim(msg)//')')
         return
      end if
      inquire (unit=unit, size=bytes)
      if (bytes > max_csv_bytes) then
         close (unit)
         call fatal_error(error, pre//'is '//to_str(bytes)//' bytes; at most '// &
                          to_str(max_csv_bytes)//' are read')
         return
      end if
      allocate (character(len=int(max(bytes, 0_i8))) :: text)
      if (bytes > 0) read (unit, iostat=stat, iomsg=msg) text
      close (unit)
      if (stat /= 0) then
         call fatal_error(error, pre//'cannot be read ('//trim(msg)//')')
         return
      end if
      call parse_series(text, series, error, coords, units, what, optional_columns)
      if (allocated(error)) error%message = "invalid data file '"//printable(filename)// &
                                            "' "//error%message
   end subroutine read_series

   !> Parse the whole text of a series file; an error message starts with
   !> 'line L: ' (or 'has ...' for a file without a header or rows).
   subroutine parse_series(text, series, error, coords, units, what, optional_columns)
      character(len=*), intent(in) :: text              !! the file's contents
      type(series_t), intent(out) :: series             !! the samples
      type(error_t), allocatable, intent(out) :: error  !! the first problem
      !> a model's coordinates (names, units; see `read_series`)
      character(len=*), intent(in), optional :: coords(:), units(:)
      !> what the coords columns are (see `read_series`)
      character(len=*), intent(in), optional :: what
      !> the coords columns may be absent (see `read_series`)
      logical, intent(in), optional :: optional_columns
      character(len=1), parameter :: lf = achar(10), cr = achar(13)
      integer :: start, eol, line, n_fields, col_t, cap
      integer :: col_q(2*max_dof)
      real(dp) :: scale(2*max_dof), offset(2*max_dof)
      logical :: header_seen
      character(len=:), allocatable :: row
      real(dp), allocatable :: tt(:), qq(:, :)
      integer, allocatable :: ll(:)
      real(dp) :: values(0:2*max_dof)
      header_seen = .false.
      if (present(coords) .and. present(units)) then
         series%coord_names = coords
         series%coord_units = units
         if (present(what)) series%what = what
         if (present(optional_columns)) series%optional = optional_columns
      end if
      start = 1
      if (len(text) >= 3) then
         if (text(1:3) == utf8_bom) then
            series%bom = .true.
            start = 4
         end if
      end if
      if (len(text) >= 2) then
         if (text(1:2) == char(255)//char(254) .or. text(1:2) == char(254)//char(255)) &
            then
            call fatal_error(error, 'is UTF-16 text (it starts with the byte order mark ' &
                             //trim(merge('FF FE', 'FE FF', text(1:1) == char(255)))// &
                             '); save it as UTF-8 or ASCII CSV')
            return
         end if
      end if
      cap = 256
      allocate (series%t(cap), series%q(2*max_dof, cap), series%line(cap))
      series%k = 0
      n_fields = 0
      col_t = 0
      col_q = 0
      line = 0
      do while (start <= len(text))
         eol = index(text(start:), lf)
         if (eol == 0) then
            eol = len(text) + 1
         else
            eol = start + eol - 1
         end if
         line = line + 1
         row = text(start:eol - 1)
         start = eol + 1
         if (len(row) > 0) then
            if (row(len(row):len(row)) == cr) row = row(:len(row) - 1)
         end if
         if (len_trim(row) == 0) cycle
         if (index(adjustl(row), '#') == 1) cycle
         if (.not. header_seen) then
            series%separator = detect_separator(row)
            call parse_header(row, line, n_fields, col_t, col_q, scale, offset, series, &
                              error)
            if (allocated(error)) return
            header_seen = .true.
            deallocate (series%q)   ! one row per observed column, not the largest count
            allocate (series%q(series%n_obs, cap))
            cycle
         end if
         call parse_row(row, line, series%separator, n_fields, col_t, col_q(:series%n_obs), &
                        scale(:series%n_obs), offset(:series%n_obs), &
                        obs_names(series), values(0:series%n_obs), error)
         if (allocated(error)) return
         call check_row(series, line, values(0:series%n_obs), error)
         if (allocated(error)) return
         call append_row(series, cap, line, values(0:series%n_obs))
      end do
      if (.not. header_seen) then
         call fatal_error(error, 'has no header line (expected e.g. '//example_header(series) &
                          //')')
         return
      end if
      if (series%k == 0) then
         call fatal_error(error, 'has no data rows after the header (line ' &
                          //to_str(line)//' is the last)')
         return
      end if
      tt = series%t(:series%k)
      call move_alloc(tt, series%t)
      qq = series%q(:series%n_obs, :series%k)
      call move_alloc(qq, series%q)
      if (series%relative) then   ! as read, and as the absolute angles q
         series%raw = series%q
         series%q = to_absolute(series%raw)
      end if
      ll = series%line(:series%k)
      call move_alloc(ll, series%line)
   end subroutine parse_series

   !> A row's values are ones the fit can work with (beyond, its sums of squares and
   !> time differences would overflow or vanish): |t| <= max_time, |value| <= 1e6,
   !> and its time is after the previous row's.
   subroutine check_row(series, line, values, error)
      type(series_t), intent(in) :: series              !! the rows so far
      integer, intent(in) :: line                       !! the row's line number
      real(dp), intent(in) :: values(0:)                !! t, observations
      type(error_t), allocatable, intent(out) :: error  !! out of range, not after
      if (abs(values(0)) > max_time) then
         call fatal_error(error, 'line '//to_str(line)//': t = '//real_str(values(0))// &
                          ' s is beyond '//real_str(max_time)//' s')
         return
      end if
      if (any(abs(values(1:series%n_obs)) > max_sample_value)) then
         if (allocated(series%what)) then
            call fatal_error(error, 'line '//to_str(line)//': a value of '//series%what// &
                             ' beyond '//real_str(max_sample_value))
         else
            call fatal_error(error, 'line '//to_str(line)//': a value beyond '// &
                             real_str(max_sample_value)//' (angles in rad, positions in '// &
                             'the file''s unit)')
         end if
         return
      end if
      if (series%k > 0) then
         if (.not. (values(0) - series%t(series%k) >= &
                    1e-9_dp*max(1.0_dp, abs(values(0))))) then
            call fatal_error(error, 'line '//to_str(line)//': t = '// &
                             real_str(values(0))//' s is not after t = '// &
                             real_str(series%t(series%k))//' s of line '// &
                             to_str(series%line(series%k))// &
                             ' by at least 1e-9 max(1, |t|) s '// &
                             '(times must increase)')
            return
         end if
      end if
   end subroutine check_row

   !> Append a row (the arrays doubled when full, `cap` their size).
   subroutine append_row(series, cap, line, values)
      type(series_t), intent(inout) :: series  !! the rows so far
      integer, intent(inout) :: cap            !! rows allocated
      integer, intent(in) :: line              !! the row's line number
      real(dp), intent(in) :: values(0:)       !! t, observations
      real(dp), allocatable :: tt(:), qq(:, :)
      integer, allocatable :: ll(:)
      if (series%k == cap) then
         cap = 2*cap
         allocate (tt(cap), qq(series%n_obs, cap), ll(cap))
         tt(:series%k) = series%t(:series%k)
         qq(:, :series%k) = series%q(:, :series%k)
         ll(:series%k) = series%line(:series%k)
         call move_alloc(tt, series%t)
         call move_alloc(qq, series%q)
         call move_alloc(ll, series%line)
      end if
      series%k = series%k + 1
      series%t(series%k) = values(0)
      series%q(:series%n_obs, series%k) = values(1:series%n_obs)
      series%line(series%k) = line
   end subroutine append_row

   !> The header: the column of t and those of the N angles (or 2N positions), with
   !> the scale and offset that convert each to q [rad] or to m.
   subroutine parse_header(row, line, n_fields, col_t, col_q, scale, offset, series, error)
      character(len=*), intent(in) :: row               !! the header line
      integer, intent(in) :: line                       !! its number
      integer, intent(out) :: n_fields                  !! fields per row
      integer, intent(out) :: col_t                     !! column of t
      integer, intent(out) :: col_q(2*max_dof)          !! column of observation i
      real(dp), intent(out) :: scale(2*max_dof)         !! value = scale × number + offset
      real(dp), intent(out) :: offset(2*max_dof)
      type(series_t), intent(inout) :: series           !! n, n_obs, theta, positions set
      type(error_t), allocatable, intent(out) :: error  !! missing or repeated columns
      character(len=:), allocatable :: field, name, unit, kind, pre, listing
      integer :: start, col, idx, br, col_x(max_dof), col_y(max_dof)
      real(dp) :: sx(max_dof), sy(max_dof)
      logical :: quoted
      pre = 'line '//to_str(line)//' (header): '
      listing = ''
      col_t = 0
      col_q = 0
      col_x = 0
      col_y = 0
      scale = 1.0_dp
      offset = 0.0_dp
      kind = ''
      n_fields = 0
      start = 1
      do while (start <= len(row) + 1)
         call next_field(row, series%separator, start, field, quoted, error)
         if (allocated(error)) then
            error%message = pre//error%message
            return
         end if
         if (quoted) series%quoted = .true.
         n_fields = n_fields + 1
         col = n_fields
         if (n_fields <= 8) then
            if (n_fields > 1) listing = listing//', '
            listing = listing//"'"//printable_40(field)//"'"
         end if
         name = to_lower(field)
         unit = ''
         br = index(name, '[')
         if (br > 0) then
            unit = trim(adjustl(name(br:)))
            name = trim(name(:br - 1))
         end if
         if (name == 't') then
            call time_column(unit, col, pre, col_t, error)
            if (allocated(error)) return
         else if (coordinate_index(series, name) > 0) then
            call coordinate_column(series, name, unit, col, pre, col_q, scale, error)
            if (allocated(error)) return
            kind = 'model'
         else if (allocated(series%coord_names)) then
            continue   ! theta and q columns name the pendulum's angles only
         else if (angle_name(name, 'theta') .or. angle_name(name, 'q') .or. &
                  angle_name(name, 'phi')) then
            call angle_column(name, unit, col, pre, kind, col_q, scale, error)
            if (allocated(error)) return
            if (unit == '[deg]') series%degrees = .true.
            if (allocated(error)) return
         else if (angle_name(name, 'x') .or. angle_name(name, 'y')) then
            call position_column(name, unit, col, pre, col_x, col_y, sx, sy, error)
            if (allocated(error)) return
         end if
      end do
      if (n_fields == 1) then
         call fatal_error(error, pre//'1 field ('//listing//'); separators tried: , ; tab ' &
                          //'(expected a header such as '//example_header(series)//')')
         return
      end if
      if (col_t == 0) then
         call fatal_error(error, pre//"no column 't' among the "//to_str(n_fields)// &
                          ' fields '//listing//trim(merge(', ...', '     ', n_fields > 8))// &
                          ' (separator '//separator_name(series%separator)// &
                          '; expected a header such as '//example_header(series)//')')
         return
      end if
      if (kind == 'model') then
         call coordinates_complete(series, col_q, pre, error)
         return
      end if
      series%n = count(col_q > 0)
      if (series%n == 0 .and. any(col_x > 0 .or. col_y > 0)) then
         call positions_complete(pre, col_x, col_y, sx, sy, col_q, scale, series, error)
         return
      end if
      if (series%n == 0 .and. allocated(series%coord_names) .and. series%optional) then
         series%n_obs = 0
         return
      end if
      if (series%n == 0 .and. allocated(series%coord_names)) then
         if (allocated(series%what)) then
            call fatal_error(error, pre//'no columns '//coordinate_list(series)// &
                             ' ('//series%what//')')
         else
            call fatal_error(error, pre//'no columns '//coordinate_list(series)// &
                             " (the model's coordinates) and no positions (x1,y1)")
         end if
         return
      end if
      if (series%n == 0) then
         call fatal_error(error, pre//'no angle columns (theta1, theta2, ... from the ' &
                          //'hanging position, q1, q2, ... from the horizontal, or phi1, ' &
                          //'phi2, ... relative to the previous link, in rad) and no ' &
                          //'positions (x1,y1, ...)')
         return
      end if
      series%n_obs = series%n
      do idx = 1, series%n
         if (col_q(idx) == 0) then
            call fatal_error(error, pre//'missing column '//kind//to_str(idx)//' ('// &
                             to_str(series%n)//' angle columns must be '//kind//'1 to '// &
                             kind//to_str(series%n)//')')
            return
         end if
      end do
      series%theta = kind == 'theta'
      series%relative = kind == 'phi'
      if (series%theta) offset(:series%n) = -half_pi
   end subroutine parse_header

   !> The column t: once, in s.
   subroutine time_column(unit, col, pre, col_t, error)
      character(len=*), intent(in) :: unit, pre         !! its unit, message prefix
      integer, intent(in) :: col                        !! its column
      integer, intent(inout) :: col_t                   !! column of t (0: none yet)
      type(error_t), allocatable, intent(out) :: error  !! repeated, wrong unit
      if (col_t /= 0) then
         call fatal_error(error, pre//"column 't' appears twice")
         return
      end if
      if (len(unit) > 0 .and. unit /= '[s]') then
         call fatal_error(error, pre//"column 't' has the unit '"//printable_40(unit)// &
                          "' (accepted: [s] or none)")
         return
      end if
      col_t = col
   end subroutine time_column

   !> An angle column thetaI or qI: all of one kind, I in [1, max_dof], once, in rad
   !> or deg (then its scale is π/180).
   subroutine angle_column(name, unit, col, pre, kind, col_q, scale, error)
      character(len=*), intent(in) :: name, unit, pre   !! column, unit, message prefix
      integer, intent(in) :: col                        !! its column
      character(len=:), allocatable, intent(inout) :: kind  !! 'theta', 'q' or ''
      integer, intent(inout) :: col_q(:)                !! column of angle i
      real(dp), intent(inout) :: scale(:)               !! value = scale × number
      type(error_t), allocatable, intent(out) :: error  !! mixed, repeated, wrong unit
      character(len=:), allocatable :: this
      integer :: idx
      if (angle_name(name, 'theta')) then
         this = 'theta'
      else if (angle_name(name, 'phi')) then
         this = 'phi'
      else
         this = 'q'
      end if
      if (len(kind) == 0) kind = this
      if (this /= kind) then
         call fatal_error(error, pre//"column '"//name//"' mixes "//kind//' and '//this// &
                          ' columns (give all angles one way: theta, phi or q)')
         return
      end if
      call link_index(name, len(this) + 1, pre, idx, error)
      if (allocated(error)) return
      if (col_q(idx) /= 0) then
         call fatal_error(error, pre//"column '"//name//"' appears twice")
         return
      end if
      if (len(unit) > 0 .and. unit /= '[rad]' .and. unit /= '[deg]') then
         call fatal_error(error, pre//"column '"//name//"' has the unit '"// &
                          printable_40(unit)// &
                          "' (accepted: [rad], [deg] or none for rad)")
         return
      end if
      col_q(idx) = col
      if (unit == '[deg]') scale(idx) = rad_per_deg
   end subroutine angle_column

   !> The link I of a column named PREFIX I (its digits from `first` on), in
   !> [1, max_dof].
   subroutine link_index(name, first, pre, idx, error)
      character(len=*), intent(in) :: name, pre         !! column, message prefix
      integer, intent(in) :: first                      !! position of the digits
      integer, intent(out) :: idx                       !! the link
      type(error_t), allocatable, intent(out) :: error  !! outside [1, max_dof]
      integer :: stat
      read (name(first:), *, iostat=stat) idx
      if (stat /= 0) idx = 0
      if (idx < 1 .or. idx > max_dof) then
         call fatal_error(error, pre//"column '"//name//"': link "//to_str(idx)// &
                          ' is outside [1, '//to_str(max_dof)//']')
         return
      end if
   end subroutine link_index

   !> A position column xI or yI: I in [1, max_dof], once, in m, cm or mm.
   subroutine position_column(name, unit, col, pre, col_x, col_y, sx, sy, error)
      character(len=*), intent(in) :: name, unit, pre   !! column, unit, message prefix
      integer, intent(in) :: col                        !! its column
      integer, intent(inout) :: col_x(:), col_y(:)      !! columns of x_i and y_i
      real(dp), intent(inout) :: sx(:), sy(:)           !! their scales to m
      type(error_t), allocatable, intent(out) :: error  !! repeated, wrong unit
      integer :: idx
      real(dp) :: f
      call link_index(name, 2, pre, idx, error)
      if (allocated(error)) return
      select case (unit)
      case ('', '[m]')
         f = 1.0_dp
      case ('[cm]')
         f = 0.01_dp
      case ('[mm]')
         f = 0.001_dp
      case default
         call fatal_error(error, pre//"column '"//name//"' has the unit '"// &
                          printable_40(unit)// &
                          "' (accepted: [m], [cm], [mm] or none for m)")
         return
      end select
      if (name(1:1) == 'x') then
         if (col_x(idx) /= 0) then
            call fatal_error(error, pre//"column '"//name//"' appears twice")
            return
         end if
         col_x(idx) = col
         sx(idx) = f
      else
         if (col_y(idx) /= 0) then
            call fatal_error(error, pre//"column '"//name//"' appears twice")
            return
         end if
         col_y(idx) = col
         sy(idx) = f
      end if
   end subroutine position_column

   !> Positions x_i, y_i of link ends: each point given has both columns; N is the
   !> last point given (the tip), and the points before it may be missing (a camera
   !> that sees the tip only: t,x2,y2). Whether the points given determine the motion
   !> is the fit's to judge (`check_observed_points`).
   subroutine positions_complete(pre, col_x, col_y, sx, sy, col_q, scale, series, error)
      character(len=*), intent(in) :: pre               !! message prefix
      integer, intent(in) :: col_x(:), col_y(:)         !! columns of x_i and y_i
      real(dp), intent(in) :: sx(:), sy(:)              !! their scales to m
      integer, intent(inout) :: col_q(:)                !! column of observation i
      real(dp), intent(inout) :: scale(:)               !! value = scale × number
      type(series_t), intent(inout) :: series           !! n, n_obs, points set
      type(error_t), allocatable, intent(out) :: error  !! a half point
      integer :: idx, k
      series%n = 0
      do idx = 1, size(col_x)
         if (col_x(idx) > 0 .or. col_y(idx) > 0) series%n = idx
      end do
      allocate (series%points(0))
      k = 0
      do idx = 1, series%n
         if (col_x(idx) == 0 .and. col_y(idx) == 0) cycle
         if (col_x(idx) == 0 .or. col_y(idx) == 0) then
            call fatal_error(error, pre//'missing column '//trim(merge('x', 'y', &
                             col_x(idx) == 0))//to_str(idx)//' (a point needs both x'// &
                             to_str(idx)//' and y'//to_str(idx)//')')
            return
         end if
         k = k + 1
         series%points = [series%points, idx]
         col_q(2*k - 1) = col_x(idx)
         col_q(2*k) = col_y(idx)
         scale(2*k - 1) = sx(idx)
         scale(2*k) = sy(idx)
      end do
      series%positions = .true.
      series%n_obs = 2*k
   end subroutine positions_complete

   !> Column names of the observations, for messages.
   function obs_names(series) result(names)
      type(series_t), intent(in) :: series
      character(len=16) :: names(series%n_obs)
      integer :: i
      if (series%positions) then   ! the points given, in order
         do i = 1, series%n_obs/2
            names(2*i - 1) = 'x'//to_str(series%points(i))
            names(2*i) = 'y'//to_str(series%points(i))
         end do
         return
      end if
      do i = 1, series%n
         if (series%coords_found) then
            names(i) = series%coord_names(i)
         else if (series%theta) then
            names(i) = 'theta'//to_str(i)
         else
            names(i) = 'q'//to_str(i)
         end if
      end do
   end function obs_names

   !> One data row: t and the observations (converted to q or m).
   subroutine parse_row(row, line, sep, n_fields, col_t, col_q, scale, offset, names, &
                        values, error)
      character(len=*), intent(in) :: row               !! the line
      integer, intent(in) :: line                       !! its number
      character(len=1), intent(in) :: sep               !! the field separator
      integer, intent(in) :: n_fields                   !! fields of the header
      integer, intent(in) :: col_t                      !! column of t
      integer, intent(in) :: col_q(:)                   !! columns of the observations
      real(dp), intent(in) :: scale(:), offset(:)       !! their conversions
      character(len=*), intent(in) :: names(:)          !! their names
      real(dp), intent(out) :: values(0:)               !! t, observations
      type(error_t), allocatable, intent(out) :: error  !! wrong count, bad number
      integer :: start, col, k
      character(len=:), allocatable :: field
      logical :: quoted
      values = 0.0_dp
      col = 0
      start = 1
      do while (start <= len(row) + 1)
         call next_field(row, sep, start, field, quoted, error)
         if (allocated(error)) then
            error%message = 'line '//to_str(line)//': '//error%message
            return
         end if
         col = col + 1
         if (col > n_fields) exit
         if (col == col_t) then
            call parse_number(field, 't', values(0), error)
            if (allocated(error)) return
         else
            do k = 1, size(col_q)
               if (col_q(k) == col) then
                  call parse_number(field, trim(names(k)), values(k), error)
                  if (allocated(error)) return
                  values(k) = scale(k)*values(k) + offset(k)
               end if
            end do
         end if
      end do
      if (col /= n_fields) then
         call fatal_error(error, 'line '//to_str(line)//': '//to_str(col)// &
                          merge(' field ', ' fields', col == 1)//', the header has '// &
                          to_str(n_fields)//' (every row has one value per column)')
      end if
   contains
      !> A number by `parse_real`, after a check that the field holds only the
      !> characters of a number (a message echoes it escaped, at most 40 characters).
      subroutine parse_number(text, name, x, err)
         character(len=*), intent(in) :: text, name
         real(dp), intent(out) :: x
         type(error_t), allocatable, intent(out) :: err
         character(len=:), allocatable :: why, field
         ! the one strict parser (dpend_parse): blanks around the field are allowed
         field = trim(adjustl(text))
         call read_real(field, x, why)
         if (len(why) == 0) return
         if (index(field, ',') > 0) why = 'is not a number (a decimal comma? write a point)'
         call fatal_error(err, 'line '//to_str(line)//', column '//trim(name)//': '// &
                          quote_text(field)//' '//why)
      end subroutine parse_number
   end subroutine parse_row

   !> The separator of a header line: the one of ',', ';', tab that occurs most often
   !> outside quotes (ties in that order; none: ',').
   pure function detect_separator(row) result(sep)
      character(len=*), intent(in) :: row   !! the header line
      character(len=1) :: sep
      integer :: counts(size(separators)), i, k
      logical :: inside
      counts = 0
      inside = .false.
      do i = 1, len(row)
         if (row(i:i) == '"') inside = .not. inside
         if (inside) cycle
         do k = 1, size(separators)
            if (row(i:i) == separators(k)) counts(k) = counts(k) + 1
         end do
      end do
      sep = separators(maxloc(counts, dim=1))
   end function detect_separator

   !> The next field of `row` from position `start` (updated to the start of the field
   !> after; beyond len(row) + 1 after the last): blanks around it removed (and tabs,
   !> unless the tab separates), a quoted field's quotes removed ("" inside: one quote).
   pure subroutine next_field(row, sep, start, field, quoted, error)
      character(len=*), intent(in) :: row               !! the line
      character(len=1), intent(in) :: sep               !! the separator
      integer, intent(inout) :: start                   !! where the field starts
      character(len=:), allocatable, intent(out) :: field  !! its text
      logical, intent(out) :: quoted                    !! it was quoted
      type(error_t), allocatable, intent(out) :: error  !! an unclosed quote, text after one
      character(len=:), allocatable :: blanks
      integer :: i, j, next, open_at
      blanks = ' '
      if (sep /= achar(9)) blanks = ' '//achar(9)
      quoted = .false.
      i = start
      do while (i <= len(row))
         if (index(blanks, row(i:i)) == 0) exit
         i = i + 1
      end do
      if (i <= len(row)) quoted = row(i:i) == '"'
      if (.not. quoted) then
         next = index(row(start:), sep)
         if (next == 0) then
            field = trim_blanks(row(start:))
            start = len(row) + 2
         else
            field = trim_blanks(row(start:start + next - 2))
            start = start + next
         end if
         return
      end if
      open_at = i
      field = ''
      j = i + 1
      do
         if (j > len(row)) then
            call fatal_error(error, 'the quote opened at character '//to_str(open_at)// &
                             ' is not closed')
            return
         end if
         if (row(j:j) == '"') then
            if (j < len(row)) then
               if (row(j + 1:j + 1) == '"') then
                  field = field//'"'
                  j = j + 2
                  cycle
               end if
            end if
            exit
         end if
         next = index(row(j:), '"')
         if (next == 0) next = len(row) - j + 2
         field = field//row(j:j + next - 2)
         j = j + next - 1
      end do
      i = j + 1   ! after the closing quote: blanks, then the separator or the end
      do while (i <= len(row))
         if (index(blanks, row(i:i)) == 0) exit
         i = i + 1
      end do
      if (i > len(row)) then
         start = len(row) + 2
      else if (row(i:i) == sep) then
         start = i + 1
      else
         call fatal_error(error, "text after the quote closed at character "//to_str(j)// &
                          ' (a quoted field ends at the separator '//separator_name(sep)//')')
      end if
   contains
      pure function trim_blanks(t) result(u)
         character(len=*), intent(in) :: t
         character(len=:), allocatable :: u
         integer :: a, b
         a = 1
         b = len(t)
         do while (a <= b)
            if (index(blanks, t(a:a)) == 0) exit
            a = a + 1
         end do
         do while (b >= a)
            if (index(blanks, t(b:b)) == 0) exit
            b = b - 1
         end do
         u = t(a:b)
      end function trim_blanks
   end subroutine next_field

   !> ',' as "','", a tab as 'tab'.
   pure function separator_name(sep) result(t)
      character(len=1), intent(in) :: sep
      character(len=:), allocatable :: t
      if (sep == achar(9)) then
         t = 'tab'
      else
         t = "'"//sep//"'"
      end if
   end function separator_name

   !> What the reader detected that differs from a plain comma-separated file, e.g.
   !> "separator ';', BOM removed, quoted names" ('' for a plain file).
   function csv_format(series) result(t)
      type(series_t), intent(in) :: series   !! as read
      character(len=:), allocatable :: t
      t = ''
      if (series%separator /= ',') t = 'separator '//separator_name(series%separator)
      if (series%bom) t = t//', BOM removed'
      if (series%quoted) t = t//', quoted names'
      if (series%degrees) t = t//', angles in deg converted to rad'
      if (len(t) > 0) then
         if (t(1:1) == ',') t = t(3:)
      end if
   end function csv_format

   !> `name` is `prefix` followed by digits only.
   pure logical function angle_name(name, prefix)
      character(len=*), intent(in) :: name, prefix
      angle_name = .false.
      if (len(name) <= len(prefix)) return
      if (name(:len(prefix)) /= prefix) return
      angle_name = verify(name(len(prefix) + 1:), '0123456789') == 0
   end function angle_name

   !> At most 40 characters of `s`, bytes outside printable ASCII as '?'.
   pure function printable_40(s) result(t)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: t
      t = printable(s(:min(len(s), 40)))
      if (len(s) > 40) t = t//'...'
   end function printable_40

   ! ---------------------------------------------- a model's coordinates as columns

   !> Index of `name` among the model's coordinates (0: none or not given).
   pure integer function coordinate_index(series, name) result(i)
      type(series_t), intent(in) :: series  !! with coord_names
      character(len=*), intent(in) :: name  !! a column name, lower case
      if (allocated(series%coord_names)) then
         do i = 1, size(series%coord_names)
            if (to_lower(trim(series%coord_names(i))) == name) return
         end do
      end if
      i = 0
   end function coordinate_index

   !> Column `col`, named `name` with `unit` ('' or '[...]'), is coordinate i: its
   !> unit must be the coordinate's (or none), and it must not repeat.
   !> A coordinate in rad may be given in deg (its scale then π/180).
   subroutine coordinate_column(series, name, unit, col, pre, col_q, scale, error)
      type(series_t), intent(inout) :: series           !! with coord_names, _units
      character(len=*), intent(in) :: name, unit, pre   !! column, unit, message prefix
      integer, intent(in) :: col                        !! its column
      integer, intent(inout) :: col_q(:)                !! column of each coordinate
      real(dp), intent(inout) :: scale(:)               !! value = scale × number
      type(error_t), allocatable, intent(out) :: error  !! repeated, wrong unit
      integer :: i
      logical :: deg
      i = coordinate_index(series, name)
      deg = trim(series%coord_units(i)) == 'rad' .and. unit == '[deg]'
      if (col_q(i) /= 0) then
         call fatal_error(error, pre//"column '"//name//"' appears twice")
      else if (len(unit) > 0 .and. unit /= '['//to_lower(trim(series%coord_units(i)))//']' &
               .and. &
               .not. deg) then
         call fatal_error(error, pre//"column '"//name//"' has the unit '"// &
                          printable_40(unit)//"' (accepted: ["// &
                          trim(series%coord_units(i))//']'// &
                          trim(merge(', [deg]', '       ', &
                                     trim(series%coord_units(i)) == 'rad'))//' or none)')
      else
         col_q(i) = col
         if (deg) then
            scale(i) = rad_per_deg
            series%degrees = .true.
         end if
      end if
   end subroutine coordinate_column

   !> Every coordinate has its column: the series observes the model's q.
   subroutine coordinates_complete(series, col_q, pre, error)
      type(series_t), intent(inout) :: series           !! n, n_obs set
      integer, intent(in) :: col_q(:)                   !! column of each coordinate
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! a coordinate missing
      integer :: i
      do i = 1, size(series%coord_names)
         if (col_q(i) == 0) then
            call fatal_error(error, pre//'missing column '//trim(series%coord_names(i))// &
                             ' (the columns must be '//coordinate_list(series)//')')
            return
         end if
      end do
      series%n = size(series%coord_names)
      series%n_obs = series%n
      series%coords_found = .true.
   end subroutine coordinates_complete

   !> An example header for messages: 't,theta1,theta2', or 't,tau1,tau2' for the
   !> named columns of `what`.
   function example_header(series) result(s)
      type(series_t), intent(in) :: series  !! with coord_names when named
      character(len=:), allocatable :: s
      integer :: i
      s = 't,theta1,theta2'
      if (.not. allocated(series%what)) return
      s = 't'
      do i = 1, min(2, size(series%coord_names))
         s = s//','//trim(series%coord_names(i))
      end do
   end function example_header

   !> 'r [m], phi [rad]'.
   function coordinate_list(series) result(s)
      type(series_t), intent(in) :: series  !! with coord_names, _units
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(series%coord_names)
         if (i > 1) s = s//', '
         s = s//trim(series%coord_names(i))//' ['//trim(series%coord_units(i))//']'
      end do
   end function coordinate_list
end module dpend_csv
