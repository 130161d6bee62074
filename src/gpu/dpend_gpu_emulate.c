/* A stand-in for libdpend_gpu.so without CUDA: the same exports as
 * src/gpu/dpend_sweep_kernel.cu, computed on the host with the same per-trajectory
 * functions (src/gpu/dpend_gpu_step.h). It exercises dpend's GPU path (dlopen,
 * the calls, the file) on machines without a GPU: scripts/gpu/build_gpu.sh --emulate.
 * Its probe reports one device named "host emulation (no GPU)".
 *
 * A library of its own, not part of dpend: fpm compiles every .c file under src/
 * into dpend's library, so the code below is compiled only with
 * -DDPEND_GPU_EMULATE, which scripts/gpu/build_gpu.sh --emulate passes; under fpm
 * this file compiles to an object without code or symbols. */
#ifdef DPEND_GPU_EMULATE
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "dpend_gpu_step.h"

int dpend_gpu_abi(void) { return 1; }

int dpend_gpu_probe(int *count, char *name, int name_len, int *driver, int *runtime,
                    char *msg, int msg_len)
{
    *count = 1; *driver = 0; *runtime = 0;
    if (name_len > 0) snprintf(name, (size_t)name_len, "%s", "host emulation (no GPU)");
    if (msg_len > 0) msg[0] = '\0';
    return 0;
}

int dpend_gpu_run_block(const double *coef, const double *bounds, double escale, double h,
                        long long n_steps, int stop_rule, long long steps_per_launch, int n,
                        const double *y0, double *t_flip1, double *t_flip2, double *t_flip,
                        double *energy0, double *energy_error, double *t_stop, double *fin,
                        int *status, int *steps, double *kernel_ms, int *launches, char *msg,
                        int msg_len)
{
    dpend_coef_t c;
    dpend_traj_t t;
    long long kmax;
    int j;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    c.m11 = coef[0]; c.m22 = coef[1]; c.k = coef[2]; c.ga = coef[3]; c.gb = coef[4];
    c.m11k = coef[5]; c.m22k = coef[6]; c.detk = coef[7]; c.gak = coef[8]; c.gbk = coef[9];
    kmax = steps_per_launch > 0 && steps_per_launch < n_steps ? steps_per_launch : n_steps;
    *launches = 0;
    for (j = 0; j < n; ++j) {
        int k = 0;
        dpend_traj_start(&c, bounds, &y0[4 * (size_t)j], &t);
        while (!t.ended) {   /* launches of at most kmax steps, as the kernel */
            dpend_traj_advance(&c, h, n_steps, stop_rule, kmax, &t);
            ++k;
        }
        if (k > *launches) *launches = k;
        dpend_traj_results(&c, escale, h, n_steps, &y0[4 * (size_t)j], &t, &t_flip1[j],
                           &t_flip2[j], &t_flip[j], &energy0[j], &energy_error[j], &t_stop[j],
                           &fin[4 * (size_t)j], &status[j], &steps[j]);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    *kernel_ms = 1e3 * (double)(t1.tv_sec - t0.tv_sec) + 1e-6 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (msg_len > 0) msg[0] = '\0';
    return 0;
}

#else
/* ISO C wants a declaration in every file; this one emits nothing. */
typedef int dpend_gpu_emulate_not_built;
#endif
