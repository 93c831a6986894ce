// plyfit drape [SCENE.ini] [flags]: one drape, outputs into -o DIR.

#include "commands/commands.hpp"
#include "job/drape_job.hpp"
#include "job/outcome.hpp"
#include "job/scene_file.hpp"
#include "report/drape_report.hpp"

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/builtin_molds.hpp>

#include <algorithm>
#include <atomic>
#include <iostream>

namespace plyfit::cli {
namespace {

// Set by SIGINT/SIGTERM: the drape stops and no output is written.
std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int) {
  g_interrupted.store(true);
}

// The drape job's keys and the command's own options.
const OptionTable& drape_command_options() {
  static const OptionTable table = [] {
    OptionTable t = drape_options();
    t.push_back({"dump-scene", "", "", "print the effective scene as INI and exit"});
    t.push_back(quiet_option());
    t.push_back({"outcome", "FILE", "", "also write the outcome as JSON (used by plyfit batch)"});
    t.push_back({"scene-keys", "", "", "print the scene keys as a Markdown table and exit"});
    t.push_back(help_option());
    return t;
  }();
  return table;
}

const CommandHelp kDrapeHelp = {
    "plyfit drape [SCENE.ini] [options]",
    "Drapes a woven ply on one face of a mold and writes the outputs into -o DIR.\n"
    "A scene file holds the same keys as the options (without dashes); options given\n"
    "on the command line override it.\n",
    [](std::ostream& os) {
      os << "\nbuilt-in molds (--mold builtin:NAME[:key=value,...]):\n";
      for (const auto& b : builtin_molds()) {
        os << "  " << b.name << ":";
        for (const auto& p : b.params) os << " " << p.key << "=" << p.value;
        os << "\n      " << b.placement << "\n";
      }
    }};

// The outcome file (--outcome), written at every exit once the flags are read.
struct OutcomeFile {
  std::string path;

  int write(int code, const JobOutcome& out) const {
    if (path.empty()) return code;
    if (auto st = exporters::write_file_atomic(path, outcome_to_json(out, code)); !st) {
      print_error(st.error());
      return code == kExitOk ? kExitFailure : code;
    }
    return code;
  }
  // Prints the error and writes it as the outcome.
  int fail(int code, const Error& e, const exporters::InputNamer& name_input) const {
    print_error(e, name_input);
    JobOutcome out;
    out.status = code == kExitInterrupted ? "cancelled" : "error";
    out.error = exporters::describe(e, name_input);
    out.error_code = to_string(e.code);
    return write(code, out);
  }
};

// An input error fails the job (1) when the value it blames came from the scene file, and is a
// bad command line (2) when it came from a flag.
int input_exit_code(const Error& e, const RawOptions& raw) {
  return origin_of(raw, e.input) == kCommandLine ? kExitUsage : kExitFailure;
}

int drape_job(const DrapeJob& job, bool quiet, const OutcomeFile& outcome) {
  const CatchInterrupts interrupts(on_interrupt);
  auto out = run_job(job, &g_interrupted, !quiet);
  // A job that finished wrote its outputs whole: it counts even if a signal came late.
  if (!out && g_interrupted.load())
    return outcome.fail(kExitInterrupted, Error{ErrorCode::kInterrupted}, {});
  if (!out) return outcome.fail(kExitFailure, out.error(), job.name_input);
  std::cout << drape_summary(*out, job.outdir);
  if (!quiet) {
    for (const auto* ws : {&out->mold_warnings, &out->warnings})
      for (const auto& w : *ws) std::cerr << "plyfit: warning: " << exporters::message(w) << "\n";
  }
  return outcome.write(kExitOk, *out);
}

int run_drape(const std::vector<std::string>& args_in) {
  if (wants_help(args_in)) {
    print_help(std::cout, kDrapeHelp, drape_command_options());
    return kExitOk;
  }
  if (std::find(args_in.begin(), args_in.end(), "--scene-keys") != args_in.end()) {
    scene_keys_markdown(std::cout);
    return kExitOk;
  }
  std::vector<std::string> args = args_in;
  std::string scene;
  if (!args.empty() && args.front().rfind("-", 0) != 0) {
    scene = args.front();
    args.erase(args.begin());
  }
  const OptionTable& table = drape_command_options();
  auto flags = parse_command_line(args, table, {}, "a scene file must come first");
  if (!flags) {
    print_error(flags.error(), flag_namer(table));
    return kExitUsage;
  }
  const Options command(*flags, table);
  const OutcomeFile outcome{command.text("outcome").value_or("")};
  RawOptions raw = *flags;
  if (!scene.empty()) {
    auto loaded = raw_from_scene(scene);
    if (!loaded) return outcome.fail(kExitFailure, loaded.error(), scene_namer(scene));
    raw = merge(*loaded, raw);
  }
  const bool dump = command.given("dump-scene");
  auto job = make_job(raw, !dump);
  if (!job)
    return outcome.fail(input_exit_code(job.error(), raw), job.error(),
                        input_namer(raw, drape_options()));
  if (dump) {
    std::cout << dump_scene(*job);
    return kExitOk;
  }
  return drape_job(*job, command.given("quiet"), outcome);
}

const CommandRegistrar kRegister{
    {"drape", "drape a ply on a mold face and write the outputs", 20, run_drape}};

}  // namespace
}  // namespace plyfit::cli
