// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Newton's linear system in tangent coordinates (the same equations as tangent_newton_system.h), solved
// iteratively: MINRES with the package's algebraic multigrid as preconditioner, in memory and time linear in the
// mesh size, where a sparse factorization grows like n^1.5 in time and n log n in memory (3.3M faces: 100 s and
// gigabytes per step).
//
// Why these choices:
// - For symmetric weights the Jacobian -J is symmetric but indefinite: near the solution it has three negative
//   eigenvalues (close to the Moebius boosts) and three zeros (the rotations). MINRES accepts an indefinite operator
//   with a positive definite preconditioner; conjugate gradients would not.
// - The rotations are deflated: the unknowns and the residual are kept orthogonal to the three rotation fields
//   (orthonormalized), so the system MINRES sees is nonsingular on its space and no vertex is pinned. Solving
//   P(-J)P d = F there is the rotation-consistent step J d = -F - R mu of tangent_newton_system.h.
// - The preconditioner is one V-cycle of the scalar graph Laplacian of the weights (built once per mesh: it does
//   not depend on the positions) applied to each ambient coordinate of the tangent vectors, then projected back to
//   the tangent planes: -J differs from that projected Laplacian only by terms of the order of the squared edge
//   lengths and by the frame rotations between neighbours.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_KRYLOV_SYSTEM_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_KRYLOV_SYSTEM_H

#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Ruge_stueben_hierarchy.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_newton_system.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

class Tangent_krylov_system
{
public:
  explicit Tangent_krylov_system(const Sphere_system& system) : m_system(system) {}

  // The Laplacian's diagonal is raised by this fraction: its constants (whose tangent parts are the boosts) are
  // otherwise a null space, and the coarsest level's direct solve would be singular.
  static constexpr double laplacian_shift = 1e-8;

  // Assembles the equations at x (frames, diagonal, right-hand side); builds the multigrid on the first call.
  bool assemble(const std::vector<Vector3>& x)
  {
    const std::size_t n = m_system.number_of_vertices;
    if(!m_hierarchy_built)
    {
      if(!build_preconditioner())
        return false;
      m_hierarchy_built = true;
    }
    m_t1.resize(n);
    m_t2.resize(n);
    m_alpha.resize(n);
    m_rhs.assign(2 * n, 0.);
    for(std::size_t i = 0; i < n; ++i)
    {
      tangent_frame(x[i], m_t1[i], m_t2[i]);
      Vector3 force;
      double alpha = 0.;
      force_and_alpha(m_system, x, i, force, alpha);
      m_alpha[i] = alpha;
      m_rhs[2 * i] = dot(m_t1[i], force);
      m_rhs[2 * i + 1] = dot(m_t2[i], force);
    }
    build_rotation_basis(x);
    project_out_rotations(m_rhs.data());
    return true;
  }

  // Newton's step as tangent vectors, with the linear residual reduced by `relative_tolerance` (preconditioned
  // norm); false when MINRES breaks down or the step is not finite.
  bool solve(std::vector<Vector3>& step, double relative_tolerance, int max_iterations = 500)
  {
    const std::size_t n = m_system.number_of_vertices;
    const AMG::Index size = static_cast<AMG::Index>(2 * n);
    m_solution.assign(2 * n, 0.);
    auto apply_operator = [this](const double* in, double* out) { multiply(in, out); };
    auto apply_preconditioner = [this](const double* in, double* out) { precondition(in, out); };
    const AMG::Krylov_result result = AMG::minres(apply_operator, apply_preconditioner, m_rhs.data(), m_solution.data(),
                                                  size, relative_tolerance, max_iterations, m_workspace);
    m_last_iterations = result.iterations;
    m_last_relative_residual = result.relative_residual;
    step.resize(n);
    for(std::size_t i = 0; i < n; ++i)
    {
      step[i] = m_solution[2 * i] * m_t1[i] + m_solution[2 * i + 1] * m_t2[i];
      if(!std::isfinite(step[i].x) || !std::isfinite(step[i].y) || !std::isfinite(step[i].z))
        return false;
    }
    return result.iterations > 0 || result.converged;
  }

  int last_iterations() const { return m_last_iterations; }
  double last_relative_residual() const { return m_last_relative_residual; }

private:
  // out = P (-J) P in, with P the projection orthogonal to the rotations.
  void multiply(const double* in, double* out)
  {
    const std::size_t n = m_system.number_of_vertices;
    m_projected.resize(2 * n);
    project_out_rotations(in, m_projected.data());
    m_ambient.resize(n);
    for(std::size_t i = 0; i < n; ++i)
      m_ambient[i] = m_projected[2 * i] * m_t1[i] + m_projected[2 * i + 1] * m_t2[i];
    for(std::size_t i = 0; i < n; ++i)
    {
      Vector3 pull;
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
        pull +=
            (m_system.weights[k] * m_system.row_sums[i]) * m_ambient[static_cast<std::size_t>(m_system.neighbors[k])];
      out[2 * i] = m_alpha[i] * m_projected[2 * i] - dot(m_t1[i], pull);
      out[2 * i + 1] = m_alpha[i] * m_projected[2 * i + 1] - dot(m_t2[i], pull);
    }
    project_out_rotations(out);
  }

