#include <plyfit/kernel/drape.hpp>

#include <plyfit/kernel/cells.hpp>

#include "mapped_cells.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace plyfit {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The base plane must cut the surface at the start: the sine of the angle between the base
// plane and the tangent plane there must exceed this.
constexpr double kMinPlaneCutSin = 1e-3;
// A 3D sweep direction must make at least this sine with the base path in the tangent plane.
constexpr double kMinSweepSin = 1e-6;
// The cloth overlaps itself where a new node lands within kOverlapRel * d (3D) of a mapped
// node at least kOverlapSeparation * d away from it on the ply (2D): a closed plane
// section, or a closed face wrapped all round.
constexpr double kOverlapRel = 0.5;
constexpr double kOverlapSeparation = 2.0;
// A node solved from two neighbours whose link to a further known neighbour is off by more
// than this (relative to d) is not mapped: two fronts met around a hole in the net and
// disagree. Fronts that agree do so to the solver's tolerance.
constexpr double kFrontMismatchRel = 1e-9;
// On an open face, nodes sheared past this (radians: 60 degrees) are tested for overlap.
constexpr double kOverlapCheckShear = 1.0471975511965976;
// How often (resolved nodes) the scan checks for cancellation and reports progress.
constexpr std::uint32_t kCancelEvery = 4096;
constexpr std::uint32_t kProgressEvery = 65536;
// Node-count estimate (expected_nodes): samples per cell width across the face, the grid's
// bounds per direction, a relative margin, boundary-ring nodes per sqrt(nodes), and a floor.
constexpr double kEstimateSamplesPerCell = 0.3;
constexpr int kEstimateGridMin = 8;
constexpr int kEstimateGridMax = 64;
constexpr double kEstimateMargin = 1.05;
constexpr double kEstimateRing = 8.0;
constexpr double kEstimateMinNodes = 64.0;
// A regular node farther than this many cell diagonals from the base path line has plain
// regular neighbours (no link split by the path); the extrapolated guess's stencil spans
// kStencilCells cell diagonals.
constexpr double kFarFromPathCells = 2.0;
constexpr double kStencilCells = 6.0;
// GuessRule::kExtrapolated: the two threads' cubic continuations are used when they agree to
// this fraction of the cell's step (scaled (u, v) lengths); else the twist-corrected
// parallelogram.
constexpr double kExtrapolationAgreement = 1e-4;
// ... and an extrapolated guess is used only within this fraction of the cell's step from the
// parallelogram a + b - c (smooth regions: O(d^2) relative; near a pole (u, v) is not smooth).
constexpr double kExtrapolationTrust = 0.1;

std::uint64_t mix(std::uint64_t k) {  // splitmix64 finaliser
  k ^= k >> 30;
  k *= 0xbf58476d1ce4e5b9ULL;
  k ^= k >> 27;
  k *= 0x94d049bb133111ebULL;
  return k ^ (k >> 31);
}

}  // namespace

const char* to_string(GuessRule g) {
  switch (g) {
    case GuessRule::kPaper:
      return "paper";
    case GuessRule::kParallelogram:
      return "parallelogram";
    case GuessRule::kExtrapolated:
      return "extrapolated";
  }
  return "paper";
}

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
    case NodeStatus::kOverlap:
      return "overlap";
    case NodeStatus::kPending:
      return "pending";
  }
  return "failed";
}

// ---------------------------------------------------------------------------------------
// NodeIndex

std::int64_t NodeIndex::probe(const std::vector<Slot>& slots, std::uint64_t key) {
  if (slots.empty()) return -1;
  const std::size_t mask = slots.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots[h].key == key) return slots[h].value;
    if (slots[h].key == kEmpty) return -1;
  }
}

void NodeIndex::put(std::vector<Slot>& slots, std::size_t& count, std::uint64_t key,
                    std::uint32_t value) {
  if ((count + 1) * 2 > slots.size()) {
    std::vector<Slot> old = std::move(slots);
    slots.assign(old.empty() ? 16 : old.size() * 2, Slot{kEmpty, 0});
    count = 0;
    for (const Slot& s : old)
      if (s.key != kEmpty) put(slots, count, s.key, s.value);
  }
  const std::size_t mask = slots.size() - 1;
  for (std::size_t h = mix(key) & mask;; h = (h + 1) & mask) {
    if (slots[h].key == kEmpty) {
      slots[h] = {key, value};
      ++count;
      return;
    }
  }
}

namespace {
inline std::uint64_t block_key(std::int32_t i, std::int32_t j, int bits) {
  return NodeId::regular(i >> bits, j >> bits).key();  // arithmetic shift: floor division
}
inline std::size_t block_offset(std::int32_t i, std::int32_t j, int bits) {
  const std::int32_t m = (1 << bits) - 1;
  return static_cast<std::size_t>(i & m) << bits | static_cast<std::size_t>(j & m);
}
}  // namespace

std::int64_t NodeIndex::find(const NodeId& id) const {
  if (id.is_path_only()) return probe(path_, id.key());
  const std::uint64_t bk = block_key(id.i, id.j, kBlockBits);
  if (bk != last_key_) {
    last_key_ = bk;
    last_block_ = probe(blocks_, bk);
  }
  if (last_block_ < 0) return -1;
  const std::int32_t v = cells_[static_cast<std::size_t>(last_block_) * kBlock * kBlock +
                                block_offset(id.i, id.j, kBlockBits)];
  return v;
}

