#include <plyfit/kernel/drape.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace plyfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The base plane must cut the surface at the start: the sine of the angle between the base
// plane and the tangent plane there must exceed this.
constexpr double kMinPlaneCutSin = 1e-3;
// A 3D sweep direction must make at least this sine with the base path in the tangent plane.
constexpr double kMinSweepSin = 1e-6;
// How often (resolved nodes) the scan checks for cancellation and reports progress.
constexpr std::uint32_t kCancelEvery = 4096;
constexpr std::uint32_t kProgressEvery = 65536;

std::uint64_t mix(std::uint64_t k) {  // splitmix64 finaliser
  k ^= k >> 30;
  k *= 0xbf58476d1ce4e5b9ULL;
  k ^= k >> 27;
  k *= 0x94d049bb133111ebULL;
  return k ^ (k >> 31);
}

}  // namespace

const char* to_string(NodeStatus s) {
  switch (s) {
    case NodeStatus::kMapped:
      return "mapped";
    case NodeStatus::kOutside:
      return "outside";
    case NodeStatus::kOffPly:
      return "off_ply";
    case NodeStatus::kShearLimit:
      return "shear_limit";
    case NodeStatus::kFailed:
      return "failed";
    case NodeStatus::kPending:
      return "pending";
  }
  return "failed";
}

// ---------------------------------------------------------------------------------------
// NodeIndex

std::int64_t NodeIndex::find(const NodeId& id) const {
  if (slots_.empty()) return -1;
  const std::uint64_t key = id.key();
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots_[h].key == key) return slots_[h].value;
    if (slots_[h].key == kEmpty) return -1;
  }
}

void NodeIndex::insert(const NodeId& id, std::uint32_t index) {
  if ((size_ + 1) * 2 > slots_.size()) grow();
  const std::uint64_t key = id.key();
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots_[h].key == kEmpty) {
      slots_[h] = {key, index};
      ++size_;
      return;
    }
  }
}

