// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The angle error of a spherical map, as users compare tools: each corner's angle in the mesh against that of the
// straight triangle between the mapped points. measure_spherical_distortion() reports it; the mapper compares two
// candidate maps by it (Sphere_mapper::least_distortion()).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ANGLE_ERROR_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ANGLE_ERROR_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/number_type_config.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Angle_error
{
  double mean_degrees = 0.; // over all corners
  double max_degrees = 0.;
};

inline Angle_error angle_error(const std::vector<Vector3>& points, const std::vector<std::array<int, 3>>& triangles,
                               const std::vector<Vector3>& x)
{
  auto angle = [](const Vector3& a, const Vector3& b) { return std::atan2(length(cross(a, b)), dot(a, b)); };
  Angle_error error;
  std::size_t corners = 0;
  for(const std::array<int, 3>& t : triangles)
  {
    const Vector3 p[3] = {points[std::size_t(t[0])], points[std::size_t(t[1])], points[std::size_t(t[2])]};
    const Vector3 q[3] = {x[std::size_t(t[0])], x[std::size_t(t[1])], x[std::size_t(t[2])]};
    for(int k = 0; k < 3; ++k)
    {
      const double in_mesh = angle(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
      const double on_sphere = angle(q[(k + 1) % 3] - q[k], q[(k + 2) % 3] - q[k]);
      const double corner = std::abs(on_sphere - in_mesh) * 180. / CGAL_PI;
      error.mean_degrees += corner;
      error.max_degrees = (std::max)(error.max_degrees, corner);
      ++corners;
    }
  }
  if(corners > 0)
    error.mean_degrees /= static_cast<double>(corners);
  return error;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ANGLE_ERROR_H
