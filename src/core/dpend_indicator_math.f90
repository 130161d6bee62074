!> The formulas of the fast chaos indicators, in one place for every path that
!> computes them: `dpend_indicators` (one orbit, any model, 2n vectors) and the
!> sweep's batch kernel (`dpend_pendulum_lanes`, one or two vectors per lane). The
!> definitions and references are in dpend_indicators' header.
!>
!> Deviation vectors are renormalised to length 1 after every step (the two-link
!> batch kernel rescales them by a power of two instead, exactly, and carries
!> ln |δ|), the logarithm of the growth dl = ln(|δ(b)|/|δ(a)|) over the step [a, b]
!> entering `megno_step`.
module dpend_indicator_math
   use dpend_kinds, only: dp
   use dpend_lapack, only: dgeqrf
   implicit none
   private
   public :: initial_vectors, sali, gali, megno_step

contains

   !> One step [t_prev, t] of the running sums of one deviation vector, elemental
   !> over vectors or lanes: the log-norm lg = ln |δ| (FLI), the MEGNO integral
   !> ig = ∫ (s - t0) δ̇·δ/(δ·δ) ds (midpoint weight times dl, exact for the growth
   !> within the step), Y(t) = 2 ig/(t - t0), and sy = ∫ Y ds by the trapezoidal
   !> rule; on entry yy is Y(t_prev) (0 at t0), on return Y(t). <Y>(t) = sy/(t - t0).
   pure elemental subroutine megno_step(dl, t_prev, t, t0, lg, ig, yy, sy)
      real(dp), intent(in) :: dl          !! ln of the growth of |δ| over the step
      real(dp), intent(in) :: t_prev, t   !! step start and end [s], t > t0
      real(dp), intent(in) :: t0          !! start of the orbit [s]
      real(dp), intent(inout) :: lg       !! ln |δ(t)| [1]
      real(dp), intent(inout) :: ig       !! ∫ (s - t0) d ln|δ| [s]
      real(dp), intent(inout) :: yy       !! Y(t_prev) in, Y(t) out [1]
      real(dp), intent(inout) :: sy       !! ∫ Y ds [s]
      real(dp) :: y_new
      lg = lg + dl
      ig = ig + (0.5_dp*((t_prev - t0) + (t - t0)))*dl
      y_new = 2.0_dp*ig/(t - t0)
      sy = sy + 0.5_dp*(t - t_prev)*(yy + y_new)
      yy = y_new
   end subroutine megno_step

   !> SALI of two vectors: min(|â + b̂|, |â - b̂|), â = a/|a|.
   pure real(dp) function sali(a, b)
      real(dp), intent(in) :: a(:), b(:)  !! the vectors, not zero
      real(dp) :: ah(size(a)), bh(size(b))
      ah = a/norm2(a); bh = b/norm2(b)
      sali = min(norm2(ah + bh), norm2(ah - bh))
   end function sali

   !> GALI_j of the columns of v (m, j), j <= m: the volume of the parallelepiped of
   !> the unit vectors v_i/|v_i|, i.e. the product of the singular values of their
   !> matrix A, computed as |det R| = Π |R_ii| of its QR decomposition A = Q R
   !> (LAPACK dgeqrf; AᵀA = RᵀR, so both are √det(AᵀA)). info /= 0: dgeqrf failed.
   !> (dgesvd would give the same product, but the reference LAPACK's SVD raises
   !> IEEE exceptions internally, which the debug build traps.)
   subroutine gali(v, g, info)
      real(dp), intent(in) :: v(:, :)  !! the vectors (m, j), not zero
      real(dp), intent(out) :: g       !! GALI_j [1]
      integer, intent(out) :: info     !! 0 on success
      real(dp) :: a(size(v, 1), size(v, 2)), tau(size(v, 2)), work(64*size(v, 2))
      integer :: m, j, i
      m = size(v, 1); j = size(v, 2)
      do i = 1, j
         a(:, i) = v(:, i)/norm2(v(:, i))
      end do
      call dgeqrf(m, j, a, m, tau, work, size(work), info)
      g = 1.0_dp
      do i = 1, j
         g = g*abs(a(i, i))
      end do
   end subroutine gali

   !> The initial deviation vectors: the columns of the Householder reflection
   !> H = I - 2 w wᵀ/(wᵀw), w_i = 1 + i φ (φ the golden ratio), an orthonormal set
   !> in general position. The unit vectors e_i would not do: at a turning point
   !> (all q̇ = 0, as in the releases from rest) a velocity perturbation leaves the
   !> energy and, by time-reversal symmetry, the actions unchanged to first order,
   !> so e_(n+1) .. e_2n lie in the tangent space of the torus, never grow, and
   !> GALI_j of a regular orbit would decay as t^-(j-N) instead of t^-2(j-N).
   pure function initial_vectors(k) result(v)
      integer, intent(in) :: k  !! dimension of the state (2n)
      real(dp) :: v(k, k)
      real(dp) :: w(k)
      integer :: i
      w = [(1.0_dp + real(i, dp)*0.5_dp*(1.0_dp + sqrt(5.0_dp)), i=1, k)]
      do i = 1, k
         v(:, i) = -2.0_dp*w(i)/dot_product(w, w)*w
         v(i, i) = v(i, i) + 1.0_dp
      end do
   end function initial_vectors
end module dpend_indicator_math
