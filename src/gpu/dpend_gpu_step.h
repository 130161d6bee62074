/* The two-link flip map, one trajectory at a time, for the CUDA kernel
 * (src/gpu/dpend_sweep_kernel.cu, one thread per trajectory) and for the host
 * (src/gpu/dpend_gpu_host.c, compiled by fpm, compared with the Fortran kernel in
 * test/test_gpu.f90).
 *
 * Copy of the formulas of src/lanes/dpend_pendulum_kernel.f90 for one lane, in the
 * same operation order: `sincos_poly`, `sincos_exact`, `sincos_add`,
 * `sincos_add_stage`, `accel_trig`, `energy_formula`, `rk4_lanes` (its fast path
 * with carried sin and cos, and `rk4_lanes_ref` through `rk4_lanes_fallback` for a
 * step whose offsets leave |d| <= d_max), `dclamp`, `wsq`, `runaway`, and the
 * per-lane logic of `integrate_batch`, `start_results` and `close_results` for a
 * flip map (no Lyapunov exponent, no indicators): the energy skip
 * (`flip_energy_bounds`), the flip rule (an angle passing pi/2 + 2 pi k, time
 * interpolated inside the step), the exact sin and cos again every `resync_steps`
 * steps, the stop rules and the statuses. test/test_copies.f90 names this file as
 * a copy; test/test_gpu.f90 compares it with the Fortran kernel step by step.
 *
 * Every function is marked for host and device by DPEND_HD; nothing here
 * allocates, prints or calls anything but sin, cos, floor, fabs, fmin, fmax. */
#ifndef DPEND_GPU_STEP_H
#define DPEND_GPU_STEP_H

#include <math.h>

#ifdef __CUDACC__
#define DPEND_HD static __host__ __device__ __forceinline__
#else
#define DPEND_HD static inline
#endif

/* statuses (dpend_pendulum_lanes st_*) and stop rules (stop_*) */
#define DPEND_ST_END 1
#define DPEND_ST_FLIPPED 2
#define DPEND_ST_CANNOT_FLIP 3
#define DPEND_ST_NONFINITE 4
#define DPEND_STOP_BOTH 1
#define DPEND_STOP_EITHER 2
#define DPEND_STOP_END 3

/* The constants of `batch_coef_t`, in its order (the Fortran side passes them). */
typedef struct {
    double m11, m22, k, ga, gb, m11k, m22k, detk, gak, gbk;
} dpend_coef_t;

/* One trajectory in flight: state, carried sin and cos, flip bookkeeping. */
typedef struct {
    double q1, q2, w1, w2;     /* state [rad, rad/s] */
    double s1, c1, s2, c2;     /* carried sin, cos of q1, q2 */
    double e0, err;            /* E(0) [J], max |E - E(0)| so far [J] */
    double tf1, tf2;           /* first flips [s], -1: none yet */
    double n1, n2;             /* index of the last upward vertical below q1, q2 */
    long long ks;              /* steps done */
    int sync;                  /* steps left to the next exact sin and cos */
    int can1, can2;            /* link can flip by energy */
    int todo;                  /* integrated (else below the bounds: skipped) */
    int ended;                 /* the stop rule ended it */
} dpend_traj_t;

#define DPEND_PI 3.14159265358979323846264338327950288
#define DPEND_HALF_PI (0.5 * DPEND_PI)
#define DPEND_TWO_PI (2.0 * DPEND_PI)
#define DPEND_INV_TWO_PI (1.0 / DPEND_TWO_PI)
#define DPEND_SINCOS_EXACT_MAX (1048576.0 * DPEND_HALF_PI)
#define DPEND_LANE_BOUND 1.0e15
#define DPEND_D_MAX 0.0625
#define DPEND_RESYNC_STEPS 1024

/* `sincos_poly`: Cody-Waite reduction by pi/2 in three parts, fdlibm's
 * polynomials, the quadrant by exact arithmetic (|x| <= DPEND_SINCOS_EXACT_MAX). */
