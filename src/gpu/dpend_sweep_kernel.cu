// The two-link flip map on an NVIDIA GPU: one thread per trajectory, fp64, the
// per-trajectory step of src/gpu/dpend_gpu_step.h (the same formulas, operation
// order, flip rule, energy skip and stop rules as the CPU kernel). Built by
// scripts/gpu/build_gpu.sh into libdpend_gpu.so, which dpend loads at run time
// (dlopen, src/io/dpend_posix.c; docs/gpu.md); dpend never links CUDA.
//
// Exports (extern "C"; every one returns 0 or a CUDA error code, fills `msg`):
//   dpend_gpu_abi            the interface version (1)
//   dpend_gpu_probe          devices, the name of device 0, driver and runtime
//   dpend_gpu_run_block      a block of initial conditions, in launches of at most
//                            `steps_per_launch` steps, the unfinished trajectories
//                            re-packed between launches (0: one launch runs every
//                            trajectory to its end, no re-packing)
#include <cuda_runtime.h>
#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/iterator/counting_iterator.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include "dpend_gpu_step.h"

namespace {

const int threads_per_block = 128;

__global__ void __launch_bounds__(threads_per_block)
    start_kernel(dpend_coef_t c, double b1, double b2, const double *y0, dpend_traj_t *traj,
                 int n)
{
    int j = blockIdx.x * blockDim.x + threadIdx.x;
    if (j >= n) return;
    double bounds[2] = {b1, b2};
    dpend_traj_t t;
    dpend_traj_start(&c, bounds, &y0[4 * (size_t)j], &t);
    traj[j] = t;
}

__global__ void __launch_bounds__(threads_per_block)
    advance_kernel(dpend_coef_t c, double h, long long n_steps, int stop_rule, long long kmax,
                   const int *idx, int m, dpend_traj_t *traj)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= m) return;
    int j = idx[i];
    dpend_traj_t t = traj[j];
    dpend_traj_advance(&c, h, n_steps, stop_rule, kmax, &t);
    traj[j] = t;
}

__global__ void __launch_bounds__(threads_per_block)
    results_kernel(dpend_coef_t c, double escale, double h, long long n_steps,
                   const double *y0, const dpend_traj_t *traj, int n, double *t_flip1,
                   double *t_flip2, double *t_flip, double *energy0, double *energy_error,
                   double *t_stop, double *fin, int *status, int *steps)
{
    int j = blockIdx.x * blockDim.x + threadIdx.x;
    if (j >= n) return;
    dpend_traj_t t = traj[j];
    dpend_traj_results(&c, escale, h, n_steps, &y0[4 * (size_t)j], &t, &t_flip1[j],
                       &t_flip2[j], &t_flip[j], &energy0[j], &energy_error[j], &t_stop[j],
                       &fin[4 * (size_t)j], &status[j], &steps[j]);
}

// a trajectory still to integrate (the stable compaction's predicate)
struct unfinished {
    const dpend_traj_t *traj;
    __host__ __device__ bool operator()(int j) const { return !traj[j].ended; }
};

void set_msg(char *msg, int msg_len, const char *what, cudaError_t e)
{
    if (msg && msg_len > 0) {
        snprintf(msg, (size_t)msg_len, "%s: %s", what, cudaGetErrorString(e));
    }
}

int grid_of(int m) { return (m + threads_per_block - 1) / threads_per_block; }

} // namespace

extern "C" int dpend_gpu_abi(void) { return 1; }

