// The outline's coverage and the warning when it falls short (kernel/src/search/coverage.cpp).
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/optimize.hpp>

#include <catch2/catch.hpp>

#include "support/builtin_surfaces.hpp"
#include "support/problems.hpp"
#include "support/warnings.hpp"

using namespace plyfit;
using plyfit::support::problem;

TEST_CASE("search: a drape whose outline covers less of the face than the rule allows says so") {
  // The plate 100 x 60 at d = 10, from its middle line y = 30: its boundary band (cell
  // diagonal 14.1 times the perimeter 320: 4525 mm^2) is larger than the half one sweep
  // leaves (3000 mm^2), so the mapped cells' test says nothing; the outline covers half.
  const MoldSurface plate = support::builtin_surface("plate", {});
  auto half = drape(plate,
                    problem(10.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1)}, Vec3(50, 30, 0),
                            Vec3(0, 1, 0), {Vec3(0, 1, 0)}),
                    DrapeOptions{});
  REQUIRE(half);
  REQUIRE_FALSE(half->partial);
  CHECK(support::with_code(half->warnings, WarningCode::kUncoveredArea).empty());
  const FlatPattern fp = flat_pattern(plate, *half, FlatPatternOptions{});
  CHECK(outline_surface_area(*half, fp) == Approx(3000).epsilon(1e-9));
  warn_outline_short(fp, plate.area(), *half);
  const auto w = support::with_code(half->warnings, WarningCode::kOutlineShort);
  REQUIRE(w.size() == 1);
  CHECK(support::value(w[0], 0) == Approx(0.5).epsilon(1e-9));
  CHECK(support::value(w[0], 1) == kCoverageSlack);
  for (std::size_t k = 2; k <= 6; ++k) CHECK(support::value(w[0], k) == 0);
  CHECK(exporters::message(w[0]).find("the flat pattern's outline covers 50.0% of the surface "
                                      "(50.0% uncovered, more than the 0.5%") == 0);
  // Both sweeps cover the plate: no warning.
  auto whole = drape(plate,
                     problem(10.0, Vec2(0, 0), Vec2(1, 0), {Vec2(0, 1), Vec2(0, -1)},
                             Vec3(50, 30, 0), Vec3(0, 1, 0), {Vec3(0, 1, 0), Vec3(0, -1, 0)}),
                     DrapeOptions{});
  REQUIRE(whole);
  const FlatPattern all = flat_pattern(plate, *whole, FlatPatternOptions{});
  CHECK(outline_surface_area(*whole, all) == Approx(6000).epsilon(1e-9));
  warn_outline_short(all, plate.area(), *whole);
  CHECK(support::with_code(whole->warnings, WarningCode::kOutlineShort).empty());
}
