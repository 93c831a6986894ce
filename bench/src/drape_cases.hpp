#pragma once
// Drape setups shared by the drape benchmarks (throughput, tolerance, convergence, hard
// cases): faces, problems with their initial conditions, timed runs with memory figures, and
// the net's constraint errors measured from the nodes.

#include <plyfit/kernel/result.hpp>
#include "drape/drape.hpp"
#include "surface/face.hpp"

#include "support/problems.hpp"

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace plyfit::bench {

/// Folder of the shared CAD files (../shared next to the source tree, or $PLYFIT_SHARED).
std::string shared_dir();

using FacePtr = std::shared_ptr<const Face>;
/// A built-in mold's face.
Result<FacePtr> builtin_face(const std::string& name, const std::map<std::string, double>& params);
/// Face `index` of a file in shared_dir().
Result<FacePtr> cad_face(const std::string& file, int index);
/// A face from surface data and optional trim loops.
Result<FacePtr> data_face(NurbsSurfaceData surface, std::vector<TrimLoop> loops = {});

/// A drape problem with square spacing d, 2D start s2, 2D base direction b2, 2D sweeps w2 and
/// the 3D start s3, base-plane normal bn and 3D sweeps w3 (the tests' builder).
using support::problem;
/// A problem for any face: the start at the contained sample nearest to the middle of the
/// face's samples, the base path along Su there (the base plane holds Su and the normal),
/// swept both ways across it (or one way).
Result<DrapeProblem> middle_problem(const Face& f, double d, bool both_sides = true);
/// Spacing at which the face holds about `nodes` mesh points: sqrt(area / nodes).
double spacing_for_nodes(const Face& f, double nodes);

/// One drape with what it cost.
struct DrapeRun {
  DrapeResult result;
  double seconds = 0.0;          ///< wall time of drape()
  std::size_t peak_heap = 0;     ///< peak heap bytes held during drape() above the start
  double peak_rss_bytes = -1.0;  ///< peak RSS growth during drape(), -1 if unavailable
};
/// Runs drape() once, timed, with the heap counter's and RSS's peaks. `cold`: first frees
/// the scratch a previous drape left the thread (release_drape_scratch()), so that the peaks
/// are a first drape's, scratch included; else the drape reuses it, as in optimize.
Result<DrapeRun> run_drape(const Face& f, const DrapeProblem& pb, const DrapeOptions& opt,
                           bool cold = false);
/// Median wall time of `runs` (>= kMinRuns) drapes, seconds; the first run (cold) gives its
/// result and memory figures in `first`.
Result<double> median_drape_time(const Face& f, const DrapeProblem& pb, const DrapeOptions& opt,
                                 int runs, DrapeRun* first);

/// Mapped nodes, regular and auxiliary: the nodes of the net.
inline std::uint64_t net_nodes(const DrapeResult& r) {
  return r.metrics.nodes.mapped + r.metrics.nodes.auxiliary;
}

/// Constraint errors of a net, measured from its nodes (not from the solvers' residuals).
struct NetErrors {
  double link_rel = 0.0;        ///< max | |p_a - p_b| - rest | / d over links of mapped nodes
  double base_plane_rel = 0.0;  ///< max distance of mapped path nodes from the base plane / d
  double surface_rel = -1.0;    ///< max distance of mapped nodes from the surface / d (-1: not
                                ///< measured)
  double max_shear = 0.0;       ///< max |pi/2 - gamma| over nodes with a thread angle
};
/// Link, base-plane and shear figures; the surface distance if `distance` is given (called
/// with each mapped node's point and (u, v) as a seed).
NetErrors net_errors(const DrapeResult& r,
                     const std::function<double(const Vec3&, const Vec2&)>& distance = {});

/// Prints "plyfit-bench: WHAT: the error's text" on stderr.
void print_error(const std::string& what, const Error& e);

/// True when `r` failed: its error printed (print_error) and `ok` cleared.
template <typename T>
bool failed(const Result<T>& r, const std::string& what, bool& ok) {
  if (r) return false;
  print_error(what, r.error());
  ok = false;
  return true;
}

/// "complete" or "partial (warnings...)".
std::string drape_status(const DrapeResult& r);

}  // namespace plyfit::bench
