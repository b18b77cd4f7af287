"""check_surface: the command line's check-surface from Python, on arrays and topographies."""

import json

import numpy as np
import pytest

import persson_check
from conftest import save

# Wall times and the page's list of files differ from run to run; everything else is equal.
VOLATILE = {"wall_s"}


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


def test_the_curve_equals_the_command_lines(cli, tmp_path):
    scans = _windows()
    files = [save(tmp_path / f"scan{i}.npy", h) for i, h in enumerate(scans)]
    out = tmp_path / "cli"
    cli("check-surface", "--heights", *files, "--pixel-size", "0.5", "--out", out)
    theirs = json.loads((out / "surface.json").read_text())
    ours = persson_check.check_surface(scans, pixel_size=0.5)
    assert len(ours["curve"]) >= 5
    assert [p["a_r"] for p in ours["curve"]] == [p["a_r"] for p in theirs["curve"]]
    ours.pop("scans"), theirs.pop("scans")  # the names: heights[i] against file paths
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
    by_array = persson_check.check_surface(scan, pixel_size=0.5, loads=loads, cross_check=False)
    by_topo = persson_check.check_surface(_Topography(scan, 0.5), loads=loads, cross_check=False)
    assert _stable(by_topo) == _stable(by_array)
    with pytest.raises(ValueError, match="pixel_size"):
        persson_check.check_surface(_Topography(scan, 0.5), pixel_size=0.25, loads=loads)


def test_surface_topography_if_installed():
    topography = pytest.importorskip("SurfaceTopography")
    scan = _windows()[0]
    t = topography.Topography(scan, physical_sizes=(24.0, 24.0), periodic=False)
    loads = [0.02]
    ours = persson_check.check_surface(t, loads=loads, cross_check=False)
    plain = persson_check.check_surface(scan, pixel_size=0.5, loads=loads, cross_check=False)
    assert ours["curve"] == plain["curve"]


def test_bad_scans_are_refused_by_name():
    scan = _windows()[0]
    with pytest.raises(ValueError, match="pixel_size"):
        persson_check.check_surface(scan)
    holed = scan.copy()
    holed[3, 5] = np.nan
    holed[7, 1] = np.inf
    with pytest.raises(ValueError, match=r"2 of 2304 heights are not finite.*row 3, column 5"):
        persson_check.check_surface(holed, pixel_size=0.5)
    with pytest.raises(ValueError, match="one-dimensional"):
        persson_check.check_surface(scan[0], pixel_size=0.5)
    with pytest.raises(ValueError, match="pixel_size"):
        persson_check.check_surface(scan, pixel_size=-1.0)
    with pytest.raises(ValueError, match="loads"):
        persson_check.check_surface(scan, pixel_size=0.5, loads=[12.0])
