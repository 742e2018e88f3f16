// The input mesh read once into flat arrays: every later stage works on these, never on the FaceGraph.
// Faces keep the order of faces(tm) and each face starts at its smallest vertex index (orientation kept),
// so that Surface_mesh, Polyhedron_3 or any FaceGraph with the same vertex and face order give the same arrays.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_ARRAYS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_ARRAYS_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Mesh_arrays {
  std::vector<Vector3> points;                 // indexed by the vertex index map
  std::vector<std::vector<int>> polygons;      // as read (any degree), one per face
  std::vector<std::array<int, 3>> triangles;   // filled when every polygon is a triangle
};

// Rotates a triangle so that it starts at its smallest index: a canonical form that keeps the orientation.
inline std::array<int, 3> canonical_triangle(int a, int b, int c)
{
  if(b < a && b < c) return {b, c, a};
  if(c < a && c < b) return {c, a, b};
  return {a, b, c};
}

// Fills `triangles` from `polygons` when they are all triangles; returns false otherwise.
inline bool make_triangles(Mesh_arrays& mesh)
{
  mesh.triangles.clear();
  mesh.triangles.reserve(mesh.polygons.size());
  for(const std::vector<int>& p : mesh.polygons) {
    if(p.size() != 3) { mesh.triangles.clear(); return false; }
    mesh.triangles.push_back(canonical_triangle(p[0], p[1], p[2]));
  }
  return true;
}

// Reads the coordinates through `coordinates(p, x, y, z)` (the geometric traits' functors, by default p.x()...).
template <typename FaceGraph, typename VertexPointMap, typename VertexIndexMap, typename Coordinates>
Mesh_arrays read_face_graph(const FaceGraph& tm, VertexPointMap vpm, VertexIndexMap vim, const Coordinates& coordinates)
{
  Mesh_arrays mesh;
  const std::size_t nv = static_cast<std::size_t>(num_vertices(tm));
  mesh.points.resize(nv);
  for(auto v : vertices(tm)) {
    double x, y, z;
    coordinates(get(vpm, v), x, y, z);
    mesh.points[static_cast<std::size_t>(get(vim, v))] = Vector3(x, y, z);
  }
  mesh.polygons.reserve(static_cast<std::size_t>(num_faces(tm)));
  for(auto f : faces(tm)) {
    std::vector<int> polygon;
    for(auto v : vertices_around_face(halfedge(f, tm), tm))
      polygon.push_back(static_cast<int>(get(vim, v)));
    mesh.polygons.push_back(std::move(polygon));
  }
  make_triangles(mesh);
  return mesh;
}

template <typename FaceGraph, typename VertexPointMap, typename VertexIndexMap>
Mesh_arrays read_face_graph(const FaceGraph& tm, VertexPointMap vpm, VertexIndexMap vim)
{
  return read_face_graph(tm, vpm, vim, [](const auto& p, double& x, double& y, double& z) {
    x = CGAL::to_double(p.x());
    y = CGAL::to_double(p.y());
    z = CGAL::to_double(p.z());
  });
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_ARRAYS_H
