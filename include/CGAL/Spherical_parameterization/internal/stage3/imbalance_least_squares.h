// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 3, beyond the paper: the map of least imbalance, for non-symmetric weights (mean value), whose balance
// equations are three too many and in general have no exact solution.
//
// It minimizes the imbalances themselves, each in its own scale:
//   Psi(x) = 1/2 sum_i |r_i|^2,   r_i = F_i / l_i,   F_i = P_i sum_j w_ij (x_j - x_i),   l_i = sum_j |w_ij| s(c_ij)
// (normalized weights, P_i the projection on the tangent plane at x_i, s(c_ij) the tangential length of the edge of
// chord c_ij = |x_j - x_i|, see vertex_imbalance), so |r_i| = e_i, the imbalance of the
// convergence test. Where a balanced map exists, it is the minimum (Psi = 0). Unlike the absolute residuals, whose
// least-squares problem the collapse onto a point solves (every F_i -> 0), Psi is scale-free: a collapse keeps the
// imbalances near 0.5, so the iterations are not drawn along the boosts towards it.
// Steps, in tangent coordinates, each cut back until Phi decreases (Armijo) and every triangle stays positive:
// - plain Gauss-Newton steps d = -(J P_N)^+ r (rotations left out), from one sparse LU of J (gauss_newton_step())
//   or, from Solver_tuning::least_squares_krylov_vertices on, by GMRES with the weights' multigrid
//   (krylov_gauss_newton_step(), with the LU as its fallback);
// - Marquardt's steps (J^T J + B + lambda diag(J^T J + B)) d = -grad Phi where those crawl or do not descend (step());
// - where the triangles stop the steps, the minimum subject to det(x_a, x_b, x_c) > 0 through
//   Phi_mu(x) = Psi(x) - mu sum_f c_f log det_f, with B = mu sum_f c_f b_f b_f^T / det_f^2 the barrier's positive
//   part and c_f set per phase as in constrained_balance.h.
// Every step is a descent step of one function, so the iterations cannot cycle.
//
// Stationarity, in the scale of the imbalance: sigma_k = |grad_k Phi_mu| / S_k with S_k = |alpha_k| / l_k +
// m_sum{j: k in N(j)} |w_jk| / l_j, the size of grad_k Psi if every r_i of its terms had length 1.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_IMBALANCE_LEAST_SQUARES_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_IMBALANCE_LEAST_SQUARES_H

#include <CGAL/Spherical_parameterization/internal/Sphere_state.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/stage3/constrained_balance.h>
#include <CGAL/Spherical_parameterization/internal/stage3/sparse_factorization.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_multigrid.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_newton_system.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

class Imbalance_least_squares
{
public:
  explicit Imbalance_least_squares(const Sphere_system& system) : m_system(system) {}

  // Phi_mu at x; +infinity when a face is not positive and mu > 0. Keeps the per-vertex terms of x.
  double evaluate(const std::vector<Vector3>& x, double mu)
  {
    compute_least_squares_terms(m_system, x, m_terms);
    double psi = 0.;
    for(std::size_t i = 0; i < m_system.number_of_vertices; ++i)
    {
      const double l = m_terms.scale[i];
      if(l > 0.)
        psi += 0.5 * squared_length(m_terms.force[i]) / (l * l);
    }
    if(mu > 0.)
    {
      for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
      {
        const auto& t = m_system.triangles[f];
        const double det = face_determinant(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                                            x[static_cast<std::size_t>(t[2])]);
        if(!(det > 0.))
          return HUGE_VAL;
        psi -= mu * m_face_scale[f] * std::log(det);
      }
    }
    return psi;
  }

  // After evaluate(x, 0): c_f such that the face's barrier force at each of its vertices k is at most mu S_k now
  // (thin triangles and slivers: with c_f = 1 their barrier force was 1e5 times the imbalance's scale).
  void set_face_scales(const std::vector<Vector3>& x)
  {
    m_face_scale = barrier_face_scales(m_system, x, stationarity_scales());
  }

  // S_k for every vertex (after evaluate()): see stationarity_size().
  std::vector<double> stationarity_scales() const
  {
    std::vector<double> size(m_system.number_of_vertices);
    for(std::size_t k = 0; k < size.size(); ++k)
      size[k] = stationarity_size(m_system, m_terms, k);
    return size;
  }

