!> Values of the chaos files (the dataset inventory): every dataset that
!> `dpend lyapunov`, `indicators`, `divergence` and `poincare` write is compared
!> with an independent computation made here, for two links and (where the command
!> takes it) a chain of 3 links:
!>
!> - lyapunov: the tangent matrix Φ(t) (library propagation, itself checked against
!>   nearby trajectories in chaos/tangent_vs_nearby_trajectories) is carried here
!>   WITHOUT renormalisation; one Gram–Schmidt QR of Φ(t_j) at each stored time gives
!>   Σ ln R_ii directly (the product of the file's successive QR steps has the same
!>   diagonal), hence the running estimates, the exponents, the batch exponents and
!>   their standard error; the sum of the spectrum is ln det Φ / t ≈ 0 (Liouville);
!> - indicators: from the same unnormalised vectors, ln|δ_i|, FLI = max, SALI,
!>   GALI_j as the square root of the Gram determinant (not a QR), MEGNO by
!>   integration by parts, Y = 2 (L − (1/t) ∫ L ds), and ⟨Y⟩ by the trapezoidal rule
!>   over every step; GALI_2 = SALI (1 − SALI²/4)^½ on the stored values;
!> - divergence: each pair integrated here step by step from the reference orbit,
!>   the partner displaced by δ0 (1, …, 1)/2, |δ(0)| = δ0 √(2N)/2, energies in closed
!>   form (uniform rods, written out here);
!> - poincare: each orbit integrated here from its stored initial state, crossings of
!>   q1 = −π/2 (q̇1 > 0) located by a secant search on the step length, momenta and
!>   energy in closed form.
module test_values_chaos
   use dpend_kinds, only: dp
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t, pendulum_model
   use dpend_chain, only: chain_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator
   use dpend_propagate, only: march_t
   use dpend_tangent, only: tangent_t
   use dpend_indicator_math, only: initial_vectors
   use dpend_hdf5, only: h5file_t
   use dpend_cli, only: to_str
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   use test_cli, only: run_command, scratch_dir, read_text
   implicit none
   private
   public :: collect_values_chaos, energy_cf, momenta_cf, make_model

   real(dp), parameter :: pi = acos(-1.0_dp)
   real(dp), parameter :: g_default = 9.8_dp  !! the commands' default g [m/s²]

   !> Unnormalised tangent vectors Φ(t) V0 at every step end of a run.
   type :: tangent_history_t
      integer :: n = 0                          !! step ends recorded
      real(dp), allocatable :: t(:)             !! their times (n) [s]
      real(dp), allocatable :: v(:, :, :)       !! Φ(t) V0 (m, k, n)
      real(dp), allocatable :: y(:, :)          !! (q, q̇) at each step end (m, n)
   end type tangent_history_t

