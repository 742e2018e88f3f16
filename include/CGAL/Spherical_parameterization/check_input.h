// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Is a mesh a valid input (closed, connected, manifold, oriented, genus-0 triangle mesh)?

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_CHECK_INPUT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_CHECK_INPUT_H

#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Union_find.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The verdict of `check_input()`: an error code and a message with the figures (how many loops, the genus...).
struct Input_check
{
  Error_code status = Error_code::OK; ///< `Error_code::OK`, or the code of the first defect found.
  std::string message;                ///< `get_error_message(status)` with the figures of the defect.
  /// `true` when `status == Error_code::OK`.
  explicit operator bool() const { return status == Error_code::OK; }
};

namespace internal {

// CGAL::Union_find of the indices 0 .. n-1, with one handle per index.
using Index_sets = CGAL::Union_find<std::size_t>;

inline std::vector<Index_sets::handle> make_singletons(Index_sets& sets, std::size_t n)
{
  std::vector<Index_sets::handle> handles;
  handles.reserve(n);
  for(std::size_t i = 0; i < n; ++i)
    handles.push_back(sets.make_set(i));
  return handles;
}

inline Input_check make_check(Error_code code, const std::string& details = std::string())
{
  Input_check check;
  check.status = code;
  check.message = get_error_message(code);
  if(!details.empty())
    check.message += ": " + details;
  return check;
}

// All checks on the polygon list, in an order that names the first real defect:
// a pinched vertex passes the edge checks, so it is looked for before the Euler characteristic.
inline Input_check check_mesh_arrays(const Mesh_arrays& mesh)
{
  const std::size_t nv = mesh.points.size();
  const std::size_t nf = mesh.polygons.size();
  if(nf == 0)
    return make_check(Error_code::EMPTY_MESH);

  for(std::size_t v = 0; v < nv; ++v)
    if(!is_finite(mesh.points[v]))
      return make_check(Error_code::NON_FINITE_COORDINATES, "vertex " + std::to_string(v));

  std::size_t non_triangles = 0;
  for(const auto& p : mesh.polygons)
    if(p.size() != 3)
      ++non_triangles;
  if(non_triangles > 0)
    return make_check(Error_code::NOT_TRIANGLE_MESH, std::to_string(non_triangles) + " of " + std::to_string(nf)
                                                         + " faces have more or fewer than 3 vertices");

  std::size_t repeated = 0;
  for(const auto& p : mesh.polygons)
  {
    for(int i : p)
      if(i < 0 || static_cast<std::size_t>(i) >= nv)
        return make_check(Error_code::DEGENERATE_FACE, "a face refers to a vertex that does not exist (index "
                                                           + (i < 0 ? std::string("out of range") : std::to_string(i))
                                                           + ")");
    if(p[0] == p[1] || p[1] == p[2] || p[2] == p[0])
      ++repeated;
  }
  if(repeated > 0)
    return make_check(Error_code::DEGENERATE_FACE, std::to_string(repeated) + " faces repeat a vertex");

  // Undirected edges with the direction in which each face uses them, bucketed by their smaller vertex (a
  // counting sort: sorting all 3 nf uses at once took most of the time of these checks on large meshes).
  struct Edge_use
  {
    int other;
    int face;
    bool forward;
  };
  std::vector<std::size_t> bucket(nv + 1, 0);
  for(std::size_t f = 0; f < nf; ++f)
  {
    const auto& p = mesh.polygons[f];
    for(int k = 0; k < 3; ++k)
      ++bucket[static_cast<std::size_t>(std::min(p[k], p[(k + 1) % 3])) + 1];
  }
  std::partial_sum(bucket.begin(), bucket.end(), bucket.begin());
  std::vector<Edge_use> uses(3 * nf);
  {
    std::vector<std::size_t> fill(bucket.begin(), bucket.end() - 1);
    for(std::size_t f = 0; f < nf; ++f)
    {
      const auto& p = mesh.polygons[f];
      for(int k = 0; k < 3; ++k)
      {
        const int a = p[k], b = p[(k + 1) % 3];
        uses[fill[static_cast<std::size_t>(std::min(a, b))]++] = {std::max(a, b), static_cast<int>(f), a < b};
      }
    }
  }

  std::size_t number_of_edges = 0, border_edges = 0, non_manifold_edges = 0, misoriented_edges = 0;
  Index_sets border_loops;
  const std::vector<Index_sets::handle> border_vertex = make_singletons(border_loops, nv);
  std::vector<char> on_border(nv, 0);
  for(std::size_t a = 0; a < nv; ++a)
  {
    const auto first = uses.begin() + static_cast<std::ptrdiff_t>(bucket[a]);
    const auto last = uses.begin() + static_cast<std::ptrdiff_t>(bucket[a + 1]);
    std::sort(first, last, [](const Edge_use& l, const Edge_use& r) {
      return l.other < r.other || (l.other == r.other && l.face < r.face);
    });
    for(auto i = first; i != last;)
    {
      auto j = i;
      while(j != last && j->other == i->other)
        ++j;
      ++number_of_edges;
      const auto count = j - i;
      if(count == 1)
      {
        ++border_edges;
        const std::size_t b = static_cast<std::size_t>(i->other);
        border_loops.unify_sets(border_vertex[a], border_vertex[b]);
        on_border[a] = on_border[b] = 1;
      }
      else if(count > 2)
      {
        ++non_manifold_edges;
      }
      else if(i->forward == (i + 1)->forward)
      {
        ++misoriented_edges;
      }
      i = j;
    }
  }
  std::vector<Edge_use>().swap(uses);

  if(non_manifold_edges > 0)
    return make_check(Error_code::NON_MANIFOLD_EDGE,
                      std::to_string(non_manifold_edges) + " edges are shared by more than two faces");
  if(border_edges > 0)
  {
    std::size_t loops = 0;
    for(std::size_t v = 0; v < nv; ++v)
      if(on_border[v] && border_loops.find(border_vertex[v]) == border_vertex[v])
        ++loops;
    return make_check(Error_code::HAS_BORDER, std::to_string(border_edges) + " boundary edges in "
                                                  + std::to_string(loops) + " boundary loop(s)");
  }

  // Faces around each vertex: the link (pairs of neighbours joined by a face) must be one cycle.
  std::vector<std::size_t> offsets(nv + 1, 0);
  for(const auto& p : mesh.polygons)
    for(int i : p)
      ++offsets[static_cast<std::size_t>(i) + 1];
  std::size_t isolated = 0;
  for(std::size_t v = 0; v < nv; ++v)
    if(offsets[v + 1] == 0)
      ++isolated;
  if(isolated > 0)
    return make_check(Error_code::ISOLATED_VERTEX, std::to_string(isolated) + " vertices belong to no face");
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<std::pair<int, int>> link(offsets[nv]);
  {
    std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
    for(const auto& p : mesh.polygons)
      for(int k = 0; k < 3; ++k)
        link[fill[static_cast<std::size_t>(p[k])]++] = {p[(k + 1) % 3], p[(k + 2) % 3]};
  }
  // The link of v is one cycle when a walk along it, from one link edge to the next through their shared end,
  // comes back only after visiting every link edge. Every neighbour is an end of exactly two link edges here (each
  // edge of the mesh has two faces, checked above), so the ends sorted by vertex come in pairs, and the link edge
  // beyond an end is the one at its partner's position.
  std::size_t pinched = 0;
  std::vector<std::pair<int, std::size_t>> ends; // (neighbour, 2 * link edge + which end), sorted
  std::vector<std::size_t> position_of_end;      // where each end of each link edge landed in `ends`
  for(std::size_t v = 0; v < nv; ++v)
  {
    const std::size_t degree = offsets[v + 1] - offsets[v];
    ends.clear();
    for(std::size_t k = 0; k < degree; ++k)
    {
      ends.emplace_back(link[offsets[v] + k].first, 2 * k);
      ends.emplace_back(link[offsets[v] + k].second, 2 * k + 1);
    }
    std::sort(ends.begin(), ends.end());
    position_of_end.resize(2 * degree);
    bool paired = true;
    for(std::size_t p = 0; p < ends.size(); ++p)
    {
      position_of_end[ends[p].second] = p;
      paired = paired && ends[p].first == ends[p ^ 1].first;
    }
    std::size_t visited = 0;
    if(paired)
    {
      std::size_t end = 1; // leave link edge 0 through its second end
      do
      {
        ++visited;
        const std::size_t entered = ends[position_of_end[end] ^ 1].second; // the same vertex on the next link edge
        end = entered ^ 1;                                                 // leave that edge through its other end
      } while(end / 2 != 0 && visited <= degree);
    }
    if(visited != degree)
      ++pinched;
  }
  if(pinched > 0)
    return make_check(Error_code::NON_MANIFOLD_VERTEX,
                      std::to_string(pinched) + " vertices have more than one fan of faces");

  if(misoriented_edges > 0)
    return make_check(Error_code::INCONSISTENT_ORIENTATION,
                      std::to_string(misoriented_edges)
                          + " edges are traversed in the same direction by their two faces");

  Index_sets components;
  const std::vector<Index_sets::handle> vertex = make_singletons(components, nv);
  for(const auto& p : mesh.polygons)
    for(int k = 0; k < 3; ++k)
      components.unify_sets(vertex[static_cast<std::size_t>(p[k])], vertex[static_cast<std::size_t>(p[(k + 1) % 3])]);
  const std::size_t number_of_components = components.number_of_sets();
  if(number_of_components > 1)
    return make_check(Error_code::MULTIPLE_COMPONENTS, std::to_string(number_of_components) + " connected components");

  const long long euler =
      static_cast<long long>(nv) - static_cast<long long>(number_of_edges) + static_cast<long long>(nf);
  if(euler != 2)
    return make_check(Error_code::GENUS_NOT_ZERO, "genus " + std::to_string((2 - euler) / 2) + " (Euler characteristic "
                                                      + std::to_string(euler) + ")");
  return make_check(Error_code::OK);
}

// The mesh as arrays, its points read the same way by every public function: through the `vertex_point_map`
// named parameter and the coordinate functors of `geom_traits`, converted to double (so that points of any
// kernel, exact ones too, are accepted), stored at the indices of `vim`.
template <typename TriangleMesh, typename VertexIndexMap, typename NamedParameters>
Mesh_arrays read_mesh_arrays(const TriangleMesh& tm, VertexIndexMap vim, const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                              get_const_property_map(CGAL::vertex_point, tm));
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  const auto compute_x = gt.compute_x_3_object();
  const auto compute_y = gt.compute_y_3_object();
  const auto compute_z = gt.compute_z_3_object();
  return read_face_graph(tm, vpm, vim, [&](const auto& p, double& x, double& y, double& z) {
    x = CGAL::to_double(compute_x(p));
    y = CGAL::to_double(compute_y(p));
    z = CGAL::to_double(compute_z(p));
  });
}

