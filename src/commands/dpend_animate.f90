!> `dpend animate`: an animated GIF of the double pendulum (or the chain of N links)
!> from a `dpend simulate` file, drawn by gnuplot (scripts/plot/animate.gp) from a data
!> file written here.
!>
!> Frames: N = round(duration × fps) (at least 1) without --duration the whole
!> trajectory, N = floor(span × fps / speed) + 1; frame k (k = 0 … N−1) shows the
!> state at t = t(1) + k·speed/fps, interpolated linearly in the angles between
!> the stored samples (the rods keep their lengths). gnuplot receives file names
!> only as arguments, never inside code; it runs without a shell. The entry point
!> of the command is `animate_command`.
module dpend_animate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_cli, only: arg_t, next_option, option_outcome, parse_int, parse_real, to_str, &
                        is_long_option, printable
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_output, only: output_t, check_output_path, register_input
   use dpend_trajectory_figure, only: figure_track_t, read_figure, resample_figure
   use dpend_limits, only: check_range, sci, max_time, max_angle
   use dpend_resources, only: check_memory
   use dpend_os, only: find_script, run_program, make_temp_file, remove_file, echo_to_stderr, &
                           directory_of, base_name, path_kind, path_directory, path_missing, &
                           move_noreplace, move_replace, sync_path, errno_text
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_command_common, only: take_quiet, with_quiet, summary_quiet, refusal_line, &
      error_line
   implicit none
   private
   public :: animate_command
   public :: animate_config_t, parse_animate, run_animate, animate_help
   public :: max_frames
   public :: track_t, read_track, animation_labels

   integer, parameter :: max_frames = 10000        !! most frames of one animation
   integer, parameter :: min_fps = 1, max_fps = 100
   integer, parameter :: min_pixels = 64, max_pixels = 4096
   real(dp), parameter :: min_speed = 1e-3_dp, max_speed = 1e3_dp
   real(dp), parameter :: min_duration = 1e-2_dp, max_duration = 1e5_dp
   real(dp), parameter :: trail_span = 1.5_dp       !! tip trail: the last 1.5 s [s]
   real(dp), parameter :: trail_step = 0.01_dp      !! finest trail sampling [s]
   integer, parameter :: max_trail_rows = 400000    !! most trail samples in all
   !> At most 1e6 rods drawn in all (frames × links of both files): gnuplot draws
   !> each, a few µs each, so an animation takes seconds, not hours.
   integer, parameter :: max_drawn_links = 1000000

   !> What to animate and how.
   type :: animate_config_t
      character(len=:), allocatable :: input        !! simulate file
      character(len=:), allocatable :: output       !! GIF ('' = input with .gif)
      character(len=:), allocatable :: overlay      !! second simulate file or ''
      character(len=:), allocatable :: frames       !! PNG directory or ''
      logical :: force = .false.                    !! replace existing outputs
      logical :: reactions = .false.                !! draw F01 and F21
      integer :: fps = 25                           !! frames per second
      integer :: width = 640, height = 640          !! pixels
      real(dp) :: speed = 1.0_dp                    !! simulated s per real s
      real(dp) :: duration = -1.0_dp                !! animation length [s]; < 0 = all
      character(len=:), allocatable :: layout       !! with --overlay: 'overlay' or 'side'
      logical :: size_given = .false.               !! --size given
      !> the clock's unit: 's', or 'natural' (also in s; the file's √(l1/g) or √(l0/g))
      character(len=7) :: time_unit = 's'
   end type animate_config_t

   !> The samples of one simulate file that the animation needs.
   type :: track_t
      character(len=:), allocatable :: path, method
      !> what the run was, for the labels: 'rk4, dt 0.001 s'; and the settings compared
      !> between two files ('method', 'dt', 'q0', 'qdot0', 'body', 'm', 'l', 'g': text)
      character(len=:), allocatable :: run_text
      character(len=64) :: settings(8) = ''
      !> per link, where its point mass sits as a fraction of the link (com_i / l_i when
      !> the link has no moment of inertia about its centre of mass), else -1: no bob
      real(dp), allocatable :: bob(:)
      real(dp), allocatable :: t(:)                 !! sample times (n) [s]
      !> the natural time unit of the file's model [s] (√(l1/g) from the attributes l
      !> and g, √(l0/g) from l0 and g; 0: not recorded) and its name
      real(dp) :: natural = 0.0_dp
      character(len=16) :: natural_name = ''
      !> the figure the file describes (anchor, points, forces; dpend_trajectory_figure)
      type(figure_track_t) :: fig
   end type track_t

   !> The frames and the trail of one animation (`plan_frames`).
   type :: plan_t
      integer :: nframes = 1     !! frames
      real(dp) :: dtf = 0.0_dp   !! time between frames [s]
      integer :: m = 1           !! trail samples per frame interval
      real(dp) :: ht = 0.0_dp    !! time between trail samples [s]
      integer :: ntr = 1         !! trail length in samples
      integer :: nrows = 1       !! trail samples in all
   end type plan_t

   !> The temporary files gnuplot reads and the stem of its PNG frames
   !> (`make_temp_files`, `remove_temp_files`): names, and which were made.
   type :: temp_files_t
      character(len=:), allocatable :: params, frames_dat, trail_dat, stem
      logical :: made_params = .false., made_frames = .false.
      logical :: made_trail = .false., made_stem = .false.
   end type temp_files_t

   character(len=*), parameter :: nl = new_line('a')

