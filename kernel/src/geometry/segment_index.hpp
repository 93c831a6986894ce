// Private to the kernel: a uniform grid over 2D segments for the two queries the shell and the
// flat pattern ask of a face's boundary polylines: where a segment p -> q crosses them, and
// which of them pass near a point.
#pragma once

#include <plyfit/kernel/types.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace plyfit::detail {

/// A grid over segments in the (u, v) plane.
class SegmentIndex {
 public:
  struct Seg {
    Vec2 a, b;
    int id;  ///< the caller's tag
  };
  /// Cells of the grid per direction (at most).
  static constexpr int kGridMax = 256;

  SegmentIndex() = default;
  explicit SegmentIndex(std::vector<Seg> segs) : segs_(std::move(segs)) {
    if (segs_.empty()) return;
    lo_ = hi_ = segs_[0].a;
    for (const Seg& g : segs_) {
      lo_ = lo_.cwiseMin(g.a).cwiseMin(g.b);
      hi_ = hi_.cwiseMax(g.a).cwiseMax(g.b);
    }
    n_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segs_.size()))), 1, kGridMax);
    cell_ = ((hi_ - lo_) / n_).cwiseMax(Vec2::Constant(1e-300));
    grid_.assign(static_cast<std::size_t>(n_) * n_, {});
    for (int k = 0; k < static_cast<int>(segs_.size()); ++k) {
      int i0, j0, i1, j1;
      range(segs_[k].a.cwiseMin(segs_[k].b), segs_[k].a.cwiseMax(segs_[k].b), i0, j0, i1, j1);
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) grid_[static_cast<std::size_t>(i) * n_ + j].push_back(k);
    }
  }

  bool empty() const { return segs_.empty(); }
  const Seg& seg(int k) const { return segs_[static_cast<std::size_t>(k)]; }

  /// Parameters t in (0, 1) where segment p -> q crosses the indexed segments, sorted, with
  /// the segment crossed (its position in the index). Half-open rules count a crossing
  /// through a shared vertex of two segments once.
  std::vector<std::pair<double, int>> crossings(const Vec2& p, const Vec2& q) const {
    std::vector<std::pair<double, int>> out;
    if (segs_.empty()) return out;
    const Vec2 r = q - p;
    for_candidates(p.cwiseMin(q), p.cwiseMax(q), [&](int k) {
      const Vec2 a = segs_[k].a, e = segs_[k].b - segs_[k].a;
      const double den = cross2(r, e);
      if (den == 0.0) return;  // parallel
      const double t = cross2(a - p, e) / den;
      const double s = cross2(a - p, r) / den;
      if (t > 0.0 && t < 1.0 && s >= 0.0 && s < 1.0) out.push_back({t, k});
    });
    std::sort(out.begin(), out.end());
    return out;
  }

  /// Calls f(k) once for every segment whose box meets the box [lo, hi].
  template <class F>
  void for_candidates(const Vec2& lo, const Vec2& hi, F&& f) const {
    if (segs_.empty()) return;
    if (hi.x() < lo_.x() || hi.y() < lo_.y() || lo.x() > hi_.x() || lo.y() > hi_.y()) return;
    int i0, j0, i1, j1;
    range(lo, hi, i0, j0, i1, j1);
    std::vector<int> cand;  // local: queries on a shared index may run in parallel
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        for (int k : grid_[static_cast<std::size_t>(i) * n_ + j]) cand.push_back(k);
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    for (int k : cand) {
      const Seg& g = segs_[static_cast<std::size_t>(k)];
      const Vec2 slo = g.a.cwiseMin(g.b), shi = g.a.cwiseMax(g.b);
      if (shi.x() < lo.x() || shi.y() < lo.y() || slo.x() > hi.x() || slo.y() > hi.y()) continue;
      f(k);
    }
  }

 private:
  void range(const Vec2& a, const Vec2& b, int& i0, int& j0, int& i1, int& j1) const {
    auto idx = [&](double x, double o, double c) {
      return std::clamp(static_cast<int>(std::floor((x - o) / c)), 0, n_ - 1);
    };
    i0 = idx(a.x(), lo_.x(), cell_.x());
    i1 = idx(b.x(), lo_.x(), cell_.x());
    j0 = idx(a.y(), lo_.y(), cell_.y());
    j1 = idx(b.y(), lo_.y(), cell_.y());
  }
  std::vector<Seg> segs_;
  Vec2 lo_ = Vec2::Zero(), hi_ = Vec2::Zero(), cell_ = Vec2::Ones();
  int n_ = 1;
  std::vector<std::vector<int>> grid_;
};

}  // namespace plyfit::detail
