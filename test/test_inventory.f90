!> The dataset inventory: every dataset that a kind of output file holds is
!> named in `test/inventory/<kind>.txt` together with the tests that check its values
!> against an independent computation. One test per kind produces the files of that
!> kind in a scratch directory (every variant that writes different datasets), lists
!> their datasets and fails on
!>
!> - a dataset without a row (naming the dataset and the file variant),
!> - a row that no produced file holds (a stale row),
!> - a row whose test does not exist, or whose test procedure (with the procedures it
!>   contains) does not mention the dataset's leaf name,
!> - a missing or malformed inventory file.
!>
!> Row format, one per line, `#` starts a comment line:
!>
!>     /group/dataset   suite/test[,suite/test...]   how it is checked (free text)
!>
!> A path component `*` matches any one component (`/cases/*/*/step/h` in a study
!> file). The sources are read from `test/` relative to the working directory (fpm
!> test runs in the project root); without it the tests are skipped.
module test_inventory
   use dpend_kinds, only: dp
   use dpend_hdf5, only: h5file_t
   use dpend_cli, only: to_str
   use dpend_study_settings, only: study_config_t, validate_study_config
   use dpend_study, only: study_result_t, run_study
   use dpend_study_command, only: write_study_h5
   use test_cli, only: run_command, scratch_dir, read_text
   use testing, only: unittest_t, new_unittest, check_true, error_t, fatal_error, &
                      skip_test, have_tool, tiny_study_config
   implicit none
   private
   public :: collect_inventory, check_inventory, variant_t

   !> One way of producing a file of a kind: a label and the `dpend` arguments, in
   !> which `@OUT` stands for the output file (dir/label.h5) and `@DIR` for the
   !> scratch directory.
   type :: variant_t
      character(len=:), allocatable :: label  !! names the file variant in messages
      character(len=:), allocatable :: args   !! dpend command line
   end type variant_t

   !> A dataset found in a produced file.
   type :: found_t
      character(len=:), allocatable :: variant  !! the file variant holding it
      character(len=:), allocatable :: path     !! its absolute path
   end type found_t

   !> A row of an inventory file.
   type :: row_t
      integer :: line = 0                              !! line number in the file
      character(len=:), allocatable :: path            !! dataset path (may hold `*`)
      character(len=:), allocatable :: tests           !! suite/test[,suite/test...]
   end type row_t

   !> A source file of the test directory.
   type :: source_t
      character(len=:), allocatable :: name  !! path
      character(len=:), allocatable :: text  !! its lines joined by new_line
   end type source_t

   character(len=*), parameter :: inventory_dir = 'test/inventory/'
   integer, parameter :: max_listed = 60   !! most problems spelled out in one message

