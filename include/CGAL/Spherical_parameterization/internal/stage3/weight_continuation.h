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
// larger s. The step in s grows while Newton converges and is halved when it does not. The path of solutions may
// end before s = 1 (cotangent weights: a triangle degenerates, or the path turns back, and the Jacobian becomes
// singular): the target weights have no bijective balanced solution on this path.
//
// With `hold`, the path goes on where it would end: the vertices where it ends keep the weights of the last
// parameter reached (a vertex held at h_i has the weights (1 - s_ij) + s_ij w_ij on its edges, s_ij = min(s, h_i,
// h_j), symmetric), and the others go on to s = 1. Which vertices: where the step in s has shrunk below
// Solver_tuning::hold_min_step, those moving fastest along the path in their own scale (near a turning point the
// path's velocity is the Jacobian's null vector, and it is large where the map is about to change most), with one
// ring; and after each short step, the vertices of the faces whose shape (det / sum of squared edges), extrapolated
// linearly in s, would degenerate within the next step. The map reached is balanced, and bijective like every map of
// the path, for weights that are the target's except at the held vertices: Result::held_weight_vertices says how
// many, Result::held_weight_parameter the smallest h_i (the manual's Method section has the measurements).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H

#include <CGAL/Spherical_parameterization/internal/stage3/mobius.h>
#include <CGAL/Spherical_parameterization/internal/stage3/mobius_newton.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Continuation_report
{
  bool reached = false;       // s = 1 was reached (with held vertices if `holds` is not empty)
  double last_parameter = 0.; // the largest s whose balanced solution was found (bijective)
  // With holding: per vertex the parameter its weights are held at (1: not held); empty when none was held.
  std::vector<double> holds;
  std::size_t newton_steps = 0;
  bool out_of_time = false;
  bool cancelled = false;
};

// The raw weights (1 - s) + s w_ij of the target system, normalized as every Sphere_system is; with `holds`, the
// parameter of edge ij is min(s, holds[i], holds[j]) (symmetric).
inline void blend_with_tutte(const Sphere_system& target, double s, Sphere_system& blend,
                             const std::vector<double>* holds = nullptr)
{
  // (1 - s) times Tutte's Laplacian plus s times the target's: semi-definite where the target's is, unless holds
  // blend some edges at other parameters.
  bool one_parameter = true;
  for(std::size_t i = 0; i < target.number_of_vertices; ++i)
  {
    double sum = 0.;
    for(std::size_t k = target.offsets[i]; k < target.offsets[i + 1]; ++k)
    {
      double edge_s = s;
      if(holds != nullptr && !holds->empty())
        edge_s = std::min(edge_s, std::min((*holds)[i], (*holds)[static_cast<std::size_t>(target.neighbors[k])]));
      one_parameter = one_parameter && edge_s == s;
      blend.weights[k] = (1. - edge_s) + edge_s * target.weights[k] * target.row_sums[i];
      sum += blend.weights[k];
    }
    for(std::size_t k = target.offsets[i]; k < target.offsets[i + 1]; ++k)
      blend.weights[k] /= sum;
    blend.row_sums[i] = sum;
  }
  blend.symmetric = true;
  blend.signed_laplacian_semidefinite = target.signed_laplacian_semidefinite && one_parameter;
}

// The shape of a face on the sphere, scale-free: det(a, b, c) over the sum of its squared chords (0 when degenerate).
inline double face_shape(const std::vector<Vector3>& x, const std::array<int, 3>& t)
{
  const Vector3& a = x[static_cast<std::size_t>(t[0])];
  const Vector3& b = x[static_cast<std::size_t>(t[1])];
  const Vector3& c = x[static_cast<std::size_t>(t[2])];
  const double chords = squared_length(a - b) + squared_length(b - c) + squared_length(c - a);
  return chords > 0. ? dot(a, cross(b - a, c - a)) / chords : 0.;
}

// Holds the vertices flagged in `mark` and one ring around them at parameter s; returns how many were not held before.
inline std::size_t hold_vertices(const Sphere_system& system, std::vector<char> mark, double s,
                                 std::vector<double>& holds)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<char> ring = mark;
  for(std::size_t i = 0; i < n; ++i)
    if(mark[i])
      for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
        ring[static_cast<std::size_t>(system.neighbors[k])] = 1;
  std::size_t added = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(ring[i] && holds[i] > s)
    {
      holds[i] = s;
      ++added;
    }
  return added;
}

// The vertices of the faces whose shape, extrapolated linearly from `previous` (at s0) to `x` (at s), degenerates
// before s + horizon.
inline std::vector<char> faces_about_to_degenerate(const Sphere_system& system, const std::vector<Vector3>& previous,
                                                   double s0, const std::vector<Vector3>& x, double s, double horizon)
{
  std::vector<char> mark(system.number_of_vertices, 0);
  for(const auto& t : system.triangles)
  {
    const double shape = face_shape(x, t), before = face_shape(previous, t);
    if(!(shape > 0.) || (shape < before && shape / (before - shape) * (s - s0) < horizon))
      for(int v : t)
        mark[static_cast<std::size_t>(v)] = 1;
  }
  return mark;
}

