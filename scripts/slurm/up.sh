#!/usr/bin/env bash
# Start a real one-node Slurm cluster on this machine (for CI and for trying
# examples/slurm/study.sbatch without a cluster): Debian 12's Slurm 22.05 and MUNGE,
# run as root without systemd (a CI container has none). Idempotent: a second run restarts
# the Slurm daemons on a fresh configuration and reuses a munged that still answers.
# Exits non-zero, with the daemons' logs, when the node is not idle within $SLURM_UP_TIMEOUT s.
set -euo pipefail

TIMEOUT=${SLURM_UP_TIMEOUT:-60}
HERE=$(cd "$(dirname "$0")" && pwd)
NODE=$(hostname -s)          # slurmd finds its NodeName line by this name
CPUS=$(nproc)
LOG=/var/log/slurm

fail() { # say why, show the daemons' logs, exit 1
  echo "slurm-up: FAILED: $*" >&2
  for f in "$LOG/slurmctld.log" "$LOG/slurmd.log"; do echo "--- $f" >&2; tail -n 40 "$f" >&2 || true; done
  exit 1
}

[ "$(id -u)" = 0 ] || { echo "slurm-up: must run as root" >&2; exit 1; }
# This script writes /etc/slurm/slurm.conf: never over a configuration it did not write
# (a real cluster's), unless told to.
if [ -s /etc/slurm/slurm.conf ] && ! grep -q '^# Written by scripts/slurm/up.sh' /etc/slurm/slurm.conf &&
  [ "${SLURM_UP_FORCE:-0}" != 1 ]; then
  echo "slurm-up: /etc/slurm/slurm.conf exists and was not written by this script; not touching" \
    "it (SLURM_UP_FORCE=1 replaces it)" >&2
  exit 1
fi

# 1. Packages. --no-install-recommends: 8 packages instead of 37 (the recommends are
#    optional plugins: IPMI, HDF5, InfluxDB, ROCm SMI, ... and their -dev packages).
pkgs="slurmctld slurmd slurm-client munge"
if dpkg -s $pkgs >/dev/null 2>&1; then   # dpkg -s fails if any one is not installed
  echo "slurm-up: $pkgs already installed"
else
  export DEBIAN_FRONTEND=noninteractive
  t=$SECONDS
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends $pkgs >/dev/null
  echo "slurm-up: installed $pkgs in $((SECONDS - t)) s"
fi

# 2. MUNGE: Slurm's daemons and commands authenticate every message with it.
#    The munge package's postinst makes /etc/munge/munge.key; make one if it is missing.
if [ ! -s /etc/munge/munge.key ]; then
  mungekey --create --keyfile=/etc/munge/munge.key
fi
chown munge:munge /etc/munge/munge.key && chmod 0400 /etc/munge/munge.key
if munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
  echo "slurm-up: munged already running"
else
  # systemd's unit would make /run/munge (its socket and pid file) and run munged as munge.
  install -d -o munge -g munge -m 0755 /run/munge
  runuser -u munge -- /usr/sbin/munged && munge -n </dev/null | unmunge >/dev/null ||
    { echo "slurm-up: FAILED: munged"; tail -n 20 /var/log/munge/munged.log; exit 1; } >&2
fi

# 3. Stop Slurm daemons a previous run left, so the new slurm.conf is the one in force.
"$HERE/down.sh" --keep-munge

# 4. slurm.conf: one node, everything that needs cgroups, a database or systemd turned off.
install -d -o slurm -g slurm /var/lib/slurm/slurmctld /var/lib/slurm/slurmd "$LOG"
cat >/etc/slurm/slurm.conf <<EOF
# Written by scripts/slurm/up.sh: a one-node cluster for CI.
ClusterName=shoalci
# The controller is this machine; the address in parentheses spares a DNS lookup (this
# works even when the host name does not resolve; NODE=localhost works as well).
SlurmctldHost=$NODE(127.0.0.1)
# The package creates the slurm user and owns /var/lib/slurm and /var/log/slurm by it;
# slurmctld drops to it, slurmd stays root (it must start jobs as their submitter).
SlurmUser=slurm
AuthType=auth/munge
StateSaveLocation=/var/lib/slurm/slurmctld
SlurmdSpoolDir=/var/lib/slurm/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$LOG/slurmctld.log
SlurmdLogFile=$LOG/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# Track a job's processes through /proc and bind no tasks to CPUs: nothing to set up.
# (proctrack/cgroup depends on the machine's cgroup mounts and needs a cgroup.conf: without
# one every task "completes" 0:0 unrun, "cgroup namespace 'freezer' not mounted", and the
# node drains.)
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
# No slurmdbd, no accounting, no job completion log: nothing to install or start.
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
# Debian has no /usr/bin/mail here; without this slurmctld logs "Configured MailProg is invalid".
MailProg=/bin/true
# Give out single cores so the array's tasks run side by side (one per core).
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# A node that was down comes back as soon as its slurmd registers.
ReturnToService=2
# The node: CPUs = nproc; a small RealMemory that any CI machine has (memory is not scheduled).
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF

# 5. Start afresh: no jobs or node states of an earlier run (files an earlier run left as
#    another SlurmUser would stop slurmctld clearing them: "opendir(...): Permission denied").
rm -rf /var/lib/slurm/slurmctld/* /var/lib/slurm/slurmd/*
: >"$LOG/slurmctld.log"; : >"$LOG/slurmd.log"
# Daemon mode (they fork, detach and write their logs): nothing keeps this script's or CI's
# output open, and down.sh stops them by the pids in their pid files.
slurmctld || fail "slurmctld exited $?"
slurmd || fail "slurmd exited $?"

# 6. Wait until the node is idle.
state=""
for ((i = 0; i < TIMEOUT; i++)); do
  state=$(sinfo -h -N -n "$NODE" -o %t 2>/dev/null || true)
  [ "$state" = idle ] && { echo "slurm-up: node $NODE idle after ${i}s"; exit 0; }
  sleep 1
done
fail "node $NODE not idle after ${TIMEOUT}s (state: '${state:-no answer}')"
