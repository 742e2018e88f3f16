// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Classical (Ruge-Stueben) algebraic multigrid: strength of connection, C/F splitting,
// classical interpolation, Galerkin coarse operators, and the V-cycle with Gauss-Seidel smoothing.
// References: J. W. Ruge, K. Stueben, "Algebraic multigrid", in Multigrid Methods, SIAM 1987;
// K. Stueben, "An introduction to algebraic multigrid", Appendix A of Trottenberg et al., Multigrid, 2001.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_RUGE_STUEBEN_HIERARCHY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_RUGE_STUEBEN_HIERARCHY_H

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>

#include <CGAL/assertions.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

// Setup parameters of the hierarchy (AMG_solver_traits::Parameters holds one and documents it).
struct Hierarchy_parameters
{
  double strength_threshold = 0.25; // j strongly influences i if -a_ij >= theta max_k(-a_ik)
  int max_coarse_size = 200;        // coarsening stops at this number of unknowns, solved directly
  int max_levels = 25;              // the finest included
  int pre_smoothing_sweeps = 1;     // forward Gauss-Seidel sweeps before the coarse-grid correction
  int post_smoothing_sweeps = 1;    // backward Gauss-Seidel sweeps after it

  bool operator==(const Hierarchy_parameters& o) const
  {
    return strength_threshold == o.strength_threshold && max_coarse_size == o.max_coarse_size
           && max_levels == o.max_levels && pre_smoothing_sweeps == o.pre_smoothing_sweeps
           && post_smoothing_sweeps == o.post_smoothing_sweeps;
  }
  bool operator!=(const Hierarchy_parameters& o) const { return !(*this == o); }
};

// Sparsity pattern only (the strength graph has no values).
struct Compressed_row_pattern
{
  Index number_of_rows = 0;
  std::vector<Index> row_start;
  std::vector<Index> column;

  Index begin(Index i) const { return row_start[i]; }
  Index end(Index i) const { return row_start[i + 1]; }
};

inline Compressed_row_pattern transpose(const Compressed_row_pattern& S)
{
  Compressed_row_pattern T;
  T.number_of_rows = S.number_of_rows;
  T.row_start.assign(std::size_t(S.number_of_rows) + 1, 0);
  for(Index c : S.column)
    ++T.row_start[c + 1];
  for(Index i = 0; i < T.number_of_rows; ++i)
    T.row_start[i + 1] += T.row_start[i];
  T.column.resize(S.column.size());
  std::vector<Index> next(T.row_start.begin(), T.row_start.end() - 1);
  for(Index i = 0; i < S.number_of_rows; ++i)
    for(Index k = S.begin(i); k < S.end(i); ++k)
      T.column[next[S.column[k]]++] = i;
  return T;
}

// Row i of S lists the points j that strongly influence i:
// -a_ij >= threshold * max_k(-a_ik) in rows whose off-diagonals are all non-positive (M-matrix rows),
// |a_ij| >= threshold * max_k |a_ik| in rows that also have positive off-diagonals.
inline Compressed_row_pattern strength_of_connection(const Compressed_row_matrix& A, double threshold)
{
  // Calls on_strong(j) for each j strongly influencing i.
  auto for_each_strong = [&A, threshold](Index i, auto&& on_strong) {
    bool has_positive_off_diagonal = false;
    double largest_negative = 0., largest_absolute = 0.;
    for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
    {
      if(A.column[k] == i)
        continue;
      const double a = A.value[k];
      has_positive_off_diagonal |= (a > 0.);
      largest_negative = std::max(largest_negative, -a);
      largest_absolute = std::max(largest_absolute, std::abs(a));
    }
    if(has_positive_off_diagonal)
    {
      const double bound = threshold * largest_absolute;
      for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
        if(A.column[k] != i && std::abs(A.value[k]) >= bound && A.value[k] != 0.)
          on_strong(A.column[k]);
    }
    else if(largest_negative > 0.)
    {
      const double bound = threshold * largest_negative;
      for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
        if(A.column[k] != i && -A.value[k] >= bound)
          on_strong(A.column[k]);
    }
  };

  // Count, then fill: the pattern is allocated once at its exact size.
  Compressed_row_pattern S;
  S.number_of_rows = A.number_of_rows;
  S.row_start.assign(std::size_t(A.number_of_rows) + 1, 0);
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    Index count = 0;
    for_each_strong(i, [&count](Index) { ++count; });
    S.row_start[i + 1] = S.row_start[i] + count;
  }
  S.column.resize(S.row_start.back());
  for(Index i = 0; i < A.number_of_rows; ++i)
  {
    Index position = S.row_start[i];
    for_each_strong(i, [&](Index j) { S.column[position++] = j; });
  }
  return S;
}

