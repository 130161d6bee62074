!> What the chaos commands `dpend lyapunov`, `dpend divergence`, `dpend poincare`
!> and `dpend indicators` share: their settings (the group &chaos) with the
!> defaults of each command, the reading of the common flags and namelist groups of
!> `dpend_config`, of the group &chaos and of each command's flags, the validation
!> of the settings, the --help texts, and the run around a command's own work
!> (`run_chaos`: the method, the output file written through `dpend_output`, the
!> exit status of a failure); for the commands' writers, the root attributes of
!> every chaos file (`write_common`), the run status and the number formats of the
!> summaries; and the shape of every chaos command from its arguments to its summary
!> (`chaos_command`). Each command's run and file writing, and its entry point, is in
!> its own module: `dpend_lyapunov_command`, `dpend_divergence_command`,
!> `dpend_poincare_command`, `dpend_indicators_command`.
module dpend_chaos_common
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, run_failure, error_run_failed
   use dpend_cli, only: arg_t, next_option, parse_real, parse_int, option_outcome
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_namelist, only: read_run_config, namelist_error
   use dpend_run_flags, only: apply_run_flag, run_flags_help, take_initial_run_flag, &
      initial_angles_help
   use dpend_pendulum, only: energy_limit
   use dpend_limits, only: finite_positive
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model
   use dpend_output, only: output_t
   use dpend_version, only: version
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use dpend_cli, only: to_str
   use dpend_cli, only: scan_help_config, real_str, printable
   use dpend_limits, only: in_range, check_range, check_count, sci, max_time, max_steps, &
                           max_samples, max_angle, max_angular_velocity, min_delta0_relative
   use dpend_resources, only: check_memory, check_disk
   use dpend_command_common, only: take_quiet, last_line, refusal_line, error_line
   implicit none
   private
   public :: chaos_command
   public :: chaos_config_t, chaos_defaults, chaos_run_defaults, parse_chaos, chaos_help
   public :: read_chaos_config, validate_chaos, run_chaos, chaos_run_body
   public :: write_common, run_status, stopped, n_vectors, num, es, fixed

   real(dp), parameter :: pi = acos(-1.0_dp)
   character(len=*), parameter :: nl = new_line('a')

   !> Settings of the chaos commands (namelist group &chaos); each command uses
   !> its own subset.
   !> --vectors not given: all 2N exponents (a value no user can give: huge is
   !> refused by parse_int's range, and the check accepts only 1 … 2N otherwise).
   integer, parameter :: all_vectors = -huge(1)

   type :: chaos_config_t
      character(len=:), allocatable :: command  !! 'lyapunov', 'divergence', 'poincare'
                                                !! or 'indicators'
      ! lyapunov (and indicators: the sampling interval)
      real(dp) :: tau = 0.5_dp           !! renormalisation interval [s]
      integer :: vectors = all_vectors   !! tangent vectors (exponents computed), 1 to 2N;
                                         !! 0: all 2N
      integer :: batches = 10            !! batches for the statistical spread
      ! divergence
      real(dp) :: delta0 = 1e-9_dp       !! initial distance in (q, q̇)
      logical :: same_energy = .false.   !! partner on the same energy surface
      integer :: pairs = 20              !! pairs averaged (pair 1 from the initial state)
      real(dp) :: pair_spacing = 25.0_dp !! time between pair starts along the orbit [s]
      real(dp) :: fit_start = 0.0_dp     !! fit window start [s] (with fit_end > fit_start)
      real(dp) :: fit_end = 0.0_dp       !! fit window end [s]; 0: automatic
      real(dp) :: lyapunov_t = 1000.0_dp !! duration of the Benettin run reported beside [s]
      ! poincare
      integer :: n_ics = 40              !! orbits (initial states on the energy shell)
      integer :: n_points = 400          !! most section points per orbit
      logical :: energy_given = .false.  !! energy set (else: energy of the initial state)
      real(dp) :: energy = 0.0_dp        !! energy of the section [J]
      integer :: section_link = 1        !! link whose angle defines the section
      real(dp) :: section_angle = -0.5_dp*pi  !! section angle [rad] (modulo 2π)
      integer :: section_direction = 1   !! +1: q̇ > 0 at the crossing, -1: < 0, 0: both
   end type chaos_config_t

   abstract interface
      !> The run and file writing of one chaos command: integrate with `integ`,
      !> write the HDF5 file `filename`, and set `summary` (standard output, its
      !> last line the result for scripts). `error` is set when the file cannot be
      !> written, or for a run that stopped early (`failed`: the file holds what
      !> was computed before).
      subroutine chaos_run_body(cfg, ch, integ, filename, summary, error, failed)
         import :: run_config_t, chaos_config_t, integrator_t, error_t
         type(run_config_t), intent(in) :: cfg
         type(chaos_config_t), intent(in) :: ch
         class(integrator_t), intent(inout) :: integ
         character(len=*), intent(in) :: filename  !! the file to write
         character(len=:), allocatable, intent(inout) :: summary
         type(error_t), allocatable, intent(out) :: error
         logical, intent(inout) :: failed
      end subroutine chaos_run_body
   end interface

contains

   !> Defaults of the &chaos settings for `command`.
   function chaos_defaults(command) result(ch)
      character(len=*), intent(in) :: command  !! command name
      type(chaos_config_t) :: ch
      ch%command = command
   end function chaos_defaults

   !> Defaults of the run configuration for `command`: the chapter's parameters,
   !> both links horizontal at rest, rk4 with dt = 1e-3 s.
   function chaos_run_defaults(command) result(cfg)
      character(len=*), intent(in) :: command  !! command name
      type(run_config_t) :: cfg
      cfg%method = 'rk4'
      cfg%dt = 1e-3_dp
      cfg%output = command//'.h5'
      select case (command)
      case ('lyapunov', 'indicators')
         cfg%t_end = 1000.0_dp
      case ('divergence')
         cfg%t_end = 40.0_dp
         cfg%output_dt = 0.01_dp
      case default
         cfg%t_end = 2000.0_dp
      end select
   end function chaos_run_defaults

   !> Help text of `dpend command`.
   function chaos_help(command) result(s)
      character(len=*), intent(in) :: command  !! command name
      character(len=:), allocatable :: s
      type(run_config_t) :: cfg
      type(chaos_config_t) :: ch
      cfg = chaos_run_defaults(command)
      ch = chaos_defaults(command)
      s = 'usage: dpend '//command//' [options]'//nl//nl
      select case (command)
      case ('lyapunov')
         s = s//'Lyapunov exponents of one trajectory (Benettin et al. 1980): K tangent'//nl// &
             'vectors are integrated along it with the analytic Jacobian and'//nl// &
             're-orthonormalised by QR (LAPACK) every tau; the running estimates go'//nl// &
             'to HDF5. The last output line is "lyapunov: l1 l2 l3 l4" (1/s, descending).'
      case ('indicators')
         s = s//'Fast chaos indicators of one trajectory from its tangent dynamics: 2N'//nl// &
             'deviation vectors (N links; an orthonormal set in general position) are'//nl// &
             'integrated with the analytic Jacobian and rescaled to length 1 after'//nl// &
             'every step (directions kept). Time series to HDF5, sampled every tau:'//nl// &
             '  MEGNO Y(t) and its running mean <Y>(t) (Cincotta & Simo 2000): <Y> -> 2'//nl// &
             '    on regular orbits, ~ lambda1 t/2 on chaotic ones;'//nl// &
             '  FLI(t) = max_i ln|delta_i(t)| (Froeschle et al. 1997): ~ ln t (regular),'//nl// &
             '    ~ lambda1 t (chaotic);'//nl// &
             '  SALI (vectors 1, 2) and GALI_k, k = 2 .. 2N (Skokos et al. 2001, 2007):'//nl// &
             '    GALI_k ~ t^(-2(k-N)) for k > N (regular), exponential decay (chaotic).'//nl// &
             'The last output line is "indicators: <Y> FLI SALI GALI_2 .. GALI_2N".'
      case ('divergence')
         s = s//'Divergence of nearby trajectories: pairs started delta0 apart in'//nl// &
             '(q1, q2, w1, w2); log10|delta(t)| (angle differences wrapped), averaged'//nl// &
             'over the pairs, with a straight-line fit over the exponential phase and,'//nl// &
             'beside it, the largest Lyapunov exponent of the same initial state.'//nl// &
             'The last output line is "divergence slope: S" (1/s, natural log).'
      case default
         s = s//'Poincare section at one energy: orbits started on the energy shell of'//nl// &
             'the section (Halton points), each crossing of the section located to'//nl// &
             'roundoff and recorded as (angle, momentum) of the other link.'
      end select
      s = s//nl//'Output: HDF5 (docs/hdf5-layout.md); figures: scripts/plot_chaos.sh FILE.h5'// &
          nl//nl//'options (SI units; angles in rad from the horizontal x axis, y up):'//nl// &
          run_flags_help(cfg, t_end_text(command))//nl// &
          initial_angles_help()// &
          '  --torque-file F   applied joint torques: CSV with columns t [s] and tau1 ..'//nl// &
          '                    tauN [N m] (joint i on link i), linear between samples,'//nl// &
          '                    covering '//torque_span_text(command)//' (docs/robot.md)'//nl// &
          '                    (namelist group &chaos holds the settings below)'//nl
      select case (command)
      case ('lyapunov')
         s = s//'  --tau S           renormalisation (QR) interval; default ' &
             //real_str(ch%tau)//nl// &
             '  --vectors K       exponents computed, 1 (largest) to 2N (N links);'//nl// &
             '                    default all 2N'//nl// &
             '  --batches N       time segments for the spread (standard error of the'//nl// &
             '                    segment exponents); default '//to_str(ch%batches)//nl
      case ('indicators')
         s = s//'  --tau S           sampling interval of the time series; default ' &
             //real_str(ch%tau)//nl
      case ('divergence')
         s = s//'  --output-dt S     sampling interval of |delta|; default ' &
             //real_str(cfg%output_dt)//nl// &
             '  --delta0 D        initial distance in (q, w) [rad, rad/s]; default ' &
             //real_str(ch%delta0)//nl// &
             '  --same-energy     put the partner on the energy surface of the reference'//nl// &
             '  --pairs N         pairs averaged; pair k starts at t = (k-1)*spacing on the'//nl// &
             '                    orbit of the initial state; default '//to_str(ch%pairs)//nl// &
             '  --pair-spacing S  time between pair starts; default ' &
             //real_str(ch%pair_spacing)//nl// &
             '  --fit-start S, --fit-end S  fit window; default automatic (from 1 decade'//nl// &
             '                    above delta0 to 1.5 decades below saturation)'//nl// &
             '  --lyapunov-t S    duration of the Benettin run reported beside (0: none);' &
             //nl//'                    default '//real_str(ch%lyapunov_t)//nl
      case default
         s = s//'  --energy J        energy of the section; default: that of the initial state' &
             //nl//'                    (--q1 --q2 --w1 --w2; 0 J = both links horizontal' &
             //' at rest)'//nl//'  --ics N           orbits; default '//to_str(ch%n_ics)//nl// &
             '  --points N        most section points per orbit; default ' &
             //to_str(ch%n_points)//nl// &
             '  --section-link L  link whose angle defines the section, 1 or 2; default ' &
             //to_str(ch%section_link)//nl// &
             '  --section-angle A section angle (mod 2 pi); default '// &
             real_str(ch%section_angle)//nl// &
             '  --section-direction D  +1: crossing with w_L > 0, -1: w_L < 0, 0: both;' &
             //' default '//to_str(ch%section_direction)//nl
      end select
      s = s//'  --output FILE     HDF5 file to write; default '//cfg%output//nl// &
          '  --force           overwrite an existing output file'//nl// &
          '  --quiet           print only the last line (the result scripts read)'//nl// &
          '  -h, --help        this text'
   contains
      !> What --t-end means for the command.
      function t_end_text(command) result(t)
         character(len=*), intent(in) :: command
         character(len=:), allocatable :: t
         select case (command)
         case ('divergence'); t = 'duration of each pair'
         case ('poincare'); t = 'longest integration of each orbit'
         case default; t = 'end time'
         end select
      end function t_end_text
   end function chaos_help

   !> Read the group &chaos of `filename` into `ch` (absent group: unchanged).
   subroutine read_chaos_config(filename, ch, error)
      character(len=*), intent(in) :: filename          !! namelist file
      type(chaos_config_t), intent(inout) :: ch         !! updated from the file
      type(error_t), allocatable, intent(out) :: error  !! unreadable or invalid
      real(dp) :: tau, delta0, pair_spacing, fit_start, fit_end, lyapunov_t, energy, &
                  section_angle
      integer :: vectors, batches, pairs, n_ics, n_points, section_link, section_direction
      logical :: same_energy
      integer :: unit, stat
      character(len=512) :: msg
      namelist /chaos/ tau, vectors, batches, delta0, same_energy, pairs, pair_spacing, &
         fit_start, fit_end, lyapunov_t, n_ics, n_points, energy, section_link, &
         section_angle, section_direction
      tau = ch%tau; vectors = ch%vectors; batches = ch%batches
      delta0 = ch%delta0; same_energy = ch%same_energy; pairs = ch%pairs
      pair_spacing = ch%pair_spacing; fit_start = ch%fit_start; fit_end = ch%fit_end
      lyapunov_t = ch%lyapunov_t; n_ics = ch%n_ics; n_points = ch%n_points
      energy = huge(1.0_dp)
      section_link = ch%section_link; section_angle = ch%section_angle
      section_direction = ch%section_direction
      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//printable(filename)//"'")
         return
      end if
      read (unit, nml=chaos, iostat=stat, iomsg=msg)
      close (unit)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'chaos', msg))
         return
      end if
      ch%tau = tau; ch%vectors = vectors; ch%batches = batches
      ch%delta0 = delta0; ch%same_energy = same_energy; ch%pairs = pairs
      ch%pair_spacing = pair_spacing; ch%fit_start = fit_start; ch%fit_end = fit_end
      ch%lyapunov_t = lyapunov_t; ch%n_ics = n_ics; ch%n_points = n_points
      if (energy /= huge(1.0_dp)) then
         ch%energy = energy
         ch%energy_given = .true.
      end if
      ch%section_link = section_link; ch%section_angle = section_angle
      ch%section_direction = section_direction
   end subroutine read_chaos_config

   !> Build the configuration of `command` from defaults, --config and flags.
   subroutine parse_chaos(command, args, cfg, ch, help, error)
      character(len=*), intent(in) :: command           !! 'lyapunov', 'divergence', 'poincare'
      type(arg_t), intent(in) :: args(:)                !! arguments after the command
      type(run_config_t), intent(out) :: cfg            !! run configuration
      type(chaos_config_t), intent(out) :: ch           !! chaos settings
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value, config
      logical :: matched, missing
      integer :: i
      cfg = chaos_run_defaults(command)
      ch = chaos_defaults(command)
      help = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_run_config(config, cfg, error, &
                              extra_groups=[character(len=16) :: 'chaos'])
         if (allocated(error)) return
         call read_chaos_config(config, ch, error)
         if (allocated(error)) return
      end if
      i = 1
      do while (i <= size(args))
         select case (args(i)%s)
         case ('--force')
            cfg%force = .true.
            i = i + 1
            cycle
         case ('--same-energy')
            if (command == 'divergence') then
               ch%same_energy = .true.
               i = i + 1
               cycle
            end if
         end select
         if (args(i)%s(1:min(2, len(args(i)%s))) /= '--' .and. args(i)%s /= '-o') then
            call fatal_error(error, "unexpected argument '"//printable(args(i)%s)//"' (dpend "// &
                             command//' --help lists the options)')
            return
         end if
         call next_option(args, i, name, value, .true., error, missing)
         if (name == '--config') cycle
         call take_initial_run_flag(cfg, name, value, missing, matched, error)
         if (.not. matched .and. name /= '--save-every' .and. &
             (name /= '--output-dt' .or. command == 'divergence')) &
            call apply_run_flag(cfg, name, value, matched, error)
         if (.not. matched) call apply_chaos_flag(command, ch, name, value, matched, error)
         if (command == 'divergence') then
            call option_outcome(command, name, matched, missing, &
                                [character(len=16) :: '--force', '--same-energy'], error, &
                                chaos_help(command))
         else
            call option_outcome(command, name, matched, missing, &
                                [character(len=16) :: '--force'], error, chaos_help(command))
         end if
         if (allocated(error)) return
      end do
      call validate_run_config(cfg, error)
      if (allocated(error)) return
      ! the command's own times, given in the run's unit (dt and t_end are converted)
      ch%tau = cfg%seconds(ch%tau)
      ch%pair_spacing = cfg%seconds(ch%pair_spacing)
      ch%fit_start = cfg%seconds(ch%fit_start)
      ch%fit_end = cfg%seconds(ch%fit_end)
      ch%lyapunov_t = cfg%seconds(ch%lyapunov_t)
      call validate_chaos(cfg, ch, error)
   end subroutine parse_chaos

   !> Apply one of the flags of `command`; `matched` is false if it is not one.
   subroutine apply_chaos_flag(command, ch, name, value, matched, error)
      character(len=*), intent(in) :: command           !! command name
      type(chaos_config_t), intent(inout) :: ch         !! settings to update
      character(len=*), intent(in) :: name              !! option
      character(len=*), intent(in) :: value             !! its value
      logical, intent(out) :: matched                   !! it is a flag of the command
      type(error_t), allocatable, intent(out) :: error  !! invalid value
      matched = .true.
      select case (command//' '//name)
      case ('lyapunov --tau'); call parse_real(value, name, ch%tau, error)
      case ('lyapunov --vectors'); call parse_int(value, name, ch%vectors, error)
      case ('lyapunov --batches'); call parse_int(value, name, ch%batches, error)
      case ('indicators --tau'); call parse_real(value, name, ch%tau, error)
      case ('divergence --delta0'); call parse_real(value, name, ch%delta0, error)
      case ('divergence --pairs'); call parse_int(value, name, ch%pairs, error)
      case ('divergence --pair-spacing'); call parse_real(value, name, ch%pair_spacing, error)
      case ('divergence --fit-start'); call parse_real(value, name, ch%fit_start, error)
      case ('divergence --fit-end'); call parse_real(value, name, ch%fit_end, error)
      case ('divergence --lyapunov-t'); call parse_real(value, name, ch%lyapunov_t, error)
      case ('poincare --energy')
         call parse_real(value, name, ch%energy, error)
         ch%energy_given = .true.
      case ('poincare --ics'); call parse_int(value, name, ch%n_ics, error)
      case ('poincare --points'); call parse_int(value, name, ch%n_points, error)
      case ('poincare --section-link'); call parse_int(value, name, ch%section_link, error)
      case ('poincare --section-angle'); call parse_real(value, name, ch%section_angle, error)
      case ('poincare --section-direction')
         call parse_int(value, name, ch%section_direction, error)
      case default
         matched = .false.
      end select
   end subroutine apply_chaos_flag

   !> Check the settings of the command; messages name the field and the range
   !> (limits and reasons in `dpend_limits`). Counts are compared before any division:
   !> steps (fixed-step methods) at most `max_steps` per integration, renormalisations,
   !> samples and section points at most `max_samples`, and what is kept must fit
   !> the available memory and the free space of the output's file system.
   subroutine validate_chaos(cfg, ch, error)
      type(run_config_t), intent(in) :: cfg             !! run configuration (validated)
      type(chaos_config_t), intent(in) :: ch            !! chaos settings
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      class(integrator_t), allocatable :: integ
      logical :: fixed
      if (.not. finite_positive(cfg%t_end)) then
         call fatal_error(error, 'invalid t_end: must be finite and > 0 (s)')
         return
      end if
      call new_integrator(cfg%method, integ, error)
      if (allocated(error)) return
      fixed = .not. integ%adaptive()
      select case (ch%command)
      case ('lyapunov'); call validate_lyapunov(cfg, ch, fixed, error)
      case ('indicators'); call validate_indicators(cfg, ch, fixed, error)
      case ('divergence'); call validate_divergence(cfg, ch, fixed, error)
      case ('poincare'); call validate_poincare(cfg, ch, error)
      end select
   end subroutine validate_chaos

   !> `dpend lyapunov`: tau, vectors, batches; renormalisations kept.
   subroutine validate_lyapunov(cfg, ch, fixed, error)
      type(run_config_t), intent(in) :: cfg             !! run configuration (validated)
      type(chaos_config_t), intent(in) :: ch            !! chaos settings
      logical, intent(in) :: fixed                      !! a fixed-step method
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      real(dp) :: n
      if (.not. (finite_positive(ch%tau) .and. in_range(ch%tau, 0.0_dp, max_time))) then
         call fatal_error(error, 'invalid tau: must be in (0, '//sci(max_time)//'] (s)')
      else if (fixed .and. ch%tau < cfg%dt) then
         call fatal_error(error, 'invalid tau: '//sci(ch%tau)//' s is below the step dt = ' &
                          //sci(cfg%dt)//' s of '//cfg%method//' (renormalisations '// &
                          'happen at step ends; use tau >= dt)')
      else if (ch%vectors /= all_vectors .and. &
               (ch%vectors < 1 .or. ch%vectors > cfg%model%n_state())) then
         call fatal_error(error, 'invalid vectors: '//to_str(ch%vectors)// &
                          ' must be an integer from 1 to '//to_str(cfg%model%n_state())// &
                          ' (2N for N links)')
      else if (ch%batches < 1 .or. ch%batches > 100000) then
         call fatal_error(error, 'invalid batches: must be an integer from 1 to 100000')
      end if
      if (allocated(error)) return
      call check_count('tau', ch%tau, cfg%t_end, 't_end', max_samples, &
                       'renormalisations', 'use a larger --tau or a shorter --t-end', error)
      if (allocated(error)) return
      n = cfg%t_end/ch%tau + 2.0_dp
      call check_resources(cfg%output, 'tau', n, 3.0_dp*8.0_dp*real(1 + n_vectors(ch, cfg), dp), &
                           8.0_dp*real(1 + n_vectors(ch, cfg), dp), sci(n)// &
                           ' renormalisations', &
                           'use a larger --tau', error)
   end subroutine validate_lyapunov

   !> `dpend indicators`: tau; samples kept.
   subroutine validate_indicators(cfg, ch, fixed, error)
      type(run_config_t), intent(in) :: cfg             !! run configuration (validated)
      type(chaos_config_t), intent(in) :: ch            !! chaos settings
      logical, intent(in) :: fixed                      !! a fixed-step method
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      real(dp) :: n
      if (.not. (finite_positive(ch%tau) .and. in_range(ch%tau, 0.0_dp, max_time))) then
         call fatal_error(error, 'invalid tau: '//sci(ch%tau)//' must be in (0, '// &
                          sci(max_time)//'] (s)')
      else if (fixed .and. ch%tau < cfg%dt) then
         call fatal_error(error, 'invalid tau: '//sci(ch%tau)//' s is below the step dt = ' &
                          //sci(cfg%dt)//' s of '//cfg%method//' (samples are taken '// &
                          'at step ends; use tau >= dt)')
      end if
      if (allocated(error)) return
      call check_count('tau', ch%tau, cfg%t_end, 't_end', max_samples, &
                       'samples', 'use a larger --tau or a shorter --t-end', error)
      if (allocated(error)) return
      n = cfg%t_end/ch%tau + 2.0_dp
      ! per sample: time, FLI, SALI, 2N log-norms, 2N Y, 2N <Y>, 2N-1 GALI; copies
      call check_resources(cfg%output, 'tau', n, &
                           3.0_dp*8.0_dp*real(2 + 8*cfg%model%n_state(), dp), &
                           8.0_dp*real(2 + 8*cfg%model%n_state(), dp), sci(n)// &
                           ' samples', 'use a larger --tau', error)
   end subroutine validate_indicators

   !> The times the torques must cover, in words for the help.
   pure function torque_span_text(command) result(s)
      character(len=*), intent(in) :: command  !! command name
      character(len=:), allocatable :: s
      select case (command)
      case ('divergence')
         s = '[0, max((pairs-1) pair_spacing + t_end, lyapunov_t)]'
      case ('poincare')
         s = '[0, t_end] (refused: a section needs a conservative model)'
      case default
         s = '[0, t_end]'
      end select
   end function torque_span_text

   !> `dpend divergence`: delta0, the pairs, the fit window, lyapunov_t, output_dt;
   !> steps, samples and renormalisations kept.
   subroutine validate_divergence(cfg, ch, fixed, error)
      type(run_config_t), intent(in) :: cfg             !! run configuration (validated)
      type(chaos_config_t), intent(in) :: ch            !! chaos settings
      logical, intent(in) :: fixed                      !! a fixed-step method
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      real(dp) :: n, y_max, span
      y_max = max(1.0_dp, maxval(abs(cfg%q0())), maxval(abs(cfg%w0())))
      if (.not. finite_positive(ch%delta0) .or. .not. finite_positive(0.1_dp - ch%delta0)) &
         then
         call fatal_error(error, 'invalid delta0: must be in (0, 0.1) (rad, rad/s)')
      else if (ch%delta0 < min_delta0_relative*y_max) then
         call fatal_error(error, 'invalid delta0: '//sci(ch%delta0)//' is below '// &
                          sci(min_delta0_relative*y_max)//' = 1e-13 max(1, |state|): '// &
                          'the displacement would be lost in the rounding of the state')
      else if (ch%pairs < 1 .or. ch%pairs > 100000) then
         call fatal_error(error, 'invalid pairs: must be an integer from 1 to 100000')
      else if (.not. (finite_positive(ch%pair_spacing) .and. &
                    in_range(ch%pair_spacing, 0.0_dp, max_time))) then
         call fatal_error(error, 'invalid pair_spacing: must be in (0, '//sci(max_time)// &
                          '] (s)')
      else if (ch%pair_spacing*real(ch%pairs - 1, dp) > max_time) then
         call fatal_error(error, 'invalid pair_spacing: (pairs - 1) * pair_spacing = ' &
                          //sci(ch%pair_spacing*real(ch%pairs - 1, dp))//' s is above ' &
                          //sci(max_time)//' s')
      else if (.not. (in_range(ch%fit_start, 0.0_dp, max_time) .and. &
                      in_range(ch%fit_end, 0.0_dp, max_time))) then
         call fatal_error(error, 'invalid fit_start/fit_end: must be in [0, '// &
                          sci(max_time)//'] (s)')
      else if (ch%fit_end > 0.0_dp .and. ch%fit_end <= ch%fit_start) then
         call fatal_error(error, 'invalid fit_end: must be > fit_start (s), or 0 (automatic)')
      else if (.not. in_range(ch%lyapunov_t, 0.0_dp, max_time)) then
         call fatal_error(error, 'invalid lyapunov_t: must be in [0, '//sci(max_time)// &
                          '] (s; 0 = none)')
      else if (.not. finite_positive(cfg%output_dt) .or. cfg%output_dt > cfg%t_end) then
         call fatal_error(error, 'invalid output_dt: must be > 0 and <= t_end (s)')
      end if
      if (allocated(error)) return
      if (fixed) then
         call check_count('pair_spacing', cfg%dt, ch%pair_spacing*real(ch%pairs - 1, dp), &
                          '(pairs - 1) * pair_spacing', max_steps, 'steps', &
                          'use a larger --dt, fewer --pairs or a shorter --pair-spacing', &
                          error)
         if (allocated(error)) return
         call check_count('lyapunov_t', cfg%dt, ch%lyapunov_t, 'lyapunov_t', max_steps, &
                          'steps', 'use a larger --dt or a shorter --lyapunov-t', error)
         if (allocated(error)) return
      end if
      call check_count('lyapunov_t', 0.5_dp, ch%lyapunov_t, 'lyapunov_t', max_samples, &
                       'renormalisations', 'use a shorter --lyapunov-t', error)
      if (allocated(error)) return
      call check_count('output_dt', cfg%output_dt, cfg%t_end, 't_end', max_samples, &
                       'samples', 'use a larger --output-dt or a shorter --t-end', error)
      if (allocated(error)) return
      n = cfg%t_end/cfg%output_dt + 2.0_dp
      ! per sample: times, two (4, n) state arrays and their copies, the pairs' curves
      call check_resources(cfg%output, 'output_dt', n, 8.0_dp*(20.0_dp + real(ch%pairs, dp)), &
                           8.0_dp*(2.0_dp + real(ch%pairs, dp)), sci(n)//' samples of ' &
                           //to_str(ch%pairs)//' pair(s)', &
                           'use a larger --output-dt or fewer --pairs', error)
      if (allocated(error)) return
      ! pair p runs [(p − 1) pair_spacing, (p − 1) pair_spacing + t_end] of the driven
      ! orbit; Benettin's lambda1 [0, lyapunov_t]
      if (cfg%torque%active()) then
         span = max(ch%pair_spacing*real(ch%pairs - 1, dp) + cfg%t_end, ch%lyapunov_t)
         if (.not. cfg%torque%covers(0.0_dp, span)) then
            call fatal_error(error, 'invalid torque_file: the runs span [0, '//sci(span, 6) &
                             //'] s ((pairs - 1) pair_spacing + t_end, lyapunov_t), the ' &
                             //'torques are '//cfg%torque%text()//' (a series is not ' &
                             //'extrapolated; --lyapunov-t 0 skips Benettin''s exponent)')
            return
         end if
      end if
      n = ch%lyapunov_t/0.5_dp + 2.0_dp
      call check_resources(cfg%output, 'lyapunov_t', n, 48.0_dp, 0.0_dp, &
                           sci(n)//' renormalisations', &
                           'use a shorter --lyapunov-t', error)
   end subroutine validate_divergence

   !> `dpend poincare`: a model with sections, the orbits, the section, the energy;
   !> section points kept.
   subroutine validate_poincare(cfg, ch, error)
      type(run_config_t), intent(in) :: cfg             !! run configuration (validated)
      type(chaos_config_t), intent(in) :: ch            !! chaos settings
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      real(dp) :: n, e_lim
      e_lim = energy_limit(cfg%pendulum(), max_angular_velocity)
      if (.not. cfg%model%energy_sections()) then
         call fatal_error(error, 'invalid command: poincare needs a model with '// &
                          'energy-shell sections; the '//cfg%model%name()//' has none')
      else if (ch%n_ics < 1 .or. ch%n_ics > 1000000) then
         call fatal_error(error, 'invalid n_ics (--ics): must be an integer from 1 to 1000000')
      else if (ch%n_points < 1) then
         call fatal_error(error, 'invalid n_points (--points): must be an integer >= 1')
      else if (real(ch%n_points, dp)*real(ch%n_ics, dp) > real(max_samples, dp)) then
         call fatal_error(error, 'invalid n_points (--points): '//to_str(ch%n_ics)// &
                          ' orbits of '//to_str(ch%n_points)//' points keep more than ' &
                          //sci(real(max_samples, dp))//' section points (fewer points)')
      else if (ch%section_link /= 1 .and. ch%section_link /= 2) then
         call fatal_error(error, 'invalid section_link: must be 1 or 2')
      else if (abs(ch%section_direction) > 1) then
         call fatal_error(error, 'invalid section_direction: must be -1, 0 or 1')
      end if
      if (allocated(error)) return
      call check_range('section_angle', ch%section_angle, -max_angle, max_angle, 'rad', &
                       error)
      if (allocated(error)) return
      call check_range('energy', ch%energy, -e_lim, e_lim, 'J', error, 'the energy of '// &
                       'angular velocities up to 1e6 rad/s with these parameters')
      if (allocated(error)) return
      n = real(ch%n_points, dp)*real(ch%n_ics, dp)
      ! per point: the orbit's buffers (4 reals), the gathered result (5) and copies
      call check_resources(cfg%output, 'n_points (--points)', n, 2.0_dp*8.0_dp*9.0_dp, 48.0_dp, &
                           sci(n)//' section points', 'use fewer --points or --ics', error)
   end subroutine validate_poincare

   !> Memory (n·per_memory) and file size (n·per_file, on the file system of `output`)
   !> of n kept items.
   subroutine check_resources(output, field, n, per_memory, per_file, what, hint, err)
      character(len=*), intent(in) :: output            !! the output file
      character(len=*), intent(in) :: field, what, hint !! for the message
      real(dp), intent(in) :: n                         !! items kept
      real(dp), intent(in) :: per_memory, per_file      !! bytes per item
      type(error_t), allocatable, intent(out) :: err    !! does not fit
      call check_memory(field, n*per_memory, what, hint, err)
      if (allocated(err) .or. per_file <= 0.0_dp) return
      call check_disk(field, n*per_file + 65536.0_dp, output, hint, err)
   end subroutine check_resources

   !> A chaos command `command` from its arguments (after the command's name) to its
   !> summary: parse → settings → `run_command` (the command's run and file, through
   !> `run_chaos`) → the summary on standard output (with --quiet its last line). A
   !> refusal or a failed run comes back as `error`, its message the one line 'dpend
   !> COMMAND: ...'; the summary of a run that stopped early is printed before.
   subroutine chaos_command(command, args, run_command, error)
      character(len=*), intent(in) :: command           !! 'lyapunov', 'divergence', ...
      type(arg_t), intent(in) :: args(:)                !! the arguments after the command
      procedure(chaos_run_body) :: run_command          !! the command's run and writing
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(run_config_t) :: cfg
      type(chaos_config_t) :: ch
      character(len=:), allocatable :: summary
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_chaos(command, rest, cfg, ch, help, error)
      if (allocated(error)) then
         call refusal_line(error, command)
         return
      end if
      if (help) then
         write (output_unit, '(a)') chaos_help(command)
         return
      end if
      call run_chaos(cfg, ch, run_command, summary, error)
      if (quiet .and. .not. allocated(error)) summary = last_line(summary)
      if (len(summary) > 0) write (output_unit, '(a)') summary
      if (allocated(error)) call error_line(error, command)
   end subroutine chaos_command

   !> Run the command: `run_command`, the run and file writing of `ch%command`,
   !> between the making of the method and the installing of the file. `error` is
   !> set for invalid input (nothing written) or for a failed run (`failed`; the
   !> file holds what was computed before). `summary` is the text for standard
   !> output, its last line the scripting line.
   subroutine run_chaos(cfg, ch, run_command, summary, error)
      type(run_config_t), intent(in) :: cfg             !! validated run configuration
      type(chaos_config_t), intent(in) :: ch            !! validated chaos settings
      procedure(chaos_run_body) :: run_command          !! the command's run and writing
      character(len=:), allocatable, intent(out) :: summary  !! standard output
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      class(integrator_t), allocatable :: integ
      type(output_t) :: out
      type(error_t), allocatable :: werr
      logical :: failed   ! the run stopped early: its file holds what was computed
      failed = .false.
      summary = ''
      call new_integrator(cfg%method, integ, error, method_options_t(rtol=cfg%rtol, &
                          atol=cfg%atol, omega=cfg%omega, max_steps=cfg%max_steps))
      if (allocated(error)) return
      call out%begin(cfg%output, cfg%force, error)
      if (allocated(error)) return
      call run_command(cfg, ch, integ, out%temp, summary, error, failed)
      ! the summary's first line names a body other than the uniform rod
      if (len(summary) > 0 .and. len(cfg%model%body_description()) > 0) &
         summary = 'dpend '//ch%command//': links: '//cfg%model%body_description() &
                   //new_line('a')//summary
      ! a complete file (also of a run that stopped early) goes into place; a file
      ! whose writing failed is removed and the old output stays as it was
      if (.not. allocated(error) .or. failed) then
         call out%commit(werr)
         if (allocated(werr)) call move_alloc(werr, error)
      end if
      call out%explain(error)
      call out%discard()
      ! refused input found only now (made as error_bad_input: an energy with no state
      ! on the section) keeps exit status 2; any other error ends a run that had started
      if (allocated(error)) then
         if (.not. failed) summary = ''
         call run_failure(error)
      end if
   end subroutine run_chaos

   !> Root attributes shared by the chaos commands.
   subroutine write_common(h5, cfg, integ, command, status)
      type(h5file_t), intent(inout) :: h5          !! the file (keeps the first failure)
      type(run_config_t), intent(in) :: cfg
      class(integrator_t), intent(in) :: integ
      character(len=*), intent(in) :: command, status
      call h5%writeattr('/', 'command', command)
      call record_model(h5, cfg%model)
      call h5%writeattr('/', 'method', integ%name())
      call h5%writeattr('/', 'order', integ%order())
      call h5%writeattr('/', 'dt', cfg%dt)
      call h5%writeattr('/', 't_end', cfg%t_end)
      if (integ%adaptive()) then
         call h5%writeattr('/', 'rtol', cfg%rtol)
         call h5%writeattr('/', 'atol', cfg%atol)
      end if
      call h5%writeattr('/', 'q0', cfg%q0())
      call h5%writeattr('/', 'qdot0', cfg%w0())
      call h5%writeattr('/', 'links', cfg%links)
      call h5%writeattr('/', 'm', cfg%m(:cfg%links))
      call h5%writeattr('/', 'l', cfg%l(:cfg%links))
      call h5%writeattr('/', 'energy0', cfg%model%energy(0.0_dp, [cfg%q0(), cfg%w0()]))
      if (cfg%torque%active()) call h5%writeattr('/', 'torque', cfg%torque%text())
      if (allocated(cfg%torque_file)) call h5%writeattr('/', 'torque_file', cfg%torque_file)
      if (cfg%initial_angles == 'relative') call h5%writeattr('/', 'initial_angles', &
         'relative (given; q0 and qdot0 are the absolute ones)')
      call h5%writeattr('/', 'n_steps', integ%n_steps)
      call h5%writeattr('/', 'status', status)
      call h5%writeattr('/', 'version', version)
   end subroutine write_common

   !> 'completed' or the failure and the time reached (t < 0: not known).
   function run_status(stat, t) result(s)
      integer, intent(in) :: stat
      real(dp), intent(in) :: t
      character(len=:), allocatable :: s
      if (stat == stat_ok) then
         s = 'completed'
      else if (t >= 0.0_dp) then
         s = status_message(stat)//' after t = '//num(t)//' s'
      else
         s = status_message(stat)
      end if
   end function run_status

   !> Mark the run as failed: `error` names the failure and the file that holds
   !> what was computed before it.
   subroutine stopped(status, output, error, failed)
      character(len=*), intent(in) :: status, output
      type(error_t), allocatable, intent(inout) :: error
      logical, intent(inout) :: failed
      failed = .true.
      call fatal_error(error, 'run stopped: '//status//"; '"//output// &
                       "' holds what was computed before the failure", error_run_failed)
   end subroutine stopped

   !> Tangent vectors of `dpend lyapunov`: --vectors, or all 2N when not given.
   pure integer function n_vectors(ch, cfg)
      type(chaos_config_t), intent(in) :: ch  !! chaos settings
      type(run_config_t), intent(in) :: cfg   !! run settings (model built)
      n_vectors = ch%vectors
      if (n_vectors == all_vectors) n_vectors = cfg%model%n_state()
   end function n_vectors

   !> Compact text of a number for summaries: up to 6 significant digits.
   pure function num(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      s = real_str(x, 6)
   end function num

   !> A number in exponent form with 8 significant digits (es15.7, no blanks);
   !> 'nan' for NaN.
   pure function es(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      if (ieee_is_nan(x)) then
         s = 'nan'
         return
      end if
      write (buf, '(es15.7)') x
      s = trim(adjustl(buf))
   end function es

   !> A number with 3 decimals (f0.3), with its leading 0 below 1.
   pure function fixed(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(f0.3)') x
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0'//s
      if (len(s) >= 2) then
         if (s(1:2) == '-.') s = '-0'//s(2:)
      end if
   end function fixed

end module dpend_chaos_common
