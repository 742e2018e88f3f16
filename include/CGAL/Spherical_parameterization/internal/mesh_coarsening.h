// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The multilevel start (beyond the paper): a coarser genus-0 mesh by half-edge collapses, and the way back.
//
// Each round removes an independent set of vertices (no two removed vertices adjacent), each by collapsing it into
// one neighbour that keeps the mesh a closed manifold of genus 0 (the link condition: the two vertices share
// exactly the two neighbours of the faces they span). The way back inserts the removed vertices in the reverse
// order, each inside its ring as it was when the vertex was removed, so that a bijective coarse map gives a
// bijective fine one (each inserted vertex is placed where its fan of triangles is positive, see prolong()).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_COARSENING_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_COARSENING_H

#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// A collapse may not raise a vertex's degree above this: high degrees make the coarse problem a poor model of
// the fine one (long fans of thin triangles).
constexpr std::size_t coarsening_max_degree = 12;

struct Coarsening
{
  Mesh_arrays coarse;                    // the kept vertices (compact indices, in the fine order) and triangles
                                         // (no polygons: nothing checks the coarse mesh as input)
  std::vector<int> coarse_index;         // fine vertex -> its coarse index, -1 if removed
  std::vector<int> removed;              // fine indices, in the order of their removal
  std::vector<int> targets;              // the neighbour each removed vertex was collapsed into (fine index)
  std::vector<std::size_t> ring_offsets; // ring of removed[k]: rings[ring_offsets[k] .. ring_offsets[k + 1])
  std::vector<int> rings;                // fine indices, counter-clockwise, as at the removal
  std::size_t rounds = 0;
};

namespace coarsening_detail {

// The neighbours of u counter-clockwise, from its incident faces (each face (u, a, b) puts b after a).
inline void ring_of(int u, const std::vector<std::array<int, 3>>& faces, const std::vector<int>& incident,
                    std::vector<int>& ring)
{
  ring.clear();
  if(incident.empty())
    return;
  auto others = [&](int f, int& a, int& b) {
    const std::array<int, 3>& t = faces[static_cast<std::size_t>(f)];
    const int k = t[0] == u ? 0 : (t[1] == u ? 1 : 2);
    a = t[(k + 1) % 3];
    b = t[(k + 2) % 3];
  };
  int a, b;
  others(incident.front(), a, b);
  const int first = a;
  ring.push_back(a);
  int current = b;
  while(current != first && ring.size() <= incident.size())
  {
    ring.push_back(current);
    bool found = false;
    for(int f : incident)
    {
      others(f, a, b);
      if(a == current)
      {
        current = b;
        found = true;
        break;
      }
    }
    if(!found)
      break;
  }
}

inline void erase_value(std::vector<int>& values, int value)
{
  auto it = std::find(values.begin(), values.end(), value);
  if(it != values.end())
  {
    *it = values.back();
    values.pop_back();
  }
}

// A triangle whose doubled area is below 1e-12 times its longest edge squared: its corners are on a line up to
// rounding.
inline bool degenerate_in_3d(const Vector3& a, const Vector3& b, const Vector3& c)
{
  const double longest = (std::max)({squared_length(b - a), squared_length(c - b), squared_length(a - c)});
  return !(length(cross(b - a, c - a)) > 1e-12 * longest);
}

} // namespace coarsening_detail

