#!/usr/bin/env bash
# The stability map (issue 6): builds stability_map if needed, sweeps every model over lambda/a x
# V dt/dx and four inputs (src/tools/stability_map.cpp), writes doc/data/stability_map.csv and
# plots doc/figures/stability_map.png. About 1 CPU-minute; extra options go to stability_map
# (e.g. --lambdas 6 --ratios 4 --no-exact for a quick look).
# usage: scripts/stability_map.sh [stability_map options...]
set -eo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
export PATH="/usr/bin:$PATH"
if [ ! -f build/Makefile ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3
fi
make -C build -j2 stability_map > /dev/null
mkdir -p doc/data
time build/devel/lib/wheel_rail_contact/stability_map --out doc/data "$@"
/usr/bin/python3 scripts/plot_stability.py doc/data/stability_map.csv doc/figures/stability_map.png
