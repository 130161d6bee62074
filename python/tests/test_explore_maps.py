"""dpend explore on every kind of map dpend sweep writes, without a browser: a pixel's
run (dpend.explore._pixel.run_pixel, what a click computes) gives back every value
the map's file holds for that pixel, to the bit, and its motion starts at the
pixel's initial state with the pixel's parameters."""
from __future__ import annotations

import math

import numpy as np
import pytest

import dpend
from dpend.explore._map import MapError, open_map
from dpend.explore._pixel import run_pixel

COMMON = dict(n1=5, n2=4, t_end=8, dt=0.02)
KINDS = {
    "flip": dict(),
    "flip_q_axes": dict(axis1="q1", axis2="q2", min1=-1, max1=2, min2=-2, max2=1),
    "velocities_lambda1": dict(axis1="w1", axis2="w2", min1=-3, max1=3, min2=-3, max2=3,
                               q1=-1, q2=0.5, indicator="lambda1"),
    "fli": dict(indicator="fli"),
    "sali": dict(indicator="sali"),
    "gali2": dict(indicator="gali2"),
    "megno_mass_length": dict(axis1="m2/m1", axis2="l2/l1", min1=0.2, max1=3, min2=0.2,
                              max2=3, q1=0, q2=0, indicator="megno"),
    "theta1_mass": dict(axis2="m2", min2=0.5, max2=2, q2=-1),
    "named_g_com2": dict(axis1="g", axis2="com2", min1=5, max1=12, min2=0.2, max2=0.9),
    "point_masses": dict(body="point"),
    "triple_flip": dict(links=3),
    "triple_l2": dict(links=3, axis2="l2/l1", min2=0.5, max2=2, indicator="fli"),
    "elastic": dict(model="elastic", k=29.4, l0=1, m=1, g=9.8, q=[1.2, -1.5],
                    w=[0, 0], axis1="r", axis2="phi", min1=0.8, max1=2, min2=-2.8,
                    max2=-0.35, indicator="megno"),
    "elastic_k_l0": dict(model="elastic", m=1, g=9.8, q=[1.2, -1.2], w=[0, 0], axis1="k",
                         axis2="l0", min1=10, max1=40, min2=0.5, max2=1.5, indicator="sali"),
}


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("maps")


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_pixel_run_gives_the_maps_values(folder, kind):
    path = str(folder / f"{kind}.h5")
    dpend.sweep(progress=None, **COMMON, **KINDS[kind]).dpend.to_hdf5(path)
    m = open_map(path)
    for i, j in ((1, 2), (m.n1 - 1, 0)):
        run = run_pixel(m, i, j)
        assert run.page["map"].keys() == run.page["run"].keys() == m.maps.keys()
        for name, value in run.page["map"].items():
            got = run.page["run"][name]
            assert (value is None and got is None) or value == got, (kind, i, j, name,
                                                                      value, got)
        ds = run.trajectory
        q0 = np.asarray(ds.attrs["q0"], dtype=float)
        for axis, value in ((m.axis1, m.values1[i]), (m.axis2, m.values2[j])):
            if axis.startswith("theta"):
                assert q0[int(axis[5:]) - 1] == value - math.pi / 2
            elif axis in ("q1", "q2", "r", "phi"):
                assert q0[{"q1": 0, "q2": 1, "r": 0, "phi": 1}[axis]] == value
        for name, values in m.params.items():   # the pixel's own parameters
            attr = ds.attrs.get(name)
            if attr is None and name[-1].isdigit():
                attr = np.asarray(ds.attrs[name[:-1]])[int(name[-1]) - 1]
            assert float(attr) == values[j, i], (kind, name)
        assert ds.attrs["method"] == "rk4" and float(ds.attrs["dt"]) == float(m.attrs["h"])


def test_what_is_not_a_map_is_refused(folder, tmp_path):
    sim = str(tmp_path / "sim.h5")
    dpend.simulate(t_end=0.1).dpend.to_hdf5(sim)
    with pytest.raises(MapError, match="no group /sweep"):
        open_map(sim)
    text = tmp_path / "text.h5"
    text.write_text("not HDF5")
    with pytest.raises(MapError, match="not a readable HDF5 file"):
        open_map(str(text))
    with pytest.raises(MapError, match="no such file"):
        open_map(str(tmp_path / "missing.h5"))
    lst = tmp_path / "list.txt"
    lst.write_text("0 0 0 0\n0.1 0.2 0 0\n")
    listed = str(tmp_path / "list.h5")
    dpend.sweep(progress=None, ic_file=str(lst), t_end=1).dpend.to_hdf5(listed)
    with pytest.raises(MapError, match="list of initial conditions"):
        open_map(listed)


def test_a_forced_map_is_refused_not_replayed_without_its_forces(folder):
    """A map of a damped chain (the sweep integrates it with its energy balance) has
    forces in its configuration (c1, c2) that explore does not replay: refused when
    opened, never shown with pixel runs of the free pendulum."""
    path = str(folder / "damped.h5")
    ds = dpend.sweep(progress=None, **COMMON, damping=[0.1, 0.05])
    assert "energy balance" in ds["energy_error"].attrs["description"]   # one group: /sweep
    ds.dpend.to_hdf5(path)
    with pytest.raises(MapError, match="c1.*cannot replay"):
        open_map(path)
