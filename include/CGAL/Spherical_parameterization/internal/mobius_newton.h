// Stage 3, beyond the paper, for symmetric weights: Newton's method on all vertices at once with the Moebius
// boosts handled exactly (see mobius.h).
//
// Each iteration (1) balances the boosts (maximizes the spring energy over them), (2) solves Newton's system in
// tangent coordinates (tangent_newton_system.h), (3) splits the step into its rotation part (dropped: rotations
// change nothing), its boost part (applied as an exact boost, whose linearization is poor) and the rest (added
// and projected back onto the sphere), and (4) shortens the step until every positive triangle stays positive
// (exact predicate) and the merit decreases (Step_merit); when no such step exists, five of the paper's local Newton
// sweeps move the iterate instead. When the steps keep being cut short, it gives up and restores its best
// iterate, so that another strategy can continue (global_newton.h).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_NEWTON_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_NEWTON_H

#include <CGAL/Spherical_parameterization/internal/mobius.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/tangent_krylov_system.h>
#include <CGAL/Spherical_parameterization/internal/tangent_newton_system.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Mobius_newton_statistics {
  std::size_t newton_steps = 0;    // accepted Newton steps
  std::size_t full_steps = 0;      // of which taken whole (t = 1)
  std::size_t boosts = 0;          // balancing boosts applied
  bool gave_up = false;            // Newton's steps were too short: the caller should continue otherwise
  std::size_t linear_iterations = 0;  // MINRES iterations (iterative linear solves only)
};

// Newton's linear systems are solved by MINRES with the multigrid preconditioner (tangent_krylov_system.h) from this
// many vertices on, by a sparse factorization below. Measured per Newton step (2 threads, this package's AMG): a
// factorization costs 0.02 s at 3k vertices, 0.3 s at 38k (bunny00), 7 s at 134k (igea) and grows like n^1.5; MINRES
// costs 0.05 to 0.1 s at 38k and grows like n. Below a few thousand vertices both take milliseconds, and the exact
// step is the more robust on small meshes with thin parts (CGAL's cow and hand: 1e-2-inexact steps from the initial
// guess end on a folded balanced map where exact ones converge).
constexpr std::size_t iterative_newton_min_vertices = 8000;

// Inexact Newton (Eisenstat and Walker's second choice of the forcing term): the linear residual is reduced by
// eta_k = 0.9 (Res_k / Res_{k-1})^2, at most `newton_max_forcing` (looser steps, 0.1 or 0.3, wander on igea and man:
// measured) and at least `newton_min_forcing`. A step the line search rejects is solved again with the smallest
// forcing before the phase gives up.
constexpr double newton_max_forcing = 1e-2;
constexpr double newton_min_forcing = 1e-8;
// A bound on one solve's MINRES iterations (uniform weights take 2 to 20 at the forcing, about 60 at the smallest
// one): the iterate of MINRES is still a descent step when it stops early, and the line search judges it.
constexpr int newton_max_minres_iterations = 200;

// The signed spherical areas add up to 4 pi times the degree of the map. Folds keep the degree; a collapse of the
// map onto a small cap, the trivial solution the boosts lead to, has to pass through a triangle larger than a
// hemisphere, which changes the sum by a multiple of 4 pi.
inline bool has_degree_one(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double area = 0.;
  for(const auto& t : system.triangles)
    area += signed_spherical_area(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])]);
  return std::abs(area - 4. * CGAL_PI) < CGAL_PI;
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
enum class Step_merit { RESIDUAL, IMBALANCE };

