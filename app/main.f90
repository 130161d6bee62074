!> The `dpend` command: subcommands over the dpend library.
!> Exit status: 0 success, 1 a run that started and failed, 2 invalid input.
program dpend
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t, get_arguments
   use dpend_config, only: run_config_t
   use dpend_integrators, only: method_names
   use dpend_simulate, only: parse_simulate, run_simulate, simulate_help
   use dpend_version, only: version
   use dpend_export, only: export_columns
   use dpend_study_config, only: study_config_t, parse_study, study_help
   use dpend_study_output, only: run_study_command
   implicit none

   type(arg_t), allocatable :: args(:)
   character(len=*), parameter :: nl = new_line('a')

   call get_arguments(args)
   if (size(args) == 0) then
      write (output_unit, '(a)') main_help()
      stop 0, quiet=.true.
   end if
   select case (args(1)%s)
   case ('-h', '--help', 'help')
      write (output_unit, '(a)') main_help()
   case ('--version', 'version')
      write (output_unit, '(a)') 'dpend '//version
   case ('methods')
      write (output_unit, '(a)') method_names
   case ('simulate')
      call simulate(args(2:))
   case ('export')
      call export(args(2:))
   case ('study')
      call study(args(2:))
   case default
      call fail(2, "dpend: unknown command '"//args(1)%s//"' (dpend --help lists them)")
   end select

contains

   function main_help() result(s)
      character(len=:), allocatable :: s
      s = 'dpend '//version//' - the compound double pendulum'//nl//nl// &
          'usage: dpend COMMAND [options]     (dpend COMMAND --help for its options)'//nl//nl// &
          'commands:'//nl// &
          '  simulate   integrate one trajectory and write it to HDF5'//nl// &
          '  export     print HDF5 datasets as text columns (for gnuplot)'//nl// &
          '  study      energy-conservation study of every method: data, summary, figures'//nl// &
          '  methods    list the integration methods'//nl// &
          '  version    print the version'//nl//nl// &
          'Conventions: SI units; angles q1, q2 in rad from the horizontal x axis,'//nl// &
          'counter-clockwise positive, y up (hanging equilibrium q1 = q2 = -pi/2).'//nl// &
          'Defaults are the chapter''s: m1 = m2 = 1 kg, l1 = l2 = 1 m, g = 9.8 m/s^2.'
   end function main_help

   subroutine simulate(sub)
      type(arg_t), intent(in) :: sub(:)
      type(run_config_t) :: cfg
      type(error_t), allocatable :: error
      logical :: help, failed
      call parse_simulate(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend simulate: '//error%message)
      if (help) then
         write (output_unit, '(a)') simulate_help()
         return
      end if
      call run_simulate(cfg, error, failed)
      if (allocated(error)) then
         if (failed) call fail(1, 'dpend simulate: '//error%message)
         call fail(2, 'dpend simulate: '//error%message)
      end if
      write (output_unit, '(a)') "dpend simulate: wrote '"//cfg%output//"'"
   end subroutine simulate

   subroutine study(sub)
      type(arg_t), intent(in) :: sub(:)
      type(study_config_t) :: cfg
      type(error_t), allocatable :: error
      logical :: help, failed
      call parse_study(sub, cfg, help, error)
      if (allocated(error)) call fail(2, 'dpend study: '//error%message)
      if (help) then
         write (output_unit, '(a)') study_help()
         return
      end if
      call run_study_command(cfg, error, failed)
      if (allocated(error)) then
         if (failed) call fail(1, 'dpend study: '//error%message)
         call fail(2, 'dpend study: '//error%message)
      end if
   end subroutine study

   subroutine export(sub)
      type(arg_t), intent(in) :: sub(:)
      type(error_t), allocatable :: error
      character(len=256), allocatable :: paths(:)
      integer :: i
      if (size(sub) < 2 .or. any([(sub(i)%s == '--help' .or. sub(i)%s == '-h', &
                                   i=1, size(sub))])) then
         write (output_unit, '(a)') 'usage: dpend export FILE.h5 DATASET [DATASET ...]'//nl// &
            'Print datasets as whitespace-separated columns: a (n) dataset gives one'//nl// &
            'column, an (n, k) dataset (h5py order) gives k; all must share n.'
         if (size(sub) < 2) call fail(2, 'dpend export: needs a file and at least one dataset')
         return
      end if
      allocate (paths(size(sub) - 1))
      do i = 2, size(sub)
         paths(i - 1) = sub(i)%s
      end do
      call export_columns(sub(1)%s, paths, output_unit, error)
      if (allocated(error)) call fail(2, 'dpend export: '//error%message)
   end subroutine export

   !> One line on stderr, then exit with `code` and no runtime noise.
   subroutine fail(code, message)
      integer, intent(in) :: code
      character(len=*), intent(in) :: message
      write (error_unit, '(a)') message
      select case (code)
      case (1); stop 1, quiet=.true.
      case default; stop 2, quiet=.true.
      end select
   end subroutine fail
end program dpend
