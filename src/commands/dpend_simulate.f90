!> `dpend simulate`: one trajectory from the command line through an integrator
!> into an HDF5 file (layout in docs/hdf5-layout.md). The entry point of the
!> command is `simulate_command`.
module dpend_simulate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error, run_failure, error_run_failed
   use dpend_cli, only: arg_t, next_option, option_outcome
   use dpend_run_settings, only: run_config_t, validate_run_config, time_text
   use dpend_namelist, only: read_run_config
   use dpend_run_flags, only: apply_run_flag, run_flags_help, take_initial_run_flag, &
      initial_angles_help
   use dpend_model, only: model_t, max_dof
   use dpend_model_factory, only: default_model
   use dpend_work, only: needs_work, work_model, split_work, is_work_model, augmented_state, &
                         work_slots, n_works
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_methods, only: new_integrator, method_options_t
   use dpend_propagate, only: march_t, integrate_sampled, march_progress_t
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model, coordinate_labels, record_torques
   use dpend_output, only: output_t
   use dpend_version, only: version
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_cli, only: to_str
   use dpend_cli, only: scan_help_config, printable
   use dpend_limits, only: check_count, max_samples, sci
   use dpend_resources, only: check_memory, check_disk
   use dpend_os, only: available_memory_bytes
   use dpend_progress, only: wall_seconds
   use dpend_cli, only: real_str, seconds_str
   use dpend_command_common, only: take_quiet, refusal_line, error_line
   implicit none
   private
   public :: simulate_command
   public :: simulate_defaults, parse_simulate, run_simulate, simulate_help
   public :: trajectory_t, write_trajectory, check_simulate_resources
   public :: largest_error

   !> Memory per kept sample: t, q, q̇ with room for the geometric growth (2 × 40 B)
   !> and the derived quantities written beside them (25 reals) [B].
   real(dp), parameter :: sample_memory = 288.0_dp
   !> File size per kept sample: 30 reals [B], and the fixed part of a file [B].
   real(dp), parameter :: sample_file = 240.0_dp, file_overhead = 65536.0_dp

   !> Sampled states of a run: internal variables converted to (q, q̇).
   type :: trajectory_t
      integer :: n = 0                      !! number of samples
      real(dp), allocatable :: t(:)         !! times [s]
      real(dp), allocatable :: q(:, :)      !! angles (2, n) [rad]
      real(dp), allocatable :: qd(:, :)     !! angular velocities (2, n) [rad/s]
      !> W_friction, W_support, W_torque (n_works, n) [J] of a damped or driven chain
      !> (dpend_work)
      real(dp), allocatable :: w(:, :)
      character(len=:), allocatable :: status  !! 'completed' or why the run stopped
   end type trajectory_t

