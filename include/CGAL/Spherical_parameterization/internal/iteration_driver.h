// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The loop that every iterative stage shares (stage 2's Gauss-Seidel, the paper's local Newton, the Moebius-aware
// and the cautious Newton): Iteration_driver owns the caps, the time budget, progress and cancellation, stagnation,
// the best iterate and the counters; a stage supplies only its iteration. It also measures each iterate once (Res
// and every imbalance in one pass: measure_map), where the stopping test, the stagnation rule and the best-iterate
// rule each used to measure it again. backtracking_line_search() is the line search of every global step.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ITERATION_DRIVER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ITERATION_DRIVER_H

#include <CGAL/Spherical_parameterization/internal/Sphere_state.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/solver_tuning.h>

#include <CGAL/Real_timer.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

class Laplacian_preconditioner_ahead; // stage3/tangent_multigrid.h

struct Iteration_options
{
  double tolerance = 1e-6;
  Convergence_test convergence_test = Convergence_test::IMBALANCE;
  std::size_t max_gauss_seidel_sweeps = 1000;
  std::size_t max_newton_sweeps = 200000;
  double max_seconds = -1.; // negative: no budget
  bool preserve_bijectivity = true;
  Solver_tuning tuning;
  // Called after every sweep; returning false cancels the iterations.
  std::function<bool(const char* stage, std::size_t sweep, double residual, std::size_t invalid_faces)> progress;
  // Polled inside long iterations (it repeats the last progress report); returning false cancels.
  std::function<bool()> keep_going;
  // Stage 3's preconditioner of the system being solved, built ahead on another thread (levels of the multilevel
  // start with CGAL::Parallel_tag), or nullptr: stage 3 builds its own.
  Laplacian_preconditioner_ahead* preconditioner_ahead = nullptr;
  // CGAL::Parallel_tag with TBB: on meshes of tuning.side_by_side_min_vertices or more, stage 3 runs independent
  // computations at the same time (side_by_side.h; the iterates do not change).
  bool parallel = false;
  // The stage that mobius_newton's progress reports name (Progress::stage): "weight continuation" for its solves along
  // the weight continuation (weight_continuation.h), whose counts start again at each blend of the weights.
  const char* newton_stage = "global newton";
  // The least-distortion minimization follows where this call ends unconverged (named parameter least_distortion):
  // global_newton() leaves out its last resort, the cautious Newton, whose map that minimization would replace, and
  // every way to the balanced map ends as soon as Newton's full steps reach a folded one
  // (Iteration_report::balanced_map_folded): the minimization is the answer then.
  bool least_distortion_follows = false;
  // Stage 3 ends after Newton's full steps (global_newton): a retry from another partition's two-disk guess
  // (Sphere_mapper::retry_other_partitions), where the slow bijectivity-preserving steps have had their turn already.
  bool free_steps_only = false;

  bool cancel_requested() const { return keep_going && !keep_going(); }
};

struct Iteration_report
{
  std::size_t sweeps = 0;
  double residual = -1.;
  bool converged = false;
  bool out_of_time = false;
  bool stagnated = false; // the convergence measure stopped decreasing before the tolerance
  bool cancelled = false; // the progress callback asked to stop
  std::size_t rejected_moves = 0;
  std::size_t linear_iterations = 0;   // iterations of the iterative linear solver (MINRES), if one ran
  double continuation_parameter = -1.; // how far the continuation from Tutte's weights got (-1: not tried)
  // The tips solved with regularized weights (stage3/tip_regularization.h) when the map returned needed them.
  std::vector<char> regularized_tips;
  // Per vertex the continuation parameter its weights are held at (weight_continuation.h) when the map returned is
  // balanced for those held weights; empty otherwise.
  std::vector<double> weight_holds;
  // Newton's full steps reached a balanced map of degree 1 with non-positive faces (not only tips below double
  // precision, which tip_regularization.h resolves), or approached one linearly with the rest of the map nearly
  // balanced (mobius_newton.h): the weights' balanced map found is not bijective.
  bool balanced_map_folded = false;
  // That folded balanced map, when balanced_map_folded (the least-distortion minimization may start from it, its
  // folds repaired: stage3/fold_repair.h); empty otherwise.
  std::vector<Vector3> folded_balanced_map;
};

