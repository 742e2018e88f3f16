// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The balance equations alpha_i x_i = sum_j w_ij x_j in compact form: for every vertex its neighbours in
// counter-clockwise order (CSR), the weights normalized to sum to one per vertex, and for every entry (i, j)
// the position of the entry (j, i), so that moving x_i updates the sums of its neighbours in O(degree).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SYSTEM_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SYSTEM_H

#include <CGAL/Spherical_parameterization/Error_code.h>
#include <CGAL/Spherical_parameterization/enum.h>
#include <CGAL/Spherical_parameterization/internal/Mesh_arrays.h>
#include <CGAL/Spherical_parameterization/internal/Vector3.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

// A fill-reducing order of a mesh's vertices (stage3/tangent_newton_system.h's elimination_rank()), computed once and
// shared by the copies of its system, which change the weights, never the connectivity.
struct Vertex_order_cache
{
  std::mutex mutex;
  std::vector<int> rank;  // rank[i]: the position of vertex i; empty until computed
  std::size_t edges = 0; // the size of the neighbour lists ordered (a check that the connectivity is the same)
};

struct Sphere_system
{
  std::size_t number_of_vertices = 0;
  std::vector<std::size_t> offsets; // row i is [offsets[i], offsets[i+1])
  std::vector<int> neighbors;       // counter-clockwise around the vertex, starting at the smallest index
  std::vector<std::size_t> reverse; // position of the entry (j, i) for the entry (i, j)
  std::vector<double> weights;      // normalized: each row sums to one
  std::vector<double> row_sums;     // raw weight of (i, j) = weights[k] * row_sums[i]
  bool symmetric = true;            // raw weights satisfy w_ij = w_ji
  std::size_t clamped_weights = 0;  // weights with a degenerate corner or edge, bounded (see out_of_bounds)
  // The Laplacian of the raw weights with their signs (off-diagonals -w_ij, diagonal sum_j w_ij) is known to be
  // positive semi-definite: cotangent weights, none clamped (it is then the sum of the faces' cotangent forms, each the
  // Dirichlet energy of the linear functions on its triangle, obtuse or not), their blends with Tutte's at one
  // parameter (stage3/weight_continuation.h), and those made admissible (all positive). In exact arithmetic: near the
  // clamping bound (corners of 1e-6) rounding can leave a face's form indefinite by about eps / angle^2, which the
  // preconditioner's relative shift of its diagonal covers (an independent check: no negative pivot of L + 1e-8 diag(L)
  // on 59 of CGAL's and the shared meshes). Only the MINRES preconditioner reads it (stage3/tangent_multigrid.h); set
  // by assign_weights(), false for Tutte's and the user's weights; copies that change the weights otherwise clear it.
  bool signed_laplacian_semidefinite = false;
  std::vector<int> ring_faces;      // for the entry (i, j = ring[k]): the face (i, ring[k], ring[k+1])
  std::vector<std::array<int, 3>> triangles;
  // Vertices of arm tips solved with regularized weights because their balanced positions lie below double precision
  // (stage3/tip_regularization.h): counted, not tested. Empty when there are none.
  std::vector<char> regularized_tips;
  std::shared_ptr<Vertex_order_cache> vertex_order = std::make_shared<Vertex_order_cache>();

