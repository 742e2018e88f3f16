// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The direct solver AMG_solver_traits hands small systems to, where it is faster than a multigrid setup:
// Eigen::SimplicialLDLT for symmetric matrices, Eigen::SparseLU otherwise.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIRECT_SOLVER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIRECT_SOLVER_H

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

class Direct_solver
{
public:
  typedef Eigen::SparseMatrix<double, Eigen::ColMajor, int> Eigen_matrix;

  void clear()
  {
    m_ldlt.reset();
    m_lu.reset();
    m_matrix.clear_and_release();
  }

  // Keeps A (for the residuals of the refinement) and factors it; an empty matrix needs no factor.
  bool factor(Compressed_row_matrix&& A, bool symmetric)
  {
    clear();
    m_matrix = std::move(A);
    if(m_matrix.number_of_rows == 0)
      return true;
    const Compressed_row_matrix& R = m_matrix;
    Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> map(
        R.number_of_rows, R.number_of_columns, Index(R.number_of_nonzeros()), R.row_start.data(), R.column.data(),
        R.value.data());
    const Eigen_matrix matrix = map;
    if(symmetric)
    {
      m_ldlt.reset(new Eigen::SimplicialLDLT<Eigen_matrix>(matrix));
      return m_ldlt->info() == Eigen::Success;
    }
    m_lu.reset(new Eigen::SparseLU<Eigen_matrix>(matrix));
    return m_lu->info() == Eigen::Success;
  }

  const Compressed_row_matrix& matrix() const { return m_matrix; }

  // Direct solve plus up to two steps of iterative refinement, so that the tolerance of the multigrid path holds
  // here too; `iterations` counts the refinement steps.
  Krylov_result solve(const double* b_data, double* x_data, double target, double reference_norm)
  {
    Krylov_result result;
    const Compressed_row_matrix& A = m_matrix;
    const Index m = A.number_of_rows;
    Eigen::Map<const Eigen::VectorXd> b(b_data, m);
    Eigen::Map<Eigen::VectorXd> x(x_data, m);
    m_residual.resize(m);
    Eigen::Map<Eigen::VectorXd> residual(m_residual.data(), m);
    auto direct_solve = [this](const auto& rhs) -> Eigen::VectorXd {
      return m_ldlt ? Eigen::VectorXd(m_ldlt->solve(rhs)) : Eigen::VectorXd(m_lu->solve(rhs));
    };
    x = direct_solve(b);
    for(int step = 0;; ++step)
    {
      internal::AMG::residual(A, x.data(), b.data(), residual.data());
      const double residual_norm = residual.norm();
      result.relative_residual = residual_norm / reference_norm;
      if(!std::isfinite(residual_norm))
        return result;
      if(residual_norm <= target)
      {
        result.converged = true;
        return result;
      }
      if(step == 2)
        return result;
      x += direct_solve(residual);
      ++result.iterations;
    }
  }

private:
  Compressed_row_matrix m_matrix;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen_matrix>> m_ldlt;
  std::unique_ptr<Eigen::SparseLU<Eigen_matrix>> m_lu;
  std::vector<double> m_residual;
};

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIRECT_SOLVER_H
