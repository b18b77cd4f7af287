"""persson_check: Persson's rough-contact theory against contact simulations, from Python.

The functions call the Rust library behind the ``persson-check`` command line (not the
command line itself): the same surfaces, solvers, theory and validations, with numpy
arrays in and out.

* :func:`surface` -- a self-affine surface, the command line's realization bit for bit;
* :func:`solve` -- hard-wall contact on any square height array (CG or GFMD);
* :func:`sweep` -- warm-started solves while roughness is added, as an iterator;
* :func:`theory` -- Persson's theory on a surface's own spectrum;
* :func:`validate`, :func:`plan`, :func:`merge`, :func:`report` -- the validations.

Units: lengths in grid spacings, pressures in units of E* (E* = 1), generated surfaces of
unit rms gradient. Bad input raises ValueError or TypeError with the command line's
message (a flag such as ``--p0`` named by its keyword ``p0``); a solve that does not
converge raises :class:`SolveError`. Solves release the GIL, and Ctrl-C stops them.
Paths may be given as strings or as :class:`os.PathLike` objects (``pathlib.Path``).
"""

from __future__ import annotations

import numpy as _np

from . import _native
from ._native import (
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
    "Solution",
    "SolveError",
    "Sweep",
    "SweepStep",
    "Theory",
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


for _wrapper in (solve, sweep, theory, validate, merge, report):
    _wrapper.__doc__ = getattr(_native, _wrapper.__name__).__doc__
del _wrapper
