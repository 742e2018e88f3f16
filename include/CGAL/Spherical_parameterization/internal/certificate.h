// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Orientation of spherical triangles under CGAL's exact predicate, and their signed areas.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_CERTIFICATE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_CERTIFICATE_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// The sum of the absolute values of the six products in a . (b x c): the scale of its rounding error.
inline double determinant_permanent(const Vector3& a, const Vector3& b, const Vector3& c)
{
  return std::abs(a.x) * (std::abs(b.y * c.z) + std::abs(b.z * c.y))
         + std::abs(a.y) * (std::abs(b.z * c.x) + std::abs(b.x * c.z))
         + std::abs(a.z) * (std::abs(b.x * c.y) + std::abs(b.y * c.x));
}

// True when the spherical triangle (a, b, c) is positively oriented: orientation(ORIGIN, a, b, c) is POSITIVE,
// decided exactly on the double coordinates. The determinant a . (b x c) is computed in double first; when it is
// farther from 0 than its worst-case rounding error (Shewchuk's bound for orient3d, with the fourth point at the
// origin so that no translation error occurs) its sign is certain; otherwise CGAL's exact predicate decides.
// The iterations call this millions of times, mostly on clear cases.
inline bool is_positive(const Vector3& a, const Vector3& b, const Vector3& c)
{
  const double bc_x = b.y * c.z - b.z * c.y, bc_y = b.z * c.x - b.x * c.z, bc_z = b.x * c.y - b.y * c.x;
  const double det = a.x * bc_x + a.y * bc_y + a.z * bc_z;
  const double permanent = determinant_permanent(a, b, c);
  const double bound = 7.7715611723761027e-16 * permanent; // (7 + 56 eps) eps, eps = 2^-53
  if(det > bound)
    return true;
  if(det < -bound)
    return false;
  // A non-finite coordinate makes the permanent non-finite: never positive (the exact arithmetic cannot take it,
  // and a backtracked move pulled through the centre of the sphere yields one).
  if(!std::isfinite(permanent))
    return false;
  using P = CGAL::Epick::Point_3;
  return CGAL::orientation(P(CGAL::ORIGIN), P(a.x, a.y, a.z), P(b.x, b.y, b.z), P(c.x, c.y, c.z)) == CGAL::POSITIVE;
}

