"""Stopping a long sweep: dpend.cancel() from another thread, and Ctrl-C (SIGINT) in
a process running a sweep in its main thread. Each stop returns within a block's
time (the measured seconds are printed; the bound asserted here is loose, the figure
is quoted from scripts/python_bench.py)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import dpend

# A sweep of minutes in the release build (262144 pixels to t = 1000 sqrt(l1/g)).
LONG = dict(n=512, t_end=1000, stop_at="end")


def test_cancel_from_another_thread():
    box = {}

    def work():
        try:
            dpend.sweep(**LONG)
            box["error"] = None
        except BaseException as e:       # the RunError expected
            box["error"] = e
        box["t"] = time.monotonic()

    worker = threading.Thread(target=work)
    worker.start()
    time.sleep(1.0)
    t0 = time.monotonic()
    dpend.cancel()
    worker.join(30)
    assert not worker.is_alive(), "the sweep did not stop"
    seconds = box["t"] - t0
    print(f"cancel: the sweep returned {seconds:.3f} s after the request")
    assert isinstance(box["error"], dpend.RunError), box["error"]
    assert "interrupted on request" in str(box["error"])
    assert box["error"].result is not None        # the blocks done
    assert seconds < 5.0
    # the library is usable after it
    assert float(dpend.simulate(t_end=0.1).energy[0]) == 0.0


@pytest.mark.parametrize("command, kw", [
    ("simulate", dict(t_end=1e5, dt=1e-4, save_every=10000)),
    ("lyapunov", dict(t_end=1e6)),
    ("indicators", dict(t_end=1e6)),
])
def test_cancel_stops_the_other_commands(command, kw):
    """A trajectory of minutes stops within 256 steps of the request: a RunError
    whose result holds the samples so far."""
    box = {}

    def work():
        try:
            getattr(dpend, command)(**kw, progress=None)
            box["error"] = None
        except BaseException as e:
            box["error"] = e
        box["t"] = time.monotonic()

    worker = threading.Thread(target=work)
    worker.start()
    time.sleep(1.0)
    t0 = time.monotonic()
    dpend.cancel()
    worker.join(30)
    assert not worker.is_alive(), f"{command} did not stop"
    seconds = box["t"] - t0
    print(f"cancel: {command} returned {seconds:.3f} s after the request")
    assert isinstance(box["error"], dpend.RunError), box["error"]
    assert "stopped on request" in str(box["error"]), str(box["error"])
    assert seconds < 1.0


def test_sigint_stops_a_sweep_in_the_main_thread(tmp_path):
    script = tmp_path / "run.py"
    script.write_text(textwrap.dedent(f"""
        import sys, time, dpend
        print("started", flush=True)
        try:
            dpend.sweep(**{LONG!r})
            print("finished", flush=True)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic(), flush=True)
        print("after", float(dpend.simulate(t_end=0.1).energy[0]), flush=True)
    """))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                            env=dict(os.environ))
    assert proc.stdout.readline().strip() == "started"
    time.sleep(1.5)
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    lines = out.split("\n")
    assert lines[0].startswith("interrupted"), out
    seconds = float(lines[0].split()[1]) - t0
    print(f"SIGINT: the sweep returned {seconds:.3f} s after the signal")
    assert seconds < 5.0
    assert lines[1] == "after 0.0", out
    assert proc.returncode == 0
