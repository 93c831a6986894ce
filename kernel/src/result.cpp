// The names of the error and warning codes (result.hpp).
#include <plyfit/kernel/result.hpp>

#include <cstddef>

namespace plyfit {

namespace {

#define PLYFIT_NAME_ENTRY(name, snake) #snake,
constexpr const char* kErrorNames[] = {PLYFIT_ERROR_CODES(PLYFIT_NAME_ENTRY)};
constexpr const char* kWarningNames[] = {PLYFIT_WARNING_CODES(PLYFIT_NAME_ENTRY)};
#undef PLYFIT_NAME_ENTRY

// The name of `code` in its table (in the order of its enumeration), `fallback` for a value
// out of range.
template <typename Code, std::size_t N>
const char* name_of(const char* const (&names)[N], Code code, const char* fallback) {
  const auto k = static_cast<std::size_t>(code);
  return k < N ? names[k] : fallback;
}

}  // namespace

const char* to_string(ErrorCode code) {
  return name_of(kErrorNames, code, "internal");
}

const char* to_string(WarningCode code) {
  return name_of(kWarningNames, code, "note");
}

}  // namespace plyfit
