#!/usr/bin/env bash
# How the RRT-like baseline's time and objective grow with the tree (samples 𝔯 per node, nodes
# kept per step) and the team size N, against the MPC on the same scenarios (BENCHMARKS.md,
# "MPC against sampling"). Usage: scripts/rrt_scaling.sh [SHOAL] [OUT]; SHOAL defaults to
# target/release/shoal (build it with `cargo build --release`), OUT to rrt-scaling.
set -euo pipefail
shoal=${1:-target/release/shoal}
out=${2:-rrt-scaling}
seeds=${SEEDS:-1-3}
mkdir -p "$out"
row() { # the summary.md rows of a compare run, prefixed with its settings
  tail -n +3 "$1/summary.md" | sed "s/^/| $2 /"
}
{
  echo "| 𝔯 | budget | scenario | method | N | planned / passed / runs | wall time s, median (range) | P2 objective | energy Σ‖U‖² | mean height m | explored km² | USV moved m | draws |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for n in 1 3 5; do
    "$shoal" compare --methods mpc --auvs "$n" --seeds "$seeds" --no-plot -o "$out/mpc-n$n" >/dev/null 2>&1
    row "$out/mpc-n$n" "- | -"
    for r in 4 16 64; do
      for b in 50 200 1000 5000; do
        [ "$n" -gt 1 ] && [ "$b" -gt 1000 ] && continue # minutes per plan; the trend is clear
        d="$out/rrt-n$n-r$r-b$b"
        "$shoal" compare --methods rrt-like --auvs "$n" --seeds "$seeds" --no-plot -o "$d" \
          --set "sampling.samples=$r" --set "sampling.tree_budget=$b" >/dev/null 2>&1
        row "$d" "$r | $b"
      done
    done
  done
} | tee "$out/table.md"
