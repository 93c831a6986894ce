// plyfit: composite-ply flat patterns from CAD molds. Thin dispatcher over subcommands.

#include "commands/commands.hpp"

#include <plyfit/occt/module.hpp>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <set>
#include <string>

namespace {

void usage(std::ostream& os) {
  auto list = plyfit::cli::commands();
  std::sort(list.begin(), list.end(),
            [](const auto& a, const auto& b) { return a.order < b.order; });
  os << "plyfit " PLYFIT_VERSION " - composite-ply flat patterns from CAD molds\n\n"
     << "usage: plyfit COMMAND [options]   (plyfit COMMAND --help for its options)\n\n"
     << "commands:\n";
  for (const auto& c : list) {
    os << "  " << c.name << std::string(c.name.size() < 10 ? 10 - c.name.size() : 1, ' ')
       << c.summary << "\n";
  }
}

// Debugging and tests: when PLYFIT_DEBUG_LIBRARIES names a file, the shared objects mapped into
// the process at the end of the command (from /proc/self/maps), one path a line, are written
// there; e.g. a drape on a built-in mold lists no OpenCASCADE library.
void write_loaded_libraries() {
  const char* out = std::getenv("PLYFIT_DEBUG_LIBRARIES");
  if (!out || !*out) return;
  std::ifstream maps("/proc/self/maps");
  std::set<std::string> libs;
  std::string line;
  while (std::getline(maps, line)) {
    const auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    if (path.find(".so") != std::string::npos) libs.insert(path);
  }
  std::ofstream os(out);
  for (const auto& l : libs) os << l << "\n";
}

int run(int argc, char** argv) {
  using namespace plyfit::cli;
  if (argc < 2) {
    usage(std::cerr);
    return kExitUsage;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    usage(std::cout);
    return kExitOk;
  }
  if (name == "--version") {
    std::cout << "plyfit " PLYFIT_VERSION "\n";
    return kExitOk;
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    try {
      return c.run(args);
    } catch (const std::exception& e) {
      // Only broken internal invariants throw; still one line and a non-zero exit.
      print_error(plyfit::Error{plyfit::ErrorCode::kInternal, "", {std::string(e.what())}});
      return kExitFailure;
    }
  }
  print_error(plyfit::Error{plyfit::ErrorCode::kUnknownCommand, "", {name}});
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  // Benchmarks: PLYFIT_DEBUG_PRELOAD_OCCT=1 loads the OpenCASCADE module at the start, the cost
  // every job would pay if it were not loaded on first use (plyfit-bench small-jobs).
  if (const char* p = std::getenv("PLYFIT_DEBUG_PRELOAD_OCCT"); p && *p == '1')
    static_cast<void>(plyfit::occt::occt_module_symbol("plyfit_occt_importers"));
  const int code = run(argc, argv);
  write_loaded_libraries();
  return code;
}