  std::size_t degree(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
};

// Whether every weight is positive (Tutte's, admissible ones, cotangent weights of a Delaunay mesh).
inline bool has_positive_weights(const Sphere_system& system)
{
  for(double w : system.weights)
    if(!(w > 0.))
      return false;
  return true;
}

// Builds the counter-clockwise rings of the triangles on `n` vertices, and keeps the triangles: the system is where
// they are stored from here on (the pipeline moves them in). Requires a closed, oriented, vertex-manifold triangle
// mesh (one that passed check_mesh_arrays(): the callers check the input first, so a violation here is a bug, not a
// user error).
inline Sphere_system make_connectivity(std::vector<std::array<int, 3>> triangles, std::size_t n)
{
  CGAL_precondition(!triangles.empty());
  Sphere_system system;
  system.number_of_vertices = n;
  system.triangles = std::move(triangles);
  const std::vector<std::array<int, 3>>& faces = system.triangles;
  system.offsets.assign(n + 1, 0);
  for(const auto& t : faces)
    for(int i : t)
      ++system.offsets[static_cast<std::size_t>(i) + 1];
  for(std::size_t i = 0; i < n; ++i)
    system.offsets[i + 1] += system.offsets[i];

  // For vertex v in face f = (v, b, c), c follows b counter-clockwise around v.
  std::vector<std::array<int, 3>> successor(system.offsets[n]);
  {
    std::vector<std::size_t> fill(system.offsets.begin(), system.offsets.end() - 1);
    for(std::size_t f = 0; f < faces.size(); ++f)
    {
      const auto& t = faces[f];
      for(int k = 0; k < 3; ++k)
        successor[fill[static_cast<std::size_t>(t[k])]++] = {t[(k + 1) % 3], t[(k + 2) % 3], static_cast<int>(f)};
    }
  }
  system.neighbors.resize(system.offsets[n]);
  system.ring_faces.resize(system.offsets[n]);
  for(std::size_t v = 0; v < n; ++v)
  {
    auto first = successor.begin() + static_cast<std::ptrdiff_t>(system.offsets[v]);
    auto last = successor.begin() + static_cast<std::ptrdiff_t>(system.offsets[v + 1]);
    std::sort(first, last);
    auto entry = first;
    for(std::size_t k = system.offsets[v]; k < system.offsets[v + 1]; ++k)
    {
      // Closed and vertex-manifold: the face after each face around v exists.
      CGAL_assertion(entry != last);
      system.neighbors[k] = (*entry)[0];
      system.ring_faces[k] = (*entry)[2];
      const std::array<int, 3> key{(*entry)[1], -1, -1};
      entry = std::lower_bound(first, last, key);
      CGAL_assertion(entry != last && (*entry)[0] == key[0]);
    }
    // One fan: the walk came back to the face it started from.
    CGAL_assertion(entry == first);
  }

  system.reverse.resize(system.neighbors.size());
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
      for(std::size_t m = system.offsets[j]; m < system.offsets[j + 1]; ++m)
        if(system.neighbors[m] == static_cast<int>(i))
        {
          system.reverse[k] = m;
          break;
        }
      CGAL_assertion(system.neighbors[system.reverse[k]] == static_cast<int>(i)); // closed: (j, i) exists
    }
  return system;
}

// The same with a copy of the mesh's triangles (the mesh keeps its own).
inline Sphere_system make_connectivity(const Mesh_arrays& mesh)
{
  return make_connectivity(mesh.triangles, mesh.points.size());
}

// Degenerate corners (zero-area faces, coincident vertices, needles) make cotangent and mean-value weights
// infinite or NaN. Angles outside [minimum_corner_angle, pi - minimum_corner_angle] count as the nearest bound,
// and edge lengths are bounded from below, so every weight stays finite; such weights are counted as clamped.
// The bound leaves real needles (a CAD mesh's 0.0003 degree = 5e-6 rad slivers) untouched, and every other
// corner gets exactly the usual formula.
constexpr double minimum_corner_angle = 1e-6;

// -1: the angle between a and b is below the bound (or undefined: a zero vector), 1: above pi minus the bound.
inline int out_of_bounds(double sine_length, double cosine_length)
{
  const double angle = std::atan2(sine_length, cosine_length);
  if(!(angle >= minimum_corner_angle))
    return -1;
  return angle > CGAL_PI - minimum_corner_angle ? 1 : 0;
}

// Cotangent of the angle between a and b.
inline double bounded_cotangent(const Vector3& a, const Vector3& b, bool& clamped)
{
  const double s = length(cross(a, b)), c = dot(a, b);
  const int side = out_of_bounds(s, c);
  if(side == 0)
    return c / s;
  clamped = true;
  return -side / std::tan(minimum_corner_angle);
}

// Tangent of half the angle between a and b.
inline double bounded_tangent_of_half_angle(const Vector3& a, const Vector3& b, bool& clamped)
{
  const double s = length(cross(a, b)), c = dot(a, b);
  const int side = out_of_bounds(s, c);
  if(side == 0)
    return s / (length(a) * length(b) + c);
  clamped = true;
  return side < 0 ? std::tan(0.5 * minimum_corner_angle) : 1. / std::tan(0.5 * minimum_corner_angle);
}

