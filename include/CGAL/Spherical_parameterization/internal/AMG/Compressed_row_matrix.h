// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Compressed sparse row matrix and the few kernels the algebraic multigrid needs.
// Flat arrays and 32-bit indices: the kernels are memory bound, so smaller is faster.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_COMPRESSED_ROW_MATRIX_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_COMPRESSED_ROW_MATRIX_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

using Index = int;

struct Compressed_row_matrix
{
  Index number_of_rows = 0;
  Index number_of_columns = 0;
  std::vector<Index> row_start; // size number_of_rows + 1
  std::vector<Index> column;    // sorted within each row
  std::vector<double> value;

  std::size_t number_of_nonzeros() const { return column.size(); }

  std::size_t memory_bytes() const
  {
    return row_start.capacity() * sizeof(Index) + column.capacity() * sizeof(Index) + value.capacity() * sizeof(double);
  }

  void clear_and_release()
  {
    Compressed_row_matrix empty;
    std::swap(*this, empty);
  }
};

// (A x)_i
inline double row_product(const Compressed_row_matrix& A, Index i, const double* x)
{
  const Index* column = A.column.data();
  const double* value = A.value.data();
  double sum = 0.;
  for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
    sum += value[k] * x[column[k]];
  return sum;
}

// y = A x
inline void multiply(const Compressed_row_matrix& A, const double* x, double* y)
{
  for(Index i = 0; i < A.number_of_rows; ++i)
    y[i] = row_product(A, i, x);
}

// r = b - A x
inline void residual(const Compressed_row_matrix& A, const double* x, const double* b, double* r)
{
  const Index* row_start = A.row_start.data();
  const Index* column = A.column.data();
  const double* value = A.value.data();
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    double sum = b[i];
    for(Index k = row_start[i]; k < row_start[i + 1]; ++k)
      sum -= value[k] * x[column[k]];
    r[i] = sum;
  }
}

// y += A x
inline void multiply_add(const Compressed_row_matrix& A, const double* x, double* y)
{
  for(Index i = 0; i < A.number_of_rows; ++i)
    y[i] += row_product(A, i, x);
}

// Counting-sort transpose: columns of the result come out sorted.
inline Compressed_row_matrix transpose(const Compressed_row_matrix& A)
{
  Compressed_row_matrix T;
  T.number_of_rows = A.number_of_columns;
  T.number_of_columns = A.number_of_rows;
  T.row_start.assign(std::size_t(T.number_of_rows) + 1, 0);
  for(Index c : A.column)
    ++T.row_start[c + 1];
  for(Index i = 0; i < T.number_of_rows; ++i)
    T.row_start[i + 1] += T.row_start[i];
  T.column.resize(A.number_of_nonzeros());
  T.value.resize(A.number_of_nonzeros());
  std::vector<Index> next(T.row_start.begin(), T.row_start.end() - 1);
  for(Index i = 0; i < A.number_of_rows; ++i)
    for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
    {
      const Index position = next[A.column[k]]++;
      T.column[position] = i;
      T.value[position] = A.value[k];
    }
  return T;
}

// y += P^T x, without forming P^T (restriction in the V-cycle).
inline void multiply_transpose_add(const Compressed_row_matrix& P, const double* x, double* y)
{
  const Index* row_start = P.row_start.data();
  const Index* column = P.column.data();
  const double* value = P.value.data();
  for(Index i = 0; i < P.number_of_rows; ++i)
  {
    const double xi = x[i];
    for(Index k = row_start[i]; k < row_start[i + 1]; ++k)
      y[column[k]] += value[k] * xi;
  }
}

// Sorts the entries of each row by column (rows are short: insertion sort, in place, no allocation).
inline void sort_rows(Compressed_row_matrix& A)
{
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    const Index begin = A.row_start[i], end = A.row_start[i + 1];
    for(Index p = begin + 1; p < end; ++p)
    {
      const Index c = A.column[p];
      const double v = A.value[p];
      Index q = p;
      for(; q > begin && A.column[q - 1] > c; --q)
      {
        A.column[q] = A.column[q - 1];
        A.value[q] = A.value[q - 1];
      }
      A.column[q] = c;
      A.value[q] = v;
    }
  }
}

