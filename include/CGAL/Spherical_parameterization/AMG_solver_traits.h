// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Classical Ruge-Stueben algebraic multigrid as a CGAL sparse linear solver traits class.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H

#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Eigen_vector.h>
#include <CGAL/Real_timer.h>

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Diagonal_row_elimination.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Direct_solver.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Ruge_stueben_hierarchy.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Setup_cache.h>

#include <climits>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/*!
\ingroup PkgSphericalParameterizationRef

The class `AMG_solver_traits` solves sparse linear systems with a classical Ruge-Stueben algebraic multigrid
(AMG) used as the preconditioner of a Krylov method: conjugate gradient for symmetric systems, restarted GMRES or
BiCGStab for non-symmetric ones. It is meant for the large Laplacian-like systems of mesh parameterization
(Tutte, cotangent and mean-value weights), where its cost grows about linearly with the number of unknowns,
whereas the fill-in of direct solvers grows faster.

Rows that hold only a diagonal entry (the border rows of
`CGAL::Surface_mesh_parameterization::Fixed_border_parameterizer_3`) are eliminated: their values are known and
move to the right-hand side, so that the uniform and cotangent systems of the interior become symmetric and
are solved by conjugate gradient. Rows with a negative diagonal are negated.

The setup (strength of connection, coarse/fine splitting, classical interpolation, Galerkin coarse operators) is
done by `factor()`, or by the first call of `linear_solver(A, B, X, D)`, and is cached: a call with a matrix of
the same size, structure and values reuses it, so that solving for the u and then the v coordinates costs one
setup. Copies of a traits object share the setup and the statistics, as copies of `CGAL::Eigen_solver_traits`
share their solver; `independent_copy()` (in `<CGAL/Spherical_parameterization/independent_copy.h>`) makes one
with the same parameters and a setup of its own, for another thread.

Below `Parameters::direct_solver_threshold` unknowns (`Parameters::direct_solver_threshold_non_symmetric` for
non-symmetric systems) the system is handed over to a direct solver (`Eigen::SimplicialLDLT` when symmetric,
`Eigen::SparseLU` otherwise), which is faster on small systems.

All functions return `false`, and never loop forever, on a matrix or right-hand side with non-finite entries,
on a zero diagonal entry, on a singular system, on a Krylov breakdown, or when the iteration cap is reached
before the relative residual \f$ \|B - AX\| / \|B\| \f$ falls below `Parameters::tolerance`.

\cgalModels{SparseLinearAlgebraWithFactorTraits_d}

\sa `CGAL::Eigen_solver_traits`
\sa `CGAL::Eigen_sparse_matrix<T>`
\sa `CGAL::Eigen_vector<T>`
*/
class AMG_solver_traits
{
public:
  /// \name Types
  /// @{

  /// Number type.
  typedef double NT;
  /// Sparse matrix type; it is assembled (by `eigen_object()`) when the solver reads it.
  typedef CGAL::Eigen_sparse_matrix<double> Matrix;
  /// Vector type.
  typedef CGAL::Eigen_vector<double> Vector;

  /// Outer Krylov method.
  enum class Krylov_method
  {
    AUTOMATIC,          ///< conjugate gradient if the (reduced) matrix is numerically symmetric, GMRES otherwise
    CONJUGATE_GRADIENT, ///< for symmetric positive definite systems
    BICGSTAB,           ///< for non-symmetric systems; two V-cycles per iteration
    GMRES               ///< restarted GMRES for non-symmetric systems; one V-cycle per iteration
  };

  /// Setup parameters of the multigrid hierarchy, with these fields:
  /// - `double strength_threshold = 0.25`: `j` strongly influences `i` if
  ///   \f$ -a_{ij} \ge \theta \max_k(-a_{ik}) \f$ (\f$ |a_{ij}| \f$ in rows with positive off-diagonal entries);
  /// - `int max_coarse_size = 200`: coarsening stops at this number of unknowns, solved directly;
  /// - `int max_levels = 25`: maximal number of levels, the finest included;
  /// - `int pre_smoothing_sweeps = 1`: forward Gauss-Seidel sweeps before the coarse-grid correction;
  /// - `int post_smoothing_sweeps = 1`: backward Gauss-Seidel sweeps after the coarse-grid correction.
  ///
  /// It has `operator==`.
  typedef internal::AMG::Hierarchy_parameters Hierarchy_parameters;

