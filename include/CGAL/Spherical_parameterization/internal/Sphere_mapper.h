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
#include <CGAL/Spherical_parameterization/internal/angle_error.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/internal/certificate.h>
#include <CGAL/Spherical_parameterization/internal/disk_embedding.h>
#include <CGAL/Spherical_parameterization/internal/inscribability.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/mesh_coarsening.h>
#include <CGAL/Spherical_parameterization/internal/sphere_iterations.h>
#include <CGAL/Spherical_parameterization/internal/stage3/global_newton.h>
#include <CGAL/Spherical_parameterization/internal/stage3/fold_repair.h>
#include <CGAL/Spherical_parameterization/internal/stage3/least_distortion.h>
#include <CGAL/Spherical_parameterization/internal/stage3/multilevel_least_distortion.h>
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
using Sparse_LU_solver_traits = CGAL::Eigen_solver_traits<
    Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;

// CGAL's METIS functions take `METIS_options(&options)` (a pointer to the array); the array itself works too.
inline const idx_t* metis_options_pointer(const idx_t* options)
{
  return options;
}
inline const idx_t* metis_options_pointer(const idx_t (*options)[METIS_NOPTIONS])
{
  return options ? *options : nullptr;
}

struct Pipeline_options
{
  Weighting weighting = Weighting::UNIFORM;
  bool admissible_weights = false; // the weights were made symmetric and positive
  bool hold_weights = false;       // the weight continuation may hold weights where its path ends (weight_continuation.h)
  bool least_distortion = false;   // an unconverged map is replaced by the bijective map of least distortion
  Nonlinear_solver nonlinear_solver = Nonlinear_solver::GLOBAL_NEWTON;
  int metis_seed = 0;
  const idx_t* metis_options = nullptr; // METIS_NOPTIONS values, or nullptr for METIS' defaults and metis_seed
  bool verbose = false;
  bool parallel = false;  // CGAL::Parallel_tag with TBB
  bool multilevel = true; // the multilevel start where it applies (multilevel_applies)
  // A coarser level of the multilevel start: only Newton's full steps are tried. When they fail, the finer level
  // starts from its own two disks, so the fallbacks of stages 2 and 3 would be spent on a mere start (the manual's
  // Method section has what that cost).
  bool coarse_level = false;
  // This call is a retry from another METIS partition (retry_other_partitions): no retries of its own.
  bool partition_retry = false;
  Iteration_options iterations; // its max_seconds counts from `call_clock`'s start
  CGAL::Real_timer call_clock;  // started when the user's call began (input checks and stage 1 count too)
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
  std::vector<char> side(n, 0); // 1: disk A, 2: disk B (the loop counts as A)
  for(std::size_t f = 0; f < system.triangles.size(); ++f)
    for(int g : system.triangles[f])
      if(partition.face_in_disk_a[f])
        side[static_cast<std::size_t>(g)] = 1;
      else if(side[static_cast<std::size_t>(g)] == 0)
        side[static_cast<std::size_t>(g)] = 2;
  bool embedded_a = false, embedded_b = false;
#ifdef CGAL_LINKED_WITH_TBB
  if(parallel)
  {
    // Unqualified: a user's overload in the solver's namespace is found too.
    const SolverTraits solver_a = independent_copy(solver), solver_b = independent_copy(solver);
    tbb::parallel_invoke(
        [&] { embedded_a = embed_one_disk(mesh, system, partition, 1, weighting, solver_a, u_a, v_a); },
        [&] { embedded_b = embed_one_disk(mesh, system, partition, 0, weighting, solver_b, u_b, v_b); });
  }
  else
#endif
  {
    CGAL_USE(parallel);
    embedded_a = embed_one_disk(mesh, system, partition, 1, weighting, solver, u_a, v_a);
    embedded_b = embedded_a && embed_one_disk(mesh, system, partition, 0, weighting, solver, u_b, v_b);
  }
  if(!embedded_a || !embedded_b)
    return false;
  x.resize(n);
  for(std::size_t i = 0; i < n; ++i)
    x[i] = side[i] == 2 ? inverse_stereographic(u_b[i], v_b[i], true) : inverse_stereographic(u_a[i], v_a[i], false);
  return true;
}

template <typename SolverTraits>
class Sphere_mapper
{
public:
  Sphere_mapper(const Mesh_arrays& mesh, Sphere_system& system, const Pipeline_options& options,
                const SolverTraits& solver)
    : m_mesh(mesh), m_system(system), m_options(options), m_solver(solver)
  {}

  // The whole map into x: a start, stages 2 and 3, the certificate and the figures.
  Result map(std::vector<Vector3>& x)
  {
    m_result = Result();
    m_stage_1_deferred = false;
    m_total = CGAL::Real_timer();
    m_total.start();
    m_result.number_of_vertices = m_system.number_of_vertices;
    m_result.partition_seed = m_options.metis_seed;
    m_result.number_of_faces = m_system.triangles.size();
    // With least_distortion, on the mesh given, for weights other than Tutte's and under the imbalance test (with the
    // paper's, least_distortion() returns at once), the minimization follows the ways to the weights' balanced map:
    // with a time budget, those ways get a share of it and the minimization the rest
    // (Solver_tuning::least_distortion_balance_share); and the cautious Newton, their last resort, gives way to the
    // minimization, except where the held continuation (which comes after it) was asked for.
    const bool minimization_follows = m_options.least_distortion && !m_options.coarse_level
                                      && !has_tutte_weights(m_system)
                                      && m_options.iterations.convergence_test == Convergence_test::IMBALANCE;
    const double budget = m_options.iterations.max_seconds;
    if(minimization_follows && budget >= 0.)
      m_options.iterations.max_seconds = budget * m_options.iterations.tuning.least_distortion_balance_share;
    // The watchdog through folds (Solver_tuning::free_newton_nonmonotone_window) is for Tutte's weights, where it was
    // measured; for other weights it is off, on their coarser levels too (which inherit this tuning): with it there,
    // those levels' Tutte maps changed in their last bits, and the cotangent paths from them with it (oded_hammer,
    // balanced in 15 s, then ended unconverged).
    if(!m_options.coarse_level && !has_tutte_weights(m_system))
    {
      m_options.iterations.tuning.free_newton_nonmonotone_window = 1;
      m_options.iterations.tuning.boost_step_part_where_unsettled = false; // the same reason
    }
    m_iteration_options = m_options.iterations;
    m_iteration_options.least_distortion_follows = minimization_follows && !m_options.hold_weights;
    if(multilevel_applies())
      m_multilevel_tried = true;
    // A folded balanced map reached on the way (with least_distortion only) ends the ways to the balanced map: the
    // multilevel start's figures stay.
    if(m_multilevel_tried && (multilevel_start(x) || m_balanced_map_folded))
    {
      // Stage 1 is everything before this mesh's smoothing and Newton steps (the coarser levels, solved, and the map
      // carried back); stage 2 the smoothing.
      m_result.newton.seconds = m_multilevel_newton_seconds - m_result.gauss_seidel.seconds;
      m_result.initial_guess.seconds = m_total.time() - m_multilevel_newton_seconds;
      m_result.newton.iterations = m_newton.sweeps;
      m_result.newton.linear_iterations = m_newton.linear_iterations;
      m_result.newton.residual = m_newton.residual;
    }
    else if(m_iteration_options.least_distortion_follows && (!m_system.symmetric || m_multilevel_tried)
            && has_least_distortion_levels(m_system.number_of_vertices, m_options.iterations.tuning))
    {
      // The minimization follows at once (non-symmetric weights; or the multilevel start ended unbalanced, cotangent)
      // and starts from its own coarser levels, whose map replaced stage 1's on every mesh measured, so stage 1 runs
      // only where that start fails (least_distortion()): 1.4 s saved on c3d_igea and vol2surf_lh_pial with mean-value
      // weights, 0.7 s on bigbrain; 1.1 s on vol2surf_lh_pial with cotangent weights.
      m_stage_1_deferred = true;
      x.clear();
      m_result.levels.clear(); // those of the multilevel start, if it ran: its map is not the one returned
      m_result.initial_flipped_faces = 0;
      m_result.initial_guess = Stage_statistics();
      m_system.regularized_tips.clear();
      check_for_a_balanced_map();
    }
    else
    {
      m_result.levels.clear();
      m_system.regularized_tips.clear(); // a failed multilevel start's tips belong to its map, not to this one
      if(!two_disk_start(x))
      {
        m_options.iterations.max_seconds = budget;
        return m_result;
      }
      if(m_iteration_options.least_distortion_follows && (!m_system.symmetric || m_multilevel_tried))
      {
        // Non-symmetric weights have no balanced map, and the minimization replaces their least-squares map (see
        // least_distortion()): its iterations are not run (bunny00's 12.5 s of 23.6 s with mean-value weights).
        // Where the multilevel start failed, the minimization follows at once too: the two-disk guess is only the
        // bijective map it starts from if its own start is not better (multilevel_start).
      }
      else if(partition_retries_apply())
      {
        fast_ways_first(x);
      }
      else
      {
        iterate(x);
        if(multilevel_fallback_applies(x))
          multilevel_fallback(x);
      }
    }
    m_options.iterations.max_seconds = budget;
    if(m_options.least_distortion && !m_options.coarse_level)
      least_distortion(x);
    if(m_stage_1_deferred && x.empty() && !two_disk_start(x)) // the minimization gave no map: stage 1's
      return m_result;
    if(x.empty()) // stage 1 failed within least_distortion() (the result says why)
      return m_result;
    certify_and_report(x);
    m_result.total_seconds = m_total.time();
    return m_result;
  }

private:
  // A coarser level of the multilevel start goes through its own coarser level first down to
  // multilevel_fallback_min_vertices, not only from multilevel_min_vertices on: its two-disk guess is the slower
  // start there (CGAL's man.off refined once: its levels of 17,493 and 4,373 vertices spent 3.4 s of 6.8 on their two
  // disks before their own coarser levels solved them; 3.7 s in all through the levels).
  // Symmetric weights other than Tutte's (cotangent of either sign, admissible ones, the user's) go multilevel first
  // from Solver_tuning::multilevel_min_vertices_other_weights on.
  bool multilevel_applies() const
  {
    const Solver_tuning& tuning = m_options.iterations.tuning;
    const std::size_t min_vertices = m_options.coarse_level       ? tuning.multilevel_fallback_min_vertices
                                     : has_tutte_weights(m_system) ? tuning.multilevel_min_vertices
                                                                   : tuning.multilevel_min_vertices_other_weights;
    return m_options.multilevel && multilevel_weights() && m_options.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON
           && m_system.number_of_vertices >= min_vertices && m_options.iterations.max_newton_sweeps > 0;
  }

