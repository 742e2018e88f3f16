// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 3, beyond the paper: the constrained balance, for symmetric weights whose balanced map is not bijective
// (cotangent weights can be negative: their balanced map may fold) or cannot be reached without leaving the
// bijective maps.
//
// The balance equations are the critical points of the spring energy E(x) = 1/2 sum_edges w_ij |x_i - x_j|^2 on the
// sphere. With every spherical triangle kept positive, the map sought is a critical point of E subject to
// det(x_a, x_b, x_c) > 0 for every face: where no triangle holds it back, the balanced map itself. It is sought by
// an interior-point (log-barrier) method: the critical points of
//   Phi_mu(x) = E(x) - mu sum_f c_f log det_f
// for mu = mu_0, mu_0 / 10, ..., each found by Newton's method (Riemannian gradient and Hessian in tangent
// coordinates, a sparse LU, a line search that keeps every det_f > 0 and lowers the scale-free norm of the
// gradient), each phase starting from the previous one's map. The boost part of each step is applied as an exact
// boost, as in mobius_newton.h (added and projected, it folded the map at every step length).
// c_f, set at the start of each phase, makes the face's barrier force at each of its vertices at most mu times the
// vertex's spring scale l_i = sum_j |w_ij| |x_j - x_i|, on every scale of the mesh (thin limbs whose triangles are
// orders of magnitude smaller than the body's, slivers): with c_f from the edge lengths alone, the barrier's force
// dwarfed the spring scale at slivers and no step got anywhere. As mu -> 0 the barrier's force vanishes except at
// the faces that hold the map back.
//
// Where the target weights' balanced map is bijective, the iterations reach it (the manual's Method section has
// the meshes and step counts). Where it folds, the steps are cut ever shorter by the triangles about to degenerate
// (a primal barrier's Newton model holds only close to the central path): `reached` stays false, and
// global_newton.h goes on from the better of this map and its own.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_CONSTRAINED_BALANCE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_CONSTRAINED_BALANCE_H

#include <CGAL/Spherical_parameterization/internal/Sphere_state.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/stage3/mobius.h>
#include <CGAL/Spherical_parameterization/internal/stage3/sparse_factorization.h>

#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Constrained_balance_report
{
  bool reached = false; // the last phase's gradient met the tolerance
  std::size_t newton_steps = 0;
  bool cancelled = false;
};

// det(a, b, c) with differences, so that tiny triangles keep their digits.
inline double face_determinant(const Vector3& a, const Vector3& b, const Vector3& c)
{
  return dot(a, cross(b - a, c - a));
}

// d det(p, q, r) / d p = q x r, written as (q - p) x (r - p) + p x (r - q) for tiny triangles' digits.
inline Vector3 determinant_gradient(const Vector3& p, const Vector3& q, const Vector3& r)
{
  return cross(q - p, r - p) + cross(p, r - q);
}

// The barrier's face constants c_f: the force of -c_f log det_f at each vertex k of the face is at most `size[k]`
// (per unit mu) at x, on every scale of the mesh. Faces not positive at x get 0.
inline std::vector<double> barrier_face_scales(const Sphere_system& system, const std::vector<Vector3>& x,
                                               const std::vector<double>& size)
{
  std::vector<double> scales(system.triangles.size(), 0.);
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
  {
    const auto& t = system.triangles[f];
    const Vector3 p[3] = {x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                          x[static_cast<std::size_t>(t[2])]};
    const double det = face_determinant(p[0], p[1], p[2]);
    double c = HUGE_VAL;
    for(int k = 0; k < 3; ++k)
    {
      const double force = length(tangential_part(p[k], determinant_gradient(p[k], p[(k + 1) % 3], p[(k + 2) % 3])));
      if(force > 0.)
        c = std::min(c, size[static_cast<std::size_t>(t[k])] / force);
    }
    scales[f] = std::isfinite(c) && det > 0. ? c * det : 0.;
  }
  return scales;
}

class Constrained_balance
{
public:
  // `rotation_shift`: the relative diagonal shift against the rotations, an exact null space of the Hessian.
  explicit Constrained_balance(const Sphere_system& system, double rotation_shift = Solver_tuning().cautious_damping)
    : m_system(system), m_rotation_shift(rotation_shift)
  {}

