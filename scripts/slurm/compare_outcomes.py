#!/usr/bin/env python3
"""Compares the outcomes of two runs of the validations (folders with <name>.json and
<name>.csv): every number, error bar, golden value, detail and check must be equal; wall
times, thread counts and the provenance of a merge are left out. Exit code 1 on a
difference."""
import csv
import json
import pathlib
import sys

IGNORED = {"wall_s", "threads", "merge"}


def outcome(path):
    data = json.loads(path.read_text())
    return {k: v for k, v in data.items() if k not in IGNORED}


def table(path):
    with path.open() as f:
        rows = list(csv.reader(f))
    keep = [not c.startswith("wall") for c in rows[0]]
    return [[c for c, k in zip(r, keep) if k] for r in rows]


def main(a, b):
    a, b = pathlib.Path(a), pathlib.Path(b)
    names = sorted(p.stem for p in a.glob("*.json"))
    if not names:
        sys.exit(f"no outcomes in {a}")
    bad = []
    for name in names:
        if not (b / f"{name}.json").exists():
            bad.append(f"{name}: missing in {b}")
            continue
        x, y = outcome(a / f"{name}.json"), outcome(b / f"{name}.json")
        for key in sorted(set(x) | set(y)):
            if x.get(key) != y.get(key):
                bad.append(f"{name}: {key} differs")
        if (a / f"{name}.csv").exists() and table(a / f"{name}.csv") != table(b / f"{name}.csv"):
            bad.append(f"{name}.csv differs")
    for line in bad:
        print(line)
    print(f"{len(names)} outcomes compared, {len(bad)} differences")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main(*sys.argv[1:3])
