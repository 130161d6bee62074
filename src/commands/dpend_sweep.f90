!> `dpend sweep`: many initial conditions through the batch RK4 kernel
!> (dpend_pendulum_lanes) for two links, or one at a time through the registry's rk4
!> on the run's model (dpend_trajectory_batch) for any other number of links, in
!> blocks distributed over OpenMP threads, into one HDF5 file (layout in
!> docs/hdf5-layout.md, design in docs/sweep.md).
!>
!> Crash safety and resume. While it runs, the results go to a *working* file,
!> FILE.part beside the output FILE, whose datasets are chunked (one chunk per
!> block), uncompressed and allocated in full when the file is created, so writing
!> a block changes raw data only, never the file's metadata: a kill at any moment
!> leaves a valid file. A block's data are written and flushed before its flag in
!> /sweep/done. A kill during a block's write may tear its chunks (a checksum
!> that no longer matches); the block is not flagged, so the resume does not check
!> its checksums (`verify_blocks`) nor needs its old contents (`write_block`).
!> When every block is done, the results are rewritten with compressed chunks
!> through the one writer (dpend_output: temporary file, checked close, one-step
!> move) into FILE, marked complete, and the working file is removed. FILE itself
!> is never changed before the new result is complete. Rerunning the same command
!> computes only the blocks not flagged done in FILE.part; another configuration
!> is refused unless --force.
module dpend_sweep
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
      ieee_quiet_nan
   use omp_lib, only: omp_set_num_threads, omp_get_max_threads
   use dpend_limits, only: sci, max_sweep_points, max_angle, max_angular_velocity, &
                           max_axis_points, max_run_time => max_time, in_range
   use dpend_resources, only: check_memory, check_disk
   use dpend_model, only: max_dof
   use dpend_kinds, only: dp, i8, half_pi
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_output, only: output_t, check_output_path
   use dpend_os, only: path_kind, path_missing, path_file, remove_file
   use dpend_config, only: check_regular_file
   use dpend_pendulum_lanes, only: batch_options_t, batch_result_t, integrate_batch, &
      potential_range, flip_energy_bounds, st_cannot_flip, st_flipped
   use dpend_sweep_config, only: sweep_config_t, time_scale, stop_rule, grid_mode, axis_variable
   use dpend_sweep_config, only: indicator_vectors, axis_parameter, pixel_parameters, &
                                 pixel_model, flip_model, sweep_variable, &
                                 natural_time
   use dpend_pendulum, only: pendulum_t
   use dpend_model, only: model_t
   use dpend_trajectory_batch, only: integrate_trajectories, link_flip_bounds
   use dpend_integrator, only: integrator_t
   use dpend_methods, only: new_integrator
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_progress, only: progress_t, wall_seconds
   use dpend_version, only: version
   use dpend_cli, only: to_str, real_str, seconds_str, printable
   use dpend_parse, only: read_real, quoted
   implicit none
   private
   public :: sweep_setup_t, build_setup, block_initial_conditions, compute_block
   public :: run_sweep, sweep_summary_t, compare_sweeps, summary_text
   public :: config_value, open_sweep_file, check_sweep_data
   ! the pieces of run_sweep, shared with the MPI sweep (mpi/, docs/mpi.md)
   public :: block_range, open_output, write_block, finalize_file, working_file

   !> sweep-compare: accepted --rel, stored time unit sqrt(l1/g) [s] and flip times [s]
   real(dp), parameter :: max_rel = 1000.0_dp, min_tau = 1e-150_dp, max_tau = 1e150_dp, &
                          max_time = 1e300_dp

   !> Everything derived from a configuration that the blocks need.
   type :: sweep_setup_t
      type(sweep_config_t) :: cfg               !! the configuration
      type(batch_options_t) :: opt              !! kernel options (step in s)
      logical :: grid = .true.                  !! grid or list
      integer :: n = 0                          !! initial conditions in all
      integer :: nblocks = 0                    !! blocks
      integer :: block = 0                      !! initial conditions per full block
      integer :: rows = 0                       !! grid: rows of axis 1 per block
      integer :: var1 = 0, var2 = 0             !! swept values: index in (q1..qN, w1..wN)
      !> swept parameters (`axis_parameter`: 1 m1 .. 6 l2/l1; 0: an initial value)
      integer :: par1 = 0, par2 = 0
      real(dp), allocatable :: axis1(:)         !! grid: axis values (axis units)
      real(dp), allocatable :: axis2(:)         !! grid: axis values (axis units)
      real(dp), allocatable :: list(:, :)       !! list: (2N, n) states (q, q̇)
      integer :: links = 2                      !! number of links N
      !> Integrate one trajectory at a time (dpend_trajectory_batch) instead of the
      !> batch kernel: every N but 2; tests set it for N = 2 to compare the paths.
      logical :: per_trajectory = .false.
      !> The model has rods that flip (the pendulum): t_flip, the flip stop rules and
      !> bounds apply. False for the elastic pendulum (docs/sweep.md).
      logical :: flips = .true.
      real(dp), allocatable :: gl(:)            !! G_i of V = Σ G_i sin q_i [J] (N)
      !> The method of the per-trajectory path (rk4 from the registry), copied for
      !> every block in flight.
      class(integrator_t), allocatable :: integ
      real(dp) :: tau = 1                       !! √(L1/g) [s]
      character(len=:), allocatable :: config   !! canonical configuration text
      !> Fletcher-32 checksums on the working file's datasets (the final file always
      !> has them). The MPI sweep turns them off: parallel HDF5 writes filtered
      !> datasets only collectively, and its blocks arrive in any order.
      logical :: checksum = .true.
   end type sweep_setup_t

   !> What a run did, for the closing line.
   type :: sweep_summary_t
      integer :: n = 0                   !! initial conditions
      integer :: blocks_computed = 0     !! blocks computed by this run
      integer :: blocks_before = 0       !! blocks found done in an existing file
      integer(i8) :: computed = 0        !! initial conditions computed by this run
      integer(i8) :: skipped = 0         !! of those: below the flip energy bound
      real(dp) :: seconds = 0            !! wall time of the computation [s]
      logical :: flips = .true.          !! the model has flips (the closing line's bound)
   end type sweep_summary_t


contains

   !> The closing line of a run that computed something: 'N initial conditions
   !> computed (K below the flip energy bound) in 0.4 s, 1.2e5 per second'.
   function summary_text(summary) result(s)
      type(sweep_summary_t), intent(in) :: summary  !! what the run did
      character(len=:), allocatable :: s
      s = to_str(summary%computed)//' initial conditions computed'
      if (summary%flips) s = s//' ('//to_str(summary%skipped)//' below the flip energy bound)'
      s = s//' in '//seconds_str(summary%seconds)//' s, '// &
          real_str(real(summary%computed, dp)/max(summary%seconds, 1e-9_dp), 3)//' per second'
   end function summary_text

   ! ------------------------------------------------------------- setup ---

   !> Derive the step, the initial conditions and the blocks; read a list file.
   subroutine build_setup(cfg, setup, error)
      type(sweep_config_t), intent(in) :: cfg           !! validated configuration
      type(sweep_setup_t), intent(out) :: setup         !! the setup
      type(error_t), allocatable, intent(out) :: error  !! unreadable list
      real(dp) :: scale, t_end
      integer :: i
      setup%cfg = cfg
      setup%grid = grid_mode(cfg)
      setup%links = cfg%run%model%n_dof()   ! N links; the elastic pendulum's 2
      setup%flips = flip_model(cfg)
      setup%per_trajectory = setup%links /= 2 .or. .not. setup%flips
      call new_integrator(cfg%run%method, setup%integ, error)
      if (allocated(error)) return
      setup%gl = cfg%run%model%potential_weights()   ! G_i (any N, also 2)
      setup%tau = natural_time(cfg)   ! √(L1/g), the elastic pendulum's √(l0/g)
      scale = time_scale(cfg)
      t_end = cfg%run%t_end*scale
      setup%opt%n_steps = max(1_i8, ceiling(cfg%run%t_end/cfg%run%dt*(1.0_dp - 1e-12_dp), i8))
      setup%opt%h = t_end/real(setup%opt%n_steps, dp)
      setup%opt%stop_rule = stop_rule(cfg)
      setup%opt%lyapunov = cfg%lyapunov
      setup%opt%vectors = indicator_vectors(cfg)
      if (setup%grid) then
         setup%var1 = sweep_variable(cfg, cfg%axis1)
         setup%var2 = sweep_variable(cfg, cfg%axis2)
         setup%par1 = axis_parameter(cfg%axis1)
         setup%par2 = axis_parameter(cfg%axis2)
         allocate (setup%axis1(cfg%n1), setup%axis2(cfg%n2))
         do i = 1, cfg%n1
            setup%axis1(i) = axis_value(cfg%min1, cfg%max1, cfg%n1, i)
         end do
         do i = 1, cfg%n2
            setup%axis2(i) = axis_value(cfg%min2, cfg%max2, cfg%n2, i)
         end do
         setup%n = cfg%n1*cfg%n2
         setup%rows = max(1, min(cfg%n2, cfg%block/cfg%n1))
         setup%block = setup%rows*cfg%n1
         setup%nblocks = (cfg%n2 + setup%rows - 1)/setup%rows
      else
         call read_list(cfg, setup%list, error)
         if (allocated(error)) return
         if (.not. setup%flips) call check_list_states(cfg, setup%list, error)
         if (allocated(error)) return
         setup%n = size(setup%list, 2)
         setup%block = min(cfg%block, setup%n)
         setup%nblocks = (setup%n + setup%block - 1)/setup%block
      end if
      setup%config = canonical_config(setup)
   end subroutine build_setup

   !> Every state of a list within the model (`check_state`: the elastic pendulum's r
   !> above its collapse), for a model without flips.
   subroutine check_list_states(cfg, list, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, model built
      real(dp), intent(in) :: list(:, :)                !! (2n, count) states
      type(error_t), allocatable, intent(out) :: error  !! the first state refused
      integer :: j, n
      n = size(list, 1)/2
      do j = 1, size(list, 2)
         call cfg%run%model%check_state(list(:n, j), list(n + 1:, j), error)
         if (allocated(error)) then
            error%message = "invalid ic_file '"//printable(cfg%ic_file)//"': initial " &
                            //'condition '//to_str(j)//' is refused: '//error%message
            return
         end if
      end do
   end subroutine check_list_states

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

   !> Value number i of n on [lo, hi].
   pure real(dp) function axis_value(lo, hi, n, i)
      real(dp), intent(in) :: lo, hi  !! range
      integer, intent(in) :: n, i     !! points, index
      if (n == 1) then
         axis_value = lo
      else if (i == n) then
         axis_value = hi
      else
         axis_value = lo + (hi - lo)*(real(i - 1, dp)/real(n - 1, dp))
      end if
   end function axis_value

   !> Initial state component from an axis value (θ → q = θ - π/2).
   pure real(dp) function state_value(name, x)
      character(len=*), intent(in) :: name  !! axis name
      real(dp), intent(in) :: x             !! axis value
      state_value = x
      if (index(name, 'theta') == 1) state_value = x - half_pi
   end function state_value

   !> First initial condition and number of initial conditions of block b.
   pure subroutine block_range(setup, b, j0, nb)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      integer, intent(in) :: b                  !! block, 1-based
      integer, intent(out) :: j0, nb            !! first index, count
      j0 = (b - 1)*setup%block + 1
      nb = min(setup%block, setup%n - j0 + 1)
   end subroutine block_range

   !> The initial states (q1 .. qN, q̇1 .. q̇N) of block b.
   subroutine block_initial_conditions(setup, b, y0)
      type(sweep_setup_t), intent(in) :: setup      !! setup
      integer, intent(in) :: b                      !! block, 1-based
      real(dp), allocatable, intent(out) :: y0(:, :) !! (2N, nb)
      real(dp) :: base(2*setup%links)
      integer :: j0, nb, j, jj, i1, i2
      call block_range(setup, b, j0, nb)
      allocate (y0(2*setup%links, nb))
      if (.not. setup%grid) then
         y0 = setup%list(:, j0:j0 + nb - 1)
         return
      end if
      base = [setup%cfg%run%q0(), setup%cfg%run%w0()]
      do j = 1, nb
         jj = j0 + j - 1
         i1 = mod(jj - 1, setup%cfg%n1) + 1
         i2 = (jj - 1)/setup%cfg%n1 + 1
         y0(:, j) = base
         if (setup%var1 > 0) y0(setup%var1, j) = state_value(setup%cfg%axis1, setup%axis1(i1))
         if (setup%var2 > 0) y0(setup%var2, j) = state_value(setup%cfg%axis2, setup%axis2(i2))
      end do
   end subroutine block_initial_conditions

   !> True if an axis sweeps a parameter (m1, m2, l1, l2, m2/m1, l2/l1).
   pure logical function parameter_axes(setup)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      parameter_axes = setup%par1 > 0 .or. setup%par2 > 0
   end function parameter_axes

   !> The parameters (m1, m2, l1, l2) of the pixels of block b (4, nb).
   subroutine block_parameters(setup, b, p)
      type(sweep_setup_t), intent(in) :: setup      !! setup
      integer, intent(in) :: b                      !! block, 1-based
      real(dp), allocatable, intent(out) :: p(:, :) !! (4, nb) [kg, kg, m, m]
      integer :: j0, nb, j, jj, i1, i2
      call block_range(setup, b, j0, nb)
      allocate (p(4, nb))
      do j = 1, nb
         jj = j0 + j - 1
         i1 = 1; i2 = 1
         if (setup%grid) then
            i1 = mod(jj - 1, setup%cfg%n1) + 1
            i2 = (jj - 1)/setup%cfg%n1 + 1
            p(:, j) = pixel_parameters(setup%cfg, setup%par1, setup%axis1(i1), setup%par2, &
                                       setup%axis2(i2))
         else
            p(:, j) = pixel_parameters(setup%cfg, 0, 0.0_dp, 0, 0.0_dp)
         end if
      end do
   end subroutine block_parameters

   !> Integrate block b: the batch kernel for two links, else one trajectory at a
   !> time with this block's own copy of the method.
   subroutine compute_block(setup, b, res)
      type(sweep_setup_t), intent(in) :: setup    !! setup
      integer, intent(in) :: b                    !! block, 1-based
      type(batch_result_t), intent(out) :: res    !! its results
      real(dp), allocatable :: y0(:, :)
      class(integrator_t), allocatable :: integ
      call block_initial_conditions(setup, b, y0)
      if (parameter_axes(setup)) then
         call compute_parameter_block(setup, b, y0, res)
      else if (setup%per_trajectory) then
         allocate (integ, source=setup%integ)
         call integrate_trajectories(setup%cfg%run%model, integ, setup%gl, setup%opt, y0, res)
      else
         call integrate_batch(setup%cfg%run%pendulum(), setup%opt, y0, res)
      end if
   end subroutine compute_block

   !> Integrate block b of a sweep over parameters: its pixels in groups of equal
   !> parameters (the pixels of one value of each parameter axis: with one
   !> parameter axis, a whole row (axis 2) or a column of the block's rows (axis 1)),
   !> each group by the batch kernel with its own constants (or the per-trajectory
   !> path with its own model). The lanes never mix, so a pixel's results do not
   !> depend on its group, block or thread. With both axes parameters every group is
   !> one pixel and the kernel's other lanes idle.
   subroutine compute_parameter_block(setup, b, y0, res)
      type(sweep_setup_t), intent(in) :: setup    !! setup
      integer, intent(in) :: b                    !! block, 1-based
      real(dp), intent(in) :: y0(:, :)            !! (2N, nb) its initial states
      type(batch_result_t), intent(out) :: res    !! its results
      real(dp), allocatable :: p(:, :)
      integer, allocatable :: key(:, :), idx(:)
      logical, allocatable :: todo(:)
      type(batch_result_t) :: sub
      type(pendulum_t) :: par
      class(model_t), allocatable :: model
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      integer :: j, k, nb, j0, jj
      call block_parameters(setup, b, p)
      call block_range(setup, b, j0, nb)
      ! the group of a pixel: its index on each parameter axis (0: not a parameter)
      allocate (key(2, nb), todo(nb))
      do j = 1, nb
         jj = j0 + j - 1
         key(1, j) = merge(mod(jj - 1, setup%cfg%n1) + 1, 0, setup%par1 > 0)
         key(2, j) = merge((jj - 1)/setup%cfg%n1 + 1, 0, setup%par2 > 0)
      end do
      todo = .true.
      do j = 1, nb
         if (.not. todo(j)) cycle
         idx = pack([(k, k=1, nb)], key(1, :) == key(1, j) .and. key(2, :) == key(2, j))
         todo(idx) = .false.
         if (setup%per_trajectory) then
            call pixel_model(setup%cfg, p(:, j), model, err)   ! checked by validate_sweep
            if (.not. allocated(integ)) allocate (integ, source=setup%integ)
            call integrate_trajectories(model, integ, model%potential_weights(), setup%opt, &
                                        y0(:, idx), sub)
         else
            ! the lanes' constant record (the kernel's own parameters, not a model)
            par = setup%cfg%run%pendulum()
            par%m1 = p(1, j); par%m2 = p(2, j); par%l1 = p(3, j); par%l2 = p(4, j)
            call integrate_batch(par, setup%opt, y0(:, idx), sub)
         end if
         call place_results(sub, idx, nb, res)
      end do
   end subroutine compute_parameter_block

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

   !> Read a list of initial conditions: text rows "q1 q2 w1 w2" ('#' comments) or
   !> an HDF5 dataset of shape (n, 4) as h5py sees it; for N links rows
   !> "q1 .. qN w1 .. wN", (n, 2N).
   subroutine read_list(cfg, list, error)
      type(sweep_config_t), intent(in) :: cfg            !! configuration
      real(dp), allocatable, intent(out) :: list(:, :)   !! (2N, n)
      type(error_t), allocatable, intent(out) :: error   !! unreadable or invalid
      type(h5file_t) :: h5
      integer, allocatable :: dims(:)
      real(dp), allocatable :: tmp(:, :)
      real(dp) :: row(2*cfg%run%links)
      character(len=4096) :: line
      character(len=:), allocatable :: what, cols, fields, why
      integer :: unit, stat, n, nline, hash, nl
      what = "invalid ic_file '"//printable(cfg%ic_file)//"'"
      nl = cfg%run%links
      cols = to_str(2*nl)
      fields = '"q1 q2 w1 w2"'
      if (nl == 1) fields = '"q1 w1"'
      if (nl > 2) fields = '"q1 .. q'//to_str(nl)//' w1 .. w'//to_str(nl)//'"'
      ! a regular file (a FIFO would block, a directory cannot be read)
      call check_regular_file(cfg%ic_file, what//': ', error)
      if (allocated(error)) return
      if (is_hdf5(cfg%ic_file)) then
         call h5%open(cfg%ic_file, 'r', error)
         if (.not. allocated(error)) call h5%shape(cfg%ic_dataset, dims, error)
         if (allocated(error)) then
            error%message = what//': '//error%message
            return
         end if
         if (size(dims) /= 2) then
            call fatal_error(error, what//': dataset '//cfg%ic_dataset// &
                             ' must have shape (n, '//cols//')')
         else if (dims(1) /= 2*nl) then
            call fatal_error(error, what//': dataset '//cfg%ic_dataset// &
                             ' must have shape (n, '//cols//')')
         else if (dims(2) > max_sweep_points) then
            call fatal_error(error, what//': '//to_str(dims(2))//' initial conditions, at ' &
                             //'most '//to_str(max_sweep_points))
         else
            call h5%read(cfg%ic_dataset, list, error)
         end if
         call h5%close()
         if (allocated(error)) return
      else
         open (newunit=unit, file=cfg%ic_file, status='old', action='read', iostat=stat)
         if (stat /= 0) then
            call fatal_error(error, what//': cannot open it')
            return
         end if
         allocate (list(2*nl, 1024))
         n = 0
         nline = 0
         do
            read (unit, '(a)', iostat=stat) line
            if (stat < 0) exit
            nline = nline + 1
            hash = index(line, '#')
            if (hash > 0) line(hash:) = ' '
            if (stat > 0) then
               call fatal_error(error, what//': cannot read line '//to_str(nline))
               exit
            end if
            if (len_trim(line) == 0) cycle
            if (count_fields(line) /= 2*nl) then
               call fatal_error(error, what//': line '//to_str(nline)// &
                                ' is not '//cols//' numbers '//fields)
               exit
            end if
            call read_fields(line, row, why)   ! the one strict parser, field by field
            if (len(why) > 0) then
               call fatal_error(error, what//': line '//to_str(nline)//': '//why)
               exit
            end if
            if (n >= max_sweep_points) then
               call fatal_error(error, what//': more than '//to_str(max_sweep_points)// &
                                ' initial conditions')
               exit
            end if
            if (n == size(list, 2)) then
               allocate (tmp(2*nl, min(2*n, max_sweep_points)))
               tmp(:, :n) = list
               call move_alloc(tmp, list)
            end if
            n = n + 1
            list(:, n) = row
         end do
         close (unit)
         if (allocated(error)) return
         list = list(:, :n)
      end if
      if (size(list, 2) == 0) then
         call fatal_error(error, what//': it holds no initial condition')
      else if (.not. all(ieee_is_finite(list))) then
         call fatal_error(error, what//': every value must be finite')
      else if (maxval(abs(list(1:nl, :))) > max_angle) then
         call fatal_error(error, what//': angles must be within [-'//sci(max_angle)//', ' &
                          //sci(max_angle)//'] rad')
      else if (maxval(abs(list(nl + 1:2*nl, :))) > max_angular_velocity) then
         call fatal_error(error, what//': angular velocities must be within [-' &
                          //sci(max_angular_velocity)//', '//sci(max_angular_velocity)// &
                          '] rad/s')
      end if
      if (allocated(error)) return
      if (cfg%ic_angles == 'theta') list(1:nl, :) = list(1:nl, :) - half_pi
   end subroutine read_list

   !> Number of blank-separated fields of a line.
   !> The fields of `line` (separated by blanks, tabs or commas, as `count_fields`
   !> counts them) read into `row` by the strict parser; `why` names the first field
   !> that is not a number ('' when all are).
   subroutine read_fields(line, row, why)
      character(len=*), intent(in) :: line                !! text, count_fields(line) fields
      real(dp), intent(out) :: row(:)                     !! the values
      character(len=:), allocatable, intent(out) :: why   !! '' or the reason
      character(len=*), parameter :: seps = ' ,'//achar(9)
      integer :: i, j, k
      why = ''
      row = 0.0_dp
      i = 1
      do k = 1, size(row)
         do while (index(seps, line(i:i)) > 0)
            i = i + 1
         end do
         j = i
         do while (j < len_trim(line))
            if (index(seps, line(j + 1:j + 1)) > 0) exit
            j = j + 1
         end do
         call read_real(line(i:j), row(k), why)
         if (len(why) > 0) then
            why = quoted(line(i:j))//' '//why
            return
         end if
         i = j + 1
      end do
   end subroutine read_fields

   pure integer function count_fields(line)
      character(len=*), intent(in) :: line  !! text
      integer :: i
      logical :: in_field
      count_fields = 0
      in_field = .false.
      do i = 1, len_trim(line)
         if (line(i:i) == ' ' .or. line(i:i) == achar(9) .or. line(i:i) == ',') then
            in_field = .false.
         else if (.not. in_field) then
            in_field = .true.
            count_fields = count_fields + 1
         end if
      end do
   end function count_fields

   !> The whole configuration as "key = value" lines; two runs whose texts are equal
   !> produce identical files. Threads and progress options are not part of it.
   function canonical_config(setup) result(s)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      associate (c => setup%cfg, p => setup%cfg%run%pendulum())
         if (.not. setup%flips) then   ! a model without rods: its parameters by name
            s = 'program = dpend '//version//nl//'command = sweep'//nl// &
                'method = '//c%run%method//nl//'kernel = per trajectory'//nl// &
                'model = '//c%run%spec%model_name()//nl//model_lines()// &
                'q = '//rl(c%run%q0())//nl//'w = '//rl(c%run%w0())//nl
         else if (setup%links == 2) then   ! as before issue 12: older files resume
            s = 'program = dpend '//version//nl//'command = sweep'//nl// &
                'method = '//c%run%method//nl//'kernel = batch rk4'//nl// &
                'm1 = '//r(p%m1)//nl//'m2 = '//r(p%m2)//nl//'l1 = '//r(p%l1)//nl// &
                'l2 = '//r(p%l2)//nl//'g = '//r(p%g)//nl// &
                'q1 = '//r(c%run%q(1))//nl//'q2 = '//r(c%run%q(2))//nl// &
                'w1 = '//r(c%run%w(1))//nl//'w2 = '//r(c%run%w(2))//nl
         else
            s = 'program = dpend '//version//nl//'command = sweep'//nl// &
                'method = '//c%run%method//nl//'kernel = per trajectory'//nl// &
                'links = '//to_str(setup%links)//nl// &
                'm = '//rl(c%run%m(:setup%links))//nl//'l = '//rl(c%run%l(:setup%links))// &
                nl//'g = '//r(c%run%g)//nl//'q = '//rl(c%run%q0())//nl// &
                'w = '//rl(c%run%w0())//nl
         end if
         s = s//'time_unit = '//c%time_unit//nl//'dt = '//r(c%run%dt)//nl// &
             't_end = '//r(c%run%t_end)//nl//'h = '//r(setup%opt%h)//nl// &
             'n_steps = '//to_str(setup%opt%n_steps)//nl// &
             'stop_at = '//stop_name(setup%opt%stop_rule)//nl// &
             'lyapunov = '//trim(merge('true ', 'false', c%lyapunov))//nl// &
             indicator_line()// &
             'stats = '//trim(merge('true ', 'false', c%stats))//nl// &
             'block = '//to_str(setup%block)//nl
         if (setup%grid) then
            s = s//'initial = grid'//nl// &
                'axis1 = '//c%axis1//nl//'n1 = '//to_str(c%n1)//nl// &
                'min1 = '//r(c%min1)//nl//'max1 = '//r(c%max1)//nl// &
                'axis2 = '//c%axis2//nl//'n2 = '//to_str(c%n2)//nl// &
                'min2 = '//r(c%min2)//nl//'max2 = '//r(c%max2)
         else
            s = s//'initial = list'//nl//'ic_file = '//c%ic_file//nl// &
                'ic_dataset = '//c%ic_dataset//nl//'ic_angles = '//c%ic_angles//nl// &
                'ic_count = '//to_str(setup%n)//nl//'ic_hash = '//to_str(list_hash(setup%list))
         end if
      end associate
   contains
      !> 'k = 4.0e+001' lines of the model's parameters, in its order.
      function model_lines() result(t)
         character(len=:), allocatable :: t, name, units
         real(dp) :: x
         integer :: i
         t = ''
         do i = 1, setup%cfg%run%model%n_parameters()
            call setup%cfg%run%model%parameter(i, name, x, units)
            t = t//name//' = '//r(x)//nl
         end do
      end function model_lines
      !> 'indicator = megno' for the indicators of the kernel's deviation vectors;
      !> nothing for flip and lambda1 (files from before the indicators resume).
      function indicator_line() result(t)
         character(len=:), allocatable :: t
         t = ''
         if (indicator_vectors(setup%cfg) > 0) t = 'indicator = '//setup%cfg%indicator//nl
      end function indicator_line
      function r(x) result(t)
         real(dp), intent(in) :: x
         character(len=:), allocatable :: t
         character(len=32) :: buf
         write (buf, '(es24.16e3)') x
         t = trim(adjustl(buf))
      end function r
      !> A list, comma-separated.
      function rl(x) result(t)
         real(dp), intent(in) :: x(:)
         character(len=:), allocatable :: t
         integer :: i
         t = r(x(1))
         do i = 2, size(x)
            t = t//', '//r(x(i))
         end do
      end function rl
   end function canonical_config

   !> Name of a stop rule.
   pure function stop_name(rule) result(s)
      integer, intent(in) :: rule  !! stop_* code
      character(len=:), allocatable :: s
      select case (rule)
      case (1); s = 'both'
      case (2); s = 'either'
      case default; s = 'end'
      end select
   end function stop_name

   !> A checksum of the bit patterns of a list of initial conditions.
   pure integer(i8) function list_hash(list)
      real(dp), intent(in) :: list(:, :)  !! (4, n)
      integer(i8), parameter :: p = 2147483647_i8, mask = 2147483647_i8
      integer(i8) :: bits
      integer :: i, j, k
      list_hash = 17
      do j = 1, size(list, 2)
         do i = 1, size(list, 1)
            bits = transfer(list(i, j), bits)
            do k = 0, 2
               list_hash = mod(list_hash*1000003_i8 + iand(ishft(bits, -31*k), mask), p)
            end do
         end do
      end do
   end function list_hash

   ! ------------------------------------------------------------ layout ---

   !> Names of the result datasets under /sweep (reals, then integers).
   subroutine result_names(setup, reals, ints)
      type(sweep_setup_t), intent(in) :: setup                     !! setup
      character(len=32), allocatable, intent(out) :: reals(:)      !! real datasets
      character(len=32), allocatable, intent(out) :: ints(:)       !! integer datasets
      character(len=32) :: name
      integer :: i
      if (.not. setup%flips) then   ! no t_flip: final/q1 .. final/qn, final/w1 .. final/wn
         allocate (reals(2*setup%links + 3))
         reals(1:3) = [character(len=32) :: 'energy0', 'energy_error', 't_stop']
         do i = 1, setup%links
            reals(3 + i) = 'final/q'//to_str(i)
            reals(setup%links + 3 + i) = 'final/w'//to_str(i)
         end do
      else if (setup%links == 2) then
         reals = [character(len=32) :: 't_flip', 't_flip1', 't_flip2', 'energy0', &
                  'energy_error', 't_stop', 'final/q1', 'final/q2', 'final/w1', 'final/w2']
      else   ! N links: t_flip1 .. t_flipN, final/q1 .. final/qN, final/w1 .. final/wN
         allocate (reals(3*setup%links + 4))
         reals(1) = 't_flip'
         do i = 1, setup%links
            reals(1 + i) = 't_flip'//to_str(i)
            reals(setup%links + 4 + i) = 'final/q'//to_str(i)
            reals(2*setup%links + 4 + i) = 'final/w'//to_str(i)
         end do
         reals(setup%links + 2) = 'energy0'
         reals(setup%links + 3) = 'energy_error'
         reals(setup%links + 4) = 't_stop'
      end if
      if (setup%cfg%lyapunov) reals = [reals, [character(len=32) :: 'lyapunov']]
      select case (setup%cfg%indicator)
      case ('megno'); reals = [reals, [character(len=32) :: 'megno', 'megno_y']]
      case ('fli', 'sali', 'gali2')
         name = setup%cfg%indicator   ! (one length in the constructor under -fcheck)
         reals = [reals, name]
      end select
      if (parameter_axes(setup)) reals = [reals, [character(len=32) :: 'param/m1', &
                                          'param/m2', 'param/l1', 'param/l2']]
      ints = [character(len=32) :: 'status']
      if (setup%cfg%stats) ints = [ints, [character(len=32) :: 'steps']]
   end subroutine result_names

   !> Units of a swept variable: 'rad' for an angle, 'rad/s' for a velocity.
   pure function axis_units(axis) result(units)
      character(len=*), intent(in) :: axis  !! theta1, theta2, q1, q2, w1, w2, m1, ...
      character(len=:), allocatable :: units
      select case (axis_parameter(axis))
      case (1, 2); units = 'kg'
      case (3, 4); units = 'm'
      case (5, 6); units = '1'
      case default
         if (index(axis, 'w') == 1) then
            units = 'rad/s'
         else
            units = 'rad'
         end if
      end select
   end function axis_units

   !> Units and description of the sweep dataset `name` (below /sweep).
   subroutine dataset_info(name, axis_units, units, text, links)
      character(len=*), intent(in) :: name                 !! e.g. 't_flip', 'final/q1'
      character(len=*), intent(in) :: axis_units           !! units of the swept axis
      character(len=:), allocatable, intent(out) :: units  !! SI units, '1' dimensionless
      character(len=:), allocatable, intent(out) :: text   !! one-line description
      integer, intent(in), optional :: links               !! number of links (default 2)
      integer :: nl
      nl = 2
      if (present(links)) nl = links
      if (nl /= 2) then   ! the names and texts of N links; two links as before
         if (name == 't_flip') then
            units = 's'; text = 'first flip of any link (NaN: none before t_stop); '// &
               'divide by /sweep@sqrt_l1_over_g for the natural unit sqrt(l1/g)'
            return
         else if (index(name, 't_flip') == 1) then
            units = 's'; text = 'first flip of link '//name(7:)//' (NaN: none before '// &
               't_stop); divide by /sweep@sqrt_l1_over_g for the natural unit sqrt(l1/g)'
            return
         else if (index(name, 'final/q') == 1) then
            units = 'rad'; text = 'angle at t_stop from the horizontal x axis'
            return
         else if (index(name, 'final/w') == 1) then
            units = 'rad/s'; text = 'angular velocity at t_stop'
            return
         else if (name == 'energy0') then
            units = 'J'; text = 'initial energy E(0) (V = 0 with every link horizontal)'
            return
         else if (name == 'status') then
            units = '1'; text = '0 not computed, 1 integrated to t_end, 2 stopped after '// &
               'a flip, 3 below every flip bound, 4 a step was not finite'
            return
         else if (name == 'initial') then
            units = 'rad, rad/s'; text = 'initial states (q1 .. qN, qdot1 .. qdotN), '// &
               'angles from the horizontal x axis'
            return
         end if
      end if
      select case (name)
      case ('t_flip')
         units = 's'; text = 'first flip of either link (NaN: none before t_stop); '// &
            'divide by /sweep@sqrt_l1_over_g for the natural unit sqrt(l1/g)'
      case ('t_flip1')
         units = 's'; text = 'first flip of link 1 (NaN: none before t_stop); '// &
            'divide by /sweep@sqrt_l1_over_g for the natural unit sqrt(l1/g)'
      case ('t_flip2')
         units = 's'; text = 'first flip of link 2 (NaN: none before t_stop); '// &
            'divide by /sweep@sqrt_l1_over_g for the natural unit sqrt(l1/g)'
      case ('energy0')
         units = 'J'; text = 'initial energy E(0) (V = 0 with both links horizontal)'
      case ('energy_error')
         units = '1'; text = 'max |E(t) - E(0)| / potential_range (NaN: not integrated)'
      case ('t_stop')
         units = 's'; text = 'time the trajectory was integrated to (0: not integrated)'
      case ('final/q1', 'final/q2')
         units = 'rad'; text = 'angle at t_stop from the horizontal x axis'
      case ('final/w1', 'final/w2')
         units = 'rad/s'; text = 'angular velocity at t_stop'
      case ('lyapunov')
         units = '1/s'; text = 'largest Lyapunov exponent'
      case ('param/m1', 'param/m2')
         units = 'kg'; text = 'mass of link '//name(8:8)//' of the pixel (parameter axes)'
      case ('param/l1', 'param/l2')
         units = 'm'; text = 'length of link '//name(8:8)//' of the pixel (parameter axes)'
      case ('megno')
         units = '1'; text = 'MEGNO running mean <Y>(t_stop) of one deviation vector '// &
            '(regular orbits -> 2, chaotic ~ lambda1 t/2; NaN: not finite)'
      case ('megno_y')
         units = '1'; text = 'MEGNO Y(t_stop) = 2/t int s (ddot.d)/(d.d) ds of one '// &
            'deviation vector (NaN: not finite)'
      case ('fli')
         units = '1'; text = 'fast Lyapunov indicator ln |d(t_stop)| of one deviation '// &
            'vector, |d(0)| = 1 (regular ~ ln t, chaotic ~ lambda1 t; NaN: not finite)'
      case ('sali')
         units = '1'; text = 'SALI of two deviation vectors at t_stop (chaotic -> 0 '// &
            'as exp(-(lambda1 - lambda2) t), regular stays away from 0; NaN: not finite)'
      case ('gali2')
         units = '1'; text = 'GALI_2 of two deviation vectors at t_stop (chaotic -> 0 '// &
            'as exp(-(lambda1 - lambda2) t), regular stays away from 0; NaN: not finite)'
      case ('status')
         units = '1'; text = '0 not computed, 1 integrated to t_end, 2 stopped after a '// &
            'flip, 3 below both flip bounds, 4 state became non-finite'
      case ('steps')
         units = '1'; text = 'RK4 steps taken (4 right-hand-side evaluations each)'
      case ('done')
         units = '1'; text = '1 for every block written (resume flags)'
      case ('axis1', 'axis2')
         units = axis_units; text = 'grid values on '//name(1:4)//' '//name(5:5)
      case ('initial')
         units = 'rad, rad/s'; text = 'initial states (q1, q2, qdot1, qdot2), angles '// &
            'from the horizontal x axis'
      case default
         units = '1'; text = name
      end select
   end subroutine dataset_info

   !> Create the file with every dataset and attribute: the working layout
   !> (uncompressed, allocated now) or the final one (compressed).
   subroutine create_layout(h5, filename, setup, final, error)
      type(h5file_t), intent(inout) :: h5               !! file object, left open
      character(len=*), intent(in) :: filename          !! file to create (truncated)
      type(sweep_setup_t), intent(in) :: setup          !! setup
      logical, intent(in) :: final                      !! compressed, complete
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      character(len=32), allocatable :: reals(:), ints(:)
      character(len=:), allocatable :: units, text
      integer, allocatable :: dims(:), chunk(:)
      real(dp) :: nan, range
      real(dp), allocatable :: bounds(:)
      integer :: i
      nan = ieee_value(nan, ieee_quiet_nan)
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      if (setup%grid) then
         dims = [setup%cfg%n1, setup%cfg%n2]
         chunk = [setup%cfg%n1, setup%rows]
      else
         dims = [setup%n]
         chunk = [setup%block]
      end if
      call result_names(setup, reals, ints)
      do i = 1, size(reals)
         call dataset_info(trim(reals(i)), '', units, text, setup%links)
         if (.not. setup%flips) call model_dataset_info(setup, trim(reals(i)), units, text)
         call h5%create_dataset('/sweep/'//trim(reals(i)), 'real64', dims, chunk, error, &
                                fill=nan, compress=final, alloc_early=.not. final, &
                                checksum=final .or. setup%checksum, units=units, &
                                description=text)
         if (allocated(error)) return
      end do
      do i = 1, size(ints)
         call dataset_info(trim(ints(i)), '', units, text, setup%links)
         if (.not. setup%flips) call model_dataset_info(setup, trim(ints(i)), units, text)
         call h5%create_dataset('/sweep/'//trim(ints(i)), 'int32', dims, chunk, error, &
                                fill=0.0_dp, compress=final, alloc_early=.not. final, &
                                checksum=final .or. setup%checksum, units=units, &
                                description=text)
         if (allocated(error)) return
      end do
      call dataset_info('done', '', units, text)
      call h5%write('/sweep/done', spread(merge(1, 0, final), 1, setup%nblocks), error, &
                    units, text)
      if (allocated(error)) return
      if (setup%grid) then
         call dataset_info('axis1', axis_units(setup%cfg%axis1), units, text)
         if (.not. setup%flips) call model_dataset_info(setup, 'axis1', units, text)
         call h5%write('/sweep/axis1', setup%axis1, error, units, text)
         call dataset_info('axis2', axis_units(setup%cfg%axis2), units, text)
         if (.not. setup%flips) call model_dataset_info(setup, 'axis2', units, text)
         if (.not. allocated(error)) call h5%write('/sweep/axis2', setup%axis2, error, &
                                                   units, text)
      else
         call dataset_info('initial', '', units, text, setup%links)
         if (.not. setup%flips) call model_dataset_info(setup, 'initial', units, text)
         call h5%write('/sweep/initial', setup%list, error, units, text)
      end if
      if (allocated(error)) return
      if (.not. setup%flips) then
         call model_attributes(h5, setup, final)
         call h5%take_error(error)
         return
      else if (setup%links == 2) then
         bounds = flip_energy_bounds(setup%cfg%run%pendulum())
         range = potential_range(setup%cfg%run%pendulum())
      else
         bounds = link_flip_bounds(setup%gl)
         range = 2.0_dp*sum(setup%gl)
      end if
      ! the attributes pass no `error`: h5 keeps the first failure (take_error below)
      associate (c => setup%cfg, p => setup%cfg%run%pendulum())
         call h5%writeattr('/', 'program', 'dpend sweep')
         call h5%writeattr('/', 'version', version)
         call h5%writeattr('/', 'method', c%run%method)
         call h5%writeattr('/sweep', 'config', setup%config)
         call h5%writeattr('/sweep', 'complete', merge(1, 0, final))
         if (setup%links == 2) then
            call h5%writeattr('/sweep', 'm1', p%m1)
            call h5%writeattr('/sweep', 'm2', p%m2)
            call h5%writeattr('/sweep', 'l1', p%l1)
            call h5%writeattr('/sweep', 'l2', p%l2)
         end if
         call h5%writeattr('/sweep', 'links', setup%links)
         call h5%writeattr('/sweep', 'm', c%run%m(:setup%links))
         call h5%writeattr('/sweep', 'l', c%run%l(:setup%links))
         call h5%writeattr('/sweep', 'g', c%run%g)
         call h5%writeattr('/sweep', 'q0', c%run%q0())
         call h5%writeattr('/sweep', 'qdot0', c%run%w0())
         call h5%writeattr('/sweep', 'h', setup%opt%h)
         call h5%writeattr('/sweep', 't_end', setup%opt%h*setup%opt%n_steps)
         call h5%writeattr('/sweep', 'n_steps', setup%opt%n_steps)
         call h5%writeattr('/sweep', 'sqrt_l1_over_g', setup%tau)
         call h5%writeattr('/sweep', 'potential_range', range)
         call h5%writeattr('/sweep', 'flip_energy_bounds', bounds)
         call h5%writeattr('/sweep', 'stop_at', stop_name(setup%opt%stop_rule))
         call h5%writeattr('/sweep', 'block', setup%block)
         call h5%writeattr('/sweep', 'initial', merge('grid', 'list', setup%grid))
         if (setup%grid) then
            call h5%writeattr('/sweep', 'axis1', c%axis1)
            call h5%writeattr('/sweep', 'axis2', c%axis2)
         end if
      end associate
      call h5%take_error(error)
   end subroutine create_layout

   !> Units and description of dataset `name` of a sweep of a model without flips
   !> (the elastic pendulum), from the model's coordinates: q_k and w_k, the axes and
   !> the initial states in the model's units; the energy error in its energy_scale.
   !> Other names keep what `dataset_info` gave.
   subroutine model_dataset_info(setup, name, units, text)
      type(sweep_setup_t), intent(in) :: setup                  !! setup, flips false
      character(len=*), intent(in) :: name                      !! dataset below /sweep
      character(len=:), allocatable, intent(inout) :: units     !! SI units
      character(len=:), allocatable, intent(inout) :: text      !! one-line description
      character(len=:), allocatable :: cname, cunits, punits, all_names, all_units
      integer :: k, n, var
      n = setup%links
      k = 0
      if (index(name, 'final/') == 1) then
         read (name(8:), *) k
         if (name(7:7) == 'w') k = n + k
      end if
      select case (name)
      case ('energy0')
         units = 'J'; text = 'initial energy E(0) ('//setup%cfg%run%model%energy_text()//')'
      case ('energy_error')
         units = '1'; text = 'max |E(t) - E(0)| / energy_scale(E(0)) of the model (NaN: ' &
                             //'not finite)'
      case ('status')
         units = '1'; text = '0 not computed, 1 integrated to t_end, 4 a step was not finite'
      case ('axis1', 'axis2')
         var = setup%var1
         if (name == 'axis2') var = setup%var2
         call state_info(var, units, cname)
         text = 'grid values on '//name(1:4)//' '//name(5:5)//': initial '//cname
      case ('initial')
         all_names = ''; all_units = ''
         do var = 1, 2*n
            call state_info(var, cunits, cname)
            all_names = all_names//merge(', ', '  ', var > 1)//cname
            all_units = all_units//merge(', ', '  ', var > 1)//cunits
         end do
         units = all_units(3:); text = 'initial states ('//all_names(3:)//')'
      case default
         if (k > 0) then
            call state_info(k, units, cname)
            text = cname//' at t_stop'
         end if
      end select
   contains
      !> Units and name of state component var: q_k = its coordinate, w_k its rate.
      subroutine state_info(var, u, nm)
         integer, intent(in) :: var
         character(len=:), allocatable, intent(out) :: u, nm
         if (var <= n) then
            call setup%cfg%run%model%coordinate(var, nm, u, punits)
         else
            call setup%cfg%run%model%coordinate(var - n, nm, u, punits)
            nm = nm//'dot'; u = u//'/s'
         end if
      end subroutine state_info
   end subroutine model_dataset_info

   !> The /sweep attributes of a model without flips: the model, its parameters by
   !> name, the fixed initial values, the step and the end time, the natural time unit
   !> √(l0/g) [s], the stop rule, the blocks and the axes (no flip bounds).
   subroutine model_attributes(h5, setup, final)
      type(h5file_t), intent(inout) :: h5        !! open file (keeps the first failure)
      type(sweep_setup_t), intent(in) :: setup   !! setup, flips false
      logical, intent(in) :: final               !! the final file (complete)
      character(len=:), allocatable :: name, units
      real(dp) :: x
      integer :: i
      associate (c => setup%cfg)
         call h5%writeattr('/', 'program', 'dpend sweep')
         call h5%writeattr('/', 'version', version)
         call h5%writeattr('/', 'method', c%run%method)
         call h5%writeattr('/sweep', 'config', setup%config)
         call h5%writeattr('/sweep', 'complete', merge(1, 0, final))
         call h5%writeattr('/sweep', 'model', c%run%spec%model_name())
         do i = 1, c%run%model%n_parameters()
            call c%run%model%parameter(i, name, x, units)
            call h5%writeattr('/sweep', name, x)
         end do
         call h5%writeattr('/sweep', 'q0', c%run%q0())
         call h5%writeattr('/sweep', 'qdot0', c%run%w0())
         call h5%writeattr('/sweep', 'h', setup%opt%h)
         call h5%writeattr('/sweep', 't_end', setup%opt%h*setup%opt%n_steps)
         call h5%writeattr('/sweep', 'n_steps', setup%opt%n_steps)
         call h5%writeattr('/sweep', 'sqrt_l0_over_g', setup%tau)
         call h5%writeattr('/sweep', 'stop_at', stop_name(setup%opt%stop_rule))
         call h5%writeattr('/sweep', 'block', setup%block)
         call h5%writeattr('/sweep', 'initial', merge('grid', 'list', setup%grid))
         if (setup%grid) then
            call h5%writeattr('/sweep', 'axis1', c%axis1)
            call h5%writeattr('/sweep', 'axis2', c%axis2)
         end if
      end associate
   end subroutine model_attributes

   !> Write the results of block b, flush, then flag it done and flush again.
   !> `flush` false leaves out the flushes: for a file opened with MPI-IO, where a
   !> flush is collective and the independent raw-data writes of allocated,
   !> unfiltered chunks bypass HDF5's caches (they reach the file, in order, before
   !> the write returns).
   subroutine write_block(h5, setup, b, res, error, flush)
      type(h5file_t), intent(inout) :: h5               !! open working file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: b                          !! block, 1-based
      type(batch_result_t), intent(in) :: res           !! its results
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      logical, intent(in), optional :: flush            !! flush the file (default true)
      real(dp), allocatable :: p(:, :)
      integer :: j0, nb, i
      logical :: sync
      sync = .true.
      if (present(flush)) sync = flush
      call block_range(setup, b, j0, nb)
      if (setup%flips) call put_r('t_flip', res%t_flip)
      if (.not. setup%flips) then
      else if (setup%links == 2) then
         call put_r('t_flip1', res%t_flip1)
         call put_r('t_flip2', res%t_flip2)
      else
         do i = 1, setup%links
            call put_r('t_flip'//to_str(i), res%t_flip_link(i, :))
         end do
      end if
      call put_r('energy0', res%energy0)
      call put_r('energy_error', res%energy_error)
      call put_r('t_stop', res%t_stop)
      do i = 1, setup%links
         call put_r('final/q'//to_str(i), res%final(i, :))
      end do
      do i = 1, setup%links
         call put_r('final/w'//to_str(i), res%final(setup%links + i, :))
      end do
      if (setup%cfg%lyapunov) call put_r('lyapunov', res%lyapunov)
      select case (setup%cfg%indicator)
      case ('megno')
         call put_r('megno', res%megno)
         call put_r('megno_y', res%megno_y)
      case ('fli'); call put_r('fli', res%fli)
      case ('sali'); call put_r('sali', res%sali)
      case ('gali2'); call put_r('gali2', res%gali2)
      end select
      if (parameter_axes(setup)) then
         call block_parameters(setup, b, p)
         call put_r('param/m1', p(1, :))
         call put_r('param/m2', p(2, :))
         call put_r('param/l1', p(3, :))
         call put_r('param/l2', p(4, :))
      end if
      call put_i('status', res%status)
      if (setup%cfg%stats) call put_i('steps', res%steps)
      if (allocated(error)) return
      if (sync) call h5%flush()
      call h5%write_slab('/sweep/done', [1], [b], error)
      if (allocated(error)) return
      if (sync) call h5%flush()
   contains
      ! each block is whole chunks: a chunk torn by a kill during its write (its
      ! block not flagged done) is replaced without its old checksum being checked
      subroutine put_r(name, v)
         character(len=*), intent(in) :: name
         real(dp), intent(in) :: v(:)
         real(dp), allocatable :: a2(:, :), a1(:)
         if (allocated(error)) return
         if (setup%grid) then
            a2 = reshape(v, [setup%cfg%n1, nb/setup%cfg%n1])
            call h5%write_slab('/sweep/'//name, a2, [1, (j0 - 1)/setup%cfg%n1 + 1], error, &
                               whole_chunks=.true.)
         else
            a1 = v   ! contiguous copy
            call h5%write_slab('/sweep/'//name, a1, [j0], error, whole_chunks=.true.)
         end if
      end subroutine put_r
      subroutine put_i(name, v)
         character(len=*), intent(in) :: name
         integer, intent(in) :: v(:)
         integer, allocatable :: a2(:, :), a1(:)
         if (allocated(error)) return
         if (setup%grid) then
            a2 = reshape(v, [setup%cfg%n1, nb/setup%cfg%n1])
            call h5%write_slab('/sweep/'//name, a2, [1, (j0 - 1)/setup%cfg%n1 + 1], error, &
                               whole_chunks=.true.)
         else
            a1 = v   ! contiguous copy
            call h5%write_slab('/sweep/'//name, a1, [j0], error, whole_chunks=.true.)
         end if
      end subroutine put_i
   end subroutine write_block

   !> The working file of the sweep whose output is `output`: FILE.part.
   pure function working_file(output) result(path)
      character(len=*), intent(in) :: output  !! the output file
      character(len=:), allocatable :: path
      path = output//'.part'
   end function working_file

   !> Rewrite the complete working file of `filename` with compressed chunks into
   !> `filename` (through the one writer), then remove the working file.
   subroutine finalize_file(filename, setup, error)
      character(len=*), intent(in) :: filename          !! the output file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      type(h5file_t) :: src, dst
      type(output_t) :: out
      character(len=32), allocatable :: reals(:), ints(:)
      character(len=:), allocatable :: path, part
      real(dp), allocatable :: r1(:), r2(:, :)
      integer, allocatable :: i1(:), i2(:, :)
      integer :: k, err
      logical :: unreadable
      unreadable = .false.
      part = working_file(filename)
      call out%begin(filename, setup%cfg%run%force, error)
      if (allocated(error)) return
      call src%open(part, 'r', error)
      if (allocated(error)) then
         call out%discard()
         return
      end if
      call create_layout(dst, out%temp, setup, .true., error)
      call result_names(setup, reals, ints)
      do k = 1, size(reals)
         if (allocated(error)) exit
         path = '/sweep/'//trim(reals(k))
         if (setup%grid) then
            call src%read(path, r2, error)
            unreadable = unreadable .or. allocated(error)
            if (.not. allocated(error)) call dst%write_slab(path, r2, [1, 1], error)
         else
            call src%read(path, r1, error)
            unreadable = unreadable .or. allocated(error)
            if (.not. allocated(error)) call dst%write_slab(path, r1, [1], error)
         end if
      end do
      do k = 1, size(ints)
         if (allocated(error)) exit
         path = '/sweep/'//trim(ints(k))
         if (setup%grid) then
            call src%read(path, i2, error)
            unreadable = unreadable .or. allocated(error)
            if (.not. allocated(error)) call dst%write_slab(path, i2, [1, 1], error)
         else
            call src%read(path, i1, error)
            unreadable = unreadable .or. allocated(error)
            if (.not. allocated(error)) call dst%write_slab(path, i1, [1], error)
         end if
      end do
      call src%close()
      call install_file(dst, out, setup, error)
      if (unreadable) then
         ! a checksum failed: nothing was installed and the working file is damaged
         error%message = "'"//part//"' is damaged: "//error%message// &
                         ' (a checksum does not match); use --force to start again'
         return
      else if (allocated(error)) then
         error%message = 'cannot write the final file: '//error%message// &
                         "; the working file '"//part//"' is complete and valid: "// &
                         'rerun to finish'
         return
      end if
      err = remove_file(part)
   end subroutine finalize_file

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
      call open_output(setup, h5, done, complete, error)
      if (allocated(error)) return
      summary%blocks_before = count(done == 1)
      if (complete == 1) then
         call h5%close()
         return
      end if

      missing = pack([(b, b=1, setup%nblocks)], done /= 1)
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
         !$omp atomic read
         stop_now = failed
         if (stop_now) return
         call compute_block(setup, bb, res)
         call block_range(setup, bb, jj0, nnb)
         !$omp critical (dpend_sweep_io)
         if (.not. failed) then
            call write_block(h5, setup, bb, res, werr)
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

   !> Open the working file for writing: resume FILE.part of the same configuration,
   !> refuse another unless --force, else create a new working file. A complete FILE
   !> of the same configuration needs nothing (`complete` = 1); another FILE is
   !> refused unless --force, and with --force it is replaced only at the end.
   subroutine open_output(setup, h5, done, complete, error)
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(h5file_t), intent(inout) :: h5               !! the working file, opened 'rw'
      integer, allocatable, intent(out) :: done(:)      !! block flags
      integer, intent(out) :: complete                  !! 1 if already complete
      type(error_t), allocatable, intent(out) :: error  !! refused or I/O failure
      type(output_t) :: probe, work
      character(len=:), allocatable :: file, part
      logical :: force
      file = setup%cfg%run%output
      part = working_file(file)
      force = setup%cfg%run%force
      complete = 0
      ! the output and the working file: regular files or missing, in a writable
      ! directory (a real temporary file, removed at once)
      call check_output_path(file, .true., error)
      if (.not. allocated(error)) call check_output_path(part, .true., error, &
                                                          '--output (its working file)')
      if (.not. allocated(error)) call probe%begin(file, .true., error)
      call probe%discard()
      if (allocated(error)) return
      if (path_kind(file) == path_file .and. .not. force) then
         call read_stored(file, done, complete, error)
         if (allocated(error)) return
         if (complete /= 1) then
            call fatal_error(error, "invalid --output: '"//file//"' holds an unfinished "// &
                             'sweep written by an older dpend (use --force to start again)')
         end if
         return
      end if
      if (path_kind(part) == path_file .and. .not. force) then
         call read_stored(part, done, complete, error)
         if (allocated(error)) return
         call h5%open(part, 'rw', error)
         if (allocated(error)) then
            error%message = error%message//' (use --force to start again)'
            call run_failure(error)
         end if
         if (.not. allocated(error) .and. .not. setup%checksum) call check_unfiltered()
         return
      end if
      ! a new working file, complete before it gets its name
      call work%begin(part, .true., error, '--output (its working file)')
      if (allocated(error)) return
      call create_layout(h5, work%temp, setup, .false., error)
      call install_file(h5, work, setup, error)
      if (allocated(error)) then
         error%message = 'cannot create the working file: '//error%message
         call run_failure(error)
         return
      end if
      call h5%open(part, 'rw', error)
      allocate (done(setup%nblocks))
      done = 0
   contains
      !> A program that writes blocks without filters (the MPI sweep) cannot resume a
      !> working file whose datasets carry checksums (one started by `dpend sweep`).
      subroutine check_unfiltered()
         character(len=32), allocatable :: reals(:), ints(:)
         integer :: n
         call result_names(setup, reals, ints)
         call h5%filters('/sweep/'//trim(reals(1)), n, error)
         if (allocated(error) .or. n == 0) return
         call h5%close()
         call fatal_error(error, "invalid --output: '"//part//"' was started by dpend "// &
                          'sweep, whose checksummed blocks parallel HDF5 cannot write one '// &
                          'by one: finish it with dpend sweep, or use --force to start again')
      end subroutine check_unfiltered
      !> The block flags and the completeness of an existing sweep file of this
      !> configuration; refused when it is another file or another configuration.
      subroutine read_stored(path, done, complete, error)
         character(len=*), intent(in) :: path
         integer, allocatable, intent(out) :: done(:)
         integer, intent(out) :: complete
         type(error_t), allocatable, intent(out) :: error
         type(h5file_t) :: f
         character(len=:), allocatable :: stored
         complete = 0
         if (.not. is_hdf5(path)) then
            call fatal_error(error, "invalid --output: '"//path//"' exists and is not "// &
                             'an HDF5 file (use --force to overwrite)')
            return
         end if
         call f%open(path, 'r', error)
         if (.not. allocated(error)) call f%readattr('/sweep', 'config', stored, error)
         if (allocated(error)) then
            call f%close()
            call fatal_error(error, "invalid --output: '"//path//"' exists and is not "// &
                             'a dpend sweep file (use --force to overwrite)')
            return
         end if
         if (stored /= setup%config) then
            call f%close()
            call fatal_error(error, "invalid --output: '"//path//"' holds a sweep with "// &
                             'another configuration ('//first_difference(setup%config, &
                             stored)//'); use --force to overwrite it')
            return
         end if
         call f%read('/sweep/done', done, error)
         if (.not. allocated(error)) call f%readattr('/sweep', 'complete', complete, error)
         if (allocated(error)) then
            error%message = "invalid --output: '"//path//"' is damaged ("//error%message// &
                            '); use --force to start again'
         else if (size(done) /= setup%nblocks) then
            call fatal_error(error, "invalid --output: '"//path//"' has a damaged block "// &
                             'list (use --force to start again)')
         else
            call verify_blocks(f, path, setup, done, error)
         end if
         call f%close()
      end subroutine read_stored
   end subroutine open_output

   !> Check the results of an existing sweep file before it is resumed or reported
   !> complete: every flag in /sweep/done is 0 or 1; every result dataset has the
   !> sweep's shape; every block flagged done reads back (the Fletcher-32 checksums
   !> of its chunks match; files written before checksums are read all the same)
   !> and has a status for each of its initial conditions; the chunk index of every
   !> other block reads. Those other blocks' checksums are not checked: a kill
   !> during a block's write may leave its chunks torn, and resuming rewrites them
   !> whole (`write_block`). A damaged file is refused, never finished or copied.
   subroutine verify_blocks(h5, path, setup, done, error)
      type(h5file_t), intent(inout) :: h5               !! the open file
      character(len=*), intent(in) :: path              !! its name, for messages
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: done(:)                    !! its block flags
      type(error_t), allocatable, intent(out) :: error  !! the first damage found
      character(len=32), allocatable :: reals(:), ints(:), names(:)
      integer, allocatable :: status(:), start(:), cnt(:), dims(:), want(:)
      character(len=:), allocatable :: damaged, name
      integer :: k, b, j0, nb
      damaged = "invalid --output: '"//path//"' is damaged ("
      if (any(done /= 0 .and. done /= 1)) then
         call fatal_error(error, damaged//'/sweep/done holds flags other than 0 and 1); '// &
                          'use --force to start again')
         return
      end if
      call result_names(setup, reals, ints)   ! ints(1) is the status
      if (setup%grid) then
         want = [setup%cfg%n1, setup%cfg%n2]
      else
         want = [setup%n]
      end if
      names = [reals, ints]
      do k = 1, size(names)
         name = '/sweep/'//trim(names(k))
         call h5%shape(name, dims, error)
         if (allocated(error)) then
            error%message = damaged//error%message//'); use --force to start again'
            return
         end if
         if (size(dims) /= size(want)) then
            call fatal_error(error, damaged//name//' has rank '//to_str(size(dims))// &
                             ', not '//to_str(size(want))//'); use --force to start again')
         else if (any(dims /= want)) then
            call fatal_error(error, damaged//name//' has shape '//shape_str(dims)// &
                             ', not '//shape_str(want)//'); use --force to start again')
         end if
         if (allocated(error)) return
      end do
      do b = 1, setup%nblocks
         call block_range(setup, b, j0, nb)
         if (setup%grid) then
            start = [1, (j0 - 1)/setup%cfg%n1 + 1]
            cnt = [setup%cfg%n1, nb/setup%cfg%n1]
         else
            start = [j0]
            cnt = [nb]
         end if
         do k = 1, size(ints)
            call read_block(trim(ints(k)), .false.)
            if (allocated(error)) return
            if (k == 1 .and. done(b) == 1 .and. any(status == 0)) then
               call fatal_error(error, damaged//'block '//to_str(b)//' is flagged done '// &
                                'but not written); use --force to start again')
               return
            end if
         end do
         do k = 1, size(reals)
            call read_block(trim(reals(k)), .true.)
            if (allocated(error)) return
         end do
      end do
   contains
      !> Read block b of dataset /sweep/name (integers into `status`), with its
      !> checksums checked if the block is flagged done.
      subroutine read_block(name, real_values)
         character(len=*), intent(in) :: name
         logical, intent(in) :: real_values
         real(dp), allocatable :: r1(:), r2(:, :)
         integer, allocatable :: i2(:, :)
         logical :: sums
         sums = done(b) == 1
         if (real_values .and. setup%grid) then
            call h5%read_slab('/sweep/'//name, start, cnt, r2, error, sums)
         else if (real_values) then
            call h5%read_slab('/sweep/'//name, start, cnt, r1, error, sums)
         else if (setup%grid) then
            call h5%read_slab('/sweep/'//name, start, cnt, i2, error, sums)
            if (.not. allocated(error)) status = reshape(i2, [size(i2)])
         else
            call h5%read_slab('/sweep/'//name, start, cnt, status, error, sums)
         end if
         if (.not. allocated(error)) return
         if (sums) then
            error%message = damaged//'/sweep/'//name//' does not read back in block '// &
                            to_str(b)//': a checksum does not match or its chunk index '// &
                            'is broken); use --force to start again'
         else
            error%message = damaged//'/sweep/'//name//' does not read back in block '// &
                            to_str(b)//', not yet computed: its chunk index is broken); '// &
                            'use --force to start again'
         end if
      end subroutine read_block
      !> '[n1, n2]' in Fortran order (h5py shows the reverse)
      function shape_str(d) result(text)
         integer, intent(in) :: d(:)
         character(len=:), allocatable :: text
         integer :: i
         text = '['//to_str(d(1))
         do i = 2, size(d)
            text = text//', '//to_str(d(i))
         end do
         text = text//']'
      end function shape_str
   end subroutine verify_blocks

   !> Put a freshly written file in place: close it (the close checked unless an
   !> error is already set), verify it, and commit it through the one writer; on
   !> any failure the temporary file is removed and the target is as it was.
   subroutine install_file(h5, out, setup, error)
      type(h5file_t), intent(inout) :: h5                 !! the new file, open on out%temp
      type(output_t), intent(inout) :: out                !! its output
      type(sweep_setup_t), intent(in) :: setup            !! setup, for the check
      type(error_t), allocatable, intent(inout) :: error  !! set on entry or by a step
      if (allocated(error)) then
         call h5%close()
      else
         call h5%close(error)
      end if
      if (.not. allocated(error)) call verify_file(out%temp, setup, error)
      if (.not. allocated(error)) call out%commit(error)
      call out%explain(error)
      call out%discard()
   end subroutine install_file

   !> Check that a freshly written file opens and holds this configuration.
   subroutine verify_file(filename, setup, error)
      character(len=*), intent(in) :: filename          !! file to check
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(error_t), allocatable, intent(out) :: error  !! unreadable
      type(h5file_t) :: h5
      character(len=:), allocatable :: stored
      integer, allocatable :: done(:)
      call h5%open(filename, 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'config', stored, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      call h5%close()
      if (allocated(error)) return
      if (stored /= setup%config .or. size(done) /= setup%nblocks) &
         call fatal_error(error, "'"//filename//"' did not read back as written")
   end subroutine verify_file

   !> "key: a here, b in the file" for the first line where two configurations differ.
   function first_difference(new, old) result(s)
      character(len=*), intent(in) :: new, old  !! configuration texts
      character(len=:), allocatable :: s
      character(len=:), allocatable :: a, b, ra, rb
      integer :: ia, ib
      character(len=1), parameter :: nl = new_line('a')
      ra = new//nl
      rb = old//nl
      do
         ia = index(ra, nl)
         ib = index(rb, nl)
         if (ia == 0 .or. ib == 0) exit
         a = ra(:ia - 1)
         b = rb(:ib - 1)
         if (a /= b) then
            s = readable(a)//' here, '//readable(b)//' in the file'
            return
         end if
         ra = ra(ia + 1:)
         rb = rb(ib + 1:)
      end do
      s = 'the configurations differ'
   contains
      !> 'key = value' with a stored real (es24.16e3, kept so that older files still
      !> compare equal) shown as real_str shows it: 't_end = 6'.
      function readable(line) result(t)
         character(len=*), intent(in) :: line
         character(len=:), allocatable :: t
         real(dp) :: x
         integer :: eq, stat, comma
         character(len=:), allocatable :: rest, u
         t = line
         eq = index(line, ' = ')
         if (eq == 0) return
         if (index(line(eq + 3:), 'E') == 0) return
         if (verify(trim(line(eq + 3:)), '0123456789.E+-, ') /= 0) return
         ! one real, or a list of reals 'a, b, c' (N links: m, l, q, w)
         rest = line(eq + 3:)
         u = ''
         do
            comma = index(rest, ',')
            if (comma == 0) comma = len(rest) + 1
            read (rest(:comma - 1), *, iostat=stat) x
            if (stat /= 0) return
            u = u//real_str(x)
            if (comma > len(rest)) exit
            u = u//', '
            rest = rest(comma + 1:)
         end do
         t = line(:eq + 2)//u
      end function readable
   end function first_difference

   ! ----------------------------------------------------------- compare ---

   !> Accuracy report: compare the flip times of two complete sweeps of the same
   !> initial conditions (e.g. step dt and dt/2). A pixel changes if it flips in one
   !> and not the other, or if |t_B - t_A| > rel t_A. Prints `key: value unit` lines.
   !> Sweeps that are not comparable (grid or list, shape, axes, ranges, initial
   !> states, parameters, time unit, t_end, stop rule) or not complete are refused,
   !> naming what differs, as are damaged values (a time unit sqrt(l1/g) or flip
   !> times that are not finite and in range).
   subroutine compare_sweeps(file_a, file_b, rel, unit, error)
      character(len=*), intent(in) :: file_a, file_b    !! the two sweeps
      real(dp), intent(in) :: rel                       !! relative tolerance
      integer, intent(in) :: unit                       !! where to print
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      type(h5file_t) :: h5
      real(dp), allocatable :: ta(:), tb(:)
      real(dp) :: tau, tau_b, ha, hb, bands(5)
      integer, allocatable :: sa(:), dims_a(:), dims_b(:)
      character(len=:), allocatable :: cfg_a, cfg_b, va, vb
      integer :: i, k, n_changed, n_flip, band_n(4), band_c(4), n_noflip_changed
      logical :: fa, fb, changed, in_band
      character(len=*), parameter :: band_names(4) = [character(len=12) :: 'lt_10', &
                                                      '10_to_100', '100_to_1000', 'ge_1000']
      ! what must be equal for two sweeps to hold the same initial conditions
      character(len=*), parameter :: same(*) = [character(len=10) :: 'initial', 'axis1', &
         'axis2', 'n1', 'n2', 'min1', 'max1', 'min2', 'max2', 'ic_count', 'ic_hash', 'q1', &
         'q2', 'w1', 'w2', 'm1', 'm2', 'l1', 'l2', 'g', 'time_unit', 't_end', 'stop_at', &
         'links', 'm', 'l', 'q', 'w']
      if (.not. (rel > 0.0_dp .and. rel <= max_rel)) then
         call fatal_error(error, 'sweep-compare: invalid --rel: '//sci(rel)// &
                          ' (accepted: > 0 and <= 1000)')
         return
      end if
      call read_times(file_a, ta, sa, tau, ha, dims_a, cfg_a, error)
      if (allocated(error)) return
      call read_times(file_b, tb, sa, tau_b, hb, dims_b, cfg_b, error)
      if (allocated(error)) return
      do k = 1, size(same)
         va = config_value(cfg_a, trim(same(k)))
         vb = config_value(cfg_b, trim(same(k)))
         if (va /= vb) then
            call refuse(trim(same(k))//' = '//va//" in '"//file_a//"', "//vb//" in '"// &
                        file_b//"'")
            return
         end if
         if (same(k) == 'initial') then   ! then the shapes, in the file's terms
            if (size(dims_a) /= size(dims_b)) then
               call refuse('t_flip has shape '//shape_text(dims_a)//" in '"//file_a// &
                           "', "//shape_text(dims_b)//" in '"//file_b//"'")
            else if (any(dims_a /= dims_b)) then
               call refuse('t_flip has shape '//shape_text(dims_a)//" in '"//file_a// &
                           "', "//shape_text(dims_b)//" in '"//file_b//"'")
            end if
            if (allocated(error)) return
         end if
      end do
      if (abs(tau - tau_b) > 1e-12_dp*tau) then
         call refuse('sqrt_l1_over_g = '//sci(tau)//" s in '"//file_a//"', "// &
                     sci(tau_b)//" s in '"//file_b//"' (another time unit)")
         return
      end if
      bands = [0.0_dp, 10.0_dp, 100.0_dp, 1000.0_dp, huge(1.0_dp)]
      n_changed = 0; n_flip = 0; band_n = 0; band_c = 0; n_noflip_changed = 0
      do i = 1, size(ta)
         fa = .not. ieee_is_nan(ta(i))
         fb = .not. ieee_is_nan(tb(i))
         if (fa .and. fb) then
            changed = abs(tb(i) - ta(i)) > rel*abs(ta(i))
         else
            changed = fa .neqv. fb
         end if
         if (fa .or. fb) n_flip = n_flip + 1
         if (changed) n_changed = n_changed + 1
         if (fa) then
            do k = 1, 4
               ! t/tau in [bands(k), bands(k+1)), without dividing by tau
               in_band = ta(i) >= bands(k)*tau
               if (k < 4) in_band = in_band .and. ta(i) < bands(k + 1)*tau
               if (in_band) then
                  band_n(k) = band_n(k) + 1
                  if (changed) band_c(k) = band_c(k) + 1
               end if
            end do
         else if (changed) then
            n_noflip_changed = n_noflip_changed + 1
         end if
      end do
      write (unit, '(a)') 'step_a: '//real_str(ha, 6)//' s'
      write (unit, '(a)') 'step_b: '//real_str(hb, 6)//' s'
      write (unit, '(a)') 'relative_tolerance: '//real_str(rel)
      write (unit, '(a, i0)') 'pixels: ', size(ta)
      write (unit, '(a, i0)') 'pixels_flipping: ', n_flip
      write (unit, '(a, i0)') 'pixels_changed: ', n_changed
      write (unit, '(a)') 'changed_fraction: '//pct(n_changed, size(ta))//' %'
      write (unit, '(a)') 'changed_fraction_of_flipping: '//pct(n_changed, n_flip)//' %'
      do k = 1, 4
         write (unit, '(a, i0, a)') 'changed_fraction_tflip_'//trim(band_names(k))// &
            ': '//pct(band_c(k), band_n(k))//' % (of ', band_n(k), ' pixels)'
      end do
      write (unit, '(a, i0)') 'pixels_changed_no_flip_in_a: ', n_noflip_changed
   contains
      !> 100 a/b rounded to 3 decimals ('0' when b = 0).
      function pct(a, b) result(t)
         integer, intent(in) :: a, b
         character(len=:), allocatable :: t
         t = '0'
         if (b > 0) t = real_str(anint(1e5_dp*real(a, dp)/real(b, dp))/1e3_dp)
      end function pct
      subroutine refuse(what)
         character(len=*), intent(in) :: what
         call fatal_error(error, 'sweep-compare: invalid pair of sweeps, not comparable: '// &
                          what//' (compare sweeps of the same initial conditions)')
      end subroutine refuse
      function shape_text(d) result(s)
         integer, intent(in) :: d(:)
         character(len=:), allocatable :: s
         integer :: j
         s = to_str(d(1))
         do j = 2, size(d)
            s = s//'x'//to_str(d(j))
         end do
         if (size(d) == 1) s = s//' (a list)'
      end function shape_text
      subroutine read_times(file, t, st, tau, h, dims, config, error)
         character(len=*), intent(in) :: file
         real(dp), allocatable, intent(out) :: t(:)
         integer, allocatable, intent(out) :: st(:)
         real(dp), intent(out) :: tau, h
         integer, allocatable, intent(out) :: dims(:)
         character(len=:), allocatable, intent(out) :: config
         type(error_t), allocatable, intent(out) :: error
         real(dp), allocatable :: t2(:, :)
         integer, allocatable :: s2(:, :), done(:)
         integer :: complete, j
         character(len=:), allocatable :: pre
         pre = "sweep-compare: invalid sweep '"//file//"': "
         tau = 1; h = 0; complete = 0
         call open_sweep_file(file, pre, h5, config, error)
         if (allocated(error)) return
         call check_sweep_data(h5, pre, config, '/sweep/t_flip', dims, error)
         if (allocated(error)) then
            call h5%close()
            return
         end if
         call h5%readattr('/sweep', 'complete', complete, error)
         if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
         if (.not. allocated(error)) then
            if (size(dims) == 2) then
               call h5%read('/sweep/t_flip', t2, error)
               if (.not. allocated(error)) call h5%read('/sweep/status', s2, error)
               if (.not. allocated(error)) t = reshape(t2, [size(t2)])
               if (.not. allocated(error)) st = reshape(s2, [size(s2)])
            else
               call h5%read('/sweep/t_flip', t, error)
               if (.not. allocated(error)) call h5%read('/sweep/status', st, error)
            end if
         end if
         if (.not. allocated(error)) call h5%readattr('/sweep', 'sqrt_l1_over_g', tau, error)
         if (.not. allocated(error)) call h5%readattr('/sweep', 'h', h, error)
         call h5%close()
         if (allocated(error)) then
            error%message = pre//error%message
         else if (complete /= 1 .or. any(done /= 1) .or. any(st == 0)) then
            call fatal_error(error, pre//'not complete ('//to_str(count(done == 1))// &
                             ' of '//to_str(size(done))//' blocks done; rerun the sweep '// &
                             'to finish it)')
         else if (size(st) /= size(t)) then
            call fatal_error(error, pre//'damaged: /sweep/status and /sweep/t_flip '// &
                             'differ in size')
         else if (.not. tau_ok(tau)) then
            call fatal_error(error, pre//'damaged: attribute sqrt_l1_over_g = '// &
                             sci(tau)//' (accepted: 1e-150 to 1e150 s)')
         else
            do j = 1, size(t)   ! element by element: an ordered comparison with NaN traps
               ! the status says whether the pixel flipped: t_flip agrees with it
               if ((st(j) == st_flipped .and. ieee_is_nan(t(j))) .or. &
                   (st(j) == st_cannot_flip .and. .not. ieee_is_nan(t(j)))) then
                  call fatal_error(error, pre//'damaged: /sweep/t_flip at pixel '// &
                                   to_str(j)//' disagrees with its status '//to_str(st(j))// &
                                   ' (2: flipped, a time; 3: cannot flip, NaN)')
                  exit
               end if
               if (ieee_is_nan(t(j))) cycle
               if (.not. (ieee_is_finite(t(j)) .and. abs(t(j)) <= max_time)) then
                  call fatal_error(error, pre//'damaged: /sweep/t_flip holds '// &
                                   sci(t(j))//' (accepted: NaN or finite, |t| <= 1e300 s)')
                  exit
               end if
            end do
         end if
      end subroutine read_times
      !> Finite and in [min_tau, max_tau] (no ordered comparison with NaN: it traps).
      logical function tau_ok(x)
         real(dp), intent(in) :: x
         tau_ok = .false.
         if (ieee_is_finite(x)) tau_ok = x >= min_tau .and. x <= max_tau
      end function tau_ok
   end subroutine compare_sweeps

   !> Open an existing sweep file for reading and read its /sweep config attribute;
   !> refused (with `pre` before the reason, h5 closed) unless it is a regular HDF5
   !> file with that attribute. Shared by sweep-compare and --agreement.
   subroutine open_sweep_file(file, pre, h5, config, error)
      character(len=*), intent(in) :: file                 !! the file
      character(len=*), intent(in) :: pre                  !! message prefix
      type(h5file_t), intent(inout) :: h5                  !! opened on success
      character(len=:), allocatable, intent(out) :: config !! /sweep@config
      type(error_t), allocatable, intent(out) :: error     !! refused
      call check_regular_file(file, pre, error)
      if (allocated(error)) return
      if (.not. is_hdf5(file)) then
         call fatal_error(error, pre//'not an HDF5 file')
         return
      end if
      call h5%open(file, 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'config', config, error)
      if (allocated(error)) then
         call h5%close()
         call fatal_error(error, pre//'not a dpend sweep file (no /sweep config)')
      end if
   end subroutine open_sweep_file

   !> Check the data of a sweep file from elsewhere against what sweep-compare
   !> assumes, not only its config attribute (`pre` before the reason): the grid
   !> (n1 × n2 with 1-D axes axis1, axis2 of n1 and n2 finite values) or list
   !> (ic_count points) that the config names, with `ref` (t_flip or an indicator)
   !> and status of that shape; status values 1 to 4 (0: not computed, left to the
   !> caller's completeness check); the attributes a sweep writes within its ranges:
   !> links 1..32 (and the config's links, if any), t_end finite within [0, 1e9] s
   !> (also in the config), h finite within (0, 1e9] s. `dims` is the shape of `ref`
   !> (Fortran order). The file stays open.
   subroutine check_sweep_data(h5, pre, config, ref, dims, error)
      type(h5file_t), intent(inout) :: h5               !! the open sweep file
      character(len=*), intent(in) :: pre               !! message prefix
      character(len=*), intent(in) :: config            !! its /sweep config attribute
      character(len=*), intent(in) :: ref               !! the dataset compared
      integer, allocatable, intent(out) :: dims(:)      !! shape of `ref`
      type(error_t), allocatable, intent(out) :: error  !! damaged
      integer, allocatable :: d(:), st(:), st2(:, :), want(:)
      real(dp), allocatable :: ax(:)
      real(dp) :: x
      integer :: n1, n2, links, k
      character(len=:), allocatable :: initial
      logical :: ok
      character(len=2), parameter :: axes(2) = ['1', '2']
      call h5%shape(ref, dims, error)
      if (allocated(error)) then
         error%message = pre//error%message
         return
      end if
      initial = config_value(config, 'initial')
      select case (initial)
      case ('grid')
         call config_int('n1', max_axis_points, n1, ok)
         if (ok) call config_int('n2', max_axis_points, n2, ok)
         if (.not. ok) return
         want = [n1, n2]
         do k = 1, 2
            call h5%shape('/sweep/axis'//trim(axes(k)), d, error)
            if (allocated(error)) then
               error%message = pre//'damaged: '//error%message
               return
            end if
            if (size(d) /= 1) then
               call damaged('/sweep/axis'//trim(axes(k))//' is not 1-D')
               return
            else if (d(1) /= want(k)) then
               call damaged('/sweep/axis'//trim(axes(k))//' has '//to_str(d(1))// &
                            ' values, the config n'//trim(axes(k))//' = '//to_str(want(k)))
               return
            end if
            call h5%read('/sweep/axis'//trim(axes(k)), ax, error)
            if (allocated(error)) then
               error%message = pre//'damaged: '//error%message
               return
            end if
            if (.not. all(ieee_is_finite(ax))) then
               call damaged('/sweep/axis'//trim(axes(k))//' holds values that are not finite')
               return
            end if
         end do
      case ('list')
         call config_int('ic_count', max_sweep_points, n1, ok)
         if (.not. ok) return
         want = [n1]
      case default
         call damaged("config initial = '"//initial//"' (a sweep writes grid or list)")
         return
      end select
      if (size(dims) /= size(want)) then
         call damaged(ref//' has rank '//to_str(size(dims))//', the config '//initial// &
                      ' gives rank '//to_str(size(want)))
         return
      else if (any(dims /= want)) then
         call damaged(ref//' does not have the shape of the config '//initial)
         return
      end if
      call h5%shape('/sweep/status', d, error)
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (size(d) /= size(dims)) then
         call damaged('/sweep/status does not have the shape of '//ref)
         return
      else if (any(d /= dims)) then
         call damaged('/sweep/status does not have the shape of '//ref)
         return
      end if
      if (size(dims) == 2) then
         call h5%read('/sweep/status', st2, error)
         if (.not. allocated(error)) st = reshape(st2, [size(st2)])
      else
         call h5%read('/sweep/status', st, error)
      end if
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (any(st < 0 .or. st > 4)) then
         call damaged('/sweep/status holds '//to_str(minval(st, st < 0 .or. st > 4))// &
                      ' (a sweep writes 0 to 4)')
         return
      end if
      links = 2
      if (h5%attr_exists('/sweep', 'links')) call h5%readattr('/sweep', 'links', links, error)
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (links < 1 .or. links > max_dof) then
         call damaged('attribute links = '//to_str(links)//' (a sweep writes 1 to '// &
                      to_str(max_dof)//')')
         return
      end if
      if (len(config_value(config, 'links')) > 0) then
         if (config_value(config, 'links') /= to_str(links)) then
            call damaged('config links = '//config_value(config, 'links')// &
                         ', attribute links = '//to_str(links))
            return
         end if
      end if
      call real_attr('t_end', 0.0_dp, max_run_time, .true.)
      if (.not. allocated(error)) call real_attr('h', tiny(1.0_dp), max_run_time, .true.)
      if (allocated(error)) return
      x = config_real('t_end')
      if (allocated(error)) return
      if (.not. in_range(x, 0.0_dp, max_run_time)) &
         call damaged('config t_end = '//config_value(config, 't_end')// &
                      ' (a sweep writes 0 to 1e9)')
   contains
      subroutine damaged(why)
         character(len=*), intent(in) :: why
         call fatal_error(error, pre//'damaged: '//why)
      end subroutine damaged
      !> A count of the config in [1, hi]; refused otherwise.
      subroutine config_int(key, hi, n, good)
         character(len=*), intent(in) :: key
         integer, intent(in) :: hi
         integer, intent(out) :: n
         logical, intent(out) :: good
         character(len=:), allocatable :: v
         integer :: stat
         n = 0
         v = config_value(config, key)
         good = len(v) > 0 .and. len(v) <= 10 .and. verify(v, '0123456789') == 0
         if (good) then
            read (v, *, iostat=stat) n
            good = stat == 0 .and. n >= 1 .and. n <= hi
         end if
         if (.not. good) call damaged('config '//key//" = '"//v//"' (a sweep writes 1 to "// &
                                      to_str(hi)//')')
      end subroutine config_int
      !> A real of the config (NaN when it is not a number).
      real(dp) function config_real(key) result(v)
         character(len=*), intent(in) :: key
         integer :: stat
         character(len=:), allocatable :: text
         text = config_value(config, key)
         v = ieee_value(v, ieee_quiet_nan)
         if (len(text) == 0 .or. len(text) > 40 .or. &
             verify(text, '0123456789+-.eE') /= 0) return
         read (text, *, iostat=stat) v
         if (stat /= 0) v = ieee_value(v, ieee_quiet_nan)
      end function config_real
      !> The scalar real attribute `name` of /sweep, finite within [lo, hi].
      subroutine real_attr(name, lo, hi, required)
         character(len=*), intent(in) :: name
         real(dp), intent(in) :: lo, hi
         logical, intent(in) :: required
         real(dp) :: v
         if (.not. required .and. .not. h5%attr_exists('/sweep', name)) return
         call h5%readattr('/sweep', name, v, error)
         if (allocated(error)) then
            error%message = pre//'damaged: '//error%message
            return
         end if
         if (.not. in_range(v, lo, hi)) &
            call damaged('attribute '//name//' = '//sci(v)//' s (a sweep writes '// &
                         trim(merge('0 to   ', 'above 0', lo <= 0.0_dp))//' ... '// &
                         sci(hi)//' s)')
      end subroutine real_attr
   end subroutine check_sweep_data

   !> The value of `key` in a configuration text of "key = value" lines ('' if absent).
   function config_value(text, key) result(v)
      character(len=*), intent(in) :: text  !! configuration text
      character(len=*), intent(in) :: key   !! key
      character(len=:), allocatable :: v
      character(len=1), parameter :: nl = new_line('a')
      character(len=:), allocatable :: probe
      integer :: at, eol
      v = ''
      probe = nl//text
      at = index(probe, nl//key//' = ')
      if (at == 0) return
      at = at + len(key) + 4
      eol = index(probe(at:), nl)
      if (eol == 0) then
         v = probe(at:)
      else
         v = probe(at:at + eol - 2)
      end if
   end function config_value


end module dpend_sweep
