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

struct Sphere_certificate {
  std::size_t flipped_faces = 0;   // not POSITIVE under the exact predicate
  double total_signed_area = 0.;
  bool bijective = false;
};

// Bijective iff every triangle is positive and the areas add up to 4 pi. With all triangles positive the total
// is 4 pi times the degree of the map, so a tolerance of pi separates degree 1 from any other degree.
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
  const double four_pi = 4. * 3.14159265358979323846;
  certificate.bijective = certificate.flipped_faces == 0 && std::abs(certificate.total_signed_area - four_pi) < 3.14159265358979323846;
  return certificate;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ORIENTATION_H
