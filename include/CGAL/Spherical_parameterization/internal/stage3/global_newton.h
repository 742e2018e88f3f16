// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 3, beyond the paper: Newton's method on all vertices at once, in tangent coordinates.
//
// Non-symmetric weights (mean value) minimize their imbalances by the least-squares iterations of
// imbalance_least_squares.h (least_squares_newton() below).
// global_newton() first runs the Moebius-aware Newton of mobius_newton.h (symmetric weights), which converges
// in a few steps on most meshes. Where its steps keep being cut short, weights other than Tutte's are reached by
// continuation from Tutte's (weight_continuation.h), then by interior-point iterations from where the path ends
// (constrained_balance.h). Where that fails too (non-symmetric weights, meshes whose
// thin parts must shrink by orders of magnitude, weights whose solutions degenerate), the cautious Newton below
// takes over from the best iterate:
// unknowns d_i in the tangent planes, equations F_i = T_i^T sum_j W_ij x_j, the Jacobian
// dF_i = -(x_i . s_i) d_i + sum_j W_ij T_i^T T_j d_j with a tiny diagonal shift against the rotations
// (Levenberg-Marquardt steps (J^T J + mu I) d = J^T F for non-symmetric weights under the paper's criterion), each step halved until it keeps
// every positively oriented triangle positive (exact predicate) and lowers the paper's residual, and the
// paper's local Newton sweeps whenever no such step exists.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_GLOBAL_NEWTON_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_GLOBAL_NEWTON_H

#include <CGAL/Spherical_parameterization/internal/small_symmetric_matrix.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/stage3/constrained_balance.h>
#include <CGAL/Spherical_parameterization/internal/stage3/imbalance_least_squares.h>
#include <CGAL/Spherical_parameterization/internal/stage3/mobius_newton.h>
#include <CGAL/Spherical_parameterization/internal/stage3/sparse_factorization.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_newton_system.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tip_regularization.h>
#include <CGAL/Spherical_parameterization/internal/stage3/weight_continuation.h>

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

class Global_newton
{
public:
  Global_newton(const Sphere_system& system, const Solver_tuning& tuning, bool preserve_bijectivity = true)
    : m_system(system), m_tuning(tuning), m_preserve_bijectivity(preserve_bijectivity),
      m_marquardt(tuning.marquardt_initial), m_damping(tuning.cautious_damping)
  {}

  // One Newton step; returns false when no acceptable step was found, or when `options` asked to stop in the middle
  // (then cancelled() is true).
  bool step(Sphere_state& state, double& residual, const Iteration_options* options = nullptr)
  {
    m_cancelled = false;
    const std::size_t n = m_system.number_of_vertices;
    const std::vector<Vector3>& x = state.positions();
    tangent_frames(x, m_t1, m_t2);

    if(m_jacobian.rows() != Eigen::Index(2 * n))
      build_pattern();
    Eigen::VectorXd rhs(2 * n);
    double* values = m_jacobian.valuePtr();
    for(std::size_t i = 0; i < n; ++i)
    {
      const double scale = m_system.row_sums[i];
      const Vector3 s = scale * state.sum(i);
      const double alpha = dot(x[i], s);
      rhs[2 * i] = -dot(m_t1[i], s);
      rhs[2 * i + 1] = -dot(m_t2[i], s);
      const double diagonal = -alpha * (1. + m_damping);
      const std::array<std::size_t, 4>& d = m_diagonal_slots[i];
      values[d[0]] = diagonal;
      values[d[1]] = 0.;
      values[d[2]] = 0.;
      values[d[3]] = diagonal;
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        const double w = m_system.weights[k] * scale;
        const std::array<std::size_t, 4>& slot = m_block_slots[k];
        const std::array<double, 4> block = tangent_block(w, m_t1[i], m_t2[i], m_t1[j], m_t2[j]);
        for(int b = 0; b < 4; ++b)
          values[slot[b]] = block[b];
      }
    }
    const Eigen::SparseMatrix<double>& jacobian = m_jacobian;

