!> One resolution of every setting (src/settings/dpend_run_settings.f90, filled by
!> dpend_namelist and dpend_run_flags): a quantity given in &model, in &pendulum or by
!> a flag builds the same model (its parameters and the energy at t = 0 bit for bit);
!> the flags override the file whatever group gave it; two groups of one file giving
!> one quantity, and a setting the model has no parameter for, are refused.
module test_run_settings
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_namelist, only: read_run_config
   use dpend_run_flags, only: apply_run_flag, take_initial_angles
   use dpend_kinds, only: half_pi
   use testing, only: unittest_t, new_unittest, check_true
   implicit none
   private
   public :: collect_run_settings

contains

   subroutine collect_run_settings(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [ &
              new_unittest('same_quantity_three_ways', test_three_ways), &
              new_unittest('flags_over_either_group', test_flags_over_file), &
              new_unittest('two_groups_refused', test_two_groups), &
              new_unittest('unused_settings_refused', test_unused), &
              new_unittest('time_unit_once', test_time_unit), &
              new_unittest('relative_initial_angles_once', test_relative_angles) &
              ]
   end subroutine collect_run_settings

   !> m, l, g through &model, through &pendulum and through flags: one model.
   subroutine test_three_ways(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: e(3), p(3)
      character(len=*), parameter :: init = '&initial q1 = -1, q2 = 0.5, w1 = 0.3 /'
      call energy_of([character(len=80) :: "&model name = 'pendulum', m = 2, 3, " &
                      //'l = 0.5, 0.7, g = 3 /', init], [character(len=16) ::], &
                     e(1), p(1), error)
      if (allocated(error)) return
      call energy_of([character(len=80) :: '&pendulum m1 = 2, m2 = 3, l1 = 0.5, ' &
                      //'l2 = 0.7, g = 3 /', init], [character(len=16) ::], e(2), p(2), error)
      if (allocated(error)) return
      call energy_of([character(len=80) :: init], [character(len=16) :: '--m', '2,3', &
                      '--l', '0.5,0.7', '--g', '3'], e(3), p(3), error)
      if (allocated(error)) return
      call check_true(error, all(e == e(1)) .and. all(p == p(1)), &
                      'E(0) and the parameters from &model, &pendulum and flags are one')
      ! the elastic pendulum's mass and g: &model or flags
      call energy_of([character(len=80) :: "&model name = 'elastic', m = 2, g = 3, " &
                      //'k = 40, l0 = 1 /', '&initial q = 1.2, -1 /'], &
                     [character(len=16) ::], e(1), p(1), error)
      if (allocated(error)) return
      call energy_of([character(len=80) :: '&initial q = 1.2, -1 /'], &
                     [character(len=16) :: '--model', 'elastic', '--m', '2', '--g', '3', &
                      '--k', '40', '--l0', '1'], e(2), p(2), error)
      if (allocated(error)) return
      call check_true(error, e(1) == e(2) .and. p(1) == p(2), &
                      'elastic: E(0) and m from &model equal those from flags')
   end subroutine test_three_ways

   !> The flags override a value of &model as they override one of &pendulum.
   subroutine test_flags_over_file(error)
      type(error_t), allocatable, intent(out) :: error
      real(dp) :: e(3), p(3)
      character(len=*), parameter :: init = '&initial q1 = -1, q2 = 0.5 /'
      call energy_of([character(len=80) :: "&model name = 'pendulum', m = 2, 3 /", init], &
                     [character(len=16) :: '--m', '4,5'], e(1), p(1), error)
      if (allocated(error)) return
      call energy_of([character(len=80) :: '&pendulum m = 2, 3 /', init], &
                     [character(len=16) :: '--m', '4,5'], e(2), p(2), error)
      if (allocated(error)) return
      call energy_of([character(len=80) :: init], [character(len=16) :: '--m', '4,5'], &
                     e(3), p(3), error)
      if (allocated(error)) return
      call check_true(error, all(e == e(3)) .and. all(p == 4.0_dp), &
                      '--m 4,5 overrides &model m and &pendulum m alike (m1 = 4 used)')
   end subroutine test_flags_over_file

   !> One quantity in &model and in &pendulum: refused naming both.
   subroutine test_two_groups(error)
      type(error_t), allocatable, intent(out) :: error
      call refused([character(len=80) :: "&model name = 'pendulum', m = 2, 3 /", &
                    '&pendulum m1 = 2 /'], [character(len=16) ::], &
                   'm is given in &model and as m1 in &pendulum', error)
      if (allocated(error)) return
      call refused([character(len=80) :: '&model g = 3 /', '&pendulum g = 2 /'], &
                   [character(len=16) ::], 'g is given in &model and as g in &pendulum', error)
      if (allocated(error)) return
      call refused([character(len=80) :: '&model com = 0.5, 0.5 /', &
                    '&pendulum com = 0.4, 0.4 /'], [character(len=16) ::], &
                   'com is given in &model and as com in &pendulum', error)
   end subroutine test_two_groups

   !> The pendulum's settings for a model without them: refused, by flag or file.
   subroutine test_unused(error)
      type(error_t), allocatable, intent(out) :: error
      character(len=16), parameter :: el(4) = [character(len=16) :: '--model', 'elastic', &
                                               '--q', '1.2,-1']
      call refused([character(len=80) ::], [character(len=16) :: el, '--l1', '2'], &
                   'invalid l1: not a parameter of model elastic', error)
      if (allocated(error)) return
      call refused([character(len=80) ::], [character(len=16) :: el, '--m2', '3'], &
                   'invalid m2: not a parameter of model elastic', error)
      if (allocated(error)) return
      call refused([character(len=80) ::], [character(len=16) :: el, '--support-phase', '1,1'], 'invalid support_phase', error)
      if (allocated(error)) return
      call refused([character(len=80) ::], [character(len=16) :: '--model', 'elastic', &
                                            '--theta1', '2'], 'invalid theta1', error)
      if (allocated(error)) return
      call refused([character(len=80) :: "&model name = 'elastic' /", &
                    '&pendulum support_frequency = 2 /', '&initial q = 1.2, -1 /'], &
                   [character(len=16) ::], 'invalid support_frequency', error)
   end subroutine test_unused

   !> time_unit natural: dt, t_end and output_dt given in sqrt(l1/g) are converted to
   !> seconds once, by sqrt(l1/g) computed here (l1 = 2.45 m, g = 9.8: exactly 0.5 s),
   !> and validating again converts nothing more; from &integration or a flag, which
   !> overrides the file; an unknown unit and the elastic pendulum's sqrt(l0/g).
   subroutine test_time_unit(error)
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      character(len=*), parameter :: pend = '&pendulum l1 = 2.45, g = 9.8 /'
      call settings_of([character(len=80) :: pend, "&integration dt = 0.01, t_end = 40, " &
                        //"output_dt = 0.5, time_unit = 'natural' /"], [character(len=16) ::], &
                       cfg, error)
      if (allocated(error)) return
      call check_true(error, abs(cfg%dt - 0.005_dp) < 1e-15_dp .and. &
                      abs(cfg%t_end - 20.0_dp) < 1e-13_dp .and. &
                      abs(cfg%output_dt - 0.25_dp) < 1e-15_dp .and. &
                      abs(cfg%seconds(3.0_dp) - 1.5_dp) < 1e-15_dp, &
                      'natural: dt, t_end, output_dt in s (sqrt(2.45/9.8) = 0.5 s)')
      if (allocated(error)) return
      call validate_run_config(cfg, error)
      if (allocated(error)) return
      call check_true(error, abs(cfg%t_end - 20.0_dp) < 1e-13_dp, 'converted once')
      if (allocated(error)) return
      call settings_of([character(len=80) :: pend, "&integration t_end = 40, " &
                        //"time_unit = 'natural' /"], [character(len=16) :: '--time-unit', &
                        's'], cfg, error)
      if (allocated(error)) return
      call check_true(error, cfg%t_end == 40.0_dp .and. cfg%time_scale == 1.0_dp, &
                      '--time-unit s overrides the file')
      if (allocated(error)) return
      call settings_of([character(len=80) :: '&initial q = 1.2, -1 /'], [character(len=16) :: &
                       '--model', 'elastic', '--l0', '0.98', '--g', '9.8', '--k', '40', &
                       '--t-end', '10', '--time-unit', 'natural'], cfg, error)
      if (allocated(error)) return
      call check_true(error, abs(cfg%t_end - 10.0_dp*sqrt(0.1_dp)) < 1e-14_dp, &
                      'elastic: sqrt(l0/g)')
      if (allocated(error)) return
      call refused([character(len=80) :: "&integration time_unit = 'min' /"], &
                   [character(len=16) ::], "invalid time_unit: 'min' (accepted: s, natural)", &
                   error)
      if (allocated(error)) return
      call refused([character(len=80) ::], [character(len=16) :: '--time-unit', 'S'], &
                   "invalid time_unit: 'S'", error)
   end subroutine test_time_unit

   !> --angles relative: φ = (0.3, −0.5, 0.2) rad, φ̇ = (0.1, 0.2, −0.4) rad/s of three
   !> links give q = (0.3 − π/2, q1 − 0.5, q2 + 0.2), q̇ = (0.1, 0.3, −0.1), converted
   !> once (a second validation leaves them).
   subroutine test_relative_angles(error)
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      real(dp) :: q(3), w(3)
      call settings_of([character(len=80) ::], [character(len=16) :: '--links', '3', &
                       '--q', '0.3,-0.5,0.2', '--w', '0.1,0.2,-0.4'], cfg, error)
      if (allocated(error)) return
      q = cfg%q(1:3); w = cfg%w(1:3)
      call check_true(error, all(q == [0.3_dp, -0.5_dp, 0.2_dp]), 'absolute by default')
      if (allocated(error)) return
      call take_initial_angles(cfg, 'relative', error)
      if (allocated(error)) return
      cfg%angles_resolved = .false.
      call validate_run_config(cfg, error)
      if (allocated(error)) return
      call validate_run_config(cfg, error)
      if (allocated(error)) return
      q(1) = 0.3_dp - half_pi; q(2) = q(1) - 0.5_dp; q(3) = q(2) + 0.2_dp
      call check_true(error, all(cfg%q(1:3) == q) .and. &
                      all(cfg%w(1:3) == [0.1_dp, 0.1_dp + 0.2_dp, 0.1_dp + 0.2_dp - 0.4_dp]), &
                      'relative: q1 = phi1 - pi/2, q_i = q_(i-1) + phi_i, once')
   end subroutine test_relative_angles

   !> The settings of a file with these lines, then these flags (name, value pairs).
   subroutine settings_of(lines, flags, cfg, error)
      character(len=*), intent(in) :: lines(:), flags(:)
      type(run_config_t), intent(out) :: cfg
      type(error_t), allocatable, intent(out) :: error
      character(len=*), parameter :: path = '/tmp/dpend-test-run-settings.nml'
      integer :: unit, k
      logical :: matched
      cfg%method = 'rk4'
      if (size(lines) > 0) then
         open (newunit=unit, file=path, status='replace', action='write')
         do k = 1, size(lines)
            write (unit, '(a)') trim(lines(k))
         end do
         close (unit)
         call read_run_config(path, cfg, error)
         open (newunit=unit, file=path, status='old')
         close (unit, status='delete')
         if (allocated(error)) return
      end if
      do k = 1, size(flags), 2
         call apply_run_flag(cfg, trim(flags(k)), trim(flags(k + 1)), matched, error)
         if (allocated(error)) return
         call check_true(error, matched, trim(flags(k))//' is a run flag')
         if (allocated(error)) return
      end do
      call validate_run_config(cfg, error)
   end subroutine settings_of

   !> E(0) of the run and its model's first parameter named m (m1 of the pendulum).
   subroutine energy_of(lines, flags, e0, m1, error)
      character(len=*), intent(in) :: lines(:), flags(:)
      real(dp), intent(out) :: e0, m1
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      character(len=:), allocatable :: name, units
      real(dp) :: x
      integer :: i, n
      e0 = 0; m1 = 0
      call settings_of(lines, flags, cfg, error)
      if (allocated(error)) return
      n = cfg%model%n_dof()
      e0 = cfg%model%energy(0.0_dp, [cfg%q(:n), cfg%w(:n)])
      do i = cfg%model%n_parameters(), 1, -1
         call cfg%model%parameter(i, name, x, units)
         if (name == 'm' .or. name == 'm1') m1 = x
      end do
   end subroutine energy_of

   !> The settings are refused with a message containing `text`.
   subroutine refused(lines, flags, text, error)
      character(len=*), intent(in) :: lines(:), flags(:), text
      type(error_t), allocatable, intent(out) :: error
      type(run_config_t) :: cfg
      type(error_t), allocatable :: why
      call settings_of(lines, flags, cfg, why)
      call check_true(error, allocated(why), 'refused: '//text)
      if (allocated(error)) return
      call check_true(error, index(why%message, text) > 0, "message '"//why%message// &
                      "' names: "//text)
   end subroutine refused

end module test_run_settings
