// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Writes the meshes of the manual's pictures as POV-Ray include files (rendered by scripts/make_figures.sh):
// the input mesh, its two halves, the two planar disks, the initial sphere (stage 1, uniform weights) and the
// final spheres for uniform, mean-value and cotangent weights. Every vertex is coloured by the normal of the
// input mesh at that vertex, (n + 1) / 2 as RGB, which shows where each part of the shape lies on the sphere,
// as the paper's figures do.
//
//   make_figure_meshes INPUT OUT_DIR [--stages] [--weights uniform,mean_value,cotangent] [--view-from X,Y,Z] [--up X,Y,Z]
//
// The stages use the package's internal functions read-only, in the order spherical_parameterize() calls them,
// so the pictures show what the package computes. Coordinates are written in the display frame: the input mesh
// is centred, scaled into the unit ball and turned so that --view-from points at the viewer (+z) and --up is +y;
// POV-Ray's left-handed frame gets (x, y, -z).

#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
namespace SPI = CGAL::Spherical_parameterization::internal;
using Vector3 = SPI::Vector3;
using Point = CGAL::Epick::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

bool parse_vector(const std::string& text, Vector3& v)
{
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  return static_cast<bool>(in >> v.x >> c1 >> v.y >> c2 >> v.z) && c1 == ',' && c2 == ',';
}

Vector3 normalized(const Vector3& v) { return v * (1. / SPI::length(v)); }

// Area-weighted vertex normals of the input: the colour key of every picture.
std::vector<Vector3> vertex_normals(const SPI::Mesh_arrays& mesh)
{
  std::vector<Vector3> normals(mesh.points.size());
  for(const auto& t : mesh.triangles) {
    const Vector3& a = mesh.points[static_cast<std::size_t>(t[0])];
    const Vector3 n = SPI::cross(mesh.points[static_cast<std::size_t>(t[1])] - a, mesh.points[static_cast<std::size_t>(t[2])] - a);
    for(int i : t) normals[static_cast<std::size_t>(i)] += n;
  }
  for(Vector3& n : normals) n = SPI::length(n) > 0. ? normalized(n) : Vector3(0., 0., 1.);
  return normals;
}

// Rows of the rotation that takes `view_from` to +z and `up` to +y.
struct Display_frame {
  Vector3 right, up, back;
  Vector3 operator()(const Vector3& p) const { return Vector3(SPI::dot(right, p), SPI::dot(up, p), SPI::dot(back, p)); }
};

Display_frame make_frame(const Vector3& view_from, const Vector3& up_hint)
{
  Display_frame frame;
  frame.back = normalized(view_from);
  frame.up = normalized(up_hint - SPI::dot(up_hint, frame.back) * frame.back);
  frame.right = SPI::cross(frame.up, frame.back);
  return frame;
}

void write_vector(std::ostream& out, const Vector3& p) { out << '<' << p.x << ',' << p.y << ',' << -p.z << '>'; }

// A POV-Ray mesh2 named `name`: vertex colours from `colour_normals` (none if empty: the scene gives the texture), smooth shading with `shading_normals`, and a
// macro `name_edges(R)` with the edges as cylinders of radius R (the scene decides whether to draw them).
void write_mesh2(std::ostream& out, const std::string& name, const std::vector<Vector3>& points,
                 const std::vector<std::array<int, 3>>& triangles, const std::vector<char>& keep_face,
                 const std::vector<Vector3>& colour_normals, const std::vector<Vector3>& shading_normals)
{
  const std::size_t n = points.size();
  out << "#declare " << name << " = mesh2 {\n  vertex_vectors { " << n;
  for(const Vector3& p : points) { out << ",\n"; write_vector(out, p); }
  out << " }\n  normal_vectors { " << n;
  for(const Vector3& p : shading_normals) { out << ",\n"; write_vector(out, p); }
  out << " }\n";
  if(!colour_normals.empty()) {
    out << "  texture_list { " << n;
    for(const Vector3& c : colour_normals) {
      const Vector3 rgb = 0.5 * (c + Vector3(1., 1., 1.));
      out << ",\n texture { pigment { srgb <" << rgb.x << ',' << rgb.y << ',' << rgb.z << "> } }";
    }
    out << " }\n";
  }
  std::size_t kept = 0;
  for(char k : keep_face) kept += (k != 0);
  out << "  face_indices { " << kept;
  for(std::size_t f = 0; f < triangles.size(); ++f) {
    if(!keep_face[f]) continue;
    const auto& t = triangles[f];
    out << ",\n<" << t[0] << ',' << t[1] << ',' << t[2] << '>';
    if(!colour_normals.empty()) out << ',' << t[0] << ',' << t[1] << ',' << t[2];
  }
  out << " }\n}\n\n#macro " << name << "_edges(R)\nunion {\n";
  for(std::size_t f = 0; f < triangles.size(); ++f) {
    if(!keep_face[f]) continue;
    const auto& t = triangles[f];
    for(int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if(a > b) continue;  // each edge of a closed mesh once; a disk's border edges are the loop, drawn apart
      out << "cylinder { ";
      write_vector(out, points[static_cast<std::size_t>(a)]);
      out << ", ";
      write_vector(out, points[static_cast<std::size_t>(b)]);
      out << ", R }\n";
    }
  }
  out << "}\n#end\n\n";
}

