"""One pixel's run: its values by the map's own sweep on a 1 x 1 grid, its motion by
simulate (module docstring of _map), and what the page draws of them."""
from __future__ import annotations

import io
import math
import time
from dataclasses import dataclass
from typing import Any, Dict, List

import numpy as np
import xarray as xr

from .. import _commands
from ._map import MapFile, _number, same_bits


@dataclass
class PixelRun:
    """The run of pixel (i, j): the page's JSON and the trajectory's Dataset."""
    i: int
    j: int
    page: Dict[str, Any]
    trajectory: xr.Dataset

    def csv(self) -> bytes:
        """The trajectory as CSV: t, the coordinates, their rates, the energy."""
        ds = self.trajectory
        names = str(ds.attrs.get("coordinates", "")).split()
        q = np.asarray(ds["q"].values, dtype=float)
        qd = np.asarray(ds["qdot"].values, dtype=float)
        if not names or len(names) != q.shape[1]:
            names = [f"q{k + 1}" for k in range(q.shape[1])]
        out = io.StringIO()
        out.write("# dpend explore: pixel (i, j) = (%d, %d); SI units, angles from the "
                  "horizontal x axis\n" % (self.i, self.j))
        out.write(",".join(["t"] + names + [n + "dot" for n in names] + ["energy"]) + "\n")
        columns = np.column_stack([ds["t"].values, q, qd, ds["energy"].values])
        for row in columns:
            out.write(",".join(repr(float(x)) for x in row) + "\n")
        return out.getvalue().encode("utf-8")


def _points(ds: xr.Dataset) -> np.ndarray:
    """(frames, points, 2): the anchor, then the model's drawing points."""
    anchor = np.asarray(ds[str(ds.attrs.get("draw_anchor", "rA"))].values, dtype=float)
    points = np.asarray(ds[str(ds.attrs.get("draw_points", "rJ"))].values, dtype=float)
    anchor = anchor.reshape(anchor.shape[0], 1, 2)
    points = points.reshape(points.shape[0], -1, 2)
    return np.concatenate([anchor, points], axis=1)


def _rounded(a: np.ndarray, digits: int = 9) -> List[Any]:
    """Drawing data for JSON: 9 significant digits (the page draws, never compares)."""
    return [float(f"{x:.{digits}g}") if math.isfinite(x) else None
            for x in np.asarray(a, dtype=float).ravel()]


def run_pixel(m: MapFile, i: int, j: int) -> PixelRun:
    """Run pixel (i, j) of map m: the sweep's values and the motion (both in process)."""
    start = time.perf_counter()
    values = _commands.run("sweep", progress=None, **m.sweep_options(i, j))
    t_sweep = time.perf_counter() - start
    ds = _commands.run("simulate", progress=None, **m.simulate_options(i, j))
    t_simulate = time.perf_counter() - start - t_sweep
    got = {name: np.asarray(values[name].values).ravel()[0] for name in m.maps
           if name in values}
    run_values = {name: _number(v) for name, v in got.items()}
    same = {name: name in got and same_bits(m.maps[name][j, i], got[name])
            for name in m.maps}
    status = int(np.asarray(values["status"].values).ravel()[0]) if "status" in values \
        else None
    energy = np.asarray(ds["energy"].values, dtype=float)
    points = _points(ds)
    finite = np.abs(points[np.isfinite(points)])
    q = np.asarray(ds["q"].values, dtype=float)
    names = str(ds.attrs.get("coordinates", "")).split() or \
        [f"q{k + 1}" for k in range(q.shape[1])]
    page = {
        "i": i, "j": j,
        "x": float(m.values1[i]), "y": float(m.values2[j]),
        "map": m.pixel_values(i, j), "run": run_values, "same": same, "status": status,
        "t": _rounded(ds["t"].values), "frames": int(points.shape[0]),
        "points": _rounded(points), "npoints": int(points.shape[1]),
        "coordinates": names, "q": _rounded(q),
        "energy_change": _rounded(energy - energy[0], 4),
        "style": str(ds.attrs.get("draw_style", "rods")),
        "body": str(ds.attrs.get("body", "")),
        "model": m.model, "extent": float(finite.max()) if finite.size else 1.0,
        "save_every": int(ds.attrs.get("save_every", 1)),
        "seconds": {"sweep": t_sweep, "simulate": t_simulate},
    }
    return PixelRun(i, j, page, ds)
