#include "job/ini.hpp"

#include <sstream>

namespace plyfit::cli {

namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}
}  // namespace

std::string ini_place(const std::string& source, int line) {
  return source + ":" + std::to_string(line);
}

Result<std::vector<IniLine>> read_ini(const std::string& text, const std::string& source) {
  std::vector<IniLine> out;
  std::istringstream in(text);
  std::string raw, section;
  for (int n = 1; std::getline(in, raw); ++n) {
    const std::string line = trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    IniLine l;
    l.line = n;
    if (line.front() == '[' && line.back() == ']') {
      section = trim(line.substr(1, line.size() - 2));
      l.is_section = true;
    } else if (const auto eq = line.find('='); eq != std::string::npos) {
      l.key = trim(line.substr(0, eq));
      l.value = trim(line.substr(eq + 1));
    } else {
      Error e{ErrorCode::kIniSyntax, "", {line}};
      e.where = ini_place(source, n);
      return e;
    }
    l.section = section;
    out.push_back(std::move(l));
  }
  return out;
}

}  // namespace plyfit::cli
