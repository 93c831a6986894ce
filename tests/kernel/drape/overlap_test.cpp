// The overlap test is complete (issue 13 item 4): every mapped node that lands on cloth
// already laid is flagged, on open faces too, not only on faces that close on themselves.
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "surface/face.hpp"

#include <catch2/catch.hpp>

#include "drape/scan/overlap_grid.hpp"
#include "support/net_checks.hpp"
#include "support/problems.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace plyfit;
using plyfit::support::problem;

namespace {

// The drape's overlap criterion (scanner.hpp), restated: a node within this fraction of d
// (3D) of another at least kSeparation d away from it on the ply lies on cloth already laid.
constexpr double kNearRel = 0.5;
constexpr double kSeparation = 2.0;

// A node of the grid test below: 3D point and ply position.
struct GridNode {
  Vec3 p;
  Vec2 ply;
};

// Pairs of mapped nodes that break the criterion, by brute force.
int cloth_on_cloth(const DrapeResult& r, double d) {
  int pairs = 0;
  for (std::size_t a = 0; a < r.nodes.size(); ++a) {
    const DrapeNode& p = r.nodes[a];
    if (!p.mapped()) continue;
    for (std::size_t b = a + 1; b < r.nodes.size(); ++b) {
      const DrapeNode& q = r.nodes[b];
      if (q.mapped() && (p.point - q.point).norm() < kNearRel * d &&
          (p.ply - q.ply).norm() >= kSeparation * d)
        ++pairs;
    }
  }
  return pairs;
}

// An open cylinder face (R 10, height 20) running 450 degrees round its axis: its first
// quarter turn lies under its last.
Face cylinder_450() {
  FaceData fd;
  fd.surface = cylinder_patch(10.0, 0.0, 2.5 * kPi, 0.0, 20.0);
  auto f = Face::create(std::move(fd));
  REQUIRE(f.ok());
  return std::move(f).value();
}

// Its drape at spacing d: base path along the axis half-way round, swept both ways round, so
// that the fronts lay cloth over the same quarter turn from both ends.
DrapeProblem cylinder_450_problem(double d) {
  const double a = 1.25 * kPi;  // half-way round
  const Vec3 s3(10 * std::cos(a), 10 * std::sin(a), 10.0);
  const Vec3 t(-std::sin(a), std::cos(a), 0.0);  // round the axis, increasing angle
  return problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(1, 0), Vec2(-1, 0)}, s3, t, {t, Vec3(-t)});
}

}  // namespace

TEST_CASE("drape: cloth landing on cloth already laid is flagged on an open face") {
  // An open cylinder face running 450 degrees round its axis: the first quarter turn is
  // covered twice. Base path along the axis half-way round, swept both ways round: the
  // fronts lay cloth over the same quarter turn from both ends. The net is not sheared.
  for (double d : {1.0, 0.7}) {
    INFO("d = " << d);
    const Face f = cylinder_450();
    REQUIRE_FALSE(f.closes_on_itself());
    auto rr = drape(f, cylinder_450_problem(d));
    REQUIRE(rr.ok());
    const DrapeResult& r = rr.value();
    CHECK(r.metrics.nodes.overlap > 0);
    CHECK(r.metrics.nodes.failed == 0);
    CHECK(r.metrics.nodes.conflict == 0);
    CHECK(cloth_on_cloth(r, d) == 0);
    // A full turn of cloth is laid: about the face's circumference times its height.
    CHECK(r.metrics.surface_area > 0.9 * 2 * kPi * 10 * 20);
  }
}

