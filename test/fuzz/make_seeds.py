#!/usr/bin/env python3
"""Writes the committed seed corpora of the fuzz targets (test/fuzz/corpus/<target>/).

fuzz_contact_step decodes its bytes with libFuzzer's FuzzedDataProvider, which takes every choice
from the END of the data: a seed is its choices in decoding order, reversed. The encoder below
mirrors Decoder / decodeParameters / decodeInput in fuzz_contact_step.cpp (keep them in step);
doubles are encoded as raw bits (Decoder::value case 3), so every seed value is exact.
fuzz_scenario_csv seeds are text: the shipped scenes, cut-down scenes and malformed variants.
usage: make_seeds.py   (rewrites the generated seeds of both corpus folders)
"""
import math
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
MODELS = ["steady", "shen-li", "nss", "exact"]
PAPER = dict(G=1e6, nu=0.28, mu=0.4013, a0=0.02, b0=0.02, fz0=470.5, nx=20, ny=20, fz_max=588.125)
DEFAULT_INPUT = dict(dt=1e-3, V=20.0, xi=2e-3, eta=0.0, phi=0.0, fz=8e4)
FIELDS = ["dt", "V", "xi", "eta", "phi", "fz"]


class Encoder:
    def __init__(self):
        self.choices = []  # bytes in the order the decoder consumes them

    def pick(self, k):
        self.choices.append(k)

    def flag(self, b):
        self.choices.append(1 if b else 0)

    def value(self, x):
        self.pick(3)  # raw bits: ConsumeIntegral<uint64_t> takes the most significant byte first
        self.choices.extend(struct.pack(">d", x))

    def param(self, x):  # Decoder::param, raw bits (case 2); x within 2^+-30 of the default
        self.flag(x is not None)
        if isinstance(x, tuple):  # ("special", k): kSpecial[k] * default (0, -1, NaN, Inf)
            self.pick(1)
            self.pick(x[1])
        elif x is not None:
            self.pick(2)
            self.choices.extend(struct.pack(">d", x))

    def data(self):
        return bytes(reversed(self.choices))


def encode(model="steady", mesh="fixed", nx=20, ny=20, params=None, steps=(), chi_missing=False):
    """steps: dicts of changed input fields; a dict with reset=True calls reset() first."""
    params = params or {}
    e = Encoder()
    e.pick(MODELS.index(model))
    e.flag(mesh == "adaptive")
    e.pick(max(nx, 2) - 2)
    e.flag(nx < 2)
    if nx < 2:
        e.pick(2 - nx)
    e.pick(max(ny, 1) - 1)
    e.flag(ny < 1)
    if ny < 1:
        e.pick(1 - ny)
    for name in ["G", "nu", "mu", "a0", "b0", "fz0"]:
        e.param(params.get(name))
    e.flag("fz_max" in params)
    if "fz_max" in params:
        e.param(params["fz_max"])
    e.pick(15 if chi_missing else 0)
    e.pick(len(steps))
    for s in steps:
        e.pick(7 if s.get("reset") else 0)
        for f in FIELDS:
            e.flag(f in s)
            if f in s:
                e.value(s[f])
        # Per-step geometry (a and b together) and friction: decodeInput's pick(4) == 3 gives them.
        e.pick(3 if "a" in s or "b" in s else 0)
        if "a" in s or "b" in s:
            a, b = s.get("a", 0.0), s.get("b", 0.0)
            e.flag(a == 0.0)
            if a != 0.0:
                e.value(a)
            e.pick(7 if b == 0.0 else 0)
            if b != 0.0:
                e.value(b)
        e.pick(3 if "mu" in s else 0)
        if "mu" in s:
            e.flag(s["mu"] == 0.0)
            if s["mu"] != 0.0:
                e.value(s["mu"])
    return e.data()


