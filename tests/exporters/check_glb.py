#!/usr/bin/python3
"""Reads DIR/net.glb with an independent glTF reader, Assimp (Debian assimp-utils: `assimp info -r`
and `assimp export` to ASCII PLY, which applies the node's transform), and checks it against
DIR/report.json:

- two meshes (Assimp makes one per glTF primitive): the triangles and the lines, each with one
  vertex per mapped node (nodes.mapped + nodes.auxiliary);
- the triangles' area, converted from square metres, is report.json's surface_area (the mapped
  cells' 3D area) within what float32 positions allow; each triangle is wound counter-clockwise
  seen from its corners' normals, which are unit vectors;
- every line (a link between two mapped nodes: a thread segment, or a base-path link, which
  lies in one cell) is no longer than the cell's diagonal times (1 + residual.edge_length_max_rel),
  in metres;
- the start point (mm, Z up) is a vertex at (x, z, -y) / 1000 (metres, glTF's Y up).

usage: check_glb.py DIR
"""
import math
import os
import re
import subprocess
import sys
import tempfile

from check_report import Case, finish  # same folder

MM_PER_M = 1000.0
FLOAT32_EPS = 2.0 ** -23  # the float32 positions' relative rounding
UNIT_NORMAL = 1e-5        # |n| = 1 within float32 and Assimp's 9-digit output
ROUNDING_ULPS = 4         # a position's rounding in the file and in Assimp's output, in float32 ulps


def assimp_meshes(path):
    """(vertices, faces, primitive type) per mesh, from `assimp info` without post-processing
    (which would drop the vertices no triangle uses)."""
    out = subprocess.run(["assimp", "info", path, "-r"], capture_output=True, text=True, check=True).stdout
    return [(int(v), int(f), t) for v, f, t in
            re.findall(r"^\s*\d+ \(.*\): \[(\d+) / \d+ / (\d+) \| (\w+)\]$", out, re.M)]


def read_ply(path):
    """Vertices (x, y, z, nx, ny, nz) and faces (index lists) of Assimp's ASCII PLY."""
    with open(path, encoding="ascii") as f:
        lines = f.read().split("\n")
    counts, k = {}, 0
    while lines[k] != "end_header":
        m = re.match(r"element (\w+) (\d+)", lines[k])
        if m:
            counts[m.group(1)] = int(m.group(2))
        k += 1
    k += 1
    verts = [tuple(float(x) for x in lines[k + n].split()[:6]) for n in range(counts["vertex"])]
    k += counts["vertex"]
    faces = [[int(x) for x in lines[k + n].split()[1:]] for n in range(counts["face"])]
    return verts, faces


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def norm(a):
    return math.sqrt(dot(a, a))


def main():
    case = Case(sys.argv[1], "net.glb")
    path, report, failures, check = case.path, case.report, case.failures, case.check

    mapped = report["nodes"]["mapped"] + report["nodes"]["auxiliary"]
    meshes = assimp_meshes(path)
    check([t for _, _, t in meshes] == ["triangle", "line"], "meshes %r, expected triangles and lines" % meshes)
    for v, _, t in meshes:
        check(v == mapped, "%s mesh: %d vertices, %d mapped nodes" % (t, v, mapped))

    with tempfile.TemporaryDirectory() as tmp:
        ply = os.path.join(tmp, "net.ply")
        subprocess.run(["assimp", "export", path, ply], capture_output=True, check=True)
        verts, faces = read_ply(ply)
    reach = max(abs(c) for v in verts for c in v[:3]) if verts else 0.0
    rounding = ROUNDING_ULPS * FLOAT32_EPS * reach  # metres

    area, bound, triangles, lines = 0.0, 0.0, 0, 0
    spacing = math.hypot(report["inputs"]["spacing_weft"], report["inputs"]["spacing_warp"]) / MM_PER_M
    longest = spacing * (1 + report["residual"]["edge_length_max_rel"]) + 2 * rounding
    for f in faces:
        p = [verts[i][:3] for i in f]
        if len(f) == 3:
            triangles += 1
            n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
            area += 0.5 * norm(n)
            bound += rounding * sum(norm(sub(p[(k + 1) % 3], p[k])) for k in range(3))
            normals = [verts[i][3:] for i in f]
            for m in normals:
                check(abs(norm(m) - 1) <= UNIT_NORMAL, "a normal of length %r" % norm(m))
            mean = [sum(m[i] for m in normals) for i in range(3)]
            check(dot(n, mean) > 0, "a triangle wound clockwise seen from its normals: %r" % (f,))
        elif len(f) == 2:
            lines += 1
            length = norm(sub(p[1], p[0]))
            check(0 < length <= longest, "a line of length %r m, cell diagonal %r m" % (length, spacing))
        else:
            check(False, "a face of %d vertices" % len(f))
    check(triangles == (meshes[0][1] if meshes else -1), "%d triangles in the PLY" % triangles)
    want = report["surface_area"] / MM_PER_M ** 2
    check(abs(area - want) <= bound, "triangles' area %.12g m^2, report.json surface_area %.12g mm^2 (bound %.3g)"
          % (area, report["surface_area"], bound))

    s = [c / MM_PER_M for c in report["start"]["point"]]
    start = (s[0], s[2], -s[1])
    check(any(norm(sub(v[:3], start)) <= 2 * rounding + FLOAT32_EPS * norm(start) for v in verts),
          "no vertex at the start point %r (metres, Y up)" % (start,))

    return finish("check_glb", path, failures, "%d vertices, %d triangles of area %.9g m^2, %d lines"
                  % (mapped, triangles, area, lines))


if __name__ == "__main__":
    sys.exit(main())