void NodeIndex::insert(const NodeId& id, std::uint32_t index) {
  ++size_;
  if (id.is_path_only()) {
    put(path_, path_count_, id.key(), index);
    return;
  }
  const std::uint64_t bk = block_key(id.i, id.j, kBlockBits);
  std::int64_t b = probe(blocks_, bk);
  if (b < 0) {
    b = static_cast<std::int64_t>(block_count_);
    put(blocks_, block_count_, bk, static_cast<std::uint32_t>(b));
    cells_.resize(cells_.size() + kBlock * kBlock, -1);
  }
  last_key_ = bk;
  last_block_ = b;
  cells_[static_cast<std::size_t>(b) * kBlock * kBlock + block_offset(id.i, id.j, kBlockBits)] =
      static_cast<std::int32_t>(index);
}

std::size_t NodeIndex::memory_bytes() const {
  return blocks_.capacity() * sizeof(Slot) + cells_.capacity() * sizeof(std::int32_t) +
         path_.capacity() * sizeof(Slot);
}

// ---------------------------------------------------------------------------------------
// DrapeResult queries

const DrapeNode* DrapeResult::neighbour(const NodeId& id, ThreadDir dir) const {
  const DrapeNode* n = find(id);
  return n ? neighbour(*n, dir) : nullptr;
}

double DrapeResult::rest_length(const DrapeNode& n, ThreadDir dir) const {
  const double spacing = is_weft(dir) ? ply->spec().d_weft : ply->spec().d_warp;
  const DrapeNode* m = neighbour(n, dir);
  if (!m || (!n.id.is_path_only() && !m->id.is_path_only())) return spacing;
  return (m->ply - n.ply).norm();  // a link split by the path: the 2D distance
}

namespace {

// Calls f(a, b, rest, kind) for every link between two mapped nodes: thread links (split at
// the base path) from their regular end, then the base path's own links; see links().
template <class F>
void for_each_link(const DrapeResult& r, F&& f) {
  const auto& nodes = r.nodes;
  for (std::uint32_t k = 0; k < nodes.size(); ++k) {
    const DrapeNode& n = nodes[k];
    if (!n.mapped() || n.id.is_path_only()) continue;
    for (int d = 0; d < 4; ++d) {
      const auto dir = static_cast<ThreadDir>(d);
      const DrapeNode* m = r.neighbour(n, dir);
      if (!m || !m->mapped()) continue;
      // Regular-regular links once (from their -x / -y end); links to path nodes from the
      // regular end, both sides.
      const bool plus = dir == ThreadDir::kPlusX || dir == ThreadDir::kPlusY;
      if (!m->id.is_path_only() && !plus) continue;
      f(k, static_cast<std::uint32_t>(m - nodes.data()), r.rest_length(n, dir),
        is_weft(dir) ? LinkKind::kWeft : LinkKind::kWarp);
    }
  }
  const auto& bp = r.base_path;
  for (std::size_t k = 1; k < bp.size(); ++k) {
    const DrapeNode& a = nodes[bp[k - 1]];
    const DrapeNode& b = nodes[bp[k]];
    // A path along a thread between two crossings is that thread's link, listed already.
    if (!a.id.is_path_only() && !b.id.is_path_only() &&
        std::abs(a.id.i - b.id.i) + std::abs(a.id.j - b.id.j) == 1)
      continue;
    f(bp[k - 1], bp[k], (b.ply - a.ply).norm(), LinkKind::kBase);
  }
}

}  // namespace

std::vector<DrapeLink> DrapeResult::links() const {
  std::vector<DrapeLink> out;
  for_each_link(*this, [&](std::uint32_t a, std::uint32_t b, double rest, LinkKind kind) {
    out.push_back({a, b, rest, kind});
  });
  return out;
}

std::vector<std::vector<std::uint32_t>> DrapeResult::threads(bool weft) const {
  // A run starts at a mapped node whose backward neighbour is not mapped and follows the
  // forward links while they lead to mapped nodes.
  const ThreadDir fwd = weft ? ThreadDir::kPlusX : ThreadDir::kPlusY;
  const ThreadDir back = opposite(fwd);
  auto on_thread = [&](const DrapeNode& n) {
    if (!n.id.is_path_only()) return true;
    const PathNode* pn = ply->path_node_if(n.id.j);
    return pn && pn->link_from && (pn->link_dir == ThreadDir::kPlusX) == weft;
  };
  std::vector<std::vector<std::uint32_t>> out;
  for (std::uint32_t k = 0; k < nodes.size(); ++k) {
    const DrapeNode& n = nodes[k];
    if (!n.mapped() || !on_thread(n)) continue;
    const DrapeNode* b = neighbour(n, back);
    if (b && b->mapped()) continue;  // not the start of a run
    std::vector<std::uint32_t> run{k};
    for (const DrapeNode* m = neighbour(n, fwd); m && m->mapped(); m = neighbour(*m, fwd))
      run.push_back(static_cast<std::uint32_t>(m - nodes.data()));
    if (run.size() >= 2) out.push_back(std::move(run));
  }
  // Deterministic order: by thread line, then position along it.
  auto line = [&](const DrapeNode& n) { return weft ? n.ply.y() : n.ply.x(); };
  auto along = [&](const DrapeNode& n) { return weft ? n.ply.x() : n.ply.y(); };
  std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
    const DrapeNode &x = nodes[a[0]], &y = nodes[b[0]];
    if (line(x) != line(y)) return line(x) < line(y);
    return along(x) < along(y);
  });
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
  std::uint32_t node;
};
struct FrontierLater {
  bool operator()(const FrontierEntry& a, const FrontierEntry& b) const {
    if (a.sweep != b.sweep) return a.sweep > b.sweep;
    if (a.dist != b.dist) return a.dist > b.dist;
    if (a.i != b.i) return a.i > b.i;
    return a.j > b.j;
  }
};

