#pragma once
// Subcommands of the plyfit executable. Each lives in its own file and registers itself
// with a static CommandRegistrar; main() dispatches on the first argument.

#include <functional>
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

/// Prints "plyfit: error: <message>" on one line to stderr.
void print_error(const std::string& message);

}  // namespace plyfit::cli
