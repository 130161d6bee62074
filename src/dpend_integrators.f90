!> The factory: every integration method of dpend, constructed by name.
module dpend_integrators
   use dpend_error, only: error_t, fatal_error
   use dpend_integrator, only: integrator_t
   use dpend_rk_explicit, only: rk4_t
   use dpend_symplectic, only: gauss, verlet_t, composition, triple_jump, kahan_li_6, kahan_li_8
   use dpend_tao, only: tao_t
   implicit none
   private
   public :: new_integrator, method_names

   !> Names accepted by --method, space separated.
   character(len=*), parameter :: method_names = 'rk4' &
                                                 //' midpoint gauss4 gauss6 gauss8 verlet' &
                                                 //' yoshida4 comp6 comp8 tao2 tao4'

contains

   !> Allocate the method called `name`.
   subroutine new_integrator(name, integ, error)
      character(len=*), intent(in) :: name                        !! method name
      class(integrator_t), allocatable, intent(out) :: integ      !! the method
      type(error_t), allocatable, intent(out) :: error            !! unknown name
      select case (name)
      case ('rk4')
         allocate (rk4_t :: integ)
      case ('midpoint')
         allocate (integ, source=gauss(1))
      case ('gauss4')
         allocate (integ, source=gauss(2))
      case ('gauss6')
         allocate (integ, source=gauss(3))
      case ('gauss8')
         allocate (integ, source=gauss(4))
      case ('verlet')
         allocate (verlet_t :: integ)
      case ('yoshida4')
         allocate (integ, source=composition(verlet_t(), triple_jump(), 4, 'yoshida4'))
      case ('comp6')
         allocate (integ, source=composition(verlet_t(), kahan_li_6(), 6, 'comp6'))
      case ('comp8')
         allocate (integ, source=composition(verlet_t(), kahan_li_8(), 8, 'comp8'))
      case ('tao2')
         allocate (tao_t :: integ)
      case ('tao4')
         allocate (integ, source=composition(tao_t(), triple_jump(), 4, 'tao4'))
      case default
         call fatal_error(error, "invalid method: '"//trim(name)//"' (accepted: " &
                          //method_names//")")
      end select
   end subroutine new_integrator
end module dpend_integrators
