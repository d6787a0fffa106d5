#!/usr/bin/env python3
"""Speed against accuracy (issue 6) from the CSV speed_accuracy writes.

doc/figures/speed_accuracy.png: error against cost per step, log-log, one marker per model, mesh and
FastSim variant (the mesh n of n x n written beside it), two panels: the worst and the mean error
over the scenes, and (lower row) the worst over the varying-load and over the combined scenes (the
sweep is linear, where the variants agree: the calibration acts at finite creepage). A model's classic and calibrated FastSim share a colour and a marker: classic
filled on a solid line through its meshes, calibrated open on a dashed one. The Pareto front (no
other point is both cheaper and more accurate) is drawn in grey and its points are printed, so that
doc/validation.md can be read against them; so are every row, auto against the cheapest fixed
choice, and the numbers auto's rule reads off the chart (auto_rule), per variant.
The real-profile cases (speed_accuracy_patches.csv beside the table, when there): A-2.2's
gauge-corner patch (y = 5 mm) and tread patches (y = 0.5, 0 mm), each FastSim model on the patch as its equivalent ellipse (dotted)
and on its strips (solid; auto, given the strips, chooses between them and the ellipse), and the exact solver on coarser grids, drawn in
<figure>_patches.png (worst error over the harmonic scenes, of the exact peak force, and over
the held creepages, of mu Fn) and
printed per model, mesh, variant and geometry.
Usage: python3 scripts/plot_speed_accuracy.py [doc/data/speed_accuracy.csv] [doc/figures/speed_accuracy.png]
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TABLE = sys.argv[1] if len(sys.argv) > 1 else "doc/data/speed_accuracy.csv"
OUT = sys.argv[2] if len(sys.argv) > 2 else "doc/figures/speed_accuracy.png"
# Colours of plot_figures.py; a model added later falls back to the cycle below.
COLOUR = {"exact": "k", "nss fixed": "tab:red", "nss adaptive": "tab:orange",
          "shen-li": "tab:blue", "steady": "tab:green", "auto": "tab:purple"}
MARKER = {"exact": "s", "nss fixed": "o", "nss adaptive": "D", "shen-li": "^", "steady": "v",
          "auto": "*"}
SPARE = ["tab:brown", "tab:pink", "tab:olive", "tab:cyan"]
# auto's relaxation length over a at a/b = 1 (AutoModel::relaxationLength, from nss's linear
# response: the calibration leaves it alone, ratios are 1 at zero creepage).
L_OVER_A = 1.67
# auto is drawn at these tolerances; the others in the table (the rungs of auto's mesh ladders,
# scripts/speed_accuracy.sh) are printed only.
DRAWN_TOLERANCES = (0.1, 0.05)
LOAD_SWING = 0.25  # the varying-load scenes' Fz0 (1 + 0.25 sin): paper_scenes.cpp


def label(r):
    if r["model"] == "auto":
        return "auto"
    return r["model"] if r["model"] in ("exact", "shen-li", "steady") else f"{r['model']} {r['mesh']}"


def variant(r):
    return r["fastsim"]


def series(r):
    return label(r) if variant(r) == "-" else f"{label(r)}, {variant(r)}"


def tag(r):
    """The mesh n beside each marker; auto's also names the tolerance that chose it."""
    return f"{r['nx']}@{float(r['tolerance']):g}" if r["model"] == "auto" else r["nx"]


