!> Error reporting for set-up and I/O: an allocatable `error_t` that callers test
!> with `allocated(error)`. The library never stops; only `app/` and tests do.
module dpend_error
   implicit none
   private
   public :: error_t, fatal_error

   !> A set-up or I/O failure with a one-line, user-facing message.
   type :: error_t
      character(len=:), allocatable :: message  !! names the field and the accepted range
   end type error_t

contains

   !> Allocate `error` with `message`.
   pure subroutine fatal_error(error, message)
      type(error_t), allocatable, intent(out) :: error  !! the error to create
      character(len=*), intent(in) :: message           !! what went wrong
      allocate (error)
      error%message = message
   end subroutine fatal_error
end module dpend_error
