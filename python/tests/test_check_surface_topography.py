"""check_surface on topographies that SurfaceTopography builds, as it reads them from
instrument files: undefined data (masked), rectangular scans, non-square pixels, lengths in
m. Skipped when SurfaceTopography is not installed."""

import math

import numpy as np
import pytest

import persson_check
from test_check_surface import QUICK, _rectangle, _rising, _windows

st = pytest.importorskip("SurfaceTopography")


def _topography(heights, pixel, unit="m", mask=None, pixels=None):
    """A SurfaceTopography topography of `heights` (masked where `mask`), pixel sides
    `pixels` (default: square `pixel`)."""
    rows, cols = heights.shape
    px = pixels or (pixel, pixel)
    data = heights if mask is None else np.ma.masked_array(heights, mask)
    return st.Topography(
        data, physical_sizes=(px[0] * rows, px[1] * cols), periodic=False, unit=unit
    )


def test_surface_topography_is_read_as_its_array():
    scan = _windows()[0]
    t = st.Topography(scan, physical_sizes=(24.0, 24.0), periodic=False)
    loads = [0.02]
    ours = persson_check.check_surface(t, loads=loads, **QUICK)
    plain = persson_check.check_surface(scan, pixel_size=0.5, loads=loads, **QUICK)
    assert ours["curve"] == plain["curve"]


def test_undefined_data_of_a_topography_is_refused_filled_or_refused_beyond_a_tenth():
    # A rectangular 60 x 90 window in m (pixel 50 nm), its undefined data masked.
    h = 50e-9 * _rectangle(60, 90)
    mask = np.zeros(h.shape, dtype=bool)
    mask[::13, ::17] = True
    mask[40:44, 10:30] = True
    t = _topography(h, 50e-9, mask=mask)
    assert t.has_undefined_data
    count = int(mask.sum())
    with pytest.raises(ValueError, match=rf"{count} of 5400 heights .*undefined"):
        persson_check.check_surface(t, **QUICK)
    r = persson_check.check_surface(t, fill="interpolate", loads=[0.003, 0.01], **QUICK)
    assert r["filled"] == [count] and r["unit"] == "m"
    assert (r["rows"], r["cols"]) == (60, 90)
    assert r["pixel_size"] == pytest.approx(50e-9, rel=1e-12)
    # Most of it unmeasured, as scans of rough optics come: refused, never a curve.
    mask[:, :30] = True
    with pytest.raises(ValueError, match="more than the 10%"):
        persson_check.check_surface(_topography(h, 50e-9, mask=mask), fill="interpolate")


def test_non_square_pixels_within_the_tolerance_run_and_beyond_it_are_refused():
    h = 1e-6 * _rectangle(48, 64)
    # 1.8534 x 1.8546 um: 0.065% apart, as an optical profiler's calibration rounds them.
    t = _topography(h, None, unit="µm", pixels=(1.8534, 1.8546))
    r = persson_check.check_surface(t, loads=[0.002, 0.005], **QUICK)
    assert r["pixel_sides"] == pytest.approx([1.8534, 1.8546])
    assert r["pixel_size"] == pytest.approx(math.sqrt(1.8534 * 1.8546))
    assert r["unit"] == "µm"
    wide = _topography(h, None, unit="µm", pixels=(0.1277, 0.3146))
    with pytest.raises(ValueError, match="resample") as e:
        persson_check.check_surface(wide, **QUICK)
    assert "np.float64" not in str(e.value)


def test_a_rectangular_scan_in_m_gives_a_rising_curve_with_pascals(tmp_path):
    # 96 x 160 (rows x columns), pixel 20 nm, lengths in m.
    h = 20e-9 * _rectangle(96, 160, seed=3)
    t = _topography(h, 20e-9)
    r = persson_check.check_surface(t, modulus=70e9, out=tmp_path / "o", verbose=False)
    _rising(r)
    for p in r["curve"]:
        assert p["p0_pa"] == pytest.approx(70e9 * p["p0"], rel=1e-15)
    md = (tmp_path / "o" / "surface.md").read_text()
    assert "lengths in m" in md and "p0 (Pa)" in md and "J/m^2" in md
    assert r["statistics"]["h_rms"]["value"] > 0 and r["reentry"]["shells"] > 10
    # The cross-check ran and agrees.
    assert r["solvers_agree"] is True and not r["failures"]


def test_a_line_scan_at_non_uniform_positions_is_resampled_with_a_warning():
    # A profile whose positions alternate 0.4 and 0.6 apart (as a stylus file's rounded
    # positions come), as SurfaceTopography reads an x-y text file.
    full = persson_check.surface(512, 0.8, 256.0, 4.0, 3)
    h = 0.5 * full[7].copy()
    x = np.cumsum(np.where(np.arange(h.size) % 2 == 0, 0.4, 0.6))
    x -= x[0]
    t = st.NonuniformLineScan(x, h, unit="µm")
    kw = dict(loads=[0.01, 0.05], line_side=64, line_seeds=2, **QUICK)
    with pytest.warns(UserWarning, match=r"non-uniform positions \(spacings 0\.4 to 0\.6\)"):
        r = persson_check.check_surface(t, **kw)
    pixel = x[-1] / (h.size - 1)
    assert r["pixel_size"] == pytest.approx(pixel, rel=1e-12) and r["unit"] == "µm"
    even = np.interp(pixel * np.arange(h.size), x, h)
    assert r["curve"] == persson_check.check_surface(even, pixel_size=pixel, **kw)["curve"]
    # Positions that do not increase cannot be resampled: refused by name.
    with pytest.raises(ValueError, match="increase strictly"):
        persson_check.check_surface(st.NonuniformLineScan(x[::-1].copy(), h), **kw)
