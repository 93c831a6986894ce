// splice_pattern: the fewest pieces no wider than the roll, their seams placed on the least
// sheared cloth (docs/decisions/splices.md), the pieces cut from the outline by the polygon
// layer and carried onto the mold.

#include <plyfit/kernel/splice.hpp>

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>

namespace plyfit {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

Status check_splice_options(const SpliceOptions& o, double d_weft) {
  const std::pair<const char*, double> values[] = {
      {"roll-width", o.roll_width}, {"splice-overlap", o.overlap}, {"splice-stagger", o.stagger}};
  for (const auto& [key, v] : values)
    if (!std::isfinite(v)) return Error{ErrorCode::kSpliceValueNotFinite, key, {std::string(key)}};
  if (o.roll_width < 2.0 * d_weft)
    return Error{ErrorCode::kRollNarrowerThanCells, "roll-width", {o.roll_width, 2.0 * d_weft}};
  if (o.overlap < 0.0)
    return Error{ErrorCode::kSpliceOverlapNegative, "splice-overlap", {o.overlap}};
  if (o.overlap > o.roll_width - d_weft)
    return Error{
        ErrorCode::kSpliceOverlapTooWide, "splice-overlap", {o.overlap, o.roll_width, d_weft}};
  if (o.stagger < 0.0)
    return Error{ErrorCode::kSpliceStaggerNegative, "splice-stagger", {o.stagger}};
  return ok_status();
}

namespace {

// Shear of the nodes on each warp thread i (mapped nodes with a thread angle).
struct ColumnShear {
  double max = 0.0, sum = 0.0;
  std::int64_t count = 0;
};

std::map<std::int32_t, ColumnShear> column_shear(const DrapeResult& r) {
  std::map<std::int32_t, ColumnShear> cols;
  for (const DrapeNode& n : r.nodes) {
    if (!n.mapped() || n.id.is_path_only() || !n.has(DrapeNode::kHasAngle)) continue;
    const double s = std::abs(kPi / 2 - n.thread_angle);
    ColumnShear& c = cols[n.id.i];
    c.max = std::max(c.max, s);
    c.sum += s;
    ++c.count;
  }
  return cols;
}

// Where the line x = s crosses the cut outline: each crossing's y and its point on the mold
// (linear along the outline edge, as the cut outline's own chords are).
struct Crossing {
  double y;
  Vec3 p3;
};

std::vector<Crossing> crossings(const std::vector<OutlineLoop>& loops, double s) {
  std::vector<Crossing> out;
  for (const OutlineLoop& l : loops)
    for (std::size_t k = 0, n = l.points.size(); k < n; ++k) {
      const Vec2 &a = l.points[k], &b = l.points[(k + 1) % n];
      if ((a.x() > s) == (b.x() > s)) continue;  // half-open: a vertex on the line counts once
      const double t = (s - a.x()) / (b.x() - a.x());
      out.push_back({a.y() + t * (b.y() - a.y()),
                     l.points3d[k] + t * (l.points3d[(k + 1) % n] - l.points3d[k])});
    }
  std::sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) { return a.y < b.y; });
  return out;
}

// The point of the warp line x = s on weft thread j, between the draped nodes (i, j) and
// (i + 1, j) of the threads round it; false where one is not mapped.
bool seam_point(const DrapeResult& r, double d_weft, double s, std::int32_t j, Vec3& p) {
  const double u = s / d_weft;
  const auto i = static_cast<std::int32_t>(std::floor(u));
  const double t = u - i;
  const DrapeNode* a = r.find(NodeId::regular(i, j));
  if (!a || !a->mapped()) return false;
  if (t == 0.0) {
    p = a->point;
    return true;
  }
  const DrapeNode* b = r.find(NodeId::regular(i + 1, j));
  if (!b || !b->mapped()) return false;
  p = (1.0 - t) * a->point + t * b->point;
  return true;
}

// The points of the warp line x = s on the mold strictly between y0 and y1 (either order), at
// the weft threads, in order from y0 to y1.
std::vector<Vec3> seam_run(const DrapeResult& r, double s, double y0, double y1) {
  const double dx = r.ply->spec().d_weft, dy = r.ply->spec().d_warp;
  std::vector<Vec3> out;
  const double lo = std::min(y0, y1), hi = std::max(y0, y1);
  for (auto j = static_cast<std::int32_t>(std::floor(lo / dy)) + 1; j * dy < hi; ++j) {
    Vec3 p;
    if (j * dy > lo && seam_point(r, dx, s, j, p)) out.push_back(p);
  }
  if (y1 < y0) std::reverse(out.begin(), out.end());
  return out;
}

