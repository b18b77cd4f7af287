"""check_surface: the command line's check-surface from Python, on arrays and topographies
(SurfaceTopography's own: test_check_surface_topography.py)."""

import json
import math

import numpy as np
import pytest

import persson_check
from conftest import save

# Wall times and the page's list of files differ from run to run; everything else is equal.
VOLATILE = {"wall_s"}

# Checks that need only the headline curve.
QUICK = {"cross_check": False, "reentry": False, "verbose": False}


def _stable(value):
    if isinstance(value, dict):
        return {k: _stable(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [_stable(v) for v in value]
    return value


def _windows():
    """Two non-periodic 48 x 48 windows of one generated surface, pixel 0.5."""
    full = persson_check.surface(128, 0.8, 64.0, 4.0, 3)
    return [0.5 * full[:48, :48].copy(), 0.5 * full[64:112, 64:112].copy()]


def _rising(result, at_least=5):
    curve = result["curve"]
    assert len(curve) >= at_least, f"{len(curve)} loads"
    areas = [p["a_r"] for p in curve]
    assert all(b > a for a, b in zip(areas, areas[1:])), areas
    for p in curve:
        assert all(math.isfinite(p[k]) for k in ("a_r", "a_r_persson", "energy")), p
    assert "NaN" not in json.dumps(result)


def test_the_curve_equals_the_command_lines(cli, tmp_path):
    scans = _windows()
    files = [save(tmp_path / f"scan{i}.npy", h) for i, h in enumerate(scans)]
    out = tmp_path / "cli"
    cli("check-surface", "--heights", *files, "--pixel-size", "0.5", "--out", out)
    theirs = json.loads((out / "surface.json").read_text())
    ours = persson_check.check_surface(scans, pixel_size=0.5, verbose=False)
    assert len(ours["curve"]) >= 5
    assert [p["a_r"] for p in ours["curve"]] == [p["a_r"] for p in theirs["curve"]]
    ours.pop("scans"), theirs.pop("scans")  # the names: heights[i] against file paths
    for failure in ours["failures"] + theirs["failures"]:
        failure.pop("scan")
    ours["reentry"].pop("wall_s"), theirs["reentry"].pop("wall_s")
    assert _stable(ours) == _stable(theirs)


class _Topography:
    """What SurfaceTopography's topographies offer: heights() and physical_sizes."""

    def __init__(self, heights, pixel):
        self._heights = heights
        self.physical_sizes = (pixel * heights.shape[0], pixel * heights.shape[1])

    def heights(self):
        return self._heights


def test_a_topography_brings_its_pixel():
    scan = _windows()[0]
    loads = [0.01, 0.03]
    by_array = persson_check.check_surface(scan, pixel_size=0.5, loads=loads, **QUICK)
    by_topo = persson_check.check_surface(_Topography(scan, 0.5), loads=loads, **QUICK)
    assert _stable(by_topo) == _stable(by_array)
    with pytest.raises(ValueError, match="pixel_size") as e:
        persson_check.check_surface(_Topography(scan, 0.5), pixel_size=0.25, loads=loads)
    assert "np.float64" not in str(e.value)


def test_masked_points_are_refused_with_their_count_and_position_or_filled():
    scan = _windows()[0]
    mask = np.zeros(scan.shape, dtype=bool)
    mask[4, 7] = mask[10, 2] = mask[30:33, 20:24] = True
    masked = np.ma.masked_array(scan, mask)
    # np.asarray would drop the mask and solve the hidden values as heights.
    with pytest.raises(ValueError, match=r"14 of 2304 heights .*undefined.*row 4, column 7"):
        persson_check.check_surface(masked, pixel_size=0.5, **QUICK)
    with pytest.raises(ValueError, match="fill=interpolate"):
        persson_check.check_surface(masked, pixel_size=0.5, **QUICK)
    # solve refuses them too, rather than taking the hidden values.
    with pytest.raises(ValueError, match="row 4, column 7 is NaN"):
        persson_check.solve(np.ma.masked_array(scan[:32, :32], mask[:32, :32]), p0=0.05)
    loads = [0.01, 0.03]
    filled = persson_check.check_surface(
        masked, pixel_size=0.5, loads=loads, fill="interpolate", **QUICK
    )
    assert filled["filled"] == [14]
    # The filled points are the mean of their neighbours: a single inner point is.
    plain = persson_check.check_surface(scan, pixel_size=0.5, loads=loads, **QUICK)
    assert plain["filled"] == [0]
    for a, b in zip(filled["curve"], plain["curve"]):
        assert abs(a["a_r"] - b["a_r"]) < 0.05 * b["a_r"] + 2 / scan.size
    with pytest.raises(ValueError, match="fill"):
        persson_check.check_surface(scan, pixel_size=0.5, fill="guess")


def test_bad_scans_are_refused_by_name():
    scan = _windows()[0]
    with pytest.raises(ValueError, match="pixel_size"):
        persson_check.check_surface(scan)
    holed = scan.copy()
    holed[3, 5] = np.nan
    holed[7, 1] = np.inf
    with pytest.raises(ValueError, match=r"2 of 2304 heights .*undefined.*row 3, column 5"):
        persson_check.check_surface(holed, pixel_size=0.5)
    # A row is a line scan: 48 points are too few to convert its spectrum.
    with pytest.raises(ValueError, match="line scan of 48 points"):
        persson_check.check_surface(scan[0], pixel_size=0.5)
    with pytest.raises(ValueError, match="pixel_size"):
        persson_check.check_surface(scan, pixel_size=-1.0)
    with pytest.raises(ValueError, match="loads"):
        persson_check.check_surface(scan, pixel_size=0.5, loads=[12.0])
    with pytest.raises(ValueError, match="modulus"):
        persson_check.check_surface(scan, pixel_size=0.5, modulus=-1.0)


def test_one_line_per_load_goes_to_stderr(capsys):
    scan = _windows()[0]
    r = persson_check.check_surface(
        scan, pixel_size=0.5, loads=[0.01, 0.02, 0.04], cross_check=False, reentry=False
    )
    lines = [
        line for line in capsys.readouterr().err.splitlines() if line.startswith("check_surface:")
    ]
    # The scan's outliers first (before any solve), then one line per load.
    assert "beyond 6 rms" in lines[0], lines
    loads = lines[1:]
    assert len(loads) == len(r["curve"]) == 3, lines
    assert "load 3/3" in loads[-1] and "a_r =" in loads[-1]


def _rectangle(rows, cols, seed=7):
    """A rows x cols window of a generated surface, in grid units."""
    side = 1 << max(rows, cols).bit_length()
    full = persson_check.surface(side, 0.8, side / 2, 4.0, seed)
    return full[:rows, :cols].copy()


def test_a_640_by_480_window_gives_a_rising_curve():
    h = _rectangle(480, 640, seed=11)
    r = persson_check.check_surface(h, pixel_size=1.0, **QUICK)
    _rising(r)
    assert (r["rows"], r["cols"]) == (480, 640)


def test_a_line_scan_is_checked_on_surfaces_synthesized_with_its_spectrum():
    # One profile (a 1D array) of a generated surface, pixel 0.5: a line scan by the rule.
    full = persson_check.surface(512, 0.8, 256.0, 4.0, 3)
    profile = 0.5 * full[7].copy()
    loads = [0.01, 0.05]
    r = persson_check.check_surface(
        profile, pixel_size=0.5, loads=loads, line_side=64, line_seeds=2, **QUICK
    )
    assert (r["line"]["profiles"], r["line"]["points"]) == (1, 512)
    assert r["line"]["synthesized_side"] == 64 and len(r["scans"]) == 2
    areas = [p["a_r"] for p in r["curve"]]
    assert len(areas) == 2 and areas[1] > areas[0] > 0, areas
    assert [p["p0"] for p in r["line"]["persson"]] == loads
    assert r["line"]["converted"][-1]["uncertain"] == "cutoff"
    # The rows of a 2D array with line=True: 64 profiles, and the columns across them.
    rows = persson_check.check_surface(
        0.5 * full[:64, :], pixel_size=0.5, line=True, loads=[0.05],
        line_side=64, line_seeds=2, **QUICK
    )
    assert rows["line"]["profiles"] == 64
    assert rows["line"]["spectrum_across"] is not None


def test_a_line_scan_that_cannot_be_checked_is_refused_with_a_word_about_line_scans():
    profile = persson_check.surface(128, 0.8, 64.0, 4.0, 1)[0].copy()
    with pytest.raises(ValueError, match="heights\\[0\\] is a line scan"):
        persson_check.check_surface(profile, **QUICK)
    with pytest.raises(ValueError, match="a profile must hold 64"):
        persson_check.check_surface(profile[:10], pixel_size=1.0, **QUICK)
    with pytest.raises(ValueError, match="line_seeds"):
        persson_check.check_surface(profile, pixel_size=1.0, line_seeds=1, **QUICK)


def _spiky():
    """A 32 x 32 window of a generated surface with two spikes of 40 rms heights."""
    h = persson_check.surface(64, 0.8, 32.0, 4.0, 5)[:32, :32].copy()
    rms = h.std()
    h[10, 7] += 40 * rms
    h[20, 25] += 40 * rms
    return h


def test_spikes_are_reported_and_a_spent_budget_fails_with_the_solver_state():
    result = persson_check.check_surface(_spiky(), 1.0, max_iterations=3, **QUICK)
    assert result["max_iterations"] == 3
    outliers = result["outliers"][0]
    # In units of the spiky scan's own rms: two 40-rms spikes in 1024 points double it
    # (sqrt(1 + 2 * 40^2 / 1024) = 2.0), so the largest reads about 20.
    assert outliers["count"] == 2 and outliers["max_rms"] > 15, outliers
    assert result["failures"], "3 iterations converge nothing cold"
    for f in result["failures"]:
        assert f["state"]["iterations"] == 3, f
        assert f["state"]["residual"] > f["state"]["tol"], f


def test_despike_replaces_the_spikes_and_says_how_many():
    result = persson_check.check_surface(_spiky(), 1.0, loads=[0.05], despike=8, **QUICK)
    outliers = result["outliers"][0]
    assert outliers["despiked"] == 2 and outliers["count"] == 0, outliers
    with pytest.raises(ValueError, match="despike"):
        persson_check.check_surface(_spiky(), 1.0, despike=1, **QUICK)
