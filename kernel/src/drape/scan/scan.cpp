// The frontier scan of §6.2: nodes next to mapped ones, in sweep order; node bookkeeping, and
// the overlap and fold tests that stop the cloth where it would lie on itself.
#include "drape/scan/scanner.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit::detail {

Scanner::Scanner(const DrapeSurface& s, Ply& ply, const DrapeOptions& opt, DrapeResult& res)
    : s_(s), ply_(ply), opt_(opt), res_(res) {
  st_.spacing = ply.d();
  st_.tol = opt.tol;
  res_.gamma_min_limit = std::max(0.0, kPi / 2 - opt.lock_angle);
  st_.gamma_min = std::max(res_.gamma_min_limit, opt.tol.fold_angle);
  far_ = kFarFromPathCells * std::hypot(ply.spec().d_weft, ply.spec().d_warp);
  one_face_ = s.face_count() == 1;
  cell_ = kOverlapRel * ply.d();
  // With the test every mapped node is recorded; without it only the base path's nodes (the
  // path's own test for a plane section that comes round): the table grows from its least.
  grid_.init(cell_, opt.overlap_test ? res_.nodes.capacity() : 0);
}

void Scanner::run(const Vec3& t3) {
  map_path(t3);
  scan();
  finish_cuts();
}

// The id across the thread link from `id` in direction d, if that node can exist.
std::optional<NodeId> Scanner::neighbour_id(const NodeId& id, ThreadDir d) const {
  if (!id.is_path_only()) {
    if (far_from_path(ply_.pos(id.i, id.j))) {  // no link of (i, j) is split by the path
      const int k = static_cast<int>(d);
      return NodeId::regular(id.i + (k == 0   ? 1
                                     : k == 1 ? -1
                                              : 0),
                             id.j + (k == 2   ? 1
                                     : k == 3 ? -1
                                              : 0));
    }
    const auto n = ply_.neighbour(id.i, id.j, d);
    return n ? std::optional<NodeId>(n->id) : std::nullopt;
  }
  const PathNode* pn = ply_.path_node_if(id.j);
  if (!pn || !pn->link_from) return std::nullopt;
  if (d == opposite(pn->link_dir)) return *pn->link_from;
  if (d == pn->link_dir) {
    const NodeId a = *pn->link_from;
    return pn->link_dir == ThreadDir::kPlusX ? NodeId::regular(a.i + 1, a.j)
                                             : NodeId::regular(a.i, a.j + 1);
  }
  return std::nullopt;
}

// True when ply point p lies so far from the base path line that no thread link from it
// (and no link within kFarFromPathCells - 1 cells of it) can cross the path.
bool Scanner::far_from_path(const Vec2& p) const {
  return std::abs(cross2(ply_.base_dir(), p - ply_.spec().start)) > far_;
}

// Node for id, created (pending) at ply position `pos` if absent, linked both ways to the
// existing nodes across its thread links.
std::uint32_t Scanner::node_for(const NodeId& id, const Vec2& pos) {
  const auto k = res_.index->find(id);
  if (k >= 0) return static_cast<std::uint32_t>(k);
  DrapeNode n;
  n.id = id;
  n.ply = pos;
  const auto idx = static_cast<std::uint32_t>(res_.nodes.size());
  for (int d = 0; d < 4; ++d) {
    const auto nid = neighbour_id(id, static_cast<ThreadDir>(d));
    if (!nid) continue;
    const auto m = res_.index->find(*nid);
    if (m < 0) continue;
    n.nb[d] = static_cast<std::int32_t>(m);
    const auto mi = static_cast<std::uint32_t>(m);
    std::int32_t& back = res_.nodes[mi].nb[static_cast<int>(opposite(static_cast<ThreadDir>(d)))];
    back = static_cast<std::int32_t>(idx);
  }
  if (res_.nodes.size() == res_.nodes.capacity())  // beyond the estimate: grow by half
    res_.nodes.reserve(res_.nodes.capacity() + res_.nodes.capacity() / 2 + 16);
  res_.nodes.push_back(n);
  res_.index->insert(id, idx);
  return idx;
}

