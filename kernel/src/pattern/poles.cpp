// Poles of the boundary (its collapsed edges) and the boundary near them as short 3D pieces:
// near a pole a straight (u, v) segment is an arc about it, so edges there are clipped in
// tangent planes against these pieces (edge_crossings.cpp).

#include "pattern/grid_keys.hpp"
#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

namespace {

// Near a pole the boundary is taken as 3D pieces: each boundary segment is split until its
// pieces are at most kPieceLength spacings long and their chords within kPieceSagitta
// spacings of the curve in the middle, up to kPieceMaxDepth halvings.
constexpr double kPieceLength = 0.5;
constexpr double kPieceSagitta = 1e-4;
constexpr int kPieceMaxDepth = 40;

}  // namespace

// The poles of the boundary (its collapsed segments' points, 3D).
void OutlineBuilder::find_poles() {
  const double same = st_.tol.roundoff_rel * s_.size() * 16;
  for (const auto& b : boundary_)
    for (std::size_t k = 0; k < b.points.size(); ++k) {
      if (b.kinds[k] != BoundaryLoop::kCollapsed) continue;
      const SurfaceEval1 e = s_.eval1(b.points[k]);
      if (!e.ok) continue;
      bool known = false;
      for (const Vec3& p : poles_) known = known || (p - e.p).norm() <= same;
      if (known) continue;
      poles_.push_back(e.p);
      const SurfaceNormal nn = s_.normal(s_.wrap(b.points[k]));
      pole_normals_.push_back(nn.ok ? nn.n : Vec3::Zero());
    }
}

// The pole nearest p within kPolarSpacings spacings whose normal is known, or -1.
int OutlineBuilder::nearest_pole(const Vec3& p) const {
  double best = kPolarSpacings * dmax_;
  int out = -1;
  for (std::size_t q = 0; q < poles_.size(); ++q)
    if (const double dq = (poles_[q] - p).norm();
        dq <= best && pole_normals_[q].squaredNorm() > 0.0) {
      best = dq;
      out = static_cast<int>(q);
    }
  return out;
}

// True when p lies within kPolarSpacings spacings of a pole.
bool OutlineBuilder::near_pole(const Vec3& p) const {
  const double r = kPolarSpacings * dmax_;
  for (const Vec3& q : poles_)
    if ((p - q).squaredNorm() <= r * r) return true;
  return false;
}

// 3D point of vertex k of boundary loop l (evaluated once).
const Vec3& OutlineBuilder::loop_point(int l, int k) {
  if (loop3d_.empty()) {
    loop3d_.resize(boundary_.size());
    for (std::size_t i = 0; i < boundary_.size(); ++i)
      loop3d_[i].assign(boundary_[i].points.size(), Vec3::Constant(NAN));
  }
  Vec3& p = loop3d_[static_cast<std::size_t>(l)][static_cast<std::size_t>(k)];
  if (std::isnan(p.x())) {
    const SurfaceEval1 e = s_.eval1(
        s_.wrap(boundary_[static_cast<std::size_t>(l)].points[static_cast<std::size_t>(k)]));
    p = e.ok ? e.p : Vec3::Zero();
  }
  return p;
}

// Location at parameter s of boundary segment (l, k) (both ends on one face).
SurfaceLocation OutlineBuilder::segment_point(int l, int k, double s) const {
  const auto& L = boundary_[static_cast<std::size_t>(l)].points;
  const SurfaceLocation& a = L[static_cast<std::size_t>(k)];
  const SurfaceLocation& b = L[(static_cast<std::size_t>(k) + 1) % L.size()];
  return a.with_uv(a.uv + s * s_.delta(a, b));
}

// Splits boundary segment (l, k) into 3D pieces (see kPieceLength, kPieceSagitta) and
// appends them to `out`; spans for which keep(centre, radius) is false are dropped unsplit.
template <class Keep>
void OutlineBuilder::subdivide(int l, int k, Keep&& keep, std::vector<Piece>& out) const {
  const double max_len = kPieceLength * dmax_, max_sag = kPieceSagitta * dmax_;
  auto point = [&](double s) {
    const SurfaceEval1 e = s_.eval1(s_.wrap(segment_point(l, k, s)));
    return e.ok ? e.p : Vec3(NAN, NAN, NAN);
  };
  struct Span {
    double s0, s1;
    Vec3 a, b;
    int depth;
  };
  std::vector<Span> stack{{0.0, 1.0, point(0.0), point(1.0), 0}};
  while (!stack.empty()) {
    const Span sp = stack.back();
    stack.pop_back();
    const double sm = 0.5 * (sp.s0 + sp.s1);
    const Vec3 m = point(sm);
    if (!sp.a.allFinite() || !sp.b.allFinite() || !m.allFinite()) continue;
    const double len = (sp.b - sp.a).norm(), sag = (m - 0.5 * (sp.a + sp.b)).norm();
    if (!keep(m, 0.5 * len + sag)) continue;
    if ((len <= max_len && sag <= max_sag) || sp.depth >= kPieceMaxDepth) {
      out.push_back({sp.a, sp.b, l, k, sp.s0, sp.s1});
      continue;
    }
    stack.push_back({sm, sp.s1, m, sp.b, sp.depth + 1});
    stack.push_back({sp.s0, sm, sp.a, m, sp.depth + 1});
  }
}

