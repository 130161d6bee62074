!> `dpend methods`: the integration methods of the registry (dpend_method_registry),
!> one row each: name, variables, order, properties, the commands that accept it,
!> then a line of description each; `--names`: the names on one line;
!> `--plot-styles`: the plot groups and the colour of each method, for
!> scripts/plot_study.sh. The entry point of the command is `methods_command`.
module dpend_methods_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, is_long_option, unknown_option_text, pad, to_str
   use dpend_method_registry, only: method_names, method_table, n_methods, plot_groups
   use dpend_command_common, only: take_quiet, data_quiet, refusal_line
   implicit none
   private
   public :: methods_command, methods_help

   character(len=*), parameter :: nl = new_line('a')

contains

   !> Help text of `dpend methods`.
   function methods_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend methods [--names | --plot-styles]'//nl &
          //nl//'The integration methods of --method: variables advanced ((q, qdot) or' &
          //nl//'canonical (q, p); (q, p)*: canonical on Hamiltonian models, (q, qdot)' &
          //nl//'on damped or driven ones), classical order, properties and the' &
          //nl//'commands that accept them, then one line of description each.'//nl &
          //'--names prints only the names, on one line (for scripts).'//nl &
          //'--plot-styles prints the study''s plot styles (for scripts), one record a' &
          //nl//'line, words separated by one blank:'//nl &
          //'  group ID TITLE...       a panel of the figures, in panel order'//nl &
          //'  method NAME #RRGGBB ID  a method, its colour and its group'//nl//data_quiet
   end function methods_help

   !> The entry point of `dpend methods [--names | --plot-styles]` (app/main.f90): the
   !> options in order (--help prints the help where it stands), then the form asked
   !> for on standard output. A refusal comes back as `error`, its message the one
   !> line 'dpend methods: ...'.
   subroutine methods_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `methods`
      type(error_t), allocatable, intent(out) :: error  !! the refusal
      type(arg_t), allocatable :: rest(:)
      character(len=:), allocatable :: mode
      integer :: i
      call take_quiet(args, rest)
      mode = 'table'
      do i = 1, size(rest)
         select case (rest(i)%s)
         case ('-h', '--help')
            write (output_unit, '(a)') methods_help()
            return
         case ('--names')
            mode = 'names'
         case ('--plot-styles')
            mode = 'styles'
         case default
            if (is_long_option(rest(i)%s)) then
               call fatal_error(error, unknown_option_text('methods', rest(i)%s, &
                                                           '--names --plot-styles --help'))
            else
               call fatal_error(error, "unexpected argument '"//rest(i)%s// &
                                "' (dpend methods --help)")
            end if
            call refusal_line(error, 'methods')
            return
         end select
      end do
      select case (mode)
      case ('names')
         write (output_unit, '(a)') method_names()
      case ('styles')
         call print_styles()
      case default
         call print_table()
      end select
   end subroutine methods_command

   !> `--plot-styles`: the plot groups in panel order, then each method's colour and
   !> group.
   subroutine print_styles()
      integer :: i
      do i = 1, size(plot_groups)
         write (output_unit, '(a)') 'group '//trim(plot_groups(i)%id)//' '// &
            trim(plot_groups(i)%title)
      end do
      do i = 1, n_methods
         associate (m => method_table(i))
            write (output_unit, '(a)') 'method '//trim(m%name)//' '//m%colour//' '// &
               trim(m%group)
         end associate
      end do
   end subroutine print_styles

   !> The table of the methods, its notes, then a line of description each.
   subroutine print_table()
      character(len=:), allocatable :: props, commands, variables
      character(len=*), parameter :: all = 'simulate lyapunov indicators divergence ' &
                                           //'poincare study'
      integer :: i
      write (output_unit, '(a)') 'method    variables  order  properties' &
         //'                        commands'
      do i = 1, n_methods
         associate (m => method_table(i))
            props = trim(merge('implicit', 'explicit', m%implicit))
            if (m%adaptive) props = props//', adaptive'
            if (m%symplectic) props = props//', symplectic'
            if (m%symmetric) props = props//', symmetric'
            commands = all
            ! fit integrates (q, qdot) (dpend_fit_config); sweep its batch rk4
            if (.not. m%canonical) commands = commands//' fit'
            if (m%name == 'rk4') commands = commands//' sweep'
            variables = '(q, qdot)'
            if (m%canonical) variables = trim(merge('(q, p) ', '(q, p)*', m%hamiltonian))
            write (output_unit, '(a)') m%name//pad(variables, 11)// &
               pad(to_str(m%order), 7)//pad(props, 34)//commands
         end associate
      end do
      write (output_unit, '(a)') nl//'* (q, p) on Hamiltonian models, (q, qdot) on ' &
         //'damped or driven ones (--damping,'//nl//'  --support-*), where they are ' &
         //'not symplectic; the other (q, p) methods refuse those.' &
         //nl//'sweep accepts only rk4: it integrates with its ' &
         //'own vectorised batch rk4 (dpend sweep --help).'//nl
      do i = 1, n_methods
         write (output_unit, '(a)') method_table(i)%name//trim(method_table(i)%description)
      end do
   end subroutine print_table
end module dpend_methods_command
