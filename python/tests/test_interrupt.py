"""Ctrl-C stops a long solve; the GIL is free while it runs."""

import os
import signal
import sys
import threading
import time

import numpy as np
import pytest

import persson_check

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


@pytest.fixture(scope="module")
def large():
    return persson_check.surface(1024, 0.8, 1024.0, 2.0, 1)


def _interrupt_after(seconds):
    timer = threading.Timer(seconds, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    return timer


def test_ctrl_c_stops_a_long_solve(large):
    # GFMD to a tight tolerance on 1024^2 takes far longer than the signal's delay.
    timer = _interrupt_after(0.5)
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        persson_check.solve(large, p0=0.01, solver="gfmd", tol=1e-13, max_iter=10**7)
    timer.join()
    assert time.perf_counter() - start < 5.0
    # The package is usable afterwards.
    small = persson_check.surface(32, 0.8, 16.0, 4.0, 1)
    assert persson_check.solve(small, p0=0.1).termination == "converged"


def test_ctrl_c_stops_a_sweep(large):
    sweep = persson_check.sweep(large, p0=0.01, solver="gfmd", tol=1e-13, zetas=[500.0], max_iter=10**7)
    timer = _interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        next(sweep)
    timer.join()
    with pytest.raises(StopIteration):
        next(sweep)


def test_a_raising_progress_callback_stops_the_solve(large):
    class Enough(Exception):
        pass

    def stop(iteration, residual):
        if iteration >= 32:
            raise Enough(iteration)

    with pytest.raises(Enough):
        persson_check.solve(large, p0=0.01, solver="gfmd", tol=1e-13, progress=stop)


def test_other_threads_run_during_a_solve():
    h = persson_check.surface(512, 0.8, 512.0, 2.0, 3)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    start = time.perf_counter()
    persson_check.solve(h, p0=0.05, solver="gfmd", tol=1e-10)
    end = time.perf_counter()
    done.set()
    worker.join()
    during = [t for t in ticks if start < t < end]
    # With the GIL held the counter would stall for the whole solve.
    assert len(during) >= max(1, int((end - start) / 0.01)), (len(during), end - start)
