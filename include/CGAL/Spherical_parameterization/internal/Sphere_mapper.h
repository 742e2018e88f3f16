// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The pipeline behind spherical_parameterize(), as one class whose methods are its stages: the start (the
// multilevel start, or the paper's stage 1 from two disks), stages 2 and 3, then the certificate and the figures of
// the Result. spherical_parameterize.h is the front end (named parameters in, property map out).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_MAPPER_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_MAPPER_H

#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/Progress.h>
#include <CGAL/Spherical_parameterization/Result.h>
#include <CGAL/Spherical_parameterization/enum.h>
#include <CGAL/Spherical_parameterization/independent_copy.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>
#include <CGAL/Spherical_parameterization/internal/disk_embedding.h>
#include <CGAL/Spherical_parameterization/internal/inscribability.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/mesh_coarsening.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/stage3/global_newton.h>
#include <CGAL/Spherical_parameterization/internal/two_disk_partition.h>

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Eigen_sparse_matrix.h>
#include <CGAL/use.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/parallel_invoke.h>
#endif

#include <Eigen/SparseLU>

#include <algorithm>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// Eigen's sparse LU on CGAL SMP's full system: the disk solver's fallback (public as Sparse_LU_disk_solver_traits).
using Sparse_LU_solver_traits =
    CGAL::Eigen_solver_traits<Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;

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
  // starts from its own two disks, so the fallbacks of stages 2 and 3 would be spent on a mere start (the manual's
  // Method section has what that cost).
  bool coarse_level = false;
  Iteration_options iterations;   // its max_seconds counts from `call_clock`'s start
  CGAL::Real_timer call_clock;    // started when the user's call began (input checks and stage 1 count too)
  // Stage-level progress (the user's callback and the verbose printing); false cancels.
  std::function<bool(const Progress&)> report;
};

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
    // Unqualified: a user's overload in the solver's namespace is found too.
    const SolverTraits solver_a = independent_copy(solver), solver_b = independent_copy(solver);
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
class Sphere_mapper {
public:
  Sphere_mapper(const Mesh_arrays& mesh, Sphere_system& system, const Pipeline_options& options, const SolverTraits& solver)
    : mesh_(mesh), system_(system), options_(options), solver_(solver) {}

  // The whole map into x: a start, stages 2 and 3, the certificate and the figures.
  Result map(std::vector<Vector3>& x)
  {
    result_ = Result();
    total_ = CGAL::Real_timer();
    total_.start();
    result_.number_of_vertices = system_.number_of_vertices;
    result_.number_of_faces = system_.triangles.size();
    iteration_options_ = options_.iterations;
    if(multilevel_applies() && multilevel_start(x)) {
      // Stage 1 is everything before this mesh's smoothing and Newton steps (the coarser levels, solved, and the map
      // carried back); stage 2 the smoothing.
      result_.newton.seconds = multilevel_newton_seconds_ - result_.gauss_seidel.seconds;
      result_.initial_guess.seconds = total_.time() - multilevel_newton_seconds_;
      result_.newton.iterations = newton_.sweeps;
      result_.newton.linear_iterations = newton_.linear_iterations;
      result_.newton.residual = newton_.residual;
    } else {
      result_.levels.clear();
      if(!two_disk_start(x)) return result_;
      iterate(x);
    }
    certify_and_report(x);
    result_.total_seconds = total_.time();
    return result_;
  }

private:
  bool multilevel_applies() const
  {
    return options_.multilevel && options_.weighting == Weighting::UNIFORM && system_.symmetric &&
           options_.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON &&
           system_.number_of_vertices >= options_.iterations.tuning.multilevel_min_vertices &&
           options_.iterations.max_newton_sweeps > 0;
  }

  // The multilevel start: the mesh collapsed to about `Solver_tuning::multilevel_coarsening_ratio` of its vertices, that mesh
  // solved by the whole pipeline (itself multilevel while it is large enough), its map carried back (prolong()),
  // smoothed by a few Gauss-Seidel sweeps (the vertices carried back sit where their ring was positive, not where
  // they balance), then Newton's full steps on this mesh, the boosts solved as outer unknowns (Boost_aim::ROOT).
  // From the two-disk guess the number of Newton steps grows with the mesh; from the level below it stays a few
  // (the manual's Method and Performance sections have the counts).
  // Returns true when this mesh's map converged (or the time or a cancel stopped it); otherwise `x` is unspecified
  // and the caller starts again with the paper's stage 1.

