#!/usr/bin/env python3
"""Figures of the NSS-FastSim accuracy study from the CSVs accuracy_report writes (doc/data).

Redoes the paper's Figs. 1-4 and 8-10 with our exact solver in the place of CONTACT:
  doc/figures/freq_ab1.png        |C^|/C_steady and phase against lambda/a, a/b = 1, every kind (Fig. 1)
  doc/figures/combined{1,2,3}.png force magnitude and angle, combined creepages (Figs. 2-4)
  doc/figures/load_dfx.png        dFx/(mu dFz) against lambda/a0 for each xi (Fig. 8)
  doc/figures/load_xi0.05_l15.png, doc/figures/load_xi0.1_l15.png  Fx and Fz histories (Figs. 9-10)
  doc/figures/patch_freq.png      fs^ and mz^ over exact's steady gains against lambda/a on A-2.2's
                                  gauge-corner and tread patches (patch_frequency's patch_freq.csv)
Usage: python3 scripts/plot_figures.py [doc/data] [doc/figures] [FIGURE ...]
FIGURE: freq, combined, load, patch_freq (all when none is named).
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DATA = sys.argv[1] if len(sys.argv) > 1 else "doc/data"
OUT = sys.argv[2] if len(sys.argv) > 2 else "doc/figures"
STYLE = {"exact": ("k", "-"), "nss": ("tab:red", "--"), "shen-li": ("tab:blue", ":"),
         "steady": ("tab:green", "-.")}


def rows(name):
    with open(f"{DATA}/{name}") as f:
        return list(csv.DictReader(f))


def unwrapped_phase(ratios):
    """Phase [deg] of ratios ordered by lambda/a, continuous from the longest wave (where it is
    near 0) down: C23's response spirals through the origin at short waves."""
    out, last = [0.0] * len(ratios), 0.0
    for i in reversed(range(len(ratios))):
        phi = math.degrees(math.atan2(ratios[i].imag, ratios[i].real))
        phi += 360.0 * round((last - phi) / 360.0)
        out[i] = last = phi
    return out


def freq_figure():
    data = defaultdict(lambda: defaultdict(list))
    for r in rows("freq_ab1.csv"):
        data[r["kind"]][r["model"]].append(
            (float(r["lambda_over_a"]), complex(float(r["ratio_real"]), float(r["ratio_imag"]))))
    fig, ax = plt.subplots(2, 3, figsize=(13, 7), sharex=True)
    for col, kind in enumerate(["11", "22", "23"]):
        for model, pts in data[kind].items():
            c, ls = STYLE[model]
            lam = [p[0] for p in pts]
            ax[0][col].semilogx(lam, [abs(p[1]) for p in pts], color=c, ls=ls, label=model)
            ax[1][col].semilogx(lam, unwrapped_phase([p[1] for p in pts]), color=c, ls=ls,
                                label=model)
        ax[0][col].set_title(f"C{kind}, a/b = 1")
        ax[1][col].set_xlabel("lambda / a")
    ax[0][0].set_ylabel("|C^| / C_steady")
    ax[1][0].set_ylabel("phase [deg]")
    ax[0][0].legend()
    fig.tight_layout()
    fig.savefig(f"{OUT}/freq_ab1.png", dpi=90)


