!> Every dataset a `dpend sweep` file holds, read back from the file and checked
!> against an independent computation (the dataset inventory,
!> test/inventory/sweep.txt). Each pixel is run again here, one trajectory at a time:
!> the model from the factory (the double pendulum's own formulation for two links,
!> the chain for three, the elastic pendulum) stepped by the registry's rk4 through
!> a direct `integ%step` call, with the flip rule (a crossing of q_i = π/2 + 2π k,
!> interpolated linearly in q_i within the step), the stop rules, the flip energy
!> bounds (G_i − Σ_(j≠i) G_j with G_i = g L_i (m_i/2 + Σ_(k>i) m_k)) and the energy
!> (the rods' or the spring's closed form, written out below) of the test's own code.
!> The axes come from the configuration's min, max and n, `done` from the block
!> count, the fast indicators from an in-process `chaos_indicators` run of the same
!> pixel, the largest Lyapunov exponent from central finite differences of two
!> neighbouring runs, the parameter datasets from the parameter axis.
!>
!> Two links: the sweep's vectorized kernel (Lagrange's form in lanes) against the
!> model's own field (they differ by rounding); three links: the chain lanes (the
!> mass-matrix system solved in lanes; they differ by rounding); the elastic
!> pendulum: the sweep's per-trajectory path against the same model and method.
module test_values_sweep
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_value, ieee_quiet_nan
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp, i8
   use dpend_hdf5, only: h5file_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, model_spec, new_model
   use dpend_indicators, only: indicators_result_t, chaos_indicators
   use dpend_cli, only: to_str
   use test_cli, only: run_command, scratch_dir
   use test_values_fit, only: read_csv
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error
   implicit none
   private
   public :: collect_values_sweep

   real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
   real(dp), parameter :: half_pi = 0.5_dp*pi, two_pi = 2.0_dp*pi

   integer, parameter :: rule_both = 1, rule_either = 2, rule_end = 3

   !> The result datasets of one map, read from the file, one column per pixel
   !> (a grid's pixels in storage order: axis 1 fastest).
   type :: map_t
      integer :: n = 0                          !! pixels
      real(dp), allocatable :: t_any(:)         !! t_flip (absent: no flips)
      real(dp), allocatable :: tf(:, :)         !! t_flip1 .. t_flipN (N, n)
      real(dp), allocatable :: e0(:), err(:), t_stop(:)
      real(dp), allocatable :: y(:, :)          !! final/q1 .. final/wN (2N, n)
      integer, allocatable :: status(:), steps(:)
   end type map_t

   !> One pixel run again by the test.
   type :: ref_t
      real(dp) :: e0 = 0, err = 0, t_stop = 0, t_any = 0
      real(dp), allocatable :: tf(:), y(:)
      integer :: status = 0, steps = 0
   end type ref_t

   !> Closed-form energy of the model being rerun: rods (m, l, g) or the spring.
   type :: energy_t
      logical :: spring = .false.
      real(dp), allocatable :: m(:), l(:)
      real(dp) :: g = 9.8_dp, k = 0, l0 = 0
   end type energy_t

contains

   subroutine collect_values_sweep(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('flip_map_two_links', test_flip_two), &
               new_unittest('flip_map_three_links', test_flip_three), &
               new_unittest('indicator_maps_two_links', test_indicators), &
               new_unittest('list_sweep', test_list), &
               new_unittest('parameter_axis_map', test_parameters), &
               new_unittest('elastic_map', test_elastic)]
   end subroutine collect_values_sweep

   ! ------------------------------------------------------------------ tests ---

   !> A 5 × 4 flip map of two unequal links (w1 ≠ 0, --stats, two blocks, stop rule
   !> both) against 20 reruns: t_flip, t_flip1, t_flip2, final/q1, final/q2,
   !> final/w1, final/w2, t_stop, status, steps, energy0 (closed form),
   !> energy_error (max over the steps of the rerun), axis1, axis2 (min, max, n),
   !> done (2 blocks). Statuses 1, 2 and 3 all occur. Measured largest differences
   !> (kernel vs model: rounding), printed as '    flip_map_two_links: ...': final
   !> state 1.1e-12 (tolerance 1e-11), flip times 4.9e-15 s, energy0 7.1e-15 J
   !> (1e-13 relative), energy_error 5.2e-9 relative (tolerance 1e-7).
   subroutine test_flip_two(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: par = '--m1 1.3 --m2 0.9 --l1 1.1 --l2 0.8 --g 9.81'
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      type(map_t) :: map
      type(energy_t) :: en
      real(dp), allocatable :: ax1(:), ax2(:), y0(:, :)
      integer, allocatable :: done(:)
      integer :: stat, i1, i2, j
      dir = scratch_dir('values2-flip2')
      stat = run_command(dir, 'sweep --quiet '//par//' --w1 0.5 --n1 5 --n2 4 --min1 -3 '// &
                         '--max1 3 --min2 -2.5 --max2 2.5 --time-unit s --dt 0.01 --t-end 3 '// &
                         '--stats --block 10 --threads 1 --output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep exits 0')
      if (allocated(error)) return
      allocate (map%tf(2, 20), map%y(4, 20))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      call read_px(h5, '/sweep/t_flip', map%t_any, error)
      call read_row(h5, '/sweep/t_flip1', map%tf, 1, error)
      call read_row(h5, '/sweep/t_flip2', map%tf, 2, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/w1', map%y, 3, error)
      call read_row(h5, '/sweep/final/w2', map%y, 4, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call read_ipx(h5, '/sweep/steps', map%steps, error)
      call h5%close()
      if (allocated(error)) return
      map%n = 20
      call check_axis(error, ax1, -3.0_dp, 3.0_dp, 5, 'axis1')
      call check_axis(error, ax2, -2.5_dp, 2.5_dp, 4, 'axis2')
      call check_true(error, size(done) == 2 .and. all(done == 1), &
                      'done: 2 blocks of 2 rows, both flagged 1')
      if (allocated(error)) return
      allocate (y0(4, 20))
      do i2 = 1, 4
         do i1 = 1, 5
            j = i1 + 5*(i2 - 1)
            y0(:, j) = [ax1(i1) - half_pi, ax2(i2) - half_pi, 0.5_dp, 0.0_dp]
         end do
      end do
      en%m = [1.3_dp, 0.9_dp]; en%l = [1.1_dp, 0.8_dp]; en%g = 9.81_dp
      call compare_map(error, 'flip_map_two_links', map, en, y0, 0.01_dp, 300_i8, &
                       rule_both, tol=1e-11_dp, kinds=[1, 2, 3])
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_flip_two

   !> A 5 × 3 flip map of a chain of three unequal links (link 3 hanging, --stats,
   !> three blocks, stop rule both) against 15 reruns of the chain: t_flip, t_flip1,
   !> t_flip2, t_flip3, final/q1 .. final/q3, final/w1 .. final/w3, t_stop, status,
   !> steps, energy0 (closed form), energy_error, axis1, axis2, done (3 blocks).
   subroutine test_flip_three(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: par = '--links 3 --m 1,0.8,1.2 --l 1,0.7,0.9 --g 9.81'
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      type(map_t) :: map
      type(energy_t) :: en
      real(dp), allocatable :: ax1(:), ax2(:), y0(:, :)
      integer, allocatable :: done(:)
      integer :: stat, i1, i2, j
      dir = scratch_dir('values2-flip3')
      stat = run_command(dir, 'sweep --quiet '//par//' --q 0,0,-1.5707963267948966 '// &
                         '--w 0,0,0 --n1 5 --n2 3 --min1 -3 --max1 3 --min2 -3 --max2 0.2 '// &
                         '--time-unit s --dt 0.01 --t-end 2 --stats --block 5 --threads 1 '// &
                         '--output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep --links 3 exits 0')
      if (allocated(error)) return
      allocate (map%tf(3, 15), map%y(6, 15))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      call read_px(h5, '/sweep/t_flip', map%t_any, error)
      call read_row(h5, '/sweep/t_flip1', map%tf, 1, error)
      call read_row(h5, '/sweep/t_flip2', map%tf, 2, error)
      call read_row(h5, '/sweep/t_flip3', map%tf, 3, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/q3', map%y, 3, error)
      call read_row(h5, '/sweep/final/w1', map%y, 4, error)
      call read_row(h5, '/sweep/final/w2', map%y, 5, error)
      call read_row(h5, '/sweep/final/w3', map%y, 6, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call read_ipx(h5, '/sweep/steps', map%steps, error)
      call h5%close()
      if (allocated(error)) return
      map%n = 15
      call check_axis(error, ax1, -3.0_dp, 3.0_dp, 5, 'axis1')
      call check_axis(error, ax2, -3.0_dp, 0.2_dp, 3, 'axis2')
      call check_true(error, size(done) == 3 .and. all(done == 1), &
                      'done: 3 blocks of one row, all flagged 1')
      if (allocated(error)) return
      allocate (y0(6, 15))
      do i2 = 1, 3
         do i1 = 1, 5
            j = i1 + 5*(i2 - 1)
            y0(:, j) = [ax1(i1) - half_pi, ax2(i2) - half_pi, -half_pi, 0.0_dp, 0.0_dp, 0.0_dp]
         end do
      end do
      en%m = [1.0_dp, 0.8_dp, 1.2_dp]; en%l = [1.0_dp, 0.7_dp, 0.9_dp]; en%g = 9.81_dp
      ! (the chain lanes: rounding only, measured 4.5e-12 after 200 steps)
      call compare_map(error, 'flip_map_three_links', map, en, y0, 0.01_dp, 200_i8, &
                       rule_both, tol=1e-10_dp, kinds=[1, 2, 3])
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_flip_three

   !> The indicator maps of two links (3 × 2 pixels, 2 s, dt = 0.005 s): megno and
   !> megno_y, fli, sali, gali2 against `chaos_indicators` of each pixel (the
   !> library's tangent flow on the rk4 orbit; the kernel's extended rk4 differs by
   !> O(h^4): tolerance 5e-4 relative, measured 6.5e-5), and lyapunov
   !> (--indicator lambda1: the kernel renormalizes the deviation (1, 1, 1, 1)/2 at
   !> every step) against ln(|y(T; y0 + ε d) − y(T; y0 − ε d)|/(2ε))/T of two reruns,
   !> ε = 1e-6 (the derivative of the rk4 map; tolerance 1e-8 relative, measured 1.2e-9).
   !> The MEGNO map's other datasets (t_flip, t_flip1, t_flip2, the final state,
   !> t_stop, status, energy0, energy_error) against reruns to t_end: every pixel is
   !> integrated, and one below every flip bound keeps status 3.
   subroutine test_indicators(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: base = 'sweep --quiet --w1 0.5 --n1 3 --n2 2 '// &
         '--min1 -2.5 --max1 3 --min2 -2 --max2 1 --time-unit s --dt 0.005 --t-end 2 '// &
         '--threads 1 --output '
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), megno(:), megno_y(:), fli(:), sali(:), &
                               gali2(:), lyapunov(:)
      real(dp) :: y0(4), d(4), ya(4), yb(4), worst(6), x(5), r(5), lam, t_end
      real(dp), allocatable :: yy(:, :)
      type(map_t) :: map
      type(energy_t) :: en
      type(indicators_result_t) :: ind
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      integer :: stat, i1, i2, j, m
      dir = scratch_dir('values2-ind')
      stat = 0
      stat = stat + run_command(dir, base//dir//'/m.h5 --indicator megno')
      stat = stat + run_command(dir, base//dir//'/f.h5 --indicator fli')
      stat = stat + run_command(dir, base//dir//'/s.h5 --indicator sali')
      stat = stat + run_command(dir, base//dir//'/g.h5 --indicator gali2')
      stat = stat + run_command(dir, base//dir//'/l.h5 --indicator lambda1')
      call check_true(error, stat == 0, 'the five indicator sweeps exit 0')
      if (allocated(error)) return
      allocate (map%tf(2, 6), map%y(4, 6))
      call h5%open(dir//'/m.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      call read_px(h5, '/sweep/megno', megno, error)
      call read_px(h5, '/sweep/megno_y', megno_y, error)
      ! the flip datasets of an indicator map (every pixel run to t_end)
      call read_px(h5, '/sweep/t_flip', map%t_any, error)
      call read_row(h5, '/sweep/t_flip1', map%tf, 1, error)
      call read_row(h5, '/sweep/t_flip2', map%tf, 2, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/w1', map%y, 3, error)
      call read_row(h5, '/sweep/final/w2', map%y, 4, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call h5%close()
      map%n = 6
      call read_one(dir//'/f.h5', '/sweep/fli', fli)
      call read_one(dir//'/s.h5', '/sweep/sali', sali)
      call read_one(dir//'/g.h5', '/sweep/gali2', gali2)
      call read_one(dir//'/l.h5', '/sweep/lyapunov', lyapunov)
      if (allocated(error)) return
      call check_axis(error, ax1, -2.5_dp, 3.0_dp, 3, 'axis1')
      call check_axis(error, ax2, -2.0_dp, 1.0_dp, 2, 'axis2')
      call pendulum(model, [1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], 9.8_dp, err)
      if (.not. allocated(err)) call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, err%message)
         return
      end if
      allocate (yy(4, 6))
      do i2 = 1, 2
         do i1 = 1, 3
            yy(:, i1 + 3*(i2 - 1)) = [ax1(i1) - half_pi, ax2(i2) - half_pi, 0.5_dp, 0.0_dp]
         end do
      end do
      en%m = [1.0_dp, 1.0_dp]; en%l = [1.0_dp, 1.0_dp]; en%g = 9.8_dp
      call compare_map(error, 'indicator_maps_two_links', map, en, yy, 0.005_dp, 400_i8, &
                       rule_end, tol=1e-11_dp, kinds=[1, 3], all_run=.true.)
      call check_true(error, any(.not. ieee_is_nan(map%tf(1, :))) .and. &
                      any(.not. ieee_is_nan(map%tf(2, :))), 'both links flip in some pixel')
      if (allocated(error)) return
      t_end = 2.0_dp
      worst = 0
      d = 0.5_dp
      do i2 = 1, 2
         do i1 = 1, 3
            j = i1 + 3*(i2 - 1)
            y0 = [ax1(i1) - half_pi, ax2(i2) - half_pi, 0.5_dp, 0.0_dp]
            call chaos_indicators(integ, model, 0.0_dp, y0, t_end, 0.005_dp, t_end, ind, stat)
            call check_true(error, stat == stat_ok .and. ind%n >= 1, 'chaos_indicators runs')
            if (allocated(error)) return
            m = ind%n
            call check(error, ind%t(m), t_end, 'indicators sampled at t_end', rel=1e-12_dp)
            x = [megno(j), megno_y(j), fli(j), sali(j), gali2(j)]
            r = [ind%mean_all(1, m), ind%megno_all(1, m), ind%log_norm(1, m), ind%sali(m), &
                 ind%gali(1, m)]
            worst(1:5) = max(worst(1:5), abs(x - r)/abs(r))
            call check(error, x, r, 'megno, megno_y, fli, sali, gali2 of pixel', rel=5e-4_dp)
            call run_to(model, integ, y0 + 1e-6_dp*d, 0.005_dp, 400_i8, ya)
            call run_to(model, integ, y0 - 1e-6_dp*d, 0.005_dp, 400_i8, yb)
            lam = log(norm2(ya - yb)/(2e-6_dp*norm2(d)))/t_end
            worst(6) = max(worst(6), abs(lyapunov(j) - lam)/abs(lam))
            call check(error, lyapunov(j), lam, 'lyapunov of pixel', rel=1e-8_dp)
            if (allocated(error)) return
         end do
      end do
      write (output_unit, '(a, 6es9.2)') '    indicator_maps_two_links: largest relative '// &
         'differences (megno, megno_y, fli, sali, gali2, lyapunov)', worst
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine read_one(path, name, v)
         character(len=*), intent(in) :: path, name
         real(dp), allocatable, intent(out) :: v(:)
         if (allocated(error)) return
         call h5%open(path, 'r', error)
         call read_px(h5, name, v, error)
         call h5%close()
      end subroutine read_one
   end subroutine test_indicators

   !> The list sweep of data/sweep_list.nml (its ic_file data/sweep_list.txt, stop
   !> rule both, --stats; shortened to 3 s, dt 0.01 s): `initial` against the rows of
   !> the text file read here, and every pixel against a rerun (t_flip, t_flip1,
   !> t_flip2, final/q1 .. final/w2, t_stop, status, steps, energy0, energy_error);
   !> `done` against the block count (block 3: 5 rows, 2 blocks).
   subroutine test_list(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      type(map_t) :: map
      type(energy_t) :: en
      real(dp), allocatable :: initial(:, :), rows(:, :)
      integer, allocatable :: done(:)
      integer :: stat, n
      dir = scratch_dir('values2-list')
      stat = run_command(dir, 'sweep --quiet --config data/sweep_list.nml --time-unit s '// &
                         '--dt 0.01 --t-end 3 --block 3 --threads 1 --output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep of data/sweep_list.nml exits 0')
      if (allocated(error)) return
      call read_csv('data/sweep_list.txt', 4, rows, error, header=.false.)
      if (allocated(error)) return
      n = size(rows, 2)
      call check_true(error, n == 5, 'data/sweep_list.txt holds 5 rows')
      if (allocated(error)) return
      allocate (map%tf(2, n), map%y(4, n))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/initial', initial, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      call read_px(h5, '/sweep/t_flip', map%t_any, error)
      call read_row(h5, '/sweep/t_flip1', map%tf, 1, error)
      call read_row(h5, '/sweep/t_flip2', map%tf, 2, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/w1', map%y, 3, error)
      call read_row(h5, '/sweep/final/w2', map%y, 4, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call read_ipx(h5, '/sweep/steps', map%steps, error)
      call h5%close()
      if (allocated(error)) return
      map%n = n
      call check_true(error, all(shape(initial) == [4, n]), 'initial is (4, 5)')
      if (allocated(error)) return
      call check(error, reshape(initial, [4*n]), reshape(rows, [4*n]), &
                 'initial: the rows of data/sweep_list.txt', rel=0.0_dp, abs=0.0_dp)
      call check_true(error, size(done) == 2 .and. all(done == 1), &
                      'done: 2 blocks (5 rows by 3), both flagged 1')
      if (allocated(error)) return
      en%m = [1.0_dp, 1.0_dp]; en%l = [1.0_dp, 1.0_dp]; en%g = 9.8_dp
      call compare_map(error, 'list_sweep', map, en, rows, 0.01_dp, 300_i8, rule_both, &
                       tol=1e-11_dp, kinds=[1, 2, 3])
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_list

   !> The (theta1, m2/m1) map of data/sweep_theta1_mass_ratio.nml (stop rule either),
   !> shrunk to 4 × 3 pixels and 3 s: param/m1, param/m2, param/l1, param/l2 against
   !> the axis (m2 = value m1, the rest the &pendulum values), and every pixel against
   !> a rerun of the pendulum with its own parameters (t_flip, t_flip1, t_flip2, the
   !> final state, t_stop, status, energy0, energy_error); axis2 from min, max, n.
   subroutine test_parameters(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      type(map_t) :: map
      type(energy_t) :: en
      real(dp), allocatable :: ax1(:), ax2(:), y0(:, :), m1(:), m2(:), l1(:), l2(:)
      integer :: stat, i1, i2, j
      dir = scratch_dir('values2-param')
      stat = run_command(dir, 'sweep --quiet --config data/sweep_theta1_mass_ratio.nml '// &
                         '--n1 4 --n2 3 --time-unit s --dt 0.01 --t-end 3 --threads 1 '// &
                         '--output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep of data/sweep_theta1_mass_ratio.nml exits 0')
      if (allocated(error)) return
      allocate (map%tf(2, 12), map%y(4, 12))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      call read_px(h5, '/sweep/param/m1', m1, error)
      call read_px(h5, '/sweep/param/m2', m2, error)
      call read_px(h5, '/sweep/param/l1', l1, error)
      call read_px(h5, '/sweep/param/l2', l2, error)
      call read_px(h5, '/sweep/t_flip', map%t_any, error)
      call read_row(h5, '/sweep/t_flip1', map%tf, 1, error)
      call read_row(h5, '/sweep/t_flip2', map%tf, 2, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/w1', map%y, 3, error)
      call read_row(h5, '/sweep/final/w2', map%y, 4, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call h5%close()
      if (allocated(error)) return
      map%n = 12
      call check_axis(error, ax1, -3.0_dp, 3.0_dp, 4, 'axis1')
      call check_axis(error, ax2, 0.1_dp, 4.0_dp, 3, 'axis2 (m2/m1)')
      if (allocated(error)) return
      allocate (y0(4, 1))
      do i2 = 1, 3
         do i1 = 1, 4
            j = i1 + 4*(i2 - 1)
            call check(error, [m1(j), m2(j), l1(j), l2(j)], [1.0_dp, ax2(i2), 1.0_dp, &
                       1.0_dp], 'param/m1, param/m2 = m2/m1 m1, param/l1, param/l2', &
                       rel=1e-15_dp)
            if (allocated(error)) return
            y0(:, 1) = [ax1(i1) - half_pi, 0.0_dp, 0.0_dp, 0.0_dp]   ! &initial q2 = 0
            en%m = [1.0_dp, ax2(i2)]; en%l = [1.0_dp, 1.0_dp]; en%g = 9.8_dp
            call compare_map(error, 'parameter_axis_map', pixel(map, j), en, y0, 0.01_dp, &
                             300_i8, rule_either, tol=1e-11_dp)
            if (allocated(error)) return
         end do
      end do
      call check_true(error, any(map%status == 2) .and. any(map%status == 1), &
                      'pixels that flip and pixels that do not')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_parameters

   !> The elastic pendulum's (r, phi) MEGNO map of data/elastic_sweep.nml shrunk to
   !> 3 × 2 pixels and 2 s: final/q1 (r), final/q2 (phi), final/w1, final/w2, t_stop,
   !> status, energy0 (E = m/2 (ṙ² + r² φ̇²) + k/2 (r − l0)² + m g r sin φ),
   !> energy_error (rerun, in the model's energy_scale), megno and megno_y (an
   !> in-process chaos_indicators run of the pixel), axis1, axis2, done.
   subroutine test_elastic(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      type(map_t) :: map
      type(energy_t) :: en
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(indicators_result_t) :: ind
      type(error_t), allocatable :: err
      real(dp), allocatable :: ax1(:), ax2(:), y0(:, :), megno(:), megno_y(:)
      integer, allocatable :: done(:)
      integer :: stat, i1, i2, j, m
      dir = scratch_dir('values2-elastic')
      stat = run_command(dir, 'sweep --quiet --config data/elastic_sweep.nml --n1 3 --n2 2 '// &
                         '--time-unit s --dt 0.01 --t-end 2 --threads 1 --output '// &
                         dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep of data/elastic_sweep.nml exits 0')
      if (allocated(error)) return
      allocate (map%y(4, 6))
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      call read_px(h5, '/sweep/energy0', map%e0, error)
      call read_px(h5, '/sweep/energy_error', map%err, error)
      call read_px(h5, '/sweep/t_stop', map%t_stop, error)
      call read_row(h5, '/sweep/final/q1', map%y, 1, error)
      call read_row(h5, '/sweep/final/q2', map%y, 2, error)
      call read_row(h5, '/sweep/final/w1', map%y, 3, error)
      call read_row(h5, '/sweep/final/w2', map%y, 4, error)
      call read_ipx(h5, '/sweep/status', map%status, error)
      call read_px(h5, '/sweep/megno', megno, error)
      call read_px(h5, '/sweep/megno_y', megno_y, error)
      call h5%close()
      if (allocated(error)) return
      map%n = 6
      call check_axis(error, ax1, 0.8_dp, 2.0_dp, 3, 'axis1 (r)')
      call check_axis(error, ax2, -2.8_dp, -0.35_dp, 2, 'axis2 (phi)')
      call check_true(error, size(done) == 1 .and. all(done == 1), 'done: one block')
      if (allocated(error)) return
      allocate (y0(4, 6))
      do i2 = 1, 2
         do i1 = 1, 3
            y0(:, i1 + 3*(i2 - 1)) = [ax1(i1), ax2(i2), 0.0_dp, 0.0_dp]
         end do
      end do
      en%spring = .true.; en%m = [1.0_dp]; en%k = 29.4_dp; en%l0 = 1.0_dp; en%g = 9.8_dp
      call compare_map(error, 'elastic_map', map, en, y0, 0.01_dp, 200_i8, rule_end, &
                       tol=1e-12_dp, kinds=[1])
      if (allocated(error)) return
      spec = model_spec('elastic')
      call spec%set('m', [1.0_dp]); call spec%set('k', [29.4_dp]); call spec%set('l0', [1.0_dp])
      call spec%set('g', [9.8_dp])
      call new_model(spec, model, err)
      if (.not. allocated(err)) call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, err%message)
         return
      end if
      do j = 1, 6
         call chaos_indicators(integ, model, 0.0_dp, y0(:, j), 2.0_dp, 0.01_dp, 2.0_dp, ind, &
                               stat)
         call check_true(error, stat == stat_ok .and. ind%n >= 1, 'chaos_indicators runs')
         if (allocated(error)) return
         m = ind%n
         call check(error, [megno(j), megno_y(j)], [ind%mean_all(1, m), ind%megno_all(1, m)], &
                    'megno, megno_y of pixel', rel=1e-12_dp)
         if (allocated(error)) return
      end do
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_elastic

   ! ---------------------------------------------------------------- helpers ---

   !> Compare every pixel of `map` with a rerun of its initial state y0(:, j): the
   !> model (rods of en%m, en%l or the spring) by rk4 at step h for at most n_steps
   !> steps, stop rule `rule`. tol: relative tolerance of the final state, the flip
   !> times and the energy error; `kinds` lists statuses that must occur.
   subroutine compare_map(error, what, map, en, y0, h, n_steps, rule, tol, kinds, all_run)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      character(len=*), intent(in) :: what                !! test name, for the printout
      type(map_t), intent(in) :: map                      !! the file's datasets
      type(energy_t), intent(in) :: en                    !! model and its closed forms
      real(dp), intent(in) :: y0(:, :)                    !! (2N, n) initial states
      real(dp), intent(in) :: h                           !! step [s]
      integer(i8), intent(in) :: n_steps                  !! steps to t_end
      integer, intent(in) :: rule                         !! stop rule
      real(dp), intent(in) :: tol                         !! relative tolerance
      integer, intent(in), optional :: kinds(:)           !! statuses that must occur
      logical, intent(in), optional :: all_run            !! indicator map: every pixel
                                                          !! runs to t_end (default false)
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(model_spec_t) :: spec
      type(ref_t) :: r
      real(dp) :: worst(4)
      character(len=16) :: px
      integer :: j, k
      logical :: every
      if (allocated(error)) return
      every = .false.
      if (present(all_run)) every = all_run
      if (en%spring) then
         spec = model_spec('elastic')
         call spec%set('m', en%m); call spec%set('k', [en%k]); call spec%set('l0', [en%l0])
         call spec%set('g', [en%g])
         call new_model(spec, model, err)
      else
         call pendulum(model, en%m, en%l, en%g, err)
      end if
      if (.not. allocated(err)) call new_integrator('rk4', integ, err)
      if (allocated(err)) then
         call fatal_error(error, err%message)
         return
      end if
      worst = 0
      do j = 1, map%n
         write (px, '("pixel ", i0)') j
         call rerun(model, integ, en, y0(:, j), h, n_steps, rule, every, r)
         call check_true(error, map%status(j) == r%status, trim(px)//': status '// &
                         to_str(map%status(j))//', rerun '//to_str(r%status))
         if (allocated(map%steps)) call check_true(error, map%steps(j) == r%steps, &
                                                    trim(px)//': steps '//to_str(map%steps(j)) &
                                                    //', rerun '//to_str(r%steps))
         call check(error, map%t_stop(j), r%t_stop, trim(px)//': t_stop', rel=1e-14_dp)
         call check(error, map%e0(j), r%e0, trim(px)//': energy0 (closed form)', &
                    rel=1e-13_dp, abs=1e-13_dp)
         call check(error, map%y(:, j), r%y, trim(px)//': final state (q, w)', rel=tol, &
                    abs=tol)
         if (ieee_is_nan(r%err)) then
            call check_true(error, ieee_is_nan(map%err(j)), trim(px)//': energy_error NaN '// &
                            '(not integrated)')
         else
            call check(error, map%err(j), r%err, trim(px)//': energy_error', rel=1e-7_dp, &
                       abs=1e-14_dp)
            worst(4) = max(worst(4), abs(map%err(j) - r%err)/max(abs(r%err), 1e-300_dp))
         end if
         if (allocated(map%tf)) then
            do k = 1, size(map%tf, 1)
               call same_time(map%tf(k, j), r%tf(k), trim(px)//': t_flip'//to_str(k))
            end do
            call same_time(map%t_any(j), r%t_any, trim(px)//': t_flip')
            worst(2) = max(worst(2), maxval(abs(map%tf(:, j) - r%tf), &
                                            mask=.not. ieee_is_nan(r%tf)))
         end if
         worst(1) = max(worst(1), maxval(abs(map%y(:, j) - r%y)))
         worst(3) = max(worst(3), abs(map%e0(j) - r%e0))
         if (allocated(error)) return
      end do
      if (present(kinds)) then
         do k = 1, size(kinds)
            call check_true(error, any(map%status == kinds(k)), 'a pixel of status '// &
                            to_str(kinds(k))//' (the test covers it)')
         end do
      end if
      if (map%n > 1) write (output_unit, '(a, 4es9.2)') '    '//what//': largest '// &
         'differences from the reruns: final state, flip time [s], energy0 [J], '// &
         'relative energy_error', worst
   contains
      subroutine same_time(x, y, name)
         real(dp), intent(in) :: x, y
         character(len=*), intent(in) :: name
         if (ieee_is_nan(y)) then
            call check_true(error, ieee_is_nan(x), name//': NaN (no flip) in the rerun, '// &
                            'not in the file')
         else
            call check_true(error, .not. ieee_is_nan(x), name//': a flip in the rerun, '// &
                            'NaN in the file')
            if (.not. allocated(error)) call check(error, x, y, name, rel=tol, abs=tol)
         end if
      end subroutine same_time
   end subroutine compare_map

   !> One pixel of `map` as a map of its own.
   function pixel(map, j) result(one)
      type(map_t), intent(in) :: map
      integer, intent(in) :: j
      type(map_t) :: one
      one%n = 1
      one%t_any = [map%t_any(j)]
      if (allocated(map%tf)) one%tf = map%tf(:, j:j)
      one%e0 = [map%e0(j)]; one%err = [map%err(j)]; one%t_stop = [map%t_stop(j)]
      one%y = map%y(:, j:j)
      one%status = [map%status(j)]
      if (allocated(map%steps)) one%steps = [map%steps(j)]
   end function pixel

   !> Run y0 again: rk4 steps of h through `integ%step`, the flips, the stop rule,
   !> the flip energy bounds (a pixel below every bound has status 3 and is not
   !> integrated unless `every`) and the largest |E(t_k) − E(0)| over the steps, in
   !> the test's own code.
   subroutine rerun(model, integ, en, y0, h, n_steps, rule, every, r)
      class(model_t), intent(in) :: model
      class(integrator_t), intent(inout) :: integ
      type(energy_t), intent(in) :: en
      real(dp), intent(in) :: y0(:), h
      integer(i8), intent(in) :: n_steps
      integer, intent(in) :: rule
      logical, intent(in) :: every
      type(ref_t), intent(out) :: r
      real(dp), allocatable :: gl(:), bound(:), p(:), y(:)
      logical, allocatable :: can(:)
      real(dp) :: t, hs, scale, nan, qc
      integer(i8) :: ks
      integer :: nl, i, k, stat
      logical :: ended
      nl = size(y0)/2
      nan = ieee_value(nan, ieee_quiet_nan)
      r%e0 = energy(en, y0)
      allocate (r%tf(nl))
      r%tf = nan
      r%t_any = nan
      r%y = y0
      if (en%spring) then
         e_ref: block
            real(dp) :: e_ref
            e_ref = en%m(1)*en%g*en%l0 + 0.5_dp*en%k*en%l0**2
            scale = merge(abs(r%e0), e_ref, abs(r%e0) >= 1e-3_dp*e_ref)
         end block e_ref
         allocate (can(nl))
         can = .false.
      else
         allocate (gl(nl), bound(nl), can(nl))
         do i = 1, nl
            gl(i) = en%g*en%l(i)*(0.5_dp*en%m(i) + sum(en%m(i + 1:)))
         end do
         do i = 1, nl
            bound(i) = gl(i) - (sum(gl) - gl(i))
            can(i) = .not. (r%e0 < bound(i) - 1e-12_dp*sum(gl))
         end do
         scale = 2.0_dp*sum(gl)
         if (.not. any(can) .and. .not. every) then
            r%status = 3; r%err = nan; r%t_stop = 0; r%steps = 0
            return
         end if
      end if
      y = y0
      t = 0.0_dp
      r%err = 0.0_dp
      call integ%clear_step()
      do ks = 1, n_steps
         p = y(1:nl)
         hs = h
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) then
            r%status = 4; r%err = nan
            exit
         end if
         t = real(ks, dp)*h
         r%err = max(r%err, abs(energy(en, y) - r%e0))
         do i = 1, merge(0, nl, en%spring)
            k = crossing(p(i), y(i))
            if (k /= huge(1) .and. ieee_is_nan(r%tf(i))) then
               qc = half_pi + two_pi*real(k, dp)
               r%tf(i) = (real(ks - 1, dp) + (qc - p(i))/(y(i) - p(i)))*h
            end if
         end do
         select case (rule)
         case (rule_both)
            ended = all(.not. ieee_is_nan(r%tf) .or. .not. can)
         case (rule_either)
            ended = any(.not. ieee_is_nan(r%tf))
         case default
            ended = .false.
         end select
         if (ended .or. ks == n_steps) exit
      end do
      r%steps = int(min(ks, n_steps))
      r%t_stop = real(r%steps, dp)*h
      r%y = y
      if (r%status /= 4) then
         r%status = merge(1, 2, r%steps == n_steps)
         if (.not. (en%spring .or. any(can))) r%status = 3
         r%err = r%err/scale
      end if
      if (any(.not. ieee_is_nan(r%tf))) r%t_any = minval(r%tf, mask=.not. ieee_is_nan(r%tf))
   end subroutine rerun

   !> The upward vertical q = π/2 + 2π k crossed from a to b (the larger k when
   !> several), huge(1) when none: the windows (π/2 + 2π k, π/2 + 2π (k + 1)] of a and
   !> b differ.
   integer function crossing(a, b) result(k)
      real(dp), intent(in) :: a, b   !! angle before and after the step [rad]
      integer :: ka, kb
      ka = floor((a - half_pi)/two_pi)
      kb = floor((b - half_pi)/two_pi)
      k = huge(1)
      if (ka /= kb) k = max(ka, kb)
   end function crossing

   !> Energy in closed form [J]: uniform rods (centres C_i, I = m L²/12, V = 0 with
   !> every link horizontal) or the spring pendulum.
   pure real(dp) function energy(en, y) result(e)
      type(energy_t), intent(in) :: en
      real(dp), intent(in) :: y(:)   !! (q, q̇)
      real(dp) :: vj(2), vc(2), yj, yc
      integer :: nl, i
      nl = size(y)/2
      if (en%spring) then
         e = 0.5_dp*en%m(1)*(y(3)**2 + (y(1)*y(4))**2) + 0.5_dp*en%k*(y(1) - en%l0)**2 + &
             en%m(1)*en%g*y(1)*sin(y(2))
         return
      end if
      e = 0.0_dp
      vj = 0.0_dp; yj = 0.0_dp
      do i = 1, nl
         vc = vj + 0.5_dp*en%l(i)*y(nl + i)*[-sin(y(i)), cos(y(i))]
         yc = yj + 0.5_dp*en%l(i)*sin(y(i))
         e = e + 0.5_dp*en%m(i)*sum(vc**2) + en%m(i)*en%l(i)**2*y(nl + i)**2/24.0_dp + &
             en%m(i)*en%g*yc
         vj = vj + en%l(i)*y(nl + i)*[-sin(y(i)), cos(y(i))]
         yj = yj + en%l(i)*sin(y(i))
      end do
   end function energy

   !> The pendulum of links (m, l) from the factory (two links: the double
   !> pendulum's own formulation).
   subroutine pendulum(model, m, l, g, err)
      class(model_t), allocatable, intent(out) :: model
      real(dp), intent(in) :: m(:), l(:), g
      type(error_t), allocatable, intent(out) :: err
      type(model_spec_t) :: spec
      spec = model_spec('pendulum')
      call spec%set('links', [real(size(m), dp)])
      call spec%set('m', m); call spec%set('l', l); call spec%set('g', [g])
      call new_model(spec, model, err)
   end subroutine pendulum

   !> y0 run n steps of h (no stop): the end state.
   subroutine run_to(model, integ, y0, h, n, y)
      class(model_t), intent(in) :: model
      class(integrator_t), intent(inout) :: integ
      real(dp), intent(in) :: y0(:), h
      integer(i8), intent(in) :: n
      real(dp), intent(out) :: y(:)
      real(dp) :: t, hs
      integer(i8) :: ks
      integer :: stat
      y = y0
      t = 0.0_dp
      call integ%clear_step()
      do ks = 1, n
         hs = h
         call integ%step(model, t, y, hs, stat)
         t = real(ks, dp)*h
      end do
   end subroutine run_to

   !> The grid axis against min + (max − min) (i − 1)/(n − 1).
   subroutine check_axis(error, ax, lo, hi, n, name)
      type(error_t), allocatable, intent(inout) :: error
      real(dp), intent(in) :: ax(:), lo, hi
      integer, intent(in) :: n
      character(len=*), intent(in) :: name
      integer :: i
      if (allocated(error)) return
      call check_true(error, size(ax) == n, name//' holds n values')
      if (allocated(error)) return
      call check(error, ax, [(lo + (hi - lo)*real(i - 1, dp)/real(n - 1, dp), i=1, n)], &
                 name//' from min, max, n', rel=1e-15_dp, abs=1e-15_dp)
   end subroutine check_axis

   !> A real dataset of a grid (n1, n2) or a list (n) as a vector of pixels.
   subroutine read_px(h5, name, v, error)
      type(h5file_t), intent(inout) :: h5
      character(len=*), intent(in) :: name
      real(dp), allocatable, intent(out) :: v(:)
      type(error_t), allocatable, intent(inout) :: error
      real(dp), allocatable :: a(:, :)
      integer, allocatable :: dims(:)
      if (allocated(error)) return
      call h5%shape(name, dims, error)
      if (allocated(error)) return
      if (size(dims) == 2) then
         call h5%read(name, a, error)
         if (.not. allocated(error)) v = reshape(a, [size(a)])
      else
         call h5%read(name, v, error)
      end if
      if (allocated(error)) error%message = name//': '//error%message
   end subroutine read_px

   !> As read_px, into row `row` of a (rows, pixels) array.
   subroutine read_row(h5, name, a, row, error)
      type(h5file_t), intent(inout) :: h5
      character(len=*), intent(in) :: name
      real(dp), intent(inout) :: a(:, :)
      integer, intent(in) :: row
      type(error_t), allocatable, intent(inout) :: error
      real(dp), allocatable :: v(:)
      call read_px(h5, name, v, error)
      if (allocated(error)) return
      if (size(v) /= size(a, 2)) then
         call fatal_error(error, name//': '//to_str(size(v))//' pixels, expected '// &
                          to_str(size(a, 2)))
         return
      end if
      a(row, :) = v
   end subroutine read_row

   !> An integer dataset of a grid or a list as a vector of pixels.
   subroutine read_ipx(h5, name, v, error)
      type(h5file_t), intent(inout) :: h5
      character(len=*), intent(in) :: name
      integer, allocatable, intent(out) :: v(:)
      type(error_t), allocatable, intent(inout) :: error
      integer, allocatable :: a(:, :), dims(:)
      if (allocated(error)) return
      call h5%shape(name, dims, error)
      if (allocated(error)) return
      if (size(dims) == 2) then
         call h5%read(name, a, error)
         if (.not. allocated(error)) v = reshape(a, [size(a)])
      else
         call h5%read(name, v, error)
      end if
      if (allocated(error)) error%message = name//': '//error%message
   end subroutine read_ipx

end module test_values_sweep
