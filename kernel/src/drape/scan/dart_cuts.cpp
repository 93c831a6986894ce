// The scan beside darts: a node's known neighbours on the two sides of a dart are not solved
// together. The node is solved from the larger group of neighbours that no dart separates;
// its links to the others are cut. Where the cloth of every group lands across the dart from
// it, the node waits (parked) until a neighbour on its own side is mapped; a node no side
// ever holds lies in the cloth the dart cuts out.
#include "drape/scan/scanner.hpp"

#include <algorithm>

namespace plyfit::detail {

namespace {

// The solve gave a point the cloth would go on from (or two fronts disagreeing there): its
// links must not cross a dart. Outside the face the cloth ends anyway.
bool lands(const DrapeSurface& s, const SolveResult& r) {
  if (!r.point.allFinite()) return false;
  return r.status == SolveStatus::kConverged || r.fronts_disagree ||
         (r.status == SolveStatus::kLeftFace && r.extended && s.in_hole(r.at));
}

}  // namespace

bool Scanner::near_dart(const Known known[4], int nk) const {
  for (int x = 0; x < nk; ++x)
    if (darts_->near(known[x].n->point)) return true;
  return false;
}

void Scanner::cut_link(std::uint32_t a, const DrapeNode* b) {
  const std::uint32_t bi = res_.index_of(*b);
  cuts_.insert(DrapeResult::link_key(a, bi));
  const std::size_t last = std::max(a, bi);
  if (cut_ends_.size() <= last) cut_ends_.resize(std::max(res_.nodes.capacity(), last + 1), false);
  cut_ends_[a] = cut_ends_[bi] = true;
}

// Groups the known neighbours (a neighbour joins the first group whose first member it is
// not separated from by a dart), largest group first, and solves qi from the first group
// whose cloth lands on its side of the darts. False: parked.
bool Scanner::solve_beside_darts(std::uint32_t qi, const Known known[4], int nk, SolveResult& r) {
  int group[4] = {-1, -1, -1, -1}, size[4] = {0, 0, 0, 0}, ng = 0;
  for (int x = 0; x < nk; ++x) {
    for (int g = 0; g < ng && group[x] < 0; ++g) {
      const int first = static_cast<int>(std::find(group, group + nk, g) - group);
      if (!darts_->crosses(known[first].n->point, known[x].n->point)) group[x] = g;
    }
    if (group[x] < 0) group[x] = ng++;
    ++size[group[x]];
  }
  int order[4] = {0, 1, 2, 3};
  std::stable_sort(order, order + ng, [&](int a, int b) { return size[a] > size[b]; });
  for (int o = 0; o < ng; ++o) {
    const int g = order[o];
    Known sub[4];
    int ns = 0;
    for (int x = 0; x < nk; ++x)
      if (group[x] == g) sub[ns++] = known[x];
    // A group's solve from a weft and a warp neighbour marks the node (set_solved_from); the
    // group that holds it marks it again.
    node(qi).flags &= static_cast<std::uint8_t>(~kSolveFlags);
    SolveResult t = solve_known(qi, sub, ns);
    bool across = false;
    for (int x = 0; x < ns && lands(s_, t); ++x)
      across = across || darts_->crosses(t.point, sub[x].n->point);
    if (across) {  // this side's cloth does not reach the node
      for (int x = 0; x < ns; ++x) cut_link(qi, sub[x].n);
      continue;
    }
    for (int x = 0; x < nk; ++x)
      if (group[x] != g) cut_link(qi, known[x].n);
    r = t;
    return true;
  }
  parked_.insert(qi);
  return false;
}

// A parked node gets another try when a neighbour of it is mapped.
void Scanner::unpark(std::int32_t k) {
  const auto qi = static_cast<std::uint32_t>(k);
  if (!parked_.erase(qi)) return;
  const DrapeNode& q = node(qi);
  heap_.push({ply_.sweep_distance(q.ply), (q.ply - ply_.spec().start).norm(), q.id.i, q.id.j, qi});
}

// After the scan: nodes still parked hold no cloth (off the ply: the dart cut them out, counted
// per nearest dart), and the cut links go to the result, sorted.
void Scanner::finish_cuts() {
  if (!darts_ && cuts_.empty()) return;
  cut_out_.assign(darts_ ? darts_->curves().size() : 0, 0);
  std::vector<std::uint32_t> parked(parked_.begin(), parked_.end());
  std::sort(parked.begin(), parked.end());
  for (std::uint32_t k : parked) {
    DrapeNode& n = node(k);
    n.status = NodeStatus::kOffPly;
    n.order = order_++;
    const DrapeNode* m = nullptr;
    for (int d = 0; d < 4 && !m; ++d)
      if (n.nb[d] >= 0 && res_.nodes[static_cast<std::size_t>(n.nb[d])].mapped())
        m = &res_.nodes[static_cast<std::size_t>(n.nb[d])];
    const int dart = m && darts_ ? darts_->nearest(m->point) : -1;
    if (dart >= 0) ++cut_out_[static_cast<std::size_t>(dart)];
  }
  parked_.clear();
  res_.cut_links.assign(cuts_.begin(), cuts_.end());
  std::sort(res_.cut_links.begin(), res_.cut_links.end());
  res_.cut_ends.assign(res_.nodes.size(), false);
  for (std::uint64_t key : res_.cut_links)
    res_.cut_ends[key >> 32] = res_.cut_ends[key & 0xffffffffu] = true;
}

}  // namespace plyfit::detail
