// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Newton's linear system for the balance equations in tangent coordinates, for symmetric weights.
//
// Unknowns: a displacement d_i = a_i t1_i + b_i t2_i in the tangent plane of every x_i. Equations: the tangential
// residuals F_i = T_i^T sum_j W_ij (x_j - x_i) with the raw weights W (written with differences, so that tiny
// triangles keep their digits). Linearized: dF_i = sum_j W_ij T_i^T T_j d_j - alpha_i d_i with
// alpha_i = x_i . sum_j W_ij x_j: a sparse symmetric 2n x 2n matrix when W is symmetric. Rotations are an exact
// null space; they are removed by fixing a gauge (vertex 0 does not move, and a vertex at about 90 degrees from it
// does not move around it). The matrix is factorized with a sparse LDL^T whose fill-reducing order is computed
// once, on the vertex graph, and whose pattern (upper triangle only) is written in place at every step.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_NEWTON_SYSTEM_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_NEWTON_SYSTEM_H

#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/deferred_stop_signals.h>
#include <CGAL/Spherical_parameterization/internal/stage3/supernodal_ldlt.h>

#include <CGAL/assertions.h>

#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <metis.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <mutex>
#include <numeric>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// From this many vertices the unknowns are ordered by nested dissection and factorized by supernodes (the large
// meshes, where the factorization is most of a step's time); below, by minimum degree and column by column.
constexpr std::size_t nested_dissection_min_vertices = 20000;

// A fill-reducing order of the vertices, computed on the vertex graph (a quarter of the unknowns' graph):
// approximate minimum degree for small meshes, where it is the faster to compute, METIS nested dissection for
// large ones, where its smaller fill pays. rank[i] is the position of vertex i.
inline std::vector<int> vertex_elimination_rank(const Sphere_system& system)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<int> rank(n);
  std::iota(rank.begin(), rank.end(), 0);
  if(n < 3)
    return rank;
  if(n < nested_dissection_min_vertices)
  {
    Eigen::SparseMatrix<double> pattern(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(n + system.neighbors.size());
    for(std::size_t i = 0; i < n; ++i)
    {
      entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 1.);
      for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
        entries.emplace_back(static_cast<int>(i), system.neighbors[k], 1.);
    }
    pattern.setFromTriplets(entries.begin(), entries.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(pattern, inverse);
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order = inverse.inverse();
    for(std::size_t i = 0; i < n; ++i)
      rank[i] = order.indices()[static_cast<Eigen::Index>(i)];
    return rank;
  }
  idx_t nv = static_cast<idx_t>(n);
  std::vector<idx_t> xadj(system.offsets.begin(), system.offsets.end());
  std::vector<idx_t> adjncy(system.neighbors.begin(), system.neighbors.end());
  std::vector<idx_t> perm(n), iperm(n);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  const Metis_call_guard metis_call; // no stop signal lost inside METIS (see deferred_stop_signals.h)
  if(METIS_NodeND(&nv, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data()) != METIS_OK)
    return rank;
  for(std::size_t i = 0; i < n; ++i)
    rank[i] = static_cast<int>(iperm[i]);
  return rank;
}

// vertex_elimination_rank(system), computed on the first call for the mesh and kept with its system: each call of
// mobius_newton builds a Newton system of its own (three on oded_hammer's finest level, cotangent weights), and the
// least-distortion minimization factorizes Hessians of the same graph (two unknowns per vertex). Each METIS ordering
// took 0.15 s on CGAL's bunny00, 0.7 s on a brain cortex of 163,842 vertices. The cache also records the size of the
// graph it ordered: a system whose connectivity differs (none does: copies change weights only) is ordered anew, as a
// stale order would still factorize correctly but with far more fill.
inline std::vector<int> elimination_rank(const Sphere_system& system)
{
  if(!system.vertex_order)
    return vertex_elimination_rank(system);
  Vertex_order_cache& cache = *system.vertex_order;
  std::lock_guard<std::mutex> lock(cache.mutex);
  if(cache.rank.size() != system.number_of_vertices || cache.edges != system.neighbors.size())
  {
    cache.rank = vertex_elimination_rank(system);
    cache.edges = system.neighbors.size();
  }
  return cache.rank;
}

