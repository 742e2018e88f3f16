// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Preconditioned Krylov methods over raw arrays: conjugate gradient (symmetric), BiCGStab and restarted GMRES
// (non-symmetric, right-preconditioned). All stop on the unpreconditioned residual ||b - A x||, recomputed
// explicitly before convergence is reported. Work vectors live in Krylov_workspace and are reused between solves.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_KRYLOV_SOLVERS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_KRYLOV_SOLVERS_H

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {
namespace AMG {

struct Krylov_result
{
  bool converged = false;
  bool stopped = false; // the caller's stop() asked to end (a time budget); x is the iterate reached
  int iterations = 0;
  double relative_residual = 0.;
};

struct Krylov_workspace
{
  std::vector<std::vector<double>> vectors;

  double* vector(std::size_t k, std::size_t n)
  {
    if(vectors.size() <= k)
      vectors.resize(k + 1);
    if(vectors[k].size() != n)
      vectors[k].assign(n, 0.);
    return vectors[k].data();
  }

  // The first N vectors, each of size n.
  template <std::size_t N>
  std::array<double*, N> first(std::size_t n)
  {
    std::array<double*, N> v;
    for(std::size_t k = 0; k < N; ++k)
      v[k] = vector(k, n);
    return v;
  }
};

inline double dot(const double* x, const double* y, Index n)
{
  double sum = 0.;
  for(Index i = 0; i < n; ++i)
    sum += x[i] * y[i];
  return sum;
}

inline double norm(const double* x, Index n)
{
  return std::sqrt(dot(x, x, n));
}

// The stopping rule the solvers share, on the true residual r = b - A x (the recursive one drifts near 1e-10
// relative accuracy): true when the iterations end here, converged or not, with `result` set.
inline bool ends_at_true_residual(const Compressed_row_matrix& A, const double* x, const double* b, double* r,
                                  double target_residual_norm, double reference_norm, int max_iterations,
                                  Krylov_result& result, double& residual_norm)
{
  residual(A, x, b, r);
  residual_norm = norm(r, A.number_of_rows);
  result.relative_residual = residual_norm / reference_norm;
  if(!std::isfinite(residual_norm))
    return true;
  result.converged = residual_norm <= target_residual_norm;
  return result.converged || result.iterations >= max_iterations;
}

// target_residual_norm: absolute bound on ||b - A x||; x holds the initial guess.
template <class Preconditioner>
Krylov_result conjugate_gradient(const Compressed_row_matrix& A, const double* b, double* x,
                                 Preconditioner& apply_preconditioner, double target_residual_norm,
                                 double reference_norm, int max_iterations, Krylov_workspace& workspace)
{
  const Index n = A.number_of_rows;
  double* r = workspace.vector(0, n);
  double* p = workspace.vector(1, n);
  // z = M^{-1} r and q = A p are never needed at the same time: one vector for both.
  double* z = workspace.vector(2, n);
  double* q = z;
  Krylov_result result;

  bool restart = true;
  double rz = 0.;
  while(true)
  {
    if(restart)
    {
      double residual_norm = 0.;
      if(ends_at_true_residual(A, x, b, r, target_residual_norm, reference_norm, max_iterations, result, residual_norm))
        return result;
      apply_preconditioner(r, z);
      std::copy(z, z + n, p);
      rz = dot(r, z, n);
      restart = false;
    }
    multiply(A, p, q);
    const double pq = dot(p, q, n);
    if(!(pq > 0.) || !(rz > 0.))
      return result; // not positive definite (or the preconditioner is not): breakdown
    const double alpha = rz / pq;
    double residual_norm_squared = 0.;
    for(Index i = 0; i < n; ++i)
    {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      residual_norm_squared += r[i] * r[i];
    }
    ++result.iterations;
    const double residual_norm = std::sqrt(residual_norm_squared);
    if(!std::isfinite(residual_norm))
      return result;
    if(residual_norm <= target_residual_norm || result.iterations >= max_iterations)
    {
      restart = true;
      continue;
    }
    apply_preconditioner(r, z);
    const double rz_new = dot(r, z, n);
    const double beta = rz_new / rz;
    rz = rz_new;
    for(Index i = 0; i < n; ++i)
      p[i] = z[i] + beta * p[i];
  }
}

template <class Preconditioner>
Krylov_result bicgstab(const Compressed_row_matrix& A, const double* b, double* x, Preconditioner& apply_preconditioner,
                       double target_residual_norm, double reference_norm, int max_iterations,
                       Krylov_workspace& workspace)
{
  const Index n = A.number_of_rows;
  const auto [r, r0, p, v, p_hat, s_hat, t] = workspace.first<7>(n);
  Krylov_result result;

  while(true)
  {
    double residual_norm = 0.;
    if(ends_at_true_residual(A, x, b, r, target_residual_norm, reference_norm, max_iterations, result, residual_norm))
      return result;

    std::copy(r, r + n, r0);
    std::fill(p, p + n, 0.);
    std::fill(v, v + n, 0.);
    double rho = 1., alpha = 1., omega = 1.;
    const double r0_norm_squared = dot(r0, r0, n);
    while(result.iterations < max_iterations)
    {
      const double rho_new = dot(r0, r, n);
      // Breakdown (r orthogonal to the shadow residual): restart from the true residual.
      if(std::abs(rho_new) <= 1e-30 * r0_norm_squared)
        break;
      const double beta = (rho_new / rho) * (alpha / omega);
      rho = rho_new;
      for(Index i = 0; i < n; ++i)
        p[i] = r[i] + beta * (p[i] - omega * v[i]);
      apply_preconditioner(p, p_hat);
      multiply(A, p_hat, v);
      const double r0v = dot(r0, v, n);
      if(r0v == 0. || !std::isfinite(r0v))
        return result;
      alpha = rho / r0v;
      for(Index i = 0; i < n; ++i)
      {
        x[i] += alpha * p_hat[i];
        r[i] -= alpha * v[i]; // r now holds s
      }
      ++result.iterations;
      residual_norm = norm(r, n);
      if(!std::isfinite(residual_norm))
        return result;
      if(residual_norm <= target_residual_norm)
        break;
      apply_preconditioner(r, s_hat);
      multiply(A, s_hat, t);
      const double tt = dot(t, t, n);
      omega = tt > 0. ? dot(t, r, n) / tt : 0.;
      if(omega == 0. || !std::isfinite(omega))
        break;
      for(Index i = 0; i < n; ++i)
      {
        x[i] += omega * s_hat[i];
        r[i] -= omega * t[i];
      }
      residual_norm = norm(r, n);
      if(residual_norm <= target_residual_norm)
        break;
    }
  }
}

// Restarted GMRES(m) with right preconditioning and Givens rotations; one preconditioner application per
// iteration plus one per restart (x += M^{-1} V y). Matrix-free: apply_operator(in, out) is out = A in and
// compute_residual(x, b, r) is r = b - A x, on arrays of n values (stage 3's Jacobians are not stored as
// Compressed_row_matrix). `stop`, when given, is asked after every iteration: true ends the solve with the iterate
// reached (Krylov_result::stopped), so that a solve of hundreds of iterations keeps a time budget.
template <class Operator, class Residual, class Preconditioner>
Krylov_result gmres(Operator& apply_operator, Residual& compute_residual, Index n, const double* b, double* x,
                    Preconditioner& apply_preconditioner, double target_residual_norm, double reference_norm,
                    int max_iterations, int restart_length, Krylov_workspace& workspace,
                    const std::function<bool()>& stop = {})
{
  const int m = std::max(restart_length, 1);
  double* r = workspace.vector(0, n);
  double* z = workspace.vector(1, n);
  std::vector<double> hessenberg(std::size_t(m + 1) * m, 0.); // column-major, (m+1) x m
  std::vector<double> cosines(m), sines(m), g(m + 1), y(m);
  Krylov_result result;

  while(true)
  {
    compute_residual(x, b, r);
    const double residual_norm = norm(r, n);
    result.relative_residual = residual_norm / reference_norm;
    if(!std::isfinite(residual_norm))
      return result;
    result.converged = residual_norm <= target_residual_norm;
    if(result.converged || result.iterations >= max_iterations || result.stopped)
      return result;

    double* v0 = workspace.vector(2, n);
    for(Index i = 0; i < n; ++i)
      v0[i] = r[i] / residual_norm;
    std::fill(g.begin(), g.end(), 0.);
    g[0] = residual_norm;
    int k = 0;
    while(k < m && result.iterations < max_iterations)
    {
      double* h = &hessenberg[std::size_t(k) * (m + 1)];
      apply_preconditioner(workspace.vectors[2 + k].data(), z);
      double* w = workspace.vector(2 + k + 1, n);
      apply_operator(z, w);
      for(int i = 0; i <= k; ++i) // modified Gram-Schmidt
      {
        const double* vi = workspace.vectors[2 + i].data();
        h[i] = dot(w, vi, n);
        for(Index j = 0; j < n; ++j)
          w[j] -= h[i] * vi[j];
      }
      h[k + 1] = norm(w, n);
      if(!std::isfinite(h[k + 1]))
        return result;
      if(h[k + 1] > 0.)
        for(Index j = 0; j < n; ++j)
          w[j] /= h[k + 1];
      for(int i = 0; i < k; ++i)
      {
        const double temporary = cosines[i] * h[i] + sines[i] * h[i + 1];
        h[i + 1] = -sines[i] * h[i] + cosines[i] * h[i + 1];
        h[i] = temporary;
      }
      const double radius = std::hypot(h[k], h[k + 1]);
      if(radius == 0.)
        return result;
      cosines[k] = h[k] / radius;
      sines[k] = h[k + 1] / radius;
      h[k] = radius;
      h[k + 1] = 0.;
      g[k + 1] = -sines[k] * g[k];
      g[k] = cosines[k] * g[k];
      ++k;
      ++result.iterations;
      if(std::abs(g[k]) <= target_residual_norm)
        break;
      if(stop && stop())
      {
        result.stopped = true;
        break;
      }
    }
    // y = H^{-1} g, then x += M^{-1} (V y)
    for(int i = k - 1; i >= 0; --i)
    {
      double sum = g[i];
      for(int j = i + 1; j < k; ++j)
        sum -= hessenberg[std::size_t(j) * (m + 1) + i] * y[j];
      y[i] = sum / hessenberg[std::size_t(i) * (m + 1) + i];
    }
    std::fill(r, r + n, 0.);
    for(int j = 0; j < k; ++j)
    {
      const double* vj = workspace.vectors[2 + j].data();
      for(Index i = 0; i < n; ++i)
        r[i] += y[j] * vj[i];
    }
    apply_preconditioner(r, z);
    for(Index i = 0; i < n; ++i)
      x[i] += z[i];
  }
}

// The same GMRES on a stored matrix.
template <class Preconditioner>
Krylov_result gmres(const Compressed_row_matrix& A, const double* b, double* x, Preconditioner& apply_preconditioner,
                    double target_residual_norm, double reference_norm, int max_iterations, int restart_length,
                    Krylov_workspace& workspace)
{
  auto apply_operator = [&A](const double* in, double* out) { multiply(A, in, out); };
  auto compute_residual = [&A](const double* in, const double* rhs, double* r) { residual(A, in, rhs, r); };
  return gmres(apply_operator, compute_residual, A.number_of_rows, b, x, apply_preconditioner, target_residual_norm,
               reference_norm, max_iterations, restart_length, workspace);
}

// Preconditioned MINRES (Paige and Saunders, 1975) for a symmetric, possibly indefinite operator with a symmetric
// positive definite preconditioner, matrix-free: apply_operator(in, out) and apply_preconditioner(in, out) on arrays
// of n values. Starts from x = 0 and stops when the preconditioned residual norm sqrt(r^T M^{-1} r) falls to
// relative_tolerance times its initial value (a monotone estimate that MINRES updates for free). `stop`, when given,
// is asked after every iteration that did not converge: true ends the solve (Krylov_result::stopped; x is the
// iterate reached), so that a cancel or a time budget need not wait for a solve of seconds (bigbrain's first Newton
// step with cotangent weights: 99 iterations, 5.5 s).
template <class Operator, class Preconditioner>
Krylov_result minres(Operator& apply_operator, Preconditioner& apply_preconditioner, const double* b, double* x,
                     Index n, double relative_tolerance, int max_iterations, Krylov_workspace& workspace,
                     const std::function<bool()>& stop = {})
{
  auto [r1, r2, y, v, w, w1, w2] = workspace.first<7>(n);
  Krylov_result result;
  std::fill(x, x + n, 0.);
  std::fill(w, w + n, 0.);
  std::fill(w2, w2 + n, 0.);
  std::copy(b, b + n, r1);
  std::copy(b, b + n, r2);
  apply_preconditioner(r1, y);
  double beta1 = dot(r1, y, n);
  if(!(beta1 >= 0.) || !std::isfinite(beta1))
    return result;
  beta1 = std::sqrt(beta1);
  if(beta1 == 0.)
  {
    result.converged = true;
    return result;
  }
  double old_beta = 0., beta = beta1, dbar = 0., epsilon = 0., phibar = beta1, cs = -1., sn = 0.;
  while(result.iterations < max_iterations)
  {
    ++result.iterations;
    const double s = 1. / beta;
    for(Index i = 0; i < n; ++i)
      v[i] = s * y[i];
    apply_operator(v, y);
    if(result.iterations >= 2)
    {
      const double c = beta / old_beta;
      for(Index i = 0; i < n; ++i)
        y[i] -= c * r1[i];
    }
    const double alpha = dot(v, y, n);
    const double c = alpha / beta;
    for(Index i = 0; i < n; ++i)
      y[i] -= c * r2[i];
    std::swap(r1, r2);
    std::copy(y, y + n, r2);
    apply_preconditioner(r2, y);
    old_beta = beta;
    beta = dot(r2, y, n);
    if(!(beta >= 0.) || !std::isfinite(beta))
      return result;
    beta = std::sqrt(beta);
    const double old_epsilon = epsilon;
    const double delta = cs * dbar + sn * alpha;
    const double gbar = sn * dbar - cs * alpha;
    epsilon = sn * beta;
    dbar = -cs * beta;
    const double gamma = std::max(std::hypot(gbar, beta), 1e-300);
    cs = gbar / gamma;
    sn = beta / gamma;
    const double phi = cs * phibar;
    phibar *= sn;
    std::swap(w1, w2);
    std::swap(w2, w);
    for(Index i = 0; i < n; ++i)
    {
      w[i] = (v[i] - old_epsilon * w1[i] - delta * w2[i]) / gamma;
      x[i] += phi * w[i];
    }
    result.relative_residual = phibar / beta1;
    if(result.relative_residual <= relative_tolerance || beta == 0.)
    {
      result.converged = true;
      return result;
    }
    if(stop && stop())
    {
      result.stopped = true;
      return result;
    }
  }
  return result;
}

} // namespace AMG
} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_AMG_KRYLOV_SOLVERS_H
