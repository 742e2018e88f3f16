// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 1a: split a closed genus-0 mesh into two topological disks along a simple closed loop of edges.
//
// METIS gives a balanced vertex separator, but a separator is not a cycle: it can branch, have loose ends, and
// leave sides that are disconnected or pinched. So the separator only guides the cut: disk A is grown face by
// face from the inside of METIS' first part, and a face joins only if A stays a disk (it shares one edge with A
// and brings a new vertex, or shares two edges). The boundary of a disk on a sphere is a simple loop and its
// complement is a disk too, whatever the separator looked like. Faces with two edges on the loop would have all
// three vertices on the unit circle (flat on the equator after projection), so they are moved to the other side.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TWO_DISK_PARTITION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TWO_DISK_PARTITION_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/deferred_stop_signals.h>

#include <metis.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Two_disk_partition
{
  std::vector<char> face_in_disk_a; // 1: disk A, 0: disk B
  std::vector<int> loop;            // the shared boundary, counter-clockwise around disk A
  std::size_t separator_size = 0;   // vertices in METIS' separator (0 when METIS was not used)
  bool valid = false;
};

// opposite[3 f + k] = the face across the edge (t[k], t[k+1]) of face f: the face of the directed edge
// t[k+1] -> t[k], read off the ring of t[k+1] (no global sort of the 3 nf edges, which took a large share of the
// partition's time on large meshes); -1 where there is none.
inline std::vector<int> face_adjacency(const Sphere_system& system)
{
  const std::vector<std::array<int, 3>>& triangles = system.triangles;
  std::vector<int> opposite(3 * triangles.size(), -1);
  for(std::size_t f = 0; f < triangles.size(); ++f)
    for(std::size_t k = 0; k < 3; ++k)
    {
      const int a = triangles[f][k];
      const std::size_t b = static_cast<std::size_t>(triangles[f][(k + 1) % 3]);
      for(std::size_t m = system.offsets[b]; m < system.offsets[b + 1]; ++m)
        if(system.neighbors[m] == a)
        {
          opposite[3 * f + k] = system.ring_faces[m];
          break;
        }
    }
  return opposite;
}

