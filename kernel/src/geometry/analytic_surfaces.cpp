#include "geometry/analytic_surfaces.hpp"

#include <algorithm>
#include <cmath>

namespace plyfit {

namespace {

// cos and sin of multiples of pi/2 are rounded to exact 0 and +-1, so that the poles of a
// sphere coincide exactly and its pole is a true collapsed edge (below 1 ulp of 1).
constexpr double kTrigSnap = 1e-15;
// A sweep within this many quarter turns above a whole number of them needs no extra arc
// (its rounding).
constexpr double kQuarterTurnSlack = 1e-12;

double snap(double x) {
  if (std::abs(x) < kTrigSnap) return 0.0;
  if (std::abs(std::abs(x) - 1.0) < kTrigSnap) return x > 0 ? 1.0 : -1.0;
  return x;
}

// Unit-circle arc control points (x, y), weights and knots (The NURBS Book, A7.1), for the
// parametrisation (cos t, sin t), t from t0 to t1 (signed sweep).
struct ArcNet {
  std::vector<Eigen::Vector2d> pts;
  std::vector<double> w;
  std::vector<double> knots;
};

ArcNet unit_arc(double t0, double t1) {
  const double sweep = t1 - t0;
  const int narcs =
      std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (kPi / 2) - kQuarterTurnSlack)));
  const double dt = sweep / narcs;
  const double wm = std::cos(dt / 2);
  ArcNet a;
  a.pts.emplace_back(snap(std::cos(t0)), snap(std::sin(t0)));
  a.w.push_back(1.0);
  double angle = t0;
  for (int i = 0; i < narcs; ++i) {
    const double a2 = angle + dt;
    const double am = angle + dt / 2;
    a.pts.emplace_back(snap(std::cos(am)) / wm, snap(std::sin(am)) / wm);
    a.w.push_back(wm);
    a.pts.emplace_back(snap(std::cos(a2)), snap(std::sin(a2)));
    a.w.push_back(1.0);
    angle = a2;
  }
  a.knots = {0.0, 0.0, 0.0};
  for (int i = 1; i < narcs; ++i) {
    a.knots.push_back(static_cast<double>(i) / narcs);
    a.knots.push_back(static_cast<double>(i) / narcs);
  }
  a.knots.insert(a.knots.end(), {1.0, 1.0, 1.0});
  return a;
}

}  // namespace

NurbsCurveData2 line2(const Vec2& a, const Vec2& b) {
  NurbsCurveData2 c;
  c.degree = 1;
  c.knots = {0, 0, 1, 1};
  c.poles = {a, b};
  return c;
}

NurbsCurveData2 circle_arc(double radius, double a0, double a1) {
  return ellipse_arc(radius, radius, a0, a1);
}

NurbsCurveData2 ellipse_arc(double a, double b, double t0, double t1) {
  const ArcNet net = unit_arc(t0, t1);
  NurbsCurveData2 c;
  c.degree = 2;
  c.knots = net.knots;
  c.weights = net.w;
  for (const auto& p : net.pts) c.poles.emplace_back(a * p.x(), b * p.y());
  return c;
}

NurbsSurfaceData plane_patch(const Vec3& origin, const Vec3& u_edge, const Vec3& v_edge) {
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.poles = {origin, origin + v_edge, origin + u_edge, origin + u_edge + v_edge};
  return s;
}

NurbsSurfaceData revolve(const NurbsCurveData2& profile, double a0, double a1) {
  const ArcNet arc = unit_arc(a0, a1);
  NurbsSurfaceData s;
  s.degree_u = profile.degree;
  s.degree_v = 2;
  s.count_u = static_cast<int>(profile.poles.size());
  s.count_v = static_cast<int>(arc.pts.size());
  s.knots_u = profile.knots;
  s.knots_v = arc.knots;
  for (int i = 0; i < s.count_u; ++i) {
    const double r = profile.poles[i].x(), z = profile.poles[i].y();
    const double wi = profile.weights.empty() ? 1.0 : profile.weights[i];
    for (int j = 0; j < s.count_v; ++j) {
      s.poles.emplace_back(r * arc.pts[j].x(), r * arc.pts[j].y(), z);
      s.weights.push_back(wi * arc.w[j]);  // the arc is always rational
    }
  }
  return s;
}

