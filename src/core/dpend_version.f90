!> Program version, written into every output file, and what the running binary
!> was built with.
module dpend_version
   use, intrinsic :: iso_fortran_env, only: compiler_options
   implicit none
   private
   public :: version, slow_build_note

   character(len=*), parameter :: version = '0.1.0'  !! keep in step with fpm.toml

contains

   !> '' when this binary was built for a target ISA (`-march=...` other than the
   !> baseline x86-64): the sweep kernel vectorizes with any flags, but
   !> the baseline has only 2-wide SSE2 vectors and no FMA; otherwise one line
   !> saying so and how to build the fast binary. Read from `compiler_options()`.
   function slow_build_note() result(note)
      character(len=:), allocatable :: note
      character(len=*), parameter :: flags = ' '//compiler_options()//' '
      if (index(flags, ' -march=') > 0 .and. index(flags, ' -march=x86-64 ') == 0) then
         note = ''
      else
         note = 'note: this binary was built without -march, so the sweep kernel uses '// &
                '2-wide SSE2 vectors (about 2x slower than -march=native on AVX2); '// &
                'the fast one: '// &
                'scripts/dpend sweep ... (or fpm run --profile release --flag '// &
                '"-O3 -march=native -fno-math-errno -fno-trapping-math -fopenmp" -- sweep ...)'
      end if
   end function slow_build_note
end module dpend_version
