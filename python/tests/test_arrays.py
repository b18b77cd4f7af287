"""Arrays in and out: shapes, dtypes, orders, no changes to the input."""

import numpy as np
import pytest

import persson_check


def test_surface_array(rough):
    assert rough.shape == (64, 64)
    assert rough.dtype == np.float64
    assert rough.flags.c_contiguous and rough.flags.writeable
    assert abs(rough.mean()) < 1e-12


def test_solution_fields_round_trip(rough):
    before = rough.copy()
    s = persson_check.solve(rough, p0=0.1)
    assert np.array_equal(rough, before), "the input is not modified"
    for name in ("pressure", "displacement", "gap", "heights"):
        a = getattr(s, name)
        assert a.shape == (64, 64) and a.dtype == np.float64 and a.flags.c_contiguous
    # The solved heights are the input (at full resolution, through the FFT and back).
    assert np.max(np.abs(s.heights - rough)) < 1e-12
    assert s.pressure.mean() == pytest.approx(0.1, rel=1e-6)
    assert s.contact_area == pytest.approx(np.mean(s.pressure > 0))
    assert np.all(s.pressure >= 0)
    assert s.termination == "converged"
    assert s.residual <= 1e-8
    assert s.summary()["contact_area"] == s.contact_area
    assert "Solution(" in repr(s)
    # Fields can be fed back in: the gap is a surface like any other.
    again = persson_check.solve(s.heights, p0=0.1)
    assert again.contact_area == pytest.approx(s.contact_area, abs=1e-12)


@pytest.mark.parametrize(
    "convert",
    [
        lambda h: np.asfortranarray(h),
        lambda h: h.astype(np.float32).astype(np.float64),
        lambda h: h.tolist(),
        lambda h: h[::1, ::1].copy(),
    ],
)
def test_any_square_real_array(rough, convert):
    s = persson_check.solve(convert(rough), p0=0.1)
    ref = persson_check.solve(np.asarray(convert(rough), dtype=np.float64), p0=0.1)
    assert s.contact_area == ref.contact_area


def test_threads_do_not_change_the_answer(rough):
    one = persson_check.solve(rough, p0=0.1, threads=1)
    two = persson_check.solve(rough, p0=0.1, threads=2)
    assert abs(one.contact_area - two.contact_area) <= 1e-12
    assert np.max(np.abs(one.pressure - two.pressure)) <= 1e-12


def test_progress_callback_sees_iterations(rough):
    seen = []
    persson_check.solve(rough, p0=0.1, solver="gfmd", progress=lambda i, r: seen.append((i, r)))
    assert seen and all(i % 16 == 0 for i, _ in seen)


def test_sweep_follows_the_magnification(rough):
    sweep = persson_check.sweep(rough, p0=0.1, lambda_l=32.0, zeta_from=1.0)
    assert len(sweep) == len(sweep.zetas) > 10
    steps = list(sweep)
    assert len(steps) == len(sweep.zetas)
    zetas = [s.zeta for s in steps]
    assert zetas == sorted(zetas) and zetas[-1] == pytest.approx(8.0)
    assert all(s.pressure is None for s in steps)
    # The last warm-started step is the cold solve at full resolution.
    cold = persson_check.solve(rough, p0=0.1, lambda_l=32.0, tol=1e-8)
    assert steps[-1].contact_area == pytest.approx(cold.contact_area, abs=2 / 64**2)
    assert steps[-1].elastic_energy == pytest.approx(cold.elastic_energy, rel=1e-6)
    with pytest.raises(StopIteration):
        next(sweep)


def test_sweep_at_a_contact_area_with_fields(rough):
    sweep = persson_check.sweep(rough, contact_area=0.3, lambda_l=32.0, zetas=[2.0, 4.0, 8.0], fields=True)
    steps = list(sweep)
    assert [s.zeta for s in steps] == [2.0, 4.0, 8.0]
    assert steps[0].contact_area == pytest.approx(0.3, abs=0.01)
    assert len({s.p0 for s in steps}) == 1
    assert steps[-1].pressure.shape == (64, 64)


def test_theory_on_the_surface_spectrum(rough):
    t = persson_check.theory(rough, 0.1, lambda_l=32.0)
    from math import erf, sqrt

    assert t.variant == "original" and t.zeta_max == pytest.approx(8.0)
    a = t.contact_area()
    assert a == pytest.approx(erf(0.1 / sqrt(2 * t.total_broadening())), rel=1e-12)
    assert t.non_contact_area() == pytest.approx(1 - a, rel=1e-12)
    p = np.linspace(0, 2, 20001)
    integral = np.trapz(t.pressure_density(p), p) if hasattr(np, "trapz") else None
    if integral is not None:
        assert integral == pytest.approx(a, rel=1e-3)
    shells = t.shells()
    assert shells["contact_area"][-1] == pytest.approx(a)
    assert np.all(np.diff(shells["zeta"]) > 0)
    corrected = persson_check.theory(rough, 0.1, variant="yang_persson", lambda_l=32.0)
    assert corrected.variant == "corrected"
    assert corrected.contact_area() > a
    assert 0 < persson_check.contact_area_law(0.5) < 1