// The time budget, checked between iterations and, inside the long ones, between their parts.
inline bool past_time_budget(const Iteration_options& options, const CGAL::Real_timer& clock)
{
  return options.max_seconds >= 0. && clock.time() > options.max_seconds;
}

// What a part that asks often (a MINRES solve between its iterations, a factorization between its supernodes) is told:
// stop on a cancel, which `cancelled` remembers (the poll behind it answers at most every tenth of a second), or past
// the time budget.
inline bool stop_requested(const Iteration_options& options, const CGAL::Real_timer& clock, bool& cancelled)
{
  cancelled = cancelled || options.cancel_requested();
  return cancelled || past_time_budget(options, clock);
}

// Whether a part that cannot be interrupted (a factorization, a sweep), as long as the last one (`last_seconds`),
// would end past the time budget if started now.
inline bool next_part_passes_time_budget(const Iteration_options& options, const CGAL::Real_timer& clock,
                                         double last_seconds)
{
  return options.max_seconds >= 0. && clock.time() + last_seconds > options.max_seconds;
}

// The stopping test of every solver: no non-positive face, and every vertex balanced in its own scale (or the
// paper's Res below the tolerance, when that test was chosen). For non-symmetric weights, whose equations generally
// have no exact solution, the imbalance test bounds the stationarity of their least-squares problem instead.
inline bool has_converged(const Map_measure& measure, std::size_t invalid_faces, const Iteration_options& options)
{
  if(invalid_faces != 0)
    return false;
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL)
    return measure.residual < options.tolerance;
  return measure.tested().balanced();
}

// What the stagnation rules watch: the quantity the convergence test bounds (the worst imbalance over its allowed
// value, or Res). Res alone keeps falling on a map that drifts towards collapse while no vertex gets balanced.
inline double convergence_measure(const Map_measure& measure, const Iteration_options& options)
{
  return options.convergence_test == Convergence_test::PAPER_RESIDUAL ? measure.residual : measure.tested().worst_ratio;
}

// Backtracking along a step: t = 1, 1/2, 1/4, ... while t > min_step. `admissible(t)` builds the trial point at t and
// says whether it may be judged at all (orientation or degree kept); `acceptable(t)` judges it (a merit decreased).
// Returns the t taken, 0 when none was.
template <typename Admissible, typename Acceptable>
double backtracking_line_search(double min_step, Admissible&& admissible, Acceptable&& acceptable)
{
  for(double t = 1.; t > min_step; t *= 0.5)
  {
    if(!admissible(t))
      continue;
    if(acceptable(t))
      return t;
  }
  return 0.;
}

class Iteration_driver
{
public:
  // `stage`: the name in progress reports; `max_iterations`: the cap.
  Iteration_driver(Sphere_state& state, const Iteration_options& options, const CGAL::Real_timer& clock,
                   const char* stage, std::size_t max_iterations)
    : m_state(state), m_options(options), m_clock(clock), m_stage(stage), m_max_iterations(max_iterations)
  {}

  // Stop when the convergence measure fell by less than 1 - tuning.stagnation_ratio over `window` iterations.
  void watch_stagnation(std::size_t window) { m_stagnation_window = window; }

  // Keep the best iterate from now on: the fewest non-positive faces, then the lowest imbalances (root mean square;
  // never Res: the iterate of lowest Res can be the most collapsed one). restore_best() puts it back.
  void keep_best_iterate()
  {
    m_keep_best = true;
    const Map_measure& now = measure();
    m_best = m_state.positions();
    m_best_invalid = m_state.invalid_faces();
    m_best_imbalance = now.imbalance.rms;
  }

  // The measures of the current iterate, computed once per change of the positions. `residual`, when given,
  // replaces Res (the paper's sweeps compute their own from the cached sums, in another rounding).
  const Map_measure& measure()
  {
    if(!m_measured || m_measured_revision != m_state.revision())
    {
      m_measure = measure_map(m_state.system(), m_state.positions(), m_options.tolerance);
      m_measured = true;
      m_measured_revision = m_state.revision();
      if(m_has_given_residual && m_given_residual_revision == m_measured_revision)
        m_measure.residual = m_given_residual; // end_iteration(residual) was told it for these positions
    }
    return m_measure;
  }
  const Map_measure& measure(double residual)
  {
    measure();
    m_measure.residual = residual;
    return m_measure;
  }