    // Symmetric weights: plain Newton. Otherwise the rotations are not an exact null space of the equations,
    // and Newton's step blows up along them: take Levenberg-Marquardt steps (J^T J + mu I) d = J^T rhs instead.
    for(int attempt = 0; attempt < (m_system.symmetric ? 1 : m_tuning.marquardt_attempts); ++attempt)
    {
      if(attempt > 0 && options != nullptr && options->cancel_requested())
      {
        m_cancelled = true;
        return false;
      }
      Eigen::VectorXd delta;
      if(m_system.symmetric)
      {
        if(!solve(jacobian, rhs, delta))
          return false;
      }
      else
      {
        Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(jacobian.transpose()) * jacobian;
        const double shift = m_marquardt * normal.diagonal().mean();
        for(int k = 0; k < normal.rows(); ++k)
          normal.coeffRef(k, k) += shift;
        // The pattern of J^T J is the same at every step: order it (METIS) once, factorize every time (ordering it
        // at every attempt was slow: the manual's Method section).
        if(!m_ldlt.factorize(normal))
          return false;
        delta = m_ldlt.solver().solve(jacobian.transpose() * rhs);
        if(!delta.allFinite())
          return false;
      }
      double accepted_t = 0.;
      if(try_step(state, residual, delta, accepted_t))
      {
        if(!m_system.symmetric)
          m_marquardt = accepted_t == 1. ? std::max(m_marquardt / 3., 1e-12) : m_marquardt * 2.;
        return true;
      }
      m_marquardt = std::min(m_marquardt * 10., m_tuning.marquardt_max);
    }
    return false;
  }

  bool cancelled() const { return m_cancelled; }

private:
  // Line search along delta (halving t) for a point that keeps every positive face positive and lowers Res.
  bool try_step(Sphere_state& state, double& residual, const Eigen::VectorXd& delta, double& accepted_t)
  {
    const std::size_t n = m_system.number_of_vertices;
    const std::vector<Vector3>& x = state.positions();
    std::vector<Vector3> displacement(n);
    for(std::size_t i = 0; i < n; ++i)
      displacement[i] = delta[2 * i] * m_t1[i] + delta[2 * i + 1] * m_t2[i];
    remove_rotation(x, displacement);

    std::vector<Vector3> trial(n);
    double trial_residual = 0.;
    accepted_t = backtracking_line_search(
        m_tuning.cautious_min_step,
        [&](double t) {
          for(std::size_t i = 0; i < n; ++i)
          {
            Vector3 y = x[i] + t * displacement[i];
            trial[i] = y * (1. / length(y));
          }
          return !m_preserve_bijectivity || state.keeps_positive_faces(trial);
        },
        [&](double) {
          trial_residual = compute_residuals(m_system, trial).paper;
          return trial_residual < residual;
        });
    if(accepted_t == 0.)
      return false;
    state.assign(trial, m_preserve_bijectivity);
    residual = trial_residual;
    return true;
  }

  // Subtracts the infinitesimal rotation omega x x_i that best fits the displacements (least squares):
  // rotations leave the residual unchanged, so a rotation part in the step only adds second-order error.
  static void remove_rotation(const std::vector<Vector3>& x, std::vector<Vector3>& d)
  {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for(std::size_t i = 0; i < x.size(); ++i)
    {
      const Eigen::Vector3d xi(x[i].x, x[i].y, x[i].z);
      normal += Eigen::Matrix3d::Identity() - xi * xi.transpose();
      const Vector3 m = cross(x[i], d[i]);
      moment += Eigen::Vector3d(m.x, m.y, m.z);
    }
    const Eigen::Vector3d omega = solve_symmetric(normal, moment);
    const Vector3 w(omega[0], omega[1], omega[2]);
    for(std::size_t i = 0; i < x.size(); ++i)
      d[i] -= cross(w, x[i]);
  }

  bool solve(const Eigen::SparseMatrix<double>& jacobian, const Eigen::VectorXd& rhs, Eigen::VectorXd& delta)
  {
    if(m_system.symmetric)
    {
      if(m_ldlt.factorize(jacobian))
      {
        delta = m_ldlt.solver().solve(rhs);
        if(m_ldlt.solver().info() == Eigen::Success && delta.allFinite())
          return true;
      }
    }
    if(!m_lu.factorize(jacobian))
      return false;
    delta = m_lu.solver().solve(rhs);
    return m_lu.solver().info() == Eigen::Success && delta.allFinite();
  }

  // The Jacobian's pattern (2x2 blocks of the vertex adjacency plus the diagonal) and, for every block, where its
  // four values sit in the compressed storage, so that each step writes values in place without sorting.
  void build_pattern() { build_block_pattern(m_system, m_jacobian, m_diagonal_slots, m_block_slots); }

  const Sphere_system& m_system;
  const Solver_tuning& m_tuning;
  bool m_preserve_bijectivity;
  Eigen::SparseMatrix<double> m_jacobian;
  std::vector<std::array<std::size_t, 4>> m_diagonal_slots, m_block_slots;
  bool m_cancelled = false;
  double m_marquardt; // relative Levenberg-Marquardt shift (non-symmetric weights)
  double m_damping;   // relative diagonal shift: keeps the rotations from blowing up the step
  std::vector<Vector3> m_t1, m_t2;
  Sparse_ldlt m_ldlt; // J (symmetric weights) or J^T J
  Sparse_lu m_lu;
};

