#!/usr/bin/env bash
# CLI harness: `cairn plan`, timed as a user runs it:
# the 10- and 14-brick pyramids enumerated completely (frictionless, and the
# 10-brick one with friction 0.5), the 54-block Jenga tower's first stable
# sequence and its first 10, Fig. 6 with its exits. Prints, per run, the
# AND/OR nodes, node checks, path simulations, sequences and the planner's
# own time (stats.time) beside the wall time of the whole command.
# Usage: bench/plan_bench.sh [path/to/cairn] [threads] (defaults:
# build-bench/cairn, every core).
set -uo pipefail
cd "$(dirname "$0")/.."
cairn=${1:-build-bench/cairn}
threads=${2:-0}
run() {  # label, args...
  local label=$1
  shift
  local start=${EPOCHREALTIME/./}
  "$cairn" plan "$@" --json --threads "$threads" > /tmp/cairn_plan_bench_$$.json
  local rc=$?
  local us=$((${EPOCHREALTIME/./} - start))
  python3 - "$label" "$rc" "$us" /tmp/cairn_plan_bench_$$.json <<'PY'
import json, sys
label, rc, us, path = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
doc = json.load(open(path))
s = doc["stats"]
count = s["sequences_total"] if doc["complete"] else len(doc["sequences"])
print(f"{label}: exit {rc}, wall {us / 1e6:.2f} s, planner {s['time']:.2f} s on {s['threads']} threads; "
      f"{s['nodes']} nodes, {s['edges']} edges, {s['node_checks']} node checks, "
      f"{s['path_simulations']} path simulations, {s['decided_by_nodes']} paths by node checks, "
      f"{s['pruned_by_proposition_1']} pruned; {count:.6g} sequences"
      + ("" if doc["complete"] else " found"))
PY
  rm -f /tmp/cairn_plan_bench_$$.json
}
run "pyramid10, complete" examples/pyramid10.json
run "pyramid14, complete" examples/pyramid14.json
run "pyramid10 with friction 0.5, complete" examples/pyramid10.json --friction 0.5
run "paper Fig. 6 with its exits, complete" examples/paper_fig6.json --paths examples/paths/paper_fig6_exits.paths.json
run "Jenga, first sequence" examples/jenga.json --max 1
run "Jenga, 10 sequences" examples/jenga.json --max 10
