// The package's entry point: a bijective map of a closed genus-0 triangle mesh onto the unit sphere.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>
#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/Result.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/disk_embedding.h>
#include <CGAL/Spherical_parameterization/internal/global_newton.h>
#include <CGAL/Spherical_parameterization/internal/inscribability.h>
#include <CGAL/Spherical_parameterization/internal/mesh_coarsening.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/sphere_orientation.h>
#include <CGAL/Spherical_parameterization/internal/two_disk_partition.h>
#include <CGAL/Spherical_parameterization/parameters.h>

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>
#include <CGAL/use.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_invoke.h>
#endif

#include <Eigen/SparseLU>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The linear solver of the disk stage when none is given: the package's Ruge-Stueben AMG traits, which drop
/// CGAL SMP's identity border rows, and hand small systems to a direct solver.
using Default_disk_solver_traits = AMG_solver_traits;

/// \ingroup PkgSphericalParameterizationRef
/// Eigen's sparse LU on CGAL SMP's full (non-symmetric) system: the reference the AMG is measured against.
using Sparse_LU_disk_solver_traits =
    CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;

namespace internal {

// CGAL's METIS functions take `METIS_options(&options)` (a pointer to the array); the array itself works too.
inline const idx_t* metis_options_pointer(const idx_t* options) { return options; }
inline const idx_t* metis_options_pointer(const idx_t (*options)[METIS_NOPTIONS]) { return options ? *options : nullptr; }

struct Pipeline_options {
  Weighting weighting = Weighting::UNIFORM;
  bool admissible_weights = false;  // the weights were made symmetric and positive
  Nonlinear_solver nonlinear_solver = Nonlinear_solver::GLOBAL_NEWTON;
  int metis_seed = 0;
  const idx_t* metis_options = nullptr;  // METIS_NOPTIONS values, or nullptr for METIS' defaults and metis_seed
  bool verbose = false;
  bool parallel = false;  // CGAL::Parallel_tag with TBB
  bool multilevel = true;  // the multilevel start where it applies (multilevel_applies)
  // A coarser level of the multilevel start: only Newton's full steps are tried. When they fail, the finer level
  // starts from its own two disks, so the fallbacks of stages 2 and 3 would be spent on a mere start (measured on
  // Loop subdivisions of CGAL's man and bull: 35 s and 17 s lost on a coarse level that did not converge).
  bool coarse_level = false;
  Iteration_options iterations;   // its max_seconds counts from `call_clock`'s start
  Stopwatch call_clock;           // started when the user's call began (input checks and stage 1 count too)
  // Stage-level progress (the user's callback and the verbose printing); false cancels.
  std::function<bool(const Progress&)> report;
};

// A solver that shares no state with `solver`, for a disk embedded on another thread (copies of the solver
// traits share their factorization, as CGAL's Eigen_solver_traits do).
template <typename SolverTraits>
SolverTraits independent_solver(const SolverTraits&) { return SolverTraits(); }
inline AMG_solver_traits independent_solver(const AMG_solver_traits& solver) { return AMG_solver_traits(solver.parameters()); }

// Stage 1 for one weighting: two disks, Moebius inversion and inverse stereographic projection. With `parallel`
// (CGAL::Parallel_tag and TBB) the two disks are embedded at the same time; the result is the same.
template <typename SolverTraits>
bool initial_sphere(const Mesh_arrays& mesh, const Sphere_system& system, const Two_disk_partition& partition,
                    Weighting weighting, const SolverTraits& solver, std::vector<Vector3>& x, bool parallel = false)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<double> u_a(n, 0.), v_a(n, 0.), u_b(n, 0.), v_b(n, 0.);
  std::vector<char> side(n, 0);  // 1: disk A, 2: disk B (the loop counts as A)
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
    for(int g : system.triangles[f])
      if(partition.face_in_disk_a[f]) side[static_cast<std::size_t>(g)] = 1;
      else if(side[static_cast<std::size_t>(g)] == 0) side[static_cast<std::size_t>(g)] = 2;
  bool embedded_a = false, embedded_b = false;
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel) {
    const SolverTraits solver_a = independent_solver(solver), solver_b = independent_solver(solver);
    tbb::parallel_invoke([&] { embedded_a = embed_one_disk(mesh, system, partition, 1, weighting, solver_a, u_a, v_a); },
                         [&] { embedded_b = embed_one_disk(mesh, system, partition, 0, weighting, solver_b, u_b, v_b); });
  } else
#endif
  {
    CGAL_USE(parallel);
    embedded_a = embed_one_disk(mesh, system, partition, 1, weighting, solver, u_a, v_a);
    embedded_b = embedded_a && embed_one_disk(mesh, system, partition, 0, weighting, solver, u_b, v_b);
  }
  if(!embedded_a || !embedded_b) return false;
  x.resize(n);
  for(std::size_t i = 0; i < n; ++i)
    x[i] = side[i] == 2 ? inverse_stereographic(u_b[i], v_b[i], true) : inverse_stereographic(u_a[i], v_a[i], false);
  return true;
}

