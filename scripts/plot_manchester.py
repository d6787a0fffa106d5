#!/usr/bin/env python3
"""Figures of the Manchester benchmark's case A-2.2 (doc/manchester.md), from manchester_a22's output.

usage: plot_manchester.py [DATA_PREFIX [FIGURE_DIR]]
DATA_PREFIX (default doc/data/manchester_a22): reads <prefix>.csv (one row per case, wheel and patch),
<prefix>_strips.csv (our strips) and <prefix>_exact_map.csv (the exact solver's loaded elements).
Writes to FIGURE_DIR (default doc/figures):
  manchester_a22_contact_point.png: the contact point on the rail (rail file's lateral coordinate)
    against the wheelset's lateral displacement, both wheels: ours (the patch's centre, its lateral
    extent as a bar, the marker's area the normal force) and CONTACT's published reference points;
  manchester_a22_pressure.png: per loaded patch of the right wheel at the mapped displacements, our
    pressure (each strip a semi-ellipse along x between its trailing and leading edge, as the strip
    method assumes) beside the exact half-space solution, and the peak pressure across the patch;
  manchester_a22_creep.png (from <prefix>_creep.csv, if present): fx, fs, mz per loaded patch
    against y, both wheels: the exact tangential solution on the same patch, each model through
    WheelsetContact, CONTACT's published values; and each model's error in % of mu fn.
Prints the compact tables of doc/manchester.md.
"""
import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

prefix = sys.argv[1] if len(sys.argv) > 1 else "doc/data/manchester_a22"
figdir = sys.argv[2] if len(sys.argv) > 2 else "doc/figures"