  /// Setup and solve parameters.
  struct Parameters
  {
    /// Setup of the multigrid hierarchy (strength threshold, coarsening limits, smoothing sweeps).
    Hierarchy_parameters hierarchy;
    /// Target relative residual \f$ \|B - AX\| / \|B\| \f$.
    double tolerance = 1e-10;
    /// Maximal number of Krylov iterations per solve.
    int max_iterations = 200;
    /// Outer Krylov method.
    Krylov_method krylov_method = Krylov_method::AUTOMATIC;
    /// Restart length of GMRES.
    int gmres_restart = 30;
    /// Relative tolerance of the symmetry test \f$ |a_{ij} - a_{ji}| \le \epsilon \max(|a_{ij}|, |a_{ji}|) \f$.
    double symmetry_tolerance = 1e-12;
    /// Symmetric systems with fewer unknowns (after the elimination of the diagonal rows) are solved by
    /// `Eigen::SimplicialLDLT`; 0 always uses AMG. The default is about where both take the same time for two
    /// right-hand sides on disk meshes (measured by `benchmark_AMG_solver_traits`: 20k on grids, 30k-110k on
    /// meshes, the fill-in of the factor depending on the mesh).
    std::size_t direct_solver_threshold = 100000;
    /// Non-symmetric systems with fewer unknowns are solved by `Eigen::SparseLU`, which is slower than
    /// `Eigen::SimplicialLDLT`: AMG wins from about 5k unknowns on disk meshes. 0 always uses AMG.
    std::size_t direct_solver_threshold_non_symmetric = 5000;
  };

  /// What the last setup and the last solve did.
  struct Statistics
  {
    std::size_t number_of_setups = 0;                       ///< setups (or direct factorizations) done so far
    std::size_t number_of_solves = 0;                       ///< solves done so far
    std::size_t number_of_unknowns = 0;                     ///< after the elimination of the diagonal rows
    std::size_t number_of_eliminated_rows = 0;              ///< rows with only a diagonal entry
    bool symmetric = false;                                 ///< whether the reduced matrix is numerically symmetric
    bool direct_solver = false;                             ///< whether the direct solver was used instead of AMG
    Krylov_method krylov_method = Krylov_method::AUTOMATIC; ///< the method actually used
    std::vector<std::size_t> level_sizes;                   ///< unknowns per level, finest first
    std::vector<std::size_t> level_nonzeros;                ///< nonzeros per level, finest first
    double operator_complexity = 0.;                        ///< total nonzeros of all levels / nonzeros of the finest
    double grid_complexity = 0.;                            ///< total unknowns of all levels / unknowns of the finest
    std::size_t hierarchy_bytes = 0; ///< memory of the matrices and work vectors of the hierarchy
    int iterations = 0;              ///< Krylov iterations of the last solve
    double relative_residual = 0.;   ///< \f$ \|B - AX\| / \|B\| \f$ of the last solve
    double setup_seconds = 0.;       ///< time of the last setup
    double solve_seconds = 0.;       ///< time of the last solve
  };

  /// @}

  /// \name Creation
  /// @{

  /// Constructor with the default parameters.
  AMG_solver_traits() : m_parameters(), m_state(std::make_shared<State>()) {}

  /// Constructor.
  /// \param parameters setup and solve parameters
  explicit AMG_solver_traits(const Parameters& parameters)
    : m_parameters(parameters), m_state(std::make_shared<State>())
  {}

  /// @}

  /// \name Access
  /// @{

  /// The parameters, which can be changed between calls; a change of a setup parameter triggers a new setup.
  Parameters& parameters() { return m_parameters; }
  /// The parameters.
  const Parameters& parameters() const { return m_parameters; }

  /// The statistics of the last setup and solve (shared by the copies of this object).
  const Statistics& statistics() const { return m_state->statistics; }

  /// @}

  /// \name Operations
  /// @{

  /// Solves the sparse linear system \f$ A \times X = B \f$. The solution is \f$ (1/D) \times X \f$, with `D = 1`.
  /// The setup of the previous call is reused if `A` has not changed.
  /// \return `true` if the relative residual is below `Parameters::tolerance`.
  /// \pre `A.row_dimension() == B.dimension()` and `A` is square.
  bool linear_solver(const Matrix& A, const Vector& B, Vector& X, NT& D)
  {
    D = 1;
    return factor_if_changed(A) && solve(B, X);
  }

  /// Sets up the multigrid hierarchy of \f$ A \f$ (a direct factorization below
  /// `Parameters::direct_solver_threshold` unknowns), reused by `linear_solver(B, X)`. `D` is set to 1.
  /// \return `true` if the setup is successful.
  bool factor(const Matrix& A, NT& D)
  {
    D = 1;
    return factor_if_changed(A);
  }

