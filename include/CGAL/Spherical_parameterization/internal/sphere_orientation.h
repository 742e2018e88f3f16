// Orientation of spherical triangles under CGAL's exact predicate, and their signed areas.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ORIENTATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ORIENTATION_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// True when the spherical triangle (a, b, c) is positively oriented: orientation(ORIGIN, a, b, c) is POSITIVE,
// decided exactly on the double coordinates (filtered, so cheap in the common case). A non-finite point is not
// positive: the exact arithmetic cannot take it (a CGAL assertion, undefined without assertions), and a
// backtracked move pulled through the centre of the sphere yields one.
inline bool is_positive(const Vector3& a, const Vector3& b, const Vector3& c)
{
  if(!is_finite(a) || !is_finite(b) || !is_finite(c)) return false;
  using P = CGAL::Epick::Point_3;
  return CGAL::orientation(P(CGAL::ORIGIN), P(a.x, a.y, a.z), P(b.x, b.y, b.z), P(c.x, c.y, c.z)) == CGAL::POSITIVE;
}

// Signed area of the spherical triangle on the unit sphere (Van Oosterom and Strackee). `positive`: the exact
// predicate's verdict, when known. A triangle spanning nearly a great circle has an area near 2 pi, where atan2
// has its branch cut: a rounded determinant of the wrong sign would count -2 pi instead of 2 pi (found by the
// fuzzer), so the exact sign is used for the determinant's.
inline double signed_spherical_area(const Vector3& a, const Vector3& b, const Vector3& c, bool positive = false)
{
  const double determinant_abc = determinant(a, b, c);
  const double numerator = positive ? std::abs(determinant_abc) : determinant_abc;
  const double denominator = 1. + dot(a, b) + dot(b, c) + dot(c, a);
  return 2. * std::atan2(numerator, denominator);
}

// How many of the spherical triangles contain a generic point of the sphere, decided with exact predicates: with
// every triangle positive this is the degree of the map. Areas cannot decide it when the map is degenerate:
// triangles whose vertices are within rounding of two antipodal points (found by the fuzzer) have areas that
// rounding sets anywhere in (0, 2 pi). Returns -1 if every candidate point lies on the boundary of a triangle.
inline long covering_number(const std::vector<std::array<int, 3>>& triangles, const std::vector<Vector3>& x)
{
  using P = CGAL::Epick::Point_3;
  const P origin(CGAL::ORIGIN);
  // Points with no structure, so that no mesh lies along them by accident; the next one is tried on a boundary.
  const P candidates[] = {P(0.3141592653589793, 0.5772156649015329, 0.7539022543433046),
                          P(-0.6180339887498949, 0.2718281828459045, -0.4142135623730950),
                          P(0.1234567890123456, -0.8765432109876543, 0.3456789012345678),
                          P(-0.2236067977499790, -0.1732050807568877, -0.9486832980505138)};
  for(const P& p : candidates) {
    long count = 0;
    bool on_boundary = false;
    for(const auto& t : triangles) {
      const Vector3& a = x[static_cast<std::size_t>(t[0])];
      const Vector3& b = x[static_cast<std::size_t>(t[1])];
      const Vector3& c = x[static_cast<std::size_t>(t[2])];
      if(!is_finite(a) || !is_finite(b) || !is_finite(c)) continue;
      const P pa(a.x, a.y, a.z), pb(b.x, b.y, b.z), pc(c.x, c.y, c.z);
      const CGAL::Orientation o1 = CGAL::orientation(origin, pa, pb, p);
      if(o1 == CGAL::NEGATIVE) continue;
      const CGAL::Orientation o2 = CGAL::orientation(origin, pb, pc, p);
      if(o2 == CGAL::NEGATIVE) continue;
      const CGAL::Orientation o3 = CGAL::orientation(origin, pc, pa, p);
      if(o3 == CGAL::NEGATIVE) continue;
      if(o1 == CGAL::ZERO || o2 == CGAL::ZERO || o3 == CGAL::ZERO) { on_boundary = true; break; }
      ++count;
    }
    if(!on_boundary) return count;
  }
  return -1;
}

struct Sphere_certificate {
  std::size_t flipped_faces = 0;   // not POSITIVE under the exact predicate
  double total_signed_area = 0.;
  bool bijective = false;
};

// Bijective iff every triangle is positive and a generic point is covered exactly once: an orientation-preserving
// map of a sphere onto the sphere is a branched covering, and degree 1 leaves no room for branch points or
// multiple coverings. Everything is decided by exact predicates; the total area (4 pi times the degree when every
// area is well conditioned) is reported as a figure.
inline Sphere_certificate certify(const std::vector<std::array<int, 3>>& triangles, const std::vector<Vector3>& x)
{
  Sphere_certificate certificate;
  for(const auto& t : triangles) {
    const Vector3& a = x[static_cast<std::size_t>(t[0])];
    const Vector3& b = x[static_cast<std::size_t>(t[1])];
    const Vector3& c = x[static_cast<std::size_t>(t[2])];
    if(!is_finite(a) || !is_finite(b) || !is_finite(c)) { ++certificate.flipped_faces; continue; }
    const bool positive = is_positive(a, b, c);
    if(!positive) ++certificate.flipped_faces;
    certificate.total_signed_area += signed_spherical_area(a, b, c, positive);
  }
  certificate.bijective = certificate.flipped_faces == 0 && covering_number(triangles, x) == 1;
  return certificate;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ORIENTATION_H
