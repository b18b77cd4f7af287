#!/usr/bin/env bash
# Submits a sharded validation run to Slurm: N array tasks (one share each) and a merge
# job that waits for all of them (afterok). Prints the two job ids.
#
#   scripts/slurm/submit.sh [--reduced] [--shards N] [--cpus C] [--time HH:MM:SS]
#                           [--partition P] OUT [NAME ...]
#
# OUT must be a folder every node sees (NFS or the like). Without --shards, N is chosen so
# that each share's estimated time on C cores is at most the time limit (default 24 h).
# Memory per task: the largest grid of the planned jobs times BYTES_PER_POINT (measured
# peak of one job per grid point, see docs/measured.md, "Memory"), plus a fixed 512 MiB.
set -euo pipefail

BYTES_PER_POINT=${BYTES_PER_POINT:-200}
scale_flag=--full
shards=
cpus=1
time_limit=24:00:00
partition=()
while [[ $# -gt 0 ]]; do
    case "$1" in
        --reduced) scale_flag=; shift ;;
        --shards) shards=$2; shift 2 ;;
        --cpus) cpus=$2; shift 2 ;;
        --time) time_limit=$2; shift 2 ;;
        --partition) partition=(--partition "$2"); shift 2 ;;
        -*) echo "unknown option $1" >&2; exit 2 ;;
        *) break ;;
    esac
done
[[ $# -ge 1 ]] || { echo "usage: $0 [options] OUT [NAME ...]" >&2; exit 2; }
out=$(realpath -m "$1"); shift
names="$*"
here=$(cd "$(dirname "$0")" && pwd)
bin=${PERSSON_CHECK:-$(command -v persson-check || echo "$here/../../target/release/persson-check")}
[[ -x "$bin" ]] || { echo "no persson-check binary (set PERSSON_CHECK)" >&2; exit 2; }
mkdir -p "$out"

plan="$out/plan.json"
# shellcheck disable=SC2086
"$bin" validate $names $scale_flag --plan >"$plan"
IFS=: read -r h m s <<<"$time_limit"
limit_s=$(( 10#$h * 3600 + 10#$m * 60 + 10#$s ))
read -r auto_shards mem_mib < <(python3 - "$plan" "$limit_s" "$cpus" "$BYTES_PER_POINT" <<'PY'
import json, math, sys
plan = json.load(open(sys.argv[1]))
limit, cpus, bpp = float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
costs = [j["cost"] for j in plan["jobs"]]
# The longest job bounds a share from below; aim for 80% of the limit on `cpus` cores.
n = max(1, math.ceil(sum(costs) / (0.8 * limit * cpus)))
n = min(n, len(costs))
mem = math.ceil(max(j["points"] for j in plan["jobs"]) * bpp * cpus / 2**20) + 512
print(n, mem)
PY
)
shards=${shards:-$auto_shards}
export PERSSON_CHECK=$bin OUT=$out SCALE_FLAG=$scale_flag NAMES=$names
array=$(sbatch --parsable "${partition[@]}" --array="1-$shards" --cpus-per-task="$cpus" \
    --mem="${mem_mib}M" --time="$time_limit" --chdir="$out" --export=ALL \
    "$here/array.sbatch")
merge=$(sbatch --parsable "${partition[@]}" --dependency="afterok:${array%%;*}" \
    --chdir="$out" --export=ALL "$here/merge.sbatch")
echo "array ${array%%;*} ($shards shares, ${mem_mib} MiB each), merge ${merge%%;*}"
