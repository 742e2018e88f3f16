// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 3, beyond the paper, for symmetric weights: Newton's method on all vertices at once with the Moebius
// boosts handled exactly (see mobius.h).
//
// Each iteration (1) balances the boosts (maximizes the spring energy over them), (2) solves Newton's system in
// tangent coordinates (tangent_newton_system.h), (3) splits the step into its rotation part (dropped: rotations
// change nothing), its boost part (applied as an exact boost, whose linearization is poor) and the rest (added
// and projected back onto the sphere), and (4) shortens the step until every positive triangle stays positive
// (exact predicate) and the merit decreases (Step_merit; through folds, where none does, below the largest of the last
// few merits); when no such step exists, five of the paper's local Newton sweeps move the iterate instead. When the
// steps keep being cut short, it gives up and restores its best iterate, so that another strategy can continue
// (global_newton.h).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_NEWTON_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_NEWTON_H

#include <CGAL/Spherical_parameterization/internal/side_by_side.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/stage3/mobius.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_krylov_system.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_newton_system.h>

#include <CGAL/number_type_config.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Mobius_newton_statistics
{
  std::size_t newton_steps = 0;      // accepted Newton steps
  bool gave_up = false;              // Newton's steps were too short: the caller should continue otherwise
  std::size_t linear_iterations = 0; // MINRES iterations (iterative linear solves only)
  // The steps through folds reached a balanced map with non-positive faces: that map (tip_regularization.h).
  std::vector<Vector3> folded_balanced_map;
};

// The signed spherical areas add up to 4 pi times the degree of the map. Folds keep the degree; a collapse of the
// map onto a small cap, the trivial solution the boosts lead to, has to pass through a triangle larger than a
// hemisphere, which changes the sum by a multiple of 4 pi.
inline bool has_degree_one(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double area = 0.;
  for(const auto& t : system.triangles)
    area += signed_spherical_area(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])],
                                  x[static_cast<std::size_t>(t[2])]);
  return std::abs(area - 4. * CGAL_PI) < CGAL_PI;
}

// Whether the folds are local (the vertices of non-positive faces and their neighbours at most a hundredth of the
// vertices) and every vertex away from them has an imbalance of at most `level` (or its rounding floor; vertices below
// precision are not tested).
inline bool balanced_away_from_folds(const Sphere_state& state, double level)
{
  const Sphere_system& system = state.system();
  const std::vector<Vector3>& x = state.positions();
  std::vector<char> near_fold(system.number_of_vertices, 0);
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
    if(!state.face_positive(f)) // the state's own orientation test, kept up to date with every move
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t v = static_cast<std::size_t>(system.triangles[f][k]);
        near_fold[v] = 1;
        for(std::size_t j = system.offsets[v]; j < system.offsets[v + 1]; ++j)
          near_fold[static_cast<std::size_t>(system.neighbors[j])] = 1;
      }
  if(100 * static_cast<std::size_t>(std::count(near_fold.begin(), near_fold.end(), 1)) > system.number_of_vertices)
    return false;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
  {
    if(near_fold[i])
      continue;
    const Vertex_imbalance v = vertex_imbalance(system, x, i);
    if(!v.below_precision
       && !(v.rounding_floor <= max_rounding_floor && v.imbalance <= std::max(level, v.rounding_floor)))
      return false; // as summarize_imbalance() tests a vertex, at `level`
  }
  return true;
}

// Iterates until the convergence test holds with every face positive, the caps, or `patience` iterations in a row
// whose step had to be cut below a quarter (Newton's model does not hold: far from the solution, or a multi-scale
// mesh whose thin parts must shrink by orders of magnitude); then `gave_up` is set and the best iterate is restored.
//
// `allow_folds`: the steps may fold triangles on the way, as long as the map keeps degree 1 (has_degree_one); the
// balanced map is bijective, and Newton's full steps reach it from the initial guess on most meshes in 4 to 20
// steps, where steps shortened to keep every triangle positive crawl (thin limbs: the first steps fold some tiny
// triangles wherever they go). It gives up after `patience` iterations without convergence, when no step lowers
// Res, or on a balanced map that is folded (a balanced map of degree 1 need not be bijective).
// `boost_aim`: how the boosts are balanced before each step (Boost_aim: ROOT from a map close to the solution,
// which also drops the boost part of each step).
// What the line search lowers. Res suits the steps where thin parts must shrink by orders of magnitude on the way
// (their imbalances rise for a while: camel, man and four others of the 66 meshes fail when every step must lower
// them), but any shrinking of the map lowers Res too, and on some meshes the steps then slide along the boosts
// towards a collapse (CGAL's handle). The imbalances (imbalance_merit) are scale-free: a collapse does not lower them.
enum class Step_merit
{
  RESIDUAL,
  IMBALANCE
};

