"""check_surface(..., scales=True): two generated scans of one surface at pixel sizes ten
times apart, as (heights, pixel_size, unit) tuples or SurfaceTopography topographies, are
stitched into the generating spectrum and each set against Persson on its band and on the
whole surface, as `check-surface --scales` does; the multi-scale form is explicit."""

import json

import numpy as np
import pytest

import persson_check

QUICK = dict(loads=[0.005, 0.02], cross_check=False, reentry=False, verbose=False)


def _generating(q):
    """C(q) = q^-3.6 (nm^4, q in 1/nm): H = 0.8."""
    return q ** -3.6


def _window(n, side, pixel, seed):
    """A side x side window of an n x n Gaussian realization of the generating spectrum
    at pixel `pixel` nm (heights in nm), C = A / (2 pi)^2 <|h~|^2>."""
    rng = np.random.default_rng(seed)
    q = 2 * np.pi * np.hypot(*np.meshgrid(np.fft.fftfreq(n), np.fft.fftfreq(n))) / pixel
    c = np.where(q > 0, _generating(np.where(q > 0, q, 1.0)), 0.0)
    area = (n * pixel) ** 2
    # Re(ifft) halves the power: E|m|^2 = 2 C (2 pi)^2 / A gives E|h~|^2 = C (2 pi)^2 / A.
    amplitude = np.sqrt(c * (2 * np.pi) ** 2 / area)
    modes = amplitude * (rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n)))
    h = np.real(np.fft.ifft2(modes)) * n * n
    return np.ascontiguousarray(h[:side, :side])


def _two_scans():
    return _window(512, 128, 10.0, 1), _window(512, 256, 1.0, 2)


def _check(result):
    stitched = result["stitched"]
    assert stitched["gaps"] == []
    fine_lo = result["scans"][1]["band"]["lo"]
    coarse_hi = result["scans"][0]["band"]["hi"]
    joined = 0
    for b in stitched["bins"]:
        d = b["c"] / _generating(b["q"]) - 1
        assert abs(d) < 0.1 + 3 * b["std_error"] / b["c"], (b, d)
        if fine_lo < b["q"] < coarse_hi:
            joined += 1
            assert abs(d) < 0.1, (b, d)
    assert joined >= 2
    coarse, fine = (s["comparison"][0]["whole_over_band"] for s in result["scans"])
    assert coarse < 0.7 and 0.8 < fine < 1.0


def test_tuples_of_scans_at_two_scales_are_stitched_and_compared(tmp_path):
    coarse, fine = _two_scans()
    r = persson_check.check_surface(
        [(coarse, 10.0, "nm"), (fine * 1e-3, 1e-3, "µm")],
        scales=True,
        out=tmp_path / "o",
        **QUICK,
    )
    assert r["unit"] == "nm"
    assert r["scans"][1]["pixel_size"] == pytest.approx(1.0, rel=1e-12)
    _check(r)
    md = (tmp_path / "o" / "scales.md").read_text()
    assert "Persson, whole surface" in md and "no gap" in md
    assert json.loads((tmp_path / "o" / "scales.json").read_text())["unit"] == "nm"


def test_python_and_the_command_line_give_the_same_stitched_spectrum(tmp_path, cli):
    coarse, fine = _two_scans()
    np.save(tmp_path / "coarse.npy", coarse)
    np.save(tmp_path / "fine.npy", fine)
    (tmp_path / "scales.toml").write_text(
        '[[scan]]\nfile = "coarse.npy"\npixel_size = 10\nunit = "nm"\n\n'
        '[[scan]]\nfile = "fine.npy"\npixel_size = 1\nunit = "nm"\n'
    )
    cli(
        "check-surface", "--scales", tmp_path / "scales.toml", "--loads", "0.005,0.02",
        "--no-cross-check", "--no-reentry", "--out", tmp_path / "cli",
    )
    ours = json.loads((tmp_path / "cli" / "scales.json").read_text())
    r = persson_check.check_surface([(coarse, 10.0, "nm"), (fine, 1.0, "nm")], scales=True, **QUICK)
    assert r["stitched"]["bins"] == ours["stitched"]["bins"]
    rows = [s["comparison"] for s in r["scans"]]
    assert rows == [s["comparison"] for s in ours["scans"]]


def test_the_multi_scale_form_is_explicit():
    coarse, fine = _two_scans()
    with pytest.raises(ValueError, match="scales=True"):
        persson_check.check_surface([(coarse, 10.0), (fine, 1.0)], **QUICK)
    with pytest.raises(ValueError, match="each scan brings its own"):
        persson_check.check_surface([coarse, fine], scales=True, **QUICK)
    with pytest.raises(ValueError, match="pixel_size and unit"):
        persson_check.check_surface([(coarse, 10.0), (fine, 1.0)], pixel_size=1.0, scales=True)
    with pytest.raises(ValueError, match=r"heights\[1\].pixel_size = -1"):
        persson_check.check_surface([(coarse, 10.0), (fine, -1.0)], scales=True, **QUICK)
    with pytest.raises(ValueError, match=r"heights\[0\].unit"):
        persson_check.check_surface([(coarse, 10.0), (fine, 1e-3, "µm")], scales=True, **QUICK)


def test_topographies_at_two_scales_bring_their_pixels_and_units():
    st = pytest.importorskip("SurfaceTopography")
    coarse, fine = _two_scans()
    t1 = st.Topography(coarse * 1e-9, physical_sizes=(1280e-9, 1280e-9), unit="m")
    t2 = st.Topography(fine * 1e-3, physical_sizes=(0.256, 0.256), unit="µm")
    r = persson_check.check_surface([t1, t2], scales=True, **QUICK)
    assert r["unit"] == "m"
    assert r["scans"][1]["pixel_size"] == pytest.approx(1e-9, rel=1e-9)
    # In m: C scales by (1e-9)^4 and q by 1e9.
    for b in r["stitched"]["bins"]:
        b["q"] *= 1e-9
        b["c"] *= 1e36
        b["std_error"] *= 1e36
    for s in r["scans"]:
        s["band"] = {k: v * 1e-9 for k, v in s["band"].items()}
    _check(r)
