!> `dpend-mpi sweep`: the engine of the serial sweep (src/engines/) over MPI ranks (docs/mpi.md).
!>
!> Same configuration, blocks, kernel and file layout as the serial sweep, whose
!> pieces it calls (build_setup, open_output, compute_block, write_block,
!> finalize_file): the files are identical in content.
!>
!> * Rank 0 opens or creates the working file exactly as the serial sweep does
!>   (resume from the `done` flags, refusal of another configuration, creation
!>   under a temporary name), closes it and sends the flags to every rank.
!> * Every rank opens the working file with MPI-IO (collective). Its chunks are
!>   unfiltered and allocated at creation, so a block write changes raw data only
!>   and is done with independent I/O: blocks go to the file as they complete, in
!>   any order, from any rank. A block's data are written before its done flag.
!> * Dynamic load balancing: the missing blocks are handed out by an atomic
!>   counter on rank 0 (dpend_mpi_counter); every rank, rank 0 included, and every
!>   OpenMP thread of a rank takes the next block when it is free.
!> * When every block is written, all ranks close the file and rank 0 alone
!>   rewrites it compressed (the serial finalize_file; parallel HDF5 writes
!>   filtered datasets only collectively).
!>
!> Every MPI and HDF5 call inside the parallel region is made in one OpenMP
!> critical section (MPI_THREAD_SERIALIZED; HDF5 is not thread-safe).
module dpend_mpi_sweep
   use, intrinsic :: iso_fortran_env, only: error_unit
   use mpi_f08, only: MPI_Comm, MPI_INFO_NULL, MPI_IN_PLACE, MPI_INTEGER, MPI_INTEGER8, &
      MPI_DOUBLE_PRECISION, MPI_CHARACTER, MPI_MIN, MPI_MAX, MPI_SUM, MPI_Comm_rank, &
      MPI_Comm_size, MPI_Allreduce, MPI_Bcast, MPI_Gather, MPI_Reduce, MPI_Wtime
   use hdf5, only: hid_t, H5P_FILE_ACCESS_F, h5open_f, h5pcreate_f, h5pclose_f, &
      h5pset_fapl_mpio_f
   use omp_lib, only: omp_set_num_threads, omp_get_max_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_lane_batch, only: batch_result_t, st_cannot_flip
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_setup, only: sweep_setup_t, sweep_summary_t, build_setup, block_range, &
      block_share_note
   use dpend_sweep_engine, only: compute_block
   use dpend_sweep_resume, only: open_output
   use dpend_sweep_layout, only: write_block, finalize_file, working_file
   use dpend_hdf5, only: h5file_t
   use dpend_output, only: output_t
   use dpend_os, only: io_failure_reason
   use dpend_progress, only: progress_t
   use dpend_mpi_counter, only: shared_counter_t
   implicit none
   private
   public :: run_mpi_sweep, mpi_report_t, write_balance, write_block_times, agree

   !> Per-rank figures, in the order of `mpi_report_t%ranks`' rows.
   integer, parameter :: f_blocks = 1, f_traj = 2, f_steps = 3, f_busy = 4, f_io = 5, &
                         f_finish = 6, f_threads = 7, f_cpu = 8, n_fields = 8

   !> What an MPI sweep did: the summary of the serial sweep, and on rank 0 the
   !> load balance (per rank) and the cost of every block computed by this run.
   type :: mpi_report_t
      type(sweep_summary_t) :: summary        !! as `dpend sweep` reports it
      integer :: nranks = 1                   !! MPI ranks
      real(dp) :: wall = 0                    !! wall time of the distributed phase [s]
      real(dp) :: finalize = 0                !! rank 0: the compressed rewrite [s]
      real(dp), allocatable :: ranks(:, :)    !! (n_fields, nranks): blocks, trajectories,
                                              !! RK4 steps, busy thread-seconds in the
                                              !! kernel, seconds writing, time of its last
                                              !! block since the start [s], threads, CPU
                                              !! seconds of the process in that time
      integer, allocatable :: block_rank(:)   !! rank that computed block b (-1: not
                                              !! computed by this run)
      integer, allocatable :: block_size(:)   !! initial conditions of block b
      integer(i8), allocatable :: block_steps(:)  !! RK4 steps of block b
      real(dp), allocatable :: block_seconds(:)   !! kernel wall time of block b [s]
   end type mpi_report_t

