// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Shows a mesh's spherical image in CGAL's basic viewer (needs CGAL_Qt5: built only when it is found).
//   draw_sphere [input.off]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/draw_surface_mesh.h>

#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace SP = CGAL::Spherical_parameterization;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = Mesh::Vertex_index;

int main(int argc, char** argv)
{
  const std::string input = (argc > 1) ? argv[1] : "data/bunny.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh))
  {
    std::cerr << "Cannot read a mesh from " << input << std::endl;
    return EXIT_FAILURE;
  }
  auto sphere = mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere", CGAL::ORIGIN).first;
  const SP::Result result = SP::spherical_parameterize(mesh, sphere);
  std::cout << "status: " << SP::get_error_name(result.status) << std::endl;
  if(!result)
    return EXIT_FAILURE;

  // CGAL::draw() shows a mesh's own points: give the mesh the sphere positions.
  for(vertex_descriptor v : vertices(mesh))
    mesh.point(v) = sphere[v];
  CGAL::draw(mesh, "Spherical parameterization"); // returns at once when CGAL_TEST_SUITE is set
  return EXIT_SUCCESS;
}
