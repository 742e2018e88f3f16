// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// The Python module `cgal_spherical_parameterization`: the package's map, certificate, distortion measure and
// surface readers on NumPy arrays.
//
//   import cgal_spherical_parameterization as sp
//   X, info = sp.map_to_sphere(V, F, weights="uniform", tolerance=1e-6)
//
// The work runs without the GIL; the progress callable (if any) and Ctrl-C are served from the progress reports,
// at most ten times a second. Invalid input raises ValueError whose message starts with the error code.

#include <CGAL/Spherical_parameterization/IO/brain_surfaces.h>
#include <CGAL/Spherical_parameterization/IO/read_polygon_soup.h>
#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/measure_spherical_distortion.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace py = pybind11;
namespace SP = CGAL::Spherical_parameterization;
using Point = CGAL::Epick::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

using Vertices = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Faces = py::array_t<long long, py::array::c_style | py::array::forcecast>;

// (n,3) and (m,3) arrays as a polygon soup; shapes and indices checked here, the rest by check_polygon_soup().
void read_arrays(const Vertices& V, const Faces& F, std::vector<Point>& points,
                 std::vector<std::vector<std::size_t>>& faces)
{
  if(V.ndim() != 2 || V.shape(1) != 3)
    throw py::value_error("INVALID_ARGUMENT: V must be an (n, 3) array of coordinates");
  if(F.ndim() != 2 || F.shape(1) != 3)
    throw py::value_error("INVALID_ARGUMENT: F must be an (m, 3) array of vertex indices");
  const auto v = V.unchecked<2>();
  const auto f = F.unchecked<2>();
  points.reserve(static_cast<std::size_t>(v.shape(0)));
  for(py::ssize_t i = 0; i < v.shape(0); ++i)
    points.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  faces.reserve(static_cast<std::size_t>(f.shape(0)));
  for(py::ssize_t i = 0; i < f.shape(0); ++i)
  {
    std::vector<std::size_t> face;
    for(int k = 0; k < 3; ++k)
    {
      const long long index = f(i, k);
      if(index < 0 || index >= v.shape(0))
        throw py::value_error("INVALID_ARGUMENT: face " + std::to_string(i) + " refers to vertex "
                              + std::to_string(index) + ", of " + std::to_string(v.shape(0)));
      face.push_back(static_cast<std::size_t>(index));
    }
    faces.push_back(std::move(face));
  }
}

// The mesh of (V, F) after the package's input checks (closed, connected, manifold, oriented, genus 0, ...), or
// only after the check that (V, F) is a polygon mesh (`full_check` false: a map to certify may be degenerate).
Mesh checked_mesh(const Vertices& V, const Faces& F, bool full_check = true)
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  read_arrays(V, F, points, faces);
  if(full_check)
  {
    const SP::Input_check check = SP::check_polygon_soup(points, faces);
    if(!check)
      throw py::value_error(std::string(SP::get_error_name(check.status)) + ": " + check.message);
  }
  else if(!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(faces))
  {
    throw py::value_error("INVALID_ARGUMENT: (X, F) is not an oriented polygon mesh");
  }
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

py::dict stage_dict(const SP::Stage_statistics& s)
{
  py::dict d;
  d["seconds"] = s.seconds;
  d["iterations"] = s.iterations;
  d["linear_iterations"] = s.linear_iterations;
  d["residual"] = s.residual >= 0. ? py::object(py::float_(s.residual)) : py::object(py::none());
  return d;
}

