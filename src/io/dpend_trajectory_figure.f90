!> The figure of a `dpend simulate` file, as the file describes it (root attributes
!> draw_anchor, draw_points, draw_style, draw_forces: docs/hdf5-layout.md): the
!> anchor, the chain of points drawn from it and the forces, sample by sample, and
!> their values at any time between the samples. Nothing here knows a model: a chain
!> of rods, a spring or any model that describes its figure is read alike.
!>
!> Files from before the description (a pendulum of `links` rods with the root
!> attribute `l`, or `l1`, `l2` for two links) are read as that chain: the points from
!> the angles q and the lengths, the forces F_joint (or F01 and −F21).
!>
!> Between samples every segment (from the anchor to point 1, from point i−1 to
!> point i) is interpolated in polar form: its length linearly and its direction by the
!> shorter turn, so that a rod keeps its length and a spring stretches smoothly.
module dpend_trajectory_figure
   use dpend_kinds, only: dp, pi
   use dpend_error, only: error_t, fatal_error
   use dpend_hdf5, only: h5file_t
   use dpend_strings, only: to_str, real_str
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: figure_track_t, read_figure, resample_figure, max_figure_coordinate
   public :: max_figure_force

   !> Largest |x|, |y| of a point accepted [m]: far beyond any pendulum (1e6 links of
   !> 1e6 m), small enough that the figure's arithmetic stays finite.
   real(dp), parameter :: max_figure_coordinate = 1e12_dp
   !> Smallest reach of a figure (largest |x|, |y| of its anchor and points) [m]: a
   !> link is at least 1e-6 m; a figure within 1e-9 m of the origin is damaged data
   !> (its scale of force arrows, N per m of the reach, would overflow).
   real(dp), parameter :: min_figure_reach = 1e-9_dp
   !> Largest force component drawn [N]: beyond, no arrow has a sensible scale.
   real(dp), parameter :: max_figure_force = 1e100_dp
   !> Most points or forces of one figure.
   integer, parameter :: max_figure_rows = 1000

   !> The figure of one file, per sample.
   type :: figure_track_t
      character(len=:), allocatable :: style      !! 'rods' or 'spring'
      integer :: n_points = 0                     !! points P after the anchor
      integer :: n_forces = 0                     !! forces K (0: none described)
      real(dp), allocatable :: t(:)               !! sample times (n) [s]
      real(dp), allocatable :: anchor(:, :)       !! (2, n) [m]
      real(dp), allocatable :: points(:, :, :)    !! (2, P, n) [m]
      real(dp), allocatable :: forces(:, :, :)    !! (2, K, n) [N]
   end type figure_track_t