def read(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def num(r, k):
    v = r.get(k, "")
    return float(v) if v not in ("", None) else math.nan


rows = read(prefix + ".csv")
strips = read(prefix + "_strips.csv")
exact = read(prefix + "_exact_map.csv")


def on_rail(r, eta_mm):
    """A point eta [mm] along the patch's contact plane, on the rail file's lateral axis [mm]."""
    return num(r, "y_rail_mm") - eta_mm * math.cos(num(r, "contact_angle"))


# --- the compact table (doc/manchester.md) -----------------------------------------------------
print("| wheel | y (mm) | zone | rail y ours / CONTACT (mm) | angle ours / CONTACT (rad) | "
      "fn ours / exact / CONTACT (kN) | pmax ours / exact / CONTACT (MPa) |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for r in rows:
    if r["method"] == "merged":  # a candidate whose patch another took over (fn 0)
        print(f"| {r['wheel']} | {num(r, 'y_mm'):.1f} | {r['zone']} | {r['status']} | - | - | - |")
        continue
    ref = not math.isnan(num(r, "contact_fn_N"))

    def pair(a, b, fmt):
        return f"{a:{fmt}} / " + (f"{b:{fmt}}" if ref else "-")

    print(f"| {r['wheel']} | {num(r, 'y_mm'):.1f} | {r['zone']} | "
          f"{pair(num(r, 'y_rail_centre_mm'), num(r, 'contact_y_rail_mm'), '.2f')} | "
          f"{pair(num(r, 'contact_angle'), num(r, 'contact_angle_ref'), '.3f')} | "
          f"{num(r, 'fn_N') / 1e3:.2f} / {num(r, 'exact_fn_N') / 1e3:.2f} / "
          + (f"{num(r, 'contact_fn_N') / 1e3:.2f}" if ref else "-") + " | "
          f"{num(r, 'pmax_MPa'):.0f} / {num(r, 'exact_pmax_MPa'):.0f} / "
          + (f"{num(r, 'contact_pmax_MPa'):.0f}" if ref else "-") + " |")

# --- contact point on the rail against y -------------------------------------------------------
fig, axes = plt.subplots(1, 2, figsize=(13, 5), sharey=True)
for ax, wheel in zip(axes, ("right", "left")):
    mine = [r for r in rows if r["wheel"] == wheel and num(r, "fn_N") > 0]
    for zone, colour in (("tread", "tab:blue"), ("corner", "tab:orange"), ("flange", "tab:red")):
        z = [r for r in mine if r["zone"] == zone]
        if not z:
            continue
        y = [num(r, "y_mm") for r in z]
        c = [num(r, "y_rail_centre_mm") for r in z]
        lo = [on_rail(r, num(r, "eta_max_mm")) for r in z]
        hi = [on_rail(r, num(r, "eta_min_mm")) for r in z]
        ax.vlines(y, np.minimum(lo, hi), np.maximum(lo, hi), color=colour, alpha=0.35, lw=4)
        ax.scatter(y, c, s=[num(r, "fn_N") / 150 for r in z], color=colour,
                   label=f"ours, {zone} (area: fn; bar: lateral extent)")
    ref = [r for r in rows if r["wheel"] == wheel and not math.isnan(num(r, "contact_fn_N"))]
    ax.plot([num(r, "y_mm") for r in ref], [num(r, "contact_y_rail_mm") for r in ref], "kx",
            ms=8, label="CONTACT (published reference points)")
    ax.set_title(f"{wheel} wheel")
    ax.set_xlabel("wheelset lateral displacement y [mm] (benchmark's axes, to the right)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
axes[0].set_ylabel("contact point on the rail, rail file's lateral coordinate [mm]\n"
                   "(right file's axes: + toward the field side)")
fig.suptitle("Manchester benchmark A-2.2: contact point on the rail")
fig.tight_layout()
fig.savefig(f"{figdir}/manchester_a22_contact_point.png", dpi=110)

# --- pressure maps -------------------------------------------------------------------------------
patches = sorted({(float(s["y_mm"]), int(s["patch"])) for s in strips if s["wheel"] == "right"})
if patches:
    fig, axes = plt.subplots(len(patches), 3, figsize=(15, 4.2 * len(patches)), squeeze=False)
    fig.subplots_adjust(hspace=0.55, wspace=0.35)
    for row, (y, patch) in zip(axes, patches):
        info = next(r for r in rows if r["wheel"] == "right" and num(r, "y_mm") == y
                    and int(r["patch"]) == patch)
        st = [s for s in strips if s["wheel"] == "right" and float(s["y_mm"]) == y
              and int(s["patch"]) == patch]
        ex = [e for e in exact if e["wheel"] == "right" and float(e["y_mm"]) == y
              and int(e["patch"]) == patch]
        xs = sorted({float(e["x_mm"]) for e in ex})
        es = sorted({float(e["eta_mm"]) for e in ex})
        dx = float(ex[0]["dx_mm"]) if ex else 0.1
        de = float(ex[0]["deta_mm"]) if ex else 0.1
        xmin = min([float(s["x_trail_mm"]) for s in st] + [x - dx for x in xs])
        xmax = max([float(s["x_lead_mm"]) for s in st] + [x + dx for x in xs])
        emin = min([float(s["eta_mm"]) - float(s["width_mm"]) for s in st] + [e - de for e in es])
        emax = max([float(s["eta_mm"]) + float(s["width_mm"]) for s in st] + [e + de for e in es])
        # Exact: its elements on their own regular grid.
        nx = int(round((xmax - xmin) / dx)) + 1
        ne = int(round((emax - emin) / de)) + 1
        pe = np.zeros((ne, nx))
        for e in ex:
            i = int(round((float(e["eta_mm"]) - emin) / de))
            j = int(round((float(e["x_mm"]) - xmin) / dx))
            if 0 <= i < ne and 0 <= j < nx:
                pe[i, j] = float(e["p_MPa"])
        # Ours: each strip's semi-ellipse p = pmax sqrt(1 - ((x - xm) / L)^2) on a fine raster.
        gx = np.linspace(xmin, xmax, 400)
        ge = np.linspace(emin, emax, 300)
        po = np.zeros((len(ge), len(gx)))
        for s in st:
            e0, w = float(s["eta_mm"]), float(s["width_mm"])
            lead, trail, pm = float(s["x_lead_mm"]), float(s["x_trail_mm"]), float(s["pmax_MPa"])
            xm, half = 0.5 * (lead + trail), 0.5 * (lead - trail)
            if half <= 0:
                continue
            rows_in = (ge >= e0 - 0.5 * w) & (ge < e0 + 0.5 * w)
            prof = pm * np.sqrt(np.clip(1 - ((gx - xm) / half) ** 2, 0, None))
            po[rows_in, :] = np.maximum(po[rows_in, :], prof)
        vmax = max(pe.max(initial=0), po.max(initial=0))
        extent_e = [xmin - 0.5 * dx, xmin + (nx - 0.5) * dx, emin - 0.5 * de, emin + (ne - 0.5) * de]
        im = row[0].imshow(po, origin="lower", aspect="auto", extent=[xmin, xmax, emin, emax],
                           vmin=0, vmax=vmax, cmap="viridis")
        row[1].imshow(pe, origin="lower", aspect="auto", extent=extent_e, vmin=0, vmax=vmax,
                      cmap="viridis")
        title = f"y = {y:g} mm, {info['zone']} (angle {num(info, 'contact_angle'):.2f} rad)"
        row[0].set_title(f"ours ({info['method']}), {title}\nfn {num(info, 'fn_N') / 1e3:.2f} kN, "
                         f"pmax {num(info, 'pmax_MPa'):.0f} MPa", fontsize=9)
        row[1].set_title(f"exact half-space, fn {num(info, 'exact_fn_N') / 1e3:.2f} kN, "
                         f"pmax {num(info, 'exact_pmax_MPa'):.0f} MPa", fontsize=9)
        for a in row[:2]:
            a.set_xlabel("x, rolling direction [mm]")
        row[0].set_ylabel("eta, lateral in the contact plane [mm]")
        fig.colorbar(im, ax=row[:2].tolist(), label="p [MPa]")
        # Peak pressure across the patch.
        row[2].step([float(s["eta_mm"]) for s in st], [float(s["pmax_MPa"]) for s in st],
                    where="mid", label="ours: strip peak")
        if ex:
            row[2].plot(emin + de * np.arange(ne), pe.max(axis=1), "o", ms=3,
                        label="exact: peak over x")
        row[2].set_xlabel("eta [mm]")
        row[2].set_ylabel("peak pressure [MPa]")
        row[2].grid(True, alpha=0.3)
        row[2].legend(fontsize=8)
    fig.suptitle("Manchester benchmark A-2.2, right wheel: pressure, our method against the exact "
                 "half-space solver on the same gap", y=0.92)
    fig.savefig(f"{figdir}/manchester_a22_pressure.png", dpi=100, bbox_inches="tight")

# --- creep forces ------------------------------------------------------------------------------
try:
    creep = read(prefix + "_creep.csv")
except FileNotFoundError:
    creep = []
MODELS = (("nss", "tab:green", "o"), ("steady", "tab:blue", "s"), ("shen_li", "tab:purple", "^"))
if creep:
    print()
    print("| wheel | y (mm) | zone | fn (kN) | a/b | exact fx / fs (N), mz (N m) | "
          "nss fx / fs / mz error (%) | steady fx / fs error (%) | shen-li fx / fs error (%) | "
          "CONTACT fx / fs (N), mz (N m) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in creep:
        def err(m, c):
            return f"{num(r, m + '_err_' + c + '_pct'):+.1f}"

        status = r["nss_status"]
        nss = (f"{err('nss', 'fx')} / {err('nss', 'fs')} / {err('nss', 'mz')}"
               + ("" if status == "ok" else f" ({status})"))
        ref = not math.isnan(num(r, "contact_fn_N"))
        contact = (f"{num(r, 'contact_fx_N'):.0f} / {num(r, 'contact_fs_N'):.0f}, "
                   f"{num(r, 'contact_mz_Nm'):.2f}") if ref else "-"
        print(f"| {r['wheel']} | {num(r, 'y_mm'):.1f} | {r['zone']} | {num(r, 'fn_N') / 1e3:.2f} | "
              f"{num(r, 'a_mm') / num(r, 'b_mm'):.2f} | {num(r, 'exact_fx_N'):.0f} / "
              f"{num(r, 'exact_fs_N'):.0f}, {num(r, 'exact_mz_Nm'):.2f} | {nss} | "
              f"{err('steady', 'fx')} / {err('steady', 'fs')} | "
              f"{err('shen_li', 'fx')} / {err('shen_li', 'fs')} | {contact} |")

    fig, axes = plt.subplots(4, 2, figsize=(13, 14), sharex=True)
    rows_of = (("fx_N", "fx [N]"), ("fs_N", "fs [N]"), ("mz_Nm", "mz [N m]"))
    for col, wheel in enumerate(("right", "left")):
        mine = [r for r in creep if r["wheel"] == wheel]
        for row, (key, label) in enumerate(rows_of):
            ax = axes[row][col]
            for zone, colour in (("tread", "k"), ("corner", "tab:orange"), ("flange", "tab:red")):
                z = [r for r in mine if r["zone"] == zone]
                if z:
                    ax.plot([num(r, "y_mm") for r in z], [num(r, "exact_" + key) for r in z], "-",
                            color=colour, lw=1.5, label=f"exact, {zone}")
            for m, colour, marker in MODELS:
                ax.plot([num(r, "y_mm") for r in mine], [num(r, f"{m}_{key}") for r in mine],
                        marker, color=colour, ms=4, mfc="none", ls="none",
                        label=m.replace("_", "-") + " (WheelsetContact)")
            ref = [r for r in mine if not math.isnan(num(r, "contact_fn_N"))]
            ax.plot([num(r, "y_mm") for r in ref], [num(r, "contact_" + key) for r in ref], "x",
                    color="grey", ms=7, label="CONTACT (published, its own fn)")
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
            if row == 0:
                ax.set_title(f"{wheel} wheel")
                ax.legend(fontsize=7)
        ax = axes[3][col]
        for m, colour, marker in MODELS:
            e = [max(abs(num(r, f"{m}_err_fx_pct")), abs(num(r, f"{m}_err_fs_pct"))) for r in mine]
            ax.semilogy([num(r, "y_mm") for r in mine], np.maximum(e, 1e-2), marker, color=colour,
                        ms=5, mfc="none", label=m.replace("_", "-"))
        ax.axhline(5.0, color="r", lw=1, ls="--", label="target 5 % (nss)")
        ax.set_ylabel("max |error| of fx, fs [% of mu fn]")
        ax.set_xlabel("wheelset lateral displacement y [mm] (benchmark's axes, to the right)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Manchester benchmark A-2.2: creep forces on each patch (contact frame, on the "
                 "wheel), models against the exact tangential solution on the same patch", y=0.995)
    fig.tight_layout()
    fig.savefig(f"{figdir}/manchester_a22_creep.png", dpi=90)