// The map `vsm` of a user (the coordinates as double), stored at the indices of the `vertex_index_map` named
// parameter, as read_mesh_arrays() stores the points.
template <typename TriangleMesh, typename VertexSphereMap, typename NamedParameters>
std::vector<Vector3> read_sphere_map(const TriangleMesh& tm, VertexSphereMap vsm, const NamedParameters& np)
{
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  std::vector<Vector3> x(static_cast<std::size_t>(num_vertices(tm)));
  for(auto v : vertices(tm))
  {
    const auto& p = get(vsm, v);
    x[static_cast<std::size_t>(get(vim, v))] =
        Vector3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  return x;
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Checks that `tm` can be mapped onto the sphere: it has faces, all triangles, no face repeats a vertex, all
/// coordinates are finite, every vertex belongs to a face, it is closed, edge- and vertex-manifold, consistently
/// oriented, connected and of genus 0. Returns the first defect found with its figures.
///
/// \tparam TriangleMesh a model of `FaceListGraph` and `VertexListGraph`.
/// \tparam NamedParameters a sequence of named parameters.
/// \param tm the mesh, not modified.
/// \param np optional named parameters among the ones listed below.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::vertex_descriptor`
///                    as key type and `Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///     \cgalParamExtra{If this parameter is omitted, an internal property map for `CGAL::vertex_point_t` must be
///                     available in `TriangleMesh`.}
///   \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{an instance of a geometric traits class, whose `Compute_x_3`, `Compute_y_3` and
///                           `Compute_z_3` read the points (converted to `double` with `CGAL::to_double()`), as in
///                           `spherical_parameterize()`}
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
template <typename TriangleMesh, typename NamedParameters = CGAL::parameters::Default_named_parameters>
Input_check check_input(const TriangleMesh& tm, const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::check_mesh_arrays(
      internal::read_mesh_arrays(tm, CGAL::get_initialized_vertex_index_map(tm, np), np));
}

/// \ingroup PkgSphericalParameterizationRef
/// The same checks on a polygon soup (points and faces as index lists), such as the
/// output of `CGAL::IO::read_polygon_soup()`: soups can hold what a halfedge data structure cannot (non-manifold edges).
///
/// \tparam PointRange a range of points with `x()`, `y()` and `z()` convertible by `CGAL::to_double()`.
/// \tparam PolygonRange a range of ranges of integral indices into `points`.
/// \param points the vertices.
/// \param polygons the faces, each as a list of indices into `points`.
template <typename PointRange, typename PolygonRange>
Input_check check_polygon_soup(const PointRange& points, const PolygonRange& polygons)
{
  internal::Mesh_arrays mesh;
  mesh.points.reserve(points.size());
  for(const auto& p : points)
    mesh.points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  for(const auto& polygon : polygons)
  {
    std::vector<int> face;
    for(const auto i : polygon)
    {
      // An index past the points (or past int) must not wrap around onto an existing vertex.
      const long long index = static_cast<long long>(i);
      face.push_back(index >= 0 && static_cast<unsigned long long>(index) < points.size() ? static_cast<int>(index)
                                                                                          : -1);
    }
    mesh.polygons.push_back(std::move(face));
  }
  return internal::check_mesh_arrays(mesh);
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_CHECK_INPUT_H
