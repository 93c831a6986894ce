#!/usr/bin/python3
"""Loads a laminate's DIR/plybook.html (plyfit laminate) in headless Chromium (Debian package
`chromium`) and checks what a person would get:

- the page is self-contained: no script, no stylesheet link, no image or frame loaded from
  anywhere; its links are relative and lead to files that exist (or to its own anchors);
- Chromium loads it with no console message and no failed load (--enable-logging=stderr);
- the DOM Chromium built (--dump-dom) has the table with one row per ply of plybook.json, in
  stacking order, and per ply its section with one flat pattern and one shear map picture
  (inline SVG) when the ply was draped, none when it was not;
- the screenshot (--screenshot) is a PNG of the window's size with ink: at least INK_SHARE of
  its pixels are not white, in at least MIN_COLOURS colours (the pictures' colour scales).

The screenshot is kept as DIR/plybook-chromium.png for a person to look at.

usage: check_plybook.py DIR
"""
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

from check_report import finish

WINDOW = (1280, 2400)
INK_SHARE = 0.02
MIN_COLOURS = 32
SAMPLE = 2     # every second pixel of every second row is looked at
TIMEOUT_S = 120


def chromium(args, profile):
    cmd = ["chromium", "--headless", "--disable-gpu", "--no-sandbox", "--no-first-run",
           "--user-data-dir=" + profile, "--host-resolver-rules=MAP * ~NOTFOUND",
           "--enable-logging=stderr", "--v=0"] + args
    return subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT_S)


def png_pixels(path):
    """Width, height and the RGB(A) rows of an 8-bit non-interlaced PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unexpected PNG format"
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def static_checks(d, html, problems):
    for bad in ("<script", "<link", "<iframe", "<img", "<object", "<embed", "@import"):
        if bad in html.lower():
            problems.append(f"the page has {bad}")
    for url in re.findall(r'(?:href|src)="([^"]*)"', html):
        if url.startswith("#"):
            if f'id="{url[1:]}"' not in html:
                problems.append(f"link {url}: no such anchor")
        elif "://" in url or url.startswith("//") or url.startswith("/"):
            problems.append(f"link {url} is not relative")
        elif not os.path.isfile(os.path.join(d, url)):
            problems.append(f"link {url}: no such file")


def dom_checks(dom, book, problems):
    rows = re.findall(r'<tr><td class="num">(\d+)</td><td><a href="#ply-([^"]+)"', dom)
    want = [(str(p["sequence"]), p["name"]) for p in book["plies"]]
    if rows != want:
        problems.append(f"table rows {rows}, not {want}")
    sections = re.split(r'<section class="ply" id="ply-', dom)[1:]
    if len(sections) != len(book["plies"]):
        problems.append(f"{len(sections)} ply sections, not {len(book['plies'])}")
    for p, s in zip(book["plies"], sections):
        drawn = p["status"] in ("ok", "partial")
        flat = s.count('<figure class="picture flat">')
        shear = s.count('<figure class="picture shear">')
        svgs = s.count("<svg")
        if (flat, shear) != ((1, 1) if drawn else (0, 0)) or svgs < 2 * drawn:
            problems.append(f"{p['name']}: {flat} flat, {shear} shear pictures, {svgs} svg")


def main():
    d = os.path.abspath(sys.argv[1])
    page = os.path.join(d, "plybook.html")
    book = json.load(open(os.path.join(d, "plybook.json")))
    problems = []
    static_checks(d, open(page, encoding="utf-8").read(), problems)
    profile = tempfile.mkdtemp(prefix="plyfit_chromium_")
    try:
        shot = os.path.join(d, "plybook-chromium.png")
        r = chromium(["--dump-dom", "file://" + page], profile)
        if r.returncode != 0:
            problems.append(f"chromium --dump-dom exited {r.returncode}: {r.stderr[-500:]}")
        dom_checks(r.stdout, book, problems)
        r2 = chromium(["--screenshot=" + shot, "--window-size=%d,%d" % WINDOW,
                       "--hide-scrollbars", "file://" + page], profile)
        for line in (r.stderr + r2.stderr).splitlines():
            if "CONSOLE" in line or "net::ERR" in line or "Failed to load" in line:
                problems.append("chromium: " + line.strip())
        if not os.path.isfile(shot):
            problems.append(f"no screenshot: {r2.stderr[-500:]}")
        else:
            w, h, bpp, rows = png_pixels(shot)
            if (w, h) != WINDOW:
                problems.append(f"screenshot {w}x{h}, not {WINDOW}")
            ink, colours = 0, set()
            for row in rows[::SAMPLE]:
                for x in range(0, len(row), SAMPLE * bpp):
                    px = row[x:x + 3]
                    if px != b"\xff\xff\xff":
                        ink += 1
                        colours.add(px)
            if ink < INK_SHARE * (w // SAMPLE) * (h // SAMPLE) or len(colours) < MIN_COLOURS:
                problems.append(f"screenshot nearly blank: {ink} ink pixels, {len(colours)} colours")
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return finish("check_plybook", page, problems,
                  f"{len(book['plies'])} plies, pictures inline, rendered by Chromium")


if __name__ == "__main__":
    sys.exit(main())