contains

   !> The suite `values_chaos`.
   subroutine collect_values_chaos(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
              new_unittest('lyapunov_file_values', test_lyapunov), &
              new_unittest('indicators_file_values', test_indicators), &
              new_unittest('divergence_file_values', test_divergence), &
              new_unittest('poincare_file_values', test_poincare)]
   end subroutine collect_values_chaos

   ! ------------------------------------------------------------ closed forms

   !> Mass matrix of a chain of uniform rods (angles from the horizontal), from the
   !> velocity of each rod's centre, v_ck = Σ_j c_kj l_j q̇_j (−sin q_j, cos q_j) with
   !> c = 1 (j < k), 1/2 (j = k), plus the rotation m_k l_k²/12 [kg m²].
   pure function mass_cf(m, l, q) result(mm)
      real(dp), intent(in) :: m(:)   !! masses [kg]
      real(dp), intent(in) :: l(:)   !! lengths [m]
      real(dp), intent(in) :: q(:)   !! angles [rad]
      real(dp) :: mm(size(q), size(q))
      real(dp) :: jx(size(q)), jy(size(q))
      integer :: k, j, n
      n = size(q)
      mm = 0.0_dp
      do k = 1, n
         jx = 0.0_dp; jy = 0.0_dp
         do j = 1, k
            jx(j) = -merge(0.5_dp, 1.0_dp, j == k)*l(j)*sin(q(j))
            jy(j) = merge(0.5_dp, 1.0_dp, j == k)*l(j)*cos(q(j))
         end do
         do j = 1, n
            mm(:, j) = mm(:, j) + m(k)*(jx*jx(j) + jy*jy(j))
         end do
         mm(k, k) = mm(k, k) + m(k)*l(k)**2/12.0_dp
      end do
   end function mass_cf

   !> Energy T + V of a chain of uniform rods of 1 kg, 1 m (the commands' defaults),
   !> V = Σ m_k g y_ck with y up [J].
   pure real(dp) function energy_cf(q, qd) result(e)
      real(dp), intent(in) :: q(:)    !! angles [rad]
      real(dp), intent(in) :: qd(:)   !! angular velocities [rad/s]
      real(dp) :: m(size(q)), l(size(q)), y
      integer :: k
      m = 1.0_dp; l = 1.0_dp
      e = 0.5_dp*dot_product(qd, matmul(mass_cf(m, l, q), qd))
      y = 0.0_dp
      do k = 1, size(q)
         e = e + m(k)*g_default*(y + 0.5_dp*l(k)*sin(q(k)))
         y = y + l(k)*sin(q(k))
      end do
   end function energy_cf

   !> Canonical momenta p = M(q) q̇ of the default chain [kg m²/s].
   pure function momenta_cf(q, qd) result(p)
      real(dp), intent(in) :: q(:)    !! angles [rad]
      real(dp), intent(in) :: qd(:)   !! angular velocities [rad/s]
      real(dp) :: p(size(q))
      real(dp) :: m(size(q)), l(size(q))
      m = 1.0_dp; l = 1.0_dp
      p = matmul(mass_cf(m, l, q), qd)
   end function momenta_cf

   !> The commands' default model of `links` links (1 kg, 1 m, g = 9.8).
   subroutine make_model(links, model)
      integer, intent(in) :: links                        !! number of links
      class(model_t), allocatable, intent(out) :: model   !! the model
      type(error_t), allocatable :: err
      real(dp) :: ones(links)
      ones = 1.0_dp
      if (links == 2) then
         allocate (model, source=pendulum_model(pendulum_t()))
      else
         allocate (model, source=chain_model(ones, ones, g_default, err))
      end if
   end subroutine make_model

   !> ln det M(q) of the default chain, by Cholesky.
   pure real(dp) function log_det_mass(q) result(ld)
      real(dp), intent(in) :: q(:)  !! angles [rad]
      real(dp) :: a(size(q), size(q)), ones(size(q))
      integer :: j, r
      ones = 1.0_dp
      a = mass_cf(ones, ones, q)
      ld = 0.0_dp
      do j = 1, size(q)
         a(j, j) = sqrt(a(j, j) - sum(a(j, 1:j - 1)**2))
         do r = j + 1, size(q)
            a(r, j) = (a(r, j) - sum(a(r, 1:j - 1)*a(j, 1:j - 1)))/a(j, j)
         end do
         ld = ld + 2.0_dp*log(a(j, j))
      end do
   end function log_det_mass

   ! ----------------------------------------------------------------- helpers

   !> Φ(t) V0 at every step end of the rk4 run (step dt) from (q0, q̇0) to t_end.
   subroutine tangent_history(model, q0, qd0, t_end, dt, v0, hist, ok)
      class(model_t), intent(in) :: model      !! the system
      real(dp), intent(in) :: q0(:), qd0(:)    !! initial state [rad, rad/s]
      real(dp), intent(in) :: t_end, dt        !! end time, step [s]
      real(dp), intent(in) :: v0(:, :)         !! initial vectors (2n, k)
      type(tangent_history_t), intent(out) :: hist  !! the history
      logical, intent(out) :: ok               !! every step succeeded
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(tangent_t) :: tan
      type(march_t) :: march
      real(dp) :: t, h
      real(dp), allocatable :: y(:)
      integer :: stat, cap
      call new_integrator('rk4', integ, err)
      ok = .not. allocated(err)
      if (.not. ok) return
      cap = nint(t_end/dt) + 8
      allocate (hist%t(cap), hist%v(size(v0, 1), size(v0, 2), cap), hist%y(size(v0, 1), cap))
      y = integ%to_internal(model, q0, qd0)
      call tan%init(v0)
      t = 0.0_dp; h = dt
      call integ%clear_step()
      call march%start(integ, t, t_end, h)
      do while (.not. march%finished)
         call march%next(integ, model, t, y, h, stat)
         ok = stat == stat_ok .and. hist%n < cap
         if (.not. ok) return
         call tan%propagate(integ, model)
         hist%n = hist%n + 1
         hist%t(hist%n) = t
         hist%v(:, :, hist%n) = tan%v
         call integ%to_physical(model, y, hist%y(1:size(q0), hist%n), hist%y(size(q0) + 1:, &
                                hist%n))
      end do
   end subroutine tangent_history

   !> Index of the recorded step end at time t (0 if none within 1e-9 s).
   pure integer function step_at(hist, t) result(i)
      type(tangent_history_t), intent(in) :: hist  !! the history
      real(dp), intent(in) :: t                    !! time [s]
      i = minloc(abs(hist%t(1:hist%n) - t), dim=1)
      if (abs(hist%t(i) - t) > 1e-9_dp) i = 0
   end function step_at

   !> ln R_ii of the QR decomposition of a (m, k), by classical Gram–Schmidt with
   !> one re-orthogonalisation (CGS2).
   pure function log_r_diag(a) result(lr)
      real(dp), intent(in) :: a(:, :)    !! the vectors (m, k)
      real(dp) :: lr(size(a, 2))
      real(dp) :: q(size(a, 1), size(a, 2)), w(size(a, 1)), c(size(a, 2))
      integer :: j, pass
      do j = 1, size(a, 2)
         w = a(:, j)
         do pass = 1, 2
            if (j > 1) then
               c(1:j - 1) = matmul(w, q(:, 1:j - 1))
               w = w - matmul(q(:, 1:j - 1), c(1:j - 1))
            end if
         end do
         lr(j) = log(norm2(w))
         q(:, j) = w/norm2(w)
      end do
   end function log_r_diag

   !> Run `dpend ARGS --output dir/NAME.h5`; fails the test on a non-zero exit.
   subroutine run_ok(error, dir, args, file)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      character(len=*), intent(in) :: dir                 !! scratch directory
      character(len=*), intent(in) :: args                !! the command line
      character(len=*), intent(in) :: file                !! output file
      character(len=:), allocatable :: text
      integer :: stat, n
      stat = run_command(dir, args//' --output '//file)
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 0, 'dpend '//args//': exit '//to_str(stat)//' '//text)
   end subroutine run_ok

   ! -------------------------------------------------------------------- tests

   !> `dpend lyapunov` (two links, horizontal release; 3 links): every dataset
   !> against the in-process Φ(t) and one QR per stored time.
   subroutine test_lyapunov(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      integer :: links
      dir = scratch_dir('values-lyapunov')
      do links = 2, 3
         call one(links)
         if (allocated(error)) return
      end do
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine one(links)
         integer, intent(in) :: links
         real(dp), parameter :: t_end = 3.0_dp, tau = 0.5_dp, dt = 1e-3_dp
         integer, parameter :: nb = 3
         class(model_t), allocatable :: model
         type(tangent_history_t) :: hist
         type(h5file_t) :: h5
         real(dp), allocatable :: t(:), running(:, :), exponents(:), spread(:), batches(:, :)
         real(dp), allocatable :: run_cf(:, :), sums(:, :), bat_cf(:, :), eye(:, :)
         real(dp), allocatable :: q0(:), mean(:), spread_cf(:)
         integer, allocatable :: perm(:)
         character(len=:), allocatable :: file, tag, extra
         integer :: m, j, i, n, b, jb, jprev
         logical :: ok
         tag = to_str(links)//' links: '
         m = 2*links
         q0 = [(0.1_dp*real(i - 1, dp), i=1, links)]
         extra = ''
         if (links == 3) extra = ' --links 3 --q 0,0.1,0.2'
         if (links == 2) q0 = 0.0_dp
         file = dir//'/l'//to_str(links)//'.h5'
         call run_ok(error, dir, 'lyapunov --t-end 3 --tau 0.5 --batches 3'//extra, file)
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (allocated(error)) return
         call h5%read('/lyapunov/t', t, error)
         if (.not. allocated(error)) call h5%read('/lyapunov/running', running, error)
         if (.not. allocated(error)) call h5%read('/lyapunov/exponents', exponents, error)
         if (.not. allocated(error)) call h5%read('/lyapunov/spread', spread, error)
         if (.not. allocated(error)) call h5%read('/lyapunov/batches', batches, error)
         call h5%close()
         if (allocated(error)) return
         n = nint(t_end/tau)
         call check_true(error, size(t) == n .and. all(shape(running) == [m, n]) .and. &
                         size(exponents) == m .and. size(spread) == m .and. &
                         all(shape(batches) == [m, nb]), tag//'shapes')
         if (allocated(error)) return
         ! t: every tau
         call check(error, t, [(tau*real(j, dp), j=1, n)], tag//'t = j tau', abs=1e-12_dp)
         allocate (eye(m, m))
         eye = 0.0_dp
         do i = 1, m
            eye(i, i) = 1.0_dp
         end do
         call make_model(links, model)
         call tangent_history(model, q0, 0.0_dp*q0, t_end, dt, eye, hist, ok)
         call check_true(error, ok, tag//'in-process run')
         if (allocated(error)) return
         ! Σ ln R_ii at each stored time from one QR of Φ(t_j)
         allocate (sums(m, n), run_cf(m, n))
         do j = 1, n
            i = step_at(hist, t(j))
            call check_true(error, i > 0, tag//'stored time '//to_str(j)//' is a step end')
            if (allocated(error)) return
            sums(:, j) = log_r_diag(hist%v(:, :, i))
            run_cf(:, j) = sums(:, j)/t(j)
         end do
         ! the file orders the exponents by their final values, descending
         perm = [(i, i=1, m)]
         do i = 2, m
            b = perm(i)
            j = i - 1
            do while (j >= 1)
               if (.not. (run_cf(perm(j), n) < run_cf(b, n))) exit
               perm(j + 1) = perm(j)
               j = j - 1
            end do
            perm(j + 1) = b
         end do
         run_cf = run_cf(perm, :)
         sums = sums(perm, :)
         ! measured deviations: 1e-14 (2 links), 3e-13 1/s (3 links), roundoff of the
         ! two QR routes
         call check(error, maxval(abs(running - run_cf)), 0.0_dp, &
                    tag//'running = (1/t) sum ln R_ii of one QR of Phi(t)', abs=3e-12_dp)
         call check(error, exponents, run_cf(:, n), tag//'exponents', abs=3e-12_dp)
         ! Liouville: the flow keeps the volume in (q, p); rk4 carries (q, qdot), p = M qdot,
         ! so ln det Phi = ln det M(q(0)) - ln det M(q(t)) and the spectrum sums to that
         ! over t (measured 4e-10 (2 links), 1.5e-9 1/s (3 links): rk4's truncation, dt = 1e-3 s)
         do j = 1, n
            i = step_at(hist, t(j))
            call check(error, sum(running(:, j)), (log_det_mass(q0) - &
                       log_det_mass(hist%y(1:links, i)))/t(j), &
                       tag//'sum of the running spectrum (Liouville, closed form)', abs=1e-8_dp)
         end do
         call check(error, sum(exponents), (log_det_mass(q0) - &
                    log_det_mass(hist%y(1:links, hist%n)))/t_end, &
                    tag//'sum of the exponents (Liouville)', abs=1e-8_dp)
         ! batches: equal segments of t_end/nb ending at a renormalisation
         allocate (bat_cf(m, nb))
         jprev = 0
         do b = 1, nb
            jb = b*n/nb
            if (jprev == 0) then
               bat_cf(:, b) = sums(:, jb)/t(jb)
            else
               bat_cf(:, b) = (sums(:, jb) - sums(:, jprev))/(t(jb) - t(jprev))
            end if
            jprev = jb
         end do
         ! measured 9e-13 1/s (3 links)
         call check(error, maxval(abs(batches - bat_cf)), 0.0_dp, &
                    tag//'batch exponents from Sigma ln R_ii at the segment ends', abs=1e-11_dp)
         mean = sum(bat_cf, dim=2)/real(nb, dp)
         spread_cf = [(sqrt(sum((bat_cf(i, :) - mean(i))**2)/real(nb - 1, dp)/real(nb, dp)), &
                       i=1, m)]
         ! measured 3e-13 1/s (3 links)
         call check(error, maxval(abs(spread - spread_cf)), 0.0_dp, &
                    tag//'spread = std(batches)/sqrt(n)', abs=3e-12_dp)
      end subroutine one
   end subroutine test_lyapunov

   !> `dpend indicators` (two links, horizontal release; 3 links), sampled every
   !> 0.05 s over 1 s: every dataset from the in-process unnormalised vectors.
   subroutine test_indicators(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      integer :: links
      dir = scratch_dir('values-indicators')
      do links = 2, 3
         call one(links)
         if (allocated(error)) return
      end do
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine one(links)
         integer, intent(in) :: links
         real(dp), parameter :: t_end = 1.0_dp, tau = 0.05_dp, dt = 1e-3_dp
         class(model_t), allocatable :: model
         type(tangent_history_t) :: hist
         type(h5file_t) :: h5
         real(dp), allocatable :: t(:), megno(:), megno_mean(:), fli(:), sali(:), gali(:, :)
         real(dp), allocatable :: log_norm(:, :), megno_vectors(:, :), megno_mean_vectors(:, :)
         real(dp), allocatable :: lcf(:, :), ycf(:, :), ymcf(:, :), q0(:), u(:, :), gram(:, :)
         real(dp), allocatable :: int_l(:), int_y(:), sali_cf(:), gali_cf(:, :)
         character(len=:), allocatable :: file, tag, extra
         integer :: m, n, i, j, s, jj
         real(dp) :: tp, gal
         logical :: ok
         tag = to_str(links)//' links: '
         m = 2*links
         q0 = [(0.1_dp*real(i - 1, dp), i=1, links)]
         extra = ''
         if (links == 3) extra = ' --links 3 --q 0,0.1,0.2'
         if (links == 2) q0 = 0.0_dp
         file = dir//'/i'//to_str(links)//'.h5'
         call run_ok(error, dir, 'indicators --t-end 1 --tau 0.05'//extra, file)
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (allocated(error)) return
         call h5%read('/indicators/t', t, error)
         if (.not. allocated(error)) call h5%read('/indicators/megno', megno, error)
         if (.not. allocated(error)) call h5%read('/indicators/megno_mean', megno_mean, error)
         if (.not. allocated(error)) call h5%read('/indicators/fli', fli, error)
         if (.not. allocated(error)) call h5%read('/indicators/sali', sali, error)
         if (.not. allocated(error)) call h5%read('/indicators/gali', gali, error)
         if (.not. allocated(error)) call h5%read('/indicators/log_norm', log_norm, error)
         if (.not. allocated(error)) call h5%read('/indicators/megno_vectors', &
                                                  megno_vectors, error)
         if (.not. allocated(error)) call h5%read('/indicators/megno_mean_vectors', &
                                                  megno_mean_vectors, error)
         call h5%close()
         if (allocated(error)) return
         n = nint(t_end/tau)
         call check_true(error, size(t) == n .and. size(megno) == n .and. &
                         size(megno_mean) == n .and. size(fli) == n .and. size(sali) == n &
                         .and. all(shape(gali) == [m - 1, n]) .and. &
                         all(shape(log_norm) == [m, n]) .and. &
                         all(shape(megno_vectors) == [m, n]) .and. &
                         all(shape(megno_mean_vectors) == [m, n]), tag//'shapes')
         if (allocated(error)) return
         call check(error, t, [(tau*real(j, dp), j=1, n)], tag//'t = j tau', abs=1e-12_dp)
         call make_model(links, model)
         call tangent_history(model, q0, 0.0_dp*q0, t_end, dt, initial_vectors(m), hist, ok)
         call check_true(error, ok, tag//'in-process run')
         if (allocated(error)) return
         ! L_i = ln |Φ v_i| at every step; Y_i = 2 (L_i - (1/t) ∫ L_i ds) (integration by
         ! parts of (2/t) ∫ s dL); <Y_i> = (1/t) ∫ Y_i ds; trapezoids over the steps
         allocate (lcf(m, hist%n), ycf(m, hist%n), ymcf(m, hist%n), int_l(m), int_y(m))
         int_l = 0.0_dp; int_y = 0.0_dp; tp = 0.0_dp
         do s = 1, hist%n
            lcf(:, s) = [(log(norm2(hist%v(:, i, s))), i=1, m)]
            if (s == 1) then
               int_l = 0.5_dp*(hist%t(s) - tp)*lcf(:, s)
            else
               int_l = int_l + 0.5_dp*(hist%t(s) - tp)*(lcf(:, s - 1) + lcf(:, s))
            end if
            ycf(:, s) = 2.0_dp*(lcf(:, s) - int_l/hist%t(s))
            if (s == 1) then
               int_y = 0.5_dp*(hist%t(s) - tp)*ycf(:, s)
            else
               int_y = int_y + 0.5_dp*(hist%t(s) - tp)*(ycf(:, s - 1) + ycf(:, s))
            end if
            ymcf(:, s) = int_y/hist%t(s)
            tp = hist%t(s)
         end do
         allocate (sali_cf(n), gali_cf(m - 1, n), u(m, m), gram(m, m))
         do j = 1, n
            s = step_at(hist, t(j))
            call check_true(error, s > 0, tag//'sample '//to_str(j)//' is a step end')
            if (allocated(error)) return
            ! measured deviations (both link counts): log_norm, fli 9e-15, megno 1.2e-14,
            ! megno_mean 3e-15
            call check(error, log_norm(:, j), lcf(:, s), tag//'log_norm = ln|Phi v_i|', &
                       abs=1e-13_dp)
            call check(error, fli(j), maxval(lcf(:, s)), tag//'fli = max_i ln|Phi v_i|', &
                       abs=1e-13_dp)
            call check(error, megno_vectors(:, j), ycf(:, s), &
                       tag//'megno_vectors = 2 (L - mean L)', abs=1e-13_dp)
            call check(error, megno(j), ycf(1, s), tag//'megno of vector 1', abs=1e-13_dp)
            call check(error, megno_mean_vectors(:, j), ymcf(:, s), &
                       tag//'megno_mean_vectors = (1/t) int Y', abs=3e-14_dp)
            call check(error, megno_mean(j), ymcf(1, s), tag//'megno_mean of vector 1', &
                       abs=3e-14_dp)
            do i = 1, m
               u(:, i) = hist%v(:, i, s)/norm2(hist%v(:, i, s))
            end do
            sali_cf(j) = min(norm2(u(:, 1) + u(:, 2)), norm2(u(:, 1) - u(:, 2)))
            ! GALI_jj = sqrt(det G), G the Gram matrix of u_1 .. u_jj (Cholesky)
            gram = matmul(transpose(u), u)
            gal = 1.0_dp
            do jj = 1, m
               call cholesky_column(gram, jj)
               gal = gal*gram(jj, jj)
               if (jj >= 2) gali_cf(jj - 1, j) = gal
            end do
            if (allocated(error)) return
         end do
         ! measured: sali 3.6e-15, gali 2.7e-15 (Gram determinant against the file's QR)
         call check(error, sali, sali_cf, tag//'sali = min(|u1 + u2|, |u1 - u2|)', &
                    abs=3e-14_dp)
         do j = 1, n
            call check(error, gali(:, j), gali_cf(:, j), tag//'gali = sqrt(det Gram)', &
                       abs=3e-14_dp)
         end do
         ! GALI_2 = |u1||u2| sin(theta) = SALI sqrt(1 - SALI^2/4) on the stored values
         ! (measured 4.4e-16)
         call check(error, gali(1, :), sali*sqrt(1.0_dp - sali**2/4.0_dp), &
                    tag//'GALI_2 = SALI sqrt(1 - SALI^2/4)', abs=5e-15_dp)
      end subroutine one

      !> Column jj of the Cholesky factor of g in place (lower triangle, g(jj, jj) the
      !> diagonal element), the columns before it done.
      pure subroutine cholesky_column(g, jj)
         real(dp), intent(inout) :: g(:, :)
         integer, intent(in) :: jj
         integer :: r
         g(jj, jj) = sqrt(g(jj, jj) - sum(g(jj, 1:jj - 1)**2))
         do r = jj + 1, size(g, 1)
            g(r, jj) = (g(r, jj) - sum(g(r, 1:jj - 1)*g(jj, 1:jj - 1)))/g(jj, jj)
         end do
      end subroutine cholesky_column
   end subroutine test_indicators

   !> `dpend divergence` (two links, horizontal release; 3 links), 3 pairs 0.5 s
   !> apart, 1 s each, sampled every 0.05 s: every pair integrated here.
   subroutine test_divergence(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      integer :: links
      dir = scratch_dir('values-divergence')
      do links = 2, 3
         call one(links)
         if (allocated(error)) return
      end do
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine one(links)
         integer, intent(in) :: links
         real(dp), parameter :: t_end = 1.0_dp, out_dt = 0.05_dp, dt = 1e-3_dp, &
                                spacing = 0.5_dp, delta0 = 1e-9_dp
         integer, parameter :: pairs = 3
         class(model_t), allocatable :: model
         class(integrator_t), allocatable :: integ
         type(h5file_t) :: h5
         real(dp), allocatable :: t(:), log10_delta(:), log10_delta_pairs(:, :), start(:, :)
         real(dp), allocatable :: delta_start(:), energy_difference(:), q0(:)
         real(dp), allocatable :: ref(:), ya(:), yb(:), lcf(:, :)
         character(len=:), allocatable :: file, tag, extra
         integer :: m, n, i, p, s, stat, per
         real(dp) :: tt, h
         tag = to_str(links)//' links: '
         m = 2*links
         q0 = [(0.1_dp*real(i - 1, dp), i=1, links)]
         extra = ''
         if (links == 3) extra = ' --links 3 --q 0,0.1,0.2'
         if (links == 2) q0 = 0.0_dp
         file = dir//'/d'//to_str(links)//'.h5'
         call run_ok(error, dir, 'divergence --t-end 1 --pairs 3 --pair-spacing 0.5 ' &
                     //'--output-dt 0.05 --lyapunov-t 0.5'//extra, file)
         if (allocated(error)) return
         call h5%open(file, 'r', error)
         if (allocated(error)) return
         call h5%read('/divergence/t', t, error)
         if (.not. allocated(error)) call h5%read('/divergence/log10_delta', log10_delta, error)
         if (.not. allocated(error)) call h5%read('/divergence/log10_delta_pairs', &
                                                  log10_delta_pairs, error)
         if (.not. allocated(error)) call h5%read('/divergence/start', start, error)
         if (.not. allocated(error)) call h5%read('/divergence/delta_start', delta_start, error)
         if (.not. allocated(error)) call h5%read('/divergence/energy_difference', &
                                                  energy_difference, error)
         call h5%close()
         if (allocated(error)) return
         n = nint(t_end/out_dt) + 1
         call check_true(error, size(t) == n .and. size(log10_delta) == n .and. &
                         all(shape(log10_delta_pairs) == [pairs, n]) .and. &
                         all(shape(start) == [m, pairs]) .and. size(delta_start) == pairs &
                         .and. size(energy_difference) == pairs, tag//'shapes')
         if (allocated(error)) return
         call check(error, t, [(out_dt*real(i - 1, dp), i=1, n)], tag//'t = (i-1) output_dt', &
                    abs=1e-12_dp)
         if (allocated(error)) return   ! new_integrator's error is intent(out)
         call make_model(links, model)
         call new_integrator('rk4', integ, error)
         if (allocated(error)) return
         per = nint(out_dt/dt)
         ! the reference orbit from the initial state (rk4's internal state is (q, qdot))
         ref = [q0, 0.0_dp*q0]
         tt = 0.0_dp
         allocate (lcf(pairs, n))
         do p = 1, pairs
            if (p > 1) then
               do s = 1, nint(spacing/dt)
                  h = dt
                  call integ%step(model, tt, ref, h, stat)
               end do
            end if
            ! the same rk4 steps: measured 0 (bit for bit)
            call check(error, start(:, p), ref, tag//'start of pair '//to_str(p)// &
                       ' on the reference orbit', abs=1e-13_dp)
            ! partner: displaced by delta0 (1, ..., 1)/2
            ya = start(:, p)
            yb = ya + 0.5_dp*delta0
            ! measured 7e-8 relative (roundoff of a difference of 1e-9)
            call check(error, delta_start(p), delta0*sqrt(real(m, dp))/2.0_dp, &
                       tag//'delta_start = delta0 sqrt(2N)/2', rel=1e-6_dp)
            ! measured 7e-15 J
            call check(error, energy_difference(p), &
                       energy_cf(yb(1:links), yb(links + 1:)) - &
                       energy_cf(ya(1:links), ya(links + 1:)), &
                       tag//'energy_difference in closed form', abs=1e-13_dp)
            lcf(p, 1) = log10(dist(ya, yb))
            do i = 2, n
               do s = 1, per
                  h = dt
                  call integ%step(model, tt, ya, h, stat)
                  if (stat /= stat_ok) exit
                  h = dt
                  call integ%step(model, tt, yb, h, stat)
                  if (stat /= stat_ok) exit
               end do
               call check_true(error, stat == stat_ok, tag//'in-process pair run')
               if (allocated(error)) return
               lcf(p, i) = log10(dist(ya, yb))
            end do
            if (allocated(error)) return
         end do
         ! the same rk4 steps as the file's: measured 0 (bit for bit); the tolerance
         ! allows the roundoff of a 1e-9 difference (3e-8 relative, 1e-8 in log10)
         call check(error, maxval(abs(log10_delta_pairs - lcf)), 0.0_dp, &
                    tag//'log10_delta_pairs from the pairs run here', abs=1e-7_dp)
         call check(error, log10_delta, sum(lcf, dim=1)/real(pairs, dp), &
                    tag//'log10_delta = mean over the pairs', abs=1e-7_dp)
         call check(error, log10_delta, sum(log10_delta_pairs, dim=1)/real(pairs, dp), &
                    tag//'log10_delta = mean of the stored pairs', abs=1e-12_dp)
      end subroutine one

      !> Distance in (q, qdot) with the angle differences wrapped to (-pi, pi].
      pure real(dp) function dist(a, b)
         real(dp), intent(in) :: a(:), b(:)
         real(dp) :: d(size(a))
         integer :: nq
         nq = size(a)/2
         d = b - a
         d(1:nq) = d(1:nq) - 2.0_dp*pi*anint(d(1:nq)/(2.0_dp*pi))
         dist = norm2(d)
      end function dist
   end subroutine test_divergence

   !> `dpend poincare` (two links, horizontal release: E = 0), 3 orbits of up to 6
   !> points over 6 s: each orbit integrated here from its stored initial state.
   subroutine test_poincare(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      real(dp), parameter :: dt = 1e-3_dp, t_end = 6.0_dp, angle = -0.5_dp*pi
      integer, parameter :: points = 6
      character(len=:), allocatable :: dir, file
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(h5file_t) :: h5
      real(dp), allocatable :: q(:), p(:), t(:), energy(:), initial_q(:, :), initial_qdot(:, :)
      integer, allocatable :: orbit(:), count(:), orbit_status(:)
      real(dp), allocatable :: qcf(:), pcf(:), tcf(:), ecf(:)
      integer, allocatable :: orbit_cf(:), count_cf(:), status_cf(:)
      real(dp) :: e_attr, y(4), yp(4), tt, h, s_lo, s_hi, s, g_lo, g_hi, g, ys(4), ts, pm(2)
      real(dp) :: tprev
      integer :: o, n_orb, stat, it, k, nstep
      dir = scratch_dir('values-poincare')
      file = dir//'/p.h5'
      call run_ok(error, dir, 'poincare --t-end 6 --ics 3 --points 6', file)
      if (allocated(error)) return
      call h5%open(file, 'r', error)
      if (allocated(error)) return
      call h5%read('/poincare/q', q, error)
      if (.not. allocated(error)) call h5%read('/poincare/p', p, error)
      if (.not. allocated(error)) call h5%read('/poincare/t', t, error)
      if (.not. allocated(error)) call h5%read('/poincare/energy', energy, error)
      if (.not. allocated(error)) call h5%read('/poincare/orbit', orbit, error)
      if (.not. allocated(error)) call h5%read('/poincare/count', count, error)
      if (.not. allocated(error)) call h5%read('/poincare/orbit_status', orbit_status, error)
      if (.not. allocated(error)) call h5%read('/poincare/initial_q', initial_q, error)
      if (.not. allocated(error)) call h5%read('/poincare/initial_qdot', initial_qdot, error)
      if (.not. allocated(error)) call h5%readattr('/', 'energy', e_attr, error)
      call h5%close()
      if (allocated(error)) return
      n_orb = size(count)
      call check_true(error, n_orb == 3 .and. size(orbit_status) == 3 .and. &
                      all(shape(initial_q) == [2, 3]) .and. &
                      all(shape(initial_qdot) == [2, 3]), '3 orbits')
      if (allocated(error)) return
      ! the section energy: that of the horizontal release at rest, in closed form
      call check(error, e_attr, energy_cf([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp]), &
                 'energy of the initial state', abs=1e-14_dp)
      if (allocated(error)) return   ! new_integrator's error is intent(out)
      call make_model(2, model)
      call new_integrator('rk4', integ, error)
      if (allocated(error)) return
      allocate (qcf(0), pcf(0), tcf(0), ecf(0), orbit_cf(0), count_cf(n_orb), status_cf(n_orb))
      do o = 1, n_orb
         ! initial states: on the section, crossing upward, on the energy shell
         call check(error, sin(initial_q(1, o) - angle), 0.0_dp, 'initial q1 on the section', &
                    abs=1e-14_dp)
         call check_true(error, cos(initial_q(1, o) - angle) > 0.0_dp .and. &
                         initial_qdot(1, o) > 0.0_dp, 'initial state crosses upward')
         call check(error, energy_cf(initial_q(:, o), initial_qdot(:, o)), e_attr, &
                    'initial_q, initial_qdot on the energy shell', abs=1e-12_dp)
         ! the initial state is the first point
         call add_point(0.0_dp, [initial_q(:, o), initial_qdot(:, o)])
         count_cf(o) = 1
         y = [initial_q(:, o), initial_qdot(:, o)]
         tt = 0.0_dp
         stat = stat_ok
         nstep = nint(t_end/dt)
         do k = 1, nstep
            if (count_cf(o) == points) exit
            yp = y
            tprev = tt
            h = dt
            call integ%step(model, tt, y, h, stat)
            if (stat /= stat_ok) exit
            g_lo = wrapped(yp(1) - angle); g_hi = wrapped(y(1) - angle)
            if (.not. (g_lo < 0.0_dp .and. g_hi >= 0.0_dp .and. g_hi - g_lo < 1.0_dp)) cycle
            ! secant with bracketing on the length s of one step from yp
            s_lo = 0.0_dp; s_hi = dt
            s = dt
            do it = 1, 60
               s = s_lo - g_lo*(s_hi - s_lo)/(g_hi - g_lo)
               ys = yp; ts = 0.0_dp; h = s
               call integ%step(model, ts, ys, h, stat)
               g = wrapped(ys(1) - angle)
               if (abs(g) < 1e-15_dp) exit
               if (g < 0.0_dp) then
                  s_lo = s; g_lo = g
               else
                  s_hi = s; g_hi = g
               end if
            end do
            call add_point(tprev + s, ys)
            count_cf(o) = count_cf(o) + 1
         end do
         status_cf(o) = stat
         orbit_cf = [orbit_cf, (o, k=1, count_cf(o))]
      end do
      call check_true(error, all(count == count_cf), 'count = crossings found here: '// &
                      to_str(count(1))//' '//to_str(count_cf(1)))
      call check_true(error, all(orbit_status == status_cf) .and. all(status_cf == stat_ok), &
                      'orbit_status = status of the run here (0)')
      if (allocated(error)) return
      call check_true(error, size(orbit) == size(orbit_cf), 'points')
      if (allocated(error)) return
      call check_true(error, all(orbit == orbit_cf), 'orbit = 1 .. n_orbits, count(o) each')
      ! measured: t 3.3e-13 s, q 3.6e-15 rad, p 5.8e-15 kg m^2/s, energy 1.6e-14 J (the
      ! file's located crossing against a partial rk4 step), conservation 5.6e-8 J
      call check(error, t, tcf, 't of the crossings', abs=3e-12_dp)
      call check(error, q, qcf, 'q (other link, wrapped)', abs=1e-13_dp)
      call check(error, p, pcf, 'p = M qdot of the other link', abs=1e-13_dp)
      call check(error, energy, ecf, 'energy at the crossing in closed form', abs=1e-13_dp)
      call check(error, maxval(abs(energy - e_attr)), 0.0_dp, &
                 'energy conserved on the section (rk4, dt = 1e-3 s)', abs=5e-7_dp)
      call execute_command_line('rm -rf '//dir)
   contains
      pure real(dp) function wrapped(x)
         real(dp), intent(in) :: x
         wrapped = x - 2.0_dp*pi*anint(x/(2.0_dp*pi))
      end function wrapped

      subroutine add_point(tc, yc)
         real(dp), intent(in) :: tc, yc(4)
         pm = momenta_cf(yc(1:2), yc(3:4))
         qcf = [qcf, wrapped(yc(2))]
         pcf = [pcf, pm(2)]
         tcf = [tcf, tc]
         ecf = [ecf, energy_cf(yc(1:2), yc(3:4))]
      end subroutine add_point
   end subroutine test_poincare
end module test_values_chaos
