// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Tests of CGAL::Spherical_parameterization::AMG_solver_traits: accuracy against Eigen's SparseLU on disk
// systems of real meshes (uniform, cotangent, mean-value weights; with and without CGAL's identity border rows),
// iteration counts on Poisson grids, use through CGAL's Fixed_border_parameterizer_3, and failure on bad input.

#include <CGAL/Spherical_parameterization/AMG_solver_traits.h>
#include <CGAL/Spherical_parameterization/independent_copy.h>
#include <CGAL/Spherical_parameterization/internal/AMG/Krylov_solvers.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/surface_mesh_parameterization.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <Eigen/SparseLU>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

typedef CGAL::Epick Kernel;
typedef Kernel::Point_3 Point_3;
typedef Kernel::Point_2 Point_2;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef CGAL::Spherical_parameterization::AMG_solver_traits AMG_traits;
typedef Eigen::SparseMatrix<double> Sparse_matrix;
typedef Eigen::Triplet<double> Triplet;

AMG_traits::Parameters amg_only()
{
  AMG_traits::Parameters parameters;
  parameters.direct_solver_threshold = 0; // the test systems are small: force the multigrid path
  parameters.direct_solver_threshold_non_symmetric = 0;
  return parameters;
}

Mesh read_mesh(const std::string& name)
{
  Mesh mesh;
  const std::string path = std::string(SP_SHARED_MESHES) + "/" + name;
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || mesh.is_empty())
    ADD_FAILURE() << "cannot read " << path;
  return mesh;
}

Eigen::Vector3d to_eigen(const Point_3& p)
{
  return Eigen::Vector3d(p.x(), p.y(), p.z());
}

enum class Weighting
{
  UNIFORM,
  COTANGENT,
  MEAN_VALUE
};

// Weight of the edge from interior vertex i to its neighbour j = source(h), h pointing to i.
double edge_weight(const Mesh& mesh, Mesh::Halfedge_index h, Weighting weighting)
{
  if(weighting == Weighting::UNIFORM)
    return 1.;
  const Eigen::Vector3d xi = to_eigen(mesh.point(mesh.target(h)));
  const Eigen::Vector3d xj = to_eigen(mesh.point(mesh.source(h)));
  const Eigen::Vector3d k1 = to_eigen(mesh.point(mesh.target(mesh.next(h))));
  const Eigen::Vector3d k2 = to_eigen(mesh.point(mesh.target(mesh.next(mesh.opposite(h)))));
  if(weighting == Weighting::COTANGENT)
  {
    auto cotangent = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return u.dot(v) / u.cross(v).norm(); };
    return 0.5 * (cotangent(xi - k1, xj - k1) + cotangent(xi - k2, xj - k2));
  }
  auto half_angle_tangent = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return std::tan(0.5 * std::atan2(u.cross(v).norm(), u.dot(v)));
  };
  return (half_angle_tangent(xj - xi, k1 - xi) + half_angle_tangent(xj - xi, k2 - xi)) / (xj - xi).norm();
}

struct Disk_system
{
  Sparse_matrix A;
  Eigen::VectorXd bu, bv;
};