def pareto(points):
    """Points (cost, error, row) not dominated by a cheaper-or-equal, more accurate one."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def drawn(r):
    return r["model"] != "auto" or float(r["tolerance"]) in DRAWN_TOLERANCES


def panel(ax, table, column, title):
    table = [r for r in table if drawn(r)]
    groups = {}
    for r in table:
        groups.setdefault((label(r), variant(r)), []).append(r)
    colours, spare = {}, iter(SPARE)
    for (name, kind), rs in groups.items():
        colour = colours.setdefault(name, COLOUR.get(name) or next(spare, "grey"))
        rs = sorted(rs, key=lambda r: float(r["ns_per_step"]))
        xs = [float(r["ns_per_step"]) for r in rs]
        ys = [100 * float(r[column]) for r in rs]
        calibrated = kind == "calibrated"
        ax.plot(xs, ys, ls="--" if calibrated else "-", lw=0.8, marker=MARKER.get(name, "P"),
                color=colour, markerfacecolor="white" if calibrated else colour,
                label=name if kind == "-" else f"{name}, {kind}")
        for x, y, r in zip(xs, ys, rs):
            ax.annotate(tag(r), (x, y), textcoords="offset points",
                        xytext=(4, -9) if calibrated else (4, 3), fontsize=6)
    front = pareto([(float(r["ns_per_step"]), 100 * float(r[column]), r) for r in table])
    ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="grey", lw=1,
            zorder=0, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost per step [ns] (least of the passes, thread CPU time)")
    ax.set_ylabel("error [% of exact peak force]")
    ax.set_title(title if "scenes" in title else f"{title} over the scenes")
    ax.grid(True, which="both", alpha=0.3)
    print(f"Pareto front, {title.lower()} error:" if "scenes" not in title else f"Pareto front, {title.lower()}:")
    for x, y, r in front:
        print(f"  {series(r):26s} {r['nx']:>2}x{r['ny']:<2} {x:10.0f} ns/step {y:7.2f} %")


def rows_table(table):
    """Every row: worst and mean error and cost per model, mesh and variant."""
    print("model, variant, mesh: worst %, mean %, worst within reach is in auto_rule; ns/step")
    for r in table:
        at = f"@{float(r['tolerance']):g}" if r["model"] == "auto" else ""
        print(f"  {series(r):26s} {r['nx']:>2}x{r['ny']:<2}{at:6s} worst {100 * float(r['worst_error']):6.2f}"
              f" mean {100 * float(r['mean_error']):5.2f} load {100 * float(r['worst_load']):5.2f}"
              f" combined {100 * float(r['worst_combined']):5.2f} {float(r['ns_per_step']):9.0f} ns")


def in_reach(r):
    """The scenes NSS-FastSim is made for: combined, varying load, frequency sweep from
    lambda/a = 10."""
    return not (r["family"] == "freq" and float(r["scene"].split("_l")[-1]) < 10)


def read_scenes(scenes_csv):
    with open(scenes_csv) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r.setdefault("fastsim", "-" if r["model"] == "exact" else "classic")
    return rows


def within_reach(scenes):
    """auto against the cheapest fixed choice, per tolerance and variant, on the scenes within
    reach: worst error and mean cost per step over those scenes. The cheapest fixed choice is
    looked for among every variant and among auto's own."""
    worst, costs = {}, {}
    for r in scenes:
        if not in_reach(r):
            continue
        key = (r["model"], r["mesh"], r["fastsim"], r["nx"], r["tolerance"])
        worst[key] = max(worst.get(key, 0.0), float(r["error"]))
        costs.setdefault(key, []).append(float(r["ns_per_step"]))
    cost = {k: sum(v) / len(v) for k, v in costs.items()}

    def text(k):
        return f"{k[0]} {k[1]} {k[2]} {k[3]}x{k[3]}: {100 * worst[k]:.1f} %, {cost[k]:.0f} ns"

    print("auto within reach (worst error and mean cost over combined, load and frequency sweep "
          "from lambda/a = 10):")
    for key in sorted(k for k in worst if k[0] == "auto"):
        t = float(key[4])
        fixed = [k for k in worst if k[0] not in ("auto", "exact") and worst[k] <= t]
        best = min(fixed, key=lambda k: cost[k], default=None)
        own = min((k for k in fixed if k[2] == key[2]), key=lambda k: cost[k], default=None)
        same = ("nss", "adaptive", key[2], key[3], "0")
        print(f"  tolerance {100 * t:g} %, auto {key[2]} {key[3]}x{key[3]}: {100 * worst[key]:.1f} %, "
              f"{cost[key]:.0f} ns; cheapest fixed choice within it: {text(best) if best else 'none'}"
              f"; of its variant: {text(own) if own else 'none'}"
              f"; nss adaptive, same mesh: {text(same) if same in worst else '-'}")


