"""The package's functions on the library (no command line needed)."""
from __future__ import annotations

import pathlib
import threading
import typing

import h5py
import io
import numpy as np
import pytest
import xarray as xr

import dpend


def test_simulate_returns_the_energy():
    ds = dpend.simulate(q1=0, q2=0, t_end=1)
    assert isinstance(ds, xr.Dataset)
    assert ds.energy.dims == ("time",)
    assert ds.energy.attrs["units"] == "J"
    assert ds.t.attrs["units"] == "s" and ds.t.values[-1] == 1.0
    assert ds.q.dims == ("time", "coordinate")
    assert list(ds.coordinate.values) == ["q1", "q2"]
    assert ds.attrs["method"] == "rk4"
    e = ds.energy.values
    assert np.all(np.isfinite(e)) and abs(e[-1] - e[0]) < 1e-8


def test_the_dataset_holds_the_file_as_h5py_reads_it():
    ds = dpend.simulate(q1=0.5, q2=-0.25, t_end=0.5, method="dop853")
    with h5py.File(io.BytesIO(ds.dpend.image), "r") as f:
        for name, dset in f["trajectory"].items():
            assert ds[name].shape == dset.shape and ds[name].dtype == dset.dtype
            assert np.array_equal(ds[name].values, dset[()], equal_nan=True)
            assert ds[name].attrs["description"] == dset.attrs["description"]


def test_refused_input_raises_value_error():
    with pytest.raises(ValueError) as info:
        dpend.simulate(q1=0, q2=0, t_end=-1)
    assert str(info.value).startswith("dpend simulate: ")


def test_an_unknown_option_is_refused():
    with pytest.raises(ValueError, match=r"^dpend simulate: "):
        dpend.simulate(no_such_option=1)


def test_options():
    assert dpend.options(t_end=1, q1=0.1, m=[1, 2.5], fit_damping=True, x=False,
                         y=None) == ["--t-end", "1", "--q1", "0.1", "--m", "1,2.5",
                                     "--fit-damping"]
    assert dpend.options(dt=1e-4, g=np.float64(9.81)) == ["--dt", "0.0001", "--g", "9.81"]
    with pytest.raises(TypeError):
        dpend.options(output="x.h5")


def test_to_hdf5_roundtrip(tmp_path):
    ds = dpend.simulate(q1=0, q2=0, t_end=1)
    path = tmp_path / "release.h5"
    ds.dpend.to_hdf5(path)
    assert path.read_bytes() == ds.dpend.image
    with pytest.raises(FileExistsError):
        ds.dpend.to_hdf5(path)
    ds.dpend.to_hdf5(path, force=True)
    with h5py.File(path, "r") as f:
        assert np.array_equal(f["trajectory/energy"][()], ds.energy.values)
    back = dpend.from_image(path.read_bytes())
    xr.testing.assert_identical(back, ds)
    assert [p.name for p in tmp_path.iterdir()] == ["release.h5"]   # no temporary left


def test_to_hdf5_refuses_a_changed_dataset(tmp_path):
    ds = dpend.simulate(q1=0, q2=0, t_end=1)
    with pytest.raises(ValueError):
        ds.isel(time=slice(0, 10)).dpend.to_hdf5(tmp_path / "part.h5")


@pytest.mark.parametrize("function, dims", [
    (dpend.lyapunov, {"exponent"}),
    (dpend.divergence, {"time", "pair"}),
    (dpend.indicators, {"time", "vector"}),
])
def test_chaos_commands(function, dims):
    ds = function(t_end=2)
    assert dims <= set(ds.sizes)


def test_sweep_maps_have_the_axes():
    ds = dpend.sweep(n1=8, n2=6, t_end=1)
    assert ds.t_flip.dims == ("axis2", "axis1")
    assert ds.sizes["axis1"] == 8 and ds.sizes["axis2"] == 6
    assert ds["final/q1"].dims == ("axis2", "axis1")


