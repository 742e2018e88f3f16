// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A combinatorial proof that a triangulated sphere is not inscribable, when a simple one exists; and, for the
// tetrahedron, the exact condition on the weights for a balanced bijective map.
//
// The paper (Section 2) notes that for a non-inscribable connectivity the balance equations have no bijective
// solution for any positive weights: the iterations can only stall. Rivin's characterization gives a cheap
// certificate: an inscribable polyhedron admits edge weights in (0, 1/2] that sum to 1 around every vertex,
// so the weights sum to n/2 in all, and an independent set S of vertices collects |S| of it on its own edges.
// Hence |S| <= n/2, with equality only if no edge joins two vertices outside S (those edges would get weight 0).
// A greedy independent set, smallest degrees first, finds such an S on the usual culprits: the triakis
// tetrahedron and every mesh whose faces were split at their centres (the centres outnumber the rest).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INSCRIBABILITY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INSCRIBABILITY_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Inscribability_check
{
  bool proven_not_inscribable = false;
  std::size_t independent_set_size = 0; // |S| of the greedy independent set
  bool edge_outside_set = false;        // an edge joins two vertices outside S
};

inline Inscribability_check check_inscribability(const Sphere_system& system)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return system.degree(a) < system.degree(b); });
  std::vector<char> in_set(n, 0), blocked(n, 0);
  Inscribability_check check;
  for(std::size_t v : order)
  {
    if(blocked[v])
      continue;
    in_set[v] = 1;
    ++check.independent_set_size;
    for(std::size_t k = system.offsets[v]; k < system.offsets[v + 1]; ++k)
      blocked[std::size_t(system.neighbors[k])] = 1;
  }
  for(std::size_t v = 0; v < n && !check.edge_outside_set; ++v)
  {
    if(in_set[v])
      continue;
    for(std::size_t k = system.offsets[v]; k < system.offsets[v + 1]; ++k)
      if(!in_set[std::size_t(system.neighbors[k])])
      {
        check.edge_outside_set = true;
        break;
      }
  }
  const std::size_t twice = 2 * check.independent_set_size;
  check.proven_not_inscribable = twice > n || (twice == n && check.edge_outside_set);
  return check;
}

// The tetrahedron (the one closed triangulated sphere of 4 vertices, every pair adjacent) has a balanced bijective
// map for exactly the symmetric weights of one form, which cotangent weights do not have in general (positive ones
// included: existence is not a matter of the connectivity alone).
//
// Balanced means M X = 0, with X the 4 x 3 matrix of the positions and M = diag(alpha) - W, W the raw weights
// (the tangential part of sum_j w_ij x_j vanishes at every vertex: sum_j w_ij x_j = alpha_i x_i, alpha_i of either
// sign). A bijective map of the tetrahedron has four positions spanning space around the origin, so X has rank 3
// and its one linear dependency sum_i u_i x_i = 0 has coefficients of one sign (the origin is inside their hull).
// Then M has rank 1, M = s u u^T, and its off-diagonal entries -w_ij = s u_i u_j: the six weights are nonzero, of
// one sign, and of rank one, w_01 w_23 = w_02 w_13 = w_03 w_12, with |u_i| = sqrt(w_ij w_ik / w_jk). The unit
// vectors x_i with sum_i u_i x_i = 0 not in a plane (a closed, non-planar quadrilateral of sides u_i) exist if and
// only if each u_i is smaller than the sum of the other three. Conversely, such a quadrilateral is a balanced
// bijective map (reflected if its orientation is the mesh's opposite).
// The proof is about exact balance; the convergence test allows an imbalance up to the tolerance, which weights
// that miss the form by little can meet. So a condition counts as failed only where it fails by more than `margin`
// (relatively; the weights are scaled to a largest magnitude of 1 first, so that no product underflows).
struct Tetrahedron_weights_check
{
  bool proven_no_balanced_map = false;
  std::string reason; // which condition fails, with its figures
};