  bool multilevel_start(std::vector<Vector3>& x)
  {
    CGAL::Real_timer clock;
    clock.start();
    const std::size_t n = system_.number_of_vertices;
    Coarsening coarsening = coarsen_mesh(mesh_.points, system_.triangles,
                                         static_cast<std::size_t>(options_.iterations.tuning.multilevel_coarsening_ratio * static_cast<double>(n)));
    Sphere_system coarse_system = make_connectivity(std::move(coarsening.coarse.triangles), coarsening.coarse.points.size());
    std::string message;
    if(assign_weights(coarse_system, coarsening.coarse, Weighting::UNIFORM, {}, message) != Error_code::OK) return false;
    const double coarsening_seconds = clock.time();
    std::vector<Vector3> coarse_x;
    Pipeline_options coarse_options = options_;
    coarse_options.coarse_level = true;
    const Result coarse = Sphere_mapper(coarsening.coarse, coarse_system, coarse_options, solver_).map(coarse_x);
    if(coarse.status == Error_code::CANCELLED && coarse_x.size() == coarse_system.number_of_vertices) {
      // Stopped on a coarser level: its map, carried back, is the best map there is for this one.
      prolong(coarsening, coarse_x, x);
      cancelled_ = true;
      result_.levels = coarse.levels;
      return true;
    }
    if(coarse.status != Error_code::OK) {
      if(options_.verbose) std::cerr << "multilevel: the level of " << coarse_system.number_of_vertices << " vertices ended "
                                    << get_error_message(coarse.status) << "; the two-disk guess on " << n << " vertices follows\n";
      return false;
    }
    clock.reset();
    const std::size_t folded = prolong(coarsening, coarse_x, x);
    const std::size_t rounds = coarsening.rounds;
    coarsening = Coarsening();
    Iteration_options level_options = options_.iterations;
    if(level_options.max_seconds >= 0.)
      level_options.max_seconds = std::max(0., level_options.max_seconds - options_.call_clock.time());
    Sphere_state state(system_, x);
    result_.initial_flipped_faces = state.invalid_faces();
    CGAL::Real_timer iterations_clock;
    iterations_clock.start();
    Iteration_options smoothing = level_options;
    smoothing.max_gauss_seidel_sweeps = options_.iterations.tuning.multilevel_smoothing_sweeps;
    const Iteration_report smoothed = projected_gauss_seidel(state, smoothing, iterations_clock);
    result_.gauss_seidel.iterations = smoothed.sweeps;
    result_.gauss_seidel.residual = smoothed.residual;
    result_.gauss_seidel.seconds = iterations_clock.time();
    result_.initial_guess.residual = smoothed.residual;
    // The map carried back is close to the solution: the boost equations are solved as equations (Boost_aim).
    newton_ = full_newton_steps(state, level_options, iterations_clock, Boost_aim::ROOT);
    cancelled_ = cancelled_ || newton_.cancelled;
    multilevel_newton_seconds_ = iterations_clock.time();
    result_.levels = coarse.levels;
    if(result_.levels.empty()) {
      Level_statistics coarsest;
      coarsest.vertices = coarse.number_of_vertices;
      coarsest.newton_steps = coarse.newton.iterations;
      coarsest.linear_iterations = coarse.newton.linear_iterations;
      coarsest.seconds = coarse.total_seconds;
      result_.levels.push_back(coarsest);
    }
    Level_statistics level;
    level.vertices = n;
    level.newton_steps = newton_.sweeps;
    level.linear_iterations = newton_.linear_iterations;
    level.seconds = coarsening_seconds + clock.time();
    result_.levels.push_back(level);
    if(options_.verbose)
      std::cerr << "multilevel: " << n << " vertices from " << coarse.number_of_vertices << " (" << rounds
                << " rounds of collapses, " << coarsening_seconds << " s; " << folded << " vertices inserted folded): "
                << newton_.sweeps << " Newton steps, " << newton_.linear_iterations << " MINRES iterations, max imbalance "
                << summarize_imbalance(system_, x, options_.iterations.tolerance).max << ", " << clock.time() << " s\n";
    return newton_.converged || newton_.cancelled || newton_.out_of_time;
  }

