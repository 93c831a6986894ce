// Shell::create: the faces, their boundary segments and the shared edges between them, as a
// list of steps (the orientation, the creases and the boundary loops have files of their own).
#include "surface/shell/topology.hpp"

#include <cstdint>
#include <limits>

namespace plyfit {

namespace {

// The two sides of a shared edge may be at most this far apart, relative to the shell size.
constexpr double kMaxGapRel = 1e-2;
// Offset (fraction of a boundary segment's (u, v) length) at which the inward side of the
// segment is tested with contains(), and the number of times it is halved if neither side
// tests inside (a corner).
constexpr double kInwardProbe = 1e-3;
constexpr int kInwardHalvings = 20;

// The counts of the shell's data: faces, their indices in the file, shared edges.
Status check_counts(const ShellData& data) {
  const std::size_t n = data.faces.size();
  if (n == 0) return Error{ErrorCode::kShellNoFaces};
  constexpr std::size_t kMaxFaces = std::numeric_limits<std::uint16_t>::max();
  if (n > kMaxFaces)
    return Error{ErrorCode::kShellTooManyFaces,
                 {},
                 {static_cast<std::int64_t>(n), static_cast<std::int64_t>(kMaxFaces)}};
  if (!data.source_faces.empty() && data.source_faces.size() != n)
    return Error{ErrorCode::kShellFaceIndices};
  if (data.edge_count < 0) return Error{ErrorCode::kShellEdgeCountNegative};
  return ok_status();
}

// The loops of every face as the face keeps them (Face::create drops a repeated closing point:
// the tags follow their segments).
std::vector<std::vector<TrimLoop>> tagged_loops(const ShellData& data) {
  std::vector<std::vector<TrimLoop>> loops(data.faces.size());
  for (std::size_t k = 0; k < data.faces.size(); ++k)
    for (auto loop : data.faces[k].loops) {
      if (loop.points.size() > 1 && loop.points.front() == loop.points.back()) {
        loop.points.pop_back();
        if (!loop.edges.empty()) loop.edges.pop_back();
      }
      loops[k].push_back(std::move(loop));
    }
  return loops;
}

// The side of segment s the face lies on (+1: inward * perp(b - a) points into it), by
// contains() just off its middle, the offset halved while both sides test alike (a corner).
double inward_side(const Face& face, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a, mid = 0.5 * (a + b);
  const Vec2 nrm = perp(d);
  double h = kInwardProbe;
  for (int it = 0; it < kInwardHalvings; ++it, h *= 0.5) {
    const bool plus = face.contains(Vec2(mid + h * nrm)),
               minus = face.contains(Vec2(mid - h * nrm));
    if (plus != minus) return plus ? 1.0 : -1.0;
  }
  return 1.0;
}

}  // namespace

Shell::Shell() : topo_(std::make_unique<Topology>()) {}
Shell::~Shell() = default;
Shell::Shell(Shell&&) noexcept = default;
Shell& Shell::operator=(Shell&&) noexcept = default;

Result<Shell> Shell::create(ShellData data, const Tolerances& tol) {
  if (auto st = check_counts(data); !st) return st.error();
  Shell sh;
  sh.tol_ = tol;
  sh.tolerance_ = data.tolerance;
  for (std::size_t k = 0; k < data.faces.size(); ++k)
    sh.source_.push_back(data.source_faces.empty() ? static_cast<int>(k) : data.source_faces[k]);
  if (auto st = sh.check_tags(data); !st) return st.error();
  const auto loops = tagged_loops(data);
  if (auto st = sh.build_faces(data); !st) return st.error();
  sh.build_topology(loops);
  sh.measure();
  double gap = 0.0;
  if (auto st = sh.build_edges(data.edge_count, gap); !st) return st.error();
  if (auto st = sh.set_gap(gap, data.tolerance); !st) return st.error();
  if (auto st = sh.orient(); !st) return st.error();
  sh.measure_creases();
  sh.trace_boundary();
  sh.find_neighbours();
  bool seams = false;
  for (const auto& f : sh.faces_) seams = seams || f->closed_u() || f->closed_v();
  sh.closes_ = seams || sh.euler_ != 1 || sh.boundary_.size() != 1;
  return sh;
}

ShellData Shell::data() const {
  ShellData d;
  for (const auto& f : faces_) d.faces.push_back(f->data());
  d.edge_count = edge_count();
  d.source_faces = source_;
  d.tolerance = tolerance_;
  return d;
}

// Every loop's tags, before anything is built: one per segment, each a shared edge in range.
Status Shell::check_tags(const ShellData& data) const {
  for (std::size_t k = 0; k < data.faces.size(); ++k) {
    const auto& loops = data.faces[k].loops;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const TrimLoop& loop = loops[l];
      if (!loop.edges.empty() && loop.edges.size() != loop.points.size())
        return Error(ErrorCode::kTrimLoopEdgeTags, {},
                     {static_cast<std::int64_t>(l), static_cast<std::int64_t>(loop.edges.size()),
                      static_cast<std::int64_t>(loop.points.size())})
            .at_face(source_[k]);
      for (std::int32_t e : loop.edges)
        if (e != TrimLoop::kFreeEdge && (e < 0 || e >= data.edge_count))
          return Error(ErrorCode::kSharedEdgeRange, {}, {std::int64_t{e}}).at_face(source_[k]);
    }
  }
  return ok_status();
}

