// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

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

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_H

#include <CGAL/Spherical_parameterization/internal/Sphere_state.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/side_by_side.h>
#include <CGAL/Spherical_parameterization/internal/small_symmetric_matrix.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// The boost with vector c, its constants computed once (tanh and the square root) for the many vertices it moves.
class Boost
{
public:
  explicit Boost(const Vector3& c)
  {
    const double s = length(c);
    m_identity = !(s > 0.);
    if(m_identity)
      return;
    m_axis = c * (1. / s);
    m_t = std::tanh(s);
    m_root = std::sqrt((1. - m_t) * (1. + m_t));
  }

  Vector3 operator()(const Vector3& x) const
  {
    if(m_identity)
      return x;
    const double u = dot(m_axis, x);
    const Vector3 y = ((u + m_t) * m_axis + m_root * (x - u * m_axis)) * (1. / (1. + u * m_t));
    return y * (1. / length(y));
  }

private:
  bool m_identity = true;
  Vector3 m_axis;
  double m_t = 0., m_root = 1.;
};

inline Vector3 apply_boost(const Vector3& x, const Vector3& c)
{
  return Boost(c)(x);
}

// The raw (unnormalized) weight of the entry k = (i, j) and its mean with the weight of (j, i): the weights of
// the symmetric energy that the boosts are balanced against (the raw weights themselves when they are symmetric).
inline double symmetric_raw_weight(const Sphere_system& system, std::size_t i, std::size_t k)
{
  const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
  return 0.5 * (system.weights[k] * system.row_sums[i] + system.weights[system.reverse[k]] * system.row_sums[j]);
}

// The symmetric raw weight of every entry, in the order of system.neighbors.
inline std::vector<double> symmetric_raw_weights(const Sphere_system& system)
{
  std::vector<double> w(system.neighbors.size());
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      w[k] = symmetric_raw_weight(system, i, k);
  return w;
}

// E(x) = 1/2 sum over edges of the symmetric raw weights w times |x_i - x_j|^2, and -dE/dc at c = 0 for the boost
// with vector c: sum_i of the tangential part of sum_j w_ij (x_j - x_i), because the boost field at x_i,
// e_k - (e_k.x_i) x_i, is the tangential part of e_k. One pass computes both.
inline void spring_energy_and_boost_gradient(const Sphere_system& system, const std::vector<double>& w,
                                             const std::vector<Vector3>& x, double* energy, Eigen::Vector3d* gradient)
{
  double e = 0.;
  Vector3 g;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
  {
    Vector3 s;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const Vector3 edge = x[static_cast<std::size_t>(system.neighbors[k])] - x[i];
      if(energy != nullptr)
        e += w[k] * squared_length(edge);
      s += w[k] * edge;
    }
    g += s - dot(s, x[i]) * x[i];
  }
  if(energy != nullptr)
    *energy = 0.25 * e;
  if(gradient != nullptr)
    *gradient = Eigen::Vector3d(g.x, g.y, g.z);
}

// The Jacobian of the boost gradient g along the boosts: column l is the derivative of g(B_{s e_l}(x)) at s = 0.
// With P_i = I - x_i x_i^T, s_i = sum_j w_ij (x_j - x_i), t_i = P_i s_i, sigma_i = s_i . x_i and
// M_i = sum_j w_ij x_j x_j^T, differentiating g = sum_i t_i along the boost fields P_i e_l gives
//   sum_i (-P_i M_i - x_i t_i^T - sigma_i P_i)
// (checked against finite differences in the tests). One pass, where finite differences take three boosted ones.
inline Eigen::Matrix3d boost_gradient_jacobian(const Sphere_system& system, const std::vector<double>& w,
                                               const std::vector<Vector3>& x)
{
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
  {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const Eigen::Vector3d xi(x[i].x, x[i].y, x[i].z);
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const Vector3& p = x[static_cast<std::size_t>(system.neighbors[k])];
      const Eigen::Vector3d xj(p.x, p.y, p.z);
      m.noalias() += w[k] * (xj * xj.transpose());
      sum += w[k] * (xj - xi);
    }
    const double sigma = sum.dot(xi);
    const Eigen::Vector3d t = sum - sigma * xi;
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - xi * xi.transpose();
    jacobian -= projector * m + xi * t.transpose() + sigma * projector;
  }
  return jacobian;
}