  // The paper's stage 1 (two disks, Moebius inversion, inverse stereographic projection) and the settings of the
  // iterations that follow from it; false when no initial guess could be made (result says why).
  bool two_disk_start(std::vector<Vector3>& x)
  {
    CGAL::Real_timer stage;
    stage.start();
    const Two_disk_partition partition = split_into_two_disks(system_, options_.metis_seed, options_.metis_options);
    if(!partition.valid) {
      result_.status = Error_code::PARTITION_FAILED;
      result_.message = get_error_message(result_.status);
      return false;
    }
    result_.separator_size = partition.separator_size;
    result_.cut_loop_length = partition.loop.size();
    // Stage 1's iterations count the pairs of disks embedded: one, or more when a solver or the weights fell back.
    result_.initial_guess.iterations = 1;
    bool embedded = initial_sphere(mesh_, system_, partition, options_.weighting, solver_, x, options_.parallel);
    if(!embedded) {
      ++result_.initial_guess.iterations;
      // An iterative solver can give up where a direct one does not: try Eigen's sparse LU before failing.
      embedded = initial_sphere(mesh_, system_, partition, options_.weighting, Sparse_LU_solver_traits(), x, options_.parallel);
      if(options_.verbose && embedded) std::cerr << "stage 1: the disk solver failed; Eigen's sparse LU was used\n";
    }
    Sphere_certificate start = embedded ? certify(system_.triangles, x) : Sphere_certificate();
    if(options_.weighting != Weighting::UNIFORM && (!embedded || start.flipped_faces > 0)) {
      // Weights that may be negative or non-symmetric can fold the disks: Tutte's disks cannot.
      std::vector<Vector3> uniform_start;
      ++result_.initial_guess.iterations;
      if(initial_sphere(mesh_, system_, partition, Weighting::UNIFORM, solver_, uniform_start, options_.parallel)) {
        const Sphere_certificate uniform_certificate = certify(system_.triangles, uniform_start);
        if(!embedded || uniform_certificate.flipped_faces < start.flipped_faces) {
          x.swap(uniform_start);
          start = uniform_certificate;
          embedded = true;
          result_.uniform_initial_guess_fallback = true;
        }
      }
    }
    if(!embedded) {
      result_.status = Error_code::DISK_EMBEDDING_FAILED;
      result_.message = get_error_message(result_.status);
      return false;
    }
    result_.initial_flipped_faces = start.flipped_faces;
    result_.initial_guess.residual = compute_residuals(system_, x).paper;
    const double initial_imbalance = summarize_imbalance(system_, x, options_.iterations.tolerance).max;
    result_.initial_guess.seconds = stage.time();
    if(options_.verbose)
      std::cerr << "stage 1: separator " << result_.separator_size << " vertices, loop " << result_.cut_loop_length
                << " vertices, Res " << result_.initial_guess.residual << ", non-positive faces " << start.flipped_faces
                << ", max imbalance " << initial_imbalance << ", " << result_.initial_guess.seconds << " s\n";
    if(options_.report) {
      Progress progress;
      progress.stage = "initial guess";
      progress.residual = result_.initial_guess.residual;
      progress.max_imbalance = initial_imbalance;
      progress.non_positive_faces = start.flipped_faces;
      progress.seconds = total_.time();
      cancelled_ = !options_.report(progress);
    }

    // A non-inscribable connectivity has no bijective balanced solution for positive weights: iterating cannot
    // succeed, so the initial guess (bijective by construction in all but rare cases) is the answer; a few
    // bijectivity-preserving iterations only serve to repair it if some of its triangles are not positive.
    bool positive_weights = true;
    for(double w : system_.weights) positive_weights = positive_weights && w > 0.;
    inscribability_ = check_inscribability(system_);
    no_balanced_solution_ = positive_weights && inscribability_.proven_not_inscribable;
    // Non-symmetric weights (mean value) have no exact solution in general: with the imbalance test their iterations
    // stop on the stationarity of the least-squares problem instead (summarize_stationarity).
    if(no_balanced_solution_) {
      iteration_options_.max_gauss_seidel_sweeps = start.flipped_faces == 0 ? 0 : std::min<std::size_t>(iteration_options_.max_gauss_seidel_sweeps, 100);
      iteration_options_.max_newton_sweeps = start.flipped_faces == 0 ? 0 : std::min<std::size_t>(iteration_options_.max_newton_sweeps, 100);
      iteration_options_.tolerance = 0.;  // stop at the caps; no residual is the goal here
    }

    return true;
  }