DPEND_HD void dpend_sincos_poly(double x, double *s, double *c)
{
    const double two_over_pi = 6.36619772367581382433e-01;
    const double round_magic = 6755399441055744.0;
    const double pio2_1 = 1.57079632673412561417e+00;
    const double pio2_2 = 6.07710050630396597660e-11;
    const double pio2_2t = 2.02226624879595063154e-21;
    const double sin_p1 = -1.66666666666666324348e-01, sin_p2 = 8.33333333332248946124e-03,
                 sin_p3 = -1.98412698298579493134e-04, sin_p4 = 2.75573137070700676789e-06,
                 sin_p5 = -2.50507602534068634195e-08, sin_p6 = 1.58969099521155010221e-10;
    const double cos_p1 = 4.16666666666666019037e-02, cos_p2 = -1.38888888888741095749e-03,
                 cos_p3 = 2.48015872894767294178e-05, cos_p4 = -2.75573143513906633035e-07,
                 cos_p5 = 2.08757232129817482790e-09, cos_p6 = -1.13596475577881948265e-11;
    double xi, fn, fq, fo, fh, r, z, sr, cr, hz, wc, sa, ca;
    xi = fmin(fmax(x, -DPEND_SINCOS_EXACT_MAX), DPEND_SINCOS_EXACT_MAX);
    fn = (xi * two_over_pi + round_magic) - round_magic;
    r = ((xi - fn * pio2_1) - fn * pio2_2) - fn * pio2_2t;
    fq = fn - 4.0 * ((0.25 * (fn - 1.5) + round_magic) - round_magic);
    fo = fq - 2.0 * ((0.5 * (fq - 0.5) + round_magic) - round_magic);
    fh = 0.5 * (fq - fo);
    z = r * r;
    sr = r + r * z * (sin_p1 + z * (sin_p2 + z * (sin_p3 + z * (sin_p4 + z * (sin_p5
                                                                         + z * sin_p6)))));
    hz = 0.5 * z;
    wc = 1.0 - hz;
    cr = wc + (((1.0 - wc) - hz)
               + z * z * (cos_p1 + z * (cos_p2 + z * (cos_p3 + z * (cos_p4 + z * (cos_p5
                                                                     + z * cos_p6))))));
    sa = fo * cr + (1.0 - fo) * sr;
    ca = fo * sr + (1.0 - fo) * cr;
    *s = (1.0 - 2.0 * fh) * sa;
    *c = (1.0 - 2.0 * (fh - fo) * (fh - fo)) * ca;
}

/* `sincos_exact`: the polynomial within its range, sin and cos beyond (and NaN). */
DPEND_HD void dpend_sincos_exact(double x, double *s, double *c)
{
    if (fabs(x) <= DPEND_SINCOS_EXACT_MAX) {
        dpend_sincos_poly(x, s, c);
    } else {
        *s = sin(x);
        *c = cos(x);
    }
}

/* `sincos_add_stage`: sin, cos of x0 + d for the RK4 stages (|d| <= d_max). */
DPEND_HD void dpend_sincos_add_stage(double s0, double c0, double d, double *s, double *c)
{
    const double a3 = -1.66666666666661522633e-01, a5 = 8.33333330968069607714e-03,
                 a7 = -1.98396551545965599316e-04, b2 = -4.99999999999953814722e-01,
                 b4 = 4.16666664537929387624e-02, b6 = -1.38874356708829365011e-03;
    double d2 = d * d;
    double sd = d + d * d2 * (a3 + d2 * (a5 + d2 * a7));
    double cm1 = d2 * (b2 + d2 * (b4 + d2 * b6));
    *s = s0 + (s0 * cm1 + c0 * sd);
    *c = c0 + (c0 * cm1 - s0 * sd);
}

/* `sincos_add`: sin, cos of x0 + d by the Taylor polynomials (|d| <= d_max). */
DPEND_HD void dpend_sincos_add(double s0, double c0, double d, double *s, double *c)
{
    double d2 = d * d;
    double sd = d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0
                                                                 + d2 * (1.0 / 362880.0)))));
    double cm1 = d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40320.0))));
    *s = s0 + (s0 * cm1 + c0 * sd);
    *c = c0 + (c0 * cm1 - s0 * sd);
}

/* `sincos_near_lanes` for one lane: the addition formulas for |d| <= d_max, else
 * the exact values of x (NaN d included). */
