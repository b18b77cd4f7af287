#!/usr/bin/env bash
# Brings up a one-node Slurm cluster on this Debian machine (run as root) from the
# distribution's packages, runs the reduced scenes of every validation as a 4-task job
# array plus the merge job (scripts/slurm/submit.sh), and checks that the merged outcomes
# equal those of one process running everything. Not part of `cargo test`.
#
#   sudo scripts/slurm/one-node-test.sh [WORK_DIR]      (default: /tmp/persson-slurm)
#
# Each step is announced (`== step`); a step that fails names itself and shows the end of
# its log. The daemons are waited for (munge's socket, slurmctld answering, the node idle)
# for at most READY_SECONDS (default 60) each, and the merge job for MERGE_SECONDS
# (default 4 h). Leaves slurmctld, slurmd and munged running;
# `scripts/slurm/one-node-test.sh --stop` stops them (by their pid files).
set -Eeuo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)

CLUSTER=persson
READY_SECONDS=${READY_SECONDS:-60}
MERGE_SECONDS=${MERGE_SECONDS:-14400}
MUNGE_SOCKET=/run/munge/munge.socket.2
MUNGE_PID=/run/munge/munged.pid
CTLD_PID=/run/slurmctld.pid
SLURMD_PID=/run/slurmd.pid
CTLD_STATE=/var/spool/slurmctld
CTLD_LOG=/var/log/slurm/slurmctld.log
SLURMD_LOG=/var/log/slurm/slurmd.log

if [[ "${1:-}" == "--stop" ]]; then
    for pidfile in "$SLURMD_PID" "$CTLD_PID" "$MUNGE_PID"; do
        if [[ -s "$pidfile" ]]; then kill "$(cat "$pidfile")" 2>/dev/null || true; fi
    done
    exit 0
fi
[[ $(id -u) -eq 0 ]] || { echo "run as root (it installs packages and starts daemons)" >&2; exit 2; }
work=$(realpath -m "${1:-/tmp/persson-slurm}")

# The step under way and the log that tells what went wrong in it.
step=start
step_log=
begin() {
    step=$1
    step_log=${2:-}
    echo "== $step"
}
on_error() {
    local rc=$? line=${BASH_LINENO[0]}
    trap - ERR
    echo "one-node-test: FAILED in step \"$step\" (exit status $rc, line $line)" >&2
    if [[ -n "$step_log" && -r "$step_log" ]]; then
        echo "--- the last 30 lines of $step_log:" >&2
        tail -n 30 "$step_log" >&2
    elif [[ -n "$step_log" ]]; then
        echo "--- no log at $step_log" >&2
    fi
    exit "$rc"
}
trap on_error ERR

# wait_for SECONDS WHAT COMMAND...: runs COMMAND once a second until it succeeds; fails,
# saying what was not ready, after SECONDS.
wait_for() {
    local limit=$1 what=$2
    shift 2
    local waited
    for ((waited = 0; waited < limit; waited++)); do
        if "$@" >/dev/null 2>&1; then return 0; fi
        sleep 1
    done
    echo "one-node-test: $what not ready after $limit s" >&2
    return 1
}

# fail MESSAGE: fails the current step with a message.
fail() {
    echo "one-node-test: $*" >&2
    return 1
}

rm -rf "$work"
mkdir -p "$work"

begin packages "$work/packages.log"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    {
        apt-get update -q
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge
    } >"$work/packages.log" 2>&1
fi

begin munge /var/log/munge/munged.log
if [[ ! -s /etc/munge/munge.key ]]; then
    dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key status=none
fi
chown munge:munge /etc/munge/munge.key
chmod 0400 /etc/munge/munge.key
install -d -o munge -g munge -m 0755 /run/munge /var/log/munge /var/lib/munge
if ! pgrep -x munged >/dev/null; then
    runuser -u munge -- /usr/sbin/munged
fi
wait_for "$READY_SECONDS" "munge's socket $MUNGE_SOCKET" test -S "$MUNGE_SOCKET"
munge -n | unmunge >/dev/null