// Raw weight of neighbour j = ring[k] in the equation of vertex i, from the two faces (i, j, next), (i, prev, j).
// `minimum_length` bounds the edge length of mean-value weights from below.
inline double geometric_weight(Weighting weighting, const std::vector<Vector3>& p, std::size_t i, int prev, int j,
                               int next, double minimum_length, bool& clamped)
{
  const Vector3& xi = p[i];
  const Vector3& xj = p[static_cast<std::size_t>(j)];
  const Vector3& xn = p[static_cast<std::size_t>(next)];
  const Vector3& xp = p[static_cast<std::size_t>(prev)];
  switch(weighting)
  {
  case Weighting::COTANGENT:
    return 0.5 * (bounded_cotangent(xi - xn, xj - xn, clamped) + bounded_cotangent(xi - xp, xj - xp, clamped));
  case Weighting::MEAN_VALUE:
  {
    double edge = length(xj - xi);
    if(!(edge >= minimum_length))
    {
      clamped = true;
      edge = minimum_length;
    }
    return (bounded_tangent_of_half_angle(xj - xi, xn - xi, clamped)
            + bounded_tangent_of_half_angle(xp - xi, xj - xi, clamped))
           / edge;
  }
  default:
    return 1.;
  }
}

// Fills and normalizes the weights. `user_weight(i, j)` is used for Weighting::USER_MAP (never clamped: the
// user's weights are taken as given). Returns OK, or INVALID_WEIGHTS with a message naming the first bad vertex
// (a non-finite weight, or weights that do not sum to a positive value, e.g. cotangent weights around a vertex
// whose obtuse corners outweigh the rest).
inline Error_code assign_weights(Sphere_system& system, const Mesh_arrays& mesh, Weighting weighting,
                                 const std::function<double(std::size_t, int)>& user_weight, std::string& message)
{
  const std::size_t n = system.number_of_vertices;
  system.weights.assign(system.neighbors.size(), 1.);
  system.row_sums.assign(n, 1.);
  system.clamped_weights = 0;
  system.signed_laplacian_semidefinite = false;
  // Edge lengths below 1e-12 of the bounding box diagonal (coincident vertices) count as that length.
  Vector3 low = n > 0 ? mesh.points[0] : Vector3(), high = low;
  for(const Vector3& q : mesh.points)
  {
    low = Vector3(std::min(low.x, q.x), std::min(low.y, q.y), std::min(low.z, q.z));
    high = Vector3(std::max(high.x, q.x), std::max(high.y, q.y), std::max(high.z, q.z));
  }
  const double diagonal = length(high - low);
  const double minimum_length = diagonal > 0. && std::isfinite(diagonal) ? 1e-12 * diagonal : 1e-300;
  for(std::size_t i = 0; i < n; ++i)
  {
    const std::size_t begin = system.offsets[i], end = system.offsets[i + 1], d = end - begin;
    double sum = 0.;
    for(std::size_t k = begin; k < end; ++k)
    {
      const int j = system.neighbors[k];
      const int next = system.neighbors[begin + (k - begin + 1) % d];
      const int prev = system.neighbors[begin + (k - begin + d - 1) % d];
      bool clamped = false;
      const double w = weighting == Weighting::USER_MAP
                           ? user_weight(i, j)
                           : geometric_weight(weighting, mesh.points, i, prev, j, next, minimum_length, clamped);
      system.clamped_weights += clamped;
      if(!std::isfinite(w))
      {
        message = "the weight of edge (" + std::to_string(input_vertex_index(mesh, i)) + ", "
                  + std::to_string(input_vertex_index(mesh, static_cast<std::size_t>(j)))
                  + ") is not finite (degenerate geometry?)";
        return Error_code::INVALID_WEIGHTS;
      }
      system.weights[k] = w;
      sum += w;
    }
    if(!(sum > 0.) || !std::isfinite(1. / sum))
    {
      std::ostringstream text;
      text << "the weights around vertex " << input_vertex_index(mesh, i) << " sum to " << sum
           << " (they must sum to a positive value)";
      message = text.str();
      return Error_code::INVALID_WEIGHTS;
    }
    for(std::size_t k = begin; k < end; ++k)
      system.weights[k] /= sum;
    system.row_sums[i] = sum;
  }
  system.signed_laplacian_semidefinite = weighting == Weighting::COTANGENT && system.clamped_weights == 0;
  system.symmetric = true;
  for(std::size_t i = 0; i < n && system.symmetric; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
      const double wij = system.weights[k] * system.row_sums[i],
                   wji = system.weights[system.reverse[k]] * system.row_sums[j];
      if(std::abs(wij - wji) > 1e-12 * (std::abs(wij) + std::abs(wji)))
      {
        system.symmetric = false;
        break;
      }
    }
  return Error_code::OK;
}

