!> Tests of the C interface (src/capi): a run through `dpend_run` writes, in memory,
!> the file the command writes (compared dataset by dataset and attribute by
!> attribute with h5diff against the command's file, for several methods, models,
!> bodies and commands); its refusals are the command line's lines; two runs in two
!> threads give the results of two single runs; options the library sets itself and
!> commands it does not run are refused with their kinds; a progress callback is
!> told of a sweep from its start to its end; a result's named arrays are the
!> datasets and attributes of its file.
module test_capi
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_null_char, c_loc, &
      c_null_ptr, c_associated, c_long_long, c_funptr, c_funloc, c_null_funptr, &
      c_f_pointer
   use, intrinsic :: iso_fortran_env, only: int8
   use testing, only: unittest_t, new_unittest, check_true, error_t, have_tool, skip_test
   use test_cli, only: run_command, scratch_dir, read_text
   use dpend_strings, only: to_str
   use dpend_capi, only: dpend_run, dpend_run_progress
   use dpend_capi_result, only: dpend_result_bytes, dpend_result_copy, dpend_result_free, &
      dpend_result_items, dpend_result_item, dpend_result_find, dpend_result_item_copy, &
      dpend_result_item_bytes
   use dpend_hdf5, only: h5file_t
   use dpend_kinds, only: dp
   use dpend_output, only: output_t
   use dpend_capi_settings, only: dpend_settings_new, dpend_settings_set, &
      dpend_settings_run, dpend_settings_free
   use dpend_error, only: fatal_error
   implicit none
   private
   public :: collect_capi

   !> What the progress callback was told: calls, the first and last `done`, the
   !> totals seen, whether `done` ever went back, the last unit and label.
   type :: told_t
      integer :: calls = 0
      integer(c_long_long) :: first = -1, last = -1, total = -1
      logical :: monotone = .true., same_total = .true.
      character(len=32) :: what = '', label = ''
   end type told_t
   type(told_t), save :: told

   !> A string kept alive for its C pointer.
   type :: c_text_t
      character(kind=c_char, len=:), allocatable :: s
   end type c_text_t