// Number of devices, the name of device 0, driver and runtime versions (1000 major
// + 10 minor). count = 0 (and 0 returned) when the driver finds no device.
extern "C" int dpend_gpu_probe(int *count, char *name, int name_len, int *driver,
                               int *runtime, char *msg, int msg_len)
{
    cudaError_t e;
    cudaDeviceProp prop;
    *count = 0; *driver = 0; *runtime = 0;
    if (name_len > 0) name[0] = '\0';
    cudaDriverGetVersion(driver);
    cudaRuntimeGetVersion(runtime);
    e = cudaGetDeviceCount(count);
    if (e == cudaErrorNoDevice || e == cudaErrorInsufficientDriver) {
        *count = 0;
        if (*driver == 0 && msg && msg_len > 0) {
            snprintf(msg, (size_t)msg_len, "no NVIDIA driver: libcuda.so.1 not found");
        } else {
            set_msg(msg, msg_len, "cudaGetDeviceCount", e);
        }
        return 0;
    }
    if (e != cudaSuccess) {
        *count = 0;
        set_msg(msg, msg_len, "cudaGetDeviceCount", e);
        return (int)e;
    }
    if (*count < 1) return 0;
    e = cudaGetDeviceProperties(&prop, 0);
    if (e != cudaSuccess) {
        set_msg(msg, msg_len, "cudaGetDeviceProperties", e);
        return (int)e;
    }
    if (name_len > 0) {
        strncpy(name, prop.name, (size_t)name_len - 1);
        name[name_len - 1] = '\0';
    }
    return 0;
}

