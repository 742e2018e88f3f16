// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The tuning constants of stages 2 and 3 in one place, each with the evidence it was chosen on. They are fields (not
// constants) so that a test or an experiment can change one without editing the solvers; the package's calls always
// use the defaults. "The 66 meshes" are CGAL's 48 closed genus-0 sample meshes and the 18 of ../shared/meshes.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_TUNING_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_TUNING_H

#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Solver_tuning
{
  // --- The multilevel start (spherical_parameterize.h) ---
  // Meshes from this many vertices on start from a coarser mesh (Tutte's weights, global solver).
  std::size_t multilevel_min_vertices = 20000;
  // The same for symmetric weights other than Tutte's (cotangent, admissible ones, the user's): their coarser levels
  // are solved with Tutte's weights, and their two-disk path is the slower and less reliable from a few hundred
  // vertices on. CGAL's 48 meshes and ../shared's 18 with admissible cotangent weights (2026-11-27): camel converges
  // (1.4 s) where its two disks did not in 60 s; c3d_cheburashka 0.3 s instead of 48 s, and its angle error 6.9 degrees
  // instead of 77 (its two disks led to a nearly degenerate balanced map; spool likewise, 2.6 instead of 69);
  // homer 0.2 s where it ended unconverged; slower: bear_bis and bull (0.2 s to 1.1 s).
  std::size_t multilevel_min_vertices_other_weights = 200;
  // Of 1/2, 1/4, 1/8 of the vertices and 3, 10 smoothing sweeps, 1/4 with 10 sweeps was the most even on bunny00 and
  // armadillo Loop x2 (1/2 took 52 steps on bunny00 once); 30 or 60 sweeps did not lower the Newton steps.
  double multilevel_coarsening_ratio = 0.25;
  // Where the multilevel start of the mesh given fails, it is tried once more through levels of this ratio
  // (Sphere_mapper; coarser levels are not retried): as the first choice it cost bunny00 1.6 s instead of 1.05 s and
  // man refined once 2.5 s instead of 1.9 s; as the retry, CGAL's camel and u refined twice converge (8.7 s and 2 s)
  // where the ratio 1/4 failed.
  double multilevel_retry_coarsening_ratio = 0.5;
  // Smaller meshes where the two-disk path ends unconverged try the multilevel start as well (Sphere_mapper); below
  // this size its coarser level would be a handful of vertices. Also the size from which a coarser level of the
  // multilevel start is itself solved from its own coarser level first (the two-disk path as its fallback); a coarser
  // level below it is the coarsest, and keeps stages 2 and 3 as its fallback (Sphere_mapper).
  std::size_t multilevel_fallback_min_vertices = 200;
  // Where the fast ways end unconverged on the mesh given with symmetric positive weights (whose balanced map is
  // bijective), the two-disk guesses of this many other METIS partitions are tried (seeds seed + 1, seed + 2, ...),
  // each with Newton's full steps only (Sphere_mapper::fast_ways_first). The path to the balanced map depends
  // on the partition: CGAL's part.off (175 vertices) ended unconverged with 50 of the seeds 0 to 124; with 6 retries
  // all 125 converge, the worst after 4.
  std::size_t partition_retries = 6;
  std::size_t multilevel_smoothing_sweeps = 10;
  // The coarser levels stop at this largest imbalance, whatever the user's tolerance. The boosts change the
  // imbalances only slightly, so a level stopped at 1e-6 may sit a boost away from its balanced map, and the finer
  // level's steps start from that: bunny00's finest level took 29 Newton steps (6.2 s) from a level stopped at
  // 6.4e-7, 6 from one stopped at 1e-8. Newton's last step on a level usually lands far below 1e-6 anyway. Not
  // tighter with a tighter tolerance: a coarser level's map is only where the finer level starts, its interpolation
  // error (imbalances near 1e-2) dwarfs 1e-8, and a map stopped elsewhere sends the finer levels on other paths
  // (bunny00 at 1e-10: 4.8 s when its levels stopped at 1e-10, 0.78 s now, the default's path plus one step).
  double multilevel_coarse_tolerance = 1e-8;

  // --- Newton's linear systems (mobius_newton.h) ---
  // MINRES with the multigrid preconditioner from this many vertices on, a sparse factorization below. Per Newton
  // step (2 threads): a factorization costs 0.02 s at 3k vertices, 0.3 s at 38k (bunny00), 7 s at 134k (igea) with
  // Eigen's simplicial LDLT and 1 to 1.5 s with the supernodal one (from nested_dissection_min_vertices), like n^1.5;
  // MINRES 0.05 to 0.1 s at 38k, like n. On small meshes with thin parts the exact step is the more robust
  // (CGAL's cow and hand: 1e-2-inexact steps from the initial guess end on a folded balanced map). With negative
  // weights, steps whose forcing is below newton_max_forcing may factorize (newton_factorize_after_minres_iterations).
  std::size_t iterative_newton_min_vertices = 8000;
  // With CGAL::Parallel_tag, the Newton steps compute independent quantities at the same time (the boosts' Jacobian
  // beside their energy and gradient, the line searches' tests beside their merits: side_by_side.h) from this many
  // vertices on; below, handing the work to another thread costs about what it saves.
  std::size_t side_by_side_min_vertices = 10000;
  // Inexact Newton (Eisenstat and Walker's second forcing term): the linear residual is reduced by
  // eta_k = 0.9 (Res_k / Res_{k-1})^2 within these bounds (looser steps, 0.1 or 0.3, wander on igea and man). A step
  // the line search rejects is solved again with the smallest forcing before the phase gives up (negative weights:
  // before the rest of the phase factorizes).
  double newton_max_forcing = 1e-2;
  double newton_min_forcing = 1e-8;
  // When the step can be the last one (mobius_newton.h, last_step_forcing), the forcing is at most this over the
  // distance to the test: in the last steps on bunny00 the worst imbalance fell by 6 to 8 times the relative residual
  // that MINRES reached, so a hundredth leaves a margin, for 3 to 7 more MINRES iterations.
  double newton_last_step_forcing = 1e-2;
  // Uniform weights take 2 to 20 MINRES iterations at the forcing, about 60 at the smallest one; an iterate of
  // MINRES stopped early is still a descent step, and the line search judges it. With negative weights (from a map
  // carried back), reaching the cap makes the rest of the phase factorize.
  int newton_max_minres_iterations = 200;
  // With weights of either sign, a step whose forcing is below newton_max_forcing factorizes when the last MINRES
  // solve took more than this many iterations, or the map has folded faces (mobius_newton.h): about what one
  // factorization costs on the meshes where MINRES then needed hundreds (c3d_igea's 134k vertices: 1 to 1.5 s, 35 to
  // 45 iterations).
  int newton_factorize_after_minres_iterations = 30;

  // --- Newton's steps (mobius_newton.h, global_newton.h) ---
  // Newton's full steps through folds are given this many iterations: the meshes of the 66 that converge this way
  // need at most about 20.
  std::size_t free_newton_patience = 30;
  // With weights of either sign, they stop after this many steps in a row cut short by the line search on the same
  // number of folded faces, where the folds are local and the rest of the map nearly balanced (mobius_newton.h): the
  // balanced map they approach, linearly, is folded.
  std::size_t free_newton_damped_fold_steps = 3;
  // Through folds, where no step lowers the merit, a step is accepted that lowers the largest of the merits of the
  // last this many iterates (a non-monotone line search, Grippo, Lampariello and Lucidi, used as a watchdog), with
  // Tutte's weights (1 turns it off): paths through folds lower the merit only on the whole. Without it CGAL's camel
  // refined twice ended unconverged: on its level of 156,290 vertices the full steps went through 110,000 folded
  // faces and at the fourth step no step lowered Res; with it, one such step, then the usual ones converge there.
  std::size_t free_newton_nonmonotone_window = 5;
  // The bijectivity-preserving steps give up after this many steps in a row cut below `short_step`.
  std::size_t cautious_patience = 3;
  // The cap of Newton steps of the least-distortion minimization (least_distortion.h), far above what it takes: at
  // most 83 (CGAL's u) on the meshes of the corpus where it runs (the manual's Method section).
  std::size_t least_distortion_max_steps = 2000;
  // Its Marquardt shift (relative to the unit diagonal) falls after full steps down to this floor. The floor caps the
  // steps along directions flatter than it; with the boosts balanced apart and the gradient's digits kept, 1e-12
  // (the shift always added) takes CGAL's camel to its minimum in 45 steps, 490 with a floor of 1e-8; 1e-14 left
  // triceratops at stationarity 2.4e-6, where no step lowered F above its rounding (the manual's Method section).
  // Lowered during a minimization only where it caps the steps (least_distortion.h, since 2026-12-02).
  double least_distortion_marquardt_floor = 1e-12;
  // Its boosts (balance_distortion_boosts): before the first step and after each one, at most this many Newton
  // iterations on the three boost parameters, while the decrease of F they predict exceeds this share of what the
  // step itself achieved.
  int least_distortion_boost_iterations = 3;
  double least_distortion_boost_share = 0.01;
  // Its multilevel start (multilevel_least_distortion.h): meshes of at least this many vertices over the coarsening
  // ratio get coarser levels, the coarsest of at least this many (CGAL's man coarsened to 273 vertices had slivers
  // whose minimum was not reached in 2,000 steps; at 1,093 it took 35); each coarser level's minimization stops at this
  // stationarity or this many steps (it only needs to settle the map's global shape: on vol2surf_lh_pial the mesh's
  // tolerance cost 14 s on two levels); vertices carried back get sweeps of nonlinear Gauss-Seidel until one lowers F
  // by at least this share of what the sweep before did (smooth_conformal_distortion), at most this many.
  std::size_t least_distortion_coarsest_vertices = 1000;
  std::size_t least_distortion_coarse_max_steps = 100;
  double least_distortion_coarse_tolerance = 1e-4;
  double least_distortion_smoothing_stall = 0.7;
  int least_distortion_max_smoothing_sweeps = 100;
  // Its start from a folded balanced map (fold_repair.h): at most this many rounds of moves around the folds. That
  // map repaired, or a balanced map, is the start where its distortion is at most this (the levels' starts measured
  // 1.003 to 1.017, the repaired balanced maps 1.002 to 1.013, 31 of the 44 bijective balanced cotangent maps of the
  // 66 meshes 1.00003 to 1.089; maps whose thin parts are squeezed to the limits of double precision are far above:
  // CGAL's dragknob 6.5e10, oblong 6.6e5, which start as unbalanced maps do; the inscribed cubes 1.11, star 1.49).
  int fold_repair_max_rounds = 10;
  double least_distortion_start_max_energy = 1.1;
  // With a time budget, the ways to the balanced map of weights other than Tutte's get this share of it when the
  // minimization follows them; the minimization gets the rest (the large meshes' attempts took the whole 60 s before:
  // CGAL's horse and Oded's scorpion never reached the minimization).
  double least_distortion_balance_share = 0.5;
  double short_step = 0.25;
  // Line searches halve the step down to these lengths (Moebius-aware Newton, cautious Newton, boosts).
  double newton_min_step = 1e-3;
  double cautious_min_step = 1e-6;
  double boost_min_step = 1e-3;
  // When no step is acceptable, this many of the paper's local Newton sweeps move the iterate.
  int local_sweeps_without_step = 5;           // Moebius-aware Newton
  int cautious_local_sweeps_without_step = 20; // cautious Newton

  // --- Arm tips below double precision (tip_regularization.h) ---
  // A balanced map whose non-positive faces all touch vertices with a mean chord below tip_scale has its tips (the
  // regions below tip_scale around those faces) solved again with weights that fall by tip_weight_ratio_per_ring per
  // ring from the third ring in, placed by one linear solve with the band below tip_band_scale around them. On the
  // thin-arms surfaces of the corpus, 2e-2 keeps the smallest tip edges at 4e-14 to 1e-13 (from below 1e-17) with
  // no fold; starting the decay at the first ring folded faces next to the rest of the mesh.
  double tip_scale = 1e-9;
  double tip_weight_ratio_per_ring = 2e-2;
  double tip_band_scale = 1e-6;

  // --- The boosts (mobius.h) ---
  // Before each Newton step the boosts are balanced until |g| <= boost_target_factor * Res * n (small next to the
  // residual forces that the step removes), at most `boost_max_iterations` Newton steps on the boost parameters,
  // each at most `boost_max_step` long (a boost of tanh(1) = 0.76 already squeezes half the sphere into a cap).
  double boost_target_factor = 1e-3;
  std::size_t boost_max_iterations = 8;
  double boost_max_step = 1.;
  // On the multilevel levels (Boost_aim::ROOT) a Newton step drops its boost part, except where the balancing before
  // it did not settle (no root of the boost equations near the map): then the step's boost part is applied, at most
  // boost_max_step long (mobius_newton.h). With Tutte's weights (false turns it off), where it was measured: bunny00
  // 0.46 of the time; for other weights it is off, on their coarser levels too (which inherit this tuning), as for
  // the watchdog above: their Tutte maps changed, and the cotangent paths from them lost oded_hammer and c3d_igea.
  bool boost_step_part_where_unsettled = true;

  // --- Stagnation: stop when the convergence measure (the worst imbalance over its allowance, or Res) fell by less
  // than 1 - stagnation_ratio over the window ---
  double stagnation_ratio = 0.99;
  std::size_t newton_stagnation_window = 50;    // Moebius-aware Newton: full steps that lower Res without balancing
  std::size_t cautious_stagnation_window = 200; // cautious Newton: non-symmetric weights level off at a floor
  std::size_t local_stagnation_window = 1000;   // the paper's local Newton

  // --- Levenberg-Marquardt steps of the cautious Newton (non-symmetric weights) ---
  double marquardt_initial = 1e-6; // relative shift of J^T J
  double marquardt_max = 1e6;
  int marquardt_attempts = 6;
  double cautious_damping = 1e-10; // relative diagonal shift against the rotations (symmetric weights)

  // --- Held weights (weight_continuation.h): where the path of balanced maps from Tutte's weights ends ---
  // The path ends when its step in s falls below hold_min_step; then the vertices moving fastest along it (in their
  // own scale, at least hold_velocity_fraction of the fastest: near a turning point the velocity is the Jacobian's
  // null vector) are held, with one ring around them. After a step of at most hold_predict_max_step, the faces whose
  // shape, extrapolated linearly in s, degenerates within hold_predict_factor steps are held before the step.
  // Each attempt at a parameter first takes up to hold_free_steps of Newton's full steps (through folds, kept when
  // they end balanced and bijective: from the Tutte map of CGAL's bull, whose legs are squeezed to edges of 1e-11,
  // the steps that keep every triangle positive failed even at s = 0.008), then gives up after hold_patience short
  // steps in a row (20 without holding: a failed attempt cost up to 20 steps, triceratops 24 s instead of 12 s).
  double hold_min_step = 1e-2;
  double hold_velocity_fraction = 0.2;
  double hold_predict_max_step = 0.05;
  double hold_predict_factor = 1.5;
  std::size_t hold_free_steps = 8;
  std::size_t hold_patience = 5;
  std::size_t max_holds = 40;

  // --- The interior-point iterations (constrained_balance.h) where the weight continuation ends ---
  // The first barrier parameter: the path's last map is balanced for other weights, and its imbalances under the
  // target weights are of order 0.1 to 1 (homer, cow, triceratops), so a barrier force of 1% of the spring scale
  // leaves them to Newton. Each phase divides it by barrier_reduction, down to a hundredth of the tolerance.
  double barrier_first_parameter = 1e-2;
  double barrier_reduction = 10.;
  // A phase ends after this many steps in a row cut below a quarter (the constrained case: cow's steps, cut to
  // 1e-7 and below, ran 121 times without progress).
  std::size_t barrier_patience = 5;
  // A phase is solved until max_i |grad_i Phi_mu| / l_i <= barrier_phase_factor * mu (the barrier's own forces are up
  // to mu l_i: tighter is wasted on a phase that is left anyway); the last phase, at mu = barrier_final_fraction times
  // the tolerance (barrier forces far below it), to the tolerance.
  double barrier_phase_factor = 10.;
  double barrier_final_fraction = 1e-2;
  // The least-squares iterations (imbalance_least_squares.h) use the constants above for their barrier phases,
  // each at most this many steps (Gauss-Newton's steps of a barrier phase crawl where many vertices stay far from
  // balanced: triceratops with mean-value weights, hundreds of steps at mu = 1e-2 for a stationarity of 0.18).
  std::size_t least_squares_phase_steps = 30;
  // The plain Gauss-Newton steps (one sparse LU each) give way to Marquardt's (a Cholesky factorization of J^T J)
  // once the worst stationarity has not halved in this many steps.
  std::size_t least_squares_plain_window = 5;
  // The plain steps by GMRES with the multigrid (krylov_gauss_newton_step()) instead of one sparse LU each, from this
  // many vertices on: measured time per step, GMRES against the LU, 0.20 s against 0.15 s at 6.7k vertices
  // (c3d_cheburashka), 0.16 s against 0.30 s at 10k (bear_bis), 0.45 s against 1.05 s at 38k (bunny00).
  std::size_t least_squares_krylov_vertices = 10000;
  // Their inexact-Newton forcing term, on the linear model's gradient (Eisenstat and Walker's choice 2:
  // gamma (|g_k| / |g_k-1|)^2, safeguarded), within bounds.
  double krylov_forcing_gamma = 0.9;
  double krylov_max_forcing = 0.1;
  double krylov_min_forcing = 1e-6;
  // The relative residual of the three transposed solves that refine the left null space at each step: each step
  // starts from the previous one's, so the error still shrinks step after step (bunny00: 1e-3 and 1e-2 take the
  // same 18 steps, 1e-2 a sixth fewer GMRES iterations; 1e-1 two steps more).
  double krylov_left_tolerance = 1e-2;
  int krylov_max_iterations = 300;
  // GMRES(30) stagnated on the transposed solves of oded_hammer (715 iterations in one step); GMRES(60) does not.
  int krylov_restart = 60;

  // --- Proofs that no balanced map exists (inscribability.h) ---
  // The tetrahedron's condition on its weights counts as failed where it fails by more than this many times the
  // tolerance (relatively): the regular tetrahedron's imbalance under weights whose products of opposite edges
  // differ by 2e-6 is 6.7e-7, within the default tolerance; a difference of ten times the tolerance puts every map
  // that passes the test within a few times the tolerance of flat.
  double tetrahedron_margin = 10.;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_TUNING_H
