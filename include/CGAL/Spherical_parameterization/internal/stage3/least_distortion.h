// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The bijective map of least conformal distortion (named parameter least_distortion): where the balanced map of
// shape-preserving weights is not reached (it folds, or for mean value does not exist), a minimum of
//   F(x) = sum_f A_f * (sum_k cot(theta_k) |e'_k|^2) / (4 S_f),
// the conformal distortion (MIPS) of the flat triangle through the three sphere points against the 3D triangle:
// theta_k the 3D angles, A_f the 3D areas over their sum, e'_k the edges of the flat triangle, S_f its area signed by
// the orientation the certificate tests (det(a, b, c) / (2 |c|), c the centroid, |c| floored: centroid_floor; |N_f| / 2 would not vanish where three points of one great circle make a degenerate spherical triangle). The term of a face is A_f times
// (s1^2 + s2^2) / (2 s1 s2) (s1, s2 the singular values of the affine map between the two triangles) times |N_f| /
// (2 S_f), which is 1 for faces small against the sphere and a little above 1 for large ones (the regular
// tetrahedron: F = 1.04): at least A_f, about A_f for similar small triangles, and infinite as the face degenerates
// on the sphere, so F is minimized over the open
// set of bijective maps: a minimization, unlike the balance equations (a saddle), and its stationarity can be tested.
// Newton's method in the tangent planes: per-face Hessians projected on their positive part until full steps are
// accepted, then the whole Hessian (its factorization's negative pivots, a handful, taken by their magnitude) while
// full steps are accepted; a Marquardt shift on the diagonal;
// every trial point keeps every face positive; before the first step and after each one the three Moebius boosts,
// along which F is nearly flat, are balanced by Newton's method of their own (balance_distortion_boosts). The
// manual's Method section says why and what it gives.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_LEAST_DISTORTION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_LEAST_DISTORTION_H

#include <CGAL/Spherical_parameterization/internal/Vector3.h>
#include <CGAL/Spherical_parameterization/internal/iteration_driver.h>
#include <CGAL/Spherical_parameterization/internal/side_by_side.h>
#include <CGAL/Spherical_parameterization/internal/small_symmetric_matrix.h>
#include <CGAL/Spherical_parameterization/internal/stage3/mobius.h>
#include <CGAL/Spherical_parameterization/internal/stage3/supernodal_ldlt.h>

#include <CGAL/Real_timer.h>
#include <CGAL/assertions.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Least_distortion_report
{
  bool started = false;    // the start had every face positive (in the orientation used here)
  bool stationary = false; // every vertex's stationarity <= the tolerance (or its rounding floor)
  bool out_of_time = false;
  bool cancelled = false;
  std::size_t newton_steps = 0; // steps taken (accepted by the line search)
  std::size_t boosts = 0;       // boosts applied between them (balance_distortion_boosts)
  double energy = -1.; // F (3D areas summing to 1): about 1 when every small triangle keeps its shape
  double max_stationarity = -1.; // max_k sigma_k, 0 for the vertices within their rounding floor
  std::size_t unstationary_vertices = 0;
  std::size_t vertices_at_rounding_floor = 0; // sigma_k above the tolerance but within its rounding floor
  double last_step_seconds = 0.; // the last pass that took or tried a step: its assembly, factorization, line search
};

namespace least_distortion_detail {

using V3 = Eigen::Vector3d;
using Vector9 = Eigen::Matrix<double, 9, 1>;
using Matrix9 = Eigen::Matrix<double, 9, 9>;

inline V3 to_eigen(const Vector3& v) { return V3(v.x, v.y, v.z); }

inline Eigen::Matrix3d cross_matrix(const V3& v)
{
  Eigen::Matrix3d m;
  m << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
  return m;
}

// The orientation seen from the origin, in the relative form (differences first: triangles with edges of 1e-10
// keep their digits): ((b - a) x (c - a)) . (a + b + c) = 3 det(a, b, c).
inline double orientation(const V3& a, const V3& b, const V3& c) { return (b - a).cross(c - a).dot(a + b + c); }

struct Face_shape
{
  double weight = 0.; // A_f over the sum of the 3D areas
  double cot[3] = {0., 0., 0.}; // of the 3D angle at each corner
};

// Where a face spans nearly a hemisphere its centroid c nears the origin: there |N| stays large while det -> 0 (the
// orientation flips with no change of the flat triangle's shape), and det / |c| is 0 / 0. |c| is therefore taken as
// sqrt(|c|^2 + centroid_floor^2), scaled so that small faces (|c| = 1) are unchanged: a barrier on det there too (the
// tetrahedra of CGAL's data stalled at |c| = 3e-7 without it).
constexpr double centroid_floor = 0.1;

// What F_f and its derivatives share: the centroid c, |c| floored (c_norm), det = N.c, s = scale det / c_norm (twice
// the signed area), Q, and F_f = A_f Q / (2 s).
struct Face_terms
{
  V3 c;
  double c_norm, det, scale, s, q = 0., energy;

  Face_terms(const Face_shape& shape, const V3 (&p)[3])
  {
    const V3 e[3] = {p[2] - p[1], p[0] - p[2], p[1] - p[0]}; // e[k] opposite corner k
    c = (p[0] + p[1] + p[2]) / 3.;
    c_norm = std::sqrt(c.squaredNorm() + centroid_floor * centroid_floor);
    det = (p[1] - p[0]).cross(p[2] - p[0]).dot(c);
    scale = std::sqrt(1. + centroid_floor * centroid_floor);
    s = scale * det / c_norm;
    for(int k = 0; k < 3; ++k)
      q += shape.cot[k] * e[k].squaredNorm();
    energy = shape.weight * q / (2. * s);
  }
};

// What F_f's gradient and Hessian share (face_energy(), face_tangent_derivatives()): the face's cotangent Laplacian L
// (Q = p^T (L x I3) p), and the gradients of Q, det, |c| (floored) and s in the nine coordinates, and F_f's.
struct Face_gradients
{
  Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
  Vector9 grad_q, grad_det, grad_c, grad_s, gradient;

