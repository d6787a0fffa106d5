#!/usr/bin/env bash
# Builds the libFuzzer targets of test/fuzz/ with clang (ASan + UBSan, build-fuzz/) and runs each
# for a fixed time from its committed seed corpus (test/fuzz/corpus/<target>/, read only; new
# inputs go to build-fuzz/corpus/<target>/). Prints the executions reached and any finding; exits
# non-zero on a finding (its input is kept in build-fuzz/artifacts/<target>/).
# Usage: scripts/run_fuzz.sh [--junit FILE]   (FILE: one JUnit testcase per target)
# Env: WRC_FUZZ_SECONDS  time per target [s] (default 45)
#      WRC_FUZZ_TARGETS  targets to run (default: all, "fuzz_contact_step fuzz_scenario_csv")
# Reproduce a finding: build-fuzz/<target> build-fuzz/artifacts/<target>/crash-...
set -o pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
# shellcheck source=scripts/make_retry.sh
source scripts/make_retry.sh
junit=""
[ "${1:-}" = "--junit" ] && junit="$2"
export PATH="/usr/bin:$PATH"
dir=build-fuzz
seconds="${WRC_FUZZ_SECONDS:-45}"
targets=(${WRC_FUZZ_TARGETS:-fuzz_contact_step fuzz_scenario_csv})
jobs="${WRC_JOBS:-$(nproc)}"

results=()  # "name|seconds|verdict|log"
record() { results+=("$1|$2|$3|$4"); }
finish() {
  [ -z "$junit" ] || /usr/bin/python3 scripts/write_junit.py fuzz "$junit" "${results[@]}"
  for r in "${results[@]}"; do [[ "$r" == *"|passed|"* ]] || exit 1; done
  exit 0
}

t0=$(date +%s)
mkdir -p "$dir/logs"
if ! { cmake -S test/fuzz -B "$dir" -DCMAKE_CXX_COMPILER=clang++ > "$dir/logs/build.log" 2>&1 &&
  make_retry "$dir/logs/build.log" -C "$dir" -j"$jobs" "${targets[@]}"; }; then
  tail -40 "$dir/logs/build.log"
  record fuzz_build "$(($(date +%s) - t0))" "build failed" "$dir/logs/build.log"
  finish
fi
echo "[fuzz] built ${targets[*]} in $(($(date +%s) - t0)) s; ${seconds} s each"

for t in "${targets[@]}"; do
  log="$dir/logs/$t.log"
  seeds="test/fuzz/corpus/$t"
  rm -rf "$dir/artifacts/$t"
  mkdir -p "$dir/corpus/$t" "$dir/artifacts/$t"
  start=$(date +%s)
  # -timeout: one input running longer than 20 s is a hang (a finding); the seeds run first.
  "$dir/$t" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$dir/artifacts/$t/" "$dir/corpus/$t" "$seeds" > "$log" 2>&1
  rc=$?
  runs=$(grep -oE "stat::number_of_executed_units: [0-9]+" "$log" | grep -oE "[0-9]+$")
  cov=$(grep -oE "cov: [0-9]+ ft: [0-9]+ corp: [0-9]+/[^ ]+" "$log" | tail -1)
  artifacts=$(find "$dir/artifacts/$t" -type f | head -5)
  if [ "$rc" -ne 0 ] || [ -n "$artifacts" ]; then
    verdict="finding (exit code $rc)"
    grep -m5 -E "FINDING:|ERROR: (Address|Leak)Sanitizer|runtime error:|deadly signal|timeout" \
      "$log"
    grep -A3 "FINDING:" "$log" | head -8
    echo "[fuzz] $t: input kept: ${artifacts:-none}; log: $log"
  else
    verdict="passed"
  fi
  echo "[fuzz] $t: ${runs:-?} executions in $(($(date +%s) - start)) s, $cov: $verdict"
  record "$t" "$(($(date +%s) - start))" "$verdict" "$log"
done
finish
