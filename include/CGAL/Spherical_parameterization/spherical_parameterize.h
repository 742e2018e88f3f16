// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The package's entry point: a bijective map of a closed genus-0 triangle mesh onto the unit sphere.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>
#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/Result.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/independent_copy.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_mapper.h>
#include <CGAL/Spherical_parameterization/internal/Sphere_system.h>
#include <CGAL/Spherical_parameterization/parameters.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Real_timer.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
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
using Sparse_LU_disk_solver_traits = internal::Sparse_LU_solver_traits;

/// \ingroup PkgSphericalParameterizationRef
/// Maps the closed, connected, genus-0 triangle mesh `tm` onto the unit sphere with the method of Saba, Yavneh,
/// Gotsman and Sheffer: an initial guess from two planar disks (METIS separator, CGAL's fixed-border
/// parameterizers, Moebius inversion, inverse stereographic projection), projected Gauss-Seidel while the
/// residual decreases, then Newton steps (by default on all vertices at once; the paper's local Newton on request)
/// until every vertex is balanced in its own scale (`Convergence_test::IMBALANCE`). The output is
/// certified: every spherical triangle is positively oriented and a generic point is covered once, both under
/// exact predicates (`Result::bijective`); only then is the status `Error_code::OK`.
///
/// The mesh is never modified. On an input error, and where no initial guess could be made (`PARTITION_FAILED`,
/// `DISK_EMBEDDING_FAILED`), nothing is written to `vsm`; otherwise `vsm` receives the final (best) iterate, also
/// when the status is `NOT_CONVERGED` or `NOT_BIJECTIVE`.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB: the two disks of stage 1 are
///         embedded at the same time; each level of the multilevel start builds its Newton steps' preconditioner
///         while the coarser levels are solved; from 10,000 vertices on, the Newton steps compute independent
///         quantities at the same time) or `CGAL::Parallel_if_available_tag`. The result does not depend on it: it is
///         the same to the last bit.
/// \tparam TriangleMesh a model of `FaceListGraph` and `VertexListGraph`; also of `HalfedgeListGraph` when
///         `halfedge_weight_map` is given (its halfedges are then iterated).
/// \tparam VertexSphereMap a model of `WritablePropertyMap` from vertices to a `Point_3` constructible from three doubles.
/// \tparam NamedParameters a sequence of named parameters (the package's own, from
///         `CGAL::Spherical_parameterization::parameters`, and CGAL's, joined by `parameters::combine()`).
///
/// \param tm the mesh, only read.
/// \param vsm receives the position of every vertex on the unit sphere.
/// \param np optional named parameters among the ones listed below.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{a property map associating points to the vertices of `tm`}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::vertex_descriptor`
///                    as key type and `Point_3` as value type}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, tm)`}
///     \cgalParamExtra{If this parameter is omitted, an internal property map for `CGAL::vertex_point_t` must be
///                     available in `TriangleMesh`.}
///   \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{an instance of a geometric traits class, whose `Compute_x_3`, `Compute_y_3` and
///                           `Compute_z_3` read the points (converted to `double` with `CGAL::to_double()`), so that
///                           exact kernels are accepted}
///     \cgalParamType{a model of `Kernel`}
///     \cgalParamDefault{the kernel of the point type of `vertex_point_map` (`CGAL::Kernel_traits`)}
///   \cgalParamNEnd
///   \cgalParamNBegin{vertex_index_map}
///     \cgalParamDescription{a property map associating to each vertex of `tm` a unique index between `0` and
///                           `num_vertices(tm) - 1`}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::vertex_descriptor`
///                    as key type and an integer type as value type}
///     \cgalParamDefault{an automatically indexed internal map}
///   \cgalParamNEnd
///   \cgalParamNBegin{weighting}
///     \cgalParamDescription{the weights `w_ij` of the balance equations}
///     \cgalParamType{`Weighting`}
///     \cgalParamDefault{`Weighting::UNIFORM`, or `Weighting::USER_MAP` when `halfedge_weight_map` is given}
///   \cgalParamNEnd
///   \cgalParamNBegin{halfedge_weight_map}
///     \cgalParamDescription{the weight of `source(h)` in the equation of `target(h)`; the weights of a vertex must
///                           be finite with a positive sum}
///     \cgalParamType{a model of `ReadablePropertyMap` with `boost::graph_traits<TriangleMesh>::halfedge_descriptor`
///                    as key type and a value type convertible to `double`}
///     \cgalParamDefault{none}
///     \cgalParamExtra{The halfedges of `tm` are iterated: `TriangleMesh` must then be a model of
///                     `HalfedgeListGraph`.}
///   \cgalParamNEnd
///   \cgalParamNBegin{admissible_weights}
///     \cgalParamDescription{solve with the closest symmetric positive weights (`w_ij`, `w_ji` replaced by their
///                           mean, weights below 1% of the local mean raised to it), for which the theory guarantees a
///                           bijective solution on inscribable meshes; `Result::raised_weights` counts the edges raised}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`false`}
///   \cgalParamNEnd
///   \cgalParamNBegin{hold_weights}
///     \cgalParamDescription{symmetric weights other than Tutte's (cotangent) whose balanced maps, followed from
///                           Tutte's weights, end before them: hold the weights of the vertices where that path ends
///                           at the blend reached and go on with the others; the map returned is balanced for those
///                           weights and certified, `Result::held_weight_vertices` counts the vertices held}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`false`}
///   \cgalParamNEnd
///   \cgalParamNBegin{least_distortion}
///     \cgalParamDescription{where the map of the weights given ends unbalanced or not bijective (cotangent;
///                           mean value always, whose least-squares map is not balanced: its iterations are
///                           skipped): return the bijective map of least conformal distortion instead (a
///                           stationary minimum of the flat triangles' conformal distortion over bijective maps);
///                           a balanced map of cotangent weights is followed by the minimization too and replaced
///                           where its map has less mean angle error (`Result::replaced_balanced_map_distortion`,
///                           `Result::replaced_balanced_map_angle_error`);
///                           `Result::least_distortion_map` says so (`Result::balanced_map_folded`: the
///                           weights' balanced map reached was folded, the other ways to one were skipped);
///                           `false`: the weights' own map only}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`true` for `Weighting::COTANGENT` and `Weighting::MEAN_VALUE` (unless
///                       `admissible_weights`), `false` otherwise}
///   \cgalParamNEnd
///   \cgalParamNBegin{multilevel}
///     \cgalParamDescription{with the global solver, on meshes of 20,000 vertices or more with uniform weights and of
///                           200 or more with other symmetric weights (cotangent, of either sign; admissible;
///                           the user's, if symmetric), start from a coarser mesh (half-edge collapses to a
///                           quarter of the vertices, recursively) solved first with Tutte's weights, its map carried
///                           back, instead of the paper's two-disk guess on the mesh itself (which the coarsest level
///                           uses, and which is the fallback); `Result::levels` reports the levels}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`true`}
///   \cgalParamNEnd
///   \cgalParamNBegin{tolerance}
///     \cgalParamDescription{stop when every vertex's imbalance `e_i` is at most this value (or its rounding floor,
///                           where larger; for non-symmetric weights, the stationarity of their least-squares
///                           problem); with `Convergence_test::PAPER_RESIDUAL`, when `Res` is below it}
///     \cgalParamType{`double`}
///     \cgalParamDefault{`1e-6`}
///   \cgalParamNEnd
///   \cgalParamNBegin{convergence_test}
///     \cgalParamDescription{the stopping test of the iterations}
///     \cgalParamType{`Convergence_test`}
///     \cgalParamDefault{`Convergence_test::IMBALANCE`}
///   \cgalParamNEnd
///   \cgalParamNBegin{max_gauss_seidel_sweeps}
///     \cgalParamDescription{iteration cap of stage 2}
///     \cgalParamType{`std::size_t`}
///     \cgalParamDefault{1000}
///   \cgalParamNEnd
///   \cgalParamNBegin{max_newton_sweeps}
///     \cgalParamDescription{iteration cap of stage 3}
///     \cgalParamType{`std::size_t`}
///     \cgalParamDefault{200000}
///   \cgalParamNEnd
///   \cgalParamNBegin{max_seconds}
///     \cgalParamDescription{time budget of the whole call (input checks, stage 1, stages 2 and 3), in seconds; a
///                           negative value means none. Stage 1 always runs to its end (every returned map needs it);
///                           the iterations check the budget at every iteration and between the parts of a Newton
///                           step, so the call ends at most one such part past it (see the manual)}
///     \cgalParamType{`double`}
///     \cgalParamDefault{unlimited}
///   \cgalParamNEnd
///   \cgalParamNBegin{preserve_bijectivity}
///     \cgalParamDescription{backtrack moves that would fold a triangle}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`true`}
///   \cgalParamNEnd
///   \cgalParamNBegin{nonlinear_solver}
///     \cgalParamDescription{the solver of stage 3}
///     \cgalParamType{`Nonlinear_solver`}
///     \cgalParamDefault{`Nonlinear_solver::GLOBAL_NEWTON`}
///   \cgalParamNEnd
///   \cgalParamNBegin{metis_seed}
///     \cgalParamDescription{seed of METIS: the same seed gives bitwise identical output. With symmetric positive
///                           weights, where the fast ways from its partition end unconverged, the partitions of the
///                           next seeds are tried (`Result::partition_retries`, `Result::partition_seed`)}
///     \cgalParamType{`int`}
///     \cgalParamDefault{0}
///   \cgalParamNEnd
///   \cgalParamNBegin{METIS_options}
///     \cgalParamDescription{the `METIS_NOPTIONS` options of `METIS_ComputeVertexSeparator` (CGAL's tag); overrides
///                           `metis_seed`}
///     \cgalParamType{`idx_t*`, or a pointer to an array of `METIS_NOPTIONS` `idx_t`}
///     \cgalParamDefault{METIS' defaults with `metis_seed`}
///   \cgalParamNEnd
///   \cgalParamNBegin{sparse_linear_solver}
///     \cgalParamDescription{the linear solver of the disk stage; if it fails, Eigen's sparse LU is tried before
///                           `Error_code::DISK_EMBEDDING_FAILED`. With `CGAL::Parallel_tag` each disk is embedded
///                           with its own `independent_copy()` of it}
///     \cgalParamType{a model of `SphericalParameterizationDiskSolverTraits`}
///     \cgalParamDefault{`AMG_solver_traits` (`Default_disk_solver_traits`)}
///   \cgalParamNEnd
///   \cgalParamNBegin{progress_callback}
///     \cgalParamDescription{called after stage 1 and after every iteration (see `Progress`); returning `false`
///                           cancels (status `Error_code::CANCELLED`, the iterate reached is written: in stage 3 the
///                           best one); it is not called again after it returned `false`}
///     \cgalParamType{a model of `SphericalParameterizationProgressCallback`}
///     \cgalParamDefault{none}
///   \cgalParamNEnd
///   \cgalParamNBegin{verbose}
///     \cgalParamDescription{print the figures of each stage to `std::cerr`, and the progress at most once a second}
///     \cgalParamType{`bool`}
///     \cgalParamDefault{`false`}
///   \cgalParamNEnd
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

  CGAL::Real_timer clock;
  clock.start();
  auto vim = CGAL::get_initialized_vertex_index_map(tm, np);
  internal::Mesh_arrays mesh = internal::read_mesh_arrays(tm, vim, np);
  const Input_check check = internal::check_mesh_arrays(mesh);
  if(!check)
  {
    Result result;
    result.status = check.status;
    result.message = check.message;
    result.number_of_vertices = mesh.points.size();
    result.number_of_faces = mesh.polygons.size();
    return result;
  }
  std::vector<std::vector<int>>().swap(mesh.polygons); // checked: from here on the triangles say it all
  internal::renumber_for_locality(mesh);

  constexpr bool has_user_weights = !is_default_parameter<NamedParameters, internal_np::halfedge_weight_map_t>::value;
  internal::Pipeline_options options;
  options.call_clock = clock;
  options.parallel = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
  options.iterations.parallel = options.parallel;
  options.weighting = choose_parameter(get_parameter(np, internal_np::weighting),
                                       has_user_weights ? Weighting::USER_MAP : Weighting::UNIFORM);
  options.nonlinear_solver =
      choose_parameter(get_parameter(np, internal_np::nonlinear_solver), Nonlinear_solver::GLOBAL_NEWTON);
  options.metis_seed = choose_parameter(get_parameter(np, internal_np::metis_seed), 0);
  options.metis_options = internal::metis_options_pointer(
      choose_parameter(get_parameter(np, CGAL::internal_np::METIS_options), static_cast<idx_t*>(nullptr)));
  options.verbose = choose_parameter(get_parameter(np, CGAL::internal_np::verbose), false);
  options.iterations.tolerance = choose_parameter(get_parameter(np, internal_np::tolerance), 1e-6);
  options.iterations.convergence_test =
      choose_parameter(get_parameter(np, internal_np::convergence_test), Convergence_test::IMBALANCE);
  options.iterations.max_gauss_seidel_sweeps =
      choose_parameter(get_parameter(np, internal_np::max_gauss_seidel_sweeps), default_max_gauss_seidel_sweeps);
  options.iterations.max_newton_sweeps =
      choose_parameter(get_parameter(np, internal_np::max_newton_sweeps), std::size_t(200000));
  options.iterations.max_seconds = choose_parameter(get_parameter(np, internal_np::max_seconds), -1.);
  options.iterations.preserve_bijectivity =
      choose_parameter(get_parameter(np, internal_np::preserve_bijectivity), true);
  options.multilevel = choose_parameter(get_parameter(np, internal_np::multilevel), true);
  // Progress: the user's callback sees the end of stage 1 and every iteration; verbose prints at most once a second.
  std::function<bool(const Progress&)> user_callback;
  if constexpr(!is_default_parameter<NamedParameters, internal_np::progress_callback_t>::value)
    user_callback = get_parameter(np, internal_np::progress_callback);
  if(user_callback || options.verbose)
  {
    const bool verbose = options.verbose;
    auto last_print = std::make_shared<double>(-1.);
    // The last report sent, which the polls below repeat: the stage-level one (the end of stage 1) counts too, so
    // that the polls ask from the start of stage 3 (before, a solver's first step could be a long factorization
    // with no report yet to repeat: the least-squares iterations of mean-value weights waited for the end of the
    // run, minutes, when they sent no reports at all).
    auto last = std::make_shared<Progress>();
    // A cancellation is final: once the callback has returned false, every later report is refused without calling
    // it again, so that a stage that did not pass the refusal on stops at its next report. Before, the multilevel
    // levels' smoothing sweeps dropped it, the next reports were the callback's to answer, and Python's module accepts
    // them again (a Ctrl-C is seen once): in 2 of 10 runs of its Ctrl-C test on a loaded machine the run went on to
    // its time budget (KeyboardInterrupt after 10 s instead of 1 s; 0 of 14 since).
    auto refused = std::make_shared<bool>(false);
    options.report = [user_callback, verbose, last_print, last, refused](const Progress& progress) {
      *last = progress;
      if(*refused)
        return false;
      if(verbose && progress.iteration > 0 && progress.seconds - *last_print >= 1.)
      {
        *last_print = progress.seconds;
        std::cerr << "  " << progress.stage << " iteration " << progress.iteration << ": Res " << progress.residual
                  << ", non-positive faces " << progress.non_positive_faces << ", " << progress.seconds << " s\n";
      }
      *refused = user_callback && !user_callback(progress);
      return !*refused;
    };
    options.iterations.progress = [report = options.report, clock, last](const char* stage, std::size_t sweep,
                                                                         double residual, std::size_t invalid) {
      last->stage = stage;
      last->iteration = sweep;
      last->residual = residual;
      last->max_imbalance = -1.; // measured at the end of stage 1 only (Progress::max_imbalance)
      last->non_positive_faces = invalid;
      last->seconds = clock.time();
      return report(*last);
    };
    // Inside an iteration that lasts (a Levenberg-Marquardt step with several factorizations, a Newton step on a
    // large mesh), the last report is repeated with the time updated, at most every tenth of a second, so that a
    // cancellation takes effect well within the 1.2 s the command line waits after a stop signal (with every half
    // second, 2 of 5 SIGTERMs in bigbrain's minimization with cotangent weights ended the run with nothing written:
    // the wait for the next poll, the part of the step under way and the figures of the result added up to 1.26 s).
    auto last_poll = std::make_shared<double>(0.);
    options.iterations.keep_going = [report = options.report, clock, last, last_poll]() {
      const double now = clock.time();
      if(*last->stage == '\0' || now - *last_poll < 0.1)
        return true;
      *last_poll = now;
      last->seconds = now;
      return report(*last);
    };
  }

  // The triangles move into the system: the only copy from here on (the mesh keeps its points).
  internal::Sphere_system system = internal::make_connectivity(std::move(mesh.triangles), mesh.points.size());
  std::string weight_message;
  std::function<double(std::size_t, int)> user_weight;
  std::vector<std::pair<std::uint64_t, double>> user_table;
  if constexpr(has_user_weights)
  {
    auto weight_map = get_parameter(np, internal_np::halfedge_weight_map);
    for(auto h : halfedges(tm))
    {
      if(is_border(h, tm))
        continue;
      const std::uint64_t i = static_cast<std::uint64_t>(get(vim, target(h, tm)));
      const std::uint64_t j = static_cast<std::uint64_t>(get(vim, source(h, tm)));
      user_table.emplace_back(i << 32 | j, static_cast<double>(get(weight_map, h)));
    }
    std::sort(user_table.begin(), user_table.end());
    user_weight = [&user_table, &mesh](std::size_t i, int j) {
      const std::uint64_t key =
          static_cast<std::uint64_t>(internal::input_vertex_index(mesh, i)) << 32
          | static_cast<std::uint64_t>(internal::input_vertex_index(mesh, static_cast<std::size_t>(j)));
      auto it = std::lower_bound(
          user_table.begin(), user_table.end(), key,
          [](const std::pair<std::uint64_t, double>& entry, std::uint64_t k) { return entry.first < k; });
      return it != user_table.end() && it->first == key ? it->second : 0.;
    };
  }
  else if(options.weighting == Weighting::USER_MAP)
  {
    Result result;
    result.status = Error_code::INVALID_WEIGHTS;
    result.message =
        std::string(get_error_message(result.status)) + ": Weighting::USER_MAP needs the halfedge_weight_map parameter";
    return result;
  }
  const Error_code weight_status =
      internal::assign_weights(system, mesh, options.weighting, user_weight, weight_message);
  if(weight_status != Error_code::OK)
  {
    Result result;
    result.status = weight_status;
    result.message = std::string(get_error_message(weight_status)) + ": " + weight_message;
    result.clamped_weights = system.clamped_weights;
    result.number_of_vertices = mesh.points.size();
    result.number_of_faces = system.triangles.size();
    return result;
  }
  const bool admissible = choose_parameter(get_parameter(np, internal_np::admissible_weights), false);
  const std::size_t raised_weights = admissible ? internal::make_weights_admissible(system) : 0;
  if(admissible)
    options.weighting = Weighting::USER_MAP; // the disks use the same (admissible) weights
  options.admissible_weights = admissible;
  options.hold_weights = choose_parameter(get_parameter(np, internal_np::hold_weights), false);
  options.least_distortion = choose_parameter(get_parameter(np, internal_np::least_distortion),
                                              least_distortion_by_default(options.weighting, admissible));

  using Solver = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::sparse_linear_solver_t,
                                                                    NamedParameters, Default_disk_solver_traits>::type;
  const Solver solver = choose_parameter<Solver>(get_parameter(np, CGAL::internal_np::sparse_linear_solver));

  std::vector<internal::Vector3> x;
  Result result = internal::Sphere_mapper<Solver>(mesh, system, options, solver).map(x);
  result.admissible_weights = admissible;
  result.raised_weights = raised_weights;
  result.clamped_weights = system.clamped_weights;
  if(system.clamped_weights > 0)
  {
    result.message += " [" + std::to_string(system.clamped_weights) + " weights of degenerate corners were clamped]";
    if(options.verbose)
      std::cerr << "weights: " << system.clamped_weights << " of degenerate corners clamped\n";
  }
  if(x.size() == mesh.points.size())
  {
    using Point = typename boost::property_traits<VertexSphereMap>::value_type;
    std::vector<std::size_t> internal_index(x.size());
    for(std::size_t i = 0; i < x.size(); ++i)
      internal_index[internal::input_vertex_index(mesh, i)] = i;
    for(auto v : vertices(tm))
    {
      const internal::Vector3& p = x[internal_index[static_cast<std::size_t>(get(vim, v))]];
      put(vsm, v, Point(p.x, p.y, p.z));
    }
  }
  result.total_seconds = clock.time();
  return result;
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPHERICAL_PARAMETERIZE_H