def test_two_sweeps_in_two_threads_are_the_single_runs():
    """Two sweeps started at once in two threads (run one at a time by the library's
    lock) give, variable by variable, the Datasets of the same sweeps run alone."""
    settings = [dict(n=24, t_end=10), dict(n=16, t_end=5, indicator="megno")]
    alone = [dpend.sweep(**kw, progress=None) for kw in settings]
    together = [None, None]

    def work(i):
        together[i] = dpend.sweep(**settings[i], progress=None)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, together):
        assert b is not None
        assert set(a.variables) == set(b.variables)
        for name in a.variables:
            assert a[name].values.tobytes() == b[name].values.tobytes(), name


DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def test_fit_takes_the_csv_path():
    ds = dpend.fit(DATA / "fit_example.csv")
    assert ds.estimate.dims == ("parameter",)
    assert ds.q_data.dims == ("time", "coordinate") or ds.q_data.dims[0] == "time"
    assert ds.attrs["command"] == "fit"


def test_study_quick_holds_its_summary():
    ds = dpend.study(quick=True, methods="rk4,dop853", cases="small")
    assert "rk4" in str(ds["summary/markdown"].values)
    assert ds.attrs["threads"] >= 1


def test_models_and_methods():
    assert "elastic" in dpend.models()
    assert {"rk4", "dop853", "verlet"} <= set(dpend.methods())


def test_a_missing_csv_is_refused(tmp_path):
    with pytest.raises(ValueError, match=r"^dpend fit: "):
        dpend.fit(tmp_path / "none.csv")


def test_help_shows_the_command_lines_options():
    import inspect
    params = inspect.signature(dpend.sweep).parameters
    assert {"t_end", "n", "indicator", "axis1", "stop_at", "threads"} <= set(params)
    assert params["n"].annotation == typing.Optional[int]
    assert params["lyapunov"].annotation == typing.Optional[bool]
    assert "output" not in params and "quiet" not in params
    assert "usage: dpend sweep" in dpend.sweep.__doc__
    assert list(inspect.signature(dpend.fit).parameters)[0] == "data"
    assert "usage: dpend study" in dpend.study.__doc__


def test_help_parsing_of_option_lines():
    from dpend._signatures import parse_help
    text = ("usage: dpend x [options]\n--links N) and prose\n"
            "  --m1, --m2 KG     masses; default 1, 1\n"
            "  --support-amplitude AX,AY  moving pin\n"
            "  --rtol, --atol    tolerances; default 1e-9, 1e-12\n"
            "  --model elastic   the spring pendulum\n"
            "  --force           overwrite\n"
            "  --config, --links, --dt (default 1e-3),\n"
            "                    --not-an-option here\n")
    assert parse_help(text) == [("m1", "float"), ("m2", "float"),
                                ("support_amplitude", "sequence"), ("rtol", "float"),
                                ("atol", "float"), ("model", "text"), ("config", "any"),
                                ("links", "any"), ("dt", "any")]


@pytest.mark.parametrize("command, kw", [
    ("simulate", dict(q1=0.5, q2=-1, t_end=1)),
    ("simulate", dict(links=3, body="point", t_end=0.5)),
    ("simulate", dict(model="elastic", q1=1.0, q2=0.5, t_end=0.5)),
    ("lyapunov", dict(t_end=2)),
    ("indicators", dict(t_end=2)),
    ("divergence", dict(t_end=2)),
    ("poincare", dict(t_end=10)),
    ("sweep", dict(n=16, t_end=5)),
    ("sweep", dict(n=16, t_end=5, indicator="megno")),
    ("study", dict(quick=True, methods="rk4", cases="small")),
])
def test_arrays_are_the_files_datasets(command, kw):
    """The Dataset made from the result's arrays (no HDF5) is identical, variable by
    variable and attribute by attribute, to the one read from the file's image."""
    ds = getattr(dpend, command)(**kw)
    assert len(ds.encoding["dpend_result"]) > 0          # made from the items
    assert ds.identical(dpend.from_image(ds.dpend.image))
    values = next(iter(ds.data_vars.values())).values
    assert not values.flags.writeable                     # the library's memory


def test_the_arrays_outlive_the_dataset():
    energy = dpend.simulate(t_end=1).energy.values
    import gc
    gc.collect()
    assert energy.shape == (101,) and np.isfinite(energy).all()
