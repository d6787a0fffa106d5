#!/usr/bin/env python3
"""Held-out non-steady cases for calibrated FastSim (doc/calibrated_fastsim.md#non-steady-accuracy).

Harmonic creepages on the paper's contact (config/paper.yaml: a = b = 20 mm, G = 1 MPa, mu = 0.4013,
Fz = 470.5 N), V = 25 mm/s: xi = xi0 + A_xi cos(2 pi q / lambda), eta = -A_eta cos(2 pi q / lambda),
phi constant or phi_amp cos(2 pi q / lambda); one row per exact element length (2.2 a / 40), three
periods (four at lambda/a = 3). The exact histories (contact_cli --model exact, 40x40) are solved
once into DIR and reused; each model is then run and its error taken over the last period as
accuracy_report does: RMS |F - F_exact| / peak |F_exact| (F = (Fx, Fy)), and RMS |Mz - Mz_exact| /
peak |Mz_exact|.

usage: scripts/calibrated_heldout.py DIR [CLI ...]   (CLI: contact_cli binaries to compare, each run
       with --fastsim classic and calibrated; default build/devel/lib/wheel_rail_contact/contact_cli)
Writes the table as CSV to stdout. The exact runs take about a minute each on a 2-core machine.
"""
import math
import os
import subprocess
import sys

import numpy as np

A, V, GRID = 0.02, 0.025, 40
# name, xi0, A_xi, A_eta, phi (constant), phi amplitude (harmonic), lambda/a
CASES = [
    ("l3", 0, 0.052, 0.052, 1, 0, 3),
    ("l5", 0, 0.052, 0.052, 1, 0, 5),
    ("l20", 0, 0.052, 0.052, 1, 0, 20),
    ("lin", 0, 0.0052, 0.0052, 1, 0, 10),
    ("lin3", 0, 0.0052, 0.0052, 1, 0, 3),
    ("a26", 0, 0.026, 0.026, 1, 0, 10),
    ("a08", 0, 0.08, 0.08, 1, 0, 10),
    ("sp2", 0, 0.052, 0.052, 2, 0, 10),
    ("mix", 0.03, 0.02, 0.1, 0.5, 0, 15),
    ("xi", 0, 0.04, 0, 0, 0, 10),
    ("xi5", 0, 0.052, 0, 0, 0, 5),
    ("ns5", 0, 0.052, 0.052, 0, 0, 5),
    ("lphi5", 0, 0, 0, 0, 0.01, 5),
    ("lphi20", 0, 0, 0, 0, 0.01, 20),
    ("phi", 0, 0, 0, 0, 3, 10),
]
HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONFIG = os.path.join(HERE, "config", "paper.yaml")


def write_scene(path, xi0, axi, aeta, phi, aphi, lam):
    step, lamb = 2.2 * A / GRID, lam * A
    n = int(round((4 if lam < 5 else 3) * lamb / step))
    with open(path, "w") as f:
        f.write("t,V,xi,eta,phi,fz\n")
        for k in range(n + 1):
            q = k * step
            c = math.cos(2 * math.pi * q / lamb)
            f.write("%.17g,%.17g,%.17g,%.17g,%.17g,470.5\n" %
                    (q / V, V, xi0 + axi * c, -aeta * c, phi + aphi * c))


def run(cli, scene, *args):
    out = subprocess.run([cli, "run", "--scenario", scene, "--config", CONFIG, "--fz_max", "470.5"] +
                         list(args), capture_output=True, text=True, check=True).stdout
    rows = [line.split(",")[:4] for line in out.strip().split("\n")[1:]]
    return np.array([[float(x) for x in r] for r in rows])  # t, fx, fy, mz


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    clis = sys.argv[2:] or [os.path.join(HERE, "build/devel/lib/wheel_rail_contact/contact_cli")]
    os.makedirs(folder, exist_ok=True)
    cols = ["%s_%d_%s" % (q, i, v) for i in range(len(clis)) for q in ("classic", "calibrated")
            for v in ("f", "mz")]
    print("case,xi_mean,xi_amp,eta_amp,phi,phi_amp,lambda_over_a," + ",".join(cols))
    for name, xi0, axi, aeta, phi, aphi, lam in CASES:
        scene = os.path.join(folder, name + ".csv")
        write_scene(scene, xi0, axi, aeta, phi, aphi, lam)
        exact_path = os.path.join(folder, name + ".exact.npy")
        if not os.path.exists(exact_path):
            np.save(exact_path, run(clis[0], scene, "--model", "exact", "--nx", str(GRID),
                                    "--ny", str(GRID)))
        ex = np.load(exact_path)
        t = ex[:, 0]
        last = t > t[-1] - lam * A / V * (1 + 1e-9)
        peak = np.max(np.hypot(ex[last, 1], ex[last, 2]))
        mz_peak = np.max(np.abs(ex[last, 3]))
        errs = []
        for cli in clis:
            for fastsim in ("classic", "calibrated"):
                m = run(cli, scene, "--model", "nss", "--fastsim", fastsim, "--mesh", "fixed")
                d = m[last] - ex[last]
                errs.append(np.sqrt(np.mean(d[:, 1] ** 2 + d[:, 2] ** 2)) / peak)
                errs.append(np.sqrt(np.mean(d[:, 3] ** 2)) / mz_peak)
        print("%s,%g,%g,%g,%g,%g,%g," % (name, xi0, axi, aeta, phi, aphi, lam) +
              ",".join("%.4f" % e for e in errs))


if __name__ == "__main__":
    main()
