#include "file_checks.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace plyfit::importers::occt {

namespace {

// The value of a number's text (a Fortran D exponent read as E), or nothing when strtod does
// not read all of it. Text such as INF or NaN reads as a number too: IGES readers take it so.
std::optional<double> number_value(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c == 'D' || c == 'd') c = 'E';
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return v;
}

// The error of the number `text` (value `v`) of entity `where`: not finite, or beyond
// kMaxFileNumber when `bounded` (a length, parameter, weight or factor); ok when acceptable.
Status number_problem(std::string_view text, double v, bool bounded, const std::string& where) {
  Error e;
  if (!std::isfinite(v))
    e = Error{ErrorCode::kFileNumberNotFinite, {}, {std::string(text)}};
  else if (bounded && std::abs(v) > kMaxFileNumber)
    e = Error{ErrorCode::kFileNumberTooLarge, {}, {std::string(text), kMaxFileNumber}};
  else
    return ok_status();
  e.where = where;
  return e;
}

// An error of the file's entity `where` (its text: error_text_occt.cpp).
Error entity_error(ErrorCode code, std::string where, std::vector<MessageValue> values = {}) {
  Error e{code, {}, std::move(values)};
  e.where = std::move(where);
  return e;
}

// ---- STEP ----------------------------------------------------------------------------------

// Entities of ISO 10303-42 geometry and of the measures that scale it (units, uncertainty):
// their numbers are coordinates, direction ratios, knots, weights, radii, trim parameters and
// unit factors. Other entities may legitimately hold large numbers (a part's volume in mm^3).
constexpr std::array<std::string_view, 21> kStepGeometry = {"CARTESIAN_POINT",
                                                            "DIRECTION",
                                                            "VECTOR",
                                                            "LINE",
                                                            "CIRCLE",
                                                            "ELLIPSE",
                                                            "HYPERBOLA",
                                                            "PARABOLA",
                                                            "PLANE",
                                                            "POLYLINE",
                                                            "TRIMMED_CURVE",
                                                            "RECTANGULAR_TRIMMED_SURFACE",
                                                            "CYLINDRICAL_SURFACE",
                                                            "CONICAL_SURFACE",
                                                            "SPHERICAL_SURFACE",
                                                            "TOROIDAL_SURFACE",
                                                            "DEGENERATE_TOROIDAL_SURFACE",
                                                            "SURFACE_OF_REVOLUTION",
                                                            "SURFACE_OF_LINEAR_EXTRUSION",
                                                            "LENGTH_MEASURE_WITH_UNIT",
                                                            "UNCERTAINTY_MEASURE_WITH_UNIT"};
constexpr std::array<std::string_view, 8> kStepGeometryPrefixes = {
    "B_SPLINE_", "RATIONAL_B_SPLINE_",
    "BEZIER_",   "QUASI_UNIFORM_",
    "UNIFORM_",  "OFFSET_",
    "AXIS",      "CARTESIAN_TRANSFORMATION_OPERATOR"};

bool step_geometry(std::string_view keyword) {
  if (std::find(kStepGeometry.begin(), kStepGeometry.end(), keyword) != kStepGeometry.end())
    return true;
  return std::any_of(kStepGeometryPrefixes.begin(), kStepGeometryPrefixes.end(),
                     [&](std::string_view p) { return keyword.substr(0, p.size()) == p; });
}

// "#123".
std::string hash_name(long id) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "#%ld", id);
  return buf;
}

// The entities of a STEP file and the ones each refers to. OpenCASCADE's reader follows the
// references recursively: a cycle (an entity referring to itself, directly or not) makes it
// recurse without end, and so would a chain deeper than any real file's.
class ReferenceGraph {
 public:
  void add(long id, std::string keyword, std::vector<long> refs) {
    index_.emplace(id, static_cast<int>(nodes_.size()));
    nodes_.push_back(Node{id, std::move(keyword), std::move(refs)});
  }

