// Stage 3, beyond the paper: Newton's method on all vertices at once, in tangent coordinates.
//
// Unknowns: a displacement d_i in the tangent plane of every x_i (frame t1_i, t2_i). Equations: the tangential
// part of the raw weighted sums, F_i = T_i^T sum_j W_ij x_j (zero exactly at balanced positions). Linearized,
// dF_i = -(x_i . s_i) d_i + sum_j W_ij T_i^T T_j d_j, a sparse 2n x 2n system that is symmetric when the raw
// weights are (uniform, cotangent). Rotations of the sphere leave the equations invariant, so the matrix is
// nearly singular along them; a tiny diagonal shift removes that without changing the step elsewhere.
// A step is accepted only if it keeps every positively oriented triangle positive (exact predicate) and lowers
// the paper's residual; otherwise it is halved. The local Newton sweeps take over if a step cannot be found.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_GLOBAL_NEWTON_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_GLOBAL_NEWTON_H

#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <Eigen/SparseCholesky>
#include <Eigen/MetisSupport>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

inline void tangent_frame(const Vector3& x, Vector3& t1, Vector3& t2)
{
  const Vector3 helper = std::abs(x.x) < 0.6 ? Vector3(1, 0, 0) : (std::abs(x.y) < 0.6 ? Vector3(0, 1, 0) : Vector3(0, 0, 1));
  t1 = cross(x, helper);
  t1 *= 1. / length(t1);
  t2 = cross(x, t1);
}

class Global_newton {
public:
  explicit Global_newton(const Sphere_system& system, bool preserve_bijectivity = true)
    : system_(system), preserve_bijectivity_(preserve_bijectivity) {}

  // One Newton step; returns false when no acceptable step was found.
  bool step(Sphere_state& state, double& residual)
  {
    const std::size_t n = system_.number_of_vertices;
    const std::vector<Vector3>& x = state.positions();
    t1_.resize(n);
    t2_.resize(n);
    for(std::size_t i = 0; i < n; ++i) tangent_frame(x[i], t1_[i], t2_[i]);

    if(jacobian_.rows() != Eigen::Index(2 * n)) build_pattern();
    Eigen::VectorXd rhs(2 * n);
    double* values = jacobian_.valuePtr();
    for(std::size_t i = 0; i < n; ++i) {
      const double scale = system_.row_sums[i];
      const Vector3 s = scale * state.sum(i);
      const double alpha = dot(x[i], s);
      rhs[2 * i] = -dot(t1_[i], s);
      rhs[2 * i + 1] = -dot(t2_[i], s);
      const double diagonal = -alpha * (1. + damping_);
      const std::array<std::size_t, 4>& d = diagonal_slots_[i];
      values[d[0]] = diagonal;
      values[d[1]] = 0.;
      values[d[2]] = 0.;
      values[d[3]] = diagonal;
      for(std::size_t k = system_.offsets[i]; k < system_.offsets[i + 1]; ++k) {
        const std::size_t j = static_cast<std::size_t>(system_.neighbors[k]);
        const double w = system_.weights[k] * scale;
        const std::array<std::size_t, 4>& b = block_slots_[k];
        values[b[0]] = w * dot(t1_[i], t1_[j]);
        values[b[1]] = w * dot(t1_[i], t2_[j]);
        values[b[2]] = w * dot(t2_[i], t1_[j]);
        values[b[3]] = w * dot(t2_[i], t2_[j]);
      }
    }
    const Eigen::SparseMatrix<double>& jacobian = jacobian_;

    // Symmetric weights: plain Newton. Otherwise the rotations are not an exact null space of the equations,
    // and Newton's step blows up along them: take Levenberg-Marquardt steps (J^T J + mu I) d = J^T rhs instead.
    for(int attempt = 0; attempt < (system_.symmetric ? 1 : 6); ++attempt) {
      Eigen::VectorXd delta;
      if(system_.symmetric) {
        if(!solve(jacobian, rhs, delta)) return false;
      } else {
        Eigen::SparseMatrix<double> normal = Eigen::SparseMatrix<double>(jacobian.transpose()) * jacobian;
        const double shift = marquardt_ * normal.diagonal().mean();
        for(int k = 0; k < normal.rows(); ++k) normal.coeffRef(k, k) += shift;
        ldlt_.compute(normal);
        if(ldlt_.info() != Eigen::Success) return false;
        delta = ldlt_.solve(jacobian.transpose() * rhs);
        if(!delta.allFinite()) return false;
      }
      double accepted_t = 0.;
      if(try_step(state, residual, delta, accepted_t)) {
        if(!system_.symmetric) marquardt_ = accepted_t == 1. ? std::max(marquardt_ / 3., 1e-12) : marquardt_ * 2.;
        return true;
      }
      marquardt_ = std::min(marquardt_ * 10., 1e6);
    }
    return false;
  }

private:
  // Line search along delta (halving t) for a point that keeps every positive face positive and lowers Res.
  bool try_step(Sphere_state& state, double& residual, const Eigen::VectorXd& delta, double& accepted_t)
  {
    const std::size_t n = system_.number_of_vertices;
    const std::vector<Vector3>& x = state.positions();
    std::vector<Vector3> displacement(n);
    for(std::size_t i = 0; i < n; ++i) displacement[i] = delta[2 * i] * t1_[i] + delta[2 * i + 1] * t2_[i];
    remove_rotation(x, displacement);

    std::vector<Vector3> trial(n);
    for(double t = 1.; t > 1e-6; t *= 0.5) {
      for(std::size_t i = 0; i < n; ++i) {
        Vector3 y = x[i] + t * displacement[i];
        trial[i] = y * (1. / length(y));
      }
      const bool keeps = !preserve_bijectivity_ || state.keeps_positive_faces(trial);
      const double trial_residual = compute_residuals(system_, trial).paper;
      if(!keeps) continue;
      if(trial_residual < residual) {
        state.assign(trial);
        residual = trial_residual;
        accepted_t = t;
        return true;
      }
    }
    return false;
  }

