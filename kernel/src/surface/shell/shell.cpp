#include "surface/shell/shell.hpp"

#include "geometry/segment_index.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace plyfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A point within kGapFactor times the sewing gap (the larger of the shell's tolerance and the
// largest distance measured between the two sides of a shared edge) of a shared edge is on
// the shell: the two faces' boundary polylines approximate the edge independently, and a
// solution can fall in the sliver between them.
constexpr double kGapFactor = 2.0;
// The two sides of a shared edge may be at most this far apart, relative to the shell size.
constexpr double kMaxGapRel = 1e-2;
// A path that leaves its face's domain through a pole shared by several faces goes on on the
// face that holds its 3D point (the face extended past the pole) within this fraction of the
// step's 3D length (the extension of a surface of revolution past its pole is the surface).
constexpr double kPoleReachRel = 1e-3;
// A path in a face's parameters crosses at most this many shared edges in one locate().
constexpr int kMaxEdgeCrossings = 8;
// Points sampled along a shared edge for its crease angle and orientation.
constexpr int kEdgeSamples = 17;
// Offset (fraction of a boundary segment's (u, v) length) at which the inward side of the
// segment is tested with contains(), and the number of times it is halved if neither side
// tests inside (a corner).
constexpr double kInwardProbe = 1e-3;
constexpr int kInwardHalvings = 20;

Vec2 perp(const Vec2& d) {
  return Vec2(-d.y(), d.x());
}

// Least-squares (u, v) step whose image under the first derivatives in e is v.
Vec2 metric_solve(const SurfaceEval1& e, const Vec3& v) {
  Eigen::Matrix2d G;
  G << e.du.dot(e.du), e.du.dot(e.dv), e.du.dot(e.dv), e.dv.dot(e.dv);
  const Vec2 rhs(e.du.dot(v), e.dv.dot(v));
  const double det = G.determinant();
  if (!(std::abs(det) > 0.0)) {
    // A pole: the step along the one derivative that does not vanish.
    const double a = G(0, 0), b = G(1, 1);
    if (a >= b && a > 0.0) return Vec2(rhs.x() / a, 0.0);
    if (b > 0.0) return Vec2(0.0, rhs.y() / b);
    return Vec2::Zero();
  }
  const Vec2 r = G.inverse() * rhs;
  return r.allFinite() ? r : Vec2::Zero();
}

// Distance from p to segment ab and the parameter of the nearest point.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b, double& t) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

// Per face: every boundary segment (the face's boundary() loops), its shared edge (or
// kFreeEdge), its kind, the sign of its inward side, and a grid over the segments that are
// real boundaries (not collapsed, not seams).
struct Shell::Topology {
  struct Seg {
    Vec2 a, b;
    std::int32_t edge = TrimLoop::kFreeEdge;
    BoundaryLoop::Kind kind = BoundaryLoop::kEdge;
    double inward = 1.0;  // the face lies on the side inward * perp(b - a)
    int loop = 0, index = 0;
  };
  struct FaceTopo {
    std::vector<Seg> segs;
    std::vector<BoundaryLoop> loops;  // the face's own boundary()
    detail::SegmentIndex index;       // over segs (id = position in segs)
    bool shared = false;              // has a shared edge
    // How far (3D) a point may lie off a shared edge and still be on the shell: the sewing
    // gap, and at least the rounding margin contains() grants at the face's domain.
    double near = 0.0;
    bool pole = false;  // has a collapsed edge shared with other faces (see neighbours_)
  };
  std::vector<FaceTopo> faces;
};

Shell::Shell() : topo_(std::make_unique<Topology>()) {}
Shell::~Shell() = default;
Shell::Shell(Shell&&) noexcept = default;
Shell& Shell::operator=(Shell&&) noexcept = default;

