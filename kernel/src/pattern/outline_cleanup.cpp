#include "pattern/outline_cleanup.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace plyfit {

namespace {

// Bisection steps that place a chord's end where the width reaches w along an edge: the
// bracket shrinks to 2^-60 of the edge, far below rounding of the coordinates.
constexpr int kWidthBisections = 60;
// Cuts made in one loop at most: its initial vertex count plus this (each cut removes at
// least one vertex of a tip and adds at most two; the cap only bounds a pathological case).
constexpr int kExtraCuts = 16;

// A test that passes over what lies beyond a distance (nearest_on, chord_clear) or takes a
// sample's hull as wider than w (hull_narrower) does so only beyond it by this much of it (or
// of the coordinates): far above rounding, far below any width.
constexpr double kBoundMargin = 1e-9;
// Points of a long loop sampled first for the width test (hull_narrower): one in this many.
constexpr std::size_t kHullSampleStride = 16;

using Index = std::ptrdiff_t;

struct Loop {
  std::vector<Vec2> p;
  std::vector<Vec3> p3;  // empty, or one per point
  bool hole = false;
  Index n() const { return static_cast<Index>(p.size()); }
  // (Without a division for the indices already in range: most of them, in hot loops.)
  Index wrap(Index k) const { return k >= 0 && k < n() ? k : ((k % n()) + n()) % n(); }
  const Vec2& at(Index k) const { return p[static_cast<std::size_t>(wrap(k))]; }
  Vec3 at3(Index k) const {
    return p3.empty() ? Vec3::Zero() : p3[static_cast<std::size_t>(wrap(k))];
  }
};

// Signed turn at vertex k (degrees, + left, 0 straight on, +-180 back).
double turn_deg(const Loop& l, Index k) {
  const Vec2 in = l.at(k) - l.at(k - 1), o = l.at(k + 1) - l.at(k);
  return std::atan2(cross2(in, o), in.dot(o)) * 180.0 / kPi;
}

// The tip starting at vertex k: the last vertex q of a run k..q shorter than w in all that
// turns back by more than kSliverTurnDeg (as the outline checks find a spike), or none.
std::optional<Index> tip_at(const Loop& l, Index k, double w) {
  const Index n = l.n();
  double sum = turn_deg(l, k), len = 0.0;
  if (std::abs(sum) > kSliverTurnDeg) return k;
  for (Index j = 1; j < n - 1; ++j) {
    len += (l.at(k + j) - l.at(k + j - 1)).norm();
    if (len >= w) break;
    sum += turn_deg(l, k + j);
    if (std::abs(sum) > kSliverTurnDeg) return k + j;
  }
  return std::nullopt;
}

// A polyline through loop vertices first, first + step, ... (count vertices), step +-1.
struct Arc {
  const Loop* l;
  Index first, step, count;
  Vec2 vertex(Index i) const { return l->at(first + step * i); }
  Index edges() const { return count - 1; }
};

// A point on an arc: edge e (from vertex e to e + 1 of the arc) at parameter t in [0, 1].
struct ArcPoint {
  Index e = 0;
  double t = 0.0;
  Vec2 pt = Vec2::Zero();
  double dist = 0.0;
  bool operator<=(const ArcPoint& o) const { return e < o.e || (e == o.e && t <= o.t); }
};

// The nearest point to x of edge i of `a`.
ArcPoint nearest_on_edge(const Arc& a, Index i, const Vec2& x) {
  const Vec2 s = a.vertex(i), e = a.vertex(i + 1) - s;
  const double ee = e.squaredNorm();
  const double t = ee > 0.0 ? std::clamp((x - s).dot(e) / ee, 0.0, 1.0) : 0.0;
  const Vec2 q = s + t * e;
  return {i, t, q, (q - x).norm()};
}

// Whether the boxes of the segments a0-a1 and b0-b1 lie farther apart than `gap` along an axis
// (then every point of one lies farther than `gap` from every point of the other).
bool boxes_apart(const Vec2& a0, const Vec2& a1, const Vec2& b0, const Vec2& b1, double gap) {
  return (a0.cwiseMin(a1) - b0.cwiseMax(b1)).maxCoeff() > gap ||
         (b0.cwiseMin(b1) - a0.cwiseMax(a1)).maxCoeff() > gap;
}

// The nearest point of `a` to x (the first of the nearest in the arc's order). Given `bound`,
// the distance to a point of `a` already known, the edges whose box lies beyond it (by
// kBoundMargin, far above rounding) are passed over: none of them can be the nearest.
ArcPoint nearest_on(const Arc& a, const Vec2& x, double bound = INFINITY) {
  const double reach = bound * (1.0 + kBoundMargin);
  ArcPoint best;
  best.dist = INFINITY;
  for (Index i = 0; i < a.edges(); ++i) {
    if (reach < INFINITY && boxes_apart(a.vertex(i), a.vertex(i + 1), x, x, reach)) continue;
    if (const ArcPoint p = nearest_on_edge(a, i, x); p.dist < best.dist) best = p;
  }
  return best;
}

// Whether edge i of `a` passes closer than w to x.
bool edge_within(const Arc& a, Index i, const Vec2& x, double w) {
  return nearest_on_edge(a, i, x).dist < w;
}

// Whether some edge of `a` passes closer than w to x (nearest_on(a, x).dist < w, the same
// distances, stopping at the first such edge).
bool within(const Arc& a, const Vec2& x, double w) {
  for (Index i = 0; i < a.edges(); ++i)
    if (edge_within(a, i, x, w)) return true;
  return false;
}

// The edges of `a` that may pass closer than w to a point of the segment p..q: all but those
// whose box lies farther than 2 w from the segment's along an axis (farther than w from
// every point of it, rounding of the points on it included).
std::vector<Index> edges_near(const Arc& a, const Vec2& p, const Vec2& q, double w) {
  std::vector<Index> near;
  for (Index i = 0; i < a.edges(); ++i)
    if (!boxes_apart(a.vertex(i), a.vertex(i + 1), p, q, 2.0 * w)) near.push_back(i);
  return near;
}

// Walks `a` from its vertex `start` while its points stay closer than w to `other`; the
// first point where the distance reaches w (found by bisection on the edge, on the side
// where it is at least w), or none when the arc ends first.
std::optional<ArcPoint> mouth(const Arc& a, Index start, const Arc& other, double w) {
  for (Index i = start; i < a.edges(); ++i) {
    const Vec2 s = a.vertex(i), e = a.vertex(i + 1) - s;
    if (within(other, a.vertex(i + 1), w)) continue;
    // The bisection's points all lie on this edge: only the edges of `other` near it can
    // be closer than w to them (the same answers as within(), without the whole arc).
    const std::vector<Index> near = edges_near(other, s, a.vertex(i + 1), w);
    const auto near_within = [&](const Vec2& x) {
      return std::any_of(near.begin(), near.end(),
                         [&](Index j) { return edge_within(other, j, x, w); });
    };
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < kWidthBisections; ++it) {
      const double mid = 0.5 * (lo + hi);
      (near_within(s + mid * e) ? lo : hi) = mid;
    }
    ArcPoint m;
    m.e = i;
    m.t = hi;
    m.pt = hi == 1.0 ? a.vertex(i + 1) : Vec2(s + hi * e);
    // Within a hair of the bisection's last point inside w: nearer than 2 w, so the
    // nearest edge is one of `near` (the others lie farther than 2 w).
    m.dist = INFINITY;
    for (Index j : near) m.dist = std::min(m.dist, nearest_on_edge(other, j, m.pt).dist);
    if (!(m.dist <= 2.0 * w)) m.dist = nearest_on(other, m.pt).dist;
    return m;
  }
  return std::nullopt;
}

