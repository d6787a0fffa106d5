#!/usr/bin/env python3
"""Splits each model's error on the varying-load scenes (paper section 4.2) into a static and a
dynamic part (doc/validation.md, "Why nss and shen-li tie under a varying load").

  static  = F_qs,model(Fz(t)) - F_qs,exact(Fz(t))     (the model's steady force at the current load
                                                       against the exact steady force)
  dynamic = (F_model - F_qs,model) - (F_exact - F_qs,exact)

so error = static + dynamic; each is given as RMS and mean over the last period / exact peak force,
as accuracy_report's rms_over_peak. The quasi-static tables F_qs(Fz) are computed once at 33 loads
over [0.75, 1.25] Fz0 with contact_cli and cached in OUT/quasi_static.csv: exact (30x30, the
scenes' grid) from one long step (it restarts from rest 10 nx elements before the step's end: its
steady state), steady FastSim (the adaptive mesh's force at constant load) and nss on the fixed
mesh (sized for 1.25 Fz0) after 400 steps at constant load. The force is linear between the loads.

usage: scripts/split_load_error.py [BUILD_BIN_DIR] [DATA_DIR=doc/data] [OUT=/tmp/split_load]
"""
import bisect
import csv
import math
import os
import subprocess
import sys
from collections import defaultdict

bin_dir = sys.argv[1] if len(sys.argv) > 1 else "build/devel/lib/wheel_rail_contact"
data = sys.argv[2] if len(sys.argv) > 2 else "doc/data"
out = sys.argv[3] if len(sys.argv) > 3 else "/tmp/split_load"
os.makedirs(out, exist_ok=True)
cli = os.path.join(bin_dir, "contact_cli")
common = ["--G", "1e6", "--nu", "0.28", "--mu", "0.4013", "--a0", "0.02", "--b0", "0.02",
          "--fz0", "470.5", "--fz_max", str(1.25 * 470.5)]
xis = [0.002, 0.01, 0.05, 0.1]


def last_fx(rows, *args):
    path = os.path.join(out, "scene.csv")
    with open(path, "w") as f:
        f.write("t,V,xi,eta,phi,fz\n" + "".join(rows))
    r = subprocess.run([cli, "run", "--scenario", path, *args, *common], check=True,
                       capture_output=True, text=True)
    return float(r.stdout.strip().splitlines()[-1].split(",")[1])


table_path = os.path.join(out, "quasi_static.csv")
if not os.path.exists(table_path):
    with open(table_path, "w") as f:
        f.write("xi,fz,exact,steady,nss_fixed\n")
        for xi in xis:
            for k in range(33):
                fz = 470.5 * (0.75 + 0.5 * k / 32)
                one = [f"0,0.25,{xi},0,0,{fz!r}\n", f"4,0.25,{xi},0,0,{fz!r}\n"]
                many = [f"{i * 0.00632!r},0.25,{xi},0,0,{fz!r}\n" for i in range(400)]
                ex = last_fx(one, "--model", "exact", "--nx", "30", "--ny", "30")
                st = last_fx(many, "--model", "steady")
                nf = last_fx(many, "--model", "nss", "--mesh", "fixed")
                f.write(f"{xi},{fz!r},{ex!r},{st!r},{nf!r}\n")
            print(f"quasi-static xi {xi} done", file=sys.stderr)

qs = defaultdict(list)
with open(table_path) as f:
    for r in csv.DictReader(f):
        qs[float(r["xi"])].append((float(r["fz"]), float(r["exact"]), float(r["steady"]),
                                   float(r["nss_fixed"])))


def at(tab, fz, col):
    fzs = [r[0] for r in tab]
    i = min(max(bisect.bisect(fzs, fz) - 1, 0), len(fzs) - 2)
    w = (fz - fzs[i]) / (fzs[i + 1] - fzs[i])
    return tab[i][col] * (1 - w) + tab[i + 1][col] * w


# The quasi-static column of each model: steady FastSim on the patch (adaptive mesh, steady
# model) or on the fixed mesh sized for 1.25 Fz0 (nss and shen-li fixed: the same steady march).
column = {("nss", "adaptive"): 2, ("nss", "fixed"): 3, ("shen-li", "fixed"): 3,
          ("shen-li", "adaptive"): 2, ("steady", "fixed"): 2}
print("| scene | model | total RMS (mean) | static RMS (mean) | dynamic RMS (mean) |")
print("| --- | --- | --- | --- | --- |")
for xi in xis:
    for lam in (5, 15, 40):
        name = f"load_xi{xi:.3f}_l{lam}"
        hist = defaultdict(list)
        with open(f"{data}/scene_{name}.csv") as f:
            for r in csv.DictReader(f):
                hist[(r["model"], r["mesh"])].append((float(r["t"]), float(r["fz"]),
                                                      float(r["fx"])))
        ex = hist[("exact", "grid")]
        period = lam * 0.02 / 0.25
        idx = [i for i, r in enumerate(ex) if r[0] > ex[-1][0] - period * (1 + 1e-9)]
        peak = max(abs(ex[i][2]) for i in idx)
        tab = qs[xi]

        def stats(v):
            return (100 * math.sqrt(sum(x * x for x in v) / len(v)) / peak,
                    100 * sum(v) / len(v) / peak)
        for key, col in column.items():
            m = hist[key]
            if not m:  # a table from before shen-li adaptive was reported
                continue
            total = [m[i][2] - ex[i][2] for i in idx]
            static = [at(tab, ex[i][1], col) - at(tab, ex[i][1], 1) for i in idx]
            dynamic = [t - s for t, s in zip(total, static)]
            cells = " | ".join("%.2f %% (%+.2f)" % stats(v) for v in (total, static, dynamic))
            print(f"| {name} | {key[0]} {key[1]} | {cells} |")
