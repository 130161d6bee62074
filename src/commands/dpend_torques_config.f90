!> The command line and the data of `dpend torques` and `dpend identify` (both read a
!> measured motion and filter it): the settings record `torques_config_t` and its
!> defaults, the parsing of the arguments, the reading of the measured series
!> (angles; rates and torques when the file has them), their checks against the
!> model and the filter, the work and memory bounds, and the `--help` texts. The
!> computations are in `dpend_torques_command` and `dpend_identify_command`.
module dpend_torques_config
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, take_data_file, next_option, option_outcome, scan_help_config, parse_real, &
                        parse_int, real_str, to_str, printable
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_run_flags, only: apply_run_flag, is_model_flag
   use dpend_model, only: model_t, max_dof
   use dpend_model_factory, only: new_model, default_model, body_list
   use dpend_chain, only: chain_t
   use dpend_csv, only: series_t, read_series
   use dpend_smoothing, only: max_degree, max_half_width, min_half_width
   use dpend_output, only: check_output_path, register_input
   use dpend_limits, only: check_range, sci
   use dpend_resources, only: check_memory
   implicit none
   private
   public :: torques_config_t, parse_torques, torques_help, identify_help, filter_work, &
      max_filter_work

   !> Most floating-point operations of the filter (samples × window × degree²).
   real(dp), parameter :: max_filter_work = 2e10_dp
   !> Largest noise given by --sigma [rad].
   real(dp), parameter :: max_sigma = 1.0_dp

   !> Everything `dpend torques` needs.
   type :: torques_config_t
      type(run_config_t) :: run                  !! the model's settings, output, force
      type(chain_t) :: chain                     !! the model built (the general chain)
      character(len=:), allocatable :: input     !! the CSV file
      type(series_t) :: angles                   !! t and q (N, K) [rad]
      type(series_t) :: rates                    !! qdot1..N [rad/s] if the file has them
      type(series_t) :: measured                 !! tau1..N [N m] if the file has them
      integer :: degree = 4                      !! the filter's polynomial degree
      integer :: window = 0                      !! samples in a window (0: plug-in rule)
      real(dp) :: sigma = 0.0_dp                 !! noise of the angles (0: estimated)
      character(len=:), allocatable :: csv       !! --csv FILE ('' none)
      character(len=:), allocatable :: command   !! 'torques' or 'identify'
      !> identify: which frictions are estimated (--friction); the others are known,
      !> at the model's values (--damping, --coulomb)
      logical :: fit_viscous = .true., fit_coulomb = .true.
      !> identify: the motors' reflected inertias g_r² I_r are estimated (--rotors
      !> estimate), else known (--rotor-inertia, --gear-ratio; default none)
      logical :: fit_rotors = .false.
   end type torques_config_t

   !> The run flags that make sense here (the model; no integration, no initial state).
   character(len=20), parameter :: run_flags(16) = [character(len=20) :: '--links', '--m', &
      '--l', '--g', '--m1', '--m2', '--l1', '--l2', '--damping', '--support-amplitude', &
      '--support-frequency', '--support-phase', '--output', '-o', '--body', '--model']

