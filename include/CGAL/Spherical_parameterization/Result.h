// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// What spherical_parameterize() reports.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H

#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/enum.h>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Figures of one stage of the method.
struct Stage_statistics
{
  /// Stage 1: the pairs of disks embedded (1, or more when the disk solver failed and Eigen's sparse LU was tried,
  /// or when the weights folded the disks and Tutte's were tried; 0 with the multilevel start, whose levels are in
  /// `Result::levels`, unless it came as the fallback after the two-disk path: then that path's). Stage 2: the sweeps
  /// over the vertices. Stage 3: the iterations of the `nonlinear_solver`
  /// (Newton steps, or the local Newton's sweeps over the vertices).
  std::size_t iterations = 0;
  double seconds = 0.;               ///< Wall-clock time of the stage.
  /// The paper's `Res` at the end of the stage (-1 when not computed); with the multilevel start, stage 1's is that
  /// of the map carried back after the smoothing sweeps (stage 2's).
  double residual = -1.;
  /// Stage 3: MINRES iterations of Newton's iterative linear solves (0 when every system was factorized; the GMRES
  /// iterations of the least-squares steps of non-symmetric weights are not counted).
  std::size_t linear_iterations = 0;
};

/// \ingroup PkgSphericalParameterizationRef
/// Figures of one level of the multilevel start (`Result::levels`).
struct Level_statistics
{
  std::size_t vertices = 0;          ///< Vertices of the level's mesh.
  std::size_t newton_steps = 0;      ///< Newton steps on this level (from the map carried up from the level below).
  std::size_t linear_iterations = 0; ///< MINRES iterations of those steps (0 when the systems were factorized).
  double seconds = 0.;               ///< Wall-clock time of this level alone (coarsening, carrying up, Newton).
};

/// \ingroup PkgSphericalParameterizationRef
/// The outcome of `spherical_parameterize()`. Figures that were not computed (after an input error) keep their
/// default values: -1 for residuals, 0 for counts and times.
struct Result
{
  Error_code status = Error_code::OK; ///< `Error_code::OK` only when converged and certified bijective.
  std::string message;                ///< Human-readable explanation, with figures for input errors.

  /// The paper's residual \f$ Res = \frac{1}{n} \sqrt{\sum_i \| \alpha_i x_i - \sum_j w_{ij} x_j \|^2} \f$ with the
  /// weights of each vertex normalized to sum to one and \f$ \alpha_i = x_i \cdot \sum_j w_{ij} x_j \f$ (its
  /// least-squares value).
  double residual = -1.;
  double max_tangential_residual = -1.; ///< `max_i |alpha_i x_i - sum_j w_ij x_j|` (same normalization).

