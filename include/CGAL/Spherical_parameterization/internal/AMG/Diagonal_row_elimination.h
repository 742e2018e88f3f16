// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Elimination of the rows that hold only a diagonal entry, such as the border rows of CGAL's
// Fixed_border_parameterizer_3: their values are known and move to the right-hand side, so that the uniform and
// cotangent systems of the interior become symmetric. Rows with a negative diagonal are negated, so that the
// reduced matrix of such systems is positive definite.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIAGONAL_ROW_ELIMINATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIAGONAL_ROW_ELIMINATION_H

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

class Diagonal_row_elimination
{
public:
  typedef Eigen::SparseMatrix<double, Eigen::ColMajor, int> Eigen_matrix;

  // Splits the rows of the square matrix E into eliminated ones and the reduced system, read directly from
  // Eigen's column-major storage; columns come out sorted. false on a non-finite entry or a zero diagonal entry.
  bool eliminate(const Eigen_matrix& E, Compressed_row_matrix& reduced)
  {
    const Index n = Index(E.rows());
    const int* outer = E.outerIndexPtr();
    const int* inner = E.innerIndexPtr();
    const double* value = E.valuePtr();
    m_size = std::size_t(n);

    std::vector<double> diagonal(n, 0.);
    std::vector<char> has_off_diagonal(n, 0);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        if(!std::isfinite(value[k]))
          return false;
        if(inner[k] == j)
          diagonal[j] += value[k];
        else if(value[k] != 0.)
          has_off_diagonal[inner[k]] = 1;
      }

    std::vector<Index> reduced_index(n, -1), eliminated_ordinal(n, -1);
    m_original_index.clear();
    m_eliminated_index.clear();
    m_eliminated_diagonal.clear();
    m_row_sign.clear();
    for(Index i = 0; i < n; ++i)
    {
      if(diagonal[i] == 0.)
        return false; // zero diagonal entry: singular, or not a system this solver handles
      if(has_off_diagonal[i])
      {
        reduced_index[i] = Index(m_original_index.size());
        m_original_index.push_back(i);
        m_row_sign.push_back(diagonal[i] < 0. ? -1. : 1.);
      }
      else
      {
        eliminated_ordinal[i] = Index(m_eliminated_index.size());
        m_eliminated_index.push_back(i);
        m_eliminated_diagonal.push_back(diagonal[i]);
      }
    }
    const Index m = Index(m_original_index.size());
    m_identity = (m == n) && std::find(m_row_sign.begin(), m_row_sign.end(), -1.) == m_row_sign.end();

    reduced = Compressed_row_matrix();
    reduced.number_of_rows = reduced.number_of_columns = m;
    reduced.row_start.assign(std::size_t(m) + 1, 0);
    Compressed_row_matrix& coupling = m_coupling;
    coupling = Compressed_row_matrix();
    coupling.number_of_rows = m;
    coupling.number_of_columns = Index(m_eliminated_index.size());
    coupling.row_start.assign(std::size_t(m) + 1, 0);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        const Index r = reduced_index[inner[k]];
        if(r < 0 || (value[k] == 0. && inner[k] != j))
          continue;
        if(reduced_index[j] >= 0)
          ++reduced.row_start[r + 1];
        else
          ++coupling.row_start[r + 1];
      }
    for(Index r = 0; r < m; ++r)
    {
      reduced.row_start[r + 1] += reduced.row_start[r];
      coupling.row_start[r + 1] += coupling.row_start[r];
    }
    reduced.column.resize(reduced.row_start.back());
    reduced.value.resize(reduced.row_start.back());
    coupling.column.resize(coupling.row_start.back());
    coupling.value.resize(coupling.row_start.back());
    std::vector<Index> next_reduced(reduced.row_start.begin(), reduced.row_start.end() - 1);
    std::vector<Index> next_coupling(coupling.row_start.begin(), coupling.row_start.end() - 1);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        const Index r = reduced_index[inner[k]];
        if(r < 0 || (value[k] == 0. && inner[k] != j))
          continue;
        const double signed_value = m_row_sign[r] * value[k];
        if(reduced_index[j] >= 0)
        {
          const Index p = next_reduced[r]++;
          reduced.column[p] = reduced_index[j];
          reduced.value[p] = signed_value;
        }
        else
        {
          const Index p = next_coupling[r]++;
          coupling.column[p] = eliminated_ordinal[j];
          coupling.value[p] = signed_value;
        }
      }
    return true;
  }

  // Number of rows of the full system.
  std::size_t size() const { return m_size; }
  std::size_t number_of_eliminated_rows() const { return m_eliminated_index.size(); }
  // Nothing eliminated or negated: the reduced system is the full one.
  bool is_identity() const { return m_identity; }

  // The reduced right-hand side b of the full one B; the known values are kept for expand().
  void reduce(const double* B, std::vector<double>& b)
  {
    m_known_values.resize(m_eliminated_index.size());
    for(std::size_t e = 0; e < m_eliminated_index.size(); ++e)
      m_known_values[e] = B[m_eliminated_index[e]] / m_eliminated_diagonal[e];
    const Index m = m_coupling.number_of_rows;
    b.resize(m);
    for(Index r = 0; r < m; ++r)
    {
      double value = m_row_sign[r] * B[m_original_index[r]];
      for(Index k = m_coupling.row_start[r]; k < m_coupling.row_start[r + 1]; ++k)
        value -= m_coupling.value[k] * m_known_values[m_coupling.column[k]];
      b[r] = value;
    }
  }

  // The full solution X from the reduced one x and the known values of the last reduce().
  void expand(const double* x, double* X) const
  {
    for(std::size_t e = 0; e < m_eliminated_index.size(); ++e)
      X[m_eliminated_index[e]] = m_known_values[e];
    for(std::size_t r = 0; r < m_original_index.size(); ++r)
      X[m_original_index[r]] = x[r];
  }

private:
  std::size_t m_size = 0;
  std::vector<Index> m_original_index;   // of each reduced unknown
  std::vector<Index> m_eliminated_index; // rows with only a diagonal entry
  std::vector<double> m_eliminated_diagonal;
  std::vector<double> m_row_sign;   // of each reduced row: -1 where the diagonal was negative
  Compressed_row_matrix m_coupling; // reduced rows x eliminated unknowns
  bool m_identity = false;
  std::vector<double> m_known_values; // of the eliminated unknowns, for the last right-hand side
};

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_DIAGONAL_ROW_ELIMINATION_H
