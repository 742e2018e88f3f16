// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Arm tips whose balanced map lies below double precision.
//
// A long thin arm (length over radius above about 35: the arms of marching-cubes surfaces) is a tube, and a balanced
// map of a tube shrinks it by a constant factor per ring of vertices (about exp(-2 pi / k) for k vertices a ring with
// Tutte's weights): its tip ends at spherical edges of 1e-20 and below. Rounded to double, such vertices coincide and
// their triangles degenerate, so that balanced map has no bijective representation in double at all: Newton reaches
// it (Res 1e-19) with non-positive faces at the tips, and no solver can do better with these equations.
//
// Where that happens, the tip (the vertices around the non-positive faces whose neighbourhoods are below
// Solver_tuning::tip_scale: the end of the arm) is solved with other weights, which fall by a constant ratio per ring
// of the tip (rings: the distance in edges from the rest of the mesh), from the third ring in. The weights stay
// positive and symmetric, so the map of the tip is a convex-combination map (Tutte, Floater: no fold in exact
// arithmetic) and the Newton and multigrid machinery applies unchanged. With weights that weaken towards the end of
// the tube, each vertex follows its outer neighbours more than its inner ones, and the tube's shrinking per ring
// drops from about exp(-2 pi / k) (k vertices a ring) to about (2 pi / k)^2 / |log ratio|, so the tip stays orders of
// magnitude above rounding. Weighting only the edges along the rings less was tried first: on marching-tetrahedra
// arms a third of a ring's edges join two rings, and the tips still ended at 3e-17.
// Every other vertex keeps its equation exactly (an edge with one end outside the tip keeps its weight): the rest of
// the mesh is balanced and tested as before, and the tip vertices, whose balanced positions double cannot hold, are
// counted (Result::regularized_tip_vertices, among Result::vertices_below_precision), not tested.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TIP_REGULARIZATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TIP_REGULARIZATION_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// The largest region (distance from its centre) solved as flat by place_tips(): the equations change by about its
// square, 1e-8 at most.
constexpr double max_flat_region = 1e-4;

// The weighted mean chord of vertex i's edges: the size of its neighbourhood on the sphere.
inline double mean_chord(const Sphere_system& system, const std::vector<Vector3>& x, std::size_t i)
{
  double chords = 0., weights = 0.;
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
  {
    const double w = std::abs(system.weights[k]);
    chords += w * length(x[static_cast<std::size_t>(system.neighbors[k])] - x[i]);
    weights += w;
  }
  return weights > 0. ? chords / weights : 0.;
}

// The tips to regularize on a balanced map `x` with non-positive faces: a flag per vertex, or an empty vector when
// some non-positive face has no vertex below `tip_scale` (then the folds are not a matter of precision) or a tip
// vertex has a weight that is not positive.
inline std::vector<char> unresolvable_tips(const Sphere_system& system, const std::vector<Vector3>& x, double tip_scale)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<double> scale(n);
  for(std::size_t i = 0; i < n; ++i)
    scale[i] = mean_chord(system, x, i);
  std::vector<char> tip(n, 0);
  std::vector<int> stack;
  bool any = false;
  for(const auto& t : system.triangles)
  {
    if(is_positive(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                   x[static_cast<std::size_t>(t[2])]))
      continue;
    bool small = false;
    for(int v : t)
      small = small || scale[static_cast<std::size_t>(v)] < tip_scale;
    if(!small)
      return {};
    any = true;
    for(int v : t)
      if(!tip[static_cast<std::size_t>(v)] && scale[static_cast<std::size_t>(v)] < tip_scale)
      {
        tip[static_cast<std::size_t>(v)] = 1;
        stack.push_back(v);
      }
  }
  if(!any)
    return {};
  // The whole region below tip_scale around them.
  while(!stack.empty())
  {
    const std::size_t i = static_cast<std::size_t>(stack.back());
    stack.pop_back();
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const int j = system.neighbors[k];
      if(!tip[static_cast<std::size_t>(j)] && scale[static_cast<std::size_t>(j)] < tip_scale)
      {
        tip[static_cast<std::size_t>(j)] = 1;
        stack.push_back(j);
      }
    }
  }
  // The regularized map of a tip is a convex-combination map only when its weights are positive (cotangent weights
  // may not be): elsewhere the folds are left to the other fallbacks.
  for(std::size_t i = 0; i < n; ++i)
    if(tip[i])
      for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
        if(!(system.weights[k] > 0.))
          return {};
  return tip;
}

