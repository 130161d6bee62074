!> The sweep engine's setup (docs/sweep.md): everything derived from a validated
!> configuration that the blocks need (`build_setup`: the step, the axes or the list
!> of initial conditions, the blocks, the canonical configuration text stored in the
!> file), the initial states and parameters of a block, and the closing line.
module dpend_sweep_setup
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_limits, only: sci, max_sweep_points, max_angle, max_angular_velocity
   use dpend_kinds, only: dp, i8, half_pi
   use dpend_error, only: error_t, fatal_error
   use dpend_output, only: check_regular_file
   use dpend_lane_batch, only: batch_options_t
   use dpend_sweep_settings, only: sweep_config_t, time_scale, stop_rule, grid_mode, &
      indicator_vectors, axis_parameter, pixel_parameters, flip_model, sweep_variable, &
      natural_time, model_axis, pendulum_param_names, pendulum_param_values, pendulum_axis, &
      kernel_pendulum
   use dpend_integrator, only: integrator_t
   use dpend_joint_torque, only: joint_torque_t
   use dpend_methods, only: new_integrator
   use dpend_chain_lanes, only: chain_kernel_choice
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_version, only: version
   use dpend_cli, only: to_str, real_str, seconds_str, printable
   use dpend_parse, only: read_real, quoted
   implicit none
   private
   public :: sweep_setup_t, sweep_summary_t, summary_text, build_setup, block_range, &
      block_initial_conditions, parameter_axes, block_parameters, stop_name, parameter_names
   public :: named_parameter, named_axes, block_share_note, mass_length_or_g

   !> The code of a parameter axis by name (a model without flips: its parameters;
   !> the pendulum: those of `pendulum_axis`, beside the axes coded 1 to 6 by
   !> `axis_parameter`).
   integer, parameter :: named_parameter = 7

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
      ! the chain lanes: flip maps of 3 to 8 links through dpend_chain_lanes
      logical :: chain_lanes = .false.  !! the blocks go through the chain lanes
      !> axis 1, axis 2 sweeps a parameter of the pendulum by name (com1, g, ...)
      logical :: named1 = .false., named2 = .false.
      !> the names of `block_parameters`' rows, set once by build_setup (no call in
      !> the blocks' threads of what gfortran 12 keeps in static lengths: "Threads")
      character(len=32), allocatable :: param_names(:)
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
      !> those below the bound are integrated all the same (an indicator, lambda1)
      logical :: bound_integrated = .false.
      !> no flip bound holds: a moving support or torques feed energy
      logical :: energy_fed = .false.
   end type sweep_summary_t

