#include "net_util.hpp"

#include <plyfit/kernel/cells.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <utility>

namespace plyfit::exporters::detail {

std::string exact_text(double x) {
  if (x == 0.0) return "0";  // also -0
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof(buf), x, std::chars_format::fixed);
  if (r.ec != std::errc()) {  // beyond 512 characters: fall back to the shortest general form
    const auto g = std::to_chars(buf, buf + sizeof(buf), x);
    return std::string(buf, g.ptr);
  }
  return std::string(buf, r.ptr);
}

std::string fixed_text(double x, int decimals) {
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof(buf), x, std::chars_format::fixed, decimals);
  std::string s(buf, r.ec == std::errc() ? r.ptr : buf);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0" || s.empty()) return std::string(1, '0');
  return s;
}

double node_shear(const DrapeNode& n) {
  if (!n.mapped() || !n.has(DrapeNode::kHasAngle)) return -1.0;
  return std::abs(kPi / 2 - n.thread_angle);
}

std::vector<NetCell> mapped_cells(const DrapeResult& r) {
  std::vector<NetCell> out;
  for (const MappedCell& m : plyfit::mapped_cells(r)) {
    NetCell c;
    c.i = m.i;
    c.j = m.j;
    c.nodes = m.nodes;
    for (std::uint32_t k : c.nodes) c.shear = std::max(c.shear, node_shear(r.nodes[k]));
    out.push_back(std::move(c));
  }
  return out;
}

std::string Rgb::hex() const {
  static const char* kDigits = "0123456789abcdef";
  std::string s = "#";
  for (double v : {r, g, b}) {
    const int x = static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    s += kDigits[x / 16];
    s += kDigits[x % 16];
  }
  return s;
}

Rgb Rgb::shaded(double f) const {
  return {r * f, g * f, b * f};
}

Rgb shear_colour(double t) {
  // Viridis sampled at nine points, linearly interpolated.
  static constexpr std::array<std::array<double, 3>, 9> kStops = {{{0.267, 0.005, 0.329},
                                                                   {0.283, 0.141, 0.458},
                                                                   {0.254, 0.265, 0.530},
                                                                   {0.207, 0.372, 0.553},
                                                                   {0.164, 0.471, 0.558},
                                                                   {0.128, 0.567, 0.551},
                                                                   {0.135, 0.659, 0.518},
                                                                   {0.478, 0.821, 0.318},
                                                                   {0.993, 0.906, 0.144}}};
  if (!std::isfinite(t)) t = 0.0;
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(k);
  Rgb c;
  c.r = kStops[k][0] + f * (kStops[k + 1][0] - kStops[k][0]);
  c.g = kStops[k][1] + f * (kStops[k + 1][1] - kStops[k][1]);
  c.b = kStops[k][2] + f * (kStops[k + 1][2] - kStops[k][2]);
  return c;
}

std::u32string utf8_decode(const std::string& s) {
  constexpr char32_t kReplacement = 0xFFFD;
  std::u32string out;
  for (std::size_t k = 0; k < s.size();) {
    const auto b0 = static_cast<unsigned char>(s[k]);
    int len = 0;
    char32_t cp = 0;
    if (b0 < 0x80) {
      len = 1;
      cp = b0;
    } else if ((b0 & 0xE0) == 0xC0) {
      len = 2;
      cp = b0 & 0x1F;
    } else if ((b0 & 0xF0) == 0xE0) {
      len = 3;
      cp = b0 & 0x0F;
    } else if ((b0 & 0xF8) == 0xF0) {
      len = 4;
      cp = b0 & 0x07;
    }
    bool ok = len > 0 && k + static_cast<std::size_t>(len) <= s.size();
    for (int m = 1; ok && m < len; ++m) {
      const auto b = static_cast<unsigned char>(s[k + static_cast<std::size_t>(m)]);
      if ((b & 0xC0) != 0x80) ok = false;
      cp = (cp << 6) | (b & 0x3F);
    }
    // Overlong forms, surrogates and values past U+10FFFF are invalid too.
    static constexpr char32_t kMinForLength[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (ok && (cp < kMinForLength[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)))
      ok = false;
    if (!ok) {
      out += kReplacement;
      ++k;
      continue;
    }
    out += cp;
    k += static_cast<std::size_t>(len);
  }
  return out;
}

std::string utf8_encode(const std::u32string& s) {
  std::string o;
  for (const char32_t c : s) {
    if (c < 0x80) {
      o += static_cast<char>(c);
    } else if (c < 0x800) {
      o += static_cast<char>(0xC0 | (c >> 6));
      o += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      o += static_cast<char>(0xE0 | (c >> 12));
      o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      o += static_cast<char>(0xF0 | (c >> 18));
      o += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      o += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return o;
}

std::string xml_escape(const std::string& s) {
  std::u32string clean;
  for (const char32_t c : utf8_decode(s)) {
    // Control characters are not allowed in XML 1.0 (tab and newline are, but a label has no
    // use for them); neither are U+FFFE and U+FFFF.
    if (c < 0x20 || c == 0x7F || c == 0xFFFE || c == 0xFFFF)
      clean += U' ';
    else
      clean += c;
  }
  std::string o;
  for (const char ch : utf8_encode(clean)) {
    switch (ch) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      case '\'':
        o += "&apos;";
        break;
      default:
        o += ch;
    }
  }
  return o;
}

}  // namespace plyfit::exporters::detail
