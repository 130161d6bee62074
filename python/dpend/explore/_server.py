"""The page's server: the map it was started with, its own assets, and pixel runs.

Routes (GET and HEAD only):

  /                   the page (static/index.html); /explore.js, /explore.css
  /api/map            the map's description (JSON: axes, maps, settings)
  /api/values?name=N  one map's values, float64 little-endian, row j = axis 2
  /api/pixel?i=I&j=J  pixel (I, J)'s run (JSON: map and run values, the motion)
  /api/run.h5?i=I&j=J the same run's trajectory as dpend simulate's HDF5 file
  /api/run.csv?i=I&j=J  the same as CSV

Every request is checked before any work: the path among the routes, each query
key among the route's, each value whole and in range. A refusal is one line (HTTP
400, 404 or 405; the page shows it) and the same line goes to the log. A request
starts at most one pixel's run (the value: the map's sweep for that pixel; the
motion: simulate to the map's t_end), at most `max_runs` at once (503 beyond).
"""
from __future__ import annotations

import collections
import ipaddress
import json
import os
import re
import socket
import sys
import threading
import time
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any, Callable, Dict, Optional, TextIO, Tuple
from urllib.parse import parse_qsl, urlsplit

from ._map import MapFile
from ._pixel import PixelRun, run_pixel

_ASSETS = {"/": ("index.html", "text/html; charset=utf-8"),
           "/index.html": ("index.html", "text/html; charset=utf-8"),
           "/explore.js": ("explore.js", "text/javascript; charset=utf-8"),
           "/explore.css": ("explore.css", "text/css; charset=utf-8")}
_PIXEL_ROUTES = ("/api/pixel", "/api/run.h5", "/api/run.csv")
_MAX_QUERY = 512
_INDEX = re.compile(r"[0-9]{1,9}")


def _shown(text: str, n: int = 40) -> str:
    """A request's text in a one-line message: at most n characters, control and
    non-ASCII characters escaped (no forged log lines, no terminal escapes)."""
    return ascii(text[:n])[1:-1]


class Refusal(Exception):
    """A request refused before any work: (HTTP status, one line)."""

    def __init__(self, status: HTTPStatus, line: str) -> None:
        super().__init__(line)
        self.status = status
        self.line = line


def _asset(name: str) -> bytes:
    return resources.files("dpend.explore").joinpath("static", name).read_bytes()


