!> The model a file's numbers come from, as root attributes of the file: every
!> parameter under the name the model gives it (`parameter`: m1, l2, g, c1, com2, k, …)
!> and, for links other than uniform rods, the body's description (`body`). One writer
!> for the files of every command, so that the model can be rebuilt from any of them.
module dpend_model_record
   use dpend_kinds, only: dp
   use dpend_model, only: model_t
   use dpend_hdf5, only: h5file_t
   implicit none
   private
   public :: record_model

contains

   !> Write the model's parameters and body as attributes of `group` (default '/').
   subroutine record_model(h5, model, group)
      type(h5file_t), intent(inout) :: h5              !! the open file
      class(model_t), intent(in) :: model              !! the model the run used
      character(len=*), intent(in), optional :: group  !! where ('/' if absent)
      character(len=:), allocatable :: where, name, units
      real(dp) :: value
      integer :: j
      where = '/'
      if (present(group)) where = group
      do j = 1, model%n_parameters()
         call model%parameter(j, name, value, units)
         call h5%writeattr(where, name, value)
      end do
      if (len(model%body_description()) > 0) &
         call h5%writeattr(where, 'body', model%body_description())
   end subroutine record_model

end module dpend_model_record
