// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Benchmark of CGAL::Spherical_parameterization::AMG_solver_traits against Eigen's solvers:
// setup and solve times for two right-hand sides (u and v, as in a disk parameterization) to a relative
// residual of 1e-10, iterations, residual, and the peak memory added by each method.
//
// Usage: benchmark_AMG_solver_traits [--runs N] [--sizes 10k,100k,1M,4M] [--mesh file.off]...
// Each measurement runs in a forked child, so that its peak memory (VmHWM) is its own; the table gives medians.

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

typedef CGAL::Spherical_parameterization::AMG_solver_traits AMG_traits;
typedef Eigen::SparseMatrix<double> Sparse_matrix;
typedef Eigen::Triplet<double> Triplet;
typedef CGAL::Surface_mesh<CGAL::Epick::Point_3> Mesh;
typedef std::chrono::steady_clock Clock;

struct System
{
  std::string name;
  Sparse_matrix A;
  Eigen::VectorXd bu, bv;
  bool symmetric = true;
};

double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

System poisson_grid(int side)
{
  System system;
  std::ostringstream name;
  name << "grid " << side << "^2";
  system.name = name.str();
  const int n = side * side;
  std::vector<Triplet> triplets;
  triplets.reserve(std::size_t(5) * n);
  for(int y = 0; y < side; ++y)
    for(int x = 0; x < side; ++x)
    {
      const int i = y * side + x;
      triplets.emplace_back(i, i, 4.);
      if(x > 0)
        triplets.emplace_back(i, i - 1, -1.);
      if(x + 1 < side)
        triplets.emplace_back(i, i + 1, -1.);
      if(y > 0)
        triplets.emplace_back(i, i - side, -1.);
      if(y + 1 < side)
        triplets.emplace_back(i, i + side, -1.);
    }
  system.A.resize(n, n);
  system.A.setFromTriplets(triplets.begin(), triplets.end());
  // Dirichlet values u = x, v = y on the boundary, as a parameterization would impose.
  system.bu = Eigen::VectorXd::Zero(n);
  system.bv = Eigen::VectorXd::Zero(n);
  for(int k = 0; k < side; ++k)
  {
    system.bu[k * side + side - 1] += 1.;   // u = 1 on the right side
    system.bv[(side - 1) * side + k] += 1.; // v = 1 on the top side
  }
  return system;
}

Eigen::Vector3d to_eigen(const CGAL::Epick::Point_3& p)
{
  return Eigen::Vector3d(p.x(), p.y(), p.z());
}

// Interior system of a disk (the closed mesh minus the star of its first vertex) with the border on the unit
// circle; cotangent weights (symmetric) or mean-value weights (non-symmetric).
System mesh_disk_system(const std::string& path, bool mean_value)
{
  System system;
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || mesh.is_empty())
  {
    std::cerr << "cannot read " << path << "\n";
    return system;
  }
  const std::string file = path.substr(path.find_last_of('/') + 1);
  system.name = file.substr(0, file.find('.')) + (mean_value ? " mean-value" : " cotangent");
  system.symmetric = !mean_value;

  const Mesh::Vertex_index center = *mesh.vertices().begin();
  std::vector<Mesh::Vertex_index> border;
  for(auto v : CGAL::vertices_around_target(mesh.halfedge(center), mesh))
    border.push_back(v);
  std::vector<Eigen::Vector2d> uv(mesh.number_of_vertices());
  std::vector<char> is_border(mesh.number_of_vertices(), 0);
  for(std::size_t k = 0; k < border.size(); ++k)
  {
    const double angle = 2. * CGAL_PI * double(k) / double(border.size());
    uv[border[k]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    is_border[border[k]] = 1;
  }
  std::vector<int> index(mesh.number_of_vertices(), -1);
  int n = 0;
  for(auto v : mesh.vertices())
    if(v != center && !is_border[v])
      index[v] = n++;

  auto weight = [&](Mesh::Halfedge_index h) {
    const Eigen::Vector3d xi = to_eigen(mesh.point(mesh.target(h)));
    const Eigen::Vector3d xj = to_eigen(mesh.point(mesh.source(h)));
    const Eigen::Vector3d k1 = to_eigen(mesh.point(mesh.target(mesh.next(h))));
    const Eigen::Vector3d k2 = to_eigen(mesh.point(mesh.target(mesh.next(mesh.opposite(h)))));
    if(!mean_value)
    {
      auto cotangent = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.dot(b) / a.cross(b).norm(); };
      return 0.5 * (cotangent(xi - k1, xj - k1) + cotangent(xi - k2, xj - k2));
    }
    auto half_tangent = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::tan(0.5 * std::atan2(a.cross(b).norm(), a.dot(b)));
    };
    return (half_tangent(xj - xi, k1 - xi) + half_tangent(xj - xi, k2 - xi)) / (xj - xi).norm();
  };

  system.bu = Eigen::VectorXd::Zero(n);
  system.bv = Eigen::VectorXd::Zero(n);
  std::vector<Triplet> triplets;
  for(auto v : mesh.vertices())
  {
    if(index[v] < 0)
      continue;
    const int i = index[v];
    double diagonal = 0.;
    for(auto h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
    {
      const auto w = mesh.source(h);
      const double w_ij = weight(h);
      diagonal += w_ij;
      if(index[w] >= 0)
        triplets.emplace_back(i, index[w], -w_ij);
      else
      {
        system.bu[i] += w_ij * uv[w].x();
        system.bv[i] += w_ij * uv[w].y();
      }
    }
    triplets.emplace_back(i, i, diagonal);
  }
  system.A.resize(n, n);
  system.A.setFromTriplets(triplets.begin(), triplets.end());
  return system;
}

