#!/usr/bin/env bash
# The OMPL RRT* reference (scripts/ompl_rrt_star.py) on every scenario × N × seed, as waypoints
# files for `shoal compare --waypoints DIR` (docs/baseline.md). Not part of any test run.
#
#   python3 -m pip install -r scripts/ompl-requirements.txt && cargo build --release
#   scripts/ompl_compare.sh                      # writes ompl-waypoints/SCENARIO-nN-sSEED.json
#   target/release/shoal compare default examples/bathymetry/abrolhos.toml --waypoints ompl-waypoints
#
# Settings (environment): SCENARIOS ("default" and/or scenario files), AUVS, SEEDS, TIME (s per
# plan), OUT (directory), SHOAL (the binary), PYTHON. Each run plans the MPC first: RRT* plans the
# AUVs against the MPC plan's USV track (the script's header says why), over the floor the plan
# used, exported as an ESRI ASCII grid.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
shoal=${SHOAL:-target/release/shoal}
python=${PYTHON:-python3}
out=${OUT:-ompl-waypoints}
time=${TIME:-30}
mkdir -p "$out/work"
for scenario in ${SCENARIOS:-default}; do
  if [ "$scenario" = default ]; then name=default; args=(); else name=$(basename "$scenario" .toml); args=("$scenario"); fi
  for n in ${AUVS:-1 3 5}; do
    for seed in ${SEEDS:-1 2 3 4 5}; do
      run="$name-n$n-s$seed"
      work="$out/work/$run"
      sets=(--set "team.auvs=$n" --set "seed=$seed")
      "$shoal" plan "${args[@]}" "${sets[@]}" -o "$work/mpc" --no-plot -q
      "$shoal" seafloor export "${args[@]}" "${sets[@]}" -o "$work/floor.asc" >/dev/null
      if "$python" "$here/ompl_rrt_star.py" "$work/mpc/plan.json" --floor "$work/floor.asc" \
        -o "$out/$run.json" --time "$time" --seed "$seed" >"$work/ompl.log" 2>&1; then
        echo "$run: $(grep -m1 -i 'cost' "$work/ompl.log" || echo written)"
      else
        echo "$run: no path (see $work/ompl.log)"
      fi
    done
  done
done
