// plyfit sample NAME[:k=v,...] -o FILE [--format F]: writes a built-in mold (one face) or a
// built-in shell (several faces, sewn) as a STEP or IGES mold file (the sample molds under
// samples/ are made with it).

#include "commands/commands.hpp"

#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

namespace plyfit::cli {
namespace {

const OptionTable& sample_options() {
  static const OptionTable table = {
      help_option(),
      output_option("FILE", "mold file to write (.step/.stp or .iges/.igs)"),
      {"format", "F", "", "step or iges, overriding the extension"},
      {"name", "TEXT", "", "face name written into the file (default: NAME)"},
      {"mold", "NAME", "", "built-in mold, as for --mold builtin:NAME"},
  };
  return table;
}

const CommandHelp kSampleHelp = {
    "plyfit sample NAME[:key=value,...] -o FILE [options]",
    "Writes a built-in mold as a one-face STEP or IGES file (exact NURBS surface,\n"
    "trims and holes as exact curves on it, the face normal as plyfit's, 17\n"
    "significant digits, a fixed header time stamp so that the bytes depend only\n"
    "on the inputs), or a built-in shell as one file of several faces sewn along\n"
    "their shared edges.\n",
    [](std::ostream& os) {
      os << "\nbuilt-in molds (see plyfit drape --help for their parameters):";
      for (const auto& b : builtin_molds()) os << " " << b.name;
      os << "\nbuilt-in shells:";
      for (const auto& b : builtin_shells()) os << " " << b.name;
      os << "\n";
    }};

// The format a mold file is written in: --format, else the file's extension; one the writer
// does not know is a bad command line.
Result<std::string> mold_format(const std::string& path, std::string format) {
  if (format.empty()) {
    format = std::filesystem::path(path).extension().string();
    if (!format.empty()) format.erase(0, 1);
    std::transform(format.begin(), format.end(), format.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (format == "stp") format = "step";
    if (format == "igs") format = "iges";
  }
  const auto known = exporters::mold_formats();
  if (std::find(known.begin(), known.end(), format) == known.end())
    return Error{ErrorCode::kUnknownMoldFormat, path, {format}};
  return format;
}

// Writes the built-in mold or shell `spec` (bad command lines: 2; a failed write: 1).
int write_sample(const std::string& spec_text, const std::string& path,
                 exporters::MoldWriteOptions wo) {
  auto spec =
      parse_builtin_spec(spec_text.rfind("builtin:", 0) == 0 ? spec_text.substr(8) : spec_text);
  if (!spec) return error_exit(kExitUsage, spec.error());
  if (wo.name.empty()) wo.name = spec->first;
  const bool shell_mold = is_builtin_shell(spec->first);
  Result<ShellData> shell = ShellData{};
  Result<BuiltinFace> face = BuiltinFace{};
  if (shell_mold)
    shell = builtin_shell(spec->first, spec->second);
  else
    face = builtin_face(spec->first, spec->second);
  if (!shell || !face) return error_exit(kExitUsage, shell ? face.error() : shell.error());
  if (auto f = mold_format(path, wo.format); !f) return error_exit(kExitUsage, f.error());
  const Status written = shell_mold ? exporters::write_shell(*shell, path, wo)
                                    : exporters::write_mold(*face, path, wo);
  return written ? kExitOk : error_exit(kExitFailure, written.error());
}

int run_sample(const Options& o) {
  if (!o.given("output")) return error_exit(kExitUsage, o.missing("output"), o.namer());
  exporters::MoldWriteOptions wo;
  wo.format = o.text("format").value_or("");
  wo.name = o.text("name").value_or("");
  return write_sample(*o.text("mold"), *o.text("output"), wo);
}

const CommandRegistrar kRegisterSample{
    options_command("sample", "write a built-in mold as a STEP or IGES file (the sample molds)", 50,
                    {sample_options, {"mold", "built-in mold"}, kSampleHelp}, run_sample)};

}  // namespace
}  // namespace plyfit::cli
