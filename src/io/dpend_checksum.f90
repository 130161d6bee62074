!> The CRC-32 of an array's bytes (zlib's, through dpend_chunk_codec.c): the checksum
!> the sweep's working file keeps of every block it writes (dpend_sweep_layout), so
!> that a block flagged done is checked before it is trusted.
module dpend_checksum
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_int64_t
   use, intrinsic :: iso_fortran_env, only: int8
   use dpend_kinds, only: dp
   implicit none
   private
   public :: crc32_of

   !> CRC-32 of the bytes of a real(dp), default-integer or byte array, as a default
   !> integer holding its 32-bit pattern.
   interface crc32_of
      module procedure crc32_real, crc32_int, crc32_bytes
   end interface crc32_of

   interface
      integer(c_int64_t) function c_crc32(p, n) bind(C, name='dpend_crc32')
         import :: c_ptr, c_int64_t
         type(c_ptr), value :: p
         integer(c_int64_t), value :: n
      end function c_crc32
   end interface

contains

   integer function crc32_real(a) result(crc)
      real(dp), intent(in), target, contiguous :: a(..)  !! values
      crc = bits32(c_crc32(c_loc(a), int(size(a), c_int64_t)*storage_size(a)/8))
   end function crc32_real

   integer function crc32_int(a) result(crc)
      integer, intent(in), target, contiguous :: a(..)   !! values
      crc = bits32(c_crc32(c_loc(a), int(size(a), c_int64_t)*storage_size(a)/8))
   end function crc32_int

   integer function crc32_bytes(a) result(crc)
      integer(int8), intent(in), target, contiguous :: a(:)  !! bytes
      crc = bits32(c_crc32(c_loc(a), int(size(a), c_int64_t)))
   end function crc32_bytes

   !> The low 32 bits of v as a default integer (two's complement).
   pure integer function bits32(v)
      integer(c_int64_t), intent(in) :: v
      bits32 = int(v - merge(4294967296_c_int64_t, 0_c_int64_t, v >= 2147483648_c_int64_t))
   end function bits32

end module dpend_checksum
