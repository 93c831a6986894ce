#pragma once
// The CAD corpus: the real CAD files of ../shared/cad beside the clone (PLYFIT_SHARED_DIR,
// defined for the corpus test executables only). Tests that read it are built into those
// executables, whose main (tests/corpus_main.cpp) skips every test when it is absent.

#include <filesystem>
#include <string>

namespace plyfit::test {

/// Exit code of a corpus test executable run without the corpus: CTest reports the test as
/// skipped (SKIP_RETURN_CODE in tests/CMakeLists.txt), not passed.
constexpr int kCorpusSkipCode = 77;

/// The corpus folder (../shared/cad beside the source tree).
inline std::string corpus_dir() {
  return std::string(PLYFIT_SHARED_DIR) + "/cad";
}

/// True when the corpus folder exists.
inline bool corpus_present() {
  std::error_code ec;
  return std::filesystem::is_directory(corpus_dir(), ec);
}

/// A file of the corpus.
inline std::string shared_cad(const std::string& name) {
  return corpus_dir() + "/" + name;
}

}  // namespace plyfit::test
