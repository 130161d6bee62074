"""Loading libdpend.so with ctypes and calling its C interface (src/capi/).

The library lies next to this file (meson.build installs it into the package);
the environment variable DPEND_LIBRARY names another one (a development build).
ctypes releases the GIL around every call of a function of a ``ctypes.CDLL``
library, so a run blocks only its own thread: other Python threads go on, and one
of them may call :func:`cancel` to stop it. Runs are serialized by a lock (see
:func:`run`); Ctrl-C during a run in the main thread cancels it.
"""
from __future__ import annotations

import ctypes
import os
import pathlib
import threading
from typing import Any, Callable, List, Optional, Sequence, Tuple

import numpy as np

_MESSAGE_BYTES = 1 << 16   # the help texts and the models' table fit
_lock = threading.Lock()
_run_lock = threading.Lock()
_lib: Optional[ctypes.CDLL] = None

#: The error kinds of dpend_run (the command line's exit statuses, and 3).
OK, RUN_FAILED, BAD_INPUT, UNAVAILABLE = 0, 1, 2, 3

#: dpend_progress_fn: (done, total, what, label, user)
PROGRESS_FN = ctypes.CFUNCTYPE(None, ctypes.c_longlong, ctypes.c_longlong, ctypes.c_char_p,
                               ctypes.c_char_p, ctypes.c_void_p)

#: A progress callback of Python: (done, total, what, label).
Progress = Callable[[int, int, str, str], None]


def library_path() -> pathlib.Path:
    """The path of the library that :func:`library` loads."""
    override = os.environ.get("DPEND_LIBRARY")
    if override:
        return pathlib.Path(override)
    return pathlib.Path(__file__).resolve().parent / "libdpend.so"


def library() -> ctypes.CDLL:
    """libdpend.so, loaded once (OSError naming the path when it cannot be)."""
    global _lib
    with _lock:
        if _lib is None:
            path = library_path()
            try:
                lib = ctypes.CDLL(str(path))
            except OSError as e:
                raise OSError(f"dpend: cannot load the library {path}: {e}") from e
            _declare(lib)
            _lib = lib
        return _lib


def _declare(lib: ctypes.CDLL) -> None:
    """The C signatures of the functions the library has (a missing one is left
    out; :func:`function` says so when it is called)."""
    c_int, c_ll, c_void_p, c_char_p = (ctypes.c_int, ctypes.c_longlong, ctypes.c_void_p,
                                       ctypes.c_char_p)
    signatures = {
        "dpend_run": (c_int, [c_char_p, c_int, ctypes.POINTER(c_char_p),
                              ctypes.POINTER(c_void_p), c_char_p, c_int]),
        "dpend_run_progress": (c_int, [c_char_p, c_int, ctypes.POINTER(c_char_p),
                                       ctypes.POINTER(c_void_p), c_char_p, c_int,
                                       PROGRESS_FN, c_void_p]),
        "dpend_result_items": (c_int, [c_void_p]),
        "dpend_result_item": (c_int, [c_void_p, c_int, c_char_p, c_int, c_char_p, c_int,
                                      ctypes.POINTER(c_int), ctypes.POINTER(c_ll),
                                      ctypes.POINTER(c_int), ctypes.POINTER(c_ll)]),
        "dpend_result_item_bytes": (c_ll, [c_void_p, c_int]),
        "dpend_result_item_data": (c_void_p, [c_void_p, c_int]),
        "dpend_result_bytes": (c_ll, [c_void_p]),
        "dpend_result_copy": (c_int, [c_void_p, c_void_p, c_ll]),
        "dpend_result_data": (c_void_p, [c_void_p]),
        "dpend_result_free": (None, [c_void_p]),
        "dpend_cancel": (None, []),
        "dpend_version": (c_int, [c_char_p, c_int]),
    }
    for name, (restype, argtypes) in signatures.items():
        try:
            f = getattr(lib, name)
        except AttributeError:
            continue
        f.restype = restype
        f.argtypes = argtypes


def function(name: str):
    """The library's C function `name`; RuntimeError when this build lacks it."""
    lib = library()
    try:
        return getattr(lib, name)
    except AttributeError:
        raise RuntimeError(
            f"dpend: the library {library_path()} has no {name}: it was built without "
            "the C interface (src/capi/dpend_capi.f90); update the checkout and "
            "reinstall (pip install .)") from None


#: The item types of dpend_result_item (dpend.h).
REAL, INTEGER, STRING, TEXT = 1, 2, 3, 4


class _Memory:
    """Bytes of a result's item seen by numpy without a copy (read-only); holds the
    result, so the memory lives as long as any array made from it."""

    def __init__(self, owner: "Result", address: int, size: int) -> None:
        self.owner = owner
        self.__array_interface__ = {"shape": (size,), "typestr": "|u1",
                                    "data": (address, True), "version": 3}