// The faces (Face::create); an error names the face.
Status Shell::build_faces(ShellData& data) {
  for (std::size_t k = 0; k < data.faces.size(); ++k) {
    auto f = Face::create(std::move(data.faces[k]), tol_);
    if (!f) return Error(f.error()).at_face(source_[k]);
    faces_.push_back(std::make_unique<Face>(std::move(f).value()));
  }
  return ok_status();
}

// Boundary segments per face, with their edges and inward sides, and the grid over them.
void Shell::build_topology(const std::vector<std::vector<TrimLoop>>& loops) {
  topo_->faces.resize(faces_.size());
  for (std::size_t k = 0; k < faces_.size(); ++k) {
    const Face& F = *faces_[k];
    auto& T = topo_->faces[k];
    T.loops = F.boundary();
    std::vector<detail::SegmentIndex::Seg> index;
    for (int l = 0; l < static_cast<int>(T.loops.size()); ++l) {
      const auto& L = T.loops[static_cast<std::size_t>(l)];
      const int m = static_cast<int>(L.points.size());
      const TrimLoop* tl = l < static_cast<int>(loops[k].size()) ? &loops[k][l] : nullptr;
      for (int i = 0; i < m; ++i) {
        Topology::Seg s;
        s.a = L.points[static_cast<std::size_t>(i)].uv;
        s.b = L.points[static_cast<std::size_t>((i + 1) % m)].uv;
        s.kind = L.kinds[static_cast<std::size_t>(i)];
        s.loop = l;
        s.index = i;
        if (tl && !tl->edges.empty() && s.kind == BoundaryLoop::kEdge)
          s.edge = tl->edges[static_cast<std::size_t>(i)];
        s.inward = inward_side(F, s.a, s.b);
        T.shared = T.shared || s.edge >= 0;
        if (s.kind == BoundaryLoop::kEdge)
          index.push_back({s.a, s.b, static_cast<int>(T.segs.size())});
        T.segs.push_back(s);
      }
    }
    T.index = detail::SegmentIndex(std::move(index));
  }
}

// The shell's box, size, area and rounding: its faces'.
void Shell::measure() {
  BBox3 box;
  for (const auto& f : faces_) {
    box.add(f->bbox().min);
    box.add(f->bbox().max);
    area_ += f->area();
    rounding_ = std::max(rounding_, f->rounding());
  }
  size_ = std::max(box.diagonal(), detail::kDivisionFloor);
  bbox_ = box;
}

// Shared edges: two uses on two faces, their polylines in (u, v) and 3D; `gap` is the largest
// distance between the two sides.
Status Shell::build_edges(std::int32_t edge_count, double& gap) {
  edges_.resize(static_cast<std::size_t>(edge_count));
  for (std::int32_t e = 0; e < edge_count; ++e) {
    Edge& E = edges_[static_cast<std::size_t>(e)];
    // Every segment of a face tagged e, in loop order, makes that face's use (a face that
    // tags e twice, joining itself, makes one use).
    std::vector<std::int32_t> faces_of;
    for (std::size_t k = 0; k < faces_.size(); ++k) {
      bool any = false;
      for (const auto& s : topo_->faces[k].segs) any = any || s.edge == e;
      if (any) faces_of.push_back(static_cast<std::int32_t>(k));
    }
    if (faces_of.size() != 2)
      return Error{ErrorCode::kSharedEdgeUses,
                   {},
                   {std::int64_t{e}, static_cast<std::int64_t>(faces_of.size())}};
    for (int u = 0; u < 2; ++u)
      if (!trace_use(E, u, faces_of[static_cast<std::size_t>(u)], e))
        return Error{ErrorCode::kSharedEdgeNotEvaluated, {}, {std::int64_t{e}}};
    for (const Vec3& p : E.xyz[0]) {
      double best = INFINITY;
      for (std::size_t i = 0; i + 1 < E.xyz[1].size(); ++i) {
        double t;
        best = std::min(best, detail::segment_distance(p, E.xyz[1][i], E.xyz[1][i + 1], t));
      }
      gap = std::max(gap, best);
    }
  }
  return ok_status();
}