  Face_gradients(const Face_shape& shape, const V3 (&p)[3], const Face_terms& terms)
  {
    for(int k = 0; k < 3; ++k)
    {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      L(i, i) += shape.cot[k];
      L(j, j) += shape.cot[k];
      L(i, j) -= shape.cot[k];
      L(j, i) -= shape.cot[k];
    }
    // grad_q and grad_det in the relative form too (L's rows sum to 0; p_j x p_k = p_i x (p_k - p_j) + (p_j - p_i) x
    // (p_k - p_i)): the absolute forms sum_j L_ij p_j and p_j x p_k lost five digits to cancellation on faces squeezed
    // to edges of 1e-10 (CGAL's bull: the gradient's sum along a boost came out as 14.6 where differences of F give
    // 0.001), and the minimization crawled on that noise.
    for(int i = 0; i < 3; ++i)
    {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      grad_q.segment<3>(3 * i) = 2. * (L(i, j) * (p[j] - p[i]) + L(i, k) * (p[k] - p[i]));
      grad_det.segment<3>(3 * i) = p[i].cross(p[k] - p[j]) + (p[j] - p[i]).cross(p[k] - p[i]);
      grad_c.segment<3>(3 * i) = terms.c / (3. * terms.c_norm);
    }
    grad_s = terms.scale * (grad_det / terms.c_norm - terms.det * grad_c / (terms.c_norm * terms.c_norm));
    gradient = shape.weight / 2. * (grad_q / terms.s - terms.q * grad_s / (terms.s * terms.s));
  }
};

// F_f, and when asked its gradient and Hessian in the nine coordinates. s = N.c / |c| (twice the signed area; c the
// centroid, N = (p1 - p0) x (p2 - p0), so N.c = det(p0, p1, p2)); Q = sum_k cot_k |e'_k|^2 (the face's cotangent form).
inline double face_energy(const Face_shape& shape, const V3 (&p)[3], Vector9* gradient = nullptr,
                          Matrix9* hessian = nullptr)
{
  const Face_terms terms(shape, p);
  const V3& c = terms.c;
  const double c_norm = terms.c_norm, det = terms.det, scale = terms.scale, s = terms.s, q = terms.q;
  const double energy = terms.energy;
  if(gradient == nullptr)
    return energy;
  const Face_gradients gradients(shape, p, terms);
  const Eigen::Matrix3d& L = gradients.L;
  const Vector9 &grad_q = gradients.grad_q, &grad_det = gradients.grad_det, &grad_c = gradients.grad_c,
                &grad_s = gradients.grad_s;
  const double w = shape.weight / 2.;
  *gradient = gradients.gradient;
  if(hessian == nullptr)
    return energy;

  Matrix9 hess_q = Matrix9::Zero(), hess_det = Matrix9::Zero(), hess_c;
  for(int i = 0; i < 3; ++i)
  {
    for(int j = 0; j < 3; ++j)
      hess_q.block<3, 3>(3 * i, 3 * j) = 2. * L(i, j) * Eigen::Matrix3d::Identity();
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    hess_det.block<3, 3>(3 * i, 3 * j) = -cross_matrix(p[k]);
    hess_det.block<3, 3>(3 * j, 3 * i) = cross_matrix(p[k]);
  }
  const Eigen::Matrix3d hess_c1 =
      (Eigen::Matrix3d::Identity() - c * c.transpose() / (c_norm * c_norm)) / (9. * c_norm);
  for(int i = 0; i < 3; ++i)
    for(int j = 0; j < 3; ++j)
      hess_c.block<3, 3>(3 * i, 3 * j) = hess_c1;
  const Matrix9 hess_s = scale * (hess_det / c_norm
                         - (grad_det * grad_c.transpose() + grad_c * grad_det.transpose()) / (c_norm * c_norm)
                         + 2. * det * grad_c * grad_c.transpose() / (c_norm * c_norm * c_norm)
                         - det * hess_c / (c_norm * c_norm));
  *hessian = w * (hess_q / s - (grad_q * grad_s.transpose() + grad_s * grad_q.transpose()) / (s * s)
                  + 2. * q * grad_s * grad_s.transpose() / (s * s * s) - q * hess_s / (s * s));
  return energy;
}

// F_f, its gradient and Hessian in the coordinates of corner k alone (the smoother's moves): face_energy()'s
// formulas restricted to that corner's block, each entry computed by the same operations (the same values), for about
// a ninth of the cost of the whole Hessian.
inline double face_energy_at_corner(const Face_shape& shape, const V3 (&p)[3], int k, V3& gradient,
                                    Eigen::Matrix3d& hessian)
{
  const Face_terms terms(shape, p);
  const V3& c = terms.c;
  const double c_norm = terms.c_norm, det = terms.det, scale = terms.scale, s = terms.s, q = terms.q;
  const double energy = terms.energy;
  const int j = (k + 1) % 3, l = (k + 2) % 3;
  // L(k, j) = -cot at l, L(k, l) = -cot at j, L(k, k) = cot at j + cot at l (face_energy()'s order of the sums).
  const double L_kk = (0. + shape.cot[j]) + shape.cot[l];
  const double L_kj = 0. - shape.cot[l], L_kl = 0. - shape.cot[j];
  const V3 grad_q = 2. * (L_kj * (p[j] - p[k]) + L_kl * (p[l] - p[k]));
  const V3 grad_det = p[k].cross(p[l] - p[j]) + (p[j] - p[k]).cross(p[l] - p[k]);
  const V3 grad_c = c / (3. * c_norm);
  const V3 grad_s = scale * (grad_det / c_norm - det * grad_c / (c_norm * c_norm));
  const double w = shape.weight / 2.;
  gradient = w * (grad_q / s - q * grad_s / (s * s));
  const Eigen::Matrix3d hess_q = 2. * L_kk * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d hess_c =
      (Eigen::Matrix3d::Identity() - c * c.transpose() / (c_norm * c_norm)) / (9. * c_norm);
  const Eigen::Matrix3d hess_s = scale * (Eigen::Matrix3d::Zero() / c_norm
                                 - (grad_det * grad_c.transpose() + grad_c * grad_det.transpose()) / (c_norm * c_norm)
                                 + 2. * det * grad_c * grad_c.transpose() / (c_norm * c_norm * c_norm)
                                 - det * hess_c / (c_norm * c_norm));
  hessian = w * (hess_q / s - (grad_q * grad_s.transpose() + grad_s * grad_q.transpose()) / (s * s)
                 + 2. * q * grad_s * grad_s.transpose() / (s * s * s) - q * hess_s / (s * s));
  return energy;
}

// F_f, its gradient in the nine coordinates, and its gradient and Hessian in the corners' tangent bases `basis` (corner
// k's 3x2, orthonormal columns): face_energy()'s Hessian H, block (a, b) taken as basis[a]^T H_ab basis[b], but
// formed in the six coordinates directly (each outer product of two gradients is one of their projections; the blocks
// of Q's and det's Hessians are 2x2 products of the bases), a third of the operations of the 9x9 Hessian and its
// projection (bunny00's 75,408 faces at its map: 0.24 against 0.82 microseconds). The retraction's term is the
// caller's.
inline double face_tangent_derivatives(const Face_shape& shape, const V3 (&p)[3],
                                       const Eigen::Matrix<double, 3, 2> (&basis)[3], Vector9& gradient,
                                       Eigen::Matrix<double, 6, 1>& tangent_gradient,
                                       Eigen::Matrix<double, 6, 6>& tangent_hessian)
{
  const Face_terms terms(shape, p);
  const V3& c = terms.c;
  const double c_norm = terms.c_norm, det = terms.det, scale = terms.scale, s = terms.s, q = terms.q;
  const Face_gradients gradients(shape, p, terms);
  const Eigen::Matrix3d& L = gradients.L;
  const Vector9 &grad_q = gradients.grad_q, &grad_det = gradients.grad_det, &grad_s = gradients.grad_s;
  const V3 grad_c = gradients.grad_c.segment<3>(0); // the same at every corner
  const double w = shape.weight / 2.;
  gradient = gradients.gradient;
  // The projections (6-vectors) of the gradients, and of c.
  Eigen::Matrix<double, 6, 1> tq, tdet, tc, ts, tcent;
  for(int k = 0; k < 3; ++k)
  {
    const Eigen::Matrix<double, 2, 3> bt = basis[k].transpose();
    tq.segment<2>(2 * k) = bt * grad_q.segment<3>(3 * k);
    tdet.segment<2>(2 * k) = bt * grad_det.segment<3>(3 * k);
    tc.segment<2>(2 * k) = bt * grad_c;
    ts.segment<2>(2 * k) = bt * grad_s.segment<3>(3 * k);
    tcent.segment<2>(2 * k) = bt * c;
    tangent_gradient.segment<2>(2 * k) = bt * gradient.segment<3>(3 * k);
  }
  // Q's Hessian is 2 L (x) I3, det's has -[p_k]x in block (i, j) and [p_k]x in (j, i) for j = i + 1, k = i + 2, and
  // |c|'s (floored) is (I - c c^T / |c|^2) / (9 |c|) in every block.
  const double c2 = c_norm * c_norm;
  for(int a = 0; a < 3; ++a)
    for(int b = 0; b <= a; ++b)
    {
      const Eigen::Matrix2d dots = basis[a].transpose() * basis[b];
      Eigen::Matrix2d hess_det = Eigen::Matrix2d::Zero();
      if(a != b)
      {
        // (a, b) = (j, i) with j = i + 1 (mod 3): [p_k]x, k the third corner; (a, b) = (i, j): -[p_k]x.
        const int k = 3 - a - b;
        const double sign = a == (b + 1) % 3 ? 1. : -1.;
        for(int r = 0; r < 2; ++r)
          for(int t = 0; t < 2; ++t)
            hess_det(r, t) = sign * basis[a].col(r).dot(p[k].cross(basis[b].col(t)));
      }
      const Eigen::Matrix2d hess_c =
          (dots - tcent.segment<2>(2 * a) * tcent.segment<2>(2 * b).transpose() / c2) / (9. * c_norm);
      const Eigen::Matrix2d hess_s =
          scale * (hess_det / c_norm
                   - (tdet.segment<2>(2 * a) * tc.segment<2>(2 * b).transpose()
                      + tc.segment<2>(2 * a) * tdet.segment<2>(2 * b).transpose()) / c2
                   + 2. * det * tc.segment<2>(2 * a) * tc.segment<2>(2 * b).transpose() / (c2 * c_norm)
                   - det * hess_c / c2);
      Eigen::Matrix2d block =
          w * (2. * L(a, b) * dots / s
               - (tq.segment<2>(2 * a) * ts.segment<2>(2 * b).transpose()
                  + ts.segment<2>(2 * a) * tq.segment<2>(2 * b).transpose()) / (s * s)
               + 2. * q * ts.segment<2>(2 * a) * ts.segment<2>(2 * b).transpose() / (s * s * s) - q * hess_s / (s * s));
      if(a == b)
        block(0, 1) = block(1, 0); // symmetric to the last bit, as the blocks off the diagonal are
      tangent_hessian.block<2, 2>(2 * a, 2 * b) = block;
      tangent_hessian.block<2, 2>(2 * b, 2 * a) = block.transpose();
    }
  return terms.energy;
}

// The shapes of the 3D triangles (their cotangents, their areas over the sum); false if one is degenerate.
inline bool face_shapes(const std::vector<std::array<int, 3>>& triangles, const std::vector<Vector3>& points,
                        std::vector<Face_shape>& shapes)
{
  const std::size_t m = triangles.size();
  shapes.assign(m, Face_shape());
  double total_area = 0.;
  for(std::size_t f = 0; f < m; ++f)
  {
    V3 corner[3];
    for(int k = 0; k < 3; ++k)
      corner[k] = to_eigen(points[triangles[f][k]]);
    for(int k = 0; k < 3; ++k)
    {
      const V3 u = corner[(k + 1) % 3] - corner[k], v = corner[(k + 2) % 3] - corner[k];
      shapes[f].cot[k] = u.dot(v) / u.cross(v).norm();
    }
    shapes[f].weight = 0.5 * (corner[1] - corner[0]).cross(corner[2] - corner[0]).norm();
    total_area += shapes[f].weight;
  }
  for(Face_shape& shape : shapes)
  {
    shape.weight /= total_area;
    if(!std::isfinite(shape.weight) || !std::isfinite(shape.cot[0]) || !std::isfinite(shape.cot[1])
       || !std::isfinite(shape.cot[2]))
      return false; // a degenerate 3D triangle: no shape to keep
  }
  return true;
}

// A face's share of energy_and_boost_gradient() on several threads: whether it is positive, and the tangential parts
// of its gradient at its corners.
struct Face_boost_terms
{
  bool positive = false;
  std::array<V3, 3> tangential;
};

// F face by face at z (`terms`) and its gradient along the three boosts, sum_i of the tangential part of grad_i F
// (the boost field of e_l at z_i is e_l - (e_l . z_i) z_i); false if a face is not positive. With `parallel` the
// faces' terms are computed on all threads into `buffer`, then added up in the order of the faces by one: the same
// sums, to the last bit, as on one thread.
inline bool energy_and_boost_gradient(const std::vector<std::array<int, 3>>& triangles,
                                      const std::vector<Face_shape>& shapes, const std::vector<V3>& z,
                                      std::vector<double>& terms, V3& gradient, bool parallel = false,
                                      std::vector<Face_boost_terms>* buffer = nullptr)
{
  gradient.setZero();
  const std::size_t m = triangles.size();
  terms.resize(m);
  auto face_terms = [&](std::size_t f, Face_boost_terms& out) {
    V3 p[3];
    for(int k = 0; k < 3; ++k)
      p[k] = z[static_cast<std::size_t>(triangles[f][k])];
    out.positive = orientation(p[0], p[1], p[2]) > 0.;
    if(!out.positive)
      return;
    Vector9 g;
    terms[f] = face_energy(shapes[f], p, &g);
    for(int k = 0; k < 3; ++k)
    {
      const V3 gk = g.segment<3>(3 * k);
      out.tangential[k] = gk - gk.dot(p[k]) * p[k];
    }
  };
  auto add_up = [&](const Face_boost_terms& face) {
    for(int k = 0; k < 3 && face.positive; ++k)
      gradient += face.tangential[k];
    return face.positive;
  };
  if(parallel && buffer != nullptr)
  {
    buffer->resize(m);
    constexpr std::size_t grain = 256; // faces per task
    for_each_block(true, m, grain, [&](std::size_t begin, std::size_t end) {
      for(std::size_t f = begin; f < end; ++f)
        face_terms(f, (*buffer)[f]);
    });
    for(std::size_t f = 0; f < m; ++f)
      if(!add_up((*buffer)[f]))
        return false;
    return true;
  }
  Face_boost_terms face;
  for(std::size_t f = 0; f < m; ++f)
  {
    face_terms(f, face);
    if(!add_up(face))
      return false;
  }
  return true;
}

// (y + d) / |y + d| for a unit y and a tangent d, written as y plus a difference: as d -> 0 it gives y itself, bit for
// bit. Normalizing y + d instead rounds every vertex again, moved or not, and F of maps with slivers (edges of 1e-11)
// changes with that rounding: on oded_scorpion's finest level, F of y normalized once more differed from F of y by
// 2e-8, above what the last steps would lower it, and every step was refused.
inline V3 retract(const V3& y, const V3& d)
{
  const double s = d.squaredNorm(), root = std::sqrt(1. + s);
  return y + (d - (s / (1. + root)) * y) / root;
}

// `out`: the map z moved by the boost with vector c (mobius.h's Boost, applied to every vertex).
inline void boost_map(const std::vector<V3>& z, const V3& c, std::vector<V3>& out, bool parallel = false)
{
  const Boost boost(Vector3(c[0], c[1], c[2]));
  out.resize(z.size());
  for_each_block(parallel, z.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for(std::size_t i = begin; i < end; ++i)
    {
      const Vector3 b = boost(Vector3(z[i][0], z[i][1], z[i][2]));
      out[i] = V3(b.x, b.y, b.z);
    }
  });
}

