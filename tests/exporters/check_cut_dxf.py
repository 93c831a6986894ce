#!/usr/bin/python3
"""Checks a laminate's DIR/cut.dxf (plyfit laminate) against DIR/plybook.json and each ply's
own DIR/<ply>/flat.dxf, reading them with ezdxf:

- the file passes ezdxf's audit with no error and no fix;
- layers: ROLL, holding the roll's two edges (x = 0 and x = roll width), and one layer per
  draped ply named after it; no layer for a ply that was not draped;
- each ply's closed polylines are its flat.dxf OUTLINE and HOLES loops moved by one offset
  (not turned: the grain is kept), their area (outer minus holes) the ply book's flat area;
- the plies' boxes lie inside the roll and no two overlap;
- each ply is labelled on its layer: its name, angle and material, and the grain arrow
  ("WARP" and three lines);
- a ply split for its roll (plybook.json `pieces`) is its pieces instead, each a part as above
  on a layer named after it, its loops flat.dxf's PIECE_<name> loops moved, its area the
  piece's, its label "PIECE: <name> (PLY <ply>, SEQ n)".

usage: check_cut_dxf.py DIR
"""
import json
import os
import sys

import ezdxf
from ezdxf import recover

from check_report import finish

REL = 1e-9     # relative tolerance of coordinates written in shortest exact decimal form
AREA_REL = 1e-6


def area(pts):
    s = 0.0
    for k in range(len(pts)):
        (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % len(pts)]
        s += x0 * y1 - x1 * y0
    return 0.5 * s


def loops_on(msp, layers):
    out = []
    for e in msp.query("LWPOLYLINE"):
        if e.dxf.layer in layers and e.closed:
            out.append([(p[0], p[1]) for p in e.get_points("xy")])
    return out


def box(loops):
    xs = [p[0] for l in loops for p in l]
    ys = [p[1] for l in loops for p in l]
    return min(xs), min(ys), max(xs), max(ys)


def check_part(msp, d, ply, part, problems):
    """A part on the roll: a whole ply (part None) or a piece of a ply split for its roll."""
    name = part["name"] if part else ply["name"]
    cut = loops_on(msp, {name})
    flat_layers = {"PIECE_" + name} if part else {"OUTLINE", "HOLES"}
    flat = loops_on(ezdxf.readfile(os.path.join(d, ply["name"], "flat.dxf")).modelspace(),
                    flat_layers)
    if len(cut) != len(flat) or not cut:
        problems.append(f"{name}: {len(cut)} loops in cut.dxf, {len(flat)} in flat.dxf")
        return None
    dx = cut[0][0][0] - flat[0][0][0]
    dy = cut[0][0][1] - flat[0][0][1]
    scale = max(abs(c) for l in cut for p in l for c in p) + 1.0
    for lc, lf in zip(cut, flat):
        if len(lc) != len(lf) or any(abs(a[0] - b[0] - dx) > REL * scale or
                                     abs(a[1] - b[1] - dy) > REL * scale
                                     for a, b in zip(lc, lf)):
            problems.append(f"{name}: a loop is not flat.dxf's moved by one offset (turned?)")
            return None
    a = sum(area(l) for l in cut)
    want = part["area_mm2"] if part else ply["flat_area_mm2"]
    if abs(a - want) > AREA_REL * want:
        problems.append(f"{name}: area {a} against the ply book's {want}")
    texts = [t.dxf.text for t in msp.query("TEXT") if t.dxf.layer == name]
    angle = f"{ply['angle_deg']:.2f}".rstrip("0").rstrip(".")
    if angle == "-0":
        angle = "0"
    first = f"PIECE: {name} (PLY {ply['name']}, " if part else f"PLY: {name} "
    for want in (first, "ANGLE: " + angle, "MATERIAL: " + ply["material"], "WARP"):
        if not any(t.startswith(want) for t in texts):
            problems.append(f"{name}: no label starting {want!r} (has {texts})")
    lines = [e for e in msp.query("LINE") if e.dxf.layer == name]
    if len(lines) != 3:
        problems.append(f"{name}: {len(lines)} grain arrow lines, not 3")
    return box(cut)


def main():
    d = sys.argv[1]
    book = json.load(open(os.path.join(d, "plybook.json")))
    doc, auditor = recover.readfile(os.path.join(d, "cut.dxf"))
    problems = [f"audit: {e}" for e in auditor.errors] + [f"audit fix: {f}" for f in auditor.fixes]
    msp = doc.modelspace()
    w = book["roll_width_mm"]
    drawn = [p for p in book["plies"] if p["status"] in ("ok", "partial")]
    layers = {l.dxf.name for l in doc.layers} - {"0", "Defpoints"}
    parts = [(p, q) for p in drawn for q in (p.get("pieces") or [None])]
    if layers != {"ROLL"} | {q["name"] if q else p["name"] for p, q in parts}:
        problems.append(f"layers {sorted(layers)}")
    edges = sorted(round(e.dxf.start[0], 9) for e in msp.query("LINE") if e.dxf.layer == "ROLL")
    if edges != [0.0, round(w, 9)]:
        problems.append(f"roll edges at x = {edges}, not 0 and {w}")
    boxes = {}
    for p, q in parts:
        b = check_part(msp, d, p, q, problems)
        if b:
            boxes[q["name"] if q else p["name"]] = b
    for n, (x0, y0, x1, y1) in boxes.items():
        if x0 < 0 or x1 > w or y0 < 0:
            problems.append(f"{n}: box {x0, y0, x1, y1} outside the roll [0, {w}]")
    names = sorted(boxes)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            (ax0, ay0, ax1, ay1), (bx0, by0, bx1, by1) = boxes[a], boxes[b]
            if min(ax1, bx1) > max(ax0, bx0) and min(ay1, by1) > max(ay0, by0):
                problems.append(f"{a} and {b}: boxes overlap")
    return finish("check_cut_dxf", os.path.join(d, "cut.dxf"), problems,
                  f"{len(boxes)} plies on a {w} mm roll, audit clean")


if __name__ == "__main__":
    sys.exit(main())