// The loop shared by the two halves, as a macro `name(R)` of cylinders and spheres.
void write_loop(std::ostream& out, const std::string& name, const std::vector<Vector3>& points, const std::vector<int>& loop)
{
  out << "#macro " << name << "(R)\nunion {\n";
  for(std::size_t k = 0; k < loop.size(); ++k) {
    const Vector3& a = points[static_cast<std::size_t>(loop[k])];
    const Vector3& b = points[static_cast<std::size_t>(loop[(k + 1) % loop.size()])];
    out << "cylinder { ";
    write_vector(out, a);
    out << ", ";
    write_vector(out, b);
    out << ", R }\nsphere { ";
    write_vector(out, a);
    out << ", R }\n";
  }
  out << "}\n#end\n\n";
}

bool write_file(const std::string& path, const std::string& text)
{
  std::ofstream out(path);
  out << text;
  return static_cast<bool>(out);
}

const char* status_name(SP::Error_code status)
{
  switch(status) {
    case SP::Error_code::OK: return "certified bijective";
    case SP::Error_code::NOT_CONVERGED: return "not converged";
    case SP::Error_code::NOT_BIJECTIVE: return "not bijective";
    default: return "failed";
  }
}

// "Res 8.117e-07, 0 flipped": the figures a picture shows (four digits, so that a value just below the tolerance
// does not print as the tolerance; times vary from run to run, so they stay out of it).
std::string figures_text(double residual, std::size_t flipped)
{
  char text[100];
  std::snprintf(text, sizeof text, "Res %.3e, %zu flipped", residual, flipped);
  return text;
}

} // namespace