  // After evaluate(x, mu): the Jacobian of the r_i and the gradient of Phi_mu in tangent coordinates.
  void linearize(const std::vector<Vector3>& x, double mu)
  {
    const std::size_t n = m_system.number_of_vertices;
    tangent_frames(x, m_t1, m_t2);
    if(m_jacobian.rows() != Eigen::Index(2 * n))
      build_pattern();
    m_residual.resize(static_cast<Eigen::Index>(2 * n));
    double* values = m_jacobian.valuePtr();
    for(std::size_t i = 0; i < n; ++i)
    {
      const double l = m_terms.scale[i];
      const std::array<std::size_t, 4>& diagonal = m_diagonal_slots[i];
      if(!(l > 0.))
      {
        m_residual[Eigen::Index(2 * i)] = m_residual[Eigen::Index(2 * i + 1)] = 0.;
        for(int b = 0; b < 4; ++b)
          values[diagonal[b]] = 0.;
        for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
          for(int b = 0; b < 4; ++b)
            values[m_block_slots[k][b]] = 0.;
        continue;
      }
      const double f[2] = {dot(m_t1[i], m_terms.force[i]) / l, dot(m_t2[i], m_terms.force[i]) / l}; // r_i in the frame
      m_residual[Eigen::Index(2 * i)] = f[0];
      m_residual[Eigen::Index(2 * i + 1)] = f[1];
      // d r_i / d x_i = -alpha_i / l_i I + r_i (T_i^T U_i)^T / l_i, U_i = sum_j |w_ij| s'(c_ij) (x_j - x_i) / c_ij.
      const double u[2] = {dot(m_t1[i], m_terms.pull[i]) / l, dot(m_t2[i], m_terms.pull[i]) / l};
      values[diagonal[0]] = -m_terms.alpha[i] / l + f[0] * u[0];
      values[diagonal[1]] = f[0] * u[1];
      values[diagonal[2]] = f[1] * u[0];
      values[diagonal[3]] = -m_terms.alpha[i] / l + f[1] * u[1];
      // d r_i / d x_j = w_ij / l_i T_i^T T_j - |w_ij| s'(c_ij) r_i (T_j^T u_ij)^T / l_i, u_ij the unit edge vector.
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        const double w = m_system.weights[k];
        const Vector3 e = x[j] - x[i];
        const double length_e = length(e);
        const double v[2] = {length_e > 0. ? dot(m_t1[j], e) / length_e : 0.,
                             length_e > 0. ? dot(m_t2[j], e) / length_e : 0.};
        const std::array<std::size_t, 4>& slot = m_block_slots[k];
        const double c = std::abs(w) * tangential_edge_length_derivative(length_e, tangential_edge_length(x[i], e)) / l;
        values[slot[0]] = w / l * dot(m_t1[i], m_t1[j]) - c * f[0] * v[0];
        values[slot[1]] = w / l * dot(m_t1[i], m_t2[j]) - c * f[0] * v[1];
        values[slot[2]] = w / l * dot(m_t2[i], m_t1[j]) - c * f[1] * v[0];
        values[slot[3]] = w / l * dot(m_t2[i], m_t2[j]) - c * f[1] * v[1];
      }
    }
    m_gradient = m_jacobian.transpose() * m_residual;
    if(mu > 0.)
    {
      for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
      {
        const auto& t = m_system.triangles[f];
        const Vector3 p[3] = {x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                              x[static_cast<std::size_t>(t[2])]};
        const double factor = mu * m_face_scale[f] / face_determinant(p[0], p[1], p[2]);
        for(int k = 0; k < 3; ++k)
        {
          const std::size_t v = static_cast<std::size_t>(t[k]);
          const Vector3 g = determinant_gradient(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
          m_gradient[Eigen::Index(2 * v)] -= factor * dot(m_t1[v], g);
          m_gradient[Eigen::Index(2 * v + 1)] -= factor * dot(m_t2[v], g);
        }
      }
    }
  }

  // sigma_k for every vertex against `tolerance` (after linearize()), each with its rounding floor.
  Imbalance_summary stationarity(double tolerance) const
  {
    return summarize_stationarity(m_system, m_terms, tolerance, [&](std::size_t k) {
      return std::hypot(m_gradient[Eigen::Index(2 * k)], m_gradient[Eigen::Index(2 * k + 1)]);
    });
  }

