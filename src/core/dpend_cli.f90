!> Command-line helpers: the argument list, option splitting (`--name value` or
!> `--name=value`) and validated number parsing with one-line error messages.
module dpend_cli
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   !> the one strict parser and escaping helper; `printable` is `escaped` under the
   !> name the messages used before
   use dpend_parse, only: read_real, read_int, quoted, overflows_real
   !> the text helpers, re-exported for the commands that import them from here
   use dpend_strings, only: to_lower, printable, pad, real_str, seconds_str, to_str, &
                            did_you_mean
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_is_negative
   implicit none
   private
   public :: arg_t, get_arguments, environment, next_option, parse_real, parse_int
   public :: parse_logical, take_data_file
   public :: check_repeated_options, help_options, unknown_option_text
   public :: real_str, seconds_str, to_str, scan_help_config, option_outcome, is_long_option
   public :: overflows_real, to_lower, printable, pad, quoted

   !> Parse an integer (default or 64-bit) for a field.
   interface parse_int
      module procedure parse_int_default, parse_int_i8
   end interface parse_int

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

   !> The environment variable `name`, or `default` when it is unset or empty.
   function environment(name, default) result(value)
      character(len=*), intent(in) :: name     !! the variable
      character(len=*), intent(in) :: default  !! its value when unset or empty
      character(len=:), allocatable :: value
      integer :: n, stat
      call get_environment_variable(name, length=n, status=stat)
      if (stat == 0 .and. n > 0) then
         allocate (character(len=n) :: value)
         call get_environment_variable(name, value)
      else
         value = default
      end if
   end function environment

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
   !> the value's own error, in that order. With the command's `help` text, an
   !> unknown option names the nearest one it lists ("did you mean --t-end?").
   subroutine option_outcome(command, name, matched, missing, flags, error, help)
      character(len=*), intent(in) :: command             !! e.g. 'simulate'
      character(len=*), intent(in) :: name                !! the option
      logical, intent(in) :: matched                      !! a valued option of the command
      logical, intent(in) :: missing                      !! its value was missing
      character(len=*), intent(in) :: flags(:)            !! the command's flags
      type(error_t), allocatable, intent(inout) :: error  !! the value's error, if any
      character(len=*), intent(in), optional :: help      !! the command's --help text
      if (any(flags == name)) then
         if (allocated(error)) deallocate (error)
         call fatal_error(error, 'option '//name//' takes no value')
      else if (.not. matched) then
         if (allocated(error)) deallocate (error)
         if (present(help)) then
            call fatal_error(error, unknown_option_text(command, name, help_options(help)))
         else
            call fatal_error(error, unknown_option_text(command, name, ''))
         end if
      else if (missing) then
         if (allocated(error)) deallocate (error)
         call fatal_error(error, 'option '//name//' needs a value')
      end if
   end subroutine option_outcome

   !> The refusal of the unknown option `name` of `command`, with the nearest of
   !> `options` (blank-separated) when one is close: "unknown option '--t_end' (did
   !> you mean --t-end? dpend simulate --help lists the options)".
   pure function unknown_option_text(command, name, options) result(s)
      character(len=*), intent(in) :: command  !! e.g. 'simulate'
      character(len=*), intent(in) :: name     !! the option given
      character(len=*), intent(in) :: options  !! the command's options
      character(len=:), allocatable :: s, hint
      hint = did_you_mean(name, options)
      if (len(hint) > 0) hint = hint//' '
      s = "unknown option '"//printable(name)//"' ("//hint//'dpend '//command// &
          ' --help lists the options)'
   end function unknown_option_text

   !> The long options a --help text names ('--t-end', '--q1', ...), each once,
   !> blank-separated, in the order of their first mention.
   pure function help_options(help) result(s)
      character(len=*), intent(in) :: help  !! a command's --help text
      character(len=:), allocatable :: s, word
      character(len=*), parameter :: name_chars = 'abcdefghijklmnopqrstuvwxyz0123456789-'
      integer :: i, j
      s = ' '
      i = index(help, '--')
      do while (i > 0)
         j = i + 2
         do while (j <= len(help))
            if (index(name_chars, help(j:j)) == 0) exit
            j = j + 1
         end do
         word = help(i:j - 1)
         if (i > 1) then          ! '--' inside a word ('a--b') names no option
            if (index(name_chars(:36), to_lower(help(i - 1:i - 1))) > 0) word = '--'
         end if
         if (len(word) > 2 .and. index(s, ' '//word//' ') == 0) s = s//word//' '
         if (j > len(help)) exit
         i = index(help(j:), '--')
         if (i > 0) i = i + j - 1
      end do
      s = trim(adjustl(s))
   end function help_options

   !> Refuse an option given twice (`--t-end 1 ... --t-end 2`): which one counts
   !> would depend on the order, as a repeated key of a namelist group would. Options
   !> are the arguments that start with '--' (never a value), compared by their name
   !> (before '=', for `--name=value`); `-o` is `--output` (the two set one file:
   !> refused naming both, in either order). Flags still override a --config file.
   subroutine check_repeated_options(args, error)
      type(arg_t), intent(in) :: args(:)                !! a command's arguments
      type(error_t), allocatable, intent(out) :: error  !! the first repeated option
      character(len=:), allocatable :: a, b
      integer :: i, j
      do i = 2, size(args)
         if (.not. (is_long_option(args(i)%s) .or. args(i)%s == '-o')) cycle
         a = option_name(args(i)%s)
         do j = 1, i - 1
            if (.not. (is_long_option(args(j)%s) .or. args(j)%s == '-o')) cycle
            b = option_name(args(j)%s)
            if (a /= b) cycle
            if (args(i)%s == '-o' .neqv. args(j)%s == '-o') then
               call fatal_error(error, 'invalid --output: -o and --output were both given ' &
                                //'(-o is --output); give one of them')
            else
               call fatal_error(error, 'invalid '//printable(a)//': given twice (give each ' &
                                //'option once)')
            end if
            return
         end do
      end do
   contains
      pure function option_name(arg) result(name)
         character(len=*), intent(in) :: arg
         character(len=:), allocatable :: name
         name = arg
         if (index(arg, '=') > 0) name = arg(:index(arg, '=') - 1)
         if (name == '-o') name = '--output'
      end function option_name
   end subroutine check_repeated_options

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
   !> Whether `arg` is a positional argument (not an option, not -o): then it is the
   !> command's one data file, stored in `input` ('' before); a second is refused.
   logical function take_data_file(arg, input, command, error) result(taken)
      character(len=*), intent(in) :: arg                 !! the argument
      character(len=:), allocatable, intent(inout) :: input  !! the data file so far
      character(len=*), intent(in) :: command             !! e.g. 'fit'
      type(error_t), allocatable, intent(out) :: error    !! a second data file
      taken = arg(1:min(2, len(arg))) /= '--' .and. arg /= '-o'
      if (.not. taken) return
      if (len(input) > 0) then
         call fatal_error(error, "unexpected argument '"//printable(arg)// &
                          "' (one data file; dpend "//command//' --help)')
         return
      end if
      input = arg
   end function take_data_file

end module dpend_cli
