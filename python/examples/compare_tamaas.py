#!/usr/bin/env python3
"""Solve one rough surface with persson_check and, if it is installed, with tamaas.

Both solve the same array in this one process: a self-affine surface from
persson_check.surface (512^2, H = 0.8, lambda_l = 256, lambda_s = 4, unit rms gradient),
pressed at mean pressure p0 = 0.1 E* to tolerance 1e-8. Printed: each contact area, the
best wall and CPU time of --repeats solves, their ratios, and then one reduced validation's
verdict.

    pip install ./python          # from the repository's root
    pip install tamaas            # optional: the reference, never a dependency
    python python/examples/compare_tamaas.py

Times are the solve calls alone: persson_check.solve(...) (which also checks the input and
returns the pressure, displacement and gap arrays) against tamaas'
PolonskyKeerRey.solve(p0). Both get the same number of threads (--threads, default all
cores). The machine may be shared: quote ratios, and rerun.
"""

import argparse
import os
import sys
import tempfile
import time


def parse():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=512)
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--p0", type=float, default=0.1)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--validation", default="d_onset", help="a validation to run ('' for none)")
    return ap.parse_args()


def timed(call):
    """`call()`, its wall time and the process's CPU time (all threads) during it."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = call()
    return result, time.perf_counter() - wall, time.process_time() - cpu


def tamaas_solver(h, p0, tol):
    """tamaas' Polonsky-Keer solve of the same heights (E* = 1, grid spacing 1), ready to run;
    returns the contact area once called."""
    import numpy as np
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.warning)
    n = h.shape[0]
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [float(n), float(n)], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, h, tol)
    solver.max_iter = 1_000_000

    def run():
        solver.solve(p0)
        return float(np.mean(np.asarray(model.traction) > 0))

    return run


def summary(name, runs):
    """Best wall and CPU time of `runs` [(wall, cpu)]."""
    walls = [w for w, _ in runs]
    cpus = [c for _, c in runs]
    return (f"{name}: best wall {min(walls):.3f} s, best CPU {min(cpus):.3f} s "
            f"(walls: {', '.join(f'{w:.3f}' for w in walls)})")


def main():
    args = parse()
    os.environ.setdefault("OMP_NUM_THREADS", str(args.threads))
    import numpy as np

    import persson_check

    n = args.n
    h = persson_check.surface(n, args.hurst, n / 2, 4.0, args.seed)
    print(f"surface: {n} x {n}, H = {args.hurst}, lambda_l = {n / 2:g}, lambda_s = 4, "
          f"seed {args.seed}; p0 = {args.p0}, tol = {args.tol:g}, {args.threads} threads")

    try:
        import tamaas  # noqa: F401
    except ImportError:
        tamaas = None
        print("tamaas: not installed (pip install tamaas), no comparison")

    # Runs alternate between the two, so that a change of the machine's load (shared
    # machines) falls on both alike.
    ours_runs, theirs_runs, area = [], [], None
    for _ in range(args.repeats):
        ours, wall, cpu = timed(
            lambda: persson_check.solve(h, p0=args.p0, tol=args.tol, threads=args.threads)
        )
        ours_runs.append((wall, cpu))
        if tamaas is not None:
            run = tamaas_solver(np.ascontiguousarray(h), args.p0, args.tol)
            area, wall, cpu = timed(run)
            theirs_runs.append((wall, cpu))
    print(f"persson_check: contact area {ours.contact_area:.6f}, {ours.iterations} CG "
          f"iterations, residual {ours.residual:.2e}")
    print(summary("persson_check.solve", ours_runs))
    if tamaas is not None:
        print(f"tamaas:        contact area {area:.6f}")
        print(summary("tamaas PolonskyKeerRey.solve", theirs_runs))
        wall = min(w for w, _ in theirs_runs) / min(w for w, _ in ours_runs)
        cpu = min(c for _, c in theirs_runs) / min(c for _, c in ours_runs)
        print(f"contact areas differ by {abs(area - ours.contact_area):.2e}; persson_check is "
              f"{wall:.1f}x faster in wall time, {cpu:.1f}x in CPU time "
              f"(best of {args.repeats} each)")

    if args.validation:
        with tempfile.TemporaryDirectory() as out:
            start = time.perf_counter()
            (o,) = persson_check.validate(args.validation, out=out)
            print(f"validation {o['name']} (reduced): {o['statistic'].split(' (')[0]} = "
                  f"{o['value']:.4f} +- {o['std_error']:.4f}, verdict {o['verdict']} "
                  f"(the paper's: {o['paper_verdict']}) "
                  f"[{time.perf_counter() - start:.1f} s]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
