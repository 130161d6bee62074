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

   type(suite_t), allocatable :: suites(:)
   type(error_t), allocatable :: error
   character(len=:), allocatable :: filter, full, reason
   integer :: i, j, n_pass, n_fail, n_skip, n_arg, length, stat
   logical :: no_skip, skipped
   character(len=8) :: value

   allocate (suites(42))
   suites(1)%name = 'model'; call collect_model(suites(1)%tests)
   suites(2)%name = 'hdf5'; call collect_hdf5(suites(2)%tests)
   suites(3)%name = 'cli'; call collect_cli(suites(3)%tests)
   suites(4)%name = 'integrators'; call collect_integrators(suites(4)%tests)
   suites(5)%name = 'symplectic'; call collect_symplectic(suites(5)%tests)
   suites(6)%name = 'chaos'; call collect_chaos(suites(6)%tests)
   suites(7)%name = 'sweep'; call collect_sweep(suites(7)%tests)
   suites(8)%name = 'study'; call collect_study(suites(8)%tests)
   suites(9)%name = 'limits'; call collect_limits(suites(9)%tests)
   suites(10)%name = 'animate'; call collect_animate(suites(10)%tests)
   suites(11)%name = 'messages'; call collect_messages(suites(11)%tests)
   suites(12)%name = 'copies'; call collect_copies(suites(12)%tests)
   suites(13)%name = 'registry'; call collect_registry(suites(13)%tests)
   suites(14)%name = 'interface'; call collect_interface(suites(14)%tests)
   suites(15)%name = 'chain'; call collect_chain(suites(15)%tests)
   suites(16)%name = 'files'; call collect_files(suites(16)%tests)
   suites(17)%name = 'indicators'; call collect_indicators(suites(17)%tests)
   suites(18)%name = 'damping'; call collect_damping(suites(18)%tests)
   suites(19)%name = 'kapitza'; call collect_kapitza(suites(19)%tests)
   suites(20)%name = 'gauss_damped'; call collect_gauss_damped(suites(20)%tests)
   suites(21)%name = 'estimate'; call collect_estimate(suites(21)%tests)
   suites(22)%name = 'factory'; call collect_factory(suites(22)%tests)
   suites(23)%name = 'elastic'; call collect_elastic(suites(23)%tests)
   suites(24)%name = 'parse'; call collect_parse(suites(24)%tests)
   suites(25)%name = 'dense'; call collect_dense(suites(25)%tests)
   suites(26)%name = 'balance'; call collect_balance(suites(26)%tests)
   suites(27)%name = 'sweep_values'; call collect_sweep_values(suites(27)%tests)
   suites(28)%name = 'fit_stats'; call collect_fit_stats(suites(28)%tests)
   suites(29)%name = 'phase_distance'; call collect_phase_distance(suites(29)%tests)
   suites(30)%name = 'inventory'; call collect_inventory(suites(30)%tests)
   suites(31)%name = 'values_simulate'; call collect_values_simulate(suites(31)%tests)
   suites(32)%name = 'values_chaos'; call collect_values_chaos(suites(32)%tests)
   suites(33)%name = 'values_study'; call collect_values_study(suites(33)%tests)
   suites(34)%name = 'figures'; call collect_figures(suites(34)%tests)
   suites(35)%name = 'values_sweep'; call collect_values_sweep(suites(35)%tests)
   suites(36)%name = 'values_fit'; call collect_values_fit(suites(36)%tests)
   suites(37)%name = 'bodies'; call collect_bodies(suites(37)%tests)
   suites(38)%name = 'fit_params'; call collect_fit_params(suites(38)%tests)
   suites(39)%name = 'chain_lanes'; call collect_chain_lanes(suites(39)%tests)
   suites(40)%name = 'lanes'; call collect_lanes(suites(40)%tests)
   suites(41)%name = 'gpu'; call collect_gpu(suites(41)%tests)
   suites(42)%name = 'run_settings'; call collect_run_settings(suites(42)%tests)

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
end program tester
