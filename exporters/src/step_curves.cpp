// Native STEP (ISO 10303-21, AP214) writer of named 3D curve sets, in the structure
// OpenCASCADE's XDE reader maps to named shapes (docs/decisions/net-step-writer.md): per set a
// PRODUCT with its definition, formation, shape and category, and a
// GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION holding one GEOMETRIC_CURVE_SET of
// B_SPLINE_CURVE_WITH_KNOTS; one representation context in millimetres shared by all sets.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/step_curves.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace plyfit::exporters {

namespace {

// The schema of AP214 (IS), as OpenCASCADE names it for "AP214IS".
constexpr const char* kSchema = "AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }";
// Length uncertainty written into the representation context (mm): OpenCASCADE's
// Precision::Confusion(), what its own writer puts there.
constexpr const char* kUncertainty = "1.E-07";
// Lines of the data section are broken after this many characters (at a comma).
constexpr size_t kLineWidth = 72;

// A real in Part 21 syntax (a decimal point always, "E" for the exponent), with the fewest
// digits that read back to the same double.
std::string real(double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, res.ptr);
  const size_t e = s.find('e');
  std::string mantissa = e == std::string::npos ? s : s.substr(0, e);
  if (mantissa.find('.') == std::string::npos) mantissa += '.';
  if (e == std::string::npos) return mantissa;
  return mantissa + "E" + s.substr(e + 1);
}

// Appends code point `cp` as hexadecimal digits (4 for \X2\, 8 for \X4\).
void hex(std::string& out, std::uint32_t cp, int digits) {
  static const char* const kHex = "0123456789ABCDEF";
  for (int k = digits - 1; k >= 0; --k) out += kHex[(cp >> (4 * k)) & 0xF];
}

// A Part 21 string literal: apostrophes and backslashes doubled, text outside printable ASCII
// encoded (UTF-8 input as \X2\ (or \X4\) ... \X0\ runs, stray bytes as \X\hh).
std::string text(const std::string& s) {
  std::string out = "'";
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7F) {
      if (c == '\'')
        out += "''";
      else if (c == '\\')
        out += "\\\\";
      else
        out += static_cast<char>(c);
      ++i;
      continue;
    }
    // Decode one UTF-8 sequence; anything malformed is a single byte.
    int len = c >= 0xF0 && c < 0xF8 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 0;
    std::uint32_t cp = len == 4 ? c & 0x07 : len == 3 ? c & 0x0F : c & 0x1F;
    for (int k = 1; k < len; ++k) {
      const auto d = i + k < s.size() ? static_cast<unsigned char>(s[i + k]) : 0u;
      if ((d & 0xC0) != 0x80) {
        len = 0;
        break;
      }
      cp = (cp << 6) | (d & 0x3F);
    }
    if (len == 0) {
      out += "\\X\\";
      hex(out, c, 2);
      ++i;
      continue;
    }
    out += cp > 0xFFFF ? "\\X4\\" : "\\X2\\";
    hex(out, cp, cp > 0xFFFF ? 8 : 4);
    out += "\\X0\\";
    i += static_cast<size_t>(len);
  }
  return out + "'";
}

std::string ref(int id) {
  std::string s = std::to_string(id);
  s.insert(s.begin(), '#');
  return s;
}

// Entities numbered in the order they are written; a long entity is broken after a comma
// (outside strings) once its line passes kLineWidth characters.
class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) {}
  int add(const std::string& body) {
    std::string line = ref(++count_);
    line += '=';
    bool in_string = false;
    for (const char c : body) {
      line += c;
      if (c == '\'') in_string = !in_string;
      if (c == ',' && !in_string && line.size() >= kLineWidth) {
        out_ << line << "\n";
        line = "  ";
      }
    }
    out_ << line << ";\n";
    return count_;
  }

 private:
  std::ostream& out_;
  int count_ = 0;
};

std::string refs(const std::vector<int>& ids) {
  std::string s = "(";
  for (size_t k = 0; k < ids.size(); ++k) {
    if (k) s += ',';
    s += ref(ids[k]);
  }
  return s + ")";
}

// An error of a curve of set `name`: the set is its place in the file.
Error in_set(Error e, const std::string& name) {
  if (e.where.empty()) e.where = name;
  return e;
}

