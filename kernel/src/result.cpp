// The names of the error and warning codes (result.hpp).
#include <plyfit/kernel/result.hpp>

namespace plyfit {

const char* to_string(ErrorCode code) {
  switch (code) {
#define PLYFIT_NAME_ENTRY(name, snake) \
  case ErrorCode::k##name:             \
    return #snake;
    PLYFIT_ERROR_CODES(PLYFIT_NAME_ENTRY)
#undef PLYFIT_NAME_ENTRY
  }
  return "internal";
}

const char* to_string(WarningCode code) {
  switch (code) {
#define PLYFIT_NAME_ENTRY(name, snake) \
  case WarningCode::k##name:           \
    return #snake;
    PLYFIT_WARNING_CODES(PLYFIT_NAME_ENTRY)
#undef PLYFIT_NAME_ENTRY
  }
  return "note";
}

}  // namespace plyfit