// The figures of the command line's JSON object, with the same keys.
py::dict result_dict(const SP::Result& r, const std::string& weights, const std::string& criterion, double tolerance)
{
  py::dict d;
  // None where the JSON has null: not computed (negative), or infinite (JSON has no infinity).
  auto number = [](double x) {
    return x >= 0. && std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
  };
  d["status"] = SP::get_error_name(r.status);
  d["success"] = r.status == SP::Error_code::OK;
  d["message"] = r.message;
  d["vertices"] = r.number_of_vertices;
  d["faces"] = r.number_of_faces;
  d["weights"] = weights;
  d["criterion"] = criterion;
  d["tolerance"] = tolerance;
  d["max_imbalance"] = number(r.max_imbalance);
  d["imbalance_percentile_99"] = number(r.imbalance_percentile_99);
  d["unbalanced_vertices"] = r.unbalanced_vertices;
  d["max_stationarity"] = number(r.max_stationarity);
  // Counts the command line gives as null where they do not apply: None here too.
  auto count_if = [](std::size_t n, bool applies) { return applies ? py::object(py::int_(n)) : py::object(py::none()); };
  d["unstationary_vertices"] = count_if(r.unstationary_vertices, r.max_stationarity >= 0.);
  d["vertices_at_rounding_floor"] = r.vertices_at_rounding_floor;
  d["vertices_below_precision"] = r.vertices_below_precision;
  d["regularized_tip_vertices"] = r.regularized_tip_vertices;
  d["held_weight_vertices"] = r.held_weight_vertices;
  d["held_weight_parameter"] = r.held_weight_parameter;
  d["requested_weights_max_imbalance"] = number(r.requested_weights_max_imbalance);
  d["least_distortion_map"] = r.least_distortion_map;
  d["balanced_map_folded"] = r.balanced_map_folded;
  d["least_distortion_from_balanced_map"] = r.least_distortion_from_balanced_map;
  d["replaced_balanced_map_distortion"] = number(r.replaced_balanced_map_distortion);
  d["replaced_balanced_map_angle_error"] = number(r.replaced_balanced_map_angle_error);
  d["distortion_energy"] = number(r.distortion_energy);
  d["max_distortion_stationarity"] = number(r.max_distortion_stationarity);
  d["least_distortion_steps"] = count_if(r.least_distortion_steps, r.least_distortion_map);
  d["distortion_vertices_at_rounding_floor"] = count_if(r.distortion_vertices_at_rounding_floor, r.least_distortion_map);
  d["multilevel_fallback"] = r.multilevel_fallback;
  d["partition_retries"] = r.partition_retries;
  d["partition_seed"] = r.partition_seed;
  d["residual"] = number(r.residual);
  d["max_tangential_residual"] = number(r.max_tangential_residual);
  d["flipped_faces"] = r.flipped_faces;
  d["total_signed_area"] = r.total_signed_area;
  d["bijective"] = r.bijective;
  d["initial_flipped_faces"] = r.initial_flipped_faces;
  d["uniform_initial_guess_fallback"] = r.uniform_initial_guess_fallback;
  d["admissible_weights"] = r.admissible_weights;
  d["raised_weights"] = r.raised_weights;
  d["clamped_weights"] = r.clamped_weights;
  d["rejected_moves"] = r.rejected_moves;
  d["separator_size"] = r.separator_size;
  d["cut_loop_length"] = r.cut_loop_length;
  py::dict stages;
  stages["initial_guess"] = stage_dict(r.initial_guess);
  stages["gauss_seidel"] = stage_dict(r.gauss_seidel);
  stages["newton"] = stage_dict(r.newton);
  d["stages"] = stages;
  py::list levels;
  for(const SP::Level_statistics& level : r.levels)
  {
    py::dict l;
    l["vertices"] = level.vertices;
    l["newton_steps"] = level.newton_steps;
    l["linear_iterations"] = level.linear_iterations;
    l["seconds"] = level.seconds;
    levels.append(l);
  }
  d["levels"] = levels;
  d["seconds"] = r.total_seconds;
  return d;
}