contains

   !> Read the figure of the open simulate file `h5` (its times t already read and
   !> checked: finite and increasing). Refusals name what is wrong.
   subroutine read_figure(h5, t, tr, error)
      type(h5file_t), intent(inout) :: h5               !! the open file
      real(dp), intent(in) :: t(:)                      !! its sample times [s]
      type(figure_track_t), intent(out) :: tr           !! the figure
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      character(len=:), allocatable :: anchor, points, forces
      real(dp), allocatable :: a3(:, :, :)
      tr%t = t
      if (h5%attr_exists('/', 'draw_points')) then
         call h5%readattr('/', 'draw_anchor', anchor, error)
         if (.not. allocated(error)) call h5%readattr('/', 'draw_points', points, error)
         if (.not. allocated(error)) call h5%readattr('/', 'draw_style', tr%style, error)
         if (.not. allocated(error)) call h5%readattr('/', 'draw_forces', forces, error)
         if (allocated(error)) return
         call read_rows(h5, anchor, size(t), a3, error)
         if (.not. allocated(error)) then
            if (size(a3, 2) /= 1) then
               call fatal_error(error, 'the anchor /trajectory/'//anchor//' is not one point')
            else
               tr%anchor = a3(:, 1, :)
            end if
         end if
         if (.not. allocated(error)) call read_rows(h5, points, size(t), tr%points, error)
         if (.not. allocated(error) .and. len(forces) > 0) &
            call read_rows(h5, forces, size(t), tr%forces, error)
         if (allocated(error)) return
      else
         call legacy_rods(h5, size(t), tr, error)
         if (allocated(error)) return
      end if
      if (tr%style /= 'rods' .and. tr%style /= 'spring') then
         call fatal_error(error, "draw_style '"//tr%style//"' is not a style (accepted: " &
                          //'rods, spring)')
         return
      end if
      tr%n_points = size(tr%points, 2)
      if (.not. allocated(tr%forces)) allocate (tr%forces(2, 0, size(t)))
      tr%n_forces = size(tr%forces, 2)
      call check_values(tr, error)
   end subroutine read_figure

   !> Dataset /trajectory/`name` of (2, rows, n) values (or (2, n): one row), as
   !> (2, rows, n).
   subroutine read_rows(h5, name, n, v, error)
      type(h5file_t), intent(inout) :: h5               !! the open file
      character(len=*), intent(in) :: name              !! dataset name
      integer, intent(in) :: n                          !! samples
      real(dp), allocatable, intent(out) :: v(:, :, :)  !! the values (2, rows, n)
      type(error_t), allocatable, intent(out) :: error  !! missing, wrong shape
      integer, allocatable :: dims(:)
      real(dp), allocatable :: a2(:, :)
      if (verify(name, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') &
          /= 0 .or. len(name) == 0) then
         call fatal_error(error, "the figure names '"//name//"', not a dataset name")
         return
      end if
      if (.not. h5%exists('/trajectory/'//name)) then
         call fatal_error(error, 'the figure names /trajectory/'//name//', which is missing')
         return
      end if
      call h5%shape('/trajectory/'//name, dims, error)
      if (allocated(error)) return
      if (size(dims) == 2) then
         if (dims(1) /= 2 .or. dims(2) /= n) then
            call fatal_error(error, '/trajectory/'//name//' is not (samples, 2)')
            return
         end if
      else if (size(dims) == 3) then
         if (dims(1) /= 2 .or. dims(3) /= n .or. dims(2) < 1 .or. &
             dims(2) > max_figure_rows) then
            call fatal_error(error, '/trajectory/'//name//' is not (samples, rows, 2) with ' &
                             //'1 to '//to_str(max_figure_rows)//' rows')
            return
         end if
      else
         call fatal_error(error, '/trajectory/'//name//' has '//to_str(size(dims)) &
                          //' dimensions (a figure needs (samples, 2) or (samples, rows, 2))')
         return
      end if
      if (size(dims) == 2) then
         call h5%read('/trajectory/'//name, a2, error)
         if (.not. allocated(error)) v = reshape(a2, [2, 1, n])
      else
         call h5%read('/trajectory/'//name, v, error)
      end if
   end subroutine read_rows

   !> A file from before the description: the pendulum of `links` rods (2 without
   !> the attribute), its points from q and the lengths l (l1, l2 for two links), its
   !> forces F_joint, or F01 and −F21.
   subroutine legacy_rods(h5, n, tr, error)
      type(h5file_t), intent(inout) :: h5               !! the open file
      integer, intent(in) :: n                          !! samples
      type(figure_track_t), intent(inout) :: tr         !! the figure
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      real(dp), allocatable :: q(:, :), l(:), f01(:, :), f21(:, :)
      real(dp) :: l1, l2
      integer :: links, k, j
      tr%style = 'rods'
      links = 2
      if (h5%attr_exists('/', 'links')) call h5%readattr('/', 'links', links, error)
      if (allocated(error)) return
      if (links < 1 .or. links > max_figure_rows) then
         call fatal_error(error, 'links = '//to_str(links)//' (accepted: 1..' &
                          //to_str(max_figure_rows)//')')
         return
      end if
      if (h5%attr_exists('/', 'l')) then
         call h5%readattr('/', 'l', l, error)
      else
         call h5%readattr('/', 'l1', l1, error)
         if (.not. allocated(error)) call h5%readattr('/', 'l2', l2, error)
         if (.not. allocated(error)) l = [l1, l2]
      end if
      if (allocated(error)) return
      call h5%read('/trajectory/q', q, error)
      if (allocated(error)) return
      if (size(l) /= links .or. any(shape(q) /= [links, n])) then
         call fatal_error(error, '/trajectory/q or the lengths l do not match links = ' &
                          //to_str(links)//' and the samples')
         return
      end if
      do j = 1, links
         if (.not. (ieee_is_finite(l(j)) .and. l(j) >= 1e-6_dp .and. l(j) <= 1e6_dp)) then
            call fatal_error(error, 'link length l'//to_str(j)//' = '//real_str(l(j))// &
                             ' m (accepted: 1e-6..1e6 m)')
            return
         end if
      end do
      if (.not. all(ieee_is_finite(q)) .or. any(abs(q) > 1e6_dp)) then
         call fatal_error(error, '/trajectory/q holds angles that are not finite or ' &
                          //'beyond 1e6 rad')
         return
      end if
      allocate (tr%anchor(2, n), tr%points(2, links, n))
      tr%anchor = 0.0_dp
      do k = 1, n
         tr%points(:, 1, k) = l(1)*[cos(q(1, k)), sin(q(1, k))]
         do j = 2, links
            tr%points(:, j, k) = tr%points(:, j - 1, k) + l(j)*[cos(q(j, k)), sin(q(j, k))]
         end do
      end do
      if (h5%exists('/trajectory/F_joint')) then
         call read_rows(h5, 'F_joint', n, tr%forces, error)
      else if (links == 2 .and. h5%exists('/trajectory/F01')) then
         call h5%read('/trajectory/F01', f01, error)
         if (.not. allocated(error)) call h5%read('/trajectory/F21', f21, error)
         if (allocated(error)) return
         if (any(shape(f01) /= [2, n]) .or. any(shape(f21) /= [2, n])) then
            call fatal_error(error, '/trajectory/F01 or F21 is not (samples, 2)')
            return
         end if
         allocate (tr%forces(2, 2, n))
         tr%forces(:, 1, :) = f01
         tr%forces(:, 2, :) = -f21
      end if
   end subroutine legacy_rods

   !> Shapes agree with the samples; every value finite and within range.
   subroutine check_values(tr, error)
      type(figure_track_t), intent(in) :: tr            !! the figure
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      integer :: n
      n = size(tr%t)
      if (any(shape(tr%anchor) /= [2, n]) .or. size(tr%points, 3) /= n .or. &
          size(tr%forces, 3) /= n) then
         call fatal_error(error, 'the figure''s datasets and /trajectory/t differ in length')
      else if (.not. (all(ieee_is_finite(tr%anchor)) .and. all(ieee_is_finite(tr%points)))) &
         then
         call fatal_error(error, 'the figure''s points are not all finite')
      else if (any(abs(tr%anchor) > max_figure_coordinate) .or. &
               any(abs(tr%points) > max_figure_coordinate)) then
         call fatal_error(error, 'the figure''s points reach beyond ' &
                          //real_str(max_figure_coordinate)//' m')
      else if (max(maxval(abs(tr%anchor)), maxval(abs(tr%points))) < min_figure_reach) then
         call fatal_error(error, 'the figure''s points all lie within ' &
                          //real_str(min_figure_reach)//' m of the origin (a link is ' &
                          //'at least 1e-6 m)')
      else if (.not. all(ieee_is_finite(tr%forces))) then
         call fatal_error(error, 'the figure''s forces are not all finite')
      else if (any(abs(tr%forces) > max_figure_force)) then
         call fatal_error(error, 'the figure''s forces reach beyond ' &
                          //real_str(max_figure_force)//' N')
      end if
   end subroutine check_values

   !> The figure at times `tt` (increasing, within the samples' span): the anchor
   !> and forces linear in time, each segment's length linear and its direction turned
   !> by the shorter way between the samples.
   pure subroutine resample_figure(tr, tt, anchor, points, forces)
      type(figure_track_t), intent(in) :: tr                       !! samples
      real(dp), intent(in) :: tt(:)                                !! times [s]
      real(dp), intent(out) :: anchor(2, size(tt))                 !! [m]
      real(dp), intent(out) :: points(2, tr%n_points, size(tt))    !! [m]
      real(dp), intent(out) :: forces(2, tr%n_forces, size(tt))    !! [N]
      real(dp) :: w, d0(2), d1(2), a0, a1, da, r
      integer :: i, j, k, n
      n = size(tr%t)
      k = 1
      do i = 1, size(tt)
         do while (k < n - 1 .and. tr%t(min(k + 1, n)) < tt(i))
            k = k + 1
         end do
         if (n == 1) then
            anchor(:, i) = tr%anchor(:, 1)
            points(:, :, i) = tr%points(:, :, 1)
            forces(:, :, i) = tr%forces(:, :, 1)
            cycle
         end if
         w = 0.0_dp
         if (tr%t(k + 1) > tr%t(k)) w = (tt(i) - tr%t(k))/(tr%t(k + 1) - tr%t(k))
         w = min(1.0_dp, max(0.0_dp, w))
         anchor(:, i) = (1 - w)*tr%anchor(:, k) + w*tr%anchor(:, k + 1)
         forces(:, :, i) = (1 - w)*tr%forces(:, :, k) + w*tr%forces(:, :, k + 1)
         do j = 1, tr%n_points
            d0 = tr%points(:, j, k) - start(k, j)
            d1 = tr%points(:, j, k + 1) - start(k + 1, j)
            a0 = atan2(d0(2), d0(1)); a1 = atan2(d1(2), d1(1))
            da = modulo(a1 - a0 + pi, 2*pi) - pi
            r = (1 - w)*hypot(d0(1), d0(2)) + w*hypot(d1(1), d1(2))
            if (j == 1) then
               points(:, j, i) = anchor(:, i) + r*[cos(a0 + w*da), sin(a0 + w*da)]
            else
               points(:, j, i) = points(:, j - 1, i) + r*[cos(a0 + w*da), sin(a0 + w*da)]
            end if
         end do
      end do
   contains
      !> The start of segment j at sample k: the anchor or point j − 1.
      pure function start(k, j) result(p)
         integer, intent(in) :: k, j
         real(dp) :: p(2)
         if (j == 1) then
            p = tr%anchor(:, k)
         else
            p = tr%points(:, j - 1, k)
         end if
      end function start
   end subroutine resample_figure
end module dpend_trajectory_figure
