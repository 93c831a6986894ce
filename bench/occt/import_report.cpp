// plyfit-bench import-table [--runs R] [--stress-dir DIR] [--baseline BIN]: import speed per
// file against OpenCASCADE's own read time, and plyfit info's process time.
// plyfit-bench areas [--stress-dir DIR]: plyfit's face areas against OpenCASCADE's.
// plyfit-bench small-jobs [--runs R] [--baseline BIN]: process time of small jobs.
// The stress files (plyfit-bench stress-mold) are written into DIR (default: a folder in the
// system's temporary directory) when missing. BIN is another plyfit binary (e.g. one built from
// the commit before OpenCASCADE was loaded lazily) timed in the same run.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include "bench.hpp"
#include "face_measure.hpp"  // occt/src: the integration itself, in both directions
#include "tables.hpp"

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

namespace plyfit::bench {

namespace {

namespace fs = std::filesystem;

// The accuracies the importer asks for (importers/src/occt_mold.cpp).
constexpr double kListingRel = 1e-6, kDescribedRel = 1e-9;
// OpenCASCADE's 1e-12 integration of a file's faces is timed once, not kMinRuns times, when
// one run takes longer than this (seconds): 24 s on the 25-face stress file.
constexpr double kSlowOnceSeconds = 5.0;
// Runs of each small job (they take tens of milliseconds).
constexpr int kSmallJobRuns = 21;

// The stress files: name, faces, poles per direction, holes.
struct Stress {
  const char* name;
  int faces, poles, holes;
};
constexpr Stress kStress[] = {
    {"stress-25x30.igs", 25, 30, 3},   // 3.4 MB, the size of the propeller IGES
    {"stress-25x30.step", 25, 30, 3},  // the same faces in STEP
    {"stress-4x100.igs", 4, 100, 3},   // few very large faces
};

// A file of the tables: its label and path.
struct File {
  std::string label, path;
};

std::vector<File> files(const std::string& stress_dir, bool* ok) {
  std::vector<File> out;
  const std::string cad = std::string(PLYFIT_SHARED_DIR) + "/cad";
  for (const char* name :
       {"BUC50025.igs", "PRO20359-L1.igs", "occ22470.igs", "surf114.igs", "example_45_faces.iges",
        "bug27693_cornetta-step.stp", "trj7_c2-td-203.stp", "trj8_c2-db-214.stp"})
    if (fs::exists(cad + "/" + name)) out.push_back({name, cad + "/" + name});
  std::error_code ec;
  fs::create_directories(stress_dir, ec);
  for (const Stress& s : kStress) {
    const std::string path = stress_dir + "/" + s.name;
    if (!fs::exists(path) && !write_stress_mold(path, s.faces, s.poles, s.holes)) {
      std::fprintf(stderr, "plyfit-bench: could not write %s\n", path.c_str());
      *ok = false;
      continue;
    }
    out.push_back({std::string(s.name) + " (stress-mold)", path});
  }
  return out;
}

std::string default_stress_dir() {
  return (fs::temp_directory_path() / "plyfit-bench-stress").string();
}

bool is_iges(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext == ".igs" || ext == ".iges";
}

// OpenCASCADE's own reading of a file (ReadFile and TransferRoots, lengths in mm as plyfit
// asks), and its faces in TopExp::MapShapes order.
TopTools_IndexedMapOfShape occt_read(const std::string& path) {
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  TopoDS_Shape shape;
  if (is_iges(path)) {
    IGESControl_Reader r;
    r.ReadFile(path.c_str());
    r.TransferRoots();
    shape = r.OneShape();
  } else {
    STEPControl_Reader r;
    r.ReadFile(path.c_str());
    r.TransferRoots();
    shape = r.OneShape();
  }
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  return faces;
}

// Median wall-clock seconds of `runs` runs; ok false if one failed.
double median_process(const std::vector<std::string>& args, const std::vector<std::string>& env,
                      int runs, bool* ok) {
  std::vector<double> t;
  for (int i = 0; i < std::max(runs, kMinRuns); ++i) {
    const ProcessRun p = run_process(args, env);
    if (p.code != 0) *ok = false;
    t.push_back(p.seconds);
  }
  return median(t);
}

// The face a drape of the file would find heaviest to import: the most poles, then the
// largest area.
int heaviest_face(const Mold& m) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(m.faces.size()); ++i) {
    const FaceInfo &a = m.faces[static_cast<size_t>(i)], &b = m.faces[static_cast<size_t>(best)];
    if (a.poles_u * a.poles_v > b.poles_u * b.poles_v ||
        (a.poles_u * a.poles_v == b.poles_u * b.poles_v && a.area > b.area))
      best = i;
  }
  return best;
}

