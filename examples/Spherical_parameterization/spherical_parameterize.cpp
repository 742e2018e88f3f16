// Command line: map a closed genus-0 triangle mesh onto the unit sphere, bijectively.
//
//   spherical_parameterize input.(off|off.gz|obj|ply|stl) [-o sphere.off] [options]
//
// The output keeps the input's vertex order and face list; coordinates are written with 17 significant digits.

#include <CGAL/Spherical_parameterization/IO/read_polygon_soup.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

enum Exit_code { EXIT_OK = 0, EXIT_NOT_SOLVED = 1, EXIT_BAD_INPUT = 2, EXIT_IO = 3, EXIT_USAGE = 4 };

void print_usage(std::ostream& out)
{
  out << "Usage: spherical_parameterize INPUT [-o OUTPUT] [options]\n"
         "Maps a closed, connected, genus-0 triangle mesh onto the unit sphere, bijectively\n"
         "(Saba, Yavneh, Gotsman, Sheffer: Practical Spherical Embedding of Manifold Triangle Meshes).\n\n"
         "  INPUT                 a mesh: .off (also gzip-compressed, .off.gz), .obj, .ply, .stl\n"
         "  -o, --output FILE     where to write the sphere mesh (.off or .ply), same vertex order and faces\n"
         "                        (default: INPUT's name with _sphere.off)\n"
         "  -w, --weights W       uniform (default, Tutte), cotangent (conformal), mean_value\n"
         "  -t, --tolerance T     stop when the paper's residual Res < T (default 1e-6)\n"
         "  -s, --solver S        stage 3: global (Newton on all vertices, default) or local (the paper's)\n"
         "      --disk-solver D   linear solver of the disk stage: amg (default) or sparse_lu (Eigen)\n"
         "      --max-seconds S   time budget of the iterations (default: none)\n"
         "      --seed N          METIS seed (default 0); equal seeds give identical output\n"
         "      --no-backtracking let moves fold triangles (the paper's plain iterations; for experiments)\n"
         "  -q, --quiet           print nothing but errors\n"
         "  -h, --help            this text\n\n"
         "Exit status: 0 success (converged and certified bijective), 1 not converged or not bijective,\n"
         "2 invalid mesh, 3 file error, 4 usage error.\n";
}

bool parse_weights(const std::string& name, SP::Weighting& weighting)
{
  if(name == "uniform" || name == "tutte") weighting = SP::Weighting::UNIFORM;
  else if(name == "cotangent" || name == "conformal") weighting = SP::Weighting::COTANGENT;
  else if(name == "mean_value" || name == "mean-value" || name == "mvc") weighting = SP::Weighting::MEAN_VALUE;
  else return false;
  return true;
}

