!> Per-lane constants and the shared tangent step of the batch kernel:
!> a lane with its own pendulum gives, bit for bit, what a kernel with that pendulum
!> in every lane gives; the two-vector tangent step equals two one-vector steps bit
!> for bit; the pixels of a sweep over (m2/m1, l2/l1) equal direct runs of the
!> kernel with each pixel's own parameters, bit for bit, flip times and indicators.
module test_lanes
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t
   use dpend_lane_batch, only: lane_width, batch_options_t, batch_result_t
   use dpend_pendulum_kernel, only: batch_coef, batch_coef_t, lane_coef_t, lane_coef, &
      set_lane_coef, rk4_lanes, energy_lanes, lane_trig_t, set_lane_trig
   use dpend_pendulum_tangent_lanes, only: rk4_tangent_lanes, rk4_tangent2_lanes, &
      rk4_tangent_fused_lanes, log_lanes
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_cli, only: arg_t, to_str
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep
   use dpend_sweep_setup, only: block_initial_conditions, block_parameters, sweep_setup_t, &
      build_setup, block_range
   use dpend_sweep_engine, only: compute_block
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error
   implicit none
   private
   public :: collect_lanes

   integer, parameter :: w = lane_width

contains

   !> The lanes suite.
   subroutine collect_lanes(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [new_unittest('lane_constants_bitwise', test_lane_constants), &
               new_unittest('tangent2_matches_tangent', test_tangent2), &
               new_unittest('ratio_axes_pixels_equal_direct_runs', test_ratio_axes), &
               new_unittest('tangent_fused_matches', test_tangent_fused), &
               new_unittest('log_lanes_vs_intrinsic', test_log_lanes)]
   end subroutine collect_lanes

   !> Lane l's pendulum of the tests: masses and lengths from 0.3 to 2.7.
   pure type(pendulum_t) function lane_pendulum(l) result(par)
      integer, intent(in) :: l  !! lane
      par%m1 = 0.3_dp + 0.15_dp*l
      par%m2 = 2.7_dp - 0.13_dp*l
      par%l1 = 0.4_dp + 0.11_dp*mod(7*l, w)
      par%l2 = 2.5_dp - 0.09_dp*mod(5*l, w)
   end function lane_pendulum

   !> 400 steps of `rk4_lanes`, `rk4_tangent_lanes` and `energy_lanes` with every
   !> lane its own pendulum (`lane_coef_t`) against the same with lane l's pendulum
   !> in every lane (`batch_coef_t`): lane l equal bit for bit.
   subroutine test_lane_constants(error)
      type(error_t), allocatable, intent(out) :: error
      type(lane_coef_t) :: lc
      type(batch_coef_t) :: bc
      real(dp), dimension(w) :: q1, q2, w1, w2, e, u1, u2, v1, v2
      real(dp), dimension(w) :: p1, p2, pw1, pw2, pe, pu1, pu2, pv1, pv2
      real(dp), dimension(w) :: q10, q20, w10, w20
      type(lane_trig_t) :: tr, ptr
      real(dp), parameter :: h = 0.005_dp
      integer :: l, i, k
      logical :: same
      do l = 1, w
         call set_lane_coef(lc, l, batch_coef(lane_pendulum(l)))
         q10(l) = -1.0_dp + 0.17_dp*l; q20(l) = 2.0_dp - 0.23_dp*l
         w10(l) = 0.3_dp*mod(l, 3); w20(l) = -0.5_dp + 0.1_dp*l
      end do
      same = .true.
      ! carried sin/cos (rk4_lanes) and the tangent step
      q1 = q10; q2 = q20; w1 = w10; w2 = w20
      u1 = 1; u2 = 0.5_dp; v1 = -0.25_dp; v2 = 0.125_dp
      call set_lane_trig(q1, q2, tr)
      do k = 1, 400
         call rk4_lanes(lc, h, q1, q2, w1, w2, e, tr)
      end do
      do l = 1, w
         p1 = q10; p2 = q20; pw1 = w10; pw2 = w20
         call set_lane_trig(p1, p2, ptr)
         do k = 1, 400
            call rk4_lanes(batch_coef(lane_pendulum(l)), h, p1, p2, pw1, pw2, pe, ptr)
         end do
         same = same .and. all([p1(l), p2(l), pw1(l), pw2(l), pe(l), ptr%s1(l), ptr%c2(l)] &
                               == [q1(l), q2(l), w1(l), w2(l), e(l), tr%s1(l), tr%c2(l)])
      end do
      call check_true(error, same, 'rk4_lanes: lane l with its own constants = lane l of '// &
                      'a run with its pendulum in every lane, bit for bit')
      if (allocated(error)) return
      q1 = q10; q2 = q20; w1 = w10; w2 = w20
      do k = 1, 400
         call rk4_tangent_lanes(lc, h, q1, q2, w1, w2, u1, u2, v1, v2, e)
      end do
      do l = 1, w
         p1 = q10; p2 = q20; pw1 = w10; pw2 = w20
         pu1 = 1; pu2 = 0.5_dp; pv1 = -0.25_dp; pv2 = 0.125_dp
         do k = 1, 400
            call rk4_tangent_lanes(batch_coef(lane_pendulum(l)), h, p1, p2, pw1, pw2, &
                                   pu1, pu2, pv1, pv2, pe)
         end do
         same = same .and. all([p1(l), pw2(l), pu1(l), pu2(l), pv1(l), pv2(l), pe(l)] &
                               == [q1(l), w2(l), u1(l), u2(l), v1(l), v2(l), e(l)])
         call energy_lanes(batch_coef(lane_pendulum(l)), q1, q2, w1, w2, pe)
         call energy_lanes(lc, q1, q2, w1, w2, pw1)
         same = same .and. pe(l) == pw1(l)
      end do
      call check_true(error, same, 'rk4_tangent_lanes, energy_lanes: lane l with its own '// &
                      'constants = lane l of a run with its pendulum in every lane')
      ! the lanes' constants themselves
      do i = 1, w
         bc = batch_coef(lane_pendulum(i))
         same = same .and. lc%k(i) == bc%k .and. lc%gbk(i) == bc%gbk .and. lc%m11(i) == bc%m11
      end do
      lc = lane_coef(bc)
      call check_true(error, same .and. all(lc%detk == bc%detk) .and. all(lc%ga == bc%ga), &
                      'set_lane_coef and lane_coef copy batch_coef')
   end subroutine test_lane_constants

   !> 300 steps of `rk4_tangent2_lanes` (SALI's two vectors at once, one Jacobian per
   !> stage) against `rk4_tangent_lanes` on each vector alone: state, both vectors
   !> and energy equal bit for bit, every lane its own pendulum.
   subroutine test_tangent2(error)
      type(error_t), allocatable, intent(out) :: error
      type(lane_coef_t) :: lc
      real(dp), dimension(w) :: q1, q2, w1, w2, e, p1, p2, pw1, pw2, pe
      real(dp) :: d(w, 4, 2), d1(w, 4), d2(w, 4)
      real(dp), parameter :: h = 0.01_dp
      integer :: l, k
      logical :: same
      do l = 1, w
         call set_lane_coef(lc, l, batch_coef(lane_pendulum(l)))
      end do
      call tangent_start(q1, q2, w1, w2, d)
      p1 = q1; p2 = q2; pw1 = w1; pw2 = w2
      d1 = d(:, :, 1); d2 = d(:, :, 2)
      same = .true.
      do k = 1, 300
         call rk4_tangent2_lanes(lc, h, q1, q2, w1, w2, d, e)
         call rk4_tangent_lanes(lc, h, p1, p2, pw1, pw2, d1(:, 1), d1(:, 2), d1(:, 3), &
                                d1(:, 4), pe)
         same = same .and. all(e == pe) .and. all(q1 == p1) .and. all(q2 == p2) .and. &
                all(w1 == pw1) .and. all(w2 == pw2) .and. all(d(:, :, 1) == d1)
      end do
      ! vector 2 along the same trajectory, from the start again
      call check_true(error, same, 'rk4_tangent2_lanes: state and vector 1 = rk4_tangent_lanes')
      if (allocated(error)) return
      call second_vector(error)
   contains
      subroutine second_vector(error)
         type(error_t), allocatable, intent(out) :: error
         real(dp) :: dd(w, 4, 2)
         call tangent_start(q1, q2, w1, w2, dd)
         p1 = q1; p2 = q2; pw1 = w1; pw2 = w2
         d2 = dd(:, :, 2)
         do k = 1, 300
            call rk4_tangent2_lanes(lc, h, q1, q2, w1, w2, dd, e)
            call rk4_tangent_lanes(lc, h, p1, p2, pw1, pw2, d2(:, 1), d2(:, 2), d2(:, 3), &
                                   d2(:, 4), pe)
            same = same .and. all(dd(:, :, 2) == d2)
         end do
         call check_true(error, same, 'rk4_tangent2_lanes: vector 2 = rk4_tangent_lanes')
      end subroutine second_vector
   end subroutine test_tangent2

   !> 200 steps of `rk4_tangent_fused_lanes` (the tangent step fused into one
   !> loop body, sin and cos carried from step to step) against `rk4_tangent_lanes`
   !> (one vector) and `rk4_tangent2_lanes` (two), which take exact sin and cos at
   !> every step start: state, vectors and energy equal to 1e-9 relative (they differ
   !> by rounding: the carried sines, the stages' shorter polynomials, FMA contraction
   !> in the release profile), every lane its own pendulum;
   !> lane 3 starts fast (stage offsets beyond d_max), so that the fallback to those
   !> routines runs too, and lane 5 beyond sincos_exact_max (2e6 rad), where the
   !> carried sines start from the intrinsic's.
   subroutine test_tangent_fused(error)
      type(error_t), allocatable, intent(out) :: error
      type(lane_coef_t) :: lc
      type(lane_trig_t) :: tr
      real(dp), dimension(w) :: q1, q2, w1, w2, e, p1, p2, pw1, pw2, pe
      real(dp) :: d(w, 4, 2), dr(w, 4, 2)
      real(dp), parameter :: h = 0.01_dp
      integer :: l, k, nv
      logical :: same
      real(dp) :: worst
      same = .true.
      worst = 0
      do nv = 1, 2
         do l = 1, w
            call set_lane_coef(lc, l, batch_coef(lane_pendulum(l)))
         end do
         call tangent_start(q1, q2, w1, w2, d)
         w1(3) = 20.0_dp
         q2(5) = 2.0e6_dp
         call set_lane_trig(q1, q2, tr)
         p1 = q1; p2 = q2; pw1 = w1; pw2 = w2; dr = d
         do k = 1, 200
            call rk4_tangent_fused_lanes(lc, h, q1, q2, w1, w2, nv, d, e, tr)
            if (nv == 1) then
               call rk4_tangent_lanes(lc, h, p1, p2, pw1, pw2, dr(:, 1, 1), dr(:, 2, 1), &
                                      dr(:, 3, 1), dr(:, 4, 1), pe)
            else
               call rk4_tangent2_lanes(lc, h, p1, p2, pw1, pw2, dr, pe)
            end if
            worst = max(worst, rel(e, pe), rel(q1, p1), rel(q2, p2), rel(w1, pw1), &
                        rel(w2, pw2), rel(reshape(d(:, :, 1:nv), [4*w*nv]), &
                                          reshape(dr(:, :, 1:nv), [4*w*nv])))
         end do
      end do
      write (*, '(4x, a, es10.3)') 'rk4_tangent_fused_lanes vs rk4_tangent_lanes, '// &
         'rk4_tangent2_lanes: largest relative difference ', worst
      call check_true(error, worst <= 1e-9_dp, 'rk4_tangent_fused_lanes = rk4_tangent_lanes '// &
                      '(1 vector), rk4_tangent2_lanes (2 vectors) to 1e-9 relative')
      if (allocated(error)) return
      call lanes_independent(error)
   contains
      !> Lane 3 on the fallback or not: the other lanes' values are the same bit for
      !> bit (also in the release profile, where the two paths may differ by rounding).
      subroutine lanes_independent(error)
         type(error_t), allocatable, intent(out) :: error
         real(dp) :: da(w, 4, 2), qa(w, 4), ea(w)
         integer :: run
         do run = 1, 2
            call tangent_start(q1, q2, w1, w2, d)
            if (run == 2) w1(3) = 20.0_dp
            call set_lane_trig(q1, q2, tr)
            do k = 1, 50
               call rk4_tangent_fused_lanes(lc, h, q1, q2, w1, w2, 2, d, e, tr)
            end do
            if (run == 1) then
               da = d; ea = e
               qa(:, 1) = q1; qa(:, 2) = q2; qa(:, 3) = w1; qa(:, 4) = w2
            end if
         end do
         same = .true.
         do l = 1, w
            if (l == 3) cycle
            same = same .and. all(d(l, :, :) == da(l, :, :)) .and. e(l) == ea(l) .and. &
                   q1(l) == qa(l, 1) .and. q2(l) == qa(l, 2) .and. w1(l) == qa(l, 3) .and. &
                   w2(l) == qa(l, 4)
         end do
         call check_true(error, same, 'rk4_tangent_fused_lanes: a lane on the fallback '// &
                         'leaves the other lanes unchanged')
      end subroutine lanes_independent

      !> Largest |a - b| / max(|b|, 1e-300) [1].
      pure real(dp) function rel(a, b)
         real(dp), intent(in) :: a(:), b(:)
         rel = maxval(abs(a - b)/max(abs(b), 1e-300_dp))
      end function rel
   end subroutine test_tangent_fused

   !> The start of the tangent tests: lane l at q = (0.1 l, -0.2 l) rad, q̇ = (1 - 0.1 l,
   !> 0.05 l) rad/s, vectors d(l, j, 1) = 0.5^j + 0.01 l, d(l, j, 2) = (-0.7)^j - 0.02 l.
   pure subroutine tangent_start(q1, q2, w1, w2, d)
      real(dp), dimension(w), intent(out) :: q1, q2  !! angles [rad]
      real(dp), dimension(w), intent(out) :: w1, w2  !! velocities [rad/s]
      real(dp), intent(out) :: d(w, 4, 2)            !! deviation vectors
      integer :: l, j
      do l = 1, w
         q1(l) = 0.1_dp*l; q2(l) = -0.2_dp*l; w1(l) = 1.0_dp - 0.1_dp*l; w2(l) = 0.05_dp*l
         do j = 1, 4
            d(l, j, 1) = 0.5_dp**j + 0.01_dp*l
            d(l, j, 2) = (-0.7_dp)**j - 0.02_dp*l
         end do
      end do
   end subroutine tangent_start

   !> A sweep over (m2/m1, l2/l1), 5 × 5 pixels in blocks of 7 (lanes refilled with
   !> other parameters), flip map and SALI map: every pixel equals, bit for bit, the
   !> kernel run on that pixel alone with its own pendulum (m2 = r1 m1, l2 = r2 l1
   !> from the axes, checked to the last bit of the product) — flip times, final
   !> state, energy error, steps, status, and the indicators.
   subroutine test_ratio_axes(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=16), parameter :: base(26) = [character(len=16) :: '--n', '5', &
         '--axis1', 'm2/m1', '--axis2', 'l2/l1', '--min1', '0.3', '--max1', '3', &
         '--min2', '0.4', '--max2', '2.5', '--t-end', '4', '--time-unit', 's', '--dt', &
         '0.01', '--block', '7', '--q1', '0', '--q2', '0.5']
      character(len=16), parameter :: ind(2) = [character(len=16) :: '--stats', '--quiet']
      character(len=16), parameter :: sal(2) = [character(len=16) :: '--indicator', 'sali']
      call one_map([base, ind], error)
      if (.not. allocated(error)) call one_map([base, ind, sal], error)
   end subroutine test_ratio_axes

   !> The map of `words` against direct runs (`test_ratio_axes`).
   subroutine one_map(words, error)
      character(len=16), intent(in) :: words(:)
      type(error_t), allocatable, intent(out) :: error
      type(arg_t), allocatable :: args(:)
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(batch_result_t) :: res, one
      type(pendulum_t) :: par
      type(error_t), allocatable :: err
      real(dp), allocatable :: y0(:, :), p(:, :)
      logical :: help, same
      integer :: j, b, j0, nb, i1, i2, nflip
      allocate (args(size(words)))
      do j = 1, size(words)
         args(j)%s = trim(words(j))
      end do
      call parse_sweep(args, cfg, help, err)
      if (.not. allocated(err)) call build_setup(cfg, setup, err)
      if (allocated(err)) then
         call fatal_error(error, 'set-up: '//err%message)
         return
      end if
      same = .true.
      nflip = 0
      do b = 1, setup%nblocks
         call compute_block(setup, b, res)
         call block_initial_conditions(setup, b, y0)
         call block_parameters(setup, b, p)
         call block_range(setup, b, j0, nb)
         do j = 1, nb
            i1 = mod(j0 + j - 2, cfg%n1) + 1
            i2 = (j0 + j - 2)/cfg%n1 + 1
            par = cfg%run%pendulum()
            par%m2 = setup%axis1(i1)*par%m1
            par%l2 = setup%axis2(i2)*par%l1
            call check_true(error, all(p(:, j) == [par%m1, par%m2, par%l1, par%l2]), &
                            'pixel parameters: m2 = (m2/m1) m1, l2 = (l2/l1) l1')
            if (allocated(error)) return
            call integrate_batch(par, setup%opt, y0(:, j:j), one)
            same = same .and. eq(res%t_flip1(j), one%t_flip1(1)) .and. &
                   eq(res%t_flip2(j), one%t_flip2(1)) .and. eq(res%t_flip(j), one%t_flip(1)) &
                   .and. all(res%final(:, j) == one%final(:, 1)) .and. &
                   eq(res%energy0(j), one%energy0(1)) .and. &
                   eq(res%energy_error(j), one%energy_error(1)) .and. &
                   res%steps(j) == one%steps(1) .and. res%status(j) == one%status(1) .and. &
                   eq(res%sali(j), one%sali(1)) .and. eq(res%gali2(j), one%gali2(1)) .and. &
                   eq(res%megno(j), one%megno(1)) .and. eq(res%fli(j), one%fli(1))
            if (one%t_flip(1) == one%t_flip(1)) nflip = nflip + 1
         end do
      end do
      call check_true(error, same, trim(words(size(words)))// &
                      ': every pixel = a direct run with its parameters, bit for bit')
      if (.not. allocated(error)) call check_true(error, nflip > 0 .and. nflip < 25 .or. &
                                                  cfg%indicator /= 'flip', &
                                                  'some pixels flip, some do not: '// &
                                                  to_str(nflip))
   contains
      !> Equal bit for bit, or both NaN.
      logical function eq(x, y)
         real(dp), intent(in) :: x, y
         eq = transfer(x, 1_i8) == transfer(y, 1_i8) .or. (x /= x .and. y /= y)
      end function eq
   end subroutine one_map

   !> `log_lanes` (the indicators' vectorizable ln) against the intrinsic log: within
   !> 1 ulp of it over 2^-1000 .. 2^1000 (random exponents and mantissas, and
   !> arguments next to 1, where the result is small), and equal to it on the lanes
   !> it hands to the intrinsic (subnormal, Inf, NaN; not 0 or negative, whose log
   !> traps in the debug profile, and which a norm never is but by underflow).
   subroutine test_log_lanes(error)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
         ieee_is_nan
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: x(w), r(w), u(w), worst, special(7)
      integer :: k, i
      logical :: same
      worst = 0
      do k = 1, 2000
         call random_number(u)
         if (mod(k, 2) == 0) then
            x = exp((u - 0.5_dp)*1386.0_dp)            ! e^±693: 2^±1000
         else
            x = 1.0_dp + (u - 0.5_dp)*2.0_dp**(-mod(k, 50))  ! next to 1
         end if
         call log_lanes(x, r)
         do i = 1, w
            worst = max(worst, abs(r(i) - log(x(i)))/spacing(max(abs(log(x(i))), tiny(1.0_dp))))
         end do
      end do
      write (*, '(4x, a, f0.3, a)') 'log_lanes vs log: largest difference ', worst, ' ulp'
      call check_true(error, worst <= 1.0_dp, 'log_lanes within 1 ulp of the intrinsic log')
      if (allocated(error)) return
      special = [tiny(1.0_dp)/8, tiny(1.0_dp)*2.0_dp**(-40), &
                 ieee_value(1.0_dp, ieee_positive_inf), ieee_value(1.0_dp, ieee_quiet_nan), &
                 huge(1.0_dp), tiny(1.0_dp), 1.0_dp]
      x = 2.0_dp
      x(1:7) = special
      call log_lanes(x, r)
      same = .true.
      do i = 1, w
         if (ieee_is_nan(log(x(i)))) then
            same = same .and. ieee_is_nan(r(i))
         else if (x(i) > huge(1.0_dp)) then
            same = same .and. r(i) == log(x(i))
         else
            same = same .and. abs(r(i) - log(x(i))) <= spacing(abs(log(x(i))))
         end if
      end do
      call check_true(error, same, 'log_lanes = log (1 ulp) at subnormals, Inf, NaN, huge, tiny, 1')
   end subroutine test_log_lanes
end module test_lanes
