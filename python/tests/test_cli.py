"""Python and the command line give bitwise the same files: set DPEND_CLI to the
release binary (scripts/python_package.sh --dpend PATH); skipped without it."""
from __future__ import annotations

import io
import os
import subprocess

import h5py
import numpy as np
import pytest

import dpend

CLI = os.environ.get("DPEND_CLI")
pytestmark = pytest.mark.skipif(not CLI, reason="DPEND_CLI names no dpend binary")

# Root attributes that differ between two runs of the same input (none known so
# far; the wall time of a run is printed, not stored).
VOLATILE: set = set()

CASES = [
    dict(method="rk4", q1=0, q2=0, t_end=1),
    dict(method="dop853", q1=0.5, q2=-1.25, t_end=2),
    dict(method="dopri5", q1=1, q2=2, t_end=1),
    dict(method="verlet", q1=0, q2=0, t_end=1, dt=1e-3),
    dict(method="gauss6", q1=0.3, q2=0.1, t_end=0.5),
    dict(method="yoshida4", q1=0, q2=0, t_end=1),
    dict(method="tao4", q1=0, q2=0, t_end=1),
    dict(model="elastic", q1=1.0, q2=0.5, t_end=1),
    dict(links=3, t_end=1),
    dict(body="point", q1=0, q2=0.5, t_end=1),
    dict(damping=[0.1, 0.05], q1=0, q2=0, t_end=1),
]


def _cli(command, tmp_path, **kw):
    out = tmp_path / "cli.h5"
    args = [CLI, command, *dpend.options(**kw), "--output", str(out), "--quiet"]
    done = subprocess.run(args, capture_output=True, text=True)
    assert done.returncode == 0, f"{args}: {done.stderr}"
    return out


def _items(f):
    found = {}
    f.visititems(lambda name, obj: found.setdefault(name, obj))
    return found


def _same_files(cli_path, image):
    with h5py.File(cli_path, "r") as a, h5py.File(io.BytesIO(image), "r") as b:
        ia, ib = _items(a), _items(b)
        assert sorted(ia) == sorted(ib)
        for name in ia:
            x, y = ia[name], ib[name]
            assert type(x) is type(y), name
            assert dict(x.attrs) .keys() == dict(y.attrs).keys(), name
            if isinstance(x, h5py.Dataset):
                u, v = x[()], y[()]
                assert x.dtype == y.dtype and x.shape == y.shape, name
                if isinstance(u, np.ndarray) and u.dtype.kind in "fc":
                    # bitwise: the bytes, so -0.0 and NaN payloads count too
                    assert u.tobytes() == v.tobytes(), name
                else:
                    assert np.array_equal(u, v), name
        for key in a.attrs:
            if key not in VOLATILE:
                assert np.array_equal(np.asarray(a.attrs[key]), np.asarray(b.attrs[key])), key


@pytest.mark.parametrize("kw", CASES, ids=lambda kw: "-".join(f"{k}={v}" for k, v in kw.items()))
def test_simulate_is_bitwise_the_command_line(kw, tmp_path):
    ds = dpend.simulate(**kw)
    _same_files(_cli("simulate", tmp_path, **kw), ds.dpend.image)


@pytest.mark.parametrize("command, kw", [
    ("lyapunov", dict(t_end=2)),
    ("indicators", dict(t_end=2)),
    ("divergence", dict(t_end=2)),
    ("poincare", dict(t_end=10)),
    ("sweep", dict(n1=16, n2=12, t_end=2)),
])
def test_other_commands_are_bitwise_the_command_line(command, kw, tmp_path):
    ds = getattr(dpend, command)(**kw)
    _same_files(_cli(command, tmp_path, **kw), ds.dpend.image)


def test_refusal_is_the_command_lines(tmp_path):
    with pytest.raises(ValueError) as info:
        dpend.simulate(t_end=-1)
    done = subprocess.run([CLI, "simulate", "--t-end", "-1", "--output",
                           str(tmp_path / "x.h5")], capture_output=True, text=True)
    assert done.returncode == 2
    assert str(info.value) in done.stderr


def test_fit_is_bitwise_the_command_line(tmp_path):
    csv = os.path.join(os.path.dirname(__file__), "..", "..", "data", "fit_example.csv")
    csv = os.path.abspath(csv)
    ds = dpend.fit(csv)
    out = tmp_path / "cli.h5"
    done = subprocess.run([CLI, "fit", csv, "--output", str(out), "--quiet"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    _same_files(out, ds.dpend.image)
