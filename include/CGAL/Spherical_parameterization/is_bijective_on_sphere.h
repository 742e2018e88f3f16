// Kept so that code written against the earlier layout still compiles: the certificate (certify_sphere_map(),
// is_bijective_on_sphere()) and the distortion (measure_spherical_distortion()) now have a header each.

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H

#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
#include <CGAL/Spherical_parameterization/measure_spherical_distortion.h>

#endif // CGAL_SPHERICAL_PARAMETERIZATION_IS_BIJECTIVE_ON_SPHERE_H
