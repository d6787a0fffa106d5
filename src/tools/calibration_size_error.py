#!/usr/bin/env python3
"""What a smaller calibration table would cost: data size against worst steady error.

Makes doc/figures/calibration_size_error.png and doc/data/calibration_size_error.csv
(doc/calibration_data.md). Each representation of the calibrated FastSim's table is evaluated by
identify_calibration against the committed exact curves (doc/data/steady_exact_curves.csv) on the
FastSim mesh 20x20 (the default): the worst force error max(|dFx|, |dFy|) / (mu fz) and the worst
moment error |dMz| / peak |Mz| over every ray (single creepages, the combined and held-out rays)
and a/b 0.2-5. Sizes are those of the five-mesh table stored that way.

Representations:
  - the shipped table (int32 millionths), and the same compressed with xz (lossless);
  - the shipped values quantised: ln value in int16 and int8 steps per kind, float16;
  - re-identified on coarser grids (identify_calibration --nx 20 with fewer epsilon knots, spin
    shares or xi shares), and on the shipped grid itself for reference.

Usage (from the repository root, after building identify_calibration):
  python3 src/tools/calibration_size_error.py [--build build] [--threads N]
It takes some 5 minutes on 2 cores (the re-identifications).
"""
import argparse
import csv
import lzma
import math
import os
import re
import struct
import subprocess
import sys
import tempfile

MESHES = 5  # the shipped table's meshes (sizes are of the five-mesh product)
NX = 20
# The shipped grids (src/core/calibration/calibration_schema.hpp).
KNOTS = [0, 0.1, 0.2, 0.35, 0.5, 0.6, 0.75, 0.9, 1, 1.25, 1.5, 2, 3, 4.5, 7, 10, 15]
CORR_KNOTS = [0, 0.1, 0.2, 0.35, 0.5, 0.6, 0.75, 0.9, 1, 1.25, 1.5, 1.65, 1.85, 2, 2.25, 3,
              3.75, 4.5, 5.5, 7, 10, 15]
SPIN_SHARES = [0.03, 0.045, 0.06, 0.1, 0.175, 0.25, 0.375, 0.5, 0.625, 0.75, 0.825, 0.9, 0.95]
XI_SHARES = [0, 0.125, 0.25, 0.375, 0.5, 0.75, 0.875, 0.9375, 1]


def every_other(values):
    """Every other value, the last kept."""
    out = values[::2]
    return out if out[-1] == values[-1] else out + [values[-1]]


def grid_arg(values):
    return ",".join(f"{v:g}" for v in values)


def run(tool, args):
    return subprocess.run([tool] + args, check=True, capture_output=True, text=True).stdout


def evaluate(tool, table):
    """Worst force and moment errors of `table` at NX (identify_calibration's evaluation)."""
    out = run(tool, ["--nx", str(NX), "--table", table])
    force = moment = 0.0
    for line in out.splitlines():
        f = line.split()
        if len(f) == 6 and re.match(r"^[0-9.]+$", f[0]):
            force = max(force, float(f[3]))
            if f[5] != "-":
                moment = max(moment, float(f[5]))
    return force, moment


def header_size(path):
    with open(path, "rb") as b:
        data = b.read(20)
    schema = int.from_bytes(data[16:20], "little")
    return 8 + 4 + 4 + 4 + schema + 4


def five_mesh_size(path):
    """A one-mesh table's binary size as the five-mesh table's (header once, five blocks)."""
    h = header_size(path)  # up to the mesh count; then per mesh a directory entry and a block
    return h + MESHES * (os.path.getsize(path) - h)


