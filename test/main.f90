!> Test driver: runs every suite, or only the suites and tests named on the command
!> line, any number of them (`fpm test -- model`, `fpm test -- model chain/energy`):
!> their union, in registration order, each test once. An argument that names no
!> suite and no test is refused before anything runs: one line naming it and listing
!> the suites, exit status 2. The suites are registered below by the floor of src/
!> that each mainly tests, in the floors' order (docs/testing.md). A test whose tool
!> is missing reports itself skipped (`skip_test`). Closes with
!> `N passed, M failed, K skipped` and exits non-zero on any failure. With the
!> environment variable DPEND_TEST_NO_SKIP=1 (set by CI, .ci/run) a skipped test
!> counts as a failure: CI expects every test to run.
program tester
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use testing, only: unittest_t, error_t, take_skip
   ! src/core/
   use test_limits, only: collect_limits
   use test_parse, only: collect_parse
   ! src/models/
   use test_model, only: collect_model
   use test_copies, only: collect_copies
   use test_interface, only: collect_interface
   use test_chain, only: collect_chain
   use test_damping, only: collect_damping
   use test_joint_torque, only: collect_joint_torque
   use test_inverse_dynamics, only: collect_inverse_dynamics
   use test_identify, only: collect_identify
   use test_kapitza, only: collect_kapitza
   use test_factory, only: collect_factory
   use test_elastic, only: collect_elastic
   use test_bodies, only: collect_bodies
   ! src/integrators/
   use test_integrators, only: collect_integrators
   use test_symplectic, only: collect_symplectic
   use test_registry, only: collect_registry
   use test_gauss_damped, only: collect_gauss_damped
   use test_dense, only: collect_dense
   ! src/analysis/
   use test_chaos, only: collect_chaos
   use test_indicators, only: collect_indicators
   use test_estimate, only: collect_estimate
   use test_fit_stats, only: collect_fit_stats
   use test_phase_distance, only: collect_phase_distance
   use test_fit_params, only: collect_fit_params
   ! src/lanes/
   use test_lanes, only: collect_lanes
   use test_chain_lanes, only: collect_chain_lanes
   ! src/io/
   use test_hdf5, only: collect_hdf5
   use test_files, only: collect_files
   ! src/settings/
   use test_run_settings, only: collect_run_settings
   ! src/engines/
   use test_sweep, only: collect_sweep
   use test_study, only: collect_study
   use test_gpu, only: collect_gpu
   ! src/commands/
   use test_cli, only: collect_cli
   use test_animate, only: collect_animate
   use test_messages, only: collect_messages
   use test_balance, only: collect_balance
   use test_sweep_vs_simulate, only: collect_sweep_vs_simulate
   use test_inventory, only: collect_inventory
   use test_values_simulate, only: collect_values_simulate
   use test_values_chaos, only: collect_values_chaos
   use test_values_study, only: collect_values_study
   use test_figures, only: collect_figures
   use test_values_sweep, only: collect_values_sweep
   use test_values_fit, only: collect_values_fit
   use test_values_torques, only: collect_values_torques
   use test_capi, only: collect_capi
   implicit none

   type :: suite_t
      character(len=:), allocatable :: name
      type(unittest_t), allocatable :: tests(:)
   end type suite_t

   !> A command-line argument: a suite, or a test as suite/test.
   type :: filter_t
      character(len=:), allocatable :: name
   end type filter_t

   abstract interface
      !> A suite's collector: its tests.
      subroutine collector(tests)
         import :: unittest_t
         type(unittest_t), allocatable, intent(out) :: tests(:)
      end subroutine collector
   end interface

   type(suite_t), allocatable :: suites(:)
   type(filter_t), allocatable :: filters(:)
   type(error_t), allocatable :: error
   character(len=:), allocatable :: full, reason, unknown, names
   integer :: i, j, k, n_pass, n_fail, n_skip, n_arg, length, stat
   logical :: no_skip, skipped
   character(len=8) :: value

   allocate (suites(0))   ! a suite a line below: no count to keep
   ! src/core/: limits before work, the strict parser
   call add('limits', collect_limits)
   call add('parse', collect_parse)
   ! src/models/: the models, their factory, the copies of their formulas
   call add('model', collect_model)
   call add('copies', collect_copies)
   call add('interface', collect_interface)
   call add('chain', collect_chain)
   call add('damping', collect_damping)
   call add('joint_torque', collect_joint_torque)
   call add('inverse_dynamics', collect_inverse_dynamics)
   call add('identify', collect_identify)
   call add('kapitza', collect_kapitza)
   call add('factory', collect_factory)
   call add('elastic', collect_elastic)
   call add('bodies', collect_bodies)
   ! src/integrators/: the methods, their registry, dense output
   call add('integrators', collect_integrators)
   call add('symplectic', collect_symplectic)
   call add('registry', collect_registry)
   call add('gauss_damped', collect_gauss_damped)
   call add('dense', collect_dense)
   ! src/analysis/: tangent dynamics, chaos indicators, estimation
   call add('chaos', collect_chaos)
   call add('indicators', collect_indicators)
   call add('estimate', collect_estimate)
   call add('fit_stats', collect_fit_stats)
   call add('phase_distance', collect_phase_distance)
   call add('fit_params', collect_fit_params)
   ! src/lanes/: the lane kernels and their driver
   call add('lanes', collect_lanes)
   call add('chain_lanes', collect_chain_lanes)
   ! src/io/: HDF5 and the files that describe themselves
   call add('hdf5', collect_hdf5)
   call add('files', collect_files)
   ! src/settings/: one resolution of every setting
   call add('run_settings', collect_run_settings)
   ! src/engines/: sweeps, studies, the GPU path
   call add('sweep', collect_sweep)
   call add('study', collect_study)
   call add('gpu', collect_gpu)
   ! src/commands/: the commands end to end, run as processes, and the values they write
   call add('cli', collect_cli)
   call add('animate', collect_animate)
   call add('messages', collect_messages)
   call add('balance', collect_balance)
   call add('sweep_vs_simulate', collect_sweep_vs_simulate)
   call add('inventory', collect_inventory)
   call add('values_simulate', collect_values_simulate)
   call add('values_chaos', collect_values_chaos)
   call add('values_study', collect_values_study)
   call add('figures', collect_figures)
   call add('values_sweep', collect_values_sweep)
   call add('values_fit', collect_values_fit)
   call add('values_torques', collect_values_torques)
   ! src/capi/: the C interface, its files against the commands'
   call add('capi', collect_capi)

   n_arg = command_argument_count()
   allocate (filters(n_arg))
   do k = 1, n_arg
      call get_command_argument(k, length=length)
      allocate (character(len=length) :: filters(k)%name)
      call get_command_argument(k, filters(k)%name)
   end do
   unknown = ''
   do k = 1, n_arg
      if (.not. names_something(filters(k)%name)) then
         if (len(unknown) > 0) unknown = unknown//', '
         unknown = unknown//''''//filters(k)%name//''''
      end if
   end do
   if (len(unknown) > 0) then
      names = ''
      do i = 1, size(suites)
         names = names//' '//suites(i)%name
      end do
      write (error_unit, '(a)') 'dpend-tests: no suite or test named '//unknown// &
         ' (suites:'//names//')'
      stop 2, quiet=.true.
   end if

   call get_environment_variable('DPEND_TEST_NO_SKIP', value, status=stat)
   no_skip = stat == 0 .and. value == '1'

   n_pass = 0; n_fail = 0; n_skip = 0
   do i = 1, size(suites)
      do j = 1, size(suites(i)%tests)
         full = suites(i)%name//'/'//suites(i)%tests(j)%name
         if (.not. selected(suites(i)%name, full)) cycle
         call suites(i)%tests(j)%run(error)
         skipped = take_skip(reason)   ! a failure before the skip stays a failure
         if (allocated(error)) then
            n_fail = n_fail + 1
            write (output_unit, '(a)') '  FAIL '//full//': '//error%message
            deallocate (error)
         else if (skipped) then
            if (no_skip) then
               n_fail = n_fail + 1
               write (output_unit, '(a)') '  FAIL '//full//': skipped ('//reason// &
                  '), and DPEND_TEST_NO_SKIP=1 expects every test to run'
            else
               n_skip = n_skip + 1
               write (output_unit, '(a)') '  skip '//full//': '//reason
            end if
         else
            n_pass = n_pass + 1
            write (output_unit, '(a)') '  ok   '//full
         end if
         flush (output_unit)
      end do
   end do
   write (output_unit, '(i0, " passed, ", i0, " failed, ", i0, " skipped")') &
      n_pass, n_fail, n_skip
   if (n_fail > 0 .or. n_pass == 0) error stop 1
contains
   !> Register the suite `name` with the tests its collector gives.
   subroutine add(name, collect)
      character(len=*), intent(in) :: name
      procedure(collector) :: collect
      type(suite_t) :: suite
      suite%name = name
      call collect(suite%tests)
      suites = [suites, suite]
   end subroutine add

   !> Whether the test `full` (suite/test) of suite `suite` runs: every test runs
   !> without arguments, else those whose suite or suite/test is an argument.
   logical function selected(suite, full)
      character(len=*), intent(in) :: suite, full
      integer :: m
      selected = size(filters) == 0
      do m = 1, size(filters)
         if (filters(m)%name == suite .or. filters(m)%name == full) selected = .true.
      end do
   end function selected

   !> Whether `arg` names a registered suite or a test (suite/test) of one.
   logical function names_something(arg)
      character(len=*), intent(in) :: arg
      integer :: m, n
      names_something = .false.
      do m = 1, size(suites)
         if (arg == suites(m)%name) names_something = .true.
         do n = 1, size(suites(m)%tests)
            if (arg == suites(m)%name//'/'//suites(m)%tests(n)%name) names_something = .true.
         end do
      end do
   end function names_something
end program tester
