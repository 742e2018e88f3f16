// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// What stage 3's two Krylov solvers share (tangent_krylov_system.h for symmetric weights, the least-squares steps of
// imbalance_least_squares.h for non-symmetric ones), in the 2n tangent coordinates of a map x:
// - Tangent_laplacian_preconditioner: one algebraic-multigrid V-cycle of the scalar graph Laplacian of the weights,
//   applied to the three ambient coordinates of a tangent field and projected back on the tangent planes. Both
//   Jacobians are, up to a diagonal scaling of their rows, that projected Laplacian plus terms of the order of the
//   squared edge lengths and of the frame rotations between neighbours.
// - Laplacian_preconditioner_ahead: that V-cycle's hierarchy built on another thread while the coarser levels of the
//   multilevel start are solved.
// - Rotation_basis: an orthonormal basis of the three rotation fields, the null space of both Jacobians, and the
//   projection orthogonal to it.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_MULTIGRID_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_MULTIGRID_H

#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Ruge_stueben_hierarchy.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/deferred_stop_signals.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <future>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

class Tangent_laplacian_preconditioner
{
public:
  // The Laplacian's diagonal is raised by this fraction: its constants (whose tangent parts are the boosts) are
  // otherwise a null space, and the coarsest level's direct solve would be singular.
  static constexpr double laplacian_shift = 1e-8;

  bool is_built() const { return m_built; }

  // The graph Laplacian of the raw weights, off-diagonals -w_ij, its diagonal sum_j w_ij where that Laplacian is
  // known to be positive semi-definite (Sphere_system::signed_laplacian_semidefinite: cotangent weights), otherwise
  // sum_j |w_ij| (semi-definite whatever the signs; the same matrix for positive weights); the diagonal raised by
  // laplacian_shift makes it definite, as MINRES needs. The signed one is the Laplacian in the Jacobian itself: with
  // the absolute values, the vertices with negative weights got diagonals too large, and MINRES needed far more
  // iterations from the maps carried back (bigbrain's finest level, cotangent weights: 101 for its first step, 3.6 s,
  // where a factorized step takes 1.15 s; 51 for all its steps now; from Tutte's map of nilearn_fsavg5_pial_left,
  // 43 against 134 to a plain relative residual of 1e-6: unit test CotangentWeightsArePreconditionedByTheirOwnLaplacian). Its constants are then nearly a null space, as with
  // Tutte's weights: in this preconditioner's norm, in which MINRES tests its forcing, the boost fields (their
  // tangent parts) weigh far more than the rest, so the rest of a step is solved 10 to 45 times less tightly than the
  // forcing says (measured on two cortices, as with Tutte's weights; the steps on the multilevel levels drop their
  // boost part anyway). With `symmetrize`, w_ij is replaced by (w_ij + w_ji) / 2: non-symmetric weights then get a
  // symmetric V-cycle, as good for J^T as for J.
  bool build(const Sphere_system& system, bool symmetrize)
  {
    const std::size_t n = system.number_of_vertices;
    AMG::Compressed_row_matrix laplacian;
    laplacian.number_of_rows = laplacian.number_of_columns = static_cast<AMG::Index>(n);
    laplacian.row_start.assign(n + 1, 0);
    laplacian.column.reserve(n + system.neighbors.size());
    laplacian.value.reserve(n + system.neighbors.size());
    std::vector<std::pair<AMG::Index, double>> row;
    const bool signed_diagonal = system.signed_laplacian_semidefinite && system.symmetric;
    for(std::size_t i = 0; i < n; ++i)
    {
      row.clear();
      double diagonal = 0.;
      for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
        double w = system.weights[k] * system.row_sums[i];
        if(symmetrize)
          w = 0.5 * (w + system.weights[system.reverse[k]] * system.row_sums[j]);
        diagonal += signed_diagonal ? w : std::abs(w);
        row.emplace_back(static_cast<AMG::Index>(j), -w);
      }
      row.emplace_back(static_cast<AMG::Index>(i), diagonal * (1. + laplacian_shift));
      std::sort(row.begin(), row.end());
      for(const auto& entry : row)
      {
        laplacian.column.push_back(entry.first);
        laplacian.value.push_back(entry.second);
      }
      laplacian.row_start[i + 1] = static_cast<AMG::Index>(laplacian.column.size());
    }
    m_built = m_hierarchy.build(std::move(laplacian), AMG::Hierarchy_parameters());
    return m_built;
  }

  // out = T^T (L^-1 (x) I3) T in for the frames (t1, t2): one V-cycle for the three ambient coordinates at once.
  // `out` may be `in`.
  void apply(const std::vector<Vector3>& t1, const std::vector<Vector3>& t2, const double* in, double* out)
  {
    const std::size_t n = t1.size();
    m_coordinates_in.resize(3 * n);
    m_coordinates_out.resize(3 * n);
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector3 v = in[2 * i] * t1[i] + in[2 * i + 1] * t2[i];
      m_coordinates_in[3 * i] = v.x;
      m_coordinates_in[3 * i + 1] = v.y;
      m_coordinates_in[3 * i + 2] = v.z;
    }
    m_hierarchy.apply_v_cycle_block<3>(m_coordinates_in.data(), m_coordinates_out.data());
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector3 v(m_coordinates_out[3 * i], m_coordinates_out[3 * i + 1], m_coordinates_out[3 * i + 2]);
      out[2 * i] = dot(t1[i], v);
      out[2 * i + 1] = dot(t2[i], v);
    }
  }

private:
  AMG::Ruge_stueben_hierarchy m_hierarchy;
  std::vector<double> m_coordinates_in, m_coordinates_out; // three ambient coordinates, interleaved
  bool m_built = false;
};