py::tuple map_to_sphere(const Vertices& V, const Faces& F, const std::string& weights, double tolerance,
                        const std::string& criterion, py::object max_seconds, bool admissible_weights,
                        py::object progress, bool hold_weights, py::object least_distortion)
{
  SP::Weighting weighting;
  if(weights == "uniform")
    weighting = SP::Weighting::UNIFORM;
  else if(weights == "cotangent")
    weighting = SP::Weighting::COTANGENT;
  else if(weights == "mean_value")
    weighting = SP::Weighting::MEAN_VALUE;
  else
    throw py::value_error("INVALID_ARGUMENT: weights must be \"uniform\", \"cotangent\" or \"mean_value\", not \""
                          + weights + "\"");
  if(criterion != "imbalance" && criterion != "paper")
    throw py::value_error("INVALID_ARGUMENT: criterion must be \"imbalance\" or \"paper\", not \"" + criterion + "\"");
  if(!(tolerance > 0.))
    throw py::value_error("INVALID_ARGUMENT: tolerance must be positive");
  const double budget = max_seconds.is_none() ? -1. : max_seconds.cast<double>();
  // None: the library's default (on for cotangent and mean-value weights not made admissible).
  const bool minimize_distortion = least_distortion.is_none()
                                       ? SP::least_distortion_by_default(weighting, admissible_weights)
                                       : least_distortion.cast<bool>();
  const Mesh mesh = checked_mesh(V, F);

  // Called without the GIL: takes it at most ten times a second, for the user's callable and for Ctrl-C.
  bool interrupted = false;
  std::string callback_error;
  auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  auto report = [&](const SP::Progress& p) {
    const auto now = std::chrono::steady_clock::now();
    if(now - last < std::chrono::milliseconds(100))
      return true;
    last = now;
    py::gil_scoped_acquire gil;
    if(PyErr_CheckSignals() != 0)
    {
      interrupted = true;
      return false;
    }
    if(progress.is_none())
      return true;
    try
    {
      py::object answer = progress(std::string(p.stage), p.iteration, p.residual, p.non_positive_faces, p.seconds);
      return answer.is_none() || answer.cast<bool>();
    }
    catch(py::error_already_set& e)
    {
      callback_error = e.what();
      return false;
    }
  };

  std::vector<Point> sphere_points(num_vertices(mesh));
  auto sphere = boost::make_iterator_property_map(sphere_points.begin(), get(CGAL::vertex_index, mesh));
  SP::Result result;
  SP::Spherical_distortion d;
  {
    py::gil_scoped_release no_gil;
    result = SP::spherical_parameterize(
        mesh, sphere,
        SP::parameters::combine(
            SP::parameters::weighting(weighting), SP::parameters::tolerance(tolerance),
            SP::parameters::max_seconds(budget), SP::parameters::admissible_weights(admissible_weights),
            SP::parameters::hold_weights(hold_weights), SP::parameters::least_distortion(minimize_distortion),
            SP::parameters::progress_callback(report),
            SP::parameters::convergence_test(criterion == "paper" ? SP::Convergence_test::PAPER_RESIDUAL
                                                                  : SP::Convergence_test::IMBALANCE)));
    // The map's shape against the mesh's, as in the command line's JSON.
    if(result.residual >= 0.)
      d = SP::measure_spherical_distortion(mesh, sphere);
  }
  if(interrupted)
    throw py::error_already_set(); // KeyboardInterrupt, set by PyErr_CheckSignals()
  if(!callback_error.empty())
    throw std::runtime_error("the progress callable raised: " + callback_error);
  if(result.residual < 0.)
    throw py::value_error(std::string(SP::get_error_name(result.status)) + ": " + result.message);
  py::array_t<double> X({static_cast<py::ssize_t>(sphere_points.size()), py::ssize_t(3)});
  auto x = X.mutable_unchecked<2>();
  for(std::size_t i = 0; i < sphere_points.size(); ++i)
  {
    x(static_cast<py::ssize_t>(i), 0) = sphere_points[i].x();
    x(static_cast<py::ssize_t>(i), 1) = sphere_points[i].y();
    x(static_cast<py::ssize_t>(i), 2) = sphere_points[i].z();
  }
  py::dict info = result_dict(result, weights, criterion, tolerance);
  py::dict distortion;
  distortion["mean_angle_error_degrees"] = d.mean_angle_error_degrees;
  distortion["max_angle_error_degrees"] = d.max_angle_error_degrees;
  distortion["log_area_ratio_stddev"] = d.log_area_ratio_stddev;
  info["distortion"] = distortion;
  return py::make_tuple(X, info);
}

py::dict certify(const Vertices& X, const Faces& F)
{
  const Mesh mesh = checked_mesh(X, F, false); // the positions are the map: its flips are for the certificate to count
  std::vector<Point> points(mesh.points().begin(), mesh.points().end());
  const SP::Sphere_map_certificate c =
      SP::certify_sphere_map(mesh, boost::make_iterator_property_map(points.begin(), get(CGAL::vertex_index, mesh)));
  py::dict d;
  d["bijective"] = c.bijective;
  d["flipped_faces"] = c.flipped_faces;
  d["total_signed_area"] = c.total_signed_area;
  d["faces"] = c.number_of_faces;
  return d;
}

py::dict measure_distortion(const Vertices& V, const Vertices& X, const Faces& F)
{
  const Mesh mesh = checked_mesh(V, F);
  if(X.ndim() != 2 || X.shape(0) != V.shape(0) || X.shape(1) != 3)
    throw py::value_error("INVALID_ARGUMENT: X must have V's shape");
  const auto x = X.unchecked<2>();
  std::vector<Point> sphere;
  for(py::ssize_t i = 0; i < x.shape(0); ++i)
    sphere.emplace_back(x(i, 0), x(i, 1), x(i, 2));
  const SP::Spherical_distortion d = SP::measure_spherical_distortion(
      mesh, boost::make_iterator_property_map(sphere.begin(), get(CGAL::vertex_index, mesh)));
  py::dict out;
  out["mean_angle_error_degrees"] = d.mean_angle_error_degrees;
  out["max_angle_error_degrees"] = d.max_angle_error_degrees;
  out["log_area_ratio_stddev"] = d.log_area_ratio_stddev;
  return out;
}

// Any format the command line reads: OFF, OBJ, PLY, STL, FreeSurfer (by its contents), GIfTI (.gii).
py::tuple read_surface(const std::string& path)
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  SP::IO::File_read read;
  std::string head;
  {
    std::ifstream in(path, std::ios::binary);
    char magic[3] = {0, 0, 0};
    in.read(magic, 3);
    head.assign(magic, static_cast<std::size_t>(in.gcount()));
  }
  const bool gifti = path.size() >= 4 && path.compare(path.size() - 4, 4, ".gii") == 0;
  if(gifti)
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
    read = SP::IO::read_GIfTI_surface(path, points, faces);