def auto_rule(scenes):
    """The numbers of auto's rule (auto_model.cpp), read off the chart per variant:
    - mesh ladder: worst error within reach of nss adaptive per mesh;
    - load weight: steady FastSim's error beyond nss adaptive's on the same mesh over the lag
      estimate l |dfz/dq| / fz / sqrt 2 (peak of the ratio for Fz0 (1 + 0.25 sin));
    - shares: on the frequency sweep from lambda/a = 10, steady's error beyond nss's and steady's
      own against the estimate l 2 pi / lambda / sqrt 2."""
    err = {}
    for r in scenes:
        err[(r["model"], r["mesh"], r["fastsim"], r["nx"], r["tolerance"], r["scene"])] = \
            float(r["error"])
    kinds = sorted({k[2] for k in err if k[2] != "-"})
    for kind in kinds:
        print(f"auto's rule read off the chart, {kind} FastSim:")
        meshes = sorted({int(k[3]) for k in err if k[0] == "nss" and k[1] == "adaptive"
                         and k[2] == kind})
        for n in meshes:
            reach = [(v, k[5]) for k, v in err.items() if k[:5] == ("nss", "adaptive", kind, str(n), "0")
                     and in_reach({"family": "freq" if k[5].startswith("freq") else "x",
                                   "scene": k[5]})]
            w, at = max(reach)
            print(f"  nss adaptive {n}x{n}: worst within reach {w:.4f} ({at})")
        for n in ("5", "20"):
            ratios, beyond = [], []
            for k, v in err.items():
                if k[:5] != ("steady", "fixed", kind, n, "0"):
                    continue
                nss = err.get(("nss", "adaptive", kind, n, "0", k[5]))
                if nss is None:
                    continue
                if k[5].startswith("combined"):
                    continue
                lam = float(k[5].split("_l")[-1])
                if k[5].startswith("load"):
                    lag = L_OVER_A * 2 * math.pi / lam * LOAD_SWING / math.sqrt(1 - LOAD_SWING ** 2)
                    ratios.append(((v - nss) / (lag / math.sqrt(2)), k[5]))
                elif k[5].startswith("freq") and lam >= 10:
                    est = L_OVER_A * 2 * math.pi / lam / math.sqrt(2)
                    beyond.append(((v - nss) / est, k[5], nss))
            if ratios:
                lo, hi = min(ratios), max(ratios)
                print(f"  {n}x{n} load: steady's error beyond nss's over the lag estimate "
                      f"{lo[0]:.3f} ({lo[1]}) to {hi[0]:.3f} ({hi[1]})")
            if beyond:
                lo, hi = min(beyond), max(beyond)
                own = max((x[2], x[1]) for x in beyond)
                print(f"  {n}x{n} sweep from lambda/a = 10: steady's error beyond nss's over the "
                      f"estimate {lo[0]:.3f} ({lo[1]}) to {hi[0]:.3f} ({hi[1]}); nss's own error "
                      f"at most {own[0]:.4f} ({own[1]})")


PATCHES = (("corner_y5", "gauge corner, y = 5 mm (Hertz)"),
           ("tread_y0.5", "tread, y = 0.5 mm (our patch narrower than exact's)"),
           ("tread_y0", "tread, y = 0 mm (a/b 0.26)"))


def patch_rows(path):
    """Per model, mesh, variant, geometry and patch: worst error over the harmonic scenes (of the
    exact peak force), the held (steady) scene's (of mu fn), and the mean cost per step."""
    groups = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            patch = r["scene"].split("_held")[0].split("_linear")[0].split("_partial")[0]
            key = (r["model"], r["mesh"], r["fastsim"], r["nx"], r["ny"], r["tolerance"],
                   r["geometry"], patch)
            groups.setdefault(key, []).append(r)
    out = []
    for key, rs in groups.items():
        held = [float(r["error"]) for r in rs if r["scene"].endswith("_held")]
        wave = [float(r["error"]) for r in rs if not r["scene"].endswith("_held")]
        out.append({"model": key[0], "mesh": key[1], "fastsim": key[2], "nx": key[3],
                    "ny": key[4], "tolerance": key[5], "geometry": key[6], "patch": key[7],
                    "worst": max(wave, default=0.0), "held": max(held, default=0.0),
                    "ns": sum(float(r["ns_per_step"]) for r in rs) / len(rs)})
    return out


def shown_geometry(name, geometry):
    """auto given the strips chooses between them and the ellipse itself (auto_model.hpp)."""
    return "given strips (its choice)" if name.startswith("auto") and geometry == "strips" \
        else geometry


