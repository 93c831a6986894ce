// Seams found by the scan: where two fronts of cloth meet at a node and disagree (a conflict:
// a third link off, links that cannot meet, a thread that would stretch), the node is solved
// from the neighbours of one front and its links to the others are cut. The cut links lie
// along the line where the fronts met, as the scan reaches it; after the scan they become a
// seam (a dart along that line, detail::seam_curves) with its two cut lines
// (docs/decisions/darts.md, "Seams in the scan").
#include "drape/scan/scanner.hpp"

#include <algorithm>
#include <bit>

namespace plyfit::detail {

void Scanner::seam_where_fronts_meet(bool on) {
  seams_ = on;
}

// The groups of known neighbours to try (every proper subset), largest first, then those
// whose best pair is better (a weft and a warp neighbour whose cell's fourth corner is
// mapped), then the older cloth (the group's latest resolution order the earliest).
int Scanner::seam_fronts(const DrapeNode& q, const Known known[4], int nk,
                         SeamFront out[16]) const {
  const unsigned full = (1u << nk) - 1u;
  int n = 0;
  for (unsigned m = 1; m < full; ++m) {
    Known sub[4];
    SeamFront f{m, std::popcount(m), 0, 0};
    int ns = 0;
    for (int x = 0; x < nk; ++x)
      if ((m >> x) & 1u) {
        sub[ns++] = known[x];
        f.newest = std::max(f.newest, known[x].n->order);
      }
    int a = 0, b = 1;
    f.pair = ns >= 2 ? best_pair(q, sub, ns, a, b) : -1;
    out[n++] = f;
  }
  std::stable_sort(out, out + n, [](const SeamFront& a, const SeamFront& b) {
    if (a.size != b.size) return a.size > b.size;
    if (a.pair != b.pair) return a.pair > b.pair;
    return a.newest < b.newest;
  });
  return n;
}

// Node qi, whose solve `r` found fronts that disagree: solved again from the first group of its
// known neighbours whose cloth holds it (a solve that neither fails nor finds fronts that
// disagree), its links to the others cut (a seam). False, r and the node's flags as they were,
// when no group holds it.
bool Scanner::solve_across_seam(std::uint32_t qi, SolveResult& r) {
  Known known[4];
  const int nk = known_neighbours(node(qi), known);
  if (nk < 2) return false;
  SeamFront fronts[16];
  const int nf = seam_fronts(node(qi), known, nk, fronts);
  const std::uint8_t flags = node(qi).flags;
  for (int f = 0; f < nf; ++f) {
    Known sub[4];
    int ns = 0;
    for (int x = 0; x < nk; ++x)
      if ((fronts[f].mask >> x) & 1u) sub[ns++] = known[x];
    node(qi).flags &= static_cast<std::uint8_t>(~kSolveFlags);
    SolveResult t = solve_known(qi, sub, ns);
    if (t.fronts_disagree || t.status == SolveStatus::kFailed) continue;
    for (int x = 0; x < nk; ++x)
      if (!((fronts[f].mask >> x) & 1u)) {
        cut_link(qi, known[x].n);
        seam_links_.push_back(DrapeResult::link_key(qi, res_.index_of(*known[x].n)));
      }
    r = t;
    return true;
  }
  node(qi).flags = flags;
  return false;
}

}  // namespace plyfit::detail
