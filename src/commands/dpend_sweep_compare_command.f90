!> `dpend sweep-compare A.h5 B.h5`: the accuracy report of two complete sweeps of the
!> same initial conditions, of the quantity they map: flip times (the engine's
!> `compare_sweeps`, dpend_sweep_compare) or an indicator's values and classes
!> (`compare_indicator_maps`, dpend_sweep_agreement); or with --agreement the
!> pixels' regular or chaotic classes by two indicators (`sweep_agreement`). The entry point `sweep_compare_command`
!> reads the command line and prints the report; the engine's messages name the
!> command themselves ('sweep-compare: ...').
module dpend_sweep_compare_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, is_long_option, next_option, option_outcome, parse_real, to_str
   use dpend_sweep_compare, only: compare_sweeps
   use dpend_sweep_agreement, only: agreement_options_t, sweep_agreement, &
      compare_indicator_maps, map_indicator
   use dpend_command_common, only: take_quiet, summary_quiet, refusal_line
   implicit none
   private
   public :: sweep_compare_command, sweep_compare_help

   character(len=*), parameter :: nl = new_line('a')

contains

   !> Help text of `dpend sweep-compare`.
   function sweep_compare_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend sweep-compare A.h5 B.h5 [--rel R]'//nl// &
          '       dpend sweep-compare A.h5 B.h5 --agreement [--threshold-a X]'//nl// &
          '             [--threshold-b Y] [--output FILE [--force]]'//nl//nl// &
          'Accuracy report of two complete sweeps of the same initial conditions (e.g.'//nl// &
          'steps dt and dt/2), of the quantity they map. Flip-time maps: the fraction'//nl// &
          'of pixels whose first flip time changes by more than R (default 0.01, at'//nl// &
          'most 1000) relative, or that flip in one and not the other, overall and by'//nl// &
          'flip time in units of sqrt(l1/g). Indicator maps (dpend sweep --indicator,'//nl// &
          '--lyapunov; the same indicator and t_end in both): the fraction of pixels'//nl// &
          'whose value changes by more than R relative (SALI, GALI_2: where both call'//nl// &
          'the pixel regular) and the agreement of their regular/chaotic classes by the'//nl// &
          'default thresholds below. Sweeps of other initial conditions (grid or list,'//nl// &
          'shape, axes, ranges, parameters, time unit, t_end, stop rule) are refused.'//nl// &
          'Nothing is written.'//nl//nl// &
          '--agreement: classify every pixel of each sweep as regular or chaotic by its'//nl// &
          'indicator (the two may differ, as may t_end and the step) and report the'//nl// &
          'fraction of pixels where the two agree, with both times; stored in FILE only'//nl// &
          'with --output FILE. Chaotic: megno <Y> > X (default 2.5); lambda1'//nl// &
          'lambda1 sqrt(l1/g) > X (default 0.05); fli > X (no default); sali, gali2'//nl// &
          '< X (default 1e-8). --threshold-a, --threshold-b: X of file A, B.'//nl// &
          summary_quiet
   end function sweep_compare_help

   !> The entry point of `dpend sweep-compare A B [--rel R]` (app/main.f90), the
   !> option anywhere (also --rel=R); `--agreement` classifies the pixels by their
   !> indicators instead. Parse → the comparison → the report on standard output. A
   !> refusal or a failed run comes back as `error`, its message the one line 'dpend
   !> sweep-compare: ...'.
   subroutine sweep_compare_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after the command
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:), files(:)
      type(agreement_options_t) :: agree
      real(dp) :: rel
      logical :: agreement, help, quiet
      integer :: i, unit, stat
      call take_quiet(args, rest, quiet)
      help = any([(rest(i)%s == '--help' .or. rest(i)%s == '-h', i=1, size(rest))])
      if (help) then
         write (output_unit, '(a)') sweep_compare_help()
         return
      end if
      call parse_sweep_compare(rest, files, rel, agreement, agree, error)
      if (allocated(error)) then
         call refusal_line(error, 'sweep-compare')
         return
      end if
      unit = output_unit
      if (quiet) then   ! the report into a scratch file: of it only its last line
         open (newunit=unit, status='scratch', action='readwrite', iostat=stat)
         if (stat /= 0) unit = output_unit
      end if
      if (agreement) then
         call sweep_agreement(files(1)%s, files(2)%s, agree, unit, error)
      else if (len(map_indicator(files(1)%s)) > 0 .or. &
               len(map_indicator(files(2)%s)) > 0) then
         call compare_indicator_maps(files(1)%s, files(2)%s, rel, unit, error)
      else
         call compare_sweeps(files(1)%s, files(2)%s, rel, unit, error)
      end if
      if (unit /= output_unit) then
         if (.not. allocated(error)) call print_last_line(unit)
         close (unit)
      end if
      ! the engine's messages begin with 'sweep-compare: '
      if (allocated(error)) error%message = 'dpend '//error%message
   end subroutine sweep_compare_command

   !> Print the last line of the formatted scratch file `unit` on standard output.
   subroutine print_last_line(unit)
      integer, intent(in) :: unit  !! an open formatted sequential file
      character(len=4096) :: line, last
      integer :: stat
      last = ''
      rewind (unit)
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         last = line
      end do
      write (output_unit, '(a)') trim(last)
   end subroutine print_last_line

   !> The options and the two files of `dpend sweep-compare` (without --help and
   !> --quiet): --rel, or --agreement with its thresholds, output and --force.
   subroutine parse_sweep_compare(args, files, rel, agreement, agree, error)
      type(arg_t), intent(in) :: args(:)                  !! the arguments after the command
      type(arg_t), allocatable, intent(out) :: files(:)   !! the two sweep files
      real(dp), intent(out) :: rel                        !! --rel R (default 0.01)
      logical, intent(out) :: agreement                   !! --agreement was given
      type(agreement_options_t), intent(out) :: agree     !! the options of --agreement
      type(error_t), allocatable, intent(out) :: error    !! invalid input
      character(len=:), allocatable :: name, value, needs_agreement
      logical :: missing, matched, rel_given
      integer :: i
      rel = 0.01_dp
      agreement = .false.
      agree%output = ''
      needs_agreement = ''
      rel_given = .false.
      allocate (files(0))
      i = 1
      do while (i <= size(args))
         if (.not. is_long_option(args(i)%s)) then
            files = [files, args(i)]
            i = i + 1
            cycle
         end if
         if (args(i)%s == '--agreement' .or. args(i)%s == '--force') then
            if (args(i)%s == '--agreement') agreement = .true.
            if (args(i)%s == '--force') agree%force = .true.
            if (args(i)%s == '--force') needs_agreement = '--force'
            i = i + 1
            cycle
         end if
         call next_option(args, i, name, value, .true., error, missing)
         matched = .true.
         select case (name)
         case ('--rel'); call parse_real(value, name, rel, error); rel_given = .true.
         case ('--threshold-a')
            call parse_real(value, name, agree%threshold_a, error)
            agree%set_a = .true.
         case ('--threshold-b')
            call parse_real(value, name, agree%threshold_b, error)
            agree%set_b = .true.
         case ('--output')
            agree%output = value
            if (len(value) == 0) call fatal_error(error, 'invalid --output: empty '// &
                                                  '(accepted: a file name)')
         case default; matched = .false.
         end select
         if (name /= '--rel' .and. matched) needs_agreement = name
         call option_outcome('sweep-compare', name, matched, missing, &
                             [character(len=16) :: '--agreement', '--force'], error, &
                             '--rel --agreement --threshold-a --threshold-b --output --force')
         if (allocated(error)) return
      end do
      if (size(files) /= 2) then
         call fatal_error(error, 'needs two files, got '//to_str(size(files))// &
                          ' (dpend sweep-compare --help)')
      else if (.not. agreement .and. len(needs_agreement) > 0) then
         call fatal_error(error, 'invalid '//needs_agreement//': an option of '// &
                          '--agreement (dpend sweep-compare --help)')
      else if (agreement .and. rel_given) then
         call fatal_error(error, 'invalid --rel: not an option of --agreement '// &
                          '(its thresholds: --threshold-a, --threshold-b)')
      else if (agree%force .and. len(agree%output) == 0) then
         call fatal_error(error, 'invalid --force: given without --output (nothing is ' &
                          //'written unless --output FILE is given)')
      end if
   end subroutine parse_sweep_compare
end module dpend_sweep_compare_command
