// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Stages 2 and 3 of the paper on the flat arrays of a Sphere_system:
//  - projected Gauss-Seidel (Section 3.2), stopped as soon as the residual grows;
//  - local Newton (Section 3.3): each vertex in turn, in a frame where it sits on the x-axis, takes a Newton step
//    on (theta, phi) that lowers the squared residuals of its one-ring, with the paper's line search.
// Both can preserve bijectivity as the paper's conclusion proposes: a move that would turn one of the vertex's
// positively oriented spherical triangles (exact predicate) non-positive is pulled back towards the previous
// position, and dropped if that does not help.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H

#include <CGAL/Spherical_parameterization/internal/Sphere_state.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// Paper, Section 3.2, with lambda = 1: x_i <- s_i / |s_i| in turn, while Res decreases. The last iterate whose
// residual did not grow is kept.
// `test_each_sweep`: the convergence test after every sweep (the paper's stage 2); without it, only after the last
// one (the multilevel smoothing: a few sweeps from a map carried back, which does not pass the test).
inline Iteration_report projected_gauss_seidel(Sphere_state& state, const Iteration_options& options,
                                               const CGAL::Real_timer& clock, bool test_each_sweep = true)
{
  Iteration_driver driver(state, options, clock, "gauss-seidel", options.max_gauss_seidel_sweeps);
  const Sphere_system& system = state.system();
  std::vector<Vector3>& x = state.positions();
  double residual = state.refresh_sums();
  std::vector<Vector3> previous;
  // The paper sweeps once before testing: the test comes after each sweep.
  while(driver.may_start(false))
  {
    previous = x;
    for(std::size_t i = 0; i < system.number_of_vertices; ++i)
    {
      const Vector3 s = state.sum(i);
      const double norm = length(s);
      if(!(norm > 0.))
        continue;
      if(!state.move_preserving_orientation(i, s * (1. / norm), options.preserve_bijectivity))
        ++driver.report().rejected_moves;
    }
    const double next = state.refresh_sums();
    const bool go_on = driver.end_iteration(next);
    if(!(next < residual))
    {
      // Res grew: return to the previous iterate (faces flags follow the positions).
      for(std::size_t i = 0; i < system.number_of_vertices; ++i)
        if(!(x[i] == previous[i]))
          state.move(i, previous[i]);
      state.refresh_sums();
      break;
    }
    residual = next;
    if(test_each_sweep && driver.converged())
      break;
    if(!go_on)
      break;
  }
  Iteration_report report = driver.report();
  report.converged = driver.converged();
  report.residual = residual;
  return report;
}

// The squared residuals of the one-ring of i if x_i moved to y: |y x s_i|^2 + sum_k |x_k x (s_k + w_ki (y - x_i))|^2.
inline double one_ring_energy(const Sphere_state& state, std::vector<Vector3>& x, std::size_t i, const Vector3& y)
{
  const Sphere_system& system = state.system();
  const Vector3 delta = y - x[i];
  double energy = squared_length(cross(y, state.sum(i)));
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
  {
    const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
    energy += squared_length(cross(x[j], state.sum(j) + system.weights[system.reverse[k]] * delta));
  }
  return energy;
}

// Paper, Section 3.3. Rotating the one-ring so that x_i is the x-axis amounts to the frame (x_i, t1, t2) with
// x(theta, phi) = cos(phi) cos(theta) x_i + cos(phi) sin(theta) t1 + sin(phi) t2, so theta = phi = 0 at x_i.
// The 2x2 system is the Newton (Gauss-Newton) system of the one-ring energy in (theta, phi); the line search
// starts at lambda = 1 and halves while that lowers the energy further, down to lambda > 0.05.
inline bool local_newton_step(Sphere_state& state, std::size_t i, bool preserve)
{
  const Sphere_system& system = state.system();
  std::vector<Vector3>& x = state.positions();
  const Vector3 xi = x[i];
  const Vector3 helper =
      std::abs(xi.x) < 0.6 ? Vector3(1, 0, 0) : (std::abs(xi.y) < 0.6 ? Vector3(0, 1, 0) : Vector3(0, 0, 1));
  Vector3 t1 = cross(xi, helper);
  t1 *= 1. / length(t1);
  const Vector3 t2 = cross(xi, t1);

  // Residual vectors r = x_k x s_k and their derivatives along t1 (theta) and t2 (phi).
  double h11 = 0., h12 = 0., h22 = 0., g1 = 0., g2 = 0.;
  auto accumulate = [&](const Vector3& r, const Vector3& d1, const Vector3& d2) {
    h11 += dot(d1, d1);
    h12 += dot(d1, d2);
    h22 += dot(d2, d2);
    g1 += dot(d1, r);
    g2 += dot(d2, r);
  };
  const Vector3& si = state.sum(i);
  accumulate(cross(xi, si), cross(t1, si), cross(t2, si));
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
  {
    const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
    const double w = system.weights[system.reverse[k]];
    accumulate(cross(x[j], state.sum(j)), w * cross(x[j], t1), w * cross(x[j], t2));
  }
  const double det = h11 * h22 - h12 * h12;
  if(!(det > 1e-300))
    return false;
  const double theta = -(h22 * g1 - h12 * g2) / det;
  const double phi = -(h11 * g2 - h12 * g1) / det;

  auto position = [&](double lambda) {
    const double a = lambda * theta, b = lambda * phi;
    return std::cos(b) * std::cos(a) * xi + std::cos(b) * std::sin(a) * t1 + std::sin(b) * t2;
  };
  const double current = one_ring_energy(state, x, i, xi);
  double best_lambda = 1.;
  double best = one_ring_energy(state, x, i, position(1.));
  for(double lambda = 0.5; lambda > 0.05; lambda *= 0.5)
  {
    const double e = one_ring_energy(state, x, i, position(lambda));
    if(!(e < best))
      break;
    best = e;
    best_lambda = lambda;
  }
  if(!(best < current))
    return false;
  Vector3 y = position(best_lambda);
  y *= 1. / length(y);
  return state.move_preserving_orientation(i, y, preserve);
}

// The paper's stage 3: local Newton sweeps until the convergence test holds, no vertex moves, or 1000 sweeps gained
// less than 1% in all; when it does not converge, the best iterate is returned.
inline Iteration_report local_newton(Sphere_state& state, const Iteration_options& options,
                                     const CGAL::Real_timer& clock)
{
  Iteration_driver driver(state, options, clock, "local newton", options.max_newton_sweeps);
  driver.watch_stagnation(options.tuning.local_stagnation_window);
  const Sphere_system& system = state.system();
  driver.measure(state.refresh_sums());
  driver.keep_best_iterate();
  while(driver.may_start())
  {
    std::size_t moved = 0;
    for(std::size_t i = 0; i < system.number_of_vertices; ++i)
    {
      if(local_newton_step(state, i, options.preserve_bijectivity))
        ++moved;
      else
        ++driver.report().rejected_moves;
    }
    if(!driver.end_iteration(state.refresh_sums()))
      break;
    if(moved == 0)
    {
      driver.report().stagnated = true;
      break;
    }
  }
  if(!driver.converged())
  {
    driver.restore_best();
    state.refresh_sums();
  }
  Iteration_report report = driver.finish();
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H
