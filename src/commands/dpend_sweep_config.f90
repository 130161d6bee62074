!> The command line of `dpend sweep`: its flags, the namelist group &sweep (the keys
!> are described in dpend_sweep_settings) and its help, read into the sweep's
!> settings; `parse_sweep` validates them and resolves the device.
module dpend_sweep_config
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, next_option, parse_real, parse_int, real_str, option_outcome, &
      to_str, scan_help_config, printable
   use dpend_model, only: max_dof
   use dpend_model_factory, only: body_list
   use dpend_namelist, only: read_run_config, namelist_error
   use dpend_run_flags, only: apply_run_flag, take_torque_file
   use dpend_run_settings, only: time_unit_option_help
   use dpend_sweep_settings, only: sweep_config_t, sweep_defaults, validate_sweep
   use dpend_sweep_gpu, only: resolve_device
   implicit none
   private
   public :: parse_sweep, sweep_help

contains

   !> Help text of `dpend sweep`.
   function sweep_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(sweep_config_t) :: cfg
      cfg = sweep_defaults()
      s = 'usage: dpend sweep [options]'//nl//nl// &
          'Integrate many initial conditions with a vectorized, parallel RK4 and write'//nl// &
          'per-condition results (flip times, energy, energy error, final state, optional'//nl// &
          'Lyapunov exponent) to HDF5, block by block. Rerunning the same command after'//nl// &
          'an interruption computes only the missing blocks. Layout: docs/hdf5-layout.md;'//nl// &
          'figures: scripts/plot_sweep.sh FILE.h5 OUTDIR; examples: data/sweep_*.nml.'//nl//nl// &
          'initial conditions (a grid over two values, the rest from --q1 --q2 --w1 --w2):' &
          //nl// &
          '  --axis1, --axis2 NAME  swept values: theta1 theta2 (rad from the hanging'//nl// &
          '                    position, theta = q + pi/2), q1 q2 (rad from horizontal),'//nl// &
          '                    w1 w2 (rad/s); with --links N: theta1..thetaN, q1..qN,'//nl// &
          '                    w1..wN; or a parameter (2 or more links): m1 m2 (kg),'//nl// &
          '                    l1 l2 (m), m2/m1 (m2 = value m1), l2/l1 (l2 = value l1),'//nl// &
          '                    stored per pixel in /sweep/param (--time-unit natural'//nl// &
          '                    uses --l1); rods and point masses (--body point); any'//nl// &
          '                    other real parameter of the pendulum by name (dpend'//nl// &
          '                    models): g (m/s^2), and per link k = 1..N: mk, lk (k >= 3),'//nl// &
          '                    comk (m), inertiak (kg m^2), any body, each pixel its own'//nl// &
          '                    model one trajectory at a time (not damping,'//nl// &
          '                    friction, support_* or motors); a model'//nl// &
          '                    without flips: its own parameters by name (the'//nl// &
          '                    elastic pendulum: m k l0 g); default '//cfg%axis1//', ' &
          //cfg%axis2//nl// &
          '  --n N             points on both axes; --n1 N, --n2 N each (1 to 1e6, at most'//nl// &
          '                    1e9 in all); default '//to_str(cfg%n1)//nl// &
          '  --min1, --max1, --min2, --max2 X  axis ranges; default '//real_str(cfg%min1)// &
          ' .. '//real_str(cfg%max1)//nl// &
          '  --ic-file FILE    a list instead of a grid: text rows "q1 q2 w1 w2" or HDF5'//nl// &
          '                    (N links: rows "q1 .. qN w1 .. wN", shape (n, 2N))'//nl// &
          '  --ic-dataset PATH dataset of an HDF5 list, shape (n, 4); default ' &
          //cfg%ic_dataset//nl// &
          '  --ic-angles q|theta  angles of the list measured as q or theta; default q' &
          //nl//nl// &
          'integration (rk4 only: --method rk4; the step is t_end / ceiling(t_end / dt);'//nl// &
          'two links: the vectorized kernel; 3 to 8 links: the chain lanes, flip maps and'//nl// &
          'indicators; 1 link, more than 8, or a model per pixel: one trajectory at a time):' &
          //nl// &
          time_unit_option_help(trim(cfg%run%time_unit))//nl// &
          '  --dt DT, --t-end T  step and end time in that unit; default ' &
          //real_str(cfg%run%dt)//', '//real_str(cfg%run%t_end)//nl// &
          '  --stop-at RULE    both: stop once every link that can flip has flipped;'//nl// &
          '                    either: at the first flip; end: run to t_end; default ' &
          //cfg%stop_at//nl// &
          '  --lyapunov        also the largest Lyapunov exponent (all run to t_end;'//nl// &
          '                    two links only)'//nl// &
          '  --indicator NAME  per-pixel chaos indicator beside the flip time (all run'//nl// &
          '                    to t_end): flip (none), lambda1 (= --lyapunov), megno'//nl// &
          '                    (running mean <Y>, and Y), fli (ln |d|), sali, gali2;'//nl// &
          '                    default '//cfg%indicator//nl// &
          '  --stats           also the number of steps of every trajectory'//nl//nl// &
          'parameters (as in dpend simulate):'//nl// &
          '  --m1, --m2 KG, --l1, --l2 M, --g M/S^2; --q1, --q2 RAD, --w1, --w2 RAD/S'//nl// &
          '                    (fixed initial values of what is not swept; default 0);'//nl// &
          '                    --theta1, --theta2 RAD from the hanging position instead'//nl// &
          '  --links N         number of links, 1 to '//to_str(max_dof)// &
          ' (default 2); --m, --l, --q, --w LIST'//nl// &
          '                    one value per link, e.g. --links 3 --q 0,0,-1.5707963'//nl// &
          '  --body NAME       the links'' mass distribution: '//body_list()//' (dpend models);'//nl// &
          '                    --com, --inertia LIST any other body (d_i in m, I_i in'//nl// &
          '                    kg m^2, one per link); default rod'//nl// &
          '  --damping, --coulomb, --coulomb-speed, --support-amplitude,'//nl// &
          '  --support-frequency, --support-phase, --rotor-inertia, --gear-ratio'//nl// &
          '                    as in dpend simulate (--help there): a damped, driven or'//nl// &
          '                    motored chain, integrated one trajectory at a time (not on'//nl// &
          '                    the GPU, no --lyapunov); its energy_error is then that of'//nl// &
          '                    the energy balance (docs/sweep.md)'//nl// &
          '  --torque-file F   applied joint torques: CSV with columns t [s] and tau1 ..'//nl// &
          '                    tauN [N m], linear between samples, covering [0, t_end];'//nl// &
          '                    every trajectory starts at t = 0 (docs/robot.md)'//nl// &
          '  --NAME X          any other parameter of the model by name (--k, --l0 of'//nl// &
          '                    --model elastic; dpend models lists them)'//nl// &
          '  --model elastic   the spring pendulum (docs/sweep.md): axes r phi rdot phidot'//nl// &
          '                    (or q1 q2 w1 w2); indicator maps only: megno fli sali gali2'//nl// &
          '  --config FILE     namelist file: &pendulum &initial &integration &output'//nl// &
          '                    &sweep (keys as the long options, e.g. n1, min1, stop_at)' &
          //nl//nl// &
          'run:'//nl// &
          '  --output FILE     HDF5 file; default '//cfg%run%output//nl// &
          '  --force           overwrite a file written with another configuration'//nl// &
          '  --block N         initial conditions per block (whole rows of axis 1 in a'//nl// &
          '                    grid); default '//to_str(cfg%block)//nl// &
          '  --threads N       OpenMP threads, 0 (all) to 1024; default all'//nl// &
          '  --device D        cpu, gpu (NVIDIA, two-link flip maps: docs/gpu.md) or'//nl// &
          '                    auto (the GPU if it can); default '//cfg%device//nl// &
          '  --gpu-repack K    GPU: steps per kernel launch, the unfinished trajectories'//nl// &
          '                    re-packed between launches; 0: one launch; default ' &
          //to_str(cfg%gpu_repack)//nl// &
          '  --quiet           no progress report on stderr'//nl// &
          '  -h, --help        this text'
   end function sweep_help

   !> Build the configuration from defaults, --config and flags; `help` if asked.
   subroutine parse_sweep(args, cfg, help, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'sweep'
      type(sweep_config_t), intent(out) :: cfg          !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value, config
      logical :: matched, missing
      integer :: i, n
      cfg = sweep_defaults()
      help = .false.
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_sweep_config(config, cfg, error)
         if (allocated(error)) return
      end if
      ! --n sets n1 and n2: with --n1 or --n2 which one counts would depend on the order
      if (any([(args(i)%s == '--n' .or. index(args(i)%s, '--n=') == 1, i=1, size(args))]) &
          .and. any([(args(i)%s == '--n1' .or. args(i)%s == '--n2' .or. &
                      index(args(i)%s, '--n1=') == 1 .or. index(args(i)%s, '--n2=') == 1, &
                      i=1, size(args))])) then
         call fatal_error(error, 'invalid --n: given with --n1 or --n2; they are two forms ' &
                          //'of the grid size (give --n, or --n1 and --n2)')
         return
      end if
      i = 1
      do while (i <= size(args))
         select case (args(i)%s)
         case ('--force'); cfg%run%force = .true.; i = i + 1; cycle
         case ('--quiet'); cfg%quiet = .true.; i = i + 1; cycle
         case ('--lyapunov'); cfg%lyapunov = .true.; i = i + 1; cycle
         case ('--stats'); cfg%stats = .true.; i = i + 1; cycle
         end select
         if (args(i)%s(1:min(2, len(args(i)%s))) /= '--' .and. args(i)%s /= '-o') then
            call fatal_error(error, "unexpected argument '"//printable(args(i)%s)// &
                             "' (dpend sweep --help lists the options)")
            return
         end if
         call next_option(args, i, name, value, .true., error, missing)
         matched = .true.
         select case (name)
         case ('--axis1', '--axis2', '--min1', '--max1', '--min2', '--max2')
            cfg%grid_given = cfg%grid_given//name//' '
         end select
         select case (name)
         case ('--config')
         case ('--axis1'); cfg%axis1 = value
         case ('--axis2'); cfg%axis2 = value
         case ('--n')
            call parse_int(value, name, n, error)
            cfg%n1 = n; cfg%n2 = n
         case ('--n1'); call parse_int(value, name, cfg%n1, error)
         case ('--n2'); call parse_int(value, name, cfg%n2, error)
         case ('--min1'); call parse_real(value, name, cfg%min1, error)
         case ('--max1'); call parse_real(value, name, cfg%max1, error)
         case ('--min2'); call parse_real(value, name, cfg%min2, error)
         case ('--max2'); call parse_real(value, name, cfg%max2, error)
         case ('--ic-file'); cfg%ic_file = value
         case ('--ic-dataset'); cfg%ic_dataset = value; cfg%ic_dataset_given = .true.
         case ('--ic-angles'); cfg%ic_angles = value; cfg%ic_angles_given = .true.
         case ('--stop-at'); cfg%stop_at = value; cfg%stop_at_given = '--stop-at'
         case ('--indicator'); cfg%indicator = value
         case ('--block')
            call parse_int(value, name, cfg%block, error); cfg%block_given = .true.
         case ('--device'); cfg%device = value
         case ('--gpu-repack'); call parse_int(value, name, cfg%gpu_repack, error)
         case ('--threads'); call parse_int(value, name, cfg%threads, error)
         case ('--torque-file')
            if (.not. (missing .or. allocated(error))) call take_torque_file(cfg%run, value, error)
         case ('--save-every', '--rtol', '--atol', '--output-dt', '--omega', '--max-steps')
            matched = .false.
         case default
            call apply_run_flag(cfg%run, name, value, matched, error)
         end select
         call option_outcome('sweep', name, matched, missing, [character(len=16) :: &
                             '--force', '--quiet', '--lyapunov', '--stats'], error, sweep_help())
         if (allocated(error)) return
      end do
      call validate_sweep(cfg, error)
      if (.not. allocated(error)) call resolve_device(cfg, error)
   end subroutine parse_sweep

   !> Read the common groups and &sweep of `filename` into `cfg`.
   subroutine read_sweep_config(filename, cfg, error)
      character(len=*), intent(in) :: filename          !! namelist file
      type(sweep_config_t), intent(inout) :: cfg        !! updated from the file
      type(error_t), allocatable, intent(out) :: error  !! unreadable or invalid
      character(len=16) :: axis1, axis2, ic_angles, time_unit, stop_at, indicator, device
      character(len=1024) :: ic_file, ic_dataset
      character(len=512) :: msg
      integer :: n1, n2, block, threads, unit, stat, gpu_repack
      real(dp) :: min1, max1, min2, max2
      logical :: lyapunov, stats, quiet
      namelist /sweep/ axis1, axis2, n1, n2, min1, max1, min2, max2, ic_file, ic_dataset, &
         ic_angles, time_unit, stop_at, block, lyapunov, stats, threads, quiet, indicator, &
         device, gpu_repack
      ! length 16 as read_run_config's own list (-fcheck=all checks constructors)
      call read_run_config(filename, cfg%run, error, &
                           extra_groups=[character(len=16) :: 'sweep'])
      if (allocated(error)) return
      axis1 = cfg%axis1; axis2 = cfg%axis2
      n1 = cfg%n1; n2 = cfg%n2
      min1 = cfg%min1; max1 = cfg%max1; min2 = cfg%min2; max2 = cfg%max2
      ! blank: not given in the file (then the current values stay)
      ic_file = cfg%ic_file; ic_dataset = ''; ic_angles = ''
      time_unit = ''; stop_at = cfg%stop_at; indicator = cfg%indicator
      block = cfg%block; threads = cfg%threads
      lyapunov = cfg%lyapunov; stats = cfg%stats; quiet = cfg%quiet
      device = cfg%device; gpu_repack = cfg%gpu_repack
      open (newunit=unit, file=filename, status='old', action='read', iostat=stat)
      if (stat /= 0) then
         call fatal_error(error, "invalid --config: cannot read '"//printable(filename)//"'")
         return
      end if
      ! the grid's keys and stop_at start unset so that the file's own are known
      axis1 = achar(0); axis2 = achar(0)
      min1 = -huge(1.0_dp); max1 = -huge(1.0_dp); min2 = -huge(1.0_dp)
      max2 = -huge(1.0_dp); stop_at = achar(0)
      block = -huge(1)   ! unset: known as not given
      read (unit, nml=sweep, iostat=stat, iomsg=msg)
      close (unit)
      if (stat > 0) then
         call fatal_error(error, namelist_error(filename, 'sweep', msg))
         return
      end if
      if (axis1 == achar(0)) then; axis1 = cfg%axis1; else; call grid_key('axis1'); end if
      if (axis2 == achar(0)) then; axis2 = cfg%axis2; else; call grid_key('axis2'); end if
      if (min1 == -huge(1.0_dp)) then; min1 = cfg%min1; else; call grid_key('min1'); end if
      if (max1 == -huge(1.0_dp)) then; max1 = cfg%max1; else; call grid_key('max1'); end if
      if (min2 == -huge(1.0_dp)) then; min2 = cfg%min2; else; call grid_key('min2'); end if
      if (max2 == -huge(1.0_dp)) then; max2 = cfg%max2; else; call grid_key('max2'); end if
      if (stop_at == achar(0)) then
         stop_at = cfg%stop_at
      else
         cfg%stop_at_given = 'stop_at [&sweep]'
      end if
      cfg%axis1 = trim(axis1); cfg%axis2 = trim(axis2)
      cfg%n1 = n1; cfg%n2 = n2
      cfg%min1 = min1; cfg%max1 = max1; cfg%min2 = min2; cfg%max2 = max2
      cfg%ic_file = trim(ic_file)
      if (len_trim(ic_dataset) > 0) then
         cfg%ic_dataset = trim(ic_dataset); cfg%ic_dataset_given = .true.
      end if
      if (len_trim(ic_angles) > 0) then
         cfg%ic_angles = trim(ic_angles); cfg%ic_angles_given = .true.
      end if
      if (len_trim(time_unit) > 0) then
         call fatal_error(error, "invalid config '"//printable(filename)//"' in &sweep: " &
                          //'time_unit is a setting of every command: give it in ' &
                          //"&integration (time_unit = '"//printable(trim(time_unit))//"')")
         return
      end if
      cfg%stop_at = trim(stop_at)
      cfg%indicator = trim(indicator)
      if (block == -huge(1)) then
         block = cfg%block
      else
         cfg%block_given = .true.
      end if
      cfg%block = block; cfg%threads = threads
      cfg%lyapunov = lyapunov; cfg%stats = stats; cfg%quiet = quiet
      cfg%device = trim(device); cfg%gpu_repack = gpu_repack
   contains
      subroutine grid_key(key)
         character(len=*), intent(in) :: key
         cfg%grid_given = cfg%grid_given//key//' '
      end subroutine grid_key
   end subroutine read_sweep_config

end module dpend_sweep_config
