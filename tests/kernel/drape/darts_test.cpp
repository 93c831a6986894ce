#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>

#include <catch2/catch.hpp>

#include "drape/darts.hpp"
#include "drape/drape.hpp"
#include "drape/scan/solve_memo.hpp"
#include "support/builtin_surfaces.hpp"
#include "support/problems.hpp"

#include <algorithm>
#include <cmath>
#include <random>

using namespace plyfit;

namespace {

// On a plane both sides of a dart drape as the uncut ply: its cut lines coincide to the
// solver's accuracy (links to 1e-10 d), relative to d.
constexpr double kFlatRel = 1e-9;

// The drape of a result that must not be an error.
DrapeResult ok(Result<DrapeResult> r) {
  INFO((r.ok() ? std::string() : exporters::describe(r.error())));
  REQUIRE(r.ok());
  return std::move(r).value();
}

// Largest shear (|90 deg - thread angle|) of the mapped nodes within `reach` of a curve.
double shear_near(const DrapeResult& r, const std::vector<Vec3>& curve, double reach) {
  double m = 0.0;
  for (const auto& n : r.nodes) {
    if (!n.has(DrapeNode::kHasAngle) || !n.mapped()) continue;
    double dist = INFINITY;
    for (const Vec3& p : curve) dist = std::min(dist, (p - n.point).norm());
    if (dist <= reach) m = std::max(m, std::abs(kPi / 2 - n.thread_angle));
  }
  return m;
}

using support::builtin_surface;
using support::problem;

}  // namespace

TEST_CASE("darts: the frozen grid finds points as the cube grid does, and boxes in their cubes") {
  // Points on a sphere of radius 3 and off it, some in one cube, some on cube faces (integer
  // coordinates at cell 0.5), negative coordinates too; a third left out.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> pts;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p(u(rng), u(rng), u(rng));
    pts.push_back(k % 5 == 0 ? Vec3(std::round(4 * p.x()) / 2, std::round(4 * p.y()) / 2, 0.0)
                             : Vec3(3.0 * p.normalized() + 0.1 * p));
  }
  const double cell = 0.5;
  const auto keep = [](std::uint32_t k) { return k % 3 != 1; };
  detail::NodeGrid loose;
  loose.cell = cell;
  for (std::uint32_t k = 0; k < pts.size(); ++k)
    if (keep(k)) loose.add(pts[k], k);
  const detail::FrozenGrid frozen(cell, static_cast<std::uint32_t>(pts.size()), keep,
                                  [&](std::uint32_t k) { return pts[k]; });
  std::size_t seen = 0;
  for (int q = 0; q < 500; ++q) {
    const Vec3 p = 3.5 * Vec3(u(rng), u(rng), u(rng));
    std::vector<std::uint32_t> a, b;
    loose.around(p, [&](std::uint32_t k) { a.push_back(k); });
    frozen.around(p, [&](std::uint32_t k) { b.push_back(k); });
    REQUIRE(a == b);
    seen += a.size();
  }
  CHECK(seen > 1000);  // the queries met points, not only empty cubes

  // Boxes in every cube they meet: the cube holding p lists the boxes whose cubes hold it, in
  // increasing order.
  std::vector<std::pair<Vec3, Vec3>> boxes;
  for (int k = 0; k < 300; ++k) {
    const Vec3 a = 3.0 * Vec3(u(rng), u(rng), u(rng)), b = a + Vec3(u(rng), u(rng), u(rng));
    boxes.emplace_back(a.cwiseMin(b), a.cwiseMax(b));
  }
  const detail::CubeKeys cubes{cell};
  auto holds = [&](std::size_t k, const Vec3& p) {
    for (int i = 0; i < 3; ++i)
      if (cubes.at(p[i]) < cubes.at(boxes[k].first[i]) ||
          cubes.at(p[i]) > cubes.at(boxes[k].second[i]))
        return false;
    return true;
  };
  const detail::FrozenGrid boxed(
      cell, static_cast<std::uint32_t>(boxes.size()),
      [&](std::uint32_t k, auto&& emit) { cubes.in_box(boxes[k].first, boxes[k].second, emit); });
  std::size_t listed = 0;
  for (int q = 0; q < 500; ++q) {
    const Vec3 p = 3.5 * Vec3(u(rng), u(rng), u(rng));
    std::vector<std::uint32_t> want, got;
    for (std::uint32_t k = 0; k < boxes.size(); ++k)
      if (holds(k, p)) want.push_back(k);
    for (std::uint32_t k : boxed.in(p)) got.push_back(k);
    REQUIRE(got == want);
    listed += got.size();
  }
  CHECK(listed > 100);
}