  // The Gauss-Newton step without the barrier (after linearize(x, 0)), d = -(J P_N)^+ r, from a sparse LU of J
  // itself rather than a Cholesky factorization of J^T J (whose pattern is the two-ring: on bunny00, 81% of the time
  // went into that factorization). J is square; where r = 0 its null space is the rotations N and its range misses a
  // 3-dimensional left null space (the three equations too many); elsewhere J N != 0 (the frames turn with the map).
  // The step is the least-squares step over the maps modulo rotations: d orthogonal to N with J d + r in L, the left
  // null space of J P_N (P_N J^T z = 0 for z in L). With J_e = J + E (E tiny: regular), L = J_e^-T N (one transposed
  // solve per rotation field), and d = J_e^-1 (-(r - P_L r)), which is orthogonal to N by construction: the same step
  // as krylov_gauss_newton_step()'s. (Until 2026-11-28 two steps of inverse iteration from N gave J_e^-2T N instead,
  // not L where J N != 0: CGAL's cow took 82 steps instead of 11.) E adds 1e-10 |J_kk| to each
  // diagonal entry (1e-10 of the largest where J_kk = 0), not 1e-10 of the largest everywhere: the rows carry 1/l_i,
  // so where spherical edges span 1e-9 to 0.4 the largest entry is the shortest edges', and 1e-10 of it distorted
  // the steps of the map's sparse part (with Marquardt's shift below, the same change: 56 of the 66 test meshes
  // stationary within 30 s instead of 51).
  bool gauss_newton_step(const std::vector<Vector3>& x, std::vector<Vector3>& d)
  {
    const std::size_t n = m_system.number_of_vertices;
    const Eigen::Index m = Eigen::Index(2 * n);
    Eigen::SparseMatrix<double> shifted = m_jacobian;
    double largest = 0.;
    for(Eigen::Index k = 0; k < m; ++k)
      largest = std::max(largest, std::abs(shifted.coeff(k, k)));
    for(Eigen::Index k = 0; k < m; ++k)
    {
      const double diagonal = std::abs(shifted.coeff(k, k));
      shifted.coeffRef(k, k) += 1e-10 * (diagonal > 0. ? diagonal : largest);
    }
    if(!m_lu.factorize(shifted))
      return false;
    Eigen::VectorXd rotations[3], basis[3];
    for(int axis = 0; axis < 3; ++axis)
    {
      rotations[axis].resize(m);
      Vector3 omega;
      (axis == 0 ? omega.x : axis == 1 ? omega.y : omega.z) = 1.;
      for(std::size_t i = 0; i < n; ++i)
      {
        const Vector3 rotation = cross(omega, x[i]);
        rotations[axis][Eigen::Index(2 * i)] = dot(m_t1[i], rotation);
        rotations[axis][Eigen::Index(2 * i + 1)] = dot(m_t2[i], rotation);
      }
    }
    auto orthonormalize = [](Eigen::VectorXd* vectors) {
      for(int k = 0; k < 3; ++k)
      {
        for(int previous = 0; previous < k; ++previous)
          vectors[k] -= vectors[previous].dot(vectors[k]) * vectors[previous];
        const double norm = vectors[k].norm();
        if(!(norm > 0.) || !vectors[k].allFinite())
          return false;
        vectors[k] /= norm;
      }
      return true;
    };
    if(!orthonormalize(rotations))
      return false;
    for(int k = 0; k < 3; ++k)
      basis[k] = m_lu.solver().transpose().solve(rotations[k]);
    if(!orthonormalize(basis))
      return false;
    Eigen::VectorXd rhs = -m_residual;
    for(int k = 0; k < 3; ++k)
      rhs -= basis[k].dot(rhs) * basis[k];
    // N^T J_e^-1 rhs = (J_e^-T N)^T rhs = 0, rhs being orthogonal to L: the solve has no rotation part but rounding.
    Eigen::VectorXd delta = m_lu.solver().solve(rhs);
    for(int k = 0; k < 3; ++k)
      delta -= rotations[k].dot(delta) * rotations[k];
    return to_tangent_vectors(delta, d) && m_slope < 0.;
  }