double megabytes(const std::string& path) {
  std::error_code ec;
  return static_cast<double>(fs::file_size(path, ec)) / (1024.0 * 1024.0);
}

}  // namespace

ImportReport import_report(int runs, const std::string& stress_dir, const std::string& baseline) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  ImportReport rep;
  rep.table.caption = format(
      "Import speed, medians of %d runs. *OpenCASCADE read*: STEPControl_Reader or "
      "IGESControl_Reader, ReadFile and TransferRoots, in this process. *open*: "
      "importers::open_mold (read, transfer, face walk); *listing*: open and mold() (every "
      "face described, areas to 1e-6: plyfit info's work); *import*: load_face of the file's "
      "heaviest face (most poles): open, its description with the area to 1e-9, conversion and "
      "Face::create, what a drape's `timing_ms.import` covers. *plyfit info*: the whole "
      "process, output discarded%s.",
      std::max(runs, kMinRuns),
      baseline.empty() ? "" : "; *before*: the same with the baseline binary");
  rep.table.header = {
      "file",         "MB",   "faces",       "OpenCASCADE read (ms)",     "open (ms)",
      "listing (ms)", "face", "import (ms)", "import / OpenCASCADE read", "plyfit info (ms)"};
  if (!baseline.empty()) rep.table.header.push_back("plyfit info before (ms)");
  rep.table.right = std::vector<bool>(rep.table.header.size(), true);
  rep.table.right[0] = false;
  for (const File& f : files(stress_dir, &rep.ok)) {
    std::fprintf(stderr, "import: %s\n", f.label.c_str());
    auto file = importers::open_mold(f.path);
    if (!file) {
      std::fprintf(stderr, "plyfit-bench: %s\n", exporters::describe(file.error()).c_str());
      rep.ok = false;
      continue;
    }
    const int face = heaviest_face((*file)->mold());
    bool ok = true;
    const double t_occt = median_time([&] { ok = occt_read(f.path).Extent() > 0 && ok; }, runs);
    const double t_open = median_time([&] { ok = importers::open_mold(f.path).ok() && ok; }, runs);
    const double t_list = median_time(
        [&] {
          auto m = importers::open_mold(f.path);
          ok = m.ok() && !(*m)->mold().faces.empty() && ok;
        },
        runs);
    const double t_import =
        median_time([&] { ok = importers::load_face(f.path, face).ok() && ok; }, runs);
    const double t_info = median_process({plyfit_binary(), "info", f.path}, {}, runs, &ok);
    rep.ok = rep.ok && ok;
    const double ratio = t_import / t_occt;
    rep.max_ratio = std::max(rep.max_ratio, ratio);
    rep.max_info_s = std::max(rep.max_info_s, t_info);
    std::vector<std::string> row = {f.label,
                                    format("%.2f", megabytes(f.path)),
                                    format("%zu", (*file)->mold().faces.size()),
                                    format("%.1f", 1e3 * t_occt),
                                    format("%.1f", 1e3 * t_open),
                                    format("%.1f", 1e3 * t_list),
                                    format("%d", face),
                                    format("%.1f", 1e3 * t_import),
                                    format("%.2f", ratio),
                                    format("%.0f", 1e3 * t_info)};
    if (!baseline.empty()) {
      bool base_ok = true;
      row.push_back(
          format("%.0f", 1e3 * median_process({baseline, "info", f.path}, {}, runs, &base_ok)));
      if (!base_ok) row.back() += " (failed)";
    }
    rep.table.add(row);
  }
  return rep;
}

