!> Program version, written into every output file, and what the running binary
!> was built with.
module dpend_version
   use, intrinsic :: iso_fortran_env, only: compiler_options
   implicit none
   private
   public :: version, slow_build_note

   character(len=*), parameter :: version = '0.1.0'  !! keep in step with fpm.toml

contains

   !> '' when this binary was built with the flags that vectorize the sweep kernel
   !> (a target ISA, `-march=...`, and `-fno-math-errno`, which lets gfortran call
   !> glibc's vector sin/cos); otherwise one line saying so and how to build the
   !> fast binary. Read from `compiler_options()`.
   function slow_build_note() result(note)
      character(len=:), allocatable :: note
      character(len=*), parameter :: flags = compiler_options()
      if (index(flags, '-march=') > 0 .and. index(flags, '-fno-math-errno') > 0) then
         note = ''
      else
         note = 'note: this binary was built without -march=native -fno-math-errno, so '// &
                'the sweep kernel is not vectorized (about 3x slower); the fast one: '// &
                'scripts/dpend sweep ... (or fpm run --profile release --flag '// &
                '"-O3 -march=native -fno-math-errno -fno-trapping-math -fopenmp" -- sweep ...)'
      end if
   end function slow_build_note
end module dpend_version