def paper_scene(kind, n, model="nss", mesh="fixed", nx=20, ny=20):
    """n rows of the paper's scenes (scripts/make_scenes.py), one element of travel per step."""
    a, v, lam = 0.02, 0.025, 0.2
    dt = (2 * a / 20) / v
    steps = []
    for k in range(n):
        c = math.cos(2 * math.pi * v * k * dt / lam)
        if kind == "combined":
            s = dict(xi=0.052 * c, eta=-0.052 * c, phi=1.0, fz=470.5)
        else:
            s = dict(xi=0.052, eta=0.0, phi=0.0,
                     fz=470.5 * (1 + 0.25 * math.sin(2 * math.pi * v * k * dt / lam)))
        if k == 0:
            s.update(dt=dt, V=v)
        steps.append(s)
    return encode(model, mesh, nx, ny, PAPER, steps)


def step_seeds():
    nan, inf = float("nan"), float("inf")
    seeds = {}
    for model in MODELS:
        for mesh in ["fixed", "adaptive"]:
            if model == "exact" and mesh == "adaptive":
                continue
            grid = 6 if model == "exact" else 20
            seeds[f"{model}_{mesh}_defaults"] = encode(model, mesh, grid, grid, steps=[{}, {}, {}])
    for model in ["shen-li", "nss"]:
        for mesh in ["fixed", "adaptive"]:
            seeds[f"{model}_{mesh}_paper_combined"] = paper_scene("combined", 12, model, mesh)
            seeds[f"{model}_{mesh}_paper_varying_load"] = paper_scene("varying", 12, model, mesh)
    seeds["exact_paper_combined"] = paper_scene("combined", 4, "exact", "fixed", 6, 6)
    seeds["steady_paper_combined"] = paper_scene("combined", 8, "steady")
    # Inputs at the edges of the step rules, through every model.
    edges = [dict(xi=nan), dict(eta=inf), dict(phi=-inf), dict(dt=-1e-3), dict(dt=0.0),
             dict(V=0.0), dict(V=-20.0), dict(fz=0.0), dict(fz=-1.0), dict(fz=8e4, xi=1e300),
             dict(xi=-1e-300, eta=5e-324), dict(fz=1e-300), dict(fz=1e300), dict(dt=1e300),
             dict(V=1e-300), dict(dt=1e-3, V=20.0, xi=2e-3, fz=8e4)]
    for model in MODELS:
        grid = 5 if model == "exact" else 12
        seeds[f"{model}_edge_inputs"] = encode(model, "fixed", grid, grid, steps=[{}] + edges[:11])
        seeds[f"{model}_extreme_inputs"] = encode(model, "fixed", grid, grid,
                                                  steps=[{}] + edges[11:] + [{}])
    # Load jumps and dt = 0 after a saturated step (history kept, patch resized).
    jump = [dict(xi=0.05, eta=0.05), dict(fz=2e4), dict(dt=0.0, fz=1.5e5), dict(dt=0.0, fz=1e3),
            dict(dt=1e-3, fz=8e4), dict(reset=True), {}]
    for model in ["steady", "shen-li", "nss"]:
        for mesh in ["fixed", "adaptive"]:
            seeds[f"{model}_{mesh}_load_jumps"] = encode(model, mesh, 16, 10, steps=jump)
    # Parameters at the edges of validate().
    seeds["mesh_nx1_invalid"] = encode("steady", "fixed", 1, 20, steps=[{}])
    seeds["mesh_ny0_invalid"] = encode("nss", "fixed", 20, 0, steps=[{}])
    seeds["mesh_60x60_nss"] = encode("nss", "adaptive", 60, 60, steps=[{}, dict(fz=1.2e5)])
    seeds["mesh_2x1_shenli"] = encode("shen-li", "fixed", 2, 1, steps=[{}, {}, dict(phi=3.0)])
    seeds["mu_zero"] = encode("nss", "fixed", 10, 10, dict(mu=("special", 0)),
                              steps=[{}, {}, dict(eta=1e-3)])
    seeds["a_over_b_10"] = encode("nss", "adaptive", 10, 10, dict(a0=0.04, b0=0.004),
                                  steps=[{}, dict(fz=4e4)])
    seeds["a_over_b_0.1"] = encode("shen-li", "fixed", 10, 10, dict(a0=0.0004, b0=0.004),
                                   steps=[{}, dict(fz=4e4)])
    seeds["nu_half"] = encode("steady", "fixed", 10, 10, dict(nu=0.5), steps=[{}])
    seeds["G_nan_invalid"] = encode("steady", "fixed", 10, 10, dict(G=("special", 2)), steps=[{}])
    seeds["fz_max_small"] = encode("nss", "fixed", 10, 10, dict(fz_max=1e3), steps=[{}, {}])
    seeds["exact_fz_above_max"] = encode("exact", "fixed", 4, 4, dict(fz_max=9e4),
                                         steps=[{}, dict(fz=1e5), {}])
    seeds["chi_table_missing"] = encode("nss", "fixed", 10, 10, steps=[{}], chi_missing=True)
    return seeds