// True when boundary segment k of loop l is a free edge on one face.
bool OutlineBuilder::real_segment(int l, int k) const {
  const auto& B = boundary_[static_cast<std::size_t>(l)];
  return B.kinds[static_cast<std::size_t>(k)] == BoundaryLoop::kEdge &&
         B.points[static_cast<std::size_t>(k)].face ==
             B.points[(static_cast<std::size_t>(k) + 1) % B.points.size()].face;
}

// The boundary near the poles as short 3D pieces, in a uniform grid of cells of
// kPolarSpacings spacings (built on first use).
void OutlineBuilder::build_pieces() {
  if (pieces_built_) return;
  pieces_built_ = true;
  const double reach = (kPolarSpacings + 2.0) * dmax_;
  auto near = [&](const Vec3& c, double rad) {
    for (const Vec3& q : poles_)
      if ((c - q).norm() - rad <= reach) return true;
    return false;
  };
  for (int l = 0; l < static_cast<int>(boundary_.size()); ++l)
    for (int k = 0; k < static_cast<int>(boundary_[static_cast<std::size_t>(l)].points.size()); ++k)
      if (real_segment(l, k)) subdivide(l, k, near, pieces_);
  grid_cell_ = kPolarSpacings * dmax_;
  for (int k = 0; k < static_cast<int>(pieces_.size()); ++k) {
    const Piece& pc = pieces_[static_cast<std::size_t>(k)];
    for_grid_cells(pc.a.cwiseMin(pc.b), pc.a.cwiseMax(pc.b), grid_cell_,
                   [&](std::uint64_t key) { piece_grid_[key].push_back(k); });
  }
}

// The pieces of boundary segment (l, k), all of it (split on first use).
const std::vector<OutlineBuilder::Piece>& OutlineBuilder::segment_pieces(int l, int k) {
  const std::uint64_t key = (static_cast<std::uint64_t>(l) << 32) | static_cast<std::uint32_t>(k);
  auto it = segment_pieces_.find(key);
  if (it == segment_pieces_.end()) {
    std::vector<Piece> v;
    subdivide(
        l, k, [](const Vec3&, double) { return true; }, v);
    it = segment_pieces_.emplace(key, std::move(v)).first;
  }
  return it->second;
}

// The pieces near the poles whose boxes meet [lo, hi], each once.
std::vector<const OutlineBuilder::Piece*> OutlineBuilder::polar_pieces(const Vec3& lo,
                                                                       const Vec3& hi) {
  build_pieces();
  std::vector<int> ks;
  for_grid_cells(lo, hi, grid_cell_, [&](std::uint64_t key) {
    const auto it = piece_grid_.find(key);
    if (it != piece_grid_.end()) ks.insert(ks.end(), it->second.begin(), it->second.end());
  });
  std::sort(ks.begin(), ks.end());
  ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
  std::vector<const Piece*> out;
  for (int k : ks) out.push_back(&pieces_[static_cast<std::size_t>(k)]);
  return out;
}

// The pieces of the free-boundary segments near the ends of an edge between two faces:
// those near each end in its own face's (u, v), the span of the edge carried there.
std::vector<const OutlineBuilder::Piece*> OutlineBuilder::face_pieces(const Vertex& P,
                                                                      const Vertex& Q) {
  std::vector<std::pair<int, int>> segs;
  for (const Vertex* A : {&P, &Q}) {
    const Vertex& B = A == &P ? Q : P;
    const Vec2 span = s_.delta(A->at, B.at).cwiseAbs();
    index_.near(A->at.face, A->at.uv - span, A->at.uv + span,
                [&](const Vec2&, const Vec2&, const BoundaryIndex::Ref& ref) {
                  segs.push_back({ref.loop, ref.index});
                });
  }
  std::sort(segs.begin(), segs.end());
  segs.erase(std::unique(segs.begin(), segs.end()), segs.end());
  std::vector<const Piece*> out;
  for (const auto& [l, k] : segs)
    for (const Piece& pc : segment_pieces(l, k)) out.push_back(&pc);
  return out;
}

// Unit outward normal at a vertex (its limit at a pole).
Vec3 OutlineBuilder::normal_at(const Vertex& v) const {
  const SurfaceNormal n = s_.normal(v.at);
  return n.ok ? n.n : Vec3::Zero();
}

}  // namespace plyfit::detail