inline Iteration_report mobius_newton(Sphere_state& state, const Iteration_options& options, const Stopwatch& clock,
                                      Mobius_newton_statistics* statistics = nullptr, std::size_t patience = 3,
                                      bool allow_folds = false, Step_merit step_merit = Step_merit::RESIDUAL,
                                      Boost_aim boost_aim = Boost_aim::MAXIMUM)
{
  Iteration_report report;
  Mobius_newton_statistics counts;
  const Sphere_system& system = state.system();
  const std::size_t n = system.number_of_vertices;
  std::vector<Vector3>& x = state.positions();
  Tangent_newton_system newton(system);
  // The full-step phase on large meshes solves iteratively; the bijectivity-preserving steps keep the factorization,
  // whose gauge they were tuned with (see Tangent_newton_system::solve).
  // The preconditioner is the weights' graph Laplacian, a good model of the Jacobian when every weight is positive
  // (Tutte's, mean value made admissible, cotangent on Delaunay meshes); with negative cotangent weights MINRES
  // needed hundreds of iterations per step (c3d_igea: 2,973 in 22 steps, 197 s against 48 s factorized).
  bool positive_weights = true;
  for(double w : system.weights) positive_weights = positive_weights && w > 0.;
  const bool iterative = allow_folds && positive_weights && n >= iterative_newton_min_vertices;
  Tangent_krylov_system krylov(system);
  const std::vector<double> boost_weights = symmetric_raw_weights(system);
  double forcing = newton_max_forcing;
  std::vector<Vector3> step, trial(n);
  double residual = compute_residuals(system, x).paper;
  auto merit_of = [&](const std::vector<Vector3>& y) {
    return step_merit == Step_merit::IMBALANCE ? imbalance_merit(system, y) : compute_residuals(system, y).paper;
  };
  double merit = merit_of(x);  // what the line search lowers
  // The best iterate: the lowest imbalances among those with the fewest non-positive faces (never Res: the
  // iterate of lowest Res can be the most collapsed one).
  const std::vector<Vector3> start = x;
  std::vector<Vector3> best = x;
  double best_merit = imbalance_merit(system, x);
  std::size_t best_invalid = state.invalid_faces();
  std::size_t short_steps = 0;
  std::vector<double> history;
  while(!has_converged(system, x, residual, state.invalid_faces(), options)) {
    if(report.sweeps >= options.max_newton_sweeps) break;
    if(allow_folds && (report.sweeps >= patience ||
                       (state.invalid_faces() > 0 && summarize_imbalance(system, x, options.tolerance).balanced()))) {
      counts.gave_up = true;
      break;
    }
    if(past_time_budget(options, clock)) { report.out_of_time = true; break; }

    // The boost gradient only needs to be small next to the residual forces that Newton is about to remove.
    counts.boosts += balance_boosts(state, boost_weights, 1e-3 * residual * static_cast<double>(n), 8, boost_aim);
    if(options.cancel_requested()) { report.cancelled = true; break; }
    if(past_time_budget(options, clock)) { report.out_of_time = true; break; }
    const double previous_residual = residual;
    residual = compute_residuals(system, x).paper;
    merit = merit_of(x);

    double accepted_t = 0.;
    bool has_step = false;
    if(iterative) {
      has_step = krylov.assemble(x) && krylov.solve(step, forcing, newton_max_minres_iterations);
      counts.linear_iterations += static_cast<std::size_t>(krylov.last_iterations());
    } else {
      has_step = newton.factorize(x) && newton.solve(step, allow_folds);
    }
    if(options.cancel_requested()) { report.cancelled = true; break; }
    if(past_time_budget(options, clock)) { report.out_of_time = true; break; }
    if(has_step) {
      Vector3 rotation, boost;
      remove_rotation_and_boost(x, step, rotation, boost);
      // With Boost_aim::ROOT the boosts are outer unknowns, set by balance_boosts before each step; the step keeps
      // to the other directions. Its boost part is Newton's estimate along the nearly singular directions, poor
      // after the balancing (0.1 to 5 on bunny00's finest level, where it cost 15 steps instead of 6).
      if(boost_aim == Boost_aim::ROOT) boost = Vector3();
      for(double t = 1.; t > 1e-3; t *= 0.5) {
        for(std::size_t i = 0; i < n; ++i) {
          const Vector3 y = x[i] + t * step[i];
          trial[i] = apply_boost(y * (1. / length(y)), t * boost);
        }
        if(allow_folds ? !has_degree_one(system, trial) : options.preserve_bijectivity && !state.keeps_positive_faces(trial)) continue;
        const double trial_merit = merit_of(trial);
        if(trial_merit < merit) {
          state.assign(trial);
          merit = trial_merit;
          residual = compute_residuals(system, x).paper;
          accepted_t = t;
          ++counts.newton_steps;
          if(t == 1.) ++counts.full_steps;
          break;
        }
      }
    }
    if(iterative) {
      if(accepted_t == 0. && forcing > newton_min_forcing) {
        forcing = newton_min_forcing;  // the same point again, with a nearly exact step
        ++report.sweeps;
        continue;
      }
      const double ratio = previous_residual > 0. ? residual / previous_residual : 1.;
      forcing = std::min(newton_max_forcing, std::max(newton_min_forcing, 0.9 * ratio * ratio));
    }
    if(accepted_t == 0. && allow_folds) {
      counts.gave_up = true;
      break;
    }
    if(accepted_t == 0.) {
      // No acceptable step: the paper's local Newton sweeps (which keep every positive triangle positive) move
      // the iterate, so that the next Newton step starts elsewhere.
      for(int sweep = 0; sweep < 5; ++sweep)
        for(std::size_t i = 0; i < n; ++i)
          if(!local_newton_step(state, i, options.preserve_bijectivity)) ++report.rejected_moves;
      state.refresh_sums();
      residual = compute_residuals(system, x).paper;
      merit = merit_of(x);
    }
    ++report.sweeps;
    const double current_merit = imbalance_merit(system, x);
    if(state.invalid_faces() < best_invalid || (state.invalid_faces() == best_invalid && current_merit < best_merit)) {
      best = x;
      best_merit = current_merit;
      best_invalid = state.invalid_faces();
    }
    if(options.progress && !options.progress("global newton", report.sweeps, residual, state.invalid_faces())) {
      report.cancelled = true;
      break;
    }
    short_steps = accepted_t >= 0.25 ? 0 : short_steps + 1;
    if(!allow_folds && short_steps >= patience) { counts.gave_up = true; break; }
    // Full steps that lower Res forever without balancing any vertex: a drift towards collapse.
    history.push_back(convergence_measure(system, x, residual, options));
    if(history.size() > 50 && history.back() > 0.99 * history[history.size() - 51]) { counts.gave_up = true; break; }
  }
  // A collapse onto a great circle can pass the orientation test with a small residual; the areas expose it,
  // and then none of these iterates is trusted.
  if(!counts.gave_up && has_converged(system, x, residual, state.invalid_faces(), options) && !certify(system.triangles, x).bijective) {
    counts.gave_up = true;
    best = start;
  }
  if(counts.gave_up || report.cancelled || report.out_of_time) {
    state.assign(best);
    residual = compute_residuals(system, x).paper;
  }
  report.residual = residual;
  report.converged = has_converged(system, x, residual, state.invalid_faces(), options);
  report.stagnated = counts.gave_up;
  report.linear_iterations = counts.linear_iterations;
  if(statistics != nullptr) *statistics = counts;
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_NEWTON_H