class Explorer:
    """The state behind the page: the checked map, its assets, the runs in flight
    (at most `max_runs`) and the last runs (a few, for the downloads)."""

    def __init__(self, m: MapFile, max_runs: int = 2, log: TextIO = sys.stderr,
                 runner: Callable[[MapFile, int, int], PixelRun] = run_pixel,
                 quiet: bool = False) -> None:
        self.map = m
        self.quiet = quiet
        self.log = log
        self.runner = runner
        self.max_runs = max_runs
        self.slots = threading.BoundedSemaphore(max_runs)
        self.recent: "collections.OrderedDict[Tuple[int, int], PixelRun]" = \
            collections.OrderedDict()
        self.lock = threading.Lock()
        self.assets = {path: (_asset(name), kind) for path, (name, kind) in _ASSETS.items()}
        self.description = json.dumps(m.describe()).encode("utf-8")
        stem = os.path.splitext(os.path.basename(m.path))[0]
        self.stem = re.sub(r"[^A-Za-z0-9._-]", "_", stem) or "map"   # a header's file name
        self.values: Dict[str, bytes] = {}
        self.hosts: Optional[set] = None       # the Host headers accepted (None: any)

    def check_host(self, host: Optional[str]) -> None:
        """A server on a loopback address answers only requests addressed to it (a web
        page elsewhere cannot reach it through a name that resolves here)."""
        if self.hosts is not None and (host or "").lower() not in self.hosts:
            raise Refusal(HTTPStatus.FORBIDDEN, f"Host '{_shown(host or '')}' is not this "
                          "server's address (only 127.0.0.1, localhost or ::1 and its port)")

    def say(self, line: str) -> None:
        print(f"dpend explore: {line}", file=self.log, flush=True)

    # -- checks ------------------------------------------------------------------
    def query(self, route: str, text: str, allowed: Tuple[str, ...]) -> Dict[str, str]:
        """The query's values by key: each key allowed, given once, with a value."""
        if len(text) > _MAX_QUERY:
            raise Refusal(HTTPStatus.BAD_REQUEST,
                          f"the query has {len(text)} characters (at most {_MAX_QUERY})")
        try:
            pairs = parse_qsl(text, keep_blank_values=True, strict_parsing=bool(text),
                              errors="strict", max_num_fields=8)
        except (ValueError, UnicodeDecodeError) as e:
            raise Refusal(HTTPStatus.BAD_REQUEST, f"the query '{_shown(text, 60)}' is not "
                          f"key=value pairs ({e})") from None
        got: Dict[str, str] = {}
        for key, value in pairs:
            if key not in allowed:
                hint = ""
                if key in ("t_end", "dt", "n_steps", "method", "h"):
                    hint = (f" (a pixel's run uses the map's settings: t_end = "
                            f"{float(self.map.attrs['t_end']):.6g} s, rk4, "
                            f"h = {float(self.map.attrs['h']):.6g} s)")
                raise Refusal(HTTPStatus.BAD_REQUEST, f"{_shown(key)} = '{_shown(value)}': "
                              f"not a parameter of {route}{hint}; accepted: "
                              f"{', '.join(allowed) or 'none'}")
            if key in got:
                raise Refusal(HTTPStatus.BAD_REQUEST, f"{_shown(key)} is given twice")
            got[key] = value
        for key in allowed:
            if key not in got:
                raise Refusal(HTTPStatus.BAD_REQUEST, f"{key} is missing: {route} needs "
                              f"{', '.join(allowed)}")
        return got

    def pixel(self, q: Dict[str, str]) -> Tuple[int, int]:
        """The pixel (i, j) of a query: whole integers inside the grid."""
        out = []
        for key, n, axis in (("i", self.map.n1, self.map.axis1),
                             ("j", self.map.n2, self.map.axis2)):
            value = q[key]
            if not _INDEX.fullmatch(value) or int(value) >= n:
                raise Refusal(HTTPStatus.BAD_REQUEST,
                              f"{key} = '{_shown(value)}': the pixel's index along axis "
                              f"{axis}, an integer in [0, {n - 1}]")
            out.append(int(value))
        return out[0], out[1]

    # -- work --------------------------------------------------------------------
    def run(self, i: int, j: int) -> PixelRun:
        """Pixel (i, j)'s run (the last few are kept); at most max_runs at once."""
        with self.lock:
            done = self.recent.get((i, j))
            if done is not None:
                self.recent.move_to_end((i, j))
                return done
        if not self.slots.acquire(blocking=False):
            raise Refusal(HTTPStatus.SERVICE_UNAVAILABLE,
                          f"busy: {self.max_runs} run{'s' if self.max_runs > 1 else ''} in "
                          "progress (the most at once: --max-runs); try again")
        try:
            result = self.runner(self.map, i, j)
        finally:
            self.slots.release()
        with self.lock:
            self.recent[(i, j)] = result
            while len(self.recent) > 8:
                self.recent.popitem(last=False)
        return result

    def answer(self, path: str, text: str) -> Tuple[bytes, str, Dict[str, str]]:
        """The body, content type and extra headers of a GET of `path`?`text`."""
        if path in self.assets:
            self.query(path, text, ())
            body, kind = self.assets[path]
            return body, kind, {}
        if path == "/api/map":
            self.query(path, text, ())
            return self.description, "application/json", {}
        if path == "/api/values":
            name = self.query(path, text, ("name",))["name"]
            if name not in self.map.maps:
                raise Refusal(HTTPStatus.BAD_REQUEST, f"name = '{_shown(name)}': not a map "
                              f"of this file; accepted: {', '.join(self.map.maps)}")
            with self.lock:                     # each map's bytes made once
                if name not in self.values:
                    self.values[name] = self.map.maps[name].astype("<f8").tobytes()
                return self.values[name], "application/octet-stream", {}
        if path in _PIXEL_ROUTES:
            i, j = self.pixel(self.query(path, text, ("i", "j")))
            result = self.run(i, j)
            if path == "/api/pixel":
                return json.dumps(result.page).encode("utf-8"), "application/json", {}
            stem = f"{self.stem}_pixel_{i}_{j}"
            if path == "/api/run.csv":
                return result.csv(), "text/csv; charset=utf-8", \
                    {"Content-Disposition": f'attachment; filename="{stem}.csv"'}
            return result.trajectory.dpend.image, "application/x-hdf5", \
                {"Content-Disposition": f'attachment; filename="{stem}.h5"'}
        raise Refusal(HTTPStatus.NOT_FOUND, f"'{_shown(path, 80)}' is not served (only the page, "
                      f"its assets and the map {os.path.basename(self.map.path)}: "
                      "/, /api/map, /api/values, /api/pixel, /api/run.h5, /api/run.csv)")


