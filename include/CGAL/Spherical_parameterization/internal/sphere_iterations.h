// Stages 2 and 3 of the paper on the flat arrays of a Sphere_system:
//  - projected Gauss-Seidel (Section 3.2), stopped as soon as the residual grows;
//  - local Newton (Section 3.3): each vertex in turn, in a frame where it sits on the x-axis, takes a Newton step
//    on (theta, phi) that lowers the squared residuals of its one-ring, with the paper's line search.
// Both can preserve bijectivity as the paper's conclusion proposes: a move that would turn one of the vertex's
// positively oriented spherical triangles (exact predicate) non-positive is pulled back towards the previous
// position, and dropped if that does not help.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/sphere_orientation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Iteration_options {
  double tolerance = 1e-6;
  Convergence_test convergence_test = Convergence_test::IMBALANCE;
  std::size_t max_gauss_seidel_sweeps = 1000;
  std::size_t max_newton_sweeps = 200000;
  double max_seconds = -1.;           // negative: no budget
  bool preserve_bijectivity = true;
  // Called after every sweep; returning false cancels the iterations.
  std::function<bool(const char* stage, std::size_t sweep, double residual, std::size_t invalid_faces)> progress;
  // Polled inside long iterations (it repeats the last progress report); returning false cancels.
  std::function<bool()> keep_going;

  bool cancel_requested() const { return keep_going && !keep_going(); }
};

struct Iteration_report {
  std::size_t sweeps = 0;
  double residual = -1.;
  bool converged = false;
  bool out_of_time = false;
  bool stagnated = false;       // the residual stopped decreasing before the tolerance
  bool cancelled = false;       // the progress callback asked to stop
  std::size_t rejected_moves = 0;
  std::size_t linear_iterations = 0;    // iterations of the iterative linear solver (MINRES), if one ran
  double continuation_parameter = -1.;  // how far the continuation from Tutte's weights got (-1: not tried)
};

// Positions, cached neighbour sums s_i = sum_j w_ij x_j, and which faces are positively oriented.
class Sphere_state {
public:
  Sphere_state(const Sphere_system& system, std::vector<Vector3>& x) : system_(system), x_(x)
  {
    face_positive_.assign(system.triangles.size(), 0);
    for(std::size_t f = 0; f < system.triangles.size(); ++f) {
      const auto& t = system.triangles[f];
      face_positive_[f] = is_positive(x[static_cast<std::size_t>(t[0])], x[static_cast<std::size_t>(t[1])], x[static_cast<std::size_t>(t[2])]);
      invalid_faces_ += !face_positive_[f];
    }
    refresh_sums();
  }

  const Sphere_system& system() const { return system_; }
  std::vector<Vector3>& positions() { return x_; }
  const Vector3& sum(std::size_t i) const { return s_[i]; }
  std::size_t invalid_faces() const { return invalid_faces_; }
  bool face_is_positive(std::size_t f) const { return face_positive_[f] != 0; }

  // Recomputes every s_i (removes the drift of incremental updates) and returns the paper's Res.
  double refresh_sums()
  {
    const std::size_t n = system_.number_of_vertices;
    s_.resize(n);
    double total = 0.;
    for(std::size_t i = 0; i < n; ++i) {
      s_[i] = weighted_neighbor_sum(system_, x_, i);
      total += squared_length(cross(x_[i], s_[i]));
    }
    return std::sqrt(total) / static_cast<double>(std::max<std::size_t>(n, 1));
  }

  // Replaces all positions at once (a global step), keeping the face flags and sums consistent.
  void assign(const std::vector<Vector3>& y)
  {
    x_ = y;
    invalid_faces_ = 0;
    for(std::size_t f = 0; f < system_.triangles.size(); ++f) {
      const auto& t = system_.triangles[f];
      face_positive_[f] = is_positive(x_[static_cast<std::size_t>(t[0])], x_[static_cast<std::size_t>(t[1])], x_[static_cast<std::size_t>(t[2])]);
      invalid_faces_ += !face_positive_[f];
    }
    refresh_sums();
  }

  // True when no positive face of the current positions is non-positive at y.
  bool keeps_positive_faces(const std::vector<Vector3>& y) const
  {
    for(std::size_t f = 0; f < system_.triangles.size(); ++f) {
      if(!face_positive_[f]) continue;
      const auto& t = system_.triangles[f];
      if(!is_positive(y[static_cast<std::size_t>(t[0])], y[static_cast<std::size_t>(t[1])], y[static_cast<std::size_t>(t[2])]))
        return false;
    }
    return true;
  }

  void move(std::size_t i, const Vector3& y)
  {
    ring_orientation(i, y, false);
    commit(i, y);
  }

