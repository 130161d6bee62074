"""A map written by ``dpend sweep``, checked, and the run of one of its pixels.

The file is hostile until checked (:func:`open_map`): the group /sweep, a complete
grid, the axes' and every map's shape and type, a bounded size, and its ``config``
attribute, the settings the sweep used as ``key = value`` lines. Those settings
are replayed for one pixel through the library's own option checks:

* the pixel's values: ``dpend sweep`` over a 1 x 1 grid at the pixel's axis
  values (the same doubles as in the file): the same code on the same numbers,
  so a CPU map's value comes back to the bit;
* the pixel's motion: ``dpend simulate`` with the same model, initial state, method
  (rk4), step h and t_end (seconds, the file's attributes), every k-th step kept.

A key of the configuration this module does not know how to replay is refused
when the map is opened (never dropped).
"""
from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from typing import Any, Dict, List, Tuple

import h5py
import numpy as np

# The most pixels a map may have (a 4096 x 4096 grid), the most frames of a pixel's
# motion sent to the page, the most bytes of map values held.
MAX_PIXELS = 4096 * 4096
MAX_FRAMES = 4000
MAX_BYTES = 2**30           # the maps and per-pixel parameters held in memory
MAX_AXIS = 8192             # points on one axis (a browser's canvas holds 32767 px)
MAX_STEPS = 10**8           # steps of one pixel's run (a few seconds of one click)

# Datasets of /sweep a page can colour the map by: (name, label, unit, scale).
# scale: 'flip' (log, in sqrt(l1/g), white = none), 'log', 'megno' (0..4), 'linear'.
_MAPS = [
    ("t_flip", "first flip of any link", "s", "flip"),
] + [(f"t_flip{k}", f"first flip of link {k}", "s", "flip") for k in range(1, 33)] + [
    ("energy_error", "maximum energy error |E(t) - E(0)| / (V_max - V_min)", "1", "log"),
    ("megno", "MEGNO <Y> at t_end (2: regular; > 2: chaotic)", "1", "megno"),
    ("fli", "fast Lyapunov indicator ln |delta(t_end)|", "1", "linear"),
    ("sali", "SALI at t_end (-> 0: chaotic)", "1", "log"),
    ("gali2", "GALI_2 at t_end (-> 0: chaotic)", "1", "log"),
    ("lyapunov", "largest Lyapunov exponent", "1/s", "linear"),
    ("energy0", "initial energy E(0)", "J", "linear"),
]

# Keys of the configuration that describe the run rather than set it (the sweep
# derives them), and keys passed through to both commands under their own name.
_DERIVED = {"program", "command", "kernel", "h", "n_steps", "initial", "method", "device"}
_SWEEP_ONLY = {"time_unit", "dt", "t_end", "stop_at", "indicator", "block", "axis1", "n1",
               "min1", "max1", "axis2", "n2", "min2", "max2", "lyapunov", "stats",
               "gpu_repack", "threads"}
_SCALARS = {"m1", "m2", "l1", "l2", "g", "q1", "q2", "w1", "w2", "k", "l0"}
_LISTS = {"m", "l", "q", "w", "com", "inertia", "damping"}


class MapError(ValueError):
    """A file that is not a map explore can show (one line: the file and why)."""


