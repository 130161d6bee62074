!> The settings of a sweep (`dpend sweep`, the MPI front end, library callers): the
!> record and its keys (dpend_sweep_record), the pixels of a sweep over parameters
!> (dpend_sweep_pixels), both passed on from here, and their validation
!> (`validate_sweep`: every field, the axes and their ranges, each corner pixel's
!> model built by the factory before any work) with the texts that follow from them
!> (the horizon in both time units, the accepted axes).
module dpend_sweep_settings
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: real_str, to_str, printable
   use dpend_lane_batch, only: stop_both, stop_either, stop_end
   use dpend_limits, only: sci, max_threads, max_axis_points, max_sweep_points, max_angle, &
      max_angular_velocity, max_time, check_parameter, parameter_mass, parameter_length
   use dpend_model, only: model_t
   use dpend_pendulum, only: pendulum_t
   use dpend_model_factory, only: model_spec_t, new_model, model_info_t, model_catalogue, &
      find_model, spec_values
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use dpend_strings, only: to_lower, did_you_mean
   use dpend_run_settings, only: run_config_t, validate_run_config
   use dpend_work, only: needs_work
   use dpend_sweep_record
   use dpend_sweep_pixels
   implicit none
   private
   ! the record and the pixels, passed on: the one module a command or engine uses
   public :: sweep_config_t, sweep_defaults, validate_sweep, axis_names, time_scale, &
      stop_rule, grid_mode, axis_variable, indicator_names, indicator_vectors, &
      axis_parameter, param_axis_names, pixel_parameters, pixel_model, flip_model, &
      sweep_variable, natural_time, horizon_text, kernel_pendulum
   public :: model_axis, model_axis_names, pixel_model_named, pixel_pendulum, pixel_pendulums
   public :: pendulum_axis, pendulum_param_names, pendulum_param_values, pixel_model_axes, &
      named_axis_units, coded_axes

