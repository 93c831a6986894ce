// plyfit optimize: drapes on one shared face run concurrently as they do alone; the search
// beats the paper's three sphere-octant cases (their energies from drapes of the sample
// scenes, here) while covering the face as fully; the same input gives the same output for
// any -j; its bounds hold; bad input fails cleanly. (Its options and files are checked against
// docs/optimize.md with every other command's, in readme_test.cpp.)

#include <plyfit/kernel/builtin_molds.hpp>
#include "drape/drape.hpp"
#include "pattern/flat_pattern.hpp"
#include "surface/face.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"
#include "cli/rejected.hpp"

#include <cmath>
#include <optional>
#include <sstream>
#include <thread>

using namespace plyfit;
using namespace plyfit::test;
using nlohmann::json;

namespace {

/// The coverage slack of plyfit optimize (docs/optimize.md: 0.5% of the face).
constexpr double kCoverageSlack = 0.005;
/// Figures that two runs of the same drape must reproduce, relative (they are printed with
/// 17 digits, so equal runs agree exactly; this only absorbs the decimal round trip).
constexpr double kSameRel = 1e-12;

std::string sample(const std::string& name) {
  return std::string(PLYFIT_SOURCE_DIR) + "/samples/" + name;
}

json read_json(const std::string& path) {
  return json::parse(slurp(path));
}

bool same(double a, double b) {
  return std::abs(a - b) <= kSameRel * std::max(std::abs(a), std::abs(b));
}

/// A drape's figures and nodes, for bit-for-bit comparisons.
struct Snapshot {
  std::vector<double> numbers;
  std::vector<int> statuses;
  bool operator==(const Snapshot& o) const {
    return numbers == o.numbers && statuses == o.statuses;
  }
};

/// The drape and flat pattern of `pb` (no Catch2 assertion: threads call it); empty if the
/// drape fails.
std::optional<Snapshot> snapshot(const Face& face, const DrapeProblem& pb) {
  auto res = drape(face, pb);
  if (!res) return std::nullopt;
  Snapshot s;
  for (const DrapeNode& n : res->nodes) {
    s.numbers.insert(s.numbers.end(),
                     {n.point.x(), n.point.y(), n.point.z(), n.uv.x(), n.uv.y(), n.thread_angle});
    s.statuses.push_back(static_cast<int>(n.status));
  }
  const DrapeMetrics& m = res->metrics;
  s.numbers.insert(s.numbers.end(), {m.shear_energy, m.gamma_min, m.gamma_max, m.surface_area,
                                     m.flat_area, static_cast<double>(m.nodes.mapped)});
  const FlatPattern fp = flat_pattern(face, *res);
  for (const auto& loop : fp.outline)
    for (const Vec2& p : loop.points) s.numbers.insert(s.numbers.end(), {p.x(), p.y()});
  s.numbers.push_back(fp.area);
  return s;
}

/// Drapes of the sphere octant from seeds spread over it, base paths along normal sections
/// at several angles to the threads, both sides swept.
std::vector<DrapeProblem> octant_problems() {
  std::vector<DrapeProblem> out;
  const double R = 20.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 3; ++b) {
      const double th = 0.15 + 0.35 * a, ph = 0.2 + 0.5 * b;
      const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      Vec3 t = Vec3::UnitX() - n.x() * n;
      t.normalize();
      DrapeProblem pb;
      pb.start = R * n;
      pb.base_normal = t.cross(n);
      const double beta = 0.3 * (a + b);
      pb.ply.base_dir = Vec2(std::cos(beta), std::sin(beta));
      pb.ply.sweeps = {Vec2(-std::sin(beta), std::cos(beta)),
                       Vec2(std::sin(beta), -std::cos(beta))};
      pb.sweeps = {n.cross(t), -n.cross(t)};
      out.push_back(pb);
    }
  return out;
}

