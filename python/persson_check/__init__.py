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

import numpy as _np

from . import _native
from ._native import (
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
    """``heights`` as a C-contiguous float64 array: no copy when it already is one."""
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
    solver="cg",
    tol=1e-8,
    lambda_l=None,
    threads=None,
    zeta=None,
    max_iter=100_000,
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
    solver="cg",
    tol=1e-8,
    lambda_l=None,
    threads=None,
    fields=False,
    max_iter=100_000,
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
):
    return _native.merge(names, out, full, solver, accept_other_commit, dir)


def report(source="out", out="scorecard.md", golden=None, speed=False, speed_n=256):
    return _native.report(source, out, golden, speed, speed_n)


def _is_topography(value):
    """A SurfaceTopography topography, or anything with ``heights()`` and
    ``physical_sizes``."""
    return callable(getattr(value, "heights", None)) and hasattr(value, "physical_sizes")


def _scan(value, pixel_size, i):
    """One scan's heights and the pixel size it implies (``None`` for an array)."""
    if not _is_topography(value):
        return _heights(value), None
    heights = _np.asarray(value.heights())
    sizes = _np.atleast_1d(_np.asarray(value.physical_sizes, dtype=float))
    if heights.ndim != 2 or sizes.size != 2:
        # The library names the shape (a line scan is refused there, with its reason).
        return _heights(heights), None
    pixels = sizes / _np.asarray(heights.shape, dtype=float)
    if not _np.isclose(pixels[0], pixels[1], rtol=1e-9, atol=0.0):
        raise ValueError(
            f"heights[{i}]: pixels of {pixels[0]!r} x {pixels[1]!r} (physical_sizes "
            f"{tuple(sizes)} over {heights.shape} points): square pixels are needed"
        )
    return _heights(heights), float(pixels[0])


def _scans(heights, pixel_size):
    """The scans as float64 arrays and the one pixel size of them all."""
    several = isinstance(heights, (list, tuple)) and any(
        isinstance(h, _np.ndarray) or _is_topography(h) for h in heights
    )
    values = list(heights) if several else [heights]
    scans, pixels = [], []
    for i, value in enumerate(values):
        array, pixel = _scan(value, pixel_size, i)
        scans.append(array)
        if pixel is not None:
            pixels.append(pixel)
    if pixel_size is None:
        if not pixels:
            raise ValueError(
                "pixel_size: required for plain arrays (a positive length, in the heights' "
                "unit); a topography brings its own"
            )
        pixel_size = pixels[0]
    for pixel in pixels:
        if not _np.isclose(pixel, pixel_size, rtol=1e-9, atol=0.0):
            raise ValueError(
                f"pixel_size: {pixel_size!r} given, but a topography's pixel is {pixel!r} "
                "(physical_sizes over points); give one or the other, or equal ones"
            )
    return scans, float(pixel_size)


def check_surface(
    heights,
    pixel_size=None,
    periodic=False,
    loads=None,
    solver="gfmd",
    cross_check=True,
    tol=1e-6,
    out=None,
    threads=None,
    progress=None,
):
    scans, pixel_size = _scans(heights, pixel_size)
    return _native.check_surface(
        scans,
        pixel_size,
        periodic,
        None if loads is None else [float(p) for p in loads],
        solver,
        cross_check,
        tol,
        None if out is None else _os.fspath(out),
        threads,
        progress,
    )


check_surface.__doc__ = """Persson's theory checked on a measured surface, as ``persson-check
check-surface`` checks it; returns the dict of ``surface.json``.

``heights`` is a 2D height map (a numpy array with ``pixel_size`` in the heights' length
unit, or a SurfaceTopography topography, anything with ``heights()`` and
``physical_sizes``, whose pixel it brings), or a list of them: several scans of one
surface, treated as realizations, from which the error bars come. Scans must be square.
``periodic=False`` (a measured window) solves on a free-boundary half-space and detrends
and windows the spectrum; ``periodic=True`` solves with the periodic kernel, as
:func:`solve` does. ``loads`` are nominal pressures ``p0 / E*`` (default: eight loads
giving contact areas of about 1% to 30%). ``solver`` heads the comparison, and
``cross_check`` also solves with a second solver (CG for GFMD, GFMD for any other). ``out`` writes ``surface.json``,
``surface.md`` and the figures there. The result's ``curve`` holds, per load, ``p0``,
``a_r`` and Persson's ``a_r_persson`` and ``a_r_persson_corrected`` with the elastic
energies; ``comparisons`` holds the verdicts. The GIL is released; Ctrl-C stops it.
"""


for _wrapper in (solve, sweep, theory, validate, merge, report):
    _wrapper.__doc__ = getattr(_native, _wrapper.__name__).__doc__
del _wrapper