void Scanner::resolve(std::uint32_t idx, const SolveResult& r) {
  DrapeNode& n = node(idx);
  n.order = order_++;
  ++res_.metrics.solves;
  res_.metrics.iterations += static_cast<std::uint64_t>(r.iterations);
  res_.metrics.evaluations += static_cast<std::uint64_t>(r.evaluations);
  switch (r.status) {
    case SolveStatus::kConverged:
      n.status = NodeStatus::kMapped;
      n.point = r.point;
      n.set_at(r.at);
      res_.metrics.solve_residual_max_rel =
          std::max(res_.metrics.solve_residual_max_rel, r.residual / st_.spacing);
      break;
    case SolveStatus::kLeftFace:
      n.status = NodeStatus::kOutside;
      if (r.extended) {
        n.point = r.point;
        n.set_at(r.at);
        n.flags |= DrapeNode::kExtended;
        // In a hole of the face the surface runs on under it: the cloth goes on from the node
        // as on a face without the hole (the flat pattern cuts the hole out).
        if (s_.in_hole(r.at)) n.flags |= DrapeNode::kInHole;
      }
      break;
    case SolveStatus::kShearLimit: {
      // Only the lock stops a node at the shear limit; a fold guard's node is cloth folded
      // onto itself (an overlap, counted by the guard's code).
      const ShearStop stop = shear_stop(r);
      const bool lock = stop == ShearStop::kLock || stop == ShearStop::kBehindStop;
      n.status = lock ? NodeStatus::kShearLimit : NodeStatus::kOverlap;
      res_.failures.emplace_back(idx, to_string(stop));
      break;
    }
    case SolveStatus::kFailed:
      // The base path ends where its plane's section turns back (path_end).
      if (r.section_ends && n.has(DrapeNode::kOnPath)) {
        n.status = NodeStatus::kPathEnd;
        break;
      }
      // A thread continued from one node whose plane's section turns back within the link:
      // the surface curls back tighter than the thread spacing (surf114 face 2, towards its
      // degenerate edge: at most 0.97 d from the node). No point of the face lies a link
      // ahead on the thread: the cloth leaves the surface there, outside (warned).
      if (r.section_ends) {
        n.status = NodeStatus::kOutside;
        if (thread_ends_.nodes++ == 0) thread_ends_.first = n.ply;
        break;
      }
      n.status = r.fronts_disagree ? NodeStatus::kConflict : NodeStatus::kFailed;
      res_.failures.emplace_back(idx, r.reason);
      break;
  }
}

// The guard that stopped a node at the shear limit: an angle past gamma_min is the lock's
// where it passes the lock angle, else the fold angle's (Tolerances::fold_angle).
ShearStop Scanner::shear_stop(const SolveResult& r) const {
  if (r.shear_stop != ShearStop::kLock) return r.shear_stop;
  const double lock = res_.gamma_min_limit;
  const bool past_lock = lock > 0.0 && (r.thread_angle < lock || r.thread_angle > kPi - lock);
  return past_lock ? ShearStop::kLock : ShearStop::kFoldAngle;
}

// True if node k (just mapped) lies on cloth already laid: a recorded node within
// kOverlapRel * d in 3D but at least kOverlapSeparation * d away on the ply; otherwise
// records it.
bool Scanner::overlaps(std::uint32_t k) {
  const DrapeNode& n = node(k);
  // Called only for nodes the grid's filter passes (rare): everything it needs is worked
  // out here, not before the test.
  return grid_.test_insert(n.point, k, [this, &n](std::uint32_t m) {
    const DrapeNode& o = res_.nodes[m];
    const double sep = kOverlapSeparation * ply_.d();
    // Cloth beside a dart lies close to the other side's across it: no overlap.
    return (o.point - n.point).squaredNorm() < cell_ * cell_ &&
           (o.ply - n.ply).squaredNorm() >= sep * sep &&
           !(darts_ && darts_->crosses(o.point, n.point));
  });
}