inline double spring_energy(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double e = 0.;
  spring_energy_and_boost_gradient(system, symmetric_raw_weights(system), x, &e, nullptr);
  return e;
}

inline Eigen::Vector3d boost_gradient(const Sphere_system& system, const std::vector<Vector3>& x)
{
  Eigen::Vector3d g;
  spring_energy_and_boost_gradient(system, symmetric_raw_weights(system), x, nullptr, &g);
  return g;
}

// The least-squares infinitesimal rotation w and boost c that best explain the tangent displacements d_i
// (d_i ~ w x x_i + c - (c.x_i) x_i); both are subtracted from d.
inline void remove_rotation_and_boost(const std::vector<Vector3>& x, std::vector<Vector3>& d, Vector3& rotation,
                                      Vector3& boost)
{
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  Matrix6 normal = Matrix6::Zero();
  Vector6 moment = Vector6::Zero();
  const Vector3 axis[3] = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
  for(std::size_t i = 0; i < x.size(); ++i)
  {
    Vector3 field[6];
    for(int k = 0; k < 3; ++k)
    {
      field[k] = cross(axis[k], x[i]);
      field[3 + k] = axis[k] - x[i][k] * x[i];
    }
    for(int a = 0; a < 6; ++a)
    {
      moment[a] += dot(field[a], d[i]);
      for(int b = a; b < 6; ++b)
        normal(a, b) += dot(field[a], field[b]);
    }
  }
  for(int a = 0; a < 6; ++a)
    for(int b = 0; b < a; ++b)
      normal(a, b) = normal(b, a);
  const Vector6 c = solve_symmetric(normal, moment);
  if(!c.allFinite())
  {
    rotation = boost = Vector3();
    return;
  }
  rotation = Vector3(c[0], c[1], c[2]);
  boost = Vector3(c[3], c[4], c[5]);
  for(std::size_t i = 0; i < x.size(); ++i)
    d[i] -= cross(rotation, x[i]) + (boost - dot(boost, x[i]) * x[i]);
}

// What the boosts are balanced to. E is a maximum along the boosts at the balanced map, but not at every iterate on
// the way: on a map carried back from a coarser level the boosts' 3x3 Hessian often has a positive eigenvalue, and
// steps restricted to going up E (the gradient where Newton's step does not) crawl away from the critical point; the
// Newton steps on the whole map that follow then fold and wander. Solving g(c) = 0 as equations (ROOT, with the
// boost part of Newton's step dropped: mobius_newton) suits such a map, close to the solution (fewer Newton steps
// per level: the manual's Method section). Far from the solution (the two-disk guess) the root of g that Newton
// heads for can be the collapse at infinity, where g vanishes like exp(-2s) along a boost (Newton's steps keep the
// length 1/2 there): CGAL's u.off and openscad1580 collapsed. There the steps go up E (MAXIMUM), the collapse being
// E's minimum.
enum class Boost_aim
{
  MAXIMUM,
  ROOT
};

