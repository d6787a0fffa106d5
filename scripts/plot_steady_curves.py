#!/usr/bin/env python3
"""Steady creep curves exact / classic FastSim / calibrated FastSim (doc/calibrated_fastsim.md).

Reads doc/data/steady_curves.csv (written by identify_calibration --curves) and writes
doc/figures/steady_curves_ab<R>.png, one figure per a/b: one column per ray (creepage kind or
combination), forces over mu fz on top, the spin moment over mu fz sqrt(ab) below.
usage: scripts/plot_steady_curves.py [--data doc/data/steady_curves.csv] [--out doc/figures]
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RAYS = [("11", "xi only"), ("22", "eta only"), ("23", "phi only"), ("xe", "xi = eta"),
        ("xep", "xi = eta = phi"), ("opp", "xi, -eta, phi"), ("spin", "0.3 xi, -0.3 eta, phi"),
        ("h1", "xi, 0.5 eta, 0.8 phi"), ("h2", "0.4 xi, eta, -0.7 phi"), ("h3", "xi, -eta, 0.2 phi"), ("h4", "0.5 xi, eta, 0.25 phi"),
        ("h5", "xi, 0.6 eta, -0.5 phi"), ("h6", "0.8 xi, 0.8 eta, 0.55 phi"),
        ("h7", "0.6 xi, eta, -0.33 phi"), ("h8", "xi, 0.4 eta, 0.3 phi")]
VARIANTS = [("exact", "k-", "exact"), ("classic", "C0--", "classic"),
            ("calibrated", "C3-", "calibrated")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", default="doc/data/steady_curves.csv")
    ap.add_argument("--out", default="doc/figures")
    ap.add_argument("--ab", default="0.2,1,5")
    args = ap.parse_args()
    rows = defaultdict(list)
    with open(args.data) as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            rows[(float(r["a_over_b"]), r["ray"])].append(r)
    os.makedirs(args.out, exist_ok=True)
    for ab in (float(x) for x in args.ab.split(",")):
        fig, ax = plt.subplots(2, len(RAYS), figsize=(3.0 * len(RAYS), 5.5), sharex="col")
        for c, (ray, title) in enumerate(RAYS):
            pts = sorted(rows[(ab, ray)], key=lambda r: float(r["epsilon"]))
            if not pts:
                continue
            e = [0.0] + [float(r["epsilon"]) for r in pts]
            for key, style, label in VARIANTS:
                for comp, marker in (("fx", ""), ("fy", "")):
                    v = [0.0] + [float(r[f"{comp}_{key}"]) for r in pts]
                    if max(abs(x) for x in v) < 1e-3:
                        continue
                    ax[0, c].plot(e, v, style, marker=marker,
                                  label=f"{label} {comp}" if c == 0 or ray == "xe" else None,
                                  lw=1.2 if comp == "fx" else 2.0)
                mz = [0.0] + [float(r[f"mz_{key}"]) for r in pts]
                ax[1, c].plot(e, mz, style, label=label)
            ax[0, c].set_title(title, fontsize=9)
            ax[1, c].set_xlabel("normalised creepage e")
            ax[0, c].set_xscale("symlog", linthresh=1.0)
            ax[0, c].grid(alpha=0.3)
            ax[1, c].grid(alpha=0.3)
        ax[0, 0].set_ylabel("F / (mu Fz)")
        ax[1, 0].set_ylabel("Mz / (mu Fz sqrt(ab))")
        ax[0, 0].legend(fontsize=6)
        ax[0, 3].legend(fontsize=6)
        ax[1, 0].legend(fontsize=7)
        fig.suptitle(f"Steady creep curves at a/b = {ab:g}: exact (20x20) / classic / calibrated "
                     f"FastSim (20x20); thin fx, thick fy", fontsize=10)
        fig.tight_layout()
        path = os.path.join(args.out, f"steady_curves_ab{ab:g}.png")
        fig.savefig(path, dpi=90)
        print("wrote", path)


if __name__ == "__main__":
    main()
