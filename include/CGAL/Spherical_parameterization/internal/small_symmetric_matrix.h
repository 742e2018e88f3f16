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

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// A = V diag(values) V^T: values ascending, V's columns orthonormal; reads the lower triangle, as Eigen's solvers do.
// False (and nothing written) when an entry is not finite, or in the unlikely case that the QR steps do not settle
// within 30 N steps. The method is Eigen's and LAPACK's: Householder reflections reduce A to a tridiagonal
// T = Q^T A Q, then implicit symmetric QR steps with Wilkinson's shift (Golub and Van Loan, "Matrix Computations", 8.3)
// on T's diagonal and subdiagonal drive the subdiagonal to zero. Eigenvalues to eps |A| (absolute accuracy, as
// Eigen's). The matrix is scaled by its largest entry first (no overflow in the squares). On 20,000 of bunny00's 6x6
// per-face Hessians (least_distortion.h), a decomposition and the projection V max(D, 0) V^T took 1.0 microseconds,
// Eigen's SelfAdjointEigenSolver 1.2, the cyclic Jacobi rotations used before 2.7 (2026-12-04).
template <int N>
bool symmetric_eigen(const Eigen::Matrix<double, N, N>& matrix, Eigen::Matrix<double, N, 1>& values,
                     Eigen::Matrix<double, N, N>& vectors)
{
  double t[N][N], q[N][N];
  double largest = 0.;
  for(int i = 0; i < N; ++i)
    for(int j = 0; j <= i; ++j)
    {
      if(!std::isfinite(matrix(i, j)))
        return false;
      largest = std::max(largest, std::abs(matrix(i, j)));
    }
  const double scale = largest > 0. ? largest : 1.;
  for(int i = 0; i < N; ++i)
    for(int j = 0; j <= i; ++j)
    {
      t[i][j] = t[j][i] = matrix(i, j) / scale;
      q[i][j] = q[j][i] = i == j ? 1. : 0.;
    }
  // Column k below its subdiagonal zeroed by H = I - beta v v^T: T = H T H (as T - v w^T - w v^T), Q = Q H.
  for(int k = 0; k + 2 < N; ++k)
  {
    double tail = 0.;
    for(int i = k + 2; i < N; ++i)
      tail += t[i][k] * t[i][k];
    if(tail <= std::numeric_limits<double>::min()) // entries of 1e-154 |A| or less dropped: beta would overflow
      continue;
    const double head = t[k + 1][k];
    const double alpha = -std::copysign(std::sqrt(head * head + tail), head);
    double v[N] = {}, w[N] = {};
    v[k + 1] = head - alpha;
    for(int i = k + 2; i < N; ++i)
      v[i] = t[i][k];
    const double beta = 2. / (v[k + 1] * v[k + 1] + tail);
    double v_w = 0.;
    for(int i = k + 1; i < N; ++i)
    {
      double sum = 0.;
      for(int j = k + 1; j < N; ++j)
        sum += t[i][j] * v[j];
      w[i] = beta * sum;
      v_w += v[i] * w[i];
    }
    for(int i = k + 1; i < N; ++i)
      w[i] -= 0.5 * beta * v_w * v[i];
    for(int i = k + 1; i < N; ++i)
      for(int j = k + 1; j < N; ++j)
        t[i][j] -= v[i] * w[j] + w[i] * v[j];
    t[k + 1][k] = t[k][k + 1] = alpha;
    for(int i = k + 2; i < N; ++i)
      t[i][k] = t[k][i] = 0.;
    for(int r = 0; r < N; ++r)
    {
      double sum = 0.;
      for(int j = k + 1; j < N; ++j)
        sum += q[r][j] * v[j];
      for(int j = k + 1; j < N; ++j)
        q[r][j] -= beta * sum * v[j];
    }
  }
  // The tridiagonal T as its diagonal d and subdiagonal e (e[i] = T(i + 1, i)): kept so, T stays exactly symmetric
  // (as a full matrix whose two triangles were rotated separately it drifted apart by rounding, and a block of two
  // eigenvalues at rounding level no rotation could diagonalize took every step: a reviewer's A = Q diag(-1, -1, 0, 0,
  // 1, 1) Q^T, 71 in 20,000, returned wrong eigenvalues).
  double d[N], e[N];
  for(int i = 0; i < N; ++i)
  {
    d[i] = t[i][i];
    e[i] = i + 1 < N ? t[i + 1][i] : 0.;
  }
  // QR steps on the lowest unreduced block [low, high], each rotation of rows and columns k, k + 1 chasing the bulge
  // down. e[i] counts as 0 below eps (|d[i]| + |d[i + 1]|), or below eps^2 (|A| is 1 here: far below the accuracy).
  const double eps = std::numeric_limits<double>::epsilon();
  bool converged = false;
  for(int step = 0; step < 30 * N; ++step) // two or three steps per eigenvalue, as a rule
  {
    for(int i = 0; i + 1 < N; ++i)
      if(std::abs(e[i]) <= eps * (std::abs(d[i]) + std::abs(d[i + 1])) || std::abs(e[i]) <= eps * eps)
        e[i] = 0.;
    int high = N - 1;
    while(high > 0 && e[high - 1] == 0.)
      --high;
    if(high == 0)
    {
      converged = true;
      break;
    }
    int low = high - 1;
    while(low > 0 && e[low - 1] != 0.)
      --low;
    // Wilkinson's shift: the eigenvalue of the block's last 2x2 closer to its last diagonal entry.
    const double last = e[high - 1], half = 0.5 * (d[high - 1] - d[high]);
    const double shift = d[high] - last * last / (half + std::copysign(std::hypot(half, last), half));
    double x = d[low] - shift, z = e[low];
    for(int k = low; k < high; ++k)
    {
      // The rotation [c s; -s c] with c x - s z = r, s x + c z = 0: T = G^T T G on rows and columns k, k + 1.
      double c = 1., s = 0.;
      if(std::abs(z) > std::abs(x))
      {
        const double ratio = -x / z;
        s = 1. / std::sqrt(1. + ratio * ratio);
        c = s * ratio;
      }
      else if(z != 0.)
      {
        const double ratio = -z / x;
        c = 1. / std::sqrt(1. + ratio * ratio);
        s = c * ratio;
      }
      if(k > low)
        e[k - 1] = c * x - s * z; // the bulge below it is zeroed
      const double a = d[k], b = e[k], g = d[k + 1];
      d[k] = c * c * a - 2. * c * s * b + s * s * g;
      d[k + 1] = s * s * a + 2. * c * s * b + c * c * g;
      e[k] = c * s * (a - g) + (c * c - s * s) * b;
      for(int r = 0; r < N; ++r)
      {
        const double left = q[r][k], right = q[r][k + 1];
        q[r][k] = c * left - s * right;
        q[r][k + 1] = s * left + c * right;
      }
      if(k + 1 < high)
      {
        x = e[k];
        z = -s * e[k + 1]; // the bulge at (k + 2, k)
        e[k + 1] *= c;
      }
    }
  }
  if(!converged)
    return false;
  int order[N];
  for(int i = 0; i < N; ++i)
    order[i] = i;
  for(int i = 1; i < N; ++i) // insertion sort, ascending
    for(int j = i; j > 0 && d[order[j]] < d[order[j - 1]]; --j)
      std::swap(order[j], order[j - 1]);
  for(int k = 0; k < N; ++k)
  {
    values(k) = scale * d[order[k]];
    for(int r = 0; r < N; ++r)
      vectors(r, k) = q[r][order[k]];
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
