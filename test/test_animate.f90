!> `dpend animate` run as a process: the GIF it writes is parsed block by block
!> (header, logical screen, extensions, image descriptors, trailer) and its frame
!> count and size are checked against the options. Skipped when gnuplot is missing.
module test_animate
   use testing, only: unittest_t, new_unittest, check_true, error_t, fatal_error, &
                      skip_test, have_tool
   use test_cli, only: run_command, scratch_dir, read_text, dpend_binary
   use dpend_cli, only: to_str
   use dpend_kinds, only: dp
   use dpend_animate, only: animate_config_t, track_t, read_track, animation_labels
   implicit none
   private
   public :: collect_animate, gif_info

contains

   subroutine collect_animate(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('gif_frames_and_size', test_gif), &
               new_unittest('three_links', test_three_links), &
               new_unittest('refused_options', test_refused), &
               new_unittest('tidy_summary_quiet_gnuplot', test_tidy_summary), &
               new_unittest('overlay_labels_bobs_side', test_overlay_labels)]
   end subroutine collect_animate

   !> Two runs of point masses from q2 = 0 and 0.001 rad, and one of rods: each point
   !> mass is drawn as a bob at the end of its link (com_i / l_i = 1), a rod has none;
   !> the labels name each file with its method and step, the title says in what the
   !> runs differ (q0), or that they do not; --layout side draws the two side by side
   !> (1280 x 640 by default), and is refused without --overlay or with another name;
   !> rods against points: 'body (uniform rods | point masses)'.
   subroutine test_overlay_labels(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, title, label1, label2, text
      type(animate_config_t) :: cfg
      type(track_t) :: a, b, r
      integer :: stat, n
      if (.not. have_tool('gnuplot')) then
         call skip_test('gnuplot not found')
         return
      end if
      dir = scratch_dir('animate-labels')
      stat = run_command(dir, 'simulate --body point --q1 0 --q2 0 --t-end 1 --output-dt '// &
                         '0.02 --output '//dir//'/pa.h5')
      stat = stat + run_command(dir, 'simulate --body point --q1 0 --q2 0.001 --t-end 1 '// &
                                '--output-dt 0.02 --output '//dir//'/pb.h5')
      stat = stat + run_command(dir, 'simulate --q1 0 --q2 0 --t-end 1 --output-dt 0.02 '// &
                                '--output '//dir//'/rod.h5')
      call check_true(error, stat == 0, 'three simulations')
      if (allocated(error)) return
      call read_track(dir//'/pa.h5', 'input', a, error)
      if (.not. allocated(error)) call read_track(dir//'/pb.h5', 'overlay', b, error)
      if (.not. allocated(error)) call read_track(dir//'/rod.h5', 'overlay', r, error)
      if (allocated(error)) return
      call check_true(error, size(a%bob) == 2 .and. all(abs(a%bob - 1.0_dp) < 1e-15_dp), &
                      'point masses: a bob at the end of each link')
      call check_true(error, all(r%bob < 0.0_dp), 'rods: no bob')
      cfg%input = dir//'/pa.h5'
      cfg%overlay = dir//'/pb.h5'
      call animation_labels(cfg, a, b, .true., title, label1, label2)
      call check_true(error, label1 == 'pa.h5 (rk4, dt 0.001 s)' .and. &
                      label2 == 'pb.h5 (rk4, dt 0.001 s)', 'labels: '//label1//'; '//label2)
      call check_true(error, index(title, 'pa.h5 and pb.h5') > 0 .and. &
                      index(title, 'they differ in q0 (0,0 rad | 0,0.001 rad)') > 0, &
                      'title: '//title)
      call animation_labels(cfg, a, a, .true., title, label1, label2)
      call check_true(error, index(title, 'the same method, dt') > 0, 'same runs: '//title)
      ! rods against point masses: the body in a few words (a rod file has no body
      ! attribute: the default); a title too wide for the frame names the setting only
      call animation_labels(cfg, r, a, .true., title, label1, label2)
      call check_true(error, index(title, 'they differ in body (uniform rods | point ' &
                      //'masses)') > 0, 'rods and points: '//title)
      cfg%width = 200
      call animation_labels(cfg, r, a, .true., title, label1, label2)
      call check_true(error, index(title, 'they differ in body (in full on stdout)') > 0, &
                      'a narrow title: '//title)
      cfg%width = 640
      call expect_gif(error, dir, '--overlay '//dir//'/pb.h5 --layout side --duration 0.4 '// &
                      '--fps 10', 'side.gif', 4, 1280, 640, 'pa.h5')
      stat = run_command(dir, 'animate '//dir//'/pa.h5 --layout side --output '//dir// &
                         '/x.gif')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. index(text, 'needs --overlay') > 0, &
                      'side without an overlay refused: '//text)
      stat = run_command(dir, 'animate '//dir//'/pa.h5 --overlay '//dir//'/pb.h5 '// &
                         '--layout sides --output '//dir//'/x.gif')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 2 .and. index(text, 'invalid layout') > 0, &
                      'an unknown layout refused: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_overlay_labels

   !> Parse the GIF file `path`: logical screen width and height, the number of
   !> images, and whether it is well formed up to its trailer (`why` says otherwise).
   subroutine gif_info(path, width, height, frames, why)
      character(len=*), intent(in) :: path
      integer, intent(out) :: width, height, frames
      character(len=:), allocatable, intent(out) :: why
      character(len=1), allocatable :: b(:)
      integer :: unit, stat, n, p, packed
      width = 0; height = 0; frames = 0; why = ''
      open (newunit=unit, file=path, access='stream', form='unformatted', status='old', &
            action='read', iostat=stat)
      if (stat /= 0) then
         why = 'cannot open '//path
         return
      end if
      inquire (unit=unit, size=n)
      allocate (b(n))
      read (unit, iostat=stat) b
      close (unit)
      if (stat /= 0 .or. n < 13) then
         why = 'short file'
         return
      end if
      if (transfer(b(1:6), repeat(' ', 6)) /= 'GIF89a' .and. &
          transfer(b(1:6), repeat(' ', 6)) /= 'GIF87a') then
         why = 'no GIF header'
         return
      end if
      width = u8(7) + 256*u8(8)
      height = u8(9) + 256*u8(10)
      packed = u8(11)
      p = 14                                          ! after the 13-byte header + screen
      if (iand(packed, 128) /= 0) p = p + 3*2**(iand(packed, 7) + 1)
      do
         if (p > n) then
            why = 'no trailer (0x3B)'
            return
         end if
         select case (u8(p))
         case (int(z'21'))                           ! extension: label, sub-blocks
            p = p + 2
            call skip_blocks()
         case (int(z'2C'))                           ! image descriptor
            if (p + 9 > n) exit
            packed = u8(p + 9)
            p = p + 10
            if (iand(packed, 128) /= 0) p = p + 3*2**(iand(packed, 7) + 1)
            p = p + 1                                 ! LZW minimum code size
            call skip_blocks()
            frames = frames + 1
         case (int(z'3B'))                           ! trailer
            return
         case default
            why = 'unexpected block 0x'//hex(u8(p))//' at byte '//to_str(p - 1)
            return
         end select
         if (len(why) > 0) return
      end do
      why = 'truncated image descriptor'
   contains
      integer function u8(i)
         integer, intent(in) :: i
         u8 = ichar(b(i))
      end function u8
      subroutine skip_blocks()
         do
            if (p > n) then
               why = 'truncated sub-blocks'
               return
            end if
            if (u8(p) == 0) then
               p = p + 1
               return
            end if
            p = p + 1 + u8(p)
         end do
      end subroutine skip_blocks
      function hex(i) result(s)
         integer, intent(in) :: i
         character(len=2) :: s
         write (s, '(z2.2)') i
      end function hex
   end subroutine gif_info

   !> Run animate on dir/sim.h5 (or dir/INPUT) with options and check the GIF's frame
   !> count and size.
   subroutine expect_gif(error, dir, options, name, frames, width, height, input)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: dir, options, name
      integer, intent(in) :: frames, width, height
      character(len=*), intent(in), optional :: input   !! simulate file in dir
      integer :: stat, w, h, k, n
      character(len=:), allocatable :: why, text, file
      if (allocated(error)) return
      file = 'sim.h5'
      if (present(input)) file = input
      stat = run_command(dir, 'animate '//dir//'/'//file//' --output '//dir//'/'//name// &
                         ' '//options)
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 0, '['//options//'] exit status 0, got '// &
                      to_str(stat)//': '//text)
      if (allocated(error)) return
      call gif_info(dir//'/'//name, w, h, k, why)
      call check_true(error, len(why) == 0, '['//options//'] well-formed GIF: '//why)
      call check_true(error, k == frames, '['//options//'] '//to_str(frames)// &
                      ' frames, got '//to_str(k))
      call check_true(error, w == width .and. h == height, '['//options//'] size '// &
                      to_str(width)//'x'//to_str(height)//', got '//to_str(w)//'x'//to_str(h))
   end subroutine expect_gif

   subroutine test_gif(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      integer :: stat
      if (.not. have_tool('gnuplot')) then
         call skip_test('gnuplot not found')
         return
      end if
      dir = scratch_dir('animate')
      ! 101 samples over 1 s
      stat = run_command(dir, 'simulate --t-end 1 --dt 1e-3 --save-every 10 --output '// &
                         dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate for animate')
      if (allocated(error)) return
      ! fps × duration frames: 10 × 0.8 = 8
      call expect_gif(error, dir, '--fps 10 --duration 0.8 --size 200x150', 'a.gif', 8, &
                      200, 150)
      ! slowed playback: 10 × 1.5 = 15 frames at t = 0, 0.05, ..., 0.7 s, with arrows
      call expect_gif(error, dir, '--fps 10 --duration 1.5 --speed 0.5 --size 96x64 '// &
                      '--reactions', 'b.gif', 15, 96, 64)
      ! the whole trajectory: floor(1 s × 5 fps / speed 1) + 1 = 6 frames, default size
      call expect_gif(error, dir, '--fps 5', 'c.gif', 6, 640, 640)
      ! an overlay and PNG frames
      call expect_gif(error, dir, '--fps 4 --overlay '//dir//'/sim.h5 --size 128x128 '// &
                      '--frames '//dir, 'd.gif', 5, 128, 128)
      block
         logical :: exists
         inquire (file=dir//'/frame_0005.png', exist=exists)
         call check_true(error, exists, 'PNG frame 5 written')
         inquire (file=dir//'/frame_0006.png', exist=exists)
         call check_true(error, .not. exists, 'no PNG frame 6')
      end block
   end subroutine test_gif

   !> A triple pendulum (simulate --links 3): frame count and size as for two links,
   !> with the reactions at the three joints, an overlay of a double pendulum, and
   !> PNG frames.
   subroutine test_three_links(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      integer :: stat
      logical :: exists
      if (.not. have_tool('gnuplot')) then
         call skip_test('gnuplot not found')
         return
      end if
      dir = scratch_dir('animate-3')
      ! 101 samples over 1 s of the triple pendulum released horizontally
      stat = run_command(dir, 'simulate --links 3 --q 0,0,0 --t-end 1 --dt 1e-3 '// &
                         '--save-every 10 --output '//dir//'/sim3.h5')
      call check_true(error, stat == 0, 'simulate --links 3 for animate')
      if (allocated(error)) return
      stat = run_command(dir, 'simulate --t-end 1 --dt 1e-3 --save-every 10 --output '// &
                         dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate (two links) for animate')
      if (allocated(error)) return
      ! fps × duration frames: 10 × 0.8 = 8, with the arrows at three joints
      call expect_gif(error, dir, '--fps 10 --duration 0.8 --size 200x150 --reactions', &
                      'a.gif', 8, 200, 150, 'sim3.h5')
      ! the whole trajectory: floor(1 s × 5 fps) + 1 = 6 frames, a double pendulum
      ! overlaid, PNG frames
      call expect_gif(error, dir, '--fps 5 --overlay '//dir//'/sim.h5 --size 128x96 '// &
                      '--frames '//dir, 'b.gif', 6, 128, 96, 'sim3.h5')
      if (allocated(error)) return
      inquire (file=dir//'/frame_0006.png', exist=exists)
      call check_true(error, exists, 'PNG frame 6 written')
      inquire (file=dir//'/frame_0007.png', exist=exists)
      call check_true(error, .not. exists, 'no PNG frame 7')
   end subroutine test_three_links

   !> Refused values: exit 2, one line, no GIF.
   subroutine test_refused(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      integer :: stat
      dir = scratch_dir('animate-bad')
      stat = run_command(dir, 'simulate --t-end 0.1 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate for animate')
      call refused('--fps 0', 'invalid fps')
      call refused('--fps 101', 'invalid fps')
      call refused('--size 10x10', 'invalid size')
      call refused('--speed 0', 'invalid speed')
      call refused('--duration 1000', 'invalid duration')
      call refused('--time-unit hours', "invalid time_unit: 'hours'")
   contains
      subroutine refused(options, needle)
         character(len=*), intent(in) :: options, needle
         character(len=:), allocatable :: text
         integer :: st, n
         logical :: exists
         if (allocated(error)) return
         st = run_command(dir, 'animate '//dir//'/sim.h5 --output '//dir//'/x.gif '//options)
         call read_text(dir//'/stderr', text, n)
         inquire (file=dir//'/x.gif', exist=exists)
         call check_true(error, st == 2 .and. n == 1 .and. index(text, needle) > 0 .and. &
                         .not. exists, '['//options//'] refused with "'//needle//'": '// &
                         to_str(st)//' '//text)
      end subroutine refused
   end subroutine test_refused

   !> The summary prints times to 4 significant digits (the whole 1 s at
   !> 30 fps: 31 frames playing 31/30 s, "1.033 s", not 1.0333333333333334), and gnuplot's messages ("N frames
   !> in animation sequence") stay off stderr on success; a failing gnuplot script
   !> (a copy of animate.gp with a bad last line, through DPEND_ROOT) shows them.
   subroutine test_tidy_summary(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, root
      integer :: stat, n, b
      if (.not. have_tool('gnuplot')) then
         call skip_test('gnuplot not found')
         return
      end if
      dir = scratch_dir('animate-tidy')
      stat = run_command(dir, 'simulate --t-end 1 --dt 1e-3 --save-every 10 --output '// &
                         dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate for animate')
      if (allocated(error)) return
      stat = run_command(dir, 'animate '//dir//'/sim.h5 --output '//dir//'/a.gif '// &
                         '--fps 30 --size 64x64')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'animate --fps 30: exit status 0')
      call check_true(error, index(text, '31 frames, 1.033 s at 30 fps, t = 0 .. 1 s') > 0, &
                      'summary with times to 4 digits: '//text)
      call read_text(dir//'/stderr', text, n)
      call check_true(error, n == 0, 'nothing on stderr on success, got: '//text)
      if (allocated(error)) return
      ! the clock in the natural unit too: sqrt(1/9.8) s = 0.3194 s, so 1 s = 3.13 of it
      stat = run_command(dir, 'animate '//dir//'/sim.h5 --output '//dir//'/n.gif '// &
                         '--fps 30 --size 64x64 --time-unit natural')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 't = 0 .. 3.13 sqrt(l1/g) = ' &
                      //'0 .. 1 s') > 0, 'summary in both units: '//text)
      if (allocated(error)) return
      ! a broken copy of scripts/plot/animate.gp: gnuplot fails, its message is shown
      root = dpend_binary()
      b = index(root, '/build/', back=.true.)
      if (b == 0) return
      root = root(:b - 1)
      call execute_command_line('mkdir -p '//dir//'/root/scripts/plot && cp '//root// &
                                '/scripts/plot/animate.gp '//dir//'/root/scripts/plot/ && echo '// &
                                'no_such_command_25 >> '//dir//'/root/scripts/plot/animate.gp')
      call execute_command_line('DPEND_ROOT='//dir//'/root '//dpend_binary()//' animate '// &
                                dir//'/sim.h5 --output '//dir//'/b.gif --fps 5 --size 64x64'// &
                                ' > '//dir//'/stdout 2> '//dir//'/stderr', exitstat=stat)
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 1, 'broken animate.gp: exit status 1, got '//to_str(stat))
      call check_true(error, index(text, 'no_such_command_25') > 0 .and. &
                      index(text, 'gnuplot failed') > 0, &
                      "broken animate.gp: gnuplot's message and the failure shown: "//text)
   end subroutine test_tidy_summary
end module test_animate
