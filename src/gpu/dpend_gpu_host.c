/* The per-trajectory step of the GPU kernel (src/gpu/dpend_gpu_step.h) compiled
 * for the host, for the tests (test/test_gpu.f90 compares it with the Fortran
 * kernel through bind(C)): one RK4 step, and a whole block of the flip map, one
 * trajectory after the other, with the CUDA kernel's functions and results. */
#include "dpend_gpu_step.h"

/* batch_coef_t's ten constants, in order, as the header's struct. */
static dpend_coef_t coef_of(const double *coef)
{
    dpend_coef_t c;
    c.m11 = coef[0]; c.m22 = coef[1]; c.k = coef[2]; c.ga = coef[3]; c.gb = coef[4];
    c.m11k = coef[5]; c.m22k = coef[6]; c.detk = coef[7]; c.gak = coef[8]; c.gbk = coef[9];
    return c;
}

/* One step of h [s] from y = (q1, q2, w1, w2) with the carried sin and cos
 * trig = (s1, c1, s2, c2), both updated; e: the energy before the step [J]. */
void dpend_gpu_host_step(const double *coef, double h, double *y, double *trig, double *e)
{
    dpend_coef_t c;
    c = coef_of(coef);
    dpend_rk4_step(&c, h, &y[0], &y[1], &y[2], &y[3], e, &trig[0], &trig[1], &trig[2],
                   &trig[3]);
}

/* The flip map of n initial states y0 (4, n) on the host, as the CUDA kernel
 * computes it (arguments as dpend_gpu_run_block of src/gpu/dpend_sweep_kernel.cu). */
void dpend_gpu_host_block(const double *coef, const double *bounds, double escale, double h,
                          long long n_steps, int stop_rule, int n, const double *y0,
                          double *t_flip1, double *t_flip2, double *t_flip, double *energy0,
                          double *energy_error, double *t_stop, double *fin, int *status,
                          int *steps)
{
    dpend_coef_t c;
    dpend_traj_t t;
    int j;
    c = coef_of(coef);
    for (j = 0; j < n; ++j) {
        dpend_traj_start(&c, bounds, &y0[4 * j], &t);
        dpend_traj_advance(&c, h, n_steps, stop_rule, n_steps, &t);
        dpend_traj_results(&c, escale, h, n_steps, &y0[4 * j], &t, &t_flip1[j], &t_flip2[j],
                           &t_flip[j], &energy0[j], &energy_error[j], &t_stop[j], &fin[4 * j],
                           &status[j], &steps[j]);
    }
}

/* The accelerations [rad/s^2] a = (a1, a2) and the energy e [J] at y = (q1, q2, w1,
 * w2), sin and cos exact (`dpend_sincos_exact`), velocities squared by `dpend_wsq`:
 * the header's formulas, for the copy test (test/test_copies.f90). */
void dpend_gpu_host_accel(const double *coef, const double *y, double *a, double *e)
{
    dpend_coef_t c;
    double s1, c1, s2, c2;
    c = coef_of(coef);
    dpend_sincos_exact(y[0], &s1, &c1);
    dpend_sincos_exact(y[1], &s2, &c2);
    dpend_accel_trig(&c, s1, c1, s2, c2, dpend_wsq(y[2]), dpend_wsq(y[3]), &a[0], &a[1]);
    *e = dpend_energy_formula(&c, s1, c1, s2, c2, y[2], y[3]);
}
