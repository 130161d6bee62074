!> Values of the study file (the dataset inventory): a tiny study is run
!> in process and written by the study command's writer, and every dataset of the
!> file is compared with an independent computation made here:
!>
!> - grids (steps, tolerances, time bins, sample steps, ω) from their closed forms;
!> - the reference states from a second method (dop853 at rtol 1e-13) run here;
!> - every point of every sweep run again here, one trajectory at a time, with the
!>   energy in closed form (uniform rods, test_values_chaos): global error, energy
!>   errors, bins, counters, mean steps, status; the drift exponents and their
!>   standard errors by a least-squares line written here;
!> - the roundoff runs again, with H in quadruple precision from a closed form
!>   written here; the RMS over the runs from those errors;
!> - the Tao runs again;
!> - wall times bounded by the elapsed time of the whole study, measured here;
!> - the namelist read back gives the configuration the test set; the summary's
!>   orders are least-squares slopes of the stored errors computed here.
module test_values_study
   use, intrinsic :: iso_fortran_env, only: qp => real128
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use dpend_kinds, only: dp, i8
   use dpend_model, only: model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_symplectic, only: symplectic_t
   use dpend_propagate, only: march_t
   use dpend_hdf5, only: h5file_t
   use dpend_cli, only: to_str
   use dpend_study_settings, only: study_config_t, study_defaults, validate_study_config
   use dpend_study_config, only: read_study_config
   use dpend_study, only: study_result_t, run_study
   use dpend_study_command, only: write_study_h5
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, tiny_study_config
   use test_cli, only: scratch_dir
   use test_values_chaos, only: energy_cf, momenta_cf, make_model
   implicit none
   private
   public :: collect_values_study

   real(dp), parameter :: pi = acos(-1.0_dp)

   !> What one sweep point gives when run again here.
   type :: point_t
      real(dp), allocatable :: y_check(:, :)   !! (q, q̇) at the checkpoints (2N, K)
      real(dp) :: global_error = 0.0_dp        !! against the stored reference
      real(dp) :: energy_max_short = 0.0_dp, energy_max_long = 0.0_dp, energy_final = 0.0_dp
      real(dp) :: mean_step_short = 0.0_dp, mean_step_long = 0.0_dp  !! [s]
      integer(i8) :: short(4) = 0, long(4) = 0  !! steps, rhs, iterations, rejected
      integer :: status = stat_ok
      real(dp), allocatable :: bins(:)         !! energy_bins row (NaN: empty)
   end type point_t

