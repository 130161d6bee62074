!> Kapitza's pendulum (docs/kapitza.md): the compound pendulum (one uniform
!> rod, N = 1) upside down on a vertically vibrating pin y_A = a cos ω t, against
!> independently known values:
!> - the transition curve of Mathieu's equation x'' + (δ + ε cos τ) x = 0 through
!>   δ = 0, quoted in docs/kapitza.md from DLMF 28.6.1 (a_0(q) with a = 4δ, q = −2ε):
!>   δ_c = −ε²/2 + 7ε⁴/32 − 29ε⁶/144 + 68687ε⁸/294912 + …, against the δ at which the
!>   trace of dpend's monodromy matrix is 2: the rod upright on the pin vibrating
!>   with ω = 1 rad/s is Mathieu's equation in τ = t with δ = −k g, ε = k a
!>   (k = 3/(2L)); dpend's chain model, dop853 run and tangent propagation
!>   (`dpend_tangent`, the Lyapunov machinery) give the monodromy matrix over one
!>   period. Two independent checks of that trace: a plain RK4 of Mathieu's
!>   equation in this file, and central differences of dpend's nonlinear runs;
!> - the threshold amplitude of the inverted position, located by bisection on
!>   simulated runs of the chain (rk4, 64 steps per period of the pin; stable: the
!>   angle from the upward vertical stays below 0.5 rad for 60 s) against the derived
!>   a_c: Kapitza's a² ω² = (4/3) g L, and with the Mathieu and finite-angle
!>   corrections of docs/kapitza.md.
!> Each test prints its measured figures on one line ('    kapitza: …').
module test_kapitza
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_integrator, only: integrator_t, stat_ok
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: advance_to, march_t
   use dpend_tangent, only: tangent_t
   use dpend_cli, only: real_str, to_str
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_kapitza

   real(dp), parameter :: pi = acos(-1.0_dp)
   !> The case of docs/kapitza.md: L = 1 m, m = 1 kg, g = 9.81 m/s², ω such that
   !> Kapitza's threshold is a = 0.01 L; start φ0 = 0.05 rad from upright, at rest.
   real(dp), parameter :: len_rod = 1.0_dp, grav = 9.81_dp, phi0 = 0.05_dp
   real(dp), parameter :: omega = sqrt(4.0_dp*grav/(3.0_dp*len_rod))/0.01_dp
   !> Classification: fallen once |φ| > phi_fall; stable if not within t_run.
   real(dp), parameter :: phi_fall = 0.5_dp, t_run = 60.0_dp
   integer, parameter :: steps_per_period = 64

