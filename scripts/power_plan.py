#!/usr/bin/env python3
"""The sample-size plan: how many realizations each undecided claim needs, and its cost.

For every evidence claim that the paper-scale outcomes (results/full/*.json) leave "not
established", the plan asks how many realizations n make the claim's interval (the
outcome's interval_z standard errors either side: Student's t for fewer than four
realizations, 3 otherwise) at most half as wide as the rule's band: the width of the
rule's region for `within`, `outside` and `near`, and the unit's band for one-sided rules
(src/validation/unit.rs). The standard error is the committed one scaled as 1/sqrt(n).
The measured value is never read: the plan depends on the error bars alone, so it cannot
lean towards a verdict.

A claim whose error is a fit's (`error = "fit"`: a constant fitted to a law, whose error
is the scatter of the points about the law) gets no plan: more realizations do not shrink
that scatter.

Each claim's realizations are the seed lists its definition names (`realizations`); the
plan extends the shortest of them. The cost of one more realization is the cost model's
(`persson-check validate NAME --full --plan`) for the jobs that one planned realization
(`more_seeds`) adds, over every solver the scene runs; a list without planned
realizations (a finer grid's) is priced from its stored jobs. A scene's planned
realizations are the most that any of its claims needs within the budget (8 core-hours a
scene by default); the claims beyond it are listed with their cost.

    python3 scripts/power_plan.py                   # print the plan as Markdown
    python3 scripts/power_plan.py --write docs/power-plan.md --apply
    python3 scripts/power_plan.py --remaining --write docs/undecided.md

`--remaining` registers nothing: on the outcomes as they are, it prices what would decide
each claim still not established, by the same criterion, including the fitted constants,
whose points are the partial-contact loads times the targets: the loads the fit would need
and the jobs one more load adds (their measured cost where the jobs ran). A claim whose
list has planned realizations not yet merged is listed as waiting for them.

`--apply` writes the planned realizations into the definitions' `more_seeds`, numbered on
from the largest seed of the list. Run it once, before any planned job runs, and commit the
plan with the definitions: that commit is the plan's registration.
"""

import argparse
import glob
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import tomllib

# Student's t quantile at the coverage of three normal standard errors (99.73%), by
# degrees of freedom; as src/validation/claims.rs (interval_z).
T_QUANTILE = {1: 235.7837, 2: 19.2060}
# The unit's band (src/validation/unit.rs); `number` takes the validation's resolution.
UNIT_BAND = {
    "fraction": 0.02,
    "percent_of_a0": 0.02,
    "points": 0.02,
    "ratio": 0.05,
    "relative": 0.05,
    "exponent": 0.1,
}
BUDGET_CORE_HOURS = 8.0


def interval_z(n):
    return T_QUANTILE.get(n - 1, 3.0) if n is not None else 3.0


def band(claim, resolution):
    """The rule's width: its region's, or the unit's band for a one-sided rule."""
    (kind, value), = claim["rule"].items()
    paper = claim.get("paper_value")
    if kind == "near":
        return 2 * abs(paper) * value, "region"
    if kind in ("within", "outside"):
        return value[1] - value[0], "region"
    return UNIT_BAND.get(claim.get("unit"), resolution), f"{claim.get('unit')} band"


def needed(n, se, width):
    """The fewest realizations whose interval is at most half the band wide."""
    m = n
    while interval_z(m) * se * math.sqrt(n / m) > width / 4:
        m += 1
        if m > 10**6:
            return None
    return m


def section_of(path):
    """The definition's table that lists a realization path's seeds, and its key."""
    parts = path.split(".")
    if parts == ["seeds"]:
        return ("[full]", None, "seeds")
    if parts == ["waterfall"]:
        return ("[full.waterfall]", None, "seed")
    if len(parts) == 3 and parts[0] == "variants" and parts[2] == "seeds":
        return ("[[full.variants]]", parts[1], "seeds")
    return None


