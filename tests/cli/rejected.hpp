#pragma once
// Command lines plyfit must reject: one error line with its code, naming what is wrong, the
// exit code that says whose fault it is, and no output written.

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace plyfit::test {

/// A command line plyfit must reject: its arguments, the exit code (2: a bad command line; 1:
/// the job failed), the error's code (empty: any code, for errors of modules not yet given a
/// code of their own, whose words `names` then checks) and what the error line names (the
/// option, the file).
struct Rejected {
  std::string args;
  int exit;
  std::string code, names;
};

/// `plyfit COMMAND ARGS -o OUT` for each case: its exit code, its error's code, the line naming
/// what it should, and OUT not written.
inline void check_rejected(const std::string& command, const std::vector<Rejected>& cases,
                           const Scratch& s) {
  const std::string out = s.file("out");
  for (const Rejected& c : cases) {
    const CliRun r = plyfit_run(command + " " + c.args + " -o '" + out + "'", s);
    INFO("plyfit " << command << " " << c.args << "\n-> exit " << r.code << ": " << r.err);
    CHECK(r.code == c.exit);
    CHECK((c.code.empty() ? !error_code(r).empty() : error_code(r) == c.code));
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace plyfit::test
