#!/usr/bin/python3
"""Renders DIR/flat.dxf with LibreCAD (`librecad dxf2pdf -a`, headless through Qt's offscreen
platform) and pdftoppm (poppler-utils), and checks what a person would see:

- LibreCAD writes a PDF of exactly one page (pdfinfo);
- the rasterised page has ink, and the ink's bounding box has the aspect ratio of the
  drawing's extents (the outline, the origin circle and the rest, read with ezdxf): LibreCAD
  drew the pattern, fitted to the page (-a);
- mapping the drawing onto the ink's box, there is ink at every label and at the grain arrow:
  next to each TEXT's insertion point (the first characters) and along the arrow's shaft;
- the labels' insertion points and the grain arrow's ends lie inside the outline (from the
  DXF geometry: OUTLINE and HOLES, even-odd).

The rendered page is kept as DIR/flat-librecad-1.png for a person to look at.

With --cut, DIR is a laminate's folder and the drawing its cut.dxf (plyfit laminate): every
ply's outline, labels and grain arrow are on the ply's own layer (every layer but ROLL and 0),
one arrow per ply; the page is kept as DIR/cut-librecad-1.png.

usage: check_librecad.py DIR [--cut]
"""
import os
import shutil
import subprocess
import sys
import tempfile

import ezdxf
from ezdxf import bbox

from check_dxf import inside  # the even-odd point-in-outline test (same folder)
from check_report import finish

DPI = 100             # rasterisation of the A4 page
INK = 240             # a grey level below this is ink (not white: cyan layers are light)
ASPECT_REL = 0.03     # the ink box's aspect ratio against the drawing's (line widths, rounding)
PROBE_PX = 4          # ink searched this many pixels around a point
TIMEOUT_S = 120


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    # Binary PGM: P5, width, height, maxval, then the pixels.
    fields = []
    pos = 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    assert fields[0] == b"P5" and int(fields[3]) < 256, "not an 8-bit binary PGM"
    w, h = int(fields[1]), int(fields[2])
    pixels = data[pos + 1:pos + 1 + w * h]
    return w, h, pixels


