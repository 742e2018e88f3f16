// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Using a spherical parameterization:
//  1. longitude/latitude texture coordinates, written as a textured OBJ;
//  2. a per-vertex value transferred onto an icosphere: each icosphere vertex is located in the spherical
//     triangles of the map and the value is interpolated with barycentric coordinates. The value here is the
//     position on the input surface, so the result is the input remeshed with the icosphere's connectivity
//     (where the map shrinks the surface, as the bunny's ears with uniform weights, it gets few samples).
//   use_sphere_map [input.off] [textured.obj] [remeshed.off]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace PMP = CGAL::Polygon_mesh_processing;
namespace SP = CGAL::Spherical_parameterization;

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point_3 = Kernel::Point_3;
using Vector_3 = Kernel::Vector_3;
using Ray_3 = Kernel::Ray_3;
using Mesh = CGAL::Surface_mesh<Point_3>;
using vertex_descriptor = Mesh::Vertex_index;
using face_descriptor = Mesh::Face_index;
using Sphere_map = Mesh::Property_map<vertex_descriptor, Point_3>;

// Longitude and latitude scaled to [0, 1]: u = 0.5 + longitude / 2 pi, v = 0.5 + latitude / pi.
// One texture coordinate per face corner, so that a face across the date line (u jumps from 1 to 0) can wrap.
bool write_textured_obj(const std::string& filename, const Mesh& mesh, Sphere_map sphere)
{
  std::ofstream out(filename);
  out.precision(17);
  for(vertex_descriptor v : vertices(mesh))
    out << "v " << mesh.point(v) << '\n';
  for(face_descriptor f : faces(mesh))
  {
    double u[3], v[3];
    int k = 0;
    for(vertex_descriptor w : vertices_around_face(halfedge(f, mesh), mesh))
    {
      const Point_3& p = sphere[w];
      u[k] = 0.5 + std::atan2(p.y(), p.x()) / (2. * CGAL_PI);
      v[k] = 0.5 + std::asin((std::max)(-1., (std::min)(1., p.z()))) / CGAL_PI;
      ++k;
    }
    for(int i = 0; i < 3; ++i)
      if((std::max)({u[0], u[1], u[2]}) - (std::min)({u[0], u[1], u[2]}) > 0.5 && u[i] < 0.5)
        u[i] += 1.;
    for(int i = 0; i < 3; ++i)
      out << "vt " << u[i] << ' ' << v[i] << '\n';
  }
  std::size_t corner = 1;
  for(face_descriptor f : faces(mesh))
  {
    out << 'f';
    for(vertex_descriptor w : vertices_around_face(halfedge(f, mesh), mesh))
      out << ' ' << std::size_t(w) + 1 << '/' << corner++;
    out << '\n';
  }
  return static_cast<bool>(out);
}

int main(int argc, char** argv)
{
  const std::string input = (argc > 1) ? argv[1] : "data/bunny.off";
  const std::string textured = (argc > 2) ? argv[2] : "bunny_textured.obj";
  const std::string remeshed = (argc > 3) ? argv[3] : "bunny_remeshed.off";

  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh))
  {
    std::cerr << "Cannot read a mesh from " << input << std::endl;
    return EXIT_FAILURE;
  }
  Sphere_map sphere = mesh.add_property_map<vertex_descriptor, Point_3>("v:sphere", CGAL::ORIGIN).first;
  const SP::Result result = SP::spherical_parameterize(mesh, sphere);
  if(!result)
  {
    std::cerr << "No bijective map: " << result.message << std::endl;
    return EXIT_FAILURE;
  }

  // 1. Texture coordinates.
  if(!write_textured_obj(textured, mesh, sphere))
  {
    std::cerr << "Cannot write " << textured << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "texture coordinates (longitude, latitude) written: " << textured << std::endl;

  // 2. An icosphere: a subdivided icosahedron with its vertices pushed onto the unit sphere.
  Mesh icosphere;
  CGAL::make_icosahedron(icosphere, Point_3(0, 0, 0), 1.);
  CGAL::Subdivision_method_3::Loop_subdivision(icosphere, CGAL::parameters::number_of_iterations(4));
  for(vertex_descriptor v : vertices(icosphere))
  {
    const Vector_3 radius = icosphere.point(v) - CGAL::ORIGIN;
    icosphere.point(v) = CGAL::ORIGIN + radius / std::sqrt(radius.squared_length());
  }

  // The map is bijective, so every ray from the center crosses exactly one of the flat triangles spanned by the
  // sphere positions: locate each icosphere point on those triangles, with an AABB tree over them.
  using AABB_traits = CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Mesh, Sphere_map>>;
  CGAL::AABB_tree<AABB_traits> tree;
  PMP::build_AABB_tree(mesh, tree, CGAL::parameters::vertex_point_map(sphere));

  std::size_t located = 0;
  for(vertex_descriptor v : vertices(icosphere))
  {
    const PMP::Face_location<Mesh, double> location = PMP::locate_with_AABB_tree(
        Ray_3(CGAL::ORIGIN, icosphere.point(v)), tree, mesh, CGAL::parameters::vertex_point_map(sphere));
    if(location.first == Mesh::null_face())
      continue;
    ++located;
    // The value to transfer, interpolated with the barycentric coordinates, which refer to source(h), target(h)
    // and target(next(h)) for h = halfedge(f). Here the value is the position on the input.
    const Mesh::Halfedge_index h = halfedge(location.first, mesh);
    const vertex_descriptor corners[3] = {source(h, mesh), target(h, mesh), target(next(h, mesh), mesh)};
    Vector_3 value = CGAL::NULL_VECTOR;
    for(int k = 0; k < 3; ++k)
      value = value + location.second[k] * (mesh.point(corners[k]) - CGAL::ORIGIN);
    icosphere.point(v) = CGAL::ORIGIN + value;
  }
  std::cout << located << " of " << num_vertices(icosphere) << " icosphere vertices located on the sphere map"
            << std::endl;
  if(located != num_vertices(icosphere))
  {
    std::cerr << "Some points were not located: the map is not bijective" << std::endl;
    return EXIT_FAILURE;
  }
  if(!CGAL::IO::write_polygon_mesh(remeshed, icosphere, CGAL::parameters::stream_precision(17)))
  {
    std::cerr << "Cannot write " << remeshed << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "remeshed input written: " << remeshed << std::endl;
  return EXIT_SUCCESS;
}