  // The weights the multilevel start is for: symmetric ones (Tutte's; cotangent weights, of either sign; cotangent or
  // mean-value weights made admissible; the user's, if symmetric). Its coarser levels are solved with Tutte's weights,
  // whatever the weights of the mesh given:
  // they are a mere start, and each level's map carried back is close to Tutte's map there, which its Newton steps
  // reach robustly. The mesh given then goes from that map to the balanced map of its own weights. With admissible
  // weights, 62 of the 66 meshes converge instead of 57 (cotangent) and 64 instead of 62 (mean value), in a third of
  // the time or less (the manual's Method section has the figures). Coarser levels with the same kind of weights
  // computed on their own geometry failed (a collapsed mesh's cotangent weights, raised where negative, are far from
  // the fine mesh's: bigbrain's levels ended unconverged, 68 s).
  // Cotangent weights with negative ones (every mesh of the 66 has some) went this way too from 2026-11-27: 49 of the
  // 66 converge instead of 45 (c3d_igea, oded_hammer, oded_koala, brainspace_conte69_32k), in 382 s in all instead of
  // 483 s (a 30 s budget each); homer 0.17 s instead of 13 s, bunny00 1.1 s instead of 3.2 s. Where this mesh's
  // Newton steps fail from the map carried back, its two disks follow as before (fandisk_large: 10.7 s instead of
  // 1.6 s). Their balanced map need not be bijective, nor unique: a map balanced from another start may differ
  // (fandisk: angle error 1.54 degrees instead of 1.37, both balanced and bijective).
  bool multilevel_weights() const { return m_system.symmetric; }

  // Below multilevel_min_vertices the two-disk path comes first (faster there on most meshes); where it ends
  // unconverged, the multilevel start is tried too: its coarser level carries the global shape that Newton's steps from
  // the two-disk guess could not find (CGAL's u.off and part.off refined by one Loop subdivision: NOT_CONVERGED at max
  // imbalance 0.37 and 0.09 from the two disks, OK in 0.04 and 0.06 s from their levels of 84 and 173 vertices).
  // Only for the mesh given: a coarser level from that size on has gone multilevel first (multilevel_applies).
  // Non-symmetric weights (mean value) never go multilevel first, and take this fallback from 200 vertices on, with
  // no upper limit: their least-squares iterations from the balanced map of Tutte's weights, carried back from the
  // levels, find a stationary map on triceratops (11.1 degrees, 11 s in all; 13.3 in 8 s since 2026-11-28) and
  // oblong (from its two disks since the LU's steps are the least-squares step, imbalance_least_squares.h), where
  // those from the two-disk guess stalled. First they lost more than they won: 47 of the 66 meshes stationary
  // instead of 49 (bear, from Tutte's map, ends at another minimum of the least-squares problem, 6.6 degrees instead
  // of 3.6, not stationary in 30 s; likewise diplodocus, brainspace_conte69_32k and oded_hammer).
  bool multilevel_fallback_applies(const std::vector<Vector3>& x) const
  {
    if(!m_options.multilevel || m_multilevel_tried || m_cancelled || m_no_balanced_solution || m_balanced_map_folded
       || m_options.nonlinear_solver != Nonlinear_solver::GLOBAL_NEWTON
       || (m_system.symmetric && m_system.number_of_vertices >= m_options.iterations.tuning.multilevel_min_vertices)
       || m_system.number_of_vertices < m_options.iterations.tuning.multilevel_fallback_min_vertices
       || m_options.iterations.max_newton_sweeps == 0 || m_newton.out_of_time
       || m_options.iterations.convergence_test != Convergence_test::IMBALANCE)
      return false;
    if(m_options.iterations.max_seconds >= 0. && m_options.call_clock.time() >= m_options.iterations.max_seconds)
      return false;
    const double tolerance = m_options.iterations.tolerance;
    return !((m_system.symmetric ? summarize_imbalance(m_system, x, tolerance)
                                 : summarize_stationarity(m_system, x, tolerance))
                 .balanced()
             && certify(m_system.triangles, x).bijective);
  }

  // Symmetric positive weights (Tutte's, admissible ones, the user's) have a bijective balanced map, so where every
  // way to it ends unconverged on the mesh given, the path failed, not the weights; the path starts from the METIS
  // partition of the two-disk guess. Then other partitions are worth trying (retry_other_partitions), and the fast
  // ways of each come before the slow ways of the first (fast_ways_first). Not for the paper's setting (local Newton,
  // or its Res test), nor with the user's own METIS options (whose seed is theirs).
  bool partition_retries_apply() const
  {
    return !(m_options.coarse_level || m_options.partition_retry || m_options.metis_options != nullptr || m_cancelled
             || m_no_balanced_solution || m_options.nonlinear_solver != Nonlinear_solver::GLOBAL_NEWTON
             || m_options.iterations.convergence_test != Convergence_test::IMBALANCE
             || m_options.iterations.max_newton_sweeps == 0 || !m_system.symmetric
             || !has_positive_weights(m_system));
  }

  // Whether x still needs another way: not converged, nor stopped (cancel, time budget), nor ended on a folded
  // balanced map (with least_distortion the minimization follows then).
  bool other_ways_needed(const std::vector<Vector3>& x) const
  {
    if(m_cancelled || m_newton.out_of_time || m_balanced_map_folded || x.empty())
      return false;
    if(m_options.iterations.max_seconds >= 0. && m_options.call_clock.time() >= m_options.iterations.max_seconds)
      return false;
    return !converged_and_bijective(x);
  }

  // With symmetric positive weights, from the two-disk guess in x: first the fast ways (Newton's full steps from the
  // guess and after stage 2, the multilevel fallback, the fast ways of other partitions), then, where none converged,
  // the slow ones from the first partition's guess (the bijectivity-preserving steps, the cautious Newton), which
  // take seconds to fail. Where the first partition's full steps converge, nothing changes. In the order before
  // (every way of the first partition first), a first partition whose slow ways fail cost their time before the
  // multilevel fallback or a retry converged: CGAL's bull with METIS seed 4 16.6 s, 2.1 s now; cow refined once
  // with seed 2 23.8 s, 3.5 s now (the manual's Method section).
  void fast_ways_first(std::vector<Vector3>& x)
  {
    CGAL::Real_timer clock;
    clock.start();
    const std::vector<Vector3> guess = x;
    const Result after_start = m_result;
    const Iteration_options iteration_options = m_iteration_options;
    m_iteration_options.free_steps_only = true;
    iterate(x);
    if(multilevel_fallback_applies(x))
      multilevel_fallback(x);
    if(other_ways_needed(x))
      retry_other_partitions(x);
    if(!other_ways_needed(x))
      return;
    // The slow ways, from the first partition's guess; the fast ways' time counts in stage 3.
    const std::size_t retries = m_result.partition_retries;
    const double spent = clock.time();
    x = guess;
    m_result = after_start;
    m_result.partition_retries = retries;
    m_iteration_options = iteration_options;
    iterate(x);
    m_result.newton.seconds += spent;
  }

