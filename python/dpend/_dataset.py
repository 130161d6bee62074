"""An HDF5 file image of dpend as an xarray.Dataset, and the ``ds.dpend`` accessor.

Naming (docs/python.md, "The dpend package"):

* **Variables.** Every HDF5 dataset is a variable, named by its path below the
  command's group when the file has one top-level group (``/trajectory/energy``
  -> ``energy``, ``/sweep/final/q1`` -> ``final/q1``), else by its whole path
  without the leading ``/``. Values, dtypes and shapes exactly as h5py reads them
  (strings: ``bytes`` decoded to ``str`` only in attributes). The attributes of a
  dataset (``units``, ``description``, ...) become the variable's ``attrs``.
* **Attributes.** The root attributes go to ``ds.attrs``, then those of the
  command's group (``/sweep@axis1`` -> ``ds.attrs['axis1']``; a name already taken
  by the root gets the group's prefix, ``'sweep/g'``), then those of deeper
  groups as ``'final/NAME'``.
* **Dimensions.** In a group with a 1-D dataset ``t`` (n samples), ``t`` is a
  coordinate on the dimension ``time`` (``crossing`` for the Poincare section;
  ``GROUP/time`` for a nested group), and every dataset of that group whose first
  axis has n entries starts with that dimension. Then, by the axis' length and
  the dataset's meaning: ``coordinate`` for q, qdot, qddot, p (coordinate labels
  from the root attribute ``coordinates``: q1 q2; r phi), ``link`` for the N links
  (root attribute ``links``), ``xy`` (labels x, y) for the last axis of a vector
  whose description has ``(x, y)``, ``axis2, axis1`` for a sweep map (the
  datasets ``axis1``, ``axis2`` are their coordinates), ``pair``, ``orbit``,
  ``vector``, ``exponent``, ``parameter`` where the command's layout names them.
  Any other axis is ``NAME_dim_K`` (K from 0), private to the variable NAME.
"""
from __future__ import annotations

import io
import os
import tempfile
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple

import h5py
import numpy as np
import xarray as xr

if TYPE_CHECKING:
    from . import _library

_ENCODING_KEY = "dpend_image"        # ds.encoding[...]: the HDF5 file image (bytes)
_RESULT_KEY = "dpend_result"         # ds.encoding[...]: the library's result

# The second axis of these datasets, by (group, name): per-command layouts.
_AXES: Dict[Tuple[str, str], Tuple[str, ...]] = {
    ("divergence", "delta_start"): ("pair",),
    ("divergence", "energy_difference"): ("pair",),
    ("divergence", "start"): ("pair", "state"),
    ("divergence", "log10_delta_pairs"): ("time", "pair"),
    ("poincare", "count"): ("orbit",),
    ("poincare", "orbit_status"): ("orbit",),
    ("poincare", "initial_q"): ("orbit", "coordinate"),
    ("poincare", "initial_qdot"): ("orbit", "coordinate"),
    ("lyapunov", "exponents"): ("exponent",),
    ("lyapunov", "spread"): ("exponent",),
    ("lyapunov", "batches"): ("batch", "exponent"),
    ("lyapunov", "running"): ("time", "exponent"),
    ("indicators", "log_norm"): ("time", "vector"),
    ("indicators", "megno_vectors"): ("time", "vector"),
    ("indicators", "megno_mean_vectors"): ("time", "vector"),
    ("indicators", "gali"): ("time", "k"),
    ("fit", "estimate"): ("parameter",),
    ("fit", "guess"): ("parameter",),
    ("fit", "standard_error"): ("parameter",),
    ("fit", "interval95"): ("parameter", "bound"),
    ("fit", "covariance"): ("parameter", "parameter_2"),
    ("fit", "correlation"): ("parameter", "parameter_2"),
    ("identify", "estimate"): ("parameter",),
    ("identify", "std_error"): ("parameter",),
    ("identify", "interval95"): ("parameter", "bound"),
    ("identify", "covariance"): ("parameter", "parameter_2"),
    ("identify", "physical"): ("link", "standard"),
    ("identify", "singular"): ("direction",),
    ("torque", "sample_t"): ("sample",),
    ("torque", "sample_tau"): ("sample", "link"),
}
_TIME_NAME = {"poincare": "crossing"}
_COORDINATE_DATASETS = ("q", "qdot", "qddot", "p")


