// The in/out test of a face: its trim loops as a grid of cells and slabs of segments.
#include "surface/face.hpp"

#include "geometry/numeric.hpp"

#include <plyfit/kernel/polygon2d.hpp>

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {

// Grid over the trim loops' box for contains(): about this many cells per direction per
// square root of the segment count, within bounds.
constexpr double kCellsPerSegmentRoot = 4.0;
constexpr int kCellsMin = 64;
constexpr int kCellsMax = 512;
// Relative widening of a segment's box when marking the cells it touches.
constexpr double kCellPadRel = 1e-6;
// Horizontal slabs of the trim segments for the crossing count: at most this many.
constexpr int kSlabsMax = 4096;

}  // namespace

void Face::build_slabs() {
  segs_.clear();
  slabs_.clear();
  if (loops_.empty()) return;
  loops_min_ = loops_max_ = loops_.front().points.front();
  for (const auto& l : loops_) {
    const size_t n = l.points.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2& a = l.points[k];
      const Vec2& b = l.points[(k + 1) % n];
      loops_min_ = loops_min_.cwiseMin(a);
      loops_max_ = loops_max_.cwiseMax(a);
      if (a.y() != b.y()) segs_.push_back({a, b});  // horizontal edges never cross the ray
    }
  }
  const int nslab =
      std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segs_.size()))), 1, kSlabsMax);
  slab_v0_ = loops_min_.y();
  slab_h_ = std::max((loops_max_.y() - loops_min_.y()) / nslab, detail::kDivisionFloor);
  slabs_.assign(nslab, {});
  for (int s = 0; s < static_cast<int>(segs_.size()); ++s) {
    const double lo = std::min(segs_[s].a.y(), segs_[s].b.y());
    const double hi = std::max(segs_[s].a.y(), segs_[s].b.y());
    const int k0 =
        std::clamp(static_cast<int>(std::floor((lo - slab_v0_) / slab_h_)), 0, nslab - 1);
    const int k1 =
        std::clamp(static_cast<int>(std::floor((hi - slab_v0_) / slab_h_)), 0, nslab - 1);
    for (int k = k0; k <= k1; ++k) slabs_[k].push_back(s);
  }
  // Cells of the loops' box that no loop segment touches are wholly inside or outside: their
  // centre's answer holds for all their points, and contains() needs no crossing count there.
  cells_n_ = std::clamp(
      static_cast<int>(kCellsPerSegmentRoot * std::sqrt(static_cast<double>(segs_.size() + 1))),
      kCellsMin, kCellsMax);
  cell_size_ =
      ((loops_max_ - loops_min_) / cells_n_).cwiseMax(Vec2::Constant(detail::kDivisionFloor));
  cells_.assign(static_cast<std::size_t>(cells_n_) * cells_n_, kCellUnknown);
  auto cell = [&](double x, double o, double c) {
    return std::clamp(static_cast<int>(std::floor((x - o) / c)), 0, cells_n_ - 1);
  };
  for (const auto& l : loops_) {
    const size_t n = l.points.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec2 lo = l.points[k].cwiseMin(l.points[(k + 1) % n]);
      const Vec2 hi = l.points[k].cwiseMax(l.points[(k + 1) % n]);
      // The segment's box widened by a hair: a point on a cell's border, which rounding may
      // put in either cell, is tested exactly.
      const Vec2 pad = kCellPadRel * cell_size_;
      const int i0 = cell(lo.x() - pad.x(), loops_min_.x(), cell_size_.x());
      const int i1 = cell(hi.x() + pad.x(), loops_min_.x(), cell_size_.x());
      const int j0 = cell(lo.y() - pad.y(), loops_min_.y(), cell_size_.y());
      const int j1 = cell(hi.y() + pad.y(), loops_min_.y(), cell_size_.y());
      for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j)
          cells_[static_cast<std::size_t>(i) * cells_n_ + j] = kCellBoundary;
    }
  }
  for (int i = 0; i < cells_n_; ++i)
    for (int j = 0; j < cells_n_; ++j) {
      auto& c = cells_[static_cast<std::size_t>(i) * cells_n_ + j];
      if (c == kCellUnknown)
        c = inside_trims(loops_min_ + Vec2((i + 0.5) * cell_size_.x(), (j + 0.5) * cell_size_.y()))
                ? kCellInside
                : kCellOutside;
    }
}

bool Face::inside_trims_fast(const Vec2& uv) const {
  const double u = uv.x(), v = uv.y();
  if (v < loops_min_.y() || v > loops_max_.y() || u < loops_min_.x() || u > loops_max_.x())
    return false;
  const int i =
      std::clamp(static_cast<int>((u - loops_min_.x()) / cell_size_.x()), 0, cells_n_ - 1);
  const int j =
      std::clamp(static_cast<int>((v - loops_min_.y()) / cell_size_.y()), 0, cells_n_ - 1);
  const std::uint8_t c = cells_[static_cast<std::size_t>(i) * cells_n_ + j];
  if (c != kCellBoundary) return c == kCellInside;
  return inside_trims(uv);
}

bool Face::inside_trims(const Vec2& uv) const {
  const double u = uv.x(), v = uv.y();
  if (v < loops_min_.y() || v > loops_max_.y() || u < loops_min_.x() || u > loops_max_.x())
    return false;
  const int k = std::clamp(static_cast<int>(std::floor((v - slab_v0_) / slab_h_)), 0,
                           static_cast<int>(slabs_.size()) - 1);
  bool inside = false;  // even-odd, over the segments of the slab
  for (int s : slabs_[k])
    if (crosses_ray(segs_[s].a, segs_[s].b, uv)) inside = !inside;
  return inside;
}

bool Face::contains(const Vec2& uv) const {
  const Vec2 w = wrap(uv);
  const auto& d = domain();
  if (!d.contains(w.x(), w.y(), tol_.param_rel * d.width_u(), tol_.param_rel * d.width_v()))
    return false;
  return loops_.empty() || natural_ || inside_trims_fast(w);
}

bool Face::in_hole(const Vec2& uv) const {
  if (outer_ < 0) return false;
  const Vec2 w = wrap(uv);
  if (!domain().contains(w.x(), w.y()) || contains(w)) return false;
  return inside_polygon(loops_[static_cast<std::size_t>(outer_)].points, w);
}

}  // namespace plyfit
