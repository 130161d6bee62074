!> The energy balance that simulate writes (`/trajectory/W_friction`, `W_support`,
!> `balance_error`, and `energy`) against an independent recomputation from the stored
!> states (a mutant that survived the earlier suite: the balance written without the
!> friction term).
!>
!> The two-link chain of uniform rods (m = 1 kg, L = 1 m, g = 9.8 m/s²) is written
!> out here in closed form, from the chain's conventions (dpend_chain's notes) but
!> none of its code: C_1 = A + (L/2) u_1, C_2 = A + L u_1 + (L/2) u_2, u_i = (cos q_i,
!> sin q_i), the pin A = (a_x cos ωt, a_y cos ωt);
!>   E = Σ ½ m |v_Ci|² + ½ (m L²/12) q̇_i² + m g y_Ci,
!>   P_friction = c_1 q̇_1² + c_2 (q̇_2 − q̇_1)²,
!>   P_support = F_01 · v_A,  F_01 = Σ m (a_Ci + g ĵ)   (Newton for the whole chain),
!> with a_Ci from the stored q, q̇, q̈. The works are composite Boole integrals over
!> the samples (output every 1 ms), so at every 4th sample the file's values must match:
!>   energy (the closed form), W_friction, W_support (the quadratures), and
!>   balance_error = (E − E(0) + W_friction − W_support)/|E(0)|,
!> the latter also below 1e-8 (dop853 at rtol 1e-12: the balance closes).
!> Measured (damped; damped and driven), largest differences: energy 1.1e-14, 1.6e-14 J;
!> W_friction 8.7e-12, 2.2e-10 J; W_support 0, 1.3e-9 J; balance_error 2.5e-12, 2.3e-10
!> (tolerances 1e-13 J, 1e-8 J, 2e-9). Printed on one line ('    balance: …').
!> Dropping W_friction from balance_error changes it by W_friction/|E(0)| ≈ 5.
module test_balance
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   use test_cli, only: run_command, scratch_dir
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_balance
   public :: boole   ! also used by test_values_simulate

   real(dp), parameter :: g = 9.8_dp      !! gravity [m/s²] (the default)
   real(dp), parameter :: m = 1.0_dp      !! link mass [kg] (the default)
   real(dp), parameter :: l = 1.0_dp      !! link length [m] (the default)

