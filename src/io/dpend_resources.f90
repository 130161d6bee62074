!> The checks of the machine's resources before work starts: the memory a run
!> needs against what is available, the size of an output against the free space of
!> its file system. They ask the operating system (dpend_os), so they live in io/,
!> above core/ (whose dpend_limits holds the limits themselves).
module dpend_resources
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_os, only: available_memory_bytes, free_disk_bytes, directory_of
   use dpend_limits, only: bytes_text
   implicit none
   private
   public :: check_memory, check_disk

contains

   !> Refuse when `bytes` of memory are needed and less is available (unknown
   !> availability: accepted). Message: 'invalid FIELD: WHAT needs B of memory,
   !> A available (HINT)'.
   subroutine check_memory(field, bytes, what, hint, error)
      character(len=*), intent(in) :: field             !! field to change
      real(dp), intent(in) :: bytes                     !! estimate [B]
      character(len=*), intent(in) :: what              !! what is kept
      character(len=*), intent(in) :: hint              !! what to do
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      integer(i8) :: avail
      avail = available_memory_bytes()
      if (avail < 0) return
      if (bytes <= real(avail, dp)) return
      call fatal_error(error, 'invalid '//field//': '//what//' needs '//bytes_text(bytes)// &
                       ' of memory, '//bytes_text(real(avail, dp))//' available ('//hint//')')
   end subroutine check_memory

   !> Refuse when a file of `bytes` does not fit the free space of the file system
   !> of `path`. Unknown or zero free space (a pseudo file system such as /proc, or a
   !> full disk) is left to the writer, which names the cause when it fails.
   subroutine check_disk(field, bytes, path, hint, error)
      character(len=*), intent(in) :: field             !! field to change
      real(dp), intent(in) :: bytes                     !! estimated file size [B]
      character(len=*), intent(in) :: path              !! the output file
      character(len=*), intent(in) :: hint              !! what to do
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      integer(i8) :: free
      free = free_disk_bytes(directory_of(path))
      if (free <= 0) return
      if (bytes <= real(free, dp)) return
      call fatal_error(error, 'invalid '//field//": the output '"//path//"' needs about " &
                       //bytes_text(bytes)//', '//bytes_text(real(free, dp))// &
                       ' free on its file system ('//hint//')')
   end subroutine check_disk
end module dpend_resources
