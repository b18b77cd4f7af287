"""persson_check: Persson's rough-contact theory against contact simulations, from Python.

The functions call the Rust library behind the ``persson-check`` command line (not the
command line itself): the same surfaces, solvers, theory and validations, with numpy
arrays in and out.

* :func:`surface` -- a self-affine surface, the command line's realization bit for bit;
* :func:`solve` -- hard-wall contact on any square height array, by any solver of
  :data:`SOLVERS` (CG, GFMD, FIRE);
* :func:`sweep` -- warm-started solves while roughness is added, as an iterator;
* :func:`theory` -- Persson's theory on a surface's own spectrum;
* :func:`validate`, :func:`plan`, :func:`merge`, :func:`report` -- the validations;
* :func:`check_surface` -- Persson's theory checked on your own height maps (arrays or
  SurfaceTopography topographies), periodic or with a free boundary.

Units: lengths in grid spacings, pressures in units of E* (E* = 1), generated surfaces of
unit rms gradient. Bad input raises ValueError or TypeError with the command line's
message (a flag such as ``--p0`` named by its keyword ``p0``); a solve that does not
converge raises :class:`SolveError`. Solves release the GIL, and Ctrl-C stops them.
Paths may be given as strings or as :class:`os.PathLike` objects (``pathlib.Path``).
"""

from __future__ import annotations

import os as _os
import warnings as _warnings

import numpy as _np

from . import _native
from ._native import (
    DEFAULT_MAX_ITER,
    DEFAULT_SOLVER,
    DEFAULT_TOL,
    SOLVERS,
    Solution,
    SolveError,
    Sweep,
    SweepStep,
    Theory,
    contact_area_law,
    plan,
    surface,
)

__all__ = [
    "DEFAULT_MAX_ITER",
    "DEFAULT_SOLVER",
    "DEFAULT_TOL",
    "SOLVERS",
    "Solution",
    "SolveError",
    "Sweep",
    "SweepStep",
    "Theory",
    "check_surface",
    "contact_area_law",
    "merge",
    "plan",
    "report",
    "solve",
    "surface",
    "sweep",
    "theory",
    "validate",
]

__version__ = "0.1.0"


def _heights(heights):
    """``heights`` as a C-contiguous float64 array: no copy when it already is one. The
    masked points of a masked array (undefined data) become NaN, which every function
    refuses (or ``check_surface`` fills when asked), never heights."""
    if _np.ma.isMaskedArray(heights):
        a = _np.ma.asarray(heights)
        if a.dtype.kind not in "fiu":
            raise TypeError(
                f"dtype is {a.dtype.str!r} ({a.dtype}), expected real numbers (float64 preferred)"
            )
        return _np.ascontiguousarray(_np.ma.filled(a.astype(_np.float64), _np.nan))
    a = _np.asarray(heights)
    if a.dtype.kind not in "fiu":
        raise TypeError(
            f"dtype is {a.dtype.str!r} ({a.dtype}), expected real numbers (float64 preferred)"
        )
    return _np.ascontiguousarray(a, dtype=_np.float64)


def solve(
    heights,
    p0=None,
    contact_area=None,
    solver=_native.DEFAULT_SOLVER,
    tol=_native.DEFAULT_TOL,
    lambda_l=None,
    threads=None,
    zeta=None,
    max_iter=_native.DEFAULT_MAX_ITER,
    progress=None,
):
    return _native.solve(
        _heights(heights),
        p0=p0,
        contact_area=contact_area,
        solver=solver,
        tol=tol,
        lambda_l=lambda_l,
        threads=threads,
        zeta=zeta,
        max_iter=max_iter,
        progress=progress,
    )


