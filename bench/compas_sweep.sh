#!/usr/bin/env bash
# Every shared COMPAS assembly at mu = 0.1, 0.3, 0.5, 0.84 and 1.0, with the
# supports of docs/compas-format.md: the verdict, the moving parts, the
# stability proved and the time of each `cairn check`.
# Usage: bench/compas_sweep.sh CAIRN [SHARED_DATASETS_DIR] [MU...]
set -uo pipefail
cairn=${1:?usage: compas_sweep.sh CAIRN [DATASETS] [MU...]}
data=${2:-$(dirname "$0")/../../shared/datasets}
shift 2 2>/dev/null || shift $#
mus=("$@")
((${#mus[@]})) || mus=(0.1 0.3 0.5 0.84 1.0)
# file|model options (supports as the example scripts set them)
cases=(
  "compas_assembly/arch_assembly.json|"
  "compas_assembly/crossvault_assembly.json|"
  "compas_assembly/stack_assembly.json|"
  "compas_assembly/two-blocks_assembly.json|"
  "compas_assembly/wall_assembly.json|"
  "compas_cra/A.json|--supports 0,1"
  "compas_cra/H.json|--supports 0,1"
  "compas_cra/cubes.json|--supports 0"
  "compas_cra/type-a.json|--supports 0,1"
  "compas_cra/type-b.json|--supports 0,1"
  "compas_cra/type-c.json|--supports 0,1"
  "compas_cra/type-d.json|--supports 0,1"
  "compas_cra/concave-short.json|--supports 0"
  "compas_cra/concave-long.json|--supports 0"
  "compas_cra/cube-curve-short.json|--supports 0"
  "compas_cra/cube-curve-tall.json|--supports 0 --interfaces stored"
  "compas_cra/curve-3-blocks.json|--supports 0 --interfaces stored"
  "compas_cra/shelf.json|--supports 0"
  "compas_cra/shelf-stable.json|--supports 0"
  "compas_cra/shelf-s1.json|--supports 0"
  "compas_cra/shelf-s2.json|--supports 0"
  "compas_cra/shelf-s3.json|--supports 0"
  "compas_cra/snake.json|--supports 0"
  "compas_cra/bridge.json|--supports 0,1"
  "compas_cra/armadillo.json|"
  "compas_cra/armadillo_cra.json|--interfaces stored"
)
printf '%-40s %5s %5s %-9s %-14s %8s  %s\n' file mu exit verdict stability seconds moving
for c in "${cases[@]}"; do
  file=${c%%|*} opts=${c#*|}
  for mu in "${mus[@]}"; do
    start=$(date +%s.%N)
    json=$(timeout 600 "$cairn" check "$data/$file" --format compas --friction "$mu" $opts --json 2>/tmp/sweep_err)
    code=$?
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    if [[ $code -le 1 && -n "$json" ]]; then
      line=$(printf '%s' "$json" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); m=d["moving"]; print(d["verdict"].replace(" ","_"), str(d.get("stability")).replace(" ","_"), len(m), ",".join(m[:8])+("..." if len(m)>8 else ""))')
      read -r verdict stab nmov names <<<"$line"
    else
      verdict="exit$code" stab="-" nmov="-" names=$(head -c 80 /tmp/sweep_err)
    fi
    printf '%-40s %5s %5s %-9s %-14s %8.2f  %s %s\n' "$file" "$mu" "$code" "$verdict" "$stab" "$secs" "$nmov" "$names"
  done
done
