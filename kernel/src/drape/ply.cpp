#include <plyfit/kernel/ply.hpp>

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {
bool finite2(const Vec2& v) {
  return v.allFinite();
}
}  // namespace

Status check_sweep_direction(const Vec2& base_dir, const Vec2& sweep, std::size_t k,
                             const Tolerances& tol) {
  const auto which = static_cast<std::int64_t>(k + 1);
  if (!finite2(sweep) || !(sweep.norm() > 0.0))
    return Error{ErrorCode::kSweepZero, "sweep2d", {which}};
  const double sn = std::abs(cross2(base_dir.normalized(), sweep.normalized()));
  if (sn >= std::sin(tol.sweep_min_angle)) return ok_status();
  return Error{ErrorCode::kSweepAlongPath,
               "sweep2d",
               {which, std::asin(std::min(sn, 1.0)) * kRadToDeg, tol.sweep_min_angle * kRadToDeg}};
}

// Sets n.id / n.pos / n.link_from for a path point at n.pos: a regular node when it is on a
// crossing (both threads within the merge tolerance, position snapped), a split of the
// warp link it lies on, a split of the weft link, or a free point (the start inside a cell).
static void classify_path_point(const PlySpec& spec, double merge, std::int32_t k, PathNode& n) {
  const double dx = spec.d_weft, dy = spec.d_warp;
  const double fi = n.pos.x() / dx, fj = n.pos.y() / dy;
  const double ri = std::round(fi), rj = std::round(fj);
  const bool on_i = std::abs(fi - ri) * dx <= merge;  // on warp thread x = ri dx
  const bool on_j = std::abs(fj - rj) * dy <= merge;  // on weft thread y = rj dy
  n.link_from.reset();
  if (on_i && on_j) {
    n.id = NodeId::regular(static_cast<std::int32_t>(ri), static_cast<std::int32_t>(rj));
    n.pos = Vec2(ri * dx, rj * dy);
    return;
  }
  n.id = NodeId::path(k);
  if (on_i) {
    n.pos.x() = ri * dx;
    n.link_from =
        NodeId::regular(static_cast<std::int32_t>(ri), static_cast<std::int32_t>(std::floor(fj)));
    n.link_dir = ThreadDir::kPlusY;
  } else if (on_j) {
    n.pos.y() = rj * dy;
    n.link_from =
        NodeId::regular(static_cast<std::int32_t>(std::floor(fi)), static_cast<std::int32_t>(rj));
    n.link_dir = ThreadDir::kPlusX;
  }
}

Result<Ply> Ply::create(PlySpec spec, const Tolerances& tol) {
  if (!(spec.d_weft > 0.0) || !std::isfinite(spec.d_weft))
    return Error{
        ErrorCode::kSpacingNotPositive, "spacing-weft", {std::string("weft"), spec.d_weft}};
  if (!(spec.d_warp > 0.0) || !std::isfinite(spec.d_warp))
    return Error{
        ErrorCode::kSpacingNotPositive, "spacing-warp", {std::string("warp"), spec.d_warp}};
  if (spec.rect && (!(spec.rect->x() > 0.0) || !(spec.rect->y() > 0.0) || !finite2(*spec.rect)))
    return Error{ErrorCode::kPlySizeNotPositive, "ply"};
  if (!finite2(spec.start)) return Error{ErrorCode::kStart2dNotFinite, "start2d"};
  if (!finite2(spec.base_dir) || !(spec.base_dir.norm() > 0.0))
    return Error{ErrorCode::kBaseDirZero, "base2d"};
  if (spec.sweeps.empty()) return Error{ErrorCode::kNoSweep, "sweep2d"};
  if (spec.sweeps.size() > 2) return Error{ErrorCode::kTooManySweeps, "sweep2d"};
  Ply p;
  p.d_ = std::min(spec.d_weft, spec.d_warp);
  p.merge_ = tol.ply_merge_rel * p.d_;
  spec.base_dir.normalize();
  for (size_t k = 0; k < spec.sweeps.size(); ++k) {
    auto& w = spec.sweeps[k];
    if (auto st = check_sweep_direction(spec.base_dir, w, k, tol); !st) return st.error();
    w.normalize();
    const double c = cross2(spec.base_dir, w);
    int& slot = c > 0 ? p.sweep_plus_ : p.sweep_minus_;
    if (slot >= 0) return Error{ErrorCode::kSweepsSameSide, "sweep2d"};
    slot = static_cast<int>(k);
  }
  if (spec.rect) {
    const Vec2& r = *spec.rect;
    if (spec.start.x() < -p.merge_ || spec.start.y() < -p.merge_ ||
        spec.start.x() > r.x() + p.merge_ || spec.start.y() > r.y() + p.merge_)
      return Error{ErrorCode::kStart2dOffPly, "start2d"};
  }
  p.spec_ = std::move(spec);
  // Path node 0: the start, possibly on a crossing or a thread.
  PathNode s;
  s.tau = 0.0;
  s.pos = p.spec_.start;
  classify_path_point(p.spec_, p.merge_, 0, s);
  p.ahead_.push_back(s);
  return p;
}

