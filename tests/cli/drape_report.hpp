#pragma once
// A drape through the binary that must succeed, and its report.json: the one run most CLI
// tests check figures of.

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include "cli/cli_util.hpp"

#include <string>

namespace plyfit::test {

/// Runs `plyfit drape FLAGS -o DIR` (DIR: the scratch folder's `out`), requires exit code 0
/// and returns the report.json it wrote.
inline nlohmann::json drape_report(const std::string& flags, const Scratch& tmp,
                                   const std::string& out = "out") {
  const std::string dir = tmp.file(out);
  const CliRun r = plyfit_run("drape " + flags + " -o '" + dir + "'", tmp);
  INFO(r.err);
  REQUIRE(r.code == 0);
  return nlohmann::json::parse(slurp(dir + "/report.json"));
}

}  // namespace plyfit::test
