// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The input mesh read once into flat arrays: every later stage works on these, never on the FaceGraph.
// Faces keep the order of faces(tm) and each face starts at its smallest vertex index (orientation kept),
// so that Surface_mesh, Polyhedron_3 or any FaceGraph with the same vertex and face order give the same arrays
// (and, after renumber_for_locality(), the same renumbered arrays).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_ARRAYS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_ARRAYS_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Mesh_arrays
{
  std::vector<Vector3> points;               // indexed by the vertex index map
  std::vector<std::vector<int>> polygons;    // as read (any degree), one per face: what the input checks read
  std::vector<std::array<int, 3>> triangles; // filled when every polygon is a triangle (spherical_parameterize()
                                             // moves them into its Sphere_system: they are stored once)
  std::vector<int> input_index;              // after renumber_for_locality(): the input's index of each vertex
};

// The input's index of vertex i (for messages and for the output).
inline std::size_t input_vertex_index(const Mesh_arrays& mesh, std::size_t i)
{
  return mesh.input_index.empty() ? i : static_cast<std::size_t>(mesh.input_index[i]);
}

// Rotates a triangle so that it starts at its smallest index: a canonical form that keeps the orientation.
inline std::array<int, 3> canonical_triangle(int a, int b, int c)
{
  if(b < a && b < c)
    return {b, c, a};
  if(c < a && c < b)
    return {c, a, b};
  return {a, b, c};
}

// Fills `triangles` from `polygons` when they are all triangles; returns false otherwise.
inline bool make_triangles(Mesh_arrays& mesh)
{
  mesh.triangles.clear();
  mesh.triangles.reserve(mesh.polygons.size());
  for(const std::vector<int>& p : mesh.polygons)
  {
    if(p.size() != 3)
    {
      mesh.triangles.clear();
      return false;
    }
    mesh.triangles.push_back(canonical_triangle(p[0], p[1], p[2]));
  }
  return true;
}

// Spreads the 21 low bits of v to every third bit (bit b goes to bit 3 b).
inline std::uint64_t spread_bits_by_three(std::uint64_t v)
{
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// Renumbers the vertices of a triangle mesh along a Morton (Z-order) curve through their points and sorts the faces
// by their first vertex, so that the vertices of a face, and neighbouring faces, sit close together in memory. Every
// later stage (disk systems and AMG, sphere iterations, certificate) walks these arrays; in the input's order they
// can be far apart (subdivided or shuffled files), which costs time on large meshes (the manual's Performance
// section has the figures). The keys are integers, the order is deterministic. `input_index` keeps the way back.
// `polygons`, in the input's numbering and read by nothing after the input checks, are released, not renumbered.
//
// Only meshes of `minimum_vertices` or more are renumbered: below, the arrays fit in the caches anyway, and a new
// order only changes the iterates (METIS' separator, the Gauss-Seidel order), and with them the outcome of the
// hardest cases: renumbering every mesh turned 5 of the test corpus' hard cases from OK to NOT_CONVERGED
// (and one the other way).
constexpr std::size_t renumbering_minimum_vertices = 100000;

inline void renumber_for_locality(Mesh_arrays& mesh, std::size_t minimum_vertices = renumbering_minimum_vertices)
{
  const std::size_t n = mesh.points.size();
  if(n == 0 || n < minimum_vertices)
    return;
  std::array<double, 3> low{mesh.points[0].x, mesh.points[0].y, mesh.points[0].z}, high = low;
  for(const Vector3& p : mesh.points)
    for(int d = 0; d < 3; ++d)
    {
      low[d] = std::min(low[d], p[d]);
      high[d] = std::max(high[d], p[d]);
    }
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    std::uint64_t key = 0;
    for(int d = 0; d < 3; ++d)
    {
      const double extent = high[d] - low[d];
      const double cell = extent > 0. ? (mesh.points[i][d] - low[d]) / extent * 2097151. : 0.;
      key |= spread_bits_by_three(static_cast<std::uint64_t>(std::min(std::max(cell, 0.), 2097151.))) << d;
    }
    keyed[i] = {key, static_cast<int>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(n);
  for(std::size_t k = 0; k < n; ++k)
    order[k] = keyed[k].second;
  std::vector<std::pair<std::uint64_t, int>>().swap(keyed);
  const std::vector<Vector3> points = mesh.points;
  std::vector<int> rank(n);
  for(std::size_t k = 0; k < n; ++k)
  {
    rank[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
    mesh.points[k] = points[static_cast<std::size_t>(order[k])];
  }
  for(std::array<int, 3>& t : mesh.triangles)
    t = canonical_triangle(rank[static_cast<std::size_t>(t[0])], rank[static_cast<std::size_t>(t[1])],
                           rank[static_cast<std::size_t>(t[2])]);
  std::stable_sort(mesh.triangles.begin(), mesh.triangles.end(),
                   [](const std::array<int, 3>& a, const std::array<int, 3>& b) { return a[0] < b[0]; });
  std::vector<std::vector<int>>().swap(mesh.polygons);
  mesh.input_index = std::move(order);
}

// Reads the coordinates through `coordinates(p, x, y, z)` (the geometric traits' functors, by default p.x()...).
template <typename FaceGraph, typename VertexPointMap, typename VertexIndexMap, typename Coordinates>
Mesh_arrays read_face_graph(const FaceGraph& tm, VertexPointMap vpm, VertexIndexMap vim, const Coordinates& coordinates)
{
  Mesh_arrays mesh;
  const std::size_t nv = static_cast<std::size_t>(num_vertices(tm));
  mesh.points.resize(nv);
  for(auto v : vertices(tm))
  {
    double x, y, z;
    coordinates(get(vpm, v), x, y, z);
    mesh.points[static_cast<std::size_t>(get(vim, v))] = Vector3(x, y, z);
  }
  mesh.polygons.reserve(static_cast<std::size_t>(num_faces(tm)));
  for(auto f : faces(tm))
  {
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
