// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The multilevel start of the least-distortion minimization (named parameter least_distortion): the mesh is coarsened
// by the collapses of the multilevel start (mesh_coarsening.h) down to a few thousand vertices; the coarsest level's
// Tutte map is minimized there, carried back one level (each vertex inserted at the centre of its ring's kernel, then
// smoothed by nonlinear Gauss-Seidel sweeps), minimized again, and so on up to the mesh itself, whose minimization the
// caller runs. The coarse levels settle the global shape of the map (how far each limb must shrink, the boosts) for a
// fraction of the cost, which the Newton steps on the whole mesh settle slowly: CGAL's man (17,495 vertices) became
// stationary after 104 to 174 steps on the mesh itself (12 to 28 s) from this start against 297 (35 s) from Tutte's
// map, and at a lower distortion (angle error 4.7 degrees against 5.2). The manual's Method section gives the figures.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MULTILEVEL_LEAST_DISTORTION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MULTILEVEL_LEAST_DISTORTION_H

#include <CGAL/Spherical_parameterization/internal/mesh_coarsening.h>
#include <CGAL/Spherical_parameterization/internal/stage3/least_distortion.h>

#include <CGAL/Real_timer.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Least_distortion_level
{
  std::size_t vertices = 0;
  std::size_t newton_steps = 0;
  bool stationary = false;
  double seconds = 0.;
  int smoothing_sweeps = 0; // of its map carried back to the next finer level (smooth_conformal_distortion)
  double smoothing_seconds = 0.;
  double last_step_seconds = 0.; // its last step's duration (Least_distortion_report::last_step_seconds)
};

// What a step on a level of `vertices` is expected to take from the last step of the coarser `level`: a sparse
// factorization of a surface's Hessian grows about as the vertices to the power 1.5 (nested dissection's operation
// count on planar graphs, George 1973), used by the time budget (minimize_conformal_distortion's first_pass_seconds).
inline double scaled_step_seconds(const Least_distortion_level& level, std::size_t vertices)
{
  if(level.vertices == 0)
    return 0.;
  return level.last_step_seconds
         * std::pow(static_cast<double>(vertices) / static_cast<double>(level.vertices), 1.5);
}

struct Multilevel_least_distortion_report
{
  bool cancelled = false;
  bool out_of_time = false;
  std::vector<Least_distortion_level> levels; // the coarser levels, coarsest first
};

// Whether a mesh of `vertices` has a coarser level (multilevel_least_distortion_start() coarsens from this size on).
inline bool has_least_distortion_levels(std::size_t vertices, const Solver_tuning& tuning)
{
  return vertices
         >= static_cast<std::size_t>(tuning.least_distortion_coarsest_vertices / tuning.multilevel_coarsening_ratio);
}

// The start for the mesh of `points` and `triangles`: true with `x` set (every face positive), false when the mesh is
// too small for a coarser level, the coarsest level has no map (`coarsest_map(const Mesh_arrays&,
// std::vector<Vector3>&)` returns false: the caller's Tutte map of that level), or the budget or a cancel stopped a
// level (the report says which).
template <typename Coarsest_map>
bool multilevel_least_distortion_start(const std::vector<Vector3>& points,
                                       const std::vector<std::array<int, 3>>& triangles,
                                       const Coarsest_map& coarsest_map, const Iteration_options& options,
                                       const CGAL::Real_timer& clock, std::vector<Vector3>& x,
                                       Multilevel_least_distortion_report& multilevel)
{
  const Solver_tuning& tuning = options.tuning;
  multilevel = Multilevel_least_distortion_report();
  std::vector<Coarsening> hierarchy; // hierarchy[L] coarsens level L (level 0: the mesh) into level L + 1
  auto level_points = [&](std::size_t level) -> const std::vector<Vector3>& {
    return level == 0 ? points : hierarchy[level - 1].coarse.points;
  };
  auto level_triangles = [&](std::size_t level) -> const std::vector<std::array<int, 3>>& {
    return level == 0 ? triangles : hierarchy[level - 1].coarse.triangles;
  };
  while(has_least_distortion_levels(level_points(hierarchy.size()).size(), tuning))
  {
    const std::size_t n = level_points(hierarchy.size()).size();
    Coarsening coarsening =
        coarsen_mesh(level_points(hierarchy.size()), level_triangles(hierarchy.size()),
                     static_cast<std::size_t>(tuning.multilevel_coarsening_ratio * static_cast<double>(n)));
    if(10 * coarsening.coarse.points.size() > 9 * n)
      break; // the collapses are blocked (their link condition or degree cap): no coarser level worth solving
    hierarchy.push_back(std::move(coarsening));
  }
  if(hierarchy.empty())
    return false;
  std::vector<Vector3> y;
  if(!coarsest_map(hierarchy.back().coarse, y) || y.size() != hierarchy.back().coarse.points.size())
  {
    multilevel.out_of_time = past_time_budget(options, clock); // its map ended unconverged for lack of time
    return false;
  }
  Iteration_options level_options = options;
  level_options.max_newton_sweeps = std::min(options.max_newton_sweeps, tuning.least_distortion_coarse_max_steps);
  level_options.tolerance = std::max(options.tolerance, tuning.least_distortion_coarse_tolerance);
  for(std::size_t level = hierarchy.size(); level > 0; --level)
  {
    const double start_time = clock.time();
    const double first_step_seconds =
        multilevel.levels.empty() ? 0. : scaled_step_seconds(multilevel.levels.back(), y.size());
    const Least_distortion_report report = minimize_conformal_distortion(level_triangles(level), level_points(level), y,
                                                                         level_options, clock, first_step_seconds);
    if(!report.started)
      return false;
    if(report.cancelled || report.out_of_time)
    {
      multilevel.cancelled = report.cancelled;
      multilevel.out_of_time = report.out_of_time;
      return false;
    }
    Least_distortion_level figures;
    figures.vertices = y.size();
    figures.newton_steps = report.newton_steps;
    figures.stationary = report.stationary;
    figures.seconds = clock.time() - start_time;
    figures.last_step_seconds = report.last_step_seconds;
    multilevel.levels.push_back(figures);
    std::vector<Vector3> finer;
    // A vertex left folded (no positive place in its ring, which rounding alone should cause) makes F infinite: no
    // start (the caller falls back to Tutte's map). Smoothing cannot unfold it. Each new face must also be positive
    // in the orientation F is defined by (its sign can differ from the exact predicate's on faces squeezed to the
    // limits of double precision), as the minimization tests its start (after normalizing it).
    if(prolong(hierarchy[level - 1], y, finer, Insertion::KERNEL_CENTRE, positive_in_distortion_orientation) != 0)
      return false;
    const double smoothing_start = clock.time();
    multilevel.levels.back().smoothing_sweeps =
        smooth_conformal_distortion(level_triangles(level - 1), level_points(level - 1), finer,
                                    tuning.least_distortion_max_smoothing_sweeps,
                                    tuning.least_distortion_smoothing_stall, options, clock);
    multilevel.levels.back().smoothing_seconds = clock.time() - smoothing_start;
    y.swap(finer);
  }
  // The same test as the minimization's (every face positive in its orientation), which the exact predicate of
  // prolong() need not imply on faces at the limits of double precision.
  if(!std::isfinite(conformal_distortion(triangles, points, y)))
    return false;
  x.swap(y);
  return true;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MULTILEVEL_LEAST_DISTORTION_H
