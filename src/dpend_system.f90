!> Small operating-system services for long-running commands (POSIX, Linux):
!> whether stderr is a terminal, the path of the running executable, creating
!> directories, the host name and CPU model for output files, and a wall clock.
module dpend_system
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_size_t, c_null_char
   use, intrinsic :: iso_fortran_env, only: int64
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   implicit none
   private
   public :: stderr_is_terminal, executable_path, make_directories, host_name, cpu_model
   public :: wall_clock, directory_of

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
   end interface

contains

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
end module dpend_system
