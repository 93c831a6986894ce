// Built-in molds and shells: every one builds with its defaults, and bad names, keys and
// values are refused with their codes.
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>
#include "surface/face.hpp"
#include "surface/shell/shell.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

using namespace plyfit;

namespace {

using Params = std::map<std::string, double>;
using V = std::vector<MessageValue>;

Error mold_error(const std::string& name, const Params& params) {
  auto r = builtin_face(name, params);
  REQUIRE_FALSE(r.ok());
  return r.error();
}

Error shell_error(const std::string& name, const Params& params) {
  auto r = builtin_shell(name, params);
  REQUIRE_FALSE(r.ok());
  return r.error();
}

}  // namespace

TEST_CASE("molds: every built-in mold and shell builds with its defaults") {
  REQUIRE(builtin_molds().size() == 12);
  for (const BuiltinInfo& b : builtin_molds()) {
    INFO(b.name);
    auto face = builtin_face(b.name, {});
    REQUIRE(face.ok());
    CHECK(face->face.name == b.name);
    CHECK(Face::create(face->face).ok());
    CHECK_FALSE(is_builtin_shell(b.name));
  }
  REQUIRE(builtin_shells().size() == 3);
  for (const BuiltinInfo& b : builtin_shells()) {
    INFO(b.name);
    CHECK(is_builtin_shell(b.name));
    auto shell = builtin_shell(b.name, {});
    REQUIRE(shell.ok());
    CHECK(Shell::create(std::move(shell).value()).ok());
  }
}

TEST_CASE("molds: a built-in's parameters override its defaults, a trimmed one has exact loops") {
  auto plate = builtin_face("plate", {{"hole_r", 10.0}});
  REQUIRE(plate.ok());
  CHECK(plate->exact_loops.size() == 2);  // the border and the hole
  CHECK(plate->face.loops.size() == 2);
  CHECK(plate->natural_outer);
  auto dish = builtin_face("dish", {});
  REQUIRE(dish.ok());
  CHECK(dish->exact_loops.size() == 1);
  CHECK_FALSE(dish->natural_outer);
  auto wave = builtin_mold("wave", {{"n", 5.0}});
  REQUIRE(wave.ok());
  CHECK(wave->surface.count_u == 5);
}

TEST_CASE("molds: unknown built-ins and keys are refused with the known ones") {
  Error e = mold_error("spere", {});
  CHECK(e.code == ErrorCode::kUnknownBuiltin);
  REQUIRE(e.values.size() == 3);
  CHECK(e.values[0] == MessageValue(std::string("mold")));
  CHECK(e.values[1] == MessageValue(std::string("spere")));
  CHECK(std::get<std::string>(e.values[2]).rfind("sphere-octant, hemisphere, ", 0) == 0);

  e = mold_error("plane", {{"X", 1.0}});
  CHECK(e.code == ErrorCode::kBuiltinNoParameter);
  CHECK(e.values ==
        V{std::string("mold"), std::string("plane"), std::string("X"), std::string("W, H")});

  e = mold_error("plane", {{"W", NAN}});
  CHECK(e.code == ErrorCode::kBuiltinParameterNotFinite);
  CHECK(e.values == V{std::string("W"), std::string("plane")});

  e = shell_error("sphere-9", {});
  CHECK(e.code == ErrorCode::kUnknownBuiltin);
  CHECK(e.values[0] == MessageValue(std::string("shell")));
}

TEST_CASE("molds: bad values are refused, naming the parameter and the built-in") {
  auto check = [](const Error& e, ErrorCode code, const V& values) {
    CHECK(e.code == code);
    CHECK(e.values == values);
  };
  check(mold_error("sphere-octant", {{"R", 0.0}}), ErrorCode::kBuiltinParameterNotPositive,
        {std::string("R"), std::string("sphere-octant")});
  check(mold_error("cylinder", {{"angle", 400.0}}), ErrorCode::kBuiltinAngleRange,
        {std::string("angle"), std::string("cylinder")});
  check(mold_error("wave", {{"n", 4.5}}), ErrorCode::kBuiltinIntegerRange,
        {std::string("n"), std::string("wave"), std::int64_t{4}, std::int64_t{200}});
  check(mold_error("blade", {{"twist", 91.0}}), ErrorCode::kBuiltinParameterRange,
        {std::string("twist"), std::string("blade"), -90.0, 90.0});
  check(mold_error("blade", {{"nv", 3.0}}), ErrorCode::kBuiltinIntegerRange,
        {std::string("nv"), std::string("blade"), std::int64_t{4}, std::int64_t{2000}});
  CHECK(mold_error("cylinder", {{"window_angle", 100.0}, {"window_height", 5.0}}).code ==
        ErrorCode::kBuiltinCylinderWindow);
  CHECK(mold_error("cone", {{"r0", 0.0}, {"r1", 0.0}}).code == ErrorCode::kBuiltinConeRadii);
  CHECK(mold_error("plate", {{"hole_r", 40.0}}).code == ErrorCode::kBuiltinPlateHole);
  CHECK(mold_error("dish", {{"hole_r", 30.0}}).code == ErrorCode::kBuiltinDishHole);
  CHECK(mold_error("torus", {{"r", 30.0}}).code == ErrorCode::kBuiltinTorusTube);
  CHECK(mold_error("torus", {{"t1", -90.0}}).code == ErrorCode::kBuiltinTorusAngles);
  check(shell_error("cylinder-split", {{"parts", 1.0}}), ErrorCode::kBuiltinIntegerRange,
        {std::string("parts"), std::string("cylinder-split"), std::int64_t{2}, std::int64_t{64}});
  check(shell_error("flange-fillet-wall", {{"Hw", -1.0}}), ErrorCode::kBuiltinParameterNotPositive,
        {std::string("Hw"), std::string("flange-fillet-wall")});
}

TEST_CASE("molds: a built-in's spec is parsed into its name and parameters") {
  auto spec = parse_builtin_spec("plate:W=10,hole_r=2.5");
  REQUIRE(spec.ok());
  CHECK(spec->first == "plate");
  CHECK(spec->second == Params{{"W", 10.0}, {"hole_r", 2.5}});
  spec = parse_builtin_spec("hemisphere");
  REQUIRE(spec.ok());
  CHECK(spec->second.empty());

  CHECK(parse_builtin_spec(":R=1").error().code == ErrorCode::kBuiltinNameMissing);
  auto bad = parse_builtin_spec("plate:W");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::kBuiltinParameterSyntax);
  CHECK(bad.error().values == V{std::string("W")});
  bad = parse_builtin_spec("plate:W=1x");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().code == ErrorCode::kBuiltinParameterValue);
  CHECK(bad.error().values == V{std::string("W"), std::string("1x")});
}

TEST_CASE("molds: the errors' texts name the built-in, the parameter and the rule") {
  CHECK(exporters::describe(mold_error("plane", {{"X", 1.0}})) ==
        "built-in mold 'plane' has no parameter 'X' (its parameters: W, H)");
  CHECK(exporters::describe(mold_error("cylinder", {{"angle", 0.0}})) ==
        "parameter 'angle' of 'cylinder' must be in (0, 360]");
  CHECK(exporters::describe(mold_error("blade", {{"camber", 1.0}})) ==
        "parameter 'camber' of 'blade' must be in [0, 0.25]");
  CHECK(exporters::describe(mold_error("wave", {{"n", 3.0}})) ==
        "parameter 'n' of 'wave' must be an integer from 4 to 200");
  CHECK(exporters::describe(parse_builtin_spec("plate:W=abc").error()) ==
        "built-in mold parameter 'W' has a malformed value 'abc'");
}
