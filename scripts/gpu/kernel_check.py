#!/usr/bin/env python3
"""The GPU library alone, without dpend (scripts/gpu/gpu_device_check.sh): the
classic 1024^2 flip map (data/sweep_classic.nml) through dpend_gpu_run_block via
ctypes, its kernel time (cudaEvent) and wall time, with and without re-packing, and
optionally the agreement of its flip times with a dpend sweep file (h5py).

usage: scripts/gpu/kernel_check.py LIB [--n N] [--repack K ...] [--compare FILE.h5] [--json OUT]
"""
import argparse
import ctypes as C
import json
import math
import sys
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lib")
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--repack", type=int, nargs="*", default=[2048, 0])
    ap.add_argument("--compare", default="")
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    lib = C.CDLL(a.lib)
    dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")
    ip = np.ctypeslib.ndpointer(dtype=np.int32, flags="C_CONTIGUOUS")
    lib.dpend_gpu_probe.argtypes = [C.POINTER(C.c_int), C.c_char_p, C.c_int,
                                    C.POINTER(C.c_int), C.POINTER(C.c_int), C.c_char_p, C.c_int]
    lib.dpend_gpu_run_block.argtypes = [dp, dp, C.c_double, C.c_double, C.c_longlong, C.c_int,
                                        C.c_longlong, C.c_int, dp, dp, dp, dp, dp, dp, dp, dp,
                                        ip, ip, C.POINTER(C.c_double), C.POINTER(C.c_int),
                                        C.c_char_p, C.c_int]
    count, drv, rt = C.c_int(), C.c_int(), C.c_int()
    name, msg = C.create_string_buffer(256), C.create_string_buffer(512)
    rc = lib.dpend_gpu_probe(C.byref(count), name, 256, C.byref(drv), C.byref(rt), msg, 512)
    out = {"probe_rc": rc, "devices": count.value, "name": name.value.decode(),
           "driver": drv.value, "runtime": rt.value, "probe_msg": msg.value.decode()}
    print(json.dumps(out))
    if count.value < 1:
        return 1
    # the classic map: m = L = 1, g = 9.8, theta in [-3, 3], from rest, 1000 sqrt(L/g)
    m1 = m2 = l1 = l2 = 1.0
    g = 9.8
    c = dict(m11=(m1 / 3 + m2) * l1 ** 2, m22=m2 * l2 ** 2 / 3, k=0.5 * m2 * l1 * l2,
             ga=(0.5 * m1 + m2) * g * l1, gb=0.5 * m2 * g * l2)
    coef = np.array([c["m11"], c["m22"], c["k"], c["ga"], c["gb"], c["m11"] / c["k"],
                     c["m22"] / c["k"], (c["m11"] / c["k"]) * (c["m22"] / c["k"]),
                     c["ga"] / c["k"], c["gb"] / c["k"]])
    bounds = np.array([c["ga"] - c["gb"], c["gb"] - c["ga"]])
    escale = 2 * (c["ga"] + c["gb"])
    tau = math.sqrt(l1 / g)
    n_steps = math.ceil(1000.0 / 0.005 * (1 - 1e-12))
    h = 1000.0 * tau / n_steps
    n1 = a.n
    th = np.array([-3.0 + 6.0 * (i - 1) / (n1 - 1) for i in range(1, n1 + 1)])
    t1, t2 = np.meshgrid(th, th, indexing="xy")   # axis 1 fastest
    n = n1 * n1
    y0 = np.zeros((n, 4))
    y0[:, 0] = t1.ravel() - math.pi / 2
    y0[:, 1] = t2.ravel() - math.pi / 2
    y0 = np.ascontiguousarray(y0)
    results = []
    for k in a.repack:
        r = {x: np.zeros(n) for x in ("tf1", "tf2", "tf", "e0", "err", "ts")}
        fin = np.zeros(4 * n)
        st = np.zeros(n, dtype=np.int32)
        steps = np.zeros(n, dtype=np.int32)
        kms, launches = C.c_double(), C.c_int()
        w0 = time.perf_counter()
        rc = lib.dpend_gpu_run_block(coef, bounds, escale, h, n_steps, 2, k, n, y0.ravel(),
                                     r["tf1"], r["tf2"], r["tf"], r["e0"], r["err"], r["ts"],
                                     fin, st, steps, C.byref(kms), C.byref(launches), msg, 512)
        wall = time.perf_counter() - w0
        flipping = int(np.sum(~np.isnan(r["tf"])))
        total_steps = int(np.sum(steps.astype(np.int64)))
        res = {"repack": k, "rc": rc, "msg": msg.value.decode(), "kernel_s": kms.value / 1e3,
               "wall_s": wall, "launches": launches.value, "flipping": flipping,
               "status_counts": np.bincount(st, minlength=5).tolist(),
               "trajectory_steps": total_steps,
               "ns_per_trajectory_step": kms.value * 1e6 / max(total_steps, 1)}
        if a.compare:
            import h5py
            with h5py.File(a.compare, "r") as f:
                ref = f["/sweep/t_flip"][()].ravel()
            both = ~np.isnan(ref) & ~np.isnan(r["tf"])
            rel = np.abs(r["tf"][both] - ref[both]) / np.maximum(np.abs(ref[both]), 1e-300)
            res["compare_file"] = a.compare
            res["differ_gt_1pct_fraction_of_flipping"] = float(np.sum(rel > 0.01)) / max(
                int(np.sum(~np.isnan(ref))), 1)
            res["nan_mismatch"] = int(np.sum(np.isnan(ref) != np.isnan(r["tf"])))
            res["median_rel_diff"] = float(np.median(rel)) if rel.size else 0.0
        print(json.dumps(res))
        results.append(res)
    out["runs"] = results
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
