!> The sweep's file layout (docs/hdf5-layout.md): the names, units and descriptions
!> of the result datasets, the working and the final file's datasets and attributes,
!> writing one block, and the final file installed through the one writer.
module dpend_sweep_layout
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_f_pointer
   use, intrinsic :: iso_fortran_env, only: int8
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error
   use dpend_output, only: output_t
   use dpend_os, only: remove_file, reserve_space, errno_text
   use dpend_checksum, only: crc32_of
   use dpend_lane_batch, only: batch_result_t
   use dpend_pendulum_kernel, only: potential_range, flip_energy_bounds
   use dpend_sweep_settings, only: stop_rule, axis_parameter, pendulum_axis, named_axis_units
   use dpend_lane_batch, only: link_flip_bounds
   use dpend_hdf5, only: h5file_t
   use dpend_version, only: version
   use dpend_cli, only: to_str
   use dpend_sweep_gpu, only: gpu_fallback_blocks
   use dpend_model_record, only: record_torques
   use dpend_sweep_setup, only: mass_length_or_g, sweep_setup_t, block_range, parameter_axes, &
      block_parameters, parameter_names, stop_name
   implicit none
   private
   public :: result_names, create_layout, write_block, working_file, finalize_file, install_file
   public :: crc_path, block_crcs, read_crcs, block_result_crcs, block_values_t, block_values
   public :: write_values

   !> The results of one block as written: real and integer columns by name.
   type :: block_values_t
      character(len=32), allocatable :: real_names(:)  !! /sweep/ names of r's columns
      character(len=32), allocatable :: int_names(:)   !! /sweep/ names of i's columns
      real(dp), allocatable :: r(:, :)                 !! (initial conditions, results)
      integer, allocatable :: i(:, :)                  !! (initial conditions, results)
   end type block_values_t

   !> The CRC-32 of every block of a result held whole (`write_block`'s checksums).
   interface block_crcs
      module procedure block_crcs_real, block_crcs_int
   end interface block_crcs

   !> The working file's checksums: the CRC-32 of every block of every result as
   !> written (row k: the k-th of `result_names`' reals then integers; column b:
   !> block b), written with the block before its flag in /sweep/done. Its datasets
   !> carry no HDF5 filter, so that they are allocated, not written, when the file
   !> is made (a sparse file whose space `install_file` reserves).
   character(len=*), parameter :: crc_path = '/sweep/block_crc32'

   !> Values in a chunk of the final file (whole rows of a grid, at least one): the
   !> final file is written once, whole, its chunks encoded on every thread, and read
   !> by any program, so its chunks need not be blocks (the working file's are).
   integer, parameter :: final_chunk_values = 32768

contains

   ! ------------------------------------------------------------ layout ---

   !> Names of the result datasets under /sweep (reals, then integers).
   subroutine result_names(setup, reals, ints)
      type(sweep_setup_t), intent(in) :: setup                     !! setup
      character(len=32), allocatable, intent(out) :: reals(:)      !! real datasets
      character(len=32), allocatable, intent(out) :: ints(:)       !! integer datasets
      character(len=32) :: name
      character(len=32), allocatable :: names(:)
      integer :: i, k
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
      if (parameter_axes(setup)) then
         names = parameter_names(setup)
         do k = 1, size(names)
            if (len_trim(names(k)) == 0) cycle
            name = 'param/'//trim(names(k))   ! (one length in the constructor)
            reals = [reals, name]
         end do
      end if
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
      if (setup%grid) then   ! the working file: one chunk per block
         dims = [setup%cfg%n1, setup%cfg%n2]
         chunk = [setup%cfg%n1, merge(max(1, final_chunk_values/setup%cfg%n1), setup%rows, final)]
      else
         dims = [setup%n]
         chunk = [merge(final_chunk_values, setup%block, final)]
      end if
      call result_names(setup, reals, ints)
      do i = 1, size(reals)
         call dataset_info(trim(reals(i)), '', units, text, setup%links)
         if (trim(reals(i)) == 'energy_error' .and. .not. setup%cfg%run%model%conservative()) &
            text = 'max |E(t) - E(0) + W_friction - W_support - W_torque| / potential_range: ' &
                   //'the error of the energy balance (NaN: not integrated)'
         if (.not. setup%flips) call model_dataset_info(setup, trim(reals(i)), units, text)
         if (setup%flips .and. index(reals(i), 'param/') == 1) then
            if (pendulum_axis(setup%cfg, trim(reals(i)(7:)))) then   ! a parameter by name
               units = named_axis_units(setup%cfg, trim(reals(i)(7:)))
               text = 'parameter '//trim(reals(i)(7:))//' of the pixel (parameter axes)'
            end if
         end if
         call h5%create_dataset('/sweep/'//trim(reals(i)), 'real64', dims, chunk, error, &
                                fill=nan, compress=final, alloc_early=.not. final, &
                                checksum=final, units=units, &
                                description=text)
         if (allocated(error)) return
      end do
      do i = 1, size(ints)
         call dataset_info(trim(ints(i)), '', units, text, setup%links)
         if (.not. setup%flips) call model_dataset_info(setup, trim(ints(i)), units, text)
         call h5%create_dataset('/sweep/'//trim(ints(i)), 'int32', dims, chunk, error, &
                                fill=0.0_dp, compress=final, alloc_early=.not. final, &
                                checksum=final, units=units, &
                                description=text)
         if (allocated(error)) return
      end do
      call dataset_info('done', '', units, text)
      call h5%write('/sweep/done', spread(merge(1, 0, final), 1, setup%nblocks), error, &
                    units, text)
      if (allocated(error)) return
      if (.not. final .and. setup%checksum) then
         call h5%create_dataset(crc_path, 'int32', [size(reals) + size(ints), setup%nblocks], &
                                [size(reals) + size(ints), min(setup%nblocks, 4096)], error, &
                                compress=.false., alloc_early=.true., units='1', &
                                description='CRC-32 of each block (column) of each result '// &
                                '(row: the result datasets in the order they were created)')
         if (allocated(error)) return
      end if
      if (setup%grid) then
         call dataset_info('axis1', axis_units(setup%cfg%axis1), units, text)
         if (.not. setup%flips) call model_dataset_info(setup, 'axis1', units, text)
         if (setup%flips .and. pendulum_axis(setup%cfg, setup%cfg%axis1)) &
            call named_axis_info(setup%cfg%axis1, 'axis1', units, text)
         call h5%write('/sweep/axis1', setup%axis1, error, units, text)
         call dataset_info('axis2', axis_units(setup%cfg%axis2), units, text)
         if (.not. setup%flips) call model_dataset_info(setup, 'axis2', units, text)
         if (setup%flips .and. pendulum_axis(setup%cfg, setup%cfg%axis2)) &
            call named_axis_info(setup%cfg%axis2, 'axis2', units, text)
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
         ! links other than uniform rods say so, with d_i and I_i and units
         if (len(c%run%model%body_description()) > 0) &
            call h5%writeattr('/sweep', 'body', c%run%model%body_description())
         call h5%writeattr('/sweep', 'm', c%run%m(:setup%links))
         call h5%writeattr('/sweep', 'l', c%run%l(:setup%links))
         call h5%writeattr('/sweep', 'g', c%run%g)
         call h5%writeattr('/sweep', 'q0', c%run%q0())
         call h5%writeattr('/sweep', 'qdot0', c%run%w0())
         call h5%writeattr('/sweep', 'h', setup%opt%h)
         call h5%writeattr('/sweep', 't_end', setup%opt%h*setup%opt%n_steps)
         call h5%writeattr('/sweep', 'n_steps', setup%opt%n_steps)
         call h5%writeattr('/sweep', 'sqrt_l1_over_g', setup%tau)
         ! the unit its dt and t_end were given in (the file's times are in s)
         call h5%writeattr('/sweep', 'time_unit', trim(c%run%time_unit))
         call h5%writeattr('/sweep', 'potential_range', range)
         ! energy fed by a support or torques: no bound holds (none applied)
         if (c%run%model%autonomous()) call h5%writeattr('/sweep', 'flip_energy_bounds', bounds)
         call record_forces(h5, setup)
         call h5%writeattr('/sweep', 'stop_at', stop_name(setup%opt%stop_rule))
         call h5%writeattr('/sweep', 'block', setup%block)
         call h5%writeattr('/sweep', 'initial', merge('grid', 'list', setup%grid))
         if (setup%grid) then
            call h5%writeattr('/sweep', 'axis1', c%axis1)
            call h5%writeattr('/sweep', 'axis2', c%axis2)
         end if
         ! the device of the run that created (or completed) the file
         if (c%device == 'gpu') then
            if (gpu_fallback_blocks() > 0) then
               call h5%writeattr('/sweep', 'device', 'gpu: '//c%device_name//'; '// &
                                 to_str(gpu_fallback_blocks())// &
                                 ' block(s) computed on the CPU after a GPU failure')
            else
               call h5%writeattr('/sweep', 'device', 'gpu: '//c%device_name)
            end if
         else
            call h5%writeattr('/sweep', 'device', 'cpu')
         end if
      end associate
      call h5%take_error(error)
   contains
      !> Units and description of the grid values of an axis over a pendulum
      !> parameter by name (its catalogue units).
      subroutine named_axis_info(axis, name, units, text)
         character(len=*), intent(in) :: axis, name
         character(len=:), allocatable, intent(inout) :: units, text
         units = named_axis_units(setup%cfg, axis)
         text = 'grid values on '//name(1:4)//' '//name(5:5)//': parameter '//axis
      end subroutine named_axis_info
   end subroutine create_layout

   !> What a damped, driven or motored chain adds to the /sweep attributes: each of its
   !> parameters beyond m, l, g and the body (c1, coulomb1, coulomb_speed,
   !> rotor_inertia1, gear_ratio1, support_ax, …; none for the conservative rods), and
   !> the applied torques (`record_torques`).
   subroutine record_forces(h5, setup)
      type(h5file_t), intent(inout) :: h5        !! open file (keeps the first failure)
      type(sweep_setup_t), intent(in) :: setup   !! setup, flips true
      character(len=:), allocatable :: name, units
      real(dp) :: x
      integer :: i
      associate (model => setup%cfg%run%model)
         do i = 1, model%n_parameters()
            call model%parameter(i, name, x, units)
            if (.not. mass_length_or_g(name) .and. index(name, 'com') /= 1 .and. &
                index(name, 'inertia') /= 1) call h5%writeattr('/sweep', name, x)
         end do
      end associate
      call record_torques(h5, setup%cfg%run%torque, setup%cfg%run%torque_file)
   end subroutine record_forces

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
         if (var > 0) then
            call state_info(var, units, cname)
            text = 'grid values on '//name(1:4)//' '//name(5:5)//': initial '//cname
         else   ! a parameter axis
            cname = setup%cfg%axis1
            if (name == 'axis2') cname = setup%cfg%axis2
            units = parameter_units(cname)
            text = 'grid values on '//name(1:4)//' '//name(5:5)//': parameter '//cname
         end if
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
         else if (index(name, 'param/') == 1) then
            units = parameter_units(name(7:))
            text = 'parameter '//name(7:)//' of the pixel (parameter axes)'
         end if
      end select
   contains
      !> The units of the run's model's parameter `pname`.
      function parameter_units(pname) result(u)
         character(len=*), intent(in) :: pname
         character(len=:), allocatable :: u, other, other_units
         real(dp) :: x
         integer :: i
         u = '1'
         do i = 1, setup%cfg%run%model%n_parameters()
            call setup%cfg%run%model%parameter(i, other, x, other_units)
            if (other == pname) u = other_units
         end do
      end function parameter_units
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

   !> The results of block b as written, each a column, in the order of
   !> `result_names`, whose names `reals` and `ints` are (given, not made here: no
   !> text is built on the blocks' threads, see dpend_sweep_setup's "Threads").
   subroutine block_values(setup, b, res, reals, ints, v)
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: b                          !! block, 1-based
      type(batch_result_t), intent(in) :: res           !! its results
      character(len=32), intent(in) :: reals(:), ints(:)  !! `result_names`
      type(block_values_t), intent(out) :: v            !! its columns
      real(dp), allocatable :: p(:, :)
      integer :: i, k, j0, nb, nr
      call block_range(setup, b, j0, nb)
      allocate (v%r(nb, size(reals)), v%i(nb, size(ints)))
      v%real_names = reals
      v%int_names = ints
      nr = 0
      if (setup%flips) call take_r(res%t_flip)
      if (.not. setup%flips) then
      else if (setup%links == 2) then
         call take_r(res%t_flip1)
         call take_r(res%t_flip2)
      else
         do i = 1, setup%links
            call take_r(res%t_flip_link(i, :))
         end do
      end if
      call take_r(res%energy0)
      call take_r(res%energy_error)
      call take_r(res%t_stop)
      do i = 1, setup%links
         call take_r(res%final(i, :))
      end do
      do i = 1, setup%links
         call take_r(res%final(setup%links + i, :))
      end do
      if (setup%cfg%lyapunov) call take_r(res%lyapunov)
      select case (setup%cfg%indicator)
      case ('megno')
         call take_r(res%megno)
         call take_r(res%megno_y)
      case ('fli'); call take_r(res%fli)
      case ('sali'); call take_r(res%sali)
      case ('gali2'); call take_r(res%gali2)
      end select
      if (parameter_axes(setup)) then
         call block_parameters(setup, b, p)
         do k = 1, size(setup%param_names)
            if (len_trim(setup%param_names(k)) > 0) call take_r(p(k, :))
         end do
      end if
      if (nr /= size(reals) .or. size(ints) /= merge(2, 1, setup%cfg%stats)) &
         error stop 'internal error: block results are not result_names'
      v%i(:, 1) = res%status
      if (setup%cfg%stats) v%i(:, 2) = res%steps
   contains
      subroutine take_r(x)
         real(dp), intent(in) :: x(:)
         nr = nr + 1
         if (nr > size(reals)) error stop 'internal error: block results exceed result_names'
         v%r(:, nr) = x
      end subroutine take_r
   end subroutine block_values

   !> The CRC-32 of each result of a block as written (`block_values`), in the
   !> order of `result_names` (reals, then integers).
   function block_result_crcs(v) result(crcs)
      type(block_values_t), intent(in) :: v             !! the block's results
      integer :: crcs(size(v%r, 2) + size(v%i, 2))
      integer :: k
      do k = 1, size(v%r, 2)
         crcs(k) = crc32_of(v%r(:, k))
      end do
      do k = 1, size(v%i, 2)
         crcs(size(v%r, 2) + k) = crc32_of(v%i(:, k))
      end do
   end function block_result_crcs

   !> Write the results of block b and their CRC-32, flush, then flag it done and
   !> flush again (`write_values`).
   subroutine write_block(h5, setup, b, res, error, flush)
      type(h5file_t), intent(inout) :: h5               !! open working file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: b                          !! block, 1-based
      type(batch_result_t), intent(in) :: res           !! its results
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      logical, intent(in), optional :: flush            !! flush the file (default true)
      type(block_values_t), target :: v
      character(len=32), allocatable :: reals(:), ints(:)
      call result_names(setup, reals, ints)
      call block_values(setup, b, res, reals, ints, v)
      call write_values(h5, setup, b, v, block_result_crcs(v), error, flush)
   end subroutine write_block

   !> Write the results `v` of block b and their CRC-32 `crcs` (`crc_path`, when the
   !> file has it; `block_result_crcs`), flush, then flag it done and flush again.
   !> `flush` false leaves out the flushes: for a file opened with MPI-IO, where a
   !> flush is collective and the independent raw-data writes of allocated,
   !> unfiltered chunks bypass HDF5's caches (they reach the file, in order, before
   !> the write returns).
   subroutine write_values(h5, setup, b, v, crcs, error, flush)
      type(h5file_t), intent(inout) :: h5               !! open working file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: b                          !! block, 1-based
      type(block_values_t), intent(in), target :: v     !! its results
      integer, intent(in) :: crcs(:)                    !! their CRC-32
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      logical, intent(in), optional :: flush            !! flush the file (default true)
      real(dp), pointer, contiguous :: r2(:, :)
      integer, pointer, contiguous :: i2(:, :)
      integer :: j0, nb, k, n1
      logical :: sync
      sync = .true.
      if (present(flush)) sync = flush
      call block_range(setup, b, j0, nb)
      ! each block is whole chunks: a chunk torn by a kill during its write (its
      ! block not flagged done) is replaced without its old checksum being checked
      n1 = merge(setup%cfg%n1, nb, setup%grid)
      do k = 1, size(v%real_names)
         if (allocated(error)) exit
         r2(1:n1, 1:nb/n1) => v%r(:, k)
         if (setup%grid) then
            call h5%write_slab('/sweep/'//trim(v%real_names(k)), r2, &
                               [1, (j0 - 1)/n1 + 1], error, whole_chunks=.true.)
         else
            call h5%write_slab('/sweep/'//trim(v%real_names(k)), v%r(:, k), [j0], error, &
                               whole_chunks=.true.)
         end if
      end do
      do k = 1, size(v%int_names)
         if (allocated(error)) exit
         i2(1:n1, 1:nb/n1) => v%i(:, k)
         if (setup%grid) then
            call h5%write_slab('/sweep/'//trim(v%int_names(k)), i2, &
                               [1, (j0 - 1)/n1 + 1], error, whole_chunks=.true.)
         else
            call h5%write_slab('/sweep/'//trim(v%int_names(k)), v%i(:, k), [j0], error, &
                               whole_chunks=.true.)
         end if
      end do
      if (allocated(error)) return
      if (h5%exists(crc_path)) call h5%write_slab(crc_path, reshape(crcs, [size(crcs), 1]), &
                                                  [1, b], error)
      if (allocated(error)) return
      if (sync) call h5%flush()
      call h5%write_slab('/sweep/done', [1], [b], error)
      if (allocated(error)) return
      if (sync) call h5%flush()
   end subroutine write_values

   !> The working file of the sweep whose output is `output`: FILE.part.
   pure function working_file(output) result(path)
      character(len=*), intent(in) :: output  !! the output file
      character(len=:), allocatable :: path
      path = output//'.part'
   end function working_file

   !> Rewrite the complete working file of `filename` with compressed chunks into
   !> `filename` (through the one writer), then remove the working file. Each
   !> result is read whole, its blocks checked against their CRC-32 (a working file
   !> that has them), and its chunks encoded on every thread (`write_chunked`).
   subroutine finalize_file(filename, setup, error)
      character(len=*), intent(in) :: filename          !! the output file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      type(h5file_t) :: src, dst
      type(output_t) :: out
      character(len=32), allocatable :: names(:), reals(:), ints(:)
      character(len=:), allocatable :: path, part
      real(dp), allocatable :: r1(:), r2(:, :)
      integer, allocatable :: i1(:), i2(:, :), stored(:, :), crcs(:)
      integer :: k, err
      logical :: unreadable, summed
      unreadable = .false.
      part = working_file(filename)
      call out%begin(filename, setup%cfg%run%force, error)
      if (allocated(error)) return
      call src%open(part, 'r', error)
      if (allocated(error)) then
         call out%discard()
         return
      end if
      call result_names(setup, reals, ints)
      names = [reals, ints]
      summed = src%exists(crc_path)
      if (summed) call read_crcs(src, setup, size(names), stored, error)
      unreadable = allocated(error)
      if (.not. allocated(error)) call create_layout(dst, out%temp, setup, .true., error)
      do k = 1, size(names)
         if (allocated(error)) exit
         path = '/sweep/'//trim(names(k))
         if (k <= size(reals) .and. setup%grid) then
            call src%read(path, r2, error)
            if (summed .and. .not. allocated(error)) crcs = block_crcs(setup, r2)
         else if (k <= size(reals)) then
            call src%read(path, r1, error)
            if (summed .and. .not. allocated(error)) crcs = block_crcs(setup, r1)
         else if (setup%grid) then
            call src%read(path, i2, error)
            if (summed .and. .not. allocated(error)) crcs = block_crcs(setup, i2)
         else
            call src%read(path, i1, error)
            if (summed .and. .not. allocated(error)) crcs = block_crcs(setup, i1)
         end if
         if (summed .and. .not. allocated(error)) then
            if (any(crcs /= stored(k, :))) call fatal_error(error, path// &
               ' does not read back as written in block '// &
               to_str(findloc(crcs /= stored(k, :), .true., dim=1)))
         end if
         unreadable = allocated(error)
         if (allocated(error)) exit
         if (k <= size(reals) .and. setup%grid) then
            call dst%write_chunked(path, r2, error)
         else if (k <= size(reals)) then
            call dst%write_chunked(path, r1, error)
         else if (setup%grid) then
            call dst%write_chunked(path, i2, error)
         else
            call dst%write_chunked(path, i1, error)
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

   !> The checksums of a working file (`crc_path`), checked to be one per result
   !> (`n_results`) and block.
   subroutine read_crcs(h5, setup, n_results, stored, error)
      type(h5file_t), intent(inout) :: h5               !! the open working file
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: n_results                  !! results per block
      integer, allocatable, intent(out) :: stored(:, :) !! (n_results, nblocks)
      type(error_t), allocatable, intent(out) :: error  !! unreadable or another shape
      integer, allocatable :: dims(:)
      call h5%shape(crc_path, dims, error)
      if (allocated(error)) return
      if (size(dims) /= 2) then
         call fatal_error(error, crc_path//' has rank '//to_str(size(dims))//', not 2')
      else if (dims(1) /= n_results .or. dims(2) /= setup%nblocks) then
         call fatal_error(error, crc_path//' has shape ['//to_str(dims(1))//', '// &
                          to_str(dims(2))//'], not ['//to_str(n_results)//', '// &
                          to_str(setup%nblocks)//']')
      else
         call h5%read(crc_path, stored, error)
      end if
   end subroutine read_crcs

   !> The CRC-32 of every block of a real(dp) result held whole (rank 1 or 2, the
   !> sweep's shape), as `write_block` computes it, on every thread.
   function block_crcs_real(setup, values) result(crcs)
      type(sweep_setup_t), intent(in) :: setup                !! setup
      real(dp), intent(in), target, contiguous :: values(..)  !! the result
      integer :: crcs(setup%nblocks)
      crcs = block_crcs_at(setup, c_loc(values), storage_size(values)/8)
   end function block_crcs_real

   !> `block_crcs_real` for a default-integer result.
   function block_crcs_int(setup, values) result(crcs)
      type(sweep_setup_t), intent(in) :: setup                !! setup
      integer, intent(in), target, contiguous :: values(..)   !! the result
      integer :: crcs(setup%nblocks)
      crcs = block_crcs_at(setup, c_loc(values), storage_size(values)/8)
   end function block_crcs_int

   !> The CRC-32 of every block of the result at `base` (the sweep's values in
   !> order, `esize` bytes each), on every thread.
   function block_crcs_at(setup, base, esize) result(crcs)
      type(sweep_setup_t), intent(in) :: setup   !! setup
      type(c_ptr), intent(in) :: base            !! the result's first byte
      integer, intent(in) :: esize               !! bytes per value
      integer :: crcs(setup%nblocks)
      integer(int8), pointer, contiguous :: bytes(:)
      integer(i8) :: first, last
      integer :: b, j0, nb
      call c_f_pointer(base, bytes, [int(setup%n, i8)*esize])
      !$omp parallel do schedule(static) private(j0, nb, first, last)
      do b = 1, setup%nblocks
         call block_range(setup, b, j0, nb)
         first = int(j0 - 1, i8)*esize + 1
         last = int(j0 - 1 + nb, i8)*esize
         crcs(b) = crc32_of(bytes(first:last))
      end do
      !$omp end parallel do
   end function block_crcs_at

   !> Put a freshly written file in place: close it (the close checked unless an
   !> error is already set), with `reserve` give it disk blocks for all its length
   !> (the working file, whose chunks are allocated and not written), verify it,
   !> and commit it through the one writer; on any failure the temporary file is
   !> removed and the target is as it was.
   subroutine install_file(h5, out, setup, error, reserve)
      type(h5file_t), intent(inout) :: h5                 !! the new file, open on out%temp
      type(output_t), intent(inout) :: out                !! its output
      type(sweep_setup_t), intent(in) :: setup            !! setup, for the check
      type(error_t), allocatable, intent(inout) :: error  !! set on entry or by a step
      logical, intent(in), optional :: reserve            !! take its disk space now
      integer :: err
      if (allocated(error)) then
         call h5%close()
      else
         call h5%close(error)
      end if
      err = 0
      if (present(reserve) .and. .not. allocated(error) .and. .not. out%memory) then
         if (reserve) err = reserve_space(out%temp)
      end if
      if (err /= 0) call fatal_error(error, "cannot take the disk space of '"//out%temp// &
                                     "': "//errno_text(err))
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

end module dpend_sweep_layout