// Node k, mapped or in a hole, lies on cloth already laid (`why`: the test that found it):
// mapped, it is an overlap; in a hole, the cloth under the hole goes no further from it.
void Scanner::stop_overlap(std::uint32_t k, const char* why) {
  DrapeNode& n = node(k);
  if (n.mapped()) {
    n.status = NodeStatus::kOverlap;
    res_.failures.emplace_back(k, why);
  } else {
    n.flags = static_cast<std::uint8_t>(n.flags & ~DrapeNode::kInHole);
  }
}

bool Scanner::cancelled_now() {
  if (opt_.cancel && opt_.cancel->load(std::memory_order_relaxed)) cancelled_ = true;
  return cancelled_;
}

// Adds the unknown regular neighbours of a mapped node to the frontier.
void Scanner::push_neighbours(std::uint32_t idx) {
  for (int d = 0; d < 4; ++d) {
    if (node(idx).nb[d] >= 0) {  // already reached (pending or resolved)
      if (!parked_.empty()) unpark(node(idx).nb[d]);
      continue;
    }
    const auto q = neighbour_id(node(idx).id, static_cast<ThreadDir>(d));
    if (!q || q->is_path_only()) continue;  // path nodes are mapped by the base path
    const Vec2 qp = ply_.pos(q->i, q->j);
    const int side = ply_.side(qp);
    // On the path: mapped (or not) by the base path, which goes on across holes of the face
    // (map_path). (Solving the line from the sweep that reaches it first lets one sweep's
    // cloth cross the line and meet the other's sheared on a curved face.) Beyond the
    // path's ends the line is plain cloth between the two swept half-planes: a face whose
    // outline comes back across the line past a notch is reached there (beyond_path()).
    if (side == 0 ? !beyond_path(qp) : ply_.sweep_for_side(side) < 0) continue;
    if (res_.nodes.size() >= opt_.max_nodes) {
      truncated_ = true;
      continue;
    }
    const std::uint32_t qi = node_for(*q, qp);
    if (!ply_.on_ply(qp)) {
      node(qi).status = NodeStatus::kOffPly;
      node(qi).order = order_++;
      continue;
    }
    heap_.push({ply_.sweep_distance(qp), (qp - ply_.spec().start).norm(), q->i, q->j, qi});
  }
}

// True when ply point p on the base path's line lies beyond both ends of the mapped path
// (more than a merge distance past its last node, the one where it stopped), with both
// half-planes swept: the cloth may cross the line there.
bool Scanner::beyond_path(const Vec2& p) const {
  if (ply_.sweep_for_side(1) < 0 || ply_.sweep_for_side(-1) < 0) return false;
  const double t = (p - ply_.spec().start).dot(ply_.base_dir());
  const double merge = opt_.tol.ply_merge_rel * ply_.d();
  return t > path_t_[1] + merge || t < path_t_[0] - merge;
}

// True if a thread through node k (just mapped) turns back on itself there: the link to
// a mapped neighbour and that neighbour's next link along the same thread make an angle
// over 90 degrees. A smooth surface turns a thread by about d / R per link (60 degrees
// at a curvature radius R = d); more is cloth folded onto itself, which two-sphere solves
// from a net sheared nearly flat can produce without end on a face that never lets it go.
bool Scanner::folds_back(std::uint32_t k) const {
  const DrapeNode& q = res_.nodes[k];
  for (int d = 0; d < 4; ++d) {
    const DrapeNode* a = mapped_nb(q, static_cast<ThreadDir>(d));
    const DrapeNode* a2 = a ? mapped_nb(*a, static_cast<ThreadDir>(d)) : nullptr;
    if (!a2) continue;
    const Vec3 l1 = a2->point - a->point, l2 = a->point - q.point;
    if (l1.dot(l2) >= 0.0) continue;
    // Past a crease (a shell's G0 shared edge, a thin flange's rim) the surface itself turns:
    // a thread turning by no more than 90 degrees beyond the turn of the surface's normal
    // between its ends follows the surface.
    const SurfaceNormal n1 = s_.normal(a2->at()), n2 = s_.normal(q.at());
    const double turn = std::atan2(l1.cross(l2).norm(), l1.dot(l2));
    const double bend = std::atan2(n1.n.cross(n2.n).norm(), n1.n.dot(n2.n));
    if (!n1.ok || !n2.ok || turn > bend + 0.5 * kPi) return true;
  }
  return false;
}