// The two quantities of vertex i that Newton's equations need, with the raw weights W: the force
// sum_j W_ij (x_j - x_i) (its tangential part is the residual) and alpha_i = x_i . sum_j W_ij x_j (the diagonal of
// the Jacobian), both written with differences, alpha_i = sum_j W_ij (1 - |x_j - x_i|^2 / 2), so that tiny triangles
// keep their digits.
inline void force_and_alpha(const Sphere_system& system, const std::vector<Vector3>& x, std::size_t i, Vector3& force,
                            double& alpha)
{
  force = Vector3();
  alpha = 0.;
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
  {
    const double w = system.weights[k] * system.row_sums[i];
    const Vector3 e = x[static_cast<std::size_t>(system.neighbors[k])] - x[i];
    force += w * e;
    alpha += w * (1. - 0.5 * squared_length(e));
  }
}

// The Jacobian builder of every Newton step in tangent coordinates: the 2x2 block of the equations of vertex i in
// the unknowns of vertex j is w T_i^T T_j (rows: i's frame t1_i, t2_i; columns: j's), with w the raw weight; the
// diagonal block is -alpha_i I (force_and_alpha). In the order (t1.t1, t1.t2, t2.t1, t2.t2).
inline std::array<double, 4> tangent_block(double w, const Vector3& t1_i, const Vector3& t2_i, const Vector3& t1_j,
                                           const Vector3& t2_j)
{
  return {w * dot(t1_i, t1_j), w * dot(t1_i, t2_j), w * dot(t2_i, t1_j), w * dot(t2_i, t2_j)};
}

// Where the values of the 2x2 blocks sit in a compressed column-major matrix, so that each step writes them in place.
inline std::size_t compressed_slot(const Eigen::SparseMatrix<double>& matrix, Eigen::Index row, Eigen::Index column)
{
  const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[column];
  const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[column + 1];
  const int* slot = std::lower_bound(begin, end, static_cast<int>(row));
  CGAL_assertion(slot != end && *slot == static_cast<int>(row)); // the pattern holds every block
  return static_cast<std::size_t>(slot - matrix.innerIndexPtr());
}

// A 2n x 2n matrix with the 2x2 blocks (i, i) and (i, j), j a neighbour of i, all zero, and where each block's four
// values sit in its compressed storage (`diagonal_slots[i]`, `block_slots[k]` for the k-th neighbour entry), so that
// each step writes them in place without sorting.
inline void build_block_pattern(const Sphere_system& system, Eigen::SparseMatrix<double>& matrix,
                                std::vector<std::array<std::size_t, 4>>& diagonal_slots,
                                std::vector<std::array<std::size_t, 4>>& block_slots)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * (n + system.neighbors.size()));
  auto add_block = [&](std::size_t i, std::size_t j) {
    for(int a = 0; a < 2; ++a)
      for(int b = 0; b < 2; ++b)
        triplets.emplace_back(int(2 * i + std::size_t(a)), int(2 * j + std::size_t(b)), 0.);
  };
  for(std::size_t i = 0; i < n; ++i)
  {
    add_block(i, i);
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      add_block(i, std::size_t(system.neighbors[k]));
  }
  matrix.resize(int(2 * n), int(2 * n));
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();
  auto slot = [&](std::size_t row, std::size_t column) {
    return compressed_slot(matrix, static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column));
  };
  auto block = [&](std::size_t i, std::size_t j) {
    return std::array<std::size_t, 4>{slot(2 * i, 2 * j), slot(2 * i, 2 * j + 1), slot(2 * i + 1, 2 * j),
                                      slot(2 * i + 1, 2 * j + 1)};
  };
  diagonal_slots.resize(n);
  block_slots.resize(system.neighbors.size());
  for(std::size_t i = 0; i < n; ++i)
  {
    diagonal_slots[i] = block(i, i);
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      block_slots[k] = block(i, std::size_t(system.neighbors[k]));
  }
}

class Tangent_newton_system
{
public:
  explicit Tangent_newton_system(const Sphere_system& system) : m_system(system) {}

  // Whether the factorization of large systems splits its work between two threads (Supernodal_ldlt::set_parallel).
  void set_parallel(bool parallel) { m_supernodal.set_parallel(parallel); }
  // Asked during the factorization of large systems (Supernodal_ldlt::set_stop); stopped(): the last one was abandoned.
  void set_stop(std::function<bool()> stop) { m_supernodal.set_stop(std::move(stop)); }
  bool stopped() const
  {
    return m_system.number_of_vertices >= nested_dissection_min_vertices && m_supernodal.stopped();
  }