DPEND_HD void dpend_sincos_near(double s0, double c0, double x, double d, double *s,
                                double *c)
{
    if (fabs(d) <= DPEND_D_MAX) {
        dpend_sincos_add(s0, c0, d, s, c);
    } else {
        dpend_sincos_exact(x, s, c);
    }
}

/* `dclamp` and `wsq` */
DPEND_HD double dpend_dclamp(double d) { return fmin(fmax(d, -DPEND_D_MAX), DPEND_D_MAX); }
DPEND_HD double dpend_wsq(double w) { return fmin(w * w, DPEND_LANE_BOUND * DPEND_LANE_BOUND); }

/* `runaway`: the state is not finite or beyond the lane bound. */
DPEND_HD int dpend_runaway(double q1, double q2, double w1, double w2)
{
    double s = fabs(q1) + fabs(q2) + fabs(w1) + fabs(w2);
    if (s - s == 0.0) return s > DPEND_LANE_BOUND;
    return 1;
}

/* `accel_trig`: the accelerations [rad/s^2] from sin, cos and the squared velocities. */
DPEND_HD void dpend_accel_trig(const dpend_coef_t *c, double s1, double c1, double s2,
                               double c2, double w1sq, double w2sq, double *a1, double *a2)
{
    double cd = c1 * c2 + s1 * s2;
    double sd = s1 * c2 - c1 * s2;
    double r1 = -c->gak * c1 - sd * w2sq;
    double r2 = -c->gbk * c2 + sd * w1sq;
    double rdet = 1.0 / (c->detk - cd * cd);
    *a1 = (c->m22k * r1 - cd * r2) * rdet;
    *a2 = (c->m11k * r2 - cd * r1) * rdet;
}

/* `energy_formula`: T + V [J]. */
DPEND_HD double dpend_energy_formula(const dpend_coef_t *c, double s1, double c1, double s2,
                                     double c2, double w1, double w2)
{
    return 0.5 * (c->m11 * w1 * w1 + 2.0 * c->k * (c1 * c2 + s1 * s2) * w1 * w2
                  + c->m22 * w2 * w2) + (c->ga * s1 + c->gb * s2);
}

/* The energy of a state with exact sin and cos (`energy_lanes`) [J]. */
DPEND_HD double dpend_energy(const dpend_coef_t *c, double q1, double q2, double w1, double w2)
{
    double s1, c1, s2, c2;
    dpend_sincos_exact(q1, &s1, &c1);
    dpend_sincos_exact(q2, &s2, &c2);
    return dpend_energy_formula(c, s1, c1, s2, c2, w1, w2);
}

/* `rk4_lanes_ref` for one lane, from exact sin and cos of the step start (as
 * `rk4_lanes_fallback` calls it): stage by stage, each stage's sin and cos by
 * `dpend_sincos_near`. */
DPEND_HD void dpend_rk4_ref(const dpend_coef_t *c, double h, double *q1, double *q2,
                            double *w1, double *w2, double *e, double *ts1, double *tc1,
                            double *ts2, double *tc2)
{
    double hh = 0.5 * h, h6 = h / 6.0;
    double s1, c1, s2, c2, x1, x2, y1, y2;
    double ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2, vb1, vb2, vc1, vc2, vd1, vd2;
    double S1, C1, S2, C2;
    dpend_sincos_exact(*q1, &S1, &C1);
    dpend_sincos_exact(*q2, &S2, &C2);
    dpend_accel_trig(c, S1, C1, S2, C2, dpend_wsq(*w1), dpend_wsq(*w2), &ka1, &ka2);
    *e = dpend_energy_formula(c, S1, C1, S2, C2, *w1, *w2);
    x1 = *q1 + hh * *w1; x2 = *q2 + hh * *w2;
    vb1 = *w1 + hh * ka1; vb2 = *w2 + hh * ka2;
    dpend_sincos_near(S1, C1, x1, x1 - *q1, &s1, &c1);
    dpend_sincos_near(S2, C2, x2, x2 - *q2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vb1), dpend_wsq(vb2), &kb1, &kb2);
    x1 = *q1 + hh * vb1; x2 = *q2 + hh * vb2;
    vc1 = *w1 + hh * kb1; vc2 = *w2 + hh * kb2;
    dpend_sincos_near(S1, C1, x1, x1 - *q1, &s1, &c1);
    dpend_sincos_near(S2, C2, x2, x2 - *q2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vc1), dpend_wsq(vc2), &kc1, &kc2);
    y1 = *q1 + h * vc1; y2 = *q2 + h * vc2;
    vd1 = *w1 + h * kc1; vd2 = *w2 + h * kc2;
    dpend_sincos_near(S1, C1, y1, y1 - *q1, &s1, &c1);
    dpend_sincos_near(S2, C2, y2, y2 - *q2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vd1), dpend_wsq(vd2), &kd1, &kd2);
    y1 = *q1 + h6 * ((*w1 + 2.0 * (vb1 + vc1)) + vd1);
    y2 = *q2 + h6 * ((*w2 + 2.0 * (vb2 + vc2)) + vd2);
    *w1 = *w1 + h6 * ((ka1 + 2.0 * (kb1 + kc1)) + kd1);
    *w2 = *w2 + h6 * ((ka2 + 2.0 * (kb2 + kc2)) + kd2);
    dpend_sincos_near(S1, C1, y1, y1 - *q1, ts1, tc1);
    dpend_sincos_near(S2, C2, y2, y2 - *q2, ts2, tc2);
    *q1 = y1; *q2 = y2;
}

