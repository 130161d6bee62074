!> The `dpend` command: subcommands over the dpend library.
!> Exit status: 0 success, 1 a run that started and failed, 2 invalid input.
program dpend
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use dpend_error, only: error_t, exit_status
   use dpend_cli, only: arg_t, get_arguments, printable, check_repeated_options
   use dpend_run_settings, only: run_config_t
   use dpend_method_registry, only: method_names, method_table, n_methods, plot_groups
   use dpend_simulate, only: natural_text
   use dpend_simulate, only: parse_simulate, run_simulate, simulate_help
   use dpend_version, only: version, slow_build_note
   use dpend_export, only: export_columns, export_matrix, export_list
   use dpend_chaos_common, only: chaos_config_t, parse_chaos, run_chaos, chaos_help
   use dpend_lyapunov_command, only: run_lyapunov
   use dpend_divergence_command, only: run_divergence
   use dpend_poincare_command, only: run_poincare
   use dpend_indicators_command, only: run_indicators
   use dpend_sweep_settings, only: sweep_config_t, horizon_text
   use dpend_sweep_config, only: parse_sweep, sweep_help
   use dpend_sweep, only: run_sweep, sweep_summary_t, compare_sweeps, summary_text
   use dpend_sweep_agreement, only: agreement_options_t, sweep_agreement
   use dpend_cli, only: parse_real, is_long_option, next_option, option_outcome, to_str, &
                        real_str, pad, unknown_option_text
   use dpend_strings, only: did_you_mean
   use dpend_kinds, only: dp
   use dpend_model_factory, only: describe_models
   use, intrinsic :: iso_c_binding, only: c_int
   use dpend_study_settings, only: study_config_t
   use dpend_study_config, only: parse_study, study_help
   use dpend_study_command, only: run_study_command
   use dpend_animate, only: animate_config_t, parse_animate, run_animate, animate_help
   use dpend_fit_command, only: fit_config_t, parse_fit, run_fit, fit_help
   use dpend_output, only: track_inputs
   use dpend_progress, only: silence_progress, progress_header
   use dpend_limits, only: bound_threads
   implicit none

   interface
      !> POSIX _exit(2): end the process at once, without exit handlers.
      subroutine c_exit(status) bind(C, name='_exit')
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit
   end interface

   type(arg_t), allocatable :: args(:)
   character(len=*), parameter :: nl = new_line('a')
   !> The --quiet line of the help texts that lack one (every command's
   !> --help mentions it).
   character(len=*), parameter :: summary_quiet = '  --quiet           no progress ' &
      //'report; of the summary only its last line'
   character(len=*), parameter :: data_quiet = '  --quiet           accepted (every ' &
      //'command takes it); the data print as always'
   !> --quiet was given: no progress report, and of a command's summary only its last
   !> line (sweep reads its own --quiet).
   logical :: quiet = .false.
   !> The commands (for the suggestion on a mistyped one).
   character(len=*), parameter :: command_names = 'simulate lyapunov indicators divergence ' &
      //'poincare sweep sweep-compare export study animate fit methods models version help'

   ! every input a command reads is registered: an output never replaces one
   call track_inputs(.true.)
   call get_arguments(args)
   block   ! the OpenMP runtime's threads from the environment, bounded as --threads
      character(len=:), allocatable :: note
      call bound_threads(note)
      if (len(note) > 0) write (error_unit, '(a)') 'dpend: '//note
   end block
   if (size(args) == 0) then
      write (output_unit, '(a)') main_help()
      stop 0, quiet=.true.
   end if
   block   ! an option given twice is refused for every command, before any parsing
      type(error_t), allocatable :: error
      call check_repeated_options(args(2:), error)
      if (allocated(error)) call fail(2, 'dpend '//printable(args(1)%s)//': '// &
                                      error%message)
   end block
   if (args(1)%s /= 'sweep') call take_quiet(args)
   select case (args(1)%s)
   case ('-h', '--help', 'help')
      write (output_unit, '(a)') main_help()
   case ('--version', 'version')
      write (output_unit, '(a)') 'dpend '//version
   case ('methods')
      call methods(args(2:))
   case ('models')
      call models(args(2:))
   case ('simulate')
      call simulate(args(2:))
   case ('export')
      call export(args(2:))
   case ('lyapunov', 'divergence', 'poincare', 'indicators')
      call chaos(args(1)%s, args(2:))
   case ('sweep')
      call sweep(args(2:))
   case ('sweep-compare')
      call sweep_compare(args(2:))
   case ('study')
      call study(args(2:))
   case ('animate')
      call animate(args(2:))
   case ('fit')
      call fit(args(2:))
   case default
      block
         character(len=:), allocatable :: hint
         hint = did_you_mean(args(1)%s, command_names)
         if (len(hint) > 0) hint = hint//' '
         call fail(2, "dpend: unknown command '"//printable(args(1)%s)//"' ("//hint// &
                   'dpend --help lists them)')
      end block
   end select