// Replaces the weights by the closest ones the theory covers (Gotsman, Gu and Sheffer: symmetric and positive; a
// bijective balanced solution is still not guaranteed, see inscribability.h's tetrahedron): w_ij and w_ji by their
// mean,
// then every weight below 1% of the mean weight of its two vertices by that 1%. Works on the raw weights, then
// normalizes again. Returns the number of edges whose weight was raised.
inline std::size_t make_weights_admissible(Sphere_system& system)
{
  const std::size_t n = system.number_of_vertices;
  std::vector<double> raw(system.weights.size());
  std::vector<double> mean_magnitude(n, 0.);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
      raw[k] = 0.5 * (system.weights[k] * system.row_sums[i] + system.weights[system.reverse[k]] * system.row_sums[j]);
      mean_magnitude[i] += std::abs(raw[k]) / static_cast<double>(system.degree(i));
    }
  std::size_t clamped = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    double sum = 0.;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[k]);
      const double floor = 0.01 * 0.5 * (mean_magnitude[i] + mean_magnitude[j]);
      if(raw[k] < floor)
      {
        raw[k] = floor;
        clamped += i < j; // each edge once
      }
      sum += raw[k];
    }
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
      system.weights[k] = raw[k] / sum;
    system.row_sums[i] = sum;
  }
  system.symmetric = true;
  return clamped;
}

// sum_j w_ij x_j
inline Vector3 weighted_neighbor_sum(const Sphere_system& system, const std::vector<Vector3>& x, std::size_t i)
{
  Vector3 s;
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    s += system.weights[k] * x[static_cast<std::size_t>(system.neighbors[k])];
  return s;
}

// The tangential part of s at the unit vector x: s - (x.s) x, i.e. alpha x - s up to sign with alpha = x.s.
inline Vector3 tangential_part(const Vector3& x, const Vector3& s)
{
  return s - dot(x, s) * x;
}

struct Residuals
{
  double paper = 0.;          // (1/n) sqrt(sum |r_i|^2), the paper's Res
  double max_tangential = 0.; // max |r_i|
};

// The residual alpha_i x_i - sum_j w_ij x_j of vertex i (normalized weights, alpha_i = x_i . sum_j w_ij x_j),
// written as the tangential part of sum_j w_ij (x_j - x_i): the differences keep the digits of tiny triangles,
// which sums of O(1) positions would lose.
inline Vector3 tangential_residual(const Sphere_system& system, const std::vector<Vector3>& x, std::size_t i)
{
  Vector3 s;
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    s += system.weights[k] * (x[static_cast<std::size_t>(system.neighbors[k])] - x[i]);
  return tangential_part(x[i], s);
}

inline Residuals compute_residuals(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double sum = 0., largest = 0.;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
  {
    const double r2 = squared_length(tangential_residual(system, x, i));
    sum += r2;
    largest = std::max(largest, r2);
  }
  Residuals r;
  r.paper = std::sqrt(sum) / static_cast<double>(std::max<std::size_t>(system.number_of_vertices, 1));
  r.max_tangential = std::sqrt(largest);
  return r;
}