// How far the map is from the convergence test, in units of what the test allows: <= 1 passes (the worst imbalance
// over its allowance, or Res over the tolerance).
inline double distance_to_convergence(const Map_measure& measure, const Iteration_options& options)
{
  const double value = convergence_measure(measure, options);
  return options.convergence_test == Convergence_test::PAPER_RESIDUAL ? value / options.tolerance : value;
}

// The forcing of the next step: Eisenstat and Walker's `forcing`, made tight enough for the test to pass after the
// step when Newton's quadratic convergence says it can be the last one. With d_k the distance to the test after step
// k (distance_to_convergence), d_{k+1} ~ K d_k^2 and K ~ d_k / d_{k-1}^2 predict d_{k+1} ~ d_k^3 / d_{k-1}^2; when that
// is <= 1, the linear residual is reduced to Solver_tuning::newton_last_step_forcing / d_k, so that the inexact
// solve does not leave the map just above the test (bunny00 and armadillo Loop x2 ended steps at 1.6 and 1.7 times
// the tolerance with the forcing at 1e-3, each costing one more Newton step). `previous`: d_{k-1}, updated to d_k.
inline double last_step_forcing(double forcing, double& previous, Iteration_driver& driver,
                                const Iteration_options& options)
{
  const double distance = distance_to_convergence(driver.measure(), options);
  const double last = previous;
  previous = distance;
  if(!(distance > 1.) || !(last > 0.) || !std::isfinite(distance) || !std::isfinite(last))
    return forcing;
  const double predicted = distance * (distance / last) * (distance / last);
  if(!(predicted <= 1.))
    return forcing;
  return std::max(options.tuning.newton_min_forcing,
                  std::min(forcing, options.tuning.newton_last_step_forcing / distance));
}