// Galerkin coarse operator P^T A P, one coarse row at a time: the intermediate product A P is never stored,
// which bounds the setup's peak memory, for about the same number of operations as (P^T (A P)).
// A first pass counts the entries so that no array is reallocated.
inline Compressed_row_matrix galerkin_product(const Compressed_row_matrix& A, const Compressed_row_matrix& P)
{
  const Compressed_row_matrix Pt = transpose(P);
  const Index nc = P.number_of_columns;
  Compressed_row_matrix C;
  C.number_of_rows = C.number_of_columns = nc;
  C.row_start.assign(std::size_t(nc) + 1, 0);

  std::vector<Index> marker(nc, -1);
  for(Index I = 0; I < nc; ++I)
  {
    Index count = 0;
    for(Index kt = Pt.row_start[I]; kt < Pt.row_start[I + 1]; ++kt)
    {
      const Index i = Pt.column[kt];
      for(Index ka = A.row_start[i]; ka < A.row_start[i + 1]; ++ka)
      {
        const Index j = A.column[ka];
        for(Index kp = P.row_start[j]; kp < P.row_start[j + 1]; ++kp)
        {
          const Index J = P.column[kp];
          if(marker[J] != I)
          {
            marker[J] = I;
            ++count;
          }
        }
      }
    }
    C.row_start[I + 1] = C.row_start[I] + count;
  }

  C.column.resize(C.row_start.back());
  C.value.resize(C.row_start.back());
  std::vector<Index>& position = marker; // reused: positions of earlier rows are below the current begin
  std::fill(position.begin(), position.end(), -1);
  for(Index I = 0; I < nc; ++I)
  {
    const Index begin = C.row_start[I];
    Index end = begin;
    for(Index kt = Pt.row_start[I]; kt < Pt.row_start[I + 1]; ++kt)
    {
      const Index i = Pt.column[kt];
      const double r = Pt.value[kt];
      for(Index ka = A.row_start[i]; ka < A.row_start[i + 1]; ++ka)
      {
        const Index j = A.column[ka];
        const double ra = r * A.value[ka];
        for(Index kp = P.row_start[j]; kp < P.row_start[j + 1]; ++kp)
        {
          const Index J = P.column[kp];
          Index p = position[J];
          if(p < begin)
          {
            p = end++;
            position[J] = p;
            C.column[p] = J;
            C.value[p] = 0.;
          }
          C.value[p] += ra * P.value[kp];
        }
      }
    }
  }
  sort_rows(C);
  return C;
}

inline bool all_values_finite(const Compressed_row_matrix& A)
{
  for(double v : A.value)
    if(!std::isfinite(v))
      return false;
  return true;
}

// |a_ij - a_ji| <= relative_tolerance * max(|a_ij|, |a_ji|) for all i, j (a missing entry is zero).
// Binary searches in the sorted rows instead of a transposed copy: no extra memory.
inline bool is_numerically_symmetric(const Compressed_row_matrix& A, double relative_tolerance)
{
  if(A.number_of_rows != A.number_of_columns)
    return false;
  auto find = [&A](Index i, Index j) -> double {
    const auto first = A.column.begin() + A.row_start[i];
    const auto last = A.column.begin() + A.row_start[i + 1];
    const auto it = std::lower_bound(first, last, j);
    return (it != last && *it == j) ? A.value[it - A.column.begin()] : 0.;
  };
  for(Index i = 0; i < A.number_of_rows; ++i)
    for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
    {
      const Index j = A.column[k];
      if(j == i)
        continue;
      // Each pair is checked from both rows, which also catches an entry missing on one side.
      const double transposed = find(j, i);
      if(std::abs(A.value[k] - transposed) > relative_tolerance * std::max(std::abs(A.value[k]), std::abs(transposed)))
        return false;
    }
  return true;
}

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_COMPRESSED_ROW_MATRIX_H