// F's Hessian along the three boosts at z (symmetrized), from forward differences of the boost gradient `gradient`
// (energy_and_boost_gradient's at z); false if a boosted map has a face that is not positive.
inline bool boost_hessian(const std::vector<std::array<int, 3>>& triangles, const std::vector<Face_shape>& shapes,
                          const std::vector<V3>& z, const V3& gradient, Eigen::Matrix3d& hessian,
                          bool parallel = false, std::vector<Face_boost_terms>* buffer = nullptr)
{
  // A boost rounds every position again, which changes a face with edges of 1e-11 by eps / 1e-11 ~ 2e-5 of its size:
  // differences over boosts of 1e-5 were noise on a map with such faces (an indefinite Hessian), over 1e-3 they agree
  // with central differences.
  const double difference_step = 1e-3;
  std::vector<V3> moved_map;
  std::vector<double> terms;
  for(int l = 0; l < 3; ++l)
  {
    V3 moved;
    boost_map(z, difference_step * V3::Unit(l), moved_map, parallel);
    if(!energy_and_boost_gradient(triangles, shapes, moved_map, terms, moved, parallel, buffer))
      return false;
    hessian.col(l) = (moved - gradient) / difference_step;
  }
  hessian = (0.5 * (hessian + hessian.transpose())).eval();
  return true;
}

// F is nearly invariant under the Moebius boosts of the sphere (conformal maps: only the flat triangles through the
// sphere points tell them apart), so its Hessian is nearly singular along them and the Marquardt-shifted steps crawl
// there (from CGAL's bull after 1,000 steps, one exact boost of length 0.78 lowered F from 1.06226 to 1.05963, two
// thirds of the way to its minimum; its Hessian along the boosts: 0.004 to 0.012). Here Newton's method on the three
// boost parameters, their Hessian from forward differences of the boost gradient, each boost applied exactly
// (mobius.h), halved until F falls enough with every face positive. Where that Hessian is not positive definite: at
// the minimization's start (`at_start`), its eigenvalues' magnitudes (see below); later, no boost. At most
// `iterations`, while the decrease it predicts exceeds `share` times `reference` (what the last Newton step achieved;
// 0 before the first). Returns the number of boosts applied.
inline std::size_t balance_distortion_boosts(const std::vector<std::array<int, 3>>& triangles,
                                             const std::vector<Face_shape>& shapes, std::vector<V3>& y,
                                             int iterations, double share, double reference, bool at_start,
                                             bool parallel = false)
{
  std::vector<double> terms, trial_terms;
  std::vector<V3> trial;
  std::vector<Face_boost_terms> buffer; // energy_and_boost_gradient's with `parallel`
  std::size_t applied = 0;
  V3 gradient;
  if(!energy_and_boost_gradient(triangles, shapes, y, terms, gradient, parallel, &buffer))
    return 0;
  for(int iteration = 0; iteration < iterations; ++iteration)
  {
    Eigen::Matrix3d hessian;
    if(!boost_hessian(triangles, shapes, y, gradient, hessian, parallel, &buffer))
      return applied;
    V3 eigenvalues;
    Eigen::Matrix3d eigenvectors;
    if(!symmetric_eigen(hessian, eigenvalues, eigenvectors) || !(eigenvalues[at_start ? 2 : 0] > 0.))
      break;
    // A start (the levels' map carried back, a repaired balanced map) may sit anywhere along the boosts, where F is not
    // convex: there the step is Newton's with the eigenvalues' magnitudes, the smallest raised to 1e-3 times the
    // largest (a descent direction that also leaves the ridge). Skipped instead, the boosts were left to the Newton
    // steps on the whole map, which crawl along them: the minimization of bunny00 started from its cotangent balanced
    // map, as an experiment (eigenvalues -1.7e-5, 2.8e-4, 2.9e-4), took 8 steps, the last five along the boosts
    // (lengths 0.02 to 1), and 3 with this; triceratops with mean-value weights 21 instead of 31. Not after the steps: near the minimum, on
    // maps with slivers, these forward differences are mostly noise (oded_scorpion: the smallest eigenvalue from
    // -0.007 to 2e-4 between consecutive steps), and such boosts cost oded_scorpion 5 steps more.
    const V3 curvature =
        at_start ? V3(eigenvalues.cwiseAbs().cwiseMax(1e-3 * eigenvalues[2])) : eigenvalues;
    V3 step = -(eigenvectors * curvature.cwiseInverse().asDiagonal() * eigenvectors.transpose() * gradient);
    const double slope = gradient.dot(step);
    double energy = 0.;
    for(double term : terms)
      energy += term;
    // Below the rounding of F's terms a predicted decrease is noise.
    const double noise = 64. * std::numeric_limits<double>::epsilon() * energy;
    if(!(-0.5 * slope > std::max(share * reference, noise)))
      break;
    step *= std::min(1., 1. / step.norm()); // a boost of length 1 at most (mobius.h's steps too)
    V3 next_gradient;
    double t = 1.;
    bool accepted = false;
    for(int tries = 0; tries < 10 && !accepted; ++tries, t *= 0.5) // down to 1/512 of the step
    {
      boost_map(y, t * step, trial, parallel);
      if(!energy_and_boost_gradient(triangles, shapes, trial, trial_terms, next_gradient, parallel, &buffer))
        continue;
      double change = 0.; // face by face, as energy_change() in the minimization
      for(std::size_t f = 0; f < terms.size(); ++f)
        change += trial_terms[f] - terms[f];
      accepted = change <= 1e-4 * t * std::min(0., gradient.dot(step));
    }
    if(!accepted)
      break;
    y.swap(trial);
    terms.swap(trial_terms);
    gradient = next_gradient;
    ++applied;
  }
  return applied;
}

