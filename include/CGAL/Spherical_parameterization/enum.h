// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The choices of the package's named parameters (`weighting`, `nonlinear_solver`, `convergence_test`): plain enums,
// without the named-parameter machinery of parameters.h, so that the internal stages can use them too.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ENUM_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ENUM_H

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The edge weights `w_ij` of the balance equations `alpha_i x_i = sum_j w_ij x_j`.
enum class Weighting
{
  UNIFORM,    ///< Tutte weights `w_ij = 1`: symmetric and positive, the case covered by the theory (default).
  COTANGENT,  ///< Conformal weights `(cot a_ij + cot b_ij) / 2`: symmetric, may be negative.
  MEAN_VALUE, ///< Floater's mean-value weights: positive, not symmetric.
  USER_MAP    ///< Weights read from the `halfedge_weight_map` named parameter.
};

/// \ingroup PkgSphericalParameterizationRef
/// The solver of stage 3 (after projected Gauss-Seidel).
enum class Nonlinear_solver
{
  GLOBAL_NEWTON, ///< Newton on all vertices at once in tangent coordinates, with the sphere's conformal boosts handled
                 ///< exactly and bijectivity-preserving step control (default).
  LOCAL_NEWTON   ///< The paper's local Newton iteration on (theta, phi) with line search (Section 3.3).
};

/// \ingroup PkgSphericalParameterizationRef
/// When the iterations stop (named parameter `convergence_test`).
enum class Convergence_test
{
  /// Every vertex balanced in its own scale (default): the imbalance
  /// \f$ e_i = |t_i| / \sum_j |w_{ij}| \, s(|x_j - x_i|) \f$, with \f$ t_i \f$ the tangential part of
  /// \f$ \sum_j w_{ij} (x_j - x_i) \f$ (weights normalized to sum to one) and \f$ s(c) = c \sqrt{1 - c^2/4} \f$ the
  /// length of an edge's tangential part, is at most the tolerance at every vertex, or at most the vertex's rounding
  /// floor where that is larger (see `Result::vertices_at_rounding_floor`); vertices below double precision (where
  /// that floor would exceed 1/2) are counted, not tested (`Result::vertices_below_precision`).
  /// For non-symmetric weights (mean value), whose equations generally have no exact solution, the stationarity of
  /// their least-squares problem instead (`Result::max_stationarity`, see the manual), at every vertex.
  IMBALANCE,
  /// The paper's test: `Res < tolerance`. `Res` carries a factor 1/sqrt(n) against the root mean square of the
  /// per-vertex residuals, so on large meshes it passes while vertices are still far from balanced; kept to
  /// reproduce the paper's setting.
  PAPER_RESIDUAL
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ENUM_H
