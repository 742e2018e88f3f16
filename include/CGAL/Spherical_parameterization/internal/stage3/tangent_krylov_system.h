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
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_multigrid.h>
#include <CGAL/Spherical_parameterization/internal/stage3/tangent_newton_system.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

class Tangent_krylov_system
{
public:
  // `prebuilt`: the preconditioner of `system` built already (Laplacian_preconditioner_ahead), or nullptr to build one
  // on the first call of assemble().
  explicit Tangent_krylov_system(const Sphere_system& system, Tangent_laplacian_preconditioner* prebuilt = nullptr)
    : m_system(system), m_preconditioner(prebuilt != nullptr ? prebuilt : &m_own_preconditioner)
  {}

  // Assembles the equations at x (frames, diagonal, right-hand side); builds the multigrid on the first call.
  bool assemble(const std::vector<Vector3>& x)
  {
    const std::size_t n = m_system.number_of_vertices;
    if(!m_preconditioner->is_built() && !m_preconditioner->build(m_system, false))
      return false;
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
    m_rotations.set_rotations(x, m_t1, m_t2);
    m_rotations.project_out(m_rhs.data());
    return true;
  }

  // Newton's step as tangent vectors, with the linear residual reduced by `relative_tolerance` (preconditioned
  // norm); false when MINRES breaks down, the step is not finite, or `stop` (asked after every iteration) ended the
  // solve (then stopped() is true).
  bool solve(std::vector<Vector3>& step, double relative_tolerance, int max_iterations = 500,
             const std::function<bool()>& stop = {})
  {
    const std::size_t n = m_system.number_of_vertices;
    const AMG::Index size = static_cast<AMG::Index>(2 * n);
    m_solution.assign(2 * n, 0.);
    auto apply_operator = [this](const double* in, double* out) { multiply(in, out); };
    auto apply_preconditioner = [this](const double* in, double* out) { precondition(in, out); };
    const AMG::Krylov_result result = AMG::minres(apply_operator, apply_preconditioner, m_rhs.data(), m_solution.data(),
                                                  size, relative_tolerance, max_iterations, m_workspace, stop);
    m_last_iterations = result.iterations;
    m_last_relative_residual = result.relative_residual;
    m_stopped = result.stopped;
    if(m_stopped)
      return false;
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
  bool stopped() const { return m_stopped; }
  double last_relative_residual() const { return m_last_relative_residual; }

  // |b - A s| / |b| of the last solve's step s in the plain norm of the tangent coordinates. MINRES's own test is in
  // the preconditioner's norm, where the boost fields (the tangent parts of the constants, nearly a null space of the
  // Laplacian of Tutte's weights and of cotangent weights' own) weigh far more than the rest: see tangent_multigrid.h.
  double plain_relative_residual()
  {
    std::vector<double> applied(m_rhs.size());
    multiply(m_solution.data(), applied.data());
    double residual = 0., rhs = 0.;
    for(std::size_t r = 0; r < m_rhs.size(); ++r)
    {
      residual += (m_rhs[r] - applied[r]) * (m_rhs[r] - applied[r]);
      rhs += m_rhs[r] * m_rhs[r];
    }
    return rhs > 0. ? std::sqrt(residual / rhs) : 0.;
  }

private:
  // out = P (-J) P in, with P the projection orthogonal to the rotations.
  void multiply(const double* in, double* out)
  {
    const std::size_t n = m_system.number_of_vertices;
    m_projected.resize(2 * n);
    m_rotations.project_out(in, m_projected.data());
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
    m_rotations.project_out(out);
  }

  // out = P T^T (L^-1 (x) I3) T P in: one V-cycle for the three ambient coordinates at once.
  void precondition(const double* in, double* out)
  {
    m_projected.resize(2 * m_system.number_of_vertices);
    m_rotations.project_out(in, m_projected.data());
    m_preconditioner->apply(m_t1, m_t2, m_projected.data(), out);
    m_rotations.project_out(out);
  }

  const Sphere_system& m_system;
  std::vector<Vector3> m_t1, m_t2, m_ambient;
  std::vector<double> m_alpha, m_rhs, m_solution, m_projected;
  Tangent_basis3 m_rotations; // orthonormal
  Tangent_laplacian_preconditioner m_own_preconditioner;
  Tangent_laplacian_preconditioner* m_preconditioner; // m_own_preconditioner or the one built ahead
  AMG::Krylov_workspace m_workspace;
  int m_last_iterations = 0;
  double m_last_relative_residual = 0.;
  bool m_stopped = false;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_KRYLOV_SYSTEM_H
