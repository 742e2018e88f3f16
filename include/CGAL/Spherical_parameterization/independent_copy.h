// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The copy of the disk solver that each disk gets when the two disks are embedded at the same time.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INDEPENDENT_COPY_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INDEPENDENT_COPY_H

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>

#include <CGAL/Eigen_solver_traits.h>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Returns a disk solver with the settings of `solver` that can be used on another thread at the same time as
/// `solver`: with `CGAL::Parallel_tag`, `spherical_parameterize()` embeds each of the two disks with its own one.
/// This default is a copy (copy construction). A type whose copies share state that two threads may not use at
/// once (a factorization, a cache) overloads `independent_copy()` in its own namespace, where
/// argument-dependent lookup finds it, as the package does for `AMG_solver_traits` and `CGAL::Eigen_solver_traits`.
/// \tparam DiskSolverTraits a model of `SphericalParameterizationDiskSolverTraits`.
template <typename DiskSolverTraits>
DiskSolverTraits independent_copy(const DiskSolverTraits& solver)
{
  return solver;
}

/// \ingroup PkgSphericalParameterizationRef
/// Copies of `AMG_solver_traits` share their setup and statistics: this one has the parameters of `solver`, and a
/// setup and statistics of its own.
inline AMG_solver_traits independent_copy(const AMG_solver_traits& solver)
{
  return AMG_solver_traits(solver.parameters());
}

/// \ingroup PkgSphericalParameterizationRef
/// Copies of `CGAL::Eigen_solver_traits` share their Eigen solver, and Eigen's sparse solvers cannot be copied:
/// this one holds a new, default-constructed Eigen solver, so settings made through `solver()` are not carried
/// over. Wrap the traits in a type of your own, with an `independent_copy()` overload, to carry them.
template <typename EigenSolver>
CGAL::Eigen_solver_traits<EigenSolver> independent_copy(const CGAL::Eigen_solver_traits<EigenSolver>&)
{
  return CGAL::Eigen_solver_traits<EigenSolver>();
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INDEPENDENT_COPY_H
