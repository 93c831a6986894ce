#include <plyfit/kernel/splice.hpp>

#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/face.hpp"

#include <catch2/catch.hpp>

#include "support/problems.hpp"

#include <cmath>

using namespace plyfit;

namespace {

// A quarter cylinder R = 10, H = 20 draped with the warp along its generators: the ply is
// the rectangle R alpha x H, R alpha = 15.71 wide across the warp.
constexpr double kR = 10, kH = 20, kAlpha = kPi / 2, kD = 0.2;
// Areas of the cut outline within 0.1 % of the exact R alpha H at d = 1/100 of the part.
constexpr double kAreaRel = 1e-3;

struct Draped {
  Face face;
  DrapeResult result;
  FlatPattern flat;
};

Draped drape_cylinder() {
  auto f = Face::create(builtin_mold("cylinder", {{"R", kR}, {"H", kH}, {"angle", 90}}).value());
  REQUIRE(f.ok());
  const double a = 0.37;
  const Vec3 s3(kR * std::cos(a), kR * std::sin(a), 7.3), tang(-std::sin(a), std::cos(a), 0);
  auto r = drape(*f, support::problem(kD, Vec2(0, 0), Vec2(0, 1), {Vec2(-1, 0), Vec2(1, 0)}, s3,
                                      tang, {tang, -tang}));
  REQUIRE(r.ok());
  REQUIRE(r->metrics.nodes.failed == 0);
  FlatPattern flat = flat_pattern(*f, *r, FlatPatternOptions{0.0});
  return {std::move(f).value(), std::move(r).value(), std::move(flat)};
}

// The angle about the cylinder's axis of a point on it.
double azimuth(const Vec3& p) {
  return std::atan2(p.y(), p.x());
}

// The chord sag of the net between nodes d apart on the circle of radius R: how far an
// interpolated point lies inside the cylinder.
constexpr double kSag = kD * kD / (8 * kR);

}  // namespace

TEST_CASE("splice: a cylinder ply 2.5 roll widths wide gives 3 pieces within the roll") {
  const Draped dr = drape_cylinder();
  const double width = kR * kAlpha, W = width / 2.5;
  REQUIRE(dr.flat.cut_area == Approx(kR * kAlpha * kH).epsilon(kAreaRel));
  for (const double o : {0.0, 0.5}) {
    INFO("overlap " << o);
    SpliceOptions so;
    so.roll_width = W;
    so.overlap = o;
    so.ply_name = "P1";
    auto plan = splice_pattern(dr.flat, dr.result, so);
    REQUIRE(plan.ok());
    REQUIRE(plan->pieces.size() == 3);
    REQUIRE(plan->seams.size() == 2);
    CHECK(plan->pieces[0].name == "P1A");
    CHECK(plan->pieces[2].name == "P1C");
    CHECK(plan->pattern_width == Approx(width).epsilon(kAreaRel));
    double sum = 0;
    for (const auto& p : plan->pieces) {
      CHECK(p.width() <= W * (1 + Tolerances{}.outline_merge_rel));
      sum += p.area;
      // Every point of the piece lies on the cylinder (to the net's chord sag).
      for (const auto& l : p.loops)
        for (const Vec3& q : l.points3d) {
          CHECK(std::hypot(q.x(), q.y()) == Approx(kR).margin(2 * kSag));
          CHECK(q.z() >= -kSag);
          CHECK(q.z() <= kH + kSag);
        }
    }
    // Union of the pieces = the ply, each seam's overlap strip o x H counted twice.
    CHECK(sum == Approx(kR * kAlpha * kH + 2 * o * kH).epsilon(kAreaRel));
    CHECK(sum - 2 * o * kH == Approx(dr.flat.cut_area).epsilon(1e-9));
    // A seam is a generator of the cylinder: one azimuth, the full height.
    for (const auto& s : plan->seams) {
      CHECK(s.length == Approx(kH).epsilon(1e-9));
      CHECK(s.length3d == Approx(kH).epsilon(kAreaRel));
      REQUIRE(s.polylines.size() == 1);
      const double a0 = azimuth(s.polylines[0].front());
      for (const Vec3& q : s.polylines[0]) CHECK(azimuth(q) == Approx(a0).margin(1e-9));
    }
    // Where the seams lie round the axis: warp thread i at i links from the start, each link a
    // chord d long of the circle (an arc of theta = 2 asin(d / 2R)), and a seam at t of the
    // way from thread i to i + 1 on that chord.
    const double theta = 2 * std::asin(kD / (2 * kR));
    auto round_axis = [&](double x) {
      const double i = std::floor(x / kD), t = x / kD - i;
      return i * theta + std::atan2(t * std::sin(theta), 1 - t + t * std::cos(theta));
    };
    const double da =
        std::abs(azimuth(plan->seams[1].polylines[0][0]) - azimuth(plan->seams[0].polylines[0][0]));
    CHECK(da == Approx(std::abs(round_axis(plan->seams[1].x) - round_axis(plan->seams[0].x)))
                    .epsilon(1e-9));
  }
}

