!> The model factory: the one place a model is built (docs/architecture.md).
!>
!> A model is asked for by a specification (`model_spec_t`): the model's name and
!> its parameters by name, each a list of reals (a per-link parameter has one value
!> per link). `new_model` checks the specification against the model's description
!> (names, counts, ranges; every range comes from `dpend_limits`) and builds it.
!> `model_catalogue` describes every model: its coordinates, its parameters (names,
!> units, ranges, defaults) and what it supports; `dpend models` prints it, and the
!> tests ask it what exists instead of naming models.
!>
!> Adding a model: its module under models/, one row in `model_catalogue` (its
!> description) and one branch in `build` (its construction).
module dpend_model_factory
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: model_t, max_dof
   use dpend_pendulum, only: pendulum_t, pendulum_model, body_general
   use dpend_chain, only: chain_t, chain_model
   use dpend_joint_torque, only: joint_torque_t
   use dpend_elastic, only: elastic_t, elastic_model, min_stiffness, max_stiffness
   use dpend_strings, only: to_str, real_str, did_you_mean
   use dpend_limits, only: min_mass, max_mass, min_length, max_length, min_g, max_g, &
                           max_damping, max_support_amplitude, max_support_frequency, &
                           max_angle, max_torque, min_coulomb_speed, max_coulomb_speed, &
                           max_rotor_inertia, min_gear_ratio, max_gear_ratio
   implicit none
   private
   public :: model_spec_t, spec_item_t, param_info_t, model_info_t
   public :: model_spec, new_model, model_catalogue, find_model, default_model, describe_models
   public :: spec_values, derived_default, has_parameter, body_names, body_list

   !> The named bodies of the pendulum's links (--body NAME, &pendulum body = 'NAME'),
   !> each link's mass distribution; --com and --inertia give any other.
   character(len=*), parameter :: body_names(2) = [character(len=5) :: 'rod', 'point']
   !> What each of `body_names` sets, in their order.
   character(len=*), parameter :: body_meanings(2) = [character(len=64) :: &
      'uniform rods, d_i = l_i/2, I_i = m_i l_i^2/12 (the default)', &
      'point masses at the link ends, d_i = l_i, I_i = 0']

   !> The model a specification without a name asks for: the chapter's pendulum.
   character(len=*), parameter :: default_model = 'pendulum'

   !> One named parameter of a specification.
   type :: spec_item_t
      character(len=:), allocatable :: name  !! parameter name, e.g. 'm'
      real(dp), allocatable :: values(:)     !! its value(s) in the parameter's units
   end type spec_item_t

   !> What to build: a model name and parameters by name. Parameters not given take
   !> the description's defaults.
   type :: model_spec_t
      character(len=:), allocatable :: name            !! model name (default_model if unset)
      type(spec_item_t), allocatable :: items(:)       !! parameters given
      !> build the general form (the chain, also for two links without damping),
      !> whose parameters a fit varies continuously
      logical :: general = .false.
      !> applied joint torques τ_i(t) (a series or a closed form; inactive: none), for
      !> a model whose description takes them (`model_info_t%torques`)
      type(joint_torque_t) :: torque
   contains
      !> Set parameter `name` to `values` (replacing an earlier value).
      procedure :: set => spec_set
      !> Index of parameter `name` in `items`, 0 if not given.
      procedure :: find => spec_find
      !> The values of `name`, or `default` if not given.
      procedure :: get => spec_get
      !> The model name asked for (default_model if unset).
      procedure :: model_name => spec_model_name
   end type model_spec_t

   !> The description of one parameter.
   type :: param_info_t
      character(len=:), allocatable :: name     !! e.g. 'm'
      character(len=:), allocatable :: units    !! e.g. 'kg' ('' for a count)
      character(len=:), allocatable :: meaning  !! one line for people
      real(dp) :: lower = 0.0_dp                !! smallest accepted value
      real(dp) :: upper = 0.0_dp                !! largest accepted value
      real(dp) :: default = 0.0_dp              !! value when not given
      !> How many values: 1 (a scalar), -1 (one per link), or a fixed count (2: x, y).
      integer :: count = 1
      logical :: integer_valued = .false.       !! a count (e.g. links)
      !> A map (dpend sweep, whose kernels integrate the conservative model) may take
      !> it as an axis: false for what makes the model dissipative or driven (damping,
      !> friction, the support's motion) or only shapes such a term
      logical :: map_axis = .true.
   end type param_info_t

   !> The description of one model.
   type :: model_info_t
      character(len=:), allocatable :: name         !! the name --model takes
      character(len=:), allocatable :: summary      !! one line
      character(len=:), allocatable :: coordinates  !! names and units of q
      character(len=:), allocatable :: supports     !! capabilities, one line
      character(len=:), allocatable :: bodies       !! its named bodies ('' : none)
      type(param_info_t), allocatable :: params(:)  !! its parameters
      logical :: torques = .false.                  !! takes applied joint torques
   end type model_info_t

contains

   ! ------------------------------------------------------------- the catalogue

   !> Every model dpend can build, described.
   function model_catalogue() result(models)
      type(model_info_t), allocatable :: models(:)
      models = [pendulum_info(), elastic_info()]
   end function model_catalogue

   !> The chapter's pendulum: N rigid uniform rods (N = 2: the double pendulum),
   !> optional joint damping and a moving support.
   function pendulum_info() result(info)
      type(model_info_t) :: info
      info%name = 'pendulum'
      info%summary = 'N links hinged in a chain: uniform rods (N = 2: the chapter''s ' &
                     //'compound double pendulum), point masses or any body; optional ' &
                     //'joint damping and a moving support'
      info%bodies = body_text()
      info%coordinates = 'q_i: angle of link i from the horizontal x axis, counter-' &
                         //'clockwise (rad), i = 1..N; hanging: q_i = -pi/2'
      info%supports = 'Hamiltonian structure (no damping, fixed support; motors keep ' &
                      //'it), damping, driving (moving support), applied joint torques, ' &
                      //'motors (rotor inertia, gear ratio), SIMD sweep lanes (2 to 8 ' &
                      //'links, without motors), Poincare sections (2 links, conservative, ' &
                      //'without motors)'
      info%torques = .true.
      info%params = [ &
         param('links', '', 'number of links N', 1.0_dp, real(max_dof, dp), 2.0_dp, 1, &
               .true.), &
         param('m', 'kg', 'link masses m_i', min_mass, max_mass, &
               1.0_dp, -1), &
         param('l', 'm', 'link lengths l_i', min_length, max_length, &
               1.0_dp, -1), &
         param('g', 'm/s^2', 'gravitational acceleration (-y)', min_g, max_g, 9.8_dp, 1), &
         param('damping', 'N m s', 'joint damping c_i', 0.0_dp, &
               max_damping, 0.0_dp, -1, map_axis=.false.), &
         param('coulomb', 'N m', 'Coulomb joint friction c_f,i, smoothed: c_f,i tanh(w_i/v_s) ' &
               //'against the joint''s relative rate w_i', 0.0_dp, max_torque, 0.0_dp, -1, &
               map_axis=.false.), &
         param('coulomb_speed', 'rad/s', 'the Coulomb friction''s smoothing speed v_s (a link ' &
               //'held below c_f creeps at most at about v_s)', min_coulomb_speed, &
               max_coulomb_speed, 1e-3_dp, 1, map_axis=.false.), &
         param('rotor_inertia', 'kg m^2', 'rotor inertia I_r,i of the motor at joint i ' &
               //'(its stator on link i-1): adds g_r,i^2 I_r,i to the inertia of the ' &
               //'relative rate w_i', 0.0_dp, max_rotor_inertia, 0.0_dp, -1, &
               map_axis=.false.), &
         param('gear_ratio', '', 'gear ratio g_r,i of the motor at joint i (rotor speed / ' &
               //'joint speed)', min_gear_ratio, max_gear_ratio, 1.0_dp, -1, &
               map_axis=.false.), &
         param('support_amplitude', 'm', 'support motion amplitudes a_x, a_y', &
               -max_support_amplitude, max_support_amplitude, 0.0_dp, 2, map_axis=.false.), &
         param('support_frequency', 'rad/s', 'support motion angular frequency', 0.0_dp, &
               max_support_frequency, 0.0_dp, 1, map_axis=.false.), &
         param('support_phase', 'rad', 'support motion phases phi_x, phi_y', -max_angle, &
               max_angle, 0.0_dp, 2, map_axis=.false.), &
         param('com', 'm', 'distance d_i from joint i to the centre of mass of link i, ' &
               //'along the link (default l_i/2: a uniform rod; d_i > l_i: a bob beyond ' &
               //'the next pin)', 0.0_dp, max_length, 0.5_dp, -1), &
         param('inertia', 'kg m^2', 'moment of inertia I_i of link i about its centre of ' &
               //'mass (default m_i l_i^2/12: a uniform rod; 0: a point mass)', 0.0_dp, &
               max_mass*max_length**2, 1.0_dp/12.0_dp, -1)]
   end function pendulum_info

   !> The elastic (spring) pendulum: a point mass on a massless spring.
   function elastic_info() result(info)
      type(model_info_t) :: info
      info%name = 'elastic'
      info%summary = 'a point mass m on a massless spring (stiffness k, rest length l0) ' &
                     //'hung from the pin A (docs/elastic.md)'
      info%bodies = ''
      info%coordinates = 'r: the spring length (m); phi: its angle from the horizontal x ' &
                         //'axis, counter-clockwise (rad); hanging: phi = -pi/2'
      info%supports = 'Hamiltonian structure (every method applies); sweep indicator maps ' &
                      //'(no flip map: no rods to flip); fit of k and l0; no damping, ' &
                      //'driving, SIMD lanes or Poincare sections'
      info%params = [ &
         param('m', 'kg', 'mass of the bob', min_mass, max_mass, 1.0_dp, 1), &
         param('k', 'N/m', 'stiffness of the spring', min_stiffness, max_stiffness, 40.0_dp, &
               1), &
         param('l0', 'm', 'rest length of the spring', min_length, max_length, 1.0_dp, 1), &
         param('g', 'm/s^2', 'gravitational acceleration (-y)', min_g, max_g, 9.8_dp, 1)]
   end function elastic_info

   !> A parameter description.
   pure function param(name, units, meaning, lower, upper, default, count, integer_valued, &
                       map_axis) result(p)
      character(len=*), intent(in) :: name, units, meaning  !! see param_info_t
      real(dp), intent(in) :: lower, upper, default         !! range and default
      integer, intent(in) :: count                          !! values (-1: per link)
      logical, intent(in), optional :: integer_valued       !! a count
      logical, intent(in), optional :: map_axis             !! may be a map's axis
      type(param_info_t) :: p
      p%name = name; p%units = units; p%meaning = meaning
      p%lower = lower; p%upper = upper; p%default = default; p%count = count
      if (present(integer_valued)) p%integer_valued = integer_valued
      if (present(map_axis)) p%map_axis = map_axis
   end function param

   !> Index of model `name` in the catalogue `models`, 0 if none.
   pure integer function find_model(models, name) result(k)
      type(model_info_t), intent(in) :: models(:)  !! the catalogue
      character(len=*), intent(in) :: name         !! model name
      do k = 1, size(models)
         if (models(k)%name == name) return
      end do
      k = 0
   end function find_model

   !> Whether the catalogue's model `model` has the parameter `name` (an unknown
   !> model: none).
   logical function has_parameter(model, name)
      character(len=*), intent(in) :: model  !! model name
      character(len=*), intent(in) :: name   !! parameter name
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      k = find_model(models, model)
      has_parameter = .false.
      if (k == 0) return
      has_parameter = any([(models(k)%params(i)%name == name, i=1, size(models(k)%params))])
   end function has_parameter

   ! ---------------------------------------------------------------- the factory

   !> Build the model `spec` asks for, after checking every parameter given against
   !> the model's description (a known name, the right number of values, each in
   !> range). Refusals name the parameter, its value and the accepted range.
   subroutine new_model(spec, model, error)
      type(model_spec_t), intent(in) :: spec                 !! what to build
      class(model_t), allocatable, intent(out) :: model      !! the model built
      type(error_t), allocatable, intent(out) :: error       !! set when refused
      type(model_info_t), allocatable :: models(:)
      integer :: k
      character(len=:), allocatable :: hint
      models = model_catalogue()
      k = find_model(models, spec%model_name())
      if (k == 0) then
         hint = did_you_mean(spec%model_name(), model_list(models), '; ')
         call fatal_error(error, "invalid model: '"//spec%model_name()//"' is not a model " &
                          //'(accepted: '//model_list(models)//'; dpend models describes ' &
                          //'them)'//hint)
         return
      end if
      call check_spec(spec, models(k), error)
      if (allocated(error)) return
      call build(spec, models(k), model, error)
   end subroutine new_model

   !> The models' names, comma-separated.
   function model_list(models) result(s)
      type(model_info_t), intent(in) :: models(:)  !! the catalogue
      character(len=:), allocatable :: s
      integer :: k
      s = models(1)%name
      do k = 2, size(models)
         s = s//', '//models(k)%name
      end do
   end function model_list

   !> Every parameter given is one of the model's, with as many values as it takes,
   !> each within its range (integers where a count is asked).
   subroutine check_spec(spec, info, error)
      type(model_spec_t), intent(in) :: spec            !! what to build
      type(model_info_t), intent(in) :: info            !! the model's description
      type(error_t), allocatable, intent(out) :: error  !! first violation
      integer :: i, j, k, want
      if (spec%torque%active() .and. .not. info%torques) then
         call fatal_error(error, 'invalid torque: model '//info%name//' has no joints to ' &
                          //'apply torques to (model pendulum takes them)')
         return
      end if
      if (allocated(spec%items)) then
         do i = 1, size(spec%items)
            k = param_index(info, spec%items(i)%name)
            if (k == 0) then
               call fatal_error(error, 'invalid '//spec%items(i)%name//': not a parameter ' &
                                //'of model '//info%name//' (its parameters: ' &
                                //param_list(info)//')')
               return
            end if
         end do
      end if
      do k = 1, size(info%params)
         associate (p => info%params(k))
            i = spec%find(p%name)
            if (i == 0) cycle
            associate (v => spec%items(i)%values)
               want = p%count
               if (want < 0) want = n_links(spec, info)  ! 'links' comes first: checked
               if (size(v) /= want) then
                  call fatal_error(error, 'invalid '//p%name//': '//to_str(size(v))// &
                                   ' values, model '//info%name//' takes '//count_text(p, want))
                  return
               end if
               ! a count here; every other value is checked by the model's constructor
               ! (its messages name the element: m2, damping c1, support_amplitude a_x)
               if (p%integer_valued) then
                  do j = 1, size(v)
                     call check_value(element_name(p, j, size(v)), v(j), p, error)
                     if (allocated(error)) return
                  end do
               end if
            end associate
         end associate
      end do
   end subroutine check_spec

   !> The name of value j of parameter p in messages: 'm2' for a per-link list,
   !> 'support_amplitude 2' for a pair, the name for a scalar.
   pure function element_name(p, j, n) result(s)
      type(param_info_t), intent(in) :: p  !! the parameter
      integer, intent(in) :: j, n          !! which value, of how many
      character(len=:), allocatable :: s
      if (p%count < 0) then
         s = p%name//to_str(j)
      else if (n > 1) then
         s = p%name//' '//to_str(j)
      else
         s = p%name
      end if
   end function element_name

   !> 'one per link (3)', '2 (x, y)' or '1'.
   pure function count_text(p, want) result(s)
      type(param_info_t), intent(in) :: p  !! the parameter
      integer, intent(in) :: want          !! values expected
      character(len=:), allocatable :: s
      if (p%count < 0) then
         s = 'one per link ('//to_str(want)//')'
      else
         s = to_str(want)
      end if
   end function count_text

   !> `x` within p's range (and integer-valued for a count).
   subroutine check_value(field, x, p, error)
      character(len=*), intent(in) :: field             !! name in the message
      real(dp), intent(in) :: x                         !! the value
      type(param_info_t), intent(in) :: p               !! its description
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      character(len=:), allocatable :: u
      u = ''
      if (len(p%units) > 0) u = ' '//p%units
      if (.not. (x >= p%lower .and. x <= p%upper)) then
         call fatal_error(error, 'invalid '//field//': '//real_str(x)//u//' is outside [' &
                          //real_str(p%lower)//', '//real_str(p%upper)//']')
      else if (p%integer_valued .and. x /= aint(x)) then
         call fatal_error(error, 'invalid '//field//': '//real_str(x)//' is not an integer')
      end if
   end subroutine check_value

   !> Index of parameter `name` in `info`, 0 if none.
   pure integer function param_index(info, name) result(k)
      type(model_info_t), intent(in) :: info  !! the model's description
      character(len=*), intent(in) :: name    !! parameter name
      do k = 1, size(info%params)
         if (info%params(k)%name == name) return
      end do
      k = 0
   end function param_index

   !> The parameters' names, comma-separated.
   function param_list(info) result(s)
      type(model_info_t), intent(in) :: info  !! the model's description
      character(len=:), allocatable :: s
      integer :: k
      s = info%params(1)%name
      do k = 2, size(info%params)
         s = s//', '//info%params(k)%name
      end do
   end function param_list

   !> The values of parameter `name` of the checked `spec`, or its default (repeated
   !> per link or per component).
   function value_of(spec, info, name, n) result(v)
      type(model_spec_t), intent(in) :: spec    !! what to build (checked)
      type(model_info_t), intent(in) :: info    !! the model's description
      character(len=*), intent(in) :: name      !! parameter name
      integer, intent(in) :: n                  !! number of links
      real(dp), allocatable :: v(:)
      integer :: k, want
      k = param_index(info, name)
      want = info%params(k)%count
      if (want < 0) want = n
      v = spec%get(name, spread(info%params(k)%default, 1, want))
   end function value_of

   !> The number of links of a model with a 'links' parameter (given or its
   !> default), 1 for other models. `spec`'s links is checked before use.
   function n_links(spec, info) result(n)
      type(model_spec_t), intent(in) :: spec  !! what to build
      type(model_info_t), intent(in) :: info  !! the model's description
      integer :: n
      real(dp), allocatable :: v(:)
      n = 1
      if (param_index(info, 'links') == 0) return
      v = value_of(spec, info, 'links', 1)
      n = nint(v(1))
   end function n_links

   !> Construct the checked model. One branch per model.
   subroutine build(spec, info, model, error)
      type(model_spec_t), intent(in) :: spec             !! what to build (checked)
      type(model_info_t), intent(in) :: info             !! its description
      class(model_t), allocatable, intent(out) :: model  !! the model built
      type(error_t), allocatable, intent(out) :: error   !! set when refused
      select case (info%name)
      case ('pendulum')
         call build_pendulum(spec, info, model, error)
      case ('elastic')
         block
            type(elastic_t) :: elastic
            real(dp), allocatable :: m(:), k(:), l0(:), g(:)
            m = value_of(spec, info, 'm', 1); k = value_of(spec, info, 'k', 1)
            l0 = value_of(spec, info, 'l0', 1); g = value_of(spec, info, 'g', 1)
            elastic = elastic_model(m(1), k(1), l0(1), g(1), error)
            if (.not. allocated(error)) allocate (model, source=elastic)
         end block
      case default
         call fatal_error(error, 'internal error: model '//info%name//' has no constructor')
      end select
   end subroutine build

   !> The chapter's pendulum: the double pendulum's own formulation for two links
   !> without damping, friction, support motion or torques (the fast path of every method), the
   !> chain otherwise.
   subroutine build_pendulum(spec, info, model, error)
      type(model_spec_t), intent(in) :: spec             !! what to build (checked)
      type(model_info_t), intent(in) :: info             !! its description
      class(model_t), allocatable, intent(out) :: model  !! the model built
      type(error_t), allocatable, intent(out) :: error   !! set when refused
      real(dp), allocatable :: m(:), l(:), c(:), g(:), a(:), w(:), phi(:), d(:), ic(:), &
                               cf(:), vs(:), ir(:), gr(:)
      integer :: n
      logical :: rod
      n = n_links(spec, info)
      m = value_of(spec, info, 'm', n)
      l = value_of(spec, info, 'l', n)
      g = value_of(spec, info, 'g', n)
      c = value_of(spec, info, 'damping', n)
      cf = value_of(spec, info, 'coulomb', n)
      vs = value_of(spec, info, 'coulomb_speed', n)
      ir = value_of(spec, info, 'rotor_inertia', n)
      gr = value_of(spec, info, 'gear_ratio', n)
      if (spec%find('gear_ratio') > 0 .and. spec%find('rotor_inertia') == 0) then
         call fatal_error(error, 'invalid gear_ratio: given without a rotor_inertia (it ' &
                          //'only scales the rotor''s inertia: g_r^2 I_r)')
         return
      end if
      a = value_of(spec, info, 'support_amplitude', n)
      w = value_of(spec, info, 'support_frequency', n)
      phi = value_of(spec, info, 'support_phase', n)
      ! the mass distribution: uniform rods unless com or inertia is given;
      ! then the one not given takes the rod's value (d_i = l_i/2, I_i = m_i l_i²/12)
      rod = spec%find('com') == 0 .and. spec%find('inertia') == 0
      block
         type(chain_t) :: chain
         type(pendulum_t) :: par
         ! the chain checks every parameter (also those the two-link form ignores)
         chain = chain_model(m, l, g(1), error, c, a, w(1), phi, torque=spec%torque, &
                             coulomb=cf, coulomb_speed=vs(1), rotor_inertia=ir, gear_ratio=gr)
         if (allocated(error)) return
         if (.not. rod) then   ! m and l checked: the defaults m l²/12 are finite
            if (spec%find('com') > 0) then
               d = spec%get('com', [0.0_dp])
            else
               d = 0.5_dp*l
            end if
            if (spec%find('inertia') > 0) then
               ic = spec%get('inertia', [0.0_dp])
            else
               ic = m*l**2/12.0_dp
            end if
            chain = chain_model(m, l, g(1), error, c, a, w(1), phi, d, ic, spec%torque, &
                                cf, vs(1), ir, gr)
            if (allocated(error)) return
         end if
         if (n == 2 .and. all(c == 0.0_dp) .and. all(a == 0.0_dp) .and. all(cf == 0.0_dp) &
             .and. .not. chain%motors .and. &
             .not. (spec%general .or. spec%torque%active())) then
            par = pendulum_t(m1=m(1), m2=m(2), l1=l(1), l2=l(2), g=g(1))
            if (.not. rod) then
               par%body = body_general
               par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
            end if
            allocate (model, source=pendulum_model(par))
         else
            allocate (model, source=chain)
         end if
      end block
   end subroutine build_pendulum

   ! ------------------------------------------------------------ the description

   !> `dpend models`: every model with its coordinates, parameters and capabilities.
   function describe_models() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      s = ''
      do k = 1, size(models)
         associate (m => models(k))
            if (k > 1) s = s//nl
            s = s//m%name//': '//m%summary//nl// &
                '  coordinates: '//m%coordinates//nl// &
                '  at rest:     '//rest_text(m%name)//nl// &
                '  supports:    '//m%supports//nl
            if (len(m%bodies) > 0) s = s//'  bodies:      '//m%bodies//nl
            s = s//'  parameters (flag --NAME with - for _, namelist key NAME):'//nl
            do i = 1, size(m%params)
               s = s//param_line(m%params(i))//nl
            end do
         end associate
      end do
      s = s(:len(s) - 1)
   end function describe_models

   !> The named bodies in words: '--body rod: uniform rods, ... (the default); --body
   !> point: ...; any other: --com and --inertia, one value per link'.
   function body_text() result(s)
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(body_names)
         s = s//'--body '//trim(body_names(i))//': '//trim(body_meanings(i))//'; '
      end do
      s = s//'any other body: --com and --inertia, one value per link'
   end function body_text

   !> The body names joined by `sep` (default ', '): 'rod, point', 'rod|point'.
   function body_list(sep) result(s)
      character(len=*), intent(in), optional :: sep  !! the separator
      character(len=:), allocatable :: s, between
      integer :: i
      between = ', '
      if (present(sep)) between = sep
      s = trim(body_names(1))
      do i = 2, size(body_names)
         s = s//between//trim(body_names(i))
      end do
   end function body_list

   !> The state of rest of the model's defaults: 'q = -1.5707963267948966,
   !> -1.5707963267948966 (--q of the defaults' state of rest)'.
   function rest_text(name) result(s)
      character(len=*), intent(in) :: name  !! model name
      character(len=:), allocatable :: s
      class(model_t), allocatable :: model
      type(error_t), allocatable :: error
      real(dp), allocatable :: q(:)
      integer :: i
      call new_model(model_spec(name), model, error)
      if (allocated(error)) then
         s = '(its defaults are refused: '//error%message//')'
         return
      end if
      allocate (q(model%n_dof()))
      call model%rest_state(q)
      s = 'q = '
      do i = 1, size(q)
         s = s//real_str(q(i))//merge(', ', '  ', i < size(q))
      end do
      s = trim(s)//" (--q of the defaults' state of rest)"
   end function rest_text

   !> '    m                  kg     [1e-6, 1e6]  default 1, one per link: meaning'.
   function param_line(p) result(s)
      type(param_info_t), intent(in) :: p  !! the parameter
      character(len=:), allocatable :: s, count
      select case (p%count)
      case (-1); count = ', one per link'
      case (1); count = ''
      case default; count = ', '//to_str(p%count)//' values'
      end select
      s = '    '//pad_to(p%name, 19)//pad_to(p%units, 7)//pad_to('['//real_str(p%lower) &
          //', '//real_str(p%upper)//']', 22)//'default '//real_str(p%default)//count &
          //': '//p%meaning
   end function param_line

   !> `text` padded with blanks to `width` columns (at least one blank).
   pure function pad_to(text, width) result(s)
      character(len=*), intent(in) :: text  !! text
      integer, intent(in) :: width          !! columns
      character(len=:), allocatable :: s
      s = text//repeat(' ', max(1, width - len(text)))
   end function pad_to

   ! ------------------------------------------------------ the specification type

   !> A specification of model `name` with no parameter given (all defaults).
   pure function model_spec(name) result(spec)
      character(len=*), intent(in) :: name  !! model name
      type(model_spec_t) :: spec
      spec%name = name
      allocate (spec%items(0))
   end function model_spec

   subroutine spec_set(self, name, values)
      class(model_spec_t), intent(inout) :: self  !! specification
      character(len=*), intent(in) :: name        !! parameter name
      real(dp), intent(in) :: values(:)           !! its value(s)
      type(spec_item_t), allocatable :: items(:)
      integer :: i
      i = self%find(name)
      if (i > 0) then
         self%items(i)%values = values
         return
      end if
      if (.not. allocated(self%items)) allocate (self%items(0))
      allocate (items(size(self%items) + 1))
      items(:size(self%items)) = self%items
      items(size(items))%name = name
      items(size(items))%values = values
      call move_alloc(items, self%items)
   end subroutine spec_set

   pure integer function spec_find(self, name) result(i)
      class(model_spec_t), intent(in) :: self  !! specification
      character(len=*), intent(in) :: name     !! parameter name
      if (allocated(self%items)) then
         do i = 1, size(self%items)
            if (self%items(i)%name == name) return
         end do
      end if
      i = 0
   end function spec_find

   pure function spec_get(self, name, default) result(v)
      class(model_spec_t), intent(in) :: self  !! specification
      character(len=*), intent(in) :: name     !! parameter name
      real(dp), intent(in) :: default(:)       !! values when not given
      real(dp), allocatable :: v(:)
      integer :: i
      i = self%find(name)
      if (i > 0) then
         v = self%items(i)%values
      else
         v = default
      end if
   end function spec_get

   pure function spec_model_name(self) result(name)
      class(model_spec_t), intent(in) :: self  !! specification
      character(len=:), allocatable :: name
      if (allocated(self%name)) then
         name = self%name
      else
         name = default_model
      end if
   end function spec_model_name
   ! ------------------------------------------ values a spec stands for (the fit)

   !> Whether parameter `name` is absent from `spec` and its value then follows other
   !> parameters (the pendulum's com = l_i/2 and inertia = m_i l_i²/12 of a uniform
   !> rod), so that its catalogue default is not its value.
   logical function derived_default(spec, name)
      type(model_spec_t), intent(in) :: spec  !! what to build
      character(len=*), intent(in) :: name    !! parameter name
      derived_default = spec%model_name() == 'pendulum' .and. spec%find(name) == 0 .and. &
                        (name == 'com' .or. name == 'inertia')
   end function derived_default

   !> The n values of parameter `name` that the model built from `spec` uses: the
   !> spec's, else the derived ones (`derived_default`), else the catalogue default.
   !> `spec` and `name` must be valid (a fit's checked spec and catalogue name).
   function spec_values(spec, name, n) result(v)
      type(model_spec_t), intent(in) :: spec  !! what to build
      character(len=*), intent(in) :: name    !! parameter name
      integer, intent(in) :: n                !! components wanted (links for lists)
      real(dp), allocatable :: v(:)
      type(model_info_t), allocatable :: models(:)
      real(dp), allocatable :: m(:), l(:)
      integer :: k, links
      models = model_catalogue()
      k = find_model(models, spec%model_name())
      if (derived_default(spec, name)) then
         links = n_links(spec, models(k))
         l = value_of(spec, models(k), 'l', links)
         if (name == 'com') then
            v = 0.5_dp*l
         else
            m = value_of(spec, models(k), 'm', links)
            v = m*l**2/12.0_dp
         end if
      else
         v = spec%get(name, spread(models(k)%params(param_index(models(k), name))%default, &
                                   1, n))
      end if
   end function spec_values
end module dpend_model_factory
