!> Small operating-system services (POSIX, Linux): whether stderr is a terminal,
!> the path of the running executable, creating directories, the host name and
!> CPU model for output files, a wall clock; and, through src/dpend_posix.c, the
!> kind of a path, free disk and memory, unique temporary files, fsync, one-step
!> moves (with or without replacing), errno texts, and running a program with an
!> argument vector and no shell. The file operations return 0 or an errno value.
module dpend_os
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_long_long, c_size_t, &
      c_null_char, c_ptr, c_loc, c_null_ptr
   use, intrinsic :: iso_fortran_env, only: int64, error_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t
   implicit none
   private
   public :: stderr_is_terminal, executable_path, make_directories, host_name, cpu_model
   public :: wall_clock, directory_of, base_name, find_script
   public :: path_kind, path_missing, path_file, path_directory, path_link, path_other
   public :: free_disk_bytes, available_memory_bytes, file_id, make_temp_file, sync_path
   public :: reserve_space
   public :: move_noreplace, move_replace, remove_file, errno_text, run_program
   public :: echo_to_stderr  ! for the figure scripts
   public :: errno_exists, errno_nospc, io_failure_reason
   public :: capture_outputs, capturing_outputs, capture_buffer, take_capture
   public :: make_temp_directory, remove_directory

   !> What `path_kind` finds at a path.
   integer, parameter :: path_missing = 0, path_file = 1, path_directory = 2, &
                         path_link = 3, path_other = 4
   !> errno values that callers test (Linux).
   integer, parameter :: errno_exists = 17, errno_nospc = 28

   interface
      function c_isatty(fd) bind(C, name='isatty') result(r)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: r
      end function c_isatty
      function c_readlink(path, buf, bufsiz) bind(C, name='readlink') result(r)
         import :: c_char, c_size_t, c_long
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_size_t), value :: bufsiz
         integer(c_long) :: r
      end function c_readlink
      function c_mkdir(path, mode) bind(C, name='mkdir') result(r)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: r
      end function c_mkdir
      integer(c_int) function c_make_temp_dir(template) bind(C, name='dpend_make_temp_dir')
         import :: c_int, c_char
         character(kind=c_char), intent(inout) :: template(*)
      end function c_make_temp_dir
      integer(c_int) function c_remove_dir(path) bind(C, name='dpend_remove_dir')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c_remove_dir
      subroutine c_capture_set(on) bind(C, name='dpend_capture_set')
         import :: c_int
         integer(c_int), value :: on
      end subroutine c_capture_set
      integer(c_int) function c_capture_active() bind(C, name='dpend_capture_active')
         import :: c_int
      end function c_capture_active
      type(c_ptr) function c_capture_buffer(n) bind(C, name='dpend_capture_buffer')
         import :: c_ptr, c_size_t
         integer(c_size_t), value :: n
      end function c_capture_buffer
      type(c_ptr) function c_capture_take(n) bind(C, name='dpend_capture_take')
         import :: c_ptr, c_size_t
         integer(c_size_t), intent(out) :: n
      end function c_capture_take
      integer(c_int) function c_path_kind(path, follow) bind(C, name='dpend_path_kind')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: follow
      end function c_path_kind
      integer(c_int) function c_file_id(path, dev, ino) bind(C, name='dpend_file_id')
         import :: c_int, c_char, c_long_long
         character(kind=c_char), intent(in) :: path(*)
         integer(c_long_long), intent(out) :: dev, ino
      end function c_file_id
      integer(c_long_long) function c_free_bytes(path) bind(C, name='dpend_free_bytes')
         import :: c_long_long, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c_free_bytes
      integer(c_int) function c_make_temp(template) bind(C, name='dpend_make_temp')
         import :: c_int, c_char
         character(kind=c_char), intent(inout) :: template(*)
      end function c_make_temp
      integer(c_int) function c_sync_path(path) bind(C, name='dpend_sync_path')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c_sync_path
      integer(c_int) function c_reserve_space(path) bind(C, name='dpend_reserve_space')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c_reserve_space
      integer(c_int) function c_move_noreplace(from, to) bind(C, name='dpend_move_noreplace')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
      end function c_move_noreplace
      integer(c_int) function c_move_replace(from, to) bind(C, name='dpend_move_replace')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
      end function c_move_replace
      integer(c_int) function c_remove(path) bind(C, name='dpend_remove')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
      end function c_remove
      subroutine c_error_text(err, buf, length) bind(C, name='dpend_error_text')
         import :: c_int, c_char
         integer(c_int), value :: err, length
         character(kind=c_char), intent(out) :: buf(*)
      end subroutine c_error_text
      integer(c_int) function c_spawn_wait(argv, status) bind(C, name='dpend_spawn_wait')
         import :: c_int, c_ptr
         type(c_ptr), intent(in) :: argv(*)
         integer(c_int), intent(out) :: status
      end function c_spawn_wait
      integer(c_int) function c_spawn_wait_err(argv, status, errpath) &
         bind(C, name='dpend_spawn_wait_err')
         import :: c_int, c_ptr, c_char
         type(c_ptr), intent(in) :: argv(*)
         integer(c_int), intent(out) :: status
         character(kind=c_char), intent(in) :: errpath(*)
      end function c_spawn_wait_err
   end interface

