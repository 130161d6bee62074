!> Test driver: runs every suite, or only the tests whose suite or name is given
!> on the command line (`fpm test -- model`, `fpm test -- model/energy`).
!> A test whose tool is missing reports itself skipped (`skip_test`). Closes with
!> `N passed, M failed, K skipped` and exits non-zero on any failure. With the
!> environment variable DPEND_TEST_NO_SKIP=1 (set by CI, .ci/run) a skipped test
!> counts as a failure: CI expects every test to run.
program tester
   use, intrinsic :: iso_fortran_env, only: output_unit
   use testing, only: unittest_t, error_t, take_skip
   use test_model, only: collect_model
   use test_hdf5, only: collect_hdf5
   use test_cli, only: collect_cli
   use test_integrators, only: collect_integrators
   use test_symplectic, only: collect_symplectic
   use test_chaos, only: collect_chaos
   use test_sweep, only: collect_sweep
   use test_study, only: collect_study
   use test_limits, only: collect_limits
   use test_animate, only: collect_animate
   use test_messages, only: collect_messages
   use test_copies, only: collect_copies
   use test_registry, only: collect_registry
   use test_interface, only: collect_interface
   use test_chain, only: collect_chain
   use test_files, only: collect_files
   use test_indicators, only: collect_indicators
   use test_damping, only: collect_damping
   use test_kapitza, only: collect_kapitza
   use test_gauss_damped, only: collect_gauss_damped
   use test_estimate, only: collect_estimate
   use test_factory, only: collect_factory
   use test_elastic, only: collect_elastic
   use test_parse, only: collect_parse
   use test_dense, only: collect_dense
   use test_balance, only: collect_balance
   use test_sweep_values, only: collect_sweep_values
   use test_fit_stats, only: collect_fit_stats
   use test_phase_distance, only: collect_phase_distance
   use test_inventory, only: collect_inventory
   use test_values_simulate, only: collect_values_simulate
   use test_values_chaos, only: collect_values_chaos
   use test_values_study, only: collect_values_study
   use test_figures, only: collect_figures
   use test_values_sweep, only: collect_values_sweep
   use test_values_fit, only: collect_values_fit
   use test_bodies, only: collect_bodies
   use test_fit_params, only: collect_fit_params
   use test_chain_lanes, only: collect_chain_lanes
   use test_lanes, only: collect_lanes
   use test_gpu, only: collect_gpu
   use test_run_settings, only: collect_run_settings
   implicit none

   type :: suite_t
      character(len=:), allocatable :: name
      type(unittest_t), allocatable :: tests(:)
   end type suite_t

   abstract interface
      !> A suite's collector: its tests.
      subroutine collector(tests)
         import :: unittest_t
         type(unittest_t), allocatable, intent(out) :: tests(:)
      end subroutine collector
   end interface

   type(suite_t), allocatable :: suites(:)
   type(error_t), allocatable :: error
   character(len=:), allocatable :: filter, full, reason
   integer :: i, j, n_pass, n_fail, n_skip, n_arg, length, stat
   logical :: no_skip, skipped
   character(len=8) :: value

   allocate (suites(0))   ! a suite a line below: no count to keep
   call add('model', collect_model)
   call add('hdf5', collect_hdf5)
   call add('cli', collect_cli)
   call add('integrators', collect_integrators)
   call add('symplectic', collect_symplectic)
   call add('chaos', collect_chaos)
   call add('sweep', collect_sweep)
   call add('study', collect_study)
   call add('limits', collect_limits)
   call add('animate', collect_animate)
   call add('messages', collect_messages)
   call add('copies', collect_copies)
   call add('registry', collect_registry)
   call add('interface', collect_interface)
   call add('chain', collect_chain)
   call add('files', collect_files)
   call add('indicators', collect_indicators)
   call add('damping', collect_damping)
   call add('kapitza', collect_kapitza)
   call add('gauss_damped', collect_gauss_damped)
   call add('estimate', collect_estimate)
   call add('factory', collect_factory)
   call add('elastic', collect_elastic)
   call add('parse', collect_parse)
   call add('dense', collect_dense)
   call add('balance', collect_balance)
   call add('sweep_values', collect_sweep_values)
   call add('fit_stats', collect_fit_stats)
   call add('phase_distance', collect_phase_distance)
   call add('inventory', collect_inventory)
   call add('values_simulate', collect_values_simulate)
   call add('values_chaos', collect_values_chaos)
   call add('values_study', collect_values_study)
   call add('figures', collect_figures)
   call add('values_sweep', collect_values_sweep)
   call add('values_fit', collect_values_fit)
   call add('bodies', collect_bodies)
   call add('fit_params', collect_fit_params)
   call add('chain_lanes', collect_chain_lanes)
   call add('lanes', collect_lanes)
   call add('gpu', collect_gpu)
   call add('run_settings', collect_run_settings)

   n_arg = command_argument_count()
   if (n_arg >= 1) then
      call get_command_argument(1, length=length)
      filter = repeat(" ", length)
      call get_command_argument(1, filter)
   else
      filter = ''
   end if

   call get_environment_variable('DPEND_TEST_NO_SKIP', value, status=stat)
   no_skip = stat == 0 .and. value == '1'

   n_pass = 0; n_fail = 0; n_skip = 0
   do i = 1, size(suites)
      do j = 1, size(suites(i)%tests)
         full = suites(i)%name//'/'//suites(i)%tests(j)%name
         if (len(filter) > 0) then
            if (filter /= suites(i)%name .and. filter /= full) cycle
         end if
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
end program tester
