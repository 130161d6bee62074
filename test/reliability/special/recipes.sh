#!/usr/bin/env bash
# Special reliability test: the three recipes of docs/architecture.md, tried on a
# scratch copy of the tree. It copies the tree (git's tracked and untracked files,
# not build/) into the scratch directory and follows each recipe literally:
#   "How to add a model": src/models/dpend_simple.f90 (the simple pendulum: a point
#     mass on a massless rod, q = angle from the horizontal x axis, hanging -pi/2,
#     parameters m, l, g), the factory's row (a `simple_info` catalogue function and
#     one `case` in `build` of src/models/dpend_model_factory.f90);
#   "How to add a method": src/integrators/dpend_heun.f90 (Heun's method, the
#     explicit trapezoid, order 2), one record in dpend_method_registry.f90
#     (n_methods one more) and one `case` in new_integrator (dpend_methods.f90);
#   "The command shape": src/commands/dpend_time_unit_command.f90 (`dpend
#     time-unit [--model NAME]`, the natural time unit of a model's defaults) and
#     one row of the command table in app/main.f90.
# The edits of existing files are small text insertions at anchors; an anchor that
# is not found exactly once fails with one line naming the file and the step (the
# recipe is stale: update docs/architecture.md and this test). Then it builds the
# copy (debug flags, `fpm build --verbose`: no compiler warning in a new or edited
# file), and checks, one line per failure: `dpend models` lists the model; the
# catalogue walk (every_model_command.sh, DPEND_MODELS=simple) passes on it; `dpend
# methods` lists heun and `simulate --method heun` converges with order 2 (final
# state against an rk4 reference at steps h and h/2; the run starts at the state
# given); the unit suites `registry`, `factory` and every suite whose tests walk the
# registry or the catalogue (chain, damping, elastic, study) pass on the copy with no
# test edited; `dpend time-unit` prints sqrt(l/g) of the model, its --help exits 0
# and an unknown flag is refused in one line (exit 2); `dpend --help` lists the
# command; scripts/check_layers.sh accepts the copy.
# About 1 minute on 2 cores, most of it the copy's debug build (library and tests).
# Environment (set by the reliability runner): DPEND (unused: the test builds its own
# binary), ROOT, SCRATCH (the cwd). Exit 0: pass, 77: skip (a tool missing), 1: fail.
set -uo pipefail
: "${ROOT:?}" "${SCRATCH:?}"
for tool in gfortran fpm python3 gnuplot h5dump awk; do
  if ! command -v "$tool" > /dev/null 2>&1; then
    echo "SKIP recipes: $tool not installed"
    exit 77
  fi
done
cd "$SCRATCH" || exit 1
T0=$SECONDS
failures=0
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
ok() { printf 'ok   %s\n' "$1"; }

# ---------------------------------------------------------------- the copy
S=$SCRATCH/tree
mkdir -p "$S"
if git -C "$ROOT" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  # tracked and untracked files as they are on disk (not ignored ones: build/)
  (cd "$ROOT" && git ls-files -z --cached --others --exclude-standard |
     while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
     xargs -0 -r cp --parents -t "$S") ||
    { echo "FAIL copying the tree of $ROOT"; exit 1; }
else
  for d in src app test bench mpi scripts data docs fpm.toml; do
    [ -e "$ROOT/$d" ] && cp -r "$ROOT/$d" "$S/"
  done
  rm -rf "$S/build"
fi
for f in fpm.toml src/models/dpend_model_factory.f90 src/integrators/dpend_methods.f90 \
         src/integrators/dpend_method_registry.f90 app/main.f90; do
  [ -f "$S/$f" ] || { echo "FAIL recipe stale: $f is not in the tree"; exit 1; }
done