// The flip map of the n initial states y0 (4, n, column-major as Fortran's y0(4, n))
// with the constants coef (batch_coef_t's ten, in order), the flip energy bounds
// [J], escale = V_max - V_min [J], step h [s], n_steps, stop_rule (1 both,
// 2 either, 3 end); outputs as batch_result_t's arrays. kernel_ms: the GPU time of
// the kernels and compactions (cudaEvent), launches: advance launches.
static int run_block(const double *coef, const double *bounds, double escale, double h,
                     long long n_steps, int stop_rule, long long steps_per_launch, int n,
                     const double *y0, double *t_flip1, double *t_flip2, double *t_flip,
                     double *energy0, double *energy_error, double *t_stop, double *fin,
                     int *status, int *steps, double *kernel_ms, int *launches, char *msg,
                     int msg_len)
{
    dpend_coef_t c;
    cudaError_t e = cudaSuccess;
    double *d_y0 = 0, *d_real = 0, *d_fin = 0;
    int *d_int = 0, *d_idx = 0, *d_idx2 = 0;
    dpend_traj_t *d_traj = 0;
    cudaEvent_t ev0 = 0, ev1 = 0;
    float ms = 0;
    int m, todo = 0;
    long long kmax;
    const char *what = "";
    size_t nn = (size_t)(n > 0 ? n : 1);
    *kernel_ms = 0; *launches = 0;
    if (msg_len > 0) msg[0] = '\0';
    if (n < 1) return 0;
    c.m11 = coef[0]; c.m22 = coef[1]; c.k = coef[2]; c.ga = coef[3]; c.gb = coef[4];
    c.m11k = coef[5]; c.m22k = coef[6]; c.detk = coef[7]; c.gak = coef[8]; c.gbk = coef[9];
    kmax = steps_per_launch > 0 && steps_per_launch < n_steps ? steps_per_launch : n_steps;

#define DPEND_CK(call)            \
    do {                          \
        what = #call;             \
        e = (call);               \
        if (e != cudaSuccess) goto done; \
    } while (0)

    DPEND_CK(cudaMalloc(&d_y0, 4 * nn * sizeof(double)));
    DPEND_CK(cudaMalloc(&d_fin, 4 * nn * sizeof(double)));
    DPEND_CK(cudaMalloc(&d_real, 6 * nn * sizeof(double)));
    DPEND_CK(cudaMalloc(&d_int, 2 * nn * sizeof(int)));
    DPEND_CK(cudaMalloc(&d_idx, nn * sizeof(int)));
    DPEND_CK(cudaMalloc(&d_idx2, nn * sizeof(int)));
    DPEND_CK(cudaMalloc(&d_traj, nn * sizeof(dpend_traj_t)));
    DPEND_CK(cudaEventCreate(&ev0));
    DPEND_CK(cudaEventCreate(&ev1));
    DPEND_CK(cudaMemcpy(d_y0, y0, 4 * nn * sizeof(double), cudaMemcpyHostToDevice));

    DPEND_CK(cudaEventRecord(ev0));
    start_kernel<<<grid_of(n), threads_per_block>>>(c, bounds[0], bounds[1], d_y0, d_traj, n);
    DPEND_CK(cudaGetLastError());
    {
        unfinished pred = {d_traj};
        m = (int)(thrust::copy_if(thrust::device, thrust::counting_iterator<int>(0),
                                  thrust::counting_iterator<int>(n), d_idx, pred) - d_idx);
    }
    todo = m;
    while (m > 0) {
        advance_kernel<<<grid_of(m), threads_per_block>>>(c, h, n_steps, stop_rule, kmax, d_idx,
                                                          m, d_traj);
        DPEND_CK(cudaGetLastError());
        *launches += 1;
        if (kmax >= n_steps) break;   // every trajectory has ended
        {
            unfinished pred = {d_traj};
            int m2 = (int)(thrust::copy_if(thrust::device, d_idx, d_idx + m, d_idx2, pred)
                           - d_idx2);
            int *tmp = d_idx; d_idx = d_idx2; d_idx2 = tmp;
            m = m2;
        }
    }
    results_kernel<<<grid_of(n), threads_per_block>>>(
        c, escale, h, n_steps, d_y0, d_traj, n, d_real, d_real + nn, d_real + 2 * nn,
        d_real + 3 * nn, d_real + 4 * nn, d_real + 5 * nn, d_fin, d_int, d_int + nn);
    DPEND_CK(cudaGetLastError());
    DPEND_CK(cudaEventRecord(ev1));
    DPEND_CK(cudaEventSynchronize(ev1));
    DPEND_CK(cudaEventElapsedTime(&ms, ev0, ev1));
    *kernel_ms = ms;
    DPEND_CK(cudaMemcpy(t_flip1, d_real, nn * sizeof(double), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(t_flip2, d_real + nn, nn * sizeof(double), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(t_flip, d_real + 2 * nn, nn * sizeof(double), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(energy0, d_real + 3 * nn, nn * sizeof(double),
                        cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(energy_error, d_real + 4 * nn, nn * sizeof(double),
                        cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(t_stop, d_real + 5 * nn, nn * sizeof(double), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(fin, d_fin, 4 * nn * sizeof(double), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(status, d_int, nn * sizeof(int), cudaMemcpyDeviceToHost));
    DPEND_CK(cudaMemcpy(steps, d_int + nn, nn * sizeof(int), cudaMemcpyDeviceToHost));
    {
        const char *env = getenv("DPEND_GPU_TIMING");
        if (env && env[0] != '\0' && env[0] != '0') {
            fprintf(stderr,
                    "dpend-gpu: block of %d (%d integrated): kernel time %.4f s, %d launch(es)"
                    " of at most %lld steps\n",
                    n, todo, ms / 1000.0, *launches, kmax);
        }
    }
#undef DPEND_CK
done:
    if (e != cudaSuccess) set_msg(msg, msg_len, what, e);
    if (ev0) cudaEventDestroy(ev0);
    if (ev1) cudaEventDestroy(ev1);
    cudaFree(d_y0); cudaFree(d_fin); cudaFree(d_real); cudaFree(d_int);
    cudaFree(d_idx); cudaFree(d_idx2); cudaFree(d_traj);
    return (int)e;
}

extern "C" int dpend_gpu_run_block(const double *coef, const double *bounds, double escale,
                                   double h, long long n_steps, int stop_rule,
                                   long long steps_per_launch, int n, const double *y0,
                                   double *t_flip1, double *t_flip2, double *t_flip,
                                   double *energy0, double *energy_error, double *t_stop,
                                   double *fin, int *status, int *steps, double *kernel_ms,
                                   int *launches, char *msg, int msg_len)
{
    try {
        return run_block(coef, bounds, escale, h, n_steps, stop_rule, steps_per_launch, n, y0,
                         t_flip1, t_flip2, t_flip, energy0, energy_error, t_stop, fin, status,
                         steps, kernel_ms, launches, msg, msg_len);
    } catch (const std::exception &ex) {   // thrust reports CUDA errors by exceptions
        if (msg && msg_len > 0) snprintf(msg, (size_t)msg_len, "thrust: %s", ex.what());
        return -1;
    }
}