// True if a neighbour of q stopped at the shear limit (the lock, or behind it: a fold guard's
// node is an overlap). Such a node, reached from one side only, is stopped as well: continuing its
// thread straight (solver 3) past the locked node would fold the cloth over the cells the lock left
// open (on the sphere octant, case (c) with a 30 degree lock: mapped nodes sheared to 88 degrees,
// links off by 0.7 d).
bool Scanner::behind_lock(const DrapeNode& q) const {
  for (int d = 0; d < 4; ++d) {
    const std::int32_t k = q.nb[d];
    if (k >= 0 && res_.nodes[static_cast<std::size_t>(k)].status == NodeStatus::kShearLimit)
      return true;
  }
  return false;
}

// The scan: the frontier's nodes in sweep order, until none is left or it is cancelled.
void Scanner::scan() {
  while (!heap_.empty()) {
    const FrontierEntry e = heap_.top();
    heap_.pop();
    if (++popped_ % kCancelEvery == 0 && cancelled_now()) break;
    if (opt_.progress && popped_ % kProgressEvery == 0) opt_.progress(res_.metrics.solves);
    step(e.node);
  }
  while (!heap_.empty()) heap_.pop();  // cancelled: pending nodes stay unresolved
}

// Solves frontier node qi from its known neighbours and, if the cloth goes on from it,
// adds its neighbours to the frontier.
void Scanner::step(std::uint32_t qi) {
  const DrapeNode& qn = node(qi);
  Known known[4];
  const int nk = known_neighbours(qn, known);
  SolveResult r;
  if (darts_ && near_dart(known, nk)) {
    if (!solve_beside_darts(qi, known, nk, r)) return;  // parked: no side's cloth holds it yet
  } else {
    r = solve_or_reuse(qi, known, nk);
  }
  if (seams_ && r.fronts_disagree) solve_across_seam(qi, r);
  resolve(qi, r);
  // The cloth can come round onto itself (a closed face, a face that wraps over itself, a
  // net sheared nearly flat), or fold its threads back (folds_back()). In a hole the cloth
  // under the hole stops there (the node stays outside).
  if (!node(qi).carries()) return;
  if (opt_.overlap_test && overlaps(qi))
    stop_overlap(qi, kOnLaidCloth);
  else if (folds_back(qi))
    stop_overlap(qi, kThreadTurnsBack);
  if (node(qi).carries()) push_neighbours(qi);
}

// Node qi from its nk known neighbours: two or more (solver 2), one (solver 3, unless it is
// behind the shear limit), none.
SolveResult Scanner::solve_known(std::uint32_t qi, const Known known[4], int nk) {
  const DrapeNode& qn = node(qi);
  SolveResult r;
  if (nk >= 2) {
    r = solve_from_two(qi, known, nk);
  } else if (nk == 1 && behind_lock(qn)) {
    r.status = SolveStatus::kShearLimit;
    r.shear_stop = ShearStop::kBehindStop;
    r.reason = "behind the shear limit";
  } else if (nk == 1) {
    r = solve_one(qn, *known[0].n, known[0].dir, res_.rest_length(qn, known[0].dir));
  } else {
    r.reason = "no known neighbour";
  }
  return r;
}

