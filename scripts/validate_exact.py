#!/usr/bin/env python3
"""Fine-grid validation of the exact half-space reference against CONTACT (test/data/contact_reference/).

Runs the built contact_cli (freq --model exact) and prints, per row, our value and CONTACT's:
  1. contact_c11_ab1.csv: |C/C_steady| and phase of C11(lambda/a) at a/b = 1 on 30x30 and 40x40;
  2. contact_steady_coefficients.csv: C11, C22, C23 at a/b = 0.2 .. 5 on 50x50 (and Kalker's table).
Usage: python3 scripts/validate_exact.py [path/to/contact_cli]   (about 3 minutes on one core)
"""
import csv
import math
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    root, "build/devel/lib/wheel_rail_contact/contact_cli")
ref = os.path.join(root, "test", "data", "contact_reference")


def freq(kind, ab, lambdas, m):
    out = subprocess.run([cli, "freq", "--model", "exact", "--kind", kind, "--ab", str(ab),
                          "--lambda-over-a", ",".join(str(x) for x in lambdas),
                          "--nx", str(m), "--ny", str(m)],
                         check=True, capture_output=True, text=True).stdout
    return list(csv.DictReader(out.splitlines()))


rows = list(csv.DictReader(open(os.path.join(ref, "contact_c11_ab1.csv"))))
worst_ratio = worst_phase = 0.0
print("C11(lambda/a), a/b = 1: lambda/a, grid, |C/Cs| ours, CONTACT, phase ours, CONTACT [deg]")
for m in sorted({int(r["grid_mx"]) for r in rows}):
    sub = [r for r in rows if int(r["grid_mx"]) == m]
    ours = freq("xi", 1, [float(r["lambda_over_a"]) for r in sub], m)
    for r, o in zip(sub, ours):
        ratio = float(o["magnitude"]) / float(o["c_steady"])
        dr = ratio - float(r["magnitude_over_steady"])
        dp = float(o["phase_deg"]) - float(r["phase_deg"])
        worst_ratio, worst_phase = max(worst_ratio, abs(dr)), max(worst_phase, abs(dp))
        print(f"{r['lambda_over_a']:>5} {m}x{m} {ratio:.6f} {float(r['magnitude_over_steady']):.6f}"
              f" {float(o['phase_deg']):9.4f} {float(r['phase_deg']):9.4f}")
print(f"max |ratio error| = {worst_ratio:.1e}, max |phase error| = {worst_phase:.4f} deg\n")

print("steady, 50x50: a/b, coefficient, ours, CONTACT, error vs CONTACT, error vs Kalker's table")
kinds = {"C11": "xi", "C22": "eta", "C23": "phi"}
for r in csv.DictReader(open(os.path.join(ref, "contact_steady_coefficients.csv"))):
    ours = float(freq(kinds[r["coef"]], r["ab_ratio"], [100], int(r["grid_mx"]))[0]["c_steady"])
    c, k = float(r["coef_value"]), float(r["coef_kalker_table"])
    print(f"{r['ab_ratio']:>4} {r['coef']} {ours:.5f} {c:.5f} {100 * (ours / c - 1):+.3f} %"
          f" {100 * (ours / k - 1):+.3f} %")