  // out = P T^T (L^-1 (x) I3) T P in: one V-cycle for the three ambient coordinates at once.
  void precondition(const double* in, double* out)
  {
    const std::size_t n = m_system.number_of_vertices;
    m_projected.resize(2 * n);
    project_out_rotations(in, m_projected.data());
    m_coordinates_in.resize(3 * n);
    m_coordinates_out.resize(3 * n);
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector3 v = m_projected[2 * i] * m_t1[i] + m_projected[2 * i + 1] * m_t2[i];
      m_coordinates_in[3 * i] = v.x;
      m_coordinates_in[3 * i + 1] = v.y;
      m_coordinates_in[3 * i + 2] = v.z;
    }
    m_hierarchy.apply_v_cycle_block<3>(m_coordinates_in.data(), m_coordinates_out.data());
    for(std::size_t i = 0; i < n; ++i)
    {
      const Vector3 v(m_coordinates_out[3 * i], m_coordinates_out[3 * i + 1], m_coordinates_out[3 * i + 2]);
      out[2 * i] = dot(m_t1[i], v);
      out[2 * i + 1] = dot(m_t2[i], v);
    }
    project_out_rotations(out);
  }

  // The graph Laplacian of the raw weights, off-diagonals -w_ij, diagonal sum_j |w_ij| (positive definite also
  // for cotangent weights of either sign), slightly raised.
  bool build_preconditioner()
  {
    const std::size_t n = m_system.number_of_vertices;
    AMG::Compressed_row_matrix laplacian;
    laplacian.number_of_rows = laplacian.number_of_columns = static_cast<AMG::Index>(n);
    laplacian.row_start.assign(n + 1, 0);
    laplacian.column.reserve(n + m_system.neighbors.size());
    laplacian.value.reserve(n + m_system.neighbors.size());
    std::vector<std::pair<AMG::Index, double>> row;
    for(std::size_t i = 0; i < n; ++i)
    {
      row.clear();
      double diagonal = 0.;
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const double w = m_system.weights[k] * m_system.row_sums[i];
        diagonal += std::abs(w);
        row.emplace_back(static_cast<AMG::Index>(m_system.neighbors[k]), -w);
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
    return m_hierarchy.build(std::move(laplacian), AMG::Hierarchy_parameters());
  }

  // An orthonormal basis (in the 2n tangent coordinates) of the three rotation fields e_k x x_i.
  void build_rotation_basis(const std::vector<Vector3>& x)
  {
    const std::size_t n = m_system.number_of_vertices;
    const Vector3 axis[3] = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
    for(std::size_t k = 0; k < 3; ++k)
    {
      std::vector<double>& q = m_rotations[k];
      q.resize(2 * n);
      for(std::size_t i = 0; i < n; ++i)
      {
        const Vector3 f = cross(axis[k], x[i]);
        q[2 * i] = dot(m_t1[i], f);
        q[2 * i + 1] = dot(m_t2[i], f);
      }
      for(int pass = 0; pass < 2; ++pass)
        for(std::size_t m = 0; m < k; ++m)
        {
          const double c = AMG::dot(q.data(), m_rotations[m].data(), static_cast<AMG::Index>(2 * n));
          for(std::size_t r = 0; r < 2 * n; ++r)
            q[r] -= c * m_rotations[m][r];
        }
      const double length_q = AMG::norm(q.data(), static_cast<AMG::Index>(2 * n));
      for(double& value : q)
        value /= length_q;
    }
  }

  // v = in - sum_k (v . q_k) q_k over the three rotations in turn (modified Gram-Schmidt), each subtraction in the pass
  // that takes the next product: four passes instead of a copy and six (a projection runs four times per MINRES
  // iteration), the same values. `v` may be `in`.
  void project_out_rotations(const double* in, double* v) const
  {
    const std::size_t size = 2 * m_system.number_of_vertices;
    const double* q0 = m_rotations[0].data();
    const double* q1 = m_rotations[1].data();
    const double* q2 = m_rotations[2].data();
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
  void project_out_rotations(double* v) const { project_out_rotations(v, v); }

  const Sphere_system& m_system;
  std::vector<Vector3> m_t1, m_t2, m_ambient;
  std::vector<double> m_alpha, m_rhs, m_solution, m_projected;
  std::vector<double> m_rotations[3];
  std::vector<double> m_coordinates_in, m_coordinates_out; // three ambient coordinates, interleaved
  AMG::Ruge_stueben_hierarchy m_hierarchy;
  AMG::Krylov_workspace m_workspace;
  bool m_hierarchy_built = false;
  int m_last_iterations = 0;
  double m_last_relative_residual = 0.;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_KRYLOV_SYSTEM_H
