#!/usr/bin/env bash
# The 108-run comparison: a change that must not alter any force (renames, layout, build flags)
# is checked by recording contact_cli's outputs before it and comparing them byte for byte after.
#   scripts/compare_runs.sh record DIR    writes DIR/<scene>_<config>_<model>_<mesh>.csv
#   scripts/compare_runs.sh compare DIR   re-runs the same runs and compares them with DIR
# Runs: scenes/*.csv (3) x config {default, paper} x model {steady, shen-li, nss, exact, auto}
# x mesh {fixed, adaptive} (60), each in its default FastSim variant; nss and auto once more with
# fastsim classic (24); steady with fastsim calibrated (12); and model auto at tolerance 0.01 and
# 0.2 with config paper (12).
# Env: WRC_CLI (default build/devel/lib/wheel_rail_contact/contact_cli).
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
mode="${1:-}"
dir="${2:-}"
if [ -z "$dir" ] || { [ "$mode" != record ] && [ "$mode" != compare ]; }; then
  echo "usage: $0 {record|compare} DIR" >&2
  exit 2
fi
cli="${WRC_CLI:-build/devel/lib/wheel_rail_contact/contact_cli}"
[ -x "$cli" ] || { echo "$0: $cli not built" >&2; exit 2; }
mkdir -p "$dir"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

runs=0
differ=0
run() {  # name, then contact_cli run's arguments
  local name="$1"
  shift
  local out="$tmp/$name.csv"
  # stdout, then the exit status and stderr of a refused run (its message is part of the behaviour)
  "$cli" run "$@" > "$out" 2> "$tmp/err" || { echo "exit $?"; cat "$tmp/err"; } >> "$out"
  runs=$((runs + 1))
  if [ "$mode" = record ]; then
    cp "$out" "$dir/$name.csv"
  elif ! cmp -s "$out" "$dir/$name.csv"; then
    echo "DIFFERS: $name"
    differ=$((differ + 1))
  fi
}

for scene in scenes/*.csv; do
  s="$(basename "$scene" .csv)"
  for config in default paper; do
    for model in steady shen-li nss exact auto; do
      for mesh in fixed adaptive; do
        run "${s}_${config}_${model}_${mesh}" --scenario "$scene" --config "config/$config.yaml" \
          --model "$model" --mesh "$mesh"
      done
    done
  done
  for config in default paper; do
    for model in nss auto; do
      for mesh in fixed adaptive; do
        run "${s}_${config}_${model}-classic_${mesh}" --scenario "$scene" \
          --config "config/$config.yaml" --model "$model" --mesh "$mesh" --fastsim classic
      done
    done
  done
  for config in default paper; do
    for mesh in fixed adaptive; do
      run "${s}_${config}_steady-calibrated_${mesh}" --scenario "$scene" \
        --config "config/$config.yaml" --model steady --mesh "$mesh" --fastsim calibrated
    done
  done
  for tol in 0.01 0.2; do
    for mesh in fixed adaptive; do
      run "${s}_paper_auto-tol${tol}_${mesh}" --scenario "$scene" --config config/paper.yaml \
        --model auto --tolerance "$tol" --mesh "$mesh"
    done
  done
done
if [ "$mode" = record ]; then
  echo "[compare_runs] recorded $runs runs in $dir"
else
  echo "[compare_runs] $runs runs, $differ differ"
  [ "$differ" -eq 0 ]
fi