void NodeIndex::grow() {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(old.empty() ? 64 : old.size() * 2, Slot{});
  size_ = 0;
  const std::size_t mask = slots_.size() - 1;
  for (const Slot& s : old) {
    if (s.key == kEmpty) continue;
    for (std::size_t h = mix(s.key) & mask;; h = (h + 1) & mask) {
      if (slots_[h].key == kEmpty) {
        slots_[h] = s;
        ++size_;
        break;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// DrapeResult queries

const DrapeNode* DrapeResult::neighbour(const NodeId& id, ThreadDir dir) const {
  if (!id.is_path_only()) {
    const auto n = ply->neighbour(id.i, id.j, dir);
    return n ? find(n->id) : nullptr;
  }
  for (const auto& tn : ply->thread_neighbours(id))
    if (tn.dir == dir) return find(tn.n.id);
  return nullptr;
}

std::vector<DrapeLink> DrapeResult::links() const {
  std::vector<DrapeLink> out;
  auto idx = [&](const DrapeNode& n) { return static_cast<std::uint32_t>(&n - nodes.data()); };
  for (const DrapeNode& n : nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    for (int d = 0; d < 4; ++d) {
      const auto dir = static_cast<ThreadDir>(d);
      const auto nb = ply->neighbour(n.id.i, n.id.j, dir);
      if (!nb) continue;
      // Regular-regular links once (from their -x / -y end); links to path-only nodes from
      // the regular end, both sides.
      const bool plus = dir == ThreadDir::kPlusX || dir == ThreadDir::kPlusY;
      if (!nb->id.is_path_only() && !plus) continue;
      const DrapeNode* m = find(nb->id);
      if (!m || !m->mapped()) continue;
      out.push_back({idx(n), idx(*m), nb->rest, is_weft(dir) ? LinkKind::kWeft : LinkKind::kWarp});
    }
  }
  for (std::size_t k = 1; k < base_path.size(); ++k) {
    const DrapeNode& a = nodes[base_path[k - 1]];
    const DrapeNode& b = nodes[base_path[k]];
    // A path along a thread between two crossings is that thread's link, listed already.
    if (!a.id.is_path_only() && !b.id.is_path_only() &&
        std::abs(a.id.i - b.id.i) + std::abs(a.id.j - b.id.j) == 1)
      continue;
    out.push_back({base_path[k - 1], base_path[k], (b.ply - a.ply).norm(), LinkKind::kBase});
  }
  return out;
}

std::vector<std::vector<std::uint32_t>> DrapeResult::threads(bool weft) const {
  // Bucket mapped nodes by thread line: weft thread j (y = j d_warp) or warp thread i.
  struct Entry {
    double along;
    std::uint32_t node;
  };
  std::unordered_map<std::int32_t, std::vector<Entry>> lines;
  for (std::uint32_t k = 0; k < nodes.size(); ++k) {
    const DrapeNode& n = nodes[k];
    if (!n.mapped()) continue;
    std::int32_t line;
    if (!n.id.is_path_only()) {
      line = weft ? n.id.j : n.id.i;
    } else {
      const PathNode* pn = ply->path_node_if(n.id.j);
      if (!pn || !pn->link_from) continue;
      const bool on_weft = pn->link_dir == ThreadDir::kPlusX;
      if (on_weft != weft) continue;
      line = weft ? pn->link_from->j : pn->link_from->i;
    }
    lines[line].push_back({weft ? n.ply.x() : n.ply.y(), k});
  }
  std::vector<std::int32_t> keys;
  for (const auto& kv : lines) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end());
  std::vector<std::vector<std::uint32_t>> out;
  const ThreadDir fwd = weft ? ThreadDir::kPlusX : ThreadDir::kPlusY;
  for (std::int32_t key : keys) {
    auto& v = lines[key];
    std::sort(v.begin(), v.end(), [](const Entry& a, const Entry& b) { return a.along < b.along; });
    std::vector<std::uint32_t> run;
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (!run.empty()) {
        // Consecutive only if linked: the previous node's forward neighbour is this one.
        const DrapeNode* nb = neighbour(nodes[run.back()].id, fwd);
        if (nb != &nodes[v[k].node]) {
          if (run.size() >= 2) out.push_back(run);
          run.clear();
        }
      }
      run.push_back(v[k].node);
    }
    if (run.size() >= 2) out.push_back(run);
  }
  return out;
}

double DrapeResult::bytes_per_node() const {
  if (nodes.empty()) return 0.0;
  return static_cast<double>(nodes.capacity() * sizeof(DrapeNode) + index.memory_bytes()) /
         static_cast<double>(nodes.size());
}

// ---------------------------------------------------------------------------------------
// The scan

namespace {

struct FrontierEntry {
  double sweep;  // distance from the base path along the sweep direction
  double dist;   // distance to the start (tie-break)
  std::int32_t i, j;
};
struct FrontierLater {
  bool operator()(const FrontierEntry& a, const FrontierEntry& b) const {
    if (a.sweep != b.sweep) return a.sweep > b.sweep;
    if (a.dist != b.dist) return a.dist > b.dist;
    if (a.i != b.i) return a.i > b.i;
    return a.j > b.j;
  }
};

class Scanner {
 public:
  Scanner(const DrapeSurface& s, Ply& ply, const DrapeOptions& opt, DrapeResult& res)
      : s_(s), ply_(ply), opt_(opt), res_(res) {
    st_.spacing = ply.d();
    st_.tol = opt.tol;
    st_.gamma_min = std::max(0.0, kPi / 2 - opt.lock_angle);
    res_.gamma_min_limit = st_.gamma_min;
  }

  void run(const Vec3& t3) {
    map_path(t3);
    scan();
  }
  bool truncated() const { return truncated_; }
  bool cancelled() const { return cancelled_; }

 private:
  // Node for id, created (pending) at ply position `pos` if absent.
  std::uint32_t node_for(const NodeId& id, const Vec2& pos) {
    const auto k = res_.index.find(id);
    if (k >= 0) return static_cast<std::uint32_t>(k);
    DrapeNode n;
    n.id = id;
    n.ply = pos;
    res_.nodes.push_back(n);
    const auto idx = static_cast<std::uint32_t>(res_.nodes.size() - 1);
    res_.index.insert(id, idx);
    return idx;
  }

  void resolve(std::uint32_t idx, const SolveResult& r) {
    DrapeNode& n = res_.nodes[idx];
    n.order = order_++;
    ++res_.metrics.solves;
    res_.metrics.iterations += static_cast<std::uint64_t>(r.iterations);
    res_.metrics.evaluations += static_cast<std::uint64_t>(r.evaluations);
    switch (r.status) {
      case SolveStatus::kConverged:
        n.status = NodeStatus::kMapped;
        n.point = r.point;
        n.uv = r.uv;
        break;
      case SolveStatus::kLeftFace:
        n.status = NodeStatus::kOutside;
        if (r.extended) {
          n.point = r.point;
          n.uv = r.uv;
          n.flags |= DrapeNode::kExtended;
        }
        break;
      case SolveStatus::kShearLimit:
        n.status = NodeStatus::kShearLimit;
        break;
      case SolveStatus::kFailed:
        n.status = NodeStatus::kFailed;
        break;
    }
  }

  Vec3 normal_at(const DrapeNode& n) const { return s_.normal(n.uv).n; }

  // §5.1: the base path both ways from the start.
  void map_path(const Vec3& t3) {
    const PathNode* p0 = ply_.path_node(0);
    const std::uint32_t i0 = node_for(p0->id, p0->pos);
    DrapeNode& n0 = res_.nodes[i0];
    n0.status = NodeStatus::kMapped;
    n0.point = res_.start_point;
    n0.uv = res_.start_uv;
    n0.flags |= DrapeNode::kOnPath | DrapeNode::kStart;
    n0.order = order_++;
    std::vector<std::uint32_t> ahead{i0}, behind;
    for (int dirn = 0; dirn < 2; ++dirn) {
      const bool fwd = dirn == 0;
      auto& chain = fwd ? ahead : behind;
      std::uint32_t prev = i0;
      Vec3 travel = fwd ? t3 : Vec3(-t3);
      for (std::int32_t k = fwd ? 1 : -1;; k += fwd ? 1 : -1) {
        const PathNode* pk = ply_.path_node(k);
        if (!pk) {
          // Off the ply rectangle (or the path cap): the cloth ends here.
          if (ply_.spec().rect) ++path_off_ply_;
          break;
        }
        const PathNode* pp = ply_.path_node_if(fwd ? k - 1 : k + 1);
        const std::uint32_t idx = node_for(pk->id, pk->pos);
        DrapeNode& n = res_.nodes[idx];
        n.flags |= DrapeNode::kOnPath;
        const DrapeNode& from = res_.nodes[prev];
        const SolveResult r = solve_base_path(
            s_, {from.point, from.uv, res_.base_normal, travel, std::abs(pk->tau - pp->tau)}, st_);
        resolve(idx, r);
        if (!res_.nodes[idx].mapped()) break;
        chain.push_back(idx);
        travel = res_.nodes[idx].point - from.point;
        prev = idx;
        if (cancelled_now()) break;
      }
    }
    std::reverse(behind.begin(), behind.end());
    res_.base_path = behind;
    res_.base_path.insert(res_.base_path.end(), ahead.begin(), ahead.end());
    for (std::uint32_t k : res_.base_path) push_neighbours(k);
  }

  bool cancelled_now() {
    if (opt_.cancel && opt_.cancel->load(std::memory_order_relaxed)) cancelled_ = true;
    return cancelled_;
  }

  // Adds the unknown regular neighbours of a mapped node to the frontier.
  void push_neighbours(std::uint32_t idx) {
    const NodeId id = res_.nodes[idx].id;
    for (const auto& tn : ply_.thread_neighbours(id)) {
      const NodeId q = tn.n.id;
      if (q.is_path_only()) continue;  // path nodes are mapped by the base path
      const Vec2 qp = ply_.pos(q.i, q.j);
      const int side = ply_.side(qp);
      if (side == 0) continue;  // on the path: mapped (or not) by the base path
      if (ply_.sweep_for_side(side) < 0) continue;  // that half-plane is not swept
      if (res_.index.find(q) >= 0) continue;  // pending or resolved
      if (res_.nodes.size() >= opt_.max_nodes) {
        truncated_ = true;
        continue;
      }
      const std::uint32_t qi = node_for(q, qp);
      if (!ply_.on_ply(qp)) {
        res_.nodes[qi].status = NodeStatus::kOffPly;
        res_.nodes[qi].order = order_++;
        continue;
      }
      heap_.push({ply_.sweep_distance(qp), (qp - ply_.spec().start).norm(), q.i, q.j});
    }
  }

  const DrapeNode* mapped_neighbour(const NodeId& id, ThreadDir dir, double* rest = nullptr) const {
    std::optional<PlyNeighbour> nb;
    if (!id.is_path_only()) {
      nb = ply_.neighbour(id.i, id.j, dir);
    } else {
      for (const auto& tn : ply_.thread_neighbours(id))
        if (tn.dir == dir) nb = tn.n;
    }
    if (!nb) return nullptr;
    const DrapeNode* n = res_.find(nb->id);
    if (!n || !n->mapped()) return nullptr;
    if (rest) *rest = nb->rest;
    return n;
  }

  // Solver 2 for q from neighbours a (direction da from q) and b (db).
  SolveResult solve_two(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra,
                        const DrapeNode& b, ThreadDir db, double rb) {
    // Branch: the triangle (a, b, q) keeps its 2D orientation about the normal.
    const Vec2 e2 = b.ply - a.ply;
    double c2 = cross2(e2, q.ply - a.ply);
    if (std::abs(c2) <= opt_.tol.ply_merge_rel * ply_.d() * e2.norm()) {
      const int k = ply_.sweep_for_side(ply_.side(q.ply));
      c2 = cross2(e2, ply_.spec().sweeps[k]);
    }
    TwoSphereStep step{a.point, a.uv, ra, b.point, b.uv, rb, c2 > 0 ? 1.0 : -1.0, std::nullopt};
    // Initial guess.
    const DrapeNode* ap = mapped_neighbour(a.id, da);  // a's predecessor on q's thread
    const DrapeNode* bp = mapped_neighbour(b.id, db);
    const DrapeNode* c = nullptr;  // the cell's fourth corner
    if (!a.id.is_path_only() && !b.id.is_path_only()) {
      c = res_.find(NodeId::regular(a.id.i + b.id.i - q.id.i, a.id.j + b.id.j - q.id.j));
      if (c && !c->mapped()) c = nullptr;
    }
    auto paper = [&] {
      step.guess = two_sphere_guess(s_, a.uv, ap->uv, a.point, ap->point, ra, b.uv, bp->uv,
                                    b.point, bp->point, rb);
    };
    auto parallelogram = [&] { step.guess = a.uv + s_.delta(c->uv, b.uv); };
    if (opt_.guess == GuessRule::kPaper) {
      if (ap && bp) paper();
      else if (c) parallelogram();
    } else {
      if (c) parallelogram();
      else if (ap && bp) paper();
    }
    SolverSettings st = st_;
    if (is_weft(da) == is_weft(db)) st.gamma_min = 0.0;  // same thread: no thread angle
    return solve_two_spheres(s_, step, st);
  }

  // Solver 3 for q from its one known neighbour a (direction da from q, rest ra).
  SolveResult solve_one(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra) {
    const Vec3 na = normal_at(a);
    const Vec2 q2 = q.ply - a.ply;
    Vec3 ref3;
    Vec2 ref2;
    const DrapeNode* ap = mapped_neighbour(a.id, da);  // a's predecessor on q's thread
    if (a.has(DrapeNode::kOnPath)) {
      // Next to the base path: the 2D angle between the path and the thread is kept on the
      // tangent plane (§6.1, Fig. 9); the path tangent is that of the plane section.
      ref3 = na.cross(res_.base_normal);
      const Vec3 chord = path_chord(a);
      if (ref3.dot(chord) < 0) ref3 = -ref3;
      ref2 = ply_.base_dir();
    } else if (ap) {
      // Elsewhere: continue the thread along its previous segment.
      ref3 = a.point - ap->point;
      ref2 = a.ply - ap->ply;
    } else {
      // Fall back on any mapped neighbour of a, keeping the 2D angle to it.
      const DrapeNode* r = nullptr;
      for (int d = 0; d < 4 && !r; ++d) r = mapped_neighbour(a.id, static_cast<ThreadDir>(d));
      if (!r) {
        SolveResult f;
        f.reason = "no reference direction at the known neighbour";
        return f;
      }
      ref3 = r->point - a.point;
      ref2 = r->ply - a.ply;
    }
    ref3 -= ref3.dot(na) * na;
    if (!(ref3.norm() > 0.0)) {
      SolveResult f;
      f.reason = "the reference direction is normal to the surface";
      return f;
    }
    const double theta = std::atan2(cross2(ref2, q2), ref2.dot(q2));
    const Vec3 dir = rotate_about(ref3.normalized(), na, theta);
    return solve_plane_sphere(s_, {a.point, a.uv, ra, dir}, st_);
  }

  // Direction of the base path at path node a, along +tau (a chord to a path neighbour).
  Vec3 path_chord(const DrapeNode& a) const {
    const auto& bp = res_.base_path;
    const auto it = std::find(bp.begin(), bp.end(), static_cast<std::uint32_t>(&a - res_.nodes.data()));
    if (it == bp.end()) return res_.base_tangent;
    if (it + 1 != bp.end()) return res_.nodes[*(it + 1)].point - a.point;
    if (it != bp.begin()) return a.point - res_.nodes[*(it - 1)].point;
    return res_.base_tangent;
  }

  void scan() {
    std::uint32_t popped = 0;
    while (!heap_.empty()) {
      const FrontierEntry e = heap_.top();
      heap_.pop();
      if (++popped % kCancelEvery == 0 && cancelled_now()) break;
      if (opt_.progress && popped % kProgressEvery == 0) opt_.progress(res_.metrics.solves);
      const NodeId qid = NodeId::regular(e.i, e.j);
      const std::uint32_t qi = static_cast<std::uint32_t>(res_.index.find(qid));
      // Known neighbours, weft and warp.
      struct Known {
        ThreadDir dir;
        const DrapeNode* n;
        double rest;
      };
      Known known[4];
      int nk = 0;
      for (int d = 0; d < 4; ++d) {
        double rest = 0.0;
        const auto dir = static_cast<ThreadDir>(d);
        if (const DrapeNode* m = mapped_neighbour(qid, dir, &rest)) known[nk++] = {dir, m, rest};
      }
      const DrapeNode q = res_.nodes[qi];
      SolveResult r;
      if (nk >= 2) {
        // Prefer a weft-warp pair whose cell's fourth corner is mapped, then any weft-warp
        // pair, then two neighbours on one thread; ties by earlier mapping.
        int best_a = 0, best_b = 1, best_score = -1;
        for (int x = 0; x < nk; ++x) {
          for (int y = x + 1; y < nk; ++y) {
            int score = 0;
            if (is_weft(known[x].dir) != is_weft(known[y].dir)) {
              score = 1;
              const DrapeNode* a = known[x].n;
              const DrapeNode* b = known[y].n;
              if (!a->id.is_path_only() && !b->id.is_path_only()) {
                const DrapeNode* c = res_.find(NodeId::regular(a->id.i + b->id.i - qid.i, a->id.j + b->id.j - qid.j));
                if (c && c->mapped()) score = 2;
              }
            }
            if (score > best_score) {
              best_score = score;
              best_a = x;
              best_b = y;
            }
          }
        }
        // Order the pair (weft first) so that guesses and branches are reproducible.
        Known ka = known[best_a], kb = known[best_b];
        if (!is_weft(ka.dir) && is_weft(kb.dir)) std::swap(ka, kb);
        r = solve_two(q, *ka.n, ka.dir, ka.rest, *kb.n, kb.dir, kb.rest);
      } else if (nk == 1) {
        r = solve_one(q, *known[0].n, known[0].dir, known[0].rest);
      } else {
        r.reason = "no known neighbour";
      }
      resolve(qi, r);
      if (res_.nodes[qi].mapped()) push_neighbours(qi);
    }
    if (!heap_.empty()) {
      // Cancelled: whatever is still pending stays unresolved and is dropped.
      while (!heap_.empty()) heap_.pop();
    }
  }

 public:
  std::uint64_t path_off_ply_ = 0;

 private:
  const DrapeSurface& s_;
  Ply& ply_;
  const DrapeOptions& opt_;
  DrapeResult& res_;
  SolverSettings st_;
  std::priority_queue<FrontierEntry, std::vector<FrontierEntry>, FrontierLater> heap_;
  std::uint32_t order_ = 0;
  bool truncated_ = false, cancelled_ = false;
};

double tri_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }
double tri_area2(const Vec2& a, const Vec2& b, const Vec2& c) { return 0.5 * std::abs(cross2(b - a, c - a)); }

// Thread angles at mapped regular nodes: weft and warp directions by central differences
// where both neighbours along the thread are mapped, one-sided otherwise.
void thread_angles(DrapeResult& res) {
  for (DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    auto direction = [&](ThreadDir plus, Vec3& out) {
      const DrapeNode* p = res.neighbour(n.id, plus);
      const DrapeNode* m = res.neighbour(n.id, opposite(plus));
      const bool hp = p && p->mapped(), hm = m && m->mapped();
      if (hp && hm) out = p->point - m->point;
      else if (hp) out = p->point - n.point;
      else if (hm) out = n.point - m->point;
      else return false;
      return out.norm() > 0.0;
    };
    Vec3 wf, wp;
    if (!direction(ThreadDir::kPlusX, wf) || !direction(ThreadDir::kPlusY, wp)) continue;
    n.thread_angle = std::atan2(wf.cross(wp).norm(), wf.dot(wp));
    n.flags |= DrapeNode::kHasAngle;
  }
}

// 2D and 3D area of the mapped cells. A cell the base path crosses is split by the path
// into two convex parts, each counted if all its corners are mapped.
void cell_areas(DrapeResult& res) {
  const Ply& ply = *res.ply;
  double a2 = 0.0, a3 = 0.0;
  auto add_polygon = [&](const std::vector<const DrapeNode*>& poly) {
    for (const DrapeNode* v : poly)
      if (!v || !v->mapped()) return;
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
      a2 += tri_area2(poly[0]->ply, poly[k]->ply, poly[k + 1]->ply);
      a3 += tri_area(poly[0]->point, poly[k]->point, poly[k + 1]->point);
    }
  };
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    const std::int32_t i = n.id.i, j = n.id.j;
    // Cell with lower-left corner (i, j): corners counter-clockwise, with the path nodes that
    // split its edges.
    const NodeId corner[4] = {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                              NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)};
    const ThreadDir edge_dir[4] = {ThreadDir::kPlusX, ThreadDir::kPlusY, ThreadDir::kMinusX,
                                   ThreadDir::kMinusY};
    std::vector<NodeId> ring;
    bool cut = false;
    for (int e = 0; e < 4; ++e) {
      ring.push_back(corner[e]);
      const auto nb = ply.neighbour(corner[e].i, corner[e].j, edge_dir[e]);
      if (!nb) {
        cut = true;  // split by a path node that was never generated: count nothing
        ring.clear();
        break;
      }
      if (nb->id.is_path_only()) {
        ring.push_back(nb->id);
        cut = true;
      }
    }
    if (ring.empty()) continue;
    // Are the corners on both sides of the path (or is a path node inside the cell)?
    int sides = 0;
    for (const NodeId& c : corner) sides |= (ply.side(ply.pos(c.i, c.j)) > 0 ? 1 : 0) | (ply.side(ply.pos(c.i, c.j)) < 0 ? 2 : 0);
    const bool crossed = cut || sides == 3;
    if (!crossed) {
      std::vector<const DrapeNode*> poly;
      for (const NodeId& c : corner) poly.push_back(res.find(c));
      add_polygon(poly);
      continue;
    }
    // Split the ring by the path: path nodes on the ring (splits, and corners on the path)
    // plus path-only nodes strictly inside the cell (the start) form the cut.
    std::vector<const DrapeNode*> inside;
    const Vec2 lo = ply.pos(i, j), hi = ply.pos(i + 1, j + 1);
    for (std::uint32_t k : res.base_path) {
      const DrapeNode& p = res.nodes[k];
      if (!p.id.is_path_only()) continue;
      if (p.ply.x() > lo.x() && p.ply.x() < hi.x() && p.ply.y() > lo.y() && p.ply.y() < hi.y())
        inside.push_back(&p);
    }
    for (int s : {1, -1}) {
      std::vector<const DrapeNode*> poly;
      std::vector<Vec2> pos2;
      for (const NodeId& id : ring) {
        const Vec2 p = ply.pos(id);
        const int sd = id.is_path_only() ? 0 : ply.side(p);
        if (sd == s || sd == 0) {
          poly.push_back(res.find(id));
          pos2.push_back(p);
        }
      }
      if (poly.size() + inside.size() < 3) continue;
      for (const DrapeNode* p : inside) {
        poly.push_back(p);
        pos2.push_back(p->ply);
      }
      // Order the convex part counter-clockwise about its centroid.
      Vec2 c = Vec2::Zero();
      for (const auto& p : pos2) c += p;
      c /= static_cast<double>(pos2.size());
      std::vector<std::size_t> ord(poly.size());
      for (std::size_t k = 0; k < ord.size(); ++k) ord[k] = k;
      std::sort(ord.begin(), ord.end(), [&](std::size_t x, std::size_t y) {
        return std::atan2(pos2[x].y() - c.y(), pos2[x].x() - c.x()) <
               std::atan2(pos2[y].y() - c.y(), pos2[y].x() - c.x());
      });
      std::vector<const DrapeNode*> sorted;
      for (std::size_t k : ord) sorted.push_back(poly[k]);
      add_polygon(sorted);
    }
  }
  res.metrics.flat_area = a2;
  res.metrics.surface_area = a3;
}