class Result:
    """A run's result (dpend_result_* of dpend.h): its items, the file's datasets and
    attributes in the order written, and the file's image (made when first asked
    for). Released when the last reference to it (or to an array of it) goes."""

    def __init__(self, handle: int) -> None:
        self._handle = ctypes.c_void_p(handle)
        self._image: Optional[bytes] = None
        self._free = function("dpend_result_free")

    def __del__(self) -> None:
        if getattr(self, "_handle", None) is not None and self._handle.value:
            self._free(self._handle)
            self._handle = ctypes.c_void_p()

    def __len__(self) -> int:
        return function("dpend_result_items")(self._handle)

    def item(self, i: int) -> Tuple[str, str, int, int, Tuple[int, ...]]:
        """Item i: (path, name ('' a dataset), type, bytes per element, shape)."""
        path = ctypes.create_string_buffer(4096)
        name = ctypes.create_string_buffer(1024)
        kind, rank = ctypes.c_int(), ctypes.c_int()
        itemsize = ctypes.c_longlong()
        dims = (ctypes.c_longlong * 8)()
        if function("dpend_result_item")(self._handle, i, path, len(path), name, len(name),
                                         ctypes.byref(kind), ctypes.byref(itemsize),
                                         ctypes.byref(rank), dims) != OK:
            raise RuntimeError(f"dpend: dpend_result_item refused item {i}")
        return (path.value.decode("utf-8"), name.value.decode("utf-8"), kind.value,
                itemsize.value, tuple(dims[:rank.value]))

    def value(self, i: int, kind: int, itemsize: int, shape: Tuple[int, ...]) -> Any:
        """Item i's values: a read-only numpy array over the result's memory (no
        copy), or a str for a text attribute."""
        n = function("dpend_result_item_bytes")(self._handle, i)
        address = function("dpend_result_item_data")(self._handle, i)
        if kind == TEXT:
            return ctypes.string_at(address, n).decode("utf-8", errors="replace") if n else ""
        if kind == REAL:
            dtype = np.dtype("<f%d" % itemsize)
        elif kind == INTEGER:
            dtype = np.dtype("<i%d" % itemsize)
        elif kind == STRING:
            dtype = np.dtype("S%d" % itemsize)
        else:
            raise RuntimeError(f"dpend: item {i} has the unknown type {kind}")
        count = int(np.prod(shape, dtype=np.int64))
        if count * dtype.itemsize != n:
            raise RuntimeError(f"dpend: item {i} holds {n} bytes, not {count} x "
                               f"{dtype.itemsize}")
        if n == 0:
            return np.zeros(shape, dtype)
        return np.asarray(_Memory(self, address, n)).view(dtype).reshape(shape)

    def image(self) -> bytes:
        """The file's image (bytes), made once."""
        if self._image is None:
            n = function("dpend_result_bytes")(self._handle)
            address = function("dpend_result_data")(self._handle)
            if n <= 0 or not address:
                raise RuntimeError("dpend: the result's file image could not be made")
            self._image = ctypes.string_at(address, n)
        return self._image


def run(command: str, args: Sequence[str],
        progress: Optional[Progress] = None) -> Tuple[int, Optional[Result], str]:
    """dpend_run: (error kind, the result or None, the message).

    Runs are serialized (one at a time in the process, ``_run_lock``: the Fortran
    library runs one call at a time too: its command code is not reentrant; each
    run uses OpenMP threads itself). In the
    main thread the run goes to a worker thread so that Ctrl-C is seen: it calls
    dpend_cancel, waits for the run to stop and raises KeyboardInterrupt.

    `progress(done, total, what, label)` is called from the run's threads (see
    dpend_run_progress in dpend.h); if it raises, the run is cancelled and the
    exception raised here."""
    function("dpend_run")                      # a clear error before any thread
    if threading.current_thread() is not threading.main_thread():
        return _run(command, args, progress)
    box: list = []

    def work() -> None:
        try:
            box.append(("ok", _run(command, args, progress)))
        except BaseException as e:             # handed to the caller below
            box.append(("error", e))

    worker = threading.Thread(target=work, name=f"dpend {command}", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.1)
    except KeyboardInterrupt:
        try:
            cancel()
            worker.join()
        except RuntimeError:                   # a library without dpend_cancel
            pass
        raise
    status, value = box[0]
    if status == "error":
        raise value
    return value


def _run(command: str, args: Sequence[str],
         progress: Optional[Progress] = None) -> Tuple[int, Optional[Result], str]:
    with _run_lock:
        return _run_unlocked(command, args, progress)


def _run_unlocked(command: str, args: Sequence[str],
                  progress: Optional[Progress] = None) -> Tuple[int, Optional[Result], str]:
    encoded = [a.encode("utf-8") for a in args]
    argv = (ctypes.c_char_p * max(len(encoded), 1))(*encoded)
    result = ctypes.c_void_p()
    message = ctypes.create_string_buffer(_MESSAGE_BYTES)
    raised: List[BaseException] = []
    if progress is None:
        kind = function("dpend_run")(command.encode("utf-8"), len(encoded), argv,
                                     ctypes.byref(result), message, _MESSAGE_BYTES)
    else:
        def tell(done, total, what, label, _user):
            if raised:
                return
            try:
                progress(int(done), int(total), (what or b"").decode(),
                         (label or b"").decode())
            except BaseException as e:         # the run stops; raised below
                raised.append(e)
                cancel()

        callback = PROGRESS_FN(tell)           # alive until the call returns
        kind = function("dpend_run_progress")(command.encode("utf-8"), len(encoded), argv,
                                              ctypes.byref(result), message,
                                              _MESSAGE_BYTES, callback, None)
    if raised:
        if result.value:
            function("dpend_result_free")(result)
        raise raised[0]
    text = message.value.decode("utf-8", errors="replace")
    return kind, (Result(result.value) if result.value else None), text


def cancel() -> None:
    """Ask the run in progress in another thread to stop (between blocks or steps);
    it then ends as a failed run (:class:`dpend.RunError`)."""
    function("dpend_cancel")()


def version() -> str:
    """The library's version string (dpend_version)."""
    buf = ctypes.create_string_buffer(256)
    function("dpend_version")(buf, len(buf))
    return buf.value.decode("utf-8", errors="replace")
