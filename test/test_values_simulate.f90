!> Every dataset of a simulate file checked against an independent computation written
!> here (the inventory test/inventory/simulate.txt). None of dpend's model
!> code is used: the chain of N uniform rods on pin joints (two rods, three) and the
!> elastic pendulum are written out from their definitions.
!>
!> The chain (angles q_i from the horizontal, u_i = (cos q_i, sin q_i), n_i = (−sin q_i,
!> cos q_i), the pin A = (a_x cos(ωt + φ_x), a_y cos(ωt + φ_y))):
!>   C_k = A + Σ_{j<k} L_j u_j + (L_k/2) u_k,  J_k = A + Σ_{j≤k} L_j u_j (far end of k),
!>   v and a by differentiating in closed form (q̇, q̈ from the file),
!>   F_joint_i = Σ_{k≥i} m_k (a_Ck + g ĵ)   (Newton on bodies i … N; F01 = F_joint_1,
!>   F21 = −F_joint_2),
!>   E = Σ ½ m_k |v_Ck|² + ½ (m_k L_k²/12) q̇_k² + m_k g y_Ck,  p = M q̇,
!>   q̈ from the principle of virtual work: Σ_k m_k (∂C_k/∂q_i)·(a_Ck + g ĵ) + I_i q̈_i = Q_i,
!>   Q_i = −c_i (q̇_i − q̇_(i−1)) + c_(i+1) (q̇_(i+1) − q̇_i) + τ_i − τ_(i+1),
!>   with applied joint torques τ_i = a_i + b_i t (linear: the torque file's samples
!>   interpolate it exactly),
!>   q, q̇ by a classical RK4 of that q̈ written here, with the file's step,
!>   W_friction, W_support, W_torque by composite Boole quadrature over the samples of
!>   Σ c_i (q̇_i − q̇_(i−1))², F01 · v_A and Σ τ_i (q̇_i − q̇_(i−1)), balance_error from E,
!>   the works and E_s = |E(0)|.
!> The elastic pendulum (q = (r, φ), bob m on a spring k, l0):
!>   r̈ = r φ̇² − (k/m)(r − l0) − g sin φ,  φ̈ = −(2 ṙ φ̇ + g cos φ)/r,
!>   E = ½ m (ṙ² + r² φ̇²) + ½ k (r − l0)² + m g r sin φ,  p = (m ṙ, m r² φ̇),
!>   tension k (r − l0), F_joint = −k (r − l0) u = m (a_C + g ĵ).
!> Aliases (rC1 = rC(:, 1, :), ...) are checked against the general dataset and the
!> closed form. Each test names the datasets it checks; the helper checks exactly those.
module test_values_simulate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   use dpend_cli, only: to_str
   use test_cli, only: run_command, scratch_dir
   use test_balance, only: boole
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error
   implicit none
   private
   public :: collect_values_simulate

   integer, parameter :: nl = 16   !! length of a dataset name here

   !> A chain of rods: parameters and the closed forms over every sample.
   type :: chain_t
      integer :: n = 2                          !! links
      real(dp), allocatable :: m(:), l(:), c(:) !! masses [kg], lengths [m], damping [N m s]
      real(dp) :: g = 9.8_dp                    !! gravity [m/s²]
      real(dp) :: a(2) = 0.0_dp                 !! support amplitudes [m]
      real(dp) :: w = 0.0_dp                    !! support frequency [rad/s]
      real(dp) :: ph(2) = 0.0_dp                !! support phases [rad]
      !> applied joint torques τ_i = ta_i + tb_i t [N m] (none when not allocated)
      real(dp), allocatable :: ta(:), tb(:)
   end type chain_t