  // Stages 2 and 3 from the initial guess in x.
  void iterate(std::vector<Vector3>& x)
  {
    CGAL::Real_timer stage;
    stage.start();
    // Stages 2 and 3, with what is left of the time budget: it bounds the whole call, and stage 1 (which every
    // returned map needs) runs to its end even when it alone takes longer.
    if(iteration_options_.max_seconds >= 0.)
      iteration_options_.max_seconds = std::max(0., iteration_options_.max_seconds - options_.call_clock.time());
    const std::vector<Vector3> initial_guess = x;
    Sphere_state state(system_, x);
    CGAL::Real_timer iterations_clock;
    iterations_clock.start();
    // The default solver first tries Newton's full steps (through folds, keeping degree 1) from the initial guess:
    // where they converge (most meshes, in 4 to 20 steps) stage 2 is not needed. Otherwise the paper's order
    // follows from the initial guess again: stage 2, then stage 3 (which tries the same steps from stage 2's result
    // before the bijectivity-preserving ones). Non-symmetric weights (imbalance test): the least-squares iterations
    // first, which need no smoothing either (bear, mean value: 2.6 s from the initial guess, 25 s after stage 2).
    Iteration_report direct_newton;
    CGAL::Real_timer direct_clock;
    direct_clock.start();
    const bool try_direct_newton = !cancelled_ && !no_balanced_solution_ &&
                                   options_.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON && iteration_options_.max_newton_sweeps > 0 &&
                                   (system_.symmetric || iteration_options_.convergence_test == Convergence_test::IMBALANCE);
    if(try_direct_newton) {
      direct_newton = system_.symmetric ? full_newton_steps(state, iteration_options_, iterations_clock)
                                        : least_squares_newton(state, iteration_options_, iterations_clock);
      if(options_.coarse_level && !direct_newton.converged) {
        iteration_options_.max_gauss_seidel_sweeps = 0;
        iteration_options_.max_newton_sweeps = 0;
      }
      cancelled_ = direct_newton.cancelled;
      if(!direct_newton.converged && !cancelled_ && !direct_newton.out_of_time) state.assign(initial_guess);
      if(iteration_options_.max_newton_sweeps > direct_newton.sweeps) iteration_options_.max_newton_sweeps -= direct_newton.sweeps;
      else iteration_options_.max_newton_sweeps = 0;
    }
    const double direct_seconds = direct_clock.time();
    const bool direct_done = direct_newton.converged || direct_newton.out_of_time;

    stage.reset();
    Iteration_report gauss_seidel;
    if(!cancelled_ && !direct_done) gauss_seidel = projected_gauss_seidel(state, iteration_options_, iterations_clock);
    else gauss_seidel.residual = direct_newton.converged ? direct_newton.residual : result_.initial_guess.residual;
    cancelled_ = cancelled_ || gauss_seidel.cancelled;
    result_.gauss_seidel.iterations = gauss_seidel.sweeps;
    result_.gauss_seidel.residual = gauss_seidel.residual;
    result_.gauss_seidel.seconds = stage.time();
    if(options_.verbose)
      std::cerr << "stage 2: " << gauss_seidel.sweeps << " sweeps, Res " << gauss_seidel.residual << ", non-positive faces "
                << state.invalid_faces() << ", " << result_.gauss_seidel.seconds << " s\n";

    stage.reset();
    if(!direct_done && !gauss_seidel.converged && !gauss_seidel.out_of_time && !cancelled_ && iteration_options_.max_newton_sweeps > 0)
      newton_ = options_.nonlinear_solver == Nonlinear_solver::LOCAL_NEWTON
                   ? local_newton(state, iteration_options_, iterations_clock)
                   : global_newton(state, iteration_options_, iterations_clock, &initial_guess);
    else newton_.residual = gauss_seidel.residual;
    cancelled_ = cancelled_ || newton_.cancelled;
    result_.newton.iterations = newton_.sweeps + direct_newton.sweeps;
    result_.newton.linear_iterations = newton_.linear_iterations + direct_newton.linear_iterations;
    result_.newton.residual = direct_done ? direct_newton.residual : newton_.residual;
    result_.newton.seconds = stage.time() + direct_seconds;
    result_.rejected_moves = gauss_seidel.rejected_moves + newton_.rejected_moves;
    result_.continuation_parameter = newton_.continuation_parameter;
    if(options_.verbose)
      std::cerr << "stage 3: " << newton_.sweeps << " sweeps, Res " << newton_.residual << ", non-positive faces "
                << state.invalid_faces() << ", " << result_.newton.seconds << " s\n";
  }

