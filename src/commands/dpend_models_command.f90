!> `dpend models`: every model of the factory's catalogue (`describe_models`,
!> dpend_model_factory) with its coordinates, parameters (units, ranges, defaults)
!> and capabilities. The entry point of the command is `models_command`.
module dpend_models_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t
   use dpend_model_factory, only: describe_models
   use dpend_command_common, only: take_quiet, data_quiet, refusal_line
   implicit none
   private
   public :: models_command, models_help

   character(len=*), parameter :: nl = new_line('a')

contains

   !> Help text of `dpend models`.
   function models_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend models'//nl//nl// &
          'Lists every model dpend can build: its coordinates, its parameters (units,' &
          //nl//'accepted ranges, defaults) and what it supports.'//nl//data_quiet
   end function models_help

   !> The entry point of `dpend models` (app/main.f90): no options but --help. A
   !> refusal comes back as `error`, its message the one line 'dpend models: ...'.
   subroutine models_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `models`
      type(error_t), allocatable, intent(out) :: error  !! the refusal
      type(arg_t), allocatable :: rest(:)
      call take_quiet(args, rest)
      if (size(rest) == 0) then
         write (output_unit, '(a)') describe_models()
      else if (rest(1)%s == '--help' .or. rest(1)%s == '-h') then
         write (output_unit, '(a)') models_help()
      else
         call fatal_error(error, "unexpected argument '"//rest(1)%s// &
                          "' (dpend models takes no options)")
         call refusal_line(error, 'models')
      end if
   end subroutine models_command
end module dpend_models_command