// The preconditioner of one Sphere_system, built on a thread of its own as soon as the system exists. It depends on the
// weights only, not on the positions, so on a level of the multilevel start it is built while the coarser levels are
// solved, and its set-up (armadillo Loop x3: 3.3 s on its finest level, as long as a Newton step) leaves the path.
// The same hierarchy is built either way: the iterates do not change. The thread reads the system, which must not
// change or go before this object does (the destructor waits for the thread).
class Laplacian_preconditioner_ahead
{
public:
  Laplacian_preconditioner_ahead() = default;
  Laplacian_preconditioner_ahead(const Laplacian_preconditioner_ahead&) = delete;
  Laplacian_preconditioner_ahead& operator=(const Laplacian_preconditioner_ahead&) = delete;
  ~Laplacian_preconditioner_ahead()
  {
    if(m_future.valid())
      m_future.wait();
  }

  bool started() const { return m_system != nullptr; }

  void start(const Sphere_system& system)
  {
    m_system = &system;
    m_future = std::async(std::launch::async, [&system]() {
      // No stop signal for this thread: while a METIS call of the calling thread holds them back, METIS' own handler
      // is installed, and a signal delivered here would run it (deferred_stop_signals.h).
      const Deferred_stop_signals hold_back;
      std::unique_ptr<Tangent_laplacian_preconditioner> preconditioner(new Tangent_laplacian_preconditioner());
      preconditioner->build(system, false);
      return preconditioner;
    });
  }

  // The preconditioner, once built, if it was built for `system` itself (a copy may have other weights: tip
  // regularization, weight continuation); nullptr otherwise.
  Tangent_laplacian_preconditioner* get(const Sphere_system& system)
  {
    if(&system != m_system)
      return nullptr;
    if(m_future.valid())
      m_preconditioner = m_future.get();
    return m_preconditioner && m_preconditioner->is_built() ? m_preconditioner.get() : nullptr;
  }

private:
  const Sphere_system* m_system = nullptr;
  std::future<std::unique_ptr<Tangent_laplacian_preconditioner>> m_future;
  std::unique_ptr<Tangent_laplacian_preconditioner> m_preconditioner;
};

// Three orthonormal vectors of the 2n tangent coordinates, and the projection orthogonal to them.
class Tangent_basis3
{
public:
  std::vector<double>& operator[](std::size_t k) { return m_q[k]; }
  const std::vector<double>& operator[](std::size_t k) const { return m_q[k]; }

  // The rotation fields e_k x x_i in the frames (t1, t2), orthonormalized.
  void set_rotations(const std::vector<Vector3>& x, const std::vector<Vector3>& t1, const std::vector<Vector3>& t2)
  {
    const std::size_t n = x.size();
    const Vector3 axis[3] = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
    for(std::size_t k = 0; k < 3; ++k)
    {
      std::vector<double>& q = m_q[k];
      q.resize(2 * n);
      for(std::size_t i = 0; i < n; ++i)
      {
        const Vector3 f = cross(axis[k], x[i]);
        q[2 * i] = dot(t1[i], f);
        q[2 * i + 1] = dot(t2[i], f);
      }
    }
    orthonormalize();
  }

  // Gram-Schmidt on the three vectors as they are (each twice against the previous ones); false when they are
  // (numerically) dependent or not finite.
  bool orthonormalize()
  {
    const AMG::Index size = static_cast<AMG::Index>(m_q[0].size());
    for(std::size_t k = 0; k < 3; ++k)
    {
      std::vector<double>& q = m_q[k];
      for(int pass = 0; pass < 2; ++pass)
        for(std::size_t m = 0; m < k; ++m)
        {
          const double c = AMG::dot(q.data(), m_q[m].data(), size);
          for(std::size_t r = 0; r < q.size(); ++r)
            q[r] -= c * m_q[m][r];
        }
      const double length_q = AMG::norm(q.data(), size);
      if(!(length_q > 0.) || !std::isfinite(length_q))
        return false;
      for(double& value : q)
        value /= length_q;
    }
    return true;
  }

  // v = in - sum_k (v . q_k) q_k over the three vectors in turn (modified Gram-Schmidt), each subtraction in the pass
  // that takes the next product: four passes instead of a copy and six (a projection runs four times per MINRES
  // iteration), the same values. `v` may be `in`.
  void project_out(const double* in, double* v) const
  {
    const std::size_t size = m_q[0].size();
    const double* q0 = m_q[0].data();
    const double* q1 = m_q[1].data();
    const double* q2 = m_q[2].data();
    double c0 = 0.;
    for(std::size_t r = 0; r < size; ++r)
      c0 += in[r] * q0[r];
    double c1 = 0.;
    for(std::size_t r = 0; r < size; ++r)
    {
      const double a = in[r] - c0 * q0[r];
      v[r] = a;
      c1 += a * q1[r];
    }
    double c2 = 0.;
    for(std::size_t r = 0; r < size; ++r)
    {
      const double a = v[r] - c1 * q1[r];
      v[r] = a;
      c2 += a * q2[r];
    }
    for(std::size_t r = 0; r < size; ++r)
      v[r] -= c2 * q2[r];
  }
  void project_out(double* v) const { project_out(v, v); }

  // The three coordinates (q_k . v).
  void coordinates(const double* v, double c[3]) const
  {
    for(std::size_t k = 0; k < 3; ++k)
      c[k] = AMG::dot(m_q[k].data(), v, static_cast<AMG::Index>(m_q[k].size()));
  }

private:
  std::vector<double> m_q[3];
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_MULTIGRID_H