struct Measurement
{
  bool ok = false;
  double setup_seconds = 0., solve_seconds = 0.;
  int iterations = 0;
  double relative_residual = 0.;
  double peak_megabytes = 0.;
};

double status_megabytes(const char* field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while(std::getline(status, line))
    if(line.compare(0, std::strlen(field), field) == 0)
      return std::atof(line.c_str() + std::strlen(field)) / 1024.;
  return 0.;
}

// The peak memory of a method is the high-water mark minus the size once its inputs are ready.
double memory_at_start_megabytes = 0.;

void start_memory_measurement()
{
  std::ofstream("/proc/self/clear_refs") << "5"; // resets VmHWM to the current size (Linux >= 4.0)
  memory_at_start_megabytes = status_megabytes("VmRSS:");
}

double relative_residual(const System& s, const Eigen::VectorXd& xu, const Eigen::VectorXd& xv)
{
  return std::max((s.bu - s.A * xu).norm() / s.bu.norm(), (s.bv - s.A * xv).norm() / s.bv.norm());
}

enum class Method
{
  AMG,
  SIMPLICIAL_LDLT,
  SPARSE_LU,
  BICGSTAB_ILUT
};

const char* method_name(Method method, bool symmetric)
{
  switch(method)
  {
  case Method::AMG:
    return symmetric ? "AMG+CG" : "AMG+GMRES";
  case Method::SIMPLICIAL_LDLT:
    return "Eigen SimplicialLDLT";
  case Method::SPARSE_LU:
    return "Eigen SparseLU";
  default:
    return "BiCGSTAB+IncompleteLUT";
  }
}

template <class EigenSolver>
Measurement run_eigen_solver(const System& s, EigenSolver& solver)
{
  Measurement m;
  start_memory_measurement();
  Clock::time_point start = Clock::now();
  solver.compute(s.A);
  m.setup_seconds = seconds_since(start);
  if(solver.info() != Eigen::Success)
    return m;
  start = Clock::now();
  const Eigen::VectorXd xu = solver.solve(s.bu);
  const bool u_ok = solver.info() == Eigen::Success;
  const Eigen::VectorXd xv = solver.solve(s.bv);
  m.solve_seconds = seconds_since(start);
  m.ok = u_ok && solver.info() == Eigen::Success;
  m.relative_residual = relative_residual(s, xu, xv);
  return m;
}

Measurement run_method(const System& s, Method method)
{
  Measurement m;
  switch(method)
  {
  case Method::AMG:
  {
    AMG_traits::Parameters parameters;
    parameters.direct_solver_threshold = 0; // measure AMG itself at every size
    parameters.direct_solver_threshold_non_symmetric = 0;
    AMG_traits solver(parameters);
    const AMG_traits::Matrix A(s.A);
    AMG_traits::Vector bu(std::size_t(s.bu.size())), bv(std::size_t(s.bv.size())), xu, xv;
    bu = s.bu;
    bv = s.bv;
    A.eigen_object(); // assembled: the input of the solver, as s.A is for Eigen's solvers
    double D;
    start_memory_measurement();
    Clock::time_point start = Clock::now();
    m.ok = solver.factor(A, D);
    m.setup_seconds = seconds_since(start);
    start = Clock::now();
    m.ok = m.ok && solver.linear_solver(bu, xu);
    const int iterations_u = solver.statistics().iterations;
    m.ok = m.ok && solver.linear_solver(bv, xv);
    m.solve_seconds = seconds_since(start);
    m.iterations = std::max(iterations_u, solver.statistics().iterations);
    m.relative_residual = relative_residual(s, xu, xv);
    break;
  }
  case Method::SIMPLICIAL_LDLT:
  {
    Eigen::SimplicialLDLT<Sparse_matrix> solver;
    m = run_eigen_solver(s, solver);
    break;
  }
  case Method::SPARSE_LU:
  {
    Eigen::SparseLU<Sparse_matrix> solver;
    m = run_eigen_solver(s, solver);
    break;
  }
  case Method::BICGSTAB_ILUT:
  {
    Eigen::BiCGSTAB<Sparse_matrix, Eigen::IncompleteLUT<double>> solver;
    solver.setTolerance(1e-10);
    solver.setMaxIterations(2000);
    m = run_eigen_solver(s, solver);
    m.iterations = int(solver.iterations());
    break;
  }
  }
  m.ok = m.ok && m.relative_residual <= 1e-10;
  return m;
}