def handler_for(explorer: Explorer) -> type:
    """The request handler class of a server for `explorer`."""

    class Handler(BaseHTTPRequestHandler):
        server_version = "dpend-explore"
        sys_version = ""
        timeout = 60                           # an idle connection is closed

        def log_message(self, format: str, *args: Any) -> None:   # noqa: A002
            pass                                   # one line per request: below

        def _send(self, status: HTTPStatus, body: bytes, kind: str,
                  headers: Optional[Dict[str, str]] = None, head: bool = False) -> None:
            self.send_response(status)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.send_header("X-Content-Type-Options", "nosniff")
            self.send_header("Content-Security-Policy",
                             "default-src 'self'; img-src 'self' data: blob:; "
                             "style-src 'self'; script-src 'self'")
            for k, v in (headers or {}).items():
                self.send_header(k, v)
            self.end_headers()
            if not head:
                self.wfile.write(body)

        def _get(self, head: bool) -> None:
            start = time.perf_counter()
            try:
                explorer.check_host(self.headers.get("Host"))
                if len(self.path) > 2 * _MAX_QUERY:
                    raise Refusal(HTTPStatus.BAD_REQUEST,
                                  f"the request's path has {len(self.path)} characters")
                parts = urlsplit(self.path)
                body, kind, headers = explorer.answer(parts.path, parts.query)
                self._send(HTTPStatus.OK, body, kind, headers, head)
                if parts.path.startswith("/api/") and parts.path != "/api/values" \
                        and not explorer.quiet:
                    explorer.say(f"{self.command} {_shown(self.path, 120)}: "
                                 f"{time.perf_counter() - start:.3f} s")
            except Refusal as r:
                explorer.say(f"refused {self.command} {_shown(self.path, 120)}: {r.line}")
                self._send(r.status, (r.line + "\n").encode("utf-8"),
                           "text/plain; charset=utf-8", head=head)
            except (ValueError, RuntimeError) as e:   # the library's refusal or failure
                line = str(e).splitlines()[0] if str(e) else type(e).__name__
                if isinstance(e, ValueError):    # the map's settings, not the request
                    line = f"the library refused the map's settings: {line}"
                explorer.say(f"failed {self.command} {_shown(self.path, 120)}: {line}")
                self._send(HTTPStatus.INTERNAL_SERVER_ERROR, (line + "\n").encode(),
                           "text/plain; charset=utf-8", head=head)
            except (BrokenPipeError, ConnectionResetError):
                pass                                   # the page went away
            except Exception as e:                     # a bug: said, and the server stays up
                line = f"internal error: {type(e).__name__}: {e}".splitlines()[0]
                explorer.say(f"failed {self.command} {_shown(self.path, 120)}: {line}")
                self._send(HTTPStatus.INTERNAL_SERVER_ERROR, (line + "\n").encode(),
                           "text/plain; charset=utf-8", head=head)

        def do_GET(self) -> None:                      # noqa: N802
            self._get(head=False)

        def do_HEAD(self) -> None:                     # noqa: N802
            self._get(head=True)

        def _refuse_method(self) -> None:
            line = f"method {_shown(self.command)} is not served (GET and HEAD only)"
            explorer.say(f"refused {_shown(self.command)} {_shown(self.path, 120)}: {line}")
            self._send(HTTPStatus.METHOD_NOT_ALLOWED, (line + "\n").encode(),
                       "text/plain; charset=utf-8")

        do_POST = do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _refuse_method

    return Handler


class _Server6(ThreadingHTTPServer):
    address_family = socket.AF_INET6


def make_server(explorer: Explorer, host: str, port: int) -> ThreadingHTTPServer:
    """A threading HTTP server for `explorer` bound to (host, port) (0: any free port;
    an IPv6 address too). On a loopback address it answers only requests whose Host
    header names it (`Explorer.check_host`)."""
    kind = _Server6 if ":" in host else ThreadingHTTPServer
    server = kind((host, port), handler_for(explorer))
    server.daemon_threads = True
    bound = server.server_address[1]
    try:
        loopback = host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        loopback = False
    if loopback:
        explorer.hosts = {f"{name}:{bound}" for name in ("127.0.0.1", "localhost", "[::1]")}
    return server


def serve_in_thread(explorer: Explorer, host: str = "127.0.0.1",
                    port: int = 0) -> Tuple[ThreadingHTTPServer, str]:
    """Start a server in a background thread (tests, notebooks): (server, address)."""
    server = make_server(explorer, host, port)
    thread = threading.Thread(target=server.serve_forever, name="dpend explore",
                              daemon=True)
    thread.start()
    return server, f"http://{host}:{server.server_address[1]}/"