// The first t in (0, limit] at which the face (a, b, c), its corners moved to a + t u, b + t v, c + t w (tangent
// moves), stops being positive; +infinity if it stays positive. Retracting the corners onto the sphere scales each by a
// positive factor, which leaves the sign of det(a(t), b(t), c(t)) unchanged: the test is that of a cubic in t, its
// coefficients in the relative form det(a, b - a, c - a) (faces with edges of 1e-10 keep their digits). The first
// sign change is found on the cubic's monotone pieces (split at its critical points) by bisection, to 0.1%; the line
// search tests the trial points themselves, so the bound only chooses where to start.
inline double first_nonpositive_time(const V3& a, const V3& b, const V3& c, const V3& u, const V3& v, const V3& w,
                                     double limit)
{
  const V3 e1 = b - a, e2 = c - a, d1 = v - u, d2 = w - u;
  const V3 e1_e2 = e1.cross(e2), d1_d2 = d1.cross(d2), e1_d2 = e1.cross(d2), d1_e2 = d1.cross(e2);
  const double c0 = a.dot(e1_e2);
  const double c1 = u.dot(e1_e2) + a.dot(d1_e2) + a.dot(e1_d2);
  const double c2 = a.dot(d1_d2) + u.dot(d1_e2) + u.dot(e1_d2);
  const double c3 = u.dot(d1_d2);
  // No sign change possible on the interval (nearly every face), or none to find: a face positive in the line
  // search's test whose c0 rounds to 0 or below is left to the line search.
  if(!(c0 > 0.) || c0 - limit * (std::abs(c1) + limit * (std::abs(c2) + limit * std::abs(c3))) > 0.)
    return std::numeric_limits<double>::infinity();
  auto cubic = [&](double t) { return c0 + t * (c1 + t * (c2 + t * c3)); };
  double ends[3]; // the critical points in (0, limit), in order, then limit
  int count = 0;
  const double qa = 3. * c3, qb = 2. * c2, qc = c1; // the derivative
  if(qa != 0.)
  {
    const double discriminant = qb * qb - 4. * qa * qc;
    if(discriminant >= 0.)
    {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
      const double r1 = q / qa, r2 = q != 0. ? qc / q : r1;
      for(double r : {(std::min)(r1, r2), (std::max)(r1, r2)})
        if(r > 0. && r < limit)
          ends[count++] = r;
    }
  }
  else if(qb != 0. && -qc / qb > 0. && -qc / qb < limit)
    ends[count++] = -qc / qb;
  ends[count++] = limit;
  double low = 0.;
  for(int k = 0; k < count; ++k)
  {
    double high = ends[k];
    if(cubic(high) > 0.)
    {
      low = high; // positive at both ends of a monotone piece: on all of it
      continue;
    }
    for(int bisection = 0; bisection < 60 && high - low > 1e-3 * high; ++bisection)
    {
      const double middle = 0.5 * (low + high);
      (cubic(middle) > 0. ? low : high) = middle;
    }
    return low;
  }
  return std::numeric_limits<double>::infinity();
}

} // namespace least_distortion_detail

// Positive in the orientation F is defined by, the points normalized first as the minimization does with its start
// (its sign can differ from the exact predicate's on faces squeezed to the limits of double precision).
inline bool positive_in_distortion_orientation(const Vector3& a, const Vector3& b, const Vector3& c)
{
  using least_distortion_detail::to_eigen;
  return least_distortion_detail::orientation(to_eigen(a).normalized(), to_eigen(b).normalized(),
                                              to_eigen(c).normalized()) > 0.;
}

// F of the map x (1 when every flat triangle is similar to its 3D triangle); +infinity when a face is not positive
// (in the relative orientation used here) or a 3D triangle is degenerate.
inline double conformal_distortion(const std::vector<std::array<int, 3>>& triangles, const std::vector<Vector3>& points,
                                   const std::vector<Vector3>& x)
{
  using namespace least_distortion_detail;
  std::vector<Face_shape> shapes;
  if(!face_shapes(triangles, points, shapes))
    return std::numeric_limits<double>::infinity();
  double energy = 0.;
  for(std::size_t f = 0; f < triangles.size(); ++f)
  {
    V3 p[3];
    for(int k = 0; k < 3; ++k)
      p[k] = to_eigen(x[triangles[f][k]]).normalized();
    if(!(orientation(p[0], p[1], p[2]) > 0.))
      return std::numeric_limits<double>::infinity();
    energy += face_energy(shapes[f], p);
  }
  return energy;
}