// Signed area of the spherical triangle (a, b, c) on the unit sphere (Van Oosterom and Strackee):
// 2 atan2(a . (b x c), 1 + a.b + b.c + c.a). When the triangle is nearly degenerate, both arguments are within
// rounding of 0 (a vertex within rounding of another or of its antipode) and their rounded values would put the
// area anywhere in (-2 pi, 2 pi) (found by the fuzzer); they are then evaluated exactly on the double coordinates,
// so that the area is the one of the triangle the exact orientation test judged. `positive`: that test's
// verdict, when known, used for the sign of the area.
inline double signed_spherical_area(const Vector3& a, const Vector3& b, const Vector3& c, bool positive = false)
{
  double numerator = determinant(a, b, c);
  double denominator = 1. + dot(a, b) + dot(b, c) + dot(c, a);
  const double numerator_scale = determinant_permanent(a, b, c);
  const double denominator_scale = 1. + std::abs(a.x * b.x) + std::abs(a.y * b.y) + std::abs(a.z * b.z)
                                   + std::abs(b.x * c.x) + std::abs(b.y * c.y) + std::abs(b.z * c.z)
                                   + std::abs(c.x * a.x) + std::abs(c.y * a.y) + std::abs(c.z * a.z);
  // The angle atan2(numerator, denominator) is off by about (rounding error of the arguments) / |(numerator,
  // denominator)|: about 1e-15 on a small or ordinary triangle (the denominator is near 4), ill-conditioned only
  // when both arguments are near 0. Below 1e-8 of accuracy per triangle, they are evaluated exactly (rarely).
  const double rounding = 8e-16 * (numerator_scale + denominator_scale);
  if(std::isfinite(rounding) && std::abs(numerator) + std::abs(denominator) < 1e8 * rounding)
  {
    using Q = CGAL::Exact_rational;
    const Q ax(a.x), ay(a.y), az(a.z), bx(b.x), by(b.y), bz(b.z), cx(c.x), cy(c.y), cz(c.z);
    numerator = CGAL::to_double(ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx));
    denominator =
        CGAL::to_double(Q(1) + ax * bx + ay * by + az * bz + bx * cx + by * cy + bz * cz + cx * ax + cy * ay + cz * az);
  }
  if(positive)
    numerator = std::abs(numerator);
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
  for(const P& p : candidates)
  {
    long count = 0;
    bool on_boundary = false;
    for(const auto& t : triangles)
    {
      const Vector3& a = x[static_cast<std::size_t>(t[0])];
      const Vector3& b = x[static_cast<std::size_t>(t[1])];
      const Vector3& c = x[static_cast<std::size_t>(t[2])];
      if(!is_finite(a) || !is_finite(b) || !is_finite(c))
        continue;
      const P pa(a.x, a.y, a.z), pb(b.x, b.y, b.z), pc(c.x, c.y, c.z);
      const CGAL::Orientation o1 = CGAL::orientation(origin, pa, pb, p);
      if(o1 == CGAL::NEGATIVE)
        continue;
      const CGAL::Orientation o2 = CGAL::orientation(origin, pb, pc, p);
      if(o2 == CGAL::NEGATIVE)
        continue;
      const CGAL::Orientation o3 = CGAL::orientation(origin, pc, pa, p);
      if(o3 == CGAL::NEGATIVE)
        continue;
      if(o1 == CGAL::ZERO || o2 == CGAL::ZERO || o3 == CGAL::ZERO)
      {
        on_boundary = true;
        break;
      }
      ++count;
    }
    if(!on_boundary)
      return count;
  }
  return -1;
}

struct Sphere_certificate
{
  std::size_t flipped_faces = 0; // not POSITIVE under the exact predicate
  double total_signed_area = 0.;
  bool bijective = false;
};

// Bijective iff every triangle is positive and a generic point is covered exactly once: an orientation-preserving
// map of a sphere onto the sphere is a branched covering, and degree 1 leaves no room for branch points or
// multiple coverings. Both are decided by exact predicates on x, so two certificates of the same points agree.
// The total area (4 pi times the degree when every triangle is positive) is reported, not decisive: on a map whose
// points sit within rounding of two antipodal points, the exact areas of the same triangles after a renormalization
// by one ulp differ by up to 2 pi each (found by the fuzzer).
// `unit`: where the areas are measured, when x is not on the unit sphere (the user's map, radially projected);
// the exact tests run on x itself, and their verdict also gives the sign of each area, because projecting can
// move a triangle along a great circle across atan2's branch cut (found by the fuzzer).
inline Sphere_certificate certify(const std::vector<std::array<int, 3>>& triangles, const std::vector<Vector3>& x,
                                  const std::vector<Vector3>* unit = nullptr)
{
  const std::vector<Vector3>& on_sphere = unit != nullptr ? *unit : x;
  Sphere_certificate certificate;
  for(const auto& t : triangles)
  {
    const std::size_t i = static_cast<std::size_t>(t[0]), j = static_cast<std::size_t>(t[1]),
                      k = static_cast<std::size_t>(t[2]);
    if(!is_finite(x[i]) || !is_finite(x[j]) || !is_finite(x[k]))
    {
      ++certificate.flipped_faces;
      continue;
    }
    const bool positive = is_positive(x[i], x[j], x[k]);
    if(!positive)
      ++certificate.flipped_faces;
    certificate.total_signed_area += signed_spherical_area(on_sphere[i], on_sphere[j], on_sphere[k], positive);
  }
  certificate.bijective = certificate.flipped_faces == 0 && covering_number(triangles, x) == 1;
  return certificate;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_CERTIFICATE_H
