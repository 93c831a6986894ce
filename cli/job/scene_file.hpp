#pragma once
// Scene files: a drape job's keys as INI text (sections for grouping, keys as the flags
// without dashes), read into raw values and written back from a job (--dump-scene).

#include "job/drape_job.hpp"
#include "job/ini.hpp"

#include <string>

namespace plyfit::cli {

/// Reads a scene file. Errors are placed in the file (Error::where "FILE:LINE") or blame a key
/// (name them with scene_namer(path)).
Result<RawOptions> raw_from_scene(const std::string& path);

/// A scene (or laminate) file's lines; errors: scene_cannot_open, or placed in the file.
Result<std::vector<IniLine>> read_scene_lines(const std::string& path);

/// Adds a key = value line of a scene file (`path`, relative paths from `dir`) to raw values:
/// sections are for grouping ("[ply] spacing = 1" is the key "spacing"), a dotted key is its
/// last part. Messages name the key as coming from `origin` (empty: the file).
Status add_scene_key(const IniLine& l, const std::string& path, const std::string& dir,
                     RawOptions& raw, const std::string& origin = {});

/// Names a scene file's keys in messages: "FILE: key 'key'".
exporters::InputNamer scene_namer(const std::string& path);

/// The effective scene as INI text (defaults filled in), loadable again with raw_from_scene.
std::string dump_scene(const DrapeJob& job);

}  // namespace plyfit::cli
