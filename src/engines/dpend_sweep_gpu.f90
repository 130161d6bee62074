!> The GPU path of `dpend sweep` (docs/gpu.md): the two-link flip map of
!> a block on an NVIDIA GPU through the optional library libdpend_gpu.so
!> (src/gpu/dpend_sweep_kernel.cu, built by scripts/gpu/build_gpu.sh), loaded at run time
!> with dlopen by the C glue (src/io/dpend_posix.c): dpend never links CUDA.
!>
!> `gpu_open` finds, loads and probes the library once (before any work);
!> `gpu_integrate_block` fills a block's `batch_result_t` as `integrate_batch` does
!> for a flip map (same statuses, NaN conventions and results up to rounding: the
!> kernel's per-trajectory step, src/gpu/dpend_gpu_step.h, is a copy of the lanes'
!> formulas in their order).
module dpend_sweep_gpu
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_long_long, c_char, c_null_char
   use, intrinsic :: iso_fortran_env, only: error_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use dpend_kinds, only: dp, i8
   use dpend_pendulum, only: pendulum_t
   use dpend_lane_batch, only: batch_options_t, batch_result_t, stop_end
   use dpend_pendulum_kernel, only: batch_coef_t, batch_coef, flip_energy_bounds, &
      potential_range
   use dpend_pendulum_lanes, only: integrate_batch
   use dpend_os, only: executable_path
   use dpend_error, only: error_t, fatal_error
   use dpend_sweep_settings, only: sweep_config_t, flip_model, grid_mode, axis_parameter, &
      model_axis, kernel_pendulum
   implicit none
   private
   public :: resolve_device
   public :: gpu_open, gpu_library_path, gpu_integrate_block, gpu_kernel_seconds
   public :: gpu_fallback_blocks
   public :: gpu_no_library, gpu_no_device, gpu_ready

   integer, parameter :: gpu_ready = 0       !! loaded and a device found
   integer, parameter :: gpu_no_library = 1  !! no loadable library
   integer, parameter :: gpu_no_device = 2   !! library loaded, no usable GPU

   !> The probe's outcome, kept for later calls (`gpu_open` probes once).
   integer, save :: probed = -1
   character(len=:), allocatable, save :: probed_name, probed_why
   !> Kernel time of the blocks computed so far [s] (cudaEvent timing of the library).
   real(dp), save :: kernel_seconds = 0
   !> Blocks computed on the CPU after the library failed in this run (the file says so).
   integer, save :: fallback_blocks = 0

   interface
      integer(c_int) function c_gpu_load(path, msg, msg_len) bind(C, name='dpend_gpu_load')
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         character(kind=c_char), intent(out) :: msg(*)
         integer(c_int), value :: msg_len
      end function c_gpu_load
      integer(c_int) function c_gpu_probe(count, name, name_len, driver, runtime, msg, &
                                          msg_len) bind(C, name='dpend_gpu_call_probe')
         import :: c_int, c_char
         integer(c_int), intent(out) :: count, driver, runtime
         character(kind=c_char), intent(out) :: name(*), msg(*)
         integer(c_int), value :: name_len, msg_len
      end function c_gpu_probe
      integer(c_int) function c_gpu_run(coef, bounds, escale, h, n_steps, stop_rule, &
                                        steps_per_launch, n, y0, t_flip1, t_flip2, t_flip, &
                                        energy0, energy_error, t_stop, fin, status, steps, &
                                        kernel_ms, launches, msg, msg_len) &
         bind(C, name='dpend_gpu_call_run')
         import :: c_int, c_char, c_double, c_long_long
         real(c_double), intent(in) :: coef(*), bounds(*), y0(*)
         real(c_double), value :: escale, h
         integer(c_long_long), value :: n_steps, steps_per_launch
         integer(c_int), value :: stop_rule, n, msg_len
         real(c_double), intent(out) :: t_flip1(*), t_flip2(*), t_flip(*), energy0(*)
         real(c_double), intent(out) :: energy_error(*), t_stop(*), fin(*), kernel_ms
         integer(c_int), intent(out) :: status(*), steps(*), launches
         character(kind=c_char), intent(out) :: msg(*)
      end function c_gpu_run
   end interface