@dataclass
class MapFile:
    """A checked map: its axes, its maps and the settings of its sweep."""
    path: str
    n1: int
    n2: int
    axis1: str
    axis2: str
    values1: np.ndarray
    values2: np.ndarray
    units1: str
    units2: str
    maps: Dict[str, np.ndarray]
    labels: Dict[str, Tuple[str, str, str]]
    attrs: Dict[str, Any]
    config: List[Tuple[str, str]]
    params: Dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def model(self) -> str:
        return dict(self.config).get("model", "pendulum")

    @property
    def links(self) -> int:
        return int(self.attrs.get("links", 2))

    @property
    def gpu(self) -> bool:
        return str(self.attrs.get("device", "cpu")).startswith("gpu")

    def pixel_values(self, i: int, j: int) -> Dict[str, Any]:
        """The map's values at pixel (i, j): i along axis 1 (column), j along axis 2."""
        return {name: _number(m[j, i]) for name, m in self.maps.items()}

    # -- the pixel's run ---------------------------------------------------------
    def sweep_options(self, i: int, j: int) -> Dict[str, Any]:
        """The sweep's options for the 1 x 1 grid at pixel (i, j)."""
        opts = _replayed(self.config, sweep=True)
        for axis in (self.axis1, self.axis2):      # the value an axis sweeps is not fixed
            opts.pop(_fixed_by(axis), None)
        opts.update(n1=1, n2=1, block=1,
                    min1=float(self.values1[i]), max1=float(self.values1[i]),
                    min2=float(self.values2[j]), max2=float(self.values2[j]))
        return opts

    def simulate_options(self, i: int, j: int, frames: int = MAX_FRAMES) -> Dict[str, Any]:
        """simulate's options for pixel (i, j): the sweep's model and initial state with
        the pixel's axis values, rk4 with the file's step h up to its t_end [s]."""
        opts = _replayed(self.config, sweep=False)
        for axis, value in ((self.axis1, self.values1[i]), (self.axis2, self.values2[j])):
            self._set_axis(opts, axis, float(value), i, j)
        n_steps = int(self.attrs["n_steps"])
        opts.update(method="rk4", dt=float(self.attrs["h"]), t_end=float(self.attrs["t_end"]),
                    save_every=max(1, math.ceil(n_steps / frames)))
        return opts

    def _set_axis(self, opts: Dict[str, Any], axis: str, value: float, i: int,
                  j: int) -> None:
        """Put one axis' value of the pixel into simulate's options."""
        elastic = self.model == "elastic"
        state = {"r": ("q", 0), "phi": ("q", 1), "rdot": ("w", 0), "phidot": ("w", 1)}
        if elastic and axis in state:
            kind, k = state[axis]
            _set_list(opts, kind, k, value, 2)
            return
        for prefix, kind, shift in (("theta", "q", -math.pi / 2), ("q", "q", 0.0),
                                    ("w", "w", 0.0)):
            rest = axis[len(prefix):]
            if axis.startswith(prefix) and rest.isdigit():
                k = int(rest) - 1
                if "q" in opts or "w" in opts or self.links != 2 or elastic:
                    _set_list(opts, kind, k, value + shift, self.links if not elastic else 2)
                elif prefix == "theta":
                    opts[f"theta{k + 1}"] = value     # simulate converts as the sweep does
                    opts.pop(f"q{k + 1}", None)
                else:
                    opts[f"{kind}{k + 1}"] = value
                return
        # a parameter: the file holds every pixel's value of every swept parameter
        names = [n for n in self.params] or [axis]
        for name in names:
            if name not in self.params:
                raise MapError(f"{self.path}: axis '{axis}' has no /sweep/param dataset")
            v = float(self.params[name][j, i])
            kind = name.rstrip("0123456789")
            digits = name[len(kind):]
            listed = digits and kind in _LISTS and (kind in opts or self.links != 2
                                                    or name not in _SCALARS)
            if listed:                              # entry k of a per-link list
                _set_list(opts, kind, int(digits) - 1, v, self.links)
            elif name in opts or name in _SCALARS:
                opts[name] = v
            else:
                raise MapError(f"{self.path}: cannot replay the parameter axis '{name}'")

    def describe(self) -> Dict[str, Any]:
        """What the page needs to draw the map (JSON)."""
        tau = float(self.attrs["tau"])
        return {
            "file": os.path.basename(self.path), "n1": self.n1, "n2": self.n2,
            "axis1": self.axis1, "axis2": self.axis2, "units1": self.units1,
            "units2": self.units2, "values1": self.values1.tolist(),
            "values2": self.values2.tolist(), "tau": tau,
            "tau_label": f"√({self.attrs['tau_length']}/g)",
            "t_end": float(self.attrs["t_end"]), "n_steps": int(self.attrs["n_steps"]),
            "model": self.model, "links": self.links, "gpu": self.gpu,
            "device": str(self.attrs.get("device", "cpu")),
            "maps": [{"name": n, "label": self.labels[n][0], "units": self.labels[n][1],
                      "scale": self.labels[n][2]} for n in self.maps],
            "config": [f"{k} = {v}" for k, v in self.config],
        }