  // Assembles and factorizes at x; false when the factorization fails.
  bool factorize(const std::vector<Vector3>& x)
  {
    const std::size_t n = m_system.number_of_vertices;
    if(m_rank.empty())
      build_pattern();
    tangent_frames(x, m_t1, m_t2);
    // Gauge: vertex 0 does not move, and vertex g, the closest to 90 degrees from it, does not turn around it.
    std::size_t g = 0;
    double smallest = 2.;
    for(std::size_t i = 1; i < n; ++i)
    {
      const double c = std::abs(dot(x[i], x[0]));
      if(c < smallest)
      {
        smallest = c;
        g = i;
      }
    }
    Vector3 around = cross(x[0], x[g]);
    const bool has_gauge = g != 0 && length(around) > 1e-3;
    if(has_gauge)
    {
      m_t1[g] = around * (1. / length(around));
      m_t2[g] = cross(x[g], m_t1[g]);
    }

    double* value = m_matrix.valuePtr();
    m_rhs.resize(static_cast<Eigen::Index>(2 * n));
    for(std::size_t i = 0; i < n; ++i)
    {
      Vector3 force;
      double alpha = 0.;
      force_and_alpha(m_system, x, i, force, alpha);
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        const double w = m_system.weights[k] * m_system.row_sums[i];
        if(m_rank[i] < m_rank[j])
        {
          const std::array<std::size_t, 4>& slot = m_block_slots[k];
          const std::array<double, 4> block = tangent_block(w, m_t1[i], m_t2[i], m_t1[j], m_t2[j]);
          for(int b = 0; b < 4; ++b)
            value[slot[b]] = block[b];
        }
      }
      const std::array<std::size_t, 3>& d = m_diagonal_slots[i];
      value[d[0]] = -alpha;
      value[d[1]] = 0.;
      value[d[2]] = -alpha;
      m_rhs[unknown(i, 0)] = -dot(m_t1[i], force);
      m_rhs[unknown(i, 1)] = -dot(m_t2[i], force);
    }
    // The right-hand sides of the three equations the gauge drops, kept for solve().
    m_pinned_rows.clear();
    m_pinned_rows.push_back({0, 0, m_rhs[unknown(0, 0)]});
    m_pinned_rows.push_back({0, 1, m_rhs[unknown(0, 1)]});
    if(has_gauge)
      m_pinned_rows.push_back({g, 0, m_rhs[unknown(g, 0)]});
    for(const Pinned_row& row : m_pinned_rows)
      fix_unknown(row.vertex, row.component);
    m_x = &x;