contains

   !> The inventory suite: one test per kind of output file.
   subroutine collect_inventory(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)  !! the tests
      tests = [ &
               new_unittest('simulate', test_simulate), &
               new_unittest('lyapunov', test_lyapunov), &
               new_unittest('indicators', test_indicators), &
               new_unittest('divergence', test_divergence), &
               new_unittest('poincare', test_poincare), &
               new_unittest('sweep', test_sweep), &
               new_unittest('study', test_study), &
               new_unittest('fit', test_fit), &
               new_unittest('torques', test_torques), &
               new_unittest('identify', test_identify), &
               new_unittest('animate', test_animate)]
   end subroutine collect_inventory

   !> simulate: two rods, damped with a moving support (W_friction, W_support,
   !> balance_error), a chain of 3 links, a damped chain, applied joint torques
   !> (W_torque, tau, the torque samples), the elastic pendulum, dense output of an
   !> adaptive method (--output-dt) and --save-every.
   subroutine test_simulate(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: common = 'simulate --t-end 0.05 --output @OUT'
      call produce_and_check(error, 'simulate', [ &
         variant_t('two_rods', common), &
         variant_t('damped_moving_support', common//' --damping 0.1,0.2 ' &
                   //'--support-amplitude 0.01,0.02 --support-frequency 3'), &
         variant_t('chain3', common//' --links 3 --q 0,0.1,0.2'), &
         variant_t('chain3_damped', common//' --links 3 --q 0,0.1,0.2 --damping 0.1,0.1,0.1'), &
         variant_t('chain1', common//' --links 1 --q 0.3'), &
         variant_t('torques', common//' --torque-file data/torque_example.csv'), &
         variant_t('elastic', common//' --model elastic --q 1.2,-1'), &
         variant_t('output_dt', common//' --method dop853 --output-dt 0.01'), &
         variant_t('save_every', common//' --save-every 3')])
   end subroutine test_simulate

   !> lyapunov: two rods and a chain of 3 links.
   subroutine test_lyapunov(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: common = 'lyapunov --t-end 2 --tau 0.5 --batches 2 ' &
                                              //'--output @OUT'
      call produce_and_check(error, 'lyapunov', [ &
         variant_t('two_rods', common), &
         variant_t('chain3', common//' --links 3 --q 0,0.1,0.2')])
   end subroutine test_lyapunov

   !> indicators: two rods and a chain of 3 links.
   subroutine test_indicators(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: common = 'indicators --t-end 1 --tau 0.1 --output @OUT'
      call produce_and_check(error, 'indicators', [ &
         variant_t('two_rods', common), &
         variant_t('chain3', common//' --links 3 --q 0,0.1,0.2')])
   end subroutine test_indicators

   !> divergence: two rods and a chain of 3 links (with the Benettin run beside it).
   subroutine test_divergence(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: common = 'divergence --t-end 1 --pairs 2 ' &
                                      //'--pair-spacing 0.5 --lyapunov-t 1 --output @OUT'
      call produce_and_check(error, 'divergence', [ &
         variant_t('two_rods', common), &
         variant_t('chain3', common//' --links 3 --q 0,0.1,0.2')])
   end subroutine test_divergence

   !> poincare: two rods (the sections need the two-link energy shell).
   subroutine test_poincare(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call produce_and_check(error, 'poincare', [ &
         variant_t('two_rods', 'poincare --t-end 5 --ics 2 --points 4 --output @OUT')])
   end subroutine test_poincare

   !> sweep: a flip grid (with --lyapunov and --stats), every indicator map, a list of
   !> initial conditions, a parameter axis, three links and the elastic pendulum.
   subroutine test_sweep(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), parameter :: common = 'sweep --n 4 --t-end 1 --quiet --threads 1 ' &
                                              //'--output @OUT'
      call produce_and_check(error, 'sweep', [ &
         variant_t('flip_grid', common), &
         variant_t('flip_lyapunov_stats', common//' --lyapunov --stats'), &
         variant_t('megno', common//' --indicator megno'), &
         variant_t('fli', common//' --indicator fli'), &
         variant_t('sali', common//' --indicator sali'), &
         variant_t('gali2', common//' --indicator gali2'), &
         variant_t('lambda1', common//' --indicator lambda1'), &
         variant_t('list', 'sweep --config data/sweep_list.nml --t-end 1 --quiet ' &
                   //'--threads 1 --output @OUT'), &
         variant_t('parameter_axis', 'sweep --config data/sweep_theta1_mass_ratio.nml ' &
                   //'--n 4 --t-end 1 --quiet --threads 1 --output @OUT'), &
         variant_t('triple', 'sweep --config data/sweep_triple.nml --n 4 --t-end 1 --quiet ' &
                   //'--threads 1 --output @OUT'), &
         variant_t('elastic_megno', 'sweep --config data/elastic_sweep.nml --n 4 --t-end 1 ' &
                   //'--quiet --threads 1 --output @OUT')])
   end subroutine test_sweep

   !> study: a tiny study run in process (two cases, four methods, a roundoff and a
   !> Tao experiment), written by the study command's writer.
   subroutine test_study(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      character(len=:), allocatable :: dir
      if (.not. have_sources()) return
      cfg = tiny_study_config(300.0_dp, 30.0_dp)
      call validate_study_config(cfg, error)
      if (allocated(error)) return
      call run_study(cfg, res, quiet=.true.)
      dir = scratch_dir('inventory-study')
      call write_study_h5(cfg, res, dir//'/tiny_study.h5', error)
      if (allocated(error)) return
      call check_inventory(error, 'study', [character(len=10) :: 'tiny_study'], &
                           [dir//'/tiny_study.h5'])
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_study

   !> fit: angles (data/fit_example.csv, with and without --fit-damping; a short fit
   !> window keeps it fast), the elastic pendulum (data/fit_elastic.csv) and the
   !> positions of the link ends (a file written here: the pendulum hanging at rest).
   subroutine test_fit(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: csv
      integer :: i
      csv = 't,x1,y1,x2,y2'//new_line('a')
      do i = 0, 10
         csv = csv//to_str(i)//'e-2,0,-1,0,-2'//new_line('a')
      end do
      call produce_and_check(error, 'fit', [ &
         variant_t('angles', 'fit data/fit_example.csv --fit-window 0.3 --output @OUT'), &
         variant_t('angles_damping', 'fit data/fit_example.csv --fit-damping ' &
                   //'--fit-window 0.3 --output @OUT'), &
         variant_t('elastic', 'fit data/fit_elastic.csv --model elastic --output @OUT'), &
         variant_t('positions', 'fit @DIR/positions.csv --output @OUT')], &
         'positions.csv', csv)
   end subroutine test_fit

   !> torques: angles only (data/fit_example.csv) and with measured torques
   !> (data/robot_example.csv): the latter adds tau_measured and residual.
   subroutine test_torques(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call produce_and_check(error, 'torques', [ &
         variant_t('angles', 'torques data/fit_example.csv --damping 0.05,0.03 --quiet ' &
                   //'--output @OUT'), &
         variant_t('measured', 'torques data/robot_example.csv --m 1,0.7 --l 0.8,0.6 ' &
                   //'--quiet --output @OUT')])
   end subroutine test_torques

   !> identify: data/robot_example.csv, every friction estimated and none.
   subroutine test_identify(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      call produce_and_check(error, 'identify', [ &
         variant_t('robot', 'identify data/robot_example.csv --m 1,0.7 --l 0.8,0.6 ' &
                   //'--coulomb-speed 0.5 --quiet --output @OUT'), &
         variant_t('friction_known', 'identify data/robot_example.csv --m 1,0.7 --l 0.8,0.6 ' &
                   //'--friction none --damping 0.02,0.01 --coulomb 0.05,0.03 ' &
                   //'--coulomb-speed 0.5 --quiet --output @OUT')])
   end subroutine test_identify

   !> animate writes a GIF and no HDF5 file: its data go to gnuplot through transient
   !> text tables written by private procedures. The inventory of `animate` lists no
   !> dataset; the test checks that the run writes its GIF and no other file.
   subroutine test_animate(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=:), allocatable :: dir, listing
      integer :: stat, n
      if (.not. have_sources()) return
      if (.not. have_tool('gnuplot')) then
         call skip_test('gnuplot not found')
         return
      end if
      dir = scratch_dir('inventory-animate')
      stat = run_command(dir, 'simulate --t-end 0.2 --output '//dir//'/sim.h5')
      call check_true(error, stat == 0, 'inventory/animate: the simulate run failed')
      if (allocated(error)) return
      stat = run_command(dir, 'animate '//dir//'/sim.h5 --fps 10 --size 64x64 --output ' &
                         //dir//'/anim.gif')
      call check_true(error, stat == 0, 'inventory/animate: dpend animate exit '// &
                      to_str(stat))
      if (allocated(error)) return
      ! the scratch directory holds the input, the GIF and the captured output only
      call execute_command_line('ls '//dir//' > '//dir//'/listing.txt', exitstat=stat)
      call read_text(dir//'/listing.txt', listing, n)
      call check_true(error, listing == 'anim.gif'//new_line('a')//'listing.txt'// &
                      new_line('a')//'sim.h5'//new_line('a')//'stderr'//new_line('a')// &
                      'stdout'//new_line('a'), 'inventory/animate: animate wrote '// &
                      'files other than its GIF: '//listing)
      if (allocated(error)) return
      call check_inventory(error, 'animate', [character(len=1) ::], [character(len=1) ::])
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine test_animate

   ! ----------------------------------------------------------------- helpers

   !> Whether the test sources are here; skips the running test if not.
   logical function have_sources()
      inquire (file='test/main.f90', exist=have_sources)
      if (.not. have_sources) call skip_test('test/main.f90 not found: run from the project '// &
                                             'root (the inventory reads the test sources)')
   end function have_sources

   !> Run every variant of `kind` into a scratch directory, then check the inventory.
   !> `input_name` and `input_text`: a file written into the scratch directory first.
   subroutine produce_and_check(error, kind, variants, input_name, input_text)
      type(error_t), allocatable, intent(out) :: error   !! set on failure
      character(len=*), intent(in) :: kind               !! kind of output file
      type(variant_t), intent(in) :: variants(:)         !! how to produce its files
      character(len=*), intent(in), optional :: input_name  !! an input file (@DIR/name)
      character(len=*), intent(in), optional :: input_text  !! its text
      character(len=:), allocatable :: dir, args, text
      character(len=256), allocatable :: labels(:), files(:)
      integer :: i, stat, n, unit
      if (.not. have_sources()) return
      dir = scratch_dir('inventory-'//kind)
      if (present(input_name) .and. present(input_text)) then
         open (newunit=unit, file=dir//'/'//input_name, status='replace', action='write', &
               access='stream', form='unformatted')
         write (unit) input_text
         close (unit)
      end if
      allocate (labels(size(variants)), files(size(variants)))
      do i = 1, size(variants)
         labels(i) = variants(i)%label
         files(i) = dir//'/'//variants(i)%label//'.h5'
         args = replace_all(replace_all(variants(i)%args, '@OUT', trim(files(i))), '@DIR', dir)
         stat = run_command(dir, args)
         if (stat /= 0) then
            call read_text(dir//'/stderr', text, n)
            call fatal_error(error, 'inventory/'//kind//': variant '//variants(i)%label// &
                             ': `dpend '//args//'` exit '//to_str(stat)//': '//text)
            return
         end if
      end do
      call check_inventory(error, kind, labels, files)
      if (.not. allocated(error)) call execute_command_line('rm -rf '//dir)
   end subroutine produce_and_check

   !> Check the inventory of `kind` against the datasets of `files` (variant `labels`).
   subroutine check_inventory(error, kind, labels, files)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      character(len=*), intent(in) :: kind              !! kind of output file
      character(len=*), intent(in) :: labels(:)         !! file variants
      character(len=*), intent(in) :: files(:)          !! the files, one per variant
      type(found_t), allocatable :: found(:)
      type(row_t), allocatable :: rows(:)
      type(source_t), allocatable :: sources(:)
      character(len=:), allocatable :: main, problems, why
      integer :: i, j, k, n_problems
      logical :: covered
      if (.not. have_sources()) return
      call list_all(labels, files, found, error)
      if (allocated(error)) return
      call read_rows(kind, rows, error)
      if (allocated(error)) return
      problems = ''
      n_problems = 0
      ! every dataset has a row (named once, with every file variant that holds it)
      do i = 1, size(found)
         covered = .false.
         do k = 1, i - 1
            if (found(k)%path == found(i)%path) covered = .true.
         end do
         if (covered) cycle   ! named with its first occurrence
         do j = 1, size(rows)
            if (path_matches(rows(j)%path, found(i)%path)) then
               covered = .true.
               exit
            end if
         end do
         if (covered) cycle
         why = found(i)%variant
         do k = i + 1, size(found)
            if (found(k)%path == found(i)%path) why = why//', '//found(k)%variant
         end do
         call add_problem(found(i)%path//' has no row (file variants: '//why//')')
      end do
      ! every row names a dataset that some file holds
      do j = 1, size(rows)
         covered = .false.
         do i = 1, size(found)
            if (path_matches(rows(j)%path, found(i)%path)) then
               covered = .true.
               exit
            end if
         end do
         if (.not. covered) call add_problem('stale row '//row_name(rows(j))// &
                                             ': no produced file holds it')
      end do
      ! every row's tests exist and name the dataset's leaf
      if (size(rows) > 0) then
         call read_sources(main, sources, error)
         if (allocated(error)) return
      end if
      do j = 1, size(rows)
         k = 1
         do
            call next_test(rows(j)%tests, k, why)
            if (len(why) == 0) exit
            call check_named_test(why)
         end do
      end do
      if (n_problems > 0) then
         if (n_problems > max_listed) problems = problems//'; and '// &
                                                  to_str(n_problems - max_listed)//' more'
         call fatal_error(error, inventory_dir//kind//'.txt: '//to_str(n_problems)// &
                          ' problem(s): '//problems)
      end if
   contains
      !> Record one problem (the first max_listed are spelled out).
      subroutine add_problem(text)
         character(len=*), intent(in) :: text  !! the problem
         n_problems = n_problems + 1
         if (n_problems > max_listed) return
         if (len(problems) > 0) problems = problems//'; '
         problems = problems//text
      end subroutine add_problem

      !> The test `name` (suite/test) of row j exists and mentions the leaf.
      subroutine check_named_test(name)
         character(len=*), intent(in) :: name  !! suite/test
         character(len=:), allocatable :: body, leaf, reason
         call test_source(main, sources, name, body, reason)
         if (len(reason) > 0) then
            call add_problem(row_name(rows(j))//': '//reason)
            return
         end if
         leaf = leaf_of(rows(j)%path)
         if (index(body, leaf) == 0) call add_problem(row_name(rows(j))//': the procedure '// &
            'of test '//name//' does not mention '''//leaf//'''')
      end subroutine check_named_test
   end subroutine check_inventory

   !> "path (line N)" for messages.
   function row_name(row) result(s)
      type(row_t), intent(in) :: row  !! the row
      character(len=:), allocatable :: s
      s = row%path//' (line '//to_str(row%line)//')'
   end function row_name

   !> The datasets of every file, with the variant that holds each.
   subroutine list_all(labels, files, found, error)
      character(len=*), intent(in) :: labels(:)          !! file variants
      character(len=*), intent(in) :: files(:)           !! the files
      type(found_t), allocatable, intent(out) :: found(:) !! every dataset of every file
      type(error_t), allocatable, intent(out) :: error   !! set on failure
      type(h5file_t) :: h5
      character(len=:), allocatable :: paths(:)
      integer :: i, j
      allocate (found(0))
      do i = 1, size(files)
         call h5%open(trim(files(i)), 'r', error)
         if (allocated(error)) return
         call h5%datasets('/', paths, error)
         call h5%close()
         if (allocated(error)) return
         do j = 1, size(paths)
            found = [found, found_t(trim(labels(i)), trim(paths(j)))]
         end do
      end do
   end subroutine list_all

   !> The rows of test/inventory/<kind>.txt; a missing file or a malformed row fails.
   subroutine read_rows(kind, rows, error)
      character(len=*), intent(in) :: kind                !! kind of output file
      type(row_t), allocatable, intent(out) :: rows(:)    !! the rows
      type(error_t), allocatable, intent(out) :: error    !! set on failure
      character(len=:), allocatable :: text, line, file
      integer :: n, pos, eol, number, a, b
      logical :: exists
      file = inventory_dir//kind//'.txt'
      allocate (rows(0))
      inquire (file=file, exist=exists)
      if (.not. exists) then
         call fatal_error(error, file//' is missing: the inventory of '//kind// &
                          ' files has no rows')
         return
      end if
      call read_text(file, text, n)
      pos = 1
      number = 0
      do while (pos <= len(text))
         eol = index(text(pos:), new_line('a')) + pos - 1
         line = text(pos:eol - 1)
         pos = eol + 1
         number = number + 1
         a = verify(line, ' '//achar(9))
         if (a == 0) cycle
         if (line(a:a) == '#') cycle
         block
            type(row_t) :: row
            row%line = number
            b = end_of_token(line, a)
            row%path = line(a:b)
            a = verify(line(b + 1:)//' ', ' '//achar(9)) + b
            if (a > len(line)) then
               call fatal_error(error, file//' line '//to_str(number)//': a row is '// &
                  '"/group/dataset  suite/test[,suite/test]  how it is checked": '//line)
               return
            end if
            b = end_of_token(line, a)
            row%tests = line(a:b)
            if (row%path(1:1) /= '/' .or. verify(line(b + 1:), ' '//achar(9)) == 0 .or. &
                index(row%tests, '/') == 0 .or. leaf_of(row%path) == '*' .or. &
                leaf_of(row%path) == '') then
               call fatal_error(error, file//' line '//to_str(number)//': a row is '// &
                  '"/group/dataset  suite/test[,suite/test]  how it is checked" (an '// &
                  'absolute path with a named leaf, tests, then the description): '//line)
               return
            end if
            rows = [rows, row]
         end block
      end do
   end subroutine read_rows

   !> Position of the last character of the blank-delimited token that starts at a.
   pure integer function end_of_token(line, a) result(b)
      character(len=*), intent(in) :: line  !! the line
      integer, intent(in) :: a              !! first character of the token
      b = scan(line(a:), ' '//achar(9))
      if (b == 0) then
         b = len(line)
      else
         b = a + b - 2
      end if
   end function end_of_token

   !> The next comma-separated item of `list` from position k (empty at the end).
   subroutine next_test(list, k, item)
      character(len=*), intent(in) :: list                !! suite/test,suite/test...
      integer, intent(inout) :: k                         !! position, advanced
      character(len=:), allocatable, intent(out) :: item  !! the item
      integer :: c
      if (k > len(list)) then
         item = ''
         return
      end if
      c = index(list(k:), ',')
      if (c == 0) then
         item = list(k:)
         k = len(list) + 1
      else
         item = list(k:k + c - 2)
         k = k + c
      end if
   end subroutine next_test

   !> The last path component.
   pure function leaf_of(path) result(leaf)
      character(len=*), intent(in) :: path  !! /a/b/c
      character(len=:), allocatable :: leaf
      leaf = path(index(path, '/', back=.true.) + 1:)
   end function leaf_of

   !> Whether `path` matches `pattern` component by component (`*` matches any one).
   pure logical function path_matches(pattern, path) result(ok)
      character(len=*), intent(in) :: pattern  !! row path, may hold `*` components
      character(len=*), intent(in) :: path     !! dataset path
      integer :: a, b, ea, eb
      ok = .false.
      a = 1; b = 1
      do
         ea = index(pattern(a:)//'/', '/') + a - 1   ! one past the component
         eb = index(path(b:)//'/', '/') + b - 1
         if (pattern(a:ea - 1) /= '*' .and. pattern(a:ea - 1) /= path(b:eb - 1)) return
         if (pattern(a:ea - 1) == '*' .and. eb == b) return   ! `*` needs a name
         a = ea + 1; b = eb + 1
         if (a > len(pattern) .or. b > len(path)) exit
      end do
      ok = a > len(pattern) .and. b > len(path)
   end function path_matches

   !> Every occurrence of `what` in `s` replaced by `by`.
   function replace_all(s, what, by) result(r)
      character(len=*), intent(in) :: s, what, by  !! text, pattern, replacement
      character(len=:), allocatable :: r
      integer :: p, k
      r = ''
      p = 1
      do
         k = index(s(p:), what)
         if (k == 0) exit
         r = r//s(p:p + k - 2)//by
         p = p + k - 1 + len(what)
      end do
      r = r//s(p:)
   end function replace_all

   !> test/main.f90 and every test/*.f90.
   subroutine read_sources(main, sources, error)
      character(len=:), allocatable, intent(out) :: main            !! test/main.f90
      type(source_t), allocatable, intent(out) :: sources(:)        !! test/*.f90
      type(error_t), allocatable, intent(out) :: error              !! set on failure
      character(len=:), allocatable :: dir, listing, name, text
      integer :: n, pos, eol, stat
      call read_text('test/main.f90', main, n)
      dir = scratch_dir('inventory-sources')
      call execute_command_line('ls test/*.f90 > '//dir//'/sources.txt', exitstat=stat)
      call read_text(dir//'/sources.txt', listing, n)
      if (stat /= 0 .or. n == 0) then
         call fatal_error(error, 'inventory: cannot list test/*.f90')
         return
      end if
      allocate (sources(0))
      pos = 1
      do while (pos <= len(listing))
         eol = index(listing(pos:), new_line('a')) + pos - 1
         name = listing(pos:eol - 1)
         pos = eol + 1
         call read_text(name, text, n)
         sources = [sources, source_t(name, text)]
      end do
      call execute_command_line('rm -rf '//dir)
   end subroutine read_sources

   !> The source of the procedure of test `name` (suite/test), with the procedures it
   !> contains; `reason` says why not found (empty when found).
   subroutine test_source(main, sources, name, body, reason)
      character(len=*), intent(in) :: main                  !! test/main.f90
      type(source_t), intent(in) :: sources(:)              !! test/*.f90
      character(len=*), intent(in) :: name                  !! suite/test
      character(len=:), allocatable, intent(out) :: body    !! the procedure's text
      character(len=:), allocatable, intent(out) :: reason  !! why not found
      character(len=:), allocatable :: suite, test, collect, proc, cbody
      integer :: slash, k, i
      body = ''
      slash = index(name, '/')
      suite = name(:slash - 1)
      test = name(slash + 1:)
      k = index(main, "call add('"//suite//"', collect_")
      if (slash <= 1 .or. k == 0) then
         reason = 'test '//name//': no suite '''//suite//''' in test/main.f90'
         return
      end if
      collect = identifier_at(main, k + len("call add('"//suite//"', "))
      do i = 1, size(sources)
         cbody = procedure_text(sources(i)%text, collect)
         if (len(cbody) == 0) cycle
         k = index(cbody, "new_unittest('"//test//"'")
         if (k == 0) then
            reason = 'test '//name//': no new_unittest('''//test//''', ...) in '//collect// &
                     ' ('//sources(i)%name//')'
            return
         end if
         k = k + len("new_unittest('"//test//"'")
         k = k + verify(cbody(k:), ' ,&'//new_line('a')//achar(9)) - 1
         proc = identifier_at(cbody, k)
         body = procedure_text(sources(i)%text, proc)
         reason = ''
         if (len(body) == 0) reason = 'test '//name//': procedure '//proc//' not found in '// &
                                      sources(i)%name
         return
      end do
      reason = 'test '//name//': subroutine '//collect//' not found in test/*.f90'
   end subroutine test_source

   !> The identifier (letters, digits, _) that starts at position k of s.
   pure function identifier_at(s, k) result(id)
      character(len=*), intent(in) :: s  !! text
      integer, intent(in) :: k           !! start
      character(len=:), allocatable :: id
      integer :: e
      character(len=*), parameter :: chars = 'abcdefghijklmnopqrstuvwxyz' // &
                                     'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
      if (k < 1 .or. k > len(s)) then
         id = ''
         return
      end if
      e = verify(s(k:), chars)
      if (e == 0) then
         id = s(k:)
      else
         id = s(k:k + e - 2)
      end if
   end function identifier_at

   !> The text from `subroutine NAME(` to `end subroutine NAME` in `text` (empty if
   !> absent), which includes the procedures NAME contains.
   function procedure_text(text, name) result(body)
      character(len=*), intent(in) :: text  !! a source file
      character(len=*), intent(in) :: name  !! procedure name
      character(len=:), allocatable :: body
      integer :: a, b
      body = ''
      if (len(name) == 0) return
      a = word_index(text, 'subroutine '//name//'(')
      if (a == 0) return
      b = index(text(a:), 'end subroutine '//name)
      if (b == 0) return
      body = text(a:a + b - 2 + len('end subroutine '//name))
   end function procedure_text

   !> First position of `word` in `text` preceded by a blank or a line start.
   pure integer function word_index(text, word) result(k)
      character(len=*), intent(in) :: text, word  !! where, what
      integer :: p, j
      p = 1
      do
         j = index(text(p:), word)
         if (j == 0) then
            k = 0
            return
         end if
         k = p + j - 1
         if (k == 1) return
         if (text(k - 1:k - 1) == ' ' .or. text(k - 1:k - 1) == new_line('a')) return
         p = k + 1
      end do
   end function word_index
end module test_inventory