contains

   !> The suite `values_study`.
   subroutine collect_values_study(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [new_unittest('tiny_study_file_values', test_file_values)]
   end subroutine collect_values_study

   ! ------------------------------------------------------------ independent forms

   !> The fixed-step grid: n steps from h_max down to h_min, each interval/m with m
   !> the nearest integer, strictly increasing m.
   pure function step_grid_cf(h_min, h_max, n, interval) result(h)
      real(dp), intent(in) :: h_min, h_max, interval  !! [s]
      integer, intent(in) :: n                       !! points
      real(dp) :: h(n)
      integer :: k, m, m_prev
      m_prev = 0
      do k = 1, n
         m = max(1, nint(interval/(h_max*(h_min/h_max)**(real(k - 1, dp)/real(n - 1, dp)))))
         m = max(m, m_prev + 1)
         h(k) = interval/real(m, dp)
         m_prev = m
      end do
   end function step_grid_cf

   !> n values from a to b in geometric progression.
   pure function geometric_cf(a, b, n) result(x)
      real(dp), intent(in) :: a, b  !! ends
      integer, intent(in) :: n      !! values (>= 2)
      real(dp) :: x(n)
      integer :: k
      x = [(exp(log(a) + (log(b) - log(a))*real(k - 1, dp)/real(n - 1, dp)), k=1, n)]
   end function geometric_cf

   !> Least-squares line of ln y against ln x over the points with x in [x_lo, x_hi]
   !> and finite y > y_min: slope, its standard error (NaN with < 3 points), points.
   pure subroutine loglog_cf(x, y, x_lo, x_hi, y_min, slope, stderr, n)
      real(dp), intent(in) :: x(:), y(:), x_lo, x_hi, y_min
      real(dp), intent(out) :: slope, stderr
      integer, intent(out) :: n
      real(dp), allocatable :: lx(:), ly(:)
      logical :: use(size(x))
      real(dp) :: a, b, sxx
      use = x >= x_lo .and. x <= x_hi .and. y > y_min .and. y < huge(1.0_dp)
      n = count(use)
      slope = -huge(1.0_dp); stderr = -huge(1.0_dp)
      if (n < 2) return
      lx = log(pack(x, use)); ly = log(pack(y, use))
      sxx = sum((lx - sum(lx)/n)**2)
      slope = sum((lx - sum(lx)/n)*(ly - sum(ly)/n))/sxx
      if (n < 3) return
      b = sum(ly)/n - slope*sum(lx)/n
      a = sum((ly - b - slope*lx)**2)
      stderr = sqrt(a/real(n - 2, dp)/sxx)
   end subroutine loglog_cf

   !> Energy scale: |H(0)|, or the potential energy with every link upright when
   !> H(0) vanishes [J].
   pure real(dp) function scale_cf(e0, links) result(es)
      real(dp), intent(in) :: e0    !! H(0) [J]
      integer, intent(in) :: links  !! number of links
      real(dp) :: up(links)
      up = 0.5_dp*pi
      es = abs(e0)
      if (es < 1e-9_dp*energy_cf(up, 0.0_dp*up)) es = energy_cf(up, 0.0_dp*up)
   end function scale_cf

   !> H(q, p) of the default double pendulum (1 kg, 1 m, g = 9.8) in quadruple
   !> precision: ½ pᵀ M⁻¹ p + V with M = [[4/3, c/2], [c/2, 1/3]], c = cos(q1 − q2)
   !> (g is the double 9.8 of the model, converted).
   pure real(qp) function hamiltonian_q(y) result(h)
      real(qp), intent(in) :: y(4)  !! (q1, q2, p1, p2)
      real(qp) :: c, m11, m12, m22, det
      c = cos(y(1) - y(2))
      m11 = 4.0_qp/3.0_qp; m12 = 0.5_qp*c; m22 = 1.0_qp/3.0_qp
      det = m11*m22 - m12*m12
      h = 0.5_qp*(m22*y(3)**2 - 2.0_qp*m12*y(3)*y(4) + m11*y(4)**2)/det &
          + real(9.8_dp, qp)*(1.5_qp*sin(y(1)) + 0.5_qp*sin(y(2)))
   end function hamiltonian_q

   ! -------------------------------------------------------------------- the test

   subroutine test_file_values(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir, file
      integer(i8) :: c0, c1, rate
      real(dp) :: elapsed, par(5)
      integer :: ic, i
      cfg = tiny_study_config(1000.0_dp, 200.0_dp)
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call system_clock(c0, rate)
      call run_study(cfg, res, quiet=.true.)
      call system_clock(c1)
      elapsed = real(c1 - c0, dp)/real(rate, dp)
      dir = scratch_dir('values-study')
      file = dir//'/tiny.h5'
      call write_study_h5(cfg, res, file, error)
      if (allocated(error)) return
      call h5%open(file, 'r', error)
      if (allocated(error)) return
      ! the closed forms here are those of the default rods: the file must say so
      call h5%readattr('/config', 'm1', par(1), error)
      if (.not. allocated(error)) call h5%readattr('/config', 'm2', par(2), error)
      if (.not. allocated(error)) call h5%readattr('/config', 'l1', par(3), error)
      if (.not. allocated(error)) call h5%readattr('/config', 'l2', par(4), error)
      if (.not. allocated(error)) call h5%readattr('/config', 'g', par(5), error)
      if (.not. allocated(error)) call check(error, par, [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, &
                                                          9.8_dp], 'default rods', abs=0.0_dp)
      do ic = 1, size(cfg%cases)
         if (.not. allocated(error)) call check_case(ic)
      end do
      do i = 1, size(cfg%ro_methods)
         if (.not. allocated(error)) call check_roundoff(i)
      end do
      do i = 1, size(cfg%tao_methods)
         if (.not. allocated(error)) call check_tao(i)
      end do
      if (.not. allocated(error)) call check_namelist()
      if (.not. allocated(error)) call check_summary()
      call h5%close()
      if (allocated(error)) return
      call execute_command_line('rm -rf '//dir)
   contains

      !> /cases/<case>: the reference, then every sweep of every method.
      subroutine check_case(ic)
         integer, intent(in) :: ic
         real(dp), allocatable :: t(:), state(:, :), y_ref(:, :)
         character(len=:), allocatable :: g
         integer :: im, k, n
         g = '/cases/'//cfg%cases(ic)%name
         n = size(cfg%cases(ic)%q0)
         call h5%read(g//'/reference/t', t, error)
         if (.not. allocated(error)) call h5%read(g//'/reference/state', state, error)
         if (allocated(error)) return
         call check_true(error, size(t) == cfg%n_check .and. &
                         all(shape(state) == [2*n, cfg%n_check]), g//': reference shapes')
         call check(error, t, [(real(k, dp)*cfg%t_short/real(cfg%n_check, dp), &
                                k=1, cfg%n_check)], g//': reference/t = k t_short/K', &
                    rel=1e-15_dp)
         if (allocated(error)) return
         ! a second method, here: dop853 at rtol 1e-13 (measured 1.5e-13 rad, rad/s)
         call run_checkpoints('dop853', method_options_t(rtol=1e-13_dp, atol=1e-15_dp), &
                              cfg%cases(ic)%q0, cfg%cases(ic)%w0, t, 0.0_dp, y_ref, k)
         call check_true(error, k == stat_ok, g//': dop853 run')
         if (allocated(error)) return
         call check(error, maxval(abs(state - y_ref)), 0.0_dp, &
                    g//': reference/state against dop853 here', abs=1e-12_dp)
         do im = 1, size(cfg%methods)
            call check_sweep(ic, im, .false., t, state)
            if (allocated(error)) return
            if (cfg%methods(im)%rtol_min > 0.0_dp) call check_sweep(ic, im, .true., t, state)
            if (allocated(error)) return
         end do
      end subroutine check_case

      !> /cases/<case>/<method>/step or tol: every dataset against the runs here.
      subroutine check_sweep(ic, im, tol, t_ref, y_ref)
         integer, intent(in) :: ic, im
         logical, intent(in) :: tol
         real(dp), intent(in) :: t_ref(:), y_ref(:, :)
         character(len=:), allocatable :: g
         real(dp), allocatable :: x(:), atol(:), global_error(:), energy_max_short(:), &
                                  energy_max_long(:), energy_final(:), drift_exponent(:), &
                                  drift_stderr(:), mean_step_short(:), mean_step_long(:), &
                                  wall_short(:), wall_long(:), t_bins(:), energy_bins(:, :), &
                                  hs(:), bins_cf(:)
         integer(i8), allocatable :: short_steps(:), short_rhs(:), short_iterations(:), &
                                     short_rejected(:), long_steps(:), long_rhs(:), &
                                     long_iterations(:), long_rejected(:)
         integer, allocatable :: status(:)
         type(point_t) :: pt
         real(dp) :: t_long, interval, slope, stderr, es
         integer :: n, k, nb, j, np
         associate (me => cfg%methods(im), cs => cfg%cases(ic))
            g = '/cases/'//cs%name//'/'//me%name//merge('/tol ', '/step', tol)
            g = trim(g)
            interval = cfg%t_short/real(cfg%n_check, dp)
            if (tol) then
               call h5%read(g//'/rtol', x, error)
               if (.not. allocated(error)) call h5%read(g//'/atol', atol, error)
            else
               call h5%read(g//'/h', x, error)
            end if
            if (.not. allocated(error)) call h5%read(g//'/global_error', global_error, error)
            if (.not. allocated(error)) call h5%read(g//'/energy_max_short', &
                                                     energy_max_short, error)
            if (.not. allocated(error)) call h5%read(g//'/energy_max_long', &
                                                     energy_max_long, error)
            if (.not. allocated(error)) call h5%read(g//'/energy_final', energy_final, error)
            if (.not. allocated(error)) call h5%read(g//'/drift_exponent', drift_exponent, error)
            if (.not. allocated(error)) call h5%read(g//'/drift_stderr', drift_stderr, error)
            if (.not. allocated(error)) call h5%read(g//'/mean_step_short', &
                                                     mean_step_short, error)
            if (.not. allocated(error)) call h5%read(g//'/mean_step_long', mean_step_long, error)
            if (.not. allocated(error)) call h5%read(g//'/short_steps', short_steps, error)
            if (.not. allocated(error)) call h5%read(g//'/short_rhs', short_rhs, error)
            if (.not. allocated(error)) call h5%read(g//'/short_iterations', &
                                                     short_iterations, error)
            if (.not. allocated(error)) call h5%read(g//'/short_rejected', short_rejected, error)
            if (.not. allocated(error)) call h5%read(g//'/long_steps', long_steps, error)
            if (.not. allocated(error)) call h5%read(g//'/long_rhs', long_rhs, error)
            if (.not. allocated(error)) call h5%read(g//'/long_iterations', &
                                                     long_iterations, error)
            if (.not. allocated(error)) call h5%read(g//'/long_rejected', long_rejected, error)
            if (.not. allocated(error)) call h5%read(g//'/wall_short', wall_short, error)
            if (.not. allocated(error)) call h5%read(g//'/wall_long', wall_long, error)
            if (.not. allocated(error)) call h5%read(g//'/status', status, error)
            if (.not. allocated(error)) call h5%read(g//'/t_bins', t_bins, error)
            if (.not. allocated(error)) call h5%read(g//'/energy_bins', energy_bins, error)
            if (.not. allocated(error)) call h5%readattr(g, 't_long', t_long, error)
            if (allocated(error)) return
            ! grids in closed form
            n = merge(cfg%n_rtol, cfg%n_h, tol)
            nb = cfg%decades*cfg%bins_per_decade
            call check_true(error, size(x) == n .and. all(shape(energy_bins) == [n, nb]) &
                            .and. size(t_bins) == nb, g//': shapes')
            if (allocated(error)) return
            if (tol) then
               call check(error, x, geometric_cf(me%rtol_max, me%rtol_min, n), &
                          g//': rtol geometric from rtol_max to rtol_min', rel=1e-14_dp)
               call check(error, atol, cfg%atol_ratio*x, g//': atol = atol_ratio rtol', &
                          rel=1e-15_dp)
            else
               call check(error, x, step_grid_cf(me%h_min, me%h_max, n, interval), &
                          g//': h = (t_short/K)/m', rel=1e-15_dp)
            end if
            hs = step_grid_cf(me%h_min, me%h_max, cfg%n_h, interval)
            call check(error, t_long, cs%long_steps*hs((cfg%n_h + 1)/2), &
                       g//': t_long = long_steps h_mid', rel=1e-15_dp)
            call check(error, t_bins, [(t_long*10.0_dp**(-real(nb - j, dp)/ &
                                                         real(cfg%bins_per_decade, dp)), &
                                        j=1, nb)], g//': t_bins = t_long 10^(-j/b)', &
                       rel=1e-14_dp)
            if (allocated(error)) return
            es = scale_cf(energy_cf(cs%q0, cs%w0), size(cs%q0))
            do k = 1, n
               call run_point(me%name, tol, x(k), cs%q0, cs%w0, t_ref, y_ref, t_long, &
                              t_bins, es, pt)
               associate (tag => g//' point '//to_str(k)//': ')
                  call check_true(error, status(k) == pt%status .and. pt%status == stat_ok, &
                                  tag//'status = that of the run here')
                  ! measured: global_error 0 (the same steps); energies 5e-16 absolute (the
                  ! file's H(q, p) for canonical methods, T + V of (q, qdot) here)
                  call check(error, global_error(k), pt%global_error, tag//'global_error', &
                             rel=1e-12_dp, abs=1e-15_dp)
                  call check(error, energy_max_short(k), pt%energy_max_short, &
                             tag//'energy_max_short', rel=1e-9_dp, abs=2e-15_dp)
                  call check(error, energy_max_long(k), pt%energy_max_long, &
                             tag//'energy_max_long', rel=1e-9_dp, abs=2e-15_dp)
                  call check(error, energy_final(k), pt%energy_final, tag//'energy_final', &
                             rel=1e-9_dp, abs=2e-15_dp)
                  call check_true(error, short_steps(k) == pt%short(1) .and. &
                                  short_rhs(k) == pt%short(2) .and. &
                                  short_iterations(k) == pt%short(3) .and. &
                                  short_rejected(k) == pt%short(4), &
                                  tag//'short_steps, short_rhs, short_iterations, '// &
                                  'short_rejected = counters of the run here')
                  call check_true(error, long_steps(k) == pt%long(1) .and. &
                                  long_rhs(k) == pt%long(2) .and. &
                                  long_iterations(k) == pt%long(3) .and. &
                                  long_rejected(k) == pt%long(4), &
                                  tag//'long_steps, long_rhs, long_iterations, '// &
                                  'long_rejected = counters of the run here')
                  if (.not. tol) call check_true(error, short_steps(k) == &
                                                 nint(cfg%t_short/x(k), i8), &
                                                 tag//'short_steps = t_short/h')
                  call check(error, mean_step_short(k), cfg%t_short/real(pt%short(1), dp), &
                             tag//'mean_step_short = t_short/steps', rel=1e-15_dp)
                  call check(error, mean_step_long(k), t_long/real(pt%long(1), dp), &
                             tag//'mean_step_long = t_long/steps', rel=1e-12_dp)
                  ! the bins: the same NaN pattern, the same maxima
                  call check_true(error, all(ieee_is_nan(energy_bins(k, :)) .eqv. &
                                             ieee_is_nan(pt%bins)), tag//'energy_bins: empty bins')
                  bins_cf = merge(pt%bins, 0.0_dp, .not. ieee_is_nan(pt%bins))
                  call check(error, merge(energy_bins(k, :), 0.0_dp, &
                                          .not. ieee_is_nan(energy_bins(k, :))), bins_cf, &
                             tag//'energy_bins', rel=1e-9_dp, abs=2e-15_dp)
                  ! the drift exponent from the stored bins, least squares here
                  call loglog_cf(t_bins, merge(energy_bins(k, :), -1.0_dp, &
                                               .not. ieee_is_nan(energy_bins(k, :))), &
                                 t_long*10.0_dp**(-cfg%drift_decades), t_long, 0.0_dp, &
                                 slope, stderr, np)
                  call check_true(error, np >= 3, tag//'drift fit points')
                  call check(error, drift_exponent(k), slope, tag//'drift_exponent', &
                             abs=1e-12_dp)
                  call check(error, drift_stderr(k), stderr, tag//'drift_stderr', abs=1e-12_dp)
                  ! wall times: bounded by the elapsed time of the whole study, measured here
                  call check_true(error, wall_short(k) > 0.0_dp .and. &
                                  wall_short(k) <= elapsed .and. wall_long(k) > 0.0_dp &
                                  .and. wall_long(k) <= elapsed, &
                                  tag//'0 < wall_short, wall_long <= the study''s elapsed time')
               end associate
               if (allocated(error)) return
            end do
         end associate
      end subroutine check_sweep

      !> One sweep point run here: the short run with checkpoints, the long run with
      !> bins; energies in closed form from the physical state.
      subroutine run_point(method, tol, x, q0, w0, t_ref, y_ref, t_long, t_bins, es, pt)
         character(len=*), intent(in) :: method
         logical, intent(in) :: tol
         real(dp), intent(in) :: x, q0(:), w0(:), t_ref(:), y_ref(:, :), t_long, t_bins(:), es
         type(point_t), intent(out) :: pt
         class(integrator_t), allocatable :: integ
         class(model_t), allocatable :: model
         type(method_options_t) :: opt
         type(error_t), allocatable :: err
         real(dp) :: e0, e, h0, y_end(2*size(q0))
         integer :: jb
         if (tol) then
            opt = method_options_t(rtol=x, atol=cfg%atol_ratio*x)
         else
            opt = method_options_t(fixed_step=.true.)
         end if
         h0 = merge(0.0_dp, x, tol)
         e0 = energy_cf(q0, w0)
         call run_checkpoints(method, opt, q0, w0, t_ref, h0, pt%y_check, pt%status, &
                              e0, es, pt%energy_max_short, counters=pt%short)
         if (pt%status /= stat_ok) return
         pt%global_error = maxval(abs(pt%y_check - y_ref))
         pt%mean_step_short = cfg%t_short/real(pt%short(1), dp)
         allocate (pt%bins(size(t_bins)))
         pt%bins = -1.0_dp
         call new_integrator(method, integ, err, opt)
         call make_model(size(q0), model)
         block
            type(march_t) :: march
            real(dp) :: t, hh
            real(dp), allocatable :: y(:)
            integer :: stat
            y = integ%to_internal(model, q0, w0)
            t = 0.0_dp; hh = h0; jb = 1; e = 0.0_dp
            pt%energy_max_long = 0.0_dp
            call march%start(integ, t, t_long, hh)
            do while (.not. march%finished)
               call march%next(integ, model, t, y, hh, stat)
               if (stat /= stat_ok) exit
               call integ%to_physical(model, y, y_end(1:size(q0)), y_end(size(q0) + 1:))
               e = abs(energy_cf(y_end(1:size(q0)), y_end(size(q0) + 1:)) - e0)/es
               do while (jb < size(t_bins))
                  if (t <= t_bins(jb)) exit
                  jb = jb + 1
               end do
               pt%bins(jb) = max(pt%bins(jb), e)
               pt%energy_max_long = max(pt%energy_max_long, e)
            end do
            pt%status = stat
         end block
         pt%energy_final = e
         pt%long = [integ%n_steps, integ%n_rhs, integ%n_iter, integ%n_rejected]
         pt%mean_step_long = t_long/real(pt%long(1), dp)
         where (pt%bins < 0.0_dp) pt%bins = ieee_value_nan()
      end subroutine run_point

      !> (q, q̇) at the times t_ref from (q0, w0): fixed step h (each time hit exactly)
      !> or adaptive (h = 0); optionally the largest |E − e0|/es over the steps and the
      !> counters (steps, rhs, iterations, rejected).
      subroutine run_checkpoints(method, opt, q0, w0, t_ref, h, ys, stat, e0, es, emax, &
                                 counters)
         character(len=*), intent(in) :: method
         type(method_options_t), intent(in) :: opt
         real(dp), intent(in) :: q0(:), w0(:), t_ref(:), h
         real(dp), allocatable, intent(out) :: ys(:, :)
         integer, intent(out) :: stat
         real(dp), intent(in), optional :: e0, es
         real(dp), intent(out), optional :: emax
         integer(i8), intent(out), optional :: counters(4)
         class(integrator_t), allocatable :: integ
         class(model_t), allocatable :: model
         type(error_t), allocatable :: err
         type(march_t) :: march
         real(dp) :: t, hh, qq(size(q0)), ww(size(q0))
         real(dp), allocatable :: y(:)
         integer :: k, n
         n = size(q0)
         call new_integrator(method, integ, err, opt)
         call make_model(n, model)
         allocate (ys(2*n, size(t_ref)))
         y = integ%to_internal(model, q0, w0)
         t = 0.0_dp; hh = h
         if (present(emax)) emax = 0.0_dp
         stat = stat_ok
         do k = 1, size(t_ref)
            if (h > 0.0_dp) hh = h
            call march%start(integ, t, t_ref(k), hh)
            do while (.not. march%finished)
               call march%next(integ, model, t, y, hh, stat)
               if (stat /= stat_ok) return
               if (present(emax)) then
                  call integ%to_physical(model, y, qq, ww)
                  emax = max(emax, abs(energy_cf(qq, ww) - e0)/es)
               end if
            end do
            call integ%to_physical(model, y, ys(1:n, k), ys(n + 1:, k))
         end do
         if (present(counters)) counters = [integ%n_steps, integ%n_rhs, integ%n_iter, &
                                            integ%n_rejected]
      end subroutine run_checkpoints

      !> /roundoff/<method>: the runs again, H in quadruple precision here.
      subroutine check_roundoff(i)
         integer, intent(in) :: i
         character(len=:), allocatable :: g
         integer(i8), allocatable :: steps(:), steps_cf(:)
         real(dp), allocatable :: t(:), rms_compensated(:), rms_plain(:), &
                                  error_compensated(:, :), error_plain(:, :), &
                                  wall_compensated(:), wall_plain(:), err(:, :, :)
         integer, allocatable :: status_compensated(:), status_plain(:), stat(:, :)
         integer :: ic, r, c, j, s, runs
         g = '/roundoff/'//trim(cfg%ro_methods(i))
         call h5%read(g//'/steps', steps, error)
         if (.not. allocated(error)) call h5%read(g//'/t', t, error)
         if (.not. allocated(error)) call h5%read(g//'/rms_compensated', rms_compensated, error)
         if (.not. allocated(error)) call h5%read(g//'/rms_plain', rms_plain, error)
         if (.not. allocated(error)) call h5%read(g//'/error_compensated', &
                                                  error_compensated, error)
         if (.not. allocated(error)) call h5%read(g//'/error_plain', error_plain, error)
         if (.not. allocated(error)) call h5%read(g//'/status_compensated', &
                                                  status_compensated, error)
         if (.not. allocated(error)) call h5%read(g//'/status_plain', status_plain, error)
         if (.not. allocated(error)) call h5%read(g//'/wall_compensated', wall_compensated, error)
         if (.not. allocated(error)) call h5%read(g//'/wall_plain', wall_plain, error)
         if (allocated(error)) return
         ! sample steps: nint(10^(j/b)) below ro_steps, distinct, then ro_steps itself
         allocate (steps_cf(0))
         do j = 0, 1000
            if (nint(10.0_dp**(real(j, dp)/real(cfg%bins_per_decade, dp)), i8) >= &
                nint(cfg%ro_steps, i8)) exit
            s = nint(10.0_dp**(real(j, dp)/real(cfg%bins_per_decade, dp)))
            if (size(steps_cf) > 0) then
               if (s <= steps_cf(size(steps_cf))) cycle
            end if
            steps_cf = [steps_cf, int(s, i8)]
         end do
         steps_cf = [steps_cf, nint(cfg%ro_steps, i8)]
         runs = cfg%ro_runs
         call check_true(error, size(steps) == size(steps_cf), g//': number of sample steps')
         if (allocated(error)) return
         call check_true(error, all(steps == steps_cf), g//': steps = nint(10^(j/b)), ro_steps')
         call check(error, t, real(steps, dp)*cfg%ro_dt(i), g//': t = steps dt', rel=1e-15_dp)
         call check_true(error, all(shape(error_compensated) == [runs, size(steps)]) .and. &
                         all(shape(error_plain) == [runs, size(steps)]) .and. &
                         size(status_compensated) == runs .and. size(status_plain) == runs, &
                         g//': shapes')
         if (allocated(error)) return
         ic = 0
         do j = 1, size(cfg%cases)
            if (cfg%cases(j)%name == cfg%ro_case) ic = j
         end do
         allocate (err(runs, size(steps), 2), stat(runs, 2))
         do c = 1, 2
            do r = 1, runs
               call roundoff_run(cfg%ro_methods(i), cfg%ro_dt(i), c == 1, &
                                 cfg%cases(ic)%q0 + cfg%ro_perturb*real(r - 1, dp)* &
                                 [1.0_dp, -0.7_dp], cfg%cases(ic)%w0, steps, &
                                 err(r, :, c), stat(r, c))
            end do
         end do
         call check_true(error, all(status_compensated == stat(:, 1)) .and. &
                         all(status_plain == stat(:, 2)) .and. all(stat == stat_ok), &
                         g//': status_compensated, status_plain = the runs here')
         ! measured: 0 (the same states; H in quadruple precision by two formulas)
         call check(error, maxval(abs(error_compensated - err(:, :, 1))), 0.0_dp, &
                    g//': error_compensated from H in quadruple precision here', abs=1e-25_dp)
         call check(error, maxval(abs(error_plain - err(:, :, 2))), 0.0_dp, &
                    g//': error_plain from H in quadruple precision here', abs=1e-25_dp)
         call check(error, rms_compensated, sqrt(sum(err(:, :, 1)**2, dim=1)/real(runs, dp)), &
                    g//': rms_compensated over the runs', rel=1e-12_dp, abs=1e-30_dp)
         call check(error, rms_plain, sqrt(sum(err(:, :, 2)**2, dim=1)/real(runs, dp)), &
                    g//': rms_plain over the runs', rel=1e-12_dp, abs=1e-30_dp)
         call check_true(error, all(wall_compensated > 0.0_dp .and. wall_compensated <= &
                                    elapsed) .and. all(wall_plain > 0.0_dp .and. &
                                                       wall_plain <= elapsed), &
                         g//': 0 < wall_compensated, wall_plain <= the study''s elapsed time')
      end subroutine check_roundoff

      !> One roundoff run: (H − H0)/E_s at the sample steps, H in quadruple precision
      !> at y + comp (the compensated remainder of a symplectic method).
      subroutine roundoff_run(method, dt, compensated, q0, w0, steps, errs, stat)
         character(len=*), intent(in) :: method
         real(dp), intent(in) :: dt, q0(2), w0(2)
         logical, intent(in) :: compensated
         integer(i8), intent(in) :: steps(:)
         real(dp), intent(out) :: errs(:)
         integer, intent(out) :: stat
         class(integrator_t), allocatable :: integ
         class(model_t), allocatable :: model
         type(error_t), allocatable :: err
         real(dp) :: y(4), t, h, comp(4), es
         real(qp) :: h0
         integer(i8) :: n
         integer :: j
         call new_integrator(method, integ, err, method_options_t(compensated=compensated))
         call make_model(2, model)
         y = integ%to_internal(model, q0, w0)
         ! canonical variables (q, p) inside, p = M qdot (checked here)
         call check(error, y(3:4), momenta_cf(q0, w0), method//': internal state (q, p)', &
                    rel=1e-14_dp)
         h0 = hamiltonian_q(real(y, qp))
         es = scale_cf(real(h0, dp), 2)
         t = 0.0_dp; j = 1; stat = stat_ok
         errs = 0.0_dp
         do n = 1, steps(size(steps))
            h = dt
            call integ%step(model, t, y, h, stat)
            if (stat /= stat_ok) return
            if (n == steps(j)) then
               comp = 0.0_dp
               select type (integ)
               class is (symplectic_t)
                  comp = integ%comp(:4)
               end select
               errs(j) = real((hamiltonian_q(real(y, qp) + real(comp, qp)) - h0)/real(es, qp), dp)
               j = j + 1
            end if
         end do
      end subroutine roundoff_run

      !> /tao/<method>: the runs again.
      subroutine check_tao(i)
         integer, intent(in) :: i
         character(len=:), allocatable :: g
         real(dp), allocatable :: omega(:), energy_max(:), energy_final(:), global_error(:), &
                                  t_ref(:), y_ref(:, :), ys(:, :)
         integer, allocatable :: status(:)
         real(dp) :: e0, es, emax, e, t, hh, qq(2), ww(2)
         real(dp), allocatable :: y(:)
         integer :: ic, k, j, stat
         class(integrator_t), allocatable :: integ
         class(model_t), allocatable :: model
         type(error_t), allocatable :: err
         type(march_t) :: march
         g = '/tao/'//trim(cfg%tao_methods(i))
         ic = 0
         do j = 1, size(cfg%cases)
            if (cfg%cases(j)%name == cfg%tao_case) ic = j
         end do
         call h5%read(g//'/omega', omega, error)
         if (.not. allocated(error)) call h5%read(g//'/energy_max', energy_max, error)
         if (.not. allocated(error)) call h5%read(g//'/energy_final', energy_final, error)
         if (.not. allocated(error)) call h5%read(g//'/global_error', global_error, error)
         if (.not. allocated(error)) call h5%read(g//'/status', status, error)
         if (.not. allocated(error)) call h5%read('/cases/'//cfg%cases(ic)%name// &
                                                  '/reference/t', t_ref, error)
         if (.not. allocated(error)) call h5%read('/cases/'//cfg%cases(ic)%name// &
                                                  '/reference/state', y_ref, error)
         if (allocated(error)) return
         call check(error, omega, geometric_cf(cfg%omega_min, cfg%omega_max, cfg%n_omega), &
                    g//': omega geometric from omega_min to omega_max', rel=1e-14_dp)
         if (allocated(error)) return
         associate (cs => cfg%cases(ic))
            e0 = energy_cf(cs%q0, cs%w0)
            es = scale_cf(e0, 2)
            do k = 1, cfg%n_omega
               call run_checkpoints(trim(cfg%tao_methods(i)), method_options_t(omega=omega(k)), &
                                    cs%q0, cs%w0, t_ref, cfg%tao_dt, ys, stat)
               call check_true(error, stat == stat_ok .and. status(k) == stat, &
                               g//': status = that of the run here')
               ! measured: 0 relative (the same steps)
               call check(error, global_error(k), maxval(abs(ys - y_ref)), &
                          g//': global_error against the stored reference', rel=1e-12_dp)
               call new_integrator(trim(cfg%tao_methods(i)), integ, err, &
                                   method_options_t(omega=omega(k)))
               call make_model(2, model)
               y = integ%to_internal(model, cs%q0, cs%w0)
               t = 0.0_dp; hh = cfg%tao_dt; emax = 0.0_dp; e = 0.0_dp
               call march%start(integ, t, cfg%tao_t_end, hh)
               do while (.not. march%finished)
                  call march%next(integ, model, t, y, hh, stat)
                  if (stat /= stat_ok) exit
                  call integ%to_physical(model, y, qq, ww)
                  e = abs(energy_cf(qq, ww) - e0)/es
                  emax = max(emax, e)
               end do
               ! measured: 2e-16 absolute (H(q, p) in the file, T + V of (q, qdot) here)
               call check(error, energy_max(k), emax, g//': energy_max, closed form here', &
                          rel=1e-9_dp, abs=2e-15_dp)
               call check(error, energy_final(k), e, g//': energy_final, closed form here', &
                          rel=1e-9_dp, abs=2e-15_dp)
               if (allocated(error)) return
            end do
         end associate
      end subroutine check_tao

      !> /config/namelist: read back, it gives the configuration this test set.
      subroutine check_namelist()
         character(len=:), allocatable :: namelist, path
         type(study_config_t) :: back
         integer :: unit, j
         call h5%read('/config/namelist', namelist, error)
         if (allocated(error)) return
         path = dir//'/back.nml'
         open (newunit=unit, file=path, status='replace', action='write')
         write (unit, '(a)') namelist
         close (unit)
         back = study_defaults()
         call read_study_config(path, back, error)
         if (allocated(error)) return
         call check_true(error, size(back%cases) == size(cfg%cases) .and. &
                         size(back%methods) == size(cfg%methods), &
                         'namelist: the cases and methods of the test')
         if (allocated(error)) return
         do j = 1, size(cfg%cases)
            call check_true(error, back%cases(j)%name == cfg%cases(j)%name, &
                            'namelist: case name '//cfg%cases(j)%name)
            call check(error, [back%cases(j)%q0, back%cases(j)%w0, back%cases(j)%long_steps], &
                       [cfg%cases(j)%q0, cfg%cases(j)%w0, cfg%cases(j)%long_steps], &
                       'namelist: case '//cfg%cases(j)%name, abs=0.0_dp)
         end do
         do j = 1, size(cfg%methods)
            associate (a => back%methods(j), b => cfg%methods(j))
               call check_true(error, a%name == b%name, 'namelist: method '//b%name)
               call check(error, [a%h_min, a%h_max, a%rtol_min, a%rtol_max], &
                          [b%h_min, b%h_max, b%rtol_min, b%rtol_max], &
                          'namelist: ranges of '//b%name, abs=0.0_dp)
            end associate
         end do
         call check_true(error, back%n_h == cfg%n_h .and. back%n_rtol == cfg%n_rtol .and. &
                         back%decades == cfg%decades .and. back%ro_runs == cfg%ro_runs .and. &
                         back%n_omega == cfg%n_omega .and. back%order_case == cfg%order_case &
                         .and. back%drift_case == cfg%drift_case, &
                         'namelist: n_h, n_rtol, decades, ro_runs, n_omega, order/drift case')
         call check(error, [back%ro_steps, back%ro_fit_t_min, back%tao_t_end, back%tao_dt, &
                            back%ro_dt(1)], [cfg%ro_steps, cfg%ro_fit_t_min, cfg%tao_t_end, &
                                             cfg%tao_dt, cfg%ro_dt(1)], &
                    'namelist: roundoff and Tao settings', abs=0.0_dp)
      end subroutine check_namelist

      !> /summary/markdown: the orders table ("Orders in every case") holds, per method
      !> and case, the least-squares slopes of the stored global and energy errors
      !> against h (computed here) and the drift exponent at the middle step.
      subroutine check_summary()
         character(len=:), allocatable :: markdown, row, cell, g
         real(dp), allocatable :: h(:), ge(:), en(:), drift(:)
         real(dp) :: a, b, d, slope, stderr, check_difference
         integer :: im, ic, p, q, np, ios
         call h5%read('/summary/markdown', markdown, error)
         if (allocated(error)) return
         p = index(markdown, '## Orders in every case')
         call check_true(error, p > 0, 'summary: the orders table')
         if (allocated(error)) return
         markdown = markdown(p:)
         do im = 1, size(cfg%methods)
            p = index(markdown, new_line('a')//'| '//cfg%methods(im)%name//' | ')
            call check_true(error, p > 0, 'summary: a row for '//cfg%methods(im)%name)
            if (allocated(error)) return
            row = markdown(p + 1:)
            row = row(:index(row, new_line('a')) - 1)
            ! skip "| name | p |"
            q = index(row(3:), '|') + 2
            q = index(row(q + 1:), '|') + q
            row = row(q + 1:)
            do ic = 1, size(cfg%cases)
               cell = row(:index(row, '|') - 1)
               row = row(index(row, '|') + 1:)
               p = index(cell, '/'); q = index(cell, ';')
               read (cell(:p - 1), *, iostat=ios) a
               if (ios == 0) read (cell(p + 1:q - 1), *, iostat=ios) b
               if (ios == 0) read (cell(q + 1:), *, iostat=ios) d
               call check_true(error, ios == 0 .and. p > 0 .and. q > 0, &
                               'summary: cell "'//cell//'"')
               if (allocated(error)) return
               g = '/cases/'//cfg%cases(ic)%name//'/'//cfg%methods(im)%name//'/step'
               call h5%read(g//'/h', h, error)
               if (.not. allocated(error)) call h5%read(g//'/global_error', ge, error)
               if (.not. allocated(error)) call h5%read(g//'/energy_max_short', en, error)
               if (.not. allocated(error)) call h5%read(g//'/drift_exponent', drift, error)
               if (.not. allocated(error)) call h5%readattr('/cases/'//cfg%cases(ic)%name// &
                                                           '/reference', 'check_difference', &
                                                           check_difference, error)
               if (allocated(error)) return
               call loglog_cf(h, ge, 0.0_dp, huge(1.0_dp), max(1e-14_dp, &
                              10.0_dp*check_difference), slope, stderr, np)
               call check(error, a, slope, 'summary: order (global) of '// &
                          cfg%methods(im)%name//' in '//cfg%cases(ic)%name, abs=0.0051_dp)
               call loglog_cf(h, en, 0.0_dp, huge(1.0_dp), 1e-14_dp, slope, stderr, np)
               call check(error, b, slope, 'summary: order (energy) of '// &
                          cfg%methods(im)%name//' in '//cfg%cases(ic)%name, abs=0.0051_dp)
               call check(error, d, drift((size(h) + 1)/2), 'summary: drift of '// &
                          cfg%methods(im)%name//' in '//cfg%cases(ic)%name, abs=0.0051_dp)
               if (allocated(error)) return
            end do
         end do
      end subroutine check_summary
   end subroutine test_file_values

   !> A quiet NaN.
   real(dp) function ieee_value_nan() result(x)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      x = ieee_value(1.0_dp, ieee_quiet_nan)
   end function ieee_value_nan
end module test_values_study