/// Runs plyfit with `args`; REQUIREs the exit code.
CliRun run_ok(const std::string& args, const Scratch& s) {
  const CliRun r = plyfit_run(args, s);
  INFO("plyfit " << args << "\n" << r.err);
  REQUIRE(r.code == 0);
  return r;
}

/// Lines of `text`.
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE(
    "optimize: drapes of one shared face run concurrently equal the serial ones bit for bit") {
  const Face face = Face::create(builtin_mold("sphere-octant", {}).value()).value();
  const auto problems = octant_problems();
  std::vector<Snapshot> serial;
  for (const auto& pb : problems) {
    auto snap = snapshot(face, pb);
    REQUIRE(snap);
    // Every drape maps nodes (the comparison compares something).
    CHECK(snap->statuses.size() > 100);
    serial.push_back(std::move(*snap));
  }
  constexpr int kThreads = 4;
  std::vector<std::vector<std::optional<Snapshot>>> parallel(
      kThreads, std::vector<std::optional<Snapshot>>(problems.size()));
  std::vector<std::thread> pool;
  for (int t = 0; t < kThreads; ++t)
    pool.emplace_back([&, t] {
      // Each thread drapes every problem, starting at a different one.
      for (std::size_t i = 0; i < problems.size(); ++i) {
        const std::size_t k = (i + 3 * static_cast<std::size_t>(t)) % problems.size();
        parallel[static_cast<std::size_t>(t)][k] = snapshot(face, problems[k]);
      }
    });
  for (auto& th : pool) th.join();
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t k = 0; k < problems.size(); ++k) {
      INFO("thread " << t << ", problem " << k);
      const auto& p = parallel[static_cast<std::size_t>(t)][k];
      REQUIRE(p);
      CHECK(*p == serial[k]);
    }
}

TEST_CASE(
    "optimize: from each paper sphere-octant case it finds a lower energy, covering as fully") {
  Scratch s("optimize_octant");
  const std::vector<std::string> cases = {"a", "b", "c"};
  // The figures to beat: drapes of the three sample scenes.
  double beat = 1e300;
  for (const auto& c : cases) {
    const std::string dir = s.file("drape-" + c);
    run_ok("drape '" + sample("sphere-octant-" + c + ".ini") + "' -o '" + dir +
               "' --outputs json --quiet",
           s);
    const json rep = read_json(dir + "/report.json");
    REQUIRE(rep["status"] == "ok");
    beat = std::min(beat, rep["shear_energy"].get<double>());
  }
  INFO("lowest energy of the paper's cases: " << beat);
  REQUIRE(beat > 20.0);  // case (b), 21.05: the drapes above must have run
  std::vector<json> results;
  double scene_coverage = 0.0;  // the largest coverage of the three scenes
  for (const auto& c : cases) {
    const std::string dir = s.file("opt-" + c);
    run_ok("optimize '" + sample("sphere-octant-" + c + ".ini") + "' -o '" + dir + "' --quiet", s);
    results.push_back(read_json(dir + "/optimize.json"));
    scene_coverage =
        std::max(scene_coverage, results.back()["scene_drape"]["coverage"].get<double>());
  }
  for (std::size_t k = 0; k < cases.size(); ++k) {
    INFO("from case (" << cases[k] << ")");
    const json& r = results[k];
    const json& best = r["best"]["energy"];
    REQUIRE(best.is_object());
    CHECK(best["feasible"] == true);
    CHECK(best["status"] == "ok");
    CHECK(best["energy"].get<double>() < beat);
    // As fully covered as any of the three scenes (to the slack) and not more than the face.
    CHECK(best["coverage"].get<double>() >= scene_coverage - kCoverageSlack);
    CHECK(best["coverage"].get<double>() <= 1.0 + kCoverageSlack);
    CHECK(r["drapes"].get<int>() <= 200);
    // The saved scene drapes to the same figure, status ok, every stop at the face's edge:
    // the cloth reaches the whole face.
    const std::string dir = s.file("best-" + cases[k]);
    run_ok("drape '" + s.file("opt-" + cases[k]) + "/best-energy.ini' -o '" + dir +
               "' --outputs json --quiet",
           s);
    const json rep = read_json(dir + "/report.json");
    CHECK(rep["status"] == "ok");
    CHECK(rep["shear_energy"].get<double>() < beat);
    CHECK(same(rep["shear_energy"].get<double>(), best["energy"].get<double>()));
    CHECK(same(rep["flat_outline"]["area"].get<double>(), best["flat_area"].get<double>()));
    for (const char* stop : {"shear_limit", "failed", "overlap", "conflict", "off_ply"})
      CHECK(rep["nodes"][stop].get<int>() == 0);
    CHECK(rep["nodes"]["outside"].get<int>() > 0);
  }
}

