// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Kept so that code written against the earlier layout still compiles: the certificate (certify_sphere_map(),
// is_bijective_on_sphere()) and the distortion (measure_spherical_distortion()) now have a header each.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H

#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
#include <CGAL/Spherical_parameterization/measure_spherical_distortion.h>

#endif // CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H