  // The two-disk guesses of other METIS partitions (seeds after the one given), each followed by Newton's full steps
  // only (from the guess, then after stage 2): where they converge, in hundredths of a second on small meshes, that
  // map replaces x; the bijectivity-preserving steps, the multilevel start and the cautious Newton, which take seconds
  // to fail, are left to the first partition (fast_ways_first). Measured over METIS seeds 0 to 124 on CGAL's
  // part.off: 50 seeds ended unconverged without the retries, none with them (1 to 4 retries; the manual's Method
  // section).
  void retry_other_partitions(std::vector<Vector3>& x)
  {
    CGAL::Real_timer clock;
    clock.start();
    const std::size_t tries = m_options.iterations.tuning.partition_retries;
    for(std::size_t k = 1; k <= tries; ++k)
    {
      if(m_options.iterations.max_seconds >= 0. && m_options.call_clock.time() >= m_options.iterations.max_seconds)
        break;
      Pipeline_options options = m_options;
      options.metis_seed = m_options.metis_seed + static_cast<int>(k);
      options.partition_retry = true;
      options.multilevel = false;
      options.least_distortion = false;
      options.iterations.free_steps_only = true;
      Sphere_system system = m_system; // the retry writes its own regularized tips
      system.regularized_tips.clear();
      std::vector<Vector3> y;
      const double before = m_total.time();
      Result retry = Sphere_mapper(m_mesh, system, options, m_solver).map(y);
      m_result.partition_retries = k;
      if(m_options.verbose)
        std::cerr << "partition retry " << k << " (METIS seed " << options.metis_seed
                  << "): " << get_error_message(retry.status) << ", max imbalance " << retry.max_imbalance << ", "
                  << clock.time() << " s\n";
      if(retry.status == Error_code::CANCELLED)
      {
        m_cancelled = true;
        return;
      }
      if(retry.status == Error_code::OK && y.size() == x.size())
      {
        // Stage 1 of the map returned includes every attempt before it.
        retry.initial_guess.seconds += before;
        retry.partition_retries = k;
        retry.partition_seed = options.metis_seed;
        m_result = retry;
        m_system.regularized_tips = system.regularized_tips;
        m_newton = Iteration_report();
        m_newton.converged = true;
        x.swap(y);
        return;
      }
    }
  }

  // The multilevel start after the two-disk path: its map replaces x only if it converged.
  void multilevel_fallback(std::vector<Vector3>& x)
  {
    const Result two_disk_result = m_result;
    const Iteration_report two_disk_newton = m_newton;
    const std::vector<char> two_disk_tips = m_system.regularized_tips;
    CGAL::Real_timer clock;
    clock.start();
    std::vector<Vector3> y;
    if(multilevel_start(y) && m_newton.converged)
    {
      x.swap(y);
      m_result.newton.seconds = m_multilevel_newton_seconds - m_result.gauss_seidel.seconds;
      m_result.initial_guess.seconds = two_disk_result.initial_guess.seconds + two_disk_result.gauss_seidel.seconds
                                       + two_disk_result.newton.seconds + clock.time() - m_multilevel_newton_seconds;
      m_result.newton.iterations = m_newton.sweeps;
      m_result.newton.linear_iterations = m_newton.linear_iterations;
      m_result.newton.residual = m_newton.residual;
      m_result.multilevel_fallback = true;
      return;
    }
    // Not better: the two-disk path's map and figures stay (the fallback's time is counted in stage 3).
    const double spent = clock.time();
    m_result = two_disk_result;
    m_result.newton.seconds += spent;
    m_newton = two_disk_newton;
    m_system.regularized_tips = two_disk_tips;
    m_cancelled = m_cancelled || m_newton.cancelled;
  }

  // The multilevel start: the mesh collapsed to about `Solver_tuning::multilevel_coarsening_ratio` of its vertices,
  // that mesh solved by the whole pipeline (itself multilevel while it is large enough), its map carried back
  // (prolong()), smoothed by a few Gauss-Seidel sweeps (the vertices carried back sit where their ring was positive,
  // not where they balance), then Newton's full steps on this mesh, the boosts solved as outer unknowns
  // (Boost_aim::ROOT), and where they fail from a bijective map, the steps that keep it bijective (non-symmetric
  // weights, in the multilevel fallback only: the least-squares iterations instead).
  // From the two-disk guess the number of Newton steps grows with the mesh; from the level below it stays a few
  // (the manual's Method and Performance sections have the counts).
  // Returns true when this mesh's map converged (or the time or a cancel stopped it); otherwise `x` is unspecified
  // and the caller starts again with the paper's stage 1.
  // Where it fails on the mesh given (not for want of time; a coarser level is a mere start, see coarse_level), it is
  // tried once more through levels of `Solver_tuning::multilevel_retry_coarsening_ratio` of the vertices (and so on
  // down): a map carried back from a level closer in size is closer to this level's solution, so Newton's steps fold
  // less (CGAL's camel.off refined twice: its finest level of 156,290 vertices stalls from its level of a quarter of
  // them, and converges through levels of halves; u.off refined twice likewise).
  bool multilevel_start(std::vector<Vector3>& x)
  {
    const Solver_tuning& tuning = m_options.iterations.tuning;
    if(multilevel_attempt(x, tuning.multilevel_coarsening_ratio))
      return true;
    const bool budget_left =
        !(m_options.iterations.max_seconds >= 0. && m_options.call_clock.time() >= m_options.iterations.max_seconds);
    // With the minimization following (least_distortion), no retry either: it ends with a bijective map of least
    // distortion whether or not the weights' balanced map exists, and the retry and the two-disk path after it, which
    // look for one, took most of the time where they ran (oded_scorpion with cotangent weights: 57 of its 70 s;
    // c3d_cheburashka 19 of 21 s; the manual's Method section).
    if(m_options.coarse_level || m_cancelled || m_newton.out_of_time || !budget_left || m_balanced_map_folded
       || m_iteration_options.least_distortion_follows
       || !(tuning.multilevel_retry_coarsening_ratio > tuning.multilevel_coarsening_ratio))
      return false;
    if(m_options.verbose)
      std::cerr << "multilevel: " << m_system.number_of_vertices << " vertices tried again through levels of "
                << tuning.multilevel_retry_coarsening_ratio << " of the vertices\n";
    return multilevel_attempt(x, tuning.multilevel_retry_coarsening_ratio);
  }

