// The paper's three graphical tools (§7, Figs. 11, 13-15) and a small 3D view as self-contained SVG
// files (no external references, no scripts):
//   flat.svg   the plane development in ply coordinates (x right = weft, y up = warp): the
//              mapped cells coloured by shear, the thread grid, the mapped links in bold, the
//              staircase outline of the mapped cells, the exact outline, the base path as
//              dots, the start point P_s and the sweep arrows, shear-warning cells, a legend
//   drape.svg  the 3D fitting in an orthographic view along ExportOptions::view (towards the
//              viewer; default isometric (1, 1, 1), Z up on the page): the mapped cells
//              coloured by shear and shaded by their slope to the view, the threads, the base
//              path, the face boundary mapped to 3D; painter's algorithm (every cell, segment
//              and node sorted by depth, far first)
//   shear.svg  the thread-angle distribution as a height field over the plane development
//              (paper Fig. 15): height = gamma from 0 to pi, drawn in an oblique parallel
//              projection (x and height true, the ply's y axis receding at 40 degrees,
//              foreshortened to 0.75) with depth sorting
//   view.svg   a small static 3D view for the ply book (plybook.html inlines it): the net from
//              a fixed oblique direction at the start, cells coloured by shear with thin
//              thread edges, coarsened to at most a few thousand triangles; no text
// Every mapped regular node is one element of class "node" in flat.svg and drape.svg; in
// shear.svg every mapped regular node with a thread angle is. Base-path nodes are class
// "path-node". Cell shear: the largest |90 deg - gamma| over the cell's corners (net_util).
// Coordinates are written with two decimals (pixels); equal inputs give equal bytes. The
// pictures are in svg/ (one file each, and their drawing: svg/draw.hpp).

#include <plyfit/exporters/exporters.hpp>

#include "plugins.hpp"
#include "svg/pictures.hpp"

namespace plyfit::exporters {

Exporter make_svg_exporter() {
  return file_exporter(
      "svg",
      "flat.svg, drape.svg, shear.svg, view.svg: plane development, 3D fitting, thread-angle "
      "field, a small 3D view",
      {{"flat.svg", svg::flat_svg},
       {"drape.svg", svg::drape_svg},
       {"shear.svg", svg::shear_svg},
       {"view.svg", svg::view_svg}});
}

}  // namespace plyfit::exporters