def quantised(tool, shipped, how, folder):
    """The shipped mesh NX with every value stored `how`, as a table file; its size if stored so."""
    dump = run(tool, ["--dump", str(NX), "--table", shipped]).splitlines()
    rows = list(csv.reader(dump))
    head, body = rows[0], rows[1:]
    kinds = {}
    for r in body:
        kinds.setdefault(r[1], []).append(float(r[3]))
    ratio = {k: all(v > 0 for v in vals) for k, vals in kinds.items()}  # ratios: their ln
    bits = {"int16": 16, "int8": 8}.get(how)
    scale = {}
    for k, vals in kinds.items():
        x = [math.log(v) if ratio[k] else v for v in vals]
        lo, hi = min(x), max(x)
        scale[k] = (lo, (hi - lo) / (2 ** bits - 1) if bits and hi > lo else 0.0)
    for r in body:
        v = float(r[3])
        if how == "float16":
            q = struct.unpack("e", struct.pack("e", v))[0]  # IEEE half precision
        else:
            x = math.log(v) if ratio[r[1]] else v
            lo, step = scale[r[1]]
            x = lo + round((x - lo) / step) * step if step > 0 else x
            q = math.exp(x) if ratio[r[1]] else x
        if r[2] == "0" and r[1] in ("xi_ratio", "eta_ratio", "spin_ratio", "eta_ratio_no_spin") \
                or (r[2] == "0" and r[1].endswith("_multiplier")):
            q = 1.0  # linear theory's 1, kept exactly (a reader requires it)
        if ratio[r[1]]:
            q = max(q, 1e-6)
        r[3] = f"{q:.6f}"
    text = os.path.join(folder, f"{how}.csv")
    with open(text, "w", newline="") as out:
        w = csv.writer(out, lineterminator="\n")
        w.writerow(head)
        w.writerows(body)
    table = os.path.join(folder, f"{how}.bin")
    run(tool, ["--convert", text, "--out", table])
    per_value = {"float16": 2, "int16": 2, "int8": 1}[how]
    values = len(body) * MESHES
    return table, header_size(shipped) + 16 * MESHES + values * per_value


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--out", default="doc/figures/calibration_size_error.png")
    ap.add_argument("--csv", default="doc/data/calibration_size_error.csv")
    ap.add_argument("--plot-only", action="store_true", help="plot --csv as it is (no runs)")
    a = ap.parse_args()
    if a.plot_only:
        with open(a.csv) as f:
            results = [(r["representation"], r["group"], int(r["bytes"]),
                        float(r["worst_force_error"]), float(r["worst_moment_error"]))
                       for r in csv.DictReader(f)]
        plot(results, a.out)
        return
    tool = os.path.join(a.build, "devel/lib/wheel_rail_contact/identify_calibration")
    shipped = "config/calibration.bin"
    if not os.path.exists(tool) or not os.path.exists(shipped):
        sys.exit(f"run from the repository root after building {tool}")
    results = []  # (label, group, size, force, moment)
    with tempfile.TemporaryDirectory() as folder:
        force, moment = evaluate(tool, shipped)
        size = os.path.getsize(shipped)
        results.append(("shipped: int32 millionths", "shipped", size, force, moment))
        with open(shipped, "rb") as b:
            xz = len(lzma.compress(b.read(), preset=9))
        results.append(("shipped, xz-compressed", "shipped", xz, force, moment))
        for how in ("float16", "int16", "int8"):
            table, qsize = quantised(tool, shipped, how, folder)
            label = {"float16": "float16 values", "int16": "int16 ln values",
                     "int8": "int8 ln values"}[how]
            results.append((label, "quantised", qsize) + evaluate(tool, table))
        grids = [
            ("re-identified, shipped grid", []),
            ("every other correction knot", ["--correction-knots", grid_arg(every_other(CORR_KNOTS))]),
            ("every other single knot", ["--knots", grid_arg(every_other(KNOTS))]),
            ("7 of 13 spin shares", ["--spin-shares", grid_arg(SPIN_SHARES[::2])]),
            ("5 of 9 xi shares", ["--xi-shares", grid_arg(every_other(XI_SHARES))]),
            ("all four halved", ["--correction-knots", grid_arg(every_other(CORR_KNOTS)),
                                 "--knots", grid_arg(every_other(KNOTS)),
                                 "--spin-shares", grid_arg(SPIN_SHARES[::2]),
                                 "--xi-shares", grid_arg(every_other(XI_SHARES))]),
        ]
        for i, (label, options) in enumerate(grids):
            table = os.path.join(folder, f"grid{i}.bin")
            print(f"identifying: {label}", flush=True)
            run(tool, ["--nx", str(NX), "--threads", str(a.threads), "--out", table] + options)
            results.append((label, "re-identified", five_mesh_size(table)) + evaluate(tool, table))
    with open(a.csv, "w", newline="") as out:
        w = csv.writer(out, lineterminator="\n")
        w.writerow(["representation", "group", "bytes", "worst_force_error", "worst_moment_error"])
        for r in results:
            w.writerow([r[0], r[1], r[2], f"{r[3]:.4f}", f"{r[4]:.4f}"])
    plot(results, a.out)
    for r in results:
        print(f"{r[0]:32s} {r[2] / 1e6:6.2f} MB  force {r[3]:.4f}  moment {r[4]:.4f}")


def plot(results, path):
    """The figure: size against the worst force and moment errors, one point per representation."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.6))
    style = {"shipped": ("o", "C0"), "quantised": ("s", "C1"), "re-identified": ("^", "C2")}
    for ax, col, name in ((axes[0], 3, "worst force error  max(|dFx|, |dFy|) / (mu Fz)"),
                          (axes[1], 4, "worst moment error  |dMz| / peak |Mz|")):
        for group, (marker, colour) in style.items():
            pts = [(i, r) for i, r in enumerate(results) if r[1] == group]
            ax.scatter([r[2] / 1e6 for _, r in pts], [r[col] for _, r in pts], marker=marker,
                       color=colour, label=group, zorder=3)
            for i, r in pts:  # numbered: the key below the plots names them
                ax.annotate(str(i + 1), (r[2] / 1e6, r[col]), fontsize=8,
                            xytext=(4, 2 + 7 * (i % 3)), textcoords="offset points")
        ax.set_xlabel("size of the five-mesh table [MB]")
        ax.set_ylabel(name)
        ax.set_xlim(left=0)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=8)
    key = [f"{i + 1}: {r[0]}" for i, r in enumerate(results)]
    half = (len(key) + 1) // 2
    fig.text(0.08, 0.02, "\n".join(key[:half]), fontsize=8, va="bottom")
    fig.text(0.55, 0.02, "\n".join(key[half:]), fontsize=8, va="bottom")
    fig.suptitle(f"Calibrated FastSim's table: size against worst steady error "
                 f"(FastSim {NX}x{NX}, every ray and a/b 0.2-5, against the exact curves)",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.2, 1, 1))
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
