!> The sweep engine: many initial conditions through the batch RK4 kernel
!> (dpend_pendulum_lanes) for the double pendulum, or one at a time through the
!> registry's rk4 on the run's model (dpend_trajectory_batch) for any other model, in
!> blocks distributed over OpenMP threads, into one HDF5 file (layout in
!> dpend_sweep_layout, resume in dpend_sweep_resume, design in docs/sweep.md).
module dpend_sweep_engine
   use omp_lib, only: omp_set_num_threads, omp_get_max_threads
   use dpend_limits, only: sci
   use dpend_resources, only: check_memory, check_disk
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, run_failure, fatal_error
   use dpend_stop_request, only: stop_requested
   use dpend_lane_batch, only: batch_result_t, st_cannot_flip
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_sweep_settings, only: sweep_config_t, pixel_model, pixel_model_named, &
      pixel_pendulums, pixel_model_axes
   use dpend_model, only: model_t
   use dpend_trajectory_batch, only: integrate_trajectories
   use dpend_chain_lanes, only: integrate_chain_lanes
   use dpend_integrator, only: integrator_t
   use dpend_hdf5, only: h5file_t
   use dpend_progress, only: progress_t, wall_seconds
   use dpend_cli, only: to_str
   use dpend_sweep_setup, only: sweep_setup_t, sweep_summary_t, build_setup, block_range, &
      block_initial_conditions, parameter_axes, block_parameters, parameter_names, named_axes
   use dpend_sweep_layout, only: result_names, working_file, finalize_file, &
      block_result_crcs, block_values_t, block_values, write_values
   use dpend_sweep_resume, only: open_output
   use dpend_sweep_gpu, only: gpu_integrate_block
   implicit none
   private
   public :: compute_block, run_sweep