// Cautious global Newton steps until the convergence test holds; a batch of local Newton sweeps whenever no
// acceptable global step exists, then Newton again. When it does not converge, the best iterate is returned.
// Stagnation: non-symmetric weights (mean value) generally admit no exact solution, because the three torque
// identities that make the equations consistent for symmetric weights fail; the residual then levels off at a
// least-squares floor (tuning.cautious_stagnation_window).
inline Iteration_report cautious_newton(Sphere_state& state, const Iteration_options& options,
                                        const CGAL::Real_timer& clock)
{
  const Solver_tuning& tuning = options.tuning;
  Iteration_driver driver(state, options, clock, "global newton", options.max_newton_sweeps);
  driver.watch_stagnation(tuning.cautious_stagnation_window);
  Global_newton newton(state.system(), tuning, options.preserve_bijectivity);
  state.refresh_sums();
  double residual = driver.measure().residual;
  driver.keep_best_iterate();
  while(driver.may_start())
  {
    if(!newton.step(state, residual, &options))
    {
      if(newton.cancelled())
      {
        driver.report().cancelled = true;
        break;
      }
      // No global step helps: relax locally for a while.
      for(int sweep = 0; sweep < tuning.cautious_local_sweeps_without_step; ++sweep)
        for(std::size_t i = 0; i < state.system().number_of_vertices; ++i)
          if(!local_newton_step(state, i, options.preserve_bijectivity))
            ++driver.report().rejected_moves;
      state.refresh_sums();
      residual = driver.measure().residual;
    }
    if(!driver.end_iteration())
      break;
  }
  if(!driver.converged())
    driver.restore_best();
  return driver.finish();
}

// True when every raw weight is the same (Tutte's weights, up to a factor).
inline bool has_tutte_weights(const Sphere_system& system)
{
  if(system.weights.empty())
    return true;
  const double first = system.weights[0] * system.row_sums[0];
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      if(std::abs(system.weights[k] * system.row_sums[i] - first) > 1e-12 * std::abs(first))
        return false;
  return true;
}