def sweep(
    heights,
    p0=None,
    contact_area=None,
    zeta_from=1.0,
    zeta_to=None,
    zetas=None,
    solver=_native.DEFAULT_SOLVER,
    tol=_native.DEFAULT_TOL,
    lambda_l=None,
    threads=None,
    fields=False,
    max_iter=_native.DEFAULT_MAX_ITER,
    progress=None,
):
    return _native.sweep(
        _heights(heights),
        p0=p0,
        contact_area=contact_area,
        zeta_from=zeta_from,
        zeta_to=zeta_to,
        zetas=None if zetas is None else [float(z) for z in zetas],
        solver=solver,
        tol=tol,
        lambda_l=lambda_l,
        threads=threads,
        fields=fields,
        max_iter=max_iter,
        progress=progress,
    )


def theory(heights, p0, variant="original", lambda_l=None, e_star=1.0):
    return _native.theory(
        _heights(heights), p0, variant=variant, lambda_l=lambda_l, e_star=e_star
    )


def validate(
    names=None,
    out="out",
    full=False,
    solver=None,
    resume=False,
    dir=None,
    threads=None,
):
    return _native.validate(names, out, full, solver, resume, dir, threads)


def merge(
    names=None,
    out="out",
    full=False,
    solver=None,
    accept_other_commit=False,
    dir=None,
    partial=False,
):
    return _native.merge(names, out, full, solver, accept_other_commit, dir, partial)


def report(source="out", out="scorecard.md", golden=None):
    return _native.report(source, out, golden)


def _is_topography(value):
    """A SurfaceTopography topography, or anything with ``heights()`` and
    ``physical_sizes``."""
    return callable(getattr(value, "heights", None)) and hasattr(value, "physical_sizes")


def _number(x):
    """``x`` for a message: a plain float, never ``np.float64(...)``."""
    return repr(float(x))


def _scan(value, i):
    """One scan's heights (NaN where undefined), the pixel sides it implies and its unit
    (both ``None`` for an array)."""
    if not _is_topography(value):
        return _heights(value), None, None
    heights = value.heights()
    sizes = _np.atleast_1d(_np.asarray(value.physical_sizes, dtype=float))
    unit = getattr(value, "unit", None)
    unit = unit if isinstance(unit, str) else None
    if getattr(value, "is_uniform", True) is False and callable(
        getattr(value, "positions_and_heights", None)
    ):
        # A line scan at non-uniform positions (stylus profilometers, x-y text files).
        x, h = value.positions_and_heights()
        profile, pixels = _uniform_profile(x, h, i)
        return profile, pixels, unit
    if _np.ndim(heights) == 1 and sizes.size == 1 and _np.size(heights) > 0:
        # A line scan: its spacing is its length over its points.
        pixel = float(sizes[0]) / _np.size(heights)
        return _heights(heights), (pixel, pixel), unit
    if _np.ndim(heights) != 2 or sizes.size != 2:
        # The library names the shape (a line scan is refused there, with its reason).
        return _heights(heights), None, None
    pixels = tuple(float(p) for p in sizes / _np.asarray(_np.shape(heights), dtype=float))
    return _heights(heights), pixels, unit


def _uniform_profile(x, h, i):
    """A profile at increasing positions ``x`` resampled onto as many evenly spaced points
    from its first to its last position, by linear interpolation (the library's
    resampling, as ``persson-check check-surface --line-scan`` does it), with a warning
    that names the spacings it had; returns ``(heights, (pixel, pixel))``. Positions that
    do not increase strictly are refused, naming the point."""
    x = _np.asarray(x, dtype=float)
    h = _np.asarray(h, dtype=float)
    if x.ndim != 1 or h.ndim != 1:
        raise ValueError(
            f"heights[{i}]: a non-uniform line scan needs positions and heights of one "
            f"length, at least 2"
        )
    resampled, pixel, warning = _native.resample_line_scan(
        f"heights[{i}]", x.tolist(), h.tolist()
    )
    _warnings.warn(f"heights[{i}]: {warning}", stacklevel=5)
    return _heights(_np.asarray(resampled, dtype=float)), (float(pixel), float(pixel))


def _same(a, b):
    return all(_np.isclose(x, y, rtol=1e-9, atol=0.0) for x, y in zip(a, b))