  // One multilevel start through coarser levels of `ratio` times the vertices (the coarser levels keep that ratio).
  bool multilevel_attempt(std::vector<Vector3>& x, double ratio)
  {
    CGAL::Real_timer clock;
    clock.start();
    m_system.regularized_tips.clear(); // those of an earlier attempt or path belong to its map (the fallback keeps them)
    const std::size_t n = m_system.number_of_vertices;
    // With CGAL::Parallel_tag, the preconditioner of this level's Newton steps is built while the coarser levels are
    // solved (Laplacian_preconditioner_ahead).
    if(m_options.parallel && m_system.symmetric && !m_preconditioner_ahead.started()
       && n >= m_options.iterations.tuning.iterative_newton_min_vertices) // (MINRES is for symmetric weights)
      m_preconditioner_ahead.start(m_system);
    Coarsening coarsening =
        coarsen_mesh(m_mesh.points, m_system.triangles, static_cast<std::size_t>(ratio * static_cast<double>(n)));
    Sphere_system coarse_system =
        make_connectivity(std::move(coarsening.coarse.triangles), coarsening.coarse.points.size());
    std::string message;
    if(assign_weights(coarse_system, coarsening.coarse, Weighting::UNIFORM, {}, message) != Error_code::OK)
      return false;
    const double coarsening_seconds = clock.time();
    std::vector<Vector3> coarse_x;
    Pipeline_options coarse_options = m_options;
    coarse_options.coarse_level = true;
    coarse_options.weighting = Weighting::UNIFORM; // the coarser levels' weights (multilevel_weights)
    coarse_options.admissible_weights = false;
    coarse_options.hold_weights = false;
    coarse_options.iterations.tuning.multilevel_coarsening_ratio = ratio;
    coarse_options.iterations.tolerance = m_options.iterations.tuning.multilevel_coarse_tolerance;
    const Result coarse = Sphere_mapper(coarsening.coarse, coarse_system, coarse_options, m_solver).map(coarse_x);
    if(coarse.status == Error_code::CANCELLED && coarse_x.size() == coarse_system.number_of_vertices)
    {
      // Stopped on a coarser level: its map, carried back, is the best map there is for this one.
      prolong(coarsening, coarse_x, x);
      m_cancelled = true;
      m_result.levels = coarse.levels;
      return true;
    }
    if(coarse.status != Error_code::OK)
    {
      if(m_options.verbose)
        std::cerr << "multilevel: the level of " << coarse_system.number_of_vertices << " vertices ended "
                  << get_error_message(coarse.status) << "; the two-disk guess on " << n << " vertices follows\n";
      return false;
    }
    clock.reset();
    const std::size_t folded = prolong(coarsening, coarse_x, x);
    const std::size_t rounds = coarsening.rounds;
    coarsening = Coarsening();
    Iteration_options level_options = m_options.iterations;
    level_options.preconditioner_ahead = &m_preconditioner_ahead;
    level_options.least_distortion_follows = m_iteration_options.least_distortion_follows;
    if(level_options.max_seconds >= 0.)
      level_options.max_seconds = std::max(0., level_options.max_seconds - m_options.call_clock.time());
    Sphere_state state(m_system, x);
    m_result.initial_flipped_faces = state.invalid_faces();
    CGAL::Real_timer iterations_clock;
    iterations_clock.start();
    Iteration_options smoothing = level_options;
    smoothing.max_gauss_seidel_sweeps = m_options.iterations.tuning.multilevel_smoothing_sweeps;
    const Iteration_report smoothed = projected_gauss_seidel(state, smoothing, iterations_clock, false);
    m_result.gauss_seidel.iterations = smoothed.sweeps;
    m_result.gauss_seidel.residual = smoothed.residual;
    m_result.gauss_seidel.seconds = iterations_clock.time();
    m_result.initial_guess.residual = smoothed.residual;
    // The map carried back is close to the solution: the boost equations are solved as equations (Boost_aim).
    const std::vector<Vector3> smoothed_map = state.positions();
    const bool smoothed_map_positive = state.invalid_faces() == 0;
    // Non-symmetric weights (the multilevel fallback): the least-squares iterations from the map carried back.
    m_newton = m_system.symmetric ? full_newton_steps(state, level_options, iterations_clock, Boost_aim::ROOT)
                                  : least_squares_newton(state, level_options, iterations_clock);
    // With least_distortion, a folded balanced map ends the ways to the balanced map (Iteration_options::
    // least_distortion_follows); the map carried back stays where it was bijective (the map returned if the
    // minimization cannot run).
    m_balanced_map_folded = m_newton.balanced_map_folded && level_options.least_distortion_follows;
    if(m_balanced_map_folded)
      m_folded_balanced_map = std::move(m_newton.folded_balanced_map);
    if(m_balanced_map_folded && smoothed_map_positive)
    {
      state.assign(smoothed_map);
      m_newton.residual = smoothed.residual;
    }
    if(m_system.symmetric && !m_newton.converged && !m_newton.cancelled && !m_newton.out_of_time
       && smoothed_map_positive && !m_balanced_map_folded)
    {
      // The full steps folded their way astray, but the map carried back was bijective: from it, the steps that keep
      // every triangle positive (CGAL's man.off refined once: its level of 4,373 vertices converges in 7 such steps,
      // where the full steps ended at max imbalance 0.94 and the finer levels fell back to their two disks).
      state.assign(smoothed_map);
      Iteration_options remaining = level_options;
      remaining.max_newton_sweeps =
          level_options.max_newton_sweeps > m_newton.sweeps ? level_options.max_newton_sweeps - m_newton.sweeps : 0;
      Iteration_report bijective_steps =
          mobius_newton(state, remaining, iterations_clock, nullptr, m_options.iterations.tuning.cautious_patience,
                        false, Step_merit::IMBALANCE, Boost_aim::ROOT);
      bijective_steps.sweeps += m_newton.sweeps;
      bijective_steps.linear_iterations += m_newton.linear_iterations;
      m_newton = bijective_steps;
    }
    m_system.regularized_tips = m_newton.regularized_tips;
    m_cancelled = m_cancelled || m_newton.cancelled;
    m_multilevel_newton_seconds = iterations_clock.time();
    m_result.levels = coarse.levels;
    if(m_result.levels.empty())
    {
      Level_statistics coarsest;
      coarsest.vertices = coarse.number_of_vertices;
      coarsest.newton_steps = coarse.newton.iterations;
      coarsest.linear_iterations = coarse.newton.linear_iterations;
      coarsest.seconds = coarse.total_seconds;
      m_result.levels.push_back(coarsest);
    }
    Level_statistics level;
    level.vertices = n;
    level.newton_steps = m_newton.sweeps;
    level.linear_iterations = m_newton.linear_iterations;
    level.seconds = coarsening_seconds + clock.time();
    m_result.levels.push_back(level);
    if(m_options.verbose)
      std::cerr << "multilevel: " << n << " vertices from " << coarse.number_of_vertices << " (" << rounds
                << " rounds of collapses, " << coarsening_seconds << " s; " << folded
                << " vertices inserted folded): " << m_newton.sweeps << " Newton steps, " << m_newton.linear_iterations
                << " MINRES iterations, max imbalance "
                << summarize_imbalance(m_system, x, m_options.iterations.tolerance).max << ", " << clock.time()
                << " s\n";
    return m_newton.converged || m_newton.cancelled || m_newton.out_of_time;
  }

  // The paper's stage 1 (two disks, Moebius inversion, inverse stereographic projection) and the settings of the
  // iterations that follow from it; false when no initial guess could be made (result says why).
  bool two_disk_start(std::vector<Vector3>& x)
  {
    m_stage_1_deferred = false;
    CGAL::Real_timer stage;
    stage.start();
    const Two_disk_partition partition = split_into_two_disks(m_system, m_options.metis_seed, m_options.metis_options);
    if(!partition.valid)
    {
      m_result.status = Error_code::PARTITION_FAILED;
      m_result.message = get_error_message(m_result.status);
      return false;
    }
    m_result.separator_size = partition.separator_size;
    m_result.cut_loop_length = partition.loop.size();
    // Stage 1's iterations count the pairs of disks embedded: one, or more when a solver or the weights fell back.
    m_result.initial_guess.iterations = 1;
    bool embedded = initial_sphere(m_mesh, m_system, partition, m_options.weighting, m_solver, x, m_options.parallel);
    if(!embedded)
    {
      ++m_result.initial_guess.iterations;
      // An iterative solver can give up where a direct one does not: try Eigen's sparse LU before failing.
      embedded = initial_sphere(m_mesh, m_system, partition, m_options.weighting, Sparse_LU_solver_traits(), x,
                                m_options.parallel);
      if(m_options.verbose && embedded)
        std::cerr << "stage 1: the disk solver failed; Eigen's sparse LU was used\n";
    }
    Sphere_certificate start = embedded ? certify(m_system.triangles, x) : Sphere_certificate();
    if(m_options.weighting != Weighting::UNIFORM && (!embedded || start.flipped_faces > 0))
    {
      // Weights that may be negative or non-symmetric can fold the disks: Tutte's disks cannot.
      std::vector<Vector3> uniform_start;
      ++m_result.initial_guess.iterations;
      if(initial_sphere(m_mesh, m_system, partition, Weighting::UNIFORM, m_solver, uniform_start, m_options.parallel))
      {
        const Sphere_certificate uniform_certificate = certify(m_system.triangles, uniform_start);
        if(!embedded || uniform_certificate.flipped_faces < start.flipped_faces)
        {
          x.swap(uniform_start);
          start = uniform_certificate;
          embedded = true;
          m_result.uniform_initial_guess_fallback = true;
        }
      }
    }
    if(!embedded)
    {
      m_result.status = Error_code::DISK_EMBEDDING_FAILED;
      m_result.message = get_error_message(m_result.status);
      return false;
    }
    m_result.initial_flipped_faces = start.flipped_faces;
    m_result.initial_guess.residual = compute_residuals(m_system, x).paper;
    const double initial_imbalance = summarize_imbalance(m_system, x, m_options.iterations.tolerance).max;
    m_result.initial_guess.seconds = stage.time();
    if(m_options.verbose)
      std::cerr << "stage 1: separator " << m_result.separator_size << " vertices, loop " << m_result.cut_loop_length
                << " vertices, Res " << m_result.initial_guess.residual << ", non-positive faces "
                << start.flipped_faces << ", max imbalance " << initial_imbalance << ", "
                << m_result.initial_guess.seconds << " s\n";
    if(m_options.report)
    {
      Progress progress;
      progress.stage = "initial guess";
      progress.residual = m_result.initial_guess.residual;
      progress.max_imbalance = initial_imbalance;
      progress.non_positive_faces = start.flipped_faces;
      progress.seconds = m_total.time();
      m_cancelled = !m_options.report(progress);
    }

    // A non-inscribable connectivity has no bijective balanced solution for positive weights: iterating cannot
    // succeed, so the initial guess (bijective by construction in all but rare cases) is the answer; a few
    // bijectivity-preserving iterations only serve to repair it if some of its triangles are not positive.
    check_for_a_balanced_map();
    // A tetrahedron's two disks are no answer (one of their four triangles was folded on every tetrahedron tried, and
    // the repair collapsed three vertices onto one point): its vertices seen from their centroid are, bijective by
    // construction. They are also the start of any other tetrahedron whose two disks fold a triangle: from the folded
    // start, the mean-value least-squares iterations collapsed CGAL's tetrahedron.off onto two antipodal pairs; from
    // the centroid map they are stationary in 3 steps.
    if(m_tetrahedron.proven_no_balanced_map || (m_system.number_of_vertices == 4 && start.flipped_faces > 0))
    {
      tetrahedron_map(m_mesh.points, m_system.triangles, x);
      start = certify(m_system.triangles, x);
      m_result.initial_flipped_faces = start.flipped_faces;
      m_result.initial_guess.residual = compute_residuals(m_system, x).paper;
    }
    // Non-symmetric weights (mean value) have no exact solution in general: with the imbalance test their iterations
    // stop on the stationarity of the least-squares problem instead (summarize_stationarity).
    if(m_no_balanced_solution)
    {
      m_iteration_options.max_gauss_seidel_sweeps =
          start.flipped_faces == 0 ? 0 : std::min<std::size_t>(m_iteration_options.max_gauss_seidel_sweeps, 100);
      m_iteration_options.max_newton_sweeps =
          start.flipped_faces == 0 ? 0 : std::min<std::size_t>(m_iteration_options.max_newton_sweeps, 100);
      m_iteration_options.tolerance = 0.; // stop at the caps; no residual is the goal here
    }

    return true;
  }

