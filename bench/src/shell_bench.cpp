// plyfit-bench shell FILE [--faces all|I,J,...] [--runs R]: how long sewing faces of a mold into
// a shell and converting them takes (MoldFile::convert_shell), against converting the same
// faces one by one (convert_face) in the same run. Medians of R >= 5 runs, each on a freshly
// opened file (so that no face listing is cached between runs), the three kinds interleaved.

#include "bench.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

namespace plyfit::bench {

namespace {

constexpr const char* kUsage = "usage: plyfit-bench shell FILE [--faces all|I,J,...] [--runs R]\n";

int run_shell(const std::vector<std::string>& args) {
  std::string path, faces_arg = "all";
  int runs = kMinRuns;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--faces" && i + 1 < args.size()) {
      faces_arg = args[++i];
    } else if (args[i] == "--runs" && i + 1 < args.size()) {
      runs = std::stoi(args[++i]);
    } else if (path.empty()) {
      path = args[i];
    } else {
      std::cerr << kUsage;
      return 2;
    }
  }
  if (path.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  std::vector<int> faces;  // empty: all
  if (faces_arg != "all") {
    std::stringstream ss(faces_arg);
    for (std::string tok; std::getline(ss, tok, ',');) faces.push_back(std::stoi(tok));
  }
  auto file = importers::open_mold(path);
  if (!file) {
    std::cerr << "plyfit-bench: " << exporters::describe(file.error()) << "\n";
    return 1;
  }
  const std::vector<int> chosen = faces.empty() ? (*file)->all_faces() : faces;
  auto shell = (*file)->convert_shell(faces);
  if (!shell) {
    std::cerr << "plyfit-bench: " << exporters::describe(shell.error()) << "\n";
    return 1;
  }
  // The three timings interleaved run by run, so that a change in the machine's load (it is
  // shared) touches them alike.
  bool ok = true;
  std::vector<double> opens, shells, each;
  for (int r = 0; r < std::max(runs, kMinRuns); ++r) {
    opens.push_back(time_once([&] { ok = ok && importers::open_mold(path).ok(); }));
    shells.push_back(time_once([&] {
      auto f = importers::open_mold(path);
      ok = ok && f.ok() && (*f)->convert_shell(faces).ok();
    }));
    each.push_back(time_once([&] {
      auto f = importers::open_mold(path);
      ok = ok && f.ok();
      for (int i : chosen) ok = ok && (*f)->convert_face(i).ok();
    }));
  }
  const double t_open = median(opens), t_shell = median(shells), t_faces = median(each);
  if (!ok) {
    std::cerr << "plyfit-bench: an import failed during timing\n";
    return 1;
  }
  size_t loops = 0, points = 0, free_segments = 0, shared_segments = 0;
  for (const auto& fd : shell->faces)
    for (const auto& l : fd.loops) {
      ++loops;
      points += l.points.size();
      for (auto e : l.edges) (e == TrimLoop::kFreeEdge ? free_segments : shared_segments) += 1;
    }
  std::printf("file: %s, %zu faces sewn\n", path.c_str(), shell->faces.size());
  std::printf(
      "shared edges %d, largest gap closed %.3g mm; %zu loops, %zu points, %zu segments "
      "on shared edges, %zu free\n",
      shell->edge_count, shell->tolerance, loops, points, shared_segments, free_segments);
  for (const auto& w : (*file)->summary().warnings)
    std::printf("warning: %s\n", exporters::message(w).c_str());
  std::printf("open (read + transfer):            %8.1f ms (median of %d)\n", 1e3 * t_open,
              std::max(runs, kMinRuns));
  std::printf("open + convert_shell:              %8.1f ms\n", 1e3 * t_shell);
  std::printf("open + convert_face of each face:  %8.1f ms\n", 1e3 * t_faces);
  // The cost of sewing (and of the loops of untrimmed faces) against the conversions alone.
  std::printf("convert_shell / converting each face (open excluded): %.2f\n",
              (t_shell - t_open) / (t_faces - t_open));
  return 0;
}

const BenchmarkRegistrar kRegisterShell{Benchmark{
    "shell", "time of sewing faces of a mold into a shell and converting them", run_shell}};

}  // namespace

}  // namespace plyfit::bench
