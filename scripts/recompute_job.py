#!/usr/bin/env python3
"""Recomputes one stored job result of a (full or reduced) run and compares it, bit for
bit, with the stored one: the check that a committed result is what the code computes.

    scripts/recompute_job.py results/full KEY [--bin target/release/persson-check]

KEY is the file name of the result under <DIR>/jobs/<family>/<scale>/ (without .json).
The job runs alone, as the one share of a plan with one job per share, in a temporary
folder; the two `result` objects must be equal (the provenance, `run`, differs).
Exit code 0 when they are equal, 1 when they differ, 2 on bad input."""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", type=pathlib.Path, help="the run folder holding jobs/")
    ap.add_argument("key", help="the job's key (its result file's name)")
    ap.add_argument("--bin", default="target/release/persson-check")
    args = ap.parse_args()
    found = list(args.dir.glob(f"jobs/*/*/{args.key}.json"))
    if len(found) != 1:
        sys.exit(f"recompute_job: {len(found)} results named {args.key}.json under {args.dir}/jobs")
    stored = json.loads(found[0].read_text())
    run, scale = stored.get("run") or {}, found[0].parent.name
    name, solver = run.get("definition"), stored["solver"]
    if not name:
        sys.exit("recompute_job: the stored result names no definition (no provenance)")
    scale_flag = ["--full"] if scale == "full" else []
    base = [args.bin, "validate", name, *scale_flag, "--solver", solver]
    plan = json.loads(subprocess.run(base + ["--plan"], check=True, capture_output=True).stdout)
    count = len(plan["jobs"])
    plan = json.loads(
        subprocess.run(base + ["--plan", "--shards", str(count)], check=True, capture_output=True).stdout
    )
    owner = [j["shard"] for j in plan["jobs"] if j["key"] == args.key]
    if not owner:
        sys.exit(f"recompute_job: {name} ({scale}, {solver}) plans no job with key {args.key}: "
                 "the definition or the code changed what the job computes")
    with tempfile.TemporaryDirectory() as tmp:
        print(f"recompute_job: {name} {scale} {solver} job {args.key} (share {owner[0]}/{count}) ...",
              flush=True)
        subprocess.run(base + ["--out", tmp, "--shard", f"{owner[0]}/{count}"], check=True)
        again = json.loads(next(pathlib.Path(tmp).glob(f"jobs/*/*/{args.key}.json")).read_text())
    same = again["result"] == stored["result"] and again["job"] == stored["job"]
    print(f"recompute_job: stored by commit {run.get('commit')} on {run.get('host')}; "
          f"recomputed result {'equal' if same else 'DIFFERS'}")
    sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