// The disk is the closed mesh minus the faces around its first vertex; the link of that vertex is the border,
// mapped to the unit circle by arc length. With keep_border_rows, the border vertices keep identity rows as in
// CGAL's Fixed_border_parameterizer_3; otherwise only the interior unknowns remain.
Disk_system build_disk_system(const Mesh& mesh, Weighting weighting, bool keep_border_rows)
{
  const Vertex center = *mesh.vertices().begin();
  std::vector<Vertex> border;
  for(Vertex v : CGAL::vertices_around_target(mesh.halfedge(center), mesh))
    border.push_back(v);
  std::vector<double> arc_length(border.size() + 1, 0.);
  for(std::size_t k = 0; k < border.size(); ++k)
    arc_length[k + 1] =
        arc_length[k]
        + (to_eigen(mesh.point(border[(k + 1) % border.size()])) - to_eigen(mesh.point(border[k]))).norm();
  std::vector<Eigen::Vector2d> border_uv(mesh.number_of_vertices());
  std::vector<char> is_border(mesh.number_of_vertices(), 0);
  for(std::size_t k = 0; k < border.size(); ++k)
  {
    const double angle = 2. * CGAL_PI * arc_length[k] / arc_length.back();
    border_uv[border[k]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    is_border[border[k]] = 1;
  }

  std::vector<int> index(mesh.number_of_vertices(), -1);
  int n = 0;
  for(Vertex v : mesh.vertices())
    if(v != center && (keep_border_rows || !is_border[v]))
      index[v] = n++;

  Disk_system system;
  system.bu = Eigen::VectorXd::Zero(n);
  system.bv = Eigen::VectorXd::Zero(n);
  std::vector<Triplet> triplets;
  for(Vertex v : mesh.vertices())
  {
    if(index[v] < 0)
      continue;
    const int i = index[v];
    if(is_border[v])
    {
      triplets.emplace_back(i, i, 1.);
      system.bu[i] = border_uv[v].x();
      system.bv[i] = border_uv[v].y();
      continue;
    }
    double diagonal = 0.;
    for(Mesh::Halfedge_index h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
    {
      const Vertex w = mesh.source(h);
      const double weight = edge_weight(mesh, h, weighting);
      diagonal += weight;
      if(index[w] >= 0)
        triplets.emplace_back(i, index[w], -weight);
      else
      {
        system.bu[i] += weight * border_uv[w].x();
        system.bv[i] += weight * border_uv[w].y();
      }
    }
    triplets.emplace_back(i, i, diagonal);
  }
  system.A.resize(n, n);
  system.A.setFromTriplets(triplets.begin(), triplets.end());
  return system;
}

// 5-point Laplacian with Dirichlet conditions on a side x side grid.
Sparse_matrix poisson_grid(int side)
{
  std::vector<Triplet> triplets;
  triplets.reserve(std::size_t(5) * side * side);
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
  Sparse_matrix A(side * side, side * side);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

AMG_traits::Vector to_vector(const Eigen::VectorXd& v)
{
  AMG_traits::Vector result(std::size_t(v.size()));
  result = v;
  return result;
}

double relative_residual(const Sparse_matrix& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x)
{
  return (b - A * x).norm() / b.norm();
}

double relative_difference(const Eigen::VectorXd& x, const Eigen::VectorXd& reference)
{
  return (x - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

Eigen::VectorXd solve_with_sparse_lu(const Sparse_matrix& A, const Eigen::VectorXd& b)
{
  Eigen::SparseLU<Sparse_matrix> lu(A);
  EXPECT_EQ(lu.info(), Eigen::Success);
  return lu.solve(b);
}

struct Disk_case
{
  std::string mesh;
  Weighting weighting;
  bool keep_border_rows;
};

std::string case_name(const testing::TestParamInfo<Disk_case>& info)
{
  std::string name = info.param.mesh.substr(0, info.param.mesh.find('.'));
  name += info.param.weighting == Weighting::UNIFORM     ? "_uniform"
          : info.param.weighting == Weighting::COTANGENT ? "_cotangent"
                                                         : "_mean_value";
  name += info.param.keep_border_rows ? "_border_rows" : "_reduced";
  return name;
}

class Disk_systems : public testing::TestWithParam<Disk_case>
{};

TEST_P(Disk_systems, MatchSparseLUToTightTolerance)
{
  const Disk_case& test_case = GetParam();
  const Mesh mesh = read_mesh(test_case.mesh);
  ASSERT_FALSE(mesh.is_empty());
  const Disk_system system = build_disk_system(mesh, test_case.weighting, test_case.keep_border_rows);

  AMG_traits solver(amg_only());
  const AMG_traits::Matrix A(system.A);
  AMG_traits::Vector Xu, Xv;
  double Du = 0., Dv = 0.;
  ASSERT_TRUE(solver.linear_solver(A, to_vector(system.bu), Xu, Du));
  EXPECT_EQ(solver.statistics().number_of_setups, 1u);
  ASSERT_TRUE(solver.linear_solver(A, to_vector(system.bv), Xv, Dv));
  EXPECT_EQ(solver.statistics().number_of_setups, 1u) << "the second right-hand side must reuse the setup";
  EXPECT_EQ(Du, 1.);
  EXPECT_EQ(Dv, 1.);

  const AMG_traits::Statistics& statistics = solver.statistics();
  EXPECT_FALSE(statistics.direct_solver);
  EXPECT_GT(statistics.level_sizes.size(), 1u);
  EXPECT_LE(statistics.iterations, 40);
  EXPECT_EQ(statistics.symmetric, test_case.weighting != Weighting::MEAN_VALUE);
  EXPECT_EQ(statistics.number_of_eliminated_rows > 0, test_case.keep_border_rows);

  EXPECT_LE(relative_residual(system.A, system.bu, Xu), 1e-10);
  EXPECT_LE(relative_residual(system.A, system.bv, Xv), 1e-10);
  EXPECT_LE(relative_difference(Xu, solve_with_sparse_lu(system.A, system.bu)), 1e-8);
  EXPECT_LE(relative_difference(Xv, solve_with_sparse_lu(system.A, system.bv)), 1e-8);
}

std::vector<Disk_case> disk_cases()
{
  std::vector<Disk_case> cases;
  for(const char* mesh : {"c3d_fandisk.off", "nilearn_fsavg5_pial_left.off"})
    for(Weighting weighting : {Weighting::UNIFORM, Weighting::COTANGENT, Weighting::MEAN_VALUE})
      for(bool keep_border_rows : {false, true})
        cases.push_back({mesh, weighting, keep_border_rows});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, Disk_systems, testing::ValuesIn(disk_cases()), case_name);

TEST(Disk_systems_krylov, BiCGStabAndGMRESAgreeOnMeanValueWeights)
{
  const Disk_system system = build_disk_system(read_mesh("c3d_fandisk.off"), Weighting::MEAN_VALUE, true);
  const Eigen::VectorXd reference = solve_with_sparse_lu(system.A, system.bu);
  for(AMG_traits::Krylov_method method : {AMG_traits::Krylov_method::BICGSTAB, AMG_traits::Krylov_method::GMRES})
  {
    AMG_traits::Parameters parameters = amg_only();
    parameters.krylov_method = method;
    AMG_traits solver(parameters);
    AMG_traits::Vector X;
    double D;
    ASSERT_TRUE(solver.linear_solver(AMG_traits::Matrix(system.A), to_vector(system.bu), X, D));
    EXPECT_EQ(solver.statistics().krylov_method, method);
    EXPECT_LE(relative_residual(system.A, system.bu, X), 1e-10);
    EXPECT_LE(relative_difference(X, reference), 1e-8);
  }
}

int grid_iterations(int side)
{
  const Sparse_matrix A = poisson_grid(side);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  AMG_traits solver(amg_only());
  AMG_traits::Vector X;
  double D;
  EXPECT_TRUE(solver.linear_solver(AMG_traits::Matrix(A), to_vector(b), X, D));
  EXPECT_LE(relative_residual(A, b, X), 1e-10);
  const AMG_traits::Statistics& statistics = solver.statistics();
  EXPECT_TRUE(statistics.symmetric);
  EXPECT_EQ(statistics.krylov_method, AMG_traits::Krylov_method::CONJUGATE_GRADIENT);
  EXPECT_LT(statistics.operator_complexity, 3.5);
  EXPECT_LT(statistics.grid_complexity, 2.2);
  EXPECT_LE(statistics.level_sizes.back(), 200u);
  return statistics.iterations;
}

TEST(Poisson_grid, IterationCountsAreBoundedAndDoNotGrowWithSize)
{
  const int iterations_10k = grid_iterations(100);
  const int iterations_100k = grid_iterations(316);
  EXPECT_LE(iterations_10k, 15);
  EXPECT_LE(iterations_100k, 15);
  EXPECT_LE(iterations_100k, iterations_10k + 3);
}

// GMRES's stop(): asked after every iteration, it ends the solve there with the iterate reached (a time budget
// inside one Krylov solve: stage 3's least-squares steps on brain cortices ran 600 iterations, 20 s, in one step).
TEST(Gmres_stop, EndsTheSolveWhereAsked)
{
  namespace AMG = CGAL::Spherical_parameterization::internal::AMG;
  // A non-symmetric tridiagonal system (convection-diffusion on a line), matrix-free, no preconditioner.
  const AMG::Index n = 400;
  auto apply = [n](const double* in, double* out) {
    for(AMG::Index i = 0; i < n; ++i)
      out[i] = 2.5 * in[i] - (i > 0 ? 1.4 * in[i - 1] : 0.) - (i + 1 < n ? 0.6 * in[i + 1] : 0.);
  };
  std::vector<double> product(static_cast<std::size_t>(n));
  auto residual = [&](const double* x, const double* b, double* r) {
    apply(x, product.data());
    for(AMG::Index i = 0; i < n; ++i)
      r[i] = b[i] - product[static_cast<std::size_t>(i)];
  };
  auto identity = [n](const double* in, double* out) { std::copy(in, in + n, out); };
  const std::vector<double> b(static_cast<std::size_t>(n), 1.);
  const double b_norm = std::sqrt(double(n));
  AMG::Krylov_workspace workspace;

  std::vector<double> x(static_cast<std::size_t>(n), 0.);
  const AMG::Krylov_result free_run =
      AMG::gmres(apply, residual, n, b.data(), x.data(), identity, 1e-10 * b_norm, b_norm, 1000, 30, workspace);
  EXPECT_TRUE(free_run.converged);
  EXPECT_FALSE(free_run.stopped);
  ASSERT_GT(free_run.iterations, 7);

  int asked = 0;
  std::fill(x.begin(), x.end(), 0.);
  const AMG::Krylov_result stopped = AMG::gmres(apply, residual, n, b.data(), x.data(), identity, 1e-10 * b_norm,
                                                b_norm, 1000, 30, workspace, [&]() { return ++asked >= 7; });
  EXPECT_TRUE(stopped.stopped);
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(stopped.iterations, 7);
  EXPECT_EQ(asked, 7);
  // The iterate reached is kept: its residual is below the start's (x = 0, relative residual 1).
  std::vector<double> r(static_cast<std::size_t>(n));
  residual(x.data(), b.data(), r.data());
  double r_norm = 0.;
  for(double value : r)
    r_norm += value * value;
  EXPECT_LT(std::sqrt(r_norm), 0.9 * b_norm);
  EXPECT_NEAR(stopped.relative_residual, std::sqrt(r_norm) / b_norm, 1e-12);
}

// An open disk: the closed mesh minus the faces around its first vertex, built by hand.
Mesh open_disk(const Mesh& closed)
{
  const Vertex center = *closed.vertices().begin();
  Mesh disk;
  std::vector<Vertex> copy(closed.number_of_vertices());
  for(Vertex v : closed.vertices())
    if(v != center)
      copy[v] = disk.add_vertex(closed.point(v));
  for(Mesh::Face_index f : closed.faces())
  {
    std::vector<Vertex> corners;
    for(Vertex v : CGAL::vertices_around_face(closed.halfedge(f), closed))
      corners.push_back(v);
    if(std::find(corners.begin(), corners.end(), center) == corners.end())
      disk.add_face(copy[corners[0]], copy[corners[1]], copy[corners[2]]);
  }
  return disk;
}

template <class SolverTraits>
std::vector<Point_2> parameterize_with(Mesh& disk, const SolverTraits& solver)
{
  namespace SMP = CGAL::Surface_mesh_parameterization;
  typedef SMP::Circular_border_arc_length_parameterizer_3<Mesh> Border;
  typedef SMP::Barycentric_mapping_parameterizer_3<Mesh, Border, SolverTraits> Parameterizer;
  const Mesh::Halfedge_index border = CGAL::Polygon_mesh_processing::longest_border(disk).first;
  auto uv_map = disk.add_property_map<Vertex, Point_2>("v:uv").first;
  const SMP::Error_code status = SMP::parameterize(disk, Parameterizer(Border(), solver), border, uv_map);
  EXPECT_EQ(status, SMP::OK);
  std::vector<Point_2> uv;
  for(Vertex v : disk.vertices())
    uv.push_back(uv_map[v]);
  disk.remove_property_map(uv_map);
  return uv;
}

TEST(Fixed_border_parameterizer, MatchesDefaultSolverAndSetsUpOnce)
{
  Mesh disk = open_disk(read_mesh("c3d_fandisk.off"));
  ASSERT_FALSE(disk.is_empty());

  AMG_traits solver(amg_only());
  const std::vector<Point_2> amg_uv = parameterize_with(disk, solver);
  // Copies share the state: the parameterizer's copy reports through ours.
  EXPECT_EQ(solver.statistics().number_of_setups, 1u);
  EXPECT_EQ(solver.statistics().number_of_solves, 2u);
  EXPECT_FALSE(solver.statistics().direct_solver);
  EXPECT_TRUE(solver.statistics().symmetric) << "identity border rows must be eliminated";
  EXPECT_LE(solver.statistics().relative_residual, 1e-10);

  typedef CGAL::Eigen_solver_traits<
      Eigen::BiCGSTAB<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::IncompleteLUT<double>>>
      Default_traits;
  const std::vector<Point_2> default_uv = parameterize_with(disk, Default_traits());
  ASSERT_EQ(amg_uv.size(), default_uv.size());
  double largest_difference = 0., largest_coordinate = 0.;
  for(std::size_t k = 0; k < amg_uv.size(); ++k)
  {
    largest_difference = (std::max)(
        {largest_difference, std::abs(amg_uv[k].x() - default_uv[k].x()), std::abs(amg_uv[k].y() - default_uv[k].y())});
    largest_coordinate = (std::max)({largest_coordinate, std::abs(default_uv[k].x()), std::abs(default_uv[k].y())});
  }
  EXPECT_LE(largest_difference / largest_coordinate, 1e-8);
}

TEST(Factor_and_solve, ReusesTheSetupAndSharesItWithCopies)
{
  const Disk_system system = build_disk_system(read_mesh("c3d_fandisk.off"), Weighting::COTANGENT, false);
  AMG_traits solver(amg_only());
  double D = 0.;
  ASSERT_TRUE(solver.factor(AMG_traits::Matrix(system.A), D));
  EXPECT_EQ(D, 1.);
  AMG_traits copy = solver;
  AMG_traits::Vector Xu, Xv;
  ASSERT_TRUE(solver.linear_solver(to_vector(system.bu), Xu));
  ASSERT_TRUE(copy.linear_solver(to_vector(system.bv), Xv));
  EXPECT_EQ(solver.statistics().number_of_setups, 1u);
  EXPECT_EQ(solver.statistics().number_of_solves, 2u);
  EXPECT_LE(relative_residual(system.A, system.bu, Xu), 1e-10);
  EXPECT_LE(relative_residual(system.A, system.bv, Xv), 1e-10);

  // Changed values: a new setup.
  Sparse_matrix scaled = 2. * system.A;
  ASSERT_TRUE(solver.factor(AMG_traits::Matrix(scaled), D));
  EXPECT_EQ(solver.statistics().number_of_setups, 2u);
  ASSERT_TRUE(solver.linear_solver(to_vector(system.bu), Xu));
  EXPECT_LE(relative_residual(scaled, system.bu, Xu), 1e-10);
}

// The setup is kept while the matrix and the setup parameters (the hierarchy's, the symmetry test, the direct
// solver thresholds) stay the same; a solve parameter does not count. independent_copy() keeps the parameters and
// shares no setup.
TEST(Factor_and_solve, SetupParametersTriggerANewSetup)
{
  const Disk_system system = build_disk_system(read_mesh("c3d_fandisk.off"), Weighting::COTANGENT, false);
  AMG_traits solver(amg_only());
  double D = 0.;
  ASSERT_TRUE(solver.factor(AMG_traits::Matrix(system.A), D));
  solver.parameters().tolerance = 1e-8;
  solver.parameters().max_iterations = 100;
  ASSERT_TRUE(solver.factor(AMG_traits::Matrix(system.A), D));
  EXPECT_EQ(solver.statistics().number_of_setups, 1u);

  std::size_t setups = 1;
  const auto expect_new_setup = [&](const char* what) {
    ASSERT_TRUE(solver.factor(AMG_traits::Matrix(system.A), D)) << what;
    EXPECT_EQ(solver.statistics().number_of_setups, ++setups) << what;
  };
  solver.parameters().hierarchy.strength_threshold = 0.5;
  expect_new_setup("strength_threshold");
  solver.parameters().hierarchy.post_smoothing_sweeps = 2;
  expect_new_setup("post_smoothing_sweeps");
  solver.parameters().symmetry_tolerance = 1e-10;
  expect_new_setup("symmetry_tolerance");
  solver.parameters().direct_solver_threshold = 1;
  expect_new_setup("direct_solver_threshold");

  AMG_traits copy = CGAL::Spherical_parameterization::independent_copy(solver);
  EXPECT_TRUE(copy.parameters().hierarchy == solver.parameters().hierarchy);
  EXPECT_EQ(copy.parameters().tolerance, 1e-8);
  EXPECT_EQ(copy.statistics().number_of_setups, 0u);
  ASSERT_TRUE(copy.factor(AMG_traits::Matrix(system.A), D));
  EXPECT_EQ(copy.statistics().number_of_setups, 1u);
  EXPECT_EQ(solver.statistics().number_of_setups, setups);
}

TEST(Direct_solver_threshold, SmallSystemsGoToTheDirectSolver)
{
  const Mesh mesh = read_mesh("c3d_fandisk.off"); // 6467 interior vertices
  for(Weighting weighting : {Weighting::COTANGENT, Weighting::MEAN_VALUE})
  {
    const Disk_system system = build_disk_system(mesh, weighting, true);
    for(bool default_thresholds : {true, false})
    {
      AMG_traits::Parameters parameters;
      if(!default_thresholds)
        parameters.direct_solver_threshold_non_symmetric = parameters.direct_solver_threshold;
      AMG_traits solver(parameters);
      AMG_traits::Vector X;
      double D;
      ASSERT_TRUE(solver.linear_solver(AMG_traits::Matrix(system.A), to_vector(system.bu), X, D));
      // By default, only the symmetric system of this size goes to the direct solver (SparseLU is slow).
      EXPECT_EQ(solver.statistics().direct_solver, weighting == Weighting::COTANGENT || !default_thresholds);
      EXPECT_LE(relative_residual(system.A, system.bu, X), 1e-10);
      EXPECT_LE(relative_difference(X, solve_with_sparse_lu(system.A, system.bu)), 1e-8);
    }
  }
}

// Pure Neumann 5-point Laplacian: singular, and a right-hand side of ones is not in its range.
Sparse_matrix neumann_grid(int side)
{
  std::vector<Triplet> triplets;
  for(int y = 0; y < side; ++y)
    for(int x = 0; x < side; ++x)
    {
      const int i = y * side + x;
      double degree = 0.;
      auto add = [&](int j) {
        triplets.emplace_back(i, j, -1.);
        degree += 1.;
      };
      if(x > 0)
        add(i - 1);
      if(x + 1 < side)
        add(i + 1);
      if(y > 0)
        add(i - side);
      if(y + 1 < side)
        add(i + side);
      triplets.emplace_back(i, i, degree);
    }
  Sparse_matrix A(side * side, side * side);
  A.setFromTriplets(triplets.begin(), triplets.end());
  return A;
}

TEST(Bad_input, SingularAndNonFiniteSystemsFailQuickly)
{
  const auto start = std::chrono::steady_clock::now();
  for(std::size_t threshold : {std::size_t(0), std::size_t(1) << 40})
  {
    AMG_traits::Parameters parameters;
    parameters.direct_solver_threshold = threshold;
    parameters.direct_solver_threshold_non_symmetric = threshold;
    AMG_traits::Vector X;
    double D;
    {
      const Sparse_matrix A = neumann_grid(100);
      EXPECT_FALSE(AMG_traits(parameters)
                       .linear_solver(AMG_traits::Matrix(A), to_vector(Eigen::VectorXd::Ones(A.rows())), X, D));
    }
    {
      Sparse_matrix A = poisson_grid(50);
      for(Sparse_matrix::InnerIterator it(A, 7); it; ++it)
        it.valueRef() = 0.; // zero column 7 and, by symmetry of the pattern, the 7th diagonal entry
      A.prune(0.);
      EXPECT_FALSE(AMG_traits(parameters)
                       .linear_solver(AMG_traits::Matrix(A), to_vector(Eigen::VectorXd::Ones(A.rows())), X, D));
    }
    {
      Sparse_matrix A = poisson_grid(50);
      A.coeffRef(10, 11) = std::numeric_limits<double>::quiet_NaN();
      AMG_traits solver(parameters);
      EXPECT_FALSE(solver.linear_solver(AMG_traits::Matrix(A), to_vector(Eigen::VectorXd::Ones(A.rows())), X, D));
      EXPECT_FALSE(solver.factor(AMG_traits::Matrix(A), D));
    }
    {
      const Sparse_matrix A = poisson_grid(50);
      Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
      b[3] = std::numeric_limits<double>::infinity();
      EXPECT_FALSE(AMG_traits(parameters).linear_solver(AMG_traits::Matrix(A), to_vector(b), X, D));
    }
  }
  {
    AMG_traits solver;
    AMG_traits::Vector X;
    EXPECT_FALSE(solver.linear_solver(to_vector(Eigen::VectorXd::Ones(4)), X)) << "no factor() before";
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.);
}

TEST(Negative_diagonal, RowsAreNegated)
{
  const Sparse_matrix A = poisson_grid(60);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1., 2.);
  // Negate every third row: a non-symmetric system with negative diagonal entries, same solution.
  Eigen::VectorXd sign = Eigen::VectorXd::Ones(A.rows());
  for(Eigen::Index i = 0; i < A.rows(); i += 3)
    sign[i] = -1.;
  const Sparse_matrix signed_A = sign.asDiagonal() * A;
  const Eigen::VectorXd signed_b = sign.asDiagonal() * b;
  AMG_traits solver(amg_only());
  AMG_traits::Vector X;
  double D;
  ASSERT_TRUE(solver.linear_solver(AMG_traits::Matrix(signed_A), to_vector(signed_b), X, D));
  EXPECT_TRUE(solver.statistics().symmetric) << "negating the rows back restores the symmetry";
  EXPECT_LE(relative_residual(signed_A, signed_b, X), 1e-10);
  EXPECT_LE(relative_difference(X, solve_with_sparse_lu(A, b)), 1e-8);
}

TEST(Zero_right_hand_side, GivesZero)
{
  const Sparse_matrix A = poisson_grid(40);
  AMG_traits solver(amg_only());
  AMG_traits::Vector X;
  double D;
  ASSERT_TRUE(solver.linear_solver(AMG_traits::Matrix(A), to_vector(Eigen::VectorXd::Zero(A.rows())), X, D));
  EXPECT_EQ(X.cwiseAbs().maxCoeff(), 0.);
}

} // namespace
