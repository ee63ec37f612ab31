#!/usr/bin/env bash
# `cairn batch` and `cairn plan` across MPI ranks (docs/benchmarks.md, "cairn
# batch" and "cairn plan across MPI ranks"):
#  1. 1 000 generated scenes (scripts/batch_scenes.py) checked by the
#     command's document function in one process (batch_overhead_bench: the
#     baseline), then by `cairn batch` on 1 rank (one worker thread), and
#     under mpirun on 2 ranks (rank 0 serves, 1 worker) and 3 ranks (2
#     workers): jobs per second, and the overhead per job against the
#     baseline;
#  2. `cairn plan` of a 15-brick pyramid (16 parts) with friction 0.5,
#     complete enumeration, on 1, 2 and 4 ranks (--oversubscribe beyond the
#     cores), one thread per rank: the planner's time, each rank's time in
#     tasks and in communication (waiting included).
# Usage: bench/mpi_bench.sh [path/to/cairn] [path/to/batch_overhead_bench] [scenes]
# (defaults: build/cairn, build/bench/batch_overhead_bench, 1000).
set -euo pipefail
cd "$(dirname "$0")/.."
cairn=${1:-build/cairn}
baseline=${2:-build/bench/batch_overhead_bench}
scenes=${3:-1000}
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
dir=$(mktemp -d /tmp/cairn_mpi_bench.XXXXXX)
trap 'rm -rf "$dir"' EXIT
seconds() { python3 -c "import sys; print(f'{(int(sys.argv[2]) - int(sys.argv[1])) / 1e6:.3f}')" "$@"; }

echo "== cairn batch: $scenes generated scenes (check jobs)"
python3 scripts/batch_scenes.py "$dir" "$scenes"
"$baseline" "$dir/jobs.jsonl" 3
batch() {  # label, launcher... (best of 3 runs: the machine is shared)
  local label=$1
  shift
  local best=""
  for _ in 1 2 3; do
    local start=${EPOCHREALTIME/./}
    "$@" "$cairn" batch "$dir/jobs.jsonl" -o "$dir/results.jsonl" --fresh --threads 1 > /dev/null
    local end=${EPOCHREALTIME/./}
    local s
    s=$(seconds "$start" "$end")
    best=$(python3 -c "import sys; print(min(float(x) for x in sys.argv[1:] if x))" "$s" "$best")
  done
  python3 -c "import sys; n, s = int(sys.argv[2]), float(sys.argv[3]); \
print(f'{sys.argv[1]}: {s:.2f} s (best of 3), {n / s:.0f} jobs/s, {1e6 * s / n:.0f} us per job')" \
    "$label" "$scenes" "$best"
}
batch "batch, 1 rank (1 thread)"
batch "batch, mpirun -n 2 (1 worker)" mpirun --oversubscribe -n 2
batch "batch, mpirun -n 3 (2 workers)" mpirun --oversubscribe -n 3

echo "== cairn plan: 15-brick pyramid (16 parts), friction 0.5, complete"
python3 bench/pyramid_scene.py "$dir/pyramid.json" 5,4,3,2,1 0.5
plan() {  # ranks
  local launcher=()
  if (($1 > 1)); then launcher=(mpirun --oversubscribe -n "$1"); fi
  local start=${EPOCHREALTIME/./}
  "${launcher[@]}" "$cairn" plan "$dir/pyramid.json" --json --threads 1 > "$dir/plan.json" || true
  local end=${EPOCHREALTIME/./}
  python3 - "$1" "$(seconds "$start" "$end")" "$dir/plan.json" <<'PY'
import json, sys
ranks, wall, doc = int(sys.argv[1]), float(sys.argv[2]), json.load(open(sys.argv[3]))
s = doc["stats"]
work = s.get("rank_time", [s["time"]])
comm = s.get("communication_time", [0.0])
print(f"plan, {ranks} rank(s): planner {s['time']:.2f} s (wall {wall:.2f} s with the output); "
      f"{s['node_checks']} node checks, {s['path_simulations']} path simulations; "
      f"per rank in tasks {', '.join(f'{w:.2f}' for w in work)} s; "
      f"communication {', '.join(f'{c:.2f}' for c in comm)} s")
PY
}
for ranks in 1 2 4; do plan "$ranks"; done