  // Moves i to the first of y, then points pulled back towards x_i, that is acceptable; false if none is.
  bool move_preserving_orientation(std::size_t i, Vector3 y, bool preserve)
  {
    if(preserve) {
      const Vector3 start = x_[i];
      int halvings = 0;
      while(!ring_orientation(i, y, true)) {
        if(++halvings > 12) return false;
        y = start + 0.5 * (y - start);
        y *= 1. / length(y);
      }
    } else {
      ring_orientation(i, y, false);
    }
    commit(i, y);
    return true;
  }

private:
  // The orientations of the faces around i with i at y, into ring_positive_. With `stop_at_fold`, returns false
  // (leaving ring_positive_ incomplete) as soon as a positive face would turn non-positive.
  bool ring_orientation(std::size_t i, const Vector3& y, bool stop_at_fold)
  {
    const std::size_t begin = system_.offsets[i], end = system_.offsets[i + 1];
    ring_positive_.resize(end - begin);
    for(std::size_t k = begin; k < end; ++k) {
      const Vector3& a = x_[static_cast<std::size_t>(system_.neighbors[k])];
      const Vector3& b = x_[static_cast<std::size_t>(system_.neighbors[k + 1 < end ? k + 1 : begin])];
      const bool positive = is_positive(y, a, b);
      ring_positive_[k - begin] = positive;
      if(stop_at_fold && !positive && face_positive_[static_cast<std::size_t>(system_.ring_faces[k])]) return false;
    }
    return true;
  }

  // Moves i to y; the orientations of its faces are those just computed by ring_orientation(i, y, ...).
  void commit(std::size_t i, const Vector3& y)
  {
    const Vector3 delta = y - x_[i];
    x_[i] = y;
    const std::size_t begin = system_.offsets[i], end = system_.offsets[i + 1];
    for(std::size_t k = begin; k < end; ++k) {
      s_[static_cast<std::size_t>(system_.neighbors[k])] += system_.weights[system_.reverse[k]] * delta;
      const std::size_t f = static_cast<std::size_t>(system_.ring_faces[k]);
      const char positive = ring_positive_[k - begin];
      invalid_faces_ = invalid_faces_ + (face_positive_[f] ? 1 : 0) - (positive ? 1 : 0);
      face_positive_[f] = positive;
    }
  }

  const Sphere_system& system_;
  std::vector<Vector3>& x_;
  std::vector<Vector3> s_;
  std::vector<char> face_positive_;
  std::vector<char> ring_positive_;   // scratch of ring_orientation()
  std::size_t invalid_faces_ = 0;
};

// The stopping test of every solver: no non-positive face, and every vertex balanced in its own scale (or the
// paper's Res below the tolerance, when that test was chosen).
inline bool has_converged(const Sphere_system& system, const std::vector<Vector3>& x, double residual,
                          std::size_t invalid_faces, const Iteration_options& options)
{
  if(invalid_faces != 0) return false;
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL) return residual < options.tolerance;
  return summarize_imbalance(system, x, options.tolerance).balanced();
}

// What the stagnation rules watch: the quantity the convergence test bounds (the worst imbalance over its allowed
// value, or Res). Res alone keeps falling on a map that drifts towards collapse while no vertex gets balanced.
inline double convergence_measure(const Sphere_system& system, const std::vector<Vector3>& x, double residual,
                                  const Iteration_options& options)
{
  if(options.convergence_test == Convergence_test::PAPER_RESIDUAL) return residual;
  return summarize_imbalance(system, x, options.tolerance).worst_ratio;
}

class Stopwatch {
public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
private:
  std::chrono::steady_clock::time_point start_;
};

// The time budget, checked between iterations and, inside the long ones, between their parts.
inline bool past_time_budget(const Iteration_options& options, const Stopwatch& clock)
{
  return options.max_seconds >= 0. && clock.seconds() > options.max_seconds;
}

// Paper, Section 3.2, with lambda = 1: x_i <- s_i / |s_i| in turn, while Res decreases. The last iterate whose
// residual did not grow is kept.
inline Iteration_report projected_gauss_seidel(Sphere_state& state, const Iteration_options& options, const Stopwatch& clock)
{
  Iteration_report report;
  const Sphere_system& system = state.system();
  std::vector<Vector3>& x = state.positions();
  double residual = state.refresh_sums();
  std::vector<Vector3> previous;
  while(report.sweeps < options.max_gauss_seidel_sweeps) {
    if(past_time_budget(options, clock)) { report.out_of_time = true; break; }
    previous = x;
    for(std::size_t i = 0; i < system.number_of_vertices; ++i) {
      const Vector3 s = state.sum(i);
      const double norm = length(s);
      if(!(norm > 0.)) continue;
      if(!state.move_preserving_orientation(i, s * (1. / norm), options.preserve_bijectivity)) ++report.rejected_moves;
    }
    ++report.sweeps;
    const double next = state.refresh_sums();
    if(options.progress && !options.progress("gauss-seidel", report.sweeps, next, state.invalid_faces())) report.cancelled = true;
    if(!(next < residual)) {
      // Res grew: return to the previous iterate (faces flags follow the positions).
      for(std::size_t i = 0; i < system.number_of_vertices; ++i)
        if(!(x[i] == previous[i])) state.move(i, previous[i]);
      state.refresh_sums();
      break;
    }
    residual = next;
    if(has_converged(system, x, residual, state.invalid_faces(), options)) { report.converged = true; break; }
    if(report.cancelled) break;
  }
  report.residual = residual;
  return report;
}