  // A depth-first walk without recursion: a reference to an entity on the walk's path is a
  // cycle; an entity's depth is the longest chain of references below it.
  Status check() const {
    std::vector<int> state(nodes_.size(), 0), depth(nodes_.size(), 0);  // state 1: on the path
    std::vector<std::pair<int, size_t>> path;
    for (int start = 0; start < static_cast<int>(nodes_.size()); ++start) {
      if (state[static_cast<size_t>(start)]) continue;
      path.emplace_back(start, 0);
      state[static_cast<size_t>(start)] = 1;
      while (!path.empty()) {
        auto& [v, next] = path.back();
        const Node& n = nodes_[static_cast<size_t>(v)];
        if (next < n.refs.size()) {
          const auto it = index_.find(n.refs[next++]);
          if (it == index_.end()) continue;  // dangling: the reader reports it
          const int w = it->second;
          if (state[static_cast<size_t>(w)] == 1) return cycle(path, w);
          if (state[static_cast<size_t>(w)] == 0) {
            state[static_cast<size_t>(w)] = 1;
            path.emplace_back(w, 0);
          } else {
            depth[static_cast<size_t>(v)] =
                std::max(depth[static_cast<size_t>(v)], depth[static_cast<size_t>(w)] + 1);
          }
          continue;
        }
        const int done = v;
        state[static_cast<size_t>(done)] = 2;
        path.pop_back();
        if (depth[static_cast<size_t>(done)] > kMaxStepReferenceDepth)
          return entity_error(ErrorCode::kStepReferencesTooDeep, name(done),
                              {std::int64_t{kMaxStepReferenceDepth}});
        if (!path.empty()) {
          const size_t up = static_cast<size_t>(path.back().first);
          depth[up] = std::max(depth[up], depth[static_cast<size_t>(done)] + 1);
        }
      }
    }
    return ok_status();
  }

 private:
  struct Node {
    long id;
    std::string keyword;
    std::vector<long> refs;
  };

  std::string name(int k) const {
    const Node& n = nodes_[static_cast<size_t>(k)];
    return hash_name(n.id) + (n.keyword.empty() ? "" : " (" + n.keyword + ")");
  }

  // The cycle from `w` along the path back to `w`.
  Status cycle(const std::vector<std::pair<int, size_t>>& path, int w) const {
    size_t first = path.size() - 1;
    while (path[first].first != w) --first;
    std::string chain;
    for (size_t k = first; k < path.size() && k < first + 6; ++k)
      chain += hash_name(nodes_[static_cast<size_t>(path[k].first)].id) + " -> ";
    if (path.size() - first > 6) chain += "... -> ";
    return entity_error(ErrorCode::kStepReferenceCycle, name(w),
                        {chain + hash_name(nodes_[static_cast<size_t>(w)].id)});
  }

  std::vector<Node> nodes_;
  std::unordered_map<long, int> index_;
};

bool keyword_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// One pass over a STEP file's text: statements (#id = KEYWORD(...); or a complex entity
// #id = (A(...) B(...));) with their nesting depth, keywords and numbers. Strings, binaries
// and comments are skipped.
class StepScanner {
 public:
  explicit StepScanner(const std::string& text) : t_(text) {}

