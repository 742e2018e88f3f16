// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The whole pipeline on a list of meshes, printed as a table in the style of the paper's Table 1 (and as CSV).
//
//   benchmark_spherical_parameterization [--runs N] [--weights uniform,mean_value,cotangent]
//                                        [--solvers global,local,paper] [--tolerance T] [--max-seconds S]
//                                        [--sequential] [--csv FILE] MESH...
// Solvers: global = the default (global Newton, multilevel start where it applies, stopping on the imbalance);
// local = the paper's local Newton, stopping on the imbalance; paper = the paper's setting as published (two-disk
// start, local Newton, stopping on its Res).
// CGAL::Parallel_if_available_tag by default (with TBB: the two disks of stage 1 at the same time, the multilevel
// levels' preconditioners built ahead, the Newton steps' independent quantities side by side; the same maps);
// --sequential uses CGAL::Sequential_tag.
//
// Each configuration runs N times; the table gives the median seconds and the figures of the median run.
// Peak memory is the process' VmHWM after the run, reading the mesh included (monotone over the program: run one
// mesh per process for per-mesh peaks, as scripts/run_benchmark.sh does). --csv appends to an existing file.

#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
using Point = CGAL::Epick::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

std::vector<std::string> split(const std::string& list)
{
  std::vector<std::string> items;
  std::stringstream in(list);
  for(std::string item; std::getline(in, item, ',');)
    if(!item.empty())
      items.push_back(item);
  return items;
}

double peak_megabytes()
{
  std::ifstream status("/proc/self/status");
  for(std::string line; std::getline(status, line);)
    if(line.rfind("VmHWM:", 0) == 0)
      return std::stod(line.substr(6)) / 1024.;
  return -1.;
}

SP::Weighting weighting_of(const std::string& name)
{
  if(name == "cotangent")
    return SP::Weighting::COTANGENT;
  if(name == "mean_value")
    return SP::Weighting::MEAN_VALUE;
  return SP::Weighting::UNIFORM;
}

// "vertices:Newton steps" of each multilevel level, coarsest first, separated by ';' (empty without levels).
std::string levels_of(const SP::Result& result)
{
  std::string text;
  for(const SP::Level_statistics& level : result.levels)
    text += (text.empty() ? "" : ";") + std::to_string(level.vertices) + ":" + std::to_string(level.newton_steps);
  return text;
}

} // namespace

int main(int argc, char** argv)
{
  int runs = 3;
  double max_seconds = 600., tolerance = 1e-6;
  std::vector<std::string> weights = {"uniform"}, solvers = {"global"}, meshes;
  std::string csv_path;
  bool sequential = false;
  for(int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if(arg == "--runs" && a + 1 < argc)
      runs = std::max(1, std::atoi(argv[++a]));
    else if(arg == "--weights" && a + 1 < argc)
      weights = split(argv[++a]);
    else if(arg == "--solvers" && a + 1 < argc)
      solvers = split(argv[++a]);
    else if(arg == "--max-seconds" && a + 1 < argc)
      max_seconds = std::atof(argv[++a]);
    else if(arg == "--tolerance" && a + 1 < argc)
      tolerance = std::atof(argv[++a]);
    else if(arg == "--csv" && a + 1 < argc)
      csv_path = argv[++a];
    else if(arg == "--sequential")
      sequential = true;
    else
      meshes.push_back(arg);
  }
  if(meshes.empty())
  {
    std::cerr << "usage: benchmark_spherical_parameterization [options] MESH...\n";
    return 2;
  }

  // An existing CSV file is appended to, so that a script can run one mesh per process (per-mesh peak memory).
  std::ofstream csv;
  if(!csv_path.empty())
  {
    const bool exists = std::ifstream(csv_path).good();
    csv.open(csv_path, std::ios::app);
    if(!exists)
      csv << "mesh,faces,weights,solver,tolerance,status,initial_s,gauss_seidel_s,newton_s,total_s,gs_sweeps,newton_"
             "steps,res,max_tangential,flips,peak_mb,runs,max_imbalance,levels\n";
  }
  std::printf("%-28s %9s %-10s %-6s %-14s %8s %8s %8s %8s %10s %10s %6s %8s\n", "mesh", "faces", "weights", "solver",
              "status", "init s", "gs s", "newton s", "total s", "Res", "max e_i", "flips", "peak MB");
  for(const std::string& path : meshes)
  {
    Mesh mesh;
    if(!CGAL::IO::read_polygon_mesh(path, mesh))
    {
      std::cerr << "cannot read " << path << "\n";
      continue;
    }
    std::string name = path.substr(path.find_last_of('/') + 1);
    name = name.substr(0, name.find_last_of('.'));
    auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere").first;
    for(const std::string& w : weights)
      for(const std::string& s : solvers)
      {
        std::vector<SP::Result> results;
        for(int r = 0; r < runs; ++r)
        {
          const bool paper = s == "paper";
          const auto parameters = SP::parameters::combine(
              SP::parameters::weighting(weighting_of(w)), SP::parameters::max_seconds(max_seconds),
              SP::parameters::tolerance(tolerance),
              SP::parameters::nonlinear_solver(s == "global" ? SP::Nonlinear_solver::GLOBAL_NEWTON
                                                             : SP::Nonlinear_solver::LOCAL_NEWTON),
              SP::parameters::convergence_test(paper ? SP::Convergence_test::PAPER_RESIDUAL
                                                     : SP::Convergence_test::IMBALANCE),
              SP::parameters::multilevel(!paper));
          results.push_back(
              sequential ? SP::spherical_parameterize<CGAL::Sequential_tag>(mesh, sphere, parameters)
                         : SP::spherical_parameterize<CGAL::Parallel_if_available_tag>(mesh, sphere, parameters));
        }
        std::sort(results.begin(), results.end(),
                  [](const SP::Result& a, const SP::Result& b) { return a.total_seconds < b.total_seconds; });
        const SP::Result& m = results[results.size() / 2];
        const double peak = peak_megabytes();
        std::printf("%-28s %9zu %-10s %-6s %-14s %8.3f %8.3f %8.3f %8.3f %10.3g %10.3g %6zu %8.0f\n", name.c_str(),
                    m.number_of_faces, w.c_str(), s.c_str(), SP::get_error_name(m.status), m.initial_guess.seconds,
                    m.gauss_seidel.seconds, m.newton.seconds, m.total_seconds, m.residual, m.max_imbalance,
                    m.flipped_faces, peak);
        std::fflush(stdout);
        if(csv.is_open())
          csv << name << ',' << m.number_of_faces << ',' << w << ',' << s << ',' << tolerance << ','
              << SP::get_error_name(m.status) << ',' << m.initial_guess.seconds << ',' << m.gauss_seidel.seconds << ','
              << m.newton.seconds << ',' << m.total_seconds << ',' << m.gauss_seidel.iterations << ','
              << m.newton.iterations << ',' << m.residual << ',' << m.max_tangential_residual << ',' << m.flipped_faces
              << ',' << peak << ',' << runs << ',' << m.max_imbalance << ',' << levels_of(m) << '\n';
      }
  }
  return 0;
}
