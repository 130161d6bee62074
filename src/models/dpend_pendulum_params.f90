!> The parameters of the double pendulum (`pendulum_t`, SI units), the kinds of its
!> links' mass distribution, their checks and the constants of a general body: what
!> the formulas of dpend_pendulum read, and what the constructors check (`validate`
!> for the double pendulum; `check_bodies`, shared with the N-link chain).
!>
!> dpend_pendulum passes every public name of this module on; use it from there.
module dpend_pendulum_params
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: check_parameter, parameter_mass, parameter_length, &
                           parameter_gravity, check_range, max_length, max_mass
   use dpend_strings, only: real_str
   implicit none
   private
   public :: pendulum_t, body_rod, body_general, validate, check_bodies, body_constants
   public :: body_kind_name

   !> The body kind of `pendulum_t`: uniform rods (the chapter's; d_i = l_i/2,
   !> I_i = m_i l_i²/12, the fields d1 … i2 unused) or links of any mass distribution
   !> (d1, d2, i1, i2 given). The rod's formulas keep their own arithmetic (results
   !> bit for bit unchanged by the general bodies); the general ones reduce to them for rod values
   !> (test/test_bodies.f90 compares them).
   integer, parameter :: body_rod = 0
   integer, parameter :: body_general = 1

   !> Physical parameters (SI units). Defaults are the chapter's numerical application.
   type :: pendulum_t
      real(dp) :: m1 = 1.0_dp   !! mass of link 1 [kg]
      real(dp) :: m2 = 1.0_dp   !! mass of link 2 [kg]
      real(dp) :: l1 = 1.0_dp   !! length of link 1 [m]
      real(dp) :: l2 = 1.0_dp   !! length of link 2 [m]
      real(dp) :: g = 9.8_dp    !! gravitational acceleration [m/s²]
      integer :: body = body_rod   !! body_rod (uniform rods) or body_general
      real(dp) :: d1 = 0.5_dp   !! joint A to the centre of mass C1 (body_general) [m]
      real(dp) :: d2 = 0.5_dp   !! joint B to the centre of mass C2 (body_general) [m]
      real(dp) :: i1 = 1.0_dp/12.0_dp  !! inertia of link 1 about C1 (body_general) [kg m²]
      real(dp) :: i2 = 1.0_dp/12.0_dp  !! inertia of link 2 about C2 (body_general) [kg m²]
   end type pendulum_t

contains

   !> Check that every parameter is finite and within its accepted range
   !> (`dpend_limits`: [1e-6, 1e6] each, so that no product of the model overflows).
   subroutine validate(par, error)
      type(pendulum_t), intent(in) :: par               !! parameters to check
      type(error_t), allocatable, intent(out) :: error  !! set if a value is invalid
      character(len=*), parameter :: names(5) = ['m1', 'm2', 'l1', 'l2', 'g ']
      integer, parameter :: rows(5) = [parameter_mass, parameter_mass, parameter_length, &
                                       parameter_length, parameter_gravity]
      real(dp) :: x(5)
      integer :: i
      x = [par%m1, par%m2, par%l1, par%l2, par%g]
      do i = 1, 5
         call check_parameter(rows(i), trim(names(i)), x(i), error)
         if (allocated(error)) return
      end do
      if (par%body /= body_rod) call check_bodies([par%m1, par%m2], [par%l1, par%l2], &
                                                  [par%d1, par%d2], [par%i1, par%i2], error)
   end subroutine validate

   !> Check the mass distribution of links with masses m and lengths l (checked
   !> before): d_i (joint i to the centre of mass C_i, along the link) in
   !> [0, max_length] m, I_i (about C_i) in [0, max_mass max_length²] kg m², and each
   !> link's inertia about its own joint, I_i + m_i d_i², at least 1e-12 m_i l_i²:
   !> without it the link (a point mass on its own pin) has no inertia to turn, and
   !> the mass matrix is singular (for the last link everywhere, for another where the
   !> links align). d_i > l_i is accepted (a bob beyond the next pin or the tip);
   !> d_i < 0 (a counterweight behind the pin) is not: d is measured from the joint
   !> towards the link's far end.
   subroutine check_bodies(m, l, d, inertia, error)
      real(dp), intent(in) :: m(:)                      !! masses [kg]
      real(dp), intent(in) :: l(:)                      !! lengths [m]
      real(dp), intent(in) :: d(:)                      !! joint to centre of mass [m]
      real(dp), intent(in) :: inertia(:)                !! inertia about C_i [kg m²]
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      character(len=20) :: k
      integer :: i
      do i = 1, size(m)
         write (k, '(i0)') i
         call check_range('com'//trim(k), d(i), 0.0_dp, max_length, 'm', error, &
                          'the distance from joint '//trim(k)//' to the centre of mass ' &
                          //'of link '//trim(k)//' along the link')
         if (allocated(error)) return
         call check_range('inertia'//trim(k), inertia(i), 0.0_dp, max_mass*max_length**2, &
                          'kg m^2', error, 'the moment of inertia of link '//trim(k) &
                          //' about its centre of mass')
         if (allocated(error)) return
         if (.not. inertia(i) + m(i)*d(i)**2 >= 1e-12_dp*m(i)*l(i)**2) then
            call fatal_error(error, 'invalid com'//trim(k)//', inertia'//trim(k)//': com' &
                             //trim(k)//' = '//real_str(d(i))//' m with inertia'//trim(k)//' = ' &
                             //real_str(inertia(i))//' kg m^2 leaves link '//trim(k) &
                             //' no inertia about its joint (inertia + m com^2 must be at ' &
                             //'least 1e-12 m l^2, else the mass matrix is singular)')
            return
         end if
      end do
   end subroutine check_bodies

   !> The constants of a general two-link body (`body_general`): M11 = I1 + m1 d1² +
   !> m2 l1², M22 = I2 + m2 d2² [kg m²], k = m2 l1 d2 (M12 = k cos(q1 − q2)) [kg m²],
   !> and V = ga sin q1 + gb sin q2 with ga = g (m1 d1 + m2 l1), gb = g m2 d2 [J].
   !> The rod's formulas keep their own arithmetic; for rod values these agree with
   !> them to rounding.
   pure function body_constants(par) result(c)
      type(pendulum_t), intent(in) :: par  !! parameters (any body kind: d, I used)
      real(dp) :: c(5)                     !! (M11, M22, k, ga, gb)
      c(1) = par%i1 + par%m1*par%d1**2 + par%m2*par%l1**2
      c(2) = par%i2 + par%m2*par%d2**2
      c(3) = par%m2*par%l1*par%d2
      c(4) = par%g*(par%m1*par%d1 + par%m2*par%l1)
      c(5) = par%g*par%m2*par%d2
   end function body_constants

   !> 'rod', 'point' (d_i = l_i, I_i = 0) or 'general': the body of a parameter set.
   pure function body_kind_name(par) result(name)
      type(pendulum_t), intent(in) :: par  !! parameters
      character(len=:), allocatable :: name
      if (par%body == body_rod) then
         name = 'rod'
      else if (par%d1 == par%l1 .and. par%d2 == par%l2 .and. par%i1 == 0.0_dp &
               .and. par%i2 == 0.0_dp) then
         name = 'point'
      else
         name = 'general'
      end if
   end function body_kind_name
end module dpend_pendulum_params
