#!/usr/bin/env bash
# Brings up a one-node Slurm cluster on this Debian machine (run as root) from the
# distribution's packages, runs the reduced scenes of every validation as a 4-task job
# array plus the merge job (scripts/slurm/submit.sh), and checks that the merged outcomes
# equal those of one process running everything. Not part of `cargo test`.
#
#   sudo scripts/slurm/one-node-test.sh [WORK_DIR]      (default: /tmp/persson-slurm)
#
# Leaves slurmctld, slurmd and munged running; `scripts/slurm/one-node-test.sh --stop`
# stops them.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)

if [[ "${1:-}" == "--stop" ]]; then
    pkill -x slurmd || true; pkill -x slurmctld || true; pkill -x munged || true
    exit 0
fi
[[ $(id -u) -eq 0 ]] || { echo "run as root (it installs packages and starts daemons)" >&2; exit 2; }
work=$(realpath -m "${1:-/tmp/persson-slurm}")

echo "== packages"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge
fi

echo "== munge"
if [[ ! -s /etc/munge/munge.key ]]; then
    dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key status=none
fi
chown munge:munge /etc/munge/munge.key
chmod 0400 /etc/munge/munge.key
install -d -o munge -g munge -m 0755 /run/munge /var/log/munge /var/lib/munge
if ! pgrep -x munged >/dev/null; then
    runuser -u munge -- /usr/sbin/munged
fi
munge -n | unmunge >/dev/null

echo "== slurm"
host=$(hostname -s)
cpus=$(nproc)
mem_mib=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
install -d /var/spool/slurmd /var/spool/slurmctld /var/log/slurm
cat >/etc/slurm/slurm.conf <<CONF
ClusterName=persson
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
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
MinJobAge=3600
NodeName=$host CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=main Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
if ! pgrep -x slurmctld >/dev/null; then slurmctld; fi
if ! pgrep -x slurmd >/dev/null; then slurmd; fi
for _ in $(seq 60); do
    state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
    [[ "$state" == idle* || "$state" == mix* ]] && break
    scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true
    sleep 1
done
sinfo

echo "== build"
(cd "$repo" && cargo build --release --quiet)
bin="$repo/target/release/persson-check"

rm -rf "$work"
mkdir -p "$work"
echo "== one process (reduced scenes, every validation)"
"$bin" validate --out "$work/single" >"$work/single.log"

echo "== 4-task job array and merge"
ids=$(PERSSON_CHECK="$bin" "$here/submit.sh" --reduced --shards 4 --time 01:00:00 "$work/sharded")
echo "$ids"
merge=$(sed -E 's/.*merge ([0-9]+).*/\1/' <<<"$ids")
while squeue -h -j "$merge" 2>/dev/null | grep -q .; do sleep 5; done
state=$(scontrol show job "$merge" | sed -nE 's/.*JobState=([A-Z_]+).*/\1/p')
[[ "$state" == COMPLETED ]] || { echo "merge job ended $state; see $work/sharded/*.out" >&2; exit 1; }

echo "== compare"
python3 "$here/compare_outcomes.py" "$work/single" "$work/sharded"
echo "one-node Slurm: 4-task array + merge equal to one process"