def _fixed_by(axis: str) -> str:
    """The configuration's key of the fixed value that `axis` replaces: q1 for theta1
    or q1, m2 for m2/m1, g for g, ..."""
    if axis.startswith("theta") and axis[5:].isdigit():
        return "q" + axis[5:]
    return axis.split("/")[0]


def _number(x: Any) -> Any:
    """A value for JSON: the float, or 'nan', 'inf', '-inf' (JSON has no such numbers)."""
    x = float(x)
    if math.isfinite(x):
        return x
    return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")


def same_bits(a: Any, b: Any) -> bool:
    """The map's value and the run's are the same double (every NaN alike)."""
    a, b = np.float64(a), np.float64(b)
    if np.isnan(a) or np.isnan(b):
        return bool(np.isnan(a) and np.isnan(b))
    return a.tobytes() == b.tobytes()


def _link_values(opts: Dict[str, Any], kind: str, n: int) -> List[float]:
    """Masses or lengths of the n links from the options (lists, or m1 m2 l1 l2;
    default 1)."""
    if kind in opts and isinstance(opts[kind], list):
        return [float(x) for x in opts[kind]]
    return [float(opts.get(f"{kind}{k + 1}", 1.0)) for k in range(n)]


def _set_list(opts: Dict[str, Any], kind: str, k: int, value: float, n: int) -> None:
    """Entry k of the list option `kind`; a centre of mass or inertia list not given
    starts from the rods' defaults l_i/2 and m_i l_i^2/12 (simulate's)."""
    if kind in opts:
        values = list(opts[kind])
    elif kind == "com":
        values = [x / 2 for x in _link_values(opts, "l", n)]
    elif kind == "inertia":
        values = [m * l**2 / 12 for m, l in zip(_link_values(opts, "m", n),
                                                 _link_values(opts, "l", n))]
    else:
        values = [0.0] * n
    while len(values) < n:
        values.append(0.0)
    values[k] = value
    opts[kind] = values


def _parse_value(key: str, text: str) -> Any:
    """A configuration value: a real, a list of reals, an integer, true/false, a word."""
    text = text.strip()
    if text in ("true", "false"):
        return text == "true"
    parts = [p.strip() for p in text.split(",")]
    try:
        numbers = [float(p) for p in parts]
    except ValueError:
        if len(parts) != 1 or not text or any(c.isspace() for c in text):
            raise MapError(f"configuration key '{key}': value '{text}' is not a word, "
                           "a number or a list of numbers") from None
        return text
    if not all(math.isfinite(x) for x in numbers):
        raise MapError(f"configuration key '{key}': value '{text}' is not finite")
    if key in _LISTS:
        return numbers
    if len(numbers) != 1:
        raise MapError(f"configuration key '{key}': a list '{text}' where one value belongs")
    if all(c.isdigit() for c in parts[0]):
        return int(parts[0])
    return numbers[0]


def _replayed(config: List[Tuple[str, str]], sweep: bool) -> Dict[str, Any]:
    """The options of the sweep (sweep=True) or of simulate for the configuration."""
    opts: Dict[str, Any] = {}
    coms: Dict[int, float] = {}
    inertias: Dict[int, float] = {}
    for key, text in config:
        if key in _DERIVED:
            continue
        value = _parse_value(key, text)
        if key in _SWEEP_ONLY:
            if sweep and value is not False:
                opts[key] = value
            continue
        for prefix, into in (("com", coms), ("inertia", inertias)):
            if key.startswith(prefix) and key[len(prefix):].isdigit():
                into[int(key[len(prefix):])] = float(value)
                break
        else:
            if key == "model" or key == "links" or key in _SCALARS or key in _LISTS:
                opts[key] = value
            else:
                raise MapError(f"configuration key '{key}' = '{text}': explore cannot "
                               "replay it")
    for name, into in (("com", coms), ("inertia", inertias)):
        if into:
            if sorted(into) != list(range(1, len(into) + 1)):
                raise MapError(f"configuration: {name}1 ... {name}N are not all given")
            opts[name] = [into[k] for k in sorted(into)]
    if opts.get("model") == "elastic" and isinstance(opts.get("m"), list):
        if len(opts["m"]) != 1:
            raise MapError("configuration: the elastic pendulum's m is one mass")
        opts["m"] = opts["m"][0]
    return opts


