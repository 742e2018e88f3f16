// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A user project: find_package() the installed package and map an icosahedron.
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <iostream>
int main()
{
  using P = CGAL::Epick::Point_3;
  CGAL::Surface_mesh<P> m;
  CGAL::make_icosahedron(m, P(0, 0, 0), 1.);
  auto s = m.add_property_map<CGAL::Surface_mesh<P>::Vertex_index, P>("v:s").first;
  auto r = CGAL::Spherical_parameterization::spherical_parameterize(m, s);
  std::cout << CGAL::Spherical_parameterization::get_error_name(r.status) << "\n";
  return r ? 0 : 1;
}
