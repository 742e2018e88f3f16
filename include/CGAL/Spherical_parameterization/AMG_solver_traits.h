// Classical Ruge-Stueben algebraic multigrid as a CGAL sparse linear solver traits class.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H

#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Eigen_vector.h>

#include <CGAL/Spherical_parameterization/internal/AMG/Compressed_row_matrix.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Ruge_stueben_hierarchy.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
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
share their solver.

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

  /// Setup and solve parameters.
  struct Parameters
  {
    /// `j` strongly influences `i` if \f$ -a_{ij} \ge \theta \max_k(-a_{ik}) \f$
    /// (\f$ |a_{ij}| \f$ in rows with positive off-diagonal entries).
    double strength_threshold = 0.25;
    /// Forward Gauss-Seidel sweeps before the coarse-grid correction.
    int pre_smoothing_sweeps = 1;
    /// Backward Gauss-Seidel sweeps after the coarse-grid correction.
    int post_smoothing_sweeps = 1;
    /// Coarsening stops at this number of unknowns, solved directly.
    int max_coarse_size = 200;
    /// Maximal number of levels, the finest included.
    int max_levels = 25;
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
    std::size_t number_of_setups = 0;          ///< setups (or direct factorizations) done so far
    std::size_t number_of_solves = 0;          ///< solves done so far
    std::size_t number_of_unknowns = 0;        ///< after the elimination of the diagonal rows
    std::size_t number_of_eliminated_rows = 0; ///< rows with only a diagonal entry
    bool symmetric = false;                    ///< whether the reduced matrix is numerically symmetric
    bool direct_solver = false;                ///< whether the direct solver was used instead of AMG
    Krylov_method krylov_method = Krylov_method::AUTOMATIC; ///< the method actually used
    std::vector<std::size_t> level_sizes;      ///< unknowns per level, finest first
    std::vector<std::size_t> level_nonzeros;   ///< nonzeros per level, finest first
    double operator_complexity = 0.;           ///< total nonzeros of all levels / nonzeros of the finest
    double grid_complexity = 0.;               ///< total unknowns of all levels / unknowns of the finest
    std::size_t hierarchy_bytes = 0;           ///< memory of the matrices and work vectors of the hierarchy
    int iterations = 0;                        ///< Krylov iterations of the last solve
    double relative_residual = 0.;             ///< \f$ \|B - AX\| / \|B\| \f$ of the last solve
    double setup_seconds = 0.;                 ///< time of the last setup
    double solve_seconds = 0.;                 ///< time of the last solve
  };

  /// @}

  /// \name Creation
  /// @{

  /// Constructor with the default parameters.
  AMG_solver_traits() : m_parameters(), m_state(std::make_shared<State>()) { }

  /// Constructor.
  /// \param parameters setup and solve parameters
  explicit AMG_solver_traits(const Parameters& parameters)
    : m_parameters(parameters), m_state(std::make_shared<State>())
  { }

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
  typedef std::chrono::steady_clock Clock;

  struct Fingerprint
  {
    std::size_t rows = 0, columns = 0, nonzeros = 0;
    std::uint64_t hash = 0;
    Parameters parameters; // the setup parameters among them

    bool operator==(const Fingerprint& o) const
    {
      const Parameters& p = parameters;
      const Parameters& q = o.parameters;
      return rows == o.rows && columns == o.columns && nonzeros == o.nonzeros && hash == o.hash
          && p.strength_threshold == q.strength_threshold && p.pre_smoothing_sweeps == q.pre_smoothing_sweeps
          && p.post_smoothing_sweeps == q.post_smoothing_sweeps && p.max_coarse_size == q.max_coarse_size
          && p.max_levels == q.max_levels && p.symmetry_tolerance == q.symmetry_tolerance
          && p.direct_solver_threshold == q.direct_solver_threshold
          && p.direct_solver_threshold_non_symmetric == q.direct_solver_threshold_non_symmetric;
    }
  };

  struct State
  {
    bool has_setup = false;
    bool setup_succeeded = false;
    Fingerprint fingerprint;

    // Elimination of the rows that hold only a diagonal entry.
    std::size_t original_size = 0;
    std::vector<Index> original_index;          // of each reduced unknown
    std::vector<Index> eliminated_index;        // rows with only a diagonal entry
    std::vector<double> eliminated_diagonal;
    std::vector<double> row_sign;               // of each reduced row: -1 where the diagonal was negative
    Compressed_row_matrix coupling;             // reduced rows x eliminated unknowns
    bool identity_reduction = false;            // nothing eliminated or negated: solve in place in X

    bool symmetric = false;
    bool direct = false;
    Krylov_method krylov_method = Krylov_method::AUTOMATIC;
    internal::AMG::Ruge_stueben_hierarchy hierarchy;
    Compressed_row_matrix direct_matrix;        // the reduced matrix when the direct solver is used
    std::unique_ptr<Eigen::SimplicialLDLT<Eigen_matrix>> ldlt;
    std::unique_ptr<Eigen::SparseLU<Eigen_matrix>> lu;

    internal::AMG::Krylov_workspace workspace;
    std::vector<double> reduced_right_hand_side, reduced_solution, known_values, correction;
    Statistics statistics;

    const Compressed_row_matrix& reduced_matrix() const
    {
      return direct ? direct_matrix : hierarchy.fine_matrix();
    }
  };

  static double seconds_since(Clock::time_point start)
  {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  static std::uint64_t hash_words(std::uint64_t hash, const void* data, std::size_t bytes)
  {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for(; i + 8 <= bytes; i += 8)
    {
      std::uint64_t word;
      std::memcpy(&word, p + i, 8);
      hash = (hash ^ word) * 0x100000001b3ULL;
      hash ^= hash >> 29;
    }
    for(; i < bytes; ++i)
      hash = (hash ^ p[i]) * 0x100000001b3ULL;
    return hash;
  }

  static Fingerprint fingerprint_of(const Eigen_matrix& E, const Parameters& parameters)
  {
    Fingerprint f;
    f.rows = std::size_t(E.rows());
    f.columns = std::size_t(E.cols());
    f.nonzeros = std::size_t(E.nonZeros());
    f.parameters = parameters;
    std::uint64_t hash = 0xcbf29ce484222325ULL;
    hash = hash_words(hash, E.outerIndexPtr(), sizeof(int) * (std::size_t(E.outerSize()) + 1));
    hash = hash_words(hash, E.innerIndexPtr(), sizeof(int) * f.nonzeros);
    hash = hash_words(hash, E.valuePtr(), sizeof(double) * f.nonzeros);
    f.hash = hash;
    return f;
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
    const Fingerprint fingerprint = fingerprint_of(*E, m_parameters);
    State& state = *m_state;
    if(state.has_setup && state.fingerprint == fingerprint)
      return state.setup_succeeded;

    state.fingerprint = fingerprint;
    state.has_setup = true;
    state.setup_succeeded = false;
    const Clock::time_point start = Clock::now();
    state.setup_succeeded = setup(*E, state);
    state.statistics.setup_seconds = seconds_since(start);
    ++state.statistics.number_of_setups;
    return state.setup_succeeded;
  }

  // Splits the rows into eliminated ones (only a diagonal entry: the value is known) and the reduced system,
  // read directly from Eigen's column-major storage; columns come out sorted.
  static bool eliminate_diagonal_rows(const Eigen_matrix& E, State& state, Compressed_row_matrix& reduced)
  {
    const Index n = Index(E.rows());
    const int* outer = E.outerIndexPtr();
    const int* inner = E.innerIndexPtr();
    const double* value = E.valuePtr();

    std::vector<double> diagonal(n, 0.);
    std::vector<char> has_off_diagonal(n, 0);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        if(!std::isfinite(value[k]))
          return false;
        if(inner[k] == j)
          diagonal[j] += value[k];
        else if(value[k] != 0.)
          has_off_diagonal[inner[k]] = 1;
      }

    std::vector<Index> reduced_index(n, -1), eliminated_ordinal(n, -1);
    state.original_index.clear();
    state.eliminated_index.clear();
    state.eliminated_diagonal.clear();
    state.row_sign.clear();
    for(Index i = 0; i < n; ++i)
    {
      if(diagonal[i] == 0.)
        return false; // zero diagonal entry: singular, or not a system this solver handles
      if(has_off_diagonal[i])
      {
        reduced_index[i] = Index(state.original_index.size());
        state.original_index.push_back(i);
        state.row_sign.push_back(diagonal[i] < 0. ? -1. : 1.);
      }
      else
      {
        eliminated_ordinal[i] = Index(state.eliminated_index.size());
        state.eliminated_index.push_back(i);
        state.eliminated_diagonal.push_back(diagonal[i]);
      }
    }
    const Index m = Index(state.original_index.size());
    state.identity_reduction = (m == n)
      && std::find(state.row_sign.begin(), state.row_sign.end(), -1.) == state.row_sign.end();

    reduced = Compressed_row_matrix();
    reduced.number_of_rows = reduced.number_of_columns = m;
    reduced.row_start.assign(std::size_t(m) + 1, 0);
    Compressed_row_matrix& coupling = state.coupling;
    coupling = Compressed_row_matrix();
    coupling.number_of_rows = m;
    coupling.number_of_columns = Index(state.eliminated_index.size());
    coupling.row_start.assign(std::size_t(m) + 1, 0);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        const Index r = reduced_index[inner[k]];
        if(r < 0 || (value[k] == 0. && inner[k] != j))
          continue;
        if(reduced_index[j] >= 0)
          ++reduced.row_start[r + 1];
        else
          ++coupling.row_start[r + 1];
      }
    for(Index r = 0; r < m; ++r)
    {
      reduced.row_start[r + 1] += reduced.row_start[r];
      coupling.row_start[r + 1] += coupling.row_start[r];
    }
    reduced.column.resize(reduced.row_start.back());
    reduced.value.resize(reduced.row_start.back());
    coupling.column.resize(coupling.row_start.back());
    coupling.value.resize(coupling.row_start.back());
    std::vector<Index> next_reduced(reduced.row_start.begin(), reduced.row_start.end() - 1);
    std::vector<Index> next_coupling(coupling.row_start.begin(), coupling.row_start.end() - 1);
    for(Index j = 0; j < n; ++j)
      for(Index k = outer[j]; k < outer[j + 1]; ++k)
      {
        const Index r = reduced_index[inner[k]];
        if(r < 0 || (value[k] == 0. && inner[k] != j))
          continue;
        const double signed_value = state.row_sign[r] * value[k];
        if(reduced_index[j] >= 0)
        {
          const Index p = next_reduced[r]++;
          reduced.column[p] = reduced_index[j];
          reduced.value[p] = signed_value;
        }
        else
        {
          const Index p = next_coupling[r]++;
          coupling.column[p] = eliminated_ordinal[j];
          coupling.value[p] = signed_value;
        }
      }
    return true;
  }

  bool setup(const Eigen_matrix& E, State& state) const
  {
    Statistics& statistics = state.statistics;
    statistics.level_sizes.clear();
    statistics.level_nonzeros.clear();
    statistics.operator_complexity = statistics.grid_complexity = 0.;
    statistics.hierarchy_bytes = 0;
    state.ldlt.reset();
    state.lu.reset();
    state.hierarchy = internal::AMG::Ruge_stueben_hierarchy();
    state.direct_matrix.clear_and_release();
    state.original_size = std::size_t(E.rows());

    if(E.rows() != E.cols() || E.nonZeros() >= INT_MAX)
      return false;
    Compressed_row_matrix reduced;
    if(!eliminate_diagonal_rows(E, state, reduced))
      return false;

    statistics.number_of_unknowns = std::size_t(reduced.number_of_rows);
    statistics.number_of_eliminated_rows = state.eliminated_index.size();
    state.symmetric = internal::AMG::is_numerically_symmetric(reduced, m_parameters.symmetry_tolerance);
    statistics.symmetric = state.symmetric;
    state.direct = std::size_t(reduced.number_of_rows)
                 < (state.symmetric ? m_parameters.direct_solver_threshold
                                    : m_parameters.direct_solver_threshold_non_symmetric);
    statistics.direct_solver = state.direct;
    state.krylov_method = m_parameters.krylov_method;
    if(state.krylov_method == Krylov_method::AUTOMATIC)
      state.krylov_method = state.symmetric ? Krylov_method::CONJUGATE_GRADIENT : Krylov_method::GMRES;
    statistics.krylov_method = state.direct ? Krylov_method::AUTOMATIC : state.krylov_method;

    if(reduced.number_of_rows == 0)
    {
      state.direct = true;
      state.direct_matrix = std::move(reduced);
      return true;
    }

    if(state.direct)
    {
      state.direct_matrix = std::move(reduced);
      const Compressed_row_matrix& R = state.direct_matrix;
      Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> map(
        R.number_of_rows, R.number_of_columns, Index(R.number_of_nonzeros()),
        R.row_start.data(), R.column.data(), R.value.data());
      const Eigen_matrix matrix = map;
      statistics.level_sizes.push_back(std::size_t(R.number_of_rows));
      statistics.level_nonzeros.push_back(R.number_of_nonzeros());
      statistics.operator_complexity = statistics.grid_complexity = 1.;
      if(state.symmetric)
      {
        state.ldlt.reset(new Eigen::SimplicialLDLT<Eigen_matrix>(matrix));
        return state.ldlt->info() == Eigen::Success;
      }
      state.lu.reset(new Eigen::SparseLU<Eigen_matrix>(matrix));
      return state.lu->info() == Eigen::Success;
    }

    internal::AMG::Hierarchy_parameters hierarchy_parameters;
    hierarchy_parameters.strength_threshold = m_parameters.strength_threshold;
    hierarchy_parameters.max_coarse_size = m_parameters.max_coarse_size;
    hierarchy_parameters.max_levels = m_parameters.max_levels;
    hierarchy_parameters.pre_smoothing_sweeps = m_parameters.pre_smoothing_sweeps;
    hierarchy_parameters.post_smoothing_sweeps = m_parameters.post_smoothing_sweeps;
    const bool built = state.hierarchy.build(std::move(reduced), hierarchy_parameters);

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
    const Clock::time_point start = Clock::now();
    statistics.iterations = 0;
    statistics.relative_residual = 0.;
    ++statistics.number_of_solves;
    const bool solved = solve_reduced(B, X, state);
    statistics.solve_seconds = seconds_since(start);
    return solved;
  }

  bool solve_reduced(const Vector& B, Vector& X, State& state) const
  {
    Statistics& statistics = state.statistics;
    statistics.relative_residual = std::numeric_limits<double>::infinity();
    if(!state.has_setup || !state.setup_succeeded || std::size_t(B.size()) != state.original_size)
      return false;
    const Index n = Index(state.original_size);
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
    const Compressed_row_matrix& A = state.reduced_matrix();
    const Index m = A.number_of_rows;
    if(state.identity_reduction && static_cast<const void*>(&B) != static_cast<const void*>(&X))
    {
      X.setZero();
      return state.direct ? solve_direct(state, B.data(), X.data(), target, right_hand_side_norm)
                          : solve_multigrid(state, B.data(), X.data(), target, right_hand_side_norm);
    }

    // Known values of the eliminated rows, then the reduced right-hand side.
    state.known_values.resize(state.eliminated_index.size());
    for(std::size_t e = 0; e < state.eliminated_index.size(); ++e)
      state.known_values[e] = B[state.eliminated_index[e]] / state.eliminated_diagonal[e];
    state.reduced_right_hand_side.resize(m);
    state.reduced_solution.assign(m, 0.);
    for(Index r = 0; r < m; ++r)
    {
      double value = state.row_sign[r] * B[state.original_index[r]];
      for(Index k = state.coupling.row_start[r]; k < state.coupling.row_start[r + 1]; ++k)
        value -= state.coupling.value[k] * state.known_values[state.coupling.column[k]];
      state.reduced_right_hand_side[r] = value;
    }

    const double* b = state.reduced_right_hand_side.data();
    double* x = state.reduced_solution.data();
    bool converged = true;
    if(m > 0)
      converged = state.direct ? solve_direct(state, b, x, target, right_hand_side_norm)
                               : solve_multigrid(state, b, x, target, right_hand_side_norm);
    else
      state.statistics.relative_residual = 0.;

    for(std::size_t e = 0; e < state.eliminated_index.size(); ++e)
      X[state.eliminated_index[e]] = state.known_values[e];
    for(Index r = 0; r < m; ++r)
      X[state.original_index[r]] = x[r];
    return converged;
  }

  bool solve_multigrid(State& state, const double* b, double* x, double target, double reference_norm) const
  {
    auto preconditioner = [&state](const double* r, double* z) { state.hierarchy.apply_v_cycle(r, z); };
    const Compressed_row_matrix& A = state.hierarchy.fine_matrix();
    internal::AMG::Krylov_result result;
    switch(state.krylov_method)
    {
      case Krylov_method::CONJUGATE_GRADIENT:
        result = internal::AMG::conjugate_gradient(A, b, x, preconditioner, target, reference_norm,
                                                   m_parameters.max_iterations, state.workspace);
        break;
      case Krylov_method::BICGSTAB:
        result = internal::AMG::bicgstab(A, b, x, preconditioner, target, reference_norm,
                                         m_parameters.max_iterations, state.workspace);
        break;
      default:
        result = internal::AMG::gmres(A, b, x, preconditioner, target, reference_norm,
                                      m_parameters.max_iterations, m_parameters.gmres_restart, state.workspace);
        break;
    }
    state.statistics.iterations = result.iterations;
    state.statistics.relative_residual = result.relative_residual;
    return result.converged;
  }

  // Direct solve plus up to two steps of iterative refinement, so that the same tolerance holds on both paths.
  bool solve_direct(State& state, const double* b_data, double* x_data, double target,
                    double reference_norm) const
  {
    const Compressed_row_matrix& A = state.direct_matrix;
    const Index m = A.number_of_rows;
    Eigen::Map<const Eigen::VectorXd> b(b_data, m);
    Eigen::Map<Eigen::VectorXd> x(x_data, m);
    state.correction.resize(m);
    Eigen::Map<Eigen::VectorXd> residual(state.correction.data(), m);
    auto direct_solve = [&state](const auto& rhs) -> Eigen::VectorXd {
      return state.ldlt ? Eigen::VectorXd(state.ldlt->solve(rhs)) : Eigen::VectorXd(state.lu->solve(rhs));
    };
    x = direct_solve(b);
    for(int step = 0;; ++step)
    {
      internal::AMG::residual(A, x.data(), b.data(), residual.data());
      const double residual_norm = residual.norm();
      state.statistics.relative_residual = residual_norm / reference_norm;
      if(!std::isfinite(residual_norm))
        return false;
      if(residual_norm <= target)
        return true;
      if(step == 2)
        return false;
      x += direct_solve(residual);
      ++state.statistics.iterations;
    }
  }

  Parameters m_parameters;
  std::shared_ptr<State> m_state;
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_AMG_SOLVER_TRAITS_H
