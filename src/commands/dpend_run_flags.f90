!> The command-line flags shared by every command that runs the model (--m1 --dt
!> --method ...), applied to the run settings (dpend_run_settings) after the
!> namelist file, and their help lines.
module dpend_run_flags
   use dpend_kinds, only: dp, half_pi
   use dpend_error, only: error_t, fatal_error
   use dpend_model, only: max_dof
   use dpend_cli, only: parse_real, parse_int, real_str, to_str, printable
   use dpend_limits, only: in_range, max_angle
   use dpend_methods, only: method_names
   use dpend_strings, only: canonical_name, replace_char
   use dpend_model_factory, only: body_list
   use dpend_run_settings, only: run_config_t, set_body, model_names, is_model_parameter, &
      mark_given, time_unit_option_help
   implicit none
   private
   public :: apply_run_flag, run_flags_help, set_time_unit, is_model_flag, take_torque_file, &
      take_initial_angles, initial_angles_help, take_initial_run_flag

contains

   !> Apply one of the common flags; `matched` is false if `name` is not one of them.
   subroutine apply_run_flag(cfg, name, value, matched, error)
      type(run_config_t), intent(inout) :: cfg          !! configuration to update
      character(len=*), intent(in) :: name              !! option, e.g. '--dt'
      character(len=*), intent(in) :: value             !! its value
      logical, intent(out) :: matched                   !! whether it was a common flag
      type(error_t), allocatable, intent(out) :: error  !! invalid value
      matched = .true.
      call check_flag_forms(cfg, name, error)
      if (allocated(error)) return
      select case (name)
      case ('--links'); call parse_int(value, name, cfg%links, error)
      case ('--m'); call set_list(cfg, 1, name, value, error)
      case ('--l'); call set_list(cfg, 2, name, value, error)
      case ('--q'); call set_list(cfg, 3, name, value, error)
      case ('--w'); call set_list(cfg, 4, name, value, error)
      case ('--q1'); call parse_real(value, name, cfg%q(1), error)
      case ('--q2'); call parse_real(value, name, cfg%q(2), error)
      case ('--theta1', '--theta2')   ! from the hanging position, as the sweep's axes
         call set_theta(cfg, merge(1, 2, name == '--theta1'), name, value, error)
      case ('--w1'); call parse_real(value, name, cfg%w(1), error)
      case ('--w2'); call parse_real(value, name, cfg%w(2), error)
      case ('--m1'); call parse_real(value, name, cfg%m(1), error)
      case ('--m2'); call parse_real(value, name, cfg%m(2), error)
      case ('--l1'); call parse_real(value, name, cfg%l(1), error)
      case ('--l2'); call parse_real(value, name, cfg%l(2), error)
      case ('--g'); call parse_real(value, name, cfg%g, error)
      case ('--method'); cfg%method = canonical_name(value, method_names())
      case ('--dt'); call parse_real(value, name, cfg%dt, error)
      case ('--t-end'); call parse_real(value, name, cfg%t_end, error)
      case ('--save-every'); call parse_int(value, name, cfg%save_every, error)
      case ('--rtol'); call parse_real(value, name, cfg%rtol, error)
      case ('--atol'); call parse_real(value, name, cfg%atol, error)
      case ('--output-dt'); call parse_real(value, name, cfg%output_dt, error)
      case ('--omega'); call parse_real(value, name, cfg%omega, error)
      case ('--max-steps'); call parse_int(value, name, cfg%max_steps, error)
      case ('--time-unit'); call set_time_unit(cfg, value, '--time-unit', error)
      case ('--damping'); call set_list(cfg, 0, name, value, error)
      case ('--support-amplitude')
         call parse_pair(name, value, cfg%support_amplitude, 'a_x,a_y (m)', error)
      case ('--support-frequency'); call parse_real(value, name, cfg%support_frequency, error)
      case ('--support-phase')
         call parse_pair(name, value, cfg%support_phase, 'phi_x,phi_y (rad)', error)
      case ('--output', '-o'); cfg%output = value
      case ('--model'); cfg%model_name = canonical_name(value, model_names())
      case ('--body'); call set_body(cfg, value, error)
      case default
         matched = .false.
         ! a parameter of another model, by name (--k 40 --l0 1 for the elastic pendulum);
         ! a flag writes the name's '_' as '-' (one spelling: --support-phase)
         if (len(name) > 2 .and. index(name, '_') == 0) then
            if (is_model_parameter(setting_key(name))) then
               matched = .true.
               call set_named(cfg, setting_key(name), name, value, error)
            end if
         end if
      end select
      if (matched .and. .not. allocated(error)) call mark_given(cfg, setting_key(name))
   end subroutine apply_run_flag

   !> Whether `name` is --model or the flag of a parameter of a model of the catalogue
   !> (its '_' written '-': --coulomb-speed), which `apply_run_flag` takes; with
   !> `model`, of that model only.
   logical function is_model_flag(name, model)
      character(len=*), intent(in) :: name  !! the option
      character(len=*), intent(in), optional :: model  !! e.g. 'pendulum'
      is_model_flag = name == '--model'
      if (is_model_flag .or. len(name) < 3) return
      if (index(name, '_') > 0) return
      is_model_flag = is_model_parameter(setting_key(name), model)
   end function is_model_flag

   !> --torque-file FILE: once, a path that is not empty.
   subroutine take_torque_file(cfg, value, error)
      type(run_config_t), intent(inout) :: cfg          !! torque_file set
      character(len=*), intent(in) :: value             !! the path given
      type(error_t), allocatable, intent(out) :: error  !! given twice, empty
      if (allocated(cfg%torque_file)) then
         call fatal_error(error, 'invalid torque_file: given twice (--torque-file)')
      else if (len_trim(value) == 0) then
         call fatal_error(error, 'invalid torque_file: an empty path (--torque-file)')
      else
         cfg%torque_file = value
      end if
   end subroutine take_torque_file

   !> The flags of the commands that integrate from a given initial state (simulate,
   !> the chaos commands) beside the common ones: --torque-file and --angles.
   !> `matched` is false for any other; an error of reading the option (`missing`, or
   !> `error` set already) is kept.
   subroutine take_initial_run_flag(cfg, name, value, missing, matched, error)
      type(run_config_t), intent(inout) :: cfg            !! configuration to update
      character(len=*), intent(in) :: name, value         !! the option and its value
      logical, intent(in) :: missing                      !! the value is missing
      logical, intent(out) :: matched                     !! it is one of the two
      type(error_t), allocatable, intent(inout) :: error  !! invalid value
      matched = name == '--torque-file' .or. name == '--angles'
      if (.not. matched .or. missing .or. allocated(error)) return
      if (name == '--torque-file') then
         call take_torque_file(cfg, value, error)
      else
         call take_initial_angles(cfg, value, error)
      end if
   end subroutine take_initial_run_flag

   !> --angles relative|absolute: the convention of the initial angles and rates
   !> given (`run_config_t%initial_angles`), once.
   subroutine take_initial_angles(cfg, value, error)
      type(run_config_t), intent(inout) :: cfg          !! initial_angles set
      character(len=*), intent(in) :: value             !! as given
      type(error_t), allocatable, intent(out) :: error  !! twice, another word
      if (allocated(cfg%flags_seen)) then
         if (index(cfg%flags_seen, ' --angles ') > 0) then
            call fatal_error(error, 'invalid angles: given twice (--angles)')
            return
         end if
      else
         cfg%flags_seen = ' '
      end if
      if (value /= 'relative' .and. value /= 'absolute') then
         call fatal_error(error, "invalid angles: '"//printable(value)//"' (accepted: " &
                          //'absolute, relative) [--angles]')
         return
      end if
      cfg%initial_angles = value
      cfg%flags_seen = cfg%flags_seen//'--angles '
   end subroutine take_initial_angles

   !> The help lines of --angles.
   pure function initial_angles_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = '  --angles WHICH    the convention of the initial angles and rates given (the'//nl// &
          '                    q and w flags): absolute (default; from the'//nl// &
          '                    horizontal x axis) or relative (robotics: phi1 = q1 + pi/2'//nl// &
          '                    from hanging, phi_i = q_i - q_(i-1); unset values 0 in it)'//nl
   end function initial_angles_help

   !> Set the unit of the times given: 's' or 'natural' (`run_config_t%time_unit`).
   subroutine set_time_unit(cfg, value, field, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%time_unit set
      character(len=*), intent(in) :: value             !! as given
      character(len=*), intent(in) :: field             !! '--time-unit' or the key's name
      type(error_t), allocatable, intent(out) :: error  !! neither unit
      if (value /= 's' .and. value /= 'natural') then
         call fatal_error(error, "invalid time_unit: '"//printable(value)//"' (accepted: s, " &
                          //'natural) ['//field//']')
         return
      end if
      cfg%time_unit = value
   end subroutine set_time_unit

   !> The setting a flag gives, by its namelist key: '--support-frequency' is
   !> 'support_frequency', '-o' is 'output'.
   pure function setting_key(flag) result(key)
      character(len=*), intent(in) :: flag  !! the option
      character(len=:), allocatable :: key
      if (flag == '-o') then
         key = 'output'
         return
      end if
      key = replace_char(flag(3:), '-', '_')
   end function setting_key

   !> Refuse a second form of one quantity on the command line (`--m 1,2 --m1 3`,
   !> `--q1` with `--theta1`): which one wins would depend on their order. The
   !> same flag twice is the same form (refused by check_repeated_options). Records
   !> `name` in cfg%flags_seen.
   subroutine check_flag_forms(cfg, name, error)
      type(run_config_t), intent(inout) :: cfg          !! flags_seen updated
      character(len=*), intent(in) :: name              !! the option
      type(error_t), allocatable, intent(out) :: error  !! a second form
      character(len=:), allocatable :: others
      integer :: k
      select case (name)
      case ('--m', '--l', '--w')
         others = name//'1 '//name//'2'
      case ('--q')
         others = '--q1 --q2 --theta1 --theta2'
      case ('--m1', '--m2', '--l1', '--l2', '--w1', '--w2')
         others = name(:3)
      case ('--q1', '--q2')
         others = '--q --theta'//name(4:4)
      case ('--theta1', '--theta2')
         others = '--q --q'//name(8:8)
      case default
         return
      end select
      if (.not. allocated(cfg%flags_seen)) cfg%flags_seen = ' '
      others = ' '//others//' '
      do k = 1, len(others) - 1
         if (others(k:k) /= ' ' .or. others(k + 1:k + 1) == ' ') cycle
         if (index(cfg%flags_seen, ' '//first_word(others(k + 1:))//' ') > 0) then
            call fatal_error(error, 'invalid '//name//': '//first_word(others(k + 1:))// &
                             ' was given too; they are two forms of one quantity ' &
                             //'(--m, --l, --q, --w: one value per link; --m1 ... for ' &
                             //'two links); give one of them')
            return
         end if
      end do
      if (index(cfg%flags_seen, ' '//name//' ') == 0) &
         cfg%flags_seen = cfg%flags_seen//name//' '
   end subroutine check_flag_forms

   !> The first blank-separated word of `t`.
   pure function first_word(t) result(w)
      character(len=*), intent(in) :: t  !! text
      character(len=:), allocatable :: w
      w = t(:index(t//' ', ' ') - 1)
   end function first_word

   !> q_k = θ_k − π/2 from --theta1/--theta2 (θ from the hanging position,
   !> counter-clockwise) [rad].
   subroutine set_theta(cfg, k, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! q(k) set
      integer, intent(in) :: k                          !! the link, 1 or 2
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not a number, out of range
      real(dp) :: theta
      call parse_real(value, name, theta, error)
      if (allocated(error)) return
      if (.not. in_range(theta, -max_angle, max_angle)) then
         call fatal_error(error, 'invalid '//name//': '//real_str(theta)// &
                          ' rad is outside [-1e6, 1e6]')
         return
      end if
      cfg%q(k) = theta - half_pi
   end subroutine set_theta

   !> A comma-separated list of at most max_dof numbers, one per link: list k of
   !> `list_names` (m, l, q, w), or the damping for k = 0.
   subroutine set_list(cfg, k, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! the list and its size set
      integer, intent(in) :: k                          !! which list
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      integer :: n
      select case (k)
      case (0); call parse_real_list(value, name, cfg%damping, n, error)
      case (1); call parse_real_list(value, name, cfg%m, n, error)
      case (2); call parse_real_list(value, name, cfg%l, n, error)
      case (3); call parse_real_list(value, name, cfg%q, n, error)
      case default; call parse_real_list(value, name, cfg%w, n, error)
      end select
      if (allocated(error)) return
      if (k > 0) then
         cfg%list_size(k) = n
      else
         cfg%damping_size = n
      end if
   end subroutine set_list

   !> A comma-separated list of numbers for the model parameter `key` (--k 40).
   subroutine set_named(cfg, key, name, value, error)
      type(run_config_t), intent(inout) :: cfg          !! cfg%extra updated
      character(len=*), intent(in) :: key               !! the parameter
      character(len=*), intent(in) :: name, value       !! the option and its value
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      real(dp) :: values(max_dof)
      integer :: n
      call parse_real_list(value, name, values, n, error)
      if (.not. allocated(error)) call cfg%extra%set(key, values(:n))
   end subroutine set_named

   !> Two comma-separated numbers (`what` names them in the message).
   subroutine parse_pair(name, value, values, what, error)
      character(len=*), intent(in) :: name, value       !! the option and its value
      real(dp), intent(inout) :: values(2)              !! the numbers
      character(len=*), intent(in) :: what              !! e.g. 'a_x,a_y (m)'
      type(error_t), allocatable, intent(out) :: error  !! not two numbers
      integer :: comma
      comma = index(value, ',')
      if (comma == 0 .or. index(value(comma + 1:), ',') > 0) then
         call fatal_error(error, 'invalid '//name//": '"//printable(value)//"' must be two " &
                          //'comma-separated numbers '//what)
         return
      end if
      call parse_real(value(:comma - 1), name, values(1), error)
      if (allocated(error)) return
      call parse_real(value(comma + 1:), name, values(2), error)
   end subroutine parse_pair

   !> A comma-separated list of at most size(values) numbers (one per link for the
   !> per-link fields), each through the strict parser; `n` values read.
   subroutine parse_real_list(text, name, values, n, error)
      character(len=*), intent(in) :: text              !! the flag's value
      character(len=*), intent(in) :: name              !! the flag, for messages
      real(dp), intent(inout) :: values(:)              !! the numbers
      integer, intent(out) :: n                         !! how many
      type(error_t), allocatable, intent(out) :: error  !! not numbers, too many
      integer :: start, comma
      n = 0
      start = 1
      do
         comma = index(text(start:), ',')
         if (n == size(values)) then
            call fatal_error(error, 'invalid '//name//': more than '//to_str(size(values))// &
                             ' values (at most '//to_str(size(values))//' links)')
            return
         end if
         n = n + 1
         if (comma == 0) then
            call parse_real(text(start:), name, values(n), error)
            exit
         end if
         call parse_real(text(start:start + comma - 2), name, values(n), error)
         if (allocated(error)) return
         start = start + comma
      end do
   end subroutine parse_real_list

   !> Help lines for the common flags, with units and the defaults of `cfg`.
   function run_flags_help(cfg, t_end_text) result(s)
      type(run_config_t), intent(in) :: cfg  !! defaults to show
      character(len=*), intent(in), optional :: t_end_text  !! what --t-end means, if not
                                                            !! 'end time'
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      character(len=:), allocatable :: t_end_line
      t_end_line = 'end time'
      if (present(t_end_text)) t_end_line = t_end_text
      s = '  --config FILE     Fortran namelist file (groups &model &pendulum &initial' &
          //nl//'                    &integration &output; see data/*.nml); flags below' &
          //nl//'                    override it'//nl// &
          '  --model NAME      the model (dpend models lists them, with their parameters);'//nl// &
          '                    default pendulum. Parameters of other models by name, e.g.' &
          //nl//'                    --model elastic --m 1 --k 40 --l0 1 --q 1.2,-1.0'//nl// &
          '  --links N         number of links (uniform rods), 1 to '//to_str(max_dof)// &
          '; default '//to_str(cfg%links)//nl// &
          '                    (2: the double pendulum; 3: the triple pendulum, ...)'//nl// &
          '  --m, --l, --q, --w LIST  one value per link, comma-separated: masses (kg),'//nl// &
          '                    lengths (m), initial angles (rad), angular velocities (rad/s),'// &
          nl//'                    e.g. --links 3 --m 1,1,1 --q 0,0.5,-1; defaults 1 kg, 1 m, 0, 0' &
          //nl// &
          '  --q1, --q2 RAD    initial angles from the horizontal x axis, counter-clockwise' &
          //nl//'                    (hanging: -pi/2); default '//real_str(cfg%q(1))//', ' &
          //real_str(cfg%q(2))//nl// &
          '  --theta1, --theta2 RAD  the same angles from the hanging position, as the'//nl// &
          "                    sweep's axes: q = theta - pi/2"//nl// &
          '  --w1, --w2 RAD/S  initial angular velocities; default '//real_str(cfg%w(1))//', ' &
          //real_str(cfg%w(2))//nl// &
          '  --m1, --m2 KG     link masses (m1 m2 l1 l2 g: each in [1e-6, 1e6]); default ' &
          //real_str(cfg%m(1))//', ' &
          //real_str(cfg%m(2))//nl// &
          '  --l1, --l2 M      link lengths; default '//real_str(cfg%l(1))//', ' &
          //real_str(cfg%l(2))//nl// &
          '  --g M/S^2         gravitational acceleration; default '//real_str(cfg%g)//nl// &
          '  --body '//body_list('|')//'  the links: uniform rods (default; com l_i/2, inertia'//nl// &
          '                    m_i l_i^2/12) or point masses on massless rods (com l_i,'//nl// &
          '                    inertia 0: the textbook double pendulum)'//nl// &
          '  --com LIST        joint i to the centre of mass of link i along the link (m,'//nl// &
          '                    one per link, >= 0; default l_i/2)'//nl// &
          '  --inertia LIST    moment of inertia of link i about its centre of mass'//nl// &
          '                    (kg m^2, one per link, >= 0; default m_i l_i^2/12)'//nl// &
          '  --damping LIST    joint damping c_i (N m s, one per joint, each in [0, 1e6]):'//nl// &
          '                    torque -c_i (qdot_i - qdot_(i-1)) at joint i; default 0'//nl// &
          '  --coulomb LIST    Coulomb joint friction c_f,i (N m, one per joint, each in'//nl// &
          '                    [0, 1e6]): torque -c_f,i tanh(w_i/v_s) at joint i, w_i ='//nl// &
          '                    qdot_i - qdot_(i-1); default 0 (docs/robot.md)'//nl// &
          '  --coulomb-speed V its smoothing speed v_s (rad/s, in [1e-6, 1e3]); default 1e-3'//nl// &
          '  --rotor-inertia LIST  rotor inertia I_r,i of the motor at joint i (kg m^2,'//nl// &
          '                    one per joint, each in [0, 1e6]): adds g_r,i^2 I_r,i to the'//nl// &
          '                    inertia of w_i; default 0 (docs/robot.md)'//nl// &
          '  --gear-ratio LIST its gear ratio g_r,i (rotor speed / joint speed, each in'//nl// &
          '                    [1e-3, 1e4], g_r^2 I_r <= 1e12); default 1'//nl// &
          '  --support-amplitude AX,AY  moving pin: x_A = AX cos(w t + PX),'//nl// &
          '                    y_A = AY cos(w t + PY) (m, each in [-1e6, 1e6]); default 0,0'//nl// &
          '  --support-frequency W  w (rad/s, in [0, 1e6]); default 0'//nl// &
          '  --support-phase PX,PY  phases (rad); default 0,0. Damping or a moving support'//nl// &
          '                    makes the model the (damped, driven) chain, also for two'//nl// &
          '                    links: rk4, dopri5, dop853, midpoint, gauss4/6/8 only;'//nl// &
          '                    simulate writes the energy balance (W_friction,'//nl// &
          '                    W_support, balance_error)'//nl// &
          '  --method NAME     integrator (dpend methods lists them); default '//cfg%method//nl// &
          '  --dt S            step (first trial step for adaptive methods); default ' &
          //real_str(cfg%dt)//nl// &
          '  --t-end S         '//t_end_line//'; default '//real_str(cfg%t_end)//nl// &
          time_unit_option_help(trim(cfg%time_unit))//nl// &
          '  --rtol, --atol    tolerances of the adaptive methods; default '//real_str(cfg%rtol) &
          //', '//real_str(cfg%atol)//nl// &
          "  --omega 1/S       binding constant of Tao's methods; default "//real_str(cfg%omega)// &
          nl//'  --max-steps N     most accepted steps of one integration of an adaptive'//nl// &
          '                    method (steps); reaching it stops the run; default ' &
          //to_str(cfg%max_steps)
   end function run_flags_help

end module dpend_run_flags