def _scale_item(value, i):
    """One scan of a surface at several scales: ``(heights, pixel, unit)`` from a
    topography (its pixel and unit) or a tuple ``(heights, pixel_size[, unit])``."""
    if isinstance(value, tuple):
        if not 2 <= len(value) <= 3:
            raise ValueError(
                f"heights[{i}]: a scan at its own scale is (heights, pixel_size) or "
                f"(heights, pixel_size, unit), not a tuple of {len(value)}"
            )
        unit = value[2] if len(value) == 3 else None
        if unit is not None and not isinstance(unit, str):
            raise TypeError(f"heights[{i}].unit: a length unit's name (str), not {unit!r}")
        return _heights(value[0]), float(value[1]), unit
    if not _is_topography(value):
        raise ValueError(
            f"heights[{i}]: with scales=True each scan brings its own pixel size: a "
            "SurfaceTopography topography, or a tuple (heights, pixel_size[, unit])"
        )
    array, pixels, unit = _scan(value, i)
    if pixels is None:
        raise ValueError(f"heights[{i}]: a topography of shape {_np.shape(array)}, not a scan")
    a, b = pixels
    if abs(a - b) > 1e-3 * max(a, b):
        raise ValueError(
            f"heights[{i}].pixel_size: {_number(a)} x {_number(b)}: square pixels, sides "
            "within 0.1% of each other (resample the topography onto square pixels first)"
        )
    return array, float(_np.sqrt(a * b)), unit


def _scans(heights, pixel_size, unit):
    """The scans as float64 arrays, the pixel sides of them all and their length unit."""
    several = isinstance(heights, (list, tuple)) and any(
        isinstance(h, (_np.ndarray, tuple)) or _is_topography(h) for h in heights
    )
    values = list(heights) if several else [heights]
    for i, value in enumerate(values):
        if isinstance(value, tuple):
            raise ValueError(
                f"heights[{i}]: a (heights, pixel_size[, unit]) tuple is a scan at its own "
                "scale: pass scales=True to check one surface measured at several scales"
            )
    scans, pixels, units = [], [], []
    for i, value in enumerate(values):
        array, pixel, scan_unit = _scan(value, i)
        scans.append(array)
        if pixel is not None:
            pixels.append(pixel)
        if scan_unit is not None:
            units.append((i, scan_unit))
    if pixel_size is None:
        profile = next((i for i, a in enumerate(scans) if a.ndim == 1), None)
        if not pixels and profile is not None:
            raise ValueError(
                f"pixel_size: heights[{profile}] is a line scan (a profile of "
                f"{scans[profile].size} heights): give the spacing of its points, in the "
                "heights' unit (a 1D topography brings its own)"
            )
        if not pixels:
            raise ValueError(
                "pixel_size: required for plain arrays (a positive length, in the heights' "
                "unit, or two: between rows, between columns); a topography brings its own"
            )
        pixel_size = pixels[0]
    sides = tuple(float(p) for p in _np.broadcast_to(_np.asarray(pixel_size, dtype=float), (2,)))
    for pixel in pixels:
        if not _same(pixel, sides):
            raise ValueError(
                f"pixel_size: {_number(sides[0])} x {_number(sides[1])} given, but a "
                f"topography's pixel is {_number(pixel[0])} x {_number(pixel[1])} "
                "(physical_sizes over points); give one or the other, or equal ones "
                "(scans of one surface at several scales: scales=True)"
            )
    for i, scan_unit in units:
        if unit is None:
            unit = scan_unit
        elif scan_unit != unit:
            raise ValueError(
                f"unit: {unit!r}, but heights[{i}] is in {scan_unit!r}; give scans in one "
                "unit (SurfaceTopography: topography.to_unit(...))"
            )
    return scans, sides, unit


_CHECK = _native.CHECK_SURFACE_DEFAULTS