contains

   !> The closing line of a run that computed something: 'N initial conditions
   !> computed (K below the flip energy bound) in 0.4 s, 1.2e5 per second'.
   function summary_text(summary) result(s)
      type(sweep_summary_t), intent(in) :: summary  !! what the run did
      character(len=:), allocatable :: s
      s = to_str(summary%computed)//' initial conditions computed'
      if (summary%flips .and. summary%energy_fed) then
         s = s//' (every one integrated: the support or the torques feed energy, so no ' &
             //'flip energy bound holds)'
      else if (summary%flips) then
         s = s//' ('//to_str(summary%skipped)//' below the flip energy bound'
         if (summary%bound_integrated .and. summary%skipped > 0) &
            s = s//': they cannot flip, integrated all the same for the map'
         s = s//')'
      end if
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
      if (cfg%device == 'auto' .or. (cfg%device == 'gpu' .and. len(cfg%device_name) == 0)) &
         then   ! a library caller's: resolve_device opens the GPU after validate_sweep
         call fatal_error(error, "invalid device: '"//cfg%device//"' is not resolved " &
                          //'(resolve_device after validate_sweep)')
         return
      end if
      setup%cfg = cfg
      setup%grid = grid_mode(cfg)
      setup%links = cfg%run%model%n_dof()   ! N links; the elastic pendulum's 2
      setup%flips = flip_model(cfg)
      setup%per_trajectory = setup%links /= 2 .or. .not. setup%flips .or. &
                             .not. kernel_pendulum(cfg)
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
         if (model_axis(cfg, cfg%axis1)) setup%par1 = named_parameter
         if (model_axis(cfg, cfg%axis2)) setup%par2 = named_parameter
         ! a pendulum map over a parameter by name: each pixel its own model
         if (named_axes(setup)) setup%per_trajectory = .true.
         if (setup%flips .and. named_axes(setup)) then
            setup%named1 = pendulum_axis(cfg, cfg%axis1)
            setup%named2 = pendulum_axis(cfg, cfg%axis2)
         end if
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
      ! the chain lanes (not for parameter maps; DPEND_SWEEP_KERNEL checked)
      call chain_kernel_choice(cfg%run%model, setup%opt, setup%chain_lanes, error)
      if (allocated(error)) return
      setup%chain_lanes = setup%chain_lanes .and. .not. parameter_axes(setup)
      setup%param_names = make_parameter_names(setup)
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
   !> Whether the blocks give each of `workers` (MPI ranks) work, and if not why they
   !> stay as they are and what would: '' when there are at least as many blocks as
   !> workers, else "1 block of 4096 pixels for 4 ranks: 3 ranks get no work; ...".
   !> The block size is part of the file's configuration (a rerun resumes only the
   !> same blocks, and the serial sweep may finish an MPI file), so it is not changed
   !> behind the user's back: the note names the --block that makes about four
   !> blocks per worker (whole rows of axis 1 in a grid), or says that the map has
   !> fewer rows than workers.
   function block_share_note(setup, workers) result(s)
      type(sweep_setup_t), intent(in) :: setup  !! setup (blocks known)
      integer, intent(in) :: workers            !! MPI ranks
      character(len=:), allocatable :: s
      integer :: units, per_unit, rows
      s = ''
      if (setup%nblocks >= workers) return
      s = to_str(setup%nblocks)//trim(merge(' block ', ' blocks', setup%nblocks == 1))// &
          ' of '//to_str(setup%block)//' pixels for '//to_str(workers)//' ranks: '// &
          to_str(workers - setup%nblocks)//merge(' rank gets', ' ranks get', &
          workers - setup%nblocks == 1)//' no work; the block size is part of ' &
          //"the file's configuration (a rerun resumes the same blocks), so it stays as "// &
          trim(merge('given  ', 'default', setup%cfg%block_given))
      if (setup%grid) then
         units = setup%cfg%n2           ! whole rows of axis 1
         per_unit = setup%cfg%n1
      else
         units = setup%n
         per_unit = 1
      end if
      if (units < workers) then
         s = s//'; the map has '//to_str(units)//trim(merge(' rows of axis 1', &
             ' pixels        ', setup%grid))//': at most that many ranks can work'
      else
         rows = max(1, units/(4*workers))   ! about four blocks per rank
         s = s//'; --block '//to_str(rows*per_unit)//' makes '// &
             to_str((units + rows - 1)/rows)//' blocks'
      end if
   end function block_share_note

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

   !> The names of the parameters of `block_parameters` (set by build_setup).
   pure function parameter_names(setup) result(names)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      character(len=32), allocatable :: names(:)
      names = setup%param_names
   end function parameter_names

   !> The names of the parameters of `block_parameters`: m1 m2 l1 l2 of a model with
   !> flips, with the pendulum's parameters by name after them; the swept parameters
   !> of another model ('' for an axis of initial values).
   function make_parameter_names(setup) result(names)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      character(len=32), allocatable :: names(:)
      if (setup%flips .and. named_axes(setup)) then
         names = pendulum_param_names(setup%cfg)
      else if (setup%flips) then
         names = [character(len=32) :: 'm1', 'm2', 'l1', 'l2']
      else
         names = [character(len=32) :: '', '']
         if (setup%par1 == named_parameter) names(1) = setup%cfg%axis1
         if (setup%par2 == named_parameter) names(2) = setup%cfg%axis2
      end if
   end function make_parameter_names

   !> True if an axis sweeps a parameter by name (`named_parameter`).
   pure logical function named_axes(setup)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      named_axes = setup%par1 == named_parameter .or. setup%par2 == named_parameter
   end function named_axes

   !> True if an axis sweeps a parameter (m1, m2, l1, l2, m2/m1, l2/l1, by name).
   pure logical function parameter_axes(setup)
      type(sweep_setup_t), intent(in) :: setup  !! setup
      parameter_axes = setup%par1 > 0 .or. setup%par2 > 0
   end function parameter_axes

   !> The parameters of the pixels of block b: (m1, m2, l1, l2) (4, nb) of a model
   !> with flips; of another model the values of its parameter axes (2, nb), 0 for
   !> an axis of initial values (`parameter_names`).
   subroutine block_parameters(setup, b, p)
      type(sweep_setup_t), intent(in) :: setup      !! setup
      integer, intent(in) :: b                      !! block, 1-based
      real(dp), allocatable, intent(out) :: p(:, :) !! (4, nb) [kg, kg, m, m] or (2, nb)
      integer :: j0, nb, j, jj, i1, i2
      call block_range(setup, b, j0, nb)
      if (.not. setup%flips) then
         allocate (p(2, nb))
         p = 0.0_dp
         do j = 1, nb
            jj = j0 + j - 1
            i1 = mod(jj - 1, setup%cfg%n1) + 1
            i2 = (jj - 1)/setup%cfg%n1 + 1
            if (setup%par1 == named_parameter) p(1, j) = setup%axis1(i1)
            if (setup%par2 == named_parameter) p(2, j) = setup%axis2(i2)
         end do
         return
      end if
      if (named_axes(setup)) then   ! the pendulum's parameters by name
         allocate (p(size(parameter_names(setup)), nb))
         do j = 1, nb
            jj = j0 + j - 1
            i1 = mod(jj - 1, setup%cfg%n1) + 1
            i2 = (jj - 1)/setup%cfg%n1 + 1
            p(:, j) = pendulum_param_values(setup%cfg, setup%named1, setup%named2, &
                                             setup%axis1(i1), setup%axis2(i2))
         end do
         return
      end if
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
         else if (setup%links == 2 .and. kernel_pendulum(c)) then
            ! two-link files of every version resume
            s = 'program = dpend '//version//nl//'command = sweep'//nl// &
                'method = '//c%run%method//nl//'kernel = '// &
                trim(merge('per trajectory', 'batch rk4     ', named_axes(setup)))//nl// &
                'm1 = '//r(p%m1)//nl//'m2 = '//r(p%m2)//nl//'l1 = '//r(p%l1)//nl// &
                'l2 = '//r(p%l2)//nl//'g = '//r(p%g)//nl// &
                'q1 = '//r(c%run%q(1))//nl//'q2 = '//r(c%run%q(2))//nl// &
                'w1 = '//r(c%run%w(1))//nl//'w2 = '//r(c%run%w(2))//nl
         else
            s = 'program = dpend '//version//nl//'command = sweep'//nl// &
                'method = '//c%run%method//nl//'kernel = '// &
                trim(merge('chain lanes   ', 'per trajectory', setup%chain_lanes))//nl// &
                'links = '//to_str(setup%links)//nl// &
                'm = '//rl(c%run%m(:setup%links))//nl//'l = '//rl(c%run%l(:setup%links))// &
                nl//'g = '//r(c%run%g)//nl//'q = '//rl(c%run%q0())//nl// &
                'w = '//rl(c%run%w0())//nl
         end if
         if (setup%flips) s = s//body_lines()   ! '' for uniform rods
         if (c%run%torque%active()) s = s//'torque = '//c%run%torque%text()//nl// &
            'torque_hash = '//to_str(torque_hash(c%run%torque))//nl
         s = s//'time_unit = '//trim(c%run%time_unit)//nl//'dt = '//r(c%run%dt)//nl// &
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
      !> A line of every parameter of the model beyond m_i, l_i and g, in its order:
      !> 'c1 = …' of the damping, the Coulomb friction, the motors, the support's motion,
      !> 'com1 = …' and 'inertia1 = …' of links other than uniform rods (a sweep of another
      !> body never resumes one of rods); none for the conservative rods.
      function body_lines() result(t)
         character(len=:), allocatable :: t, pname, units
         real(dp) :: x
         integer :: i
         t = ''
         do i = 1, setup%cfg%run%model%n_parameters()
            call setup%cfg%run%model%parameter(i, pname, x, units)
            if (.not. mass_length_or_g(pname)) t = t//pname//' = '//r(x)//nl
         end do
      end function body_lines
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

   !> The parameter is one of the pendulum's masses, lengths or g: m1, m2, …, l1, l2, …
   !> or g (of every pendulum file; the others, c1, com1, gear_ratio2, … only of some).
   pure logical function mass_length_or_g(pname)
      character(len=*), intent(in) :: pname  !! the model's name of a parameter
      mass_length_or_g = pname == 'g'
      if (len(pname) > 1) then
         if (pname(1:1) == 'm' .or. pname(1:1) == 'l') &
            mass_length_or_g = verify(pname(2:), '0123456789') == 0
      end if
   end function mass_length_or_g

   !> A hash of the applied torques' numbers (a series' times and values, a closed
   !> form's coefficients), for the resume key: two files of one configuration text
   !> but other torques never resume one another.
   pure integer(i8) function torque_hash(torque)
      type(joint_torque_t), intent(in) :: torque  !! the torques, active
      real(dp), allocatable :: v(:)
      v = [real(dp) :: real(torque%n, dp)]
      if (allocated(torque%t)) v = [v, torque%t, reshape(torque%tau, [size(torque%tau)])]
      if (allocated(torque%bias)) v = [v, torque%bias, reshape(torque%amp, [size(torque%amp)]), &
                                       torque%omega, reshape(torque%phase, [size(torque%phase)])]
      torque_hash = list_hash(reshape(v, [1, size(v)]))
   end function torque_hash

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

end module dpend_sweep_setup
