#!/usr/bin/env python3
"""Prints and plots the closed-loop wheelset demo on real profiles (profile_wheelset_sim;
scripts/wheelset_demo.sh, doc/wheelset_demo.md).

usage: plot_profile_wheelset.py OUTPUT_DIR PNG
Reads OUTPUT_DIR/profile_summary.csv, profile_kinematics.csv, profile_geometry.csv and
profile_<model>_<case>.csv (hunting, impact) for the models in the summary; prints the figures and
writes PNG: (a) the profiles' rolling-radius difference and equivalent conicity, (b) hunting,
(c) where the left wheel touches its rail while hunting, (d) the impact, (e) the contact points'
path across the rail during the impact, (f) the same on the rail's profile.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, png = sys.argv[1], sys.argv[2]
summary = list(csv.DictReader(open(f"{out}/profile_summary.csv")))
models = list(dict.fromkeys(r["model"] for r in summary))
kin = list(csv.DictReader(open(f"{out}/profile_kinematics.csv")))
geo = list(csv.DictReader(open(f"{out}/profile_geometry.csv")))


def run(model, case):
    try:
        return list(csv.DictReader(open(f"{out}/profile_{model}_{case}.csv")))
    except FileNotFoundError:
        return []


def col(rows, key, scale=1.0):
    return [scale * float(r[key]) if r[key] != "" else float("nan") for r in rows]


def fig(r, key, fmt="{:.3g}", scale=1.0):
    return fmt.format(scale * float(r[key])) if r[key] != "" else "-"


for r in summary:
    print(f"[wheelset_demo] profiles, {r['model']:6s} {r['case']:8s} at {float(r['speed']):g} m/s: "
          f"amplitude {fig(r, 'amplitude', '{:.2f}', 1e3)} mm, wavelength "
          f"{fig(r, 'wavelength', '{:.2f}')} m (Klingel {fig(r, 'klingel_wavelength', '{:.2f}')} m "
          f"with lambda_e {fig(r, 'equivalent_conicity', '{:.3f}')}), max |y| "
          f"{fig(r, 'max_abs_y', '{:.2f}', 1e3)} mm, flange steps {r['flange_steps']}, two-point "
          f"steps {r['two_point_steps']}, refused patches' steps {r['rejected_steps']}, max wheel "
          f"|Fy| {fig(r, 'max_wheel_fy', '{:.0f}', 1e-3)} kN, {float(r['us_per_step']):.0f} us/step")

zone_colour = {"tread": "tab:blue", "gauge_corner": "tab:orange", "flange": "tab:red"}
f, ax = plt.subplots(2, 3, figsize=(15, 8.4))

# (a) the profiles' rolling-radius difference and equivalent conicity
a = ax[0][0]
a.plot(col(kin, "y", 1e3), col(kin, "radius_difference", 1e3), color="k")
a.set_xlabel("lateral displacement y [mm]")
a.set_ylabel("rolling-radius difference r_L - r_R [mm]")
a.set_title("S1002 on UIC60 1:40: rigid kinematics")
a2 = a.twinx()
ka = [r for r in kin if r["amplitude"] != "" and float(r["amplitude"]) >= 2e-4]
a2.plot(col(ka, "amplitude", 1e3), col(ka, "equivalent_conicity"), color="tab:green")
a2.set_ylabel("equivalent conicity at amplitude A = y [-]", color="tab:green")
a2.set_ylim(0, 1.2)
for r in summary:
    if r["case"] == "hunting" and r["amplitude"] != "":
        a2.plot([1e3 * float(r["amplitude"])], [float(r["equivalent_conicity"])], "o",
                color="tab:green")

# (b) hunting, (d) impact: lateral displacement of each model
for panel, case in ((ax[0][1], "hunting"), (ax[1][0], "impact")):
    for m in models:
        rows = run(m, case)
        if rows:
            panel.plot(col(rows, "t"), col(rows, "y", 1e3), label=m, lw=1)
    panel.set_xlabel("t [s]")
    panel.set_ylabel("lateral displacement y [mm]")
    s = [r for r in summary if r["case"] == case]
    if case == "hunting" and s:
        panel.set_title("hunting at {} m/s: ".format(s[0]["speed"]) + ", ".join(
            f"{r['model']} {fig(r, 'wavelength', '{:.2f}')} m (Klingel "
            f"{fig(r, 'klingel_wavelength', '{:.2f}')} m)" for r in s), fontsize=9)
    elif s:
        panel.set_title(f"lateral impact at {s[0]['speed']} m/s: flange contact", fontsize=10)
    panel.legend(fontsize=8)
imp = run(models[-1], "impact")
if imp:
    d2 = ax[1][0].twinx()
    d2.plot(col(imp, "t"), col(imp, "fy_left", 1e-3), color="tab:red", lw=0.8)
    d2.set_ylabel(f"left wheel's lateral force, {models[-1]} [kN]", color="tab:red")


def points(rows, wheel):
    """(t, rail_y [mm], zone) of every patch of one wheel."""
    pts = []
    for r in rows:
        for k in (1, 2):
            z = r[f"zone{k}_{wheel}"]
            if z:
                pts.append((float(r["t"]), 1e3 * float(r[f"rail_y{k}_{wheel}"]), z,
                            r[f"patches_{wheel}"] == "2"))
    return pts


# (c) hunting, (e) impact: where the left wheel touches its rail over time
for panel, rows, title in ((ax[0][2], run(models[-1], "hunting"), "hunting"),
                           (ax[1][1], imp, "impact")):
    pts = points(rows, "left")
    for z, c in zone_colour.items():
        one = [p for p in pts if p[2] == z and not p[3]]
        two = [p for p in pts if p[2] == z and p[3]]
        panel.plot([p[0] for p in one], [p[1] for p in one], ".", ms=2, color=c, label=z)
        panel.plot([p[0] for p in two], [p[1] for p in two], "x", ms=4, color=c,
                   label=f"{z}, two patches on the wheel" if two else None)
    panel.set_xlabel("t [s]")
    panel.set_ylabel("contact point on the left rail, y of the rail file [mm]")
    panel.set_title(f"{title}, {models[-1]}: the contact point's path across the rail", fontsize=9)
    panel.legend(fontsize=7, markerscale=2)

# (f) the impact's contact points on the rail's profile (the file's z points down)
a = ax[1][2]
rail = [(1e3 * float(r["y_file"]), -1e3 * float(r["z_file"])) for r in geo if r["profile"] == "rail"]
head = [p for p in rail if p[1] > -25.0]
a.plot([p[0] for p in head], [p[1] for p in head], color="grey", lw=1.5)


def height(y):
    near = [p for p in head if abs(p[0] - y) < 0.6]
    return max(p[1] for p in near) if near else float("nan")


for z, c in zone_colour.items():
    pts = sorted({round(p[1], 1) for p in points(imp, "left") if p[2] == z})
    a.plot(pts, [height(y) for y in pts], "o", ms=4, color=c, label=z)
a.set_aspect("equal")
a.set_xlabel("rail profile: y of the file [mm] (gauge side to the left)")
a.set_ylabel("height [mm]")
a.set_title(f"impact, {models[-1]}: the left wheel's contact points on the rail", fontsize=9)
a.legend(fontsize=8)
for row in ax:
    for p in row:
        p.grid(True, alpha=0.3)
f.tight_layout()
f.savefig(png, dpi=80)
