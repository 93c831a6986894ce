#!/usr/bin/python3
"""Checks that the pictures of a drape read the same at every scale: run on the outputs of the
same part drawn at very different sizes (a 1 mm, a 100 mm and a 20 m plate), each DIR holding
flat.svg, drape.svg, shear.svg and flat.dxf.

SVG (Python's XML parser; translate/scale transforms composed, font sizes read from the
file's own <style>):
- every text's height (its font size times its scale) is between TEXT_MIN_REL and
  TEXT_MAX_REL of the picture's larger side (viewBox): readable on the drawing, never a
  speck on a 20 m drawing nor a giant on a small one;
- the threads' strokes (flat.svg's links path, drape.svg's thread lines, shear.svg's cell
  edges) are at most STROKE_MAX_REL of the median drawn link (segment or edge) length, so a
  fine net does not turn solid black;
- the labels on the drawing (the groups of class "label": flat.svg's "sweep N" and "Ps",
  drape.svg's "Ps", MIN_LABELS of them at least) do not overlap each
  other nor any other text, and do not cover the base path's marks (class "path-node") nor
  the start's marker (id "origin"); a text's box is estimated as CHAR_EM of its font size per
  character wide, ASCENT_EM above and DESCENT_EM below its baseline.

DXF (ezdxf): every TEXT's height is between DXF_TEXT_MIN_REL and DXF_TEXT_MAX_REL of the
pattern's extent (the larger side of its OUTLINE); no text's box (one text height per
character wide, DESCENT_EM below the baseline, rotation applied) meets the BASEPATH polyline,
the ORIGIN circle, or another text's box.

usage: check_scales.py DIR...
"""
import math
import os
import re
import statistics
import sys
import xml.etree.ElementTree as ET

import ezdxf

SVG = "{http://www.w3.org/2000/svg}"
TEXT_MIN_REL = 0.0075   # text height at least 0.75 % of the picture's larger side ...
TEXT_MAX_REL = 0.05     # ... and at most 5 %
STROKE_MAX_REL = 0.25   # a thread's stroke at most a quarter of a link
CHAR_EM = 0.62          # a generous average character width of the sans-serif font
ASCENT_EM = 0.8
DESCENT_EM = 0.25
DXF_TEXT_MIN_REL = 1.0 / 400.0  # flat.dxf's labels: 0.25 % .. 2.5 % of the pattern
DXF_TEXT_MAX_REL = 1.0 / 40.0
REL_SLACK = 1e-9
# Label groups: flat.svg's "sweep N" (one per sweep, at least one) and "Ps", drape.svg's "Ps".
MIN_LABELS = {"flat.svg": 2, "drape.svg": 1, "shear.svg": 0}


def transform_of(el, parent):
    """(scale, tx, ty) of el composed with its parent's: point -> s * p + t."""
    s, tx, ty = parent
    for kind, args in re.findall(r"(translate|scale)\(([^)]*)\)", el.get("transform", "")):
        v = [float(a) for a in re.split(r"[ ,]+", args.strip())]
        if kind == "translate":
            tx, ty = tx + s * v[0], ty + s * (v[1] if len(v) > 1 else 0.0)
        else:
            s = s * v[0]
    return (s, tx, ty)


def apply(t, x, y):
    return (t[0] * x + t[1], t[0] * y + t[2])


def boxes_meet(a, b):
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def union(a, b):
    return (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))


def disc_meets_box(cx, cy, r, b):
    dx = max(b[0] - cx, 0.0, cx - b[2])
    dy = max(b[1] - cy, 0.0, cy - b[3])
    return math.hypot(dx, dy) <= r


def segment_meets_box(p, q, b):
    """Liang-Barsky: does segment pq meet the box (x0, y0, x1, y1)?"""
    t0, t1 = 0.0, 1.0
    d = (q[0] - p[0], q[1] - p[1])
    for axis in (0, 1):
        for pp, qq in ((-d[axis], p[axis] - b[axis]), (d[axis], b[axis + 2] - p[axis])):
            if pp == 0.0:
                if qq < 0:
                    return False
            else:
                t = qq / pp
                if pp < 0:
                    t0 = max(t0, t)
                else:
                    t1 = min(t1, t)
                if t0 > t1:
                    return False
    return True