std::string default_output(std::string input)
{
  if(input.size() > 3 && input.compare(input.size() - 3, 3, ".gz") == 0) input.resize(input.size() - 3);  // mesh.off.gz
  const std::size_t slash = input.find_last_of('/');
  const std::size_t dot = input.find_last_of('.');
  const std::string stem = (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ? input.substr(0, dot) : input;
  return stem + "_sphere.off";
}

bool ends_with(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The output's folder must exist and take a new file, and the output itself must not be a folder.
bool can_write_next_to(const std::string& path, std::string& error)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  struct stat info;
  if(::stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
    error = "cannot write '" + path + "': the folder '" + folder + "' does not exist";
    return false;
  }
  if(::access(folder.c_str(), W_OK) != 0) {
    error = "cannot write '" + path + "': the folder '" + folder + "' is not writable";
    return false;
  }
  if(::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
    error = "cannot write '" + path + "': it is a folder";
    return false;
  }
  return true;
}

// Writes to a temporary file next to `path`, then renames it: a failure never leaves a half-written file.
bool write_sphere(const std::string& path, const std::vector<Point>& sphere, const std::vector<std::vector<std::size_t>>& faces,
                  std::string& error)
{
  const std::string temporary = path + ".partial." + std::to_string(::getpid());
  {
    std::ofstream out(temporary);
    if(!out) { error = "cannot open '" + temporary + "' for writing"; return false; }
    out << std::setprecision(17);
    if(ends_with(path, ".ply")) {
      out << "ply\nformat ascii 1.0\nelement vertex " << sphere.size() << "\nproperty double x\nproperty double y\n"
          << "property double z\nelement face " << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    } else {
      out << "OFF\n" << sphere.size() << ' ' << faces.size() << " 0\n";
    }
    for(const Point& p : sphere) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for(const auto& f : faces) {
      out << f.size();
      for(std::size_t i : f) out << ' ' << i;
      out << '\n';
    }
    out.flush();
    if(!out) { error = "writing '" + temporary + "' failed"; std::remove(temporary.c_str()); return false; }
  }
  if(std::rename(temporary.c_str(), path.c_str()) != 0) {
    error = "cannot move '" + temporary + "' to '" + path + "'";
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

} // namespace

int main(int argc, char** argv)
{
  std::string input, output;
  SP::Weighting weighting = SP::Weighting::UNIFORM;
  double tolerance = 1e-6, max_seconds = -1.;
  int seed = 0;
  bool quiet = false, backtracking = true;
  SP::Nonlinear_solver solver = SP::Nonlinear_solver::GLOBAL_NEWTON;
  bool sparse_lu = false;

  for(int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&](const char* what) -> std::string {
      if(a + 1 >= argc) { std::cerr << "error: " << arg << " needs " << what << "\n"; std::exit(EXIT_USAGE); }
      return argv[++a];
    };
    auto number = [&](const char* what) -> double {
      const std::string text = value(what);
      char* end = nullptr;
      const double x = std::strtod(text.c_str(), &end);
      if(end == text.c_str() || *end != '\0') { std::cerr << "error: " << arg << " expects " << what << ", got '" << text << "'\n"; std::exit(EXIT_USAGE); }
      return x;
    };
    if(arg == "-h" || arg == "--help") { print_usage(std::cout); return EXIT_OK; }
    else if(arg == "-o" || arg == "--output") output = value("a file name");
    else if(arg == "-w" || arg == "--weights") {
      const std::string name = value("uniform, cotangent or mean_value");
      if(!parse_weights(name, weighting)) { std::cerr << "error: unknown weights '" << name << "' (uniform, cotangent, mean_value)\n"; return EXIT_USAGE; }
    }
    else if(arg == "-t" || arg == "--tolerance") {
      tolerance = number("a positive number");
      if(!(tolerance > 0.)) { std::cerr << "error: the tolerance must be positive\n"; return EXIT_USAGE; }
    }
    else if(arg == "--max-seconds") max_seconds = number("a number of seconds");
    else if(arg == "--seed") seed = static_cast<int>(number("an integer"));
    else if(arg == "-q" || arg == "--quiet") quiet = true;
    else if(arg == "--no-backtracking") backtracking = false;
    else if(arg == "--disk-solver") {
      const std::string name = value("amg or sparse_lu");
      if(name == "amg") sparse_lu = false;
      else if(name == "sparse_lu") sparse_lu = true;
      else { std::cerr << "error: unknown disk solver '" << name << "' (amg, sparse_lu)\n"; return EXIT_USAGE; }
    }
    else if(arg == "-s" || arg == "--solver") {
      const std::string name = value("global or local");
      if(name == "global") solver = SP::Nonlinear_solver::GLOBAL_NEWTON;
      else if(name == "local") solver = SP::Nonlinear_solver::LOCAL_NEWTON;
      else { std::cerr << "error: unknown solver '" << name << "' (global, local)\n"; return EXIT_USAGE; }
    }
    else if(!arg.empty() && arg[0] == '-') { std::cerr << "error: unknown option '" << arg << "' (see --help)\n"; return EXIT_USAGE; }
    else if(input.empty()) input = arg;
    else { std::cerr << "error: more than one input file ('" << input << "', '" << arg << "')\n"; return EXIT_USAGE; }
  }
  if(input.empty()) { print_usage(std::cerr); return EXIT_USAGE; }
  if(output.empty()) output = default_output(input);

  // An output that cannot be written is found before the work, not after it.
  std::string output_error;
  if(!can_write_next_to(output, output_error)) { std::cerr << "error: " << output_error << "\n"; return EXIT_IO; }

  // Read as a polygon soup first: a soup can hold what a halfedge structure refuses, so the error is precise.
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  const SP::IO::File_read read = SP::IO::read_polygon_soup(input, points, faces);
  if(!read) {
    std::cerr << "error: " << read.message << " [" << SP::IO::get_file_status_name(read.status) << "]\n";
    return EXIT_IO;
  }
  const SP::Input_check check = SP::check_polygon_soup(points, faces);
  if(!check) {
    std::cerr << "error: " << input << ": " << check.message << " [" << SP::get_error_name(check.status) << "]\n";
    return EXIT_BAD_INPUT;
  }
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);

  auto sphere_map = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", Point(0, 0, 0)).first;
  const auto options =
      SP::parameters::combine(SP::parameters::weighting(weighting), SP::parameters::tolerance(tolerance),
                              SP::parameters::max_seconds(max_seconds), SP::parameters::metis_seed(seed),
                              SP::parameters::preserve_bijectivity(backtracking), SP::parameters::nonlinear_solver(solver),
                              CGAL::parameters::verbose(!quiet));
  const SP::Result result =
      sparse_lu ? SP::spherical_parameterize(mesh, sphere_map, SP::parameters::combine(options, CGAL::parameters::sparse_linear_solver(SP::Sparse_LU_disk_solver_traits())))
                : SP::spherical_parameterize(mesh, sphere_map, options);

  if(!quiet) {
    std::cout << "mesh:                   " << input << " (" << result.number_of_vertices << " vertices, " << result.number_of_faces << " faces)\n"
              << "status:                 " << SP::get_error_name(result.status) << ": " << result.message << "\n"
              << "Res (paper):            " << result.residual << "\n"
              << "max tangential residual " << result.max_tangential_residual << "\n"
              << "flipped faces (exact):  " << result.flipped_faces << "\n"
              << "total signed area:      " << std::setprecision(12) << result.total_signed_area << " (4 pi = 12.5663706144)\n"
              << std::setprecision(4)
              << "initial guess:          " << result.initial_guess.seconds << " s (Res " << result.initial_guess.residual
              << ", " << result.initial_flipped_faces << " non-positive faces"
              << (result.uniform_initial_guess_fallback ? ", uniform-weight fallback" : "") << ")\n"
              << "gauss-seidel:           " << result.gauss_seidel.seconds << " s, " << result.gauss_seidel.iterations << " sweeps\n"
              << "newton:                 " << result.newton.seconds << " s, " << result.newton.iterations << " sweeps\n"
              << "moves not taken:        " << result.rejected_moves << "\n"
              << "total:                  " << result.total_seconds << " s\n";
  }
  if(result.number_of_vertices == 0 || result.residual < 0.) {
    std::cerr << "error: " << result.message << " [" << SP::get_error_name(result.status) << "]\n";
    return result.status == SP::Error_code::OK ? EXIT_NOT_SOLVED : EXIT_BAD_INPUT;
  }

  std::vector<Point> sphere(points.size());
  for(Mesh::Vertex_index v : mesh.vertices()) sphere[static_cast<std::size_t>(v)] = sphere_map[v];
  std::string error;
  if(!write_sphere(output, sphere, faces, error)) { std::cerr << "error: " << error << "\n"; return EXIT_IO; }
  if(!quiet) std::cout << "written:                " << output << "\n";
  if(result.status != SP::Error_code::OK) {
    std::cerr << "error: " << result.message << " [" << SP::get_error_name(result.status) << "]\n";
    return EXIT_NOT_SOLVED;
  }
  return EXIT_OK;
}