double polyline_length(const std::vector<Vec3>& p) {
  double l = 0.0;
  for (std::size_t k = 1; k < p.size(); ++k) l += (p[k] - p[k - 1]).norm();
  return l;
}

// The seam x = s: its stretches inside the outline on the mold, lengths and shear.
Seam make_seam(const FlatPattern& flat, const DrapeResult& r,
               const std::map<std::int32_t, ColumnShear>& cols, double s) {
  Seam seam;
  seam.x = s;
  const auto cr = crossings(flat.cut, s);
  for (std::size_t k = 0; k + 1 < cr.size(); k += 2) {
    // Points closer than the outline's merge distance are one (a crossing on a weft thread).
    const double merge = r.ply->d() * Tolerances{}.outline_merge_rel;
    std::vector<Vec3> line{cr[k].p3};
    auto add = [&](const Vec3& p) {
      if ((p - line.back()).norm() > merge) line.push_back(p);
    };
    for (const Vec3& p : seam_run(r, s, cr[k].y, cr[k + 1].y)) add(p);
    add(cr[k + 1].p3);
    seam.length += cr[k + 1].y - cr[k].y;
    seam.length3d += polyline_length(line);
    seam.polylines.push_back(std::move(line));
  }
  const auto i = static_cast<std::int32_t>(std::floor(s / r.ply->spec().d_weft));
  double sum = 0.0;
  std::int64_t count = 0;
  for (std::int32_t c : {i, i + 1})
    if (const auto it = cols.find(c); it != cols.end()) {
      seam.shear_max = std::max(seam.shear_max, it->second.max);
      sum += it->second.sum;
      count += it->second.count;
    }
  seam.shear_mean = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return seam;
}

