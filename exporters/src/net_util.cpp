#include "net_util.hpp"

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
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

bool inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  bool in = false;  // even-odd over all loops
  for (const auto& l : loops) in = in != inside_polygon(l.points, p);
  return in;
}

namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// Signed distance: positive inside the outline.
double signed_distance(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  const double d = outline_distance(loops, p);
  return inside_outline(loops, p) ? d : -d;
}

// Does segment ab meet the box [lo, hi]? (Liang-Barsky clipping.)
bool segment_meets_box(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      // side -1: a + t d >= lo; side +1: a + t d <= hi.
      const double q = side < 0 ? a[axis] - lo[axis] : hi[axis] - a[axis];
      const double pp = side < 0 ? -d[axis] : d[axis];
      if (pp == 0.0) {
        if (q < 0) return false;
      } else {
        const double t = q / pp;
        if (pp < 0)
          t0 = std::max(t0, t);
        else
          t1 = std::min(t1, t);
        if (t0 > t1) return false;
      }
    }
  }
  return true;
}

}  // namespace

double outline_distance(const std::vector<OutlineLoop>& loops, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& l : loops) {
    const std::size_t n = l.points.size();
    for (std::size_t k = 0, m = n - 1; k < n; m = k++)
      best = std::min(best, segment_distance(p, l.points[m], l.points[k]));
  }
  return best;
}

InteriorPoint interior_point(const std::vector<OutlineLoop>& loops, double precision) {
  InteriorPoint out;
  Box2 box;
  for (const auto& l : loops)
    if (l.points.size() >= 3)
      for (const Vec2& p : l.points) box.add(p);
  if (box.empty() || !(precision > 0)) return out;
  const Vec2 size = box.size();
  const double lo_side = std::min(size.x(), size.y()), hi_side = std::max(size.x(), size.y());
  // Square cells: kGridCells along the long side, no wider than the short side (a thin
  // outline gets cells across it), and never more than kMaxInteriorProbes of them.
  const double cell = std::max(std::min(hi_side / kGridCells, lo_side),
                               hi_side / static_cast<double>(kMaxInteriorProbes));
  if (!(cell > 0)) return out;
  struct Probe {
    Vec2 p;
    double d;
  };
  std::vector<Probe> grid;
  const auto nx = static_cast<int>(std::ceil(size.x() / cell)),
             ny = static_cast<int>(std::ceil(size.y() / cell));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx && static_cast<int>(grid.size()) < kMaxInteriorProbes; ++i) {
      const Vec2 c = box.lo + cell * Vec2(i + 0.5, j + 0.5);
      grid.push_back({c, signed_distance(loops, c)});
    }
  // The best grid points, each climbed uphill (pattern search: the best of eight neighbours
  // at the current step, else half the step) to a local maximum of the distance.
  std::stable_sort(grid.begin(), grid.end(),
                   [](const Probe& a, const Probe& b) { return a.d > b.d; });
  Probe best{Vec2::Zero(), -std::numeric_limits<double>::infinity()};
  const std::size_t seeds = std::min<std::size_t>(grid.size(), kClimbSeeds);
  for (std::size_t k = 0; k < seeds; ++k) {
    Probe at = grid[k];
    if (!(at.d > 0)) break;
    double step = 0.5 * cell;
    for (int it = 0; it < kMaxClimbSteps && step > 0.25 * precision; ++it) {
      Probe next = at;
      for (int m = 0; m < 8; ++m) {
        const double a = m * kPi / 4;
        const Vec2 q = at.p + step * Vec2(std::cos(a), std::sin(a));
        const double dq = signed_distance(loops, q);
        if (dq > next.d) next = {q, dq};
      }
      if (next.d > at.d)
        at = next;
      else
        step *= 0.5;
    }
    if (at.d > best.d) best = at;
  }
  if (!(best.d > 0)) return out;
  out.point = best.p;
  out.radius = best.d;
  out.found = true;
  return out;
}

bool box_inside_outline(const std::vector<OutlineLoop>& loops, const Vec2& lo, const Vec2& hi) {
  if (!inside_outline(loops, 0.5 * (lo + hi))) return false;
  for (const auto& l : loops) {
    const std::size_t n = l.points.size();
    for (std::size_t k = 0, m = n - 1; k < n; m = k++)
      if (segment_meets_box(l.points[m], l.points[k], lo, hi)) return false;
  }
  return true;
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

std::string mold_label(const std::string& mold) {
  if (mold.rfind("builtin:", 0) == 0) return mold;
  const std::string name = std::filesystem::path(mold).filename().string();
  return name.empty() ? mold : name;
}

std::string faces_label(const std::vector<int>& faces) {
  constexpr std::size_t kListedFaces = 6;  // more are counted, not listed
  if (faces.size() <= 1) return "face " + std::to_string(faces.empty() ? 0 : faces.front());
  if (faces.size() > kListedFaces) return std::to_string(faces.size()) + " faces";
  std::string out = "faces ";
  for (std::size_t k = 0; k < faces.size(); ++k) out += (k ? ", " : "") + std::to_string(faces[k]);
  return out;
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