enum Point_type : signed char
{
  UNDECIDED = 0,
  COARSE_POINT = 1,
  FINE_POINT = -1
};

// Buckets of undecided points keyed by their measure, with O(1) move and O(1) amortized max extraction.
class Measure_buckets
{
public:
  Measure_buckets(Index number_of_points, Index largest_measure)
    : m_head(std::size_t(largest_measure) + 1, -1), m_next(number_of_points, -1), m_previous(number_of_points, -1),
      m_measure(number_of_points, 0), m_top(-1)
  {}

  void insert(Index i, Index measure)
  {
    m_measure[i] = measure;
    m_previous[i] = -1;
    m_next[i] = m_head[measure];
    if(m_head[measure] >= 0)
      m_previous[m_head[measure]] = i;
    m_head[measure] = i;
    m_top = std::max(m_top, measure);
  }

  void remove(Index i)
  {
    if(m_previous[i] >= 0)
      m_next[m_previous[i]] = m_next[i];
    else
      m_head[m_measure[i]] = m_next[i];
    if(m_next[i] >= 0)
      m_previous[m_next[i]] = m_previous[i];
  }

  void change_measure(Index i, Index delta)
  {
    remove(i);
    insert(i, m_measure[i] + delta);
  }

  // Point of largest measure, -1 when empty.
  Index top()
  {
    while(m_top >= 0 && m_head[m_top] < 0)
      --m_top;
    return m_top >= 0 ? m_head[m_top] : -1;
  }

private:
  std::vector<Index> m_head, m_next, m_previous, m_measure;
  Index m_top;
};

// Classical C/F splitting. First pass: greedy maximal independent set by the measure
// lambda_i = number of undecided points i strongly influences + 2 * number of such F points.
// Second pass: every strong F-F connection must share a common C point (criterion 1, enforced strictly).
inline std::vector<signed char> split_coarse_fine(const Compressed_row_pattern& S, const Compressed_row_pattern& ST)
{
  const Index n = S.number_of_rows;
  std::vector<signed char> type(n, UNDECIDED);

  Index largest_influence = 0;
  for(Index i = 0; i < n; ++i)
    largest_influence = std::max(largest_influence, ST.end(i) - ST.begin(i));

  // A measure can at most double: each point it influences becomes F once.
  Measure_buckets buckets(n, 2 * largest_influence + 1);
  for(Index i = 0; i < n; ++i)
  {
    // Points neither influencing nor depending on anything are left to the smoother.
    if(S.begin(i) == S.end(i) && ST.begin(i) == ST.end(i))
      type[i] = FINE_POINT;
    else
      buckets.insert(i, ST.end(i) - ST.begin(i));
  }

  for(Index i = buckets.top(); i >= 0; i = buckets.top())
  {
    type[i] = COARSE_POINT;
    buckets.remove(i);
    for(Index k = ST.begin(i); k < ST.end(i); ++k)
    {
      const Index j = ST.column[k];
      if(type[j] != UNDECIDED)
        continue;
      type[j] = FINE_POINT;
      buckets.remove(j);
      // The new F point j needs C points among those it depends on: make them more attractive.
      for(Index l = S.begin(j); l < S.end(j); ++l)
        if(type[S.column[l]] == UNDECIDED)
          buckets.change_measure(S.column[l], +1);
    }
    // i no longer needs the points it depends on.
    for(Index k = S.begin(i); k < S.end(i); ++k)
      if(type[S.column[k]] == UNDECIDED)
        buckets.change_measure(S.column[k], -1);
  }

  std::vector<Index> marker(n, -1);
  for(Index i = 0; i < n; ++i)
  {
    if(type[i] != FINE_POINT)
      continue;
    for(Index k = S.begin(i); k < S.end(i); ++k)
      if(type[S.column[k]] == COARSE_POINT)
        marker[S.column[k]] = i;
    Index tentative_coarse_point = -1;
    for(Index k = S.begin(i); k < S.end(i); ++k)
    {
      const Index j = S.column[k];
      if(type[j] != FINE_POINT)
        continue;
      bool shares_coarse_point = false;
      for(Index l = S.begin(j); l < S.end(j) && !shares_coarse_point; ++l)
        shares_coarse_point = (marker[S.column[l]] == i);
      if(shares_coarse_point)
        continue;
      if(tentative_coarse_point >= 0)
      {
        // Two neighbours would need new C points: making i itself C is cheaper.
        type[tentative_coarse_point] = FINE_POINT;
        type[i] = COARSE_POINT;
        break;
      }
      tentative_coarse_point = j;
      type[j] = COARSE_POINT;
      marker[j] = i;
    }
  }
  return type;
}

