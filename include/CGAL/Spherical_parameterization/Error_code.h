// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Status codes of the Spherical_parameterization package, each with its own message.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H

#include <cstddef>

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
  NO_BALANCED_SOLUTION, ///< Proven: no bijective balanced map exists (a connectivity that is not inscribable, for
                        ///< any positive weights; or a tetrahedron whose weights are not w_ij = u_i u_j of one sign
                        ///< with each u_i below the sum of the others).
  CANCELLED             ///< The `progress_callback` asked to stop.
};

namespace internal {

struct Error_code_text
{
  Error_code code;
  const char* name;
  const char* message;
};

// One row per enumerator, in their order (checked below).
inline constexpr Error_code_text error_code_texts[] = {
    {Error_code::OK, "OK", "Success: converged and certified bijective"},
    {Error_code::EMPTY_MESH, "EMPTY_MESH", "The mesh has no face"},
    {Error_code::NOT_TRIANGLE_MESH, "NOT_TRIANGLE_MESH", "The mesh has a face that is not a triangle"},
    {Error_code::DEGENERATE_FACE, "DEGENERATE_FACE",
     "A face uses the same vertex more than once, or a vertex that does not exist"},
    {Error_code::NON_FINITE_COORDINATES, "NON_FINITE_COORDINATES", "A vertex has a NaN or infinite coordinate"},
    {Error_code::ISOLATED_VERTEX, "ISOLATED_VERTEX", "A vertex belongs to no face"},
    {Error_code::HAS_BORDER, "HAS_BORDER", "The mesh is not closed: it has boundary loops"},
    {Error_code::NON_MANIFOLD_EDGE, "NON_MANIFOLD_EDGE", "An edge is shared by more than two faces"},
    {Error_code::NON_MANIFOLD_VERTEX, "NON_MANIFOLD_VERTEX",
     "The faces around a vertex do not form a single fan (pinched vertex)"},
    {Error_code::INCONSISTENT_ORIENTATION, "INCONSISTENT_ORIENTATION", "The faces are not consistently oriented"},
    {Error_code::MULTIPLE_COMPONENTS, "MULTIPLE_COMPONENTS", "The mesh has more than one connected component"},
    {Error_code::GENUS_NOT_ZERO, "GENUS_NOT_ZERO", "The mesh is not a topological sphere (genus > 0)"},
    {Error_code::INVALID_WEIGHTS, "INVALID_WEIGHTS",
     "A weight is not finite or the weights of a vertex do not sum to a positive value"},
    {Error_code::PARTITION_FAILED, "PARTITION_FAILED", "The mesh could not be split into two topological disks"},
    {Error_code::DISK_EMBEDDING_FAILED, "DISK_EMBEDDING_FAILED", "The planar embedding of a half of the mesh failed"},
    {Error_code::NOT_CONVERGED, "NOT_CONVERGED", "Not converged within the iteration caps or the time budget"},
    {Error_code::NOT_BIJECTIVE, "NOT_BIJECTIVE",
     "The map converged but is not bijective (a triangle not positively oriented, or a degree other than 1)"},
    {Error_code::NO_BALANCED_SOLUTION, "NO_BALANCED_SOLUTION",
     "Proven: the balance equations have no bijective solution (a connectivity that is not inscribable has none for "
     "positive weights; a tetrahedron has none for most weights)"},
    {Error_code::CANCELLED, "CANCELLED", "Cancelled by the progress callback"},
};

inline constexpr std::size_t number_of_error_codes = sizeof(error_code_texts) / sizeof(error_code_texts[0]);

constexpr bool error_code_texts_in_order()
{
  for(std::size_t k = 0; k < number_of_error_codes; ++k)
    if(static_cast<std::size_t>(error_code_texts[k].code) != k)
      return false;
  return static_cast<std::size_t>(Error_code::CANCELLED) + 1 == number_of_error_codes;
}
static_assert(error_code_texts_in_order(), "one row per Error_code, in the enumerators' order");

inline const Error_code_text* find_error_code_text(Error_code code)
{
  const std::size_t k = static_cast<std::size_t>(code);
  return k < number_of_error_codes ? &error_code_texts[k] : nullptr;
}

} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// A one-line explanation of `code`.
inline const char* get_error_message(Error_code code)
{
  const internal::Error_code_text* text = internal::find_error_code_text(code);
  return text ? text->message : "Unknown error code";
}

/// \ingroup PkgSphericalParameterizationRef
/// The enumerator's name, such as `"GENUS_NOT_ZERO"` (used by the command line and the tests).
inline const char* get_error_name(Error_code code)
{
  const internal::Error_code_text* text = internal::find_error_code_text(code);
  return text ? text->name : "UNKNOWN";
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_ERROR_CODE_H
