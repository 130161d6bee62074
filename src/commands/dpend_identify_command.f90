!> `dpend identify`: the parameters a measured motion and its joint torques determine.
!> The motion is filtered as `dpend torques` filters it (`filter_motion`); the rows
!> used are the interior samples every window (so that their filter errors are
!> independent); `dpend_identify` finds the base parameters, refuses a combination the
!> data cannot separate (naming it) and estimates the rest by weighted least squares.
!> The report gives the estimates with standard errors and 95 % intervals, the
!> condition number, the torque residual per joint, and the physical checks with the
!> masses given; the file (group /identify, docs/hdf5-layout.md) goes through the one
!> writer. The command line and the data: `dpend_torques_config`.
module dpend_identify_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_cli, only: arg_t, real_str, to_str, printable, pad
   use dpend_strings, only: with_uncertainty
   use dpend_identify, only: n_kinds, base_t, base_parameters, identify_result_t, &
                             identify_parameters, standard_values, physical_parameters, &
                             parameter_label, kind_units
   use dpend_smoothing, only: smooth_derivatives, noise_factors
   use dpend_hdf5, only: h5file_t
   use dpend_model_record, only: record_model
   use dpend_output, only: output_t
   use dpend_version, only: version
   use dpend_command_common, only: report_unit, take_quiet, with_quiet, summary_quiet, &
      refusal_line, error_line
   use dpend_torques_config, only: torques_config_t, parse_torques, identify_help
   use dpend_torques_command, only: torques_result_t, filter_motion
   implicit none
   private
   public :: identify_command

   character(len=*), parameter :: nl = new_line('a')

   !> The physical checks of one link.
   type :: link_check_t
      real(dp) :: theta(n_kinds) = 0.0_dp, se(n_kinds) = 0.0_dp
      logical :: found(n_kinds) = .false.
      real(dp) :: d = 0.0_dp, ic = 0.0_dp   !! h/m [m], J − h²/m [kg m²]
      character(len=:), allocatable :: verdict
   end type link_check_t

