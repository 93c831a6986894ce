// plyfit laminate end to end on a built-in mold: plies into their folders in stacking order,
// the ply book's data files, bit-for-bit equal runs at -j 1 and -j 2 (timings aside), one mold
// import shared by the plies, a failing ply failing alone and named with its key, the laminate
// file's own errors, and a piece wider than the roll.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <set>

using namespace plyfit::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// Four plies at 0/45/-45/90 on the sphere octant, sections out of stacking order; `extra` is
/// appended (more sections, or keys of the last ply).
std::string laminate_text(const std::string& extra = {}) {
  return "[laminate]\nmold = builtin:sphere-octant\nseed = 10,10,14\nrosette = 1,0,0\n"
         "spacing = 1\nroll-width = 200\n\n"
         "[ply B]\nsequence = 20\nangle = 45\n\n[ply A]\nsequence = 10\nangle = 0\n\n"
         "[ply C]\nangle = -45\n\n[ply D]\nsequence = 5\nangle = 90\nmaterial = carbon-twill\n" +
         extra;
}

/// Every file under `root`, relative, sorted.
std::set<std::string> files_under(const fs::path& root) {
  std::set<std::string> s;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) s.insert(fs::relative(e.path(), root).string());
  return s;
}

/// A file's bytes; report.json without its timings (the one thing allowed to differ).
std::string comparable(const fs::path& file) {
  if (file.filename() != "report.json") return slurp(file.string());
  json j = json::parse(slurp(file.string()));
  j.erase("timing_ms");
  return j.dump();
}

}  // namespace

TEST_CASE("cli laminate: every ply into its folder, the ply book's data in stacking order") {
  Scratch s("laminate_order");
  spit(s.file("lam.ini"), laminate_text());
  const CliRun r = plyfit_run("laminate lam.ini -o out -j 2 --quiet", s, s.path.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json book = json::parse(slurp(s.file("out/plybook.json")));
  std::vector<std::string> names;
  std::vector<long> sequences;
  for (const auto& p : book.at("plies")) {
    names.push_back(p.at("name"));
    sequences.push_back(p.at("sequence"));
    CHECK(p.at("status") == "ok");
    CHECK(p.at("flat_area_mm2").get<double>() > 0.0);
    for (const auto& f : p.at("files"))
      CHECK(fs::is_regular_file(s.file("out/" + f.get<std::string>())));
  }
  // Stacking order is by sequence; C, without one, follows A (10 + 1).
  CHECK(names == std::vector<std::string>{"D", "A", "C", "B"});
  CHECK(sequences == std::vector<long>{5, 10, 11, 20});
  CHECK(book.at("plies")[0].at("material") == "carbon 2/2 twill");
  CHECK(book.at("plies")[0].at("angle_deg") == 90.0);
  // Each ply's report says what the drape laid: its own angle, its own name.
  for (const auto& [name, angle] : {std::pair{"A", 0.0}, {"B", 45.0}, {"C", -45.0}, {"D", 90.0}}) {
    const json rep = json::parse(slurp(s.file(std::string("out/") + name + "/report.json")));
    CHECK(rep.at("ply").at("laid_angle_deg").get<double>() == Approx(angle).margin(1e-6));
  }
  const std::string csv = slurp(s.file("out/plybook.csv"));
  CHECK(lines(csv) == 5);
  CHECK(csv.find("\n5,D,90,carbon 2/2 twill,ok,") != std::string::npos);
  for (const char* f : {"plybook.html", "cut.dxf"})
    CHECK(fs::is_regular_file(s.file(std::string("out/") + f)));
}

TEST_CASE("cli laminate: -j 1 and -j 2 write the same bytes but the timings, from one import") {
  Scratch s("laminate_repro");
  spit(s.file("lam.ini"), laminate_text());
  for (const char* j : {"1", "2"}) {
    const CliRun r = plyfit_run(std::string("laminate lam.ini --quiet -o out") + j + " -j " + j, s,
                                s.path.string());
    INFO(r.err);
    REQUIRE(r.code == 0);
  }
  const auto files = files_under(s.path / "out1");
  REQUIRE(files == files_under(s.path / "out2"));
  // The laminate's four documents, and per ply the nine files of the default outputs (flat.dxf,
  // net.step, report.json, four pictures, net.vtk, net.glb).
  CHECK(files.size() == 4 + 4 * 9);
  for (const auto& f : files) {
    INFO(f);
    CHECK(comparable(s.path / "out1" / f) == comparable(s.path / "out2" / f));
  }
  // The mold was imported once: every ply reports the one import's time.
  std::set<double> imports;
  for (const char* p : {"A", "B", "C", "D"})
    imports.insert(json::parse(slurp(s.file(std::string("out2/") + p + "/report.json")))
                       .at("timing_ms")
                       .at("import")
                       .get<double>());
  CHECK(imports.size() == 1);
}

TEST_CASE("cli laminate: a failing ply fails alone, its error naming the ply and the key") {
  Scratch s("laminate_bad_ply");
  spit(s.file("lam.ini"), laminate_text("spacing = -1\n\n[ply E]\nangle = 200\n\n[ply F]\n"
                                        "seed = 10,10,1000\n"));
  const CliRun r = plyfit_run("laminate lam.ini -o out --quiet", s, s.path.string());
  CHECK(r.code == 1);
  CHECK(r.err.find("plyfit: error: ply D: lam.ini [ply D]: key 'spacing': ") != std::string::npos);
  CHECK(r.err.find("[spacing_not_positive]") != std::string::npos);
  CHECK(r.err.find("plyfit: error: ply E: lam.ini [ply E]: key 'angle': ") != std::string::npos);
  CHECK(r.err.find("[out_of_range]") != std::string::npos);
  CHECK(r.err.find("plyfit: error: ply F: ") != std::string::npos);
  CHECK(r.err.find("[seed_off_mold]") != std::string::npos);
  const json book = json::parse(slurp(s.file("out/plybook.json")));
  std::map<std::string, std::string> status, code;
  for (const auto& p : book.at("plies")) {
    status[p.at("name")] = p.at("status");
    code[p.at("name")] = p.at("error_code");
  }
  CHECK(status ==
        std::map<std::string, std::string>{
            {"A", "ok"}, {"B", "ok"}, {"C", "ok"}, {"D", "error"}, {"E", "error"}, {"F", "error"}});
  CHECK(code["D"] == "spacing_not_positive");
  CHECK(code["F"] == "seed_off_mold");
  CHECK(fs::is_regular_file(s.file("out/A/flat.dxf")));
  CHECK_FALSE(fs::exists(s.file("out/D")));
}

TEST_CASE("cli laminate: a bad laminate file is one error line with its code, nothing written") {
  Scratch s("laminate_bad_file");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[laminate]\nmold = builtin:sphere-octant\n", "laminate_no_plies"},
      {"spacing = 1\n[ply A]\n", "laminate_section"},
      {"[laminate]\n[plies]\n", "laminate_section"},
      {"[ply A]\n[ply A]\n", "ply_repeated"},
      {"[ply a/b]\n", "ply_name_invalid"},
      {"[ply A]\nsequence = 1\n[ply B]\nsequence = 1\n", "sequence_repeated"},
      {"[ply A]\nsplice-stagger = 10\n", "key_not_in_laminate"},
      {"[laminate]\nsequence = 3\n[ply A]\n", "key_not_in_laminate"},
      {"[ply A]\noutput = x\n", "key_not_in_laminate"},
      {"[ply A]\nply-angle = 45\n", "key_not_in_laminate"},
      {"[ply A]\nspacingg = 1\n", "unknown_key"},
      {"[laminate]\nroll-width = 0\n[ply A]\n", "out_of_range"},
      {"[ply A]\nsequence = x\n", "not_a_number"},
      {"[laminate]\nsplice-stagger = -1\n[ply A]\n", "splice_stagger_negative"},
      {"[ply A]\nsequence = 1.5\n", "not_an_integer"},
  };
  for (const auto& [text, code] : cases) {
    INFO(text);
    spit(s.file("bad.ini"), text);
    const CliRun r = plyfit_run("laminate bad.ini -o out", s, s.path.string());
    CHECK(r.code == 1);
    CHECK(error_code(r) == code);
    CHECK_FALSE(fs::exists(s.file("out")));
  }
  const CliRun missing = plyfit_run("laminate none.ini -o out", s, s.path.string());
  CHECK(missing.code == 1);
  CHECK(error_code(missing) == "scene_cannot_open");
  CHECK(error_code(plyfit_run("laminate bad.ini", s, s.path.string())) == "missing_option");
}