  // Subtracts the infinitesimal rotation omega x x_i that best fits the displacements (least squares):
  // rotations leave the residual unchanged, so a rotation part in the step only adds second-order error.
  static void remove_rotation(const std::vector<Vector3>& x, std::vector<Vector3>& d)
  {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for(std::size_t i = 0; i < x.size(); ++i) {
      const Eigen::Vector3d xi(x[i].x, x[i].y, x[i].z);
      normal += Eigen::Matrix3d::Identity() - xi * xi.transpose();
      const Vector3 m = cross(x[i], d[i]);
      moment += Eigen::Vector3d(m.x, m.y, m.z);
    }
    const Eigen::Vector3d omega = normal.ldlt().solve(moment);
    const Vector3 w(omega[0], omega[1], omega[2]);
    for(std::size_t i = 0; i < x.size(); ++i) d[i] -= cross(w, x[i]);
  }

  bool solve(const Eigen::SparseMatrix<double>& jacobian, const Eigen::VectorXd& rhs, Eigen::VectorXd& delta)
  {
    if(system_.symmetric) {
      // The pattern never changes: order and analyse once, factorize at every step.
      if(!ldlt_analyzed_) { ldlt_.analyzePattern(jacobian); ldlt_analyzed_ = true; }
      ldlt_.factorize(jacobian);
      if(ldlt_.info() == Eigen::Success) {
        delta = ldlt_.solve(rhs);
        if(ldlt_.info() == Eigen::Success && delta.allFinite()) return true;
      }
    }
    lu_.compute(jacobian);
    if(lu_.info() != Eigen::Success) return false;
    delta = lu_.solve(rhs);
    return lu_.info() == Eigen::Success && delta.allFinite();
  }

