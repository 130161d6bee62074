!> The constructor of the N-link chain (`chain_model`, interface in dpend_chain): the
!> checks of every parameter, with the messages the factory passes on, and the
!> constants K_ij, G_i, μ_i of the formulas (dpend_chain's notes). Run once per
!> model, never within a step.
submodule (dpend_chain) dpend_chain_build
   use dpend_error, only: fatal_error
   use dpend_limits, only: check_range, check_parameter, parameter_mass, parameter_length, &
                           parameter_gravity, max_damping, max_support_amplitude, &
                           max_support_frequency, max_angle, max_torque, &
                           min_coulomb_speed, max_coulomb_speed, max_rotor_inertia, &
                           min_gear_ratio, max_gear_ratio, max_reflected_inertia
   use dpend_strings, only: to_str
   use dpend_pendulum, only: check_bodies
   implicit none

contains

   module procedure chain_model
      character(len=*), parameter :: reason = 'keeps every product of the model finite'
      integer :: i, j, n
      real(dp) :: tail
      n = size(m)
      if (n < 1 .or. n > max_dof) then
         call fatal_error(error, 'invalid links: '//to_str(n)//' is outside [1, ' &
                          //to_str(max_dof)//']')
         return
      end if
      if (size(l) /= n) then
         call fatal_error(error, 'invalid l: '//to_str(size(l))//' lengths for ' &
                          //to_str(n)//' links (one per link)')
         return
      end if
      do i = 1, n
         call check_parameter(parameter_mass, 'm'//to_str(i), m(i), error)
         if (allocated(error)) return
      end do
      do i = 1, n
         call check_parameter(parameter_length, 'l'//to_str(i), l(i), error)
         if (allocated(error)) return
      end do
      call check_parameter(parameter_gravity, 'g', g, error)   ! g >= 1e-6 as for N = 2
      if (allocated(error)) return
      allocate (model%c(n))
      model%c = 0.0_dp
      if (present(damping)) then
         if (size(damping) /= n) then
            call fatal_error(error, 'invalid damping: '//to_str(size(damping))// &
                             ' coefficients for '//to_str(n)//' links (one per joint)')
            return
         end if
         do i = 1, n
            call check_range('damping c'//to_str(i), damping(i), 0.0_dp, max_damping, &
                             'N m s', error, reason)
            if (allocated(error)) return
         end do
         model%c = damping
      end if
      model%damped = any(model%c > 0.0_dp)
      allocate (model%cf(n))
      model%cf = 0.0_dp
      if (present(coulomb)) then
         if (size(coulomb) /= n) then
            call fatal_error(error, 'invalid coulomb: '//to_str(size(coulomb))// &
                             ' friction torques for '//to_str(n)//' links (one per joint)')
            return
         end if
         do i = 1, n
            call check_range('coulomb c_f'//to_str(i), coulomb(i), 0.0_dp, max_torque, &
                             'N m', error, reason)
            if (allocated(error)) return
         end do
         model%cf = coulomb
      end if
      model%coulomb = any(model%cf > 0.0_dp)
      if (present(coulomb_speed)) then
         call check_range('coulomb_speed', coulomb_speed, min_coulomb_speed, &
                          max_coulomb_speed, 'rad/s', error, 'keeps the friction''s ' &
                          //'slope c_f/v_s finite')
         if (allocated(error)) return
         model%vs = coulomb_speed
      end if
      call set_motors(error)
      if (allocated(error)) return
      if (present(amplitude)) then
         do i = 1, 2
            call check_range('support_amplitude '//merge('a_x', 'a_y', i == 1), &
                             amplitude(i), -max_support_amplitude, max_support_amplitude, &
                             'm', error, reason)
            if (allocated(error)) return
         end do
         model%sup_a = amplitude
      end if
      if (present(frequency)) then
         call check_range('support_frequency', frequency, 0.0_dp, max_support_frequency, &
                          'rad/s', error, reason)
         if (allocated(error)) return
         model%sup_w = frequency
      end if
      if (present(phase)) then
         do i = 1, 2
            call check_range('support_phase '//merge('phi_x', 'phi_y', i == 1), phase(i), &
                             -max_angle, max_angle, 'rad', error, reason)
            if (allocated(error)) return
         end do
         model%sup_phi = phase
      end if
      ! a nonzero amplitude moves the pin (with ω = 0 it only offsets it)
      model%driven = any(model%sup_a /= 0.0_dp)
      if (present(torque)) then
         if (torque%active()) then
            if (torque%n /= n) then
               call fatal_error(error, 'invalid torque: '//to_str(torque%n)// &
                                ' joint torques for '//to_str(n)//' links (one per joint)')
               return
            end if
            model%torque = torque
            model%torqued = .true.
         end if
      end if
      model%rod = .not. (present(com) .or. present(inertia))
      if (model%rod) then
         model%d = 0.5_dp*l
         model%ic = m*l**2/12.0_dp
      else
         if (.not. (present(com) .and. present(inertia))) then
            call fatal_error(error, 'internal error: chain_model needs both com and inertia')
            return
         end if
         if (size(com) /= n) then
            call fatal_error(error, 'invalid com: '//to_str(size(com))//' values for ' &
                             //to_str(n)//' links (one per link)')
            return
         end if
         if (size(inertia) /= n) then
            call fatal_error(error, 'invalid inertia: '//to_str(size(inertia))//' values for ' &
                             //to_str(n)//' links (one per link)')
            return
         end if
         call check_bodies(m, l, com, inertia, error)
         if (allocated(error)) return
         model%d = com
         model%ic = inertia
      end if
      model%n = n
      model%m = m
      model%l = l
      model%g = g
      allocate (model%k(n, n), model%gl(n), model%mu(n))
      ! tail = Σ_(k>i) m_k, from the tip
      tail = 0.0_dp
      if (.not. model%rod) then
         do i = n, 1, -1
            model%k(i, i) = model%ic(i) + m(i)*model%d(i)**2 + tail*l(i)**2
            do j = i + 1, n
               model%k(i, j) = l(i)*(m(j)*model%d(j) + l(j)*sum(m(j + 1:n)))
               model%k(j, i) = model%k(i, j)
            end do
            model%gl(i) = g*(m(i)*model%d(i) + l(i)*tail)
            model%mu(i) = m(i)*model%d(i) + l(i)*tail
            tail = tail + m(i)
         end do
         return
      end if
      do i = n, 1, -1
         model%k(i, i) = (m(i)/3.0_dp + tail)*l(i)**2
         do j = i + 1, n
            model%k(i, j) = (0.5_dp*m(j) + sum(m(j + 1:n)))*l(i)*l(j)
            model%k(j, i) = model%k(i, j)
         end do
         model%gl(i) = g*l(i)*(0.5_dp*m(i) + tail)
         model%mu(i) = l(i)*(0.5_dp*m(i) + tail)
         tail = tail + m(i)
      end do
   contains
      !> The motors: rotor inertia I_r,i ∈ [0, max_rotor_inertia], gear ratio g_r,i ∈
      !> [min_gear_ratio, max_gear_ratio] (default 1), the reflected g_r,i² I_r,i at
      !> most max_reflected_inertia.
      subroutine set_motors(error)
         type(error_t), allocatable, intent(out) :: error
         allocate (model%ir(n), model%gr(n))
         model%ir = 0.0_dp
         model%gr = 1.0_dp
         if (present(rotor_inertia)) then
            if (size(rotor_inertia) /= n) then
               call fatal_error(error, 'invalid rotor_inertia: '//to_str(size(rotor_inertia)) &
                                //' values for '//to_str(n)//' links (one per joint)')
               return
            end if
            do i = 1, n
               call check_range('rotor_inertia I_r'//to_str(i), rotor_inertia(i), 0.0_dp, &
                                max_rotor_inertia, 'kg m^2', error, reason)
               if (allocated(error)) return
            end do
            model%ir = rotor_inertia
         end if
         if (present(gear_ratio)) then
            if (size(gear_ratio) /= n) then
               call fatal_error(error, 'invalid gear_ratio: '//to_str(size(gear_ratio)) &
                                //' values for '//to_str(n)//' links (one per joint)')
               return
            end if
            do i = 1, n
               call check_range('gear_ratio g_r'//to_str(i), gear_ratio(i), min_gear_ratio, &
                                max_gear_ratio, '', error, reason)
               if (allocated(error)) return
            end do
            model%gr = gear_ratio
         end if
         model%im = model%gr**2*model%ir
         do i = 1, n
            call check_range('rotor_inertia I_r'//to_str(i)//' times gear_ratio g_r' &
                             //to_str(i)//' squared', model%im(i), 0.0_dp, &
                             max_reflected_inertia, 'kg m^2', error, 'keeps the mass ' &
                             //'matrix''s condition finite')
            if (allocated(error)) return
         end do
         model%motors = any(model%im > 0.0_dp)
      end subroutine set_motors
   end procedure chain_model
end submodule dpend_chain_build
