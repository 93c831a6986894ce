// Main of the test executables that need the CAD corpus (../shared/cad): without it every test
// prints why and exits with kCorpusSkipCode, which CTest reports as skipped. Listing the tests
// (catch_discover_tests at build time) works either way.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "corpus.hpp"

#include <iostream>

int main(int argc, char* argv[]) {
  Catch::Session session;
  if (const int rc = session.applyCommandLine(argc, argv); rc != 0) return rc;
  const Catch::ConfigData& c = session.configData();
  const bool listing =
      c.listTests || c.listTestNamesOnly || c.listTags || c.listReporters || c.showHelp;
  if (!listing && !plyfit::test::corpus_present()) {
    std::cout << "skipped: this test needs the CAD corpus " << plyfit::test::corpus_dir()
              << " (../shared/cad beside the clone), which is absent\n";
    return plyfit::test::kCorpusSkipCode;
  }
  const int failures = session.run();
  // A run that failed exactly kCorpusSkipCode checks must not read as skipped.
  return failures == plyfit::test::kCorpusSkipCode ? 1 : failures;
}