// Newton's full steps through folds (mobius_newton with allow_folds). When they end on a balanced map whose
// non-positive faces all lie in arm tips below double precision, the tips are regularized (tip_regularization.h)
// and the steps go on from that map under those weights; the report then names the tips (regularized_tips).
inline Iteration_report newton_through_folds(Sphere_state& state, const Iteration_options& options,
                                             const CGAL::Real_timer& clock, Mobius_newton_statistics* statistics,
                                             Step_merit step_merit = Step_merit::RESIDUAL,
                                             Boost_aim boost_aim = Boost_aim::MAXIMUM,
                                             bool* other_merit_agrees = nullptr)
{
  Mobius_newton_statistics counts;
  Iteration_report report = mobius_newton(state, options, clock, &counts, options.tuning.free_newton_patience, true,
                                          step_merit, boost_aim, other_merit_agrees);
  if(!counts.folded_balanced_map.empty() && !report.cancelled && !report.out_of_time)
  {
    const Sphere_system& system = state.system();
    std::vector<char> tips = unresolvable_tips(system, counts.folded_balanced_map, options.tuning.tip_scale);
    if(!tips.empty())
    {
      const Sphere_system regularized = regularize_tips(system, tips, options.tuning.tip_weight_ratio_per_ring);
      std::vector<Vector3> x = counts.folded_balanced_map;
      if(place_tips(regularized, tips, options.tuning.tip_band_scale, x))
      {
        Sphere_state tip_state(regularized, x);
        Iteration_options remaining = options;
        remaining.max_newton_sweeps =
            options.max_newton_sweeps > report.sweeps ? options.max_newton_sweeps - report.sweeps : 0;
        Mobius_newton_statistics tip_counts;
        bool tip_steps_agree = true;
        Iteration_report tip_report =
            mobius_newton(tip_state, remaining, clock, &tip_counts, options.tuning.free_newton_patience, true,
                          step_merit, boost_aim, other_merit_agrees != nullptr ? &tip_steps_agree : nullptr);
        if(other_merit_agrees != nullptr)
          *other_merit_agrees = *other_merit_agrees && tip_steps_agree;
        if(tip_report.converged || tip_report.cancelled || tip_report.out_of_time)
        {
          state.assign(x);
          tip_report.sweeps += report.sweeps;
          tip_report.linear_iterations += report.linear_iterations;
          tip_report.rejected_moves += report.rejected_moves;
          tip_report.regularized_tips = std::move(tips);
          tip_counts.newton_steps += counts.newton_steps;
          tip_counts.linear_iterations += counts.linear_iterations;
          report = std::move(tip_report);
          counts = std::move(tip_counts);
        }
      }
    }
    // Folds that are all arm tips below double precision (tips not empty) are a matter of precision, not of the weights.
    report.balanced_map_folded = tips.empty() && !report.converged && !report.cancelled && !report.out_of_time;
    if(report.balanced_map_folded && options.least_distortion_follows) // the minimization's start (Sphere_mapper)
      report.folded_balanced_map = std::move(counts.folded_balanced_map);
  }
  if(statistics != nullptr)
    *statistics = std::move(counts);
  return report;
}

// Newton's full steps through folds from the current map; when they do not converge (nor were stopped), once more
// from the same map with the line search on the scale-free imbalances instead of Res (see Step_merit: Res led
// some steps along the boosts towards a collapse). The first phase from the two-disk guess and on each multilevel
// level (`boost_aim`: Boost_aim::ROOT there). The reports of both attempts are added up. The retry is skipped where
// the imbalances judged every trial of the first attempt's line searches as Res did: it would take the same steps,
// one for one (vol2surf_lh_pial with cotangent weights: two steps on 110,646 vertices, about 3 s, taken twice).
inline Iteration_report full_newton_steps(Sphere_state& state, const Iteration_options& options,
                                          const CGAL::Real_timer& clock, Boost_aim boost_aim = Boost_aim::MAXIMUM)
{
  const std::vector<Vector3> start = state.positions();
  bool imbalances_agree = true;
  Iteration_report report =
      newton_through_folds(state, options, clock, nullptr, Step_merit::RESIDUAL, boost_aim, &imbalances_agree);
  if(report.converged || report.cancelled || report.out_of_time
     || (report.balanced_map_folded && options.least_distortion_follows) || imbalances_agree)
    return report;
  state.assign(start);
  const std::size_t first_sweeps = report.sweeps, first_linear_iterations = report.linear_iterations;
  report = newton_through_folds(state, options, clock, nullptr, Step_merit::IMBALANCE, boost_aim);
  report.sweeps += first_sweeps;
  report.linear_iterations += first_linear_iterations;
  return report;
}

