#!/usr/bin/python3
"""Parses DIR/flat.svg, drape.svg, shear.svg and view.svg with Python's XML parser and checks
them against DIR/report.json:

- well-formed SVG with a viewBox, self-contained (no external references, images or
  scripts), and one element of class "node" per mapped regular node (flat.svg, drape.svg:
  nodes.mapped; shear.svg: nodes.with_angle, the nodes with a thread angle);
- flat.svg is printable 1:1: its width and height are in millimetres and equal to its
  viewBox's, so one user unit is one millimetre; the outline drawn (id "outline") spans
  exactly the width and height of report.json's flat_outline loops (to the 0.01 mm the
  coordinates are written with); the scale bar (id "scale-bar") is a line as long as the
  length its label names;
- titles and subtitles (the group id "title") are wrapped, not cut: every line fits the
  picture's width (at 0.62 em a character, wider than DejaVu Sans's average; in px of the
  title block's own scale), and the
  subtitle lines put together hold the whole subtitle (the mold's file name, never its folder, and the shear summary);
- flat.svg of a ply split for the roll (report.json `pieces`): one outline of class "piece"
  per piece, named, in order, each drawn as wide and high as its loops and placed beside the
  first as report.json places it; the seams (id "seams") dashed, each a vertical line at its
  seam's x; of a ply with darts: two cut lines per dart of as many segments as its points;
- shear.svg has one unit, degrees: no pi in any text, the gamma axis labelled in degrees;
- view.svg is small: well-formed and self-contained, at most VIEW_PX wide and high, no text,
  between 1 and VIEW_MAX_CELLS cells (polygons of class "cell"), the base path drawn.

usage: check_svg.py DIR
"""
import json
import os
import re
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"
WRITTEN_MM = 0.01      # flat.svg coordinates have two decimals
CHAR_EM = 0.62         # a generous average character width of the pictures' sans-serif font
FONT_PX = {"title": 17.0, "sub": 12.0, "small": 11.0}
MARGIN_PX = 40.0       # the pictures' margin
VIEW_PX = 400.0        # view.svg: its largest size
VIEW_MAX_CELLS = 1500  # view.svg: the most cells (or blocks of cells) it draws


def number(s):
    return float(re.match(r"[-+0-9.eE]+", s).group(0))


def path_points(d):
    return [(float(x), float(y)) for x, y in re.findall(r"([-0-9.]+),([-0-9.]+)", d)]


def text_lines(root):
    """(class, text, in the title block) of every text element."""
    out = []

    def walk(el, in_title):
        in_title = in_title or el.get("id") == "title"
        if el.tag == SVG + "text":
            out.append((el.get("class", ""), "".join(el.itertext()), in_title))
        for c in el:
            walk(c, in_title)

    walk(root, False)
    return out


def foreign(root, path):
    """What makes the picture not self-contained: images, scripts, external references."""
    out = []
    for el in root.iter():
        tag = el.tag.replace(SVG, "")
        if tag in ("image", "script", "foreignObject", "use"):
            out.append("%s: has a <%s> element" % (path, tag))
        for k, v in el.attrib.items():
            if k.endswith("href") and not v.startswith("#"):
                out.append("%s: external reference %s=%s" % (path, k, v))
            if "url(" in v and "url(#" not in v:
                out.append("%s: external url in %s" % (path, k))
    return out


def check_view(d):
    """view.svg's failures, and prints its verdict."""
    path = os.path.join(d, "view.svg")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        return ["%s: not well-formed XML: %s" % (path, e)]
    out = foreign(root, path)
    vb = [float(x) for x in root.get("viewBox", "0 0 0 0").split()]
    if root.tag != SVG + "svg" or not (0 < vb[2] <= VIEW_PX and 0 < vb[3] <= VIEW_PX):
        out.append("%s: root %s, viewBox %r: not a picture of at most %g px" % (path, root.tag, vb, VIEW_PX))
    cells = sum(1 for el in root.iter(SVG + "polygon") if el.get("class") == "cell")
    if not 0 < cells <= VIEW_MAX_CELLS:
        out.append("%s: %d cells, expected 1 to %d" % (path, cells, VIEW_MAX_CELLS))
    if any(True for _ in root.iter(SVG + "text")):
        out.append("%s: has text" % path)
    if not any(el.get("stroke") == "#1f5fd6" for el in root.iter(SVG + "line")):
        out.append("%s: no base path" % path)
    if not out:
        print("check_svg: %s: ok (%d cells, %g x %g px)" % (path, cells, vb[2], vb[3]))
    return out