  // The same least-squares step d = -(J P_N)^+ r, iteratively (after linearize(x, 0)): GMRES on J, preconditioned by
  // one multigrid V-cycle of the weights' Laplacian, solved to the relative residual `forcing` (inexact Newton). False
  // when a solve fails (then gauss_newton_step() is the fallback).
  // Scaling: row i of J carries 1/l_i, and the normalized weights divide by the raw row sum rho_i, so
  // J^ = S J with S = diag(rho_i l_i) is, up to the frames' rotations and the derivatives of l_i, minus the raw
  // weights' Laplacian: J^ is solved with the V-cycle as right preconditioner (its rows then have comparable sizes).
  // The step is fixed by two 3-dimensional spaces. N, the rotations, is known. L^, the left null space of J^ modulo
  // rotations (P_N J^^T z = 0), is not: starting from a guess U (the previous step's L^, moved to the new frames, or
  // the rotations, which it is for symmetric weights), z_k = u_k + w_k with w_k solving the transposed system
  //   (P_N J^^T P_U + N U^T) w_k = -P_N J^^T u_k,
  // nonsingular by construction; the solution has U^T w_k = 0 and P_N J^^T z_k = 0. Near a stationary point r lies
  // almost entirely in L = S L^, so L must be accurate where P_L r is small: each step refines the previous L^ (an
  // inverse iteration), to the relative residual krylov_left_tolerance. With L, J d = -(r - P_L r) (Euclidean
  // projection: the step is then a descent direction for the inexact solve too, its error lying in L's complement),
  // d orthogonal to N, is the nonsingular system
  //   (P_L^ J^ P_N + Q N^T) d = -S (r - P_L r),   Q an orthonormal basis of L^.
  // `stop` (a time budget) is asked after every GMRES iteration; when it ends a solve, the step fails and
  // stopped() is true.
  bool krylov_gauss_newton_step(const std::vector<Vector3>& x, std::vector<Vector3>& d, const Solver_tuning& tuning,
                                const std::function<bool()>& stop = {})
  {
    m_stopped = false;
    const double left_tolerance = tuning.krylov_left_tolerance;
    const int max_iterations = tuning.krylov_max_iterations;
    const int restart_length = tuning.krylov_restart;
    const std::size_t n = m_system.number_of_vertices;
    const std::size_t m = 2 * n;
    if(!m_multigrid.is_built() && !m_multigrid.build(m_system, true))
      return false;
    m_row_scale.resize(n);
    for(std::size_t i = 0; i < n; ++i)
    {
      m_row_scale[i] = std::abs(m_system.row_sums[i]) * m_terms.scale[i];
      if(!(m_row_scale[i] > 0.) || !std::isfinite(m_row_scale[i]))
        return false; // a zero row of J: its rank drops below 2n - 3, left to the LU
    }
    m_rotations.set_rotations(x, m_t1, m_t2);
    // U: the previous L^ in the new frames, or the rotations.
    bool have_guess = m_left_ambient[0].size() == n;
    if(have_guess)
    {
      for(std::size_t k = 0; k < 3; ++k)
      {
        m_left[k].resize(m);
        for(std::size_t i = 0; i < n; ++i)
        {
          m_left[k][2 * i] = dot(m_t1[i], m_left_ambient[k][i]);
          m_left[k][2 * i + 1] = dot(m_t2[i], m_left_ambient[k][i]);
        }
      }
      have_guess = m_left.orthonormalize();
    }
    if(!have_guess)
      for(std::size_t k = 0; k < 3; ++k)
        m_left[k] = m_rotations[k];
    m_krylov_iterations = 0;

    // Scaled products: out = J^ in and out = J^^T in.
    m_in.resize(static_cast<Eigen::Index>(m));
    m_out.resize(static_cast<Eigen::Index>(m));
    auto scaled_jacobian = [&](const double* in, double* out) {
      std::copy(in, in + m, m_in.data());
      m_out.noalias() = m_jacobian * m_in;
      for(std::size_t r = 0; r < m; ++r)
        out[r] = m_row_scale[r / 2] * m_out[Eigen::Index(r)];
    };
    auto scaled_jacobian_transpose = [&](const double* in, double* out) {
      for(std::size_t r = 0; r < m; ++r)
        m_in[Eigen::Index(r)] = m_row_scale[r / 2] * in[r];
      m_out.noalias() = m_jacobian.transpose() * m_in;
      std::copy(m_out.data(), m_out.data() + m, out);
    };
    // The bordered operator (P_B A P_C + B C^T) and its preconditioner (-P_C V P_B + C B^T), A = J^ with (B, C) =
    // (Q, N), or A = J^^T with (B, C) = (N, U).
    m_scratch.resize(m);
    auto bordered = [&](auto& product, const Tangent_basis3& range_complement, const Tangent_basis3& domain_null) {
      return [&, product](const double* in, double* out) mutable {
        double c[3];
        domain_null.coordinates(in, c);
        domain_null.project_out(in, m_scratch.data());
        product(m_scratch.data(), out);
        range_complement.project_out(out);
        for(std::size_t k = 0; k < 3; ++k)
          for(std::size_t r = 0; r < m; ++r)
            out[r] += c[k] * range_complement[k][r];
      };
    };
    auto bordered_preconditioner = [&](const Tangent_basis3& range_complement, const Tangent_basis3& domain_null) {
      return [&](const double* in, double* out) {
        double c[3];
        range_complement.coordinates(in, c);
        range_complement.project_out(in, m_scratch.data());
        m_multigrid.apply(m_t1, m_t2, m_scratch.data(), out);
        for(std::size_t r = 0; r < m; ++r)
          out[r] = -out[r];
        domain_null.project_out(out);
        for(std::size_t k = 0; k < 3; ++k)
          for(std::size_t r = 0; r < m; ++r)
            out[r] += c[k] * domain_null[k][r];
      };
    };
    auto solve = [&](auto& apply, auto& precondition, const std::vector<double>& rhs, std::vector<double>& solution,
                     double tolerance, bool from_zero = true) {
      const double rhs_norm = AMG::norm(rhs.data(), AMG::Index(m));
      if(from_zero)
        solution.assign(m, 0.);
      if(!(rhs_norm > 0.))
        return std::isfinite(rhs_norm);
      m_residual_work.resize(m);
      auto residual = [&](const double* in, const double* b, double* r) {
        apply(in, m_residual_work.data());
        for(std::size_t k = 0; k < m; ++k)
          r[k] = b[k] - m_residual_work[k];
      };
      const AMG::Krylov_result result =
          AMG::gmres(apply, residual, AMG::Index(m), rhs.data(), solution.data(), precondition, tolerance * rhs_norm,
                     rhs_norm, max_iterations, restart_length, m_workspace, stop);
      m_krylov_iterations += result.iterations;
      if(result.stopped && !result.converged)
      {
        m_stopped = true;
        return false;
      }
      // Not converged in max_iterations but well reduced: still a useful step (the line search judges it).
      return std::isfinite(result.relative_residual) && result.relative_residual <= std::max(tolerance, 0.5);
    };

    // L^: three transposed solves.
    {
      auto apply = bordered(scaled_jacobian_transpose, m_rotations, m_left);
      auto precondition = bordered_preconditioner(m_rotations, m_left);
      Tangent_basis3 z;
      for(std::size_t k = 0; k < 3; ++k)
      {
        m_rhs.resize(m);
        scaled_jacobian_transpose(m_left[k].data(), m_rhs.data());
        m_rotations.project_out(m_rhs.data());
        for(double& value : m_rhs)
          value = -value;
        if(!solve(apply, precondition, m_rhs, m_solution, left_tolerance))
          return false;
        z[k].resize(m);
        for(std::size_t r = 0; r < m; ++r)
          z[k][r] = m_left[k][r] + m_solution[r];
      }
      if(!z.orthonormalize())
        return false;
      m_left_iterations = m_krylov_iterations;
      for(std::size_t k = 0; k < 3; ++k)
        m_left[k] = z[k];
    }
    // L = S L^ in the Euclidean metric, and the right-hand side -S (r - P_L r).
    Tangent_basis3 left_euclidean;
    for(std::size_t k = 0; k < 3; ++k)
    {
      left_euclidean[k].resize(m);
      for(std::size_t r = 0; r < m; ++r)
        left_euclidean[k][r] = m_row_scale[r / 2] * m_left[k][r];
    }
    if(!left_euclidean.orthonormalize())
      return false;
    m_rhs.resize(m);
    for(std::size_t r = 0; r < m; ++r)
      m_rhs[r] = m_residual[Eigen::Index(r)];
    left_euclidean.project_out(m_rhs.data());
    for(std::size_t r = 0; r < m; ++r)
      m_rhs[r] = -m_row_scale[r / 2] * m_rhs[r];
    // The inexact Gauss-Newton step asks the linear model's gradient J^T (J d + r) to be at most eta times the
    // gradient J^T r (Gratton, Lawless and Nichols, 2007), both in the norm of the stationarity test (vertex k's
    // two entries over S_k); the residual of J d = -(r - P_L r) alone says little about it (armadillo: the
    // stationarity stalled, and Marquardt's factorizations took over). eta: Eisenstat and Walker's choice 2 on
    // that gradient, at most krylov_max_forcing.
    m_stationarity_scale = stationarity_scales();
    auto gradient_norm = [&](const Eigen::VectorXd& g) {
      double sum = 0.;
      for(std::size_t i = 0; i < n; ++i)
      {
        const double a = g[Eigen::Index(2 * i)], b = g[Eigen::Index(2 * i + 1)];
        const double size = m_stationarity_scale[i] > 0. ? m_stationarity_scale[i] : 1.;
        sum += (a * a + b * b) / (size * size);
      }
      return std::sqrt(sum);
    };
    const double reducible = gradient_norm(m_gradient);
    double forcing = tuning.krylov_max_forcing;
    if(m_previous_reducible > 0.)
    {
      const double ratio = reducible / m_previous_reducible;
      forcing = tuning.krylov_forcing_gamma * ratio * ratio;
      const double safeguard = tuning.krylov_forcing_gamma * m_forcing * m_forcing;
      if(safeguard > 0.1)
        forcing = std::max(forcing, safeguard);
      forcing = std::min(std::max(forcing, tuning.krylov_min_forcing), tuning.krylov_max_forcing);
    }
    m_forcing = forcing;
    m_previous_reducible = reducible;
    {
      auto apply = bordered(scaled_jacobian, m_left, m_rotations);
      auto precondition = bordered_preconditioner(m_left, m_rotations);
      double tolerance = forcing;
      for(int round = 0;; ++round)
      {
        if(!solve(apply, precondition, m_rhs, m_solution, tolerance, round == 0))
          return false;
        // The linear model's gradient J^T (J d + r), d without its rotation part.
        m_delta = Eigen::Map<const Eigen::VectorXd>(m_solution.data(), Eigen::Index(m));
        m_rotations.project_out(m_delta.data());
        m_out.noalias() = m_jacobian * m_delta;
        m_out += m_residual;
        m_in.noalias() = m_jacobian.transpose() * m_out;
        // Its rotation part, (J N)^T (J d + r), is not the step's to remove (J N = 0 only where r = 0), and the
        // gradient J^T r has none (Psi is invariant under rotations).
        m_rotations.project_out(m_in.data());
        const double model_gradient = gradient_norm(m_in);
        if(!std::isfinite(model_gradient))
          return false;
        if(model_gradient <= forcing * reducible || round == 4)
          break;
        tolerance *= 0.1;
      }
    }
    m_rotations.project_out(m_solution.data());
    // L^ as ambient fields, for the next step's frames.
    for(std::size_t k = 0; k < 3; ++k)
    {
      m_left_ambient[k].resize(n);
      for(std::size_t i = 0; i < n; ++i)
        m_left_ambient[k][i] = m_left[k][2 * i] * m_t1[i] + m_left[k][2 * i + 1] * m_t2[i];
    }
    Eigen::VectorXd delta = Eigen::Map<const Eigen::VectorXd>(m_solution.data(), Eigen::Index(m));
    return to_tangent_vectors(delta, d) && m_slope < 0.;
  }

