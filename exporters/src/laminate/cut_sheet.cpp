// cut.dxf: a laminate's cut outlines on one roll. The roll runs along +y, the warp direction of
// every ply's flat pattern, so the grain is kept by never turning a piece (a 180 degree turn,
// the only one a woven ply allows, leaves a piece's box as it is and gains a shelf packing
// nothing). Pieces go in stacking order onto shelves across the roll: a piece that does not fit
// beside the last one on its shelf starts the next shelf above the tallest piece of this one.
// Layers: ROLL (the roll's two edges), then one per ply, named after it, holding its outline,
// holes, grain arrow and labels (name and sequence, angle, material). A ply split for its roll
// is cut as its pieces, each a part of its own on a layer named after it (ply name + letter).

#include <plyfit/exporters/laminate.hpp>

#include "dxf/document.hpp"
#include "dxf/labels.hpp"
#include "net_util.hpp"
#include "render/label_placement.hpp"
#include "render/text.hpp"

#include <algorithm>

namespace plyfit::exporters {

namespace {

using detail::Box2;

// The label text is at most this fraction of the piece's extent high.
constexpr double kMaxTextRel = 1.0 / 20.0;
constexpr const char* kRollLayer = "ROLL";
// A part fits across the roll to within this fraction of its width: the rounding of its
// coordinates (a piece spliced to the roll's width less the margins comes out that wide, to
// the last digits).
constexpr double kFitRel = 1e-9;
// ACI colours the plies' layers cycle through (red, yellow, green, cyan, blue, magenta).
constexpr int kPlyColours[] = {1, 2, 3, 4, 5, 6};

// What is cut: a ply, or each piece of a ply split for the roll.
struct Part {
  std::size_t ply;
  int piece;
  const std::string& name;
  const std::vector<OutlineLoop>& loops;
};

std::vector<Part> parts_of(const Plybook& book) {
  std::vector<Part> parts;
  for (std::size_t k = 0; k < book.plies.size(); ++k) {
    const PlySheet& p = book.plies[k];
    if (p.pieces.empty()) parts.push_back({k, -1, p.name, p.cut});
    for (std::size_t i = 0; i < p.pieces.size(); ++i)
      parts.push_back({k, static_cast<int>(i), p.pieces[i].name, p.pieces[i].loops});
  }
  return parts;
}

// The parts' places: shelves across the roll from x = gap to roll_width - gap.
std::vector<CutPlace> shelf_pack(const Plybook& book, const std::vector<Part>& parts,
                                 CutSheet& sheet) {
  const double w = book.roll_width, gap = kCutGapRel * w;
  std::vector<CutPlace> places;
  double x = gap, shelf_y = gap, shelf_h = 0.0;
  for (const Part& p : parts) {
    Box2 box;
    box.add(p.loops);
    if (box.empty()) continue;
    const Vec2 size = box.size();
    const double room = (w - 2.0 * gap) * (1.0 + kFitRel);
    if (size.x() > room) {
      sheet.left_out.push_back(Error{ErrorCode::kPieceWiderThanRoll, p.name, {size.x(), w}});
      continue;
    }
    if (x - gap + size.x() > room) {
      shelf_y += shelf_h + gap;
      x = gap;
      shelf_h = 0.0;
    }
    CutPlace c;
    c.ply = p.ply;
    c.piece = p.piece;
    c.lo = Vec2(x, shelf_y);
    c.hi = c.lo + size;
    c.offset = c.lo - box.lo;
    places.push_back(c);
    x += size.x() + gap;
    shelf_h = std::max(shelf_h, size.y());
  }
  sheet.length = places.empty() ? 0.0 : shelf_y + shelf_h + gap;
  return places;
}

std::vector<OutlineLoop> moved(const std::vector<OutlineLoop>& loops, const Vec2& offset) {
  std::vector<OutlineLoop> out = loops;
  for (auto& l : out)
    for (auto& p : l.points) p += offset;
  return out;
}

// The name of a placed part: its ply's, or its piece's.
const std::string& part_name(const Plybook& book, const CutPlace& c) {
  const PlySheet& p = book.plies[c.ply];
  return c.piece < 0 ? p.name : p.pieces[static_cast<std::size_t>(c.piece)].name;
}

// A placed part: its loops and its label block, all on its own layer.
void add_piece(dxf::Writer& e, const PlySheet& p, const CutPlace& c) {
  const bool whole = c.piece < 0;
  const std::string& name = whole ? p.name : p.pieces[static_cast<std::size_t>(c.piece)].name;
  const std::vector<OutlineLoop> loops =
      moved(whole ? p.cut : p.pieces[static_cast<std::size_t>(c.piece)].loops, c.offset);
  for (const auto& l : loops) e.polyline(name.c_str(), l.points, true);
  const std::string seq = std::to_string(p.sequence);
  const std::vector<std::string> lines = {
      whole ? "PLY: " + p.name + " (SEQ " + seq + ")"
            : "PIECE: " + name + " (PLY " + p.name + ", SEQ " + seq + ")",
      "ANGLE: " + render::degrees_text(p.angle_deg, 2), "MATERIAL: " + p.material};
  const render::BlockShape shape = dxf::label_shape(lines);
  const double extent = std::max(c.hi.x() - c.lo.x(), c.hi.y() - c.lo.y());
  const render::BlockPlace place =
      render::place_block(loops, shape, extent, kMaxTextRel * extent, c.lo);
  dxf::add_labels(e, lines, shape, place, name.c_str(), name.c_str());
}

}  // namespace

CutSheet cut_sheet(const Plybook& book) {
  CutSheet sheet;
  sheet.places = shelf_pack(book, parts_of(book), sheet);
  std::vector<dxf::Layer> layers = {{"0", 7}, {kRollLayer, 8}};
  for (std::size_t k = 0; k < sheet.places.size(); ++k)
    layers.push_back({part_name(book, sheet.places[k]),
                      kPlyColours[k % (sizeof(kPlyColours) / sizeof(kPlyColours[0]))]});
  dxf::Writer e(dxf::first_entity_handle(layers));
  const double w = book.roll_width, len = std::max(sheet.length, kCutGapRel * w);
  e.line(kRollLayer, Vec2(0.0, 0.0), Vec2(0.0, len));
  e.line(kRollLayer, Vec2(w, 0.0), Vec2(w, len));
  double text_h = kCutGapRel * w;
  for (const auto& c : sheet.places) {
    add_piece(e, book.plies[c.ply], c);
    text_h = std::min(text_h, kMaxTextRel * std::max(c.hi.x() - c.lo.x(), c.hi.y() - c.lo.y()));
  }
  dxf::DocumentInfo info;
  info.lo = Vec2::Zero();
  info.hi = Vec2(w, len);
  info.text_height = text_h;
  info.layers = std::move(layers);
  sheet.dxf = dxf::document(e, info);
  return sheet;
}

}  // namespace plyfit::exporters
