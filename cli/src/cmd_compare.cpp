// plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]: drapes scenes on one
// mold face with different initial conditions and prints the comparison of the paper's
// Tables 2 and 4, marking the best scene for each criterion.

#include "commands.hpp"
#include "drape_job.hpp"
#include "scene_names.hpp"

#include <boost/program_options.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace plyfit::cli {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
/// Two figures closer than this (relative to the larger) tie: both are marked best. Counts
/// tie only when equal.
constexpr double kTieRel = 1e-9;

/// One compared criterion: a column of the table.
struct Criterion {
  std::string key;     ///< CSV column and `best` entry
  std::string header;  ///< table header
  bool larger_better;  ///< else smaller is better
  bool count;          ///< an integer count (exact ties)
  int digits;          ///< decimals shown
};

const std::vector<Criterion>& criteria() {
  static const std::vector<Criterion> list = {
      {"area", "area (mesh points)", false, true, 0},
      {"flat_area", "flat area", false, false, 2},
      {"gamma_min_deg", "gamma min (deg)", true, false, 3},
      {"gamma_max_deg", "gamma max (deg)", false, false, 3},
      {"energy", "energy sum cos^2", false, false, 3},
      {"coverage_pct", "coverage (%)", true, false, 2},
      {"shear_limit", "shear-limit stops", false, true, 0},
  };
  return list;
}

struct Row {
  std::string name, path;
  bool ok = false;
  std::string error;
  std::vector<double> values;  ///< one per criterion
  std::vector<bool> best;
};

std::string fixed(double x, int digits) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << x;
  return os.str();
}

bool ties(double a, double b, bool count) {
  if (count) return a == b;
  return std::abs(a - b) <= kTieRel * std::max(std::abs(a), std::abs(b));
}

void mark_best(std::vector<Row>& rows) {
  for (auto& r : rows) r.best.assign(criteria().size(), false);
  for (std::size_t c = 0; c < criteria().size(); ++c) {
    const Criterion& k = criteria()[c];
    bool any = false;
    double best = 0.0;
    for (const auto& r : rows) {
      if (!r.ok) continue;
      const double v = r.values[c];
      if (!any || (k.larger_better ? v > best : v < best)) best = v;
      any = true;
    }
    for (auto& r : rows)
      if (r.ok && ties(r.values[c], best, k.count)) r.best[c] = true;
  }
}

std::string cell(const Row& r, std::size_t c) {
  return fixed(r.values[c], criteria()[c].digits);
}

void print_text(const std::vector<Row>& rows, std::ostream& os) {
  std::vector<std::vector<std::string>> t;
  std::vector<std::string> head = {"scene"};
  for (const auto& k : criteria()) head.push_back(k.header);
  t.push_back(head);
  for (const auto& r : rows) {
    std::vector<std::string> line = {r.name};
    for (std::size_t c = 0; c < criteria().size(); ++c)
      line.push_back(r.ok ? cell(r, c) + (r.best[c] ? " *" : "  ") : "-");
    t.push_back(line);
  }
  std::vector<std::size_t> w(head.size(), 0);
  for (const auto& line : t)
    for (std::size_t c = 0; c < line.size(); ++c) w[c] = std::max(w[c], line[c].size());
  for (const auto& line : t) {
    std::string s;
    for (std::size_t c = 0; c < line.size(); ++c) {
      std::string v = line[c];
      // Scene names left-aligned, figures right-aligned.
      if (c == 0)
        v += std::string(w[c] - v.size(), ' ');
      else
        v = std::string(w[c] - v.size(), ' ') + v;
      s += (c ? "  " : "") + v;
    }
    os << s << "\n";
  }
  for (const auto& r : rows)
    if (!r.ok) os << r.name << ": error: " << r.error << "\n";
  os << "* best in its column: smallest area, flat area, gamma max, energy and shear-limit "
        "stops; largest gamma min and coverage (ties, within 1e-9 relative, are all marked)\n";
}

void print_markdown(const std::vector<Row>& rows, std::ostream& os) {
  os << "| scene |";
  for (const auto& k : criteria()) os << " " << k.header << " |";
  os << "\n|---|";
  for (std::size_t c = 0; c < criteria().size(); ++c) os << "---:|";
  os << "\n";
  for (const auto& r : rows) {
    os << "| " << r.name << " |";
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok)
        os << " error |";
      else if (r.best[c])
        os << " **" << cell(r, c) << "** |";
      else
        os << " " << cell(r, c) << " |";
    }
    os << "\n";
  }
  os << "\nBest in bold: smallest area, flat area, gamma max, energy and shear-limit stops; "
        "largest gamma min and coverage (ties, within 1e-9 relative, are all marked).\n";
}