// The vertices not held yet that move fastest from `previous` to `x` in their own scale (the tangential
// displacement without its rotation and boost parts, over the mean chord): at least `fraction` of the fastest.
inline std::vector<char> fastest_vertices(const Sphere_system& system, const std::vector<Vector3>& previous,
                                          const std::vector<Vector3>& x, const std::vector<double>& holds,
                                          double fraction)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<Vector3> d(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    const Vector3 e = x[i] - previous[i];
    d[i] = e - dot(e, x[i]) * x[i];
  }
  Vector3 rotation, boost;
  remove_rotation_and_boost(x, d, rotation, boost);
  std::vector<double> speed(n, 0.);
  double fastest = 0.;
  for(std::size_t i = 0; i < n; ++i)
  {
    if(holds[i] < 1.)
      continue;
    double chords = 0.;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      chords += length(x[static_cast<std::size_t>(system.neighbors[k])] - x[i]);
    chords /= static_cast<double>(system.degree(i));
    speed[i] = chords > 0. ? length(d[i]) / chords : 0.;
    fastest = std::max(fastest, speed[i]);
  }
  std::vector<char> mark(n, 0);
  for(std::size_t i = 0; i < n; ++i)
    mark[i] = fastest > 0. && speed[i] >= fraction * fastest;
  return mark;
}

// Each solution along the path is computed to the caller's test (to `path_tolerance` when that is the paper's Res). On failure x holds the solution at report.last_parameter (or, if even
// Tutte's weights failed, whatever Newton's best iterate was).
// `initial_guess`: where Tutte's solution is sought (a balanced Tutte map itself is the best start).
inline Continuation_report weight_continuation(const Sphere_system& target, std::vector<Vector3>& x,
                                               const Iteration_options& options, const CGAL::Real_timer& clock,
                                               const std::vector<Vector3>* initial_guess = nullptr,
                                               bool hold = false, double path_tolerance = 1e-13)
{
  const Solver_tuning& tuning = options.tuning;
  const std::size_t patience = hold ? tuning.hold_patience : 20; // at s > 0
  const std::size_t n = target.number_of_vertices;
  std::vector<double> holds;
  if(hold)
    holds.assign(n, 1.);
  std::size_t hold_rounds = 0;
  // Tutte's solution is found most reliably from stage 1's initial guess (not from an iterate balanced for
  // other weights).
  if(initial_guess != nullptr && initial_guess->size() == x.size())
    x = *initial_guess;
  Continuation_report report;
  Sphere_system blend = target;
  Iteration_options path = options;
  path.newton_stage = "weight continuation"; // its progress reports say so: their counts start at each blend
  // The imbalance is scale-free; the paper's Res needs to be far below the tolerance for a good start.
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL)
    path.tolerance = std::min(options.tolerance, path_tolerance);
  std::vector<Vector3> saved, previous;
  double previous_s = 0.;
  auto solve_at = [&](double s) {
    blend_with_tutte(target, s, blend, &holds);
    Sphere_state state(blend, x);
    // Gauss-Seidel first, as in stage 2, then Newton.
    if(s == 0.)
      projected_gauss_seidel(state, path, clock);
    Mobius_newton_statistics statistics;
    if(hold && s > 0.)
    {
      const std::vector<Vector3> from = x;
      Mobius_newton_statistics free_statistics;
      const Iteration_report free_steps =
          mobius_newton(state, path, clock, &free_statistics, tuning.hold_free_steps, true);
      report.newton_steps += free_statistics.newton_steps;
      if(free_steps.converged && !free_statistics.gave_up && state.invalid_faces() == 0)
        return true;
      state.assign(from);
    }
    const Iteration_report newton = mobius_newton(state, path, clock, &statistics, s == 0. ? 20 : patience);
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
      previous.swap(saved);
      previous_s = s;
      s = next;
      step = std::min(1., 1.5 * step);
      // Short steps: the path is near its end, and the linear extrapolation of the faces' shapes is worth trusting.
      if(hold && s < 1. && s - previous_s <= tuning.hold_predict_max_step && hold_rounds < tuning.max_holds
         && hold_vertices(target,
                          faces_about_to_degenerate(target, previous, previous_s, x, s,
                                                    tuning.hold_predict_factor * std::min(step, 1. - s)),
                          s, holds) > 0)
        ++hold_rounds;
    }
    else
    {
      x = saved;
      step *= 0.5;
      if(step < (hold ? tuning.hold_min_step : 1e-3))
      {
        if(!hold || previous.empty() || hold_rounds >= tuning.max_holds
           || hold_vertices(target, fastest_vertices(target, previous, x, holds, tuning.hold_velocity_fraction), s,
                            holds) == 0)
          break;
        ++hold_rounds;
        step = 0.1;
      }
    }
  }
  report.last_parameter = s;
  report.reached = s == 1.;
  if(hold && std::find_if(holds.begin(), holds.end(), [](double h) { return h < 1.; }) != holds.end())
    report.holds = std::move(holds);
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_WEIGHT_CONTINUATION_H
