// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// AMG_solver_traits wherever CGAL takes a sparse linear solver: here CGAL's own planar parameterization of a
// disk mesh (discrete conformal map), then the traits on their own: one setup, several right-hand sides.
//   AMG_solver_traits_planar_parameterization [disk_mesh.off]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace SMP = CGAL::Surface_mesh_parameterization;
namespace SP = CGAL::Spherical_parameterization;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_2 = Kernel::Point_2;
using Point_3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = Mesh::Vertex_index;
using halfedge_descriptor = Mesh::Halfedge_index;
using face_descriptor = Mesh::Face_index;

void print_hierarchy(const SP::AMG_solver_traits::Statistics& statistics)
{
  std::cout << "  AMG levels:";
  for(std::size_t size : statistics.level_sizes)
    std::cout << ' ' << size;
  std::cout << " unknowns; setups: " << statistics.number_of_setups << ", solves: " << statistics.number_of_solves
            << "; last solve: " << statistics.iterations << " iterations, relative residual "
            << statistics.relative_residual << std::endl;
}

int main(int argc, char** argv)
{
  const std::string input = (argc > 1) ? argv[1] : CGAL::data_file_path("meshes/nefertiti.off");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh))
  {
    std::cerr << "Cannot read a mesh from " << input << std::endl;
    return EXIT_FAILURE;
  }
  const halfedge_descriptor border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
  if(border == Mesh::null_halfedge())
  {
    std::cerr << input << " has no border: a disk is needed" << std::endl;
    return EXIT_FAILURE;
  }

  // 1. The solver of CGAL's fixed-border parameterizers. Copies of the traits share their setup and statistics,
  //    so `amg` reports what the copy inside the parameterizer did. The u and v solves share one setup.
  SP::AMG_solver_traits amg;
  amg.parameters().direct_solver_threshold = 0; // multigrid even on a small system (default: a direct solver)
  using Border_parameterizer = SMP::Circular_border_arc_length_parameterizer_3<Mesh>;
  using Parameterizer = SMP::Discrete_conformal_map_parameterizer_3<Mesh, Border_parameterizer, SP::AMG_solver_traits>;

  Mesh::Property_map<vertex_descriptor, Point_2> uv = mesh.add_property_map<vertex_descriptor, Point_2>("v:uv").first;
  const SMP::Error_code status = SMP::parameterize(mesh, Parameterizer(Border_parameterizer(), amg), border, uv);
  if(status != SMP::OK)
  {
    std::cerr << "The parameterization failed (error code " << status << ")" << std::endl;
    return EXIT_FAILURE;
  }
  std::size_t folded = 0;
  for(face_descriptor f : faces(mesh))
  {
    const halfedge_descriptor h = halfedge(f, mesh);
    if(CGAL::orientation(uv[source(h, mesh)], uv[target(h, mesh)], uv[target(next(h, mesh), mesh)]) != CGAL::LEFT_TURN)
      ++folded;
  }
  std::cout << "discrete conformal map: OK, " << num_vertices(mesh) << " vertices, " << folded << " folded triangles"
            << std::endl;
  print_hierarchy(amg.statistics());

  // 2. On its own: implicit Laplacian smoothing of the positions, (I + t L) X = X0 with the graph Laplacian L.
  //    factor() builds the hierarchy once; each coordinate is one more solve.
  const int n = static_cast<int>(num_vertices(mesh)); // a freshly read Surface_mesh has indices 0..n-1
  const double t = 1.;
  SP::AMG_solver_traits::Matrix A(n, n);
  for(vertex_descriptor v : vertices(mesh))
  {
    double degree = 0.;
    for(vertex_descriptor w : vertices_around_target(v, mesh))
    {
      A.set_coef(static_cast<int>(v), static_cast<int>(w), -t, true);
      degree += 1.;
    }
    A.set_coef(static_cast<int>(v), static_cast<int>(v), 1. + t * degree, true);
  }
  SP::AMG_solver_traits smoother;
  smoother.parameters().direct_solver_threshold = 0;
  double D = 1.;
  if(!smoother.factor(A, D))
  {
    std::cerr << "The AMG setup failed" << std::endl;
    return EXIT_FAILURE;
  }
  SP::AMG_solver_traits::Vector B(n), X(n);
  double largest_move = 0.;
  for(int coordinate = 0; coordinate < 3; ++coordinate)
  {
    for(vertex_descriptor v : vertices(mesh))
      B[static_cast<int>(v)] = mesh.point(v)[coordinate];
    if(!smoother.linear_solver(B, X))
    {
      std::cerr << "The AMG solve failed" << std::endl;
      return EXIT_FAILURE;
    }
    for(int i = 0; i < n; ++i)
      largest_move = (std::max)(largest_move, std::abs(X[i] - B[i]));
  }
  std::cout << "implicit smoothing: largest coordinate change " << largest_move << std::endl;
  print_hierarchy(smoother.statistics());
  return EXIT_SUCCESS;
}
