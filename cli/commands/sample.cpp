// plyfit sample NAME[:k=v,...] -o FILE [--format F]: writes a built-in mold (one face) or a
// built-in shell (several faces, sewn) as a STEP or IGES mold file (the sample molds under
// samples/ are made with it).

#include "commands/commands.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/mold_writer.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <boost/program_options.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

namespace plyfit::cli {
namespace {

namespace po = boost::program_options;

int run_sample(const std::vector<std::string>& args) {
  po::options_description opts("plyfit sample NAME[:key=value,...] -o FILE [options]");
  opts.add_options()("help,h", "show this help")("output,o", po::value<std::string>(),
                                                 "mold file to write (.step/.stp or .iges/.igs)")(
      "format", po::value<std::string>(), "step or iges, overriding the extension")(
      "name", po::value<std::string>(), "face name written into the file (default: NAME)")(
      "mold", po::value<std::string>(), "built-in mold, as for --mold builtin:NAME");
  po::positional_options_description pos;
  pos.add("mold", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(opts).positional(pos).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    print_error(std::string("sample: ") + e.what());
    return kExitUsage;
  }
  if (vm.count("help")) {
    std::cout << "Writes a built-in mold as a one-face STEP or IGES file (exact NURBS surface,\n"
                 "trims and holes as exact curves on it, the face normal as plyfit's, 17\n"
                 "significant digits, a fixed header time stamp so that the bytes depend only\n"
                 "on the inputs), or a built-in shell as one file of several faces sewn along\n"
                 "their shared edges.\n\n"
              << opts << "\nbuilt-in molds (see plyfit drape --help for their parameters):";
    for (const auto& b : builtin_molds()) std::cout << " " << b.name;
    std::cout << "\nbuilt-in shells:";
    for (const auto& b : builtin_shells()) std::cout << " " << b.name;
    std::cout << "\n";
    return kExitOk;
  }
  if (!vm.count("mold") || !vm.count("output")) {
    print_error("sample: usage: plyfit sample NAME[:key=value,...] -o FILE [--format step|iges]");
    return kExitUsage;
  }
  std::string spec_text = vm["mold"].as<std::string>();
  if (spec_text.rfind("builtin:", 0) == 0) spec_text = spec_text.substr(8);
  auto spec = parse_builtin_spec(spec_text);
  if (!spec) {
    print_error("sample: " + exporters::describe(spec.error()));
    return kExitUsage;
  }
  Result<ShellData> shell = ShellData{};
  Result<BuiltinFace> face = BuiltinFace{};
  if (is_builtin_shell(spec->first))
    shell = builtin_shell(spec->first, spec->second);
  else
    face = builtin_face(spec->first, spec->second);
  if (!shell || !face) {
    print_error("sample: " + exporters::describe(shell ? face.error() : shell.error()));
    return kExitUsage;
  }
  exporters::MoldWriteOptions wo;
  if (vm.count("format")) wo.format = vm["format"].as<std::string>();
  wo.name = vm.count("name") ? vm["name"].as<std::string>() : spec->first;
  const std::string path = vm["output"].as<std::string>();
  // A format the writer does not know is a bad command line (2), not a failed write (1).
  {
    std::string f = wo.format;
    if (f.empty()) {
      f = std::filesystem::path(path).extension().string();
      if (!f.empty()) f.erase(0, 1);
      std::transform(f.begin(), f.end(), f.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      if (f == "stp") f = "step";
      if (f == "igs") f = "iges";
    }
    const auto known = exporters::mold_formats();
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      print_error("sample: " + path + ": unknown mold format '" + f +
                  "' (use a .step, .stp, .iges or .igs file, or --format step|iges)");
      return kExitUsage;
    }
  }
  const Status st = is_builtin_shell(spec->first) ? exporters::write_shell(*shell, path, wo)
                                                  : exporters::write_mold(*face, path, wo);
  if (!st) {
    print_error(exporters::describe(st.error()));
    return kExitFailure;
  }
  return kExitOk;
}

const CommandRegistrar kRegisterSample{Command{
    "sample", "write a built-in mold as a STEP or IGES file (the sample molds)", 50, run_sample}};

}  // namespace
}  // namespace plyfit::cli
