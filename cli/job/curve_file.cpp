// Curves from a file: CSV blocks of 3D points, or a STEP/IGES file's curves (read by the
// importers), picked by index or name.

#include "job/curve_file.hpp"

#include <plyfit/importers/importers.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace plyfit::cli {

namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Three numbers separated by commas (spaces around them allowed).
bool parse_point(const std::string& line, Vec3& p) {
  std::stringstream ss(line);
  std::string field;
  int k = 0;
  while (std::getline(ss, field, ',')) {
    const std::string f = trim(field);
    if (k >= 3 || f.empty()) return false;
    char* end = nullptr;
    p[k] = std::strtod(f.c_str(), &end);
    if (end != f.c_str() + f.size() || !std::isfinite(p[k])) return false;
    ++k;
  }
  return k == 3;
}

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e.empty() ? e : e.substr(1);
}

Result<std::vector<BoundaryCurve>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) return Error{ErrorCode::kCurveFileCannotOpen, path};
  std::vector<BoundaryCurve> curves;
  BoundaryCurve block;
  std::string line;
  const auto close_block = [&]() {
    if (!block.points.empty()) curves.push_back(std::move(block));
    block = BoundaryCurve{};
  };
  for (std::int64_t n = 1; std::getline(in, line); ++n) {
    const std::string text = trim(line.substr(0, line.find('#')));
    if (text.empty()) {
      if (trim(line).empty()) close_block();  // a comment line does not end a loop
      continue;
    }
    Vec3 p;
    if (!parse_point(text, p)) return Error{ErrorCode::kCurveFileSyntax, path, {n, text}};
    if (block.points.empty()) {
      block.name = path + " line " + std::to_string(n);
      block.closed = true;
    }
    block.points.push_back(p);
  }
  close_block();
  return curves;
}

// A STEP or IGES file's curves, each named for errors "FILE curve N 'NAME'"; `keys` gets the
// names picks match (the entity names).
Result<std::vector<BoundaryCurve>> read_cad(const std::string& path,
                                            std::vector<std::string>& keys) {
  auto read = importers::read_curves(path);
  if (!read) return Error{ErrorCode::kCurveFileUnreadable, path}.because(read.error());
  std::vector<BoundaryCurve> curves;
  for (importers::FileCurve& c : *read) {
    BoundaryCurve b;
    b.name =
        path + " curve " + std::to_string(c.index) + (c.name.empty() ? "" : " '" + c.name + "'");
    b.closed = c.closed;
    b.points = std::move(c.points);
    curves.push_back(std::move(b));
    keys.push_back(c.name);
  }
  if (curves.empty()) return Error{ErrorCode::kCurveFileNoCurves, path};
  return curves;
}

// The curves picked: each by index from 0, or by name (keys[k]: the name curve k is picked by):
// a name picks every curve that bears it, in file order (CAD systems name a wire's or a face
// border's edges after it: the curves of one loop).
Result<std::vector<BoundaryCurve>> pick(const CurveFileSpec& spec, std::vector<BoundaryCurve> all,
                                        const std::vector<std::string>& keys) {
  if (spec.pick.empty()) return all;
  std::vector<BoundaryCurve> out;
  for (const std::string& p : spec.pick) {
    char* end = nullptr;
    const long k = std::strtol(p.c_str(), &end, 10);
    const bool index = !p.empty() && end == p.c_str() + p.size();
    const std::size_t before = out.size();
    if (index && k >= 0 && k < static_cast<long>(all.size()))
      out.push_back(all[static_cast<std::size_t>(k)]);
    else if (!index)
      for (std::size_t c = 0; c < keys.size(); ++c)
        if (keys[c] == p) out.push_back(all[c]);
    if (out.size() == before)
      return Error{
          ErrorCode::kCurveNotFound, spec.path, {p, static_cast<std::int64_t>(all.size())}};
  }
  return out;
}

}  // namespace

CurveFileSpec parse_curve_spec(const std::string& text) {
  CurveFileSpec spec{text, {}};
  const auto colon = text.rfind(':');
  std::error_code ec;
  if (colon == std::string::npos || fs::exists(text, ec)) return spec;
  spec.path = text.substr(0, colon);
  std::stringstream ss(text.substr(colon + 1));
  std::string item;
  while (std::getline(ss, item, ','))
    if (!trim(item).empty()) spec.pick.push_back(trim(item));
  return spec;
}

std::string to_string(const CurveFileSpec& spec) {
  std::string s = spec.path;
  for (std::size_t k = 0; k < spec.pick.size(); ++k) s += (k == 0 ? ":" : ",") + spec.pick[k];
  return s;
}

bool is_cad_curve_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "step" || ext == "stp" || ext == "iges" || ext == "igs";
}

Result<std::vector<BoundaryCurve>> read_curves(const CurveFileSpec& spec) {
  const std::string ext = lower_extension(spec.path);
  const bool cad = is_cad_curve_file(spec.path);
  if (ext != "csv" && !cad) return Error{ErrorCode::kCurveFileFormat, spec.path, {ext}};
  std::error_code ec;
  if (!fs::is_regular_file(spec.path, ec)) return Error{ErrorCode::kCurveFileCannotOpen, spec.path};
  std::vector<std::string> keys;
  auto all = cad ? read_cad(spec.path, keys) : read_csv(spec.path);
  if (!all) return all.error();
  keys.resize(all->size());
  if (!cad)
    for (std::size_t k = 0; k < all->size(); ++k) keys[k] = (*all)[k].name;
  auto picked = pick(spec, std::move(all).value(), keys);
  if (!picked) return picked.error();
  if (picked->empty()) return Error{ErrorCode::kBoundaryEmpty, spec.path};
  return picked;
}

}  // namespace plyfit::cli
