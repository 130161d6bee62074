!> The options of an integration method, in one record passed to the factory
!> (`new_integrator(name, integ, error, options)`) or to `integ%configure(options)`.
!>
!> A method reads the options it has and ignores the others: the tolerances and
!> `fixed_step` reach the adaptive pairs (dopri5, dop853), ω reaches Tao's methods
!> (tao2, and tao4 through its base), `compensated` the canonical (q, p) methods,
!> `max_steps` every method. A real option left at 0 (and `max_steps` at 0) keeps
!> the method's own default; the logical options hold the methods' defaults.
module dpend_method_options
   use dpend_kinds, only: dp, i8
   implicit none
   private
   public :: method_options_t

   !> Options of one method; 0 means "the method's default".
   type :: method_options_t
      real(dp) :: rtol = 0.0_dp        !! relative tolerance (adaptive methods; 0: 1e-9)
      real(dp) :: atol = 0.0_dp        !! absolute tolerance (adaptive methods; 0: 1e-12)
      real(dp) :: omega = 0.0_dp       !! Tao's binding constant ω [1/s] (0: 20)
      integer(i8) :: max_steps = 0     !! most accepted steps of one adaptive
                                       !! integration (0: default_max_steps)
      !> Adaptive methods take exactly the given step, without error control
      !> (the study's fixed-step sweeps of dopri5 and dop853).
      logical :: fixed_step = .false.
      !> Kahan-compensated update of the (q, p) methods; .false. shows the plain
      !> roundoff (the study's Brouwer experiment).
      logical :: compensated = .true.
   end type method_options_t
end module dpend_method_options
