// The faces' geometry as the reader made it (occt/src/geometry_checks.hpp), in
// millimetres: what the file's numbers become after its unit and placements are applied must be
// finite and of a sane size, or opening the file is an error naming the face's entity.

#include <plyfit/importers/importers.hpp>

#include <catch2/catch.hpp>

#include "occt/error_checks.hpp"

using namespace plyfit;
using namespace plyfit::test;

TEST_CASE("importers: a unit that makes the mold 1,000 km large is an error naming the face") {
  TempDir dir("geometry_checks_unit");
  // The dish in a length unit of 1e7 mm: every number in the file is sane, the mold is not.
  std::string s = read_bytes(sample_mold("dish.step"));
  const std::string mm = "#167 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";
  const size_t at = s.find(mm);
  REQUIRE(at != std::string::npos);
  s.replace(at, mm.size(),
            "#167 = ( CONVERSION_BASED_UNIT('BIG',#171) LENGTH_UNIT() NAMED_UNIT(#172) );\n"
            "#171 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E+07),#173);\n"
            "#172 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
            "#173 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );");
  const std::string path = dir.file("big_unit.step");
  write_bytes(path, s);
  auto r = importers::open_mold(path);
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), path);
  CHECK(r.error().code == ErrorCode::kFaceGeometryTooLarge);
  CHECK(r.error().face == 0);  // the dish's face, made by entity #17
  CHECK(r.error().where == "#17");

  // The same unit at 1e3 mm (a metre) is a sane mold of 75 m.
  s.replace(s.find("1.E+07"), 6, "1.E+03");
  write_bytes(path, s);
  r = importers::open_mold(path);
  REQUIRE(r.ok());
  CHECK((*r)->mold().faces.at(0).bbox.diagonal() > 1e4);
}
