!> Applied joint torques (dpend_joint_torque, the chain's generalized forces and the
!> work W_torque), against independently known values:
!> - the series: its samples exactly, straight lines between them (a linear torque
!>   sampled at irregular times is reproduced to rounding anywhere), the end values
!>   outside; the closed form against its formula; every refusal in one line;
!> - a torque-driven single link against its analytic solution: τ(t) = G cos(q0 + Ω t)
!>   (G = g m l/2) holds the link in uniform rotation q = q0 + Ω t, whatever gravity
!>   does, and does the work W = G (sin q − sin q0);
!> - a single link under a constant torque: W_torque = τ (q − q0) exactly;
!> - the double pendulum with a torque at joint 2 only and at both joints against a
!>   second formulation: Lagrange's equations in absolute angles (dpend_pendulum's
!>   `qddot_lagrange`) with the generalized forces Q1 = τ1 − τ2, Q2 = τ2, rods and
!>   general bodies;
!> - the energy balance E(t) − E(0) + W_friction − W_support − W_torque of dop853 at
!>   rtol 1e-12 over 50 s with torques, damping, Coulomb friction and a moving support;
!> - a motor (rotor inertia I_r, gear ratio g_r): one rod without gravity's effect
!>   under a constant τ turns by τ t²/(2 (J + g_r² I_r)); the double pendulum with
!>   motors at both joints against Lagrange's equations with M + Dᵀ diag(g_r² I_r) D;
!> - Coulomb friction c_f tanh(ω/v_s) on one rod (gravity 1e-6) under a constant τ:
!>   below c_f it creeps at v_s atanh(τ/c_f), and its rate from rest follows the
!>   closed form t(ω) = K v_s [τ u + c_f ln((τ cosh u − c_f sinh u)/τ)]/(τ² − c_f²),
!>   u = ω/v_s (the integral of K dω/(τ − c_f tanh(ω/v_s))), below and above c_f;
!> - the chain's Jacobian with Coulomb friction and damping against central differences.
!> Each test prints its measured figures on one line ('    joint_torque: …').
module test_joint_torque
   use, intrinsic :: iso_fortran_env, only: output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_joint_torque, only: joint_torque_t, torque_series, torque_sines
   use dpend_chain, only: chain_t, chain_model
   use dpend_pendulum, only: pendulum_t, qddot_lagrange, mass_matrix, body_general
   use dpend_work, only: work_model_t, work_model, balance_energy
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec, model_spec_t, new_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to
   use dpend_cli, only: real_str, to_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_joint_torque

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_joint_torque(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('series_and_closed_form', test_values), &
               new_unittest('refusals', test_refusals), &
               new_unittest('single_link_uniform_rotation', test_rotation), &
               new_unittest('single_link_constant_torque_work', test_constant), &
               new_unittest('double_pendulum_vs_lagrange', test_lagrange), &
               new_unittest('energy_balance_dop853', test_balance), &
               new_unittest('coulomb_creep_and_closed_form', test_coulomb), &
               new_unittest('coulomb_jacobian', test_coulomb_jacobian), &
               new_unittest('motor_constant_torque', test_motor_constant), &
               new_unittest('motors_vs_lagrange', test_motor_lagrange)]
   end subroutine collect_joint_torque

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    joint_torque: '//text
   end subroutine report

   !> A linear torque τ_i = a_i + b_i t sampled at irregular times is reproduced
   !> between the samples (to rounding), the samples exactly, the end values outside;
   !> the closed form equals its formula.
   subroutine test_values(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      real(dp) :: t(40), v(2, 40), tau(2), worst, x
      real(dp), parameter :: a(2) = [0.3_dp, -1.7_dp], b(2) = [2.5_dp, 0.4_dp]
      integer :: k
      x = 0.37_dp
      t(1) = -0.5_dp
      do k = 2, size(t)
         x = mod(x*7.31_dp + 0.17_dp, 1.0_dp)
         t(k) = t(k - 1) + 0.01_dp + 0.3_dp*x
      end do
      do k = 1, size(t)
         v(:, k) = a + b*t(k)
      end do
      tq = torque_series(t, v, err)
      call check_true(error, .not. allocated(err) .and. tq%active() .and. tq%n == 2, &
                      'series refused')
      if (allocated(error)) return
      worst = 0.0_dp
      do k = 1, 997
         x = t(1) + (t(size(t)) - t(1))*real(k, dp)/997.0_dp
         call tq%values(x, tau)
         worst = max(worst, maxval(abs(tau - (a + b*x))))
      end do
      do k = 1, size(t)
         call tq%values(t(k), tau)
         call check(error, tau, v(:, k), 'a sample', abs=0.0_dp)
         if (allocated(error)) return
      end do
      call report('linear torque from 40 irregular samples, 997 times: max error '// &
                  real_str(worst, 2)//' N m')
      call check(error, worst, 0.0_dp, 'linear interpolation', abs=1e-13_dp)
      if (allocated(error)) return
      call tq%values(t(1) - 3.0_dp, tau)
      call check(error, tau, v(:, 1), 'before the first sample', abs=0.0_dp)
      call tq%values(t(size(t)) + 3.0_dp, tau)
      call check(error, tau, v(:, size(t)), 'after the last sample', abs=0.0_dp)
      call check_true(error, tq%covers(t(1), t(size(t))) .and. .not. tq%covers(t(1) - &
                      1e-9_dp, t(2)) .and. .not. tq%covers(t(1), t(size(t)) + 1e-9_dp), 'covers')
      if (allocated(error)) return
      tq = torque_sines([0.5_dp, -0.2_dp], reshape([1.0_dp, 2.0_dp, 0.3_dp, -0.4_dp], &
                        [2, 2]), [3.0_dp, 7.0_dp], reshape([0.1_dp, 0.2_dp, -0.3_dp, &
                        1.1_dp], [2, 2]), err)
      call check_true(error, .not. allocated(err) .and. tq%covers(-1e9_dp, 1e9_dp), &
                      'closed form refused')
      if (allocated(error)) return
      x = 0.731_dp
      call tq%values(x, tau)
      call check(error, tau, [0.5_dp + 1.0_dp*sin(3.0_dp*x + 0.1_dp) &
                 + 0.3_dp*sin(7.0_dp*x - 0.3_dp), -0.2_dp + 2.0_dp*sin(3.0_dp*x + 0.2_dp) &
                 - 0.4_dp*sin(7.0_dp*x + 1.1_dp)], 'closed form', abs=1e-15_dp)
   end subroutine test_values

   !> Too few samples, times not increasing, NaN, a torque beyond 1e6 N m, the wrong
   !> number of joints for the chain, torques for a model without joints: refused in
   !> one line naming the sample or field.
   subroutine test_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      real(dp) :: nan
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      tq = torque_series([0.0_dp], reshape([1.0_dp], [1, 1]), err)
      call refused(err, 'at least 2')
      if (allocated(error)) return
      tq = torque_series([0.0_dp, 1.0_dp, 1.0_dp], reshape([1.0_dp, 2.0_dp, 3.0_dp], &
                         [1, 3]), err)
      call refused(err, 'sample 3: t = 1 s is not after')
      if (allocated(error)) return
      tq = torque_series([0.0_dp, 1.0_dp], reshape([1.0_dp, nan], [1, 2]), err)
      call refused(err, 'sample 2: tau1')
      if (allocated(error)) return
      tq = torque_series([0.0_dp, 1.0_dp], reshape([1.0_dp, 2e6_dp], [1, 2]), err)
      call refused(err, 'tau1 = 2e6 N m is not finite within')
      if (allocated(error)) return
      tq = torque_sines([1.0_dp], reshape([1e6_dp], [1, 1]), [1.0_dp], &
                        reshape([0.0_dp], [1, 1]), err)
      call refused(err, 'invalid torque tau1: |bias| + sum |amplitude|')
      if (allocated(error)) return
      tq = torque_series([0.0_dp, 1.0_dp], reshape([1.0_dp, 2.0_dp], [1, 2]), err)
      chain = chain_model([1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp], 9.8_dp, err, torque=tq)
      call refused(err, 'invalid torque: 1 joint torques for 2 links')
      if (allocated(error)) return
      spec = model_spec('elastic')
      spec%torque = tq
      call new_model(spec, model, err)
      call refused(err, 'invalid torque: model elastic has no joints')
   contains
      subroutine refused(e, text)
         type(error_t), allocatable, intent(inout) :: e
         character(len=*), intent(in) :: text
         call check_true(error, allocated(e), 'not refused: '//text)
         if (allocated(error)) return
         call check_true(error, index(e%message, text) > 0 .and. &
                         index(e%message, new_line('a')) == 0, &
                         "message '"//e%message//"' lacks '"//text//"'")
         deallocate (e)
      end subroutine refused
   end subroutine test_refusals

   !> One rod (m 1.3 kg, l 0.8 m, g 9.81) under τ(t) = G cos(q0 + Ω t) = G sin(Ω t +
   !> q0 + π/2), started at q0 with q̇ = Ω: q(t) = q0 + Ω t exactly and W_torque(t) =
   !> G (sin q(t) − sin q0). dop853, rtol 1e-14, 5 s (the rotation is neutrally stable:
   !> a step's error is carried along, so the tolerance is the tight one).
   subroutine test_rotation(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(work_model_t) :: wm
      class(integrator_t), allocatable :: integ
      real(dp), parameter :: m = 1.3_dp, l = 0.8_dp, g = 9.81_dp, omega = 2.3_dp, &
                             q0 = -0.4_dp
      real(dp) :: y(6), t, h, gg, dq, dw, dwork
      integer :: k, stat
      gg = g*m*l/2.0_dp
      tq = torque_sines([0.0_dp], reshape([gg], [1, 1]), [omega], &
                        reshape([q0 + 0.5_dp*pi], [1, 1]), err)
      wm%chain = chain_model([m], [l], g, err, torque=tq)
      wm%k = 2
      call check_true(error, .not. allocated(err) .and. wm%n_dof() == 3, 'chain refused')
      if (allocated(error)) return
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-14_dp, &
                          atol=1e-15_dp))
      ! (q, W_friction, W_torque, q̇, W_support, 0): n_dof 3
      y = [q0, 0.0_dp, 0.0_dp, omega, 0.0_dp, 0.0_dp]
      t = 0.0_dp; h = 0.0_dp; dq = 0.0_dp; dw = 0.0_dp; dwork = 0.0_dp
      do k = 1, 50
         call advance_to(integ, wm, t, y, 0.1_dp*k, h, stat)
         call check_true(error, stat == stat_ok, 'integration failed')
         if (allocated(error)) return
         dq = max(dq, abs(y(1) - (q0 + omega*t)))
         dw = max(dw, abs(y(4) - omega))
         dwork = max(dwork, abs(y(3) - gg*(sin(q0 + omega*t) - sin(q0)))/gg)
      end do
      call report('uniform rotation, dop853 rtol 1e-14, 5 s: |q - q0 - Omega t| '//real_str(dq, 2)// &
                  ' rad, |qdot - Omega| '//real_str(dw, 2)//' rad/s, W_torque rel '// &
                  real_str(dwork, 2))
      call check(error, dq, 0.0_dp, 'angle of the uniform rotation', abs=1e-10_dp)
      call check(error, dw, 0.0_dp, 'rate of the uniform rotation', abs=1e-10_dp)
      call check(error, dwork, 0.0_dp, 'work of the torque', abs=1e-10_dp)
   end subroutine test_rotation

   !> One rod under a constant τ = 1.7 N m from hanging at rest: the work is τ (q − q0)
   !> at every time (and the link swings about the tilted equilibrium cos q* = τ/G).
   subroutine test_constant(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      class(model_t), allocatable :: wm
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp), parameter :: tau = 1.7_dp, q0 = -0.5_dp*pi
      real(dp) :: y(6), t, h, d, qmax
      integer :: k, stat
      chain = chain_model([0.9_dp], [1.1_dp], 9.81_dp, err, &
                          torque=torque_series([0.0_dp, 20.0_dp], &
                                               reshape([tau, tau], [1, 2]), err))
      call check_true(error, .not. allocated(err), 'chain refused')
      if (allocated(error)) return
      call work_model(chain, wm)
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      y = [q0, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      t = 0.0_dp; h = 0.0_dp; d = 0.0_dp; qmax = 0.0_dp
      do k = 1, 200
         call advance_to(integ, wm, t, y, 0.1_dp*k, h, stat)
         call check_true(error, stat == stat_ok, 'integration failed')
         if (allocated(error)) return
         d = max(d, abs(y(3) - tau*(y(1) - q0)))
         qmax = max(qmax, y(1) - q0)
      end do
      call report('constant torque 1.7 N m, 20 s: |W_torque - tau (q - q0)| '// &
                  real_str(d, 2)//' J (swing up to '//real_str(qmax, 4)//' rad)')
      call check(error, d, 0.0_dp, 'work of a constant torque', abs=1e-10_dp)
   end subroutine test_constant

   !> q̈ of the chain (Newton–Euler with Q_i = τ_i − τ_(i+1)) against Lagrange's
   !> accelerations plus M⁻¹ (τ1 − τ2, τ2), at 50 states and times, rods and general
   !> bodies, a torque at joint 2 only and at both joints.
   subroutine test_lagrange(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      type(pendulum_t) :: par
      real(dp) :: y(4), f(4), mm(2, 2), q(2), tau(2), expect(2), s, t, worst, det
      integer :: k, body, which
      worst = 0.0_dp
      s = 0.29_dp
      do body = 1, 2
         do which = 1, 2
            ! joint 2 only (which 1) or both (which 2): sums of two sines
            tq = torque_sines([0.0_dp, 0.8_dp], reshape([merge(0.0_dp, 3.0_dp, which == 1), &
                              2.0_dp, merge(0.0_dp, -1.5_dp, which == 1), 0.7_dp], [2, 2]), &
                              [1.3_dp, 4.1_dp], reshape([0.2_dp, -0.6_dp, 1.0_dp, 0.4_dp], &
                              [2, 2]), err)
            par = pendulum_t(m1=1.2_dp, m2=0.7_dp, l1=0.9_dp, l2=1.3_dp, g=9.81_dp)
            if (body == 1) then
               chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err, &
                                   torque=tq)
            else
               par%body = body_general
               par%d1 = 0.6_dp; par%d2 = 1.5_dp; par%i1 = 0.05_dp; par%i2 = 0.11_dp
               chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err, &
                                   com=[par%d1, par%d2], inertia=[par%i1, par%i2], torque=tq)
            end if
            call check_true(error, .not. allocated(err), 'chain refused')
            if (allocated(error)) return
            do k = 1, 50
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(1) = 6.0_dp*s - 3.0_dp
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(2) = 6.0_dp*s - 3.0_dp
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(3) = 8.0_dp*s - 4.0_dp
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(4) = 8.0_dp*s - 4.0_dp
               t = 0.53_dp*k
               call chain%field(t, y, f)
               call tq%values(t, tau)
               q = y(1:2)
               mm = mass_matrix(par, q)
               det = mm(1, 1)*mm(2, 2) - mm(1, 2)*mm(2, 1)
               expect = qddot_lagrange(par, q, y(3:4)) + &
                        [mm(2, 2)*(tau(1) - tau(2)) - mm(1, 2)*tau(2), &
                         mm(1, 1)*tau(2) - mm(2, 1)*(tau(1) - tau(2))]/det
               worst = max(worst, maxval(abs(f(3:4) - expect))/max(1.0_dp, maxval(abs(expect))))
            end do
         end do
      end do
      call report('double pendulum, torques at joint 2 / both, rods and bodies, 200 '// &
                  'states: max |qddot NE - qddot Lagrange| / max(1, |qddot|) '// &
                  real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'Newton-Euler against Lagrange with torques', &
                 abs=1e-12_dp)
   end subroutine test_lagrange

   !> dop853 at rtol 1e-12 over 50 s, N = 2 and 3, torques from a series and from a
   !> closed form, with damping and a moving support: the balance error
   !> |E(t) − E(0) + W_friction − W_support − W_torque| / energy scale.
   subroutine test_balance(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      class(model_t), allocatable :: wm
      class(integrator_t), allocatable :: integ
      real(dp), allocatable :: y(:), ts(:), vs(:, :)
      real(dp) :: t, h, e0, scale, worst, b, wt
      character(len=:), allocatable :: text
      integer :: n, k, stat, form, i
      worst = 0.0_dp
      text = ''
      do n = 2, 3
         do form = 1, 2
            if (form == 1) then   ! 501 samples of a chirp-like sum over [0, 50] s
               allocate (ts(501), vs(n, 501))
               do k = 1, 501
                  ts(k) = 0.1_dp*(k - 1)
                  vs(:, k) = [(1.5_dp/i*sin(0.7_dp*i*ts(k) + 0.02_dp*ts(k)**2), i = 1, n)]
               end do
               tq = torque_series(ts, vs, err)
               deallocate (ts, vs)
            else
               tq = torque_sines([(0.3_dp, i = 1, n)], reshape([(1.0_dp/i, i = 1, 2*n)], &
                                 [n, 2]), [1.1_dp, 2.9_dp], reshape([(0.1_dp*i, i = 1, 2*n)], &
                                 [n, 2]), err)
            end if
            chain = chain_model([(1.0_dp, i = 1, n)], [(1.0_dp, i = 1, n)], 9.81_dp, err, &
                                damping=[(0.05_dp/i, i = 1, n)], amplitude=[0.01_dp, 0.02_dp], &
                                frequency=5.0_dp, phase=[0.5_dp, 0.0_dp], torque=tq, &
                                coulomb=[(0.2_dp*(form - 1)/i, i = 1, n)], coulomb_speed=0.05_dp, &
                                rotor_inertia=[(2e-3_dp*(form - 1), i = 1, n)], &
                                gear_ratio=[(4.0_dp + i, i = 1, n)])
            call check_true(error, .not. allocated(err), 'chain refused')
            if (allocated(error)) return
            call work_model(chain, wm)
            call new_integrator('dop853', integ, err, method_options_t(rtol=1e-12_dp, &
                                atol=1e-14_dp))
            allocate (y(2*wm%n_dof()))
            y = 0.0_dp
            y(1:n) = -0.5_dp*pi + [(0.3_dp/i, i = 1, n)]
            e0 = balance_energy(wm, 0.0_dp, y)
            scale = wm%energy_scale(e0)
            t = 0.0_dp; h = 0.0_dp; b = 0.0_dp
            do k = 1, 50
               call advance_to(integ, wm, t, y, real(k, dp), h, stat)
               call check_true(error, stat == stat_ok, 'integration failed')
               if (allocated(error)) return
               b = max(b, abs(balance_energy(wm, t, y) - e0)/scale)
            end do
            wt = y(n + 2)
            worst = max(worst, b)
            text = text//' N='//to_str(n)//trim(merge(' series', ' sines ', form == 1))// &
                   ' '//real_str(b, 2)//' (W_torque '//real_str(wt, 3)//' J);'
            deallocate (y)
         end do
      end do
      call report('energy balance with torques, damping, support (sines: and Coulomb '// &
                  'friction, motors), dop853 rtol 1e-12, '// &
                  '50 s, max rel error:'//text)
      call check(error, worst, 0.0_dp, 'energy balance error', abs=1e-10_dp)
   end subroutine test_balance

   !> One rod (m 1 kg, l 1 m, g 1e-6: J = 1/3 kg m², gravity's torque ≤ 5e-7 N m) with a
   !> motor (I_r = 2e-3 kg m², g_r = 10: 0.2 kg m² reflected) from rest under τ = 1 N m:
   !> q − q0 = τ t²/(2 (J + g_r² I_r)) = 0.9375 t², to gravity's share (1e-6 relative).
   subroutine test_motor_constant(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp), parameter :: tau = 1.0_dp, q0 = -0.5_dp*pi, jt = 1.0_dp/3.0_dp + 0.2_dp
      real(dp) :: y(2), t, h, d
      integer :: k, stat
      chain = chain_model([1.0_dp], [1.0_dp], 1e-6_dp, err, &
                          torque=torque_series([0.0_dp, 3.0_dp], &
                                               reshape([tau, tau], [1, 2]), err), &
                          rotor_inertia=[2e-3_dp], gear_ratio=[10.0_dp])
      call check_true(error, .not. allocated(err), 'chain refused')
      if (allocated(error)) return
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      y = [q0, 0.0_dp]
      t = 0.0_dp; h = 0.0_dp; d = 0.0_dp
      do k = 1, 30
         call advance_to(integ, chain, t, y, 0.1_dp*k, h, stat)
         call check_true(error, stat == stat_ok, 'integration failed')
         if (allocated(error)) return
         d = max(d, abs((y(1) - q0) - tau*t**2/(2*jt))/(tau*t**2/(2*jt)))
      end do
      call report('motor (J 1/3 + g_r^2 I_r 0.2 kg m^2) under 1 N m, 3 s: max rel '// &
                  '|q - q0 - tau t^2/(2 J_total)| '//real_str(d, 2)//' (without the '// &
                  'rotor the angle would be '//real_str(jt/(1.0_dp/3.0_dp), 3)//' times larger)')
      call check(error, d, 0.0_dp, 'motor under a constant torque', abs=1e-5_dp)
   end subroutine test_motor_constant

   !> The double pendulum with motors at both joints (reflected inertias 0.05 and
   !> 0.02 kg m²) and torques at both joints: (M + R) q̈ = M q̈_Lagrange + Q, R =
   !> Dᵀ diag(Im) D = [[Im1 + Im2, −Im2], [−Im2, Im2]], Q = (τ1 − τ2, τ2), 100 states,
   !> rods and general bodies.
   subroutine test_motor_lagrange(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(joint_torque_t) :: tq
      type(chain_t) :: chain
      type(pendulum_t) :: par
      real(dp), parameter :: im(2) = [0.05_dp, 0.02_dp]
      real(dp) :: y(4), f(4), mm(2, 2), q(2), tau(2), expect(2), rhs(2), s, t, worst, det
      integer :: k, body
      worst = 0.0_dp
      s = 0.53_dp
      tq = torque_sines([0.4_dp, -0.3_dp], reshape([2.0_dp, 1.0_dp, -0.7_dp, 0.5_dp], [2, 2]), &
                        [1.9_dp, 3.3_dp], reshape([0.1_dp, 0.2_dp, 0.3_dp, 0.4_dp], [2, 2]), err)
      do body = 1, 2
         par = pendulum_t(m1=1.1_dp, m2=0.6_dp, l1=0.7_dp, l2=0.9_dp, g=9.81_dp)
         if (body == 1) then
            chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err, torque=tq, &
                                rotor_inertia=im/[25.0_dp, 4.0_dp], gear_ratio=[5.0_dp, 2.0_dp])
         else
            par%body = body_general
            par%d1 = 0.5_dp; par%d2 = 1.2_dp; par%i1 = 0.04_dp; par%i2 = 0.09_dp
            chain = chain_model([par%m1, par%m2], [par%l1, par%l2], par%g, err, &
                                com=[par%d1, par%d2], inertia=[par%i1, par%i2], torque=tq, &
                                rotor_inertia=im/[25.0_dp, 4.0_dp], gear_ratio=[5.0_dp, 2.0_dp])
         end if
         call check_true(error, .not. allocated(err), 'chain refused')
         if (allocated(error)) return
         do k = 1, 50
            s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(1) = 6.0_dp*s - 3.0_dp
            s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(2) = 6.0_dp*s - 3.0_dp
            s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(3) = 8.0_dp*s - 4.0_dp
            s = mod(s*7.31_dp + 0.17_dp, 1.0_dp); y(4) = 8.0_dp*s - 4.0_dp
            t = 0.61_dp*k
            call chain%field(t, y, f)
            call tq%values(t, tau)
            q = y(1:2)
            mm = mass_matrix(par, q)
            rhs = matmul(mm, qddot_lagrange(par, q, y(3:4))) + [tau(1) - tau(2), tau(2)]
            mm = mm + reshape([im(1) + im(2), -im(2), -im(2), im(2)], [2, 2])
            det = mm(1, 1)*mm(2, 2) - mm(1, 2)*mm(2, 1)
            expect = [mm(2, 2)*rhs(1) - mm(1, 2)*rhs(2), mm(1, 1)*rhs(2) - mm(2, 1)*rhs(1)]/det
            worst = max(worst, maxval(abs(f(3:4) - expect))/max(1.0_dp, maxval(abs(expect))))
         end do
      end do
      call report('double pendulum with motors (g_r^2 I_r 0.05, 0.02 kg m^2), torques at '// &
                  'both joints, rods and bodies, 100 states: max |qddot chain - qddot '// &
                  'Lagrange + rotors| / max(1, |qddot|) '//real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'chain with motors against Lagrange', abs=1e-12_dp)
   end subroutine test_motor_lagrange

   !> One rod (m 1 kg, l 1 m, g 1e-6: K = 1/3 kg m², gravity's torque ≤ 5e-7 N m) with
   !> Coulomb friction c_f = 1 N m, v_s = 1e-3 rad/s, from rest under a constant τ:
   !> τ = 0.5 creeps at v_s atanh(0.5) and never faster; τ = 0.5 and τ = 2 follow
   !> t(ω) of the closed form (times compared, gravity's share below 1e-5 s).
   subroutine test_coulomb(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      class(model_t), allocatable :: wm
      class(integrator_t), allocatable :: integ
      real(dp), parameter :: cf = 1.0_dp, vs = 1e-3_dp, kk = 1.0_dp/3.0_dp
      real(dp) :: y(6), t, h, tau, wmax, dtime, creep, u
      integer :: k, stat, case
      do case = 1, 2
         tau = merge(0.5_dp, 2.0_dp, case == 1)
         chain = chain_model([1.0_dp], [1.0_dp], 1e-6_dp, err, &
                             torque=torque_series([0.0_dp, 10.0_dp], reshape([tau, tau], &
                                                  [1, 2]), err), coulomb=[cf], coulomb_speed=vs)
         call check_true(error, .not. allocated(err), 'chain refused')
         if (allocated(error)) return
         call work_model(chain, wm)
         call new_integrator('dop853', integ, err, method_options_t(rtol=1e-13_dp, &
                             atol=1e-16_dp))
         y = [-0.5_dp*pi, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
         t = 0.0_dp; h = 0.0_dp; wmax = 0.0_dp; dtime = 0.0_dp
         creep = huge(1.0_dp)   ! (no creep above c_f)
         if (tau < cf) creep = vs*atanh(tau/cf)
         do k = 1, 200   ! every 10 µs over the first millisecond, then every 50 ms
            call advance_to(integ, wm, t, y, merge(1e-5_dp*k, 1e-3_dp + 0.05_dp*(k - 100), &
                            k <= 100), h, stat)
            call check_true(error, stat == stat_ok, 'integration failed')
            if (allocated(error)) return
            wmax = max(wmax, y(4))
            u = y(4)/vs
            ! the closed form's time, where it is well conditioned (not at the creep
            ! rate itself, where t(ω) has its logarithmic pole); ln(τ cosh u − c_f sinh u)
            ! = u + ln(((τ − c_f) + (τ + c_f) e^(−2u))/2), finite for large u
            if (case == 2 .or. y(4) < 0.9_dp*creep) dtime = max(dtime, abs(t - kk*vs* &
               (tau*u + cf*(u + log(((tau - cf) + (tau + cf)*exp(-2.0_dp*u))/(2.0_dp*tau)))) &
               /(tau**2 - cf**2)))
         end do
         if (case == 1) then
            call report('Coulomb c_f 1 N m, v_s 1e-3 rad/s, tau 0.5 N m, 5 s: creep '// &
                        real_str(y(4), 6)//' rad/s (v_s atanh(tau/c_f) '// &
                        real_str(creep, 6)//'), fastest '//real_str(wmax, 6)// &
                        ', closed-form time error '//real_str(dtime, 2)//' s')
            call check(error, y(4), creep, 'creep rate', rel=1e-6_dp)
            call check_true(error, wmax <= creep*(1.0_dp + 1e-6_dp) .and. wmax < vs, &
                            'faster than the creep rate')
         else
            call report('Coulomb c_f 1 N m, tau 2 N m: qdot '//real_str(y(4), 9)// &
                        ' rad/s at t = '//real_str(t, 6)//' s (closed form for u >> 1: '// &
                        real_str((tau - cf)/kk*(t - kk*vs*cf*log((tau - cf)/(2.0_dp*tau)) &
                        /(tau**2 - cf**2)), 9)//'), closed-form time error '// &
                        real_str(dtime, 2)//' s')
         end if
         call check(error, dtime, 0.0_dp, 'time of the closed form', abs=1e-5_dp)
         if (allocated(error)) return
      end do
   end subroutine test_coulomb

   !> The Jacobian of the chain with Coulomb friction (v_s 0.3 rad/s: the slope varies
   !> over the states) and damping, N = 1, 2, 3, against central differences of the field.
   subroutine test_coulomb_jacobian(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      real(dp) :: y(6), yp(6), ym(6), fp(6), fm(6), jac(6, 6), jfd(6, 6), s, dx, worst
      integer :: n, m, k, i
      worst = 0.0_dp
      s = 0.41_dp
      do n = 1, 3
         m = 2*n
         chain = chain_model([(0.5_dp + 0.3_dp*i, i = 1, n)], [(1.2_dp - 0.2_dp*i, i = 1, n)], &
                             9.81_dp, err, damping=[(0.1_dp*i, i = 1, n)], &
                             coulomb=[(0.4_dp/i, i = 1, n)], coulomb_speed=0.3_dp)
         call check_true(error, .not. allocated(err), 'chain refused')
         if (allocated(error)) return
         do k = 1, 20
            do i = 1, m
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
               y(i) = 2.0_dp*s - 1.0_dp
            end do
            call chain%jacobian(0.0_dp, y(1:m), jac(1:m, 1:m))
            do i = 1, m
               dx = 1e-6_dp*max(1.0_dp, abs(y(i)))
               yp(1:m) = y(1:m); ym(1:m) = y(1:m)
               yp(i) = y(i) + dx; ym(i) = y(i) - dx
               call chain%field(0.0_dp, yp(1:m), fp(1:m))
               call chain%field(0.0_dp, ym(1:m), fm(1:m))
               jfd(1:m, i) = (fp(1:m) - fm(1:m))/(2.0_dp*dx)
            end do
            worst = max(worst, maxval(abs(jac(1:m, 1:m) - jfd(1:m, 1:m))) &
                        /maxval(abs(jfd(1:m, 1:m))))
         end do
      end do
      call report('Jacobian with Coulomb friction and damping, N = 1..3, 60 states: '// &
                  'max rel difference from central differences '//real_str(worst, 2))
      call check(error, worst, 0.0_dp, 'Jacobian against differences', abs=1e-7_dp)
   end subroutine test_coulomb_jacobian
end module test_joint_torque
