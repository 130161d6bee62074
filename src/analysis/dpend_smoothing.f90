!> Smoothing and differentiating a sampled signal by local polynomials (the
!> Savitzky–Golay filter, on the samples' own times):
!> - at sample j, a polynomial of degree p is fitted by least squares to the 2k + 1
!>   samples nearest in index (centred on j; at the ends the first or last 2k + 1), in
!>   s = t − t_j; its value, slope and curvature at s = 0 are the estimates of y,
!>   ẏ and ÿ. Each is a linear combination Σ w_d,i y_i of the window's samples with
!>   weights w_d (`derivative_weights`, by a QR factorisation of the scaled
!>   Vandermonde matrix), so the filter's error is known from the weights:
!>     noise:  σ (Σ w_d,i²)^(1/2)       for white noise of standard deviation σ;
!>     bias:   y^(m) Σ w_d,i s_i^m / m!  the first moment the weights do not cancel
!>             (m = p + 1, or p + 2 where symmetry cancels p + 1: `bias_order`);
!> - the noise σ of a column is estimated from its fourth differences, robustly:
!>   σ = 1.4826 median|Δ⁴y| / √70 (Δ⁴ of white noise has variance 70 σ²; of a smooth
!>   signal sampled finely, h⁴ y⁽⁴⁾, negligible beside the noise of real data);
!> - the window is chosen by an iterated plug-in rule (after Gasser, Kneip and Köhler
!>   1991): the half-width k minimising the estimated mean square error of ÿ summed
!>   over the columns, σ_c² Σ w_2,i² + (R_c Σ w_2,i s_i^m / m!)², where R_c is the RMS
!>   of y_c^(m) estimated by a local polynomial of degree m + 1 on a window twice as
!>   wide as the current choice; three rounds from k = 8 (`choose_half_width`).
!> Pure procedures, no state.
module dpend_smoothing
   use dpend_kinds, only: dp
   use dpend_sorting, only: median
   implicit none
   private
   public :: derivative_weights, smooth_derivatives, noise_sigma, bias_order, &
      choose_half_width, filter_error, predicted_errors, noise_factors, min_half_width, &
      max_half_width, max_degree

   !> Highest polynomial degree of the filter.
   integer, parameter :: max_degree = 8
   !> Widest half-width k (window 2k + 1 samples).
   integer, parameter :: max_half_width = 2000
   !> Narrowest half-width the plug-in rule tries.
   integer, parameter :: min_half_width = 2

contains

   !> The weights (0:2, 2k + 1) of y, ẏ and ÿ at t(j) of a polynomial of degree p
   !> fitted to the samples lo .. lo + 2k of t (`window_start`): estimate_d = Σ w(d, i)
   !> y(lo + i − 1). Needs p + 1 <= 2k + 1 <= size(t).
   pure subroutine derivative_weights(t, j, k, p, lo, w)
      real(dp), intent(in) :: t(:)       !! sample times [s] (increasing)
      integer, intent(in) :: j, k, p     !! the sample, half-width, degree
      integer, intent(out) :: lo         !! first sample of the window
      real(dp), intent(out) :: w(0:, :)  !! (0:2, 2k + 1) weights
      real(dp) :: h
      integer :: d
      lo = window_start(size(t), j, k)
      h = max(abs(t(lo + 2*k) - t(j)), abs(t(lo) - t(j)))
      call coefficient_weights((t(lo:lo + 2*k) - t(j))/h, p, min(2, p), w)
      do d = 0, min(2, p)
         w(d, :) = w(d, :)*factorial(d)/h**d
      end do
      w(min(2, p) + 1:, :) = 0.0_dp
   end subroutine derivative_weights

   !> The weights (0:dmax, n) of the coefficients a_0 .. a_dmax of the least-squares
   !> polynomial Σ a_c s^c of degree p through (s_i, y_i): a_d = Σ w(d, i) y_i. By
   !> the QR factorisation of the Vandermonde matrix (Gram–Schmidt, each column twice
   !> orthogonalised): a = R⁻¹ Qᵀ y, so w(d, :) = Q z with Rᵀ z = e_d. Needs
   !> p + 1 <= n distinct s, scaled to about [−1, 1].
   pure subroutine coefficient_weights(s, p, dmax, w)
      real(dp), intent(in) :: s(:)       !! abscissae (n)
      integer, intent(in) :: p, dmax     !! degree, highest coefficient wanted
      real(dp), intent(out) :: w(0:, :)  !! (0:dmax, n)
      real(dp) :: q(size(s), p + 1), r(p + 1, p + 1), z(p + 1), x
      integer :: c, i, d, pass
      r = 0.0_dp
      do c = 1, p + 1
         q(:, c) = s**(c - 1)
         do pass = 1, 2
            do i = 1, c - 1
               x = dot_product(q(:, i), q(:, c))
               r(i, c) = r(i, c) + x
               q(:, c) = q(:, c) - x*q(:, i)
            end do
         end do
         r(c, c) = norm2(q(:, c))
         q(:, c) = q(:, c)/r(c, c)
      end do
      do d = 0, dmax
         z = 0.0_dp
         z(d + 1) = 1.0_dp
         do c = 1, p + 1
            z(c) = (z(c) - dot_product(r(1:c - 1, c), z(1:c - 1)))/r(c, c)
         end do
         w(d, :) = matmul(q, z)
      end do
   end subroutine coefficient_weights

   !> The first sample of the window of half-width k about sample j of n.
   pure integer function window_start(n, j, k) result(lo)
      integer, intent(in) :: n, j, k
      lo = min(max(j - k, 1), n - 2*k)
   end function window_start

   !> y, ẏ and ÿ of every column of y (m, n) at every sample: ys(0:2, m, n).
   pure subroutine smooth_derivatives(t, y, k, p, ys)
      real(dp), intent(in) :: t(:)              !! times (n) [s]
      real(dp), intent(in) :: y(:, :)           !! samples (m columns, n)
      integer, intent(in) :: k, p               !! half-width, degree
      real(dp), intent(out) :: ys(0:, :, :)     !! (0:2, m, n)
      real(dp) :: w(0:2, 2*k + 1)
      integer :: j, lo, d
      do j = 1, size(t)
         call derivative_weights(t, j, k, p, lo, w)
         do d = 0, 2
            ys(d, :, j) = matmul(y(:, lo:lo + 2*k), w(d, :))
         end do
      end do
   end subroutine smooth_derivatives

   !> The noise of one column from its fourth differences (see the module's notes);
   !> 0 with fewer than 5 samples.
   pure real(dp) function noise_sigma(y) result(sigma)
      real(dp), intent(in) :: y(:)
      real(dp), allocatable :: d4(:)
      integer :: n
      n = size(y)
      sigma = 0.0_dp
      if (n < 5) return
      d4 = abs(y(5:n) - 4*y(4:n - 1) + 6*y(3:n - 2) - 4*y(2:n - 3) + y(1:n - 4))
      sigma = 1.482602218505602_dp*median(d4)/sqrt(70.0_dp)
   end function noise_sigma

   !> The order m of the derivative that the bias of ÿ of degree p follows: p + 1,
   !> or p + 2 when p is even (a centred window's weights cancel the odd moment p + 1).
   pure integer function bias_order(p) result(m)
      integer, intent(in) :: p
      m = p + 1
      if (mod(p, 2) == 0) m = p + 2
   end function bias_order

   !> The noise factors (Σ w_d,i²)^(1/2) of y, ẏ, ÿ (d = 0, 1, 2) at the middle
   !> sample: white noise σ gives errors of standard deviation σ × factor(d).
   pure function noise_factors(t, k, p) result(f)
      real(dp), intent(in) :: t(:)
      integer, intent(in) :: k, p
      real(dp) :: f(0:2)
      real(dp) :: w(0:2, 2*k + 1)
      integer :: lo
      call derivative_weights(t, (size(t) + 1)/2, k, p, lo, w)
      f = norm2(w, dim=2)
   end function noise_factors

   !> The filter's error factors for ÿ at an interior sample j of t: noise factor
   !> (Σ w_2,i²)^(1/2) [1/s²] and bias factor |Σ w_2,i s_i^m| / m! [s^(m−2)].
   pure subroutine filter_error(t, j, k, p, noise, bias)
      real(dp), intent(in) :: t(:)
      integer, intent(in) :: j, k, p
      real(dp), intent(out) :: noise, bias
      real(dp) :: w(0:2, 2*k + 1)
      integer :: lo, m
      call derivative_weights(t, j, k, p, lo, w)
      m = bias_order(p)
      noise = norm2(w(2, :))
      bias = abs(sum(w(2, :)*(t(lo:lo + 2*k) - t(j))**m))/factorial(m)
   end subroutine filter_error

   !> The half-width of the plug-in rule (module's notes) for the columns y (m, n)
   !> with noise sigma (m), degree p: at least max(min_half_width, p/2 + 1), at most
   !> min(max_half_width, (n − 1)/2 − 1 over 2 for the pilot).
   pure integer function choose_half_width(t, y, sigma, p) result(k)
      real(dp), intent(in) :: t(:), y(:, :), sigma(:)
      integer, intent(in) :: p
      integer :: lower, upper, round, kk, mo, c, j
      real(dp) :: r(size(y, 1)), best, mse, noise, bias
      lower = max(min_half_width, p/2 + 1)
      upper = min(max_half_width, (size(t) - 1)/4)
      if (upper <= lower) then
         k = max(lower, min(upper, (size(t) - 1)/2))
         return
      end if
      mo = bias_order(p)
      j = (size(t) + 1)/2
      k = min(8, upper)
      do round = 1, 3
         ! the pilot: y^(m) of each column by degree m + 1 on the half-width 2k; its RMS
         r = pilot_rms(t, y, pilot_half_width(size(t), k, mo), mo)
         best = huge(1.0_dp)
         kk = lower
         do while (kk <= upper)
            call filter_error(t, j, kk, p, noise, bias)
            mse = 0.0_dp
            do c = 1, size(y, 1)
               mse = mse + (sigma(c)*noise)**2 + (r(c)*bias)**2
            end do
            if (mse < best) then
               best = mse
               k = kk
            end if
            kk = max(kk + 1, int(kk*1.15_dp))
         end do
      end do
   end function choose_half_width

   !> The RMS over the samples of y^(m) of each column, by a local polynomial of degree
   !> m + 1 on the half-width kp (every size(t)/200-th sample); 0 when the series is
   !> too short for it (2 kp + 1 < m + 2).
   pure function pilot_rms(t, y, kp, m) result(r)
      real(dp), intent(in) :: t(:), y(:, :)
      integer, intent(in) :: kp, m
      real(dp) :: r(size(y, 1))
      real(dp) :: w(0:m, 2*kp + 1), h, s2(size(y, 1))
      integer :: j, lo, c, n, stride, count
      n = 2*kp + 1
      r = 0.0_dp
      if (n < m + 2 .or. n > size(t)) return
      s2 = 0.0_dp
      count = 0
      stride = max(1, size(t)/200)   ! 200 samples of the series suffice for an RMS
      do j = 1, size(t), stride
         lo = window_start(size(t), j, kp)
         h = max(abs(t(lo + n - 1) - t(j)), abs(t(lo) - t(j)))
         call coefficient_weights((t(lo:lo + n - 1) - t(j))/h, m + 1, m, w)
         do c = 1, size(y, 1)
            ! (bounded: a hostile series of huge values at tiny steps stays finite)
            s2(c) = s2(c) + min(abs(dot_product(w(m, :), y(c, lo:lo + n - 1))*factorial(m)/ &
                                    h**m), 1e100_dp)**2
         end do
         count = count + 1
      end do
      r = sqrt(s2/max(count, 1))
   end function pilot_rms

   !> The predicted RMS errors of ÿ of each column at the half-width k and degree p:
   !> noise σ_c (Σ w_2,i²)^(1/2) and bias R_c |Σ w_2,i s_i^m| / m! at the middle
   !> sample, R_c the pilot RMS of y_c^(m) on the half-width 2k (module's notes).
   pure subroutine predicted_errors(t, y, sigma, k, p, noise, bias)
      real(dp), intent(in) :: t(:), y(:, :), sigma(:)
      integer, intent(in) :: k, p
      real(dp), allocatable, intent(out) :: noise(:), bias(:)
      real(dp) :: fn, fb
      integer :: mo
      mo = bias_order(p)
      call filter_error(t, (size(t) + 1)/2, k, p, fn, fb)
      noise = sigma*fn
      bias = pilot_rms(t, y, pilot_half_width(size(t), k, mo), mo)*fb
   end subroutine predicted_errors

   !> The pilot's half-width for the chosen k: 2k, at least enough samples for its
   !> degree m + 1, at most what the series holds.
   pure integer function pilot_half_width(n, k, m) result(kp)
      integer, intent(in) :: n, k, m
      kp = min(max(2*k, (m + 2)/2 + 1), (n - 1)/2)
   end function pilot_half_width

   pure real(dp) function factorial(n)
      integer, intent(in) :: n
      integer :: i
      factorial = 1.0_dp
      do i = 2, n
         factorial = factorial*i
      end do
   end function factorial

end module dpend_smoothing