def patch_freq_figure():
    """Amplitude and phase of fs^ over exact's steady dfs/deta, and the amplitude of mz^ over
    exact's steady dmz/deta (about the contact point), on the real patches: the models on our
    strips (the styles of freq_ab1), nss also on the equivalent ellipse and on the exact
    solution's own strips (thin)."""
    data = defaultdict(lambda: defaultdict(list))
    for r in rows("patch_freq.csv"):
        data[r["patch"]][(r["model"], r["geometry"])].append(
            (float(r["lambda_over_a"]), complex(float(r["fs_re"]), float(r["fs_im"])),
             complex(float(r["mz_re"]), float(r["mz_im"]))))
    thin = {("nss", "ellipse"): ("tab:red", ":", "nss, ellipse"),
            ("nss", "exact_strips"): ("tab:purple", "-", "nss, exact's strips")}
    titles = {"corner_y5": "gauge corner, y = 5 mm", "tread_y0.5": "tread, y = 0.5 mm"}
    fig, ax = plt.subplots(3, len(data), figsize=(10, 8), sharex=True, squeeze=False)
    for col, (patch, curves) in enumerate(sorted(data.items())):
        for (model, geometry), pts in curves.items():
            if geometry in ("grid", "strips"):
                c, ls = STYLE[model]
                lw, name = 1.5, model if model == "exact" else f"{model}, strips"
            elif (model, geometry) in thin:
                c, ls, name = thin[(model, geometry)]
                lw = 0.8
            else:
                continue
            pts.sort(key=lambda p: p[0])
            lam = [p[0] for p in pts]
            ax[0][col].semilogx(lam, [abs(p[1]) for p in pts], color=c, ls=ls, lw=lw, label=name)
            ax[1][col].semilogx(lam, unwrapped_phase([p[1] for p in pts]), color=c, ls=ls, lw=lw)
            ax[2][col].semilogx(lam, [abs(p[2]) for p in pts], color=c, ls=ls, lw=lw)
        ax[0][col].set_title(titles.get(patch, patch))
        ax[2][col].set_xlabel("lambda / a (a of the equivalent ellipse)")
    ax[0][0].set_ylabel("|fs^| / exact steady dfs/deta")
    ax[1][0].set_ylabel("phase of fs^ [deg]")
    ax[2][0].set_ylabel("|mz^| / exact steady dmz/deta")
    ax[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{OUT}/patch_freq.png", dpi=80)


def history(name):
    out = defaultdict(lambda: ([], [], [], []))
    for r in rows(f"scene_{name}.csv"):
        key = r["model"] if r["model"] in ("exact", "steady") else f"{r['model']} {r['mesh']}"
        t, fz, fx, fy = out[key]
        t.append(float(r["t"]))
        fz.append(float(r["fz"]))
        fx.append(float(r["fx"]))
        fy.append(float(r["fy"]))
    return out


def combined_figure(n):
    h = history(f"combined{n}")
    fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for key, (t, _, fx, fy) in h.items():
        if key.endswith("adaptive"):  # at constant load the same as fixed
            continue
        c, ls = STYLE[key.split()[0]]
        ax[0].plot(t, [math.hypot(a, b) for a, b in zip(fx, fy)], color=c, ls=ls, label=key)
        ax[1].plot(t, [math.degrees(math.atan2(b, a)) for a, b in zip(fx, fy)], color=c, ls=ls)
    ax[0].set_ylabel("|F| [N]")
    ax[1].set_ylabel("angle of F [deg]")
    ax[1].set_xlabel("t [s]")
    ax[0].legend()
    ax[0].set_title(f"combined creepages, case {n} (paper eq. {15 + n})")
    fig.tight_layout()
    fig.savefig(f"{OUT}/combined{n}.png", dpi=90)


def load_figures():
    table = rows("scenes.csv")
    fig, ax = plt.subplots(figsize=(8, 5))
    series = defaultdict(list)
    for r in table:
        if not r["scene"].startswith("load_"):
            continue
        xi, lam = r["scene"][len("load_xi"):].split("_l")
        if r["model"] == "nss" and r["mesh"] == "adaptive":
            series[(xi, "nss")].append((float(lam), float(r["dfx_over_mu_dfz"])))
            series[(xi, "exact")].append((float(lam), float(r["exact_dfx_over_mu_dfz"])))
    for (xi, model), pts in sorted(series.items()):
        pts.sort()
        c = {"0.002": "tab:blue", "0.010": "tab:orange", "0.050": "tab:green", "0.100": "tab:red"}[xi]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c,
                ls="-" if model == "exact" else "--", marker="o", label=f"{model} xi={xi}")
    ax.set_xlabel("lambda / a0")
    ax.set_ylabel("dFx / (mu dFz)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{OUT}/load_dfx.png", dpi=90)
    for xi in ("0.050", "0.100"):
        h = history(f"load_xi{xi}_l15")
        fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
        for key, (t, fz, fx, _) in h.items():
            if key == "shen-li adaptive":  # in the table only: one shen-li line, as in the paper
                continue
            c, ls = STYLE[key.split()[0]]
            ax[0].plot(t, fx, color=c, ls=ls, label=key)
        t, fz = h["exact"][0], h["exact"][1]
        ax[1].plot(t, fz, "k")
        ax[0].set_ylabel("Fx [N]")
        ax[1].set_ylabel("Fz [N]")
        ax[1].set_xlabel("t [s]")
        ax[0].legend()
        ax[0].set_title(f"varying load, xi = {xi}, lambda/a0 = 15")
        fig.tight_layout()
        fig.savefig(f"{OUT}/load_xi{xi}_l15.png", dpi=90)


if __name__ == "__main__":
    only = set(sys.argv[3:])
    if not only or "freq" in only:
        freq_figure()
    if not only or "combined" in only:
        for n in (1, 2, 3):
            combined_figure(n)
    if not only or "load" in only:
        load_figures()
    if not only or "patch_freq" in only:
        patch_freq_figure()
    print(f"figures written to {OUT}/")
