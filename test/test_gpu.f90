!> The GPU path of `dpend sweep` without a GPU (docs/gpu.md): the CUDA
!> kernel's per-trajectory code (src/gpu/dpend_gpu_step.h) compiled for the host
!> (src/gpu/dpend_gpu_host.c) against the Fortran batch kernel
!> (dpend_pendulum_lanes), and the refusals of --device that need no library.
!>
!> - `step_vs_rk4_lanes`: one RK4 step from the same state and the same carried sin
!>   and cos, the header's against `rk4_lanes`' lane, along trajectories of the
!>   classic map (chaotic, and one fast enough for the fallback path of |d| > 1/16);
!>   the Fortran trajectory drives both, so the comparison stays a one-step one
!>   (bit for bit in the debug build, within 1e-13 in the release build).
!> - `flip_map_vs_integrate_batch`: a 24 x 24 map of the classic pendulum to 10
!>   sqrt(L/g) under each stop rule, the header's whole trajectory logic (flip rule,
!>   energy skip, resynchronised sin and cos, statuses, closing pass) against
!>   `integrate_batch`: the same statuses and step counts, flip times and every other
!>   result within 1e-9 (the debug profile agrees bit for bit; the release profile's
!>   fused multiply-adds change the last bits, which 10 sqrt(L/g) amplifies to far
!>   less than that).
!> - `device_refusals`: --device and --gpu-repack values, and the maps the GPU does
!>   not compute, refused before any library is looked for.
!> - `device_attribute`: a CPU sweep's file says device = 'cpu'.
!> - `gpu_failure_falls_back_to_cpu`: a block meant for the GPU whose library call
!>   fails (here: none loaded) is computed by the CPU kernel, the same results, and
!>   counted for the file's `device` attribute.
module test_gpu
   use, intrinsic :: iso_c_binding, only: c_double, c_int, c_long_long
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use dpend_kinds, only: dp, half_pi
   use dpend_pendulum, only: pendulum_t
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t, stop_both, &
      stop_either, stop_end
   use dpend_pendulum_kernel, only: batch_coef_t, batch_coef, rk4_lanes, lane_trig_t, &
      set_lane_trig, sincos_exact, flip_energy_bounds, potential_range
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep
   use dpend_sweep_setup, only: sweep_summary_t, sweep_setup_t, build_setup
   use dpend_sweep_engine, only: run_sweep, compute_block
   use dpend_hdf5, only: h5file_t
   use dpend_sweep_gpu, only: gpu_fallback_blocks
   use test_cli, only: scratch_dir, args_of
   use testing, only: unittest_t, new_unittest, check_true, error_t
   implicit none
   private
   public :: collect_gpu

   interface
      subroutine host_step(coef, h, y, trig, e) bind(C, name='dpend_gpu_host_step')
         import :: c_double
         real(c_double), intent(in) :: coef(*)
         real(c_double), value :: h
         real(c_double), intent(inout) :: y(*), trig(*)
         real(c_double), intent(out) :: e
      end subroutine host_step
      subroutine host_block(coef, bounds, escale, h, n_steps, stop_rule, n, y0, t_flip1, &
                            t_flip2, t_flip, energy0, energy_error, t_stop, fin, status, &
                            steps) bind(C, name='dpend_gpu_host_block')
         import :: c_double, c_int, c_long_long
         real(c_double), intent(in) :: coef(*), bounds(*), y0(*)
         real(c_double), value :: escale, h
         integer(c_long_long), value :: n_steps
         integer(c_int), value :: stop_rule, n
         real(c_double), intent(out) :: t_flip1(*), t_flip2(*), t_flip(*), energy0(*)
         real(c_double), intent(out) :: energy_error(*), t_stop(*), fin(*)
         integer(c_int), intent(out) :: status(*), steps(*)
      end subroutine host_block
   end interface

