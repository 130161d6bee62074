!> `dpend sweep-compare`: two flip-time maps compared pixel by pixel, and the checks
!> of a sweep file read from elsewhere (hostile until checked: its configuration,
!> shapes, statuses and attributes) that the comparison and the agreement share.
module dpend_sweep_compare
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
      ieee_quiet_nan
   use dpend_limits, only: sci, max_sweep_points, max_axis_points, max_run_time => max_time, &
      in_range
   use dpend_model, only: max_dof
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_output, only: check_regular_file
   use dpend_lane_batch, only: st_cannot_flip, st_flipped
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_cli, only: to_str, real_str, printable
   implicit none
   private
   public :: compare_sweeps, open_sweep_file, check_sweep_data, config_value, config_difference, &
      pct

   !> sweep-compare: accepted --rel, stored time unit sqrt(l1/g) [s] and flip times [s]
   real(dp), parameter :: max_rel = 1000.0_dp, min_tau = 1e-150_dp, max_tau = 1e150_dp, &
                          max_time = 1e300_dp

contains

   ! ----------------------------------------------------------- compare ---

   !> Accuracy report: compare the flip times of two complete sweeps of the same
   !> initial conditions (e.g. step dt and dt/2). A pixel changes if it flips in one
   !> and not the other, or if |t_B - t_A| > rel t_A. Prints `key: value unit` lines.
   !> Sweeps that are not comparable (grid or list, shape, axes, ranges, initial
   !> states, parameters, time unit, t_end, stop rule) or not complete are refused,
   !> naming what differs, as are damaged values (a time unit sqrt(l1/g) or flip
   !> times that are not finite and in range).
   subroutine compare_sweeps(file_a, file_b, rel, unit, error)
      character(len=*), intent(in) :: file_a, file_b    !! the two sweeps
      real(dp), intent(in) :: rel                       !! relative tolerance
      integer, intent(in) :: unit                       !! where to print
      type(error_t), allocatable, intent(out) :: error  !! unreadable or mismatched
      real(dp), allocatable :: ta(:), tb(:)
      real(dp) :: tau, tau_b, ha, hb
      integer, allocatable :: sa(:), dims_a(:), dims_b(:)
      character(len=:), allocatable :: cfg_a, cfg_b, va
      ! what must be equal for two sweeps to hold the same initial conditions
      character(len=*), parameter :: same(*) = [character(len=10) :: 'initial', 'axis1', &
         'axis2', 'n1', 'n2', 'min1', 'max1', 'min2', 'max2', 'ic_count', 'ic_hash', 'q1', &
         'q2', 'w1', 'w2', 'm1', 'm2', 'l1', 'l2', 'g', 'time_unit', 't_end', 'stop_at', &
         'links', 'm', 'l', 'q', 'w']
      ! what may differ: the step and how the work was done (and the program's version)
      character(len=*), parameter :: free = ' program command method kernel dt h '// &
                                            'n_steps block stats '
      if (.not. (rel > 0.0_dp .and. rel <= max_rel)) then
         call fatal_error(error, 'sweep-compare: invalid --rel: '//sci(rel)// &
                          ' (accepted: > 0 and <= 1000)')
         return
      end if
      call read_flip_times(file_a, ta, sa, tau, ha, dims_a, cfg_a, error)
      if (allocated(error)) return
      call read_flip_times(file_b, tb, sa, tau_b, hb, dims_b, cfg_b, error)
      if (allocated(error)) return
      ! grid or list first (same(1)), then the shapes in the file's terms, then the rest
      va = config_difference(cfg_a, cfg_b, file_a, file_b, same(1:1))
      if (len(va) == 0) then
         if (size(dims_a) /= size(dims_b)) then
            call refuse('t_flip has shape '//shape_text(dims_a)//" in '"//file_a// &
                        "', "//shape_text(dims_b)//" in '"//file_b//"'")
         else if (any(dims_a /= dims_b)) then
            call refuse('t_flip has shape '//shape_text(dims_a)//" in '"//file_a// &
                        "', "//shape_text(dims_b)//" in '"//file_b//"'")
         end if
         if (allocated(error)) return
         va = config_difference(cfg_a, cfg_b, file_a, file_b, same, free)
      end if
      if (len(va) > 0) then
         call refuse(va)
         return
      end if
      if (abs(tau - tau_b) > 1e-12_dp*tau) then
         call refuse('sqrt_l1_over_g = '//sci(tau)//" s in '"//file_a//"', "// &
                     sci(tau_b)//" s in '"//file_b//"' (another time unit)")
         return
      end if
      call report_changes(ta, tb, tau, rel, ha, hb, config_value(cfg_a, 'time_unit') == 's', &
                          unit)
   contains
      subroutine refuse(what)
         character(len=*), intent(in) :: what
         call fatal_error(error, 'sweep-compare: invalid pair of sweeps, not comparable: '// &
                          what//' (compare sweeps of the same initial conditions)')
      end subroutine refuse
      function shape_text(d) result(s)
         integer, intent(in) :: d(:)
         character(len=:), allocatable :: s
         integer :: j
         s = to_str(d(1))
         do j = 2, size(d)
            s = s//'x'//to_str(d(j))
         end do
         if (size(d) == 1) s = s//' (a list)'
      end function shape_text
   end subroutine compare_sweeps

   !> sweep-compare: the flip times, statuses, time unit sqrt(l1/g) and step of a
   !> complete sweep file, its shape and configuration, checked (`check_sweep_data`,
   !> then completeness, statuses against the flip times, values in range).
   subroutine read_flip_times(file, t, st, tau, h, dims, config, error)
      character(len=*), intent(in) :: file                     !! the sweep file
      real(dp), allocatable, intent(out) :: t(:)               !! t_flip, flattened [s]
      integer, allocatable, intent(out) :: st(:)               !! status, flattened
      real(dp), intent(out) :: tau, h                          !! sqrt(l1/g), step [s]
      integer, allocatable, intent(out) :: dims(:)             !! shape of t_flip
      character(len=:), allocatable, intent(out) :: config     !! its configuration
      type(error_t), allocatable, intent(out) :: error         !! refused
      type(h5file_t) :: h5
      real(dp), allocatable :: t2(:, :)
      integer, allocatable :: s2(:, :), done(:)
      integer :: complete, j
      character(len=:), allocatable :: pre
      pre = "sweep-compare: invalid sweep '"//file//"': "
      tau = 1; h = 0; complete = 0
      call open_sweep_file(file, pre, h5, config, error)
      if (allocated(error)) return
      if (.not. h5%exists('/sweep/t_flip')) then   ! an indicator map, another model
         call h5%close()
         call fatal_error(error, pre//'it holds no flip-time map (/sweep/t_flip; '// &
                          'it is a map of '//map_kind(file)//'): sweep-compare compares ' &
                          //'two flip-time maps')
         return
      end if
      call check_sweep_data(h5, pre, config, '/sweep/t_flip', dims, error)
      if (allocated(error)) then
         call h5%close()
         return
      end if
      call h5%readattr('/sweep', 'complete', complete, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      if (.not. allocated(error)) then
         if (size(dims) == 2) then
            call h5%read('/sweep/t_flip', t2, error)
            if (.not. allocated(error)) call h5%read('/sweep/status', s2, error)
            if (.not. allocated(error)) t = reshape(t2, [size(t2)])
            if (.not. allocated(error)) st = reshape(s2, [size(s2)])
         else
            call h5%read('/sweep/t_flip', t, error)
            if (.not. allocated(error)) call h5%read('/sweep/status', st, error)
         end if
      end if
      if (.not. allocated(error)) call h5%readattr('/sweep', 'sqrt_l1_over_g', tau, error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'h', h, error)
      call h5%close()
      if (allocated(error)) then
         error%message = pre//error%message
      else if (complete /= 1 .or. any(done /= 1) .or. any(st == 0)) then
         call fatal_error(error, pre//'not complete ('//to_str(count(done == 1))// &
                          ' of '//to_str(size(done))//' blocks done; rerun the sweep '// &
                          'to finish it)')
      else if (size(st) /= size(t)) then
         call fatal_error(error, pre//'damaged: /sweep/status and /sweep/t_flip '// &
                          'differ in size')
      else if (.not. tau_ok(tau)) then
         call fatal_error(error, pre//'damaged: attribute sqrt_l1_over_g = '// &
                          sci(tau)//' (accepted: 1e-150 to 1e150 s)')
      else
         do j = 1, size(t)   ! element by element: an ordered comparison with NaN traps
            ! the status says whether the pixel flipped: t_flip agrees with it
            if ((st(j) == st_flipped .and. ieee_is_nan(t(j))) .or. &
                (st(j) == st_cannot_flip .and. .not. ieee_is_nan(t(j)))) then
               call fatal_error(error, pre//'damaged: /sweep/t_flip at pixel '// &
                                to_str(j)//' disagrees with its status '//to_str(st(j))// &
                                ' (2: flipped, a time; 3: cannot flip, NaN)')
               exit
            end if
            if (ieee_is_nan(t(j))) cycle
            if (.not. (ieee_is_finite(t(j)) .and. abs(t(j)) <= max_time)) then
               call fatal_error(error, pre//'damaged: /sweep/t_flip holds '// &
                                sci(t(j))//' (accepted: NaN or finite, |t| <= 1e300 s)')
               exit
            end if
         end do
      end if
   end subroutine read_flip_times

   !> Finite and in [min_tau, max_tau] (no ordered comparison with NaN: it traps).
   logical function tau_ok(x)
      real(dp), intent(in) :: x
      tau_ok = .false.
      if (ieee_is_finite(x)) tau_ok = x >= min_tau .and. x <= max_tau
   end function tau_ok

   !> sweep-compare's report: the pixels whose flip changes (|t_B - t_A| > rel t_A, or
   !> a flip in one only), in all and by band of t_A / sqrt(l1/g), as `key: value`.
   subroutine report_changes(ta, tb, tau, rel, ha, hb, seconds, unit)
      real(dp), intent(in) :: ta(:), tb(:)   !! flip times of A and B [s] (NaN: none)
      real(dp), intent(in) :: tau            !! sqrt(l1/g) [s]
      real(dp), intent(in) :: rel            !! relative tolerance
      logical, intent(in) :: seconds         !! the sweeps ran in s (else sqrt(l1/g)): first
      real(dp), intent(in) :: ha, hb         !! the two steps [s]
      integer, intent(in) :: unit            !! where to print
      real(dp) :: bands(5)
      integer :: i, k, n_changed, n_flip, band_n(4), band_c(4), n_noflip_changed
      logical :: fa, fb, changed, in_band
      character(len=*), parameter :: band_names(4) = [character(len=12) :: 'lt_10', &
                                                      '10_to_100', '100_to_1000', 'ge_1000']
      bands = [0.0_dp, 10.0_dp, 100.0_dp, 1000.0_dp, huge(1.0_dp)]
      n_changed = 0; n_flip = 0; band_n = 0; band_c = 0; n_noflip_changed = 0
      do i = 1, size(ta)
         fa = .not. ieee_is_nan(ta(i))
         fb = .not. ieee_is_nan(tb(i))
         if (fa .and. fb) then
            changed = abs(tb(i) - ta(i)) > rel*abs(ta(i))
         else
            changed = fa .neqv. fb
         end if
         if (fa .or. fb) n_flip = n_flip + 1
         if (changed) n_changed = n_changed + 1
         if (fa) then
            do k = 1, 4
               ! t/tau in [bands(k), bands(k+1)), without dividing by tau
               in_band = ta(i) >= bands(k)*tau
               if (k < 4) in_band = in_band .and. ta(i) < bands(k + 1)*tau
               if (in_band) then
                  band_n(k) = band_n(k) + 1
                  if (changed) band_c(k) = band_c(k) + 1
               end if
            end do
         else if (changed) then
            n_noflip_changed = n_noflip_changed + 1
         end if
      end do
      write (unit, '(a)') 'step_a: '//both(ha)
      write (unit, '(a)') 'step_b: '//both(hb)
      write (unit, '(a)') 'tflip_bands_unit: sqrt(l1/g) = '//real_str(tau, 6)//' s'
      write (unit, '(a)') 'relative_tolerance: '//real_str(rel)
      write (unit, '(a, i0)') 'pixels: ', size(ta)
      write (unit, '(a, i0)') 'pixels_flipping: ', n_flip
      write (unit, '(a, i0)') 'pixels_changed: ', n_changed
      write (unit, '(a)') 'changed_fraction: '//pct(n_changed, size(ta))//' %'
      write (unit, '(a)') 'changed_fraction_of_flipping: '//pct(n_changed, n_flip)//' %'
      do k = 1, 4
         write (unit, '(a, i0, a)') 'changed_fraction_tflip_'//trim(band_names(k))// &
            ': '//pct(band_c(k), band_n(k))//' % (of ', band_n(k), ' pixels)'
      end do
      write (unit, '(a, i0)') 'pixels_changed_no_flip_in_a: ', n_noflip_changed
      write (unit, '(a)') 'dpend sweep-compare: '//pct(n_changed, size(ta))//' % of the '// &
         to_str(size(ta))//' pixels change their flip time by more than '// &
         real_str(rel)//' relative ('//to_str(n_changed)//' pixels)'
   contains
      !> A time [s] in both units, the sweeps' own first.
      function both(t) result(b)
         real(dp), intent(in) :: t
         character(len=:), allocatable :: b
         if (seconds) then
            b = real_str(t, 6)//' s = '//real_str(t/tau, 6)//' sqrt(l1/g)'
         else
            b = real_str(t/tau, 6)//' sqrt(l1/g) = '//real_str(t, 6)//' s'
         end if
      end function both
   end subroutine report_changes

   !> 100 a/b rounded to 3 decimals ('0' when b = 0): the percentages of the reports.
   function pct(a, b) result(t)
      integer, intent(in) :: a, b
      character(len=:), allocatable :: t
      t = '0'
      if (b > 0) t = real_str(anint(1e5_dp*real(a, dp)/real(b, dp))/1e3_dp)
   end function pct

   !> What a sweep file without flip times maps: its indicator (/sweep/megno, ...)
   !> and the model, as far as the file says ('unknown quantities' otherwise).
   function map_kind(file) result(s)
      character(len=*), intent(in) :: file  !! a sweep file, open-able
      character(len=:), allocatable :: s
      type(h5file_t) :: h5
      type(error_t), allocatable :: error
      character(len=:), allocatable :: model
      character(len=*), parameter :: maps(4) = [character(len=5) :: 'megno', 'fli', &
                                                'sali', 'gali']
      integer :: i
      s = ''
      call h5%open(file, 'r', error)
      if (allocated(error)) then
         s = 'unknown quantities'
         return
      end if
      do i = 1, size(maps)
         if (h5%exists('/sweep/'//trim(maps(i)))) s = trim(maps(i))
         if (len(s) > 0) exit
      end do
      if (len(s) == 0) s = 'unknown quantities'
      if (h5%attr_exists('/sweep', 'model')) then
         call h5%readattr('/sweep', 'model', model, error)
         if (.not. allocated(error)) s = s//' of model '//printable(model)
      end if
      call h5%close()
   end function map_kind

   !> Open an existing sweep file for reading and read its /sweep config attribute;
   !> refused (with `pre` before the reason, h5 closed) unless it is a regular HDF5
   !> file with that attribute. Shared by sweep-compare and --agreement.
   subroutine open_sweep_file(file, pre, h5, config, error)
      character(len=*), intent(in) :: file                 !! the file
      character(len=*), intent(in) :: pre                  !! message prefix
      type(h5file_t), intent(inout) :: h5                  !! opened on success
      character(len=:), allocatable, intent(out) :: config !! /sweep@config
      type(error_t), allocatable, intent(out) :: error     !! refused
      call check_regular_file(file, pre, error)
      if (allocated(error)) return
      if (.not. is_hdf5(file)) then
         call fatal_error(error, pre//'not an HDF5 file')
         return
      end if
      call h5%open(file, 'r', error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'config', config, error)
      if (allocated(error)) then
         call h5%close()
         call fatal_error(error, pre//'not a dpend sweep file (no /sweep config)')
      end if
   end subroutine open_sweep_file

   !> Check the data of a sweep file from elsewhere against what sweep-compare
   !> assumes, not only its config attribute (`pre` before the reason): the grid
   !> (n1 × n2 with 1-D axes axis1, axis2 of n1 and n2 finite values) or list
   !> (ic_count points) that the config names, with `ref` (t_flip or an indicator)
   !> and status of that shape; status values 1 to 4 (0: not computed, left to the
   !> caller's completeness check); the attributes a sweep writes within its ranges:
   !> links 1..32 (and the config's links, if any), t_end finite within [0, 1e9] s
   !> (also in the config), h finite within (0, 1e9] s. `dims` is the shape of `ref`
   !> (Fortran order). The file stays open.
   subroutine check_sweep_data(h5, pre, config, ref, dims, error)
      type(h5file_t), intent(inout) :: h5               !! the open sweep file
      character(len=*), intent(in) :: pre               !! message prefix
      character(len=*), intent(in) :: config            !! its /sweep config attribute
      character(len=*), intent(in) :: ref               !! the dataset compared
      integer, allocatable, intent(out) :: dims(:)      !! shape of `ref`
      type(error_t), allocatable, intent(out) :: error  !! damaged
      integer, allocatable :: d(:), want(:)
      real(dp), allocatable :: ax(:)
      integer :: n1, n2, k
      character(len=:), allocatable :: initial
      logical :: ok
      character(len=2), parameter :: axes(2) = ['1', '2']
      call h5%shape(ref, dims, error)
      if (allocated(error)) then
         error%message = pre//error%message
         return
      end if
      initial = config_value(config, 'initial')
      select case (initial)
      case ('grid')
         call config_int('n1', max_axis_points, n1, ok)
         if (ok) call config_int('n2', max_axis_points, n2, ok)
         if (.not. ok) return
         want = [n1, n2]
         do k = 1, 2
            call h5%shape('/sweep/axis'//trim(axes(k)), d, error)
            if (allocated(error)) then
               error%message = pre//'damaged: '//error%message
               return
            end if
            if (size(d) /= 1) then
               call damaged('/sweep/axis'//trim(axes(k))//' is not 1-D')
               return
            else if (d(1) /= want(k)) then
               call damaged('/sweep/axis'//trim(axes(k))//' has '//to_str(d(1))// &
                            ' values, the config n'//trim(axes(k))//' = '//to_str(want(k)))
               return
            end if
            call h5%read('/sweep/axis'//trim(axes(k)), ax, error)
            if (allocated(error)) then
               error%message = pre//'damaged: '//error%message
               return
            end if
            if (.not. all(ieee_is_finite(ax))) then
               call damaged('/sweep/axis'//trim(axes(k))//' holds values that are not finite')
               return
            end if
         end do
      case ('list')
         call config_int('ic_count', max_sweep_points, n1, ok)
         if (.not. ok) return
         want = [n1]
      case default
         call damaged("config initial = '"//initial//"' (a sweep writes grid or list)")
         return
      end select
      if (size(dims) /= size(want)) then
         call damaged(ref//' has rank '//to_str(size(dims))//', the config '//initial// &
                      ' gives rank '//to_str(size(want)))
         return
      else if (any(dims /= want)) then
         call damaged(ref//' does not have the shape of the config '//initial)
         return
      end if
      call check_status_data(h5, pre, ref, dims, error)
      if (.not. allocated(error)) call check_sweep_attributes(h5, pre, config, error)
   contains
      subroutine damaged(why)
         character(len=*), intent(in) :: why
         call fatal_error(error, pre//'damaged: '//why)
      end subroutine damaged
      !> A count of the config in [1, hi]; refused otherwise.
      subroutine config_int(key, hi, n, good)
         character(len=*), intent(in) :: key
         integer, intent(in) :: hi
         integer, intent(out) :: n
         logical, intent(out) :: good
         character(len=:), allocatable :: v
         integer :: stat
         n = 0
         v = config_value(config, key)
         good = len(v) > 0 .and. len(v) <= 10 .and. verify(v, '0123456789') == 0
         if (good) then
            read (v, *, iostat=stat) n
            good = stat == 0 .and. n >= 1 .and. n <= hi
         end if
         if (.not. good) call damaged('config '//key//" = '"//v//"' (a sweep writes 1 to "// &
                                      to_str(hi)//')')
      end subroutine config_int
   end subroutine check_sweep_data

   !> `check_sweep_data`: /sweep/status has the shape `dims` of `ref` and holds 0 to 4.
   subroutine check_status_data(h5, pre, ref, dims, error)
      type(h5file_t), intent(inout) :: h5               !! the open sweep file
      character(len=*), intent(in) :: pre               !! message prefix
      character(len=*), intent(in) :: ref               !! the dataset compared
      integer, intent(in) :: dims(:)                    !! shape of `ref`
      type(error_t), allocatable, intent(out) :: error  !! damaged
      integer, allocatable :: d(:), st(:), st2(:, :)
      call h5%shape('/sweep/status', d, error)
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (size(d) /= size(dims)) then
         call fatal_error(error, pre//'damaged: '//'/sweep/status does not have the shape of '//ref)
         return
      else if (any(d /= dims)) then
         call fatal_error(error, pre//'damaged: '//'/sweep/status does not have the shape of '//ref)
         return
      end if
      if (size(dims) == 2) then
         call h5%read('/sweep/status', st2, error)
         if (.not. allocated(error)) st = reshape(st2, [size(st2)])
      else
         call h5%read('/sweep/status', st, error)
      end if
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (any(st < 0 .or. st > 4)) then
         call fatal_error(error, pre//'damaged: '//'/sweep/status holds '//to_str(minval(st, st < 0 .or. st > 4))// &
                      ' (a sweep writes 0 to 4)')
         return
      end if
   end subroutine check_status_data

   !> `check_sweep_data`: the attributes a sweep writes within its ranges: links
   !> 1..32 (and the config's links, if any), t_end finite within [0, 1e9] s (also in
   !> the config), h finite within (0, 1e9] s.
   subroutine check_sweep_attributes(h5, pre, config, error)
      type(h5file_t), intent(inout) :: h5               !! the open sweep file
      character(len=*), intent(in) :: pre               !! message prefix
      character(len=*), intent(in) :: config            !! its /sweep config attribute
      type(error_t), allocatable, intent(out) :: error  !! damaged
      real(dp) :: x
      integer :: links
      links = 2
      if (h5%attr_exists('/sweep', 'links')) call h5%readattr('/sweep', 'links', links, error)
      if (allocated(error)) then
         error%message = pre//'damaged: '//error%message
         return
      end if
      if (links < 1 .or. links > max_dof) then
         call fatal_error(error, pre//'damaged: '//'attribute links = '//to_str(links)//' (a sweep writes 1 to '// &
                      to_str(max_dof)//')')
         return
      end if
      if (len(config_value(config, 'links')) > 0) then
         if (config_value(config, 'links') /= to_str(links)) then
            call fatal_error(error, pre//'damaged: '//'config links = '//config_value(config, 'links')// &
                         ', attribute links = '//to_str(links))
            return
         end if
      end if
      call real_attr('t_end', 0.0_dp, max_run_time, .true.)
      if (.not. allocated(error)) call real_attr('h', tiny(1.0_dp), max_run_time, .true.)
      if (allocated(error)) return
      x = config_real('t_end')
      if (allocated(error)) return
      if (.not. in_range(x, 0.0_dp, max_run_time)) &
         call fatal_error(error, pre//'damaged: '//'config t_end = '//config_value(config, 't_end')// &
                      ' (a sweep writes 0 to 1e9)')
   contains
      !> A real of the config (NaN when it is not a number).
      real(dp) function config_real(key) result(v)
         character(len=*), intent(in) :: key
         integer :: stat
         character(len=:), allocatable :: text
         text = config_value(config, key)
         v = ieee_value(v, ieee_quiet_nan)
         if (len(text) == 0 .or. len(text) > 40 .or. &
             verify(text, '0123456789+-.eE') /= 0) return
         read (text, *, iostat=stat) v
         if (stat /= 0) v = ieee_value(v, ieee_quiet_nan)
      end function config_real
      !> The scalar real attribute `name` of /sweep, finite within [lo, hi].
      subroutine real_attr(name, lo, hi, required)
         character(len=*), intent(in) :: name
         real(dp), intent(in) :: lo, hi
         logical, intent(in) :: required
         real(dp) :: v
         if (.not. required .and. .not. h5%attr_exists('/sweep', name)) return
         call h5%readattr('/sweep', name, v, error)
         if (allocated(error)) then
            error%message = pre//'damaged: '//error%message
            return
         end if
         if (.not. in_range(v, lo, hi)) &
            call fatal_error(error, pre//'damaged: '//'attribute '//name//' = '//sci(v)//' s (a sweep writes '// &
                         trim(merge('0 to   ', 'above 0', lo <= 0.0_dp))//' ... '// &
                         sci(hi)//' s)')
      end subroutine real_attr
   end subroutine check_sweep_attributes

   !> The value of `key` in a configuration text of "key = value" lines ('' if absent).
   function config_value(text, key) result(v)
      character(len=*), intent(in) :: text  !! configuration text
      character(len=*), intent(in) :: key   !! key
      character(len=:), allocatable :: v
      character(len=1), parameter :: nl = new_line('a')
      character(len=:), allocatable :: probe
      integer :: at, eol
      v = ''
      probe = nl//text
      at = index(probe, nl//key//' = ')
      if (at == 0) return
      at = at + len(key) + 4
      eol = index(probe(at:), nl)
      if (eol == 0) then
         v = probe(at:)
      else
         v = probe(at:at + eol - 2)
      end if
   end function config_value

   !> The first difference between two sweeps' configurations (their /sweep config
   !> attributes): of the keys `keys` in their order, then of the model, then of every
   !> other key either file has (the bodies' com1 .., inertia1 .., another model's
   !> parameters: the elastic pendulum's k and l0, ...) except those of `free`, which
   !> may differ. As "KEY = VA in 'FILE_A', VB in 'FILE_B'" ('(not set: the default)'
   !> for a key one file lacks), or '' if they agree. Shared by the comparison and the agreement.
   function config_difference(cfg_a, cfg_b, file_a, file_b, keys, free) result(what)
      character(len=*), intent(in) :: cfg_a, cfg_b     !! the config attributes
      character(len=*), intent(in) :: file_a, file_b    !! their files (for the text)
      character(len=*), intent(in) :: keys(:)           !! keys that must agree, first
      !> ' key key ': may differ; absent: `keys` and the model only
      character(len=*), intent(in), optional :: free
      character(len=:), allocatable :: what
      integer :: i
      what = ''
      do i = 1, size(keys)
         if (differs(trim(keys(i)))) return
      end do
      if (differs('model')) return
      if (.not. present(free)) return
      if (walk(cfg_a)) return
      if (walk(cfg_b)) return
   contains
      !> Whether a key of `cfg` (one 'key = value' a line) outside `free` differs.
      logical function walk(cfg)
         character(len=*), intent(in) :: cfg
         integer :: start, eol, eq
         walk = .false.
         start = 1
         do while (start <= len(cfg))
            eol = index(cfg(start:), new_line('a'))
            if (eol == 0) eol = len(cfg) - start + 2
            eq = index(cfg(start:start + eol - 2), ' = ')
            if (eq > 1) then
               if (index(free, ' '//cfg(start:start + eq - 2)//' ') == 0) then
                  walk = differs(cfg(start:start + eq - 2))
                  if (walk) return
               end if
            end if
            start = start + eol
         end do
      end function walk
      !> Whether `key` differs; then its text in `what`.
      logical function differs(key)
         character(len=*), intent(in) :: key
         character(len=:), allocatable :: va, vb
         va = config_value(cfg_a, key)
         vb = config_value(cfg_b, key)
         differs = va /= vb
         if (.not. differs) return
         if (len(va) == 0) va = '(not set: the default)'
         if (len(vb) == 0) vb = '(not set: the default)'
         what = key//' = '//va//" in '"//file_a//"', "//vb//" in '"//file_b//"'"
         if (index(key, 'com') == 1 .or. index(key, 'inertia') == 1) &
            what = what//" (the links' bodies differ: uniform rods are the default, " &
                   //'--body point or --com, --inertia set them)'
      end function differs
   end function config_difference

end module dpend_sweep_compare
