// Child processes for the benchmarks that time plyfit as a user runs it.
#include "bench.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>

extern char** environ;

namespace plyfit::bench {

ProcessRun run_process(const std::vector<std::string>& args, const std::vector<std::string>& env) {
  std::vector<std::string> envs;
  for (char** e = environ; *e; ++e) envs.emplace_back(*e);
  envs.insert(envs.end(), env.begin(), env.end());
  std::vector<char*> argv, envp;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  for (const auto& e : envs) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  ProcessRun r;
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data()) == 0) {
    rusage u{};
    int status = 0;
    if (wait4(pid, &status, 0, &u) == pid) {
      r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      r.max_rss = 1024.0 * static_cast<double>(u.ru_maxrss);
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  posix_spawn_file_actions_destroy(&actions);
  return r;
}

int run_quiet(const std::string& cmd) {
  const int rc = std::system((cmd + " >/dev/null 2>&1").c_str());
  return (rc != -1 && WIFEXITED(rc)) ? WEXITSTATUS(rc) : -1;
}

std::optional<std::string> plyfit_with_command(Table& t, const std::string& command,
                                               bool* available) {
  const std::string bin = plyfit_binary();
  const bool there = run_quiet("'" + bin + "' " + command + " --help") == 0;
  if (available) *available = there;
  if (there) return bin;
  t.caption += format(" Not measured: `%s %s` is not available in this build.", bin.c_str(),
                      command.c_str());
  return std::nullopt;
}

std::filesystem::path scratch_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("plyfit-bench-" + name + "-" + std::to_string(::getpid()));
}

CommandTimes time_command(const std::string& cmd, const std::function<void()>& before) {
  CommandTimes r;
  std::vector<double> cpu;
  r.wall = median_time([&] {
    before();
    const double c0 = children_cpu_seconds();
    r.ok = run_quiet(cmd) == 0 && r.ok;
    cpu.push_back(children_cpu_seconds() - c0);
  });
  r.cpu = median(cpu);
  return r;
}

}  // namespace plyfit::bench
