// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

/*!
\ingroup PkgSphericalParameterizationConcepts
\cgalConcept

The concept `SphericalParameterizationProgressCallback` describes the `progress_callback` named parameter of
`CGAL::Spherical_parameterization::spherical_parameterize()`: a callable object that is told how the computation
goes, and that can stop it.

It is called once at the end of stage 1 (stage `"initial guess"`, iteration 0; with the multilevel start, at the
end of the coarsest level's), then after every sweep of the projected Gauss-Seidel iterations (`"gauss-seidel"`)
and after every iteration of the nonlinear solver (`"global newton"` or `"local newton"`) that gave a new
iterate, on every level, from the thread that called `spherical_parameterize()`. Inside an
iteration that lasts (a Levenberg-Marquardt step with several factorizations, a Newton step on a large mesh) the
last report is repeated with its time updated, at most every half second, so that a cancellation takes effect
within about a second. It should return quickly: on small meshes it is called thousands of times a second.

Returning `false` stops the computation at that point: the status is `Error_code::CANCELLED` (unless the
connectivity is provably not inscribable: `Error_code::NO_BALANCED_SOLUTION` takes precedence), and the map
receives the iterate reached (in stage 3 the best one so far), which is certified like any other (`Result::bijective`, `Result::flipped_faces`).
A lambda, a function pointer or a `std::function<bool(const CGAL::Spherical_parameterization::Progress&)>` are
models.

\cgalRefines{`CopyConstructible`}

\cgalHasModel{`std::function<bool(const CGAL::Spherical_parameterization::Progress&)>`}
*/
class SphericalParameterizationProgressCallback
{
public:
  /// \name Operations
  /// @{

  /// Receives the stage, the iteration, the residual `Res`, the number of non-positive spherical triangles and
  /// the seconds since the call started.
  /// \return `true` to continue, `false` to stop.
  bool operator()(const CGAL::Spherical_parameterization::Progress& progress);

  /// @}
};