begin "slurm configuration"
host=$(hostname -s)
cpus=$(nproc)
mem_mib=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
install -d /var/spool/slurmd "$CTLD_STATE" /var/log/slurm
cat >/etc/slurm/slurm.conf <<CONF
ClusterName=$CLUSTER
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
StateSaveLocation=$CTLD_STATE
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$CTLD_LOG
SlurmdLogFile=$SLURMD_LOG
MinJobAge=3600
NodeName=$host CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=main Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
# slurmctld refuses to start on the saved state of another cluster.
saved=$CTLD_STATE/clustername
if [[ -s "$saved" && "$(cat "$saved")" != "$CLUSTER" ]]; then
    fail "$saved names the cluster \"$(cat "$saved")\", not \"$CLUSTER\": slurmctld would stop" \
        "at start (CLUSTER NAME MISMATCH). Stop the daemons ($0 --stop) and remove $saved" \
        "(or the whole $CTLD_STATE) if that state is not needed."
fi

begin slurmctld "$CTLD_LOG"
if ! pgrep -x slurmctld >/dev/null; then slurmctld; fi
wait_for "$READY_SECONDS" "slurmctld (scontrol ping)" bash -c 'scontrol ping | grep -q UP'
running=$(scontrol show config | sed -nE 's/^ClusterName *= *(.*)$/\1/p')
if [[ "$running" != "$CLUSTER" ]]; then
    fail "the slurmctld running serves cluster \"$running\", not \"$CLUSTER\" (started with" \
        "another configuration): stop it ($0 --stop) and run again."
fi

begin slurmd "$SLURMD_LOG"
if ! pgrep -x slurmd >/dev/null; then slurmd; fi
node_idle() {
    local state
    state=$(sinfo -h -n "$host" -o %t)
    [[ "$state" == idle* || "$state" == mix* ]] && return 0
    scontrol update nodename="$host" state=resume || true
    return 1
}
wait_for "$READY_SECONDS" "node $host (idle in sinfo)" node_idle
sinfo

begin build "$work/build.log"
(cd "$repo" && cargo build --release --quiet) >"$work/build.log" 2>&1
target=${CARGO_TARGET_DIR:-target}
[[ "$target" == /* ]] || target=$repo/$target
bin="$target/release/persson-check"
[[ -x "$bin" ]] || fail "no binary at $bin after the build"

begin "one process (reduced scenes, every validation)" "$work/single.log"
"$bin" validate --out "$work/single" >"$work/single.log" 2>&1

begin "4-task job array and merge" "$work/submit.log"
ids=$(PERSSON_CHECK="$bin" "$here/submit.sh" --reduced --shards 4 --time 01:00:00 \
    "$work/sharded" 2>"$work/submit.log")
echo "$ids" | tee -a "$work/submit.log"
merge=$(sed -nE 's/.*merge ([0-9]+).*/\1/p' <<<"$ids")
[[ -n "$merge" ]] || fail "no merge job id in the output of submit.sh: $ids"

begin "waiting for the merge job $merge" "$work/sharded/persson-merge-$merge.out"
merge_ended() { ! squeue -h -j "$merge" 2>/dev/null | grep -q .; }
wait_for "$MERGE_SECONDS" "the merge job $merge (still queued or running)" merge_ended
state=$(scontrol show job "$merge" | sed -nE 's/.*JobState=([A-Z_]+).*/\1/p')
if [[ "$state" != COMPLETED ]]; then
    for out in "$work"/sharded/persson-shard-*.out; do
        if [[ -s "$out" ]]; then
            echo "--- the last lines of $out:" >&2
            tail -n 5 "$out" >&2
        fi
    done
    fail "the merge job $merge ended $state; see $work/sharded/*.out"
fi

begin compare
python3 "$here/compare_outcomes.py" "$work/single" "$work/sharded"
echo "one-node Slurm: 4-task array + merge equal to one process"