# ------------------------------------------------- the recipes' new modules
# "How to add a model", step 1: one module, its formulas and the type.
cat > "$S/src/models/dpend_simple.f90" <<'EOF'
!> The simple pendulum (a scratch model of test/reliability/special/recipes.sh,
!> written by following docs/architecture.md, "How to add a model"): a point mass m
!> on a massless rod of length l, hung from the pin A at the origin, gravity g along
!> −y. One coordinate q, the rod's angle from the horizontal x axis,
!> counter-clockwise [rad] (hanging: q = −π/2); the state is y = (q, q̇).
!>
!>   L = m l²/2 q̇² − m g l sin q,  q̈ = −(g/l) cos q,
!>   E = m l²/2 q̇² + m g l sin q,  p = m l² q̇,  H = p²/(2 m l²) + m g l sin q.
!> Small oscillations about q = −π/2 have the period 2π √(l/g).
module dpend_simple
   use dpend_kinds, only: dp
   use dpend_error, only: error_t
   use dpend_limits, only: check_parameter, parameter_mass, parameter_length, &
                           parameter_gravity, check_range, max_angle, max_angular_velocity
   use dpend_model, only: model_t
   implicit none
   private
   public :: simple_t, simple_model

   !> The simple pendulum (SI units); build it with `simple_model`.
   type, extends(model_t) :: simple_t
      real(dp) :: m = 1.0_dp   !! mass of the bob [kg]
      real(dp) :: l = 1.0_dp   !! length of the rod [m]
      real(dp) :: g = 9.8_dp   !! gravitational acceleration [m/s²]
   contains
      procedure :: n_dof => sp_n_dof
      procedure :: name => sp_name
      procedure :: field => sp_field
      procedure :: jacobian => sp_jacobian
      procedure :: energy => sp_energy
      procedure :: energy_scale => sp_energy_scale
      procedure :: potential_energy => sp_potential_energy
      procedure :: kinetic_energy => sp_kinetic_energy
      procedure :: hamiltonian => sp_true
      procedure :: momenta => sp_momenta
      procedure :: velocities => sp_velocities
      procedure :: hamiltonian_value => sp_hamiltonian_value
      procedure :: canonical_field => sp_canonical_field
      procedure :: canonical_jacobian => sp_canonical_jacobian
      procedure :: n_outputs => sp_n_outputs
      procedure :: output_info => sp_output_info
      procedure :: outputs => sp_outputs
      procedure :: n_parameters => sp_n_parameters
      procedure :: parameter => sp_parameter
      procedure :: coordinate => sp_coordinate
      procedure :: coordinates_text => sp_coordinates_text
      procedure :: figure => sp_figure
      procedure :: check_state => sp_check_state
      procedure :: time_unit => sp_time_unit
      procedure :: rest_state => sp_rest_state
   end type simple_t

   !> The writer's per-sample outputs (the chain's layout with one body).
   integer, parameter :: n_out = 5
   character(len=7), parameter :: out_names(n_out) = [character(len=7) :: &
      'rC', 'vC', 'aC', 'F_joint', 'rA']
   character(len=5), parameter :: out_units(n_out) = &
      [character(len=5) :: 'm', 'm/s', 'm/s^2', 'N', 'm']
   integer, parameter :: out_rows(n_out) = [1, 1, 1, 1, 0]
   character(len=64), parameter :: out_text(n_out) = [character(len=64) :: &
      'position of the bob C (x, y)', 'velocity of the bob C (x, y)', &
      'acceleration of the bob C (x, y)', &
      'force of the ground on the rod at A (x, y), also on the bob', &
      'position of the pin A, the support (x, y)']