def segments_of_path(d):
    pts = [(float(x), float(y)) for x, y in re.findall(r"[ML]([-0-9.]+),([-0-9.]+)", d)]
    return list(zip(pts[0::2], pts[1::2]))


def walk(el, t, label, out):
    """Collects texts (box, label id), path-node and origin circles, with their transforms."""
    t = transform_of(el, t)
    if el.tag == SVG + "g" and "label" in el.get("class", "").split():
        label = id(el)
    tag = el.tag.replace(SVG, "")
    if tag == "text":
        out["texts"].append((el, t, label))
    elif tag == "circle":
        cx, cy = apply(t, float(el.get("cx")), float(el.get("cy")))
        r = t[0] * float(el.get("r"))
        if "path-node" in el.get("class", "").split():
            out["marks"].append((cx, cy, r, "a base-path mark"))
        if el.get("id") == "origin":
            sw = float(el.get("stroke-width", "0"))
            out["marks"].append((cx, cy, r + 0.5 * t[0] * sw, "the origin marker"))
    for c in el:
        walk(c, t, label, out)


def text_box(el, t, font_px):
    """The estimated box of a text in the picture's user units, and its height."""
    cls = el.get("class", "").split()
    em = font_px[cls[0]] if cls and cls[0] in font_px else None
    if em is None:
        raise ValueError("text %r has no known font size class %r" % ("".join(el.itertext()), cls))
    x, y = float(el.get("x")), float(el.get("y"))
    n = len("".join(el.itertext()))
    w = CHAR_EM * em * n
    x0 = x - (w if el.get("text-anchor") == "end" else 0.0)
    a = apply(t, x0, y - ASCENT_EM * em)
    b = apply(t, x0 + w, y + DESCENT_EM * em)
    return (a[0], a[1], b[0], b[1]), t[0] * em


def thread_strokes(name, root):
    """(stroke width, median link length) of the picture's threads, in user units."""
    widths, lengths = [], []
    for el in root.iter():
        tag = el.tag.replace(SVG, "")
        if name == "flat.svg" and tag == "path" and el.get("id") == "links":
            widths.append(float(el.get("stroke-width")))
            lengths += [math.dist(p, q) for p, q in segments_of_path(el.get("d"))]
        elif name == "drape.svg" and tag == "line" and el.get("stroke") == "#262626":
            widths.append(float(el.get("stroke-width")))
            lengths.append(math.dist((float(el.get("x1")), float(el.get("y1"))),
                                     (float(el.get("x2")), float(el.get("y2")))))
        elif name == "shear.svg" and tag == "polygon" and el.get("class") == "cell":
            widths.append(float(el.get("stroke-width")))
            pts = [tuple(map(float, p.split(","))) for p in el.get("points").split()]
            lengths += [math.dist(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts))]
    lengths = [v for v in lengths if v > 0]
    return (max(widths) if widths else None), (statistics.median(lengths) if lengths else None)


def check_svg(path, name, failures):
    root = ET.parse(path).getroot()
    vb = [float(v) for v in root.get("viewBox").split()]
    side = max(vb[2], vb[3])
    style = "".join(s.text or "" for s in root.iter(SVG + "style"))
    font_px = {c: float(v) for c, v in re.findall(r"\.([a-z-]+)\{font-size:([0-9.]+)px", style)}
    found = {"texts": [], "marks": []}
    walk(root, (1.0, 0.0, 0.0), None, found)
    boxes = []  # (box, label id, text)
    heights = []
    for el, t, label in found["texts"]:
        box, h = text_box(el, t, font_px)
        heights.append(h / side)
        boxes.append((box, label, "".join(el.itertext())))
        if not TEXT_MIN_REL * (1 - REL_SLACK) <= h / side <= TEXT_MAX_REL * (1 + REL_SLACK):
            failures.append("%s: text %r is %.4g high, %.3f %% of the picture's %.4g: not in %.2f .. %.0f %%"
                            % (path, "".join(el.itertext()), h, 100 * h / side, side,
                               100 * TEXT_MIN_REL, 100 * TEXT_MAX_REL))
    width, link = thread_strokes(name, root)
    if width is None or link is None:
        failures.append("%s: no threads drawn" % path)
    elif width > STROKE_MAX_REL * link * (1 + REL_SLACK):
        failures.append("%s: thread stroke %.4g wider than %.2f of the median link %.4g"
                        % (path, width, STROKE_MAX_REL, link))
    labels = {}
    for box, label, s in boxes:
        if label is not None:
            labels[label] = union(labels[label], box) if label in labels else box
    names = {label: " ".join(s for _, l2, s in boxes if l2 == label) for label in labels}
    for label, box in labels.items():
        for other, obox in labels.items():
            if other != label and id(other) < id(label) and boxes_meet(box, obox):
                failures.append("%s: labels %r and %r overlap" % (path, names[label], names[other]))
        for tbox, l2, s in boxes:
            if l2 is None and boxes_meet(box, tbox):
                failures.append("%s: label %r overlaps the text %r" % (path, names[label], s))
        for cx, cy, r, what in found["marks"]:
            if disc_meets_box(cx, cy, r, box):
                failures.append("%s: label %r covers %s at (%.4g, %.4g)" % (path, names[label], what, cx, cy))
                break
    if len(labels) < MIN_LABELS[name]:
        failures.append("%s: %d label groups, at least %d expected" % (path, len(labels), MIN_LABELS[name]))
    return len(labels), min(heights), max(heights), width, link


