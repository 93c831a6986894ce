// A solve taken from the last drape's memo: the two-sphere and plane-sphere solves, their stop
// tests and the choice of neighbours read the node's neighbours and their neighbours (the
// thread's predecessor, the cell's fourth corner), nothing farther except the initial guess.
// A node whose neighbours and their neighbours are the same (bit for bit: points, locations,
// statuses, which links the cloth goes on across) solves the same equations and stops the
// same way; only the guess, from a wider stencil, may differ, which moves the converged point
// within the solver's tolerance. The memo keeps a 64-bit hash of what the solve read.
#include "drape/scan/scanner.hpp"

#include <bit>
#include <cstring>

namespace plyfit::detail {

namespace {

// One word into the hash (a multiply and a fold: cheap, as every node solved hashes some 20
// nodes); finished by Scanner::seen with splitmix64's finaliser.
std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h = (h ^ v) * 0x9e3779b97f4a7c15ull;
  return h ^ (h >> 29);
}

std::uint64_t mix(std::uint64_t h, double v) {
  return mix(h, std::bit_cast<std::uint64_t>(v));
}

std::uint64_t finish(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// What a solve reads of node n: its place on the surface, status and flags.
std::uint64_t mix(std::uint64_t h, const DrapeNode& n) {
  h = mix(h, n.point.x()), h = mix(h, n.point.y()), h = mix(h, n.point.z());
  h = mix(h, n.uv.x()), h = mix(h, n.uv.y());
  return mix(h, (std::uint64_t{n.face} << 16) |
                    (std::uint64_t{static_cast<std::uint8_t>(n.status)} << 8) | n.flags);
}

}  // namespace

void Scanner::memo(const SolveMemo* last, SolveMemo* next) {
  memo_last_ = last;
  memo_next_ = next;
  if (next) {
    next->nodes.reserve(res_.nodes.capacity());
    next->index = res_.index;
  }
}

// The hash of what q's solve reads: q's neighbours (status; whether the cloth goes on from
// them) and, for those it goes on from, their place and the neighbours the cloth goes on to.
std::uint64_t Scanner::seen(const DrapeNode& q) const {
  std::uint64_t h = mix(0, q.id.key());
  for (int d = 0; d < 4; ++d) {
    const std::int32_t k = q.nb[d];
    if (k < 0) {
      h = mix(h, std::uint64_t{1});
      continue;
    }
    const DrapeNode* a = mapped_nb(q, static_cast<ThreadDir>(d));
    h = mix(mix(h, std::uint64_t{a ? 2u : 3u}), res_.nodes[static_cast<std::size_t>(k)]);
    if (!a) continue;
    for (int e = 0; e < 4; ++e) {
      const DrapeNode* b = mapped_nb(*a, static_cast<ThreadDir>(e));
      h = b ? mix(h, *b) : mix(h, std::uint64_t{4});
    }
  }
  return finish(h);
}

// Node qi's solve: the last drape's where it saw the same (SolveMemo), else solved; kept for
// the next drape.
SolveResult Scanner::solve_or_reuse(std::uint32_t qi, const Known known[4], int nk) {
  if (!memo_next_) return solve_known(qi, known, nk);
  DrapeNode& q = node(qi);
  const std::uint64_t h = seen(q);
  if (memo_next_->nodes.size() <= qi) memo_next_->nodes.resize(qi + 1);
  const std::int64_t k = memo_last_ && memo_last_->index ? memo_last_->index->find(q.id) : -1;
  if (k >= 0 && static_cast<std::size_t>(k) < memo_last_->nodes.size()) {
    const SolveMemo::Entry& e = memo_last_->nodes[static_cast<std::size_t>(k)];
    if (e.kept && e.seen == h) {
      q.flags = static_cast<std::uint8_t>((q.flags & ~kSolveFlags) | e.flags);
      if (e.guess != 0) {
        if (guess_kind_.size() <= qi) {
          guess_kind_.resize(res_.nodes.capacity(), GuessKind::kNone);
          guess_error_.resize(res_.nodes.capacity());
        }
        guess_error_[qi] = {e.du, e.dv};
        guess_kind_[qi] = static_cast<GuessKind>(e.guess);
      }
      ++memo_next_->reused;
      memo_next_->nodes[qi] = e;
      SolveResult r = e.r;
      r.iterations = r.evaluations = 0;  // no solver work done
      return r;
    }
  }
  SolveResult r = solve_known(qi, known, nk);
  SolveMemo::Entry& e = memo_next_->nodes[qi];
  e = SolveMemo::Entry{h, r, static_cast<std::uint8_t>(q.flags & kSolveFlags)};
  e.kept = true;
  if (qi < guess_kind_.size() && guess_kind_[qi] != GuessKind::kNone) {
    e.du = guess_error_[qi].du, e.dv = guess_error_[qi].dv;
    e.guess = static_cast<std::uint8_t>(guess_kind_[qi]);
  }
  return r;
}

}  // namespace plyfit::detail
