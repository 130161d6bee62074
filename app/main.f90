program main
   use dpend_kinds, only: dp
   use hdf5
   implicit none
   integer :: err
   call h5open_f(err)
   print *, 'ok', err
   call h5close_f(err)
end program main
