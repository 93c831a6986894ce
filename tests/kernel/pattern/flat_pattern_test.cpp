#include "pattern/flat_pattern.hpp"
#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include "support/problems.hpp"
#include "support/shells.hpp"
#include "support/surfaces.hpp"

#include <cmath>

using namespace plyfit;

namespace {

// Outline area and perimeter within 0.1% of exact at a spacing of 1/50 of the part.
constexpr double kOutlineRel = 1e-3;

Face builtin(const std::string& name, std::map<std::string, double> p = {}) {
  auto f = Face::create(builtin_mold(name, p).value());
  REQUIRE(f.ok());
  return std::move(f).value();
}

FlatPattern drape_flat(const Face& f, double d, Vec2 b2, std::vector<Vec2> w2, Vec3 s3, Vec3 bn,
                       std::vector<Vec3> w3, Vec2 s2 = Vec2(0, 0)) {
  auto r = drape(f, support::problem(d, s2, b2, std::move(w2), s3, bn, std::move(w3)));
  REQUIRE(r.ok());
  REQUIRE(r->metrics.nodes.failed == 0);
  REQUIRE(r->metrics.nodes.conflict == 0);
  return flat_pattern(f, *r);
}

// Loops are simple (no two non-adjacent edges cross, no two vertices closer than the ply's
// outline merge distance at spacing d), outer counter-clockwise, holes clockwise (signed area), and
// the reported area/perimeter match the points.
void check_loops(const FlatPattern& fp, double d) {
  const double merge = Tolerances{}.outline_merge_rel * d;
  for (const auto& l : fp.outline) {
    const auto& p = l.points;
    const std::size_t n = p.size();
    double a = 0.0, per = 0.0, shortest = INFINITY;
    for (std::size_t k = 0; k < n; ++k) {
      a += cross2(p[k], p[(k + 1) % n]);
      per += (p[(k + 1) % n] - p[k]).norm();
      shortest = std::min(shortest, (p[(k + 1) % n] - p[k]).norm());
    }
    CHECK(shortest > merge);
    CHECK((a > 0) == !l.hole);
    CHECK(std::abs(a) / 2 == Approx(l.area).epsilon(1e-12));
    CHECK(per == Approx(l.perimeter).epsilon(1e-12));
    int crossings = 0;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 2; j < n; ++j) {
        if (i == 0 && j == n - 1) continue;
        const Vec2 a0 = p[i], a1 = p[(i + 1) % n], b0 = p[j], b1 = p[(j + 1) % n];
        const double d1 = cross2(a1 - a0, b0 - a0), d2 = cross2(a1 - a0, b1 - a0);
        const double d3 = cross2(b1 - b0, a0 - b0), d4 = cross2(b1 - b0, a1 - b0);
        if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 &&
            d4 != 0)
          ++crossings;
      }
    }
    CHECK(crossings == 0);
  }
}

// The errors of the previous (coarser) spacing's outline: a finer one must be closer.
struct OutlineErrors {
  double area = 0, perimeter = 0;
};

// The flat pattern of a sector drape along `tang` from s3 at spacing d: one simple loop whose
// area and perimeter are within kOutlineRel of the exact A and P, and closer than `prev`'s.
FlatPattern developed(const Face& f, double d, Vec3 s3, Vec3 tang, double A, double P,
                      OutlineErrors& prev) {
  const FlatPattern fp =
      drape_flat(f, d, Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, s3, tang, {tang, -tang});
  REQUIRE(fp.outline.size() == 1);
  check_loops(fp, d);
  const double ea = std::abs(fp.area - A) / A, ep = std::abs(fp.perimeter - P) / P;
  INFO("d = " << d << " area error " << ea << " perimeter error " << ep);
  CHECK(ea < kOutlineRel);
  CHECK(ep < kOutlineRel);
  if (prev.area > 0) {
    CHECK(ea < prev.area);
    CHECK(ep < prev.perimeter);
  }
  prev = {ea, ep};
  return fp;
}

}  // namespace

TEST_CASE("flat pattern: a cylinder sector develops into the rectangle R alpha x H") {
  const double R = 10, H = 20, alpha = kPi / 2;
  const Face f = builtin("cylinder", {{"R", R}, {"H", H}, {"angle", 90}});
  const double a = 0.37;  // start off-centre, at an arbitrary height
  const Vec3 s3(R * std::cos(a), R * std::sin(a), 7.3), tang(-std::sin(a), std::cos(a), 0);
  const double size = std::max(R * alpha, H);  // ~20
  OutlineErrors prev;
  for (double d : {size / 50, size / 100}) {
    const FlatPattern fp = developed(f, d, s3, tang, R * alpha * H, 2 * (R * alpha + H), prev);
    // The staircase is coarser and inside.
    REQUIRE_FALSE(fp.staircase.empty());
    CHECK(fp.staircase[0].area < fp.area);
  }
}

