!> Lyapunov exponents by the method of Benettin, Galgani, Giorgilli and Strelcyn
!> (Meccanica 15, 9 and 21, 1980), as in Skokos, Lect. Notes Phys. 790 (2010) 63:
!> k tangent vectors are carried along the trajectory (`dpend_tangent`) and every
!> τ they are re-orthonormalised by a QR decomposition V = Q R (LAPACK dgeqrf and
!> dorgqr, R with a positive diagonal); V ← Q and the logarithms of R's diagonal
!> are summed. After a time t the i-th exponent is estimated by
!>   λ_i(t) = (1/t) Σ ln R_ii,
!> the "running estimate", recorded at every renormalisation so that its
!> convergence can be plotted. For k = 1 this is Benettin's largest exponent
!> (the vector is renormalised by its length); for k = 4 the whole spectrum.
!>
!> The accumulation (`renormalize`, `lyapunov_acc_t`) knows nothing of the
!> pendulum: it takes tangent matrices from any source, so that it can be tested
!> on a linear flow whose exponents are known (the real parts of the eigenvalues).
!> `lyapunov_spectrum` drives it along a pendulum trajectory with any method.
!>
!> Statistical spread. Successive renormalisation intervals are correlated, so
!> the spread is estimated by batch means: the run is cut into `n_batches` equal
!> time segments, the exponent of each segment is (ΔΣ ln R_ii)/Δt, and the
!> spread is the standard error of their mean, std/√n_batches.
module dpend_lyapunov
   use dpend_kinds, only: dp, i8
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite, state_ok, &
                               stat_tangent_substeps
   use dpend_propagate, only: march_t, march_progress_t
   use dpend_tangent, only: tangent_t
   use dpend_lapack, only: dgeqrf, dorgqr
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private
   public :: qr_positive, lyapunov_acc_t, renormalize, batch_exponents
   public :: lyapunov_result_t, lyapunov_spectrum, sort_descending, next_multiple

   !> Running sums of ln R_ii from time t0 and their history.
   type :: lyapunov_acc_t
      integer :: k = 0                       !! number of exponents
      real(dp) :: t0 = 0.0_dp                !! start time [s]
      real(dp) :: t = 0.0_dp                 !! time of the last renormalisation [s]
      real(dp), allocatable :: s(:)          !! Σ ln R_ii (k)
      integer :: n = 0                       !! renormalisations recorded
      real(dp), allocatable :: times(:)      !! their times (capacity ≥ n) [s]
      real(dp), allocatable :: sums(:, :)    !! Σ ln R_ii after each (k, capacity)
   contains
      procedure :: init => acc_init
      procedure :: add => acc_add
      procedure :: exponents => acc_exponents
      procedure :: running => acc_running
   end type lyapunov_acc_t

   !> Result of a Lyapunov run.
   type :: lyapunov_result_t
      integer :: k = 0                          !! exponents computed
      real(dp), allocatable :: exponents(:)     !! λ_i at the end (k) [1/s], descending
      real(dp), allocatable :: spread(:)        !! standard error from batch means (k) [1/s]
      real(dp), allocatable :: batches(:, :)    !! exponents of each batch (k, n_batches) [1/s]
      real(dp), allocatable :: t(:)             !! renormalisation times (n) [s]
      real(dp), allocatable :: running(:, :)    !! running estimates λ_i(t) (k, n) [1/s]
      real(dp) :: t_reached = 0.0_dp            !! time reached [s]
      real(dp), allocatable :: y(:)             !! internal state reached
      integer(i8) :: n_sub = 0                  !! tangent substeps
   end type lyapunov_result_t

