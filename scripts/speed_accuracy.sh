#!/usr/bin/env bash
# Speed against accuracy (issue 6): every model and mesh through the frequency-response sweep, the
# paper's combined cases and the varying-load cases, error against the fine-grid exact solver and
# least cost per step over repeated passes and three sweeps (--rounds); writes doc/data/speed_accuracy.csv and doc/figures/speed_accuracy.png.
# Every FastSim model runs in both variants, classic and calibrated FastSim (--fastsim), each row
# naming its own: the chart does not depend on the parameters' default variant. The plot script
# also prints the rows, auto against the cheapest fixed choice and auto's rule's numbers per variant
# (doc/performance.md#model-auto); the printout goes to doc/data/speed_accuracy_reading.txt.
# The exact reference histories are cached in doc/data/speed_accuracy_reference.csv (15 min
# here on a busy machine; --refresh forces it, and is needed after a change to the exact solver or
# the paper scenes). The real-profile cases (A-2.2's gauge corner and two tread patches, the patch
# as its equivalent ellipse and as its strips, and exact at coarser grids, against exact 40x30)
# add about a minute and write doc/data/speed_accuracy_patches.csv and
# doc/figures/speed_accuracy_patches.png; --parts paper or --parts patches runs one part alone.
# Needs a Release build of speed_accuracy.
# usage: scripts/speed_accuracy.sh [speed_accuracy options, e.g. --models nss:fixed,auto:adaptive]
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
bin="$here/build/devel/lib/wheel_rail_contact/speed_accuracy"
if [ ! -x "$bin" ]; then
  echo "speed_accuracy not built: make -C build speed_accuracy" >&2
  exit 1
fi
start=$(date +%s)
echo "# $(date -u +%FT%TZ) $(nproc) cores; load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
# auto at 10 % and 5 % (drawn) and at the rungs of both its mesh ladders (auto_model.cpp; printed
# in the reading: auto within reach at each rung), so that the ladders can be checked in one run.
"$bin" --out doc/data --tolerances 0.1,0.064,0.05,0.047,0.045,0.043,0.04,0.032 "$@"
echo "# done in $(($(date +%s) - start)) s; load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
/usr/bin/python3 scripts/plot_speed_accuracy.py doc/data/speed_accuracy.csv \
  doc/figures/speed_accuracy.png | tee doc/data/speed_accuracy_reading.txt
