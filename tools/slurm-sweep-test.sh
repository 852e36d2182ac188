#!/usr/bin/env bash
# A sweep on a real SLURM job array (not run in CI): installs SLURM from the distribution's
# packages (Debian/Ubuntu: slurm-wlm, munge), starts a single-node cluster on localhost
# (munged, slurmctld, slurmd with a minimal slurm.conf), submits a small sweep of paper-2s
# variants as a job array with one shard per array task, merges the shards and compares the
# merged results.csv with a local, unsharded run of the same sweep (every column but
# wall_seconds must be equal).
#
# Usage (as root, from the repository; it changes /etc/slurm and /etc/munge):
#   cargo build --release -p surfgrav-scenarios
#   tools/slurm-sweep-test.sh [path/to/surfgrav]
# Exit code 0 when the merged results equal the local ones.
set -euo pipefail

SURFGRAV=$(realpath "${1:-target/release/surfgrav}")
SHARDS=3
WORK=$(mktemp -d /tmp/surfgrav-slurm-XXXXXX)
HOST=$(hostname -s)

[ "$(id -u)" = 0 ] || { echo "run as root (it installs packages and starts daemons)"; exit 2; }
[ -x "$SURFGRAV" ] || { echo "no surfgrav binary at $SURFGRAV: cargo build --release first"; exit 2; }

step() { echo "== $*"; }

step "installing slurm-wlm and munge"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi
slurmctld -V

step "starting munged"
mkdir -p /etc/munge /var/lib/munge /var/log/munge /run/munge
if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
fi
chown -R munge:munge /etc/munge /var/lib/munge /var/log/munge /run/munge
chmod 0700 /etc/munge /var/lib/munge /var/log/munge
chmod 0400 /etc/munge/munge.key
chmod 0755 /run/munge
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged
munge -n | unmunge >/dev/null && echo "munge: credentials round-trip"

step "starting slurmctld and slurmd on $HOST"
CPUS=$(nproc)
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat > /etc/slurm/slurm.conf <<EOF
ClusterName=surfgrav-test
SlurmctldHost=$HOST(127.0.0.1)
AuthType=auth/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
# No cgroup.conf: slurmd 22.05 autodetects cgroups and runs without them in a container
# (`CgroupPlugin=disabled` exists only from 23.02 on).
cleanup() {
    scontrol shutdown >/dev/null 2>&1 || true
}
trap cleanup EXIT INT TERM
running() { [ -s "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
running /run/slurmctld.pid || slurmctld
running /run/slurmd.pid || slurmd
for _ in $(seq 1 30); do
    if sinfo -h -o %T 2>/dev/null | grep -qE "idle|mixed"; then break; fi
    sleep 1
done
sinfo

step "a sweep of 6 paper-2s variants as a job array of $SHARDS shards"
cd "$WORK"
cat > sweep.toml <<'EOF'
base = "paper-2s"
name = "slurm-test"

[set]
t_end = 20.0

[[vary]]
field = "body_b.mass"
values = [0.8, 1.0, 1.25]

[[vary]]
field = "body_a.polar_radius"
linspace = [0.25, 0.4, 2]
EOF
cat > sweep.sbatch <<EOF
#!/bin/bash
#SBATCH --job-name=surfgrav-sweep
#SBATCH --array=0-$((SHARDS - 1))
#SBATCH --cpus-per-task=1
#SBATCH --output=$WORK/shard-%a.log
"$SURFGRAV" sweep "$WORK/sweep.toml" --shard \$SLURM_ARRAY_TASK_ID/$SHARDS --out "$WORK/cluster" --jobs 1 --quiet
EOF
cat sweep.sbatch
sbatch --wait sweep.sbatch
sacct -n -X -o JobID,State,ExitCode 2>/dev/null || squeue
ls cluster
"$SURFGRAV" sweep merge cluster

step "the same sweep locally, unsharded"
"$SURFGRAV" sweep sweep.toml --out local --quiet

step "comparing (every column but wall_seconds)"
strip() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "wall_seconds") w = i }
             { out = ""; for (i = 1; i <= NF; i++) if (i != w) out = out (out == "" ? "" : ",") $i; print out }' "$1"
}
strip cluster/results.csv > cluster.csv
strip local/results.csv > local.csv
cat cluster.csv
if cmp -s cluster.csv local.csv; then
    echo "PASS: the job array's merged results.csv equals the local run ($(($(wc -l < local.csv) - 1)) tasks)"
else
    diff cluster.csv local.csv || true
    echo "FAIL: merged results differ from the local run"
    exit 1
fi