def check_surface(
    heights,
    pixel_size=None,
    periodic=False,
    loads=None,
    solver=_CHECK["solver"],
    cross_check=True,
    tol=_CHECK["tol"],
    out=None,
    threads=None,
    progress=None,
    unit=None,
    modulus=None,
    fill="none",
    reentry=True,
    verbose=True,
    cross_check_all=False,
    line=False,
    line_side=_CHECK["line_side"],
    line_seeds=_CHECK["line_seeds"],
    max_iterations=_CHECK["max_iterations"],
    despike=None,
    extrapolate=True,
    cutoff=True,
    tip_radius=None,
    scales=False,
):
    if scales:
        return _check_scales(
            heights,
            pixel_size,
            unit,
            periodic=periodic,
            loads=loads,
            solver=solver,
            cross_check=cross_check,
            cross_check_all=cross_check_all,
            tol=tol,
            fill=fill,
            modulus=modulus,
            reentry=reentry,
            out=out,
            threads=threads,
            progress=progress,
            verbose=verbose,
            line=line,
            max_iterations=max_iterations,
            despike=despike,
            extrapolate=extrapolate,
            cutoff=cutoff,
            tip_radius=tip_radius,
        )
    scans, sides, unit = _scans(heights, pixel_size, unit)
    return _native.check_surface(
        scans,
        sides,
        unit,
        periodic,
        None if loads is None else [float(p) for p in loads],
        solver,
        cross_check,
        cross_check_all,
        tol,
        fill,
        None if modulus is None else float(modulus),
        reentry,
        None if out is None else _os.fspath(out),
        threads,
        progress,
        verbose,
        line,
        int(line_side),
        int(line_seeds),
        max_iterations,
        None if despike is None else float(despike),
        bool(extrapolate),
        bool(cutoff),
        None if tip_radius is None else float(tip_radius),
    )


def _check_scales(heights, pixel_size, unit, **kw):
    """``check_surface(..., scales=True)``: the scans of one surface at several scales."""
    if pixel_size is not None or unit is not None:
        raise ValueError(
            "pixel_size and unit: with scales=True each scan brings its own (a topography, "
            "or a tuple (heights, pixel_size[, unit])); leave them out"
        )
    if not isinstance(heights, (list, tuple)) or len(heights) < 2:
        raise ValueError(
            "heights: with scales=True a list of scans of one surface at different scales"
        )
    scans = [_scale_item(value, i) for i, value in enumerate(heights)]
    loads = kw.pop("loads")
    modulus = kw.pop("modulus")
    despike = kw.pop("despike")
    tip_radius = kw.pop("tip_radius")
    out = kw.pop("out")
    return _native.check_scales(
        scans,
        kw.pop("periodic"),
        None if loads is None else [float(p) for p in loads],
        kw.pop("solver"),
        kw.pop("cross_check"),
        kw.pop("cross_check_all"),
        kw.pop("tol"),
        kw.pop("fill"),
        None if modulus is None else float(modulus),
        kw.pop("reentry"),
        None if out is None else _os.fspath(out),
        kw.pop("threads"),
        kw.pop("progress"),
        kw.pop("verbose"),
        kw.pop("line"),
        kw.pop("max_iterations"),
        None if despike is None else float(despike),
        bool(kw.pop("extrapolate")),
        bool(kw.pop("cutoff")),
        None if tip_radius is None else float(tip_radius),
    )