def title_scale(root):
    """The user units per px of the title block: the scale of the transforms around the group
    id "title" (flat.svg draws its annotation scaled to the drawing; the pixel pictures at 1)."""

    def walk(el, scale):
        for kind, args in re.findall(r"(scale)\(([^)]*)\)", el.get("transform", "")):
            scale *= float(re.split(r"[ ,]+", args.strip())[0])
        if el.get("id") == "title":
            return scale
        for c in el:
            found = walk(c, scale)
            if found is not None:
                return found
        return None

    return walk(root, 1.0) or 1.0


def extent(pts):
    return (min(p[0] for p in pts), max(p[0] for p in pts), min(p[1] for p in pts), max(p[1] for p in pts))


def segments(d):
    """The segments of a path of "M a L b" pairs."""
    pts = path_points(d)
    return [(pts[k], pts[k + 1]) for k in range(0, len(pts) - 1, 2)]


def check_pieces_and_darts(root, report, path):
    """flat.svg's pieces and seams against report.json's pieces and splices, and its dart cut
    lines against report.json's darts (relative to the first piece: the drawing's origin is
    its own)."""
    out = []
    tol = 2 * WRITTEN_MM
    pieces = report.get("pieces", [])
    drawn = [el for el in root.iter(SVG + "path") if "piece" in el.get("class", "").split()]
    if len(drawn) != len(pieces):
        out.append("%s: %d piece outlines, report.json has %d pieces" % (path, len(drawn), len(pieces)))
    elif pieces:
        ref = None
        for el, piece in zip(drawn, pieces):
            if el.get("data-name") != piece["name"]:
                out.append("%s: piece %r drawn as %r" % (path, piece["name"], el.get("data-name")))
            x0, x1, y0, y1 = extent(path_points(el.get("d")))
            pts = [p for l in piece["loops"] for p in l["points"]]
            px0, px1, py0, py1 = extent(pts)
            if ref is None:
                ref = (x0, px0)
            if abs((x1 - x0) - (px1 - px0)) > tol or abs((y1 - y0) - (py1 - py0)) > tol:
                out.append("%s: piece %s drawn %.3f x %.3f, its loops are %.3f x %.3f"
                           % (path, piece["name"], x1 - x0, y1 - y0, px1 - px0, py1 - py0))
            if abs((x0 - ref[0]) - (px0 - ref[1])) > tol:
                out.append("%s: piece %s drawn at %.3f from the first, report.json %.3f"
                           % (path, piece["name"], x0 - ref[0], px0 - ref[1]))
        seams = [el for el in root.iter(SVG + "path") if el.get("id") == "seams"]
        want = report["splices"]["seams"]
        if len(seams) != 1 or not seams[0].get("stroke-dasharray"):
            out.append("%s: %d seam paths, dashed: %s" % (path, len(seams), seams and seams[0].get("stroke-dasharray")))
        else:
            segs = segments(seams[0].get("d"))
            xs = sorted({round(a[0], 2) for a, b in segs})
            if any(abs(a[0] - b[0]) > WRITTEN_MM for a, b in segs):
                out.append("%s: a seam is not along the warp" % path)
            if len(xs) != len(want) or any(abs((x - ref[0]) - (s["x"] - ref[1])) > tol for x, s in zip(xs, want)):
                out.append("%s: seams drawn at %s from the first piece, report.json %s"
                           % (path, [round(x - ref[0], 2) for x in xs], [round(s["x"] - ref[1], 2) for s in want]))
    darts = report.get("darts", {}).get("darts", [])
    want = sum(2 * (d["cut_line_points"] - 1) for d in darts if d["cut_line_points"] >= 2)
    lines = [el for el in root.iter(SVG + "path") if el.get("id") == "darts"]
    got = len(segments(lines[0].get("d"))) if lines else 0
    if got != want:
        out.append("%s: %d dart cut line segments, report.json's darts make %d" % (path, got, want))
    return out


