// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Named parameters of the Spherical_parameterization package.
//
// CGAL 5.5's chain members (`.vertex_point_map(...)`) come from a fixed list, so the package's own
// parameters are free functions: `parameters::tolerance(1e-8)` starts a chain, and every function takes an
// optional chain to extend, e.g. `parameters::weighting(Weighting::MEAN_VALUE, CGAL::parameters::verbose(true))`.
// `parameters::combine(np1, np2, ...)` joins any chains (ours and CGAL's). CGAL functions ignore our tags.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_PARAMETERS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_PARAMETERS_H

#include <CGAL/Spherical_parameterization/Progress.h>
#include <CGAL/Spherical_parameterization/enum.h>

#include <CGAL/Named_function_parameters.h>

#include <cstddef>
#include <type_traits>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The default of the `max_gauss_seidel_sweeps` named parameter.
constexpr std::size_t default_max_gauss_seidel_sweeps = 1000;

namespace internal_np {
// Tag types of the package's own named parameters.
enum weighting_t
{
  weighting
};
enum halfedge_weight_map_t
{
  halfedge_weight_map
};
enum tolerance_t
{
  tolerance
};
enum max_gauss_seidel_sweeps_t
{
  max_gauss_seidel_sweeps
};
enum max_newton_sweeps_t
{
  max_newton_sweeps
};
enum max_seconds_t
{
  max_seconds
};
enum preserve_bijectivity_t
{
  preserve_bijectivity
};
enum nonlinear_solver_t
{
  nonlinear_solver
};
enum metis_seed_t
{
  metis_seed
};
enum progress_callback_t
{
  progress_callback
};
enum admissible_weights_t
{
  admissible_weights
};
enum convergence_test_t
{
  convergence_test
};
enum multilevel_t
{
  multilevel
};
enum hold_weights_t
{
  hold_weights
};
enum least_distortion_t
{
  least_distortion
};
} // namespace internal_np

/// \ingroup PkgSphericalParameterizationRef
/// The default of the named parameter `least_distortion`: on for the shape-preserving weights (cotangent, mean value),
/// whose balanced map may fold, not exist, or keep the shapes less well than the minimum; off for Tutte's weights, the
/// user's, and weights made admissible, whose balanced map is what was asked for. The command line and the Python
/// module resolve their default with it.
inline bool least_distortion_by_default(Weighting weighting, bool admissible_weights)
{
  return !admissible_weights && (weighting == Weighting::COTANGENT || weighting == Weighting::MEAN_VALUE);
}

namespace parameters {

using CGAL::parameters::choose_parameter;
using CGAL::parameters::default_values;
using CGAL::parameters::get_parameter;

#define CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(NAME)                                                          \
  template <typename K>                                                                                                \
  CGAL::Named_function_parameters<K, internal_np::NAME##_t> NAME(const K& k)                                           \
  {                                                                                                                    \
    return CGAL::Named_function_parameters<K, internal_np::NAME##_t>(k);                                               \
  }                                                                                                                    \
  template <typename K, typename T, typename Tag, typename Base>                                                       \
  CGAL::Named_function_parameters<K, internal_np::NAME##_t, CGAL::Named_function_parameters<T, Tag, Base>> NAME(       \
      const K& k, const CGAL::Named_function_parameters<T, Tag, Base>& np)                                             \
  {                                                                                                                    \
    return CGAL::Named_function_parameters<K, internal_np::NAME##_t, CGAL::Named_function_parameters<T, Tag, Base>>(   \
        k, np);                                                                                                        \
  }