// METIS vertex separator: part[v] is 0 or 1 for the two sides, 2 for the separator. Empty on failure.
inline std::vector<idx_t> metis_vertex_separator(const Sphere_system& system, int seed, const idx_t* user_options)
{
  idx_t n = static_cast<idx_t>(system.number_of_vertices);
  if(n < 6)
    return {}; // too small for a meaningful separator: the disk growth alone balances it
  std::vector<idx_t> xadj(system.offsets.begin(), system.offsets.end());
  std::vector<idx_t> adjncy(system.neighbors.begin(), system.neighbors.end());
  std::vector<idx_t> part(static_cast<std::size_t>(n), 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = static_cast<idx_t>(seed);
  if(user_options != nullptr)
    std::copy(user_options, user_options + METIS_NOPTIONS, options);
  idx_t separator_size = 0;
  const Metis_call_guard metis_call; // no stop signal lost inside METIS (see deferred_stop_signals.h)
  if(METIS_ComputeVertexSeparator(&n, xadj.data(), adjncy.data(), nullptr, options, &separator_size, part.data())
     != METIS_OK)
    return {};
  return part;
}

class Disk_grower
{
public:
  Disk_grower(const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& opposite, std::size_t nv)
    : m_triangles(&triangles), m_opposite(&opposite), m_in_disk(triangles.size(), 0), m_faces_at_vertex(nv, 0)
  {}

  std::size_t size() const { return m_size; }
  const std::vector<char>& in_disk() const { return m_in_disk; }
  bool contains(std::size_t f) const { return m_in_disk[f] != 0; }

  int shared_edges(std::size_t f) const
  {
    int shared = 0;
    for(int k = 0; k < 3; ++k)
      shared += m_in_disk[static_cast<std::size_t>((*m_opposite)[3 * f + static_cast<std::size_t>(k)])];
    return shared;
  }

  // Adding f keeps a disk iff it shares two edges, or one edge and its third vertex is new to the disk.
  bool can_add(std::size_t f) const
  {
    if(m_in_disk[f])
      return false;
    if(m_size == 0)
      return true;
    const int shared = shared_edges(f);
    if(shared == 2)
      return true;
    if(shared != 1)
      return false;
    for(int k = 0; k < 3; ++k)
      if(m_in_disk[static_cast<std::size_t>((*m_opposite)[3 * f + static_cast<std::size_t>(k)])])
        return m_faces_at_vertex[static_cast<std::size_t>((*m_triangles)[f][(k + 2) % 3])] == 0;
    return false;
  }

  void add(std::size_t f) { set(f, 1); }
  void remove(std::size_t f) { set(f, 0); }

private:
  void set(std::size_t f, char value)
  {
    m_in_disk[f] = value;
    for(int v : (*m_triangles)[f])
      m_faces_at_vertex[static_cast<std::size_t>(v)] += value ? 1 : -1;
    m_size = value ? m_size + 1 : m_size - 1;
  }

  const std::vector<std::array<int, 3>>* m_triangles;
  const std::vector<int>* m_opposite;
  std::vector<char> m_in_disk;
  std::vector<int> m_faces_at_vertex;
  std::size_t m_size = 0;
};

inline int boundary_edges(const Disk_grower& disk, const std::vector<int>& opposite, std::size_t f)
{
  int count = 0;
  for(int k = 0; k < 3; ++k)
    count += disk.contains(static_cast<std::size_t>(opposite[3 * f + static_cast<std::size_t>(k)])) != disk.contains(f);
  return count;
}

// Moves faces with two edges on the loop to the other side; each move shortens the loop by one edge.
inline void remove_ears(Disk_grower& disk, const std::vector<int>& opposite, std::size_t nf)
{
  std::deque<std::size_t> work;
  for(std::size_t f = 0; f < nf; ++f)
    work.push_back(f);
  while(!work.empty())
  {
    const std::size_t f = work.front();
    work.pop_front();
    if(boundary_edges(disk, opposite, f) != 2)
      continue;
    if(disk.contains(f))
    {
      if(disk.size() <= 1)
        continue;
      disk.remove(f);
    }
    else
    {
      if(nf - disk.size() <= 1)
        continue;
      disk.add(f);
    }
    for(int k = 0; k < 3; ++k)
      work.push_back(static_cast<std::size_t>(opposite[3 * f + static_cast<std::size_t>(k)]));
  }
}

// Breadth-first growth of a disk from `seed` over the allowed faces, up to `target` faces, then ear removal.
inline Disk_grower grow_disk(const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& opposite,
                             std::size_t nv, const std::vector<char>& allowed, std::size_t seed, std::size_t target)
{
  Disk_grower disk(triangles, opposite, nv);
  std::deque<std::size_t> queue{seed};
  while(!queue.empty() && disk.size() < target)
  {
    const std::size_t f = queue.front();
    queue.pop_front();
    if(!allowed[f] || !disk.can_add(f))
      continue;
    // Faces that share two edges with the disk are added at once: the disk stays compact, without ears.
    std::vector<std::size_t> added{f};
    disk.add(f);
    while(!added.empty() && disk.size() < target)
    {
      const std::size_t g = added.back();
      added.pop_back();
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t h = static_cast<std::size_t>(opposite[3 * g + static_cast<std::size_t>(k)]);
        queue.push_back(h);
        if(allowed[h] && !disk.contains(h) && disk.shared_edges(h) == 2 && disk.size() + 1 < triangles.size()
           && disk.size() < target)
        {
          disk.add(h);
          added.push_back(h);
        }
      }
    }
  }
  remove_ears(disk, opposite, triangles.size());
  return disk;
}