  // The proofs that no bijective balanced map exists: a non-inscribable connectivity with positive weights, or a
  // tetrahedron whose weights are not of the form of inscribability.h (its proof is about the weights given: with
  // hold_weights the map may be balanced for held ones).
  void check_for_a_balanced_map()
  {
    m_inscribability = check_inscribability(m_system);
    if(!m_options.hold_weights)
      m_tetrahedron = check_tetrahedron_weights(
          m_system, std::max(1e-9, m_options.iterations.tuning.tetrahedron_margin * m_options.iterations.tolerance));
    m_no_balanced_solution = (has_positive_weights(m_system) && m_inscribability.proven_not_inscribable)
                             || m_tetrahedron.proven_no_balanced_map;
  }

  // Stages 2 and 3 from the initial guess in x.
  void iterate(std::vector<Vector3>& x)
  {
    CGAL::Real_timer stage;
    stage.start();
    // Stages 2 and 3, with what is left of the time budget: it bounds the whole call, and stage 1 (which every
    // returned map needs) runs to its end even when it alone takes longer.
    if(m_iteration_options.max_seconds >= 0.)
      m_iteration_options.max_seconds = std::max(0., m_iteration_options.max_seconds - m_options.call_clock.time());
    const std::vector<Vector3> initial_guess = x;
    Sphere_state state(m_system, x);
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
    const bool try_direct_newton =
        !m_cancelled && !m_no_balanced_solution && m_options.nonlinear_solver == Nonlinear_solver::GLOBAL_NEWTON
        && m_iteration_options.max_newton_sweeps > 0
        && (m_system.symmetric || m_iteration_options.convergence_test == Convergence_test::IMBALANCE);
    if(try_direct_newton)
    {
      direct_newton = m_system.symmetric ? full_newton_steps(state, m_iteration_options, iterations_clock)
                                         : least_squares_newton(state, m_iteration_options, iterations_clock);
      // A coarser level that failed here is left to the finer level's other paths, except the coarsest: nothing
      // coarser solves it, and the stages below balance such small meshes in hundredths of a second (CGAL's camel
      // refined once, under a coarsening tried on 2026-11-28: its level of 152 vertices failed Newton's full steps;
      // manual, Method).
      if(m_options.coarse_level && !direct_newton.converged
         && m_system.number_of_vertices >= m_options.iterations.tuning.multilevel_fallback_min_vertices)
      {
        m_iteration_options.max_gauss_seidel_sweeps = 0;
        m_iteration_options.max_newton_sweeps = 0;
      }
      m_cancelled = direct_newton.cancelled;
      m_system.regularized_tips = direct_newton.regularized_tips;
      if(!direct_newton.converged && !m_cancelled && !direct_newton.out_of_time)
        state.assign(initial_guess);
      if(m_iteration_options.max_newton_sweeps > direct_newton.sweeps)
        m_iteration_options.max_newton_sweeps -= direct_newton.sweeps;
      else
        m_iteration_options.max_newton_sweeps = 0;
    }
    const double direct_seconds = direct_clock.time();
    // The state goes back to the initial guess (the map kept where the minimization cannot run); the folded map is
    // kept for the minimization's start (least_distortion()).
    m_balanced_map_folded = direct_newton.balanced_map_folded && m_iteration_options.least_distortion_follows;
    if(m_balanced_map_folded)
      m_folded_balanced_map = std::move(direct_newton.folded_balanced_map);
    const bool direct_done = direct_newton.converged || direct_newton.out_of_time || m_balanced_map_folded;
    // The report the multilevel fallback reads: out of time on this path is out of time for it too (it started with
    // 5 s left and ran 17 s on vol2surf_lh_pial, mean-value weights).
    if(direct_newton.out_of_time)
      m_newton.out_of_time = true;

    stage.reset();
    Iteration_report gauss_seidel;
    if(!m_cancelled && !direct_done)
      gauss_seidel = projected_gauss_seidel(state, m_iteration_options, iterations_clock);
    else
      gauss_seidel.residual = direct_newton.converged ? direct_newton.residual : m_result.initial_guess.residual;
    m_cancelled = m_cancelled || gauss_seidel.cancelled;
    m_result.gauss_seidel.iterations = gauss_seidel.sweeps;
    m_result.gauss_seidel.residual = gauss_seidel.residual;
    m_result.gauss_seidel.seconds = stage.time();
    if(m_options.verbose)
      std::cerr << "stage 2: " << gauss_seidel.sweeps << " sweeps, Res " << gauss_seidel.residual
                << ", non-positive faces " << state.invalid_faces() << ", " << m_result.gauss_seidel.seconds << " s\n";

    stage.reset();
    if(!direct_done && !gauss_seidel.converged && !gauss_seidel.out_of_time && !m_cancelled
       && m_iteration_options.max_newton_sweeps > 0)
      m_newton = m_options.nonlinear_solver == Nonlinear_solver::LOCAL_NEWTON
                     ? local_newton(state, m_iteration_options, iterations_clock)
                     : global_newton(state, m_iteration_options, iterations_clock, &initial_guess, tutte_map());
    else
      m_newton.residual = gauss_seidel.residual;
    m_cancelled = m_cancelled || m_newton.cancelled;
    if(!m_balanced_map_folded && m_newton.balanced_map_folded && m_iteration_options.least_distortion_follows)
    {
      m_balanced_map_folded = true;
      m_folded_balanced_map = std::move(m_newton.folded_balanced_map);
    }
    if(!direct_done)
      m_system.regularized_tips = m_newton.regularized_tips;
    if(!direct_done && !m_newton.weight_holds.empty())
      hold_weights(x, m_newton.weight_holds);
    m_result.newton.iterations = m_newton.sweeps + direct_newton.sweeps;
    m_result.newton.linear_iterations = m_newton.linear_iterations + direct_newton.linear_iterations;
    m_result.newton.residual = m_balanced_map_folded && !direct_newton.converged ? gauss_seidel.residual
                               : direct_done                                  ? direct_newton.residual
                                                                              : m_newton.residual;
    m_result.newton.seconds = stage.time() + direct_seconds;
    m_result.rejected_moves = gauss_seidel.rejected_moves + m_newton.rejected_moves;
    m_result.continuation_parameter = m_newton.continuation_parameter;
    if(m_options.verbose)
      std::cerr << "stage 3: " << m_newton.sweeps << " sweeps, Res " << m_newton.residual << ", non-positive faces "
                << state.invalid_faces() << ", " << m_result.newton.seconds << " s\n";
  }

