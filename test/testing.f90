!> A small test harness in the spirit of test-drive: each suite exposes
!> `collect_<suite>(tests)` returning named tests; a test reports failure by
!> allocating its `error_t`. `check` compares with absolute/relative tolerance.
module testing
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   implicit none
   private
   public :: unittest_t, test_proc, new_unittest, check, check_true, error_t, fatal_error

   abstract interface
      subroutine test_proc(error)
         import :: error_t
         type(error_t), allocatable, intent(out) :: error
      end subroutine test_proc
   end interface

   !> A named test.
   type :: unittest_t
      character(len=:), allocatable :: name      !! name used on the command line
      procedure(test_proc), pointer, nopass :: run => null()  !! the test body
   end type unittest_t

   interface check
      module procedure check_real, check_real_array
   end interface check

contains

   !> Build a named test.
   function new_unittest(name, run) result(t)
      character(len=*), intent(in) :: name     !! test name
      procedure(test_proc) :: run              !! test body
      type(unittest_t) :: t
      t%name = name
      t%run => run
   end function new_unittest

   !> Fail unless |actual - expected| <= max(abs, rel*|expected|).
   subroutine check_real(error, actual, expected, what, abs, rel)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      real(dp), intent(in) :: actual                      !! computed value
      real(dp), intent(in) :: expected                    !! independently known value
      character(len=*), intent(in) :: what                !! what is compared
      real(dp), intent(in), optional :: abs               !! absolute tolerance
      real(dp), intent(in), optional :: rel               !! relative tolerance
      real(dp) :: tol
      character(len=200) :: msg
      if (allocated(error)) return
      tol = 0.0_dp
      if (present(abs)) tol = max(tol, abs)
      if (present(rel)) tol = max(tol, rel*abs_(expected))
      if (.not. (abs_(actual - expected) <= tol)) then
         write (msg, '(a, ": got ", es23.15, " expected ", es23.15, " (diff ", es9.2, &
            & ", tol ", es9.2, ")")') what, actual, expected, abs_(actual - expected), tol
         call fatal_error(error, trim(msg))
      end if
   contains
      elemental real(dp) function abs_(x)
         real(dp), intent(in) :: x
         abs_ = merge(x, -x, x >= 0.0_dp)
      end function abs_
   end subroutine check_real

   !> Element-wise `check_real` over an array.
   subroutine check_real_array(error, actual, expected, what, abs, rel)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      real(dp), intent(in) :: actual(:)                   !! computed values
      real(dp), intent(in) :: expected(:)                 !! known values
      character(len=*), intent(in) :: what                !! what is compared
      real(dp), intent(in), optional :: abs               !! absolute tolerance
      real(dp), intent(in), optional :: rel               !! relative tolerance
      integer :: i
      character(len=16) :: idx
      do i = 1, size(actual)
         write (idx, '("(", i0, ")")') i
         call check_real(error, actual(i), expected(i), what//trim(idx), abs, rel)
      end do
   end subroutine check_real_array

   !> Fail with `what` unless `condition` holds.
   subroutine check_true(error, condition, what)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      logical, intent(in) :: condition                    !! must be true
      character(len=*), intent(in) :: what                !! message on failure
      if (allocated(error)) return
      if (.not. condition) call fatal_error(error, what)
   end subroutine check_true
end module testing