// A face with two or three edges on the loop has all its vertices on the unit circle: flat on the equator.
// Any face with its three vertices on the loop is flat, even with fewer loop edges.
inline bool has_flat_face(const Disk_grower& disk, const std::vector<std::array<int, 3>>& triangles,
                          const std::vector<int>& opposite, std::size_t nv)
{
  const std::size_t nf = triangles.size();
  if(disk.size() == 0 || disk.size() >= nf)
    return true;
  std::vector<char> on_loop(nv, 0);
  for(std::size_t f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k)
      if(disk.contains(static_cast<std::size_t>(opposite[3 * f + static_cast<std::size_t>(k)])) != disk.contains(f))
        on_loop[static_cast<std::size_t>(triangles[f][k])] =
            on_loop[static_cast<std::size_t>(triangles[f][(k + 1) % 3])] = 1;
  for(const auto& t : triangles)
    if(on_loop[static_cast<std::size_t>(t[0])] && on_loop[static_cast<std::size_t>(t[1])]
       && on_loop[static_cast<std::size_t>(t[2])])
      return true;
  return false;
}

inline Two_disk_partition split_into_two_disks(const Sphere_system& system, int metis_seed,
                                               const idx_t* metis_options = nullptr)
{
  Two_disk_partition partition;
  const auto& triangles = system.triangles;
  const std::size_t nf = triangles.size(), nv = system.number_of_vertices;
  if(nf < 2)
    return partition;
  const std::vector<int> opposite = face_adjacency(system);
  for(int o : opposite)
    if(o < 0)
      return partition;

  // Faces that may join disk A: none of their vertices in METIS' second part.
  const std::vector<idx_t> part = metis_vertex_separator(system, metis_seed, metis_options);
  std::vector<char> allowed(nf, 1);
  std::size_t seed = 0, target = nf / 2;
  if(!part.empty())
  {
    for(idx_t p : part)
      partition.separator_size += (p == 2);
    bool found_seed = false;
    std::size_t allowed_count = 0;
    for(std::size_t f = 0; f < nf; ++f)
    {
      bool touches_b = false, inside_a = true;
      for(int v : triangles[f])
      {
        touches_b = touches_b || part[static_cast<std::size_t>(v)] == 1;
        inside_a = inside_a && part[static_cast<std::size_t>(v)] == 0;
      }
      allowed[f] = !touches_b;
      allowed_count += allowed[f];
      if(inside_a && !found_seed)
      {
        seed = f;
        found_seed = true;
      }
    }
    if(found_seed && allowed_count < nf)
      target = nf - 1;
    else
      std::fill(allowed.begin(), allowed.end(), 1);
  }

  Disk_grower disk = grow_disk(triangles, opposite, nv, allowed, seed, target);
  if(has_flat_face(disk, triangles, opposite, nv))
  {
    // METIS' side was too small or thin to avoid a face with all vertices on the loop (tiny meshes): grow half
    // of the faces from successive seeds instead, keeping the first split without such a face.
    std::fill(allowed.begin(), allowed.end(), 1);
    for(std::size_t start = 0; start < std::min<std::size_t>(nf, 16); ++start)
    {
      disk = grow_disk(triangles, opposite, nv, allowed, start, nf / 2);
      if(!has_flat_face(disk, triangles, opposite, nv))
        break;
    }
  }
  // The loop: boundary edges of A, oriented as A's faces, so A lies on their left.
  std::vector<int> next(nv, -1);
  std::size_t loop_edges = 0;
  int start = -1;
  for(std::size_t f = 0; f < nf; ++f)
  {
    if(!disk.contains(f))
      continue;
    for(int k = 0; k < 3; ++k)
    {
      if(disk.contains(static_cast<std::size_t>(opposite[3 * f + static_cast<std::size_t>(k)])))
        continue;
      const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
      if(next[static_cast<std::size_t>(a)] != -1)
        return partition; // not a simple loop
      next[static_cast<std::size_t>(a)] = b;
      ++loop_edges;
      if(start == -1 || a < start)
        start = a;
    }
  }
  int v = start;
  do
  {
    partition.loop.push_back(v);
    v = next[static_cast<std::size_t>(v)];
  } while(v != start && v != -1 && partition.loop.size() <= loop_edges);
  if(v != start || partition.loop.size() != loop_edges || loop_edges < 3)
  {
    partition.loop.clear();
    return partition;
  }

  partition.face_in_disk_a = disk.in_disk();
  partition.valid = true;
  return partition;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_TWO_DISK_PARTITION_H
