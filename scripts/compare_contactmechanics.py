#!/usr/bin/env python3
"""A non-periodic scan solved by `persson-check check-surface` and by ContactMechanics.

Both tools solve the same problem: the scan's heights without their best-fit plane, on an
elastic half-space with a free boundary (no periodic images; ContactMechanics's
`FreeFFTElasticHalfSpace`, this project's Boussinesq kernel on the doubled grid), at the
loads that check-surface chose (read from its surface.json), each load warm-started from
the last. ContactMechanics runs its constrained conjugate gradients (Polonsky & Keer) at
its default tolerances; persson-check runs its CG alone (`--solver cg --no-cross-check`)
for the like-for-like time, and its default (GFMD with the CG cross-check) for the time a
user waits. The script prints the contact area of each load by both tools and the times.

Times are the solves alone: ContactMechanics's solver calls, and the `wall_s` of
persson-check's solvers in surface.json (reading, spectra and figures excluded).
persson-check uses every core (its global `--threads N` flag sets fewer), while
ContactMechanics's serial FFTs use one: say so with the ratio. ContactMechanics is a
reference, not a dependency:

    pip install ContactMechanics numpy
    cargo build --release
    python3 scripts/compare_contactmechanics.py scan.npy --pixel-size 0.1

Quote the ratios: the machines this runs on are shared.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np


def without_plane(h):
    """The heights less their least-squares plane (the same detrending as check-surface)."""
    n0, n1 = h.shape
    i, j = np.meshgrid(np.arange(n0), np.arange(n1), indexing="ij")
    a = np.column_stack([np.ones(h.size), i.ravel(), j.ravel()])
    coef, *_ = np.linalg.lstsq(a, h.ravel(), rcond=None)
    return h - (a @ coef).reshape(h.shape)


def check_surface(binary, scan, pixel, extra, out):
    """Runs check-surface; returns its surface.json."""
    cmd = [binary, "check-surface", "--heights", scan, "--pixel-size", str(pixel),
           "--out", out] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "surface.json")) as f:
        return json.load(f)


def contact_mechanics(heights, loads):
    """Contact areas and the solve time of ContactMechanics at `loads` (p0 / E*)."""
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    from SurfaceTopography import Topography

    n = heights.shape[0]
    # Lengths in pixels and E* = 1: a pixel's force is its pressure over E*.
    topography = Topography(heights, physical_sizes=(n, n), periodic=False)
    substrate = FreeFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(n, n))
    areas, iterations, wall = [], [], 0.0
    disp = None
    for p0 in loads:
        start = time.perf_counter()
        result = constrained_conjugate_gradients(
            substrate, topography, external_force=p0 * n * n,
            initial_displacements=disp)
        wall += time.perf_counter() - start
        if not result.success:
            sys.exit(f"ContactMechanics did not converge at p0 = {p0}: {result.message}")
        disp = result.x
        forces = result.jac[:n, :n]
        areas.append(float(np.count_nonzero(forces > 0)) / (n * n))
        iterations.append(int(result.nit))
    return areas, iterations, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scan", help="a square .npy height map (non-periodic)")
    ap.add_argument("--pixel-size", type=float, required=True)
    ap.add_argument("--binary", default="target/release/persson-check")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        ours_cg = check_surface(args.binary, args.scan, args.pixel_size,
                                ["--solver", "cg", "--no-cross-check"],
                                os.path.join(tmp, "cg"))
        ours = check_surface(args.binary, args.scan, args.pixel_size, [],
                             os.path.join(tmp, "default"))
    loads = [point["p0"] for point in ours["curve"]]
    heights = without_plane(np.load(args.scan) / args.pixel_size)
    areas, iterations, wall = contact_mechanics(heights, loads)

    print(f"{'p0/E*':>10} {'a_r (ours, cg)':>15} {'a_r (ContactMechanics)':>23} "
          f"{'rel. diff':>10} {'CM iter':>8}")
    worst = 0.0
    for point, a, it in zip(ours_cg["curve"], areas, iterations):
        diff = (point["a_r"] - a) / a
        worst = max(worst, abs(diff))
        print(f"{point['p0']:10.4e} {point['a_r']:15.6f} {a:23.6f} {diff:10.2e} {it:8d}")
    cg_wall = sum(s["wall_s"] for s in ours_cg["solvers"])
    default_wall = sum(s["wall_s"] for s in ours["solvers"])
    print(f"largest relative difference in a_r: {worst:.2e}")
    print(f"solve time: ContactMechanics {wall:.2f} s; persson-check cg {cg_wall:.2f} s "
          f"(ratio {wall / cg_wall:.1f}); persson-check gfmd + cg cross-check "
          f"{default_wall:.2f} s (ratio {wall / default_wall:.1f})")


if __name__ == "__main__":
    main()