template <typename SolverTraits>
Result run_pipeline(const Mesh_arrays& mesh, Sphere_system& system, const Pipeline_options& options,
                    const SolverTraits& solver, std::vector<Vector3>& x);

// The multilevel start: the mesh collapsed to about `multilevel_coarsening_ratio` of its vertices, that mesh
// solved by the whole pipeline (itself multilevel while it is large enough), its map carried back (prolong()),
// smoothed by a few Gauss-Seidel sweeps (the vertices carried back sit where their ring was positive, not where
// they balance), then Newton's full steps on this mesh, the boosts solved as outer unknowns (Boost_aim::ROOT).
// From the two-disk guess the number of Newton steps grows with the mesh (armadillo: 7, its Loop subdivisions: 14
// to 25); from the level below it is 3 to 6 on the meshes measured (real meshes of 24k to 164k vertices, armadillo
// Loop x2 and x3), where the boosts balanced only upwards and taken from Newton's step took 4 to 27.
// Ratio and sweeps: of 1/2, 1/4, 1/8 and 3, 10 sweeps, 1/4 with 10 sweeps was the most even on bunny00 and
// armadillo Loop x2 (1/2 took 52 steps on bunny00 once); 30 or 60 sweeps did not lower the steps.
// Returns true when this mesh's map converged (or the time or a cancel stopped it); otherwise `x` is unspecified
// and the caller starts again with the paper's stage 1.
constexpr std::size_t multilevel_min_vertices = 20000;
constexpr double multilevel_coarsening_ratio = 0.25;
constexpr std::size_t multilevel_smoothing_sweeps = 10;

inline bool multilevel_applies(const Sphere_system& system, const Pipeline_options& options)
{
  return options.multilevel && options.weighting == Weighting::UNIFORM && system.symmetric &&
         options.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON && system.number_of_vertices >= multilevel_min_vertices &&
         options.iterations.max_newton_sweeps > 0;
}

template <typename SolverTraits>
bool multilevel_solve(const Mesh_arrays& mesh, const Sphere_system& system, const Pipeline_options& options,
                      const SolverTraits& solver, std::vector<Vector3>& x, Result& result, Iteration_report& newton,
                      double& newton_seconds, bool& cancelled)
{
  Stopwatch clock;
  const std::size_t n = system.number_of_vertices;
  Coarsening coarsening = coarsen_mesh(mesh, static_cast<std::size_t>(multilevel_coarsening_ratio * static_cast<double>(n)));
  Sphere_system coarse_system = make_connectivity(coarsening.coarse);
  std::string message;
  if(assign_weights(coarse_system, coarsening.coarse, Weighting::UNIFORM, {}, message) != Error_code::OK) return false;
  const double coarsening_seconds = clock.seconds();
  std::vector<Vector3> coarse_x;
  Pipeline_options coarse_options = options;
  coarse_options.coarse_level = true;
  const Result coarse = run_pipeline(coarsening.coarse, coarse_system, coarse_options, solver, coarse_x);
  if(coarse.status == Error_code::CANCELLED && coarse_x.size() == coarse_system.number_of_vertices) {
    // Stopped on a coarser level: its map, carried back, is the best map there is for this one.
    prolong(coarsening, coarse_x, x);
    cancelled = true;
    result.levels = coarse.levels;
    return true;
  }
  if(coarse.status != Error_code::OK) {
    if(options.verbose) std::cerr << "multilevel: the level of " << coarse_system.number_of_vertices << " vertices ended "
                                  << get_error_message(coarse.status) << "; the two-disk guess on " << n << " vertices follows\n";
    return false;
  }
  clock = Stopwatch();
  const std::size_t folded = prolong(coarsening, coarse_x, x);
  const std::size_t rounds = coarsening.rounds;
  coarsening = Coarsening();
  Iteration_options iteration_options = options.iterations;
  if(iteration_options.max_seconds >= 0.)
    iteration_options.max_seconds = std::max(0., iteration_options.max_seconds - options.call_clock.seconds());
  Sphere_state state(system, x);
  result.initial_flipped_faces = state.invalid_faces();
  Stopwatch iterations_clock;
  Iteration_options smoothing = iteration_options;
  smoothing.max_gauss_seidel_sweeps = multilevel_smoothing_sweeps;
  const Iteration_report smoothed = projected_gauss_seidel(state, smoothing, iterations_clock);
  result.gauss_seidel.iterations = smoothed.sweeps;
  result.gauss_seidel.residual = smoothed.residual;
  result.gauss_seidel.seconds = iterations_clock.seconds();
  result.initial_guess.residual = smoothed.residual;
  // The map carried back is close to the solution: the boost equations are solved as equations (Boost_aim).
  newton = full_newton_steps(state, iteration_options, iterations_clock, Boost_aim::ROOT);
  cancelled = cancelled || newton.cancelled;
  newton_seconds = iterations_clock.seconds();
  result.levels = coarse.levels;
  if(result.levels.empty()) {
    Level_statistics coarsest;
    coarsest.vertices = coarse.number_of_vertices;
    coarsest.newton_steps = coarse.newton.iterations;
    coarsest.linear_iterations = coarse.newton.linear_iterations;
    coarsest.seconds = coarse.total_seconds;
    result.levels.push_back(coarsest);
  }
  Level_statistics level;
  level.vertices = n;
  level.newton_steps = newton.sweeps;
  level.linear_iterations = newton.linear_iterations;
  level.seconds = coarsening_seconds + clock.seconds();
  result.levels.push_back(level);
  if(options.verbose)
    std::cerr << "multilevel: " << n << " vertices from " << coarse.number_of_vertices << " (" << rounds
              << " rounds of collapses, " << coarsening_seconds << " s; " << folded << " vertices inserted folded): "
              << newton.sweeps << " Newton steps, " << newton.linear_iterations << " MINRES iterations, max imbalance "
              << summarize_imbalance(system, x, options.iterations.tolerance).max << ", " << clock.seconds() << " s\n";
  return newton.converged || newton.cancelled || newton.out_of_time;
}