  static double determinant(const Vector3& a, const Vector3& b, const Vector3& c) { return face_determinant(a, b, c); }

  // c_f such that the face's barrier force at each of its vertices is at most mu times the vertex's scale l_k now.
  void set_face_scales(const std::vector<Vector3>& x)
  {
    const std::size_t n = m_system.number_of_vertices;
    std::vector<double> l(n, 0.);
    for(std::size_t i = 0; i < n; ++i)
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
        l[i] += std::abs(m_system.weights[k] * m_system.row_sums[i])
                * length(x[static_cast<std::size_t>(m_system.neighbors[k])] - x[i]);
    m_scale = barrier_face_scales(m_system, x, l);
  }

  // The Riemannian gradient of Phi_mu at every vertex (tangent vectors) and the scale l_i of each vertex.
  // Returns false if a face is not positive (the barrier is infinite there).
  bool gradient(const std::vector<Vector3>& x, double mu, std::vector<Vector3>& g, std::vector<double>& l) const
  {
    const std::size_t n = m_system.number_of_vertices;
    g.assign(n, Vector3());
    l.assign(n, 0.);
    for(std::size_t i = 0; i < n; ++i)
    {
      Vector3 force;
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const double w = m_system.weights[k] * m_system.row_sums[i];
        const Vector3 e = x[static_cast<std::size_t>(m_system.neighbors[k])] - x[i];
        force += w * e;
        l[i] += std::abs(w) * length(e);
      }
      g[i] = -1. * tangential_part(x[i], force);
    }
    for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
    {
      const auto& t = m_system.triangles[f];
      const Vector3& a = x[static_cast<std::size_t>(t[0])];
      const Vector3& b = x[static_cast<std::size_t>(t[1])];
      const Vector3& c = x[static_cast<std::size_t>(t[2])];
      const double det = determinant(a, b, c);
      if(!(det > 0.))
        return false;
      const double factor = -mu * m_scale[f] / det;
      const Vector3 p[3] = {a, b, c};
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t v = static_cast<std::size_t>(t[k]);
        g[v] += factor * tangential_part(p[k], opposite_cross(p[k], p[(k + 1) % 3], p[(k + 2) % 3]));
      }
    }
    return true;
  }

  // max_i |g_i| / l_i and the sum of squares of |g_i| / l_i.
  static void scaled_norms(const std::vector<Vector3>& g, const std::vector<double>& l, double& max, double& sum)
  {
    max = 0.;
    sum = 0.;
    for(std::size_t i = 0; i < g.size(); ++i)
    {
      const double r = l[i] > 0. ? length(g[i]) / l[i] : 0.;
      max = std::max(max, r);
      sum += r * r;
    }
  }

  // Newton's step: H d = -g, with H the Riemannian Hessian of Phi_mu (plus a tiny shift against the rotations).
  bool newton_step(const std::vector<Vector3>& x, double mu, const std::vector<Vector3>& g, std::vector<Vector3>& step)
  {
    const std::size_t n = m_system.number_of_vertices;
    const Eigen::SparseMatrix<double> hessian = assemble_hessian(x, mu);
    if(!m_lu.factorize(hessian))
      return false;
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(2 * n));
    for(std::size_t i = 0; i < n; ++i)
    {
      rhs[static_cast<Eigen::Index>(2 * i)] = -dot(m_t1[i], g[i]);
      rhs[static_cast<Eigen::Index>(2 * i + 1)] = -dot(m_t2[i], g[i]);
    }
    const Eigen::VectorXd d = m_lu.solver().solve(rhs);
    if(!d.allFinite())
      return false;
    step.resize(n);
    for(std::size_t i = 0; i < n; ++i)
      step[i] = d[static_cast<Eigen::Index>(2 * i)] * m_t1[i] + d[static_cast<Eigen::Index>(2 * i + 1)] * m_t2[i];
    return true;
  }

  const std::vector<Vector3>& frame1() const { return m_t1; }
  const std::vector<Vector3>& frame2() const { return m_t2; }

  Eigen::SparseMatrix<double> assemble_hessian(const std::vector<Vector3>& x, double mu)
  {
    const std::size_t n = m_system.number_of_vertices;
    tangent_frames(x, m_t1, m_t2);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(8 * n + 4 * m_system.neighbors.size() + 36 * m_system.triangles.size());
    double largest_diagonal = 0.;
    std::vector<double> diagonal(n, 0.);
    // The spring energy: H_ii = alpha_i I, H_ij = -w_ij T_i^T T_j.
    for(std::size_t i = 0; i < n; ++i)
    {
      double alpha = 0.;
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        const double w = m_system.weights[k] * m_system.row_sums[i];
        alpha += w * (1. - 0.5 * squared_length(x[j] - x[i]));
        add_block(entries, i, j, -w, m_t1[j], m_t2[j]);
      }
      diagonal[i] = alpha;
    }
    // The barrier: for face (a, b, c) with g_p = d det / d x_p and lambda = mu c_f / det, block (p, q) =
    // lambda (T_p^T g_p)(T_q^T g_q)^T / det - lambda T_p^T (d g_p / d x_q) T_q, plus lambda det I on the diagonal
    // blocks (the sphere's curvature: x_p . g_p = det).
    for(std::size_t f = 0; f < m_system.triangles.size(); ++f)
    {
      const auto& t = m_system.triangles[f];
      const Vector3 p[3] = {x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                            x[static_cast<std::size_t>(t[2])]};
      const double det = determinant(p[0], p[1], p[2]);
      const double lambda = mu * m_scale[f] / det; // the face's multiplier on the central path
      double tg[3][2];
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t v = static_cast<std::size_t>(t[k]);
        const Vector3 gk = opposite_cross(p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
        tg[k][0] = dot(m_t1[v], gk);
        tg[k][1] = dot(m_t2[v], gk);
      }
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t v = static_cast<std::size_t>(t[k]);
        diagonal[v] += lambda * det;
        for(int m = 0; m < 3; ++m)
        {
          const std::size_t u = static_cast<std::size_t>(t[m]);
          double block[2][2];
          for(int r = 0; r < 2; ++r)
            for(int s = 0; s < 2; ++s)
              block[r][s] = lambda * tg[k][r] * tg[m][s] / det;
          if(m != k)
          {
            // d g_k / d x_m = -[x_o]x when m = k + 1, +[x_o]x when m = k + 2, x_o the third vertex.
            const bool next = m == (k + 1) % 3;
            const Vector3& o = p[next ? (k + 2) % 3 : (k + 1) % 3];
            const double sign = next ? -1. : 1.;
            const Vector3 tk[2] = {m_t1[v], m_t2[v]};
            const Vector3 tm[2] = {m_t1[u], m_t2[u]};
            for(int r = 0; r < 2; ++r)
              for(int s = 0; s < 2; ++s)
                block[r][s] -= lambda * sign * dot(tk[r], cross(o, tm[s]));
          }
          for(int r = 0; r < 2; ++r)
            for(int s = 0; s < 2; ++s)
              entries.emplace_back(static_cast<int>(2 * v + r), static_cast<int>(2 * u + s), block[r][s]);
        }
      }
    }
    for(std::size_t i = 0; i < n; ++i)
      largest_diagonal = std::max(largest_diagonal, std::abs(diagonal[i]));
    const double shift = m_rotation_shift * largest_diagonal;
    for(std::size_t i = 0; i < n; ++i)
      for(int r = 0; r < 2; ++r)
        entries.emplace_back(static_cast<int>(2 * i + r), static_cast<int>(2 * i + r), diagonal[i] + shift);
    Eigen::SparseMatrix<double> hessian(static_cast<Eigen::Index>(2 * n), static_cast<Eigen::Index>(2 * n));
    hessian.setFromTriplets(entries.begin(), entries.end());
    hessian.makeCompressed();
    return hessian;
  }