Result<Shell> Shell::create(ShellData data, const Tolerances& tol) {
  const std::size_t n = data.faces.size();
  if (n == 0) return Error{"the shell has no faces"};
  if (n > std::numeric_limits<std::uint16_t>::max())
    return Error{"the shell has " + std::to_string(n) + " faces; at most 65535 are supported"};
  if (!data.source_faces.empty() && data.source_faces.size() != n)
    return Error{"the shell's face indices do not match its faces"};
  Shell sh;
  sh.tol_ = tol;
  for (std::size_t k = 0; k < n; ++k)
    sh.source_.push_back(data.source_faces.empty() ? static_cast<int>(k) : data.source_faces[k]);
  auto name = [&](std::size_t k) { return "face " + std::to_string(sh.source_[k]); };
  if (data.edge_count < 0) return Error{"the shell's edge count is negative"};
  // Check the tags before building anything.
  for (std::size_t k = 0; k < n; ++k) {
    for (const auto& loop : data.faces[k].loops) {
      if (!loop.edges.empty() && loop.edges.size() != loop.points.size())
        return Error{name(k) + ": a trim loop has " + std::to_string(loop.edges.size()) +
                     " edge tags for " + std::to_string(loop.points.size()) + " segments"};
      for (std::int32_t e : loop.edges)
        if (e != TrimLoop::kFreeEdge && (e < 0 || e >= data.edge_count))
          return Error{name(k) + ": shared edge " + std::to_string(e) + " out of range"};
    }
  }
  // Loops as the faces keep them (Face::create may drop a repeated closing point: the tags
  // follow their segments).
  std::vector<std::vector<TrimLoop>> loops(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (auto loop : data.faces[k].loops) {
      if (loop.points.size() > 1 && loop.points.front() == loop.points.back()) {
        loop.points.pop_back();
        if (!loop.edges.empty()) loop.edges.pop_back();
      }
      loops[k].push_back(std::move(loop));
    }
    auto f = Face::create(std::move(data.faces[k]), tol);
    if (!f) return Error{name(k)}.because(f.error());
    sh.faces_.push_back(std::make_unique<Face>(std::move(f).value()));
  }

  // Boundary segments per face, with their edges and inward sides.
  sh.topo_->faces.resize(n);
  std::vector<std::vector<std::pair<std::int32_t, int>>> uses(
      static_cast<std::size_t>(data.edge_count));  // (face, first segment) per use
  for (std::size_t k = 0; k < n; ++k) {
    const Face& F = *sh.faces_[k];
    auto& T = sh.topo_->faces[k];
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
        // The inward side: the face's side of the segment, by contains() just off its middle.
        const Vec2 d = s.b - s.a, mid = 0.5 * (s.a + s.b);
        const Vec2 nrm = perp(d);
        double h = kInwardProbe;
        for (int it = 0; it < kInwardHalvings; ++it, h *= 0.5) {
          const bool plus = F.contains(Vec2(mid + h * nrm)),
                     minus = F.contains(Vec2(mid - h * nrm));
          if (plus != minus) {
            s.inward = plus ? 1.0 : -1.0;
            break;
          }
        }
        if (s.edge >= 0) {
          T.shared = true;
          auto& u = uses[static_cast<std::size_t>(s.edge)];
          if (u.empty() || u.back().first != static_cast<std::int32_t>(k))
            u.push_back({static_cast<std::int32_t>(k), static_cast<int>(T.segs.size())});
        }
        if (s.kind == BoundaryLoop::kEdge)
          index.push_back({s.a, s.b, static_cast<int>(T.segs.size())});
        T.segs.push_back(s);
      }
    }
    T.index = detail::SegmentIndex(std::move(index));
  }

  // Shared edges: two uses on two faces; their polylines in (u, v) and 3D.
  BBox3 box;
  for (const auto& f : sh.faces_) {
    box.add(f->bbox().min);
    box.add(f->bbox().max);
    sh.area_ += f->area();
    sh.rounding_ = std::max(sh.rounding_, f->rounding());
  }
  sh.size_ = std::max(box.diagonal(), 1e-300);
  sh.bbox_ = box;
  double measured = 0.0;
  sh.edges_.resize(static_cast<std::size_t>(data.edge_count));
  for (std::int32_t e = 0; e < data.edge_count; ++e) {
    Edge& E = sh.edges_[static_cast<std::size_t>(e)];
    // Every segment of a face tagged e, in loop order, makes that face's use.
    std::vector<std::int32_t> faces_of;
    for (std::size_t k = 0; k < n; ++k) {
      const auto& T = sh.topo_->faces[k];
      bool any = false;
      for (const auto& s : T.segs) any = any || s.edge == e;
      if (any) faces_of.push_back(static_cast<std::int32_t>(k));
    }
    if (faces_of.size() != 2)
      return Error{"shared edge " + std::to_string(e) + " is used by " +
                   std::to_string(faces_of.size()) + " faces (a shared edge joins two faces)"};
    for (int u = 0; u < 2; ++u) {
      const std::int32_t k = faces_of[static_cast<std::size_t>(u)];
      E.face[u] = k;
      const auto& T = sh.topo_->faces[static_cast<std::size_t>(k)];
      const Face& F = *sh.faces_[static_cast<std::size_t>(k)];
      // The run of segments tagged e in its loop (segments of one loop are contiguous in
      // T.segs), from the segment that follows one of another edge.
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
        if (!ev.ok) return Error{"shared edge " + std::to_string(e) + ": cannot evaluate it"};
        E.xyz[u].push_back(ev.p);
      }
    }
    if (E.face[0] == E.face[1])
      return Error{"shared edge " + std::to_string(e) + " joins face " +
                   std::to_string(sh.source_[static_cast<std::size_t>(E.face[0])]) + " to itself"};
    // The gap between the two sides.
    for (const Vec3& p : E.xyz[0]) {
      double best = INFINITY;
      for (std::size_t i = 0; i + 1 < E.xyz[1].size(); ++i) {
        double t;
        best = std::min(best, segment_distance(p, E.xyz[1][i], E.xyz[1][i + 1], t));
      }
      measured = std::max(measured, best);
    }
  }
  if (measured > kMaxGapRel * sh.size_)
    return Error{"the two sides of a shared edge are " + std::to_string(measured) +
                 " apart (more than 1% of the shell's size): the faces were not sewn"};
  sh.gap_ = kGapFactor * std::max({measured, data.tolerance,
                                   tol.roundoff_rel * (sh.size_ + box.max.cwiseAbs().maxCoeff())});
  for (std::size_t k = 0; k < n; ++k) {
    const Face& F = *sh.faces_[k];
    const auto& d = F.domain();
    const Vec2 sp = F.speeds();
    sh.topo_->faces[k].near =
        std::max(sh.gap_, kGapFactor * tol.param_rel *
                              Vec2(d.width_u() * sp.x(), d.width_v() * sp.y()).norm());
  }

  // Orientation: across every shared edge the two faces' outward normals must agree. For a
  // consistently oriented pair, (n x inward) . t has opposite signs on the two sides (unfold
  // one face onto the other: the inward directions oppose, the normals agree). Faces are
  // flipped, breadth first from face 0, until every edge agrees.
  {
    std::vector<int> state(n, 0);  // 0 unvisited, +1 kept, -1 flipped
    std::vector<std::vector<std::pair<std::int32_t, double>>> adj(n);  // (other face, sign)
    for (std::int32_t e = 0; e < data.edge_count; ++e) {
      const Edge& E = sh.edges_[static_cast<std::size_t>(e)];
      const std::size_t mid = E.uv[0].size() / 2;
      const Vec2 x0 = E.uv[0][mid > 0 ? mid - 1 : 0],
                 x1 = E.uv[0][std::min(mid, E.uv[0].size() - 1)];
      const Vec2 xa = 0.5 * (x0 + x1);
      const Face& F0 = *sh.faces_[static_cast<std::size_t>(E.face[0])];
      const Face& F1 = *sh.faces_[static_cast<std::size_t>(E.face[1])];
      const SurfaceEval1 e0 = F0.eval1(xa);
      const Projection p1 = F1.project_from(e0.p, E.uv[1][E.uv[1].size() / 2], false);
      // Inward directions from the segments nearest the sample on each side.
      auto inward3 = [&](std::int32_t face, const Vec2& uv, const SurfaceEval1& ev) {
        const auto& T = sh.topo_->faces[static_cast<std::size_t>(face)];
        double best = INFINITY;
        Vec3 out = Vec3::Zero();
        for (const auto& s : T.segs) {
          if (s.edge != e) continue;
          const Vec2 d = s.b - s.a;
          const double t =
              std::clamp((uv - s.a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
          const double dist = (s.a + t * d - uv).norm();
          if (dist < best) {
            best = dist;
            const Vec2 w = s.inward * perp(d);
            out = ev.du * w.x() + ev.dv * w.y();
          }
        }
        return out;
      };
      const SurfaceEval1 e1 = F1.eval1(p1.at.uv);
      const Vec3 t = (E.xyz[0].back() - E.xyz[0].front()).normalized();
      const Vec3 n0 = F0.normal(xa).n, n1 = F1.normal(p1.at.uv).n;
      const double s0 = n0.cross(inward3(E.face[0], xa, e0)).dot(t);
      const double s1 = n1.cross(inward3(E.face[1], p1.at.uv, e1)).dot(t);
      const double sign = (s0 * s1 < 0.0) ? 1.0 : -1.0;  // +1 consistent as they are
      adj[static_cast<std::size_t>(E.face[0])].push_back({E.face[1], sign});
      adj[static_cast<std::size_t>(E.face[1])].push_back({E.face[0], sign});
    }
    for (std::size_t root = 0; root < n; ++root) {
      if (state[root]) continue;
      state[root] = 1;
      std::vector<std::size_t> stack{root};
      while (!stack.empty()) {
        const std::size_t f = stack.back();
        stack.pop_back();
        for (const auto& [g, sign] : adj[f]) {
          const int want = state[f] * static_cast<int>(sign);
          const auto gi = static_cast<std::size_t>(g);
          if (!state[gi]) {
            state[gi] = want;
            stack.push_back(gi);
          } else if (state[gi] != want) {
            return Error{"the faces cannot be oriented consistently (face " +
                         std::to_string(sh.source_[gi]) + " and its neighbours)"};
          }
        }
      }
    }
    for (std::size_t k = 0; k < n; ++k)
      if (state[k] < 0) *sh.faces_[k] = sh.faces_[k]->flipped();
  }

  // Crease angles: the normals of the two faces along each edge.
  for (std::int32_t e = 0; e < data.edge_count; ++e) {
    Edge& E = sh.edges_[static_cast<std::size_t>(e)];
    const Face& F0 = *sh.faces_[static_cast<std::size_t>(E.face[0])];
    const Face& F1 = *sh.faces_[static_cast<std::size_t>(E.face[1])];
    const std::size_t m = E.uv[0].size();
    for (int q = 0; q < kEdgeSamples; ++q) {
      const std::size_t i =
          std::min(m - 1, static_cast<std::size_t>(q) * (m - 1) / (kEdgeSamples - 1));
      const Vec2 uv0 = E.uv[0][i];
      const SurfaceNormal a = F0.normal(uv0);
      // Seed on the other side: its polyline point nearest in 3D.
      std::size_t best = 0;
      for (std::size_t j = 1; j < E.xyz[1].size(); ++j)
        if ((E.xyz[1][j] - E.xyz[0][i]).squaredNorm() <
            (E.xyz[1][best] - E.xyz[0][i]).squaredNorm())
          best = j;
      const Projection p1 = F1.project_from(E.xyz[0][i], E.uv[1][best], false);
      if (!p1.ok) continue;
      const SurfaceNormal b = F1.normal(p1.at.uv);
      if (!a.ok || !b.ok || a.degenerate || b.degenerate) continue;
      E.crease = std::max(E.crease, std::atan2(a.n.cross(b.n).norm(), a.n.dot(b.n)));
    }
  }

  // Free boundary loops: runs of free segments, chained around the shell's vertices. After a
  // free run, the boundary goes on at its end vertex: across the shared edge that follows it
  // in its face's loop to the neighbouring face, round the vertex face by face until a free
  // run starts there.
  {
    // A run is a maximal piece of a face's loop of one class: a shared edge (its index), or
    // free segments that are a boundary (-1), a closed face's seam (-2) or collapsed (-3).
    struct Run {
      std::int32_t face;
      int first, count;  // segments in T.segs
      std::int32_t edge;
      int cls;
    };
    auto cls_of = [](const Topology::Seg& sg) {
      if (sg.edge >= 0) return static_cast<int>(sg.edge);
      return sg.kind == BoundaryLoop::kSeam ? -2 : sg.kind == BoundaryLoop::kCollapsed ? -3 : -1;
    };
    std::vector<Run> runs;
    std::vector<std::vector<int>> runs_of(n);  // per face, run indices in loop order
    for (std::size_t k = 0; k < n; ++k) {
      const auto& T = sh.topo_->faces[k];
      for (std::size_t l = 0; l < T.loops.size(); ++l) {
        int base = -1, m = 0;
        for (int i = 0; i < static_cast<int>(T.segs.size()); ++i)
          if (T.segs[static_cast<std::size_t>(i)].loop == static_cast<int>(l)) {
            if (base < 0) base = i;
            ++m;
          }
        if (m == 0) continue;
        // Start at a class change so that no run wraps round the loop's start.
        auto cls_at = [&](int i) { return cls_of(T.segs[static_cast<std::size_t>(base + i)]); };
        int start = 0;
        for (int i = 0; i < m; ++i)
          if (cls_at(i) != cls_at((i + m - 1) % m)) {
            start = i;
            break;
          }
        for (int g = 0; g < m;) {
          const int i0 = (start + g) % m;
          const int cls = cls_at(i0);
          int c = 0;
          while (g + c < m && cls_at((start + g + c) % m) == cls) ++c;
          Run r{static_cast<std::int32_t>(k), base + i0, c, cls >= 0 ? cls : TrimLoop::kFreeEdge,
                cls};
          // A run that wraps (the whole loop is one run) keeps its segment order via modulo.
          runs_of[k].push_back(static_cast<int>(runs.size()));
          runs.push_back(r);
          g += c;
        }
      }
    }
    auto seg_at = [&](const Run& r, int g) -> const Topology::Seg& {
      const auto& T = sh.topo_->faces[static_cast<std::size_t>(r.face)];
      const auto& s0 = T.segs[static_cast<std::size_t>(r.first)];
      const int lm = static_cast<int>(T.loops[static_cast<std::size_t>(s0.loop)].points.size());
      const int base = r.first - s0.index;
      return T.segs[static_cast<std::size_t>(base + (s0.index + g) % lm)];
    };
    auto point3 = [&](std::int32_t face, const Vec2& uv) {
      return sh.faces_[static_cast<std::size_t>(face)]->eval1(uv).p;
    };
    auto run_start = [&](const Run& r, bool rev) {
      return rev ? seg_at(r, r.count - 1).b : seg_at(r, 0).a;
    };
    auto run_end = [&](const Run& r, bool rev) {
      return rev ? seg_at(r, 0).a : seg_at(r, r.count - 1).b;
    };
    // The run of face `face` next to run `ri` in its loop, before (-1) or after (+1) it.
    auto neighbour_run = [&](int ri, int dir) {
      const Run& r = runs[static_cast<std::size_t>(ri)];
      const auto& list = runs_of[static_cast<std::size_t>(r.face)];
      const int loop = seg_at(r, 0).loop;
      std::vector<int> same;
      for (int x : list)
        if (seg_at(runs[static_cast<std::size_t>(x)], 0).loop == loop) same.push_back(x);
      const auto it = std::find(same.begin(), same.end(), ri);
      const int pos = static_cast<int>(it - same.begin());
      const int m = static_cast<int>(same.size());
      return same[static_cast<std::size_t>((pos + dir + m) % m)];
    };
    const double merge = sh.gap_ + tol.roundoff_rel * sh.size_;
    std::vector<bool> used(runs.size(), false);
    // Euler characteristic: vertices are run ends (merged in 3D), edges the shared edges and
    // the free runs, collapsed runs left out.
    std::vector<Vec3> verts;
    auto vertex = [&](const Vec3& p) {
      for (std::size_t i = 0; i < verts.size(); ++i)
        if ((verts[i] - p).norm() <= merge) return;
      verts.push_back(p);
    };
    // Edges counted twice: a shared edge once per side, a free edge twice, a seam (whose two
    // sides are both in its face's loop) once per side.
    int edges2 = 0;
    for (const Run& r : runs) {
      if (r.cls == -3) continue;  // a collapsed edge is a vertex
      edges2 += r.cls == -1 ? 2 : 1;
      vertex(point3(r.face, run_start(r, false)));
      vertex(point3(r.face, run_end(r, false)));
    }
    sh.euler_ = static_cast<int>(verts.size()) - edges2 / 2 + static_cast<int>(n);
    for (std::size_t ri = 0; ri < runs.size(); ++ri) {
      if (used[ri] || runs[ri].edge >= 0) continue;
      BoundaryLoop loop;
      int cur = static_cast<int>(ri);
      bool rev = false;
      for (std::size_t guard = 0; guard <= runs.size(); ++guard) {
        used[static_cast<std::size_t>(cur)] = true;
        const Run& r = runs[static_cast<std::size_t>(cur)];
        // The run's points, its segments' kinds; a junction to the next run.
        for (int g = 0; g < r.count; ++g) {
          const auto& s = seg_at(r, rev ? r.count - 1 - g : g);
          loop.points.emplace_back(rev ? s.b : s.a, r.face);
          loop.kinds.push_back(s.kind);
        }
        // Round the end vertex to the next free run.
        const Vec3 v = point3(r.face, run_end(r, rev));
        int at = cur;
        int dir = rev ? -1 : 1;
        int next = -1;
        bool next_rev = false;
        for (std::size_t hop = 0; hop <= runs.size() && next < 0; ++hop) {
          const int nb = neighbour_run(at, dir);
          const Run& q = runs[static_cast<std::size_t>(nb)];
          if (q.edge < 0) {
            next = nb;
            next_rev = dir < 0;
            break;
          }
          // Across shared edge q.edge: the other face's use, its end at v.
          const Edge& E = sh.edges_[static_cast<std::size_t>(q.edge)];
          const int other = E.face[0] == q.face ? 1 : 0;
          const bool at_front =
              (E.xyz[other].front() - v).norm() <= (E.xyz[other].back() - v).norm();
          int use_run = -1;
          for (int x : runs_of[static_cast<std::size_t>(E.face[other])])
            if (runs[static_cast<std::size_t>(x)].edge == q.edge) use_run = x;
          if (use_run < 0) break;
          // The use's polyline runs in its loop's order: its front is the run's start.
          at = use_run;
          dir = at_front ? -1 : 1;
        }
        if (next < 0) break;  // malformed: close the loop here
        // The next run starts where this one ends: on this face (a run of another class in
        // the same loop) the loop goes straight on; on another face (a corner of the shell) a
        // junction joins the two faces' copies of the vertex.
        const Vec2 last = run_end(r, rev);
        const Run& nr = runs[static_cast<std::size_t>(next)];
        if (nr.face != r.face || run_start(nr, next_rev) != last) {
          loop.points.emplace_back(last, r.face);
          loop.kinds.push_back(BoundaryLoop::kJunction);
        }
        if (next == static_cast<int>(ri) || used[static_cast<std::size_t>(next)]) break;
        cur = next;
        rev = next_rev;
      }
      bool real = false;
      for (auto k : loop.kinds) real = real || k == BoundaryLoop::kEdge;
      if (real && loop.points.size() >= 3) sh.boundary_.push_back(std::move(loop));
    }
  }
  // Neighbours for settle(): across each shared edge (seeds: its polyline points, a few), and
  // round each pole (a collapsed run's middle) that several faces share.
  sh.neighbours_.assign(n, {});
  auto add_neighbour = [&](std::int32_t f, std::int32_t g, const Vec2& seed) {
    auto& list = sh.neighbours_[static_cast<std::size_t>(f)];
    for (auto& nb : list)
      if (nb.face == g) {
        nb.seeds.push_back(seed);
        return;
      }
    list.push_back({g, {seed}});
  };
  for (const Edge& E : sh.edges_)
    for (int u = 0; u < 2; ++u) {
      const auto& pts = E.uv[1 - u];
      for (std::size_t i = 0; i < pts.size(); i += std::max<std::size_t>(1, pts.size() / 4))
        add_neighbour(E.face[u], E.face[1 - u], pts[i]);
      add_neighbour(E.face[u], E.face[1 - u], pts.back());
    }
  {
    struct SharedPole {
      std::int32_t face;
      Vec2 uv;
      Vec3 p;
    };
    std::vector<SharedPole> poles;
    for (std::size_t k = 0; k < n; ++k)
      for (const auto& sg : sh.topo_->faces[k].segs)
        if (sg.kind == BoundaryLoop::kCollapsed) {
          const Vec2 mid = 0.5 * (sg.a + sg.b);
          poles.push_back({static_cast<std::int32_t>(k), mid, sh.faces_[k]->eval1(mid).p});
        }
    const double merge = sh.gap_ + tol.roundoff_rel * sh.size_;
    for (const SharedPole& a : poles)
      for (const SharedPole& b : poles)
        if (a.face != b.face && (a.p - b.p).norm() <= merge) {
          add_neighbour(a.face, b.face, b.uv);
          sh.topo_->faces[static_cast<std::size_t>(a.face)].pole = true;
        }
  }

  bool seams = false;
  for (const auto& f : sh.faces_) seams = seams || f->closed_u() || f->closed_v();
  sh.closes_ = seams || sh.euler_ != 1 || sh.boundary_.size() != 1;
  return sh;
}

std::pair<std::int32_t, std::int32_t> Shell::edge_faces(std::int32_t e) const {
  const Edge& E = edges_[static_cast<std::size_t>(e)];
  return {E.face[0], E.face[1]};
}

double Shell::crease_angle(std::int32_t f, std::int32_t g) const {
  double out = 0.0;
  for (const Edge& E : edges_)
    if ((E.face[0] == f && E.face[1] == g) || (E.face[0] == g && E.face[1] == f))
      out = std::max(out, E.crease);
  return out;
}

bool Shell::contains(const SurfaceLocation& at) const {
  const Face& F = *faces_[static_cast<std::size_t>(at.face)];
  if (F.contains(at.uv)) return true;
  return near_shared_edge(at.face, F.wrap(at.uv), nullptr);
}

// True when uv (outside its face's polylines) lies within the gap of a shared segment of
// the face (3D distance, measured with the face's parametric speeds); the segment in *segment.
bool Shell::near_shared_edge(std::int32_t face, const Vec2& uv, int* segment) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(face)];
  if (!T.shared) return false;
  const Vec2 sp = faces_[static_cast<std::size_t>(face)]->speeds();
  const Vec2 h(T.near / std::max(sp.x(), 1e-300), T.near / std::max(sp.y(), 1e-300));
  double best = INFINITY;
  int found = -1;
  T.index.for_candidates(uv - h, uv + h, [&](int k) {
    const int si = T.index.seg(k).id;
    const auto& s = T.segs[static_cast<std::size_t>(si)];
    if (s.edge < 0) return;
    const Vec2 d = s.b - s.a;
    const double t = std::clamp((uv - s.a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
    const double dist = (s.a + t * d - uv).cwiseProduct(sp).norm();
    if (dist <= T.near && dist < best) {
      best = dist;
      found = si;
    }
  });
  if (segment) *segment = found;
  return found >= 0;
}

SurfaceLocation Shell::settle(const SurfaceLocation& at, const Vec3& p, double reach) const {
  if (contains(at)) return at;
  // Past a pole of at's own face: the face itself holds p there.
  const SurfaceLocation own = faces_[static_cast<std::size_t>(at.face)]->settle(at, p, reach);
  if (own != at && contains(own)) return own;
  // The neighbour that holds p nearest: a projection from each of its seeds.
  SurfaceLocation best = at;
  double best_d = reach;
  for (const Neighbour& nb : neighbours_[static_cast<std::size_t>(at.face)]) {
    const Face& G = *faces_[static_cast<std::size_t>(nb.face)];
    // The seed nearest p in 3D first.
    const Vec2* seed = &nb.seeds.front();
    double sd = INFINITY;
    for (const Vec2& q : nb.seeds) {
      const SurfaceEval1 e = G.eval1(q);
      if (e.ok && (e.p - p).norm() < sd) {
        sd = (e.p - p).norm();
        seed = &q;
      }
    }
    const Projection pr = G.project_from(p, *seed, false);
    const SurfaceLocation g(pr.at.uv, nb.face);
    if (pr.ok && pr.distance <= best_d && contains(g)) {
      best = g;
      best_d = pr.distance;
    }
  }
  return best;
}

SurfaceLocation Shell::locate(const SurfaceLocation& from, const Vec2& uv) const {
  return locate_from(from, uv, TrimLoop::kFreeEdge, 0);
}

SurfaceLocation Shell::locate_from(const SurfaceLocation& from, const Vec2& uv, std::int32_t except,
                                   int depth) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(from.face)];
  if (!T.shared || depth >= kMaxEdgeCrossings) return {uv, from.face};
  const Face& F = *faces_[static_cast<std::size_t>(from.face)];
  if (F.contains(uv)) return {uv, from.face};
  // The path from -> uv ends off the face. It goes on to a neighbour where it first crosses a
  // shared edge outwards (free edges are passed over: where a free and a shared edge meet,
  // rounding may let a path that leaves across the shared edge graze the free one first).
  const Vec2 p = F.wrap(from.uv);
  const Vec2 q = p + F.delta(from.uv, uv);
  auto outward = [&](int si) {
    const auto& sg = T.segs[static_cast<std::size_t>(si)];
    return (q - p).dot(sg.inward * perp(sg.b - sg.a)) < 0.0;
  };
  // Crossings with a shared segment, its ends widened by the near distance: at a corner
  // where a free and a shared edge meet, rounding may pass the path a hair beyond the
  // shared segment's end.
  const Vec2 sp = F.speeds();
  const Vec2 pad(T.near / std::max(sp.x(), 1e-300), T.near / std::max(sp.y(), 1e-300));
  int seg = -1;
  double t = INFINITY;
  const Vec2 r = q - p;
  T.index.for_candidates(p.cwiseMin(q) - pad, p.cwiseMax(q) + pad, [&](int k) {
    const int si = T.index.seg(k).id;
    const auto& sg = T.segs[static_cast<std::size_t>(si)];
    if (sg.edge < 0 || sg.edge == except || !outward(si)) return;
    const Vec2 e = sg.b - sg.a;
    const double den = cross2(r, e);
    if (den == 0.0) return;
    const double tc = cross2(sg.a - p, e) / den;
    const double sc = cross2(sg.a - p, r) / den;
    const double slack = T.near / std::max(e.cwiseProduct(sp).norm(), 1e-300);
    if (tc > 0.0 && tc <= 1.0 && sc >= -slack && sc <= 1.0 + slack && tc < t) {
      t = tc;
      seg = si;
    }
  });
  if (seg < 0) {
    // No shared edge crossed: `from` may lie past one already, within the sewing gap (then
    // cross it here, if the path goes on outwards); a path that leaves the face's domain
    // through a pole several faces share goes on where its 3D point lies; else the path
    // stays on this face.
    if (near_shared_edge(from.face, p, &seg) && outward(seg)) {
      t = 0.0;
    } else {
      if (T.pole && !F.domain().contains(q.x(), q.y())) {
        const SurfaceEval1 eq = F.eval1(q), ep = F.eval1(p);
        if (eq.ok && ep.ok) {
          const double reach = T.near + kPoleReachRel * (eq.p - ep.p).norm();
          const SurfaceLocation g = settle(SurfaceLocation(q, from.face), eq.p, reach);
          if (g.face != from.face) return g;
        }
      }
      return {uv, from.face};
    }
  }
  const auto& s = T.segs[static_cast<std::size_t>(seg)];
  if (s.edge < 0 || s.edge == except) return {uv, from.face};
  const Vec2 x = p + t * (q - p);
  Vec2 rest;
  const SurfaceLocation g = cross_edge(from.face, seg, x, q - x, &rest);
  if (g.face < 0) return {uv, from.face};
  return locate_from(g, g.uv + rest, s.edge, depth + 1);
}