contains

   subroutine collect_values_simulate(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [new_unittest('two_rods_every_dataset', test_two_rods), &
               new_unittest('damped_moving_support_every_dataset', test_damped_support), &
               new_unittest('chain3_every_dataset', test_chain3), &
               new_unittest('torques_every_dataset', test_torques), &
               new_unittest('elastic_every_dataset', test_elastic)]
   end subroutine collect_values_simulate

   !> Two rods of unequal masses and lengths, fixed pin, no damping.
   subroutine test_two_rods(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(chain_t) :: ch
      ch%n = 2
      ch%m = [1.3_dp, 0.7_dp]; ch%l = [0.9_dp, 1.2_dp]; ch%c = [0.0_dp, 0.0_dp]
      ch%g = 9.7_dp
      call check_chain(error, 'two_rods', ch, '--m 1.3,0.7 --l 0.9,1.2 --g 9.7 ' &
                       //'--q 0.3,-0.4 --w 1.5,-2', [character(len=nl) :: &
                       't', 'q', 'qdot', 'qddot', 'p', 'energy', 'kinetic', 'potential', 'rA', 'rB', &
                       'rC', 'rC1', 'rC2', 'rJ', 'vC', 'vC1', 'vC2', 'vJ', 'aC', 'aC1', 'aC2', 'aJ', &
                       'F01', 'F21', 'F_joint'])
   end subroutine test_two_rods

   !> Two rods, damped joints, the pin moving along both axes with phases.
   subroutine test_damped_support(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(chain_t) :: ch
      ch%n = 2
      ch%m = [1.3_dp, 0.7_dp]; ch%l = [0.9_dp, 1.2_dp]; ch%c = [0.3_dp, 0.2_dp]
      ch%g = 9.7_dp
      ch%a = [0.04_dp, 0.07_dp]; ch%w = 5.0_dp; ch%ph = [0.3_dp, -0.2_dp]
      call check_chain(error, 'damped_support', ch, '--m 1.3,0.7 --l 0.9,1.2 --g 9.7 ' &
                       //'--q 0.3,-0.4 --w 1.5,-2 --damping 0.3,0.2 --support-amplitude ' &
                       //'0.04,0.07 --support-frequency 5 --support-phase 0.3,-0.2', &
                       [character(len=nl) :: 't', 'q', 'qdot', 'qddot', 'energy', &
                       'kinetic', 'potential', 'W_friction', 'W_support', 'balance_error', 'rA', 'rB', 'rC', 'rC1', &
                       'rC2', 'rJ', 'vC', 'vC1', 'vC2', 'vJ', 'aC', 'aC1', 'aC2', 'aJ', &
                       'F01', 'F21', 'F_joint'])
   end subroutine test_damped_support

   !> Three rods, damped, with applied joint torques τ_i = a_i + b_i t from a torque
   !> file of 4 irregular samples over [0, 0.5] s ('samples': /torque/sample_t and
   !> /torque/sample_tau, the series as the file gave it).
   subroutine test_torques(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(chain_t) :: ch
      ch%n = 3
      ch%m = [1.1_dp, 0.8_dp, 1.4_dp]; ch%l = [1.0_dp, 0.7_dp, 1.2_dp]
      ch%c = [0.1_dp, 0.0_dp, 0.05_dp]
      ch%ta = [2.0_dp, -1.5_dp, 0.5_dp]; ch%tb = [-3.0_dp, 4.0_dp, 1.0_dp]
      ! 'samples' compares /torque/sample_t and /torque/sample_tau with the file written
      call check_chain(error, 'torques', ch, '--links 3 --m 1.1,0.8,1.4 --l 1,0.7,1.2 ' &
                       //'--q 0.1,0.5,-1 --w 0,1,0 --damping 0.1,0,0.05', &
                       [character(len=nl) :: 't', 'q', 'qdot', 'qddot', 'energy', &
                       'kinetic', 'potential', 'W_torque', 'balance_error', 'tau', 'F_joint', &
                       'samples'])
   end subroutine test_torques

   !> A chain of three rods of unequal masses and lengths.
   subroutine test_chain3(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(chain_t) :: ch
      ch%n = 3
      ch%m = [1.1_dp, 0.8_dp, 1.4_dp]; ch%l = [1.0_dp, 0.7_dp, 1.2_dp]
      ch%c = [0.0_dp, 0.0_dp, 0.0_dp]
      call check_chain(error, 'chain3', ch, '--links 3 --m 1.1,0.8,1.4 --l 1,0.7,1.2 ' &
                       //'--q 0.1,0.5,-1 --w 0,1,0', [character(len=nl) :: 't', 'q', &
                       'qdot', 'qddot', 'p', 'energy', 'kinetic', 'potential', 'rA', 'rC', 'rJ', &
                       'vC', 'vJ', 'aC', 'aJ', 'F_joint'])
   end subroutine test_chain3

   !> The elastic pendulum (m = 1.2 kg, k = 40 N/m, l0 = 0.9 m, g = 9.8 m/s²).
   subroutine test_elastic(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call check_elastic(error, [character(len=nl) :: 't', 'q', 'qdot', 'qddot', 'p', &
                         'energy', 'kinetic', 'potential', 'rA', 'rC', 'vC', 'aC', 'F_joint', &
                         'spring_length', 'tension'])
   end subroutine test_elastic

   ! ------------------------------------------------------------------ chain

   !> Simulate the chain (rk4, dt = 1 ms, every step kept, 0.5 s) and check `names`.
   subroutine check_chain(error, tag, ch, args, names)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), intent(in) :: tag               !! case name
      type(chain_t), intent(in) :: ch                   !! the chain
      character(len=*), intent(in) :: args              !! its dpend options
      character(len=*), intent(in) :: names(:)          !! datasets to check
      real(dp), parameter :: dt = 1.0e-3_dp
      !> the torque file's sample times [s] (a chain with torques)
      real(dp), parameter :: sample_times(4) = [0.0_dp, 0.13_dp, 0.31_dp, 0.5_dp]
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), x2(:, :), x3(:, :, :), x1(:)
      real(dp), allocatable :: rc(:, :, :), vc(:, :, :), ac(:, :, :), rj(:, :, :), vj(:, :, :)
      real(dp), allocatable :: aj(:, :, :), fj(:, :, :), ra(:, :), va(:, :), e(:), p(:, :)
      real(dp), allocatable :: qddx(:, :), pf(:), ps(:), wf(:), ws(:), y(:, :), tk(:), vp(:)
      real(dp), allocatable :: pt(:), wt(:), tau(:, :)
      real(dp) :: e_s
      integer :: stat, n, i, k
      dir = scratch_dir('values-'//tag)
      if (allocated(ch%ta)) then   ! the torque file: t, tau1 .. tauN at 4 irregular times
         call write_torques(dir//'/tau.csv', ch, sample_times)
         stat = run_command(dir, 'simulate --method rk4 --dt 1e-3 --t-end 0.5 --save-every 1 ' &
                            //args//' --torque-file '//dir//'/tau.csv --output '//dir//'/sim.h5')
      else
         stat = run_command(dir, 'simulate --method rk4 --dt 1e-3 --t-end 0.5 --save-every 1 ' &
                            //args//' --output '//dir//'/sim.h5')
      end if
      call check_true(error, stat == 0, tag//': simulate exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/sim.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qddot', qdd, error)
      if (allocated(error)) return
      n = size(t)
      call check_true(error, n == 501 .and. all(shape(q) == [ch%n, n]), tag// &
                      ': 501 samples of '//to_str(ch%n)//' angles')
      if (allocated(error)) return
      ! closed forms from the stored q, qdot, qddot
      allocate (rc(2, ch%n, n), vc(2, ch%n, n), ac(2, ch%n, n), rj(2, ch%n, n), &
                vj(2, ch%n, n), aj(2, ch%n, n), fj(2, ch%n, n), ra(2, n), va(2, n), e(n), &
                p(ch%n, n), qddx(ch%n, n), pf(n), ps(n), tk(n), vp(n), pt(n), tau(ch%n, n))
      do i = 1, n
         call kinematics(ch, t(i), q(:, i), qd(:, i), qdd(:, i), ra(:, i), va(:, i), &
                         rc(:, :, i), vc(:, :, i), ac(:, :, i), rj(:, :, i), vj(:, :, i), &
                         aj(:, :, i))
         do k = ch%n, 1, -1   ! Newton on bodies k … N
            fj(:, k, i) = ch%m(k)*(ac(:, k, i) + [0.0_dp, ch%g])
            if (k < ch%n) fj(:, k, i) = fj(:, k, i) + fj(:, k + 1, i)
         end do
         e(i) = sum(0.5_dp*ch%m*sum(vc(:, :, i)**2, dim=1) &
                    + 0.5_dp*ch%m*ch%l**2/12.0_dp*qd(:, i)**2 + ch%m*ch%g*rc(2, :, i))
         tk(i) = sum(0.5_dp*ch%m*sum(vc(:, :, i)**2, dim=1) &
                     + 0.5_dp*ch%m*ch%l**2/12.0_dp*qd(:, i)**2)
         vp(i) = sum(ch%m*ch%g*rc(2, :, i))
         p(:, i) = matmul(mass_matrix(ch, q(:, i)), qd(:, i))
         qddx(:, i) = accelerations(ch, t(i), q(:, i), qd(:, i))
         pf(i) = sum(ch%c*(qd(:, i) - eoshift(qd(:, i), -1))**2)
         ps(i) = dot_product(fj(:, 1, i), va(:, i))
         tau(:, i) = torques(ch, t(i))
         pt(i) = sum(tau(:, i)*(qd(:, i) - eoshift(qd(:, i), -1)))
      end do
      e_s = abs(e(1))
      do k = 1, size(names)
         if (allocated(error)) exit
         select case (trim(names(k)))
         case ('t')   ! every step kept: t = k dt
            call h5%read('/trajectory/t', x1, error)
            call compare(error, tag, 't', x1, [(real(i, dp)*dt, i=0, n - 1)], 1.0e-15_dp)
         case ('q', 'qdot')   ! an RK4 of the virtual-work equations written here
            if (.not. allocated(y)) y = rk4_run(ch, dt, n, [q(:, 1), qd(:, 1)])
            call h5%read('/trajectory/'//trim(names(k)), x2, error)
            if (trim(names(k)) == 'q') then
               call compare(error, tag, 'q', pack(x2, .true.), pack(y(:ch%n, :), .true.), &
                            1.0e-13_dp)   ! measured 6.4e-16 (scale 1.2)
            else
               call compare(error, tag, 'qdot', pack(x2, .true.), &
                            pack(y(ch%n + 1:, :), .true.), 1.0e-13_dp)   ! measured 3.6e-15 / 7.3
            end if
            ! and the initial state given on the command line
            call check_true(error, all(abs(x2(:, 1) - merge(q0_of(tag), w0_of(tag), &
                            trim(names(k)) == 'q')) < 1.0e-15_dp), tag//': '// &
                            trim(names(k))//' starts at the given initial state')
         case ('qddot')
            call compare(error, tag, 'qddot', pack(qdd, .true.), pack(qddx, .true.), &
                         1.0e-13_dp)   ! measured 5.3e-14 / 62
         case ('p')
            call h5%read('/trajectory/p', x2, error)
            call compare(error, tag, 'p', pack(x2, .true.), pack(p, .true.), 1.0e-13_dp)
         case ('energy')
            call h5%read('/trajectory/energy', x1, error)
            call compare(error, tag, 'energy', x1, e, 1.0e-13_dp)   ! measured 1.6e-14 / 2.1
         case ('kinetic')   ! sum of 1/2 m |v_C|^2 + 1/2 I qdot^2 from the kinematics here
            call h5%read('/trajectory/kinetic', x1, error)
            call compare(error, tag, 'kinetic', x1, tk, 1.0e-13_dp)
         case ('potential')   ! sum of m g y_C
            call h5%read('/trajectory/potential', x1, error)
            call compare(error, tag, 'potential', x1, vp, 1.0e-13_dp)
         case ('W_friction')   ! Boole over the samples at every 4th
            call h5%read('/trajectory/W_friction', x1, error)
            wf = boole(t, pf)
            call compare(error, tag, 'W_friction', x1(1:n:4), wf, 5.0e-10_dp)   ! measured 6.3e-11
            call check_true(error, x1(n) > 0.05_dp*e_s, tag//': W_friction too small')
         case ('W_support')
            call h5%read('/trajectory/W_support', x1, error)
            ws = boole(t, ps)
            call compare(error, tag, 'W_support', x1(1:n:4), ws, 1.0e-10_dp)   ! measured 1.3e-11
            call check_true(error, maxval(abs(x1)) > 1.0e-2_dp*e_s, tag// &
                            ': W_support too small')
         case ('W_torque')
            call h5%read('/trajectory/W_torque', x1, error)
            wt = boole(t, pt)
            call compare(error, tag, 'W_torque', x1(1:n:4), wt, 5.0e-10_dp)   ! measured 1.1e-10
            ! (the quadrature's error, as W_friction's: both works come out of the run's
            ! own integration of the power)
            call check_true(error, maxval(abs(x1)) > 1.0e-2_dp*e_s, tag// &
                            ': W_torque too small')
         case ('samples')   ! /torque/sample_t, sample_tau: the file's samples, as written
            call h5%read('/torque/sample_t', x1, error)
            if (.not. allocated(error)) call h5%read('/torque/sample_tau', x2, error)
            if (allocated(error)) exit
            call compare(error, tag, 'torque/sample_t', x1, sample_times, 1.0e-16_dp)
            call compare(error, tag, 'torque/sample_tau', pack(x2, .true.), &
                         [(torques(ch, sample_times(i)), i = 1, 4)], 1.0e-15_dp)
         case ('tau')   ! a_i + b_i t
            call h5%read('/trajectory/tau', x2, error)
            call compare(error, tag, 'tau', pack(x2, .true.), pack(tau, .true.), 1.0e-15_dp)
         case ('balance_error')   ! from the closed-form E and the quadratures
            call h5%read('/trajectory/balance_error', x1, error)
            wf = boole(t, pf); ws = boole(t, ps); wt = boole(t, pt)
            call compare(error, tag, 'balance_error', x1(1:n:4), &
                         (e(1:n:4) - e(1) + wf - ws - wt)/e_s, 2.0e-10_dp)   ! measured 1.8e-11
            ! the torques' case 1.5e-9 (2.3e-8, 1.5e-9, 9.4e-11 at dt = 2, 1, 0.5 ms:
            ! fourth order), the damped one below 1e-9
            call check_true(error, maxval(abs(x1)) < merge(5.0e-9_dp, 1.0e-9_dp, &
                            tag == 'torques'), tag//': |balance_error| below 1e-9 '// &
                            '(5e-9 with torques; rk4, dt = 1 ms)')
         case ('rA')
            call h5%read('/trajectory/rA', x2, error)
            call compare(error, tag, 'rA', pack(x2, .true.), pack(ra, .true.), 1.0e-15_dp)
         case ('rB')
            call h5%read('/trajectory/rB', x2, error)
            call compare(error, tag, 'rB', pack(x2, .true.), pack(rj(:, 1, :), .true.), &
                         1.0e-14_dp)
         case ('rC', 'vC', 'aC', 'rJ', 'vJ', 'aJ', 'F_joint')
            call h5%read('/trajectory/'//trim(names(k)), x3, error)
            select case (trim(names(k)))
            case ('rC'); call compare3(rc, 1.0e-14_dp)
            case ('vC'); call compare3(vc, 1.0e-14_dp)
            case ('aC'); call compare3(ac, 1.0e-14_dp)
            case ('rJ'); call compare3(rj, 1.0e-14_dp)
            case ('vJ'); call compare3(vj, 1.0e-14_dp)
            case ('aJ'); call compare3(aj, 1.0e-14_dp)
            case ('F_joint'); call compare3(fj, 1.0e-14_dp)
            end select
         case ('rC1', 'rC2', 'vC1', 'vC2', 'aC1', 'aC2')   ! aliases: general and closed form
            call h5%read('/trajectory/'//trim(names(k)), x2, error)
            i = merge(1, 2, names(k)(3:3) == '1')
            call h5%read('/trajectory/'//names(k)(1:2), x3, error)
            if (allocated(error)) exit
            call check_true(error, all(x2 == x3(:, i, :)), tag//': '//trim(names(k))// &
                            ' equals '//names(k)(1:2)//'(:, '//to_str(i)//', :)')
            select case (names(k)(1:1))
            case ('r'); call compare(error, tag, trim(names(k)), pack(x2, .true.), &
                                     pack(rc(:, i, :), .true.), 1.0e-14_dp)
            case ('v'); call compare(error, tag, trim(names(k)), pack(x2, .true.), &
                                     pack(vc(:, i, :), .true.), 1.0e-14_dp)
            case ('a'); call compare(error, tag, trim(names(k)), pack(x2, .true.), &
                                     pack(ac(:, i, :), .true.), 1.0e-14_dp)
            end select
         case ('F01')   ! the ground on link 1: Newton on both bodies
            call h5%read('/trajectory/F01', x2, error)
            call compare(error, tag, 'F01', pack(x2, .true.), pack(fj(:, 1, :), .true.), &
                         1.0e-14_dp)
         case ('F21')   ! link 2 on link 1 = −(link 1 on link 2) = −m2 (aC2 + g)
            call h5%read('/trajectory/F21', x2, error)
            call compare(error, tag, 'F21', pack(x2, .true.), pack(-fj(:, 2, :), .true.), &
                         1.0e-14_dp)
         case default
            call fatal_error(error, tag//': no check for dataset '//trim(names(k)))
         end select
      end do
      call h5%close()
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> Compare a (2, N, n) dataset with its closed form.
      subroutine compare3(want, rel)
         real(dp), intent(in) :: want(:, :, :)  !! closed form
         real(dp), intent(in) :: rel            !! tolerance relative to the largest value
         if (allocated(error)) return
         call check_true(error, all(shape(x3) == shape(want)), tag//': '//trim(names(k))// &
                         ' has shape (2, '//to_str(ch%n)//', n)')
         call compare(error, tag, trim(names(k)), pack(x3, .true.), pack(want, .true.), rel)
      end subroutine compare3
   end subroutine check_chain

   !> The initial angles of a case (its command line).
   function q0_of(tag) result(q)
      character(len=*), intent(in) :: tag  !! case name
      real(dp), allocatable :: q(:)
      q = [0.3_dp, -0.4_dp]
      if (tag == 'chain3' .or. tag == 'torques') q = [0.1_dp, 0.5_dp, -1.0_dp]
   end function q0_of

   !> τ_i = a_i + b_i t of the chain (zero without torques).
   pure function torques(ch, t) result(tau)
      type(chain_t), intent(in) :: ch   !! the chain
      real(dp), intent(in) :: t         !! time [s]
      real(dp) :: tau(ch%n)
      tau = 0.0_dp
      if (allocated(ch%ta)) tau = ch%ta + ch%tb*t
   end function torques

   !> Write the torque file of the chain: a header t,tau1,… and a row per time.
   subroutine write_torques(path, ch, times)
      character(len=*), intent(in) :: path      !! file to write
      type(chain_t), intent(in) :: ch           !! the chain (ta, tb)
      real(dp), intent(in) :: times(:)          !! sample times [s]
      integer :: unit, k, i
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)', advance='no') 't [s]'
      do i = 1, ch%n
         write (unit, '(a)', advance='no') ',tau'//to_str(i)//' [N m]'
      end do
      write (unit, '(a)') ''
      do k = 1, size(times)
         write (unit, '(es24.17)', advance='no') times(k)
         do i = 1, ch%n
            write (unit, '(a,es24.17)', advance='no') ',', ch%ta(i) + ch%tb(i)*times(k)
         end do
         write (unit, '(a)') ''
      end do
      close (unit)
   end subroutine write_torques

   !> The initial angular velocities of a case.
   function w0_of(tag) result(w)
      character(len=*), intent(in) :: tag  !! case name
      real(dp), allocatable :: w(:)
      w = [1.5_dp, -2.0_dp]
      if (tag == 'chain3' .or. tag == 'torques') w = [0.0_dp, 1.0_dp, 0.0_dp]
   end function w0_of

   !> Fail unless max |got − want| ≤ rel · max(|want|, 1); prints the measured value.
   subroutine compare(error, tag, name, got, want, rel)
      type(error_t), allocatable, intent(inout) :: error  !! set on failure
      character(len=*), intent(in) :: tag, name           !! case, dataset
      real(dp), intent(in) :: got(:), want(:)             !! file, closed form
      real(dp), intent(in) :: rel                         !! relative tolerance
      real(dp) :: d, s
      if (allocated(error)) return
      call check_true(error, size(got) == size(want), tag//': '//name//' has '// &
                      to_str(size(want))//' values, found '//to_str(size(got)))
      if (allocated(error)) return
      d = maxval(abs(got - want))
      s = max(maxval(abs(want)), 1.0_dp)
      write (output_unit, '(4x, a, es9.2, a, es9.2)') tag//' '//name//': max diff ', d, &
         ', scale ', s
      call check(error, d, 0.0_dp, tag//': '//name//' against the closed form (max diff)', &
                 abs=rel*s)
   end subroutine compare

   !> Support, centres, far ends: positions, velocities, accelerations.
   pure subroutine kinematics(ch, t, q, qd, qdd, ra, va, rc, vc, ac, rj, vj, aj)
      type(chain_t), intent(in) :: ch                   !! the chain
      real(dp), intent(in) :: t, q(:), qd(:), qdd(:)    !! time, state, accelerations
      real(dp), intent(out) :: ra(2), va(2)             !! pin position, velocity
      real(dp), intent(out) :: rc(:, :), vc(:, :), ac(:, :)  !! centres (2, N)
      real(dp), intent(out) :: rj(:, :), vj(:, :), aj(:, :)  !! far ends (2, N)
      real(dp) :: u(2), nn(2), aa(2), r(2), v(2), a(2)
      integer :: k
      call support(ch, t, ra, va, aa)
      r = ra; v = va; a = aa
      do k = 1, ch%n
         u = [cos(q(k)), sin(q(k))]; nn = [-sin(q(k)), cos(q(k))]
         rc(:, k) = r + 0.5_dp*ch%l(k)*u
         vc(:, k) = v + 0.5_dp*ch%l(k)*qd(k)*nn
         ac(:, k) = a + 0.5_dp*ch%l(k)*(qdd(k)*nn - qd(k)**2*u)
         r = r + ch%l(k)*u
         v = v + ch%l(k)*qd(k)*nn
         a = a + ch%l(k)*(qdd(k)*nn - qd(k)**2*u)
         rj(:, k) = r; vj(:, k) = v; aj(:, k) = a
      end do
   end subroutine kinematics

   !> The pin A: a_x cos(ωt + φ_x), a_y cos(ωt + φ_y) and its derivatives.
   pure subroutine support(ch, t, ra, va, aa)
      type(chain_t), intent(in) :: ch         !! the chain
      real(dp), intent(in) :: t               !! time [s]
      real(dp), intent(out) :: ra(2), va(2), aa(2)  !! position, velocity, acceleration
      ra = ch%a*cos(ch%w*t + ch%ph)
      va = -ch%a*ch%w*sin(ch%w*t + ch%ph)
      aa = -ch%a*ch%w**2*cos(ch%w*t + ch%ph)
   end subroutine support

   !> ∂C_k/∂q_j = w(k, j) n_j: L_j before k, L_k/2 at k, 0 after.
   pure real(dp) function lever(ch, k, j)
      type(chain_t), intent(in) :: ch  !! the chain
      integer, intent(in) :: k, j      !! body, coordinate
      lever = 0.0_dp
      if (j < k) lever = ch%l(j)
      if (j == k) lever = 0.5_dp*ch%l(k)
   end function lever

   !> M_ij = Σ_k m_k w_ki w_kj cos(q_i − q_j) + (m_i L_i²/12) δ_ij.
   pure function mass_matrix(ch, q) result(mm)
      type(chain_t), intent(in) :: ch  !! the chain
      real(dp), intent(in) :: q(:)     !! angles [rad]
      real(dp) :: mm(ch%n, ch%n)
      integer :: i, j, k
      do i = 1, ch%n
         do j = 1, ch%n
            mm(i, j) = 0.0_dp
            do k = 1, ch%n
               mm(i, j) = mm(i, j) + ch%m(k)*lever(ch, k, i)*lever(ch, k, j)*cos(q(i) - q(j))
            end do
         end do
         mm(i, i) = mm(i, i) + ch%m(i)*ch%l(i)**2/12.0_dp
      end do
   end function mass_matrix

   !> q̈ from virtual work: M q̈ = Q − Σ_k m_k w_ki n_i·(a_A + g ĵ − Σ_j w_kj q̇_j² u_j).
   pure function accelerations(ch, t, q, qd) result(qdd)
      type(chain_t), intent(in) :: ch          !! the chain
      real(dp), intent(in) :: t, q(:), qd(:)   !! time, angles, rates
      real(dp) :: qdd(ch%n)
      real(dp) :: mm(ch%n, ch%n), rhs(ch%n), ra(2), va(2), aa(2), b(2), qdx(0:ch%n + 1)
      real(dp) :: tau(ch%n)
      integer :: i, j, k
      call support(ch, t, ra, va, aa)
      tau = torques(ch, t)
      mm = mass_matrix(ch, q)
      qdx = 0.0_dp
      qdx(1:ch%n) = qd
      do i = 1, ch%n
         rhs(i) = -ch%c(i)*(qdx(i) - qdx(i - 1))
         if (i < ch%n) rhs(i) = rhs(i) + ch%c(i + 1)*(qdx(i + 1) - qdx(i))
         rhs(i) = rhs(i) + tau(i)
         if (i < ch%n) rhs(i) = rhs(i) - tau(i + 1)
         do k = 1, ch%n
            b = aa + [0.0_dp, ch%g]
            do j = 1, ch%n
               b = b - lever(ch, k, j)*qd(j)**2*[cos(q(j)), sin(q(j))]
            end do
            rhs(i) = rhs(i) - ch%m(k)*lever(ch, k, i)*dot_product([-sin(q(i)), cos(q(i))], b)
         end do
      end do
      qdd = solve(mm, rhs)
   end function accelerations

   !> Gaussian elimination with partial pivoting (small dense systems).
   pure function solve(a_in, b_in) result(x)
      real(dp), intent(in) :: a_in(:, :), b_in(:)  !! matrix, right-hand side
      real(dp) :: x(size(b_in))
      real(dp) :: a(size(b_in), size(b_in)), b(size(b_in)), row(size(b_in)), s, f
      integer :: n, i, k, p
      a = a_in; b = b_in; n = size(b)
      do k = 1, n
         p = maxloc(abs(a(k:, k)), dim=1) + k - 1
         row = a(k, :); a(k, :) = a(p, :); a(p, :) = row
         s = b(k); b(k) = b(p); b(p) = s
         do i = k + 1, n
            f = a(i, k)/a(k, k)
            a(i, k:) = a(i, k:) - f*a(k, k:)
            b(i) = b(i) - f*b(k)
         end do
      end do
      do i = n, 1, -1
         x(i) = (b(i) - dot_product(a(i, i + 1:), x(i + 1:)))/a(i, i)
      end do
   end function solve

   !> Classical RK4 of (q, q̇) with step dt: the states at the n samples t = k dt.
   function rk4_run(ch, dt, n, y0) result(y)
      type(chain_t), intent(in) :: ch   !! the chain
      real(dp), intent(in) :: dt        !! step [s]
      integer, intent(in) :: n          !! samples
      real(dp), intent(in) :: y0(:)     !! (q, q̇) at t = 0
      real(dp) :: y(size(y0), n)
      real(dp), dimension(size(y0)) :: k1, k2, k3, k4
      real(dp) :: t
      integer :: i
      y(:, 1) = y0
      do i = 2, n
         t = real(i - 2, dp)*dt
         k1 = f(t, y(:, i - 1))
         k2 = f(t + 0.5_dp*dt, y(:, i - 1) + 0.5_dp*dt*k1)
         k3 = f(t + 0.5_dp*dt, y(:, i - 1) + 0.5_dp*dt*k2)
         k4 = f(t + dt, y(:, i - 1) + dt*k3)
         y(:, i) = y(:, i - 1) + dt/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
      end do
   contains
      function f(t, z) result(dz)
         real(dp), intent(in) :: t, z(:)
         real(dp) :: dz(size(z))
         dz(:ch%n) = z(ch%n + 1:)
         dz(ch%n + 1:) = accelerations(ch, t, z(:ch%n), z(ch%n + 1:))
      end function f
   end function rk4_run

   ! ---------------------------------------------------------------- elastic

   !> Simulate the elastic pendulum (rk4, dt = 1 ms, every step, 0.5 s); check `names`.
   subroutine check_elastic(error, names)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), intent(in) :: names(:)          !! datasets to check
      real(dp), parameter :: m = 1.2_dp, kk = 40.0_dp, l0 = 0.9_dp, g = 9.8_dp, dt = 1.0e-3_dp
      character(len=*), parameter :: tag = 'elastic'
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), x1(:), x2(:, :), x3(:, :, :)
      real(dp), allocatable :: y(:, :), rc(:, :), vc(:, :), ac(:, :), e(:), p(:, :), qddx(:, :)
      real(dp), allocatable :: tk(:), vp(:)
      real(dp) :: u(2), nn(2), z(4), k1(4), k2(4), k3(4), k4(4)
      integer :: stat, n, i, k
      dir = scratch_dir('values-elastic')
      stat = run_command(dir, 'simulate --model elastic --m 1.2 --k 40 --l0 0.9 --g 9.8 ' &
                         //'--q 1.2,-1 --w 0.3,0.5 --method rk4 --dt 1e-3 --t-end 0.5 ' &
                         //'--save-every 1 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'elastic: simulate exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/sim.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qddot', qdd, error)
      if (allocated(error)) return
      n = size(t)
      call check_true(error, n == 501 .and. all(shape(q) == [2, n]), 'elastic: 501 samples')
      if (allocated(error)) return
      allocate (rc(2, n), vc(2, n), ac(2, n), e(n), p(2, n), qddx(2, n), y(4, n), tk(n), vp(n))
      do i = 1, n
         associate (r => q(1, i), ph => q(2, i), rd => qd(1, i), phd => qd(2, i))
            u = [cos(ph), sin(ph)]; nn = [-sin(ph), cos(ph)]
            rc(:, i) = r*u
            vc(:, i) = rd*u + r*phd*nn
            ac(:, i) = (qdd(1, i) - r*phd**2)*u + (r*qdd(2, i) + 2.0_dp*rd*phd)*nn
            e(i) = 0.5_dp*m*(rd**2 + r**2*phd**2) + 0.5_dp*kk*(r - l0)**2 + m*g*r*sin(ph)
            tk(i) = 0.5_dp*m*sum(vc(:, i)**2)   ! from the bob's velocity
            vp(i) = 0.5_dp*kk*(norm2(rc(:, i)) - l0)**2 + m*g*rc(2, i)
            p(:, i) = [m*rd, m*r**2*phd]
            qddx(:, i) = field([r, ph, rd, phd])
         end associate
      end do
      y(:, 1) = [q(:, 1), qd(:, 1)]
      do i = 2, n   ! RK4 written here
         z = y(:, i - 1)
         k1 = [z(3:4), field(z)]
         k2 = [z(3:4) + 0.5_dp*dt*k1(3:4), field(z + 0.5_dp*dt*k1)]
         k3 = [z(3:4) + 0.5_dp*dt*k2(3:4), field(z + 0.5_dp*dt*k2)]
         k4 = [z(3:4) + dt*k3(3:4), field(z + dt*k3)]
         y(:, i) = z + dt/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
      end do
      do k = 1, size(names)
         if (allocated(error)) exit
         select case (trim(names(k)))
         case ('t')
            call h5%read('/trajectory/t', x1, error)
            call compare(error, tag, 't', x1, [(real(i, dp)*dt, i=0, n - 1)], 1.0e-15_dp)
         case ('q')
            call compare(error, tag, 'q', pack(q, .true.), pack(y(1:2, :), .true.), 1.0e-13_dp)
            call check_true(error, all(abs(q(:, 1) - [1.2_dp, -1.0_dp]) < 1.0e-15_dp), &
                            'elastic: q starts at the given state')
         case ('qdot')
            call compare(error, tag, 'qdot', pack(qd, .true.), pack(y(3:4, :), .true.), &
                         1.0e-13_dp)
            call check_true(error, all(abs(qd(:, 1) - [0.3_dp, 0.5_dp]) < 1.0e-15_dp), &
                            'elastic: qdot starts at the given state')
         case ('qddot')
            call compare(error, tag, 'qddot', pack(qdd, .true.), pack(qddx, .true.), 1.0e-13_dp)
         case ('p')
            call h5%read('/trajectory/p', x2, error)
            call compare(error, tag, 'p', pack(x2, .true.), pack(p, .true.), 1.0e-13_dp)
         case ('energy')
            call h5%read('/trajectory/energy', x1, error)
            call compare(error, tag, 'energy', x1, e, 1.0e-13_dp)
         case ('kinetic')
            call h5%read('/trajectory/kinetic', x1, error)
            call compare(error, tag, 'kinetic', x1, tk, 1.0e-13_dp)
         case ('potential')
            call h5%read('/trajectory/potential', x1, error)
            call compare(error, tag, 'potential', x1, vp, 1.0e-13_dp)
         case ('rA')
            call h5%read('/trajectory/rA', x2, error)
            call compare(error, tag, 'rA', pack(x2, .true.), [(0.0_dp, i=1, 2*n)], 0.0_dp)
         case ('rC', 'vC', 'aC', 'F_joint')
            call h5%read('/trajectory/'//trim(names(k)), x3, error)
            if (allocated(error)) exit
            call check_true(error, all(shape(x3) == [2, 1, n]), 'elastic: '// &
                            trim(names(k))//' has shape (2, 1, n)')
            select case (trim(names(k)))
            case ('rC'); call compare(error, tag, 'rC', pack(x3, .true.), pack(rc, .true.), &
                                      1.0e-14_dp)
            case ('vC'); call compare(error, tag, 'vC', pack(x3, .true.), pack(vc, .true.), &
                                      1.0e-14_dp)
            case ('aC'); call compare(error, tag, 'aC', pack(x3, .true.), pack(ac, .true.), &
                                      1.0e-14_dp)
            case ('F_joint')   ! Newton on the bob, and −k (r − l0) u
               call compare(error, tag, 'F_joint', pack(x3, .true.), &
                            pack(m*(ac + spread([0.0_dp, g], 2, n)), .true.), 1.0e-14_dp)
               call compare(error, tag, 'F_joint', pack(x3, .true.), pack(-kk* &
                            spread(q(1, :) - l0, 1, 2)*reshape([cos(q(2, :)), sin(q(2, :))], &
                            [2, n], order=[2, 1]), .true.), 1.0e-13_dp)
            end select
         case ('spring_length')
            call h5%read('/trajectory/spring_length', x2, error)
            call compare(error, tag, 'spring_length', pack(x2, .true.), q(1, :), 1.0e-15_dp)
            call compare(error, tag, 'spring_length |rC - rA|', pack(x2, .true.), &
                         norm2(rc, dim=1), 1.0e-14_dp)
         case ('tension')
            call h5%read('/trajectory/tension', x2, error)
            call compare(error, tag, 'tension', pack(x2, .true.), kk*(q(1, :) - l0), 1.0e-14_dp)
         case default
            call fatal_error(error, tag//': no check for dataset '//trim(names(k)))
         end select
      end do
      call h5%close()
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      !> (r̈, φ̈) of the elastic pendulum at z = (r, φ, ṙ, φ̇).
      pure function field(z) result(a)
         real(dp), intent(in) :: z(4)
         real(dp) :: a(2)
         a(1) = z(1)*z(4)**2 - kk/m*(z(1) - l0) - g*sin(z(2))
         a(2) = -(2.0_dp*z(3)*z(4) + g*cos(z(2)))/z(1)
      end function field
   end subroutine check_elastic

end module test_values_simulate
