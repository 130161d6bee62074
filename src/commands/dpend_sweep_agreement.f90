!> `dpend sweep-compare A.h5 B.h5 --agreement`: classify every pixel of two
!> complete sweeps of the same initial conditions as regular or chaotic by their
!> indicators (e.g. MEGNO after a short run against λ1 after a ten times longer
!> one) and report how often the two classifications agree, printed as
!> `key: value` lines and stored in an HDF5 file (docs/sweep.md, "Indicators").
!>
!> Classification of a pixel by the indicator of its file (threshold x):
!>   megno    <Y>(t_end) > x chaotic (default 2.5: regular orbits tend to 2)
!>   lambda1  λ1 √(l1/g) > x chaotic, λ1 in units of the natural time (default 0.05)
!>   fli      ln |δ(t_end)| > x chaotic (no default: it depends on t_end)
!>   sali     SALI < x chaotic (default 1e-8)
!>   gali2    GALI_2 < x chaotic (default 1e-8)
!> A pixel whose value is NaN (not finite) is left out of the comparison.
!>
!> Without --agreement, two maps of one indicator (e.g. steps dt and dt/2) are
!> compared by `compare_indicator_maps`: their values pixel by pixel (a change by
!> more than a relative tolerance) and their regular/chaotic classes.
module dpend_sweep_agreement
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_hdf5, only: h5file_t
   use dpend_output, only: output_t
   use dpend_cli, only: to_str, real_str
   use dpend_limits, only: sci, in_range
   use dpend_sweep_compare, only: config_value, open_sweep_file, check_sweep_data, &
                                  config_difference, pct
   implicit none
   private
   public :: agreement_options_t, sweep_agreement, compare_indicator_maps, map_indicator

   !> Options of the agreement report.
   type :: agreement_options_t
      real(dp) :: threshold_a = 0.0_dp      !! threshold of file A's indicator
      real(dp) :: threshold_b = 0.0_dp      !! threshold of file B's indicator
      logical :: set_a = .false.            !! threshold_a given (else the default)
      logical :: set_b = .false.            !! threshold_b given (else the default)
      character(len=:), allocatable :: output  !! HDF5 file of the report ('': none)
      logical :: force = .false.            !! replace an existing output
   end type agreement_options_t

   !> One classified sweep.
   type :: classified_t
      character(len=:), allocatable :: file, config, indicator, dataset
      real(dp) :: threshold = 0.0_dp        !! in the indicator's unit (λ1: natural)
      logical :: above = .true.             !! chaotic above the threshold
      real(dp) :: tau = 1.0_dp              !! the natural time unit [s]
      character(len=:), allocatable :: tau_name  !! 'sqrt(l1/g)' (elastic: 'sqrt(l0/g)')
      real(dp) :: t_end = 0.0_dp            !! [s]
      real(dp) :: h = 0.0_dp                !! the step [s]
      logical :: classified = .true.        !! a threshold is known (FLI: given)
      integer, allocatable :: dims(:)       !! shape of the datasets
      real(dp), allocatable :: v(:)         !! the indicator's values as stored
      integer, allocatable :: cls(:)        !! 1 chaotic, 0 regular, -1 not classified
   end type classified_t

