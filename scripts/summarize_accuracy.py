#!/usr/bin/env python3
"""Prints the accuracy tables of doc/validation.md from accuracy_report's CSVs (doc/data)."""
import csv
import os
import sys
from collections import defaultdict

data = sys.argv[1] if len(sys.argv) > 1 else "doc/data"

curves = defaultdict(list)
with open(f"{data}/freq_errors.csv") as f:
    for r in csv.DictReader(f):
        curves[(r["a_over_b"], r["kind"])].append(
            (float(r["lambda_over_a"]), float(r["err_nss"]), float(r["err_shenli"]),
             float(r["err_steady"])))
print("| a/b | kind | nss max, λ/a ≥ 2 | nss within 0.05 from λ/a | shen-li max, λ/a ≥ 2 | steady max, λ/a ≥ 2 |")
print("| --- | --- | --- | --- | --- | --- |")
for (ab, kind), pts in sorted(curves.items(), key=lambda kv: (float(kv[0][0]), kv[0][1])):
    above = [p for p in pts if p[0] >= 2.0 - 1e-9]
    good_from = min((p[0] for p in pts if all(q[1] <= 0.05 for q in pts if q[0] >= p[0])),
                    default=float("nan"))
    print(f"| {ab} | C{kind} | {max(p[1] for p in above):.3f} | {good_from:.2f} | "
          f"{max(p[2] for p in above):.3f} | {max(p[3] for p in above):.3f} |")

if not os.path.exists(f"{data}/scenes.csv"):  # a --parts freq run
    sys.exit(0)
print()
print("| scene | nss fixed | nss adaptive | shen-li fixed | shen-li adaptive | steady |"
      " ΔFx/(μΔFz) exact / nss adaptive |")
print("| --- | --- | --- | --- | --- | --- | --- |")
scenes = defaultdict(dict)
order = []
with open(f"{data}/scenes.csv") as f:
    for r in csv.DictReader(f):
        if r["scene"] not in scenes:
            order.append(r["scene"])
        scenes[r["scene"]][(r["model"], r["mesh"])] = r
for s in order:
    m = scenes[s]
    cell = lambda k: f"{100 * float(m[k]['rms_over_peak']):.1f} %" if k in m else "-"
    ratio = ""
    if s.startswith("load"):
        r = m[("nss", "adaptive")]
        ratio = f"{float(r['exact_dfx_over_mu_dfz']):.3f} / {float(r['dfx_over_mu_dfz']):.3f}"
    print(f"| {s} | {cell(('nss', 'fixed'))} | {cell(('nss', 'adaptive'))} | "
          f"{cell(('shen-li', 'fixed'))} | {cell(('shen-li', 'adaptive'))} | "
          f"{cell(('steady', 'fixed'))} | {ratio} |")