// The squared residuals of the one-ring of i if x_i moved to y: |y x s_i|^2 + sum_k |x_k x (s_k + w_ki (y - x_i))|^2.
inline double one_ring_energy(const Sphere_state& state, std::vector<Vector3>& x, std::size_t i, const Vector3& y)
{
  const Sphere_system& system = state.system();
  const Vector3 delta = y - x[i];
  double energy = squared_length(cross(y, state.sum(i)));
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k) {
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
  const Vector3 helper = std::abs(xi.x) < 0.6 ? Vector3(1, 0, 0) : (std::abs(xi.y) < 0.6 ? Vector3(0, 1, 0) : Vector3(0, 0, 1));
  Vector3 t1 = cross(xi, helper);
  t1 *= 1. / length(t1);
  const Vector3 t2 = cross(xi, t1);

  // Residual vectors r = x_k x s_k and their derivatives along t1 (theta) and t2 (phi).
  double h11 = 0., h12 = 0., h22 = 0., g1 = 0., g2 = 0.;
  auto accumulate = [&](const Vector3& r, const Vector3& d1, const Vector3& d2) {
    h11 += dot(d1, d1); h12 += dot(d1, d2); h22 += dot(d2, d2);
    g1 += dot(d1, r); g2 += dot(d2, r);
  };
  const Vector3& si = state.sum(i);
  accumulate(cross(xi, si), cross(t1, si), cross(t2, si));
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k) {
    const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
    const double w = system.weights[system.reverse[k]];
    accumulate(cross(x[j], state.sum(j)), w * cross(x[j], t1), w * cross(x[j], t2));
  }
  const double det = h11 * h22 - h12 * h12;
  if(!(det > 1e-300)) return false;
  const double theta = -(h22 * g1 - h12 * g2) / det;
  const double phi = -(h11 * g2 - h12 * g1) / det;

  auto position = [&](double lambda) {
    const double a = lambda * theta, b = lambda * phi;
    return std::cos(b) * std::cos(a) * xi + std::cos(b) * std::sin(a) * t1 + std::sin(b) * t2;
  };
  const double current = one_ring_energy(state, x, i, xi);
  double best_lambda = 1.;
  double best = one_ring_energy(state, x, i, position(1.));
  for(double lambda = 0.5; lambda > 0.05; lambda *= 0.5) {
    const double e = one_ring_energy(state, x, i, position(lambda));
    if(!(e < best)) break;
    best = e;
    best_lambda = lambda;
  }
  if(!(best < current)) return false;
  Vector3 y = position(best_lambda);
  y *= 1. / length(y);
  return state.move_preserving_orientation(i, y, preserve);
}

inline Iteration_report local_newton(Sphere_state& state, const Iteration_options& options, const Stopwatch& clock)
{
  Iteration_report report;
  const Sphere_system& system = state.system();
  double residual = state.refresh_sums();
  std::vector<double> history;
  while(!has_converged(system, state.positions(), residual, state.invalid_faces(), options)) {
    if(report.sweeps >= options.max_newton_sweeps) break;
    if(past_time_budget(options, clock)) { report.out_of_time = true; break; }
    std::size_t moved = 0;
    for(std::size_t i = 0; i < system.number_of_vertices; ++i) {
      if(local_newton_step(state, i, options.preserve_bijectivity)) ++moved;
      else ++report.rejected_moves;
    }
    ++report.sweeps;
    residual = state.refresh_sums();
    if(options.progress && !options.progress("local newton", report.sweeps, residual, state.invalid_faces())) {
      report.cancelled = true;
      break;
    }
    // Stagnation: no vertex moved, or 1000 sweeps gained less than 1% in all.
    history.push_back(convergence_measure(system, state.positions(), residual, options));
    if(moved == 0 || (history.size() > 1000 && history.back() > 0.99 * history[history.size() - 1001])) {
      report.stagnated = true;
      break;
    }
  }
  report.residual = residual;
  report.converged = has_converged(system, state.positions(), residual, state.invalid_faces(), options);
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_ITERATIONS_H
