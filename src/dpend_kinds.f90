!> Working precision of dpend.
module dpend_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int64
   implicit none
   private
   public :: dp, i8

   integer, parameter :: dp = real64   !! double precision, used for every real
   integer, parameter :: i8 = int64    !! 64-bit integers for counters
end module dpend_kinds
