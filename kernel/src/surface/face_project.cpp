// The nearest point of a face: seeds from samples, then a damped Newton iteration.
#include "surface/face.hpp"

#include "geometry/numeric.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {

// Projection: Levenberg-Marquardt iteration cap and damping schedule (relative to the
// diagonal of the Gauss-Newton matrix).
constexpr int kProjectMaxIterations = 200;
constexpr double kProjectDampingStart = 1e-6;
constexpr double kProjectDampingUp = 8.0;
constexpr double kProjectDampingDown = 0.25;
constexpr double kProjectMaxDamping = 1e16;
// Face::project: samples per direction, and how many of the nearest are seeds.
constexpr int kProjectSamples = 24;
constexpr std::size_t kProjectSeeds = 4;

}  // namespace

Projection Face::project(const Vec3& p) const {
  Projection best;
  std::call_once(project_samples_->once,
                 [&] { project_samples_->points = sample_face(*this, kProjectSamples); });
  const auto& samples = project_samples_->points;
  if (samples.empty()) return best;
  // Seeds: the few nearest samples.
  std::vector<size_t> order(samples.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const size_t nseed = std::min<size_t>(kProjectSeeds, order.size());
  std::partial_sort(order.begin(), order.begin() + nseed, order.end(), [&](size_t a, size_t b) {
    return (samples[a].second - p).squaredNorm() < (samples[b].second - p).squaredNorm();
  });
  for (size_t si = 0; si < nseed; ++si) {
    const Projection q = project_from(p, samples[order[si]].first, true);
    if (q.ok && (!best.ok || q.distance < best.distance)) best = q;
  }
  return best;
}

Projection Face::project_from(const Vec3& p, const Vec2& seed, bool on_face) const {
  Projection out;
  const auto& d = domain();
  const Eigen::Array2d width(d.width_u(), d.width_v());
  Vec2 uv = wrap(seed);
  if (!closed_u_) uv.x() = std::clamp(uv.x(), d.u0, d.u1);
  if (!closed_v_) uv.y() = std::clamp(uv.y(), d.v0, d.v1);
  const SurfaceEval1 e0 = eval1(uv);
  if (!e0.ok) return out;
  double dist = (e0.p - p).norm();
  // Levenberg-Marquardt on |S(u, v) - p|^2 with Marquardt scaling: the full Hessian where
  // it is positive definite, Gauss-Newton elsewhere; damping grows when a step is refused
  // (longer distance or off the face) and shrinks when one is taken.
  double lambda = 0.0;
  for (int it = 0; it < kProjectMaxIterations; ++it) {
    const SurfaceEval2 e = eval2(uv);
    if (!e.ok) break;
    const Vec3 r = e.p - p;
    const Vec2 g(e.du.dot(r), e.dv.dot(r));
    const Eigen::Matrix2d A = detail::metric(e);
    Eigen::Matrix2d H = A;
    H(0, 0) += r.dot(e.duu);
    H(0, 1) += r.dot(e.duv);
    H(1, 0) += r.dot(e.duv);
    H(1, 1) += r.dot(e.dvv);
    if (!(H.determinant() > 0.0 && H(0, 0) > 0.0)) H = A;
    const Vec2 D(std::max(A(0, 0), detail::kDivisionFloor),
                 std::max(A(1, 1), detail::kDivisionFloor));
    bool taken = false, converged = false;
    while (lambda < kProjectMaxDamping) {
      const Vec2 step = detail::damped_step(H, g, D, lambda);
      if (!step.allFinite()) break;
      Vec2 cand = uv + step;
      if (!closed_u_) cand.x() = std::clamp(cand.x(), d.u0, d.u1);
      if (!closed_v_) cand.y() = std::clamp(cand.y(), d.v0, d.v1);
      cand = wrap(cand);
      const bool tiny = (delta(uv, cand).cwiseAbs().array() <= tol_.param_rel * width).all();
      if (tiny) {
        converged = true;
        break;
      }
      if (!on_face || contains(cand)) {
        const SurfaceEval1 c = eval1(cand);
        const double cd = (c.p - p).norm();
        // Near the minimum a step of length h changes the distance by O(h^2), below its
        // rounding: there, a step that keeps the distance and shrinks the (scaled)
        // gradient is progress too.
        const Vec3 rc = c.p - p;
        const double gc =
            std::hypot(c.du.dot(rc) / std::sqrt(D.x()), c.dv.dot(rc) / std::sqrt(D.y()));
        const double g0 = std::hypot(g.x() / std::sqrt(D.x()), g.y() / std::sqrt(D.y()));
        const bool flat = cd <= dist + tol_.roundoff_rel * (p.norm() + dist + size_);
        if (c.ok && (cd < dist || (flat && gc < g0))) {
          uv = cand;
          dist = cd;
          taken = true;
          lambda *= kProjectDampingDown;
          break;
        }
      }
      lambda = lambda == 0.0 ? kProjectDampingStart : lambda * kProjectDampingUp;
    }
    if (!taken || converged) break;
  }
  out.at = SurfaceLocation(uv);
  out.point = eval1(uv).p;
  out.distance = dist;
  out.ok = true;
  return out;
}

}  // namespace plyfit