  Status run() {
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\'' || c == '"') {
        skip_quoted(c);
      } else if (c == '/' && i_ + 1 < t_.size() && t_[i_ + 1] == '*') {
        const size_t end = t_.find("*/", i_ + 2);
        i_ = end == std::string::npos ? t_.size() : end + 2;
      } else if (c == '#') {
        reference();
      } else if (c == '=' && depth_ == 0) {
        after_equals_ = true;
        ++i_;
      } else if (c == '(') {
        if (after_equals_ && depth_ == 0 && keywords_.empty()) complex_ = true;
        if (++depth_ > kMaxStepNesting)
          return entity_error(ErrorCode::kStepNestingTooDeep, entity(),
                              {std::int64_t{kMaxStepNesting}});
        ++i_;
      } else if (c == ')') {
        depth_ = std::max(0, depth_ - 1);
        ++i_;
      } else if (c == ';' && depth_ == 0) {
        if (auto st = end_statement(); !st) return st;
        ++i_;
      } else if (c == '.' && i_ + 1 < t_.size() &&
                 std::isalpha(static_cast<unsigned char>(t_[i_ + 1]))) {
        const size_t end = t_.find('.', i_ + 1);  // an enumeration .NAME.
        i_ = end == std::string::npos ? t_.size() : end + 1;
      } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
        number();
      } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
        keyword();
      } else {
        ++i_;
      }
    }
    return graph_.check();
  }

 private:
  std::string entity() const {
    std::string s = id_.empty() ? "an entity" : id_;
    if (!keywords_.empty()) s += " (" + keywords_.front() + ")";
    return s;
  }

  void skip_quoted(char q) {
    ++i_;
    while (i_ < t_.size()) {
      if (t_[i_] == q) {
        if (q == '\'' && i_ + 1 < t_.size() && t_[i_ + 1] == '\'') {
          i_ += 2;
          continue;
        }
        ++i_;
        return;
      }
      ++i_;
    }
  }

  void reference() {
    size_t j = i_ + 1;
    while (j < t_.size() && std::isdigit(static_cast<unsigned char>(t_[j]))) ++j;
    if (depth_ == 0 && !after_equals_)
      id_ = t_.substr(i_, j - i_);
    else if (after_equals_ && j > i_ + 1)
      refs_.push_back(std::strtol(t_.c_str() + i_ + 1, nullptr, 10));
    i_ = j;
  }

  void keyword() {
    size_t j = i_;
    while (j < t_.size() && (keyword_char(t_[j]) || t_[j] == '-')) ++j;
    std::string k = t_.substr(i_, j - i_);
    i_ = j;
    if (!after_equals_) return;
    while (j < t_.size() && std::isspace(static_cast<unsigned char>(t_[j]))) ++j;
    if (j == t_.size() || t_[j] != '(') {
      // A word that is no keyword of an entity or a typed value (INF, NaN): no STEP value.
      if (!bare_) bare_ = std::move(k);
      return;
    }
    // The statement's own keywords: the entity's, or the partial entities' of a complex one.
    if (depth_ == (complex_ ? 1 : 0)) {
      geometric_ = geometric_ || step_geometry(k);
      keywords_.push_back(std::move(k));
    }
  }

  void number() {
    size_t j = i_;
    if (t_[j] == '-' || t_[j] == '+') ++j;
    const size_t digits = j;
    while (j < t_.size() && std::isdigit(static_cast<unsigned char>(t_[j]))) ++j;
    if (j < t_.size() && t_[j] == '.') {
      ++j;
      while (j < t_.size() && std::isdigit(static_cast<unsigned char>(t_[j]))) ++j;
    }
    if (j == digits || (j == digits + 1 && t_[digits] == '.')) {  // a lone sign or dot
      i_ = j == i_ ? i_ + 1 : j;
      return;
    }
    if (j < t_.size() && (t_[j] == 'E' || t_[j] == 'e')) {
      size_t k = j + 1;
      if (k < t_.size() && (t_[k] == '-' || t_[k] == '+')) ++k;
      if (k < t_.size() && std::isdigit(static_cast<unsigned char>(t_[k]))) {
        while (k < t_.size() && std::isdigit(static_cast<unsigned char>(t_[k]))) ++k;
        j = k;
      }
    }
    const std::string_view text(t_.data() + i_, j - i_);
    i_ = j;
    if (!after_equals_) return;
    const auto v = number_value(text);
    if (!v) return;
    if (!std::isfinite(*v) && !nonfinite_) nonfinite_ = Number{std::string(text), *v};
    if (std::isfinite(*v) && std::abs(*v) > kMaxFileNumber && !huge_)
      huge_ = Number{std::string(text), *v};
  }

  Status end_statement() {
    Status st = ok_status();
    if (nonfinite_)
      st = number_problem(nonfinite_->text, nonfinite_->value, false, entity());
    else if (geometric_ && huge_)
      st = number_problem(huge_->text, huge_->value, true, entity());
    else if (geometric_ && bare_)
      st = entity_error(ErrorCode::kStepWordForNumber, entity(), {*bare_});
    if (id_.size() > 1)
      graph_.add(std::strtol(id_.c_str() + 1, nullptr, 10),
                 keywords_.empty() ? std::string() : keywords_.front(), std::move(refs_));
    refs_.clear();
    id_.clear();
    keywords_.clear();
    nonfinite_.reset();
    huge_.reset();
    bare_.reset();
    after_equals_ = complex_ = geometric_ = false;
    return st;
  }

  const std::string& t_;
  size_t i_ = 0;
  int depth_ = 0;
  std::string id_;  // "#123" of the current statement
  std::vector<std::string> keywords_;
  struct Number {
    std::string text;
    double value;
  };
  std::optional<Number> nonfinite_, huge_;  // the statement's first such numbers
  std::optional<std::string> bare_;         // its first word that is no keyword
  std::vector<long> refs_;                  // the entities it refers to
  ReferenceGraph graph_;
  bool after_equals_ = false, complex_ = false, geometric_ = false;
};

// ---- IGES ----------------------------------------------------------------------------------

// IGES entity types whose numbers are coordinates, parameters, weights, factors, counts or
// pointers: curves, surfaces, points, directions and transformation matrices (100-199), and the
// B-rep entities (vertex list to shell, 502-514).
bool iges_geometry(int type) {
  return (type >= 100 && type < 200) || (type >= 502 && type <= 514);
}

struct IgesRecords {
  std::string global;
  // Parameter data of each directory entry, in file order: (DE number, text).
  std::vector<std::pair<int, std::string>> params;
};

IgesRecords iges_records(const std::string& text) {
  IgesRecords r;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    std::string_view line(text.data() + pos, eol - pos);
    pos = eol + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.size() < 73) continue;
    if (line[72] == 'G') {
      r.global.append(line.substr(0, 72));
    } else if (line[72] == 'P') {
      const int de = std::atoi(std::string(line.substr(64, 8)).c_str());
      if (r.params.empty() || r.params.back().first != de) r.params.emplace_back(de, "");
      r.params.back().second.append(line.substr(0, 64));
    }
  }
  return r;
}