  int krylov_iterations() const { return m_krylov_iterations; }
  bool stopped() const { return m_stopped; }
  int left_iterations() const { return m_left_iterations; }
  double forcing() const { return m_forcing; }

  // The Gauss-Newton step with the relative Marquardt shift `lambda` (after linearize()), as tangent vectors.
  bool step(const std::vector<Vector3>& x, double mu, double lambda, std::vector<Vector3>& d)
  {
    Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(m_jacobian.transpose()) * m_jacobian;
    if(mu > 0.)
    {
      // The barrier's positive part: mu b_f b_f^T / det_f^2 (its curvature part is left out: the matrix stays
      // positive definite, so the step is a descent direction).
      for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
      {
        const auto& t = m_system.triangles[f];
        const Vector3 p[3] = {x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                              x[static_cast<std::size_t>(t[2])]};
        const double det = face_determinant(p[0], p[1], p[2]);
        const double weight = mu * m_face_scale[f];
        if(!(weight > 0.))
          continue;
        double b[6];
        for(int k = 0; k < 3; ++k)
        {
          const std::size_t v = static_cast<std::size_t>(t[k]);
          const Vector3 g = determinant_gradient(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
          b[2 * k] = dot(m_t1[v], g) / det;
          b[2 * k + 1] = dot(m_t2[v], g) / det;
        }
        for(int r = 0; r < 6; ++r)
          for(int s = 0; s < 6; ++s)
          {
            const Eigen::Index row = Eigen::Index(2 * static_cast<std::size_t>(t[r / 2]) + std::size_t(r % 2));
            const Eigen::Index column = Eigen::Index(2 * static_cast<std::size_t>(t[s / 2]) + std::size_t(s % 2));
            normal.coeffRef(row, column) += weight * b[r] * b[s];
          }
      }
    }
    // Besides lambda (at least 1e-12), a shift of 1e-12 of each diagonal entry itself, and of the mean diagonal only
    // where an entry is 0: J^T J is singular along the rotations (the step's rotation part is harmless: Psi is
    // invariant under rotations, and the line search judges the step). Not 1e-12 of the mean everywhere: where
    // spherical edges span 1e-9 to 0.4 (CGAL's cow with mean-value weights), the entries span some 20 orders of
    // magnitude, the mean is the shortest edges', and that shift outweighed the curvature of the map's sparse part,
    // whose steps then shrank to a crawl (the worst stationarity from 8e-4 to 3.6e-4 in 400 steps; stationary in 102
    // steps with this shift).
    double mean_diagonal = 0.;
    for(Eigen::Index k = 0; k < normal.rows(); ++k)
      mean_diagonal += normal.coeff(k, k);
    mean_diagonal /= double(std::max<Eigen::Index>(normal.rows(), 1));
    for(Eigen::Index k = 0; k < normal.rows(); ++k)
    {
      const double diagonal = normal.coeff(k, k);
      normal.coeffRef(k, k) += lambda * diagonal + 1e-12 * (diagonal > 0. ? diagonal : mean_diagonal);
    }
    if(!m_ldlt.factorize(normal))
      return false;
    return to_tangent_vectors(m_ldlt.solver().solve(-m_gradient), d);
  }

  // The directional derivative of Phi_mu along the last step.
  double slope() const { return m_slope; }

  // After linearize(): the Jacobian of the r_i and the gradient of Phi_mu, in the tangent frames below.
  const Eigen::SparseMatrix<double>& jacobian() const { return m_jacobian; }
  const Eigen::VectorXd& gradient() const { return m_gradient; }
  const std::vector<Vector3>& frame1() const { return m_t1; }
  const std::vector<Vector3>& frame2() const { return m_t2; }

private:
  // The step of tangent coordinates `delta` as tangent vectors, and its slope; false when it is not finite.
  bool to_tangent_vectors(const Eigen::VectorXd& delta, std::vector<Vector3>& d)
  {
    if(!delta.allFinite())
      return false;
    d.resize(m_system.number_of_vertices);
    for(std::size_t i = 0; i < d.size(); ++i)
      d[i] = delta[Eigen::Index(2 * i)] * m_t1[i] + delta[Eigen::Index(2 * i + 1)] * m_t2[i];
    m_slope = m_gradient.dot(delta);
    return true;
  }

  void build_pattern() { build_block_pattern(m_system, m_jacobian, m_diagonal_slots, m_block_slots); }

  const Sphere_system& m_system;
  Least_squares_terms m_terms;
  std::vector<Vector3> m_t1, m_t2;
  std::vector<double> m_face_scale;
  Eigen::SparseMatrix<double> m_jacobian;
  std::vector<std::array<std::size_t, 4>> m_diagonal_slots, m_block_slots;
  Eigen::VectorXd m_residual, m_gradient;
  double m_slope = 0.;
  Sparse_ldlt m_ldlt; // J^T J + B + lambda diag(J^T J + B), Marquardt's steps
  Sparse_lu m_lu;     // J, the plain Gauss-Newton steps
  // The plain steps by GMRES (krylov_gauss_newton_step()).
  Tangent_laplacian_preconditioner m_multigrid;
  Tangent_basis3 m_rotations, m_left;     // N (rotations) and L^, orthonormal
  std::vector<Vector3> m_left_ambient[3]; // L^ of the last step, as ambient fields
  std::vector<double> m_row_scale;        // rho_i l_i
  std::vector<double> m_rhs, m_solution, m_scratch, m_residual_work;
  Eigen::VectorXd m_in, m_out, m_delta;
  std::vector<double> m_stationarity_scale;
  AMG::Krylov_workspace m_workspace;
  int m_krylov_iterations = 0, m_left_iterations = 0;
  bool m_stopped = false;
  double m_forcing = 0., m_previous_reducible = 0.;
};

struct Least_squares_report
{
  bool stationary = false; // max sigma_k <= tolerance (or its rounding floor), without the barrier or at its last mu
  bool barrier = false;    // triangles stopped the plain steps: the barrier phases ran
  std::size_t steps = 0;
  bool cancelled = false;
  bool out_of_time = false;
};

// Gauss-Newton iterations on Phi_mu from a map with every face positive. First without the barrier (mu = 0), each
// step the least-squares step of one sparse LU, with Marquardt's steps where it does not lower Psi. When the positivity
// of the triangles cuts the steps short (tuning.barrier_patience steps in a row below tuning.short_step, or none
// taken), the barrier phases: mu = tuning.barrier_first_parameter, divided by tuning.barrier_reduction down to
// tuning.barrier_final_fraction times the tolerance, each with c_f set at its start, solved to
// max(tolerance, tuning.barrier_phase_factor mu), for at most tuning.least_squares_phase_steps steps. Every iterate
// is bijective; the one of least Psi (root mean square imbalance) is returned when the test is not met.
inline Least_squares_report imbalance_least_squares(Sphere_state& state, const Iteration_options& options,
                                                    const CGAL::Real_timer& clock)
{
  Least_squares_report report;
  const Solver_tuning& tuning = options.tuning;
  const Sphere_system& system = state.system();
  const std::size_t n = system.number_of_vertices;
  if(state.invalid_faces() != 0)
    return report;
  Imbalance_least_squares problem(system);
  const bool use_krylov = n >= tuning.least_squares_krylov_vertices;
  std::vector<Vector3>& x = state.positions();
  std::vector<Vector3> d, trial(n), best = x;
  double best_psi = problem.evaluate(x, 0.);
  double lambda = tuning.marquardt_initial;
  double mu = 0.;
  const double final_mu =
      std::min(tuning.barrier_first_parameter, std::max(tuning.barrier_final_fraction * options.tolerance, 1e-12));
  double phi = best_psi;
  std::size_t short_steps = 0, phase_steps = 0;
  // Ends the current phase: the next, smaller mu (the first one when the plain steps stall). False after the last.
  auto next_phase = [&]() {
    if(report.barrier && mu <= final_mu)
      return false;
    mu = report.barrier ? std::max(mu / tuning.barrier_reduction, final_mu) : tuning.barrier_first_parameter;
    report.barrier = true;
    short_steps = phase_steps = 0;
    problem.evaluate(x, 0.);
    problem.set_face_scales(x);
    phi = problem.evaluate(x, mu);
    return true;
  };
  // The duration of the last attempt of each kind, which predicts the next one's: a plain step by GMRES can take a
  // fraction of a second where Marquardt's factorization of J^T J takes seconds (brain cortices), and up to
  // marquardt_attempts of them follow each other within one step. (GMRES itself stops on the budget: one step's
  // solves on vol2surf_lh_pial took 645 iterations, 20 s.)
  double last_plain_seconds = 0., last_marquardt_seconds = 0.;
  bool plain_steps_allowed = true;
  std::vector<double> stationarity_history;
  for(;;)
  {
    if(past_time_budget(options, clock))
    {
      report.out_of_time = true;
      break;
    }
    if(options.cancel_requested())
    {
      report.cancelled = true;
      break;
    }
    if(report.steps >= options.max_newton_sweeps)
      break;
    problem.linearize(x, mu);
    const bool last_phase = !report.barrier || mu <= final_mu;
    const Imbalance_summary stationarity = problem.stationarity(
        last_phase ? options.tolerance : std::max(options.tolerance, tuning.barrier_phase_factor * mu));
    if(stationarity.balanced())
    {
      if(last_phase)
      {
        report.stationary = true;
        break;
      }
      next_phase();
      continue;
    }
    // Plain Gauss-Newton steps converge only linearly where the residuals stay large; where they crawl (the worst
    // stationarity not halved in tuning.least_squares_plain_window steps: homer, 2.5e-6 for 200 steps), Marquardt's.
    if(plain_steps_allowed)
    {
      stationarity_history.push_back(stationarity.max);
      const std::size_t window = tuning.least_squares_plain_window;
      if(stationarity_history.size() > window
         && !(stationarity.max < 0.5 * stationarity_history[stationarity_history.size() - 1 - window]))
        plain_steps_allowed = false;
    }
    double t = 0.;
    for(int attempt = 0; attempt < tuning.marquardt_attempts && t == 0.; ++attempt)
    {
      // Without the barrier, the plain Gauss-Newton step first; Marquardt's steps when it does not lower Phi.
      const bool plain = attempt == 0 && mu == 0. && plain_steps_allowed;
      // A factorization cannot be interrupted: no attempt is started that the last one of its kind says would end
      // past the budget (this also holds once the budget is spent).
      if(next_part_passes_time_budget(options, clock, plain ? last_plain_seconds : last_marquardt_seconds))
      {
        report.out_of_time = true;
        break;
      }
      const double attempt_start = clock.time();
      // The plain step by GMRES on large meshes, the sparse LU where GMRES fails.
      auto plain_step = [&]() {
        if(use_krylov)
        {
          if(problem.krylov_gauss_newton_step(x, d, tuning, [&]() { return past_time_budget(options, clock); }))
            return true;
          if(problem.stopped())
            return false; // out of time: no factorization after it
        }
        return problem.gauss_newton_step(x, d);
      };
      const bool stepped = plain ? plain_step() : problem.step(x, mu, lambda, d);
      if(plain && problem.stopped())
      {
        report.out_of_time = true;
        break;
      }
      // The attempt's duration, however it ends.
      auto record_duration = [&]() {
        (plain ? last_plain_seconds : last_marquardt_seconds) = clock.time() - attempt_start;
      };
      if(!stepped)
      {
        record_duration();
        lambda = std::min(lambda * 10., tuning.marquardt_max);
        continue;
      }
      const double slope = problem.slope();
      double trial_phi = HUGE_VAL;
      t = backtracking_line_search(
          tuning.cautious_min_step,
          [&](double s) {
            for(std::size_t i = 0; i < n; ++i)
            {
              const Vector3 y = x[i] + s * d[i];
              trial[i] = y * (1. / length(y));
            }
            return state.keeps_positive_faces(trial);
          },
          [&](double s) {
            trial_phi = problem.evaluate(trial, mu);
            return trial_phi <= phi + 1e-4 * s * slope; // Armijo's sufficient decrease
          });
      record_duration();
      if(t > 0.)
      {
        state.assign(trial, true);
        phi = trial_phi;
        ++report.steps;
        ++phase_steps;
        if(!plain)
          lambda = t == 1. ? std::max(lambda / 3., 1e-12) : lambda * 2.;
      }
      else
      {
        lambda = std::min(lambda * 10., tuning.marquardt_max);
      }
    }
    if(report.out_of_time)
      break;
    // One report per step, as the other stage-3 solvers send (their Iteration_driver): the progress line, and the
    // user's callback, whose false cancels.
    if(options.progress && !options.progress("global newton", report.steps, compute_residuals(system, x).paper, 0))
    {
      report.cancelled = true;
      break;
    }
    const double psi = problem.evaluate(x, 0.);
    if(psi < best_psi)
    {
      best_psi = psi;
      best = x;
    }
    if(mu > 0.)
      problem.evaluate(x, mu); // linearize() reads the terms of x
    short_steps = t >= tuning.short_step ? 0 : short_steps + 1;
    if(t == 0. || short_steps >= tuning.barrier_patience
       || (report.barrier && phase_steps >= tuning.least_squares_phase_steps))
      if(!next_phase())
        break;
  }
  if(!report.stationary && !(best == x))
    state.assign(best);
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_IMBALANCE_LEAST_SQUARES_H
