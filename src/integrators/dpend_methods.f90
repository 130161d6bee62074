!> The factory: every integration method of dpend, constructed by name. The names,
!> orders and properties are those of the method registry (dpend_method_registry);
!> this module only allocates the type that implements each name.
module dpend_methods
   use dpend_error, only: error_t, fatal_error
   use dpend_integrator, only: integrator_t
   use dpend_method_options, only: method_options_t
   use dpend_method_registry, only: method_index, method_names
   use dpend_strings, only: canonical_name, did_you_mean, printable
   use dpend_rk_explicit, only: rk4_t, dopri5_t, dop853_t
   use dpend_symplectic, only: gauss, verlet_t, composition, triple_jump, kahan_li_6, kahan_li_8
   use dpend_tao, only: tao_t
   implicit none
   private
   public :: new_integrator, method_names, method_options_t

contains

   !> Allocate the method called `name` (a name of the registry) and set its
   !> options (`integ%configure`): tolerances of the adaptive methods, Tao's ω,
   !> the most accepted steps of one adaptive integration, ... Without `options`
   !> every method has its defaults. The name is taken without regard to case
   !> (`RK4` is rk4); an unknown one is refused with the nearest name, if close.
   subroutine new_integrator(name, integ, error, options)
      character(len=*), intent(in) :: name                        !! method name
      class(integrator_t), allocatable, intent(out) :: integ      !! the method
      type(error_t), allocatable, intent(out) :: error            !! unknown name
      type(method_options_t), intent(in), optional :: options     !! its options
      character(len=:), allocatable :: key, hint
      key = canonical_name(trim(name), method_names())
      if (method_index(key) == 0) then
         hint = did_you_mean(trim(name), method_names(), '; ')
         call fatal_error(error, "invalid method: '"//printable(trim(name))//"' (accepted: " &
                          //method_names()//")"//hint)
         return
      end if
      select case (key)
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
         call fatal_error(error, "method '"//trim(name)//"' is in the registry but " &
                          //"new_integrator cannot build it")
         return
      end select
      if (present(options)) call integ%configure(options)
   end subroutine new_integrator
end module dpend_methods
