#!/usr/bin/env bash
# Stop the daemons up.sh started, by the pids in their pid files.
# --keep-munge: leave munged running (up.sh uses this before restarting Slurm).
set -euo pipefail

stop() { # stop NAME PIDFILE: SIGTERM, then wait up to 20 s for the process to exit (~2 s each)
  local name=$1 pidfile=$2 pid
  [ -s "$pidfile" ] || return 0
  pid=$(cat "$pidfile")
  if kill -0 "$pid" 2>/dev/null && grep -q "$name" "/proc/$pid/comm" 2>/dev/null; then
    kill "$pid"
    for ((i = 0; i < 100; i++)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    kill -0 "$pid" 2>/dev/null && { echo "slurm-down: $name ($pid) still running" >&2; return 1; }
    echo "slurm-down: stopped $name ($pid)"
  fi
  rm -f "$pidfile"
}

stop slurmd /run/slurmd.pid
stop slurmctld /run/slurmctld.pid
[ "${1:-}" = --keep-munge ] || stop munged /run/munge/munged.pid
