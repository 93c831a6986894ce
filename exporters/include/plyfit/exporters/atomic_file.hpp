#pragma once
/// \file Output files are written whole or not at all: a temporary file in the same folder,
/// renamed over the target once everything is written and flushed. Files are read whole.

#include <plyfit/kernel/result.hpp>

#include <fstream>
#include <optional>
#include <string>

namespace plyfit::exporters {

/// A file being written. Write to stream(), then commit(); if commit() is never reached
/// (an error, an exception, a cancelled job) the destructor removes the temporary file and
/// the target is untouched.
class AtomicFile {
 public:
  /// Opens a temporary file next to `path`. Check ok() (or the Status of commit()).
  explicit AtomicFile(std::string path, bool binary = false);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// False if the temporary file could not be created.
  bool ok() const { return static_cast<bool>(out_); }
  std::ofstream& stream() { return out_; }
  /// Temporary file name (for writers that need a path, e.g. OpenCASCADE's STEP writer).
  const std::string& temp_path() const { return temp_; }
  /// Flushes, closes and renames over the target. The error names the file.
  Status commit();
  /// Closes and removes the temporary file; the target is untouched.
  void discard();

 private:
  std::string path_, temp_;
  std::ofstream out_;
  bool done_ = false;
};

/// Writes `content` to `path` atomically.
Status write_file_atomic(const std::string& path, const std::string& content);

/// The whole content of the file `path` (bytes as they are), or nothing when it cannot be
/// opened or read.
std::optional<std::string> read_file(const std::string& path);

}  // namespace plyfit::exporters