TEST_CASE("cli laminate: a piece wider than the roll is left out of cut.dxf, and said so") {
  // The octant's pieces are 31.4 (D, 90 deg), 31.5 (C), 32.0 (A) and 32.3 mm (B) wide; the roll
  // keeps 1 % of its width free at each edge: 0.98 x 32.4 = 31.75 mm takes D and C only. A and
  // B are given a roll of their own wide enough not to be spliced (docs/splices.md).
  Scratch s("laminate_roll");
  std::string text = laminate_text();
  text.replace(text.find("roll-width = 200"), 16, "roll-width = 32.4");
  for (const char* ply : {"[ply A]\n", "[ply B]\n"})
    text.insert(text.find(ply) + std::string(ply).size(), "roll-width = 1000\n");
  spit(s.file("lam.ini"), text);
  const CliRun r = plyfit_run("laminate lam.ini -o out --quiet", s, s.path.string());
  CHECK(r.code == 1);
  for (const char* ply : {"A", "B"}) {
    INFO(r.err);
    CHECK(r.err.find(std::string("plyfit: error: ply ") + ply + ": the cut outline is ") !=
          std::string::npos);
  }
  CHECK(r.err.find("[piece_wider_than_roll]") != std::string::npos);
  const std::string dxf = slurp(s.file("out/cut.dxf"));
  auto layer = [&](const std::string& name) {
    return dxf.find("AcDbLayerTableRecord\n  2\n" + name + "\n") != std::string::npos;
  };
  for (const char* name : {"A", "B"}) CHECK_FALSE(layer(name));
  for (const char* name : {"C", "D", "ROLL"}) CHECK(layer(name));
  CHECK(json::parse(slurp(s.file("out/plybook.json"))).at("plies")[1].at("status") == "ok");
}

TEST_CASE("cli laminate: a ply's keys replace the laminate's that stand for them") {
  Scratch s("laminate_alternatives");
  // E gives the paper's start keys instead of the laminate's seed, and its own thread spacings.
  spit(s.file("lam.ini"), laminate_text("\n[ply E]\nstart2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\n"
                                        "start3d = 0,0,20\nbase-normal = 0,1,0\nsweep3d = 0,1,0\n"
                                        "spacing-weft = 1\nspacing-warp = 1.5\n"));
  const CliRun r = plyfit_run("laminate lam.ini -o out --quiet", s, s.path.string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  const json rep = json::parse(slurp(s.file("out/E/report.json")));
  CHECK(rep.at("ply").at("defined_by") == "start");
  CHECK(json::parse(slurp(s.file("out/A/report.json"))).at("ply").at("defined_by") == "seed");
}
