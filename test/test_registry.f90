!> The method registry (dpend_method_registry): its table is consistent, every
!> record builds through the factory, and the built method reports the order and
!> properties written in the table; options reach the methods through one record.
module test_registry
   use dpend_kinds, only: dp, i8
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_method_registry, only: method_table, n_methods, method_index, method_names, &
                                    plot_groups, field_method_names
   use dpend_rk_explicit, only: rk_adaptive_t
   use dpend_symplectic, only: symplectic_t, composition_t
   use dpend_tao, only: tao_t
   use testing, only: unittest_t, new_unittest, check_true, error_t
   implicit none
   private
   public :: collect_registry

contains

   subroutine collect_registry(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('table', test_table), &
              new_unittest('factory_matches_table', test_factory), &
              new_unittest('configure', test_configure)]
   end subroutine collect_registry

   !> The table is consistent, whatever methods it holds: n_methods records, unique
   !> plain names, valid ranges, costs, groups and colours; `method_names` and
   !> `field_method_names` list the table's names (the latter those without the
   !> `hamiltonian` flag) in its order.
   subroutine test_table(error)
      type(error_t), allocatable, intent(out) :: error
      integer :: i, j
      character(len=:), allocatable :: names
      call check_true(error, n_methods >= 1 .and. size(method_table) == n_methods, &
                      'n_methods = size(method_table) >= 1')
      if (allocated(error)) return
      names = ''
      do i = 1, n_methods
         associate (m => method_table(i))
            call check_true(error, len_trim(m%name) > 0 .and. verify(trim(m%name), &
                            'abcdefghijklmnopqrstuvwxyz0123456789') == 0, &
                            'plain name: '//m%name)
            call check_true(error, method_index(trim(m%name)) == i, 'unique name '//m%name)
            call check_true(error, m%order >= 1 .and. m%h_min > 0.0_dp .and. &
                            m%h_min <= m%h_max .and. m%cost > 0.0_dp, 'order, h, cost of ' &
                            //m%name)
            call check_true(error, (m%rtol_min > 0.0_dp .and. m%rtol_min <= m%rtol_max &
                                    .and. m%rtol_max < 1.0_dp) .eqv. m%adaptive, &
                            'tolerance range only and always for adaptive: '//m%name)
            call check_true(error, any([(plot_groups(j)%id == m%group, &
                                         j=1, size(plot_groups))]), 'group of '//m%name)
            call check_true(error, m%colour(1:1) == '#' .and. &
                            verify(m%colour(2:), '0123456789abcdef') == 0, 'colour of '//m%name)
            call check_true(error, len_trim(m%description) > 0, 'description of '//m%name)
            call check_true(error, m%canonical .or. .not. m%hamiltonian, &
                            'needs a Hamiltonian but not canonical: '//m%name)
            if (i > 1) names = names//' '
            names = names//trim(m%name)
         end associate
         if (allocated(error)) return
      end do
      call check_true(error, method_names() == names, 'method_names: '//method_names())
      names = field_list()
      call check_true(error, field_method_names() == names, 'field_method_names: ' &
                      //field_method_names()//'; expected: '//names)
      ! each name is listed exactly when the method accepts models without a Hamiltonian
      names = ', '//field_method_names()//', '
      i = index(names, ' or ')
      if (i > 0) names = names(:i - 1)//','//names(i + 3:)
      do i = 1, n_methods
         call check_true(error, (index(names, ', '//trim(method_table(i)%name)//', ') > 0) &
                         .neqv. method_table(i)%hamiltonian, 'field_method_names and ' &
                         //'the hamiltonian flag of '//trim(method_table(i)%name))
      end do
      call check_true(error, method_index('dopri') == 0 .and. method_index('') == 0, &
                      'unknown names')
   end subroutine test_table

   !> The names of the table's methods without the `hamiltonian` flag, in its order,
   !> as a reader would write them: "a", "a or b", "a, b or c", ...
   function field_list() result(list)
      character(len=:), allocatable :: list
      integer :: i, n, k
      n = count(.not. method_table%hamiltonian)
      list = ''
      k = 0
      do i = 1, n_methods
         if (method_table(i)%hamiltonian) cycle
         k = k + 1
         if (k == n .and. k > 1) then
            list = list//' or '
         else if (k > 1) then
            list = list//', '
         end if
         list = list//trim(method_table(i)%name)
      end do
   end function field_list

   !> Every name builds, and the built method agrees with its record.
   subroutine test_factory(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      character(len=:), allocatable :: name
      integer :: i
      do i = 1, n_methods
         name = trim(method_table(i)%name)
         associate (m => method_table(i))
            call new_integrator(name, integ, err)
            call check_true(error, .not. allocated(err), 'factory rejects '//name)
            if (allocated(error)) return
            call check_true(error, integ%name() == name, 'name of '//name)
            call check_true(error, integ%order() == m%order, 'order of '//name)
            call check_true(error, integ%adaptive() .eqv. m%adaptive, 'adaptive of '//name)
            call check_true(error, integ%implicit() .eqv. m%implicit, 'implicit of '//name)
            call check_true(error, integ%symplectic() .eqv. m%symplectic, &
                            'symplectic of '//name)
            call check_true(error, integ%symmetric() .eqv. m%symmetric, 'symmetric of '//name)
            call check_true(error, integ%canonical() .eqv. m%canonical, &
                            'canonical of '//name)
            call check_true(error, integ%needs_hamiltonian() .eqv. m%hamiltonian, &
                            'needs_hamiltonian of '//name)
            select type (integ)
            class is (symplectic_t)
               call check_true(error, m%compensated, 'compensated of '//name)
            class default
               call check_true(error, .not. m%compensated, 'compensated of '//name)
            end select
            call check_true(error, m%omega .eqv. has_omega(integ), 'omega of '//name)
         end associate
         if (allocated(error)) return
      end do
      call new_integrator('dopri', integ, err)
      call check_true(error, allocated(err), 'unknown method accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, "invalid method: 'dopri' (accepted: " &
                                   //method_names()//")") == 1, 'message: '//err%message)
   end subroutine test_factory

   !> Options reach the methods through the record: the factory's `options` and
   !> `configure` set rtol, atol, fixed_step and max_steps of the adaptive pairs,
   !> ω of tao2 and tao4 (through its base), `compensated` of the (q, p) methods;
   !> 0 keeps a default.
   subroutine test_configure(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(method_options_t) :: opt
      opt = method_options_t(rtol=1e-7_dp, atol=1e-10_dp, omega=35.0_dp, max_steps=77_i8, &
                             fixed_step=.true., compensated=.false.)
      call new_integrator('dop853', integ, err, opt)
      select type (integ)
      class is (rk_adaptive_t)
         call check_true(error, integ%rtol == 1e-7_dp .and. integ%atol == 1e-10_dp .and. &
                         integ%fixed_step .and. integ%max_steps == 77_i8, 'dop853 options')
      class default
         call check_true(error, .false., 'dop853 is not an rk_adaptive_t')
      end select
      if (allocated(error)) return
      call integ%configure(method_options_t(atol=1e-11_dp))
      select type (integ)
      class is (rk_adaptive_t)
         call check_true(error, integ%rtol == 1e-7_dp .and. integ%atol == 1e-11_dp .and. &
                         .not. integ%fixed_step .and. integ%max_steps == 77_i8, &
                         'configure keeps what is 0')
      end select
      if (allocated(error)) return
      call new_integrator('tao2', integ, err, opt)
      select type (integ)
      class is (tao_t)
         call check_true(error, integ%omega == 35.0_dp .and. .not. integ%compensated, &
                         'tao2 options')
      class default
         call check_true(error, .false., 'tao2 is not a tao_t')
      end select
      if (allocated(error)) return
      call new_integrator('tao4', integ, err, opt)
      select type (integ)
      class is (composition_t)
         call check_true(error, .not. integ%compensated, 'tao4 compensated')
         select type (b => integ%base)
         class is (tao_t)
            call check_true(error, b%omega == 35.0_dp, 'tao4 omega through its base')
         class default
            call check_true(error, .false., 'the base of tao4 is not a tao_t')
         end select
      class default
         call check_true(error, .false., 'tao4 is not a composition_t')
      end select
      if (allocated(error)) return
      call new_integrator('gauss6', integ, err, method_options_t(compensated=.false.))
      select type (integ)
      class is (symplectic_t)
         call check_true(error, .not. integ%compensated .and. &
                         integ%max_steps /= 77_i8, 'gauss6 options')
      end select
   end subroutine test_configure

   !> The method has Tao's ω (tao_t, or a composition of it).
   logical function has_omega(integ)
      class(integrator_t), intent(in) :: integ
      has_omega = .false.
      select type (integ)
      class is (tao_t)
         has_omega = .true.
      class is (composition_t)
         select type (b => integ%base)
         class is (tao_t)
            has_omega = .true.
         end select
      end select
   end function has_omega
end module test_registry