// One measurement in a forked child: the peak memory is the child's high-water mark minus its size at start.
Measurement measure_in_child(const System& s, Method method)
{
  int channel[2];
  if(pipe(channel) != 0)
    return Measurement();
  const pid_t child = fork();
  if(child == 0)
  {
    close(channel[0]);
    Measurement m = run_method(s, method);
    m.peak_megabytes = status_megabytes("VmHWM:") - memory_at_start_megabytes;
    const ssize_t written = write(channel[1], &m, sizeof(m));
    _exit(written == ssize_t(sizeof(m)) ? 0 : 1);
  }
  close(channel[1]);
  Measurement m;
  const ssize_t got = read(channel[0], &m, sizeof(m));
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if(got != ssize_t(sizeof(m)))
    return Measurement();
  return m;
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Would this method obviously take more than about two minutes (measured orders of magnitude on 2 cores)?
bool too_slow(Method method, Eigen::Index n)
{
  switch(method)
  {
  case Method::SIMPLICIAL_LDLT:
    return n > 1500000;
  case Method::SPARSE_LU:
    return n > 1500000;
  case Method::BICGSTAB_ILUT:
    return n > 300000;
  default:
    return false;
  }
}

void benchmark(const System& s, int runs)
{
  std::vector<Method> methods = {Method::AMG, s.symmetric ? Method::SIMPLICIAL_LDLT : Method::SPARSE_LU,
                                 Method::BICGSTAB_ILUT};
  for(Method method : methods)
  {
    std::printf("| %-26s | %9ld | %-22s |", s.name.c_str(), long(s.A.rows()), method_name(method, s.symmetric));
    if(too_slow(method, s.A.rows()))
    {
      std::printf(" skipped |\n");
      std::fflush(stdout);
      continue;
    }
    std::vector<double> setup, solve, peak;
    Measurement last;
    for(int r = 0; r < runs; ++r)
    {
      last = measure_in_child(s, method);
      setup.push_back(last.setup_seconds);
      solve.push_back(last.solve_seconds);
      peak.push_back(last.peak_megabytes);
      if(last.setup_seconds + last.solve_seconds > 30.)
        break; // one run is enough to rank a slow method
    }
    std::printf(" %8.3f | %8.3f | %8.3f | %5d | %9.2e | %8.0f | %s |\n", median(setup), median(solve),
                median(setup) + median(solve), last.iterations, last.relative_residual, median(peak),
                last.ok ? "yes" : "NO");
    std::fflush(stdout);
  }
}

int parse_size(const std::string& text)
{
  double value = std::atof(text.c_str());
  if(text.find_first_of("kK") != std::string::npos)
    value *= 1e3;
  if(text.find_first_of("mM") != std::string::npos)
    value *= 1e6;
  return int(std::lround(std::sqrt(value)));
}

} // namespace

int main(int argc, char** argv)
{
  int runs = 3;
  std::vector<int> grid_sides;
  std::vector<std::string> meshes;
  for(int a = 1; a < argc; ++a)
  {
    const std::string argument = argv[a];
    if(argument == "--runs" && a + 1 < argc)
      runs = std::max(1, std::atoi(argv[++a]));
    else if(argument == "--sizes" && a + 1 < argc)
    {
      std::stringstream list(argv[++a]);
      std::string item;
      while(std::getline(list, item, ','))
        grid_sides.push_back(parse_size(item));
    }
    else if(argument == "--mesh" && a + 1 < argc)
      meshes.push_back(argv[++a]);
    else
    {
      std::cerr << "usage: " << argv[0] << " [--runs N] [--sizes 10k,100k,1M,4M] [--mesh file.off]...\n";
      return 1;
    }
  }
  if(grid_sides.empty() && meshes.empty())
    grid_sides = {100, 316, 1000, 2000};

  std::printf("Two right-hand sides to a relative residual of 1e-10; medians of %d runs; peak = memory added.\n", runs);
  std::printf("| system | unknowns | method | setup s | solve s | total s | iter | rel. residual | peak MB | ok |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for(int side : grid_sides)
    benchmark(poisson_grid(side), runs);
  for(const std::string& path : meshes)
    for(bool mean_value : {false, true})
    {
      const System s = mesh_disk_system(path, mean_value);
      if(s.A.rows() > 0)
        benchmark(s, runs);
    }
  return 0;
}