    if(m_system.number_of_vertices >= nested_dissection_min_vertices)
      return m_supernodal.factorize(m_matrix);
    if(!m_analyzed)
    {
      m_ldlt.analyzePattern(m_matrix);
      m_analyzed = true;
    }
    m_ldlt.factorize(m_matrix);
    return m_ldlt.info() == Eigen::Success;
  }

  // Newton's step as tangent vectors; false when it is not finite.
  //
  // Away from the solution the linearized equations J d = -F are inconsistent along the rotations: the torque
  // identity sum_i x_i x F_i = 0 holds for every x, so its linearization leaves sum_i d_i x F_i in the three equations
  // the gauge drops, all of it at two vertices. That would make the step ascend there. Instead the step solves
  // J d = -F - R mu, with R mu the infinitesimal rotation field mu x x_i (smooth, spread over every vertex, and
  // orthogonal to F by the same identity, so the step still descends on sum |F_i|^2), mu chosen so that the dropped
  // equations hold too: three more back-substitutions with the same factorization, made in the step's own pass over
  // it. `consistent_rotations`: false keeps the plain gauge, whose steps the bijectivity-preserving Newton and the
  // weight continuation were tuned with (with the correction the continuation stalls on cow's admissible cotangent
  // weights, and Res no longer falls quadratically at the end: unit tests).
  bool solve(std::vector<Vector3>& step, bool consistent_rotations = true)
  {
    const std::size_t n = m_system.number_of_vertices;
    Eigen::VectorXd solution = m_rhs;
    const std::size_t m = m_pinned_rows.size();
    const bool rotations = consistent_rotations && m == 3 && m_x != nullptr;
    // The rotation fields' right-hand sides (their rows of the dropped equations zeroed, their values kept), solved
    // with the step's own (solve_all: at once on large meshes).
    Eigen::VectorXd fields[3];
    double field_rows[3][3];
    if(rotations)
    {
      const std::vector<Vector3>& x = *m_x;
      const Vector3 axis[3] = {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
      for(int k = 0; k < 3; ++k)
      {
        Eigen::VectorXd& field = fields[k];
        field.resize(solution.size());
        for(std::size_t i = 0; i < n; ++i)
        {
          const Vector3 f = cross(axis[k], x[i]);
          field[unknown(i, 0)] = -dot(m_t1[i], f);
          field[unknown(i, 1)] = -dot(m_t2[i], f);
        }
        for(std::size_t r = 0; r < 3; ++r)
        {
          field_rows[k][r] = field[unknown(m_pinned_rows[r].vertex, m_pinned_rows[r].component)];
          field[unknown(m_pinned_rows[r].vertex, m_pinned_rows[r].component)] = 0.;
        }
      }
    }
    Eigen::VectorXd* right_hand_sides[4] = {&solution, &fields[0], &fields[1], &fields[2]};
    if(!solve_all(right_hand_sides, rotations ? 4 : 1))
      return false;
    if(rotations)
    {
      Eigen::Vector3d mismatch;
      for(std::size_t r = 0; r < 3; ++r)
        mismatch[static_cast<Eigen::Index>(r)] = dropped_equation_residual(r, solution, m_pinned_rows[r].rhs);
      Eigen::Matrix<double, Eigen::Dynamic, 3> rotation_solutions(solution.size(), 3);
      Eigen::Matrix3d coupling;
      for(int k = 0; k < 3; ++k)
      {
        rotation_solutions.col(k) = fields[k];
        for(std::size_t r = 0; r < 3; ++r)
          coupling(static_cast<Eigen::Index>(r), k) =
              dropped_equation_residual(r, rotation_solutions.col(k), field_rows[k][r]);
      }
      const Eigen::Vector3d mu = coupling.fullPivLu().solve(-mismatch);
      if(mu.allFinite() && rotation_solutions.allFinite())
        solution += rotation_solutions * mu;
    }
    step.resize(n);
    for(std::size_t i = 0; i < n; ++i)
      step[i] = solution[unknown(i, 0)] * m_t1[i] + solution[unknown(i, 1)] * m_t2[i];
    return true;
  }

private:
  // x = A^-1 x for each of the `count` vectors, with the factorization of the last factorize(); false if the first
  // result is not finite (as before, the others' finiteness is the caller's to test).
  bool solve_all(Eigen::VectorXd* const* xs, std::size_t count) const
  {
    if(m_system.number_of_vertices >= nested_dissection_min_vertices)
      m_supernodal.solve_in_place(xs, count);
    else
      for(std::size_t c = 0; c < count; ++c)
      {
        *xs[c] = m_ldlt.solve(*xs[c]).eval();
        if(c == 0 && m_ldlt.info() != Eigen::Success)
          return false;
      }
    return xs[0]->allFinite();
  }

  struct Pinned_row
  {
    std::size_t vertex;
    int component;
    double rhs; // -F of that equation
  };

  Eigen::Index unknown(std::size_t i, int component) const
  {
    return 2 * static_cast<Eigen::Index>(m_rank[i]) + component;
  }

  // (J d)_row - rhs for the r-th dropped equation, with the full (ungauged) Jacobian row.
  template <typename Vector>
  double dropped_equation_residual(std::size_t r, const Vector& d, double rhs) const
  {
    const std::vector<Vector3>& x = *m_x;
    const std::size_t v = m_pinned_rows[r].vertex;
    const Vector3& t = m_pinned_rows[r].component == 0 ? m_t1[v] : m_t2[v];
    Vector3 pull;
    double alpha = 0.;
    for(std::size_t k = m_system.offsets[v]; k < m_system.offsets[v + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
      const double w = m_system.weights[k] * m_system.row_sums[v];
      pull += w * (d[unknown(j, 0)] * m_t1[j] + d[unknown(j, 1)] * m_t2[j]);
      alpha += w * (1. - 0.5 * squared_length(x[j] - x[v]));
    }
    const double own = m_pinned_rows[r].component == 0 ? d[unknown(v, 0)] : d[unknown(v, 1)];
    return dot(t, pull) - alpha * own - rhs;
  }

  // The upper triangle of the 2x2-block pattern in elimination order, and where every block's values sit.
  void build_pattern()
  {
    const std::size_t n = m_system.number_of_vertices;
    m_rank = elimination_rank(m_system);
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(3 * n + 2 * m_system.neighbors.size());
    for(std::size_t i = 0; i < n; ++i)
    {
      triplets.emplace_back(unknown(i, 0), unknown(i, 0), 0.);
      triplets.emplace_back(unknown(i, 0), unknown(i, 1), 0.);
      triplets.emplace_back(unknown(i, 1), unknown(i, 1), 0.);
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        if(m_rank[i] > m_rank[j])
          continue;
        for(int a = 0; a < 2; ++a)
          for(int b = 0; b < 2; ++b)
            triplets.emplace_back(unknown(i, a), unknown(j, b), 0.);
      }
    }
    m_matrix.resize(static_cast<Eigen::Index>(2 * n), static_cast<Eigen::Index>(2 * n));
    m_matrix.setFromTriplets(triplets.begin(), triplets.end());
    m_matrix.makeCompressed();
    auto slot = [&](Eigen::Index row, Eigen::Index column) { return compressed_slot(m_matrix, row, column); };
    m_diagonal_slots.resize(n);
    m_block_slots.assign(m_system.neighbors.size(), {0, 0, 0, 0});
    for(std::size_t i = 0; i < n; ++i)
    {
      m_diagonal_slots[i] = {slot(unknown(i, 0), unknown(i, 0)), slot(unknown(i, 0), unknown(i, 1)),
                             slot(unknown(i, 1), unknown(i, 1))};
      for(std::size_t k = m_system.offsets[i]; k < m_system.offsets[i + 1]; ++k)
      {
        const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
        if(m_rank[i] > m_rank[j])
          continue;
        m_block_slots[k] = {slot(unknown(i, 0), unknown(j, 0)), slot(unknown(i, 0), unknown(j, 1)),
                            slot(unknown(i, 1), unknown(j, 0)), slot(unknown(i, 1), unknown(j, 1))};
      }
    }
  }

  // Turns the unknown into d = 0: its row and column become those of the identity, its right-hand side 0.
  void fix_unknown(std::size_t v, int component)
  {
    double* value = m_matrix.valuePtr();
    const std::array<std::size_t, 3>& d = m_diagonal_slots[v];
    value[component == 0 ? d[0] : d[2]] = 1.;
    value[d[1]] = 0.;
    for(std::size_t k = m_system.offsets[v]; k < m_system.offsets[v + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(m_system.neighbors[k]);
      if(m_rank[v] < m_rank[j])
      {
        value[m_block_slots[k][2 * component]] = 0.; // row `component` of the block (v, j)
        value[m_block_slots[k][2 * component + 1]] = 0.;
      }
      else
      {
        const std::array<std::size_t, 4>& slot = m_block_slots[m_system.reverse[k]];
        value[slot[component]] = 0.; // column `component` of the block (j, v)
        value[slot[2 + component]] = 0.;
      }
    }
    m_rhs[unknown(v, component)] = 0.;
  }

  const Sphere_system& m_system;
  std::vector<int> m_rank;
  Eigen::SparseMatrix<double> m_matrix;
  std::vector<std::array<std::size_t, 3>> m_diagonal_slots;
  std::vector<std::array<std::size_t, 4>> m_block_slots;
  std::vector<Vector3> m_t1, m_t2;
  Eigen::VectorXd m_rhs;
  std::vector<Pinned_row> m_pinned_rows;
  const std::vector<Vector3>* m_x = nullptr; // the positions of the last factorize()
  bool m_analyzed = false;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> m_ldlt;
  // From nested_dissection_min_vertices, in the order of m_rank: a cortex's factorized step (bigbrain, 163,842
  // vertices, cotangent weights) took about 10 s with the simplicial factorization, 2.4 s by supernodes. Below, the
  // simplicial one: the same steps up to rounding, but with negative weights the small levels' paths turn on it
  // (the manual's Method section).
  Supernodal_ldlt m_supernodal{false, Eigen::Upper};
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_TANGENT_NEWTON_SYSTEM_H