int orient(const Vec2& o, const Vec2& p, const Vec2& q) {
  const double c = cross2(p - o, q - o);
  return c > 0 ? 1 : c < 0 ? -1 : 0;
}

bool on_box(const Vec2& p, const Vec2& a, const Vec2& b) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

// Whether segments ab and cd cross or touch (an end of one on the other, ends shared
// excepted).
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto touches = [](const Vec2& p, const Vec2& s, const Vec2& e) {
    return p != s && p != e && on_box(p, s, e);
  };
  return (o1 == 0 && touches(c, a, b)) || (o2 == 0 && touches(d, a, b)) ||
         (o3 == 0 && touches(a, c, d)) || (o4 == 0 && touches(b, c, d));
}

// A cut of loop `l`: the piece from P (on loop edge ev, from vertex ev to ev + 1) forward
// through vertices ev + 1 .. eu to Q (on loop edge eu) is replaced by the chord Q-P.
struct Cut {
  Index ev = 0, eu = 0;  // loop indices (unwrapped: ev < eu)
  Vec2 P, Q;
  Vec3 P3, Q3;
  double area = 0.0;  // signed area of the piece (P, ev + 1 .. eu, Q): > 0 cloth, < 0 a gap
};

// The loop with the cut made.
Loop apply(const Loop& l, const Cut& c) {
  Loop out;
  out.hole = l.hole;
  auto push = [&](const Vec2& x, const Vec3& x3) {
    if (!out.p.empty() && out.p.back() == x) return;
    out.p.push_back(x);
    if (!l.p3.empty()) out.p3.push_back(x3);
  };
  push(c.Q, c.Q3);
  for (Index k = c.eu + 1; k <= c.ev + l.n(); ++k) push(l.at(k), l.at3(k));
  push(c.P, c.P3);
  if (out.p.size() > 1 && out.p.front() == out.p.back()) {
    out.p.pop_back();
    if (!out.p3.empty()) out.p3.pop_back();
  }
  return out;
}

