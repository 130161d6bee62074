!> Model, kinematics and reactions against independently known values.
module test_model
   use dpend_kinds, only: dp
   use dpend_pendulum
   use dpend_pendulum, only: kinematics_t, kinematics
   use dpend_pendulum, only: reactions
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_model, random_pendulum, random_state

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_model(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('newton_euler_equals_lagrange', test_ne_lagrange), &
               new_unittest('kinematics_finite_differences', test_kinematics_fd), &
               new_unittest('static_equilibrium_reactions', test_static), &
               new_unittest('horizontal_release_closed_form', test_release), &
               new_unittest('hamiltonian_gradients_fd', test_dh), &
               new_unittest('hamiltonian_equals_energy', test_h_energy), &
               new_unittest('reactions_balance_momentum', test_momentum_balance), &
               new_unittest('invalid_parameters_rejected', test_validate), &
               new_unittest('jacobians_finite_differences', test_jacobians), &
               new_unittest('jacobian_qp_hamiltonian', test_jacobian_hamiltonian), &
               new_unittest('sin_cos_near_matches_direct', test_sin_cos_near)]
   end subroutine collect_model

   !> Random parameters in [0.2, 5] (masses, lengths) and g in [1, 20].
   function random_pendulum() result(par)
      type(pendulum_t) :: par
      real(dp) :: r(5)
      call random_number(r)
      par = pendulum_t(m1=0.2_dp + 4.8_dp*r(1), m2=0.2_dp + 4.8_dp*r(2), &
                       l1=0.2_dp + 4.8_dp*r(3), l2=0.2_dp + 4.8_dp*r(4), g=1.0_dp + 19.0_dp*r(5))
   end function random_pendulum

   !> Random angles in [-2π, 2π] and velocities in [-10, 10] rad/s.
   subroutine random_state(q, qd)
      real(dp), intent(out) :: q(2), qd(2)
      call random_number(q); call random_number(qd)
      q = 4.0_dp*pi*(q - 0.5_dp)
      qd = 20.0_dp*(qd - 0.5_dp)
   end subroutine random_state

   subroutine seed()
      integer :: n, i
      call random_seed(size=n)
      call random_seed(put=[(1234567 + 97*i, i=1, n)])
   end subroutine seed

   subroutine test_ne_lagrange(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), a(2), b(2), scale
      integer :: i
      call seed()
      do i = 1, 200
         par = random_pendulum()
         call random_state(q, qd)
         a = qddot_newton_euler(par, q, qd)
         b = qddot_lagrange(par, q, qd)
         scale = maxval(abs(b))
         call check(error, a, b, 'NE vs Lagrange', rel=1e-12_dp, abs=1e-12_dp*scale)
         if (allocated(error)) return
      end do
   end subroutine test_ne_lagrange

   !> Velocities and accelerations equal 4th-order central differences of positions
   !> along the path q(t) = q0 + q̇0 t + q̈0 t²/2.
   subroutine test_kinematics_fd(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(kinematics_t) :: k0, km2, km1, kp1, kp2
      real(dp) :: q(2), qd(2), qdd(2), h
      integer :: i
      call seed()
      h = 1e-3_dp
      do i = 1, 20
         par = random_pendulum()
         call random_state(q, qd)
         call random_number(qdd); qdd = 40.0_dp*(qdd - 0.5_dp)
         k0 = kinematics(par, q, qd, qdd)
         km2 = at(-2*h); km1 = at(-h); kp1 = at(h); kp2 = at(2*h)
         call check(error, d1(km2%rc1, km1%rc1, kp1%rc1, kp2%rc1), k0%vc1, 'vC1', abs=1e-7_dp)
         call check(error, d1(km2%rc2, km1%rc2, kp1%rc2, kp2%rc2), k0%vc2, 'vC2', abs=1e-7_dp)
         call check(error, d1(km2%rb, km1%rb, kp1%rb, kp2%rb), k0%vb, 'vB', abs=1e-7_dp)
         call check(error, d2(km2%rc1, km1%rc1, k0%rc1, kp1%rc1, kp2%rc1), k0%ac1, 'aC1', &
                    abs=1e-5_dp)
         call check(error, d2(km2%rc2, km1%rc2, k0%rc2, kp1%rc2, kp2%rc2), k0%ac2, 'aC2', &
                    abs=1e-5_dp)
         call check(error, d2(km2%rb, km1%rb, k0%rb, kp1%rb, kp2%rb), k0%ab, 'aB', abs=1e-5_dp)
         ! the chapter's explicit component formulas (6.2, 6.4)
         call check(error, k0%rc1, 0.5_dp*par%l1*[cos(q(1)), sin(q(1))], 'rC1 (6.2)', &
                    abs=1e-14_dp)
         call check(error, k0%rc2, par%l1*[cos(q(1)), sin(q(1))] &
                    + 0.5_dp*par%l2*[cos(q(2)), sin(q(2))], 'rC2 (6.4)', abs=1e-13_dp)
         if (allocated(error)) return
      end do
   contains
      function at(t) result(k)
         real(dp), intent(in) :: t
         type(kinematics_t) :: k
         k = kinematics(par, q + qd*t + 0.5_dp*qdd*t*t, qd, qdd)
      end function at
      function d1(rm2, rm1, rp1, rp2) result(v)
         real(dp), intent(in) :: rm2(2), rm1(2), rp1(2), rp2(2)
         real(dp) :: v(2)
         v = (rm2 - 8.0_dp*rm1 + 8.0_dp*rp1 - rp2)/(12.0_dp*h)
      end function d1
      function d2(rm2, rm1, r0, rp1, rp2) result(a)
         real(dp), intent(in) :: rm2(2), rm1(2), r0(2), rp1(2), rp2(2)
         real(dp) :: a(2)
         a = (-rm2 + 16.0_dp*rm1 - 30.0_dp*r0 + 16.0_dp*rp1 - rp2)/(12.0_dp*h*h)
      end function d2
   end subroutine test_kinematics_fd

   !> Hanging at rest: q̈ = 0, F01 = (0, (m1+m2) g), F21 = (0, -m2 g).
   subroutine test_static(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qdd(2), f01(2), f21(2)
      integer :: i
      call seed()
      do i = 1, 10
         par = random_pendulum()
         q = [-0.5_dp*pi, -0.5_dp*pi]
         qdd = qddot(par, q, [0.0_dp, 0.0_dp])
         call check(error, qdd, [0.0_dp, 0.0_dp], 'qdd at equilibrium', abs=1e-13_dp*par%g)
         call reactions(par, q, [0.0_dp, 0.0_dp], qdd, f01, f21)
         call check(error, f01, [0.0_dp, (par%m1 + par%m2)*par%g], 'F01', abs=1e-12_dp*par%g)
         call check(error, f21, [0.0_dp, -par%m2*par%g], 'F21', abs=1e-12_dp*par%g)
         if (allocated(error)) return
      end do
   end subroutine test_static

   !> Both links horizontal, at rest (docs/physics.md §"Horizontal release"):
   !> q̈1 = -3g(2m1+m2)/(L1(4m1+3m2)), q̈2 = 3 m1 g/(L2(4m1+3m2)),
   !> F21 = (0, -m2(L1 q̈1 + L2 q̈2/2 + g)), F01 = (0, m1(L1 q̈1/2 + g) - F21y).
   subroutine test_release(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: qdd(2), f01(2), f21(2), e1, e2, den
      integer :: i
      ! the chapter's numbers: q̈ = (-9g/7, 3g/7), F21 = (0, g/14), F01 = (0, 2g/7)
      par = pendulum_t()
      qdd = qddot(par, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp])
      call check(error, qdd, [-9.0_dp*9.8_dp/7.0_dp, 3.0_dp*9.8_dp/7.0_dp], 'qdd chapter', &
                 rel=1e-14_dp)
      call reactions(par, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], qdd, f01, f21)
      call check(error, f21, [0.0_dp, 9.8_dp/14.0_dp], 'F21 chapter', abs=1e-14_dp)
      call check(error, f01, [0.0_dp, 2.0_dp*9.8_dp/7.0_dp], 'F01 chapter', abs=1e-14_dp)
      call seed()
      do i = 1, 10
         par = random_pendulum()
         den = 4.0_dp*par%m1 + 3.0_dp*par%m2
         e1 = -3.0_dp*par%g*(2.0_dp*par%m1 + par%m2)/(par%l1*den)
         e2 = 3.0_dp*par%m1*par%g/(par%l2*den)
         qdd = qddot(par, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp])
         call check(error, qdd, [e1, e2], 'qdd release', rel=1e-13_dp)
         call reactions(par, [0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], qdd, f01, f21)
         call check(error, f21(2), -par%m2*(par%l1*e1 + 0.5_dp*par%l2*e2 + par%g), 'F21y', &
                    abs=1e-12_dp*par%m2*par%g)
         call check(error, f01(2), par%m1*(0.5_dp*par%l1*e1 + par%g) - f21(2), 'F01y', &
                    abs=1e-12_dp*(par%m1 + par%m2)*par%g)
         call check(error, [f01(1), f21(1)], [0.0_dp, 0.0_dp], 'x components', abs=1e-12_dp)
         if (allocated(error)) return
      end do
   end subroutine test_release

   !> ∂H/∂q and ∂H/∂p against 4th-order central differences of H.
   subroutine test_dh(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), p(2), e(2), gq(2), gp(2), fq(2), fp(2), h, scale
      integer :: i, j
      call seed()
      do i = 1, 50
         par = random_pendulum()
         call random_state(q, qd)
         p = momenta(par, q, qd)
         gq = dh_dq(par, q, p); gp = dh_dp(par, q, p)
         do j = 1, 2
            e = 0.0_dp; e(j) = 1.0_dp
            h = 1e-3_dp
            fq(j) = fd(q, p, e, [0.0_dp, 0.0_dp])
            h = 1e-3_dp*max(1.0_dp, maxval(abs(p)))
            fp(j) = fd(q, p, [0.0_dp, 0.0_dp], e)
         end do
         scale = abs(hamiltonian(par, q, p)) + 1.0_dp
         call check(error, fq, gq, 'dH/dq', abs=1e-7_dp*scale)
         call check(error, fp, gp, 'dH/dp', abs=1e-7_dp*maxval(abs(gp)) + 1e-9_dp)
         if (allocated(error)) return
      end do
   contains
      real(dp) function fd(q, p, dq, dp_)
         real(dp), intent(in) :: q(2), p(2), dq(2), dp_(2)
         fd = (hamiltonian(par, q - 2*h*dq, p - 2*h*dp_) &
               - 8.0_dp*hamiltonian(par, q - h*dq, p - h*dp_) &
               + 8.0_dp*hamiltonian(par, q + h*dq, p + h*dp_) &
               - hamiltonian(par, q + 2*h*dq, p + 2*h*dp_))/(12.0_dp*h)
      end function fd
   end subroutine test_dh

   !> H(q, M q̇) equals T + V, and the Hamiltonian field reproduces q̈:
   !> ṗ = d/dt (M q̇) = (∂M/∂t) q̇ + M q̈ must equal -∂H/∂q.
   subroutine test_h_energy(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), p(2), f(4), qdd(2), m(2, 2), dm12, pdot(2)
      integer :: i
      call seed()
      do i = 1, 100
         par = random_pendulum()
         call random_state(q, qd)
         p = momenta(par, q, qd)
         call check(error, hamiltonian(par, q, p), energy(par, q, qd), 'H = T + V', &
                    abs=1e-12_dp*(kinetic_energy(par, q, qd) + abs(potential_energy(par, q))))
         f = rhs_qp(par, [q, p])
         call check(error, f(1:2), qd, 'dH/dp = qdot', rel=1e-11_dp, abs=1e-11_dp)
         qdd = qddot(par, q, qd)
         m = mass_matrix(par, q)
         dm12 = -0.5_dp*par%m2*par%l1*par%l2*sin(q(1) - q(2))*(qd(1) - qd(2))
         pdot = matmul(m, qdd) + dm12*[qd(2), qd(1)]
         call check(error, f(3:4), pdot, 'pdot', abs=1e-10_dp*(maxval(abs(pdot)) + 1.0_dp))
         if (allocated(error)) return
      end do
   end subroutine test_h_energy

   !> Newton's second law for the whole system: F01 + G1 + G2 = m1 aC1 + m2 aC2, and the
   !> moment balance of link 2 about C2 (corrected 6.24) and of link 1 about A (6.19).
   subroutine test_momentum_balance(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      type(kinematics_t) :: k
      real(dp) :: q(2), qd(2), qdd(2), f01(2), f21(2), lhs, rhs, s
      integer :: i
      call seed()
      do i = 1, 100
         par = random_pendulum()
         call random_state(q, qd)
         qdd = qddot(par, q, qd)
         call reactions(par, q, qd, qdd, f01, f21)
         k = kinematics(par, q, qd, qdd)
         s = (par%m1 + par%m2)*(par%g + maxval(abs(k%ac2)) + maxval(abs(k%ac1)))
         call check(error, f01 - [0.0_dp, (par%m1 + par%m2)*par%g], &
                    par%m1*k%ac1 + par%m2*k%ac2, 'system momentum', abs=1e-12_dp*s)
         lhs = par%m2*par%l2**2/12.0_dp*qdd(2)
         rhs = 0.5_dp*par%l2*(f21(2)*cos(q(2)) - f21(1)*sin(q(2)))
         call check(error, lhs, rhs, 'link 2 moment about C2', abs=1e-12_dp*s*par%l2)
         lhs = par%m1*par%l1**2/3.0_dp*qdd(1)
         rhs = -par%m1*par%g*0.5_dp*par%l1*cos(q(1)) + f21(2)*par%l1*cos(q(1)) &
               - f21(1)*par%l1*sin(q(1))
         call check(error, lhs, rhs, 'link 1 moment about A', abs=1e-12_dp*s*par%l1)
         if (allocated(error)) return
      end do
   end subroutine test_momentum_balance

   subroutine test_validate(error)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf, ieee_quiet_nan
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: e
      real(dp) :: zero
      zero = 0.0_dp
      call validate(pendulum_t(), e)
      call check_true(error, .not. allocated(e), 'defaults valid')
      call validate(pendulum_t(m1=-1.0_dp), e)
      call check_true(error, allocated(e), 'm1 < 0 rejected')
      if (allocated(e)) call check_true(error, index(e%message, 'm1') > 0, 'names m1')
      call validate(pendulum_t(l2=ieee_value(zero, ieee_quiet_nan)), e)
      call check_true(error, allocated(e), 'NaN l2 rejected')
      call validate(pendulum_t(g=ieee_value(zero, ieee_positive_inf)), e)
      call check_true(error, allocated(e), 'Inf g rejected')
   end subroutine test_validate

   !> Both analytic Jacobians against 4th-order central differences of the fields.
   subroutine test_jacobians(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), y(4), z(4), ja(4, 4), jb(4, 4), e(4), h
      integer :: i, j
      call seed()
      do i = 1, 50
         par = random_pendulum()
         call random_state(q, qd)
         y = [q, qd]
         z = [q, momenta(par, q, qd)]
         ja = jacobian_qqdot(par, y)
         jb = jacobian_qp(par, z)
         do j = 1, 4
            e = 0.0_dp; e(j) = 1.0_dp
            h = 1e-4_dp*max(1.0_dp, abs(y(j)))
            call check(error, ja(:, j), (rhs_qqdot(par, y - 2*h*e) - 8*rhs_qqdot(par, y - h*e) &
                       + 8*rhs_qqdot(par, y + h*e) - rhs_qqdot(par, y + 2*h*e))/(12*h), &
                       'jacobian_qqdot column', abs=1e-6_dp*(1.0_dp + maxval(abs(ja))))
            h = 1e-4_dp*max(1.0_dp, abs(z(j)))
            call check(error, jb(:, j), (rhs_qp(par, z - 2*h*e) - 8*rhs_qp(par, z - h*e) &
                       + 8*rhs_qp(par, z + h*e) - rhs_qp(par, z + 2*h*e))/(12*h), &
                       'jacobian_qp column', abs=1e-6_dp*(1.0_dp + maxval(abs(jb))))
         end do
         if (allocated(error)) return
      end do
   end subroutine test_jacobians

   !> The Jacobian of a Hamiltonian field is Ω⁻¹ ∇²H, so Ω J is symmetric
   !> (Ω = [0 I; -I 0]): an identity the analytic Jacobian must satisfy to roundoff.
   subroutine test_jacobian_hamiltonian(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q(2), qd(2), jb(4, 4), om(4, 4), s(4, 4)
      integer :: i
      om = 0.0_dp
      om(1, 3) = 1.0_dp; om(2, 4) = 1.0_dp; om(3, 1) = -1.0_dp; om(4, 2) = -1.0_dp
      call seed()
      do i = 1, 50
         par = random_pendulum()
         call random_state(q, qd)
         jb = jacobian_qp(par, [q, momenta(par, q, qd)])
         s = matmul(om, jb)
         call check(error, reshape(s - transpose(s), [16]), [(0.0_dp, i=1, 16)], &
                    'Omega J symmetric', abs=1e-12_dp*maxval(abs(s)))
         if (allocated(error)) return
      end do
   end subroutine test_jacobian_hamiltonian

   !> Angle addition with Taylor-series sin d, cos d - 1 (rk4's stages) against the
   !> direct sine and cosine, over |d| ≤ 0.25 rad and past it (fallback), for angles
   !> up to 200 rad; and the Newton–Euler field from it against `qddot`.
   subroutine test_sin_cos_near(error)
      type(error_t), allocatable, intent(out) :: error
      type(pendulum_t) :: par
      real(dp) :: q0(2), d(2), q(2), sc(4), qd(2), worst
      integer :: i
      call seed()
      worst = 0.0_dp
      do i = 1, 2000
         call random_number(q0); call random_number(d); call random_number(qd)
         ! angles within ±2π for the first half, up to ±200 rad after
         q0 = merge(400.0_dp, 4.0_dp*pi, i > 1000)*(q0 - 0.5_dp)
         d = merge(0.6_dp, 0.5_dp, i > 1800)*(2.0_dp*d - 1.0_dp)
         q = q0 + d
         sc = sin_cos_near(sin_cos(q0), q, d)
         ! reference: sin and cos of the exact q0 + d differ from those of the rounded
         ! q by up to ulp(q)/2; compare with the libm values at q within that
         worst = max(worst, maxval(abs(sc - [sin(q), cos(q)])))
         call check(error, sc, [sin(q), cos(q)], 'sin_cos_near', abs=4.0_dp*spacing(maxval(abs(q))))
         par = random_pendulum()
         qd = 20.0_dp*(qd - 0.5_dp)
         if (i <= 1000) call check(error, qddot_trig(par, sc, qd), qddot(par, q, qd), &
                                   'qddot_trig', abs=1e-12_dp*maxval(abs(qddot(par, q, qd))))
         if (allocated(error)) return
      end do
      call check_true(error, worst > 0.0_dp .and. worst < 1e-13_dp, 'worst difference sane')
   end subroutine test_sin_cos_near
end module test_model