// The neighbours of q the cloth goes on from (Scanner::mapped_nb), weft and warp.
int Scanner::known_neighbours(const DrapeNode& q, Known known[4]) const {
  int nk = 0;
  for (int d = 0; d < 4; ++d)
    if (const DrapeNode* m = mapped_nb(q, static_cast<ThreadDir>(d)))
      known[nk++] = {static_cast<ThreadDir>(d), m};
  return nk;
}

// The pair of known neighbours to solve from: a weft-warp pair whose cell's fourth corner is
// mapped (score 2), then any weft-warp pair (1), then two neighbours on one thread (0); its
// score.
int Scanner::best_pair(const DrapeNode& q, const Known known[4], int nk, int& best_a,
                       int& best_b) const {
  int best_score = -1;
  for (int x = 0; x < nk; ++x) {
    for (int y = x + 1; y < nk; ++y) {
      int score = 0;
      if (is_weft(known[x].dir) != is_weft(known[y].dir)) {
        score = 1;
        const DrapeNode* a = known[x].n;
        const DrapeNode* b = known[y].n;
        if (!a->id.is_path_only() && !b->id.is_path_only()) {
          const DrapeNode* c = mapped_nb(*a, known[y].dir);
          if (c && c->id == NodeId::regular(a->id.i + b->id.i - q.id.i, a->id.j + b->id.j - q.id.j))
            score = 2;
        }
      }
      if (score > best_score) {
        best_score = score;
        best_a = x;
        best_b = y;
      }
    }
  }
  return best_score;
}

// Node qi from two of its nk >= 2 known neighbours (solver 2), the links to the others checked.
SolveResult Scanner::solve_from_two(std::uint32_t qi, const Known known[4], int nk) {
  const DrapeNode& qn = node(qi);
  int best_a = 0, best_b = 1;
  best_pair(qn, known, nk, best_a, best_b);
  // Weft neighbour first, so that guesses and branches are reproducible.
  Known ka = known[best_a], kb = known[best_b];
  if (!is_weft(ka.dir) && is_weft(kb.dir)) std::swap(ka, kb);
  if (is_weft(ka.dir) != is_weft(kb.dir)) node(qi).set_solved_from(ka.dir, kb.dir);  // eq. 12
  SolveResult r = solve_two(qn, *ka.n, ka.dir, res_.rest_length(qn, ka.dir), *kb.n, kb.dir,
                            res_.rest_length(qn, kb.dir));
  // The solver tests eq. (12) on the face only; under a hole the cloth stops at the shear
  // limit as it would on the face without the hole.
  if (is_weft(ka.dir) != is_weft(kb.dir) && r.status == SolveStatus::kLeftFace && r.extended &&
      st_.gamma_min > 0.0 &&
      (r.thread_angle < st_.gamma_min || r.thread_angle > kPi - st_.gamma_min) &&
      s_.in_hole(r.at)) {
    r.status = SolveStatus::kShearLimit;
    r.shear_stop = ShearStop::kLock;
    r.reason = "thread angle beyond the shear limit (under a hole of the face)";
  }
  // Links to further known neighbours (fronts that met around a hole in the net) are
  // not solved for: a node that breaks one is no point of the cloth (three links on a
  // 2-D surface: in general no point fits them all; a conflict, not a solver failure).
  const bool landed = r.status == SolveStatus::kConverged ||
                      (r.status == SolveStatus::kLeftFace && r.extended && s_.in_hole(r.at));
  for (int x = 0; x < nk && landed && r.status != SolveStatus::kFailed; ++x) {
    if (known[x].n == ka.n || known[x].n == kb.n) continue;
    const double rest = res_.rest_length(qn, known[x].dir);
    const double err = std::abs((r.point - known[x].n->point).norm() - rest);
    if (err > kFrontMismatchRel * ply_.d()) {
      r.status = SolveStatus::kFailed;
      r.reason = "the fronts disagree: a third link is off";
      r.fronts_disagree = true;
    }
  }
  return r;
}

}  // namespace plyfit::detail
