#!/usr/bin/env bash
# Instructions per step of every FastSim model and mesh (callgrind: independent of the machine's
# load), and their ratio to steady FastSim on the same mesh. Scene: bench/step_inputs.hpp.
# usage: scripts/step_cost.sh [SIZES...]   (default: 10 20 40); needs valgrind and a Release build.
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="$here/build/devel/lib/wheel_rail_contact/step_cost"
steps=1000
count() {  # model mesh n load -> instructions per step
  local out
  out="$(mktemp)"
  valgrind --tool=callgrind --toggle-collect='*runSteps*' --callgrind-out-file="$out" \
    "$bin" "$1" "$2" "$3" "$4" "$steps" > /dev/null 2>&1
  callgrind_annotate "$out" 2> /dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}' |
    { read -r total; echo $((total / steps)); }
  rm -f "$out"
}
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(10 20 40)
echo "| mesh | steady | shen-li | nss fixed | nss adaptive | nss adaptive, constant load |"
echo "| --- | --- | --- | --- | --- | --- |"
for n in "${sizes[@]}"; do
  s="$(count steady fixed "$n" vary)"
  cell() { local c; c="$(count "$@")"; awk -v c="$c" -v s="$s" 'BEGIN {printf "%d (%.2fx)", c, c / s}'; }
  echo "| ${n}x${n} | $s | $(cell shen-li fixed "$n" vary) | $(cell nss fixed "$n" vary) |" \
    "$(cell nss adaptive "$n" vary) | $(cell nss adaptive "$n" constant) |"
done
