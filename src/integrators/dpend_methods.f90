!> The factory: every integration method of dpend, constructed by name.
module dpend_methods
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_integrator, only: integrator_t
   use dpend_rk_explicit, only: rk4_t, dopri5_t, dop853_t, rk_adaptive_t
   use dpend_symplectic, only: gauss, verlet_t, composition, triple_jump, kahan_li_6, kahan_li_8
   use dpend_tao, only: tao_t, set_omega
   implicit none
   private
   public :: new_integrator, method_names

   !> Names accepted by --method, space separated.
   character(len=*), parameter :: method_names = 'rk4 dopri5 dop853' &
                                                  //' midpoint gauss4 gauss6 gauss8 verlet' &
                                                  //' yoshida4 comp6 comp8 tao2 tao4'

contains

   !> Allocate the method called `name` and set its options: tolerances for the
   !> adaptive methods, the binding constant for Tao's (ignored by the others), the
   !> most accepted steps of one adaptive integration.
   subroutine new_integrator(name, integ, error, rtol, atol, omega, max_steps)
      character(len=*), intent(in) :: name                        !! method name
      class(integrator_t), allocatable, intent(out) :: integ      !! the method
      type(error_t), allocatable, intent(out) :: error            !! unknown name
      real(dp), intent(in), optional :: rtol                      !! relative tolerance
      real(dp), intent(in), optional :: atol                      !! absolute tolerance
      real(dp), intent(in), optional :: omega                     !! Tao's ω [1/s]
      integer(i8), intent(in), optional :: max_steps              !! most steps of one
                                                                  !! adaptive integration
      logical :: found
      select case (name)
      case ('rk4')
         allocate (rk4_t :: integ)
      case ('dopri5')
         allocate (dopri5_t :: integ)
      case ('dop853')
         allocate (dop853_t :: integ)
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
         return
      end select
      select type (integ)
      class is (rk_adaptive_t)
         if (present(rtol)) integ%rtol = rtol
         if (present(atol)) integ%atol = atol
      end select
      if (present(omega)) call set_omega(integ, omega, found)
      if (present(max_steps)) integ%max_steps = max_steps
   end subroutine new_integrator
end module dpend_methods