// Classical interpolation (Ruge-Stueben, with the usual sign modification):
//   w_ij = -(a_ij + m_sum{k in F_i^s} a_ik a_kj / m_sum{m in C_i^s} a_km) / (a_ii + m_sum{weak k} a_ik)
// where only the entries a_km of sign opposite to a_kk are distributed; an F neighbour without such an entry
// towards C_i^s is lumped onto the diagonal.
inline Compressed_row_matrix classical_interpolation(const Compressed_row_matrix& A, const Compressed_row_pattern& S,
                                                     const std::vector<signed char>& type,
                                                     const std::vector<Index>& coarse_index,
                                                     Index number_of_coarse_points)
{
  const Index n = A.number_of_rows;
  Compressed_row_matrix P;
  P.number_of_rows = n;
  P.number_of_columns = number_of_coarse_points;
  P.row_start.assign(std::size_t(n) + 1, 0);
  for(Index i = 0; i < n; ++i)
  {
    Index count = 0;
    if(type[i] == COARSE_POINT)
      count = 1;
    else
      for(Index k = S.begin(i); k < S.end(i); ++k)
        count += (type[S.column[k]] == COARSE_POINT);
    P.row_start[i + 1] = P.row_start[i] + count;
  }
  P.column.resize(P.row_start.back());
  P.value.resize(P.row_start.back());

  std::vector<Index> strong_row(n, -1);    // strong_row[j] == i  <=>  j in S_i
  std::vector<Index> position_in_P(n, -1); // where C point j sits in the current row of P, or < begin
  std::vector<double> diagonal(n, 0.);
  for(Index i = 0; i < n; ++i)
    for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
      if(A.column[k] == i)
        diagonal[i] += A.value[k];

  for(Index i = 0; i < n; ++i)
  {
    const Index begin = P.row_start[i];
    if(type[i] == COARSE_POINT)
    {
      P.column[begin] = coarse_index[i];
      P.value[begin] = 1.;
      continue;
    }
    if(begin == P.row_start[i + 1])
      continue; // no strong C neighbour: the smoother alone takes care of this point

    Index end = begin;
    for(Index k = S.begin(i); k < S.end(i); ++k)
    {
      const Index j = S.column[k];
      strong_row[j] = i;
      if(type[j] == COARSE_POINT)
      {
        position_in_P[j] = end;
        P.column[end] = coarse_index[j];
        P.value[end] = 0.;
        ++end;
      }
    }

    double lumped_diagonal = 0.;
    for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
    {
      const Index j = A.column[k];
      const double a_ij = A.value[k];
      if(j == i || strong_row[j] != i)
      {
        lumped_diagonal += a_ij; // the diagonal itself and the weak connections
        continue;
      }
      if(type[j] == COARSE_POINT)
      {
        P.value[position_in_P[j]] += a_ij;
        continue;
      }
      // Strong F neighbour j: distribute a_ij over the common strong C points.
      const double sign_of_diagonal = diagonal[j] >= 0. ? 1. : -1.;
      double denominator = 0.;
      for(Index l = A.row_start[j]; l < A.row_start[j + 1]; ++l)
      {
        const Index m = A.column[l];
        const Index p = position_in_P[m];
        // Positions set for earlier rows are all below begin.
        if(p >= begin && type[m] == COARSE_POINT && A.value[l] * sign_of_diagonal < 0.)
          denominator += A.value[l];
      }
      if(denominator == 0.)
      {
        lumped_diagonal += a_ij;
        continue;
      }
      const double factor = a_ij / denominator;
      for(Index l = A.row_start[j]; l < A.row_start[j + 1]; ++l)
      {
        const Index m = A.column[l];
        const Index p = position_in_P[m];
        // Positions set for earlier rows are all below begin.
        if(p >= begin && type[m] == COARSE_POINT && A.value[l] * sign_of_diagonal < 0.)
          P.value[p] += factor * A.value[l];
      }
    }
    // A lumped diagonal of the wrong sign or near zero would blow up the weights: keep a_ii then.
    if(!(lumped_diagonal * diagonal[i] > 1e-3 * diagonal[i] * diagonal[i]))
      lumped_diagonal = diagonal[i];
    const double inverse = -1. / lumped_diagonal;
    for(Index p = begin; p < end; ++p)
      P.value[p] *= inverse;
  }
  return P;
}

