!> The one writer: every output file of every command (.h5, .md, figures) is made
!> through an `output_t`.
!>
!> `begin` checks the path before any computation and creates a temporary file
!> with a unique name in the target directory (the real writability check; no
!> fixed-name probe). The command writes the temporary file (`output%temp`) and
!> closes it, checking the close; `commit` then flushes it to the device and
!> moves it into place in one step:
!> - without `force`, the move fails if the target exists by then (RENAME_NOREPLACE,
!>   or a hard link), so two runs racing for one name never both succeed;
!> - with `force`, it replaces only a regular file (never a directory, device,
!>   FIFO or symbolic link).
!> The old file is never opened, truncated or changed: a process holding it open
!> keeps reading the old contents. A failure at any point removes the temporary
!> file (`discard`); a killed process leaves at most a `.NAME.tmp-XXXXXX` file
!> beside the target, never a damaged file at the target's name.
!>
!> An output never replaces an input. The command line program turns input
!> tracking on (`track_inputs`); then every input file a command reads is
!> registered (`register_input`, called where inputs are checked: config files,
!> --ic-file, trajectories, sweep files, fit CSVs), and `check_output_path` (so also
!> `begin`) refuses an output whose device and inode are those of a registered
!> input, with or without --force, whatever name reaches it (a hard link,
!> "./a.h5"). The library default is off, so that tests running many commands in
!> one process do not see each other's inputs.
module dpend_output
   use dpend_error, only: error_t, fatal_error
   use, intrinsic :: iso_fortran_env, only: int64
   use dpend_os, only: capturing_outputs, file_id, path_kind, path_missing, path_file, path_directory, path_link, &
                           directory_of, base_name, make_temp_file, sync_path, &
                           move_noreplace, move_replace, remove_file, errno_text, &
                           errno_exists, path_other
   implicit none
   private
   public :: output_t, check_output_path, track_inputs, register_input, clear_inputs
   public :: check_regular_file

   !> One input file of the running command: its name and identity.
   type :: input_t
      character(len=:), allocatable :: path  !! the name it was given by
      integer(int64) :: id(2) = -1           !! device, inode
   end type input_t

   logical, save :: tracking = .false.            !! register_input records inputs
   type(input_t), allocatable, save :: inputs(:)  !! the inputs registered so far
   integer, save :: n_inputs = 0                  !! used entries of `inputs`

   !> One output file on its way into place.
   type :: output_t
      character(len=:), allocatable :: target  !! the final path
      character(len=:), allocatable :: temp    !! the temporary file to write
      character(len=:), allocatable :: option  !! the option that named it (for messages)
      logical :: force = .false.               !! replace an existing regular file
      logical :: active = .false.              !! a temporary file exists
      !> a library call's output, captured in memory (`capture_outputs`): no
      !> temporary file, nothing moved or removed
      logical :: memory = .false.
   contains
      procedure :: begin => output_begin
      procedure :: commit => output_commit
      procedure :: discard => output_discard
      procedure :: explain => output_explain
   end type output_t

   integer, parameter :: max_name = 240  !! longest base name kept in a temporary name

