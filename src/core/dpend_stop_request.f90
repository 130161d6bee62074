!> A request to stop the run in progress, made from outside it: a library caller's
!> `dpend_cancel` (src/capi), from another thread. Long loops look at it where they
!> can stop cleanly: the sweep between blocks and when a lane takes its next
!> trajectory, every march of a method every 256 steps (`dpend_propagate`: simulate,
!> the chaos commands, the fit, the study). The one piece of process-wide state of the core, like a signal; a
!> volatile flag, set and cleared whole.
module dpend_stop_request
   implicit none
   private
   public :: request_stop, clear_stop_request, stop_requested

   logical, volatile, save :: requested = .false.

contains

   !> Ask the run in progress to stop.
   subroutine request_stop()
      requested = .true.
   end subroutine request_stop

   !> Forget a request (a new run starts).
   subroutine clear_stop_request()
      requested = .false.
   end subroutine clear_stop_request

   !> Whether a stop was requested since the last `clear_stop_request`.
   logical function stop_requested()
      stop_requested = requested
   end function stop_requested
end module dpend_stop_request