contains

   !> The gpu suite.
   subroutine collect_gpu(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
         new_unittest('step_vs_rk4_lanes', test_step), &
         new_unittest('flip_map_vs_integrate_batch', test_flip_map), &
         new_unittest('device_refusals', test_refusals), &
         new_unittest('device_attribute', test_device_attribute), &
         new_unittest('gpu_failure_falls_back_to_cpu', test_fallback) &
         ]
   end subroutine collect_gpu

   !> batch_coef_t's ten constants in the order of the header's struct.
   function coef_array(c) result(a)
      type(batch_coef_t), intent(in) :: c  !! constants
      real(dp) :: a(10)
      a = [c%m11, c%m22, c%k, c%ga, c%gb, c%m11k, c%m22k, c%detk, c%gak, c%gbk]
   end function coef_array

   !> One step of the header against one step of `rk4_lanes` (lane 1; the other lanes
   !> hold the hanging state), from the Fortran trajectory's state and carried sin and
   !> cos, for 3000 steps of five trajectories of the classic pendulum (h = 0.005
   !> sqrt(L/g)); the sin and cos set exactly every 1024 steps as integrate_batch does.
   !> The state and the new sin and cos within 1e-13 of 1 + |q1| + |q2| + |q̇1| + |q̇2|
   !> (sin and cos inherit the angles' absolute rounding), the energy within 1e-13 of
   !> 1 + the sum of its terms' sizes. The debug build agrees bit for bit; the release
   !> build contracts products and sums into fused multiply-adds in the Fortran
   !> (-march) but not in the C: a few ulps of the terms, which cancel in the fast
   !> trajectory's velocities (measured 7e-16 in these units; test_copies' tolerance,
   !> 1e-13, for the same reason).
   subroutine test_step(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), parameter :: tol = 1e-13_dp
      real(dp), parameter :: starts(4, 5) = reshape([ &
         2.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, &      ! chaotic
         2.9_dp, -2.5_dp, 0.0_dp, 0.0_dp, &     ! chaotic, flips early
         -1.0_dp, 2.5_dp, 0.5_dp, -0.3_dp, &
         0.1_dp, -0.2_dp, 0.0_dp, 0.0_dp, &     ! near the bottom (small angles)
         0.3_dp, 0.7_dp, 150.0_dp, -90.0_dp], & ! fast: |d| > 1/16, the fallback step
         [4, 5])
      type(pendulum_t) :: par
      type(batch_coef_t) :: c
      type(lane_trig_t) :: tr
      real(dp), dimension(lane_width) :: q1, q2, w1, w2, e
      real(dp) :: coef(10), y(4), trig(4), ec, h, worst, d
      integer :: k, s
      par = pendulum_t(m1=1.0_dp, m2=1.0_dp, l1=1.0_dp, l2=1.0_dp, g=9.8_dp)
      c = batch_coef(par)
      coef = coef_array(c)
      h = 0.005_dp*sqrt(1.0_dp/9.8_dp)
      worst = 0
      do k = 1, size(starts, 2)
         q1 = -half_pi; q2 = -half_pi; w1 = 0; w2 = 0
         q1(1) = starts(1, k) - half_pi; q2(1) = starts(2, k) - half_pi
         w1(1) = starts(3, k); w2(1) = starts(4, k)
         call set_lane_trig(q1, q2, tr)
         do s = 1, 3000
            y = [q1(1), q2(1), w1(1), w2(1)]
            trig = [tr%s1(1), tr%c1(1), tr%s2(1), tr%c2(1)]
            call host_step(coef, h, y, trig, ec)
            call rk4_lanes(c, h, q1, q2, w1, w2, e, tr)
            ! the state in units of its size (a velocity sums terms of h |q̇|² that cancel)
            d = maxval(abs(y - [q1(1), q2(1), w1(1), w2(1)])) &
                /(1.0_dp + sum(abs([q1(1), q2(1), w1(1), w2(1)])))
            ! sin and cos inherit the angles' absolute differences: the same units
            d = max(d, maxval(abs(trig - [tr%s1(1), tr%c1(1), tr%s2(1), tr%c2(1)])) &
                /(1.0_dp + sum(abs([q1(1), q2(1), w1(1), w2(1)]))))
            ! the energy's error in units of its terms (T's three and V's two: they cancel)
            d = max(d, abs(ec - e(1))/(1.0_dp + 0.5_dp*(c%m11*w1(1)**2 + 2.0_dp*c%k* &
                    abs(w1(1)*w2(1)) + c%m22*w2(1)**2) + abs(c%ga) + abs(c%gb)))
            worst = max(worst, d)
            if (d > tol) write (*, '(a, i0, a, i0, a, es10.3, a, 4es12.4)') &
               '       trajectory ', k, ' step ', s, ': difference ', d, ' at ', &
               q1(1), q2(1), w1(1), w2(1)
            call check_true(error, d <= tol, 'header step differs from rk4_lanes '// &
                            'beyond 1e-13 (trajectory '//achar(48 + k)//')')
            if (allocated(error)) return
            if (mod(s, 1024) == 0) then
               call sincos_exact(q1(1), tr%s1(1), tr%c1(1))
               call sincos_exact(q2(1), tr%s2(1), tr%c2(1))
            end if
         end do
      end do
      write (*, '(a, es9.2)') '       largest one-step difference: ', worst
   end subroutine test_step

   !> The header's whole flip map against integrate_batch, each stop rule.
   subroutine test_flip_map(error)
      type(error_t), allocatable, intent(out) :: error
      integer, parameter :: n1 = 24, n = n1*n1
      type(pendulum_t) :: par
      type(batch_options_t) :: opt
      type(batch_result_t) :: ref
      real(dp) :: y0(4, n), coef(10), bounds(2), th
      real(dp) :: tf1(n), tf2(n), tf(n), e0(n), err(n), ts(n), fin(4, n)
      integer(c_int) :: st(n), steps(n)
      integer :: i, j, r
      integer, parameter :: rules(3) = [stop_both, stop_either, stop_end]
      par = pendulum_t(m1=1.0_dp, m2=1.0_dp, l1=1.0_dp, l2=1.0_dp, g=9.8_dp)
      do j = 1, n1
         do i = 1, n1
            th = -3.0_dp + 6.0_dp*real(i - 1, dp)/real(n1 - 1, dp)
            y0(1, i + n1*(j - 1)) = th - half_pi
            th = -3.0_dp + 6.0_dp*real(j - 1, dp)/real(n1 - 1, dp)
            y0(2, i + n1*(j - 1)) = th - half_pi
         end do
      end do
      y0(3:4, :) = 0
      y0(3, 7) = 40.0_dp   ! a fast one
      coef = coef_array(batch_coef(par))
      bounds = flip_energy_bounds(par)
      opt%n_steps = 2000
      opt%h = 10.0_dp*sqrt(1.0_dp/9.8_dp)/real(opt%n_steps, dp)
      do r = 1, size(rules)
         opt%stop_rule = rules(r)
         call integrate_batch(par, opt, y0, ref)
         call host_block(coef, bounds, potential_range(par), opt%h, &
                         int(opt%n_steps, c_long_long), int(opt%stop_rule, c_int), &
                         int(n, c_int), y0, tf1, tf2, tf, e0, err, ts, fin, st, steps)
         call check_true(error, all(st == ref%status), 'statuses differ (rule '// &
                         achar(48 + r)//')')
         if (.not. allocated(error)) call check_true(error, all(steps == ref%steps), &
                                                     'steps differ')
         if (.not. allocated(error)) call check_true(error, &
            close(tf1, ref%t_flip1) .and. close(tf2, ref%t_flip2) .and. &
            close(tf, ref%t_flip), 't_flip1, t_flip2, t_flip differ beyond 1e-9')
         if (.not. allocated(error)) call check_true(error, &
            close(e0, ref%energy0) .and. close(ts, ref%t_stop) .and. &
            close(reshape(fin, [4*n]), reshape(ref%final, [4*n])), &
            'energy0, t_stop or final differ beyond 1e-9')
         if (.not. allocated(error)) call check_true(error, close(err, ref%energy_error), &
                                                     'energy_error differs')
         if (.not. allocated(error)) call check_true(error, &
            count(st == 3) > 0 .and. count(st == 2) > 0 .eqv. r /= 3, &
            'the map has no skipped or no stopped pixels')
         if (allocated(error)) return
      end do
   contains
      !> Equal within 1e-9 (1 + |b|), NaN where the other is NaN.
      logical function close(a, b)
         real(dp), intent(in) :: a(:), b(:)
         integer :: k
         close = .true.
         do k = 1, size(a)
            if (ieee_is_nan(a(k)) .or. ieee_is_nan(b(k))) then
               close = close .and. (ieee_is_nan(a(k)) .eqv. ieee_is_nan(b(k)))
            else
               close = close .and. abs(a(k) - b(k)) <= 1e-9_dp*(1.0_dp + abs(b(k)))
            end if
         end do
      end function close
   end subroutine test_flip_map

   !> --device and --gpu-repack refused by value, and the GPU refused for what it
   !> does not compute (these refusals come before any library is looked for).
   subroutine test_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      call refused('--device xpu', "invalid device: 'xpu' (accepted: cpu, gpu, auto)")
      if (.not. allocated(error)) call refused('--device gpu --gpu-repack -1', &
                                               'invalid gpu_repack: -1')
      if (.not. allocated(error)) call refused('--device gpu --lyapunov', &
                                               'invalid device: gpu: the GPU computes flip maps')
      if (.not. allocated(error)) call refused('--device gpu --indicator megno', &
                                               'invalid device: gpu: the GPU computes flip maps')
      if (.not. allocated(error)) call refused('--device gpu --links 3', &
                                               'invalid device: gpu: the GPU computes the two-link')
      if (.not. allocated(error)) call refused('--device gpu --axis1 m2/m1 --min1 0.5 --max1 2', &
                                               'invalid device: gpu: the GPU computes maps over')
   contains
      subroutine refused(line, expected)
         character(len=*), intent(in) :: line, expected
         type(sweep_config_t) :: cfg
         type(error_t), allocatable :: err
         logical :: help
         call parse_sweep(args_of(line//' --n 4 --output never.h5'), cfg, help, err)
         call check_true(error, allocated(err), "'"//line//"' is refused")
         if (allocated(error)) return
         call check_true(error, index(err%message, expected) == 1, "'"//line// &
                         "' refused with: "//err%message)
      end subroutine refused
   end subroutine test_refusals

   !> The /sweep attribute device of a sweep computed on the CPU: 'cpu'.
   subroutine test_device_attribute(error)
      type(error_t), allocatable, intent(out) :: error
      type(sweep_config_t) :: cfg
      type(sweep_summary_t) :: summary
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      character(len=:), allocatable :: dir, device
      logical :: help
      dir = scratch_dir('gpuattr')
      call parse_sweep(args_of('--n 4 --t-end 1 --quiet --device cpu --output '//dir// &
                               '/d.h5'), cfg, help, err)
      if (.not. allocated(err)) call run_sweep(cfg, summary, err)
      if (.not. allocated(err)) call h5%open(dir//'/d.h5', 'r', err)
      if (.not. allocated(err)) call h5%readattr('/sweep', 'device', device, err)
      call h5%close()
      call check_true(error, .not. allocated(err), 'sweep written and its device read')
      if (allocated(error)) return
      call check_true(error, device == 'cpu', "device = '"//device//"', expected 'cpu'")
   end subroutine test_device_attribute

   !> compute_block with device = 'gpu' and no library loaded: the CPU kernel's
   !> results (one line on stderr says so).
   subroutine test_fallback(error)
      type(error_t), allocatable, intent(out) :: error
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: cpu, gpu
      type(error_t), allocatable :: err
      logical :: help
      integer :: before
      call parse_sweep(args_of('--n 6 --t-end 5 --stop-at either --output never.h5'), cfg, &
                       help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      call check_true(error, .not. allocated(err), 'configuration accepted')
      if (allocated(error)) return
      call compute_block(setup, 1, cpu)
      setup%cfg%device = 'gpu'
      before = gpu_fallback_blocks()
      call compute_block(setup, 1, gpu)
      ! the file's device attribute counts these blocks (create_layout)
      call check_true(error, gpu_fallback_blocks() == before + 1, 'the fallback is counted')
      if (allocated(error)) return
      call check_true(error, all(gpu%status == cpu%status) .and. all(gpu%steps == cpu%steps) &
                      .and. all(gpu%t_stop == cpu%t_stop) .and. &
                      all(gpu%energy0 == cpu%energy0), 'fallback results differ from the CPU''s')
   end subroutine test_fallback
end module test_gpu