  // With hold_weights, where weights other than Tutte's are followed from Tutte's (global_newton: the weight
  // continuation), its start: Tutte's balanced map by the whole pipeline with uniform weights (the multilevel start
  // where it applies), which finds it where the two-disk guess alone does not (CGAL's bull: the path's start failed).
  std::function<bool(std::vector<Vector3>&)> tutte_map()
  {
    if(!m_options.hold_weights || m_options.weighting == Weighting::UNIFORM || !m_system.symmetric
       || m_iteration_options.convergence_test != Convergence_test::IMBALANCE)
      return {};
    return [this](std::vector<Vector3>& y) {
      if(m_options.verbose)
        std::cerr << "stage 3: Tutte's balanced map, the start of the path towards the weights requested\n";
      return compute_tutte_map(y);
    };
  }

  // Tutte's balanced map of this mesh by the whole pipeline with uniform weights; true when it is certified.
  bool compute_tutte_map(std::vector<Vector3>& y) { return uniform_map(m_mesh, m_system.triangles, false, y); }

  // Tutte's balanced map of the mesh of `mesh.points` and `triangles` (this mesh, or a coarser level of it: then
  // solved as the multilevel start's levels are, `coarse_level`).
  bool uniform_map(const Mesh_arrays& mesh, const std::vector<std::array<int, 3>>& triangles, bool coarse_level,
                   std::vector<Vector3>& y)
  {
    Sphere_system uniform = make_connectivity(triangles, mesh.points.size());
    if(&triangles == &m_system.triangles)
      uniform.vertex_order = m_system.vertex_order; // the same mesh: its order (elimination_rank())
    std::string message;
    if(assign_weights(uniform, mesh, Weighting::UNIFORM, {}, message) != Error_code::OK)
      return false;
    Pipeline_options uniform_options = m_options;
    uniform_options.weighting = Weighting::UNIFORM;
    uniform_options.admissible_weights = false;
    uniform_options.hold_weights = false;
    uniform_options.least_distortion = false;
    if(coarse_level)
    {
      uniform_options.coarse_level = true;
      uniform_options.iterations.tolerance = m_options.iterations.tuning.multilevel_coarse_tolerance;
    }
    const Result uniform_result = Sphere_mapper(mesh, uniform, uniform_options, m_solver).map(y);
    // A cancel there (the progress callback, the command line's SIGTERM) is this call's cancel.
    m_cancelled = m_cancelled || uniform_result.status == Error_code::CANCELLED;
    return uniform_result.status == Error_code::OK;
  }

  // Whether x passes this call's convergence test (balanced, or stationary for non-symmetric weights, or the paper's
  // Res) and the certificate.
  bool converged_and_bijective(const std::vector<Vector3>& x) const
  {
    const double tolerance = m_options.iterations.tolerance;
    const bool converged =
        m_iteration_options.convergence_test == Convergence_test::PAPER_RESIDUAL
            ? compute_residuals(m_system, x).paper < tolerance
            : (m_system.symmetric ? summarize_imbalance(m_system, x, tolerance)
                                  : summarize_stationarity(m_system, x, tolerance))
                  .balanced();
    return converged && certify(m_system.triangles, x).bijective;
  }