// Spatial hash of mapped nodes for the overlap test "is there a recorded node within
// `radius` (3D)?": cells of edge 2 radius, so that the test's ball meets at most 2 x 2 x 2
// cells; open addressing on the cell (collisions of the 64-bit cell hash only merge cells,
// which adds candidates), the nodes of a cell chained in one vector (no allocation per node
// beyond the vectors' growth).
class OverlapGrid {
 public:
  void init(double radius, std::size_t expected) {
    inv_cell_ = 1.0 / (2.0 * radius);
    entries_.reserve(expected);
    std::size_t n = 16;
    while (n < 2 * expected) n *= 2;
    slots_.assign(n, Slot{0, kNone});
  }
  // Calls f(node) for every recorded node in the cells the ball of the test about p meets,
  // until f returns true; true if it did.
  template <class F>
  bool any_near(const Vec3& p, F&& f) const {
    std::int64_t c[3][2];
    for (int a = 0; a < 3; ++a) {
      const double x = p[a] * inv_cell_, fl = std::floor(x);
      c[a][0] = static_cast<std::int64_t>(fl);
      c[a][1] = c[a][0] + (x - fl < 0.5 ? -1 : 1);
    }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
          for (std::uint32_t e = head(key(c[0][i], c[1][j], c[2][k])); e != kNone;
               e = entries_[e].next)
            if (f(entries_[e].node)) return true;
    return false;
  }
  void insert(const Vec3& p, std::uint32_t node) {
    const std::uint64_t k = key(static_cast<std::int64_t>(std::floor(p.x() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.y() * inv_cell_)),
                                static_cast<std::int64_t>(std::floor(p.z() * inv_cell_)));
    if (2 * (count_ + 1) > slots_.size()) grow();
    Slot& s = find(k);
    if (s.head == kNone) {
      s.key = k;
      ++count_;
    }
    entries_.push_back({node, s.head});
    s.head = static_cast<std::uint32_t>(entries_.size() - 1);
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Slot {
    std::uint64_t key;
    std::uint32_t head;  // first entry of the cell, kNone for an empty slot
  };
  struct Entry {
    std::uint32_t node, next;
  };
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return mix(static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
               static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
               static_cast<std::uint64_t>(z));
  }
  Slot& find(std::uint64_t k) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = mix(k) & mask;; h = (h + 1) & mask)
      if (slots_[h].head == kNone || slots_[h].key == k) return slots_[h];
  }
  std::uint32_t head(std::uint64_t k) const {
    if (slots_.empty()) return kNone;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = mix(k) & mask;; h = (h + 1) & mask) {
      if (slots_[h].head == kNone) return kNone;
      if (slots_[h].key == k) return slots_[h].head;
    }
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<std::size_t>(16, 2 * old.size()), Slot{0, kNone});
    for (const Slot& o : old)
      if (o.head != kNone) find(o.key) = o;
  }
  double inv_cell_ = 1.0;
  std::vector<Slot> slots_;
  std::size_t count_ = 0;
  std::vector<Entry> entries_;
};

class Scanner {
 public:
  Scanner(const DrapeSurface& s, Ply& ply, const DrapeOptions& opt, DrapeResult& res)
      : s_(s), ply_(ply), opt_(opt), res_(res) {
    st_.spacing = ply.d();
    st_.tol = opt.tol;
    res_.gamma_min_limit = std::max(0.0, kPi / 2 - opt.lock_angle);
    st_.gamma_min = std::max(res_.gamma_min_limit, opt.tol.fold_angle);
    far_ = kFarFromPathCells * std::hypot(ply.spec().d_weft, ply.spec().d_warp);
    const auto& d = s.domain();
    closed_ = s.wrap(Vec2(d.u1 + 0.5 * d.width_u(), d.v0)).x() <= d.u1 ||
              s.wrap(Vec2(d.u0, d.v1 + 0.5 * d.width_v())).y() <= d.v1;
    cell_ = kOverlapRel * ply.d();
    // Open faces record only the base path and steep nodes; closed ones every mapped node.
    grid_.init(cell_, closed_ ? res_.nodes.capacity() : 64);
  }

  void run(const Vec3& t3) {
    map_path(t3);
    scan();
  }
  bool truncated() const { return truncated_; }
  bool cancelled() const { return cancelled_; }
  std::uint64_t path_off_ply() const { return path_off_ply_; }

 private:
  DrapeNode& node(std::uint32_t k) { return res_.nodes[k]; }

