#include <plyfit/exporters/atomic_file.hpp>

#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace plyfit::exporters {

namespace {
std::string temp_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}
}  // namespace

AtomicFile::AtomicFile(std::string path, bool binary)
    : path_(std::move(path)), temp_(temp_name(path_)) {
  out_.open(temp_, binary ? std::ios::out | std::ios::binary | std::ios::trunc
                          : std::ios::out | std::ios::trunc);
}

AtomicFile::~AtomicFile() {
  if (!done_) discard();
}

void AtomicFile::discard() {
  if (out_.is_open()) out_.close();
  std::error_code ec;
  std::filesystem::remove(temp_, ec);
  done_ = true;
}

Status AtomicFile::commit() {
  if (done_) return Error{ErrorCode::kFileAlreadyClosed, path_};
  if (!out_.is_open()) {
    done_ = true;
    return Error{ErrorCode::kFileNotCreated, path_};
  }
  out_.flush();
  const bool good = static_cast<bool>(out_);
  out_.close();
  if (!good || out_.fail()) {
    discard();
    return Error{ErrorCode::kFileWriteFailed, path_};
  }
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) {
    discard();
    return Error{ErrorCode::kFileNotRenamed, path_, {ec.message()}};
  }
  done_ = true;
  return ok_status();
}

Status write_file_atomic(const std::string& path, const std::string& content) {
  AtomicFile f(path);
  if (!f.ok()) return Error{ErrorCode::kFileNotCreated, path};
  f.stream() << content;
  return f.commit();
}

std::optional<std::string> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return std::move(text).str();
}

}  // namespace plyfit::exporters
