!> The pixels of a sweep over parameters: which parameter an axis sweeps (the
!> coded masses and lengths of the double pendulum's lanes, or any real parameter
!> of the model's catalogue row by name), each pixel's parameters, and its model or
!> the lanes' constant record. The settings record: dpend_sweep_record; its
!> validation: dpend_sweep_settings.
module dpend_sweep_pixels
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: real_str, to_str, printable
   use dpend_lane_batch, only: stop_both, stop_either, stop_end
   use dpend_limits, only: sci, max_threads, max_axis_points, max_sweep_points, max_angle, &
      max_angular_velocity, max_time, check_parameter, parameter_mass, parameter_length
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t
   use dpend_model_factory, only: model_spec_t, new_model, model_info_t, model_catalogue, &
      find_model, spec_values
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_strings, only: to_lower, did_you_mean
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_sweep_record
   implicit none
   private
   public :: axis_parameter, pixel_parameters, pixel_model, coded_spec, coded_axes, &
      pendulum_axis, split_axis, named_axis_units, pendulum_axis_text, &
      pendulum_param_names, pendulum_param_values, pixel_model_axes, pixel_pendulums, &
      pixel_pendulum, point_masses, model_axis, model_axis_names, pixel_model_named

contains

   !> The parameter an axis sweeps: 1 m1, 2 m2, 3 l1, 4 l2, 5 m2/m1, 6 l2/l1; 0 for
   !> an initial value or an unknown name.
   pure integer function axis_parameter(name)
      character(len=*), intent(in) :: name  !! axis name
      select case (name)
      case ('m1'); axis_parameter = 1
      case ('m2'); axis_parameter = 2
      case ('l1'); axis_parameter = 3
      case ('l2'); axis_parameter = 4
      case ('m2/m1'); axis_parameter = 5
      case ('l2/l1'); axis_parameter = 6
      case default; axis_parameter = 0
      end select
   end function axis_parameter

   !> (m1, m2, l1, l2) of a pixel: the configured ones with the values x1, x2 of the
   !> parameter axes p1, p2 (axis_parameter codes, 0: an initial value), the masses
   !> and lengths first, then the ratios (m2 = r m1 with m1 possibly swept).
   pure function pixel_parameters(cfg, p1, x1, p2, x2) result(p)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      integer, intent(in) :: p1, p2            !! axis_parameter of axis 1 and 2
      real(dp), intent(in) :: x1, x2           !! the pixel's axis values
      real(dp) :: p(4)
      p = [cfg%run%m(1), cfg%run%m(2), cfg%run%l(1), cfg%run%l(2)]
      if (p1 >= 1 .and. p1 <= 4) p(p1) = x1
      if (p2 >= 1 .and. p2 <= 4) p(p2) = x2
      if (p1 == 5) p(2) = x1*p(1)
      if (p2 == 5) p(2) = x2*p(1)
      if (p1 == 6) p(4) = x1*p(3)
      if (p2 == 6) p(4) = x2*p(3)
   end function pixel_parameters

   !> The model of a pixel of a parameter sweep, from the factory: a copy of the run's
   !> specification (`cfg%run%spec`) with the masses and lengths of links 1 and 2 set
   !> by name to p = (m1, m2, l1, l2) of `pixel_parameters`.
   subroutine pixel_model(cfg, p, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      real(dp), intent(in) :: p(4)                       !! (m1, m2, l1, l2) [kg, kg, m, m]
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      spec = cfg%run%spec
      call coded_spec(cfg, p, spec)
      call new_model(spec, model, error)
   end subroutine pixel_model

   !> Set the masses and lengths of links 1 and 2 of `spec` to p = (m1, m2, l1, l2)
   !> of `pixel_parameters` (point masses: com and inertia follow the lengths).
   subroutine coded_spec(cfg, p, spec)
      type(sweep_config_t), intent(in) :: cfg     !! configuration, model built
      real(dp), intent(in) :: p(4)                !! (m1, m2, l1, l2) [kg, kg, m, m]
      type(model_spec_t), intent(inout) :: spec   !! the pixel's specification
      real(dp), allocatable :: m(:), l(:)
      m = spec%get('m', cfg%run%m(:cfg%run%links))
      l = spec%get('l', cfg%run%l(:cfg%run%links))
      m(1:2) = p(1:2); l(1:2) = p(3:4)
      call spec%set('m', m)
      call spec%set('l', l)
      if (point_masses(cfg)) then   ! the body follows the pixel's lengths
         call spec%set('com', l)
         call spec%set('inertia', spread(0.0_dp, 1, size(l)))
      end if
   end subroutine coded_spec

   !> True if an axis of the grid is a coded parameter axis (m1 m2 l1 l2 m2/m1 l2/l1).
   pure logical function coded_axes(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      coded_axes = axis_parameter(cfg%axis1) > 0 .or. axis_parameter(cfg%axis2) > 0
   end function coded_axes

   !> Whether `axis` sweeps a parameter of the pendulum by name, beside the coded
   !> axes (`axis_parameter`): a real scalar of its catalogue row (g) or component k
   !> of a per-link list, k = 1 .. N (m3, l3, com1, inertia2, ...). Not the
   !> parameters the catalogue marks as no map's axis (`param_info_t%map_axis`).
   logical function pendulum_axis(cfg, axis)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      character(len=:), allocatable :: base
      integer :: k
      pendulum_axis = .false.
      if (.not. flip_model(cfg)) return
      if (axis_parameter(axis) > 0 .or. axis_variable(axis, cfg%run%links) > 0) return
      call split_axis(cfg, axis, base, k)
      pendulum_axis = len(base) > 0
   end function pendulum_axis

   !> The catalogue parameter `base` of a named pendulum axis and its link k (0 for a
   !> scalar); base = '' if `axis` is none.
   subroutine split_axis(cfg, axis, base, k)
      type(sweep_config_t), intent(in) :: cfg             !! configuration, model built
      character(len=*), intent(in) :: axis                !! axis name
      character(len=:), allocatable, intent(out) :: base  !! catalogue name or ''
      integer, intent(out) :: k                           !! link, 0: a scalar
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, d, stat
      base = ''; k = 0
      models = model_catalogue()
      m = find_model(models, cfg%run%spec%model_name())
      if (m == 0 .or. len_trim(axis) == 0) return
      do i = 1, size(models(m)%params)
         associate (p => models(m)%params(i))
            if (p%integer_valued .or. .not. p%map_axis) cycle
            if (p%count == 1 .and. axis == p%name) then
               base = p%name; k = 0
               return
            else if (p%count == -1 .and. index(axis, p%name) == 1 .and. &
                     len(axis) > len(p%name) .and. len(axis) <= len(p%name) + 3) then
               d = len(p%name) + 1
               if (verify(axis(d:), '0123456789') /= 0 .or. axis(d:d) == '0') cycle
               read (axis(d:), *, iostat=stat) k
               if (stat /= 0 .or. k < 1 .or. k > cfg%run%links) then
                  k = 0
                  cycle
               end if
               base = p%name
               return
            end if
         end associate
      end do
   end subroutine split_axis

   !> The units of a named pendulum axis (its catalogue parameter's), '' if none.
   function named_axis_units(cfg, axis) result(units)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      character(len=:), allocatable :: units, base
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, k
      units = ''
      call split_axis(cfg, axis, base, k)
      if (len(base) == 0) return
      models = model_catalogue()
      m = find_model(models, cfg%run%spec%model_name())
      do i = 1, size(models(m)%params)
         if (models(m)%params(i)%name == base) units = models(m)%params(i)%units
      end do
   end function named_axis_units

   !> The named pendulum axes of N links for messages: ' m3..mN l3..lN g com1..comN
   !> inertia1..inertiaN' (the per-link lists beyond the coded m1 m2 l1 l2).
   function pendulum_axis_text(links) result(s)
      integer, intent(in) :: links  !! number of links N
      character(len=:), allocatable :: s
      type(model_info_t), allocatable :: models(:)
      integer :: i, m, first
      s = ''
      models = model_catalogue()
      m = find_model(models, 'pendulum')
      do i = 1, size(models(m)%params)
         associate (p => models(m)%params(i))
            if (p%integer_valued .or. .not. p%map_axis) cycle
            if (p%count == 1) then
               s = s//' '//p%name
            else if (p%count == -1) then
               first = 1
               if (p%name == 'm' .or. p%name == 'l') first = 3   ! m1 m2 l1 l2: coded
               if (links < first) cycle
               if (links == first) then
                  s = s//' '//p%name//to_str(first)
               else if (links == first + 1) then
                  s = s//' '//p%name//to_str(first)//' '//p%name//to_str(links)
               else
                  s = s//' '//p%name//to_str(first)//'..'//p%name//to_str(links)
               end if
            end if
         end associate
      end do
   end function pendulum_axis_text

   !> The parameters recorded per pixel of a pendulum map with a named axis
   !> (`pendulum_axis`): m1 m2 l1 l2 with a coded axis, then each named axis.
   function pendulum_param_names(cfg) result(names)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=32), allocatable :: names(:)
      character(len=32) :: all(6)
      integer :: n
      n = 0
      if (coded_axes(cfg)) then
         all(1:4) = [character(len=32) :: 'm1', 'm2', 'l1', 'l2']
         n = 4
      end if
      if (pendulum_axis(cfg, cfg%axis1)) then
         n = n + 1
         all(n) = cfg%axis1
      end if
      if (pendulum_axis(cfg, cfg%axis2)) then
         n = n + 1
         all(n) = cfg%axis2
      end if
      names = all(:n)
   end function pendulum_param_names

   !> The values of `pendulum_param_names` of the pixel at axis values (x1, x2).
   pure function pendulum_param_values(cfg, named1, named2, x1, x2) result(p)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      logical, intent(in) :: named1, named2    !! axis 1, 2 a parameter by name (`pendulum_axis`)
      real(dp), intent(in) :: x1, x2           !! the pixel's axis values
      real(dp), allocatable :: p(:)
      real(dp) :: all(6)
      integer :: n
      n = 0
      if (coded_axes(cfg)) then
         all(1:4) = pixel_parameters(cfg, axis_parameter(cfg%axis1), x1, &
                                     axis_parameter(cfg%axis2), x2)
         n = 4
      end if
      if (named1) then
         n = n + 1
         all(n) = x1
      end if
      if (named2) then
         n = n + 1
         all(n) = x2
      end if
      p = all(:n)
   end function pendulum_param_values

   !> The model of a pixel of a pendulum map with a named axis, from the factory: a
   !> copy of the run's specification with (m1, m2, l1, l2) = x(1:4) as
   !> `pixel_model` when names(1:4) are those of a coded axis, then each named
   !> parameter (`pendulum_param_names`) set by name: a scalar to x(k), a per-link
   !> list's component to x(k), its other components those the run's model uses
   !> (`spec_values`: com and inertia of rods follow the pixel's m and l).
   subroutine pixel_model_axes(cfg, names, x, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      character(len=*), intent(in) :: names(:)           !! `pendulum_param_names`
      real(dp), intent(in) :: x(:)                       !! the pixel's values of names
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      character(len=:), allocatable :: base
      real(dp), allocatable :: v(:)
      integer :: j, k, first
      spec = cfg%run%spec
      first = 1
      if (size(names) >= 4) then
         if (names(1) == 'm1' .and. names(4) == 'l2') then   ! a coded axis
            call coded_spec(cfg, x(1:4), spec)
            first = 5
         end if
      end if
      do j = first, size(names)
         call split_axis(cfg, trim(names(j)), base, k)
         if (len(base) == 0) error stop 'internal error: not a pendulum axis: '//trim(names(j))
         if (k == 0) then
            call spec%set(base, [x(j)])
         else
            v = spec_values(spec, base, cfg%run%links)
            v(k) = x(j)
            call spec%set(base, v)
         end if
      end do
      call new_model(spec, model, error)
   end subroutine pixel_model_axes

   !> The double pendulum's constant records of the pixels p(:, j) of a parameter
   !> sweep (`pixel_pendulum` of each).
   pure function pixel_pendulums(cfg, p) result(pars)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: p(:, :)          !! (4, n) (m1, m2, l1, l2) [kg, kg, m, m]
      type(pendulum_t) :: pars(size(p, 2))
      integer :: j
      do j = 1, size(p, 2)
         pars(j) = pixel_pendulum(cfg, p(:, j))
      end do
   end function pixel_pendulums

   !> The double pendulum's constant record of a pixel of a parameter sweep (the lane
   !> kernel's parameters, not a model): the run's with (m1, m2, l1, l2) = p; point
   !> masses sit at the pixel's link ends.
   pure function pixel_pendulum(cfg, p) result(par)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: p(4)             !! (m1, m2, l1, l2) [kg, kg, m, m]
      type(pendulum_t) :: par
      par = cfg%run%pendulum()
      par%m1 = p(1); par%m2 = p(2); par%l1 = p(3); par%l2 = p(4)
      if (point_masses(cfg)) then
         par%d1 = p(3); par%d2 = p(4)
      end if
   end function pixel_pendulum

   !> The links are point masses (--body point): their centres follow a swept length.
   pure logical function point_masses(cfg)
      type(sweep_config_t), intent(in) :: cfg  !! configuration
      point_masses = .false.
      if (allocated(cfg%run%body)) point_masses = cfg%run%body == 'point'
   end function point_masses

   !> Whether `axis` sweeps a parameter by name: of a model without flips a real
   !> scalar parameter of its catalogue row (the elastic pendulum's m, k, l0, g); of
   !> the pendulum those of `pendulum_axis` (not the coded axes).
   logical function model_axis(cfg, axis)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=*), intent(in) :: axis     !! axis name
      model_axis = .false.
      if (flip_model(cfg)) then   ! the pendulum's parameters by name
         model_axis = pendulum_axis(cfg, axis)
         return
      end if
      model_axis = index(' '//model_axis_names(cfg)//' ', ' '//axis//' ') > 0 .and. &
                   len_trim(axis) > 0
   end function model_axis

   !> The parameters a map of a model without flips may sweep, blank-separated: the
   !> real scalar parameters of its catalogue row.
   function model_axis_names(cfg) result(names)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: names
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      names = ''
      models = model_catalogue()
      k = find_model(models, cfg%run%spec%model_name())
      if (k == 0) return
      do i = 1, size(models(k)%params)
         associate (p => models(k)%params(i))
            if (p%count == 1 .and. .not. p%integer_valued) then
               if (len(names) > 0) names = names//' '
               names = names//p%name
            end if
         end associate
      end do
   end function model_axis_names

   !> The model of a pixel of a map of a model without flips whose axes sweep its
   !> parameters: a copy of the run's specification with each parameter names(k)
   !> set to x(k) ('': axis k sweeps an initial value).
   subroutine pixel_model_named(cfg, names, x, model, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration, model built
      character(len=*), intent(in) :: names(2)           !! the axes' parameters or ''
      real(dp), intent(in) :: x(2)                       !! the pixel's axis values
      class(model_t), allocatable, intent(out) :: model  !! the pixel's model
      type(error_t), allocatable, intent(out) :: error   !! refused by the factory
      type(model_spec_t) :: spec
      integer :: k
      spec = cfg%run%spec
      do k = 1, 2
         if (len_trim(names(k)) > 0) call spec%set(trim(names(k)), [x(k)])
      end do
      call new_model(spec, model, error)
   end subroutine pixel_model_named
end module dpend_sweep_pixels