  // With least_distortion: where the map of the weights given did not converge (or is not bijective, or provably
  // cannot be balanced), the bijective map of least conformal distortion (stage3/least_distortion.h) from it, or from
  // Tutte's map where some of its faces are not positive in double precision. It replaces x only when certified.
  void least_distortion(std::vector<Vector3>& x)
  {
    // Not under the paper's criterion (its tolerance bounds Res, not a stationarity), nor past the time budget (Tutte's
    // map would cost a whole stage 1 more).
    // Non-symmetric weights (mean value) have no exact solution in general: their least-squares map, stationary, still
    // leaves vertices unbalanced, and it is replaced as an unconverged map is (unless it happens to be balanced). Its
    // iterations run before this only with hold_weights; otherwise map() skips them.
    // With stage 1 deferred (map()), x is empty: the start is the coarser levels', stage 1's map only where they give
    // none, and x stays empty where no map results (map() runs stage 1 then).
    if(m_cancelled || m_iteration_options.convergence_test != Convergence_test::IMBALANCE)
      return;
    // A balanced map of shape-preserving weights (not Tutte's, which do not keep shapes; not with hold_weights, whose
    // map is the one asked for), certified, is followed by the minimization too, and replaced by its map where that has
    // less angle error (replace_balanced_map). Balanced maps of cotangent weights are saddles of their energy, which
    // falls towards the maps that shrink the sphere to a point, and where along the three boosts the one reached sits
    // is fixed only by the discretization: CGAL's dragknob, balanced to 1e-10 and bijective, had 60 degrees of mean
    // angle error, its least-distortion map 3; c3d_igea 0.306 against 0.205, oded_springer 1.78 against 1.40 (the
    // boosts alone gave 0.206 and 1.41). Where the balanced map is the better one (the inscribed cubes, 0 degrees
    // against 4.5; star, cube-meshed, ellipsoid, sphere966, oded_wingnut), it stays.
    double balanced_distortion = -1.;
    if(!x.empty() && !m_no_balanced_solution && converged_and_bijective(x)
       && (m_system.symmetric || summarize_imbalance(m_system, x, m_options.iterations.tolerance).balanced()))
    {
      balanced_distortion = conformal_distortion(m_system.triangles, m_mesh.points, x);
      // F is infinite also where a 3D triangle has no shape (zero area: the minimization cannot run on the mesh).
      std::vector<least_distortion_detail::Face_shape> shapes;
      if(m_options.hold_weights || has_tutte_weights(m_system)
         || !least_distortion_detail::face_shapes(m_system.triangles, m_mesh.points, shapes))
        return;
      if(m_options.verbose)
        std::cerr << "least distortion: the balanced map reached has distortion " << balanced_distortion
                  << ": the minimization follows\n";
    }
    Iteration_options options = m_options.iterations;
    if(options.max_seconds >= 0.)
    {
      options.max_seconds -= m_options.call_clock.time();
      if(options.max_seconds <= 0.)
        return;
    }
    CGAL::Real_timer clock;
    clock.start();
    options.max_newton_sweeps = std::min(options.max_newton_sweeps, options.tuning.least_distortion_max_steps);
    // The mesh's fill-reducing order, the one its Newton systems share (elimination_rank(): computed already where a
    // level's Newton steps were factorized), taken when a minimization on the mesh starts (not before: where none
    // does, METIS' call would be lost time that cannot be interrupted): METIS' on large meshes, as the minimization's
    // own would be; small ones keep the minimization's own (METIS too, where elimination_rank() takes minimum degree).
    std::vector<int> vertex_rank;
    auto given_rank = [&]() -> const std::vector<int>* {
      if(m_system.number_of_vertices < nested_dissection_min_vertices)
        return nullptr;
      if(vertex_rank.empty())
        vertex_rank = elimination_rank(m_system);
      return &vertex_rank;
    };
    // A balanced map whose triangles keep their shape is the start: close to the minimum but along the boosts,
    // which the minimization balances first (bunny00 with cotangent weights: 3 boosts and 5 Newton steps, 0.9 s). One
    // squeezed beyond Solver_tuning::least_distortion_start_max_energy starts as an unbalanced map does.
    if(balanced_distortion >= 0. && balanced_distortion <= options.tuning.least_distortion_start_max_energy)
    {
      std::vector<Vector3> y = x;
      const Least_distortion_report report =
          minimize_conformal_distortion(m_system.triangles, m_mesh.points, y, options, clock, 0., given_rank());
      m_cancelled = m_cancelled || report.cancelled;
      if(m_options.verbose)
        std::cerr << "least distortion: from the balanced map, " << report.newton_steps << " Newton steps, "
                  << report.boosts << " boosts, distortion " << report.energy << ", max stationarity "
                  << report.max_stationarity << (report.stationary ? " (stationary)" : "") << ", " << clock.time()
                  << " s\n";
      m_result.newton.seconds += clock.time();
      replace_balanced_map(x, y, report, balanced_distortion);
      m_result.least_distortion_from_balanced_map = m_result.least_distortion_map;
      return;
    }
    // The start of lower distortion: the map reached, or the multilevel start (multilevel_least_distortion.h), or on
    // meshes too small for it Tutte's map (the maps where cotangent weights end often squeeze faces to the limits of
    // double precision, which a minimization of their shape cannot undo: CGAL's man ended at distortion 12,000 from
    // there after 110 s, 9.9 degrees of angle error from Tutte's map).
    double reached =
        x.empty() ? std::numeric_limits<double>::infinity() : conformal_distortion(m_system.triangles, m_mesh.points, x);
    // First from the folded balanced map that Newton's full steps reached, its folds repaired (stage3/fold_repair.h):
    // close to conformal but at its folds, it is a better start than the levels below give, which are then not
    // computed (bigbrain with cotangent weights: distortion 1.00166 against 1.0083, 7 s of levels saved). Only where
    // the repair leaves every face positive and the distortion is at most
    // Solver_tuning::least_distortion_start_max_energy (where cotangent weights squeeze thin parts to the
    // limits of double precision, the minimization cannot recover from their map: see the levels below); and where the
    // minimization from it ends short of stationary, or its map is not taken (take_least_distortion_map), with time
    // left, the levels' start is tried after all (with the time left: the budget counts from `clock`'s start).
    if(!m_folded_balanced_map.empty())
    {
      std::vector<Vector3> repaired;
      repaired.swap(m_folded_balanced_map); // not needed after this
      const Fold_repair_report repair =
          repair_folds(m_system, repaired, options.tuning.fold_repair_max_rounds);
      // The vertices moved sit where their rings' kernels are widest, not where their faces keep their shape: the
      // smoother of the levels' maps carried back removes that local error (bigbrain: the minimization's start at
      // stationarity 0.11 instead of 421, 4 Newton steps instead of 9).
      const int sweeps = repair.repaired ? smooth_conformal_distortion(
                                               m_system.triangles, m_mesh.points, repaired,
                                               options.tuning.least_distortion_max_smoothing_sweeps,
                                               options.tuning.least_distortion_smoothing_stall, options, clock)
                                         : 0;
      const double start_energy = repair.repaired ? conformal_distortion(m_system.triangles, m_mesh.points, repaired)
                                                  : std::numeric_limits<double>::infinity();
      const bool start_taken = start_energy <= options.tuning.least_distortion_start_max_energy;
      if(m_options.verbose)
        std::cerr << "least distortion: the folded balanced map, " << repair.folded_faces << " non-positive faces, "
                  << (repair.repaired ? "repaired" : "not repaired") << " by moving " << repair.moved_vertices
                  << " vertices in " << repair.rounds << " rounds, " << sweeps
                  << " sweeps of Gauss-Seidel: distortion " << start_energy
                  << (start_taken ? ", the start" : ", not a start") << "\n";
      if(start_taken)
      {
        const Least_distortion_report report =
            minimize_conformal_distortion(m_system.triangles, m_mesh.points, repaired, options, clock, 0., given_rank());
        m_cancelled = m_cancelled || report.cancelled;
        if(m_options.verbose)
          std::cerr << "least distortion: from the repaired balanced map, " << report.newton_steps
                    << " Newton steps, distortion " << report.energy << ", max stationarity "
                    << report.max_stationarity << (report.stationary ? " (stationary)" : "") << ", " << clock.time()
                    << " s\n";
        const bool stopped = report.cancelled || report.out_of_time || past_time_budget(options, clock);
        if(report.stationary || stopped)
        {
          take_least_distortion_map(x, repaired, report, reached);
          m_result.least_distortion_from_balanced_map = m_result.least_distortion_map;
          if(m_result.least_distortion_map || stopped)
          {
            m_result.newton.seconds += clock.time();
            return;
          }
        }
      }
    }
    std::vector<Vector3> y = x, other;
    Multilevel_least_distortion_report levels;
    const bool multilevel = multilevel_least_distortion_start(
        m_mesh.points, m_system.triangles,
        [this](const Mesh_arrays& coarse, std::vector<Vector3>& z) {
          return uniform_map(coarse, coarse.triangles, true, z) && !m_cancelled;
        },
        options, clock, other, levels);
    m_cancelled = m_cancelled || levels.cancelled;
    const bool stopped = levels.cancelled || levels.out_of_time;
    if(m_options.verbose)
      for(const Least_distortion_level& level : levels.levels)
        std::cerr << "least distortion: level of " << level.vertices << " vertices, " << level.newton_steps
                  << " Newton steps" << (level.stationary ? " (stationary)" : "") << ", " << level.seconds
                  << " s; carried back: " << level.smoothing_sweeps << " sweeps of Gauss-Seidel, "
                  << level.smoothing_seconds << " s\n";
    if(!multilevel && !stopped && !m_cancelled && !has_tutte_weights(m_system) && !past_time_budget(options, clock)
       && !compute_tutte_map(other))
      other.clear(); // only a certified Tutte's map is a start, as before the multilevel start
    if(!other.empty() && !m_cancelled)
    {
      const double from_other = conformal_distortion(m_system.triangles, m_mesh.points, other);
      if(m_options.verbose)
        std::cerr << "least distortion: distortion " << reached << " of the map reached, " << from_other << " of "
                  << (multilevel ? "the multilevel start" : "Tutte's map") << "\n";
      if(from_other < reached)
        y.swap(other);
    }
    if(y.empty())
    {
      if(stopped || m_cancelled || !two_disk_start(x))
        return;
      y = x;
      reached = conformal_distortion(m_system.triangles, m_mesh.points, x);
    }
    // The first step on the mesh is expected to take the last coarser level's, scaled (scaled_step_seconds: its
    // factorization cannot be interrupted); a coarser level stopped by the budget leaves no time for it.
    const double first_step_seconds =
        levels.levels.empty() ? 0. : scaled_step_seconds(levels.levels.back(), m_system.number_of_vertices);
    Least_distortion_report report; // the time budget counts from `clock`'s start, Tutte's map included
    if(!m_cancelled && !levels.out_of_time && !past_time_budget(options, clock))
      report = minimize_conformal_distortion(m_system.triangles, m_mesh.points, y, options, clock, first_step_seconds,
                                             given_rank());
    m_cancelled = m_cancelled || report.cancelled;
    if(m_options.verbose)
      std::cerr << "least distortion: " << (report.started ? "" : "not started, ") << report.newton_steps
                << " Newton steps, " << report.boosts << " boosts, distortion " << report.energy
                << ", max stationarity " << report.max_stationarity
                << (report.stationary ? " (stationary)" : "") << ", " << clock.time() << " s\n";
    m_result.newton.seconds += clock.time();
    if(balanced_distortion >= 0.)
      replace_balanced_map(x, y, report, balanced_distortion);
    else
      take_least_distortion_map(x, y, report, reached);
  }

  // The minimization's map y, followed from the balanced map x, replaces it only where stationary (a minimization
  // stopped short of it, by the budget or for want of a step lowering F, would turn a converged map into
  // NOT_CONVERGED) and of less angle error: F and the angle error disagree on faces large against the sphere (F's area
  // is measured by the sphere's orientation, a little more than the flat triangle's): the cube's balanced map,
  // inscribed, has no angle error but F = 1.11, its least-distortion map 4.5 degrees (F 1.09).
  void replace_balanced_map(std::vector<Vector3>& x, std::vector<Vector3>& y, const Least_distortion_report& report,
                            double balanced_distortion)
  {
    if(!report.started || !report.stationary)
    {
      if(m_options.verbose && report.started)
        std::cerr << "least distortion: its map is not stationary, the balanced map stays\n";
      return;
    }
    const double balanced_angle_error = angle_error(m_mesh.points, m_system.triangles, x).mean_degrees;
    if(!(angle_error(m_mesh.points, m_system.triangles, y).mean_degrees < balanced_angle_error))
    {
      if(m_options.verbose)
        std::cerr << "least distortion: its map has no less angle error than the balanced map, which stays\n";
      return;
    }
    take_least_distortion_map(x, y, report, balanced_distortion);
    if(m_result.least_distortion_map)
    {
      m_result.replaced_balanced_map_distortion = balanced_distortion;
      m_result.replaced_balanced_map_angle_error = balanced_angle_error;
    }
  }