contains

   !> Refuse a sweep whose blocks in flight do not fit the available memory or whose
   !> file does not fit the free space of the output's file system. Memory: one block
   !> per thread at about 256 B per initial condition (state, results, flags), plus a
   !> list's states. Disk: the working file (every dataset uncompressed) and, while
   !> it is rewritten compressed at the end, the final file (at most as large), less
   !> the size of an existing output that is resumed or replaced.
   subroutine check_sweep_resources(setup, error)
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=32), allocatable :: reals(:), ints(:)
      real(dp) :: mem, disk, per_point, existing
      integer(i8) :: fsize
      logical :: exists
      mem = real(omp_get_max_threads(), dp)*real(setup%block, dp)*256.0_dp
      if (.not. setup%grid) mem = mem + 32.0_dp*real(setup%n, dp)
      call check_memory('block', mem, to_str(omp_get_max_threads())//' thread(s) with blocks of ' &
                        //to_str(setup%block)//' initial conditions', &
                        'use a smaller --block or fewer --threads', error)
      if (allocated(error)) return
      call result_names(setup, reals, ints)
      per_point = 8.0_dp*real(size(reals) + 1, dp) + 4.0_dp*real(size(ints), dp)
      ! the working file and the final file side by side, plus HDF5's own bytes; an
      ! existing working file (a resume) already has its share
      disk = 2.0_dp*per_point*real(setup%n, dp) + 65536.0_dp
      existing = 0.0_dp
      inquire (file=working_file(setup%cfg%run%output), exist=exists, size=fsize)
      if (exists .and. fsize > 0) existing = real(fsize, dp)
      call check_disk(trim(merge('n1, n2 ', 'ic_file', setup%grid)), disk - existing, &
                      setup%cfg%run%output, sci(real(setup%n, dp))//' initial conditions; '// &
                      'use fewer points or another --output directory', error)
   end subroutine check_sweep_resources

   !> Integrate block b: the batch kernel for two links, the chain lanes for flip maps
   !> of 3 to 8 links (dpend_chain_lanes), else one trajectory at a time with this
   !> block's own copy of the method.
   subroutine compute_block(setup, b, res)
      type(sweep_setup_t), intent(in) :: setup    !! setup
      integer, intent(in) :: b                    !! block, 1-based
      type(batch_result_t), intent(out) :: res    !! its results
      real(dp), allocatable :: y0(:, :)
      class(integrator_t), allocatable :: integ
      call block_initial_conditions(setup, b, y0)
      if (setup%cfg%device == 'gpu') then   ! the flip map on the GPU
         call gpu_integrate_block(setup%cfg%run%pendulum(), setup%opt, &
                                  int(setup%cfg%gpu_repack, i8), y0, res)
      else if (parameter_axes(setup)) then
         call compute_parameter_block(setup, b, y0, res)
      else if (setup%chain_lanes) then   ! chains of 3 to 8 links
         call integrate_chain_lanes(setup%cfg%run%model, setup%opt, y0, res)
      else if (setup%per_trajectory) then
         allocate (integ, source=setup%integ)
         call integrate_trajectories(setup%cfg%run%model, integ, setup%gl, setup%opt, y0, res)
      else
         call integrate_batch(setup%cfg%run%pendulum(), setup%opt, y0, res)
      end if
   end subroutine compute_block

   !> Integrate block b of a sweep over parameters. Two links: the whole block by the
   !> batch kernel, every pixel with its own constants in its lane
   !> (`integrate_batch`'s `pars`), so that the lanes fill whatever the axes. Other
   !> models, N links and axes over a parameter by name (g, com1, m3, ...): the pixels in groups of equal parameters (`parameter_groups`), each
   !> group by the per-trajectory path with its own model. The lanes never mix, so a
   !> pixel's results do not depend on its block or thread, and equal those of a
   !> direct run with its parameters.
   subroutine compute_parameter_block(setup, b, y0, res)
      type(sweep_setup_t), intent(in) :: setup    !! setup
      integer, intent(in) :: b                    !! block, 1-based
      real(dp), intent(in) :: y0(:, :)            !! (2N, nb) its initial states
      type(batch_result_t), intent(out) :: res    !! its results
      real(dp), allocatable :: p(:, :)
      integer, allocatable :: idx(:)
      type(batch_result_t) :: sub
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      integer :: j, g, nb, j0
      integer, allocatable :: group(:)
      character(len=32), allocatable :: names(:)
      call block_parameters(setup, b, p)
      call block_range(setup, b, j0, nb)
      if (.not. setup%per_trajectory) then
         ! the lanes' constant records (the kernel's own parameters, not models)
         call integrate_batch(setup%cfg%run%pendulum(), setup%opt, y0, res, &
                              pixel_pendulums(setup%cfg, p(:, 1:nb)))
         return
      end if
      call parameter_groups(setup, j0, nb, group)
      do g = 1, maxval(group)
         idx = pack([(j, j=1, nb)], group == g)
         ! one thread at a time: the factory is not reentrant under gfortran 12
         ! (docs/architecture.md, "Threads")
         !$omp critical (dpend_build)
         if (setup%flips .and. named_axes(setup)) then   ! the pendulum's by name
            names = parameter_names(setup)
            call pixel_model_axes(setup%cfg, names, p(:, idx(1)), model, err)
         else if (setup%flips) then
            call pixel_model(setup%cfg, p(:, idx(1)), model, err)
         else
            names = parameter_names(setup)
            call pixel_model_named(setup%cfg, names, p(:, idx(1)), model, err)
         end if
         !$omp end critical (dpend_build)
         if (allocated(err)) error stop 'internal error: a pixel model refused after ' &
            //'validate_sweep: '//err%message
         if (.not. allocated(integ)) allocate (integ, source=setup%integ)
         call integrate_trajectories(model, integ, model%potential_weights(), setup%opt, &
                                     y0(:, idx), sub)
         call place_results(sub, idx, nb, res)
      end do
   end subroutine compute_parameter_block

   !> The group of each of the nb pixels from j0 on of a sweep over parameters: pixels
   !> of one group have equal parameters (the same index on each parameter axis; with
   !> one parameter axis, a whole row (axis 2) or a column of the block's rows (axis
   !> 1)), numbered 1, 2, ... in the order of their first pixel.
   subroutine parameter_groups(setup, j0, nb, group)
      type(sweep_setup_t), intent(in) :: setup      !! setup
      integer, intent(in) :: j0                     !! first pixel
      integer, intent(in) :: nb                     !! pixels
      integer, allocatable, intent(out) :: group(:) !! (nb) group of each pixel
      integer :: key(2, nb), j, jj, k, ng
      do j = 1, nb
         jj = j0 + j - 1
         key(1, j) = merge(mod(jj - 1, setup%cfg%n1) + 1, 0, setup%par1 > 0)
         key(2, j) = merge((jj - 1)/setup%cfg%n1 + 1, 0, setup%par2 > 0)
      end do
      allocate (group(nb))
      group = 0
      ng = 0
      do j = 1, nb
         if (group(j) > 0) cycle
         ng = ng + 1
         do k = j, nb
            if (key(1, k) == key(1, j) .and. key(2, k) == key(2, j)) group(k) = ng
         end do
      end do
   end subroutine parameter_groups

   !> Copy the results `sub` of a group into `res` at the indices idx (`res`
   !> allocated for nb initial conditions on the first call).
   subroutine place_results(sub, idx, nb, res)
      type(batch_result_t), intent(in) :: sub     !! results of the group
      integer, intent(in) :: idx(:)               !! their indices in res
      integer, intent(in) :: nb                   !! size of res
      type(batch_result_t), intent(inout) :: res  !! the block's results
      if (.not. allocated(res%t_flip)) then
         res%n = nb
         allocate (res%t_flip1(nb), res%t_flip2(nb), res%t_flip(nb), res%energy0(nb), &
                   res%energy_error(nb), res%t_stop(nb), res%final(size(sub%final, 1), nb), &
                   res%lyapunov(nb), res%status(nb), res%steps(nb), res%megno(nb), &
                   res%megno_y(nb), res%fli(nb), res%sali(nb), res%gali2(nb))
         if (allocated(sub%t_flip_link)) allocate (res%t_flip_link(size(sub%t_flip_link, 1), nb))
      end if
      res%t_flip1(idx) = sub%t_flip1; res%t_flip2(idx) = sub%t_flip2
      res%t_flip(idx) = sub%t_flip; res%energy0(idx) = sub%energy0
      res%energy_error(idx) = sub%energy_error; res%t_stop(idx) = sub%t_stop
      res%final(:, idx) = sub%final; res%lyapunov(idx) = sub%lyapunov
      res%status(idx) = sub%status; res%steps(idx) = sub%steps
      res%megno(idx) = sub%megno; res%megno_y(idx) = sub%megno_y; res%fli(idx) = sub%fli
      res%sali(idx) = sub%sali; res%gali2(idx) = sub%gali2
      if (allocated(res%t_flip_link)) res%t_flip_link(:, idx) = sub%t_flip_link
   end subroutine place_results

   ! --------------------------------------------------------------- run ---

   !> Run or resume the sweep of `cfg` into cfg%run%output. Errors leave the file
   !> valid and resumable.
   subroutine run_sweep(cfg, summary, error)
      type(sweep_config_t), intent(in) :: cfg           !! validated configuration
      type(sweep_summary_t), intent(out) :: summary     !! what was done
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      type(sweep_setup_t) :: setup
      type(h5file_t) :: h5
      type(progress_t) :: progress
      integer, allocatable :: done(:), missing(:)
      character(len=32), allocatable :: reals(:), ints(:)
      integer(i8) :: n_done
      integer :: complete, b, j0, nb, k
      logical :: failed
      real(dp) :: t0

      if (cfg%threads > 0) call omp_set_num_threads(cfg%threads)
      call build_setup(cfg, setup, error)
      if (allocated(error)) return
      call check_sweep_resources(setup, error)
      if (allocated(error)) return
      summary%n = setup%n
      summary%flips = setup%flips
      summary%energy_fed = .not. setup%cfg%run%model%autonomous()
      summary%bound_integrated = setup%opt%vectors > 0 .or. setup%opt%lyapunov .or. &
                                 .not. setup%opt%skip_cannot_flip
      call open_output(setup, h5, done, complete, error)
      if (allocated(error)) return
      summary%blocks_before = count(done == 1)
      if (complete == 1) then
         call h5%close()
         return
      end if

      missing = pack([(b, b=1, setup%nblocks)], done /= 1)
      call result_names(setup, reals, ints)   ! here: no text is made on the threads
      n_done = 0
      do b = 1, setup%nblocks
         call block_range(setup, b, j0, nb)
         if (done(b) == 1) n_done = n_done + nb
      end do
      call progress%start('dpend sweep', int(setup%n, i8), n_done, cfg%quiet)
      failed = .false.
      t0 = wall_seconds()
      !$omp parallel do schedule(dynamic, 1) default(shared) private(k)
      do k = 1, size(missing)
         call do_block(missing(k))
      end do
      !$omp end parallel do
      summary%seconds = wall_seconds() - t0
      call h5%close()
      call progress%finish()
      if (failed) then
         error%message = error%message//"; '"//working_file(cfg%run%output)// &
                         "' holds the blocks done so far: rerun to resume"
         call run_failure(error)
         return
      end if
      call finalize_file(cfg%run%output, setup, error)
      if (allocated(error)) call run_failure(error)

   contains

      subroutine do_block(bb)
         integer, intent(in) :: bb
         type(batch_result_t) :: res
         type(error_t), allocatable :: werr
         logical :: stop_now
         integer :: jj0, nnb
         integer, allocatable :: crcs(:)
         type(block_values_t), target :: vals
         !$omp atomic read
         stop_now = failed
         if (stop_now) return
         if (stop_requested()) then   ! a library caller asked to stop (src/capi)
            !$omp critical (dpend_sweep_io)
            if (.not. failed) then
               call fatal_error(error, 'interrupted on request')
               !$omp atomic write
               failed = .true.
            end if
            !$omp end critical (dpend_sweep_io)
            return
         end if
         call compute_block(setup, bb, res)
         ! the block's columns and checksums on this thread, before the lock
         call block_values(setup, bb, res, reals, ints, vals)
         crcs = block_result_crcs(vals)
         call block_range(setup, bb, jj0, nnb)
         !$omp critical (dpend_sweep_io)
         ! a block cut short by a stop request is not written
         if (stop_requested() .and. .not. failed) then
            call fatal_error(error, 'interrupted on request')
            !$omp atomic write
            failed = .true.
         end if
         if (.not. failed) then
            call write_values(h5, setup, bb, vals, crcs, werr)
            if (allocated(werr)) then
               call move_alloc(werr, error)
               !$omp atomic write
               failed = .true.
            else
               summary%blocks_computed = summary%blocks_computed + 1
               summary%computed = summary%computed + nnb
               summary%skipped = summary%skipped + count(res%status == st_cannot_flip)
               call progress%update(int(nnb, i8))
            end if
         end if
         !$omp end critical (dpend_sweep_io)
      end subroutine do_block
   end subroutine run_sweep

end module dpend_sweep_engine