// The multigrid hierarchy with its work vectors (allocated once, reused by every V-cycle).
class Ruge_stueben_hierarchy
{
public:
  struct Level
  {
    Compressed_row_matrix A; // once built, the diagonal entry comes first in each row, the others sorted
    Compressed_row_matrix P; // interpolation from the next coarser level; restriction is P^T
    std::vector<double> solution, right_hand_side; // of the coarse levels only
  };

  // Returns false when a diagonal entry is not positive or when the coarsest operator is singular.
  bool build(Compressed_row_matrix&& fine_matrix, const Hierarchy_parameters& parameters)
  {
    m_parameters = parameters;
    m_levels.clear();
    m_levels.emplace_back();
    m_levels.back().A = std::move(fine_matrix);

    while(m_levels.back().A.number_of_rows > std::max(parameters.max_coarse_size, 1)
          && int(m_levels.size()) < std::max(parameters.max_levels, 1))
    {
      Level& fine = m_levels.back();
      const Index n = fine.A.number_of_rows;
      std::vector<Index> coarse_index(n, -1);
      Index number_of_coarse_points = 0;
      Compressed_row_matrix P;
      {
        const Compressed_row_pattern S = strength_of_connection(fine.A, parameters.strength_threshold);
        std::vector<signed char> type;
        {
          const Compressed_row_pattern ST = transpose(S);
          type = split_coarse_fine(S, ST);
        }
        for(Index i = 0; i < n; ++i)
          if(type[i] == COARSE_POINT)
            coarse_index[i] = number_of_coarse_points++;
        // Coarsening stalled: a direct solve on this level is cheaper than more levels.
        if(number_of_coarse_points == 0 || number_of_coarse_points > Index(0.9 * n))
          break;
        P = classical_interpolation(fine.A, S, type, coarse_index, number_of_coarse_points);
      }
      Compressed_row_matrix coarse_matrix = galerkin_product(fine.A, P);
      fine.P = std::move(P);
      m_levels.emplace_back();
      m_levels.back().A = std::move(coarse_matrix);
    }

    for(std::size_t l = 0; l < m_levels.size(); ++l)
    {
      Level& level = m_levels[l];
      const Index n = level.A.number_of_rows;
      // The smoother finds the diagonal first in its row: no separate array of diagonals.
      for(Index i = 0; i < n; ++i)
      {
        const Index first = level.A.row_start[i];
        Index k = first;
        while(k < level.A.row_start[i + 1] && level.A.column[k] != i)
          ++k;
        if(k == level.A.row_start[i + 1] || !(level.A.value[k] > 0.) || !std::isfinite(level.A.value[k]))
          return false;
        std::swap(level.A.column[k], level.A.column[first]);
        std::swap(level.A.value[k], level.A.value[first]);
      }
      if(l > 0)
      {
        level.solution.assign(n, 0.);
        level.right_hand_side.assign(n, 0.);
      }
    }
    return setup_coarsest_solver();
  }

