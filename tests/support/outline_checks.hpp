#pragma once
// What every flat-pattern outline must be, checked from its points alone: no spike (a vertex
// where the outline turns back by more than kSpikeTurnDeg) and no self-intersection (two
// edges of the outline, of one loop or of two, that cross, or where a vertex lies on another
// edge, or that run along each other; a pinch, where the outline passes twice through one
// vertex, is no crossing). Shared by the kernel tests, the sample tests and the fuzz's C++
// counterpart.

#include <plyfit/kernel/flat_pattern.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace plyfit::support {

/// A vertex where the outline turns back by more than this (degrees) is a spike: the
/// outline runs out and back along a sliver (issue 13).
inline constexpr double kSpikeTurnDeg = 170.0;

/// A run of consecutive outline edges shorter than this many spacings that turns back, all
/// told, by more than kSpikeTurnDeg is a spike too: a sliver whose tip is two or more
/// vertices close together (as near a pole, issue 13). A hole of perimeter below this would
/// count as one; the drapes checked have none.
inline constexpr double kSpikeRunSpacings = 0.5;

/// One defect of an outline.
struct OutlineDefect {
  enum Kind { kSpike, kCrossing } kind;
  int loop = 0, index = 0;    ///< the spike's vertex, or the first edge of a crossing
  int loop2 = 0, index2 = 0;  ///< the second edge of a crossing
  Vec2 at = Vec2::Zero();
  double turn_deg = 0.0;  ///< a spike's turn
};

/// The defects of `loops` (at most `max` of them) of a drape at spacing d.
inline std::vector<OutlineDefect> outline_defects(const std::vector<OutlineLoop>& loops, double d,
                                                  std::size_t max = 20) {
  std::vector<OutlineDefect> out;
  constexpr double kPi = 3.14159265358979323846;
  for (int l = 0; l < static_cast<int>(loops.size()); ++l) {
    const auto& p = loops[static_cast<std::size_t>(l)].points;
    const int n = static_cast<int>(p.size());
    // turn[k]: the signed turn at vertex k from the incoming to the outgoing direction
    // (degrees, 0 straight on, +-180 back).
    std::vector<double> turn(static_cast<std::size_t>(n), 0.0);
    for (int k = 0; k < n && out.size() < max; ++k) {
      const Vec2 a = p[static_cast<std::size_t>((k + n - 1) % n)];
      const Vec2 b = p[static_cast<std::size_t>(k)];
      const Vec2 c = p[static_cast<std::size_t>((k + 1) % n)];
      const Vec2 in = b - a, o = c - b;
      turn[static_cast<std::size_t>(k)] = std::atan2(cross2(in, o), in.dot(o)) * 180.0 / kPi;
      if (in.norm() == 0.0 || o.norm() == 0.0 ||
          std::abs(turn[static_cast<std::size_t>(k)]) > kSpikeTurnDeg)
        out.push_back({OutlineDefect::kSpike, l, k, 0, 0, b, turn[static_cast<std::size_t>(k)]});
    }
    // Runs of two or more vertices joined by edges shorter than kSpikeRunSpacings d in all.
    for (int k = 0; k < n && out.size() < max && n > 3; ++k) {
      double len = 0.0, sum = turn[static_cast<std::size_t>(k)];
      for (int j = 1; j < n - 1; ++j) {
        const int q = (k + j) % n;
        len +=
            (p[static_cast<std::size_t>(q)] - p[static_cast<std::size_t>((q + n - 1) % n)]).norm();
        if (len >= kSpikeRunSpacings * d) break;
        sum += turn[static_cast<std::size_t>(q)];
        if (std::abs(sum) > kSpikeTurnDeg) {
          out.push_back({OutlineDefect::kSpike, l, k, 0, 0, p[static_cast<std::size_t>(k)], sum});
          break;
        }
      }
    }
  }
  // Every pair of edges: proper crossings, and touching (an end on the other edge) unless the
  // two edges are consecutive in one loop (they share that vertex).
  struct Edge {
    Vec2 a, b;
    int loop, index, n;
  };
  std::vector<Edge> edges;
  for (int l = 0; l < static_cast<int>(loops.size()); ++l) {
    const auto& p = loops[static_cast<std::size_t>(l)].points;
    const int n = static_cast<int>(p.size());
    for (int k = 0; k < n; ++k)
      edges.push_back(
          {p[static_cast<std::size_t>(k)], p[static_cast<std::size_t>((k + 1) % n)], l, k, n});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return std::min(x.a.x(), x.b.x()) < std::min(y.a.x(), y.b.x());
  });
  auto orient = [](const Vec2& o, const Vec2& p, const Vec2& q) {
    const double c = cross2(p - o, q - o);
    return c > 0 ? 1 : c < 0 ? -1 : 0;
  };
  auto on_segment = [](const Vec2& p, const Vec2& a, const Vec2& b) {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
           std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
  };
  for (std::size_t i = 0; i < edges.size() && out.size() < max; ++i) {
    const Edge& e = edges[i];
    const double xmax = std::max(e.a.x(), e.b.x());
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const Edge& f = edges[j];
      if (std::min(f.a.x(), f.b.x()) > xmax) break;
      if (std::max(e.a.y(), e.b.y()) < std::min(f.a.y(), f.b.y()) ||
          std::max(f.a.y(), f.b.y()) < std::min(e.a.y(), e.b.y()))
        continue;
      const int o1 = orient(e.a, e.b, f.a), o2 = orient(e.a, e.b, f.b);
      const int o3 = orient(f.a, f.b, e.a), o4 = orient(f.a, f.b, e.b);
      bool hit = o1 * o2 < 0 && o3 * o4 < 0;
      // An end of one edge on the other: a crossing unless it is a vertex of both (consecutive
      // edges, or a pinch where the outline passes twice through one vertex).
      auto touches = [&](const Vec2& p, const Edge& g) {
        return p != g.a && p != g.b && on_segment(p, g.a, g.b);
      };
      if (!hit)
        hit = (o1 == 0 && touches(f.a, e)) || (o2 == 0 && touches(f.b, e)) ||
              (o3 == 0 && touches(e.a, f)) || (o4 == 0 && touches(e.b, f)) ||
              (o1 == 0 && o2 == 0 && e.a == f.b && e.b == f.a) ||
              (o1 == 0 && o2 == 0 && e.a == f.a && e.b == f.b);
      if (hit) {
        out.push_back({OutlineDefect::kCrossing, e.loop, e.index, f.loop, f.index, e.a, 0.0});
        if (out.size() >= max) break;
      }
    }
  }
  return out;
}

/// The defects as text, one a line.
inline std::string describe(const std::vector<OutlineDefect>& defects) {
  std::ostringstream s;
  s.precision(10);
  for (const auto& d : defects) {
    if (d.kind == OutlineDefect::kSpike)
      s << "spike: loop " << d.loop << " vertex " << d.index << " at (" << d.at.x() << ", "
        << d.at.y() << ") turns " << d.turn_deg << " deg\n";
    else
      s << "crossing: loop " << d.loop << " edge " << d.index << " and loop " << d.loop2 << " edge "
        << d.index2 << " near (" << d.at.x() << ", " << d.at.y() << ")\n";
  }
  return s.str();
}

}  // namespace plyfit::support