TEST_CASE("darts: a straight dart on a plane cuts the links it crosses and opens nothing") {
  const MoldSurface f = builtin_surface("plane");  // [0, 100]^2, z = 0
  const double d = 2.0;
  // Nodes at 3D (2i + 49.7, 2j + 49.3): the start (0.3, 0.7) of the ply lands on (50, 50).
  DrapeProblem pb = problem(d, Vec2(0.3, 0.7), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                            Vec3(50, 50, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  const DrapeResult plain = ok(drape(f, pb));
  const Vec3 a(20.3, 0, 0), b(60.3, 35.1, 0);  // from the edge y = 0 into the ply
  pb.darts = {{a, b}};
  const DrapeResult r = ok(drape(f, pb));
  REQUIRE(r.darts.size() == 1);
  const DartResult& dart = r.darts[0];
  // It crosses the warp threads x = 23.7, ..., 59.7 (19; x = 21.7 below y = 1.3, where that
  // thread's link leaves the plane) and the weft threads y = 1.3, 3.3, ..., 33.3 (17): one
  // link of each between nodes on the plane.
  CHECK(dart.links_cut == 36);
  CHECK(dart.nodes_cut_out == 0);
  CHECK(dart.length == Approx((b - a).norm()).epsilon(1e-12));
  CHECK((dart.tip - b).norm() < kFlatRel * d);
  // Both sides drape as the uncut ply: every node, the same area.
  CHECK(r.metrics.nodes.mapped == plain.metrics.nodes.mapped);
  CHECK(r.metrics.nodes.conflict == 0);
  CHECK(r.metrics.flat_area == Approx(plain.metrics.flat_area).epsilon(1e-12));
  CHECK(r.metrics.edge_length_max_rel < kFlatRel);
  // The two cut lines are the curve moved by the ply's offset, and coincide.
  REQUIRE(dart.line_left.size() >= static_cast<std::size_t>((b - a).norm() / d));
  REQUIRE(dart.line_left.size() == dart.line_right.size());
  const Vec2 shift(50 - 0.3, 50 - 0.7);
  for (std::size_t i = 0; i < dart.line_left.size(); ++i) {
    CHECK((dart.line_left[i] - dart.line_right[i]).norm() < kFlatRel * d);
    const Vec2 p = dart.line_left[i] + shift;  // on the segment a-b
    const Vec2 e = (b - a).head<2>().normalized();
    CHECK(std::abs(cross2(e, p - a.head<2>())) < kFlatRel * d);
  }
  CHECK(dart.width_max < kFlatRel * d);
  CHECK(dart.removed_area < kFlatRel * d * d);
  CHECK(dart.opening_area < kFlatRel * d * d);
}

TEST_CASE("darts: a dart on a hemisphere from the rim lowers the shear beside it and cuts a V") {
  const double R = 10.0, d = 0.5;
  const MoldSurface f = builtin_surface("hemisphere", {{"R", R}});
  // Base path on the plane x = 0 through the pole, sweeps both ways: the most sheared cloth
  // lies on the meridians half-way between the threads through the pole (azimuth 45 deg).
  DrapeProblem pb = support::pole_problem(R, d);
  const DrapeResult plain = ok(drape(f, pb));
  // The dart: that meridian from the rim up to 40 degrees from the pole.
  const std::vector<Vec3> curve = support::meridian_dart(R);
  pb.darts = {curve};
  const DrapeResult r = ok(drape(f, pb));
  REQUIRE(r.darts.size() == 1);
  const DartResult& dart = r.darts[0];
  CHECK(dart.length == Approx(R * 50.0 * kDegToRad).epsilon(1e-3));
  const double before = shear_near(plain, curve, 2 * d), after = shear_near(r, curve, 2 * d);
  INFO("shear beside the dart: " << before * kRadToDeg << " deg without it, " << after * kRadToDeg
                                 << " deg with it; V " << dart.removed_area << " mm2 cut out, "
                                 << dart.opening_area << " mm2 open, width " << dart.width_max
                                 << ", cut out nodes " << dart.nodes_cut_out << ", links cut "
                                 << dart.links_cut << ", points " << dart.line_left.size());
  CHECK(after < before);
  // A sphere holds less surface round a point than the plane: the two sides' cloth would
  // overlap at the dart, and the V between the cut lines is cut out.
  CHECK(dart.removed_area > 0.0);
  CHECK(dart.removed_area > 10.0 * dart.opening_area);
  CHECK(dart.nodes_cut_out > 0);  // ply nodes in the V: no side's cloth holds them
  CHECK(r.metrics.nodes.conflict == 0);
}

TEST_CASE("darts: bad dart curves are errors with codes") {
  const MoldSurface f = builtin_surface("plane");
  DrapeProblem pb = problem(2.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, Vec3(50, 50, 0),
                            Vec3(0, 1, 0), {Vec3(0, 1, 0)});
  pb.darts = {{Vec3(10, 10, 0)}};
  auto one = drape(f, pb);
  REQUIRE_FALSE(one.ok());
  CHECK(one.error().code == ErrorCode::kDartCurvePoints);
  pb.darts = {{Vec3(10, 10, 0), Vec3(20, 20, 5)}};  // 5 mm above a 141 mm mold
  auto off = drape(f, pb);
  REQUIRE_FALSE(off.ok());
  CHECK(off.error().code == ErrorCode::kDartOffMold);
  pb.darts = {{Vec3(10, 10, 0), Vec3(NAN, 20, 0)}};
  auto nan = drape(f, pb);
  REQUIRE_FALSE(nan.ok());
  CHECK(nan.error().code == ErrorCode::kDartCurvePoints);
}

TEST_CASE("darts: automatic darts on a hemisphere locked at 40 degrees") {
  const double R = 10.0, d = 0.5;
  const MoldSurface f = builtin_surface("hemisphere", {{"R", R}});
  const DrapeProblem pb = problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)},
                                  Vec3(0, 0, R), Vec3(1, 0, 0), {Vec3(1, 0, 0), Vec3(-1, 0, 0)});
  DrapeOptions opt;
  opt.lock_angle = 40.0 * kDegToRad;
  const DrapeResult plain = ok(drape(f, pb, opt));
  // The cloth shears most on the meridians between the threads through the pole: it locks
  // there before the rim.
  REQUIRE(plain.metrics.nodes.shear_limit > 0);
  const DrapeResult r = ok(drape_auto_darts(f, pb, opt, 3));
  INFO("without darts: " << plain.metrics.nodes.shear_limit << " shear-limit, "
                         << plain.metrics.nodes.conflict << " conflict, "
                         << plain.metrics.nodes.mapped << " mapped; with " << r.darts.size()
                         << " automatic darts after " << r.drapes
                         << " drapes: " << r.metrics.nodes.shear_limit << " shear-limit, "
                         << r.metrics.nodes.conflict << " conflict, " << r.metrics.nodes.mapped
                         << " mapped, shear max " << r.metrics.shear_max * kRadToDeg);
  CHECK(r.darts_auto);
  CHECK(r.drapes <= 3);
  CHECK(!r.darts.empty());
  CHECK(r.metrics.nodes.conflict == 0);
  CHECK(r.metrics.nodes.shear_limit == 0);
  CHECK(r.metrics.shear_max <= opt.lock_angle);
}