// Collapses the mesh of `points` and `triangles` (closed, oriented, manifold, genus 0) down to about
// `target_vertices` (never below 8). Vertices are visited in index order, which follows the space-filling curve on
// large meshes.
inline Coarsening coarsen_mesh(const std::vector<Vector3>& points, const std::vector<std::array<int, 3>>& triangles,
                               std::size_t target_vertices)
{
  using namespace coarsening_detail;
  const std::size_t n = points.size();
  target_vertices = std::max<std::size_t>(target_vertices, 8);
  CGAL_precondition(2 * n == triangles.size() + 4); // closed genus 0: F = 2 V - 4
  Coarsening result;
  std::vector<std::array<int, 3>> faces = triangles;
  std::vector<char> face_alive(faces.size(), 1), vertex_alive(n, 1), locked(n, 0);
  std::vector<std::vector<int>> incident(n);
  for(std::size_t f = 0; f < faces.size(); ++f)
    for(int v : faces[f])
      incident[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
  std::vector<int> in_ring_of(n, -1); // in_ring_of[w] == u: w is a neighbour of u (the vertex being tried)
  std::vector<int> ring;
  result.ring_offsets.push_back(0);
  std::size_t alive = n;
  bool progress = true;
  while(alive > target_vertices && progress)
  {
    progress = false;
    ++result.rounds;
    std::fill(locked.begin(), locked.end(), 0);
    for(std::size_t iu = 0; iu < n && alive > target_vertices; ++iu)
    {
      if(!vertex_alive[iu] || locked[iu])
        continue;
      const int u = static_cast<int>(iu);
      ring_of(u, faces, incident[iu], ring);
      const std::size_t d = ring.size();
      if(d != incident[iu].size() || d < 3)
        continue; // not a simple ring (cannot happen on a valid mesh)
      for(int w : ring)
        in_ring_of[static_cast<std::size_t>(w)] = u;
      // The target: the neighbour that gives the smallest degree, then the shortest edge.
      std::size_t best = d;
      std::size_t best_degree = coarsening_max_degree + 1;
      double best_length = std::numeric_limits<double>::infinity();
      for(std::size_t k = 0; k < d; ++k)
      {
        const std::size_t v = static_cast<std::size_t>(ring[k]);
        const std::size_t degree = d + incident[v].size() - 4;
        if(degree > coarsening_max_degree || degree > best_degree)
          continue;
        const int before = ring[(k + d - 1) % d], after = ring[(k + 1) % d];
        // Link condition: u and v share no neighbour but `before` and `after`.
        bool link = true;
        for(int f : incident[v])
        {
          for(int w : faces[static_cast<std::size_t>(f)])
            if(w != static_cast<int>(v) && w != u && w != before && w != after
               && in_ring_of[static_cast<std::size_t>(w)] == u)
            {
              link = false;
              break;
            }
          if(!link)
            break;
        }
        if(!link)
          continue;
        // Nor one that leaves a face degenerate in 3D (its corners on a line, as marching cubes' grids give): the
        // least-distortion levels keep each face's shape (its cotangents), and a flat face has none. On a
        // marching-tetrahedra surface with thin arms, three such faces of the level of 8,039 vertices stopped the
        // multilevel start of the minimization there (from Tutte's map instead: not stationary after 219 steps, 60
        // s; through the levels: stationary after 188).
        bool flat = false;
        for(std::size_t m = 0; m < d && !flat; ++m)
        {
          const std::size_t a = static_cast<std::size_t>(ring[m]), b = static_cast<std::size_t>(ring[(m + 1) % d]);
          if(a != v && b != v)
            flat = degenerate_in_3d(points[v], points[a], points[b]);
        }
        if(flat)
          continue;
        const double edge = squared_length(points[v] - points[iu]);
        if(degree < best_degree || edge < best_length)
        {
          best = k;
          best_degree = degree;
          best_length = edge;
        }
      }
      if(best == d)
        continue;
      const int v = ring[best];
      // Collapse u into v: the two faces on the edge go, the others take v for u.
      for(int f : incident[iu])
      {
        std::array<int, 3>& t = faces[static_cast<std::size_t>(f)];
        if(t[0] == v || t[1] == v || t[2] == v)
        {
          face_alive[static_cast<std::size_t>(f)] = 0;
          for(int w : t)
            if(w != u)
              erase_value(incident[static_cast<std::size_t>(w)], f);
        }
        else
        {
          for(int& w : t)
            if(w == u)
              w = v;
          incident[static_cast<std::size_t>(v)].push_back(f);
        }
      }
      incident[iu].clear();
      vertex_alive[iu] = 0;
      --alive;
      progress = true;
      for(int w : ring)
        locked[static_cast<std::size_t>(w)] = 1;
      result.removed.push_back(u);
      result.targets.push_back(v);
      result.rings.insert(result.rings.end(), ring.begin(), ring.end());
      result.ring_offsets.push_back(result.rings.size());
    }
  }
  result.coarse_index.assign(n, -1);
  int next = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(vertex_alive[i])
    {
      result.coarse_index[i] = next++;
      result.coarse.points.push_back(points[i]);
    }
  for(std::size_t f = 0; f < faces.size(); ++f)
  {
    if(!face_alive[f])
      continue;
    const std::array<int, 3>& t = faces[f];
    result.coarse.triangles.push_back(canonical_triangle(result.coarse_index[static_cast<std::size_t>(t[0])],
                                                         result.coarse_index[static_cast<std::size_t>(t[1])],
                                                         result.coarse_index[static_cast<std::size_t>(t[2])]));
  }
  // The collapses kept the link condition: still a closed genus-0 mesh.
  CGAL_postcondition(2 * result.coarse.points.size() == result.coarse.triangles.size() + 4);
  return result;
}

// The same for a mesh's arrays.
inline Coarsening coarsen_mesh(const Mesh_arrays& mesh, std::size_t target_vertices)
{
  return coarsen_mesh(mesh.points, mesh.triangles, target_vertices);
}

// A point of the sphere where the fan from it over `ring` (counter-clockwise) is positive, far from folding: the centre
// of the largest circle inside the ring's kernel, in the gnomonic projection about `centre` (which maps
// great circles to straight lines, so that the kernel is an intersection of half-planes). The largest circle touches
// three of the ring's edge lines: each triple is solved and the best one that keeps every constraint is taken (rings
// have a few edges). False if the kernel is empty, or a ring vertex is not in the open hemisphere about `centre`.
inline bool kernel_centre(const Vector3& centre, const std::vector<Vector3>& ring, Vector3& result)
{
  Vector3 e1, e2;
  tangent_frame(centre, e1, e2);
  const std::size_t d = ring.size();
  std::vector<double> u(d), v(d);
  for(std::size_t m = 0; m < d; ++m)
  {
    const double height = dot(ring[m], centre);
    if(!(height > 0.))
      return false;
    const Vector3 q = ring[m] * (1. / height);
    u[m] = dot(q, e1);
    v[m] = dot(q, e2);
  }
  // Edge m, from ring[m] to ring[m + 1]: the signed distance of a point (a, b) to its left is
  // normal_u[m] a + normal_v[m] b + offset[m].
  std::vector<double> normal_u(d), normal_v(d), offset(d);
  for(std::size_t m = 0; m < d; ++m)
  {
    const std::size_t next = (m + 1) % d;
    const double du = u[next] - u[m], dv = v[next] - v[m];
    const double edge = std::sqrt(du * du + dv * dv);
    if(!(edge > 0.))
      return false;
    normal_u[m] = -dv / edge;
    normal_v[m] = du / edge;
    offset[m] = (dv * u[m] - du * v[m]) / edge;
  }
  double best_radius = 0., best_u = 0., best_v = 0.;
  for(std::size_t i = 0; i < d; ++i)
    for(std::size_t j = i + 1; j < d; ++j)
      for(std::size_t k = j + 1; k < d; ++k)
      {
        const std::size_t rows[3] = {i, j, k};
        double a[3][3], rhs[3];
        for(int r = 0; r < 3; ++r)
        {
          a[r][0] = normal_u[rows[r]];
          a[r][1] = normal_v[rows[r]];
          a[r][2] = -1.;
          rhs[r] = -offset[rows[r]];
        }
        // Cramer's rule on the 3x3 system (distance to each of the three lines = radius).
        auto det3 = [](const double (&m)[3][3]) {
          return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                 + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        };
        const double det = det3(a);
        if(!(std::abs(det) > 1e-12))
          continue;
        double solution[3];
        for(int c = 0; c < 3; ++c)
        {
          double b[3][3];
          for(int r = 0; r < 3; ++r)
            for(int cc = 0; cc < 3; ++cc)
              b[r][cc] = cc == c ? rhs[r] : a[r][cc];
          solution[c] = det3(b) / det;
        }
        if(!(solution[2] > best_radius))
          continue;
        bool inside = true;
        for(std::size_t m = 0; m < d && inside; ++m)
          inside = normal_u[m] * solution[0] + normal_v[m] * solution[1] + offset[m] >= solution[2] * (1. - 1e-9);
        if(inside)
        {
          best_radius = solution[2];
          best_u = solution[0];
          best_v = solution[1];
        }
      }
  if(!(best_radius > 0.))
    return false;
  const Vector3 q = centre + best_u * e1 + best_v * e2;
  result = q * (1. / length(q));
  return true;
}

// Where prolong() puts a vertex inserted back.
enum class Insertion
{
  RING_MEAN,     // the normalized mean of its ring (the balance point of uniform weights) where its fan is positive there
  KERNEL_CENTRE  // kernel_centre(): as far from folding as the ring allows
};

// The fine map from the coarse one: kept vertices where the coarse map put them, removed ones inserted back in
// the reverse order of their removal. A vertex goes to the normalized mean of its ring (the balance point of
// uniform weights) when its fan of triangles is positive there. Otherwise it goes close to the vertex it was
// collapsed into, v, along the bisector of the angle that its ring spans at v: the fan of v over the ring was
// positive (it is made of faces of the coarser map), so that angle is below 2 pi, both halves are below pi, and
// near enough to v the new fan is positive. Positive means the exact predicate of the certificate: where the
// coarse map squeezes a thin part to edges of 1e-11 (bull.off refined once), a plain determinant of the unit
// vectors is rounding noise, and 432 of 4,649 vertices were left folded by it. Returns how many vertices found no
// positive place (the mean is kept and the fan is folded; Newton's steps may still unfold it).
// With Insertion::KERNEL_CENTRE, each vertex goes to the centre of its ring's kernel first (about the ring's mean,
// then about v): the least-distortion minimization (stage3/least_distortion.h) cannot start from a folded map, and a
// face left barely positive by the mean makes later rings' kernels empty (CGAL's man: 2 of 3,280 vertices left folded
// from a map of least distortion with the mean, none with the kernel's centre).
// `also_positive(p, q, r)`: a test each new face must pass too (the least-distortion start: the orientation its
// energy is defined by, see multilevel_least_distortion.h).
struct Any_positive_face
{
  bool operator()(const Vector3&, const Vector3&, const Vector3&) const { return true; }
};

template <typename Also_positive = Any_positive_face>
std::size_t prolong(const Coarsening& coarsening, const std::vector<Vector3>& coarse_x, std::vector<Vector3>& x,
                    Insertion insertion = Insertion::RING_MEAN, const Also_positive& also_positive = Also_positive())
{
  const std::size_t n = coarsening.coarse_index.size();
  CGAL_precondition(coarse_x.size() == coarsening.coarse.points.size());
  x.assign(n, Vector3());
  for(std::size_t i = 0; i < n; ++i)
    if(coarsening.coarse_index[i] >= 0)
      x[i] = coarse_x[static_cast<std::size_t>(coarsening.coarse_index[i])];
  std::size_t folded = 0;
  std::vector<Vector3> ring_points;
  for(std::size_t k = coarsening.removed.size(); k-- > 0;)
  {
    const int* ring = coarsening.rings.data() + coarsening.ring_offsets[k];
    const std::size_t d = coarsening.ring_offsets[k + 1] - coarsening.ring_offsets[k];
    auto at = [&](std::size_t m) -> const Vector3& { return x[static_cast<std::size_t>(ring[m % d])]; };
    auto positive_fan = [&](const Vector3& p) {
      for(std::size_t m = 0; m < d; ++m)
        if(!is_positive(p, at(m), at(m + 1)) || !also_positive(p, at(m), at(m + 1)))
          return false;
      return true;
    };
    Vector3 mean;
    for(std::size_t m = 0; m < d; ++m)
      mean += at(m);
    Vector3& p = x[static_cast<std::size_t>(coarsening.removed[k])];
    p = mean * (1. / length(mean));
    if(insertion == Insertion::KERNEL_CENTRE)
    {
      ring_points.resize(d);
      for(std::size_t m = 0; m < d; ++m)
        ring_points[m] = at(m);
      Vector3 centre;
      if((kernel_centre(p, ring_points, centre) && positive_fan(centre))
         || (kernel_centre(x[static_cast<std::size_t>(coarsening.targets[k])], ring_points, centre)
             && positive_fan(centre)))
      {
        p = centre;
        continue;
      }
    }
    if(positive_fan(p))
      continue;
    // The ring around v counter-clockwise: ..., before, v, after, ...; the angle at v from `after` to `before`.
    const int v = coarsening.targets[k];
    std::size_t position = 0;
    while(position < d && ring[position] != v)
      ++position;
    const Vector3& centre = x[static_cast<std::size_t>(v)];
    Vector3 e1, e2;
    tangent_frame(centre, e1, e2);
    auto angle_of = [&](const Vector3& q) {
      const Vector3 t = q - centre;
      return std::atan2(dot(t, e2), dot(t, e1));
    };
    const double first = angle_of(at(position + 1)), last = angle_of(at(position + d - 1));
    double span = last - first;
    while(span <= 0.)
      span += 2. * CGAL_PI;
    const double bisector = first + 0.5 * span;
    // From half the longest ring edge at v down to where q rounds to v itself: a neighbour may sit an ulp from v
    // where the coarse map is squeezed below double precision, so the shortest ring edge is no scale to start from.
    double longest = 0.;
    for(std::size_t m = 0; m < d; ++m)
      longest = std::max(longest, length(at(m) - centre));
    const Vector3 direction = std::cos(bisector) * e1 + std::sin(bisector) * e2;
    bool placed = false;
    for(double t = 0.5 * longest; t > 0. && !placed; t *= 0.5)
    {
      const Vector3 q = centre + t * direction;
      const Vector3 candidate = q * (1. / length(q));
      if(candidate == centre)
        break;
      if(positive_fan(candidate))
      {
        p = candidate;
        placed = true;
      }
    }
    if(!placed)
      ++folded;
  }
  return folded;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MESH_COARSENING_H