contains

   subroutine collect_balance(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('damped_balance_recomputed', test_damped), &
               new_unittest('damped_driven_balance_recomputed', test_driven)]
   end subroutine collect_balance

   !> Damping only.
   subroutine test_damped(error)
      type(error_t), allocatable, intent(out) :: error
      call balance_case('damped', [0.3_dp, 0.2_dp], [0.0_dp, 0.0_dp], 0.0_dp, error)
   end subroutine test_damped

   !> Damping and a support moving along both axes.
   subroutine test_driven(error)
      type(error_t), allocatable, intent(out) :: error
      call balance_case('driven', [0.1_dp, 0.05_dp], [0.04_dp, 0.07_dp], 5.0_dp, error)
   end subroutine test_driven

   !> Simulate with damping c, support amplitudes a and frequency w; compare the file.
   subroutine balance_case(tag, c, a, w, error)
      character(len=*), intent(in) :: tag              !! case name
      real(dp), intent(in) :: c(2)                     !! joint damping [N m s]
      real(dp), intent(in) :: a(2)                     !! support amplitudes a_x, a_y [m]
      real(dp), intent(in) :: w                        !! support frequency [rad/s]
      type(error_t), allocatable, intent(out) :: error !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: dir, args
      character(len=80) :: buf
      real(dp), allocatable :: t(:), q(:, :), qd(:, :), qdd(:, :), e(:), wf(:), ws(:), bal(:)
      real(dp), allocatable :: ex(:), pf(:), ps(:), wfx(:), wsx(:), balx(:)
      real(dp) :: d_e, d_wf, d_ws, d_bal
      integer :: stat, n, i
      dir = scratch_dir('balance'//tag)
      write (buf, '(g0, ",", g0)') c
      args = 'simulate --method dop853 --rtol 1e-12 --atol 1e-14 --t-end 4 ' // &
             '--output-dt 0.001 --q 0.3,-0.4 --w 1.5,-2 --damping '//trim(adjustl(buf))
      if (w > 0.0_dp) then
         write (buf, '(g0, ",", g0)') a
         args = args//' --support-amplitude '//trim(adjustl(buf))
         write (buf, '(g0)') w
         args = args//' --support-frequency '//trim(adjustl(buf))
      end if
      stat = run_command(dir, args//' --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, tag//': simulate exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/sim.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qddot', qdd, error)
      if (.not. allocated(error)) call h5%read('/trajectory/energy', e, error)
      if (.not. allocated(error)) call h5%read('/trajectory/W_friction', wf, error)
      if (.not. allocated(error)) call h5%read('/trajectory/W_support', ws, error)
      if (.not. allocated(error)) call h5%read('/trajectory/balance_error', bal, error)
      call h5%close()
      if (allocated(error)) return
      n = size(t)
      call check_true(error, n == 4001 .and. all(shape(q) == [2, n]), tag//': 4001 samples')
      if (allocated(error)) return
      allocate (ex(n), pf(n), ps(n))
      do i = 1, n
         call closed_form(t(i), q(:, i), qd(:, i), qdd(:, i), c, a, w, ex(i), pf(i), ps(i))
      end do
      wfx = boole(t, pf); wsx = boole(t, ps)
      balx = (ex(1:n:4) - ex(1) + wfx - wsx)/abs(ex(1))
      d_e = maxval(abs(e - ex))
      d_wf = maxval(abs(wf(1:n:4) - wfx))
      d_ws = maxval(abs(ws(1:n:4) - wsx))
      d_bal = maxval(abs(bal(1:n:4) - balx))
      write (output_unit, '(a, 4(a, es9.2), a, 2es10.2)') '    balance: '//tag, &
         ': |dE| ', d_e, ', |dW_f| ', d_wf, ', |dW_s| ', d_ws, ', |d balance| ', d_bal, &
         '; W_f, W_s at the end', wf(n), ws(n)
      call check(error, d_e, 0.0_dp, tag//': energy vs closed form [J]', abs=1.0e-13_dp)
      call check(error, d_wf, 0.0_dp, tag//': W_friction vs Boole [J]', abs=1.0e-8_dp)
      call check(error, d_ws, 0.0_dp, tag//': W_support vs Boole [J]', abs=1.0e-8_dp)
      call check(error, d_bal, 0.0_dp, tag//': balance_error vs recomputed', abs=2.0e-9_dp)
      call check(error, maxval(abs(bal)), 0.0_dp, tag//': |balance_error|', abs=1.0e-8_dp)
      ! the case must test something: friction work of order of the energy scale
      call check_true(error, wf(n) > 0.05_dp*abs(ex(1)), tag//': friction work too small')
      if (w > 0.0_dp) call check_true(error, abs(ws(n)) > 1.0e-3_dp*abs(ex(1)) .and. &
                                      maxval(abs(ws)) > 1.0e-2_dp*abs(ex(1)), &
                                      tag//': support work too small')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine balance_case

   !> Energy, friction power and support power of the two-link chain at one sample.
   pure subroutine closed_form(t, q, qd, qdd, c, a, w, e, pf, ps)
      real(dp), intent(in) :: t            !! time [s]
      real(dp), intent(in) :: q(2)         !! angles [rad]
      real(dp), intent(in) :: qd(2)        !! rates [rad/s]
      real(dp), intent(in) :: qdd(2)       !! accelerations [rad/s²]
      real(dp), intent(in) :: c(2)         !! joint damping [N m s]
      real(dp), intent(in) :: a(2)         !! support amplitudes [m]
      real(dp), intent(in) :: w            !! support frequency [rad/s]
      real(dp), intent(out) :: e           !! energy [J]
      real(dp), intent(out) :: pf          !! friction power [W]
      real(dp), intent(out) :: ps          !! support power [W]
      real(dp) :: u(2, 2), nn(2, 2), pa(2), va(2), aa(2), v1(2), v2(2), a1(2), a2(2), f01(2)
      integer :: i
      do i = 1, 2
         u(:, i) = [cos(q(i)), sin(q(i))]
         nn(:, i) = [-sin(q(i)), cos(q(i))]
      end do
      pa = a*cos(w*t); va = -a*w*sin(w*t); aa = -a*w**2*cos(w*t)
      v1 = va + 0.5_dp*l*qd(1)*nn(:, 1)
      v2 = va + l*qd(1)*nn(:, 1) + 0.5_dp*l*qd(2)*nn(:, 2)
      a1 = aa + 0.5_dp*l*(qdd(1)*nn(:, 1) - qd(1)**2*u(:, 1))
      a2 = aa + l*(qdd(1)*nn(:, 1) - qd(1)**2*u(:, 1)) + 0.5_dp*l*(qdd(2)*nn(:, 2) &
                                                                  - qd(2)**2*u(:, 2))
      e = 0.5_dp*m*(sum(v1**2) + sum(v2**2)) + 0.5_dp*(m*l**2/12.0_dp)*sum(qd**2) &
          + m*g*((pa(2) + 0.5_dp*l*u(2, 1)) + (pa(2) + l*u(2, 1) + 0.5_dp*l*u(2, 2)))
      pf = c(1)*qd(1)**2 + c(2)*(qd(2) - qd(1))**2
      f01 = m*(a1 + [0.0_dp, g]) + m*(a2 + [0.0_dp, g])
      ps = dot_product(f01, va)
   end subroutine closed_form

   !> Cumulative composite Boole integral of y over the samples x (equal spacing,
   !> size(x) = 4k + 1), at the samples 1, 5, 9, …: S_h + (S_h − S_2h)/15, S the
   !> composite Simpson rule (Richardson; error O(h⁶)).
   pure function boole(x, y) result(s)
      real(dp), intent(in) :: x(:)     !! abscissae
      real(dp), intent(in) :: y(:)     !! ordinates
      real(dp) :: s((size(x) - 1)/4 + 1)
      real(dp) :: s1, s2
      integer :: k, i
      s(1) = 0.0_dp
      do k = 2, size(s)
         i = 4*(k - 1) + 1
         s1 = (x(i) - x(i - 4))/12.0_dp*(y(i - 4) + 4.0_dp*y(i - 3) + 2.0_dp*y(i - 2) &
                                          + 4.0_dp*y(i - 1) + y(i))
         s2 = (x(i) - x(i - 4))/6.0_dp*(y(i - 4) + 4.0_dp*y(i - 2) + y(i))
         s(k) = s(k - 1) + s1 + (s1 - s2)/15.0_dp
      end do
   end function boole

end module test_balance
