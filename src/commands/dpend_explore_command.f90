!> `dpend explore MAP.h5`: a sweep's map in the browser (docs/explore.md). The page's
!> server is the Python package's (`python -m dpend.explore`, which runs pixels through
!> the library in its own process): this command replaces itself by that interpreter,
!> `execvp` with the arguments as they came (no shell, nothing pasted into code),
!> so that Ctrl-C, the exit status and the output are the server's. The interpreter is
!> $DPEND_PYTHON, else `python3` on the PATH. Every argument is checked there
!> (dpend.explore.parse). Not a command of the library (src/capi): it ends the process.
module dpend_explore_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_loc, c_null_char, &
                                          c_null_ptr
   use dpend_error, only: error_t, fatal_error, error_run_failed
   use dpend_cli, only: arg_t, environment
   implicit none
   private
   public :: explore_command

   interface
      !> execvp(3): replaces the process; returns (-1) only when it failed.
      function c_execvp(file, argv) bind(C, name='execvp') result(status)
         import :: c_char, c_ptr, c_int
         character(kind=c_char), intent(in) :: file(*)
         type(c_ptr), intent(in) :: argv(*)
         integer(c_int) :: status
      end function c_execvp
   end interface

   !> An argument of the new process: its bytes and a closing NUL.
   type :: c_text_t
      character(kind=c_char), allocatable :: bytes(:)
   end type c_text_t

   !> The program the interpreter runs: fixed text (the user's arguments follow it
   !> in sys.argv); a missing package is one line, not a traceback.
   character(len=*), parameter :: launcher = &
      'import sys'//new_line('a')// &
      'try:'//new_line('a')// &
      '    from dpend.explore import main'//new_line('a')// &
      'except ImportError as e:'//new_line('a')// &
      '    if "-h" in sys.argv[1:] or "--help" in sys.argv[1:]:'//new_line('a')// &
      '        print("usage: dpend explore MAP.h5 [options]\n\nA map of dpend sweep in '// &
      'the browser: click a pixel, watch its pendulum.\nIts server is the Python '// &
      'package dpend, not importable by " + sys.executable + " (" + str(e) + "):\n'// &
      'pip install . in the checkout, or set DPEND_PYTHON to the interpreter that has '// &
      'it;\nthen dpend explore --help lists the options (docs/explore.md).")'//new_line('a')// &
      '        sys.exit(0)'//new_line('a')// &
      '    print("dpend explore: the Python package dpend is not importable by " + '// &
      'sys.executable + " (" + str(e) + "): pip install . in the checkout, or set '// &
      'DPEND_PYTHON to the interpreter that has it (docs/explore.md)", '// &
      'file=sys.stderr)'//new_line('a')// &
      '    sys.exit(1)'//new_line('a')// &
      'sys.exit(main(sys.argv[1:]))'

contains

   !> The entry point of `dpend explore` (app/main.f90): returns only when the
   !> interpreter could not be started (a run failure, exit status 1).
   subroutine explore_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `explore`
      type(error_t), allocatable, intent(out) :: error  !! why it could not start
      type(c_text_t), allocatable, target :: texts(:)
      type(c_ptr), allocatable :: argv(:)
      character(len=:), allocatable :: python
      integer :: k, status
      python = environment('DPEND_PYTHON', 'python3')
      allocate (texts(size(args) + 3))
      texts(1) = c_text(python)
      texts(2) = c_text('-c')
      texts(3) = c_text(launcher)
      do k = 1, size(args)
         texts(k + 3) = c_text(args(k)%s)
      end do
      allocate (argv(size(texts) + 1))
      do k = 1, size(texts)
         argv(k) = c_loc(texts(k)%bytes)
      end do
      argv(size(argv)) = c_null_ptr
      flush (output_unit)
      status = c_execvp(texts(1)%bytes, argv)
      call fatal_error(error, "dpend explore: cannot run the Python interpreter '"// &
                       python//"' (set DPEND_PYTHON to one with the dpend package: "// &
                       "pip install . in the checkout; docs/explore.md)", error_run_failed)
   end subroutine explore_command

   !> `s` as C text.
   pure function c_text(s) result(t)
      character(len=*), intent(in) :: s
      type(c_text_t) :: t
      integer :: k
      allocate (t%bytes(len(s) + 1))
      do k = 1, len(s)
         t%bytes(k) = s(k:k)
      end do
      t%bytes(len(s) + 1) = c_null_char
   end function c_text

end module dpend_explore_command
