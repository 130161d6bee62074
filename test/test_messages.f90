!> Help texts and messages: numbers in the shortest text that reads back exactly
!> (`real_str`), every option listed once, the closing lines of simulate and sweep,
!> the `dpend methods` table.
module test_messages
   use dpend_kinds, only: dp
   use testing, only: unittest_t, new_unittest, check_true, error_t
   use dpend_cli, only: real_str, seconds_str, to_lower, to_str
   use dpend_strings, only: with_uncertainty, interval_text, distance_in_errors
   use dpend_run_settings, only: run_config_t
   use dpend_simulate, only: simulate_help, simulate_defaults
   use dpend_chaos_common, only: chaos_help, chaos_config_t, chaos_defaults, chaos_run_defaults
   use dpend_sweep_config, only: sweep_help
   use dpend_sweep_settings, only: sweep_config_t, sweep_defaults
   use dpend_methods, only: method_names
   use test_cli, only: run_command, scratch_dir, read_text, args_of
   use dpend_sweep_config, only: parse_sweep
   use dpend_sweep_settings, only: horizon_text
   use dpend_indicators_command, only: indicator_verdict
   use dpend_export, only: export_columns
   use dpend_hdf5, only: h5file_t
   use dpend_progress, only: progress_t, progress_header
   use dpend_kinds, only: i8
   implicit none
   private
   public :: collect_messages

   character(len=*), parameter :: nl = new_line('a')
   !> Every command with a --help (plus the program's own help).
   character(len=16), parameter :: commands(12) = [character(len=16) :: 'simulate', &
      'lyapunov', 'divergence', 'poincare', 'indicators', 'sweep', 'sweep-compare', &
      'export', 'study', 'methods', '--help', 'help']

contains

   subroutine collect_messages(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('real_str_cases', test_real_str), &
               new_unittest('real_str_round_trip', test_round_trip), &
               new_unittest('help_numbers_shortest', test_help_numbers), &
               new_unittest('help_defaults_read_back', test_help_defaults), &
               new_unittest('help_options_once', test_options_once), &
               new_unittest('simulate_summary_line', test_simulate_summary), &
               new_unittest('sweep_closing_line', test_sweep_line), &
               new_unittest('methods_table', test_methods), &
               new_unittest('divergence_without_slope', test_divergence_no_slope), &
               new_unittest('quiet_last_line', test_quiet), &
               new_unittest('simulate_largest_error', test_largest_error), &
               new_unittest('progress_rate_limited', test_progress_rate), &
               new_unittest('sweep_horizon', test_sweep_horizon), &
               new_unittest('uncertainty_digits', test_uncertainty_digits), &
               new_unittest('indicators_verdict', test_verdict), &
               new_unittest('export_sweep_long_form', test_export_long), &
               new_unittest('help_mentions_quiet', test_help_quiet), &
               new_unittest('time_unit_every_command', test_time_unit_commands)]
   end subroutine collect_messages

   !> The table of formatter cases.
   subroutine test_real_str(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: zero
      zero = 0.0_dp
      call expect(error, 0.001_dp, '0.001')
      call expect(error, 9.8_dp, '9.8')
      call expect(error, 1e-12_dp, '1e-12')
      call expect(error, 20.0_dp, '20')
      call expect(error, 1.0_dp/3.0_dp, '0.3333333333333333')
      call expect(error, 2.0_dp/3.0_dp, '0.6666666666666666')
      call expect(error, -2.5e300_dp, '-2.5e300')
      call expect(error, 5e-324_dp, '5e-324')
      call expect(error, 0.0_dp, '0')
      call expect(error, -zero, '-0')
      call expect(error, -1.5_dp, '-1.5')
      call expect(error, 1e6_dp, '1e6')
      call expect(error, 2.5e6_dp, '2.5e6')
      call expect(error, 1234567.0_dp, '1234567')
      call expect(error, 1e-4_dp, '0.0001')
      call expect(error, 5e-5_dp, '5e-5')
      call expect(error, 123456.789_dp, '123456.789')
      call expect(error, 0.1_dp + 0.2_dp, '0.30000000000000004')
      call expect(error, huge(1.0_dp), '1.7976931348623157e308')
      call expect(error, tiny(1.0_dp), '2.2250738585072014e-308')
      call expect(error, -huge(1.0_dp), '-1.7976931348623157e308')
      call expect(error, ieee_nan(), 'NaN')
      call expect(error, ieee_inf(), 'Infinity')
      call expect(error, -ieee_inf(), '-Infinity')
      ! with a limit on the significant digits (measured values)
      call check_true(error, real_str(1.0_dp/3.0_dp, 2) == '0.33', 'real_str(1/3, 2) = ' &
                      //real_str(1.0_dp/3.0_dp, 2))
      call check_true(error, real_str(3.2e-13_dp*1.0001_dp, 2) == '3.2e-13', &
                      'real_str(3.2e-13, 2) = '//real_str(3.2e-13_dp*1.0001_dp, 2))
      call check_true(error, seconds_str(0.4_dp) == '0.4', 'seconds 0.4: '//seconds_str(0.4_dp))
      call check_true(error, seconds_str(0.0432_dp) == '0.043', 'seconds 0.0432: ' &
                      //seconds_str(0.0432_dp))
      call check_true(error, seconds_str(12.34_dp) == '12.3', 'seconds 12.34: ' &
                      //seconds_str(12.34_dp))
   end subroutine test_real_str

   !> Shortest and exact on numbers of every magnitude: the text reads back to the
   !> same bits, and one digit less does not.
   subroutine test_round_trip(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: x, y, u
      integer :: i, stat, digits
      character(len=:), allocatable :: s, shorter
      do i = 1, 2000
         call random_number(u)
         x = (u - 0.5_dp)*10.0_dp**(real(mod(i*37, 600), dp) - 300.0_dp)
         if (mod(i, 3) == 0) x = real(nint(u*1e6_dp), dp)/1000.0_dp
         s = real_str(x)
         read (s, *, iostat=stat) y
         if (stat /= 0 .or. y /= x) then
            call check_true(error, .false., 'does not read back: '//s)
            return
         end if
         digits = significant_digits(s)
         if (digits > 17) then
            call check_true(error, .false., 'more than 17 digits: '//s)
            return
         end if
         if (digits > 1) then
            shorter = real_str(x, digits - 1)
            if (shorter /= s) then
               read (shorter, *) y
               if (y == x) then
                  call check_true(error, .false., 'not the shortest: '//s)
                  return
               end if
            end if
         end if
      end do
   end subroutine test_round_trip

   !> Every number in every --help is printed with no more significant digits than
   !> the shortest text that reads back (real_str), e.g. never 0.10000000000000000E-2.
   subroutine test_help_numbers(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, token
      integer :: i, n, stat, pos
      real(dp) :: x
      dir = scratch_dir('helpnum')
      do i = 1, size(commands)
         if (commands(i)(1:2) == '--' .or. commands(i) == 'help') then
            stat = run_command(dir, trim(commands(i)))
         else
            stat = run_command(dir, trim(commands(i))//' --help')
         end if
         call read_text(dir//'/stdout', text, n)
         call check_true(error, stat == 0 .and. n > 1, trim(commands(i))//' --help')
         if (allocated(error)) return
         pos = 1
         do while (next_token(text, pos, token))
            if (.not. numeric(token)) cycle
            if (verify(token, '0123456789') == 0) cycle   ! an integer
            read (token, *, iostat=stat) x
            if (stat /= 0) cycle
            ! hand-written prose may say 1e5 for 100000: as few digits, not the same text
            call check_true(error, significant_digits(token) <= &
                            significant_digits(real_str(x)) .and. &
                            scan(token, 'E') == 0, trim(commands(i))// &
                            ' --help prints '//token//', shortest is '//real_str(x))
            if (allocated(error)) return
         end do
      end do
      call execute_command_line('rm -rf '//dir)
   end subroutine test_help_numbers

   !> The defaults shown read back to the bits of the defaults used.
   subroutine test_help_defaults(error)
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      type(chaos_config_t) :: ch
      type(sweep_config_t) :: sw
      character(len=:), allocatable :: text
      text = simulate_help()
      cfg = simulate_defaults()
      call shown(error, text, '--dt S', [cfg%dt])
      call shown(error, text, '--t-end S', [cfg%t_end])
      call shown(error, text, '--rtol, --atol', [cfg%rtol, cfg%atol])
      call shown(error, text, '--omega', [cfg%omega])
      call shown(error, text, '--g M/S^2', [cfg%g])
      call shown(error, text, '--l1, --l2', cfg%l(1:2))
      call shown(error, text, '--m1, --m2', cfg%m(1:2))
      text = chaos_help('divergence')
      cfg = chaos_run_defaults('divergence')
      ch = chaos_defaults('divergence')
      call shown(error, text, '--t-end S', [cfg%t_end])
      call shown(error, text, '--delta0', [ch%delta0])
      call shown(error, text, '--output-dt', [cfg%output_dt])
      call shown(error, text, '--pair-spacing', [ch%pair_spacing])
      text = chaos_help('lyapunov')
      ch = chaos_defaults('lyapunov')
      call shown(error, text, '--tau', [ch%tau])
      text = chaos_help('indicators')
      ch = chaos_defaults('indicators')
      call shown(error, text, '--tau', [ch%tau])
      text = chaos_help('poincare')
      ch = chaos_defaults('poincare')
      call shown(error, text, '--section-angle', [ch%section_angle])
      text = sweep_help()
      sw = sweep_defaults()
      call shown(error, text, '--dt DT, --t-end T', [sw%run%dt, sw%run%t_end])
   end subroutine test_help_defaults

   !> Each option once in each --help.
   subroutine test_options_once(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, token, seen
      integer :: i, n, stat, pos, start
      dir = scratch_dir('helpopt')
      do i = 1, size(commands)
         if (commands(i)(1:2) == '--' .or. commands(i) == 'help') cycle
         stat = run_command(dir, trim(commands(i))//' --help')
         call read_text(dir//'/stdout', text, n)
         seen = ' '
         pos = 1
         do
            ! an option is listed where a line starts with '  --' or after ', --'
            start = listed_option(text, pos)
            if (start == 0) exit
            pos = start
            token = ''
            do while (pos <= len(text))
               if (index(' =,;)'//nl, text(pos:pos)) > 0) exit
               token = token//text(pos:pos)
               pos = pos + 1
            end do
            call check_true(error, index(seen, ' '//token//' ') == 0, &
                            trim(commands(i))//' --help lists '//token//' twice')
            if (allocated(error)) return
            seen = seen//token//' '
         end do
      end do
      call execute_command_line('rm -rf '//dir)
   end subroutine test_options_once

   !> simulate prints, after 'wrote', the steps, evaluations, energy error, time.
   subroutine test_simulate_summary(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('simsum')
      stat = run_command(dir, 'simulate --t-end 1 --q1 0.5 --output '//dir//'/s.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 2, 'simulate: two lines: '//text)
      if (allocated(error)) return
      call check_true(error, index(text, 'dpend simulate: rk4: 1000 steps, 4000 f evaluations,' &
                                   //' relative energy error largest ') > 0 .and. &
                      index(text, ' sqrt(l1/g)), final ') > 0 .and. &
                      index(text, ' s'//nl) > 0, 'simulate summary: '//text)
      ! the horizon in seconds and in the natural unit sqrt(l1/g) = sqrt(1/9.8) s
      call check_true(error, index(text, "wrote '"//dir//"/s.h5': t = 0 .. 1 s = 3.13 " &
                                   //'sqrt(l1/g)'//nl) > 0, 'simulate horizon: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_simulate_summary

   !> sweep's closing line: '0.4 s' style seconds, no E-notation, kept by --quiet.
   subroutine test_sweep_line(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('sweepline')
      stat = run_command(dir, 'sweep --n 4 --t-end 1 --quiet --output '//dir//'/s.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 1, 'sweep --quiet: one line: '//text)
      call check_true(error, index(text, '16 initial conditions computed') > 0 .and. &
                      index(text, ' .') == 0 .and. index(text, 'E+') == 0 .and. &
                      index(text, ' s, ') > 0, 'sweep closing line: '//text)
      call read_text(dir//'/stderr', text, n)
      call check_true(error, n == 0, '--quiet: nothing on stderr: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_sweep_line

   !> `dpend methods`: a header and one row per method; --names the bare list.
   subroutine test_methods(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('methods')
      stat = run_command(dir, 'methods')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'method ') == 1 .and. &
                      index(text, nl//'gauss4    (q, p)*    4      implicit, symplectic, ' &
                            //'symmetric') > 0 .and. &
                      index(text, nl//'verlet    (q, p)     2      implicit, symplectic, ' &
                            //'symmetric') > 0 .and. &
                      index(text, nl//'dopri5    (q, qdot)  5      explicit, adaptive ') > 0 &
                      .and. index(text, nl//'rk4       (q, qdot)  4      explicit' &
                      //repeat(' ', 26)//'simulate lyapunov indicators divergence ' &
                      //'poincare study fit sweep'//nl) &
                      > 0 .and. index(text, 'poincare study'//nl//'gauss6 ') > 0, &
                      'methods table (indicators everywhere, fit on (q, qdot)): '//text)
      stat = run_command(dir, 'methods --names')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. text == method_names()//nl, 'methods --names: ' &
                      //text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_methods

   !> A divergence curve without an exponential phase (a regular orbit, a short run)
   !> ends with a line that says why there is no slope, not 'slope: nan'.
   subroutine test_divergence_no_slope(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('noslope')
      stat = run_command(dir, 'divergence --t-end 1 --q1 -1.5 --q2 -1.5 --pairs 2 ' &
                         //'--lyapunov-t 0 --output '//dir//'/d.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, nl//'divergence slope: none (no ' &
                      //'exponential phase: ') > 0 .and. index(text, ' within 1 s = 3.13 sqrt(l1/g);') > 0 &
                      .and. index(to_lower(text), 'nan') == 0, 'no slope: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_divergence_no_slope

   !> --quiet (every command): simulate and lyapunov print only their last
   !> line, nothing on stderr; the file is written as without it.
   subroutine test_quiet(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('quiet')
      stat = run_command(dir, 'simulate --t-end 0.1 --quiet --output '//dir//'/s.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 1 .and. index(text, 'dpend simulate: rk4: ') &
                      == 1 .and. index(text, 'relative energy error') > 0, 'simulate: '//text)
      if (allocated(error)) return
      call read_text(dir//'/stderr', text, n)
      call check_true(error, n == 0, 'simulate --quiet: stderr '//text)
      if (allocated(error)) return
      stat = run_command(dir, 'lyapunov --quiet --t-end 1 --output '//dir//'/l.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. n == 1 .and. index(text, 'lyapunov: ') == 1, &
                      'lyapunov: '//text)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_quiet

   !> Every command that takes times accepts --time-unit natural and reports its
   !> times in that unit first, then in seconds: with l1 = 2.45 m, g = 9.8 m/s^2 the
   !> unit sqrt(l1/g) is 0.5 s exactly, so 4 units are 2 s, and tau = 0.5 units gives
   !> 2 s / 0.25 s = 8 renormalisations (the command's own times converted too).
   subroutine test_time_unit_commands(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, common
      dir = scratch_dir('timeunit')
      common = ' --l1 2.45 --t-end 4 --time-unit natural --force --output '//dir//'/o.h5'
      call expect_out('simulate'//common, 't = 0 .. 4 sqrt(l1/g) = 2 s')
      call expect_out('lyapunov --tau 0.5'//common, &
                      't = 0 .. 4 sqrt(l1/g) = 2 s, tau = 0.5 sqrt(l1/g) = 0.25 s, 8 renormalisations')
      call expect_out('indicators --tau 0.5'//common, &
                      't = 0 .. 4 sqrt(l1/g) = 2 s, tau = 0.5 sqrt(l1/g) = 0.25 s, 8 samples')
      call expect_out('divergence --pairs 1 --lyapunov-t 0'//common, &
                      '1 pair(s) over 4 sqrt(l1/g) = 2 s')
      call expect_out('poincare --ics 2'//common, 'orbits up to t = 4 sqrt(l1/g) = 2 s')
      call expect_out('sweep --n 2 --l1 2.45 --t-end 4 --force --output '//dir//'/w.h5', &
                      't_end = 4 sqrt(l1/g) = 2 s')
      ! fit: the window in the unit (9.4 sqrt(1/9.8) s = 3.003 s: the samples to 3 s)
      call expect_out('fit data/fit_example.csv --time-unit natural --fit-window 9.4 ' &
                      //'--force --output '//dir//'/f.h5', 'sqrt(l1/g) = 3 s (151 samples)')
      call expect_out('simulate --l1 2.45 --t-end 4 --force --output '//dir//'/o.h5', &
                      't = 0 .. 4 s = 8 sqrt(l1/g)')
      call execute_command_line('rm -rf '//dir)
   contains
      subroutine expect_out(args, text)
         character(len=*), intent(in) :: args, text
         character(len=:), allocatable :: out, err
         integer :: n, stat
         if (allocated(error)) return
         stat = run_command(dir, args)
         call read_text(dir//'/stdout', out, n)
         call read_text(dir//'/stderr', err, n)   ! (sweep: the horizon on stderr)
         out = out//err
         call check_true(error, stat == 0 .and. index(out, text) > 0, 'dpend '//args// &
                         ': no '''//text//''' in '//out)
      end subroutine expect_out
   end subroutine test_time_unit_commands

   ! ----------------------------------------------------------------- helpers

   subroutine expect(error, x, text)
      type(error_t), allocatable, intent(inout) :: error
      real(dp), intent(in) :: x
      character(len=*), intent(in) :: text
      real(dp) :: y
      integer :: stat
      if (allocated(error)) return
      call check_true(error, real_str(x) == text, 'real_str gives '//real_str(x)// &
                      ', expected '//text)
      if (allocated(error) .or. x /= x) return
      read (text, *, iostat=stat) y
      call check_true(error, stat == 0 .and. (y == x .and. (sign(1.0_dp, y) == &
                      sign(1.0_dp, x))), text//' does not read back')
   end subroutine expect

   !> The numbers after 'default' on the line of `option` equal `values` exactly.
   subroutine shown(error, text, option, values)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: text, option
      real(dp), intent(in) :: values(:)
      character(len=:), allocatable :: line, token
      integer :: a, b, i, pos, stat
      real(dp) :: x
      if (allocated(error)) return
      a = index(text, nl//'  '//option)
      call check_true(error, a > 0, 'help has no line '//option)
      if (allocated(error)) return
      ! the option's entry: up to the next line that starts an option
      b = index(text(a + 1:), nl//'  -')
      if (b == 0) b = len(text) - a
      line = text(a + 1:a + b)
      a = index(line, 'default ')
      call check_true(error, a > 0, option//': no default in '//line)
      if (allocated(error)) return
      pos = a + len('default ')
      do i = 1, size(values)
         call check_true(error, next_token(line, pos, token), option//': missing value')
         if (allocated(error)) return
         read (token, *, iostat=stat) x
         call check_true(error, stat == 0 .and. x == values(i) .and. token == &
                         real_str(values(i)), option//': shows '//token//' for '// &
                         real_str(values(i)))
         if (allocated(error)) return
      end do
   end subroutine shown

   !> The next blank-separated word of `text` from `pos`, without surrounding
   !> brackets and punctuation; false at the end.
   logical function next_token(text, pos, token) result(found)
      character(len=*), intent(in) :: text
      integer, intent(inout) :: pos
      character(len=:), allocatable, intent(out) :: token
      integer :: a
      token = ''
      do while (pos <= len(text))
         if (index(' '//nl, text(pos:pos)) == 0) exit
         pos = pos + 1
      end do
      found = pos <= len(text)
      if (.not. found) return
      a = pos
      do while (pos <= len(text))
         if (index(' '//nl, text(pos:pos)) > 0) exit
         pos = pos + 1
      end do
      token = text(a:pos - 1)
      do while (len(token) > 0)
         if (index('([', token(1:1)) == 0) exit
         token = token(2:)
      end do
      do while (len(token) > 0)
         if (index(')],;:.', token(len(token):len(token))) == 0) exit
         token = token(:len(token) - 1)
      end do
   end function next_token

   !> A number as printed: digits with an optional sign, point and exponent.
   pure logical function numeric(token)
      character(len=*), intent(in) :: token
      numeric = len(token) > 0 .and. verify(token, '0123456789.eE-+') == 0 .and. &
                scan(token, '0123456789') > 0
      if (numeric) numeric = scan(token(1:1), '0123456789-') > 0
   end function numeric

   !> Position of the next listed option (its '--') from `pos`, 0 if none.
   integer function listed_option(text, pos) result(at)
      character(len=*), intent(in) :: text
      integer, intent(in) :: pos
      integer :: a, b
      a = index(text(pos:), nl//'  --')
      b = index(text(pos:), ', --')
      if (a > 0) a = a + pos - 1 + 3
      if (b > 0) b = b + pos - 1 + 2
      if (a == 0) then
         at = b
      else if (b == 0) then
         at = a
      else
         at = min(a, b)
      end if
   end function listed_option

   !> Significant digits of a real_str text.
   pure integer function significant_digits(s)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: m
      integer :: e, k
      e = scan(s, 'eE')
      m = s
      if (e > 0) m = s(:e - 1)
      significant_digits = 0
      k = 0
      do e = 1, len(m)
         if (scan(m(e:e), '0123456789') == 0) cycle
         if (k == 0 .and. m(e:e) == '0') cycle   ! leading zeros
         k = k + 1
      end do
      ! trailing zeros of an integer without point do not count
      if (index(m, '.') == 0) then
         do e = len(m), 1, -1
            if (m(e:e) /= '0') exit
            k = k - 1
         end do
      end if
      significant_digits = k
   end function significant_digits

   function ieee_nan() result(x)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      real(dp) :: x
      x = ieee_value(x, ieee_quiet_nan)
   end function ieee_nan

   function ieee_inf() result(x)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
      real(dp) :: x
      x = ieee_value(x, ieee_positive_inf)
   end function ieee_inf
   !> The summary's largest relative energy error is the largest over
   !> the file's energy dataset, |E(t_k) - E(0)| / energy_scale, recomputed here from
   !> /trajectory/energy and the root attribute energy_scale: the chapter's run with
   !> the README's settings (data/simulate.nml: rk4, dt = 1e-4 s, t = 10 s; about
   !> 8e-13), a short one, and a damped run (the balance: E(t) - E(0) + W_friction
   !> - W_support from /trajectory/W_friction and W_support).
   subroutine test_largest_error(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('simlargest')
      call one('--dt 1e-4 --t-end 10 --save-every 10', .false., 5e-13_dp, 2e-12_dp)
      call one('--t-end 3 --q1 0.5 --method gauss4', .false., 0.0_dp, 1.0_dp)
      call one('--t-end 3 --damping 0.2,0.1', .true., 0.0_dp, 1.0_dp)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine one(flags, balance, lo, hi)
         character(len=*), intent(in) :: flags
         logical, intent(in) :: balance
         real(dp), intent(in) :: lo, hi   ! bounds of the largest error
         character(len=:), allocatable :: text
         type(h5file_t) :: h5
         type(error_t), allocatable :: err
         real(dp), allocatable :: e(:), wf(:), ws(:), r(:)
         real(dp) :: scale, printed, final
         integer :: n, stat, at, k
         if (allocated(error)) return
         stat = run_command(dir, 'simulate --force '//flags//' --output '//dir//'/s.h5')
         call read_text(dir//'/stdout', text, n)
         call check_true(error, stat == 0, flags//': exit 0: '//text)
         if (allocated(error)) return
         call h5%open(dir//'/s.h5', 'r', err)
         if (.not. allocated(err)) call h5%read('/trajectory/energy', e, err)
         if (.not. allocated(err)) call h5%readattr('/', 'energy_scale', scale, err)
         if (.not. allocated(err) .and. balance) call h5%read('/trajectory/W_friction', wf, err)
         if (.not. allocated(err) .and. balance) call h5%read('/trajectory/W_support', ws, err)
         call h5%close()
         if (allocated(err)) then
            call check_true(error, .false., flags//': '//err%message)
            return
         end if
         r = abs(e - e(1))
         if (balance) r = abs(e - e(1) + wf - ws)
         r = r/scale
         at = index(text, 'largest ') + 8
         read (text(at:), *, iostat=stat) printed
         k = index(text, 'final ') + 6
         if (stat == 0) read (text(k:index(text(k:), ',') + k - 2), *, iostat=stat) final
         call check_true(error, stat == 0 .and. at > 8 .and. k > 6, flags// &
                         ': largest and final in the summary: '//text)
         if (allocated(error)) return
         ! printed with 2 significant digits
         call check_true(error, abs(printed - maxval(r)) <= 0.051_dp*maxval(r), flags// &
                         ': largest '//real_str(printed)//' vs the file '//real_str(maxval(r)))
         call check_true(error, abs(final - r(size(r))) <= 0.051_dp*r(size(r)) + tiny(1.0_dp), &
                         flags//': final '//real_str(final)//' vs the file '// &
                         real_str(r(size(r))))
         call check_true(error, printed >= lo .and. printed <= hi, flags//': largest '// &
                         real_str(printed)//' within ['//real_str(lo)//', '//real_str(hi)//']')
         call check_true(error, (index(text, 'balance error largest') > 0) .eqv. balance, &
                         flags//': names the balance for a damped run: '//text)
      end subroutine one
   end subroutine test_largest_error

   !> The progress report's rate limiter with an injected clock: without
   !> a terminal, at most one line every 10 s and none in the first 10 s, whatever
   !> the rate of updates; none when quiet; a queued header printed once at the
   !> start. The lines go to a scratch file, counted and read back.
   subroutine test_progress_rate(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n
      dir = scratch_dir('progress')
      ! 0.5 s between updates for 100 s: lines at 10, 20, ... 100 s
      call run(200, 0.5_dp, .false., 10, 10)
      ! a short run (9.5 s) writes none; nor does the end of the run by itself
      call run(19, 0.5_dp, .false., 0, 0)
      ! irregular updates (every 3.3 s for 99 s): at 13.2, 26.4, ... at most 1 per 10 s
      call run(30, 3.3_dp, .false., 7, 7)
      ! one update per 25 s: each is due
      call run(4, 25.0_dp, .false., 4, 4)
      call run(200, 0.5_dp, .true., 0, 0)   ! quiet
      call progress_header('dpend test: header')
      call run(3, 1.0_dp, .false., 0, 1)
      if (allocated(error)) return
      call read_text(dir//'/p.txt', text, n)
      call check_true(error, text == 'dpend test: header'//nl, 'header printed once: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine run(updates, step, quiet, expected, file_lines)
         integer, intent(in) :: updates, expected, file_lines
         real(dp), intent(in) :: step
         logical, intent(in) :: quiet
         type(progress_t) :: p
         real(dp) :: now, last
         integer :: k, unit, before
         open (newunit=unit, file=dir//'/p.txt', status='replace', action='write')
         p%unit = unit
         call p%start('dpend test', int(updates, i8)*5, 0_i8, quiet, now=0.0_dp)
         ! as without a terminal, whatever this test's stderr is
         p%tty = .false.
         p%t_last = p%t_start
         last = -huge(1.0_dp)
         do k = 1, updates
            now = k*step
            before = p%lines
            call p%update(5_i8, now=now)
            if (p%lines > before) then
               call check_true(error, now - last >= 10.0_dp, 'a line at '//real_str(now)// &
                               ' s only '//real_str(now - last)//' s after the last')
               last = now
            end if
         end do
         call p%finish()
         close (unit)
         call check_true(error, p%lines == expected, real_str(step)//' s x '// &
                         to_str(updates)//': '//to_str(p%lines)//' lines, expected '// &
                         to_str(expected))
         call read_text(dir//'/p.txt', text, n)
         call check_true(error, n == file_lines, 'lines in the file: '//to_str(n)//': '//text)
      end subroutine run
   end subroutine test_progress_rate

   !> An estimate with its uncertainty to the digits the uncertainty supports (two
   !> significant digits of it, the estimate to the same place; a common exponent
   !> more than 6 decimals or beyond 1e7), against strings written by hand; then lyapunov and
   !> divergence print every estimate so, and say what the uncertainty covers.
   subroutine test_uncertainty_digits(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: stat, n
      call same(0.82405931_dp, 0.092779532_dp, '0.824 +- 0.093')
      call same(1.1539559_dp, 0.0016414673_dp, '1.1540 +- 0.0016')
      call same(123456.7_dp, 2345.6_dp, '123500 +- 2300')
      call same(8.2e-7_dp, 3.1e-9_dp, '(8.200 +- 0.031)e-07')
      call same(3e12_dp, 4e10_dp, '(3.000 +- 0.040)e+12')
      call same(1.0_dp, 0.0996_dp, '1.00 +- 0.10')
      call same(-0.024698354_dp, 0.042706098_dp, '-0.025 +- 0.043')
      call same(-1e-4_dp, 0.042706098_dp, '0.000 +- 0.043')
      call same(2.5_dp, 0.0_dp, '2.5 (no uncertainty)')
      call same(0.6500013425_dp, 4.4e-5_dp, '0.650001 +- 0.000044')
      ! an interval's ends to the estimate's decimal place (the fit's 95 % intervals)
      call same_interval(0.226246_dp, 0.23227_dp, 0.0015_dp, '[0.2262, 0.2323]')
      call same_interval(-0.00522459_dp, 0.0110134_dp, 0.0041_dp, '[-0.0052, 0.0110]')
      call same_interval(8.14e-7_dp, 8.26e-7_dp, 3.1e-9_dp, '[8.140, 8.260]e-07')
      call same_interval(1.0_dp, 2.0_dp, 0.0_dp, '[1, 2]')
      call check_true(error, distance_in_errors(1.3_dp, 1.0_dp, '1', 0.1_dp) == &
                      '1 is 3 standard errors away' .and. distance_in_errors(-0.1_dp, &
                      0.0_dp, '0', 0.1_dp) == '0 within 1 standard error', 'distances')
      if (allocated(error)) return
      dir = scratch_dir('uncertainty')
      stat = run_command(dir, 'lyapunov --t-end 20 --output '//dir//'/l.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'standard error') > 0 .and. &
                      index(text, 'statistical only') > 0 .and. &
                      index(text, nl//'  1   0.') > 0 .and. index(text, ' +- ') > 0 .and. &
                      index(text, '0 within') > 0, 'lyapunov: estimates +- errors: '//text)
      ! the report has no 8-digit exponent form; the scripting line after it keeps them
      n = index(text, 'dpend lyapunov: wrote')
      call check_true(error, n > 0, 'lyapunov: the closing line')
      if (allocated(error)) return
      call check_true(error, index(text(:n), 'E-0') == 0 .and. index(text(:n), 'E+0') == 0, &
                      'lyapunov: no exponent form in the report: '//text)
      stat = run_command(dir, 'divergence --t-end 20 --lyapunov-t 100 --output '//dir//'/d.h5')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'slope: 1.') > 0 .and. &
                      index(text, 'statistical only, not the choice of the window') > 0 .and. &
                      index(text, 'slope / lambda1 = 1.') > 0 .and. &
                      (index(text, ' standard errors away)') > 0 .or. &
                       index(text, '(1 within ') > 0) .and. &
                      index(text, 'standard error') > 0, 'divergence: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine same(x, u, want)
         real(dp), intent(in) :: x, u
         character(len=*), intent(in) :: want
         call check_true(error, with_uncertainty(x, u) == want, real_str(x)//' +- '// &
                         real_str(u)//': '//with_uncertainty(x, u)//', not '//want)
      end subroutine same
      subroutine same_interval(lo, hi, u, want)
         real(dp), intent(in) :: lo, hi, u
         character(len=*), intent(in) :: want
         if (allocated(error)) return
         call check_true(error, interval_text(lo, hi, u) == want, 'interval: '// &
                         interval_text(lo, hi, u)//', not '//want)
      end subroutine same_interval
   end subroutine test_uncertainty_digits

   !> The sweep's horizon and step in both units, against the natural
   !> unit computed here: sqrt(l1/g) = sqrt(1/9.8) s = 0.31943828... s, so 100 of it
   !> is 31.94 s (4 digits); in seconds, 30 s is 93.91 of it; sqrt(l0/g) of the
   !> elastic pendulum with l0 = 2 m.
   subroutine test_sweep_horizon(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: tn
      tn = sqrt(1.0_dp/9.8_dp)
      call check_true(error, abs(100*tn - 31.94_dp) < 0.005_dp .and. &
                      abs(0.01_dp*tn - 0.003194_dp) < 5e-7_dp .and. &
                      abs(30/tn - 93.91_dp) < 0.005_dp, 'the natural unit')
      call one('--n 2', 't_end = 100 sqrt(l1/g) = 31.94 s, dt = 0.01 sqrt(l1/g) = 0.003194 s')
      call one('--n 2 --time-unit s --t-end 30 --dt 0.001', &
               't_end = 30 s = 93.91 sqrt(l1/g), dt = 0.001 s = 0.00313 sqrt(l1/g)')
      call one('--n 2 --l1 4 --g 9.8', 't_end = 100 sqrt(l1/g) = 63.89 s')
      call one('--n 2 --model elastic --k 40 --l0 2 --q 1.2,-1.0 --axis1 r --axis2 phi ' &
               //'--min1 1 --max1 1.5 --indicator megno', 't_end = 100 sqrt(l0/g) = 45.18 s')
      call one('--n 2 --axis1 l1 --min1 0.5 --max1 2', 'of the configured l1 = 1 m; l1 is swept')
   contains
      subroutine one(line, expected)
         character(len=*), intent(in) :: line, expected
         type(sweep_config_t) :: cfg
         type(error_t), allocatable :: err
         logical :: help
         character(len=:), allocatable :: text
         if (allocated(error)) return
         call parse_sweep(args_of(line), cfg, help, err)
         if (allocated(err)) then
            call check_true(error, .false., line//': '//err%message)
            return
         end if
         text = horizon_text(cfg)
         call check_true(error, index(text, expected) > 0, line//': '//text//' lacks '//expected)
      end subroutine one
   end subroutine test_sweep_horizon

   !> `dpend indicators` ends its summary (before the line scripts read) with a
   !> verdict: chaotic on the horizontal release (lambda1 = 1.18 1/s:
   !> <Y> ~ lambda1 t/2 ~ 23 at 40 s), regular on the orbit 1 rad from hanging
   !> (docs/chaos.md: <Y> -> 2, SALI bounded), undecided on a run too short to
   !> tell; and the criterion's edges on given values.
   subroutine test_verdict(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      real(dp), parameter :: tn = 0.3194382824999699_dp
      dir = scratch_dir('verdict')
      call run('--t-end 40', 'verdict: chaotic (')
      call run('--t-end 40 --theta1 1 --theta2 1 --dt 1e-2', 'verdict: regular (')
      call run('--t-end 5 --theta1 1 --theta2 1 --dt 1e-2', 'verdict: undecided (')
      call given(4.01_dp, 0.99e-4_dp, 1.0_dp, 'verdict: chaotic (')
      call given(4.0_dp, 1e-8_dp, 1.0_dp, 'verdict: undecided (')
      call given(30.0_dp, 1e-4_dp, 1000.0_dp, 'verdict: undecided (')
      call given(2.1_dp, 1e-4_dp, 100*tn, 'verdict: regular (')
      call given(0.0_dp, 0.5_dp, 1000.0_dp, 'verdict: regular (')
      call given(2.11_dp, 0.5_dp, 1000.0_dp, 'verdict: undecided (')
      call given(1.9_dp, 0.5_dp, 99*tn, 'verdict: undecided (')
      call given(1.9_dp, 0.99e-4_dp, 1000.0_dp, 'verdict: undecided (')
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine run(flags, expected)
         character(len=*), intent(in) :: flags, expected
         character(len=:), allocatable :: text, last
         integer :: n, stat, k
         if (allocated(error)) return
         stat = run_command(dir, 'indicators --force '//flags//' --output '//dir//'/i.h5')
         call read_text(dir//'/stdout', text, n)
         call check_true(error, stat == 0, flags//': exit 0: '//text)
         k = index(text, nl//'verdict: ')
         call check_true(error, k > 0, flags//': a verdict: '//text)
         if (allocated(error)) return
         call check_true(error, index(text(k + 1:), expected) == 1 .and. &
                         index(text(k + 1:), 'criterion: ') > 0, flags//': '//text(k + 1:))
         ! the line scripts read stays the last
         last = text(k + 1:)
         last = last(index(last, nl) + 1:)
         call check_true(error, index(last, 'indicators: ') == 1, flags//': last line: '//last)
      end subroutine run
      subroutine given(y, sali, t, expected)
         real(dp), intent(in) :: y, sali, t
         character(len=*), intent(in) :: expected
         character(len=:), allocatable :: v
         if (allocated(error)) return
         v = indicator_verdict(y, sali, t, tn, 'sqrt(l1/g)')
         call check_true(error, index(v, expected) == 1, real_str(y)//' '//real_str(sali)// &
                         ' '//real_str(t)//': '//v)
      end subroutine given
   end subroutine test_verdict

   !> `export --csv` of a grid sweep's maps is long form: a header
   !> 'theta1 [rad],w2 [rad/s],t_flip [s],energy_error [1]', then one row per pixel,
   !> axis 1 fastest, each row's axis values and map values equal to the file's
   !> /sweep/axis1(j1), /sweep/axis2(j2) and map(j1, j2) read here; names given
   !> as 't_flip,energy_error' or as two words give the same text; a 1-D dataset
   !> keeps the column form.
   subroutine test_export_long(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, file, line
      type(h5file_t) :: h5
      type(error_t), allocatable :: err
      real(dp), allocatable :: a1(:), a2(:), tf(:, :), ee(:, :)
      real(dp) :: row(4)
      integer :: stat, unit, j1, j2, pos, k
      character(len=:), allocatable :: text2
      dir = scratch_dir('exportlong')
      file = dir//'/s.h5'
      stat = run_command(dir, 'sweep --n1 3 --n2 2 --t-end 5 --quiet --axis2 w2 --min2 -1 ' &
                         //'--max2 2 --output '//file)
      call check_true(error, stat == 0, 'sweep exits 0')
      if (allocated(error)) return
      call h5%open(file, 'r', err)
      if (.not. allocated(err)) call h5%read('/sweep/axis1', a1, err)
      if (.not. allocated(err)) call h5%read('/sweep/axis2', a2, err)
      if (.not. allocated(err)) call h5%read('/sweep/t_flip', tf, err)
      if (.not. allocated(err)) call h5%read('/sweep/energy_error', ee, err)
      call h5%close()
      call check_true(error, .not. allocated(err), 'read the sweep file')
      if (allocated(error)) return
      call check_true(error, size(a1) == 3 .and. size(a2) == 2 .and. size(tf, 1) == 3 .and. &
                      size(tf, 2) == 2, 'shapes (h5py (2, 3))')
      if (allocated(error)) return
      call export_to(['t_flip,energy_error'], text)
      call export_to([character(len=12) :: 't_flip', 'energy_error'], text2)
      if (allocated(error)) return
      call check_true(error, text == text2, 'comma-separated names give the same text')
      pos = index(text, nl)
      call check_true(error, text(:pos - 1) == 'theta1 [rad],w2 [rad/s],t_flip [s],' &
                      //'energy_error [1]', 'header: '//text(:pos - 1))
      k = 0
      do j2 = 1, 2
         do j1 = 1, 3
            if (allocated(error)) return
            text = text(pos + 1:)
            pos = index(text, nl)
            line = text(:pos - 1)
            read (line, *, iostat=stat) row
            k = k + 1
            call check_true(error, stat == 0, 'row '//real_str(real(k, dp))//': '//line)
            if (allocated(error)) return
            call check_true(error, row(1) == a1(j1) .and. row(2) == a2(j2) .and. &
                            same(row(3), tf(j1, j2)) .and. same(row(4), ee(j1, j2)), &
                            'row '//real_str(real(k, dp))//' = the file''s pixel: '//line)
         end do
      end do
      call check_true(error, len(text) == pos, 'six rows, nothing after: '//text(pos + 1:))
      call export_to(['axis1'], text)
      call check_true(error, index(text, 'axis1 [rad]'//nl) == 1, '1-D: column form: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   contains
      subroutine export_to(names, out)
         character(len=*), intent(in) :: names(:)
         character(len=:), allocatable, intent(out) :: out
         integer :: m
         out = ''
         open (newunit=unit, file=dir//'/e.csv', status='replace', action='write')
         call export_columns(file, names, unit, err, csv=.true.)
         close (unit)
         call check_true(error, .not. allocated(err), 'export_columns')
         if (allocated(error)) return
         call read_text(dir//'/e.csv', out, m)
      end subroutine export_to
      logical function same(a, b)
         real(dp), intent(in) :: a, b
         same = a == b .or. (a /= a .and. b /= b)
      end function same
   end subroutine test_export_long

   !> Every command's --help names --quiet, and dpend --help every model.
   subroutine test_help_quiet(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      character(len=16), parameter :: all(13) = [character(len=16) :: 'simulate', &
         'lyapunov', 'divergence', 'poincare', 'indicators', 'sweep', 'sweep-compare', &
         'export', 'study', 'animate', 'fit', 'methods', 'models']
      integer :: i, n, stat
      dir = scratch_dir('helpquiet')
      do i = 1, size(all)
         stat = run_command(dir, trim(all(i))//' --help')
         call read_text(dir//'/stdout', text, n)
         call check_true(error, stat == 0 .and. index(text, '--quiet') > 0, &
                         trim(all(i))//' --help names --quiet: '//text)
         if (allocated(error)) return
      end do
      stat = run_command(dir, '--help')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, index(text, nl//'  pendulum ') > 0 .and. &
                      index(text, nl//'  elastic ') > 0 .and. index(text, '--damping') > 0 &
                      .and. index(text, '--support-amplitude') > 0 .and. &
                      index(text, '--links N') > 0, 'dpend --help: the models: '//text)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_help_quiet
end module test_messages
