#!/usr/bin/python3
"""Reads DIR/flat.dxf with ezdxf (an independent DXF reader) and checks it against
DIR/report.json, as a cutter or nesting program would use it:

- no audit errors, millimetres, R2000 or later, the layers OUTLINE, HOLES, BASEPATH, ORIGIN,
  GRAIN, SHEAR_WARN and LABELS, and THREADS only when the thread grid is asked for (a cutter
  that imports every layer cuts every line: no THREADS layer at all by default);
- OUTLINE holds closed counter-clockwise polylines, HOLES closed clockwise ones, and their
  signed areas add up to flat_outline.area within 1e-9 relative (as many loops and holes as
  report.json lists);
- THREADS lines (when present) lie inside the outline and end on it;
- the labels (PLY, MATERIAL, PLY ANGLE, SPACING, AREA, SHEAR, MOLD) and the grain arrow lie
  inside the outline: every TEXT's insertion point and its extents (one text height per
  character, \\U+XXXX counted as one), and every GRAIN line's ends;
- no label holds a folder: no word of a label starts with '/' or a drive or holds the mold's
  folder, and the MOLD label names the mold file alone;
- the degree sign is a real character: the file declares $DWGCODEPAGE ANSI_1252, its bytes
  hold 0xB0 (the sign in cp1252), ezdxf decodes the PLY ANGLE and SHEAR labels to U+00B0,
  and no AutoCAD %%d code is left; the PLY ANGLE label shows inputs.ply_angle_deg;
- SHEAR_WARN closed polylines present or absent as expected;
- a ply split for the roll (report.json `pieces`): OUTLINE and HOLES empty, each piece's loops
  on PIECE_<name> with the piece's area, its label inside it, its seams on SEAMS.

usage: check_dxf.py DIR --shear-warn yes|no [--threads yes|no]
"""
import argparse
import json
import math
import os
import re
import sys

import ezdxf

from check_report import finish  # same folder

AREA_REL = 1e-9          # outline area as in report.json to 1e-9 relative
INSIDE_REL = 1e-9        # a THREADS line ends on the outline within this fraction of its size
LABEL_ROUNDING = 5e-4    # the AREA label shows three decimals
ANGLE_ROUNDING = 5e-3    # the PLY ANGLE label shows two decimals
LAYERS = ["OUTLINE", "HOLES", "BASEPATH", "ORIGIN", "GRAIN", "SHEAR_WARN", "LABELS"]
LABEL_KEYS = ["PLY", "MATERIAL", "PLY ANGLE", "SPACING", "AREA", "SHEAR", "MOLD"]
DEGREE = "\u00b0"


def signed_area(pts):
    a = 0.0
    for k in range(len(pts)):
        x0, y0 = pts[k]
        x1, y1 = pts[(k + 1) % len(pts)]
        a += x0 * y1 - x1 * y0
    return 0.5 * a


def inside(loops, x, y):
    """Even-odd point-in-polygon test over all loops (holes are outside)."""
    c = False
    for pts in loops:
        for k in range(len(pts)):
            x0, y0 = pts[k]
            x1, y1 = pts[(k + 1) % len(pts)]
            if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
                c = not c
    return c


def dist_to_loops(loops, x, y):
    best = float("inf")
    for pts in loops:
        for k in range(len(pts)):
            x0, y0 = pts[k]
            x1, y1 = pts[(k + 1) % len(pts)]
            dx, dy = x1 - x0, y1 - y0
            L = dx * dx + dy * dy
            t = 0.0 if L == 0 else max(0.0, min(1.0, ((x - x0) * dx + (y - y0) * dy) / L))
            px, py = x0 + t * dx, y0 + t * dy
            best = min(best, ((x - px) ** 2 + (y - py) ** 2) ** 0.5)
    return best


