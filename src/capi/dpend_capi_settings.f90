!> A run's settings as an opaque handle of the C interface (dpend.h): a command and its
!> options given one by one, by name and value, then run. The options are kept as the
!> command line's words (`--t-end 1`) and checked, when the run starts, by the same
!> settings layer as the command line (`run_arguments`): the same refusals, word for
!> word, and an option given twice refused. Only the name's spelling is checked as it
!> is set.
module dpend_capi_settings
   use, intrinsic :: iso_c_binding, only: c_int, c_ptr, c_null_ptr, c_funptr, c_loc, &
      c_associated, c_f_pointer
   use dpend_cli, only: arg_t
   use dpend_capi, only: run_arguments
   use dpend_capi_result, only: c_string
   use dpend_strings, only: replace_char
   implicit none
   private
   public :: dpend_settings_new, dpend_settings_set, dpend_settings_run, dpend_settings_free

   integer(c_int), parameter :: kind_ok = 0, kind_refused = 2

   !> A command and the words of its options so far.
   type :: settings_t
      character(len=:), allocatable :: command
      type(arg_t), allocatable :: words(:)
      integer :: n = 0
   end type settings_t

contains

   !> New settings of `command` (e.g. "simulate"), without options.
   type(c_ptr) function dpend_settings_new(command) bind(C, name='dpend_settings_new')
      type(c_ptr), value :: command  !! const char *
      type(settings_t), pointer :: s
      allocate (s)
      s%command = c_string(command)
      allocate (s%words(16))
      dpend_settings_new = c_loc(s)
   end function dpend_settings_new

   !> Set an option: `name` as on the command line without its dashes, "t-end" or
   !> "t_end" (letters, digits, '-', '_', a letter first); `value` its text, NULL for a
   !> flag. A NULL or empty name gives a positional argument (fit's CSV file). 0, or
   !> 2 for a NULL handle, a misspelt name or a positional argument without a value.
   integer(c_int) function dpend_settings_set(settings, name, value) &
      bind(C, name='dpend_settings_set')
      type(c_ptr), value :: settings     !! the handle
      type(c_ptr), value :: name, value  !! const char *
      type(settings_t), pointer :: s
      character(len=:), allocatable :: key
      dpend_settings_set = kind_refused
      if (.not. c_associated(settings)) return
      call c_f_pointer(settings, s)
      key = c_string(name)
      if (len(key) == 0) then
         if (.not. c_associated(value)) return
         call add(s, c_string(value))
      else
         if (.not. option_name(key)) return
         call add(s, '--'//replace_char(key, '_', '-'))
         if (c_associated(value)) call add(s, c_string(value))
      end if
      dpend_settings_set = kind_ok
   end function dpend_settings_set

   !> Run the settings' command with its options: as `dpend_run_progress` (`fn` NULL:
   !> no progress callback). A NULL handle is refused (kind 2, no result).
   integer(c_int) function dpend_settings_run(settings, result, message, msg_len, fn, &
                                              user) bind(C, name='dpend_settings_run')
      type(c_ptr), value :: settings          !! the handle
      type(c_ptr), intent(out) :: result      !! void **: the result or NULL
      type(c_ptr), value :: message           !! char *
      integer(c_int), value :: msg_len        !! its size [B]
      type(c_funptr), value :: fn             !! the progress callback or NULL
      type(c_ptr), value :: user              !! handed to fn
      type(settings_t), pointer :: s
      result = c_null_ptr
      dpend_settings_run = kind_refused
      if (.not. c_associated(settings)) return
      call c_f_pointer(settings, s)
      dpend_settings_run = run_arguments(s%command, s%words(:s%n), result, message, &
                                         msg_len, fn, user)
   end function dpend_settings_run

   !> Release settings (NULL is ignored).
   subroutine dpend_settings_free(settings) bind(C, name='dpend_settings_free')
      type(c_ptr), value :: settings  !! the handle
      type(settings_t), pointer :: s
      if (.not. c_associated(settings)) return
      call c_f_pointer(settings, s)
      deallocate (s)
   end subroutine dpend_settings_free

   !> Append one word.
   subroutine add(s, word)
      type(settings_t), intent(inout) :: s
      character(len=*), intent(in) :: word
      type(arg_t), allocatable :: grown(:)
      if (s%n == size(s%words)) then
         allocate (grown(2*size(s%words)))
         grown(:s%n) = s%words(:s%n)
         call move_alloc(grown, s%words)
      end if
      s%n = s%n + 1
      s%words(s%n)%s = word
   end subroutine add

   !> A name of letters, digits, '-' and '_', a letter first.
   pure logical function option_name(key)
      character(len=*), intent(in) :: key
      integer :: i
      option_name = len(key) > 0
      do i = 1, len(key)
         select case (key(i:i))
         case ('a':'z', 'A':'Z')
         case ('0':'9', '-', '_')
            option_name = option_name .and. i > 1
         case default
            option_name = .false.
         end select
      end do
   end function option_name

end module dpend_capi_settings