contains

   !> The entry point of `dpend animate FILE.h5 [options]` (app/main.f90): parse →
   !> settings → `run_animate` (the GIF through gnuplot) → its closing line. A refusal
   !> or a failed run comes back as `error`, its message the one line 'dpend animate:
   !> ...'.
   subroutine animate_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `animate`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(animate_config_t) :: cfg
      character(len=:), allocatable :: summary
      logical :: help
      call take_quiet(args, rest)
      call parse_animate(rest, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'animate')
      else if (help) then
         write (output_unit, '(a)') with_quiet(animate_help(), summary_quiet)
      else
         call run_animate(cfg, summary, error)
         if (allocated(error)) then
            call error_line(error, 'animate')
         else
            write (output_unit, '(a)') 'dpend animate: '//summary
         end if
      end if
   end subroutine animate_command

   !> Help text of `dpend animate`.
   function animate_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend animate FILE.h5 [options]'//nl//nl// &
          'Animated GIF of the double pendulum (or the chain of N links, --links) from'//nl// &
          'a dpend simulate file, drawn by gnuplot: every rod, the pins, a fading trail'//nl// &
          'of the tip (the last 1.5 s of simulated time), the time, equal axis scales'//nl// &
          'fixed at +-(l1 + l2 + ...) and a margin.'//nl//nl// &
          'Frame k (k = 0, 1, ...) shows t = t0 + k*speed/fps, interpolated linearly in'//nl// &
          'the angles between the stored samples (use --output-dt in simulate for'//nl// &
          'exact states). Frames: round(duration*fps), at least 1; without --duration'//nl// &
          'floor(span*fps/speed) + 1 covering the whole trajectory (with --overlay the'//nl// &
          'shorter of the two); at most '// &
          to_str(max_frames)//'.'//nl// &
          'The GIF delay is in 1/100 s: the frame rate played is 100/round(100/fps).'//nl//nl// &
          'options:'//nl// &
          '  --output FILE   GIF to write; default FILE.gif beside the input (.h5 replaced)'//nl// &
          '  --force         overwrite an existing GIF (and PNG frames)'//nl// &
          '  --fps N         frames per second, '//to_str(min_fps)//'..'//to_str(max_fps)// &
          '; default 25'//nl// &
          '  --duration S    length of the animation [s of playback], '//sci(min_duration)// &
          '..'//sci(max_duration)//';'//nl// &
          '                  default: the whole trajectory at the chosen speed'//nl// &
          '  --speed X       playback speed: 1 real time, 0.25 four times slower, 2 twice'//nl// &
          '                  as fast; '//sci(min_speed)//'..'//sci(max_speed)//'; default 1'//nl// &
          '  --size WxH      image size in pixels, each '//to_str(min_pixels)//'..'// &
          to_str(max_pixels)//'; default 640x640'//nl// &
          '  --reactions     arrows of the joint reactions F01 (ground on link 1, at A) and'//nl// &
          '                  F21 (link 2 on link 1, at B); for N links other than 2 the'//nl// &
          '                  force of body i-1 on body i at every joint i (F_joint); to one'//nl// &
          '                  scale [N per m] chosen from the largest |F| shown, stated in'//nl// &
          '                  a legend'//nl// &
          '  --overlay FILE2 a second simulate file drawn in another colour on the same'//nl// &
          '                  frames (e.g. two nearby initial conditions separating); the'//nl// &
          '                  title says in what the two runs differ, the key names each'//nl// &
          '                  link of each file'//nl// &
          '  --time-unit U   the clock of the frames: s (default) or natural, also in the'//nl// &
          "                  file's sqrt(l1/g) (sqrt(l0/g) for the elastic pendulum)"//nl// &
          '  --layout L      with --overlay: overlay (both in one frame, default) or side'//nl// &
          '                  (side by side, each in its own panel; default size 1280x640)'//nl// &
          '  --frames DIR    also write frame_0001.png, ... into the existing directory DIR'//nl// &
          '  -h, --help      this text'//nl//nl// &
          'Needs gnuplot (5.4 or later) on PATH and scripts/plot/animate.gp of the source'//nl// &
          'tree (found beside the build, or under $DPEND_ROOT).'
   end function animate_help

   !> Read the command line: one input file and the options, each value checked.
   subroutine parse_animate(args, cfg, help, error)
      type(arg_t), intent(in) :: args(:)                !! arguments after 'animate'
      type(animate_config_t), intent(out) :: cfg        !! the configuration
      logical, intent(out) :: help                      !! --help was given
      type(error_t), allocatable, intent(out) :: error  !! invalid input
      character(len=:), allocatable :: name, value
      logical :: matched, missing
      real(dp) :: x
      integer :: i, n
      cfg%input = ''
      cfg%output = ''
      cfg%overlay = ''
      cfg%frames = ''
      cfg%layout = 'overlay'
      help = any([(args(i)%s == '-h' .or. args(i)%s == '--help', i=1, size(args))])
      if (help) return
      i = 1
      do while (i <= size(args))
         if (.not. is_long_option(args(i)%s)) then
            if (len(cfg%input) > 0 .or. len(args(i)%s) == 0) then
               call fatal_error(error, "unexpected argument '"//args(i)%s// &
                                "' (dpend animate --help lists the options)")
               return
            end if
            cfg%input = args(i)%s
            i = i + 1
            cycle
         end if
         if (args(i)%s == '--force' .or. args(i)%s == '--reactions') then
            if (args(i)%s == '--force') cfg%force = .true.
            if (args(i)%s == '--reactions') cfg%reactions = .true.
            i = i + 1
            cycle
         end if
         call next_option(args, i, name, value, .true., error, missing)
         matched = .true.
         if (allocated(error)) deallocate (error)
         select case (name)
         case ('--output')
            cfg%output = value
            if (len(value) == 0 .and. .not. missing) &
               call fatal_error(error, 'invalid --output: empty file name')
         case ('--overlay')
            cfg%overlay = value
            if (len(value) == 0 .and. .not. missing) &
               call fatal_error(error, 'invalid overlay: empty file name')
         case ('--frames')
            cfg%frames = value
            if (.not. missing) call check_frames_dir(value, error)
         case ('--fps')
            call parse_int(value, 'fps', n, error)
            if (.not. allocated(error)) call check_range('fps', real(n, dp), &
               real(min_fps, dp), real(max_fps, dp), 'frames per second', error)
            cfg%fps = n
         case ('--speed')
            call parse_real(value, 'speed', x, error)
            if (.not. allocated(error)) call check_range('speed', x, min_speed, max_speed, &
               '', error, 'simulated seconds per second of playback')
            cfg%speed = x
         case ('--duration')
            call parse_real(value, 'duration', x, error)
            if (.not. allocated(error)) call check_range('duration', x, min_duration, &
               max_duration, 's', error, 'length of the animation')
            cfg%duration = x
         case ('--size')
            call parse_size(value, cfg%width, cfg%height, error)
            cfg%size_given = .true.
         case ('--time-unit')
            cfg%time_unit = value(:min(len(value), 7))
            if (value /= 's' .and. value /= 'natural' .and. .not. missing) &
               call fatal_error(error, "invalid time_unit: '"//printable(value)// &
                                "' (accepted: s, natural) [--time-unit]")
         case ('--layout')
            cfg%layout = value
            if (value /= 'overlay' .and. value /= 'side' .and. .not. missing) &
               call fatal_error(error, "invalid layout: '"//printable(value)// &
                                "' (accepted: overlay, side)")
         case default
            matched = .false.
         end select
         call option_outcome('animate', name, matched, missing, &
                             [character(len=16) :: '--force', '--reactions'], error, animate_help())
         if (allocated(error)) return
      end do
      if (len(cfg%input) == 0) then
         call fatal_error(error, 'invalid input: no simulate file given '// &
                          '(usage: dpend animate FILE.h5 [options])')
         return
      end if
      if (cfg%layout == 'side' .and. len(cfg%overlay) == 0) then
         call fatal_error(error, 'invalid layout: side needs --overlay FILE2 (two runs '// &
                          'side by side)')
         return
      end if
      if (cfg%layout == 'side' .and. .not. cfg%size_given) cfg%width = 2*cfg%height
      if (len(cfg%output) == 0) cfg%output = gif_name(cfg%input)
      ! a frame budget known from the options alone (the default duration is checked
      ! once the file's span is known)
      if (cfg%duration > 0.0_dp) then
         if (cfg%duration*real(cfg%fps, dp) > real(max_frames, dp) + 0.5_dp) &
            call fatal_error(error, 'invalid duration: '//sci(cfg%duration)//' s at '// &
                             to_str(cfg%fps)//' fps gives '// &
                             sci(real(nint(cfg%duration*real(cfg%fps, dp)), dp))// &
                             ' frames; at most '//to_str(max_frames)// &
                             ' (use a smaller --duration or --fps)')
      end if
   end subroutine parse_animate

   !> The GIF beside the input: FILE.h5 → FILE.gif, other names get .gif appended.
   pure function gif_name(input) result(path)
      character(len=*), intent(in) :: input  !! simulate file
      character(len=:), allocatable :: path
      integer :: n
      n = len(input)
      path = input//'.gif'
      if (n > 3) then
         if (input(n - 2:n) == '.h5') path = input(:n - 3)//'.gif'
      end if
   end function gif_name

   !> Parse 'WxH' (pixels), each in [min_pixels, max_pixels].
   subroutine parse_size(text, w, h, error)
      character(len=*), intent(in) :: text              !! e.g. '640x480'
      integer, intent(inout) :: w, h                    !! width and height
      type(error_t), allocatable, intent(out) :: error  !! refused
      integer :: x
      character(len=*), parameter :: rng = ' (accepted: WxH pixels, each 64..4096, e.g. 640x640)'
      x = scan(text, 'xX')
      if (x < 2 .or. x == len(text)) then
         call fatal_error(error, "invalid size: '"//text//"' is not WxH"//rng)
         return
      end if
      if (verify(text(:x - 1), '0123456789') /= 0 .or. verify(text(x + 1:), '0123456789') /= 0) &
         then
         call fatal_error(error, "invalid size: '"//text//"' is not WxH"//rng)
         return
      end if
      if (x > 6 .or. len(text) - x > 5) then      ! more than 5 digits: too large to read
         call fatal_error(error, "invalid size: '"//text//"' is outside 64..4096"//rng)
         return
      end if
      read (text(:x - 1), *) w
      read (text(x + 1:), *) h
      if (min(w, h) < min_pixels .or. max(w, h) > max_pixels) &
         call fatal_error(error, "invalid size: '"//text//"' is outside 64..4096"//rng)
   end subroutine parse_size

   !> The --frames directory must exist.
   subroutine check_frames_dir(dir, error)
      character(len=*), intent(in) :: dir               !! directory
      type(error_t), allocatable, intent(out) :: error  !! refused
      if (len(dir) == 0) then
         call fatal_error(error, 'invalid frames: empty directory name')
      else if (path_kind(dir) /= path_directory .and. &
               path_kind(dir//'/.') /= path_directory) then
         call fatal_error(error, "invalid frames: '"//dir//"' is not an existing directory")
      end if
   end subroutine check_frames_dir

   !> Read the samples of a simulate file; refuse other files.
   subroutine read_track(path, field, tr, error)
      character(len=*), intent(in) :: path              !! simulate file
      character(len=*), intent(in) :: field             !! 'input' or 'overlay'
      type(track_t), intent(out) :: tr                  !! its samples
      type(error_t), allocatable, intent(out) :: error  !! refused
      type(h5file_t) :: h5
      tr%path = path
      select case (path_kind(path, .true.))
      case (path_missing)
         call fatal_error(error, 'invalid '//field//": '"//path//"' does not exist")
         return
      case (path_directory)
         call fatal_error(error, 'invalid '//field//": '"//path//"' is a directory")
         return
      end select
      if (.not. is_hdf5(path)) then
         call fatal_error(error, 'invalid '//field//": '"//path//"' is not an HDF5 file")
         return
      end if
      call register_input(path)   ! the GIF or a frame never replaces it
      call h5%open(path, 'r', error)
      if (allocated(error)) then
         error%message = 'invalid '//field//': '//error%message
         return
      end if
      if (.not. h5%exists('/trajectory/q')) then
         call h5%close()
         call fatal_error(error, 'invalid '//field//": '"//path//"' is not a dpend simulate "// &
                          'file (no /trajectory/q)')
         return
      end if
      ! the samples (t, q and the figure) must fit the memory before anything is read
      call check_track_size(error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', tr%t, error)
      if (.not. allocated(error)) call check_times(tr%t, error)
      if (.not. allocated(error)) call check_coordinates(error)
      if (.not. allocated(error)) call read_figure(h5, tr%t, tr%fig, error)
      if (.not. allocated(error)) then
         if (h5%attr_exists('/', 'method')) then
            call h5%readattr('/', 'method', tr%method, error)
         else
            tr%method = '?'
         end if
      end if
      if (.not. allocated(error)) call read_run_facts(h5, tr, error)
      call h5%close()
      if (allocated(error)) error%message = 'invalid '//field//": '"//path//"': "// &
                                            error%message
   contains
      !> The samples the file declares, before anything is read: what the track
      !> keeps (t, q and the figure, a copy while reading) must fit the available
      !> memory. Each read is also checked by dpend_hdf5.
      subroutine check_track_size(err)
         type(error_t), allocatable, intent(out) :: err
         integer, allocatable :: dt(:), dq(:)
         call h5%shape('/trajectory/t', dt, err)
         if (allocated(err)) return
         if (size(dt) /= 1) then
            call fatal_error(err, '/trajectory/t is not 1-D')
            return
         end if
         call h5%shape('/trajectory/q', dq, err)
         if (allocated(err)) return
         if (size(dq) /= 2) then
            call fatal_error(err, '/trajectory/q is not (samples, coordinates)')
            return
         end if
         call check_memory('input', 8.0_dp*real(dt(1), dp)*(1.0_dp + 10.0_dp* &
                           real(dq(1), dp)), "the samples of '"//path//"'", &
                           'animate a shorter trajectory', err)
      end subroutine check_track_size
      !> q: one column per coordinate, a row per sample, finite and within the
      !> documented range (|q| <= 1e6); a `links` attribute, where the file has one,
      !> counts its columns.
      subroutine check_coordinates(err)
         type(error_t), allocatable, intent(out) :: err
         real(dp), allocatable :: q(:, :)
         integer :: links
         call h5%read('/trajectory/q', q, err)
         if (allocated(err)) return
         if (size(q, 2) /= size(tr%t) .or. size(q, 1) < 1) then
            call fatal_error(err, '/trajectory/q and /trajectory/t differ in length')
         else if (.not. all(ieee_is_finite(q))) then
            call fatal_error(err, 'non-finite samples in /trajectory/q')
         else if (maxval(abs(q)) > max_angle) then
            call fatal_error(err, '/trajectory/q holds '//sci(maxval(abs(q)))// &
                             ' (accepted: |q| <= '//sci(max_angle)//')')
         else if (h5%attr_exists('/', 'links')) then
            call h5%readattr('/', 'links', links, err)
            if (.not. allocated(err) .and. links /= size(q, 1)) &
               call fatal_error(err, 'links = '//to_str(links)//' does not match the '// &
                                to_str(size(q, 1))//' columns of /trajectory/q')
         end if
      end subroutine check_coordinates
   end subroutine read_track

   !> Sample times: finite, strictly increasing, within the documented |t| <= 1e9 s.
   subroutine check_times(t, error)
      real(dp), intent(in) :: t(:)                      !! sample times [s]
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      integer :: k
      if (size(t) < 1) then
         call fatal_error(error, '/trajectory/t holds no sample')
         return
      end if
      if (.not. all(ieee_is_finite(t))) then
         call fatal_error(error, 'non-finite samples in /trajectory/t')
         return
      end if
      do k = 2, size(t)
         if (.not. (t(k) > t(k - 1))) then
            call fatal_error(error, 'time does not increase at sample '//to_str(k)//' (t = ' &
                             //sci(t(k - 1))//', '//sci(t(k))//' s; a trajectory has ' &
                             //'strictly increasing t)')
            return
         end if
      end do
      if (maxval(abs(t)) > max_time) call fatal_error(error, '/trajectory/t holds ' &
         //sci(maxval(abs(t)))//' s (accepted: |t| <= '//sci(max_time)//' s)')
   end subroutine check_times

   !> The natural time unit of the file's model from its attributes: √(l1/g) from l
   !> (the first link) and g, else √(l0/g) from l0 and g; each read checked, finite
   !> and positive, else 0 (not recorded: --time-unit natural is then refused).
   subroutine read_natural_unit(h5, tr)
      type(h5file_t), intent(inout) :: h5   !! the open simulate file
      type(track_t), intent(inout) :: tr    !! tr%natural, tr%natural_name set
      real(dp), allocatable :: l(:)
      real(dp) :: g, l0
      type(error_t), allocatable :: err
      tr%natural = 0.0_dp
      tr%natural_name = ''
      if (.not. h5%attr_exists('/', 'g')) return
      call h5%readattr('/', 'g', g, err)
      if (allocated(err)) return
      if (.not. (ieee_is_finite(g) .and. g > 0.0_dp)) return
      if (h5%attr_exists('/', 'l')) then
         call h5%readattr('/', 'l', l, err)
         if (allocated(err)) return
         if (size(l) < 1) return
         l0 = l(1)
         tr%natural_name = 'sqrt(l1/g)'
      else if (h5%attr_exists('/', 'l0')) then
         call h5%readattr('/', 'l0', l0, err)
         if (allocated(err)) return
         tr%natural_name = 'sqrt(l0/g)'
      else
         return
      end if
      if (.not. (ieee_is_finite(l0) .and. l0 > 0.0_dp)) return
      if (.not. (ieee_is_finite(l0/g) .and. l0/g > 0.0_dp)) return
      tr%natural = sqrt(l0/g)
   end subroutine read_natural_unit

   !> The run's facts for the labels and the title (method, dt, the initial state, the
   !> body, masses, lengths, g: their texts in tr%settings, missing or unreadable ones
   !> '?') and each link's point mass (tr%bob: com_i / l_i where inertia_i = 0, from
   !> the attributes com<i>, inertia<i> and l, each checked finite, l_i > 0, 0 <=
   !> com_i <= 1e6 l_i; else no bob). A file from elsewhere: nothing here is trusted
   !> beyond a label, and a label that cannot be read says '?'.
   subroutine read_run_facts(h5, tr, error)
      type(h5file_t), intent(inout) :: h5               !! the open simulate file
      type(track_t), intent(inout) :: tr                !! method read; facts set
      type(error_t), allocatable, intent(inout) :: error  !! unchanged (labels only)
      real(dp), allocatable :: l(:)
      real(dp) :: com, inertia
      integer :: i, links
      tr%settings(1) = 'method '//tr%method
      tr%settings(2) = 'dt '//scalar_text('dt')//' s'
      tr%settings(3) = 'q0 '//array_text('q0')//' rad'
      tr%settings(4) = 'qdot0 '//array_text('qdot0')//' rad/s'
      tr%settings(5) = 'body '//body_text()
      tr%settings(6) = 'm '//array_text('m')//' kg'
      tr%settings(7) = 'l '//array_text('l')//' m'
      tr%settings(8) = 'g '//scalar_text('g')//' m/s^2'
      tr%run_text = tr%method//', dt '//scalar_text('dt')//' s'
      call read_natural_unit(h5, tr)
      links = tr%fig%n_points
      allocate (tr%bob(max(links, 1)))
      tr%bob = -1.0_dp
      if (tr%fig%style /= 'rods' .or. .not. h5%attr_exists('/', 'l')) return
      call h5%readattr('/', 'l', l, error)
      if (allocated(error)) then
         deallocate (error)
         return
      end if
      if (size(l) /= links) return
      do i = 1, links
         if (.not. (h5%attr_exists('/', 'com'//to_str(i)) .and. &
                    h5%attr_exists('/', 'inertia'//to_str(i)))) cycle
         call h5%readattr('/', 'com'//to_str(i), com, error)
         if (.not. allocated(error)) call h5%readattr('/', 'inertia'//to_str(i), inertia, error)
         if (allocated(error)) then
            deallocate (error)
            cycle
         end if
         if (.not. (ieee_is_finite(com) .and. ieee_is_finite(l(i)))) cycle
         if (inertia == 0.0_dp .and. l(i) > 0.0_dp .and. com >= 0.0_dp .and. &
             com <= 1e6_dp*l(i)) tr%bob(i) = com/l(i)
      end do
   contains
      function scalar_text(name) result(t)
         character(len=*), intent(in) :: name
         character(len=:), allocatable :: t
         real(dp) :: x
         type(error_t), allocatable :: err
         t = '?'
         if (.not. h5%attr_exists('/', name)) return
         call h5%readattr('/', name, x, err)
         if (.not. allocated(err)) t = sci(x, 6)
      end function scalar_text
      function array_text(name) result(t)
         character(len=*), intent(in) :: name
         character(len=:), allocatable :: t
         real(dp), allocatable :: x(:)
         type(error_t), allocatable :: err
         integer :: k
         t = '?'
         if (.not. h5%attr_exists('/', name)) return
         call h5%readattr('/', name, x, err)
         if (allocated(err)) return   ! (then x may not be allocated: a test of its own)
         if (size(x) == 0 .or. size(x) > 32) return
         t = sci(x(1), 6)
         do k = 2, size(x)
            t = t//','//sci(x(k), 6)
         end do
      end function array_text
      !> The links' body in a few words: 'uniform rods' (a file of links without the
      !> attribute body: the default), 'point masses', or the attribute's words
      !> before its parenthesis.
      function body_text() result(t)
         character(len=:), allocatable :: t
         integer :: p
         if (.not. h5%attr_exists('/', 'body')) then
            t = '?'
            if (tr%fig%style == 'rods') t = 'uniform rods'
            return
         end if
         t = string_text('body')
         p = index(t, ' on massless rods')
         if (p == 0) p = index(t, ' (')
         if (p > 1) t = t(:p - 1)
      end function body_text
      function string_text(name) result(t)
         character(len=*), intent(in) :: name
         character(len=:), allocatable :: t, v
         type(error_t), allocatable :: err
         t = '?'
         if (.not. h5%attr_exists('/', name)) return
         call h5%readattr('/', name, v, err)
         if (.not. allocated(err)) t = printable(v(:min(len(v), 40)))
      end function string_text
   end subroutine read_run_facts

   !> The animation's title and the labels of its two files: 'sim.h5 (rk4, dt 0.001
   !> s)'; with an overlay the title names both files and, on a second line, in what
   !> the runs differ (`run_differences`).
   subroutine animation_labels(cfg, a, b, overlay, title, label1, label2)
      type(animate_config_t), intent(in) :: cfg          !! the files' names
      type(track_t), intent(in) :: a, b                  !! their tracks (b: overlay)
      logical, intent(in) :: overlay                     !! b is drawn
      character(len=:), allocatable, intent(out) :: title, label1, label2
      label1 = base_name(cfg%input)//' ('//a%run_text//')'
      label2 = ''
      title = figure_title(a)//': '//label1
      if (overlay) then
         label2 = base_name(cfg%overlay)//' ('//b%run_text//')'
         title = figure_title(a)//': '//base_name(cfg%input)//' and '// &
                 base_name(cfg%overlay)//new_line('a')// &
                 run_differences(a, b, title_chars(cfg))
      end if
   end subroutine animation_labels

   !> In what two runs differ, by the settings read (read_run_facts): 'differ in dt
   !> (0.001 s, 0.0005 s)'; or 'the same method, dt, initial state, body, m, l, g'.
   !> Longer than `max_chars` (what the title's width holds), the names alone: 'they
   !> differ in body, m (in full on stdout)', the summary giving them in full.
   function run_differences(a, b, max_chars) result(s)
      type(track_t), intent(in) :: a, b   !! the input's and the overlay's tracks
      integer, intent(in) :: max_chars    !! the longest line the title shows
      character(len=:), allocatable :: s
      character(len=:), allocatable :: name, names
      integer :: k, sp
      s = ''
      names = ''
      do k = 1, size(a%settings)
         if (a%settings(k) == b%settings(k)) cycle
         sp = index(a%settings(k), ' ')
         name = a%settings(k)(:sp - 1)
         if (len(s) > 0) s = s//'; '
         if (len(names) > 0) names = names//', '
         s = s//name//' ('//trim(a%settings(k)(sp + 1:))//' | '// &
             trim(b%settings(k)(index(b%settings(k), ' ') + 1:))//')'
         names = names//name
      end do
      if (len('they differ in '//s) > max_chars) s = names//' (in full on stdout)'
      if (len(s) == 0) then
         s = 'the same method, dt, initial state, body, m, l and g'
      else
         s = 'they differ in '//s
      end if
   end function run_differences

   !> The characters a title line holds at the animation's width: the font is 2.4 %
   !> of the smaller side (animate.gp), a character about 0.64 of it wide (DejaVu Sans,
   !> measured: 46 characters take 450 of 640 px).
   pure integer function title_chars(cfg)
      type(animate_config_t), intent(in) :: cfg  !! the configuration
      real(dp) :: font
      font = max(7.0_dp, 0.024_dp*real(min(cfg%width, cfg%height), dp))
      title_chars = int(0.9_dp*real(cfg%width, dp)/(0.64_dp*font))
   end function title_chars

   !> The figure's reach: the largest |x| or |y| of its anchor and points [m].
   pure real(dp) function reach(tr)
      type(track_t), intent(in) :: tr  !! the track
      reach = max(maxval(abs(tr%fig%anchor)), maxval(abs(tr%fig%points)))
   end function reach

   !> 'double pendulum', 'chain of 5 links', 'elastic pendulum': what the figure shows.
   pure function figure_title(tr) result(s)
      type(track_t), intent(in) :: tr  !! the track
      character(len=:), allocatable :: s
      if (tr%fig%style == 'spring') then
         s = 'elastic pendulum'
         return
      end if
      select case (tr%fig%n_points)
      case (1); s = 'compound pendulum'
      case (2); s = 'double pendulum'
      case (3); s = 'triple pendulum'
      case default; s = 'chain of '//to_str(tr%fig%n_points)//' links'
      end select
   end function figure_title

   !> One column per frame: the anchor (x, y), the points (x, y each) and, with
   !> `with_forces`, the forces (x, y each) at times `tf`.
   subroutine frame_table(tr, tf, tab, with_forces)
      type(track_t), intent(in) :: tr          !! the track
      real(dp), intent(in) :: tf(:)            !! frame times [s]
      real(dp), intent(out) :: tab(:, :)       !! (2 (1 + P [+ K]), frames)
      logical, intent(in) :: with_forces       !! include the forces
      real(dp), allocatable :: an(:, :), pts(:, :, :), fs(:, :, :)
      integer :: p, k
      p = tr%fig%n_points; k = tr%fig%n_forces
      allocate (an(2, size(tf)), pts(2, p, size(tf)), fs(2, k, size(tf)))
      call resample_figure(tr%fig, tf, an, pts, fs)
      tab(1:2, :) = an
      tab(3:2 + 2*p, :) = reshape(pts, [2*p, size(tf)])
      if (with_forces) tab(3 + 2*p:2 + 2*p + 2*k, :) = reshape(fs, [2*k, size(tf)])
   end subroutine frame_table

   !> The last point of the figure (the tip, the bob) at times `tt`.
   subroutine trail_table(tr, tt, tab)
      type(track_t), intent(in) :: tr          !! the track
      real(dp), intent(in) :: tt(:)            !! times [s]
      real(dp), intent(out) :: tab(:, :)       !! (2, times)
      real(dp), allocatable :: an(:, :), pts(:, :, :), fs(:, :, :)
      integer :: p
      p = tr%fig%n_points
      allocate (an(2, size(tt)), pts(2, p, size(tt)), fs(2, tr%fig%n_forces, size(tt)))
      call resample_figure(tr%fig, tt, an, pts, fs)
      tab = pts(:, p, :)
   end subroutine trail_table

   !> Name of PNG frame i in dir.
   pure function frame_name(dir, i) result(path)
      character(len=*), intent(in) :: dir  !! directory
      integer, intent(in) :: i             !! frame number (1-based)
      character(len=:), allocatable :: path
      character(len=16) :: buf
      write (buf, '(i4.4)') i
      path = dir//'/frame_'//trim(buf)//'.png'
   end function frame_name

   !> Read, check, resample, draw and write the animation.
   !> The error's kind says whether the input was refused (nothing written) or
   !> the run started and failed (exit status 1).
   subroutine run_animate(cfg, summary, error)
      type(animate_config_t), intent(in) :: cfg              !! the configuration
      character(len=:), allocatable, intent(out) :: summary  !! what was written
      type(error_t), allocatable, intent(out) :: error       !! what went wrong
      logical :: failed
      call run_animate_body(cfg, summary, error, failed)
      if (allocated(error) .and. failed) call run_failure(error)
   end subroutine run_animate

   !> Read, check, resample, draw and write. `error` with `failed` false: refused
   !> input, nothing written; with `failed` true: the run failed (nothing written
   !> either: temporary files are removed).
   subroutine run_animate_body(cfg, summary, error, failed)
      type(animate_config_t), intent(in) :: cfg         !! the configuration
      character(len=:), allocatable, intent(out) :: summary  !! what was written
      type(error_t), allocatable, intent(out) :: error  !! what went wrong
      logical, intent(out) :: failed                    !! the run started and failed
      type(track_t) :: a, b
      type(output_t) :: out
      type(plan_t) :: plan
      type(temp_files_t) :: tmp
      real(dp) :: span, lim, fmax, npm
      real(dp), allocatable :: tf(:), ttr(:), pa(:, :), pb(:, :), qa(:, :), qb(:, :)
      character(len=:), allocatable :: script, title, label1, label2, errlog
      type(arg_t) :: argv(11)
      integer :: i, stat, nb
      logical :: overlay
      failed = .false.
      summary = ''
      overlay = len(cfg%overlay) > 0
      call read_track(cfg%input, 'input', a, error)
      if (allocated(error)) return
      span = a%t(size(a%t)) - a%t(1)
      if (overlay) then
         call read_track(cfg%overlay, 'overlay', b, error)
         if (allocated(error)) return
         if (b%t(1) > a%t(1) + 1e-9_dp*max(1.0_dp, abs(a%t(1)))) then
            call fatal_error(error, "invalid overlay: '"//cfg%overlay//"' starts at t = "// &
                             sci(b%t(1))//' s, after the input ('//sci(a%t(1))//' s)')
            return
         end if
         span = min(span, b%t(size(b%t)) - a%t(1))
      end if
      if (trim(cfg%time_unit) == 'natural' .and. .not. (a%natural > 0.0_dp)) then
         call fatal_error(error, "invalid time_unit: natural, but '"//printable(cfg%input)// &
                          "' records no l1 (or l0) and g of its model (accepted: s) " &
                          //'[--time-unit]')
         return
      end if
      call plan_frames(cfg, a%t(1), span, overlay, plan, error)
      if (allocated(error)) return
      nb = 0
      if (overlay) nb = b%fig%n_points
      call check_work(cfg, plan, a%fig%n_points + a%fig%n_forces, nb, error)
      if (allocated(error)) return
      script = find_script('plot/animate.gp')
      if (len(script) == 0) then
         failed = .true.
         call fatal_error(error, 'scripts/plot/animate.gp not found (set DPEND_ROOT to the '// &
                          'dpend source tree)')
         return
      end if
      call out%begin(cfg%output, cfg%force, error)
      if (allocated(error)) return
      ! from here on, a failure is a failed run
      failed = .true.
      allocate (tf(plan%nframes), ttr(plan%nrows))
      tf = a%t(1) + plan%dtf*[(real(i, dp), i=0, plan%nframes - 1)]
      ttr = a%t(1) + plan%ht*[(real(i, dp), i=0, plan%nrows - 1)]
      ttr = min(ttr, a%t(1) + span)
      ! the frames (anchor, points, forces) and the trail (the last point)
      allocate (pa(2*(1 + a%fig%n_points + a%fig%n_forces), plan%nframes), qa(2, plan%nrows))
      call frame_table(a, tf, pa, .true.)
      call trail_table(a, ttr, qa)
      if (overlay) then
         allocate (pb(2*(1 + b%fig%n_points), plan%nframes), qb(2, plan%nrows))
         call frame_table(b, tf, pb, .false.)
         call trail_table(b, ttr, qb)
      end if
      lim = reach(a)
      if (overlay) lim = max(lim, reach(b))
      if (.not. (lim > 0.0_dp)) lim = 1.0_dp
      fmax = 0.0_dp
      npm = 0.0_dp
      if (cfg%reactions) call reaction_scale(a, pa, lim, fmax, npm)
      call make_temp_files(cfg, tmp, error)
      if (.not. allocated(error)) then
         ! numbers only: file names reach gnuplot as arguments
         call write_params(tmp%params, cfg, a, b, overlay, plan, lim, fmax, npm, stat)
         if (stat == 0) call write_frames(tmp%frames_dat, tf, pa, pb, overlay, stat)
         if (stat == 0) call write_frames(tmp%trail_dat, ttr, qa, qb, overlay, stat)
         if (stat /= 0) call fatal_error(error, "cannot write temporary files in '"// &
                                         directory_of(cfg%output)//"'")
      end if
      if (allocated(error)) then
         call remove_temp_files(tmp, plan%nframes)
         call out%discard()
         return
      end if
      call animation_labels(cfg, a, b, overlay, title, label1, label2)
      ! component by component (gfortran 12 mangles an array constructor of
      ! structure constructors with deferred-length components)
      argv(1)%s = 'gnuplot'; argv(2)%s = '-c'; argv(3)%s = script; argv(4)%s = tmp%params
      argv(5)%s = tmp%frames_dat; argv(6)%s = tmp%trail_dat; argv(7)%s = out%temp
      argv(8)%s = title; argv(9)%s = label1; argv(10)%s = label2; argv(11)%s = tmp%stem
      ! gnuplot's messages go to a file, shown only when it fails
      if (make_temp_file(directory_of(cfg%output)//'/.'//base_name(cfg%output)// &
                         '.gnuplot-', errlog) /= 0) errlog = ''
      if (len(errlog) > 0) then
         call run_program(argv, stat, error, stderr_path=errlog)
      else
         call run_program(argv, stat, error)
      end if
      if (.not. allocated(error) .and. stat /= 0) then
         if (len(errlog) > 0) call echo_to_stderr(errlog, 65536)
         call fatal_error(error, 'gnuplot failed (exit status '//to_str(stat)//', '//script//')')
      end if
      if (len(errlog) > 0) nb = remove_file(errlog)
      if (.not. allocated(error)) call out%commit(error)
      if (.not. allocated(error) .and. len(tmp%stem) > 0) &
         call move_frames(cfg, tmp%stem, plan%nframes, error)
      call out%explain(error)
      call remove_temp_files(tmp, plan%nframes)
      call out%discard()
      if (allocated(error)) return
      failed = .false.
      summary = "wrote '"//cfg%output//"': "//to_str(plan%nframes)//' frames, '// &
                sci(real(plan%nframes, dp)/real(cfg%fps, dp), 4)//' s at '//to_str(cfg%fps)// &
                ' fps, t = '
      ! the simulated times in the clock's unit (natural: that first, then s)
      if (trim(cfg%time_unit) == 'natural') summary = summary// &
         sci(tf(1)/a%natural, 4)//' .. '//sci(tf(plan%nframes)/a%natural, 4)//' '// &
         trim(a%natural_name)//' = '
      summary = summary//sci(tf(1), 4)//' .. '//sci(tf(plan%nframes), 4)//' s'
      if (trim(cfg%time_unit) /= 'natural' .and. a%natural > 0.0_dp) summary = summary// &
         ' = '//sci(tf(1)/a%natural, 4)//' .. '//sci(tf(plan%nframes)/a%natural, 4)//' '// &
         trim(a%natural_name)
      if (len(cfg%frames) > 0) summary = summary//"; PNG frames in '"//cfg%frames//"'"
      if (overlay) summary = summary//'; '//run_differences(a, b, huge(1))
      if (cfg%reactions .and. npm > 0) summary = summary//'; reaction arrows: 1 m = '// &
                                                 sci(npm, 4)//' N'
   end subroutine run_animate_body

   !> The frames and the trail of an animation of `span` seconds from `t0`, or the
   !> refusal of a --duration past the end (or of more than `max_frames` frames).
   subroutine plan_frames(cfg, t0, span, overlay, plan, error)
      type(animate_config_t), intent(in) :: cfg         !! the configuration
      real(dp), intent(in) :: t0                        !! first sample time [s]
      real(dp), intent(in) :: span                      !! time the files cover [s]
      logical, intent(in) :: overlay                    !! two files
      type(plan_t), intent(out) :: plan                 !! the frames and trail
      type(error_t), allocatable, intent(out) :: error  !! refused
      real(dp) :: dtf
      integer :: nframes
      dtf = cfg%speed/real(cfg%fps, dp)
      if (cfg%duration > 0.0_dp) then
         nframes = max(1, nint(cfg%duration*real(cfg%fps, dp)))
         if (real(nframes - 1, dp)*dtf > span*(1 + 1e-9_dp) + 1e-12_dp) then
            call fatal_error(error, 'invalid duration: '//sci(cfg%duration)//' s at speed '// &
                             sci(cfg%speed)//' shows t up to '// &
                             sci(t0 + real(nframes - 1, dp)*dtf)//' s; the trajectory'// &
                             trim(merge(' (both files)', '             ', overlay))// &
                             ' ends at t = '//sci(t0 + span)//' s (at most '// &
                             sci(span/cfg%speed)//' s at this speed)')
            return
         end if
      else
         if (span/dtf > real(max_frames, dp)) then
            call fatal_error(error, 'invalid duration: the whole trajectory ('//sci(span)// &
                             ' s at speed '//sci(cfg%speed)//', '//to_str(cfg%fps)// &
                             ' fps) gives '//sci(aint(span/dtf) + 1)//' frames; at most '// &
                             to_str(max_frames)//' (use --duration, a larger --speed or a '// &
                             'smaller --fps)')
            return
         end if
         nframes = int(span/dtf + 1e-9_dp) + 1
      end if
      plan%nframes = nframes
      plan%dtf = dtf
      ! the trail: m samples per frame interval, ntr samples long
      plan%m = max(1, min(ceiling(dtf/trail_step), max_trail_rows/nframes))
      plan%ht = dtf/real(plan%m, dp)
      plan%ntr = max(1, nint(min(trail_span/plan%ht, real(max_trail_rows, dp))))
      plan%nrows = (nframes - 1)*plan%m + 1
   end subroutine plan_frames

   !> Before anything is written: no PNG frame may exist without --force, the rods
   !> and arrows drawn (`na` + `nb` a frame) and the memory are bounded, and the
   !> --frames directory must take files (a read-only file system: refused).
   subroutine check_work(cfg, plan, na, nb, error)
      type(animate_config_t), intent(in) :: cfg         !! the configuration
      type(plan_t), intent(in) :: plan                  !! the frames and trail
      integer, intent(in) :: na                         !! segments and arrows of the input
      integer, intent(in) :: nb                         !! segments of the overlay
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: probe
      integer :: i, err
      if (len(cfg%frames) > 0) then
         do i = 1, plan%nframes
            call check_output_path(frame_name(cfg%frames, i), cfg%force, error, '--frames')
            if (allocated(error)) return
         end do
      end if
      if (real(plan%nframes, dp)*real(na + nb, dp) > real(max_drawn_links, dp)) then
         call fatal_error(error, 'invalid duration: '//to_str(plan%nframes)//' frames of '// &
                          to_str(na + nb)//' segments and arrows draw '// &
                          sci(real(plan%nframes, dp)*real(na + nb, dp))//'; at most '// &
                          sci(real(max_drawn_links, dp))//' (use --duration, a larger '// &
                          '--speed or a smaller --fps)')
         return
      end if
      call check_memory('duration', 8.0_dp*(real(plan%nframes, dp)*6.0_dp* &
                        real(na + nb + 2, dp) + real(plan%nrows, dp)*4.0_dp* &
                        real(na + nb + 2, dp)), &
                        'the frames and trail', 'use --duration or a smaller --fps', error)
      if (allocated(error)) return
      if (len(cfg%frames) > 0) then
         err = make_temp_file(cfg%frames//'/.dpend-frames-probe-', probe)
         if (err /= 0) then
            call fatal_error(error, "invalid frames: cannot write into '"//cfg%frames// &
                             "' ("//errno_text(err)//')')
            return
         end if
         err = remove_file(probe)
      end if
   end subroutine check_work

   !> Reaction arrows: the longest 0.3 to 0.6 `lim` (the figure's reach), the scale
   !> `npm` a round number of N/m (0 without forces); `fmax` the largest force [N].
   subroutine reaction_scale(a, pa, lim, fmax, npm)
      type(track_t), intent(in) :: a         !! the input's track
      real(dp), intent(in) :: pa(:, :)       !! its frame table (`frame_table`)
      real(dp), intent(in) :: lim            !! the figure's reach [m]
      real(dp), intent(out) :: fmax          !! largest force [N]
      real(dp), intent(out) :: npm           !! arrow scale [N/m]
      real(dp) :: e
      integer :: i, j
      fmax = 0.0_dp
      npm = 0.0_dp
      do i = 1, size(pa, 2)
         do j = 1, a%fig%n_forces
            fmax = max(fmax, hypot(pa(2*(a%fig%n_points + j) + 1, i), &
                                   pa(2*(a%fig%n_points + j) + 2, i)))
         end do
      end do
      if (fmax > 0.0_dp) then
         e = log10(fmax) - log10(0.6_dp*lim)
         ! (a power of ten within range: forces of 1e-310 N would make it 0, 1/10^311)
         npm = 10.0_dp**min(max(floor(e), -300), 300)
         if (fmax/npm > 5.0_dp*0.6_dp*lim) then
            npm = 10*npm
         else if (fmax/npm > 2.0_dp*0.6_dp*lim) then
            npm = 5*npm
         else if (fmax/npm > 0.6_dp*lim) then
            npm = 2*npm
         end if
      end if
   end subroutine reaction_scale

   !> The temporary files gnuplot reads (parameters, frames, trail), beside the
   !> output, and the stem of its PNG frames in the --frames directory.
   subroutine make_temp_files(cfg, tmp, error)
      type(animate_config_t), intent(in) :: cfg         !! the configuration
      type(temp_files_t), intent(out) :: tmp            !! the files made
      type(error_t), allocatable, intent(out) :: error  !! one could not be made
      character(len=:), allocatable :: dir
      dir = directory_of(cfg%output)
      tmp%params = new_temp(dir//'/.'//base_name(cfg%output)//'.params-', tmp%made_params)
      if (tmp%made_params) tmp%frames_dat = new_temp(dir//'/.'//base_name(cfg%output)// &
                                                     '.frames-', tmp%made_frames)
      if (tmp%made_frames) tmp%trail_dat = new_temp(dir//'/.'//base_name(cfg%output)// &
                                                    '.trail-', tmp%made_trail)
      tmp%stem = ''
      if (tmp%made_trail .and. len(cfg%frames) > 0) then
         tmp%stem = new_temp(cfg%frames//'/.dpend-frames-', tmp%made_stem)
         if (.not. tmp%made_stem) call fatal_error(error, "cannot write into '"// &
                                                   cfg%frames//"' (--frames)")
      end if
      if (.not. tmp%made_trail .and. .not. allocated(error)) &
         call fatal_error(error, "cannot create temporary files in '"//dir//"'")
   contains
      !> A new empty temporary file named prefix + XXXXXX.
      function new_temp(prefix, made) result(path)
         character(len=*), intent(in) :: prefix
         logical, intent(out) :: made
         character(len=:), allocatable :: path
         made = make_temp_file(prefix, path) == 0
         if (.not. made) path = ''
      end function new_temp
   end subroutine make_temp_files

   !> Remove the temporary files (and PNG frames not moved into place).
   subroutine remove_temp_files(tmp, nframes)
      type(temp_files_t), intent(in) :: tmp  !! the files made
      integer, intent(in) :: nframes         !! frames gnuplot may have written
      character(len=8) :: buf
      integer :: j, r
      if (tmp%made_params) r = remove_file(tmp%params)
      if (tmp%made_frames) r = remove_file(tmp%frames_dat)
      if (tmp%made_trail) r = remove_file(tmp%trail_dat)
      if (tmp%made_stem) then
         do j = 1, nframes
            write (buf, '(i4.4)') j
            if (path_kind(tmp%stem//'-'//trim(buf)//'.png') /= path_missing) &
               r = remove_file(tmp%stem//'-'//trim(buf)//'.png')
         end do
         r = remove_file(tmp%stem)
      end if
   end subroutine remove_temp_files

   !> Move the PNG frames gnuplot wrote (STEM-0001.png …) into place.
   subroutine move_frames(cfg, stem, nframes, error)
      type(animate_config_t), intent(in) :: cfg           !! the configuration
      character(len=*), intent(in) :: stem                !! their temporary stem
      integer, intent(in) :: nframes                      !! frames written
      type(error_t), allocatable, intent(inout) :: error  !! one could not be moved
      character(len=:), allocatable :: from, to
      character(len=8) :: buf
      integer :: j, r
      do j = 1, nframes
         write (buf, '(i4.4)') j
         from = stem//'-'//trim(buf)//'.png'
         to = frame_name(cfg%frames, j)
         r = sync_path(from)
         if (r == 0) then
            if (cfg%force) then
               r = move_replace(from, to)
            else
               r = move_noreplace(from, to)
            end if
         end if
         if (r /= 0) then
            call fatal_error(error, "cannot write '"//to//"': "//errno_text(r)// &
                             ' (the GIF is written)')
            return
         end if
      end do
   end subroutine move_frames

   !> The parameters gnuplot reads (numbers only: file names reach it as arguments).
   subroutine write_params(path, cfg, a, b, overlay, plan, lim, fmax, npm, stat)
      character(len=*), intent(in) :: path           !! the parameters file
      type(animate_config_t), intent(in) :: cfg      !! the configuration
      type(track_t), intent(in) :: a, b              !! the input and the overlay's tracks
      logical, intent(in) :: overlay                 !! b is drawn
      type(plan_t), intent(in) :: plan               !! the frames and trail
      real(dp), intent(in) :: lim                    !! the figure's reach [m]
      real(dp), intent(in) :: fmax                   !! largest force [N]
      real(dp), intent(in) :: npm                    !! arrow scale [N/m]
      integer, intent(out) :: stat                   !! iostat
      integer :: u, err, links2
      links2 = 0
      if (overlay) links2 = b%fig%n_points
      open (newunit=u, file=path, status='replace', action='write', iostat=stat)
      if (stat /= 0) return
      write (u, '(a, i0)', iostat=stat) 'links = ', a%fig%n_points
      write (u, '(a, i0)', iostat=stat) 'links2 = ', links2
      write (u, '(a, i0)', iostat=stat) 'nforces = ', a%fig%n_forces
      write (u, '(a, i0)', iostat=stat) 'spring = ', merge(1, 0, a%fig%style == 'spring')
      if (overlay) write (u, '(a, i0)', iostat=stat) 'spring2 = ', &
         merge(1, 0, b%fig%style == 'spring')
      write (u, '(a, i0)', iostat=stat) 'nframes = ', plan%nframes
      write (u, '(a, i0)', iostat=stat) 'nrows = ', plan%nrows
      write (u, '(a, i0)', iostat=stat) 'per_frame = ', plan%m
      write (u, '(a, i0)', iostat=stat) 'ntrail = ', plan%ntr
      write (u, '(a, i0)', iostat=stat) 'delay = ', max(1, nint(100.0_dp/real(cfg%fps, dp)))
      write (u, '(a, i0)', iostat=stat) 'width = ', cfg%width
      write (u, '(a, i0)', iostat=stat) 'height = ', cfg%height
      write (u, '(a, i0)', iostat=stat) 'overlay = ', merge(1, 0, overlay)
      write (u, '(a, i0)', iostat=stat) 'side = ', merge(1, 0, overlay .and. &
                                                          cfg%layout == 'side')
      ! where each link's point mass sits, as a fraction of the link (-1: none)
      write (u, '(a)', iostat=stat) 'array BOB['//to_str(size(a%bob))//'] = '//bobs(a%bob)
      if (overlay) write (u, '(a)', iostat=stat) 'array BOB2['//to_str(size(b%bob))// &
         '] = '//bobs(b%bob)
      write (u, '(a, i0)', iostat=stat) 'reactions = ', merge(1, 0, cfg%reactions .and. &
                                                               npm > 0)
      write (u, '(a, es24.16e3)', iostat=stat) 'lim = ', 1.08_dp*lim
      ! the scale the summary reports (below 1 N/m for light pendulums); 1 without arrows
      write (u, '(a, es24.16e3)', iostat=stat) 'newtons_per_m = ', merge(npm, 1.0_dp, npm > 0)
      write (u, '(a, es24.16e3)', iostat=stat) 'fmax = ', fmax
      ! the clock: in s (clock_unit 0), or also in sqrt(l1/g) (1) or sqrt(l0/g) (2),
      ! t/clock_seconds of it
      if (trim(cfg%time_unit) == 'natural' .and. a%natural > 0.0_dp) then
         write (u, '(a, i0)', iostat=stat) 'clock_unit = ', &
            merge(1, 2, a%natural_name == 'sqrt(l1/g)')
         write (u, '(a, es24.16e3)', iostat=stat) 'clock_seconds = ', a%natural
      else
         write (u, '(a, i0)', iostat=stat) 'clock_unit = ', 0
         write (u, '(a, es24.16e3)', iostat=stat) 'clock_seconds = ', 1.0_dp
      end if
      close (u, iostat=err)
      if (err /= 0) stat = err
   contains
      !> '[1.0, -1.0]': numbers only (the file is loaded by gnuplot).
      function bobs(x) result(t)
         real(dp), intent(in) :: x(:)
         character(len=:), allocatable :: t
         character(len=32) :: buf
         integer :: k
         t = '['
         do k = 1, size(x)
            write (buf, '(es24.16e3)') x(k)
            t = t//trim(adjustl(buf))//merge(',', ']', k < size(x))
         end do
         if (size(x) == 0) t = '[-1]'
      end function bobs
   end subroutine write_params

   !> Write rows t(i), pa(:, i) [, pb(:, i) with the overlay]: the frames or the trail.
   subroutine write_frames(path, t, pa, pb, overlay, stat)
      character(len=*), intent(in) :: path           !! file
      real(dp), intent(in) :: t(:)                   !! times [s]
      real(dp), intent(in) :: pa(:, :)               !! the input's columns
      real(dp), allocatable, intent(in) :: pb(:, :)  !! the overlay's (allocated with it)
      logical, intent(in) :: overlay                 !! pb is written too
      integer, intent(out) :: stat                   !! iostat
      real(dp), allocatable :: tab(:, :)
      if (.not. overlay) then
         call write_table(path, t, pa, stat)
         return
      end if
      allocate (tab(size(pa, 1) + size(pb, 1), size(t)))
      tab(1:size(pa, 1), :) = pa
      tab(size(pa, 1) + 1:, :) = pb
      call write_table(path, t, tab, stat)
   end subroutine write_frames

   !> Write rows t(i), cols(:, i).
   subroutine write_table(path, t, cols, stat)
      character(len=*), intent(in) :: path      !! file
      real(dp), intent(in) :: t(:)              !! first column
      real(dp), intent(in) :: cols(:, :)        !! next columns (ncol, n)
      integer, intent(out) :: stat              !! iostat
      integer :: u, i, err
      open (newunit=u, file=path, status='replace', action='write', iostat=stat)
      if (stat /= 0) return
      do i = 1, size(t)
         write (u, '(*(es16.8e3, :, 1x))', iostat=stat) t(i), cols(:, i)
         if (stat /= 0) exit
      end do
      close (u, iostat=err)
      if (stat == 0) stat = err
   end subroutine write_table
end module dpend_animate