// The extent of the cut outline across the warp.
std::pair<double, double> x_extent(const std::vector<OutlineLoop>& loops) {
  double lo = kInf, hi = -kInf;
  for (const OutlineLoop& l : loops)
    for (const Vec2& p : l.points) {
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
  return {lo, hi};
}

// The chain of `seams` candidates (indices 1 .. n_cand - 1 of a grid whose 0 is the pattern's
// left edge) with consecutive indices at most `reach` apart, the first within `reach` of 0 and
// the last at least `min_last`, minimising the combination (max or sum) of the candidates'
// costs; on equal cost the rightmost. Candidates with allowed[c] false are skipped. Empty when
// there is no chain.
std::vector<int> best_chain(int seams, int n_cand, int reach, int min_last,
                            const std::vector<std::int64_t>& cost, const std::vector<bool>& allowed,
                            bool use_max) {
  constexpr std::int64_t kNone = std::numeric_limits<std::int64_t>::max();
  const auto rows = static_cast<std::size_t>(seams) + 1;
  const auto width = static_cast<std::size_t>(n_cand) + 1;
  std::vector<std::vector<std::int64_t>> best(rows, std::vector<std::int64_t>(width, kNone));
  std::vector<std::vector<int>> from(rows, std::vector<int>(width, -1));
  best[0][0] = 0;
  for (std::size_t k = 1; k < rows; ++k) {
    const auto& prev = best[k - 1];
    std::deque<int> window;  // candidates of the previous seam, increasing, costs increasing
    for (int c = 1; c < n_cand; ++c) {
      const int p = c - 1;
      if (prev[p] != kNone) {
        while (!window.empty() && prev[window.back()] >= prev[p]) window.pop_back();
        window.push_back(p);
      }
      while (!window.empty() && window.front() < c - reach) window.pop_front();
      if (window.empty() || !allowed[c]) continue;
      const std::int64_t before = prev[window.front()];
      best[k][c] = use_max ? std::max(before, cost[c]) : before + cost[c];
      from[k][c] = window.front();
    }
  }
  int end = -1;
  for (int c = std::max(1, min_last); c < n_cand; ++c)
    if (best[rows - 1][c] != kNone && (end < 0 || best[rows - 1][c] <= best[rows - 1][end]))
      end = c;
  if (end < 0) return {};
  std::vector<int> chain(rows - 1);
  for (std::size_t k = rows - 1; k >= 1; --k) {
    chain[k - 1] = end;
    end = from[k][end];
  }
  return chain;
}

// The seam positions: the fewest pieces, then the least largest shear crossed, then the least
// sum of mean shears, among candidates on a grid that holds the tightest chain exactly.
struct SeamChoice {
  std::vector<double> x;
  bool stagger_met = true;
};

SeamChoice choose_seams(const FlatPattern& flat, const DrapeResult& r, const SpliceOptions& o,
                        double x0, double x1) {
  const double d = r.ply->spec().d_weft;
  const double advance = o.roll_width - o.overlap;  // new cloth per piece
  const double span = x1 - o.overlap - x0;          // from the left edge to the last seam's end
  // Widths are compared to within the outline's own merge distance.
  const double slack = r.ply->d() * Tolerances{}.outline_merge_rel;
  const int pieces = static_cast<int>(std::ceil((span - slack) / advance));
  SeamChoice choice;
  if (pieces <= 1) return choice;
  // A grid that divides the advance: the tightest chain (seams one advance apart) lies on it.
  const int steps = static_cast<int>(std::ceil(advance / (o.candidate_step_rel * d)));
  const double h = advance / steps;
  const int n_cand = static_cast<int>(std::ceil((span - slack) / h));
  const int min_last = static_cast<int>(std::ceil((span - advance - slack) / h));
  const auto cols = column_shear(r);
  const auto size = static_cast<std::size_t>(n_cand) + 1;
  std::vector<std::int64_t> qmax(size, 0), qmean(size, 0);
  std::vector<bool> all(size, true), apart(size, true);
  for (int c = 1; c < n_cand; ++c) {
    const Seam s = make_seam(flat, r, cols, x0 + c * h);
    qmax[c] = std::llround(s.shear_max / o.shear_step);
    qmean[c] = std::llround(s.shear_mean / o.shear_step);
    if (!o.avoid.empty() && o.stagger > 0.0)
      apart[c] = polyline_distance(s.polylines, o.avoid) >= o.stagger;
  }
  auto solve = [&](const std::vector<bool>& allowed) {
    const auto worst = best_chain(pieces - 1, n_cand, steps, min_last, qmax, allowed, true);
    if (worst.empty()) return worst;
    std::int64_t m = 0;
    for (int c : worst) m = std::max(m, qmax[c]);
    std::vector<bool> low = allowed;
    for (int c = 1; c < n_cand; ++c) low[c] = low[c] && qmax[c] <= m;
    return best_chain(pieces - 1, n_cand, steps, min_last, qmean, low, false);
  };
  auto chain = solve(apart);
  if (chain.empty()) {
    chain = solve(all);
    choice.stagger_met = false;
  }
  for (int c : chain) choice.x.push_back(x0 + c * h);
  return choice;
}

// A loop of a piece: its points on the mold where the cut outline has them (its vertices, and
// along its edges where a seam crosses them), and along a seam (an edge on one of `lines`)
// the weft threads' points of the warp line between its ends, so that on the mold it follows
// the seam.
OutlineLoop piece_loop(const std::vector<ClipVertex>& ring, const FlatPattern& flat,
                       const DrapeResult& r, const std::vector<double>& lines) {
  OutlineLoop loop;
  const double dy = r.ply->spec().d_warp;
  for (std::size_t k = 0, n = ring.size(); k < n; ++k) {
    const ClipVertex &a = ring[k], &b = ring[(k + 1) % n];
    const auto& from = flat.cut[a.loop].points3d;
    loop.points.push_back(a.p);
    loop.points3d.push_back(from[a.edge] + a.t * (from[(a.edge + 1) % from.size()] - from[a.edge]));
    for (const double s : lines) {
      if (a.p.x() != s || b.p.x() != s) continue;
      std::vector<std::pair<double, Vec3>> run;
      const double lo = std::min(a.p.y(), b.p.y()), hi = std::max(a.p.y(), b.p.y());
      for (auto j = static_cast<std::int32_t>(std::floor(lo / dy)) + 1; j * dy < hi; ++j) {
        Vec3 p;
        if (j * dy > lo && seam_point(r, r.ply->spec().d_weft, s, j, p)) run.push_back({j * dy, p});
      }
      if (b.p.y() < a.p.y()) std::reverse(run.begin(), run.end());
      for (const auto& [y, p] : run) {
        loop.points.emplace_back(s, y);
        loop.points3d.push_back(p);
      }
      break;
    }
  }
  const double a = signed_area(loop.points);
  loop.hole = a < 0.0;
  loop.area = std::abs(a);
  for (std::size_t k = 0, n = loop.points.size(); k < n; ++k)
    loop.perimeter += (loop.points[(k + 1) % n] - loop.points[k]).norm();
  return loop;
}

// The piece of the cut outline between x = lo and x = hi (either may be infinite).
SplicePiece cut_piece(const FlatPattern& flat, const DrapeResult& r, double lo, double hi) {
  Region2 outline;
  for (const OutlineLoop& l : flat.cut) outline.push_back(l.points);
  SplicePiece piece;
  piece.x_min = kInf;
  piece.x_max = -kInf;
  std::vector<double> lines;
  for (const double x : {lo, hi})
    if (std::isfinite(x)) lines.push_back(x);
  for (const auto& ring : clip_to_slab(outline, lo, hi)) {
    OutlineLoop loop = piece_loop(ring, flat, r, lines);
    piece.area += loop.hole ? -loop.area : loop.area;
    for (const Vec2& p : loop.points) {
      piece.x_min = std::min(piece.x_min, p.x());
      piece.x_max = std::max(piece.x_max, p.x());
    }
    piece.loops.push_back(std::move(loop));
  }
  return piece;
}

}  // namespace