void print_csv(const std::vector<Row>& rows, std::ostream& os) {
  os << "scene,status";
  for (const auto& k : criteria()) os << "," << k.key;
  os << ",best,error\n";
  for (const auto& r : rows) {
    os << r.name << "," << (r.ok ? "ok" : "error");
    std::string best;
    for (std::size_t c = 0; c < criteria().size(); ++c) {
      if (!r.ok) {
        os << ",";
        continue;
      }
      std::ostringstream v;
      v.precision(17);
      v << r.values[c];
      os << "," << v.str();
      if (r.best[c]) best += (best.empty() ? "" : ";") + criteria()[c].key;
    }
    std::string err = r.error;
    for (char& ch : err)
      if (ch == '"') ch = '\'';
    os << "," << best << "," << (err.empty() ? "" : "\"" + err + "\"") << "\n";
  }
}

/// The mold a job drapes: resolved file (or built-in spec), face and side.
std::string mold_identity(const DrapeJob& job) {
  std::string m = job.mold;
  if (m.rfind("builtin:", 0) != 0) {
    std::error_code ec;
    const auto c = fs::weakly_canonical(m, ec);
    if (!ec) m = c.string();
  }
  return m + " face " + std::to_string(job.face) + (job.flip_normal ? " (flipped)" : "");
}

int run_compare(const std::vector<std::string>& args) {
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")("csv", "print CSV (full precision)")(
      "markdown", "print a Markdown table")(
      "output,o", po::value<std::string>(),
      "also write each scene's outputs into OUTROOT/<scene name>/")(
      "force", "compare scenes on different molds or faces anyway (with a warning)")(
      "scene", po::value<std::vector<std::string>>(), "scene files");
  po::positional_options_description pos;
  pos.add("scene", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("compare: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    std::cout << "usage: plyfit compare SCENE... [--csv | --markdown] [-o OUTROOT] [--force]\n\n"
                 "Drapes every scene (one mold face, different initial conditions) and prints,\n"
                 "per scene, the figures of the paper's Tables 2 and 4: area (mapped mesh\n"
                 "points), flat area (the flat pattern's outline), thread angles gamma min and\n"
                 "max, shear energy sum cos^2(gamma), coverage of the face and the nodes stopped\n"
                 "by the shear limit; the best scene for each criterion is marked. Scenes on\n"
                 "different molds or faces are refused unless --force.\n\n"
              << opts;
    return kExitOk;
  }
  if (!vm.count("scene")) {
    print_error("compare: no scene files (plyfit compare SCENE... [--csv | --markdown])");
    return kExitUsage;
  }
  if (vm.count("csv") && vm.count("markdown")) {
    print_error("compare: --csv and --markdown exclude each other");
    return kExitUsage;
  }
  const auto paths = vm["scene"].as<std::vector<std::string>>();
  const auto names = unique_scene_names(paths);
  // Load every scene first: a bad scene or a different mold stops before any drape.
  std::vector<DrapeJob> jobs;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    auto raw = raw_from_scene(paths[i]);
    if (!raw) {
      print_error("compare: " + raw.error().message);
      return kExitFailure;
    }
    auto job = make_job(*raw, false);
    if (!job) {
      print_error("compare: " + job.error().message);
      return kExitFailure;
    }
    job->outdir.clear();
    if (vm.count("output"))
      job->outdir = (fs::path(vm["output"].as<std::string>()) / names[i]).string();
    jobs.push_back(std::move(job).value());
  }
  for (std::size_t i = 1; i < jobs.size(); ++i) {
    if (mold_identity(jobs[i]) == mold_identity(jobs[0])) continue;
    const std::string msg = paths[i] + " drapes " + mold_identity(jobs[i]) + ", but " + paths[0] +
                            " drapes " + mold_identity(jobs[0]);
    if (!vm.count("force")) {
      print_error("compare: scenes on different molds: " + msg + " (--force compares them anyway)");
      return kExitUsage;
    }
    std::cerr << "plyfit: warning: comparing scenes on different molds: " << msg << "\n";
  }
  std::vector<Row> rows;
  bool all_ok = true;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    Row r;
    r.name = names[i];
    r.path = paths[i];
    auto out = run_job(jobs[i], nullptr, true);
    if (!out) {
      r.error = out.error().message;
      all_ok = false;
    } else {
      const auto& m = out->metrics;
      r.ok = true;
      r.values = {static_cast<double>(m.area_mesh_points),
                  out->flat_outline_area,
                  m.gamma_min * kRadToDeg,
                  m.gamma_max * kRadToDeg,
                  m.shear_energy,
                  out->face_area > 0 ? 100.0 * m.surface_area / out->face_area : 0.0,
                  static_cast<double>(m.nodes.shear_limit)};
    }
    rows.push_back(std::move(r));
  }
  mark_best(rows);
  if (vm.count("csv"))
    print_csv(rows, std::cout);
  else if (vm.count("markdown"))
    print_markdown(rows, std::cout);
  else
    print_text(rows, std::cout);
  for (const auto& r : rows)
    if (!r.ok) print_error("compare: " + r.name + ": " + r.error);
  return all_ok ? kExitOk : kExitFailure;
}

const CommandRegistrar kRegisterCompare{Command{
    "compare", "compare drapes of one mold face (the paper's Tables 2 and 4)", 40, run_compare}};

}  // namespace
}  // namespace plyfit::cli