// The imbalance of vertex i, the default convergence measure: e_i = |t_i| / l_i with d_i = sum_j w_ij (x_j - x_i)
// (normalized weights), t_i its tangential part at x_i and l_i = sum_j |w_ij| s(|x_j - x_i|): how far x_i is from
// the balance point of its neighbours, in units of its own neighbourhood, whatever the size of its triangles. The
// differences keep the digits of spherical edges of 1e-10, which sums of O(1) positions would lose.
// s(c) = c sqrt(1 - c^2/4) is the length of the tangential part of an edge of chord c (the sine of its angle): an
// edge to a nearly antipodal neighbour pulls radially, so its chord would hide the vertex's imbalance in l_i (the
// collapse of a tetrahedron onto two antipodal points passed with e_i 7e-7 before). s(c) <= c, so the test is never
// looser than with chords, and stricter by 1 / sqrt(1 - c^2/4) <= 1.01 on edges up to 16 degrees.
//
// Positions rounded to double carry an imbalance of their own: moving x_i and its neighbours by half an ulp
// (|dx| <= sqrt(3) 2^-53 each) changes d_i by up to 2 sqrt(3) 2^-53 sum_j |w_ij|. `rounding_floor` is
// imbalance_rounding_factor times that, over sum_j |w_ij| |x_j - x_i| (chords: at most l_i / 0.7 on a mesh's
// edges, which stay below 90 degrees): below it no solver can balance the vertex in double precision, so a vertex
// passes when e_i <= max(tolerance, rounding_floor_i). Over l_i itself, a neighbour near the antipode (an edge of
// nearly 180 degrees, which no balanced map of a mesh has) made the floor of a collapse 0.27 to 0.5: CGAL's
// tetrahedra with cotangent weights passed, three vertices within 1e-14 of each other and the fourth opposite. The
// floor depends only on the |w|-weighted mean chord (sum_j |w_ij| cancels, whatever the signs); it exceeds 1e-6 only
// below a mean chord of about 3e-9 (the thin limbs of organic models); such vertices are counted and reported. A
// floor above max_rounding_floor would make a test that cannot fail (every e_i is at most 1, up to rounding): it
// means a mean chord below below_precision_mean_chord, and such a vertex is counted as below precision, not tested
// (a map collapsed within rounding onto two points, found by the fuzzer, is rejected by the certificate). The
// thin limbs of CGAL's man.off and of oded_scorpion have floors up to a few 1e-2 and stay testable.
constexpr double imbalance_rounding_factor = 8.;
constexpr double max_rounding_floor = 0.5;
// A vertex whose neighbours are all within this mean chord of it (about 28 ulps of 1: exactly where its floor
// reaches max_rounding_floor) is below double precision: its balance cannot be told from rounding, so it is counted
// (Result::vertices_below_precision), not tested. The thin arms of marching-cubes surfaces (length over radius above
// about 35) have balanced maps whose tips shrink below 1e-16, where positions coincide as doubles; the arms' resolved
// vertices, including those around every such tip, are still tested. A resolved vertex never passes only where its
// floor is infinite (every neighbour on it or at its antipode).
constexpr double below_precision_mean_chord =
    imbalance_rounding_factor * 2. * 1.7320508075688772 * 1.1102230246251565e-16 / max_rounding_floor;

// s = |x_i x e|, the length of the tangential part at the unit vector x_i of the edge e = x_j - x_i: c sqrt(1 - c^2/4)
// for the chord c = |e|, written as a cross product because 1 - c^2/4 cancels near antipodal neighbours (rounding
// made s 2e-8 for a neighbour within 1e-15 of the antipode).
inline double tangential_edge_length(const Vector3& x_i, const Vector3& e)
{
  return length(cross(x_i, e));
}
// ds/dc = (1 - c^2/2) / cos(theta/2) with cos(theta/2) = s / c; capped near antipodal neighbours (-infinity there).
inline double tangential_edge_length_derivative(double chord, double tangential)
{
  const double half_angle_cosine = chord > 0. ? tangential / chord : 1.;
  return (1. - 0.5 * chord * chord) / std::max(1e-8, half_angle_cosine);
}

struct Vertex_imbalance
{
  double imbalance = 0.;        // e_i
  double rounding_floor = 0.;   // the smallest e_i that double precision can promise at this vertex
  double squared_residual = 0.; // |t_i|^2: the vertex's term of the paper's Res (compute_residuals)
  // |t_i| / sum_j |w_ij| |x_j - x_i|, with chords: what the line searches lower (imbalance_merit). It differs from
  // e_i only next to nearly antipodal neighbours, and changing the merit changes the Newton paths on hard meshes
  // (CGAL's handle.off took a different path with e_i as the merit and did not converge).
  double chordal_imbalance = 0.;
  // Every neighbour within below_precision_mean_chord of x_i (weighted mean): not tested.
  bool below_precision = false;
};

inline Vertex_imbalance vertex_imbalance(const Sphere_system& system, const std::vector<Vector3>& x, std::size_t i)
{
  Vector3 d;
  double scale = 0., chordal_scale = 0., weight_magnitude = 0.;
  for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
  {
    const Vector3 e = x[static_cast<std::size_t>(system.neighbors[k])] - x[i];
    const double w = system.weights[k];
    d += w * e;
    scale += std::abs(w) * tangential_edge_length(x[i], e);
    chordal_scale += std::abs(w) * length(e);
    weight_magnitude += std::abs(w);
  }
  Vertex_imbalance result;
  result.squared_residual = squared_length(tangential_part(x[i], d));
  const double tangential = std::sqrt(result.squared_residual);
  constexpr double half_ulp = 1.1102230246251565e-16; // 2^-53
  if(scale > 0.)
  {
    result.imbalance = tangential / scale;
    result.rounding_floor =
        imbalance_rounding_factor * 2. * std::sqrt(3.) * half_ulp * weight_magnitude / chordal_scale;
  }
  else
  {
    // Every neighbour on top of x_i: balanced when nothing pulls, infinitely far from it otherwise.
    result.imbalance = tangential > 0. ? HUGE_VAL : 0.;
    result.rounding_floor = HUGE_VAL;
  }
  result.below_precision = chordal_scale <= below_precision_mean_chord * weight_magnitude
                           || (!system.regularized_tips.empty() && system.regularized_tips[i]);
  result.chordal_imbalance = chordal_scale > 0. ? tangential / chordal_scale : result.imbalance;
  if(!(result.imbalance == result.imbalance))
    result.imbalance = HUGE_VAL; // NaN positions are never balanced
  if(!(result.chordal_imbalance == result.chordal_imbalance))
    result.chordal_imbalance = HUGE_VAL;
  return result;
}