void compute_metrics(const DrapeSurface& s, DrapeResult& res) {
  DrapeMetrics& m = res.metrics;
  thread_angles(res);
  bool first = true;
  for (const DrapeNode& n : res.nodes) {
    switch (n.status) {
      case NodeStatus::kMapped:
        (n.id.is_path_only() ? m.nodes.auxiliary : m.nodes.mapped)++;
        break;
      case NodeStatus::kOutside:
        ++m.nodes.outside;
        break;
      case NodeStatus::kOffPly:
        ++m.nodes.off_ply;
        break;
      case NodeStatus::kShearLimit:
        ++m.nodes.shear_limit;
        break;
      case NodeStatus::kFailed:
        ++m.nodes.failed;
        break;
      case NodeStatus::kPending:
        break;
    }
    if (n.has(DrapeNode::kHasAngle)) {
      const double g = n.thread_angle;
      m.gamma_min = first ? g : std::min(m.gamma_min, g);
      m.gamma_max = first ? g : std::max(m.gamma_max, g);
      first = false;
      m.shear_energy += std::cos(g) * std::cos(g);
      ++m.angles;
    }
  }
  m.area_mesh_points = m.nodes.mapped;
  cell_areas(res);
  // Independent residual checks.
  const double d = res.ply->d();
  for (const DrapeLink& l : res.links()) {
    const double len = (res.nodes[l.a].point - res.nodes[l.b].point).norm();
    m.edge_length_max_rel = std::max(m.edge_length_max_rel, std::abs(len - l.rest) / d);
  }
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const SurfaceEval1 e = s.eval1(n.uv);
    m.surface_distance_max = std::max(m.surface_distance_max, e.ok ? (e.p - n.point).norm() : INFINITY);
    if (n.has(DrapeNode::kOnPath))
      m.base_plane_max_rel = std::max(
          m.base_plane_max_rel, std::abs(res.base_normal.dot(n.point - res.start_point)) / d);
  }
  if (!std::isfinite(m.surface_distance_max)) m.surface_distance_max = 1e300;
}

}  // namespace