contains

   subroutine collect_capi(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
               new_unittest('runs_equal_command_files', test_equal_files), &
               new_unittest('refusals_are_the_command_lines', test_refusals), &
               new_unittest('two_threads_equal_single_runs', test_threads), &
               new_unittest('library_options_refused', test_library_options), &
               new_unittest('progress_callback_told', test_progress), &
               new_unittest('items_are_the_files_datasets', test_items), &
               new_unittest('captured_output_explained', test_explain_captured), &
               new_unittest('settings_by_name_and_value', test_settings)]
   end subroutine collect_capi

   !> Run `command` with the blank-separated `options` through dpend_run: the error
   !> kind, the message and the image (empty when there is none).
   subroutine library_run(command, options, kind, message, image, progress)
      character(len=*), intent(in) :: command, options
      integer, intent(out) :: kind
      character(len=:), allocatable, intent(out) :: message
      integer(int8), allocatable, intent(out) :: image(:)
      type(c_funptr), intent(in), optional :: progress   !! dpend_run_progress's fn
      type(c_text_t), allocatable, target :: words(:)
      type(c_text_t), target :: name
      type(c_ptr), allocatable, target :: ptrs(:)
      character(kind=c_char, len=4096), target :: msg
      type(c_ptr) :: result
      integer :: i, n
      integer(c_long_long) :: bytes
      integer(int8), allocatable, target :: buf(:)
      call split_words(options, words)
      allocate (ptrs(max(size(words), 1)))
      do i = 1, size(words)
         ptrs(i) = c_loc(words(i)%s)
      end do
      name%s = command//c_null_char
      if (present(progress)) then
         kind = dpend_run_progress(c_loc(name%s), int(size(words), c_int), c_loc(ptrs), &
                                   result, c_loc(msg), int(len(msg), c_int), progress, &
                                   c_null_ptr)
      else
         kind = dpend_run(c_loc(name%s), int(size(words), c_int), c_loc(ptrs), result, &
                          c_loc(msg), int(len(msg), c_int))
      end if
      n = index(msg, c_null_char) - 1
      message = msg(:n)
      allocate (image(0))
      if (.not. c_associated(result)) return
      bytes = dpend_result_bytes(result)
      allocate (buf(bytes))
      if (dpend_result_copy(result, c_loc(buf), bytes) == 0) call move_alloc(buf, image)
      call dpend_result_free(result)
   end subroutine library_run

   !> The blank-separated words of `text`, each NUL-terminated.
   subroutine split_words(text, words)
      character(len=*), intent(in) :: text
      type(c_text_t), allocatable, intent(out) :: words(:)
      integer :: i, j
      allocate (words(0))
      i = 1
      do while (i <= len(text))
         if (text(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         j = index(text(i:)//' ', ' ') + i - 2
         words = [words, c_text_t(text(i:j)//c_null_char)]
         i = j + 1
      end do
   end subroutine split_words

   subroutine write_bytes(path, image)
      character(len=*), intent(in) :: path
      integer(int8), intent(in) :: image(:)
      integer :: unit
      open (newunit=unit, file=path, access='stream', form='unformatted', status='replace', &
            action='write')
      write (unit) image
      close (unit)
   end subroutine write_bytes

   !> Whether h5diff finds no difference between files a and b.
   logical function same_files(a, b)
      character(len=*), intent(in) :: a, b
      integer :: stat
      call execute_command_line('h5diff '//a//' '//b//' > /dev/null 2>&1', exitstat=stat)
      same_files = stat == 0
   end function same_files

   !> Each case through the library and through the command: the same file.
   subroutine test_equal_files(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: cases(*) = [character(len=120) :: &
         'simulate --q1 0 --q2 0 --t-end 1', &
         'simulate --method dop853 --q1 0.3 --q2 -1 --t-end 2', &
         'simulate --method gauss6 --q1 0.3 --q2 -1 --t-end 0.5', &
         'simulate --method verlet --t-end 0.5', &
         'simulate --model elastic --q 1.2,-1 --k 40 --l0 1 --t-end 1', &
         'simulate --links 3 --t-end 0.5', &
         'simulate --body point --q1 0.2 --t-end 0.5', &
         'simulate --damping 0.1,0.05 --t-end 0.5', &
         'lyapunov --t-end 2 --tau 0.5', &
         'indicators --t-end 2', &
         'divergence --t-end 1', &
         'poincare --t-end 5', &
         'sweep --n 16 --t-end 1']
      character(len=:), allocatable :: dir, message, cmd, opts
      integer(int8), allocatable :: image(:)
      integer :: i, kind, stat, sp
      if (.not. have_tool('h5diff')) then
         call skip_test('h5diff is not installed')
         return
      end if
      dir = scratch_dir('capi')
      do i = 1, size(cases)
         sp = index(cases(i), ' ')
         cmd = cases(i)(:sp - 1)
         opts = trim(cases(i)(sp + 1:))
         call library_run(cmd, opts, kind, message, image)
         call check_true(error, kind == 0 .and. size(image) > 0, '['//trim(cases(i))// &
                         '] kind 0 and a file, got kind '//to_str(kind)//': '//message)
         if (allocated(error)) return
         call write_bytes(dir//'/lib.h5', image)
         stat = run_command(dir, trim(cases(i))//' --output '//dir//'/cli.h5 --force')
         call check_true(error, stat == 0, '['//trim(cases(i))//'] the command ran')
         if (allocated(error)) return
         call check_true(error, same_files(dir//'/lib.h5', dir//'/cli.h5'), &
                         '['//trim(cases(i))//'] the library''s file equals the command''s')
         if (allocated(error)) return
      end do
   end subroutine test_equal_files

   !> A bad value: the library's message is the command's stderr line, and no file.
   subroutine test_refusals(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: cases(*) = [character(len=80) :: &
         'simulate --t-end -1', 'simulate --q1 1x', 'simulate --method nosuch', &
         'simulate --q1 0 --q1 1', 'simulate --links 0', 'lyapunov --tau 0', &
         'sweep --n 0', 'indicators --t-end nan', 'fit', 'simulate --nosuch 1']
      character(len=:), allocatable :: dir, message, text
      integer(int8), allocatable :: image(:)
      integer :: i, kind, stat, sp, n
      dir = scratch_dir('capi-refusals')
      do i = 1, size(cases)
         sp = index(cases(i), ' ')
         call library_run(cases(i)(:sp - 1), trim(cases(i)(sp + 1:)), kind, message, image)
         stat = run_command(dir, trim(cases(i))//' --output '//dir//'/out.h5')
         call read_text(dir//'/stderr', text, n)
         call check_true(error, kind == 2 .and. stat == 2 .and. size(image) == 0, &
                         '['//trim(cases(i))//'] kind 2, no file; got '//to_str(kind)// &
                         ', command exit '//to_str(stat))
         call check_true(error, message//new_line('a') == text, '['//trim(cases(i))// &
                         '] the library says "'//message//'", the command "'//text//'"')
         if (allocated(error)) return
      end do
   end subroutine test_refusals

   !> Two runs at once in two threads (the library runs them one after the other):
   !> each file is that of its single run.
   subroutine test_threads(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: cases(2) = [character(len=60) :: &
         '--method dop853 --q1 0.1 --q2 0.2 --t-end 3', '--q1 -1 --q2 2 --t-end 3']
      character(len=:), allocatable :: dir, message
      integer(int8), allocatable :: image(:)
      integer :: i, kind, kinds(2)
      character(len=:), allocatable :: paths(:)
      dir = scratch_dir('capi-threads')
      do i = 1, 2
         call library_run('simulate', trim(cases(i)), kind, message, image)
         call write_bytes(dir//'/single'//to_str(i)//'.h5', image)
      end do
      paths = [character(len=len(dir) + 12) :: dir//'/thread1.h5', dir//'/thread2.h5']
      ! (nothing in the region calls a function with a deferred-length result)
      !$omp parallel do num_threads(2)
      do i = 1, 2
         call thread_run(cases(i), paths(i), kinds(i))
      end do
      !$omp end parallel do
      do i = 1, 2
         call check_true(error, kinds(i) == 0 .and. same_files(dir//'/single'//to_str(i)// &
                         '.h5', dir//'/thread'//to_str(i)//'.h5'), 'run '//to_str(i)// &
                         ' in a thread equals its single run')
      end do
   end subroutine test_threads

   !> One run of simulate with `options`, its file written to `path`.
   subroutine thread_run(options, path, kind)
      character(len=*), intent(in) :: options, path
      integer, intent(out) :: kind
      character(len=:), allocatable :: message
      integer(int8), allocatable :: image(:)
      call library_run('simulate', options, kind, message, image)
      call write_bytes(path, image)
   end subroutine thread_run

   !> --output, --force and --quiet are the library's (kind 2); a command it does not
   !> run is kind 3.
   subroutine test_library_options(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: message
      integer(int8), allocatable :: image(:)
      integer :: kind
      call library_run('simulate', '--output x.h5', kind, message, image)
      call check_true(error, kind == 2 .and. index(message, 'dpend simulate: invalid ' &
                      //'option --output in the library') == 1, 'simulate --output: '//message)
      call library_run('sweep', '--quiet', kind, message, image)
      call check_true(error, kind == 2, 'sweep --quiet refused: '//message)
      call library_run('animate', '', kind, message, image)
      call check_true(error, kind == 3 .and. index(message, "'animate' is not available") &
                      > 0, 'animate: kind 3, got '//to_str(kind)//': '//message)
      call library_run('study', '--quick --methods rk4 --cases small', kind, message, image)
      call check_true(error, kind == 0 .and. index(message, '| small |') > 0 .and. &
                      size(image) > 0, 'study: its summary and its file, got '// &
                      to_str(kind)//': '//message(:min(len(message), 200)))
      call library_run('methods', '', kind, message, image)
      call check_true(error, kind == 0 .and. index(message, 'rk4') > 0 .and. &
                      index(message, 'dop853') > 0, 'methods: the names, got '//message)
      call library_run('models', '', kind, message, image)
      call check_true(error, kind == 0 .and. index(message, 'elastic') > 0, &
                      'models: the table, got '//message)
      call library_run('simulate', '--help', kind, message, image)
      call check_true(error, kind == 0 .and. index(message, 'usage: dpend simulate') == 1 &
                      .and. size(image) == 0, 'simulate --help gives the help')
   end subroutine test_library_options

   !> dpend_run_progress: the callback is told of a sweep's 4096 trajectories from 0 to
   !> all, never backwards, with its unit and label; dpend_run tells nothing.
   subroutine test_progress(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: message
      integer(int8), allocatable :: image(:)
      integer :: kind
      type(c_funptr) :: callback
      procedure(record_progress), pointer :: recorder
      ! the callback's address taken at run time (a c_funloc constant is a relocation
      ! in read-only data: the linker warns of text relocations in the PIE)
      recorder => record_progress
      callback = c_funloc(recorder)
      told = told_t()
      call library_run('sweep', '--n 64 --t-end 5', kind, message, image, callback)
      call check_true(error, kind == 0 .and. told%calls >= 2 .and. told%first == 0 .and. &
                      told%last == 4096 .and. told%total == 4096 .and. told%monotone &
                      .and. told%same_total, 'sweep: '//to_str(told%calls)//' calls, '// &
                      to_str(told%first)//' .. '//to_str(told%last)//' of '// &
                      to_str(told%total)//': '//message)
      if (allocated(error)) return
      call check_true(error, told%what == 'traj' .and. told%label == 'dpend sweep', &
                      'unit and label: '//trim(told%what)//', '//trim(told%label))
      if (allocated(error)) return
      told = told_t()
      call library_run('sweep', '--n 16 --t-end 1', kind, message, image, c_null_funptr)
      call check_true(error, kind == 0 .and. told%calls == 0, 'a NULL callback is not ' &
                      //'called: '//to_str(told%calls))
   end subroutine test_progress

   !> simulate's result: /trajectory/q is item (REAL, rank 2, 101 x 2 in C order) whose
   !> values are those of the file's image read back with HDF5, and its units
   !> attribute is the text 'rad'; the root's attribute 'method' is 'rk4'; a missing
   !> item is -1; an item index out of range is refused.
   subroutine test_items(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=:), allocatable :: dir, file
      integer(int8), allocatable :: image(:)
      type(c_text_t), target :: name, opt(4), path, attr, none
      type(c_ptr), target :: ptrs(4)
      character(kind=c_char, len=256), target :: msg, p_buf, n_buf
      type(c_ptr) :: result
      integer(c_int) :: kind, type, rank
      integer(c_long_long) :: itemsize, dims(8), bytes
      real(dp), allocatable, target :: q(:, :), q_file(:, :)
      character(kind=c_char, len=16), target :: units
      type(h5file_t) :: h5
      integer :: k, j
      name%s = 'simulate'//c_null_char
      opt(1)%s = '--t-end'//c_null_char; opt(2)%s = '1'//c_null_char
      opt(3)%s = '--method'//c_null_char; opt(4)%s = 'rk4'//c_null_char
      do k = 1, 4
         ptrs(k) = c_loc(opt(k)%s)
      end do
      kind = dpend_run(c_loc(name%s), 4_c_int, c_loc(ptrs), result, c_loc(msg), 256_c_int)
      call check_true(error, kind == 0 .and. dpend_result_items(result) > 20, &
                      'simulate: items, got kind '//to_str(kind))
      if (allocated(error)) return
      path%s = '/trajectory/q'//c_null_char
      none%s = c_null_char
      attr%s = 'units'//c_null_char
      k = dpend_result_find(result, c_loc(path%s), c_loc(none%s))
      j = dpend_result_item(result, int(k, c_int), c_loc(p_buf), 256_c_int, c_loc(n_buf), &
                            256_c_int, type, itemsize, rank, dims)
      call check_true(error, k >= 0 .and. j == 0 .and. type == 1 .and. itemsize == 8 &
                      .and. rank == 2 .and. dims(1) == 101 .and. dims(2) == 2 .and. &
                      p_buf(:index(p_buf, c_null_char) - 1) == '/trajectory/q', &
                      '/trajectory/q: item '//to_str(k)//', type '//to_str(type)// &
                      ', rank '//to_str(rank)//', '//to_str(dims(1))//' x '//to_str(dims(2)))
      if (allocated(error)) return
      allocate (q(2, 101))
      bytes = dpend_result_item_bytes(result, int(k, c_int))
      j = dpend_result_item_copy(result, int(k, c_int), c_loc(q), bytes)
      k = dpend_result_find(result, c_loc(path%s), c_loc(attr%s))
      units = ''
      j = j + dpend_result_item_copy(result, int(k, c_int), c_loc(units), &
                                     dpend_result_item_bytes(result, int(k, c_int)))
      call check_true(error, j == 0 .and. bytes == 8*202 .and. units(:3) == 'rad', &
                      'q copied ('//to_str(bytes)//' B), its units '//units)
      if (allocated(error)) return
      call check_true(error, dpend_result_find(result, c_loc(attr%s), c_loc(none%s)) == -1 &
                      .and. dpend_result_item(result, 100000_c_int, c_loc(p_buf), 256_c_int, &
                      c_loc(n_buf), 256_c_int, type, itemsize, rank, dims) == 2, &
                      'a missing item: -1, an index out of range: 2')
      if (allocated(error)) return
      call library_image(result, image)
      dir = scratch_dir('capi-items')
      file = dir//'/image.h5'
      call write_bytes(file, image)
      call h5%open(file, 'r', error)
      if (.not. allocated(error)) call h5%read('/trajectory/q', q_file, error)
      call h5%close()
      if (allocated(error)) return
      call check_true(error, all(shape(q_file) == shape(q)) .and. &
                      all(transfer(q_file, [0_int8]) == transfer(q, [0_int8])), &
                      'the item q is bitwise the file''s /trajectory/q')
      call dpend_result_free(result)
   end subroutine test_items

   !> A failed run's message names its output by its target: every temporary name
   !> replaced once; a captured output's temporary name is its target, and the
   !> message stays as it is (the loop that replaced it ran forever: a cancelled
   !> lyapunov in the library).
   subroutine test_explain_captured(error)
      type(error_t), allocatable, intent(out) :: error
      type(output_t) :: out
      type(error_t), allocatable :: e
      out%target = 'run.h5'
      out%temp = 'run.h5'
      call fatal_error(e, "cannot write 'run.h5' (run.h5)")
      call out%explain(e)
      call check_true(error, e%message == "cannot write 'run.h5' (run.h5)", e%message)
      if (allocated(error)) return
      out%temp = '.run.h5.tmp-1'
      call fatal_error(e, "a .run.h5.tmp-1 b .run.h5.tmp-1")
      call out%explain(e)
      call check_true(error, e%message == 'a run.h5 b run.h5', e%message)
   end subroutine test_explain_captured

   !> Settings given by name and value run as the same options given as words: the
   !> same trajectory, bitwise; a refused value gives the command line's line; a
   !> misspelt name is refused as it is set.
   subroutine test_settings(error)
      type(error_t), allocatable, intent(out) :: error
      type(c_text_t), target :: cmd, k(4), v(4), bad
      character(kind=c_char, len=512), target :: msg
      character(len=:), allocatable :: message
      integer(int8), allocatable :: image(:)
      type(c_ptr) :: settings, result
      real(dp), allocatable :: q_settings(:, :), q_words(:, :)
      integer :: i, kind, stat
      cmd%s = 'simulate'//c_null_char
      k(1)%s = 'q1'//c_null_char; v(1)%s = '0.5'//c_null_char
      k(2)%s = 't_end'//c_null_char; v(2)%s = '1'//c_null_char
      k(3)%s = 'method'//c_null_char; v(3)%s = 'dop853'//c_null_char
      settings = dpend_settings_new(c_loc(cmd%s))
      stat = 0
      do i = 1, 3
         stat = stat + dpend_settings_set(settings, c_loc(k(i)%s), c_loc(v(i)%s))
      end do
      bad%s = '--t-end'//c_null_char
      stat = stat + merge(0, 1, dpend_settings_set(settings, c_loc(bad%s), &
                                                   c_loc(v(2)%s)) == 2)
      kind = dpend_settings_run(settings, result, c_loc(msg), 512_c_int, c_null_funptr, &
                                c_null_ptr)
      call check_true(error, stat == 0 .and. kind == 0, 'settings run: kind '// &
                      to_str(kind)//', set '//to_str(stat))
      if (allocated(error)) return
      call item_q(result, q_settings)
      call dpend_result_free(result)
      call library_run('simulate', '--q1 0.5 --t-end 1 --method dop853', kind, message, &
                       image)
      call read_image_q(image, q_words)
      call check_true(error, size(q_settings) > 0 .and. &
                      all(shape(q_settings) == shape(q_words)) .and. &
                      all(transfer(q_settings, [0_int8]) == transfer(q_words, [0_int8])), &
                      'settings and words: the same q, bitwise')
      if (allocated(error)) return
      k(4)%s = 'dt'//c_null_char; v(4)%s = '-1'//c_null_char
      stat = dpend_settings_set(settings, c_loc(k(4)%s), c_loc(v(4)%s))
      kind = dpend_settings_run(settings, result, c_loc(msg), 512_c_int, c_null_funptr, &
                                c_null_ptr)
      call library_run('simulate', '--q1 0.5 --t-end 1 --method dop853 --dt -1', i, &
                       message, image)
      call check_true(error, kind == 2 .and. i == 2 .and. .not. c_associated(result) &
                      .and. msg(:index(msg, c_null_char) - 1) == message, &
                      'a refused value: '//msg(:index(msg, c_null_char) - 1))
      call dpend_settings_free(settings)
   end subroutine test_settings

   !> /trajectory/q of a result, from its item.
   subroutine item_q(result, q)
      type(c_ptr), intent(in) :: result
      real(dp), allocatable, target, intent(out) :: q(:, :)
      type(c_text_t), target :: path, none
      integer :: k
      path%s = '/trajectory/q'//c_null_char
      none%s = c_null_char
      k = dpend_result_find(result, c_loc(path%s), c_loc(none%s))
      allocate (q(2, dpend_result_item_bytes(result, int(k, c_int))/16))
      if (dpend_result_item_copy(result, int(k, c_int), c_loc(q), &
                                 dpend_result_item_bytes(result, int(k, c_int))) /= 0) &
         deallocate (q)
      if (.not. allocated(q)) allocate (q(0, 0))
   end subroutine item_q

   !> /trajectory/q of a file's image, read back with HDF5.
   subroutine read_image_q(image, q)
      integer(int8), intent(in) :: image(:)
      real(dp), allocatable, intent(out) :: q(:, :)
      type(h5file_t) :: h5
      type(error_t), allocatable :: e
      character(len=:), allocatable :: dir
      dir = scratch_dir('capi-settings')
      call write_bytes(dir//'/words.h5', image)
      call h5%open(dir//'/words.h5', 'r', e)
      if (.not. allocated(e)) call h5%read('/trajectory/q', q, e)
      call h5%close()
      if (.not. allocated(q)) allocate (q(0, 0))
   end subroutine read_image_q

   !> The image of `result` (made from its items).
   subroutine library_image(result, image)
      type(c_ptr), intent(in) :: result
      integer(int8), allocatable, target, intent(out) :: image(:)
      integer(c_long_long) :: bytes
      bytes = dpend_result_bytes(result)
      allocate (image(bytes))
      if (dpend_result_copy(result, c_loc(image), bytes) /= 0) deallocate (image)
      if (.not. allocated(image)) allocate (image(0))
   end subroutine library_image

   !> The progress callback of test_progress.
   subroutine record_progress(done, total, what, label, user) bind(C)
      integer(c_long_long), value :: done, total
      type(c_ptr), value :: what, label, user
      if (told%calls > 0) then
         told%monotone = told%monotone .and. done >= told%last
         told%same_total = told%same_total .and. total == told%total
      else
         told%first = done
      end if
      told%calls = told%calls + 1
      told%last = done
      told%total = total
      told%what = from_c(what)
      told%label = from_c(label)
   end subroutine record_progress

   !> A NUL-terminated C string (at most 32 characters of it).
   function from_c(p) result(s)
      type(c_ptr), intent(in) :: p
      character(len=32) :: s
      character(kind=c_char), pointer :: chars(:)
      integer :: i
      s = ''
      call c_f_pointer(p, chars, [32])
      do i = 1, 32
         if (chars(i) == c_null_char) exit
         s(i:i) = chars(i)
      end do
   end function from_c
end module test_capi
