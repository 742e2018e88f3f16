// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Maps a closed genus-0 Surface_mesh onto the unit sphere, bijectively, and writes the sphere.
//   spherical_parameterize_surface_mesh [input.off] [output.off]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
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
  const std::string output = (argc > 2) ? argv[2] : "bunny_sphere.off";

  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh))
  {
    std::cerr << "Cannot read a mesh from " << input << std::endl;
    return EXIT_FAILURE;
  }

  // The result goes into a property map: the mesh itself is not modified.
  Mesh::Property_map<vertex_descriptor, Point_3> sphere =
      mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere", CGAL::ORIGIN).first;

  const SP::Result result = SP::spherical_parameterize(mesh, sphere);
  std::cout << "status: " << SP::get_error_name(result.status) << " (" << result.message << ")" << std::endl;
  if(!result) // not OK: an invalid mesh, or no certified bijective solution within the limits
    return EXIT_FAILURE;

  std::cout << result.number_of_vertices << " vertices, " << result.number_of_faces << " faces in "
            << result.total_seconds << " s" << std::endl;
  std::cout << "residual Res = " << result.residual << ", flipped faces = " << result.flipped_faces << std::endl;

  // Any map onto the sphere can be certified, not only ours: exact orientation of every spherical triangle
  // and a total area of 4 pi.
  std::cout << "certified bijective: " << std::boolalpha << SP::is_bijective_on_sphere(mesh, sphere) << std::endl;

  // The sphere mesh: same vertices and faces, the sphere positions as points.
  if(!CGAL::IO::write_polygon_mesh(output, mesh, CGAL::parameters::vertex_point_map(sphere).stream_precision(17)))
  {
    std::cerr << "Cannot write " << output << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "written: " << output << std::endl;
  return EXIT_SUCCESS;
}
