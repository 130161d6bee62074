!> Every limit dpend checks before it starts work, in one place, with the reason
!> for its value, and the checks themselves.
!>
!> Two kinds of limits:
!> - ranges of the inputs, chosen so that every expression of the model (energy,
!>   mass matrix and its determinant, accelerations, momenta, Jacobians, scales like
!>   √(l/g)) stays finite and far from overflow for every accepted combination:
!>   a product of up to eight accepted magnitudes stays below 1e100;
!> - counts derived from reals (steps, samples, grid points, threads), which must fit
!>   their integer kinds, stay under a maximum, and fit the machine's memory and the
!>   free space of the output's file system.
!>
!> The checks compare before they multiply or divide (e.g. `step*max_count < span`
!> with both factors already bounded), so that validating never overflows: the debug
!> profile traps on overflow, invalid and division by zero.
module dpend_limits
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   !> `sci` is the one number formatter of dpend_cli under the name the messages use
   use dpend_strings, only: sci => real_str
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   implicit none
   private
   public :: min_mass, max_mass, min_length, max_length, min_g, max_g
   public :: max_angle, max_angular_velocity, max_time, max_dt, min_rtol, min_atol, max_atol
   public :: max_omega, max_steps, default_max_steps, max_samples, max_threads
   public :: max_axis_points, max_sweep_points, max_tangent_substeps, min_delta0_relative
   public :: diverged_bound, max_damping, max_support_amplitude, max_support_frequency
   public :: max_torque, max_torque_frequency, min_coulomb_speed, max_coulomb_speed
   public :: max_rotor_inertia, min_gear_ratio, max_gear_ratio, max_reflected_inertia
   public :: finite_positive, bound_threads
   public :: check_parameter, parameter_mass, parameter_length, parameter_gravity
   public :: in_range, check_range, check_count, sci, bytes_text

   !> Masses [kg], lengths [m] and g [m/s²] are each within [1e-6, 1e6]: every
   !> product of the model (m l² g … at most eight factors, with the angular
   !> velocities below) stays within 1e±100, far from overflow (1e308) and from
   !> subnormals, and √(l/g) is within [1e-6, 1e6] s.
   !> A state component beyond this magnitude counts as diverged: no physical state of
   !> the pendulum comes near it, and stopping there keeps every intermediate stage of
   !> the next step below overflow (which would trap under -ffpe-trap=overflow). The
   !> integrators stop at it (`state_ok`); the chain model saturates its field beyond
   !> it, so that a step that blows up within its stages cannot overflow either.
   real(dp), parameter :: diverged_bound = 1e30_dp
   real(dp), parameter :: min_mass = 1e-6_dp      !! smallest m1, m2 [kg]
   real(dp), parameter :: max_mass = 1e6_dp       !! largest m1, m2 [kg]
   real(dp), parameter :: min_length = 1e-6_dp    !! smallest l1, l2 [m]
   real(dp), parameter :: max_length = 1e6_dp     !! largest l1, l2 [m]
   real(dp), parameter :: min_g = 1e-6_dp         !! smallest g [m/s²]
   real(dp), parameter :: max_g = 1e6_dp          !! largest g [m/s²]

   !> The one range table of the physical parameters, shared by every command
   !> (simulate, the chaos commands, sweep, study, fit) through `check_parameter`:
   !> one row per kind, so that g = 0 (for example) is refused everywhere alike.
   type :: parameter_range_t
      character(len=5) :: unit   !! SI unit
      real(dp) :: lo, hi         !! accepted range (inclusive)
   end type parameter_range_t
   integer, parameter :: parameter_mass = 1     !! m_i [kg]
   integer, parameter :: parameter_length = 2   !! l_i [m]
   integer, parameter :: parameter_gravity = 3  !! g [m/s²]
   type(parameter_range_t), parameter :: parameter_ranges(3) = [ &
      parameter_range_t('kg', min_mass, max_mass), &
      parameter_range_t('m', min_length, max_length), &
      parameter_range_t('m/s^2', min_g, max_g)]

   !> |q1|, |q2| (and angles of sweeps and sections) at most 1e6 rad (160 000 turns):
   !> beyond, the rounding of the angle itself exceeds 1e-10 rad.
   real(dp), parameter :: max_angle = 1e6_dp
   !> |w1|, |w2| at most 1e6 rad/s: kinetic energy, momenta and centripetal terms
   !> (m l² w² ≤ 1e6·1e12·1e12 = 1e30) stay far below overflow and the momenta below
   !> the integrators' divergence bound (1e30).
   real(dp), parameter :: max_angular_velocity = 1e6_dp

   !> Times (t_end, tau, output_dt, pair spacing, fit window, ...) at most 1e9 s
   !> (32 years): t + 1.01 h and every count below stay finite.
   real(dp), parameter :: max_time = 1e9_dp
   !> The step (or first trial step) at most 1e9 s, as the times.
   real(dp), parameter :: max_dt = 1e9_dp

   !> rtol at least 1e-14 (45 ε): below, the error estimate of an embedded pair is
   !> dominated by the rounding of the step itself and the step shrinks until it
   !> stalls (DOPRI5 and DOP853 refuse rtol ≤ 10 ε ≈ 2.2e-15).
   real(dp), parameter :: min_rtol = 1e-14_dp
   !> atol at least 1e-30: (error/atol)² stays below overflow for any state below the
   !> divergence bound 1e30; smaller values only matter for states crossing zero.
   real(dp), parameter :: min_atol = 1e-30_dp
   !> atol at most 1 (rad, rad/s): a larger absolute error leaves nothing controlled.
   real(dp), parameter :: max_atol = 1.0_dp
   !> Tao's binding constant ω at most 1e9 1/s: ω h stays finite for every step.
   real(dp), parameter :: max_omega = 1e9_dp
   !> Largest joint damping coefficient c_i [N m s].
   real(dp), parameter :: max_damping = 1e6_dp
   !> Largest support amplitude |a_x|, |a_y| [m] and frequency ω [rad/s].
   real(dp), parameter :: max_support_amplitude = 1e6_dp
   real(dp), parameter :: max_support_frequency = 1e6_dp
   !> Largest applied joint torque |τ_i| [N m] (a sample of a series, a closed form's
   !> bias or amplitude; the sum of a closed form's terms too), as the damping's 1e6:
   !> with the masses and lengths above, q̈ stays finite.
   real(dp), parameter :: max_torque = 1e6_dp
   !> Largest angular frequency of a closed-form torque's sine [rad/s].
   real(dp), parameter :: max_torque_frequency = 1e6_dp
   !> The speed v_s of the smoothed Coulomb friction c_f tanh(ω/v_s) [rad/s]: at least
   !> 1e-6 (c_f/v_s, the friction's stiffness near rest, stays ≤ 1e12 N m s with
   !> c_f ≤ max_torque), at most 1e3 (beyond, nothing is left of the sign).
   real(dp), parameter :: min_coulomb_speed = 1e-6_dp
   real(dp), parameter :: max_coulomb_speed = 1e3_dp
   !> A motor at a joint: rotor inertia I_r [kg m²] in [0, 1e6] (as a link's inertia
   !> about its centre, m l²/12 with the largest m and l above, is bounded by the
   !> reflected inertia below), gear ratio g_r in [1e-3, 1e4] (direct drive: 1; the
   !> strongest harmonic drives: a few hundred), and the reflected inertia g_r² I_r
   !> at most 1e12 kg m² (M's added part and its products stay finite; a rotor far
   !> heavier than its links makes M ill-conditioned, as do the extreme masses and
   !> lengths the ranges above allow).
   real(dp), parameter :: max_rotor_inertia = 1e6_dp
   real(dp), parameter :: min_gear_ratio = 1e-3_dp
   real(dp), parameter :: max_gear_ratio = 1e4_dp
   real(dp), parameter :: max_reflected_inertia = 1e12_dp

   !> At most 1e12 steps in one integration of a fixed-step method (a day at 1e7
   !> steps/s): the step index is exact in real(dp) (< 2^53) and t0 + i h never
   !> stalls (h ≥ 1e-12 (t_end - t0) ≫ ε t). Also the largest --max-steps.
   integer(i8), parameter :: max_steps = 1000000000000_i8
   !> Default --max-steps of the adaptive methods (dopri5, dop853): 1e8 accepted
   !> steps per integration, like DOP853's NMAX, so that a tolerance the problem
   !> cannot meet ends the run with a status instead of never ending.
   integer(i8), parameter :: default_max_steps = 100000000_i8
   !> At most 1e9 kept samples (trajectory samples, renormalisations, section
   !> points, sweep points): arrays are indexed with default integers (2^31 − 1),
   !> and memory and disk are checked on top.
   integer(i8), parameter :: max_samples = 1000000000_i8
   !> At most 1024 OpenMP threads.
   integer, parameter :: max_threads = 1024
   !> At most 1e6 points on one sweep axis (a block holds at least one whole row).
   integer, parameter :: max_axis_points = 1000000
   !> At most 1e9 initial conditions in one sweep (default-integer indices with room
   !> for j0 + nb sums).
   integer, parameter :: max_sweep_points = 1000000000
   !> At most 1e6 substeps of the tangent (variational) equations per step: a step
   !> much longer than the Jacobian's time scale ends the run with a status.
   integer, parameter :: max_tangent_substeps = 1000000
   !> divergence: delta0 at least 1e-13 max(1, |state|): a smaller displacement is
   !> lost in the rounding of the state (the two trajectories would be equal).
   real(dp), parameter :: min_delta0_relative = 1e-13_dp
   !> At most 1e10 step-equivalents in one `dpend fit`: the integration
   !> steps of all its integrations, a step with the P sensitivity columns counted
   !> 1 + P times. Measured at about 1e6 step-equivalents per second (release build,
   !> one core, dop853, 2 links), so a fit at the limit runs about 3 hours; the data
   !> example (data/fit_example.csv) needs 1.4e7 by the estimate. `fit` refuses a
   !> larger estimate before it starts and stops a fit that goes beyond it running.
   real(dp), parameter :: max_fit_work = 1e10_dp
   public :: max_fit_work

contains

   !> x is finite and lo <= x <= hi, tested without an ordered comparison on NaN
   !> (which raises IEEE invalid and traps under -ffpe-trap=invalid).
   elemental logical function in_range(x, lo, hi)
      real(dp), intent(in) :: x       !! value
      real(dp), intent(in) :: lo, hi  !! accepted range (inclusive)
      in_range = .false.
      if (ieee_is_finite(x)) in_range = x >= lo .and. x <= hi
   end function in_range

   !> Refuse x outside [lo, hi] (or not finite): 'invalid FIELD: X UNIT is outside
   !> [LO, HI] (REASON)'.
   subroutine check_range(field, x, lo, hi, unit, error, reason)
      character(len=*), intent(in) :: field             !! field name in the message
      real(dp), intent(in) :: x                         !! value
      real(dp), intent(in) :: lo, hi                    !! accepted range (inclusive)
      character(len=*), intent(in) :: unit              !! unit text ('' for none)
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      character(len=*), intent(in), optional :: reason  !! why the range
      character(len=:), allocatable :: u, r
      u = ''
      if (len_trim(unit) > 0) u = ' '//trim(unit)
      r = ''
      if (present(reason)) r = ' ('//reason//')'
      if (.not. ieee_is_finite(x)) then
         call fatal_error(error, 'invalid '//field//': must be finite, in ['//sci(lo)//', ' &
                          //sci(hi)//']'//u//r)
      else if (x < lo .or. x > hi) then
         call fatal_error(error, 'invalid '//field//': '//sci(x)//u//' is outside [' &
                          //sci(lo)//', '//sci(hi)//']'//r)
      end if
   end subroutine check_range

   !> Refuse a physical parameter (`parameter_mass`, `parameter_length`,
   !> `parameter_gravity`) outside its row of the range table: 'invalid FIELD: X UNIT
   !> is outside [LO, HI] (keeps every product of the model finite)'.
   subroutine check_parameter(which, field, x, error)
      integer, intent(in) :: which                      !! row of the table
      character(len=*), intent(in) :: field             !! e.g. 'm2', 'g'
      real(dp), intent(in) :: x                         !! value (SI)
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      type(parameter_range_t) :: r
      r = parameter_ranges(which)
      call check_range(field, x, r%lo, r%hi, trim(r%unit), error, &
                       'keeps every product of the model finite')
   end subroutine check_parameter

   !> Refuse when span/step exceeds max_count, compared as step·max_count < span
   !> (no overflow: step and max_count are bounded). Message: 'invalid FIELD: STEP s
   !> gives N WHAT over SPANNAME = SPAN s; at most MAX (HINT)'. step > 0, span ≥ 0.
   subroutine check_count(field, step, span, span_name, max_count, what, hint, error)
      character(len=*), intent(in) :: field             !! field to change
      real(dp), intent(in) :: step                      !! the interval (> 0, ≤ max_time)
      real(dp), intent(in) :: span                      !! the time to cover (≥ 0)
      character(len=*), intent(in) :: span_name         !! e.g. 't_end'
      integer(i8), intent(in) :: max_count              !! largest count
      character(len=*), intent(in) :: what              !! e.g. 'steps'
      character(len=*), intent(in) :: hint              !! what to do
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      if (step*real(max_count, dp) >= span) return
      call fatal_error(error, 'invalid '//field//': '//sci(step)//' s gives '// &
                       ratio_text(span, step)//' '//what//' over '//span_name//' = ' &
                       //sci(span)//' s; at most '//sci(real(max_count, dp))//' ('//hint//')')
   end subroutine check_count



   !> a/b for a, b > 0 as text (4 significant digits), without forming the quotient
   !> when it would overflow.
   function ratio_text(a, b) result(s)
      real(dp), intent(in) :: a, b
      character(len=:), allocatable :: s
      real(dp) :: l
      integer :: e
      if (a <= 0.0_dp) then
         s = '0'
         return
      end if
      l = log10(a) - log10(b)
      if (l < 300.0_dp) then
         s = sci(10.0_dp**l, 4)
      else
         e = floor(l)
         s = sci(10.0_dp**(l - real(e, dp)), 4)//'e'//sci(real(e, dp))
      end if
   end function ratio_text

   !> "12.3 GB" style text of a byte count (3 significant digits).
   function bytes_text(b) result(s)
      real(dp), intent(in) :: b
      character(len=:), allocatable :: s
      character(len=*), parameter :: units(6) = ['B ', 'kB', 'MB', 'GB', 'TB', 'PB']
      real(dp) :: x
      integer :: i
      x = b
      i = 1
      do while (x >= 1000.0_dp .and. i < size(units))
         x = x/1000.0_dp
         i = i + 1
      end do
      s = sci(x, 3)//' '//trim(units(i))
   end function bytes_text

   !> x is finite and > 0, tested without an ordered comparison on NaN (which
   !> would raise IEEE invalid and trap under -ffpe-trap=invalid).
   elemental logical function finite_positive(x)
      real(dp), intent(in) :: x  !! value to test
      finite_positive = .false.
      if (ieee_is_finite(x)) finite_positive = x > 0.0_dp
   end function finite_positive

   !> Bound the threads the OpenMP runtime takes from its environment
   !> (OMP_NUM_THREADS) by max_threads, as --threads is bounded: beyond it, max_threads
   !> are used and `note` says so ('' otherwise; 100000 threads crashed the runtime).
   subroutine bound_threads(note)
      character(len=:), allocatable, intent(out) :: note  !! one line, or ''
      integer :: n
      note = ''
      n = 1
      !$ n = omp_get_max_threads()
      if (n <= max_threads) return
      !$ call omp_set_num_threads(max_threads)
      note = 'OMP_NUM_THREADS asks for '//trim(int_text(n))//' threads, above '// &
             trim(int_text(max_threads))//': using '//trim(int_text(max_threads))
   contains
      pure function int_text(i) result(s)
         integer, intent(in) :: i
         character(len=16) :: s
         write (s, '(i0)') i
      end function int_text
   end subroutine bound_threads

end module dpend_limits
