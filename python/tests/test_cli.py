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

METHODS = ["rk4", "dopri5", "dop853", "midpoint", "gauss4", "gauss6", "gauss8", "verlet",
           "yoshida4", "comp6", "comp8", "tao2", "tao4"]
CASES = [dict(method=m, q1=0.5, q2=-1.25, t_end=1) for m in METHODS] + [
    dict(method="rk4", q1=0, q2=0, t_end=1),
    dict(model="elastic", q1=1.0, q2=0.5, t_end=1),
    dict(model="elastic", method="dop853", q=[1.2, -1], k=40, l0=1, t_end=1),
    dict(links=3, t_end=1),
    dict(links=4, method="dop853", t_end=0.5),
    dict(body="point", q1=0, q2=0.5, t_end=1),
    dict(body="rod", q1=0, q2=0.5, t_end=1),
    dict(com=[0.6, 0.5], inertia=[0.08, 0.03], q1=0.2, t_end=1),
    dict(damping=[0.1, 0.05], q1=0, q2=0, t_end=1),
    dict(support_amplitude=[0, 0.01], support_frequency=20, method="dop853", t_end=1),
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


def _same_files(cli_path, image, volatile=lambda name: False, volatile_attrs=()):
    """Every dataset bitwise, every attribute's name, the root attributes' values;
    `volatile(name)` names the datasets that differ between any two runs (timings),
    compared by dtype and shape only, and `volatile_attrs` such root attributes."""
    with h5py.File(cli_path, "r") as a, h5py.File(io.BytesIO(image), "r") as b:
        ia, ib = _items(a), _items(b)
        assert sorted(ia) == sorted(ib)
        for name in ia:
            x, y = ia[name], ib[name]
            if volatile(name):
                assert x.dtype == y.dtype and x.shape == y.shape, name
                continue
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
            if key not in VOLATILE and key not in volatile_attrs:
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
    ("sweep", dict(n=64, t_end=5)),
    ("sweep", dict(n=32, t_end=5, indicator="megno")),
    ("sweep", dict(n=32, t_end=5, indicator="megno", axis1="m2/m1", axis2="l2/l1",
                   min1=0.1, max1=4, min2=0.1, max2=4, q1=0, q2=0)),
    ("sweep", dict(n=16, t_end=2, damping=[0.1, 0.05], support_amplitude=[0, 0.01],
                   support_frequency=20)),
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
    for kw in (dict(), dict(fit_damping=True)):
        ds = dpend.fit(csv, **kw)
        out = tmp_path / "cli.h5"
        done = subprocess.run([CLI, "fit", csv, *dpend.options(**kw), "--output", str(out),
                               "--quiet", "--force"], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        _same_files(out, ds.dpend.image)


def test_study_is_bitwise_the_command_line(tmp_path):
    """study --quick: every dataset but the timings (wall_*, the summary that quotes
    them) and the root's creation time and wall time, which differ between any two
    runs of the command itself, and its compiler options (the include and module
    folders of the two builds, fpm's and meson's, differ)."""
    ds = dpend.study(quick=True)
    out = tmp_path / "study.h5"
    done = subprocess.run([CLI, "study", "--quick", "--no-figures", "--output", str(out),
                           "--quiet"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    _same_files(out, ds.dpend.image,
                volatile=lambda name: name.rsplit("/", 1)[-1].startswith("wall_")
                or name == "summary/markdown",
                volatile_attrs=("created", "wall_time", "compiler_options"))


def test_identify_and_torques_files_read(tmp_path):
    """A file of `dpend identify` reads with its base parameters on one dimension,
    every variable with its units; a file of `dpend torques` with its angles'
    convention (data/robot_example.csv, the docs' worked example)."""
    data = os.path.join(os.path.dirname(__file__), "..", "..", "data", "robot_example.csv")
    flags = ["--m", "1,0.7", "--l", "0.8,0.6", "--coulomb-speed", "0.5", "--quiet"]
    out = tmp_path / "identify.h5"
    done = subprocess.run([CLI, "identify", data, *flags, "--output", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    ds = dpend.from_image(out.read_bytes())
    names = ds["names"].values.item()
    names = names.decode() if isinstance(names, bytes) else names
    assert names.split("; ")[0] == "J1 + 0.64 m2"
    assert ds["estimate"].dims == ("parameter",) and ds.sizes["parameter"] == 8
    assert ds["covariance"].dims == ("parameter", "parameter_2")
    assert all("units" in ds[v].attrs for v in ds.data_vars)
    assert ds.attrs["rotors"] == "known"
    out = tmp_path / "torques.h5"
    done = subprocess.run([CLI, "torques", data, *flags, "--output", str(out)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    ds = dpend.from_image(out.read_bytes())
    assert ds["q"].attrs["angles"] == "absolute"
    assert ds["tau"].dims == ("time", "link") and ds["tau"].attrs["units"] == "N m"


def test_forced_sweep_reads_with_its_torques(tmp_path):
    """A sweep of a damped chain under joint torques (data/torque_example.csv): the
    library's file is the command line's, bit for bit; the torque samples read on
    (sample, link); the energy error says it is the energy balance's."""
    torques = os.path.join(os.path.dirname(__file__), "..", "..", "data",
                           "torque_example.csv")
    kw = dict(n=8, t_end=2, time_unit="s", damping=[0.05, 0.02], torque_file=torques)
    ds = dpend.sweep(progress=None, **kw)
    _same_files(_cli("sweep", tmp_path, **kw), ds.dpend.image)
    assert ds["torque/sample_tau"].dims == ("sample", "link")
    assert ds["torque/sample_t"].attrs["units"] == "s"
    assert "energy balance" in ds["sweep/energy_error"].attrs["description"]
    assert ds.attrs["torque_file"] == torques