Vec2 Ply::pos(const NodeId& id) const {
  if (!id.is_path_only()) return pos(id.i, id.j);
  const PathNode* n = path_node_if(id.j);
  return n ? n->pos : Vec2::Zero();
}

int Ply::side(const Vec2& p) const {
  const double c = cross2(spec_.base_dir, p - spec_.start);
  return c > merge_ ? 1 : c < -merge_ ? -1 : 0;
}

double Ply::sweep_distance(const Vec2& p) const {
  const int s = side(p);
  const int k = sweep_for_side(s);
  if (k < 0) return 0.0;
  return cross2(spec_.base_dir, p - spec_.start) / cross2(spec_.base_dir, spec_.sweeps[k]);
}

bool Ply::on_ply(const Vec2& p) const {
  if (!spec_.rect) return true;
  return p.x() >= -merge_ && p.y() >= -merge_ && p.x() <= spec_.rect->x() + merge_ &&
         p.y() <= spec_.rect->y() + merge_;
}

bool Ply::generate_next(bool forward) {
  auto& vec = forward ? ahead_ : behind_;
  bool& done = forward ? ahead_done_ : behind_done_;
  if (done) return false;
  if (static_cast<std::int32_t>(vec.size()) >= kMaxPathNodes) {
    done = true;
    return false;
  }
  const PathNode& last = vec.empty() ? ahead_.front() : vec.back();
  const Vec2 dir = forward ? spec_.base_dir : Vec2(-spec_.base_dir);
  const double sgn = forward ? 1.0 : -1.0;
  // Next crossing with a vertical (warp) thread x = i dx and a horizontal (weft) thread
  // y = j dy, strictly beyond the last node.
  double t_v = INFINITY, t_h = INFINITY;
  const double dx = spec_.d_weft, dy = spec_.d_warp;
  if (std::abs(dir.x()) > 0.0) {
    const double f = last.pos.x() / dx;
    const double nxt =
        dir.x() > 0 ? std::floor(f + merge_ / dx) + 1 : std::ceil(f - merge_ / dx) - 1;
    t_v = (nxt * dx - last.pos.x()) / dir.x();
  }
  if (std::abs(dir.y()) > 0.0) {
    const double f = last.pos.y() / dy;
    const double nxt =
        dir.y() > 0 ? std::floor(f + merge_ / dy) + 1 : std::ceil(f - merge_ / dy) - 1;
    t_h = (nxt * dy - last.pos.y()) / dir.y();
  }
  if (!std::isfinite(t_v) && !std::isfinite(t_h)) {
    done = true;
    return false;
  }
  PathNode n;
  n.tau = last.tau + sgn * std::min(t_v, t_h);
  n.pos = spec_.start + n.tau * spec_.base_dir;
  const std::int32_t k =
      forward ? static_cast<std::int32_t>(vec.size()) : -static_cast<std::int32_t>(vec.size()) - 1;
  classify_path_point(spec_, merge_, k, n);
  if (!on_ply(n.pos)) {
    done = true;
    return false;
  }
  vec.push_back(n);
  return true;
}