TEST_CASE("darts: a drape made again takes the unchanged solves and lays what a fresh one does") {
  const double R = 10.0, d = 0.5;
  const MoldSurface f = builtin_surface("hemisphere", {{"R", R}});
  DrapeProblem pb = problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, Vec3(0, 0, R),
                            Vec3(1, 0, 0), {Vec3(1, 0, 0), Vec3(-1, 0, 0)});
  detail::SolveMemo first;
  const DrapeResult plain = ok(drape(f.impl(), pb, {}, detail::Redrape{nullptr, nullptr, &first}));
  // A dart on the meridian at azimuth 45 deg from the rim up to 40 deg from the pole: the cloth
  // swept before it reaches the dart's cells is the same as without it.
  std::vector<Vec3> curve;
  for (double polar = 90.0; polar >= 40.0; polar -= 1.0) {
    const double t = polar * kDegToRad, az = 45.0 * kDegToRad;
    curve.push_back(R * Vec3(std::sin(t) * std::cos(az), std::sin(t) * std::sin(az), std::cos(t)));
  }
  auto darts = detail::DartSet::create(f.impl(), {curve}, d, Tolerances{});
  REQUIRE(darts);
  detail::SolveMemo next;
  const auto set = std::make_shared<const detail::DartSet>(*darts);
  const DrapeResult again = ok(drape(f.impl(), pb, {}, detail::Redrape{set, &first, &next}));
  const DrapeResult fresh = ok(drape(f.impl(), pb, {}, detail::Redrape{set}));
  INFO("nodes " << fresh.nodes.size() << ", solves taken from the drape before " << next.reused);
  CHECK(next.reused > 0);
  CHECK(next.reused < fresh.nodes.size());
  // Every node as the fresh drape has it: the same status and, mapped, the same point to the
  // solver's accuracy (links to 1e-10 d).
  REQUIRE(again.nodes.size() == fresh.nodes.size());
  std::size_t differ = 0;
  double moved = 0.0;
  for (const DrapeNode& n : fresh.nodes) {
    const DrapeNode* m = again.find(n.id);
    if (!m || m->status != n.status) {
      ++differ;
      continue;
    }
    if (n.mapped()) moved = std::max(moved, (m->point - n.point).norm());
  }
  CHECK(differ == 0);
  CHECK(moved < kFlatRel * d);
  CHECK(again.darts.size() == 1);
  CHECK(again.darts[0].removed_area == Approx(fresh.darts[0].removed_area).epsilon(1e-6));
  CHECK(plain.metrics.nodes.mapped > 0);
}

