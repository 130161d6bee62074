!> The values a two-link sweep writes (the vectorized batch kernel and the sweep's
!> writer) against independent per-trajectory runs (a mutant that survived the
!> earlier suite: the two links' final angles written swapped): every pixel of a 4 × 4 grid (asymmetric
!> links, w1 ≠ 0, run to t_end) is simulated again with `dpend simulate` (the double
!> pendulum model, rk4 at the same step, every step sampled), and the file's
!> `final/q1`, `final/q2`, `final/w1`, `final/w2` and `energy0` must equal the
!> simulated end state and initial energy (Lagrange's form in lanes against the
!> model's field: they differ by rounding only; measured largest difference 1.3e-13 (tolerance 1e-12), printed,
!> '    sweep_vs_simulate: …'), and `status` must be 1 (integrated to t_end).
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
      tests = [new_unittest('final_state_matches_simulate', test_final_states)]
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
            stat = run_command(dir, 'simulate '//par//' '//trim(qs)//' --w2 0 --method rk4 '// &
                               '--dt 0.01 --t-end 2 --save-every 1 --output '//dir// &
                               '/p.h5 --force')
            call check_true(error, stat == 0, 'simulate exits 0: '//trim(qs))
            if (allocated(error)) return
            call h5%open(dir//'/p.h5', 'r', error)
            if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
            if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
            if (.not. allocated(error)) call h5%read('/trajectory/energy', e, error)
            call h5%close()
            if (allocated(error)) return
            n = size(q, 2)
            call check_true(error, n == 201, 'every step sampled')
            if (allocated(error)) return
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

end module test_sweep_vs_simulate