  std::size_t number_of_levels() const { return m_levels.size(); }
  const Level& level(std::size_t l) const { return m_levels[l]; }
  const Compressed_row_matrix& fine_matrix() const { return m_levels.front().A; }

  // x = M^{-1} b, with M^{-1} one V-cycle started from zero: a fixed linear operator,
  // symmetric when A is (forward Gauss-Seidel before, backward after, R = P^T).
  void apply_v_cycle(const double* b, double* x) { apply_v_cycle_block<1>(b, x); }

  // The same V-cycle for K right-hand sides at once, stored interleaved (entry c of row i at i * K + c): each level's
  // matrices are read once for all of them, which is where a V-cycle spends its time. Each column gets the
  // operations of apply_v_cycle.
  template <int K>
  void apply_v_cycle_block(const double* b, double* x)
  {
    const std::size_t n = static_cast<std::size_t>(m_levels.front().A.number_of_rows);
    for(std::size_t l = 1; l < m_levels.size(); ++l)
    {
      const std::size_t size = K * static_cast<std::size_t>(m_levels[l].A.number_of_rows);
      if(m_levels[l].solution.size() < size)
      {
        m_levels[l].solution.resize(size);
        m_levels[l].right_hand_side.resize(size);
      }
    }
    std::fill(x, x + K * n, 0.);
    v_cycle<K>(0, b, x);
  }

  std::size_t memory_bytes() const
  {
    std::size_t bytes = 0;
    for(const Level& l : m_levels)
      bytes += l.A.memory_bytes() + l.P.memory_bytes()
               + sizeof(double) * (l.solution.capacity() + l.right_hand_side.capacity());
    return bytes;
  }

private:
  typedef Eigen::SparseMatrix<double, Eigen::ColMajor, int> Eigen_sparse;

  bool setup_coarsest_solver()
  {
    const Compressed_row_matrix& A = m_levels.back().A;
    const Index n = A.number_of_rows;
    m_sparse_coarse_solver.reset();
    if(n <= 1000)
    {
      Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
      for(Index i = 0; i < n; ++i)
        for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
          dense(i, A.column[k]) += A.value[k];
      m_dense_coarse_solver.compute(dense);
      // A (numerically) singular coarsest operator means a singular system: report it instead of iterating.
      return m_dense_coarse_solver.rcond() > 1e-13;
    }
    Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> map(
        n, n, Index(A.number_of_nonzeros()), A.row_start.data(), A.column.data(), A.value.data());
    Eigen_sparse matrix = map;
    m_sparse_coarse_solver = std::make_shared<Eigen::SparseLU<Eigen_sparse>>();
    m_sparse_coarse_solver->compute(matrix);
    return m_sparse_coarse_solver->info() == Eigen::Success;
  }

  template <int K>
  void solve_coarsest(const double* b, double* x)
  {
    const Index n = m_levels.back().A.number_of_rows;
    typedef Eigen::Matrix<double, Eigen::Dynamic, K, K == 1 ? Eigen::ColMajor : Eigen::RowMajor> Block;
    Eigen::Map<const Block> rhs(b, n, K);
    Eigen::Map<Block> solution(x, n, K);
    const Eigen::Matrix<double, Eigen::Dynamic, K> columns = rhs; // the solvers want column-major storage
    Eigen::Matrix<double, Eigen::Dynamic, K> result;
    if(m_sparse_coarse_solver)
      result = m_sparse_coarse_solver->solve(columns);
    else
      result = m_dense_coarse_solver.solve(columns);
    solution = result;
  }

