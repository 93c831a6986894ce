// plyfit drape [SCENE.ini] [flags]: one drape, outputs into -o DIR.

#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "job/outcome.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iostream>

namespace plyfit::cli {
namespace {

// Set by SIGINT/SIGTERM: the drape stops and no output is written.
std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int) {
  g_interrupted.store(true);
}

void catch_interrupts() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void drape_help(std::ostream& os) {
  os << "usage: plyfit drape [SCENE.ini] [options]\n\n"
        "Drapes a woven ply on one face of a mold and writes the outputs into -o DIR.\n"
        "A scene file holds the same keys as the options (without dashes); options given\n"
        "on the command line override it.\n\noptions:\n";
  for (const auto& s : drape_options()) {
    std::string flag =
        "  --" + s.key + (s.key == "output" ? ", -o" : "") + (s.value.empty() ? "" : " " + s.value);
    if (flag.size() < 34)
      flag += std::string(34 - flag.size(), ' ');
    else
      flag += "\n" + std::string(34, ' ');
    os << flag << s.help << (s.def.empty() ? "" : " [" + s.def + "]")
       << (s.repeatable ? " (repeatable)" : "") << "\n";
  }
  os << "  --dump-scene                    print the effective scene as INI and exit\n"
        "  --quiet                         no progress line\n"
        "  --outcome FILE                  also write the outcome as JSON (used by plyfit batch)\n"
        "  --scene-keys                    print the scene keys as a Markdown table and exit\n"
        "\nbuilt-in molds (--mold builtin:NAME[:key=value,...]):\n";
  for (const auto& b : builtin_molds()) {
    os << "  " << b.name << ":";
    for (const auto& p : b.params) os << " " << p.key << "=" << p.value;
    os << "\n      " << b.placement << "\n";
  }
}

// The scene keys as a Markdown table (for the README), straight from drape_options().
void scene_keys_markdown(std::ostream& os) {
  os << "| key (flag `--key`) | section | value | default | meaning |\n|---|---|---|---|---|\n";
  for (const auto& s : drape_options()) {
    std::string value = s.value.empty() ? "true/false" : s.value;
    for (std::size_t p = 0; (p = value.find('|', p)) != std::string::npos; p += 2)
      value.replace(p, 1, "\\|");
    os << "| `" << s.key << "`" << (s.key == "output" ? " (`-o`)" : "") << " | " << s.section
       << " | `" << value << "` | " << (s.def.empty() ? "" : "`" + s.def + "`") << " | " << s.help
       << (s.repeatable ? " (repeatable)" : "") << " |\n";
  }
}

// Scene-file errors fail the job (1); flag errors are a bad command line (2). Messages about a
// scene start with its path (see make_job), those about flags with "--" or "missing".
int input_error(const std::string& message, const std::string& scene) {
  print_error(message);
  const bool from_scene = !scene.empty() && message.rfind(scene + ": ", 0) == 0;
  return from_scene ? kExitFailure : kExitUsage;
}

int run_drape(const std::vector<std::string>& args_in) {
  std::vector<std::string> args = args_in;
  if (std::find(args.begin(), args.end(), "--help") != args.end() ||
      std::find(args.begin(), args.end(), "-h") != args.end()) {
    drape_help(std::cout);
    return kExitOk;
  }
  if (std::find(args.begin(), args.end(), "--scene-keys") != args.end()) {
    scene_keys_markdown(std::cout);
    return kExitOk;
  }
  bool dump = false, quiet = false;
  std::string outcome_path;
  for (std::size_t i = 0; i < args.size();) {
    if (args[i] == "--outcome" && i + 1 < args.size()) {
      outcome_path = args[i + 1];
      args.erase(args.begin() + static_cast<long>(i), args.begin() + static_cast<long>(i) + 2);
    } else if (args[i].rfind("--outcome=", 0) == 0) {
      outcome_path = args[i].substr(10);
      args.erase(args.begin() + static_cast<long>(i));
    } else if (args[i] == "--outcome") {
      print_error("--outcome needs a value (FILE)");
      return kExitUsage;
    } else {
      ++i;
    }
  }
  args.erase(std::remove_if(args.begin(), args.end(),
                            [&](const std::string& a) {
                              if (a == "--dump-scene") return dump = true;
                              if (a == "--quiet") return quiet = true;
                              return false;
                            }),
             args.end());
  // Every exit after this point leaves an outcome file when asked for one.
  auto finish = [&](int code, const JobOutcome& out) {
    if (!outcome_path.empty()) {
      if (auto st = exporters::write_file_atomic(outcome_path, outcome_to_json(out, code)); !st) {
        print_error(exporters::describe(st.error()));
        return code == kExitOk ? kExitFailure : code;
      }
    }
    return code;
  };
  auto fail = [&](int code, const std::string& message) {
    JobOutcome out;
    out.status = code == kExitInterrupted ? "cancelled" : "error";
    out.error = message;
    return finish(code, out);
  };
  RawOptions raw;
  std::string scene;
  if (!args.empty() && args.front().rfind("-", 0) != 0) {
    scene = args.front();
    auto loaded = raw_from_scene(scene);
    if (!loaded)
      return fail(input_error(exporters::describe(loaded.error()), scene),
                  exporters::describe(loaded.error()));
    raw = std::move(loaded).value();
    args.erase(args.begin());
  }
  auto flags = raw_from_args(args);
  if (!flags) {
    print_error(exporters::describe(flags.error()));
    return fail(kExitUsage, exporters::describe(flags.error()));
  }
  raw = raw.origin.empty() ? std::move(flags).value() : merge(raw, *flags);
  auto job = make_job(raw, !dump);
  if (!job)
    return fail(input_error(exporters::describe(job.error()), scene),
                exporters::describe(job.error()));
  if (dump) {
    std::cout << dump_scene(*job);
    return kExitOk;
  }
  catch_interrupts();
  auto out = run_job(*job, &g_interrupted, !quiet);
  // A job that finished wrote its outputs whole: it counts even if a signal came late.
  if (!out && g_interrupted.load()) {
    print_error("interrupted: no outputs written for this drape");
    return fail(kExitInterrupted, "interrupted");
  }
  if (!out) {
    print_error(exporters::describe(out.error()));
    return fail(kExitFailure, exporters::describe(out.error()));
  }
  const auto& m = out->metrics;
  std::cout << "plyfit: " << out->status << ": " << m.nodes.mapped << " nodes mapped ("
            << m.nodes.auxiliary << " auxiliary base-path points), " << m.nodes.outside
            << " outside, " << m.nodes.off_ply << " off the ply, " << m.nodes.shear_limit
            << " at the shear limit, " << m.nodes.failed << " failed, " << m.nodes.overlap
            << " overlapping, " << m.nodes.conflict << " in conflict"
            << (m.nodes.path_end ? ", base path ended early" : "") << "; max shear "
            << out->shear_max_deg << " deg; " << static_cast<long>(out->total_ms) << " ms -> "
            << job->outdir << "\n";
  if (!quiet)
    for (const auto* list : {&out->mold_warnings, &out->warnings})
      for (const auto& w : *list) std::cerr << "plyfit: warning: " << w << "\n";
  return finish(kExitOk, *out);
}

const CommandRegistrar kRegister{
    {"drape", "drape a ply on a mold face and write the outputs", 20, run_drape}};

}  // namespace
}  // namespace plyfit::cli
