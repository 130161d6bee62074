!> Command-line helpers: the argument list, option splitting (`--name value` or
!> `--name=value`) and validated number parsing with one-line error messages.
module dpend_cli
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   !> the one strict parser and escaping helper; `printable` is `escaped` under the
   !> name the messages used before
   use dpend_parse, only: read_real, read_int, quoted, overflows_real, int_text, &
                          printable => escaped
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_is_negative
   implicit none
   private
   public :: arg_t, get_arguments, next_option, parse_real, parse_int, parse_logical
   public :: real_str, seconds_str, to_str, scan_help_config, option_outcome, is_long_option
   public :: overflows_real, to_lower, printable, pad, quoted

   !> Parse an integer (default or 64-bit) for a field.
   interface parse_int
      module procedure parse_int_default, parse_int_i8
   end interface parse_int

   !> Text of an integer (default or 64-bit), without blanks.
   interface to_str
      module procedure int_str
      procedure int_text   ! 64-bit: dpend_parse's
   end interface to_str

   !> One command-line argument.
   type :: arg_t
      character(len=:), allocatable :: s  !! its text
   end type arg_t

contains

   !> All command-line arguments after the program name.
   subroutine get_arguments(args)
      type(arg_t), allocatable, intent(out) :: args(:)  !! the arguments
      integer :: i, n, length
      n = command_argument_count()
      allocate (args(n))
      do i = 1, n
         call get_command_argument(i, length=length)
         allocate (character(len=length) :: args(i)%s)
         call get_command_argument(i, args(i)%s)
      end do
   end subroutine get_arguments

   !> Split the option at args(i): its name (with the leading dashes) and, for
   !> options that take one, its value, from `--name=value` or the next argument
   !> (which must not start with '--'). Advances i past what was consumed. Flags
   !> (`takes_value` false) get value ''. A missing value is an error unless
   !> `missing` is present: then it is reported there, so that the caller can first
   !> tell an unknown option from a known one without its value (`option_outcome`).
   subroutine next_option(args, i, name, value, takes_value, error, missing)
      type(arg_t), intent(in) :: args(:)                 !! all arguments
      integer, intent(inout) :: i                        !! current position
      character(len=:), allocatable, intent(out) :: name !! e.g. '--dt'
      character(len=:), allocatable, intent(out) :: value !! its value or ''
      logical, intent(in) :: takes_value                 !! whether the option has a value
      type(error_t), allocatable, intent(out) :: error   !! missing value
      logical, intent(out), optional :: missing          !! the value is missing
      integer :: eq
      logical :: absent
      if (present(missing)) missing = .false.
      eq = index(args(i)%s, '=')
      if (eq > 0) then
         name = args(i)%s(:eq - 1)
         value = args(i)%s(eq + 1:)
         if (.not. takes_value) call fatal_error(error, 'option '//name//' takes no value')
         i = i + 1
         return
      end if
      name = args(i)%s
      value = ''
      i = i + 1
      if (.not. takes_value) return
      absent = i > size(args)
      if (.not. absent) absent = is_long_option(args(i)%s)
      if (absent) then
         if (present(missing)) then
            missing = .true.
         else
            call fatal_error(error, 'option '//name//' needs a value')
         end if
         return
      end if
      value = args(i)%s
      i = i + 1
   end subroutine next_option

   !> The one error after a command has tried to apply option `name` (`matched`:
   !> it is one of its options; `error`: its value was refused): an unknown
   !> option, a flag (one of `flags`) given a value with '=', a missing value, or
   !> the value's own error, in that order.
   subroutine option_outcome(command, name, matched, missing, flags, error)
      character(len=*), intent(in) :: command             !! e.g. 'simulate'
      character(len=*), intent(in) :: name                !! the option
      logical, intent(in) :: matched                      !! a valued option of the command
      logical, intent(in) :: missing                      !! its value was missing
      character(len=*), intent(in) :: flags(:)            !! the command's flags
      type(error_t), allocatable, intent(inout) :: error  !! the value's error, if any
      if (any(flags == name)) then
         if (allocated(error)) deallocate (error)
         call fatal_error(error, 'option '//name//' takes no value')
      else if (.not. matched) then
         if (allocated(error)) deallocate (error)
         call fatal_error(error, "unknown option '"//printable(name)//"' (dpend "//command// &
                          ' --help lists the options)')
      else if (missing) then
         if (allocated(error)) deallocate (error)
         call fatal_error(error, 'option '//name//' needs a value')
      end if
   end subroutine option_outcome

   !> True if `arg` starts with '--' (an option, never a value).
   pure logical function is_long_option(arg)
      character(len=*), intent(in) :: arg  !! an argument
      is_long_option = .false.
      if (len(arg) >= 2) is_long_option = arg(1:2) == '--'
   end function is_long_option

   !> Parse a finite real number for field `name` with the one strict parser
   !> (`dpend_parse`): the whole token must be the number; the refusal names the field,
   !> the value (escaped) and the offending character.
   subroutine parse_real(text, name, x, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      real(dp), intent(out) :: x                        !! the value
      type(error_t), allocatable, intent(out) :: error  !! not a finite number
      character(len=:), allocatable :: why
      call read_real(text, x, why)
      if (len(why) > 0) call fatal_error(error, 'invalid '//printable(name)//': '// &
                                         quoted(trim(text))//' '//why)
   end subroutine parse_real

   !> `s` with ASCII capitals in lower case.
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s  !! text
      character(len=len(s)) :: t
      integer :: i
      t = s
      do i = 1, len(s)
         if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
      end do
   end function to_lower

   !> `text` without trailing blanks, padded with blanks to `width` columns (at least
   !> one blank).
   pure function pad(text, width) result(t)
      character(len=*), intent(in) :: text  !! text
      integer, intent(in) :: width          !! columns
      character(len=:), allocatable :: t
      t = trim(text)//repeat(' ', max(1, width - len_trim(text)))
   end function pad

   !> Parse an integer for field `name` (the strict parser of `dpend_parse`).
   subroutine parse_int_default(text, name, n, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      integer, intent(out) :: n                         !! the value
      type(error_t), allocatable, intent(out) :: error  !! not an integer
      character(len=:), allocatable :: why
      call read_int(text, n, why)
      if (len(why) > 0) call fatal_error(error, 'invalid '//printable(name)//': '// &
                                         quoted(trim(text))//' '//why)
   end subroutine parse_int_default

   !> Parse a 64-bit integer for field `name` (counts up to 9.2e18).
   subroutine parse_int_i8(text, name, n, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      integer(i8), intent(out) :: n                     !! the value
      type(error_t), allocatable, intent(out) :: error  !! not an integer
      character(len=:), allocatable :: why
      call read_int(text, n, why)
      if (len(why) > 0) call fatal_error(error, 'invalid '//printable(name)//': '// &
                                         quoted(trim(text))//' '//why)
   end subroutine parse_int_i8

   !> Parse a logical (true/false, yes/no, 1/0) for field `name`.
   subroutine parse_logical(text, name, b, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      logical, intent(out) :: b                         !! the value
      type(error_t), allocatable, intent(out) :: error  !! not a logical
      select case (text)
      case ('true', 'yes', '1', 'on', '.true.'); b = .true.
      case ('false', 'no', '0', 'off', '.false.'); b = .false.
      case default
         b = .false.
         call fatal_error(error, 'invalid '//printable(name)//': '//quoted(trim(text))// &
                          ' (accepted: true, false)')
      end select
   end subroutine parse_logical

   !> The one formatter of real numbers for people: the shortest text that reads
   !> back to the same bits (or, with `digits`, rounded to at most that many
   !> significant digits, for measured or derived values). Plain decimals for
   !> 1e-4 <= |x| < 1e6 and for integers up to 1e15 whose plain form is not longer,
   !> else 'd.ddde-12' style: 0.001, 9.8, 20, 1234567, 1e-12, 2.5e6, -2.5e300,
   !> 5e-324, 0.3333333333333333; '0', '-0', 'NaN', 'Infinity', '-Infinity'.
   pure function real_str(x, digits) result(s)
      real(dp), intent(in) :: x                 !! the number
      integer, intent(in), optional :: digits   !! most significant digits (1 to 17)
      character(len=:), allocatable :: s
      character(len=40) :: buf
      character(len=:), allocatable :: mant, plain, expo
      integer :: p, p_max, e, stat, k
      real(dp) :: y
      if (ieee_is_nan(x)) then
         s = 'NaN'
         return
      else if (.not. ieee_is_finite(x)) then
         s = merge('Infinity ', '-Infinity', x > 0.0_dp)
         s = trim(s)
         return
      else if (x == 0.0_dp) then
         s = merge('-0', '0 ', ieee_is_negative(x))
         s = trim(s)
         return
      end if
      p_max = 17
      if (present(digits)) p_max = max(1, min(17, digits))
      do p = 1, p_max
         write (buf, '(es'//int_str(p + 9)//'.'//int_str(p - 1)//'e4)') abs(x)
         if (above_huge(buf)) cycle   ! reading it would overflow
         read (buf, *, iostat=stat) y
         if (stat == 0 .and. y == abs(x)) exit
      end do
      p = min(p, p_max)
      write (buf, '(es'//int_str(p + 9)//'.'//int_str(p - 1)//'e4)') abs(x)
      buf = adjustl(buf)
      k = index(buf, 'E')
      read (buf(k + 1:), *) e
      ! the significant digits without the point and trailing zeros: x = d.ddd 10^e
      mant = buf(1:1)//buf(3:k - 1)
      do while (len(mant) > 1 .and. mant(len(mant):len(mant)) == '0')
         mant = mant(:len(mant) - 1)
      end do
      expo = mant(1:1)
      if (len(mant) > 1) expo = expo//'.'//mant(2:)
      expo = expo//'e'//int_str(e)
      if (e >= -4 .and. e < 6) then
         s = decimal(mant, e)
      else if (e >= 6 .and. e < 15 .and. len(mant) <= e + 1) then
         plain = decimal(mant, e)
         s = expo
         if (len(plain) <= len(expo)) s = plain
      else
         s = expo
      end if
      if (x < 0.0_dp) s = '-'//s
   contains
      !> Whether the text 'd.dddE+eeee' of a positive number exceeds huge(1.0_dp).
      pure logical function above_huge(t)
         character(len=*), intent(in) :: t
         real(dp) :: m
         integer :: k, ee, stat
         above_huge = .false.
         k = index(t, 'E')
         read (t(k + 1:), *, iostat=stat) ee
         if (stat /= 0 .or. ee < 308) return
         read (t(:k - 1), *, iostat=stat) m
         above_huge = ee > 308 .or. m > 1.7976931348623157_dp
      end function above_huge

      !> Plain decimal text of the digits `m` times 10^(e - len(m) + 1).
      pure function decimal(m, e) result(t)
         character(len=*), intent(in) :: m
         integer, intent(in) :: e
         character(len=:), allocatable :: t
         if (e < 0) then
            t = '0.'//repeat('0', -e - 1)//m
         else if (len(m) <= e + 1) then
            t = m//repeat('0', e + 1 - len(m))
         else
            t = m(:e + 1)//'.'//m(e + 2:)
         end if
      end function decimal
   end function real_str

   !> A duration for people, from `real_str`: two significant digits below 1 s
   !> (0.4, 0.043), one decimal above (2.5, 12.3, 1234.5); never '.4'.
   pure function seconds_str(t) result(s)
      real(dp), intent(in) :: t  !! seconds
      character(len=:), allocatable :: s
      if (.not. ieee_is_finite(t)) then
         s = real_str(t)
      else if (abs(t) < 1.0_dp) then
         s = real_str(t, 2)
      else
         s = real_str(t, min(17, floor(log10(abs(t))) + 2))
      end if
   end function seconds_str

   pure function int_str(i) result(s)
      integer, intent(in) :: i  !! the number
      character(len=:), allocatable :: s
      s = int_text(int(i, i8))
   end function int_str

   !> The first pass of every command's parser: whether -h/--help was given and
   !> the file of the last `--config FILE` or `--config=FILE` ('' if none), so that
   !> the file is read before the flags that override it. Values of other options
   !> are not looked at, so `--output --help` asks for help.
   subroutine scan_help_config(args, help, config, error)
      type(arg_t), intent(in) :: args(:)                   !! the command's arguments
      logical, intent(out) :: help                         !! -h or --help present
      character(len=:), allocatable, intent(out) :: config !! config file or ''
      type(error_t), allocatable, intent(out) :: error     !! --config without a value
      integer :: i
      help = .false.
      config = ''
      if (allocated(error)) deallocate (error)
      i = 1
      do while (i <= size(args))
         if (args(i)%s == '-h' .or. args(i)%s == '--help') then
            help = .true.
            if (allocated(error)) deallocate (error)
            return
         else if (args(i)%s == '--config') then
            if (i == size(args)) then
               if (.not. allocated(error)) &
                  call fatal_error(error, 'option --config needs a value')
               i = i + 1
            else if (is_long_option(args(i + 1)%s)) then
               if (.not. allocated(error)) &
                  call fatal_error(error, 'option --config needs a value')
               i = i + 1
            else
               config = args(i + 1)%s
               i = i + 2
            end if
         else if (index(args(i)%s, '--config=') == 1) then
            config = args(i)%s(len('--config=') + 1:)
            if (len(config) == 0 .and. .not. allocated(error)) &
               call fatal_error(error, 'invalid --config: empty file name')
            i = i + 1
         else
            i = i + 1
         end if
      end do
   end subroutine scan_help_config
end module dpend_cli
