// plyfit-bench import FILE [--face N] [--runs R]: how long opening a mold (the listing that
// plyfit info prints) and importing one face take. Medians of R >= 5 runs.

#include "bench.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <cstdio>
#include <iostream>
#include <string>

namespace plyfit::bench {

namespace {

int run_import(const std::vector<std::string>& args) {
  std::string path;
  int face = 0, runs = 5;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--face" && i + 1 < args.size()) {
      face = std::stoi(args[++i]);
    } else if (args[i] == "--runs" && i + 1 < args.size()) {
      runs = std::stoi(args[++i]);
    } else if (path.empty()) {
      path = args[i];
    } else {
      std::cerr << "usage: plyfit-bench import FILE [--face N] [--runs R]\n";
      return 2;
    }
  }
  if (path.empty()) {
    std::cerr << "usage: plyfit-bench import FILE [--face N] [--runs R]\n";
    return 2;
  }
  auto file = importers::open_mold(path);
  if (!file) {
    std::cerr << "plyfit-bench: " << exporters::describe(file.error()) << "\n";
    return 1;
  }
  const Mold& m = (*file)->mold();
  if (face < 0 || face >= static_cast<int>(m.faces.size())) {
    std::cerr << "plyfit-bench: face " << face << " out of range\n";
    return 1;
  }
  bool ok = true;
  const double t_read = median_time(
      [&] {
        auto f = importers::open_mold(path);
        ok = ok && f.ok();
      },
      runs);
  const double t_open = median_time(
      [&] {
        auto f = importers::open_mold(path);
        ok = ok && f.ok() && !(*f)->mold().faces.empty();
      },
      runs);
  const double t_load = median_time(
      [&] {
        auto f = importers::load_face(path, face);
        ok = ok && f.ok();
      },
      runs);
  const double t_convert = median_time(
      [&] {
        auto d = (*file)->convert_face(face);
        ok = ok && d.ok();
      },
      runs);
  if (!ok) {
    std::cerr << "plyfit-bench: an import failed during timing\n";
    return 1;
  }
  auto d = (*file)->convert_face(face);
  const FaceInfo& fi = m.faces[face];
  std::printf("file: %s (%zu faces)\n", path.c_str(), m.faces.size());
  std::printf("face %d: %s %dx%d, %dx%d poles, %s, %zu trim loops, %zu loop points\n", face,
              fi.kind.c_str(), fi.degree_u, fi.degree_v, fi.poles_u, fi.poles_v,
              fi.trimmed ? "trimmed" : "untrimmed", d->loops.size(), [&] {
                size_t n = 0;
                for (const auto& l : d->loops) n += l.points.size();
                return n;
              }());
  std::printf("open (read + transfer):           %8.1f ms (median of %d)\n", 1e3 * t_read,
              std::max(runs, 5));
  std::printf("open + list (plyfit info's work): %8.1f ms\n", 1e3 * t_open);
  std::printf("load_face (open + one face):      %8.1f ms\n", 1e3 * t_load);
  std::printf("convert_face alone (listed face): %8.1f ms\n", 1e3 * t_convert);
  return 0;
}

const BenchmarkRegistrar kRegisterImport{
    Benchmark{"import", "time of opening a mold file and of importing one face", run_import}};

}  // namespace

}  // namespace plyfit::bench
