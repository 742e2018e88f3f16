// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Eigenvalues and linear solves of small symmetric matrices (2x2 to 6x6: a face's Hessian, the boosts' Hessian, the
// normal equations of a rotation or Moebius fit) by short loops of our own. Eigen's SelfAdjointEigenSolver and LDLT,
// instantiated at the three fixed sizes the package needs, cost every translation unit that includes it a third or more
// of its compile time with GCC 12 (compiled one after the other at -O3: the install test's one-call program 183 s ->
// 96 s, the command line 183 s -> 147 s; the manual's Performance section).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SMALL_SYMMETRIC_MATRIX_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SMALL_SYMMETRIC_MATRIX_H

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <utility>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// A = V diag(values) V^T by cyclic Jacobi rotations: values ascending, V's columns orthonormal. Reads the lower
// triangle, as Eigen's solvers do. A rotation is skipped where the off-diagonal entry is negligible against both
// diagonal entries, which keeps the small eigenvalues accurate relative to themselves. False (and nothing written)
// when an entry is not finite. 64 sweeps at most: they settle in under 10 (quadratic convergence).
template <int N>
bool symmetric_eigen(const Eigen::Matrix<double, N, N>& matrix, Eigen::Matrix<double, N, 1>& values,
                     Eigen::Matrix<double, N, N>& vectors)
{
  double a[N][N], v[N][N];
  bool finite = true;
  for(int i = 0; i < N; ++i)
    for(int j = 0; j <= i; ++j)
    {
      a[i][j] = a[j][i] = matrix(i, j);
      v[i][j] = v[j][i] = i == j ? 1. : 0.;
      finite = finite && std::isfinite(a[i][j]);
    }
  if(!finite)
    return false;
  const double negligible = 0.5 * std::numeric_limits<double>::epsilon();
  bool settled = false;
  for(int sweep = 0; sweep < 64 && !settled; ++sweep)
  {
    settled = true;
    for(int p = 0; p < N; ++p)
      for(int q = p + 1; q < N; ++q)
      {
        const double apq = a[p][q];
        if(apq == 0.)
          continue;
        if(std::abs(apq) <= negligible * std::sqrt(std::abs(a[p][p] * a[q][q])))
        {
          a[p][q] = a[q][p] = 0.;
          continue;
        }
        settled = false;
        // The rotation by the smaller angle that zeroes a[p][q] (tan = t); beyond 1e150 theta^2 would overflow.
        const double theta = (a[q][q] - a[p][p]) / (2. * apq);
        const double t = std::abs(theta) > 1e150 ? 0.5 / theta
                                                 : (theta >= 0. ? 1. : -1.) / (std::abs(theta) + std::sqrt(1. + theta * theta));
        const double c = 1. / std::sqrt(1. + t * t), s = t * c, tau = s / (1. + c);
        a[p][p] -= t * apq;
        a[q][q] += t * apq;
        a[p][q] = a[q][p] = 0.;
        for(int r = 0; r < N; ++r)
        {
          if(r != p && r != q)
          {
            const double arp = a[r][p], arq = a[r][q];
            a[r][p] = a[p][r] = arp - s * (arq + tau * arp);
            a[r][q] = a[q][r] = arq + s * (arp - tau * arq);
          }
          const double vrp = v[r][p], vrq = v[r][q];
          v[r][p] = vrp - s * (vrq + tau * vrp);
          v[r][q] = vrq + s * (vrp - tau * vrq);
        }
      }
  }
  int order[N];
  for(int i = 0; i < N; ++i)
    order[i] = i;
  for(int i = 1; i < N; ++i) // insertion sort, ascending
    for(int j = i; j > 0 && a[order[j]][order[j]] < a[order[j - 1]][order[j - 1]]; --j)
      std::swap(order[j], order[j - 1]);
  for(int k = 0; k < N; ++k)
  {
    values(k) = a[order[k]][order[k]];
    for(int r = 0; r < N; ++r)
      vectors(r, k) = v[r][order[k]];
  }
  return true;
}

// x with A x = b by L D L^T with symmetric pivoting on the largest remaining diagonal entry, reading A's lower triangle
// (as Eigen's ldlt()). Where a pivot is zero (A singular, semi-definite) that component of the solution is 0, the
// least-squares choice Eigen's LDLT::solve() makes too.
template <int N>
Eigen::Matrix<double, N, 1> solve_symmetric(const Eigen::Matrix<double, N, N>& matrix,
                                            const Eigen::Matrix<double, N, 1>& rhs)
{
  double a[N][N];
  int row[N]; // row k of the pivoted matrix is row[k] of A
  for(int i = 0; i < N; ++i)
  {
    row[i] = i;
    for(int j = 0; j <= i; ++j)
      a[i][j] = a[j][i] = matrix(i, j);
  }
  for(int k = 0; k < N; ++k)
  {
    int pivot = k;
    for(int i = k + 1; i < N; ++i)
      if(std::abs(a[i][i]) > std::abs(a[pivot][pivot]))
        pivot = i;
    if(pivot != k)
    {
      std::swap(row[k], row[pivot]);
      for(int j = 0; j < N; ++j)
        std::swap(a[k][j], a[pivot][j]);
      for(int i = 0; i < N; ++i)
        std::swap(a[i][k], a[i][pivot]);
    }
    const double d = a[k][k];
    if(d == 0.)
    {
      for(int i = k + 1; i < N; ++i)
        a[i][k] = a[k][i] = 0.; // no contribution of this column
      continue;
    }
    for(int i = k + 1; i < N; ++i)
      for(int j = k + 1; j < N; ++j)
        a[i][j] -= a[i][k] * a[k][j] / d;
    for(int i = k + 1; i < N; ++i)
      a[i][k] /= d; // L below the diagonal; a[k][i] keeps D L^T's row for the updates above
  }
  double y[N];
  for(int k = 0; k < N; ++k)
  {
    y[k] = rhs(row[k]);
    for(int j = 0; j < k; ++j)
      y[k] -= a[k][j] * y[j];
  }
  for(int k = 0; k < N; ++k)
    y[k] = std::abs(a[k][k]) <= (std::numeric_limits<double>::min)() ? 0. : y[k] / a[k][k]; // NaN stays NaN
  for(int k = N; k-- > 0;)
    for(int i = k + 1; i < N; ++i)
      y[k] -= a[i][k] * y[i];
  Eigen::Matrix<double, N, 1> x;
  for(int k = 0; k < N; ++k)
    x(row[k]) = y[k];
  return x;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SMALL_SYMMETRIC_MATRIX_H