int main(int argc, char** argv)
{
  const char* usage = "Usage: make_figure_meshes INPUT OUT_DIR [--stages] [--weights uniform,mean_value,cotangent] "
                      "[--view-from X,Y,Z] [--up X,Y,Z]\n";
  std::string input, out_dir;
  bool stages = false;
  std::string weights = "uniform,mean_value,cotangent";
  Vector3 view_from(0., 0., 1.), up(0., 1., 0.);
  for(int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if(arg == "--stages") stages = true;
    else if(arg == "--weights" && i + 1 < argc) weights = argv[++i];
    else if(arg == "--view-from" && i + 1 < argc && parse_vector(argv[i + 1], view_from)) ++i;
    else if(arg == "--up" && i + 1 < argc && parse_vector(argv[i + 1], up)) ++i;
    else if(input.empty() && arg[0] != '-') input = arg;
    else if(out_dir.empty() && arg[0] != '-') out_dir = arg;
    else {
      std::cerr << usage;
      return 4;
    }
  }
  if(out_dir.empty()) {
    std::cerr << usage;
    return 4;
  }

  Mesh tm;
  if(!CGAL::IO::read_polygon_mesh(input, tm)) {
    std::cerr << "cannot read " << input << "\n";
    return 3;
  }
  const SP::Input_check check = SP::check_input(tm);
  if(!check) {
    std::cerr << input << ": " << check.message << "\n";
    return 2;
  }
  const SPI::Mesh_arrays mesh = SPI::read_face_graph(tm, get(CGAL::vertex_point, tm), get(CGAL::vertex_index, tm));
  const std::size_t nv = mesh.points.size(), nf = mesh.triangles.size();
  const std::vector<Vector3> normals = vertex_normals(mesh);
  const std::vector<char> all_faces(nf, 1);

  // The input in the display frame, centred on its bounding box and scaled into the unit ball.
  const Display_frame frame = make_frame(view_from, up);
  Vector3 lo = mesh.points[0], hi = mesh.points[0];
  for(const Vector3& p : mesh.points) {
    lo = Vector3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vector3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  }
  const Vector3 centre = 0.5 * (lo + hi);
  double radius = 0.;
  for(const Vector3& p : mesh.points) radius = std::max(radius, SPI::length(p - centre));
  std::vector<Vector3> shown(nv), shown_normals(nv);
  for(std::size_t i = 0; i < nv; ++i) {
    shown[i] = frame((mesh.points[i] - centre) * (1. / radius));
    shown_normals[i] = frame(normals[i]);
  }
  std::ostringstream input_inc;
  write_mesh2(input_inc, "Input_mesh", shown, mesh.triangles, all_faces, normals, shown_normals);

  input_inc << "#declare Mesh_figures = \"" << nv << " vertices, " << nf << " faces\";\n";

  // Stage 1 as Sphere_mapper::two_disk_start() runs it with uniform weights (the paper's Figure 1); every weighting starts from
  // the same partition, so its loop is drawn on every sphere.
  SPI::Sphere_system system = SPI::make_connectivity(mesh);
  std::string message;
  if(SPI::assign_weights(system, mesh, SP::Weighting::UNIFORM, {}, message) != SP::Error_code::OK) {
    std::cerr << message << "\n";
    return 1;
  }
  const SPI::Two_disk_partition partition = SPI::split_into_two_disks(system, 0, nullptr);
  if(!partition.valid) {
    std::cerr << "no partition into two disks\n";
    return 1;
  }
  if(stages) {
    const SP::Default_disk_solver_traits solver;
    std::vector<double> u(nv, 0.), v(nv, 0.);
    std::vector<Vector3> initial;
    if(!SPI::embed_one_disk(mesh, system, partition, 1, SP::Weighting::UNIFORM, solver, u, v) ||
       !SPI::embed_one_disk(mesh, system, partition, 0, SP::Weighting::UNIFORM, solver, u, v) ||
       !SPI::initial_sphere(mesh, system, partition, SP::Weighting::UNIFORM, solver, initial)) {
      std::cerr << "stage 1 failed\n";
      return 1;
    }
    const std::vector<char>& in_a = partition.face_in_disk_a;
    std::vector<char> in_b(nf);
    for(std::size_t f = 0; f < nf; ++f) in_b[f] = !in_a[f];
    write_mesh2(input_inc, "Half_a", shown, mesh.triangles, in_a, normals, shown_normals);
    write_mesh2(input_inc, "Half_b", shown, mesh.triangles, in_b, normals, shown_normals);
    write_mesh2(input_inc, "Half_a_plain", shown, mesh.triangles, in_a, {}, shown_normals);
    write_mesh2(input_inc, "Half_b_plain", shown, mesh.triangles, in_b, {}, shown_normals);

    // Disk B is seen from below (u mirrored), as the sphere's southern half is: the loop then runs the same way
    // round in both pictures of B.
    std::vector<Vector3> disk_a(nv), disk_b(nv), flat(nv, Vector3(0., 0., 1.));
    for(std::size_t i = 0; i < nv; ++i) {
      disk_a[i] = Vector3(u[i], v[i], 0.);
      disk_b[i] = Vector3(-u[i], v[i], 0.);
    }
    std::ostringstream disks;
    write_mesh2(disks, "Disk_a", disk_a, mesh.triangles, in_a, normals, flat);
    write_mesh2(disks, "Disk_b", disk_b, mesh.triangles, in_b, normals, flat);
    write_loop(disks, "Disk_loop", disk_a, partition.loop);
    write_mesh2(disks, "Initial_sphere", initial, mesh.triangles, all_faces, normals, initial);
    write_loop(disks, "Sphere_loop", initial, partition.loop);
    const SPI::Sphere_certificate start = SPI::certify(system.triangles, initial);
    disks << "#declare Initial_figures = \"" << figures_text(SPI::compute_residuals(system, initial).paper, start.flipped_faces)
          << "\";\n#declare Loop_figures = \"loop of " << partition.loop.size() << " vertices\";\n";
    if(!write_file(out_dir + "/stages.inc", disks.str())) return 3;
  }
  write_loop(input_inc, "Input_loop", shown, partition.loop);
  if(!write_file(out_dir + "/input.inc", input_inc.str())) return 3;

  const std::pair<SP::Weighting, const char*> weightings[] = {
      {SP::Weighting::UNIFORM, "uniform"}, {SP::Weighting::MEAN_VALUE, "mean_value"}, {SP::Weighting::COTANGENT, "cotangent"}};
  for(const auto& [weighting, name] : weightings) {
    if(("," + weights + ",").find(std::string(",") + name + ",") == std::string::npos) continue;
    auto sphere = tm.add_property_map<Mesh::Vertex_index, Point>("v:sphere").first;
    // The weights' own maps, as in the paper's Figures 2 and 3 (the default minimizes the distortion where they fail).
    const SP::Result result = SP::spherical_parameterize(
        tm, sphere,
        SP::parameters::combine(SP::parameters::weighting(weighting), SP::parameters::least_distortion(false)));
    if(result.status != SP::Error_code::OK && result.status != SP::Error_code::NOT_CONVERGED &&
       result.status != SP::Error_code::NOT_BIJECTIVE) {
      std::cerr << name << ": " << result.message << "\n";
      return 1;
    }
    std::vector<Vector3> x(nv);
    for(Mesh::Vertex_index vi : vertices(tm)) {
      const Point& p = sphere[vi];
      x[static_cast<std::size_t>(vi)] = Vector3(p.x(), p.y(), p.z());
    }
    std::ostringstream final_inc;
    const std::string declared = std::string("Final_") + name;
    write_mesh2(final_inc, declared, x, mesh.triangles, all_faces, normals, x);
    write_loop(final_inc, declared + "_loop", x, partition.loop);
    final_inc << "#declare " << declared << "_status = \"" << status_name(result.status) << "\";\n#declare " << declared
              << "_figures = \"" << figures_text(result.residual, result.flipped_faces) << "\";\n";
    std::cout << name << ": " << status_name(result.status) << ", " << figures_text(result.residual, result.flipped_faces)
              << (result.uniform_initial_guess_fallback ? ", from Tutte disks (these weights folded the disks)" : "")
              << ", " << result.total_seconds << " s\n";
    if(!write_file(out_dir + "/final_" + name + ".inc", final_inc.str())) return 3;
    tm.remove_property_map(sphere);
  }
  return 0;
}
