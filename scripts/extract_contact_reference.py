#!/usr/bin/env python3
"""Extracts CONTACT's published results for the Manchester benchmark's case A-2.2 into a CSV.

usage: extract_contact_reference.py RIGHT_REF_OUT LEFT_REF_OUT OUT_CSV

RIGHT_REF_OUT, LEFT_REF_OUT: CONTACT's output files examples/mbench_a22_right.ref_out and
examples/mbench_a22_left.ref_out of the repository eve70a/CONTACT (or the same blocks of them:
each case's "Case", "WHEEL-RAIL CONTACT", "WHEEL-SET POSITION", "TOTAL FORCES AND MOMENTS ON RAIL"
and, per patch, "DATA FOR CONTACT PATCH", "CONTACT REFERENCE LOCATION", "KINEMATIC CONSTANTS" and
"TOTAL FORCES, TORSIONAL MOMENT" blocks, as printed). Writes one row per wheel, case and patch, in
CONTACT's own units and signs (test/data/profiles/contact_a22_reference.csv; its header says
which). Checks each case before writing: the patches' normal and lateral forces, turned by their
contact angles, add up to the vertical force on the rail CONTACT prints, within the rounding of
its four printed digits; a case that does not is an error, so a misread number cannot pass.
"""
import math
import re
import sys

# (block title, column names in the order printed, the row's place after the title)
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[Ee][-+]?\d+)?"


def numbers(line):
    return [float(x) for x in re.findall(NUMBER, line)]


def table(lines, i, names):
    """The values under the header line at i+1 (names as printed), read into a dict."""
    header = lines[i + 1].split()
    if header != names:
        raise ValueError(f"line {i + 2}: expected columns {names}, found {header}")
    values = numbers(lines[i + 2])
    if len(values) != len(names):
        raise ValueError(f"line {i + 3}: expected {len(names)} numbers, found {lines[i + 2]!r}")
    return dict(zip(names, values))


def parse(path, wheel):
    lines = open(path).read().splitlines()
    revision = next((ln.strip(" |") for ln in lines if "$Revision" in ln), None)
    if revision is None:
        raise ValueError(f"{path}: no revision line")
    cases, case, patch = [], None, None
    for i, ln in enumerate(lines):
        s = ln.strip()
        m = re.match(r"Case\s+(\d+)$", s)
        if m:
            case = {"case": int(m.group(1)), "patches": []}
            cases.append(case)
            continue
        m = re.match(r"WHEEL-RAIL CONTACT, (LEFT|RIGHT) WHEEL,\s+(\d+) CONTACT PATCH", s)
        if m:
            if m.group(1).lower() != wheel:
                raise ValueError(f"{path}:{i + 1}: a {m.group(1)} wheel in the {wheel} file")
            case["npatch"] = int(m.group(2))
        elif s == "WHEEL-SET POSITION AND VELOCITY":
            case["pos"] = table(lines, i, ["S_WS", "Y_WS", "Z_WS", "ROLL_WS", "YAW_WS",
                                           "PITCH_WS"])
        elif s == "TOTAL FORCES AND MOMENTS ON RAIL":
            case["total"] = table(lines, i, ["FX(TR)", "FY(TR)", "FZ(TR)", "FX(WS)", "FY(WS)",
                                             "FZ(WS)"])
        elif s.startswith("----- DATA FOR CONTACT PATCH"):
            patch = {"patch": int(numbers(s)[0])}
            case["patches"].append(patch)
        elif s == "CONTACT REFERENCE LOCATION":
            patch.update(table(lines, i, ["XCP(TR)", "YCP(TR)", "ZCP(TR)", "DELTCP(TR)",
                                          "YCP(R)", "ZCP(R)"]))
            j = i + 3
            while lines[j].split() != ["XCP(W)", "YCP(W)", "ZCP(W)"]:
                j += 1
            patch.update(table(lines, j - 1, ["XCP(W)", "YCP(W)", "ZCP(W)"]))
        elif s == "KINEMATIC CONSTANTS":
            patch.update(table(lines, i, ["CHI", "DQ", "VELOC", "CKSI", "CETA", "CPHI"]))
        elif s.startswith("TOTAL FORCES, TORSIONAL MOMENT"):
            patch.update(table(lines, i, ["FN", "FX", "FS", "MN", "ELAST.EN.", "FRIC.POWER"]))
            patch.update(table(lines, i + 2, ["FN/G", "FX/FSTAT/FN", "FS/FSTAT/FN", "APPROACH",
                                              "PMAX"]))
    for c in cases:
        if len(c["patches"]) != c.get("npatch", -1):
            raise ValueError(f"{path}: case {c['case']}: {c.get('npatch')} patches announced, "
                             f"{len(c['patches'])} read")
        check(path, c)
    return revision, cases


