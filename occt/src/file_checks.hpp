#pragma once
// Checks of a STEP or IGES file's text made before OpenCASCADE reads it: what its readers would
// take in silently and choke on later. Numbers that are not finite (1.0E+999 overflows to
// infinity; an IGES reader takes INF and NaN for numbers) or absurd in a geometric entity (a
// coordinate, knot, radius or unit factor of more than kMaxFileNumber), and, in STEP, lists
// nested deeper than kMaxStepNesting, references in a cycle or chained deeper than
// kMaxStepReferenceDepth (OpenCASCADE's STEP reader recurses once per level and overflows the
// stack). Errors are codes naming the entity in Error::where (STEP "#id (KEYWORD)", IGES
// "DE n (type t), parameter k"); the caller names the file (Error::in).
//
// Private to the OpenCASCADE module (no OpenCASCADE type in the interface).

#include <plyfit/kernel/result.hpp>

#include <string>

namespace plyfit::importers::occt {

/// Largest magnitude of a number in a geometric entity of a file, in the file's unit: no mold is
/// 100 km large, and a parameter of that size leaves no digits for the geometry.
constexpr double kMaxFileNumber = 1e8;
/// Deepest nesting of parentheses in a STEP entity. Real files nest a few levels (a complex
/// entity holding a list of lists of poles); every level costs OpenCASCADE's reader a
/// recursion.
constexpr int kMaxStepNesting = 100;
/// Longest chain of references in a STEP file (an entity referring to one that refers to ...).
/// Real files chain a few dozen (product, representation, shell, face, loop, edge, curve,
/// point); the reader follows them recursively.
constexpr int kMaxStepReferenceDepth = 1000;

/// Reads the file `path` and checks it as STEP (`step`) or IGES.
Status check_file_text(const std::string& path, bool step);

/// Checks the DATA section of the STEP file `text`.
Status check_step_text(const std::string& text);

/// Checks the global and parameter sections of the IGES file `text`.
Status check_iges_text(const std::string& text);

}  // namespace plyfit::importers::occt
