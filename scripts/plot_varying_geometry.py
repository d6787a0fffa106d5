#!/usr/bin/env python3
"""Forces under a changing patch shape (doc/varying_geometry.md) from geometry_accuracy's CSVs.

doc/figures/varying_geometry.png: Fx and Fy against the rolled distance q/a0 for the exact solver
and the FastSim models, left the harmonic a/b at lambda = 10 a0, right the step of a/b from 1.4 to
0.7; a/b on a second axis.
Usage: /usr/bin/python3 scripts/plot_varying_geometry.py [doc/data] [doc/figures/varying_geometry.png]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DATA = sys.argv[1] if len(sys.argv) > 1 else "doc/data"
OUT = sys.argv[2] if len(sys.argv) > 2 else "doc/figures/varying_geometry.png"
STYLE = [("exact", "k", "-", "exact"), ("steady", "tab:green", ":", "steady"),
         ("shen-li_fixed", "tab:blue", "--", "shen-li (fixed)"),
         ("nss_fixed", "tab:red", "-", "nss (fixed)"),
         ("nss_adaptive", "tab:orange", "-.", "nss (adaptive)")]


def read(name):
    with open(f"{DATA}/geometry_{name}.csv") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex="col")
for col, (scene, title) in enumerate([("ab_harmonic_l10", "a/b harmonic 0.7-1.4, lambda = 10 a0"),
                                      ("ab_step", "a/b step 1.4 -> 0.7")]):
    d = read(scene)
    for row, force in enumerate(["fx", "fy"]):
        ax = axes[row][col]
        for key, colour, dash, label in STYLE:
            ax.plot(d["q_over_a0"], d[f"{force}_{key}"], color=colour, linestyle=dash,
                    label=label, linewidth=1.2)
        ax.set_ylabel(f"{force.upper()[0]}{force[1]} [N]")
        twin = ax.twinx()
        twin.plot(d["q_over_a0"], d["a_over_b"], color="0.7", linewidth=0.8)
        twin.set_ylabel("a/b", color="0.5")
        if row == 0:
            ax.set_title(title)
        else:
            ax.set_xlabel("rolled distance q / a0")
axes[0][0].legend(fontsize=8, loc="best")
fig.suptitle("Constant load and area, xi = 0.003, spin 0.5 1/m (paper material, a0 = b0 = 20 mm)")
fig.tight_layout()
fig.savefig(OUT, dpi=110)
print(f"wrote {OUT}")
