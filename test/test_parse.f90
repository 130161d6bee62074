!> The one strict scalar parser (dpend_parse): valid tokens read back to
!> the bits of the compiler's own literals, every kind of invalid token refused with
!> the offending character named and escaped; the escaping helper; the namelist
!> pre-scan (check_groups) refusing '%', repeated keys, two forms of one quantity
!> and numbers outside the grammar; the command line refusing two forms; g = 0
!> refused by the one range table for every number of links.
module test_parse
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t
   use dpend_parse, only: read_real, read_int, escaped, quoted
   use dpend_cli, only: parse_real, parse_int
   use dpend_run_settings, only: run_config_t
   use dpend_namelist, only: check_groups
   use dpend_run_flags, only: apply_run_flag
   use dpend_strings, only: edit_distance, nearest_name, did_you_mean, canonical_name
   use dpend_cli, only: help_options, unknown_option_text
   use dpend_methods, only: new_integrator, method_names
   use dpend_integrator, only: integrator_t
   use dpend_chain, only: chain_t, chain_model
   use dpend_limits, only: check_parameter, parameter_gravity, parameter_mass
   use testing, only: unittest_t, new_unittest, check_true, fatal_error
   implicit none
   private
   public :: collect_parse

contains

   subroutine collect_parse(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('valid_reals_bit_exact', test_valid_reals), &
              new_unittest('invalid_reals_refused', test_invalid_reals), &
              new_unittest('integers', test_integers), &
              new_unittest('escaped_one_line', test_escaped), &
              new_unittest('flag_messages', test_flag_messages), &
              new_unittest('namelist_prescan', test_namelist), &
              new_unittest('command_line_forms', test_forms), &
              new_unittest('g_range_shared', test_g_range), &
              new_unittest('names_suggested', test_suggestions), &
              new_unittest('names_any_case', test_any_case) &
              ]
   end subroutine collect_parse

   !> Each token reads to the same bits as the literal the compiler converted.
   subroutine test_valid_reals(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: tokens(16) = [character(len=24) :: &
         '0.5', '.5', '5.', '-1.25e2', '+7', '1d-3', '1D+3', '0.1', '-0', '3E-2', &
         '1.7976931348623157e308', '2.2250738585072014e-308', '123456789012345678', &
         '0.7   ', '1e0', '9.8']
      real(dp), parameter :: expected(16) = [0.5_dp, 0.5_dp, 5.0_dp, -125.0_dp, 7.0_dp, &
         1e-3_dp, 1e3_dp, 0.1_dp, -0.0_dp, 3e-2_dp, huge(1.0_dp), tiny(1.0_dp), &
         123456789012345678.0_dp, 0.7_dp, 1.0_dp, 9.8_dp]
      real(dp) :: x
      character(len=:), allocatable :: why
      integer :: i
      do i = 1, size(tokens)
         call read_real(tokens(i), x, why)
         call check_true(error, len(why) == 0, "'"//trim(tokens(i))//"' refused: "//why)
         if (allocated(error)) return
         call check_true(error, transfer(x, 1_i8) == transfer(expected(i), 1_i8), &
                         "'"//trim(tokens(i))//"' does not read back bit for bit")
         if (allocated(error)) return
      end do
   end subroutine test_valid_reals

   !> Every kind of invalid token is refused, the reason naming what is wrong.
   subroutine test_invalid_reals(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=1), parameter :: tab = achar(9), lf = achar(10)
      real(dp) :: x
      character(len=:), allocatable :: why
      call expect('0.7'//tab//'1', "character '\t' at position 4")
      call expect('0.7'//lf//'1', "character '\n' at position 4")
      call expect('1;2', "character ';' at position 2")
      call expect('1,2', "character ',' at position 2")
      call expect('1 2', "character ' ' at position 2")
      call expect(' 1', "character ' ' at position 1")
      call expect('0x10', "character 'x' at position 2")
      call expect('1.2.3', "character '.' at position 4")
      call expect('1e5.5', "character '.' at position 4")
      call expect('1.0_dp', "character '_' at position 4")
      call expect('1'//achar(0), "character '\x00' at position 2")
      call expect('2'//char(195)//char(169), "character '\xC3' at position 2")
      call expect('abc', "character 'a' at position 1")
      call expect('', 'is not a number (empty)')
      call expect('1e', 'incomplete')
      call expect('.', 'incomplete')
      call expect('-', 'incomplete')
      call expect('e5', "character 'e' at position 1")
      call expect('inf', 'is not finite')
      call expect('-Infinity', 'is not finite')
      call expect('NaN', 'is not finite')
      call expect('1e400', 'beyond the largest double')
      call expect('-1.8e308', 'beyond the largest double')
      call expect('1'//repeat('0', 999), 'beyond the largest double')
      call expect('1e9999999999', 'beyond the largest double')
   contains
      subroutine expect(token, reason)
         character(len=*), intent(in) :: token, reason
         if (allocated(error)) return
         call read_real(token, x, why)
         call check_true(error, index(why, reason) > 0 .and. x == 0.0_dp, &
                         quoted(token)//': expected "'//reason//'", got "'//why//'"')
      end subroutine expect
   end subroutine test_invalid_reals

   !> Integers: the whole token, within the kind's range.
   subroutine test_integers(error)
      type(error_t), allocatable, intent(out) :: error
      integer :: n
      integer(i8) :: n8
      character(len=:), allocatable :: why
      call read_int('42', n, why)
      call check_true(error, len(why) == 0 .and. n == 42, '42')
      if (allocated(error)) return
      call read_int('-0007', n, why)
      call check_true(error, len(why) == 0 .and. n == -7, '-0007')
      if (allocated(error)) return
      call read_int('2147483647', n, why)
      call check_true(error, len(why) == 0 .and. n == huge(n), 'huge default')
      if (allocated(error)) return
      call read_int('2147483648', n, why)
      call check_true(error, index(why, 'beyond the integer range') > 0, 'above huge: '//why)
      if (allocated(error)) return
      call read_int('9223372036854775807', n8, why)
      call check_true(error, len(why) == 0 .and. n8 == huge(n8), 'huge i8: '//why)
      if (allocated(error)) return
      call read_int('9223372036854775808', n8, why)
      call check_true(error, index(why, 'beyond the integer range') > 0, 'above i8: '//why)
      if (allocated(error)) return
      call read_int(repeat('9', 1000), n8, why)
      call check_true(error, index(why, 'beyond the integer range') > 0, '1000 digits')
      if (allocated(error)) return
      call read_int('1e3', n, why)
      call check_true(error, index(why, "character 'e' at position 2") > 0, '1e3: '//why)
      if (allocated(error)) return
      call read_int('1.0', n, why)
      call check_true(error, index(why, "character '.'") > 0, '1.0: '//why)
      if (allocated(error)) return
      call read_int('3'//achar(9), n, why)
      call check_true(error, index(why, "character '\t'") > 0, '3<tab>: '//why)
   end subroutine test_integers

   !> Control characters escaped so that a message stays on one line.
   subroutine test_escaped(error)
      type(error_t), allocatable, intent(out) :: error
      call check_true(error, escaped('a'//achar(9)//'b'//achar(10)//'c'//achar(13)) == &
                      'a\tb\nc\r', 'tab, line feed, carriage return')
      if (allocated(error)) return
      call check_true(error, escaped(achar(0)//achar(27)//achar(127)//char(200)) == &
                      '\x00\x1B\x7F\xC8', 'other bytes as \xNN')
      if (allocated(error)) return
      call check_true(error, escaped('a\b') == 'a\\b', 'a backslash doubled')
      if (allocated(error)) return
      call check_true(error, escaped('é\'//achar(10), controls_only=.true.) == 'é\\n', &
                      'controls_only leaves UTF-8 and backslashes')
      if (allocated(error)) return
      call check_true(error, quoted(repeat('x', 100)) == "'"//repeat('x', 64)//"...'", &
                      'quoted cuts long values')
   end subroutine test_escaped

   !> parse_real / parse_int: one line naming the flag and the character.
   subroutine test_flag_messages(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      real(dp) :: x
      integer :: n
      call parse_real('1;2', '--dt', x, err)
      call check_true(error, allocated(err), '--dt 1;2 accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, "invalid --dt: '1;2' is not a number " &
                                   //"(character ';' at position 2") == 1, err%message)
      if (allocated(error)) return
      call parse_real('0.7'//achar(9)//'1', '--q1', x, err)
      call check_true(error, allocated(err), '--q1 with a tab accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, achar(9)) == 0 .and. &
                      index(err%message, "'0.7\t1'") > 0, err%message)
      if (allocated(error)) return
      call parse_int('10'//achar(10), '--links', n, err)
      call check_true(error, allocated(err), '--links with a newline accepted')
      if (allocated(error)) return
      call check_true(error, index(err%message, achar(10)) == 0 .and. &
                      index(err%message, "'10\n'") > 0, err%message)
      if (allocated(error)) return
      call parse_real('0.25', '--dt', x, err)
      call check_true(error, .not. allocated(err) .and. x == 0.25_dp, '--dt 0.25')
   end subroutine test_flag_messages

   !> The namelist pre-scan refuses what the namelist read would resolve silently.
   subroutine test_namelist(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=1), parameter :: lf = achar(10)
      character(len=64) :: file
      integer :: clock
      call system_clock(clock)   ! a name of its own: parallel test runs do not collide
      write (file, '("/tmp/dpend-test-parse-", i0, ".nml")') clock
      call expect('&pendulum%m1 = 2 /', 'component syntax')
      call expect('&pendulum m1 = 2, g = 9.8, m1 = 3 /', "key 'm1' of &pendulum is given twice")
      call expect('&pendulum m = 1, 1, m1 = 5 /', "'m' (one value per link) and 'm1'")
      call expect('&initial q2 = 1'//lf//' q = 1, 2 /', 'line 2')
      call expect('&initial w = 1, 2, w2 = 1 /', "'w' (one value per link) and 'w2'")
      call expect('&pendulum l1 = 1, l = 1, 1 /', "'l' (one value per link) and 'l1'")
      call expect('&integration dt = 1;2 /', "key 'dt': '1;2' is not a number")
      call expect('&pendulum m1 = 1'//repeat('0', 999)//' /', 'beyond the largest double')
      call expect('&pendulum g = nan /', 'is not finite')
      call expect('&pendulum m = x*1 /', 'repeat count')
      call expect('&pendulum m(1) = 2, m = 1, 1 /', 'given twice')
      call expect('&integration dt = 1e-3 /'//lf//'&pendulum g = 0x1 /', 'line 2')
      ! a second value for a key that takes one (the read would keep the first)
      call expect('&integration dt = 0.001 0.002 /', "key 'dt': 2 values for a key that")
      call expect('&integration t_end = 2*5 /', "key 't_end': 2 values")
      call expect('&pendulum g = 9.8,'//lf//' 9.81 /', 'line 2')
      call expect("&integration method = 'rk4' 'dop853' /", "key 'method': 2 values")
      call expect('&output force = T F /', "key 'force': 2 values")
      ! accepted: lists, repeat counts, subscripts, strings with '%' and '=' inside,
      ! comments, logicals, tabs between values
      call accept('&pendulum m = 2*1.5, l(1) = 2, l(2) = 0.5, g = 9.81 / ! m1 = 3')
      call accept('&integration method = ''rk4'', dt = .5e-3,'//achar(9)//'t_end = 5. /')
      call accept('&output file = "a%b=c.h5", force = .true. /')
      call accept('&pendulum m = 1 2 3, damping = 0.1, 0.1, support_phase = 0 0 /')
      call accept('&initial q = 1 2, w(2) = 3 4, /'//lf//'&integration dt = 1, /')
      call accept('&initial q1 = -1.5 q2 = 0 w1 = 0, w2 = +0.0 /'//lf// &
                  '&pendulum m1 = 1, m2 = 2 /')
      call execute_command_line('rm -f '//trim(file))
   contains
      subroutine write_file(text)
         character(len=*), intent(in) :: text
         integer :: unit
         open (newunit=unit, file=trim(file), status='replace', action='write')
         write (unit, '(a)') text
         close (unit)
      end subroutine write_file
      subroutine expect(text, part)
         character(len=*), intent(in) :: text, part
         type(error_t), allocatable :: err
         if (allocated(error)) return
         call write_file(text)
         call check_groups(trim(file), [character(len=16) :: 'pendulum', 'initial', &
                                  'integration', 'output'], err)
         call check_true(error, allocated(err), 'accepted: '//text)
         if (allocated(error)) return
         call check_true(error, index(err%message, part) > 0, 'expected "'//part// &
                         '" in: '//err%message)
      end subroutine expect
      subroutine accept(text)
         character(len=*), intent(in) :: text
         type(error_t), allocatable :: err
         if (allocated(error)) return
         call write_file(text)
         call check_groups(trim(file), [character(len=16) :: 'pendulum', 'initial', &
                                  'integration', 'output'], err)
         if (allocated(err)) call fatal_error(error, 'refused: '//text//': '//err%message)
      end subroutine accept
   end subroutine test_namelist

   !> Two forms of one quantity on the command line are refused in either order.
   subroutine test_forms(error)
      type(error_t), allocatable, intent(out) :: error
      call expect(['--m ', '--m1'], ['1,2', '3  '], '--m was given too')
      call expect(['--m1', '--m '], ['3  ', '1,2'], '--m1 was given too')
      call expect(['--q1    ', '--theta1'], ['1', '1'], '--q1 was given too')
      call expect(['--theta2', '--q     '], ['1  ', '1,1'], '--theta2 was given too')
      call expect(['--w2', '--w '], ['1  ', '1,1'], '--w2 was given too')
      call expect(['--l ', '--l2'], ['1,1', '1  '], '--l was given too')
      call expect(['--q1', '--q1'], ['1', '2'], '')       ! the same flag: the last wins
      call expect(['--q1', '--q2'], ['1', '2'], '')
   contains
      subroutine expect(names, values, part)
         character(len=*), intent(in) :: names(2), values(2), part
         type(run_config_t) :: cfg
         type(error_t), allocatable :: err
         logical :: matched
         integer :: i
         if (allocated(error)) return
         do i = 1, 2
            call apply_run_flag(cfg, trim(names(i)), trim(values(i)), matched, err)
            if (allocated(err)) exit
         end do
         if (len(part) == 0) then
            call check_true(error, .not. allocated(err), trim(names(1))//' '//trim(names(2)))
         else
            call check_true(error, allocated(err), 'accepted: '//names(1)//' '//names(2))
            if (allocated(error)) return
            call check_true(error, index(err%message, part) > 0 .and. &
                            index(err%message, 'invalid '//trim(names(2))) == 1, err%message)
         end if
      end subroutine expect
   end subroutine test_forms

   !> g = 0 refused alike for 1, 2 (the range table) and 3 links; 1e-6 accepted.
   subroutine test_g_range(error)
      type(error_t), allocatable, intent(out) :: error
      type(error_t), allocatable :: err
      type(chain_t) :: chain
      integer :: n
      do n = 1, 3
         chain = chain_model(spread(1.0_dp, 1, n), spread(1.0_dp, 1, n), 0.0_dp, err)
         call check_true(error, allocated(err), 'g = 0 accepted by the chain')
         if (allocated(error)) return
         call check_true(error, index(err%message, 'invalid g: 0 m/s^2 is outside [1e-6, ' &
                                      //'1e6]') == 1, err%message)
         if (allocated(error)) return
         chain = chain_model(spread(1.0_dp, 1, n), spread(1.0_dp, 1, n), 1e-6_dp, err)
         call check_true(error, .not. allocated(err), 'g = 1e-6 refused')
         if (allocated(error)) return
      end do
      call check_parameter(parameter_gravity, 'g', 0.0_dp, err)
      call check_true(error, allocated(err), 'table: g = 0 accepted')
      if (allocated(error)) return
      call check_parameter(parameter_mass, 'm1', 1e6_dp, err)
      call check_true(error, .not. allocated(err), 'table: m1 = 1e6 refused')
   end subroutine test_g_range
   !> Edit distances by hand (insertions, deletions, substitutions, swaps; case and
   !> '_'/'-' ignored), the nearest name only when close, the options of a help text.
   subroutine test_suggestions(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: opts = '--t-end --dt --theta1 --theta2 --q1 --q --method'
      character(len=:), allocatable :: found
      call check_true(error, edit_distance('kitten', 'sitting') == 3, 'kitten/sitting 3')
      if (allocated(error)) return
      call check_true(error, edit_distance('tend', 't-end') == 1 .and. &
                      edit_distance('t_end', 'T-END') == 0 .and. &
                      edit_distance('fsp', 'fps') == 1 .and. edit_distance('', 'abc') == 3, &
                      'edit distances')
      if (allocated(error)) return
      call check_true(error, nearest_name('--t_end', opts) == '--t-end' .and. &
                      nearest_name('--tend', opts) == '--t-end' .and. &
                      nearest_name('--mehtod', opts) == '--method' .and. &
                      nearest_name('--theta', opts) == '--theta1', 'typos find their option')
      if (allocated(error)) return
      ! not close, the name itself, another number: no suggestion
      call check_true(error, nearest_name('--x', opts) == '' .and. &
                      nearest_name('--dt', opts) == '' .and. &
                      nearest_name('--q3', opts) == '' .and. &
                      nearest_name('--output', opts) == '' .and. &
                      nearest_name('rk5', method_names()) == '', 'no suggestion when far')
      if (allocated(error)) return
      call check_true(error, did_you_mean('mgeno', 'flip megno fli', '; ') == &
                      '; did you mean megno?' .and. did_you_mean('zz', 'flip megno') == '', &
                      did_you_mean('mgeno', 'flip megno fli', '; '))
      if (allocated(error)) return
      found = help_options('  --t-end S   end time (a--b is no option)'//new_line('a')// &
                           '  --q1, --q2 RAD  angles; see --t-end')
      call check_true(error, found == '--t-end --q1 --q2', 'help options: '//found)
      if (allocated(error)) return
      found = unknown_option_text('simulate', '--t_end', '--dt --t-end')
      call check_true(error, found == "unknown option '--t_end' (did you mean --t-end? dpend " &
                      //'simulate --help lists the options)', found)
   end subroutine test_suggestions

   !> Names of the registries without regard to case: every method of the registry
   !> in capitals builds; a list's own spelling comes back.
   subroutine test_any_case(error)
      type(error_t), allocatable, intent(out) :: error
      class(integrator_t), allocatable :: integ
      type(error_t), allocatable :: err
      type(run_config_t) :: cfg
      logical :: matched
      character(len=:), allocatable :: names
      integer :: a, b
      call check_true(error, canonical_name('MEGNO', 'flip megno') == 'megno' .and. &
                      canonical_name('Theta1', 'theta1,q1') == 'theta1' .and. &
                      canonical_name('nope', 'flip megno') == 'nope', 'canonical names')
      if (allocated(error)) return
      names = method_names()//' '
      a = 1
      do while (a < len(names))
         b = a + index(names(a:), ' ') - 1
         call new_integrator(upper(names(a:b - 1)), integ, err)
         call check_true(error, .not. allocated(err), 'method '//upper(names(a:b - 1)))
         if (allocated(error)) return
         call check_true(error, integ%name() == names(a:b - 1), 'name of '//names(a:b - 1))
         if (allocated(error)) return
         a = b + 1
      end do
      call apply_run_flag(cfg, '--method', 'DOP853', matched, err)
      call check_true(error, matched .and. .not. allocated(err) .and. cfg%method == 'dop853', &
                      '--method DOP853')
   contains
      pure function upper(w) result(t)
         character(len=*), intent(in) :: w
         character(len=len(w)) :: t
         integer :: k
         t = w
         do k = 1, len(w)
            if (w(k:k) >= 'a' .and. w(k:k) <= 'z') t(k:k) = achar(iachar(w(k:k)) - 32)
         end do
      end function upper
   end subroutine test_any_case

end module test_parse