// Nonlinear Gauss-Seidel on F, the smoother of the multilevel start (multilevel_least_distortion.h): passes over the
// vertices, each moved by a Newton step of its own faces' energy in its tangent plane (its 2x2 Hessian shifted so that
// its lowest eigenvalue is at least 1e-3 times its highest, at most half its shortest edge, halved until that energy
// falls and its faces stay positive). Vertices carried back from a coarser level sit where their ring's kernel is
// widest, not where their faces keep their shape: F of the carried-back map was 2 to 3.3 where the minimum is about
// 1.0 (CGAL's horse, vol2surf_lh_pial). The sweeps remove that local error, each for a few hundredths of a Newton
// step on the same level (face_energy_at_corner: a move needs its corner's block only), and stop once a sweep lowers
// F by at least `stall` times what the one before did (what is left is smooth, which Gauss-Seidel removes slowly and
// Newton's steps do not), after `max_sweeps`, or at the time budget or a cancel (which the minimization that follows
// reports). Then passes over the vertices still far from stationary (stationarity above 1) and their neighbours only,
// at most `max_sweeps` of them (see below). Returns the sweeps (the passes not counted).
inline int smooth_conformal_distortion(const std::vector<std::array<int, 3>>& triangles,
                                       const std::vector<Vector3>& points, std::vector<Vector3>& x, int max_sweeps,
                                       double stall, const Iteration_options& options, const CGAL::Real_timer& clock)
{
  using namespace least_distortion_detail;
  std::vector<Face_shape> shapes;
  if(!face_shapes(triangles, points, shapes))
    return 0;
  const std::size_t n = x.size();
  std::vector<std::size_t> offsets(n + 1, 0);
  for(const std::array<int, 3>& t : triangles)
    for(int k = 0; k < 3; ++k)
      ++offsets[static_cast<std::size_t>(t[k]) + 1];
  for(std::size_t i = 0; i < n; ++i)
    offsets[i + 1] += offsets[i];
  std::vector<std::pair<std::size_t, int>> corners(offsets[n]); // (face, corner) around each vertex
  std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
  for(std::size_t f = 0; f < triangles.size(); ++f)
    for(int k = 0; k < 3; ++k)
      corners[fill[static_cast<std::size_t>(triangles[f][k])]++] = {f, k};
  std::vector<V3> y(n);
  for(std::size_t i = 0; i < n; ++i)
    y[i] = to_eigen(x[i]).normalized();
  // The energy of the faces of v with v at `at`; with `gradient`, also its gradient and Hessian in v's coordinates.
  auto local_energy = [&](std::size_t v, const V3& at, V3* gradient, Eigen::Matrix3d* hessian) {
    double energy = 0.;
    if(gradient != nullptr)
    {
      gradient->setZero();
      hessian->setZero();
    }
    for(std::size_t c = offsets[v]; c < offsets[v + 1]; ++c)
    {
      const std::size_t f = corners[c].first;
      const int k = corners[c].second;
      V3 p[3];
      for(int l = 0; l < 3; ++l)
        p[l] = l == k ? at : y[static_cast<std::size_t>(triangles[f][l])];
      if(!(orientation(p[0], p[1], p[2]) > 0.))
        return std::numeric_limits<double>::infinity();
      if(gradient == nullptr)
      {
        energy += face_energy(shapes[f], p);
        continue;
      }
      V3 g;
      Eigen::Matrix3d h;
      energy += face_energy_at_corner(shapes[f], p, k, g, h);
      *gradient += g;
      *hessian += h;
    }
    return energy;
  };
  // One vertex moved by a Newton step of its faces' energy (see above); returns the decrease of F and sets `sigma` to
  // the vertex's stationarity before the move, as minimize_conformal_distortion() measures it (0 where it cannot move).
  auto relax = [&](std::size_t v, double& sigma) -> double {
    sigma = 0.;
    V3 g;
    Eigen::Matrix3d h;
    const double before = local_energy(v, y[v], &g, &h);
    if(!std::isfinite(before))
      return 0.;
    const V3 a = std::abs(y[v][0]) < 0.6 ? V3(1., 0., 0.) : V3(0., 1., 0.);
    Eigen::Matrix<double, 3, 2> basis;
    basis.col(0) = (a - a.dot(y[v]) * y[v]).normalized();
    basis.col(1) = y[v].cross(V3(basis.col(0)));
    const Eigen::Vector2d g2 = basis.transpose() * g;
    // The retraction's second order, as in minimize_conformal_distortion().
    Eigen::Matrix2d h2 = basis.transpose() * h * basis - g.dot(y[v]) * Eigen::Matrix2d::Identity();
    Eigen::Vector2d eigenvalues;
    Eigen::Matrix2d eigenvectors;
    if(!symmetric_eigen(h2, eigenvalues, eigenvectors))
      return 0.;
    const double lowest = eigenvalues[0], highest = eigenvalues[1];
    if(!(highest > 0.))
      return 0.;
    if(lowest < 1e-3 * highest)
      h2 += (1e-3 * highest - lowest) * Eigen::Matrix2d::Identity();
    const V3 step = basis * Eigen::Vector2d(-solve_symmetric(h2, g2));
    double shortest = std::numeric_limits<double>::infinity(), edges = 0., weight = 0.;
    for(std::size_t c = offsets[v]; c < offsets[v + 1]; ++c)
    {
      weight += shapes[corners[c].first].weight;
      for(int l = 0; l < 3; ++l)
        if(l != corners[c].second)
        {
          const double chord = (y[static_cast<std::size_t>(triangles[corners[c].first][l])] - y[v]).norm();
          shortest = std::min(shortest, chord);
          edges += chord;
        }
    }
    // As minimize_conformal_distortion() measures it: |grad| times the mean chord over the faces' weight.
    sigma = g2.norm() * edges / (2. * static_cast<double>(offsets[v + 1] - offsets[v])) / weight;
    const double length = step.norm();
    if(!(length > 0.) || !std::isfinite(length))
      return 0.;
    double t = std::min(1., 0.5 * shortest / length);
    for(int tries = 0; tries < 30; ++tries, t *= 0.5)
    {
      const V3 q = (y[v] + t * step).normalized();
      const double after = local_energy(v, q, nullptr, nullptr);
      if(after < before)
      {
        y[v] = q;
        return before - after;
      }
    }
    return 0.;
  };
  // From Solver_tuning::side_by_side_min_vertices on, the sweeps visit the vertices by colours (greedy, in the order
  // of the vertices: no two vertices of a face share one), each colour in the order of its vertices. The moves of
  // one colour are independent (a move reads its ring and writes its vertex only), so with CGAL::Parallel_tag they
  // are made on all threads, and the map is the same to the last bit either way (each move's decrease is added up
  // in the sweep's order by one thread).
  const bool coloured = n >= options.tuning.side_by_side_min_vertices;
  const bool parallel = options.parallel && coloured;
  std::vector<std::size_t> order(n), colour_starts{0, n};
  for(std::size_t v = 0; v < n; ++v)
    order[v] = v;
  if(coloured)
  {
    std::vector<int> colour(n, -1);
    std::vector<std::size_t> used; // used[c] == v + 1: colour c taken by a neighbour of v
    int colours = 0;
    for(std::size_t v = 0; v < n; ++v)
    {
      for(std::size_t c = offsets[v]; c < offsets[v + 1]; ++c)
        for(int l = 0; l < 3; ++l)
        {
          const int other = colour[static_cast<std::size_t>(triangles[corners[c].first][l])];
          if(other >= 0)
            used[static_cast<std::size_t>(other)] = v + 1;
        }
      int c = 0;
      while(c < colours && used[static_cast<std::size_t>(c)] == v + 1)
        ++c;
      if(c == colours)
      {
        ++colours;
        used.push_back(0);
      }
      colour[v] = c;
    }
    colour_starts.assign(static_cast<std::size_t>(colours) + 1, 0);
    for(std::size_t v = 0; v < n; ++v)
      ++colour_starts[static_cast<std::size_t>(colour[v]) + 1];
    for(int c = 0; c < colours; ++c)
      colour_starts[static_cast<std::size_t>(c) + 1] += colour_starts[static_cast<std::size_t>(c)];
    std::vector<std::size_t> fill_colour(colour_starts.begin(), colour_starts.end() - 1);
    for(std::size_t v = 0; v < n; ++v)
      order[fill_colour[static_cast<std::size_t>(colour[v])]++] = v;
  }
  int sweep = 0;
  std::vector<double> sigma(n, 0.), move_decrease(n, 0.);
  // The decrease of F of each sweep: the sum of its moves' local decreases (a move changes only its vertex's faces).
  double last_decrease = 0.;
  while(sweep < max_sweeps)
  {
    const double sweep_start = clock.time();
    double decrease = 0.;
    for(std::size_t c = 0; c + 1 < colour_starts.size(); ++c)
    {
      const std::size_t first = colour_starts[c];
      for_each_block(parallel, colour_starts[c + 1] - first, 64, [&](std::size_t begin, std::size_t end) {
        for(std::size_t k = first + begin; k < first + end; ++k)
          move_decrease[order[k]] = relax(order[k], sigma[order[k]]);
      });
    }
    for(std::size_t k = 0; k < n; ++k)
      decrease += move_decrease[order[k]];
    ++sweep;
    if(!(decrease > 0.) || (sweep > 1 && decrease >= stall * last_decrease) || options.cancel_requested()
       || next_part_passes_time_budget(options, clock, clock.time() - sweep_start))
      break;
    last_decrease = decrease;
  }
  // Once the sweeps stall, what is left is mostly smooth, but not everywhere: on vol2surf_lh_pial's own level 1% of the
  // vertices still had a stationarity above 1 (a move of one edge length would change their faces' energy by about its
  // whole share), up to 3,000, and the first Newton steps were cut to 1/8 to 1/2 of their length around them (24 steps
  // on that level). Passes over those vertices and their neighbours only, until none is above 1 (or a pass moves
  // none of them, or `max_sweeps` passes): each costs a fraction of a sweep.
  std::vector<std::size_t> active, visit;
  std::vector<char> marked(n, 0);
  for(std::size_t v = 0; v < n; ++v)
    if(sigma[v] > 1.)
      active.push_back(v);
  for(int pass = 0; pass < max_sweeps && !active.empty() && !options.cancel_requested(); ++pass)
  {
    const double pass_start = clock.time();
    visit.clear();
    for(std::size_t v : active)
      for(std::size_t c = offsets[v]; c < offsets[v + 1]; ++c)
        for(int l = 0; l < 3; ++l)
        {
          const std::size_t u = static_cast<std::size_t>(triangles[corners[c].first][l]);
          if(!marked[u])
          {
            marked[u] = 1;
            visit.push_back(u);
          }
        }
    std::sort(visit.begin(), visit.end()); // in the order of a sweep
    active.clear();
    for(std::size_t v : visit)
    {
      marked[v] = 0;
      double before_move = 0.;
      if(relax(v, before_move) > 0. && before_move > 1.)
        active.push_back(v);
    }
    if(next_part_passes_time_budget(options, clock, clock.time() - pass_start))
      break;
  }
  for(std::size_t i = 0; i < n; ++i)
    x[i] = Vector3(y[i][0], y[i][1], y[i][2]);
  return sweep;
}

// The Hessian's lower triangle has the same pattern at every step of a minimization: it is made once, with where each
// face's 21 entries go in it (face_entries: each step adds the faces' entries there, face after face), and so is its
// factorization's analysis (the ordering, METIS' or the mesh's given one, and the symbolic factorization, made by the
// first factorization).
struct Distortion_hessian_pattern
{
  static constexpr int entries_per_face = 21; // 3 diagonal 2x2 blocks' lower triangles, 3 blocks below the diagonal
  Eigen::SparseMatrix<double> hessian;
  std::vector<int> face_entries;
  // Supernodal: 3 to 4 times faster than Eigen's simplicial LDLT on these Hessians; ordered by vertices (blocks of 2).
  Supernodal_ldlt factorization{true, Eigen::Lower, 2};

  // (row, col, local row, local col) of face f's entries, in order.
  template <typename Visit>
  static void for_each_face_entry(const std::array<int, 3>& face, Visit&& visit)
  {
    for(int a = 0; a < 3; ++a)
      for(int b = 0; b < 3; ++b)
        for(int r = 0; r < 2; ++r)
          for(int s = 0; s < 2; ++s)
          {
            const int row = 2 * face[a] + r, col = 2 * face[b] + s;
            if(row >= col)
              visit(row, col, 2 * a + r, 2 * b + s);
          }
  }