std::string piece_letter(std::size_t k) {
  std::string s;
  for (std::size_t n = k + 1; n > 0; n = (n - 1) / 26)
    s.insert(s.begin(), static_cast<char>('A' + (n - 1) % 26));
  return s;
}

double polyline_distance(const std::vector<std::vector<Vec3>>& a,
                         const std::vector<std::vector<Vec3>>& b) {
  auto to_segments = [](const Vec3& p, const std::vector<std::vector<Vec3>>& set) {
    double best = kInf;
    for (const auto& line : set)
      for (std::size_t k = 0; k < line.size(); ++k) {
        if (k + 1 == line.size()) {
          best = std::min(best, (p - line[k]).norm());
          continue;
        }
        const Vec3 e = line[k + 1] - line[k];
        const double ee = e.squaredNorm();
        const double t = ee > 0.0 ? std::clamp((p - line[k]).dot(e) / ee, 0.0, 1.0) : 0.0;
        best = std::min(best, (p - (line[k] + t * e)).norm());
      }
    return best;
  };
  double best = kInf;
  for (const auto& line : a)
    for (const Vec3& p : line) best = std::min(best, to_segments(p, b));
  for (const auto& line : b)
    for (const Vec3& p : line) best = std::min(best, to_segments(p, a));
  return best;
}

Result<SplicePlan> splice_pattern(const FlatPattern& flat, const DrapeResult& result,
                                  const SpliceOptions& options) {
  if (!result.ply) return Error{ErrorCode::kInternal};
  const double d_weft = result.ply->spec().d_weft;
  if (auto st = check_splice_options(options, d_weft); !st) return st.error();
  SplicePlan plan;
  plan.roll_width = options.roll_width;
  plan.overlap = options.overlap;
  plan.stagger = options.stagger;
  const auto [x0, x1] = x_extent(flat.cut);
  if (flat.cut.empty()) return plan;
  plan.pattern_width = x1 - x0;
  const SeamChoice choice = choose_seams(flat, result, options, x0, x1);
  plan.stagger_met = choice.stagger_met;
  const auto cols = column_shear(result);
  for (double s : choice.x) {
    Seam seam = make_seam(flat, result, cols, s);
    if (!options.avoid.empty())
      seam.stagger_distance = polyline_distance(seam.polylines, options.avoid);
    plan.seams.push_back(std::move(seam));
  }
  if (choice.x.empty()) {
    SplicePiece whole{options.ply_name + piece_letter(0), flat.cut, flat.cut_area, x0, x1};
    plan.pieces.push_back(std::move(whole));
    return plan;
  }
  // Piece k runs from seam k - 1 to seam k and o past it (the left piece of each seam laps
  // over the right one); the outer pieces reach past the pattern's edges.
  for (std::size_t k = 0; k <= choice.x.size(); ++k) {
    const double lo = k == 0 ? -kInf : choice.x[k - 1];
    const double hi = k == choice.x.size() ? kInf : choice.x[k] + options.overlap;
    SplicePiece piece = cut_piece(flat, result, lo, hi);
    piece.name = options.ply_name + piece_letter(k);
    plan.pieces.push_back(std::move(piece));
  }
  return plan;
}

}  // namespace plyfit
