#!/usr/bin/python3
"""Reads DIR/net.vtk with VTK's own legacy reader (vtkPolyDataReader, the reader ParaView uses;
Debian python3-vtk9) and checks it against DIR/report.json:

- one point per mapped node and per node beyond the face that has a position: status 0 for
  the mapped ones (nodes.mapped + nodes.auxiliary of them), 1 for the others, and one vertex
  cell per node beyond the face;
- the polygons are the mapped cells: 3 to 5 corners, all mapped (status 0), and their 3D area
  adds up to report.json's surface_area within 1e-9 relative;
- thread_angle_deg and shear_deg in degrees: NaN exactly where undefined (nodes.with_angle
  values defined), the defined ones in [0, 180] and [0, 90] with shear = |90 - angle|, their
  extremes equal to report.json's thread_angle min_deg/max_deg and shear_max_deg;
- cell data: cell_kind 4 for the vertices, 0-2 for the links, 3 for the polygons; shear_deg
  NaN on links and vertices.

usage: check_vtk.py DIR
"""
import math
import sys

import vtk

from check_report import Case, finish  # same folder

REL = 1e-9       # areas and angle extremes as in report.json
ROUNDOFF = 1e-9  # degrees: shear against |90 - angle|


def main():
    case = Case(sys.argv[1], "net.vtk")
    path, report, failures, check = case.path, case.report, case.failures, case.check

    reader = vtk.vtkPolyDataReader()
    reader.SetFileName(path)
    reader.ReadAllScalarsOn()
    reader.Update()
    check(reader.GetErrorCode() == 0, "VTK reader error %d" % reader.GetErrorCode())
    poly = reader.GetOutput()
    nodes = report["nodes"]
    pd, cd = poly.GetPointData(), poly.GetCellData()

    def array(data, name):
        a = data.GetArray(name)
        if a is None:
            failures.append("array %s missing" % name)
            return []
        return [a.GetValue(k) for k in range(a.GetNumberOfTuples())]

    status = array(pd, "status")
    angle = array(pd, "thread_angle_deg")
    shear = array(pd, "shear_deg")
    on_path = array(pd, "on_path")
    npts = poly.GetNumberOfPoints()
    for name, a in (("status", status), ("thread_angle_deg", angle), ("shear_deg", shear), ("on_path", on_path)):
        check(len(a) == npts, "%s has %d values for %d points" % (name, len(a), npts))
    mapped = nodes["mapped"] + nodes["auxiliary"]
    check(sum(1 for s in status if s == 0) == mapped, "%d points with status 0, %d mapped nodes"
          % (sum(1 for s in status if s == 0), mapped))
    beyond = sum(1 for s in status if s == 1)
    check(all(s in (0, 1) for s in status), "status outside {0, 1}")
    check(beyond <= nodes["outside"], "%d points beyond the face, %d outside nodes" % (beyond, nodes["outside"]))
    check(poly.GetNumberOfVerts() == beyond, "%d vertices, %d points beyond the face" % (poly.GetNumberOfVerts(), beyond))

    defined = [k for k in range(len(angle)) if not math.isnan(angle[k])]
    check(len(defined) == nodes["with_angle"], "%d defined angles, report.json %d" % (len(defined), nodes["with_angle"]))
    for k in range(min(len(angle), len(shear))):
        if math.isnan(angle[k]):
            check(math.isnan(shear[k]), "shear defined where the angle is not (point %d)" % k)
            continue
        check(status[k] == 0, "an angle at a point beyond the face (%d)" % k)
        check(0 <= angle[k] <= 180, "angle %r out of [0, 180] degrees" % angle[k])
        check(abs(shear[k] - abs(90 - angle[k])) <= ROUNDOFF, "shear %r, angle %r" % (shear[k], angle[k]))
    if defined:
        lo = min(angle[k] for k in defined)
        hi = max(angle[k] for k in defined)
        ta = report["thread_angle"]
        check(abs(lo - ta["min_deg"]) <= REL * 180 and abs(hi - ta["max_deg"]) <= REL * 180,
              "angles %r .. %r, report.json %r .. %r" % (lo, hi, ta["min_deg"], ta["max_deg"]))
        check(abs(max(shear[k] for k in defined) - report["shear_max_deg"]) <= REL * 90,
              "max shear %r, report.json %r" % (max(shear[k] for k in defined), report["shear_max_deg"]))

    # Polygons: the mapped cells, their 3D area is surface_area.
    polys = poly.GetPolys()
    ids = vtk.vtkIdList()
    polys.InitTraversal()
    area = 0.0
    count = 0
    while polys.GetNextCell(ids):
        count += 1
        n = ids.GetNumberOfIds()
        check(3 <= n <= 5, "a polygon with %d corners" % n)
        p = [poly.GetPoint(ids.GetId(m)) for m in range(n)]
        for m in range(n):
            check(status[ids.GetId(m)] == 0, "a polygon corner that is not mapped")
        for m in range(1, n - 1):  # fan triangles (the parts are convex in ply coordinates)
            a = [p[m][i] - p[0][i] for i in range(3)]
            b = [p[m + 1][i] - p[0][i] for i in range(3)]
            c = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
            area += 0.5 * math.sqrt(sum(x * x for x in c))
    check(count > 0, "no polygons")
    check(abs(area - report["surface_area"]) <= REL * report["surface_area"],
          "polygons' area %.17g, report.json surface_area %.17g" % (area, report["surface_area"]))

    kind = array(cd, "cell_kind")
    cshear = array(cd, "shear_deg")
    ncells = poly.GetNumberOfCells()
    check(len(kind) == ncells and len(cshear) == ncells, "cell arrays of %d and %d values, %d cells"
          % (len(kind), len(cshear), ncells))
    nv, nl = poly.GetNumberOfVerts(), poly.GetNumberOfLines()
    for k in range(min(len(kind), len(cshear))):
        want = (4,) if k < nv else (0, 1, 2) if k < nv + nl else (3,)
        check(kind[k] in want, "cell %d of kind %r, expected %s" % (k, kind[k], want))
        if k < nv + nl:
            check(math.isnan(cshear[k]), "cell %d (a link or vertex) has a shear" % k)
        elif not math.isnan(cshear[k]):
            check(0 <= cshear[k] <= 90, "cell shear %r out of [0, 90]" % cshear[k])

    return finish("check_vtk", path, failures,
                  "%d points, %d beyond the face, %d lines, %d polygons of area %.12g"
                  % (npts, beyond, nl, count, area))


if __name__ == "__main__":
    sys.exit(main())