contains

   !> The entry point of `dpend identify DATA.csv [options]` (app/main.f90).
   subroutine identify_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after `identify`
      type(error_t), allocatable, intent(out) :: error  !! refused input or a failed run
      type(arg_t), allocatable :: rest(:)
      type(torques_config_t) :: tc
      type(torques_result_t) :: filt
      type(identify_result_t) :: res
      type(link_check_t), allocatable :: checks(:)
      integer, allocatable :: rows(:)
      logical :: help, quiet
      call take_quiet(args, rest, quiet)
      call parse_torques(rest, tc, help, error, 'identify')
      if (allocated(error)) then
         call refusal_line(error, 'identify')
         return
      else if (help) then
         write (output_unit, '(a)') with_quiet(identify_help(), summary_quiet)
         return
      end if
      call identify_run(tc, filt, rows, res, error)
      if (allocated(error)) then
         call refusal_line(error, 'identify')
         return
      end if
      checks = physical_checks(tc, res)
      call write_output(tc, filt, rows, res, checks, error)
      if (allocated(error)) then
         call run_failure(error)
         call error_line(error, 'identify')
         return
      end if
      call print_report(tc, filt, rows, res, checks, quiet)
   end subroutine identify_command

   !> Filter, choose the rows, find the base parameters and estimate them. `error`: a
   !> refusal (too few rows, parameters the data do not separate).
   subroutine identify_run(tc, filt, rows, res, error)
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(out) :: filt
      integer, allocatable, intent(out) :: rows(:)
      type(identify_result_t), intent(out) :: res
      type(error_t), allocatable, intent(out) :: error
      type(base_t) :: base
      logical, allocatable :: free(:, :)
      real(dp), allocatable :: ys(:, :, :), nv(:, :)
      real(dp) :: nf(0:2)
      integer :: n, k, kw, j
      call filter_motion(tc, filt, error)
      if (allocated(error)) return
      n = tc%angles%n
      k = tc%angles%k
      kw = filt%half_width
      rows = [(j, j = kw + 1, k - kw, 2*kw + 1)]
      allocate (free(n_kinds, n))
      free = .true.
      free(4, :) = tc%fit_viscous
      free(5, :) = tc%fit_coulomb
      free(6, :) = tc%fit_rotors
      call base_parameters(tc%chain, pack(free, .true.), base)
      if (n*size(rows) <= 2*size(base%kept)) then
         call fatal_error(error, "invalid data file '"//printable(tc%input)//"': "// &
                          to_str(size(rows))//' rows (every '//to_str(2*kw + 1)// &
                          '-th sample, the window) give '//to_str(n*size(rows))// &
                          ' torques for '//to_str(size(base%kept))//' base parameters: at ' &
                          //'least '//to_str(2*size(base%kept)/n + 1)//' rows are needed ' &
                          //'(a longer record, or a narrower --window)')
         return
      end if
      ! the measured torques through the same filter (its value): the filter's bias
      ! then cancels to first order between the two sides
      allocate (ys(0:2, n, k))
      call smooth_derivatives(tc%angles%t, tc%measured%q, kw, tc%degree, ys)
      ! the variances of the filter's q̇ and q̈ errors, for the compensation of the
      ! noise they put into the regressor
      nf = noise_factors(tc%angles%t, kw, tc%degree)
      allocate (nv(2, n))
      do j = 1, n
         nv(:, j) = (filt%sigma(j)*nf(1:2))**2
      end do
      call identify_parameters(tc%chain, base, tc%angles%t(rows), filt%q(:, rows), &
                               filt%qd(:, rows), filt%qdd(:, rows), ys(0, :, rows), &
                               pack(standard_values(tc%chain), .true.), res, error, &
                               noise_var=nv)
      if (allocated(error)) error%message = "invalid data file '"//printable(tc%input)// &
                                            "': "//error%message
   end subroutine identify_run

   !> Per link, the standard parameters that the base estimate gives with the masses
   !> given (--m), and the checks: J_i > 0, J_i >= m_i d_i² (I_C >= 0), c_i, cf_i, Im_i >= 0
   !> (each within 2 standard errors counts as holding).
   function physical_checks(tc, res) result(checks)
      type(torques_config_t), intent(in) :: tc
      type(identify_result_t), intent(in) :: res
      type(link_check_t), allocatable :: checks(:)
      real(dp) :: theta(n_kinds, tc%chain%n), se(n_kinds, tc%chain%n)
      logical :: found(n_kinds, tc%chain%n)
      integer :: i, c
      character(len=:), allocatable :: bad
      call physical_parameters(res%base, res%estimate, res%std_error, tc%chain%m, theta, &
                               se, found)
      allocate (checks(tc%chain%n))
      do i = 1, tc%chain%n
         checks(i)%theta = theta(:, i)
         checks(i)%se = se(:, i)
         checks(i)%found = found(:, i)
         bad = ''
         if (found(1, i) .and. found(2, i)) then
            checks(i)%d = theta(2, i)/theta(3, i)
            checks(i)%ic = theta(1, i) - theta(2, i)**2/theta(3, i)
            if (theta(1, i) + 2*se(1, i) <= 0.0_dp) bad = bad//' J'//to_str(i)//' <= 0;'
            if (checks(i)%ic + 2*se(1, i) < 0.0_dp) bad = bad//' J'//to_str(i)// &
               ' < m d^2 (inertia about the centre of mass negative);'
         end if
         do c = 4, 6
            if (found(c, i)) then
               if (theta(c, i) + 2*se(c, i) < 0.0_dp) bad = bad//' '// &
                  parameter_label(c, i)//' < 0;'
            end if
         end do
         if (len(bad) == 0) then
            checks(i)%verdict = 'consistent'
         else
            checks(i)%verdict = 'NOT consistent:'//bad(:len(bad) - 1)
         end if
      end do
   end function physical_checks

   !> The HDF5 file through the one writer.
   subroutine write_output(tc, filt, rows, res, checks, error)
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(in) :: filt
      integer, intent(in) :: rows(:)
      type(identify_result_t), intent(in) :: res
      type(link_check_t), intent(in) :: checks(:)
      type(error_t), allocatable, intent(out) :: error
      type(output_t) :: out
      type(error_t), allocatable :: werr
      type(h5file_t) :: h5
      integer :: i
      real(dp), allocatable :: phys(:, :), t_rows(:)
      call out%begin(tc%run%output, tc%run%force, error)
      if (allocated(error)) return
      call h5%open(out%temp, 'w', werr)
      if (.not. allocated(werr)) then
         call h5%writeattr('/', 'command', 'identify')
         call record_model(h5, tc%chain)
         call h5%writeattr('/', 'links', tc%angles%n)
         call h5%writeattr('/', 'data_file', tc%input)
         call h5%writeattr('/', 'degree', tc%degree)
         call h5%writeattr('/', 'window', 2*filt%half_width + 1)
         call h5%writeattr('/', 'window_rule', filt%window_rule)
         call h5%writeattr('/', 'sigma', filt%sigma)
         call h5%writeattr('/', 'friction', trim(merge('viscous ', '        ', &
                           tc%fit_viscous))//trim(merge(' coulomb', '        ', tc%fit_coulomb)))
         call h5%writeattr('/', 'rotors', trim(merge('estimated', 'known    ', tc%fit_rotors)))
         call h5%writeattr('/', 'condition', res%condition)
         call h5%writeattr('/', 'compensated', merge(1, 0, res%compensated))
         call h5%writeattr('/', 't95', res%t95)
         call h5%writeattr('/', 'version', version)
         call h5%writeattr('/', 'status', 'completed')
         call h5%write('/identify/names', joined(res%base%names), units='text', &
                       description='the base ' &
                       //'parameters in words, separated by "; " (the order of estimate)')
         call h5%write('/identify/units', joined(res%base%units), units='text', &
                       description='their ' &
                       //'units, separated by "; "')
         call h5%write('/identify/estimate', res%estimate, units=joined(res%base%units), &
                       description='the base ' &
                       //'parameters (units: /identify/units)')
         call h5%write('/identify/std_error', res%std_error, units=joined(res%base%units), &
                       description='their standard ' &
                       //'errors')
         call h5%write('/identify/interval95', res%interval95, units= &
                       joined(res%base%units), description='95 % ' &
                       //'intervals: estimate -/+ t95 std_error (low, high)')
         call h5%write('/identify/covariance', res%covariance, units='products of ' &
                       //'/identify/units (row i, column j: units_i units_j)', &
                       description='covariance ' &
                       //'of the estimates')
         call h5%write('/identify/singular', res%singular, units='1', &
                       description='singular values ' &
                       //'of the base regressor with unit columns, largest first')
         t_rows = tc%angles%t(rows)
         call h5%write('/identify/t', t_rows, units='s', description='the ' &
                       //'sample times used (every window-th interior sample)')
         call h5%write('/identify/residual', res%residual, units='N m', description= &
                       'measured minus model joint torques at those times')
         call h5%write('/identify/sigma_joint', res%sigma_joint, units='N m', &
                       description='residual scatter per joint (the weights 1/sigma)')
         allocate (phys(n_kinds, size(checks)))
         do i = 1, size(checks)
            phys(:, i) = merge(checks(i)%theta, ieee_nan(), checks(i)%found)
         end do
         call h5%write('/identify/physical', phys, units='kg m^2; kg m; kg; N m s; N m; ' &
                       //'kg m^2', description='per link J, h, m, c, cf, Im (the units in ' &
                       //'this order) from the base estimate with the masses given; NaN: not ' &
                       //'determined')
         call h5%close(werr)
      end if
      if (.not. allocated(werr)) call out%commit(werr)
      call out%explain(werr)
      call out%discard()
      if (allocated(werr)) call move_alloc(werr, error)
   end subroutine write_output

   function ieee_nan() result(x)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      real(dp) :: x
      x = ieee_value(x, ieee_quiet_nan)
   end function ieee_nan

   function joined(items) result(s)
      character(len=*), intent(in) :: items(:)
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(items)
         if (i > 1) s = s//'; '
         s = s//trim(items(i))
      end do
   end function joined

   !> The report; its last line names the file (--quiet: that line only).
   subroutine print_report(tc, filt, rows, res, checks, quiet)
      type(torques_config_t), intent(in) :: tc
      type(torques_result_t), intent(in) :: filt
      integer, intent(in) :: rows(:)
      type(identify_result_t), intent(in) :: res
      type(link_check_t), intent(in) :: checks(:)
      logical, intent(in) :: quiet
      character(len=:), allocatable :: s
      integer :: i, c, w
      if (quiet) then
         write (report_unit(), '(a)') "dpend identify: wrote '"//printable(tc%run%output)//"'"
         return
      end if
      w = 0
      do i = 1, size(res%base%names)
         w = max(w, len_trim(res%base%names(i)) + len_trim(res%base%units(i)) + 3)
      end do
      s = "dpend identify: '"//printable(tc%input)//"', "//to_str(size(rows))// &
          ' rows of '//to_str(tc%angles%k)//' samples (every '// &
          to_str(2*filt%half_width + 1)//'-th: the window of the filter, degree '// &
          to_str(tc%degree)//'), '//to_str(tc%angles%n)//' links'//nl// &
          'base parameters (what the torques determine), weighted least squares'// &
          trim(merge(' compensated for the filter''s noise', '                                   ', &
                     res%compensated))//', condition number '// &
          real_str(res%condition, 3)//':'//nl
      do i = 1, size(res%base%names)
         s = s//'  '//pad(trim(res%base%names(i))//' ['//trim(res%base%units(i))//']', w)// &
             '  '//with_uncertainty(res%estimate(i), res%std_error(i))//'   95 %: ['// &
             real_str(res%interval95(1, i), 4)//', '//real_str(res%interval95(2, i), 4)// &
             ']'//nl
      end do
      s = s//'not in the torques:'//absent_text(res%base)//nl// &
          'torque residual RMS per joint [N m]:'
      do i = 1, size(res%rms_residual)
         s = s//' '//real_str(res%rms_residual(i), 3)
      end do
      s = s//nl//'with the masses given (m ='
      do i = 1, size(checks)
         s = s//' '//real_str(checks(i)%theta(3), 4)
      end do
      s = s//' kg):'//nl
      do i = 1, size(checks)
         s = s//'  link '//to_str(i)//':'
         do c = 1, n_kinds
            if (c == 3 .or. .not. checks(i)%found(c)) cycle
            s = s//' '//parameter_label(c, i)//' = '// &
                with_uncertainty(checks(i)%theta(c), checks(i)%se(c))//' '// &
                trim(kind_units(c))//';'
         end do
         if (checks(i)%found(1) .and. checks(i)%found(2)) s = s//' d = '// &
            real_str(checks(i)%d, 4)//' m, I_C = '//real_str(checks(i)%ic, 4)//' kg m^2;'
         s = s//' '//checks(i)%verdict//nl
      end do
      s = s//"dpend identify: wrote '"//printable(tc%run%output)//"'"
      write (report_unit(), '(a)') s
   end subroutine print_report

   !> The standard parameters that do not show in the torques, and those that only
   !> show through the base combinations.
   function absent_text(base) result(s)
      type(base_t), intent(in) :: base
      character(len=:), allocatable :: s
      integer :: j, jj
      s = ''
      do j = 1, size(base%dropped)
         jj = base%dropped(j)
         s = s//' '//parameter_label(mod(jj - 1, n_kinds) + 1, (jj - 1)/n_kinds + 1)
         if (base%absent(j)) then
            s = s//' (no effect);'
         else
            s = s//' (only within the combinations above);'
         end if
      end do
      if (len(s) > 0) s = s(:len(s) - 1)
   end function absent_text

end module dpend_identify_command
