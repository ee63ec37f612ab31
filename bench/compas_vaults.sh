#!/usr/bin/env bash
# CLI harness: `cairn check` of the shared COMPAS vaults,
# timed as a user runs it. Usage: bench/compas_vaults.sh [path/to/cairn]
# (default build-bench/cairn). Reads ../shared/datasets; skips what is absent.
set -uo pipefail
cd "$(dirname "$0")/.."
cairn=${1:-build-bench/cairn}
data=../shared/datasets
run() {  # label, file, args...
  local label=$1 file=$2
  shift 2
  if [[ ! -f $data/$file ]]; then
    echo "$label: $data/$file not found, skipped"
    return
  fi
  local start=${EPOCHREALTIME/./} # microseconds (bash 5)
  "$cairn" check "$data/$file" --format compas "$@" > /tmp/cairn_vault_$$.txt
  local rc=$?
  local us=$((${EPOCHREALTIME/./} - start))
  printf '%s: exit %d, %d.%02d s\n' "$label" "$rc" $((us / 1000000)) $((us % 1000000 / 10000))
  sed -n '1,3p' /tmp/cairn_vault_$$.txt | sed 's/^/    /' | cut -c1-200
  rm -f /tmp/cairn_vault_$$.txt
}
run "cross vault, 184 blocks" compas_assembly/crossvault_assembly.json --friction 0.84
run "Armadillo vault, 399 blocks (stored interfaces)" compas_cra/armadillo_cra.json \
  --friction 0.84 --interfaces stored