contains

   !> The simple pendulum with mass m [kg], length l [m] and g [m/s²], each checked
   !> against its range (dpend_limits); the error names the parameter.
   function simple_model(m, l, g, error) result(model)
      real(dp), intent(in) :: m, l, g                   !! parameters [kg, m, m/s²]
      type(error_t), allocatable, intent(out) :: error  !! set when refused
      type(simple_t) :: model                           !! the model
      call check_parameter(parameter_mass, 'm', m, error)
      if (allocated(error)) return
      call check_parameter(parameter_length, 'l', l, error)
      if (allocated(error)) return
      call check_parameter(parameter_gravity, 'g', g, error)
      if (allocated(error)) return
      model%m = m; model%l = l; model%g = g
   end function simple_model

   pure integer function sp_n_dof(self)
      class(simple_t), intent(in) :: self
      sp_n_dof = 1
   end function sp_n_dof

   pure function sp_name(self) result(name)
      class(simple_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'simple pendulum'
   end function sp_name

   pure logical function sp_true(self)
      class(simple_t), intent(in) :: self
      sp_true = .true.
   end function sp_true

   !> (q̇, −(g/l) cos q).
   pure subroutine sp_field(self, t, y, f)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: f(*)
      f(1) = y(2)
      f(2) = -(self%g/self%l)*cos(y(1))
   end subroutine sp_field

   pure subroutine sp_jacobian(self, t, y, jac)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: jac(:, :)
      jac(1:2, 1:2) = 0.0_dp
      jac(1, 2) = 1.0_dp
      jac(2, 1) = (self%g/self%l)*sin(y(1))
   end subroutine sp_jacobian

   pure real(dp) function sp_energy(self, t, y)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      sp_energy = self%kinetic_energy(t, y) + self%potential_energy(t, y)
   end function sp_energy

   !> V = m g l sin q (0 with the rod horizontal) [J].
   pure real(dp) function sp_potential_energy(self, t, y)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      sp_potential_energy = self%m*self%g*self%l*sin(y(1))
   end function sp_potential_energy

   !> T = m l² q̇²/2 [J].
   pure real(dp) function sp_kinetic_energy(self, t, y)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      sp_kinetic_energy = 0.5_dp*self%m*(self%l*y(2))**2
   end function sp_kinetic_energy

   !> |E0|, or m g l when E0 is near 0 (the rule of the other models).
   pure real(dp) function sp_energy_scale(self, e0)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: e0
      real(dp) :: e_ref
      e_ref = self%m*self%g*self%l
      sp_energy_scale = merge(abs(e0), e_ref, abs(e0) >= 1e-3_dp*e_ref)
   end function sp_energy_scale

   pure subroutine sp_momenta(self, t, y, p)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: p(:)
      p(1) = self%m*self%l**2*y(2)
   end subroutine sp_momenta

   pure subroutine sp_velocities(self, t, z, qd)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: qd(:)
      qd(1) = z(2)/(self%m*self%l**2)
   end subroutine sp_velocities

   pure real(dp) function sp_hamiltonian_value(self, t, z) result(h)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      h = 0.5_dp*z(2)**2/(self%m*self%l**2) + self%m*self%g*self%l*sin(z(1))
   end function sp_hamiltonian_value

   !> (p/(m l²), −m g l cos q).
   pure subroutine sp_canonical_field(self, t, z, f)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, z(*)
      real(dp), intent(out) :: f(*)
      f(1) = z(2)/(self%m*self%l**2)
      f(2) = -self%m*self%g*self%l*cos(z(1))
   end subroutine sp_canonical_field

   pure subroutine sp_canonical_jacobian(self, t, z, jac)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, z(:)
      real(dp), intent(out) :: jac(:, :)
      jac(1:2, 1:2) = 0.0_dp
      jac(1, 2) = 1.0_dp/(self%m*self%l**2)
      jac(2, 1) = self%m*self%g*self%l*sin(z(1))
   end subroutine sp_canonical_jacobian

   pure integer function sp_n_outputs(self)
      class(simple_t), intent(in) :: self
      sp_n_outputs = n_out
   end function sp_n_outputs

   subroutine sp_output_info(self, i, name, n_comp, units, description, rows)
      class(simple_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, description
      integer, intent(out) :: n_comp
      integer, intent(out), optional :: rows
      name = trim(out_names(i)); n_comp = 2
      if (present(rows)) rows = out_rows(i)
      units = trim(out_units(i)); description = trim(out_text(i))
   end subroutine sp_output_info

   !> r_C = l u, v_C = l q̇ n, a_C = l q̈ n − l q̇² u (u = (cos q, sin q), n = u turned
   !> by +90°), F01 = m (a_C + g ĵ) (the massless rod passes it to the bob), r_A = 0.
   pure subroutine sp_outputs(self, t, y, f, values)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: t, y(:), f(:)
      real(dp), intent(out) :: values(:)
      real(dp) :: u(2), nv(2)
      u = [cos(y(1)), sin(y(1))]
      nv = [-u(2), u(1)]
      values(1:2) = self%l*u
      values(3:4) = self%l*y(2)*nv
      values(5:6) = self%l*f(2)*nv - self%l*y(2)**2*u
      values(7:8) = self%m*(values(5:6) + [0.0_dp, self%g])
      values(9:10) = 0.0_dp
   end subroutine sp_outputs

   pure integer function sp_n_parameters(self)
      class(simple_t), intent(in) :: self
      sp_n_parameters = 3
   end function sp_n_parameters

   subroutine sp_parameter(self, i, name, value, units)
      class(simple_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units
      real(dp), intent(out) :: value
      select case (i)
      case (1); name = 'm'; value = self%m; units = 'kg'
      case (2); name = 'l'; value = self%l; units = 'm'
      case default; name = 'g'; value = self%g; units = 'm/s^2'
      end select
   end subroutine sp_parameter

   subroutine sp_coordinate(self, i, name, units, momentum_units)
      class(simple_t), intent(in) :: self
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: name, units, momentum_units
      name = 'q1'; units = 'rad'; momentum_units = 'kg m^2/s'
   end subroutine sp_coordinate

   function sp_coordinates_text(self, order) result(text)
      class(simple_t), intent(in) :: self
      integer, intent(in) :: order
      character(len=:), allocatable :: text
      select case (order)
      case (0)
         text = 'q1, the angle of the rod from the horizontal x axis, counter-clockwise, ' &
                //'unwrapped (hanging: q1 = -pi/2)'
      case (1); text = 'q1dot [rad/s]'
      case default; text = 'q1ddot [rad/s^2]'
      end select
   end function sp_coordinates_text

   !> A rod from the pin A to the bob C; the force of the ground on it at A.
   subroutine sp_figure(self, anchor, points, style, forces)
      class(simple_t), intent(in) :: self
      character(len=:), allocatable, intent(out) :: anchor, points, style, forces
      anchor = 'rA'; points = 'rC'; style = 'rods'; forces = 'F_joint'
   end subroutine sp_figure

   !> q1 within ±max_angle rad, w1 within ±max_angular_velocity rad/s.
   subroutine sp_check_state(self, q, qd, error)
      class(simple_t), intent(in) :: self
      real(dp), intent(in) :: q(:), qd(:)
      type(error_t), allocatable, intent(out) :: error
      call check_range('q1', q(1), -max_angle, max_angle, 'rad', error, &
                       'beyond, the rounding of the angle exceeds 1e-10 rad')
      if (allocated(error)) return
      call check_range('w1', qd(1), -max_angular_velocity, max_angular_velocity, 'rad/s', &
                       error, 'keeps energies and momenta finite')
   end subroutine sp_check_state

   !> The natural time unit sqrt(l/g) [s].
   pure subroutine sp_time_unit(self, seconds, name)
      class(simple_t), intent(in) :: self
      real(dp), intent(out) :: seconds
      character(len=:), allocatable, intent(out) :: name
      seconds = sqrt(self%l/self%g)
      name = 'sqrt(l/g)'
   end subroutine sp_time_unit

   !> Hanging: q = −π/2.
   pure subroutine sp_rest_state(self, q)
      class(simple_t), intent(in) :: self
      real(dp), intent(out) :: q(:)
      q = -0.5_dp*acos(-1.0_dp)
   end subroutine sp_rest_state
end module dpend_simple
EOF

# "How to add a method", step 1: a type extending integrator_t that calls only
# model%field.
cat > "$S/src/integrators/dpend_heun.f90" <<'EOF'
!> Heun's method (the explicit trapezoidal rule, order 2; Hairer, Nørsett, Wanner,
!> Solving ODEs I, Table II.1.1): a scratch method of
!> test/reliability/special/recipes.sh, written by following docs/architecture.md,
!> "How to add a method".
!>   k1 = f(t, y),  k2 = f(t + h, y + h k1),  y_new = y + h/2 (k1 + k2).
module dpend_heun
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_state
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite
   implicit none
   private
   public :: heun_t

   !> Heun's method on (q, q̇), fixed steps; dense output: the base Hermite cubic.
   type, extends(integrator_t) :: heun_t
   contains
      procedure :: step => heun_step
      procedure :: name => heun_name
      procedure :: order => heun_order
   end type heun_t

contains

   !> One step of size h (stage vectors on the stack: no allocation per step).
   subroutine heun_step(self, model, t, y, h, stat)
      class(heun_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model   !! the system
      real(dp), intent(inout) :: t          !! time [s]
      real(dp), intent(inout) :: y(:)       !! state (q, q̇)
      real(dp), intent(inout) :: h          !! step [s]
      integer, intent(out) :: stat          !! status
      real(dp) :: k1(max_state), k2(max_state), ys(max_state), ynew(max_state)
      logical :: ok
      integer :: n
      n = size(y)
      call model%field(t, y, k1)
      ys(:n) = y + h*k1(:n)
      call model%field(t + h, ys, k2)
      self%n_rhs = self%n_rhs + 2
      ynew(:n) = y + (0.5_dp*h)*(k1(:n) + k2(:n))
      call self%record_finite_step(n, t, y, t + h, ynew(:n), ok, f0=k1(:n))
      if (.not. ok) then
         stat = stat_nonfinite
         return
      end if
      y = ynew(:n)
      t = t + h
      self%n_steps = self%n_steps + 1
      stat = stat_ok
   end subroutine heun_step

   pure function heun_name(self) result(name)
      class(heun_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'heun'
   end function heun_name

   pure integer function heun_order(self)
      class(heun_t), intent(in) :: self
      heun_order = 2
   end function heun_order
end module dpend_heun
EOF

# "The command shape": a module with an entry point NAME_command(args, error).
cat > "$S/src/commands/dpend_time_unit_command.f90" <<'EOF'
!> `dpend time-unit [--model NAME]`: the natural time unit of a model built from its
!> defaults (the model's `time_unit`), e.g. 'pendulum: sqrt(l1/g) = 0.319438 s'. A
!> scratch command of test/reliability/special/recipes.sh, written by following
!> docs/architecture.md, "The command shape". The entry point is `time_unit_command`.
module dpend_time_unit_command
   use, intrinsic :: iso_fortran_env, only: output_unit
   use dpend_kinds, only: dp
   use dpend_error, only: error_t, fatal_error
   use dpend_cli, only: arg_t, is_long_option, unknown_option_text, real_str
   use dpend_model, only: model_t
   use dpend_model_factory, only: model_spec, new_model, default_model
   use dpend_command_common, only: take_quiet, data_quiet, refusal_line
   implicit none
   private
   public :: time_unit_command, time_unit_option_help

   character(len=*), parameter :: nl = new_line('a')

contains

   !> Help text of `dpend time-unit`.
   function time_unit_option_help() result(s)
      character(len=:), allocatable :: s
      s = 'usage: dpend time-unit [--model NAME]'//nl//nl// &
          'Prints the natural time unit of model NAME (default '//default_model// &
          ') built from'//nl//'its defaults: its name and its value in seconds.'//nl// &
          '  --model NAME      a model of dpend models'//nl//data_quiet
   end function time_unit_option_help

   !> The entry point of `dpend time-unit` (app/main.f90): parse, build, print. A
   !> refusal comes back as `error`, its message the one line 'dpend time-unit: ...'.
   subroutine time_unit_command(args, error)
      type(arg_t), intent(in) :: args(:)                !! the arguments after the name
      type(error_t), allocatable, intent(out) :: error  !! the refusal
      type(arg_t), allocatable :: rest(:)
      class(model_t), allocatable :: model
      character(len=:), allocatable :: name, unit_name
      real(dp) :: seconds
      integer :: i
      call take_quiet(args, rest)
      name = default_model
      i = 1
      do while (i <= size(rest))
         select case (rest(i)%s)
         case ('-h', '--help')
            write (output_unit, '(a)') time_unit_option_help()
            return
         case ('--model')
            if (i == size(rest)) then
               call fatal_error(error, '--model needs a value (a model of dpend models)')
            else
               name = rest(i + 1)%s
               i = i + 1
            end if
         case default
            if (is_long_option(rest(i)%s)) then
               call fatal_error(error, unknown_option_text('time-unit', rest(i)%s, &
                                                           '--model --help --quiet'))
            else
               call fatal_error(error, "unexpected argument '"//rest(i)%s// &
                                "' (dpend time-unit --help)")
            end if
         end select
         if (allocated(error)) then
            call refusal_line(error, 'time-unit')
            return
         end if
         i = i + 1
      end do
      call new_model(model_spec(name), model, error)
      if (allocated(error)) then
         call refusal_line(error, 'time-unit')
         return
      end if
      call model%time_unit(seconds, unit_name)
      write (output_unit, '(a)') name//': '//unit_name//' = '//real_str(seconds)//' s'
   end subroutine time_unit_command
end module dpend_time_unit_command
EOF

# ------------------------------------------ the rows in the existing files
# insert FILE STEP WHAT PATTERN TEXT: insert TEXT into FILE (relative to the copy)
# where the named group `at` of PATTERN (a Python regex, multiline) matches; the
# pattern must match exactly once. TEXT '@NAME' is the snippet file NAME.
# `insert ... --increment`: add 1 to the number the group `n` matches.
cat > "$SCRATCH/insert.py" <<'EOF'
import re, sys
path, step, what, pattern, text = sys.argv[1:6]
if text.startswith('@'):
    text = open(text[1:]).read()
with open(path) as f:
    source = f.read()
found = list(re.finditer(pattern, source, re.M))
if len(found) != 1:
    print(f'FAIL recipe stale ({step}): {path}: no unique place for {what} '
          f'(/{pattern}/ matched {len(found)} times; update docs/architecture.md and '
          'test/reliability/special/recipes.sh)')
    sys.exit(1)
m = found[0]
if text == '--increment':
    source = source[:m.start('n')] + str(int(m.group('n')) + 1) + source[m.end('n'):]
else:
    source = source[:m.start('at')] + text + source[m.start('at'):]
with open(path, 'w') as f:
    f.write(source)
EOF
edits_ok=1
insert() {
  (cd "$S" && python3 "$SCRATCH/insert.py" "$@") || { edits_ok=0; failures=$((failures + 1)); }
}

# "How to add a model", step 2: one row to the factory, its description in
# model_catalogue (a <name>_info function) and one `case` in `build`.
cat > "$SCRATCH/simple_info.f90" <<'EOF'
   !> The simple pendulum (test/reliability/special/recipes.sh): a point mass on a
   !> massless rod.
   function simple_info() result(info)
      type(model_info_t) :: info
      info%name = 'simple'
      info%summary = 'a point mass m on a massless rod of length l hung from the pin A ' &
                     //'(the recipes test''s scratch model)'
      info%coordinates = 'q1: angle of the rod from the horizontal x axis, counter-' &
                         //'clockwise (rad); hanging: q1 = -pi/2'
      info%supports = 'Hamiltonian structure (every method applies); no damping, ' &
                      //'driving, SIMD lanes or Poincare sections'
      info%params = [ &
         param('m', 'kg', 'mass of the bob', min_mass, max_mass, 1.0_dp, 1), &
         param('l', 'm', 'length of the rod', min_length, max_length, 1.0_dp, 1), &
         param('g', 'm/s^2', 'gravitational acceleration (-y)', min_g, max_g, 9.8_dp, 1)]
   end function simple_info

EOF
cat > "$SCRATCH/simple_case.f90" <<'EOF'
      case ('simple')
         block
            type(simple_t) :: simple
            real(dp), allocatable :: m(:), l(:), g(:)
            m = value_of(spec, info, 'm', 1); l = value_of(spec, info, 'l', 1)
            g = value_of(spec, info, 'g', 1)
            simple = simple_model(m(1), l(1), g(1), error)
            if (.not. allocated(error)) allocate (model, source=simple)
         end block
EOF
F=src/models/dpend_model_factory.f90
insert $F 'model, step 2' 'the use of the module' \
  '^module dpend_model_factory\n(?P<at>)' $'   use dpend_simple, only: simple_t, simple_model\n'
insert $F 'model, step 2' 'the row of model_catalogue' \
  '^[ \t]*models = \[[^\]]*_info\(\)(?P<at>)\]' ', simple_info()'
insert $F 'model, step 2' 'the <name>_info function' \
  '(?P<at>)^end module dpend_model_factory' "@$SCRATCH/simple_info.f90"
insert $F 'model, step 2' "the case of build" \
  '^[ \t]*select case \(info%name\)\n(?P<at>)' "@$SCRATCH/simple_case.f90"

# "How to add a method", step 2: one row of dpend_method_registry (n_methods one
# more) and its construction in the factory (new_integrator).
cat > "$SCRATCH/heun_row.f90" <<'EOF'
, &
      method_info_t(name='heun', order=2, h_min=2.5e-3_dp, h_max=1.0e-2_dp, &
                    cost=0.15e-6_dp, group='rk', colour='#e377c2', &
                    description="Heun's method (explicit trapezoid), 2 stages")
EOF
R=src/integrators/dpend_method_registry.f90
insert $R 'method, step 2' 'the count n_methods' \
  'integer, parameter :: n_methods = (?P<n>[0-9]+)' --increment
insert $R 'method, step 2' 'the record at the end of method_table' \
  'method_table\(n_methods\) = \[ &\n(?:[^\n]*\n)*?[^\n]*\)(?P<at>)\]' \
  "$(cat "$SCRATCH/heun_row.f90")"   # $(...) drops the last line end: ')]' stays
M=src/integrators/dpend_methods.f90
insert $M 'method, step 2' 'the use of the module' \
  '^module dpend_methods\n(?P<at>)' $'   use dpend_heun, only: heun_t\n'
insert $M 'method, step 2' 'the case of new_integrator' \
  '^[ \t]*select case \(key\)\n(?P<at>)' $'      case (\'heun\')\n         allocate (heun_t :: integ)\n'

# "The command shape": a row of the table in app/main.f90 (name, line of the usage
# text, entry point).
A=app/main.f90
insert $A 'command' 'the use of the module' \
  '^module dpend_command_table\n(?P<at>)' \
  $'   use dpend_time_unit_command, only: time_unit_command\n'
insert $A 'command' "the row of command_table (before 'version')" \
  "(?P<at>)^[ \\t]*command_t\\('version'," \
  $'         command_t(\'time-unit\', \'the natural time unit of a model\'\'s defaults\', &\n                   time_unit_command), &\n'
if [ $edits_ok = 0 ]; then
  echo "recipes: $failures edits failed, nothing built; $((SECONDS - T0)) s"
  exit 1
fi
NEW_FILES="src/models/dpend_simple.f90 src/integrators/dpend_heun.f90"
NEW_FILES+=" src/commands/dpend_time_unit_command.f90 $F $R $M $A"

# --------------------------------------------------------------- the build
cd "$S" || exit 1
# shellcheck disable=SC1091
. scripts/flags.sh
t_build=$SECONDS
if ! fpm build --flag "$DEBUG_FLAGS" --verbose > "$SCRATCH/build.log" 2>&1; then
  grep -E -A4 '^[^ ]+\.(f90|c):[0-9]+:' "$SCRATCH/build.log" | head -n 30
  echo "FAIL build: the copy with the recipes' files does not build (lines above)"
  exit 1
fi
# every compiler warning with the file it is in (gfortran names the file a few
# lines before 'Warning:')
warnings=$(awk '/^[^ ]+\.(f90|F90|inc|c):[0-9]+:/ { split($0, a, ":"); file = a[1]; line = a[2]
                                                   while (file ~ /^\.\//) file = substr(file, 3) }
                /(Warning|warning):/ { print file ":" line ": " $0 }' "$SCRATCH/build.log" |
           sed "s#^$S/##" | LC_ALL=C sort -u)
while IFS= read -r w; do
  [ -n "$w" ] || continue
  if [[ " $NEW_FILES " == *" ${w%%:*} "* ]]; then fail "build: warning in a recipe's file: $w"
  else echo "note: warning outside the recipes' files: $w"; fi
done <<< "$warnings"
BIN=$S/$(fpm run dpend --flag "$DEBUG_FLAGS" --runner echo 2> /dev/null | tail -n 1)
[ -x "$BIN" ] || { echo "FAIL build: no dpend binary ($BIN)"; exit 1; }
ok "build: debug, no warning in the recipes' files ($((SECONDS - t_build)) s)"
cd "$SCRATCH" || exit 1
export DPEND_ROOT=$S

# ------------------------------------------------------------- the model
if "$BIN" models > models.txt 2>&1 && grep -q '^simple: ' models.txt; then
  ok "dpend models lists the model simple"
else
  fail "dpend models does not list the model simple: $(head -n 1 models.txt)"
fi
mkdir -p walk
t_walk=$SECONDS
if (cd walk && DPEND=$BIN ROOT=$S SCRATCH=$SCRATCH/walk DPEND_MODELS=simple \
      timeout -k 10 300 bash "$S/test/reliability/special/every_model_command.sh") \
    > walk.log 2>&1 < /dev/null; then
  ok "catalogue walk on simple: $(tail -n 1 walk.log) ($((SECONDS - t_walk)) s)"
else
  while IFS= read -r line; do fail "catalogue walk: ${line#FAIL }"; done < <(grep '^FAIL' walk.log)
  grep -q '^FAIL' walk.log || fail "catalogue walk: $(tail -n 1 walk.log)"
fi

# ------------------------------------------------------------- the method
# (outputs kept before grep -q reads them: under pipefail, `dpend | grep -q` fails
# when grep exits on its first match while dpend still writes)
names=$("$BIN" methods --names 2>&1)
table=$("$BIN" methods 2>&1)
if grep -qw heun <<< "$names" && grep -qE '^heun +\(q, qdot\) +2 ' <<< "$table"; then
  ok "dpend methods lists heun, order 2"
else
  fail "dpend methods does not list heun with order 2: $names"
fi
# final_state METHOD DT: q and qdot at t = 2 s of the simple pendulum from q = -1
final_state() {
  "$BIN" simulate --model simple --q -1 --w 0.5 --method "$1" --dt "$2" --t-end 2 \
    --output "run_$1_$2.h5" --force --quiet > /dev/null 2> "run_$1_$2.err" &&
  "$BIN" export "run_$1_$2.h5" q qdot 2> /dev/null | tail -n 1
}
ref=$(final_state rk4 0.0001)
first=$("$BIN" export run_rk4_0.0001.h5 q qdot 2> /dev/null | head -n 1)
if LC_ALL=C awk -v f="$first" 'BEGIN { n = split(f, a); exit !(n == 2 && a[1] == -1 && a[2] == 0.5) }'
then ok "simulate --model simple starts at the state given (q, qdot) = (-1, 0.5)"
else fail "simulate --model simple --q -1 --w 0.5: the file starts at (q, qdot) = ($first)"; fi
e1=$(final_state heun 0.01)
e2=$(final_state heun 0.005)
if [ -z "$ref" ] || [ -z "$e1" ] || [ -z "$e2" ]; then
  fail "simulate --method heun: no final state ($(cat run_*.err 2> /dev/null | head -n 1))"
else
  verdict=$(LC_ALL=C awk -v r="$ref" -v a="$e1" -v b="$e2" 'BEGIN {
    split(r, x); split(a, y); split(b, z)
    ea = sqrt((y[1] - x[1])^2 + (y[2] - x[2])^2); eb = sqrt((z[1] - x[1])^2 + (z[2] - x[2])^2)
    p = (eb > 0) ? log(ea / eb) / log(2) : 0
    printf "%s order %.2f (final-state errors %.2e at h = 0.01 s, %.2e at h/2)\n",
      (p > 1.8 && p < 2.2) ? "ok" : "bad", p, ea, eb }')
  if [ "${verdict%% *}" = ok ]; then ok "simulate --method heun: ${verdict#ok }"
  else fail "simulate --method heun: ${verdict#bad }, expected 2"; fi
fi

# --------------------------------------------- the unit suites, no test edited
# registry and factory, and every suite whose tests walk the registry or the
# catalogue (a test/test_*.f90 that uses dpend_method_registry or model_catalogue;
# its suite's name from test/main.f90's `call add('NAME', collect_...)`)
cd "$S" || exit 1
suites=(registry factory)
while IFS= read -r f; do
  while IFS= read -r c; do
    s=$(sed -n "s/^ *call add('\([a-z0-9_]*\)', *$c)\$/\1/p" test/main.f90)
    [ -n "$s" ] && [[ " ${suites[*]} " != *" $s "* ]] && suites+=("$s")
  done < <(sed -n 's/^ *subroutine \(collect_[a-z0-9_]*\).*/\1/p' "$f")
done < <(grep -l -E 'dpend_method_registry|model_catalogue' test/test_*.f90)
t_test=$SECONDS
if fpm test --flag "$DEBUG_FLAGS" -- "${suites[@]}" > "$SCRATCH/unit.log" 2>&1; then
  ok "fpm test -- ${suites[*]}: $(tail -n 1 "$SCRATCH/unit.log") ($((SECONDS - t_test)) s)"
else
  while IFS= read -r line; do fail "unit test ${line#*FAIL }"; done < <(grep -E '^ *FAIL ' "$SCRATCH/unit.log")
  fail "fpm test -- ${suites[*]}: $(grep -E '^[0-9]+ passed' "$SCRATCH/unit.log" | tail -n 1)"
fi
# the recipes wrote nothing under test/: the copy's tests are the tree's
while IFS= read -r f; do
  cmp -s "$ROOT/$f" "$S/$f" || fail "the recipes edited $f"
done < <(cd "$S" && find test -type f \( -name '*.f90' -o -name '*.sh' \))
cd "$SCRATCH" || exit 1

# ------------------------------------------------------------- the command
want=$(LC_ALL=C awk 'BEGIN { printf "%.4f", sqrt(1 / 9.8) }')
out=$("$BIN" time-unit --model simple 2> err.txt)
got=$(printf '%s\n' "$out" | sed -n 's/^simple: sqrt(l\/g) = \([0-9.]*\) s$/\1/p')
if [ -n "$got" ] && [ "$(LC_ALL=C awk -v g="$got" 'BEGIN { printf "%.4f", g }')" = "$want" ]; then
  ok "dpend time-unit --model simple: $out"
else
  fail "dpend time-unit --model simple: '$out' $(head -n 1 err.txt), expected sqrt(l/g) = $want s"
fi
rc=0; "$BIN" time-unit --help > help.txt 2> err.txt || rc=$?
if [ $rc = 0 ] && grep -q '^usage: dpend time-unit' help.txt && grep -q -- '--quiet' help.txt &&
   [ ! -s err.txt ]; then
  ok "dpend time-unit --help"
else
  fail "dpend time-unit --help: exit $rc, $(head -n 1 help.txt) $(head -n 1 err.txt)"
fi
rc=0; "$BIN" time-unit --no-such-flag > out.txt 2> err.txt || rc=$?
if [ $rc = 2 ] && [ "$(grep -c '' err.txt)" = 1 ] && grep -q "^dpend time-unit: .*--no-such-flag" err.txt &&
   [ ! -s out.txt ]; then
  ok "dpend time-unit --no-such-flag refused: $(cat err.txt)"
else
  fail "dpend time-unit --no-such-flag: exit $rc (expected 2), $(grep -c '' err.txt) stderr lines (expected 1): $(head -n 1 err.txt)"
fi
rc=0; "$BIN" time-unit --model nosuch > out.txt 2> err.txt || rc=$?
if [ $rc = 2 ] && [ "$(grep -c '' err.txt)" = 1 ] && grep -q "invalid model" err.txt; then
  ok "dpend time-unit --model nosuch refused: $(cut -c1-100 err.txt)"
else
  fail "dpend time-unit --model nosuch: exit $rc (expected 2): $(head -n 1 err.txt)"
fi
usage=$("$BIN" --help 2>&1)
if grep -q '^  time-unit ' <<< "$usage"; then
  ok "dpend --help lists time-unit"
else
  fail "dpend --help does not list time-unit (the row's line of the usage text)"
fi

# ----------------------------------------------------------------- the floors
if layers=$(bash "$S/scripts/check_layers.sh" "$S" 2>&1); then
  ok "check_layers.sh: the new modules use only their floor and those below"
else
  fail "check_layers.sh on the copy: $(printf '%s\n' "$layers" | grep -v '^ok' | head -n 1)"
fi

echo "recipes: $failures failed; $((SECONDS - T0)) s"
[ $failures = 0 ]
