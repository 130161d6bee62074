!> The factory: every integration method of dpend, constructed by name.
module dpend_integrators
   use dpend_error, only: error_t, fatal_error
   use dpend_integrator, only: integrator_t
   use dpend_rk_explicit, only: rk4_t, dopri5_t, dop853_t
   implicit none
   private
   public :: new_integrator, method_names

   !> Names accepted by --method, space separated.
   character(len=*), parameter :: method_names = 'rk4 dopri5 dop853'

contains

   !> Allocate the method called `name`.
   subroutine new_integrator(name, integ, error)
      character(len=*), intent(in) :: name                        !! method name
      class(integrator_t), allocatable, intent(out) :: integ      !! the method
      type(error_t), allocatable, intent(out) :: error            !! unknown name
      select case (name)
      case ('rk4')
         allocate (rk4_t :: integ)
      case ('dopri5')
         allocate (dopri5_t :: integ)
      case ('dop853')
         allocate (dop853_t :: integ)
      case default
         call fatal_error(error, "invalid method: '"//trim(name)//"' (accepted: " &
                          //method_names//")")
      end select
   end subroutine new_integrator
end module dpend_integrators
