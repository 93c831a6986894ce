// plyfit-bench: speed and accuracy figures. `plyfit-bench NAME [args]`; see BENCHMARKS.md.

#include "bench.hpp"
#include "memory.hpp"

#include <iostream>

namespace plyfit::bench {
std::vector<Benchmark>& benchmarks() {
  static std::vector<Benchmark> list;
  return list;
}
}  // namespace plyfit::bench

int main(int argc, char** argv) {
  using namespace plyfit::bench;
  auto usage = [](std::ostream& os) {
    os << "usage: plyfit-bench NAME [args]\n\nbenchmarks:\n";
    for (const auto& b : benchmarks()) os << "  " << b.name << "\t" << b.summary << "\n";
  };
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  // Large blocks are mapped and unmapped at once, so that RSS figures of successive drapes are
  // comparable.
  memory::stable_malloc();
  const std::string name = argv[1];
  if (name == "--help" || name == "-h") {
    usage(std::cout);
    return 0;
  }
  for (const auto& b : benchmarks())
    if (b.name == name) return b.run(std::vector<std::string>(argv + 2, argv + argc));
  std::cerr << "plyfit-bench: unknown benchmark '" << name << "'\n";
  usage(std::cerr);
  return 2;
}
