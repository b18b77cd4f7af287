#!/usr/bin/env bash
# The steps of the nightly run (.github/workflows/nightly.yml calls each of them; run them
# locally the same way, from the repository's root or anywhere inside it):
#
#   scripts/nightly.sh reduced OUT
#       every validation's reduced scene into OUT, compared with the committed
#       results/reduced (OUT/compare.md, OUT/compare.json)
#   scripts/nightly.sh full OUT [HOURS]
#       the full outcomes concluded from the committed job results (results/full/jobs,
#       copied into OUT/jobs) plus every job that has no committed result (a new or edited
#       definition), which runs here unless its estimate, times 1.5, exceeds HOURS (default
#       5) on this machine's cores; compared with results/full (OUT/compare.md); the jobs
#       that ran are listed in OUT/missing.json. When every missing job belongs to an
#       optional part of a scene (a re-entry variant the campaign is still running) and
#       they exceed HOURS, the outcomes are merged without those parts (--partial), as
#       results/full is
#   scripts/nightly.sh audit OUT BUDGET SEED
#       `audit --from results/full --budget BUDGET --seed SEED --out OUT`
#   scripts/nightly.sh summary OUT HISTORY REDUCED FULL AUDIT
#       the speed study into REDUCED (`speed --out REDUCED`), then the scorecards of
#       REDUCED and FULL with the trend of the headlines (HISTORY, one
#       JSON line per night, gets tonight's line), and OUT/summary.md, which opens with
#       "What changed since the committed results"
#
# BIN is the binary (default target/release/persson-check); COMMITTED_REDUCED and
# COMMITTED_FULL the committed results (default results/reduced, results/full). A step
# writes all of its files before it fails: `reduced`, `full` and `audit` exit 1 when compare
# or audit finds a difference, and any other failure names the step and shows the end of
# its log.
set -euo pipefail
cd "$(dirname "$0")/.."
BIN="${BIN:-target/release/persson-check}"
COMMITTED_REDUCED="${COMMITTED_REDUCED:-results/reduced}"
COMMITTED_FULL="${COMMITTED_FULL:-results/full}"

step="starting"
log="$(mktemp)"
trap 'rc=$?; if [[ $rc -gt 1 ]]; then echo "nightly.sh: step \"$step\" failed (exit $rc); end of its log:" >&2; tail -n 30 "$log" >&2; fi; rm -f "$log"' EXIT

# Runs a command as the named step, its output to the terminal and to the log.
run() {
    step="$1"
    shift
    echo "== $step: $*"
    "$@" 2>&1 | tee "$log"
}

# Runs compare or audit as the named step; their exit code 1 (a difference) is kept in
# `found` for the end, anything else fails at once.
found=0
answer() {
    local rc=0
    run "$@" || rc=$?
    if [[ $rc -eq 1 ]]; then
        found=1
    elif [[ $rc -ne 0 ]]; then
        exit "$rc"
    fi
}

usage() {
    step="usage"
    awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0" >&2
    exit 2
}

