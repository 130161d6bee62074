!> Shared counters for dynamic load balancing over MPI ranks: a few 64-bit
!> integers in an MPI-3 window on one rank (the host), read and advanced by any
!> rank with one atomic `MPI_Fetch_and_op` (passive target, `MPI_Win_lock_all`),
!> without any action of the host. `fetch_add(i, 1)` is a work queue: each call
!> returns a different value, so every rank takes the next task when it is free.
!>
!> Calls on one counter must not overlap in time within a process (MPI_THREAD_SERIALIZED:
!> guard them with one OpenMP critical section). `create` and `destroy` are
!> collective over the communicator.
module dpend_mpi_counter
   use, intrinsic :: iso_c_binding, only: c_ptr, c_f_pointer
   use mpi_f08, only: MPI_Comm, MPI_Win, MPI_INFO_NULL, MPI_INTEGER8, MPI_SUM, &
      MPI_REPLACE, MPI_ADDRESS_KIND, MPI_LOCK_EXCLUSIVE, MPI_MODE_NOCHECK, &
      MPI_Comm_rank, MPI_Win_allocate, MPI_Win_lock, MPI_Win_unlock, MPI_Win_lock_all, &
      MPI_Win_unlock_all, MPI_Win_free, MPI_Win_flush, MPI_Fetch_and_op, MPI_Barrier
   use dpend_kinds, only: i8
   implicit none
   private
   public :: shared_counter_t

   !> Counters 0 .. n-1 in a window on rank `host`.
   type :: shared_counter_t
      private
      type(MPI_Win) :: win          !! the window
      type(MPI_Comm) :: comm        !! its communicator
      integer :: host = 0           !! rank that holds the values
      logical :: active = .false.   !! created and not yet destroyed
   contains
      procedure :: create => counter_create
      procedure :: fetch_add => counter_fetch_add
      procedure :: swap => counter_swap
      procedure :: destroy => counter_destroy
   end type shared_counter_t

contains

   !> Create `n` counters, all 0, on rank `host` of `comm` (collective).
   subroutine counter_create(self, comm, n, host)
      class(shared_counter_t), intent(inout) :: self  !! the counters
      type(MPI_Comm), intent(in) :: comm              !! ranks that share them
      integer, intent(in) :: n                        !! number of counters
      integer, intent(in), optional :: host           !! rank holding them (default 0)
      integer(i8), pointer :: cells(:)
      integer(MPI_ADDRESS_KIND) :: bytes
      type(c_ptr) :: base
      integer :: me
      self%comm = comm
      self%host = 0
      if (present(host)) self%host = host
      call MPI_Comm_rank(comm, me)
      bytes = 0
      if (me == self%host) bytes = int(n, MPI_ADDRESS_KIND)*8
      call MPI_Win_allocate(bytes, 8, MPI_INFO_NULL, comm, base, self%win)
      if (me == self%host) then
         ! a local store into window memory, inside an exclusive epoch
         call MPI_Win_lock(MPI_LOCK_EXCLUSIVE, self%host, 0, self%win)
         call c_f_pointer(base, cells, [n])
         cells = 0
         call MPI_Win_unlock(self%host, self%win)
      end if
      call MPI_Barrier(comm)
      call MPI_Win_lock_all(MPI_MODE_NOCHECK, self%win)
      self%active = .true.
   end subroutine counter_create

   !> Add `inc` to counter `i` and return its value before (atomic).
   integer(i8) function counter_fetch_add(self, i, inc) result(old)
      class(shared_counter_t), intent(inout) :: self  !! the counters
      integer, intent(in) :: i                        !! counter, 0-based
      integer(i8), intent(in) :: inc                  !! increment
      call MPI_Fetch_and_op(inc, old, MPI_INTEGER8, self%host, &
                            int(i, MPI_ADDRESS_KIND), MPI_SUM, self%win)
      call MPI_Win_flush(self%host, self%win)
   end function counter_fetch_add

   !> Set counter `i` to `value` and return its value before (atomic).
   integer(i8) function counter_swap(self, i, value) result(old)
      class(shared_counter_t), intent(inout) :: self  !! the counters
      integer, intent(in) :: i                        !! counter, 0-based
      integer(i8), intent(in) :: value                !! new value
      call MPI_Fetch_and_op(value, old, MPI_INTEGER8, self%host, &
                            int(i, MPI_ADDRESS_KIND), MPI_REPLACE, self%win)
      call MPI_Win_flush(self%host, self%win)
   end function counter_swap

   !> Free the counters (collective; a synchronisation point of all ranks).
   subroutine counter_destroy(self)
      class(shared_counter_t), intent(inout) :: self  !! the counters
      if (.not. self%active) return
      call MPI_Win_unlock_all(self%win)
      call MPI_Win_free(self%win)
      self%active = .false.
   end subroutine counter_destroy
end module dpend_mpi_counter
