!> `dpend poincare`: the Poincare section at one energy (the numerics of
!> `dpend_poincare`: orbits started on the energy shell of the section, each
!> crossing located to roundoff), written to an HDF5 file (group /poincare,
!> docs/hdf5-layout.md) with a summary on standard output. The settings, their
!> parsing and the run around it are in `dpend_chaos_common`.
module dpend_poincare_command
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, error_bad_input
   use dpend_cli, only: arg_t, to_str
   use dpend_run_settings, only: run_config_t, time_text
   use dpend_integrator, only: integrator_t, stat_ok, status_message
   use dpend_events, only: angle_crossing_t
   use dpend_propagate, only: march_progress_t
   use dpend_poincare, only: poincare_result_t, poincare_sections, shell_samples
   use dpend_hdf5, only: h5file_t
   use dpend_chaos_common, only: chaos_config_t, write_common, stopped, num, es
   use dpend_chaos_common, only: chaos_command
   implicit none
   private
   public :: poincare_command, run_poincare

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The entry point of `dpend poincare [options]` (app/main.f90): the arguments after
   !> the command, run through `chaos_command` with `run_poincare`; a refusal or a
   !> failed run comes back as `error`.
   subroutine poincare_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `poincare`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      call chaos_command('poincare', args, run_poincare, error)
   end subroutine poincare_command

   !> `dpend poincare`.
   subroutine run_poincare(cfg, ch, integ, filename, summary, error, failed)
      type(run_config_t), intent(in) :: cfg
      type(chaos_config_t), intent(in) :: ch
      class(integrator_t), intent(inout) :: integ
      character(len=*), intent(in) :: filename  !! the file to write
      character(len=:), allocatable, intent(inout) :: summary
      type(error_t), allocatable, intent(out) :: error
      logical, intent(inout) :: failed
      type(poincare_result_t) :: res
      type(angle_crossing_t) :: section
      type(h5file_t) :: h5
      real(dp), allocatable :: q0(:, :), qd0(:, :)
      real(dp) :: e, es_
      integer :: n_found, n_failed
      character(len=:), allocatable :: status
      type(march_progress_t) :: prog   ! the report in model time
      e = ch%energy
      if (.not. ch%energy_given) e = cfg%model%energy(0.0_dp, [cfg%q0(), cfg%w0()])
      allocate (q0(2, ch%n_ics), qd0(2, ch%n_ics))
      call shell_samples(cfg%model, e, ch%section_link, ch%section_angle, ch%section_direction, &
                         ch%n_ics, q0, qd0, n_found)
      if (n_found == 0) then
         call fatal_error(error, 'invalid energy: E = '//num(e)//' J has no state on the'// &
                          ' section q'//to_str(ch%section_link)//' = '//num(ch%section_angle) &
                          //' (it lies below the potential energy there)', error_bad_input)
         return
      end if
      section = angle_crossing_t(index=ch%section_link, angle=ch%section_angle, wrap=.true.)
      section%direction = ch%section_direction
      call prog%begin('dpend poincare', real(n_found, dp)*cfg%t_end)
      call poincare_sections(integ, cfg%model, section, q0(:, 1:n_found), qd0(:, 1:n_found), &
                             cfg%t_end, cfg%dt, ch%n_points, res, prog)
      call prog%end()
      n_failed = count(res%status /= stat_ok)
      status = 'completed'
      if (n_failed > 0) status = to_str(n_failed)//' orbit(s) stopped early: '// &
                                 status_message(res%status(findloc(res%status /= stat_ok, &
                                                                   .true., dim=1)))
      es_ = cfg%model%energy_scale(e)
      call h5%open(filename, 'w', error)
      if (allocated(error)) return
      integ%n_steps = res%n_steps
      call write_common(h5, cfg, integ, 'poincare', status)
      call h5%write('/poincare/q', res%q, units='rad', description= &
         'angle of the other link at each crossing, wrapped to (-pi, pi]')
      call h5%write('/poincare/p', res%p, units='kg m^2/s', description= &
         'canonical momentum of the other link at each crossing')
      call h5%write('/poincare/t', res%t, units='s', description= &
         "crossing time from the orbit's start")
      call h5%write('/poincare/energy', res%energy, units='J', &
         description='energy at the crossing')
      call h5%write('/poincare/orbit', res%orbit, units='1', &
         description='orbit number (1-based) of each point')
      call h5%write('/poincare/initial_q', q0(:, 1:n_found), units='rad', &
         description='initial angles of each orbit (q1, q2)')
      call h5%write('/poincare/initial_qdot', qd0(:, 1:n_found), units='rad/s', &
         description='initial angular velocities of each orbit (qdot1, qdot2)')
      call h5%write('/poincare/count', res%count, units='1', &
         description='points of each orbit')
      call h5%write('/poincare/orbit_status', res%status, units='1', &
         description='0, or the step failure code of the orbit')
      call h5%writeattr('/', 'energy', e)
      call h5%writeattr('/', 'energy_scale', es_)
      call h5%writeattr('/', 'section_link', ch%section_link)
      call h5%writeattr('/', 'section_angle', ch%section_angle)
      call h5%writeattr('/', 'section_direction', ch%section_direction)
      call h5%writeattr('/', 'other_link', 3 - ch%section_link)
      call h5%writeattr('/', 'n_orbits', n_found)
      call h5%writeattr('/', 'max_points', ch%n_points)
      call h5%close(error)   ! reports the first failed write, if any
      if (allocated(error)) return
      summary = 'dpend poincare: '//integ%name()//', dt = '//time_text(cfg, cfg%dt)// &
                ', orbits up to t = '//time_text(cfg, cfg%t_end)//', E = ' &
                //num(e)//' J, section q'//to_str(ch%section_link)//' = ' &
                //num(ch%section_angle)//' (mod 2 pi), direction '// &
                to_str(ch%section_direction)//nl//to_str(n_found)//' orbits'
      if (n_found < ch%n_ics) summary = summary//' (of '//to_str(ch%n_ics)// &
                                        ' requested: the shell is thin)'
      summary = summary//', '//to_str(size(res%q))//' section points, '// &
                to_str(res%n_steps)//' steps'
      if (size(res%q) > 0) summary = summary//'; max |E - E0| / E_s = '// &
                                     es(maxval(abs(res%energy - e))/es_)
      summary = summary//nl//"dpend poincare: wrote '"//cfg%output//"'"
      if (n_failed > 0) call stopped(status, cfg%output, error, failed)
   end subroutine run_poincare

end module dpend_poincare_command
