!> Fast chaos indicators of one orbit from its tangent dynamics: MEGNO, FLI,
!> SALI and GALI_k, for any model (`class(model_t)`) and any method (the
!> tangent vectors are carried by `dpend_tangent`, in the method's internal
!> variables: (q, q̇), or (q, p) for canonical methods).
!>
!> Deviation vectors. The k = 2n vectors start as an orthonormal set in general
!> position (`initial_vectors`).
!> After every accepted step each vector is divided by its length and the
!> logarithm of that length is added to its running log-norm L_i(t) = ln |δ_i(t)|:
!> the directions are never mixed (no orthogonalisation, unlike Benettin's
!> method in `dpend_lyapunov`), so the alignment that SALI and GALI measure is
!> kept, and the norms never overflow.
!>
!> The indicators (sampled every τ and at the end):
!>  * FLI(t) = max_i L_i(t), the fast Lyapunov indicator of Froeschlé, Lega and
!>    Gonczi (Celest. Mech. Dyn. Astron. 67, 41, 1997) over the orthonormal
!>    initial set: grows like ln t on regular orbits (|δ| ∝ t), like λ1 t on
!>    chaotic ones.
!>  * MEGNO (Cincotta & Simó, Astron. Astrophys. Suppl. 147, 205, 2000) of each
!>    vector, Y(t) = (2/t) ∫_0^t s δ̇·δ/(δ·δ) ds, and its running mean
!>    <Y>(t) = (1/t) ∫_0^t Y(s) ds. Discretisation: both integrals are summed
!>    step by step, as REBOUND accumulates them, but without evaluating δ̇: the
!>    integrand is δ̇·δ/δ·δ = d ln|δ|/ds, whose integral over a step [a, b] is
!>    known exactly from the renormalisation, ΔL = ln(|δ(b)|/|δ(a)|), so
!>    ∫_a^b (s - t0) dL is summed as ((a + b)/2 - t0) ΔL (midpoint weight: second
!>    order in the step, and exact for the growth within the step however fast
!>    it varies), and ∫ Y ds by the trapezoidal rule (Y(t0) = 0).
!>    Equivalently (integration by parts) Y(t) = 2 (L(t) - (1/t) ∫_0^t L(s) ds).
!>    Regular (quasi-periodic) orbits with shear (frequencies depending on the
!>    actions): Y oscillates about 2 and <Y> → 2; exponential growth e^(μt):
!>    Y → μ t, <Y> → μ t/2; chaotic orbits: <Y> ≈ λ1 t/2.
!>    (Isochronous oscillations, |δ| bounded: <Y> → 0.)
!>    `megno` and `megno_mean` report vector 1; all vectors are kept.
!>  * SALI (Skokos, J. Phys. A 34, 10029, 2001) of vectors 1 and 2:
!>    min(|v̂1 + v̂2|, |v̂1 - v̂2|), v̂ = v/|v|; → 0 as exp(-(λ1 - λ2) t) on chaotic
!>    orbits, stays away from 0 on regular ones.
!>  * GALI_j, j = 2 .. 2n (Skokos, Bountis & Antonopoulos, Physica D 231, 30,
!>    2007): the volume of the parallelepiped of the first j unit vectors, the
!>    product of the singular values of the 2n×j matrix (v̂_1 .. v̂_j), as
!>    |det R| of its QR decomposition (LAPACK dgeqrf). Regular orbits on an
!>    N-torus: GALI_j constant for j ≤ N, ∝ t^-2(j-N) beyond; chaotic:
!>    GALI_j ∝ exp(-Σ_{i≤j} (λ1 - λi) t). GALI_2 = SALI·√(1 - SALI²/4).
module dpend_indicators
   use dpend_kinds, only: dp, i8
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite, state_ok, &
                               stat_tangent_substeps
   use dpend_propagate, only: march_t, march_progress_t
   use dpend_tangent, only: tangent_t
   use dpend_indicator_math, only: gali, sali, initial_vectors, megno_step
   use dpend_lyapunov, only: next_multiple
   implicit none
   private
   public :: indicators_result_t, chaos_indicators, gali, sali, initial_vectors

   !> Time series of the indicators of one orbit.
   type :: indicators_result_t
      integer :: k = 0                          !! deviation vectors (2n)
      integer :: n = 0                          !! samples
      real(dp), allocatable :: t(:)             !! sample times (n) [s]
      real(dp), allocatable :: log_norm(:, :)   !! ln |δ_i(t)| (k, n) [1]
      real(dp), allocatable :: fli(:)           !! FLI = max_i ln |δ_i| (n) [1]
      real(dp), allocatable :: megno_all(:, :)  !! Y(t) of each vector (k, n) [1]
      real(dp), allocatable :: mean_all(:, :)   !! <Y>(t) of each vector (k, n) [1]
      real(dp), allocatable :: sali(:)          !! SALI of vectors 1, 2 (n) [1]
      real(dp), allocatable :: gali(:, :)       !! GALI_j, row j-1 for j = 2 .. k (k-1, n) [1]
      real(dp) :: t_reached = 0.0_dp            !! time reached [s]
      real(dp), allocatable :: y(:)             !! internal state reached
      integer(i8) :: n_sub = 0                  !! tangent substeps
   contains
      procedure :: megno => res_megno
      procedure :: megno_mean => res_megno_mean
   end type indicators_result_t

