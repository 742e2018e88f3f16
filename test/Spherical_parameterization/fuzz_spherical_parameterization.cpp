// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// libFuzzer target: OFF text -> parse_OFF -> check_polygon_soup -> spherical_parameterize -> certificate.
// Built by scripts/run_sanitizers.sh with clang, -fsanitize=fuzzer,address,undefined. Besides crashes, leaks and
// undefined behaviour, it stops on a broken promise of the package:
//  - a read or check failure without a message;
//  - an input error from spherical_parameterize() on a mesh that passed the check, or the reverse;
//  - a written map with a non-finite point or a point off the unit sphere;
//  - a status OK (or a `bijective` flag) that the independent certificate does not confirm.
// Inputs are capped (64 KiB, 400 vertices, 0.25 s of iterations) so that the fuzzer explores instead of solving.

#include <CGAL/Spherical_parameterization/IO/read_polygon_soup.h>
#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
using Point = CGAL::Epick::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

[[noreturn]] void broken(const std::string& what)
{
  std::fprintf(stderr, "broken promise: %s\n", what.c_str());
  std::abort();
}

bool is_input_error(SP::Error_code code)
{
  switch(code)
  {
  case SP::Error_code::EMPTY_MESH:
  case SP::Error_code::NOT_TRIANGLE_MESH:
  case SP::Error_code::DEGENERATE_FACE:
  case SP::Error_code::NON_FINITE_COORDINATES:
  case SP::Error_code::ISOLATED_VERTEX:
  case SP::Error_code::HAS_BORDER:
  case SP::Error_code::NON_MANIFOLD_EDGE:
  case SP::Error_code::NON_MANIFOLD_VERTEX:
  case SP::Error_code::INCONSISTENT_ORIENTATION:
  case SP::Error_code::MULTIPLE_COMPONENTS:
  case SP::Error_code::GENUS_NOT_ZERO:
    return true;
  default:
    return false;
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if(size > 64 * 1024)
    return -1; // not added to the corpus
  const char* text = reinterpret_cast<const char*>(data);
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  const SP::IO::File_read read = SP::IO::parse_OFF(text, text + size, points, faces);
  if(!read)
  {
    if(read.message.empty())
      broken("a read failure without a message");
    return 0;
  }
  const SP::Input_check check = SP::check_polygon_soup(points, faces);
  if(check.message.empty())
    broken("a check without a message");
  if(!check || points.size() > 400)
    return 0;

  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);
  if(mesh.number_of_vertices() != points.size() || mesh.number_of_faces() != faces.size())
    broken("a soup that passed the check is not a halfedge mesh");
  if(SP::check_input(mesh).status != SP::Error_code::OK)
    broken("check_input disagrees with check_polygon_soup");

  // The weighting is a function of the input, so that every crash reproduces.
  const SP::Weighting weightings[3] = {SP::Weighting::UNIFORM, SP::Weighting::COTANGENT, SP::Weighting::MEAN_VALUE};
  const SP::Weighting weighting = weightings[size % 3];
  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", Point(7, 7, 7)).first;
  const SP::Result result = SP::spherical_parameterize(mesh, sphere,
                                                       SP::parameters::combine(SP::parameters::weighting(weighting),
                                                                               SP::parameters::max_seconds(0.25),
                                                                               SP::parameters::max_newton_sweeps(200)));
  const std::string status = std::string(SP::get_error_name(result.status)) + ": " + result.message;
  if(is_input_error(result.status))
    broken("an input error after a passed check: " + status);
  if(result.message.empty())
    broken("a result without a message");

  bool written = false;
  for(auto v : mesh.vertices())
    written = written || !(sphere[v] == Point(7, 7, 7));
  if(!written)
  {
    if(result.status == SP::Error_code::OK || result.status == SP::Error_code::NOT_CONVERGED
       || result.status == SP::Error_code::NOT_BIJECTIVE || result.status == SP::Error_code::NO_BALANCED_SOLUTION)
      broken("no map written with " + status);
    return 0;
  }
  for(auto v : mesh.vertices())
  {
    const Point& p = sphere[v];
    if(!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      broken("a non-finite point written with " + status);
    const double r = std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z());
    if(!(std::abs(r - 1.) < 1e-9))
      broken("a point off the unit sphere written with " + status);
  }
  const SP::Sphere_map_certificate certificate = SP::certify_sphere_map(mesh, sphere);
  if(result.status == SP::Error_code::OK && !certificate.bijective)
    broken("OK but not certified bijective");
  if(result.bijective != certificate.bijective)
    broken("Result::bijective disagrees with the certificate: " + status);
  if(result.flipped_faces != certificate.flipped_faces)
    broken("Result::flipped_faces disagrees with the certificate: " + status);
  return 0;
}
