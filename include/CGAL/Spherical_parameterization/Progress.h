// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// What the `progress_callback` named parameter receives.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H

#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// What the `progress_callback` named parameter receives: once after stage 1 (the two-disk initial guess; with the
/// multilevel start, after the coarsest level's, and again after a finer level's own two-disk guess where the level
/// below it failed), then after every iteration of stages 2 and 3 that gave a new iterate, on every level (and,
/// inside an iteration that lasts, the last report again with its time updated, at most every tenth of a second).
struct Progress
{
  /// "initial guess", "gauss-seidel", "global newton", "local newton", "weight continuation" (the global Newton
  /// steps that follow balanced maps from Tutte's weights to cotangent weights, one phase per blend of the weights),
  /// or "least distortion" (named parameter `least_distortion`: the minimization of the conformal distortion).
  const char* stage = "";
  /// Iterations so far of the current phase (0 for the initial guess): the count starts again with each phase of
  /// stage 3 (such as Newton's full steps, then the bijectivity-preserving ones) and on each level.
  std::size_t iteration = 0;
  double residual = -1.; ///< The paper's `Res` now; in stage "least distortion", the largest stationarity instead.
  double max_imbalance =
      -1.; ///< The largest imbalance `e_i` (see `Convergence_test`) at the end of stage 1; -1 in the per-iteration reports.
  std::size_t non_positive_faces = 0; ///< Spherical triangles not positively oriented now.
  double seconds = 0.;                ///< Since the call started.
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_PROGRESS_H
