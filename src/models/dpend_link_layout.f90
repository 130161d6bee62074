!> The one output layout of the pendulum of N links (docs/hdf5-layout.md), written
!> alike by the double pendulum's own formulation and by the chain, damped, driven
!> or not:
!> - per link or joint i = 1..N, (x, y) each, as h5py shows them (samples, N, 2):
!>   F_joint (the force of body i−1 on body i at joint i, body 0 the ground), rC, vC,
!>   aC (the centre of mass of link i), rJ, vJ, aJ (the far end of link i: joint i+1,
!>   the tip for i = N); and rA, the pin A (samples, 2);
!> - for two links, the chapter's names (samples, 2) as aliases of the same values:
!>   F01 = F_joint[1], F21 = −F_joint[2] (link 2 on link 1 at B), rC1 = rC[1], …,
!>   rB = rJ[1].
!> Both models fill the values through `two_link_aliases` or `chain_from_aliases`, so
!> that each alias is the same number as its per-link value.
module dpend_link_layout
   use dpend_kinds, only: dp
   use dpend_strings, only: real_str
   implicit none
   private
   public :: n_link_out, link_out_name, link_out_units, link_out_text, link_out_rows
   public :: n_alias_out, alias_out_name, alias_out_units, alias_out_text
   public :: two_link_aliases, chain_from_aliases, rod_coordinate, rod_coordinates_text
   public :: rod_figure, body_text, link_output_info

   !> Outputs of every pendulum of N links: F_joint rC vC aC rJ vJ aJ (2N values
   !> each), then rA (2 values).
   integer, parameter :: n_link_out = 8
   character(len=7), parameter :: link_out_name(n_link_out) = &
      [character(len=7) :: 'F_joint', 'rC', 'vC', 'aC', 'rJ', 'vJ', 'aJ', 'rA']
   character(len=5), parameter :: link_out_units(n_link_out) = &
      [character(len=5) :: 'N', 'm', 'm/s', 'm/s^2', 'm', 'm/s', 'm/s^2', 'm']
   character(len=*), parameter :: link_out_text(n_link_out) = [character(len=80) :: &
      'force of body i-1 on body i at joint i (x, y), i = 1..N, body 0 the ground', &
      'position of the centre of mass of link i (x, y)', &
      'velocity of the centre of mass of link i (x, y)', &
      'acceleration of the centre of mass of link i (x, y)', &
      'position of the far end of link i: joint i+1, the tip for i = N (x, y)', &
      'velocity of the far end of link i (x, y)', &
      'acceleration of the far end of link i (x, y)', &
      'position of the pin A, the support (x, y)']
   !> Rows of each output as h5py shows it: N rows (samples, N, 2), or none
   !> (samples, 2) for rA.
   logical, parameter :: link_out_rows(n_link_out) = [.true., .true., .true., .true., &
                                                      .true., .true., .true., .false.]

   !> The two-link aliases (2 values each), in this order.
   integer, parameter :: n_alias_out = 9
   character(len=3), parameter :: alias_out_name(n_alias_out) = [character(len=3) :: &
      'F01', 'F21', 'rC1', 'vC1', 'aC1', 'rC2', 'vC2', 'aC2', 'rB']
   character(len=5), parameter :: alias_out_units(n_alias_out) = &
      [character(len=5) :: 'N', 'N', 'm', 'm/s', 'm/s^2', 'm', 'm/s', 'm/s^2', 'm']
   character(len=*), parameter :: alias_out_text(n_alias_out) = [character(len=48) :: &
      'force of the ground on link 1 at A (x, y)', &
      'force of link 2 on link 1 at B (x, y)', &
      'position of the centre of mass C1 (x, y)', &
      'velocity of C1 (x, y)', 'acceleration of C1 (x, y)', &
      'position of the centre of mass C2 (x, y)', &
      'velocity of C2 (x, y)', 'acceleration of C2 (x, y)', &
      'position of the joint B (x, y)']

