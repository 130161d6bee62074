"""The dpend commands as Python functions: keyword arguments become the command
line's options, the HDF5 file the command writes comes back as an xarray.Dataset.
"""
from __future__ import annotations

import numbers
import os
import sys
import time
from typing import Any, Callable, List, Optional, Sequence, Union

import numpy as np
import xarray as xr

from . import _library
from ._dataset import from_result

_RESERVED = ("output", "force", "quiet")


class RunError(RuntimeError):
    """A run that started and failed partway (the command line's exit status 1).
    ``result`` holds what was computed (an xarray.Dataset), or None."""

    def __init__(self, message: str, result: Optional[xr.Dataset] = None) -> None:
        super().__init__(message)
        self.result = result


def _value(value: Any) -> str:
    """One option value as the command line takes it: floats by repr() (the
    shortest text that reads back to the same double), integers in decimal."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"a boolean inside a list: {value!r}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"cannot pass {type(value).__name__} {value!r} as an option value")


def options(**kw: Any) -> List[str]:
    """The command-line options of keyword arguments: ``t_end=1`` -> ``--t-end 1``,
    ``m=[1, 2]`` -> ``--m 1,2``, ``True`` -> the bare flag, ``False``/``None`` ->
    left out. Order kept. ``output``, ``force`` and ``quiet`` are refused (the
    file stays in memory: ``ds.dpend.to_hdf5(path)`` writes it)."""
    args: List[str] = []
    for key, value in kw.items():
        name = key.rstrip("_")                  # lambda_ -> lambda
        if name in _RESERVED:
            raise TypeError(f"dpend: {key}= is not an option here (the file stays in "
                            "memory; write it with ds.dpend.to_hdf5(path))")
        flag = "--" + name.replace("_", "-")
        if value is None or value is False or (isinstance(value, np.bool_) and not value):
            continue
        if value is True or isinstance(value, np.bool_):
            args.append(flag)
        elif isinstance(value, (list, tuple, np.ndarray)):
            args += [flag, ",".join(_value(v) for v in np.asarray(value, dtype=object).ravel())
                     if isinstance(value, np.ndarray) else ",".join(_value(v) for v in value)]
        else:
            args += [flag, _value(value)]
    return args


ProgressArg = Union[None, bool, str, Callable[[int, int, str, str], None]]


class _Bar:
    """A tqdm bar (tqdm.auto: a widget in a notebook) over a run's progress reports,
    drawn once the run has lasted `after` seconds (0: at once); without tqdm, a
    plain line on stderr at most every 10 s when asked for explicitly (`after` 0)."""

    def __init__(self, after: float) -> None:
        self.after = after
        self.start = time.monotonic()
        self.bar = None
        self.last_line = self.start
        try:
            from tqdm.auto import tqdm
            self.tqdm = tqdm
        except ImportError:
            self.tqdm = None

    def __call__(self, done: int, total: int, what: str, label: str) -> None:
        now = time.monotonic()
        if self.bar is None and self.tqdm is not None and now - self.start >= self.after:
            self.bar = self.tqdm(total=total, desc=label, unit=what or "part",
                                 unit_scale=True, leave=True)
        if self.bar is not None:
            self.bar.total = total
            self.bar.n = done
            self.bar.refresh()
        elif self.tqdm is None and self.after == 0 and now - self.last_line >= 10:
            self.last_line = now
            print(f"{label}: {done}/{total} {what}", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _progress(progress: ProgressArg):
    """The callback of a `progress=` argument, and the bar to close after the run."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        bar = _Bar(after=0.0)
        return bar, bar
    if isinstance(progress, str):
        if progress != "auto":
            raise ValueError(f"dpend: progress={progress!r}: give 'auto', True, False, "
                             "None or a callable (done, total, what, label)")
        bar = _Bar(after=1.0)
        return (bar, bar) if bar.tqdm is not None else (None, None)
    if callable(progress):
        return progress, None
    raise TypeError(f"dpend: progress= takes 'auto', True, False, None or a callable, "
                    f"not {type(progress).__name__}")


