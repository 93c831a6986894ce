#include <plyfit/kernel/flat_pattern.hpp>

namespace plyfit {

// Interim: the exact outline is not implemented yet (issue 6); nothing is reported.
FlatPattern flat_pattern(const DrapeSurface&, const DrapeResult&, const FlatPatternOptions&) {
  return {};
}

}  // namespace plyfit
