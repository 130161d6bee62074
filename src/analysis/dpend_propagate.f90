!> Propagation drivers shared by every command: march a method over an interval,
!> reach an end time exactly, and sample a trajectory on a uniform time grid
!> through the methods' continuous extensions (`integrator_t%interpolate`).
!>
!> Fixed-step methods take whole steps of h at t0 + i h (times are recomputed from
!> the step count, so they do not drift) and one shortened last step only when
!> t_end is not on that grid. Adaptive methods take accepted steps with the
!> proposed size, the last one capped to end exactly on t_end; a step is stretched
!> by up to 1 % to avoid a tiny last step (as in DOPRI5/DOP853). Both directions
!> of time are supported: the sign of t_end - t decides, h is taken as |h|.
!> A fixed-step method given h = 0 fails with stat_step_too_small. Every 256 steps a
!> march looks at the stop request (`dpend_stop_request`: a library caller's
!> dpend_cancel) and fails with stat_stopped when there is one.
!>
!> Progress: a command whose work is one or more marches (lyapunov, indicators,
!> divergence, poincare, simulate) reports it in model time through one
!> `march_progress_t` shared by all of them (the span they cover in all, known before
!> they start): each march given it adds the model time it covered every 256 steps
!> and at its end, so the report (`dpend_progress`: a bar on a terminal, a line at
!> most every 10 s in a log) moves however the work is split into marches or threads.
module dpend_propagate
   use dpend_kinds, only: dp, i8
   use dpend_model, only: model_t, max_state
   use dpend_integrator, only: integrator_t, stat_ok, stat_step_too_small, stat_max_steps, &
                               stat_count_limit, stat_stopped
   use dpend_stop_request, only: stop_requested
   use dpend_limits, only: max_steps, max_samples
   use dpend_progress, only: progress_t
   implicit none
   private
   public :: march_t, advance_fixed, advance_to, integrate_sampled, march_progress_t

   !> The units of a `march_progress_t` report: its span in parts per 1e9.
   integer(i8), parameter :: parts = 1000000000_i8

   !> The progress of a command's marches in model time (see the module header).
   type :: march_progress_t
      type(progress_t) :: bar          !! the report, in units of 1e-9 `span`
      real(dp) :: span = 0.0_dp        !! model time all the marches cover [s]
      real(dp) :: covered = 0.0_dp     !! model time covered so far [s]
   contains
      procedure :: begin => march_progress_begin
      procedure :: advance => march_progress_advance
      procedure :: end => march_progress_end
   end type march_progress_t

   !> A march from t0 to t_end, one step per `next` call. Use it to write custom
   !> loops (streaming output, events) that share the stepping rules above:
   !>   call march%start(integ, t, t_end, h)
   !>   do while (.not. march%finished)
   !>      call march%next(integ, model, t, y, h, stat); if (stat /= stat_ok) exit
   !>      ... the step [integ%t_old, integ%t_new] is available for interpolation
   !>   end do
   type :: march_t
      real(dp) :: t0 = 0.0_dp          !! start time [s]
      real(dp) :: t_end = 0.0_dp       !! end time [s]
      real(dp) :: dir = 1.0_dp         !! +1 forward, -1 backward
      real(dp) :: h_fixed = 0.0_dp     !! signed fixed step [s]
      integer(i8) :: n_whole = 0       !! whole fixed steps
      integer(i8) :: i = 0             !! steps taken so far (fixed-step methods)
      logical :: shortened = .false.   !! a shortened last fixed step is needed
      logical :: adaptive = .false.    !! the method controls its step
      logical :: finished = .true.     !! t_end has been reached
      logical :: too_many = .false.    !! fixed steps above max_steps: `next` refuses
      !> the command's progress this march adds to (none: not associated), the time
      !> up to which it has added, and the steps since
      type(march_progress_t), pointer :: progress => null()
      real(dp) :: t_reported = 0.0_dp
      integer :: since_report = 0
      integer(i8) :: n_adaptive = 0    !! accepted steps so far (adaptive methods)
      integer :: since_stop_check = 0  !! steps since the stop request was looked at
   contains
      procedure :: start => march_start
      procedure :: next => march_next
   end type march_t