def _text(value: Any) -> Any:
    """An attribute's value with bytes decoded (h5py gives fixed-length strings so)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.dtype.kind in ("S", "O"):
        return [_text(v) for v in value.tolist()]
    return value


def _attrs(obj: h5py.HLObject) -> Dict[str, Any]:
    return {k: _text(v) for k, v in obj.attrs.items()}


def _dims(top: str, rel: str, name: str, dset: "_Data", time: Optional[Tuple[str, int]],
          root: Dict[str, Any], maps: Optional[Tuple[int, int]]) -> List[str]:
    """The dimension names of one dataset (see the module's docstring)."""
    shape = dset.shape
    dims: List[Optional[str]] = [None] * len(shape)
    if not top and "/" in rel:   # a file of several groups (a sweep's /sweep and /torque)
        top, rel = rel.split("/", 1)
    leaf = rel.rsplit("/", 1)[-1]
    known = _AXES.get((top, leaf)) if "/" not in rel else None
    if known is not None and len(known) == len(shape):
        dims = list(known)
        if dims[0] == "time" and time is not None and time[1] == shape[0]:
            dims[0] = time[0]
        elif dims[0] == "time":
            dims[0] = None
    else:
        if shape and time is not None and shape[0] == time[1]:
            dims[0] = time[0]
        if maps is not None and len(shape) == 2 and tuple(shape) == maps:
            dims = ["axis2", "axis1"]
        description = str(dset.attrs.get("description", ""))
        if len(shape) >= 2 and shape[-1] == 2 and "(x, y)" in description:
            dims[-1] = "xy"
        if leaf in _COORDINATE_DATASETS and len(shape) == 2 and dims[1] is None:
            dims[1] = "coordinate"
        links = root.get("links")
        if isinstance(links, (int, np.integer)):
            for k in range(1, len(shape)):
                if dims[k] is None and shape[k] == int(links) and any(
                        w in description for w in ("link", "joint", "body")):
                    dims[k] = "link"
    safe = name.replace("/", "_")
    return [d if d is not None else f"{safe}_dim_{k}" for k, d in enumerate(dims)]


class _Data:
    """One dataset of a file: its values (as h5py reads them) and attributes."""

    __slots__ = ("values", "attrs")

    def __init__(self, values: Any, attrs: Dict[str, Any]) -> None:
        self.values = values
        self.attrs = attrs

    @property
    def shape(self) -> Tuple[int, ...]:
        return tuple(np.shape(self.values))

    @property
    def ndim(self) -> int:
        return len(self.shape)


#: A file as (root attributes, groups' attributes, datasets), paths without the
#: leading "/", e.g. "trajectory/energy".
_Tree = Tuple[Dict[str, Any], Dict[str, Dict[str, Any]], Dict[str, _Data]]


def _order(path: str) -> Tuple[str, ...]:
    """HDF5's visiting order: depth first, names in byte order."""
    return tuple(path.split("/"))


def _tree_of_file(f: h5py.File) -> _Tree:
    groups: Dict[str, Dict[str, Any]] = {}
    data: Dict[str, _Data] = {}

    def visit(path: str, obj: Any) -> None:
        if isinstance(obj, h5py.Dataset):
            data[path] = _Data(obj[()], _attrs(obj))
        elif isinstance(obj, h5py.Group):
            groups[path] = _attrs(obj)

    f.visititems(visit)
    return _attrs(f), groups, data


def _tree_of_result(result: "_library.Result") -> _Tree:
    """The items of a result: datasets as read-only arrays over its memory (a scalar
    as a numpy scalar, as h5py gives it), attributes as h5py gives them."""
    root: Dict[str, Any] = {}
    groups: Dict[str, Dict[str, Any]] = {}
    data: Dict[str, _Data] = {}
    for i in range(len(result)):
        path, name, kind, itemsize, shape = result.item(i)
        path = path.strip("/")
        value = result.value(i, kind, itemsize, shape)
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value[()]
        if not name:
            data[path] = _Data(value, {})
            parts = path.split("/")
            for k in range(1, len(parts)):
                groups.setdefault("/".join(parts[:k]), {})
            continue
        if not path:
            owner = root
        elif path in data:
            owner = data[path].attrs
        else:
            owner = groups.setdefault(path, {})
        owner[name] = _text(value)
    return root, groups, data


def from_image(image: bytes) -> xr.Dataset:
    """The Dataset of an HDF5 file image (the bytes of a file dpend writes); the
    image is kept in ``ds.encoding`` for ``ds.dpend.to_hdf5``."""
    with h5py.File(io.BytesIO(image), "r") as f:
        ds = _build(*_tree_of_file(f))
    ds.encoding[_ENCODING_KEY] = bytes(image)
    return ds


def from_result(result: "_library.Result") -> xr.Dataset:
    """The Dataset of a library run's result: its arrays without a copy (read-only
    numpy arrays over the library's memory; a sweep's from its file's image). The
    result is kept in ``ds.encoding`` for ``ds.dpend.to_hdf5``."""
    if len(result) == 0:
        ds = from_image(result.image())
    else:
        ds = _build(*_tree_of_result(result))
    ds.encoding[_RESULT_KEY] = result
    return ds


def _build(root: Dict[str, Any], groups: Dict[str, Dict[str, Any]],
           data: Dict[str, _Data]) -> xr.Dataset:
    """The Dataset of a file's tree (see the module's docstring)."""
    tops = [g for g in groups if "/" not in g]
    top = tops[0] if len(tops) == 1 else ""
    attrs: Dict[str, Any] = dict(root)
    datasets: List[Tuple[str, str, _Data]] = []   # (name, group path, dataset)

    def relative(path: str) -> str:
        return path[len(top) + 1:] if top and path.startswith(top + "/") else path

    for path in sorted(groups, key=_order):
        rel = relative(path) if path != top else ""
        for k, v in groups[path].items():
            key = k if not rel and k not in attrs else (f"{rel}/{k}" if rel else f"{top}/{k}")
            attrs[key] = v
    for path in sorted(data, key=_order):
        datasets.append((relative(path), path.rsplit("/", 1)[0] if "/" in path else "",
                         data[path]))

    # The time axis and the sweep maps of each group.
    times: Dict[str, Tuple[str, int]] = {}
    maps: Dict[str, Tuple[int, int]] = {}
    for name, group, dset in datasets:
        leaf = name.rsplit("/", 1)[-1]
        if leaf == "t" and dset.ndim == 1:
            rel_group = name.rsplit("/", 1)[0] if "/" in name else ""
            base = _TIME_NAME.get(top, "time")
            times[group] = (f"{rel_group}/{base}" if rel_group else base, dset.shape[0])
    for group in {g for _, g, _ in datasets}:
        prefix = f"{group}/" if group else ""
        a1, a2 = data.get(prefix + "axis1"), data.get(prefix + "axis2")
        if a1 is not None and a2 is not None:
            maps[group] = (a2.shape[0], a1.shape[0])
    # a nested group without its own t or axes shares its parent's (sweep/final)
    for name, group, dset in datasets:
        parent = group
        while parent and parent not in maps and "/" in parent:
            parent = parent.rsplit("/", 1)[0]
        if parent in maps:
            maps.setdefault(group, maps[parent])

    data_vars: Dict[str, xr.Variable] = {}
    coords: Dict[str, xr.Variable] = {}
    for name, group, dset in datasets:
        dims = _dims(top, name, name, dset, times.get(group), root, maps.get(group))
        leaf = name.rsplit("/", 1)[-1]
        if group in maps and leaf in ("axis1", "axis2") and dset.ndim == 1:
            dims = [leaf]
        var = xr.Variable(dims, dset.values, attrs=dict(dset.attrs))
        if (leaf == "t" and group in times) or dims == [name]:
            coords[name] = var
        else:
            data_vars[name] = var
    labels = root.get("coordinates")
    if isinstance(labels, str):
        names = labels.split()
        used = [v for v in list(data_vars.values()) + list(coords.values())
                if "coordinate" in v.dims]
        if used and all(v.sizes["coordinate"] == len(names) for v in used):
            coords["coordinate"] = xr.Variable(["coordinate"], names)
    if any("xy" in v.dims for v in data_vars.values()):
        coords["xy"] = xr.Variable(["xy"], ["x", "y"])
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def _same(ds: xr.Dataset, original: xr.Dataset) -> bool:
    """Whether ds still holds the run's values (same variables, shapes, dtypes,
    values; NaN equal to NaN)."""
    names = set(ds.variables) - {"coordinate", "xy"}
    if names != set(original.variables) - {"coordinate", "xy"}:
        return False
    for name in names:
        a, b = ds.variables[name].values, original.variables[name].values
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype.kind in "fc":
            if not np.array_equal(a, b, equal_nan=True):
                return False
        elif not np.array_equal(a, b):
            return False
    return True


@xr.register_dataset_accessor("dpend")
class DpendAccessor:
    """``ds.dpend``: the HDF5 file that the dpend run of ``ds`` wrote in memory."""

    def __init__(self, ds: xr.Dataset) -> None:
        self._ds = ds

    @property
    def image(self) -> bytes:
        """The HDF5 file image (bytes: exactly the file the command line writes;
        made from the run's result when first asked for)."""
        result = self._ds.encoding.get(_RESULT_KEY)
        if result is not None:
            return result.image()
        image = self._ds.encoding.get(_ENCODING_KEY)
        if image is None:
            raise ValueError("this Dataset holds no dpend file image (it was not "
                             "returned by a dpend function, or encoding was reset)")
        return image

    def _original(self) -> xr.Dataset:
        result = self._ds.encoding.get(_RESULT_KEY)
        if result is not None and len(result) > 0:
            return _build(*_tree_of_result(result))
        return from_image(self.image)

    def to_hdf5(self, path: "os.PathLike[str] | str", force: bool = False) -> None:
        """Write the run's HDF5 file to `path`: exactly the file the command line
        writes with --output. Refuses an existing `path` unless `force`, and a
        Dataset whose variables no longer hold the run's values (a selection or an
        edit: save that with ``ds.to_netcdf``). Written to a temporary file in the
        same folder, then renamed (os.replace): never a partial file at `path`."""
        image = self.image
        if not _same(self._ds, self._original()):
            raise ValueError("to_hdf5: this Dataset differs from the run's file (a "
                             "selection or a change); write it with to_netcdf instead")
        path = os.fspath(path)
        if os.path.exists(path) and not force:
            raise FileExistsError(f"to_hdf5: {path} exists (force=True replaces it)")
        folder = os.path.dirname(os.path.abspath(path))
        fd, tmp = tempfile.mkstemp(prefix=".dpend-", suffix=".h5.tmp", dir=folder)
        try:
            with os.fdopen(fd, "wb") as out:
                out.write(image)
                out.flush()
                os.fsync(out.fileno())
            if not force and os.path.exists(path):
                raise FileExistsError(f"to_hdf5: {path} exists (force=True replaces it)")
            os.replace(tmp, path)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
