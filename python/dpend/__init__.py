"""dpend from Python: the double pendulum's commands in-process.

Each command is a function whose keyword arguments are the command line's options
(``t_end=1`` -> ``--t-end 1``; docs/cli.md) and which returns the HDF5 file the
command writes, as an ``xarray.Dataset`` (names and dimensions: the docstring of
``dpend._dataset``; docs/python.md). The results are bitwise those of the
command line built with the release flags (scripts/flags.sh)::

    import dpend
    ds = dpend.simulate(q1=0, q2=0, t_end=1)
    ds.energy[-1]
    ds.dpend.to_hdf5("release.h5")     # the file `dpend simulate --output` writes

The library (libdpend.so, next to this file) is called through ctypes, which
releases the GIL during each call.
"""
from __future__ import annotations

from . import _dataset  # noqa: F401  (registers the ds.dpend accessor)
from . import _library
from ._commands import (RunError, divergence, fit, indicators, lyapunov, methods, models,
                        options, poincare, run, simulate, study, sweep)
from ._dataset import from_image
from ._library import cancel, library_path
from ._signatures import document as _document
from . import _commands


def _help_text(command: str) -> str:
    kind, _, text = _library._run(command, ["--help"])
    if kind != _library.OK:
        raise RuntimeError(text)
    return text


# help(dpend.sweep): the options and the text of `dpend sweep --help`
_document({name: getattr(_commands, name) for name in (
    "simulate", "lyapunov", "indicators", "divergence", "poincare", "sweep", "fit",
    "study")}, _help_text)


def _version() -> str:
    try:
        from importlib.metadata import version
        return version("dpend")
    except Exception:
        return "unknown"


__version__ = _version()

__all__ = ["RunError", "cancel", "divergence", "fit", "from_image", "indicators",
           "library_path", "lyapunov", "methods", "models", "options", "poincare", "run",
           "simulate", "study", "sweep", "__version__"]
