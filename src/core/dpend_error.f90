!> Error reporting for set-up and I/O: an allocatable `error_t` that callers test
!> with `allocated(error)`. The library never stops; only `app/` and tests do.
!>
!> Every error carries its kind, a field set where the error is made: the exit
!> status follows from the kind (`exit_status`), never from the message, which is for
!> people and may be reworded freely.
module dpend_error
   implicit none
   private
   public :: error_t, fatal_error, run_failure, exit_status
   public :: error_unspecified, error_bad_input, error_run_failed, error_internal

   !> Kinds of error. An error made without a kind (`error_unspecified`) is decided by
   !> the phase that catches it: a refusal while the input is checked (exit 2), a run
   !> failure once the work has started (`run_failure`, exit 1).
   integer, parameter :: error_unspecified = 0 !! decided by the catching phase
   integer, parameter :: error_bad_input = 1   !! refused input, nothing done: exit 2
   integer, parameter :: error_run_failed = 2  !! the work started and failed: exit 1
   integer, parameter :: error_internal = 3    !! a broken invariant of dpend: exit 1

   !> A set-up or I/O failure with a one-line, user-facing message.
   type :: error_t
      character(len=:), allocatable :: message  !! names the field and the accepted range
      integer :: kind = error_unspecified       !! error_bad_input, _run_failed, _internal
   end type error_t

contains

   !> Allocate `error` with `message`, of kind `kind` (default: unspecified).
   pure subroutine fatal_error(error, message, kind)
      type(error_t), allocatable, intent(out) :: error  !! the error to create
      character(len=*), intent(in) :: message           !! what went wrong
      integer, intent(in), optional :: kind             !! its kind
      allocate (error)
      error%message = message
      if (present(kind)) error%kind = kind
   end subroutine fatal_error

   !> An error caught after the work started: a run failure (exit 1) unless it was
   !> made as refused input (`error_bad_input`, e.g. an energy with no state on a
   !> section, found only by the run).
   pure subroutine run_failure(error)
      type(error_t), intent(inout) :: error  !! the error
      if (error%kind /= error_bad_input) error%kind = error_run_failed
   end subroutine run_failure

   !> The process exit status of an error: 2 for refused input (also an unspecified
   !> kind: the set-up refuses), 1 for a failed run or an internal error.
   pure integer function exit_status(error)
      type(error_t), intent(in) :: error  !! the error
      select case (error%kind)
      case (error_unspecified, error_bad_input); exit_status = 2
      case default; exit_status = 1
      end select
   end function exit_status
end module dpend_error
