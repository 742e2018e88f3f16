// Copyright (c) 2024
// SPDX-License-Identifier: GPL-3.0-or-later
//
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
  std::vector<Index> row_start;   // size number_of_rows + 1
  std::vector<Index> column;      // sorted within each row
  std::vector<double> value;

  std::size_t number_of_nonzeros() const { return column.size(); }

  std::size_t memory_bytes() const
  {
    return row_start.capacity() * sizeof(Index) + column.capacity() * sizeof(Index)
         + value.capacity() * sizeof(double);
  }

  void clear_and_release()
  {
    Compressed_row_matrix empty;
    std::swap(*this, empty);
  }
};

// y = A x
inline void multiply(const Compressed_row_matrix& A, const double* x, double* y)
{
  const Index* row_start = A.row_start.data();
  const Index* column = A.column.data();
  const double* value = A.value.data();
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    double sum = 0.;
    for(Index k = row_start[i]; k < row_start[i + 1]; ++k)
      sum += value[k] * x[column[k]];
    y[i] = sum;
  }
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
  const Index* row_start = A.row_start.data();
  const Index* column = A.column.data();
  const double* value = A.value.data();
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    double sum = 0.;
    for(Index k = row_start[i]; k < row_start[i + 1]; ++k)
      sum += value[k] * x[column[k]];
    y[i] += sum;
  }
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

// C = A B (Gustavson's row-by-row product with a dense accumulator).
// Two passes (structure, then values) so that no array is ever reallocated.
inline Compressed_row_matrix multiply(const Compressed_row_matrix& A, const Compressed_row_matrix& B)
{
  Compressed_row_matrix C;
  C.number_of_rows = A.number_of_rows;
  C.number_of_columns = B.number_of_columns;
  C.row_start.assign(std::size_t(C.number_of_rows) + 1, 0);

  std::vector<Index> last_row_seen(B.number_of_columns, -1);
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    Index count = 0;
    for(Index ka = A.row_start[i]; ka < A.row_start[i + 1]; ++ka)
    {
      const Index j = A.column[ka];
      for(Index kb = B.row_start[j]; kb < B.row_start[j + 1]; ++kb)
      {
        const Index c = B.column[kb];
        if(last_row_seen[c] != i)
        {
          last_row_seen[c] = i;
          ++count;
        }
      }
    }
    C.row_start[i + 1] = C.row_start[i] + count;
  }

  C.column.resize(C.row_start.back());
  C.value.resize(C.row_start.back());
  std::vector<Index> position_in_row(B.number_of_columns, -1);
  std::vector<std::pair<Index, double>> row;
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    const Index begin = C.row_start[i];
    Index end = begin;
    for(Index ka = A.row_start[i]; ka < A.row_start[i + 1]; ++ka)
    {
      const Index j = A.column[ka];
      const double a = A.value[ka];
      for(Index kb = B.row_start[j]; kb < B.row_start[j + 1]; ++kb)
      {
        const Index c = B.column[kb];
        Index p = position_in_row[c];
        if(p < begin)
        {
          p = end++;
          position_in_row[c] = p;
          C.column[p] = c;
          C.value[p] = 0.;
        }
        C.value[p] += a * B.value[kb];
      }
    }
    // Sorted columns keep the smoother's memory accesses monotone.
    if(!std::is_sorted(C.column.begin() + begin, C.column.begin() + end))
    {
      row.clear();
      for(Index p = begin; p < end; ++p)
        row.emplace_back(C.column[p], C.value[p]);
      std::sort(row.begin(), row.end(),
                [](const auto& l, const auto& r) { return l.first < r.first; });
      for(Index p = begin; p < end; ++p)
      {
        C.column[p] = row[p - begin].first;
        C.value[p] = row[p - begin].second;
      }
    }
  }
  return C;
}

inline bool all_values_finite(const Compressed_row_matrix& A)
{
  for(double v : A.value)
    if(!std::isfinite(v))
      return false;
  return true;
}

// Same structure and |a_ij - a_ji| <= relative_tolerance * max(|a_ij|, |a_ji|) everywhere.
inline bool is_numerically_symmetric(const Compressed_row_matrix& A, double relative_tolerance)
{
  if(A.number_of_rows != A.number_of_columns)
    return false;
  const Compressed_row_matrix T = transpose(A);
  if(T.row_start != A.row_start || T.column != A.column)
  {
    // Explicit zeros may break structural symmetry: fall back to a value check through a search.
    for(Index i = 0; i < A.number_of_rows; ++i)
      for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
      {
        const Index j = A.column[k];
        const auto first = T.column.begin() + T.row_start[i];
        const auto last = T.column.begin() + T.row_start[i + 1];
        const auto it = std::lower_bound(first, last, j);
        const double transposed = (it != last && *it == j) ? T.value[it - T.column.begin()] : 0.;
        if(std::abs(A.value[k] - transposed)
           > relative_tolerance * std::max(std::abs(A.value[k]), std::abs(transposed)))
          return false;
      }
    // Entries of A^T absent from A.
    for(Index i = 0; i < T.number_of_rows; ++i)
      for(Index k = T.row_start[i]; k < T.row_start[i + 1]; ++k)
      {
        const Index j = T.column[k];
        const auto first = A.column.begin() + A.row_start[i];
        const auto last = A.column.begin() + A.row_start[i + 1];
        const auto it = std::lower_bound(first, last, j);
        if((it == last || *it != j) && T.value[k] != 0.)
          return false;
      }
    return true;
  }
  for(std::size_t k = 0; k < A.value.size(); ++k)
    if(std::abs(A.value[k] - T.value[k])
       > relative_tolerance * std::max(std::abs(A.value[k]), std::abs(T.value[k])))
      return false;
  return true;
}

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_COMPRESSED_ROW_MATRIX_H
