!> A small test harness in the spirit of test-drive: each suite exposes
!> `collect_<suite>(tests)` returning named tests; a test reports failure by
!> allocating its `error_t`. `check` compares with absolute/relative tolerance.
!> A test that cannot run here (a tool it needs is missing) calls `skip_test` and
!> returns: the driver reports it as skipped, never as passed.
module testing
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   implicit none
   private
   public :: unittest_t, test_proc, new_unittest, check, check_true, error_t, fatal_error
   public :: skip_test, take_skip, have_tool
   public :: tiny_study_config   ! the tiny study of three suites (review follow-up)
   public :: check_same_time     ! flip times of two sweep paths (test_sweep, test_chain_lanes)

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

   !> Why the running test was skipped (set by `skip_test`, read by `take_skip`).
   character(len=:), allocatable :: skip_reason

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

   !> Mark the running test as skipped for `reason` (e.g. "gnuplot not found"); the
   !> test then returns without setting its error.
   subroutine skip_test(reason)
      character(len=*), intent(in) :: reason  !! why it cannot run here
      skip_reason = reason
   end subroutine skip_test

   !> True (and `reason` set) when the test just run called `skip_test`; clears it.
   logical function take_skip(reason)
      character(len=:), allocatable, intent(out) :: reason  !! why it was skipped
      take_skip = allocated(skip_reason)
      if (take_skip) then
         call move_alloc(skip_reason, reason)
      else
         reason = ''
      end if
   end function take_skip

   !> Whether the program `name` is on the PATH.
   logical function have_tool(name)
      character(len=*), intent(in) :: name  !! program name (a fixed word, never user input)
      integer :: stat, cmdstat
      call execute_command_line('command -v '//name//' > /dev/null 2>&1', exitstat=stat, &
                                cmdstat=cmdstat)
      have_tool = cmdstat == 0 .and. stat == 0
   end function have_tool

   !> The tiny study of the study, values_study and inventory suites: two cases (a small
   !> swing and the horizontal release, lasting t_small and t_horizontal), four methods
   !> (rk4, dopri5 with a tolerance sweep, gauss4, verlet) of three steps, two decades
   !> of long runs, two gauss4 roundoff runs of 100 steps, two values of Tao's ω over
   !> 0.2 s; one thread. A suite sets what it needs differently after the call.
   function tiny_study_config(t_small, t_horizontal) result(cfg)
      use dpend_kinds, only: pi
      use dpend_study_settings, only: study_config_t, study_case_t, study_method_t, &
         study_defaults
      real(dp), intent(in) :: t_small       !! duration of the small swing's long runs [s]
      real(dp), intent(in) :: t_horizontal  !! duration of the horizontal release's [s]
      type(study_config_t) :: cfg
      cfg = study_defaults()
      cfg%cases = [study_case_t('small', [-0.5_dp*pi + 0.3_dp, -0.5_dp*pi - 0.2_dp], &
                                [0.0_dp, 0.0_dp], t_small), &
                   study_case_t('horizontal', [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], &
                                t_horizontal)]
      cfg%methods = [study_method_t('rk4', 2.0e-3_dp, 5.0e-3_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('dopri5', 3.0e-3_dp, 8.0e-3_dp, 1.0e-10_dp, 1.0e-8_dp), &
                     study_method_t('gauss4', 1.0e-2_dp, 2.5e-2_dp, 0.0_dp, 0.0_dp), &
                     study_method_t('verlet', 5.0e-3_dp, 1.25e-2_dp, 0.0_dp, 0.0_dp)]
      cfg%n_h = 3
      cfg%n_rtol = 2
      cfg%order_case = 'small'
      cfg%drift_case = 'small'
      cfg%decades = 2
      cfg%wall_min = 0.0_dp
      cfg%ro_methods = [character(len=16) :: 'gauss4']
      cfg%ro_dt = [1.0e-2_dp]
      cfg%ro_steps = 100.0_dp
      cfg%ro_runs = 2
      cfg%ro_fit_t_min = 0.1_dp
      cfg%tao_methods = [character(len=16) :: 'tao2']
      cfg%n_omega = 2
      cfg%tao_t_end = 0.2_dp
      cfg%tao_dt = 1.0e-2_dp
      cfg%threads = 1
   end function tiny_study_config

   !> Two flip times agree: NaN (no flip) in both, or a flip in both within `rel`.
   subroutine check_same_time(error, x, y, what, rel)
      use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
      type(error_t), allocatable, intent(inout) :: error  !! failure
      real(dp), intent(in) :: x                          !! the tested path's time [s]
      real(dp), intent(in) :: y                          !! the reference time [s]
      character(len=*), intent(in) :: what               !! name in the message
      real(dp), intent(in) :: rel                        !! relative tolerance
      if (allocated(error)) return
      if (ieee_is_nan(y)) then
         call check_true(error, ieee_is_nan(x), what//': NaN in both')
      else
         call check_true(error, .not. ieee_is_nan(x), what//': a flip in both')
         if (.not. allocated(error)) call check(error, x, y, what, rel=rel)
      end if
   end subroutine check_same_time
end module testing
