!> The figure scripts (scripts/plot_*.sh) run on tiny files: every PNG they
!> name exists and is not empty, and their keys list only what is drawn. Each script
!> appends the key entries it draws, `FIGURE<TAB>TITLE<TAB>N` with N the points of
!> that series holding data, to $DPEND_PLOT_KEYS (scripts/plot/style.gp,
!> scripts/lib/output.sh); the tests read that file: every entry has data, and the
!> entries that do not belong to the run are absent (no "chaotic" reference on a
!> regular orbit, no power laws on a chaotic one, no grey "not integrated" on a sweep
!> whose every pixel was integrated). Skipped when bash, gnuplot or h5dump is missing.
module test_figures
   use testing, only: unittest_t, new_unittest, check_true, error_t, skip_test, have_tool
   use test_cli, only: run_command, scratch_dir, read_text, dpend_binary
   use dpend_cli, only: to_str
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   implicit none
   private
   public :: collect_figures

contains

   subroutine collect_figures(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('indicators_keys', test_indicators_keys), &
               new_unittest('sweep_keys', test_sweep_keys), &
               new_unittest('every_plot_script', test_every_script), &
               new_unittest('fit_position_ranges', test_fit_position_ranges)]
   end subroutine collect_figures

   !> True when the tools the plot scripts need are on PATH (else the test is skipped).
   logical function tools_present()
      tools_present = have_tool('bash') .and. have_tool('gnuplot') .and. have_tool('h5dump')
      if (.not. tools_present) call skip_test('bash, gnuplot or h5dump not found')
   end function tools_present

   !> The source tree's scripts/ directory, found above the test binary's build/.
   function scripts_dir() result(dir)
      character(len=:), allocatable :: dir
      character(len=:), allocatable :: exe
      integer :: b
      exe = dpend_binary()
      b = index(exe, '/build/', back=.true.)
      if (b > 0) then
         dir = exe(:b - 1)//'/scripts'
      else
         dir = 'scripts'
      end if
   end function scripts_dir

   !> Run `bash scripts/SCRIPT ARGS` with DPEND (the tested binary) and DPEND_PLOT_KEYS
   !> (dir/keys.txt); output in dir/plot.out. Returns the exit status.
   integer function run_plot(dir, script, args) result(stat)
      character(len=*), intent(in) :: dir, script, args
      integer :: cstat
      ! cmdstat: a script that exits 127 (a command not found) fails the test with its
      ! plot.out instead of stopping the test program
      call execute_command_line('DPEND='//dpend_binary()//' DPEND_PLOT_KEYS='//dir// &
                                '/keys.txt bash '//scripts_dir()//'/'//script//' '//args// &
                                ' > '//dir//'/plot.out 2>&1', exitstat=stat, cmdstat=cstat)
      if (cstat /= 0 .and. stat == 0) stat = 127
   end function run_plot

   !> Expect the PNG `path` to exist and hold more than a PNG header.
   subroutine expect_png(error, path)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: path
      integer :: bytes
      logical :: exists
      if (allocated(error)) return
      inquire (file=path, exist=exists, size=bytes)
      call check_true(error, exists .and. bytes > 1000, path//' written and not empty (' &
                      //to_str(bytes)//' bytes)')
   end subroutine expect_png

   !> The key entries of `figure` in the sidecar `keys`: every one has data (N > 0);
   !> `count` is their number; `found` whether one's title contains `needle`.
   subroutine key_entries(error, keys, figure, needle, count, found)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: keys, figure, needle
      integer, intent(out) :: count
      logical, intent(out) :: found
      character(len=1024) :: line
      integer :: unit, stat, t1, t2, n
      character(len=:), allocatable :: title
      count = 0
      found = .false.
      open (newunit=unit, file=keys, status='old', action='read', iostat=stat)
      if (stat /= 0) return
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         t1 = index(line, achar(9))
         t2 = index(line, achar(9), back=.true.)
         if (t1 == 0 .or. t2 <= t1) cycle
         if (line(:t1 - 1) /= figure) cycle
         title = line(t1 + 1:t2 - 1)
         read (line(t2 + 1:), *, iostat=stat) n
         call check_true(error, stat == 0 .and. n > 0, figure//': the key entry "'//title// &
                         '" has data ('//trim(line(t2 + 1:))//' points)')
         count = count + 1
         if (index(title, needle) > 0) found = .true.
      end do
      close (unit)
   end subroutine key_entries

   !> indicators.png of a regular and of a chaotic orbit: a regular orbit's key holds
   !> no chaotic reference and the power laws t^-2, t^-4 of GALI_3, GALI_4; a chaotic
   !> orbit's holds the chaotic references and no power law; SALI is listed in both.
   subroutine test_indicators_keys(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      integer :: stat, n
      logical :: found
      if (.not. tools_present()) return
      dir = scratch_dir('figures-ind')
      ! the README's regular orbit (both links 1 rad below the horizontal) and the
      ! horizontal release
      stat = run_command(dir, 'indicators --q1 -0.5707963267948966 --q2 '// &
                         '-0.5707963267948966 --t-end 30 --output '//dir//'/reg.h5')
      call check_true(error, stat == 0, 'indicators, regular orbit')
      stat = run_command(dir, 'indicators --q1 0 --q2 0 --t-end 30 --output '//dir// &
                         '/chaos.h5')
      call check_true(error, stat == 0, 'indicators, chaotic orbit')
      if (allocated(error)) return
      stat = run_plot(dir, 'plot_chaos.sh', dir//'/reg.h5 '//dir//'/reg')
      call check_true(error, stat == 0, 'plot_chaos.sh on the regular orbit')
      call expect_png(error, dir//'/reg/indicators.png')
      if (allocated(error)) return
      call key_entries(error, dir//'/keys.txt', 'indicators.png', 'chaotic', n, found)
      call check_true(error, n > 0, 'regular orbit: key entries listed')
      call check_true(error, .not. found, 'regular orbit: no chaotic reference in the key')
      call key_entries(error, dir//'/keys.txt', 'indicators.png', 't^-4', n, found)
      call check_true(error, found, 'regular orbit: the power law t^-4 in the key')
      call key_entries(error, dir//'/keys.txt', 'indicators.png', 'SALI', n, found)
      call check_true(error, found, 'regular orbit: SALI in the key')
      if (allocated(error)) return
      call execute_command_line('rm -f '//dir//'/keys.txt')
      stat = run_plot(dir, 'plot_chaos.sh', dir//'/chaos.h5 '//dir//'/chaos')
      call check_true(error, stat == 0, 'plot_chaos.sh on the chaotic orbit')
      call expect_png(error, dir//'/chaos/indicators.png')
      if (allocated(error)) return
      call key_entries(error, dir//'/keys.txt', 'indicators.png', 'chaotic', n, found)
      call check_true(error, found, 'chaotic orbit: the chaotic references in the key')
      call key_entries(error, dir//'/keys.txt', 'indicators.png', 't^-', n, found)
      call check_true(error, .not. found, 'chaotic orbit: no power law in the key')
   end subroutine test_indicators_keys

   !> A small sweep, every pixel computed: the maps are drawn and none lists the grey
   !> "not integrated" key entry; the energy map lists the pixels below the flip
   !> energy bound (grey: not integrated, their energy error NaN) with their count,
   !> the file's NaN pixels of /sweep/energy_error.
   subroutine test_sweep_keys(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      character(len=*), parameter :: maps(4) = [character(len=18) :: 'flip_map.png', &
                                    'flip_map_link1.png', 'flip_map_link2.png', &
                                    'energy_error.png']
      type(h5file_t) :: h5
      real(dp), allocatable :: e(:, :)
      integer :: stat, n, i, n_nan
      logical :: found
      if (.not. tools_present()) return
      dir = scratch_dir('figures-sweep')
      stat = run_command(dir, 'sweep --n 6 --t-end 20 --quiet --output '//dir//'/sweep.h5')
      call check_true(error, stat == 0, 'sweep for the maps')
      if (allocated(error)) return
      stat = run_plot(dir, 'plot_sweep.sh', dir//'/sweep.h5 '//dir//'/maps')
      call check_true(error, stat == 0, 'plot_sweep.sh')
      do i = 1, size(maps)
         call expect_png(error, dir//'/maps/'//trim(maps(i)))
         call key_entries(error, dir//'/keys.txt', trim(maps(i)), 'not integrated', n, found)
         call check_true(error, .not. found .or. i == 4, trim(maps(i))//': no grey "not '// &
                         'integrated" key entry when every pixel was computed')
      end do
      call h5%open(dir//'/sweep.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/sweep/energy_error', e, error)
      call h5%close()
      if (allocated(error)) return
      n_nan = count(e /= e)
      call check_true(error, n_nan > 0, 'some pixels below the flip energy bound')
      call key_count(dir//'/keys.txt', 'energy_error.png', 'cannot flip (below the energy '// &
                     'bound)', n)
      call check_true(error, n == n_nan, 'energy map: the grey pixels below the bound in '// &
                      'the key ('//to_str(n)//' of '//to_str(n_nan)//' NaN pixels)')
      ! the flip maps in the sweep's unit, and in seconds with --time-unit s: the colour
      ! scale 0.3 .. 20 sqrt(l1/g), or 0.3 .. 20 times sqrt(1/9.8) s
      call key_count(dir//'/keys.txt', 'flip_map.png', 'colour scale 0.3 .. 20 sqrt(l1/g)', n)
      call check_true(error, n == 1, 'flip map coloured in sqrt(l1/g) by default')
      stat = run_plot(dir, 'plot_sweep.sh', dir//'/sweep.h5 '//dir//'/maps_s --time-unit s')
      call check_true(error, stat == 0, 'plot_sweep.sh --time-unit s')
      call expect_png(error, dir//'/maps_s/flip_map.png')
      call key_count(dir//'/keys.txt', 'flip_map.png', 'colour scale 0.0958315 .. 6.38877 s', n)
      call check_true(error, n == 1, 'flip map coloured in s with --time-unit s')
      if (allocated(error)) return
      ! a sweep run in seconds is coloured in seconds without being told (its
      ! attribute time_unit): 6.38877 s, the same end, given as --t-end 6.38877
      stat = run_command(dir, 'sweep --n 6 --t-end 6.388765649999399 --time-unit s ' &
                         //'--dt 0.003194382824999699 --quiet --output '//dir//'/sweep_s.h5')
      call execute_command_line('rm -f '//dir//'/keys.txt')   ! this plot's entries alone
      stat = stat + run_plot(dir, 'plot_sweep.sh', dir//'/sweep_s.h5 '//dir//'/maps_ss')
      call check_true(error, stat == 0, 'a sweep in s and its maps')
      call key_count(dir//'/keys.txt', 'flip_map.png', 'colour scale 0.0958315 .. 6.38877 s', n)
      call check_true(error, n == 1, 'flip map of a sweep in s coloured in s by default')
   contains
      !> The point count of the key entry of `figure` whose title holds `needle` (0: none).
      subroutine key_count(keys, figure, needle, count)
         character(len=*), intent(in) :: keys, figure, needle
         integer, intent(out) :: count
         character(len=1024) :: line
         integer :: unit, st, t1, t2
         count = 0
         open (newunit=unit, file=keys, status='old', action='read', iostat=st)
         if (st /= 0) return
         do
            read (unit, '(a)', iostat=st) line
            if (st /= 0) exit
            t1 = index(line, achar(9)); t2 = index(line, achar(9), back=.true.)
            if (t1 == 0 .or. t2 <= t1) cycle
            if (line(:t1 - 1) == figure .and. index(line(t1 + 1:t2 - 1), needle) > 0) &
               read (line(t2 + 1:), *, iostat=st) count
         end do
         close (unit)
      end subroutine key_count
   end subroutine test_sweep_keys

   !> Each plot script on a tiny file of its command: every figure it names is written
   !> and not empty (simulate, lyapunov, divergence, poincare, fit).
   subroutine test_every_script(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      character(len=*), parameter :: sim(6) = [character(len=18) :: 'angles.png', &
                                   'angles_wrapped.png', 'phase.png', 'energy_error.png', &
                                   'reactions.png', 'tip_path.png']
      integer :: stat, i, n
      if (.not. tools_present()) return
      dir = scratch_dir('figures-all')
      stat = run_command(dir, 'simulate --t-end 2 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'simulate')
      if (allocated(error)) return
      stat = run_plot(dir, 'plot_simulate.sh', dir//'/sim.h5 '//dir//'/sim')
      call read_text(dir//'/plot.out', text, n)
      call check_true(error, stat == 0, 'plot_simulate.sh: '//text)
      do i = 1, size(sim)
         call expect_png(error, dir//'/sim/'//trim(sim(i)))
      end do
      stat = run_command(dir, 'lyapunov --t-end 5 --output '//dir//'/lyap.h5')
      if (stat == 0) stat = run_plot(dir, 'plot_chaos.sh', dir//'/lyap.h5 '//dir//'/lyap')
      call check_true(error, stat == 0, 'lyapunov and plot_chaos.sh')
      call expect_png(error, dir//'/lyap/lyapunov_convergence.png')
      call expect_png(error, dir//'/lyap/lyapunov_spectrum.png')
      stat = run_command(dir, 'divergence --t-end 5 --output '//dir//'/div.h5')
      if (stat == 0) stat = run_plot(dir, 'plot_chaos.sh', dir//'/div.h5 '//dir//'/div')
      call check_true(error, stat == 0, 'divergence and plot_chaos.sh')
      call expect_png(error, dir//'/div/divergence.png')
      stat = run_command(dir, 'poincare --energy -15 --ics 2 --points 20 --output '//dir// &
                         '/pc.h5')
      if (stat == 0) stat = run_plot(dir, 'plot_chaos.sh', dir//'/pc.h5 '//dir//'/pc')
      call check_true(error, stat == 0, 'poincare and plot_chaos.sh')
      call expect_png(error, dir//'/pc/poincare.png')
      stat = run_command(dir, 'fit '//scripts_dir()//'/../data/fit_example.csv '// &
                         '--fit-window 1 --output '//dir//'/fit.h5')
      if (stat == 0) stat = run_plot(dir, 'plot_fit.sh', dir//'/fit.h5 '//dir//'/fit')
      call check_true(error, stat == 0, 'fit and plot_fit.sh')
      call expect_png(error, dir//'/fit/fit_overlay.png')
      call expect_png(error, dir//'/fit/fit_residuals.png')
   end subroutine test_every_script
   !> The fit figures of positions (a 43 cm double pendulum of point masses, tip
   !> and elbow tracked with 1 mm noise): every residual panel is scaled to its own
   !> data, +-5 times the RMS of its residuals in the fit window (about 5 mm here, not
   !> the horizon tolerance 0.043 m, which flattened 1 mm residuals to a line), and
   !> every overlay panel has at most 6 tic labels, at least 30 px apart (they
   !> overlapped in 130 px panels). The ranges and tics come from the script's key
   !> sidecar (range and tics entries).
   subroutine test_fit_position_ranges(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, title
      type(h5file_t) :: h5
      real(dp), allocatable :: q(:, :), t(:)
      real(dp) :: lim, rms_i, x(4)
      character(len=1024) :: line
      integer :: stat, unit, k, t1, t2, nranges, ntics, tics, px, at
      if (.not. tools_present()) return
      dir = scratch_dir('figures-fitxy')
      stat = run_command(dir, 'simulate --l1 0.25 --l2 0.18 --body point --q1 -0.6 '// &
                         '--q2 -0.2 --method dop853 --rtol 1e-12 --atol 1e-14 --t-end 6 '// &
                         '--output-dt 0.02 --output '//dir//'/g.h5')
      call check_true(error, stat == 0, 'simulate of the data')
      if (allocated(error)) return
      call h5%open(dir//'/g.h5', 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      call h5%close()
      if (allocated(error)) return
      open (newunit=unit, file=dir//'/xy.csv', status='replace', action='write')
      write (unit, '(a)') 't,x1,y1,x2,y2'
      do k = 1, size(t)
         x(1:2) = 0.25_dp*[cos(q(1, k)), sin(q(1, k))]
         x(3:4) = x(1:2) + 0.18_dp*[cos(q(2, k)), sin(q(2, k))]
         x = x + 1e-3_dp*[sin(7.3_dp*k), cos(5.1_dp*k), sin(3.7_dp*k), cos(2.9_dp*k)]
         write (unit, '(f0.4, 4(",", es22.14e3))') t(k), x
      end do
      close (unit)
      stat = run_command(dir, 'fit '//dir//'/xy.csv --body point --l1 0.25 --l2 0.18 '// &
                         '--fit-window 3 --output '//dir//'/fit.h5')
      call check_true(error, stat == 0, 'fit of the positions')
      if (allocated(error)) return
      stat = run_plot(dir, 'plot_fit.sh', dir//'/fit.h5 '//dir//'/figs')
      call check_true(error, stat == 0, 'plot_fit.sh')
      if (allocated(error)) return
      call expect_png(error, dir//'/figs/fit_residuals.png')
      call expect_png(error, dir//'/figs/fit_overlay.png')
      nranges = 0; ntics = 0
      open (newunit=unit, file=dir//'/keys.txt', status='old', action='read', iostat=stat)
      call check_true(error, stat == 0, 'the key sidecar')
      if (allocated(error)) return
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         t1 = index(line, achar(9)); t2 = index(line, achar(9), back=.true.)
         if (t1 == 0 .or. t2 <= t1) cycle
         title = line(t1 + 1:t2 - 1)
         if (line(:t1 - 1) == 'fit_residuals.png' .and. index(title, 'range ') == 1) then
            ! 'range x_1 [m]: ±0.004625 (5 RMS of the window, RMS 0.000925)'
            at = index(title, '±')
            read (title(at + len('±'):index(title, ' (') - 1), *, iostat=stat) lim
            read (title(index(title, 'RMS ', back=.true.) + 4:len(title) - 1), *, &
                  iostat=stat) rms_i
            call check_true(error, stat == 0 .and. lim > 0 .and. lim < 0.01_dp .and. &
                            abs(lim - 5*rms_i) <= 1e-3_dp*lim, 'residual panel scaled '// &
                            'to 5 RMS of its data: '//title)
            nranges = nranges + 1
         else if (line(:t1 - 1) == 'fit_overlay.png' .and. index(title, 'tics ') == 1) then
            ! 'tics x_1 [m]: 5 in 190 px'
            at = index(title, ': ')
            read (title(at + 2:), *, iostat=stat) tics
            read (title(index(title, ' in ') + 4:index(title, ' px') - 1), *, iostat=stat) px
            call check_true(error, stat == 0 .and. tics >= 2 .and. tics <= 6 .and. &
                            px/tics >= 30, 'overlay tics readable: '//title)
            ntics = ntics + 1
         end if
      end do
      close (unit)
      call check_true(error, nranges == 4 .and. ntics == 4, 'four residual ranges ('// &
                      to_str(nranges)//') and four overlay tic sets ('//to_str(ntics)//')')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_fit_position_ranges
end module test_figures
