#include "report/links_report.hpp"

#include "report/text_format.hpp"

#include <plyfit/exporters/messages.hpp>
#include <plyfit/exporters/warnings_json.hpp>
#include <plyfit/kernel/types.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace plyfit::cli {

namespace {

// x to `digits` significant digits (the stream's %g).
std::string number(double x, int digits) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

}  // namespace

std::vector<FaceLinks> face_links(const MoldSurface& shell, const std::vector<int>& source_faces) {
  const auto source = [&](std::int32_t k) {
    return source_faces.empty() ? static_cast<int>(k) : source_faces[static_cast<std::size_t>(k)];
  };
  std::vector<FaceLinks> out(static_cast<std::size_t>(shell.face_count()));
  for (std::int32_t k = 0; k < shell.face_count(); ++k) {
    out[static_cast<std::size_t>(k)].index = source(k);
    out[static_cast<std::size_t>(k)].free = shell.free_boundary(k);
  }
  // Each pair of faces once, at the largest crease of the edges between them.
  auto add = [&](std::int32_t f, std::int32_t g, double crease_deg) {
    auto& list = out[static_cast<std::size_t>(f)].neighbours;
    const auto it = std::find_if(list.begin(), list.end(), [&](const FaceLinks::Neighbour& n) {
      return n.face == source(g);
    });
    if (it == list.end())
      list.push_back({source(g), crease_deg});
    else
      it->crease_deg = std::max(it->crease_deg, crease_deg);
  };
  for (const SharedEdge& e : shell.shared_edges()) {
    add(e.face_a, e.face_b, e.crease * kRadToDeg);
    add(e.face_b, e.face_a, e.crease * kRadToDeg);
  }
  for (FaceLinks& f : out)
    std::sort(f.neighbours.begin(), f.neighbours.end(),
              [](const auto& a, const auto& b) { return a.face < b.face; });
  return out;
}

void print_links(const std::string& path, const std::vector<FaceLinks>& links,
                 const std::vector<Warning>& warnings, bool json, std::ostream& os) {
  if (json) {
    nlohmann::json faces = nlohmann::json::array();
    for (const FaceLinks& f : links) {
      nlohmann::json ns = nlohmann::json::array();
      for (const auto& n : f.neighbours)
        ns.push_back({{"face", n.face}, {"crease_deg", n.crease_deg}});
      faces.push_back({{"index", f.index},
                       {"neighbours", std::move(ns)},
                       {"free_runs", f.free.runs},
                       {"free_length_mm", f.free.length}});
    }
    os << nlohmann::json{{"file", path},
                         {"faces", std::move(faces)},
                         {"warnings", exporters::warnings_json(warnings)}}
              .dump(2)
       << "\n";
    return;
  }
  os << "file: " << path << "\n"
     << pad("index", 7) << pad("free_runs", 11) << pad("free_mm", 12)
     << "neighbours (face: crease deg)\n";
  for (const FaceLinks& f : links) {
    std::string ns;
    for (const auto& n : f.neighbours)
      ns += (ns.empty() ? "" : ", ") + std::to_string(n.face) + ": " +
            number(std::round(n.crease_deg * 10) / 10, 4);
    os << pad(std::to_string(f.index), 7) << pad(std::to_string(f.free.runs), 11)
       << pad(number(f.free.length, 6), 12) << (ns.empty() ? "-" : ns) << "\n";
  }
  if (warnings.empty()) {
    os << "warnings: none\n";
  } else {
    for (const auto& w : warnings) os << "warning: " << exporters::message(w) << "\n";
  }
}

}  // namespace plyfit::cli
