#!/usr/bin/env python3
"""Check that dpend's files explain themselves to a Python user.

Runs every command that writes HDF5 on a small case (simulate, lyapunov,
divergence, poincare, sweep grid and list, study) in a temporary directory and
checks with h5py, numpy and pandas that

  * every string attribute reads as `str` (variable-length UTF-8), in
    particular `attrs['method']`;
  * every dataset has the string attributes `units` and `description`;
  * `dpend export --csv` output loads with numpy.genfromtxt(names=True) and
    pandas.read_csv as written, with the values of the file;
  * `dpend export --list` lists every dataset with its units;
  * a file written with fixed-length string attributes (the old form) still
    reads with `dpend export --list` and `--csv`;
  * the recipes of docs/python.md run: its fenced `sh` blocks, whose
    lines are `scripts/dpend ARGS` (run with the dpend under test, ARGS split as
    the shell would), write the files, then every `python` block runs in a fresh
    interpreter (this one) in that directory and must exit 0.

Offline; needs h5py, pandas and xarray (scripts/setup.sh installs Debian's
python3-h5py, python3-pandas, python3-xarray for /usr/bin/python3), which the
tests do not. Usage:

    python3 scripts/check_python.py [--dpend PATH]

PATH is the dpend binary (default: $DPEND, else the debug build that
`fpm run dpend --runner echo` names; build it first). Prints one line per
check and "N checks, M failed"; exit status 1 if any failed.
"""
import argparse
import io
import os
import re
import shlex
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import pandas as pd

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

STUDY_NML = """&study
  case_name(1) = 'small', case_q1(1) = -1.2707963267948965, case_q2(1) = -1.7707963267948965
  case_w1(1) = 0.0, case_w2(1) = 0.0, case_long_steps(1) = 3000
  case_name(2) = 'horizontal', case_q1(2) = 0.0, case_q2(2) = 0.0
  case_w1(2) = 0.0, case_w2(2) = 0.0, case_long_steps(2) = 300
  method(1) = 'rk4', h_min(1) = 2e-3, h_max(1) = 5e-3
  method(2) = 'dopri5', h_min(2) = 3e-3, h_max(2) = 8e-3, rtol_min(2) = 1e-10, rtol_max(2) = 1e-8
  method(3) = 'verlet', h_min(3) = 5e-3, h_max(3) = 1.25e-2
  n_h = 3, n_rtol = 3
  order_case = 'small', drift_case = 'small', decades = 2, wall_min = 0.0
  ro_method(1) = 'verlet', ro_dt(1) = 1e-2, ro_steps = 300, ro_runs = 2, ro_case = 'small'
  ro_fit_t_min = 0.1
  tao_method(1) = 'tao2', n_omega = 2, tao_t_end = 0.5, tao_dt = 1e-2, tao_case = 'small'
/
"""

SWEEP_LIST = """0.0 0.0 0.0 0.0
-1.5707963 -1.5707963 9.0 0.0
1.0 1.2 0.0 0.0
"""


class Checks:
    """Counts and prints the checks."""

    def __init__(self):
        self.n = 0
        self.failed = 0

    def check(self, ok, what):
        self.n += 1
        if not ok:
            self.failed += 1
        print(("ok    " if ok else "FAIL  ") + what)
        return ok


