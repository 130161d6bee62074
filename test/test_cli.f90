!> The `dpend` command run as a process: every bad input ends with one line on
!> stderr naming the field, exit status 2 and no output file; a run that blows up
!> leaves a valid file; a trajectory matches the high-precision reference.
module test_cli
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t, is_hdf5
   use testing, only: unittest_t, new_unittest, check, check_true, error_t, fatal_error
   use dpend_cli, only: to_str, arg_t
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep
   use dpend_simulate, only: parse_simulate
   use dpend_run_settings, only: run_config_t
   implicit none
   private
   public :: collect_cli, dpend_binary, run_command, scratch_dir, read_text, expect_rejected
   public :: args_of

contains

   subroutine collect_cli(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('help_lists_options', test_help), &
               new_unittest('bad_input_rejected', test_bad_input), &
               new_unittest('bad_config_rejected', test_bad_config), &
               new_unittest('existing_output_kept', test_existing_output), &
               new_unittest('nonfinite_run_leaves_valid_file', test_nonfinite), &
               new_unittest('config_file_and_flags', test_config_run), &
               new_unittest('trajectory_matches_reference', test_reference), &
               new_unittest('dense_output_matches_reference', test_reference_dense), &
               new_unittest('theta_is_q_from_hanging', test_theta), &
               new_unittest('contradictions_name_both', test_contradictions)]
   end subroutine collect_cli

   !> Path of the dpend executable built with the same flags as this test program:
   !> fpm puts both under build/<compiler_hash>/{app,test}/.
   function dpend_binary() result(path)
      character(len=:), allocatable :: path
      character(len=4096) :: self
      integer :: slash
      call get_command_argument(0, self)
      slash = index(self, '/test/', back=.true.)
      if (slash == 0) then
         path = 'dpend'
      else
         path = self(:slash)//'app/dpend'
      end if
   end function dpend_binary

   !> A fresh scratch directory for this test run.
   function scratch_dir(tag) result(dir)
      character(len=*), intent(in) :: tag
      character(len=:), allocatable :: dir
      character(len=64) :: buf
      integer :: clock
      call system_clock(clock)
      write (buf, '("/tmp/dpend-test-", a, "-", i0)') tag, clock
      dir = trim(buf)
      call execute_command_line('rm -rf '//dir//' && mkdir -p '//dir)
   end function scratch_dir

   !> Run `dpend args` with stdout and stderr captured in dir; returns the exit status.
   integer function run_command(dir, args) result(stat)
      character(len=*), intent(in) :: dir, args
      call execute_command_line(dpend_binary()//' '//args//' > '//dir//'/stdout 2> '//dir// &
                                '/stderr', exitstat=stat)
   end function run_command

   !> Whole text file as lines joined by new_line; n_lines counts them.
   subroutine read_text(path, text, n_lines)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      integer, intent(out) :: n_lines
      integer :: unit, stat
      character(len=2048) :: line
      text = ''
      n_lines = 0
      open (newunit=unit, file=path, status='old', action='read', iostat=stat)
      if (stat /= 0) return
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         n_lines = n_lines + 1
         text = text//trim(line)//new_line('a')
      end do
      close (unit)
   end subroutine read_text

   !> Run `dpend command --output dir/out.h5 args` and expect exit status 2, exactly one
   !> stderr line containing `needle`, and no output file.
   subroutine expect_rejected(error, dir, command, args, needle)
      type(error_t), allocatable, intent(inout) :: error
      character(len=*), intent(in) :: dir      !! scratch directory
      character(len=*), intent(in) :: command  !! subcommand and fixed options
      character(len=*), intent(in) :: args     !! the options under test
      character(len=*), intent(in) :: needle   !! text the message must contain
      integer :: stat, n
      logical :: exists
      character(len=:), allocatable :: text
      if (allocated(error)) return
      stat = run_command(dir, merged_options(command//' --output '//dir//'/out.h5', args))
      call read_text(dir//'/stderr', text, n)
      inquire (file=dir//'/out.h5', exist=exists)
      call check_true(error, stat == 2, '['//command//' '//args//'] exit status 2, got '// &
                      to_str(stat)//'; stderr: '//text)
      call check_true(error, n == 1, '['//args//'] one stderr line, got '//to_str(n)//': '//text)
      call check_true(error, index(text, needle) > 0, '['//args//'] message names "'// &
                      needle//'": '//text)
      call check_true(error, .not. exists, '['//args//'] no output file')
   end subroutine expect_rejected

   subroutine test_help(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat, i
      character(len=12), parameter :: opts(20) = [character(len=12) :: '--config', '--q1', &
         '--q2', '--w1', '--w2', '--m1', '--m2', '--l1', '--l2', '--g', '--method', '--dt', &
         '--t-end', '--save-every', '--output', '--force', 'RAD/S', 'KG', 'M/S^2', 'default']
      dir = scratch_dir('help')
      stat = run_command(dir, 'simulate --help')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0, 'simulate --help exits 0')
      do i = 1, size(opts)
         call check_true(error, index(text, trim(opts(i))) > 0, 'help mentions '//trim(opts(i)))
      end do
      stat = run_command(dir, '--help')
      call read_text(dir//'/stdout', text, n)
      call check_true(error, stat == 0 .and. index(text, 'simulate') > 0, 'dpend --help')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_help

   subroutine test_bad_input(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('bad')
      call expect_rejected(error, dir, 'simulate', '--m1 -1', 'm1')
      call expect_rejected(error, dir, 'simulate', '--m2 0', 'm2')
      call expect_rejected(error, dir, 'simulate', '--l1 0', 'l1')
      call expect_rejected(error, dir, 'simulate', '--l2 -3', 'l2')
      call expect_rejected(error, dir, 'simulate', '--g 0', 'g')
      call expect_rejected(error, dir, 'simulate', '--g nan', '--g')
      call expect_rejected(error, dir, 'simulate', '--m1 inf', '--m1')
      call expect_rejected(error, dir, 'simulate', '--q1 nan', '--q1')
      call expect_rejected(error, dir, 'simulate', '--w2 -inf', '--w2')
      call expect_rejected(error, dir, 'simulate', '--dt 0', 'dt')
      call expect_rejected(error, dir, 'simulate', '--dt -1e-3', 'dt')
      call expect_rejected(error, dir, 'simulate', '--t-end -1', 't_end')
      call expect_rejected(error, dir, 'simulate', '--dt abc', '--dt')
      call expect_rejected(error, dir, 'simulate', '--save-every 0', 'save_every')
      call expect_rejected(error, dir, 'simulate', '--method nosuch', 'method')
      call expect_rejected(error, dir, 'simulate', '--bogus 1', 'unknown option')
      call expect_rejected(error, dir, 'simulate', '--dt', 'needs a value')
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/missing.nml', 'config')
      call expect_rejected(error, dir, 'simulate', '--output '//dir//'/no/such/dir/x.h5', 'directory')
      call expect_rejected(error, dir, 'simulate', '--output /proc/dpend-test.h5', 'not writable')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_bad_input

   subroutine test_bad_config(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir
      dir = scratch_dir('badcfg')
      call write_file(dir//'/group.nml', '&pendulum m1 = 2 /'//new_line('a')//'&bogus x = 1 /')
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/group.nml', 'unknown namelist group')
      call write_file(dir//'/key.nml', '&pendulum m1 = 2, mass3 = 1 /')
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/key.nml', 'mass3')
      call write_file(dir//'/nan.nml', '&pendulum m1 = NaN /')
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/nan.nml', 'm1')
      call write_file(dir//'/dt.nml', '&integration dt = -1 /')
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/dt.nml', 'dt')
      call write_file(dir//'/method.nml', "&integration method = 'euler' /")
      call expect_rejected(error, dir, 'simulate', '--config '//dir//'/method.nml', 'method')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_bad_config

   !> An existing output file without --force is refused and left as it was.
   subroutine test_existing_output(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text
      integer :: n, stat
      dir = scratch_dir('exists')
      call write_file(dir//'/out.h5', 'keep me')
      stat = run_command(dir, 'simulate --t-end 0.01 --output '//dir//'/out.h5')
      call check_true(error, stat == 2, 'exit status 2 for an existing output')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, n == 1 .and. index(text, 'exists') > 0, 'message: '//text)
      call read_text(dir//'/out.h5', text, n)
      call check_true(error, text == 'keep me'//new_line('a'), 'existing file untouched')
      stat = run_command(dir, 'simulate --t-end 0.01 --output '//dir//'/out.h5 --force')
      call check_true(error, stat == 0 .and. is_hdf5(dir//'/out.h5'), '--force overwrites')
      call execute_command_line('rm -rf '//dir)
   end subroutine test_existing_output

   !> A step far too large for rk4 makes the state overflow: exit 1, one message,
   !> and a valid HDF5 file with the samples before the failure and a status.
   subroutine test_nonfinite(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, text, status
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :)
      integer :: n, stat
      dir = scratch_dir('nonfinite')
      stat = run_command(dir, 'simulate --q1 0 --q2 0 --w1 30 --dt 2 --t-end 1e6 ' &
                         //'--save-every 1 --output '//dir//'/out.h5')
      call read_text(dir//'/stderr', text, n)
      call check_true(error, stat == 1, 'exit status 1, got '//to_str(stat)//': '//text)
      call check_true(error, n == 1 .and. index(text, 'non-finite') > 0, 'message: '//text)
      call check_true(error, is_hdf5(dir//'/out.h5'), 'valid HDF5 left behind')
      if (allocated(error)) return
      call h5%open(dir//'/out.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%readattr('/', 'status', status, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, size(t) >= 1 .and. all(abs(q) < huge(1.0_dp)), &
                      'samples before the failure are finite')
      call check_true(error, index(status, 'non-finite') > 0, 'status attribute: '//status)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_nonfinite

   !> The config file sets values and flags override them.
   subroutine test_config_run(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, method
      type(h5file_t) :: h5
      real(dp) :: m2, t_end
      real(dp), allocatable :: t(:)
      integer :: stat
      dir = scratch_dir('cfg')
      call write_file(dir//'/run.nml', '! comment'//new_line('a')// &
                      '&pendulum m2 = 2.5, g = 9.81 /'//new_line('a')// &
                      "&integration method = 'rk4', dt = 0.01, t_end = 3, save_every = 5 /")
      stat = run_command(dir, 'simulate --config '//dir//'/run.nml --t-end 1 --output '// &
                         dir//'/out.h5')
      call check_true(error, stat == 0, 'run with config exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/out.h5', 'r', error)
      if (allocated(error)) return
      call h5%readattr('/', 'm2', m2, error)
      if (.not. allocated(error)) call h5%readattr('/', 't_end', t_end, error)
      if (.not. allocated(error)) call h5%readattr('/', 'method', method, error)
      if (.not. allocated(error)) call h5%read('/trajectory/t', t, error)
      call h5%close()
      if (allocated(error)) return
      call check(error, m2, 2.5_dp, 'm2 from the file', abs=0.0_dp)
      call check(error, t_end, 1.0_dp, 't_end from the flag', abs=0.0_dp)
      call check_true(error, method == 'rk4', 'method attribute')
      call check_true(error, size(t) == 21, 'samples at 0, 0.05, ..., 1: '//to_str(size(t)))
      call check(error, t(size(t)), 1.0_dp, 'last sample at t_end', abs=1e-15_dp)
      call execute_command_line('rm -rf '//dir)
   end subroutine test_config_run

   !> dop853 at rtol = 1e-13 sampled by dense output at exactly t = 1..5 s against the
   !> same 40-digit reference: 1e-9 in q and q̇.
   subroutine test_reference_dense(error)
      type(error_t), allocatable, intent(out) :: error
      call compare_with_reference(error, 'dense', '--method dop853 --rtol 1e-13 --atol 1e-15 ' &
                                  //'--output-dt 1', 1e-9_dp)
   end subroutine test_reference_dense

   !> Horizontal release with rk4, dt = 1e-4, against the 40-digit Taylor-series
   !> solution of data/reference/release_horizontal.txt: 1e-8 in q and q̇ at t = 1..5.
   subroutine test_reference(error)
      type(error_t), allocatable, intent(out) :: error
      call compare_with_reference(error, 'ref', '--method rk4 --dt 1e-4 --save-every 10000', &
                                  1e-8_dp)
   end subroutine test_reference

   !> Run simulate from the horizontal release to t = 5 s with `options`, compare
   !> samples at t = 1..5 s with data/reference/release_horizontal.txt within `tol`.
   subroutine compare_with_reference(error, tag, options, tol)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), intent(in) :: tag, options
      real(dp), intent(in) :: tol
      character(len=:), allocatable :: dir
      type(h5file_t) :: h5
      real(dp), allocatable :: t(:), q(:, :), qd(:, :)
      real(dp) :: ref(5, 5)
      integer :: stat, unit, i
      character(len=256) :: line
      open (newunit=unit, file='data/reference/release_horizontal.txt', status='old', &
            action='read', iostat=stat)
      call check_true(error, stat == 0, 'reference table readable')
      if (allocated(error)) return
      i = 0
      do while (i < 5)
         read (unit, '(a)') line
         if (line(1:1) == '#') cycle
         i = i + 1
         read (line, *) ref(:, i)
      end do
      close (unit)
      dir = scratch_dir(tag)
      stat = run_command(dir, 'simulate --q1 0 --q2 0 --t-end 5 '//options//' --output ' &
                         //dir//'/run.h5')
      call check_true(error, stat == 0, 'simulate exits 0')
      if (allocated(error)) return
      call h5%open(dir//'/run.h5', 'r', error)
      if (allocated(error)) return
      call h5%read('/trajectory/t', t, error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q, error)
      if (.not. allocated(error)) call h5%read('/trajectory/qdot', qd, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, size(t) == 6, 'samples at t = 0..5')
      if (allocated(error)) return
      do i = 1, 5
         call check(error, t(i + 1), ref(1, i), 't', abs=1e-12_dp)
         call check(error, q(:, i + 1), ref(2:3, i), 'q', abs=tol)
         call check(error, qd(:, i + 1), ref(4:5, i), 'qdot', abs=tol)
      end do
      call execute_command_line('rm -rf '//dir)
   end subroutine compare_with_reference

   subroutine write_file(path, text)
      character(len=*), intent(in) :: path, text
      integer :: unit
      open (newunit=unit, file=path, status='replace', action='write')
      write (unit, '(a)') text
      close (unit)
   end subroutine write_file

   !> --theta1/--theta2 give the angles from the hanging position: q = θ − π/2,
   !> compared with π from acos(-1) (independent of dpend's constant), and the
   !> hanging position θ = 0 is q = -π/2 for both links.
   subroutine test_theta(error)
      use dpend_run_settings, only: run_config_t
      use dpend_run_flags, only: apply_run_flag
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      logical :: matched
      real(dp), parameter :: half = 0.5_dp*acos(-1.0_dp)
      call apply_run_flag(cfg, '--theta1', '0.3', matched, error)
      if (allocated(error)) return
      call check_true(error, matched, '--theta1 is a common flag')
      if (allocated(error)) return
      call check(error, cfg%q(1), 0.3_dp - half, 'q1 = 0.3 - pi/2', rel=1e-15_dp)
      if (allocated(error)) return
      call apply_run_flag(cfg, '--theta2', '0', matched, error)
      if (allocated(error)) return
      call check(error, cfg%q(2), -half, 'theta2 = 0 is hanging, q2 = -pi/2', rel=1e-15_dp)
   end subroutine test_theta

   !> `fixed` and `args` as one command line, the options of `args` replacing those
   !> of `fixed` (dpend refuses an option given twice, and --n with --n1 or --n2):
   !> blank-separated tokens, an option's value the next token not starting '--'.
   function merged_options(fixed, args) result(line)
      character(len=*), intent(in) :: fixed, args
      character(len=:), allocatable :: line, tok, nxt
      integer :: i, j, k
      line = ''
      i = 1
      do while (i <= len_trim(fixed))
         call next_token(fixed, i, tok)
         if (len(tok) == 0) exit
         if (tok(1:min(2, len(tok))) == '--' .and. replaced(tok)) then
            j = i
            call next_token(fixed, j, nxt)
            if (len(nxt) > 0) then
               if (nxt(1:min(2, len(nxt))) /= '--') i = j   ! skip its value too
            end if
            cycle
         end if
         line = line//tok//' '
      end do
      line = line//args
   contains
      logical function replaced(opt)
         character(len=*), intent(in) :: opt
         replaced = index(' '//args//' ', ' '//opt//' ') > 0
         if (opt == '--n') replaced = replaced .or. index(' '//args, ' --n1 ') > 0 .or. &
                                      index(' '//args, ' --n2 ') > 0
         if (opt == '--n1' .or. opt == '--n2') replaced = replaced .or. &
                                                         index(' '//args//' ', ' --n ') > 0
      end function replaced
      subroutine next_token(s, pos, t)
         character(len=*), intent(in) :: s
         integer, intent(inout) :: pos
         character(len=:), allocatable, intent(out) :: t
         do while (pos <= len(s))
            if (s(pos:pos) /= ' ') exit
            pos = pos + 1
         end do
         k = pos
         do while (pos <= len(s))
            if (s(pos:pos) == ' ') exit
            pos = pos + 1
         end do
         t = s(k:pos - 1)
      end subroutine next_token
   end function merged_options
   !> Two settings of one quantity are refused by the parsers, in either
   !> order, in one message naming both; the valid neighbours parse.
   subroutine test_contradictions(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: w = '--n 2 --t-end 0.5 --quiet '
      call sweep_case(w//'--theta1 3 --axis1 theta1', '--theta1: axis1')
      call sweep_case(w//'--axis1 theta1 --theta1 3', '--theta1: axis1')
      call sweep_case(w//'--axis1 q1 --q1 3', '--q1: axis1')
      call sweep_case(w//'--q2 1', '--q2: axis2')
      call sweep_case(w//'--axis1 w1 --axis2 w2 --w2 1', '--w2: axis2')
      call sweep_case(w//'--axis2 m2/m1 --min2 1 --max2 2 --m2 3', '--m2: axis2')
      call sweep_case('--quiet --ic-file x.csv --min1 3', '--min1: given with ic_file')
      call sweep_case('--quiet --ic-file x.csv --theta1 1', '--theta1: given with ic_file')
      call sweep_case(w//'--stop-at both --indicator fli', '--stop-at')
      call sweep_case(w//'--axis1 w1 --axis2 w2 --q1 1 --q2 0.5', '')
      call sweep_case(w//'--axis1 m2/m1 --min1 1 --max1 2 --m1 3', '')
      call sweep_case(w//'--indicator sali --stop-at end', '')
      call simulate_case('--save-every 3 --output-dt 0.1', '--output-dt: given with --save-every')
      call simulate_case('--output-dt 0.1 --save-every 3', '--output-dt: given with --save-every')
      call simulate_case('--output-dt 0.1', '')
   contains
      subroutine sweep_case(line, expected)
         character(len=*), intent(in) :: line, expected
         type(sweep_config_t) :: cfg
         type(error_t), allocatable :: err
         logical :: help
         if (allocated(error)) return
         call parse_sweep(args_of(line), cfg, help, err)
         call judge(line, err, expected)
      end subroutine sweep_case
      subroutine simulate_case(line, expected)
         character(len=*), intent(in) :: line, expected
         type(run_config_t) :: cfg
         type(error_t), allocatable :: err
         logical :: help
         if (allocated(error)) return
         call parse_simulate(args_of('--t-end 0.1 '//line), cfg, help, err)
         call judge(line, err, expected)
      end subroutine simulate_case
      subroutine judge(line, err, expected)
         character(len=*), intent(in) :: line, expected
         type(error_t), allocatable, intent(in) :: err
         if (len(expected) == 0) then
            if (allocated(err)) call fatal_error(error, "'"//line//"' refused: "//err%message)
         else if (.not. allocated(err)) then
            call fatal_error(error, "'"//line//"' accepted, expected a refusal")
         else if (index(err%message, expected) == 0) then
            call fatal_error(error, "'"//line//"': '"//err%message//"' lacks '"//expected//"'")
         end if
      end subroutine judge
   end subroutine test_contradictions

   !> The blank-separated words of `line` as command-line arguments.
   function args_of(line) result(args)
      character(len=*), intent(in) :: line  !! e.g. '--n 2 --quiet'
      type(arg_t), allocatable :: args(:)
      character(len=:), allocatable :: rest
      integer :: k
      allocate (args(0))
      rest = trim(adjustl(line))
      do while (len(rest) > 0)
         k = index(rest//' ', ' ')
         args = [args, arg_t(rest(:k - 1))]
         rest = trim(adjustl(rest(k:)))
      end do
   end function args_of
end module test_cli