// Balances the boosts: Newton's method on the three equations g(c) = 0 of the boost parameters c (g =
// boost_gradient, the residual forces summed along the boost fields; its Jacobian exact with ROOT, from finite
// differences with MAXIMUM), each step shortened until g shrinks or E grows (away from the collapse, where E = 0;
// near the solution E no longer resolves the change and g decides) and every positive face stays positive. With
// Boost_aim::MAXIMUM, a Newton step that does not go up E is replaced by the gradient. Stops when |g| <= target,
// after tuning.boost_max_iterations, or when no step helps. Returns the number of boosts applied; `settled`, if given,
// tells whether |g| <= target at the end (a root of g near the map was found).
// `w`: symmetric_raw_weights(state.system()), computed once by a caller that balances the boosts again and again.
// `parallel`: the Jacobian is computed beside E and g (at the start, where it is wasted if g is already small enough,
// and beside the update of the state after each boost), and each trial's test of the faces beside its E and g
// (side_by_side.h: the same results).
inline std::size_t balance_boosts(Sphere_state& state, const std::vector<double>& w, double target,
                                  const Solver_tuning& tuning, Boost_aim aim = Boost_aim::MAXIMUM,
                                  bool parallel = false, bool* settled = nullptr)
{
  const Sphere_system& system = state.system();
  const std::vector<Vector3>& x = state.positions();
  const std::size_t n = x.size();
  std::vector<Vector3> y(n);
  auto boosted = [&](const Eigen::Vector3d& c) {
    const Boost boost(Vector3(c[0], c[1], c[2]));
    for(std::size_t i = 0; i < n; ++i)
      y[i] = boost(x[i]);
  };
  auto gradient_at = [&](const std::vector<Vector3>& z) {
    Eigen::Vector3d g;
    spring_energy_and_boost_gradient(system, w, z, nullptr, &g);
    return g;
  };
  std::size_t applied = 0;
  Eigen::Vector3d g;
  double energy = 0.;
  const bool jacobian_beside = parallel && aim == Boost_aim::ROOT;
  Eigen::Matrix3d jacobian_ahead; // boost_gradient_jacobian at x, when jacobian_beside
  side_by_side(
      jacobian_beside, [&]() { spring_energy_and_boost_gradient(system, w, x, &energy, &g); },
      [&]() {
        if(jacobian_beside)
          jacobian_ahead = boost_gradient_jacobian(system, w, x);
      });
  for(std::size_t iteration = 0; iteration < tuning.boost_max_iterations; ++iteration)
  {
    if(!(g.norm() > target))
      break;
    Eigen::Matrix3d slope;
    if(aim == Boost_aim::ROOT)
    {
      slope = jacobian_beside ? jacobian_ahead : boost_gradient_jacobian(system, w, x);
    }
    else
    {
      // The finite differences with which the two-disk path's outcomes on the test corpus were measured (the
      // exact Jacobian changed which of its hard cases converge, both ways).
      const double epsilon = 1e-6;
      for(int l = 0; l < 3; ++l)
      {
        boosted(epsilon * Eigen::Vector3d::Unit(l));
        slope.col(l) = (gradient_at(y) - g) / epsilon;
      }
    }
    // Newton's step for g(c) = 0 (see Boost_aim).
    Eigen::Vector3d c = -slope.partialPivLu().solve(g);
    if(!c.allFinite() || (aim == Boost_aim::MAXIMUM && !(-g.dot(c) > 0.)))
      c = -g;
    if(c.norm() > tuning.boost_max_step)
      c *= tuning.boost_max_step / c.norm();
    double trial_energy = 0.;
    Eigen::Vector3d trial_gradient;
    const double accepted = backtracking_line_search(
        tuning.boost_min_step,
        [&](double t) {
          boosted(t * c);
          return test_with_merit(
              parallel, [&]() { return state.keeps_positive_faces(y); },
              [&]() { spring_energy_and_boost_gradient(system, w, y, &trial_energy, &trial_gradient); });
        },
        [&](double) {
          return trial_energy > energy || trial_gradient.norm() < g.norm();
        });
    if(accepted == 0.)
      break;
    side_by_side(
        jacobian_beside, [&]() { state.assign(y, true); },
        [&]() {
          if(jacobian_beside)
            jacobian_ahead = boost_gradient_jacobian(system, w, y); // y is the next x
        });
    energy = trial_energy;
    g = trial_gradient;
    ++applied;
  }
  if(settled != nullptr)
    *settled = !(g.norm() > target);
  return applied;
}

inline std::size_t balance_boosts(Sphere_state& state, double target, const Solver_tuning& tuning = Solver_tuning(),
                                  Boost_aim aim = Boost_aim::MAXIMUM)
{
  return balance_boosts(state, symmetric_raw_weights(state.system()), target, tuning, aim);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_MOBIUS_H