TEST_CASE("overlap grid: the filtered test answers as the all-double one, at the radius") {
  // OverlapGrid filters in 16-bit integer units relative to its cells and leaves the decision to
  // the exact test: it must find every recorded node the exact test accepts, whatever the scale and
  // the distance from the origin. A flat sheet of recorded nodes; then cloth coming back
  // over it (ply positions far away) at unfavourable places: within a hair of the radius of
  // a recorded node (inside and outside), on cell boundaries, between recorded nodes, and
  // anywhere. Every answer is compared with a brute-force test over the recorded nodes.
  struct Scale {
    double d;
    Vec3 origin;
  };
  for (const Scale& sc : {Scale{1.0, Vec3(0, 0, 0)}, Scale{1e-3, Vec3(1e4, -2e4, 3e3)},
                          Scale{50.0, Vec3(-3e5, 1e5, 7e4)}}) {
    const double d = sc.d, r = kNearRel * d, sep = kSeparation * d;
    INFO("d = " << d);
    std::vector<GridNode> nodes;
    std::vector<std::uint32_t> recorded;
    plyfit::detail::OverlapGrid grid;
    grid.init(r, 64);  // small: the slot table grows
    auto exact = [&](const GridNode& n, std::uint32_t m) {
      return (nodes[m].p - n.p).squaredNorm() < r * r && (nodes[m].ply - n.ply).norm() >= sep;
    };
    int hits = 0, checked = 0;
    auto add = [&](const Vec3& p, const Vec2& ply) {
      nodes.push_back({p, ply});
      const auto k = static_cast<std::uint32_t>(nodes.size() - 1);
      bool brute = false;
      for (std::uint32_t m : recorded) brute = brute || exact(nodes[k], m);
      const bool got = grid.test_insert(p, k, [&](std::uint32_t m) { return exact(nodes[k], m); });
      CHECK(got == brute);
      if (!got) recorded.push_back(k);
      hits += got ? 1 : 0;
      ++checked;
    };
    constexpr int kSide = 24;
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) add(sc.origin + Vec3(i * d, j * d, 0.0), Vec2(i * d, j * d));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::size_t sheet = recorded.size();
    for (int n = 0; n < 3000; ++n) {
      const Vec2 far(1e3 * d + n * 3 * d, 0.0);  // no two of the returning nodes are near
      const GridNode& m = nodes[recorded[static_cast<std::size_t>(n) % sheet]];
      Vec3 dir(u(rng), u(rng), u(rng));
      dir.normalize();
      const double rel[] = {-1e-12, 1e-12, -1e-7, 1e-7, -1e-5, 1e-5, 1e-4, 2e-4, u(rng) * 0.5};
      Vec3 p = m.p + dir * r * (1 + rel[n % 9]);
      if (n % 5 == 1) p = m.p + Vec3(0.5 * d, 0.5 * d, u(rng) * r);  // between recorded nodes
      if (n % 7 == 2) {  // on a cell boundary (cell edge kCellRadii * r from the origin)
        const double edge = plyfit::detail::OverlapGrid::kCellRadii * r;
        p.x() = std::round(p.x() / edge) * edge;
      }
      add(p, far);
    }
    CHECK(checked == kSide * kSide + 3000);
    CHECK(hits > 1000);  // most of the returning cloth lands on the sheet
    CHECK(hits < 3000);
  }
}

TEST_CASE("overlap grid: nodes near cell corners are found in every neighbouring cell") {
  // A test reads p's own cell and the neighbours its ball meets along one, two or three axes
  // (a cell's edge, its corner). Points clustered round cell corners, edges and faces, on
  // both sides of the origin (negative cell coordinates), each far from all others on the
  // ply: every answer is compared with a brute-force test over the recorded nodes.
  const double r = 0.5, edge = plyfit::detail::OverlapGrid::kCellRadii * r;
  std::vector<Vec3> pts;
  std::vector<std::uint32_t> recorded;
  plyfit::detail::OverlapGrid grid;
  grid.init(r, 16);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> cell(-2, 2);
  int hits = 0, misses = 0;
  for (int n = 0; n < 4000; ++n) {
    // A corner of the cell grid, moved off it along none, one or two axes (a face or an
    // edge of the cells), and a point within 1.5 radii of that.
    Vec3 c(cell(rng) * edge, cell(rng) * edge, cell(rng) * edge);
    for (int a = 0; a < 3; ++a)
      if ((n >> a) % 3 == 0) c[a] += 0.5 * edge;
    const Vec3 p = c + 1.5 * r * Vec3(u(rng), u(rng), u(rng));
    pts.push_back(p);
    const auto k = static_cast<std::uint32_t>(pts.size() - 1);
    bool brute = false;
    for (std::uint32_t m : recorded) brute = brute || (pts[m] - p).squaredNorm() < r * r;
    const bool got =
        grid.test_insert(p, k, [&](std::uint32_t m) { return (pts[m] - p).squaredNorm() < r * r; });
    CHECK(got == brute);
    if (!got) recorded.push_back(k);
    (got ? hits : misses) += 1;
  }
  CHECK(hits > 500);  // both answers are common
  CHECK(misses > 500);
}

TEST_CASE("overlap grid: a grid of many pages hands the exact test the right nodes") {
  // Chunks come from pages, each with its chunks' node indices. Nodes on a lattice 6 radii
  // apart (eight in a cell, one chunk each), 40 000 chunks in some 40 pages; then points just
  // within and just beyond the radius of lattice nodes (the exact test accepts lattice nodes only).
  // It must be offered the node it accepts and no node beyond the filter's distance (a
  // lane's index from another chunk or page would be a node far away).
  const double r = 0.5, s = 6 * r;
  std::vector<Vec3> pts;
  plyfit::detail::OverlapGrid grid;
  grid.init(r, 16);
  const int nx = 40, ny = 40, nz = 200;  // 40 000 cells
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        pts.push_back(Vec3(i * s - 7.0, j * s + 3.0, k * s - 100.0));
        const auto n = static_cast<std::uint32_t>(pts.size() - 1);
        REQUIRE_FALSE(grid.test_insert(pts.back(), n, [](std::uint32_t) { return true; }));
      }
  const std::size_t lattice = pts.size();
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> pick(0, lattice - 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int offered_far = 0, wrong = 0;
  for (int n = 0; n < 20000; ++n) {
    const std::size_t m = pick(rng);
    Vec3 dir(u(rng), u(rng), u(rng));
    dir.normalize();
    const bool inside = n % 2 == 0;
    const Vec3 p = pts[m] + dir * r * (inside ? 1 - 1e-9 : 1 + 1e-9);
    bool offered_m = false;
    const auto k = static_cast<std::uint32_t>(pts.size());
    pts.push_back(p);  // recorded if the exact test accepts no node
    const bool got = grid.test_insert(p, k, [&](std::uint32_t o) {
      if (o >= k || (pts[o] - p).norm() > 1.01 * r) ++offered_far;
      offered_m = offered_m || o == m;
      return o < lattice && (pts[o] - p).squaredNorm() < r * r;
    });
    if (got != inside || (inside && !offered_m)) ++wrong;
  }
  CHECK(wrong == 0);
  CHECK(offered_far == 0);
  // init() empties the grid for the next drape.
  grid.init(r, 16);
  CHECK_FALSE(grid.test_insert(pts[0], 0, [](std::uint32_t) { return true; }));
}