private:
  static Vector3 opposite_cross(const Vector3& p, const Vector3& q, const Vector3& r)
  {
    return determinant_gradient(p, q, r);
  }

  void add_block(std::vector<Eigen::Triplet<double>>& entries, std::size_t i, std::size_t j, double w,
                 const Vector3& t1_j, const Vector3& t2_j) const
  {
    const Vector3 ti[2] = {m_t1[i], m_t2[i]};
    const Vector3 tj[2] = {t1_j, t2_j};
    for(int r = 0; r < 2; ++r)
      for(int s = 0; s < 2; ++s)
        entries.emplace_back(static_cast<int>(2 * i + r), static_cast<int>(2 * j + s), w * dot(ti[r], tj[s]));
  }

  const Sphere_system& m_system;
  double m_rotation_shift;
  std::vector<double> m_scale;
  std::vector<Vector3> m_t1, m_t2;
  Sparse_lu m_lu;
};

// The interior-point iterations from a map with every face positive (state.invalid_faces() == 0), for symmetric
// weights. Each phase ends when max_i |grad_i Phi_mu| / l_i <= max(tolerance, tuning.barrier_phase_factor * mu),
// the last one (mu = tuning.barrier_final_fraction * tolerance) at the tolerance. A phase also ends when
// tuning.barrier_patience steps in a row had to be cut below a quarter or when no step lowers the merit; `reached`
// says whether the last one met the tolerance. Every iterate is bijective.
inline Constrained_balance_report constrained_balance(Sphere_state& state, const Iteration_options& options,
                                                      const CGAL::Real_timer& clock)
{
  const Solver_tuning& tuning = options.tuning;
  Constrained_balance_report report;
  const Sphere_system& system = state.system();
  const std::size_t n = system.number_of_vertices;
  if(state.invalid_faces() != 0 || !system.symmetric)
    return report;
  Constrained_balance solver(system, tuning.cautious_damping);
  std::vector<Vector3>& x = state.positions();
  std::vector<Vector3> g, trial_g, step, trial(n);
  std::vector<double> l, trial_l;
  const double first_mu = tuning.barrier_first_parameter;
  const double final_mu = std::min(first_mu, std::max(tuning.barrier_final_fraction * options.tolerance, 1e-12));
  std::size_t short_steps = 0;
  double mu = first_mu;
  for(;; mu = std::max(mu / tuning.barrier_reduction, final_mu))
  {
    solver.set_face_scales(x);
    const bool last = mu == final_mu;
    const double phase_tolerance =
        last ? options.tolerance : std::max(options.tolerance, tuning.barrier_phase_factor * mu);
    solver.gradient(x, mu, g, l);
    for(;;)
    {
      if(past_time_budget(options, clock))
        return report;
      if(options.cancel_requested())
      {
        report.cancelled = true;
        return report;
      }
      if(report.newton_steps >= options.max_newton_sweeps)
        return report;
      double max_g = 0., merit = 0.;
      Constrained_balance::scaled_norms(g, l, max_g, merit);
      if(max_g <= phase_tolerance)
        break;
      if(!solver.newton_step(x, mu, g, step))
        return report;
      // Rotations change nothing; the boost part, along the nearly singular directions, is applied as an exact
      // boost (as in mobius_newton.h): added and projected, it folded the map at every step length.
      Vector3 rotation, boost;
      remove_rotation_and_boost(x, step, rotation, boost);
      double max_trial = 0., trial_merit = 0.;
      const double t = backtracking_line_search(
          tuning.newton_min_step,
          [&](double s) {
            for(std::size_t i = 0; i < n; ++i)
            {
              const Vector3 y = x[i] + s * step[i];
              trial[i] = apply_boost(y * (1. / length(y)), s * boost);
            }
            return state.keeps_positive_faces(trial) && solver.gradient(trial, mu, trial_g, trial_l);
          },
          [&](double) {
            Constrained_balance::scaled_norms(trial_g, trial_l, max_trial, trial_merit);
            return trial_merit < merit;
          });
      // A phase whose steps stall ends: the next, smaller mu often moves on (homer: no step at mu = 1e-2, then
      // full steps from mu = 1e-3 on).
      if(t == 0.)
        break;
      state.assign(trial, true);
      g.swap(trial_g); // the line search computed the gradient at the accepted point
      l.swap(trial_l);
      ++report.newton_steps;
      short_steps = t >= 0.25 ? 0 : short_steps + 1;
      if(short_steps >= tuning.barrier_patience)
        break;
    }
    if(last)
      break;
  }
  solver.gradient(x, mu, g, l);
  double max_g = 0., merit = 0.;
  Constrained_balance::scaled_norms(g, l, max_g, merit);
  report.reached = max_g <= options.tolerance;
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_CONSTRAINED_BALANCE_H
