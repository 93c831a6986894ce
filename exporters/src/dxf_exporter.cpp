// flat.dxf: the flat pattern as ASCII DXF R2000 (AC1015), millimetres ($INSUNITS 4), in ply
// coordinates, for a cutter or a nesting program. The contours to cut are on their own
// layers; everything else is marking (pen or ink) on layers of its own:
//   OUTLINE     closed LWPOLYLINEs: the outer loops of the cut outline, counter-clockwise
//               (FlatPattern::cut: the exact outline without slivers and notches narrower
//               than the minimum width; the exact outline is in report.json)
//   HOLES       closed LWPOLYLINEs: its inner loops (holes), clockwise
//   THREADS     LINEs: the warp (x = i d_weft) and weft (y = j d_warp) grid lines clipped to
//               the outline (even-odd over all loops); only when ExportOptions::dxf_threads
//               (otherwise the layer is not in the file at all)
//   BASEPATH    an open LWPOLYLINE through the mapped base-path nodes, in path order
//   ORIGIN      the start point (POINT and CIRCLE)
//   GRAIN       the grain arrow: the warp direction (+y, the fabric's 0 degree direction, along
//               the roll) as LINEs, with the TEXT "WARP" along it, inside the outline
//   SHEAR_WARN  closed LWPOLYLINEs around the mapped cells whose shear exceeds
//               ExportOptions::warn_shear (cell shear: the largest |90 deg - gamma| over the
//               cell's corners that have a thread angle)
//   LABELS      TEXT inside the outline: ply name, material, ply angle, spacing, outline
//               area, shear, and the mold's file name (never its folder) with the face
// The labels and the arrow form a block centred on the outline's pole of inaccessibility (the
// centre of a largest inscribed circle, net_util's interior_point), as large as fits inside
// the outline (box_inside_outline, with a generous width per character) up to a text height
// of 1/40 of the pattern.
//
// Text: the file declares $DWGCODEPAGE ANSI_1252, the code page of R2000 text, and writes
// U+00A0..U+00FF (the degree sign U+00B0 among them) as their single cp1252 bytes, other
// non-ASCII characters as \U+XXXX; it writes no AutoCAD %% control code.
//
// The file carries every table and object AutoCAD requires of R2000 (handles, BLOCK_RECORDs,
// the model and paper space layouts, the OBJECTS root dictionary). Numbers are written in
// their shortest exact decimal form; nothing depends on the clock or on hash order, so equal
// inputs give equal bytes.

#include <plyfit/exporters/atomic_file.hpp>
#include <plyfit/exporters/exporters.hpp>
#include <plyfit/kernel/flat_pattern.hpp>

#include "net_util.hpp"
#include "plugins.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace plyfit::exporters {

