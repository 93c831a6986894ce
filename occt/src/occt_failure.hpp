#pragma once
// OpenCASCADE's exceptions as the values of an error (ErrorCode::kOcctFailed,
// kWriterOcctFailed): its words are OpenCASCADE's, data for plyfit's text.

#include <plyfit/kernel/result.hpp>

#include <Standard_Failure.hxx>

#include <string>
#include <vector>

namespace plyfit::occt {

/// The exception's type name and its message on one line (empty when it has none).
inline std::vector<MessageValue> failure_values(const Standard_Failure& e) {
  std::string msg = e.GetMessageString() ? e.GetMessageString() : "";
  for (auto& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  return {std::string(e.DynamicType()->Name()), std::move(msg)};
}

}  // namespace plyfit::occt