// A curve as B_SPLINE_CURVE_WITH_KNOTS (distinct knots and multiplicities).
Result<int> add_curve(Writer& w, const NurbsCurveData3& c) {
  if (!c.weights.empty()) return Error{ErrorCode::kCurveRational};
  auto valid = NurbsCurve3::create(c);
  if (!valid) return Error{ErrorCode::kCurveInvalid}.because(valid.error());
  std::vector<int> points;
  for (const auto& p : c.poles) {
    points.push_back(
        w.add("CARTESIAN_POINT('',(" + real(p.x()) + "," + real(p.y()) + "," + real(p.z()) + "))"));
  }
  std::string mults = "(", knots = "(";
  for (size_t k = 0; k < c.knots.size();) {
    size_t m = 1;
    while (k + m < c.knots.size() && c.knots[k + m] == c.knots[k]) ++m;
    if (k) {
      mults += ',';
      knots += ',';
    }
    mults += std::to_string(m);
    knots += real(c.knots[k]);
    k += m;
  }
  return w.add("B_SPLINE_CURVE_WITH_KNOTS(''," + std::to_string(c.degree) + "," + refs(points) +
               ",.UNSPECIFIED.,.F.,.F.," + mults + ")," + knots + "),.UNSPECIFIED.)");
}

}  // namespace

Result<StepCurveSet> polyline_set(std::string name, const std::vector<std::vector<Vec3>>& lines,
                                  bool closed) {
  StepCurveSet set{std::move(name), {}};
  for (const auto& line : lines) {
    std::vector<Vec3> pts = line;
    if (closed && pts.size() >= 2 && pts.front() != pts.back()) pts.push_back(pts.front());
    auto c = polyline_curve(pts);
    if (!c) return in_set(c.error(), set.name);
    set.curves.push_back(c->data());
  }
  return set;
}

namespace {

// The whole file onto `out`.
Status emit(std::ostream& out, const std::vector<StepCurveSet>& sets, const StepFileInfo& info) {
  out << "ISO-10303-21;\nHEADER;\n"
      << "FILE_DESCRIPTION((" << text(info.description) << "),'2;1');\n"
      << "FILE_NAME(" << text(info.file_name) << "," << text(info.timestamp) << ",("
      << text(info.author) << "),(" << text(info.organisation) << "),'plyfit','plyfit','');\n"
      << "FILE_SCHEMA(('" << kSchema << "'));\nENDSEC;\nDATA;\n";
  Writer w(out);
  const int app =
      w.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
  w.add("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000," +
        ref(app) + ")");
  const int product_ctx = w.add("PRODUCT_CONTEXT(''," + ref(app) + ",'mechanical')");
  const int definition_ctx =
      w.add("PRODUCT_DEFINITION_CONTEXT('part definition'," + ref(app) + ",'design')");
  const int length = w.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
  const int angle = w.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
  const int solid = w.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
  const int uncertainty =
      w.add(std::string("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(") + kUncertainty + ")," +
            ref(length) + ",'distance_accuracy_value','confusion accuracy')");
  const int geometry_ctx =
      w.add("(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT(" +
            refs({uncertainty}) + ")GLOBAL_UNIT_ASSIGNED_CONTEXT(" + refs({length, angle, solid}) +
            ")REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY'))");
  for (const StepCurveSet& set : sets) {
    if (set.curves.empty()) continue;
    const std::string name = text(set.name);
    const int product = w.add("PRODUCT(" + name + "," + name + ",''," + refs({product_ctx}) + ")");
    w.add("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$," + refs({product}) + ")");
    const int formation = w.add("PRODUCT_DEFINITION_FORMATION('',''," + ref(product) + ")");
    const int definition =
        w.add("PRODUCT_DEFINITION('design',''," + ref(formation) + "," + ref(definition_ctx) + ")");
    const int shape = w.add("PRODUCT_DEFINITION_SHAPE('',''," + ref(definition) + ")");
    std::vector<int> curves;
    for (const auto& c : set.curves) {
      auto id = add_curve(w, c);
      if (!id) return in_set(id.error(), set.name);
      curves.push_back(*id);
    }
    const int curve_set = w.add("GEOMETRIC_CURVE_SET(''," + refs(curves) + ")");
    const int rep = w.add("GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION(" + name + "," +
                          refs({curve_set}) + "," + ref(geometry_ctx) + ")");
    w.add("SHAPE_DEFINITION_REPRESENTATION(" + ref(shape) + "," + ref(rep) + ")");
  }
  out << "ENDSEC;\nEND-ISO-10303-21;\n";
  return ok_status();
}

}  // namespace

Result<std::string> step_curves_text(const std::vector<StepCurveSet>& sets,
                                     const StepFileInfo& info) {
  std::ostringstream os;
  if (auto st = emit(os, sets, info); !st) return st.error();
  return os.str();
}

Status write_step_curves(const std::string& path, const std::vector<StepCurveSet>& sets,
                         const StepFileInfo& info) {
  auto text = step_curves_text(sets, info);
  if (!text) return Error(text.error()).in(path);
  return write_file_atomic(path, *text);
}

}  // namespace plyfit::exporters
