!> The model a file's numbers come from, as root attributes of the file: every
!> parameter under the name the model gives it (`parameter`: m1, l2, g, c1, com2, k, …)
!> and, for links other than uniform rods, the body's description (`body`). One writer
!> for the files of every command, so that the model can be rebuilt from any of them;
!> and the names and units of its coordinates for the datasets that hold them.
module dpend_model_record
   use dpend_kinds, only: dp
   use dpend_model, only: model_t
   use dpend_hdf5, only: h5file_t
   use dpend_joint_torque, only: joint_torque_t
   implicit none
   private
   public :: record_model, coordinate_labels, record_torques

contains

   !> Write the model's parameters and body as attributes of `group` (default '/').
   subroutine record_model(h5, model, group)
      type(h5file_t), intent(inout) :: h5              !! the open file
      class(model_t), intent(in) :: model              !! the model the run used
      character(len=*), intent(in), optional :: group  !! where ('/' if absent)
      character(len=:), allocatable :: where, name, units
      real(dp) :: value
      integer :: j
      where = '/'
      if (present(group)) where = group
      do j = 1, model%n_parameters()
         call model%parameter(j, name, value, units)
         call h5%writeattr(where, name, value)
      end do
      if (len(model%body_description()) > 0) &
         call h5%writeattr(where, 'body', model%body_description())
   end subroutine record_model

   !> The applied joint torques a run used, exactly: the root attributes `torque` (the
   !> form in words) and `torque_file` (when read from one), and a series' samples as
   !> /torque/sample_t [s] and /torque/sample_tau [N m]. Nothing without torques.
   subroutine record_torques(h5, torque, torque_file)
      type(h5file_t), intent(inout) :: h5                    !! the open file
      type(joint_torque_t), intent(in) :: torque             !! the torques applied
      character(len=:), allocatable, intent(in) :: torque_file  !! its file, if any
      if (.not. torque%active()) return
      call h5%writeattr('/', 'torque', torque%text())
      if (allocated(torque_file)) call h5%writeattr('/', 'torque_file', torque_file)
      if (.not. allocated(torque%t)) return
      call h5%write('/torque/sample_t', torque%t, units='s', description='sample ' &
                    //'times of the applied joint torques (linear between samples)')
      call h5%write('/torque/sample_tau', torque%tau, units='N m', description= &
                    'applied joint torques tau_1 .. tau_N at the sample times')
   end subroutine record_torques

   !> The labels of the coordinates' datasets from the model's description: the
   !> names ('q1 q2', 'r phi'), and the units of q, q̇, q̈ and p: one unit when every
   !> coordinate has the same, else one per column ('m, rad').
   subroutine coordinate_labels(model, names, q_units, rate_units, acc_units, p_units)
      class(model_t), intent(in) :: model                     !! the system
      character(len=:), allocatable, intent(out) :: names     !! blank-separated
      character(len=:), allocatable, intent(out) :: q_units, rate_units, acc_units, p_units
      character(len=:), allocatable :: name, u, pu, u1, pu1
      integer :: i
      logical :: same
      names = ''; q_units = ''; rate_units = ''; acc_units = ''; p_units = ''
      same = .true.
      do i = 1, model%n_dof()
         call model%coordinate(i, name, u, pu)
         if (i == 1) then
            u1 = u; pu1 = pu
         else
            names = names//' '; q_units = q_units//', '; rate_units = rate_units//', '
            acc_units = acc_units//', '; p_units = p_units//', '
            same = same .and. u == u1 .and. pu == pu1
         end if
         names = names//name; q_units = q_units//u; rate_units = rate_units//per_s(u, 1)
         acc_units = acc_units//per_s(u, 2); p_units = p_units//pu
      end do
      if (same) then
         q_units = u1; rate_units = per_s(u1, 1); acc_units = per_s(u1, 2); p_units = pu1
      end if
   contains
      pure function per_s(unit, k) result(t)
         character(len=*), intent(in) :: unit
         integer, intent(in) :: k
         character(len=:), allocatable :: t
         t = unit//'/s'
         if (k == 2) t = unit//'/s^2'
      end function per_s
   end subroutine coordinate_labels

end module dpend_model_record