TEST_CASE("optimize: the scene's own seed and angles drape the one-sided paper cases alike") {
  Scratch s("optimize_scene");
  for (const std::string c : {"a", "b", "c"}) {
    INFO("case (" << c << ")");
    const std::string dir = s.file(c);
    run_ok("optimize '" + sample("sphere-octant-" + c + ".ini") + "' --evaluations 1 -o '" + dir +
               "' --quiet",
           s);
    const json r = read_json(dir + "/optimize.json");
    REQUIRE(r["evaluations"].size() == 2);
    const json& scene = r["evaluations"][0];
    const json& own = r["evaluations"][1];
    CHECK(own["phase"] == "design");
    CHECK(own["angle_deg"] == 0.0);
    CHECK(own["path_deg"] == 0.0);
    CHECK(own["uv"] == scene["uv"]);
    // Both sides swept and the base plane rebuilt from the carried direction: on the face's
    // edge, the same drape.
    CHECK(own["mapped"] == scene["mapped"]);
    CHECK(same(own["energy"].get<double>(), scene["energy"].get<double>()));
    // The outline along the base path (the face's edge here) differs: one-sided, it runs
    // through the path's nodes; two-sided, through the crossings of the face's edge found in
    // the second side's cells (outside the face) by their interpolation, a few 1e-4 d away
    // (1.8e-5 of the area on case (b)).
    constexpr double kOutlineRel = 1e-4;
    CHECK(std::abs(own["flat_area"].get<double>() - scene["flat_area"].get<double>()) <=
          kOutlineRel * scene["flat_area"].get<double>());
    CHECK(same(own["max_shear_deg"].get<double>(), scene["max_shear_deg"].get<double>()));
  }
}

TEST_CASE("optimize: the same input gives the same output, whatever -j") {
  Scratch s("optimize_jobs");
  std::vector<std::string> outs;
  std::vector<json> results;
  for (const int j : {1, 2, 3}) {
    const std::string dir = s.file("j" + std::to_string(j));
    const CliRun r = run_ok("optimize '" + sample("sphere-octant-b.ini") +
                                "' --evaluations 60 --objective energy,area -j " +
                                std::to_string(j) + " -o '" + dir + "' --quiet",
                            s);
    json res = read_json(dir + "/optimize.json");
    CHECK(res["run"]["threads"] == j);
    res.erase("run");
    results.push_back(res);
    // The table but for its first line (time, threads) and the written files' folder.
    std::string table;
    for (const auto& line : split_lines(r.out))
      if (line.rfind("plyfit optimize:", 0) != 0 && line.rfind("written:", 0) != 0)
        table += line + "\n";
    outs.push_back(table);
    CHECK(slurp(dir + "/front.svg") == slurp(s.file("j1") + "/front.svg"));
    CHECK(slurp(dir + "/best-energy.ini") == slurp(s.file("j1") + "/best-energy.ini"));
    CHECK(slurp(dir + "/best-area.ini") == slurp(s.file("j1") + "/best-area.ini"));
  }
  // Every column has its heading: the header names as many columns as a drape's row has
  // (the row's seed holds two ", " separators), and the path column is named.
  for (const auto& line : split_lines(outs[0])) {
    if (line.find("seed x, y, z (mm)") == std::string::npos) continue;
    const auto angle = line.find("angle (deg)"), path = line.find("path (deg)");
    CHECK(angle != std::string::npos);
    CHECK(path != std::string::npos);
    CHECK(angle < path);
    CHECK(path < line.find("energy"));
  }
  CHECK(results[0]["drapes"].get<int>() > 30);
  CHECK(results[1] == results[0]);
  CHECK(results[2] == results[0]);
  CHECK(outs[1] == outs[0]);
  CHECK(outs[2] == outs[0]);
}

