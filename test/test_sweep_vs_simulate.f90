!> The values a two-link sweep writes (the vectorized batch kernel and the sweep's
!> writer) against independent per-trajectory runs (a mutant that survived the
!> earlier suite: the two links' final angles written swapped): every pixel of a 4 × 4 grid (asymmetric
!> links, w1 ≠ 0, run to t_end) is simulated again with `dpend simulate` (the double
!> pendulum model, rk4 at the same step, every step sampled), and the file's
!> `final/q1`, `final/q2`, `final/w1`, `final/w2` and `energy0` must equal the
!> simulated end state and initial energy (Lagrange's form in lanes against the
!> model's field: they differ by rounding only; measured largest difference 1.3e-13 (tolerance 1e-12), printed,
!> '    sweep_vs_simulate: …'), and `status` must be 1 (integrated to t_end).
!>
!> A damped and driven chain (damping, Coulomb friction, a moving support, applied
!> joint torques from a file; N = 2 and 3), swept one trajectory at a time with its
!> works: every pixel of a 3 × 3 grid against `dpend simulate` at the same rk4 step,
!> its final state and its `energy_error` (the error of the energy balance,
!> max |E − E(0) + W_friction − W_support − W_torque| / potential_range, computed here
!> from simulate's datasets); no pixel below a flip bound (energy is fed). With
!> damping alone the bound holds (energy only leaves), as in the conservative map.
!> And the closed form: one rod (g 1e-6) under a constant torque τ with viscous damping
!> c from rest turns by
!>   q − q0 = (τ/c) (t − (J/c)(1 − exp(−c t/J))),  J = m l²/3,
!> so its flip time (q − q0 = π) is known; the sweep's matches it to 1e-6 (relative),
!> the linear interpolation of the flip within a step of 1 ms and gravity's share.
module test_sweep_vs_simulate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   use test_cli, only: run_command, scratch_dir
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_sweep_vs_simulate

   real(dp), parameter :: half_pi = 0.5_dp*acos(-1.0_dp)

contains

   subroutine collect_sweep_vs_simulate(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('final_state_matches_simulate', test_final_states), &
               new_unittest('forced_chain_pixels_match_simulate', test_forced_chain), &
               new_unittest('forced_rod_flip_time_closed_form', test_forced_flip), &
               new_unittest('forced_resume_key_has_the_torques', test_forced_resume), &
               new_unittest('forced_flip_bounds', test_forced_bounds)]
   end subroutine collect_sweep_vs_simulate

   !> A 4 × 4 theta1 × theta2 sweep against 16 simulate runs of its pixels.
   subroutine test_final_states(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: par = '--m1 1.3 --m2 0.9 --l1 1.1 --l2 0.8 --g 9.81 --w1 0.5'
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), fq1(:, :), fq2(:, :), fw1(:, :), fw2(:, :)
      real(dp), allocatable :: e0(:, :), q(:, :), qd(:, :), e(:)
      integer, allocatable :: status(:, :)
      real(dp) :: worst, worst_e, sim(4), swept(4)
      character(len=120) :: qs
      integer :: stat, i1, i2, n
      dir = scratch_dir('sweepvalues')
      stat = run_command(dir, 'sweep --quiet '//par//' --n 4 --min1 -3 --max1 3 --min2 -2.5 '// &
                         '--max2 2.5 --time-unit s --dt 0.01 --t-end 2 --stop-at end '// &
                         '--threads 1 --output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
      if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
      if (.not. allocated(error)) call h5%read('/sweep/status', status, error)
      if (.not. allocated(error)) call h5%read('/sweep/energy0', e0, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/q1', fq1, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/q2', fq2, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/w1', fw1, error)
      if (.not. allocated(error)) call h5%read('/sweep/final/w2', fw2, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, size(ax1) == 4 .and. size(ax2) == 4 .and. &
                      all(shape(fq1) == [4, 4]), 'a 4 x 4 grid')
      if (allocated(error)) return
      worst = 0.0_dp; worst_e = 0.0_dp
      do i2 = 1, 4
         do i1 = 1, 4
            call check_true(error, status(i1, i2) == 1, 'status 1 (integrated to t_end)')
            write (qs, '("--q1 ", es25.16e3, " --q2 ", es25.16e3)') ax1(i1) - half_pi, &
               ax2(i2) - half_pi
            call simulated_run(dir, par//' '//trim(qs)//' --w2 0', q, qd, e, error)
            if (allocated(error)) return
            n = size(q, 2)
            sim = [q(1, n), q(2, n), qd(1, n), qd(2, n)]
            swept = [fq1(i1, i2), fq2(i1, i2), fw1(i1, i2), fw2(i1, i2)]
            worst = max(worst, maxval(abs(swept - sim)/max(1.0_dp, abs(sim))))
            worst_e = max(worst_e, abs(e0(i1, i2) - e(1))/max(1.0_dp, abs(e(1))))
            call check(error, swept, sim, 'final (q1, q2, w1, w2) of pixel', rel=1.0e-12_dp, &
                       abs=1.0e-12_dp)
            call check(error, e0(i1, i2), e(1), 'energy0 of pixel', rel=1.0e-13_dp, &
                       abs=1.0e-13_dp)
            if (allocated(error)) return
         end do
      end do
      write (output_unit, '(a, es9.2, a, es9.2)') '    sweep_vs_simulate: final state, largest '// &
         'relative difference', worst, '; energy0', worst_e
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_final_states

   !> `dpend simulate ARGS --method rk4 --dt 0.01 --t-end 2`, every step sampled: its
   !> angles, rates and energy, and with wf the works W_friction, W_support, W_torque.
   subroutine simulated_run(dir, args, q, qd, e, error, wf, ws, wt)
      character(len=*), intent(in) :: dir, args
      real(dp), allocatable, intent(out) :: q(:, :), qd(:, :), e(:)
      type(error_t), allocatable, intent(out) :: error
      real(dp), allocatable, intent(out), optional :: wf(:), ws(:), wt(:)
      type(h5file_t) :: h5
      integer :: stat
      stat = run_command(dir, 'simulate '//args//' --method rk4 --dt 0.01 --t-end 2 ' &
                         //'--save-every 1 --output '//dir//'/p.h5 --force')
      call check_true(error, stat == 0, 'simulate exits 0: '//args)
      if (allocated(error)) return
      call h5%open(dir//'/p.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/energy', e, error)
      if (present(wf)) then
         if (.not. allocated(error)) call h5%read('/trajectory/W_friction', wf, error)
         if (.not. allocated(error)) call h5%read('/trajectory/W_support', ws, error)
         if (.not. allocated(error)) call h5%read('/trajectory/W_torque', wt, error)
      end if
      call h5%close()
      if (.not. allocated(error)) call check_true(error, size(q, 2) == 201, &
                                                  'every step sampled')
   end subroutine simulated_run

   !> Torque samples τ1 = 0.4 sin 2t, τ2 = 0.15 cos 3t (τ3 = −0.1 sin t) every 10 ms
   !> over [0, 4] s, written to `path` for n joints; `scale` multiplies them.
   subroutine write_torques(path, n, scale)
      character(len=*), intent(in) :: path
      integer, intent(in) :: n
      real(dp), intent(in) :: scale
      integer :: u, k
      real(dp) :: t, tau(3)
      open (newunit=u, file=path, status='replace', action='write')
      write (u, '(a)') 't,tau1,tau2'//trim(merge(',tau3', '     ', n == 3))
      do k = 0, 400
         t = 0.01_dp*k
         tau = scale*[0.4_dp*sin(2*t), 0.15_dp*cos(3*t), -0.1_dp*sin(t)]
         write (u, '(es24.16e3, 3(:, ",", es24.16e3))') t, tau(1:n)
      end do
      close (u)
   end subroutine write_torques

   !> The forced chain of N = 2 and 3 links: each pixel of a 3 x 3 grid against
   !> simulate at the same rk4 step (final state and balance error).
   subroutine test_forced_chain(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir, par, forced
      type(h5file_t) :: h5
      real(dp), allocatable :: ax1(:), ax2(:), fin(:, :, :), err2(:, :), q(:, :), qd(:, :)
      real(dp), allocatable :: e(:), wf(:), ws(:), wt(:), x(:, :)
      integer, allocatable :: status(:, :)
      real(dp) :: worst, worst_e, range, balance, q0(3)
      character(len=200) :: qs
      character(len=1) :: c
      integer :: stat, i1, i2, n, k, nl
      dir = scratch_dir('sweepforced')
      worst = 0.0_dp; worst_e = 0.0_dp
      do nl = 2, 3
         call write_torques(dir//'/tq.csv', nl, 1.0_dp)
         if (nl == 2) then
            par = '--m 1.3,0.9 --l 1.1,0.8 --g 9.81 --w 0.5,0'
            forced = ' --damping 0.05,0.02 --coulomb 0.02,0.01 --coulomb-speed 0.05 ' &
                     //'--support-amplitude 0.05,0.02 --support-frequency 4 --torque-file ' &
                     //dir//'/tq.csv'
         else
            par = '--links 3 --m 1.3,0.9,0.7 --l 1.1,0.8,0.6 --g 9.81 --w 0.5,0,0'
            forced = ' --damping 0.05,0.02,0.01 --coulomb 0.02,0.01,0.01 --coulomb-speed ' &
                     //'0.05 --support-amplitude 0.05,0.02 --support-frequency 4 ' &
                     //'--torque-file '//dir//'/tq.csv'
         end if
         if (nl == 3) par = par//' --q 0,0,0.3'   ! link 3's fixed angle
         stat = run_command(dir, 'sweep --quiet '//par//' --n 3 --min1 -3 --max1 3 ' &
                            //'--min2 -2.5 --max2 2.5 --time-unit s --dt 0.01 --t-end 2 ' &
                            //'--stop-at end --threads 1 --force --output '//dir//'/s.h5'//forced)
         call check_true(error, stat == 0, 'sweep of the forced chain exits 0')
         if (allocated(error)) return
         allocate (fin(3, 3, 2*nl))
         call h5%open(dir//'/s.h5', 'r', error)
         if (.not. allocated(error)) call h5%read('/sweep/axis1', ax1, error)
         if (.not. allocated(error)) call h5%read('/sweep/axis2', ax2, error)
         if (.not. allocated(error)) call h5%read('/sweep/status', status, error)
         if (.not. allocated(error)) call h5%read('/sweep/energy_error', err2, error)
         if (.not. allocated(error)) call h5%readattr('/sweep', 'potential_range', range, error)
         do k = 1, nl
            c = achar(iachar('0') + k)
            if (.not. allocated(error)) call h5%read('/sweep/final/q'//c, x, error)
            if (.not. allocated(error)) fin(:, :, k) = x
            if (.not. allocated(error)) call h5%read('/sweep/final/w'//c, x, error)
            if (.not. allocated(error)) fin(:, :, nl + k) = x
         end do
         call h5%close()
         if (allocated(error)) return
         do i2 = 1, 3
            do i1 = 1, 3
               call check_true(error, status(i1, i2) == 1, 'status 1 (integrated to t_end)')
               q0 = [ax1(i1) - half_pi, ax2(i2) - half_pi, 0.3_dp]
               write (qs, '("--q ", es24.16e3, 2(:, ",", es24.16e3))') q0(1:nl)
               qs = '--q '//no_blanks(qs(5:))
               call simulated_run(dir, simulated(par)//' '//trim(qs)//forced, q, qd, e, &
                                  error, wf, ws, wt)
               if (allocated(error)) return
               n = size(q, 2)
               balance = maxval(abs(e - e(1) + wf - ws - wt))/range
               worst = max(worst, maxval(abs(fin(i1, i2, :) - [q(:, n), qd(:, n)])))
               worst_e = max(worst_e, abs(err2(i1, i2) - balance))
               call check(error, fin(i1, i2, :), [q(:, n), qd(:, n)], 'final state of pixel', &
                          rel=1.0e-12_dp, abs=1.0e-12_dp)
               call check(error, err2(i1, i2), balance, 'balance error of pixel', &
                          abs=1.0e-13_dp)
               call check_true(error, balance > 0.0_dp, 'a balance error of rk4 (not 0)')
               if (allocated(error)) return
            end do
         end do
         deallocate (fin)
      end do
      write (output_unit, '(a, es9.2, a, es9.2)') '    sweep_vs_simulate: forced chain, final ' &
         //'state largest difference', worst, '; balance error', worst_e
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> The text without its blanks.
      function no_blanks(text) result(t)
         character(len=*), intent(in) :: text
         character(len=:), allocatable :: t
         integer :: i
         t = ''
         do i = 1, len_trim(text)
            if (text(i:i) /= ' ') t = t//text(i:i)
         end do
      end function no_blanks
      !> The parameters without the sweep's fixed angle of link 3 (the pixel's --q).
      function simulated(p) result(t)
         character(len=*), intent(in) :: p
         character(len=:), allocatable :: t
         t = p
         if (index(p, ' --q ') > 0) t = p(:index(p, ' --q ') - 1)
      end function simulated
   end subroutine test_forced_chain

   !> One rod from rest under τ = 1 N m and damping c = 0.2 N m s: its flip time
   !> against the closed form (Newton's method on it). (Coulomb friction's smooth
   !> start, c_f tanh(ω/v_s), has no closed form here; suite joint_torque has its own.)
   subroutine test_forced_flip(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: tf(:, :)
      integer, allocatable :: status(:, :)
      real(dp), parameter :: j = 1.0_dp/3.0_dp, c = 0.2_dp, tau = 1.0_dp
      real(dp) :: t, f, fd
      integer :: stat, k, u
      dir = scratch_dir('sweepflip')
      open (newunit=u, file=dir//'/c.csv', status='replace', action='write')
      write (u, '(a)') 't,tau1', '-1,1', '10,1'
      close (u)
      stat = run_command(dir, 'sweep --quiet --links 1 --g 1e-6 --axis1 theta1 --axis2 w1 ' &
                         //'--n 1 --min1 0 --max1 0 --min2 0 --max2 0 --damping 0.2 ' &
                         //'--torque-file '//dir//'/c.csv --time-unit s ' &
                         //'--dt 0.001 --t-end 5 --stop-at either --output '//dir//'/s.h5')
      call check_true(error, stat == 0, 'sweep of the forced rod exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/s.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/t_flip', tf, error)
      if (.not. allocated(error)) call h5%read('/sweep/status', status, error)
      call h5%close()
      if (allocated(error)) return
      t = 1.5_dp
      do k = 1, 60   ! q(t) − q0 − π = 0
         f = (tau/c)*(t - (j/c)*(1.0_dp - exp(-c*t/j))) - acos(-1.0_dp)
         fd = (tau/c)*(1.0_dp - exp(-c*t/j))
         t = t - f/fd
      end do
      call check_true(error, status(1, 1) == 2, 'status 2 (flipped)')
      call check(error, tf(1, 1), t, 'flip time against the closed form', rel=1.0e-6_dp)
      write (output_unit, '(a, f12.9, a, f12.9, a, es9.2)') '    sweep_vs_simulate: forced ' &
         //'rod flips at', tf(1, 1), ' s, closed form', t, ' s, relative', abs(tf(1, 1) - t)/t
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_forced_flip

   !> The torques are part of the resume key: a file of one torque series is not taken
   !> for another of the same count and span (refused, exit 2), and is for its own.
   subroutine test_forced_resume(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir, run
      integer :: stat
      dir = scratch_dir('sweepforcedkey')
      call write_torques(dir//'/a.csv', 2, 1.0_dp)
      call write_torques(dir//'/b.csv', 2, 1.5_dp)
      run = 'sweep --quiet --n 4 --t-end 2 --damping 0.05,0.02 --output '//dir//'/s.h5 ' &
            //'--torque-file '//dir
      stat = run_command(dir, run//'/a.csv')
      call check_true(error, stat == 0, 'first sweep exits 0')
      if (allocated(error)) return
      stat = run_command(dir, run//'/b.csv')
      call check_true(error, stat == 2, 'another torque series refused (exit 2)')
      if (allocated(error)) return
      stat = run_command(dir, run//'/a.csv')
      call check_true(error, stat == 0, 'the same torque series: the file is complete')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_forced_resume

   !> The flip bounds: with damping alone the pixels below them are those of the
   !> conservative map (energy only leaves; E(0) the same); with a moving support none
   !> is (energy is fed: every pixel integrated).
   subroutine test_forced_bounds(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: grid = 'sweep --quiet --n 8 --t-end 3 --min1 -1.5 ' &
                                     //'--max1 1.5 --min2 -1.5 --max2 1.5 --output '
      character(len=:), allocatable :: dir
      integer, allocatable :: conservative(:, :), damped(:, :), driven(:, :)
      real(dp), allocatable :: e0c(:, :), e0d(:, :)
      integer :: stat
      dir = scratch_dir('sweepforcedbounds')
      stat = run_command(dir, grid//dir//'/c.h5')
      if (stat == 0) stat = run_command(dir, grid//dir//'/d.h5 --damping 0.3,0.1')
      if (stat == 0) stat = run_command(dir, grid//dir//'/s.h5 --support-amplitude 0,0.05 ' &
                                        //'--support-frequency 9')
      call check_true(error, stat == 0, 'the three sweeps exit 0')
      if (allocated(error)) return
      call read_status(dir//'/c.h5', conservative, e0c)
      if (.not. allocated(error)) call read_status(dir//'/d.h5', damped, e0d)
      if (allocated(error)) return
      ! (the free map's E(0) is the two-link kernel's arithmetic, the damped one the
      ! chain's: equal to rounding)
      call check(error, reshape(e0d, [size(e0d)]), reshape(e0c, [size(e0c)]), &
                 'damped: E(0) of the conservative map', abs=1e-12_dp, rel=1e-12_dp)
      if (.not. allocated(error)) call read_status(dir//'/s.h5', driven, e0d)
      if (allocated(error)) return
      call check_true(error, count(conservative == 3) > 0, 'some pixels below the bounds')
      if (allocated(error)) return
      call check_true(error, all((conservative == 3) .eqv. (damped == 3)), &
                      'damped: the conservative map''s pixels below the bounds')
      if (allocated(error)) return
      call check_true(error, count(driven == 3) == 0, 'driven: no pixel below a bound')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine read_status(path, status, e0)
         character(len=*), intent(in) :: path
         integer, allocatable, intent(out) :: status(:, :)
         real(dp), allocatable, intent(out) :: e0(:, :)
         type(h5file_t) :: h5
         call h5%open(path, 'r', error)
         if (.not. allocated(error)) call h5%read('/sweep/status', status, error)
         if (.not. allocated(error)) call h5%read('/sweep/energy0', e0, error)
         call h5%close()
      end subroutine read_status
   end subroutine test_forced_bounds

end module test_sweep_vs_simulate