/* `rk4_lanes` for one lane: one RK4 step of size h [s] with the carried sin and cos
 * (s1, c1, s2, c2 of the state on entry, of the new state on return); e: the energy
 * before the step [J]. A step with an offset beyond d_max (or NaN) is redone by
 * `dpend_rk4_ref` from the step start. */
DPEND_HD void dpend_rk4_step(const dpend_coef_t *c, double h, double *q1, double *q2,
                             double *w1, double *w2, double *e, double *s1a_io,
                             double *c1a_io, double *s2a_io, double *c2a_io)
{
    double hh = 0.5 * h, h6 = h / 6.0;
    double p1 = *q1, p2 = *q2, pw1 = *w1, pw2 = *w2;
    double s1a = *s1a_io, c1a = *c1a_io, s2a = *s2a_io, c2a = *c2a_io;
    double s1, c1, s2, c2, d1, d2, dc1, dc2, off;
    double ka1, ka2, kb1, kb2, kc1, kc2, kd1, kd2, sk1, sk2;
    double vb1, vb2, vc1, vc2, vd1, vd2, sv1, sv2, nw1, nw2;
    /* stage a: the step start */
    dpend_accel_trig(c, s1a, c1a, s2a, c2a, dpend_wsq(pw1), dpend_wsq(pw2), &ka1, &ka2);
    *e = dpend_energy_formula(c, s1a, c1a, s2a, c2a, pw1, pw2);
    d1 = (p1 + hh * pw1) - p1; d2 = (p2 + hh * pw2) - p2;
    vb1 = pw1 + hh * ka1; vb2 = pw2 + hh * ka2;
    /* stage b */
    dc1 = dpend_dclamp(d1); dc2 = dpend_dclamp(d2);
    off = fabs(d1 - dc1) + fabs(d2 - dc2);
    dpend_sincos_add_stage(s1a, c1a, dc1, &s1, &c1);
    dpend_sincos_add_stage(s2a, c2a, dc2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vb1), dpend_wsq(vb2), &kb1, &kb2);
    d1 = (p1 + hh * vb1) - p1; d2 = (p2 + hh * vb2) - p2;
    vc1 = pw1 + hh * kb1; vc2 = pw2 + hh * kb2;
    sv1 = vb1 + vc1; sv2 = vb2 + vc2;
    /* stage c */
    dc1 = dpend_dclamp(d1); dc2 = dpend_dclamp(d2);
    off = off + (fabs(d1 - dc1) + fabs(d2 - dc2));
    dpend_sincos_add_stage(s1a, c1a, dc1, &s1, &c1);
    dpend_sincos_add_stage(s2a, c2a, dc2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vc1), dpend_wsq(vc2), &kc1, &kc2);
    d1 = (p1 + h * vc1) - p1; d2 = (p2 + h * vc2) - p2;
    vd1 = pw1 + h * kc1; vd2 = pw2 + h * kc2;
    sk1 = kb1 + kc1; sk2 = kb2 + kc2;
    sv1 = (pw1 + 2.0 * sv1) + vd1; sv2 = (pw2 + 2.0 * sv2) + vd2;
    /* stage d */
    dc1 = dpend_dclamp(d1); dc2 = dpend_dclamp(d2);
    off = off + (fabs(d1 - dc1) + fabs(d2 - dc2));
    dpend_sincos_add_stage(s1a, c1a, dc1, &s1, &c1);
    dpend_sincos_add_stage(s2a, c2a, dc2, &s2, &c2);
    dpend_accel_trig(c, s1, c1, s2, c2, dpend_wsq(vd1), dpend_wsq(vd2), &kd1, &kd2);
    d1 = h6 * sv1; d2 = h6 * sv2;
    nw1 = pw1 + h6 * ((ka1 + 2.0 * sk1) + kd1);
    nw2 = pw2 + h6 * ((ka2 + 2.0 * sk2) + kd2);
    /* the new state and its sines and cosines */
    sv1 = p1 + d1; sv2 = p2 + d2;
    d1 = sv1 - p1; d2 = sv2 - p2;
    dc1 = dpend_dclamp(d1); dc2 = dpend_dclamp(d2);
    off = off + (fabs(d1 - dc1) + fabs(d2 - dc2));
    if (off == 0.0) {
        *q1 = sv1; *q2 = sv2; *w1 = nw1; *w2 = nw2;
        dpend_sincos_add(s1a, c1a, dc1, s1a_io, c1a_io);
        dpend_sincos_add(s2a, c2a, dc2, s2a_io, c2a_io);
        return;
    }
    *q1 = p1; *q2 = p2; *w1 = pw1; *w2 = pw2;
    dpend_rk4_ref(c, h, q1, q2, w1, w2, e, s1a_io, c1a_io, s2a_io, c2a_io);
}

