!> Chaos indicators (dpend_indicators): SALI and GALI against closed-form
!> geometry, MEGNO's accumulation against its integrated-by-parts form, and the
!> known behaviours on the double pendulum: a regular orbit (<Y> → 2, GALI_2
!> bounded, GALI_3 ∝ t^-2, GALI_4 ∝ t^-4, |δ| ∝ t) and the chaotic horizontal
!> release (<Y> ≈ λ1 t/2, GALI_2 ∝ exp(-(λ1 - λ2) t), FLI ≈ λ1 t, the rates
!> compared with the spectrum of `lyapunov_spectrum` along the same orbit).
module test_indicators
   use dpend_kinds, only: dp
   use dpend_pendulum, only: pendulum_t, pendulum_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_names, method_options_t
   use dpend_indicators, only: indicators_result_t, chaos_indicators, gali, sali, &
                               initial_vectors
   use dpend_lyapunov, only: lyapunov_result_t, lyapunov_spectrum
   use dpend_fit, only: loglog_fit, fit_t
   use dpend_error, only: error_t
   use testing, only: unittest_t, new_unittest, check, check_true
   use dpend_hdf5, only: h5file_t
   use test_cli, only: run_command, scratch_dir, read_text, expect_rejected
   implicit none
   private
   public :: collect_indicators, line_slope

   real(dp), parameter :: pi = acos(-1.0_dp)
   !> the regular orbit: both links 1 rad from the hanging state, at rest
   real(dp), parameter :: q_regular(2) = [-0.5_dp*pi + 1.0_dp, -0.5_dp*pi + 1.0_dp]