TEST_CASE("darts: the scan's seams cut the links where fronts meet round a closed torus") {
  // The outer half of a torus, closed round its axis: cloth laid from the outer equator goes
  // round both ways and its fronts meet behind the axis, where they disagree (conflict nodes).
  const double R = 30.0, r = 10.0, d = 1.0;
  const MoldSurface f =
      builtin_surface("torus", {{"R", R}, {"r", r}, {"t0", -90.0}, {"t1", 90.0}, {"angle", 360.0}});
  const DrapeProblem pb =
      problem(d, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, Vec3(R + r, 0, 0),
              Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  const DrapeResult plain = ok(drape(f, pb));
  REQUIRE(plain.metrics.nodes.conflict > 0);
  const DrapeResult seamed =
      ok(drape(f.impl(), pb, {}, detail::Redrape{nullptr, nullptr, nullptr, true}));
  INFO(plain.metrics.nodes.conflict
       << " conflict nodes, " << plain.metrics.nodes.mapped << " mapped, "
       << plain.metrics.nodes.overlap << " overlap without seams; with seams "
       << seamed.metrics.nodes.mapped << " mapped, " << seamed.metrics.nodes.overlap << " overlap, "
       << seamed.cut_links.size() << " links cut, " << seamed.darts.size() << " seams");
  CHECK(seamed.metrics.nodes.conflict == 0);
  REQUIRE(!seamed.darts.empty());
  for (const DartResult& dart : seamed.darts) CHECK(dart.seam);
  // Measured on the part: every link between mapped nodes that the scan kept has its rest
  // length (the solver's accuracy), every link it cut is off by more than that (two fronts
  // that disagree), and a seam passes between its two ends: the seam's point nearest the
  // link's midpoint on the surface, the seam's direction there (through the points before
  // and after it), the two ends on the two sides of it (seen along the normal).
  std::uint64_t kept = 0, cut_links = 0, parted = 0;
  double kept_err = 0.0, cut_err = INFINITY;
  auto parts = [&](const Vec3& a, const Vec3& b) {
    const Projection mid = f.impl().project(0.5 * (a + b));
    const std::vector<Vec3>* best = nullptr;
    std::size_t at = 0;
    for (const DartResult& dart : seamed.darts)
      for (std::size_t k = 0; k < dart.curve.size(); ++k)
        if (!best || (dart.curve[k] - mid.point).norm() < ((*best)[at] - mid.point).norm())
          best = &dart.curve, at = k;
    const std::vector<Vec3>& c = *best;
    const Vec3 t = c[std::min(at + 1, c.size() - 1)] - c[at > 0 ? at - 1 : 0];
    const Vec3 left = f.impl().normal(mid.at).n.cross(t);
    return ((a - c[at]).dot(left) > 0.0) != ((b - c[at]).dot(left) > 0.0);
  };
  for (std::uint32_t k = 0; k < seamed.nodes.size(); ++k) {
    const DrapeNode& a = seamed.nodes[k];
    if (!a.mapped()) continue;
    for (ThreadDir dir : {ThreadDir::kPlusX, ThreadDir::kPlusY}) {
      const DrapeNode* b = seamed.neighbour(a, dir);
      if (!b || !b->mapped()) continue;
      const double err = std::abs((b->point - a.point).norm() - (b->ply - a.ply).norm()) / d;
      if (seamed.cut(k, seamed.index_of(*b))) {
        ++cut_links;
        cut_err = std::min(cut_err, err);
        parted += parts(a.point, b->point);
      } else {
        ++kept;
        kept_err = std::max(kept_err, err);
      }
    }
  }
  INFO(kept << " links kept (largest error " << kept_err << " d), " << cut_links
            << " cut (smallest error " << cut_err << " d), " << parted << " parted by a seam");
  CHECK(kept_err < 1e-9);
  CHECK(cut_links > 0);
  CHECK(cut_err > 1e-9);
  CHECK(parted == cut_links);
  // Every point of a seam lies on the torus (its distance to the tube's circle is r).
  const double on_surface = 1e-9 * R;
  for (const DartResult& dart : seamed.darts)
    for (const Vec3& p : dart.curve)
      CHECK(std::abs(std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r) <= on_surface);
  // With automatic darts (from the face's edge, and seams where fronts still meet): no
  // conflict left.
  const DrapeResult cut = ok(drape_auto_darts(f, pb, DrapeOptions{}, 3));
  INFO("with " << cut.darts.size() << " darts after " << cut.drapes << " drapes: "
               << cut.metrics.nodes.conflict << " conflict, " << cut.metrics.nodes.mapped
               << " mapped (" << plain.metrics.nodes.mapped << " without)");
  CHECK(cut.drapes <= 3);
  CHECK(cut.metrics.nodes.conflict == 0);
}