TEST_CASE("flat pattern: a cone sector develops into the annular sector") {
  const double r0 = 20, r1 = 10, H = 15, alpha = kPi / 2;
  const Face f = builtin("cone", {{"r0", r0}, {"r1", r1}, {"H", H}, {"angle", 90}});
  const double L = std::hypot(r0 - r1, H);
  const double ro = r0 * L / (r0 - r1), ri = r1 * L / (r0 - r1), phi = alpha * (r0 - r1) / L;
  const double A = phi / 2 * (ro * ro - ri * ri), P = phi * (ro + ri) + 2 * L;
  const double a = kPi / 4;
  const Vec3 s3(15 * std::cos(a), 15 * std::sin(a), 7.5), tang(-std::sin(a), std::cos(a), 0);
  OutlineErrors prev;
  for (double d : {ro * phi / 50, ro * phi / 100}) developed(f, d, s3, tang, A, P, prev);
}

TEST_CASE(
    "flat pattern: every outline point of a cone sector, corners included, is within a "
    "second-order band of the exact one") {
  // The area and perimeter average errors out; this checks every point. The net's chords lie
  // within kappa d^2 / 8 of the surface (kappa its largest curvature, at the small radius:
  // cos(half-angle) / r1), so the development is that accurate up to a small factor; a band
  // of kappa d^2 / 4 holds every point with room to spare (measured 0.006 to 0.009 d^2 / mm
  // from L/50 to L/1600 against 0.0208 here). It failed where thread continuations through
  // corners solved past the face compounded (each extrapolates its last segment, doubling an
  // error): the corner cells were sheared by up to 4.5 degrees, and at d = L/400 the face's
  // corner came out 0.033 d^2 / mm (5.7e-3 d) off.
  const double r0 = 20, r1 = 10, H = 15, alpha = kPi / 2;
  const Face f = builtin("cone", {{"r0", r0}, {"r1", r1}, {"H", H}, {"angle", 90}});
  const double L = std::hypot(r0 - r1, H);
  const double ro = r0 * L / (r0 - r1), ri = r1 * L / (r0 - r1), phi = alpha * (r0 - r1) / L;
  const double kappa = std::cos(std::atan((r0 - r1) / H)) / r1;
  const double a = kPi / 4;
  const Vec3 s3(15 * std::cos(a), 15 * std::sin(a), 7.5), tang(-std::sin(a), std::cos(a), 0);
  // The start is half-way up the generator, (ro + ri) / 2 from the apex. The 2D (base,
  // sweep) = ((0, 1), (-1, 0)) turn counter-clockwise, so in 3D base x tang must point along
  // the outward normal: the base path runs down the generator, away from the apex, which
  // lies at (0, -(ro + ri) / 2) in the ply, the sector opening towards +y.
  const Vec2 apex(0, -(ro + ri) / 2);
  auto off_boundary = [&](const Vec2& p) {
    const Vec2 q = p - apex;
    const double rho = q.norm(), th = std::atan2(q.x(), q.y());
    double dist = INFINITY;
    if (std::abs(th) <= phi / 2) dist = std::min(std::abs(rho - ri), std::abs(rho - ro));
    for (double e : {-phi / 2, phi / 2}) {
      const Vec2 dir(std::sin(e), std::cos(e));
      dist = std::min(dist, (q - std::clamp(q.dot(dir), ri, ro) * dir).norm());
    }
    return dist;
  };
  for (double k : {50.0, 400.0}) {
    const double d = ro * phi / k;
    const FlatPattern fp =
        drape_flat(f, d, Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, s3, tang, {tang, -tang});
    REQUIRE(fp.outline.size() == 1);
    double worst = 0;
    Vec2 at = Vec2::Zero();
    for (const Vec2& p : fp.outline[0].points)
      if (off_boundary(p) > worst) {
        worst = off_boundary(p);
        at = p;
      }
    INFO("d = L/" << k << ": worst " << worst / (d * d) << " d^2 at (" << at.x() << ", " << at.y()
                  << ")");
    CHECK(worst <= kappa * d * d / 4);
    // The four corners of the face are in the outline, each carried in by its own cell.
    for (double e : {-phi / 2, phi / 2})
      for (double r : {ri, ro}) {
        const Vec2 c = apex + r * Vec2(std::sin(e), std::cos(e));
        double nearest = INFINITY;
        for (const Vec2& p : fp.outline[0].points) nearest = std::min(nearest, (p - c).norm());
        INFO("corner (" << c.x() << ", " << c.y() << ")");
        CHECK(nearest <= kappa * d * d / 4);
      }
  }
}

