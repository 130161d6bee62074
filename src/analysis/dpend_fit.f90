!> Least-squares power laws for the energy-conservation study: the slope of
!> log y against log x, optionally restricted to a window of x and to values
!> above a floor. It measures orders of convergence (error against step size:
!> slope = order) and drift exponents (energy error against time: slope 0 for a
!> bounded error, 1 for a linear drift, 1/2 for a random walk).
!>
!> Points that cannot lie on a power law are skipped, never trapped on: x or y
!> not finite (NaN marks an empty time bin), x <= 0 or y <= 0 (an exactly
!> conserved energy), outside [x_min, x_max], or y <= y_min (a roundoff floor).
!> Every test is a classification or is made after the finiteness check, so
!> NaN never meets an ordered comparison (debug builds trap on IEEE invalid).
module dpend_fit
   use dpend_kinds, only: dp
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: fit_t, loglog_fit, drift_exponent, usable_point

   !> A fitted power law y ≈ exp(intercept) x^slope.
   type :: fit_t
      real(dp) :: slope = 0.0_dp      !! exponent (order, drift exponent)
      real(dp) :: intercept = 0.0_dp  !! natural log of the prefactor: ln y at x = 1
      real(dp) :: stderr = 0.0_dp     !! standard error of the slope (0 with 2 points)
      real(dp) :: x_lo = 0.0_dp       !! smallest x used
      real(dp) :: x_hi = 0.0_dp       !! largest x used
      integer :: n = 0                !! number of points used
      logical :: ok = .false.         !! at least 2 usable points with distinct x
   end type fit_t

contains

   !> The point (x, y) can enter a log–log fit restricted to [x_min, x_max] with
   !> values above y_min (all optional).
   elemental logical function usable_point(x, y, x_min, x_max, y_min) result(use)
      real(dp), intent(in) :: x                   !! abscissa (> 0)
      real(dp), intent(in) :: y                   !! ordinate (> 0)
      real(dp), intent(in), optional :: x_min     !! smallest x accepted
      real(dp), intent(in), optional :: x_max     !! largest x accepted
      real(dp), intent(in), optional :: y_min     !! values must exceed this floor
      use = .false.
      if (.not. (ieee_is_finite(x) .and. ieee_is_finite(y))) return
      if (x <= 0.0_dp .or. y <= 0.0_dp) return
      if (present(x_min)) then
         if (x < x_min) return
      end if
      if (present(x_max)) then
         if (x > x_max) return
      end if
      if (present(y_min)) then
         if (y <= y_min) return
      end if
      use = .true.
   end function usable_point

   !> Least-squares fit of ln y = intercept + slope ln x over the usable points
   !> (see `usable_point`). `ok` is false, and slope 0, if fewer than two
   !> usable points with distinct x remain.
   pure function loglog_fit(x, y, x_min, x_max, y_min) result(fit)
      real(dp), intent(in) :: x(:)                !! abscissae, e.g. step sizes [s]
      real(dp), intent(in) :: y(:)                !! ordinates, same size as x
      real(dp), intent(in), optional :: x_min     !! window: smallest x used
      real(dp), intent(in), optional :: x_max     !! window: largest x used
      real(dp), intent(in), optional :: y_min     !! floor: only y > y_min are used
      type(fit_t) :: fit
      logical :: use(size(x))
      real(dp) :: lx(size(x)), ly(size(x)), mx, my, sxx, sxy, ssr
      integer :: n, i
      use = usable_point(x, y(:size(x)), x_min, x_max, y_min)
      n = count(use)
      fit%n = n
      if (n < 2) return
      lx = 0.0_dp
      ly = 0.0_dp
      do i = 1, size(x)
         if (use(i)) then
            lx(i) = log(x(i))
            ly(i) = log(y(i))
         end if
      end do
      mx = sum(lx, mask=use)/n
      my = sum(ly, mask=use)/n
      sxx = sum((lx - mx)**2, mask=use)
      if (.not. (sxx > 0.0_dp)) return
      sxy = sum((lx - mx)*(ly - my), mask=use)
      fit%slope = sxy/sxx
      fit%intercept = my - fit%slope*mx
      if (n > 2) then
         ssr = sum((ly - fit%intercept - fit%slope*lx)**2, mask=use)
         fit%stderr = sqrt(max(ssr, 0.0_dp)/real(n - 2, dp)/sxx)
      end if
      fit%x_lo = minval(x, mask=use)
      fit%x_hi = maxval(x, mask=use)
      fit%ok = .true.
   end function loglog_fit

   !> Drift exponent of an error e(t) sampled on a time grid: the slope of
   !> ln e against ln t over the window [t_min, t_max] (after the initial
   !> transient, before any roundoff regime). Bounded error: ≈ 0; linear drift:
   !> 1; random walk: 1/2. Empty samples (NaN) and zeros are skipped.
   pure function drift_exponent(t, e, t_min, t_max) result(fit)
      real(dp), intent(in) :: t(:)     !! sample times [s]
      real(dp), intent(in) :: e(:)     !! error at (or maximum up to) each time
      real(dp), intent(in) :: t_min    !! start of the window [s]
      real(dp), intent(in) :: t_max    !! end of the window [s]
      type(fit_t) :: fit
      fit = loglog_fit(t, e, x_min=t_min, x_max=t_max)
   end function drift_exponent
end module dpend_fit