contains

   !> Turn the registry of inputs on or off (off: `register_input` does nothing and
   !> the registry is emptied). The command line program turns it on.
   subroutine track_inputs(on)
      logical, intent(in) :: on  !! record inputs from now on
      tracking = on
      if (.not. on) call clear_inputs()
   end subroutine track_inputs

   !> Forget every registered input.
   subroutine clear_inputs()
      n_inputs = 0
      if (allocated(inputs)) deallocate (inputs)
   end subroutine clear_inputs

   !> Record `path` as an input of the running command (when tracking is on and
   !> the path can be examined; a missing input is refused by its reader).
   subroutine register_input(path)
      character(len=*), intent(in) :: path  !! an input file
      type(input_t), allocatable :: more(:)
      integer(int64) :: id(2)
      if (.not. tracking) return
      if (.not. file_id(path, id)) return
      if (.not. allocated(inputs)) allocate (inputs(8))
      if (n_inputs == size(inputs)) then
         allocate (more(2*n_inputs))
         more(1:n_inputs) = inputs
         call move_alloc(more, inputs)
      end if
      n_inputs = n_inputs + 1
      inputs(n_inputs)%path = path
      inputs(n_inputs)%id = id
   end subroutine register_input

   !> Refuse `target` when it is (device and inode) a registered input.
   subroutine check_not_input(target, opt, error)
      character(len=*), intent(in) :: target            !! the output path
      character(len=*), intent(in) :: opt               !! option, for the message
      type(error_t), allocatable, intent(out) :: error  !! it is an input
      integer(int64) :: id(2)
      integer :: i
      if (n_inputs == 0) return
      if (.not. file_id(target, id)) return
      do i = 1, n_inputs
         if (all(inputs(i)%id == id)) then
            call fatal_error(error, 'invalid '//opt//": '"//target//"' is the input '"// &
                             inputs(i)%path//"' of this command (an output never "// &
                             'replaces an input, with or without --force)')
            return
         end if
      end do
   end subroutine check_not_input

   !> Check `target` without creating anything: not a registered input (see the
   !> module's header), not empty, not a directory or a special file, not existing
   !> unless `force`, in an existing directory.
   subroutine check_output_path(target, force, error, option)
      character(len=*), intent(in) :: target            !! final path
      logical, intent(in) :: force                      !! replacing allowed
      type(error_t), allocatable, intent(out) :: error  !! why it cannot be written
      character(len=*), intent(in), optional :: option  !! e.g. '--output'
      character(len=:), allocatable :: opt, dir
      integer :: kind
      opt = '--output'
      if (present(option)) opt = option
      if (len_trim(target) == 0) then
         call fatal_error(error, 'invalid '//opt//': empty file name')
         return
      end if
      if (target(len(target):len(target)) == '/') then
         call fatal_error(error, 'invalid '//opt//": '"//target//"' names a directory")
         return
      end if
      kind = path_kind(target)
      if (kind == path_file .or. kind == path_link) then
         call check_not_input(target, opt, error)
         if (allocated(error)) return
      end if
      select case (kind)
      case (path_missing)
      case (path_file)
         if (.not. force) then
            call fatal_error(error, 'invalid '//opt//": '"//target// &
                             "' exists (use --force to overwrite)")
            return
         end if
      case (path_directory)
         call fatal_error(error, 'invalid '//opt//": '"//target//"' is a directory")
         return
      case (path_link)
         call fatal_error(error, 'invalid '//opt//": '"//target// &
                          "' is a symbolic link (dpend replaces only regular files)")
         return
      case default
         if (kind < 0) then
            call fatal_error(error, 'invalid '//opt//": cannot examine '"//target//"': "// &
                             errno_text(-kind))
         else
            call fatal_error(error, 'invalid '//opt//": '"//target// &
                             "' is not a regular file (a device, FIFO or socket; "// &
                             'dpend replaces only regular files)')
         end if
         return
      end select
      dir = directory_of(target)
      if (path_kind(dir) /= path_directory .and. path_kind(dir//'/.') /= path_directory) then
         call fatal_error(error, 'invalid '//opt//": directory '"//dir//"' does not exist")
      end if
   end subroutine check_output_path

   !> Check `target` (see `check_output_path`) and create the temporary file that
   !> the command will write. Call before any computation.
   subroutine output_begin(self, target, force, error, option)
      class(output_t), intent(inout) :: self            !! the output
      character(len=*), intent(in) :: target            !! final path
      logical, intent(in) :: force                      !! replace an existing file
      type(error_t), allocatable, intent(out) :: error  !! refused path (exit status 2)
      character(len=*), intent(in), optional :: option  !! e.g. '--output'
      character(len=:), allocatable :: dir, name, opt
      integer :: err
      call self%discard()
      self%memory = .false.
      opt = '--output'
      if (present(option)) opt = option
      if (capturing_outputs()) then   ! written in memory under its own name
         self%temp = target
         self%target = target
         self%option = opt
         self%memory = .true.
         self%active = .true.
         return
      end if
      call check_output_path(target, force, error, opt)
      if (allocated(error)) return
      dir = directory_of(target)
      name = base_name(target)
      if (len(name) > max_name) name = name(:max_name)
      err = make_temp_file(dir//'/.'//name//'.tmp-', self%temp)
      if (err /= 0) then
         call fatal_error(error, 'invalid '//opt//": directory '"//dir// &
                          "' is not writable ("//errno_text(err)//')')
         return
      end if
      self%target = target
      self%force = force
      self%option = opt
      self%active = .true.
   end subroutine output_begin

   !> Flush the (closed) temporary file to the device and move it into place.
   !> On failure the temporary file is removed and the target is as it was.
   subroutine output_commit(self, error)
      class(output_t), intent(inout) :: self            !! the output
      type(error_t), allocatable, intent(out) :: error  !! why it was not installed
      integer :: err
      if (.not. self%active) then
         call fatal_error(error, 'internal error: commit without begin')
         return
      end if
      if (self%memory) then   ! the image was kept when the file closed
         self%active = .false.
         return
      end if
      err = sync_path(self%temp)
      if (err /= 0) then
         call fatal_error(error, "cannot write '"//self%target//"': "//errno_text(err))
         call self%discard()
         return
      end if
      if (self%force) then
         call check_not_input(self%target, self%option, error)   ! named since begin?
         if (allocated(error)) then
            call self%discard()
            return
         end if
         select case (path_kind(self%target))
         case (path_missing, path_file)
            err = move_replace(self%temp, self%target)
         case default
            call fatal_error(error, "cannot write '"//self%target//"': it is no longer a "// &
                             'regular file (dpend replaces only regular files)')
            call self%discard()
            return
         end select
      else
         err = move_noreplace(self%temp, self%target)
         if (err == errno_exists) then
            call fatal_error(error, "cannot write '"//self%target//"': it was created by "// &
                             'another program during this run (use --force to overwrite)')
            call self%discard()
            return
         end if
      end if
      if (err /= 0) then
         call fatal_error(error, "cannot move the result into '"//self%target//"': "// &
                          errno_text(err))
         call self%discard()
         return
      end if
      self%active = .false.
      err = sync_path(directory_of(self%target))
   end subroutine output_commit

   !> Remove the temporary file, if any. The target is not touched.
   subroutine output_discard(self)
      class(output_t), intent(inout) :: self  !! the output
      integer :: err
      if (.not. self%active) return
      if (.not. self%memory) err = remove_file(self%temp)
      self%active = .false.
   end subroutine output_discard

   !> Say the target's name where a message names the temporary file (the user
   !> knows the file by its final name).
   subroutine output_explain(self, error)
      class(output_t), intent(in) :: self                 !! the output
      type(error_t), allocatable, intent(inout) :: error  !! message to rewrite, if any
      integer :: k, from
      if (.not. allocated(error) .or. .not. allocated(self%temp)) return
      if (len(self%temp) == 0) return
      from = 1   ! past the last name put in (a captured output's temp is its target)
      do
         k = index(error%message(from:), self%temp)
         if (k == 0) exit
         k = from + k - 1
         error%message = error%message(:k - 1)//self%target// &
                         error%message(k + len(self%temp):)
         from = k + len(self%target)
      end do
   end subroutine output_explain

   !> Refuse an input path that is not (a link to) a regular file, before anything
   !> opens it (a FIFO would block the open); messages start with `pre`.
   subroutine check_regular_file(filename, pre, error)
      character(len=*), intent(in) :: filename          !! the path
      character(len=*), intent(in) :: pre               !! message prefix
      type(error_t), allocatable, intent(out) :: error  !! not a regular file
      integer :: kind
      if (len_trim(filename) == 0) then
         call fatal_error(error, pre//'empty file name')
         return
      end if
      kind = path_kind(filename, follow=.true.)
      select case (kind)
      case (path_file)
         call register_input(filename)   ! an output never replaces it (dpend_output)
      case (path_missing)
         call fatal_error(error, pre//'no such file')
      case (path_directory)
         call fatal_error(error, pre//'is a directory, not a file')
      case (path_other)
         call fatal_error(error, pre//'is not a regular file (a FIFO, socket or device)')
      case default
         call fatal_error(error, pre//'cannot be examined: '//errno_text(-kind))
      end select
   end subroutine check_regular_file

end module dpend_output