  /// Solves \f$ A \times X = B \f$ with the matrix \f$ A \f$ given to `factor()`.
  /// \return `true` if the relative residual is below `Parameters::tolerance`.
  bool linear_solver(const Vector& B, Vector& X) { return solve(B, X); }

  /// @}

private:
  typedef internal::AMG::Index Index;
  typedef internal::AMG::Compressed_row_matrix Compressed_row_matrix;
  typedef Eigen::SparseMatrix<double, Eigen::ColMajor, int> Eigen_matrix;

  struct State
  {
    internal::AMG::Setup_cache cache;
    internal::AMG::Diagonal_row_elimination elimination;
    bool symmetric = false;
    bool direct = false;
    Krylov_method krylov_method = Krylov_method::AUTOMATIC;
    internal::AMG::Ruge_stueben_hierarchy hierarchy;
    internal::AMG::Direct_solver direct_solver;
    internal::AMG::Krylov_workspace workspace;
    std::vector<double> reduced_right_hand_side, reduced_solution;
    Statistics statistics;

    const Compressed_row_matrix& reduced_matrix() const
    {
      return direct ? direct_solver.matrix() : hierarchy.fine_matrix();
    }
  };

  internal::AMG::Setup_key setup_key(const Eigen_matrix& E) const
  {
    internal::AMG::Setup_key key;
    key.matrix = internal::AMG::fingerprint_of(E);
    key.hierarchy = m_parameters.hierarchy;
    key.symmetry_tolerance = m_parameters.symmetry_tolerance;
    key.direct_solver_threshold = m_parameters.direct_solver_threshold;
    key.direct_solver_threshold_non_symmetric = m_parameters.direct_solver_threshold_non_symmetric;
    return key;
  }

  bool factor_if_changed(const Matrix& A)
  {
    const Eigen_matrix& assembled = A.eigen_object();
    Eigen_matrix compressed_copy;
    const Eigen_matrix* E = &assembled;
    if(!assembled.isCompressed())
    {
      compressed_copy = assembled;
      compressed_copy.makeCompressed();
      E = &compressed_copy;
    }
    const internal::AMG::Setup_key key = setup_key(*E);
    State& state = *m_state;
    if(state.cache.holds(key))
      return state.cache.succeeded();

    state.cache.start(key);
    CGAL::Real_timer timer;
    timer.start();
    state.cache.finish(setup(*E, state));
    state.statistics.setup_seconds = timer.time();
    ++state.statistics.number_of_setups;
    return state.cache.succeeded();
  }

  // The policy: eliminate the diagonal rows, test the symmetry, then a direct solver below the threshold and
  // the multigrid hierarchy above it.
  bool setup(const Eigen_matrix& E, State& state) const
  {
    Statistics& statistics = state.statistics;
    statistics.level_sizes.clear();
    statistics.level_nonzeros.clear();
    statistics.operator_complexity = statistics.grid_complexity = 0.;
    statistics.hierarchy_bytes = 0;
    state.hierarchy = internal::AMG::Ruge_stueben_hierarchy();
    state.direct_solver.clear();

    if(E.rows() != E.cols() || E.nonZeros() >= INT_MAX)
      return false;
    Compressed_row_matrix reduced;
    if(!state.elimination.eliminate(E, reduced))
      return false;

    statistics.number_of_unknowns = std::size_t(reduced.number_of_rows);
    statistics.number_of_eliminated_rows = state.elimination.number_of_eliminated_rows();
    state.symmetric = internal::AMG::is_numerically_symmetric(reduced, m_parameters.symmetry_tolerance);
    statistics.symmetric = state.symmetric;
    state.direct =
        std::size_t(reduced.number_of_rows)
        < (state.symmetric ? m_parameters.direct_solver_threshold : m_parameters.direct_solver_threshold_non_symmetric);
    statistics.direct_solver = state.direct;
    state.krylov_method = m_parameters.krylov_method;
    if(state.krylov_method == Krylov_method::AUTOMATIC)
      state.krylov_method = state.symmetric ? Krylov_method::CONJUGATE_GRADIENT : Krylov_method::GMRES;
    statistics.krylov_method = state.direct ? Krylov_method::AUTOMATIC : state.krylov_method;

    if(reduced.number_of_rows == 0)
    {
      state.direct = true;
      return state.direct_solver.factor(std::move(reduced), state.symmetric);
    }

    if(state.direct)
    {
      statistics.level_sizes.push_back(std::size_t(reduced.number_of_rows));
      statistics.level_nonzeros.push_back(reduced.number_of_nonzeros());
      statistics.operator_complexity = statistics.grid_complexity = 1.;
      return state.direct_solver.factor(std::move(reduced), state.symmetric);
    }

    const bool built = state.hierarchy.build(std::move(reduced), m_parameters.hierarchy);

    double total_rows = 0., total_nonzeros = 0.;
    for(std::size_t l = 0; l < state.hierarchy.number_of_levels(); ++l)
    {
      const Compressed_row_matrix& A = state.hierarchy.level(l).A;
      statistics.level_sizes.push_back(std::size_t(A.number_of_rows));
      statistics.level_nonzeros.push_back(A.number_of_nonzeros());
      total_rows += A.number_of_rows;
      total_nonzeros += double(A.number_of_nonzeros());
    }
    statistics.grid_complexity = total_rows / double(statistics.level_sizes.front());
    statistics.operator_complexity = total_nonzeros / double(statistics.level_nonzeros.front());
    statistics.hierarchy_bytes = state.hierarchy.memory_bytes();
    return built;
  }