def main():
    d = sys.argv[1]
    cut = "--cut" in sys.argv[2:]
    name = "cut" if cut else "flat"
    dxf = os.path.join(d, name + ".dxf")
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    tmp = tempfile.mkdtemp(prefix="plyfit_librecad_")
    try:
        shutil.copy(dxf, os.path.join(tmp, name + ".dxf"))
        env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=tmp, HOME=tmp)
        run = subprocess.run(["librecad", "dxf2pdf", "-a", name + ".dxf"], cwd=tmp, env=env,
                             capture_output=True, text=True, timeout=TIMEOUT_S)
        pdf = os.path.join(tmp, name + ".pdf")
        if run.returncode != 0 or not os.path.exists(pdf):
            print("check_librecad: librecad dxf2pdf failed (%d): %s" % (run.returncode, run.stderr[-500:]))
            return 1
        info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True, timeout=TIMEOUT_S).stdout
        pages = [l.split()[-1] for l in info.splitlines() if l.startswith("Pages:")]
        check(pages == ["1"], "the PDF has %s pages, not 1" % pages)
        subprocess.run(["pdftoppm", "-r", str(DPI), "-gray", "-f", "1", "-l", "1", pdf,
                        os.path.join(tmp, "page")], check=True, timeout=TIMEOUT_S)
        pgm = [f for f in os.listdir(tmp) if f.startswith("page") and f.endswith(".pgm")]
        check(len(pgm) == 1, "pdftoppm wrote %s" % pgm)
        if len(pgm) != 1:
            raise SystemExit(1)
        subprocess.run(["pdftoppm", "-r", str(DPI), "-png", "-f", "1", "-l", "1", pdf,
                        os.path.join(d, name + "-librecad")], check=True, timeout=TIMEOUT_S)
        w, h, px = read_pgm(os.path.join(tmp, pgm[0]))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    ink = [(k % w, k // w) for k in range(w * h) if px[k] < INK]
    check(len(ink) > 0, "the rendered page has no ink")
    if not ink:
        return report(dxf, failures)
    ix0, ix1 = min(p[0] for p in ink), max(p[0] for p in ink)
    iy0, iy1 = min(p[1] for p in ink), max(p[1] for p in ink)

    doc = ezdxf.readfile(dxf)
    msp = doc.modelspace()
    ext = bbox.extents(msp)
    ex0, ey0, ex1, ey1 = ext.extmin.x, ext.extmin.y, ext.extmax.x, ext.extmax.y
    want = (ex1 - ex0) / (ey1 - ey0)
    got = (ix1 - ix0) / max(1, iy1 - iy0)
    check(abs(got / want - 1) <= ASPECT_REL + 2.0 / min(ix1 - ix0 + 1, iy1 - iy0 + 1),
          "the ink's aspect ratio %.4f, the drawing's %.4f" % (got, want))
    sx = (ix1 - ix0) / (ex1 - ex0)
    sy = (iy1 - iy0) / (ey1 - ey0)

    def to_px(x, y):
        return ix0 + (x - ex0) * sx, iy1 - (y - ey0) * sy

    def ink_near(x, y):
        cx, cy = to_px(x, y)
        for yy in range(int(cy) - PROBE_PX, int(cy) + PROBE_PX + 1):
            for xx in range(int(cx) - PROBE_PX, int(cx) + PROBE_PX + 1):
                if 0 <= xx < w and 0 <= yy < h and px[yy * w + xx] < INK:
                    return True
        return False

    marks = "[layer!='ROLL' & layer!='0']" if cut else "[layer=='LABELS' | layer=='GRAIN']"
    outline = "[layer!='ROLL' & layer!='0']" if cut else "[layer=='OUTLINE' | layer=='HOLES']"
    loops = [[(p[0], p[1]) for p in e.get_points("xy")] for e in msp.query("LWPOLYLINE" + outline)]
    check(len(loops) > 0, "no OUTLINE")
    pieces = len({e.dxf.layer for e in msp.query("LWPOLYLINE" + outline)})
    texts = list(msp.query("TEXT" + marks))
    check(len(texts) >= (4 * pieces if cut else 7), "%d label texts" % len(texts))
    for e in texts:
        p = e.dxf.insert
        check(inside(loops, p.x, p.y), "text %r inserted outside the outline" % e.dxf.text)
        # The first character's box: from the insertion point one text height along the
        # baseline and up (rotated with the text).
        hgt = e.dxf.height
        if e.dxf.get("rotation", 0.0) == 90.0:
            probe = (p.x - 0.5 * hgt, p.y + 0.5 * hgt)
        else:
            probe = (p.x + 0.5 * hgt, p.y + 0.5 * hgt)
        check(ink_near(*probe), "no ink at the text %r" % e.dxf.text)
    shafts = [e for e in msp.query("LINE" + ("[layer!='ROLL']" if cut else "[layer=='GRAIN']"))
              if e.dxf.start.x == e.dxf.end.x]
    check(len(shafts) == (pieces if cut else 1), "%d grain arrow shafts" % len(shafts))
    for e in shafts:
        for t in (0.0, 0.25, 0.5, 0.75, 1.0):
            x = e.dxf.start.x + t * (e.dxf.end.x - e.dxf.start.x)
            y = e.dxf.start.y + t * (e.dxf.end.y - e.dxf.start.y)
            check(inside(loops, x, y), "the grain arrow leaves the outline at (%r, %r)" % (x, y))
            check(ink_near(x, y), "no ink on the grain arrow at (%r, %r)" % (x, y))
    return report(dxf, failures, len(texts), len(ink), (w, h))


def report(dxf, failures, texts=0, ink=0, size=(0, 0)):
    return finish("check_librecad", dxf, failures,
                  "one page, %d ink pixels of %dx%d, %d labels inside and drawn"
                  % (ink, size[0], size[1], texts))


if __name__ == "__main__":
    sys.exit(main())