def run(command: str, *positional: "str | os.PathLike[str]", progress: ProgressArg = "auto",
        **kw: Any) -> xr.Dataset:
    """Run ``dpend COMMAND [POSITIONAL...] OPTIONS...`` in this process and return
    the file it writes as an xarray.Dataset (``ds.dpend.to_hdf5`` writes it out).

    Raises ValueError (refused input: the command line's one line, e.g.
    ``dpend simulate: invalid --t-end: ...``), RunError (the run failed partway;
    ``.result`` holds the partial Dataset or None), RuntimeError (internal error,
    or a library without the C interface). The GIL is released during the run
    (ctypes does so for every call into a CDLL): other threads go on, and
    ``dpend.cancel()`` from one of them stops the run (a RunError).

    ``progress``: ``"auto"`` (the default) a tqdm bar once a run has lasted a second
    (when tqdm is installed: ``pip install tqdm``); ``True`` a bar at once (or a
    line on stderr every 10 s without tqdm); ``None``/``False`` none; a callable
    ``f(done, total, what, label)`` is called at most every 0.1 s (``what`` the unit:
    'traj', 'runs', 'steps', or '' for parts of a horizon); if it raises, the run
    stops and the exception propagates."""
    args = [os.fspath(p) for p in positional] + options(**kw)
    callback, bar = _progress(progress)
    try:
        kind, handle, message = _library.run(command, args, callback)
    finally:
        if bar is not None:
            bar.close()
    result = from_result(handle) if handle is not None else None
    if kind == _library.OK:
        if result is None:
            raise RuntimeError(f"dpend {command}: the run succeeded but gave no file")
        return result
    if kind == _library.BAD_INPUT:
        raise ValueError(message)
    if kind == _library.RUN_FAILED:
        raise RunError(message, result)
    if kind == _library.UNAVAILABLE:
        raise NotImplementedError(message)
    raise RuntimeError(message or f"dpend {command}: internal error (kind {kind})")


def simulate(**kw: Any) -> xr.Dataset:
    """``dpend simulate``: one trajectory (variables t, q, qdot, energy, ... of
    /trajectory, dimension ``time``). Options as in docs/cli.md, e.g.
    ``simulate(q1=0, q2=0, method="rk4", dt=1e-4, t_end=10)``."""
    return run("simulate", **kw)


def lyapunov(**kw: Any) -> xr.Dataset:
    """``dpend lyapunov``: Lyapunov exponents with their running estimates."""
    return run("lyapunov", **kw)


def divergence(**kw: Any) -> xr.Dataset:
    """``dpend divergence``: divergence of nearby trajectories."""
    return run("divergence", **kw)


def poincare(**kw: Any) -> xr.Dataset:
    """``dpend poincare``: a Poincare section at one energy."""
    return run("poincare", **kw)


def indicators(**kw: Any) -> xr.Dataset:
    """``dpend indicators``: MEGNO, FLI, SALI, GALI_k against time."""
    return run("indicators", **kw)


def sweep(**kw: Any) -> xr.Dataset:
    """``dpend sweep``: maps over initial conditions or parameters (dimensions
    ``axis2, axis1`` for a grid, as /sweep stores them: rows axis 2)."""
    return run("sweep", **kw)


def fit(data: "str | os.PathLike[str]", **kw: Any) -> xr.Dataset:
    """``dpend fit DATA.csv``: estimate the initial state (and damping) from
    measured angles or positions; `data` the CSV file's path."""
    return run("fit", data, **kw)


def study(**kw: Any) -> xr.Dataset:
    """``dpend study``: the energy-conservation study of the methods (docs/study.md);
    e.g. ``study(quick=True)``. The Dataset holds the file docs/study-hdf5.md
    describes; its Markdown summary is ``ds["summary/markdown"]``. No figures are
    drawn (``scripts/plot_study.sh FILE DIR`` draws them from ``ds.dpend.to_hdf5``'s
    file)."""
    return run("study", **kw)


def _text(command: str) -> str:
    kind, _, message = _library.run(command, [])
    if kind != _library.OK:
        raise RuntimeError(message)
    return message


def models() -> str:
    """The models, their parameters with units and ranges, and what each command
    takes: the table of ``dpend models``."""
    return _text("models")


def methods() -> List[str]:
    """The integration methods' names (``dpend methods --names``), e.g. 'rk4'."""
    return _text("methods").split()
