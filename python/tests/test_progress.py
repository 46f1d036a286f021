"""Progress and cancel from Python: the `progress` callable sees the fit's phases and can stop
it; Ctrl-C (KeyboardInterrupt) stops a long fit within a fraction of a second."""

import signal
import threading
import time

import numpy as np
import pytest

import sfit
from conftest import wavy_grid


def noisy_grid(m=400, n=400, seed=3):
    """A height grid with noise near T = 0.5: the surface search tries many pairs (seconds)."""
    g = wavy_grid(m, n)
    g[..., 2] *= 10
    g[..., 2] += np.random.default_rng(seed).uniform(-0.4, 0.4, (m, n))
    return g


def test_progress_sees_every_phase_and_changes_nothing():
    calls = []
    fit = sfit.fit(wavy_grid(), tol=0.01, progress=calls.append)
    assert all(isinstance(p, sfit.FitProgress) for p in calls)
    phases = {p.phase for p in calls}
    assert {"search", "rows", "columns", "check"} <= phases
    assert any(p.phase == "rows" and p.done == p.total == 30 for p in calls)
    assert all(0 <= p.done <= p.total for p in calls)
    seconds = [p.seconds for p in calls]
    assert seconds == sorted(seconds)
    last = calls[-1]
    assert 0 < last.pairs_tried <= fit.report["pairs_tried"]
    nu, nv = last.best
    assert nu * nv <= fit.surface.control_points.shape[0] * fit.surface.control_points.shape[1]
    plain = sfit.fit(wavy_grid(), tol=0.01)
    assert np.array_equal(fit.surface.control_points, plain.surface.control_points)


def test_returning_false_cancels():
    seen = []

    def stop(p):
        seen.append(p.phase)
        return p.phase != "rows"

    with pytest.raises(sfit.Error) as e:
        sfit.fit(wavy_grid(), tol=0.01, progress=stop)
    assert e.value.code == "cancelled" and e.value.exit_code == 9
    assert seen[-1] == "rows"  # never called again once it said stop
    # None (a callable that returns nothing) goes on.
    sfit.fit(wavy_grid(), tol=0.01, progress=lambda p: None)


def test_an_exception_in_progress_reaches_the_caller():
    def fail(p):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        sfit.fit(wavy_grid(), tol=0.01, progress=fail)


def test_keyboard_interrupt_stops_a_long_fit_quickly():
    grid = noisy_grid()
    running = threading.Event()
    sent = {}

    def watch(p):
        if p.seconds > 0.3:
            running.set()

    def interrupt():
        if running.wait(120):
            sent["at"] = time.perf_counter()
            signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)

    t = threading.Thread(target=interrupt)
    t.start()
    start = time.perf_counter()
    try:
        with pytest.raises(KeyboardInterrupt):
            sfit.fit(grid, tol=0.5, progress=watch)
        stopped = time.perf_counter()
    finally:
        running.set()
        t.join()
    assert "at" in sent, "the fit never ran 0.3 s"
    took = stopped - sent["at"]
    print(f"\n[measured] SIGINT to KeyboardInterrupt: {took:.3f} s (fit ran {sent['at'] - start:.2f} s)")
    assert took < 1.0  # the target is 0.2 s; a loaded machine gets a generous margin


def test_keyboard_interrupt_without_a_progress_callable():
    grid = noisy_grid()

    def interrupt():
        time.sleep(0.5)
        sent["at"] = time.perf_counter()
        signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)

    sent = {}
    t = threading.Thread(target=interrupt)
    t.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sfit.fit(grid, tol=0.5)
        stopped = time.perf_counter()
    finally:
        t.join()
    took = stopped - sent["at"]
    print(f"\n[measured] SIGINT to KeyboardInterrupt, no callable: {took:.3f} s")
    assert took < 1.0