TEST_CASE("overlap grid: a grid reuses the memory its thread's last grid left, not its nodes") {
  // A drape leaves its grid's slots and pages to the next drape on the thread. The next grid
  // must find none of the old nodes (stale lanes or slots would make cloth on an empty face),
  // and find its own, with their own indices; a grid made while another is alive (a drape
  // within a drape) has memory of its own.
  using plyfit::detail::OverlapGrid;
  const double r = 0.5, s = 6 * r;
  std::vector<Vec3> pts;
  for (int k = 0; k < 60; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 30; ++i) pts.push_back(Vec3(i * s, j * s, k * s));  // ~50 pages
  auto accept_all = [](std::uint32_t) { return true; };
  OverlapGrid::release_thread_spare();
  CHECK(OverlapGrid::thread_spare_bytes() == 0);
  {
    OverlapGrid a;
    a.init(r, pts.size());  // as b: the same table size
    for (std::size_t n = 0; n < pts.size(); ++n)
      REQUIRE_FALSE(a.test_insert(pts[n], static_cast<std::uint32_t>(n), accept_all));
  }
  const std::size_t left = OverlapGrid::thread_spare_bytes();
  CHECK(left > pts.size() * 8);  // pages of a's nodes, and its slots
  OverlapGrid b;
  b.init(r, pts.size());
  CHECK(OverlapGrid::thread_spare_bytes() == 0);  // b took them
  // a's nodes are gone: b records every point again, a little off, under new indices.
  const auto base = static_cast<std::uint32_t>(pts.size());
  int stale = 0;
  for (std::size_t n = 0; n < pts.size(); ++n)
    if (b.test_insert(pts[n] + Vec3(0.1, 0, 0), base + static_cast<std::uint32_t>(n), accept_all))
      ++stale;
  CHECK(stale == 0);
  // b's own nodes are found, each by its own index.
  int wrong = 0;
  for (std::size_t n = 0; n < pts.size(); n += 7) {
    std::uint32_t got = 0;
    const bool hit = b.test_insert(pts[n], 0, [&](std::uint32_t o) {
      got = o;
      return true;
    });
    if (!hit || got != base + n) ++wrong;
  }
  CHECK(wrong == 0);
  {
    OverlapGrid c;  // while b is alive: fresh memory, empty
    c.init(r, 16);
    CHECK_FALSE(c.test_insert(pts[0], 0, accept_all));
    CHECK(c.test_insert(pts[0], 1, accept_all));
  }
  CHECK(OverlapGrid::thread_spare_bytes() > 0);  // c's memory, left for the next grid
  OverlapGrid::release_thread_spare();
  CHECK(OverlapGrid::thread_spare_bytes() == 0);
}

TEST_CASE("drape: a drape after others on the same thread is the same drape") {
  // The second drape of the 450 degree cylinder (cloth laid twice over a quarter turn)
  // reuses the overlap grid an octant's drape left (more nodes, another spacing): it must lay
  // the same cloth, node for node, as a first drape.
  const Face cyl = cylinder_450();
  auto oct = Face::create(builtin_mold("sphere-octant", {{"R", 20.0}}).value());
  REQUIRE(oct.ok());
  const DrapeProblem pc = cylinder_450_problem(0.7);
  const DrapeProblem po = problem(0.1, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, Vec3(10, 0, 10),
                                  Vec3(0, 1, 0), {Vec3(0, 1, 0)});
  release_drape_scratch();
  auto first = drape(cyl, pc);
  REQUIRE(first.ok());
  const DrapeResult& r1 = first.value();
  CHECK(r1.metrics.nodes.overlap > 0);  // the grid answers
  // Node for node: the same statuses, mapped nodes at the same points to the bit (tol 0).
  auto same = [&r1](const DrapeResult& r2) { support::same_net(r1, r2, 0.0); };
  auto twice = drape(cyl, pc);  // the first's grid: the same table size
  REQUIRE(twice.ok());
  same(twice.value());
  auto other = drape(oct.value(), po);
  REQUIRE(other.ok());
  CHECK(other.value().metrics.nodes.mapped > r1.metrics.nodes.mapped);
  auto again = drape(cyl, pc);  // the octant's grid
  REQUIRE(again.ok());
  same(again.value());
  release_drape_scratch();
}
