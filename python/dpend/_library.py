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
from typing import Callable, List, Optional, Sequence, Tuple

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


def run(command: str, args: Sequence[str],
        progress: Optional[Progress] = None) -> Tuple[int, Optional[bytes], str]:
    """dpend_run: (error kind, the HDF5 file image or None, the message).

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
         progress: Optional[Progress] = None) -> Tuple[int, Optional[bytes], str]:
    with _run_lock:
        return _run_unlocked(command, args, progress)


def _run_unlocked(command: str, args: Sequence[str],
                  progress: Optional[Progress] = None) -> Tuple[int, Optional[bytes], str]:
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
    image = None
    if result.value:
        try:
            image = _image(result)
        finally:
            function("dpend_result_free")(result)
    return kind, image, text


def _image(result: ctypes.c_void_p) -> bytes:
    """The bytes of a result's file image (one copy, from the library's memory)."""
    n = function("dpend_result_bytes")(result)
    if n < 0:
        raise RuntimeError(f"dpend: dpend_result_bytes gave {n}")
    if n == 0:
        return b""
    address = function("dpend_result_data")(result)
    if not address:
        raise RuntimeError("dpend: dpend_result_data gave NULL for a result of "
                           f"{n} bytes")
    return ctypes.string_at(address, n)


def cancel() -> None:
    """Ask the run in progress in another thread to stop (between blocks or steps);
    it then ends as a failed run (:class:`dpend.RunError`)."""
    function("dpend_cancel")()


def version() -> str:
    """The library's version string (dpend_version)."""
    buf = ctypes.create_string_buffer(256)
    function("dpend_version")(buf, len(buf))
    return buf.value.decode("utf-8", errors="replace")
