// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A map with a few folded faces made a start for the least-distortion minimization, which needs every face positive:
// each vertex of a non-positive face is moved to the centre of its ring's kernel (kernel_centre(), mesh_coarsening.h),
// where its whole fan is positive, if that kernel is not empty. A move only changes the faces of the vertex moved,
// and all of them end positive, so the faces that are not positive only become fewer. While faces stay folded (a
// vertex's kernel was empty: its neighbours are folded too), the next rounds also move the vertices around them, one
// ring further each round.
//
// The map it is for: the balanced map of cotangent weights that Newton's full steps reach with a few folded faces
// (Iteration_report::folded_balanced_map). Such a map is close to conformal everywhere but at its folds, so, repaired
// and smoothed (Sphere_mapper::least_distortion()), it is a better start than the minimization's own coarser levels
// give (bigbrain: distortion 1.00166 against 1.0083, 4 Newton steps on the mesh instead of 8), and those levels are
// not computed (7 s of bigbrain's run). The manual's Method section gives the figures.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_FOLD_REPAIR_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_FOLD_REPAIR_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>
#include <CGAL/Spherical_parameterization/internal/mesh_coarsening.h>
#include <CGAL/Spherical_parameterization/internal/stage3/least_distortion.h>

#include <CGAL/assertions.h>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// Positive for the certificate's exact predicate and in the orientation the distortion F is defined by (their signs
// can differ on faces squeezed to the limits of double precision; the minimization tests the latter).
inline bool positive_for_distortion(const Vector3& a, const Vector3& b, const Vector3& c)
{
  return is_positive(a, b, c) && positive_in_distortion_orientation(a, b, c);
}

struct Fold_repair_report
{
  bool repaired = false;         // every face positive (positive_for_distortion)
  std::size_t folded_faces = 0;  // non-positive faces before
  std::size_t moved_vertices = 0;
  int rounds = 0;
};

// Vertices of a higher degree are not moved: kernel_centre() tries every triple of ring edges (its cost grows as the
// fourth power of the degree; written for the coarsening's rings), and the fans of CAD meshes can have hundreds.
constexpr std::size_t fold_repair_max_degree = 64;

// Moves vertices of `x` (the triangles and rings of `system`, whose neighbours go counter-clockwise) until every face
// is positive, in at most `max_rounds` rounds; `x` keeps the moves made either way.
inline Fold_repair_report repair_folds(const Sphere_system& system, std::vector<Vector3>& x, int max_rounds)
{
  const std::size_t n = system.number_of_vertices;
  CGAL_precondition(x.size() == n);
  Fold_repair_report report;
  std::vector<char> candidate(n, 0), moved(n, 0);
  std::vector<Vector3> ring;
  for(int round = 0;; ++round)
  {
    std::size_t folded = 0;
    for(const std::array<int, 3>& t : system.triangles)
      if(!positive_for_distortion(x[std::size_t(t[0])], x[std::size_t(t[1])], x[std::size_t(t[2])]))
      {
        ++folded;
        for(int k = 0; k < 3; ++k)
          candidate[std::size_t(t[k])] = 1;
      }
    if(round == 0)
      report.folded_faces = folded;
    report.rounds = round;
    if(folded == 0)
    {
      report.repaired = true;
      break;
    }
    if(round >= max_rounds)
      break;
    if(round > 0) // one ring further around the folds each round
    {
      std::vector<char> grown = candidate;
      for(std::size_t v = 0; v < n; ++v)
        if(candidate[v])
          for(std::size_t k = system.offsets[v]; k < system.offsets[v + 1]; ++k)
            grown[std::size_t(system.neighbors[k])] = 1;
      candidate.swap(grown);
    }
    for(std::size_t v = 0; v < n; ++v)
    {
      const std::size_t d = system.degree(v);
      if(!candidate[v] || d > fold_repair_max_degree)
        continue;
      ring.resize(d);
      Vector3 mean;
      for(std::size_t m = 0; m < d; ++m)
      {
        ring[m] = x[std::size_t(system.neighbors[system.offsets[v] + m])];
        mean += ring[m];
      }
      // Each face of the fan tested in its own vertex order, as the count above and F test it (the orientation of F
      // is computed in double, and its rounding depends on that order).
      auto positive_fan = [&](const Vector3& p) {
        for(std::size_t m = 0; m < d; ++m)
        {
          const std::array<int, 3>& t = system.triangles[std::size_t(system.ring_faces[system.offsets[v] + m])];
          const Vector3* corner[3];
          for(int k = 0; k < 3; ++k)
            corner[k] = std::size_t(t[k]) == v ? &p : &x[std::size_t(t[k])];
          if(!positive_for_distortion(*corner[0], *corner[1], *corner[2]))
            return false;
        }
        return true;
      };
      // About the ring's mean first, as prolong() does; about the vertex where the mean's hemisphere misses a neighbour.
      Vector3 centre;
      const double mean_length = length(mean);
      if((mean_length > 0. && kernel_centre(mean * (1. / mean_length), ring, centre) && positive_fan(centre))
         || (kernel_centre(x[v], ring, centre) && positive_fan(centre)))
      {
        x[v] = centre;
        moved[v] = 1;
      }
    }
  }
  for(char m : moved)
    report.moved_vertices += std::size_t(m);
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_FOLD_REPAIR_H
