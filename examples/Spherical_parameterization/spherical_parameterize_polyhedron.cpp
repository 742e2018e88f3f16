// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// A Polyhedron_3 (or any model of FaceListGraph) onto the unit sphere: check the input first, keep the sphere
// positions in a dynamic property map, then move the polyhedron's own points onto the sphere.
//   spherical_parameterize_polyhedron [input.off] [output.off]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/boost/graph/graph_traits_Polyhedron_3.h>
#include <CGAL/boost/graph/properties_Polyhedron_3.h>

#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace SP = CGAL::Spherical_parameterization;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_3 = Kernel::Point_3;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
using vertex_descriptor = boost::graph_traits<Polyhedron>::vertex_descriptor;

int main(int argc, char** argv)
{
  const std::string input = (argc > 1) ? argv[1] : "data/bunny.off";
  const std::string output = (argc > 2) ? argv[2] : "bunny_sphere_polyhedron.off";

  Polyhedron polyhedron;
  if(!CGAL::IO::read_polygon_mesh(input, polyhedron))
  {
    std::cerr << "Cannot read a mesh from " << input << std::endl;
    return EXIT_FAILURE;
  }

  // What is wrong with a mesh, with its figures (boundary loops, genus, components...).
  const SP::Input_check check = SP::check_input(polyhedron);
  if(!check)
  {
    std::cerr << "Not a closed genus-0 triangle mesh: " << check.message << std::endl;
    return EXIT_FAILURE;
  }

  // Polyhedron_3 has no vertex property maps of its own: a dynamic one holds the sphere positions.
  // Its vertices have no indices either; spherical_parameterize() numbers them itself.
  auto sphere = get(CGAL::dynamic_vertex_property_t<Point_3>(), polyhedron);

  // Named parameters of the package are functions of SP::parameters; here a time budget for the iterations.
  const SP::Result result = SP::spherical_parameterize(polyhedron, sphere, SP::parameters::max_seconds(60.));
  std::cout << "status: " << SP::get_error_name(result.status) << " (" << result.message << ")" << std::endl;
  if(!result)
    return EXIT_FAILURE;
  std::cout << "residual Res = " << result.residual << ", " << result.flipped_faces << " flipped faces, "
            << result.gauss_seidel.iterations << " Gauss-Seidel sweeps, " << result.newton.iterations
            << " Newton iterations" << std::endl;

  // The polyhedron becomes its own spherical image.
  for(vertex_descriptor v : vertices(polyhedron))
    v->point() = get(sphere, v);
  if(!CGAL::IO::write_polygon_mesh(output, polyhedron, CGAL::parameters::stream_precision(17)))
  {
    std::cerr << "Cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "written: " << output << std::endl;
  return EXIT_SUCCESS;
}
