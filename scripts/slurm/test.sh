#!/usr/bin/env bash
# CI's end-to-end test of a study on Slurm: start a real one-node cluster (up.sh), submit
# examples/slurm/study.sbatch as a job array with sbatch, wait for it, collect the shard tables
# and check that the collected table is the local run's (`shoal sweep` of the same study on
# this machine), rows sorted by run and wall_s aside (a run's time differs run to run).
# Prints PASS or FAIL and stops the daemons on the way out. Needs root (apt-get, daemons).
#
#   SHOAL=target/release/shoal scripts/slurm/test.sh [STUDY]   (default examples/slurm/study.toml)
#   TASKS=4 (array size), SLURM_TEST_DIR (work directory; default a new temporary one),
#   SLURM_TEST_TIMEOUT=600 (seconds the array may take)
set -euo pipefail

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
STUDY=$(realpath "${1:-$ROOT/examples/slurm/study.toml}")
SHOAL=$(realpath "${SHOAL:-$ROOT/target/release/shoal}")
SBATCH_FILE=$ROOT/examples/slurm/study.sbatch
TASKS=${TASKS:-4}
WAIT=${SLURM_TEST_TIMEOUT:-600}
WORK=${SLURM_TEST_DIR:-$(mktemp -d)}
start=$SECONDS
[ -x "$SHOAL" ] || { echo "FAIL: no shoal binary at $SHOAL (set SHOAL)"; exit 1; }

trap '"$HERE/down.sh"' EXIT   # also when up.sh fails half-way
"$HERE/up.sh"

rm -rf "$WORK" && mkdir -p "$WORK"
cd "$WORK"   # the tasks' logs (--output of study.sbatch) land here

# STUDY, OUT and SHOAL reach the tasks through sbatch's default --export=ALL.
echo "== sbatch --array=0-$((TASKS - 1)) $SBATCH_FILE ($STUDY)"
t=$SECONDS
job=$(STUDY=$STUDY OUT=$WORK/slurm SHOAL=$SHOAL \
    sbatch --parsable --array="0-$((TASKS - 1))" "$SBATCH_FILE")
# Poll squeue (it lists a job until it has ended) rather than `sbatch --wait`, which polls at
# growing intervals (it returned 8 s after a 2 s array).
for ((i = 0; i < WAIT; i++)); do
    [ -z "$(squeue -h -j "$job" -o %i 2>/dev/null)" ] && break
    sleep 1
done
[ "$i" -lt "$WAIT" ] || { echo "FAIL: job $job still queued or running after ${WAIT}s"; squeue; exit 1; }
echo "== the array ended after $((SECONDS - t)) s"
for f in shoal-study-*.out; do echo "--- $f"; cat "$f"; done
# Without accounting there is no sacct; slurmctld keeps ended jobs for MinJobAge (300 s).
states=$(scontrol -o show job "$job" |
    grep -o 'ArrayTaskId=[^ ]*\|JobState=[^ ]*\|ExitCode=[^ ]*' | paste - - - | sort)
echo "$states"
ok=$(grep -c $'JobState=COMPLETED\tExitCode=0:0' <<<"$states" || true)
[ "$ok" = "$TASKS" ] || { echo "FAIL: $ok of $TASKS tasks completed with exit code 0"; exit 1; }
# A task whose job step could not start (e.g. a failing proctrack plugin) still shows
# COMPLETED 0:0 while its node drains: the shard tables are the proof that the tasks ran.
shopt -s nullglob
shards=(slurm/shard-*-of-"$TASKS".csv)
[ "${#shards[@]}" = "$TASKS" ] || { echo "FAIL: ${#shards[@]} of $TASKS shard tables"; exit 1; }

echo "== shoal sweep collect; the same study locally"
"$SHOAL" sweep collect slurm
"$SHOAL" sweep --quiet "$STUDY" -o local

# The two tables, wall_s aside and rows sorted by run, must be equal.
python3 - slurm/runs.csv local/runs.csv <<'PY'
import csv, sys
def table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    keep = [i for i, name in enumerate(header) if name != "wall_s"]
    pick = lambda r: [r[i] for i in keep]
    return pick(header), sorted((pick(r) for r in body), key=lambda r: int(r[0]))
(hs, rs), (hl, rl) = table(sys.argv[1]), table(sys.argv[2])
if hs != hl:
    sys.exit(f"FAIL: the columns differ:\n{hs}\n{hl}")
if not rl:
    sys.exit("FAIL: the local table is empty")
for a, b in zip(rs, rl):
    if a != b:
        sys.exit(f"FAIL: run {b[0]} differs:\nslurm {a}\nlocal {b}")
if len(rs) != len(rl):
    sys.exit(f"FAIL: {len(rs)} rows from Slurm, {len(rl)} locally")
print(f"{len(rl)} rows equal")
PY
echo "PASS: Slurm array of $TASKS tasks = local run ($STUDY) in $((SECONDS - start)) s"