contains

   !> Run or resume the sweep of `cfg` on the ranks of `comm` (collective). On return
   !> every rank holds the same `error`; `report` is complete on rank 0.
   subroutine run_mpi_sweep(cfg, comm, report, error)
      type(sweep_config_t), intent(in) :: cfg           !! validated configuration
      type(MPI_Comm), intent(in) :: comm                !! the ranks
      type(mpi_report_t), intent(out) :: report         !! what was done
      type(error_t), allocatable, intent(out) :: error  !! what went wrong (all ranks)
      type(sweep_setup_t) :: setup
      type(h5file_t) :: h5
      type(shared_counter_t) :: counter
      type(progress_t) :: progress
      type(error_t), allocatable :: cerr
      integer, allocatable :: done(:), missing(:)
      integer(i8) :: n_before, written
      integer :: me, np, complete, b, nmissing
      logical :: failed
      character(len=:), allocatable :: note
      real(dp) :: t0, mine(n_fields)
      real :: cpu0, cpu1

      call MPI_Comm_rank(comm, me)
      call MPI_Comm_size(comm, np)
      report%nranks = np
      if (cfg%threads > 0) call omp_set_num_threads(cfg%threads)
      call build_setup(cfg, setup, error)
      setup%checksum = .false.   ! independent block writes: no filters in the working file
      call agree(comm, error)
      if (allocated(error)) return
      if (me == 0) then   ! fewer blocks than ranks: why, and what would share them
         note = block_share_note(setup, np)
         if (len(note) > 0) write (error_unit, '(a)') 'dpend-mpi sweep: note: '//note
      end if
      report%summary%n = setup%n
      report%summary%flips = setup%flips
      report%summary%energy_fed = .not. setup%cfg%run%model%autonomous()

      call share_resume(setup, comm, me, report, done, complete, error)
      if (allocated(error)) return
      if (complete == 1) return

      missing = pack([(b, b=1, setup%nblocks)], done /= 1)
      nmissing = size(missing)
      n_before = sum(report%block_size, mask=done == 1)

      ! every rank: the working file through MPI-IO (collective open)
      call open_parallel(h5, working_file(cfg%run%output), comm, error)
      call agree(comm, error)
      if (allocated(error)) then
         call h5%close()
         return
      end if

      mine = 0
      mine(f_threads) = omp_get_max_threads()
      call progress%start('dpend-mpi sweep', int(setup%n, i8), n_before, &
                          cfg%quiet .or. me /= 0)
      call counter%create(comm, 2)   ! 0: next missing block, 1: trajectories written
      failed = .false.
      call cpu_time(cpu0)
      t0 = MPI_Wtime()
      !$omp parallel default(shared)
      call work()
      !$omp end parallel
      mine(f_finish) = MPI_Wtime() - t0
      call cpu_time(cpu1)
      mine(f_cpu) = cpu1 - cpu0
      call counter%destroy()
      report%wall = MPI_Wtime() - t0
      call h5%close(cerr)
      if (.not. allocated(error) .and. allocated(cerr)) call move_alloc(cerr, error)
      call agree(comm, error)
      if (allocated(error)) then
         call progress%finish()
         error%message = error%message//"; '"//working_file(cfg%run%output)// &
                         "' holds the blocks done so far: rerun to resume"
         return
      end if

      call gather_report(comm, me, np, setup%nblocks, mine, report)
      call progress%update(n_before + report%summary%computed - progress%done)
      call progress%finish()
      report%summary%seconds = report%wall

      ! rank 0 alone: the compressed rewrite (serial open of the closed file)
      if (me == 0) then
         t0 = MPI_Wtime()
         call finalize_file(cfg%run%output, setup, error)
         report%finalize = MPI_Wtime() - t0
      end if
      call agree(comm, error)

   contains

      !> One thread: take the next missing block until none is left.
      subroutine work()
         type(batch_result_t) :: res
         type(error_t), allocatable :: werr
         integer(i8) :: k, old
         integer :: bb, jj0, nnb
         real(dp) :: tb, tw
         do
            !$omp critical (dpend_mpi)
            k = counter%fetch_add(0, 1_i8) + 1
            !$omp end critical (dpend_mpi)
            if (k > nmissing) exit
            bb = missing(k)
            tb = MPI_Wtime()
            call compute_block(setup, bb, res)
            tb = MPI_Wtime() - tb
            call block_range(setup, bb, jj0, nnb)
            !$omp critical (dpend_mpi)
            if (.not. failed) then
               tw = MPI_Wtime()
               call write_block(h5, setup, bb, res, werr, flush=.false.)
               if (allocated(werr)) then
                  call move_alloc(werr, error)
                  failed = .true.
                  old = counter%swap(0, int(nmissing, i8))   ! every rank stops
               else
                  call record_block(report, mine, me, bb, nnb, res, tb, MPI_Wtime() - tw)
                  written = counter%fetch_add(1, int(nnb, i8)) + nnb
                  if (me == 0) call progress%update(n_before + written - progress%done)
               end if
            end if
            !$omp end critical (dpend_mpi)
         end do
      end subroutine work
   end subroutine run_mpi_sweep

   !> Count block bb of nnb initial conditions, computed by rank `me` in `tb` s and
   !> written in `io` s, in the rank's figures and the report.
   subroutine record_block(report, mine, me, bb, nnb, res, tb, io)
      type(mpi_report_t), intent(inout) :: report   !! the report
      real(dp), intent(inout) :: mine(n_fields)     !! this rank's figures
      integer, intent(in) :: me, bb, nnb            !! rank, block, its size
      type(batch_result_t), intent(in) :: res       !! its results
      real(dp), intent(in) :: tb, io                !! kernel and write time [s]
      mine(f_blocks) = mine(f_blocks) + 1
      mine(f_traj) = mine(f_traj) + nnb
      mine(f_steps) = mine(f_steps) + sum(int(res%steps, i8))
      mine(f_busy) = mine(f_busy) + tb
      mine(f_io) = mine(f_io) + io
      report%block_rank(bb) = me
      report%block_steps(bb) = sum(int(res%steps, i8))
      report%block_seconds(bb) = tb
      report%summary%blocks_computed = report%summary%blocks_computed + 1
      report%summary%computed = report%summary%computed + nnb
      report%summary%skipped = report%summary%skipped + count(res%status == st_cannot_flip)
   end subroutine record_block

   !> Rank 0 resumes, refuses or creates the working file exactly as the serial sweep
   !> (`open_output`) and closes it; every rank gets its `complete` attribute and the
   !> blocks' done flags, and `report`'s per-block arrays (collective).
   subroutine share_resume(setup, comm, me, report, done, complete, error)
      type(sweep_setup_t), intent(in) :: setup           !! setup
      type(MPI_Comm), intent(in) :: comm                 !! the ranks
      integer, intent(in) :: me                          !! this rank
      type(mpi_report_t), intent(inout) :: report        !! per-block arrays allocated
      integer, allocatable, intent(out) :: done(:)       !! 1 for every block done
      integer, intent(out) :: complete                   !! the file is complete
      type(error_t), allocatable, intent(out) :: error   !! refused (all ranks)
      type(h5file_t) :: h5
      integer :: b, j0
      complete = 0
      if (me == 0) then
         call open_output(setup, h5, done, complete, error)
         if (allocated(error)) then
            call h5%close()
         else
            call h5%close(error)
         end if
      end if
      call agree(comm, error)
      if (allocated(error)) return
      call MPI_Bcast(complete, 1, MPI_INTEGER, 0, comm)
      if (me /= 0) allocate (done(setup%nblocks))
      call MPI_Bcast(done, setup%nblocks, MPI_INTEGER, 0, comm)
      report%summary%blocks_before = count(done == 1)
      allocate (report%block_rank(setup%nblocks), report%block_size(setup%nblocks), &
                report%block_steps(setup%nblocks), report%block_seconds(setup%nblocks))
      report%block_rank = -1
      report%block_steps = 0
      report%block_seconds = 0
      do b = 1, setup%nblocks
         call block_range(setup, b, j0, report%block_size(b))
      end do
   end subroutine share_resume

   !> Open the working file `path` on every rank through MPI-IO (collective).
   subroutine open_parallel(h5, path, comm, error)
      type(h5file_t), intent(inout) :: h5                !! the file, opened 'rw'
      character(len=*), intent(in) :: path               !! the working file
      type(MPI_Comm), intent(in) :: comm                 !! the ranks
      type(error_t), allocatable, intent(out) :: error   !! this rank's failure
      integer(hid_t) :: fapl
      integer :: ierr
      call h5open_f(ierr)
      call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, ierr)
      call h5pset_fapl_mpio_f(fapl, comm%MPI_VAL, MPI_INFO_NULL%MPI_VAL, ierr)
      call h5%open(path, 'rw', error, access=fapl)
      call h5pclose_f(fapl, ierr)
   end subroutine open_parallel

   !> The report on rank 0: every rank's figures `mine` (report%ranks), the rank,
   !> steps and time of every block, and on every rank the summary's sums
   !> (collective).
   subroutine gather_report(comm, me, np, nblocks, mine, report)
      type(MPI_Comm), intent(in) :: comm                 !! the ranks
      integer, intent(in) :: me, np                      !! this rank, ranks
      integer, intent(in) :: nblocks                     !! blocks
      real(dp), intent(in) :: mine(n_fields)             !! this rank's figures
      type(mpi_report_t), intent(inout) :: report        !! completed
      real(dp), allocatable :: all_ranks(:, :)
      integer :: ignored_i(1)
      integer(i8) :: ignored_i8(1)
      real(dp) :: ignored_r(1)
      allocate (all_ranks(n_fields, np))
      call MPI_Gather(mine, n_fields, MPI_DOUBLE_PRECISION, all_ranks, n_fields, &
                      MPI_DOUBLE_PRECISION, 0, comm)
      report%block_rank = report%block_rank + 1   ! 0: not computed, for the sum
      if (me == 0) then
         call MPI_Reduce(MPI_IN_PLACE, report%block_rank, nblocks, MPI_INTEGER, &
                         MPI_SUM, 0, comm)
         call MPI_Reduce(MPI_IN_PLACE, report%block_steps, nblocks, MPI_INTEGER8, &
                         MPI_SUM, 0, comm)
         call MPI_Reduce(MPI_IN_PLACE, report%block_seconds, nblocks, &
                         MPI_DOUBLE_PRECISION, MPI_SUM, 0, comm)
      else   ! the receive buffers are not used on the other ranks
         call MPI_Reduce(report%block_rank, ignored_i, nblocks, MPI_INTEGER, &
                         MPI_SUM, 0, comm)
         call MPI_Reduce(report%block_steps, ignored_i8, nblocks, MPI_INTEGER8, &
                         MPI_SUM, 0, comm)
         call MPI_Reduce(report%block_seconds, ignored_r, nblocks, &
                         MPI_DOUBLE_PRECISION, MPI_SUM, 0, comm)
      end if
      report%block_rank = report%block_rank - 1
      call MPI_Allreduce(MPI_IN_PLACE, report%summary%blocks_computed, 1, MPI_INTEGER, &
                         MPI_SUM, comm)
      call MPI_Allreduce(MPI_IN_PLACE, report%summary%computed, 1, MPI_INTEGER8, MPI_SUM, &
                         comm)
      call MPI_Allreduce(MPI_IN_PLACE, report%summary%skipped, 1, MPI_INTEGER8, MPI_SUM, comm)
      if (me == 0) call move_alloc(all_ranks, report%ranks)
   end subroutine gather_report

   !> Give every rank the error of the lowest rank that has one (collective).
   subroutine agree(comm, error)
      type(MPI_Comm), intent(in) :: comm                  !! the ranks
      type(error_t), allocatable, intent(inout) :: error  !! this rank's error, if any
      character(len=:), allocatable :: msg
      integer :: me, np, first, n
      call MPI_Comm_rank(comm, me)
      call MPI_Comm_size(comm, np)
      first = np
      if (allocated(error)) first = me
      call MPI_Allreduce(MPI_IN_PLACE, first, 1, MPI_INTEGER, MPI_MIN, comm)
      if (first == np) return
      n = 0
      if (me == first) n = len(error%message)
      call MPI_Bcast(n, 1, MPI_INTEGER, first, comm)
      allocate (character(len=n) :: msg)
      if (me == first) msg = error%message
      if (n > 0) call MPI_Bcast(msg, n, MPI_CHARACTER, first, comm)
      if (.not. allocated(error)) call fatal_error(error, msg)
      error%message = msg
   end subroutine agree

   !> The load balance: one row per rank, then the spread of the block costs.
   subroutine write_balance(report, unit)
      type(mpi_report_t), intent(in) :: report  !! a report of rank 0
      integer, intent(in) :: unit               !! where to write
      real(dp) :: busy_mean, busy_max, finish_max, threads
      real(dp), allocatable :: secs(:)
      integer :: r
      if (.not. allocated(report%ranks)) return
      associate (t => report%ranks)
         write (unit, '(a)') 'rank  threads  blocks  trajectories       rk4_steps'// &
            '  busy_thread_s  write_s  last_block_s  cpu_s'
         do r = 1, report%nranks
            write (unit, '(i4, i9, i8, i14, i16, f15.2, f9.2, f14.2, f7.2)') r - 1, &
               nint(t(f_threads, r)), nint(t(f_blocks, r)), nint(t(f_traj, r), i8), &
               nint(t(f_steps, r), i8), t(f_busy, r), t(f_io, r), t(f_finish, r), t(f_cpu, r)
         end do
         busy_mean = sum(t(f_busy, :))/report%nranks
         busy_max = maxval(t(f_busy, :))
         finish_max = maxval(t(f_finish, :))
         threads = sum(t(f_threads, :))
         write (unit, '(a, f0.3, a, f0.3, a, f0.1, a)') 'load_balance: max/mean busy = ', &
            busy_max/max(busy_mean, 1e-12_dp), ', max/mean steps = ', &
            maxval(t(f_steps, :))/max(sum(t(f_steps, :))/report%nranks, 1.0_dp), &
            ', efficiency busy/(threads x wall) = ', &
            100*sum(t(f_busy, :))/max(threads*report%wall, 1e-12_dp), ' %'
         write (unit, '(a, f0.2, a, f0.2, a, f0.2, a)') 'wall_s: ', report%wall, &
            ' (last rank out of work at ', finish_max, ' s); compressed rewrite on rank 0: ', &
            report%finalize, ' s'
      end associate
      secs = pack(report%block_seconds, report%block_rank >= 0)
      if (size(secs) > 0) then
         call sort(secs)
         write (unit, '(a, i0, a, 5(es10.3, 1x), a, f0.3)') 'block_seconds (', size(secs), &
            ' blocks) min p50 p90 p99 max: ', secs(1), pct(0.5_dp), pct(0.9_dp), &
            pct(0.99_dp), secs(size(secs)), ' cv ', stdev(secs)/max(mean(secs), 1e-300_dp)
      end if
   contains
      !> The p-quantile of the sorted block seconds (nearest rank).
      real(dp) function pct(p)
         real(dp), intent(in) :: p  !! in [0, 1]
         pct = secs(max(1, min(size(secs), ceiling(p*size(secs)))))
      end function pct
   end subroutine write_balance

   !> Per-block costs as text columns: block, rank, initial conditions, RK4 steps,
   !> kernel seconds (blocks computed by this run only).
   subroutine write_block_times(report, filename, force, error)
      type(mpi_report_t), intent(in) :: report          !! a report of rank 0
      character(len=*), intent(in) :: filename          !! text file to write
      logical, intent(in) :: force                      !! replace an existing file
      type(error_t), allocatable, intent(out) :: error  !! unwritable
      type(output_t) :: out
      integer :: unit, stat, b
      character(len=512) :: msg
      call out%begin(filename, force, error, '--block-times')
      if (allocated(error)) return
      open (newunit=unit, file=out%temp, status='replace', action='write', iostat=stat, &
            iomsg=msg)
      if (stat == 0) write (unit, '(a, i0, a)', iostat=stat, iomsg=msg) &
         '# dpend-mpi sweep block costs, ', report%nranks, ' ranks'
      if (stat == 0) write (unit, '(a)', iostat=stat, iomsg=msg) &
         '# block rank initial_conditions rk4_steps seconds'
      do b = 1, size(report%block_rank)
         if (stat /= 0) exit
         if (report%block_rank(b) < 0) cycle
         write (unit, '(i0, 1x, i0, 1x, i0, 1x, i0, 1x, es12.5)', iostat=stat, iomsg=msg) &
            b, report%block_rank(b), report%block_size(b), report%block_steps(b), &
            report%block_seconds(b)
      end do
      if (stat == 0) then
         close (unit, iostat=stat, iomsg=msg)
      else
         close (unit)
      end if
      if (stat /= 0) then
         call fatal_error(error, "cannot write '"//filename//"': "// &
                          io_failure_reason(out%temp, trim(msg)))
      else
         call out%commit(error)
      end if
      call out%discard()
   end subroutine write_block_times

   !> Mean of x.
   pure real(dp) function mean(x)
      real(dp), intent(in) :: x(:)  !! values
      mean = sum(x)/max(size(x), 1)
   end function mean

   !> Population standard deviation of x.
   pure real(dp) function stdev(x)
      real(dp), intent(in) :: x(:)  !! values
      stdev = sqrt(sum((x - mean(x))**2)/max(size(x), 1))
   end function stdev

   !> Sort ascending (heapsort).
   subroutine sort(x)
      real(dp), intent(inout) :: x(:)  !! values, sorted on return
      real(dp) :: v
      integer :: n, i
      n = size(x)
      do i = n/2, 1, -1
         call sift(i, n)
      end do
      do i = n, 2, -1
         v = x(1); x(1) = x(i); x(i) = v
         call sift(1, i - 1)
      end do
   contains
      subroutine sift(first, last)
         integer, intent(in) :: first, last
         integer :: root, child
         real(dp) :: t
         root = first
         do while (2*root <= last)
            child = 2*root
            if (child < last) then
               if (x(child + 1) > x(child)) child = child + 1
            end if
            if (x(root) >= x(child)) return
            t = x(root); x(root) = x(child); x(child) = t
            root = child
         end do
      end subroutine sift
   end subroutine sort
end module dpend_mpi_sweep