// Use u of shared edge e on face k: the run of segments tagged e in its loop (segments of one
// loop are contiguous in T.segs), from the segment that follows one of another edge, as
// polylines in (u, v) and 3D. False where the face cannot be evaluated on it.
bool Shell::trace_use(Edge& E, int u, std::int32_t k, std::int32_t e) const {
  E.face[u] = k;
  const auto& T = topo_->faces[static_cast<std::size_t>(k)];
  const Face& F = *faces_[static_cast<std::size_t>(k)];
  int base = 0, m = 0, start = -1;
  for (int i = 0; i < static_cast<int>(T.segs.size()) && start < 0; ++i) {
    const auto& si = T.segs[static_cast<std::size_t>(i)];
    if (si.edge != e) continue;
    base = i - si.index;
    m = static_cast<int>(T.loops[static_cast<std::size_t>(si.loop)].points.size());
    start = si.index;
    for (int g = 0; g < m; ++g) {
      const int prev = (start + m - 1) % m;
      if (T.segs[static_cast<std::size_t>(base + prev)].edge != e) break;
      start = prev;
    }
  }
  for (int g = 0; g < m; ++g) {
    const int i = base + (start + g) % m;
    const auto& si = T.segs[static_cast<std::size_t>(i)];
    if (si.edge != e) break;
    if (E.uv[u].empty()) E.uv[u].push_back(si.a);
    E.uv[u].push_back(si.b);
    E.seg[u].push_back(i);
  }
  for (const Vec2& p : E.uv[u]) {
    const SurfaceEval1 ev = F.eval1(p);
    if (!ev.ok) return false;
    E.xyz[u].push_back(ev.p);
  }
  return true;
}

// The sewing gap from the largest distance measured between the two sides of a shared edge,
// the given tolerance and the rounding of the coordinates; and how far from a shared edge each
// face's points count as on the shell. An error where the sides lie too far apart.
Status Shell::set_gap(double measured, double tolerance) {
  if (measured > kMaxGapRel * size_)
    return Error{ErrorCode::kShellNotSewn, {}, {measured, 100.0 * kMaxGapRel}};
  gap_ = detail::kGapFactor *
         std::max(
             {measured, tolerance, tol_.roundoff_rel * (size_ + bbox_.max.cwiseAbs().maxCoeff())});
  for (std::size_t k = 0; k < faces_.size(); ++k) {
    const Face& F = *faces_[k];
    const auto& d = F.domain();
    const Vec2 sp = F.speeds();
    topo_->faces[k].near =
        std::max(gap_, detail::kGapFactor * tol_.param_rel *
                           Vec2(d.width_u() * sp.x(), d.width_v() * sp.y()).norm());
  }
  return ok_status();
}

// Neighbours for settle(): across each shared edge (seeds: its polyline points, a few), and
// round each pole (a collapsed run's middle) that several faces share.
void Shell::find_neighbours() {
  neighbours_.assign(faces_.size(), {});
  for (const Edge& E : edges_)
    for (int u = 0; u < 2; ++u) {
      const auto& pts = E.uv[1 - u];
      for (std::size_t i = 0; i < pts.size(); i += std::max<std::size_t>(1, pts.size() / 4))
        add_neighbour(E.face[u], E.face[1 - u], pts[i]);
      add_neighbour(E.face[u], E.face[1 - u], pts.back());
    }
  struct SharedPole {
    std::int32_t face;
    Vec2 uv;
    Vec3 p;
  };
  std::vector<SharedPole> poles;
  for (std::size_t k = 0; k < faces_.size(); ++k)
    for (const auto& sg : topo_->faces[k].segs)
      if (sg.kind == BoundaryLoop::kCollapsed) {
        const Vec2 mid = 0.5 * (sg.a + sg.b);
        poles.push_back({static_cast<std::int32_t>(k), mid, faces_[k]->eval1(mid).p});
      }
  const double merge = gap_ + tol_.roundoff_rel * size_;
  for (const SharedPole& a : poles)
    for (const SharedPole& b : poles)
      if (a.face != b.face && (a.p - b.p).norm() <= merge) {
        add_neighbour(a.face, b.face, b.uv);
        topo_->faces[static_cast<std::size_t>(a.face)].pole = true;
      }
}

// Face g and a seed on it near face f, as a neighbour of f.
void Shell::add_neighbour(std::int32_t f, std::int32_t g, const Vec2& seed) {
  auto& list = neighbours_[static_cast<std::size_t>(f)];
  for (auto& nb : list)
    if (nb.face == g) {
      nb.seeds.push_back(seed);
      return;
    }
  list.push_back({g, {seed}});
}

}  // namespace plyfit