def patches_figure(path, out):
    """Per patch (columns): the worst harmonic error and the held one against the cost, the
    default variant (calibrated) drawn, both printed; nss fixed printed only (as adaptive)."""
    table = patch_rows(path)
    print("real-profile cases (A-2.2 right wheel): per patch, worst over the harmonic scenes in % "
          "of the exact peak, held in % of mu fn, mean ns/step")
    for r in sorted(table, key=lambda r: (r["patch"], r["model"], r["mesh"], r["geometry"],
                                           r["fastsim"], int(r["nx"]), r["tolerance"])):
        if not drawn(r):
            continue
        at = f"@{float(r['tolerance']):g}" if r["model"] == "auto" else ""
        print(f"  {r['patch']:10s} {series(r):26s} {r['geometry']:8s} {r['nx']:>2}x{r['ny']:<2}"
              f"{at:6s} worst {100 * r['worst']:7.2f} held {100 * r['held']:6.2f} "
              f"{r['ns']:9.0f} ns")
    shown = [r for r in table if drawn(r) and r["fastsim"] in ("calibrated", "-")
             and label(r) != "nss fixed"]
    fig, ax = plt.subplots(2, len(PATCHES), figsize=(15, 8.5), squeeze=False)
    for col, (patch, title) in enumerate(PATCHES):
        for row, column, unit in ((0, "worst", "harmonic eta, worst: % of exact peak"),
                                  (1, "held", "creepages held: % of mu Fn")):
            axis = ax[row][col]
            groups = {}
            for r in shown:
                if r["patch"] == patch:
                    groups.setdefault((label(r), r["geometry"]), []).append(r)
            for (name, geometry), rs in sorted(groups.items()):
                rs = sorted(rs, key=lambda r: r["ns"])
                axis.plot([r["ns"] for r in rs], [100 * r[column] for r in rs],
                          ls=":" if geometry == "ellipse" else "-", lw=1,
                          marker=MARKER.get(name, "P"), color=COLOUR.get(name, "grey"),
                          markerfacecolor="white" if geometry == "ellipse" else None,
                          label=f"{name}, {shown_geometry(name, geometry)}")
                for r in rs:
                    axis.annotate(tag(r), (r["ns"], 100 * r[column]), textcoords="offset points",
                                  xytext=(3, 3), fontsize=6)
            axis.set_xscale("log")
            axis.set_yscale("log")
            axis.grid(True, which="both", alpha=0.3)
            axis.set_ylabel(unit)
            if row == 0:
                axis.set_title(title, fontsize=10)
            else:
                axis.set_xlabel("cost per step [ns] (thread CPU time)")
    handles, names = ax[0][0].get_legend_handles_labels()
    fig.legend(handles, names, fontsize=8, loc="lower center", ncol=6)
    fig.suptitle("A-2.2, right wheel: the patch as its equivalent ellipse (open, dotted) or its "
                 "strips (filled, solid), calibrated FastSim; exact on coarser grids; reference "
                 "exact 40x30")
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(out, dpi=70)
    print(f"written {out}")


def main():
    with open(TABLE) as f:
        table = list(csv.DictReader(f))
    for r in table:  # a table from before the variants: classic
        r.setdefault("fastsim", "-" if r["model"] == "exact" else "classic")
    rows_table(table)
    scenes = read_scenes(TABLE.replace("speed_accuracy.csv", "speed_accuracy_scenes.csv"))
    if any(r["model"] == "auto" for r in table):
        within_reach(scenes)
    auto_rule(scenes)
    fig, ax = plt.subplots(2, 2, figsize=(15, 12))
    panel(ax[0][0], table, "worst_error", "Worst")
    panel(ax[0][1], table, "mean_error", "Mean")
    # The sweep is linear, where the variants agree; the calibration acts at finite creepage.
    panel(ax[1][0], table, "worst_load", "Worst over the varying-load scenes")
    panel(ax[1][1], table, "worst_combined", "Worst over the combined scenes")
    handles, names = ax[0][0].get_legend_handles_labels()
    fig.legend(handles, names, fontsize=9, loc="lower center", ncol=6)
    fig.suptitle("Error against the fine-grid exact solver vs cost per step; classic FastSim "
                 "filled, calibrated open/dashed (labels: n of the n x n mesh; auto: n@tolerance)")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(OUT, dpi=90)
    print(f"written {OUT}")
    patches = TABLE.replace("speed_accuracy.csv", "speed_accuracy_patches.csv")
    if os.path.exists(patches):
        patches_figure(patches, OUT.replace(".png", "_patches.png"))


if __name__ == "__main__":
    main()