def seeds_line(text, path):
    """(start, end) of the `key = ...` line of `path` in `text`, and its seeds."""
    where = section_of(path)
    if where is None:
        return None
    header, name, key = where
    for m in re.finditer(r"(?m)^" + re.escape(header) + r"$", text):
        end = re.search(r"(?m)^\[", text[m.end():])
        block_end = m.end() + (end.start() if end else len(text) - m.end())
        block = text[m.end():block_end]
        if name is not None and not re.search(
            r'(?m)^name = "' + re.escape(name) + r'"$', block
        ):
            continue
        line = re.search(r"(?m)^" + key + r" = (\[[^\]]*\]|\d+)$", block)
        more = re.search(r"(?m)^more_seeds = \[[^\]]*\]$", block)
        seeds = [int(x) for x in re.findall(r"\d+", line.group(1))]
        if more:
            seeds += [int(x) for x in re.findall(r"\d+", more.group(0).split("=")[1])]
        return m.end() + line.end(), seeds, (m.end() + more.start(), m.end() + more.end()) if more else None
    return None


def with_more_seeds(text, path, count):
    """`text` with `count` further planned realizations of `path`."""
    at, seeds, more = seeds_line(text, path)
    new = list(range(max(seeds) + 1, max(seeds) + 1 + count))
    if more:
        old = [int(x) for x in re.findall(r"\d+", text[more[0]:more[1]].split("=")[1])]
        return text[: more[0]] + f"more_seeds = {old + new}" + text[more[1]:]
    return text[:at] + f"\nmore_seeds = {new}" + text[at:]


def plan_cost(binary, definitions, names, out):
    """Core-hours of the jobs the definitions plan without a stored result under `out`."""
    with tempfile.TemporaryDirectory() as d:
        for name, text in definitions.items():
            with open(os.path.join(d, name + ".toml"), "w") as f:
                f.write(text)
        p = subprocess.run(
            [binary, "validate", *names, "--full", "--plan", "--dir", d, "--out", out],
            capture_output=True,
            text=True,
        )
    if p.returncode:
        raise RuntimeError(p.stderr)
    jobs = json.loads(p.stdout)["jobs"]
    return sum(j["cost"] for j in jobs if j.get("measured_s") is None) / 3600


def stored_cost_per_realization(binary, root, name, path, out):
    """A list without planned realizations: its stored jobs' cost over its seeds."""
    p = subprocess.run(
        [binary, "validate", name, "--full", "--plan", "--out", out],
        capture_output=True,
        text=True,
        cwd=root,
    )
    jobs = json.loads(p.stdout)["jobs"]
    parts = path.split(".")
    if parts[0] == "resolutions":
        grid = parts[1]
        tagged = [j for j in jobs if grid.lstrip("n") in json.dumps(j["job"]) and "Resolution" in json.dumps(j["job"])]
        with open(os.path.join(root, "validations", name + ".toml"), "rb") as f:
            scene = tomllib.load(f)["full"]
        count = next(len(r["seeds"]) for r in scene["resolutions"] if r["name"] == grid)
        return sum(j["cost"] for j in tagged) / 3600 / count
    return None


def undecided(out):
    """(outcome, claim, resolution) of every evidence claim not established under `out`."""
    for f in sorted(glob.glob(os.path.join(out, "*.json"))):
        o = json.load(open(f))
        if "claims" not in o:
            continue
        for c in o["claims"]:
            if c.get("kind", "evidence") == "evidence" and c["result"] == "not_established":
                yield o, c, o["rule"]["resolution"]


def fit_row(o, spec, c, width):
    """A fitted constant's need in points and loads, from the study that fitted it."""
    study, row, _ = spec["measure"].split(":", 1)[1].split("/")
    table = next(t for t in o["studies"] if t["key"] == study)
    cells = next(r for r in table["rows"] if r["key"] == row)["cells"]
    column = [k["key"] for k in table["columns"]].index("points")
    points = int(cells[column])
    se = (c.get("measured") or {}).get("std_error")
    need = needed(points, se, width) if se else None
    return points, se, need


def load_cost(binary, root, name, out):
    """Core-hours of one load of a scene: its jobs' cost (measured where they ran) over
    its loads, every realization and solver included."""
    p = subprocess.run(
        [binary, "validate", name, "--full", "--plan", "--out", out],
        capture_output=True,
        text=True,
        cwd=root,
    )
    with open(os.path.join(root, "validations", name + ".toml"), "rb") as f:
        loads = tomllib.load(f)["full"]["contact_areas"]
    # A reference surface's sweeps (another scene's loads) are not this fit's.
    jobs = [
        j for j in json.loads(p.stdout)["jobs"]
        if isinstance(j["job"], dict) and j["job"].get("contact_area") in loads
    ]
    total = sum(j.get("measured_s") or j["cost"] for j in jobs) / 3600
    return total / len(loads), len(loads)