  // The certificate and the figures, recomputed from scratch on the final positions, the status and its message.
  void certify_and_report(const std::vector<Vector3>& x)
  {
    // Certificate and figures, recomputed from scratch on the final positions.
    const Residuals residuals = compute_residuals(system_, x);
    const Sphere_certificate certificate = certify(system_.triangles, x);
    result_.residual = residuals.paper;
    result_.max_tangential_residual = residuals.max_tangential;
    result_.flipped_faces = certificate.flipped_faces;
    result_.total_signed_area = certificate.total_signed_area;
    result_.bijective = certificate.bijective;
    std::vector<double> imbalances;
    const Imbalance_summary imbalance = summarize_imbalance(system_, x, options_.iterations.tolerance, &imbalances);
    result_.max_imbalance = imbalance.max;
    result_.imbalance_percentile_99 = imbalance.percentile_99;
    result_.vertices_at_rounding_floor = imbalance.vertices_at_rounding_floor;
    result_.unbalanced_vertices = imbalance.unbalanced_vertices;
    result_.convergence_test = iteration_options_.convergence_test;
    Imbalance_summary stationarity;
    if(!system_.symmetric) {
      stationarity = summarize_stationarity(system_, x, options_.iterations.tolerance);
      result_.max_stationarity = stationarity.max;
      result_.unstationary_vertices = stationarity.unbalanced_vertices;
    }
    const bool converged = iteration_options_.convergence_test == Convergence_test::PAPER_RESIDUAL
                               ? result_.residual < options_.iterations.tolerance
                               : (system_.symmetric ? imbalance : stationarity).balanced();
    result_.status = !converged ? Error_code::NOT_CONVERGED : (certificate.bijective ? Error_code::OK : Error_code::NOT_BIJECTIVE);
    if(cancelled_) result_.status = Error_code::CANCELLED;
    if(no_balanced_solution_) result_.status = Error_code::NO_BALANCED_SOLUTION;
    result_.message = get_error_message(result_.status);
    if(!system_.symmetric && iteration_options_.convergence_test == Convergence_test::IMBALANCE) {
      std::ostringstream note;
      note << " [non-symmetric weights: the test is the stationarity of their least-squares problem, max "
           << result_.max_stationarity << "; their imbalance cannot reach the tolerance]";
      result_.message += note.str();
    }
    if(no_balanced_solution_) {
      std::ostringstream details;
      details << " (proof: " << inscribability_.independent_set_size << " of the " << system_.number_of_vertices
              << " vertices are pairwise non-adjacent" << (2 * inscribability_.independent_set_size == system_.number_of_vertices
                                                               ? " and two of the others are adjacent" : "")
              << "). The map returned is the initial guess (two Tutte disks, "
              << "Moebius inversion, stereographic projection)" << (certificate.bijective ? ", certified bijective" : ", NOT bijective: "
              + std::to_string(certificate.flipped_faces) + " flipped faces") << ", not a balanced one";
      result_.message += details.str();
    } else if(result_.status != Error_code::OK) {
      std::ostringstream details;
      details << " (max imbalance " << result_.max_imbalance << ", " << result_.unbalanced_vertices
              << " vertices above the tolerance, Res " << result_.residual << ", " << result_.flipped_faces << " flipped faces";
      if(result_.continuation_parameter >= 0. && result_.continuation_parameter < 1.)
        details << "; the balanced maps from Tutte's weights towards these could be followed only "
                << static_cast<int>(100. * result_.continuation_parameter) << "% of the way";
      if(!system_.symmetric)
        details << "; with non-symmetric weights the balance equations generally have no exact solution";
      else if(newton_.stagnated)
        details << "; the residual stagnated";
      if(!options_.admissible_weights && (!system_.symmetric || result_.continuation_parameter >= 0.))
        details << "; the admissible_weights named parameter may help";
      details << ")";
      result_.message += details.str();
    }
  }

  const Mesh_arrays& mesh_;
  Sphere_system& system_;
  const Pipeline_options& options_;
  const SolverTraits& solver_;
  Result result_;
  CGAL::Real_timer total_;
  Iteration_options iteration_options_;   // options_.iterations as this mesh's stages run them
  bool cancelled_ = false;
  bool no_balanced_solution_ = false;     // proven: no bijective balanced map exists (inscribability_)
  Inscribability_check inscribability_;
  Iteration_report newton_;
  double multilevel_newton_seconds_ = 0.;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_MAPPER_H
