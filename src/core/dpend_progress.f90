!> Progress report of long runs on stderr: a bar redrawn in place (percent,
!> trajectories per second, time left) when stderr is a terminal, a plain line
!> every `interval` seconds otherwise (logs, CI), nothing when quiet. `--quiet` of
!> any command silences every report of the process (`silence_progress`).
module dpend_progress
   use, intrinsic :: iso_c_binding, only: c_int
   use, intrinsic :: iso_fortran_env, only: error_unit
   use dpend_kinds, only: dp, i8
   use dpend_strings, only: real_str
   implicit none
   private
   public :: progress_t, stderr_is_terminal, wall_seconds, silence_progress, progress_silenced

   !> Every report of this process is quiet (a command's --quiet: `silence_progress`).
   logical, save :: silenced = .false.

   interface
      !> POSIX isatty(3): 1 if the file descriptor is a terminal.
      integer(c_int) function c_isatty(fd) bind(C, name='isatty')
         import :: c_int
         integer(c_int), value :: fd
      end function c_isatty
   end interface

   !> State of one progress report.
   type :: progress_t
      logical :: quiet = .false.       !! print nothing
      logical :: tty = .false.         !! redraw a bar in place
      integer(i8) :: total = 0         !! units of work (trajectories) in all
      integer(i8) :: done = 0          !! units done, including those done before a resume
      integer(i8) :: done_start = 0    !! units already done when this run started
      real(dp) :: t_start = 0          !! wall clock at start [s]
      real(dp) :: t_last = -1e30_dp    !! wall clock of the last report [s]
      real(dp) :: interval = 10.0_dp   !! seconds between plain lines
      integer(i8) :: reported = -1     !! `done` at the last report
      character(len=:), allocatable :: label  !! prefix of every line
   contains
      procedure :: start => progress_start
      procedure :: update => progress_update
      procedure :: finish => progress_finish
   end type progress_t

contains

   !> Make every progress report of this process quiet (a command's --quiet).
   subroutine silence_progress()
      silenced = .true.
   end subroutine silence_progress

   !> Whether `silence_progress` was called (reports of their own stay quiet then).
   logical function progress_silenced()
      progress_silenced = silenced
   end function progress_silenced

   !> True if stderr (file descriptor 2) is a terminal.
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1
   end function stderr_is_terminal

   !> Wall-clock time [s] from an arbitrary origin.
   real(dp) function wall_seconds()
      integer(i8) :: count, rate
      call system_clock(count, rate)
      wall_seconds = real(count, dp)/real(rate, dp)
   end function wall_seconds

   !> Begin a report of `total` units of which `done` are already done.
   subroutine progress_start(self, label, total, done, quiet)
      class(progress_t), intent(inout) :: self  !! the report
      character(len=*), intent(in) :: label     !! e.g. 'dpend sweep'
      integer(i8), intent(in) :: total          !! all units of work
      integer(i8), intent(in) :: done           !! units done before this run
      logical, intent(in) :: quiet              !! print nothing
      self%label = label
      self%total = total
      self%done = done
      self%done_start = done
      self%quiet = quiet .or. silenced
      self%tty = stderr_is_terminal()
      self%t_start = wall_seconds()
      self%t_last = -1e30_dp
   end subroutine progress_start

   !> Add `units` done and report if it is time to.
   subroutine progress_update(self, units)
      class(progress_t), intent(inout) :: self  !! the report
      integer(i8), intent(in) :: units          !! units just completed
      real(dp) :: now
      self%done = self%done + units
      if (self%quiet) return
      now = wall_seconds()
      if (self%tty) then
         if (now - self%t_last < 0.2_dp .and. self%done < self%total) return
      else
         if (now - self%t_last < self%interval .and. self%done < self%total) return
      end if
      self%t_last = now
      call report(self, now)
   end subroutine progress_update

   !> End the report (a new line after the bar).
   subroutine progress_finish(self)
      class(progress_t), intent(inout) :: self  !! the report
      if (self%quiet) return
      if (self%reported /= self%done) call report(self, wall_seconds())
      if (self%tty) write (error_unit, '(a)') ''
      flush (error_unit)
   end subroutine progress_finish

   subroutine report(self, now)
      type(progress_t), intent(inout) :: self
      real(dp), intent(in) :: now
      integer, parameter :: width = 30
      real(dp) :: frac, rate, eta, elapsed
      integer :: filled
      character(len=200) :: line
      character(len=width) :: bar
      self%reported = self%done
      elapsed = max(now - self%t_start, 1e-9_dp)
      frac = 1.0_dp
      if (self%total > 0) frac = real(self%done, dp)/real(self%total, dp)
      rate = real(self%done - self%done_start, dp)/elapsed
      eta = -1.0_dp
      if (rate > 0.0_dp) eta = real(self%total - self%done, dp)/rate
      if (self%tty) then
         filled = min(width, int(frac*width))
         bar = repeat('#', filled)//repeat('.', width - filled)
         write (line, '(a, " [", a, "] ", f5.1, "%  ", a, " traj/s  ETA ", a)') &
            self%label, bar, 100.0_dp*frac, real_str(rate, 3), clock(eta)
         write (error_unit, '(a)', advance='no') achar(13)//trim(line)//'   '
      else
         write (line, '(a, ": ", a, "% (", i0, "/", i0, "), ", a, &
            &" traj/s, elapsed ", a, ", ETA ", a)') self%label, &
            real_str(anint(1000.0_dp*frac)/10.0_dp), self%done, &
            self%total, real_str(rate, 3), clock(elapsed), clock(eta)
         write (error_unit, '(a)') trim(line)
      end if
      flush (error_unit)
   end subroutine report

   !> Seconds as h:mm:ss ('--' if unknown).
   function clock(seconds) result(s)
      real(dp), intent(in) :: seconds
      character(len=:), allocatable :: s
      character(len=32) :: buf
      integer(i8) :: t
      if (.not. (seconds >= 0.0_dp .and. seconds < 1e9_dp)) then
         s = '--'
         return
      end if
      t = nint(seconds, i8)
      write (buf, '(i0, ":", i2.2, ":", i2.2)') t/3600, mod(t/60, 60_i8), mod(t, 60_i8)
      s = trim(buf)
   end function clock
end module dpend_progress
