// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The distortion of a spherical map, for any map a user has (not only ours), as CGAL's Surface_mesh_parameterization
// keeps measure_distortion() apart from the parameterizers.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_SPHERICAL_DISTORTION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_SPHERICAL_DISTORTION_H

#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/angle_error.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Distortion of a spherical map, in the spirit of CGAL SMP's `measure_distortion()`. Angles are those of the
/// straight (chordal) triangles between the mapped points; areas are compared after normalizing both totals.
struct Spherical_distortion
{
  double mean_angle_error_degrees = 0.; ///< Mean of |angle on the sphere - angle on the mesh| over all corners.
  double max_angle_error_degrees = 0.;  ///< Largest such difference.
  double log_area_ratio_stddev = 0.;    ///< Standard deviation of log(relative sphere area / relative mesh area).
};

/// \ingroup PkgSphericalParameterizationRef
/// Measures the angle and area distortion of the map `vsm` of `tm`.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `VertexListGraph`.
/// \tparam VertexSphereMap a model of `ReadablePropertyMap` from vertices to points with `x()`, `y()`, `z()`.
/// \tparam NamedParameters a sequence of named parameters.
/// \param tm the mesh.
/// \param vsm the map onto the sphere.
/// \param np optional named parameters among the ones listed below.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm` (the angles and areas of the
///                           mesh)}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::vertex_descriptor`
///                    as key type and `Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///     \cgalParamExtra{If this parameter is omitted, an internal property map for `CGAL::vertex_point_t` must be
///                     available in `TriangleMesh`.}
///   \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{an instance of a geometric traits class, whose `Compute_x_3`, `Compute_y_3` and
///                           `Compute_z_3` read the points of `vertex_point_map` (converted to `double` with
///                           `CGAL::to_double()`), as in `spherical_parameterize()`}
///     \cgalParamType{a model of `Kernel`}
///     \cgalParamDefault{the kernel of the point type of `vertex_point_map` (`CGAL::Kernel_traits`)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map}
///     \cgalParamDescription{a property map associating to each vertex of `tm` a unique index between `0` and
///                           `num_vertices(tm) - 1`}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::vertex_descriptor`
///                    as key type and an integer type as value type}
///     \cgalParamDefault{an automatically indexed internal map}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
template <typename TriangleMesh, typename VertexSphereMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Spherical_distortion measure_spherical_distortion(const TriangleMesh& tm, VertexSphereMap vsm,
                                                  const NamedParameters& np = CGAL::parameters::default_values())
{
  using internal::Vector3;
  const internal::Mesh_arrays mesh = internal::read_mesh_arrays(tm, CGAL::get_initialized_vertex_index_map(tm, np), np);
  const std::vector<Vector3> x = internal::read_sphere_map(tm, vsm, np);
  auto area = [](const Vector3& a, const Vector3& b, const Vector3& c) {
    return 0.5 * internal::length(internal::cross(b - a, c - a));
  };

  Spherical_distortion distortion;
  const internal::Angle_error angles = internal::angle_error(mesh.points, mesh.triangles, x);
  distortion.mean_angle_error_degrees = angles.mean_degrees;
  distortion.max_angle_error_degrees = angles.max_degrees;
  double mesh_total = 0., sphere_total = 0.;
  std::vector<double> mesh_areas, sphere_areas;
  for(const auto& t : mesh.triangles)
  {
    const Vector3 p[3] = {mesh.points[std::size_t(t[0])], mesh.points[std::size_t(t[1])],
                          mesh.points[std::size_t(t[2])]};
    const Vector3 q[3] = {x[std::size_t(t[0])], x[std::size_t(t[1])], x[std::size_t(t[2])]};
    mesh_areas.push_back(area(p[0], p[1], p[2]));
    sphere_areas.push_back(area(q[0], q[1], q[2]));
    mesh_total += mesh_areas.back();
    sphere_total += sphere_areas.back();
  }
  double sum = 0., sum2 = 0.;
  std::size_t counted = 0;
  for(std::size_t f = 0; f < mesh_areas.size(); ++f)
  {
    if(!(mesh_areas[f] > 0.) || !(sphere_areas[f] > 0.))
      continue;
    const double l = std::log((sphere_areas[f] / sphere_total) / (mesh_areas[f] / mesh_total));
    sum += l;
    sum2 += l * l;
    ++counted;
  }
  if(counted > 0)
  {
    const double mean = sum / static_cast<double>(counted);
    distortion.log_area_ratio_stddev = std::sqrt((std::max)(0., sum2 / static_cast<double>(counted) - mean * mean));
  }
  return distortion;
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_SPHERICAL_DISTORTION_H
