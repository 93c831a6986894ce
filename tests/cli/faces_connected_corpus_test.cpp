// plyfit drape --faces connected on a real solid of the CAD corpus (../shared/cad): its sharp
// edges stop the faces reached from the seed's face.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "corpus.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace plyfit::test;
using nlohmann::json;

namespace {

// Two faces' outward normals this close to perpendicular meet at a 90 degree edge.
constexpr double kPerpendicularCos = 1e-9;

json run_json(const std::string& args, const Scratch& tmp) {
  const CliRun r = plyfit_run(args, tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return json::parse(r.out);
}

}  // namespace

TEST_CASE("faces connected: the deflector solid's 90 degree edges stop the default 60") {
  Scratch tmp("faces_connected_cad");
  // occ22470.igs: a thin deflector (a closed solid of 18 faces). Face 0 is a side wall; it
  // meets the plate's underside (face 4) at a right angle, and joins faces 6 and 8 flush.
  const std::string file = shared_cad("occ22470.igs");
  const json f0 = run_json("info '" + file + "' --face 0 --json", tmp);
  const json f4 = run_json("info '" + file + "' --face 4 --json", tmp);
  double cosine = 0.0;
  for (int i = 0; i < 3; ++i)
    cosine += f0["normal"][i].get<double>() * f4["normal"][i].get<double>();
  CHECK(std::abs(cosine) < kPerpendicularCos);

  const json links = run_json("info '" + file + "' --neighbours --json", tmp);
  bool joined = false;
  for (const json& n : links["faces"][0]["neighbours"])
    if (n["face"] == 4) {
      joined = true;
      CHECK(n["crease_deg"].get<double>() == Approx(90.0).margin(1e-6));
    }
  CHECK(joined);

  const json p = f0["point"];
  const std::string seed = std::to_string(p[0].get<double>()) + "," +
                           std::to_string(p[1].get<double>()) + "," +
                           std::to_string(p[2].get<double>());
  const std::string out = tmp.file("out");
  auto faces_reached = [&](const std::string& limit) {
    const CliRun r =
        plyfit_run("drape --mold '" + file + "' --faces connected" + limit + " --seed " + seed +
                       " --spacing 10 --outputs json --quiet -o '" + out + "'",
                   tmp);
    INFO(r.err);
    REQUIRE(r.code == 0);
    return json::parse(slurp(out + "/report.json"))["inputs"]["faces"].get<std::vector<int>>();
  };
  CHECK(faces_reached("") == std::vector<int>{0, 6, 8});
  // Past 90 degrees the cloth's shell takes face 4 and its neighbours too.
  const std::vector<int> wide = faces_reached(" --max-crease 95");
  CHECK(wide.size() > 3);
  CHECK(std::find(wide.begin(), wide.end(), 4) != wide.end());
}
