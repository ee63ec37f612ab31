#!/usr/bin/env bash
# CLI harness: `cairn sequence` (build orders with the fewest temporary
# supports) against `cairn plan --single-parts --max 1` (the exact AND/OR
# search for one stable disassembly sequence of single parts) in the same
# run, on the models issue 33 names: the arches and the wall of
# compas_assembly, the examples' wall, the cross vault and the Armadillo.
# Each run is timed as a user runs it (wall clock, peak memory by
# /usr/bin/time) and cut at LIMIT seconds (`timeout`: "killed" when it did
# not finish). Prints, per run, the answer in one line.
# Usage: bench/sequence_bench.sh [path/to/cairn] [limit seconds]
# (defaults: build-bench/cairn, 300). Reads ../shared/datasets; skips what
# is absent.
set -uo pipefail
cd "$(dirname "$0")/.."
cairn=${1:-build-bench/cairn}
limit=${2:-300}
data=../shared/datasets
out=/tmp/cairn_sequence_bench_$$
trap 'rm -f $out.json $out.time' EXIT

run() {  # label, command (plan|sequence), file, args...
  local label=$1 command=$2 file=$3
  shift 3
  if [[ ! -f $file ]]; then
    echo "$label: $file not found, skipped"
    return
  fi
  /usr/bin/time -f '%e %M' -o $out.time timeout -s INT $((limit + 30)) \
    "$cairn" "$command" "$file" "$@" --json > $out.json 2> /dev/null
  local rc=$?
  read -r seconds kb < <(tail -1 $out.time)
  /usr/bin/python3 - "$label" "$command" "$rc" "$seconds" "$kb" $out.json <<'PY'
import json, sys
label, command, rc, seconds, kb, path = sys.argv[1:7]
head = f"{label}: {command}, exit {rc}, {float(seconds):.2f} s, {int(kb) / 1024:.0f} MB"
try:
    doc = json.load(open(path))
except (OSError, ValueError):
    print(f"{head}: no document (killed at the limit)")
    sys.exit()
if command == "plan":
    found = len(doc["sequences"])
    print(f"{head}: {found} stable sequence(s)" + ("" if doc["complete"] or found else " (search incomplete)")
          + (f"; {doc['message']}" if not found and doc.get("message") else ""))
else:
    t, s = doc["temporary"], doc["stats"]
    print(f"{head}: {'complete' if doc['complete'] else 'INCOMPLETE'}, {len(doc['order'])} placed, "
          f"{t['max_in_place']} support(s) at once ({'+'.join(t['kinds'])}), {t['placements']} in all, "
          f"lower bound {t['lower_bound']}{' (optimal)' if t['optimal'] else ''}; "
          f"{s['states_checked']} states, {s['repairs']} repairs, "
          f"{s.get('verdict_rejections', 0)} verdict rejections"
          + (f"; {doc['message']}" if doc["message"] else ""))
PY
}

ca=$data/compas_assembly
arch="$ca/arch_assembly.json --format compas --friction 0.84"
run "compas arch (28 free)" plan $arch --single-parts --max 1
run "compas arch, holds, axes" sequence $arch --directions axes
run "compas arch, props, axes" sequence $arch --directions axes --temporary prop
run "compas arch, both, axes" sequence $arch --directions axes --temporary both
wall="$ca/wall_assembly.json --format compas --friction 0.84"
run "compas wall" plan $wall --single-parts --max 1
run "compas wall" sequence $wall
run "examples/wall.json (105 bricks)" plan examples/wall.json --single-parts --max 1
run "examples/wall.json (105 bricks)" sequence examples/wall.json
vault="$ca/crossvault_assembly.json --format compas --friction 0.84"
run "cross vault (180 free)" plan $vault --single-parts --max 1
run "cross vault (180 free)" sequence $vault --time-limit "$limit"
armadillo="$data/compas_cra/armadillo_cra.json --format compas --friction 0.84 --interfaces stored"
run "Armadillo (366 free)" sequence $armadillo --time-limit "$limit"