  // The pattern of `triangles` on `n` vertices, built from each vertex's higher neighbours (column 2v holds rows 2v and
  // 2v + 1, column 2v + 1 row 2v + 1, and both the two rows of every higher neighbour, in order): the entries that
  // Eigen's setFromTriplets() makes from the faces' 21 entries each, which took as long on CGAL's bunny00 (0.06 s) as
  // the first assembly of the Hessian.
  void make(const std::vector<std::array<int, 3>>& triangles, std::size_t n)
  {
    const std::size_t m = triangles.size();
    Compressed_lists<int> higher(static_cast<int>(n)); // each edge (u, v), u < v, as v in u's list (twice or more)
    for(int pass = 0; pass < 2; ++pass)
    {
      for(const std::array<int, 3>& t : triangles)
        for(int k = 0; k < 3; ++k)
        {
          const int u = t[k], v = t[(k + 1) % 3];
          CGAL_precondition(u != v); // the input checks reject such faces
          higher.add(pass, std::min(u, v), std::max(u, v));
        }
      if(pass == 0)
        higher.counted();
    }
    std::vector<int> first(n + 1, 0); // vertex v's higher neighbours: neighbors[first[v]] to neighbors[first[v + 1] - 1]
    std::vector<int> neighbors;
    neighbors.reserve(higher.values.size() / 2);
    for(std::size_t v = 0; v < n; ++v)
    {
      int* begin = higher.values.data() + higher.start[v];
      int* end = higher.values.data() + higher.start[v + 1];
      std::sort(begin, end);
      neighbors.insert(neighbors.end(), begin, std::unique(begin, end));
      first[v + 1] = static_cast<int>(neighbors.size());
    }
    const Eigen::Index size = static_cast<Eigen::Index>(2 * n);
    std::vector<int> column_start(2 * n + 1, 0), rows;
    rows.reserve(3 * n + 4 * neighbors.size());
    for(std::size_t v = 0; v < n; ++v)
      for(int s = 0; s < 2; ++s)
      {
        for(int r = s; r < 2; ++r)
          rows.push_back(static_cast<int>(2 * v) + r);
        for(int k = first[v]; k < first[v + 1]; ++k)
        {
          rows.push_back(2 * neighbors[static_cast<std::size_t>(k)]);
          rows.push_back(2 * neighbors[static_cast<std::size_t>(k)] + 1);
        }
        column_start[2 * v + s + 1] = static_cast<int>(rows.size());
      }
    hessian = Eigen::SparseMatrix<double>(size, size);
    hessian.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
    std::copy(column_start.begin(), column_start.end(), hessian.outerIndexPtr());
    std::copy(rows.begin(), rows.end(), hessian.innerIndexPtr());
    std::fill(hessian.valuePtr(), hessian.valuePtr() + rows.size(), 0.);
    face_entries.resize(entries_per_face * m);
    for(std::size_t f = 0; f < m; ++f)
    {
      int k = 0;
      for_each_face_entry(triangles[f], [&](int row, int col, int, int) {
        const int v = col / 2, s = col % 2, u = row / 2, r = row % 2;
        int offset = r - s; // u == v: the diagonal block's lower triangle
        if(u != v)
        {
          const int* list = neighbors.data() + first[static_cast<std::size_t>(v)];
          const int* last = neighbors.data() + first[static_cast<std::size_t>(v) + 1];
          offset = (2 - s) + 2 * static_cast<int>(std::lower_bound(list, last, u) - list) + r;
        }
        face_entries[entries_per_face * f + k++] = column_start[static_cast<std::size_t>(col)] + offset;
      });
    }
  }
};

