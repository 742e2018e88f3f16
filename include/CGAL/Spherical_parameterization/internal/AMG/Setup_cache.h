// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// What a setup of AMG_solver_traits was computed from, so that a call with the same matrix and setup parameters
// reuses it: the u and v solves of a parameterization then cost one setup. The matrix is compared through its
// sizes and a hash of its compressed arrays (structure and values), which costs one pass over them instead of a
// copy of the matrix.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_SETUP_CACHE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_SETUP_CACHE_H

#include <CGAL/Spherical_parameterization/internal/AMG/Ruge_stueben_hierarchy.h>

#include <Eigen/Sparse>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

struct Matrix_fingerprint
{
  std::size_t rows = 0, columns = 0, nonzeros = 0;
  std::uint64_t hash = 0;

  bool operator==(const Matrix_fingerprint& o) const
  {
    return rows == o.rows && columns == o.columns && nonzeros == o.nonzeros && hash == o.hash;
  }
};

inline std::uint64_t hash_words(std::uint64_t hash, const void* data, std::size_t bytes)
{
  const unsigned char* p = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for(; i + 8 <= bytes; i += 8)
  {
    std::uint64_t word;
    std::memcpy(&word, p + i, 8);
    hash = (hash ^ word) * 0x100000001b3ULL;
    hash ^= hash >> 29;
  }
  for(; i < bytes; ++i)
    hash = (hash ^ p[i]) * 0x100000001b3ULL;
  return hash;
}

// E must be compressed: the hash reads its three arrays.
inline Matrix_fingerprint fingerprint_of(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& E)
{
  Matrix_fingerprint f;
  f.rows = std::size_t(E.rows());
  f.columns = std::size_t(E.cols());
  f.nonzeros = std::size_t(E.nonZeros());
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  hash = hash_words(hash, E.outerIndexPtr(), sizeof(int) * (std::size_t(E.outerSize()) + 1));
  hash = hash_words(hash, E.innerIndexPtr(), sizeof(int) * f.nonzeros);
  hash = hash_words(hash, E.valuePtr(), sizeof(double) * f.nonzeros);
  f.hash = hash;
  return f;
}

// Everything a setup depends on: the matrix, the hierarchy's parameters, and the traits' choice of the symmetry
// test and of the direct solver. The solve parameters (tolerance, Krylov method...) are not part of it.
struct Setup_key
{
  Matrix_fingerprint matrix;
  Hierarchy_parameters hierarchy;
  double symmetry_tolerance = 0.;
  std::size_t direct_solver_threshold = 0;
  std::size_t direct_solver_threshold_non_symmetric = 0;

  bool operator==(const Setup_key& o) const
  {
    return matrix == o.matrix && hierarchy == o.hierarchy && symmetry_tolerance == o.symmetry_tolerance
           && direct_solver_threshold == o.direct_solver_threshold
           && direct_solver_threshold_non_symmetric == o.direct_solver_threshold_non_symmetric;
  }
};

// The key of the last setup and whether it succeeded; a failed setup is not retried with the same key.
class Setup_cache
{
public:
  bool holds(const Setup_key& key) const { return m_has_setup && m_key == key; }
  bool has_setup() const { return m_has_setup; }
  bool succeeded() const { return m_succeeded; }

  // Counts as failed until finish(): a setup that throws leaves no half-built state marked usable.
  void start(const Setup_key& key)
  {
    m_key = key;
    m_has_setup = true;
    m_succeeded = false;
  }
  void finish(bool succeeded) { m_succeeded = succeeded; }

private:
  bool m_has_setup = false;
  bool m_succeeded = false;
  Setup_key m_key;
};

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_SETUP_CACHE_H
