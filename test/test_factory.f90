!> The model factory (dpend_model_factory): every model of the catalogue builds
!> from its defaults, every parameter's range is enforced at both ends, and the
!> models built are the ones their independent constructors make. The suite asks
!> the catalogue what exists; it names no model count.
module test_factory
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec_t, model_spec, model_info_t, new_model, model_catalogue, &
                                  find_model, default_model, describe_models
   use dpend_pendulum, only: pendulum_t, energy
   use dpend_chain, only: chain_t, chain_model
   use testing, only: unittest_t, new_unittest, check, check_true
   implicit none
   private
   public :: collect_factory

contains

   subroutine collect_factory(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('catalogue', test_catalogue), &
              new_unittest('defaults_build', test_defaults_build), &
              new_unittest('ranges_enforced', test_ranges), &
              new_unittest('refusals', test_refusals), &
              new_unittest('pendulum_forms', test_pendulum_forms), &
              new_unittest('energy_split', test_energy_split)]
   end subroutine collect_factory

   !> Names unique, the default model listed, every parameter's default within its
   !> range, and `dpend models` names every model and parameter.
   subroutine test_catalogue(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_info_t), allocatable :: models(:)
      character(len=:), allocatable :: text
      integer :: k, i
      models = model_catalogue()
      text = describe_models()
      call check_true(error, find_model(models, default_model) > 0, 'default model listed')
      do k = 1, size(models)
         call check_true(error, find_model(models, models(k)%name) == k, &
                         'unique name '//models(k)%name)
         call check_true(error, index(text, models(k)%name//': ') > 0, &
                         'described: '//models(k)%name)
         do i = 1, size(models(k)%params)
            associate (p => models(k)%params(i))
               call check_true(error, p%lower <= p%default .and. p%default <= p%upper, &
                               'default within range: '//models(k)%name//' '//p%name)
               call check_true(error, index(text, '    '//p%name//' ') > 0, &
                               'parameter described: '//p%name)
            end associate
         end do
         if (allocated(error)) return
      end do
   end subroutine test_catalogue

   !> Every model builds from its defaults alone; its state size is 2 n_dof and its
   !> energy at rest is finite.
   subroutine test_defaults_build(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_info_t), allocatable :: models(:)
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      real(dp), allocatable :: y(:)
      integer :: k
      models = model_catalogue()
      do k = 1, size(models)
         spec = model_spec(models(k)%name)
         call new_model(spec, model, error)
         if (allocated(error)) then
            error%message = models(k)%name//' defaults: '//error%message
            return
         end if
         call check_true(error, model%n_state() == 2*model%n_dof() .and. &
                         model%n_dof() >= 1, 'state size of '//models(k)%name)
         allocate (y(model%n_state()))
         y = 0.0_dp
         call check_true(error, abs(model%energy(0.0_dp, y)) < huge(1.0_dp), &
                         'finite energy of '//models(k)%name)
         deallocate (y)
         if (allocated(error)) return
      end do
   end subroutine test_defaults_build

   !> Every model splits its energy E = T + V (`kinetic_energy`, `potential_energy`):
   !> T + V equals E to rounding, T is 0 at rest (V = E), and T is quadratic in the
   !> rates, T(q, 2 q̇) = 4 T(q, q̇), at states spread over the coordinates.
   subroutine test_energy_split(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_info_t), allocatable :: models(:)
      class(model_t), allocatable :: model
      real(dp), allocatable :: y(:), y2(:)
      real(dp) :: e, t, v, worst_sum, worst_scale
      integer :: i, k, s, n
      models = model_catalogue()
      worst_sum = 0; worst_scale = 0
      do k = 1, size(models)
         call new_model(model_spec(models(k)%name), model, error)
         if (allocated(error)) return
         n = model%n_dof()
         do s = 1, 5
            y = [(1.0_dp + 0.3_dp*s - 0.2_dp*i, i=1, n), (0.7_dp*s - 1.3_dp*i, i=1, n)]
            e = model%energy(0.0_dp, y)
            t = model%kinetic_energy(0.0_dp, y)
            v = model%potential_energy(0.0_dp, y)
            worst_sum = max(worst_sum, abs(t + v - e)/max(1.0_dp, abs(t), abs(v)))
            y2 = y
            y2(n + 1:) = 2.0_dp*y(n + 1:)
            worst_scale = max(worst_scale, abs(model%kinetic_energy(0.0_dp, y2) - 4.0_dp*t) &
                              /max(1.0_dp, abs(t)))
            y(n + 1:) = 0.0_dp
            call check_true(error, model%kinetic_energy(0.0_dp, y) == 0.0_dp .and. &
                            abs(model%potential_energy(0.0_dp, y) - model%energy(0.0_dp, y)) &
                            <= 1e-15_dp*max(1.0_dp, abs(model%energy(0.0_dp, y))), &
                            models(k)%name//': T = 0 and V = E at rest')
            if (allocated(error)) return
         end do
      end do
      print '(4x,a,es9.2,a,es9.2)', 'energy split: largest |T + V - E| (relative) ', &
         worst_sum, ', |T(q, 2 qdot) - 4 T| ', worst_scale
      call check_true(error, worst_sum <= 1e-14_dp .and. worst_scale <= 1e-14_dp, &
                      'T + V = E and T quadratic in the rates, every model')
   end subroutine test_energy_split

   !> Each parameter of each model: its bounds are accepted, just outside them
   !> refused with a message naming it.
   subroutine test_ranges(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      do k = 1, size(models)
         do i = 1, size(models(k)%params)
            call one_parameter(models(k), i, error)
            if (allocated(error)) return
         end do
      end do
   end subroutine test_ranges

   subroutine one_parameter(info, i, error)
      type(model_info_t), intent(in) :: info
      integer, intent(in) :: i
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: refused
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      real(dp) :: outside(2), bound(2)
      integer :: j, n
      associate (p => info%params(i))
         n = p%count
         if (n < 0) n = nint(info%params(1)%default)   ! per link: the default links
         bound = [p%lower, p%upper]
         outside = [p%lower - max(abs(p%lower)*1e-3_dp, 1e-12_dp), &
                    p%upper + max(abs(p%upper)*1e-3_dp, 1e-12_dp)]
         do j = 1, 2
            if (p%name == 'links' .and. j == 2) cycle  ! the most links builds below
            call single(spec, bound(j))
            call new_model(spec, model, refused)
            call check_true(error, .not. allocated(refused), info%name//' '//p%name// &
                            ' at its bound accepted')
            if (allocated(error)) then
               error%message = error%message//': '//refused%message
               return
            end if
            call single(spec, outside(j))
            call new_model(spec, model, refused)
            call check_true(error, allocated(refused), info%name//' '//p%name// &
                            ' outside its range refused')
            if (allocated(error)) return
            call check_true(error, index(refused%message, 'invalid '//p%name) == 1, &
                            'message names '//p%name//': '//refused%message)
            if (allocated(error)) return
         end do
      end associate
   contains
      !> The model's defaults with parameter i at x (the gear ratio with a rotor
      !> inertia of 1e-6 kg m², without which it is refused as unused).
      subroutine single(spec, x)
         type(model_spec_t), intent(out) :: spec
         real(dp), intent(in) :: x
         spec = model_spec(info%name)
         call spec%set(info%params(i)%name, spread(x, 1, n))
         if (info%params(i)%name == 'gear_ratio') &
            call spec%set('rotor_inertia', spread(1e-6_dp, 1, n))
      end subroutine single
   end subroutine one_parameter

   !> An unknown model, an unknown parameter, a wrong count and a non-integer count
   !> are refused, each naming what is wrong.
   subroutine test_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      type(error_t), allocatable :: refused
      spec = model_spec('no such model')
      call new_model(spec, model, refused)
      call check_true(error, allocated(refused), 'unknown model refused')
      if (allocated(error)) return
      call check_true(error, index(refused%message, 'invalid model') == 1 .and. &
                      index(refused%message, default_model) > 0, refused%message)
      if (allocated(error)) return
      spec = model_spec(default_model)
      call spec%set('no_such_parameter', [1.0_dp])
      call new_model(spec, model, refused)
      call check_true(error, allocated(refused), 'unknown parameter refused')
      if (allocated(error)) return
      call check_true(error, index(refused%message, 'invalid no_such_parameter') == 1, &
                      refused%message)
      if (allocated(error)) return
      spec = model_spec('pendulum')
      call spec%set('links', [3.0_dp])
      call spec%set('m', [1.0_dp, 2.0_dp])
      call new_model(spec, model, refused)
      call check_true(error, allocated(refused), 'two masses for three links refused')
      if (allocated(error)) return
      call check_true(error, index(refused%message, 'invalid m: 2 values') == 1, &
                      refused%message)
      if (allocated(error)) return
      spec = model_spec('pendulum')
      call spec%set('links', [2.5_dp])
      call new_model(spec, model, refused)
      call check_true(error, allocated(refused), '2.5 links refused')
   end subroutine test_refusals

   !> The pendulum row builds the double pendulum's own formulation for two
   !> conservative links (its energy equals the closed form `energy` of the
   !> chapter's parameters) and the chain otherwise (equal to `chain_model`'s).
   subroutine test_pendulum_forms(error)
      type(error_t), allocatable, intent(out) :: error
      type(model_spec_t) :: spec
      class(model_t), allocatable :: model
      type(chain_t) :: chain
      real(dp), parameter :: y2(4) = [0.3_dp, -1.1_dp, 0.7_dp, -0.2_dp]
      real(dp), parameter :: y3(6) = [0.3_dp, -1.1_dp, 2.0_dp, 0.7_dp, -0.2_dp, 0.1_dp]
      spec = model_spec('pendulum')
      call spec%set('m', [1.5_dp, 0.5_dp])
      call spec%set('l', [0.8_dp, 1.2_dp])
      call spec%set('g', [9.81_dp])
      call new_model(spec, model, error)
      if (allocated(error)) return
      call check(error, model%energy(0.0_dp, y2), energy(pendulum_t(m1=1.5_dp, m2=0.5_dp, &
                 l1=0.8_dp, l2=1.2_dp, g=9.81_dp), y2(1:2), y2(3:4)), 'double pendulum energy', &
                 rel=1e-15_dp)
      if (allocated(error)) return
      select type (model)
      type is (chain_t)
         call check_true(error, .false., 'two conservative links: not the chain')
      end select
      if (allocated(error)) return
      spec = model_spec('pendulum')
      call spec%set('links', [3.0_dp])
      call spec%set('damping', [0.1_dp, 0.0_dp, 0.2_dp])
      call new_model(spec, model, error)
      if (allocated(error)) return
      chain = chain_model([1.0_dp, 1.0_dp, 1.0_dp], [1.0_dp, 1.0_dp, 1.0_dp], 9.8_dp, &
                          error, [0.1_dp, 0.0_dp, 0.2_dp])
      if (allocated(error)) return
      call check(error, model%energy(0.0_dp, y3), chain%energy(0.0_dp, y3), &
                 'damped chain energy', rel=1e-15_dp)
      if (allocated(error)) return
      call check_true(error, .not. model%conservative(), 'damped chain not conservative')
   end subroutine test_pendulum_forms
end module test_factory
