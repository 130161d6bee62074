!> Program version, written into every output file.
module dpend_version
   implicit none
   private
   public :: version

   character(len=*), parameter :: version = '0.1.0'  !! keep in step with fpm.toml
end module dpend_version