TEST_CASE("optimize: seeds stay within the radius, angles within the range, drapes within N") {
  Scratch s("optimize_bounds");
  const double radius = 5.0, range = 10.0;
  const int n = 40;
  run_ok("optimize '" + sample("sphere-octant-b.ini") + "' --radius 5 --angle-range 10 " +
             "--evaluations 40 -o '" + s.file("out") + "' --quiet",
         s);
  const json r = read_json(s.file("out") + "/optimize.json");
  CHECK(r["drapes"].get<int>() <= n);
  CHECK(r["evaluations"].size() == static_cast<std::size_t>(r["drapes"].get<int>()) + 1);
  const json& seed0 = r["evaluations"][0]["seed"];
  for (const auto& e : r["evaluations"]) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = e["seed"][k].get<double>() - seed0[k].get<double>();
      d2 += d * d;
    }
    CHECK(std::sqrt(d2) <= radius);
    CHECK(std::abs(e["angle_deg"].get<double>()) <= range);
    CHECK(e["path_deg"] == 0.0);
  }
  // The best is never worse than the scene as given when the scene is feasible.
  REQUIRE(r["scene_drape"]["feasible"] == true);
  CHECK(r["best"]["energy"]["energy"].get<double>() <= r["scene_drape"]["energy"].get<double>());

  // --vary angle: every drape from the scene's seed.
  run_ok("optimize '" + sample("sphere-octant-b.ini") + "' --vary angle --evaluations 20 -o '" +
             s.file("angle") + "' --quiet",
         s);
  const json a = read_json(s.file("angle") + "/optimize.json");
  for (const auto& e : a["evaluations"]) CHECK(e["uv"] == a["evaluations"][0]["uv"]);
}

TEST_CASE("optimize: a drape never wins by covering less of the face") {
  // The scene drapes one side of a base path through the middle of the octant: 42% of the
  // face. Both-sided drapes cover all of it; the scene, with less energy and a smaller
  // flat pattern than some of them, must not be the best of either.
  Scratch s("optimize_cover");
  const std::string scene = s.file("half.ini");
  spit(scene,
       "[mold]\nmold = builtin:sphere-octant\n[ply]\nspacing = 1\n[start]\n"
       "start2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\n"
       "start3d = 11.547005383792516,11.547005383792516,11.547005383792516\n"
       "base-normal = 0,1,0\nsweep3d = 0,1,0\n");
  run_ok("optimize '" + scene + "' --objective energy,area --evaluations 40 -o '" + s.file("out") +
             "' --quiet",
         s);
  const json r = read_json(s.file("out") + "/optimize.json");
  const json& sc = r["scene_drape"];
  REQUIRE(sc["coverage"].get<double>() < 0.5);
  CHECK(sc["feasible"] == false);
  CHECK(sc["note"].get<std::string>().find("covers") != std::string::npos);
  CHECK(r["search"]["best_coverage"].get<double>() > 0.99);
  for (const char* ob : {"energy", "max-shear", "area"}) {
    INFO(ob);
    REQUIRE(r["best"][ob].is_object());
    CHECK(r["best"][ob]["index"].get<int>() != 0);
    CHECK(r["best"][ob]["coverage"].get<double>() >=
          std::min(1.0, r["search"]["best_coverage"].get<double>()) - kCoverageSlack);
  }
  for (const auto& i : r["pareto_front"]) CHECK(r["evaluations"][i.get<int>()]["feasible"] == true);
}