/* The carried sin and cos of a trajectory set exactly (`resync`). */
DPEND_HD void dpend_traj_resync(dpend_traj_t *t)
{
    dpend_sincos_exact(t->q1, &t->s1, &t->c1);
    dpend_sincos_exact(t->q2, &t->s2, &t->c2);
    t->sync = DPEND_RESYNC_STEPS;
}

/* `floor_real` within its exact range (|y| < 2^50; clamped beyond). */
DPEND_HD double dpend_floor_real(double y)
{
    const double big = 1125899906842624.0;
    return floor(fmin(fmax(y, -big), big));
}

/* Start a trajectory from y0 = (q1, q2, w1, w2) (`start_results` and `load`):
 * its energy, which links can flip by energy (bounds [J]), whether it is
 * integrated at all. */
DPEND_HD void dpend_traj_start(const dpend_coef_t *c, const double bounds[2],
                               const double y0[4], dpend_traj_t *t)
{
    t->q1 = y0[0]; t->q2 = y0[1]; t->w1 = y0[2]; t->w2 = y0[3];
    t->e0 = dpend_energy(c, t->q1, t->q2, t->w1, t->w2);
    t->can1 = !(t->e0 < bounds[0]);
    t->can2 = !(t->e0 < bounds[1]);
    t->todo = t->can1 || t->can2;
    t->err = 0.0;
    t->tf1 = -1.0; t->tf2 = -1.0;
    t->ks = 0;
    t->ended = !t->todo;
    t->n1 = dpend_floor_real((t->q1 - DPEND_HALF_PI) * DPEND_INV_TWO_PI);
    t->n2 = dpend_floor_real((t->q2 - DPEND_HALF_PI) * DPEND_INV_TWO_PI);
    dpend_traj_resync(t);
}

/* The first passage of an angle over an upward vertical in the step from p to q
 * (`integrate_batch`'s rare path): n the index of the last vertical below, tf the
 * flip time [s] (< 0: none yet). */
DPEND_HD void dpend_flip_check(double p, double q, long long ks, double h, double *n,
                               double *tf)
{
    double m = dpend_floor_real((q - DPEND_HALF_PI) * DPEND_INV_TWO_PI);
    if (m != *n) {
        if (*tf < 0.0) {
            double qc = DPEND_HALF_PI + DPEND_TWO_PI * fmax(m, *n);
            *tf = ((double)(ks - 1) + (qc - p) / (q - p)) * h;
        }
        *n = m;
    }
}