contains

   !> The aliases (F01, F21, rC1, vC1, aC1, rC2, vC2, aC2, rB; 18 values) of a
   !> two-link sample in the per-link layout `w(:, link, k)` (k: F_joint rC vC aC rJ).
   pure subroutine two_link_aliases(w, alias)
      real(dp), intent(in) :: w(:, :, :)   !! (2, 2, >= 5): F_joint, rC, vC, aC, rJ, ...
      real(dp), intent(out) :: alias(18)   !! the aliases, 2 values each
      alias(1:2) = w(:, 1, 1); alias(3:4) = -w(:, 2, 1)
      alias(5:6) = w(:, 1, 2); alias(7:8) = w(:, 1, 3); alias(9:10) = w(:, 1, 4)
      alias(11:12) = w(:, 2, 2); alias(13:14) = w(:, 2, 3); alias(15:16) = w(:, 2, 4)
      alias(17:18) = w(:, 1, 5)
   end subroutine two_link_aliases

   !> The per-link layout (F_joint rC vC aC rJ vJ aJ, 28 values, (x, y) per link) of
   !> a double pendulum of uniform rods with a fixed pin from its aliases and the
   !> velocity and acceleration of B: the tip D is 2 C2 − B (C2 the rod's middle).
   !> The 'body' text of links other than uniform rods: 'point masses on
   !> massless rods (com_i = l_i [m], inertia_i = 0 [kg m^2])', or 'general bodies: com
   !> = 0.6, 0.8 m; inertia = 0.05, 0 kg m^2'; '' for rods.
   function body_text(rod, l, d, ic) result(text)
      logical, intent(in) :: rod          !! uniform rods
      real(dp), intent(in) :: l(:)        !! lengths [m]
      real(dp), intent(in) :: d(:)        !! joint to centre of mass [m]
      real(dp), intent(in) :: ic(:)       !! inertia about the centre of mass [kg m²]
      character(len=:), allocatable :: text
      integer :: i
      text = ''
      if (rod) return
      if (all(d == l) .and. all(ic == 0.0_dp)) then
         text = 'point masses on massless rods (com_i = l_i [m], inertia_i = 0 [kg m^2])'
         return
      end if
      text = 'general bodies: com = '
      do i = 1, size(d)
         text = text//real_str(d(i))//merge(', ', ' m', i < size(d))
      end do
      text = text//'; inertia = '
      do i = 1, size(ic)
         text = text//real_str(ic(i))
         if (i < size(ic)) text = text//', '
      end do
      text = text//' kg m^2'
   end function body_text

   pure subroutine chain_from_aliases(alias, vb, ab, values)
      real(dp), intent(in) :: alias(18)    !! F01 F21 rC1 vC1 aC1 rC2 vC2 aC2 rB
      real(dp), intent(in) :: vb(2), ab(2) !! velocity [m/s], acceleration [m/s²] of B
      real(dp), intent(out) :: values(28)  !! F_joint rC vC aC rJ vJ aJ, 4 values each
      values(1:2) = alias(1:2); values(3:4) = -alias(3:4)
      values(5:6) = alias(5:6); values(7:8) = alias(11:12)
      values(9:10) = alias(7:8); values(11:12) = alias(13:14)
      values(13:14) = alias(9:10); values(15:16) = alias(15:16)
      values(17:18) = alias(17:18); values(19:20) = 2.0_dp*alias(11:12) - alias(17:18)
      values(21:22) = vb; values(23:24) = 2.0_dp*alias(13:14) - vb
      values(25:26) = ab; values(27:28) = 2.0_dp*alias(15:16) - ab
   end subroutine chain_from_aliases

   !> Coordinate i of a chain of rods: the angle q_i [rad] of link i, its momentum
   !> [kg m²/s].
   pure subroutine rod_coordinate(i, name, units, momentum_units)
      integer, intent(in) :: i                                     !! link
      character(len=:), allocatable, intent(out) :: name, units, momentum_units
      character(len=12) :: digits
      write (digits, '(i0)') i
      name = 'q'//trim(digits); units = 'rad'; momentum_units = 'kg m^2/s'
   end subroutine rod_coordinate

   !> What q, q̇, q̈ of a chain of n rods hold.
   pure function rod_coordinates_text(n, order) result(text)
      integer, intent(in) :: n                      !! links
      integer, intent(in) :: order                  !! 0: q, 1: q̇, 2: q̈
      character(len=:), allocatable :: text
      character(len=12) :: digits
      write (digits, '(i0)') n
      select case (order)
      case (0)
         text = 'angles from the horizontal x axis, counter-clockwise, unwrapped (q1 .. q' &
                //trim(digits)//', one column per link)'
      case (1); text = 'angular velocities (qdot1 .. qdot'//trim(digits)//')'
      case default; text = 'angular accelerations (qddot1 .. qddot'//trim(digits)//')'
      end select
   end function rod_coordinates_text

   !> The figure of a chain of rods: from the pin rA through the link ends rJ, the
   !> joint forces F_joint acting at the start of each link.
   pure subroutine rod_figure(anchor, points, style, forces)
      character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      anchor = 'rA'; points = 'rJ'; style = 'rods'; forces = 'F_joint'
   end subroutine rod_figure
   !> Output i of the layout of a pendulum of n links: F_joint rC vC aC rJ vJ aJ (n
   !> rows) and rA, then the two-link aliases (`output_info` of the model interface).
   subroutine link_output_info(i, n, name, n_comp, units, description, rows)
      integer, intent(in) :: i                                   !! output
      integer, intent(in) :: n                                   !! links
      character(len=:), allocatable, intent(out) :: name         !! dataset name
      integer, intent(out) :: n_comp                             !! components per sample
      character(len=:), allocatable, intent(out) :: units        !! SI units
      character(len=:), allocatable, intent(out) :: description  !! one line
      integer, intent(out), optional :: rows                     !! vectors per sample
      integer :: r
      if (i <= n_link_out) then
         name = trim(link_out_name(i)); units = trim(link_out_units(i))
         description = trim(link_out_text(i))
         r = merge(n, 0, link_out_rows(i))
      else
         name = trim(alias_out_name(i - n_link_out))
         units = trim(alias_out_units(i - n_link_out))
         description = trim(alias_out_text(i - n_link_out))
         r = 0
      end if
      n_comp = 2*max(1, r)
      if (present(rows)) rows = r
   end subroutine link_output_info
end module dpend_link_layout