contains

   !> Classify the pixels of file_a and file_b, print the report on `unit` and
   !> store it in opt%output. Sweeps that are not comparable (other initial
   !> conditions, parameters or time unit), not complete, or without an indicator
   !> are refused.
   subroutine sweep_agreement(file_a, file_b, opt, unit, error)
      character(len=*), intent(in) :: file_a, file_b    !! the two sweeps
      type(agreement_options_t), intent(in) :: opt      !! thresholds, output
      integer, intent(in) :: unit                       !! where to print
      type(error_t), allocatable, intent(out) :: error  !! refused or I/O failure
      type(classified_t) :: a, b
      type(output_t) :: out
      integer :: counts(5)
      real(dp) :: fraction
      call classify_pair(file_a, file_b, opt, a, b, error)
      if (allocated(error)) return
      if (len(opt%output) > 0) then   ! a file only when asked for
         call out%begin(opt%output, opt%force, error)
         if (allocated(error)) then
            error%message = 'sweep-compare: '//error%message
            return
         end if
      end if
      call class_counts(a, b, counts, fraction)
      call print_agreement(unit, a, b, counts, fraction, opt%output)
      if (len(opt%output) == 0) return
      call store_agreement(out%temp, a, b, counts, fraction, error)
      if (.not. allocated(error)) call out%commit(error)
      call out%explain(error)
      call out%discard()
      if (allocated(error)) then   ! writing the agreement file failed: a failed run
         error%message = 'sweep-compare: '//error%message
         call run_failure(error)
      end if
   end subroutine sweep_agreement

   !> Read and classify two sweeps (`classify`) and check that they hold the same
   !> pixels: initial conditions, parameters, time unit and shapes (t_end, the step
   !> and the stop rule may differ). `values_only`: an indicator without a default
   !> threshold (FLI) is read unclassified instead of refused.
   subroutine classify_pair(file_a, file_b, opt, a, b, error, values_only)
      character(len=*), intent(in) :: file_a, file_b    !! the two sweeps
      type(agreement_options_t), intent(in) :: opt      !! thresholds
      type(classified_t), intent(out) :: a, b           !! their classifications
      type(error_t), allocatable, intent(out) :: error  !! refused
      logical, intent(in), optional :: values_only      !! see above
      character(len=:), allocatable :: va
      character(len=*), parameter :: same(*) = [character(len=10) :: 'initial', 'axis1', &
         'axis2', 'n1', 'n2', 'min1', 'max1', 'min2', 'max2', 'ic_count', 'ic_hash', 'q1', &
         'q2', 'w1', 'w2', 'm1', 'm2', 'l1', 'l2', 'g', 'time_unit', 'links', 'm', 'l', 'q', &
         'w']
      ! what may differ: the step, the horizon and the indicator, how the work was done
      character(len=*), parameter :: free = ' program command method kernel dt h '// &
         'n_steps block stats t_end stop_at lyapunov indicator '
      call classify(file_a, opt%set_a, opt%threshold_a, a, error, values_only)
      if (allocated(error)) return
      call classify(file_b, opt%set_b, opt%threshold_b, b, error, values_only)
      if (allocated(error)) return
      va = config_difference(a%config, b%config, file_a, file_b, same, free)
      if (len(va) > 0) then
         call refuse(va)
         return
      end if
      if (size(a%dims) /= size(b%dims)) then
         call refuse('the datasets have other shapes')
      else if (any(a%dims /= b%dims)) then
         call refuse('the datasets have other shapes')
      end if
   contains
      subroutine refuse(what)
         character(len=*), intent(in) :: what
         call fatal_error(error, 'sweep-compare: invalid pair of sweeps, not comparable: '// &
                          what//' (compare sweeps of the same initial conditions)')
      end subroutine refuse
   end subroutine classify_pair

   !> The class counts of two classifications of the same pixels: (pixels classified
   !> in both, both regular, both chaotic, chaotic only in A, only in B) and the
   !> fraction of the classified pixels where they agree (0 if none).
   pure subroutine class_counts(a, b, counts, fraction)
      type(classified_t), intent(in) :: a, b   !! the two classifications
      integer, intent(out) :: counts(5)        !! see above
      real(dp), intent(out) :: fraction        !! agreement
      counts(1) = count(a%cls >= 0 .and. b%cls >= 0)
      counts(2) = count(a%cls == 0 .and. b%cls == 0)
      counts(3) = count(a%cls == 1 .and. b%cls == 1)
      counts(4) = count(a%cls == 1 .and. b%cls == 0)
      counts(5) = count(a%cls == 0 .and. b%cls == 1)
      fraction = 0.0_dp
      if (counts(1) > 0) fraction = real(counts(2) + counts(3), dp)/real(counts(1), dp)
   end subroutine class_counts

   !> The indicator a sweep file maps ('megno', 'lambda1', 'fli', 'sali', 'gali2'),
   !> by its configuration; '' for a flip-time map or a file that is not a readable
   !> sweep (its checks are left to the comparison that reads it).
   function map_indicator(file) result(indicator)
      character(len=*), intent(in) :: file   !! a sweep file
      character(len=:), allocatable :: indicator
      type(h5file_t) :: h5
      type(error_t), allocatable :: error
      character(len=:), allocatable :: config
      indicator = ''
      call open_sweep_file(file, '', h5, config, error)
      if (allocated(error)) return
      call h5%close()
      indicator = config_value(config, 'indicator')
      if (indicator == 'flip') indicator = ''
      if (len(indicator) == 0 .and. config_value(config, 'lyapunov') == 'true') &
         indicator = 'lambda1'
   end function map_indicator

   !> sweep-compare of two maps of one indicator (e.g. steps dt and dt/2, same t_end):
   !> the pixels whose value changes by more than `rel` relative (|v_B - v_A| > rel
   !> |v_A|, or finite in one only) and the regular/chaotic classes by the default
   !> thresholds (FLI: none), printed as `key: value` lines ending in a summary.
   !> SALI and GALI_2 fall to round-off on chaotic orbits: their values are compared
   !> where both maps call the pixel regular.
   subroutine compare_indicator_maps(file_a, file_b, rel, unit, error)
      character(len=*), intent(in) :: file_a, file_b    !! the two sweeps
      real(dp), intent(in) :: rel                       !! relative tolerance
      integer, intent(in) :: unit                       !! where to print
      type(error_t), allocatable, intent(out) :: error  !! refused
      type(agreement_options_t) :: opt
      type(classified_t) :: a, b
      integer :: counts(5), j, n_cmp, n_changed
      real(dp) :: fraction, largest, change
      logical :: fa, fb, compare_here
      character(len=:), allocatable :: summary
      character(len=:), allocatable :: ind_a, ind_b
      ind_a = map_indicator(file_a)
      ind_b = map_indicator(file_b)
      if (ind_a /= ind_b .and. len(ind_a) > 0 .and. len(ind_b) > 0) then
         call fatal_error(error, "sweep-compare: invalid pair of maps: '"//file_a// &
                          "' maps "//ind_a//", '"//file_b//"' maps "//ind_b// &
                          ' (the values of one indicator are compared; --agreement ' &
                          //'compares the regular/chaotic classes of two)')
         return
      else if (ind_a /= ind_b) then
         call fatal_error(error, "sweep-compare: invalid pair of maps: '"//file_a// &
                          "' maps "//map_name(ind_a)//", '"//file_b//"' maps "// &
                          map_name(ind_b)//' (compare two maps of one quantity)')
         return
      end if
      call classify_pair(file_a, file_b, opt, a, b, error, values_only=.true.)
      if (allocated(error)) return
      if (abs(a%t_end - b%t_end) > 1e-12_dp*a%t_end) then
         call fatal_error(error, 'sweep-compare: invalid pair of maps: t_end = '// &
                          real_str(a%t_end, 6)//" s in '"//file_a//"', "// &
                          real_str(b%t_end, 6)//" s in '"//file_b//"' (an indicator " &
                          //'depends on t_end: --agreement compares the classes)')
         return
      end if
      n_cmp = 0; n_changed = 0; largest = 0.0_dp
      do j = 1, size(a%v)   ! element by element: an ordered comparison with NaN traps
         fa = .not. ieee_is_nan(a%v(j))
         fb = .not. ieee_is_nan(b%v(j))
         compare_here = fa .or. fb
         if (a%indicator == 'sali' .or. a%indicator == 'gali2') &
            compare_here = a%cls(j) == 0 .and. b%cls(j) == 0
         if (.not. compare_here) cycle
         n_cmp = n_cmp + 1
         if (fa .and. fb) then
            change = abs(b%v(j) - a%v(j))
            if (change > rel*abs(a%v(j))) n_changed = n_changed + 1
            if (abs(a%v(j)) > 0.0_dp) largest = max(largest, change/abs(a%v(j)))
         else
            n_changed = n_changed + 1
         end if
      end do
      write (unit, '(a)') 'indicator: '//a%indicator//' ('//trim(value_name(a%indicator))//')'
      ! the times in the unit the sweeps were run in first (/sweep@time_unit), then the other
      write (unit, '(a)') 'step_a: '//times_text(a, a%h)
      write (unit, '(a)') 'step_b: '//times_text(b, b%h)
      write (unit, '(a)') 't_end: '//times_text(a, a%t_end)
      write (unit, '(a)') 'relative_tolerance: '//real_str(rel)
      write (unit, '(a, i0)') 'pixels: ', size(a%v)
      write (unit, '(a, i0)') 'pixels_compared: ', n_cmp
      write (unit, '(a, i0)') 'pixels_changed: ', n_changed
      write (unit, '(a)') 'changed_fraction: '//pct(n_changed, n_cmp)//' %'
      write (unit, '(a)') 'largest_relative_change: '//real_str(largest, 3)
      summary = 'dpend sweep-compare: '//trim(value_name(a%indicator))//' changes by more '// &
                'than '//real_str(rel)//' relative at '//pct(n_changed, n_cmp)// &
                ' % of the '//to_str(n_cmp)//' pixels compared'
      if (a%classified) then
         call class_counts(a, b, counts, fraction)
         write (unit, '(a)') 'class: chaotic '//trim(merge('above', 'below', a%above))// &
            ' '//real_str(a%threshold)//trim(merge(' per sqrt(l1/g)', '               ', &
            a%indicator == 'lambda1'))
         call print_counts(unit, counts, fraction)
         summary = summary//'; the regular/chaotic classes agree on '// &
                   real_str(anint(1e5_dp*fraction)/1e3_dp)//' %'
      end if
      write (unit, '(a)') summary
   contains
      function map_name(indicator) result(t)
         character(len=*), intent(in) :: indicator
         character(len=:), allocatable :: t
         t = indicator
         if (len(t) == 0) t = 'flip times'
      end function map_name
   end subroutine compare_indicator_maps

   !> What the values of an indicator's map are, in words.
   pure function value_name(indicator) result(s)
      character(len=*), intent(in) :: indicator  !! megno, lambda1, fli, sali, gali2
      character(len=:), allocatable :: s
      select case (indicator)
      case ('megno'); s = 'MEGNO <Y>'
      case ('lambda1'); s = 'lambda1'
      case ('fli'); s = 'FLI ln |d|'
      case ('sali'); s = 'SALI'
      case default; s = 'GALI_2'
      end select
   end function value_name

   !> The agreement report as `key: value` lines on unit u; counts = (pixels
   !> classified, both regular, both chaotic, chaotic only in A, only in B).
   subroutine print_agreement(u, a, b, counts, fraction, output)
      integer, intent(in) :: u                     !! where to print
      type(classified_t), intent(in) :: a, b       !! the two classifications
      integer, intent(in) :: counts(5)             !! see above
      real(dp), intent(in) :: fraction             !! (both regular + both chaotic)/classified
      character(len=*), intent(in) :: output       !! the report's HDF5 file ('': none)
      character(len=:), allocatable :: stored
      call line(a, 'a')
      call line(b, 'b')
      write (u, '(a, i0)') 'pixels: ', size(a%cls)
      call print_counts(u, counts, fraction)
      if (len(output) > 0) write (u, '(a)') 'stored: '//output
      stored = ''
      if (len(output) > 0) stored = '; stored in '//output
      write (u, '(a)') 'dpend sweep-compare: the regular/chaotic classes agree on '// &
         real_str(anint(1e5_dp*fraction)/1e3_dp)//' % of the '//to_str(counts(1))// &
         ' pixels classified'//stored
   contains
      subroutine line(c, s)
         type(classified_t), intent(in) :: c
         character(len=1), intent(in) :: s
         character(len=:), allocatable :: per
         per = ''
         if (c%indicator == 'lambda1') per = ' per sqrt(l1/g)'
         write (u, '(a)') 'indicator_'//s//': '//c%indicator//' (chaotic '// &
            trim(merge('above', 'below', c%above))//' '//real_str(c%threshold)//per//')'
         write (u, '(a)') 't_end_'//s//': '//times_text(c, c%t_end)
      end subroutine line
   end subroutine print_agreement

   !> A time [s] of sweep c in both units, the one it was run in first (the config's
   !> time_unit; natural when it is not 's'): '20 sqrt(l1/g) = 6.38877 s'.
   function times_text(c, t) result(s)
      type(classified_t), intent(in) :: c  !! the sweep
      real(dp), intent(in) :: t            !! the time [s]
      character(len=:), allocatable :: s
      if (config_value(c%config, 'time_unit') == 's') then
         s = real_str(t, 6)//' s = '//real_str(t/c%tau, 6)//' '//c%tau_name
      else
         s = real_str(t/c%tau, 6)//' '//c%tau_name//' = '//real_str(t, 6)//' s'
      end if
   end function times_text

   !> The class counts as `key: value` lines (see print_agreement) and the agreement.
   subroutine print_counts(u, counts, fraction)
      integer, intent(in) :: u               !! where to print
      integer, intent(in) :: counts(5)       !! classified, both regular, both chaotic,
                                             !! chaotic only in A, only in B
      real(dp), intent(in) :: fraction       !! agreement
      write (u, '(a, i0)') 'pixels_classified: ', counts(1)
      write (u, '(a, i0)') 'both_regular: ', counts(2)
      write (u, '(a, i0)') 'both_chaotic: ', counts(3)
      write (u, '(a, i0)') 'chaotic_only_a: ', counts(4)
      write (u, '(a, i0)') 'chaotic_only_b: ', counts(5)
      write (u, '(a)') 'agreement: '//real_str(anint(1e5_dp*fraction)/1e3_dp)//' %'
   end subroutine print_counts

   !> Write the agreement file `path` (the writer's temporary file): both
   !> classifications (/agreement/class_a, class_b) and the counts as attributes.
   subroutine store_agreement(path, a, b, counts, fraction, error)
      character(len=*), intent(in) :: path              !! file to create
      type(classified_t), intent(in) :: a, b            !! the two classifications
      integer, intent(in) :: counts(5)                  !! as print_agreement
      real(dp), intent(in) :: fraction                  !! the agreement
      type(error_t), allocatable, intent(out) :: error  !! I/O failure
      type(h5file_t) :: h5
      call h5%open(path, 'w', error)
      if (allocated(error)) return
      call store(a, 'a')
      call store(b, 'b')
      call h5%writeattr('/', 'program', 'dpend sweep-compare --agreement')
      call h5%writeattr('/agreement', 'pixels', size(a%cls))
      call h5%writeattr('/agreement', 'pixels_classified', counts(1))
      call h5%writeattr('/agreement', 'both_regular', counts(2))
      call h5%writeattr('/agreement', 'both_chaotic', counts(3))
      call h5%writeattr('/agreement', 'chaotic_only_a', counts(4))
      call h5%writeattr('/agreement', 'chaotic_only_b', counts(5))
      call h5%writeattr('/agreement', 'agreement', fraction)
      call h5%take_error(error)
      if (allocated(error)) then
         call h5%close()
      else
         call h5%close(error)
      end if
   contains
      subroutine store(c, s)
         type(classified_t), intent(in) :: c
         character(len=1), intent(in) :: s
         character(len=*), parameter :: text = '1 chaotic, 0 regular, -1 not classified '// &
                                         '(value not finite)'
         integer, allocatable :: m2(:, :)
         if (size(c%dims) == 2) then
            m2 = reshape(c%cls, [c%dims(1), c%dims(2)])
            call h5%write('/agreement/class_'//s, m2, units='1', &
                          description=text//' by file '//s)
         else
            call h5%write('/agreement/class_'//s, c%cls, units='1', &
                          description=text//' by file '//s)
         end if
         call h5%writeattr('/agreement', 'file_'//s, c%file)
         call h5%writeattr('/agreement', 'indicator_'//s, c%indicator)
         call h5%writeattr('/agreement', 'threshold_'//s, c%threshold)
         call h5%writeattr('/agreement', 'chaotic_'//s, merge('above', 'below', c%above))
         call h5%writeattr('/agreement', 't_end_'//s, c%t_end)
         call h5%writeattr('/agreement', 't_end_natural_'//s, c%t_end/c%tau)
         call h5%writeattr('/agreement', 'sqrt_l1_over_g_'//s, c%tau)
      end subroutine store
   end subroutine store_agreement

   !> Read a complete sweep file and classify its pixels by its indicator.
   subroutine classify(file, set, threshold, c, error, values_only)
      character(len=*), intent(in) :: file              !! sweep file
      logical, intent(in) :: set                        !! threshold given
      real(dp), intent(in) :: threshold                 !! the given threshold
      type(classified_t), intent(out) :: c              !! the classification
      type(error_t), allocatable, intent(out) :: error  !! refused
      logical, intent(in), optional :: values_only      !! FLI without threshold: unclassified
      type(h5file_t) :: h5
      real(dp), allocatable :: v(:), v2(:, :)
      integer, allocatable :: done(:)
      integer :: complete, j
      character(len=:), allocatable :: pre
      pre = "sweep-compare: invalid sweep '"//file//"': "
      c%file = file
      complete = 0
      call open_sweep_file(file, pre, h5, c%config, error)
      if (allocated(error)) return
      call choose_indicator(file, pre, set, threshold, c, error, values_only)
      if (allocated(error)) then
         call h5%close()
         return
      end if
      call check_sweep_data(h5, pre, c%config, c%dataset, c%dims, error)
      if (allocated(error)) then
         call h5%close()
         return
      end if
      call h5%readattr('/sweep', 'complete', complete, error)
      if (.not. allocated(error)) call h5%read('/sweep/done', done, error)
      c%tau_name = 'sqrt(l1/g)'   ! a model without flips: its own unit (elastic: l0)
      if (.not. h5%attr_exists('/sweep', 'sqrt_l1_over_g') .and. &
          h5%attr_exists('/sweep', 'sqrt_l0_over_g')) c%tau_name = 'sqrt(l0/g)'
      if (.not. allocated(error)) call h5%readattr('/sweep', 'sqrt_'//c%tau_name(6:7)// &
                                                   '_over_g', c%tau, error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 't_end', c%t_end, error)
      if (.not. allocated(error)) call h5%readattr('/sweep', 'h', c%h, error)
      if (.not. allocated(error)) then
         if (size(c%dims) == 2) then
            call h5%read(c%dataset, v2, error)
            if (.not. allocated(error)) v = reshape(v2, [size(v2)])
            if (.not. allocated(error)) c%dims = shape(v2)   ! Fortran order
         else
            call h5%read(c%dataset, v, error)
         end if
      end if
      call h5%close()
      if (allocated(error)) then
         error%message = pre//error%message
         return
      end if
      if (complete /= 1 .or. any(done /= 1)) then
         call fatal_error(error, pre//'not complete ('//to_str(count(done == 1))//' of '// &
                          to_str(size(done))//' blocks done; rerun the sweep to finish it)')
         return
      end if
      ! the ranges a sweep can write (l1, g within [1e-6, 1e6]: sqrt(l1/g) within
      ! [1e-6, 1e6] s; t_end at most 1e9 s): beyond, the file is damaged
      if (.not. in_range(c%tau, 1e-6_dp, 1e6_dp)) then
         call fatal_error(error, pre//'damaged: attribute sqrt_'//c%tau_name(6:7)// &
                          '_over_g = '//sci(c%tau)// &
                          ' s (a sweep writes 1e-6 to 1e6)')
         return
      end if
      if (.not. in_range(c%t_end, 0.0_dp, 1e9_dp)) then
         call fatal_error(error, pre//'damaged: attribute t_end = '//sci(c%t_end)// &
                          ' s (a sweep writes 0 to 1e9)')
         return
      end if
      if (.not. in_range(c%h, 0.0_dp, 1e9_dp)) then
         call fatal_error(error, pre//'damaged: attribute h = '//sci(c%h)// &
                          ' s (a sweep writes 0 to 1e9)')
         return
      end if
      call check_values(c, v, pre, error)
      if (allocated(error)) return
      c%v = v
      allocate (c%cls(size(v)))
      do j = 1, size(v)   ! element by element: an ordered comparison with NaN traps
         if (ieee_is_nan(v(j)) .or. .not. c%classified) then
            c%cls(j) = -1
            cycle
         end if
         if (c%indicator == 'lambda1' .and. abs(v(j)) < 1e300_dp) v(j) = v(j)*c%tau
         if (c%above) then
            c%cls(j) = merge(1, 0, v(j) > c%threshold)
         else
            c%cls(j) = merge(1, 0, v(j) < c%threshold)
         end if
      end do
   end subroutine classify

   !> The indicator of a sweep's configuration (lambda1 for lyapunov = true), its
   !> dataset, its default threshold and sense, or the given `threshold`; a file
   !> without an indicator, and FLI without a threshold, are refused.
   subroutine choose_indicator(file, pre, set, threshold, c, error, values_only)
      character(len=*), intent(in) :: file              !! sweep file
      character(len=*), intent(in) :: pre               !! message prefix
      logical, intent(in) :: set                        !! threshold given
      real(dp), intent(in) :: threshold                 !! the given threshold
      type(classified_t), intent(inout) :: c            !! config in, indicator out
      type(error_t), allocatable, intent(out) :: error  !! refused
      logical, intent(in), optional :: values_only      !! FLI without threshold: unclassified
      c%indicator = config_value(c%config, 'indicator')
      if (len(c%indicator) == 0 .and. config_value(c%config, 'lyapunov') == 'true') &
         c%indicator = 'lambda1'
      select case (c%indicator)
      case ('megno'); c%dataset = '/sweep/megno'; c%threshold = 2.5_dp
      case ('lambda1'); c%dataset = '/sweep/lyapunov'; c%threshold = 0.05_dp
      case ('fli'); c%dataset = '/sweep/fli'
      case ('sali', 'gali2'); c%dataset = '/sweep/'//c%indicator; c%threshold = 1e-8_dp
         c%above = .false.
      case default
         call fatal_error(error, pre//'it has no indicator (run the sweep with --indicator '// &
                          'megno, lambda1, fli, sali or gali2)')
         return
      end select
      if (set) c%threshold = threshold
      if (c%indicator == 'fli' .and. .not. set .and. present(values_only)) then
         if (values_only) then
            c%classified = .false.
            return
         end if
      end if
      if (c%indicator == 'fli' .and. .not. set) then
         call fatal_error(error, 'sweep-compare: invalid --threshold: FLI has no default '// &
                          "threshold (it grows with t_end): give one for '"//file//"'")
         return
      end if
   end subroutine choose_indicator

   !> The indicator's values: NaN (not computed or not finite) or finite within
   !> what a sweep writes (SALI in [0, √2], GALI_2 in [0, 1]); at least one finite;
   !> MEGNO not negative everywhere (<Y> of every orbit tends to 2 or grows).
   subroutine check_values(c, v, pre, err)
      type(classified_t), intent(in) :: c                !! indicator and dataset
      real(dp), intent(in) :: v(:)                       !! its values
      character(len=*), intent(in) :: pre                !! message prefix
      type(error_t), allocatable, intent(out) :: err     !! damaged
      real(dp) :: hi, lo
      integer :: k, n_finite, n_negative
      lo = -huge(1.0_dp)
      hi = huge(1.0_dp)
      if (c%indicator == 'sali') then
         lo = 0.0_dp
         hi = sqrt(2.0_dp)*(1.0_dp + 1e-12_dp)
      else if (c%indicator == 'gali2') then
         lo = 0.0_dp
         hi = 1.0_dp + 1e-12_dp
      end if
      n_finite = 0
      n_negative = 0
      do k = 1, size(v)
         if (ieee_is_nan(v(k))) cycle
         if (.not. ieee_is_finite(v(k))) then
            call fatal_error(err, pre//'damaged: '//c%dataset//' holds '//sci(v(k))// &
                             ' (a sweep writes NaN or finite values)')
            return
         end if
         if (v(k) < lo .or. v(k) > hi) then
            call fatal_error(err, pre//'damaged: '//c%dataset//' holds '//sci(v(k))// &
                             ' (a sweep writes '//sci(lo)//' to '//sci(hi)//')')
            return
         end if
         n_finite = n_finite + 1
         if (v(k) < 0.0_dp) n_negative = n_negative + 1
      end do
      if (n_finite == 0) then
         call fatal_error(err, pre//'damaged: '//c%dataset//' has no finite value '// &
                          '(nothing to classify)')
      else if (c%indicator == 'megno' .and. n_negative == n_finite) then
         call fatal_error(err, pre//'damaged: '//c%dataset//' is negative at every '// &
                          'pixel (MEGNO tends to 2 for regular orbits and grows for '// &
                          'chaotic ones)')
      end if
   end subroutine check_values
end module dpend_sweep_agreement