template <typename SolverTraits>
Result run_pipeline(const Mesh_arrays& mesh, Sphere_system& system, const Pipeline_options& options,
                    const SolverTraits& solver, std::vector<Vector3>& x)
{
  Result result;
  Stopwatch total;
  result.number_of_vertices = system.number_of_vertices;
  result.number_of_faces = system.triangles.size();

  Iteration_options iteration_options = options.iterations;
  bool cancelled = false;
  bool no_balanced_solution = false;
  Inscribability_check inscribability;
  Iteration_report newton;
  Stopwatch stage;
  double multilevel_newton_seconds = 0.;
  const bool multilevel_done = multilevel_applies(system, options) &&
                               multilevel_solve(mesh, system, options, solver, x, result, newton, multilevel_newton_seconds, cancelled);
  if(multilevel_done) {
    // Stage 1 is everything before this mesh's smoothing and Newton steps (the coarser levels, solved, and the map
    // carried back); stage 2 the smoothing.
    result.newton.seconds = multilevel_newton_seconds - result.gauss_seidel.seconds;
    result.initial_guess.seconds = total.seconds() - multilevel_newton_seconds;
    result.newton.iterations = newton.sweeps;
    result.newton.linear_iterations = newton.linear_iterations;
    result.newton.residual = newton.residual;
  } else {
    result.levels.clear();
    // Stage 1.
    stage = Stopwatch();
    const Two_disk_partition partition = split_into_two_disks(system, options.metis_seed, options.metis_options);
    if(!partition.valid) {
      result.status = Error_code::PARTITION_FAILED;
      result.message = get_error_message(result.status);
      return result;
    }
    result.separator_size = partition.separator_size;
    result.cut_loop_length = partition.loop.size();
    bool embedded = initial_sphere(mesh, system, partition, options.weighting, solver, x, options.parallel);
    if(!embedded) {
      // An iterative solver can give up where a direct one does not: try Eigen's sparse LU before failing.
      embedded = initial_sphere(mesh, system, partition, options.weighting, Sparse_LU_disk_solver_traits(), x, options.parallel);
      if(options.verbose && embedded) std::cerr << "stage 1: the disk solver failed; Eigen's sparse LU was used\n";
    }
    Sphere_certificate start = embedded ? certify(system.triangles, x) : Sphere_certificate();
    if(options.weighting != Weighting::UNIFORM && (!embedded || start.flipped_faces > 0)) {
      // Weights that may be negative or non-symmetric can fold the disks: Tutte's disks cannot.
      std::vector<Vector3> uniform_start;
      if(initial_sphere(mesh, system, partition, Weighting::UNIFORM, solver, uniform_start, options.parallel)) {
        const Sphere_certificate uniform_certificate = certify(system.triangles, uniform_start);
        if(!embedded || uniform_certificate.flipped_faces < start.flipped_faces) {
          x.swap(uniform_start);
          start = uniform_certificate;
          embedded = true;
          result.uniform_initial_guess_fallback = true;
        }
      }
    }
    if(!embedded) {
      result.status = Error_code::DISK_EMBEDDING_FAILED;
      result.message = get_error_message(result.status);
      return result;
    }
    result.initial_flipped_faces = start.flipped_faces;
    result.initial_guess.iterations = 2;
    result.initial_guess.residual = compute_residuals(system, x).paper;
    const double initial_imbalance = summarize_imbalance(system, x, options.iterations.tolerance).max;
    result.initial_guess.seconds = stage.seconds();
    if(options.verbose)
      std::cerr << "stage 1: separator " << result.separator_size << " vertices, loop " << result.cut_loop_length
                << " vertices, Res " << result.initial_guess.residual << ", non-positive faces " << start.flipped_faces
                << ", max imbalance " << initial_imbalance << ", " << result.initial_guess.seconds << " s\n";
    if(options.report) {
      Progress progress;
      progress.stage = "initial guess";
      progress.residual = result.initial_guess.residual;
      progress.max_imbalance = initial_imbalance;
      progress.non_positive_faces = start.flipped_faces;
      progress.seconds = total.seconds();
      cancelled = !options.report(progress);
    }

    // A non-inscribable connectivity has no bijective balanced solution for positive weights: iterating cannot
    // succeed, so the initial guess (bijective by construction in all but rare cases) is the answer; a few
    // bijectivity-preserving iterations only serve to repair it if some of its triangles are not positive.
    bool positive_weights = true;
    for(double w : system.weights) positive_weights = positive_weights && w > 0.;
    inscribability = check_inscribability(system);
    no_balanced_solution = positive_weights && inscribability.proven_not_inscribable;
    // Non-symmetric weights (mean value) have no exact solution in general: the imbalance cannot reach the tolerance.
    // Until the stationarity test of their least-squares problem exists, they stop on the paper's Res, and say so.
    if(!system.symmetric) iteration_options.convergence_test = Convergence_test::PAPER_RESIDUAL;
    if(no_balanced_solution) {
      iteration_options.max_gauss_seidel_sweeps = start.flipped_faces == 0 ? 0 : std::min<std::size_t>(iteration_options.max_gauss_seidel_sweeps, 100);
      iteration_options.max_newton_sweeps = start.flipped_faces == 0 ? 0 : std::min<std::size_t>(iteration_options.max_newton_sweeps, 100);
      iteration_options.tolerance = 0.;  // stop at the caps; no residual is the goal here
    }

    // Stages 2 and 3, with what is left of the time budget: it bounds the whole call, and stage 1 (which every
    // returned map needs) runs to its end even when it alone takes longer.
    if(iteration_options.max_seconds >= 0.)
      iteration_options.max_seconds = std::max(0., iteration_options.max_seconds - options.call_clock.seconds());
    const std::vector<Vector3> initial_guess = x;
    Sphere_state state(system, x);
    Stopwatch iterations_clock;
    // The default solver first tries Newton's full steps (through folds, keeping degree 1) from the initial guess:
    // where they converge (most meshes, in 4 to 20 steps) stage 2 is not needed. Otherwise the paper's order
    // follows from the initial guess again: stage 2, then stage 3 (which tries the same steps from stage 2's result
    // before the bijectivity-preserving ones).
    Iteration_report direct_newton;
    Stopwatch direct_clock;
    const bool try_direct_newton = !cancelled && !no_balanced_solution && system.symmetric &&
                                   options.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON && iteration_options.max_newton_sweeps > 0;
    if(try_direct_newton) {
      // Measured on the 66 meshes: 8 need the second attempt (on the imbalances), all small.
      direct_newton = full_newton_steps(state, iteration_options, iterations_clock);
      if(options.coarse_level && !direct_newton.converged) {
        iteration_options.max_gauss_seidel_sweeps = 0;
        iteration_options.max_newton_sweeps = 0;
      }
      cancelled = direct_newton.cancelled;
      if(!direct_newton.converged && !cancelled && !direct_newton.out_of_time) state.assign(initial_guess);
      if(iteration_options.max_newton_sweeps > direct_newton.sweeps) iteration_options.max_newton_sweeps -= direct_newton.sweeps;
      else iteration_options.max_newton_sweeps = 0;
    }
    const double direct_seconds = direct_clock.seconds();
    const bool direct_done = direct_newton.converged || direct_newton.out_of_time;

    stage = Stopwatch();
    Iteration_report gauss_seidel;
    if(!cancelled && !direct_done) gauss_seidel = projected_gauss_seidel(state, iteration_options, iterations_clock);
    else gauss_seidel.residual = direct_newton.converged ? direct_newton.residual : result.initial_guess.residual;
    cancelled = cancelled || gauss_seidel.cancelled;
    result.gauss_seidel.iterations = gauss_seidel.sweeps;
    result.gauss_seidel.residual = gauss_seidel.residual;
    result.gauss_seidel.seconds = stage.seconds();
    if(options.verbose)
      std::cerr << "stage 2: " << gauss_seidel.sweeps << " sweeps, Res " << gauss_seidel.residual << ", non-positive faces "
                << state.invalid_faces() << ", " << result.gauss_seidel.seconds << " s\n";

    stage = Stopwatch();
    if(!direct_done && !gauss_seidel.converged && !gauss_seidel.out_of_time && !cancelled && iteration_options.max_newton_sweeps > 0)
      newton = options.nonlinear_solver == Nonlinear_solver::LOCAL_NEWTON
                   ? local_newton(state, iteration_options, iterations_clock)
                   : global_newton(state, iteration_options, iterations_clock, &initial_guess);
    else newton.residual = gauss_seidel.residual;
    cancelled = cancelled || newton.cancelled;
    result.newton.iterations = newton.sweeps + direct_newton.sweeps;
    result.newton.linear_iterations = newton.linear_iterations + direct_newton.linear_iterations;
    result.newton.residual = direct_done ? direct_newton.residual : newton.residual;
    result.newton.seconds = stage.seconds() + direct_seconds;
    result.rejected_moves = gauss_seidel.rejected_moves + newton.rejected_moves;
    result.continuation_parameter = newton.continuation_parameter;
    if(options.verbose)
      std::cerr << "stage 3: " << newton.sweeps << " sweeps, Res " << newton.residual << ", non-positive faces "
                << state.invalid_faces() << ", " << result.newton.seconds << " s\n";
  }

  // Certificate and figures, recomputed from scratch on the final positions.
  const Residuals residuals = compute_residuals(system, x);
  const Sphere_certificate certificate = certify(system.triangles, x);
  result.residual = residuals.paper;
  result.max_tangential_residual = residuals.max_tangential;
  result.flipped_faces = certificate.flipped_faces;
  result.total_signed_area = certificate.total_signed_area;
  result.bijective = certificate.bijective;
  std::vector<double> imbalances;
  const Imbalance_summary imbalance = summarize_imbalance(system, x, options.iterations.tolerance, &imbalances);
  result.max_imbalance = imbalance.max;
  result.imbalance_percentile_99 = imbalance.percentile_99;
  result.vertices_at_rounding_floor = imbalance.vertices_at_rounding_floor;
  result.unbalanced_vertices = imbalance.unbalanced_vertices;
  result.convergence_test = iteration_options.convergence_test;
  const bool converged = iteration_options.convergence_test == Convergence_test::PAPER_RESIDUAL
                             ? result.residual < options.iterations.tolerance
                             : imbalance.balanced();
  result.status = !converged ? Error_code::NOT_CONVERGED : (certificate.bijective ? Error_code::OK : Error_code::NOT_BIJECTIVE);
  if(cancelled) result.status = Error_code::CANCELLED;
  if(no_balanced_solution) result.status = Error_code::NO_BALANCED_SOLUTION;
  result.message = get_error_message(result.status);
  if(iteration_options.convergence_test != options.iterations.convergence_test)
    result.message += " [non-symmetric weights: stopped on the paper's Res, their imbalance cannot reach the tolerance]";
  if(no_balanced_solution) {
    std::ostringstream details;
    details << " (proof: " << inscribability.independent_set_size << " of the " << system.number_of_vertices
            << " vertices are pairwise non-adjacent" << (2 * inscribability.independent_set_size == system.number_of_vertices
                                                             ? " and two of the others are adjacent" : "")
            << "). The map returned is the initial guess (two Tutte disks, "
            << "Moebius inversion, stereographic projection)" << (certificate.bijective ? ", certified bijective" : ", NOT bijective: "
            + std::to_string(certificate.flipped_faces) + " flipped faces") << ", not a balanced one";
    result.message += details.str();
  } else if(result.status != Error_code::OK) {
    std::ostringstream details;
    details << " (max imbalance " << result.max_imbalance << ", " << result.unbalanced_vertices
            << " vertices above the tolerance, Res " << result.residual << ", " << result.flipped_faces << " flipped faces";
    if(result.continuation_parameter >= 0. && result.continuation_parameter < 1.)
      details << "; the balanced maps from Tutte's weights towards these could be followed only "
              << static_cast<int>(100. * result.continuation_parameter) << "% of the way";
    if(!system.symmetric)
      details << "; with non-symmetric weights the balance equations generally have no exact solution";
    else if(newton.stagnated)
      details << "; the residual stagnated";
    if(!options.admissible_weights && (!system.symmetric || result.continuation_parameter >= 0.))
      details << "; the admissible_weights named parameter may help";
    details << ")";
    result.message += details.str();
  }
  result.total_seconds = total.seconds();
  return result;
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Maps the closed, connected, genus-0 triangle mesh `tm` onto the unit sphere with the method of Saba, Yavneh,
/// Gotsman and Sheffer: an initial guess from two planar disks (METIS separator, CGAL's fixed-border
/// parameterizers, Moebius inversion, inverse stereographic projection), projected Gauss-Seidel while the
/// residual decreases, then Newton steps (by default on all vertices at once; the paper's local Newton on request)
/// until every vertex is balanced in its own scale (`Convergence_test::IMBALANCE`). The output is
/// certified: every spherical triangle is positively oriented under an exact predicate and the areas add up to
/// 4 pi (`Result::bijective`); only then is the status `Error_code::OK`.
///
/// The mesh is never modified. On an input error nothing is written to `vsm`; otherwise `vsm` receives the
/// final (best) iterate, also when the status is `NOT_CONVERGED` or `NOT_BIJECTIVE`.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB: the two disks of stage 1 are
///         embedded at the same time) or `CGAL::Parallel_if_available_tag`. The result does not depend on it.
/// \tparam TriangleMesh a model of `FaceListGraph`.
/// \tparam VertexSphereMap a model of `WritablePropertyMap` from vertices to a `Point_3` constructible from three doubles.
/// \tparam NamedParameters a sequence of named parameters (the package's own, from
///         `CGAL::Spherical_parameterization::parameters`, and CGAL's, joined by `parameters::combine()`).
///
/// \param tm the mesh, only read.
/// \param vsm receives the position of every vertex on the unit sphere.
/// \param np optional named parameters among the ones listed below.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} \cgalParamDescription{the points of the vertices}
///     \cgalParamType{a model of `ReadablePropertyMap` from vertices to points}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{its `Compute_x_3`, `Compute_y_3` and `Compute_z_3` read the
///     points (converted to `double` with `CGAL::to_double()`), so exact kernels are accepted}
///     \cgalParamType{a model of `Kernel`}
///     \cgalParamDefault{the kernel of the point type of `vertex_point_map`} \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map} \cgalParamDescription{indices `0..num_vertices(tm)-1` of the vertices}
///     \cgalParamType{a model of `ReadablePropertyMap` from vertices to an integer type}
///     \cgalParamDefault{an automatically indexed internal map} \cgalParamNEnd
///   \cgalParamNBegin{weighting} \cgalParamDescription{the weights `w_ij` of the balance equations}
///     \cgalParamType{`Weighting`}
///     \cgalParamDefault{`Weighting::UNIFORM`, or `Weighting::USER_MAP` when `halfedge_weight_map` is given} \cgalParamNEnd
///   \cgalParamNBegin{halfedge_weight_map} \cgalParamDescription{the weight of `source(h)` in the equation of
///     `target(h)`; the weights of a vertex must be finite with a positive sum}
///     \cgalParamType{a model of `ReadablePropertyMap` from halfedges to a type convertible to `double`}
///     \cgalParamDefault{none} \cgalParamNEnd
///   \cgalParamNBegin{admissible_weights} \cgalParamDescription{solve with the closest symmetric positive weights
///     (`w_ij`, `w_ji` replaced by their mean, weights below 1% of the local mean raised to it), for which the theory
///     guarantees a bijective solution on inscribable meshes; `Result::raised_weights` counts the edges raised}
///     \cgalParamType{`bool`} \cgalParamDefault{`false`} \cgalParamNEnd
///   \cgalParamNBegin{multilevel} \cgalParamDescription{on meshes of 20,000 vertices or more with uniform weights
///     and the global solver, start from a coarser mesh (half-edge collapses to a quarter of the vertices, recursively)
///     solved first, its map carried back, instead of the paper's two-disk guess on the mesh itself (which the
///     coarsest level uses, and which is the fallback); `Result::levels` reports the levels}
///     \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
///   \cgalParamNBegin{tolerance} \cgalParamDescription{stop when every vertex's imbalance `e_i` is at most this value
///     (or its rounding floor, where larger); with `Convergence_test::PAPER_RESIDUAL`, when `Res` is below it}
///     \cgalParamType{`double`} \cgalParamDefault{`1e-6`} \cgalParamNEnd
///   \cgalParamNBegin{convergence_test} \cgalParamDescription{the stopping test of the iterations}
///     \cgalParamType{`Convergence_test`} \cgalParamDefault{`Convergence_test::IMBALANCE`} \cgalParamNEnd
///   \cgalParamNBegin{max_gauss_seidel_sweeps} \cgalParamDescription{iteration cap of stage 2}
///     \cgalParamType{`std::size_t`} \cgalParamDefault{1000} \cgalParamNEnd
///   \cgalParamNBegin{max_newton_sweeps} \cgalParamDescription{iteration cap of stage 3}
///     \cgalParamType{`std::size_t`} \cgalParamDefault{200000} \cgalParamNEnd
///   \cgalParamNBegin{max_seconds} \cgalParamDescription{time budget of the whole call (input checks, stage 1, stages 2 and 3), in seconds; a negative value means none. Stage 1 always runs to its end (every returned map needs it); the iterations check the budget at every iteration and between the parts of a Newton step, so the call ends at most one such part past it (see the manual)}
///     \cgalParamType{`double`} \cgalParamDefault{unlimited} \cgalParamNEnd
///   \cgalParamNBegin{preserve_bijectivity} \cgalParamDescription{backtrack moves that would fold a triangle}
///     \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
///   \cgalParamNBegin{nonlinear_solver} \cgalParamDescription{the solver of stage 3}
///     \cgalParamType{`Nonlinear_solver`} \cgalParamDefault{`Nonlinear_solver::GLOBAL_NEWTON`} \cgalParamNEnd
///   \cgalParamNBegin{metis_seed} \cgalParamDescription{seed of METIS: the same seed gives bitwise identical output}
///     \cgalParamType{`int`} \cgalParamDefault{0} \cgalParamNEnd
///   \cgalParamNBegin{METIS_options} \cgalParamDescription{the `METIS_NOPTIONS` options of `METIS_ComputeVertexSeparator`
///     (CGAL's tag); overrides `metis_seed`}
///     \cgalParamType{`idx_t*`, or a pointer to an array of `METIS_NOPTIONS` `idx_t`}
///     \cgalParamDefault{METIS' defaults with `metis_seed`} \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver} \cgalParamDescription{the linear solver of the disk stage; if it fails,
///     Eigen's sparse LU is tried before `Error_code::DISK_EMBEDDING_FAILED`}
///     \cgalParamType{a model of `SphericalParameterizationDiskSolverTraits`}
///     \cgalParamDefault{`AMG_solver_traits` (`Default_disk_solver_traits`)} \cgalParamNEnd
///   \cgalParamNBegin{progress_callback} \cgalParamDescription{called after stage 1 and after every iteration;
///     returning `false` cancels (status `Error_code::CANCELLED`, the current iterate is written)}
///     \cgalParamType{a model of `SphericalParameterizationProgressCallback`}
///     \cgalParamDefault{none} \cgalParamNEnd
///   \cgalParamNBegin{verbose} \cgalParamDescription{print the figures of each stage to `std::cerr`, and the progress
///     at most once a second}
///     \cgalParamType{`bool`} \cgalParamDefault{`false`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \return a `Result` with the status, the residuals, the exact flip count and the figures of each stage.
///
/// \sa `check_input()`, `certify_sphere_map()`, `measure_spherical_distortion()`
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename TriangleMesh, typename VertexSphereMap,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Result spherical_parameterize(const TriangleMesh& tm, VertexSphereMap vsm,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
#ifndef CGAL_LINKED_WITH_TBB
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "spherical_parameterize: Parallel_tag is enabled but TBB is unavailable");
#endif
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;

  internal::Stopwatch clock;
  auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm));
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);

  // The geometric traits read the coordinates, so that any kernel's points (e.g. exact ones) are accepted.
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  const Geom_traits gt = choose_parameter<Geom_traits>(get_parameter(np, CGAL::internal_np::geom_traits));
  const auto compute_x = gt.compute_x_3_object();
  const auto compute_y = gt.compute_y_3_object();
  const auto compute_z = gt.compute_z_3_object();
  internal::Mesh_arrays mesh = internal::read_face_graph(tm, vpm, vim, [&](const auto& p, double& x, double& y, double& z) {
    x = CGAL::to_double(compute_x(p));
    y = CGAL::to_double(compute_y(p));
    z = CGAL::to_double(compute_z(p));
  });
  const Input_check check = internal::check_mesh_arrays(mesh);
  if(!check) {
    Result result;
    result.status = check.status;
    result.message = check.message;
    result.number_of_vertices = mesh.points.size();
    result.number_of_faces = mesh.polygons.size();
    return result;
  }
  internal::renumber_for_locality(mesh);

  constexpr bool has_user_weights = !is_default_parameter<NamedParameters, internal_np::halfedge_weight_map_t>::value;
  internal::Pipeline_options options;
  options.call_clock = clock;
  options.parallel = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
  options.weighting = choose_parameter(get_parameter(np, internal_np::weighting),
                                       has_user_weights ? Weighting::USER_MAP : Weighting::UNIFORM);
  options.nonlinear_solver = choose_parameter(get_parameter(np, internal_np::nonlinear_solver), Nonlinear_solver::GLOBAL_NEWTON);
  options.metis_seed = choose_parameter(get_parameter(np, internal_np::metis_seed), 0);
  options.metis_options = internal::metis_options_pointer(
      choose_parameter(get_parameter(np, CGAL::internal_np::METIS_options), static_cast<idx_t*>(nullptr)));
  options.verbose = choose_parameter(get_parameter(np, CGAL::internal_np::verbose), false);
  options.iterations.tolerance = choose_parameter(get_parameter(np, internal_np::tolerance), 1e-6);
  options.iterations.convergence_test = choose_parameter(get_parameter(np, internal_np::convergence_test), Convergence_test::IMBALANCE);
  options.iterations.max_gauss_seidel_sweeps =
      choose_parameter(get_parameter(np, internal_np::max_gauss_seidel_sweeps), default_max_gauss_seidel_sweeps);
  options.iterations.max_newton_sweeps = choose_parameter(get_parameter(np, internal_np::max_newton_sweeps), std::size_t(200000));
  options.iterations.max_seconds = choose_parameter(get_parameter(np, internal_np::max_seconds), -1.);
  options.iterations.preserve_bijectivity = choose_parameter(get_parameter(np, internal_np::preserve_bijectivity), true);
  options.multilevel = choose_parameter(get_parameter(np, internal_np::multilevel), true);
  // Progress: the user's callback sees every stage end and every iteration; verbose prints at most once a second.
  std::function<bool(const Progress&)> user_callback;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::progress_callback_t>::value)
    user_callback = get_parameter(np, internal_np::progress_callback);
  if(user_callback || options.verbose) {
    const bool verbose = options.verbose;
    auto last_print = std::make_shared<double>(-1.);
    options.report = [user_callback, verbose, last_print](const Progress& progress) {
      if(verbose && progress.iteration > 0 && progress.seconds - *last_print >= 1.) {
        *last_print = progress.seconds;
        std::cerr << "  " << progress.stage << " iteration " << progress.iteration << ": Res " << progress.residual
                  << ", non-positive faces " << progress.non_positive_faces << ", " << progress.seconds << " s\n";
      }
      return !user_callback || user_callback(progress);
    };
    auto last = std::make_shared<Progress>();
    options.iterations.progress = [report = options.report, clock, last](const char* stage, std::size_t sweep, double residual,
                                                                          std::size_t invalid) {
      last->stage = stage;
      last->iteration = sweep;
      last->residual = residual;
      last->non_positive_faces = invalid;
      last->seconds = clock.seconds();
      return report(*last);
    };
    // Inside an iteration that lasts (a Levenberg-Marquardt step with several factorizations, a Newton step on a
    // large mesh), the last report is repeated with the time updated, at most every half second, so that a
    // cancellation takes effect within about a second.
    auto last_poll = std::make_shared<double>(0.);
    options.iterations.keep_going = [report = options.report, clock, last, last_poll]() {
      const double now = clock.seconds();
      if(*last->stage == '\0' || now - *last_poll < 0.5) return true;
      *last_poll = now;
      last->seconds = now;
      return report(*last);
    };
  }

  internal::Sphere_system system = internal::make_connectivity(mesh);
  std::string weight_message;
  std::function<double(std::size_t, int)> user_weight;
  std::vector<std::pair<std::uint64_t, double>> user_table;
  if constexpr(has_user_weights) {
    auto weight_map = get_parameter(np, internal_np::halfedge_weight_map);
    for(auto h : halfedges(tm)) {
      if(is_border(h, tm)) continue;
      const std::uint64_t i = static_cast<std::uint64_t>(get(vim, target(h, tm)));
      const std::uint64_t j = static_cast<std::uint64_t>(get(vim, source(h, tm)));
      user_table.emplace_back(i << 32 | j, static_cast<double>(get(weight_map, h)));
    }
    std::sort(user_table.begin(), user_table.end());
    user_weight = [&user_table, &mesh](std::size_t i, int j) {
      const std::uint64_t key = static_cast<std::uint64_t>(internal::input_vertex_index(mesh, i)) << 32
                                | static_cast<std::uint64_t>(internal::input_vertex_index(mesh, static_cast<std::size_t>(j)));
      auto it = std::lower_bound(user_table.begin(), user_table.end(), key,
                                 [](const std::pair<std::uint64_t, double>& entry, std::uint64_t k) { return entry.first < k; });
      return it != user_table.end() && it->first == key ? it->second : 0.;
    };
  } else if(options.weighting == Weighting::USER_MAP) {
    Result result;
    result.status = Error_code::INVALID_WEIGHTS;
    result.message = std::string(get_error_message(result.status)) + ": Weighting::USER_MAP needs the halfedge_weight_map parameter";
    return result;
  }
  const Error_code weight_status = internal::assign_weights(system, mesh, options.weighting, user_weight, weight_message);
  if(weight_status != Error_code::OK) {
    Result result;
    result.status = weight_status;
    result.message = std::string(get_error_message(weight_status)) + ": " + weight_message;
    result.clamped_weights = system.clamped_weights;
    result.number_of_vertices = mesh.points.size();
    result.number_of_faces = mesh.polygons.size();
    return result;
  }
  const bool admissible = choose_parameter(get_parameter(np, internal_np::admissible_weights), false);
  const std::size_t raised_weights = admissible ? internal::make_weights_admissible(system) : 0;
  if(admissible) options.weighting = Weighting::USER_MAP;  // the disks use the same (admissible) weights
  options.admissible_weights = admissible;

  using Solver = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::sparse_linear_solver_t, NamedParameters,
                                                                    Default_disk_solver_traits>::type;
  const Solver solver = choose_parameter<Solver>(get_parameter(np, CGAL::internal_np::sparse_linear_solver));

  std::vector<internal::Vector3> x;
  Result result = internal::run_pipeline(mesh, system, options, solver, x);
  result.admissible_weights = admissible;
  result.raised_weights = raised_weights;
  result.clamped_weights = system.clamped_weights;
  if(system.clamped_weights > 0) {
    result.message += " [" + std::to_string(system.clamped_weights) + " weights of degenerate corners were clamped]";
    if(options.verbose) std::cerr << "weights: " << system.clamped_weights << " of degenerate corners clamped\n";
  }
  if(x.size() == mesh.points.size()) {
    using Point = typename boost::property_traits<VertexSphereMap>::value_type;
    std::vector<std::size_t> internal_index(x.size());
    for(std::size_t i = 0; i < x.size(); ++i) internal_index[internal::input_vertex_index(mesh, i)] = i;
    for(auto v : vertices(tm)) {
      const internal::Vector3& p = x[internal_index[static_cast<std::size_t>(get(vim, v))]];
      put(vsm, v, Point(p.x, p.y, p.z));
    }
  }
  result.total_seconds = clock.seconds();
  return result;
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H
