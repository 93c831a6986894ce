#include "dxf/writer.hpp"

#include "render/text.hpp"

#include <sstream>

namespace plyfit::exporters::dxf {

std::string dxf_text(const std::string& s) {
  static const char* kHex = "0123456789ABCDEF";
  std::string o;
  const std::u32string text = render::utf8_decode(s);
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char32_t c = text[k];
    if (c == U'%' && k + 1 < text.size() && text[k + 1] == U'%') {
      o += "%%%";  // a literal percent sign, so that "%%" starts no control code
    } else if (c == U'^') {
      o += "^ ";
    } else if (c < 0x20 || c == 0x7F) {
      o += ' ';
    } else if (c < 0x7F) {
      o += static_cast<char>(c);
    } else if (c >= 0xA0 && c <= 0xFF) {
      o += static_cast<char>(c);  // $DWGCODEPAGE ANSI_1252 agrees with Latin-1 here
    } else if (c <= 0xFFFF) {
      o += "\\U+";
      for (int sh = 12; sh >= 0; sh -= 4) o += kHex[(c >> sh) & 0xF];
    } else {
      o += '?';
    }
  }
  return o;
}

void Writer::tag(int code, const std::string& value) {
  std::string c = std::to_string(code);
  if (c.size() < 3) out_.append(3 - c.size(), ' ');
  out_ += c;
  out_ += '\n';
  out_ += value;
  out_ += '\n';
}

void Writer::tags(std::initializer_list<std::pair<int, int>> groups) {
  for (const auto& [code, value] : groups) tag(code, value);
}

void Writer::real(int code, double value) {
  tag(code, render::exact_text(value));
}

void Writer::reals(std::initializer_list<std::pair<int, double>> groups) {
  for (const auto& [code, value] : groups) real(code, value);
}

void Writer::handle(int code, unsigned h) {
  std::ostringstream os;
  os << std::uppercase << std::hex << h;
  tag(code, os.str());
}

void Writer::point(const Vec2& p, int base) {
  real(base, p.x());
  real(base + 10, p.y());
  real(base + 20, 0.0);
}

void Writer::entity_head(const char* type, const char* layer, const char* subclass) {
  tag(0, type);
  handle(5, next_++);
  handle(330, kBlockRecordModel);
  tag(100, "AcDbEntity");
  tag(8, layer);
  tag(100, subclass);
}

void Writer::polyline(const char* layer, const std::vector<Vec2>& pts, bool closed) {
  if (pts.size() < 2) return;
  entity_head("LWPOLYLINE", layer, "AcDbPolyline");
  tag(90, static_cast<int>(pts.size()));
  tag(70, closed ? 1 : 0);
  for (const Vec2& p : pts) {
    real(10, p.x());
    real(20, p.y());
  }
}

void Writer::line(const char* layer, const Vec2& a, const Vec2& b) {
  entity_head("LINE", layer, "AcDbLine");
  point(a, 10);
  point(b, 11);
}

void Writer::circle(const char* layer, const Vec2& c, double r) {
  entity_head("CIRCLE", layer, "AcDbCircle");
  point(c, 10);
  real(40, r);
}

void Writer::dot(const char* layer, const Vec2& p) {
  entity_head("POINT", layer, "AcDbPoint");
  point(p, 10);
}

void Writer::text(const char* layer, const Vec2& at, double height, const std::string& s,
                  double rotation) {
  entity_head("TEXT", layer, "AcDbText");
  point(at, 10);
  real(40, height);
  tag(1, dxf_text(s));
  if (rotation != 0.0) real(50, rotation);
  tag(7, "Standard");
  tag(100, "AcDbText");
}

}  // namespace plyfit::exporters::dxf
