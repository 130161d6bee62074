"""``dpend explore MAP.h5``: a map of ``dpend sweep`` in the browser. Click a pixel
to run it with the map's own settings and watch that pendulum (docs/explore.md).

    python -m dpend.explore out/flip_map.h5 [--port N] [--host H] [--open]

The server (``_server``) binds to 127.0.0.1 unless --host says otherwise, serves
only the map it was started with and its own assets (``static/``: no internet, no
CDN), and runs pixels through the library in this process (``_pixel``).
"""
from __future__ import annotations

import ipaddress
import re
import signal
import sys
from typing import List, Optional, Sequence, TextIO

USAGE = """\
usage: dpend explore MAP.h5 [--port N] [--host ADDRESS] [--open] [--max-runs N]
                           [--quiet]

Show a map written by dpend sweep in the browser: hover a pixel for its
coordinates and value, click it to run that pixel with exactly the map's
settings (its value again, beside the map's, then its motion animated, with
its angles and energy error), shift-click a second pixel to compare the two.
Arrow keys move the selected pixel, Enter runs it (Shift+Enter: the second).

options:
  --port N        the port, 0 to 65535 (0: any free one); default 8765
  --host ADDRESS  the address to listen on; default 127.0.0.1 (this machine
                  only). Another address lets others reach the page and run
                  pixels on this machine
  --open          open the page in the default browser, when there is one
  --max-runs N    pixel runs at once, 1 to 8; default 2 (more wait: refused
                  with 'busy', the page says so)
  --quiet         print only the page's address (refusals and failures are
                  still logged on stderr, one line each)
  -h, --help      this text

The page needs nothing from the internet. Ctrl-C stops the server.
Exit status: 0 stopped by Ctrl-C, 1 the server could not start, 2 invalid input."""


class UsageError(ValueError):
    """Invalid input on the command line (exit status 2), one line."""


def _integer(name: str, text: str, low: int, high: int) -> int:
    if not re.fullmatch(r"[0-9]{1,9}", text) or not (low <= int(text) <= high):
        raise UsageError(f"{name} '{ascii(text)[1:-1]}': an integer in [{low}, {high}] "
                         "is needed")
    return int(text)


def parse(argv: Sequence[str]) -> dict:
    """The options of the command line (UsageError: one line naming the field)."""
    opts = {"map": None, "port": 8765, "host": "127.0.0.1", "open": False, "max_runs": 2,
            "help": False, "quiet": False}
    seen = set()
    args = list(argv)
    k = 0
    while k < len(args):
        a = args[k]
        if a in ("-h", "--help"):
            opts["help"] = True
        elif a in ("--port", "--host", "--max-runs"):
            if a in seen:
                raise UsageError(f"{a} is given twice")
            seen.add(a)
            if k + 1 >= len(args):
                raise UsageError(f"{a} needs a value")
            value = args[k + 1]
            k += 1
            if a == "--port":
                opts["port"] = _integer("--port", value, 0, 65535)
            elif a == "--max-runs":
                opts["max_runs"] = _integer("--max-runs", value, 1, 8)
            else:
                try:
                    ipaddress.ip_address(value)
                except ValueError:
                    if value != "localhost":
                        raise UsageError(f"--host '{value}': an IPv4 or IPv6 address (e.g. "
                                         "127.0.0.1, 0.0.0.0) or localhost") from None
                opts["host"] = value
        elif a in ("--open", "--quiet"):
            if a in seen:
                raise UsageError(f"{a} is given twice")
            seen.add(a)
            opts[a[2:]] = True
        elif a.startswith("-") and a != "-":
            raise UsageError(f"unknown option '{a}' (--port, --host, --open, --max-runs, "
                             "--quiet, --help)")
        elif opts["map"] is not None:
            raise UsageError(f"a second map '{a}': explore shows one MAP.h5")
        else:
            opts["map"] = a
        k += 1
    if opts["map"] is None and not opts["help"]:
        raise UsageError("MAP.h5 is missing: dpend explore MAP.h5 (a file of dpend sweep)")
    return opts


def main(argv: Optional[List[str]] = None, out: TextIO = sys.stdout,
         err: TextIO = sys.stderr) -> int:
    """The command: parse, check the map, serve until Ctrl-C. Returns the exit status."""
    from ._map import MapError, open_map
    from ._server import Explorer, make_server

    try:
        opts = parse(sys.argv[1:] if argv is None else argv)
    except UsageError as e:
        print(f"dpend explore: {e}", file=err)
        return 2
    if opts["help"]:
        print(USAGE, file=out)
        return 0
    try:
        m = open_map(opts["map"])
    except MapError as e:
        print(f"dpend explore: {e}", file=err)
        return 2
    explorer = Explorer(m, max_runs=opts["max_runs"], log=err, quiet=opts["quiet"])
    try:
        server = make_server(explorer, opts["host"], opts["port"])
    except OSError as e:
        print(f"dpend explore: cannot listen on {opts['host']} port {opts['port']}: "
              f"{e.strerror or e}", file=err)
        return 1
    host, port = server.server_address[:2]
    shown = f"[{host}]" if ":" in str(host) else host
    url = f"http://{shown}:{port}/"
    local = ipaddress.ip_address(host).is_loopback if host != "localhost" else True
    if not opts["quiet"]:
        print(f"dpend explore: {m.path}: {m.n1} x {m.n2} pixels ({m.axis1}, {m.axis2}); "
              f"maps {', '.join(m.maps)}", file=out)
    print(f"dpend explore: serving at {url} "
          + ("(this machine only)" if local else
             f"(listening on {host}: other machines can reach it and run pixels here)"),
          file=out, flush=True)
    if opts["open"]:
        import webbrowser
        if not webbrowser.open(url):
            print("dpend explore: no browser to open here; open the address above",
                  file=err)
    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)            # kill: stops as Ctrl-C does
    signal.signal(signal.SIGINT, stop)             # also when started in the background
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("dpend explore: stopped", file=err)
    finally:
        server.server_close()
    return 0
