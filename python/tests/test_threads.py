"""Threads: results do not depend on the thread count; the GIL is released during a fit."""

import sys
import threading

import numpy as np

import sfit
from conftest import example, wavy_grid


def test_results_do_not_depend_on_the_thread_count():
    grid = wavy_grid(120, 150)
    fits = [sfit.fit(grid, tol_rel=1e-4, threads=t) for t in (1, 2, 3, 0)]
    for f in fits[1:]:
        assert np.array_equal(f.surface.control_points, fits[0].surface.control_points)
        assert np.array_equal(f.u, fits[0].u) and np.array_equal(f.v, fits[0].v)
        assert f.report["row_counts"] == fits[0].report["row_counts"]


def test_fits_from_several_python_threads_equal_serial_fits():
    inputs = [sfit.load_rows(example(n)) for n in ("ship_px121_stations", "table1_synthetic")]
    serial = [sfit.fit(r).surface.control_points for r in inputs]
    out = [None] * 6

    def work(k):
        out[k] = sfit.fit(inputs[k % 2]).surface.control_points

    threads = [threading.Thread(target=work, args=(k,)) for k in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(6):
        assert np.array_equal(out[k], serial[k % 2])


def test_the_gil_is_released_while_fitting():
    # With a switch interval of 100 s the interpreter never takes the GIL from a thread that
    # holds it: the main thread can run during the fit only if the fit released the GIL.
    grid = wavy_grid(400, 400)
    state = {"returned": False}

    def work():
        sfit.fit(grid, tol_rel=1e-5, threads=1)
        state["returned"] = True

    old = sys.getswitchinterval()
    sys.setswitchinterval(100.0)
    try:
        t = threading.Thread(target=work)
        t.start()
        threading.Event().wait(0.05)  # lets the worker reach the fit
        ran_during_fit = not state["returned"]
        t.join()
    finally:
        sys.setswitchinterval(old)
    assert ran_during_fit


def test_an_exception_in_progress_reaches_the_caller():
    def stop(p):
        raise KeyboardInterrupt("stop")

    import pytest

    with pytest.raises(KeyboardInterrupt):
        sfit.fit(wavy_grid(), tol=0.01, progress=stop)
    with pytest.raises(sfit.Error) as e:
        sfit.fit(wavy_grid(), progress=3)
    assert e.value.option == "progress"