def find_dpend(arg):
    if arg:
        return os.path.abspath(arg)
    if os.environ.get("DPEND"):
        return os.path.abspath(os.environ["DPEND"])
    flags = subprocess.run(
        ["bash", "-c", ". scripts/flags.sh && printf %s \"$DEBUG_FLAGS\""],
        cwd=ROOT, capture_output=True, text=True, check=True).stdout
    out = subprocess.run(["fpm", "run", "dpend", "--flag", flags, "--runner", "echo"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return os.path.join(ROOT, out.strip().splitlines()[-1])


def run(dpend, args, cwd):
    """Run dpend, return stdout; raise with its stderr on failure."""
    res = subprocess.run([dpend] + args, cwd=cwd, capture_output=True, text=True)
    if res.returncode != 0:
        raise RuntimeError("dpend " + " ".join(args) + ": " + res.stderr.strip())
    return res.stdout


def make_files(dpend, tmp):
    """Small runs of every command; returns {label: (file, [relative datasets])}."""
    with open(os.path.join(tmp, "study.nml"), "w") as f:
        f.write(STUDY_NML)
    with open(os.path.join(tmp, "list.txt"), "w") as f:
        f.write(SWEEP_LIST)
    runs = {
        "simulate": (["simulate", "--t-end", "1", "--output", "sim.h5"],
                     "sim.h5", ["t", "q", "qdot", "energy", "F01", "rB"]),
        "lyapunov": (["lyapunov", "--t-end", "5", "--dt", "0.01", "--output", "lyap.h5"],
                     "lyap.h5", ["t", "running"]),
        "divergence": (["divergence", "--t-end", "2", "--pairs", "2", "--dt", "0.01",
                        "--q1", "0.5", "--output", "div.h5"],
                       "div.h5", ["t", "log10_delta", "log10_delta_pairs"]),
        "poincare": (["poincare", "--t-end", "20", "--ics", "3", "--points", "10",
                      "--dt", "0.01", "--q1", "0.3", "--output", "poinc.h5"],
                     "poinc.h5", ["q", "p", "t", "energy", "orbit"]),
        "sweep grid": (["sweep", "--n", "4", "--t-end", "2", "--quiet", "--threads", "1",
                        "--output", "grid.h5"],
                       "grid.h5", ["axis1"]),
        "sweep list": (["sweep", "--ic-file", "list.txt", "--t-end", "2", "--quiet",
                        "--threads", "1", "--output", "list.h5"],
                       "list.h5", ["initial", "t_flip", "energy0", "final/q1", "status"]),
        "study": (["study", "--config", "study.nml", "--no-figures", "--threads", "1",
                   "--output", "study.h5"],
                  "study.h5", ["/cases/small/rk4/step/h",
                               "/cases/small/rk4/step/global_error"]),
    }
    files = {}
    for label, (args, name, datasets) in runs.items():
        run(dpend, args, tmp)
        files[label] = (os.path.join(tmp, name), datasets)
    return files


def all_objects(f):
    """(path, object) of every group and dataset, the root included."""
    items = [("/", f)]
    f.visititems(lambda name, obj: items.append(("/" + name, obj)))
    return items


def check_file(c, dpend, label, path, datasets):
    with h5py.File(path, "r") as f:
        if "method" in f.attrs:
            m = f.attrs["method"]
            c.check(isinstance(m, str), f"{label}: attrs['method'] is str ({m!r})")
        bad = []
        n_str = 0
        for p, obj in all_objects(f):
            for k in obj.attrs:
                v = obj.attrs[k]
                if isinstance(v, (bytes, np.bytes_)):
                    bad.append(f"{p}@{k}")
                elif isinstance(v, str):
                    n_str += 1
        c.check(not bad, f"{label}: all {n_str} string attributes are str"
                + (f" (bytes: {', '.join(bad[:5])})" if bad else ""))
        dsets = [p for p, obj in all_objects(f) if isinstance(obj, h5py.Dataset)]
        missing = [p for p in dsets
                   if not isinstance(f[p].attrs.get("units"), str)
                   or not isinstance(f[p].attrs.get("description"), str)]
        c.check(not missing, f"{label}: all {len(dsets)} datasets have str units and "
                "description" + (f" (missing: {', '.join(missing[:5])})" if missing else ""))
        # export --list names every dataset with its units
        listing = run(dpend, ["export", path, "--list"], os.path.dirname(path))
        rows = {line.split()[0]: line for line in listing.splitlines()[1:]}
        c.check(sorted(rows) == sorted(dsets)
                and all(f"  {f[p].attrs['units'] or chr(39) * 2}  " in rows[p] for p in dsets),
                f"{label}: export --list shows the {len(dsets)} datasets with their units")
        # export --csv with relative names: numpy and pandas read it as written
        text = run(dpend, ["export", path, "--csv"] + datasets, os.path.dirname(path))
        expect = []
        for name in datasets:
            full = name if name.startswith("/") else \
                next(p for p in dsets if p == "/" + name or p.split("/", 2)[-1] == name)
            a = np.asarray(f[full][...], dtype=float)
            expect.append(a.reshape(a.shape[0], -1))
        expect = np.hstack(expect)
        arr = np.genfromtxt(io.StringIO(text), delimiter=",", names=True)
        arr = np.atleast_1d(arr)
        got = np.column_stack([arr[n] for n in arr.dtype.names])
        c.check(got.shape == expect.shape and np.array_equal(got, expect, equal_nan=True),
                f"{label}: export --csv {' '.join(datasets)} -> numpy.genfromtxt(names=True)"
                f" {got.shape}, columns {list(arr.dtype.names)[:4]}..., values as in the file")
        df = pd.read_csv(io.StringIO(text), float_precision="round_trip")  # exact on pandas 1.x
        c.check(df.shape == expect.shape
                and np.array_equal(df.to_numpy(dtype=float), expect, equal_nan=True),
                f"{label}: pandas.read_csv {df.shape}, columns {list(df.columns)[:3]}...")


def check_old_form(c, dpend, tmp):
    """A file with fixed-length (bytes) string attributes, as dpend wrote before."""
    path = os.path.join(tmp, "old.h5")
    with h5py.File(path, "w") as f:
        f.attrs["method"] = np.bytes_("rk4")
        d = f.create_dataset("/trajectory/t", data=np.arange(3.0))
        d.attrs["units"] = np.bytes_("s")
        d.attrs["description"] = np.bytes_("sample times")
    listing = run(dpend, ["export", path, "--list"], tmp)
    c.check("/trajectory/t" in listing and "  s  " in listing and "sample times" in listing,
            "old fixed-length string attributes: export --list reads them")
    text = run(dpend, ["export", path, "--csv", "t"], tmp)
    c.check(text.splitlines()[0] == "t [s]", "old form: export --csv header 't [s]'")


def doc_blocks(path):
    """Fenced blocks of a Markdown file: [(language, first line number, text)]."""
    blocks, lang, start, lines = [], None, 0, []
    with open(path, encoding="utf-8") as f:
        for no, line in enumerate(f, 1):
            fence = re.match(r"^```\s*([A-Za-z0-9_+-]*)\s*$", line.rstrip("\n"))
            if fence and lang is None:
                lang, start, lines = fence.group(1) or "text", no + 1, []
            elif fence and line.strip() == "```":
                blocks.append((lang, start, "".join(lines)))
                lang = None
            elif lang is not None:
                lines.append(line)
    if lang is not None:
        raise RuntimeError(f"{path}:{start - 1}: fenced block not closed")
    return blocks


def check_recipes(c, dpend, tmp):
    """Run docs/python.md: its sh lines write the files, its python blocks read them."""
    doc = os.path.join(ROOT, "docs", "python.md")
    rel = os.path.relpath(doc, ROOT)
    work = os.path.join(tmp, "recipes")
    os.mkdir(work)
    blocks = doc_blocks(doc)
    n_python = 0
    for lang, line, text in blocks:
        if lang == "sh":
            joined = text.replace("\\\n", " ")
            for k, cmd in enumerate(joined.splitlines()):
                words = shlex.split(cmd, comments=True)
                if not words:
                    continue
                ok = words[0] == "scripts/dpend"
                if ok:
                    res = subprocess.run([dpend] + words[1:], cwd=work,
                                         capture_output=True, text=True)
                    ok = res.returncode == 0
                    err = res.stderr.strip().splitlines()[-1:] if not ok else []
                else:
                    err = ["only scripts/dpend lines are run"]
                c.check(ok, f"{rel}:{line + k}: {cmd.strip()}"
                        + (f" ({err[0]})" if err else ""))
        elif lang == "python":
            n_python += 1
            res = subprocess.run([sys.executable, "-c", text], cwd=work,
                                 capture_output=True, text=True)
            tail = (res.stderr.strip().splitlines() or ["?"])[-1]
            c.check(res.returncode == 0, f"{rel}:{line}: python recipe {n_python} runs"
                    + (f" (exit {res.returncode}: {tail})" if res.returncode else ""))
            if res.returncode:
                print(res.stdout[-2000:] + res.stderr[-2000:])
    c.check(n_python >= 3, f"{rel}: {n_python} python recipes found (at least 3)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dpend", help="dpend binary")
    ap.add_argument("--recipes-only", action="store_true",
                    help="run only the recipes of docs/python.md")
    args = ap.parse_args()
    dpend = find_dpend(args.dpend)
    c = Checks()
    print(f"dpend: {dpend}; h5py {h5py.__version__}, numpy {np.__version__}, "
          f"pandas {pd.__version__}")
    with tempfile.TemporaryDirectory(prefix="dpend-check-") as tmp:
        if not args.recipes_only:
            files = make_files(dpend, tmp)
            for label, (path, datasets) in files.items():
                check_file(c, dpend, label, path, datasets)
            check_old_form(c, dpend, tmp)
        check_recipes(c, dpend, tmp)
    print(f"{c.n} checks, {c.failed} failed")
    return 1 if c.failed else 0


if __name__ == "__main__":
    sys.exit(main())
