// plyfit batch end to end: good and broken scenes, a crashing child, Ctrl-C (SIGINT) in the
// middle, sharding, the summary files and the exit codes.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

extern char** environ;

using namespace plyfit::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// A quick scene (Table 1 case (a) on a mold file or a built-in).
std::string quick_scene(const std::string& mold) {
  return "mold = " + mold +
         "\nspacing = 1\nstart2d = 0,0\nbase2d = 1,0\nsweep2d = 0,1\nstart3d = 0,0,20\n"
         "base-normal = 0,1,0\nsweep3d = 0,1,0\n";
}

/// A scene that drapes for about a minute (4 million nodes on a plane): long enough to be
/// interrupted or killed while it runs.
const std::string kSlowScene =
    "mold = builtin:plane:W=100,H=100\nspacing = 0.05\nstart2d = 0,0\nbase2d = 1,0\n"
    "sweep2d = 0,1\nsweep2d = 0,-1\nstart3d = 50,50,0\nbase-normal = 0,1,0\nsweep3d = 0,1,0\n"
    "sweep3d = 0,-1,0\n";

/// How long a test waits for a batch to reach a state or to end.
constexpr double kWaitSeconds = 60.0;

/// Files and folders under `root`, relative, sorted.
std::set<std::string> tree(const fs::path& root) {
  std::set<std::string> s;
  for (const auto& e : fs::recursive_directory_iterator(root))
    s.insert(fs::relative(e.path(), root).string());
  return s;
}

/// The pids whose parent is `parent`.
std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> v;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = slurp("/proc/" + name + "/stat");
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream ss(stat.substr(close + 2));
    char state = 0;
    long ppid = 0;
    ss >> state >> ppid;
    if (ppid == parent && state != 'Z') v.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return v;
}