// The fields of IGES free-format data up to the record delimiter; Hollerith strings (nHtext)
// come back as "H" (their content is no number).
std::vector<std::string> iges_fields(const std::string& s, char pd, char rd, size_t from = 0) {
  std::vector<std::string> out;
  std::string field;
  size_t i = from;
  const auto plain = [&](char c) { return c != pd && c != rd && c != 'H' && c != ' '; };
  while (i < s.size()) {
    // A run of plain characters at once (appending them one by one was most of the check).
    size_t j = i;
    while (j < s.size() && plain(s[j])) ++j;
    field.append(s, i, j - i);
    if (j == s.size()) break;
    i = j;
    const char c = s[i];
    if (c == pd || c == rd) {
      out.push_back(std::move(field));
      field.clear();
      if (c == rd) return out;
      ++i;
      continue;
    }
    if (c == 'H' && !field.empty() && std::all_of(field.begin(), field.end(), [](char d) {
          return std::isdigit(static_cast<unsigned char>(d)) || d == ' ';
        })) {
      const long n = std::atol(field.c_str());
      i += 1 + static_cast<size_t>(std::max(0L, n));
      field.assign(1, 'H');
      continue;
    }
    if (c != ' ') field += c;
    ++i;
  }
  if (!field.empty()) out.push_back(field);
  return out;
}

// The global section's delimiters: its first two parameters (1H, and 1H; by default).
void iges_delimiters(const std::string& g, char& pd, char& rd, size_t& rest) {
  pd = ',';
  rd = ';';
  size_t i = 0;
  auto delimiter = [&](char& d) {
    if (g.compare(i, 2, "1H") == 0 && i + 2 < g.size()) {
      d = g[i + 2];
      i += 3;
    }
    if (i < g.size() && (g[i] == pd || g[i] == rd)) ++i;  // the field's end
  };
  delimiter(pd);
  delimiter(rd);
  rest = i;
}

// A field that is a plain decimal (an optional sign, digits, at most one point) with at most
// kPlainDigits digits before the point: finite and within kMaxFileNumber, so it needs no
// reading (most fields of a file are such; strtod on each was most of the check's time).
constexpr int kPlainDigits = 8;
static_assert(1e8 <= kMaxFileNumber, "kPlainDigits digits must stay within kMaxFileNumber");
bool plain_small_number(const std::string& f) {
  size_t i = (!f.empty() && (f[0] == '+' || f[0] == '-')) ? 1 : 0;
  int whole = 0;
  bool point = false;
  for (; i < f.size(); ++i) {
    if (f[i] == '.' && !point)
      point = true;
    else if (f[i] >= '0' && f[i] <= '9')
      whole += point ? 0 : 1;
    else
      return false;
  }
  return whole <= kPlainDigits;
}

// The field's problem, if any; `where()` names it (built only for a problem).
template <class Where>
Status check_iges_field(const std::string& field, bool bounded, const Where& where) {
  if (field.empty() || field == "H" || plain_small_number(field)) return ok_status();
  const auto v = number_value(field);
  if (!v) return ok_status();
  return number_problem(field, *v, bounded, where());
}

}  // namespace

Status check_file_text(const std::string& path, bool step) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kFileNotReadable, path};
  std::ostringstream buffer;  // whole buffers at a time (an istreambuf_iterator goes by chars)
  buffer << in.rdbuf();
  const std::string text = std::move(buffer).str();
  return step ? check_step_text(text) : check_iges_text(text);
}

Status check_step_text(const std::string& text) {
  return StepScanner(text).run();
}

Status check_iges_text(const std::string& text) {
  const IgesRecords r = iges_records(text);
  char pd = ',', rd = ';';
  size_t rest = 0;
  iges_delimiters(r.global, pd, rd, rest);
  // Global parameters from the third on; 13 is the model scale, 19 the resolution.
  const auto global = iges_fields(r.global, pd, rd, rest);
  for (size_t k = 0; k < global.size(); ++k) {
    const int index = static_cast<int>(k) + 3;
    if (auto st =
            check_iges_field(global[k], index == 13 || index == 19,
                             [&] { return "global section parameter " + std::to_string(index); });
        !st)
      return st;
  }
  for (const auto& [de, data] : r.params) {
    const auto fields = iges_fields(data, pd, rd);
    if (fields.empty()) continue;
    const int type = std::atoi(fields[0].c_str());
    // Field 0, the entity type, is a number too (the directory entry's type is the one read).
    for (size_t k = 0; k < fields.size(); ++k)
      if (auto st = check_iges_field(fields[k], k > 0 && iges_geometry(type),
                                     [&, de = de] {
                                       return "DE " + std::to_string(de) + " (type " + fields[0] +
                                              "), parameter " + std::to_string(k);
                                     });
          !st)
        return st;
  }
  return ok_status();
}

}  // namespace plyfit::importers::occt