contains

   !> QR decomposition V = Q R of V (m, k), k ≤ m, with R's diagonal positive:
   !> on return v holds Q (orthonormal columns) and r the k×k upper triangle.
   !> info /= 0: LAPACK failed (info < 0) or the columns are linearly dependent
   !> (a zero or non-finite diagonal element, info = k + 1).
   subroutine qr_positive(v, r, info)
      real(dp), intent(inout) :: v(:, :)  !! in: the vectors; out: Q
      real(dp), intent(out) :: r(:, :)    !! R (k, k), upper triangular, R_ii > 0
      integer, intent(out) :: info        !! 0 on success
      integer :: m, k, i, lwork
      real(dp) :: tau(size(v, 2)), work(64*size(v, 2))
      m = size(v, 1); k = size(v, 2)
      lwork = size(work)
      r = 0.0_dp
      call dgeqrf(m, k, v, m, tau, work, lwork, info)
      if (info /= 0) return
      do i = 1, k
         r(1:i, i) = v(1:i, i)
      end do
      call dorgqr(m, k, k, v, m, tau, work, lwork, info)
      if (info /= 0) return
      do i = 1, k
         if (.not. state_ok(1, [r(i, i)]) .or. r(i, i) == 0.0_dp) then
            info = k + 1
            return
         end if
         if (r(i, i) < 0.0_dp) then
            r(i, i:) = -r(i, i:)
            v(:, i) = -v(:, i)
         end if
      end do
   end subroutine qr_positive

   !> Start accumulating k exponents at time t0.
   subroutine acc_init(self, k, t0)
      class(lyapunov_acc_t), intent(inout) :: self  !! the accumulator
      integer, intent(in) :: k                      !! number of exponents
      real(dp), intent(in) :: t0                    !! start time [s]
      self%k = k
      self%t0 = t0
      self%t = t0
      self%n = 0
      if (allocated(self%s)) deallocate (self%s, self%times, self%sums)
      allocate (self%s(k), self%times(256), self%sums(k, 256))
      self%s = 0.0_dp
   end subroutine acc_init

   !> Add the diagonal of R of a renormalisation at time t and record it.
   subroutine acc_add(self, t, r_diag)
      class(lyapunov_acc_t), intent(inout) :: self  !! the accumulator
      real(dp), intent(in) :: t                     !! time of the renormalisation [s]
      real(dp), intent(in) :: r_diag(:)             !! R_ii > 0 (k)
      real(dp), allocatable :: tt(:), ss(:, :)
      self%s = self%s + log(r_diag)
      self%t = t
      if (self%n == size(self%times)) then
         allocate (tt(2*self%n), ss(self%k, 2*self%n))
         tt(1:self%n) = self%times; ss(:, 1:self%n) = self%sums
         call move_alloc(tt, self%times); call move_alloc(ss, self%sums)
      end if
      self%n = self%n + 1
      self%times(self%n) = t
      self%sums(:, self%n) = self%s
   end subroutine acc_add

   !> Current estimates λ_i = Σ ln R_ii / (t - t0) [1/s] (0 before any renormalisation).
   pure function acc_exponents(self) result(lam)
      class(lyapunov_acc_t), intent(in) :: self  !! the accumulator
      real(dp) :: lam(self%k)
      if (self%t == self%t0) then
         lam = 0.0_dp
      else
         lam = self%s/(self%t - self%t0)
      end if
   end function acc_exponents

   !> Running estimates after each recorded renormalisation (k, n) [1/s].
   pure function acc_running(self) result(run)
      class(lyapunov_acc_t), intent(in) :: self  !! the accumulator
      real(dp) :: run(self%k, self%n)
      integer :: j
      do j = 1, self%n
         run(:, j) = self%sums(:, j)/(self%times(j) - self%t0)
      end do
   end function acc_running

   !> One renormalisation: QR of the tangent vectors v (m, k) at time t, v ← Q,
   !> ln R_ii added to `acc`. info /= 0 as in `qr_positive` (nothing is added).
   subroutine renormalize(acc, v, t, info)
      type(lyapunov_acc_t), intent(inout) :: acc  !! the accumulator
      real(dp), intent(inout) :: v(:, :)          !! tangent vectors, then Q
      real(dp), intent(in) :: t                   !! time [s]
      integer, intent(out) :: info                !! 0 on success
      real(dp) :: r(size(v, 2), size(v, 2))
      integer :: i
      call qr_positive(v, r, info)
      if (info /= 0) return
      call acc%add(t, [(r(i, i), i=1, size(v, 2))])
   end subroutine renormalize

   !> Batch means of the recorded sums: [t0, t] cut into n_batches equal segments,
   !> each segment ending at the first renormalisation at or after its nominal
   !> end; its exponents are the increments of Σ ln R_ii over its duration.
   !> `spread` is the standard error std/√n_used (NaN with fewer than two
   !> batches; n_used is smaller than n_batches when renormalisations are fewer).
   subroutine batch_exponents(acc, n_batches, batches, spread)
      type(lyapunov_acc_t), intent(in) :: acc          !! the accumulator
      integer, intent(in) :: n_batches                 !! requested batches
      real(dp), allocatable, intent(out) :: batches(:, :) !! (k, n_used) [1/s]
      real(dp), intent(out) :: spread(:)               !! (k) [1/s]
      integer :: nb, b, j, j_prev
      real(dp) :: t_prev, s_prev(acc%k), t_b, mean(acc%k)
      nb = max(1, min(n_batches, acc%n))
      allocate (batches(acc%k, nb))
      if (acc%n == 0) then
         batches = 0.0_dp
         spread = ieee_value(1.0_dp, ieee_quiet_nan)
         return
      end if
      t_prev = acc%t0; s_prev = 0.0_dp; j_prev = 0
      j = 0
      do b = 1, nb
         t_b = acc%t0 + (acc%t - acc%t0)*real(b, dp)/real(nb, dp)
         if (b == nb) then
            j = acc%n
         else
            j = max(j_prev + 1, j)
            do while (j < acc%n - (nb - b) .and. acc%times(j) < t_b)
               j = j + 1
            end do
         end if
         batches(:, b) = (acc%sums(:, j) - s_prev)/(acc%times(j) - t_prev)
         t_prev = acc%times(j); s_prev = acc%sums(:, j); j_prev = j
      end do
      if (nb < 2) then
         spread = ieee_value(1.0_dp, ieee_quiet_nan)
         return
      end if
      mean = sum(batches, dim=2)/real(nb, dp)
      do j = 1, acc%k
         spread(j) = sqrt(sum((batches(j, :) - mean(j))**2)/real(nb - 1, dp)/real(nb, dp))
      end do
   end subroutine batch_exponents

   !> The k largest Lyapunov exponents of the trajectory from (t0, y0) to t_end,
   !> integrated with `integ` (fixed step or initial proposal h; rules of
   !> `march_t`). The tangent vectors start as the first k unit vectors of the
   !> method's internal variables and are renormalised at the end of the first
   !> step that reaches t0 + j τ, and at t_end. On failure `stat` says why
   !> (a step failure, or stat_nonfinite for non-finite tangent vectors) and
   !> `res` holds what was computed up to `res%t_reached`.
   subroutine lyapunov_spectrum(integ, model, t0, y0, t_end, h, tau, k, n_batches, res, stat, &
                                progress)
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t0                   !! start time [s]
      real(dp), intent(in) :: y0(:)                !! internal state at t0
      real(dp), intent(in) :: t_end                !! end time [s], > t0
      real(dp), intent(in) :: h                    !! step or initial proposal [s]
      real(dp), intent(in) :: tau                  !! renormalisation interval [s], > 0
      integer, intent(in) :: k                     !! exponents wanted, 1 to 2n
      integer, intent(in) :: n_batches             !! batches for the spread
      type(lyapunov_result_t), intent(out) :: res  !! exponents and running estimates
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      !> the command's progress, which the march adds to
      type(march_progress_t), intent(inout), target, optional :: progress
      type(march_t) :: march
      type(tangent_t) :: tan
      type(lyapunov_acc_t) :: acc
      real(dp) :: t, y(size(y0)), hh, eye(size(y0), size(y0)), t_next
      integer :: i, info
      integer(i8) :: j
      eye = 0.0_dp
      do i = 1, size(y0)
         eye(i, i) = 1.0_dp
      end do
      call tan%init(eye(:, 1:k))
      call acc%init(k, t0)
      t = t0; y = y0; hh = h
      j = 1
      t_next = t0 + tau
      stat = stat_ok
      call integ%clear_step()
      if (present(progress)) march%progress => progress
      call march%start(integ, t, t_end, hh)
      do while (.not. march%finished)
         call march%next(integ, model, t, y, hh, stat)
         if (stat /= stat_ok) exit
         call tan%propagate(integ, model)
         if (tan%too_stiff) then
            stat = stat_tangent_substeps
            exit
         end if
         if (.not. all([(state_ok(size(tan%v, 1), tan%v(:, i)), i=1, k)])) then
            stat = stat_nonfinite
            exit
         end if
         if (t >= t_next - 1e-9_dp*tau .or. march%finished) then
            call renormalize(acc, tan%v, t, info)
            if (info /= 0) then
               stat = stat_nonfinite
               exit
            end if
            call next_multiple(t0, tau, t, j, t_next)
         end if
      end do
      res%k = k
      res%exponents = acc%exponents()
      res%t = acc%times(1:acc%n)
      res%running = acc%running()
      res%t_reached = acc%t
      res%y = y
      res%n_sub = tan%n_sub
      allocate (res%spread(k))
      call batch_exponents(acc, n_batches, res%batches, res%spread)
      call sort_descending(res)
   end subroutine lyapunov_spectrum

   !> After a renormalisation (or sample) at t: t_next = t0 + j τ, the next multiple
   !> of τ after t (j updated), unless t_next is already after t. Found directly: a
   !> step may span many intervals (τ < step of an adaptive method), counting them
   !> one by one would not end (j fits: t_end/τ <= max_samples is validated).
   pure subroutine next_multiple(t0, tau, t, j, t_next)
      real(dp), intent(in) :: t0             !! start time [s]
      real(dp), intent(in) :: tau            !! interval [s], > 0
      real(dp), intent(in) :: t              !! time reached [s]
      integer(i8), intent(inout) :: j        !! index of t_next
      real(dp), intent(inout) :: t_next      !! next scheduled time [s]
      if (t_next <= t + 1e-9_dp*tau) then
         j = max(j + 1, int((t - t0)/tau, i8))
         t_next = t0 + real(j, dp)*tau
         do while (t_next <= t + 1e-9_dp*tau)
            j = j + 1
            t_next = t0 + real(j, dp)*tau
         end do
      end if
   end subroutine next_multiple

   !> Order the exponents descending, as documented, permuting their spreads, batch
   !> exponents and running estimates alike. The QR order is descending only in the
   !> limit; over a finite time two close exponents (e.g. the pair near zero) can
   !> come out swapped. Stable insertion sort (k <= 4); NaN stays in place.
   subroutine sort_descending(res)
      type(lyapunov_result_t), intent(inout) :: res  !! result to reorder
      integer :: perm(res%k), i, j, p
      perm = [(i, i=1, res%k)]
      do i = 2, res%k
         p = perm(i)
         j = i - 1
         do while (j >= 1)
            if (.not. (res%exponents(perm(j)) < res%exponents(p))) exit
            perm(j + 1) = perm(j)
            j = j - 1
         end do
         perm(j + 1) = p
      end do
      if (all(perm == [(i, i=1, res%k)])) return
      res%exponents = res%exponents(perm)
      if (allocated(res%spread)) res%spread = res%spread(perm)
      if (allocated(res%batches)) res%batches = res%batches(perm, :)
      if (allocated(res%running)) res%running = res%running(perm, :)
   end subroutine sort_descending
end module dpend_lyapunov
