!> `dpend sweep`: maps over initial conditions. The entry point `sweep_command` reads
!> the command line (`dpend_sweep_config`) into the sweep's settings
!> (`dpend_sweep_settings`), runs the engine of src/engines/ (setup, blocks and run:
!> dpend_sweep_engine; file layout: dpend_sweep_layout; resume and verification:
!> dpend_sweep_resume; design in docs/sweep.md, layout in docs/hdf5-layout.md) and
!> prints the closing line. The sweep reads its own --quiet with its other options.
module dpend_sweep_command
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use dpend_error, only: error_t
   use dpend_cli, only: arg_t
   use dpend_version, only: slow_build_note
   use dpend_progress, only: progress_header
   use dpend_sweep_settings, only: sweep_config_t, horizon_text
   use dpend_sweep_config, only: parse_sweep, sweep_help
   use dpend_sweep_setup, only: sweep_summary_t, summary_text
   use dpend_sweep_engine, only: run_sweep
   use dpend_command_common, only: refusal_line, error_line
   implicit none
   private
   public :: sweep_command

contains

   !> The entry point of `dpend sweep [options]` (app/main.f90): parse → settings →
   !> engine → file, then the closing line on standard output. A refusal or a failed
   !> run comes back as `error`, its message the one line 'dpend sweep: ...'.
   subroutine sweep_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `sweep`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(sweep_config_t) :: cfg
      type(sweep_summary_t) :: summary
      logical :: help
      call parse_sweep(args, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'sweep')
         return
      end if
      if (help) then
         write (output_unit, '(a)') sweep_help()
         return
      end if
      ! the horizon in both units, printed when the run starts
      if (.not. cfg%quiet) call progress_header('dpend sweep: '//horizon_text(cfg))
      if (.not. cfg%quiet .and. len(cfg%device_note) > 0) &
         write (error_unit, '(a)') 'dpend sweep: '//cfg%device_note
      call run_sweep(cfg, summary, error)
      ! refused input (found when the output is examined) or a run that failed
      if (allocated(error)) then
         call error_line(error, 'sweep')
         return
      end if
      ! once, after a run that computed (a refusal stays one line); not with --quiet
      if (summary%blocks_computed > 0 .and. .not. cfg%quiet .and. len(slow_build_note()) > 0) &
         write (error_unit, '(a)') 'dpend sweep: '//slow_build_note()
      if (summary%blocks_computed == 0) then
         write (output_unit, '(a)') "dpend sweep: '"//cfg%run%output// &
            "' is complete (nothing to compute)"
      else
         ! a body other than the uniform rod, before the closing line (--quiet: that alone)
         if (len(cfg%run%model%body_description()) > 0 .and. .not. cfg%quiet) &
            write (output_unit, '(a)') 'dpend sweep: links: '//cfg%run%model%body_description()
         write (output_unit, '(a)') "dpend sweep: wrote '"//cfg%run%output//"': "// &
            summary_text(summary)
      end if
   end subroutine sweep_command
end module dpend_sweep_command