// A scale-free measure of how far the whole map is from balanced: the root mean square of the imbalances (with
// chords, see Vertex_imbalance::chordal_imbalance).
// The paper's Res measures the forces in absolute terms, so any shrinking of the map lowers it and the trivial
// collapse onto a point has Res = 0: the iterate of lowest Res, or a line search on Res, can prefer a collapse
// (CGAL's handle and sphere966 ended collapsed onto a point, Res 1e-17, max imbalance 0.44 and 0.56). A collapse
// keeps the imbalances near 0.5.
inline double imbalance_merit(const Sphere_system& system, const std::vector<Vector3>& x)
{
  double sum = 0.;
  for(std::size_t i = 0; i < system.number_of_vertices; ++i)
  {
    const double e = vertex_imbalance(system, x, i).chordal_imbalance;
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(system.number_of_vertices, 1)));
}

struct Imbalance_summary
{
  double max = 0.;           // max_i e_i
  double rms = 0.;           // the root mean square of the merits given (imbalance_merit: chordal)
  double percentile_99 = 0.; // the 99th percentile of e_i (when the values were asked for)
  double worst_ratio = 0.;   // max_i e_i / max(tolerance, rounding_floor_i): <= 1 when balanced
  std::size_t unbalanced_vertices =
      0; // e_i > max(tolerance, rounding_floor_i), or rounding_floor_i > max_rounding_floor
  std::size_t vertices_at_rounding_floor = 0; // rounding_floor_i > tolerance: tested against their floor
  std::size_t vertices_below_precision = 0;   // Vertex_imbalance::below_precision: counted, not tested
  bool balanced() const { return unbalanced_vertices == 0; }
};

// Builds an Imbalance_summary from per-vertex values, each tested against max(tolerance, its rounding floor).
class Imbalance_accumulator
{
public:
  explicit Imbalance_accumulator(double tolerance) : m_tolerance(tolerance) {}
  // `merit`: what the root mean square adds up (by default the value itself). A vertex `below_precision` adds to the
  // root mean square only.
  void add(double value, double rounding_floor, double merit = -1., bool below_precision = false)
  {
    ++m_count;
    m_sum_of_squares += merit >= 0. ? merit * merit : value * value;
    if(below_precision)
    {
      ++m_summary.vertices_below_precision;
      return;
    }
    const double allowed = std::max(m_tolerance, rounding_floor);
    const bool measurable = rounding_floor <= max_rounding_floor;
    m_summary.max = std::max(m_summary.max, value);
    m_summary.worst_ratio =
        std::max(m_summary.worst_ratio, allowed > 0. ? value / allowed : (value > 0. ? HUGE_VAL : 0.));
    m_summary.unbalanced_vertices += !(measurable && value <= allowed);
    m_summary.vertices_at_rounding_floor += rounding_floor > m_tolerance;
  }
  Imbalance_summary summary() const
  {
    Imbalance_summary result = m_summary;
    result.rms = std::sqrt(m_sum_of_squares / static_cast<double>(std::max<std::size_t>(m_count, 1)));
    return result;
  }

private:
  double m_tolerance;
  Imbalance_summary m_summary;
  double m_sum_of_squares = 0.;
  std::size_t m_count = 0;
};