// Non-symmetric weights (mean value): the least-squares iterations of imbalance_least_squares.h, which minimize the
// imbalances in their own scale, after at most 50 cautious Newton steps where the map has non-positive faces (they
// start from a bijective map). With the paper's criterion (Res, whose least-squares problem the collapse solves), the
// cautious Newton alone, as the paper's test asks.
inline Iteration_report least_squares_newton(Sphere_state& state, const Iteration_options& options,
                                             const CGAL::Real_timer& clock)
{
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL)
    return cautious_newton(state, options, clock);
  Iteration_report report;
  if(state.invalid_faces() != 0)
  {
    Iteration_options repair = options;
    repair.max_newton_sweeps = std::min<std::size_t>(options.max_newton_sweeps, 50);
    report = cautious_newton(state, repair, clock);
    if(report.converged || report.cancelled || report.out_of_time)
      return report;
  }
  Iteration_options remaining = options;
  remaining.max_newton_sweeps =
      options.max_newton_sweeps > report.sweeps ? options.max_newton_sweeps - report.sweeps : 0;
  const Least_squares_report least_squares = imbalance_least_squares(state, remaining, clock);
  report.sweeps += least_squares.steps;
  report.cancelled = least_squares.cancelled;
  report.out_of_time = least_squares.out_of_time;
  const Map_measure measure = measure_map(state.system(), state.positions(), options.tolerance);
  report.residual = measure.residual;
  report.converged = has_converged(measure, state.invalid_faces(), options);
  report.stagnated = !report.converged && !report.cancelled && !report.out_of_time;
  return report;
}