TEST_CASE("splice: a ply narrower than the roll is one piece, the cut outline itself") {
  const Draped dr = drape_cylinder();
  SpliceOptions so;
  so.roll_width = kR * kAlpha * 1.01;
  auto plan = splice_pattern(dr.flat, dr.result, so);
  REQUIRE(plan.ok());
  REQUIRE(plan->pieces.size() == 1);
  CHECK(plan->seams.empty());
  CHECK_FALSE(plan->split());
  CHECK(plan->pieces[0].area == dr.flat.cut_area);
  CHECK(plan->pieces[0].loops.size() == dr.flat.cut.size());
}

TEST_CASE("splice: seams keep the stagger distance from another ply's seams") {
  const Draped dr = drape_cylinder();
  SpliceOptions so;
  so.roll_width = kR * kAlpha / 2.5;
  auto first = splice_pattern(dr.flat, dr.result, so);
  REQUIRE(first.ok());
  std::vector<std::vector<Vec3>> seams;
  for (const auto& s : first->seams)
    for (const auto& l : s.polylines) seams.push_back(l);
  so.avoid = seams;
  so.stagger = 1.5;
  auto second = splice_pattern(dr.flat, dr.result, so);
  REQUIRE(second.ok());
  REQUIRE(second->pieces.size() == 3);
  CHECK(second->stagger_met);
  for (const auto& s : second->seams) {
    // Measured here on the generators: the chord between the two azimuths.
    double nearest = INFINITY;
    for (const auto& l : seams) {
      const double da = std::abs(azimuth(s.polylines[0][0]) - azimuth(l[0]));
      nearest = std::min(nearest, 2 * kR * std::sin(da / 2));
    }
    CHECK(nearest >= 1.5 - 2 * kSag);
    CHECK(s.stagger_distance == Approx(nearest).margin(2 * kSag));
  }
  for (const auto& p : second->pieces) CHECK(p.width() <= so.roll_width * (1 + 1e-6));
  // A stagger the roll cannot give: seams as without it, and said so.
  so.stagger = kR * kAlpha;
  auto third = splice_pattern(dr.flat, dr.result, so);
  REQUIRE(third.ok());
  CHECK_FALSE(third->stagger_met);
  CHECK(third->pieces.size() == 3);
}

TEST_CASE("splice: bad values are errors naming the option") {
  const Draped dr = drape_cylinder();
  struct Case {
    double roll, overlap, stagger;
    ErrorCode code;
    const char* input;
  };
  const Case cases[] = {
      {2 * kD * 0.99, 0, 0, ErrorCode::kRollNarrowerThanCells, "roll-width"},
      {5, -0.1, 0, ErrorCode::kSpliceOverlapNegative, "splice-overlap"},
      {5, 5, 0, ErrorCode::kSpliceOverlapTooWide, "splice-overlap"},
      {5, 5 - 0.99 * kD, 0, ErrorCode::kSpliceOverlapTooWide, "splice-overlap"},
      {NAN, 0, 0, ErrorCode::kSpliceValueNotFinite, "roll-width"},
      {5, INFINITY, 0, ErrorCode::kSpliceValueNotFinite, "splice-overlap"},
      {5, 0, NAN, ErrorCode::kSpliceValueNotFinite, "splice-stagger"},
      {5, 0, -1, ErrorCode::kSpliceStaggerNegative, "splice-stagger"},
  };
  for (const Case& c : cases) {
    SpliceOptions so;
    so.roll_width = c.roll;
    so.overlap = c.overlap;
    so.stagger = c.stagger;
    auto plan = splice_pattern(dr.flat, dr.result, so);
    REQUIRE_FALSE(plan.ok());
    CHECK(plan.error().code == c.code);
    CHECK(plan.error().input == c.input);
  }
}

TEST_CASE("splice: piece letters run A..Z, then AA") {
  CHECK(piece_letter(0) == "A");
  CHECK(piece_letter(25) == "Z");
  CHECK(piece_letter(26) == "AA");
  CHECK(piece_letter(27) == "AB");
}
