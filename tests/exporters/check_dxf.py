#!/usr/bin/python3
"""Reads DIR/flat.dxf with ezdxf (an independent DXF reader) and checks it against
DIR/report.json: no audit errors, millimetres, the six layers, closed OUTLINE polylines whose
signed areas (outer loops counter-clockwise, holes clockwise) add up to flat_outline.area
within 1e-9 relative, THREADS lines inside the outline (or none when --threads no), BASEPATH,
ORIGIN and LABELS present, SHEAR_WARN closed polylines present or absent as expected.

usage: check_dxf.py DIR [--threads yes|no] [--shear-warn yes|no]
"""
import argparse
import json
import os
import sys

import ezdxf

AREA_REL = 1e-9          # the brief: outline area as in report.json to 1e-9 relative
INSIDE_REL = 1e-9        # a THREADS line ends on the outline within this fraction of its size
LABEL_ROUNDING = 5e-4   # the AREA label shows three decimals
LAYERS = ["OUTLINE", "THREADS", "BASEPATH", "ORIGIN", "SHEAR_WARN", "LABELS"]


def signed_area(pts):
    a = 0.0
    for k in range(len(pts)):
        x0, y0 = pts[k]
        x1, y1 = pts[(k + 1) % len(pts)]
        a += x0 * y1 - x1 * y0
    return 0.5 * a


def inside(loops, x, y):
    """Even-odd point-in-polygon test over all loops."""
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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--threads", choices=["yes", "no"], default="yes")
    ap.add_argument("--shear-warn", choices=["yes", "no"], required=True)
    a = ap.parse_args()
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    path = os.path.join(a.dir, "flat.dxf")
    with open(os.path.join(a.dir, "report.json"), encoding="utf-8") as f:
        report = json.load(f)
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    check(len(auditor.errors) == 0, "audit errors: %s" % [str(e) for e in auditor.errors])
    check(doc.dxfversion >= "AC1015", "DXF version %s" % doc.dxfversion)
    check(doc.header.get("$INSUNITS") == 4, "$INSUNITS is %s, not 4 (mm)" % doc.header.get("$INSUNITS"))
    names = {layer.dxf.name for layer in doc.layers}
    for name in LAYERS:
        check(name in names, "layer %s missing" % name)
    msp = doc.modelspace()

    # OUTLINE: closed polylines, area against report.json.
    loops = []
    for e in msp.query("*[layer=='OUTLINE']"):
        check(e.dxftype() == "LWPOLYLINE", "OUTLINE holds a %s" % e.dxftype())
        check(e.closed, "OUTLINE polyline not closed")
        loops.append([(p[0], p[1]) for p in e.get_points("xy")])
    expected = report["flat_outline"]["area"]
    check(len(loops) == len(report["flat_outline"]["loops"]),
          "%d OUTLINE loops, report.json has %d" % (len(loops), len(report["flat_outline"]["loops"])))
    total = sum(signed_area(p) for p in loops)
    check(expected > 0, "report.json's outline area is %r" % expected)
    check(abs(total - expected) <= AREA_REL * abs(expected),
          "OUTLINE area %.17g, report.json %.17g" % (total, expected))
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
    check({"POINT", "LINE"} <= origin, "ORIGIN holds %s" % origin)
    start = report["inputs"]["start2d"]
    points = list(msp.query("POINT[layer=='ORIGIN']"))
    check(len(points) == 1 and abs(points[0].dxf.location.x - start[0]) <= AREA_REL * size
          and abs(points[0].dxf.location.y - start[1]) <= AREA_REL * size, "ORIGIN point is not the start")
    labels = [e.plain_text() for e in msp.query("TEXT[layer=='LABELS']")]
    check(len(labels) >= 5, "%d LABELS texts" % len(labels))
    ply_name = report.get("inputs", {}).get("ply_name")
    text = "\n".join(labels)
    for key in ("PLY", "MATERIAL", "SPACING", "AREA", "MAX SHEAR"):
        check(key in text, "label %s missing" % key)
    area_labels = [t for t in labels if t.startswith("AREA:")]
    shown = float(area_labels[0].split()[1]) if area_labels else float("nan")
    check(abs(shown - report["flat_outline"]["area"]) <= LABEL_ROUNDING,
          "area label shows %r, report.json %r" % (shown, report["flat_outline"]["area"]))

    warn = list(msp.query("*[layer=='SHEAR_WARN']"))
    for e in warn:
        check(e.dxftype() == "LWPOLYLINE" and e.closed, "SHEAR_WARN entity not a closed polyline")
    if a.shear_warn == "yes":
        check(len(warn) > 0, "no SHEAR_WARN cells")
    else:
        check(len(warn) == 0, "%d SHEAR_WARN cells, none expected" % len(warn))

    if failures:
        for f in failures[:20]:
            print("check_dxf: %s: %s" % (path, f))
        print("check_dxf: %d failures" % len(failures))
        return 1
    print("check_dxf: %s: ok (%d outline loops, area %.12g, %d thread lines, %d shear-warning cells)"
          % (path, len(loops), total, len(threads), len(warn)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