/// A batch started in the background (stdout and stderr to files).
struct Background {
  pid_t pid = -1;
  Background(const std::vector<std::string>& args, const Scratch& tmp) {
    std::vector<std::string> a = {PLYFIT_BIN};
    a.insert(a.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& s : a) argv.push_back(s.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, tmp.file("bg.stdout").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, tmp.file("bg.stderr").c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    REQUIRE(posix_spawn(&pid, PLYFIT_BIN, &fa, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&fa);
  }
  /// Waits for the exit (killing the batch after kWaitSeconds); the exit code, or 128 + signal.
  int wait() {
    const auto t0 = std::chrono::steady_clock::now();
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(kWaitSeconds)) {
        for (pid_t c : children_of(pid)) ::kill(c, SIGKILL);
        ::kill(pid, SIGKILL);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  ~Background() {
    if (pid > 0) {
      for (pid_t c : children_of(pid)) ::kill(c, SIGKILL);
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

/// Waits until `done()` holds (false after kWaitSeconds).
template <typename F>
bool wait_until(F done) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!done()) {
    if (std::chrono::steady_clock::now() - t0 > std::chrono::duration<double>(kWaitSeconds))
      return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

/// What the output root must hold: the summary files, and for each scene with an output
/// folder exactly the files its summary entry lists (report.json among them).
std::set<std::string> expected_tree(const json& summary, const std::set<std::string>& extra) {
  std::set<std::string> t = extra;
  for (const auto& sc : summary["scenes"]) {
    if (sc["outdir"].is_null()) continue;
    const std::string name = sc["name"];
    t.insert(name);
    CHECK(std::find(sc["files"].begin(), sc["files"].end(), "report.json") != sc["files"].end());
    for (const auto& f : sc["files"]) t.insert(name + "/" + f.get<std::string>());
  }
  return t;
}

/// The scenes of the tests that stop a batch midway, written to the scratch folder: a quick
/// scene, the slow one, and a second quick one named `last` (scenes are named by their files).
struct StopScenes {
  std::string quick, slow, last;
};
StopScenes stop_scenes(const Scratch& tmp, const std::string& last) {
  const StopScenes s{tmp.file("quick.ini"), tmp.file("slow.ini"), tmp.file(last + ".ini")};
  spit(s.quick, quick_scene("builtin:sphere-octant"));
  spit(s.slow, kSlowScene);
  spit(s.last, quick_scene("builtin:sphere-octant"));
  return s;
}

json scene_entry(const json& summary, const std::string& name) {
  for (const auto& s : summary["scenes"])
    if (s["name"] == name) return s;
  FAIL("no scene " << name << " in the summary");
  return {};
}

}  // namespace

TEST_CASE("cli: batch runs the good scenes, reports the broken ones and exits 1") {
  Scratch tmp("batch_e2e");
  fs::create_directories(tmp.path / "a");
  fs::create_directories(tmp.path / "b");
  const std::string sample_step =
      std::string(PLYFIT_SOURCE_DIR) + "/samples/molds/sphere-octant.step";
  spit(tmp.file("a/good.ini"), quick_scene(sample_step));
  spit(tmp.file("b/good.ini"), quick_scene("builtin:sphere-octant"));  // same name: good-2
  // A scene's own output key is overridden by the batch's folder.
  spit(tmp.file("builtin.ini"), quick_scene("builtin:sphere-octant") + "output = own-output\n");
  spit(tmp.file("malformed.ini"), quick_scene("builtin:sphere-octant") + "lock-angle = steep\n");
  // A corrupt STEP file: the first half of a real one.
  const std::string step = slurp(sample_step);
  spit(tmp.file("corrupt.step"), step.substr(0, step.size() / 2));
  spit(tmp.file("corrupt.ini"), quick_scene("corrupt.step"));
  spit(tmp.file("nomold.ini"), quick_scene("no-such-mold.igs"));
  const std::string out = tmp.file("out");
  const CliRun r =
      plyfit_run("batch '" + tmp.file("a/good.ini") + "' '" + tmp.file("missing.ini") + "' '" +
                     tmp.file("malformed.ini") + "' '" + tmp.file("b/good.ini") + "' '" +
                     tmp.file("corrupt.ini") + "' '" + tmp.file("nomold.ini") + "' '" +
                     tmp.file("builtin.ini") + "' -j 3 -o '" + out + "'",
                 tmp);
  INFO(r.out << r.err);
  CHECK(r.code == 1);
  CHECK(r.err.empty());  // no progress line when stderr is not a terminal
  // The table: a header, one line per scene, the count line.
  CHECK(lines(r.out) == 1 + 7 + 1);
  CHECK(r.out.find("7 scenes: 3 ok, 0 partial, 4 error, 0 crashed, 0 cancelled, 0 not run") !=
        std::string::npos);
  // Only the good scenes have folders, each whole; nothing else is left in the output root.
  const json s = json::parse(slurp(out + "/summary.json"));
  CHECK(tree(out) == expected_tree(s, {"summary.json", "summary.csv"}));
  for (const char* name : {"good", "good-2", "builtin"}) CHECK(fs::exists(out + "/" + name));
  CHECK(json::parse(slurp(out + "/good/report.json"))["nodes"]["mapped"] == 716);
  CHECK_FALSE(fs::exists(tmp.file("own-output")));
  CHECK(s["counts"]["total"] == 7);
  CHECK(s["counts"]["ok"] == 3);
  CHECK(s["counts"]["error"] == 4);
  CHECK(s["interrupted"] == false);
  REQUIRE(s["scenes"].size() == 7);
  for (std::size_t i = 0; i < 7; ++i) CHECK(s["scenes"][i]["index"] == i);  // the given order
  CHECK(scene_entry(s, "good")["status"] == "ok");
  CHECK(scene_entry(s, "good")["mapped"] == 716);
  CHECK(scene_entry(s, "good")["outdir"] == out + "/good");
  CHECK(scene_entry(s, "good-2")["status"] == "ok");
  // Each error with its code; its text names the file and the key.
  CHECK(scene_entry(s, "missing")["error_code"] == "scene_cannot_open");
  CHECK(scene_entry(s, "missing")["error"].get<std::string>().rfind(tmp.file("missing.ini") + ": ",
                                                                    0) == 0);
  CHECK(scene_entry(s, "malformed")["error_code"] == "not_a_number");
  CHECK(scene_entry(s, "malformed")["error"].get<std::string>().rfind(
            tmp.file("malformed.ini") + ": key 'lock-angle': ", 0) == 0);
  CHECK(scene_entry(s, "malformed")["exit_code"] == 1);
  CHECK(scene_entry(s, "good")["error_code"] == "");
  CHECK(scene_entry(s, "corrupt")["status"] == "error");
  CHECK_FALSE(scene_entry(s, "corrupt")["error_code"].get<std::string>().empty());
  CHECK(scene_entry(s, "corrupt")["error"].get<std::string>().find("corrupt.step") !=
        std::string::npos);
  CHECK(scene_entry(s, "nomold")["error"].get<std::string>().find("no-such-mold.igs") !=
        std::string::npos);
  CHECK(scene_entry(s, "nomold")["outdir"].is_null());
  // The CSV holds the same rows.
  const std::string csv = slurp(out + "/summary.csv");
  CHECK(lines(csv) == 8);
  CHECK(
      csv.rfind("index,name,scene,status,exit_code,mapped,shear_max_deg,time_s,outdir,files,error,"
                "error_code\n",
                0) == 0);
  CHECK(csv.find("\n1,missing,") != std::string::npos);
  CHECK(csv.find(",scene_cannot_open\n") != std::string::npos);
  // The table gives each error with its code.
  CHECK(r.out.find("[scene_cannot_open]") != std::string::npos);
  CHECK(csv.find("\n3,good-2,") != std::string::npos);
  // Running the same batch again replaces the previous outputs; all good now: exit 0.
  const CliRun again = plyfit_run(
      "batch '" + tmp.file("a/good.ini") + "' '" + tmp.file("builtin.ini") + "' -o '" + out + "'",
      tmp);
  CHECK(again.code == 0);
  CHECK(json::parse(slurp(out + "/summary.json"))["counts"]["ok"] == 2);
  // A folder holding other files is never replaced.
  spit(out + "/good/notes.txt", "mine");
  const CliRun keep = plyfit_run("batch '" + tmp.file("a/good.ini") + "' -o '" + out + "'", tmp);
  CHECK(keep.code == 1);
  CHECK(slurp(out + "/good/notes.txt") == "mine");
  const json kept = scene_entry(json::parse(slurp(out + "/summary.json")), "good");
  CHECK(kept["error_code"] == "folder_holds_other_files");
  CHECK(kept["error"].get<std::string>().rfind(out + "/good: ", 0) == 0);
}

TEST_CASE("cli: batch command-line errors exit 2") {
  Scratch tmp("batch_usage");
  CliRun r = plyfit_run("batch", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "missing_argument");
  r = plyfit_run("batch x.ini -j 0", tmp);
  CHECK(r.code == 2);
  CHECK(error_code(r) == "not_an_integer");
  CHECK(r.err.rfind("plyfit: error: --jobs: ", 0) == 0);
  for (const char* shard : {"2/2", "1", "a/b", "-1/2", "1/0", "1/2/3"}) {
    INFO(shard);
    r = plyfit_run(std::string("batch x.ini --shard ") + shard, tmp);
    CHECK(r.code == 2);
    CHECK(error_code(r) == "bad_shard");
    CHECK(r.err.rfind("plyfit: error: --shard: ", 0) == 0);
  }
}

TEST_CASE("cli: batch --shard K/N runs the scenes whose index mod N is K") {
  Scratch tmp("batch_shard");
  std::string args;
  for (const char* name : {"s0.ini", "s1.ini", "s2.ini", "s3.ini", "s4.ini"}) {
    const std::string path = tmp.file(name);
    spit(path, quick_scene("builtin:sphere-octant"));
    args += " '";
    args += path;
    args += "'";
  }
  const std::string out = tmp.file("out");
  const CliRun r = plyfit_run("batch" + args + " --shard 1/2 -o '" + out + "'", tmp);
  INFO(r.out << r.err);
  CHECK(r.code == 0);
  const json s = json::parse(slurp(out + "/summary-shard-1-of-2.json"));
  CHECK(tree(out) == expected_tree(s, {"summary-shard-1-of-2.json", "summary-shard-1-of-2.csv"}));
  CHECK(fs::exists(out + "/s1"));
  CHECK(fs::exists(out + "/s3"));
  CHECK(s["shard"] == "1/2");
  REQUIRE(s["scenes"].size() == 2);
  CHECK(s["scenes"][0]["index"] == 1);
  CHECK(s["scenes"][1]["index"] == 3);
}

TEST_CASE("cli: a crashing scene does not stop the others") {
  Scratch tmp("batch_crash");
  const StopScenes sc = stop_scenes(tmp, "after");
  const std::string out = tmp.file("out");
  Background b({"batch", sc.slow, sc.quick, sc.last, "-j", "2", "-o", out}, tmp);
  // Once both quick scenes are done, the slow one is still running: crash it.
  REQUIRE(wait_until([&] { return fs::exists(out + "/quick") && fs::exists(out + "/after"); }));
  const auto kids = children_of(b.pid);
  REQUIRE(kids.size() == 1);
  ::kill(kids[0], SIGSEGV);
  CHECK(b.wait() == 1);
  const json s = json::parse(slurp(out + "/summary.json"));
  CHECK(scene_entry(s, "slow")["status"] == "crashed");
  CHECK(scene_entry(s, "slow")["signal"] == SIGSEGV);
  CHECK(scene_entry(s, "slow")["error_code"] == "drape_crashed");
  CHECK(scene_entry(s, "slow")["error"].get<std::string>().find(std::to_string(SIGSEGV)) !=
        std::string::npos);
  CHECK(scene_entry(s, "quick")["status"] == "ok");
  CHECK(scene_entry(s, "after")["status"] == "ok");
  CHECK(tree(out) == expected_tree(s, {"summary.json", "summary.csv"}));
  CHECK(fs::exists(out + "/quick"));
  CHECK(fs::exists(out + "/after"));
}

TEST_CASE("cli: Ctrl-C stops a batch cleanly") {
  Scratch tmp("batch_sigint");
  const StopScenes sc = stop_scenes(tmp, "later");
  const std::string out = tmp.file("out");
  // -j 2: quick and slow start; when quick is done, the second slow one starts; later waits.
  Background b({"batch", sc.quick, sc.slow, sc.slow, sc.last, "-j", "2", "-o", out}, tmp);
  REQUIRE(wait_until([&] { return fs::exists(out + "/quick") && children_of(b.pid).size() == 2; }));
  const auto kids = children_of(b.pid);
  ::kill(b.pid, SIGINT);
  CHECK(b.wait() == 130);
  // The finished scene keeps its outputs; the running ones left nothing (no final files, no
  // temporary files, no staging folder); the summary says what happened.
  const json s = json::parse(slurp(out + "/summary.json"));
  CHECK(tree(out) == expected_tree(s, {"summary.json", "summary.csv"}));
  CHECK(fs::exists(out + "/quick"));
  CHECK(s["interrupted"] == true);
  CHECK(scene_entry(s, "quick")["status"] == "ok");
  CHECK(scene_entry(s, "slow")["status"] == "cancelled");
  CHECK(scene_entry(s, "slow-2")["status"] == "cancelled");
  CHECK(scene_entry(s, "slow")["error_code"] == "interrupted");
  CHECK(scene_entry(s, "later")["status"] == "not run");
  CHECK(s["counts"]["cancelled"] == 2);
  CHECK(s["counts"]["not_run"] == 1);
  const std::string table = slurp(tmp.file("bg.stdout"));
  CHECK(table.find("2 cancelled, 1 not run") != std::string::npos);
  // The batch waited for its children: none is left running.
  for (pid_t k : kids) CHECK(::kill(k, 0) == -1);
}

TEST_CASE("cli: batch shows a progress line on a terminal only") {
  Scratch tmp("batch_tty");
  spit(tmp.file("a.ini"), quick_scene("builtin:sphere-octant"));
  // script(1) gives the batch a terminal.
  if (std::system("command -v script > /dev/null 2>&1") != 0) {
    WARN("script(1) not installed: terminal progress not tested");
    return;
  }
  const std::string cmd = "script -qec \"'" + std::string(PLYFIT_BIN) + "' batch '" +
                          tmp.file("a.ini") + "' -o '" + tmp.file("out") + "'\" /dev/null > '" +
                          tmp.file("tty.txt") + "' < /dev/null";
  REQUIRE(std::system(cmd.c_str()) == 0);
  const std::string text = slurp(tmp.file("tty.txt"));
  CHECK(text.find("plyfit batch: 0/1 done, 0 failed") != std::string::npos);
  // Without a terminal: nothing on stderr.
  const CliRun r =
      plyfit_run("batch '" + tmp.file("a.ini") + "' -o '" + tmp.file("out2") + "'", tmp);
  CHECK(r.code == 0);
  CHECK(r.err.empty());
}