contains

   !> What is at `path`: path_missing, path_file, path_directory, path_link or
   !> path_other (device, FIFO, socket); a negative errno value if it cannot be
   !> examined (e.g. a loop of links). A final symbolic link is reported as
   !> path_link unless `follow` is true, when the file it leads to is examined.
   integer function path_kind(path, follow)
      character(len=*), intent(in) :: path           !! file path
      logical, intent(in), optional :: follow        !! follow symbolic links
      integer(c_int) :: f
      f = 0
      if (present(follow)) f = merge(1, 0, follow)
      path_kind = int(c_path_kind(path//c_null_char, f))
   end function path_kind

   !> The device and inode of `path` (symbolic links followed) in `id`; false when
   !> it cannot be examined (e.g. missing).
   logical function file_id(path, id)
      character(len=*), intent(in) :: path           !! file path
      integer(int64), intent(out) :: id(2)           !! device, inode
      integer(c_long_long) :: dev, ino
      id = -1
      file_id = c_file_id(path//c_null_char, dev, ino) == 0
      if (file_id) id = [int(dev, int64), int(ino, int64)]
   end function file_id

   !> Bytes free for an ordinary user on the file system holding `path`, or -1.
   integer(int64) function free_disk_bytes(path)
      character(len=*), intent(in) :: path  !! a file or directory on that file system
      free_disk_bytes = int(c_free_bytes(path//c_null_char), int64)
   end function free_disk_bytes

   !> Memory available to a new process (MemAvailable in /proc/meminfo) in bytes,
   !> or -1 when unknown.
   integer(int64) function available_memory_bytes() result(bytes)
      character(len=256) :: line
      integer :: unit, stat
      integer(int64) :: kib
      bytes = -1
      open (newunit=unit, file='/proc/meminfo', status='old', action='read', iostat=stat)
      if (stat /= 0) return
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (index(line, 'MemAvailable:') == 1) then
            read (line(14:), *, iostat=stat) kib
            if (stat == 0) bytes = kib*1024_int64
            exit
         end if
      end do
      close (unit)
   end function available_memory_bytes

   !> Create a new, empty file named `prefix` followed by six unique characters;
   !> `name` is its path. Returns 0 or an errno value.
   integer function make_temp_file(prefix, name) result(err)
      character(len=*), intent(in) :: prefix            !! path and start of the name
      character(len=:), allocatable, intent(out) :: name  !! the file created
      character(kind=c_char) :: buf(len(prefix) + 7)
      integer :: i
      do i = 1, len(prefix)
         buf(i) = prefix(i:i)
      end do
      buf(len(prefix) + 1:len(prefix) + 6) = 'X'
      buf(len(prefix) + 7) = c_null_char
      err = int(c_make_temp(buf))
      allocate (character(len=len(prefix) + 6) :: name)
      do i = 1, len(name)
         name(i:i) = buf(i)
      end do
   end function make_temp_file

   !> fsync a file or a directory. Returns 0 or an errno value.
   integer function sync_path(path)
      character(len=*), intent(in) :: path
      sync_path = int(c_sync_path(path//c_null_char))
   end function sync_path

   !> Give the file `path` disk blocks for all its length, its contents unchanged (a
   !> sparse file takes its space now). Returns 0 or an errno value.
   integer function reserve_space(path)
      character(len=*), intent(in) :: path
      reserve_space = int(c_reserve_space(path//c_null_char))
   end function reserve_space

   !> Rename `from` to `to` in one step unless `to` exists (then errno_exists).
   integer function move_noreplace(from, to)
      character(len=*), intent(in) :: from, to
      move_noreplace = int(c_move_noreplace(from//c_null_char, to//c_null_char))
   end function move_noreplace

   !> Rename `from` to `to` in one step, replacing `to`. Returns 0 or an errno value.
   integer function move_replace(from, to)
      character(len=*), intent(in) :: from, to
      move_replace = int(c_move_replace(from//c_null_char, to//c_null_char))
   end function move_replace

   !> Remove a file. Returns 0 or an errno value.
   integer function remove_file(path)
      character(len=*), intent(in) :: path
      remove_file = int(c_remove(path//c_null_char))
   end function remove_file

   !> The system's text for errno value `err`, in lower case ('no space left on device').
   function errno_text(err) result(text)
      integer, intent(in) :: err
      character(len=:), allocatable :: text
      character(kind=c_char) :: buf(256)
      integer :: i, n
      call c_error_text(int(err, c_int), buf, int(size(buf), c_int))
      n = 0
      do while (n < size(buf))
         if (buf(n + 1) == c_null_char) exit
         n = n + 1
      end do
      allocate (character(len=n) :: text)
      do i = 1, n
         text(i:i) = buf(i)
         if (i == 1 .and. text(1:1) >= 'A' .and. text(1:1) <= 'Z') &
            text(1:1) = achar(iachar(text(1:1)) + 32)
      end do
   end function errno_text

   !> Run the program argv(1)%s (searched on PATH) with arguments argv(2:), each
   !> passed exactly as it is (no trimming, no splitting), without a shell, and
   !> wait for it. `status` is its exit status (128 + N when signal N ended it);
   !> `error` is set when it could not be started. With `stderr_path`, its standard
   !> error goes to that file (created or truncated) instead of dpend's.
   subroutine run_program(argv, status, error, stderr_path)
      type(arg_t), intent(in) :: argv(:)                !! program and arguments
      integer, intent(out) :: status                    !! its exit status
      type(error_t), allocatable, intent(out) :: error  !! could not start it
      character(len=*), intent(in), optional :: stderr_path  !! file for its stderr
      type :: c_string_t
         character(kind=c_char), allocatable :: s(:)
      end type c_string_t
      type(c_string_t), allocatable, target :: args(:)
      type(c_ptr) :: ptrs(size(argv) + 1)
      integer(c_int) :: cstatus, err
      integer :: i, j, n
      allocate (args(size(argv)))
      do i = 1, size(argv)
         n = len(argv(i)%s)
         allocate (args(i)%s(n + 1))
         do j = 1, n
            args(i)%s(j) = argv(i)%s(j:j)
         end do
         args(i)%s(n + 1) = c_null_char
         ptrs(i) = c_loc(args(i)%s)
      end do
      ptrs(size(argv) + 1) = c_null_ptr
      status = -1
      cstatus = -1
      if (present(stderr_path)) then
         err = c_spawn_wait_err(ptrs, cstatus, stderr_path//c_null_char)
      else
         err = c_spawn_wait(ptrs, cstatus)
      end if
      if (err /= 0) then
         call fatal_error(error, "cannot run '"//argv(1)%s//"': "//errno_text(int(err)))
         return
      end if
      status = int(cstatus)
   end subroutine run_program

   !> True when standard error (file descriptor 2) is a terminal.
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1_c_int
   end function stderr_is_terminal

   !> Absolute path of the running executable (/proc/self/exe), or '' if unknown.
   function executable_path() result(path)
      character(len=:), allocatable :: path
      character(kind=c_char) :: buf(4096)
      integer(c_long) :: n
      integer :: i
      n = c_readlink('/proc/self/exe'//c_null_char, buf, int(size(buf), c_size_t))
      if (n <= 0 .or. n >= size(buf)) then
         path = ''
         return
      end if
      allocate (character(len=int(n)) :: path)
      do i = 1, int(n)
         path(i:i) = buf(i)
      end do
   end function executable_path

   !> Path of the file scripts/NAME of the dpend source tree, or '' if not found:
   !> under $DPEND_ROOT, then above the running executable's build/ directory (fpm
   !> puts it in ROOT/build/...), then under the current directory.
   function find_script(name) result(path)
      character(len=*), intent(in) :: name  !! e.g. 'plot_study.sh'
      character(len=:), allocatable :: path
      character(len=4096) :: root
      character(len=:), allocatable :: exe
      integer :: length, stat, b
      logical :: exists
      call get_environment_variable('DPEND_ROOT', root, length, stat)
      if (stat == 0 .and. length > 0) then
         path = trim(root)//'/scripts/'//name
         inquire (file=path, exist=exists)
         if (exists) return
      end if
      exe = executable_path()
      b = index(exe, '/build/', back=.true.)
      if (b > 0) then
         path = exe(:b - 1)//'/scripts/'//name
         inquire (file=path, exist=exists)
         if (exists) return
      end if
      path = 'scripts/'//name
      inquire (file=path, exist=exists)
      if (.not. exists) path = ''
   end function find_script

   !> The directory part of `path` ('.' when there is none).
   pure function directory_of(path) result(dir)
      character(len=*), intent(in) :: path  !! a file path
      character(len=:), allocatable :: dir
      integer :: slash
      slash = index(path, '/', back=.true.)
      if (slash == 0) then
         dir = '.'
      else if (slash == 1) then
         dir = '/'
      else
         dir = path(:slash - 1)
      end if
   end function directory_of

   !> The last component of `path` (everything after the last '/').
   pure function base_name(path) result(name)
      character(len=*), intent(in) :: path  !! a file path
      character(len=:), allocatable :: name
      name = path(index(path, '/', back=.true.) + 1:)
   end function base_name

   !> Create directory `dir` and its missing parents (like mkdir -p), mode 0777
   !> before the umask. Fails if a component cannot be created.
   subroutine make_directories(dir, error)
      character(len=*), intent(in) :: dir               !! directory path
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      integer :: i, r
      logical :: exists
      character(len=:), allocatable :: part
      do i = 2, len_trim(dir) + 1
         if (i <= len_trim(dir)) then
            if (dir(i:i) /= '/') cycle
         end if
         part = dir(:i - 1)
         inquire (file=part//'/.', exist=exists)
         if (exists) cycle
         r = c_mkdir(part//c_null_char, int(o'777', c_int))
         inquire (file=part//'/.', exist=exists)
         if (.not. exists) then
            call fatal_error(error, "cannot create directory '"//part//"'")
            return
         end if
      end do
   end subroutine make_directories

   !> The host name (/proc/sys/kernel/hostname), or 'unknown'.
   function host_name() result(name)
      character(len=:), allocatable :: name
      name = first_line('/proc/sys/kernel/hostname', '')
      if (len(name) == 0) name = 'unknown'
   end function host_name

   !> The CPU model ('model name' in /proc/cpuinfo) and the number of logical
   !> CPUs listed there, e.g. 'Intel(R) Xeon(R) ... (2 logical CPUs)', or 'unknown'.
   function cpu_model() result(model)
      character(len=:), allocatable :: model
      character(len=1024) :: line
      character(len=16) :: count_text
      integer :: unit, stat, colon, n
      model = ''
      n = 0
      open (newunit=unit, file='/proc/cpuinfo', status='old', action='read', iostat=stat)
      if (stat /= 0) then
         model = 'unknown'
         return
      end if
      do
         read (unit, '(a)', iostat=stat) line
         if (stat /= 0) exit
         if (index(line, 'model name') == 1) then
            n = n + 1
            colon = index(line, ':')
            if (len(model) == 0 .and. colon > 0) model = trim(adjustl(line(colon + 1:)))
         end if
      end do
      close (unit)
      if (len(model) == 0) then
         model = 'unknown'
      else
         write (count_text, '(i0)') n
         model = model//' ('//trim(count_text)//' logical CPUs)'
      end if
   end function cpu_model

   !> Seconds since an arbitrary origin (system_clock, 64-bit).
   real(dp) function wall_clock()
      integer(int64) :: count, rate
      call system_clock(count, rate)
      wall_clock = real(count, dp)/real(rate, dp)
   end function wall_clock

   !> First line of a text file, or `default` if it cannot be read.
   function first_line(path, default) result(line)
      character(len=*), intent(in) :: path, default
      character(len=:), allocatable :: line
      character(len=1024) :: buf
      integer :: unit, stat
      line = default
      open (newunit=unit, file=path, status='old', action='read', iostat=stat)
      if (stat /= 0) return
      read (unit, '(a)', iostat=stat) buf
      close (unit)
      if (stat == 0) line = trim(adjustl(buf))
   end function first_line
   !> Why writing `path` may have failed, for a message: 'no space left on device'
   !> when its file system has (almost) no room left, else `fallback`.
   function io_failure_reason(path, fallback) result(reason)
      character(len=*), intent(in) :: path      !! the file that could not be written
      character(len=*), intent(in) :: fallback  !! what to say otherwise
      character(len=:), allocatable :: reason
      integer(int64) :: free
      free = free_disk_bytes(directory_of(path))
      if (free >= 0 .and. free < 1048576_int64) then
         reason = errno_text(errno_nospc)
      else
         reason = fallback
      end if
   end function io_failure_reason

   ! for the figure scripts: a program's captured stderr, shown only when it failed
   !> Copy the file `path` (a program's captured standard error) to dpend's standard
   !> error, at most its last `max_bytes` bytes; nothing if it is missing or empty.
   subroutine echo_to_stderr(path, max_bytes)
      character(len=*), intent(in) :: path   !! the captured text
      integer, intent(in) :: max_bytes       !! most bytes shown (the end of the file)
      character(len=:), allocatable :: text
      integer :: unit, stat, size_bytes, first
      open (newunit=unit, file=path, status='old', action='read', access='stream', &
            form='unformatted', iostat=stat)
      if (stat /= 0) return
      inquire (unit=unit, size=size_bytes)
      if (size_bytes > 0 .and. max_bytes > 0) then
         first = max(1, size_bytes - max_bytes + 1)
         allocate (character(len=size_bytes - first + 1) :: text)
         read (unit, pos=first, iostat=stat) text
         if (stat == 0) write (error_unit, '(a)', advance='no') text
         flush (error_unit)
      end if
      close (unit)
   end subroutine echo_to_stderr
   !> Start (`on`) or stop capturing this thread's outputs in memory (a library
   !> call, src/capi): while on, the HDF5 files this thread creates are written to
   !> memory and the image of the last one closed is kept for `take_capture`;
   !> `output_t` makes no temporary file and moves nothing. Either drops an image
   !> not taken. The state is this thread's alone.
   subroutine capture_outputs(on)
      logical, intent(in) :: on  !! capture from now on, or stop
      call c_capture_set(merge(1_c_int, 0_c_int, on))
   end subroutine capture_outputs

   !> Whether this thread captures its outputs in memory (`capture_outputs`).
   logical function capturing_outputs()
      capturing_outputs = c_capture_active() /= 0
   end function capturing_outputs

   !> A buffer of n bytes for the image of the captured file being closed (replacing
   !> the last one); c_null_ptr when memory is short.
   function capture_buffer(n) result(p)
      integer(c_size_t), intent(in) :: n  !! bytes
      type(c_ptr) :: p
      p = c_capture_buffer(n)
   end function capture_buffer

   !> The image of the last captured file, handed over (free it with C's free), and
   !> its size in bytes; c_null_ptr and 0 if none.
   function take_capture(n) result(p)
      integer(c_size_t), intent(out) :: n  !! bytes
      type(c_ptr) :: p
      p = c_capture_take(n)
   end function take_capture
   !> A new private directory `path` = prefix followed by six random characters
   !> (mkdtemp); 0 or an errno value.
   integer function make_temp_directory(prefix, path) result(err)
      character(len=*), intent(in) :: prefix             !! e.g. '/tmp/dpend-'
      character(len=:), allocatable, intent(out) :: path  !! the directory made
      character(kind=c_char) :: buf(len(prefix) + 7)
      integer :: i
      do i = 1, len(prefix)
         buf(i) = prefix(i:i)
      end do
      buf(len(prefix) + 1:len(prefix) + 6) = 'X'
      buf(len(prefix) + 7) = c_null_char
      err = int(c_make_temp_dir(buf))
      allocate (character(len=len(prefix) + 6) :: path)
      do i = 1, len(path)
         path(i:i) = buf(i)
      end do
   end function make_temp_directory

   !> Remove the empty directory `path`; 0 or an errno value.
   integer function remove_directory(path) result(err)
      character(len=*), intent(in) :: path  !! the directory
      err = int(c_remove_dir(path//c_null_char))
   end function remove_directory
end module dpend_os
