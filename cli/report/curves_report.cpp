#include "report/curves_report.hpp"

#include "report/text_format.hpp"

#include <nlohmann/json.hpp>

#include <ostream>

namespace plyfit::cli {

namespace {

std::string point_text(const Vec3& p) {
  return fixed(p.x(), 4) + "," + fixed(p.y(), 4) + "," + fixed(p.z(), 4);
}

nlohmann::json point_json(const Vec3& p) {
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

// A closed curve's end is its start (its polyline does not repeat it).
const Vec3& last_point(const importers::FileCurve& c) {
  return c.closed ? c.points.front() : c.points.back();
}

}  // namespace

void print_curves(const std::string& path, const std::vector<importers::FileCurve>& curves,
                  bool json, std::ostream& os) {
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (const importers::FileCurve& c : curves)
      list.push_back({{"index", c.index},
                      {"name", c.name},
                      {"kind", c.kind},
                      {"length_mm", c.length},
                      {"closed", c.closed},
                      {"start", point_json(c.points.front())},
                      {"end", point_json(last_point(c))}});
    os << nlohmann::json{{"file", path}, {"curves", std::move(list)}}.dump(2) << "\n";
    return;
  }
  os << "file: " << path << "\n";
  std::vector<std::vector<std::string>> rows = {
      {"index", "name", "kind", "length_mm", "closed", "start", "end"}};
  for (const importers::FileCurve& c : curves)
    rows.push_back({std::to_string(c.index), c.name.empty() ? "-" : c.name, c.kind,
                    fixed(c.length, 4), c.closed ? "yes" : "no", point_text(c.points.front()),
                    point_text(last_point(c))});
  print_columns(rows, os);
  os << curves.size() << (curves.size() == 1 ? " curve\n" : " curves\n");
}

}  // namespace plyfit::cli