def main():
    d = sys.argv[1]
    with open(os.path.join(d, "report.json"), encoding="utf-8") as f:
        report = json.load(f)
    expected = {"flat.svg": report["nodes"]["mapped"], "drape.svg": report["nodes"]["mapped"],
                "shear.svg": report["nodes"]["with_angle"]}
    mold = report["inputs"]["mold"]
    mold_shown = mold if mold.startswith("builtin:") else os.path.basename(mold)
    failures = []
    for name, want in expected.items():
        path = os.path.join(d, name)
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as e:
            failures.append("%s: not well-formed XML: %s" % (path, e))
            continue
        if root.tag != SVG + "svg" or "viewBox" not in root.attrib:
            failures.append("%s: root is %s, viewBox %s" % (path, root.tag, root.get("viewBox")))
            continue
        failures += foreign(root, path)
        nodes = sum(1 for el in root.iter() if "node" in el.get("class", "").split())
        if nodes != want or want <= 0:
            failures.append("%s: %d node marks, report.json says %d" % (path, nodes, want))

        vb = [float(x) for x in root.get("viewBox").split()]
        # Wrapped, not cut: every title and subtitle line fits the width (in px of annotation).
        lines = text_lines(root)
        px_per_unit = 1.0 / title_scale(root)
        width_px = vb[2] * px_per_unit
        subtitle = []
        for cls, t, in_title in lines:
            c = cls.split()[0] if cls else ""
            if in_title:
                est = len(t) * CHAR_EM * FONT_PX[c]
                if est > width_px - 2 * MARGIN_PX + 1e-6:
                    failures.append("%s: the %s line %r (about %.0f px) is wider than the picture (%.0f px)"
                                    % (path, c, t, est, width_px))
                if c == "sub":
                    subtitle.append(t)
        sub = " ".join(subtitle)
        if ("on %s, face %d" % (mold_shown, report["inputs"]["face"])) not in sub:
            failures.append("%s: the subtitle %r does not name %r and the face" % (path, sub, mold_shown))
        if "max shear" not in sub or not re.search(r"\u03b3 [0-9.]+\u00b0 \u2026 [0-9.]+\u00b0$", sub):
            failures.append("%s: the subtitle %r lacks the shear summary at its end" % (path, sub))
        folder = "" if mold.startswith("builtin:") else os.path.dirname(mold)
        if any(w.startswith("/") or (folder and folder in w) for w in sub.split()):
            failures.append("%s: the subtitle %r holds a folder" % (path, sub))

        if name == "flat.svg":
            w, h = root.get("width"), root.get("height")
            if not (w.endswith("mm") and h.endswith("mm")):
                failures.append("%s: width %r and height %r are not in mm" % (path, w, h))
            elif abs(number(w) - vb[2]) > WRITTEN_MM or abs(number(h) - vb[3]) > WRITTEN_MM or vb[:2] != [0, 0]:
                failures.append("%s: size %s x %s but viewBox %s: not 1 mm per user unit" % (path, w, h, vb))
            # The red outline is the exact one (the cut outline may leave out pieces of it: cloth
            # laid twice where a closed shell's cloth meets itself).
            outline = [el for el in root.iter(SVG + "path") if el.get("id") == "outline"]
            loops = report["flat_outline_exact"]["loops"]
            xs = [p[0] for l in loops for p in l["points"]]
            ys = [p[1] for l in loops for p in l["points"]]
            if len(outline) != 1:
                failures.append("%s: %d outline paths" % (path, len(outline)))
            else:
                pts = path_points(outline[0].get("d"))
                dw = max(p[0] for p in pts) - min(p[0] for p in pts)
                dh = max(p[1] for p in pts) - min(p[1] for p in pts)
                if abs(dw - (max(xs) - min(xs))) > 2 * WRITTEN_MM or abs(dh - (max(ys) - min(ys))) > 2 * WRITTEN_MM:
                    failures.append("%s: the outline is drawn %.3f x %.3f, report.json's is %.3f x %.3f mm"
                                    % (path, dw, dh, max(xs) - min(xs), max(ys) - min(ys)))
            failures += check_pieces_and_darts(root, report, path)
            bars = [el for el in root.iter(SVG + "g") if el.get("id") == "scale-bar"]
            if len(bars) != 1:
                failures.append("%s: %d scale bars" % (path, len(bars)))
            else:
                bar_lines = list(bars[0].iter(SVG + "line"))
                label = "".join("".join(t.itertext()) for t in bars[0].iter(SVG + "text"))
                m = re.match(r"([0-9.]+) mm$", label)
                if not bar_lines or not m:
                    failures.append("%s: scale bar %r without a line or a length" % (path, label))
                else:
                    b = bar_lines[0]
                    length = abs(float(b.get("x2")) - float(b.get("x1")))
                    if abs(length - float(m.group(1))) > WRITTEN_MM or float(m.group(1)) <= 0:
                        failures.append("%s: the scale bar is %.3f long, labelled %r" % (path, length, label))
        if name == "shear.svg":
            for cls, t, s in lines:
                if "\u03c0" in t:
                    failures.append("%s: text %r in radians (pi)" % (path, t))
            ticks = [t for cls, t, s in lines if re.fullmatch(r"[0-9]+\u00b0", t)]
            for v in ("0\u00b0", "90\u00b0", "180\u00b0"):
                if v not in ticks:
                    failures.append("%s: no gamma axis label %r" % (path, v))
        if not any(f.startswith(path + ":") for f in failures):
            print("check_svg: %s: ok (%d nodes%s)" % (path, nodes, ", 1:1 in mm" if name == "flat.svg" else ""))
    failures += check_view(d)
    for f in failures:
        print("check_svg: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