Result<DrapeResult> drape(const DrapeSurface& s, const DrapeProblem& pb, const DrapeOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  auto ply = Ply::create(pb.ply, opt.tol);
  if (!ply) return ply.error();
  if (pb.sweeps.size() != pb.ply.sweeps.size())
    return Error{"give as many 3D sweep directions as 2D ones (" +
                 std::to_string(pb.ply.sweeps.size()) + " 2D, " + std::to_string(pb.sweeps.size()) +
                 " 3D)"};
  if (!pb.start.allFinite()) return Error{"the 3D start point must be finite"};
  if (!pb.base_normal.allFinite() || !(pb.base_normal.norm() > 0.0))
    return Error{"the base-plane normal must be a non-zero vector"};
  if (!(opt.lock_angle > 0.0) || opt.lock_angle > kPi / 2)
    return Error{"the lock angle must be in (0, 90] degrees"};

  DrapeResult res;
  res.base_normal = pb.base_normal.normalized();
  const Projection pr = s.project(pb.start);
  if (!pr.ok) return Error{"cannot project the start point onto the face"};
  res.start_point = pr.point;
  res.start_uv = pr.uv;
  res.start_moved = pr.distance;
  const SurfaceNormal sn = s.normal(pr.uv);
  if (!sn.ok) return Error{"no surface normal at the start point"};
  const Vec3 n0 = sn.n;
  Vec3 t3 = n0.cross(res.base_normal);
  if (t3.norm() < kMinPlaneCutSin)
    return Error{"the base plane does not cut the face near the start (it is tangent to the "
                 "surface there); choose a base-plane normal along the surface"};
  t3.normalize();
  // Pairing of 2D and 3D: (base, sweep) has the same handedness about the normal in both.
  const Ply& P = *ply;
  std::vector<double> side3;
  for (std::size_t k = 0; k < pb.sweeps.size(); ++k) {
    Vec3 w = pb.sweeps[k];
    if (!w.allFinite() || !(w.norm() > 0.0))
      return Error{"3D sweep direction " + std::to_string(k + 1) + " must be a non-zero vector"};
    w -= w.dot(n0) * n0;
    const double c = n0.dot(t3.cross(w.normalized()));
    if (!(w.norm() > kMinSweepSin * pb.sweeps[k].norm()) || std::abs(c) < kMinSweepSin)
      return Error{"3D sweep direction " + std::to_string(k + 1) +
                   " is normal to the surface or parallel to the base path at the start"};
    side3.push_back(c > 0 ? 1.0 : -1.0);
  }
  std::vector<double> side2;
  for (const Vec2& w : P.spec().sweeps) side2.push_back(cross2(P.base_dir(), w) > 0 ? 1.0 : -1.0);
  if (side3[0] != side2[0]) {
    t3 = -t3;
    for (double& x : side3) x = -x;
  }
  if (side3.size() == 2 && side3[1] != side2[1])
    return Error{"the two 3D sweep directions must lie on the two sides of the base path, "
                 "as the 2D ones do"};
  res.base_tangent = t3;
  auto mply = std::make_shared<Ply>(std::move(ply).value());  // the scan extends the path
  res.ply = mply;

  Scanner scanner(s, *mply, opt, res);
  scanner.run(t3);
  compute_metrics(s, res);
  res.metrics.nodes.off_ply += scanner.path_off_ply_;
  if (scanner.cancelled()) {
    res.partial = true;
    res.warnings.push_back("cancelled");
  }
  if (scanner.truncated()) {
    res.partial = true;
    res.warnings.push_back("stopped at the node cap of " + std::to_string(opt.max_nodes) + " nodes");
  }
  if (res.metrics.nodes.failed > 0) {
    res.partial = true;
    res.warnings.push_back(std::to_string(res.metrics.nodes.failed) +
                           " node(s) where the solver found no solution");
  }
  res.drape_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace plyfit