contains

   !> Plan a march of `integ` from t to t_end. For fixed-step methods h is the
   !> step (its magnitude is used); for adaptive ones the initial proposal
   !> (h = 0: the method chooses it).
   subroutine march_start(self, integ, t, t_end, h)
      class(march_t), intent(inout) :: self        !! the march
      class(integrator_t), intent(in) :: integ     !! the method
      real(dp), intent(in) :: t                    !! start time [s]
      real(dp), intent(in) :: t_end                !! end time [s]
      real(dp), intent(inout) :: h                 !! step or proposal [s]; signed on return
      real(dp) :: r, tol
      integer(i8) :: n
      self%t0 = t
      self%t_end = t_end
      self%dir = merge(-1.0_dp, 1.0_dp, t_end < t)
      self%adaptive = integ%adaptive()
      self%finished = t_end == t
      self%i = 0
      self%n_whole = 0
      self%shortened = .false.
      self%too_many = .false.
      self%n_adaptive = 0
      self%t_reported = t
      self%since_report = 0
      if (self%adaptive) then
         h = self%dir*abs(h)
         if (h == 0.0_dp .and. self%dir < 0.0_dp) h = -1.0e-3_dp*abs(t_end - t)
         return
      end if
      h = self%dir*abs(h)
      self%h_fixed = h
      if (self%finished .or. h == 0.0_dp) return   ! h = 0: `next` reports it
      ! compared before dividing: (t_end - t)/h may not fit an integer (or a real)
      if (abs(t_end - t) > abs(h)*real(max_steps, dp)) then
         self%too_many = .true.                    ! `next` reports it
         return
      end if
      r = (t_end - t)/h
      n = nint(r, i8)
      tol = 16.0_dp*epsilon(1.0_dp)*max(abs(t), abs(t_end), abs(real(n, dp)*h))
      if (n >= 1 .and. abs(t + real(n, dp)*h - t_end) <= tol) then
         self%n_whole = n
      else
         self%n_whole = max(0_i8, int(r, i8))
         self%shortened = .true.
      end if
   end subroutine march_start

   !> Take the next step of the march; sets `finished` after the last one, which
   !> ends exactly on t_end. h: the fixed step, or the adaptive proposal (updated).
   !> With a progress, the model time covered is added every 256 steps and at the end
   !> (inline here: a call level more costs 4 % of a symplectic step's time).
   subroutine march_next(self, integ, model, t, y, h, stat)
      class(march_t), intent(inout) :: self        !! the march
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t                 !! time [s]
      real(dp), intent(inout) :: y(:)              !! internal state
      real(dp), intent(inout) :: h                 !! step or proposal [s]
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      real(dp) :: hs, t_save, y_save(max_state)
      integer :: ns
      logical :: last
      stat = stat_ok
      ns = size(y)
      if (self%finished) return
      self%since_stop_check = self%since_stop_check + 1
      if (self%since_stop_check >= 256) then   ! a library caller's dpend_cancel
         self%since_stop_check = 0
         if (stop_requested()) then
            stat = stat_stopped
            return
         end if
      end if
      if (associated(self%progress)) then
         self%since_report = self%since_report + 1
         if (self%since_report >= 256) call report_progress(self, t)
      end if
      if (self%adaptive) then
         if (self%n_adaptive >= integ%max_steps) then
            stat = stat_max_steps
            return
         end if
         self%n_adaptive = self%n_adaptive + 1
         last = self%dir*(t + 1.01_dp*h - self%t_end) >= 0.0_dp
         if (last) then
            hs = self%t_end - t
         else
            hs = h
         end if
         t_save = t; y_save(:ns) = y
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) return
         if (self%dir*(t - self%t_end) > 0.0_dp) then
            ! only possible when the method chose its first step (h = 0) longer
            ! than the whole interval: redo it, capped
            t = t_save; y = y_save(:ns)
            h = hs
            hs = self%t_end - t
            call integ%step(model, t, y, hs, stat)
            if (stat /= stat_ok) return
         end if
         if (abs(self%t_end - t) <= 4.0_dp*epsilon(1.0_dp)*max(abs(t), abs(self%t_end))) then
            ! the capped last step was accepted: its proposal may be artificially
            ! small, keep the one from before the capping if larger
            t = self%t_end
            self%finished = .true.
            h = sign(max(abs(h), abs(hs)), h)
            if (associated(self%progress)) call report_progress(self, t)
         else
            h = hs
         end if
         return
      end if
      if (self%h_fixed == 0.0_dp) then
         stat = stat_step_too_small              ! a fixed-step method needs h /= 0
         return
      end if
      if (self%too_many) then
         stat = stat_count_limit                 ! more than max_steps steps
         return
      end if
      if (self%i < self%n_whole) then
         hs = self%h_fixed
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) return
         self%i = self%i + 1
         t = self%t0 + real(self%i, dp)*self%h_fixed
         if (self%i == self%n_whole .and. .not. self%shortened) then
            t = self%t_end
            self%finished = .true.
            if (associated(self%progress)) call report_progress(self, t)
         end if
      else
         hs = self%t_end - t
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) return
         t = self%t_end
         self%finished = .true.
         if (associated(self%progress)) call report_progress(self, t)
      end if
   end subroutine march_next

   !> Add the model time covered since the last report to the march's progress.
   subroutine report_progress(self, t)
      type(march_t), intent(inout) :: self  !! the march (its progress associated)
      real(dp), intent(in) :: t             !! the time reached [s]
      call self%progress%advance(abs(t - self%t_reported))
      self%t_reported = t
      self%since_report = 0
   end subroutine report_progress

   !> Begin the report of marches that cover `span` seconds of model time in all (a
   !> bar after 1 s on a terminal, else a line at most every 10 s, none for a run
   !> shorter than that; nothing when the process is quiet).
   subroutine march_progress_begin(self, label, span)
      class(march_progress_t), intent(inout) :: self  !! the progress
      character(len=*), intent(in) :: label           !! e.g. 'dpend lyapunov'
      real(dp), intent(in) :: span                    !! model time in all [s]
      self%span = abs(span)
      self%covered = 0.0_dp
      ! parts per 1e9: a rate (and so a time left) even when a long run has covered
      ! a millionth of its span
      call self%bar%start(label, parts, 0_i8, .false., what='')
      if (self%bar%tty) self%bar%t_last = self%bar%t_start + 0.8_dp
   end subroutine march_progress_begin

   !> Add `dt` seconds of model time covered (from any thread).
   subroutine march_progress_advance(self, dt)
      class(march_progress_t), intent(inout) :: self  !! the progress
      real(dp), intent(in) :: dt                      !! model time just covered [s]
      integer(i8) :: done
      !$omp critical (dpend_march_progress)
      self%covered = self%covered + dt
      done = parts
      if (self%span > 0.0_dp) &
         done = int(min(real(parts, dp), real(parts, dp)*self%covered/self%span), i8)
      call self%bar%update(max(0_i8, done - self%bar%done))
      !$omp end critical (dpend_march_progress)
   end subroutine march_progress_advance

   !> End the report (the bar's closing line on a terminal, if one was drawn).
   subroutine march_progress_end(self)
      class(march_progress_t), intent(inout) :: self  !! the progress
      if (self%bar%lines > 0) call self%bar%finish()
   end subroutine march_progress_end

   !> Take exactly `nsteps` calls of `step` with h, from (t, y). For fixed-step
   !> methods t advances to t0 + nsteps h (computed without drift); adaptive
   !> methods take `nsteps` accepted steps and return the next proposal in h.
   subroutine advance_fixed(integ, model, t, y, h, nsteps, stat)
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t                 !! time [s]
      real(dp), intent(inout) :: y(:)              !! internal state
      real(dp), intent(inout) :: h                 !! step [s]
      integer(i8), intent(in) :: nsteps            !! number of steps
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      real(dp) :: t0, hs
      integer(i8) :: i
      stat = stat_ok
      t0 = t
      do i = 1, nsteps
         hs = h
         call integ%step(model, t, y, hs, stat)
         if (stat /= stat_ok) return
         if (integ%adaptive()) then
            h = hs
         else
            t = t0 + real(i, dp)*h
         end if
      end do
   end subroutine advance_fixed

   !> Advance (t, y) to exactly t = t_target (see the module header for the rules).
   !> h: the fixed step, or the initial proposal of an adaptive method (0: the
   !> method chooses), returned as the next proposal.
   subroutine advance_to(integ, model, t, y, t_target, h, stat)
      class(integrator_t), intent(inout) :: integ  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t                 !! time [s]
      real(dp), intent(inout) :: y(:)              !! internal state
      real(dp), intent(in) :: t_target             !! end time [s]
      real(dp), intent(inout) :: h                 !! step or proposal [s]
      integer, intent(out) :: stat                 !! stat_ok or a failure code
      type(march_t) :: march
      stat = stat_ok
      call march%start(integ, t, t_target, h)
      do while (.not. march%finished)
         call march%next(integ, model, t, y, h, stat)
         if (stat /= stat_ok) return
      end do
   end subroutine advance_to

   !> Integrate from (t0, y0) to t_end and return the internal states at
   !> t0 + k·output_dt (k = 0, 1, …, up to t_end) and at t_end itself (which is
   !> not repeated when it lies on the grid). Samples inside a step come from the
   !> method's continuous extension, samples on a step end are the step result.
   !> With output_dt <= 0 every step end is returned instead.
   !> h: the fixed step, or the initial proposal of an adaptive method (0: auto).
   !> The method's step memory is cleared at the start. On failure `stat` says
   !> why and the arrays hold the samples computed so far.
   subroutine integrate_sampled(integ, model, t0, y0, t_end, h, output_dt, times, states, stat, &
                                progress)
      class(integrator_t), intent(inout) :: integ        !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(in) :: t0                         !! start time [s]
      real(dp), intent(in) :: y0(:)                      !! internal state at t0
      real(dp), intent(in) :: t_end                      !! end time [s]
      real(dp), intent(in) :: h                          !! step or initial proposal [s]
      real(dp), intent(in) :: output_dt                  !! sampling interval [s]
      real(dp), allocatable, intent(out) :: times(:)     !! sample times [s]
      real(dp), allocatable, intent(out) :: states(:, :) !! internal states, (2n, samples)
      integer, intent(out) :: stat                       !! stat_ok or a failure code
      !> the command's progress, which this march adds to
      type(march_progress_t), intent(inout), target, optional :: progress
      type(march_t) :: march
      real(dp) :: t, y(size(y0)), hh, d, tk, tol, r
      integer(i8) :: k, n_grid, n
      stat = stat_ok
      call integ%clear_step()
      t = t0; y = y0; hh = h
      d = merge(-1.0_dp, 1.0_dp, t_end < t0)*abs(output_dt)
      if (output_dt > 0.0_dp .and. abs(t_end - t0) > abs(d)*real(max_samples, dp)) then
         ! compared before dividing: more samples than any array can hold
         stat = stat_count_limit
         allocate (times(1), states(size(y0), 1))
         times(1) = t0; states(:, 1) = y0
         return
      end if
      if (output_dt > 0.0_dp) then
         ! grid t0 + k d, k = 0..n_grid, and t_end if it is off the grid
         r = (t_end - t0)/d
         n_grid = int(r, i8)
         if (nint(r, i8) > n_grid .and. abs(t0 + real(nint(r, i8), dp)*d - t_end) <= &
             16.0_dp*epsilon(1.0_dp)*max(abs(t0), abs(t_end))) n_grid = nint(r, i8)
         n = n_grid + 1
         if (abs(t0 + real(n_grid, dp)*d - t_end) > &
             16.0_dp*epsilon(1.0_dp)*max(abs(t0), abs(t_end))) n = n + 1
      else
         n_grid = 0
         n = 64
      end if
      allocate (times(n), states(size(y0), n))
      n = 1
      times(1) = t0; states(:, 1) = y0
      k = 1
      if (present(progress)) march%progress => progress
      call march%start(integ, t, t_end, hh)
      do while (.not. march%finished)
         call march%next(integ, model, t, y, hh, stat)
         if (stat /= stat_ok) exit
         if (output_dt <= 0.0_dp) then
            call push(t, y)
            cycle
         end if
         tol = 4.0_dp*epsilon(1.0_dp)*max(abs(t), abs(t0))
         do while (k <= n_grid)
            tk = t0 + real(k, dp)*d
            if (march%dir*(tk - t) > tol) exit
            if (abs(tk - t) <= tol) then
               call push(tk, y)
            else
               call push(tk, interpolated(tk))
            end if
            k = k + 1
         end do
         if (march%finished .and. times(n) /= t_end) then
            if (abs(times(n) - t_end) <= 16.0_dp*epsilon(1.0_dp)*max(abs(t0), abs(t_end))) then
               times(n) = t_end
               states(:, n) = y
            else
               call push(t_end, y)
            end if
         end if
      end do
      times = times(1:n)
      states = states(:, 1:n)
   contains
      function interpolated(ts) result(ys)
         real(dp), intent(in) :: ts
         real(dp) :: ys(size(y))
         ys = y
         call integ%interpolate(model, ts, ys)
      end function interpolated

      subroutine push(ts, ys)
         real(dp), intent(in) :: ts, ys(:)
         real(dp), allocatable :: tt(:), ss(:, :)
         if (n == size(times)) then
            allocate (tt(2*n), ss(size(y0), 2*n))
            tt(1:n) = times; ss(:, 1:n) = states
            call move_alloc(tt, times); call move_alloc(ss, states)
         end if
         n = n + 1
         times(n) = ts
         states(:, n) = ys
      end subroutine push
   end subroutine integrate_sampled
end module dpend_propagate