def check(path, c):
    """FZ(TR) = sum over patches of FN cos(delta) + FS sin(delta): the patch forces' vertical
    components (CONTACT's contact angle DELTCP about the track's x axis, z down)."""
    fz = sum(p["FN"] * math.cos(p["DELTCP(TR)"]) + p["FS"] * math.sin(p["DELTCP(TR)"])
             for p in c["patches"])
    fy = sum(-p["FN"] * math.sin(p["DELTCP(TR)"]) + p["FS"] * math.cos(p["DELTCP(TR)"])
             for p in c["patches"])
    total = c["total"]
    # FN is printed with four digits (1.544E+04): up to 5 N of rounding per 10 kN.
    tol_z = 1e-3 * total["FZ(TR)"] + 5.0 * len(c["patches"])
    tol_y = 1e-3 * max(abs(total["FY(TR)"]), 1e3) + 10.0 * len(c["patches"])
    if abs(fz - total["FZ(TR)"]) > tol_z or abs(fy - total["FY(TR)"]) > tol_y:
        raise ValueError(f"{path}: case {c['case']}: the patches' forces add up to FY {fy:.1f}, "
                         f"FZ {fz:.1f} N, CONTACT prints FY {total['FY(TR)']:.1f}, "
                         f"FZ {total['FZ(TR)']:.1f} N")
    return fz, fy


COLUMNS = [
    ("wheel", None), ("case", None), ("y_ws_mm", "Y_WS"), ("yaw_ws_rad", "YAW_WS"),
    ("roll_ws_rad", "ROLL_WS"), ("z_ws_mm", "Z_WS"), ("patch", None),
    ("xcp_tr_mm", "XCP(TR)"), ("ycp_tr_mm", "YCP(TR)"), ("zcp_tr_mm", "ZCP(TR)"),
    ("deltcp_tr_rad", "DELTCP(TR)"), ("ycp_r_mm", "YCP(R)"), ("zcp_r_mm", "ZCP(R)"),
    ("ycp_w_mm", "YCP(W)"), ("zcp_w_mm", "ZCP(W)"), ("cksi", "CKSI"), ("ceta", "CETA"),
    ("cphi_per_mm", "CPHI"), ("fn_N", "FN"), ("fx_N", "FX"), ("fs_N", "FS"), ("mn_Nmm", "MN"),
    ("approach_mm", "APPROACH"), ("pmax_MPa", "PMAX"),
]


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    rows, revisions = [], []
    for wheel, path in (("right", sys.argv[1]), ("left", sys.argv[2])):
        revision, cases = parse(path, wheel)
        revisions.append(revision)
        for c in cases:
            for p in c["patches"]:
                row = []
                for name, key in COLUMNS:
                    if name == "wheel":
                        row.append(wheel)
                    elif name == "case":
                        row.append(str(c["case"]))
                    elif name == "patch":
                        row.append(str(p["patch"]))
                    else:
                        row.append(f"{(c['pos'] if key in c['pos'] else p)[key]:.10g}")
                rows.append(row)
        print(f"{path}: {len(cases)} cases, {sum(len(c['patches']) for c in cases)} patches, "
              f"forces add up on every case", file=sys.stderr)
    header = f"""# CONTACT's published results for the Manchester contact benchmark, case A-2.2 (reference points
# shown beside ours, never tuning targets). Source: repository eve70a/CONTACT (open-source edition of
# CONTACT, Vtech CMCC, Apache License 2.0), examples/mbench_a22_right.ref_out and
# examples/mbench_a22_left.ref_out; the files' revision line: {' / '.join(sorted(set(revisions)))}.
# Extracted by scripts/extract_contact_reference.py. One row per wheel, case and contact patch, in CONTACT's
# own units and signs: lengths mm (y_ws, z_ws: the wheelset's lateral and vertical position, y to the right,
# z down; xcp/ycp/zcp_tr: the patch's contact reference point in track coordinates; ycp/zcp_r: on the rail
# profile, ycp/zcp_w: on the wheel profile, both in the profile files' own coordinates, the left side mirrored),
# angles rad (deltcp_tr: the contact angle, roll of the contact plane about the track's x axis), cksi and ceta
# dimensionless, cphi 1/mm, forces N (fn normal; fx, fs tangential, longitudinal and lateral in the contact
# plane, as CONTACT prints them), mn N mm, approach mm, pmax MPa. The left wheel is the same wheelset state's
# left wheel (not the mirrored case)."""
    with open(sys.argv[3], "w") as f:
        f.write(header + "\n")
        f.write(",".join(n for n, _ in COLUMNS) + "\n")
        for row in rows:
            f.write(",".join(row) + "\n")


if __name__ == "__main__":
    main()