// Minimizes F from `x` (unit vectors, every face positive) over bijective maps; `x` holds the last iterate (each one
// lower in F than the one before, except the steps judged on F's rounding, see below_noise). Stops when every vertex
// is stationary, at `options.max_newton_sweeps`, the time budget, a cancel, or when no step lowers F any more.
// `first_pass_seconds`: what the first step is expected to take (the budget test of the later steps uses the last
// one's duration), for instance scaled from a coarser level's; 0 when unknown. `vertex_rank`, when given (one entry
// per vertex), is the fill-reducing order of the Hessian's blocks (tangent_newton_system.h's elimination_rank() of the
// mesh, computed already or kept for the next minimization); otherwise METIS orders them.
// Stationarity of vertex k: sigma_k = |grad_k F| h_k / a_k, h_k the mean chord length of its edges, a_k the
// weight of its faces: the change of F, relative to its faces' share, per move of its own edge length. Its rounding
// floor (positions rounded to double, |dx| ~ eps = 2^-52) is about eps r_k h_k / a_k, r_k the larger absolute row sum
// of the vertex's rows of the Hessian: eps / h_k times a constant on faces of good shape, far more on slivers squeezed
// to edges of 1e-11 (CGAL's man: the stationarity of such vertices wandered between 1e-3 and 2e-2 for 80 steps, within
// a few times their r_k floor). The test is sigma_k <= max(tolerance, 64 eps / h_k, 8 eps r_k h_k / a_k).
// The steps' Marquardt shift falls to Solver_tuning::least_distortion_marquardt_floor after full steps.
inline Least_distortion_report minimize_conformal_distortion(const std::vector<std::array<int, 3>>& triangles,
                                                             const std::vector<Vector3>& points, std::vector<Vector3>& x,
                                                             const Iteration_options& options,
                                                             const CGAL::Real_timer& clock,
                                                             double first_pass_seconds = 0.,
                                                             const std::vector<int>* vertex_rank = nullptr)
{
  using namespace least_distortion_detail;
  Least_distortion_report report;
  const int n = static_cast<int>(x.size());
  const std::size_t m = triangles.size();
  std::vector<V3> y(n);
  for(int i = 0; i < n; ++i)
    y[i] = to_eigen(x[i]).normalized();
  std::vector<Face_shape> shapes;
  if(!face_shapes(triangles, points, shapes))
    return report;

  auto corners = [&](const std::vector<V3>& z, std::size_t f, V3 (&p)[3]) {
    for(int k = 0; k < 3; ++k)
      p[k] = z[triangles[f][k]];
  };
  auto all_positive = [&](const std::vector<V3>& z) {
    for(const std::array<int, 3>& t : triangles)
      if(!(orientation(z[t[0]], z[t[1]], z[t[2]]) > 0.))
        return false;
    return true;
  };
  // F(z) - F(y) face by face (the total would lose the small faces' changes), F(y)'s terms as the last assembly
  // computed them; +infinity if a face is not positive.
  // With CGAL::Parallel_tag the faces' terms of the line search, the assembly, the bound of the folds and the boost
  // balancing are computed on several threads and added up in order by one, so that every sum, and with them the
  // iterates, are those of the sequential run to the last bit. On every level: a block of `grain` faces is a few
  // hundred microseconds of work (a face's Hessian and its projection take about 2 microseconds), far above what
  // handing it to another thread costs, and a mesh of fewer faces is one block, run by the caller.
  const bool parallel = options.parallel;
  constexpr std::size_t grain = 256; // faces per task
  std::vector<double> current_terms(m, 0.), face_values(parallel ? m : 0);
  auto energy_change = [&](const std::vector<V3>& z) {
    double change = 0.;
    if(parallel)
    {
      for_each_block(true, m, grain, [&](std::size_t begin, std::size_t end) {
        V3 p[3];
        for(std::size_t f = begin; f < end; ++f)
        {
          corners(z, f, p);
          face_values[f] = orientation(p[0], p[1], p[2]) > 0. ? face_energy(shapes[f], p)
                                                              : std::numeric_limits<double>::infinity();
        }
      });
      for(std::size_t f = 0; f < m; ++f)
      {
        if(face_values[f] == std::numeric_limits<double>::infinity())
          return face_values[f];
        change += face_values[f] - current_terms[f];
      }
      return change;
    }
    V3 p[3];
    for(std::size_t f = 0; f < m; ++f)
    {
      corners(z, f, p);
      if(!(orientation(p[0], p[1], p[2]) > 0.))
        return std::numeric_limits<double>::infinity();
      change += face_energy(shapes[f], p) - current_terms[f];
    }
    return change;
  };
  if(!all_positive(y))
    return report;
  report.started = true;
  const Solver_tuning& tuning = options.tuning;
  report.boosts += balance_distortion_boosts(triangles, shapes, y, tuning.least_distortion_boost_iterations,
                                             tuning.least_distortion_boost_share, 0., true, parallel);

  const double floor_scale = 64. * std::numeric_limits<double>::epsilon();
  const double rounding_floor_factor = 8.;
  std::vector<V3> t1(n), t2(n), direction(n), trial(n), moved(n); // direction: each vertex's move in 3D
  std::vector<Vector3> split_at(n), split_step(n);
  std::vector<double> edge_sum(n), face_weight(n);
  std::vector<int> edge_count(n);
  std::vector<double> row_abs(2 * n);
  Eigen::VectorXd gradient(2 * n);
  constexpr int entries_per_face = Distortion_hessian_pattern::entries_per_face;
  Distortion_hessian_pattern pattern;
  pattern.make(triangles, x.size());
  Eigen::SparseMatrix<double>& hessian = pattern.hessian;
  const std::vector<int>& face_entries = pattern.face_entries;
  auto for_each_face_entry = [&](std::size_t f, auto&& visit) {
    Distortion_hessian_pattern::for_each_face_entry(triangles[f], visit);
  };
  // A face's share of a pass, computed on its own (on several threads with `parallel`), then added up in order.
  struct Face_pass
  {
    double energy;
    double gradient[6];               // in the tangent bases of its corners
    double entries[entries_per_face]; // in for_each_face_entry's order
    double row_abs[6];                // of the tangent Hessian's rows before the projection (the rounding floor)
    double chords[3];                 // at each corner, the lengths of its two edges
  };
  constexpr std::size_t faces_per_batch = 16384;
  std::vector<Face_pass> batch(std::min(m, faces_per_batch));
  Supernodal_ldlt& factorization = pattern.factorization;
  if(vertex_rank != nullptr && vertex_rank->size() == x.size())
    factorization.set_block_order(*vertex_rank);
  factorization.set_parallel(parallel);
  // Asked between the factorization's supernodes (a step of a brain cortex factorizes for a second or more).
  bool factorization_cancelled = false;
  factorization.set_stop([&]() { return stop_requested(options, clock, factorization_cancelled); });
  double marquardt = 1e-6;
  const double marquardt_floor = options.tuning.least_distortion_marquardt_floor;
  // The floor and the shift always added (against the rotations' null space) are both scaled by floor_factor,
  // lowered where the floor itself caps the steps (below), down to 1e-4 (shifts near the unit diagonal's rounding).
  const double always_added_shift = 1e-12;
  double floor_factor = 1.;
  double previous_floor_decrease = 0.; // what the last step lowered F by, if a full step at the floor; else 0
  bool whole_hessian = false;
  std::size_t failures = 0;
  // The stationarity before the last step taken on rounding alone (see below_noise): the next such step needs less,
  // until a step lowers F for real.
  double noise_step_stationarity = std::numeric_limits<double>::infinity();
  // Each pass measures the current iterate (F, its gradient and stationarity: what the report gives), then stops or
  // takes a step.
  double pass_start = clock.time(), last_pass_seconds = std::max(0., first_pass_seconds);
  for(;;)
  {
    if(report.newton_steps > 0 || failures > 0)
      last_pass_seconds = clock.time() - pass_start;
    pass_start = clock.time();
    for(int i = 0; i < n; ++i)
    {
      const V3 a = std::abs(y[i][0]) < 0.6 ? V3(1., 0., 0.) : V3(0., 1., 0.);
      t1[i] = (a - a.dot(y[i]) * y[i]).normalized();
      t2[i] = y[i].cross(t1[i]);
    }
    gradient.setZero();
    std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.);
    double* hessian_values = hessian.valuePtr();
    std::fill(edge_sum.begin(), edge_sum.end(), 0.);
    std::fill(face_weight.begin(), face_weight.end(), 0.);
    std::fill(edge_count.begin(), edge_count.end(), 0);
    std::fill(row_abs.begin(), row_abs.end(), 0.);
    report.energy = 0.;
    auto compute_face = [&](std::size_t f, Face_pass& out) {
      V3 p[3];
      corners(y, f, p);
      Vector9 g;
      Eigen::Matrix<double, 3, 2> basis[3];
      for(int k = 0; k < 3; ++k)
      {
        const int v = triangles[f][k];
        basis[k].col(0) = t1[v];
        basis[k].col(1) = t2[v];
        out.chords[k] = (p[(k + 1) % 3] - p[k]).norm() + (p[(k + 2) % 3] - p[k]).norm();
      }
      Eigen::Matrix<double, 6, 1> g_tangent;
      Eigen::Matrix<double, 6, 6> h_tangent;
      out.energy = face_tangent_derivatives(shapes[f], p, basis, g, g_tangent, h_tangent);
      // Second order of the retraction (y + v) / |y + v| = y + v - |v|^2 y / 2: minus the radial gradient.
      for(int k = 0; k < 3; ++k)
      {
        const double radial = g.segment<3>(3 * k).dot(p[k]);
        h_tangent(2 * k, 2 * k) -= radial;
        h_tangent(2 * k + 1, 2 * k + 1) -= radial;
      }
      for(int r = 0; r < 6; ++r)
      {
        out.row_abs[r] = h_tangent.row(r).cwiseAbs().sum();
        out.gradient[r] = g_tangent[r];
      }
      if(!whole_hessian)
      {
        Eigen::Matrix<double, 6, 1> eigenvalues;
        Eigen::Matrix<double, 6, 6> eigenvectors;
        if(symmetric_eigen(h_tangent, eigenvalues, eigenvectors)) // not finite: left so, the step fails on it
          h_tangent = eigenvectors * eigenvalues.cwiseMax(0.).asDiagonal() * eigenvectors.transpose();
      }
      int k = 0;
      for_each_face_entry(f, [&](int, int, int local_row, int local_col) {
        out.entries[k++] = h_tangent(local_row, local_col);
      });
    };
    for(std::size_t first_face = 0; first_face < m; first_face += batch.size())
    {
      const std::size_t count = std::min(batch.size(), m - first_face);
      for_each_block(parallel, count, grain, [&](std::size_t begin, std::size_t end) {
        for(std::size_t b = begin; b < end; ++b)
          compute_face(first_face + b, batch[b]);
      });
      for(std::size_t b = 0; b < count; ++b)
      {
        const std::size_t f = first_face + b;
        const Face_pass& terms = batch[b];
        current_terms[f] = terms.energy;
        report.energy += terms.energy;
        for(int k = 0; k < 3; ++k)
        {
          const int v = triangles[f][k];
          edge_sum[v] += terms.chords[k];
          edge_count[v] += 2;
          face_weight[v] += shapes[f].weight;
        }
        for(int a = 0; a < 3; ++a)
          for(int r = 0; r < 2; ++r)
          {
            row_abs[2 * triangles[f][a] + r] += terms.row_abs[2 * a + r];
            gradient[2 * triangles[f][a] + r] += terms.gradient[2 * a + r];
          }
        const int* where = face_entries.data() + entries_per_face * f;
        for(int e = 0; e < entries_per_face; ++e)
          hessian_values[where[e]] += terms.entries[e];
      }
    }
    report.max_stationarity = 0.;
    report.unstationary_vertices = 0;
    report.vertices_at_rounding_floor = 0;
    for(int i = 0; i < n; ++i)
    {
      const double h = edge_sum[i] / std::max(1, edge_count[i]);
      const double sigma = gradient.segment<2>(2 * i).norm() * h / face_weight[i];
      // The rounding floor: what rounding the positions to double (|dx| ~ eps) changes in sigma, through the rows of
      // the Hessian; at least 64 eps / h (about that for faces of good shape).
      const double hessian_floor = rounding_floor_factor * std::numeric_limits<double>::epsilon()
                                   * std::max(row_abs[2 * i], row_abs[2 * i + 1]) * h / face_weight[i];
      if(sigma <= std::max(floor_scale / h, hessian_floor))
      {
        if(sigma > options.tolerance)
          ++report.vertices_at_rounding_floor;
        continue; // within its rounding floor: counts as stationary (and as 0 in the maximum)
      }
      report.max_stationarity = std::max(report.max_stationarity, sigma);
      if(sigma > options.tolerance)
        ++report.unstationary_vertices;
    }
    if(options.progress
       && !options.progress("least distortion", report.newton_steps, report.max_stationarity, 0))
    {
      report.cancelled = true;
      break;
    }
    if(report.unstationary_vertices == 0)
    {
      report.stationary = true;
      break;
    }
    if(report.newton_steps >= options.max_newton_sweeps)
      break;
    if(options.cancel_requested())
    {
      report.cancelled = true;
      break;
    }
    // A step that the budget ends during its factorization (seconds on brain cortices) is lost: none is started that
    // the last pass's duration says would end past the budget.
    if(past_time_budget(options, clock)
       || next_part_passes_time_budget(options, clock, last_pass_seconds))
    {
      report.out_of_time = true;
      break;
    }

    // Scaled symmetrically to a unit diagonal before it is factorized: the scales of the map differ by orders of
    // magnitude (thin limbs squeezed to edges of 1e-8 give diagonal entries of 1e16 and more), and unscaled, the
    // factorization's rounding swamped the steps of the large triangles (CGAL's cow: one vertex stuck at
    // stationarity 0.013 for 2,000 steps, pivots from 190 to 1.4e17).
    Eigen::VectorXd scaling(2 * n);
    for(int i = 0; i < 2 * n; ++i)
    {
      const double d = hessian.coeff(i, i);
      scaling[i] = d > 0. ? 1. / std::sqrt(d) : 1.;
    }
    for(int k = 0; k < hessian.outerSize(); ++k)
      for(Eigen::SparseMatrix<double>::InnerIterator it(hessian, k); it; ++it)
        it.valueRef() *= scaling[it.row()] * scaling[it.col()];
    const double shift = marquardt + floor_factor * always_added_shift;
    for(int i = 0; i < 2 * n; ++i)
      hessian.coeffRef(i, i) += shift;
    const bool factorized = factorization.factorize(hessian);
    if(factorization.stopped())
    {
      (factorization_cancelled ? report.cancelled : report.out_of_time) = true;
      break;
    }
    if(whole_hessian && !factorized)
    {
      whole_hessian = false; // the projected Hessians again
      continue;
    }
    if(!factorized)
      break;
    // Pivots below -1e-6 times the largest are negative curvature (the rotations, three exact zeros, and the nearly
    // invariant boosts leave pivots of rounding size and either sign: with a strict test the whole Hessian was refused
    // at nearly every step, CGAL's hand). The whole Hessian H = L D L^T is then stepped with L |D| L^T instead: H
    // plus a positive semi-definite term of rank the number of negative pivots (a handful, falling to none as the
    // minimum nears), so the step is Newton's on all but a few directions and still goes down. Refactorizing with
    // the projected Hessians instead cost a second factorization per step and converged linearly: CGAL's horse's
    // level of 3,030 vertices took 74 steps (52 now), vol2surf_lh_pial's of 27,661 vertices 11 s (4.6 s now).
    Eigen::VectorXd step = (-gradient.array() * scaling.array()).matrix();
    const Eigen::VectorXd& pivots = factorization.pivots();
    const double largest_pivot = pivots.maxCoeff();
    factorization.solve_in_place(step, pivots.minCoeff() <= -1e-6 * largest_pivot, 1e-12 * largest_pivot);
    // The shifts' share of the model's curvature along the step (scaled coordinates: shift |z|^2 over z^T M z, where
    // M z = -g).
    const double shift_share = shift * step.squaredNorm() / -(gradient.array() * scaling.array()).matrix().dot(step);
    step = (scaling.array() * step.array()).matrix();
    const double slope = gradient.dot(step);
    // The step split as in mobius_newton.h: its rotation part dropped (F does not change under rotations), its boost
    // part applied as an exact boost (F is nearly flat along the boosts), the rest added and projected back onto the
    // sphere. Whole-Hessian steps, whose shift is nearly 0, carry large parts of both (the null space and the flat
    // directions), and added to the map in the tangent planes and projected, a rotation or boost of length 0.3 is
    // neither but a distortion of the order of its square: F rose as the fourth power of the step length (change
    // 9e-4, 6e-5, 3e-6 at t = 1, 1/2, 1/4 on bigbrain's level of 40,960 vertices) and these steps were cut to 1/8.
    // Split, that level takes 14 steps instead of 42.
    for(int i = 0; i < n; ++i)
    {
      const V3 d = step[2 * i] * t1[i] + step[2 * i + 1] * t2[i];
      split_at[i] = Vector3(y[i][0], y[i][1], y[i][2]);
      split_step[i] = Vector3(d[0], d[1], d[2]);
    }
    Vector3 rotation, boost_part;
    remove_rotation_and_boost(split_at, split_step, rotation, boost_part);
    V3 boost(boost_part.x, boost_part.y, boost_part.z);
    if(boost.norm() > tuning.boost_max_step)
      boost *= tuning.boost_max_step / boost.norm();
    for(int i = 0; i < n; ++i)
    {
      const V3 d = to_eigen(split_step[i]);
      step[2 * i] = d.dot(t1[i]);
      step[2 * i + 1] = d.dot(t2[i]);
    }
    double longest = 0.;
    for(int i = 0; i < n; ++i)
      longest = std::max(longest, step.segment<2>(2 * i).norm());
    // A boost moves every vertex again and rounds it again: on oded_scorpion, boosts of 1e-7 left the
    // slivers' rounding in F, above the decrease of the last steps, which were all refused. Where the boost part is
    // no longer than the rest's largest move, the error of adding it in the tangent planes is no larger than the
    // rest's own: it is added there.
    if(boost.norm() <= longest)
    {
      for(int i = 0; i < n; ++i)
      {
        const V3 field = boost - boost.dot(y[i]) * y[i];
        step[2 * i] += field.dot(t1[i]);
        step[2 * i + 1] += field.dot(t2[i]);
      }
      boost.setZero();
      longest = 0.;
      for(int i = 0; i < n; ++i)
        longest = std::max(longest, step.segment<2>(2 * i).norm());
    }
    // At most half a radian per vertex and step; then halving until every face stays positive and F falls enough
    // (from a shorter start where faces would fold, below).
    const double first = std::min(1., 0.5 / longest);
    // Where the decrease the step predicts (-slope / 2 for a full step) is below the rounding of F's terms, comparing
    // F cannot judge it: the first trial is taken if every face stays positive and F rises by no more than that
    // rounding, as long as such steps lower the stationarity. CGAL's triceratops ended with two vertices at
    // stationarity 3.8e-6 whose steps would lower F by 1.6e-18, under the rounding of its change (F is about 1), and
    // every step was refused.
    const double noise = 64. * std::numeric_limits<double>::epsilon() * report.energy;
    const bool below_noise = -0.5 * first * slope < noise && report.max_stationarity < noise_step_stationarity;
    // Steps on the projected Hessians start their line search at 0.9 times the longest step that keeps every face
    // positive, where that is shorter (the bound of Smith and Schaefer, "Bijective parameterization with free
    // boundaries", 2015, here a cubic per face: first_nonpositive_time), not at the full step halved until no face
    // folds. Far from the minimum the faces about to fold cap those steps, and the halving took 1/8 where 0.2 was
    // possible; it also counted such steps as failures of the model and raised the shift (below), which shortened the
    // next steps again. On the marching-tetrahedra surfaces with thin arms (mean value) the mesh's own minimization
    // took 49 to 66 steps instead of 112 to 147. The whole Hessian's steps keep the halving: a fold there shows its
    // model is wrong, and starting at a tiny bound (1e-5 on CGAL's dino) only took tiny steps.
    for(int i = 0; i < n; ++i)
      direction[i] = step[2 * i] * t1[i] + step[2 * i + 1] * t2[i];
    double start = first;
    if(!whole_hessian)
    {
      double bound = std::numeric_limits<double>::infinity();
      if(parallel)
      {
        for_each_block(true, m, grain, [&](std::size_t begin, std::size_t end) {
          for(std::size_t f = begin; f < end; ++f)
          {
            const std::array<int, 3>& t = triangles[f];
            face_values[f] = first_nonpositive_time(y[t[0]], y[t[1]], y[t[2]], direction[t[0]], direction[t[1]],
                                                    direction[t[2]], first);
          }
        });
        for(std::size_t f = 0; f < m; ++f)
          bound = (std::min)(bound, face_values[f]);
      }
      else
      {
        for(const std::array<int, 3>& f : triangles)
          bound = (std::min)(bound, first_nonpositive_time(y[f[0]], y[f[1]], y[f[2]], direction[f[0]],
                                                           direction[f[1]], direction[f[2]], first));
      }
      if(bound < first)
        start = 0.9 * bound;
    }
    double t = start, accepted = 0., decrease = 0.;
    for(int tries = 0; tries < 60 && slope < 0.; ++tries, t *= 0.5)
    {
      for_each_block(parallel, static_cast<std::size_t>(n), 1024, [&](std::size_t begin, std::size_t end) {
        for(std::size_t i = begin; i < end; ++i)
          moved[i] = retract(y[i], t * direction[i]);
      });
      boost_map(moved, t * boost, trial, parallel);
      const double change = energy_change(trial);
      const bool judged_by_rounding = below_noise && t == first && change <= noise;
      if(change <= 1e-4 * t * slope || judged_by_rounding)
      {
        accepted = t;
        decrease = -change;
        if(judged_by_rounding && !(change <= 1e-4 * t * slope))
          noise_step_stationarity = report.max_stationarity;
        else if(-change > noise)
          noise_step_stationarity = std::numeric_limits<double>::infinity(); // F went down beyond its rounding
        break;
      }
    }
    if(accepted == 0.)
    {
      whole_hessian = false;
      marquardt *= 10.;
      if(++failures > 8)
        break; // no step lowers F any more (stationarity not reached: the report says so)
      continue;
    }
    ++report.newton_steps;
    failures = 0;
    y.swap(trial);
    // Not after a full step of the whole Hessian that applied its boost part as a boost (longer than the rest's
    // largest move): that step was mostly along the boosts, and its boost part is Newton's, right to second order;
    // the balancing's forward differences (over boosts of 1e-3) are coarser than what is left of the boosts' error
    // then: each balancing moved the map along the boosts by about that error, the next step took it back, and the
    // stationarity fell by only 12% a step (CGAL's diplodocus refined once, cotangent weights, its level of 23,980
    // vertices: 56 steps, 12 without). After the other steps the balancing stays: skipped after every full step of
    // the whole Hessian, it cost steps where the shift holds the flat directions back (bull refined once, mean value:
    // 21 steps on the mesh instead of 12; oded_scorpion 18 instead of 13).
    if(!(whole_hessian && accepted == first && boost.norm() > 0.))
      report.boosts += balance_distortion_boosts(triangles, shapes, y, tuning.least_distortion_boost_iterations,
                                                 tuning.least_distortion_boost_share, decrease, false, parallel);
    // Where the floor caps the steps: a full step at the floor, the shifts over half the model's curvature along it,
    // and F lowered by at least 0.8 times what the step before (also full, at the floor) lowered it: linear
    // convergence along a direction flatter than the floor. A marching-tetrahedra surface with thin arms
    // (thin_arms_14_20_90, mean value) took 90 such steps, each lowering F 2% less than the one before, along a
    // direction of curvature about 6e-14 of the diagonal: lowered, it is stationary in 112 steps instead of 188.
    // Maps whose steps at the floor converge faster keep it (CGAL's dino: 46 steps; with the floor lowered whenever
    // the shifts dominated, 82).
    const bool full_at_floor = accepted == first && marquardt <= floor_factor * marquardt_floor;
    if(full_at_floor && shift_share > 0.5 && decrease > 0.8 * previous_floor_decrease && previous_floor_decrease > 0.
       && floor_factor > 1e-4)
      floor_factor /= 100.;
    previous_floor_decrease = full_at_floor ? decrease : 0.;
    // Judged against the first trial length (a full step, or the half-radian cap).
    if(accepted == first)
      marquardt = std::max(floor_factor * marquardt_floor, marquardt / 10.);
    else if(accepted < 0.1 * start) // judged against the start the folds allow
      marquardt *= 4.;
    whole_hessian = accepted == first;
  }
  report.last_step_seconds = last_pass_seconds;
  for(int i = 0; i < n; ++i)
    x[i] = Vector3(y[i][0], y[i][1], y[i][2]);
  return report;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_STAGE3_LEAST_DISTORTION_H
