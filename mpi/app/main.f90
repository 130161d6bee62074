!> The `dpend-mpi` command: `dpend sweep` over MPI ranks with parallel HDF5
!> (docs/mpi.md). Run under mpirun or srun:
!>   mpirun -np 4 dpend-mpi sweep --config data/sweep_classic.nml
!> Same options and configuration as `dpend sweep`, same file (identical content),
!> plus --block-times FILE. Rank 0 prints; exit status 0 success, 2 invalid input
!> or a failed run (the file then holds the blocks done so far: rerun to resume).
program dpend_mpi
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use, intrinsic :: iso_c_binding, only: c_int, c_long
   use mpi_f08, only: MPI_COMM_WORLD, MPI_THREAD_SERIALIZED, MPI_Init_thread, &
      MPI_Finalize, MPI_Comm_rank, MPI_Comm_size
   use omp_lib, only: omp_get_max_threads
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, get_arguments, check_repeated_options
   use dpend_version, only: version
   use dpend_output, only: check_output_path
   use dpend_sweep_settings, only: sweep_config_t, horizon_text
   use dpend_sweep_config, only: parse_sweep, sweep_help
   use dpend_mpi_sweep, only: run_mpi_sweep, mpi_report_t, write_balance, &
      write_block_times
   use dpend_sweep_setup, only: summary_text
   use dpend_limits, only: bound_threads
   implicit none

   interface
      !> Linux prctl(2), here with PR_SET_PDEATHSIG.
      integer(c_int) function c_prctl(option, arg2, arg3, arg4, arg5) bind(C, name='prctl')
         import :: c_int, c_long
         integer(c_int), value :: option
         integer(c_long), value :: arg2, arg3, arg4, arg5
      end function c_prctl
   end interface

   type(arg_t), allocatable :: args(:)
   integer :: provided, me, np, stat
   character(len=*), parameter :: nl = new_line('a')

   ! A rank dies with its launcher (mpirun, orted, slurmstepd): after a kill -9 of
   ! mpirun no orphaned rank goes on writing the file while it is rerun.
   stat = c_prctl(1_c_int, 9_c_long, 0_c_long, 0_c_long, 0_c_long)   ! PDEATHSIG, KILL
   call MPI_Init_thread(MPI_THREAD_SERIALIZED, provided)
   call MPI_Comm_rank(MPI_COMM_WORLD, me)
   call MPI_Comm_size(MPI_COMM_WORLD, np)
   call get_arguments(args)
   block   ! the OpenMP runtime's threads from the environment, bounded as --threads
      character(len=:), allocatable :: note
      call bound_threads(note)
      if (len(note) > 0 .and. me == 0) write (error_unit, '(a)') 'dpend-mpi: '//note
   end block
   if (size(args) == 0) then
      call say(main_help())
      call finish(0)
   end if
   select case (args(1)%s)
   case ('-h', '--help', 'help')
      call say(main_help())
   case ('--version', 'version')
      call say('dpend-mpi '//version)
   case ('sweep')
      call sweep(args(2:))
   case default
      call finish(2, "dpend-mpi: unknown command '"//args(1)%s// &
                  "' (dpend-mpi --help lists them)")
   end select
   call finish(0)

contains

   function main_help() result(s)
      character(len=:), allocatable :: s
      s = 'dpend-mpi '//version//' - dpend sweep over MPI ranks, parallel HDF5'//nl//nl// &
          'usage: mpirun -np N dpend-mpi sweep [options]   (srun under Slurm)'//nl//nl// &
          'The options and the namelist file of `dpend sweep` (dpend-mpi sweep --help),'// &
          nl//'and:'//nl// &
          '  --block-times FILE  write the cost of every block computed (block, rank,'//nl// &
          '                      initial conditions, RK4 steps, seconds) to FILE'//nl//nl// &
          'Blocks go to the ranks dynamically (an atomic counter on rank 0), to the'//nl// &
          'OpenMP threads of a rank likewise (OMP_NUM_THREADS or --threads per rank);'//nl// &
          'the file is identical in content to the one of `dpend sweep` and resumes'//nl// &
          'the same way, from either program. Rank 0 prints a load-balance table.'
   end function main_help

   subroutine sweep(sub)
      type(arg_t), intent(in) :: sub(:)
      type(arg_t), allocatable :: rest(:)
      type(sweep_config_t) :: cfg
      type(mpi_report_t) :: report
      type(error_t), allocatable :: error
      character(len=:), allocatable :: times_file
      logical :: help
      call check_repeated_options(sub, error)   ! as dpend's: one value per option
      if (.not. allocated(error)) call take_block_times(sub, rest, times_file, error)
      if (.not. allocated(error)) call parse_sweep(rest, cfg, help, error)
      if (allocated(error)) call finish(2, 'dpend-mpi sweep: '//error%message)
      if (help) then
         call say(replace_usage(sweep_help())//nl//nl// &
                  'dpend-mpi only:'//nl// &
                  '  --block-times FILE  cost of every block computed, as text columns')
         return
      end if
      if (allocated(times_file)) then
         call check_output_path(times_file, cfg%run%force, error, '--block-times')
         if (allocated(error)) call finish(2, 'dpend-mpi sweep: '//error%message)
      end if
      if (provided < MPI_THREAD_SERIALIZED) cfg%threads = 1
      ! the horizon and step in both units, as dpend sweep says them (rank 0)
      if (me == 0 .and. .not. cfg%quiet) write (error_unit, '(a)') 'dpend-mpi sweep: '// &
         horizon_text(cfg)
      call run_mpi_sweep(cfg, MPI_COMM_WORLD, report, error)
      if (allocated(error)) call finish(2, 'dpend-mpi sweep: '//error%message)
      if (me /= 0) return
      if (report%summary%blocks_computed == 0) then
         write (output_unit, '(a)') "dpend-mpi sweep: '"//cfg%run%output// &
            "' is complete (nothing to compute)"
         return
      end if
      write (output_unit, '(a)') "dpend-mpi sweep: wrote '"//cfg%run%output//"': "// &
         summary_text(report%summary)
      ! the ranks' table follows the closing line; --quiet: that line alone
      if (.not. cfg%quiet) then
         write (output_unit, '(a, i0, a, i0)') 'ranks: ', np, ', threads of rank 0: ', &
            omp_get_max_threads()
         call write_balance(report, output_unit)
      end if
      if (allocated(times_file)) then
         call write_block_times(report, times_file, cfg%run%force, error)
         if (allocated(error)) then
            write (error_unit, '(a)') 'dpend-mpi sweep: '//error%message
            call finish(1)
         end if
      end if
   end subroutine sweep

   !> Remove `--block-times FILE` (or `--block-times=FILE`) from the arguments.
   subroutine take_block_times(sub, rest, file, error)
      type(arg_t), intent(in) :: sub(:)
      type(arg_t), allocatable, intent(out) :: rest(:)
      character(len=:), allocatable, intent(out) :: file
      type(error_t), allocatable, intent(out) :: error
      integer :: i
      allocate (rest(0))
      i = 1
      do while (i <= size(sub))
         if (sub(i)%s == '--block-times') then
            if (i == size(sub)) then
               call fatal_error(error, 'option --block-times needs a value')
               return
            end if
            file = sub(i + 1)%s
            i = i + 2
         else if (index(sub(i)%s, '--block-times=') == 1) then
            file = sub(i)%s(len('--block-times=') + 1:)
            i = i + 1
         else
            rest = [rest, sub(i)]
            i = i + 1
         end if
      end do
      if (allocated(file)) then
         if (len(file) == 0) call fatal_error(error, 'invalid --block-times: empty file name')
      end if
   end subroutine take_block_times

   !> The sweep help with `dpend-mpi sweep` as the command.
   function replace_usage(text) result(s)
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: s
      integer :: k
      s = text
      k = index(s, 'dpend sweep')
      if (k > 0) s = s(:k - 1)//'mpirun -np N dpend-mpi sweep'//s(k + len('dpend sweep'):)
   end function replace_usage

   !> Print on rank 0.
   subroutine say(text)
      character(len=*), intent(in) :: text
      if (me == 0) write (output_unit, '(a)') text
   end subroutine say

   !> End every rank: the message (rank 0, one line on stderr), MPI_Finalize, status.
   subroutine finish(code, message)
      integer, intent(in) :: code
      character(len=*), intent(in), optional :: message
      if (present(message) .and. me == 0) write (error_unit, '(a)') message
      flush (error_unit)
      flush (output_unit)
      call MPI_Finalize()
      select case (code)
      case (0); stop 0, quiet=.true.
      case default; stop 2, quiet=.true.
      end select
   end subroutine finish
end program dpend_mpi