contains

   !> Check the configuration; messages name the field and the accepted range.
   subroutine validate_sweep(cfg, error)
      type(sweep_config_t), intent(inout) :: cfg        !! configuration; model built
      type(error_t), allocatable, intent(out) :: error  !! first invalid field
      call validate_run_config(cfg%run, error, initial_state=grid_mode(cfg), &
                               keep_time_unit=.true.)
      if (allocated(error)) return
      ! a damped or driven chain runs per trajectory with its works (the balance)
      if (.not. (cfg%run%model%conservative() .or. needs_work(cfg%run%model))) then
         call fatal_error(error, 'invalid model: dpend sweep integrates the '// &
                          cfg%run%model%name()//' without an energy balance to check it by')
         return
      end if
      cfg%indicator = to_lower(cfg%indicator); cfg%axis1 = to_lower(cfg%axis1)
      cfg%axis2 = to_lower(cfg%axis2)   ! names without regard to case
      select case (cfg%indicator)
      case ('flip', 'lambda1', 'megno', 'fli', 'sali', 'gali2')
      case default
         call fatal_error(error, "invalid indicator: '"//cfg%indicator//"' (accepted: "// &
                          indicator_names//')'//did_you_mean(cfg%indicator, indicator_names, '; '))
         return
      end select
      if (cfg%indicator == 'lambda1') cfg%lyapunov = .true.
      if (.not. flip_model(cfg)) then
         call check_model_sweep(cfg, error)
         if (allocated(error)) return
      end if
      if (cfg%lyapunov .and. indicator_vectors(cfg) > 0) then
         call fatal_error(error, "invalid indicator: '"//cfg%indicator//"' with lyapunov "// &
                          '= true (one indicator per sweep; lambda1 is the Lyapunov exponent)')
         return
      end if
      if (cfg%lyapunov) then
         call check_sweep_lyapunov(cfg, error)
         if (allocated(error)) return
      end if
      if (cfg%run%method /= 'rk4') then
         call fatal_error(error, "invalid method: '"//cfg%run%method// &
                          "' (dpend sweep accepts: rk4)")
      else if (.not. (cfg%run%t_end > 0.0_dp)) then
         call fatal_error(error, 'invalid t_end: must be finite and > 0')
      else if (cfg%stop_at /= 'both' .and. cfg%stop_at /= 'either' .and. &
               cfg%stop_at /= 'end') then
         call fatal_error(error, "invalid stop_at: '"//cfg%stop_at// &
                          "' (accepted: both, either, end)")
      else if (cfg%block < 1 .or. cfg%block > max_sweep_points) then
         call fatal_error(error, 'invalid block: must be an integer from 1 to '// &
                          to_str(max_sweep_points))
      else if (cfg%threads < 0 .or. cfg%threads > max_threads) then
         call fatal_error(error, 'invalid threads: '//to_str(cfg%threads)// &
                          ' must be an integer from 0 (all) to '//to_str(max_threads))
      else if (cfg%run%t_end*time_scale(cfg) > max_time) then
         ! both factors are bounded (t_end <= 1e9, sqrt(l1/g) <= 1e6): no overflow
         call fatal_error(error, 'invalid t_end: '//sci(cfg%run%t_end)//' '// &
                          trim(unit_name(cfg))//' is '//sci(cfg%run%t_end*time_scale(cfg))// &
                          ' s, above '//sci(max_time)//' s')
      else if (.not. (cfg%run%t_end*time_scale(cfg) >= tiny(1.0_dp))) then
         ! (4.9e-324 in natural units is 0 s: a step of 0 s, MEGNO's 2 ∫/t divided by 0)
         call fatal_error(error, 'invalid t_end: '//sci(cfg%run%t_end)//' '// &
                          trim(unit_name(cfg))//' is '//sci(cfg%run%t_end*time_scale(cfg))// &
                          ' s, below '//sci(tiny(1.0_dp))//' s (the smallest normal double)')
      end if
      if (allocated(error)) return
      if (grid_mode(cfg) .and. (cfg%ic_angles_given .or. cfg%ic_dataset_given)) then
         call fatal_error(error, 'invalid '//trim(merge('ic_angles ', 'ic_dataset', &
                          cfg%ic_angles_given))//': given without ic_file (it describes ' &
                          //'the list of --ic-file; a grid sweep has none) [--ic-file / &sweep]')
         return
      end if
      if (grid_mode(cfg) .and. .not. flip_model(cfg)) then
         call check_model_axes(cfg, error)
      else if (grid_mode(cfg)) then
         call check_axis(cfg%axis1, 1, cfg%n1, cfg%min1, cfg%max1, cfg%run%links, error, &
                         pendulum_axis(cfg, cfg%axis1))
         if (allocated(error)) return
         call check_axis(cfg%axis2, 2, cfg%n2, cfg%min2, cfg%max2, cfg%run%links, error, &
                         pendulum_axis(cfg, cfg%axis2))
         if (allocated(error)) return
         if (merge(cfg%axis1 == cfg%axis2, same_value(cfg%axis1, cfg%axis2, cfg%run%links), &
                   pendulum_axis(cfg, cfg%axis1) .or. pendulum_axis(cfg, cfg%axis2))) then
            call fatal_error(error, "invalid axis2: '"//cfg%axis2//"' sweeps the same "// &
                             trim(merge('value        ', 'initial value', &
                                        pendulum_axis(cfg, cfg%axis2)))// &
                             " as axis1 '"//cfg%axis1//"'")
         else if (real(cfg%n1, dp)*real(cfg%n2, dp) > real(max_sweep_points, dp)) then
            call fatal_error(error, 'invalid n1, n2: n1*n2 = '// &
                             sci(real(cfg%n1, dp)*real(cfg%n2, dp))//' points, at most '// &
                             sci(real(max_sweep_points, dp))//' (fewer points)')
         else
            call check_pixel_parameters(cfg, error)
         end if
      else if (cfg%ic_angles /= 'q' .and. cfg%ic_angles /= 'theta') then
         call fatal_error(error, "invalid ic_angles: '"//cfg%ic_angles// &
                          "' (accepted: q, theta)")
      end if
      if (.not. allocated(error)) call check_sweep_forms(cfg, error)
      if (allocated(error)) return
      ! the device's name and the GPU's repacking (the GPU itself: resolve_device)
      cfg%device = to_lower(cfg%device)
      if (cfg%device /= 'cpu' .and. cfg%device /= 'gpu' .and. cfg%device /= 'auto') then
         call fatal_error(error, "invalid device: '"//printable(cfg%device)// &
                          "' (accepted: cpu, gpu, auto)")
      else if (cfg%gpu_repack < 0) then
         call fatal_error(error, 'invalid gpu_repack: '//to_str(cfg%gpu_repack)// &
                          ' must be an integer from 0 (one launch) to '//to_str(huge(1)))
      end if
   end subroutine validate_sweep

   !> The Lyapunov exponent of a sweep is the double pendulum's kernel's: refused, in
   !> one line saying why, for another number of links, another model (motors, damping,
   !> a moving support, torques: the per-trajectory path has no exponent) or an axis by
   !> name (g, com1: one trajectory at a time).
   subroutine check_sweep_lyapunov(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, lyapunov true
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: field, why
      why = ''
      if (cfg%run%links /= 2) then
         why = ' with '//to_str(cfg%run%links)//' links (dpend sweep computes it for ' &
               //'links = 2 only; dpend lyapunov computes it for any N)'
      else if (.not. kernel_pendulum(cfg)) then
         why = ' with the '//cfg%run%model%name()//' (dpend sweep computes it in the ' &
               //'double pendulum''s kernel only; dpend lyapunov computes it for this model)'
      else if (grid_mode(cfg)) then
         if (model_axis(cfg, cfg%axis2)) field = cfg%axis2
         if (model_axis(cfg, cfg%axis1)) field = cfg%axis1
         if (allocated(field)) why = ' with an axis by name ('//field//'): such a map ' &
            //'runs one trajectory at a time, without the exponent (the double ' &
            //'pendulum''s kernel computes it over initial values and m1 m2 l1 l2 m2/m1 l2/l1)'
      end if
      if (len(why) == 0) return
      field = 'lyapunov: true'
      if (cfg%indicator == 'lambda1') field = 'indicator: lambda1'
      call fatal_error(error, 'invalid '//field//why)
   end subroutine check_sweep_lyapunov

   !> Refuse two settings of one quantity, from flags or the namelist
   !> file: a fixed initial value or parameter and a grid axis that sweeps it (q1 or
   !> theta1 with axis theta1 or q1, m2 with axis m2/m1, ...); the grid's axes and
   !> ranges or fixed initial values with a list (ic_file), which gives every
   !> initial state; a stop rule with an indicator or the Lyapunov exponent, which
   !> integrate every trajectory to t_end. Lists (--q, --m) may hold the swept entry:
   !> of more than two links they are the only way to fix the others.
   subroutine check_sweep_forms(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, validated
      type(error_t), allocatable, intent(out) :: error  !! two forms of one quantity
      character(len=:), allocatable :: axis, fixed, c
      character(len=*), parameter :: initial = 'q1 q2 w1 w2'
      integer :: k
      if (len_trim(cfg%stop_at_given) > 0 .and. cfg%stop_at /= 'end' .and. &
          (cfg%lyapunov .or. indicator_vectors(cfg) > 0)) then
         fixed = 'lyapunov'
         if (cfg%indicator /= 'flip') fixed = "indicator '"//cfg%indicator//"'"
         call fatal_error(error, 'invalid '//cfg%stop_at_given//": '"//cfg%stop_at// &
                          "' given with "//fixed//' (it integrates every trajectory to ' &
                          //'t_end: stop_at end); give one of them')
         return
      end if
      if (.not. grid_mode(cfg)) then
         if (len_trim(cfg%grid_given) > 0) then
            fixed = first_word(adjustl(cfg%grid_given))
            call fatal_error(error, 'invalid '//fixed//': given with ic_file (a list ' &
                             //'sweep integrates the initial states of --ic-file; axes and ' &
                             //'ranges describe a grid); give one of them')
            return
         end if
         do k = 1, 4
            fixed = given_form(word(initial, k))
            if (len(fixed) > 0) then
               call fatal_error(error, 'invalid '//fixed//': given with ic_file (the ' &
                                //'list gives every initial state; ' &
                                //'the fixed value would be ignored); give one of them')
               return
            end if
         end do
         do k = 3, 4   ! the lists q and w (--q, --w, namelist q w) likewise
            if (cfg%run%list_size(k) == 0) cycle
            call fatal_error(error, 'invalid '//trim(merge('q', 'w', k == 3))//': given ' &
                             //'with ic_file (the list gives every initial state; the ' &
                             //'fixed values would be ignored); give one of them')
            return
         end do
         return
      end if
      do k = 1, 2
         axis = cfg%axis1
         if (k == 2) axis = cfg%axis2
         c = achar(iachar('0') + k)
         fixed = given_form(fixed_key(axis))
         if (len(fixed) == 0 .and. model_axis(cfg, axis)) then   ! a parameter by name
            if (allocated(cfg%run%given)) then
               ! the name, or the first link's form of a mass (m1 for m)
               if (index(cfg%run%given, ' '//axis//' ') > 0 .or. &
                   index(cfg%run%given, ' '//axis//'1 ') > 0) fixed = axis
            end if
         end if
         if (len(fixed) > 0) then
            call fatal_error(error, 'invalid '//fixed//": axis"//c//" '"//axis// &
                             "' sweeps the value it fixes (the axis would replace it); " &
                             //'give one of them')
            return
         end if
      end do
   contains
      !> The scalar key (q1 q2 w1 w2 m1 m2 l1 l2) whose value `axis` sweeps, '' if none.
      function fixed_key(axis) result(key)
         character(len=*), intent(in) :: axis
         character(len=:), allocatable :: key
         integer :: var, n
         key = ''
         select case (axis_parameter(axis))
         case (1); key = 'm1'
         case (2, 5); key = 'm2'
         case (3); key = 'l1'
         case (4, 6); key = 'l2'
         case default
            n = cfg%run%links
            if (.not. flip_model(cfg)) n = cfg%run%model%n_dof()
            var = sweep_variable(cfg, axis)
            if (var == 1 .or. var == 2) key = 'q'//achar(iachar('0') + var)
            if (var == n + 1 .or. var == n + 2) key = 'w'//achar(iachar('0') + var - n)
         end select
      end function fixed_key
      !> How `key` was given: '--q1' or '--theta1' (flags), 'q1 [&initial]' (the
      !> file), '' if not given.
      function given_form(key) result(form)
         character(len=*), intent(in) :: key
         character(len=:), allocatable :: form
         character(len=:), allocatable :: seen
         form = ''
         if (len(key) == 0) return
         seen = ' '
         if (allocated(cfg%run%flags_seen)) seen = cfg%run%flags_seen
         if (index(seen, ' --'//key//' ') > 0) then
            form = '--'//key
         else if (key(1:1) == 'q' .and. index(seen, ' --theta'//key(2:2)//' ') > 0) then
            form = '--theta'//key(2:2)
         else if (allocated(cfg%run%nml_given)) then
            if (index(cfg%run%nml_given, ' '//key//' ') > 0) then
               form = key//' [&initial]'
               if (key(1:1) == 'm' .or. key(1:1) == 'l') form = key//' [&pendulum]'
            end if
         end if
      end function given_form
      !> The k-th blank-separated word of `t`.
      function word(t, k) result(w)
         character(len=*), intent(in) :: t
         integer, intent(in) :: k
         character(len=:), allocatable :: w
         integer :: j
         w = adjustl(t)
         do j = 2, k
            w = adjustl(w(index(w, ' ') + 1:))
         end do
         w = first_word(w)
      end function word
      pure function first_word(t) result(w)
         character(len=*), intent(in) :: t
         character(len=:), allocatable :: w
         w = t(:index(t//' ', ' ') - 1)
      end function first_word
   end subroutine check_sweep_forms

   !> What a sweep of a model without flips (the elastic pendulum) refuses: the flip
   !> map (indicator flip, the default), the Lyapunov exponent of the batch kernel and
   !> angles of a list measured as theta.
   subroutine check_model_sweep(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: name
      name = cfg%run%spec%model_name()
      if (cfg%indicator == 'flip') then
         call fatal_error(error, "invalid indicator: 'flip' does not apply to model " &
                          //name//' (no rods to flip: no flip stop rules, t_flip or flip ' &
                          //'energy bound; use --indicator megno, fli, sali or gali2)')
      else if (cfg%lyapunov) then
         call fatal_error(error, 'invalid '//trim(merge('indicator: lambda1', &
                          'lyapunov: true    ', cfg%indicator == 'lambda1'))// &
                          ' with model '//name//' (dpend sweep computes it for the ' &
                          //'pendulum only; use --indicator megno, fli, sali or gali2, ' &
                          //'or dpend lyapunov)')
      else if (cfg%ic_angles_given .and. cfg%ic_angles /= 'q') then
         call fatal_error(error, "invalid ic_angles: '"//printable(cfg%ic_angles)// &
                          "' with model "//name//' (accepted: q; a list holds its ' &
                          //'coordinates and rates)')
      end if
   end subroutine check_model_sweep

   !> The axes of a model without flips: known names (`sweep_variable`), two
   !> different values, n and the range as every axis, and the grid's four corners
   !> (the extremes of each swept value) within the model (`check_state`).
   subroutine check_model_axes(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, model built
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: names
      real(dp), allocatable :: y(:)
      integer :: k, i, j, var(2), n(2)
      real(dp) :: lo(2), hi(2), x1, x2
      character(len=1) :: c
      character(len=:), allocatable :: axis
      character(len=32) :: pnames(2)   ! the parameter of each parameter axis, else ''
      class(model_t), allocatable :: model
      var = [sweep_variable(cfg, cfg%axis1), sweep_variable(cfg, cfg%axis2)]
      n = [cfg%n1, cfg%n2]; lo = [cfg%min1, cfg%min2]; hi = [cfg%max1, cfg%max2]
      names = 'q1..q'//to_str(cfg%run%model%n_dof())//', w1..w'// &
              to_str(cfg%run%model%n_dof())//', '//coordinate_names()//', '// &
              model_axis_names(cfg)
      do k = 1, 2
         c = achar(iachar('0') + k)
         axis = cfg%axis1
         if (k == 2) axis = cfg%axis2
         if (var(k) == 0 .and. model_axis(cfg, axis)) var(k) = -k   ! a parameter axis
         if (var(k) == 0) then
            ! theta1, theta2 are also the defaults: the pendulum's, no ranges to keep
            call fatal_error(error, 'invalid axis'//c//": '"//printable(axis)// &
                             "' (accepted for model "//cfg%run%spec%model_name()//': '// &
                             names//'; it has no default axes: give --axis1 --axis2 and ' &
                             //'their ranges)')
         else if (n(k) < 1 .or. n(k) > max_axis_points) then
            call fatal_error(error, 'invalid n'//c//': '//to_str(n(k))//' must be an ' &
                             //'integer from 1 to '//to_str(max_axis_points)// &
                             ' (points on axis '//c//')')
         else if (.not. (ieee_is_finite(lo(k)) .and. ieee_is_finite(hi(k)))) then
            call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
         else
            call check_grid_range(axis, c, n(k), lo(k), hi(k), error)
         end if
         if (allocated(error)) return
      end do
      if (var(1) == var(2) .or. cfg%axis1 == cfg%axis2) then
         call fatal_error(error, "invalid axis2: '"//cfg%axis2//"' sweeps the same "// &
                          "value as axis1 '"//cfg%axis1//"'")
         return
      else if (real(cfg%n1, dp)*real(cfg%n2, dp) > real(max_sweep_points, dp)) then
         call fatal_error(error, 'invalid n1, n2: n1*n2 = '// &
                          sci(real(cfg%n1, dp)*real(cfg%n2, dp))//' points, at most '// &
                          sci(real(max_sweep_points, dp))//' (fewer points)')
         return
      end if
      pnames = ''
      if (var(1) < 0) pnames(1) = cfg%axis1
      if (var(2) < 0) pnames(2) = cfg%axis2
      do j = 1, 2
         do i = 1, 2
            x1 = merge(lo(1), hi(1), i == 1); x2 = merge(lo(2), hi(2), j == 1)
            y = [cfg%run%q0(), cfg%run%w0()]
            if (var(1) > 0) y(var(1)) = x1
            if (var(2) > 0) y(var(2)) = x2
            if (any(var < 0)) then   ! the pixel's model (the parameters' ranges)
               call pixel_model_named(cfg, pnames, [x1, x2], model, error)
               if (.not. allocated(error)) &
                  call model%check_state(y(:size(y)/2), y(size(y)/2 + 1:), error)
            else
               call cfg%run%model%check_state(y(:size(y)/2), y(size(y)/2 + 1:), error)
            end if
            if (allocated(error)) then
               error%message = 'invalid min1, max1, min2, max2: the pixel at ('// &
                               real_str(x1)//', '//real_str(x2)//') is refused: '// &
                               error%message
               return
            end if
         end do
      end do
   contains
      !> 'r phi rdot phidot'.
      function coordinate_names() result(t)
         character(len=:), allocatable :: t, cname, units, punits
         integer :: i
         t = ''
         do i = 1, cfg%run%model%n_dof()
            call cfg%run%model%coordinate(i, cname, units, punits)
            t = t//cname//' '
         end do
         do i = 1, cfg%run%model%n_dof()
            call cfg%run%model%coordinate(i, cname, units, punits)
            t = t//cname//'dot '
         end do
         t = trim(t)
      end function coordinate_names
   end subroutine check_model_axes

   !> True if two axes set the same value: the same initial value, the same
   !> parameter, or m2 and m2/m1, l2 and l2/l1.
   pure logical function same_value(a1, a2, links)
      character(len=*), intent(in) :: a1, a2  !! axis names
      integer, intent(in) :: links            !! number of links N
      integer :: p1, p2
      p1 = axis_parameter(a1); p2 = axis_parameter(a2)
      same_value = axis_variable(a1, links) == axis_variable(a2, links) .and. p1 == p2
      if (min(p1, p2) == 2 .and. max(p1, p2) == 5) same_value = .true.
      if (min(p1, p2) == 4 .and. max(p1, p2) == 6) same_value = .true.
   end function same_value

   !> The parameters of the pixels at the four corners of a grid (the extremes: each
   !> is monotonic in either axis value) within the limits of every command, and,
   !> for N links, a chain the model accepts.
   subroutine check_pixel_parameters(cfg, error)
      type(sweep_config_t), intent(in) :: cfg           !! configuration, axes checked
      type(error_t), allocatable, intent(out) :: error  !! a corner out of range
      integer :: p1, p2, i, j
      real(dp) :: p(4), x1, x2
      character(len=*), parameter :: what = 'min1, max1, min2, max2'
      class(model_t), allocatable :: model
      logical :: named
      p1 = axis_parameter(cfg%axis1); p2 = axis_parameter(cfg%axis2)
      named = pendulum_axis(cfg, cfg%axis1) .or. pendulum_axis(cfg, cfg%axis2)
      if (p1 == 0 .and. p2 == 0 .and. .not. named) return
      ! the com and inertia given would not follow a swept mass or length (the
      ! bodies --body rod and point do)
      if ((p1 > 0 .or. p2 > 0) .and. &
          (cfg%run%extra%find('com') > 0 .or. cfg%run%extra%find('inertia') > 0)) then
         call fatal_error(error, 'invalid axis1, axis2: a mass or length axis sweeps ' &
                          //'uniform rods or point masses only (the com and inertia ' &
                          //'given would not follow it); sweep the initial values instead')
         return
      end if
      do j = 1, 2
         do i = 1, 2
            x1 = merge(cfg%min1, cfg%max1, i == 1)
            x2 = merge(cfg%min2, cfg%max2, j == 1)
            if (named) then   ! every parameter's range from the catalogue (the factory)
               call pixel_model_axes(cfg, pendulum_param_names(cfg), &
                                     pendulum_param_values(cfg, pendulum_axis(cfg, cfg%axis1), &
                                                           pendulum_axis(cfg, cfg%axis2), x1, &
                                                           x2), model, error)
               if (allocated(error)) then
                  error%message = 'invalid '//what//': the pixel at ('//real_str(x1)//', ' &
                                  //real_str(x2)//') is refused: '//error%message
                  return
               end if
               if (p1 == 0 .and. p2 == 0) cycle
            end if
            p = pixel_parameters(cfg, p1, x1, p2, x2)
            call check_parameter(parameter_mass, what//' (m1 of a pixel)', p(1), error)
            if (.not. allocated(error)) call check_parameter(parameter_mass, &
                                                             what//' (m2 of a pixel)', p(2), error)
            if (.not. allocated(error)) call check_parameter(parameter_length, &
                                                             what//' (l1 of a pixel)', p(3), error)
            if (.not. allocated(error)) call check_parameter(parameter_length, &
                                                             what//' (l2 of a pixel)', p(4), error)
            if (allocated(error)) return
            call pixel_model(cfg, p, model, error)
            if (allocated(error)) then
               error%message = 'invalid '//what//': the pixel at ('//real_str(x1)//', '// &
                               real_str(x2)//') is refused: '//error%message
               return
            end if
         end do
      end do
   end subroutine check_pixel_parameters

   !> Check one axis: a known name, n >= 1, finite min <= max (min < max if n > 1).
   subroutine check_axis(name, k, n, lo, hi, links, error, named)
      character(len=*), intent(in) :: name              !! axis name
      integer, intent(in) :: k                          !! 1 or 2
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      integer, intent(in) :: links                      !! number of links N
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      !> a parameter by name (`pendulum_axis`): n and the range as any axis; its
      !> values' range from the catalogue (`check_pixel_parameters`)
      logical, intent(in) :: named
      character(len=1) :: c
      character(len=5) :: unit
      real(dp) :: bound
      integer :: var
      c = achar(iachar('0') + k)
      var = axis_variable(name, links)
      if (var == 0 .and. axis_parameter(name) > 0) then
         call check_param_axis(name, k, n, lo, hi, links, error)
         return
      end if
      if (named) then
         if (n < 1 .or. n > max_axis_points) then
            call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer ' &
                             //'from 1 to '//to_str(max_axis_points)//' (points on axis '//c//')')
         else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
            call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
         else
            call check_grid_range(name, c, n, lo, hi, error)
         end if
         return
      end if
      ! the angles' and angular velocities' ranges of every command (dpend_limits)
      bound = max_angle
      unit = 'rad'
      if (var > links) then
         bound = max_angular_velocity
         unit = 'rad/s'
      end if
      if (var == 0 .and. not_an_axis(name)) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: " &
                          //accepted_axes(links)//'; damping, friction, the support''s ' &
                          //'motion and the motors are not axes: a map keeps them fixed, ' &
                          //'given as in dpend simulate)')
      else if (var == 0) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: " &
                          //accepted_axes(links)//')'//did_you_mean(name, accepted_axes(2), '; '))
      else if (n < 1 .or. n > max_axis_points) then
         call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer from 1' &
                          //' to '//to_str(max_axis_points)//' (points on axis '//c//')')
      else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
      else if (max(abs(lo), abs(hi)) > bound) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': '//sci(lo)//' .. ' &
                          //sci(hi)//' is outside ['//sci(-bound)//', '//sci(bound)// &
                          '] ('//trim(unit)//')')
      else
         call check_grid_range(name, c, n, lo, hi, error)
      end if
   end subroutine check_axis

   !> Check a parameter axis: two or more links, n as any axis, finite 0 < min <= max
   !> (min < max if n > 1); the pixels' parameters are checked by
   !> `check_pixel_parameters`.
   subroutine check_param_axis(name, k, n, lo, hi, links, error)
      character(len=*), intent(in) :: name              !! axis name
      integer, intent(in) :: k                          !! 1 or 2
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      integer, intent(in) :: links                      !! number of links N
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      character(len=1) :: c
      c = achar(iachar('0') + k)
      if (links < 2) then
         call fatal_error(error, 'invalid axis'//c//": '"//printable(name)//"' (accepted: "// &
                          accepted_axes(links)//'; parameter axes need 2 or more links)')
      else if (n < 1 .or. n > max_axis_points) then
         call fatal_error(error, 'invalid n'//c//': '//to_str(n)//' must be an integer from 1' &
                          //' to '//to_str(max_axis_points)//' (points on axis '//c//')')
      else if (.not. (ieee_is_finite(lo) .and. ieee_is_finite(hi))) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': must be finite')
      else if (.not. (lo > 0.0_dp)) then
         call fatal_error(error, 'invalid min'//c//': '//sci(lo)//' must be > 0 (axis '// &
                          name//')')
      else
         call check_grid_range(name, c, n, lo, hi, error)
      end if
   end subroutine check_param_axis

   !> The checks that every axis shares once its own range holds: max at most 1e12
   !> (the pixels' own limits are checked later; this bound keeps their products,
   !> ratio times mass or length, far from overflow), min <= max, and a non-empty
   !> grid.
   subroutine check_grid_range(name, c, n, lo, hi, error)
      character(len=*), intent(in) :: name              !! axis name
      character(len=1), intent(in) :: c                 !! '1' or '2'
      integer, intent(in) :: n                          !! points
      real(dp), intent(in) :: lo, hi                    !! range
      type(error_t), allocatable, intent(out) :: error  !! what is wrong
      if (hi > 1e12_dp) then
         call fatal_error(error, 'invalid max'//c//': '//sci(hi)//' must be at most 1e12 '// &
                          '(axis '//name//')')
      else if (lo > hi) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': min'//c//' = ' &
                          //real_str(lo)//' > max'//c//' = '//real_str(hi))
      else if (n > 1 .and. .not. (lo < hi)) then
         call fatal_error(error, 'invalid min'//c//', max'//c//': the grid is empty, need min' &
                          //c//' < max'//c//' when n'//c//' > 1')
      end if
   end subroutine check_grid_range
   !> The horizon and the step in both units: 't_end = 100 sqrt(l1/g) =
   !> 31.94 s, dt = 0.01 sqrt(l1/g) = 0.003194 s' (time_unit natural) or 't_end =
   !> 30 s = 93.91 sqrt(l1/g), ...' (s); with an l1 axis the natural unit is the
   !> configured l1's.
   function horizon_text(cfg) result(s)
      type(sweep_config_t), intent(in) :: cfg  !! validated configuration
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nat
      real(dp) :: tn
      tn = natural_time(cfg)
      nat = natural_name(cfg)
      s = 't_end = '//both(cfg%run%t_end)//', dt = '//both(cfg%run%dt)
      if (axis_parameter(cfg%axis1) == 3 .or. axis_parameter(cfg%axis2) == 3) &
         s = s//' ('//nat//' of the configured l1 = '//real_str(cfg%run%l(1))// &
             ' m; l1 is swept)'
   contains
      function both(t) result(b)
         real(dp), intent(in) :: t
         character(len=:), allocatable :: b
         if (trim(cfg%run%time_unit) == 'natural') then
            b = real_str(t)//' '//nat//' = '//real_str(t*tn, 4)//' s'
         else
            b = real_str(t)//' s = '//real_str(t/tn, 4)//' '//nat
         end if
      end function both
   end function horizon_text

   !> The unit of dt and t_end: 's' or the name of the natural unit.
   function unit_name(cfg) result(u)
      type(sweep_config_t), intent(in) :: cfg  !! configuration, model built
      character(len=:), allocatable :: u
      u = 's'
      if (trim(cfg%run%time_unit) == 'natural') u = natural_name(cfg)
   end function unit_name

   !> The accepted axis names for N links, for messages.
   !> `name` (a per-link one with its link number) is a parameter of the pendulum
   !> that its catalogue row marks as no map's axis (damping, friction, the support's
   !> motion: `param_info_t%map_axis`).
   logical function not_an_axis(name)
      character(len=*), intent(in) :: name   !! the axis asked for
      type(model_info_t), allocatable :: models(:)
      integer :: i, m
      not_an_axis = .false.
      models = model_catalogue()
      m = find_model(models, 'pendulum')
      do i = 1, size(models(m)%params)
         associate (p => models(m)%params(i))
            if (p%map_axis) cycle
            ! 'damping2', 'coulomb_speed', 'support_ax': the word before a link number or '_'
            if (lead(name) == lead(p%name)) not_an_axis = .true.
         end associate
      end do
   contains
      !> The leading word of a name: up to its first '_', without a link number.
      pure function lead(x) result(w)
         character(len=*), intent(in) :: x
         character(len=:), allocatable :: w
         w = x
         if (index(w, '_') > 0) w = w(:index(w, '_') - 1)
         w = w(:verify(w, '0123456789', back=.true.))
      end function lead
   end function not_an_axis

   function accepted_axes(links) result(s)
      integer, intent(in) :: links  !! number of links N
      character(len=:), allocatable :: s
      character(len=:), allocatable :: n
      n = to_str(links)
      select case (links)
      case (1); s = 'theta1 q1 w1'//pendulum_axis_text(1)//' for 1 link'
      case (2); s = axis_names//' '//param_axis_names//pendulum_axis_text(2)
      case default
         s = 'theta1..theta'//n//' q1..q'//n//' w1..w'//n//' '//param_axis_names// &
             pendulum_axis_text(links)//' for '//n//' links'
      end select
   end function accepted_axes
end module dpend_sweep_settings
