// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A combinatorial proof that a triangulated sphere is not inscribable, when a simple one exists.
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

#include <algorithm>
#include <cstddef>
#include <numeric>
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

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INSCRIBABILITY_H
