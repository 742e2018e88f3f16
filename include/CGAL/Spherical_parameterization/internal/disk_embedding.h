// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 1b: embed each of the two disks in the unit disk with CGAL's Surface_mesh_parameterization
// (Fixed_border_parameterizer_3 and its Tutte / mean-value / discrete-conformal strategies), the shared loop
// at exactly the same points of the unit circle for both halves.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DISK_EMBEDDING_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DISK_EMBEDDING_H

#include <CGAL/Spherical_parameterization/enum.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/two_disk_partition.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Fixed_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/number_type_config.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

using Half_mesh = CGAL::Surface_mesh<CGAL::Epick::Point_3>;
using Half_vertex = Half_mesh::Vertex_index;

// A border parameterizer that places the border at prescribed points (indexed like the half's vertices),
// so that both halves get exactly the same positions for the shared loop.
class Prescribed_border_parameterizer
{
public:
  using Point_2 = CGAL::Epick::Point_2;
  using halfedge_descriptor = boost::graph_traits<Half_mesh>::halfedge_descriptor;

  explicit Prescribed_border_parameterizer(const std::vector<Point_2>* positions = nullptr) : m_positions(positions) {}

  template <typename VertexUVMap, typename VertexIndexMap, typename VertexParameterizedMap>
  CGAL::Surface_mesh_parameterization::Error_code parameterize(const Half_mesh& mesh, halfedge_descriptor bhd,
                                                               VertexUVMap uvmap, VertexIndexMap,
                                                               VertexParameterizedMap vpmap)
  {
    for(Half_vertex v : vertices_around_face(bhd, mesh))
    {
      put(uvmap, v, (*m_positions)[static_cast<std::size_t>(v)]);
      put(vpmap, v, true);
    }
    return CGAL::Surface_mesh_parameterization::OK;
  }

  bool is_border_convex() const { return true; }

private:
  const std::vector<Point_2>* m_positions;
};

// The Fixed_border strategy for weights given as a table (the user's halfedge weight map): the disk stage then
// uses exactly the weights of the sphere stage.
template <typename SolverTraits>
class Weight_table_parameterizer_3
  : public CGAL::Surface_mesh_parameterization::Fixed_border_parameterizer_3<Half_mesh, Prescribed_border_parameterizer,
                                                                             SolverTraits>
{
  using Base =
      CGAL::Surface_mesh_parameterization::Fixed_border_parameterizer_3<Half_mesh, Prescribed_border_parameterizer,
                                                                        SolverTraits>;

public:
  Weight_table_parameterizer_3(Prescribed_border_parameterizer border, SolverTraits solver, const Sphere_system* system,
                               const std::vector<int>* global_index)
    : Base(border, solver), m_system(system), m_global_index(global_index)
  {}

protected:
  double compute_w_ij(const Half_mesh&, Half_vertex v_i,
                      CGAL::Vertex_around_target_circulator<Half_mesh> v_j) const override
  {
    const std::size_t i = static_cast<std::size_t>((*m_global_index)[static_cast<std::size_t>(v_i)]);
    const int j = (*m_global_index)[static_cast<std::size_t>(*v_j)];
    for(std::size_t k = m_system->offsets[i]; k < m_system->offsets[i + 1]; ++k)
      if(m_system->neighbors[k] == j)
        return m_system->weights[k];
    return 0.;
  }

private:
  const Sphere_system* m_system;
  const std::vector<int>* m_global_index;
};