// The location across shared segment `segment` of face `face` at its point x (face's (u, v)),
// and the step `rest` (face's (u, v)) unfolded about the edge into the neighbour's (u, v).
// face = -1 if the neighbour cannot be evaluated.
SurfaceLocation Shell::cross_edge(std::int32_t face, int segment, const Vec2& x, const Vec2& rest,
                                  Vec2* rest_out) const {
  const auto& T = topo_->faces[static_cast<std::size_t>(face)];
  const auto& s = T.segs[static_cast<std::size_t>(segment)];
  const Edge& E = edges_[static_cast<std::size_t>(s.edge)];
  const int other = E.face[0] == face ? 1 : 0;
  const std::int32_t g = E.face[other];
  const Face& F = *faces_[static_cast<std::size_t>(face)];
  const Face& G = *faces_[static_cast<std::size_t>(g)];
  const SurfaceEval1 ef = F.eval1(x);
  if (!ef.ok) return {x, -1};
  // The neighbour's side: nearest point of its polyline of the edge, then its surface.
  const auto& xyz = E.xyz[other];
  const auto& uvs = E.uv[other];
  double best = INFINITY, bt = 0.0;
  std::size_t bi = 0;
  for (std::size_t i = 0; i + 1 < xyz.size(); ++i) {
    double tt;
    const double dd = segment_distance(ef.p, xyz[i], xyz[i + 1], tt);
    if (dd < best) {
      best = dd;
      bi = i;
      bt = tt;
    }
  }
  const Vec2 seed = uvs[bi] + bt * (uvs[bi + 1] - uvs[bi]);
  const Projection pg = G.project_from(ef.p, seed, false);
  const Vec2 ug = pg.ok ? pg.at.uv : seed;
  const SurfaceEval1 eg = G.eval1(ug);
  if (!eg.ok) return {x, -1};
  // Unfold the rest of the step about the edge: along the edge it is kept; across it, the
  // direction out of this face becomes the direction into the neighbour.
  const Vec2 df = s.b - s.a;
  Vec3 t = ef.du * df.x() + ef.dv * df.y();
  const Vec2 wout = -s.inward * perp(df);
  Vec3 aout = ef.du * wout.x() + ef.dv * wout.y();
  // The neighbour's segment at the crossing gives its inward side.
  const auto& TG = topo_->faces[static_cast<std::size_t>(g)];
  const int gs = E.seg[other][bi];
  const Vec3 v = ef.du * rest.x() + ef.dv * rest.y();
  Vec3 vg = v;
  if (gs >= 0 && t.norm() > 0.0) {
    const auto& sg = TG.segs[static_cast<std::size_t>(gs)];
    const Vec2 dg = sg.b - sg.a;
    Vec3 tg = eg.du * dg.x() + eg.dv * dg.y();
    const Vec2 win = sg.inward * perp(dg);
    Vec3 ain = eg.du * win.x() + eg.dv * win.y();
    t.normalize();
    if (tg.norm() > 0.0) {
      tg.normalize();
      if (tg.dot(t) < 0.0) tg = -tg;
    } else {
      tg = t;
    }
    aout -= aout.dot(t) * t;
    ain -= ain.dot(tg) * tg;
    if (aout.norm() > 0.0 && ain.norm() > 0.0) {
      aout.normalize();
      ain.normalize();
      vg = v.dot(t) * tg + v.dot(aout) * ain;
    }
  }
  *rest_out = metric_solve(eg, vg);
  return {ug, g};
}

