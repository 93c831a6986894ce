#pragma once
// What plyfit drape prints on stdout: the line of a finished drape, and the scene keys as a
// Markdown table (--scene-keys, for the manual).

#include "job/drape_job.hpp"

#include <iosfwd>
#include <string>

namespace plyfit::cli {

/// "plyfit: STATUS: N nodes mapped (...), ...; max shear X deg; T ms -> OUTDIR".
std::string drape_summary(const JobOutcome& out, const std::string& outdir);

/// The scene keys (drape_options()) as a Markdown table: key, section, value, default, meaning.
void scene_keys_markdown(std::ostream& os);

}  // namespace plyfit::cli