contains

   !> The library to load: $DPEND_GPU_LIB if set, else libdpend_gpu.so next to the
   !> running executable if there, else build/gpu/libdpend_gpu.so (scripts/gpu/build_gpu.sh's
   !> default) under the current directory.
   function gpu_library_path() result(path)
      character(len=:), allocatable :: path
      character(len=4096) :: env
      character(len=:), allocatable :: exe
      integer :: length, stat, k
      logical :: exists
      call get_environment_variable('DPEND_GPU_LIB', env, length, stat)
      if (stat == 0 .and. length > 0) then
         path = trim(env)
         return
      end if
      exe = executable_path()
      k = index(exe, '/', back=.true.)
      if (k > 0) then
         path = exe(:k)//'libdpend_gpu.so'
         inquire (file=path, exist=exists)
         if (exists) return
      end if
      path = 'build/gpu/libdpend_gpu.so'
   end function gpu_library_path

   !> Load and probe the GPU library (once): `state` gpu_ready (then `name` is the
   !> GPU's name), gpu_no_library or gpu_no_device (then `why` says why, in words).
   subroutine gpu_open(state, name, why)
      integer, intent(out) :: state                          !! gpu_ready, gpu_no_*
      character(len=:), allocatable, intent(out) :: name     !! GPU 0's name
      character(len=:), allocatable, intent(out) :: why      !! why not ready
      character(kind=c_char) :: msg(512), cname(256)
      character(len=:), allocatable :: path
      integer(c_int) :: rc, count, driver, runtime
      logical :: exists
      if (probed < 0) then
         msg = c_null_char
         cname = c_null_char
         path = gpu_library_path()
         probed_name = ''
         inquire (file=path, exist=exists)
         if (.not. exists) then
            probed = gpu_no_library
            probed_why = "no GPU library '"//path//"' (scripts/gpu/build_gpu.sh builds it; " &
                         //'$DPEND_GPU_LIB names another)'
         else
            rc = c_gpu_load(path//c_null_char, msg, int(size(msg), c_int))
            if (rc /= 0) then
               probed = gpu_no_library
               probed_why = "GPU library '"//path//"' cannot be loaded: "//c_text(msg)
            else
               rc = c_gpu_probe(count, cname, int(size(cname), c_int), driver, runtime, msg, &
                                int(size(msg), c_int))
               if (rc /= 0 .or. count < 1) then
                  probed = gpu_no_device
                  probed_why = 'no GPU found'
                  if (len(c_text(msg)) > 0) probed_why = probed_why//' ('//c_text(msg)//')'
               else
                  probed = gpu_ready
                  probed_name = c_text(cname)
                  probed_why = ''
               end if
            end if
         end if
      end if
      state = probed
      name = probed_name
      why = probed_why
   end subroutine gpu_open

   !> The kernel time of the blocks computed on the GPU so far [s].
   real(dp) function gpu_kernel_seconds()
      gpu_kernel_seconds = kernel_seconds
   end function gpu_kernel_seconds

   !> The flip map of the initial states y0 (4, n) on the GPU, results as
   !> `integrate_batch` (flip map: opt%lyapunov false, opt%vectors 0); trajectories
   !> re-packed every `repack` steps (0: one launch, no re-packing). The library must
   !> be loaded (`gpu_open`). Should the GPU fail, the block is computed by
   !> `integrate_batch` on the CPU instead, with one line on stderr.
   subroutine gpu_integrate_block(par, opt, repack, y0, res)
      type(pendulum_t), intent(in) :: par           !! parameters
      type(batch_options_t), intent(in) :: opt      !! step, length, stop rule
      integer(i8), intent(in) :: repack             !! steps per launch, 0: all
      real(dp), intent(in) :: y0(:, :)              !! (4, n) initial states
      type(batch_result_t), intent(out) :: res      !! results
      type(batch_coef_t) :: c
      character(kind=c_char) :: msg(512)
      real(c_double) :: coef(10), bounds(2), kernel_ms
      integer(c_int) :: rc, launches, rule
      real(dp) :: nan
      integer :: n
      n = size(y0, 2)
      nan = ieee_value(nan, ieee_quiet_nan)
      c = batch_coef(par)
      coef = [c%m11, c%m22, c%k, c%ga, c%gb, c%m11k, c%m22k, c%detk, c%gak, c%gbk]
      bounds = flip_energy_bounds(par)
      res%n = n
      allocate (res%t_flip1(n), res%t_flip2(n), res%t_flip(n), res%energy0(n), &
                res%energy_error(n), res%t_stop(n), res%final(4, n), res%lyapunov(n), &
                res%status(n), res%steps(n), res%megno(n), res%megno_y(n), res%fli(n), &
                res%sali(n), res%gali2(n))
      res%lyapunov = nan; res%megno = nan; res%megno_y = nan; res%fli = nan
      res%sali = nan; res%gali2 = nan
      rule = int(opt%stop_rule, c_int)
      if (opt%lyapunov .or. opt%vectors > 0) rule = int(stop_end, c_int)
      rc = -1
      msg = c_null_char
      !$omp critical (dpend_sweep_gpu)
      if (n > 0) rc = c_gpu_run(coef, bounds, potential_range(par), opt%h, &
                                int(opt%n_steps, c_long_long), rule, &
                                int(repack, c_long_long), int(n, c_int), y0, res%t_flip1, &
                                res%t_flip2, res%t_flip, res%energy0, res%energy_error, &
                                res%t_stop, res%final, res%status, res%steps, kernel_ms, &
                                launches, msg, int(size(msg), c_int))
      if (rc == 0) kernel_seconds = kernel_seconds + kernel_ms/1000.0_dp
      !$omp end critical (dpend_sweep_gpu)
      if (rc == 0 .or. n == 0) return
      ! c_text's result has a deferred length: one thread at a time (docs/architecture.md,
      ! "Threads")
      !$omp critical (dpend_sweep_gpu)
      if (rc == -1 .and. len(c_text(msg)) == 0) msg(:18) = transfer('no library loaded' &
                                                                     //c_null_char, msg(:18))
      write (error_unit, '(a)') 'dpend sweep: the GPU failed ('//c_text(msg)// &
         '); this block is computed on the CPU'
      !$omp end critical (dpend_sweep_gpu)
      !$omp atomic
      fallback_blocks = fallback_blocks + 1
      call integrate_batch(par, opt, y0, res)
   end subroutine gpu_integrate_block

   !> Blocks of this run computed on the CPU after a failure of the GPU library.
   integer function gpu_fallback_blocks() result(n)
      !$omp atomic read
      n = fallback_blocks
   end function gpu_fallback_blocks

   !> The text of a NUL-terminated C string.
   function c_text(buf) result(s)
      character(kind=c_char), intent(in) :: buf(:)  !! the C string
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(buf)
         if (buf(i) == c_null_char) exit
         s = s//buf(i)
      end do
   end function c_text

   !> Resolve the device of a validated sweep (docs/gpu.md): the
   !> GPU computes the two-link flip map over initial values; 'gpu' is refused for
   !> anything else, without the library or without a GPU (saying which); 'auto'
   !> takes the GPU when it can, else the CPU, with a note. With the GPU and no
   !> block given, a block is 2^20 initial conditions (a kernel launch).
   subroutine resolve_device(cfg, error)
      type(sweep_config_t), intent(inout) :: cfg        !! configuration
      type(error_t), allocatable, intent(out) :: error  !! refused
      character(len=:), allocatable :: why, name
      integer :: state
      if (cfg%device == 'cpu') return   ! (its name and gpu_repack: validate_sweep)
      why = ''
      if (cfg%run%links /= 2 .or. .not. flip_model(cfg) .or. .not. kernel_pendulum(cfg)) then
         why = 'the GPU computes the two-link pendulum only, without damping, friction, ' &
               //'support motion, motors or torques'
      else if (cfg%lyapunov .or. cfg%indicator /= 'flip') then
         why = 'the GPU computes flip maps only (--lyapunov and --indicator run on the CPU)'
      else if (grid_mode(cfg)) then
         if (axis_parameter(cfg%axis1) > 0 .or. axis_parameter(cfg%axis2) > 0 .or. &
             model_axis(cfg, cfg%axis1) .or. model_axis(cfg, cfg%axis2)) &
            why = 'the GPU computes maps over initial values only (parameter axes run on ' &
                  //'the CPU)'
      end if
      if (len(why) == 0) then
         call gpu_open(state, name, why)
         if (state == gpu_ready) then
            cfg%device = 'gpu'
            cfg%device_name = name
            if (.not. cfg%block_given) cfg%block = 1048576
            cfg%device_note = "computing on the GPU '"//name//"'"
            return
         end if
      end if
      if (cfg%device == 'gpu') then
         call fatal_error(error, 'invalid device: gpu: '//why//' (--device cpu or auto)')
      else
         cfg%device = 'cpu'
         cfg%device_note = '--device auto: '//why//'; computing on the CPU'
      end if
   end subroutine resolve_device

end module dpend_sweep_gpu
