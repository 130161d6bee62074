!> Command-line helpers: the argument list, option splitting (`--name value` or
!> `--name=value`) and validated number parsing with one-line error messages.
module dpend_cli
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: arg_t, get_arguments, next_option, parse_real, parse_int, parse_logical
   public :: real_str, to_str, scan_help_config

   !> Text of an integer (default or 64-bit), without blanks.
   interface to_str
      module procedure int_str, int8_str
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
   !> options that take one, its value, from `--name=value` or the next argument.
   !> Advances i past what was consumed. Flags (`takes_value` false) get value ''.
   subroutine next_option(args, i, name, value, takes_value, error)
      type(arg_t), intent(in) :: args(:)                 !! all arguments
      integer, intent(inout) :: i                        !! current position
      character(len=:), allocatable, intent(out) :: name !! e.g. '--dt'
      character(len=:), allocatable, intent(out) :: value !! its value or ''
      logical, intent(in) :: takes_value                 !! whether the option has a value
      type(error_t), allocatable, intent(out) :: error   !! missing value
      integer :: eq
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
      if (i > size(args)) then
         call fatal_error(error, 'option '//name//' needs a value')
         return
      end if
      if (len(args(i)%s) >= 2) then
         if (args(i)%s(1:2) == '--') then
            call fatal_error(error, 'option '//name//' needs a value')
            return
         end if
      end if
      value = args(i)%s
      i = i + 1
   end subroutine next_option

   !> Parse a finite real number for field `name`.
   subroutine parse_real(text, name, x, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      real(dp), intent(out) :: x                        !! the value
      type(error_t), allocatable, intent(out) :: error  !! not a finite number
      integer :: stat
      x = 0.0_dp
      read (text, *, iostat=stat) x
      if (stat /= 0 .or. len_trim(text) == 0 .or. scan(trim(text), ' ,/*') /= 0) then
         call fatal_error(error, 'invalid '//name//": '"//trim(text)//"' is not a number")
      else if (.not. ieee_is_finite(x)) then
         call fatal_error(error, 'invalid '//name//': must be finite')
      end if
   end subroutine parse_real

   !> Parse an integer for field `name`.
   subroutine parse_int(text, name, n, error)
      character(len=*), intent(in) :: text              !! the text
      character(len=*), intent(in) :: name              !! field name for messages
      integer, intent(out) :: n                         !! the value
      type(error_t), allocatable, intent(out) :: error  !! not an integer
      integer :: stat
      n = 0
      read (text, *, iostat=stat) n
      if (stat /= 0 .or. len_trim(text) == 0 .or. verify(trim(text), '0123456789+-') /= 0) &
         call fatal_error(error, 'invalid '//name//": '"//trim(text)//"' is not an integer")
   end subroutine parse_int

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
         call fatal_error(error, 'invalid '//name//": '"//trim(text)//"' (accepted: true, false)")
      end select
   end subroutine parse_logical

   !> Compact text of a real number, e.g. for defaults in help texts.
   pure function real_str(x) result(s)
      real(dp), intent(in) :: x  !! the number
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(g0)') x
      s = trim(adjustl(buf))
   end function real_str

   pure function int_str(i) result(s)
      integer, intent(in) :: i  !! the number
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function int_str

   pure function int8_str(i) result(s)
      integer(i8), intent(in) :: i  !! the number
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function int8_str

   !> The first pass of every command's parser: whether -h/--help was given and
   !> the file of the last `--config FILE` ('' if none), so that the file is read
   !> before the flags that override it.
   subroutine scan_help_config(args, help, config, error)
      type(arg_t), intent(in) :: args(:)                   !! the command's arguments
      logical, intent(out) :: help                         !! -h or --help present
      character(len=:), allocatable, intent(out) :: config !! config file or ''
      type(error_t), allocatable, intent(out) :: error     !! --config without a value
      integer :: i
      help = .false.
      config = ''
      i = 1
      do while (i <= size(args))
         select case (args(i)%s)
         case ('-h', '--help')
            help = .true.
            return
         case ('--config')
            if (i == size(args)) then
               call fatal_error(error, 'option --config needs a value')
               return
            end if
            config = args(i + 1)%s
            i = i + 2
         case default
            i = i + 1
         end select
      end do
   end subroutine scan_help_config
end module dpend_cli
