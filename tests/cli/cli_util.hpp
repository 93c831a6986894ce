#pragma once
// Helpers for tests that run the built plyfit binary (PLYFIT_BIN): scratch folders, runs
// under a time limit, file reading and writing.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace plyfit::test {

/// A run of plyfit must end within this many seconds (every sample drape takes well under
/// one; a hang must fail the test, not block CI).
constexpr int kRunLimitSeconds = 120;

/// A scratch folder removed at the end of the test.
struct Scratch {
  std::filesystem::path path;
  explicit Scratch(const std::string& tag) {
    path = std::filesystem::temp_directory_path() /
           ("plyfit_test_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void spit(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// The paper's Table 1 case (a) on the built-in octant, as plyfit drape flags.
inline const std::string kOctantFlags =
    "--mold builtin:sphere-octant --spacing 1 --start2d 0,0 --base2d 1,0 --sweep2d 0,1 "
    "--start3d 0,0,20 --base-normal 0,1,0 --sweep3d 0,1,0";

/// Exit code and output of a plyfit run.
struct CliRun {
  int code = -1;
  std::string out, err;
};

/// Runs `plyfit ARGS` (a shell-quoted argument string) in `cwd` under a time limit of
/// `limit_s` seconds (coreutils timeout: exit code 124 when it had to stop it; 128 + N when a
/// signal N killed it), with the environment variables `env` ("NAME=value ...") set.
inline CliRun plyfit_run(const std::string& args, const Scratch& scratch,
                         const std::string& cwd = "", const std::string& env = "",
                         int limit_s = kRunLimitSeconds) {
  const std::string out = scratch.file("run.stdout"), err = scratch.file("run.stderr");
  const std::string cmd = (cwd.empty() ? "" : "cd '" + cwd + "' && ") +
                          (env.empty() ? "" : "env " + env + " ") + "timeout -k 5 " +
                          std::to_string(limit_s) + " '" + PLYFIT_BIN + "' " + args + " > '" + out +
                          "' 2> '" + err + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// Number of lines in `s`.
inline int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

/// The code of the one error line a run printed, "plyfit: error: TEXT [code]" (docs/errors.md);
/// empty when stderr is not one such line.
inline std::string error_code(const CliRun& r) {
  const std::string& e = r.err;
  if (lines(e) != 1 || e.rfind("plyfit: error: ", 0) != 0 || e.size() < 4) return {};
  const auto open = e.rfind(" [");
  if (open == std::string::npos || e.compare(e.size() - 2, 2, "]\n") != 0) return {};
  return e.substr(open + 2, e.size() - 2 - open - 2);
}

}  // namespace plyfit::test
