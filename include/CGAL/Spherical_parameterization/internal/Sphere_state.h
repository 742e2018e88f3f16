// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The iterate of stages 2 and 3, written by one owner: the positions on the sphere, the neighbour sums
// s_i = sum_j w_ij x_j cached for the paper's sweeps, and which faces are positively oriented (exact predicate).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_STATE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_STATE_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>

#include <CGAL/assertions.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// Positions, cached neighbour sums s_i = sum_j w_ij x_j, and which faces are positively oriented.
class Sphere_state {
public:
  Sphere_state(const Sphere_system& system, std::vector<Vector3>& x) : system_(system), x_(x)
  {
    CGAL_precondition(x.size() == system.number_of_vertices);
    face_positive_.assign(system.triangles.size(), 0);
    for(std::size_t f = 0; f < system.triangles.size(); ++f) {
      const auto& t = system.triangles[f];
      face_positive_[f] = is_positive(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])]);
      invalid_faces_ += !face_positive_[f];
    }
    refresh_sums();
  }

  const Sphere_system& system() const { return system_; }
  std::vector<Vector3>& positions() { return x_; }
  const Vector3& sum(std::size_t i) const { return s_[i]; }
  std::size_t invalid_faces() const { return invalid_faces_; }
  // Changes whenever a position does (measurements of the map are cached against it: Iteration_driver).
  std::size_t revision() const { return revision_; }

  // Recomputes every s_i (removes the drift of incremental updates) and returns the paper's Res.
  double refresh_sums()
  {
    const std::size_t n = system_.number_of_vertices;
    s_.resize(n);
    double total = 0.;
    for(std::size_t i = 0; i < n; ++i) {
      s_[i] = weighted_neighbor_sum(system_, x_, i);
      total += squared_length(cross(x_[i], s_[i]));
    }
    return std::sqrt(total) / static_cast<double>(std::max<std::size_t>(n, 1));
  }

  // Replaces all positions at once (a global step), keeping the face flags and sums consistent.
  // `positive_faces_kept`: keeps_positive_faces(y) held, so only the faces that were not positive are tested again.
  void assign(const std::vector<Vector3>& y, bool positive_faces_kept = false)
  {
    CGAL_precondition(y.size() == system_.number_of_vertices);
    ++revision_;
    x_ = y;
    invalid_faces_ = 0;
    for(std::size_t f = 0; f < system_.triangles.size(); ++f) {
      if(positive_faces_kept && face_positive_[f]) continue;
      const auto& t = system_.triangles[f];
      face_positive_[f] = is_positive(x_[static_cast<std::size_t>(t[0])], x_[static_cast<std::size_t>(t[1])], x_[static_cast<std::size_t>(t[2])]);
      invalid_faces_ += !face_positive_[f];
    }
    refresh_sums();
  }

  // True when no positive face of the current positions is non-positive at y.
  bool keeps_positive_faces(const std::vector<Vector3>& y) const
  {
    for(std::size_t f = 0; f < system_.triangles.size(); ++f) {
      if(!face_positive_[f]) continue;
      const auto& t = system_.triangles[f];
      if(!is_positive(y[static_cast<std::size_t>(t[0])], y[static_cast<std::size_t>(t[1])], y[static_cast<std::size_t>(t[2])]))
        return false;
    }
    return true;
  }

  void move(std::size_t i, const Vector3& y)
  {
    ring_orientation(i, y, false);
    commit(i, y);
  }

  // Moves i to the first of y, then points pulled back towards x_i, that is acceptable; false if none is.
  bool move_preserving_orientation(std::size_t i, Vector3 y, bool preserve)
  {
    if(preserve) {
      const Vector3 start = x_[i];
      int halvings = 0;
      while(!ring_orientation(i, y, true)) {
        if(++halvings > 12) return false;
        y = start + 0.5 * (y - start);
        y *= 1. / length(y);
      }
    } else {
      ring_orientation(i, y, false);
    }
    commit(i, y);
    return true;
  }

private:
  // The orientations of the faces around i with i at y, into ring_positive_. With `stop_at_fold`, returns false
  // (leaving ring_positive_ incomplete) as soon as a positive face would turn non-positive.
  bool ring_orientation(std::size_t i, const Vector3& y, bool stop_at_fold)
  {
    ring_vertex_ = no_vertex;
    const std::size_t begin = system_.offsets[i], end = system_.offsets[i + 1];
    ring_positive_.resize(end - begin);
    for(std::size_t k = begin; k < end; ++k) {
      const Vector3& a = x_[static_cast<std::size_t>(system_.neighbors[k])];
      const Vector3& b = x_[static_cast<std::size_t>(system_.neighbors[k + 1 < end ? k + 1 : begin])];
      const bool positive = is_positive(y, a, b);
      ring_positive_[k - begin] = positive;
      if(stop_at_fold && !positive && face_positive_[static_cast<std::size_t>(system_.ring_faces[k])]) return false;
    }
    ring_vertex_ = i;
    return true;
  }

  // Moves i to y; the orientations of its faces are those just computed by ring_orientation(i, y, ...).
  void commit(std::size_t i, const Vector3& y)
  {
    // The order of the calls: ring_orientation(i, y, ...) ran to its end just before, for this vertex.
    CGAL_precondition(ring_vertex_ == i);
    ring_vertex_ = no_vertex;
    ++revision_;
    const Vector3 delta = y - x_[i];
    x_[i] = y;
    const std::size_t begin = system_.offsets[i], end = system_.offsets[i + 1];
    for(std::size_t k = begin; k < end; ++k) {
      s_[static_cast<std::size_t>(system_.neighbors[k])] += system_.weights[system_.reverse[k]] * delta;
      const std::size_t f = static_cast<std::size_t>(system_.ring_faces[k]);
      const char positive = ring_positive_[k - begin];
      invalid_faces_ = invalid_faces_ + (face_positive_[f] ? 1 : 0) - (positive ? 1 : 0);
      face_positive_[f] = positive;
    }
  }

  const Sphere_system& system_;
  std::vector<Vector3>& x_;
  std::vector<Vector3> s_;
  std::vector<char> face_positive_;
  std::vector<char> ring_positive_;   // scratch of ring_orientation()
  static constexpr std::size_t no_vertex = std::size_t(-1);
  std::size_t ring_vertex_ = no_vertex;  // the vertex whose ring ring_positive_ holds completely, if any
  std::size_t invalid_faces_ = 0;
  std::size_t revision_ = 0;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_STATE_H