// The system with the weights inside the tips changed (see the file's comment): an edge between two tip vertices on
// rings a and b is scaled by ratio^max(0, (a + b) / 2 - 2). Symmetric weights stay symmetric.
inline Sphere_system regularize_tips(const Sphere_system& system, const std::vector<char>& tip, double ratio)
{
  const std::size_t n = system.number_of_vertices;
  // Rings: breadth-first distance from the vertices outside the tips.
  std::vector<std::size_t> ring(n, 0);
  std::vector<std::size_t> front, next;
  std::vector<char> reached(n, 0);
  for(std::size_t i = 0; i < n; ++i)
    if(!tip[i])
    {
      reached[i] = 1;
      front.push_back(i);
    }
  for(std::size_t level = 1; !front.empty(); ++level)
  {
    next.clear();
    for(std::size_t i : front)
      for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
        if(!reached[j])
        {
          reached[j] = 1;
          ring[j] = level;
          next.push_back(j);
        }
      }
    front.swap(next);
  }
  Sphere_system regularized = system;
  for(std::size_t i = 0; i < n; ++i)
  {
    if(!tip[i])
      continue;
    double sum = 0.;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
      double raw = system.weights[k] * system.row_sums[i];
      if(tip[j])
        raw *= std::pow(ratio, std::max(0., 0.5 * static_cast<double>(ring[i] + ring[j]) - 2.));
      regularized.weights[k] = raw;
      sum += raw;
    }
    regularized.row_sums[i] = sum;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      regularized.weights[k] /= sum;
  }
  regularized.regularized_tips.clear(); // the regularized system tests its tips under their own weights
  regularized.signed_laplacian_semidefinite = false; // edges scaled one by one: no longer the faces' cotangent forms
  return regularized;
}

// Places the vertices of each tip, and of the band around it whose neighbourhoods are below `band_scale`, at the
// balance point of the regularized weights, every vertex farther out kept: a linear problem in the tangent plane at
// the tip (flat at these scales: the projection changes the equations by about the square of the region's size), in
// coordinates relative to its centre, so that offsets of 1e-13 keep their digits. Newton cannot do this from the
// folded map: the forces there are absolutely tiny (1e-17), far below what its linear solves and line searches
// resolve. The band takes up the change of the tips: a perturbation at the end of a tube fades along it faster than
// the tube widens, so the vertices beyond the band stay balanced. False if a region is too large to be flat or a
// system could not be solved (x unchanged).
inline bool place_tips(const Sphere_system& regularized, const std::vector<char>& tip, double band_scale,
                       std::vector<Vector3>& x)
{
  const std::size_t n = regularized.number_of_vertices;
  std::vector<char> in_region(n, 0);
  for(std::size_t i = 0; i < n; ++i)
    in_region[i] = tip[i] || mean_chord(regularized, x, i) < band_scale;
  std::vector<char> visited(n, 0);
  std::vector<long> local(n, -1);
  std::vector<std::size_t> members, stack;
  std::vector<Vector3> placed = x;
  for(std::size_t seed = 0; seed < n; ++seed)
  {
    if(!tip[seed] || visited[seed])
      continue;
    // The region: the tip and the vertices below band_scale connected to it.
    members.clear();
    stack.assign(1, seed);
    visited[seed] = 1;
    while(!stack.empty())
    {
      const std::size_t i = stack.back();
      stack.pop_back();
      local[i] = static_cast<long>(members.size());
      members.push_back(i);
      for(std::size_t k = regularized.offsets[i]; k < regularized.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(regularized.neighbors[k]);
        if(in_region[j] && !visited[j])
        {
          visited[j] = 1;
          stack.push_back(j);
        }
      }
    }
    // The frame: the tangent plane at the normalized mean of the region's neighbours outside it.
    Vector3 centre;
    for(std::size_t i : members)
      for(std::size_t k = regularized.offsets[i]; k < regularized.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(regularized.neighbors[k]);
        if(!visited[j])
          centre += x[j];
      }
    if(!(length(centre) > 0.))
      return false;
    centre = centre * (1. / length(centre));
    double extent = 0.;
    for(std::size_t i : members)
      extent = std::max(extent, length(x[i] - centre));
    if(!(extent < max_flat_region))
      return false;
    Vector3 t1, t2;
    tangent_frame(centre, t1, t2);
    const std::size_t m = members.size();
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), 2);
    for(std::size_t r = 0; r < m; ++r)
    {
      const std::size_t i = members[r];
      double diagonal = 0.;
      for(std::size_t k = regularized.offsets[i]; k < regularized.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(regularized.neighbors[k]);
        const double w = regularized.weights[k] * regularized.row_sums[i];
        diagonal += w;
        if(visited[j])
          entries.emplace_back(static_cast<int>(r), static_cast<int>(local[j]), -w);
        else
        {
          const Vector3 offset = x[j] - centre;
          rhs(static_cast<Eigen::Index>(r), 0) += w * dot(offset, t1);
          rhs(static_cast<Eigen::Index>(r), 1) += w * dot(offset, t2);
        }
      }
      entries.emplace_back(static_cast<int>(r), static_cast<int>(r), diagonal);
    }
    Eigen::SparseMatrix<double> laplacian(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
    laplacian.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
    if(solver.info() != Eigen::Success)
      return false;
    const Eigen::MatrixXd u = solver.solve(rhs);
    if(solver.info() != Eigen::Success || !u.allFinite())
      return false;
    for(std::size_t r = 0; r < m; ++r)
    {
      const Vector3 y = centre + u(static_cast<Eigen::Index>(r), 0) * t1 + u(static_cast<Eigen::Index>(r), 1) * t2;
      placed[members[r]] = y * (1. / length(y));
    }
  }
  x.swap(placed);
  return true;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TIP_REGULARIZATION_H
