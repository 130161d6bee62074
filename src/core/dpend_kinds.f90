!> Working precision of dpend, and π (one definition for new code; older modules
!> still carry their own copies of the same value, to be folded in here).
module dpend_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int64
   implicit none
   private
   public :: dp, i8, pi, half_pi

   integer, parameter :: dp = real64   !! double precision, used for every real
   integer, parameter :: i8 = int64    !! 64-bit integers for counters
   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp  !! π
   real(dp), parameter :: half_pi = 0.5_dp*pi  !! π/2: hanging is q = -π/2, θ = q + π/2
end module dpend_kinds