contains

   !> Remove every `--quiet` from the arguments after the command (all commands
   !> take it; values never start with '--'): `quiet` is set and every progress
   !> report of the process silenced.
   subroutine take_quiet(all)
      type(arg_t), allocatable, intent(inout) :: all(:)
      integer :: i
      if (size(all) < 2) return
      if (.not. any([(all(i)%s == '--quiet', i=2, size(all))])) return
      quiet = .true.
      call silence_progress()
      all = [all(1), pack(all(2:), [(all(i)%s /= '--quiet', i=2, size(all))])]
   end subroutine take_quiet

   !> The last line of `text` (without a trailing line end).
   pure function last_line(text) result(s)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: s
      integer :: n
      n = len(text)
      if (n > 0) then
         if (text(n:n) == new_line('a')) n = n - 1
      end if
      s = text(index(text(:n), new_line('a'), back=.true.) + 1:n)
   end function last_line

   !> `help` with the --quiet line `line` appended where it does not mention --quiet.
   function with_quiet(help, line) result(s)
      character(len=*), intent(in) :: help  !! a command's help text
      character(len=*), intent(in) :: line  !! the --quiet line
      character(len=:), allocatable :: s
      s = help
      if (index(help, '--quiet') == 0) s = help//nl//line
   end function with_quiet

   function main_help() result(s)
      character(len=:), allocatable :: s
      s = 'dpend '//version//' - the compound double pendulum, chains of N rods and the'// &
          nl//'elastic pendulum: trajectories, chaos, maps, accuracy studies, fits'//nl//nl// &
          'usage: dpend COMMAND [options]     (dpend COMMAND --help for its options)'//nl//nl// &
          'commands:'//nl// &
          '  simulate   integrate one trajectory and write it to HDF5'//nl// &
          '  lyapunov   Lyapunov exponents (Benettin, QR) with their running estimates'//nl// &
          '  indicators chaos indicators MEGNO, FLI, SALI, GALI_k against time'//nl// &
          '  divergence divergence of nearby trajectories, fitted exponential slope'//nl// &
          '  poincare   Poincare section at one energy'//nl// &
          '  sweep      maps over initial conditions (flip time, energy error, Lyapunov)'//nl// &
          '  sweep-compare  accuracy report: flip times of two sweeps (e.g. dt, dt/2)'//nl// &
          '  export     print HDF5 datasets as text columns, CSV or a matrix; --list'//nl// &
          '  study      energy-conservation study of every method: data, summary, figures'//nl// &
          '  animate    animated GIF of a simulate file (gnuplot): rods, tip trail, time'//nl// &
          '  fit        estimate the initial state (and damping) from measured angles (CSV)' &
          //nl// &
          '  methods    the integration methods: order, properties, commands'//nl// &
          '  models     the models: coordinates, parameters (units, ranges), capabilities' &
          //nl// &
          '  version    print the version'//nl//nl// &
          'models (--model NAME; dpend models lists parameters, ranges, capabilities):'//nl// &
          '  pendulum   N uniform rods hinged in a chain (--links N, default 2: the'//nl// &
          '             chapter''s compound double pendulum; --m, --l: one value per link)'// &
          nl//'             with optional joint damping (--damping c1,c2,...) and a moving'// &
          nl//'             support (--support-amplitude ax,ay --support-frequency w'//nl// &
          '             --support-phase px,py): simulate, lyapunov, indicators,'//nl// &
          '             divergence and fit take them, study as cases of &study; sweep'// &
          nl//'             and poincare need the conservative chain'//nl// &
          '  elastic    a point mass on a spring (--k, --l0, --m; coordinates r, phi)'//nl//nl// &
          'Every command takes --quiet: no progress report, and of a summary only its'//nl// &
          'last line (export, methods and models print their data as always).'//nl//nl// &
          'Conventions: SI units; angles q1 .. qN in rad from the horizontal x axis,'//nl// &
          'counter-clockwise positive, y up (hanging equilibrium q_i = -pi/2); --theta1'//nl// &
          'and the sweep''s theta axes from the hanging position.'//nl// &
          'Defaults are the chapter''s: m1 = m2 = 1 kg, l1 = l2 = 1 m, g = 9.8 m/s^2.'
   end function main_help

   subroutine simulate(sub)
      type(arg_t), intent(in) :: sub(:)
      type(run_config_t) :: cfg
      type(error_t), allocatable :: error
      logical :: help
      character(len=:), allocatable :: summary
      call parse_simulate(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend simulate: '//error%message)
      if (help) then
         write (output_unit, '(a)') simulate_help()
         return
      end if
      call run_simulate(cfg, error, summary)
      if (allocated(error)) call fail(exit_status(error), 'dpend simulate: '//error%message)
      if (.not. quiet .or. len(summary) == 0) &
         write (output_unit, '(a)') "dpend simulate: wrote '"//cfg%output//"': t = 0 .. " &
         //real_str(cfg%t_end)//' s = '//natural_text(cfg, cfg%t_end)
      if (len(summary) > 0) write (output_unit, '(a)') 'dpend simulate: '//summary
   end subroutine simulate

   !> The chaos commands: lyapunov, divergence, poincare, indicators.
   subroutine chaos(command, sub)
      character(len=*), intent(in) :: command
      type(arg_t), intent(in) :: sub(:)
      type(run_config_t) :: cfg
      type(chaos_config_t) :: ch
      type(error_t), allocatable :: error
      character(len=:), allocatable :: summary
      logical :: help
      call parse_chaos(command, sub, cfg, ch, help, error)
      if (allocated(error)) call fail(2, 'dpend '//command//': '//error%message)
      if (help) then
         write (output_unit, '(a)') chaos_help(command)
         return
      end if
      select case (command)
      case ('lyapunov')
         call run_chaos(cfg, ch, run_lyapunov, summary, error)
      case ('indicators')
         call run_chaos(cfg, ch, run_indicators, summary, error)
      case ('divergence')
         call run_chaos(cfg, ch, run_divergence, summary, error)
      case default
         call run_chaos(cfg, ch, run_poincare, summary, error)
      end select
      if (quiet .and. .not. allocated(error)) summary = last_line(summary)
      if (len(summary) > 0) write (output_unit, '(a)') summary
      if (allocated(error)) call fail(exit_status(error), 'dpend '//command//': '//error%message)
   end subroutine chaos

   subroutine study(sub)
      type(arg_t), intent(in) :: sub(:)
      type(study_config_t) :: cfg
      type(error_t), allocatable :: error
      logical :: help
      call parse_study(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend study: '//error%message)
      if (help) then
         write (output_unit, '(a)') with_quiet(study_help(), summary_quiet)
         return
      end if
      call run_study_command(cfg, error)
      if (allocated(error)) call fail(exit_status(error), 'dpend study: '//error%message)
   end subroutine study

   !> `dpend animate FILE.h5 [options]`: an animated GIF through gnuplot.
   subroutine animate(sub)
      type(arg_t), intent(in) :: sub(:)
      type(animate_config_t) :: cfg
      type(error_t), allocatable :: error
      character(len=:), allocatable :: summary
      logical :: help
      call parse_animate(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend animate: '//error%message)
      if (help) then
         write (output_unit, '(a)') with_quiet(animate_help(), summary_quiet)
         return
      end if
      call run_animate(cfg, summary, error)
      if (allocated(error)) call fail(exit_status(error), 'dpend animate: '//error%message)
      write (output_unit, '(a)') 'dpend animate: '//summary
   end subroutine animate

   !> `dpend fit DATA.csv [options]`: estimates from a measured series.
   subroutine fit(sub)
      type(arg_t), intent(in) :: sub(:)
      type(fit_config_t) :: cfg
      type(error_t), allocatable :: error
      logical :: help
      call parse_fit(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend fit: '//error%message)
      if (help) then
         write (output_unit, '(a)') with_quiet(fit_help(), summary_quiet)
         return
      end if
      call run_fit(cfg, error)
      if (allocated(error)) call fail(exit_status(error), 'dpend fit: '//error%message)
   end subroutine fit

   !> `dpend models`: every model of the factory's catalogue with its coordinates,
   !> parameters (units, ranges, defaults) and capabilities.
   subroutine models(sub)
      type(arg_t), intent(in) :: sub(:)
      if (size(sub) > 0) then
         if (sub(1)%s == '--help' .or. sub(1)%s == '-h') then
            write (output_unit, '(a)') 'usage: dpend models'//nl//nl// &
               'Lists every model dpend can build: its coordinates, its parameters (units,' &
               //nl//'accepted ranges, defaults) and what it supports.'//nl//data_quiet
            return
         end if
         call fail(2, "dpend models: unexpected argument '"//sub(1)%s// &
                   "' (dpend models takes no options)")
      end if
      write (output_unit, '(a)') describe_models()
   end subroutine models

   !> `dpend methods`: one row per method of the registry (dpend_method_registry):
   !> name, variables, order, properties, commands, then a line of description
   !> each; `--names`: the names on one line; `--plot-styles`: the plot groups and
   !> the colour of each method, for scripts/plot_study.sh.
   subroutine methods(sub)
      type(arg_t), intent(in) :: sub(:)
      character(len=:), allocatable :: props, commands, mode, variables
      character(len=*), parameter :: all = 'simulate lyapunov indicators divergence ' &
                                           //'poincare study'
      integer :: i
      mode = 'table'
      do i = 1, size(sub)
         select case (sub(i)%s)
         case ('-h', '--help')
            write (output_unit, '(a)') 'usage: dpend methods [--names | --plot-styles]'//nl &
               //nl//'The integration methods of --method: variables advanced ((q, qdot) or' &
               //nl//'canonical (q, p); (q, p)*: canonical on Hamiltonian models, (q, qdot)' &
               //nl//'on damped or driven ones), classical order, properties and the' &
               //nl//'commands that accept them, then one line of description each.'//nl &
               //'--names prints only the names, on one line (for scripts).'//nl &
               //'--plot-styles prints the study''s plot styles (for scripts), one record a' &
               //nl//'line, words separated by one blank:'//nl &
               //'  group ID TITLE...       a panel of the figures, in panel order'//nl &
               //'  method NAME #RRGGBB ID  a method, its colour and its group'//nl//data_quiet
            return
         case ('--names')
            mode = 'names'
         case ('--plot-styles')
            mode = 'styles'
         case default
            if (is_long_option(sub(i)%s)) then
               call fail(2, 'dpend methods: '//unknown_option_text('methods', sub(i)%s, &
                                                                  '--names --plot-styles --help'))
            end if
            call fail(2, "dpend methods: unexpected argument '"//sub(i)%s// &
                      "' (dpend methods --help)")
         end select
      end do
      select case (mode)
      case ('names')
         write (output_unit, '(a)') method_names()
      case ('styles')
         do i = 1, size(plot_groups)
            write (output_unit, '(a)') 'group '//trim(plot_groups(i)%id)//' '// &
               trim(plot_groups(i)%title)
         end do
         do i = 1, n_methods
            associate (m => method_table(i))
               write (output_unit, '(a)') 'method '//trim(m%name)//' '//m%colour//' '// &
                  trim(m%group)
            end associate
         end do
      case default
         write (output_unit, '(a)') 'method    variables  order  properties' &
            //'                        commands'
         do i = 1, n_methods
            associate (m => method_table(i))
               props = trim(merge('implicit', 'explicit', m%implicit))
               if (m%adaptive) props = props//', adaptive'
               if (m%symplectic) props = props//', symplectic'
               if (m%symmetric) props = props//', symmetric'
               commands = all
               ! fit integrates (q, qdot) (dpend_fit_command); sweep its batch rk4
               if (.not. m%canonical) commands = commands//' fit'
               if (m%name == 'rk4') commands = commands//' sweep'
               variables = '(q, qdot)'
               if (m%canonical) variables = trim(merge('(q, p) ', '(q, p)*', m%hamiltonian))
               write (output_unit, '(a)') m%name//pad(variables, 11)// &
                  pad(to_str(m%order), 7)//pad(props, 34)//commands
            end associate
         end do
         write (output_unit, '(a)') nl//'* (q, p) on Hamiltonian models, (q, qdot) on ' &
            //'damped or driven ones (--damping,'//nl//'  --support-*), where they are ' &
            //'not symplectic; the other (q, p) methods refuse those.' &
            //nl//'sweep accepts only rk4: it integrates with its ' &
            //'own vectorised batch rk4 (dpend sweep --help).'//nl
         do i = 1, n_methods
            write (output_unit, '(a)') method_table(i)%name//trim(method_table(i)%description)
         end do
      end select
   end subroutine methods

   !> `dpend export FILE [--csv] DATASET...`, `FILE --matrix DATASET [XAXIS YAXIS
   !> [SCALE]]` or `FILE --list`; options may stand anywhere. Every failure: one
   !> line, exit 2.
   subroutine export(sub)
      type(arg_t), intent(in) :: sub(:)
      type(error_t), allocatable :: error
      character(len=:), allocatable :: usage
      type(arg_t), allocatable :: pos(:)
      character(len=:), allocatable :: paths(:)
      real(dp) :: scale
      logical :: matrix, csv, list
      integer :: i, n, width
      usage = 'usage: dpend export FILE.h5 [--csv] DATASET [DATASET ...]'//nl// &
              '       dpend export FILE.h5 --matrix DATASET [XAXIS YAXIS [SCALE]]'//nl// &
              '       dpend export FILE.h5 --list'//nl// &
              'Print datasets as whitespace-separated columns: a (n) dataset gives one'//nl// &
              'column, an (n, k) dataset (h5py order) gives k; all must share n.'//nl// &
              'A DATASET is a full path (/trajectory/q) or a name relative to the'//nl// &
              "command's group (q, energy; final/q1 in a sweep file)."//nl// &
              '  --csv     comma-separated, after a header line of names and units'//nl// &
              '            ("t [s],q1 [rad],q2 [rad]"; numpy.genfromtxt(names=True) and'//nl// &
              '            pandas.read_csv read it as written)'//nl// &
              '  --list    the datasets of the file: path, shape (h5py order), units'//nl// &
              "            ('1': dimensionless) and description"//nl// &
              '  --matrix  a 2-D dataset (ny, nx) as a gnuplot nonuniform matrix, with'//nl// &
              '            the 1-D datasets XAXIS (nx) and YAXIS (ny) as coordinates,'//nl// &
              '            values / SCALE (SCALE > 0, at least '// &
              real_str(tiny(1.0_dp))//')'//nl// &
              '  -h, --help  this text'//nl//data_quiet
      if (any([(sub(i)%s == '--help' .or. sub(i)%s == '-h', i=1, size(sub))])) then
         write (output_unit, '(a)') usage
         return
      end if
      matrix = .false.
      csv = .false.
      list = .false.
      allocate (pos(0))
      do i = 1, size(sub)
         if (sub(i)%s == '--matrix') then
            matrix = .true.
         else if (sub(i)%s == '--csv') then
            csv = .true.
         else if (sub(i)%s == '--list') then
            list = .true.
         else if (index(sub(i)%s, '--matrix=') == 1) then
            call fail(2, 'dpend export: option --matrix takes no value')
         else if (index(sub(i)%s, '--csv=') == 1) then
            call fail(2, 'dpend export: option --csv takes no value')
         else if (index(sub(i)%s, '--list=') == 1) then
            call fail(2, 'dpend export: option --list takes no value')
         else if (is_long_option(sub(i)%s)) then
            call fail(2, 'dpend export: '//unknown_option_text('export', sub(i)%s, &
                                                               '--matrix --csv --list --help'))
         else
            pos = [pos, sub(i)]
         end if
      end do
      n = size(pos)
      if (count([matrix, csv, list]) > 1) call fail(2, 'dpend export: --csv, --list and '// &
         '--matrix exclude each other (give one)')
      if (list) then
         if (n /= 1) call fail(2, 'dpend export: --list takes the file alone '// &
                               '(dpend export FILE.h5 --list)')
         call export_list(pos(1)%s, output_unit, error)
         if (allocated(error)) call fail(2, 'dpend export: '//error%message)
         return
      end if
      if (n < 2) call fail(2, 'dpend export: needs a file and at least one dataset '// &
                           '(dpend export --help)')
      if (matrix) then
         select case (n)
         case (2)
            call export_matrix(pos(1)%s, pos(2)%s, output_unit, error)
         case (4)
            call export_matrix(pos(1)%s, pos(2)%s, output_unit, error, pos(3)%s, pos(4)%s)
         case (5)
            call parse_real(pos(5)%s, 'SCALE', scale, error)
            if (allocated(error)) call fail(2, 'dpend export: '//error%message)
            if (.not. (scale >= tiny(1.0_dp))) call fail(2, 'dpend export: invalid SCALE: '// &
               pos(5)%s//' (accepted: a number >= '//real_str(tiny(1.0_dp))//')')
            call export_matrix(pos(1)%s, pos(2)%s, output_unit, error, pos(3)%s, &
                               pos(4)%s, scale)
         case default
            call fail(2, 'dpend export: --matrix takes FILE DATASET [XAXIS YAXIS [SCALE]]')
         end select
      else
         width = 1
         do i = 2, n
            width = max(width, len(pos(i)%s))
         end do
         allocate (character(len=width) :: paths(n - 1))
         do i = 2, n
            paths(i - 1) = pos(i)%s
         end do
         call export_columns(pos(1)%s, paths, output_unit, error, csv)
      end if
      if (allocated(error)) call fail(2, 'dpend export: '//error%message)
   end subroutine export


   subroutine sweep(sub)
      type(arg_t), intent(in) :: sub(:)
      type(sweep_config_t) :: cfg
      type(sweep_summary_t) :: summary
      type(error_t), allocatable :: error
      logical :: help
      call parse_sweep(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend sweep: '//error%message)
      if (help) then
         write (output_unit, '(a)') sweep_help()
         return
      end if
      ! the horizon in both units, printed when the run starts
      if (.not. cfg%quiet) call progress_header('dpend sweep: '//horizon_text(cfg))
      if (.not. cfg%quiet .and. len(cfg%device_note) > 0) &
         write (error_unit, '(a)') 'dpend sweep: '//cfg%device_note
      call run_sweep(cfg, summary, error)
      ! refused input (found when the output is examined) or a run that failed
      if (allocated(error)) call fail(exit_status(error), 'dpend sweep: '//error%message)
      ! once, after a run that computed (a refusal stays one line); not with --quiet
      if (summary%blocks_computed > 0 .and. .not. cfg%quiet .and. len(slow_build_note()) > 0) &
         write (error_unit, '(a)') 'dpend sweep: '//slow_build_note()
      if (summary%blocks_computed == 0) then
         write (output_unit, '(a)') "dpend sweep: '"//cfg%run%output// &
            "' is complete (nothing to compute)"
      else
         write (output_unit, '(a)') "dpend sweep: wrote '"//cfg%run%output//"': "// &
            summary_text(summary)
         ! a body other than the uniform rod
         if (len(cfg%run%model%body_description()) > 0) write (output_unit, '(a)') &
            'dpend sweep: links: '//cfg%run%model%body_description()
      end if
   end subroutine sweep

   !> `dpend sweep-compare A B [--rel R]`, the option anywhere (also --rel=R);
   !> `--agreement` classifies the pixels by their indicators instead.
   subroutine sweep_compare(sub)
      type(arg_t), intent(in) :: sub(:)
      type(error_t), allocatable :: error
      type(arg_t), allocatable :: files(:)
      character(len=:), allocatable :: name, value
      type(agreement_options_t) :: agree
      real(dp) :: rel
      logical :: missing, agreement, matched, rel_given
      character(len=:), allocatable :: needs_agreement
      integer :: i
      if (any([(sub(i)%s == '--help' .or. sub(i)%s == '-h', i=1, size(sub))])) then
         write (output_unit, '(a)') 'usage: dpend sweep-compare A.h5 B.h5 [--rel R]'//nl// &
            '       dpend sweep-compare A.h5 B.h5 --agreement [--threshold-a X]'//nl// &
            '             [--threshold-b Y] [--output FILE] [--force]'//nl//nl// &
            'Accuracy report of two complete sweeps of the same initial conditions (e.g.'//nl// &
            'steps dt and dt/2): the fraction of pixels whose first flip time changes by'//nl// &
            'more than R (default 0.01, at most 1000) relative, or that flip in one and'//nl// &
            'not the other, overall and by flip time in units of sqrt(l1/g). Sweeps of'//nl// &
            'other initial conditions (grid or list, shape, axes, ranges, parameters,'//nl// &
            'time unit, t_end, stop rule) are refused.'//nl//nl// &
            '--agreement: classify every pixel of each sweep as regular or chaotic by its'//nl// &
            'indicator (dpend sweep --indicator; t_end and the step may differ) and report'//nl// &
            'the fraction of pixels where the two agree, with both times; stored in FILE'//nl// &
            '(default agreement.h5). Chaotic: megno <Y> > X (default 2.5); lambda1'//nl// &
            'lambda1 sqrt(l1/g) > X (default 0.05); fli > X (no default); sali, gali2'//nl// &
            '< X (default 1e-8). --threshold-a, --threshold-b: X of file A, B.'//nl// &
            summary_quiet
         return
      end if
      rel = 0.01_dp
      agreement = .false.
      agree%output = 'agreement.h5'
      needs_agreement = ''
      rel_given = .false.
      allocate (files(0))
      i = 1
      do while (i <= size(sub))
         if (.not. is_long_option(sub(i)%s)) then
            files = [files, sub(i)]
            i = i + 1
            cycle
         end if
         if (sub(i)%s == '--agreement' .or. sub(i)%s == '--force') then
            if (sub(i)%s == '--agreement') agreement = .true.
            if (sub(i)%s == '--force') agree%force = .true.
            if (sub(i)%s == '--force') needs_agreement = '--force'
            i = i + 1
            cycle
         end if
         call next_option(sub, i, name, value, .true., error, missing)
         matched = .true.
         select case (name)
         case ('--rel'); call parse_real(value, name, rel, error); rel_given = .true.
         case ('--threshold-a')
            call parse_real(value, name, agree%threshold_a, error)
            agree%set_a = .true.
         case ('--threshold-b')
            call parse_real(value, name, agree%threshold_b, error)
            agree%set_b = .true.
         case ('--output'); agree%output = value
         case default; matched = .false.
         end select
         if (name /= '--rel' .and. matched) needs_agreement = name
         call option_outcome('sweep-compare', name, matched, missing, &
                             [character(len=16) :: '--agreement', '--force'], error, &
                             '--rel --agreement --threshold-a --threshold-b --output --force')
         if (allocated(error)) call fail(2, 'dpend sweep-compare: '//error%message)
      end do
      if (size(files) /= 2) call fail(2, 'dpend sweep-compare: needs two files, got '// &
                                      to_str(size(files))//' (dpend sweep-compare --help)')
      if (.not. agreement .and. len(needs_agreement) > 0) &
         call fail(2, 'dpend sweep-compare: invalid '//needs_agreement//': an option of '// &
                   '--agreement (dpend sweep-compare --help)')
      if (agreement .and. rel_given) &
         call fail(2, 'dpend sweep-compare: invalid --rel: not an option of --agreement '// &
                   '(its thresholds: --threshold-a, --threshold-b)')
      if (agreement) then
         call sweep_agreement(files(1)%s, files(2)%s, agree, output_unit, error)
      else
         call compare_sweeps(files(1)%s, files(2)%s, rel, output_unit, error)
      end if
      if (allocated(error)) call fail(exit_status(error), 'dpend '//error%message)
   end subroutine sweep_compare

   !> One line on stderr, then exit with `code` (1 or 2) and no runtime noise. The
   !> process ends without exit handlers: after a failed flush (full disk) HDF5's
   !> would retry closing forever. Every output file is closed or removed by then.
   subroutine fail(code, message)
      integer, intent(in) :: code
      character(len=*), intent(in) :: message
      ! one line whatever a value echoed in it holds (values are escaped where they
      ! are echoed; this is the last guard): control bytes as \t \n \xNN
      write (error_unit, '(a)') printable(message, controls_only=.true.)
      flush (error_unit)
      flush (output_unit)
      call c_exit(int(merge(1, 2, code == 1), c_int))
   end subroutine fail
end program dpend
