#!/usr/bin/env python3
"""doc/data/stability_map.csv (src/tools/stability_map.cpp) -> doc/figures/stability_map.png: one row of
panels per model, one column per input (adhesion, partial slip, full slip, spin), lambda/a against
V dt/dx, each cell coloured by its class. Prints, per model run in both FastSim variants, the cells
whose class differs between classic and calibrated, and every cell that is nan, blow-up or
oscillation."""
import csv
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

CLASSES = ["good", "inaccurate", "undersampled", "oscillation", "blow-up", "nan", "refused"]
COLOURS = ["#4caf50", "#ffc107", "#b0bec5", "#ff5722", "#b71c1c", "#000000", "#7e57c2"]


def main(src="doc/data/stability_map.csv", out="doc/figures/stability_map.png"):
    rows = list(csv.DictReader(open(src)))
    models = list(OrderedDict.fromkeys(r["model"] for r in rows))
    inputs = list(OrderedDict.fromkeys(r["input"] for r in rows))
    fig, axes = plt.subplots(len(models), len(inputs), figsize=(3.2 * len(inputs), 2.6 * len(models)),
                             squeeze=False, sharex=True, sharey=True)
    cmap = ListedColormap(COLOURS)
    for i, m in enumerate(models):
        for j, inp in enumerate(inputs):
            ax = axes[i][j]
            cells = [r for r in rows if r["model"] == m and r["input"] == inp]
            ls = sorted({float(r["lambda_over_a"]) for r in cells})
            rs = sorted({float(r["step_over_dx"]) for r in cells})
            grid = [[float("nan")] * len(ls) for _ in rs]
            for r in cells:
                grid[rs.index(float(r["step_over_dx"]))][ls.index(float(r["lambda_over_a"]))] = \
                    CLASSES.index(r["class"])
            ax.pcolormesh(edges(ls), edges(rs), grid, cmap=cmap, vmin=-0.5, vmax=len(CLASSES) - 0.5)
            for r in cells:
                if r["class"] in ("good", "inaccurate"):
                    ax.text(float(r["lambda_over_a"]), float(r["step_over_dx"]),
                            "%.0f" % (100 * float(r["error"])), ha="center", va="center", fontsize=5)
            ax.set_xscale("log")
            ax.set_yscale("log")
            if i == 0:
                ax.set_title(inp, fontsize=9)
            if j == 0:
                ax.set_ylabel("%s\nV dt / dx" % m, fontsize=8)
            if i == len(models) - 1:
                ax.set_xlabel("lambda / a", fontsize=8)
            ax.tick_params(labelsize=7)
    fig.legend(handles=[Patch(color=c, label=k) for k, c in zip(CLASSES, COLOURS)],
               loc="lower center", ncol=len(CLASSES), fontsize=8)
    fig.suptitle("Where each model breaks down (numbers: error in %; adhesion vs exact linear, "
                 "otherwise vs the same model at V dt/dx = 0.01, of mu Fz)", fontsize=9)
    fig.tight_layout(rect=(0, 0.03, 1, 0.97))
    fig.savefig(out, dpi=110)
    print("wrote", out)
    compare_variants(rows)


def compare_variants(rows):
    """Cells of one model whose class differs between its classic and calibrated rows."""
    cell = {}
    for r in rows:
        base = r["model"].rsplit(" (", 1)[0]
        key = (base, r["input"], r["lambda_over_a"], r["step_over_dx"])
        cell.setdefault(key, {})[r.get("fastsim", "-")] = r
    broken = [r for r in rows if r["class"] in ("nan", "blow-up", "oscillation")]
    print("nan, blow-up or oscillation cells:", len(broken))
    for r in broken:
        print("  %s %s lambda/a %s step/dx %s: %s" % (r["model"], r["input"], r["lambda_over_a"],
                                                       r["step_over_dx"], r["class"]))
    for base in OrderedDict.fromkeys(k[0] for k in cell):
        pairs = [(k, v) for k, v in cell.items() if k[0] == base and len(v) == 2]
        if not pairs:
            continue
        changed = [(k, v) for k, v in pairs if v["classic"]["class"] != v["calibrated"]["class"]]
        print("%s: %d of %d cells change class from classic to calibrated" % (base, len(changed),
                                                                            len(pairs)))
        for k, v in changed:
            print("  %s lambda/a %s step/dx %s: %s %.3f -> %s %.3f" % (
                k[1], k[2], k[3], v["classic"]["class"], float(v["classic"]["error"]),
                v["calibrated"]["class"], float(v["calibrated"]["error"])))


def edges(v):
    """Cell edges of a log-spaced grid (geometric midpoints, one step outside at the ends)."""
    if len(v) == 1:
        return [v[0] / 1.5, v[0] * 1.5]
    mids = [(a * b) ** 0.5 for a, b in zip(v, v[1:])]
    return [v[0] ** 2 / mids[0]] + mids + [v[-1] ** 2 / mids[-1]]


if __name__ == "__main__":
    main(*sys.argv[1:])
