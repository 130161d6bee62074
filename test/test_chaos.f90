!> Chaos: tangent dynamics against nearby trajectories, the QR step against
!> Gram–Schmidt, exponents known in closed form (a linear flow; the upright
!> equilibrium of the pendulum), the small-oscillation and chaotic regimes,
!> divergence of nearby trajectories, energy-shell sampling and Poincaré
!> sections (a normal mode's period), and the three commands run as processes.
module test_chaos
   use dpend_kinds, only: dp, i8
   use dpend_cli, only: real_str, to_str
   use dpend_pendulum, only: pendulum_t, energy, hamiltonian, momenta, velocities
   use dpend_pendulum, only: pendulum_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_names, method_options_t
   use dpend_propagate, only: march_t, advance_to, march_progress_t
   use dpend_poincare, only: poincare_sections, poincare_result_t
   use dpend_tangent, only: tangent_t
   use dpend_lyapunov, only: qr_positive, lyapunov_acc_t, renormalize, batch_exponents, &
                             lyapunov_result_t, lyapunov_spectrum
   use dpend_divergence, only: perturbed_state, phase_distance, &
                               divergence_result_t, divergence_pairs, line_fit_t, &
                               fit_exponential_phase
   use dpend_poincare, only: halton, shell_samples, section_orbit
   use dpend_pendulum, only: energy_gradient, shell_state
   use dpend_events, only: angle_crossing_t
   use dpend_error, only: error_t
   use dpend_hdf5, only: h5file_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec, model_spec_t, new_model
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   use test_cli, only: run_command, scratch_dir, read_text, expect_rejected
   implicit none
   private
   public :: collect_chaos

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_chaos(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('qr_matches_gram_schmidt', test_qr), &
              new_unittest('qr_dependent_columns_rejected', test_qr_dependent), &
              new_unittest('linear_flow_exponents', test_linear_flow), &
              new_unittest('batch_means_spread', test_batches), &
              new_unittest('tangent_vs_nearby_trajectories', test_tangent_fd), &
              new_unittest('upright_equilibrium_exponents', test_upright), &
              new_unittest('small_oscillation_exponent', test_small_oscillation), &
              new_unittest('chaotic_exponent_methods_agree', test_chaotic), &
              new_unittest('chaotic_spectrum_pairing', test_pairing), &
              new_unittest('energy_gradient_fd', test_energy_gradient), &
              new_unittest('perturbation_on_energy_surface', test_perturbation), &
              new_unittest('fit_synthetic_divergence', test_fit_synthetic), &
              new_unittest('divergence_slope_vs_lyapunov', test_divergence_slope), &
              new_unittest('divergence_pairs_on_the_driven_orbit', test_divergence_driven), &
              new_unittest('progress_covers_span', test_progress_span), &
              new_unittest('halton_sequence', test_halton), &
              new_unittest('shell_sampling_on_energy', test_shell), &
              new_unittest('section_points_on_section', test_section_points), &
              new_unittest('section_normal_mode_period', test_normal_mode), &
              new_unittest('commands_bad_input', test_cli_bad), &
              new_unittest('commands_run', test_cli_run)]
   end subroutine collect_chaos

   !> Deterministic test matrix with entries in (-1, 1).
   pure function test_matrix(m, k, seed) result(a)
      integer, intent(in) :: m, k, seed
      real(dp) :: a(m, k)
      integer :: i, j
      do j = 1, k
         do i = 1, m
            a(i, j) = sin(real(seed + 7*i + 13*j*j + i*j, dp)*1.3_dp)
         end do
      end do
   end function test_matrix

   !> Modified Gram–Schmidt, the independent reference for the QR step.
   pure subroutine gram_schmidt(a, q, r)
      real(dp), intent(in) :: a(:, :)
      real(dp), intent(out) :: q(size(a, 1), size(a, 2)), r(size(a, 2), size(a, 2))
      integer :: i, j
      q = a
      r = 0.0_dp
      do j = 1, size(a, 2)
         do i = 1, j - 1
            r(i, j) = dot_product(q(:, i), q(:, j))
            q(:, j) = q(:, j) - r(i, j)*q(:, i)
         end do
         r(j, j) = norm2(q(:, j))
         q(:, j) = q(:, j)/r(j, j)
      end do
   end subroutine gram_schmidt

   subroutine test_qr(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: shapes(2, 4) = reshape([4, 4, 4, 1, 4, 2, 6, 3], [2, 4])
      real(dp), allocatable :: a(:, :), q(:, :), r(:, :), qg(:, :), rg(:, :), eye(:, :)
      integer :: s, m, k, info, i, j
      character(len=16) :: tag
      do s = 1, size(shapes, 2)
         m = shapes(1, s); k = shapes(2, s)
         write (tag, '("(", i0, "x", i0, ")")') m, k
         a = test_matrix(m, k, s)
         q = a
         allocate (r(k, k), qg(m, k), rg(k, k), eye(k, k))
         call qr_positive(q, r, info)
         call check_true(error, info == 0, 'qr_positive info '//trim(tag))
         eye = 0.0_dp
         do i = 1, k
            eye(i, i) = 1.0_dp
         end do
         call check(error, maxval(abs(matmul(transpose(q), q) - eye)), 0.0_dp, &
                    'Q^T Q - I '//trim(tag), abs=1e-14_dp)
         call check(error, maxval(abs(matmul(q, r) - a)), 0.0_dp, 'QR - A '//trim(tag), &
                    abs=1e-14_dp)
         do j = 1, k
            call check_true(error, r(j, j) > 0.0_dp, 'R_jj > 0 '//trim(tag))
            do i = j + 1, k
               call check_true(error, r(i, j) == 0.0_dp, 'R upper triangular '//trim(tag))
            end do
         end do
         call gram_schmidt(a, qg, rg)
         call check(error, maxval(abs(q - qg)), 0.0_dp, 'Q vs Gram-Schmidt '//trim(tag), &
                    abs=1e-12_dp)
         call check(error, maxval(abs(r - rg)), 0.0_dp, 'R vs Gram-Schmidt '//trim(tag), &
                    abs=1e-12_dp)
         deallocate (r, qg, rg, eye)
         if (allocated(error)) return
      end do
   end subroutine test_qr

   subroutine test_qr_dependent(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: a(4, 3), r(3, 3)
      integer :: info
      a = test_matrix(4, 3, 5)
      a(:, 2) = 0.0_dp
      call qr_positive(a, r, info)
      call check_true(error, info /= 0, 'a zero column is reported (info /= 0)')
   end subroutine test_qr_dependent

   !> v' = A v with A = S B S⁻¹, B = [[a, -w], [w, a]] ⊕ diag(b, c): the exponents
   !> are the real parts of the eigenvalues, (a, a, b, c); S = I + N with N
   !> strictly upper triangular, so S⁻¹ = I - N + N² - N³ exactly. The exact
   !> propagator exp(A τ) = S exp(B τ) S⁻¹ feeds the accumulation.
   subroutine test_linear_flow(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), parameter :: a = 0.4_dp, w = 1.5_dp, b = -0.1_dp, c = -0.6_dp, tau = 0.5_dp
      real(dp) :: n(4, 4), s(4, 4), sinv(4, 4), eb(4, 4), phi(4, 4), eye(4, 4), v(4, 4), v1(4, 1)
      real(dp), allocatable :: batches(:, :)
      real(dp) :: spread(4), spread1(1), lam(4), lam1(1)
      type(lyapunov_acc_t) :: acc, acc1
      integer :: i, info
      eye = 0.0_dp
      do i = 1, 4
         eye(i, i) = 1.0_dp
      end do
      n = 0.0_dp
      n(1, 2) = 0.8_dp; n(1, 3) = -0.5_dp; n(1, 4) = 0.3_dp
      n(2, 3) = 0.7_dp; n(2, 4) = -0.4_dp; n(3, 4) = 0.9_dp
      s = eye + n
      sinv = eye - n + matmul(n, n) - matmul(n, matmul(n, n))
      call check(error, maxval(abs(matmul(s, sinv) - eye)), 0.0_dp, 'S S^-1 = I', abs=1e-15_dp)
      eb = 0.0_dp
      eb(1, 1) = exp(a*tau)*cos(w*tau); eb(1, 2) = -exp(a*tau)*sin(w*tau)
      eb(2, 1) = exp(a*tau)*sin(w*tau); eb(2, 2) = exp(a*tau)*cos(w*tau)
      eb(3, 3) = exp(b*tau); eb(4, 4) = exp(c*tau)
      phi = matmul(s, matmul(eb, sinv))
      call acc%init(4, 0.0_dp)
      call acc1%init(1, 0.0_dp)
      v = eye
      v1(:, 1) = [1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      do i = 1, 4000
         v = matmul(phi, v)
         call renormalize(acc, v, real(i, dp)*tau, info)
         if (info /= 0) exit
         v1 = matmul(phi, v1)
         call renormalize(acc1, v1, real(i, dp)*tau, info)
         if (info /= 0) exit
      end do
      call check_true(error, info == 0, 'renormalize info')
      lam = acc%exponents()
      lam1 = acc1%exponents()
      ! O(1/t) convergence: ln(cond S)/t ≈ 1e-3 at t = 2000 s
      call check(error, lam, [a, a, b, c], 'spectrum of the linear flow', abs=2e-3_dp)
      call check(error, lam1(1), a, 'largest exponent (one vector)', abs=2e-3_dp)
      call check(error, sum(lam), 2.0_dp*a + b + c, 'sum = trace A', abs=1e-12_dp)
      call batch_exponents(acc, 10, batches, spread)
      call check_true(error, size(batches, 2) == 10, '10 batches')
      call check_true(error, all(spread < 1e-2_dp), 'batch spread small for a linear flow')
      call batch_exponents(acc1, 10, batches, spread1)
      call check(error, batches(1, 10), a, 'last batch of the largest exponent', abs=1e-2_dp)
   end subroutine test_linear_flow

   !> Sums with rate 1 in odd and 3 in even batches: batch means exact, spread
   !> = std/√n = 1.0541/√10.
   subroutine test_batches(error)
      type(error_t), allocatable, intent(out) :: error
      type(lyapunov_acc_t) :: acc
      real(dp), allocatable :: batches(:, :)
      real(dp) :: spread(1), rate
      integer :: i, b
      call acc%init(1, 0.0_dp)
      do i = 1, 100
         b = (i - 1)/10 + 1
         rate = merge(1.0_dp, 3.0_dp, mod(b, 2) == 1)
         call acc%add(real(i, dp)*0.5_dp, [exp(rate*0.5_dp)])
      end do
      call batch_exponents(acc, 10, batches, spread)
      call check(error, batches(1, :), [(merge(1.0_dp, 3.0_dp, mod(b, 2) == 1), b=1, 10)], &
                 'batch exponents', abs=1e-12_dp)
      call check(error, spread(1), sqrt(10.0_dp/9.0_dp)/sqrt(10.0_dp), 'spread', rel=1e-12_dp)
      call check(error, acc%exponents(), [2.0_dp], 'mean exponent', abs=1e-12_dp)
   end subroutine test_batches

   !> Tangent vectors propagated along the trajectory against central
   !> differences of nearby trajectories of the same method, for every method.
   subroutine test_tangent_fd(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: names
      character(len=16) :: name
      real(dp) :: dt_m
      integer :: p, q
      names = method_names()//' '
      p = 1
      do while (p <= len_trim(names))
         q = index(names(p:), ' ') + p - 1
         name = names(p:q - 1)
         p = q + 1
         call check_method(trim(name))
         if (allocated(error)) return
      end do
   contains
      subroutine check_method(meth)
         character(len=*), intent(in) :: meth
         type(pendulum_t) :: par
         class(integrator_t), allocatable :: integ
         type(error_t), allocatable :: err
         type(tangent_t) :: tan
         type(march_t) :: march
         real(dp) :: y0(4), y(4), t, h, eye(4, 4), yp(4), ym(4), fd(4), eps, scale
         integer :: j, stat
         call new_integrator(meth, integ, err, method_options_t(rtol=1e-13_dp, atol=1e-15_dp))
         ! the nearby trajectories carry the method's own truncation error, O(dt^p):
         ! second-order methods take a smaller step to bring it below the tolerance
         dt_m = merge(1e-3_dp, 5e-5_dp, integ%order() >= 4)
         y0 = integ%to_internal(pendulum_model(par), [0.3_dp, -0.4_dp], [1.0_dp, -2.0_dp])
         eye = 0.0_dp
         do j = 1, 4
            eye(j, j) = 1.0_dp
         end do
         call tan%init(eye)
         t = 0.0_dp; y = y0; h = dt_m
         call integ%clear_step()
         call march%start(integ, t, 2.0_dp, h)
         do while (.not. march%finished)
            call march%next(integ, pendulum_model(par), t, y, h, stat)
            if (stat /= stat_ok) exit
            call tan%propagate(integ, pendulum_model(par))
         end do
         call check_true(error, stat == stat_ok, meth//': reference run')
         eps = 1e-5_dp
         do j = 1, 4
            yp = end_state(y0 + eps*eye(:, j))
            ym = end_state(y0 - eps*eye(:, j))
            fd = (yp - ym)/(2.0_dp*eps)
            scale = maxval(abs(fd))
            call check(error, maxval(abs(tan%v(:, j) - fd))/scale, 0.0_dp, &
                       meth//': tangent vs nearby trajectories, column', abs=2e-6_dp)
         end do
      end subroutine check_method

      function end_state(ys) result(ye)
         real(dp), intent(in) :: ys(4)
         real(dp) :: ye(4)
         type(pendulum_t) :: par
         class(integrator_t), allocatable :: integ
         type(error_t), allocatable :: err
         real(dp) :: t, h
         integer :: stat
         call new_integrator(trim(name), integ, err, method_options_t(rtol=1e-13_dp, atol=1e-15_dp))
         t = 0.0_dp; ye = ys; h = dt_m
         call advance_to(integ, pendulum_model(par), t, ye, 2.0_dp, h, stat)
      end function end_state
   end subroutine test_tangent_fd

   !> Both links upright at rest, q = (π/2, π/2): a hyperbolic fixed point whose
   !> linearisation M0 ü = K u has the exponents ±μ with μ² the roots of
   !> det(K − μ² M0) = 0, for equal rods μ² = (3 ± 6/√7) g/L (docs/physics.md,
   !> small oscillations, with the sign of gravity reversed). QR on a constant
   !> Jacobian is orthogonal iteration: the exponent of each renormalisation
   !> interval converges to μ_i exponentially fast (gaps ≥ 4.5 1/s). Also
   !> Liouville: Σ λ_i t = ln |det| of the tangent map = 0 here.
   subroutine test_upright(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: names
      character(len=16) :: name
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(lyapunov_result_t) :: res
      real(dp) :: mu(4), local(4), s1(4), s0(4)
      integer :: p, q, stat, n
      mu(1) = sqrt((3.0_dp + 6.0_dp/sqrt(7.0_dp))*par%g/par%l1)
      mu(2) = sqrt((3.0_dp - 6.0_dp/sqrt(7.0_dp))*par%g/par%l1)
      mu(3) = -mu(2); mu(4) = -mu(1)
      call check(error, mu(1), 7.185006_dp, 'mu1 (docs/physics.md)', abs=1e-6_dp)
      names = method_names()//' '
      p = 1
      do while (p <= len_trim(names))
         q = index(names(p:), ' ') + p - 1
         name = names(p:q - 1)
         p = q + 1
         call new_integrator(trim(name), integ, err, method_options_t(rtol=1e-10_dp, atol=1e-12_dp))
         call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, &
                                integ%to_internal(pendulum_model(par), [0.5_dp*pi, 0.5_dp*pi], [0.0_dp, 0.0_dp]), &
                                3.0_dp, 1e-3_dp, 0.25_dp, 4, 4, res, stat)
         call check_true(error, stat == stat_ok, trim(name)//': run')
         if (allocated(error)) return
         n = size(res%t)
         s1 = res%running(:, n)*res%t(n)
         s0 = res%running(:, n - 1)*res%t(n - 1)
         local = (s1 - s0)/(res%t(n) - res%t(n - 1))
         call check(error, local, mu, trim(name)//': local exponents at t = 3 s', rel=1e-5_dp)
         ! RK4 on the variational equation keeps det only to its truncation error
         call check(error, sum(s1), 0.0_dp, trim(name)//': sum of ln R_ii (Liouville)', &
                    abs=1e-6_dp*sum(abs(s1)))
         if (allocated(error)) return
      end do
   end subroutine test_upright

   !> Small oscillations about the hanging state (0.07 rad): quasi-periodic
   !> motion, tangent vectors grow at most linearly, λ1(t) = O(ln t / t).
   !> The finite-time λ1 at 300 s is compared with an independent value of the same
   !> quantity, ln(|δy(300)|/|δ0|)/300 s from two nonlinear dop853 runs (rtol 1e-13)
   !> started δ0 = 1e-7 apart along the first tangent vector (q1): measured λ1
   !> 4.3765e-3 1/s, difference to the runs 2.0e-8 (debug) and 3.0e-8 (release) 1/s;
   !> bound 3e-7 1/s, 1e-4 of λ1 itself, so a factor 2 in λ1 (or in the growth of the
   !> tangent vectors) fails.
   subroutine test_small_oscillation(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(lyapunov_result_t) :: res
      integer :: stat, i
      call new_integrator('rk4', integ, err)
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, &
                             integ%to_internal(pendulum_model(par), [-1.5_dp, -1.5_dp], [0.0_dp, 0.0_dp]), &
                             300.0_dp, 1e-3_dp, 0.5_dp, 1, 10, res, stat)
      call check_true(error, stat == stat_ok, 'run')
      call check(error, res%exponents(1), 0.0_dp, 'lambda1 at t = 300 s', abs=2e-2_dp)
      if (allocated(error)) return
      block
         real(dp), parameter :: del = 1e-7_dp
         real(dp) :: ya(4), yb(4), lam_fd
         ya = integ%to_internal(pendulum_model(par), [-1.5_dp, -1.5_dp], [0.0_dp, 0.0_dp])
         yb = ya + [del, 0.0_dp, 0.0_dp, 0.0_dp]
         call run_dop853(ya)
         call run_dop853(yb)
         if (allocated(error)) return
         lam_fd = log(norm2(yb - ya)/del)/300.0_dp
         print '(a, es12.5, a, es12.5, a, es9.2)', &
            '    chaos: small oscillations, lambda1(300 s) ', res%exponents(1), &
            ' 1/s; nearby runs ', lam_fd, ' 1/s; diff ', res%exponents(1) - lam_fd
         call check(error, res%exponents(1), lam_fd, 'lambda1 vs nearby nonlinear runs', &
                    abs=3e-7_dp)
      end block
      ! the running estimate stays below ln(t)/t from t = 10 s on
      do i = 1, size(res%t)
         if (res%t(i) < 10.0_dp) cycle
         call check_true(error, abs(res%running(1, i)) <= log(res%t(i))/res%t(i), &
                         'running lambda1 below ln(t)/t')
         if (allocated(error)) return
      end do
   contains
      !> y (internal (q, q̇) of rk4) from 0 to 300 s by dop853 at rtol 1e-13.
      subroutine run_dop853(y)
         real(dp), intent(inout) :: y(4)
         class(integrator_t), allocatable :: d8
         real(dp) :: t, h
         call new_integrator('dop853', d8, err, method_options_t(rtol=1e-13_dp, atol=1e-15_dp))
         t = 0.0_dp; h = 0.0_dp
         call advance_to(d8, pendulum_model(par), t, y, 300.0_dp, h, stat)
         call check_true(error, stat == stat_ok .and. .not. allocated(err), 'dop853 run')
      end subroutine run_dop853
   end subroutine test_small_oscillation

   !> Both links horizontal at rest: λ1 > 0, the same for rk4 and dop853 within
   !> the statistical spread of the running estimates (the trajectories
   !> themselves separate after ~20 s).
   subroutine test_chaotic(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(lyapunov_result_t) :: ra, rb
      integer :: stat
      real(dp) :: combined
      call new_integrator('rk4', integ, err)
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, integ%to_internal(pendulum_model(par), [0.0_dp, 0.0_dp], &
                             [0.0_dp, 0.0_dp]), 300.0_dp, 1e-3_dp, 0.5_dp, 1, 10, ra, stat)
      call check_true(error, stat == stat_ok, 'rk4 run')
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-10_dp, atol=1e-12_dp))
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, integ%to_internal(pendulum_model(par), [0.0_dp, 0.0_dp], &
                             [0.0_dp, 0.0_dp]), 300.0_dp, 0.0_dp, 0.5_dp, 1, 10, rb, stat)
      call check_true(error, stat == stat_ok, 'dop853 run')
      if (allocated(error)) return
      call check_true(error, ra%exponents(1) > 0.5_dp .and. rb%exponents(1) > 0.5_dp, &
                      'lambda1 > 0.5 1/s')
      combined = sqrt(ra%spread(1)**2 + rb%spread(1)**2)
      call check(error, ra%exponents(1) - rb%exponents(1), 0.0_dp, &
                 'rk4 - dop853 within 3 combined standard errors', abs=3.0_dp*combined)
      call check_true(error, combined < 0.15_dp*ra%exponents(1), 'spread below 15 %')
   end subroutine test_chaotic

   !> Full spectrum of the chaotic orbit: λ1 + λ4 ≈ 0, λ2 ≈ λ3 ≈ 0, and
   !> Liouville exactly: Σ ln R_ii = ln |det Φ| = ln(det M(q0) / det M(q(t))) in
   !> (q, q̇) variables (0 in (q, p)).
   subroutine test_pairing(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(lyapunov_result_t) :: res
      integer :: stat
      real(dp) :: lam(4), liouville
      call new_integrator('rk4', integ, err)
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, integ%to_internal(pendulum_model(par), [0.0_dp, 0.0_dp], &
                             [0.0_dp, 0.0_dp]), 300.0_dp, 1e-3_dp, 0.5_dp, 4, 10, res, stat)
      call check_true(error, stat == stat_ok, 'run')
      if (allocated(error)) return
      lam = res%exponents
      call check_true(error, lam(1) > 0.5_dp, 'lambda1 > 0.5 1/s')
      call check(error, lam(1) + lam(4), 0.0_dp, 'pairing lambda1 + lambda4', &
                 abs=0.02_dp*lam(1))
      call check(error, lam(2), 0.0_dp, 'lambda2', abs=0.05_dp*lam(1))
      call check(error, lam(3), 0.0_dp, 'lambda3', abs=0.05_dp*lam(1))
      liouville = log(det_m([0.0_dp, 0.0_dp])/det_m(res%y(1:2)))
      call check(error, sum(lam)*res%t_reached, liouville, 'sum ln R_ii = ln det', abs=1e-6_dp)
   contains
      real(dp) function det_m(q)
         real(dp), intent(in) :: q(2)
         det_m = (par%m1/3.0_dp + par%m2)*par%l1**2*par%m2*par%l2**2/3.0_dp &
                 - (0.5_dp*par%m2*par%l1*par%l2*cos(q(1) - q(2)))**2
      end function det_m
   end subroutine test_pairing

   subroutine test_energy_gradient(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: z(4), g(4), fd(4), e(4), h
      integer :: i, j
      par = pendulum_t(m1=1.3_dp, m2=0.7_dp, l1=0.9_dp, l2=1.4_dp, g=9.81_dp)
      h = 1e-5_dp
      do j = 1, 5
         z = 2.0_dp*reshape(test_matrix(4, 1, j), [4]) + [0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp]
         g = energy_gradient(par, z(1:2), z(3:4))
         do i = 1, 4
            e = 0.0_dp; e(i) = h
            fd(i) = (energy(par, z(1:2) + e(1:2), z(3:4) + e(3:4)) &
                     - energy(par, z(1:2) - e(1:2), z(3:4) - e(3:4)))/(2.0_dp*h)
         end do
         call check(error, g, fd, 'energy gradient vs FD', abs=1e-7_dp*maxval(abs(fd)))
      end do
   end subroutine test_energy_gradient

   subroutine test_perturbation(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: qa(2, 3), qda(2, 3), qb(2), qdb(2), d0
      integer :: j
      qa = reshape([0.0_dp, 0.0_dp, -1.0_dp, 0.5_dp, 2.0_dp, -2.5_dp], [2, 3])
      qda = reshape([0.0_dp, 0.0_dp, 1.0_dp, -3.0_dp, -0.5_dp, 2.0_dp], [2, 3])
      d0 = 1e-9_dp
      do j = 1, 3
         call perturbed_state(pendulum_model(par), qa(:, j), qda(:, j), d0, .false., qb, qdb)
         call check(error, phase_distance(qa(:, j), qda(:, j), qb, qdb), d0, '|delta(0)|', &
                    rel=1e-6_dp)
         call perturbed_state(pendulum_model(par), qa(:, j), qda(:, j), d0, .true., qb, qdb)
         call check(error, phase_distance(qa(:, j), qda(:, j), qb, qdb), d0, &
                    '|delta(0)| on the energy surface', rel=1e-6_dp)
         call check(error, energy(par, qb, qdb), energy(par, qa(:, j), qda(:, j)), &
                    'same energy', abs=1e-13_dp)
      end do
      call check(error, phase_distance([1.0_dp, -2.0_dp], [0.5_dp, 0.5_dp], &
                                       [1.0_dp + 2.0_dp*pi, -2.0_dp - 4.0_dp*pi], &
                                       [0.5_dp, 0.5_dp]), 0.0_dp, 'angles wrapped', &
                 abs=1e-14_dp)
   end subroutine test_perturbation

   !> log10|δ| = −9 + s t/ln 10 up to saturation at 0.5, with a deterministic
   !> wiggle: the automatic window finds the exponential phase and the slope s.
   subroutine test_fit_synthetic(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), parameter :: s = 1.3_dp
      real(dp) :: t(4001), y(4001)
      type(line_fit_t) :: fit
      integer :: i
      do i = 1, size(t)
         t(i) = 0.01_dp*real(i - 1, dp)
         y(i) = min(-9.0_dp + s*t(i)/log(10.0_dp), 0.5_dp) + 0.05_dp*sin(7.3_dp*t(i))
      end do
      call fit_exponential_phase(t, y, 0.0_dp, 0.0_dp, fit)
      call check_true(error, fit%ok .and. fit%saturated, 'fitted and saturated')
      call check(error, fit%slope, s, 'slope', rel=1e-2_dp)
      call check(error, fit%saturation, 0.5_dp, 'saturation level', abs=0.06_dp)
      call check(error, fit%t_start, (1.0_dp - 0.05_dp*sin(7.3_dp*fit%t_start))*log(10.0_dp)/s, &
                 'window starts one decade above delta0', abs=0.02_dp)
      call check_true(error, fit%t_end < (9.5_dp - 1.5_dp + 0.1_dp)*log(10.0_dp)/s, &
                      'window ends 1.5 decades below saturation')
      call fit_exponential_phase(t, y, 5.0_dp, 10.0_dp, fit)
      call check(error, fit%slope, s, 'slope over a given window', rel=1e-2_dp)
      call check(error, fit%t_start, 5.0_dp, 'given window start', abs=1e-9_dp)
      y = -9.0_dp + s*t/log(10.0_dp)/10.0_dp
      call fit_exponential_phase(t, y, 0.0_dp, 0.0_dp, fit)
      call check_true(error, .not. fit%saturated, 'not saturated')
      call check(error, fit%slope, s/10.0_dp, 'slope without saturation', rel=1e-9_dp)
   end subroutine test_fit_synthetic

   !> The slope of ⟨log10|δ|⟩ over 10 pairs agrees with Benettin's λ1 of the same
   !> orbit within 20 %.
   subroutine test_divergence_slope(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(divergence_result_t) :: dres
      type(lyapunov_result_t) :: lres
      type(line_fit_t) :: fit
      integer :: stat
      call new_integrator('rk4', integ, err)
      call divergence_pairs(integ, pendulum_model(par), [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], 30.0_dp, 0.01_dp, &
                            1e-9_dp, .false., 10, 25.0_dp, 1e-3_dp, dres, stat)
      call check_true(error, stat == stat_ok, 'divergence run')
      call check_true(error, size(dres%log10_pairs, 1) == 10 .and. size(dres%t) == 3001, &
                      'shape of the curves')
      if (allocated(error)) return
      call check(error, dres%log10_mean(1), -9.0_dp, 'log10 delta0', abs=1e-6_dp)
      call fit_exponential_phase(dres%t, dres%log10_mean, 0.0_dp, 0.0_dp, fit)
      call check_true(error, fit%ok .and. fit%saturated, 'exponential phase and saturation')
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, integ%to_internal(pendulum_model(par), [0.0_dp, 0.0_dp], &
                             [0.0_dp, 0.0_dp]), 300.0_dp, 1e-3_dp, 0.5_dp, 1, 10, lres, stat)
      call check(error, fit%slope, lres%exponents(1), 'slope vs lambda1', &
                 rel=0.2_dp)
   end subroutine test_divergence_slope

   !> Pairs of a driven system start where and when the orbit is: pair 2 of a double
   !> pendulum on a vertically shaken support (a_y 0.05 m, ω 12 rad/s: its motion depends
   !> on the drive's phase) against the same pair built here by hand: the orbit advanced
   !> to the spacing s, the partner displaced at t = s, both advanced to s + T (rk4, the
   !> same steps): log10 |δ| at the end equal to 1e-9. Pair 1 (from t = 0) likewise.
   subroutine test_divergence_driven(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      class(model_t), allocatable :: model
      type(model_spec_t) :: spec
      type(divergence_result_t) :: dres
      real(dp), parameter :: s = 0.37_dp, span = 2.0_dp, h = 1e-3_dp, d0 = 1e-6_dp
      real(dp) :: q0(2), ya(4), yb(4), t, hh, qa(2), qda(2), qb(2), qdb(2), expected
      integer :: stat, p, n
      call new_integrator('rk4', integ, error)
      if (allocated(error)) return
      spec = model_spec('pendulum')
      call spec%set('support_amplitude', [0.0_dp, 0.05_dp])
      call spec%set('support_frequency', [12.0_dp])
      call new_model(spec, model, error)
      if (allocated(error)) return
      call check_true(error, .not. model%autonomous(), 'a driven model')
      if (allocated(error)) return
      q0 = [-0.4_dp, -1.2_dp]
      call divergence_pairs(integ, model, q0, [0.0_dp, 0.0_dp], span, 0.1_dp, d0, .false., &
                            2, s, h, dres, stat)
      call check_true(error, stat == stat_ok .and. size(dres%log10_pairs, 1) == 2, &
                      'two pairs computed')
      if (allocated(error)) return
      n = size(dres%t)
      call check(error, dres%t(n), span, 'sample times from the pair''s start', abs=1e-12_dp)
      do p = 1, 2
         ya = integ%to_internal(model, q0, [0.0_dp, 0.0_dp])
         t = 0.0_dp; hh = h
         if (p == 2) call advance_to(integ, model, t, ya, s, hh, stat)
         call integ%to_physical(model, ya, qa, qda, t)
         call perturbed_state(model, qa, qda, d0, .false., qb, qdb, t)
         call check(error, dres%start(:, p), [qa, qda], 'start of pair '//to_str(p), &
                    abs=1e-12_dp)
         ya = integ%to_internal(model, qa, qda, t)
         yb = integ%to_internal(model, qb, qdb, t)
         hh = h
         call advance_to(integ, model, t, ya, real(p - 1, dp)*s + span, hh, stat)
         t = real(p - 1, dp)*s; hh = h
         call advance_to(integ, model, t, yb, real(p - 1, dp)*s + span, hh, stat)
         call integ%to_physical(model, ya, qa, qda, t)
         call integ%to_physical(model, yb, qb, qdb, t)
         expected = log10(phase_distance(qa, qda, qb, qdb))
         call check(error, dres%log10_pairs(p, n), expected, 'log10 |delta| at the end of ' &
                    //'pair '//to_str(p)//' (started at t = '//real_str(real(p - 1, dp)*s)// &
                    ')', abs=1e-9_dp)
         if (allocated(error)) return
      end do
   end subroutine test_divergence_driven

   !> A command's progress in model time covers exactly the span it announced, however
   !> the work is split into marches: the divergence's reference orbit and its pairs
   !> ((n − 1) spacing + 2 n t), poincare's orbits run in parallel (n t_end, an orbit
   !> ended early at its points counted whole), a Lyapunov run (t_end); the report
   !> then stands at its whole (1e9 parts). Quiet: no line is written.
   subroutine test_progress_span(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(pendulum_t) :: par
      type(march_progress_t) :: prog
      type(divergence_result_t) :: dres
      type(lyapunov_result_t) :: lres
      type(poincare_result_t) :: pres
      type(angle_crossing_t) :: section
      real(dp) :: q0(2, 3), qd0(2, 3)
      integer :: stat
      call new_integrator('dop853', integ, error)
      if (allocated(error)) return
      call prog%begin('test divergence', 2.0_dp*0.25_dp + 2.0_dp*3.0_dp*0.5_dp)
      prog%bar%quiet = .true.
      call divergence_pairs(integ, pendulum_model(par), [0.3_dp, 0.2_dp], [0.0_dp, 0.0_dp], 0.5_dp, 0.1_dp, &
                            1e-9_dp, .false., 3, 0.25_dp, 1e-3_dp, dres, stat, prog)
      call check_covered('divergence')
      if (allocated(error)) return
      call prog%begin('test lyapunov', 2.0_dp)
      prog%bar%quiet = .true.
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, [0.3_dp, 0.2_dp, 0.0_dp, 0.0_dp], 2.0_dp, &
                             1e-3_dp, 0.5_dp, 2, 2, lres, stat, prog)
      call check_covered('lyapunov')
      if (allocated(error)) return
      section = angle_crossing_t(index=1, angle=-0.5_dp*pi, wrap=.true.)
      section%direction = 1
      q0 = reshape([-1.0_dp, -1.2_dp, -1.5_dp, -1.0_dp, -2.0_dp, -1.4_dp], [2, 3])
      qd0 = 0.0_dp
      call prog%begin('test poincare', 3.0_dp*20.0_dp)
      prog%bar%quiet = .true.
      call poincare_sections(integ, pendulum_model(par), section, q0, qd0, 20.0_dp, 1e-3_dp, 5, pres, prog)
      call check_covered('poincare (3 orbits, ended at 5 points)')
   contains
      subroutine check_covered(what)
         character(len=*), intent(in) :: what
         call check_true(error, stat == stat_ok, what//': the run failed')
         if (allocated(error)) return
         call check_true(error, abs(prog%covered - prog%span) <= 1e-12_dp*prog%span, what// &
                         ': covered '//real_str(prog%covered)//' s of '//real_str(prog%span)//' s')
         if (allocated(error)) return
         call check_true(error, prog%bar%done == 1000000000_i8, what//': the report at '// &
                         to_str(prog%bar%done)//' of 1e9 parts')
         call prog%end()
      end subroutine check_covered
   end subroutine test_progress_span

   subroutine test_halton(error)
      type(error_t), allocatable, intent(out) :: error
      call check(error, [halton(1, 2), halton(2, 2), halton(3, 2), halton(6, 2)], &
                 [0.5_dp, 0.25_dp, 0.75_dp, 0.375_dp], 'base 2', abs=1e-15_dp)
      call check(error, [halton(1, 3), halton(2, 3), halton(5, 3)], &
                 [1.0_dp/3.0_dp, 2.0_dp/3.0_dp, 7.0_dp/9.0_dp], 'base 3', abs=1e-15_dp)
   end subroutine test_halton

   !> Samples lie on the section with the right sign of q̇_s and the energy;
   !> energies below the section's potential give none.
   subroutine test_shell(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2, 50), qd(2, 50), e
      integer :: n, j, c, link, dir
      real(dp), parameter :: energies(3) = [0.0_dp, -17.0_dp, -19.5_dp]
      do c = 1, 3
         do link = 1, 2
            do dir = -1, 1, 2
               e = energies(c)
               call shell_samples(pendulum_model(par), e, link, -0.5_dp*pi, dir, 50, q, qd, n)
               call check_true(error, n == 50, 'found 50 samples')
               do j = 1, n
                  call check_true(error, q(link, j) == -0.5_dp*pi, 'on the section')
                  call check_true(error, dir*qd(link, j) > 0.0_dp, 'crossing direction')
                  call check(error, hamiltonian(par, q(:, j), momenta(par, q(:, j), qd(:, j))), &
                             e, 'energy', abs=1e-12_dp)
               end do
               if (allocated(error)) return
            end do
         end do
      end do
      call shell_samples(pendulum_model(par), -25.0_dp, 1, -0.5_dp*pi, 1, 50, q, qd, n)
      call check_true(error, n == 0, 'no samples below the minimum -19.6 J')
   end subroutine test_shell

   !> One orbit: the initial state is the first point, then crossings in time
   !> order at the energy (rk4, dt = 1e-3: error ~1e-9 relative).
   subroutine test_section_points(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(angle_crossing_t) :: section
      real(dp) :: q(2, 1), qd(2, 1), p(2)
      real(dp), allocatable :: qo(:), po(:), t(:), e(:)
      integer :: n, stat
      call shell_samples(pendulum_model(par), 0.0_dp, 1, -0.5_dp*pi, 1, 1, q, qd, n)
      call new_integrator('rk4', integ, err)
      section = angle_crossing_t(index=1, angle=-0.5_dp*pi, wrap=.true.)
      section%direction = 1
      call section_orbit(integ, pendulum_model(par), section, q(:, 1), qd(:, 1), 500.0_dp, 1e-3_dp, 30, &
                         qo, po, t, e, stat)
      call check_true(error, stat == stat_ok .and. size(qo) == 30, '30 points')
      if (allocated(error)) return
      p = momenta(par, q(:, 1), qd(:, 1))
      call check(error, [qo(1), po(1), t(1)], [q(2, 1) - 2.0_dp*pi*anint(q(2, 1)/(2.0_dp*pi)), &
                 p(2), 0.0_dp], 'first point is the initial state', abs=1e-15_dp)
      call check_true(error, all(t(2:) > t(:29)), 'times increase')
      call check_true(error, all(abs(qo) <= pi), 'angles wrapped')
      call check(error, maxval(abs(e)), 0.0_dp, 'energy on the section', abs=1e-6_dp)
   end subroutine test_section_points

   !> Slow normal mode at amplitude a = 0.01 rad started on the section: a
   !> periodic orbit, so every return is the same point and the returns are
   !> 2π/ω1 = 2.345568 s apart (docs/physics.md), up to O(a²).
   subroutine test_normal_mode(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(angle_crossing_t) :: section
      real(dp), allocatable :: qo(:), po(:), t(:), e(:)
      real(dp) :: w1, r, a, q0(2), qd0(2)
      integer :: stat
      a = 0.01_dp
      w1 = sqrt((3.0_dp - 6.0_dp/sqrt(7.0_dp))*par%g/par%l1)
      ! mode shape from the first row of (K − ω² M0) u = 0
      r = (1.5_dp*par%g - w1**2*4.0_dp/3.0_dp)/(0.5_dp*w1**2)
      q0 = [-0.5_dp*pi, -0.5_dp*pi]
      qd0 = a*w1*[1.0_dp, r]
      call new_integrator('rk4', integ, err)
      section = angle_crossing_t(index=1, angle=-0.5_dp*pi, wrap=.true.)
      section%direction = 1
      call section_orbit(integ, pendulum_model(par), section, q0, qd0, 100.0_dp, 1e-3_dp, 11, qo, po, t, e, stat)
      call check_true(error, stat == stat_ok .and. size(t) == 11, '11 points')
      if (allocated(error)) return
      call check(error, (t(11) - t(1))/10.0_dp, 2.345568_dp, 'return time', rel=1e-4_dp)
      call check(error, maxval(abs(qo - qo(1))), 0.0_dp, 'returns to the same q2', &
                 abs=1e-3_dp*a)
      call check(error, maxval(abs(po - po(1))), 0.0_dp, 'returns to the same p2', &
                 abs=1e-3_dp*maxval(abs(momenta(par, q0, qd0))))
   end subroutine test_normal_mode

   !> Invalid input: exit status 2, one line on stderr naming the field, no file.
   subroutine test_cli_bad(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('chaosbad')
      call expect_rejected(error, dir, 'lyapunov', '--tau 0', 'tau')
      call expect_rejected(error, dir, 'lyapunov', '--vectors 5', 'vectors')
      call expect_rejected(error, dir, 'lyapunov', '--t-end 0', 't_end')
      call expect_rejected(error, dir, 'lyapunov', '--method nosuch', 'method')
      call expect_rejected(error, dir, 'lyapunov', '--output-dt 1', 'unknown option')
      call expect_rejected(error, dir, 'divergence', '--delta0 0', 'delta0')
      call expect_rejected(error, dir, 'divergence', '--pairs 0', 'pairs')
      call expect_rejected(error, dir, 'divergence', '--fit-start 5 --fit-end 2', 'fit_end')
      call expect_rejected(error, dir, 'divergence', '--output-dt 0', 'output_dt')
      call expect_rejected(error, dir, 'poincare', '--energy -100', 'energy')
      call expect_rejected(error, dir, 'poincare', '--section-link 3', 'section_link')
      call expect_rejected(error, dir, 'poincare', '--ics 0', 'n_ics')
      call expect_rejected(error, dir, 'poincare', '--tau 1', 'unknown option')
      call write_file(dir//'/bad.nml', '&chaos tau = 1.0, bogus = 2 /')
      call expect_rejected(error, dir, 'lyapunov', '--config '//dir//'/bad.nml', '&chaos')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_cli_bad


   !> Each command runs, ends its output with the scripting line, and writes
   !> the datasets of docs/hdf5-layout.md; &chaos settings are read.
   subroutine test_cli_run(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, last
      type(h5file_t) :: h5
      real(dp), allocatable :: lam(:), run(:, :), tt(:), q(:), p(:)
      integer, allocatable :: cnt(:)
      real(dp) :: x(4), slope, tau
      integer :: stat, n, ios, vectors
      dir = scratch_dir('chaosrun')
      stat = run_command(dir, 'lyapunov --t-end 20 --output '//dir//'/l.h5')
      call read_text(dir//'/stdout', text, n)
      last = last_line(text)
      call check_true(error, stat == 0, 'lyapunov exit status 0: '//text)
      call check_true(error, last(1:min(10, len(last))) == 'lyapunov: ', 'last line: '//last)
      if (allocated(error)) return
      read (last(11:), *, iostat=ios) x
      call check_true(error, ios == 0, 'four numbers on the last line: '//last)
      call h5%open(dir//'/l.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/lyapunov/exponents', lam, error)
      if (.not. allocated(error)) call h5%read('/lyapunov/running', run, error)
      if (.not. allocated(error)) call h5%read('/lyapunov/t', tt, error)
      call h5%close()
      if (allocated(error)) return
      call check(error, x, lam, 'printed = stored exponents', rel=1e-6_dp)
      call check_true(error, size(run, 1) == 4 .and. size(run, 2) == size(tt) .and. &
                      size(tt) == 40, 'running estimates (4, 40)')
      call check(error, run(:, size(tt)), lam, 'last running estimate', rel=1e-12_dp)

      stat = run_command(dir, 'divergence --t-end 25 --pairs 2 --lyapunov-t 20 --output '// &
                         dir//'/d.h5')
      call read_text(dir//'/stdout', text, n)
      last = last_line(text)
      call check_true(error, stat == 0, 'divergence exit status 0: '//text)
      call check_true(error, last(1:min(18, len(last))) == 'divergence slope: ', &
                      'last line: '//last)
      if (allocated(error)) return
      read (last(19:), *, iostat=ios) slope
      call check_true(error, ios == 0 .and. slope > 0.0_dp, 'slope > 0: '//last)
      call h5%open(dir//'/d.h5', 'r', error)
      if (allocated(error)) return
      call h5%readattr('/', 'slope', x(1), error)
      if (.not. allocated(error)) call h5%read('/divergence/t', tt, error)
      call h5%close()
      if (allocated(error)) return
      call check(error, slope, x(1), 'printed = stored slope', rel=1e-6_dp)
      call check_true(error, size(tt) == 2501, '2501 samples')

      stat = run_command(dir, 'poincare --ics 3 --points 10 --t-end 100 --output '// &
                         dir//'/p.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'poincare exit status 0: '//text)
      call h5%open(dir//'/p.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/poincare/q', q, error)
      if (.not. allocated(error)) call h5%read('/poincare/p', p, error)
      if (.not. allocated(error)) call h5%read('/poincare/count', cnt, error)
      if (.not. allocated(error)) call h5%readattr('/', 'energy', x(1), error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, size(cnt) == 3 .and. all(cnt == 10) .and. size(q) == 30 .and. &
                      size(p) == 30, '3 orbits of 10 points')
      call check(error, x(1), 0.0_dp, 'energy of the horizontal release', abs=1e-15_dp)

      call write_file(dir//'/c.nml', '&initial q1 = -1.0 /'//new_line('a')// &
                      '&chaos tau = 0.25, vectors = 2 /')
      stat = run_command(dir, 'lyapunov --config '//dir//'/c.nml --t-end 5 --output '// &
                         dir//'/c.h5')
      call read_text(dir//'/stdout', text, n)
      last = last_line(text)
      call check_true(error, stat == 0, 'lyapunov --config exit status 0: '//text)
      call h5%open(dir//'/c.h5', 'r', error)
      if (allocated(error)) return
      call h5%readattr('/', 'tau', tau, error)
      if (.not. allocated(error)) call h5%readattr('/', 'vectors', vectors, error)
      if (.not. allocated(error)) call h5%read('/lyapunov/t', tt, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, tau == 0.25_dp .and. vectors == 2 .and. size(tt) == 20, &
                      '&chaos read: tau = 0.25, vectors = 2')
      read (last(11:), *, iostat=ios) x(1:2)
      call check_true(error, ios == 0, 'two exponents printed: '//last)
      call execute_command_line('rm -rf '//dir)
   contains
      function last_line(s) result(l)
         character(len=*), intent(in) :: s
         character(len=:), allocatable :: l
         integer :: e, b
         e = len(s)
         if (e == 0) then
            l = ''
            return
         end if
         if (s(e:e) == new_line('a')) e = e - 1
         b = index(s(:e), new_line('a'), back=.true.)
         l = s(b + 1:e)
      end function last_line
   end subroutine test_cli_run

   subroutine write_file(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)') text
      close (unit)
   end subroutine write_file
end module test_chaos
