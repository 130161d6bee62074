!> Joint damping, the moving support and the energy balance, against
!> independently known values:
!> - zero damping and no support: the chain and the double pendulum unchanged, bitwise
!>   (fields of the chain built with and without the zero options; the config still
!>   builds the double pendulum for two links);
!> - damped small oscillations: the roots s = −σ ± iω of the linearized quadratic
!>   eigenproblem M s² + C s + K = 0 (the companion form [0 I; −M⁻¹K −M⁻¹C] by LAPACK
!>   dgeev) against σ and ω measured on simulated runs (dop853) started on one mode,
!>   by Prony's recurrence x_(k+2) = a x_(k+1) − b x_k of equally spaced samples
!>   (a = 2 e^(−στ) cos ωτ, b = e^(−2στ)), for N = 1, 2, 3;
!> - the energy balance E(t) − E(0) + W_friction − W_support of dop853 at rtol 1e-12
!>   over 100 s, damped, forced, damped and forced;
!> - the Jacobian and the energy gradient of the damped, driven chain against central
!>   differences; F_(0,1) · v_A of `reactions` equals P_support of `powers`;
!> - the methods that need a Hamiltonian refuse the damped chain in one line; the
!>   explicit Runge–Kutta and the Gauss methods accept it.
!> Each test prints its measured figures on one line ('    damping: …').
module test_damping
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_pendulum, only: double_pendulum_t
   use dpend_work, only: work_model_t
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods, field_method_names
   use dpend_propagate, only: advance_to
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_lapack, only: dgesv, dgeev
   use dpend_cli, only: real_str, to_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_damping

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_damping(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('zero_damping_bitwise', test_bitwise), &
               new_unittest('damped_modes_quadratic_eigenproblem', test_modes), &
               new_unittest('energy_balance_dop853', test_balance), &
               new_unittest('jacobian_reactions_power', test_derivatives), &
               new_unittest('hamiltonian_methods_refuse', test_refuse)]
   end subroutine collect_damping

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    damping: '//text
   end subroutine report

   !> Zero damping and a support of zero amplitude leave the chain as it was: fields
   !> equal bitwise at random states for N = 1, 2, 3, 5; structure queries true; the
   !> config builds the double pendulum for two links with --damping 0,0.
   subroutine test_bitwise(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: a, b
      type(run_config_t) :: cfg
      real(dp) :: y(10), fa(10), fb(10), ja(10, 10), jb(10, 10), s
      integer :: n, nn, k, i, m, n_diff
      integer, parameter :: ns(4) = [1, 2, 3, 5]
      n_diff = 0
      s = 0.3_dp
      do nn = 1, 4
         n = ns(nn); m = 2*n
         a = chain_model([(1.0_dp + 0.1_dp*i, i = 1, n)], [(0.7_dp + 0.2_dp*i, i = 1, n)], &
                         9.81_dp, err)
         b = chain_model([(1.0_dp + 0.1_dp*i, i = 1, n)], [(0.7_dp + 0.2_dp*i, i = 1, n)], &
                         9.81_dp, err, damping=[(0.0_dp, i = 1, n)], &
                         amplitude=[0.0_dp, 0.0_dp], frequency=3.0_dp, phase=[0.1_dp, 0.2_dp])
         call check_true(error, .not. allocated(err), 'zero options refused')
         if (allocated(error)) return
         call check_true(error, b%hamiltonian() .and. b%conservative() .and. b%autonomous(), &
                         'zero damping, fixed pin: not Hamiltonian/conservative/autonomous')
         if (allocated(error)) return
         do k = 1, 20
            do i = 1, m
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
               y(i) = 4.0_dp*s - 2.0_dp
            end do
            call a%field(1.5_dp, y(1:m), fa(1:m))
            call b%field(1.5_dp, y(1:m), fb(1:m))
            if (any(fa(1:m) /= fb(1:m))) n_diff = n_diff + 1
            call a%jacobian(1.5_dp, y(1:m), ja(1:m, 1:m))
            call b%jacobian(1.5_dp, y(1:m), jb(1:m, 1:m))
            if (any(ja(1:m, 1:m) /= jb(1:m, 1:m))) n_diff = n_diff + 1
            if (a%energy(1.5_dp, y(1:m)) /= b%energy(1.5_dp, y(1:m))) n_diff = n_diff + 1
         end do
      end do
      call report('zero damping, fixed pin: fields, Jacobians, energies differing at 80 '// &
                  'states x 4 chains: '//to_str(n_diff))
      call check_true(error, n_diff == 0, to_str(n_diff)//' bitwise differences')
      if (allocated(error)) return
      cfg%method = 'dop853'
      cfg%damping(1:2) = 0.0_dp; cfg%damping_size = 2
      call validate_run_config(cfg, err)
      call check_true(error, .not. allocated(err), 'two links, zero damping refused')
      if (allocated(error)) return
      select type (mdl => cfg%model)
      type is (double_pendulum_t)
      class default
         call check_true(error, .false., 'zero damping: not the double pendulum but the '// &
                         mdl%name())
         return
      end select
      cfg%damping(1:2) = [0.1_dp, 0.0_dp]
      call validate_run_config(cfg, err)
      select type (mdl => cfg%model)
      type is (chain_t)
         call check_true(error, .not. mdl%hamiltonian() .and. .not. mdl%conservative() &
                         .and. mdl%autonomous(), 'damped chain structure queries')
      class default
         call check_true(error, .false., 'damping: not the chain but the '//mdl%name())
      end select
      cfg%damping(1:2) = 0.0_dp
      cfg%support_amplitude = [0.0_dp, 0.01_dp]; cfg%support_frequency = 30.0_dp
      call validate_run_config(cfg, err)
      call check_true(error, .not. cfg%model%autonomous() .and. &
                      .not. cfg%model%conservative(), 'support: autonomous or conservative')
   end subroutine test_bitwise

   !> The chain of n links with masses, lengths and damping of the test cases.
   function damped_chain(n) result(chain)
      integer, intent(in) :: n
      type(chain_t) :: chain
      real(dp), parameter :: m3(3) = [1.0_dp, 0.6_dp, 1.4_dp], l3(3) = [1.0_dp, 0.8_dp, 0.5_dp]
      real(dp), parameter :: c3(3) = [0.05_dp, 0.03_dp, 0.02_dp]
      type(error_t), allocatable :: err
      chain = chain_model(m3(1:n), l3(1:n), 9.81_dp, err, damping=c3(1:n))
      if (allocated(err)) error stop 'test_damping: chain refused'
   end function damped_chain

   !> Roots of M s² + C s + K = 0 by dgeev against σ, ω measured by Prony's
   !> recurrence on runs started on each mode (amplitude 3e-5 rad), N = 1, 2, 3.
   subroutine test_modes(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      real(dp) :: mm(3, 3), kk(3, 3), cc(3, 3), a(6, 6), wr(6), wi(6), vl(1, 1), vr(6, 6)
      real(dp) :: work(200), rhs(3, 6), qeq(3), x0(3), v0(3), sig, om, sig_m, om_m, d_sig, d_om, amp
      complex(dp) :: zv(6)
      integer :: n, m, i, j, info, ipiv(3), comp
      character(len=:), allocatable :: text
      d_sig = 0.0_dp; d_om = 0.0_dp
      text = ''
      do n = 1, 3
         m = 2*n
         chain = damped_chain(n)
         qeq(1:n) = -0.5_dp*pi
         mm(1:n, 1:n) = chain%mass_matrix(qeq(1:n))
         ! K = ∂²V/∂q² = diag(G_i) at the hanging equilibrium, C from the c_i
         kk = 0.0_dp; cc = 0.0_dp
         do i = 1, n
            kk(i, i) = chain%gl(i)
            cc(i, i) = chain%c(i)
            if (i < n) then
               cc(i, i) = cc(i, i) + chain%c(i + 1)
               cc(i, i + 1) = -chain%c(i + 1); cc(i + 1, i) = -chain%c(i + 1)
            end if
         end do
         ! companion matrix [0 I; −M⁻¹K −M⁻¹C]
         a = 0.0_dp
         a(n + 1:m, 1:n) = -kk(1:n, 1:n)
         a(n + 1:m, n + 1:m) = -cc(1:n, 1:n)
         rhs(1:n, 1:m) = a(n + 1:m, 1:m)
         call dgesv(n, m, mm, 3, ipiv, rhs, 3, info)
         a(n + 1:m, 1:m) = rhs(1:n, 1:m)
         call check_true(error, info == 0, 'dgesv info '//to_str(info))
         if (allocated(error)) return
         do i = 1, n
            a(i, n + i) = 1.0_dp
         end do
         call dgeev('N', 'V', m, a, 6, wr, wi, vl, 1, vr, 6, work, size(work), info)
         call check_true(error, info == 0, 'dgeev info '//to_str(info))
         if (allocated(error)) return
         text = text//' N='//to_str(n)//':'
         do j = 1, m
            if (.not. wi(j) > 0.0_dp) cycle   ! one of each pair (all underdamped here)
            sig = -wr(j); om = wi(j)
            ! start on Re(w), w = v e^(iθ) with w_comp = |v_comp| real, comp the largest
            ! |v_q|: x = amp Re(w_q), ẋ = amp Re(w_q̇), amplitude of x_comp 3e-5 rad
            do i = 1, m
               zv(i) = cmplx(vr(i, j), vr(i, j + 1), dp)
            end do
            comp = maxloc(abs(zv(1:n)), 1)
            zv(1:m) = zv(1:m)*conjg(zv(comp))/abs(zv(comp))
            amp = 3e-5_dp/abs(zv(comp))
            x0(1:n) = amp*real(zv(1:n)); v0(1:n) = amp*real(zv(n + 1:m))
            call measure(chain, qeq(1:n) + x0(1:n), v0(1:n), comp, 2.0_dp*pi/om, sig_m, om_m)
            d_sig = max(d_sig, abs(sig_m - sig)/sig)
            d_om = max(d_om, abs(om_m - om)/om)
            text = text//' '//real_str(sig, 6)//'+-'//real_str(om, 8)//'i'
         end do
      end do
      call report('-s = sigma +- i omega (dgeev)'//text//'; max rel diff measured - eigen: '// &
                  'sigma '//real_str(d_sig, 2)//', omega '//real_str(d_om, 2))
      call check(error, d_sig, 0.0_dp, 'decay rates, max rel diff', abs=1e-6_dp)
      call check(error, d_om, 0.0_dp, 'frequencies, max rel diff', abs=1e-6_dp)
   end subroutine test_modes

   !> σ, ω of the coordinate `comp` sampled every τ = period/8 over four periods
   !> (dop853, rtol 1e-13), by least squares on x_(k+2) = a x_(k+1) − b x_k.
   subroutine measure(chain, q0, w0, comp, period, sig, om)
      type(chain_t), intent(in) :: chain
      real(dp), intent(in) :: q0(:), w0(:), period
      integer, intent(in) :: comp
      real(dp), intent(out) :: sig, om
      integer, parameter :: ns = 33
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      real(dp) :: y(2*size(q0)), x(ns), t, h, tau, s11, s12, s22, r1, r2, det, aa, bb
      integer :: k, stat, n
      n = size(q0)
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-13_dp, &
                          atol=1e-18_dp))
      y = [q0, w0]
      t = 0.0_dp; h = 0.0_dp
      tau = period/8.0_dp
      x(1) = y(comp) + 0.5_dp*pi
      do k = 2, ns
         call advance_to(integ, chain, t, y, real(k - 1, dp)*tau, h, stat)
         if (stat /= stat_ok) error stop 'test_damping: integration failed'
         x(k) = y(comp) + 0.5_dp*pi
      end do
      ! normal equations of min Σ (x_(k+2) − a x_(k+1) + b x_k)²
      s11 = 0.0_dp; s12 = 0.0_dp; s22 = 0.0_dp; r1 = 0.0_dp; r2 = 0.0_dp
      do k = 1, ns - 2
         s11 = s11 + x(k + 1)**2
         s12 = s12 - x(k + 1)*x(k)
         s22 = s22 + x(k)**2
         r1 = r1 + x(k + 2)*x(k + 1)
         r2 = r2 - x(k + 2)*x(k)
      end do
      det = s11*s22 - s12**2
      aa = (r1*s22 - r2*s12)/det
      bb = (s11*r2 - s12*r1)/det
      sig = -log(bb)/(2.0_dp*tau)
      om = acos(aa/(2.0_dp*sqrt(bb)))/tau
   end subroutine measure

   !> dop853 (rtol 1e-12, atol 1e-14) over 100 s on the work-augmented chain (N = 2, 3):
   !> max over the run of |E(t) − E(0) + W_friction − W_support| / energy_scale.
   subroutine test_balance(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: text
      real(dp) :: worst, b, wf, ws
      integer :: kind, n
      character(len=*), parameter :: names(3) = &
         [character(len=17) :: 'damped', 'forced', 'damped and forced']
      worst = 0.0_dp
      text = ''
      do kind = 1, 3
         do n = 2, 3
            call balance(n, kind, b, wf, ws)
            worst = max(worst, b)
            text = text//' '//trim(names(kind))//' N='//to_str(n)//' '//real_str(b, 2)// &
                   ' (W_f '//real_str(wf, 3)//' J, W_s '//real_str(ws, 3)//' J);'
         end do
      end do
      call report('energy balance, dop853 rtol 1e-12, 100 s, max rel error:'//text)
      call check(error, worst, 0.0_dp, 'energy balance error', abs=1e-10_dp)
   end subroutine test_balance

   !> One balance run: kind 1 damped, 2 forced (support a = (0.01, 0.02) m, ω = 10
   !> rad/s), 3 both; from q = −π/2 + (0.4, −0.3, 0.2), at rest.
   subroutine balance(n, kind, worst, wf, ws)
      integer, intent(in) :: n, kind
      real(dp), intent(out) :: worst, wf, ws
      type(work_model_t) :: wm
      type(error_t), allocatable :: err
      class(integrator_t), allocatable :: integ
      real(dp) :: y(2*n + 2), t, h, e0, scale, c(n)
      real(dp), parameter :: dq(3) = [0.4_dp, -0.3_dp, 0.2_dp]
      integer :: k, stat, i
      c = 0.0_dp
      if (kind /= 2) c = [(0.08_dp/i, i = 1, n)]
      if (kind == 1) then
         wm%chain = chain_model([(1.0_dp, i = 1, n)], [(1.0_dp, i = 1, n)], 9.81_dp, err, &
                                damping=c)
      else
         wm%chain = chain_model([(1.0_dp, i = 1, n)], [(1.0_dp, i = 1, n)], 9.81_dp, err, &
                                damping=c, amplitude=[0.01_dp, 0.02_dp], frequency=10.0_dp, &
                                phase=[0.5_dp, 0.0_dp])
      end if
      if (allocated(err)) error stop 'test_damping: chain refused'
      call new_integrator('dop853', integ, err, method_options_t(rtol=1e-12_dp, &
                          atol=1e-14_dp))
      y = 0.0_dp
      y(1:n) = -0.5_dp*pi + dq(1:n)
      e0 = wm%energy(0.0_dp, y)
      scale = wm%energy_scale(e0)
      t = 0.0_dp; h = 0.0_dp; worst = 0.0_dp
      do k = 1, 100
         call advance_to(integ, wm, t, y, real(k, dp), h, stat)
         if (stat /= stat_ok) error stop 'test_damping: integration failed'
         worst = max(worst, abs(wm%energy(t, y) - e0 + y(n + 1) - y(2*n + 2))/scale)
      end do
      wf = y(n + 1); ws = y(2*n + 2)
   end subroutine balance

   !> The damped chain on a moving support, N = 1, 2, 3, at states and times of a
   !> fixed sequence: Jacobian and energy gradient against central differences;
   !> F_(0,1) · v_A from `reactions` against P_support of `powers`; P_friction ≥ 0.
   subroutine test_derivatives(error)
      type(error_t), allocatable, intent(out) :: error
      type(chain_t) :: chain
      type(error_t), allocatable :: err
      real(dp) :: y(6), yp(6), ym(6), fp(6), fm(6), f(6), jac(6, 6), jfd(6, 6), g(6), gfd(6)
      real(dp) :: t, dx, s, d(3), r(2, 3), ra(2), va(2), aa(2), pf, ps
      integer :: n, m, k, i
      d = 0.0_dp
      s = 0.41_dp
      do n = 1, 3
         m = 2*n
         chain = chain_model([(0.5_dp + 0.3_dp*i, i = 1, n)], [(1.2_dp - 0.2_dp*i, i = 1, n)], &
                             9.81_dp, err, damping=[(0.1_dp*i, i = 1, n)], &
                             amplitude=[0.05_dp, 0.1_dp], frequency=7.0_dp, &
                             phase=[0.2_dp, -0.4_dp])
         do k = 1, 20
            do i = 1, m
               s = mod(s*7.31_dp + 0.17_dp, 1.0_dp)
               y(i) = 4.0_dp*s - 2.0_dp
            end do
            t = 0.37_dp*k
            call chain%jacobian(t, y(1:m), jac(1:m, 1:m))
            call chain%energy_gradient(t, y(1:m), g(1:m))
            do i = 1, m
               dx = 1e-6_dp*max(1.0_dp, abs(y(i)))
               yp(1:m) = y(1:m); ym(1:m) = y(1:m)
               yp(i) = y(i) + dx; ym(i) = y(i) - dx
               call chain%field(t, yp(1:m), fp(1:m))
               call chain%field(t, ym(1:m), fm(1:m))
               jfd(1:m, i) = (fp(1:m) - fm(1:m))/(2.0_dp*dx)
               gfd(i) = (chain%energy(t, yp(1:m)) - chain%energy(t, ym(1:m)))/(2.0_dp*dx)
            end do
            d(1) = max(d(1), maxval(abs(jac(1:m, 1:m) - jfd(1:m, 1:m))) &
                       /maxval(abs(jfd(1:m, 1:m))))
            d(2) = max(d(2), maxval(abs(g(1:m) - gfd(1:m)))/maxval(abs(gfd(1:m))))
            call chain%field(t, y(1:m), f(1:m))
            call chain%reactions(y(1:n), y(n + 1:m), f(n + 1:m), r(:, 1:n), t)
            call chain%support(t, ra, va, aa)
            call chain%powers(t, y(1:m), f(n + 1:m), pf, ps)
            d(3) = max(d(3), abs(dot_product(r(:, 1), va) - ps)/max(1.0_dp, abs(ps)))
            call check_true(error, pf >= 0.0_dp, 'P_friction < 0')
            if (allocated(error)) return
         end do
      end do
      call report('damped driven chain, central differences max rel diff: jacobian '// &
                  real_str(d(1), 2)//', energy gradient '//real_str(d(2), 2)// &
                  '; F01.vA vs P_support '//real_str(d(3), 2))
      call check(error, maxval(d(1:2)), 0.0_dp, 'derivatives vs central differences', &
                 abs=1e-7_dp)
      call check(error, d(3), 0.0_dp, 'F01 . v_A = P_support', abs=1e-12_dp)
   end subroutine test_derivatives

   !> The methods that need a Hamiltonian (the registry's `hamiltonian` flag: verlet,
   !> its compositions, Tao's) refuse the damped chain with one line naming it and the
   !> methods that accept it; the others (the explicit Runge–Kutta and the Gauss
   !> methods) accept it (and the driven chain).
   subroutine test_refuse(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(run_config_t) :: cfg
      character(len=:), allocatable :: name, tail
      integer :: i, k
      logical :: reported
      call check_true(error, any(method_table%hamiltonian) .and. &
                      .not. all(method_table%hamiltonian), 'methods that refuse and accept')
      if (allocated(error)) return
      tail = ' needs a Hamiltonian model; the damped chain of 2 links is not (use ' &
             //field_method_names()//')'
      reported = .false.
      do i = 1, n_methods
         name = trim(method_table(i)%name)
         if (.not. method_table(i)%hamiltonian) cycle
         cfg%method = name
         cfg%damping(1:2) = [0.1_dp, 0.05_dp]; cfg%damping_size = 2
         call validate_run_config(cfg, err)
         call check_true(error, allocated(err), name//' accepted the damped chain')
         if (allocated(error)) return
         if (.not. reported) call report(name//': '//err%message)
         reported = .true.
         call check_true(error, err%message == 'invalid method: '//name//tail, err%message)
         if (allocated(error)) return
      end do
      do i = 1, n_methods
         name = trim(method_table(i)%name)
         if (method_table(i)%hamiltonian) cycle
         do k = 1, 2
            cfg%method = name
            cfg%damping(1:2) = [0.1_dp, 0.05_dp]; cfg%damping_size = 2
            if (k == 2) then   ! driven, not damped
               cfg%damping(1:2) = 0.0_dp
               cfg%support_amplitude = [0.0_dp, 0.01_dp]; cfg%support_frequency = 30.0_dp
            end if
            call validate_run_config(cfg, err)
            call check_true(error, .not. allocated(err), name// &
                            ' refused the damped or driven chain')
            if (allocated(error)) return
            cfg%support_amplitude = 0.0_dp
         end do
      end do
   end subroutine test_refuse
end module test_damping