const PathNode* Ply::path_node(std::int32_t k) {
  if (k >= 0) {
    while (static_cast<std::int32_t>(ahead_.size()) <= k)
      if (!generate_next(true)) return nullptr;
    return &ahead_[k];
  }
  const std::int32_t b = -k - 1;
  while (static_cast<std::int32_t>(behind_.size()) <= b)
    if (!generate_next(false)) return nullptr;
  return &behind_[b];
}

const PathNode* Ply::path_node_if(std::int32_t k) const {
  if (k >= 0) return k < static_cast<std::int32_t>(ahead_.size()) ? &ahead_[k] : nullptr;
  const std::int32_t b = -k - 1;
  return b < static_cast<std::int32_t>(behind_.size()) ? &behind_[b] : nullptr;
}

std::optional<std::int32_t> Ply::path_index_at_tau(double tau) const {
  if (std::abs(tau) <= merge_) return 0;
  const auto& vec = tau >= 0 ? ahead_ : behind_;
  // ahead_ has increasing tau, behind_ decreasing tau.
  auto it = tau >= 0 ? std::lower_bound(vec.begin(), vec.end(), tau - merge_,
                                        [](const PathNode& n, double t) { return n.tau < t; })
                     : std::lower_bound(vec.begin(), vec.end(), tau + merge_,
                                        [](const PathNode& n, double t) { return n.tau > t; });
  if (it == vec.end() || std::abs(it->tau - tau) > merge_) return std::nullopt;
  const auto idx = static_cast<std::int32_t>(it - vec.begin());
  return tau >= 0 ? idx : -idx - 1;
}

std::optional<std::int32_t> Ply::path_index_of(std::int32_t i, std::int32_t j) const {
  const Vec2 p = pos(i, j);
  if (side(p) != 0) return std::nullopt;
  const auto k = path_index_at_tau((p - spec_.start).dot(spec_.base_dir));
  if (!k) return std::nullopt;
  const PathNode* n = path_node_if(*k);
  if (!n || n->id != NodeId::regular(i, j)) return std::nullopt;
  return k;
}

std::optional<PlyNeighbour> Ply::neighbour(std::int32_t i, std::int32_t j, ThreadDir dir) const {
  const int di = dir == ThreadDir::kPlusX ? 1 : dir == ThreadDir::kMinusX ? -1 : 0;
  const int dj = dir == ThreadDir::kPlusY ? 1 : dir == ThreadDir::kMinusY ? -1 : 0;
  const Vec2 a = pos(i, j), b = pos(i + di, j + dj);
  const double rest = is_weft(dir) ? spec_.d_weft : spec_.d_warp;
  // Does the path cross the link strictly inside? Both ends strictly on opposite sides.
  const int sa = side(a), sb = side(b);
  if (sa != 0 && sb != 0 && sa != sb) {
    const Vec2 e = b - a;
    const double den = cross2(spec_.base_dir, e);
    const double t = cross2(spec_.base_dir, spec_.start - a) / den;  // a + t e on the path
    const Vec2 x = a + t * e;
    const auto k = path_index_at_tau((x - spec_.start).dot(spec_.base_dir));
    if (!k) return std::nullopt;  // the path was not generated that far
    return PlyNeighbour{path_node_if(*k)->id, t * rest};
  }
  return PlyNeighbour{NodeId::regular(i + di, j + dj), rest};
}

std::vector<Ply::ThreadNeighbour> Ply::thread_neighbours(const NodeId& id) const {
  std::vector<ThreadNeighbour> out;
  if (!id.is_path_only()) {
    for (int d = 0; d < 4; ++d) {
      const auto dir = static_cast<ThreadDir>(d);
      if (auto n = neighbour(id.i, id.j, dir)) out.push_back({dir, *n});
    }
    return out;
  }
  const PathNode* pn = path_node_if(id.j);
  if (!pn || !pn->link_from) return out;
  const NodeId a = *pn->link_from;
  const int di = pn->link_dir == ThreadDir::kPlusX ? 1 : 0, dj = 1 - di;
  const NodeId b = NodeId::regular(a.i + di, a.j + dj);
  out.push_back({opposite(pn->link_dir), {a, (pn->pos - pos(a.i, a.j)).norm()}});
  out.push_back({pn->link_dir, {b, (pos(b.i, b.j) - pn->pos).norm()}});
  return out;
}

}  // namespace plyfit
