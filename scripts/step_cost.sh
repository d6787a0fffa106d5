#!/usr/bin/env bash
# Instructions per step of every FastSim model and mesh (callgrind: independent of the machine's
# load), and their ratio to steady FastSim on the same mesh. Scene: bench/step_inputs.hpp.
# usage: scripts/step_cost.sh [SIZES...]   (default: 10 20 40); needs valgrind and a Release build.
# CHI=shipped gives nss the shipped chi table (kind 23 second order) instead of a uniform
# first-order one.
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="$here/build/devel/lib/wheel_rail_contact/step_cost"
steps=1000
count() {  # model mesh n load -> instructions per step
  local out
  out="$(mktemp)"
  valgrind --tool=callgrind --toggle-collect='*runSteps*' --callgrind-out-file="$out" \
    "$bin" "$1" "$2" "$3" "$4" "$steps" ${CHI:+"$CHI"} > /dev/null 2>&1
  callgrind_annotate "$out" 2> /dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}' |
    { read -r total; echo $((total / steps)); }
  rm -f "$out"
}
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(10 20 40)
# Each nss column against steady FastSim on the same mesh: the adaptive mesh against SteadyModel
# (both fit the mesh to the patch), the fixed mesh against steady FastSim on that fixed mesh.
echo "| mesh | steady, fitted mesh | nss adaptive, constant load | nss adaptive, varying load |" \
  "steady, fixed mesh | nss fixed | shen-li fixed |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for n in "${sizes[@]}"; do
  cell() { local c; c="$(count "$2" "$3" "$n" "$4")"; awk -v c="$c" -v s="$1" 'BEGIN {printf "%d (%.2fx)", c, c / s}'; }
  fitted="$(count steady fitted "$n" vary)"
  fixed="$(count steady fixed "$n" vary)"
  echo "| ${n}x${n} | $fitted | $(cell "$fitted" nss adaptive constant) |" \
    "$(cell "$fitted" nss adaptive vary) | $fixed | $(cell "$fixed" nss fixed vary) |" \
    "$(cell "$fixed" shen-li fixed vary) |"
done
