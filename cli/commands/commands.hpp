#pragma once
// Subcommands of the plyfit executable. Each lives in its own file and registers itself
// with a static CommandRegistrar; main() dispatches on the first argument. Each reads its
// arguments with read_arguments() (its option table, its operands, its help: options_command
// does it for all but drape) and reports
// errors with print_error() (one line, the error's code at its end).

#include "commands/command_line.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/kernel/result.hpp>

#include <csignal>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace plyfit::cli {

/// Exit codes shared by every subcommand.
enum ExitCode : int {
  kExitOk = 0,             ///< success (a drape may still be partial)
  kExitFailure = 1,        ///< the job failed: bad file, bad scene, drape error, failed batch job
  kExitUsage = 2,          ///< bad command line: unknown option, malformed value
  kExitInterrupted = 130,  ///< stopped by SIGINT or SIGTERM (128 + SIGINT, as shells report)
};

/// A subcommand: `run` receives the arguments after the subcommand's name.
struct Command {
  std::string name;
  std::string summary;
  int order = 0;  ///< position in the help listing
  std::function<int(const std::vector<std::string>& args)> run;
};

/// Every registered subcommand.
std::vector<Command>& commands();

/// Registers a subcommand at static-initialisation time.
struct CommandRegistrar {
  explicit CommandRegistrar(Command c) { commands().push_back(std::move(c)); }
};

/// An error as one line: its text (exporters::describe, inputs named by `name_input`) and its
/// code in brackets at the end, "TEXT [code_name]", so that users can look the code up
/// (docs/errors.md) and tests can check it.
std::string error_line(const Error& e, const exporters::InputNamer& name_input = {});
/// An error's text and code as error_line writes them (for errors read back from an outcome).
std::string error_line(const std::string& text, const std::string& code);

/// Prints "plyfit: error: " + error_line(e) on one line to stderr.
void print_error(const Error& e, const exporters::InputNamer& name_input = {});
/// print_error(e), then `exit_code`, for `return error_exit(kExitUsage, e);`.
int error_exit(int exit_code, const Error& e, const exporters::InputNamer& name_input = {});

/// What `plyfit COMMAND --help` prints: "usage: USAGE", the description, the options, then
/// `more` (e.g. the built-in molds).
struct CommandHelp {
  std::string usage;        ///< e.g. "plyfit info FILE [--face N] [--json] [--format F]"
  std::string description;  ///< whole lines
  std::function<void(std::ostream&)> more = {};
};
void print_help(std::ostream& os, const CommandHelp& help, const OptionTable& table);

/// A command's operands (bare arguments): the key they are the values of, what they are (for
/// messages, e.g. "scene file"), and whether several are taken (at least one is needed).
struct Operands {
  std::string key, what;
  bool several = false;
};

/// A command's arguments read through its table, or the exit code when there is nothing more
/// to do: 0 after --help, 2 after a bad command line was printed.
struct Arguments {
  RawOptions raw;
  std::optional<int> exit;
};
Arguments read_arguments(const std::vector<std::string>& args, const OptionTable& table,
                         const Operands& operands, const CommandHelp& help);

/// How a subcommand reads its arguments through read_arguments(): its option table, its
/// operands, its help.
struct ArgumentSpec {
  const OptionTable& (*table)();
  Operands operands;
  const CommandHelp& help;
};
/// A subcommand whose `run` gets the options read as `spec` says; after --help or a bad
/// command line it exits with read_arguments()' code instead.
Command options_command(std::string name, std::string summary, int order, ArgumentSpec spec,
                        std::function<int(const Options&)> run);

/// While it lives, SIGINT and SIGTERM go to `handler`; the previous handlers come back after.
class CatchInterrupts {
 public:
  explicit CatchInterrupts(void (*handler)(int));
  ~CatchInterrupts();
  CatchInterrupts(const CatchInterrupts&) = delete;
  CatchInterrupts& operator=(const CatchInterrupts&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace plyfit::cli