contains

   !> The entry point of `dpend simulate [options]` (app/main.f90): parse → settings
   !> → run → file, then the closing lines on standard output (with --quiet only the
   !> last). A refusal or a failed run comes back as `error`, its message the one
   !> line 'dpend simulate: ...'.
   subroutine simulate_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `simulate`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(run_config_t) :: cfg
      character(len=:), allocatable :: summary
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_simulate(rest, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'simulate')
         return
      end if
      if (help) then
         write (output_unit, '(a)') simulate_help()
         return
      end if
      call run_simulate(cfg, error, summary)
      if (allocated(error)) then
         call error_line(error, 'simulate')
         return
      end if
      if (.not. quiet .or. len(summary) == 0) &
         write (output_unit, '(a)') "dpend simulate: wrote '"//cfg%output//"': t = 0 .. " &
         //time_text(cfg, cfg%t_end)
      if (len(summary) > 0) write (output_unit, '(a)') 'dpend simulate: '//summary
   end subroutine simulate_command

   !> Defaults of simulate: the chapter's parameters, both links horizontal at rest.
   function simulate_defaults() result(cfg)
      type(run_config_t) :: cfg
      cfg%method = 'rk4'
      cfg%dt = 1e-3_dp
      cfg%t_end = 10.0_dp
      cfg%save_every = 10
      cfg%output = 'simulate.h5'
   end function simulate_defaults

   !> Help text of `dpend simulate`.
   function simulate_help() result(s)
      character(len=:), allocatable :: s
      character(len=*), parameter :: nl = new_line('a')
      type(run_config_t) :: cfg
      cfg = simulate_defaults()
      s = 'usage: dpend simulate [options]'//nl//nl// &
          'Integrate one trajectory of the double pendulum (or of the chain of N links,'//nl// &
          '--links N) and write it to HDF5 (layout: docs/hdf5-layout.md; figures:'//nl// &
          'scripts/plot_simulate.sh FILE.h5; animation: dpend animate FILE.h5).'//nl//nl// &
          'options (SI units; angles in rad from the horizontal x axis, y up):'//nl// &
          run_flags_help(cfg)//nl// &
          '  --save-every N    keep every N-th step (and always the last); default ' &
          //to_str(cfg%save_every)//nl// &
          '  --output-dt S     sample at exactly k*S and t_end (dense output); 0 = off'//nl// &
          initial_angles_help()// &
          '  --torque-file F   applied joint torques: CSV with columns t [s] and tau1 ..'//nl// &
          '                    tauN [N m] (joint i on link i), linear between samples,'//nl// &
          '                    covering [0, t_end] (docs/robot.md)'//nl// &
          '  --output FILE     HDF5 file to write; default '//cfg%output//nl// &
          '  --force           overwrite an existing output file'//nl// &
          '  --quiet           print only the summary line (standard output)'//nl// &
          '  -h, --help        this text'
   end function simulate_help

   !> Build the configuration from defaults, --config and flags.
   subroutine parse_simulate(args, cfg, help, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'simulate'
      type(run_config_t), intent(out) :: cfg            !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value, config
      logical :: matched, missing, save_every_given, output_dt_given
      integer :: i
      cfg = simulate_defaults()
      help = .false.; save_every_given = .false.; output_dt_given = .false.
      ! first pass: help and the config file, so that flags override the file
      call scan_help_config(args, help, config, error)
      if (allocated(error) .or. help) return
      if (len(config) > 0) then
         call read_run_config(config, cfg, error)
         if (allocated(error)) return
      end if
      i = 1
      do while (i <= size(args))
         if (args(i)%s == '--force') then
            cfg%force = .true.
            i = i + 1
            cycle
         end if
         if (args(i)%s(1:min(2, len(args(i)%s))) /= '--' .and. args(i)%s /= '-o') then
            call fatal_error(error, "unexpected argument '"//printable(args(i)%s)// &
                             "' (dpend simulate --help lists the options)")
            return
         end if
         call next_option(args, i, name, value, .true., error, missing)
         if (name == '--config') cycle
         call take_initial_run_flag(cfg, name, value, missing, matched, error)
         if (.not. matched) call apply_run_flag(cfg, name, value, matched, error)
         call option_outcome('simulate', name, matched, missing, &
                             [character(len=16) :: '--force'], error, simulate_help())
         if (allocated(error)) return
         if (name == '--save-every') save_every_given = .true.
         if (name == '--output-dt') output_dt_given = .true.
      end do
      call check_sampling_forms(cfg, save_every_given, output_dt_given, error)
      if (allocated(error)) return
      call validate_run_config(cfg, error)
      if (allocated(error)) return
      if (cfg%links + work_slots(cfg%model) > max_dof) then
         call fatal_error(error, 'invalid links: '//to_str(cfg%links)//' with damping, a ' &
                          //'moving support or joint torques is outside [1, '// &
                          to_str(max_dof - work_slots(cfg%model))//'] (the energy balance ' &
                          //'takes '//to_str(2*work_slots(cfg%model))//' state components)')
         return
      end if
      call check_simulate_resources(cfg, error)
   end subroutine parse_simulate

   !> Refuse save_every with output_dt: two forms of the output sampling,
   !> of which output_dt > 0 would win whatever their order. Each may come from the
   !> command line or the namelist file (`run_config_t%nml_given`).
   subroutine check_sampling_forms(cfg, save_every_flag, output_dt_flag, error)
      type(run_config_t), intent(in) :: cfg             !! configuration read
      logical, intent(in) :: save_every_flag            !! --save-every given
      logical, intent(in) :: output_dt_flag             !! --output-dt given
      type(error_t), allocatable, intent(out) :: error  !! both given
      character(len=:), allocatable :: a, b
      a = ''; b = ''
      if (allocated(cfg%nml_given)) then
         if (index(cfg%nml_given, ' save_every ') > 0) a = 'save_every [&integration]'
         if (index(cfg%nml_given, ' output_dt ') > 0) b = 'output_dt [&integration]'
      end if
      if (save_every_flag) a = '--save-every'
      if (output_dt_flag) b = '--output-dt'
      if (len(a) == 0 .or. len(b) == 0) return
      call fatal_error(error, 'invalid '//b//': given with '//a//'; they are two forms of ' &
                       //'the output sampling (output_dt: samples at k*output_dt [s]; ' &
                       //'save_every: every N-th step); give one of them')
   end subroutine check_sampling_forms

   !> Refuse a run whose kept samples exceed `max_samples`, the available memory or
   !> the free space of the output's file system. The count is known for a
   !> fixed-step method (t_end/(dt save_every) + 2) and with output_dt (t_end/output_dt
   !> + 2); an adaptive method without output_dt is capped while it runs instead.
   subroutine check_simulate_resources(cfg, error)
      type(run_config_t), intent(in) :: cfg             !! validated configuration
      type(error_t), allocatable, intent(out) :: error  !! refused
      class(integrator_t), allocatable :: integ
      character(len=*), parameter :: hint = 'use a larger --save-every or --output-dt'
      real(dp) :: n, span
      call new_integrator(cfg%method, integ, error)
      if (allocated(error)) return
      span = cfg%t_end
      if (cfg%output_dt > 0.0_dp) then
         call check_count('output_dt', cfg%output_dt, span, 't_end', max_samples - 2, &
                          'samples', 'use a larger --output-dt', error)
         if (allocated(error)) return
         n = span/cfg%output_dt + 2.0_dp
         call check_memory('output_dt', n*sample_memory, sci(n)//' samples', &
                           'use a larger --output-dt', error)
         if (.not. allocated(error)) call check_disk('output_dt', n*sample_file + &
                                                     file_overhead, cfg%output, &
                                                     'use a larger --output-dt', error)
      else if (.not. integ%adaptive()) then
         ! dt save_every ≤ 1e9 s · 2^31 and max_samples ≤ 1e9: no overflow
         if (cfg%dt*real(cfg%save_every, dp)*real(max_samples - 2, dp) < span) then
            call fatal_error(error, 'invalid save_every: '//sci(real(cfg%save_every, dp))// &
                             ' keeps a sample every '//sci(cfg%dt*real(cfg%save_every, dp))// &
                             ' s, more than '//sci(real(max_samples, dp))// &
                             ' samples over t_end = '//sci(span)//' s ('//hint//')')
            return
         end if
         n = span/(cfg%dt*real(cfg%save_every, dp)) + 2.0_dp
         call check_memory('save_every', n*sample_memory, sci(n)//' samples', hint, error)
         if (.not. allocated(error)) call check_disk('save_every', n*sample_file + &
                                                     file_overhead, cfg%output, hint, error)
      end if
   end subroutine check_simulate_resources

   !> Integrate, sample and write. `error` is set for invalid input (nothing written)
   !> or for a failed run (the file holds the samples before the failure).
   !> `summary`: 'rk4: 10000 steps, 40000 f evaluations, relative energy error
   !> 3.2e-13, 0.05 s' (steps, right-hand-side evaluations, |E(t_end) − E(0)| over
   !> the energy scale, wall time), '' when nothing was integrated.
   subroutine run_simulate(cfg, error, summary)
      type(run_config_t), intent(in) :: cfg             !! validated configuration
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      character(len=:), allocatable, intent(out), optional :: summary  !! the closing line
      class(integrator_t), allocatable :: integ
      type(trajectory_t) :: traj
      type(error_t), allocatable :: werr
      type(output_t) :: out
      real(dp) :: t0, e_max, t_max, e_fin
      if (present(summary)) summary = ''
      t0 = wall_seconds()
      call new_integrator(cfg%method, integ, error, method_options_t(rtol=cfg%rtol, &
                          atol=cfg%atol, omega=cfg%omega, max_steps=cfg%max_steps))
      if (allocated(error)) return
      call out%begin(cfg%output, cfg%force, error)
      if (allocated(error)) return
      call integrate_trajectory(cfg, integ, traj)
      call write_trajectory(out%temp, cfg, integ, traj, werr)
      if (present(summary) .and. traj%n > 0) then
         ! the largest over the kept samples (the file's energy dataset) and the final
         call largest_error(cfg%model, traj, e_max, t_max, e_fin)
         summary = integ%name()//': '//to_str(integ%n_steps)//' steps, '// &
                   to_str(integ%n_rhs)//' f evaluations, relative energy '// &
                   trim(merge('balance error', 'error        ', allocated(traj%w)))// &
                   ' largest '//real_str(e_max, 2)//' (t = '//time_text(cfg, t_max)// &
                   '), final '//real_str(e_fin, 2)//', '// &
                   seconds_str(wall_seconds() - t0)//' s'
         ! a body other than the uniform rod
         if (len(cfg%model%body_description()) > 0) &
            summary = summary//'; links: '//cfg%model%body_description()
      end if
      if (.not. allocated(werr)) call out%commit(werr)
      call out%explain(werr)
      call out%discard()
      if (allocated(werr)) then
         call move_alloc(werr, error)
         call run_failure(error)
         return
      end if
      if (traj%status /= 'completed') &
         call fatal_error(error, 'run stopped: '//traj%status//"; '"//cfg%output// &
                          "' holds the samples before the failure", error_run_failed)
   end subroutine run_simulate

   !> The relative energy error |E(t) − E(0)| / energy_scale, or for a damped or
   !> driven run the balance error |E(t) − E(0) + W_friction − W_support| /
   !> energy_scale, over the kept samples: its largest value `e_max` (first at
   !> `t_max` [s]) and its final one `e_fin` (the summary quotes both).
   subroutine largest_error(model, traj, e_max, t_max, e_fin)
      class(model_t), intent(in) :: model         !! the system (without its works)
      type(trajectory_t), intent(in) :: traj      !! the samples (n >= 1)
      real(dp), intent(out) :: e_max, t_max, e_fin  !! largest, its time [s], final
      real(dp) :: e0, scale, e
      integer :: k
      e0 = model%energy(traj%t(1), [traj%q(:, 1), traj%qd(:, 1)])
      scale = model%energy_scale(e0)
      e_max = -1.0_dp
      t_max = traj%t(1)
      do k = 1, traj%n
         e = model%energy(traj%t(k), [traj%q(:, k), traj%qd(:, k)]) - e0
         if (allocated(traj%w)) e = e + traj%w(1, k) - traj%w(2, k) - traj%w(3, k)
         e = abs(e)/scale
         if (e > e_max) then
            e_max = e
            t_max = traj%t(k)
         end if
         e_fin = e
      end do
   end subroutine largest_error

   !> Integrate from t = 0 to t_end with the configured method, keeping every
   !> save_every-th step and the last one, or, with output_dt > 0, the states at
   !> exactly k·output_dt and t_end from the method's continuous extension.
   subroutine integrate_trajectory(cfg, integ, traj)
      type(run_config_t), intent(in) :: cfg               !! configuration
      class(integrator_t), intent(inout) :: integ         !! the method
      type(trajectory_t), intent(out) :: traj             !! the samples
      type(march_t) :: march
      type(march_progress_t), target :: prog
      real(dp) :: t, h
      real(dp), allocatable :: times(:), states(:, :), y(:)
      class(model_t), allocatable :: model   ! the system integrated
      integer(i8) :: k, cap, avail
      integer :: stat, i
      ! a damped or driven chain is integrated with its works (dpend_work)
      if (needs_work(cfg%model)) then
         call work_model(cfg%model, model)
      else
         allocate (model, source=cfg%model)
      end if
      ! an adaptive run without output_dt keeps an unknown number of samples: at most
      ! max_samples and what fits the memory now
      cap = max_samples
      avail = available_memory_bytes()
      if (avail > 0) cap = max(1024_i8, min(cap, int(real(avail, dp)/sample_memory, i8)))
      block   ! the works, if any, start at 0
         real(dp), allocatable :: q_aug(:), qd_aug(:)
         call augmented_state(model, cfg%q0(), cfg%w0(), q_aug, qd_aug)
         y = integ%to_internal(model, q_aug, qd_aug)
      end block
      t = 0.0_dp
      h = cfg%dt
      traj%status = 'completed'
      stat = stat_ok
      ! progress in model time: a bar after 1 s on a terminal, else a line at most
      ! every 10 s (none for a run shorter than that)
      call prog%begin('dpend simulate', cfg%t_end)
      if (cfg%output_dt > 0.0_dp) then
         call integrate_sampled(integ, model, t, y, cfg%t_end, h, cfg%output_dt, times, &
                                states, stat, prog)
         do i = 1, size(times)
            call append(traj, integ, model, times(i), states(:, i))
         end do
         if (size(times) > 0) t = times(size(times))
      else
         call append(traj, integ, model, t, y)
         call integ%clear_step()
         march%progress => prog
         call march%start(integ, t, cfg%t_end, h)
         k = 0
         do while (.not. march%finished)
            call march%next(integ, model, t, y, h, stat)
            if (stat /= stat_ok) exit
            k = k + 1
            if (mod(k, int(cfg%save_every, i8)) == 0 .or. march%finished) then
               if (traj%n >= cap) then
                  traj%status = 'kept samples reached '//sci(real(cap, dp))// &
                                ' (memory limit) after t = '//sci(t, 6)// &
                                ' s; use a larger --save-every or --output-dt'
                  exit
               end if
               call append(traj, integ, model, t, y)
            end if
         end do
      end if
      call prog%end()
      if (stat /= stat_ok) then
         traj%status = status_message(stat)//' after t = '//sci(t, 6)//' s'
      end if
   end subroutine integrate_trajectory

   !> Append the state (t, y) to the samples, growing the buffers geometrically.
   !> The state of a chain with its works (dpend_work) is split into (q, q̇) and W.
   subroutine append(traj, integ, model, t, y)
      type(trajectory_t), intent(inout) :: traj     !! samples
      class(integrator_t), intent(in) :: integ      !! for the conversion to (q, q̇)
      class(model_t), intent(in) :: model           !! the system
      real(dp), intent(in) :: t                     !! time [s]
      real(dp), intent(in) :: y(:)                  !! internal state
      real(dp), allocatable :: tt(:), qq(:, :), ww(:, :), wk(:, :)
      real(dp) :: qa(max_dof), qda(max_dof)
      integer :: cap, nd, na
      logical :: works
      na = model%n_dof()
      works = is_work_model(model)
      nd = na - work_slots(model)
      if (.not. allocated(traj%t)) then
         allocate (traj%t(1024), traj%q(nd, 1024), traj%qd(nd, 1024))
         if (works) allocate (traj%w(n_works, 1024))
      else if (traj%n == size(traj%t)) then
         cap = 2*size(traj%t)
         allocate (tt(cap), qq(nd, cap), ww(nd, cap))
         tt(:traj%n) = traj%t; qq(:, :traj%n) = traj%q; ww(:, :traj%n) = traj%qd
         call move_alloc(tt, traj%t); call move_alloc(qq, traj%q); call move_alloc(ww, traj%qd)
         if (works) then
            allocate (wk(n_works, cap))
            wk(:, :traj%n) = traj%w
            call move_alloc(wk, traj%w)
         end if
      end if
      traj%n = traj%n + 1
      traj%t(traj%n) = t
      if (works) then
         call integ%to_physical(model, y, qa(1:na), qda(1:na), t)
         call split_work(qa(1:na), qda(1:na), traj%q(:, traj%n), &
                         traj%qd(:, traj%n), traj%w(:, traj%n))
      else
         call integ%to_physical(model, y, traj%q(:, traj%n), traj%qd(:, traj%n), t)
      end if
   end subroutine append

   !> Write the samples with their derived quantities (accelerations, momenta,
   !> energy, reactions, kinematics) and the run's attributes.
   subroutine write_trajectory(filename, cfg, integ, traj, error)
      character(len=*), intent(in) :: filename          !! file to write
      type(run_config_t), intent(in) :: cfg             !! configuration
      class(integrator_t), intent(in) :: integ          !! the method and its counters
      type(trajectory_t), intent(in) :: traj            !! the samples
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      type(h5file_t) :: h5
      real(dp), allocatable :: qdd(:, :), p(:, :), e(:), out(:, :), y(:), f(:), slab(:, :)
      real(dp), allocatable :: e_w(:), kinetic(:), potential(:)
      character(len=:), allocatable :: name, units, text, cols, q_units, rate_units, &
                                       acc_units, p_units, anchor, points, style, forces
      integer :: i, n, nd, j, n_comp, off, n_out, rows
      logical :: canonical
      n = traj%n
      associate (model => cfg%model)
         nd = model%n_dof()
         canonical = model%hamiltonian()
         n_out = 0
         do j = 1, model%n_outputs()
            call model%output_info(j, name, n_comp, units, text)
            n_out = n_out + n_comp
         end do
         allocate (qdd(nd, n), p(nd, n), e(n), out(n_out, n), y(2*nd), f(2*nd))
         allocate (kinetic(n), potential(n))
         p = 0.0_dp
         do i = 1, n
            y(1:nd) = traj%q(:, i); y(nd + 1:) = traj%qd(:, i)
            call model%field(traj%t(i), y, f)
            qdd(:, i) = f(nd + 1:)
            if (canonical) call model%momenta(traj%t(i), y, p(:, i))
            e(i) = model%energy(traj%t(i), y)
            kinetic(i) = model%kinetic_energy(traj%t(i), y)
            potential(i) = model%potential_energy(traj%t(i), y)
            call model%outputs(traj%t(i), y, f, out(:, i))
         end do
         call h5%open(filename, 'w', error)
         if (allocated(error)) return
         call h5%write('/trajectory/t', traj%t(:n), units='s', description='sample times')
         call coordinate_labels(model, cols, q_units, rate_units, acc_units, p_units)
         call h5%write('/trajectory/q', traj%q(:, :n), units=q_units, &
                       description=model%coordinates_text(0))
         call h5%write('/trajectory/qdot', traj%qd(:, :n), units=rate_units, &
                       description=model%coordinates_text(1))
         call h5%write('/trajectory/qddot', qdd, units=acc_units, &
                       description=model%coordinates_text(2))
         if (cfg%spec%model_name() == default_model) then   ! link angles: their convention
            call h5%writeattr('/trajectory/q', 'angles', 'absolute')
            call h5%writeattr('/trajectory/qdot', 'angles', 'absolute rates')
            call h5%writeattr('/trajectory/qddot', 'angles', 'absolute rates')
         end if
         if (canonical) call h5%write('/trajectory/p', p, units=p_units, &
            description='canonical momenta p = M(q) qdot (p1 .. p'//to_str(nd)//')')
         call h5%writeattr('/', 'coordinates', cols)
         call model%figure(anchor, points, style, forces)
         if (len(points) > 0) then
            call h5%writeattr('/', 'draw_anchor', anchor)
            call h5%writeattr('/', 'draw_points', points)
            call h5%writeattr('/', 'draw_style', style)
            call h5%writeattr('/', 'draw_forces', forces)
         end if
         call h5%write('/trajectory/energy', e, units='J', description=model%energy_text())
         call h5%write('/trajectory/kinetic', kinetic, units='J', description='kinetic ' &
                       //'energy T of the total energy T + V')
         call h5%write('/trajectory/potential', potential, units='J', description= &
                       'potential energy V of the total energy T + V')
         if (allocated(traj%w)) then   ! the energy balance (dpend_work)
            e_w = traj%w(1, :n)   ! contiguous, for the HDF5 layer
            call h5%write('/trajectory/W_friction', e_w, units='J', description= &
               'work dissipated by the joint friction since t = 0, integral of sum c_i ' &
               //'w_i^2 + c_f,i tanh(w_i/v_s) w_i dt, w_i = qdot_i - qdot_(i-1) (viscous ' &
               //'damping and Coulomb friction)')
            e_w = traj%w(2, :n)
            call h5%write('/trajectory/W_support', e_w, units='J', description= &
               'work done by the moving support since t = 0, integral of F_01 . v_A dt')
            if (work_slots(model) > 1) then   ! applied torques
               e_w = traj%w(3, :n)
               call h5%write('/trajectory/W_torque', e_w, units='J', description= &
                  'work done by the applied joint torques since t = 0, integral of sum ' &
                  //'tau_i (qdot_i - qdot_(i-1)) dt')
            end if
            call h5%write('/trajectory/balance_error', (e - e(1) + traj%w(1, :n) - &
               traj%w(2, :n) - traj%w(3, :n))/model%energy_scale(e(1)), units='1', description= &
               '(E(t) - E(0) + W_friction - W_support - W_torque) / energy_scale: the integration ' &
               //'error of the energy balance')
         end if
         off = 0
         do j = 1, model%n_outputs()
            call model%output_info(j, name, n_comp, units, text, rows)
            slab = out(off + 1:off + n_comp, :)   ! contiguous, for the HDF5 layer
            if (rows > 0) then   ! (samples, rows, n_comp/rows) as h5py shows it
               call h5%write('/trajectory/'//name, reshape(slab, [n_comp/rows, rows, n]), &
                             units=units, description=text)
            else
               call h5%write('/trajectory/'//name, slab, units=units, description=text)
            end if
            off = off + n_comp
         end do
         call record_model(h5, model)
      end associate
      if (cfg%initial_angles == 'relative') call h5%writeattr('/', 'initial_angles', &
         'relative (given; q0 and qdot0 are the absolute ones)')
      call record_torques(h5, cfg%torque, cfg%torque_file)   ! what the run applied
      call h5%writeattr('/', 'method', integ%name())
      call h5%writeattr('/', 'dt', cfg%dt)
      call h5%writeattr('/', 't_end', cfg%t_end)
      call h5%writeattr('/', 'version', version)
      call h5%writeattr('/', 'q0', cfg%q0())
      call h5%writeattr('/', 'qdot0', cfg%w0())
      call h5%writeattr('/', 'model', cfg%spec%model_name())
      if (cfg%spec%find('links') > 0) then   ! a chain of links: its per-link arrays
         call h5%writeattr('/', 'links', cfg%links)
         call h5%writeattr('/', 'm', cfg%m(:cfg%links))
         call h5%writeattr('/', 'l', cfg%l(:cfg%links))
      end if
      call h5%writeattr('/', 'save_every', cfg%save_every)
      call h5%writeattr('/', 'order', integ%order())
      if (integ%adaptive()) then
         call h5%writeattr('/', 'rtol', cfg%rtol)
         call h5%writeattr('/', 'atol', cfg%atol)
      end if
      call h5%writeattr('/', 'n_steps', integ%n_steps)
      call h5%writeattr('/', 'n_rhs', integ%n_rhs)
      call h5%writeattr('/', 'status', traj%status)
      call h5%writeattr('/', 'energy_scale', cfg%model%energy_scale(e(1)))
      call h5%close(error)   ! reports the first failed write, if any
   end subroutine write_trajectory

end module dpend_simulate
