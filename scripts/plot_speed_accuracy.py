#!/usr/bin/env python3
"""Speed against accuracy (issue 6) from the CSV speed_accuracy writes.

doc/figures/speed_accuracy.png: error against cost per step, log-log, one marker per model and mesh (the
mesh n of n x n written beside it), two panels: the worst and the mean error over the scenes. The
Pareto front (no other point is both cheaper and more accurate) is drawn in grey and its points are
printed, so that doc/validation.md can be read against them.
Usage: python3 scripts/plot_speed_accuracy.py [doc/data/speed_accuracy.csv] [doc/figures/speed_accuracy.png]
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TABLE = sys.argv[1] if len(sys.argv) > 1 else "doc/data/speed_accuracy.csv"
OUT = sys.argv[2] if len(sys.argv) > 2 else "doc/figures/speed_accuracy.png"
# Colours of plot_figures.py; a model added later (e.g. auto) falls back to the cycle below.
COLOUR = {"exact": "k", "nss fixed": "tab:red", "nss adaptive": "tab:orange",
          "shen-li": "tab:blue", "steady": "tab:green", "auto": "tab:purple"}
MARKER = {"exact": "s", "nss fixed": "o", "nss adaptive": "D", "shen-li": "^", "steady": "v",
          "auto": "*"}
SPARE = ["tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan"]


def label(r):
    if r["model"] == "auto":
        return "auto"
    return r["model"] if r["model"] in ("exact", "shen-li", "steady") else f"{r['model']} {r['mesh']}"


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


def panel(ax, table, column, title):
    groups = {}
    for r in table:
        groups.setdefault(label(r), []).append(r)
    spare = iter(SPARE)
    for name, rs in groups.items():
        colour = COLOUR.get(name) or next(spare, "grey")
        xs = [float(r["ns_per_step"]) for r in rs]
        ys = [100 * float(r[column]) for r in rs]
        ax.plot(xs, ys, ls="none", marker=MARKER.get(name, "P"), color=colour, label=name)
        for x, y, r in zip(xs, ys, rs):
            ax.annotate(tag(r), (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    front = pareto([(float(r["ns_per_step"]), 100 * float(r[column]), r) for r in table])
    ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="grey", lw=1,
            zorder=0, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost per step [ns] (least of the passes)")
    ax.set_ylabel(f"{title} error [% of exact peak force]")
    ax.set_title(f"{title} over the scenes")
    ax.grid(True, which="both", alpha=0.3)
    print(f"Pareto front, {title.lower()} error:")
    for x, y, r in front:
        print(f"  {label(r):13s} {r['nx']:>2}x{r['ny']:<2} {x:10.0f} ns/step {y:7.2f} %")


def within_reach(scenes_csv):
    """auto against the cheapest fixed choice, per tolerance, on the scenes NSS-FastSim is made for:
    the combined and varying-load scenes and the frequency sweep from lambda/a = 10. Worst error
    and mean cost per step over those scenes."""
    worst, costs = {}, {}
    with open(scenes_csv) as f:
        for r in csv.DictReader(f):
            if r["family"] == "freq" and float(r["scene"].split("_l")[-1]) < 10:
                continue
            key = (r["model"], r["mesh"], r["nx"], r["tolerance"])
            worst[key] = max(worst.get(key, 0.0), float(r["error"]))
            costs.setdefault(key, []).append(float(r["ns_per_step"]))
    cost = {k: sum(v) / len(v) for k, v in costs.items()}
    print("auto within reach (worst error and mean cost over combined, load and frequency sweep "
          "from lambda/a = 10):")
    for key in sorted(k for k in worst if k[0] == "auto"):
        t = float(key[3])
        fixed = [k for k in worst if k[0] not in ("auto", "exact") and worst[k] <= t]
        best = min(fixed, key=lambda k: cost[k], default=None)
        cheapest = (f"{best[0]} {best[1]} {best[2]}x{best[2]}: {100 * worst[best]:.1f} %, "
                    f"{cost[best]:.0f} ns" if best else "none")
        print(f"  tolerance {100 * t:g} %: auto {key[2]}x{key[2]} {100 * worst[key]:.1f} %, "
              f"{cost[key]:.0f} ns; cheapest fixed choice within it: {cheapest}")


def main():
    with open(TABLE) as f:
        table = list(csv.DictReader(f))
    scenes_csv = TABLE.replace("speed_accuracy.csv", "speed_accuracy_scenes.csv")
    if any(r["model"] == "auto" for r in table):
        within_reach(scenes_csv)
    fig, ax = plt.subplots(1, 2, figsize=(13, 5.5))
    panel(ax[0], table, "worst_error", "Worst")
    panel(ax[1], table, "mean_error", "Mean")
    ax[1].legend(fontsize=8, loc="upper right")
    fig.suptitle("Error against the fine-grid exact solver vs cost per step "
                 "(labels: n of the n x n mesh; auto: n@tolerance)")
    fig.tight_layout()
    fig.savefig(OUT, dpi=90)
    print(f"written {OUT}")


if __name__ == "__main__":
    main()