// Embeds the faces with face_in_disk_a == side in the unit disk; writes uv of their vertices.
template <typename SolverTraits>
bool embed_one_disk(const Mesh_arrays& mesh, const Sphere_system& system, const Two_disk_partition& partition,
                    char side, Weighting weighting, const SolverTraits& solver, std::vector<double>& u,
                    std::vector<double>& v)
{
  namespace SMP = CGAL::Surface_mesh_parameterization;
  using Point_2 = CGAL::Epick::Point_2;
  const std::size_t nv = system.number_of_vertices;

  std::vector<int> local(nv, -1), global_index;
  std::size_t number_of_faces = 0;
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
    if(partition.face_in_disk_a[f] == side)
    {
      ++number_of_faces;
      for(int g : system.triangles[f])
        local[static_cast<std::size_t>(g)] = 0;
    }
  std::size_t number_of_vertices = 0;
  for(int l : local)
    number_of_vertices += (l == 0);
  Half_mesh half;
  // A disk has V + F - 1 edges: reserving them spares the mesh its reallocations.
  half.reserve(static_cast<Half_mesh::size_type>(number_of_vertices),
               static_cast<Half_mesh::size_type>(number_of_vertices + number_of_faces),
               static_cast<Half_mesh::size_type>(number_of_faces));
  global_index.reserve(number_of_vertices);
  for(std::size_t g = 0; g < nv; ++g)
    if(local[g] == 0)
    {
      local[g] = static_cast<int>(global_index.size());
      global_index.push_back(static_cast<int>(g));
      const Vector3& p = mesh.points[g];
      half.add_vertex(CGAL::Epick::Point_3(p.x, p.y, p.z));
    }
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
  {
    if(partition.face_in_disk_a[f] != side)
      continue;
    const auto& t = system.triangles[f];
    if(half.add_face(Half_vertex(static_cast<Half_mesh::size_type>(local[static_cast<std::size_t>(t[0])])),
                     Half_vertex(static_cast<Half_mesh::size_type>(local[static_cast<std::size_t>(t[1])])),
                     Half_vertex(static_cast<Half_mesh::size_type>(local[static_cast<std::size_t>(t[2])])))
       == Half_mesh::null_face())
      return false;
  }

  // The loop at evenly spaced points of the unit circle, counter-clockwise around disk A (as the paper does).
  std::vector<Point_2> border(global_index.size(), Point_2(0, 0));
  const double two_pi = 2. * CGAL_PI;
  const std::size_t m = partition.loop.size();
  for(std::size_t k = 0; k < m; ++k)
  {
    const double angle = two_pi * static_cast<double>(k) / static_cast<double>(m);
    border[static_cast<std::size_t>(local[static_cast<std::size_t>(partition.loop[k])])] =
        Point_2(std::cos(angle), std::sin(angle));
  }

  boost::graph_traits<Half_mesh>::halfedge_descriptor bhd = boost::graph_traits<Half_mesh>::null_halfedge();
  for(auto h : halfedges(half))
    if(is_border(h, half))
    {
      bhd = h;
      break;
    }
  if(bhd == boost::graph_traits<Half_mesh>::null_halfedge())
    return false;

  auto uvmap = half.add_property_map<Half_vertex, Point_2>("v:uv", Point_2(0, 0)).first;
  auto vpmap = half.add_property_map<Half_vertex, bool>("v:parameterized", false).first;
  auto vimap = get(CGAL::vertex_index, half);
  Prescribed_border_parameterizer border_parameterizer(&border);

  SMP::Error_code status = SMP::ERROR_EMPTY_MESH;
  // Degenerate corners (clamped in the sphere system) would make CGAL's own cotangent and mean-value weights
  // divide by zero, or fail its assertions: the disks then take the clamped weights of the sphere stage.
  const Weighting disk_weighting =
      weighting != Weighting::UNIFORM && system.clamped_weights > 0 ? Weighting::USER_MAP : weighting;
  auto run = [&](auto&& parameterizer) { status = parameterizer.parameterize(half, bhd, uvmap, vimap, vpmap); };
  switch(disk_weighting)
  {
  case Weighting::UNIFORM:
    run(SMP::Barycentric_mapping_parameterizer_3<Half_mesh, Prescribed_border_parameterizer, SolverTraits>(
        border_parameterizer, solver));
    break;
  case Weighting::MEAN_VALUE:
    run(SMP::Mean_value_coordinates_parameterizer_3<Half_mesh, Prescribed_border_parameterizer, SolverTraits>(
        border_parameterizer, solver));
    break;
  case Weighting::COTANGENT:
    run(SMP::Discrete_conformal_map_parameterizer_3<Half_mesh, Prescribed_border_parameterizer, SolverTraits>(
        border_parameterizer, solver));
    break;
  case Weighting::USER_MAP:
    run(Weight_table_parameterizer_3<SolverTraits>(border_parameterizer, solver, &system, &global_index));
    break;
  }
  if(status != SMP::OK)
    return false;
  for(Half_vertex hv : vertices(half))
  {
    const Point_2& q = get(uvmap, hv);
    if(!std::isfinite(q.x()) || !std::isfinite(q.y()))
      return false;
    const std::size_t g = static_cast<std::size_t>(global_index[static_cast<std::size_t>(hv)]);
    u[g] = q.x();
    v[g] = q.y();
  }
  return true;
}

// Stage 1c: disk A is the unit disk, disk B is inverted by z -> 1 / conj(z), and the plane goes to the unit sphere
// by the inverse stereographic projection P(u, v) = (2u, 2v, 1 - u^2 - v^2) / (1 + u^2 + v^2). Both are composed
// in closed form for B, P(1 / conj(z)) = (2u, 2v, |z|^2 - 1) / (1 + |z|^2), which needs no division by |z|.
inline Vector3 inverse_stereographic(double u, double v, bool inverted)
{
  const double r2 = u * u + v * v;
  const double z = inverted ? r2 - 1. : 1. - r2;
  return Vector3(2. * u, 2. * v, z) * (1. / (1. + r2));
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_DISK_EMBEDDING_H