/* Advance a started trajectory by at most kmax steps of h [s], n_steps in all, with
 * the stop rule; sets t->ended when it ends. Returns the steps taken. */
DPEND_HD long long dpend_traj_advance(const dpend_coef_t *c, double h, long long n_steps,
                                      int stop_rule, long long kmax, dpend_traj_t *t)
{
    long long k;
    double p1, p2, e, de;
    for (k = 0; k < kmax && !t->ended; ++k) {
        p1 = t->q1; p2 = t->q2;
        dpend_rk4_step(c, h, &t->q1, &t->q2, &t->w1, &t->w2, &e, &t->s1, &t->c1, &t->s2,
                       &t->c2);
        de = fabs(e - t->e0);
        t->err = de > t->err ? de : t->err;   /* gfortran's max(err, de) */
        t->ks = t->ks + 1;
        t->sync = t->sync - 1;
        if (t->sync < 1) dpend_traj_resync(t);
        dpend_flip_check(p1, t->q1, t->ks, h, &t->n1, &t->tf1);
        dpend_flip_check(p2, t->q2, t->ks, h, &t->n2, &t->tf2);
        t->ended = t->ks >= n_steps || dpend_runaway(t->q1, t->q2, t->w1, t->w2);
        if (stop_rule == DPEND_STOP_BOTH) {
            t->ended = t->ended || ((t->tf1 >= 0.0 || !t->can1) && (t->tf2 >= 0.0 || !t->can2));
        } else if (stop_rule == DPEND_STOP_EITHER) {
            t->ended = t->ended || t->tf1 >= 0.0 || t->tf2 >= 0.0;
        }
    }
    return k;
}

/* The results of an ended trajectory (`finish` and `close_results`): flip times
 * (NaN: none), E(0) [J], the energy error relative to escale = V_max - V_min
 * (NaN if not integrated or not finite), the time integrated to [s], the final
 * state, the status and the steps. */
DPEND_HD void dpend_traj_results(const dpend_coef_t *c, double escale, double h,
                                 long long n_steps, const double y0[4], const dpend_traj_t *t,
                                 double *t_flip1, double *t_flip2, double *t_flip,
                                 double *energy0, double *energy_error, double *t_stop,
                                 double fin[4], int *status, int *steps)
{
    const double nan = (double)NAN;
    double ef, err;
    *energy0 = t->e0;
    if (!t->todo) {
        *t_flip1 = nan; *t_flip2 = nan; *t_flip = nan; *energy_error = nan;
        *t_stop = 0.0;
        fin[0] = y0[0]; fin[1] = y0[1]; fin[2] = y0[2]; fin[3] = y0[3];
        *status = DPEND_ST_CANNOT_FLIP;
        *steps = 0;
        return;
    }
    *t_stop = (double)t->ks * h;
    fin[0] = t->q1; fin[1] = t->q2; fin[2] = t->w1; fin[3] = t->w2;
    *steps = (int)t->ks;
    if (dpend_runaway(t->q1, t->q2, t->w1, t->w2)) {
        *status = DPEND_ST_NONFINITE;
        *energy_error = nan;
    } else {
        *status = t->ks < n_steps ? DPEND_ST_FLIPPED : DPEND_ST_END;
        ef = dpend_energy(c, t->q1, t->q2, t->w1, t->w2);
        err = fabs(ef - t->e0);
        err = err > t->err ? err : t->err;
        *energy_error = err / escale;
    }
    if (t->tf1 >= 0.0 && t->tf2 >= 0.0) {
        *t_flip = fmin(t->tf1, t->tf2);
    } else if (t->tf1 >= 0.0) {
        *t_flip = t->tf1;
    } else if (t->tf2 >= 0.0) {
        *t_flip = t->tf2;
    } else {
        *t_flip = nan;
    }
    *t_flip1 = t->tf1 >= 0.0 ? t->tf1 : nan;
    *t_flip2 = t->tf2 >= 0.0 ? t->tf2 : nan;
}

#endif
