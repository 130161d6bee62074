!> Benchmarks of a map's file (figures in docs/performance.md, "A map's file"): the
!> classic 1024 x 1024 flip map (theta1, theta2 in [-3, 3], the chapter's pendulum)
!> with t_end = 0.05 s (5 steps of 0.01 s: almost no compute), run by the sweep
!> engine into a file (`run_sweep`: the working file, its blocks, the compressed
!> final file), against the same blocks computed in memory only (`compute_block`
!> over the threads). The difference is the file's cost; the least of three
!> interleaved runs of each. Then the map's results written again, whole, into
!> compressed datasets two ways, sizes and times side by side: through HDF5's own
!> filters in one thread (`write_slab`) and with the chunks encoded on every thread
!> (`write_chunked`, dpend_chunk_codec.c). The same map's file with --device gpu
!> (one block: one call of the library) when the GPU library loads.
!> Printed one per line as `key: value unit`. Run in the release profile:
!>   fpm run --example dpend-bench --profile release --flag "$RELEASE_FLAGS" -- --map-file
module bench_map_file
   use omp_lib, only: omp_get_max_threads
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_lane_batch, only: batch_result_t
   use dpend_sweep_settings, only: sweep_config_t, sweep_defaults, validate_sweep
   use dpend_sweep_gpu, only: resolve_device
   use dpend_sweep_setup, only: sweep_setup_t, build_setup, sweep_summary_t
   use dpend_sweep_engine, only: compute_block, run_sweep
   use dpend_hdf5, only: h5file_t
   use dpend_os, only: make_temp_directory, remove_directory, remove_file
   use dpend_progress, only: wall_seconds
   use bench_batch, only: load_average
   implicit none
   private
   public :: run_map_file_benchmarks

contains

   !> Print the figures of a map's file to `unit`: on the CPU, then, when a GPU
   !> library loads (a GPU, or the host emulation of scripts/gpu/build_gpu.sh
   !> --emulate named by $DPEND_GPU_LIB), with --device gpu and one block.
   subroutine run_map_file_benchmarks(unit)
      integer, intent(in) :: unit  !! where the figures go
      write (unit, '(a)') 'load_average_1min_at_start: '//load_average()
      write (unit, '(a, i0)') 'threads: ', omp_get_max_threads()
      call map_file_figures(unit, 'cpu')
      call map_file_figures(unit, 'gpu')
   end subroutine run_map_file_benchmarks

   !> The figures of the 1024^2 map's file on `device` ('cpu'; 'gpu' only when its
   !> library loads, else a line saying why not).
   subroutine map_file_figures(unit, device)
      integer, intent(in) :: unit              !! where the figures go
      character(len=*), intent(in) :: device   !! cpu or gpu
      type(sweep_config_t) :: cfg
      type(sweep_setup_t) :: setup
      type(error_t), allocatable :: error
      character(len=:), allocatable :: dir, file
      real(dp) :: memory_only, with_file, t
      integer(i8) :: fsize
      character(len=:), allocatable :: key
      integer :: round, err
      key = 'map_file_'//merge('    ', 'gpu_', device == 'cpu')
      key = trim(key)//'1024_'
      err = make_temp_directory('/tmp/dpend-bench-', dir)
      if (err /= 0) then
         write (unit, '(a)') 'map_file: cannot make a temporary directory'
         return
      end if
      file = dir//'/map.h5'
      cfg = sweep_defaults()
      cfg%n1 = 1024; cfg%n2 = 1024
      cfg%run%time_unit = 's'
      cfg%run%dt = 0.01_dp
      cfg%run%t_end = 0.05_dp
      cfg%quiet = .true.
      cfg%run%output = file
      cfg%run%force = .true.
      cfg%device = device
      if (device == 'gpu') cfg%block = cfg%n1*cfg%n2   ! one call of the library
      call validate_sweep(cfg, error)
      if (.not. allocated(error)) call resolve_device(cfg, error)
      if (.not. allocated(error)) call build_setup(cfg, setup, error)
      if (allocated(error)) then
         write (unit, '(a)') trim(key)//'not_measured: '//error%message
         err = remove_directory(dir)
         return
      end if
      memory_only = huge(1.0_dp); with_file = huge(1.0_dp)
      do round = 1, 3
         memory_only = min(memory_only, in_memory())
         t = in_file()
         if (t < 0) return
         with_file = min(with_file, t)
      end do
      inquire (file=file, size=fsize)
      write (unit, '(a, f0.3, a)') key//'memory_only_seconds: ', memory_only, ' s'
      write (unit, '(a, f0.3, a)') key//'with_file_seconds: ', with_file, ' s'
      write (unit, '(a, f0.3, a)') key//'file_seconds: ', with_file - memory_only, ' s'
      write (unit, '(a, f0.1, a)') key//'size: ', real(fsize, dp)/1e6_dp, ' MB'
      if (device == 'cpu') call compression_side_by_side(unit, file, dir)
      err = remove_file(file)
      err = remove_directory(dir)
   contains
      !> Wall seconds of the map's blocks computed in memory, over the threads.
      real(dp) function in_memory() result(s)
         real(dp) :: t0
         integer :: b
         t0 = wall_seconds()
         !$omp parallel do schedule(dynamic, 1)
         do b = 1, setup%nblocks
            call one_block(b)
         end do
         !$omp end parallel do
         s = wall_seconds() - t0
      end function in_memory
      subroutine one_block(b)
         integer, intent(in) :: b
         type(batch_result_t) :: res
         call compute_block(setup, b, res)
      end subroutine one_block
      !> Wall seconds of the whole sweep into `file` (replaced), -1 on failure.
      real(dp) function in_file() result(s)
         type(sweep_summary_t) :: summary
         type(error_t), allocatable :: e
         real(dp) :: t0
         t0 = wall_seconds()
         call run_sweep(cfg, summary, e)
         s = wall_seconds() - t0
         if (allocated(e)) then
            write (unit, '(a)') 'map_file: '//e%message
            s = -1
         end if
      end function in_file
   end subroutine map_file_figures

   !> The results of the map in `file` written again into compressed datasets of
   !> the final file's chunks: through HDF5's filters in one thread, and encoded on
   !> every thread; seconds and megabytes of each, and the ratio of the times.
   subroutine compression_side_by_side(unit, file, dir)
      integer, intent(in) :: unit                  !! where the figures go
      character(len=*), intent(in) :: file, dir    !! the map, a scratch directory
      character(len=:), allocatable :: paths(:)
      real(dp), allocatable :: r2(:, :)
      integer, allocatable :: i2(:, :)
      type(h5file_t) :: src
      type(error_t), allocatable :: error
      real(dp) :: secs(2), mb(2)
      integer :: way, k, err
      call src%open(file, 'r', error)
      if (.not. allocated(error)) call src%datasets('/sweep', paths, error)
      if (allocated(error)) then
         write (unit, '(a)') 'map_file: '//error%message
         return
      end if
      do way = 1, 2
         call write_all(way, dir//'/again.h5', secs(way), mb(way))
         if (secs(way) < 0) exit
      end do
      call src%close()
      if (any(secs < 0)) return
      write (unit, '(a, f0.3, a, f0.2, a)') 'map_file_hdf5_filters_one_thread: ', secs(1), &
         ' s, ', mb(1), ' MB'
      write (unit, '(a, f0.3, a, f0.2, a)') 'map_file_chunks_encoded_all_threads: ', secs(2), &
         ' s, ', mb(2), ' MB'
      write (unit, '(a, f0.2, a)') 'map_file_encoded_speedup: ', secs(1)/secs(2), ' x'
      err = remove_file(dir//'/again.h5')
   contains
      !> Write every 2-D result of the map into `name` one way; seconds, MB.
      subroutine write_all(way, name, s, megabytes)
         integer, intent(in) :: way
         character(len=*), intent(in) :: name
         real(dp), intent(out) :: s, megabytes
         type(h5file_t) :: dst
         type(error_t), allocatable :: e
         integer, allocatable :: dims(:)
         integer(i8) :: fsize
         real(dp) :: t0
         s = 0
         call dst%open(name, 'w', e)
         do k = 1, size(paths)
            if (allocated(e)) exit
            call src%shape(trim(paths(k)), dims, e)
            if (allocated(e)) exit
            if (size(dims) /= 2) cycle
            if (index(paths(k), 'status') > 0) then
               call src%read(trim(paths(k)), i2, e)
               if (.not. allocated(e)) call dst%create_dataset(trim(paths(k)), 'int32', dims, &
                  [dims(1), 32768/dims(1)], e, checksum=.true.)
               t0 = wall_seconds()
               if (way == 1 .and. .not. allocated(e)) call dst%write_slab(trim(paths(k)), i2, &
                  [1, 1], e)
               if (way == 2 .and. .not. allocated(e)) call dst%write_chunked(trim(paths(k)), &
                  i2, e)
            else
               call src%read(trim(paths(k)), r2, e)
               if (.not. allocated(e)) call dst%create_dataset(trim(paths(k)), 'real64', dims, &
                  [dims(1), 32768/dims(1)], e, checksum=.true.)
               t0 = wall_seconds()
               if (way == 1 .and. .not. allocated(e)) call dst%write_slab(trim(paths(k)), r2, &
                  [1, 1], e)
               if (way == 2 .and. .not. allocated(e)) call dst%write_chunked(trim(paths(k)), &
                  r2, e)
            end if
            s = s + wall_seconds() - t0
         end do
         t0 = wall_seconds()
         if (allocated(e)) then
            call dst%close()
         else
            call dst%close(e)
         end if
         s = s + wall_seconds() - t0
         if (allocated(e)) then
            write (unit, '(a)') 'map_file: '//e%message
            s = -1
            return
         end if
         inquire (file=name, size=fsize)
         megabytes = real(fsize, dp)/1e6_dp
      end subroutine write_all
   end subroutine compression_side_by_side

end module bench_map_file