NurbsSurfaceData cylinder_patch(double radius, double a0, double a1, double z0, double z1) {
  return revolve(line2(Vec2(radius, z1), Vec2(radius, z0)), a0, a1);
}

NurbsSurfaceData cone_patch(double r0, double r1, double z0, double z1, double a0, double a1) {
  return revolve(line2(Vec2(r1, z1), Vec2(r0, z0)), a0, a1);
}

NurbsSurfaceData sphere_patch(double radius, double lat0, double lat1, double lon0, double lon1) {
  // Profile from the upper latitude down to the lower one: the normal is then outward.
  NurbsCurveData2 prof = circle_arc(radius, lat1, lat0);
  return revolve(prof, lon0, lon1);
}

NurbsSurfaceData sphere_octant(double radius) {
  return sphere_patch(radius, 0.0, kPi / 2, 0.0, kPi / 2);
}

NurbsSurfaceData torus_patch(double major, double minor, double t0, double t1, double lon0,
                             double lon1) {
  NurbsCurveData2 prof = circle_arc(minor, t1, t0);  // decreasing tube angle: outward normal
  for (auto& p : prof.poles) p.x() += major;
  return revolve(prof, lon0, lon1);
}

NurbsSurfaceData extrude(const NurbsCurveData3& profile, const Vec3& direction) {
  NurbsSurfaceData s;
  s.degree_u = profile.degree;
  s.degree_v = 1;
  s.count_u = static_cast<int>(profile.poles.size());
  s.count_v = 2;
  s.knots_u = profile.knots;
  s.knots_v = {0, 0, 1, 1};
  for (int i = 0; i < s.count_u; ++i) {
    s.poles.push_back(profile.poles[i]);
    s.poles.push_back(profile.poles[i] + direction);
    if (!profile.weights.empty()) {
      s.weights.push_back(profile.weights[i]);
      s.weights.push_back(profile.weights[i]);
    }
  }
  return s;
}

NurbsSurfaceData wave_surface(double size, double amplitude, double wavelength, int n) {
  n = std::max(n, 4);
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 3;
  s.count_u = s.count_v = n;
  std::vector<double> k(4, 0.0);
  for (int i = 1; i <= n - 4; ++i) k.push_back(static_cast<double>(i) / (n - 3));
  k.insert(k.end(), 4, 1.0);
  s.knots_u = s.knots_v = k;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = size * i / (n - 1), y = size * j / (n - 1);
      const double z =
          amplitude * std::sin(2 * kPi * x / wavelength) * std::cos(2 * kPi * y / wavelength);
      s.poles.emplace_back(x, y, z);
    }
  }
  return s;
}

NurbsSurfaceData saddle_patch(double size, double rho) {
  const double a = size / 2;
  const double c[3] = {1.0, -1.0, 1.0};  // Bernstein coefficients of (2t - 1)^2
  const double x[3] = {-a, 0.0, a};
  NurbsSurfaceData s;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.poles.emplace_back(x[i], x[j], a * a * (c[i] - c[j]) / (2 * rho));
  return s;
}

void reverse_u(NurbsSurfaceData& s) {
  NurbsSurfaceData r = s;
  const double a = s.knots_u.front(), b = s.knots_u.back();
  for (size_t k = 0; k < s.knots_u.size(); ++k)
    r.knots_u[k] = a + b - s.knots_u[s.knots_u.size() - 1 - k];
  for (int i = 0; i < s.count_u; ++i) {
    for (int j = 0; j < s.count_v; ++j) {
      r.pole(i, j) = s.pole(s.count_u - 1 - i, j);
      if (!s.weights.empty())
        r.weights[static_cast<size_t>(i) * s.count_v + j] =
            s.weights[static_cast<size_t>(s.count_u - 1 - i) * s.count_v + j];
    }
  }
  s = std::move(r);
}

}  // namespace plyfit
