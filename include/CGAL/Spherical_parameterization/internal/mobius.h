// The Moebius group's part in the balance equations, beyond the paper.
//
// With symmetric weights the equations say that x is a critical point of the spring energy
// E(x) = 1/2 sum_edges w_ij |x_i - x_j|^2 on the product of spheres (their tangential residuals are -grad E).
// The energy is almost invariant under the conformal maps of the sphere: rotations leave it unchanged (an exact
// null space of the Jacobian), and the three "boosts" (the conformal maps that push the sphere towards one point)
// change it only by a discretization error. Along the boosts the balanced solution is a maximum of E; the
// collapsed trivial solutions (E = 0) lie at their ends. So the Jacobian is nearly singular along the boosts:
// Gauss-Seidel slides down them (the collapse the paper proves), and a Newton step along them is huge and poorly
// predicted by its linear model. Here the boosts are handled exactly, as a three-parameter group acting on all
// vertices at once: `balance_boosts` maximizes E over them, and a Newton step's boost part is applied as a boost.
//
// The boost with vector c = s a (|a| = 1) is the flow for time s of the tangent field a - (a.x) x; in closed form
//   x -> ((u + T) a + sqrt(1 - T^2) (x - u a)) / (1 + u T),   u = a.x, T = tanh(s),
// which maps the sphere onto itself, keeps its orientation and maps circles to circles.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

inline Vector3 apply_boost(const Vector3& x, const Vector3& c)
{
  const double s = length(c);
  if(!(s > 0.)) return x;
  const Vector3 a = c * (1. / s);
  const double t = std::tanh(s);
  const double u = dot(a, x);
  Vector3 y = ((u + t) * a + std::sqrt((1. - t) * (1. + t)) * (x - u * a)) * (1. / (1. + u * t));
  return y * (1. / length(y));
}

// The raw (unnormalized) weight of the entry k = (i, j) and its mean with the weight of (j, i): the weights of
// the symmetric energy that the boosts are balanced against (the raw weights themselves when they are symmetric).
inline double symmetric_raw_weight(const Sphere_system& system, std::size_t i, std::size_t k)
{
  const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
  return 0.5 * (system.weights[k] * system.row_sums[i] + system.weights[system.reverse[k]] * system.row_sums[j]);
}

// E(x) = 1/2 sum over edges of the symmetric raw weights times |x_i - x_j|^2.
inline double spring_energy(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double energy = 0.;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      energy += symmetric_raw_weight(system, i, k) * squared_length(x[i] - x[static_cast<std::size_t>(system.neighbors[k])]);
  return 0.25 * energy;
}

// -dE/dc at c = 0 for the boost with vector c: sum_i of the tangential part of sum_j w_ij (x_j - x_i), because the
// boost field at x_i, e_k - (e_k.x_i) x_i, is the tangential part of e_k.
inline Eigen::Vector3d boost_gradient(const Sphere_system& system, const std::vector<Vector3>& x)
{
  Vector3 g;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i) {
    Vector3 s;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      s += symmetric_raw_weight(system, i, k) * (x[static_cast<std::size_t>(system.neighbors[k])] - x[i]);
    g += s - dot(s, x[i]) * x[i];
  }
  return Eigen::Vector3d(g.x, g.y, g.z);
}

// The least-squares infinitesimal rotation w and boost c that best explain the tangent displacements d_i
// (d_i ~ w x x_i + c - (c.x_i) x_i); both are subtracted from d.
inline void remove_rotation_and_boost(const std::vector<Vector3>& x, std::vector<Vector3>& d, Vector3& rotation, Vector3& boost)
{
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  Matrix6 normal = Matrix6::Zero();
  Vector6 moment = Vector6::Zero();
  const Vector3 axis[3] = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
  for(std::size_t i = 0; i < x.size(); ++i) {
    Vector3 field[6];
    for(int k = 0; k < 3; ++k) {
      field[k] = cross(axis[k], x[i]);
      field[3 + k] = axis[k] - x[i][k] * x[i];
    }
    for(int a = 0; a < 6; ++a) {
      moment[a] += dot(field[a], d[i]);
      for(int b = a; b < 6; ++b) normal(a, b) += dot(field[a], field[b]);
    }
  }
  for(int a = 0; a < 6; ++a)
    for(int b = 0; b < a; ++b) normal(a, b) = normal(b, a);
  const Vector6 c = normal.ldlt().solve(moment);
  if(!c.allFinite()) { rotation = boost = Vector3(); return; }
  rotation = Vector3(c[0], c[1], c[2]);
  boost = Vector3(c[3], c[4], c[5]);
  for(std::size_t i = 0; i < x.size(); ++i) d[i] -= cross(rotation, x[i]) + (boost - dot(boost, x[i]) * x[i]);
}

// Maximizes E over the boosts: Newton on their three parameters (the Hessian from finite differences of the
// gradient), each step shortened until E grows and every positive face stays positive. Stops when |grad| <= target,
// after `max_iterations`, or when no step helps. Returns the number of boosts applied.
inline std::size_t balance_boosts(Sphere_state& state, double target, std::size_t max_iterations)
{
  const Sphere_system& system = state.system();
  const std::vector<Vector3>& x = state.positions();
  const std::size_t n = x.size();
  std::vector<Vector3> y(n);
  auto boosted = [&](const Eigen::Vector3d& c) {
    const Vector3 v(c[0], c[1], c[2]);
    for(std::size_t i = 0; i < n; ++i) y[i] = apply_boost(x[i], v);
  };
  std::size_t applied = 0;
  for(std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::Vector3d g = boost_gradient(system, x);
    if(!(g.norm() > target)) break;
    const double epsilon = 1e-6;
    Eigen::Matrix3d slope;
    for(int l = 0; l < 3; ++l) {
      boosted(epsilon * Eigen::Vector3d::Unit(l));
      slope.col(l) = (boost_gradient(system, y) - g) / epsilon;
    }
    // E grows along c when -g.c > 0; Newton's step -slope^-1 g when it does, the gradient otherwise.
    Eigen::Vector3d c = -slope.partialPivLu().solve(g);
    if(!c.allFinite() || !(-g.dot(c) > 0.)) c = -g;
    if(c.norm() > 1.) c *= 1. / c.norm();
    const double energy = spring_energy(system, x);
    bool accepted = false;
    for(double t = 1.; t > 1e-3; t *= 0.5) {
      boosted(t * c);
      if(!state.keeps_positive_faces(y)) continue;
      // Near the maximum E no longer resolves the change: the gradient decides.
      if(spring_energy(system, y) > energy || boost_gradient(system, y).norm() < g.norm()) { accepted = true; break; }
    }
    if(!accepted) break;
    state.assign(y);
    ++applied;
  }
  return applied;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_MOBIUS_H
