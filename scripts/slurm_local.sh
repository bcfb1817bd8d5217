#!/usr/bin/env bash
# Starts a single-node Slurm cluster on this machine (Debian packages
# slurm-wlm and munge, run as root), submits a study with
# examples/slurm/submit.sh, waits for it, and checks the merged table
# against a one-process run of the same study, byte for byte.
#   scripts/slurm_local.sh STUDY N TIRECONTACT
set -euo pipefail
study=$(realpath "$1")
n=$2
bin=$(realpath "$3")
here=$(cd "$(dirname "$0")/.." && pwd)
host=$(hostname -s)
# slurmctld and slurmd find each other by this name
getent hosts "$host" >/dev/null || echo "127.0.0.1 $host" >>/etc/hosts
cpus=$(nproc)
work=$(mktemp -d /tmp/tirecontact-slurm.XXXXXX)
started=()
# stop the daemons this script started, whatever happens
cleanup() {
    for d in "${started[@]}"; do pkill -x "$d" 2>/dev/null || true; done
}
trap cleanup EXIT
# the daemons' logs, when something did not work
fail() {
    echo "slurm_local: $*" >&2
    for f in /var/log/slurm/slurmctld.log /var/log/slurm/slurmd.log "$work"/tirecontact-*.out; do
        [ -f "$f" ] && { echo "--- $f" >&2; tail -20 "$f" >&2; }
    done
    exit 1
}
# the jobs call `tirecontact`: this binary, first on their PATH
ln -sf "$bin" "$work/tirecontact"
export PATH="$work:$PATH"

# munge: a key and the daemon
mkdir -p /etc/munge /var/run/munge /var/log/munge /var/lib/munge
[ -s /etc/munge/munge.key ] || dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 2>/dev/null
chown -R munge:munge /etc/munge /var/run/munge /var/log/munge /var/lib/munge 2>/dev/null || true
chmod 400 /etc/munge/munge.key
pgrep -x munged >/dev/null || { munged --force && started+=(munged); }

# slurm: one node, this host
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat >/etc/slurm/slurm.conf <<CONF
ClusterName=local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
ReturnToService=2
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=main Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
pgrep -x slurmctld >/dev/null || { slurmctld && started+=(slurmctld); }
pgrep -x slurmd >/dev/null || { slurmd && started+=(slurmd); }
up=
for _ in $(seq 60); do
    if sinfo -h -o %t 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then up=1; break; fi
    sleep 1
done
[ -n "$up" ] || fail "the node did not come up in 60 s"
sinfo

cd "$work"
"$here/examples/slurm/submit.sh" "$study" "$n" "$work/out"
done_=
for _ in $(seq 600); do
    if [ -z "$(squeue -h 2>/dev/null)" ]; then done_=1; break; fi
    sleep 1
done
[ -n "$done_" ] || fail "the jobs did not finish in 600 s"
cat "$work"/tirecontact-*.out 2>/dev/null | tail -20
[ -f "$work/out/results.csv" ] || fail "no merged table $work/out/results.csv"
"$bin" study run "$study" -o "$work/one.csv"
cmp "$work/out/results.csv" "$work/one.csv" || fail "the merged table differs from the one-process run"
echo "slurm_local: $n array tasks and their merge equal the one-process table ($(($(wc -l <"$work/one.csv") - 1)) rows); report in $work/out/report"