def dxf_text_box(t):
    """The text's box (generous: one height per character) as its four corners, rotated."""
    h = t.dxf.height
    n = len(t.plain_text())
    x, y = t.dxf.insert[0], t.dxf.insert[1]
    a = math.radians(t.dxf.get("rotation", 0.0))
    c, s = math.cos(a), math.sin(a)
    local = [(0, -DESCENT_EM * h), (n * h, -DESCENT_EM * h), (n * h, h), (0, h)]
    pts = [(x + c * u - s * v, y + s * u + c * v) for u, v in local]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    return (min(xs), min(ys), max(xs), max(ys))


def check_dxf(path, failures):
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    outline = [tuple(p[:2]) for e in msp.query("LWPOLYLINE[layer=='OUTLINE']") for p in e.get_points()]
    xs, ys = [p[0] for p in outline], [p[1] for p in outline]
    extent = max(max(xs) - min(xs), max(ys) - min(ys))
    path_segs = []
    for e in msp.query("LWPOLYLINE[layer=='BASEPATH']"):
        pts = [tuple(p[:2]) for p in e.get_points()]
        path_segs += list(zip(pts, pts[1:]))
    circles = [(c.dxf.center[0], c.dxf.center[1], c.dxf.radius) for c in msp.query("CIRCLE[layer=='ORIGIN']")]
    texts = list(msp.query("TEXT"))
    boxes = []
    for t in texts:
        h = t.dxf.height
        if not DXF_TEXT_MIN_REL * (1 - REL_SLACK) <= h / extent <= DXF_TEXT_MAX_REL * (1 + REL_SLACK):
            failures.append("%s: text %r is %.4g high, %.3f %% of the pattern's %.4g"
                            % (path, t.plain_text(), h, 100 * h / extent, extent))
        box = dxf_text_box(t)
        for p, q in path_segs:
            if segment_meets_box(p, q, box):
                failures.append("%s: the base path crosses the text %r" % (path, t.plain_text()))
                break
        for cx, cy, r in circles:
            if disc_meets_box(cx, cy, r, box):
                failures.append("%s: the origin marker meets the text %r" % (path, t.plain_text()))
        for other, s in boxes:
            if boxes_meet(box, other):
                failures.append("%s: texts %r and %r overlap" % (path, t.plain_text(), s))
        boxes.append((box, t.plain_text()))
    return len(texts), min(t.dxf.height for t in texts) / extent, extent


def main():
    failures = []
    for d in sys.argv[1:]:
        for name in ("flat.svg", "drape.svg", "shear.svg"):
            path = os.path.join(d, name)
            n = len(failures)
            labels, lo, hi, width, link = check_svg(path, name, failures)
            if len(failures) == n:
                print("check_scales: %s: ok (text %.2f .. %.2f %% of the picture, thread stroke %.3g of a link, %d labels clear)"
                      % (path, 100 * lo, 100 * hi, width / link, labels))
        path = os.path.join(d, "flat.dxf")
        n = len(failures)
        count, rel, extent = check_dxf(path, failures)
        if len(failures) == n:
            print("check_scales: %s: ok (%d texts, %.3f %% of the pattern's %.4g, clear of the base path and the origin)"
                  % (path, count, 100 * rel, extent))
    for f in failures:
        print("check_scales: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