def _string_attr(obj: Any, name: str, path: str) -> str:
    if name not in obj.attrs:
        raise MapError(f"{path}: /sweep has no attribute '{name}'")
    value = obj.attrs[name]
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="strict")
    if isinstance(value, np.ndarray) and value.shape == () and value.dtype.kind in "OSU":
        value = value[()]
        value = value.decode() if isinstance(value, bytes) else value
    if not isinstance(value, str):
        raise MapError(f"{path}: /sweep attribute '{name}' is not a string")
    return value


def _real_attr(obj: Any, name: str, path: str, positive: bool = True) -> float:
    value = obj.attrs.get(name)
    try:
        x = float(np.asarray(value).reshape(()))
    except (TypeError, ValueError):
        raise MapError(f"{path}: /sweep attribute '{name}' is not one real number") from None
    if not math.isfinite(x) or (positive and x <= 0):
        raise MapError(f"{path}: /sweep attribute '{name}' = {x!r} is not a positive "
                       "finite number")
    return x


def _local(group: Any, name: str, shape: Tuple[int, ...], path: str) -> Any:
    """group/name as a dataset of float64 values of `shape` stored in this file: a hard
    link, not external or virtual (a map must not make the server read other files)."""
    where = f"{group.name.rstrip('/')}/{name}"
    if not isinstance(group.get(name, getlink=True), h5py.HardLink):
        raise MapError(f"{path}: {where} is a link to elsewhere, not a dataset of the file")
    d = group.get(name)
    if not isinstance(d, h5py.Dataset) or d.dtype != np.float64 or d.shape != shape:
        raise MapError(f"{path}: {where} is not {' x '.join(map(str, shape))} float64 values")
    if d.is_virtual or d.external:
        raise MapError(f"{path}: {where} is stored outside the file (external or virtual)")
    return d


def _axis(sweep: Any, name: str, n: int, path: str) -> Tuple[np.ndarray, str]:
    d = _local(sweep, name, (n,), path)
    values = d[...]
    if not np.all(np.isfinite(values)):
        raise MapError(f"{path}: /sweep/{name} holds a non-finite value")
    units = d.attrs.get("units", b"")
    units = units.decode() if isinstance(units, bytes) else str(units)
    return values, units


def open_map(path: str) -> MapFile:
    """Read and check the map at `path` (MapError: one line naming what is wrong; any
    other failure to read it becomes one too)."""
    try:
        return _open_map(path)
    except MapError:
        raise
    except (OSError, ValueError, TypeError, IndexError, KeyError, OverflowError) as e:
        why = " ".join(str(e).split())[:160]
        raise MapError(f"{path}: cannot be read as a map of dpend sweep "
                       f"({type(e).__name__}: {why})") from None