def segments_cross(p, q, r, s):
    """Do the closed segments pq and rs meet?"""
    def orient(a, b, c):
        v = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        return (v > 0) - (v < 0)

    def on(a, b, c):
        return min(a[0], b[0]) <= c[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= c[1] <= max(a[1], b[1])

    o1, o2, o3, o4 = orient(p, q, r), orient(p, q, s), orient(r, s, p), orient(r, s, q)
    if o1 != o2 and o3 != o4:
        return True
    return (o1 == 0 and on(p, q, r)) or (o2 == 0 and on(p, q, s)) or \
        (o3 == 0 and on(r, s, p)) or (o4 == 0 and on(r, s, q))


def box_inside(loops, x0, y0, x1, y1):
    """The box's corners inside the outline and no outline edge crossing its sides."""
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    if not all(inside(loops, x, y) for x, y in corners):
        return False
    for pts in loops:
        for k in range(len(pts)):
            a, b = pts[k], pts[(k + 1) % len(pts)]
            for m in range(4):
                if segments_cross(a, b, corners[m], corners[(m + 1) % 4]):
                    return False
    return True


def decoded(text):
    """TEXT content with AutoCAD's \\U+XXXX escapes decoded (ezdxf 0.18 keeps them)."""
    return re.sub(r"\\U\+([0-9A-Fa-f]{4})", lambda m: chr(int(m.group(1), 16)), text)


def text_box(e):
    """A TEXT's extents: one text height per character along the baseline (wider than the
    capitals and digits of AutoCAD's and LibreCAD's fonts) and one text height across, from
    the insertion point, for rotations 0 and 90 degrees."""
    p, h = e.dxf.insert, e.dxf.height
    n = len(decoded(e.dxf.text))
    rot = e.dxf.get("rotation", 0.0)
    assert rot in (0.0, 90.0), "rotation %r" % rot
    if rot == 90.0:
        return p.x - h, p.y, p.x, p.y + n * h
    return p.x, p.y, p.x + n * h, p.y + h


def outline_loops(msp, report, check):
    """OUTLINE (counter-clockwise) and HOLES (clockwise) loops, counted against report.json."""
    loops = []
    outer = holes = 0
    for layer, sign in (("OUTLINE", 1), ("HOLES", -1)):
        for e in msp.query("*[layer=='%s']" % layer):
            check(e.dxftype() == "LWPOLYLINE", "%s holds a %s" % (layer, e.dxftype()))
            if e.dxftype() != "LWPOLYLINE":
                continue
            check(e.closed, "%s polyline not closed" % layer)
            pts = [(p[0], p[1]) for p in e.get_points("xy")]
            check(signed_area(pts) * sign > 0, "%s loop runs the wrong way (area %r)" % (layer, signed_area(pts)))
            loops.append(pts)
            outer += sign > 0
            holes += sign < 0
    report_loops = report["flat_outline"]["loops"]
    check(outer == sum(1 for l in report_loops if not l["hole"]),
          "%d OUTLINE loops, report.json has %d outer loops" % (outer, sum(1 for l in report_loops if not l["hole"])))
    check(holes == sum(1 for l in report_loops if l["hole"]),
          "%d HOLES loops, report.json has %d holes" % (holes, sum(1 for l in report_loops if l["hole"])))
    return loops


def check_pieces(msp, names, report, check):
    """A ply split for the roll: each piece's closed loops on PIECE_<name> with the piece's
    area, its label inside it, and a SEAMS line per seam."""
    for piece in report["pieces"]:
        layer = "PIECE_" + piece["name"]
        check(layer in names, "layer %s missing" % layer)
        plines = [e for e in msp.query("LWPOLYLINE") if e.dxf.layer == layer]
        check(len(plines) == len(piece["loops"]),
              "%s: %d loops, report.json %d" % (layer, len(plines), len(piece["loops"])))
        ploops = [[(p[0], p[1]) for p in e.get_points("xy")] for e in plines]
        for e in plines:
            check(e.closed, "%s polyline not closed" % layer)
        total = sum(signed_area(p) for p in ploops)
        check(abs(total - piece["area"]) <= AREA_REL * piece["area"],
              "%s area %.17g, report.json %.17g" % (layer, total, piece["area"]))
        texts = [e for e in msp.query("TEXT") if e.dxf.layer == layer]
        check(any(decoded(t.dxf.text) == "PIECE: " + piece["name"] for t in texts),
              "%s: no label PIECE: %s" % (layer, piece["name"]))
        for t in texts:
            p = t.dxf.insert
            check(inside(ploops, p.x, p.y), "%s label outside the piece" % layer)
    seams = [e for e in msp.query("LINE") if e.dxf.layer == "SEAMS"]
    check(len(seams) >= len(report["splices"]["seams"]),
          "%d SEAMS lines for %d seams" % (len(seams), len(report["splices"]["seams"])))
    for e in seams:
        x = e.dxf.start.x
        check(any(abs(x - s["x"]) <= AREA_REL * max(1.0, abs(x)) for s in report["splices"]["seams"]),
              "SEAMS line at x = %r is no seam of report.json" % x)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--threads", choices=["yes", "no"], default="no")
    ap.add_argument("--shear-warn", choices=["yes", "no"], required=True)
    a = ap.parse_args()
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    path = os.path.join(a.dir, "flat.dxf")
    with open(os.path.join(a.dir, "report.json"), encoding="utf-8") as f:
        report = json.load(f)
    with open(path, "rb") as f:
        raw = f.read()
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    check(len(auditor.errors) == 0, "audit errors: %s" % [str(e) for e in auditor.errors])
    check(doc.dxfversion >= "AC1015", "DXF version %s" % doc.dxfversion)
    check(doc.header.get("$INSUNITS") == 4, "$INSUNITS is %s, not 4 (mm)" % doc.header.get("$INSUNITS"))
    check(doc.header.get("$DWGCODEPAGE") == "ANSI_1252",
          "$DWGCODEPAGE is %r, not ANSI_1252" % doc.header.get("$DWGCODEPAGE"))
    names = {layer.dxf.name for layer in doc.layers}
    for name in LAYERS:
        check(name in names, "layer %s missing" % name)
    if a.threads == "yes":
        check("THREADS" in names, "layer THREADS missing")
    else:
        check("THREADS" not in names, "layer THREADS defined, but the thread grid is off")
    msp = doc.modelspace()

    # OUTLINE (counter-clockwise) and HOLES (clockwise): closed polylines, area against report.
    # A ply split for the roll has them empty and its pieces on layers of their own instead;
    # the outline the other checks use is then report.json's cut outline.
    pieces = report.get("pieces")
    if pieces:
        for layer in ("OUTLINE", "HOLES"):
            check(not list(msp.query("*[layer=='%s']" % layer)),
                  "%s holds entities, but the ply is cut as pieces" % layer)
        check_pieces(msp, names, report, check)
        loops = [[(p[0], p[1]) for p in l["points"]] for l in report["flat_outline"]["loops"]]
    else:
        loops = outline_loops(msp, report, check)
    expected = report["flat_outline"]["area"]
    total = sum(signed_area(p) for p in loops)
    check(expected > 0, "report.json's outline area is %r" % expected)
    check(abs(total - expected) <= AREA_REL * abs(expected),
          "OUTLINE + HOLES area %.17g, report.json %.17g" % (total, expected))
    if not loops:
        print("check_dxf: %s: no outline loops" % path)
        return 1
    xs = [p[0] for l in loops for p in l]
    ys = [p[1] for l in loops for p in l]
    size = max(max(xs) - min(xs), max(ys) - min(ys))

    # THREADS: lines inside the outline, ending on it.
    threads = list(msp.query("*[layer=='THREADS']"))
    if a.threads == "yes":
        check(len(threads) > 0, "no THREADS entities")
        for e in threads:
            check(e.dxftype() == "LINE", "THREADS holds a %s" % e.dxftype())
            s, t = e.dxf.start, e.dxf.end
            check(s.x == t.x or s.y == t.y, "THREADS line not along a thread")
            check(inside(loops, 0.5 * (s.x + t.x), 0.5 * (s.y + t.y)), "THREADS line outside the outline")
            for p in (s, t):
                check(dist_to_loops(loops, p.x, p.y) <= INSIDE_REL * size,
                      "THREADS line ends off the outline at (%r, %r)" % (p.x, p.y))
    else:
        check(len(threads) == 0, "%d THREADS entities, none expected" % len(threads))

    basepath = list(msp.query("LWPOLYLINE[layer=='BASEPATH']"))
    check(len(basepath) == 1, "%d BASEPATH polylines" % len(basepath))
    origin = {e.dxftype() for e in msp.query("*[layer=='ORIGIN']")}
    check({"POINT", "CIRCLE"} <= origin, "ORIGIN holds %s" % origin)
    start = report["inputs"]["start2d"]
    points = list(msp.query("POINT[layer=='ORIGIN']"))
    check(len(points) == 1 and abs(points[0].dxf.location.x - start[0]) <= AREA_REL * size
          and abs(points[0].dxf.location.y - start[1]) <= AREA_REL * size, "ORIGIN point is not the start")

    # The grain arrow: a shaft along +y (the warp) with a head, and its text, inside the outline.
    grain_lines = list(msp.query("LINE[layer=='GRAIN']"))
    check(len(grain_lines) >= 3, "%d GRAIN lines (a shaft and a head expected)" % len(grain_lines))
    shafts = [e for e in grain_lines if e.dxf.start.x == e.dxf.end.x and e.dxf.end.y > e.dxf.start.y]
    check(len(shafts) == 1, "%d GRAIN shafts pointing along +y" % len(shafts))
    for e in grain_lines:
        for p in (e.dxf.start, e.dxf.end):
            check(inside(loops, p.x, p.y), "GRAIN line end (%r, %r) outside the outline" % (p.x, p.y))

    # Labels: inside the outline, no folder, the degree sign decoded.
    mold = report["inputs"]["mold"]
    folder = "" if mold.startswith("builtin:") else os.path.dirname(mold)
    texts = list(msp.query("TEXT"))
    labels = [e for e in texts if e.dxf.layer == "LABELS"]
    check(any(e.dxf.layer == "GRAIN" for e in texts), "no GRAIN text")
    for e in texts:
        p = e.dxf.insert
        check(inside(loops, p.x, p.y), "%s text %r inserted outside the outline at (%r, %r)"
              % (e.dxf.layer, e.dxf.text, p.x, p.y))
        x0, y0, x1, y1 = text_box(e)
        check(box_inside(loops, x0, y0, x1, y1),
              "%s text %r extends outside the outline (%r, %r .. %r, %r)" % (e.dxf.layer, e.dxf.text, x0, y0, x1, y1))
        for token in decoded(e.dxf.text).split():
            check(not token.startswith("/") and not re.match(r"[A-Za-z]:[\\/]", token)
                  and (not folder or folder not in token), "label %r holds a path" % e.dxf.text)
        check("%%" not in e.dxf.text, "label %r holds an AutoCAD %%%% code" % e.dxf.text)
    mold_label = [e.dxf.text for e in labels if e.dxf.text.startswith("MOLD:")]
    check(all("/" not in t and "\\" not in t for t in mold_label), "MOLD label %r holds a folder" % mold_label)
    by_key = {}
    for e in labels:
        key = e.dxf.text.split(":")[0]
        by_key[key] = e.dxf.text
    for key in LABEL_KEYS:
        check(key in by_key, "label %s missing" % key)
    mold_shown = mold if mold.startswith("builtin:") else os.path.basename(mold)
    check(by_key.get("MOLD", "").startswith("MOLD: %s face %d" % (mold_shown, report["inputs"]["face"])),
          "MOLD label %r, expected the file name %r" % (by_key.get("MOLD"), mold_shown))
    check(by_key.get("PLY") == "PLY: " + report["inputs"]["ply_name"],
          "PLY label %r, ply name %r" % (by_key.get("PLY"), report["inputs"]["ply_name"]))
    angle = by_key.get("PLY ANGLE", "")
    check(angle.endswith(DEGREE), "PLY ANGLE label %r does not end in U+00B0" % angle)
    try:
        shown = float(angle.split(":")[1].strip().rstrip(DEGREE))
    except (IndexError, ValueError):
        shown = float("nan")
    check(abs(shown - report["inputs"]["ply_angle_deg"]) <= ANGLE_ROUNDING,
          "PLY ANGLE label shows %r, report.json %r" % (shown, report["inputs"]["ply_angle_deg"]))
    check(DEGREE in by_key.get("SHEAR", ""), "SHEAR label %r has no U+00B0" % by_key.get("SHEAR"))
    check(b"\xb0" in raw, "no cp1252 degree byte 0xB0 in the file")
    area_label = by_key.get("AREA", "")
    try:
        shown = float(area_label.split()[1])
    except (IndexError, ValueError):
        shown = float("nan")
    check(abs(shown - report["flat_outline"]["area"]) <= LABEL_ROUNDING,
          "area label shows %r, report.json %r" % (shown, report["flat_outline"]["area"]))

    warn = list(msp.query("*[layer=='SHEAR_WARN']"))
    for e in warn:
        check(e.dxftype() == "LWPOLYLINE" and e.closed, "SHEAR_WARN entity not a closed polyline")
    if a.shear_warn == "yes":
        check(len(warn) > 0, "no SHEAR_WARN cells")
    else:
        check(len(warn) == 0, "%d SHEAR_WARN cells, none expected" % len(warn))

    return finish("check_dxf", path, failures,
                  "%d outline loops, %d holes, area %.12g, %d thread lines, %d shear-warning cells, "
                  "%d labels inside%s" % (sum(signed_area(p) > 0 for p in loops),
                                          sum(signed_area(p) < 0 for p in loops), total,
                                          len(threads), len(warn), len(texts),
                                          ", %d pieces" % len(pieces) if pieces else ""))


if __name__ == "__main__":
    sys.exit(main())
