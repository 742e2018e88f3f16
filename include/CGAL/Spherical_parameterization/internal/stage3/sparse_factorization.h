// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The sparse factorizations of stage 3's steps. Successive steps share a matrix pattern, and ordering a pattern
// (METIS, COLAMD) is a large part of a factorization: it is done once per pattern (ordering at every step was slow,
// see the manual's Method section).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SPARSE_FACTORIZATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SPARSE_FACTORIZATION_H

#include <CGAL/Spherical_parameterization/internal/deferred_stop_signals.h>

#include <iostream> // Eigen/MetisSupport uses std::cerr without including it

#include <Eigen/MetisSupport>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// `Solver` (an Eigen sparse factorization) whose pattern analysis is redone only when the pattern changes, as told by
// its size and number of non-zeros.
template <class Solver>
class Pattern_reusing_factorization
{
public:
  bool factorize(const Eigen::SparseMatrix<double>& A)
  {
    if(!m_analyzed || A.rows() != m_rows || A.nonZeros() != m_nonzeros)
    {
      const Metis_call_guard metis_call; // METIS may order the unknowns (see deferred_stop_signals.h)
      m_solver.analyzePattern(A);
      m_analyzed = true;
      m_rows = A.rows();
      m_nonzeros = A.nonZeros();
    }
    m_solver.factorize(A);
    return m_solver.info() == Eigen::Success;
  }

  // The factorization, for its solve() and transpose().solve() (Eigen's SparseLU::transpose() is not const).
  Solver& solver() { return m_solver; }

private:
  Solver m_solver;
  bool m_analyzed = false;
  Eigen::Index m_rows = 0, m_nonzeros = 0;
};

using Sparse_ldlt = Pattern_reusing_factorization<
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::MetisOrdering<int>>>;
using Sparse_lu =
    Pattern_reusing_factorization<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>;

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_SPARSE_FACTORIZATION_H
