#include "pattern/cells.hpp"
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"

#include "support/problems.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>
#include "surface/face.hpp"

using namespace plyfit;

namespace {

// The cells within `ring` of a mapped node, each once, in the order of the nodes: the
// definition, with a std::set.
std::vector<std::pair<int, int>> touched_reference(const DrapeResult& r, int ring) {
  std::set<std::pair<int, int>> seen;
  std::vector<std::pair<int, int>> out;
  const double dx = r.ply->spec().d_weft, dy = r.ply->spec().d_warp;
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped()) continue;
    int i = n.id.i, j = n.id.j;
    if (n.id.is_path_only()) {
      i = static_cast<int>(std::floor(n.ply.x() / dx));
      j = static_cast<int>(std::floor(n.ply.y() / dy));
    }
    for (int a = -1 - ring; a <= ring; ++a)
      for (int b = -1 - ring; b <= ring; ++b)
        if (seen.insert({i + a, j + b}).second) out.push_back({i + a, j + b});
  }
  return out;
}

// Box of the touched cells over the mapped nodes, in cells per mapped node.
double box_cells_per_node(const DrapeResult& r) {
  int i0 = INT32_MAX, i1 = INT32_MIN, j0 = INT32_MAX, j1 = INT32_MIN, n = 0;
  for (const DrapeNode& d : r.nodes)
    if (d.mapped() && !d.id.is_path_only()) {
      i0 = std::min(i0, d.id.i);
      i1 = std::max(i1, d.id.i);
      j0 = std::min(j0, d.id.j);
      j1 = std::max(j1, d.id.j);
      ++n;
    }
  return static_cast<double>(i1 - i0 + 1) * (j1 - j0 + 1) / n;
}

}  // namespace

TEST_CASE("cells: touched_cells lists every cell near a mapped node once, in node order") {
  // A square plate (the touched cells fill their box: a bitmap) and a 1000 x 2 mm strip at
  // 45 degrees to the threads (a thin diagonal band of cells in a box hundreds of times
  // larger than the node count: a hash set). Both ways must give the definition.
  struct Case {
    const char* name;
    Vec3 u_edge, v_edge, start;
    bool sparse;
  };
  for (const Case& c :
       {Case{"square plate", Vec3(40, 0, 0), Vec3(0, 40, 0), Vec3(20, 20, 0), false},
        Case{"diagonal strip", Vec3(1000, 0, 0), Vec3(0, 2, 0), Vec3(500, 1, 0), true}}) {
    INFO(c.name);
    FaceData fd;
    fd.surface = plane_patch(Vec3(0, 0, 0), c.u_edge, c.v_edge);
    auto f = Face::create(fd);
    REQUIRE(f.ok());
    const auto r =
        drape(*f, support::problem(1.0, Vec2(0, 0), Vec2(1, 1), {Vec2(-1, 1), Vec2(1, -1)}, c.start,
                                   Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
    REQUIRE(r.ok());
    REQUIRE(r->metrics.nodes.mapped > 100);
    // The hash set is used beyond 16 cells of the box per node.
    CHECK((box_cells_per_node(*r) > 16) == c.sparse);
    for (int ring : {0, 1}) {
      std::vector<std::pair<int, int>> got;
      for (const auto [i, j] : touched_cells(*r, ring)) got.push_back({i, j});
      CHECK(got == touched_reference(*r, ring));
    }
  }
}
