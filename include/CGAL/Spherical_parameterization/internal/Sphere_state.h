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
class Sphere_state
{
public:
  Sphere_state(const Sphere_system& system, std::vector<Vector3>& x) : m_system(system), m_x(x)
  {
    CGAL_precondition(x.size() == system.number_of_vertices);
    m_face_positive.assign(system.triangles.size(), 0);
    for(std::size_t f = 0; f < system.triangles.size(); ++f)
    {
      const auto& t = system.triangles[f];
      m_face_positive[f] = is_positive(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                                       x[static_cast<std::size_t>(t[2])]);
      m_invalid_faces += !m_face_positive[f];
    }
    refresh_sums();
  }

  const Sphere_system& system() const { return m_system; }
  std::vector<Vector3>& positions() { return m_x; }
  const std::vector<Vector3>& positions() const { return m_x; }
  const Vector3& sum(std::size_t i) const { return m_s[i]; }
  std::size_t invalid_faces() const { return m_invalid_faces; }
  bool face_positive(std::size_t f) const { return m_face_positive[f] != 0; }
  // Changes whenever a position does (measurements of the map are cached against it: Iteration_driver).
  std::size_t revision() const { return m_revision; }

  // Recomputes every s_i (removes the drift of incremental updates) and returns the paper's Res.
  double refresh_sums()
  {
    const std::size_t n = m_system.number_of_vertices;
    m_s.resize(n);
    double total = 0.;
    for(std::size_t i = 0; i < n; ++i)
    {
      m_s[i] = weighted_neighbor_sum(m_system, m_x, i);
      total += squared_length(cross(m_x[i], m_s[i]));
    }
    return std::sqrt(total) / static_cast<double>(std::max<std::size_t>(n, 1));
  }

  // Replaces all positions at once (a global step), keeping the face flags and sums consistent.
  // `positive_faces_kept`: keeps_positive_faces(y) held, so only the faces that were not positive are tested again.
  void assign(const std::vector<Vector3>& y, bool positive_faces_kept = false)
  {
    CGAL_precondition(y.size() == m_system.number_of_vertices);
    ++m_revision;
    m_x = y;
    m_invalid_faces = 0;
    for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
    {
      if(positive_faces_kept && m_face_positive[f])
        continue;
      const auto& t = m_system.triangles[f];
      m_face_positive[f] = is_positive(m_x[static_cast<std::size_t>(t[0])], m_x[static_cast<std::size_t>(t[1])],
                                       m_x[static_cast<std::size_t>(t[2])]);
      m_invalid_faces += !m_face_positive[f];
    }
    refresh_sums();
  }

  // True when no positive face of the current positions is non-positive at y.
  bool keeps_positive_faces(const std::vector<Vector3>& y) const
  {
    for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
    {
      if(!m_face_positive[f])
        continue;
      const auto& t = m_system.triangles[f];
      if(!is_positive(y[static_cast<std::size_t>(t[0])], y[static_cast<std::size_t>(t[1])],
                      y[static_cast<std::size_t>(t[2])]))
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
    if(preserve)
    {
      const Vector3 start = m_x[i];
      int halvings = 0;
      while(!ring_orientation(i, y, true))
      {
        if(++halvings > 12)
          return false;
        y = start + 0.5 * (y - start);
        y *= 1. / length(y);
      }
    }
    else
    {
      ring_orientation(i, y, false);
    }
    commit(i, y);
    return true;
  }

private:
  // The orientations of the faces around i with i at y, into m_ring_positive. With `stop_at_fold`, returns false
  // (leaving m_ring_positive incomplete) as soon as a positive face would turn non-positive.
  bool ring_orientation(std::size_t i, const Vector3& y, bool stop_at_fold)
  {
    m_ring_vertex = no_vertex;
    const std::size_t begin = m_system.offsets[i], end = m_system.offsets[i + 1];
    m_ring_positive.resize(end - begin);
    for(std::size_t k = begin; k < end; ++k)
    {
      const Vector3& a = m_x[static_cast<std::size_t>(m_system.neighbors[k])];
      const Vector3& b = m_x[static_cast<std::size_t>(m_system.neighbors[k + 1 < end ? k + 1 : begin])];
      const bool positive = is_positive(y, a, b);
      m_ring_positive[k - begin] = positive;
      if(stop_at_fold && !positive && m_face_positive[static_cast<std::size_t>(m_system.ring_faces[k])])
        return false;
    }
    m_ring_vertex = i;
    return true;
  }

  // Moves i to y; the orientations of its faces are those just computed by ring_orientation(i, y, ...).
  void commit(std::size_t i, const Vector3& y)
  {
    // The order of the calls: ring_orientation(i, y, ...) ran to its end just before, for this vertex.
    CGAL_precondition(m_ring_vertex == i);
    m_ring_vertex = no_vertex;
    ++m_revision;
    const Vector3 delta = y - m_x[i];
    m_x[i] = y;
    const std::size_t begin = m_system.offsets[i], end = m_system.offsets[i + 1];
    for(std::size_t k = begin; k < end; ++k)
    {
      m_s[static_cast<std::size_t>(m_system.neighbors[k])] += m_system.weights[m_system.reverse[k]] * delta;
      const std::size_t f = static_cast<std::size_t>(m_system.ring_faces[k]);
      const char positive = m_ring_positive[k - begin];
      m_invalid_faces = m_invalid_faces + (m_face_positive[f] ? 1 : 0) - (positive ? 1 : 0);
      m_face_positive[f] = positive;
    }
  }

  const Sphere_system& m_system;
  std::vector<Vector3>& m_x;
  std::vector<Vector3> m_s;
  std::vector<char> m_face_positive;
  std::vector<char> m_ring_positive; // scratch of ring_orientation()
  static constexpr std::size_t no_vertex = std::size_t(-1);
  std::size_t m_ring_vertex = no_vertex; // the vertex whose ring m_ring_positive holds completely, if any
  std::size_t m_invalid_faces = 0;
  std::size_t m_revision = 0;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_STATE_H
