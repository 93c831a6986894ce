// The corners of the touched cells that the drape never reached, solved beyond the face.

#include "pattern/cells.hpp"
#include "pattern/outline_builder.hpp"

#include <algorithm>
#include <set>

namespace plyfit::detail {

namespace {

// A placed corner continues a segment whose ends were placed at most this many times over
// (a cell's corners past the face from its corner on it, across a diagonal, and round the
// narrow tip of a face): farther from the cloth a repeated segment drifts off the surface,
// and the cells there have no corner on the face.
constexpr int kMaxPlacedDepth = 4;
// A placed corner's step in (u, v) is lengthened to at most this many of its thread's last
// steps to leave the face.
constexpr int kMaxPlacedSteps = 4;

}  // namespace

// They are solved the way the drape would have: from a weft and a warp neighbour (two
// spheres) wherever two are known, which propagates no error; a thread is continued through
// a neighbour (solver 3) only where no two-sphere solve is left, first along segments of the
// drape's own nodes, and only as a last resort along segments with a virtual end: continuing
// a thread extrapolates its last segment, so an error in either end comes out doubled
// (docs/decisions/flat-pattern-outline.md).
void OutlineBuilder::solve_virtual_corners() {
  std::vector<NodeId> todo;
  std::unordered_map<std::uint64_t, std::size_t> slot;  // todo index by key
  for (const auto [i, j] : cells_)
    for (const NodeId& c : {NodeId::regular(i, j), NodeId::regular(i + 1, j),
                            NodeId::regular(i + 1, j + 1), NodeId::regular(i, j + 1)})
      if (!position(c) && slot.emplace(c.key(), todo.size()).second) todo.push_back(c);
  // Work lists, so that every node is tried again only when a neighbour gains a position:
  // `queue` for two spheres; `retry` (ordered: deterministic) for a continuation along any
  // segment, `extrapolate` for the last resort where no solve lands. Whether a node continues along
  // the drape's own segments depends on the drape alone, so one pass in order (`next`) tries each
  // node once.
  std::vector<std::size_t> queue;
  std::set<std::size_t> retry, extrapolate;
  for (std::size_t k = todo.size(); k-- > 0;) {
    queue.push_back(k);
    retry.insert(k);
    extrapolate.insert(k);
  }
  // A corner solved makes its neighbours worth trying again by every means; one placed by
  // extrapolation (no point of the surface, so no solve starts from it) only by that.
  auto solved = [&](const NodeId& id, bool extrapolated) {
    for (int d = 0; d < 4; ++d)
      if (const auto n = ply_.neighbour(id.i, id.j, static_cast<ThreadDir>(d)))
        if (const auto it = slot.find(n->id.key());
            it != slot.end() && !virtual_.count(n->id.key())) {
          if (!extrapolated) {
            queue.push_back(it->second);
            retry.insert(it->second);
          }
          extrapolate.insert(it->second);
        }
  };
  auto known = [&](std::size_t k) { return virtual_.count(todo[k].key()) > 0; };
  // Tries the work list's nodes in order until one gains a position by `place`.
  auto first_placed = [&](std::set<std::size_t>& list, auto place, bool extrapolated) {
    while (!list.empty()) {
      const std::size_t k = *list.begin();
      list.erase(list.begin());
      if (!known(k) && place(todo[k])) {
        solved(todo[k], extrapolated);
        return true;
      }
    }
    return false;
  };
  std::size_t next = 0;
  for (;;) {  // each round solves a node or ends: at most todo.size() rounds
    while (!queue.empty()) {
      const std::size_t k = queue.back();
      queue.pop_back();
      if (!known(k) && virtual_by_spheres(todo[k])) solved(todo[k], false);
    }
    bool progress = false;
    for (; next < todo.size() && !progress; ++next)
      if (!known(next) && virtual_by_continuation(todo[next], true)) {
        solved(todo[next], false);
        progress = true;
      }
    progress =
        progress ||
        first_placed(
            retry, [&](const NodeId& id) { return virtual_by_continuation(id, false); }, false) ||
        first_placed(
            extrapolate, [&](const NodeId& id) { return virtual_by_extrapolation(id); }, true);
    if (!progress) break;
  }
}

// The known neighbours of a node the drape never reached, beyond the face, or none if the
// node is a path node, known, off the ply, in an unswept half-plane (the outline stays on
// the mapped side there), or one the drape reached and stopped for another reason than
// leaving the face (a shear limit, an overlap, a failure, a conflict: the cloth goes no
// further there, and a corner solved past such a node can fold its cell).
std::vector<OutlineBuilder::Nb> OutlineBuilder::virtual_neighbours(const NodeId& id,
                                                                   bool solved_only) const {
  std::vector<Nb> nbs;
  if (id.is_path_only() || virtual_.count(id.key())) return nbs;
  if (const DrapeNode* n = r_.find(id);
      n && (n->mapped() || n->has(DrapeNode::kExtended) || n->status != NodeStatus::kOutside))
    return nbs;
  const Vec2 q2 = ply_.pos(id);
  if (!ply_.on_ply(q2)) return nbs;
  if (ply_.side(q2) != 0 && ply_.sweep_for_side(ply_.side(q2)) < 0) return nbs;
  for (int d = 0; d < 4; ++d) {
    const auto dir = static_cast<ThreadDir>(d);
    const auto n = ply_.neighbour(id.i, id.j, dir);
    if (!n) continue;
    if (auto p = position(n->id); p && !(solved_only && p->placed > 0))
      nbs.push_back({n->id, n->rest, *p, dir});
  }
  return nbs;
}

// Keeps a virtual corner only if it lands outside the face (inside, the drape stopped for
// another reason).
bool OutlineBuilder::accept_virtual(const NodeId& id, const SolveResult& res) {
  if (!(res.status == SolveStatus::kLeftFace && res.extended)) return false;
  virtual_[id.key()] = Position{res.at, res.point, false};
  return true;
}

// False when p lies on the wrong side of the line a -> b (side > 0: to its left about the
// outward normal) near a pole, seen about the pole's normal; true elsewhere (the solver's
// own side test holds there).
bool OutlineBuilder::on_side(const Vec3& a, const Vec3& b, const Vec3& p, double side) const {
  const int q = nearest_pole(0.5 * (a + b));
  if (q < 0) return true;
  return pole_normals_[static_cast<std::size_t>(q)].dot((b - a).cross(p - a)) * side > 0.0;
}

// A virtual corner from a weft and a warp neighbour with positions.
bool OutlineBuilder::virtual_by_spheres(const NodeId& id) {
  const std::vector<Nb> nbs = virtual_neighbours(id, true);
  const Vec2 q2 = ply_.pos(id);
  for (const Nb& a : nbs)
    for (const Nb& b : nbs) {
      if (!is_weft(a.dir) || is_weft(b.dir)) continue;
      const std::array<std::uint64_t, 3> key{id.key(), a.id.key(), b.id.key()};
      if (failed_spheres_.count(key)) continue;
      const double side =
          cross2(ply_.pos(b.id) - ply_.pos(a.id), q2 - ply_.pos(a.id)) > 0 ? 1.0 : -1.0;
      auto solve = [&](double sd) {
        return solve_two_spheres(
            s_, {a.p.point, a.p.at, a.rest, b.p.point, b.p.at, b.rest, sd, std::nullopt}, st_);
      };
      SolveResult res = solve(side);
      // Past a pole (u < 0 on a surface of revolution) the surface's own normal is turned
      // over and the solver's branch with it: the corner comes out mirrored across the line
      // a-b, on the point of the cell's opposite corner. The other branch is then the one.
      if (res.status == SolveStatus::kLeftFace && res.extended &&
          !on_side(a.p.point, b.p.point, res.point, side))
        res = solve(-side);
      const bool sided = !(res.status == SolveStatus::kLeftFace && res.extended &&
                           !on_side(a.p.point, b.p.point, res.point, side));
      if (sided && accept_virtual(id, res)) return true;
      failed_spheres_.insert(key);
    }
  return false;
}

// The node before neighbour `a` on the thread through the node and `a`, beyond `a`.
std::optional<PlyNeighbour> OutlineBuilder::thread_before(const Nb& a) const {
  if (!a.id.is_path_only()) return ply_.neighbour(a.id.i, a.id.j, a.dir);
  for (const auto& tn : ply_.thread_neighbours(a.id))
    if (tn.dir == a.dir) return tn.n;
  return std::nullopt;
}

// A virtual corner continuing a thread through a neighbour: the neighbour's predecessor
// beyond it, away from the node, gives the thread's last segment. With `drape_only`, both
// ends of that segment must be the drape's own nodes.
bool OutlineBuilder::virtual_by_continuation(const NodeId& id, bool drape_only) {
  for (const Nb& a : virtual_neighbours(id, true)) {
    const std::optional<PlyNeighbour> before = thread_before(a);
    if (!before) continue;
    if (drape_only && (virtual_.count(a.id.key()) || virtual_.count(before->id.key()))) continue;
    const auto pb = position(before->id);
    if (!pb || pb->placed > 0) continue;
    const std::array<std::uint64_t, 3> key{id.key(), a.id.key(), before->id.key()};
    if (failed_continuations_.count(key)) continue;
    if (accept_virtual(id, solve_plane_sphere(
                               s_, {a.p.point, a.p.at, a.rest, a.p.point - pb->point, true}, st_)))
      return true;
    failed_continuations_.insert(key);
  }
  return false;
}

// A virtual corner where no solve lands on the surface extended past the face (past a
// strongly curved edge the extension folds back and the cloth's next node has no place on
// it; near a tapering tip it runs away): the thread's last segment repeated, in (u, v) as
// the drape's own first guess (eq. 10) and in 3D. Such a corner is no point of the surface:
// it only tells where the cell's edges leave the face (in (u, v)), and each crossing is then
// placed along its edge at its chord's length from the end on the face (crossings()).
bool OutlineBuilder::virtual_by_extrapolation(const NodeId& id) {
  for (const Nb& a : virtual_neighbours(id, false)) {
    const std::optional<PlyNeighbour> before = thread_before(a);
    if (!before) continue;
    const auto pb = position(before->id);
    const int placed = pb ? std::max(pb->placed, a.p.placed) + 1 : 0;
    if (!pb || placed > kMaxPlacedDepth) continue;
    const double len = (a.p.point - pb->point).norm();
    if (!(len > 0.0)) continue;
    // Where the face's parametrisation slows towards its edge, the repeated step stops short
    // of the edge that the drape's node passed: it is lengthened until it leaves the face.
    const Vec2 step = s_.delta(pb->at, a.p.at) * (a.rest / len);
    for (int m = 1; m <= kMaxPlacedSteps; ++m) {
      const SurfaceLocation at = s_.locate(a.p.at, a.p.at.uv + m * step);
      if (s_.contains(at)) continue;
      virtual_[id.key()] = Position{
          s_.wrap(at), a.p.point + (a.p.point - pb->point) * (a.rest / len), false, placed};
      return true;
    }
  }
  return false;
}

}  // namespace plyfit::detail