Vec2 Shell::delta_between_faces(const SurfaceLocation& from, const SurfaceLocation& to) const {
  const Face& F = *faces_[static_cast<std::size_t>(from.face)];
  // Between two faces: the 3D difference through the tangent plane at `from`.
  const SurfaceEval1 ef = F.eval1(from.uv);
  const SurfaceEval1 et = eval1(to);
  if (!ef.ok || !et.ok) return Vec2::Zero();
  return metric_solve(ef, et.p - ef.p);
}

Projection Shell::project(const Vec3& p) const {
  // Faces in order of their boxes' distance from p; a face whose box is farther than the
  // best distance found cannot hold a nearer point.
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < faces_.size(); ++k) {
    const BBox3& b = faces_[k]->bbox();
    const Vec3 c = p.cwiseMax(b.min).cwiseMin(b.max);
    order.push_back({(c - p).norm(), k});
  }
  std::sort(order.begin(), order.end());
  Projection best;
  for (const auto& [bound, k] : order) {
    if (best.ok && bound > best.distance) break;
    Projection q = faces_[k]->project(p);
    if (q.ok && (!best.ok || q.distance < best.distance)) {
      q.at.face = static_cast<std::int32_t>(k);
      best = q;
    }
  }
  return best;
}

}  // namespace plyfit