inline Iteration_report mobius_newton(Sphere_state& state, const Iteration_options& options,
                                      const CGAL::Real_timer& clock, Mobius_newton_statistics* statistics = nullptr,
                                      std::size_t patience = 3, bool allow_folds = false,
                                      Step_merit step_merit = Step_merit::RESIDUAL,
                                      Boost_aim boost_aim = Boost_aim::MAXIMUM, bool* other_merit_agrees = nullptr)
{
  const Solver_tuning& tuning = options.tuning;
  Iteration_driver driver(state, options, clock, options.newton_stage, options.max_newton_sweeps);
  // Full steps that lower Res forever without balancing any vertex: a drift towards collapse.
  driver.watch_stagnation(tuning.newton_stagnation_window);
  Mobius_newton_statistics counts;
  const Sphere_system& system = state.system();
  const std::size_t n = system.number_of_vertices;
  std::vector<Vector3>& x = state.positions();
  // MINRES asks this after every iteration, the factorization between its supernodes: a solve can take seconds
  // (bigbrain's first step with cotangent weights: 99 MINRES iterations, 5.5 s; each factorized step after it 1.8 s),
  // longer than the command line waits for a stop signal to be taken (1.2 s).
  bool solve_cancelled = false;
  auto stop_solve = [&]() { return stop_requested(options, clock, solve_cancelled); };
  Tangent_newton_system newton(system);
  // The full-step phase on large meshes solves iteratively; the bijectivity-preserving steps keep the factorization,
  // whose gauge they were tuned with (see Tangent_newton_system::solve), except from a map carried back from a
  // coarser level (Boost_aim::ROOT): there a factorization costs more than the rest of the level (CGAL's diplodocus
  // refined twice, 383,682 vertices: 6 to 9 s a step, three steps none of which was accepted, against 0.8 s by
  // MINRES and 1.6 s for its retry to the smallest forcing). MINRES gives the rotation-consistent step, not the plain
  // gauge's, so where steps are accepted the path differs (CGAL's fandisk_large with cotangent weights now converges
  // on its finest level: the manual's Newton-Krylov item).
  // The preconditioner is the weights' graph Laplacian (tangent_multigrid.h; for cotangent weights, their own signed
  // one since 2026-12-05: the figures here are from before, with absolute values on its diagonal). With negative
  // cotangent weights MINRES needed hundreds of iterations per step from the two-disk guess (c3d_igea: 2,973 in 22
  // steps, 197 s against 48 s factorized), but few from a map carried back from a coarser level (Boost_aim::ROOT),
  // which is close to the solution on most meshes (bunny00: 44 in 5 steps, 0.46 s, where a factorized step alone
  // takes 0.3 s). There, where MINRES does not reach its forcing within its cap, or its step is rejected at the
  // smallest forcing, the rest of the phase factorizes (the exact steps).
  const bool positive_weights = has_positive_weights(system);
  bool iterative = (allow_folds || boost_aim == Boost_aim::ROOT) && n >= tuning.iterative_newton_min_vertices
                   && (positive_weights || boost_aim == Boost_aim::ROOT);
  const bool parallel = options.parallel && n >= tuning.side_by_side_min_vertices; // side_by_side.h
  newton.set_parallel(parallel);
  newton.set_stop(stop_solve);
  Tangent_krylov_system krylov(system, iterative && options.preconditioner_ahead != nullptr
                                           ? options.preconditioner_ahead->get(system)
                                           : nullptr);
  const std::vector<double> boost_weights = symmetric_raw_weights(system);
  double forcing = tuning.newton_max_forcing;
  int last_minres_iterations = 0; // of the last MINRES solve
  std::vector<Vector3> step, trial(n);
  // What the line search lowers (see Step_merit).
  auto merit_of = [&](const Map_measure& measure) {
    return step_merit == Step_merit::IMBALANCE ? measure.imbalance.rms : measure.residual;
  };
  // `other_merit_agrees`: whether the other Step_merit judged every trial of the line searches alike (then these
  // steps are what it would take, one for one: full_newton_steps skips its retry). Every other choice here is made
  // on the same figures under either merit, except the relaxed line search through folds, counted as a disagreement.
  const bool judge_other_merit = other_merit_agrees != nullptr;
  if(judge_other_merit)
    *other_merit_agrees = true;
  double residual = driver.measure().residual;
  double distance_to_test = distance_to_convergence(driver.measure(), options);
  const std::vector<Vector3> start = x;
  driver.keep_best_iterate();
  std::size_t short_steps = 0;
  std::size_t damped_fold_steps = 0, damped_folds = 0; // steps in a row cut short on that many folded faces
  std::vector<double> recent_merits; // of the last iterates, oldest first
  while(driver.may_start())
  {
    if(allow_folds && state.invalid_faces() > 0 && driver.measure().imbalance.balanced())
    {
      counts.folded_balanced_map = x;
      counts.gave_up = true;
      break;
    }
    if(allow_folds && driver.iterations() >= patience)
    {
      counts.gave_up = true;
      break;
    }

    // The boost gradient only needs to be small next to the residual forces that Newton is about to remove.
    bool boosts_settled = true;
    balance_boosts(state, boost_weights, tuning.boost_target_factor * residual * static_cast<double>(n), tuning,
                   boost_aim, parallel, &boosts_settled);
    if(!driver.within_budget())
      break;
    const double previous_residual = residual;
    residual = driver.measure().residual;
    const double merit = merit_of(driver.measure());
    recent_merits.push_back(merit);
    if(recent_merits.size() > std::max<std::size_t>(tuning.free_newton_nonmonotone_window, 1))
      recent_merits.erase(recent_merits.begin());

    bool has_step = false;
    // With negative weights, once Newton converges fast enough that the forcing tightens below its cap, and MINRES
    // already needed many iterations for the last step or the map has folded faces, the steps are exact: with the
    // Laplacian's preconditioner, a poor model of that Jacobian, the tighter forcing costs hundreds of iterations
    // (c3d_igea's finest level: 39 at the cap, then 150 for a forcing of 5e-4, 4.5 s, and up to 200 on
    // vol2surf_lh_pial, where one factorized step takes 1 to 1.5 s and converges faster). With folds the model is
    // poorer still, whatever the last solve took (measured, not explained here): armadillo Loop x2's finest level,
    // cotangent weights, took 17 iterations for the cap from its map carried back, then, among 8,198
    // folded faces, 90 for the same reduction and 200 (19 s) without reaching a forcing of 4e-4, where a factorized
    // step takes 1.7 s (4.5 s with its analysis). Where MINRES is cheap it stays (bunny00: 5 to 15 iterations a step,
    // no folds; factorized, its map took 1.6 s instead of 1.1 s). Far from the balanced map the forcing stays at its
    // cap and MINRES's inexact steps go through the folds (CGAL's armadillo: factorized there, its full steps stalled
    // among 10,000 non-positive faces).
    if(iterative && !positive_weights && forcing < tuning.newton_max_forcing
       && (last_minres_iterations > tuning.newton_factorize_after_minres_iterations || state.invalid_faces() > 0))
      iterative = false;
    if(iterative)
    {
      const bool assembled = krylov.assemble(x);
      has_step = assembled && krylov.solve(step, forcing, tuning.newton_max_minres_iterations, stop_solve);
      if(assembled) // otherwise last_iterations() is the previous solve's
      {
        counts.linear_iterations += static_cast<std::size_t>(krylov.last_iterations());
        last_minres_iterations = krylov.last_iterations();
        if(krylov.stopped())
        {
          (solve_cancelled ? driver.report().cancelled : driver.report().out_of_time) = true;
          break;
        }
      }
    }
    else
    {
      has_step = newton.factorize(x) && newton.solve(step, allow_folds);
      if(newton.stopped())
      {
        (solve_cancelled ? driver.report().cancelled : driver.report().out_of_time) = true;
        break;
      }
    }
    if(!driver.within_budget())
      break;
    double accepted_t = 0.;
    if(has_step)
    {
      Vector3 rotation, boost;
      remove_rotation_and_boost(x, step, rotation, boost);
      // With Boost_aim::ROOT the boosts are outer unknowns, set by balance_boosts before each step; the step keeps
      // to the other directions. Its boost part is Newton's estimate along the nearly singular directions, poor
      // after the balancing (0.1 to 5 on bunny00's finest level, where it cost 15 steps instead of 6). But where
      // the balancing found no root of g near the map (its Newton steps on the boosts wandered by up to the cap each,
      // |g| up and down: the rest of the map's error decides g there), the step's own boost part is the better
      // estimate, as it accounts for how the other directions respond; it is applied, at most
      // Solver_tuning::boost_max_step long (Solver_tuning::boost_step_part_where_unsettled; positive weights only;
      // the manual's Method section, multilevel item).
      const bool boost_part_applies =
          !boosts_settled && positive_weights && tuning.boost_step_part_where_unsettled;
      if(boost_aim == Boost_aim::ROOT && !boost_part_applies)
        boost = Vector3();
      else if(boost_aim == Boost_aim::ROOT && length(boost) > tuning.boost_max_step)
        boost = boost * (tuning.boost_max_step / length(boost));
      double trial_merit = 0.;
      double merit_to_lower = merit;
      auto line_search = [&]() {
        return backtracking_line_search(
            tuning.newton_min_step,
            [&](double t) {
              for(std::size_t i = 0; i < n; ++i)
              {
                const Vector3 y = x[i] + t * step[i];
                trial[i] = apply_boost(y * (1. / length(y)), t * boost);
              }
              // With `parallel`, the merit is computed beside the test of the faces (test_with_merit).
              return test_with_merit(
                  parallel,
                  [&]() {
                    return allow_folds ? has_degree_one(system, trial)
                                       : !options.preserve_bijectivity || state.keeps_positive_faces(trial);
                  },
                  [&]() {
                    trial_merit = step_merit == Step_merit::IMBALANCE ? imbalance_merit(system, trial)
                                                                      : compute_residuals(system, trial).paper;
                  });
            },
            [&](double) {
              const bool lower = trial_merit < merit_to_lower;
              if(judge_other_merit && *other_merit_agrees)
              {
                const bool other_lower = step_merit == Step_merit::IMBALANCE
                                             ? compute_residuals(system, trial).paper < driver.measure().residual
                                             : imbalance_merit(system, trial) < driver.measure().imbalance.rms;
                *other_merit_agrees = other_lower == lower && merit_to_lower == merit;
              }
              return lower;
            });
      };
      accepted_t = line_search();
      // Through folds, where no step lowers the merit, one that lowers the largest of the last few merits instead (see
      // Solver_tuning::free_newton_nonmonotone_window; Sphere_mapper turns it off for weights other than Tutte's). Only
      // with positive weights, whose balanced map is bijective, so that folds on the way are transient; with negative
      // cotangent weights the steps often head for a folded balanced map, and the relaxed steps only lengthened those
      // paths (CGAL's fandisk_large: 67 steps instead of 19).
      const double recent_merit = *std::max_element(recent_merits.begin(), recent_merits.end());
      if(accepted_t == 0. && allow_folds && positive_weights && judge_other_merit
         && tuning.free_newton_nonmonotone_window > 1)
        *other_merit_agrees = false; // the other merit's recent ones could relax its search differently
      if(accepted_t == 0. && allow_folds && positive_weights && recent_merit > merit)
      {
        merit_to_lower = recent_merit;
        accepted_t = line_search();
      }
      if(accepted_t > 0.)
      {
        state.assign(trial, !allow_folds && options.preserve_bijectivity);
        residual = driver.measure().residual;
        ++counts.newton_steps;
      }
    }
    // The steps that keep every triangle positive do not give up on a failed iterative solve (its assembly or MINRES
    // broke down): the factorized step takes over for the rest of the phase, as for negative weights below.
    if(iterative && !allow_folds && !has_step)
    {
      iterative = false;
      driver.count_retry(); // the same point again, with the factorized step
      continue;
    }
    if(iterative && !positive_weights
       && (krylov.last_iterations() >= tuning.newton_max_minres_iterations
           || (accepted_t == 0. && forcing <= tuning.newton_min_forcing)))
    {
      iterative = false;
      if(accepted_t == 0.)
      {
        driver.count_retry(); // the same point again, with the factorized step
        continue;
      }
    }
    if(iterative)
    {
      if(accepted_t == 0. && forcing > tuning.newton_min_forcing)
      {
        forcing = tuning.newton_min_forcing; // the same point again, with a nearly exact step
        driver.count_retry();
        continue;
      }
      const double ratio = previous_residual > 0. ? residual / previous_residual : 1.;
      forcing = std::min(tuning.newton_max_forcing, std::max(tuning.newton_min_forcing, 0.9 * ratio * ratio));
      forcing = last_step_forcing(forcing, distance_to_test, driver, options);
    }
    if(accepted_t == 0. && allow_folds)
    {
      counts.gave_up = true;
      break;
    }
    if(accepted_t == 0.)
    {
      // No acceptable step: the paper's local Newton sweeps (which keep every positive triangle positive) move
      // the iterate, so that the next Newton step starts elsewhere.
      for(int sweep = 0; sweep < tuning.local_sweeps_without_step; ++sweep)
        for(std::size_t i = 0; i < n; ++i)
          if(!local_newton_step(state, i, options.preserve_bijectivity))
            ++driver.report().rejected_moves;
      state.refresh_sums();
      residual = driver.measure().residual;
    }
    if(!driver.end_iteration())
    {
      counts.gave_up = driver.report().stagnated;
      break;
    }
    short_steps = accepted_t >= tuning.short_step ? 0 : short_steps + 1;
    // With weights of either sign, where the line search cuts the steps short again and again on the same number of
    // folded faces while the rest of the map is within the square root of the tolerance (at most 1e-3) of balanced
    // (where Newton's steps, converging quadratically, would be one or two from the test), the steps approach a
    // balanced map that is folded, linearly: the map of least distortion follows (least_distortion_follows) as it would
    // from that folded balanced map (the test at the top of the loop). Bigbrain, cotangent weights: on its finest level
    // (163,842 vertices) two faces stayed folded while every full step doubled Res and half steps lowered it by a
    // third, 10 factorized steps of 1.2 s each (the whole map 34 s) before the imbalances away from those faces reached
    // the tolerance; stopped after 3 (26 s), the map of least distortion from there is the same (1.277 degrees of angle
    // error). Without the tests on the rest of the map and on the folds' extent, three small meshes of CGAL's
    // (dragknob, quint_tris, tripod) stopped among folds of a large part of the mesh (dragknob: 135 of 318 faces), from
    // which the bijectivity-preserving steps still reach their bijective balanced map. With positive weights folds on
    // the way are transient (the balanced map is bijective): no stop.
    const bool damped_on_folds = allow_folds && !positive_weights && accepted_t > 0. && accepted_t < 1.
                                 && state.invalid_faces() > 0;
    damped_fold_steps =
        !damped_on_folds ? 0 : (state.invalid_faces() == damped_folds ? damped_fold_steps + 1 : 1);
    damped_folds = state.invalid_faces();
    if(damped_fold_steps >= tuning.free_newton_damped_fold_steps && options.least_distortion_follows
       && balanced_away_from_folds(state, std::min(std::sqrt(options.tolerance), 1e-3)))
    {
      counts.folded_balanced_map = x;
      counts.gave_up = true;
      break;
    }
    if(!allow_folds && short_steps >= patience)
    {
      counts.gave_up = true;
      break;
    }
  }
  Iteration_report& report = driver.report();
  // A converged map that the certificate rejects (a degenerate collapse with a degree other than 1): none of these
  // iterates is trusted.
  if(!counts.gave_up && driver.converged() && !certify(system.triangles, x).bijective)
  {
    counts.gave_up = true;
    driver.restore(start);
  }
  else if(counts.gave_up || report.cancelled || report.out_of_time)
  {
    driver.restore_best();
  }
  report.stagnated = counts.gave_up;
  report.linear_iterations = counts.linear_iterations;
  if(statistics != nullptr)
    *statistics = counts;
  return driver.finish();
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_NEWTON_H
