#!/usr/bin/env python3
"""Plots force_recorder CSV files: creep force magnitude and angle over time, one PNG.

usage: plot_forces.py OUT.png FORCES.csv [FORCES.csv ...]
Each CSV (written by force_recorder) has the columns t,fx,fy,...,force_magnitude,force_angle_deg.
No ROS import: runs anywhere python3-matplotlib is installed.
"""
import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f)]
    col = lambda k: [float(r[k]) for r in rows]  # noqa: E731
    return col("t"), col("force_magnitude"), col("force_angle_deg"), col("fz")


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out, files = argv[1], argv[2:]
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, sharex=True, figsize=(9, 8))
    for path in files:
        name = pathlib.Path(path).stem.replace("_forces", "")
        t, mag, ang, fz = read(path)
        ax1.plot(t, mag, label=name)
        ax2.plot(t, ang, label=name)
        ax3.plot(t, fz, label=name)
    ax1.set_ylabel("|F| = sqrt(Fx² + Fy²) [N]")
    ax2.set_ylabel("angle atan2(Fy, Fx) [deg]")
    ax3.set_ylabel("Fz [N]")
    ax3.set_xlabel("t [s] (creepage stamps, from the first message)")
    for ax in (ax1, ax2, ax3):
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    fig.suptitle("wheel_rail_contact: creep forces computed by contact_node")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
