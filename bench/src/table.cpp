// The table type shared by every benchmark: Markdown for the terminal and BENCHMARKS.md, CSV
// for bench/results; the subcommands that print one table.

#include "bench.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

namespace plyfit::bench {

std::string Table::markdown() const {
  std::string out;
  if (!caption.empty()) out += caption + "\n\n";
  auto line = [&](const std::vector<std::string>& cells) {
    out += "|";
    for (const auto& c : cells) {
      out += ' ';
      out += c;
      out += " |";
    }
    out += "\n";
  };
  line(header);
  out += "|";
  for (std::size_t c = 0; c < header.size(); ++c)
    out += (c < right.size() && right[c]) ? "---:|" : "---|";
  out += "\n";
  for (const auto& r : rows) line(r);
  return out;
}

std::string Table::csv() const {
  auto cell = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q(1, '"');
    for (char ch : s) {
      if (ch == '"') q += '"';
      q += ch;
    }
    q += '"';
    return q;
  };
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c) out += ',';
      out += cell(cells[c]);
    }
    out += "\n";
  };
  line(header);
  for (const auto& r : rows) line(r);
  return out;
}

Benchmark table_benchmark(
    std::string name, std::string summary,
    std::function<Table(const std::vector<std::string>& args, bool* ok)> make) {
  return {std::move(name), std::move(summary), [make](const std::vector<std::string>& args) {
            bool ok = true;
            std::cout << make(args, &ok).markdown();
            return ok ? 0 : 1;
          }};
}

Benchmark runs_table_benchmark(std::string name, std::string summary,
                               std::function<Table(int runs, bool* ok)> make) {
  return table_benchmark(
      std::move(name), std::move(summary) + " [--runs R]",
      [make](const std::vector<std::string>& args, bool* ok) {
        return make(std::stoi(option_value(args, "--runs", std::to_string(kMinRuns))), ok);
      });
}

bool write_text_file(const std::string& path, const std::string& text) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  std::ofstream os(path, std::ios::binary);
  if (!os) return false;
  os << text;
  return static_cast<bool>(os);
}

}  // namespace plyfit::bench