/// Weighting policy (`Weighting`), default `Weighting::UNIFORM`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(weighting)
/// A readable property map from halfedges to `double`: the weight of `source(h)` in the equation of `target(h)`.
/// Implies `Weighting::USER_MAP` when `weighting` is not given.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(halfedge_weight_map)
/// The tolerance of the `convergence_test` (default `1e-6`): the largest imbalance `e_i` allowed (for non-symmetric
/// weights, the largest stationarity of their least-squares problem), or the paper's `Res`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(tolerance)
/// When the iterations stop (`Convergence_test`), default `Convergence_test::IMBALANCE`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(convergence_test)
/// Iteration cap of stage 2 (projected Gauss-Seidel sweeps, default 1000).
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(max_gauss_seidel_sweeps)
/// Iteration cap of stage 3 (sweeps of the nonlinear solver, default 200000), for each of its attempts (each level of
/// the multilevel start, the two-disk path, a fallback).
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(max_newton_sweeps)
/// Wall-clock budget of the whole call in seconds (default: unlimited); stage 1 always runs to its end.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(max_seconds)
/// Backtrack any vertex move that would make one of its spherical triangles non-positive (default `true`): stage 2's
/// moves and the bijectivity-preserving Newton steps; Newton's full steps, which the global solver tries first, may
/// fold triangles on the way whatever the setting (the certificate decides).
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(preserve_bijectivity)
/// Solver of stage 3 (`Nonlinear_solver`), default `Nonlinear_solver::GLOBAL_NEWTON`.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(nonlinear_solver)
/// `true`: solve with the closest weights the theory covers instead of the given ones: `w_ij` and `w_ji` replaced by
/// their mean, then weights below 1% of the mean weight at their vertices raised to it (default `false`). Symmetric
/// positive weights are the case the theory covers (though not every such set of weights has a bijective balanced
/// solution: the manual's tetrahedron); cotangent weights (which may be negative) and mean-value weights (not
/// symmetric) are further from it. `Result::raised_weights` counts the edges raised.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(admissible_weights)
/// `true` (default): with the global Newton solver, on meshes of 20,000 vertices or more with uniform weights and of
/// 200 or more with other symmetric weights (cotangent, of either sign; admissible; the user's, if symmetric), start
/// from a coarser mesh (half-edge collapses) solved first with Tutte's weights, its map carried back to the input
/// mesh, instead of the paper's two-disk guess (used on the coarsest mesh, and as the fallback).
/// `false`: the paper's stage 1 on the input mesh.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(multilevel)
/// `true`: symmetric weights other than Tutte's (cotangent) whose balanced maps, followed from Tutte's weights, end
/// before the weights given (a triangle degenerates, or the path turns back) go on with the weights of the vertices
/// where the path ends held at the blend reached, and the map returned is balanced for those weights and certified
/// (`Result::held_weight_vertices`, `Result::held_weight_parameter`); default `false`: such maps end
/// `Error_code::NOT_CONVERGED`. An experimental option: see the manual's Method section for what it costs in shape.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(hold_weights)
/// `true` (the default with `Weighting::COTANGENT` and `Weighting::MEAN_VALUE`, unless `admissible_weights`): where
/// the map of the weights given ends unbalanced or not bijective (cotangent weights whose balanced map folds or is
/// not found; mean-value weights always, which have no balanced map in general: their least-squares iterations are
/// skipped), return instead the bijective map of least conformal distortion: a minimum, over bijective maps, of the
/// conformal distortion of the flat triangles through the sphere points against the 3D triangles, started from the
/// map reached or, of less distortion, a map minimized on coarser levels first (meshes of 4,000 vertices or more) or
/// Tutte's map. Where the map of the weights given is balanced and certified (cotangent weights, the user's), the
/// minimization follows it too (started from it where its distortion is at most 1.1), and its map replaces it where
/// stationary and of less mean angle error
/// (`Result::replaced_balanced_map_distortion`, `Result::replaced_balanced_map_angle_error`): where along the
/// Moebius boosts a balanced map sits is fixed only by the discretization, and the one reached can have up to 20
/// times the angle error of the minimum (the manual's Method section); `false` gives the balanced map. With weights
/// other than Tutte's and without `hold_weights`, this minimization replaces the slow ways to their balanced map: the
/// retry of a failed multilevel start, the two-disk path after it, the cautious Newton.
/// With weights other than Tutte's and `max_seconds`, the ways to the weights' balanced map get half the budget, the
/// minimization the rest; where Newton's full steps reach a balanced map of those weights that is folded, the other
/// ways are skipped (`Result::balanced_map_folded`). `Result::least_distortion_map` says so, and the status is
/// `Error_code::OK` when that minimum is stationary (`Result::max_distortion_stationarity`) and the map certified.
/// Only with `Convergence_test::IMBALANCE`. `false` (the default for uniform weights, the user's and admissible
/// ones): the weights' own map only (`Error_code::NOT_CONVERGED` where it is not balanced). See the manual's Method
/// section for what the minimization gives and costs.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(least_distortion)
/// Seed of METIS' randomized separator (default 0): the same seed gives bitwise identical output.
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(metis_seed)

/// A callable `bool(const Progress&)`, called after stage 1 and after every iteration (see `Progress`); returning
/// `false` cancels the run, which then ends with `Error_code::CANCELLED` and the iterate reached (in stage 3 the best one).
CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER(progress_callback)

#undef CGAL_SPHERICAL_PARAMETERIZATION_NAMED_PARAMETER

namespace internal {
// Appends every parameter of `np` (outermost first) on top of `base`.
template <typename Base>
const Base& append(const CGAL::Named_function_parameters<bool, CGAL::internal_np::all_default_t>&, const Base& base)
{
  return base;
}

template <typename T, typename Tag, typename Base>
auto append(const CGAL::Named_function_parameters<T, Tag, CGAL::internal_np::No_property>& np, const Base& base)
{
  return CGAL::Named_function_parameters<T, Tag, Base>(np.v, base);
}

template <typename T, typename Tag, typename Inner, typename Base>
auto append(const CGAL::Named_function_parameters<T, Tag, Inner>& np, const Base& base)
{
  auto appended_inner = append(static_cast<const Inner&>(np), base);
  return CGAL::Named_function_parameters<T, Tag, std::decay_t<decltype(appended_inner)>>(np.v, appended_inner);
}
} // namespace internal

/// \cond SKIP_IN_MANUAL
template <typename NP>
const NP& combine(const NP& np)
{
  return np;
}
/// \endcond

/// \ingroup PkgSphericalParameterizationRef
/// Joins named-parameter chains, the package's (`CGAL::Spherical_parameterization::parameters`) and CGAL's
/// (`CGAL::parameters`), into one: CGAL 5.5 cannot chain parameters defined outside CGAL with `.name()`.
/// When a parameter is in several chains, the first one counts.
/// \code
/// SP::parameters::combine(SP::parameters::weighting(SP::Weighting::COTANGENT), SP::parameters::tolerance(1e-7),
///                         CGAL::parameters::vertex_point_map(vpm))
/// \endcode
/// \param np1 a chain of named parameters.
/// \param np2 a chain of named parameters.
/// \param rest more chains.
template <typename NP1, typename NP2, typename... NPs>
auto combine(const NP1& np1, const NP2& np2, const NPs&... rest)
{
  return combine(internal::append(np1, np2), rest...);
}

} // namespace parameters
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_PARAMETERS_H
