#!/usr/bin/env python3
"""Writes the shipped demo scenes (scenario CSV: t,V,xi,eta,phi,fz) from the paper's cases.

Guiral, Alonso, Baeza, Gimenez 2013, combined case eq. 17 and the varying-load case of section 4.2,
on a circular patch a = b = 20 mm at Fz0 = 470.5 N, G = 1 MPa, nu = 0.28, mu = 0.4013,
V = 25 mm/s (see config/paper.yaml). lambda = 10 a. One row per step of V dt = 2a/20 (one
FastSim element at nx = 20), two wavelengths.
Spin: the paper gives phi = 0.001 without units; we read it in CONTACT's unit 1/mm, i.e.
phi = 1 1/m (choice, the same as src/validation/paper_scenes.cpp and doc/validation.md).
usage: make_scenes.py [OUT_DIR]   (default: scenes/)
"""
import math
import pathlib
import sys

A = 0.02  # m
FZ0 = 470.5  # N
V = 0.025  # m/s
LAM = 10 * A
DT = (2 * A / 20) / V  # s, V dt = one element at nx = 20
ROWS = int(round(2 * LAM / (V * DT))) + 1
PHI = 1.0  # 1/m: the paper's 0.001 read in 1/mm


def write(path, header, rows):
    with open(path, "w") as f:
        f.write(header)
        f.write("t,V,xi,eta,phi,fz\n")
        for r in rows:
            f.write(",".join(f"{v:.12g}" for v in r) + "\n")


def main(out):
    out = pathlib.Path(out)
    combined, varying = [], []
    for k in range(ROWS):
        t = k * DT
        q = V * t
        c = math.cos(2 * math.pi * q / LAM)
        xi = 0.052 * c
        eta = 0.052 * math.cos(2 * math.pi * (q - LAM / 2) / LAM)
        combined.append((t, V, xi, eta, PHI, FZ0))
        fz = FZ0 * (1 + 0.25 * math.sin(2 * math.pi * q / LAM))
        varying.append((t, V, 0.052, 0.0, 0.0, fz))
    note = "# written by scripts/make_scenes.py; parameters in config/paper.yaml\n"
    write(out / "paper_combined.csv",
          "# Combined creepages (paper eq. 17): xi = 0.052 cos(2 pi q/lambda),\n"
          "# eta = 0.052 cos(2 pi (q - lambda/2)/lambda), phi = 0.001 /mm = 1 1/m, lambda/a = 10\n" + note,
          combined)
    write(out / "paper_varying_load.csv",
          "# Varying load (paper section 4.2): Fz = Fz0 (1 + 0.25 sin(2 pi q/lambda)), xi = 0.052,\n"
          "# lambda/a = 10\n" + note, varying)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent / "scenes")
