#pragma once
/// \file The text of errors and warnings: plyfit's modules report codes with data (result.hpp);
/// the CLI and the report make their words here, and nowhere else.

#include <plyfit/kernel/result.hpp>

#include <functional>
#include <string>

namespace plyfit::exporters {

/// The sentence of an error, without the input it blames, its face or place (see describe()).
std::string message(const Error& e);

/// Names an error's input for the reader: a drape input's scene key as the flag or the scene
/// file's key it came from, a file as its path. The default names it as it is.
using InputNamer = std::function<std::string(const std::string& input)>;

/// The whole one-line error: "INPUT: face N: WHERE: sentence", the parts it has.
std::string describe(const Error& e, const InputNamer& name_input = {});

/// The sentence of a warning.
std::string message(const Warning& w);

/// The sentences of warnings, in order, joined by `separator`.
std::string messages(const std::vector<Warning>& warnings, const std::string& separator = "; ");

}  // namespace plyfit::exporters
