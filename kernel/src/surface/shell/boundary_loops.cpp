// Shell::create's last topological step: the shell's free boundary loops and its Euler
// characteristic, from the runs of its faces' boundary loops.
#include "surface/shell/topology.hpp"

#include <algorithm>

namespace plyfit {

// Free boundary loops: runs of free segments, chained around the shell's vertices. After a
// free run, the boundary goes on at its end vertex: across the shared edge that follows it in
// its face's loop to the neighbouring face, round the vertex face by face until a free run
// starts there.
class Shell::BoundaryTracer {
 public:
  explicit BoundaryTracer(const Shell& sh) : sh_(sh), runs_of_(sh.faces_.size()) {
    merge_ = sh.gap_ + sh.tol_.roundoff_rel * sh.size_;
    for (std::size_t k = 0; k < sh.faces_.size(); ++k) split_into_runs(k);
  }

  // Euler characteristic V - E + F: vertices are run ends (merged in 3D), edges the shared
  // edges and the free runs, collapsed runs left out.
  int euler_characteristic() const {
    std::vector<Vec3> verts;
    auto vertex = [&](const Vec3& p) {
      for (std::size_t i = 0; i < verts.size(); ++i)
        if ((verts[i] - p).norm() <= merge_) return;
      verts.push_back(p);
    };
    // Edges counted twice: a shared edge once per side, a free edge twice, a seam (whose two
    // sides are both in its face's loop) once per side.
    int edges2 = 0;
    for (const Run& r : runs_) {
      if (r.cls == kCollapsed) continue;  // a collapsed edge is a vertex
      edges2 += r.cls == kFree ? 2 : 1;
      vertex(point3(r.face, run_start(r, false)));
      vertex(point3(r.face, run_end(r, false)));
    }
    return static_cast<int>(verts.size()) - edges2 / 2 + static_cast<int>(sh_.faces_.size());
  }

  // The free boundary loops (those with a real boundary segment and at least 3 points).
  std::vector<BoundaryLoop> loops() {
    std::vector<BoundaryLoop> out;
    std::vector<bool> used(runs_.size(), false);
    for (std::size_t ri = 0; ri < runs_.size(); ++ri) {
      if (used[ri] || runs_[ri].edge >= 0) continue;
      BoundaryLoop loop = trace_from(static_cast<int>(ri), used);
      bool real = false;
      for (auto k : loop.kinds) real = real || k == BoundaryLoop::kEdge;
      if (real && loop.points.size() >= 3) out.push_back(std::move(loop));
    }
    return out;
  }

 private:
  // A run is a maximal piece of a face's loop of one class: a shared edge (its index), or
  // free segments that are a boundary, a closed face's seam or collapsed.
  static constexpr int kFree = -1, kSeam = -2, kCollapsed = -3;
  struct Run {
    std::int32_t face;
    int first, count;  // segments in T.segs
    std::int32_t edge;
    int cls;
  };

  static int class_of(const Topology::Seg& sg) {
    if (sg.edge >= 0) return static_cast<int>(sg.edge);
    return sg.kind == BoundaryLoop::kSeam        ? kSeam
           : sg.kind == BoundaryLoop::kCollapsed ? kCollapsed
                                                 : kFree;
  }

  // The runs of face k's loops, in loop order.
  void split_into_runs(std::size_t k) {
    const auto& T = sh_.topo_->faces[k];
    for (std::size_t l = 0; l < T.loops.size(); ++l) {
      int base = -1, m = 0;
      for (int i = 0; i < static_cast<int>(T.segs.size()); ++i)
        if (T.segs[static_cast<std::size_t>(i)].loop == static_cast<int>(l)) {
          if (base < 0) base = i;
          ++m;
        }
      if (m == 0) continue;
      // Start at a class change so that no run wraps round the loop's start.
      auto cls_at = [&](int i) { return class_of(T.segs[static_cast<std::size_t>(base + i)]); };
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
        // A run that wraps (the whole loop is one run) keeps its segment order via modulo.
        runs_of_[k].push_back(static_cast<int>(runs_.size()));
        runs_.push_back({static_cast<std::int32_t>(k), base + i0, c,
                         cls >= 0 ? cls : TrimLoop::kFreeEdge, cls});
        g += c;
      }
    }
  }