  // One Gauss-Seidel sweep on K interleaved columns, rows in increasing order (forward) or decreasing.
  template <int K, bool forward>
  static void gauss_seidel(const Level& level, const double* b, double* x)
  {
    const Compressed_row_matrix& A = level.A;
    const Index* row_start = A.row_start.data();
    const Index* column = A.column.data();
    const double* value = A.value.data();
    const Index n = A.number_of_rows;
    for(Index r = 0; r < n; ++r)
    {
      const Index i = forward ? r : n - 1 - r;
      double defect[K];
      for(int c = 0; c < K; ++c)
        defect[c] = b[K * i + c];
      for(Index k = row_start[i]; k < row_start[i + 1]; ++k)
      {
        const double a = value[k];
        const double* xj = x + K * column[k];
        for(int c = 0; c < K; ++c)
          defect[c] -= a * xj[c];
      }
      CGAL_assertion(column[row_start[i]] == i); // build() put the diagonal entry first in each row
      const double diagonal = value[row_start[i]];
      for(int c = 0; c < K; ++c)
        x[K * i + c] += defect[c] / diagonal;
    }
  }

  // coarse_b = P^T (b - A x), without storing the residual.
  template <int K>
  static void restrict_residual(const Level& level, const double* b, const double* x, double* coarse_b)
  {
    const Compressed_row_matrix& A = level.A;
    const Compressed_row_matrix& P = level.P;
    std::fill(coarse_b, coarse_b + K * static_cast<std::size_t>(P.number_of_columns), 0.);
    for(Index i = 0; i < A.number_of_rows; ++i)
    {
      double r[K];
      for(int c = 0; c < K; ++c)
        r[c] = b[K * i + c];
      for(Index k = A.row_start[i]; k < A.row_start[i + 1]; ++k)
        for(int c = 0; c < K; ++c)
          r[c] -= A.value[k] * x[K * A.column[k] + c];
      for(Index k = P.row_start[i]; k < P.row_start[i + 1]; ++k)
        for(int c = 0; c < K; ++c)
          coarse_b[K * P.column[k] + c] += P.value[k] * r[c];
    }
  }

  // x += P coarse_x on K interleaved columns.
  template <int K>
  static void interpolate_add(const Compressed_row_matrix& P, const double* coarse_x, double* x)
  {
    for(Index i = 0; i < P.number_of_rows; ++i)
    {
      double sum[K] = {};
      for(Index k = P.row_start[i]; k < P.row_start[i + 1]; ++k)
        for(int c = 0; c < K; ++c)
          sum[c] += P.value[k] * coarse_x[K * P.column[k] + c];
      for(int c = 0; c < K; ++c)
        x[K * i + c] += sum[c];
    }
  }

  // x must be zero on entry.
  template <int K>
  void v_cycle(std::size_t l, const double* b, double* x)
  {
    if(l + 1 == m_levels.size())
    {
      solve_coarsest<K>(b, x);
      return;
    }
    Level& level = m_levels[l];
    Level& coarse = m_levels[l + 1];
    for(int s = 0; s < m_parameters.pre_smoothing_sweeps; ++s)
      gauss_seidel<K, true>(level, b, x);
    restrict_residual<K>(level, b, x, coarse.right_hand_side.data());
    std::fill(coarse.solution.begin(), coarse.solution.begin() + K * static_cast<std::size_t>(coarse.A.number_of_rows),
              0.);
    v_cycle<K>(l + 1, coarse.right_hand_side.data(), coarse.solution.data());
    interpolate_add<K>(level.P, coarse.solution.data(), x);
    for(int s = 0; s < m_parameters.post_smoothing_sweeps; ++s)
      gauss_seidel<K, false>(level, b, x);
  }

  Hierarchy_parameters m_parameters;
  std::vector<Level> m_levels;
  Eigen::PartialPivLU<Eigen::MatrixXd> m_dense_coarse_solver;
  std::shared_ptr<Eigen::SparseLU<Eigen_sparse>> m_sparse_coarse_solver;
};

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_RUGE_STUEBEN_HIERARCHY_H