inline Tetrahedron_weights_check check_tetrahedron_weights(const Sphere_system& system, double margin)
{
  Tetrahedron_weights_check check;
  if(system.number_of_vertices != 4 || !system.symmetric || system.neighbors.size() != 12)
    return check;
  double w[4][4] = {};
  double largest = 0.;
  for(std::size_t i = 0; i < 4; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      double& weight = w[i][std::size_t(system.neighbors[k])];
      weight = system.weights[k] * system.row_sums[i];
      largest = std::max(largest, std::abs(weight));
    }
  if(!(largest > 0.) || !std::isfinite(largest))
    return check;
  for(std::size_t i = 0; i < 4; ++i)
    for(std::size_t j = 0; j < 4; ++j)
      w[i][j] /= largest;
  std::ostringstream reason;
  reason.precision(10);
  auto fail = [&]() {
    check.proven_no_balanced_map = true;
    check.reason = reason.str();
    return check;
  };
  // Every vertex's weights have a positive sum (assign_weights), so six weights of one sign are six positive ones.
  for(std::size_t i = 0; i < 4; ++i)
    for(std::size_t j = i + 1; j < 4; ++j)
      if(!(w[i][j] > 0.))
      {
        reason << "the weight of edge " << i << "-" << j << " is " << w[i][j] * largest
               << ": a balanced tetrahedron needs six nonzero weights of one sign";
        return fail();
      }
  const double p[3] = {w[0][1] * w[2][3], w[0][2] * w[1][3], w[0][3] * w[1][2]};
  const double most = std::max({p[0], p[1], p[2]}), least = std::min({p[0], p[1], p[2]});
  if(most - least > margin * most)
  {
    reason << "the products of the weights of opposite edges, w01 w23, w02 w13, w03 w12, differ by "
           << (most - least) / most << " of the largest: a balanced tetrahedron needs them equal";
    return fail();
  }
  double u[4];
  for(std::size_t i = 0; i < 4; ++i)
  {
    const std::size_t j = (i + 1) % 4, k = (i + 2) % 4;
    u[i] = std::sqrt(w[i][j] * w[i][k] / w[j][k]);
  }
  const double total = u[0] + u[1] + u[2] + u[3];
  for(std::size_t i = 0; i < 4; ++i)
    if(u[i] - (total - u[i]) > margin * total)
    {
      reason.precision(4);
      reason << "the weights are w_ij = u_i u_j with u proportional to (" << u[0] << ", " << u[1] << ", " << u[2]
             << ", " << u[3] << "), and the positions of a balanced map would satisfy sum_i u_i x_i = 0: no unit "
             << "vectors do, with u_" << i << " above the sum of the others (" << u[i] << " > " << total - u[i]
             << ")";
      return fail();
    }
  return check;
}

// A bijective map of the tetrahedron by construction: its vertices seen from their centroid (inside a tetrahedron
// that is not flat; reflected if the mesh is oriented inwards), or else the regular tetrahedron, likewise oriented.
inline void tetrahedron_map(const std::vector<Vector3>& points, const std::vector<std::array<int, 3>>& triangles,
                            std::vector<Vector3>& x)
{
  auto orient = [&](std::vector<Vector3>& y) {
    const auto& t = triangles.front();
    const Vector3 &a = y[std::size_t(t[0])], &b = y[std::size_t(t[1])], &c = y[std::size_t(t[2])];
    if(dot(a, cross(b, c)) < 0.)
      for(Vector3& v : y)
        v.z = -v.z;
  };
  const Vector3 centroid = (points[0] + points[1] + points[2] + points[3]) * 0.25;
  x.resize(4);
  for(std::size_t i = 0; i < 4; ++i)
  {
    const Vector3 d = points[i] - centroid;
    x[i] = d * (1. / length(d));
  }
  orient(x);
  if(certify(triangles, x).bijective)
    return;
  const double c = 1. / std::sqrt(3.);
  x = {Vector3(c, c, c), Vector3(c, -c, -c), Vector3(-c, c, -c), Vector3(-c, -c, c)};
  orient(x);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INSCRIBABILITY_H
