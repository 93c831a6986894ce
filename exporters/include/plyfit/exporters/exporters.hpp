#pragma once
/// \file Output writers: a registry of one-file plugins keyed by lower-case extension
/// (json, dxf, step, svg, vtk, glb). Each writes its files into an output folder, atomically.

#include <plyfit/kernel/drape.hpp>
#include <plyfit/kernel/mold.hpp>
#include <plyfit/kernel/result.hpp>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace plyfit {
struct FlatPattern;  // kernel/flat_pattern.hpp
struct SplicePlan;   // kernel/splice.hpp
}  // namespace plyfit

namespace plyfit::exporters {

/// Inputs of a run that are not part of the DrapeProblem, echoed in the report.
struct RunInfo {
  std::string mold;  ///< file path or "builtin:..." as given
  /// The faces draped, by their index in the mold file: one face, or the faces of a shell
  /// in the order of the surface's faces (DrapeNode::face, DrapeMetrics::faces).
  std::vector<int> faces;
  /// What the mold says about each of them.
  std::vector<FaceInfo> faces_info;
  std::string mold_unit;  ///< the file's unit (geometry is in mm)
  bool flip_normal = false;
  double tolerance_rel = 0;  ///< Newton tolerance relative to d
  int max_iterations = 0;
  double lock_angle_deg = 90;
  double warn_angle_deg = 0;            ///< as given (or the material's), echoed in report.json
  std::string guess = "paper";          ///< initial-guess rule of the two-sphere solver
  std::uint64_t max_nodes = 0;          ///< node cap
  std::string ply_name;                 ///< for labels
  std::string material;                 ///< for labels
  std::string seed_curve_file;          ///< --seed-curve FILE[:PICK] (SeedCurve::kCurve)
  std::vector<std::string> dart_files;  ///< --dart FILE[:PICK], each as given
  double import_ms = 0, drape_ms = 0, total_ms = 0;
  std::vector<std::string> outputs;  ///< exporter keys being written
  std::vector<Warning> warnings;     ///< the mold's (Mold::warnings: reading, listing, sewing it)
};

/// The ply a drape laid (report.json `ply`): how it was defined and the frame measured on the
/// drape at its start.
/// A ply's boundary as report.json and net.step give it.
struct BoundaryReport {
  std::string source;                    ///< the curve file (and the curves picked)
  double offset = 0.0;                   ///< mm along the surface
  double area = 0.0;                     ///< the region's area on the mold, mm^2
  std::vector<std::vector<Vec3>> loops;  ///< the loops on the mold (each closes on itself)
  std::vector<double> lengths;           ///< their lengths, mm
};

struct PlyReport {
  bool from_seed = false;        ///< defined by seed, rosette and angle (else the start keys)
  Vec3 seed = Vec3::Zero();      ///< the seed as given (from_seed)
  Vec3 rosette = Vec3::UnitX();  ///< the 0 deg direction as given
  double angle_deg = 0.0;        ///< the ply angle as given
  std::string seed_curve = "plane";
  Vec3 point = Vec3::Zero();               ///< the start (the seed on the mold)
  Vec3 normal = Vec3::UnitZ();             ///< the outward normal there
  Vec3 zero = Vec3::UnitX();               ///< the rosette's 0 deg direction on the surface there
  Vec3 warp = Vec3::UnitY();               ///< the warp fibres there, as laid
  Vec3 weft = Vec3::UnitX();               ///< the weft fibres there, as laid
  double laid_angle_deg = 0.0;             ///< the warp's angle from `zero`, as laid
  std::optional<BoundaryReport> boundary;  ///< the ply's boundary, if it has one
};

/// Options of the writers.
struct ExportOptions {
  /// Cells whose shear exceeds this (radians) go to the DXF SHEAR_WARN layer and are flagged
  /// in the pictures; default: 25 degrees, the warning angle of plyfit's default material.
  double warn_shear = 0.43633231299858238;
  bool dxf_threads = false;      ///< THREADS layer in flat.dxf (a cutter would cut it)
  int curve_degree = 1;          ///< net.step thread curves: 1 (polyline) or 3 (interpolated)
  Vec3 view = Vec3(1, 1, 1);     ///< drape.svg view direction (towards the viewer)
  double ply_angle_deg = 0.0;    ///< the ply's fibre direction on the part (labels, report)
  std::optional<PlyReport> ply;  ///< the ply as laid (report.json `ply`); none: not written
  std::string material_label;    ///< the material's label text; empty: RunInfo::material
  std::string materials_file;    ///< the materials table used; empty: plyfit's own
};

/// Everything a writer may use.
struct ExportContext {
  const DrapeProblem& problem;
  const DrapeResult& result;
  const MoldSurface& surface;  ///< one face or a shell
  const FlatPattern* flat;     ///< may be null
  const RunInfo& run;
  const ExportOptions& options;
  /// The pieces and seams of a flat pattern split for the roll (SplicePlan::split()); null:
  /// the pattern is one piece.
  const SplicePlan* splices = nullptr;
};

/// A registered writer.
struct Exporter {
  std::string key;                 ///< e.g. "json"
  std::vector<std::string> files;  ///< the files it writes into the output folder
  std::string description;
  std::function<Status(const ExportContext&, const std::string& outdir)> write;
};

/// All writers, in registration order.
const std::vector<Exporter>& registry();
/// Writer for a key (case-insensitive), or nullptr.
const Exporter* find_exporter(const std::string& key);
/// Comma-separated keys, for messages.
std::string supported_keys();

/// Writes the selected outputs (keys) into outdir (created if missing). Stops at the first
/// failure; files already written stay (each is whole).
Status write_outputs(const ExportContext& ctx, const std::string& outdir,
                     const std::vector<std::string>& keys);

/// The report as a JSON string (what report.json holds); also used by batch summaries.
std::string report_json(const ExportContext& ctx);

}  // namespace plyfit::exporters