def _open_map(path: str) -> MapFile:
    if not os.path.isfile(path):
        raise MapError(f"{path}: not a readable HDF5 file (no such file, or a folder)")
    try:
        f = h5py.File(path, "r")
    except (OSError, ValueError) as e:
        why = " ".join(str(e).split())[:160]       # h5py's message spans lines
        raise MapError(f"{path}: not a readable HDF5 file ({why})") from None
    with f:
        sweep = f.get("sweep")
        if not isinstance(sweep, h5py.Group):
            raise MapError(f"{path}: no group /sweep (explore shows the maps of dpend sweep)")
        if _string_attr(sweep, "initial", path) != "grid":
            raise MapError(f"{path}: a sweep over a list of initial conditions, not a grid")
        complete = sweep.attrs.get("complete")
        if complete is None or int(np.asarray(complete).reshape(())) != 1:
            raise MapError(f"{path}: the sweep is not complete (resume it first)")
        config_text = _string_attr(sweep, "config", path)
        config = []
        for line in config_text.splitlines():
            if not line.strip():
                continue
            key, eq, value = line.partition("=")
            if not eq or not key.strip().replace("/", "").replace("_", "").isalnum():
                raise MapError(f"{path}: configuration line '{line[:80]}' is not key = value")
            config.append((key.strip(), value.strip()))
        keys = dict(config)
        if keys.get("command") != "sweep":
            raise MapError(f"{path}: its configuration is not that of a sweep")
        n1, n2 = (int(_parse_value(k, keys.get(k, "0"))) for k in ("n1", "n2"))
        if not (1 <= n1 <= MAX_AXIS and 1 <= n2 <= MAX_AXIS and n1 * n2 <= MAX_PIXELS):
            raise MapError(f"{path}: grid {n1} x {n2}: explore shows 1 to {MAX_AXIS} points "
                           f"per axis and at most {MAX_PIXELS} pixels")
        values1, units1 = _axis(sweep, "axis1", n1, path)
        values2, units2 = _axis(sweep, "axis2", n2, path)
        attrs = {k: sweep.attrs[k] for k in ("t_end", "h", "n_steps", "links", "device", "potential_range")
                 if k in sweep.attrs}
        units = sorted(k for k in sweep.attrs if re.fullmatch(r"sqrt_[a-z0-9]+_over_g", k))
        if len(units) != 1:
            raise MapError(f"{path}: /sweep has no single natural time unit "
                           "(an attribute sqrt_L_over_g)")
        attrs["tau_length"] = units[0][5:-7]
        attrs["tau"] = _real_attr(sweep, units[0], path)
        for k in ("t_end", "h"):
            attrs[k] = _real_attr(sweep, k, path)
        n_steps = attrs.get("n_steps")
        if n_steps is None or np.asarray(n_steps).dtype.kind not in "iu" \
                or np.asarray(n_steps).size != 1:
            raise MapError(f"{path}: /sweep attribute 'n_steps' is not one integer")
        n_steps = attrs["n_steps"] = int(np.asarray(n_steps).reshape(()))
        if not 1 <= n_steps <= MAX_STEPS:
            raise MapError(f"{path}: n_steps = {n_steps}: explore runs pixels of 1 to "
                           f"{MAX_STEPS} steps")
        if abs(attrs["h"] * n_steps - attrs["t_end"]) > 1e-9 * attrs["t_end"]:
            raise MapError(f"{path}: h x n_steps = {attrs['h'] * n_steps!r} s is not "
                           f"t_end = {attrs['t_end']!r} s")
        for k in ("h", "n_steps"):              # the settings say the same
            if k in keys and float(keys[k]) != float(attrs[k]):
                raise MapError(f"{path}: its configuration's {k} = {keys[k]} is not the "
                               f"attribute's {attrs[k]!r}")
        links = attrs.get("links", 2)
        if np.asarray(links).dtype.kind not in "iu" or np.asarray(links).size != 1 \
                or not 1 <= int(np.asarray(links).reshape(())) <= 32:
            raise MapError(f"{path}: /sweep attribute 'links' is not an integer in [1, 32]")
        attrs["links"] = int(np.asarray(links).reshape(()))
        if "device" in attrs:
            attrs["device"] = _string_attr(sweep, "device", path)
        maps: Dict[str, np.ndarray] = {}
        labels: Dict[str, Tuple[str, str, str]] = {}
        group = sweep.get("param")
        shown = [row for row in _MAPS if row[0] in sweep]
        held = (len(shown) + (len(group) if isinstance(group, h5py.Group) else 0)) \
            * n1 * n2 * 8
        if held > MAX_BYTES:                    # estimated before anything is read
            raise MapError(f"{path}: its maps and parameters would take {held / 2**30:.1f} "
                           f"GiB in memory; explore holds at most "
                           f"{MAX_BYTES / 2**30:.0f} GiB (a coarser map: --n)")
        for name, label, units, scale in shown:
            maps[name] = _local(sweep, name, (n2, n1), path)[...]
            labels[name] = (label, units, scale)
        if not maps:
            raise MapError(f"{path}: /sweep holds no map explore can show")
        params: Dict[str, np.ndarray] = {}
        if isinstance(group, h5py.Group):
            for name in group:
                params[name] = _local(group, name, (n2, n1), path)[...]
    m = MapFile(path=path, n1=n1, n2=n2, axis1=keys.get("axis1", "?"),
                axis2=keys.get("axis2", "?"), values1=values1, values2=values2,
                units1=units1, units2=units2, maps=maps, labels=labels, attrs=attrs,
                config=config, params=params)
    _replayed(config, sweep=True)               # a key it cannot replay: refused now
    m.simulate_options(0, 0)
    return m