  // The loop that starts with free run `first`, marking the runs it takes as used.
  BoundaryLoop trace_from(int first, std::vector<bool>& used) const {
    BoundaryLoop loop;
    int cur = first;
    bool rev = false;
    for (std::size_t guard = 0; guard <= runs_.size(); ++guard) {
      used[static_cast<std::size_t>(cur)] = true;
      const Run& r = runs_[static_cast<std::size_t>(cur)];
      // The run's points, its segments' kinds; a junction to the next run.
      for (int g = 0; g < r.count; ++g) {
        const auto& s = seg_at(r, rev ? r.count - 1 - g : g);
        loop.points.emplace_back(rev ? s.b : s.a, r.face);
        loop.kinds.push_back(s.kind);
      }
      bool next_rev = false;
      const int next = next_free_run(cur, rev, next_rev);
      if (next < 0) break;  // malformed: close the loop here
      // The next run starts where this one ends: on this face (a run of another class in the
      // same loop) the loop goes straight on; on another face (a corner of the shell) a
      // junction joins the two faces' copies of the vertex.
      const Vec2 last = run_end(r, rev);
      const Run& nr = runs_[static_cast<std::size_t>(next)];
      if (nr.face != r.face || run_start(nr, next_rev) != last) {
        loop.points.emplace_back(last, r.face);
        loop.kinds.push_back(BoundaryLoop::kJunction);
      }
      if (next == first || used[static_cast<std::size_t>(next)]) break;
      cur = next;
      rev = next_rev;
    }
    return loop;
  }

  // The free run that follows run `cur` (taken reversed when `rev`) round its end vertex,
  // crossing shared edges face by face, and its direction (reversed: next_rev); -1 if none.
  int next_free_run(int cur, bool rev, bool& next_rev) const {
    const Run& r = runs_[static_cast<std::size_t>(cur)];
    const Vec3 v = point3(r.face, run_end(r, rev));
    int at = cur;
    int dir = rev ? -1 : 1;
    for (std::size_t hop = 0; hop <= runs_.size(); ++hop) {
      const int nb = neighbour_run(at, dir);
      const Run& q = runs_[static_cast<std::size_t>(nb)];
      if (q.edge < 0) {
        next_rev = dir < 0;
        return nb;
      }
      // Across shared edge q.edge: the other face's use, its end at v.
      const Edge& E = sh_.edges_[static_cast<std::size_t>(q.edge)];
      const int other = E.face[0] == q.face ? 1 : 0;
      const bool at_front = (E.xyz[other].front() - v).norm() <= (E.xyz[other].back() - v).norm();
      int use_run = -1;
      for (int x : runs_of_[static_cast<std::size_t>(E.face[other])])
        if (runs_[static_cast<std::size_t>(x)].edge == q.edge) use_run = x;
      if (use_run < 0) return -1;
      // The use's polyline runs in its loop's order: its front is the run's start.
      at = use_run;
      dir = at_front ? -1 : 1;
    }
    return -1;
  }

  // Segment g of run r, in the run's order.
  const Topology::Seg& seg_at(const Run& r, int g) const {
    const auto& T = sh_.topo_->faces[static_cast<std::size_t>(r.face)];
    const auto& s0 = T.segs[static_cast<std::size_t>(r.first)];
    const int lm = static_cast<int>(T.loops[static_cast<std::size_t>(s0.loop)].points.size());
    const int base = r.first - s0.index;
    return T.segs[static_cast<std::size_t>(base + (s0.index + g) % lm)];
  }
  Vec3 point3(std::int32_t face, const Vec2& uv) const {
    return sh_.faces_[static_cast<std::size_t>(face)]->eval1(uv).p;
  }
  Vec2 run_start(const Run& r, bool rev) const {
    return rev ? seg_at(r, r.count - 1).b : seg_at(r, 0).a;
  }
  Vec2 run_end(const Run& r, bool rev) const {
    return rev ? seg_at(r, 0).a : seg_at(r, r.count - 1).b;
  }

  // The run of run ri's face next to it in its loop, before (-1) or after (+1) it.
  int neighbour_run(int ri, int dir) const {
    const Run& r = runs_[static_cast<std::size_t>(ri)];
    const auto& list = runs_of_[static_cast<std::size_t>(r.face)];
    const int loop = seg_at(r, 0).loop;
    std::vector<int> same;
    for (int x : list)
      if (seg_at(runs_[static_cast<std::size_t>(x)], 0).loop == loop) same.push_back(x);
    const auto it = std::find(same.begin(), same.end(), ri);
    const int pos = static_cast<int>(it - same.begin());
    const int m = static_cast<int>(same.size());
    return same[static_cast<std::size_t>((pos + dir + m) % m)];
  }

  const Shell& sh_;
  std::vector<Run> runs_;
  std::vector<std::vector<int>> runs_of_;  // per face, run indices in loop order
  double merge_ = 0.0;                     // run ends closer than this (3D) are one vertex
};

void Shell::trace_boundary() {
  BoundaryTracer tracer(*this);
  euler_ = tracer.euler_characteristic();
  boundary_ = tracer.loops();
}

}  // namespace plyfit