// The imbalance of every vertex against `tolerance`. `values` (optional) receives e_i; the percentile (of the tested
// vertices, as the maximum) is computed only then, so that the stopping tests of the iterations allocate nothing.
inline Imbalance_summary summarize_imbalance(const Sphere_system& system, const std::vector<Vector3>& x,
                                             double tolerance, std::vector<double>* values = nullptr)
{
  const std::size_t n = system.number_of_vertices;
  if(values != nullptr)
    values->resize(n);
  std::vector<double> tested;
  Imbalance_accumulator accumulator(tolerance);
  for(std::size_t i = 0; i < n; ++i)
  {
    const Vertex_imbalance v = vertex_imbalance(system, x, i);
    if(values != nullptr)
    {
      (*values)[i] = v.imbalance;
      if(!v.below_precision)
        tested.push_back(v.imbalance);
    }
    accumulator.add(v.imbalance, v.rounding_floor, v.chordal_imbalance, v.below_precision);
  }
  Imbalance_summary summary = accumulator.summary();
  const std::size_t m = tested.size();
  if(m > 0)
  {
    const std::size_t rank = std::min(m - 1, static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(m))) - 1);
    std::nth_element(tested.begin(), tested.begin() + static_cast<std::ptrdiff_t>(rank), tested.end());
    summary.percentile_99 = tested[rank];
  }
  return summary;
}

// The stationarity of the least-squares problem of non-symmetric weights (mean value), whose balance equations
// generally have no exact solution: the 2n tangential equations are 3 more than the unknowns modulo rotations once
// the three torque identities of symmetric weights fail. The map then minimizes the imbalances themselves,
//   Psi = 1/2 sum_i e_i^2,   e_i = |F_i| / l_i,   F_i = P_i sum_j w_ij (x_j - x_i),   l_i = sum_j |w_ij| s(c_ij)
// with c_ij = |x_j - x_i| and s the tangential edge length of vertex_imbalance (imbalance_least_squares.h): each
// vertex in its own scale, as the convergence test measures it. (The absolute
// residuals' problem, min sum_i |F_i|^2, is solved by the collapse onto a point: its iterations drifted along the
// boosts towards it and stalled; see the manual.) With alpha_k = sum_j w_kj x_k . x_j, U_k = sum_j |w_kj| s'(c_kj) u_kj
// and u_kj the unit vector from x_k to x_j, the gradient at vertex k is the tangential part of
//   -alpha_k F_k / l_k^2 + |F_k|^2 U_k / l_k^3 + m_sum{j: k in N(j)} (w_jk F_j / l_j^2 - |w_jk| s'(c_jk) |F_j|^2 u_jk / l_j^3).
// In the scale of the imbalance, sigma_k = |grad_k Psi| / S_k with S_k = |alpha_k| / l_k + m_sum{j: k in N(j)}
// |w_jk| / l_j: the size the gradient would have if every e_i of its terms were 1. Balanced maps have sigma = 0.
// Its rounding floor is the imbalance's, carried through the same terms.
struct Least_squares_terms
{
  std::vector<Vector3> force;    // F_i
  std::vector<Vector3> pull;     // U_i
  std::vector<double> scale;     // l_i
  std::vector<double> alpha;     // alpha_i
  std::vector<double> magnitude; // sum_j |w_ij|
};

inline void compute_least_squares_terms(const Sphere_system& system, const std::vector<Vector3>& x,
                                        Least_squares_terms& terms)
{
  const std::size_t n = system.number_of_vertices;
  terms.force.resize(n);
  terms.pull.resize(n);
  terms.scale.resize(n);
  terms.alpha.resize(n);
  terms.magnitude.resize(n);
  for(std::size_t i = 0; i < n; ++i)
  {
    Vector3 d, u;
    double a = 0., l = 0., m = 0.;
    for(std::size_t k = system.offsets[i]; k < system.offsets[i + 1]; ++k)
    {
      const Vector3 e = x[static_cast<std::size_t>(system.neighbors[k])] - x[i];
      const double w = system.weights[k];
      const double length_e = length(e);
      d += w * e;
      a += w * (1. - 0.5 * squared_length(e));
      const double tangential_e = tangential_edge_length(x[i], e);
      l += std::abs(w) * tangential_e;
      m += std::abs(w);
      if(length_e > 0.)
        u += (std::abs(w) * tangential_edge_length_derivative(length_e, tangential_e) / length_e) * e;
    }
    terms.force[i] = tangential_part(x[i], d);
    terms.pull[i] = u;
    terms.scale[i] = l;
    terms.alpha[i] = a;
    terms.magnitude[i] = m;
  }
}

