"""Progress of a run: a callback is told of a sweep from its start to its end, never
backwards; one that raises stops the sweep and its exception comes out; a tqdm bar
(progress=True) ends at the total."""
from __future__ import annotations

import time

import pytest

import dpend

LONG = dict(n=512, t_end=1000, stop_at="end")   # minutes in the release build


def test_callback_sees_a_sweep_from_start_to_end():
    told = []
    dpend.sweep(n=64, t_end=5, progress=lambda *a: told.append(a))
    assert told[0] == (0, 4096, "traj", "dpend sweep")
    assert told[-1] == (4096, 4096, "traj", "dpend sweep")
    done = [t[0] for t in told]
    assert done == sorted(done)


def test_a_callback_that_raises_stops_the_sweep():
    """Raised at the first report after the start (a sweep reports as its blocks
    end): the sweep stops there, minutes before its end."""
    told = []

    def stop(done, total, what, label):
        told.append(done)
        if done > 0:
            raise KeyboardInterrupt("enough")

    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt, match="enough"):
        dpend.sweep(**LONG, progress=stop)
    elapsed = time.monotonic() - t0
    print(f"stopped by its progress callback after {elapsed:.2f} s "
          f"({told[-1]} of {512 * 512} trajectories)")
    assert told[-1] < 512 * 512 // 4 and elapsed < 60
    assert dpend.simulate(t_end=0.1).t.size > 0       # the library is usable after


def test_simulate_reports_too():
    told = []
    dpend.simulate(t_end=10, dt=1e-4, save_every=100, progress=lambda *a: told.append(a))
    assert told and told[-1][0] == told[-1][1] and told[-1][3] == "dpend simulate"


def test_a_tqdm_bar_ends_at_the_total(capsys):
    pytest.importorskip("tqdm")
    dpend.sweep(n=32, t_end=5, progress=True)
    err = capsys.readouterr().err
    assert "dpend sweep" in err and "1.02k/1.02k" in err


def test_a_bad_progress_argument_is_refused():
    with pytest.raises(ValueError, match="progress='yes'"):
        dpend.simulate(t_end=0.1, progress="yes")
