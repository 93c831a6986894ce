#pragma once
// Expected failures of the importers, as checks run on any source file: on plyfit's own sample
// molds (errors_test.cpp) and on the CAD corpus (errors_corpus_test.cpp). Every failure must
// come back as a one-line Error naming the file, never a crash or a hang; corrupted copies are
// also run through the plyfit binary under a time limit.

#include <plyfit/exporters/messages.hpp>
#include <plyfit/importers/importers.hpp>

#include <catch2/catch.hpp>

#include "occt/occt_reference.hpp"

#include <algorithm>
#include <string>
#include <vector>
#include "surface/face.hpp"

namespace plyfit::test {

/// The error is one line and names the file.
inline void check_error(const Error& e, const std::string& path) {
  const std::string text = exporters::describe(e);
  INFO(text);
  CHECK(text.find('\n') == std::string::npos);
  CHECK(text.find(path) != std::string::npos);
}

/// Opening a corrupted file gives an error naming it, or (when the damage is harmless) a mold
/// whose faces all convert or fail with such an error. True when the file was rejected.
inline bool open_corrupted(const std::string& path) {
  auto file = importers::open_mold(path);
  if (!file) {
    check_error(file.error(), path);
    return true;
  }
  for (int i = 0; i < static_cast<int>((*file)->mold().faces.size()); ++i) {
    auto d = (*file)->convert_face(i);
    if (!d) check_error(d.error(), path);
  }
  return false;
}

/// The binary on a bad file: exit code 1, one line on stderr naming the file, not a crash
/// (128 + signal) nor a hang (124).
inline void binary_rejects(const std::string& path, const TempDir& dir) {
  const Run r = run_plyfit("info '" + path + "'", dir);
  INFO(path << ": exit " << r.code << ", stderr: " << r.err);
  CHECK(r.code != 124);
  CHECK(r.code < 128);
  if (r.code == 0) return;  // harmless damage: read fine
  CHECK(r.code == 1);
  CHECK(r.err.rfind("plyfit: error: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.find(path) != std::string::npos);
}

/// Number of copies corrupted_copies() makes that cannot be read: the five truncations, the
/// cut-out middle and the garbage file.
constexpr int kUnreadableCopies = 7;

/// Truncated (5), middle cut out (1), bytes flipped (6) and garbage (1) copies of `source`.
inline std::vector<std::string> corrupted_copies(const std::string& source, const std::string& ext,
                                                 const TempDir& dir, uint64_t seed) {
  const std::string bytes = read_bytes(source);
  REQUIRE(bytes.size() > 1000);
  std::vector<std::string> out;
  int n = 0;
  auto add = [&](const std::string& content) {
    out.push_back(
        dir.file("corrupt_" + std::to_string(seed) + "_" + std::to_string(n++) + "." + ext));
    write_bytes(out.back(), content);
  };
  for (double cut : {0.02, 0.3, 0.5, 0.9, 0.999})
    add(bytes.substr(0, static_cast<size_t>(cut * bytes.size())));
  // Middle cut out, header and end kept: the parser meets dangling references.
  add(bytes.substr(0, bytes.size() * 4 / 10) + bytes.substr(bytes.size() * 9 / 10));
  Rng rng(seed);
  for (int k = 0; k < 6; ++k) {
    std::string b = bytes;
    const int flips = k < 3 ? 20 : 400;
    for (int f = 0; f < flips; ++f) {
      const size_t at = static_cast<size_t>(
          rng.integer(static_cast<int>(b.size() / 20), static_cast<int>(b.size()) - 200));
      b[at] = static_cast<char>(k % 2 ? rng.integer(0, 255) : rng.integer('#', 'z'));
    }
    add(b);
  }
  std::string garbage(20000, '\0');
  for (auto& c : garbage) c = static_cast<char>(rng.integer(0, 255));
  add(garbage);
  return out;
}

/// The binary rejects or reads every corrupted copy of a STEP and an IGES file (copies seeded
/// 31 and 32) without a crash or a hang.
inline void binary_survives_corrupted(const std::string& step, const std::string& iges,
                                      const TempDir& dir) {
  for (const auto& p : corrupted_copies(step, "stp", dir, 31)) binary_rejects(p, dir);
  for (const auto& p : corrupted_copies(iges, "igs", dir, 32)) binary_rejects(p, dir);
}

/// An IGES file renamed .step and a STEP file renamed .igs are rejected clearly, by the library
/// and the binary.
inline void check_renamed(const std::string& step, const std::string& iges, const TempDir& dir) {
  write_bytes(dir.file("really_iges.step"), read_bytes(iges));
  auto r = importers::open_mold(dir.file("really_iges.step"));
  REQUIRE_FALSE(r.ok());
  check_error(r.error(), dir.file("really_iges.step"));
  CHECK(r.error().code == ErrorCode::kFileWrongFormat);
  CHECK(r.error().values == std::vector<MessageValue>{"STEP", "IGES"});
  write_bytes(dir.file("really_step.igs"), read_bytes(step));
  r = importers::open_mold(dir.file("really_step.igs"));
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().code == ErrorCode::kFileWrongFormat);
  CHECK(r.error().values == std::vector<MessageValue>{"IGES", "STEP"});
  binary_rejects(dir.file("really_iges.step"), dir);
}

/// Truncated and corrupted copies of a STEP and an IGES file give errors (truncated ones say
/// so), never crashes or hangs.
inline void check_corrupted(const std::string& step, const std::string& iges, const TempDir& dir,
                            uint64_t seed) {
  const auto s = corrupted_copies(step, "stp", dir, seed);
  const auto i = corrupted_copies(iges, "igs", dir, seed + 1);
  int rejected = 0;
  for (const auto* set : {&s, &i}) {
    for (const auto& path : *set) {
      INFO(path);
      rejected += open_corrupted(path);
    }
  }
  CHECK(rejected >= 2 * kUnreadableCopies);
  for (const auto* set : {&s, &i}) {
    auto t = importers::open_mold((*set)[2]);
    REQUIRE_FALSE(t.ok());
    CHECK(t.error().code == ErrorCode::kFileTruncated);
  }
}

/// A STEP and an IGES file, and the seed of their corrupted copies (the IGES file's is seed + 1).
struct FilePair {
  std::string step;
  std::string iges;
  uint64_t seed;
};

/// check_renamed() and check_corrupted() on each pair of files.
inline void check_damaged_copies(const std::vector<FilePair>& pairs, const TempDir& dir) {
  for (const FilePair& p : pairs) {
    INFO(p.step << ", " << p.iges);
    check_renamed(p.step, p.iges, dir);
    check_corrupted(p.step, p.iges, dir, p.seed);
  }
}

/// Face indices outside 0..faces-1 are errors naming the file, and so is a time limit that is
/// already past.
inline void check_bad_index_and_time_limit(const std::string& path, int faces) {
  auto file = importers::open_mold(path);
  REQUIRE(file.ok());
  REQUIRE((*file)->face_count() == faces);
  for (int bad : {-1, faces, 1000}) {
    auto d = (*file)->convert_face(bad);
    REQUIRE_FALSE(d.ok());
    check_error(d.error(), path);
    CHECK(d.error().code == ErrorCode::kFaceIndexRange);
  }
  auto lf = importers::load_face(path, faces + 5);
  REQUIRE_FALSE(lf.ok());
  check_error(lf.error(), path);

  importers::ImportOptions o;
  o.time_limit_s = 0.0;  // already past: the transfer is stopped at its first check
  auto slow = importers::open_mold(path, o);
  REQUIRE_FALSE(slow.ok());
  check_error(slow.error(), path);
  CHECK(slow.error().code == ErrorCode::kReadTimeLimit);
}

}  // namespace plyfit::test