// Whether the chord of cut c stays clear of every edge of every loop (the piece's edges and
// the two it ends on excepted).
bool chord_clear(const std::vector<Loop>& loops, std::size_t li, const Cut& c) {
  if (c.P == c.Q) return false;
  const double gap = kBoundMargin * (1.0 + c.P.cwiseAbs().maxCoeff() + c.Q.cwiseAbs().maxCoeff());
  for (std::size_t m = 0; m < loops.size(); ++m) {
    const Loop& l = loops[m];
    for (Index k = 0; k < l.n(); ++k) {
      if (m == li) {
        // Edge k in the piece (ev .. eu, unwrapped) is gone or ends on the chord.
        if (c.ev + l.wrap(k - c.ev) <= c.eu) continue;
      }
      // Boxes apart by more than a hair: the segments cannot meet (the orientation tests
      // decide only for the rest).
      const Vec2 a = l.at(k), b = l.at(k + 1);
      if (boxes_apart(c.P, c.Q, a, b, gap)) continue;
      if (segments_meet(c.P, c.Q, a, b)) return false;
    }
  }
  return true;
}

Vec3 lerp3(const Loop& l, Index e, double t) {
  return (1.0 - t) * l.at3(e) + t * l.at3(e + 1);
}

// The best cut of the tip k..q of loop li, or none.
std::optional<Cut> cut_tip(const std::vector<Loop>& loops, std::size_t li, Index k, Index q,
                           double w, bool* whole_loop) {
  const Loop& l = loops[li];
  const Index n = l.n(), m = q - k;  // m: edges in the tip run
  const Index rest = n - m - 1;      // vertices outside the run
  const Index ha = (rest + 1) / 2, hb = rest - ha;
  // The two sides of the tip: A backwards from k, B forwards from q, half the rest each.
  const Arc A{&l, k, -1, 1 + ha}, B{&l, q, 1, 1 + hb};
  const double wc = w * (1.0 + kCutChordMargin);
  const auto ma = mouth(A, 0, B, wc), mb = mouth(B, 0, A, wc);
  if (!ma || !mb) {
    *whole_loop = true;
    return std::nullopt;
  }
  std::vector<Cut> cands;
  // A point on A's edge e at t lies on loop edge (k - e - 1 -> k - e) at 1 - t; on B's edge
  // e at t, on loop edge (q + e -> q + e + 1) at t.
  auto make = [&](const ArcPoint& a, const ArcPoint& b) {
    Cut c;
    c.ev = k - a.e - 1;
    c.P = a.pt;
    c.P3 = lerp3(l, c.ev, 1.0 - a.t);
    c.eu = q + b.e;
    c.Q = b.pt;
    c.Q3 = lerp3(l, c.eu, b.t);
    std::vector<Vec2> piece{c.P};
    for (Index j = c.ev + 1; j <= c.eu; ++j) piece.push_back(l.at(j));
    piece.push_back(c.Q);
    c.area = signed_area(piece);
    return c;
  };
  // From A's mouth across to the nearest point of B, if that lies no farther out than B's
  // own mouth; likewise from B's mouth; else between the two mouths.
  // (Each mouth lies on its side: its distance to the other mouth bounds the search.)
  const double across = (ma->pt - mb->pt).norm();
  if (const ArcPoint b = nearest_on(B, ma->pt, across); b <= *mb) cands.push_back(make(*ma, b));
  if (const ArcPoint a = nearest_on(A, mb->pt, across); a <= *ma) cands.push_back(make(a, *mb));
  if (cands.empty()) cands.push_back(make(*ma, *mb));
  std::optional<Cut> best;
  for (const Cut& c : cands) {
    if (c.eu - c.ev > n - 1) continue;  // no vertex left beside the chord
    if (!chord_clear(loops, li, c)) continue;
    if (!best || std::abs(c.area) < std::abs(best->area)) best = c;
  }
  return best;
}