  // The id across the thread link from `id` in direction d, if that node can exist.
  std::optional<NodeId> neighbour_id(const NodeId& id, ThreadDir d) const {
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
  bool far_from_path(const Vec2& p) const {
    return std::abs(cross2(ply_.base_dir(), p - ply_.spec().start)) > far_;
  }

  // Node for id, created (pending) at ply position `pos` if absent, linked both ways to the
  // existing nodes across its thread links.
  std::uint32_t node_for(const NodeId& id, const Vec2& pos) {
    const auto k = res_.index.find(id);
    if (k >= 0) return static_cast<std::uint32_t>(k);
    DrapeNode n;
    n.id = id;
    n.ply = pos;
    const auto idx = static_cast<std::uint32_t>(res_.nodes.size());
    for (int d = 0; d < 4; ++d) {
      const auto nid = neighbour_id(id, static_cast<ThreadDir>(d));
      if (!nid) continue;
      const auto m = res_.index.find(*nid);
      if (m < 0) continue;
      n.nb[d] = static_cast<std::int32_t>(m);
      res_.nodes[static_cast<std::size_t>(m)]
          .nb[static_cast<int>(opposite(static_cast<ThreadDir>(d)))] =
          static_cast<std::int32_t>(idx);
    }
    if (res_.nodes.size() == res_.nodes.capacity())  // beyond the estimate: grow by half
      res_.nodes.reserve(res_.nodes.capacity() + res_.nodes.capacity() / 2 + 16);
    res_.nodes.push_back(n);
    res_.index.insert(id, idx);
    return idx;
  }

  void resolve(std::uint32_t idx, const SolveResult& r) {
    DrapeNode& n = node(idx);
    n.order = order_++;
    ++res_.metrics.solves;
    res_.metrics.iterations += static_cast<std::uint64_t>(r.iterations);
    res_.metrics.evaluations += static_cast<std::uint64_t>(r.evaluations);
    switch (r.status) {
      case SolveStatus::kConverged:
        n.status = NodeStatus::kMapped;
        n.point = r.point;
        n.uv = r.uv;
        res_.metrics.solve_residual_max_rel =
            std::max(res_.metrics.solve_residual_max_rel, r.residual / st_.spacing);
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

  // True if node k (just mapped) lies on cloth already laid: a recorded node within
  // kOverlapRel * d in 3D but at least kOverlapSeparation * d away on the ply; otherwise
  // records it.
  bool overlaps(std::uint32_t k) {
    const DrapeNode& n = node(k);
    const double sep = kOverlapSeparation * ply_.d();
    const bool near = grid_.any_near(n.point, [&](std::uint32_t q) {
      const DrapeNode& m = node(q);
      return (m.point - n.point).norm() < cell_ && (m.ply - n.ply).norm() >= sep;
    });
    if (!near) grid_.insert(n.point, k);
    return near;
  }

  // The mapped node across the thread link from node k in direction d, or nullptr.
  const DrapeNode* mapped_nb(const DrapeNode& n, ThreadDir d) const {
    const std::int32_t k = n.nb[static_cast<int>(d)];
    if (k < 0) return nullptr;
    const DrapeNode& m = res_.nodes[static_cast<std::size_t>(k)];
    return m.mapped() ? &m : nullptr;
  }

  // §5.1: the base path both ways from the start.
  void map_path(const Vec3& t3) {
    const PathNode* p0 = ply_.path_node(0);
    const std::uint32_t i0 = node_for(p0->id, p0->pos);
    DrapeNode& n0 = node(i0);
    n0.status = NodeStatus::kMapped;
    n0.point = res_.start_point;
    n0.uv = res_.start_uv;
    n0.flags |= DrapeNode::kOnPath | DrapeNode::kStart;
    n0.order = order_++;
    overlaps(i0);  // records the start
    std::vector<std::uint32_t> ahead{i0}, behind;
    for (int dirn = 0; dirn < 2; ++dirn) {
      const bool fwd = dirn == 0;
      auto& chain = fwd ? ahead : behind;
      std::uint32_t prev = i0;
      Vec3 travel = fwd ? t3 : Vec3(-t3);
      for (std::int32_t k = fwd ? 1 : -1;; k += fwd ? 1 : -1) {
        const PathNode* pk = ply_.path_node(k);
        if (!pk) {
          if (ply_.spec().rect) ++path_off_ply_;  // the cloth ends here
          break;
        }
        const double rest = std::abs(pk->tau - ply_.path_node_if(fwd ? k - 1 : k + 1)->tau);
        const PathNode pcopy = *pk;  // path_node() may reallocate; keep a copy
        if (res_.nodes.size() >= opt_.max_nodes) {
          truncated_ = true;
          break;
        }
        const std::uint32_t idx = node_for(pcopy.id, pcopy.pos);
        node(idx).flags |= DrapeNode::kOnPath;
        const DrapeNode& from = node(prev);
        const SolveResult r =
            solve_base_path(s_, {from.point, from.uv, res_.base_normal, travel, rest}, st_);
        resolve(idx, r);
        if (!node(idx).mapped()) break;
        if (overlaps(idx)) {  // a closed plane section: the path came round
          node(idx).status = NodeStatus::kOverlap;
          break;
        }
        chain.push_back(idx);
        travel = node(idx).point - node(prev).point;
        prev = idx;
        if (cancelled_now()) break;
      }
    }
    std::reverse(behind.begin(), behind.end());
    res_.base_path = behind;
    res_.base_path.insert(res_.base_path.end(), ahead.begin(), ahead.end());
    for (std::uint32_t k = 0; k < res_.base_path.size(); ++k) path_pos_[res_.base_path[k]] = k;
    for (std::uint32_t k : res_.base_path) push_neighbours(k);
  }

  bool cancelled_now() {
    if (opt_.cancel && opt_.cancel->load(std::memory_order_relaxed)) cancelled_ = true;
    return cancelled_;
  }

  // Adds the unknown regular neighbours of a mapped node to the frontier.
  void push_neighbours(std::uint32_t idx) {
    for (int d = 0; d < 4; ++d) {
      if (node(idx).nb[d] >= 0) continue;  // already reached (pending or resolved)
      const auto q = neighbour_id(node(idx).id, static_cast<ThreadDir>(d));
      if (!q || q->is_path_only()) continue;  // path nodes are mapped by the base path
      const Vec2 qp = ply_.pos(q->i, q->j);
      const int side = ply_.side(qp);
      if (side == 0) continue;                      // on the path: mapped (or not) by the base path
      if (ply_.sweep_for_side(side) < 0) continue;  // that half-plane is not swept
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
    const DrapeNode* ap = mapped_nb(a, da);  // a's predecessor on q's thread
    const DrapeNode* bp = mapped_nb(b, db);
    const DrapeNode* c = nullptr;  // the cell's fourth corner
    if (!a.id.is_path_only() && !b.id.is_path_only()) {
      c = mapped_nb(a, db);
      if (c && c->id != NodeId::regular(a.id.i + b.id.i - q.id.i, a.id.j + b.id.j - q.id.j))
        c = nullptr;
    }
    auto paper = [&] {
      step.guess = two_sphere_guess(s_, a.uv, ap->uv, a.point, ap->point, ra, b.uv, bp->uv, b.point,
                                    bp->point, rb);
    };
    auto parallelogram = [&] { step.guess = a.uv + s_.delta(c->uv, b.uv); };
    const bool extrapolated = opt_.guess == GuessRule::kExtrapolated && c &&
                              extrapolated_guess(q, a, da, b, db, *c, step);
    if (extrapolated) {
      // step.guess is set
    } else if (opt_.guess != GuessRule::kParallelogram) {
      if (ap && bp)
        paper();
      else if (c)
        parallelogram();
    } else {
      if (c)
        parallelogram();
      else if (ap && bp)
        paper();
    }
    SolverSettings st = st_;
    if (is_weft(da) == is_weft(db)) st.gamma_min = 0.0;  // same thread: no thread angle
    SolveResult r = solve_two_spheres(s_, step, st);
    // The cell (a, c, b, q) must not fold: q lies across the line a-b from the fourth corner
    // c, about the normal. The solver kept the ply's orientation of (a, b, q); if c lies on
    // that side too, the net around c is already sheared past flat, and no unfolded cell
    // exists: the cloth stops there as at the shear limit.
    // (Sides compared by the parts of q - a and c - a across the line: a cell is not bent
    // by 90 degrees, and no surface evaluation is needed.)
    if (c && (r.status == SolveStatus::kConverged || r.status == SolveStatus::kShearLimit) &&
        r.point.allFinite()) {
      const Vec3 e = (b.point - a.point).normalized();
      Vec3 u = r.point - a.point, w = c->point - a.point;
      u -= u.dot(e) * e;
      w -= w.dot(e) * e;
      if (u.dot(w) >= 0.0) {
        r.status = SolveStatus::kShearLimit;
        r.reason = "the cell would fold (the cloth is sheared flat)";
      }
    }
    return r;
  }

  // GuessRule::kExtrapolated for the node across the cell (a, c, b) from c, a and b its weft
  // and warp neighbours (directions da, db from the node): both threads continued through
  // their last four nodes, cubic in (u, v) (equal steps: regular nodes only), if the two
  // continuations agree to kExtrapolationAgreement of the cell's step; else the parallelogram
  // a + b - c plus the mean twist of the two neighbouring cells. Only nodes on q's side of the
  // base path are used. False if neither applies, or if the guess is not trusted (outside the
  // parameter domain, or far from the parallelogram).
  bool extrapolated_guess(const DrapeNode& q, const DrapeNode& a, ThreadDir da, const DrapeNode& b,
                          ThreadDir db, const DrapeNode& c, TwoSphereStep& step) const {
    if (is_weft(da) == is_weft(db)) return false;
    // Only nodes swept from the same side of the base path as q: across the path (and at
    // the path's own nodes, mapped by another solver) the net is not smooth.
    const int side = ply_.side(q.ply);
    // The stencil reaches 4 cells from q: far from the path it is all on q's side.
    const bool far = std::abs(cross2(ply_.base_dir(), q.ply - ply_.spec().start)) >
                     kStencilCells * far_ / kFarFromPathCells;
    auto same_side = [&](const DrapeNode& n) { return far || ply_.side(n.ply) == side; };
    if (!same_side(a) || !same_side(b) || !same_side(c)) return false;
    auto regular = [&](const DrapeNode* n, ThreadDir d) -> const DrapeNode* {
      const DrapeNode* m = n ? mapped_nb(*n, d) : nullptr;
      return (m && !m->id.is_path_only() && same_side(*m)) ? m : nullptr;
    };
    const DrapeNode* a1 = regular(&a, da);
    const DrapeNode* b1 = regular(&b, db);
    if (!a1 || !b1) return false;
    const Vec2 sp = s_.speeds();
    auto scaled = [&](const Vec2& duv) { return duv.cwiseProduct(sp).norm(); };
    // A guess is trusted only near the parallelogram a + b - c (within kExtrapolationTrust of
    // the cell's step): where (u, v) is far from linear (near a pole) extrapolation is not.
    const Vec2 para = a.uv + s_.delta(c.uv, b.uv);
    const double cell = scaled(s_.delta(c.uv, a.uv));
    auto trusted = [&](const Vec2& g) {
      return scaled(s_.delta(para, g)) < kExtrapolationTrust * cell && in_domain(g);
    };
    const DrapeNode* a2 = regular(a1, da);
    const DrapeNode* b2 = regular(b1, db);
    const DrapeNode* a3 = regular(a2, da);
    const DrapeNode* b3 = regular(b2, db);
    if (a3 && b3) {
      const Vec2 ca = a.uv + 3.0 * (s_.delta(a1->uv, a.uv) - s_.delta(a2->uv, a1->uv)) +
                      s_.delta(a3->uv, a2->uv);
      const Vec2 cb = b.uv + 3.0 * (s_.delta(b1->uv, b.uv) - s_.delta(b2->uv, b1->uv)) +
                      s_.delta(b3->uv, b2->uv);
      const Vec2 gap = s_.delta(ca, cb);
      const Vec2 g = ca + 0.5 * gap;
      if (scaled(gap) < kExtrapolationAgreement * cell && trusted(g)) {
        step.guess = g;
        return true;
      }
    }
    const DrapeNode* c1 = regular(a1, db);  // the cells next to (a, c, b): (a1, c1) and (b1, c1b)
    const DrapeNode* c1b = regular(b1, da);
    if (!c1 || !c1b) return false;
    const Vec2 ca = s_.delta(c.uv, a.uv), cb = s_.delta(c.uv, b.uv);
    const Vec2 g =
        a.uv + cb + 0.5 * (ca - s_.delta(c1->uv, a1->uv)) + 0.5 * (cb - s_.delta(c1b->uv, b1->uv));
    if (!trusted(g)) return false;
    step.guess = g;
    return true;
  }

  // True when uv (wrapped across closed seams) lies in the surface's parameter domain. An
  // extrapolated guess past the domain edge (e.g. past a pole, where (u, v) is far from
  // linear) is left to the paper's rule.
  bool in_domain(const Vec2& uv) const {
    const Vec2 w = s_.wrap(uv);
    return s_.domain().contains(w.x(), w.y());
  }

  // Solver 3 for q from its one known neighbour a (direction da from q, rest ra).
  SolveResult solve_one(const DrapeNode& q, const DrapeNode& a, ThreadDir da, double ra) {
    const Vec3 na = s_.normal(a.uv).n;
    const Vec2 q2 = q.ply - a.ply;
    Vec3 ref3;
    Vec2 ref2;
    const DrapeNode* ap = mapped_nb(a, da);  // a's predecessor on q's thread
    if (a.has(DrapeNode::kOnPath)) {
      // Next to the base path: the 2D angle between the path and the thread is kept on the
      // tangent plane (§6.1, Fig. 9); the path tangent is that of the plane section.
      ref3 = na.cross(res_.base_normal);
      if (ref3.dot(path_chord(a)) < 0) ref3 = -ref3;
      ref2 = ply_.base_dir();
    } else if (ap) {
      // Elsewhere: continue the thread along its previous segment.
      ref3 = a.point - ap->point;
      ref2 = a.ply - ap->ply;
    } else {
      // Fall back on any mapped neighbour of a, keeping the 2D angle to it.
      const DrapeNode* r = nullptr;
      for (int d = 0; d < 4 && !r; ++d) r = mapped_nb(a, static_cast<ThreadDir>(d));
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
    const auto it = path_pos_.find(static_cast<std::uint32_t>(&a - res_.nodes.data()));
    if (it == path_pos_.end()) return res_.base_tangent;
    const auto& bp = res_.base_path;
    const std::uint32_t k = it->second;
    if (k + 1 < bp.size()) return res_.nodes[bp[k + 1]].point - a.point;
    if (k > 0) return a.point - res_.nodes[bp[k - 1]].point;
    return res_.base_tangent;
  }

  // True if a thread through node k (just mapped) turns back on itself there: the link to
  // a mapped neighbour and that neighbour's next link along the same thread make an angle
  // over 90 degrees. A smooth surface turns a thread by about d / R per link (60 degrees
  // at a curvature radius R = d); more is cloth folded onto itself, which two-sphere solves
  // from a net sheared nearly flat can produce without end on a face that never lets it go.
  bool folds_back(std::uint32_t k) const {
    const DrapeNode& q = res_.nodes[k];
    for (int d = 0; d < 4; ++d) {
      const DrapeNode* a = mapped_nb(q, static_cast<ThreadDir>(d));
      const DrapeNode* a2 = a ? mapped_nb(*a, static_cast<ThreadDir>(d)) : nullptr;
      if (a2 && (a->point - q.point).dot(a2->point - a->point) < 0.0) return true;
    }
    return false;
  }

  // True if node k (just mapped) is sheared past kOverlapCheckShear between any of its weft
  // and warp links. On an open face only such nodes are recorded and tested for overlap:
  // a net sheared nearly flat can lie on itself (a ribbon of cells folded flat along the
  // ply's diagonal, revisiting the same stretch of the face without end) while every link
  // and every solve's thread angle passes; a net sheared less cannot, and is not recorded,
  // which keeps the test's cost off ordinary drapes.
  bool steep(std::uint32_t k) const {
    const DrapeNode& q = res_.nodes[k];
    // The angle g between links a and b is below pi/2 - shear or above pi/2 + shear when
    // |cos g| > sin(shear): (a.b)^2 > sin^2(shear) |a|^2 |b|^2, no trigonometry.
    const double s2 = std::sin(kOverlapCheckShear) * std::sin(kOverlapCheckShear);
    for (int dw = 0; dw < 2; ++dw) {
      const DrapeNode* w = mapped_nb(q, static_cast<ThreadDir>(dw));
      if (!w) continue;
      for (int dv = 2; dv < 4; ++dv) {
        const DrapeNode* v = mapped_nb(q, static_cast<ThreadDir>(dv));
        if (!v) continue;
        const Vec3 a = w->point - q.point, b = v->point - q.point;
        const double ab = a.dot(b);
        if (ab * ab > s2 * a.squaredNorm() * b.squaredNorm()) return true;
      }
    }
    return false;
  }

  // True if a neighbour of q stopped at the shear limit. Such a node, reached from one side
  // only, is stopped as well: continuing its thread straight (solver 3) past the locked
  // node would fold the cloth over the cells the lock left open (on the sphere octant,
  // case (c) with a 30 degree lock: mapped nodes sheared to 88 degrees, links off by 0.7 d).
  bool behind_lock(const DrapeNode& q) const {
    for (int d = 0; d < 4; ++d) {
      const std::int32_t k = q.nb[d];
      if (k >= 0 && res_.nodes[static_cast<std::size_t>(k)].status == NodeStatus::kShearLimit)
        return true;
    }
    return false;
  }

  void scan() {
    std::uint32_t popped = 0;
    while (!heap_.empty()) {
      const FrontierEntry e = heap_.top();
      heap_.pop();
      if (++popped % kCancelEvery == 0 && cancelled_now()) break;
      if (opt_.progress && popped % kProgressEvery == 0) opt_.progress(res_.metrics.solves);
      const std::uint32_t qi = e.node;
      const DrapeNode& qn = node(qi);
      // Known neighbours, weft and warp.
      struct Known {
        ThreadDir dir;
        const DrapeNode* n;
      };
      Known known[4];
      int nk = 0;
      for (int d = 0; d < 4; ++d)
        if (const DrapeNode* m = mapped_nb(qn, static_cast<ThreadDir>(d)))
          known[nk++] = {static_cast<ThreadDir>(d), m};
      SolveResult r;
      if (nk >= 2) {
        // Prefer a weft-warp pair whose cell's fourth corner is mapped, then any weft-warp
        // pair, then two neighbours on one thread.
        int best_a = 0, best_b = 1, best_score = -1;
        for (int x = 0; x < nk; ++x) {
          for (int y = x + 1; y < nk; ++y) {
            int score = 0;
            if (is_weft(known[x].dir) != is_weft(known[y].dir)) {
              score = 1;
              const DrapeNode* a = known[x].n;
              const DrapeNode* b = known[y].n;
              if (!a->id.is_path_only() && !b->id.is_path_only()) {
                const DrapeNode* c = mapped_nb(*a, known[y].dir);
                if (c && c->id == NodeId::regular(a->id.i + b->id.i - qn.id.i,
                                                  a->id.j + b->id.j - qn.id.j))
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
        // Weft neighbour first, so that guesses and branches are reproducible.
        Known ka = known[best_a], kb = known[best_b];
        if (!is_weft(ka.dir) && is_weft(kb.dir)) std::swap(ka, kb);
        r = solve_two(qn, *ka.n, ka.dir, res_.rest_length(qn, ka.dir), *kb.n, kb.dir,
                      res_.rest_length(qn, kb.dir));
        // Links to further known neighbours (fronts that met around a hole in the net) are
        // not solved for: a node that breaks one is no point of the cloth.
        for (int x = 0; x < nk && r.status == SolveStatus::kConverged; ++x) {
          if (known[x].n == ka.n || known[x].n == kb.n) continue;
          const double rest = res_.rest_length(qn, known[x].dir);
          const double err = std::abs((r.point - known[x].n->point).norm() - rest);
          if (err > kFrontMismatchRel * ply_.d()) {
            r.status = SolveStatus::kFailed;
            r.reason = "the fronts disagree: a third link is off";
          }
        }
      } else if (nk == 1 && behind_lock(qn)) {
        r.status = SolveStatus::kShearLimit;
        r.reason = "behind the shear limit";
      } else if (nk == 1) {
        r = solve_one(qn, *known[0].n, known[0].dir, res_.rest_length(qn, known[0].dir));
      } else {
        r.reason = "no known neighbour";
      }
      resolve(qi, r);
      // On a closed face the cloth can come round onto itself; on any face, a net sheared
      // nearly flat can lie on itself or fold its threads back (steep(), folds_back()).
      if (node(qi).mapped() && (((closed_ || steep(qi)) && overlaps(qi)) || folds_back(qi)))
        node(qi).status = NodeStatus::kOverlap;
      if (node(qi).mapped()) push_neighbours(qi);
    }
    while (!heap_.empty()) heap_.pop();  // cancelled: pending nodes stay unresolved
  }

  const DrapeSurface& s_;
  Ply& ply_;
  const DrapeOptions& opt_;
  DrapeResult& res_;
  SolverSettings st_;
  std::priority_queue<FrontierEntry, std::vector<FrontierEntry>, FrontierLater> heap_;
  std::unordered_map<std::uint32_t, std::uint32_t> path_pos_;  // node -> position on the path
  double far_ = 0.0;  // distance from the path line beyond which far_from_path() holds
  std::uint32_t order_ = 0;
  std::uint64_t path_off_ply_ = 0;
  bool truncated_ = false, cancelled_ = false;
  bool closed_ = false;  // the face closes on itself across a seam
  double cell_ = 1.0;    // overlap radius
  OverlapGrid grid_;
};

double tri_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}
double tri_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * std::abs(cross2(b - a, c - a));
}

// Thread angles at mapped regular nodes: weft and warp directions by central differences
// where both neighbours along the thread are mapped, one-sided otherwise.
void thread_angles(DrapeResult& res) {
  for (DrapeNode& n : res.nodes) {
    if (!n.mapped() || n.id.is_path_only()) continue;
    auto direction = [&](ThreadDir plus, Vec3& out) {
      const DrapeNode* p = res.neighbour(n, plus);
      const DrapeNode* m = res.neighbour(n, opposite(plus));
      const bool hp = p && p->mapped(), hm = m && m->mapped();
      if (hp && hm)
        out = p->point - m->point;
      else if (hp)
        out = p->point - n.point;
      else if (hm)
        out = n.point - m->point;
      else
        return false;
      return out.norm() > 0.0;
    };
    Vec3 wf, wp;
    if (!direction(ThreadDir::kPlusX, wf) || !direction(ThreadDir::kPlusY, wp)) continue;
    n.thread_angle = std::atan2(wf.cross(wp).norm(), wf.dot(wp));
    n.flags |= DrapeNode::kHasAngle;
  }
}

// 2D and 3D area of the mapped cells (each part as a fan of triangles).
void cell_areas(DrapeResult& res) {
  double a2 = 0.0, a3 = 0.0;
  detail::visit_mapped_cells(res, [&](std::int32_t, std::int32_t, const std::uint32_t* v, int n) {
    const DrapeNode& o = res.nodes[v[0]];
    for (int k = 1; k + 1 < n; ++k) {
      const DrapeNode& b = res.nodes[v[k]];
      const DrapeNode& c = res.nodes[v[k + 1]];
      a2 += tri_area2(o.ply, b.ply, c.ply);
      a3 += tri_area(o.point, b.point, c.point);
    }
  });
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
      case NodeStatus::kOverlap:
        ++m.nodes.overlap;
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
  for_each_link(res, [&](std::uint32_t a, std::uint32_t b, double rest, LinkKind) {
    const double len = (res.nodes[a].point - res.nodes[b].point).norm();
    m.edge_length_max_rel = std::max(m.edge_length_max_rel, std::abs(len - rest) / d);
  });
  for (const DrapeNode& n : res.nodes) {
    if (!n.mapped()) continue;
    const SurfaceEval1 e = s.eval1(n.uv);
    m.surface_distance_max =
        std::max(m.surface_distance_max, e.ok ? (e.p - n.point).norm() : INFINITY);
    if (n.has(DrapeNode::kOnPath))
      m.base_plane_max_rel = std::max(m.base_plane_max_rel,
                                      std::abs(res.base_normal.dot(n.point - res.start_point)) / d);
  }
  if (!std::isfinite(m.surface_distance_max)) m.surface_distance_max = 1e300;
}

// Number of nodes the scan is expected to reach, to size the node vector once (no
// reallocation copies, no doubled capacity): the face area on the swept side(s) of the base
// plane, by the midpoint rule on a grid in (u, v), over the cell area, plus a ring of
// boundary and path nodes; bounded by the ply rectangle and the node cap. The grid has about
// kEstimateSamplesPerCell samples per ply cell across the face, from kEstimateGridMin to
// kEstimateGridMax per direction (a fraction of a percent of the drape's time).
std::size_t expected_nodes(const DrapeSurface& s, const Ply& ply, const Vec3& start,
                           const Vec3& base_normal, const std::vector<Vec3>& sweeps,
                           std::uint64_t cap) {
  const double dw = ply.spec().d_weft, dp = ply.spec().d_warp;
  const int g = std::clamp(static_cast<int>(kEstimateSamplesPerCell * s.size() / std::min(dw, dp)),
                           kEstimateGridMin, kEstimateGridMax);
  bool plus = false, minus = false;
  for (const Vec3& w : sweeps) (base_normal.dot(w) > 0 ? plus : minus) = true;
  const ParamDomain& dom = s.domain();
  const double hu = dom.width_u() / g, hv = dom.width_v() / g;
  double area = 0.0;
  for (int a = 0; a < g; ++a) {
    for (int b = 0; b < g; ++b) {
      const Vec2 uv(dom.u0 + (a + 0.5) * hu, dom.v0 + (b + 0.5) * hv);
      if (!s.contains(uv)) continue;
      const SurfaceEval1 e = s.eval1(uv);
      if (!e.ok) continue;
      const double side = base_normal.dot(e.p - start);
      if (!((side >= 0 && plus) || (side <= 0 && minus))) continue;
      area += e.du.cross(e.dv).norm() * hu * hv;
    }
  }
  double n = area / (dw * dp);
  if (ply.spec().rect)
    n = std::min(n, (ply.spec().rect->x() / dw + 2) * (ply.spec().rect->y() / dp + 2));
  n = kEstimateMargin * n + kEstimateRing * std::sqrt(n) + kEstimateMinNodes;
  return static_cast<std::size_t>(std::min(n, static_cast<double>(cap)));
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
    return Error{
        "the base plane does not cut the face near the start (it is tangent to the "
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
    return Error{
        "the two 3D sweep directions must lie on the two sides of the base path, "
        "as the 2D ones do"};
  res.base_tangent = t3;
  auto mply = std::make_shared<Ply>(std::move(ply).value());  // the scan extends the path
  res.ply = mply;

  res.nodes.reserve(
      expected_nodes(s, *mply, res.start_point, res.base_normal, pb.sweeps, opt.max_nodes));
  Scanner scanner(s, *mply, opt, res);
  scanner.run(t3);
  compute_metrics(s, res);
  res.metrics.nodes.off_ply += scanner.path_off_ply();
  if (scanner.cancelled()) {
    res.partial = true;
    res.warnings.push_back("cancelled");
  }
  if (scanner.truncated()) {
    res.partial = true;
    res.warnings.push_back("stopped at the node cap of " + std::to_string(opt.max_nodes) +
                           " nodes");
  }
  if (res.metrics.nodes.failed > 0) {
    res.partial = true;
    res.warnings.push_back(std::to_string(res.metrics.nodes.failed) +
                           " node(s) where the solver found no solution");
  }
  res.drape_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace plyfit
