#!/usr/bin/env bash
# Time per step of every FastSim model and mesh (bench_fastsim) and its ratio to steady FastSim on
# the same mesh, as doc/performance.md's "Cost per step" table. The least CPU time over ROUNDS whole sweeps
# of 25 short repetitions each: this machine's host interrupts it in spells that only ever add
# time, so the least is what the code costs; whole sweeps spread a slow spell over every model.
# usage: scripts/step_time.sh [ROUNDS]   (default 4, about a minute a round); needs a Release build.
# Instruction counts, independent of the load: scripts/step_cost.sh.
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="$here/build/devel/lib/wheel_rail_contact/bench_fastsim"
rounds="${1:-4}"
raw="$(mktemp)"
trap 'rm -f "$raw"' EXIT
for ((r = 0; r < rounds; ++r)); do
  "$bin" --benchmark_repetitions=25 --benchmark_min_time=0.05 \
    --benchmark_enable_random_interleaving=true --benchmark_format=csv 2> /dev/null >> "$raw"
done
/usr/bin/python3 - "$raw" << 'PY'
import collections, csv, sys
least = collections.defaultdict(lambda: float("inf"))
for row in csv.reader(open(sys.argv[1])):
    if len(row) < 5 or row[0] == "name" or row[0].rsplit("_", 1)[-1] in ("mean", "median", "stddev", "cv", "min"):
        continue
    least[row[0]] = min(least[row[0]], float(row[3]))  # cpu_time, ns
cols = [("Steady", None), ("NssAdaptiveConstantLoad", "Steady"), ("NssAdaptive", "Steady"),
        ("SteadyFixedMesh", None), ("NssFixed", "SteadyFixedMesh"), ("ShenLi", "SteadyFixedMesh"),
        ("NssAdaptiveConstantLoadShipped", "Steady"), ("NssAdaptiveShipped", "Steady"),
        ("NssFixedShipped", "SteadyFixedMesh")]
print("| mesh | steady, fitted mesh | nss adaptive, constant load | nss adaptive, varying load |"
      " steady, fixed mesh | nss fixed | shen-li fixed | shipped χ: adaptive, constant load |"
      " shipped χ: adaptive, varying load | shipped χ: nss fixed |")
print("|" + " --- |" * (len(cols) + 1))
for n in (10, 20, 30, 40):
    cells = []
    for name, ref in cols:
        t = least[f"{name}/{n}"]
        cells.append(f"{t / 1e3:.2f} µs" + (f" ({t / least[f'{ref}/{n}']:.2f}x)" if ref else ""))
    print(f"| {n}x{n} | " + " | ".join(cells) + " |")
PY
