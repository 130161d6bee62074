!> The `dpend` command: the table of its commands and the program that runs one.
!>
!> `dpend_command_table` holds one row per command: its name, its line of the usage
!> text and its module's entry point (`NAME_command(args, error)` of src/commands/,
!> where each command parses, runs and prints its summary). The table also gives the
!> usage text and the entry points of `help` and `version`, which print it and the
!> version (module procedures: an internal procedure as a pointer target would need
!> an executable stack for its trampoline).
!>
!> The program `dpend` reads the argument list, refuses an option given twice, looks
!> the command up in the table, runs its entry point with the arguments after the
!> name and maps the kind of a returned error to the exit status: 0 success, 1 a run
!> that started and failed, 2 invalid input.
module dpend_command_table
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t
   use dpend_strings, only: did_you_mean, word_wrap, replace_char
   use dpend_model_factory, only: model_catalogue, model_info_t, body_list
   use dpend_version, only: version
   use dpend_simulate, only: simulate_command
   use dpend_lyapunov_command, only: lyapunov_command
   use dpend_indicators_command, only: indicators_command
   use dpend_divergence_command, only: divergence_command
   use dpend_poincare_command, only: poincare_command
   use dpend_sweep_command, only: sweep_command
   use dpend_sweep_compare_command, only: sweep_compare_command
   use dpend_export_command, only: export_command
   use dpend_study_config, only: study_command
   use dpend_animate, only: animate_command
   use dpend_fit_command, only: fit_command
   use dpend_torques_command, only: torques_command
   use dpend_identify_command, only: identify_command
   use dpend_explore_command, only: explore_command
   use dpend_methods_command, only: methods_command
   use dpend_models_command, only: models_command
   implicit none
   private
   public :: command_t, command_table, usage_text, suggestion

   abstract interface
      !> A command's entry point: the arguments after the command's name; a refusal
      !> or a failed run comes back as `error`, its message the one line to print and
      !> its kind the exit status (`exit_status`).
      subroutine entry_point(args, error)
         import :: arg_t, error_t
         type(arg_t), intent(in) :: args(:)
         type(error_t), allocatable, intent(out) :: error
      end subroutine entry_point
   end interface

   !> A row of the table of commands.
   type :: command_t
      character(len=:), allocatable :: name  !! what the user types
      !> its line of the usage text ('': not listed there)
      character(len=:), allocatable :: line
      procedure(entry_point), pointer, nopass :: run => null()  !! its entry point
   end type command_t

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The commands: name, line of the usage text, entry point. The usage text lists
   !> the rows with a line, in this order; the names without a leading '-' are the
   !> ones a mistyped command is matched against.
   function command_table() result(table)
      type(command_t), allocatable :: table(:)
      table = [ &
         command_t('simulate', 'integrate one trajectory and write it to HDF5', &
                   simulate_command), &
         command_t('lyapunov', 'Lyapunov exponents (Benettin, QR) with their running ' &
                   //'estimates', lyapunov_command), &
         command_t('indicators', 'chaos indicators MEGNO, FLI, SALI, GALI_k against time', &
                   indicators_command), &
         command_t('divergence', 'divergence of nearby trajectories, fitted exponential ' &
                   //'slope', divergence_command), &
         command_t('poincare', 'Poincare section at one energy', poincare_command), &
         command_t('sweep', 'maps over initial conditions or parameters: flip time, ' &
                   //'energy error, lambda1, MEGNO, FLI, SALI, GALI_2', sweep_command), &
         command_t('sweep-compare', 'two sweeps (e.g. dt, dt/2) compared by their own ' &
                   //'quantity: flip times, or indicator values and classes', &
                   sweep_compare_command), &
         command_t('export', 'print HDF5 datasets as text columns, CSV or a matrix; --list', &
                   export_command), &
         command_t('study', 'energy-conservation study of every method: data, summary, ' &
                   //'figures', study_command), &
         command_t('animate', 'animated GIF of a simulate file (gnuplot): rods and bobs, ' &
                   //'tip trail, time; two runs overlaid or side by side', animate_command), &
         command_t('fit', 'estimate the initial state and parameters from measured angles ' &
                   //'or positions (CSV; the tip alone too)', fit_command), &
         command_t('torques', 'inverse dynamics: the joint torques and reactions a measured ' &
                   //'motion requires (Newton-Euler, filtered angles); residuals', &
                   torques_command), &
         command_t('identify', 'the inertial and friction parameters that measured motion ' &
                   //'and torques determine (base parameters, SVD, least squares)', &
                   identify_command), &
         command_t('explore', 'a map of dpend sweep in the browser: click a pixel, watch ' &
                   //'its pendulum', explore_command), &
         command_t('methods', 'the integration methods: order, properties, commands', &
                   methods_command), &
         command_t('models', 'the models: coordinates, bodies, parameters (units, ' &
                   //'ranges), capabilities', models_command), &
         command_t('version', 'print the version', version_command), &
         command_t('help', '', help_command), &
         command_t('--help', '', help_command), &
         command_t('-h', '', help_command), &
         command_t('--version', '', version_command)]
   end function command_table

   !> `dpend help` (also `--help`, `-h`): the usage text.
   subroutine help_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! ignored
      type(error_t), allocatable, intent(out) :: error  !! never set
      write (output_unit, '(a)') usage_text()
   end subroutine help_command

   !> `dpend version` (also `--version`): the version.
   subroutine version_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! ignored
      type(error_t), allocatable, intent(out) :: error  !! never set
      write (output_unit, '(a)') 'dpend '//version
   end subroutine version_command

   !> 'did you mean NAME? ' for a mistyped command, '' when no name is near.
   function suggestion(typed) result(s)
      character(len=*), intent(in) :: typed  !! the command as given
      character(len=:), allocatable :: s
      type(command_t), allocatable :: table(:)
      character(len=:), allocatable :: names
      integer :: i
      table = command_table()
      names = ''
      do i = 1, size(table)
         if (table(i)%name(1:1) /= '-') names = names//' '//table(i)%name
      end do
      s = did_you_mean(typed, names(2:))
      if (len(s) > 0) s = s//' '
   end function suggestion

   !> The usage text: what dpend is, the commands of the table with their lines, the
   !> models and the conventions.
   function usage_text() result(s)
      character(len=:), allocatable :: s
      type(command_t), allocatable :: table(:)
      character(len=:), allocatable :: rows
      integer :: i
      table = command_table()
      rows = ''
      do i = 1, size(table)
         if (len(table(i)%line) == 0) cycle
         ! the names in a column of 10; a longer one two blanks before its line
         ! (lines wrapped at 78 columns, continued under the first)
         if (len(table(i)%name) <= 10) then
            rows = rows//'  '//table(i)%name//repeat(' ', 11 - len(table(i)%name))// &
                   word_wrap(table(i)%line, 65, 13)//nl
         else
            rows = rows//'  '//table(i)%name//'  '// &
                   word_wrap(table(i)%line, 78 - 4 - len(table(i)%name), 13)//nl
         end if
      end do
      s = 'dpend '//version//' - the compound double pendulum, chains of N rods and the'// &
          nl//'elastic pendulum: trajectories, chaos, maps, accuracy studies, fits'//nl//nl// &
          'usage: dpend COMMAND [options]     (dpend COMMAND --help for its options)'//nl//nl// &
          'commands:'//nl//rows//nl// &
          'models (--model NAME; dpend models lists coordinates, bodies, parameters, ranges,'// &
          nl//'capabilities):'//nl//model_rows()//nl// &
          'Every command takes --quiet: no progress report, and of a summary only its'//nl// &
          'last line (export, methods and models print their data as always).'//nl// &
          'Every command that takes times takes --time-unit s|natural: seconds (the'//nl// &
          'default; the sweep''s is natural) or sqrt(l1/g), sqrt(l0/g) for the elastic'//nl// &
          'pendulum; the reports quote both, the unit in use first (sweep-compare: the'//nl// &
          'sweeps'' own; study reports in s, saying what was given).'//nl//nl// &
          'Conventions: SI units; angles q1 .. qN in rad from the horizontal x axis,'//nl// &
          'counter-clockwise positive, y up (hanging equilibrium q_i = -pi/2); --theta1'//nl// &
          'and the sweep''s theta axes from the hanging position.'//nl// &
          'Defaults are the chapter''s: m1 = m2 = 1 kg, l1 = l2 = 1 m, g = 9.8 m/s^2.'
   contains
      !> A row per model of the factory's catalogue: its name and its one-line summary,
      !> wrapped (the catalogue is the one description: `dpend models` prints it too).
      function model_rows() result(t)
         character(len=:), allocatable :: t
         type(model_info_t), allocatable :: models(:)
         integer :: k
         models = model_catalogue()
         t = ''
         do k = 1, size(models)
            t = t//'  '//models(k)%name//repeat(' ', max(1, 11 - len(models(k)%name)))// &
                word_wrap(models(k)%summary, 65, 13)//nl//repeat(' ', 13)// &
                word_wrap('options: '//flags_of(models(k)), 65, 13)//nl
         end do
      end function model_rows
      !> The flags of a model's parameters ('--links N --m LIST ...') and its bodies.
      function flags_of(model) result(t)
         type(model_info_t), intent(in) :: model
         character(len=:), allocatable :: t
         integer :: i
         t = ''
         do i = 1, size(model%params)
            if (i > 1) t = t//' '
            t = t//'--'//replace_char(model%params(i)%name, '_', '-')
            if (model%params(i)%name == 'links') t = t//' N'
         end do
         if (len(model%bodies) > 0) t = t//' --body '//body_list('|')
      end function flags_of
   end function usage_text
end module dpend_command_table

!> `dpend COMMAND [options]`: the command looked up in `dpend_command_table` and run;
!> its error's one line on standard error and the exit status from the error's kind.
program dpend
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use, intrinsic :: iso_c_binding, only: c_int
   use dpend_error, only: error_t, exit_status
   use dpend_cli, only: arg_t, get_arguments, printable, check_repeated_options
   use dpend_output, only: track_inputs
   use dpend_limits, only: bound_threads
   use dpend_command_table, only: command_t, command_table, usage_text, suggestion
   implicit none

   interface
      !> POSIX _exit(2): end the process at once, without exit handlers.
      subroutine c_exit(status) bind(C, name='_exit')
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit
   end interface

   type(command_t), allocatable :: commands(:)
   type(arg_t), allocatable :: args(:)
   type(error_t), allocatable :: error
   integer :: k

   ! every input a command reads is registered: an output never replaces one
   call track_inputs(.true.)
   call get_arguments(args)
   block   ! the OpenMP runtime's threads from the environment, bounded as --threads
      character(len=:), allocatable :: note
      call bound_threads(note)
      if (len(note) > 0) write (error_unit, '(a)') 'dpend: '//note
   end block
   if (size(args) == 0) then
      write (output_unit, '(a)') usage_text()
      stop 0, quiet=.true.
   end if
   ! an option given twice is refused for every command, before any parsing
   call check_repeated_options(args(2:), error)
   if (allocated(error)) call fail(2, 'dpend '//printable(args(1)%s)//': '//error%message)
   commands = command_table()
   do k = 1, size(commands)
      if (commands(k)%name == args(1)%s) exit
   end do
   if (k > size(commands)) call fail(2, "dpend: unknown command '"//printable(args(1)%s)// &
                                     "' ("//suggestion(args(1)%s)//'dpend --help lists them)')
   call commands(k)%run(args(2:), error)
   if (allocated(error)) call fail(exit_status(error), error%message)

contains

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
