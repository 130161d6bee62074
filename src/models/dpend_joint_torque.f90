!> Applied joint torques τ_i(t): what a motor at joint i exerts on link i (and, by
!> reaction, −τ_i on link i − 1; joint 1 is the pin A on the ground).
!>
!> Two forms, both functions of time only:
!> - a series of samples (t_k, τ_ik), k = 1 … K ≥ 2, strictly increasing times, read
!>   from a torque file (`--torque-file`, columns t, tau1 … tauN): between samples τ is
!>   the straight line through its neighbours (linear interpolation, so a run sees a
!>   continuous, piecewise linear torque); the settings refuse a run whose span
!>   [0, t_end] leaves the series (`covers`); a stage a rounding beyond the last sample
!>   takes the end value;
!> - a closed form τ_i(t) = b_i + Σ_k A_ik sin(ω_k t + φ_ik) (a bias and a sum of
!>   sines: the tests' exact torques and an excitation of identification runs).
!>
!> In absolute angles the torques enter Lagrange's equations as the generalized forces
!> Q_i = τ_i − τ_(i+1) (τ_(N+1) = 0), and they do the work
!>   W_torque(t) = ∫₀ᵗ Σ_i τ_i (q̇_i − q̇_(i−1)) dt   (q̇_0 = 0).
!> Every value is checked when built: finite, |τ| ≤ max_torque (for the closed form,
!> |b_i| + Σ_k |A_ik| ≤ max_torque), times within max_time.
module dpend_joint_torque
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_limits, only: max_torque, max_torque_frequency, max_time, max_angle, sci
   use dpend_strings, only: to_str
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: joint_torque_t, torque_series, torque_sines

   integer, parameter :: form_none = 0     !! no torques
   integer, parameter :: form_series = 1   !! samples, linear interpolation
   integer, parameter :: form_sines = 2    !! bias and a sum of sines

   !> The torques of the N joints (build with `torque_series` or `torque_sines`).
   type :: joint_torque_t
      integer :: n = 0                         !! joints N (0: no torques)
      integer :: form = form_none              !! which of the two forms
      real(dp), allocatable :: t(:)            !! series: sample times (K) [s]
      real(dp), allocatable :: tau(:, :)       !! series: τ_i at the samples (N, K) [N m]
      real(dp), allocatable :: bias(:)         !! closed form: b_i (N) [N m]
      real(dp), allocatable :: amp(:, :)       !! closed form: A_ik (N, terms) [N m]
      real(dp), allocatable :: omega(:)        !! closed form: ω_k (terms) [rad/s]
      real(dp), allocatable :: phase(:, :)     !! closed form: φ_ik (N, terms) [rad]
   contains
      !> Torques are applied (a series or a closed form).
      procedure :: active => torque_active
      !> τ_1 … τ_N at time t [N m].
      procedure :: values => torque_values
      !> The torques are defined on all of [t0, t1] (a series: its samples span it).
      procedure :: covers => torque_covers
      !> One line for people: the form and its extent.
      procedure :: text => torque_text
   end type joint_torque_t

contains

   !> The series (t_k, τ_ik): `times` (K), `torques` (N, K); refused (error set, the
   !> result inactive) unless K ≥ 2, the times finite, within max_time and strictly
   !> increasing, and every torque finite with |τ| ≤ max_torque.
   function torque_series(times, torques, error) result(torque)
      real(dp), intent(in) :: times(:)                  !! t_k [s]
      real(dp), intent(in) :: torques(:, :)             !! τ_ik [N m]
      type(error_t), allocatable, intent(out) :: error  !! the first problem
      type(joint_torque_t) :: torque
      integer :: k, i
      if (size(times) < 2) then
         call fatal_error(error, 'invalid torque series: '//to_str(size(times))// &
                          trim(merge(' sample ', ' samples', size(times) == 1))// &
                          '; at least 2 (the torque between them is interpolated)')
         return
      end if
      if (size(torques, 2) /= size(times) .or. size(torques, 1) < 1) then
         call fatal_error(error, 'internal error: torque series of shape ('// &
                          to_str(size(torques, 1))//', '//to_str(size(torques, 2))// &
                          ') for '//to_str(size(times))//' times')
         return
      end if
      ! (no comparison of a NaN: the debug profile traps on invalid operations)
      do k = 1, size(times)
         if (.not. finite_within(times(k), max_time)) then
            call fatal_error(error, 'invalid torque series: sample '//to_str(k)// &
                             ': t = '//sci(times(k))//' s is not finite within [-'// &
                             sci(max_time)//', '//sci(max_time)//'] s')
            return
         end if
         if (k > 1) then
            if (.not. times(k) > times(k - 1)) then
               call fatal_error(error, 'invalid torque series: sample '//to_str(k)// &
                                ': t = '//sci(times(k))//' s is not after t = '// &
                                sci(times(k - 1))//' s (times must increase)')
               return
            end if
         end if
         do i = 1, size(torques, 1)
            if (.not. finite_within(torques(i, k), max_torque)) then
               call fatal_error(error, 'invalid torque series: sample '//to_str(k)// &
                                ': tau'//to_str(i)//' = '//sci(torques(i, k))// &
                                ' N m is not finite within [-'//sci(max_torque)//', '// &
                                sci(max_torque)//'] N m')
               return
            end if
         end do
      end do
      torque%n = size(torques, 1)
      torque%form = form_series
      torque%t = times
      torque%tau = torques
   end function torque_series

   !> The closed form τ_i(t) = b_i + Σ_k A_ik sin(ω_k t + φ_ik): `bias` (N), `amp`
   !> and `phase` (N, terms), `omega` (terms); refused unless every value is finite,
   !> |b_i| + Σ_k |A_ik| ≤ max_torque, 0 ≤ ω_k ≤ max_torque_frequency, |φ| ≤ max_angle.
   function torque_sines(bias, amp, omega, phase, error) result(torque)
      real(dp), intent(in) :: bias(:)                   !! b_i [N m]
      real(dp), intent(in) :: amp(:, :)                 !! A_ik [N m]
      real(dp), intent(in) :: omega(:)                  !! ω_k [rad/s]
      real(dp), intent(in) :: phase(:, :)               !! φ_ik [rad]
      type(error_t), allocatable, intent(out) :: error  !! the first problem
      type(joint_torque_t) :: torque
      integer :: i, n
      n = size(bias)
      if (n < 1 .or. size(amp, 1) /= n .or. size(phase, 1) /= n .or. &
          size(amp, 2) /= size(omega) .or. size(phase, 2) /= size(omega)) then
         call fatal_error(error, 'internal error: closed-form torque of inconsistent shapes')
         return
      end if
      do i = 1, size(omega)
         if (.not. finite_within(omega(i), max_torque_frequency)) then
            call fatal_error(error, 'invalid torque frequency: must be finite, in [0, '// &
                             sci(max_torque_frequency)//'] rad/s')
            return
         else if (omega(i) < 0.0_dp) then
            call fatal_error(error, 'invalid torque frequency: '//sci(omega(i))// &
                             ' rad/s is outside [0, '//sci(max_torque_frequency)//'] rad/s')
            return
         end if
      end do
      if (.not. all(finite_within(phase, max_angle))) then
         call fatal_error(error, 'invalid torque phase: must be finite, in [-'// &
                          sci(max_angle)//', '//sci(max_angle)//'] rad')
         return
      end if
      do i = 1, n
         if (.not. (ieee_is_finite(bias(i)) .and. all(ieee_is_finite(amp(i, :))))) then
            call fatal_error(error, 'invalid torque tau'//to_str(i)//': must be finite')
            return
         end if
         if (abs(bias(i)) + sum(abs(amp(i, :))) > max_torque) then   ! all finite here
            call fatal_error(error, 'invalid torque tau'//to_str(i)//': |bias| + '// &
                             'sum |amplitude| = '//sci(abs(bias(i)) + sum(abs(amp(i, :))))// &
                             ' N m is beyond '//sci(max_torque)//' N m')
            return
         end if
      end do
      torque%n = n
      torque%form = form_sines
      torque%bias = bias
      torque%amp = amp
      torque%omega = omega
      torque%phase = phase
   end function torque_sines

   !> x is finite and |x| ≤ bound (no comparison of a NaN or an infinity).
   elemental logical function finite_within(x, bound)
      real(dp), intent(in) :: x       !! value
      real(dp), intent(in) :: bound   !! largest magnitude
      finite_within = .false.
      if (ieee_is_finite(x)) finite_within = abs(x) <= bound
   end function finite_within

   pure logical function torque_active(self)
      class(joint_torque_t), intent(in) :: self  !! the torques
      torque_active = self%form /= form_none
   end function torque_active

   !> τ_1 … τ_N at t (zero without torques); a series between its samples is
   !> interpolated linearly, outside it takes the nearer end sample.
   pure subroutine torque_values(self, t, tau)
      class(joint_torque_t), intent(in) :: self  !! the torques
      real(dp), intent(in) :: t                  !! time [s]
      real(dp), intent(out) :: tau(:)            !! τ_i [N m] (at least N)
      integer :: lo, hi, mid, k
      real(dp) :: w
      tau = 0.0_dp
      select case (self%form)
      case (form_series)
         k = size(self%t)
         if (t <= self%t(1)) then
            tau(1:self%n) = self%tau(:, 1)
         else if (t >= self%t(k)) then
            tau(1:self%n) = self%tau(:, k)
         else   ! t(lo) <= t < t(hi), hi = lo + 1
            lo = 1; hi = k
            do while (hi - lo > 1)
               mid = (lo + hi)/2
               if (self%t(mid) <= t) then
                  lo = mid
               else
                  hi = mid
               end if
            end do
            w = (t - self%t(lo))/(self%t(hi) - self%t(lo))
            tau(1:self%n) = self%tau(:, lo) + w*(self%tau(:, hi) - self%tau(:, lo))
         end if
      case (form_sines)
         tau(1:self%n) = self%bias
         do k = 1, size(self%omega)
            tau(1:self%n) = tau(1:self%n) + self%amp(:, k)*sin(self%omega(k)*t + self%phase(:, k))
         end do
      end select
   end subroutine torque_values

   !> The torques are defined on [t0, t1]: always for a closed form; a series when
   !> its first sample is at or before t0 and its last at or after t1.
   pure logical function torque_covers(self, t0, t1)
      class(joint_torque_t), intent(in) :: self  !! the torques
      real(dp), intent(in) :: t0, t1             !! the span [s]
      torque_covers = .true.
      if (self%form == form_series) torque_covers = self%t(1) <= t0 .and. &
                                                     self%t(size(self%t)) >= t1
   end function torque_covers

   !> 'a series of K samples over [t_1, t_K] s, linear between them' or
   !> 'a bias and S sines', for messages and the file.
   function torque_text(self) result(text)
      class(joint_torque_t), intent(in) :: self  !! the torques
      character(len=:), allocatable :: text
      select case (self%form)
      case (form_series)
         text = 'a series of '//to_str(size(self%t))//' samples over ['// &
                sci(self%t(1))//', '//sci(self%t(size(self%t)))// &
                '] s, linear between samples'
      case (form_sines)
         text = 'the closed form b_i + sum_k A_ik sin(omega_k t + phi_ik), '// &
                to_str(size(self%omega))//' sines'
      case default
         text = 'none'
      end select
   end function torque_text
end module dpend_joint_torque