Table area_table(const std::string& stress_dir) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  Table t;
  t.caption =
      "Face areas: plyfit's integration (importers/src/face_measure.cpp) against "
      "OpenCASCADE's (BRepGProp::SurfaceProperties asked for 1e-12, what the importer used "
      "before), all faces of each file, times summed over the faces (medians of 5 runs; "
      "OpenCASCADE's once where one run takes over 5 s). *listing* asks for 1e-6, *described* "
      "for 1e-9; *u-v*: the largest difference between the integration along u and along v "
      "(another path of quadratures for the same integral) at 1e-9, relative to the area; "
      "*listing error*: the largest difference of the listed area from the described one; "
      "*OpenCASCADE error*: the largest difference of OpenCASCADE's area from the described "
      "one; *short*: faces whose described area misses 1e-9 by its own estimate.";
  t.header = {
      "file", "faces",         "listing (ms)",      "described (ms)", "OpenCASCADE 1e-12 (ms)",
      "u-v",  "listing error", "OpenCASCADE error", "short"};
  t.right = std::vector<bool>(t.header.size(), true);
  t.right[0] = false;
  bool ok = true;
  for (const File& f : files(stress_dir, &ok)) {
    std::fprintf(stderr, "areas: %s\n", f.label.c_str());
    const TopTools_IndexedMapOfShape faces = occt_read(f.path);
    const int n = faces.Extent();
    auto face = [&](int i) { return TopoDS::Face(faces(i + 1)); };
    double uv = 0.0, listing_err = 0.0, occt_err = 0.0;
    int short_of = 0;
    std::vector<double> described(static_cast<size_t>(n)), occt(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const auto u = importers::occt::measure_face(face(i), kDescribedRel, false, false);
      const auto v = importers::occt::measure_face(face(i), kDescribedRel, false, true);
      const auto l = importers::occt::measure_face(face(i), kListingRel, true, false);
      described[static_cast<size_t>(i)] = u.area;
      uv = std::max(uv, std::abs(u.area - v.area) / u.area);
      listing_err = std::max(listing_err, std::abs(l.area - u.area) / u.area);
      short_of += !u.converged;
    }
    const double t_list = median_time([&] {
      for (int i = 0; i < n; ++i) importers::occt::measure_face(face(i), kListingRel, true);
    });
    const double t_desc = median_time([&] {
      for (int i = 0; i < n; ++i) importers::occt::measure_face(face(i), kDescribedRel, true);
    });
    auto occt_all = [&] {
      for (int i = 0; i < n; ++i) {
        GProp_GProps g;
        BRepGProp::SurfaceProperties(face(i), g, 1e-12);
        occt[static_cast<size_t>(i)] = g.Mass();
      }
    };
    const double once = time_once(occt_all);
    const double t_occt = once > kSlowOnceSeconds ? once : median_time(occt_all);
    for (int i = 0; i < n; ++i)
      occt_err = std::max(
          occt_err, std::abs(occt[static_cast<size_t>(i)] - described[static_cast<size_t>(i)]) /
                        described[static_cast<size_t>(i)]);
    t.add({f.label, format("%d", n), format("%.1f", 1e3 * t_list), format("%.1f", 1e3 * t_desc),
           format("%.0f%s", 1e3 * t_occt, once > kSlowOnceSeconds ? " (1 run)" : ""),
           format("%.1e", uv), format("%.1e", listing_err), format("%.1e", occt_err),
           format("%d", short_of)});
  }
  return t;
}