#else
    throw py::value_error("UNKNOWN_FORMAT: this module was built without the GIFTI library");
#endif
  }
  else if(SP::IO::internal::has_FreeSurfer_magic(head.data(), head.data() + head.size()))
  {
    read = SP::IO::read_FreeSurfer_surface(path, points, faces);
  }
  else
  {
    read = SP::IO::read_polygon_soup(path, points, faces);
  }
  if(!read)
    throw py::value_error(std::string(SP::IO::get_file_status_name(read.status)) + ": " + read.message);
  py::array_t<double> V({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)});
  auto v = V.mutable_unchecked<2>();
  for(std::size_t i = 0; i < points.size(); ++i)
    for(int k = 0; k < 3; ++k)
      v(static_cast<py::ssize_t>(i), k) = points[i][k];
  py::array_t<long long> Fa({static_cast<py::ssize_t>(faces.size()), py::ssize_t(3)});
  auto f = Fa.mutable_unchecked<2>();
  for(std::size_t i = 0; i < faces.size(); ++i)
  {
    if(faces[i].size() != 3)
      throw py::value_error("NOT_TRIANGLE_MESH: face " + std::to_string(i) + " has " + std::to_string(faces[i].size())
                            + " vertices");
    for(int k = 0; k < 3; ++k)
      f(static_cast<py::ssize_t>(i), k) = static_cast<long long>(faces[i][static_cast<std::size_t>(k)]);
  }
  return py::make_tuple(V, Fa);
}

} // namespace

PYBIND11_MODULE(cgal_spherical_parameterization, m)
{
  m.doc() = "Bijective maps of closed genus-0 triangle meshes onto the unit sphere (CGAL Spherical Parameterization).";
  m.def(
      "map_to_sphere", &map_to_sphere, py::arg("V"), py::arg("F"), py::arg("weights") = "uniform",
      py::arg("tolerance") = 1e-6, py::arg("criterion") = "imbalance", py::arg("max_seconds") = py::none(),
      py::arg("admissible_weights") = false, py::arg("progress") = py::none(), py::arg("hold_weights") = false,
      py::arg("least_distortion") = py::none(),
      "Maps the mesh (V: (n,3) float64, F: (m,3) int) onto the unit sphere. Returns (X, info): X (n,3) float64 on the\n"
      "unit sphere in V's vertex order, info a dict with the command line's JSON figures ('status', 'success',\n"
      "'max_imbalance', 'flipped_faces', 'bijective', 'distortion', 'stages', ...). A map that is not converged or\n"
      "not bijective is returned with its status; invalid input raises ValueError('CODE: message'). progress(stage,\n"
      "iteration, residual, non_positive_faces, seconds) is called at most ten times a second; returning False\n"
      "stops the run. Ctrl-C raises KeyboardInterrupt. hold_weights: cotangent weights whose balanced maps from\n"
      "Tutte's weights end before them are held where that path ends (info['held_weight_vertices']; experimental).\n"
      "least_distortion (default None: on for cotangent and mean_value weights unless admissible_weights): where\n"
      "the weights' map ends unconverged, and always for mean-value weights (whose least-squares map is not\n"
      "balanced; their iterations are skipped), the bijective map of least conformal distortion instead\n"
      "(info['least_distortion_map']; info['balanced_map_folded']: the weights' balanced map reached was folded,\n"
      "and the other ways to one were skipped); a balanced map of the weights is followed by the minimization too\n"
      "and replaced where that has less angle error (info['replaced_balanced_map_distortion'] and\n"
      "info['replaced_balanced_map_angle_error']: the balanced map's figures, else None);\n"
      "info['least_distortion_from_balanced_map']: the minimization started from the weights' balanced map\n"
      "(repaired where folded). False: the weights' own map only.");
  m.def("certify", &certify, py::arg("X"), py::arg("F"),
        "Certifies a map onto the sphere with exact predicates: dict(bijective, flipped_faces, total_signed_area, "
        "faces).");
  m.def("measure_distortion", &measure_distortion, py::arg("V"), py::arg("X"), py::arg("F"),
        "Angle and area distortion of the map X of the mesh (V, F): dict(mean_angle_error_degrees,\n"
        "max_angle_error_degrees, log_area_ratio_stddev).");
  m.def("read_surface", &read_surface, py::arg("path"),
        "Reads a triangle mesh (OFF, OBJ, PLY, STL, FreeSurfer surface, GIfTI .gii): returns (V, F).");
}