TEST_CASE("optimize: the coverage of complete drapes of a developable face is the whole face") {
  // A cylinder sector drapes without shear: the cut ply is the face developed, whatever the
  // seed and angle. The IGES trim polylines (within 1e-5 of the part) and the cells' chord
  // quadrilaterals keep the outline's surface area within this of the face's.
  constexpr double kDevelopedCoverageTol = 1e-3;
  Scratch s("optimize_cylinder");
  run_ok("optimize '" + sample("cylinder-sector.ini") + "' --evaluations 30 -o '" + s.file("out") +
             "' --quiet",
         s);
  const json r = read_json(s.file("out") + "/optimize.json");
  int complete = 0;
  for (const auto& e : r["evaluations"]) {
    if (e["status"] != "ok" || e["shear_limit"].get<int>() != 0) continue;
    INFO("drape " << e["index"]);
    CHECK(std::abs(e["coverage"].get<double>() - 1.0) <= kDevelopedCoverageTol);
    ++complete;
  }
  CHECK(complete >= 25);
}

TEST_CASE(
    "optimize: bad input is one line with its code, naming the option or file; nothing is "
    "written") {
  Scratch s("optimize_errors");
  const std::string oct = "'" + sample("sphere-octant-a.ini") + "'";
  const std::string bad_key = s.file("bad.ini");
  spit(bad_key, "[ply]\nspacing = one\n");
  check_rejected(
      "optimize",
      {
          {"", 2, "missing_argument", "plyfit optimize SCENE"},
          {oct + " " + oct, 2, "unexpected_argument", "sphere-octant-a.ini"},
          {oct + " --vary seed", 2, "unknown_value", "--vary: "},
          {oct + " --objective weight", 2, "unknown_value", "--objective: "},
          {oct + " --evaluations 0", 2, "not_an_integer", "--evaluations: "},
          {oct + " --evaluations 2.5", 2, "not_an_integer", "--evaluations: "},
          {oct + " --evaluations many", 2, "not_a_number", "--evaluations: "},
          {oct + " --min-coverage 120", 2, "out_of_range", "--min-coverage: "},
          {oct + " --radius -1", 2, "out_of_range", "--radius: "},
          {oct + " --vary angle --radius 3", 2, "option_needs_vary", "--radius: "},
          {oct + " --angle-range 0", 2, "out_of_range", "--angle-range: "},
          {oct + " --vary start --angle-range 5", 2, "option_needs_vary", "--angle-range: "},
          {oct + " --path-range 10", 2, "option_needs_vary", "--path-range: "},
          {oct + " -j 0", 2, "not_an_integer", "--jobs: "},
          {oct + " --colour red", 2, "unknown_option", "--colour"},
          {"'" + s.file("none.ini") + "'", 1, "scene_cannot_open", s.file("none.ini") + ": "},
          {"'" + bad_key + "'", 1, "missing_option", bad_key + ": "},
      },
      s);
}

TEST_CASE("optimize: an interrupted search writes nothing and exits 130") {
  Scratch s("optimize_interrupt");
  const std::string out = s.file("out");
  // A search far longer than the 2 s before SIGINT.
  const std::string cmd = "timeout --preserve-status -s INT 2 '" + std::string(PLYFIT_BIN) +
                          "' optimize '" + sample("sphere-octant-a.ini") +
                          "' --evaluations 1000000 -o '" + out + "' > /dev/null 2> '" +
                          s.file("err") + "'";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  CHECK(slurp(s.file("err")).find("[interrupted]\n") != std::string::npos);
  CHECK(!std::filesystem::exists(out));
}
