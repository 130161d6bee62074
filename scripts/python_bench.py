#!/usr/bin/env python3
"""The Python package's overhead against the command line (docs/python-package.md),
printed as figures, never asserted: run it with the interpreter of a venv where
`pip install .` put dpend, and the release binary of the same checkout.

  venv/bin/python scripts/python_bench.py --dpend build/gfortran_*/app/dpend [--repeat 5]

1. A 128 x 128 flip-time map (t_end 100 sqrt(l1/g), stopping at the flips): the
   wall time of dpend.sweep(...) returning its Dataset against that of the command
   (process, computing, writing its file); the least of --repeat runs each.
2. simulate, 1e5 rk4 steps, every step kept: dpend.simulate(...) returning the
   arrays against the command writing its file and h5py reading every dataset.
"""
from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time

import h5py

import dpend


def side_by_side(py, cli, repeat):
    """Python and the command run in turns (so a change of the machine's load hits
    both): the least time of each and the median of the ratios of each turn."""
    t_py, t_cli = [], []
    for _ in range(repeat):
        for f, times in ((py, t_py), (cli, t_cli)):
            t0 = time.perf_counter()
            f()
            times.append(time.perf_counter() - t0)
    ratios = sorted(p / c for p, c in zip(t_py, t_cli))
    return min(t_py), min(t_cli), ratios[len(ratios) // 2]


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dpend", required=True, help="the release dpend binary")
    ap.add_argument("--repeat", type=int, default=11)
    a = ap.parse_args()
    cli = os.path.abspath(a.dpend)
    work = tempfile.mkdtemp(prefix="dpend-bench-")
    print(f"python_bench: {cpu_model()}, {os.cpu_count()} CPUs, load "
          f"{os.getloadavg()[0]:.2f}; Python {platform.python_version()}, dpend "
          f"{dpend.__version__}; {a.repeat} turns, each Python then the command: the "
          "least times and the median of the turns' ratios")

    sweep_kw = dict(n=128, t_end=100)
    out = os.path.join(work, "sweep.h5")

    def sweep_cli():
        subprocess.run([cli, "sweep", *dpend.options(**sweep_kw), "--output", out,
                        "--force", "--quiet"], check=True, stdout=subprocess.DEVNULL)

    t_py, t_cli, ratio = side_by_side(lambda: dpend.sweep(**sweep_kw, progress=None),
                                      sweep_cli, a.repeat)
    print(f"sweep 128x128 to t = 100 sqrt(l1/g): Python {t_py:.3f} s, command {t_cli:.3f} s,"
          f" median ratio {ratio:.3f}")

    sim_kw = dict(method="rk4", dt=1e-4, t_end=10, save_every=1, q1=0, q2=0)
    sim = os.path.join(work, "sim.h5")

    def simulate_cli():
        subprocess.run([cli, "simulate", *dpend.options(**sim_kw), "--output", sim,
                        "--force", "--quiet"], check=True, stdout=subprocess.DEVNULL)
        arrays = []
        with h5py.File(sim, "r") as f:   # every dataset, as the Dataset holds them
            # (visititems stops at the first callback that returns a value: append)
            f.visititems(lambda name, obj: arrays.append(obj[()])
                         if isinstance(obj, h5py.Dataset) else None)
        if len(arrays) < 20:
            raise RuntimeError(f"read {len(arrays)} datasets of {sim}")

    def simulate_py():
        ds = dpend.simulate(**sim_kw, progress=None)
        _ = [v.values for v in ds.variables.values()]

    t_py, t_cli, ratio = side_by_side(simulate_py, simulate_cli, a.repeat)
    print(f"simulate rk4 1e5 steps, every step kept: Python {t_py:.3f} s, command + h5py "
          f"{t_cli:.3f} s, median ratio {ratio:.3f}")


if __name__ == "__main__":
    sys.exit(main())