namespace {

using detail::Box2;
using detail::exact_text;
using detail::fixed_text;

// Layer names and ACI colours.
struct LayerDef {
  const char* name;
  int colour;
};
constexpr LayerDef kLayers[] = {{"0", 7},       {"OUTLINE", 7},    {"HOLES", 7},
                                {"THREADS", 8}, {"BASEPATH", 5},   {"ORIGIN", 3},
                                {"GRAIN", 4},   {"SHEAR_WARN", 1}, {"LABELS", 7}};
constexpr int kLayerCount = static_cast<int>(sizeof(kLayers) / sizeof(kLayers[0]));
constexpr const char* kThreadsLayer = "THREADS";

// The label block, in units of the text height h: line pitch, the widest a character of the
// Standard style's font is drawn (AutoCAD's txt and LibreCAD's fonts draw capitals and digits
// narrower than this, so the block estimate is generous), the grain arrow's column ("WARP"
// rotated, the shaft, a gap before the text) and the depth below the last baseline.
constexpr double kLinePitch = 1.6;
constexpr double kCharWidth = 1.0;
constexpr double kArrowColumn = 3.0;
constexpr double kDescent = 0.4;
// The text height is at most this fraction of the pattern's extent.
constexpr double kMaxTextRel = 1.0 / 40.0;
// interior_point's precision, relative to the pattern's extent.
constexpr double kPolePrecisionRel = 1e-3;
// Bisection steps for the largest label block that fits.
constexpr int kFitSteps = 40;

// User text for a DXF string value: printable ASCII and U+00A0..U+00FF as single bytes of the
// file's code page (ANSI_1252), other characters as \U+XXXX (AutoCAD decodes these), the
// AutoCAD control sequences (%%x and ^x) neutralised, no line breaks.
std::string dxf_text(const std::string& s) {
  static const char* kHex = "0123456789ABCDEF";
  std::string o;
  const std::u32string text = detail::utf8_decode(s);
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

// Fixed handles of the drawing's structure; entities get handles from kFirstEntityHandle on.
enum Handle : unsigned {
  kRootDict = 0x1,
  kGroupDict,
  kLayoutDict,
  kMlineStyleDict,
  kMlineStyleStandard,
  kPlotStyleDict,
  kPlotStyleNormal,
  kLayoutModel,
  kLayoutPaper,
  kVportTable,
  kVportActive,
  kLtypeTable,
  kLtypeByBlock,
  kLtypeByLayer,
  kLtypeContinuous,
  kLayerTable,
  kStyleTable,
  kStyleStandard,
  kViewTable,
  kUcsTable,
  kAppidTable,
  kAppidAcad,
  kDimstyleTable,
  kDimstyleStandard,
  kBlockRecordTable,
  kBlockRecordModel,
  kBlockRecordPaper,
  kBlockModel,
  kEndblkModel,
  kBlockPaper,
  kEndblkPaper,
  kFirstLayerHandle,  // one per layer
  kFirstEntityHandle = kFirstLayerHandle + kLayerCount,
};

std::string hex(unsigned h) {
  std::ostringstream os;
  os << std::uppercase << std::hex << h;
  return os.str();
}

class DxfWriter {
 public:
  void tag(int code, const std::string& value) {
    // Group codes right-aligned in three columns, as AutoCAD writes them.
    std::string c = std::to_string(code);
    if (c.size() < 3) out_.append(3 - c.size(), ' ');
    out_ += c;
    out_ += '\n';
    out_ += value;
    out_ += '\n';
  }
  void tag(int code, int value) { tag(code, std::to_string(value)); }
  void real(int code, double value) { tag(code, exact_text(value)); }
  void handle(int code, unsigned h) { tag(code, hex(h)); }
  void point(const Vec2& p, int base = 10) {
    real(base, p.x());
    real(base + 10, p.y());
    real(base + 20, 0.0);
  }

  // Entities, owned by *Model_Space.
  void entity_head(const char* type, const char* layer, const char* subclass) {
    tag(0, type);
    handle(5, next_++);
    handle(330, kBlockRecordModel);
    tag(100, "AcDbEntity");
    tag(8, layer);
    tag(100, subclass);
  }
  void polyline(const char* layer, const std::vector<Vec2>& pts, bool closed) {
    if (pts.size() < 2) return;
    entity_head("LWPOLYLINE", layer, "AcDbPolyline");
    tag(90, static_cast<int>(pts.size()));
    tag(70, closed ? 1 : 0);
    for (const Vec2& p : pts) {
      real(10, p.x());
      real(20, p.y());
    }
  }
  void line(const char* layer, const Vec2& a, const Vec2& b) {
    entity_head("LINE", layer, "AcDbLine");
    point(a, 10);
    point(b, 11);
  }
  void circle(const char* layer, const Vec2& c, double r) {
    entity_head("CIRCLE", layer, "AcDbCircle");
    point(c, 10);
    real(40, r);
  }
  void dot(const char* layer, const Vec2& p) {
    entity_head("POINT", layer, "AcDbPoint");
    point(p, 10);
  }
  // `s` is user text, escaped here with dxf_text(); `rotation` in degrees.
  void text(const char* layer, const Vec2& at, double height, const std::string& s,
            double rotation = 0.0) {
    entity_head("TEXT", layer, "AcDbText");
    point(at, 10);
    real(40, height);
    tag(1, dxf_text(s));
    if (rotation != 0.0) real(50, rotation);
    tag(7, "Standard");
    tag(100, "AcDbText");
  }

  unsigned next_handle() const { return next_; }
  std::string& out() { return out_; }

 private:
  std::string out_;
  unsigned next_ = kFirstEntityHandle;
};

// Segments of the line {p : p[axis] = c} inside the outline (even-odd over all loops, each
// edge half-open so that a vertex on the line counts once).
std::vector<std::pair<double, double>> clip_line(const std::vector<OutlineLoop>& loops, int axis,
                                                 double c) {
  const int other = 1 - axis;
  std::vector<double> xs;
  for (const auto& l : loops) {
    const auto n = l.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = l.points[k];
      const Vec2& b = l.points[(k + 1) % n];
      if ((a[axis] <= c) == (b[axis] <= c)) continue;
      const double t = (c - a[axis]) / (b[axis] - a[axis]);
      xs.push_back(a[other] + t * (b[other] - a[other]));
    }
  }
  std::sort(xs.begin(), xs.end());
  std::vector<std::pair<double, double>> segs;
  for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
    if (xs[k + 1] > xs[k]) segs.emplace_back(xs[k], xs[k + 1]);
  return segs;
}

std::string degrees(double deg, int decimals) {
  return fixed_text(deg, decimals) + "\u00b0";
}

// The label block: lines of text beside a vertical grain arrow, laid out for text height h
// with the block's top-left corner at the origin.
struct LabelBlock {
  std::vector<std::string> lines;
  double width(double h) const {
    std::size_t chars = 0;
    for (const auto& l : lines) chars = std::max(chars, detail::utf8_decode(l).size());
    return h * (kArrowColumn + kCharWidth * static_cast<double>(chars));
  }
  double height(double h) const {
    return h * (1.0 + kLinePitch * static_cast<double>(lines.size() - 1) + kDescent);
  }
};

// The text height and the block's top-left corner: the largest block up to `max_h` centred
// on the outline's pole of inaccessibility that lies inside the outline. Without an outline
// (nothing mapped), below `fallback` at height max_h.
struct LabelPlace {
  double h = 0.0;                // text height
  Vec2 top_left = Vec2::Zero();  // the block's top-left corner
};
LabelPlace place_labels(const std::vector<OutlineLoop>& loops, const LabelBlock& b, double extent,
                        double max_h, const Vec2& fallback) {
  const detail::InteriorPoint pole = detail::interior_point(loops, kPolePrecisionRel * extent);
  LabelPlace out;
  out.h = max_h;
  if (!pole.found) {
    out.top_left = fallback - Vec2(0.0, 2.0 * max_h);
    return out;
  }
  auto corner = [&](double h) -> Vec2 { return pole.point + 0.5 * Vec2(-b.width(h), b.height(h)); };
  auto fits = [&](double h) {
    const Vec2 tl = corner(h);
    return detail::box_inside_outline(loops, Vec2(tl.x(), tl.y() - b.height(h)),
                                      Vec2(tl.x() + b.width(h), tl.y()));
  };
  if (fits(max_h)) {
    out.top_left = corner(max_h);
    return out;
  }
  // Bisection: a block centred on the pole shrinks into itself, so fitting is monotonic; a
  // small enough block always fits (the pole is at pole.radius > 0 from every edge).
  double lo = 0.0, hi = max_h;
  for (int k = 0; k < kFitSteps; ++k) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  out.h = lo;
  out.top_left = corner(lo);
  return out;
}

std::string build_dxf(const ExportContext& ctx) {
  const DrapeResult& r = ctx.result;
  const PlySpec& spec = ctx.problem.ply;
  const std::vector<OutlineLoop> no_loops;
  const std::vector<OutlineLoop>& loops = ctx.flat ? ctx.flat->cut : no_loops;

  // Extents: the outline, the mapped nodes and the start.
  Box2 box;
  for (const auto& l : loops)
    for (const Vec2& p : l.points) box.add(p);
  for (const DrapeNode& n : r.nodes)
    if (n.mapped()) box.add(n.ply);
  box.add(spec.start);
  const double extent = std::max(
      {box.hi.x() - box.lo.x(), box.hi.y() - box.lo.y(), std::max(spec.d_weft, spec.d_warp)});
  const double marker = extent / 80.0;

  DxfWriter e;
  // ---- entities first (their handles set $HANDSEED) ----
  for (const auto& l : loops) e.polyline(l.hole ? "HOLES" : "OUTLINE", l.points, true);

  if (ctx.options.dxf_threads && !loops.empty()) {
    const double dx = spec.d_weft, dy = spec.d_warp;
    // Warp threads: x = i dx.
    for (auto i = static_cast<long long>(std::ceil(box.lo.x() / dx));
         static_cast<double>(i) * dx <= box.hi.x(); ++i) {
      const double x = static_cast<double>(i) * dx;
      for (const auto& [a, b] : clip_line(loops, 0, x)) e.line(kThreadsLayer, {x, a}, {x, b});
    }
    // Weft threads: y = j dy.
    for (auto j = static_cast<long long>(std::ceil(box.lo.y() / dy));
         static_cast<double>(j) * dy <= box.hi.y(); ++j) {
      const double y = static_cast<double>(j) * dy;
      for (const auto& [a, b] : clip_line(loops, 1, y)) e.line(kThreadsLayer, {a, y}, {b, y});
    }
  }

  std::vector<Vec2> path;
  for (const std::uint32_t k : r.base_path) path.push_back(r.nodes[k].ply);
  e.polyline("BASEPATH", path, false);

  e.dot("ORIGIN", spec.start);
  e.circle("ORIGIN", spec.start, marker);

  const double warn = ctx.options.warn_shear;
  for (const auto& c : detail::mapped_cells(r)) {
    if (!(c.shear > warn)) continue;
    std::vector<Vec2> pts;
    for (const std::uint32_t k : c.nodes) pts.push_back(r.nodes[k].ply);
    e.polyline("SHEAR_WARN", pts, true);
  }

  // Labels and the grain arrow, inside the outline.
  const DrapeMetrics& m = r.metrics;
  const double shear_max_deg = m.shear_max * detail::kRadToDeg;
  const double lock_deg = ctx.run.lock_angle_deg;
  const std::string material =
      ctx.options.material_label.empty() || ctx.options.material_label == ctx.run.material
          ? ctx.run.material
          : ctx.options.material_label + " (" + ctx.run.material + ")";
  LabelBlock block;
  block.lines = {
      "PLY: " + ctx.run.ply_name,
      "MATERIAL: " + material,
      "PLY ANGLE: " + degrees(ctx.options.ply_angle_deg, 2),
      "SPACING: " + fixed_text(spec.d_weft, 6) + " x " + fixed_text(spec.d_warp, 6) +
          " mm (weft x warp link)",
      "AREA: " + fixed_text(ctx.flat ? ctx.flat->cut_area : 0.0, 3) + " mm\u00b2",
      "SHEAR: max " + degrees(shear_max_deg, 2) + ", warning " +
          degrees(warn * detail::kRadToDeg, 2) + ", limit " +
          (lock_deg >= 90.0 ? std::string("none") : degrees(lock_deg, 2)),
      "MOLD: " + detail::mold_label(ctx.run.mold) + " " + detail::faces_label(ctx.run.faces),
  };
  const LabelPlace place = place_labels(loops, block, extent, kMaxTextRel * extent, box.lo);
  const double text_h = place.h;
  const Vec2 top_left = place.top_left;
  const double block_h = block.height(text_h);
  // The arrow: up the block's left column, the head at the top; "WARP" along the shaft.
  const Vec2 foot = top_left + Vec2(2.0 * text_h, -block_h);
  const Vec2 tip = top_left + Vec2(2.0 * text_h, 0.0);
  const double head = std::min(1.2 * text_h, 0.3 * block_h), head_half = 0.45 * text_h;
  e.line("GRAIN", foot, tip);
  e.line("GRAIN", tip, tip + Vec2(head_half, -head));
  e.line("GRAIN", tip, tip + Vec2(-head_half, -head));
  e.text("GRAIN", foot + Vec2(-0.4 * text_h, 0.1 * block_h), text_h, "WARP", 90.0);
  for (std::size_t k = 0; k < block.lines.size(); ++k) {
    const Vec2 at = top_left + Vec2(kArrowColumn * text_h,
                                    -text_h * (1.0 + kLinePitch * static_cast<double>(k)));
    e.text("LABELS", at, text_h, block.lines[k]);
  }
  box.add(top_left);
  box.add(top_left + Vec2(block.width(text_h), -block_h));
  if (box.empty()) box.add(Vec2::Zero());

  // ---- the file ----
  DxfWriter f;
  f.tag(0, "SECTION");
  f.tag(2, "HEADER");
  f.tag(9, "$ACADVER");
  f.tag(1, "AC1015");
  f.tag(9, "$DWGCODEPAGE");
  f.tag(3, "ANSI_1252");
  f.tag(9, "$INSBASE");
  f.point(Vec2::Zero());
  f.tag(9, "$EXTMIN");
  f.point(box.lo);
  f.tag(9, "$EXTMAX");
  f.point(box.hi);
  f.tag(9, "$LIMMIN");
  f.real(10, box.lo.x());
  f.real(20, box.lo.y());
  f.tag(9, "$LIMMAX");
  f.real(10, box.hi.x());
  f.real(20, box.hi.y());
  f.tag(9, "$TEXTSIZE");
  f.real(40, text_h);
  f.tag(9, "$TEXTSTYLE");
  f.tag(7, "Standard");
  f.tag(9, "$CLAYER");
  f.tag(8, "0");
  f.tag(9, "$LUNITS");
  f.tag(70, 2);
  f.tag(9, "$LUPREC");
  f.tag(70, 4);
  f.tag(9, "$INSUNITS");
  f.tag(70, 4);  // millimetres
  f.tag(9, "$MEASUREMENT");
  f.tag(70, 1);  // metric
  f.tag(9, "$HANDSEED");
  f.handle(5, e.next_handle());
  f.tag(0, "ENDSEC");

  f.tag(0, "SECTION");
  f.tag(2, "CLASSES");
  const char* classes[][3] = {{"ACDBDICTIONARYWDFLT", "AcDbDictionaryWithDefault", "0"},
                              {"ACDBPLACEHOLDER", "AcDbPlaceHolder", "0"},
                              {"LAYOUT", "AcDbLayout", "0"}};
  for (const auto& c : classes) {
    f.tag(0, "CLASS");
    f.tag(1, c[0]);
    f.tag(2, c[1]);
    f.tag(3, "ObjectDBX Classes");
    f.tag(90, c[2]);
    f.tag(280, 0);
    f.tag(281, 0);
  }
  f.tag(0, "ENDSEC");

  f.tag(0, "SECTION");
  f.tag(2, "TABLES");
  auto table = [&](const char* name, unsigned h, int count) {
    f.tag(0, "TABLE");
    f.tag(2, name);
    f.handle(5, h);
    f.handle(330, 0);
    f.tag(100, "AcDbSymbolTable");
    f.tag(70, count);
  };
  auto record = [&](const char* type, unsigned h, unsigned owner, const char* subclass,
                    const std::string& name) {
    f.tag(0, type);
    f.handle(std::string(type) == "DIMSTYLE" ? 105 : 5, h);
    f.handle(330, owner);
    f.tag(100, "AcDbSymbolTableRecord");
    f.tag(100, subclass);
    f.tag(2, name);
    f.tag(70, 0);
  };
  table("VPORT", kVportTable, 1);
  record("VPORT", kVportActive, kVportTable, "AcDbViewportTableRecord", "*Active");
  const Vec2 centre = 0.5 * (box.lo + box.hi);
  const double view_h = 1.1 * std::max(box.hi.y() - box.lo.y(), box.hi.x() - box.lo.x());
  f.real(10, 0.0);
  f.real(20, 0.0);
  f.real(11, 1.0);
  f.real(21, 1.0);
  f.real(12, centre.x());
  f.real(22, centre.y());
  f.real(13, 0.0);
  f.real(23, 0.0);
  f.real(14, 1.0);
  f.real(24, 1.0);
  f.real(15, 1.0);
  f.real(25, 1.0);
  f.real(16, 0.0);
  f.real(26, 0.0);
  f.real(36, 1.0);
  f.real(17, 0.0);
  f.real(27, 0.0);
  f.real(37, 0.0);
  f.real(40, view_h > 0 ? view_h : 1.0);
  f.real(41, 1.5);
  f.real(42, 50.0);
  f.real(43, 0.0);
  f.real(44, 0.0);
  f.real(50, 0.0);
  f.real(51, 0.0);
  f.tag(71, 0);
  f.tag(72, 1000);
  f.tag(73, 1);
  f.tag(74, 3);
  f.tag(75, 0);
  f.tag(76, 0);
  f.tag(77, 0);
  f.tag(78, 0);
  f.tag(0, "ENDTAB");

  table("LTYPE", kLtypeTable, 3);
  for (const auto& [h, name] : {std::pair{kLtypeByBlock, "ByBlock"},
                                {kLtypeByLayer, "ByLayer"},
                                {kLtypeContinuous, "Continuous"}}) {
    record("LTYPE", h, kLtypeTable, "AcDbLinetypeTableRecord", name);
    f.tag(3, h == kLtypeContinuous ? "Solid line" : "");
    f.tag(72, 65);
    f.tag(73, 0);
    f.real(40, 0.0);
  }
  f.tag(0, "ENDTAB");

  auto defined = [&](int k) {
    return ctx.options.dxf_threads || std::string(kLayers[k].name) != kThreadsLayer;
  };
  int layer_count = 0;
  for (int k = 0; k < kLayerCount; ++k) layer_count += defined(k);
  table("LAYER", kLayerTable, layer_count);
  for (int k = 0; k < kLayerCount; ++k) {
    if (!defined(k)) continue;
    record("LAYER", kFirstLayerHandle + static_cast<unsigned>(k), kLayerTable,
           "AcDbLayerTableRecord", kLayers[k].name);
    f.tag(62, kLayers[k].colour);
    f.tag(6, "Continuous");
    f.tag(370, -3);
    f.handle(390, kPlotStyleNormal);
  }
  f.tag(0, "ENDTAB");

  table("STYLE", kStyleTable, 1);
  record("STYLE", kStyleStandard, kStyleTable, "AcDbTextStyleTableRecord", "Standard");
  f.real(40, 0.0);
  f.real(41, 1.0);
  f.real(50, 0.0);
  f.tag(71, 0);
  f.real(42, text_h);
  f.tag(3, "txt");
  f.tag(4, "");
  f.tag(0, "ENDTAB");

  table("VIEW", kViewTable, 0);
  f.tag(0, "ENDTAB");
  table("UCS", kUcsTable, 0);
  f.tag(0, "ENDTAB");

  table("APPID", kAppidTable, 1);
  record("APPID", kAppidAcad, kAppidTable, "AcDbRegAppTableRecord", "ACAD");
  f.tag(0, "ENDTAB");

  table("DIMSTYLE", kDimstyleTable, 1);
  f.tag(100, "AcDbDimStyleTable");
  record("DIMSTYLE", kDimstyleStandard, kDimstyleTable, "AcDbDimStyleTableRecord", "Standard");
  f.tag(0, "ENDTAB");

  table("BLOCK_RECORD", kBlockRecordTable, 2);
  record("BLOCK_RECORD", kBlockRecordModel, kBlockRecordTable, "AcDbBlockTableRecord",
         "*Model_Space");
  f.handle(340, kLayoutModel);
  record("BLOCK_RECORD", kBlockRecordPaper, kBlockRecordTable, "AcDbBlockTableRecord",
         "*Paper_Space");
  f.handle(340, kLayoutPaper);
  f.tag(0, "ENDTAB");
  f.tag(0, "ENDSEC");

  f.tag(0, "SECTION");
  f.tag(2, "BLOCKS");
  for (const auto& [b, end, owner, name] :
       {std::tuple{kBlockModel, kEndblkModel, kBlockRecordModel, "*Model_Space"},
        {kBlockPaper, kEndblkPaper, kBlockRecordPaper, "*Paper_Space"}}) {
    f.tag(0, "BLOCK");
    f.handle(5, b);
    f.handle(330, owner);
    f.tag(100, "AcDbEntity");
    if (owner == kBlockRecordPaper) f.tag(67, 1);
    f.tag(8, "0");
    f.tag(100, "AcDbBlockBegin");
    f.tag(2, name);
    f.tag(70, 0);
    f.point(Vec2::Zero());
    f.tag(3, name);
    f.tag(1, "");
    f.tag(0, "ENDBLK");
    f.handle(5, end);
    f.handle(330, owner);
    f.tag(100, "AcDbEntity");
    if (owner == kBlockRecordPaper) f.tag(67, 1);
    f.tag(8, "0");
    f.tag(100, "AcDbBlockEnd");
  }
  f.tag(0, "ENDSEC");

  f.tag(0, "SECTION");
  f.tag(2, "ENTITIES");
  f.out() += e.out();
  f.tag(0, "ENDSEC");

  f.tag(0, "SECTION");
  f.tag(2, "OBJECTS");
  auto dictionary = [&](unsigned h, unsigned owner,
                        const std::vector<std::pair<const char*, unsigned>>& entries) {
    f.tag(0, "DICTIONARY");
    f.handle(5, h);
    f.handle(330, owner);
    f.tag(100, "AcDbDictionary");
    f.tag(281, 1);
    for (const auto& [name, target] : entries) {
      f.tag(3, name);
      f.handle(350, target);
    }
  };
  dictionary(kRootDict, 0,
             {{"ACAD_GROUP", kGroupDict},
              {"ACAD_LAYOUT", kLayoutDict},
              {"ACAD_MLINESTYLE", kMlineStyleDict},
              {"ACAD_PLOTSTYLENAME", kPlotStyleDict}});
  dictionary(kGroupDict, kRootDict, {});
  dictionary(kLayoutDict, kRootDict, {{"Model", kLayoutModel}, {"Layout1", kLayoutPaper}});
  dictionary(kMlineStyleDict, kRootDict, {{"Standard", kMlineStyleStandard}});
  f.tag(0, "ACDBDICTIONARYWDFLT");
  f.handle(5, kPlotStyleDict);
  f.handle(330, kRootDict);
  f.tag(100, "AcDbDictionary");
  f.tag(281, 1);
  f.tag(3, "Normal");
  f.handle(350, kPlotStyleNormal);
  f.tag(100, "AcDbDictionaryWithDefault");
  f.handle(340, kPlotStyleNormal);
  f.tag(0, "ACDBPLACEHOLDER");
  f.handle(5, kPlotStyleNormal);
  f.handle(330, kPlotStyleDict);
  f.tag(0, "MLINESTYLE");
  f.handle(5, kMlineStyleStandard);
  f.handle(330, kMlineStyleDict);
  f.tag(100, "AcDbMlineStyle");
  f.tag(2, "Standard");
  f.tag(70, 0);
  f.tag(3, "");
  f.tag(62, 256);
  f.real(51, 90.0);
  f.real(52, 90.0);
  f.tag(71, 2);
  f.real(49, 0.5);
  f.tag(62, 256);
  f.tag(6, "BYLAYER");
  f.real(49, -0.5);
  f.tag(62, 256);
  f.tag(6, "BYLAYER");
  for (const auto& [h, name, tab, owner] : {std::tuple{kLayoutModel, "Model", 0, kBlockRecordModel},
                                            {kLayoutPaper, "Layout1", 1, kBlockRecordPaper}}) {
    f.tag(0, "LAYOUT");
    f.handle(5, h);
    f.handle(330, kLayoutDict);
    f.tag(100, "AcDbPlotSettings");
    f.tag(1, "");
    f.tag(2, "none_device");
    f.tag(4, "");
    f.tag(6, "");
    for (int code : {40, 41, 42, 43}) f.real(code, 0.0);
    f.real(44, 297.0);
    f.real(45, 210.0);
    for (int code : {46, 47, 48, 49, 140, 141}) f.real(code, 0.0);
    f.real(142, 1.0);
    f.real(143, 1.0);
    f.tag(70, tab == 0 ? 1024 : 0);
    f.tag(72, 1);
    f.tag(73, 0);
    f.tag(74, 5);
    f.tag(7, "");
    f.tag(75, 16);
    f.real(147, 1.0);
    f.real(148, 0.0);
    f.real(149, 0.0);
    f.tag(100, "AcDbLayout");
    f.tag(1, name);
    f.tag(70, 1);
    f.tag(71, tab);
    f.real(10, 0.0);
    f.real(20, 0.0);
    f.real(11, 297.0);
    f.real(21, 210.0);
    f.point(Vec2::Zero(), 12);
    f.point(box.lo, 14);
    f.point(box.hi, 15);
    f.real(146, 0.0);
    f.point(Vec2::Zero(), 13);
    f.real(16, 1.0);
    f.real(26, 0.0);
    f.real(36, 0.0);
    f.real(17, 0.0);
    f.real(27, 1.0);
    f.real(37, 0.0);
    f.tag(76, 0);
    f.handle(330, owner);
  }
  f.tag(0, "ENDSEC");
  f.tag(0, "EOF");
  return std::move(f.out());
}

}  // namespace

Exporter make_dxf_exporter() {
  return {"dxf",
          {"flat.dxf"},
          "flat.dxf: flat pattern (outline, threads, base path, origin, shear warnings, labels)",
          [](const ExportContext& ctx, const std::string& outdir) {
            return write_file_atomic((std::filesystem::path(outdir) / "flat.dxf").string(),
                                     build_dxf(ctx));
          }};
}

}  // namespace plyfit::exporters
