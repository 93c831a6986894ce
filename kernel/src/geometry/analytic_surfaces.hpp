#pragma once
/// \file Exact NURBS constructions of the analytic surfaces plyfit's tests, samples and
/// built-in molds use. Angles in radians. Every surface of revolution is about the Z axis,
/// with u running along the profile and v around the axis (counter-clockwise seen from +Z).
///
/// Orientation: for a surface of revolution the normal Su x Sv is the profile tangent
/// rotated by +90 degrees in the (r, z) half-plane; the constructors below choose the
/// profile direction so that the normal points away from the axis (outward, convex side).

#include <plyfit/kernel/nurbs.hpp>

namespace plyfit {

/// Rational quadratic circular arc of `radius` about the origin from angle a0 to a1 (either
/// direction, any sweep up to 2 pi), split into pieces of at most 90 degrees. Exact.
NurbsCurveData2 circle_arc(double radius, double a0, double a1);

/// Rational quadratic arc of the axis-aligned ellipse x^2/a^2 + y^2/b^2 = 1 from angle t0 to
/// t1 of its parametrisation (a cos t, b sin t). Exact.
NurbsCurveData2 ellipse_arc(double a, double b, double t0, double t1);

/// The straight segment from a to b as a degree-1 curve (parameter 0 to 1).
NurbsCurveData2 line2(const Vec2& a, const Vec2& b);

/// Bilinear patch origin + s * u_edge + t * v_edge, s, t in [0, 1]; normal u_edge x v_edge.
NurbsSurfaceData plane_patch(const Vec3& origin, const Vec3& u_edge, const Vec3& v_edge);

/// Surface of revolution of `profile` given in the (r, z) half-plane (r >= 0) about Z, from
/// angle a0 to a1 counter-clockwise (a1 > a0, a1 - a0 <= 2 pi). Exact for rational profiles.
NurbsSurfaceData revolve(const NurbsCurveData2& profile, double a0, double a1);

/// Cylinder x^2 + y^2 = R^2, angle a0..a1, z0 <= z <= z1; outward normal.
NurbsSurfaceData cylinder_patch(double radius, double a0, double a1, double z0, double z1);

/// Cone frustum with radius r0 at z0 and r1 at z1 (z1 > z0; a radius may be 0, the apex),
/// angle a0..a1; outward normal.
NurbsSurfaceData cone_patch(double r0, double r1, double z0, double z1, double a0, double a1);

/// Sphere patch of radius R between latitudes lat0 < lat1 (in [-pi/2, pi/2]) and longitudes
/// lon0 < lon1; outward normal. A latitude of +-pi/2 gives a pole (a collapsed edge).
NurbsSurfaceData sphere_patch(double radius, double lat0, double lat1, double lon0, double lon1);

/// The first octant x, y, z >= 0 of the sphere of radius R: pole (0, 0, R) at u = 0.
NurbsSurfaceData sphere_octant(double radius);

/// Torus patch: tube of radius `minor` about the circle of radius `major` in the XY plane;
/// tube angle t0..t1 (0 = outer equator, pi/2 = top), longitude lon0..lon1; outward normal.
NurbsSurfaceData torus_patch(double major, double minor, double t0, double t1, double lon0,
                             double lon1);

/// Extrusion of a 3D profile curve along `direction` (the surface is profile(u) + v * dir,
/// v in [0, 1]); normal Su x Sv.
NurbsSurfaceData extrude(const NurbsCurveData3& profile, const Vec3& direction);

/// Smooth bicubic free-form "wave": a uniform bicubic B-spline with n x n poles over
/// [0, size]^2 at heights amplitude * sin(2 pi x / wavelength) * cos(2 pi y / wavelength);
/// normal towards +Z. n >= 4.
NurbsSurfaceData wave_surface(double size, double amplitude, double wavelength, int n);

/// Saddle (hyperbolic paraboloid) z = (x^2 - y^2) / (2 rho) over [-size/2, size/2]^2, exact
/// as a biquadratic Bezier patch; normal towards +Z.
NurbsSurfaceData saddle_patch(double size, double rho);

/// Reverses the u direction of a surface (flips its normal).
void reverse_u(NurbsSurfaceData& s);

}  // namespace plyfit