contains

   subroutine collect_indicators(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('sali_gali_geometry', test_geometry), &
               new_unittest('megno_fli_upright_all_methods', test_megno_upright), &
               new_unittest('regular_orbit', test_regular), &
               new_unittest('chaotic_orbit_rates', test_chaotic), &
               new_unittest('command_bad_input', test_cli_bad), &
               new_unittest('command_run', test_cli_run)]
   end subroutine collect_indicators

   !> Least-squares slope of y against x over the points with x in [x0, x1].
   pure real(dp) function line_slope(x, y, x0, x1) result(s)
      real(dp), intent(in) :: x(:), y(:), x0, x1
      logical :: m(size(x))
      real(dp) :: mx, my
      integer :: n
      m = x >= x0 .and. x <= x1
      n = count(m)
      mx = sum(x, mask=m)/n; my = sum(y, mask=m)/n
      s = sum((x - mx)*(y - my), mask=m)/sum((x - mx)**2, mask=m)
   end function line_slope

   !> Unit vectors at angle θ: GALI_2 = sin θ, SALI = 2 sin(θ/2) (θ ≤ π/2);
   !> GALI_3 = √det(AᵀA) (Gram determinant by hand); orthonormal sets give 1;
   !> the lengths of the vectors do not matter.
   subroutine test_geometry(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: v(4, 4), a(4, 3), g, gram(3, 3), det, th
      integer :: info, j
      v = initial_vectors(4)
      call check(error, maxval(abs(matmul(transpose(v), v) - eye4())), 0.0_dp, &
                 'initial vectors orthonormal', abs=1e-15_dp)
      call check_true(error, all(abs(v) > 1e-3_dp), 'initial vectors in general position')
      do j = 2, 4
         call gali(v(:, 1:j), g, info)
         call check(error, g, 1.0_dp, 'GALI of an orthonormal set', abs=1e-14_dp)
      end do
      do j = 1, 5
         th = 0.3_dp*real(j, dp)
         a(:, 1) = [1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]*3.0_dp
         a(:, 2) = [cos(th), sin(th), 0.0_dp, 0.0_dp]*0.2_dp
         call gali(a(:, 1:2), g, info)
         call check(error, g, sin(th), 'GALI_2 = sin(theta)', abs=1e-14_dp)
         call check(error, sali(a(:, 1), a(:, 2)), 2.0_dp*sin(0.5_dp*min(th, pi - th)), &
                    'SALI = 2 sin(theta/2)', abs=1e-14_dp)
      end do
      a(:, 1) = [1.0_dp, 2.0_dp, -1.0_dp, 0.5_dp]
      a(:, 2) = [0.3_dp, -1.0_dp, 2.0_dp, 1.0_dp]
      a(:, 3) = [2.0_dp, 0.1_dp, 0.4_dp, -3.0_dp]
      do j = 1, 3
         a(:, j) = a(:, j)/norm2(a(:, j))
      end do
      gram = matmul(transpose(a), a)
      det = gram(1, 1)*(gram(2, 2)*gram(3, 3) - gram(2, 3)*gram(3, 2)) &
            - gram(1, 2)*(gram(2, 1)*gram(3, 3) - gram(2, 3)*gram(3, 1)) &
            + gram(1, 3)*(gram(2, 1)*gram(3, 2) - gram(2, 2)*gram(3, 1))
      call gali(7.0_dp*a, g, info)
      call check(error, g, sqrt(det), 'GALI_3 = sqrt(Gram determinant)', rel=1e-13_dp)
   contains
      pure function eye4() result(e)
         real(dp) :: e(4, 4)
         integer :: i
         e = 0.0_dp
         do i = 1, 4
            e(i, i) = 1.0_dp
         end do
      end function eye4
   end subroutine test_geometry

   !> Exponential growth in closed form, with every method: at the upright
   !> equilibrium (both links up, at rest) the tangent flow is linear with the
   !> exponents ±μ1, ±μ2 (test_chaos's upright test), so ln|δ| = μ1 t + c + o(1)
   !> and Y(t) = μ1 t + O(1/t), <Y>(t) = μ1 t/2 + O(ln t/t): the slopes of Y
   !> and <Y> over [t ≥ 3 s, 4 s] are μ1 and μ1/2, and FLI grows by μ1. Also FLI is the
   !> largest log-norm, and GALI_2 = SALI √(1 - SALI²/4) (the two from one pair).
   subroutine test_megno_upright(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: names
      character(len=16) :: name
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(pendulum_t) :: par
      type(indicators_result_t) :: r
      real(dp) :: mu1
      integer :: p, q, stat, i2, i3
      mu1 = sqrt((3.0_dp + 6.0_dp/sqrt(7.0_dp))*par%g/par%l1)
      names = method_names()//' '
      p = 1
      do while (p <= len_trim(names))
         q = index(names(p:), ' ') + p - 1
         name = names(p:q - 1)
         p = q + 1
         call new_integrator(trim(name), integ, err, method_options_t(rtol=1e-10_dp, &
                             atol=1e-12_dp))
         call chaos_indicators(integ, pendulum_model(par), 0.0_dp, integ%to_internal( &
                               pendulum_model(par), [0.5_dp*pi, 0.5_dp*pi], [0.0_dp, 0.0_dp]), &
                               4.0_dp, 1e-3_dp, 0.25_dp, r, stat)
         call check_true(error, stat == stat_ok, trim(name)//': run')
         if (allocated(error)) return
         ! (adaptive methods take long steps near the equilibrium: samples at their ends)
         i3 = r%n
         i2 = findloc(r%t >= 3.0_dp, .true., dim=1)
         call check_true(error, i2 < i3 .and. r%t(i3) == 4.0_dp, trim(name)//': samples')
         if (allocated(error)) return
         call check(error, (r%megno_all(:, i3) - r%megno_all(:, i2))/(r%t(i3) - r%t(i2)), &
                    spread(mu1, 1, 4), trim(name)//': slope of Y = mu1', rel=2e-2_dp)
         call check(error, (r%mean_all(:, i3) - r%mean_all(:, i2))/(r%t(i3) - r%t(i2)), &
                    spread(0.5_dp*mu1, 1, 4), trim(name)//': slope of <Y> = mu1/2', &
                    rel=5e-2_dp)
         call check(error, (r%fli(i3) - r%fli(i2))/(r%t(i3) - r%t(i2)), mu1, &
                    trim(name)//': slope of FLI = mu1', rel=1e-3_dp)
         call check(error, r%fli, maxval(r%log_norm, dim=1), trim(name)// &
                    ': FLI = max ln|delta_i|', abs=0.0_dp)
         call check(error, r%gali(1, :), r%sali*sqrt(1.0_dp - 0.25_dp*r%sali**2), &
                    trim(name)//': GALI_2 = SALI sqrt(1 - SALI^2/4)', abs=1e-12_dp)
         if (allocated(error)) return
      end do
   end subroutine test_megno_upright

   !> Regular orbit (both links 1 rad from the hanging state, at rest; its GALI_3
   !> and GALI_4 fall as powers of t), 1000 s, rk4 with dt = 1e-2 s.
   subroutine test_regular(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(pendulum_t) :: par
      type(indicators_result_t) :: r
      type(fit_t) :: f3, f4, ff
      integer :: stat
      real(dp), allocatable :: ym(:)
      call new_integrator('rk4', integ, err)
      call chaos_indicators(integ, pendulum_model(par), 0.0_dp, integ%to_internal( &
                            pendulum_model(par), q_regular, [0.0_dp, 0.0_dp]), 1000.0_dp, &
                            1e-2_dp, 0.5_dp, r, stat)
      call check_true(error, stat == stat_ok, 'run')
      if (allocated(error)) return
      ym = r%megno_mean()
      f3 = loglog_fit(r%t, r%gali(2, :), x_min=100.0_dp)
      f4 = loglog_fit(r%t, r%gali(3, :), x_min=100.0_dp)
      ff = loglog_fit(r%t, exp(r%fli), x_min=100.0_dp)
      write (*, '(a, f8.4, a, 4f8.4, a, es10.3, a, 3f8.4)') '    <Y>(1000 s) = ', ym(r%n), &
         ' (all vectors:', r%mean_all(:, r%n), '); min GALI_2 (t > 100 s) = ', &
         minval(r%gali(1, :), mask=r%t > 100.0_dp), '; exponents GALI_3, GALI_4, |delta| ', &
         f3%slope, f4%slope, ff%slope
      call check(error, ym(r%n), 2.0_dp, '<Y> at t = 1000 s', abs=0.05_dp)
      call check_true(error, minval(r%gali(1, :), mask=r%t > 100.0_dp) > 1e-3_dp, &
                      'GALI_2 bounded away from 0')
      call check(error, f3%slope, -2.0_dp, 'GALI_3 ~ t^-2', abs=0.3_dp)
      call check(error, f4%slope, -4.0_dp, 'GALI_4 ~ t^-4', abs=0.3_dp)
      call check(error, ff%slope, 1.0_dp, 'exp(FLI) = max |delta_i| ~ t', abs=0.3_dp)
   end subroutine test_regular

   !> The chaotic horizontal release (q = 0, 0 at rest), rk4 with dt = 1e-2 s, and
   !> its Lyapunov spectrum over 1000 s (`lyapunov_spectrum`, same method and step):
   !> the slope of <Y> over [100, 1000] s is λ1/2, that of FLI λ1; GALI_2, which
   !> reaches roundoff within ~40 s, is restarted every 50 s along the orbit and
   !> the mean of the 20 fitted decay rates (while 1e-12 < GALI_2 < 0.1) is λ1 - λ2.
   subroutine test_chaotic(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(pendulum_t) :: par
      type(indicators_result_t) :: r
      type(lyapunov_result_t) :: lr
      integer :: stat, seg, i1, i2
      real(dp) :: y(4), lam(4), s_megno, s_fli, rate, rates(20)
      call new_integrator('rk4', integ, err)
      y = integ%to_internal(pendulum_model(par), [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp])
      call lyapunov_spectrum(integ, pendulum_model(par), 0.0_dp, y, 1000.0_dp, 1e-2_dp, &
                             0.5_dp, 4, 10, lr, stat)
      call check_true(error, stat == stat_ok, 'lyapunov run')
      call chaos_indicators(integ, pendulum_model(par), 0.0_dp, y, 1000.0_dp, 1e-2_dp, &
                            0.5_dp, r, stat)
      call check_true(error, stat == stat_ok, 'indicators run')
      if (allocated(error)) return
      lam = lr%exponents
      s_megno = line_slope(r%t, r%megno_mean(), 100.0_dp, 1000.0_dp)
      s_fli = line_slope(r%t, r%fli, 100.0_dp, 1000.0_dp)
      do seg = 1, 20
         call chaos_indicators(integ, pendulum_model(par), 0.0_dp, y, 50.0_dp, 1e-2_dp, &
                               0.1_dp, r, stat)
         call check_true(error, stat == stat_ok, 'segment run')
         if (allocated(error)) return
         y = r%y
         i1 = findloc(r%gali(1, :) < 0.1_dp, .true., dim=1)
         i2 = findloc(r%gali(1, :) < 1e-12_dp, .true., dim=1) - 1
         if (i2 < 0) i2 = r%n
         rates(seg) = -line_slope(r%t, log(max(r%gali(1, :), tiny(1.0_dp))), r%t(i1), r%t(i2))
      end do
      rate = sum(rates)/20.0_dp
      write (*, '(a, 4f8.4, a, f8.4, a, f8.4, a, f8.4, a, f8.4)') '    spectrum ', lam, &
         '; <Y> slope ', s_megno, ' (lambda1/2 ', 0.5_dp*lam(1), '); FLI slope ', s_fli, &
         '; GALI_2 rate ', rate
      write (*, '(a, 10f6.2)') '    GALI_2 segment rates: ', rates(1:10)
      write (*, '(a, 10f6.2)') '                          ', rates(11:20)
      call check(error, s_megno, 0.5_dp*lam(1), 'slope of <Y> = lambda1/2', rel=0.1_dp)
      call check(error, s_fli, lam(1), 'slope of FLI = lambda1', rel=0.1_dp)
      call check(error, rate, lam(1) - lam(2), 'GALI_2 rate = lambda1 - lambda2', rel=0.1_dp)
   end subroutine test_chaotic

   subroutine test_cli_bad(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('indbad')
      call expect_rejected(error, dir, 'indicators', '--tau 0', 'tau')
      call expect_rejected(error, dir, 'indicators', '--tau 1e-4', 'tau')
      call expect_rejected(error, dir, 'indicators', '--t-end 0', 't_end')
      call expect_rejected(error, dir, 'indicators', '--vectors 2', 'unknown option')
      call expect_rejected(error, dir, 'indicators', '--method nosuch', 'method')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_cli_bad

   !> `dpend indicators` on the chaotic release (20 s) and on a 3-link chain (5 s):
   !> the scripting line holds the stored final values; the datasets' shapes.
   subroutine test_cli_run(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, last
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), ym(:), fli(:), sa(:), ga(:, :), ln(:, :)
      real(dp) :: x(6), x6(8)
      integer :: stat, n, ios
      dir = scratch_dir('indrun')
      stat = run_command(dir, 'indicators --t-end 20 --output '//dir//'/i.h5')
      call read_text(dir//'/stdout', text, n)
      last = text(index(text(:len(text) - 1), new_line('a'), back=.true.) + 1:len(text) - 1)
      call check_true(error, stat == 0, 'exit status 0: '//text)
      call check_true(error, index(last, 'indicators: ') == 1, 'last line: '//last)
      if (allocated(error)) return
      read (last(13:), *, iostat=ios) x
      call check_true(error, ios == 0, 'six numbers on the last line: '//last)
      call h5%open(dir//'/i.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/indicators/t', t, error)
      if (.not. allocated(error)) call h5%read('/indicators/megno_mean', ym, error)
      if (.not. allocated(error)) call h5%read('/indicators/fli', fli, error)
      if (.not. allocated(error)) call h5%read('/indicators/sali', sa, error)
      if (.not. allocated(error)) call h5%read('/indicators/gali', ga, error)
      if (.not. allocated(error)) call h5%read('/indicators/log_norm', ln, error)
      call h5%close()
      if (allocated(error)) return
      n = size(t)
      call check_true(error, n == 40 .and. size(ga, 1) == 3 .and. size(ga, 2) == 40 .and. &
                      size(ln, 1) == 4, 'shapes: 40 samples, GALI_2..4, 4 log-norms')
      if (allocated(error)) return
      call check(error, x, [ym(n), fli(n), sa(n), ga(:, n)], 'printed = stored', rel=1e-6_dp)
      call check_true(error, ym(n) > 5.0_dp .and. fli(n) > 10.0_dp .and. ga(1, n) < 1e-4_dp, &
                      'chaotic: <Y> > 5, FLI > 10, GALI_2 < 1e-4')
      stat = run_command(dir, 'indicators --links 3 --t-end 5 --output '//dir//'/c.h5')
      call read_text(dir//'/stdout', text, n)
      last = text(index(text(:len(text) - 1), new_line('a'), back=.true.) + 1:len(text) - 1)
      call check_true(error, stat == 0, '3 links: exit status 0: '//text)
      if (allocated(error)) return
      read (last(13:), *, iostat=ios) x6
      call check_true(error, ios == 0, '3 links: eight numbers (GALI_2 .. GALI_6): '//last)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_cli_run
end module test_indicators
