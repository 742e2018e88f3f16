// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Makes the large benchmark meshes: CGAL's Loop subdivision of a real mesh (armadillo: 2 rounds give
// 832,000 faces, 3 rounds 3,328,000), so that no large file is committed.
//   make_subdivided_mesh INPUT ROUNDS OUTPUT

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <cstdlib>
#include <iostream>

int main(int argc, char** argv)
{
  if(argc != 4)
  {
    std::cerr << "usage: make_subdivided_mesh INPUT ROUNDS OUTPUT\n";
    return 2;
  }
  CGAL::Surface_mesh<CGAL::Epick::Point_3> mesh;
  if(!CGAL::IO::read_polygon_mesh(argv[1], mesh))
  {
    std::cerr << "cannot read " << argv[1] << "\n";
    return 1;
  }
  CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(std::atoi(argv[2])));
  if(!CGAL::IO::write_polygon_mesh(argv[3], mesh, CGAL::parameters::stream_precision(17)))
  {
    std::cerr << "cannot write\n";
    return 1;
  }
  std::cout << argv[3] << ": " << mesh.number_of_vertices() << " vertices, " << mesh.number_of_faces() << " faces\n";
  return 0;
}
