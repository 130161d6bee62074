!> What the entry points of the commands share. app/main.f90 holds a table of the
!> commands and calls one entry point per command, `NAME_command(args, error)`: the
!> arguments after the command's name in, and a refusal or a failed run out as
!> `error`, whose message is the one line the front end prints and whose kind gives
!> the exit status (`exit_status`). Shared here: the option --quiet that every
!> command takes (`take_quiet`) and its help lines, the last line of a summary, and
!> the one line of an error ('dpend COMMAND: message'): a refusal of the input
!> (`refusal_line`, exit 2 whatever kind it was made with) or an error of the run
!> (`error_line`, its kind kept).
module dpend_command_common
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_error, only: error_t, error_bad_input
   use dpend_cli, only: arg_t
   use dpend_progress, only: silence_progress
   implicit none
   private
   public :: take_quiet, with_quiet, last_line, refusal_line, error_line
   public :: summary_quiet, data_quiet, report_unit, set_report_unit

   character(len=*), parameter :: nl = new_line('a')
   !> The --quiet line of the help texts that lack one (every command's --help
   !> mentions it): of a command that prints a summary, and of one that prints data.
   character(len=*), parameter :: summary_quiet = '  --quiet           no progress ' &
      //'report; of the summary only its last line'
   character(len=*), parameter :: data_quiet = '  --quiet           accepted (every ' &
      //'command takes it); the data print as always'

   !> Where a command writes its report (standard output; a library call sends it to
   !> a scratch file and returns it as its message, src/capi). Library calls run one
   !> at a time, so one unit for the process.
   integer, save :: report = output_unit

contains

   !> The unit of the command's report (`set_report_unit`).
   integer function report_unit()
      report_unit = report
   end function report_unit

   !> Send the commands' reports to `unit` (output_unit again after a library call).
   subroutine set_report_unit(unit)
      integer, intent(in) :: unit  !! an open formatted unit
      report = unit
   end subroutine set_report_unit

   !> `args` without any `--quiet` (all commands take it; values never start with
   !> '--'); when one was given, `quiet` is set and every progress report of the
   !> process silenced. (The sweep reads its own --quiet with its other options.)
   subroutine take_quiet(args, rest, quiet)
      type(arg_t), intent(in) :: args(:)                 !! the arguments after the command
      type(arg_t), allocatable, intent(out) :: rest(:)   !! the same without --quiet
      logical, intent(out), optional :: quiet            !! --quiet was given
      logical :: found
      integer :: i
      found = any([(args(i)%s == '--quiet', i=1, size(args))])
      if (present(quiet)) quiet = found
      if (.not. found) then
         rest = args
         return
      end if
      call silence_progress()
      rest = pack(args, [(args(i)%s /= '--quiet', i=1, size(args))])
   end subroutine take_quiet

   !> `help` with the --quiet line `line` appended where it does not mention --quiet.
   function with_quiet(help, line) result(s)
      character(len=*), intent(in) :: help  !! a command's help text
      character(len=*), intent(in) :: line  !! the --quiet line
      character(len=:), allocatable :: s
      s = help
      if (index(help, '--quiet') == 0) s = help//nl//line
   end function with_quiet

   !> The last line of `text` (without a trailing line end).
   pure function last_line(text) result(s)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: s
      integer :: n
      n = len(text)
      if (n > 0) then
         if (text(n:n) == nl) n = n - 1
      end if
      s = text(index(text(:n), nl, back=.true.) + 1:n)
   end function last_line

   !> `error`, a refusal of `command`'s input, as its one line 'dpend COMMAND:
   !> message', of kind error_bad_input (exit 2) whatever kind it was made with.
   pure subroutine refusal_line(error, command)
      type(error_t), intent(inout) :: error     !! the refusal
      character(len=*), intent(in) :: command   !! the command's name
      error%message = 'dpend '//command//': '//error%message
      error%kind = error_bad_input
   end subroutine refusal_line

   !> `error` of `command`'s run as its one line 'dpend COMMAND: message', its kind
   !> kept (a refusal found by the run: exit 2; a failed run: exit 1).
   pure subroutine error_line(error, command)
      type(error_t), intent(inout) :: error     !! the error of the run
      character(len=*), intent(in) :: command   !! the command's name
      error%message = 'dpend '//command//': '//error%message
   end subroutine error_line
end module dpend_command_common
