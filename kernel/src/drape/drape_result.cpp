// The net and result types of the drape: status names and DrapeResult's
// queries (neighbours, rest lengths, links, threads).
#include "drape/drape.hpp"

#include "drape/metrics.hpp"
#include "drape/net_links.hpp"
#include "drape/scan/node_index.hpp"

#include <algorithm>
#include <cstdlib>

namespace plyfit {

const char* to_string(SeedCurve c) {
  if (c == SeedCurve::kCurve) return "curve";
  return c == SeedCurve::kGeodesic ? "geodesic" : "plane";
}

namespace {

constexpr detail::Named<GuessRule> kGuessRules[] = {{GuessRule::kPaper, "paper"},
                                                    {GuessRule::kParallelogram, "parallelogram"},
                                                    {GuessRule::kExtrapolated, "extrapolated"}};
static_assert(detail::lists_enum(kGuessRules, GuessRule::kExtrapolated));

}  // namespace

const char* to_string(GuessRule g) {
  return detail::name_in(kGuessRules, g, "paper");
}

const char* to_string(NodeStatus s) {
  return detail::name_in(detail::kNodeStatuses, s, "failed");
}

// ---------------------------------------------------------------------------------------
// DrapeResult queries

const DrapeNode* DrapeResult::find(const NodeId& id) const {
  const auto k = index ? index->find(id) : -1;
  return k < 0 ? nullptr : &nodes[static_cast<std::size_t>(k)];
}

const DrapeNode* DrapeResult::neighbour(const NodeId& id, ThreadDir dir) const {
  const DrapeNode* n = find(id);
  return n ? neighbour(*n, dir) : nullptr;
}

bool DrapeResult::cut(std::uint32_t a, std::uint32_t b) const {
  return std::binary_search(cut_links.begin(), cut_links.end(), link_key(a, b));
}

double DrapeResult::rest_length(const DrapeNode& n, ThreadDir dir) const {
  const double spacing = is_weft(dir) ? ply->spec().d_weft : ply->spec().d_warp;
  const DrapeNode* m = neighbour(n, dir);
  if (!m || (!n.id.is_path_only() && !m->id.is_path_only())) return spacing;
  return (m->ply - n.ply).norm();  // a link split by the path: the 2D distance
}

std::vector<DrapeLink> DrapeResult::links() const {
  std::vector<DrapeLink> out;
  detail::for_each_link(*this, [&](std::uint32_t a, std::uint32_t b, double rest, LinkKind kind) {
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
    const DrapeNode* b = linked(n, back);
    if (b && b->mapped()) continue;  // not the start of a run
    std::vector<std::uint32_t> run{k};
    for (const DrapeNode* m = linked(n, fwd); m && m->mapped(); m = linked(*m, fwd))
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
  return static_cast<double>(nodes.capacity() * sizeof(DrapeNode) +
                             (index ? index->memory_bytes() : 0)) /
         static_cast<double>(nodes.size());
}

}  // namespace plyfit