  bool converged() { return has_converged(measure(), m_state.invalid_faces(), m_options); }

  // Whether another iteration may start: the map is not converged yet (when `test_convergence`), the cap is not
  // reached, and the time budget is not spent (report().out_of_time).
  bool may_start(bool test_convergence = true)
  {
    if(test_convergence && converged())
      return false;
    if(m_report.sweeps >= m_max_iterations)
      return false;
    return within_budget(false);
  }

  // Between the parts of a long iteration: false when a cancel was asked for (report().cancelled) or the time budget
  // is spent (report().out_of_time).
  bool within_budget(bool poll_cancel = true)
  {
    if(poll_cancel && m_options.cancel_requested())
    {
      m_report.cancelled = true;
      return false;
    }
    if(past_time_budget(m_options, m_clock))
    {
      m_report.out_of_time = true;
      return false;
    }
    return true;
  }

  // An iteration that produced no new iterate but counts against the cap (it is not reported).
  void count_retry() { ++m_report.sweeps; }

  // After an iteration: counts it, measures the new iterate (`residual`: as in measure()), keeps the best, reports
  // progress and watches stagnation. False when the loop must stop: cancelled, or stagnated (report().stagnated).
  bool end_iteration(double residual = -1.)
  {
    ++m_report.sweeps;
    // The map is measured only for what needs more than Res (the best iterate, stagnation): on the multilevel
    // smoothing sweeps nothing does.
    if(!m_keep_best && m_stagnation_window == 0 && residual >= 0.)
    {
      m_has_given_residual = true;
      m_given_residual = residual;
      m_given_residual_revision = m_state.revision();
      if(m_options.progress && !m_options.progress(m_stage, m_report.sweeps, residual, m_state.invalid_faces()))
      {
        m_report.cancelled = true;
        return false;
      }
      return true;
    }
    const Map_measure& now = residual >= 0. ? measure(residual) : measure();
    if(m_keep_best)
    {
      const std::size_t invalid = m_state.invalid_faces();
      if(invalid < m_best_invalid || (invalid == m_best_invalid && now.imbalance.rms < m_best_imbalance))
      {
        m_best = m_state.positions();
        m_best_invalid = invalid;
        m_best_imbalance = now.imbalance.rms;
      }
    }
    if(m_options.progress && !m_options.progress(m_stage, m_report.sweeps, now.residual, m_state.invalid_faces()))
    {
      m_report.cancelled = true;
      return false;
    }
    if(m_stagnation_window > 0)
    {
      m_history.push_back(convergence_measure(now, m_options));
      if(m_history.size() > m_stagnation_window
         && m_history.back()
                > m_options.tuning.stagnation_ratio * m_history[m_history.size() - 1 - m_stagnation_window])
      {
        m_report.stagnated = true;
        return false;
      }
    }
    return true;
  }

  // Puts the best iterate back (after keep_best_iterate()), or the given positions.
  void restore_best()
  {
    if(m_keep_best)
      m_state.assign(m_best);
  }
  void restore(const std::vector<Vector3>& positions) { m_state.assign(positions); }

  // The counters and flags, with the final Res and convergence filled in.
  Iteration_report& finish()
  {
    m_report.residual = measure().residual;
    m_report.converged = converged();
    return m_report;
  }
  Iteration_report& report() { return m_report; }
  std::size_t iterations() const { return m_report.sweeps; }

private:
  Sphere_state& m_state;
  const Iteration_options& m_options;
  const CGAL::Real_timer& m_clock;
  const char* m_stage;
  std::size_t m_max_iterations;
  Iteration_report m_report;
  Map_measure m_measure;
  bool m_measured = false;
  std::size_t m_measured_revision = 0;
  // Res as given to end_iteration() without a measure, for the positions of that revision.
  bool m_has_given_residual = false;
  double m_given_residual = 0.;
  std::size_t m_given_residual_revision = 0;
  std::size_t m_stagnation_window = 0;
  std::vector<double> m_history;
  bool m_keep_best = false;
  std::vector<Vector3> m_best;
  std::size_t m_best_invalid = 0;
  double m_best_imbalance = 0.;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_ITERATION_DRIVER_H
