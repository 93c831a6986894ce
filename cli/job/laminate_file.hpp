#pragma once
// Laminate files (plyfit laminate): a [laminate] section (the mold, the rosette, the roll width,
// the seams' stagger and any scene key as the plies' default) and one [ply NAME] section per ply in
// stacking order (sequence, angle and any scene key that differs). A ply is the laminate's keys
// overridden by its section's: one set of raw values per ply, read by make_job like a scene file's.

#include "commands/command_line.hpp"

#include <string>
#include <vector>

namespace plyfit::cli {

/// The keys a laminate file has besides the scene keys: splice-stagger in [laminate], sequence
/// in a [ply NAME] section, angle in either.
const OptionTable& laminate_keys();

/// One ply of a laminate: its name, its place in the stack and its scene (raw values).
struct LaminatePly {
  std::string name;
  long sequence = 0;
  RawOptions raw;  ///< the laminate's keys overridden by the section's; output DIR/NAME
};

/// A laminate file read: its plies in stacking order (by sequence).
struct Laminate {
  std::string path;
  double roll_width = 1000.0;   ///< mm, the cut drawing's roll ([laminate] roll-width)
  double splice_stagger = 0.0;  ///< mm, between seams of plies of one fibre direction
  std::vector<LaminatePly> plies;
};

/// Reads a laminate file; each ply's output folder is `outdir`/NAME. Errors are placed in the
/// file (Error::where "FILE:LINE") or blame a key as "FILE [ply NAME]: key 'key'".
Result<Laminate> read_laminate(const std::string& path, const std::string& outdir);

/// Where a ply's keys come from in messages: "FILE [ply NAME]".
std::string ply_origin(const std::string& path, const std::string& name);

}  // namespace plyfit::cli