case "${1:-}" in
reduced)
    [[ $# -eq 2 ]] || usage
    out="$2"
    run "reduced scenes" "$BIN" validate --out "$out"
    answer "compare with $COMMITTED_REDUCED" "$BIN" compare "$COMMITTED_REDUCED" "$out" --out "$out/compare.md"
    ;;
full)
    [[ $# -eq 2 || $# -eq 3 ]] || usage
    out="$2"
    hours="${3:-5}"
    step="seed $out/jobs from $COMMITTED_FULL/jobs"
    mkdir -p "$out"
    rm -rf "$out/jobs"
    cp -r "$COMMITTED_FULL/jobs" "$out/jobs"
    step="plan of the full scenes"
    "$BIN" validate --full --plan --out "$out" >"$out/plan.json" 2>"$log"
    step="jobs without a committed result"
    rc=0
    (python3 - "$out" "$hours" "$(nproc)" <<'PY' | tee "$log"
import glob, json, sys
out, hours, cores = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
plan = json.load(open(f"{out}/plan.json"))
missing = [j for j in plan["jobs"] if not glob.glob(f"{out}/jobs/*/full/{j['key']}.json")]
cost = sum(j["cost"] for j in missing)
validations = sorted({j["validation"] for j in missing})
hours_needed = 1.5 * cost / 3600 / cores
json.dump({"jobs": missing, "validations": validations, "core_hours": cost / 3600,
           "hours_on_this_machine": hours_needed}, open(f"{out}/missing.json", "w"), indent=1)
print(f"{len(missing)} of {len(plan['jobs'])} full jobs have no committed result "
      f"({', '.join(validations) or 'none'}): estimated {cost / 3600:.2f} core-hours, "
      f"{hours_needed:.2f} h on {cores} cores with the margin")
if hours_needed > hours:
    if missing and all(j.get("part") for j in missing):
        parts = sorted({j["part"] for j in missing})
        print(f"more than the {hours} h allowed, all of them of optional parts ({', '.join(parts)}): "
              "merging without those parts (--partial)")
        sys.exit(4)
    print(f"more than the {hours} h allowed: run them as a campaign of shares (docs/cluster.md, "
          "'Running the paper-scale scenes on a cluster') and commit the results")
    sys.exit(3)
PY
    ) || rc=$?
    if [[ $rc -eq 4 ]]; then
        run "full outcomes from the committed jobs, pending parts left out" \
            "$BIN" validate --full --merge --partial --accept-other-commit --out "$out"
    elif [[ $rc -ne 0 ]]; then
        exit "$rc"
    else
        run "full outcomes from the committed and the missing jobs" "$BIN" validate --full --resume --out "$out"
    fi
    answer "compare with $COMMITTED_FULL" "$BIN" compare "$COMMITTED_FULL" "$out" --out "$out/compare.md"
    ;;
audit)
    [[ $# -eq 4 ]] || usage
    answer "audit of $COMMITTED_FULL" "$BIN" audit --from "$COMMITTED_FULL" --budget "$3" --seed "$4" --out "$2"
    ;;
summary)
    [[ $# -eq 6 ]] || usage
    out="$2" history="$3" reduced="$4" full="$5" audit="$6"
    mkdir -p "$out" "$(dirname "$history")"
    if compgen -G "$reduced/*.json" >/dev/null; then
        run "speed study" "$BIN" speed --out "$reduced"
        run "reduced scorecard" "$BIN" report --from "$reduced" --out "$reduced/scorecard.md" --history "$history"
    fi
    if compgen -G "$full/*.json" >/dev/null; then
        run "full scorecard" "$BIN" report --from "$full" --out "$full/scorecard.md" --history "$history"
    fi
    step="what changed since the committed results"
    python3 - "$out/summary.md" "$reduced" "$full" "$audit" "$COMMITTED_REDUCED" "$COMMITTED_FULL" <<'PY'
import json, os, sys
summary, reduced, full, audit, committed_reduced, committed_full = sys.argv[1:]

def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None

lines = ["# Nightly run", "", "## What changed since the committed results", ""]

def comparison(title, folder, committed):
    c = load(f"{folder}/compare.json")
    if c is None:
        lines.append(f"- **{title}**: no comparison (the step did not finish; see its log).")
        return
    state = "nothing moved" if c["passed"] else "**CHANGED**"
    lines.append(f"- **{title}** against `{committed}`: {state}. {c['summary']}")
    for s in [s for s in c["statistics"] if s["beyond"]][:20]:
        lines.append(f"  - `{s['outcome']}` `{s['key']}`: z = {s['z']:+.1f}")
    for f in c["flips"][:20]:
        lines.append(f"  - `{f['outcome']}` `{f['key']}` flipped: {f['base']} -> {f['new']}")

comparison("Reduced scenes", reduced, committed_reduced)
missing = load(f"{full}/missing.json")
if missing is not None:
    ran = len(missing["jobs"])
    which = ", ".join(missing["validations"]) or "none"
    lines.append(f"- **Full jobs without a committed result** (new or edited definitions): {ran} "
                 f"({which}), {missing['core_hours']:.2f} core-hours estimated.")
comparison("Full scenes (committed job results and those above)", full, committed_full)
a = load(f"{audit}/audit.json")
if a is None:
    lines.append("- **Audit**: no audit (the step did not finish; see its log).")
else:
    state = "every recomputed job identical" if a["passed"] else "**DIFFERENCES**"
    lines.append(f"- **Audit** of `{a['from']}`: {state}. {a['summary']}")
    for j in a["jobs"]:
        if j["finding"] in ("differs", "failed"):
            lines.append(f"  - `{j['key']}` ({', '.join(j['validations'])}, {j['solver']}): {j['finding']}")
lines.append("")
for name, path in [("Comparison, reduced", f"{reduced}/compare.md"),
                   ("Comparison, full", f"{full}/compare.md"), ("Audit", f"{audit}/audit.md")]:
    if os.path.exists(path):
        lines.append(f"{name}: `{path}` (in the run's artifacts).")
open(summary, "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
    ;;
*)
    usage
    ;;
esac
step="done"
exit "$found"
