// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The certificate of a spherical map, for any map a user has (not only ours): certify_sphere_map() and
// is_bijective_on_sphere(). The distortion is measured in measure_spherical_distortion.h.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_CERTIFY_SPHERE_MAP_H
#define CGAL_SPHERICAL_PARAMETERIZATION_CERTIFY_SPHERE_MAP_H

#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// What `certify_sphere_map()` found.
struct Sphere_map_certificate
{
  std::size_t number_of_faces = 0; ///< Faces of the mesh.
  std::size_t flipped_faces = 0;   ///< Faces whose spherical triangle is not positively oriented (exact predicate).
  double total_signed_area = 0.;   ///< Sum of the signed areas of the spherical triangles (4 pi for a bijection).
  bool valid_mesh = false; ///< The mesh passes `check_input()` (closed, connected, manifold, oriented, genus 0).
  bool bijective = false;  ///< A valid mesh, no flipped face, a generic point covered once (both exact).
};

/// \ingroup PkgSphericalParameterizationRef
/// Certifies a map `vsm` of the vertices of the closed triangle mesh `tm` to points on (or radially projected
/// onto) the unit sphere: the mesh must pass `check_input()` (the argument below needs a closed, connected,
/// oriented genus-0 surface), every spherical triangle must be positively oriented, `CGAL::orientation(ORIGIN, p, q, r)
/// == POSITIVE` decided exactly, a generic point of the sphere must be covered by exactly one triangle, also decided
/// exactly (with every triangle positive that count is the degree of the map, so this excludes multiple
/// coverings). The sum of the signed spherical areas is reported (4 pi on a bijection, up to the rounding of
/// nearly degenerate triangles) but does not decide.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `VertexListGraph`.
/// \tparam VertexSphereMap a model of `ReadablePropertyMap` from vertices to points with `x()`, `y()`, `z()`.
/// \tparam NamedParameters a sequence of named parameters.
/// \param tm the mesh.
/// \param vsm the map to certify; the exact orientation test runs on its coordinates converted to `double`.
/// \param np optional named parameters among the ones listed below.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm` (only the input checks read
///                           them: the orientations are those of `vsm`)}
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
Sphere_map_certificate certify_sphere_map(const TriangleMesh& tm, VertexSphereMap vsm,
                                          const NamedParameters& np = CGAL::parameters::default_values())
{
  const internal::Mesh_arrays mesh = internal::read_mesh_arrays(tm, CGAL::get_initialized_vertex_index_map(tm, np), np);
  std::vector<internal::Vector3> x = internal::read_sphere_map(tm, vsm, np);
  Sphere_map_certificate certificate;
  certificate.number_of_faces = mesh.polygons.size();
  if(mesh.triangles.size() != mesh.polygons.size())
  {
    certificate.flipped_faces = mesh.polygons.size();
    return certificate;
  }
  // Orientation and area prove a bijection only for a closed, connected, oriented genus-0 surface.
  certificate.valid_mesh = internal::check_mesh_arrays(mesh).status == Error_code::OK;
  // Orientation does not depend on the radius; the areas are those of the radially projected triangles.
  std::vector<internal::Vector3> unit(x.size());
  for(std::size_t i = 0; i < x.size(); ++i)
  {
    const double r = internal::length(x[i]);
    unit[i] = r > 0. ? x[i] * (1. / r) : x[i];
  }
  const internal::Sphere_certificate on_sphere = internal::certify(mesh.triangles, x, &unit);
  certificate.flipped_faces = on_sphere.flipped_faces;
  certificate.total_signed_area = on_sphere.total_signed_area;
  certificate.bijective = certificate.valid_mesh && on_sphere.bijective;
  return certificate;
}

/// \ingroup PkgSphericalParameterizationRef
/// `true` iff `certify_sphere_map(tm, vsm, np).bijective`; same parameters as `certify_sphere_map()`.
/// \param tm the mesh.
/// \param vsm the map to certify.
/// \param np optional named parameters: `vertex_point_map`, `geom_traits`, `vertex_index_map`.
template <typename TriangleMesh, typename VertexSphereMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
bool is_bijective_on_sphere(const TriangleMesh& tm, VertexSphereMap vsm,
                            const NamedParameters& np = CGAL::parameters::default_values())
{
  return certify_sphere_map(tm, vsm, np).bijective;
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_CERTIFY_SPHERE_MAP_H