  /// The largest imbalance \f$ e_i = |t_i| / \sum_j |w_{ij}| s(|x_j - x_i|) \f$ over the vertices (see
  /// `Convergence_test::IMBALANCE`): how far a vertex is from the balance point of its neighbours, in units of its
  /// own neighbourhood. The default convergence test is `max_imbalance <= tolerance`, except at vertices whose
  /// rounding floor is larger, over the vertices tested (see `vertices_below_precision`).
  double max_imbalance = -1.;
  double imbalance_percentile_99 = -1.; ///< The 99th percentile of the imbalances \f$ e_i \f$.
  /// Vertices whose neighbourhood is so small (a weighted mean chord below about 3e-9 with the default tolerance)
  /// that positions rounded to double carry an imbalance above the tolerance:
  /// \f$ 8 \cdot 2 \sqrt{3} \, 2^{-53} \sum_j |w_{ij}| / \sum_j |w_{ij}| \, |x_j - x_i| \f$ (chords), their rounding
  /// floor. The imbalance test holds them to that floor instead of the tolerance. The floor depends on that mean
  /// chord only; where it would exceed 1/2 the vertex is below double precision (`vertices_below_precision`).
  std::size_t vertices_at_rounding_floor = 0;
  /// Vertices below double precision: all their neighbours within about 28 ulps of them (a weighted mean chord below
  /// \f$ 8 \cdot 2 \sqrt{3} \, 2^{-53} / (1/2) \approx 6.2 \cdot 10^{-15} \f$), where the balanced map shrinks the tips of
  /// long thin arms below 1e-16 and positions coincide as doubles. Their balance cannot be told from rounding: they
  /// are counted here and not tested (nor in `max_imbalance`); every vertex around them is. The certificate covers
  /// them like every other vertex. For non-symmetric weights the test is the stationarity (`max_stationarity`),
  /// which has a floor of its own and still tests them.
  std::size_t vertices_below_precision = 0;
  /// Vertices of arm tips whose balanced positions lie below double precision, so that the balanced map rounded to
  /// double has non-positive triangles there: they were solved with weights that fall by a constant factor per ring
  /// towards the tip, which keeps it orders of magnitude above rounding and bijective, and are counted in
  /// `vertices_below_precision`, not tested. Every other vertex keeps its own equation and is tested. 0 on most
  /// meshes (the manual's "Converged" section).
  std::size_t regularized_tip_vertices = 0;
  /// Symmetric weights other than Tutte's (cotangent) whose balanced maps, followed from Tutte's weights, end
  /// before the weights requested (a triangle degenerates, or the path turns back): the vertices whose weights were
  /// held on the way, so that the others could go on. A held vertex \f$i\f$ keeps the blended weights
  /// \f$(1 - s_{ij}) + s_{ij} w_{ij}\f$, \f$s_{ij} = \min(h_i, h_j)\f$, of the parameter \f$h_i < 1\f$ where it was
  /// held; every other edge has the weight requested. The map is balanced for those weights (`max_imbalance` and
  /// the convergence test are theirs) and certified like any other; `requested_weights_max_imbalance` is its largest
  /// imbalance under the weights requested. 0 when the map is balanced for the weights requested (the manual's
  /// "Converged" and Method sections).
  std::size_t held_weight_vertices = 0;
  double held_weight_parameter = 1.; ///< The smallest \f$h_i\f$ of the held vertices (1 when none is held).
  /// The largest imbalance under the weights requested when weights were held (`held_weight_vertices` > 0); -1
  /// otherwise (then `max_imbalance` is under the weights requested).
  double requested_weights_max_imbalance = -1.;
  /// With the named parameter `least_distortion` (the default for cotangent and mean-value weights): the map returned
  /// is the bijective map of least conformal distortion (not a balanced map of the weights given, whose figures
  /// `max_imbalance` and the others still report), because those weights' map ended unbalanced or not bijective
  /// (their slow ways, among them the cautious Newton, are then left out, unless `hold_weights` was given too), or
  /// balanced but with more angle error than the minimum (`replaced_balanced_map_distortion`). Then
  /// the convergence test is the stationarity of that minimum: `max_distortion_stationarity` at most the tolerance
  /// (or its rounding floor) at every vertex.
  bool least_distortion_map = false;
  /// With the named parameter `least_distortion` (and without `hold_weights`): Newton's full steps reached a map
  /// balanced for the weights given (symmetric weights other than Tutte's: cotangent, admissible, the user's), or
  /// approached one linearly with the rest of the map nearly balanced, that has
  /// non-positive faces beyond arm tips below double precision, so the other ways to a balanced map were skipped and
  /// the minimization followed at once (the manual's Method section: such a map is where those weights lead; the
  /// other ways rarely find another one, and take most of the time). It can be true while `least_distortion_map` is
  /// false (the minimization was cancelled, ran out of time, or did not lower the distortion). False otherwise.
  bool balanced_map_folded = false;
  /// When `least_distortion_map`: the minimization started from the balanced map of the weights given, not from its
  /// own coarser levels (the manual's Method section): with `balanced_map_folded`, from that folded map, its folds
  /// repaired (the vertices of its non-positive faces moved into their rings' kernels, then smoothed); with
  /// `replaced_balanced_map_distortion`, from that balanced map (where its distortion is at most 1.1). False
  /// otherwise.
  bool least_distortion_from_balanced_map = false;
  /// When `least_distortion_map` although the map of the weights given was balanced and certified: that map's
  /// conformal distortion (as `distortion_energy` measures it). With `least_distortion`, a balanced map of
  /// shape-preserving weights is followed by the minimization and replaced by its map where that is stationary and has
  /// less mean angle error (`replaced_balanced_map_angle_error`): balanced maps of cotangent weights can sit far along
  /// the boosts, their faces squeezed (the manual's Method section). -1 otherwise.
  double replaced_balanced_map_distortion = -1.;
  /// With `replaced_balanced_map_distortion`: the mean angle error of that balanced map, in degrees, as
  /// `measure_spherical_distortion()` measures it (more than the map returned has). -1 otherwise.
  double replaced_balanced_map_angle_error = -1.;
  /// The conformal distortion of the map returned when `least_distortion_map`: the mean, weighted by 3D area, of
  /// \f$(\sigma_1^2 + \sigma_2^2) / (2 \sigma_1 \sigma_2)\f$ over the affine maps from each 3D triangle to the flat
  /// triangle through its sphere points, each term measured with the area signed by the sphere's orientation (so a
  /// little more on faces large against the sphere): about 1 when every small triangle keeps its shape; -1 otherwise.
  double distortion_energy = -1.;
  /// When `least_distortion_map`: the largest stationarity of that minimum over the vertices (the manual's
  /// "Converged" section defines it; vertices within their rounding floor count as 0); -1 otherwise.
  double max_distortion_stationarity = -1.;
  /// When `least_distortion_map`: the Newton steps of that minimization; 0 otherwise.
  std::size_t least_distortion_steps = 0;
  /// When `least_distortion_map`: the vertices whose stationarity is above the tolerance but within their rounding
  /// floor (the manual's "Converged" section: positions rounded to double cannot promise less), which count as
  /// stationary; 0 otherwise.
  std::size_t distortion_vertices_at_rounding_floor = 0;
  /// The map comes from the multilevel start tried after the two-disk path ended unconverged on a mesh below the
  /// multilevel size (the manual's Method section); `levels` then describes it.
  bool multilevel_fallback = false;
  /// Symmetric positive weights only: how many other METIS partitions were tried after the fast ways from the first
  /// (Newton's full steps, the multilevel fallback) ended unconverged (at most 6, `Solver_tuning::partition_retries`;
  /// the manual's Method section); 0 when none was needed.
  std::size_t partition_retries = 0;
  /// The METIS seed of the partition whose two-disk guess led to the map returned: the seed given
  /// (`metis_seed`), or a later one when a partition retry converged.
  int partition_seed = 0;
  /// Vertices whose imbalance exceeds the tolerance (or their rounding floor, where it is larger), vertices below
  /// double precision excepted; 0 when balanced.
  std::size_t unbalanced_vertices = 0;
  /// Non-symmetric weights (mean value) only, whose balance equations generally have no exact solution: the largest
  /// stationarity \f$ \sigma_k \f$ of their least-squares problem \f$ \min \frac{1}{2} \sum_i e_i^2 \f$ (the imbalances
  /// themselves; \f$ \sigma_k \f$ is the length of its gradient at vertex \f$ k \f$ over the size of its terms, see the
  /// manual's "Converged"). For them the default test is `max_stationarity <= tolerance` instead of the imbalance;
  /// -1 for symmetric weights.
  double max_stationarity = -1.;
  std::size_t unstationary_vertices = 0; ///< Vertices whose stationarity exceeds the tolerance (non-symmetric weights).
  Convergence_test convergence_test = Convergence_test::IMBALANCE; ///< The test the iterations stopped on.

