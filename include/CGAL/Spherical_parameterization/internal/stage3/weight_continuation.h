// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stage 3, beyond the paper: continuation in the weights, for symmetric weights that Newton cannot reach directly.
//
// Tutte's weights are the easy case: from the initial guess the Moebius-aware Newton reaches their balanced
// solution on most meshes. The blended weights w(s) = (1 - s) + s w_ij (raw weights) lead from them to the target
// ones; their balanced solutions move continuously with s, so each one is a good start for Newton at a slightly
// larger s. The step in s grows while Newton converges and is halved when it does not. If the path of solutions
// ends before s = 1 (cotangent weights: a triangle degenerates and the Jacobian becomes singular), it fails, and
// that is worth knowing: the target weights have no bijective balanced solution on this path.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H

#include <CGAL/Spherical_parameterization/internal/stage3/mobius_newton.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Continuation_report
{
  bool reached = false;       // the balanced solution of the target weights was reached
  double last_parameter = 0.; // the largest s whose balanced solution was found (bijective)
  std::size_t newton_steps = 0;
  bool out_of_time = false;
  bool cancelled = false;
};

// The raw weights (1 - s) + s w_ij of the target system, normalized as every Sphere_system is.
inline void blend_with_tutte(const Sphere_system& target, double s, Sphere_system& blend)
{
  for(std::size_t i = 0; i < target.number_of_vertices; ++i)
  {
    double sum = 0.;
    for(std::size_t k = target.offsets[i]; k < target.offsets[i + 1]; ++k)
    {
      blend.weights[k] = (1. - s) + s * target.weights[k] * target.row_sums[i];
      sum += blend.weights[k];
    }
    for(std::size_t k = target.offsets[i]; k < target.offsets[i + 1]; ++k)
      blend.weights[k] /= sum;
    blend.row_sums[i] = sum;
  }
  blend.symmetric = true;
}

// Each solution along the path is computed to the caller's test (to `path_tolerance` when that is the paper's Res). On failure x holds the solution at report.last_parameter (or, if even
// Tutte's weights failed, whatever Newton's best iterate was).
inline Continuation_report weight_continuation(const Sphere_system& target, std::vector<Vector3>& x,
                                               const Iteration_options& options, const CGAL::Real_timer& clock,
                                               const std::vector<Vector3>* initial_guess = nullptr,
                                               double path_tolerance = 1e-13, std::size_t patience = 20)
{
  // Tutte's solution is found most reliably from stage 1's initial guess (not from an iterate balanced for
  // other weights).
  if(initial_guess != nullptr && initial_guess->size() == x.size())
    x = *initial_guess;
  Continuation_report report;
  Sphere_system blend = target;
  Iteration_options path = options;
  // The imbalance is scale-free; the paper's Res needs to be far below the tolerance for a good start.
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL)
    path.tolerance = std::min(options.tolerance, path_tolerance);
  std::vector<Vector3> saved;
  auto solve_at = [&](double s) {
    blend_with_tutte(target, s, blend);
    Sphere_state state(blend, x);
    // Gauss-Seidel first, as in stage 2, then Newton.
    if(s == 0.)
      projected_gauss_seidel(state, path, clock);
    Mobius_newton_statistics statistics;
    const Iteration_report newton = mobius_newton(state, path, clock, &statistics, patience);
    report.newton_steps += statistics.newton_steps;
    report.out_of_time = report.out_of_time || newton.out_of_time;
    report.cancelled = report.cancelled || newton.cancelled;
    return newton.converged && !statistics.gave_up;
  };
  if(!solve_at(0.))
    return report;
  double s = 0., step = 0.25;
  while(s < 1. && !report.out_of_time && !report.cancelled)
  {
    const double next = std::min(1., s + step);
    saved = x;
    if(solve_at(next))
    {
      s = next;
      step = std::min(1., 1.5 * step);
    }
    else
    {
      x = saved;
      step *= 0.5;
      if(step < 1e-3)
        break;
    }
  }
  report.last_parameter = s;
  report.reached = s == 1.;
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H