// S_k = |alpha_k| / l_k + m_sum{j: k in N(j)} |w_jk| / l_j, and (if `noise` is given) the rounding floor of the
// gradient carried through the same terms.
inline double stationarity_size(const Sphere_system& system, const Least_squares_terms& terms, std::size_t k,
                                double* noise = nullptr)
{
  constexpr double half_ulp = 1.1102230246251565e-16; // 2^-53
  const double rounding = imbalance_rounding_factor * 2. * std::sqrt(3.) * half_ulp;
  const double lk = terms.scale[k];
  double size = lk > 0. ? std::abs(terms.alpha[k]) / lk : 0.;
  double floor = lk > 0. ? size * rounding * terms.magnitude[k] / lk : 0.;
  for(std::size_t e = system.offsets[k]; e < system.offsets[k + 1]; ++e)
  {
    const std::size_t j = static_cast<std::size_t>(system.neighbors[e]);
    if(!(terms.scale[j] > 0.))
      continue;
    const double term = std::abs(system.weights[system.reverse[e]]) / terms.scale[j];
    size += term;
    floor += term * rounding * terms.magnitude[j] / terms.scale[j];
  }
  if(noise != nullptr)
    *noise = floor;
  return size;
}

// sigma_k against `tolerance` with its rounding floor, given |gradient_k| for every vertex.
template <typename GradientNorm>
Imbalance_summary summarize_stationarity(const Sphere_system& system, const Least_squares_terms& terms,
                                         double tolerance, GradientNorm&& gradient_norm)
{
  Imbalance_accumulator accumulator(tolerance);
  for(std::size_t k = 0; k < system.number_of_vertices; ++k)
  {
    double noise = 0.;
    const double size = stationarity_size(system, terms, k, &noise);
    const double g = gradient_norm(k);
    double sigma = size > 0. ? g / size : (g > 0. ? HUGE_VAL : 0.);
    if(!(sigma == sigma))
      sigma = HUGE_VAL;
    accumulator.add(sigma, size > 0. ? noise / size : HUGE_VAL);
  }
  return accumulator.summary();
}

inline Imbalance_summary summarize_stationarity(const Sphere_system& system, const std::vector<Vector3>& x,
                                                double tolerance)
{
  Least_squares_terms terms;
  compute_least_squares_terms(system, x, terms);
  return summarize_stationarity(system, terms, tolerance, [&](std::size_t k) {
    const double lk = terms.scale[k];
    Vector3 g;
    if(lk > 0.)
      g = (-terms.alpha[k] / (lk * lk)) * terms.force[k]
          + (squared_length(terms.force[k]) / (lk * lk * lk)) * terms.pull[k];
    for(std::size_t e = system.offsets[k]; e < system.offsets[k + 1]; ++e)
    {
      const std::size_t j = static_cast<std::size_t>(system.neighbors[e]);
      const double lj = terms.scale[j];
      if(!(lj > 0.))
        continue;
      const double w = system.weights[system.reverse[e]]; // w_jk
      const Vector3 edge = x[k] - x[j];
      const double length_edge = length(edge);
      g += (w / (lj * lj)) * terms.force[j];
      if(length_edge > 0.)
        g -= (std::abs(w) * tangential_edge_length_derivative(length_edge, tangential_edge_length(x[j], edge))
              * squared_length(terms.force[j]) / (lj * lj * lj * length_edge))
             * edge;
    }
    return length(tangential_part(x[k], g));
  });
}

// What the iterations watch, from one pass over the vertices: the paper's Res and the imbalances.
struct Map_measure
{
  double residual = 0.;           // the paper's Res (compute_residuals)
  Imbalance_summary imbalance;    // against the tolerance of the convergence test, with the root mean square
  bool least_squares = false;     // non-symmetric weights: the test is the stationarity below, not the imbalance
  Imbalance_summary stationarity; // summarize_stationarity (non-symmetric weights only)
  // What the imbalance test bounds: the imbalances, or the stationarity of the least-squares problem.
  const Imbalance_summary& tested() const { return least_squares ? stationarity : imbalance; }
};

inline Map_measure measure_map(const Sphere_system& system, const std::vector<Vector3>& x, double tolerance)
{
  const std::size_t n = system.number_of_vertices;
  Map_measure measure;
  Imbalance_accumulator accumulator(tolerance);
  double squared_residuals = 0.;
  for(std::size_t i = 0; i < n; ++i)
  {
    const Vertex_imbalance v = vertex_imbalance(system, x, i);
    squared_residuals += v.squared_residual;
    accumulator.add(v.imbalance, v.rounding_floor, v.chordal_imbalance, v.below_precision);
  }
  measure.imbalance = accumulator.summary();
  measure.residual = std::sqrt(squared_residuals) / static_cast<double>(std::max<std::size_t>(n, 1));
  if(!system.symmetric)
  {
    measure.least_squares = true;
    measure.stationarity = summarize_stationarity(system, x, tolerance);
  }
  return measure;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SPHERE_SYSTEM_H