// Stage 3. Symmetric weights: Newton's steps through folds, then the bijectivity-preserving Moebius-aware Newton; if it gives up and the weights are not Tutte's, the
// continuation from Tutte's weights; if that fails too, the cautious Newton from the best iterate so far.
// Non-symmetric weights: least_squares_newton().
// `tutte_map`, when given (hold_weights), computes the balanced map of Tutte's weights (the whole pipeline with uniform
// weights): where every way above fails, the continuation starts again from it and holds the weights where its path
// would end (weight_continuation.h).
inline Iteration_report global_newton(Sphere_state& state, const Iteration_options& options,
                                      const CGAL::Real_timer& clock,
                                      const std::vector<Vector3>* initial_guess = nullptr,
                                      const std::function<bool(std::vector<Vector3>&)>& tutte_map = {})
{
  const Sphere_system& system = state.system();
  if(!system.symmetric)
    return least_squares_newton(state, options, clock);
  // Full Newton steps through folds first: on most meshes the fastest way to the balanced map.
  Mobius_newton_statistics statistics;
  Iteration_report free_steps = newton_through_folds(state, options, clock, &statistics);
  if(free_steps.converged || free_steps.cancelled || free_steps.out_of_time
     || (free_steps.balanced_map_folded && options.least_distortion_follows) || options.free_steps_only)
    return free_steps;
  // Otherwise from where it started (restored: its best iterate has the fewest non-positive faces), with every step
  // keeping every positive triangle positive.
  Iteration_options remaining_options = options;
  remaining_options.max_newton_sweeps =
      options.max_newton_sweeps > free_steps.sweeps ? options.max_newton_sweeps - free_steps.sweeps : 0;
  Iteration_report report =
      mobius_newton(state, remaining_options, clock, &statistics, options.tuning.cautious_patience);
  report.sweeps += free_steps.sweeps;
  report.linear_iterations += free_steps.linear_iterations;
  if(!statistics.gave_up)
    return report;
  if(!has_tutte_weights(system))
  {
    const std::vector<Vector3> start = state.positions();
    const Continuation_report continuation =
        weight_continuation(system, state.positions(), options, clock, initial_guess);
    state.assign(state.positions());
    report.sweeps += continuation.newton_steps;
    report.continuation_parameter = continuation.last_parameter;
    // Whether the map reached by the continuation or the interior-point iterations passes the convergence test.
    auto passes_the_test = [&]() {
      const Map_measure measure = measure_map(system, state.positions(), options.tolerance);
      report.residual = measure.residual;
      report.converged = has_converged(measure, state.invalid_faces(), options);
      report.stagnated = false;
      return report.converged;
    };
    if(continuation.reached && passes_the_test())
      return report;
    if(continuation.cancelled)
    {
      report.cancelled = true;
      return report;
    }
    // Where the path ends, the interior-point iterations (constrained_balance.h) continue towards the target
    // weights' balanced map, every iterate bijective.
    const Constrained_balance_report barrier = constrained_balance(state, options, clock);
    report.sweeps += barrier.newton_steps;
    if(barrier.reached && passes_the_test())
      return report;
    if(barrier.cancelled)
    {
      report.cancelled = true;
      return report;
    }
    // The cautious Newton goes on from the better of the two maps (lower root mean square imbalance, the best
    // iterate's rule) and returns its best iterate, so the result is never worse than either. Where the barrier's
    // steps stall before the tolerance, its map is usually the better one by far (the manual's Method section).
    if(!(imbalance_merit(system, state.positions()) < imbalance_merit(system, start)))
      state.assign(start);
  }
  // With least_distortion, the minimization of the distortion is the last resort instead (it comes sooner: CGAL's
  // dino 4.7 s instead of 21, man reached at all within 60 s; handle and part, which the cautious Newton balances,
  // get the least-distortion map instead, closer to conformal: the manual's Method section).
  if(options.least_distortion_follows)
    return report;
  Iteration_options remaining = options;
  remaining.max_newton_sweeps =
      options.max_newton_sweeps > report.sweeps ? options.max_newton_sweeps - report.sweeps : 0;
  Iteration_report cautious = cautious_newton(state, remaining, clock);
  cautious.sweeps += report.sweeps;
  cautious.rejected_moves += report.rejected_moves;
  cautious.linear_iterations += report.linear_iterations;
  cautious.continuation_parameter = report.continuation_parameter;
  // With hold_weights, the last way to a certified map: the continuation again, from Tutte's balanced map, holding the
  // weights where its path would end. Last, so that a map balanced for the weights given is never traded for a held
  // one: with the held continuation right after the first continuation, CGAL's homer (balanced by the interior-point
  // iterations: angle error 4.3 degrees) ended with 4,930 of its vertices held (15.8 degrees), and handle (balanced
  // by the cautious Newton: 5.1 degrees) with 1,165 (25.6 degrees).
  if(tutte_map && !has_tutte_weights(system) && !cautious.converged && !cautious.cancelled
     && !past_time_budget(options, clock))
  {
    std::vector<Vector3> balanced_tutte;
    if(tutte_map(balanced_tutte) && balanced_tutte.size() == state.positions().size())
    {
      std::vector<Vector3> y = balanced_tutte;
      const Continuation_report held = weight_continuation(system, y, options, clock, &balanced_tutte, true);
      cautious.sweeps += held.newton_steps;
      cautious.cancelled = held.cancelled;
      if(held.reached && !held.cancelled)
      {
        // Balanced for the held weights (the weights given where none is held): the caller measures and certifies
        // the map with them (Result::held_weight_*).
        Sphere_system held_system = system;
        blend_with_tutte(system, 1., held_system, &held.holds);
        const Sphere_state held_state(held_system, y);
        const Map_measure measure = measure_map(held_system, y, options.tolerance);
        if(has_converged(measure, held_state.invalid_faces(), options))
        {
          state.assign(y);
          cautious.residual = measure.residual;
          cautious.converged = true;
          cautious.stagnated = false;
          cautious.out_of_time = false;
          cautious.weight_holds = held.holds;
        }
      }
    }
  }
  return cautious;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_GLOBAL_NEWTON_H