Table small_jobs_table(int runs, const std::string& baseline) {
  runs = std::max(runs, kSmallJobRuns);
  Table t;
  t.caption = format(
      "Small jobs: wall-clock time of the whole plyfit process (posix_spawn to exit, output "
      "discarded), medians of %d runs. The drape is the built-in hemisphere (R = 1) at spacing "
      "0.1 with every output (report.json, flat.dxf, net.step, the SVGs, net.vtk). *OpenCASCADE "
      "preloaded*: the same binary told to load its OpenCASCADE module at start "
      "(PLYFIT_DEBUG_PRELOAD_OCCT=1), the cost every job paid when plyfit linked OpenCASCADE%s.",
      runs, baseline.empty() ? "" : "; *baseline*: the given binary");
  t.header = {"job", "plyfit", "ms"};
  t.right = {false, false, true};
  const std::string bin = plyfit_binary();
  const std::string out = scratch_path("small").string();
  const std::vector<std::string> drape = {"drape",         "--mold",    "builtin:hemisphere",
                                          "--spacing",     "0.1",       "--start2d",
                                          "0,0",           "--base2d",  "0,1",
                                          "--sweep2d",     "-1,0",      "--sweep2d",
                                          "1,0",           "--start3d", "0,0,1",
                                          "--base-normal", "1,0,0",     "--sweep3d",
                                          "1,0,0",         "--sweep3d", "-1,0,0",
                                          "--quiet",       "-o",        out};
  auto with = [](const std::string& b, const std::vector<std::string>& args) {
    std::vector<std::string> a = {b};
    a.insert(a.end(), args.begin(), args.end());
    return a;
  };
  const std::string mold_step = std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/hemisphere.step";
  std::vector<std::string> file_drape = drape;
  file_drape[2] = mold_step;
  struct Job {
    std::string name, binary;
    std::vector<std::string> args, env;
  };
  std::vector<Job> jobs = {
      {"plyfit --version", bin, {"--version"}, {}},
      {"drape, built-in hemisphere, every output", bin, drape, {}},
      {"the same, OpenCASCADE preloaded", bin, drape, {"PLYFIT_DEBUG_PRELOAD_OCCT=1"}},
      {"drape, the hemisphere from samples/molds/hemisphere.step", bin, file_drape, {}},
      {"info samples/molds/hemisphere.step", bin, {"info", mold_step}, {}},
  };
  if (!baseline.empty()) {
    jobs.push_back({"drape, built-in hemisphere, every output", baseline, drape, {}});
    jobs.push_back(
        {"drape, the hemisphere from samples/molds/hemisphere.step", baseline, file_drape, {}});
  }
  for (const Job& j : jobs) {
    bool ok = true;
    const double s = median_process(with(j.binary, j.args), j.env, runs, &ok);
    t.add({j.name, j.binary == bin ? "this build" : "baseline",
           ok ? format("%.1f", 1e3 * s) : "failed"});
  }
  std::error_code ec;
  fs::remove_all(out, ec);
  return t;
}

namespace {

const BenchmarkRegistrar kRegisterImportTable{table_benchmark(
    "import-table",
    "import speed per file against OpenCASCADE's read [--runs R] [--stress-dir DIR] "
    "[--baseline BIN]",
    [](const std::vector<std::string>& args, bool* ok) {
      ImportReport rep =
          import_report(std::stoi(option_value(args, "--runs", std::to_string(kMinRuns))),
                        option_value(args, "--stress-dir", default_stress_dir()),
                        option_value(args, "--baseline", ""));
      *ok = rep.ok;
      return rep.table;
    })};
const BenchmarkRegistrar kRegisterAreas{
    table_benchmark("areas",
                    "face areas: plyfit's integration against OpenCASCADE's "
                    "[--stress-dir DIR]",
                    [](const std::vector<std::string>& args, bool*) {
                      return area_table(option_value(args, "--stress-dir", default_stress_dir()));
                    })};
const BenchmarkRegistrar kRegisterSmallJobs{
    table_benchmark("small-jobs", "process time of small jobs [--runs R] [--baseline BIN]",
                    [](const std::vector<std::string>& args, bool*) {
                      return small_jobs_table(
                          std::stoi(option_value(args, "--runs", std::to_string(kSmallJobRuns))),
                          option_value(args, "--baseline", ""));
                    })};

}  // namespace

}  // namespace plyfit::bench
