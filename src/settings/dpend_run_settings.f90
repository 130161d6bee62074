!> The settings of one run, shared by every command and by library callers: the
!> model's parameters (per link, or by name for other models), the initial state,
!> the method and its options, the output file. `validate_run_config` checks every
!> field against its range (dpend_limits) and builds the model through the factory
!> (dpend_model_factory); before that, `model` is not allocated. The command line
!> fills these records through dpend_namelist (--config FILE) and dpend_run_flags.
module dpend_run_settings
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_pendulum, only: pendulum_t, body_general
   use dpend_limits, only: finite_positive
   use dpend_model_factory, only: model_spec_t, model_spec, model_info_t, new_model, &
      model_catalogue, find_model, default_model, has_parameter, body_names, body_list
   use dpend_model, only: model_t, max_dof
   use dpend_cli, only: to_str, to_lower, printable, real_str
   use dpend_limits, only: in_range, check_range, check_count, max_angle, max_time, max_dt, &
      min_rtol, min_atol, max_atol, max_omega, max_steps, default_max_steps, sci, &
      max_support_frequency
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_joint_torque, only: joint_torque_t, torque_series
   use dpend_csv, only: series_t, read_series
   use dpend_output, only: register_input
   use dpend_angle_convention, only: to_absolute, rates_to_absolute
   implicit none
   private
   public :: run_config_t, validate_run_config, set_pendulum, set_body, model_names, &
      is_model_parameter, list_names, mark_given, unused_setting, natural_time, &
      natural_unit_name, time_text, time_in_unit, span_text, time_unit_option_help, &
      read_torque_file

   !> Settings of the pendulum's links and their parameter in the model catalogue: a
   !> setting given for a model without that parameter is refused. The second link's
   !> values and the angles from the hanging position need links.
   character(len=*), parameter :: link_settings(2, 11) = reshape([character(len=17) :: &
      'links', 'links', 'l', 'l', 'l1', 'l', 'l2', 'l', 'm2', 'links', 'theta1', 'links', &
      'theta2', 'links', 'damping', 'damping', 'support_amplitude', 'support_amplitude', &
      'support_frequency', 'support_frequency', 'support_phase', 'support_phase'], [2, 11])

   !> The lists a user may give (--m --l --q --w, namelist m l q w), in this order.
   character(len=1), parameter :: list_names(4) = ['m', 'l', 'q', 'w']

   !> Everything a single run needs (SI units, angles in rad from the horizontal x axis).
   !> Per-link values are kept for max_dof links; the first `links` are used.
   type :: run_config_t
      integer :: links = 2                     !! number of links N
      real(dp) :: m(max_dof) = 1.0_dp          !! link masses [kg]
      real(dp) :: l(max_dof) = 1.0_dp          !! link lengths [m]
      real(dp) :: g = 9.8_dp                   !! gravitational acceleration [m/s²]
      real(dp) :: q(max_dof) = 0.0_dp          !! initial angles [rad]
      real(dp) :: w(max_dof) = 0.0_dp          !! initial angular velocities [rad/s]
      !> Lengths of the lists given for m, l, q, w (0: none given); each must be N.
      integer :: list_size(4) = 0
      !> Joint damping c_i [N m s] and the number of values given (0: none).
      real(dp) :: damping(max_dof) = 0.0_dp
      integer :: damping_size = 0
      !> The support's motion x_A = a_x cos(ω t + φ_x), y_A = a_y cos(ω t + φ_y):
      !> amplitudes (a_x, a_y) [m], ω [rad/s], phases (φ_x, φ_y) [rad]; zero: fixed pin.
      real(dp) :: support_amplitude(2) = 0.0_dp
      real(dp) :: support_frequency = 0.0_dp
      real(dp) :: support_phase(2) = 0.0_dp
      !> Applied joint torques: the torque file (columns t, tau1 … tauN; '' or unset:
      !> none), read by `validate_run_config` into `torque`; a library caller may set
      !> `torque` itself (a series or a closed form) and leave the file unset.
      character(len=:), allocatable :: torque_file
      type(joint_torque_t) :: torque
      class(model_t), allocatable :: model     !! the system, built by validate_run_config
      character(len=:), allocatable :: method  !! integrator name
      real(dp) :: dt = 1e-3_dp                 !! step (initial step for adaptive) [s]
      real(dp) :: t_end = 10.0_dp              !! end time [s]
      integer :: save_every = 10               !! keep every N-th step
      real(dp) :: rtol = 1e-9_dp               !! relative tolerance (adaptive methods)
      real(dp) :: atol = 1e-12_dp              !! absolute tolerance (adaptive methods)
      real(dp) :: output_dt = 0.0_dp           !! sample at k·output_dt (0: every save_every steps) [s]
      !> The unit of the times given (dt, t_end, output_dt and a command's own: tau,
      !> pair spacing, fit window): 's' or 'natural', the model's √(l1/g) (√(l0/g) for
      !> the elastic pendulum). `validate_run_config` converts them to seconds once
      !> (`time_scale`, `in_seconds`); a sweep keeps them in the unit its file records.
      character(len=7) :: time_unit = 's'
      real(dp) :: time_scale = 1.0_dp          !! seconds per unit of the times given
      logical :: times_resolved = .false.      !! dt, t_end, output_dt are in seconds
      !> The convention of the initial angles and rates given (q, w; `--angles`):
      !> 'absolute' (the chapter's, from the horizontal x axis) or 'relative' (the
      !> robotics convention, φ_1 = q_1 + π/2, φ_i = q_i − q_(i−1)), converted to
      !> absolute once by `validate_run_config` (`angles_resolved`).
      character(len=8) :: initial_angles = 'absolute'
      logical :: angles_resolved = .false.
      !> the span [s] the torques must cover when it is not [0, t_end] (a fit: the
      !> data's times); unset when torque_span(2) < torque_span(1)
      real(dp) :: torque_span(2) = [0.0_dp, -1.0_dp]
      real(dp) :: omega = 20.0_dp              !! Tao's binding constant [1/s]
      integer(i8) :: max_steps = default_max_steps !! most accepted steps of one
                                               !! integration (adaptive methods)
      character(len=:), allocatable :: output  !! output file
      logical :: force = .false.               !! overwrite an existing output file
      !> The per-link flags given so far (' --m1 --q '), so that two forms of one
      !> quantity on the command line are refused (`apply_run_flag`).
      character(len=:), allocatable :: flags_seen
      !> The model (--model; unset: the factory's default, the chapter's pendulum),
      !> the parameters of models other than the pendulum given by name (--k 40), and
      !> the specification the model was built from (validate_run_config).
      character(len=:), allocatable :: model_name
      type(model_spec_t) :: extra
      type(model_spec_t) :: spec
      !> The scalar keys a namelist file gave (' q1 save_every '),
      !> so that a command refuses a fixed value it sweeps or two forms of one setting.
      character(len=:), allocatable :: nml_given
      !> The links' body: '' (not given: uniform rods unless --com or
      !> --inertia), 'rod' or 'point' (--body / &pendulum body)
      character(len=:), allocatable :: body
      !> Every setting given by a flag or the namelist file, by its key (' m2 l1
      !> theta1 support_frequency '): one the model has no parameter for is refused
      !> (`build_model`), never dropped.
      character(len=:), allocatable :: given
   contains
      !> Initial coordinates q(1:n) [rad for angles], n those of the model (`n_coords`).
      procedure :: q0 => run_q0
      !> Initial rates w(1:n) [rad/s for angles].
      procedure :: w0 => run_w0
      !> The model's coordinates n once it is built (`validate_run_config`), else N.
      procedure :: n_coords => run_n_coords
      !> The double pendulum's parameters (links 1 and 2, g).
      procedure :: pendulum => run_pendulum
      !> A time given in the run's unit, in seconds (once the model is built).
      procedure :: seconds => run_seconds
   end type run_config_t

contains

   pure function run_q0(self) result(q)
      class(run_config_t), intent(in) :: self  !! configuration
      real(dp), allocatable :: q(:)
      q = self%q(:self%n_coords())
   end function run_q0

   pure function run_w0(self) result(w)
      class(run_config_t), intent(in) :: self  !! configuration
      real(dp), allocatable :: w(:)
      w = self%w(:self%n_coords())
   end function run_w0

   !> The coordinates of the built model (its n_dof: N links, the elastic pendulum's
   !> 2, a model of one coordinate's 1), else the links N: `links` keeps its default
   !> 2 for a model without links, which need not have two coordinates.
   pure integer function run_n_coords(self) result(n)
      class(run_config_t), intent(in) :: self  !! configuration
      if (allocated(self%model)) then
         n = self%model%n_dof()
      else
         n = self%links
      end if
   end function run_n_coords

   pure function run_pendulum(self) result(par)
      class(run_config_t), intent(in) :: self  !! configuration
      type(pendulum_t) :: par
      par = pendulum_t(m1=self%m(1), m2=self%m(2), l1=self%l(1), l2=self%l(2), g=self%g)
      ! links other than uniform rods: com and inertia as the model was built
      if (self%spec%find('com') > 0 .or. self%spec%find('inertia') > 0) then
         block
            real(dp), allocatable :: d(:), ic(:)
            d = 0.5_dp*self%l(1:2)
            if (self%spec%find('com') > 0) d = self%spec%get('com', d)
            ic = [0.0_dp, 0.0_dp]
            if (self%spec%find('inertia') > 0) then
               ic = self%spec%get('inertia', ic)
            else   ! the model was built: l is within its range, m l²/12 finite
               ic = self%m(1:2)*self%l(1:2)**2/12.0_dp
            end if
            if (size(d) == 2 .and. size(ic) == 2) then
               par%body = body_general
               par%d1 = d(1); par%d2 = d(2); par%i1 = ic(1); par%i2 = ic(2)
            end if
         end block
      end if
   end function run_pendulum

   !> A time `t` given in the run's unit (`time_unit`), in seconds: t·time_scale,
   !> bounded by ±huge (refused then by the range checks) instead of overflowing.
   pure real(dp) function run_seconds(self, t) result(s)
      class(run_config_t), intent(in) :: self  !! configuration, times resolved
      real(dp), intent(in) :: t                !! time in the unit given
      s = t
      if (self%time_scale == 1.0_dp) return
      ! (huge/scale overflows for a scale below 1, where t·scale cannot; nested, as
      ! Fortran may evaluate both operands of .and.)
      if (self%time_scale > 1.0_dp) then
         if (abs(t) > huge(1.0_dp)/self%time_scale) then
            s = sign(huge(1.0_dp), t)
            return
         end if
      end if
      s = t*self%time_scale
   end function run_seconds

   !> The natural time unit [s] of the built model: √(l1/g) of the configured l1
   !> for the pendulum of any N, √(l0/g) for the elastic pendulum.
   real(dp) function natural_time(cfg)
      type(run_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: name
      call cfg%model%time_unit(natural_time, name)
   end function natural_time

   !> The name of the natural time unit of the built model, e.g. 'sqrt(l1/g)'.
   function natural_unit_name(cfg) result(name)
      type(run_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: name
      real(dp) :: seconds
      call cfg%model%time_unit(seconds, name)
   end function natural_unit_name

   !> A time [s] in both units, the run's unit first: '50 s = 156.5 sqrt(l1/g)', or
   !> with time_unit natural '156.5 sqrt(l1/g) = 50 s' (4 digits each).
   function time_text(cfg, t) result(s)
      type(run_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: t              !! time [s]
      character(len=:), allocatable :: s
      if (trim(cfg%time_unit) == 'natural') then
         s = time_in_unit(cfg, t, 4)//' = '//real_str(t, 4)//' s'
      else
         s = time_in_unit(cfg, t, 4)//' = '//real_str(t/natural_time(cfg), 4)//' '// &
             natural_unit_name(cfg)
      end if
   end function time_text

   !> A span [a, b] s in both units, the run's first, to 4 digits: '1.22 .. 8.229 s =
   !> 3.82 .. 25.76 sqrt(l1/g)', or with time_unit natural '3.82 .. 25.76 sqrt(l1/g) =
   !> 1.22 .. 8.229 s'.
   function span_text(cfg, a, b) result(s)
      type(run_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: a, b           !! the span's ends [s]
      character(len=:), allocatable :: s
      real(dp) :: tn
      character(len=:), allocatable :: nat
      tn = natural_time(cfg)
      s = real_str(a, 4)//' .. '//real_str(b, 4)//' s'
      nat = real_str(a/tn, 4)//' .. '//real_str(b/tn, 4)//' '//natural_unit_name(cfg)
      if (trim(cfg%time_unit) == 'natural') then
         s = nat//' = '//s
      else
         s = s//' = '//nat
      end if
   end function span_text

   !> A time [s] in the run's unit, to 6 digits (or `digits`): '0.001 s' or '0.00313
   !> sqrt(l1/g)'.
   function time_in_unit(cfg, t, digits) result(s)
      type(run_config_t), intent(in) :: cfg  !! configuration, model built
      real(dp), intent(in) :: t              !! time [s]
      integer, intent(in), optional :: digits  !! significant digits (default 6)
      character(len=:), allocatable :: s
      integer :: d
      d = 6
      if (present(digits)) d = digits
      if (trim(cfg%time_unit) == 'natural') then
         s = real_str(t/natural_time(cfg), d)//' '//natural_unit_name(cfg)
      else
         s = real_str(t, d)//' s'
      end if
   end function time_in_unit

   !> The help line of --time-unit, for every command that takes times.
   pure function time_unit_option_help(default) result(s)
      character(len=*), intent(in) :: default  !! the command's default unit
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = '  --time-unit U     unit of the times given and reported first: s or natural'// &
          nl//'                    (sqrt(l1/g), sqrt(l0/g) for the elastic pendulum; rates'// &
          nl//'                    stay in 1/s); default '//default
   end function time_unit_option_help

   !> Set the parameters of the double pendulum (two links) from `par`.
   pure subroutine set_pendulum(cfg, par)
      type(run_config_t), intent(inout) :: cfg  !! configuration
      type(pendulum_t), intent(in) :: par       !! parameters
      cfg%m(1:2) = [par%m1, par%m2]; cfg%l(1:2) = [par%l1, par%l2]; cfg%g = par%g
   end subroutine set_pendulum

   !> Check the whole configuration; messages name the field and the accepted range
   !> (the limits and their reasons are in `dpend_limits`). For a fixed-step method
   !> the number of steps t_end/dt is at most `max_steps`; an adaptive method stops
   !> after `max_steps` accepted steps instead (`--max-steps`).
   !> Builds `cfg%model` (the double pendulum for two links, the chain otherwise).
   subroutine validate_run_config(cfg, error, initial_state, keep_time_unit)
      type(run_config_t), intent(inout) :: cfg          !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      !> whether the run starts from the configured state (default true; false for a
      !> sweep of a list, whose rows give every initial state)
      logical, intent(in), optional :: initial_state
      !> keep dt and t_end in the unit given (a sweep; default false: in seconds)
      logical, intent(in), optional :: keep_time_unit
      class(integrator_t), allocatable :: integ
      integer :: i, n
      if (allocated(cfg%model)) deallocate (cfg%model)
      call check_range('links', real(cfg%links, dp), 1.0_dp, real(max_dof, dp), '', error)
      if (allocated(error)) return
      n = cfg%links
      do i = 1, merge(2, 0, model_has(cfg, 'links'))   ! m and l: one per link
         if (cfg%list_size(i) /= 0 .and. cfg%list_size(i) /= n) then
            call fatal_error(error, 'invalid '//list_names(i)//': '// &
                             to_str(cfg%list_size(i))//' values for '//to_str(n)// &
                             ' links (one per link; --links N sets N) [--'//list_names(i)// &
                             ' / namelist '//list_names(i)//']')
            return
         end if
      end do
      ! (a model without links refuses the damping by name, in build_model)
      if (model_has(cfg, 'links') .and. cfg%damping_size /= 0 .and. cfg%damping_size /= n) then
         call fatal_error(error, 'invalid damping: '//to_str(cfg%damping_size)// &
                          ' values for '//to_str(n)//' links (one per joint; --links N ' &
                          //'sets N) [--damping / namelist damping]')
         return
      end if
      call check_range('support_frequency', cfg%support_frequency, 0.0_dp, &
                       max_support_frequency, 'rad/s', error)
      if (allocated(error)) return
      do i = 1, 2
         call check_range('support_phase '//merge('phi_x', 'phi_y', i == 1), &
                          cfg%support_phase(i), -max_angle, max_angle, 'rad', error)
         if (allocated(error)) return
      end do
      call read_torques(cfg, error)
      if (allocated(error)) return
      call build_model(cfg, error)
      if (allocated(error)) return
      call resolve_times(cfg, error, keep_time_unit)
      if (allocated(error)) return
      call check_torque_span(cfg, error)
      if (allocated(error)) return
      call resolve_initial_angles(cfg, error)
      if (allocated(error)) return
      if (.not. present(initial_state)) then
         call check_initial_state(cfg, error)
      else if (initial_state) then
         call check_initial_state(cfg, error)
      end if
      if (allocated(error)) then
         if (cfg%initial_angles == 'relative') error%message = error%message// &
            ' (the absolute value of the relative angles and rates given: --angles relative)'
         return
      end if
      if (.not. allocated(cfg%method)) then
         call fatal_error(error, 'invalid method: none given')
         return
      end if
      call new_integrator(cfg%method, integ, error)
      if (allocated(error)) return
      call integ%check_model(cfg%model, error)   ! e.g. a canonical method, no Hamiltonian
      if (allocated(error)) return
      call check_times(cfg, integ%adaptive(), error)
      if (allocated(error)) return
      if (cfg%save_every < 1) then
         call fatal_error(error, 'invalid save_every: '//sci(real(cfg%save_every, dp))// &
                          ' must be an integer >= 1')
      else if (.not. finite_positive(cfg%rtol) .or. .not. finite_positive(1.0_dp - cfg%rtol)) &
         then
         call fatal_error(error, 'invalid rtol: must be in ['//sci(min_rtol)//', 1)')
      else if (cfg%rtol < min_rtol) then
         call fatal_error(error, 'invalid rtol: '//sci(cfg%rtol)//' is below '//sci(min_rtol) &
                          //' (double precision cannot honour it: the error estimate is '// &
                          'dominated by rounding and the step shrinks until it stalls)')
      else if (.not. in_range(cfg%atol, min_atol, max_atol)) then
         call fatal_error(error, 'invalid atol: must be in ['//sci(min_atol)//', ' &
                          //sci(max_atol)//'] (rad, rad/s)')
      else if (.not. (finite_positive(cfg%omega) .and. in_range(cfg%omega, 0.0_dp, max_omega))) &
         then
         call fatal_error(error, 'invalid omega: must be in (0, '//sci(max_omega)//'] (1/s)')
      else if (cfg%max_steps < 1 .or. cfg%max_steps > max_steps) then
         call fatal_error(error, 'invalid max_steps: must be an integer from 1 to ' &
                          //sci(real(max_steps, dp))//' (steps)')
      end if
   end subroutine validate_run_config

   !> Read the torque file (`cfg%torque_file`, if given) into `cfg%torque`: a CSV
   !> series (dpend_csv's format) with the columns t [s] and tau1 … tauN [N m], one per
   !> joint; every value checked (`torque_series`), refusals naming the file and line.
   subroutine read_torques(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration; torque set
      type(error_t), allocatable, intent(out) :: error  !! unreadable, refused
      if (.not. allocated(cfg%torque_file)) return
      if (len(cfg%torque_file) == 0) return
      if (.not. model_torques(cfg)) then
         call fatal_error(error, 'invalid torque_file: model '//model_asked(cfg)// &
                          ' has no joints to apply torques to (model pendulum takes them)')
         return
      end if
      call read_torque_file(cfg%torque_file, cfg%links, cfg%torque, error)
   end subroutine read_torques

   !> Read a torque file of `n` joints into `torque`: a CSV series (dpend_csv's format)
   !> with the columns t [s] and tau1 … tauN [N m]; every value checked
   !> (`torque_series`), refusals naming the file and the line. The file is registered
   !> as an input of the run (no output replaces it).
   subroutine read_torque_file(path, n, torque, error)
      character(len=*), intent(in) :: path              !! the torque file
      integer, intent(in) :: n                          !! joints N
      type(joint_torque_t), intent(out) :: torque       !! the series read
      type(error_t), allocatable, intent(out) :: error  !! unreadable, refused
      type(series_t) :: series
      character(len=16), allocatable :: names(:), units(:)
      integer :: i
      allocate (names(n), units(n))
      do i = 1, n
         names(i) = 'tau'//to_str(i)
         units(i) = 'N m'
      end do
      call register_input(path)   ! no output of the run replaces it
      call read_series(path, series, error, names, units, what='the joint torques')
      if (allocated(error)) then
         error%message = replace_lead(error%message)
         return
      end if
      torque = torque_series(series%t, series%q, error)
      if (allocated(error)) then
         if (index(error%message, 'invalid torque series: ') == 1) &
            error%message = "invalid torque file '"//printable(path)//"': "// &
                            error%message(len('invalid torque series: ') + 1:)
      end if
   contains
      !> 'invalid data file' → 'invalid torque file' (the reader is the fit's too).
      function replace_lead(message) result(m)
         character(len=*), intent(in) :: message
         character(len=:), allocatable :: m
         if (index(message, 'invalid data file') == 1) then
            m = 'invalid torque file'//message(len('invalid data file') + 1:)
         else
            m = message
         end if
      end function replace_lead
   end subroutine read_torque_file

   !> Whether the model asked for takes applied joint torques (its description).
   logical function model_torques(cfg)
      type(run_config_t), intent(in) :: cfg  !! configuration
      type(model_info_t), allocatable :: models(:)
      integer :: k
      models = model_catalogue()
      k = find_model(models, model_asked(cfg))
      model_torques = .false.
      if (k > 0) model_torques = models(k)%torques
   end function model_torques

   !> The torques are defined over the whole run [0, t_end] (a series does not
   !> extrapolate); t_end in seconds or, kept in the natural unit, converted.
   subroutine check_torque_span(cfg, error)
      type(run_config_t), intent(in) :: cfg             !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! the span not covered
      real(dp) :: t_end, scale
      if (.not. cfg%torque%active()) return
      if (cfg%torque_span(2) >= cfg%torque_span(1)) then
         if (cfg%torque%covers(cfg%torque_span(1), cfg%torque_span(2))) return
         call fatal_error(error, 'invalid torque_file: the data span ['// &
                          sci(cfg%torque_span(1), 6)//', '//sci(cfg%torque_span(2), 6)// &
                          '] s, the torques are '//cfg%torque%text()//' (a series is ' &
                          //'not extrapolated: give samples over the whole data)')
         return
      end if
      t_end = cfg%t_end
      if (.not. cfg%times_resolved .and. trim(cfg%time_unit) == 'natural') then
         ! kept in the natural unit (a sweep): converted here, without overflow
         scale = natural_time(cfg)
         t_end = huge(1.0_dp)
         if (abs(cfg%t_end) <= huge(1.0_dp)/max(scale, 1.0_dp)) t_end = cfg%t_end*scale
      end if
      if (cfg%torque%covers(0.0_dp, t_end)) return
      call fatal_error(error, 'invalid t_end: the run spans [0, '//sci(t_end, 6)// &
                       '] s, the torques are '//cfg%torque%text()// &
                       ' (a series is not extrapolated: give samples from t <= 0 to t >= ' &
                       //'t_end)')
   end subroutine check_torque_span

   !> dt, t_end (and the steps they make for a fixed-step method) and output_dt, in
   !> seconds; with time_unit natural a refusal says what the unit was.
   subroutine check_times(cfg, adaptive, error)
      type(run_config_t), intent(in) :: cfg             !! configuration, times resolved
      logical, intent(in) :: adaptive                   !! the method adapts its step
      type(error_t), allocatable, intent(out) :: error  !! the first time refused
      if (.not. finite_positive(cfg%dt)) then
         call fatal_error(error, 'invalid dt: must be finite and > 0, at most '//sci(max_dt) &
                          //' s')
      else
         call check_range('dt', cfg%dt, 0.0_dp, max_dt, 's', error)
      end if
      if (.not. allocated(error)) call check_range('t_end', cfg%t_end, 0.0_dp, max_time, 's', &
                                                   error)
      if (.not. (allocated(error) .or. adaptive)) &
         call check_count('dt', cfg%dt, cfg%t_end, 't_end', max_steps, 'steps', &
                          'use a larger --dt or a shorter --t-end', error)
      if (allocated(error)) then
         continue
      else if (.not. (finite_positive(cfg%output_dt) .or. cfg%output_dt == 0.0_dp)) then
         call fatal_error(error, 'invalid output_dt: must be finite and >= 0 (s; 0 = off)')
      else if (cfg%output_dt > max_time) then
         call fatal_error(error, 'invalid output_dt: '//sci(cfg%output_dt)//' s is above ' &
                          //sci(max_time)//' s')
      end if
      if (allocated(error) .and. cfg%times_resolved .and. trim(cfg%time_unit) == 'natural') &
         error%message = error%message//' (given in '//natural_unit_name(cfg)//' = '// &
                         real_str(cfg%time_scale, 6)//' s: --time-unit natural)'
   end subroutine check_times

   !> Check the time unit and, unless kept, convert dt, t_end and output_dt from it
   !> to seconds, once (`times_resolved`); `time_scale` converts a command's own.
   subroutine resolve_times(cfg, error, keep_time_unit)
      type(run_config_t), intent(inout) :: cfg          !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! an unknown unit
      logical, intent(in), optional :: keep_time_unit   !! leave the times as given
      if (trim(cfg%time_unit) /= 's' .and. trim(cfg%time_unit) /= 'natural') then
         call fatal_error(error, "invalid time_unit: '"//printable(trim(cfg%time_unit))// &
                          "' (accepted: s, natural) [--time-unit / namelist " &
                          //'&integration time_unit]')
         return
      end if
      if (present(keep_time_unit)) then
         if (keep_time_unit) return
      end if
      if (cfg%times_resolved) return
      cfg%time_scale = 1.0_dp
      if (trim(cfg%time_unit) == 'natural') cfg%time_scale = natural_time(cfg)
      cfg%dt = cfg%seconds(cfg%dt)
      cfg%t_end = cfg%seconds(cfg%t_end)
      cfg%output_dt = cfg%seconds(cfg%output_dt)
      cfg%times_resolved = .true.
   end subroutine resolve_times

   !> Whether the model `cfg` asks for has the parameter `name` (the factory's
   !> catalogue; an unknown model: none).
   logical function model_has(cfg, name)
      type(run_config_t), intent(in) :: cfg  !! configuration
      character(len=*), intent(in) :: name   !! parameter name
      model_has = has_parameter(model_asked(cfg), name)
   end function model_has

   !> The model name --model gave (or &model name), else the factory's default.
   pure function model_asked(cfg) result(name)
      type(run_config_t), intent(in) :: cfg  !! configuration
      character(len=:), allocatable :: name
      if (allocated(cfg%model_name)) then
         name = cfg%model_name
      else
         name = default_model
      end if
   end function model_asked

   !> The names of the factory's models, blank-separated (for `canonical_name`).
   function model_names() result(s)
      character(len=:), allocatable :: s
      type(model_info_t), allocatable :: models(:)
      integer :: k
      models = model_catalogue()
      s = ''
      do k = 1, size(models)
         s = s//' '//models(k)%name
      end do
   end function model_names

   !> Whether `name` is a parameter of any model of the catalogue (a flag --NAME).
   logical function is_model_parameter(name, model)
      character(len=*), intent(in) :: name  !! parameter name
      !> only this model's parameters (default: any model of the catalogue)
      character(len=*), intent(in), optional :: model
      type(model_info_t), allocatable :: models(:)
      integer :: k, i
      models = model_catalogue()
      is_model_parameter = .false.
      do k = 1, size(models)
         if (present(model)) then
            if (models(k)%name /= model) cycle
         end if
         do i = 1, size(models(k)%params)
            if (models(k)%params(i)%name == name) is_model_parameter = .true.
         end do
      end do
   end function is_model_parameter

   !> The first setting given (`cfg%given`) that the model asked for has no parameter
   !> for ('' if none): the pendulum's links, lengths, second link, angles from the
   !> hanging position, damping and support motion (`link_settings`).
   function unused_setting(cfg) result(key)
      type(run_config_t), intent(in) :: cfg  !! configuration
      character(len=:), allocatable :: key
      integer :: i
      key = ''
      if (.not. allocated(cfg%given)) return
      do i = 1, size(link_settings, 2)
         if (index(cfg%given, ' '//trim(link_settings(1, i))//' ') == 0) cycle
         if (model_has(cfg, trim(link_settings(2, i)))) cycle
         key = trim(link_settings(1, i))
         return
      end do
   end function unused_setting

   !> Record that the setting `key` was given (by a flag or the namelist file).
   pure subroutine mark_given(cfg, key)
      type(run_config_t), intent(inout) :: cfg  !! cfg%given updated
      character(len=*), intent(in) :: key       !! e.g. 'support_frequency'
      if (.not. allocated(cfg%given)) cfg%given = ' '
      if (index(cfg%given, ' '//key//' ') == 0) cfg%given = cfg%given//key//' '
   end subroutine mark_given

   !> Build `cfg%model` through the factory (the one place a model is built): the
   !> specification holds the model's parameters from the run's fields (links, m, l,
   !> g, damping, support_*) and those given by name (--k); a field set for a model
   !> that has no such parameter is refused.
   subroutine build_model(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      type(model_info_t), allocatable :: models(:)
      integer :: k, i, n
      character(len=:), allocatable :: given
      models = model_catalogue()
      cfg%spec = model_spec(model_asked(cfg))
      k = find_model(models, model_asked(cfg))
      if (k > 0) then
         n = cfg%links
         do i = 1, size(models(k)%params)
            associate (p => models(k)%params(i))
               select case (p%name)
               case ('links'); call cfg%spec%set('links', [real(cfg%links, dp)])
               case ('m'); call cfg%spec%set('m', per_link(cfg%m, 1))
               case ('l'); call cfg%spec%set('l', per_link(cfg%l, 2))
               case ('g'); call cfg%spec%set('g', [cfg%g])
               case ('damping'); call cfg%spec%set('damping', cfg%damping(:n))
               case ('support_amplitude')
                  call cfg%spec%set('support_amplitude', cfg%support_amplitude)
               case ('support_frequency')
                  call cfg%spec%set('support_frequency', [cfg%support_frequency])
               case ('support_phase'); call cfg%spec%set('support_phase', cfg%support_phase)
               end select
            end associate
         end do
         ! the pendulum's settings given to a model without them
         given = ''
         if (cfg%links /= 2) given = 'links'
         if (cfg%list_size(2) > 0) given = 'l'
         if (cfg%damping_size > 0) given = 'damping'
         if (any(cfg%support_amplitude /= 0.0_dp)) given = 'support_amplitude'
         if (len(given) > 0) then
            if (model_has(cfg, given)) given = ''
         end if
         if (len(given) == 0) given = unused_setting(cfg)
         if (len(given) > 0) then
            call fatal_error(error, 'invalid '//given//': not a parameter of model ' &
                             //model_asked(cfg)//' (dpend models lists its parameters)')
            return
         end if
      end if
      if (allocated(cfg%extra%items)) then
         do i = 1, size(cfg%extra%items)
            call cfg%spec%set(cfg%extra%items(i)%name, cfg%extra%items(i)%values)
         end do
      end if
      call apply_body(cfg, error)
      if (allocated(error)) return
      cfg%spec%torque = cfg%torque
      call new_model(cfg%spec, cfg%model, error)
      if (allocated(error)) error%message = error%message//hint(error%message)
   contains
      !> The first n values of a per-link field, or its first value for a scalar
      !> parameter (refused later by the factory if a list was given).
      function per_link(values, list) result(v)
         real(dp), intent(in) :: values(:)
         integer, intent(in) :: list
         real(dp), allocatable :: v(:)
         if (model_has(cfg, 'links')) then
            v = values(:n)
         else
            v = values(:max(1, cfg%list_size(list)))
         end if
      end function per_link
      !> Where a refused parameter is set: its flags and namelist group.
      function hint(message) result(s)
         character(len=*), intent(in) :: message
         character(len=:), allocatable :: s
         if (index(message, 'invalid model') == 1 .or. &
             index(message, 'not a parameter of model') > 0) then
            s = ''
         else if (.not. model_has(cfg, 'links')) then
            s = ' [dpend models lists the parameters of '//model_asked(cfg)//']'
         else if (index(message, 'invalid damping') == 1) then
            s = ' [--damping / &pendulum damping]'
         else if (index(message, 'invalid coulomb') == 1) then
            s = ' [--coulomb --coulomb-speed / &model coulomb coulomb_speed]'
         else if (index(message, 'invalid rotor_inertia') == 1 .or. &
                  index(message, 'invalid gear_ratio') == 1) then
            s = ' [--rotor-inertia --gear-ratio / &model rotor_inertia gear_ratio]'
         else if (index(message, 'invalid com') == 1 .or. index(message, 'invalid inertia') &
                  == 1) then
            s = ' [--com --inertia --body / &pendulum com inertia body]'
         else if (index(message, 'invalid support') == 1) then
            s = ' [--support-amplitude --support-frequency --support-phase / &pendulum]'
         else if (n == 2) then
            s = ' [--m1 --m2 --l1 --l2 --g / &pendulum]'
         else
            s = ' [--m --l --g / &pendulum]'
         end if
      end function hint
   end subroutine build_model

   !> Initial angles and rates given in the relative convention (`initial_angles`),
   !> converted to the absolute ones once (`dpend_angle_convention`); refused for a
   !> model without links and beside --theta1/--theta2 (absolute from hanging).
   subroutine resolve_initial_angles(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! q, w converted
      type(error_t), allocatable, intent(out) :: error  !! not a chain, theta given
      integer :: n
      if (cfg%initial_angles /= 'relative' .or. cfg%angles_resolved) return
      if (.not. model_has(cfg, 'links')) then
         call fatal_error(error, 'invalid angles: relative needs links; model '// &
                          model_asked(cfg)//' has none [--angles]')
         return
      end if
      if (allocated(cfg%given)) then
         if (index(cfg%given, ' theta1 ') > 0 .or. index(cfg%given, ' theta2 ') > 0) then
            call fatal_error(error, 'invalid angles: relative with --theta1/--theta2 ' &
                             //'(absolute angles from the hanging position); give the ' &
                             //'relative angles by --q or --q1, --q2 [--angles]')
            return
         end if
      end if
      n = cfg%links
      block
         real(dp) :: state(n, 1)
         state(:, 1) = cfg%q(1:n)
         state = to_absolute(state)
         cfg%q(1:n) = state(:, 1)
         state(:, 1) = cfg%w(1:n)
         state = rates_to_absolute(state)
         cfg%w(1:n) = state(:, 1)
      end block
      cfg%angles_resolved = .true.
   end subroutine resolve_initial_angles

   !> The initial state: as many q and w as the model has coordinates, within what
   !> the model accepts (`check_state`: angles and angular velocities within 1e6 for
   !> the pendulum; the elastic pendulum's r above its collapse).
   subroutine check_initial_state(cfg, error)
      type(run_config_t), intent(in) :: cfg             !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: i, nd
      nd = cfg%model%n_dof()
      do i = 3, 4
         if (cfg%list_size(i) /= 0 .and. cfg%list_size(i) /= nd) then
            if (model_has(cfg, 'links')) then
               call fatal_error(error, 'invalid '//list_names(i)//': '// &
                                to_str(cfg%list_size(i))//' values for '//to_str(nd)// &
                                ' links (one per link; --links N sets N) [--'// &
                                list_names(i)//' / namelist '//list_names(i)//']')
            else
               call fatal_error(error, 'invalid '//list_names(i)//': '// &
                                to_str(cfg%list_size(i))//' values for the '//to_str(nd)// &
                                ' coordinates of model '//model_asked(cfg)//' [--' &
                                //list_names(i)//' / namelist '//list_names(i)//']')
            end if
            return
         end if
      end do
      call cfg%model%check_state(cfg%q(:nd), cfg%w(:nd), error)
   end subroutine check_initial_state

   !> `--body NAME` / `&pendulum body = 'NAME'`: rod or point, else refused.
   subroutine set_body(cfg, value, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%body set
      character(len=*), intent(in) :: value             !! the name given
      type(error_t), allocatable, intent(out) :: error  !! not a body
      if (any(body_names == to_lower(value))) then
         cfg%body = to_lower(value)
      else
         call fatal_error(error, "invalid body: '"//printable(value)//"' is not a body " &
                          //'(accepted: '//body_list()//'; --com and --inertia give any ' &
                          //'other) [--body / &pendulum body]')
      end if
   end subroutine set_body

   !> The body asked for into cfg%spec: 'point' sets com = l and inertia = 0, 'rod'
   !> leaves the rod's defaults; either is refused beside com or inertia (the two
   !> would contradict each other), and for a model without links' bodies.
   subroutine apply_body(cfg, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%spec updated
      type(error_t), allocatable, intent(out) :: error  !! a contradiction
      real(dp), allocatable :: l(:)
      character(len=:), allocatable :: given, sets
      if (.not. allocated(cfg%body)) return
      if (.not. model_has(cfg, 'com')) then
         call fatal_error(error, 'invalid body: not a parameter of model '//model_asked(cfg) &
                          //' (dpend models lists its parameters)')
         return
      end if
      given = ''
      if (cfg%spec%find('com') > 0) given = 'com'
      if (cfg%spec%find('inertia') > 0) then
         if (len(given) > 0) given = given//' and '
         given = given//'inertia'
      end if
      if (len(given) > 0) then
         if (cfg%body == 'rod') then
            sets = 'com = l_i/2 and inertia = m_i l_i^2/12'
         else
            sets = 'com = l_i and inertia = 0'
         end if
         call fatal_error(error, 'invalid body: '//cfg%body//' contradicts the '//given &
                          //' given (--body '//cfg%body//' sets '//sets//'; give either ' &
                          //'the body or com and inertia) [--body --com --inertia / &pendulum]')
         return
      end if
      if (cfg%body == 'point') then
         l = cfg%spec%get('l', [1.0_dp])
         call cfg%spec%set('com', l)
         call cfg%spec%set('inertia', spread(0.0_dp, 1, size(l)))
      end if
   end subroutine apply_body

end module dpend_run_settings
