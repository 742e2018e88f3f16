// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A small value type for the numerics on flat arrays (positions on the sphere, sums of neighbours).

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VECTOR3_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VECTOR3_H

#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

struct Vector3
{
  double x = 0., y = 0., z = 0.;

  Vector3() = default;
  Vector3(double x0, double y0, double z0) : x(x0), y(y0), z(z0) {}

  double operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }

  Vector3& operator+=(const Vector3& o)
  {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  Vector3& operator-=(const Vector3& o)
  {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  Vector3& operator*=(double s)
  {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  friend Vector3 operator+(Vector3 a, const Vector3& b) { return a += b; }
  friend Vector3 operator-(Vector3 a, const Vector3& b) { return a -= b; }
  friend Vector3 operator*(double s, Vector3 a) { return a *= s; }
  friend Vector3 operator*(Vector3 a, double s) { return a *= s; }
  friend Vector3 operator-(const Vector3& a) { return Vector3(-a.x, -a.y, -a.z); }
  friend bool operator==(const Vector3& a, const Vector3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

inline double dot(const Vector3& a, const Vector3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vector3 cross(const Vector3& a, const Vector3& b)
{
  return Vector3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline double squared_length(const Vector3& a)
{
  return dot(a, a);
}
inline double length(const Vector3& a)
{
  return std::sqrt(dot(a, a));
}
inline double determinant(const Vector3& a, const Vector3& b, const Vector3& c)
{
  return dot(a, cross(b, c));
}
inline bool is_finite(const Vector3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// An orthonormal basis (t1, t2) of the tangent plane at the unit vector x, with (t1, t2, x) positively oriented.
inline void tangent_frame(const Vector3& x, Vector3& t1, Vector3& t2)
{
  const Vector3 helper =
      std::abs(x.x) < 0.6 ? Vector3(1, 0, 0) : (std::abs(x.y) < 0.6 ? Vector3(0, 1, 0) : Vector3(0, 0, 1));
  t1 = cross(x, helper);
  t1 *= 1. / length(t1);
  t2 = cross(x, t1);
}

// The tangent frames at every point of x.
inline void tangent_frames(const std::vector<Vector3>& x, std::vector<Vector3>& t1, std::vector<Vector3>& t2)
{
  t1.resize(x.size());
  t2.resize(x.size());
  for(std::size_t i = 0; i < x.size(); ++i)
    tangent_frame(x[i], t1[i], t2[i]);
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_VECTOR3_H