TEST_CASE("flat pattern: a circular trim hole comes out as a circle of its radius") {
  FaceData fd;
  fd.surface = plane_patch(Vec3(0, 0, 0), Vec3(100, 0, 0), Vec3(0, 100, 0));
  fd.loops.push_back({{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}});
  std::vector<Vec2> hole;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    const double t = -2 * kPi * k / n;
    hole.emplace_back(0.6 + 0.15 * std::cos(t), 0.55 + 0.15 * std::sin(t));
  }
  fd.loops.push_back({hole});
  const Face f = Face::create(fd).value();
  const FlatPattern fp =
      drape_flat(f, 2.0, Vec2(1, 0.3), {Vec2(0, 1), Vec2(0, -1)}, Vec3(30, 30, 0), Vec3(-0.3, 1, 0),
                 {Vec3(0, 1, 0), Vec3(0, -1, 0)});
  REQUIRE(fp.outline.size() == 2);
  check_loops(fp, 2.0);
  CHECK_FALSE(fp.outline[0].hole);
  CHECK(fp.outline[0].area == Approx(10000).epsilon(1e-12));
  const OutlineLoop& h = fp.outline[1];
  CHECK(h.hole);
  // On a plane the ply maps rigidly: 3D (60, 55) is 2D (30, 25) (start (0, 0) on (30, 30),
  // the base path along (1, 0.3) in both). The trim polygon is within 15 (1 - cos(pi / n))
  // of the circle.
  const double chord_gap = 15 * (1 - std::cos(kPi / n));
  for (const Vec2& p : h.points) {
    const double r = (p - Vec2(30, 25)).norm();
    CHECK(r <= 15 * (1 + 1e-12));
    CHECK(r >= 15 - chord_gap - 1e-9);
  }
  CHECK(h.area == Approx(kPi * 225).epsilon(1e-5));
  CHECK(fp.area == Approx(10000 - h.area).epsilon(1e-12));
}

TEST_CASE("flat pattern: the paper's sphere cases give one simple outline") {
  const Face f = builtin("sphere-octant");
  const FlatPattern fp =
      drape_flat(f, 1.0, Vec2(1, 0), {Vec2(0, 1)}, Vec3(0, 0, 20), Vec3(0, 1, 0), {Vec3(0, 1, 0)});
  REQUIRE(fp.outline.size() == 1);
  check_loops(fp, 1.0);
  // The pole (the start) is a right-angled corner of the pattern: the base path along x and
  // warp thread 0 along y bound it; nothing pokes past them (the pole's collapsed domain
  // edge is no boundary).
  for (const Vec2& p : fp.outline[0].points) {
    CHECK(p.x() >= -1e-9);
    CHECK(p.y() >= -1e-9);
  }
  // The cloth that covers the octant is larger than the octant's area (shear shrinks cells
  // on the surface) but not larger than the staircase plus one ring of cells.
  CHECK(fp.area > f.area());
  CHECK(fp.area > fp.staircase[0].area);
  // Case (b): the base path runs along the face's edge v = 0 (the meridian y = 0), where
  // which side a path node lies on is rounding: the outline along it is still clean.
  const FlatPattern fb = drape_flat(f, 1.0, Vec2(1, 0), {Vec2(0, 1)}, Vec3(10, 0, 10),
                                    Vec3(0, 1, 0), {Vec3(0, 1, 0)}, Vec2(20, 0));
  REQUIRE(fb.outline.size() == 1);
  check_loops(fb, 1.0);
  for (const Vec2& p : fb.outline[0].points) CHECK(p.y() >= -1e-9);
}

TEST_CASE("flat pattern: at a pole the outline has the face's corner angle") {
  // Paper case (c): start at the pole, base path at 45 degrees. Near the pole the octant's
  // 90-degree corner develops into the 2D sector between the base direction (1, 1) and
  // (-1, 1): the outline's points within 2 spacings of the start lie on those two rays.
  const Face f = builtin("sphere-octant");
  DrapeProblem pb;
  pb.ply.d_weft = pb.ply.d_warp = 1.0;
  pb.ply.start = Vec2(15, 0);
  pb.ply.base_dir = Vec2(1, 1);
  pb.ply.sweeps = {Vec2(-1, 1)};
  pb.start = Vec3(0, 0, 20);
  pb.base_normal = Vec3(0, 1, 0);
  pb.sweeps = {Vec3(0, 1, 0)};
  const auto r = drape(f, pb);
  REQUIRE(r.ok());
  const FlatPattern fp = flat_pattern(f, *r);
  REQUIRE(fp.outline.size() == 1);
  check_loops(fp, 1.0);
  int near = 0;
  for (const Vec2& p : fp.outline[0].points) {
    const Vec2 q = p - Vec2(15, 0);
    if (q.norm() > 1.5 || q.norm() == 0.0) continue;
    ++near;
    // On the ray (1, 1) or (-1, 1): |x| = y, to the crossing accuracy near the pole.
    CHECK(std::abs(std::abs(q.x()) - q.y()) < 0.01);
  }
  CHECK(near >= 2);
}