  bool solve(const Vector& B, Vector& X)
  {
    State& state = *m_state;
    Statistics& statistics = state.statistics;
    CGAL::Real_timer timer;
    timer.start();
    statistics.iterations = 0;
    statistics.relative_residual = 0.;
    ++statistics.number_of_solves;
    const bool solved = solve_reduced(B, X, state);
    statistics.solve_seconds = timer.time();
    return solved;
  }

  bool solve_reduced(const Vector& B, Vector& X, State& state) const
  {
    Statistics& statistics = state.statistics;
    statistics.relative_residual = std::numeric_limits<double>::infinity();
    if(!state.cache.has_setup() || !state.cache.succeeded() || std::size_t(B.size()) != state.elimination.size())
      return false;
    const Index n = Index(state.elimination.size());
    double right_hand_side_norm = 0.;
    for(Index i = 0; i < n; ++i)
    {
      if(!std::isfinite(B[i]))
        return false;
      right_hand_side_norm += B[i] * B[i];
    }
    right_hand_side_norm = std::sqrt(right_hand_side_norm);
    X.resize(n);
    if(right_hand_side_norm == 0.)
    {
      X.setZero();
      statistics.relative_residual = 0.;
      return true;
    }

    // The residual of the eliminated rows is zero, so ||B - AX|| = ||b - A x|| on the reduced system.
    const double target = m_parameters.tolerance * right_hand_side_norm;
    if(state.elimination.is_identity() && static_cast<const void*>(&B) != static_cast<const void*>(&X))
    {
      X.setZero();
      return solve_reduced_system(state, B.data(), X.data(), target, right_hand_side_norm);
    }

    // B is read in full before X is written: B and X may be the same vector.
    const Index m = state.reduced_matrix().number_of_rows;
    state.elimination.reduce(B.data(), state.reduced_right_hand_side);
    state.reduced_solution.assign(m, 0.);
    double* x = state.reduced_solution.data();
    bool converged = true;
    if(m > 0)
      converged = solve_reduced_system(state, state.reduced_right_hand_side.data(), x, target, right_hand_side_norm);
    else
      state.statistics.relative_residual = 0.;
    state.elimination.expand(x, X.data());
    return converged;
  }

  bool solve_reduced_system(State& state, const double* b, double* x, double target, double reference_norm) const
  {
    internal::AMG::Krylov_result result;
    if(state.direct)
      result = state.direct_solver.solve(b, x, target, reference_norm);
    else
    {
      auto preconditioner = [&state](const double* r, double* z) { state.hierarchy.apply_v_cycle(r, z); };
      const Compressed_row_matrix& A = state.hierarchy.fine_matrix();
      switch(state.krylov_method)
      {
      case Krylov_method::CONJUGATE_GRADIENT:
        result = internal::AMG::conjugate_gradient(A, b, x, preconditioner, target, reference_norm,
                                                   m_parameters.max_iterations, state.workspace);
        break;
      case Krylov_method::BICGSTAB:
        result = internal::AMG::bicgstab(A, b, x, preconditioner, target, reference_norm, m_parameters.max_iterations,
                                         state.workspace);
        break;
      default:
        result = internal::AMG::gmres(A, b, x, preconditioner, target, reference_norm, m_parameters.max_iterations,
                                      m_parameters.gmres_restart, state.workspace);
        break;
      }
    }
    state.statistics.iterations = result.iterations;
    state.statistics.relative_residual = result.relative_residual;
    return result.converged;
  }

  Parameters m_parameters;
  std::shared_ptr<State> m_state;
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H