contains

   !> Y(t) of vector 1 (n).
   pure function res_megno(self) result(y)
      class(indicators_result_t), intent(in) :: self  !! the result
      real(dp) :: y(self%n)
      y = self%megno_all(1, 1:self%n)
   end function res_megno

   !> <Y>(t) of vector 1 (n).
   pure function res_megno_mean(self) result(y)
      class(indicators_result_t), intent(in) :: self  !! the result
      real(dp) :: y(self%n)
      y = self%mean_all(1, 1:self%n)
   end function res_megno_mean

   !> The indicators of the orbit from (t0, y0) to t_end, integrated with `integ`
   !> (fixed step or initial proposal h; rules of `march_t`), sampled at the end of
   !> the first step that reaches t0 + j τ, and at t_end (t0 itself is not
   !> sampled: FLI = 0, Y = <Y> = 0, SALI = √2, GALI_j = 1 there). On failure
   !> `stat` says why (a step failure, stat_tangent_substeps, or stat_nonfinite)
   !> and `res` holds the samples up to `res%t_reached`.
   subroutine chaos_indicators(integ, model, t0, y0, t_end, h, tau, res, stat, progress)
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model          !! the system
      real(dp), intent(in) :: t0                   !! start time [s]
      real(dp), intent(in) :: y0(:)                !! internal state at t0
      real(dp), intent(in) :: t_end                !! end time [s], > t0
      real(dp), intent(in) :: h                    !! step or initial proposal [s]
      real(dp), intent(in) :: tau                  !! sampling interval [s], > 0
      type(indicators_result_t), intent(out) :: res  !! the time series
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      !> the command's progress, which the march adds to
      type(march_progress_t), intent(inout), target, optional :: progress
      type(march_t) :: march
      type(tangent_t) :: tan
      real(dp) :: t, t_prev, y(size(y0)), hh, t_next, nrm
      real(dp), dimension(size(y0)) :: lg, dl, ig, yy, yy_prev, sy
      integer :: i, k, info
      integer(i8) :: j
      k = size(y0)
      call tan%init(initial_vectors(k))
      res%k = k
      allocate (res%t(256), res%log_norm(k, 256), res%fli(256), res%megno_all(k, 256), &
                res%mean_all(k, 256), res%sali(256), res%gali(k - 1, 256))
      t = t0; y = y0; hh = h
      lg = 0.0_dp       ! ln |δ_i|
      ig = 0.0_dp       ! ∫ (s - t0) δ̇·δ/δ·δ ds
      yy_prev = 0.0_dp  ! Y at the previous step end (0 at t0)
      sy = 0.0_dp       ! ∫ Y ds
      j = 1
      t_next = t0 + tau
      stat = stat_ok
      call integ%clear_step()
      if (present(progress)) march%progress => progress
      call march%start(integ, t, t_end, hh)
      do while (.not. march%finished)
         t_prev = t
         call march%next(integ, model, t, y, hh, stat)
         if (stat /= stat_ok) exit
         call tan%propagate(integ, model)
         if (tan%too_stiff) then
            stat = stat_tangent_substeps
            exit
         end if
         if (.not. all([(state_ok(k, tan%v(:, i)), i=1, k)])) then
            stat = stat_nonfinite
            exit
         end if
         if (t == t_prev) cycle
         ! renormalise: lengths to 1, directions kept; dl = ln of the growth over
         ! the step, the exact integral of δ̇·δ/δ·δ over it
         do i = 1, k
            nrm = norm2(tan%v(:, i))
            if (.not. (nrm > 0.0_dp)) then
               stat = stat_nonfinite
               exit
            end if
            tan%v(:, i) = tan%v(:, i)/nrm
            dl(i) = log(nrm)
         end do
         if (stat /= stat_ok) exit
         call megno_step(dl, t_prev, t, t0, lg, ig, yy_prev, sy)
         yy = yy_prev
         if (stat /= stat_ok) exit
         if (t >= t_next - 1e-9_dp*tau .or. march%finished) then
            call record(info)
            if (info /= 0) then
               stat = stat_nonfinite
               exit
            end if
            call next_multiple(t0, tau, t, j, t_next)
         end if
      end do
      res%t_reached = t
      if (res%n > 0) res%t_reached = res%t(res%n)
      res%y = y
      res%n_sub = tan%n_sub
      res%t = res%t(1:res%n)
      res%log_norm = res%log_norm(:, 1:res%n)
      res%fli = res%fli(1:res%n)
      res%megno_all = res%megno_all(:, 1:res%n)
      res%mean_all = res%mean_all(:, 1:res%n)
      res%sali = res%sali(1:res%n)
      res%gali = res%gali(:, 1:res%n)
   contains
      !> Append the sample at t (growing the arrays by doubling).
      subroutine record(info)
         integer, intent(out) :: info
         integer :: n, m
         info = 0
         n = res%n + 1
         if (n > size(res%t)) call grow(2*size(res%t))
         res%t(n) = t
         res%log_norm(:, n) = lg
         res%fli(n) = maxval(lg)
         res%megno_all(:, n) = yy
         res%mean_all(:, n) = sy/(t - t0)
         res%sali(n) = sali(tan%v(:, 1), tan%v(:, 2))
         do m = 2, k
            call gali(tan%v(:, 1:m), res%gali(m - 1, n), info)
            if (info /= 0) return
         end do
         res%n = n
      end subroutine record

      subroutine grow(cap)
         integer, intent(in) :: cap
         call grow1(res%t, cap); call grow1(res%fli, cap); call grow1(res%sali, cap)
         call grow2(res%log_norm, cap); call grow2(res%megno_all, cap)
         call grow2(res%mean_all, cap); call grow2(res%gali, cap)
      end subroutine grow
   end subroutine chaos_indicators

   !> Enlarge a (n) array to (cap), keeping its contents.
   subroutine grow1(a, cap)
      real(dp), allocatable, intent(inout) :: a(:)  !! the array
      integer, intent(in) :: cap                    !! new size, >= size(a)
      real(dp), allocatable :: b(:)
      allocate (b(cap))
      b(1:size(a)) = a
      call move_alloc(b, a)
   end subroutine grow1

   !> Enlarge a (m, n) array to (m, cap), keeping its contents.
   subroutine grow2(a, cap)
      real(dp), allocatable, intent(inout) :: a(:, :)  !! the array
      integer, intent(in) :: cap                       !! new column count, >= size(a, 2)
      real(dp), allocatable :: b(:, :)
      allocate (b(size(a, 1), cap))
      b(:, 1:size(a, 2)) = a
      call move_alloc(b, a)
   end subroutine grow2
end module dpend_indicators