contains

   !> Defaults: degree 4, the plug-in window, output COMMAND.h5.
   function torques_defaults(command) result(tc)
      character(len=*), intent(in) :: command  !! 'torques' or 'identify'
      type(torques_config_t) :: tc
      tc%command = command
      tc%run%output = command//'.h5'
      tc%run%method = 'rk4'   ! unused (nothing is integrated); the settings' check needs one
      tc%input = ''
      tc%csv = ''
   end function torques_defaults

   !> Help text of `dpend torques`.
   function torques_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(torques_config_t) :: tc
      tc = torques_defaults('torques')
      s = 'usage: dpend torques DATA.csv [options]'//nl//nl// &
          'Inverse dynamics: the joint torques tau_i (joint i''s motor on link i, its'//nl// &
          'reaction on link i-1) and every joint reaction F_(i-1,i) that a measured motion'//nl// &
          'of the chain requires, by Newton-Euler from the tip, with the model''s friction'// &
          nl//'and support motion. The angles are smoothed and differentiated by a local'//nl// &
          'polynomial (Savitzky-Golay on the samples'' own times); its window is chosen'//nl// &
          'from the noise of the data (docs/robot.md) and stated with the errors it'//nl// &
          'predicts. With measured torques, their residual and its RMS per joint.'//nl// &
          'Writes HDF5 (group /torques; figures: scripts/plot_torques.sh).'//nl//nl// &
          'DATA.csv: a header line, then one row per sample (as dpend fit reads):'//nl// &
          '  t                       s, increasing'//nl// &
          '  q1..qN or theta1..thetaN  angles in rad from the horizontal x axis, or from'//nl// &
          '                          the hanging position ([deg] converted)'//nl// &
          '  qdot1..qdotN            optional: measured rates [rad/s]; then qdot and'//nl// &
          '                          qddot come from the smoothed rates'//nl// &
          '  tau1..tauN              optional: measured torques [N m], compared'//nl// &
          '  other columns ignored; lines starting with # and blank lines skipped.'//nl//nl// &
          'torques options:'//nl// &
          filter_options_help(tc)// &
          '  --csv FILE        also write t, tau1..N (and tau_measured, residual) as CSV'//nl// &
          '  --output FILE     HDF5 file to write; default '//tc%run%output//nl// &
          '  --force           overwrite existing output files'//nl//nl// &
          'model (the links from the angle columns; dpend simulate --help for each):'//nl// &
          '  --links, --m, --l, --g, --m1, --m2, --l1, --l2, --damping, --coulomb,'//nl// &
          '  --coulomb-speed, --support-amplitude, --support-frequency, --support-phase,'//nl// &
          '  --rotor-inertia, --gear-ratio (motors),'//nl// &
          '  --body '//body_list('|')//', --com LIST, --inertia LIST, --model pendulum'//nl// &
          '  -h, --help        this text'
   end function torques_help

   !> Help text of `dpend identify`.
   function identify_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(torques_config_t) :: tc
      tc = torques_defaults('identify')
      s = 'usage: dpend identify DATA.csv [options]'//nl//nl// &
          'Identify the inertial and friction parameters that the measured joint torques'//nl// &
          'determine: the dynamics is linear in J_i (inertia about joint i), h_i = m_i d_i,'// &
          nl//'m_i, c_i (viscous) and cf_i (Coulomb); the regressor of the filtered motion'//nl// &
          '(Newton-Euler) is reduced to the identifiable base combinations (e.g. J1 +'//nl// &
          'l1^2 m2) and solved by weighted least squares. Prints the base parameters with'// &
          nl//'standard errors and 95 % intervals, the condition number, the combinations'//nl// &
          'the data cannot separate (refused, named), the torque residual per joint and'//nl// &
          'the physical checks with the masses given (--m): J_i >= m_i d_i^2, c_i, cf_i >='// &
          nl//'0. Writes HDF5 (group /identify). docs/robot.md explains the method.'//nl//nl// &
          'DATA.csv: as dpend torques reads it, with the measured torques tau1..tauN [N m].'// &
          nl//'The rows used are every window-th sample (their filter errors independent).'// &
          nl//nl//'identify options:'//nl// &
          '  --friction LIST   the frictions estimated: viscous,coulomb (default), viscous,'//nl// &
          '                    coulomb or none; the others are known: --damping, --coulomb'//nl// &
          '  --rotors WHAT     the motors'' reflected inertias Im_i = g_r,i^2 I_r,i: known'//nl// &
          '                    (default: from --rotor-inertia, --gear-ratio; none if not'//nl// &
          '                    given) or estimate (Im1 shows only within J1 + Im1)'//nl// &
          filter_options_help(tc)// &
          '  --output FILE     HDF5 file to write; default '//tc%run%output//nl// &
          '  --force           overwrite an existing output file'//nl//nl// &
          'model (known: lengths, g, the support; the masses for the checks):'//nl// &
          '  --links, --m, --l, --g, --m1, --m2, --l1, --l2, --coulomb-speed (v_s of'//nl// &
          '  tanh(w/v_s)), --damping and --coulomb (known when not estimated),'//nl// &
          '  --rotor-inertia and --gear-ratio (the motors, with --rotors known),'//nl// &
          '  --support-amplitude, --support-frequency, --support-phase, --model pendulum'// &
          nl//'  (--com, --inertia and --body are refused: identify estimates the bodies)'// &
          nl//'  -h, --help        this text'
   end function identify_help

   !> The filter's options, shared by the help texts.
   function filter_options_help(tc) result(s)
      type(torques_config_t), intent(in) :: tc  !! defaults
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      s = '  --degree P        the local polynomial''s degree, 2 to '//to_str(max_degree)// &
          '; default '//to_str(tc%degree)//nl// &
          '  --window W        samples per window, odd, from P+1 (at least 5) to '// &
          to_str(2*max_half_width + 1)//nl// &
          '                    and the number of samples; default: the plug-in rule (the'//nl// &
          '                    least predicted error of qddot for the estimated noise)'//nl// &
          '  --sigma S         the noise of the angles (rad, in [1e-12, 1]); default:'//nl// &
          '                    estimated from their fourth differences'//nl
   end function filter_options_help

   !> Build the configuration and read the data; every refusal is one line.
   subroutine parse_torques(args, tc, help, error, command)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'torques'
      type(torques_config_t), intent(out) :: tc         !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=*), intent(in) :: command           !! 'torques' or 'identify'
      character(len=:), allocatable :: config
      logical :: links_given
      tc = torques_defaults(command)
      help = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call fatal_error(error, "unknown option '--config' (dpend "//command//' takes ' &
                          //'the model by its flags; dpend '//command//' --help lists the ' &
                          //'options)')
         return
      end if
      call parse_args(args, tc, links_given, error)
      if (allocated(error)) return
      if (len(tc%input) == 0) then
         call fatal_error(error, 'no data file given (usage: dpend '//command// &
                          ' DATA.csv [options]; dpend '//command//' --help)')
         return
      end if
      call check_filter_options(tc, error)
      if (allocated(error)) return
      if (command == 'identify') then
         call check_known_parameters(tc, error)
         if (allocated(error)) return
      end if
      call register_input(tc%input)   ! the outputs never replace the data file
      call check_output_path(tc%run%output, tc%run%force, error)
      if (allocated(error)) return
      if (len(tc%csv) > 0) then
         call check_output_path(tc%csv, tc%run%force, error, '--csv')
         if (allocated(error)) return
         if (tc%csv == tc%run%output) then
            call fatal_error(error, "invalid csv: '"//printable(tc%csv)//"' is also the " &
                             //'HDF5 output [--csv]')
            return
         end if
      end if
      call read_data(tc, error)
      if (allocated(error)) return
      if (command == 'identify' .and. .not. tc%measured%coords_found) then
         call fatal_error(error, "invalid data file '"//printable(tc%input)//"': no " &
                          //'measured torques (columns tau1 .. tau'//to_str(tc%angles%n)// &
                          ' [N m]); dpend identify needs them')
         return
      end if
      call build_chain(tc, links_given, error)
      if (allocated(error)) return
      call check_data(tc, error)
   end subroutine parse_torques

   !> The arguments: the data file, the command's options and the model's flags.
   subroutine parse_args(args, tc, links_given, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'torques'
      type(torques_config_t), intent(inout) :: tc       !! the configuration
      logical, intent(out) :: links_given               !! --links was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value
      logical :: matched, missing
      integer :: i
      links_given = .false.
      i = 1
      do while (i <= size(args))
         if (args(i)%s == '--force') then
            tc%run%force = .true.
            i = i + 1
            cycle
         end if
         if (take_data_file(args(i)%s, tc%input, tc%command, error)) then
            if (allocated(error)) return
            i = i + 1
            cycle
         end if
         call next_option(args, i, name, value, .true., error, missing)
         matched = .true.
         select case (name)
         case ('--degree')
            call parse_int(value, name, tc%degree, error)
         case ('--window')
            call parse_int(value, name, tc%window, error)
         case ('--sigma')
            call parse_real(value, name, tc%sigma, error)
            if (.not. allocated(error)) call check_range('sigma', tc%sigma, 1e-12_dp, &
                                                         max_sigma, 'rad', error, &
                                                         'the noise of the angles')
         case ('--csv')
            matched = tc%command == 'torques'
            tc%csv = value
         case ('--friction')
            matched = tc%command == 'identify'
            if (matched) call parse_friction(value, tc, error)
         case ('--rotors')
            matched = tc%command == 'identify'
            if (matched) then
               select case (value)
               case ('known'); tc%fit_rotors = .false.
               case ('estimate'); tc%fit_rotors = .true.
               case default
                  call fatal_error(error, "invalid rotors: '"//printable(value)// &
                                   "' (accepted: known, estimate) [--rotors]")
               end select
            end if
         case default
            if (any(run_flags == name) .or. is_model_flag(name, default_model)) then
               if (name == '--links') links_given = .true.
               call apply_run_flag(tc%run, name, value, matched, error)
            else
               matched = .false.
            end if
         end select
         if (tc%command == 'identify') then
            call option_outcome('identify', name, matched, missing, [character(len=16) :: &
                                '--force'], error, identify_help())
         else
            call option_outcome('torques', name, matched, missing, [character(len=16) :: &
                                '--force'], error, torques_help())
         end if
         if (allocated(error)) return
      end do
   end subroutine parse_args

   !> --friction: 'viscous,coulomb', 'viscous', 'coulomb' or 'none'.
   subroutine parse_friction(value, tc, error)
      character(len=*), intent(in) :: value             !! as given
      type(torques_config_t), intent(inout) :: tc       !! fit_viscous, fit_coulomb set
      type(error_t), allocatable, intent(out) :: error  !! none of these
      select case (value)
      case ('viscous,coulomb', 'coulomb,viscous')
         tc%fit_viscous = .true.; tc%fit_coulomb = .true.
      case ('viscous')
         tc%fit_viscous = .true.; tc%fit_coulomb = .false.
      case ('coulomb')
         tc%fit_viscous = .false.; tc%fit_coulomb = .true.
      case ('none')
         tc%fit_viscous = .false.; tc%fit_coulomb = .false.
      case default
         call fatal_error(error, "invalid friction: '"//printable(value)//"' (accepted: " &
                          //'viscous,coulomb, viscous, coulomb, none) [--friction]')
      end select
   end subroutine parse_friction

   !> identify estimates the bodies and the frictions it is asked for: a value given
   !> for one of them would be dropped, so it is refused.
   subroutine check_known_parameters(tc, error)
      type(torques_config_t), intent(in) :: tc          !! the configuration
      type(error_t), allocatable, intent(out) :: error  !! an estimated value given
      character(len=16), parameter :: keys(3) = [character(len=16) :: 'com', 'inertia', &
                                                 'body']
      integer :: i
      character(len=:), allocatable :: given
      given = ' '
      if (allocated(tc%run%given)) given = tc%run%given
      do i = 1, size(keys)
         if (index(given, ' '//trim(keys(i))//' ') > 0) then
            call fatal_error(error, 'invalid '//trim(keys(i))//': dpend identify estimates ' &
                             //'the bodies (J_i, h_i = m_i d_i); give the masses (--m) for ' &
                             //'its checks [--'//trim(keys(i))//']')
            return
         end if
      end do
      if (tc%fit_rotors .and. (index(given, ' rotor_inertia ') > 0 .or. &
                               index(given, ' gear_ratio ') > 0)) then
         call fatal_error(error, 'invalid rotor_inertia: dpend identify estimates the ' &
                          //'reflected rotor inertias g_r^2 I_r (--rotors known: then ' &
                          //'--rotor-inertia and --gear-ratio give them) [--rotors]')
         return
      end if
      if (tc%fit_viscous .and. index(given, ' damping ') > 0) then
         call fatal_error(error, 'invalid damping: dpend identify estimates the viscous ' &
                          //'friction c_i (--friction coulomb or none: then --damping ' &
                          //'gives its known values) [--damping]')
      else if (tc%fit_coulomb .and. index(given, ' coulomb ') > 0) then
         call fatal_error(error, 'invalid coulomb: dpend identify estimates the Coulomb ' &
                          //'friction cf_i (--friction viscous or none: then --coulomb ' &
                          //'gives its known values) [--coulomb]')
      end if
   end subroutine check_known_parameters

   !> The degree and the window given, before the data are read.
   subroutine check_filter_options(tc, error)
      type(torques_config_t), intent(in) :: tc          !! the configuration
      type(error_t), allocatable, intent(out) :: error  !! out of range
      if (tc%degree < 2 .or. tc%degree > max_degree) then
         call fatal_error(error, 'invalid degree: '//to_str(tc%degree)//' is outside [2, ' &
                          //to_str(max_degree)//'] (qddot needs a degree of at least 2) ' &
                          //'[--degree]')
      else if (tc%window /= 0 .and. (tc%window < max(tc%degree + 1, 2*min_half_width + 1) &
                                     .or. tc%window > 2*max_half_width + 1)) then
         call fatal_error(error, 'invalid window: '//to_str(tc%window)//' samples is ' &
                          //'outside ['//to_str(max(tc%degree + 1, 2*min_half_width + 1))// &
                          ', '//to_str(2*max_half_width + 1)//'] (at least degree + 1 = '// &
                          to_str(tc%degree + 1)//' and 5) [--window]')
      else if (tc%window /= 0 .and. mod(tc%window, 2) == 0) then
         call fatal_error(error, 'invalid window: '//to_str(tc%window)//' samples is even ' &
                          //'(a window is centred on its sample: 2k + 1 samples, e.g. '// &
                          to_str(tc%window + 1)//') [--window]')
      end if
   end subroutine check_filter_options

   !> The angles (t, q or theta), and the optional columns of rates and torques.
   subroutine read_data(tc, error)
      type(torques_config_t), intent(inout) :: tc       !! the configuration
      type(error_t), allocatable, intent(out) :: error  !! unreadable, refused
      character(len=16), allocatable :: names(:), units(:)
      integer :: i, n
      call read_series(tc%input, tc%angles, error)
      if (allocated(error)) return
      if (tc%angles%positions) then
         call fatal_error(error, "invalid data file '"//printable(tc%input)//"': it gives " &
                          //'positions (x1,y1, ...); dpend torques needs the angles (q1 .. ' &
                          //'qN or theta1 .. thetaN)')
         return
      end if
      n = tc%angles%n
      allocate (names(n), units(n))
      do i = 1, n   ! (a loop: gfortran 12 pads a literal of a typed implied-do wrongly)
         names(i) = 'qdot'//to_str(i)
         units(i) = 'rad/s'
      end do
      call read_series(tc%input, tc%rates, error, names, units, 'the measured rates', &
                       optional_columns=.true.)
      if (allocated(error)) return
      do i = 1, n
         names(i) = 'tau'//to_str(i)
         units(i) = 'N m'
      end do
      call read_series(tc%input, tc%measured, error, names, units, 'the measured torques', &
                       optional_columns=.true.)
   end subroutine read_data

   !> The model: the pendulum (chain) of N links, built in its general form.
   subroutine build_chain(tc, links_given, error)
      type(torques_config_t), intent(inout) :: tc       !! configuration; chain set
      logical, intent(in) :: links_given                !! --links was given
      type(error_t), allocatable, intent(out) :: error  !! refused
      class(model_t), allocatable :: model
      if (allocated(tc%run%model_name)) then
         if (tc%run%model_name /= default_model) then
            call fatal_error(error, 'invalid model: '//tc%run%model_name//' has no joints; ' &
                             //'dpend torques takes model '//default_model//' (N links) ' &
                             //'[--model]')
            return
         end if
      end if
      if (links_given .and. tc%run%links /= tc%angles%n) then
         call fatal_error(error, 'invalid links: '//to_str(tc%run%links)//" given, the data " &
                          //"file '"//printable(tc%input)//"' has "//to_str(tc%angles%n)// &
                          ' angle columns (N is the number of angle columns) [--links]')
         return
      end if
      tc%run%links = tc%angles%n
      call validate_run_config(tc%run, error, initial_state=.false.)
      if (allocated(error)) return
      tc%run%spec%general = .true.
      call new_model(tc%run%spec, model, error)
      if (allocated(error)) return
      select type (model)
      type is (chain_t)
         tc%chain = model
      class default
         call fatal_error(error, 'internal error: the pendulum''s general form is not a chain')
      end select
   end subroutine build_chain

   !> The samples against the filter (enough for the window and the noise estimate)
   !> and the work and memory the run needs.
   subroutine check_data(tc, error)
      type(torques_config_t), intent(in) :: tc          !! the configuration
      type(error_t), allocatable, intent(out) :: error  !! too few, too much
      integer :: k_min, n
      real(dp) :: bytes
      n = tc%angles%k
      k_min = max(tc%window, 2*max(min_half_width, tc%degree/2 + 1) + 1)
      if (n < k_min) then
         call fatal_error(error, "invalid data file '"//printable(tc%input)//"': "// &
                          to_str(n)//' samples; the filter of degree '//to_str(tc%degree)// &
                          ' needs at least '//to_str(k_min)//' (lines '// &
                          to_str(tc%angles%line(1))//' to '//to_str(tc%angles%line(n))//')')
         return
      end if
      if (filter_work(n, tc%window, tc%degree, tc%angles%n) > max_filter_work) then
         call fatal_error(error, 'invalid window: '//to_str(tc%window)//' samples on '// &
                          to_str(n)//' samples needs '// &
                          sci(filter_work(n, tc%window, tc%degree, tc%angles%n))// &
                          ' operations; at most '//sci(max_filter_work)//' (a narrower ' &
                          //'window or fewer samples) [--window]')
         return
      end if
      bytes = 8.0_dp*n*(14.0_dp*tc%angles%n + 8.0_dp)
      call check_memory('data file', bytes, to_str(n)//' samples', 'fewer samples', error)
   end subroutine check_data

   !> The filter's operations: samples × window × ((degree + 1)² + columns) (the
   !> weights and their products); the plug-in window counted as 2 × 64 + 1.
   pure real(dp) function filter_work(n, window, degree, links) result(w)
      integer, intent(in) :: n, window, degree, links
      integer :: width
      width = window
      if (width == 0) width = 129
      w = real(n, dp)*width*(2.0_dp*(degree + 1)**2 + 6.0_dp*links)
   end function filter_work

end module dpend_torques_config