TEST_CASE(
    "flat pattern: across a fillet the outline is the net's chord length (flange-fillet-wall)") {
  // samples/flange-fillet-wall.ini: flange L = 40, fillet r = 10, wall Hw = 40, width W = 60,
  // developable; threads along x run round the fillet, those along y along its axis. The
  // threads are straight between crossings, so over the fillet each link of d is the chord of
  // an arc 2 r asin(d / 2r): the fillet's flat length is its arc pi r / 2 shortened by the
  // factor d / (2 r asin(d / 2r)) (1 - d^2 / 24 r^2), the rectangle L + pi r / 2 + Hw by W
  // otherwise. Perimeter and area agree with that to within the four links (one per free edge
  // at each tangent join) that are partly on the fillet: each is short of its arc by at most
  // 2 r asin(d / 2r) - d; the exact 311.416 is approached as d^2.
  constexpr double L = 40, r = 10, Hw = 40, W = 60;
  auto sh = support::make_builtin_shell("flange-fillet-wall");
  REQUIRE(sh.ok());
  double previous_gap = 0.0;
  for (const double d : {1.0, 0.5}) {
    INFO("d " << d);
    const auto res = drape(
        *sh, support::problem(d, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                              Vec3(-20, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}));
    REQUIRE(res.ok());
    REQUIRE(res->metrics.nodes.failed == 0);
    REQUIRE(res->metrics.nodes.conflict == 0);
    const FlatPattern fp = flat_pattern(*sh, *res);
    REQUIRE(fp.outline.size() == 1);
    const double arc_per_link = 2 * r * std::asin(d / (2 * r));
    const double fillet = (kPi * r / 2) * d / arc_per_link;
    const double join_links = 4 * (arc_per_link - d);
    CHECK(std::abs(fp.perimeter - 2 * (L + fillet + Hw + W)) <= join_links);
    CHECK(std::abs(fp.area - (L + fillet + Hw) * W) <= W * join_links);
    const double gap = 2 * (L + kPi * r / 2 + Hw + W) - fp.perimeter;
    CHECK(gap > 0.0);
    if (previous_gap > 0.0) CHECK(std::abs(previous_gap / gap - 4.0) < 0.2);
    previous_gap = gap;
  }
}

TEST_CASE("flat pattern: a strip whose surface folds back past its long edge is cut to it") {
  // A plane strip W x H at z = 0, x(u) cubic: x = W (u + 0.45 u^2 - 0.6 u^3) / 0.85, so x(1) =
  // W with dx/du > 0 on [0, 1], but past u = 1 the extension turns back at u = 1.036, x =
  // 1.0024 W: no point lies a link past the edge x = W, and no corner of the cells that edge
  // cuts can be solved there. The threads run at an angle to the strip, so the edges cut the
  // cells anywhere. The surface is a plane: the outline is the W x H rectangle, along the
  // edges to the bisection of where each link leaves the face. Only the face's two corners
  // past the folded edge are carried into the ply through cells with a placed corner (first
  // order): each within kCornerRel of a cell's area and of a link's length.
  constexpr double W = 20, H = 60, d = 1.0, kCornerRel = 0.5;
  // Bezier poles of the cubic (power basis 0, 1, 0.45, -0.6): 0, 1/3, 1/3 + (1 + 0.45) / 3, 0.85;
  // y = H v (equally spaced poles).
  FaceData fd;
  fd.surface = support::bezier_patch(3);
  const double x[4] = {0.0, 1.0 / 3, (1.0 + 1.45) / 3, 0.85};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) fd.surface.pole(i, j) = Vec3(W * x[i] / 0.85, H * j / 3, 0.0);
  auto f = Face::create(std::move(fd));
  REQUIRE(f.ok());
  for (const double deg : {10.0, 20.0, 30.0}) {
    const double th = deg * kPi / 180;
    const Vec3 w(-std::sin(th), std::cos(th), 0);
    const FlatPattern fp =
        drape_flat(*f, d, Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)}, Vec3(W / 2, H / 2, 0), w, {w, -w});
    INFO("threads at " << deg << " degrees: area " << fp.area << ", perimeter " << fp.perimeter);
    REQUIRE(fp.outline.size() == 1);
    check_loops(fp, d);
    CHECK(std::abs(fp.area - W * H) <= 2 * kCornerRel * d * d);
    CHECK(std::abs(fp.perimeter - 2 * (W + H)) <= 2 * kCornerRel * d);
  }
}
