!> dpend as a library: the C interface (`bind(C)`; the header is
!> src/capi/dpend.h, the Python package in python/dpend calls it through ctypes).
!>
!> `dpend_run` runs one command in the calling thread, as `dpend COMMAND ARGS...`
!> would: its options are the command line's, parsed and checked by the same
!> settings layer (so a refusal is the command line's one line, word for word), and
!> the HDF5 file the command writes is written to memory instead of disk
!> (`capture_outputs`: HDF5's core driver without a backing store). The result is
!> that file's image, byte for byte the file the command would write apart from the
!> creation time, handed over as an opaque handle: `dpend_result_bytes` and
!> `dpend_result_copy` read it, `dpend_result_free` releases it. Nothing here stops
!> or exits the process; every error comes back as a kind (0 ok, 1 the run failed
!> partway, 2 refused input, 3 not available in the library) and one line.
!> Calls from several threads are safe and run one at a time (a process-wide lock:
!> gfortran 12 keeps the lengths of deferred-length character results in static
!> storage, so the settings and command code is not reentrant); each run uses its
!> own OpenMP threads inside as the command does. The captured image is per thread.
!> Progress reports are silenced for the whole process once the library is called.
module dpend_capi
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_ptr, c_null_ptr, c_null_char, &
      c_associated, c_f_pointer, c_loc, c_size_t, c_long_long
   use dpend_error, only: error_t, fatal_error, exit_status
   use dpend_cli, only: arg_t, check_repeated_options, printable, environment
   use dpend_os, only: capture_outputs, take_capture, capture_buffer, make_temp_directory, &
      remove_directory, remove_file, errno_text, path_kind, path_file
   use dpend_stop_request, only: request_stop, clear_stop_request, stop_requested
   use dpend_output_record, only: record_t, record_outputs, take_record, keep_record
   use dpend_hdf5, only: h5file_t
   use dpend_capi_result, only: new_result, library_lock, library_unlock, c_free, c_string
   use dpend_error, only: run_failure
   use dpend_sweep_settings, only: sweep_config_t
   use dpend_sweep_config, only: parse_sweep, sweep_help
   use dpend_sweep_setup, only: sweep_summary_t, summary_text
   use dpend_sweep_engine, only: run_sweep
   use dpend_sweep_layout, only: working_file
   use dpend_progress, only: silence_progress, set_progress_listener, progress_listener_i
   use, intrinsic :: iso_c_binding, only: c_funptr, c_null_funptr, c_f_procpointer, &
      c_associated_funptr => c_associated
   use dpend_strings, only: to_str
   use, intrinsic :: iso_fortran_env, only: int8, int64
   use dpend_kinds, only: i8
   use dpend_version, only: version
   use dpend_command_common, only: refusal_line, error_line, set_report_unit
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_run_settings, only: run_config_t
   use dpend_simulate, only: parse_simulate, run_simulate, simulate_help
   use dpend_chaos_common, only: chaos_config_t, parse_chaos, run_chaos, chaos_help, &
      chaos_run_body
   use dpend_lyapunov_command, only: run_lyapunov
   use dpend_indicators_command, only: run_indicators
   use dpend_divergence_command, only: run_divergence
   use dpend_poincare_command, only: run_poincare
   use dpend_fit_command, only: fit_config_t, parse_fit, run_fit, fit_help
   use dpend_study_settings, only: study_config_t
   use dpend_study_config, only: parse_study, study_help
   use dpend_study, only: study_result_t, run_study
   use dpend_study_command, only: write_study_h5, study_summary
   use dpend_model_factory, only: describe_models
   use dpend_method_registry, only: method_names
   implicit none
   private
   public :: dpend_run, dpend_run_progress, run_arguments
   public :: dpend_version, dpend_cancel

   !> The error kinds of the interface.
   integer(c_int), parameter :: kind_ok = 0, kind_refused = 2, kind_unavailable = 3

   !> The commands the library runs.
   character(len=10), parameter :: commands(10) = [character(len=10) :: 'simulate', &
      'lyapunov', 'indicators', 'divergence', 'poincare', 'fit', 'sweep', 'study', &
      'models', 'methods']


   !> The progress callback of the run in progress and its user pointer (set and
   !> cleared by `dpend_run_progress` under the lock of library runs).
   type(c_funptr), save :: progress_fn = c_null_funptr
   type(c_ptr), save :: progress_user = c_null_ptr

   abstract interface
      !> void (*)(long long done, long long total, const char *what,
      !>          const char *label, void *user)
      subroutine c_progress_i(done, total, what, label, user) bind(C)
         import :: c_long_long, c_ptr
         integer(c_long_long), value :: done, total
         type(c_ptr), value :: what, label, user
      end subroutine c_progress_i
   end interface


contains

   !> Run `command` with the `nargs` options `args` (C strings, as the command line
   !> takes them; not --output, --force, --quiet). Returns the error kind; `result`
   !> receives the file's image (c_null_ptr when nothing was written), `message` one
   !> line (the command's closing line, its refusal or why the run failed), at most
   !> msg_len bytes with the terminating NUL. With --help, `message` holds the help.
   integer(c_int) function dpend_run(command, nargs, args, result, message, msg_len) &
      bind(C, name='dpend_run')
      type(c_ptr), value :: command                !! const char *
      integer(c_int), value :: nargs               !! number of options
      type(c_ptr), value :: args                   !! const char *const *
      type(c_ptr), intent(out) :: result           !! void **: the result or NULL
      type(c_ptr), value :: message                !! char *
      integer(c_int), value :: msg_len             !! its size [B]
      dpend_run = dpend_run_progress(command, nargs, args, result, message, msg_len, &
                                     c_null_funptr, c_null_ptr)
   end function dpend_run

   !> `dpend_run` with a progress callback `fn` (NULL: none), called from the run's
   !> threads, one call at a time, at its start, at most every 0.1 s and at its end
   !> with the units done, their total, the unit ('traj', 'runs', 'steps'; '' parts
   !> of a horizon) and the report's label; `user` is handed to it.
   integer(c_int) function dpend_run_progress(command, nargs, args, result, message, &
                                              msg_len, fn, user) &
      bind(C, name='dpend_run_progress')
      type(c_ptr), value :: command                !! const char *
      integer(c_int), value :: nargs               !! number of options
      type(c_ptr), value :: args                   !! const char *const *
      type(c_ptr), intent(out) :: result           !! void **: the result or NULL
      type(c_ptr), value :: message                !! char *
      integer(c_int), value :: msg_len             !! its size [B]
      type(c_funptr), value :: fn                  !! the progress callback or NULL
      type(c_ptr), value :: user                   !! handed to fn
      type(arg_t), allocatable :: argv(:)
      type(c_ptr), pointer :: ptrs(:)
      integer :: i
      allocate (argv(max(nargs, 0)))
      if (nargs > 0) then
         call c_f_pointer(args, ptrs, [nargs])
         do i = 1, nargs
            argv(i)%s = c_string(ptrs(i))
         end do
      end if
      dpend_run_progress = run_arguments(c_string(command), argv, result, message, &
                                         msg_len, fn, user)
   end function dpend_run_progress

   !> `command` run with the options `argv` (what `dpend_run_progress` and
   !> `dpend_settings_run` do): the error kind; `result`, `message` and the progress
   !> callback `fn` as there.
   integer(c_int) function run_arguments(name, argv, result, message, msg_len, fn, &
                                         user) result(kind)
      character(len=*), intent(in) :: name         !! the command
      type(arg_t), intent(in) :: argv(:)           !! its options
      type(c_ptr), intent(out) :: result           !! the result or NULL
      type(c_ptr), intent(in) :: message           !! char *
      integer(c_int), intent(in) :: msg_len        !! its size [B]
      type(c_funptr), intent(in) :: fn             !! the progress callback or NULL
      type(c_ptr), intent(in) :: user              !! handed to fn
      procedure(progress_listener_i), pointer :: listener
      type(error_t), allocatable :: error
      character(len=:), allocatable :: text
      result = c_null_ptr
      call library_lock()
      call clear_stop_request()
      call silence_progress()
      progress_fn = fn
      progress_user = user
      listener => null()
      if (c_associated_funptr(fn)) listener => tell_progress
      call set_progress_listener(listener)
      if (.not. any(name == commands)) then
         text = "dpend: '"//printable(name)//"' is not available in the library (" &
                //'simulate, lyapunov, indicators, divergence, poincare, fit, sweep, ' &
                //'study, models and methods are)'
         call put_c_string(text, message, msg_len)
         kind = kind_unavailable
         call end_run()
         return
      end if
      call run_captured(name, argv, text, error, result)
      if (.not. allocated(error) .and. stop_requested()) then   ! a run that went on
         call fatal_error(error, 'dpend '//name//': stopped on request (dpend_cancel); ' &
                          //'the result holds what was computed')
         call run_failure(error)
      end if
      if (allocated(error)) then
         kind = int(exit_status(error), c_int)
         text = printable(error%message, controls_only=.true.)
      else
         kind = kind_ok
      end if
      text = without_wrote_lines(text, name)
      call put_c_string(text, message, msg_len)
      call end_run()
   end function run_arguments

   !> The run's progress callback forgotten, the lock released.
   subroutine end_run()
      procedure(progress_listener_i), pointer :: none
      none => null()
      call set_progress_listener(none)
      progress_fn = c_null_funptr
      progress_user = c_null_ptr
      call library_unlock()
   end subroutine end_run

   !> The listener of the run's progress reports: the C callback.
   subroutine tell_progress(label, what, done, total)
      character(len=*), intent(in) :: label, what
      integer(i8), intent(in) :: done, total
      procedure(c_progress_i), pointer :: f
      character(kind=c_char), allocatable, target :: c_label(:), c_what(:)
      call c_f_procpointer(progress_fn, f)
      call to_c_chars(label, c_label)
      call to_c_chars(what, c_what)
      call f(int(done, c_long_long), int(total, c_long_long), c_loc(c_what), &
             c_loc(c_label), progress_user)
   end subroutine tell_progress

   !> `text` as a NUL-terminated C string.
   subroutine to_c_chars(text, chars)
      character(len=*), intent(in) :: text
      character(kind=c_char), allocatable, intent(out) :: chars(:)
      integer :: i
      allocate (chars(len(text) + 1))
      do i = 1, len(text)
         chars(i) = text(i:i)
      end do
      chars(len(text) + 1) = c_null_char
   end subroutine to_c_chars

   !> `command` run with its outputs captured in memory (see the module's notes):
   !> `text` the help when asked for, `result` the handle of the last file written.
   subroutine run_captured(command, argv, text, error, result)
      character(len=*), intent(in) :: command
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(out) :: text
      type(error_t), allocatable, intent(out) :: error
      type(c_ptr), intent(out) :: result
      type(record_t), allocatable :: record
      type(c_ptr) :: image
      integer(c_size_t) :: bytes
      text = ''
      result = c_null_ptr
      call check_library_args(command, argv, error)
      if (allocated(error)) return
      call capture_outputs(.true.)
      call record_outputs(.true.)
      call dispatch(command, argv, text, error)
      call take_record(record)
      call record_outputs(.false.)
      image = take_capture(bytes)
      call capture_outputs(.false.)
      result = new_result(record, image, bytes)
   end subroutine run_captured

   !> The options the library sets itself are refused (the result is returned, not
   !> written; progress is never printed), as is an option given twice.
   subroutine check_library_args(command, argv, error)
      character(len=*), intent(in) :: command
      type(arg_t), intent(in) :: argv(:)
      type(error_t), allocatable, intent(out) :: error
      integer :: i
      character(len=:), allocatable :: opt
      do i = 1, size(argv)
         opt = argv(i)%s
         if (index(opt, '=') > 0) opt = opt(:index(opt, '=') - 1)
         select case (opt)
         case ('--output', '--force', '--quiet')
            call fatal_error(error, 'dpend '//printable(command)//': invalid option '// &
                             opt//' in the library (the result is returned; write it ' &
                             //'with to_hdf5)')
            return
         end select
      end do
      call check_repeated_options(argv, error)
      if (allocated(error)) error%message = 'dpend '//printable(command)//': '// &
         error%message
   end subroutine check_library_args

   !> The command's parse and run, without printing: its closing text in `text`.
   subroutine dispatch(command, argv, text, error)
      character(len=*), intent(in) :: command
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      select case (command)
      case ('simulate')
         call simulate(argv, text, error)
      case ('lyapunov')
         call chaos(command, argv, run_lyapunov, text, error)
      case ('indicators')
         call chaos(command, argv, run_indicators, text, error)
      case ('divergence')
         call chaos(command, argv, run_divergence, text, error)
      case ('poincare')
         call chaos(command, argv, run_poincare, text, error)
      case ('fit')
         call fit(argv, text, error)
      case ('sweep')
         call sweep(argv, text, error)
      case ('study')
         call study(argv, text, error)
      case ('models', 'methods')   ! their text: the models' table, the methods' names
         if (size(argv) > 0) then
            call fatal_error(error, 'the library takes no options here (got '// &
                             printable(argv(1)%s)//')')
            call refusal_line(error, trim(command))
         else if (command == 'models') then
            text = describe_models()
         else
            text = method_names()
         end if
      end select
   end subroutine dispatch

   subroutine simulate(argv, text, error)
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      logical :: help
      call parse_simulate(argv, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'simulate')
      else if (help) then
         text = simulate_help()
      else
         call run_simulate(cfg, error, text)
         if (allocated(error)) call error_line(error, 'simulate')
      end if
   end subroutine simulate

   subroutine chaos(command, argv, body, text, error)
      character(len=*), intent(in) :: command
      type(arg_t), intent(in) :: argv(:)
      procedure(chaos_run_body) :: body
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      type(chaos_config_t) :: ch
      logical :: help
      call parse_chaos(command, argv, cfg, ch, help, error)
      if (allocated(error)) then
         call refusal_line(error, command)
      else if (help) then
         text = chaos_help(command)
      else
         call run_chaos(cfg, ch, body, text, error)
         if (allocated(error)) call error_line(error, command)
      end if
   end subroutine chaos

   subroutine fit(argv, text, error)
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      type(fit_config_t) :: fc
      logical :: help
      integer :: unit, stat
      call parse_fit(argv, fc, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'fit')
      else if (help) then
         text = fit_help()
      else   ! its report, which the command prints, as the message
         open (newunit=unit, status='scratch', action='readwrite', form='formatted', &
               iostat=stat)
         if (stat == 0) call set_report_unit(unit)
         call run_fit(fc, error, .false.)
         call set_report_unit(output_unit)
         if (allocated(error)) call error_line(error, 'fit')
         if (stat == 0) then
            text = scratch_text(unit)
            close (unit)
         end if
      end if
   end subroutine fit

   !> The study's file in memory, its summary as the message; no figures are drawn
   !> (--no-figures is accepted and changes nothing here).
   subroutine study(argv, text, error)
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      type(study_config_t) :: cfg
      type(study_result_t) :: res
      logical :: help
      call parse_study(argv, cfg, help, error)
      if (allocated(error)) then
         call refusal_line(error, 'study')
      else if (help) then
         text = study_help()
      else
         call run_study(cfg, res)
         text = study_summary(cfg, res)
         call write_study_h5(cfg, res, 'study.h5', error)
         if (allocated(error)) then
            call run_failure(error)
            call error_line(error, 'study')
         end if
      end if
   end subroutine study

   !> The lines written to the scratch unit, joined by new lines.
   function scratch_text(unit) result(text)
      integer, intent(in) :: unit
      character(len=:), allocatable :: text
      character(len=4096) :: line
      integer :: stat
      text = ''
      rewind (unit)
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (len(text) > 0) text = text//new_line('a')
         text = text//trim(line)
      end do
   end function scratch_text

   !> A sweep writes a working file beside its output and resumes from it, so the
   !> library runs it on disk, in a private temporary directory (under $TMPDIR, else
   !> /tmp), quiet, and keeps the bytes of the file it wrote; the directory goes after.
   subroutine sweep(argv, text, error)
      type(arg_t), intent(in) :: argv(:)
      character(len=:), allocatable, intent(inout) :: text
      type(error_t), allocatable, intent(out) :: error
      type(sweep_config_t) :: cfg
      type(sweep_summary_t) :: summary
      character(len=:), allocatable :: dir, file
      logical :: help
      integer :: err, k
      call capture_outputs(.false.)   ! the sweep's own files, in the directory
      err = make_temp_directory(temp_root()//'/dpend-sweep-', dir)
      if (err /= 0) then
         call fatal_error(error, 'dpend sweep: cannot make a directory in '//temp_root()// &
                          ' for the working file: '//errno_text(err))
         call run_failure(error)
         return
      end if
      file = dir//'/sweep.h5'
      call parse_sweep([argv, arg_t('--output'), arg_t(file), arg_t('--quiet')], cfg, &
                       help, error)
      if (allocated(error)) then
         call refusal_line(error, 'sweep')
      else if (help) then
         text = sweep_help()
      else
         call run_sweep(cfg, summary, error)
         if (allocated(error)) then
            ! the working file holds the blocks done (not resumable here: it goes)
            k = index(error%message, "; '"//working_file(file)//"'")
            if (k > 0) error%message = error%message(:k - 1)//' (the result holds ' &
                                       //'the blocks done)'
            call error_line(error, 'sweep')
         else
            text = 'dpend sweep: '//summary_text(summary)
         end if
         if (path_kind(file) == path_file) then
            call keep_file(file, error)
         else if (path_kind(working_file(file)) == path_file) then
            call keep_file(working_file(file), error)
            file = working_file(file)
         end if
         if (path_kind(file) == path_file) call keep_items(file, error)
      end if
      err = remove_file(file)
      err = remove_file(working_file(file))
      err = remove_directory(dir)
   end subroutine sweep

   !> $TMPDIR, else /tmp.
   function temp_root() result(root)
      character(len=:), allocatable :: root
      root = environment('TMPDIR', '/tmp')
   end function temp_root

   !> The items of the file at `path` as the run's record (`take_record`).
   subroutine keep_items(path, error)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(inout) :: error
      type(h5file_t) :: h5
      type(record_t), allocatable :: record
      type(error_t), allocatable :: err
      call h5%open(path, 'r', err)
      if (.not. allocated(err)) call h5%to_record(record, err)
      call h5%close()
      if (allocated(err)) then
         if (.not. allocated(error)) then
            call move_alloc(err, error)
            error%message = 'dpend sweep: '//error%message
            call run_failure(error)
         end if
         return
      end if
      call keep_record(record)
   end subroutine keep_items

   !> The bytes of the file at `path` as this thread's captured image.
   subroutine keep_file(path, error)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(inout) :: error
      integer(int8), pointer :: bytes(:)
      type(c_ptr) :: buf
      integer :: unit, stat
      integer(int64) :: n
      inquire (file=path, size=n)
      if (n <= 0) return
      buf = capture_buffer(int(n, c_size_t))
      if (.not. c_associated(buf)) then
         if (.not. allocated(error)) then
            call fatal_error(error, 'dpend sweep: no memory for the result''s '// &
                             to_str(n)//' bytes')
            call run_failure(error)
         end if
         return
      end if
      call c_f_pointer(buf, bytes, [n])
      open (newunit=unit, file=path, access='stream', form='unformatted', action='read', &
            status='old', iostat=stat)
      if (stat == 0) read (unit, iostat=stat) bytes
      if (stat == 0) close (unit, iostat=stat)
      if (stat /= 0 .and. .not. allocated(error)) then
         call fatal_error(error, 'dpend sweep: cannot read back the file it wrote')
         call run_failure(error)
      end if
   end subroutine keep_file

   !> Ask the call in progress (in another thread) to stop: a sweep stops its lanes
   !> taking trajectories and its threads taking blocks, and returns kind 1 with the
   !> blocks done; the other commands stop within 256 steps of a march. Each call of
   !> `dpend_run` forgets an earlier request as it starts.
   subroutine dpend_cancel() bind(C, name='dpend_cancel')
      call request_stop()
   end subroutine dpend_cancel

   !> The version into buf (n bytes with the NUL); returns its length.
   integer(c_int) function dpend_version(buf, n) bind(C, name='dpend_version')
      type(c_ptr), value :: buf     !! char *
      integer(c_int), value :: n    !! its size [B]
      call put_c_string(version, buf, n)
      dpend_version = len(version, c_int)
   end function dpend_version

   !> `text` without the command's lines "dpend COMMAND: wrote 'FILE'..." (the library
   !> writes no file: the result holds it).
   function without_wrote_lines(text, command) result(s)
      character(len=*), intent(in) :: text, command
      character(len=:), allocatable :: s, line, rest
      integer :: k
      s = ''
      rest = text
      do while (len(rest) > 0)
         k = index(rest, new_line('a'))
         if (k == 0) k = len(rest) + 1
         line = rest(:k - 1)
         rest = rest(min(k + 1, len(rest) + 1):)
         if (index(line, 'dpend '//command//": wrote '") == 1) cycle
         if (len(s) > 0) s = s//new_line('a')
         s = s//line
      end do
   end function without_wrote_lines

   !> `text` into the C buffer p of n bytes, cut to n − 1 bytes and NUL-terminated.
   subroutine put_c_string(text, p, n)
      character(len=*), intent(in) :: text
      type(c_ptr), intent(in) :: p
      integer(c_int), intent(in) :: n
      character(kind=c_char), pointer :: chars(:)
      integer :: k, i
      if (.not. c_associated(p) .or. n < 1) return
      call c_f_pointer(p, chars, [n])
      k = min(len(text), n - 1)
      do i = 1, k
         chars(i) = text(i:i)
      end do
      chars(k + 1) = c_null_char
   end subroutine put_c_string
end module dpend_capi