// Whether the convex hull of p is narrower than w in some direction: all of it within w of
// the line of one of its edges (then the loop is narrower than w everywhere). Each edge's
// farthest point is first looked for by climbing from the last edge's (the rotating
// calipers); only when that point is nearer than w are all points measured, so the answer
// does not depend on how rounding breaks ties between nearly collinear hull points.
bool hull_narrower_all(std::vector<Vec2> p, double w) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return true;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  const std::size_t hn = h.size();
  if (hn < 3) return true;
  std::size_t j = 0;
  for (std::size_t i = 0; i < hn; ++i) {
    const Vec2 a = h[i], e = h[(i + 1) % hn] - a;
    const double len = e.norm();
    auto dist = [&](std::size_t x) { return cross2(e, h[x % hn] - a) / len; };
    for (std::size_t step = 0; step < hn && dist(j + 1) > dist(j); ++step) j = (j + 1) % hn;
    if (dist(j) >= w) continue;
    double far = 0.0;
    for (std::size_t x = 0; x < hn; ++x) far = std::max(far, dist(x));
    if (far < w) return true;
  }
  return false;
}

// hull_narrower, first on every kHullSampleStride-th point when there are many: their hull
// lies inside the loop's, so when even it is wider than w (by kBoundMargin, far above
// rounding) so is the loop's, and the answer (false) is the same without sorting every point
// after every cut of a long outline.
bool hull_narrower(std::vector<Vec2> p, double w) {
  if (p.size() >= 4 * kHullSampleStride) {
    std::vector<Vec2> sample;
    for (std::size_t i = 0; i < p.size(); i += kHullSampleStride) sample.push_back(p[i]);
    if (!hull_narrower_all(std::move(sample), w * (1.0 + kBoundMargin))) return false;
  }
  return hull_narrower_all(std::move(p), w);
}

void finish(const Loop& l, OutlineLoop& out) {
  out.points = l.p;
  out.points3d = l.p3;
  out.hole = l.hole;
  out.area = std::abs(signed_area(l.p));
  out.perimeter = 0.0;
  for (Index k = 0; k < l.n(); ++k) out.perimeter += (l.at(k + 1) - l.at(k)).norm();
}

