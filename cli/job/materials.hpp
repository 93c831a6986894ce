#pragma once
// The materials table: each woven fabric's warning and limit (locking) shear angles, read from
// an INI file, with each fabric's roll width (data/materials.ini is built into plyfit; `--materials
// FILE` reads another).

#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::cli {

/// One material of the table.
struct Material {
  std::string name;          ///< the section name, what --material takes
  std::string label;         ///< text for labels (the name when the file gives none)
  double warning_deg = 0.0;  ///< shear above which cells are flagged (degrees)
  double limit_deg = 90.0;   ///< locking angle (degrees); 90: no limit
  double roll_width = 0.0;   ///< the roll's width (mm); 0: none given (no splices)
};

/// A materials table and where it came from.
struct MaterialTable {
  std::string source;  ///< the file, or a description of the built-in table, for messages
  std::vector<Material> materials;
};

/// The material every drape uses when none is chosen.
inline constexpr const char* kDefaultMaterial = "woven";

/// Parses a table (INI text: a [name] section per material with the keys label, warning,
/// limit and roll-width). An error's place (Error::where) is "SOURCE:LINE" or "SOURCE"; its input
/// is left to the caller (the option that named the table).
Result<MaterialTable> parse_materials(const std::string& text, const std::string& source);

/// Reads a table from a file; errors name the file as their place.
Result<MaterialTable> load_materials(const std::string& path);

/// The table built into plyfit (data/materials.ini at build time).
Result<MaterialTable> builtin_materials();

/// The material `name`, or an error whose place is the table's source, listing the known
/// names.
Result<Material> find_material(const MaterialTable& table, const std::string& name);

}  // namespace plyfit::cli