check_surface.__doc__ = """Persson's theory checked on a measured surface, as ``persson-check
check-surface`` checks it; returns the dict of ``surface.json``.

``heights`` is a 2D height map (a numpy array with ``pixel_size`` in the heights' length
unit, or a SurfaceTopography topography, anything with ``heights()`` and
``physical_sizes``, whose pixel and ``unit`` it brings), or a list of them: several scans
of one surface, treated as realizations, from which the error bars come. Scans may be
rectangular. ``pixel_size`` is one length or two (between rows, between columns), equal
within 0.1%. Undefined points (NaN, infinities, the masked points of a masked array or of
a topography with undefined data) are refused with their count and the first one's
position, unless ``fill="interpolate"`` fills them by harmonic interpolation (up to 10% of
a scan; the result says how many). ``unit`` names the length unit (printed everywhere);
``modulus`` is the contact modulus E* in pascals, for loads and pressures in Pa beside
``p0 / E*``. ``periodic=False`` (a measured window) solves on a free-boundary half-space
and detrends and windows the spectrum; ``periodic=True`` (square scans) solves with the
periodic kernel, as :func:`solve` does. ``loads`` are nominal pressures ``p0 / E*``
(default: eight loads giving contact areas of about 1% to 30%). ``solver`` heads the
comparison, and ``cross_check`` also solves with a second solver (CG for GFMD, GFMD for
any other) at the lowest, the middle
and the highest load (every load with ``cross_check_all``), within a time budget per
load; every solve has a budget of ``max_iterations`` iterations, and a
failed solve is listed under ``failures`` with the solver's ``state`` (iterations, residual
against the tolerance, points in contact), never raised. Spikes and outliers are reported
before the solves under ``outliers`` (points beyond 6 rms heights, the largest in rms, and
per load the share of the contact on them); ``despike=K`` (off by default, K >= 3) first
replaces every point farther than K robust deviations (1.4826 times the median absolute
deviation) from the median of its eight neighbours by harmonic interpolation, and says how
many it replaced. ``extrapolate`` (on by default) also solves every load on the scan
coarsened by 2, and by 4 where each side keeps 32 points, and extrapolates the contact
area to a vanishing pixel (first-order Richardson, ``2 a_r(a) - a_r(2a)``): each point
of ``curve`` then has ``pixel`` (the coarse areas, ``extrapolated``, ``difference``, and
with three levels ``spread`` and ``order``), and the theory is set against the
extrapolated area. ``cutoff`` (on by default) first cuts each scan at its shortest
reliable wavelength, where its spectrum flattens into a noise floor, or where the rms
curvature exceeds that of a tip of radius ``tip_radius`` (the heights' unit) when given;
the heights solved and the spectrum Persson is evaluated on are filtered there, and the
result's ``cutoff`` names each scan's cutoff and why. ``reentry`` measures the
re-entry share over magnification. ``out`` writes ``surface.json``, ``surface.md``,
``solves.jsonl`` and the figures there; ``verbose`` writes one line per load to
``sys.stderr`` as it ends.

Line scans: a 1D array (or a 1D topography) is a profile, and ``line=True`` reads 2D arrays
as rows of profiles (the columns then test isotropy). Their averaged 1D spectrum is
converted to the isotropic 2D spectrum by the inverse Abel transform, Persson's theory is
evaluated on it, and the contact is simulated on ``line_seeds`` surfaces of
``line_side`` points synthesized with it (random phases), not on the profiles; the
result's ``line`` holds the profiles' spectrum, the converted one with the bins where it is
uncertain, and Persson on the whole converted band. The result's ``curve`` holds, per load, ``p0``, ``a_r`` and
Persson's ``a_r_persson`` and ``a_r_persson_corrected`` with the elastic energies;
``warnings`` where the scan lies outside what the theory assumes; ``comparisons`` the
verdicts. The GIL is released; Ctrl-C stops it.

One surface at several scales: ``scales=True`` with a list of scans, each bringing its own
pixel size, a SurfaceTopography topography or a tuple ``(heights, pixel_size)`` or
``(heights, pixel_size, unit)`` (a 1D array or topography, or any with ``line=True``, is
line scans). Scans in different units are converted into the first's. Their spectra are
stitched into the surface's (each over the band it resolves reliably, averaged where bands
overlap, weighted by their independent modes; a gap between bands is reported), Persson's
theory is evaluated on the stitched spectrum and on each scan's band, and each height map
is simulated alone and set against Persson on its band and on the whole surface. Returns
the dict of ``scales.json`` (``stitched``, ``scans`` with each areal scan's
``comparison`` and its own ``check``, ``whole``); ``out`` writes ``scales.md``, its
figures and each areal scan's own page in ``scan-<k>/``.
"""


for _wrapper in (solve, sweep, theory, validate, merge, report):
    _wrapper.__doc__ = getattr(_native, _wrapper.__name__).__doc__
del _wrapper
