// plyfit: composite-ply flat patterns from CAD molds. Thin dispatcher over subcommands.

#include "commands.hpp"

#include <algorithm>
#include <exception>
#include <iostream>

namespace plyfit::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

void print_error(const std::string& message) {
  std::string one_line = message;
  std::replace(one_line.begin(), one_line.end(), '\n', ' ');
  std::cerr << "plyfit: error: " << one_line << "\n";
}

}  // namespace plyfit::cli

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

}  // namespace

int main(int argc, char** argv) {
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
      print_error(std::string("internal error: ") + e.what());
      return kExitFailure;
    }
  }
  print_error("unknown command '" + name + "' (try plyfit --help)");
  return kExitUsage;
}
