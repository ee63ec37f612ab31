#!/usr/bin/env bash
# CLI harness: `cairn blocking` of FreeCAD-APLAN's toy truck (61 parts:
# chassis, cabin, drum, 39 wood screws) along x, y and z, timed as a user
# runs it. The benchmark's STEP file of the whole truck is one solid with
# voids; its parts, placed as in its FreeCAD assembly, are the shapes the
# .FCStd stores (A2plus: one Part::FeaturePython per part, its BREP placed
# by its location). They are extracted here (Python's zipfile and
# ElementTree) and written as a STEP assembly by bench/fcstd_to_step.
# Usage: bench/truck_blocking.sh FCSTD [path/to/cairn] [path/to/fcstd_to_step]
# (FCSTD: library/008_toy_truck/asm_cement_mixer_truck.FCStd of
# github.com/martcram/FreeCAD-APLAN-benchmark; defaults: build-bench/cairn,
# build-bench/bench/fcstd_to_step).
set -euo pipefail
cd "$(dirname "$0")/.."
fcstd=$1
cairn=${2:-build-bench/cairn}
convert=${3:-build-bench/bench/fcstd_to_step}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$fcstd" "$work" <<'PY'
import os, sys, zipfile, xml.etree.ElementTree as ET
fcstd, work = sys.argv[1], sys.argv[2]
z = zipfile.ZipFile(fcstd)
lines = []
for o in ET.fromstring(z.read("Document.xml")).find("ObjectData"):
    props = {p.get("name"): p for p in o.iter("Property")}
    if "Shape" not in props or "Placement" not in props:
        continue
    brep = props["Shape"].find("Part").get("file")
    label = props["Label"].find("String").get("value") if "Label" in props else o.get("name")
    with open(os.path.join(work, brep), "wb") as f:
        f.write(z.read(brep))
    lines.append(f"{label} {brep}\n")
with open(os.path.join(work, "truck.txt"), "w") as f:
    f.writelines(lines)
PY
"$convert" "$work/truck.txt" "$work/truck.step"
for d in 1,0,0 0,1,0 0,0,1; do
  start=${EPOCHREALTIME/./}
  "$cairn" blocking "$work/truck.step" --format step --direction "$d" > "$work/out.txt" 2> /dev/null
  us=$((${EPOCHREALTIME/./} - start))
  echo "blocking along $d: wall $((us / 1000)) ms; $(grep -o 'leave: .*   blocked' "$work/out.txt" | sed 's/   blocked$//')"
done