  std::size_t flipped_faces = 0; ///< Spherical triangles with `orientation(ORIGIN,p,q,r) != POSITIVE` (exact).
  double total_signed_area = 0.; ///< Sum of the signed spherical areas (4 pi when bijective).
  bool bijective = false;        ///< No flipped face and a generic point covered once (exact predicates).

  /// Stage 1: separator, two disks, Moebius, stereographic projection. Not run (`iterations` 0, `levels` empty) where
  /// the least-distortion minimization starts from its own coarser levels (meshes of 4,000 vertices and more) at once:
  /// with non-symmetric weights, and with cotangent weights where the multilevel start ended unbalanced; its time
  /// counts in `newton`.
  Stage_statistics initial_guess;
  Stage_statistics gauss_seidel;  ///< Stage 2: projected Gauss-Seidel while `Res` decreases.
  Stage_statistics newton;        ///< Stage 3: the `nonlinear_solver` until the `convergence_test` holds.
  double total_seconds = 0.;      ///< Wall-clock time of the whole call, input checks included.
  /// The multilevel start (named parameter `multilevel`), coarsest level first, the input mesh last; empty when the
  /// paper's two-disk guess on the input mesh was used. The coarsest level is solved by stages 1 to 3; its
  /// figures are in `initial_guess`, `gauss_seidel` and `newton` only when no level above it was solved.
  std::vector<Level_statistics> levels;

  std::size_t number_of_vertices = 0;          ///< Vertices of the input mesh.
  std::size_t number_of_faces = 0;             ///< Faces of the input mesh.
  std::size_t separator_size = 0;              ///< Vertices in METIS' separator.
  std::size_t cut_loop_length = 0;             ///< Vertices on the loop shared by the two disks.
  std::size_t initial_flipped_faces = 0;       ///< Non-positive spherical triangles of the initial guess.
  bool uniform_initial_guess_fallback = false; ///< The disks were embedded with uniform weights instead.
  bool admissible_weights =
      false; ///< The weights were made symmetric and positive (named parameter `admissible_weights`).
  std::size_t raised_weights = 0; ///< Edges whose weight `admissible_weights` raised to 1% of the local mean.
  /// Vertices that a sweep moving one vertex at a time left where they were, summed over the sweeps of stages 2
  /// and 3: in projected Gauss-Seidel, a vertex whose move still folded one of its positive triangles after being
  /// halved 12 times (none with `preserve_bijectivity` off); in the local Newton sweeps (`Nonlinear_solver::LOCAL_NEWTON`,
  /// and those the global solver makes where none of its steps is accepted), also a vertex whose Newton step does
  /// not lower the residuals of its one-ring, so near a solution most vertices count in every sweep. Moves that the
  /// halving shortened, and the global solver's own steps (whose line search shortens all moves at once), do not
  /// count; 0 with the multilevel start (unless it came as the fallback after the two-disk path: then that path's)
  /// and when Newton's full steps from the initial guess converge.
  std::size_t rejected_moves = 0;
  /// How far the continuation from Tutte's weights to the given ones got, in [0, 1] (1: all the way); -1 when it
  /// was not needed. Below 1, the balanced maps of the blended weights could not be followed further: with
  /// cotangent weights, typically because a triangle degenerates on the way.
  double continuation_parameter = -1.;
  /// Cotangent or mean-value weights of degenerate geometry (a corner angle below 1e-6 rad or above pi - 1e-6,
  /// zero-area faces, coincident vertices) that were bounded to stay finite: each counts once per direction.
  std::size_t clamped_weights = 0;

  /// `true` when `status == Error_code::OK`.
  explicit operator bool() const { return status == Error_code::OK; }
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
