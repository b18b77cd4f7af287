"""Against tamaas on the same array, in one process (skipped without tamaas)."""

import time

import numpy as np
import pytest

import persson_check

tm = pytest.importorskip("tamaas")


def test_same_contact_area_as_tamaas_and_faster():
    n, p0, tol = 512, 0.1, 1e-8
    h = persson_check.surface(n, 0.8, n / 2, 4.0, 1)
    start = time.perf_counter()
    ours = persson_check.solve(h, p0=p0, tol=tol)
    ours_s = time.perf_counter() - start

    tm.set_log_level(tm.LogLevel.warning)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [float(n), float(n)], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(h), tol)
    solver.max_iter = 1_000_000
    start = time.perf_counter()
    solver.solve(p0)
    theirs_s = time.perf_counter() - start
    area = np.mean(np.asarray(model.traction) > 0)

    print(f"persson_check {ours_s:.3f} s, tamaas {theirs_s:.3f} s: {theirs_s / ours_s:.1f}x")
    assert abs(area - ours.contact_area) <= 1e-3
    # The measured ratio of docs/python.md is about 20x; on a shared test machine only the
    # direction is checked.
    assert theirs_s > 3 * ours_s