  // The Jacobian's pattern (2x2 blocks of the vertex adjacency plus the diagonal) and, for every block, where its
  // four values sit in the compressed storage, so that each step writes values in place without sorting.
  void build_pattern()
  {
    const std::size_t n = system_.number_of_vertices;
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(4 * (n + system_.neighbors.size()));
    auto add_block = [&](std::size_t i, std::size_t j) {
      for(int a = 0; a < 2; ++a)
        for(int b = 0; b < 2; ++b) triplets.emplace_back(int(2 * i + a), int(2 * j + b), 0.);
    };
    for(std::size_t i = 0; i < n; ++i) {
      add_block(i, i);
      for(std::size_t k = system_.offsets[i]; k < system_.offsets[i + 1]; ++k) add_block(i, std::size_t(system_.neighbors[k]));
    }
    jacobian_.resize(int(2 * n), int(2 * n));
    jacobian_.setFromTriplets(triplets.begin(), triplets.end());
    jacobian_.makeCompressed();
    auto slot = [&](std::size_t row, std::size_t column) {
      const int* begin = jacobian_.innerIndexPtr() + jacobian_.outerIndexPtr()[column];
      const int* end = jacobian_.innerIndexPtr() + jacobian_.outerIndexPtr()[column + 1];
      return static_cast<std::size_t>(std::lower_bound(begin, end, int(row)) - jacobian_.innerIndexPtr());
    };
    auto block = [&](std::size_t i, std::size_t j) {
      return std::array<std::size_t, 4>{slot(2 * i, 2 * j), slot(2 * i, 2 * j + 1), slot(2 * i + 1, 2 * j), slot(2 * i + 1, 2 * j + 1)};
    };
    diagonal_slots_.resize(n);
    block_slots_.resize(system_.neighbors.size());
    for(std::size_t i = 0; i < n; ++i) {
      diagonal_slots_[i] = block(i, i);
      for(std::size_t k = system_.offsets[i]; k < system_.offsets[i + 1]; ++k) block_slots_[k] = block(i, std::size_t(system_.neighbors[k]));
    }
  }

  const Sphere_system& system_;
  bool preserve_bijectivity_;
  Eigen::SparseMatrix<double> jacobian_;
  std::vector<std::array<std::size_t, 4>> diagonal_slots_, block_slots_;
  bool ldlt_analyzed_ = false;
  double marquardt_ = 1e-6;  // relative Levenberg-Marquardt shift (non-symmetric weights)
  double damping_ = 1e-10;  // relative diagonal shift: keeps the rotations from blowing up the step
  std::vector<Vector3> t1_, t2_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::MetisOrdering<int>> ldlt_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
};

// Global Newton steps until Res < tolerance with no non-positive face; a batch of local Newton sweeps
// whenever no acceptable global step exists, then Newton again.
inline Iteration_report global_newton(Sphere_state& state, const Iteration_options& options, const Stopwatch& clock)
{
  Iteration_report report;
  Global_newton newton(state.system(), options.preserve_bijectivity);
  double residual = state.refresh_sums();
  std::size_t local_sweeps = 0;
  // Stagnation: non-symmetric weights (mean value) generally admit no exact solution, because the three torque
  // identities that make the equations consistent for symmetric weights fail; the residual then levels off at a
  // least-squares floor. Stop when 200 steps gained less than 1% in all.
  std::vector<double> history;
  while(!(residual < options.tolerance && state.invalid_faces() == 0)) {
    if(report.sweeps >= options.max_newton_sweeps) break;
    if(options.max_seconds >= 0. && clock.seconds() > options.max_seconds) { report.out_of_time = true; break; }
    if(!newton.step(state, residual)) {
      // No global step helps: relax locally for a while.
      for(int sweep = 0; sweep < 20; ++sweep) {
        for(std::size_t i = 0; i < state.system().number_of_vertices; ++i)
          if(!local_newton_step(state, i, options.preserve_bijectivity)) ++report.rejected_moves;
        ++local_sweeps;
      }
      residual = state.refresh_sums();
    }
    ++report.sweeps;
    if(options.progress && !options.progress("global newton", report.sweeps, residual, state.invalid_faces())) {
      report.cancelled = true;
      break;
    }
    history.push_back(residual);
    if(history.size() > 200 && residual > 0.99 * history[history.size() - 201]) { report.stagnated = true; break; }
  }
  report.residual = residual;
  report.converged = residual < options.tolerance && state.invalid_faces() == 0;
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_GLOBAL_NEWTON_H
