!> Identification of a chain's inertial and friction parameters from its motion and
!> joint torques: the dynamics is linear in the standard parameters of each link i,
!>   J_i  inertia about joint i [kg m²] (I_Ci + m_i d_i²),
!>   h_i  first moment m_i d_i [kg m],
!>   m_i  mass [kg],
!>   c_i  viscous friction [N m s],  cf_i  Coulomb friction [N m] (tanh(ω_i/v_s), v_s known),
!>   Im_i the motor's reflected rotor inertia g_r,i² I_r,i [kg m²] (on ω̇_i at joint i only),
!> with the lengths L_i, g and the support's motion known. Newton–Euler written in
!> them (`parameter_torques`; about joint i, which accelerates with a_Ai):
!>   F_i = F_(i+1) + m_i (a_Ai + g ĵ) + h_i (q̈_i n_i − q̇_i² u_i),
!>   s_i = s_(i+1) + J_i q̈_i + h_i (u_i × a_Ai + g cos q_i) + L_i u_i × F_(i+1),
!>   τ_i = s_i + c_i ω_i + cf_i tanh(ω_i/v_s) + Im_i (q̈_i − q̈_(i−1)),
!> so τ = Y(q, q̇, q̈) θ, and column j of the regressor Y is τ(θ = e_j) (`regressor`).
!>
!> Not every standard parameter shows in the torques: m_1 never does, and m_(i+1)
!> only through J_i + L_i² Σ_(k>i) m_k and h_i + L_i Σ_(k>i) m_k; Im_1 only through J_1 + Im_1
!> (joint 1's relative rate is q̇_1). The base parameters
!> are found numerically, not assumed: the regressor of 64 generic states (angles,
!> rates, accelerations spread over their ranges) has the structural rank; its
!> columns are taken in the order J_1 h_1 c_1 cf_1 Im_1 J_2 … m_1 … m_N and each kept
!> when it is not (to 1e-8 of its norm) a combination of those kept before
!> (`base_parameters`); a dropped column j is Σ_k β_kj (kept column k), which makes
!> base parameter k = θ_k + Σ_j β_kj θ_j (named so in words: 'J1 + 0.64 m2').
!>
!> Then the data (`identify_parameters`): the base regressor of the samples, its
!> columns scaled to unit norm, and its singular values (`jacobi_svd`): a direction
!> the motion does not excite (σ_min < 1e-6 σ_max) is refused naming the combination
!> (the right singular vector in physical units). The estimate is weighted least
!> squares (QR): a first fit gives each joint's residual scatter σ_i, the second
!> weighs joint i's rows by 1/σ_i; covariance s² (WᵀW)⁻¹ with s² the weighted
!> residual variance, 95 % intervals with Student's t of M − P degrees of freedom.
module dpend_identify
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_chain, only: chain_t
   use dpend_least_squares, only: jacobi_svd, qr_least_squares, r_inverse
   use dpend_estimate_statistics, only: student_t95
   use dpend_strings, only: real_str, to_str
   implicit none
   private
   public :: n_kinds, kind_names, kind_units, parameter_torques, regressor, base_t, &
      base_parameters, identify_result_t, identify_parameters, standard_values, &
      separable_tolerance, physical_parameters, parameter_label

   !> Standard parameters per link, in this order in θ (6, N).
   integer, parameter :: n_kinds = 6
   character(len=2), parameter :: kind_names(n_kinds) = ['J ', 'h ', 'm ', 'c ', 'cf', 'Im']
   character(len=6), parameter :: kind_units(n_kinds) = ['kg m^2', 'kg m  ', 'kg    ', &
                                                         'N m s ', 'N m   ', 'kg m^2']
   !> A base direction whose scaled singular value is below this fraction of the
   !> largest is not separated by the data.
   real(dp), parameter :: separable_tolerance = 1e-6_dp

   !> The base parameters: which standard parameters are kept, and how the others
   !> fold into them.
   type :: base_t
      integer, allocatable :: kept(:)          !! columns of θ (flattened, 6N) kept
      integer, allocatable :: dropped(:)       !! the others, in the base order
      real(dp), allocatable :: beta(:, :)      !! (kept, dropped): Y_dropped = Y_kept β
      logical, allocatable :: absent(:)        !! (dropped) the column is zero
      character(len=:), allocatable :: names(:)  !! each base parameter in words
      character(len=:), allocatable :: units(:)  !! its unit
   end type base_t

   !> What the identification found.
   type :: identify_result_t
      type(base_t) :: base
      real(dp), allocatable :: estimate(:)        !! base parameters (P)
      real(dp), allocatable :: std_error(:)       !! their standard errors (P)
      real(dp), allocatable :: interval95(:, :)   !! (2, P)
      real(dp), allocatable :: covariance(:, :)   !! (P, P)
      real(dp), allocatable :: singular(:)        !! of the scaled base regressor
      real(dp) :: condition = 0.0_dp              !! σ_max/σ_min
      !> residual scatter per joint [N m] (the weights 1/σ_i are the first fit's)
      real(dp), allocatable :: sigma_joint(:)
      real(dp), allocatable :: rms_residual(:)    !! RMS torque residual per joint
      real(dp), allocatable :: residual(:, :)     !! (N, rows) measured − model
      real(dp) :: t95 = 0.0_dp                    !! Student t quantile used
      integer :: rows = 0                         !! samples used
      !> the estimate was compensated for the filter's noise in the regressor
      logical :: compensated = .false.
   end type identify_result_t

contains

   !> θ (6, N) of a chain_t: J = I_C + m d², h = m d, m, c, cf, Im = g_r² I_r.
   pure function standard_values(chain) result(theta)
      type(chain_t), intent(in) :: chain
      real(dp) :: theta(n_kinds, chain%n)
      integer :: i
      do i = 1, chain%n
         theta(:, i) = [chain%ic(i) + chain%m(i)*chain%d(i)**2, chain%m(i)*chain%d(i), &
                        chain%m(i), 0.0_dp, 0.0_dp, 0.0_dp]
         if (chain%damped) theta(4, i) = chain%c(i)
         if (chain%coulomb) theta(5, i) = chain%cf(i)
         if (chain%motors) theta(6, i) = chain%im(i)
      end do
   end function standard_values

   !> The joint torques τ (N) of the motion (q, q̇, q̈) at t for the standard
   !> parameters θ (6, N), any values (module's notes); the chain gives L_i, g, v_s
   !> and the support's motion.
   pure subroutine parameter_torques(chain, t, q, qd, qdd, theta, tau)
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: t, q(:), qd(:), qdd(:), theta(:, :)
      real(dp), intent(out) :: tau(:)
      real(dp) :: aa(2, size(q)), u(2), nv(2), f(2), f_next(2), s, s_next, ra(2), va(2), w
      integer :: i, n
      n = size(q)
      ra = 0.0_dp; va = 0.0_dp; aa(:, 1) = 0.0_dp
      if (chain%driven) call chain%support(t, ra, va, aa(:, 1))
      do i = 1, n - 1
         u = [cos(q(i)), sin(q(i))]
         nv = [-u(2), u(1)]
         aa(:, i + 1) = aa(:, i) + chain%l(i)*(qdd(i)*nv - qd(i)**2*u)
      end do
      f_next = 0.0_dp
      s_next = 0.0_dp
      do i = n, 1, -1
         u = [cos(q(i)), sin(q(i))]
         nv = [-u(2), u(1)]
         f = f_next + theta(3, i)*(aa(:, i) + [0.0_dp, chain%g]) + &
             theta(2, i)*(qdd(i)*nv - qd(i)**2*u)
         s = s_next + theta(1, i)*qdd(i) + &
             theta(2, i)*(u(1)*aa(2, i) - u(2)*aa(1, i) + chain%g*u(1)) + &
             chain%l(i)*(u(1)*f_next(2) - u(2)*f_next(1))
         w = qd(i)
         if (i > 1) w = w - qd(i - 1)
         tau(i) = s + theta(4, i)*w + theta(5, i)*tanh(w/chain%vs) + theta(6, i)*qdd(i)
         if (i > 1) tau(i) = tau(i) - theta(6, i)*qdd(i - 1)
         f_next = f
         s_next = s
      end do
   end subroutine parameter_torques

   !> The regressor Y (N, 6N) at one sample: τ = Y θ with θ flattened (6, N).
   pure subroutine regressor(chain, t, q, qd, qdd, y)
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: t, q(:), qd(:), qdd(:)
      real(dp), intent(out) :: y(:, :)
      real(dp) :: theta(n_kinds*size(q))
      integer :: j
      do j = 1, n_kinds*size(q)
         theta = 0.0_dp
         theta(j) = 1.0_dp
         call parameter_torques(chain, t, q, qd, qdd, reshape(theta, [n_kinds, size(q)]), &
                                y(:, j))
      end do
   end subroutine regressor

   !> The base parameters of the columns `free` (flattened θ) of the chain's regressor,
   !> from 64 generic states (module's notes).
   subroutine base_parameters(chain, free, base)
      type(chain_t), intent(in) :: chain
      logical, intent(in) :: free(:)          !! (6N) the parameters identified
      type(base_t), intent(out) :: base
      integer :: n, np, k, j, c, i, order(size(free)), nk
      real(dp), allocatable :: y(:, :), w(:, :), kept_cols(:, :), x(:), r(:, :)
      real(dp) :: s, q(chain%n), qd(chain%n), qdd(chain%n), norm_j, resid
      logical :: ok
      n = chain%n
      np = n_kinds*n
      allocate (y(64*n, np), w(n, np))
      s = 0.377_dp
      do k = 1, 64   ! generic states: a fixed pseudo-random sequence
         do i = 1, n
            q(i) = 2*pi*next() - pi
            qd(i) = 10*next() - 5
            qdd(i) = 40*next() - 20
         end do
         call regressor(chain, 0.37_dp*k, q, qd, qdd, w)
         y((k - 1)*n + 1:k*n, :) = w
      end do
      ! the preferred order: J h c cf Im of each link, then the masses
      nk = 0
      do i = 1, n
         do c = 1, n_kinds
            if (c == 3) cycle
            nk = nk + 1
            order(nk) = (i - 1)*n_kinds + c
         end do
      end do
      do i = 1, n
         nk = nk + 1
         order(nk) = (i - 1)*n_kinds + 3
      end do
      allocate (base%kept(0), base%dropped(0))
      allocate (kept_cols(size(y, 1), 0))
      do k = 1, np
         j = order(k)
         if (.not. free(j)) cycle
         norm_j = norm2(y(:, j))
         resid = 0.0_dp
         if (size(base%kept) > 0 .and. norm_j > 0.0_dp) then
            allocate (x(size(base%kept)), r(size(base%kept), size(base%kept)))
            call qr_least_squares(kept_cols, y(:, j), x, r, ok)
            resid = norm2(y(:, j) - matmul(kept_cols, x))
            deallocate (x, r)
         else
            resid = norm_j
         end if
         if (norm_j > 0.0_dp .and. resid > 1e-8_dp*norm_j) then
            base%kept = [base%kept, j]
            kept_cols = reshape([kept_cols, y(:, j)], [size(y, 1), size(base%kept)])
         else
            base%dropped = [base%dropped, j]
         end if
      end do
      allocate (base%beta(size(base%kept), size(base%dropped)), &
                base%absent(size(base%dropped)))
      allocate (x(size(base%kept)), r(size(base%kept), size(base%kept)))
      do k = 1, size(base%dropped)
         j = base%dropped(k)
         base%absent(k) = norm2(y(:, j)) <= 1e-12_dp*maxval(norm2(y, dim=1))
         base%beta(:, k) = 0.0_dp
         if (base%absent(k)) cycle
         call qr_least_squares(kept_cols, y(:, j), x, r, ok)
         where (abs(x) > 1e-10_dp) base%beta(:, k) = x
      end do
      call name_base(n, base)
   contains
      real(dp) function next()
         s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
         next = s
      end function next
   end subroutine base_parameters

   !> Each base parameter in words: 'J1 + 0.64 m2', and its unit.
   subroutine name_base(n, base)
      integer, intent(in) :: n
      type(base_t), intent(inout) :: base
      character(len=200) :: names(size(base%kept)), units(size(base%kept))
      character(len=:), allocatable :: t
      integer :: k, j
      real(dp) :: b
      if (n < 1) return
      do k = 1, size(base%kept)
         t = label(base%kept(k))
         do j = 1, size(base%dropped)
            b = base%beta(k, j)
            if (b == 0.0_dp) cycle
            t = t//merge(' + ', ' - ', b > 0.0_dp)
            if (abs(abs(b) - 1.0_dp) > 1e-12_dp) t = t//real_str(abs(b), 6)//' '
            t = t//label(base%dropped(j))
         end do
         names(k) = t
         units(k) = trim(kind_units(kind_of(base%kept(k))))
      end do
      base%names = names
      base%units = units
   end subroutine name_base

   !> 'J1', 'cf2', … of flattened θ index j.
   pure function label(j) result(s)
      integer, intent(in) :: j
      character(len=:), allocatable :: s
      s = trim(kind_names(kind_of(j)))//to_str((j - 1)/n_kinds + 1)
   end function label

   pure integer function kind_of(j)
      integer, intent(in) :: j
      kind_of = mod(j - 1, n_kinds) + 1
   end function kind_of

   !> The estimate of the base parameters from the samples (t, q, q̇, q̈ of the filter,
   !> the measured torques) with the parameters not identified fixed at theta_fixed.
   !> A direction the data do not separate is refused naming it.
   subroutine identify_parameters(chain, base, t, q, qd, qdd, tau, theta_fixed, res, error, &
                                  noise_var)
      type(chain_t), intent(in) :: chain
      type(base_t), intent(in) :: base
      real(dp), intent(in) :: t(:), q(:, :), qd(:, :), qdd(:, :), tau(:, :)
      real(dp), intent(in) :: theta_fixed(:)        !! (6N) values of the fixed ones
      type(identify_result_t), intent(out) :: res
      type(error_t), allocatable, intent(out) :: error
      !> (2, N): the variances of the errors of q̇_i and q̈_i (the filter's): the
      !> estimate is then compensated for the noise they put into the regressor
      real(dp), intent(in), optional :: noise_var(:, :)
      real(dp), allocatable :: w(:, :), b(:), scale(:), ws(:, :), v(:, :), &
                               x(:), r(:, :), ri(:, :), wt(:), known(:)
      real(dp) :: y1(size(q, 1), n_kinds*size(q, 1)), s2
      integer :: n, k, m, np, j, i, pass
      logical :: ok
      logical, allocatable :: fixed(:)
      character(len=:), allocatable :: weak
      n = size(q, 1)
      k = size(t)
      m = n*k
      np = size(base%kept)
      res%base = base
      res%rows = k
      allocate (w(m, np), b(m), known(n))
      allocate (fixed(n_kinds*n))
      fixed = .true.
      fixed(base%kept) = .false.
      fixed(base%dropped) = .false.
      do j = 1, k
         call regressor(chain, t(j), q(:, j), qd(:, j), qdd(:, j), y1)
         w((j - 1)*n + 1:j*n, :) = y1(:, base%kept)
         known = matmul(y1, merge(theta_fixed, 0.0_dp, fixed))
         b((j - 1)*n + 1:j*n) = tau(:, j) - known
      end do
      allocate (scale(np))
      do i = 1, np
         scale(i) = norm2(w(:, i))
         if (scale(i) == 0.0_dp) scale(i) = 1.0_dp
      end do
      ws = w
      do i = 1, np
         ws(:, i) = ws(:, i)/scale(i)
      end do
      call jacobi_svd(ws, res%singular, v)
      if (np > 0) then
         res%condition = huge(1.0_dp)
         if (res%singular(np) > 0.0_dp) res%condition = res%singular(1)/res%singular(np)
         if (.not. (res%singular(np) >= separable_tolerance*res%singular(1))) then
            weak = ''
            do i = np, 1, -1
               if (res%singular(i) >= separable_tolerance*res%singular(1)) exit
               if (len(weak) > 0) weak = weak//'; '
               weak = weak//direction_text(base, v(:, i)/scale)//' changes them by '// &
                      real_str(res%singular(i)/res%singular(1), 2)
            end do
            call fatal_error(error, 'the motion does not separate the parameters (a ' &
                             //'direction that changes the torques by less than '// &
                             real_str(separable_tolerance)//' of the largest): '//weak// &
                             ' (excite the joints more variedly, or fix a parameter: ' &
                             //'--friction)')
            return
         end if
      end if
      allocate (x(np), r(np, np), wt(m), res%residual(n, k), res%sigma_joint(n), &
                res%rms_residual(n))
      wt = 1.0_dp
      do pass = 1, 2   ! unweighted, then each joint weighted by 1/σ_i of the first
         do i = 1, np
            ws(:, i) = w(:, i)*wt/scale(i)
         end do
         call qr_least_squares(ws, b*wt, x, r, ok)
         if (.not. ok) then
            call fatal_error(error, 'the motion does not separate the parameters (the ' &
                             //'base regressor is rank deficient)')
            return
         end if
         if (pass == 2) exit
         res%residual = reshape(b - matmul(w, x/scale), [n, k])
         call joint_scatter(res%residual, np, res%sigma_joint)
         do j = 1, k
            wt((j - 1)*n + 1:j*n) = 1.0_dp/res%sigma_joint
         end do
      end do
      res%estimate = x/scale
      ri = r_inverse(r)
      res%covariance = matmul(ri, transpose(ri))   ! (W_sᵀ W_s)⁻¹, scaled columns
      if (present(noise_var)) then
         call compensate(chain, base, t, q, qd, qdd, noise_var, w, b, wt, scale, res)
      end if
      res%residual = reshape(b - matmul(w, res%estimate), [n, k])
      res%rms_residual = sqrt(sum(res%residual**2, dim=2)/k)
      call joint_scatter(res%residual, np, res%sigma_joint)
      s2 = sum((b - matmul(w, res%estimate))**2*wt**2)/max(m - np, 1)
      res%covariance = s2*res%covariance
      do i = 1, np
         res%covariance(i, :) = res%covariance(i, :)/scale(i)
         res%covariance(:, i) = res%covariance(:, i)/scale(i)
      end do
      res%std_error = [(sqrt(max(res%covariance(i, i), 0.0_dp)), i = 1, np)]
      res%t95 = student_t95(max(m - np, 1))
      allocate (res%interval95(2, np))
      res%interval95(1, :) = res%estimate - res%t95*res%std_error
      res%interval95(2, :) = res%estimate + res%t95*res%std_error
   end subroutine identify_parameters

   !> The standard parameters θ (6, N) that the base estimate gives once the masses
   !> are known: θ_k = base_k − Σ_j β_kj m_j for a kept k whose dropped partners are all
   !> masses (`found` true), with its standard error (the masses exact).
   pure subroutine physical_parameters(base, estimate, std_error, masses, theta, se, found)
      type(base_t), intent(in) :: base
      real(dp), intent(in) :: estimate(:), std_error(:)   !! base parameters (P)
      real(dp), intent(in) :: masses(:)                   !! m_i [kg] (N)
      real(dp), intent(out) :: theta(:, :), se(:, :)      !! (6, N)
      logical, intent(out) :: found(:, :)                 !! (6, N)
      integer :: k, j, jj
      logical :: ok
      real(dp) :: x
      theta = 0.0_dp
      se = 0.0_dp
      found = .false.
      do k = 1, size(base%kept)
         x = estimate(k)
         ok = .true.
         do j = 1, size(base%dropped)
            if (base%beta(k, j) == 0.0_dp) cycle
            jj = base%dropped(j)
            if (kind_of(jj) /= 3) then
               ok = .false.
            else
               x = x - base%beta(k, j)*masses((jj - 1)/n_kinds + 1)
            end if
         end do
         if (.not. ok) cycle
         jj = base%kept(k)
         theta(kind_of(jj), (jj - 1)/n_kinds + 1) = x
         se(kind_of(jj), (jj - 1)/n_kinds + 1) = std_error(k)
         found(kind_of(jj), (jj - 1)/n_kinds + 1) = .true.
      end do
      do j = 1, size(masses)   ! the masses themselves: given
         theta(3, j) = masses(j)
         found(3, j) = .true.
      end do
   end subroutine physical_parameters

   !> The name of standard parameter (kind c, link i): 'J1', 'cf2'.
   pure function parameter_label(c, i) result(s)
      integer, intent(in) :: c, i
      character(len=:), allocatable :: s
      s = label((i - 1)*n_kinds + c)
   end function parameter_label

   !> The residual scatter of each joint, (Σ r_i² / (K − P/N))^(1/2) (1 where 0).
   pure subroutine joint_scatter(residual, np, sigma)
      real(dp), intent(in) :: residual(:, :)   !! (N, K)
      integer, intent(in) :: np                !! parameters estimated
      real(dp), intent(out) :: sigma(:)        !! (N)
      integer :: i
      do i = 1, size(residual, 1)
         sigma(i) = sqrt(sum(residual(i, :)**2)/max(size(residual, 2) - &
                                                    real(np, dp)/size(residual, 1), 1.0_dp))
         if (.not. (sigma(i) > 0.0_dp)) sigma(i) = 1.0_dp
      end do
   end subroutine joint_scatter

   !> Bias-compensated least squares (errors in the regressor): the filter's errors
   !> δq̇, δq̈ put E[δYᵀ D² δY] = Σ_rows Σ_k (var q̈_k A_kᵀ D² A_k + var q̇_k B_kᵀ D² B_k)
   !> into WᵀD²W (A_k = ∂Y/∂q̈_k, exact: Y is linear in q̈; B_k = ∂Y/∂q̇_k by central
   !> differences); the estimate solves (WᵀD²W − S) θ = WᵀD² b, and its covariance is
   !> the sandwich G⁻¹ (WᵀD²W) G⁻¹ (× s² by the caller). Where G is not positive
   !> definite (noise beyond the signal) the plain estimate stays.
   subroutine compensate(chain, base, t, q, qd, qdd, noise_var, w, b, wt, scale, res)
      type(chain_t), intent(in) :: chain
      type(base_t), intent(in) :: base
      real(dp), intent(in) :: t(:), q(:, :), qd(:, :), qdd(:, :), noise_var(:, :)
      real(dp), intent(in) :: w(:, :), b(:), wt(:), scale(:)
      type(identify_result_t), intent(inout) :: res
      real(dp) :: y0(size(q, 1), n_kinds*size(q, 1)), y1(size(q, 1), n_kinds*size(q, 1)), &
                  y2(size(q, 1), n_kinds*size(q, 1)), v(size(q, 1)), hstep
      real(dp), allocatable :: a(:, :), sn(:, :), g(:, :), gi(:, :), ww(:, :), rhs(:), x(:)
      integer :: n, j, kk, i, np, lo, hi
      n = size(q, 1)
      np = size(base%kept)
      allocate (sn(np, np), a(n, np))
      sn = 0.0_dp
      do j = 1, size(t)
         lo = (j - 1)*n + 1
         hi = j*n
         call regressor(chain, t(j), q(:, j), qd(:, j), qdd(:, j), y0)
         do kk = 1, n
            v = qdd(:, j)
            v(kk) = v(kk) + 1.0_dp
            call regressor(chain, t(j), q(:, j), qd(:, j), v, y1)
            a = (y1(:, base%kept) - y0(:, base%kept))
            do i = 1, np
               a(:, i) = a(:, i)*wt(lo:hi)/scale(i)
            end do
            sn = sn + noise_var(2, kk)*matmul(transpose(a), a)
            hstep = 1e-5_dp*max(1.0_dp, abs(qd(kk, j)))
            v = qd(:, j)
            v(kk) = v(kk) + hstep
            call regressor(chain, t(j), q(:, j), v, qdd(:, j), y1)
            v(kk) = v(kk) - 2*hstep
            call regressor(chain, t(j), q(:, j), v, qdd(:, j), y2)
            a = (y1(:, base%kept) - y2(:, base%kept))/(2*hstep)
            do i = 1, np
               a(:, i) = a(:, i)*wt(lo:hi)/scale(i)
            end do
            sn = sn + noise_var(1, kk)*matmul(transpose(a), a)
         end do
      end do
      allocate (ww(size(w, 1), np))
      do i = 1, np
         ww(:, i) = w(:, i)*wt/scale(i)
      end do
      g = matmul(transpose(ww), ww) - sn
      gi = spd_inverse(g)
      if (.not. allocated(gi)) return
      rhs = matmul(b*wt, ww)
      x = matmul(gi, rhs)
      res%estimate = x/scale
      res%covariance = matmul(matmul(gi, matmul(transpose(ww), ww)), gi)
      res%compensated = .true.
   end subroutine compensate

   !> The inverse of a symmetric positive definite matrix by Cholesky; unallocated
   !> when it is not positive definite.
   pure function spd_inverse(g) result(gi)
      real(dp), intent(in) :: g(:, :)
      real(dp), allocatable :: gi(:, :)
      real(dp) :: l(size(g, 1), size(g, 1)), d
      integer :: i, j, n
      n = size(g, 1)
      l = 0.0_dp
      do j = 1, n
         d = g(j, j) - dot_product(l(j, 1:j - 1), l(j, 1:j - 1))
         if (.not. (d > 1e-12_dp*abs(g(j, j)))) return
         l(j, j) = sqrt(d)
         do i = j + 1, n
            l(i, j) = (g(i, j) - dot_product(l(i, 1:j - 1), l(j, 1:j - 1)))/l(j, j)
         end do
      end do
      l = r_inverse(transpose(l))   ! L⁻ᵀ (upper triangular)
      gi = matmul(l, transpose(l))
   end function spd_inverse

   !> A direction in the base parameters in words, its largest component 1:
   !> 'c1 - 5 cf1' (components below 1e-3 of the largest left out).
   function direction_text(base, d) result(s)
      type(base_t), intent(in) :: base
      real(dp), intent(in) :: d(:)
      character(len=:), allocatable :: s
      real(dp) :: big, x
      integer :: i, lead
      lead = maxloc(abs(d), dim=1)
      big = d(lead)
      s = '('//trim(base%names(lead))//')'
      do i = 1, size(d)
         if (i == lead) cycle
         x = d(i)/big
         if (abs(x) < 1e-3_dp) cycle
         s = s//merge(' + ', ' - ', x > 0.0_dp)//real_str(abs(x), 3)//' ('// &
             trim(base%names(i))//')'
      end do
   end function direction_text

end module dpend_identify