def csv_seeds():
    seeds = {}
    for scene in sorted((ROOT / "scenes").glob("*.csv")):
        text = scene.read_text()
        seeds[f"scene_{scene.stem}"] = text
        seeds[f"scene_{scene.stem}_head"] = "".join(text.splitlines(True)[:12])
    header = "t,V,xi,eta,phi,fz\n"
    row = "0,20,0.002,-0.002,1,80000\n"
    seeds.update({
        "minimal": header + row,
        "header_only": header,
        "empty": "",
        "comments_blank_lines": "# c\n\n  \n" + header + "# mid\n" + row + "\n",
        "column_order_extra": "fz,extra,t,V,xi,eta,phi\n1e4,x,0,10,1e-3,0,0.5\n2e4,y,0.1,10,0,0,0\n",
        "crlf": (header + row + "0.1,20,0,0,0,1\n").replace("\n", "\r\n"),
        "spaces_tabs": " t , V ,xi,\teta,phi, fz \n 0 , 20 , 0 , 0 , 0 , 1 \n",
        "trailing_comma": "t,V,xi,eta,phi,fz,\n0,20,0,0,0,1,\n",
        "missing_column": "t,V,xi,eta,phi\n0,1,0,0,0\n",
        "missing_value": header + "0,1,0,0,0\n",
        "empty_cell": header + "0,1,0,,0,1\n",
        "not_a_number": header + "0,1,abc,0,0,1\n",
        "nan_inf": header + "0,nan,0,0,0,1\n1,inf,0,0,0,1\n2,-infinity,0,0,0,1\n",
        "overflow": header + "0,1e999,0,0,0,1\n",
        "hex_float": header + "0x0p0,0x1.4p4,0,0,0,0x1p16\n",
        "time_not_increasing": header + "0,1,0,0,0,1\n0,1,0,0,0,1\n",
        "time_decreasing": header + "1,1,0,0,0,1\n0.5,1,0,0,0,1\n",
        "extremes": header + "-1e308,1e308,-1e308,1e308,-1e308,1e308\n1e308,0,5e-324,0,0,-0\n",
        "negative_load_speed": header + "0,-20,0,0,0,-1\n0.1,20,0,0,0,0\n0.2,20,1,1,1,1\n",
        "duplicate_header": "t,t,V,xi,eta,phi,fz,fz\n0,1,2,0,0,0,1,2\n",
        "header_twice": header + header + row,
        "only_commas": ",,,,,\n,,,,,\n",
    })
    return {k: v.encode() for k, v in seeds.items()}


def write(folder, seeds):
    """Writes the generated seeds; inputs kept from fuzzing findings sit beside them, untouched."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, data in seeds.items():
        (folder / name).write_bytes(data)
    print(f"{folder.relative_to(ROOT)}: {len(seeds)} seeds")


if __name__ == "__main__":
    write(HERE / "corpus" / "fuzz_contact_step", step_seeds())
    write(HERE / "corpus" / "fuzz_scenario_csv", csv_seeds())