contains

   subroutine collect_kapitza(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('mathieu_transition_curve', test_mathieu), &
               new_unittest('inverted_threshold_bisection', test_threshold)]
   end subroutine collect_kapitza

   subroutine report(text)
      character(len=*), intent(in) :: text
      write (output_unit, '(a)') '    kapitza: '//text
   end subroutine report

   !> δ_c(ε) of the series (terms up to ε^(2 nterms)).
   pure function delta_series(eps, nterms) result(d)
      real(dp), intent(in) :: eps
      integer, intent(in) :: nterms
      real(dp) :: d
      real(dp), parameter :: coef(4) = [-0.5_dp, 7.0_dp/32.0_dp, -29.0_dp/144.0_dp, &
                                        68687.0_dp/294912.0_dp]
      integer :: i
      d = 0.0_dp
      do i = 1, nterms
         d = d + coef(i)*eps**(2*i)
      end do
   end function delta_series

   !> Trace of the monodromy matrix of x'' + (δ + ε cos τ) x = 0 over [0, 2π] from
   !> dpend: the compound rod (m = 1 kg, L = len_rod) upright on the pin
   !> y_A = a cos t (ω = 1 rad/s) with g = −δ/k, a = ε/k, k = 3/(2L), run by dop853
   !> (rtol 1e-13) from the upright state, its tangent vectors (identity at t = 0)
   !> propagated by `tangent_t` with RK4 substeps of about 2π/4096 s (θ = 5e-4).
   function dpend_trace(delta, eps) result(tr)
      real(dp), intent(in) :: delta, eps
      real(dp) :: tr
      type(chain_t) :: chain
      type(march_t) :: march
      type(tangent_t) :: tan
      class(integrator_t), allocatable :: integ
      real(dp) :: y(2), t, h, eye(2, 2)
      integer :: stat
      call dpend_setup(delta, eps, chain, integ)
      eye = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
      tan%theta = 5e-4_dp
      call tan%init(eye)
      y = [0.5_dp*pi, 0.0_dp]
      t = 0.0_dp; h = 0.0_dp
      call integ%clear_step()
      call march%start(integ, t, 2.0_dp*pi, h)
      do while (.not. march%finished)
         call march%next(integ, chain, t, y, h, stat)
         if (stat /= stat_ok) error stop 'test_kapitza: dop853 failed'
         call tan%propagate(integ, chain)
         if (tan%too_stiff .or. tan%too_large) error stop 'test_kapitza: tangent failed'
      end do
      tr = tan%v(1, 1) + tan%v(2, 2)
   end function dpend_trace

   !> The same trace from dpend's nonlinear runs alone: the monodromy matrix by
   !> central differences (±s = 1e-5 rad or rad/s about upright) of four dop853 runs
   !> over [0, 2π] s (error O(s²) ≈ 1e-10, roundoff ≈ rtol/s ≈ 1e-8).
   function dpend_trace_runs(delta, eps) result(tr)
      real(dp), intent(in) :: delta, eps
      real(dp) :: tr
      real(dp), parameter :: s = 1e-5_dp
      type(chain_t) :: chain
      class(integrator_t), allocatable :: integ
      real(dp) :: yp(2), ym(2), d(2)
      integer :: i
      call dpend_setup(delta, eps, chain, integ)
      tr = 0.0_dp
      do i = 1, 2
         d = 0.0_dp; d(i) = s
         yp = run(d); ym = run(-d)
         tr = tr + (yp(i) - ym(i))/(2.0_dp*s)
      end do
   contains
      function run(dy) result(y)
         real(dp), intent(in) :: dy(2)
         real(dp) :: y(2), t, h
         integer :: stat
         y = [0.5_dp*pi, 0.0_dp] + dy
         t = 0.0_dp; h = 0.0_dp
         call integ%clear_step()
         call advance_to(integ, chain, t, y, 2.0_dp*pi, h, stat)
         if (stat /= stat_ok) error stop 'test_kapitza: dop853 run failed'
      end function run
   end function dpend_trace_runs

   !> dpend's chain for Mathieu's (δ, ε) (see `dpend_trace`) and dop853.
   subroutine dpend_setup(delta, eps, chain, integ)
      real(dp), intent(in) :: delta, eps
      type(chain_t), intent(out) :: chain
      class(integrator_t), allocatable, intent(out) :: integ
      type(error_t), allocatable :: err
      real(dp) :: k
      k = 1.5_dp/len_rod
      chain = chain_model([1.0_dp], [len_rod], -delta/k, err, amplitude=[0.0_dp, eps/k], &
                          frequency=1.0_dp)
      if (allocated(err)) error stop 'test_kapitza: chain refused'
      call new_integrator('dop853', integ, err, &
                          method_options_t(rtol=1e-13_dp, atol=1e-15_dp))
      if (allocated(err)) error stop 'test_kapitza: method refused'
   end subroutine dpend_setup

   !> Trace of the monodromy matrix of x'' + (δ + ε cos τ) x = 0 over [0, 2π]
   !> (classical RK4, nstep steps): this file's own, independent of dpend.
   pure function mathieu_trace(delta, eps, nstep) result(tr)
      real(dp), intent(in) :: delta, eps
      integer, intent(in) :: nstep
      real(dp) :: tr
      real(dp) :: y(4), k1(4), k2(4), k3(4), k4(4), h, tau
      integer :: i
      y = [1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]   ! (x1, x1', x2, x2')
      h = 2.0_dp*pi/real(nstep, dp)
      do i = 0, nstep - 1
         tau = real(i, dp)*h
         k1 = rhs(tau, y)
         k2 = rhs(tau + 0.5_dp*h, y + 0.5_dp*h*k1)
         k3 = rhs(tau + 0.5_dp*h, y + 0.5_dp*h*k2)
         k4 = rhs(tau + h, y + h*k3)
         y = y + h/6.0_dp*(k1 + 2.0_dp*k2 + 2.0_dp*k3 + k4)
      end do
      tr = y(1) + y(4)
   contains
      pure function rhs(s, z) result(f)
         real(dp), intent(in) :: s, z(4)
         real(dp) :: f(4), w
         w = delta + eps*cos(s)
         f = [z(2), -w*z(1), z(4), -w*z(3)]
      end function rhs
   end function mathieu_trace

   !> The transition curve through δ = 0 by bisection on dpend's trace = 2 (unstable
   !> below, trace > 2; stable above; g >= 1e-6 m/s² keeps δ <= −1.5e-6) for ε = 0.1
   !> and 0.2: the series with n = 1 … 4 terms differs from it by O(ε^(2n+2)) if its
   !> coefficients are right and dpend's model and runs are (a wrong n-th coefficient,
   !> or a wrong support term, leaves O(ε^(2n)) or worse), so that log2 of the ratio
   !> of the differences at ε = 0.2 and 0.1 must be 2n + 2 (within 0.2). dpend's
   !> trace is checked first against this file's RK4 of Mathieu's equation (measured
   !> difference 3.2e-14 at δ = −0.004, ε = 0.1, debug and release; bound 3e-13), and at
   !> δ_c(0.2) against dpend's nonlinear runs (measured |trace − 2| 1.6e-9 debug,
   !> 1.7e-9 release; bound 1e-8).
   subroutine test_mathieu(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp), parameter :: epss(2) = [0.1_dp, 0.2_dp]
      real(dp) :: eps, lo, hi, mid, dnum(2), diff(4, 2), order(4), tr_dpend, tr_rk4, tr_runs
      character(len=:), allocatable :: text
      integer :: j, it, nt
      text = ''
      tr_dpend = dpend_trace(-0.004_dp, 0.1_dp)
      tr_rk4 = mathieu_trace(-0.004_dp, 0.1_dp, 4096)
      call report('monodromy trace at delta -0.004, eps 0.1: dpend '// &
                  real_str(tr_dpend, 15)//', RK4 of Mathieu '//real_str(tr_rk4, 15)// &
                  ', diff '//real_str(tr_dpend - tr_rk4, 2))
      call check(error, tr_dpend, tr_rk4, 'dpend monodromy trace vs RK4 of Mathieu', &
                 abs=3e-13_dp)
      if (allocated(error)) return
      do j = 1, size(epss)
         eps = epss(j)
         lo = -eps**2; hi = -1e-5_dp      ! trace > 2 at lo, < 2 at hi
         call check_true(error, dpend_trace(lo, eps) > 2.0_dp .and. &
                         dpend_trace(hi, eps) < 2.0_dp, 'no bracket at eps = '// &
                         real_str(eps))
         if (allocated(error)) return
         do it = 1, 50
            mid = 0.5_dp*(lo + hi)
            if (dpend_trace(mid, eps) > 2.0_dp) then
               lo = mid
            else
               hi = mid
            end if
         end do
         dnum(j) = 0.5_dp*(lo + hi)
         do nt = 1, 4
            diff(nt, j) = abs(dnum(j) - delta_series(eps, nt))
         end do
         text = text//' eps='//real_str(eps, 2)//': delta_c '//real_str(dnum(j), 12)// &
                ', |series - delta_c| 1..4 terms '//real_str(diff(1, j), 2)//' '// &
                real_str(diff(2, j), 2)//' '//real_str(diff(3, j), 2)//' '// &
                real_str(diff(4, j), 2)//';'
      end do
      tr_runs = dpend_trace_runs(dnum(2), epss(2))
      call report('trace from nonlinear runs at delta_c(0.2): '//real_str(tr_runs, 12)// &
                  ', minus 2: '//real_str(tr_runs - 2.0_dp, 2))
      call check(error, tr_runs, 2.0_dp, 'trace of the runs at delta_c(0.2)', abs=1e-8_dp)
      order = log(diff(:, 2)/diff(:, 1))/log(2.0_dp)
      call report('Mathieu transition curve (dpend monodromy, bisection):'//text// &
                  ' orders of the remainders '//real_str(order(1), 3)//' '// &
                  real_str(order(2), 3)//' '//real_str(order(3), 3)//' '//real_str(order(4), 3))
      call check(error, order, [4.0_dp, 6.0_dp, 8.0_dp, 10.0_dp], &
                 'order of the remainder of the series', abs=0.2_dp)
   end subroutine test_mathieu

   !> Whether the compound pendulum (m = 1 kg, L = len_rod) on the pin
   !> y_A = a cos ω t, started phi_start from upright at rest, stays within phi_fall
   !> of upright until t_end (checked once per period of the pin), integrated by
   !> `method` (fixed: steps_per_period steps a period; adaptive: rtol 1e-10).
   logical function stays_up(a, t_end, phi_start, method) result(up)
      real(dp), intent(in) :: a, t_end, phi_start
      character(len=*), intent(in) :: method
      type(chain_t) :: chain
      type(error_t), allocatable :: err
      class(integrator_t), allocatable :: integ
      real(dp) :: y(2), t, h, period
      integer :: k, stat
      chain = chain_model([1.0_dp], [len_rod], grav, err, amplitude=[0.0_dp, a], &
                          frequency=omega)
      if (allocated(err)) error stop 'test_kapitza: chain refused'
      call new_integrator(method, integ, err, &
                          method_options_t(rtol=1e-10_dp, atol=1e-12_dp))
      if (allocated(err)) error stop 'test_kapitza: method refused'
      period = 2.0_dp*pi/omega
      y = [0.5_dp*pi + phi_start, 0.0_dp]
      t = 0.0_dp
      up = .true.
      do k = 1, ceiling(t_end/period)
         h = period/real(steps_per_period, dp)
         call advance_to(integ, chain, t, y, real(k, dp)*period, h, stat)
         if (stat /= stat_ok) error stop 'test_kapitza: integration failed'
         if (abs(y(1) - 0.5_dp*pi) > phi_fall) then
            up = .false.
            return
         end if
      end do
   end function stays_up

   !> The threshold amplitude by bisection on [0.005, 0.02] m down to 1e-4
   !> relative, against Kapitza's a_c = sqrt(4 g L/3)/ω = 0.01 m (within 5 %, the
   !> required bound) and the corrected a_c of docs/kapitza.md (Mathieu's ε⁴ term and
   !> the start angle: a_c (1 + 7Δ/16) (1 + φ0²/4), Δ = k g/ω², k = 3/(2L)).
   subroutine test_threshold(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: a_sim, a_kap, a_cor, k, delta
      integer :: runs
      k = 1.5_dp/len_rod
      delta = k*grav/omega**2
      a_kap = sqrt(4.0_dp*grav*len_rod/3.0_dp)/omega
      a_cor = a_kap*(1.0_dp + 7.0_dp*delta/16.0_dp)*(1.0_dp + 0.25_dp*phi0**2)
      call bisect(t_run, phi0, 'rk4', a_sim, runs, error)
      if (allocated(error)) return
      call report('omega '//real_str(omega, 8)//' rad/s, phi0 '//real_str(phi0)// &
                  ' rad, '//to_str(runs)//' runs of '//real_str(t_run)//' s: a_sim '// &
                  real_str(a_sim, 6)//' m; Kapitza a_c '//real_str(a_kap, 6)// &
                  ' m (rel diff '//real_str((a_sim - a_kap)/a_kap, 2)//'), corrected '// &
                  real_str(a_cor, 6)//' m (rel diff '//real_str((a_sim - a_cor)/a_cor, 2)//')')
      call check(error, a_sim, a_kap, 'simulated vs Kapitza threshold', rel=0.05_dp)
      call check(error, a_sim, a_cor, 'simulated vs corrected threshold', rel=2e-4_dp)
   end subroutine test_threshold

   !> The threshold amplitude a_sim by bisection on [0.005, 0.02] m down to 1e-4
   !> relative (runs: the simulations taken); error if the ends are not one falling,
   !> one staying up.
   subroutine bisect(t_end, phi_start, method, a_sim, runs, error)
      real(dp), intent(in) :: t_end, phi_start
      character(len=*), intent(in) :: method
      real(dp), intent(out) :: a_sim
      integer, intent(out) :: runs
      type(error_t), allocatable, intent(inout) :: error
      real(dp) :: lo, hi, mid
      lo = 0.005_dp; hi = 0.02_dp
      a_sim = 0.0_dp
      call check_true(error, .not. stays_up(lo, t_end, phi_start, method), &
                      'a = 0.005 m stays up')
      call check_true(error, stays_up(hi, t_end, phi_start, method), 'a = 0.02 m falls')
      runs = 2
      if (allocated(error)) return
      do while (hi - lo > 1e-4_dp*lo)
         mid = 0.5_dp*(lo + hi)
         if (stays_up(mid, t_end, phi_start, method)) then
            hi = mid
         else
            lo = mid
         end if
         runs = runs + 1
      end do
      a_sim = 0.5_dp*(lo + hi)
   end subroutine bisect
end module test_kapitza
