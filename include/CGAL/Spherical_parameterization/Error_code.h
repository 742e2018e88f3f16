// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Status codes of the Spherical_parameterization package, each with its own message.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Why a call succeeded or failed. Input errors are detected before any work and leave every output untouched.
enum class Error_code
{
  OK = 0,                   ///< Converged (the `convergence_test` holds) and certified bijective.
  EMPTY_MESH,               ///< The mesh has no face.
  NOT_TRIANGLE_MESH,        ///< A face is not a triangle.
  DEGENERATE_FACE,          ///< A face uses the same vertex twice, or a vertex index out of range.
  NON_FINITE_COORDINATES,   ///< A vertex coordinate is NaN or infinite.
  ISOLATED_VERTEX,          ///< A vertex belongs to no face.
  HAS_BORDER,               ///< The mesh is open (has boundary loops).
  NON_MANIFOLD_EDGE,        ///< An edge is shared by more than two faces.
  NON_MANIFOLD_VERTEX,      ///< The faces around a vertex do not form a single fan.
  INCONSISTENT_ORIENTATION, ///< Two faces traverse a shared edge in the same direction.
  MULTIPLE_COMPONENTS,      ///< The mesh has several connected components.
  GENUS_NOT_ZERO,           ///< The mesh is closed but not a topological sphere.
  INVALID_WEIGHTS,          ///< A weight is not finite, or a vertex's weights do not have a positive sum.
  PARTITION_FAILED,         ///< The mesh could not be split into two disks (stage 1).
  DISK_EMBEDDING_FAILED,    ///< The planar disk embedding of a half failed (stage 1).
  NOT_CONVERGED,            ///< The iteration caps or the time budget were reached before the `convergence_test` held.
  NOT_BIJECTIVE,        ///< The convergence test holds but the map is not bijective: some spherical triangles are not
                        ///< positively oriented, or, with every one positive, the map does not have degree 1 (a
                        ///< generic point covered more than once, or signed areas that do not add up to 4 pi).
  NO_BALANCED_SOLUTION, ///< The connectivity is not inscribable: no bijective solution exists for positive weights.
  CANCELLED             ///< The `progress_callback` asked to stop.
};

/// \ingroup PkgSphericalParameterizationRef
/// A one-line explanation of `code`.
inline const char* get_error_message(Error_code code)
{
  switch(code)
  {
  case Error_code::OK:
    return "Success: converged and certified bijective";
  case Error_code::EMPTY_MESH:
    return "The mesh has no face";
  case Error_code::NOT_TRIANGLE_MESH:
    return "The mesh has a face that is not a triangle";
  case Error_code::DEGENERATE_FACE:
    return "A face uses the same vertex more than once, or a vertex that does not exist";
  case Error_code::NON_FINITE_COORDINATES:
    return "A vertex has a NaN or infinite coordinate";
  case Error_code::ISOLATED_VERTEX:
    return "A vertex belongs to no face";
  case Error_code::HAS_BORDER:
    return "The mesh is not closed: it has boundary loops";
  case Error_code::NON_MANIFOLD_EDGE:
    return "An edge is shared by more than two faces";
  case Error_code::NON_MANIFOLD_VERTEX:
    return "The faces around a vertex do not form a single fan (pinched vertex)";
  case Error_code::INCONSISTENT_ORIENTATION:
    return "The faces are not consistently oriented";
  case Error_code::MULTIPLE_COMPONENTS:
    return "The mesh has more than one connected component";
  case Error_code::GENUS_NOT_ZERO:
    return "The mesh is not a topological sphere (genus > 0)";
  case Error_code::INVALID_WEIGHTS:
    return "A weight is not finite or the weights of a vertex do not sum to a positive value";
  case Error_code::PARTITION_FAILED:
    return "The mesh could not be split into two topological disks";
  case Error_code::DISK_EMBEDDING_FAILED:
    return "The planar embedding of a half of the mesh failed";
  case Error_code::NOT_CONVERGED:
    return "Not converged within the iteration caps or the time budget";
  case Error_code::NOT_BIJECTIVE:
    return "The map converged but is not bijective (a triangle not positively oriented, or a degree other than 1)";
  case Error_code::NO_BALANCED_SOLUTION:
    return "The connectivity is not inscribable: the balance equations have no bijective solution for positive weights";
  case Error_code::CANCELLED:
    return "Cancelled by the progress callback";
  }
  return "Unknown error code";
}

/// \ingroup PkgSphericalParameterizationRef
/// The enumerator's name, such as `"GENUS_NOT_ZERO"` (used by the command line and the tests).
inline const char* get_error_name(Error_code code)
{
  switch(code)
  {
  case Error_code::OK:
    return "OK";
  case Error_code::EMPTY_MESH:
    return "EMPTY_MESH";
  case Error_code::NOT_TRIANGLE_MESH:
    return "NOT_TRIANGLE_MESH";
  case Error_code::DEGENERATE_FACE:
    return "DEGENERATE_FACE";
  case Error_code::NON_FINITE_COORDINATES:
    return "NON_FINITE_COORDINATES";
  case Error_code::ISOLATED_VERTEX:
    return "ISOLATED_VERTEX";
  case Error_code::HAS_BORDER:
    return "HAS_BORDER";
  case Error_code::NON_MANIFOLD_EDGE:
    return "NON_MANIFOLD_EDGE";
  case Error_code::NON_MANIFOLD_VERTEX:
    return "NON_MANIFOLD_VERTEX";
  case Error_code::INCONSISTENT_ORIENTATION:
    return "INCONSISTENT_ORIENTATION";
  case Error_code::MULTIPLE_COMPONENTS:
    return "MULTIPLE_COMPONENTS";
  case Error_code::GENUS_NOT_ZERO:
    return "GENUS_NOT_ZERO";
  case Error_code::INVALID_WEIGHTS:
    return "INVALID_WEIGHTS";
  case Error_code::PARTITION_FAILED:
    return "PARTITION_FAILED";
  case Error_code::DISK_EMBEDDING_FAILED:
    return "DISK_EMBEDDING_FAILED";
  case Error_code::NOT_CONVERGED:
    return "NOT_CONVERGED";
  case Error_code::NOT_BIJECTIVE:
    return "NOT_BIJECTIVE";
  case Error_code::NO_BALANCED_SOLUTION:
    return "NO_BALANCED_SOLUTION";
  case Error_code::CANCELLED:
    return "CANCELLED";
  }
  return "UNKNOWN";
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
