// plyfit drape [SCENE.ini] [flags]: one drape, outputs into -o DIR.

#include "commands.hpp"
#include "drape_job.hpp"

#include <plyfit/kernel/builtin_molds.hpp>

#include <algorithm>
#include <iostream>

namespace plyfit::cli {
namespace {

void drape_help(std::ostream& os) {
  os << "usage: plyfit drape [SCENE.ini] [options]\n\n"
        "Drapes a woven ply on one face of a mold and writes the outputs into -o DIR.\n"
        "A scene file holds the same keys as the options (without dashes); options given\n"
        "on the command line override it.\n\noptions:\n";
  for (const auto& s : drape_options()) {
    std::string flag = "  --" + s.key + (s.key == "output" ? ", -o" : "") + (s.value.empty() ? "" : " " + s.value);
    if (flag.size() < 34) flag += std::string(34 - flag.size(), ' ');
    else flag += "\n" + std::string(34, ' ');
    os << flag << s.help << (s.def.empty() ? "" : " [" + s.def + "]")
       << (s.repeatable ? " (repeatable)" : "") << "\n";
  }
  os << "  --dump-scene                    print the effective scene as INI and exit\n"
        "  --quiet                         no progress line\n"
        "\nbuilt-in molds (--mold builtin:NAME[:key=value,...]):\n";
  for (const auto& b : builtin_molds()) {
    os << "  " << b.name << ":";
    for (const auto& p : b.params) os << " " << p.key << "=" << p.value;
    os << "\n      " << b.placement << "\n";
  }
}

int run_drape(const std::vector<std::string>& args_in) {
  std::vector<std::string> args = args_in;
  if (std::find(args.begin(), args.end(), "--help") != args.end() ||
      std::find(args.begin(), args.end(), "-h") != args.end()) {
    drape_help(std::cout);
    return kExitOk;
  }
  bool dump = false, quiet = false;
  args.erase(std::remove_if(args.begin(), args.end(), [&](const std::string& a) {
               if (a == "--dump-scene") return dump = true;
               if (a == "--quiet") return quiet = true;
               return false;
             }), args.end());
  RawOptions raw;
  if (!args.empty() && args.front().rfind("-", 0) != 0) {
    auto scene = raw_from_scene(args.front());
    if (!scene) {
      print_error(scene.error().message);
      return kExitUsage;
    }
    raw = std::move(scene).value();
    args.erase(args.begin());
  }
  auto flags = raw_from_args(args);
  if (!flags) {
    print_error(flags.error().message);
    return kExitUsage;
  }
  raw = raw.origin.empty() ? std::move(flags).value() : merge(raw, *flags);
  auto job = make_job(raw, !dump);
  if (!job) {
    print_error(job.error().message);
    return kExitUsage;
  }
  if (dump) {
    std::cout << dump_scene(*job);
    return kExitOk;
  }
  auto out = run_job(*job, nullptr, !quiet);
  if (!out) {
    print_error(out.error().message);
    return kExitFailure;
  }
  const auto& m = out->metrics;
  std::cout << "plyfit: " << out->status << ": " << m.nodes.mapped << " nodes mapped ("
            << m.nodes.auxiliary << " auxiliary base-path points), " << m.nodes.outside << " outside, "
            << m.nodes.off_ply << " off the ply, " << m.nodes.shear_limit << " at the shear limit, "
            << m.nodes.failed << " failed; max shear " << out->shear_max_deg << " deg; "
            << static_cast<long>(out->total_ms) << " ms -> " << job->outdir << "\n";
  return kExitOk;
}

const CommandRegistrar kRegister{{"drape", "drape a ply on a mold face and write the outputs", 20, run_drape}};

}  // namespace
}  // namespace plyfit::cli