// The loops as worked on: repeated points (and a last point equal to the first) removed.
std::vector<Loop> working_loops(const std::vector<OutlineLoop>& loops) {
  std::vector<Loop> work;
  for (const OutlineLoop& ol : loops) {
    Loop l;
    l.hole = ol.hole;
    const bool with3d = ol.points3d.size() == ol.points.size();
    for (std::size_t k = 0; k < ol.points.size(); ++k)
      if (l.p.empty() || l.p.back() != ol.points[k]) {
        l.p.push_back(ol.points[k]);
        if (with3d) l.p3.push_back(ol.points3d[k]);
      }
    while (l.p.size() > 1 && l.p.front() == l.p.back()) {
      l.p.pop_back();
      if (with3d) l.p3.pop_back();
    }
    work.push_back(std::move(l));
  }
  return work;
}

// The clean-up of a set of loops at width w.
struct Cleanup {
  std::vector<Loop> work;
  std::vector<bool> dropped;
  double w;
  OutlineCleanupResult res;

  // Drops loop li (its area removed if cloth, added if a gap).
  void drop(std::size_t li) {
    const double a = signed_area(work[li].p);
    (a > 0 ? res.removed_area : res.added_area) += std::abs(a);
    dropped[li] = true;
    ++res.loops_dropped;
    ++res.slivers;
  }

  // Drops loop li if it is narrower than w everywhere; true if so.
  bool drop_if_narrow(std::size_t li) {
    if (work[li].n() < 3 || hull_narrower(work[li].p, w)) {
      drop(li);
      return true;
    }
    return false;
  }

  // Cuts the tips of loop li one after the other (the first found each time), until none
  // is left but those no clean cut was found for, or the loop is dropped.
  void cut_tips(std::size_t li) {
    std::vector<Vec2> left;  // tips no cut was found for (their first vertex)
    const Index cap = work[li].n() + kExtraCuts;
    for (Index cuts = 0; cuts < cap && !dropped[li];) {
      const Loop& l = work[li];
      std::optional<std::pair<Index, Index>> tip;
      for (Index k = 0; k < l.n() && !tip; ++k)
        if (const auto q = tip_at(l, k, w);
            q && std::find(left.begin(), left.end(), l.at(k)) == left.end())
          tip = std::pair{k, *q};
      if (!tip) break;
      bool whole = false;
      const auto c = cut_tip(work, li, tip->first, tip->second, w, &whole);
      if (whole) {
        drop(li);
        break;
      }
      if (!c) {
        left.push_back(l.at(tip->first));
        ++res.tips_left;
        continue;
      }
      (c->area > 0 ? res.removed_area : res.added_area) += std::abs(c->area);
      ++res.slivers;
      ++cuts;
      work[li] = apply(l, *c);
      drop_if_narrow(li);
    }
  }
};

}  // namespace

OutlineCleanupResult outline_cleanup(const std::vector<OutlineLoop>& loops,
                                     const OutlineCleanupOptions& options) {
  const double w = options.min_width;
  if (!(w > 0.0) || !std::isfinite(w)) {
    OutlineCleanupResult res;
    res.loops = loops;
    return res;
  }
  Cleanup c{working_loops(loops), {}, w, {}};
  c.dropped.assign(c.work.size(), false);
  for (std::size_t li = 0; li < c.work.size(); ++li) c.drop_if_narrow(li);
  for (std::size_t li = 0; li < c.work.size(); ++li)
    if (!c.dropped[li]) c.cut_tips(li);
  for (std::size_t li = 0; li < c.work.size(); ++li) {
    if (c.dropped[li]) continue;
    OutlineLoop out;
    finish(c.work[li], out);
    c.res.loops.push_back(std::move(out));
  }
  return std::move(c.res);
}

}  // namespace plyfit