  // The minimization's map y replaces x where it ran (a step taken, or a start found stationary), lowered the distortion
  // below `reached` (x's, or its own start's), and is certified: a start alone (no time left for a step) is no
  // least-distortion map.
  void take_least_distortion_map(std::vector<Vector3>& x, std::vector<Vector3>& y, const Least_distortion_report& report,
                                 double reached)
  {
    if(!report.started || (report.newton_steps == 0 && !report.stationary) || !(report.energy < reached)
       || !certify(m_system.triangles, y).bijective)
    {
      // With stage 1 deferred: the levels' start (or the minimization's last map) where certified, unbalanced and
      // reported so, rather than stage 1's.
      if(x.empty() && certify(m_system.triangles, y).bijective)
        x.swap(y);
      return;
    }
    x.swap(y);
    m_system.regularized_tips.clear(); // they belonged to the map replaced
    m_result.least_distortion_map = true;
    m_result.distortion_energy = report.energy;
    m_result.max_distortion_stationarity = report.max_stationarity;
    m_result.least_distortion_steps = report.newton_steps;
    m_result.distortion_vertices_at_rounding_floor = report.vertices_at_rounding_floor;
    m_least_distortion_stationary = report.stationary;
  }

  // The map is balanced for the weights requested except at the vertices held by the continuation: from here on the
  // system is the held one, so that the certificate and the figures are those of the equations the map solves.
  void hold_weights(const std::vector<Vector3>& x, const std::vector<double>& holds)
  {
    m_result.requested_weights_max_imbalance = summarize_imbalance(m_system, x, m_options.iterations.tolerance).max;
    const Sphere_system requested = m_system;
    blend_with_tutte(requested, 1., m_system, &holds);
    m_result.held_weight_vertices = 0;
    m_result.held_weight_parameter = 1.;
    for(double h : holds)
      if(h < 1.)
      {
        ++m_result.held_weight_vertices;
        m_result.held_weight_parameter = std::min(m_result.held_weight_parameter, h);
      }
  }

  // The certificate and the figures, recomputed from scratch on the final positions, the status and its message.
  void certify_and_report(const std::vector<Vector3>& x)
  {
    // Certificate and figures, recomputed from scratch on the final positions.
    const Residuals residuals = compute_residuals(m_system, x);
    const Sphere_certificate certificate = certify(m_system.triangles, x);
    m_result.residual = residuals.paper;
    m_result.max_tangential_residual = residuals.max_tangential;
    m_result.flipped_faces = certificate.flipped_faces;
    m_result.total_signed_area = certificate.total_signed_area;
    m_result.bijective = certificate.bijective;
    m_result.balanced_map_folded = m_balanced_map_folded;
    std::vector<double> imbalances;
    const Imbalance_summary imbalance = summarize_imbalance(m_system, x, m_options.iterations.tolerance, &imbalances);
    m_result.max_imbalance = imbalance.max;
    m_result.imbalance_percentile_99 = imbalance.percentile_99;
    m_result.vertices_at_rounding_floor = imbalance.vertices_at_rounding_floor;
    m_result.vertices_below_precision = imbalance.vertices_below_precision;
    m_result.regularized_tip_vertices = static_cast<std::size_t>(
        std::count(m_system.regularized_tips.begin(), m_system.regularized_tips.end(), char(1)));
    m_result.unbalanced_vertices = imbalance.unbalanced_vertices;
    m_result.convergence_test = m_iteration_options.convergence_test;
    Imbalance_summary stationarity;
    if(!m_system.symmetric)
    {
      stationarity = summarize_stationarity(m_system, x, m_options.iterations.tolerance);
      m_result.max_stationarity = stationarity.max;
      m_result.unstationary_vertices = stationarity.unbalanced_vertices;
    }
    const bool converged = m_result.least_distortion_map ? m_least_distortion_stationary
                           : m_iteration_options.convergence_test == Convergence_test::PAPER_RESIDUAL
                               ? m_result.residual < m_options.iterations.tolerance
                               : (m_system.symmetric ? imbalance : stationarity).balanced();
    m_result.status =
        !converged ? Error_code::NOT_CONVERGED : (certificate.bijective ? Error_code::OK : Error_code::NOT_BIJECTIVE);
    if(m_cancelled)
      m_result.status = Error_code::CANCELLED;
    if(m_no_balanced_solution && !m_result.least_distortion_map)
      m_result.status = Error_code::NO_BALANCED_SOLUTION;
    m_result.message = get_error_message(m_result.status);
    if(m_result.least_distortion_map)
    {
      std::ostringstream note;
      note << " [the bijective map of least conformal distortion (least_distortion), not a balanced map of the "
           << "weights given (max imbalance " << m_result.max_imbalance << "): distortion " << m_result.distortion_energy
           << ", max stationarity " << m_result.max_distortion_stationarity << " after "
           << m_result.least_distortion_steps << " Newton steps, " << m_result.flipped_faces << " flipped faces";
      if(m_result.replaced_balanced_map_distortion >= 0.)
        note << "; it replaced the balanced map reached, of distortion " << m_result.replaced_balanced_map_distortion
             << " and mean angle error " << m_result.replaced_balanced_map_angle_error << " degrees";
      note << "]";
      m_result.message += note.str();
    }
    if(!m_system.symmetric && m_iteration_options.convergence_test == Convergence_test::IMBALANCE
       && !m_result.least_distortion_map)
    {
      std::ostringstream note;
      note << " [non-symmetric weights: the test is the stationarity of their least-squares problem, max "
           << m_result.max_stationarity << "; their imbalance cannot reach the tolerance]";
      m_result.message += note.str();
    }
    if(m_no_balanced_solution && !m_result.least_distortion_map)
    {
      std::ostringstream details;
      if(m_tetrahedron.proven_no_balanced_map)
        details << " (proof, a tetrahedron: " << m_tetrahedron.reason << "). The map returned is the tetrahedron's "
                << "vertices seen from their centroid (or a regular tetrahedron where they are flat)";
      else
        details << " (proof: " << m_inscribability.independent_set_size << " of the " << m_system.number_of_vertices
                << " vertices are pairwise non-adjacent"
                << (2 * m_inscribability.independent_set_size == m_system.number_of_vertices
                        ? " and two of the others are adjacent"
                        : "")
                << "). The map returned is the initial guess (two Tutte disks, "
                << "Moebius inversion, stereographic projection)";
      details << (certificate.bijective
                      ? ", certified bijective"
                      : ", NOT bijective: " + std::to_string(certificate.flipped_faces) + " flipped faces")
              << ", not a balanced one";
      m_result.message += details.str();
    }
    else if(m_result.status != Error_code::OK && !m_result.least_distortion_map)
    {
      std::ostringstream details;
      details << " (max imbalance " << m_result.max_imbalance << ", " << m_result.unbalanced_vertices
              << " vertices above the tolerance, Res " << m_result.residual << ", " << m_result.flipped_faces
              << " flipped faces";
      if(m_result.continuation_parameter >= 0. && m_result.continuation_parameter < 1.)
        details << "; the balanced maps from Tutte's weights towards these could be followed only "
                << static_cast<int>(100. * m_result.continuation_parameter) << "% of the way";
      if(!m_system.symmetric)
        details << "; with non-symmetric weights the balance equations generally have no exact solution";
      else if(m_newton.stagnated)
        details << "; the residual stagnated";
      if(!m_options.admissible_weights && (!m_system.symmetric || m_result.continuation_parameter >= 0.))
        details << "; the admissible_weights named parameter may help";
      details << ")";
      m_result.message += details.str();
    }
  }

  const Mesh_arrays& m_mesh;
  Sphere_system& m_system;
  Pipeline_options m_options; // a copy: with least_distortion, map() shares the time budget out (least_distortion())
  const SolverTraits& m_solver;
  Result m_result;
  CGAL::Real_timer m_total;
  Iteration_options m_iteration_options; // m_options.iterations as this mesh's stages run them
  bool m_cancelled = false;
  bool m_stage_1_deferred = false; // to least_distortion(), which runs it only where its own start fails
  bool m_no_balanced_solution = false; // proven: no bijective balanced map exists (m_inscribability, m_tetrahedron)
  Inscribability_check m_inscribability;
  Tetrahedron_weights_check m_tetrahedron;
  Iteration_report m_newton;
  double m_multilevel_newton_seconds = 0.;
  bool m_least_distortion_stationary = false;
  bool m_multilevel_tried = false; // the multilevel start came first (multilevel_applies): no fallback to it
  // With least_distortion: Newton's full steps reached a balanced map of the weights given that is folded
  // (Iteration_report::balanced_map_folded); the other ways to a balanced map are skipped.
  bool m_balanced_map_folded = false;
  std::vector<Vector3> m_folded_balanced_map; // that map, where m_balanced_map_folded (a start of least_distortion())
  // Last: destroyed first, it waits for its thread, which reads m_system.
  Laplacian_preconditioner_ahead m_preconditioner_ahead;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_MAPPER_H