def remaining(args, root, binary, out, specs, texts):
    """The page of what would decide each claim not established now (registers nothing)."""
    lines = [
        "# What the undecided claims would cost",
        "",
        "Written by `scripts/power_plan.py --remaining` from the paper-scale outcomes",
        "(`results/full`) as committed with this page. It registers nothing: the registered",
        "plan is [power-plan.md](power-plan.md), and runs beyond it would be a new",
        "registration, committed before its jobs. The criterion is the plan's: the fewest",
        "realizations (for a fitted constant, points of the fit) whose interval is at most half",
        "as wide as the rule's band, from the error bar alone, never the value. The cost is",
        "the cost model's (`validate --full --plan`) for the jobs one more realization adds,",
        "both solvers included.",
        "",
        "A fitted constant's points are the partial-contact loads times the targets; its",
        "standard error is the scatter about the law over sqrt(points), so the points it needs",
        "scale as the square of the error. More loads would add points, but points of",
        "neighbouring loads share their realizations and their contact geometry: the fit's",
        "error, which takes the points as independent, would then understate the error. The",
        "cost of the loads is therefore a lower bound, and no fitted constant is planned.",
        "",
        "| claim | list | now | needed | core-hours | status |",
        "|---|---|---|---|---|---|",
    ]
    rows = []
    for o, c, resolution in undecided(out):
        name = o["name"]
        spec = specs[(name, c["key"])]
        width, _ = band(c, resolution)
        claim = f"`{name}.{c['key']}`"
        if spec.get("error") == "fit":
            points, se, need = fit_row(o, spec, c, width)
            per_load, loads = load_cost(binary, root, name, out)
            targets = points // loads if loads else 0
            more = math.ceil((need - points) / targets) if need and targets else None
            cost = None if more is None else more * per_load
            rows.append((cost, "fitted", f"| {claim} | points (loads x targets) | {points} | {need} "
                         f"| {'' if cost is None else f'{cost:.1f}'} | fitted constant: "
                         f"{more} more loads of {targets} points at {per_load:.2f} "
                         "core-hours a load; not planned, as loads that dense would "
                         "not give independent points |"))
            continue
        estimate = c.get("difference") or c.get("measured")
        n = c.get("realizations")
        se = estimate["std_error"] if estimate else None
        paths = spec.get("realizations", ["seeds"])
        # A list the definitions do not spell out (a finer grid's) counts the outcome's.
        found = [(len(x[1]) if (x := seeds_line(texts[name], p)) else n or 0, p)
                 for p in paths]
        listed, path = min(found)
        if listed > (n or 0):
            rows.append((0.0, "waiting", f"| {claim} | {path} | {n} | {listed} | | planned at "
                         f"`{spec.get('planned', '?')}`: {listed - n} realizations not "
                         f"merged yet |"))
            continue
        need = needed(n, se, width) if se and se == se else None
        if need is None:
            rows.append((None, "no error", f"| {claim} | {path} | {n} | | | no error bar |"))
            continue
        if need <= n:
            rows.append((0.0, "edge", f"| {claim} | {path} | {n} | {need} | 0 | its interval is "
                         "already that narrow and still reaches across the "
                         "rule's edge: runs added for it would be chosen from its value "
                         "(the claims page's estimate), which the plan excludes |"))
            continue
        if seeds_line(texts[name], path):
            base = plan_cost(binary, {name: texts[name]}, [name], out)
            one = plan_cost(binary, {name: with_more_seeds(texts[name], path, 1)}, [name], out)
            unit = one - base
        else:
            unit = stored_cost_per_realization(binary, root, name, path, out)
        cost = None if unit is None else unit * (need - n)
        within = cost is not None and cost <= args.budget
        kind = "ran" if spec.get("planned") else ("within" if within else "over")
        if spec.get("planned"):
            status = (f"ran as planned at `{spec['planned']}`; its error bar is wider "
                      "than the plan's estimate, and a second look at the same claim is "
                      "not in the plan")
        else:
            status = (f"{'within' if within else 'over'} the budget of "
                      f"{args.budget:g} core-hours")
        rows.append((cost, kind, f"| {claim} | {path} | {n} | {need} "
                     f"| {'' if cost is None else f'{cost:.1f}'} | {status} |"))
    rows.sort(key=lambda r: (r[0] is None, r[0] or 0.0))
    count = lambda k: sum(1 for r in rows if r[1] == k)
    over = [r[0] for r in rows if r[1] == "over"]
    summary = [
        f"**{len(rows)} not established.** {count('waiting')} wait for the registered plan's "
        f"runs; {count('ran')} ran as planned and stayed undecided; {count('edge')} meet the "
        f"plan's criterion already and lie at the rule's edge, where only runs chosen from "
        f"the value would decide; {count('fitted')} are fitted "
        f"constants; {count('over')} need more than {args.budget:g} core-hours"
        + (f" ({min(over):.1f} to {max(over):.0f})" if over else "")
        + f"; {count('within')} are within the budget and not planned. Were every planned "
        f"claim decided, {len(rows) - count('waiting')} would stay not established.",
        "",
    ]
    at = lines.index("| claim | list | now | needed | core-hours | status |")
    lines[at:at] = summary
    lines += [r[2] for r in rows]
    text = "\n".join(lines) + "\n"
    if args.write:
        with open(args.write, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument("--bin", default="target/release/persson-check")
    ap.add_argument("--budget", type=float, default=BUDGET_CORE_HOURS)
    ap.add_argument("--write", help="write the Markdown plan here")
    ap.add_argument("--apply", action="store_true", help="write more_seeds into the definitions")
    ap.add_argument("--remaining", action="store_true",
                    help="price what would decide each claim not established now; registers nothing")
    args = ap.parse_args()
    root = args.root
    binary = os.path.join(root, args.bin) if not os.path.isabs(args.bin) else args.bin
    out = os.path.join(root, "results", "full")

    specs, texts = {}, {}
    for f in sorted(glob.glob(os.path.join(root, "validations", "*.toml"))):
        with open(f, "rb") as fh:
            d = tomllib.load(fh)
        texts[d["name"]] = open(f).read()
        for c in d.get("claims", []):
            specs[(d["name"], c["key"])] = c
    if args.remaining:
        remaining(args, root, binary, out, specs, texts)
        return

    rows = []
    for o, c, resolution in undecided(out):
        spec = specs[(o["name"], c["key"])]
        width, what = band(c, resolution)
        estimate = c.get("difference") or c.get("measured")
        n = c.get("realizations")
        se = estimate["std_error"] if estimate else None
        paths = spec.get("realizations", ["seeds"])
        row = dict(validation=o["name"], key=c["key"], n=n, se=se, width=width,
                   what=what, paths=paths, need=None, path=None, cost=None, note="")
        if spec.get("error") == "fit":
            row["note"] = ("fitted constant: its error is the scatter about the law, "
                           "which more realizations do not shrink; more loads or "
                           "targets would, none planned")
            rows.append(row)
            continue
        counts = []
        for p in paths:
            found = seeds_line(texts[o["name"]], p)
            if found:
                counts.append((len(found[1]), p))
            else:
                counts.append((n or 0, p))
        now, path = min(counts)
        row["path"], row["n"] = path, now
        if se is None or se != se:
            row["need"] = max(4, now + 1)
            row["note"] = "one realization, no error bar: the fewest with the normal interval"
        else:
            row["need"] = needed(now, se * math.sqrt(now / (n or now)), width)
        rows.append(row)

    # One more planned realization of each list: its cost.
    unit_cost = {}
    for row in rows:
        key = (row["validation"], row["path"])
        if row["need"] is None or key in unit_cost:
            continue
        name, path = key
        if seeds_line(texts[name], path):
            base = plan_cost(binary, {name: texts[name]}, [name], out)
            more = plan_cost(binary, {name: with_more_seeds(texts[name], path, 1)}, [name], out)
            unit_cost[key] = more - base
        else:
            unit_cost[key] = stored_cost_per_realization(binary, root, name, path, out)
    for row in rows:
        if row["need"] is not None:
            c = unit_cost[(row["validation"], row["path"])]
            row["cost"] = None if c is None else c * (row["need"] - row["n"])

    # A scene's plan: the most realizations any claim needs within the budget.
    plans = {}
    for row in rows:
        if row["cost"] is None or row["cost"] > args.budget or row["need"] <= row["n"]:
            continue
        if not seeds_line(texts[row["validation"]], row["path"]):
            continue
        key = (row["validation"], row["path"])
        plans[key] = max(plans.get(key, row["n"]), row["need"])
    for row in rows:
        key = (row["validation"], row["path"])
        row["planned"] = plans.get(key)

    lines = []
    lines.append("| claim | realizations (list) | now | needed | planned | core-hours to need | status |")
    lines.append("|---|---|---|---|---|---|---|")
    for row in sorted(rows, key=lambda r: (r["cost"] is None, r["cost"] or 0)):
        need = "" if row["need"] is None else str(row["need"])
        cost = "" if row["cost"] is None else f"{row['cost']:.2f}"
        if row["need"] is None:
            status = row["note"]
        elif row["need"] <= row["n"]:
            status = "already meets the criterion: its interval is narrow, its value near the edge"
        elif row["planned"] and row["planned"] >= row["need"]:
            status = "planned"
        else:
            status = f"not planned: over the budget of {args.budget:g} core-hours"
        lines.append(
            f"| `{row['validation']}.{row['key']}` | {row['path'] or ', '.join(row['paths'])} "
            f"| {row['n']} | {need} | {row['planned'] or ''} | {cost} | {status} |"
        )
    scenes = ["", "| scene (list) | realizations now | planned | core-hours |", "|---|---|---|---|"]
    total = 0.0
    for (name, path), m in sorted(plans.items(), key=lambda kv: unit_cost[kv[0]] * (kv[1] - 0)):
        now = len(seeds_line(texts[name], path)[1])
        cost = unit_cost[(name, path)] * (m - now)
        total += cost
        scenes.append(f"| `{name}` ({path}) | {now} | {m} | {cost:.2f} |")
    scenes.append(f"| all | | | {total:.2f} |")
    head = [
        "# The sample-size plan",
        "",
        "Written by `scripts/power_plan.py` from the paper-scale outcomes (`results/full`) and",
        "the cost model (`persson-check validate --full --plan`), and committed with the",
        "definitions' planned realizations (`more_seeds`) before any planned job ran: that",
        "commit (`git log -- docs/power-plan.md`) registers the plan, and each claim it decides",
        "says \"planned at <commit>\" on the claims page.",
        "",
        "**Criterion.** For every evidence claim that is not established at full scale: the",
        "fewest realizations n whose interval (the outcome's `interval_z` standard errors either",
        "side: Student's t below four realizations, 3 from four on) is at most half as wide as",
        "the rule's band: its region's width for `within`, `outside` and `near`, the unit's band",
        "for a one-sided rule. The standard error is the committed one scaled as 1/sqrt(n); the",
        "value is never read, so the plan cannot lean towards a verdict, and the runs stop at",
        "the planned n whatever they show (no optional stopping). A claim whose interval is",
        "already that narrow stays undecided because its value lies at the rule's edge: more",
        "realizations would not be a plan but a search.",
        "",
        f"**Budget.** A scene's planned realizations are the most that any of its claims needs",
        f"at {args.budget:g} core-hours or less (both solvers of the cross-check included); the",
        "claims beyond are listed with their cost. The campaign runs the planned scenes",
        "cheapest first. Fitted constants (K1, K2) get no plan: their error is the scatter of",
        "the points about the law, which more realizations do not shrink; more loads or",
        "targets would widen the fit, and none is planned.",
        "",
        "## Claims",
        "",
    ]
    table = "\n".join(head + lines + ["", "## Scenes"] + scenes) + "\n"
    if args.write:
        with open(args.write, "w") as f:
            f.write(table)
    else:
        sys.stdout.write(table)
    if args.apply:
        for (name, path), m in plans.items():
            now = len(seeds_line(texts[name], path)[1])
            texts[name] = with_more_seeds(texts[name], path, m - now)
            with open(os.path.join(root, "validations", name + ".toml"), "w") as f:
                f.write(texts[name])


if __name__ == "__main__":
    main()
