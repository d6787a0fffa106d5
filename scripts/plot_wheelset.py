#!/usr/bin/env python3
"""Prints and plots the closed-loop wheelset demo (scripts/wheelset_demo.sh, doc/wheelset_demo.md).

usage: plot_wheelset.py OUTPUT_DIR PNG MODEL [MODEL ...]
Reads OUTPUT_DIR/wheelset_<model>_summary.csv and wheelset_<model>_hunting.csv (written by
wheelset_sim) for each model; prints the hunting figures and the table of the left wheel's dynamic
creep force per mm of lateral irregularity, then writes PNG: (a) the free decay of the kinematic
oscillation, (b) |Fx| per mm of irregularity against its wavelength, (c) each model against steady.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, png, models = sys.argv[1], sys.argv[2], sys.argv[3:]
summary, hunting = {}, {}
for m in models:
    summary[m] = list(csv.DictReader(open(f"{out}/wheelset_{m}_summary.csv")))
    try:
        hunting[m] = list(csv.DictReader(open(f"{out}/wheelset_{m}_hunting.csv")))
    except FileNotFoundError:
        pass


def rows(m, kind):
    return [r for r in summary[m] if r["kind"] == kind]


for m in models:
    for r in rows(m, "decay"):
        print(f"[wheelset_demo] {r['case']} at {float(r['speed']):g} m/s, {m:7s}: wavelength "
              f"{float(r['wavelength']):.3f} m (Klingel {float(r['klingel_wavelength']):.3f} m), "
              f"{float(r['frequency']):.3f} Hz, damping ratio {float(r['damping_ratio']):.4f}")
cases = [r["case"] for r in rows(models[0], "irregularity")]
if cases:
    speed = float(rows(models[0], "irregularity")[0]["speed"])
    print(f"[wheelset_demo] left wheel's |Fx| per mm of lateral irregularity at {speed:g} m/s [kN/mm]:")
    print("  wavelength [m]  f [Hz]  " + "  ".join(f"{m:>8s}" for m in models) +
          ("".join(f"  {m + '/steady':>14s}" for m in models if m != "steady")
           if "steady" in models else ""))
    for case in cases:
        value = {m: next(float(r["fx_per_m"]) for r in rows(m, "irregularity") if r["case"] == case)
                 for m in models}
        first = next(r for r in rows(models[0], "irregularity") if r["case"] == case)
        line = (f"  {float(first['irregularity_wavelength']):14.3g}  "
                f"{float(first['frequency_forced']):6.1f}  " +
                "  ".join(f"{value[m] * 1e-6:8.3f}" for m in models))
        if "steady" in models:
            line += "".join(f"  {value[m] / value['steady']:14.3f}" for m in models if m != "steady")
        print(line)

# The headline: the 0.2 m irregularity (the rostest's case) and the hunting damping, each model.
if cases and "steady" in models and len(models) > 1:
    pick = "irr_0.2" if "irr_0.2" in cases else cases[0]
    fx = {m: next(float(r["fx_per_m"]) for r in rows(m, "irregularity") if r["case"] == pick)
          for m in models}
    first = next(r for r in rows(models[0], "irregularity") if r["case"] == pick)
    print(f"[wheelset_demo] figure: |Fx| per mm at a {float(first['irregularity_wavelength']):g} m "
          f"irregularity ({float(first['frequency_forced']):g} Hz at {speed:g} m/s): " +
          ", ".join(f"{m} {fx[m] * 1e-6:.2f} kN/mm" +
                    ("" if m == "steady" else f" ({100 * (fx[m] / fx['steady'] - 1):+.1f} %)")
                    for m in models))
    decays = {m: rows(m, "decay") for m in models}
    if all(decays.values()):
        print("[wheelset_demo] figure: hunting damping ratio at "
              f"{float(decays[models[0]][0]['speed']):g} m/s: " +
              ", ".join(f"{m} {float(decays[m][0]['damping_ratio']):.4f}" for m in models))

fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
for m in models:
    if m in hunting:
        h = hunting[m]
        ax[0].plot([float(r["t"]) for r in h], [1e3 * float(r["y"]) for r in h], label=m)
    irr = rows(m, "irregularity")
    lam = [float(r["irregularity_wavelength"]) for r in irr]
    ax[1].plot(lam, [1e-6 * float(r["fx_per_m"]) for r in irr], "o-", label=m)
    if "steady" in models and m != "steady":
        base = {r["case"]: float(r["fx_per_m"]) for r in rows("steady", "irregularity")}
        ax[2].plot(lam, [float(r["fx_per_m"]) / base[r["case"]] for r in irr], "o-", label=m)
decay = rows(models[0], "decay")
ax[0].set_title("free decay of the kinematic oscillation" +
                (f" at {float(decay[0]['speed']):g} m/s" if decay else ""))
ax[0].set_xlabel("t [s]")
ax[0].set_ylabel("lateral displacement y [mm]")
ax[1].set_title("dynamic creep force, left wheel" +
                (f", {speed:g} m/s" if cases else ""))
ax[1].set_xlabel("irregularity wavelength [m]")
ax[1].set_ylabel("|Fx| per mm of lateral irregularity [kN/mm]")
ax[2].set_title("against steady FastSim")
ax[2].set_xlabel("irregularity wavelength [m]")
ax[2].set_ylabel("|Fx| / |Fx| steady [-]")
ax[2].axhline(1.0, color="grey", lw=0.8)
for a in ax[1:]:
    a.set_xscale("log")
for a in ax:
    a.grid(True, alpha=0.3)
    a.legend()
fig.tight_layout()
fig.savefig(png, dpi=110)
