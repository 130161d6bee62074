!> Progress report of long runs on stderr: a bar redrawn in place (percent,
!> trajectories per second, time left: `ETA ~h:mm:ss`, an estimate at the rate so far,
!> not a bound) when stderr is a terminal, otherwise (logs,
!> CI) a plain line at most every `interval` seconds (10 s), the first one only
!> after `interval` (a short run writes none), nothing when quiet. This is the one
!> mechanism of every long command (sweep, study, simulate, fit); the
!> clock can be injected (`update`'s `now`) to test the rate. `--quiet` of any
!> command silences every report of the process (`silence_progress`). A command may
!> queue one line (`progress_header`: the horizon of a sweep) that the next report
!> prints when it starts, so that a run refused before it starts stays one line.
!> A listener (`set_progress_listener`: the library's progress callback, src/capi) is
!> told of every report, silenced or not, at most every 0.1 s and at its start and end.
module dpend_progress
   use, intrinsic :: iso_c_binding, only: c_int
   use, intrinsic :: iso_fortran_env, only: error_unit
   use dpend_kinds, only: dp, i8
   use dpend_strings, only: real_str, to_str
   implicit none
   private
   public :: progress_t, stderr_is_terminal, wall_seconds, silence_progress, progress_silenced
   public :: progress_header, show_progress_header
   public :: progress_listener_i, set_progress_listener, progress_listened

   !> A line the next `progress_start` prints first (unless quiet); '' none.
   character(len=:), allocatable, save :: pending_header

   !> Every report of this process is quiet (a command's --quiet: `silence_progress`).
   logical, save :: silenced = .false.

   abstract interface
      !> Told that `done` of `total` units of the report `label` are done (`what`
      !> the unit: 'traj', 'runs', ''  a fraction of a horizon, in parts).
      subroutine progress_listener_i(label, what, done, total)
         import :: i8
         character(len=*), intent(in) :: label, what
         integer(i8), intent(in) :: done, total
      end subroutine progress_listener_i
   end interface

   !> The listener of every report (null: none).
   procedure(progress_listener_i), pointer, save :: listener => null()

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
      !> What a unit is ('traj': 'traj/s' in the line; '': no rate shown).
      character(len=:), allocatable :: what
      integer :: unit = error_unit     !! where the lines go (tests: a scratch file)
      integer :: lines = 0             !! lines written (plain) or bars drawn (tty)
      real(dp) :: t_told = -1e30_dp    !! wall clock when the listener was last told [s]
      integer(i8) :: told = -1         !! `done` the listener was last told
   contains
      procedure :: start => progress_start
      procedure :: update => progress_update
      procedure :: finish => progress_finish
   end type progress_t

contains

   !> Tell `f` of every report from now on (null(): no listener). A library run sets
   !> it and clears it after; the lock of library runs keeps it one run's.
   subroutine set_progress_listener(f)
      procedure(progress_listener_i), pointer, intent(in) :: f  !! the listener or null
      listener => f
   end subroutine set_progress_listener

   !> Whether a listener is set (a report that would be silent is made for it).
   logical function progress_listened()
      progress_listened = associated(listener)
   end function progress_listened

   !> Tell the listener, when there is one: at most every 0.1 s, and always when all
   !> is done or `always`.
   subroutine tell_listener(self, now, always)
      class(progress_t), intent(inout) :: self  !! the report
      real(dp), intent(in) :: now               !! the clock [s]
      logical, intent(in) :: always             !! tell now, whatever the clock
      if (.not. associated(listener)) return
      if (.not. always .and. self%done < self%total .and. now - self%t_told < 0.1_dp) return
      if (self%told == self%done .and. .not. always) return
      self%t_told = now
      self%told = self%done
      call listener(self%label, self%what, self%done, self%total)
   end subroutine tell_listener

   !> Make every progress report of this process quiet (a command's --quiet).
   subroutine silence_progress()
      silenced = .true.
   end subroutine silence_progress

   !> Queue `line` for the next report's start (printed unless that report is quiet).
   subroutine progress_header(line)
      character(len=*), intent(in) :: line  !! e.g. 'dpend sweep: t_end = ...'
      pending_header = line
   end subroutine progress_header

   !> Print the queued header now (unless the process is silenced), before work that
   !> may take long ahead of the report's start, once nothing can be refused any more
   !> (a refusal stays one line).
   subroutine show_progress_header()
      if (.not. allocated(pending_header)) return
      if (.not. silenced .and. len(pending_header) > 0) then
         write (error_unit, '(a)') pending_header
         flush (error_unit)
      end if
      deallocate (pending_header)
   end subroutine show_progress_header

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
   subroutine progress_start(self, label, total, done, quiet, what, now)
      class(progress_t), intent(inout) :: self  !! the report
      character(len=*), intent(in) :: label     !! e.g. 'dpend sweep'
      integer(i8), intent(in) :: total          !! all units of work
      integer(i8), intent(in) :: done           !! units done before this run
      logical, intent(in) :: quiet              !! print nothing
      character(len=*), intent(in), optional :: what  !! a unit ('traj'; '' no rate)
      real(dp), intent(in), optional :: now     !! the clock [s] (default wall_seconds)
      self%label = label
      self%what = 'traj'
      if (present(what)) self%what = what
      self%total = total
      self%done = done
      self%done_start = done
      self%quiet = quiet .or. silenced
      self%tty = stderr_is_terminal()
      if (present(now)) then
         self%t_start = now
      else
         self%t_start = wall_seconds()
      end if
      self%t_last = -1e30_dp
      ! a plain line only after `interval` (a short run writes none)
      if (.not. self%tty) self%t_last = self%t_start
      self%lines = 0
      self%told = -1
      call tell_listener(self, self%t_start, .true.)
      if (allocated(pending_header)) then
         if (.not. self%quiet .and. len(pending_header) > 0) then
            write (self%unit, '(a)') pending_header
            flush (self%unit)
         end if
         deallocate (pending_header)
      end if
   end subroutine progress_start

   !> Add `units` done and report if it is time to: a bar at most every 0.2 s (and
   !> at the end) on a terminal, a plain line at most every `interval` seconds
   !> otherwise (never at the end by itself: the command's closing line says it).
   subroutine progress_update(self, units, now)
      class(progress_t), intent(inout) :: self  !! the report
      integer(i8), intent(in) :: units          !! units just completed
      real(dp), intent(in), optional :: now     !! the clock [s] (default wall_seconds)
      real(dp) :: t
      self%done = self%done + units
      if (self%quiet .and. .not. associated(listener)) return
      if (present(now)) then
         t = now
      else
         t = wall_seconds()
      end if
      call tell_listener(self, t, .false.)
      if (self%quiet) return
      if (self%tty) then
         if (t - self%t_last < 0.2_dp .and. self%done < self%total) return
      else
         if (t - self%t_last < self%interval) return
      end if
      self%t_last = t
      call report(self, t)
   end subroutine progress_update

   !> End the report: the bar at 100 % and a new line on a terminal; nothing more
   !> in a log (its lines stay at most one every `interval`).
   subroutine progress_finish(self)
      class(progress_t), intent(inout) :: self  !! the report
      if (self%told /= self%done) call tell_listener(self, wall_seconds(), .true.)
      if (self%quiet .or. .not. self%tty) return
      if (self%reported /= self%done) call report(self, wall_seconds())
      write (self%unit, '(a)') ''
      flush (self%unit)
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
      self%lines = self%lines + 1
      elapsed = max(now - self%t_start, 1e-9_dp)
      frac = 1.0_dp
      if (self%total > 0) frac = real(self%done, dp)/real(self%total, dp)
      rate = real(self%done - self%done_start, dp)/elapsed
      eta = -1.0_dp
      if (rate > 0.0_dp) eta = real(self%total - self%done, dp)/rate
      if (self%tty) then
         filled = min(width, int(frac*width))
         bar = repeat('#', filled)//repeat('.', width - filled)
         write (line, '(a, " [", a, "] ", f5.1, "%  ", a, "ETA ~", a)') &
            self%label, bar, 100.0_dp*frac, rate_text(' '), clock(eta)
         write (self%unit, '(a)', advance='no') achar(13)//trim(line)//'   '
      else
         write (line, '(a, ": ", a, "%", a, ", ", a, "elapsed ", a, ", ETA ~", a)') &
            self%label, percent_text(), count_text(), &
            rate_text(', '), clock(elapsed), clock(eta)
         write (self%unit, '(a)') trim(line)
      end if
      flush (self%unit)
   contains
      !> The percentage done to 0.1, or to 2 digits below 0.1 % (a run of days moves
      !> visibly between two lines: '0.0012').
      function percent_text() result(t)
         character(len=:), allocatable :: t
         if (frac >= 0.001_dp .or. frac <= 0.0_dp) then
            t = real_str(anint(1000.0_dp*frac)/10.0_dp)
         else
            t = real_str(100.0_dp*frac, 2)
         end if
      end function percent_text
      !> ' (12/100)', or '' without a unit (a fraction of a horizon).
      function count_text() result(t)
         character(len=:), allocatable :: t
         t = ''
         if (len(self%what) > 0) t = ' ('//to_str(self%done)//'/'//to_str(self%total)//')'
      end function count_text
      !> '1.2e3 traj/s' and `sep`, or '' without a unit.
      function rate_text(sep) result(t)
         character(len=*), intent(in) :: sep
         character(len=:), allocatable :: t
         t = ''
         if (len(self%what) > 0) t = real_str(rate, 3)//' '//self%what//'/s'//sep
         if (self%tty .and. len(t) > 0) t = t//' '
      end function rate_text
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
