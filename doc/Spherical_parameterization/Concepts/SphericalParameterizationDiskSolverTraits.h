// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

/*!
\ingroup PkgSphericalParameterizationConcepts
\cgalConcept

The concept `SphericalParameterizationDiskSolverTraits` describes the sparse linear solver of the disk stage of
`CGAL::Spherical_parameterization::spherical_parameterize()` (its `sparse_linear_solver` named parameter). Each
half of the mesh is embedded in the unit disk by CGAL's
`Surface_mesh_parameterization::Fixed_border_parameterizer_3` with this type as its `SolverTraits`, so the
requirements are those of CGAL's `SparseLinearAlgebraTraits_d`, as that class uses them, plus the semantics below.

- The matrix of a half has one identity row per vertex of the loop (its position is known) and one row per
  interior vertex; it is non-symmetric as given, even for uniform weights, and symmetric for uniform and
  cotangent weights once the identity rows are eliminated.
- `linear_solver(A, B, X, D)` is called twice per half with the same `A`, for the u and then the v coordinates:
  a solver that caches its factorization (as `CGAL::Spherical_parameterization::AMG_solver_traits` does) pays
  one setup per half.
- The object is copied into each parameterizer (copy construction): the copies may share state with it, as
  copies of `CGAL::Eigen_solver_traits` and of `AMG_solver_traits` do, so that its statistics see the solves.
- With `CGAL::Parallel_tag` the two disks are embedded at the same time, on two threads, each with its own
  solver made by `CGAL::Spherical_parameterization::independent_copy(solver)` from the user's object: by
  default a copy (copy construction), so the settings of the user's object reach both disks. A type whose
  copies share state that two threads may not use at once overloads `independent_copy()` in its own namespace;
  the package does so for `AMG_solver_traits` (same parameters, own setup and statistics) and for
  `CGAL::Eigen_solver_traits` (a new Eigen solver: Eigen's solvers cannot be copied, so settings made through
  `solver()` are lost). The statistics of the user's object do not see these solves.
- Returning `false` is a recoverable failure: the package then tries Eigen's sparse LU
  (`CGAL::Spherical_parameterization::Sparse_LU_disk_solver_traits`) before it gives up with
  `Error_code::DISK_EMBEDDING_FAILED`.

\cgalRefines{`SparseLinearAlgebraTraits_d`, `DefaultConstructible`, `CopyConstructible`}

\cgalHasModel{`CGAL::Spherical_parameterization::AMG_solver_traits` (the default),
`CGAL::Spherical_parameterization::Sparse_LU_disk_solver_traits`, `CGAL::Eigen_solver_traits` with an Eigen
solver for non-symmetric matrices}
*/
class SphericalParameterizationDiskSolverTraits
{
public:
  /// \name Types
  /// @{

  /// The number type: `double`.
  typedef unspecified_type NT;

  /// A sparse square matrix: constructible from its number of rows and columns, filled with
  /// `set_coef(int i, int j, NT value, bool new_coef)`.
  typedef unspecified_type Matrix;

  /// A dense vector: constructible from its size, read and written with `operator[]`.
  typedef unspecified_type Vector;

  /// @}

  /// \name Operations
  /// @{

  /// Solves \f$ A X = B \f$; the solution is \f$ X / D \f$.
  /// \return `true` if the system was solved to the solver's accuracy.
  bool linear_solver(const Matrix& A, const Vector& B, Vector& X, NT& D);

  /// @}
};
