#!/usr/bin/env python3
"""Click to first frame of `dpend explore` on pixels of the classic flip map.

The map has the classic map's settings (data/sweep_classic.nml: rk4, step 0.005,
t_end = 1000 sqrt(L/g), stop at the first flip of either link), on a coarser grid
(--n, default 32): a pixel's run, the work of one click, is the same as on the
1024 x 1024 map. The page runs in headless chromium (Playwright); for each pixel
the time from the click to the first frame drawn (the page's performance.now(),
around the request, the JSON, the value table and the first drawing), and the
server's own seconds for the pixel's value (the 1 x 1 sweep) and its motion
(simulate to t_end, every 50th step kept). Pixels: those whose flip comes last, a
few flipping early, and the ones that cannot flip (below the energy bound: their
motion still runs to t_end), the costliest clicks.

    python scripts/explore_bench.py [--n 32] [--pixels 12] [--map FILE]
                                    [--screenshot PNG]

Needs the dpend package (pip install .), playwright and Debian's chromium. Prints
one line per pixel and the median and largest click-to-first-frame time, with the
machine (CPU, cores, load) and the library's flags.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import tempfile
import time

import numpy as np


def machine() -> str:
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return f"{cpu}, {os.cpu_count()} cores, load {load:.2f}, {platform.python_version()}"


def pixels_to_click(path: str, count: int) -> list:
    import h5py
    with h5py.File(path, "r") as f:
        t = f["/sweep/t_flip"][...]
        status = f["/sweep/status"][...]
    n2, n1 = t.shape
    order = np.argsort(np.where(np.isfinite(t), t, -1.0), axis=None)
    flips = [divmod(int(k), n1) for k in order if np.isfinite(t.flat[k])]
    never = [divmod(int(k), n1) for k in range(t.size) if status.flat[k] == 3]
    chosen = flips[-count // 2:] + flips[: count // 4] + never[: count - count // 2 - count // 4]
    return [(i, j) for j, i in chosen]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=32, help="grid points per axis (default 32)")
    ap.add_argument("--pixels", type=int, default=12, help="pixels clicked (default 12)")
    ap.add_argument("--map", help="an existing map (default: made here)")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--screenshot", help="then save the page, with the latest-flipping pixel "
                    "and its right neighbour run, as this PNG (docs/img/explore.png)")
    args = ap.parse_args()

    import dpend
    from dpend.explore._map import open_map
    from dpend.explore._server import Explorer, serve_in_thread
    from playwright.sync_api import sync_playwright

    work = tempfile.mkdtemp(prefix="dpend-explore-bench.")
    path = args.map
    if path is None:
        path = os.path.join(work, "classic.h5")
        start = time.perf_counter()
        dpend.sweep(progress=None, n=args.n, min1=-3, max1=3, min2=-3, max2=3, dt=0.005,
                    t_end=1000, stop_at="either", time_unit="natural").dpend.to_hdf5(path)
        print(f"explore_bench: the classic map's settings on {args.n} x {args.n}: made in "
              f"{time.perf_counter() - start:.1f} s")
    m = open_map(path)
    print(f"explore_bench: {machine()}")
    print(f"explore_bench: t_end {m.attrs['t_end']:.6g} s, {int(m.attrs['n_steps'])} steps "
          "of rk4 per pixel at most")
    server, url = serve_in_thread(Explorer(m, log=open(os.devnull, "w")))
    clicks = []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=args.chromium,
                                    args=["--no-sandbox", "--disable-gpu"])
        page = browser.new_page(viewport={"width": 1300, "height": 1000})
        page.goto(url)
        page.wait_for_selector("body[data-ready='1']")
        canvas = page.locator("#map")
        x, y, w, h = (float(v) for v in canvas.get_attribute("data-box").split(","))
        print(f"{'pixel':>10} {'status':>6} {'t_flip [s]':>12} {'value [s]':>9} "
              f"{'motion [s]':>10} {'click to first frame [s]':>25}")
        chosen = pixels_to_click(path, args.pixels)
        for i, j in chosen:
            page.goto("about:blank")
            page.goto(url)                         # no pixel in the address: none runs
            page.wait_for_selector("body[data-ready='1']")
            canvas.click(position={"x": x + (i + 0.5) * w / m.n1,
                                   "y": y + (m.n2 - j - 0.5) * h / m.n2})
            page.wait_for_selector("#value-row", timeout=60000)
            timing = page.evaluate("window.dpendExplore.timing")
            run = page.evaluate("window.dpendExplore.runs[0].seconds")
            status = page.evaluate("window.dpendExplore.runs[0].status")
            tf = page.evaluate("window.dpendExplore.runs[0].run.t_flip")
            seconds = (timing["firstFrame"] - timing["click"]) / 1000
            clicks.append(seconds)
            print(f"{f'({i}, {j})':>10} {status:>6} {tf if tf is not None else 'none':>12.6} "
                  f"{run['sweep']:>9.3f} {run['simulate']:>10.3f} {seconds:>25.3f}")
        if args.screenshot:                        # the latest flip and its neighbour
            i, j = chosen[0]
            i = min(i, m.n1 - 2)
            canvas.click(position={"x": x + (i + 0.5) * w / m.n1,
                                   "y": y + (m.n2 - j - 0.5) * h / m.n2})
            page.wait_for_selector("#value-row", timeout=60000)
            canvas.click(position={"x": x + (i + 1.5) * w / m.n1,
                                   "y": y + (m.n2 - j - 0.5) * h / m.n2}, modifiers=["Shift"])
            page.wait_for_selector("#separation[data-drawn='1']", timeout=60000)
            time.sleep(2.5)
            page.screenshot(path=args.screenshot, full_page=True)
            print(f"explore_bench: the page with pixels ({i}, {j}) and ({i + 1}, {j}): "
                  f"{args.screenshot}")
        browser.close()
    server.shutdown()
    print(f"explore_bench: click to first frame over {len(clicks)} pixels: median "
          f"{statistics.median(clicks):.3f} s, largest {max(clicks):.3f} s "
          f"({'within' if max(clicks) < 1 else 'ABOVE'} the 1 s target)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
