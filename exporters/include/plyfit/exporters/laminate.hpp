#pragma once
/// \file A laminate's shop documents (plyfit laminate): the ply book (plybook.html, .json,
/// .csv: every ply in stacking order with its figures, warnings, files and pictures) and the
/// cut drawing (cut.dxf: every ply's cut outline on one roll).

#include <plyfit/kernel/flat_pattern.hpp>
#include <plyfit/kernel/result.hpp>

#include <string>
#include <vector>

namespace plyfit::exporters {

/// A piece of a ply split for the roll (kernel SplicePiece), as the shop documents show it.
struct PieceSheet {
  std::string name;  ///< ply name + letter; its cut.dxf layer
  double area = 0.0;
  double width = 0.0;              ///< across the warp
  std::vector<OutlineLoop> loops;  ///< ply coordinates
};

/// A seam between two pieces of a ply.
struct SeamSheet {
  double x = 0.0;                ///< ply coordinate across the warp
  double stagger_distance = -1;  ///< to the nearest seam of the plies below of its direction
};

/// One ply of a laminate as its shop documents show it.
struct PlySheet {
  long sequence = 0;
  std::string name;        ///< also its folder and its cut.dxf layer
  double angle_deg = 0.0;  ///< the ply angle as given
  std::string material;    ///< the material's label
  std::string status;      ///< ok, partial, error, cancelled
  std::string error;       ///< for status error: its text
  std::string error_code;  ///< and its code
  double flat_area = 0.0;  ///< the cut outline's area, mm^2
  double shear_max_deg = 0.0;
  std::vector<Warning> warnings;
  std::vector<std::string> files;  ///< the files in its folder
  std::vector<OutlineLoop> cut;    ///< the cut outline, ply coordinates (warp along +y)
  /// A ply split for its roll: its pieces (each its own part in cut.dxf) and seams; empty: one
  /// piece, `cut`.
  std::vector<PieceSheet> pieces;
  std::vector<SeamSheet> seams;
  double splice_stagger = 0.0;  ///< the stagger its seams were to keep (mm)
  bool stagger_met = true;
};

/// A laminate's plies in stacking order.
struct Plybook {
  std::string laminate;  ///< the laminate file as given
  double roll_width = 0.0;
  std::vector<PlySheet> plies;
};

/// plybook.json: the laminate and its plies (no timings: equal runs give equal bytes).
std::string plybook_json(const Plybook& book);
/// plybook.csv: a row per ply.
std::string plybook_csv(const Plybook& book);
/// plybook.html: one self-contained page (inline style and SVG, no script, no link out but to
/// the plies' files): the table of plies, then per ply its flat.svg and shear.svg read from
/// `dir`/NAME/ (and view.svg, the 3D view, when the ply's folder has one).
std::string plybook_html(const Plybook& book, const std::string& dir);

/// Where a ply's cut outline lies on the roll: its outline moved by `offset` (never turned: a
/// woven ply may only be turned by 180 degrees, which leaves its box as it is).
struct CutPlace {
  std::size_t ply = 0;  ///< index in Plybook::plies
  int piece = -1;       ///< index in its PlySheet::pieces; -1: the whole ply
  Vec2 offset = Vec2::Zero();
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  ///< its box on the roll
};

/// The cut drawing: the roll runs along +y (the warp, every ply's grain kept), its edges at
/// x = 0 and x = roll_width; outlines shelf-packed across it in stacking order.
struct CutSheet {
  std::string dxf;               ///< cut.dxf
  std::vector<CutPlace> places;  ///< the plies placed
  double length = 0.0;           ///< roll used, mm
  std::vector<Error> left_out;   ///< parts not drawn (piece_wider_than_roll), input = name
};
/// Gap between pieces and from the roll's edges, as a fraction of the roll's width.
constexpr double kCutGapRel = 0.01;
CutSheet cut_sheet(const Plybook& book);

/// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s);

}  // namespace plyfit::exporters
