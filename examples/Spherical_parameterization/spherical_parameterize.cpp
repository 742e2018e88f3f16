// Copyright (c) 2026 CGAL Spherical Parameterization contributors.
// This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
//
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s)     : CGAL Spherical Parameterization contributors

// Command line: map a closed genus-0 triangle mesh onto the unit sphere, bijectively.
//
//   spherical_parameterize input.(off|off.gz|obj|ply|stl|gii) [-o sphere.off] [options]  (--help for all of them)
//   spherical_parameterize lh.white -o lh.sphere                                        (FreeSurfer surfaces)
//
// The output keeps the input's vertex order and face list; text formats get 17 significant digits, and float32
// formats (FreeSurfer, GIfTI) are certified again as written.
// stdout: the figures (text, or one JSON line with --json); stderr: progress, warnings and errors.

#include <CGAL/Spherical_parameterization/IO/brain_surfaces.h>
#include <CGAL/Spherical_parameterization/IO/read_polygon_soup.h>
#include <CGAL/Spherical_parameterization/certify_sphere_map.h>
#include <CGAL/Spherical_parameterization/check_input.h>
#include <CGAL/Spherical_parameterization/measure_spherical_distortion.h>
#include <CGAL/Spherical_parameterization/spherical_parameterize.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <boost/property_map/property_map.hpp>

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

enum Exit_code
{
  EXIT_OK = 0,
  EXIT_NOT_SOLVED = 1,
  EXIT_BAD_INPUT = 2,
  EXIT_IO = 3,
  EXIT_USAGE = 4
};

const char* const synopsis = "Usage: spherical_parameterize INPUT [-o OUTPUT] [options]\n";

void print_usage(std::ostream& out)
{
  out << synopsis
      << "Maps a closed, connected, genus-0 triangle mesh onto the unit sphere, bijectively\n"
         "(Saba, Yavneh, Gotsman, Sheffer: Practical Spherical Embedding of Manifold Triangle Meshes).\n"
         "Success means certified: every spherical triangle is positively oriented (exact predicate),\n"
         "a generic point of the sphere lies in exactly one of them (the map has degree 1), and every vertex\n"
         "is balanced: its imbalance e_i (distance from the weighted balance point of its neighbours, in\n"
         "units of its own neighbourhood) is at most the tolerance.\n"
         "\n"
         "Input and output:\n"
         "  INPUT                 a mesh: .off (also gzip-compressed, .off.gz), .obj, .ply, .stl, a FreeSurfer\n"
         "                        surface (lh.white, lh.pial, ...: recognized by its contents) or GIfTI .gii\n"
         "  -o, --output FILE     the sphere mesh with the input's vertices in the same order and its faces:\n"
         "                        .off or .ply (17 significant digits), .gii (GIfTI, float32 unless --float64),\n"
         "                        any other name a FreeSurfer surface (float32; lh.sphere). Default: INPUT\n"
         "                        without extension + _sphere.off; for a FreeSurfer input INPUT + .sphere in its\n"
         "                        format, for a GIfTI input INPUT's stem + _sphere.surf.gii\n"
         "      --radius R        write the sphere with radius R (default 1; FreeSurfer's spheres: 100)\n"
         "      --float64         GIfTI output with float64 coordinates\n"
         "  A float32 output is certified again as written: if rounding folded a triangle, the run says so\n"
         "  (JSON \"written\") and exits 1.\n"
         "      --overwrite       map again even if the output already answers this request. Without it, an\n"
         "                        existing output is kept (exit 0, JSON \"skipped\": true) when it records a\n"
         "                        successful run with the same weights, criterion, precision and radius, the\n"
         "                        same --admissible-weights, --hold-weights and --least-distortion, a\n"
         "                        tolerance at least as tight, from this very input, and its coordinates pass\n"
         "                        the certificate as stored; otherwise it is replaced (re-runs of a cohort\n"
         "                        after a killed job redo only what is missing or unfinished)\n"
         "\n"
         "Method:\n"
         "  -w, --weights W       uniform (default; Tutte weights, covered by the theory, most robust),\n"
         "                        cotangent (angle preserving; may be negative: where their balanced map is\n"
         "                        not bijective or not found, the bijective map of least conformal distortion),\n"
         "                        mean_value (angle preserving; not symmetric, no balanced map in general: the\n"
         "                        bijective map of least conformal distortion; see --least-distortion)\n"
         "      --admissible-weights  solve with the closest symmetric positive weights instead (the mean of\n"
         "                        w_ij and w_ji, those below 1% of the local mean raised to it): the theory's\n"
         "                        case, for cotangent and mean_value weights that fail\n"
         "      --hold-weights    cotangent weights whose balanced maps, followed from Tutte's weights, end\n"
         "                        before them: hold the weights where that path ends and go on (the map is\n"
         "                        balanced for the held weights: counted in the output; experimental)\n"
         "      --least-distortion  (default with cotangent and mean_value weights, unless\n"
         "                        --admissible-weights) where the map of the weights given ends unbalanced or\n"
         "                        not bijective (cotangent; mean_value always: its least-squares map is not\n"
         "                        balanced, and its iterations are skipped): return the bijective map of least\n"
         "                        conformal distortion instead, success when that minimum is stationary; a\n"
         "                        balanced map is followed by it too, and replaced where it has less angle\n"
         "                        error (--no-least-distortion for the balanced map of the weights); it\n"
         "                        replaces cotangent weights' slow ways to their balanced map (a retry of the\n"
         "                        levels, the two disks, the cautious Newton) unless --hold-weights is given\n"
         "                        too (not with --criterion paper)\n"
         "      --no-least-distortion  return the weights' own map only (NOT_CONVERGED where it is not\n"
         "                        balanced; mean_value: the least-squares map, stationary or not)\n"
         "  -t, --tolerance T     stop when every imbalance e_i <= T (default 1e-6); mean_value weights, which\n"
         "                        have no exact solution: when their least-squares problem is stationary to T\n"
         "      --gauss-seidel-sweeps N  cap of stage 2, the paper's projected Gauss-Seidel (default: the\n"
         "                        library's, see the manual)\n"
         "      --criterion C     imbalance (default) or paper: stop when the paper's Res < T instead (Res\n"
         "                        shrinks with the mesh size: on large meshes it passes while vertices are\n"
         "                        still far from balanced)\n"
         "  -s, --solver S        stage 3: global (Newton on all vertices at once, default) or local (the paper's)\n"
         "      --disk-solver D   linear solver of the disk stage: amg (default) or sparse_lu (Eigen)\n"
         "      --max-seconds S   time budget of the map (stage 1 included; reading and writing are outside),\n"
         "                        S > 0 (default: none); then the best map so far is written (exit 1)\n"
         "      --seed N          METIS seed, an integer (default 0); the same seed gives the same output\n"
         "      --start S         where the iterations start (global solver; uniform weights from 20,000\n"
         "                        vertices, cotangent and --admissible-weights from 200):\n"
         "                        multilevel (default: a coarser mesh solved first, its map carried back) or\n"
         "                        two_disks (the paper's initial guess on the mesh itself)\n"
         "      --verbose         the library's figures of every stage and level on stderr\n"
         "      --no-backtracking let moves fold triangles (the paper's plain iterations; for experiments)\n"
         "\n"
         "What is printed:\n"
         "  -q, --quiet           nothing but errors (and the JSON object with --json)\n"
         "      --json            the figures as one JSON object on one line of stdout instead of text (the\n"
         "                        lines of many runs concatenate into a JSON Lines table)\n"
         "  -h, --help            this text\n"
         "Progress goes to stderr once a run takes more than a second: stage, iteration, Res, non-positive\n"
         "faces, elapsed time; on a terminal as one line rewritten in place, otherwise at most a line a second.\n"
         "Ctrl-C, SIGTERM or SIGHUP (job schedulers, timeout) during the iterations stops them and writes the\n"
         "best map so far (exit 1), unless they are inside a part that does not stop within 1.2 s (METIS'\n"
         "ordering of a large mesh, a least-squares step of mean_value with --no-least-distortion: then\n"
         "nothing is written); before the iterations it ends the run at once (nothing written); a second\n"
         "signal quits at once. The output file is only ever replaced whole.\n"
         "Options also take the form --option=VALUE.\n"
         "\n"
         "Examples:\n"
         "  spherical_parameterize bunny.off                        writes bunny_sphere.off\n"
         "  spherical_parameterize brain.obj -o brain_sphere.ply -w cotangent -t 1e-8\n"
         "  spherical_parameterize large.off --max-seconds 600 --json > figures.json\n"
         "\n"
         "JSON object (--json), printed when the mesh was read (exit 0, 1 or 2); a figure not computed is null:\n"
         "  format (\"spherical_parameterize/1\"), input, output (null if nothing written), status (e.g. \"OK\",\n"
         "  \"GENUS_NOT_ZERO\"), success, skipped (an existing output kept: most figures null), message,\n"
         "  vertices, faces, weights, criterion, tolerance, max_imbalance,\n"
         "  imbalance_percentile_99, unbalanced_vertices, vertices_at_rounding_floor,\n"
         "  vertices_below_precision (neighbourhoods within about 28 ulps: counted, not tested),\n"
         "  regularized_tip_vertices (arm tips that double cannot hold balanced, among the previous),\n"
         "  held_weight_vertices, held_weight_parameter and requested_weights_max_imbalance (weights other than\n"
         "  Tutte's whose path from Tutte's ends: vertices whose weights were held, see the manual; 0, 1, null\n"
         "  when none),\n"
         "  least_distortion_map, distortion_energy, max_distortion_stationarity, least_distortion_steps,\n"
         "  distortion_vertices_at_rounding_floor (--least-distortion: whether the map returned is the bijective\n"
         "  map of least conformal distortion; the other four null when it is not), balanced_map_folded\n"
         "  (--least-distortion: the weights' balanced map reached was folded, the minimization followed at once),\n"
         "  least_distortion_from_balanced_map (the minimization started from the weights' balanced map, repaired\n"
         "  where folded, not from its own coarser levels), replaced_balanced_map_distortion and\n"
         "  replaced_balanced_map_angle_error (the distortion and mean angle error of a balanced and certified\n"
         "  map of the weights given that the least-distortion map, of less angle error, replaced; null\n"
         "  otherwise, and the distortion null when infinite: a face of that map without area in double\n"
         "  precision),\n"
         "  max_stationarity and unstationary_vertices (non-symmetric weights, else null), residual (Res),\n"
         "  max_tangential_residual, flipped_faces, total_signed_area, bijective,\n"
         "  distortion.{mean_angle_error_degrees,max_angle_error_degrees,log_area_ratio_stddev} (each corner's\n"
         "  angle in the mesh against that of the straight triangle between the mapped points, and the spread\n"
         "  of log(relative sphere area / relative mesh area); null when no map was computed or an existing\n"
         "  output was kept),\n"
         "  initial_flipped_faces,\n"
         "  uniform_initial_guess_fallback, multilevel_fallback, partition_retries and partition_seed (other\n"
         "  METIS partitions tried where the fast ways from the first ended unconverged, and the seed of the\n"
         "  map returned), admissible_weights, raised_weights,\n"
         "  clamped_weights, rejected_moves,\n"
         "  separator_size, cut_loop_length, levels (the multilevel start, coarsest first, [] when not used:\n"
         "  [{vertices,newton_steps,linear_iterations,seconds}, ...]),\n"
         "  stages.{initial_guess,gauss_seidel,newton}.{seconds,iterations,linear_iterations,residual},\n"
         "  written.{format,precision,radius,flipped_faces,bijective} (the coordinates as written; null if\n"
         "  nothing was written; flipped_faces null when they are the certified ones),\n"
         "  seconds.{read,map,write,total}.\n"
         "\n"
         "Exit status: 0 success (converged and certified bijective); 1 not converged or not bijective (the\n"
         "best map found is written); 2 invalid mesh (nothing written); 3 file error; 4 usage error;\n"
         "128 + the signal's number (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP) stopped before the iterations, in\n"
         "a step that did not stop within 1.2 s, or by a second signal (nothing written).\n";
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Stop signals (Ctrl-C's SIGINT, SIGTERM from job schedulers and `timeout`, SIGHUP) are blocked in every thread and
// taken by one watcher thread with sigwait(), so that no library call can swallow one (METIS traps SIGTERM while it
// runs) and no handler runs in a thread that does not expect it. Before the iterations there is nothing to keep: the
// process ends at once (nothing written, exit 128 + signal). During the iterations the first signal asks them to
// stop and the best map is written (exit 1); during the writing it lets the writing finish. A second signal ends
// the process at once, removing the temporary file of a writing under way (the output itself is only ever replaced
// whole, by a rename). The iterations stop at their next check (between MINRES iterations and between the
// supernodes of a factorization, too), but some parts cannot be interrupted (METIS' ordering, about a second on a
// 164k-vertex cortex; a sparse LU of a least-squares step of mean-value weights with --no-least-distortion, 22 s
// there), and schedulers wait little after their SIGTERM: if the library has not returned after
// `stop_grace`, the run ends as before the iterations (nothing written, exit 128 + signal).
enum Run_phase
{
  SETTING_UP,
  ITERATING,
  WRITING
};
std::atomic<int> stop_signal{0};
std::atomic<int> run_phase{SETTING_UP};
std::mutex phase_mutex; // held by the grace's end: once the writing starts, it no longer ends the run
std::condition_variable phase_changed;
constexpr std::chrono::milliseconds stop_grace(1200);
std::mutex temporary_file_mutex;
std::string temporary_file; // the file being written, if any

const char* signal_name(int signal)
{
  switch(signal)
  {
  case SIGINT:
    return "Ctrl-C";
  case SIGTERM:
    return "SIGTERM";
  case SIGHUP:
    return "SIGHUP";
  default:
    return "signal";
  }
}

[[noreturn]] void end_now(int signal, const char* why)
{
  {
    std::lock_guard<std::mutex> lock(temporary_file_mutex);
    if(!temporary_file.empty())
      std::remove(temporary_file.c_str());
  }
  std::fprintf(stderr, "\n%s (%s): nothing written\n", why, signal_name(signal));
  std::_Exit(128 + signal);
}

void start_signal_watcher()
{
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  sigaddset(&stop, SIGHUP);
  // Every thread created after this line (the progress ticker, TBB's workers) inherits the blocked set.
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  // A shell starts background jobs with SIGINT ignored, and an ignored signal is discarded: a handler that is never
  // called (the signals stay blocked) keeps them coming to sigwait().
  struct sigaction keep = {};
  keep.sa_handler = [](int) {};
  sigemptyset(&keep.sa_mask);
  for(int signal : {SIGINT, SIGTERM, SIGHUP})
    sigaction(signal, &keep, nullptr);
  std::thread([stop] {
    while(true)
    {
      int signal = 0;
      if(sigwait(&stop, &signal) != 0)
        continue;
      if(stop_signal.load() != 0)
        end_now(signal, "stopped again");
      stop_signal = signal;
      if(run_phase.load() == SETTING_UP)
        end_now(signal, "interrupted before the iterations");
      // Its own thread, so that this one goes on waiting for a second signal.
      std::thread([signal] {
        std::unique_lock<std::mutex> lock(phase_mutex);
        if(!phase_changed.wait_for(lock, stop_grace, [] { return run_phase.load() != ITERATING; }))
          end_now(signal, "the iterations did not stop within 1.2 s (a part that cannot be interrupted)");
      }).detach();
    }
  }).detach();
}

// From now on a stop signal lets the writing finish.
void start_writing_phase()
{
  {
    std::lock_guard<std::mutex> lock(phase_mutex);
    run_phase = WRITING;
  }
  phase_changed.notify_all();
}

// The progress line on stderr: rewritten in place on a terminal, otherwise at most one line a second.
// Nothing during the first second, so short runs stay quiet. Between two reports of the library (stage 1 of
// a large mesh takes minutes), a thread keeps the elapsed time going on a terminal, and repeats the last line
// every 30 seconds otherwise.
class Progress_line
{
public:
  Progress_line(bool enabled, Clock::time_point start)
    : m_enabled(enabled), m_terminal(enabled && isatty(fileno(stderr))), m_start(start)
  {
    if(m_enabled)
      m_ticker = std::thread([this] { tick(); });
  }

  ~Progress_line()
  {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_stop = true;
    }
    m_wake.notify_one();
    if(m_ticker.joinable())
      m_ticker.join();
  }

  void phase(const std::string& what) { show(what, false); }

  bool operator()(const SP::Progress& progress)
  {
    std::ostringstream line;
    line << stage_label(progress.stage);
    if(progress.iteration > 0)
      line << ": iteration " << progress.iteration;
    const bool least_distortion = std::string(progress.stage) == "least distortion";
    line << std::setprecision(3) << (least_distortion ? ", max stationarity " : ", Res ") << progress.residual << ", "
         << progress.non_positive_faces
         << " non-positive faces";
    show(line.str(), false);
    return true;
  }

  // Erases the line on a terminal before other output, and stops the updates.
  void clear()
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_current.clear();
    if(m_terminal && m_shown)
    {
      std::cerr << "\r\033[K" << std::flush;
      m_shown = false;
    }
  }

private:
  static std::string stage_label(const std::string& stage)
  {
    if(stage == "initial guess")
      return "stage 1/3, initial guess";
    if(stage == "gauss-seidel")
      return "stage 2/3, projected Gauss-Seidel";
    if(stage == "global newton" || stage == "local newton" || stage == "weight continuation")
      return "stage 3/3, " + stage;
    return stage;
  }

  // `repeat`: the ticker shows the current text again, with the time updated.
  void show(const std::string& text, bool repeat)
  {
    if(!m_enabled)
      return;
    std::lock_guard<std::mutex> lock(m_mutex);
    if(!repeat)
      m_current = text;
    if(m_current.empty())
      return;
    const double now = seconds_since(m_start);
    if(now < 1. || now - m_last < (m_terminal ? 0.1 : 1.))
      return;
    m_last = now;
    std::ostringstream line;
    line << '[' << std::fixed << std::setprecision(1) << std::setw(7) << now << " s] " << m_current;
    if(stop_signal.load() != 0)
      line << " (" << signal_name(stop_signal.load()) << ": stopping as soon as possible; a second signal quits)";
    if(m_terminal)
    {
      // A line longer than the terminal would wrap, and only its last row would be rewritten.
      std::string shown = line.str();
      winsize size{};
      if(ioctl(fileno(stderr), TIOCGWINSZ, &size) == 0 && size.ws_col > 1 && shown.size() >= size.ws_col)
        shown.resize(size.ws_col - 1u);
      std::cerr << "\r\033[K" << shown << std::flush;
      m_shown = true;
    }
    else
      std::cerr << line.str() << '\n' << std::flush;
  }

  void tick()
  {
    const double period = m_terminal ? 1. : 30.;
    std::unique_lock<std::mutex> lock(m_mutex);
    while(!m_stop)
    {
      m_wake.wait_for(lock, std::chrono::milliseconds(250));
      if(m_stop || seconds_since(m_start) - m_last < period)
        continue;
      lock.unlock();
      show(std::string(), true);
      lock.lock();
    }
  }

  bool m_enabled, m_terminal;
  Clock::time_point m_start;
  std::mutex m_mutex;
  std::condition_variable m_wake;
  std::thread m_ticker;
  std::string m_current;
  double m_last = -1.;
  bool m_shown = false, m_stop = false;
};

// --- Minimal JSON output: a fixed set of keys, every figure a number, a string, a boolean or null. ---
std::string json_string(const std::string& text)
{
  std::ostringstream out;
  out << '"';
  for(unsigned char c : text)
  {
    switch(c)
    {
    case '"':
      out << "\\\"";
      break;
    case '\\':
      out << "\\\\";
      break;
    case '\n':
      out << "\\n";
      break;
    case '\t':
      out << "\\t";
      break;
    case '\r':
      out << "\\r";
      break;
    default:
      if(c < 0x20)
        out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec << std::setfill(' ');
      else
        out << c;
    }
  }
  out << '"';
  return out.str();
}

// The shortest decimal form that reads back as the same double.
std::string json_number(double x, bool known = true)
{
  if(!known || !std::isfinite(x))
    return "null";
  std::string text;
  for(int digits = 15; digits <= 17; ++digits)
  {
    std::ostringstream out;
    out << std::setprecision(digits) << x;
    text = out.str();
    if(std::strtod(text.c_str(), nullptr) == x)
      break;
  }
  return text;
}

std::string json_count(std::size_t n, bool known = true)
{
  return known ? std::to_string(n) : "null";
}

// What the output file holds, and the certificate of its coordinates as written (rounded to float32 or scaled).
struct Written_figures
{
  std::string format;    // "off", "ply", "gifti", "freesurfer"
  std::string precision; // "float32", "float64"
  double radius = 1.;
  bool certified = false; // the written coordinates were certified (they differ from the certified map)
  std::size_t flipped_faces = 0;
  bool bijective = false;
  double total_signed_area = 0.; // of the coordinates as written, when certified
};

struct Run_figures
{
  std::string input, output; // output empty: nothing written
  Written_figures written;
  std::string weights;
  std::string criterion = "imbalance";
  double tolerance = 1e-6;
  double read_seconds = 0., map_seconds = 0., write_seconds = 0., total_seconds = 0.;
  bool skipped = false; // the output was already a certified answer to the same request, and was kept
  // The map's shape against the mesh's (measure_spherical_distortion()), when a map was computed.
  bool has_distortion = false;
  SP::Spherical_distortion distortion;
};

// The multilevel start's levels, coarsest first: [{"vertices": .., "newton_steps": .., ...}, ...].
std::string levels_json(const SP::Result& r)
{
  std::string text = "[";
  for(const SP::Level_statistics& level : r.levels)
    text += std::string(text.size() > 1 ? ", " : "") + "{\"vertices\": " + std::to_string(level.vertices)
            + ", \"newton_steps\": " + std::to_string(level.newton_steps) + ", \"linear_iterations\": "
            + std::to_string(level.linear_iterations) + ", \"seconds\": " + json_number(level.seconds) + "}";
  return text + "]";
}

// One line per run (JSON Lines), so that the figures of many runs concatenate into one table.
void print_json(std::ostream& out, const SP::Result& r, const Run_figures& run)
{
  const bool computed = r.residual >= 0.;         // the iterations ran (not an input or set-up error)
  const bool certified = computed || run.skipped; // a kept output was certified again
  auto stage = [](const SP::Stage_statistics& s) {
    return "{\"seconds\": " + json_number(s.seconds) + ", \"iterations\": " + json_count(s.iterations)
           + ", \"linear_iterations\": " + json_count(s.linear_iterations)
           + ", \"residual\": " + json_number(s.residual, s.residual >= 0.) + "}";
  };
  auto boolean = [](bool b) { return std::string(b ? "true" : "false"); };
  const std::vector<std::pair<const char*, std::string>> fields = {
      {"format", "\"spherical_parameterize/1\""},
      {"input", json_string(run.input)},
      {"output", run.output.empty() ? std::string("null") : json_string(run.output)},
      {"status", json_string(SP::get_error_name(r.status))},
      // Exactly when the exit status is 0: a map certified in double precision whose float32 (or scaled) coordinates
      // as written fold a triangle is no success, and tables built from these lines must not count it as one.
      {"success", boolean(r.status == SP::Error_code::OK && !(run.written.certified && !run.written.bijective))},
      {"skipped", boolean(run.skipped)},
      {"message", json_string(r.message)},
      {"vertices", std::to_string(r.number_of_vertices)},
      {"faces", std::to_string(r.number_of_faces)},
      {"weights", json_string(run.weights)},
      {"criterion", json_string(run.criterion)},
      {"tolerance", json_number(run.tolerance)},
      {"max_imbalance", json_number(r.max_imbalance, computed)},
      {"imbalance_percentile_99", json_number(r.imbalance_percentile_99, computed)},
      {"unbalanced_vertices", json_count(r.unbalanced_vertices, computed)},
      {"max_stationarity", json_number(r.max_stationarity, computed && r.max_stationarity >= 0.)},
      {"unstationary_vertices", json_count(r.unstationary_vertices, computed && r.max_stationarity >= 0.)},
      {"vertices_at_rounding_floor", json_count(r.vertices_at_rounding_floor, computed)},
      {"vertices_below_precision", json_count(r.vertices_below_precision, computed)},
      {"regularized_tip_vertices", json_count(r.regularized_tip_vertices, computed)},
      {"held_weight_vertices", json_count(r.held_weight_vertices, computed)},
      {"least_distortion_map", boolean(r.least_distortion_map)},
      {"balanced_map_folded", boolean(r.balanced_map_folded)},
      {"least_distortion_from_balanced_map", boolean(r.least_distortion_from_balanced_map)},
      {"replaced_balanced_map_distortion",
       json_number(r.replaced_balanced_map_distortion, computed && r.replaced_balanced_map_distortion >= 0.)},
      {"replaced_balanced_map_angle_error",
       json_number(r.replaced_balanced_map_angle_error, computed && r.replaced_balanced_map_angle_error >= 0.)},
      {"distortion_energy", json_number(r.distortion_energy, computed && r.least_distortion_map)},
      {"max_distortion_stationarity", json_number(r.max_distortion_stationarity, computed && r.least_distortion_map)},
      {"least_distortion_steps", json_count(r.least_distortion_steps, computed && r.least_distortion_map)},
      {"distortion_vertices_at_rounding_floor",
       json_count(r.distortion_vertices_at_rounding_floor, computed && r.least_distortion_map)},
      {"held_weight_parameter", json_number(r.held_weight_parameter, computed)},
      {"requested_weights_max_imbalance",
       json_number(r.requested_weights_max_imbalance, computed && r.requested_weights_max_imbalance >= 0.)},
      {"residual", json_number(r.residual, computed)},
      {"max_tangential_residual", json_number(r.max_tangential_residual, computed)},
      {"flipped_faces", json_count(r.flipped_faces, certified)},
      {"total_signed_area", json_number(r.total_signed_area, certified)},
      {"bijective", boolean(r.bijective)},
      {"distortion", run.has_distortion
                         ? "{\"mean_angle_error_degrees\": " + json_number(run.distortion.mean_angle_error_degrees)
                               + ", \"max_angle_error_degrees\": " + json_number(run.distortion.max_angle_error_degrees)
                               + ", \"log_area_ratio_stddev\": " + json_number(run.distortion.log_area_ratio_stddev)
                               + "}"
                         : std::string("null")},
      {"initial_flipped_faces", json_count(r.initial_flipped_faces, computed)},
      {"uniform_initial_guess_fallback", boolean(r.uniform_initial_guess_fallback)},
      {"multilevel_fallback", boolean(r.multilevel_fallback)},
      {"partition_retries", std::to_string(r.partition_retries)},
      {"partition_seed", std::to_string(r.partition_seed)},
      {"admissible_weights", boolean(r.admissible_weights)},
      {"raised_weights", std::to_string(r.raised_weights)},
      {"clamped_weights", std::to_string(r.clamped_weights)},
      {"rejected_moves", json_count(r.rejected_moves, computed)},
      {"separator_size", json_count(r.separator_size, computed)},
      {"cut_loop_length", json_count(r.cut_loop_length, computed)},
      {"levels", levels_json(r)},
      {"stages", "{\"initial_guess\": " + stage(r.initial_guess) + ", \"gauss_seidel\": " + stage(r.gauss_seidel)
                     + ", \"newton\": " + stage(r.newton) + "}"},
      {"written", run.output.empty()
                      ? std::string("null")
                      : "{\"format\": " + json_string(run.written.format) + ", \"precision\": "
                            + json_string(run.written.precision) + ", \"radius\": " + json_number(run.written.radius)
                            + ", \"flipped_faces\": " + json_count(run.written.flipped_faces, run.written.certified)
                            + ", \"bijective\": "
                            + (run.written.certified ? boolean(run.written.bijective) : std::string("null")) + "}"},
      {"seconds", "{\"read\": " + json_number(run.read_seconds) + ", \"map\": " + json_number(run.map_seconds)
                      + ", \"write\": " + json_number(run.write_seconds)
                      + ", \"total\": " + json_number(run.total_seconds) + "}"}};
  std::string line = "{";
  for(const auto& field : fields)
    line += (line.size() > 1 ? ", \"" : "\"") + std::string(field.first) + "\": " + field.second;
  out << line << "}\n";
}

std::string plural(std::size_t n, const std::string& noun)
{
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

void print_text(std::ostream& out, const SP::Result& r, const Run_figures& run)
{
  out << "input:           " << run.input << " (" << r.number_of_vertices << " vertices, " << r.number_of_faces
      << " faces)\n"
      << "status:          " << SP::get_error_name(r.status) << ": " << r.message << "\n";
  if(run.skipped)
    out << "kept:            " << run.output << " (" << run.written.format << ", " << run.written.precision
        << "; certified again: " << plural(run.written.flipped_faces, "flipped face")
        << (run.written.bijective ? ", bijective" : "") << ")\n";
  if(r.residual < 0.)
    return;
  out << std::setprecision(4) << "max imbalance:   " << r.max_imbalance << " (99th percentile "
      << r.imbalance_percentile_99 << "; " << r.unbalanced_vertices
      << (r.unbalanced_vertices == 1 ? " vertex" : " vertices") << " above the tolerance " << run.tolerance << ", "
      << r.vertices_at_rounding_floor << " held to their rounding floor"
      << (r.vertices_below_precision > 0
              ? ", " + std::to_string(r.vertices_below_precision) + " below double precision (not tested"
                    + (r.regularized_tip_vertices > 0 ? "; " + std::to_string(r.regularized_tip_vertices)
                                                            + " of them in arm tips solved with regularized weights"
                                                      : std::string())
                    + ")"
              : std::string())
      << "; " << run.weights << " weights, stopping on " << run.criterion << ")\n";
  if(r.least_distortion_map)
    out << "least distortion: the bijective map of least conformal distortion (--least-distortion), not a balanced "
           "map of the weights given: distortion "
        << r.distortion_energy << " (about 1: every small triangle keeps its shape), max stationarity " << r.max_distortion_stationarity
        << " after " << r.least_distortion_steps << " Newton steps ("
        << r.distortion_vertices_at_rounding_floor << " vertices held to their rounding floor)"
        << (r.balanced_map_folded ? "; the balanced map of the weights given that Newton's steps reached is folded" : "")
        << (r.balanced_map_folded && r.least_distortion_from_balanced_map
                ? " (the minimization started from it, its folds repaired)"
                : "")
        << (r.replaced_balanced_map_distortion >= 0.
                ? "; it replaced the balanced map of the weights given that was reached, of distortion "
                      + std::to_string(r.replaced_balanced_map_distortion) + " and mean angle error "
                      + std::to_string(r.replaced_balanced_map_angle_error) + " degrees"
                      + (r.least_distortion_from_balanced_map ? ", from which the minimization started" : "")
                : std::string())
        << "\n";
  if(r.held_weight_vertices > 0)
    out << "held weights:    " << r.held_weight_vertices << " of the " << r.number_of_vertices
        << " vertices keep the weights blended with Tutte's at s >= " << r.held_weight_parameter
        << " (the balanced maps from Tutte's weights end before these; the imbalances above are under the held "
           "weights; under the weights requested the largest is "
        << r.requested_weights_max_imbalance << ")\n";
  out
      << (r.max_stationarity >= 0. ? "stationarity:    " : "");
  if(r.max_stationarity >= 0.)
    out << r.max_stationarity << " (max; " << r.unstationary_vertices
        << (r.unstationary_vertices == 1 ? " vertex" : " vertices")
        << " above the tolerance: non-symmetric weights stop on the stationarity of their least-squares problem)\n";
  out << "Res (paper):     " << r.residual << "\n"
      << "max tangential:  " << r.max_tangential_residual << "\n"
      << "flipped faces:   " << r.flipped_faces << " (exact orientation test)\n"
      << std::setprecision(12) << "total area:      " << r.total_signed_area << " (4 pi = 12.5663706144)\n";
  if(run.has_distortion)
    out << std::setprecision(4) << "distortion:      mean angle error " << run.distortion.mean_angle_error_degrees
        << " degrees (max " << run.distortion.max_angle_error_degrees << "), std of log area ratios "
        << run.distortion.log_area_ratio_stddev << "\n";
  out << std::setprecision(3);
  if(r.levels.empty() && r.initial_guess.iterations == 0)
    out << "stage 1:         not run (the least-distortion minimization started from its own coarser levels)";
  else
  {
    out << "stage 1:         initial guess, " << r.initial_guess.seconds << " s, Res " << r.initial_guess.residual
        << ", " << plural(r.initial_flipped_faces, "non-positive face");
    if(r.levels.empty())
      out << ", cut loop of " << r.cut_loop_length << " vertices"
          << (r.uniform_initial_guess_fallback ? ", uniform-weight disks" : "")
          << (r.partition_retries > 0 ? ", the partition of METIS seed " + std::to_string(r.partition_seed) + " ("
                                            + plural(r.partition_retries, "partition") + " tried after the first)"
                                      : std::string());
    else
    {
      out << ", multilevel start: ";
      for(std::size_t l = 0; l < r.levels.size(); ++l)
        out << (l > 0 ? " -> " : "") << r.levels[l].vertices << " vertices ("
            << plural(r.levels[l].newton_steps, "Newton step") << ", " << r.levels[l].seconds << " s)";
    }
  }
  out << "\n"
      << "stage 2:         projected Gauss-Seidel, " << r.gauss_seidel.seconds << " s, "
      << plural(r.gauss_seidel.iterations, "sweep") << ", Res " << r.gauss_seidel.residual << "\n"
      << "stage 3:         Newton, " << r.newton.seconds << " s, " << plural(r.newton.iterations, "iteration")
      << (r.newton.linear_iterations > 0 ? " (" + plural(r.newton.linear_iterations, "MINRES iteration") + ")"
                                         : std::string())
      << ", Res " << r.newton.residual << ", " << plural(r.rejected_moves, "move") << " not taken (stages 2 and 3)\n"
      << "time:            " << run.total_seconds << " s (read " << run.read_seconds << " s, map " << run.map_seconds
      << " s, write " << run.write_seconds << " s)\n";
  if(!run.output.empty())
  {
    out << "written:         " << run.output << " (" << run.written.format << ", " << run.written.precision;
    if(run.written.radius != 1.)
      out << ", radius " << run.written.radius;
    if(run.written.certified)
      out << "; as written: " << plural(run.written.flipped_faces, "flipped face")
          << (run.written.bijective ? ", bijective" : ", NOT bijective");
    out << ")\n";
  }
}

// --- Command-line parsing, with a suggestion for every mistake. ---
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for(std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for(std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for(std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      row[j] = (std::min)({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The closest of `choices` to `word` if it is close enough to be a typo, or a choice that `word` starts.
std::string closest(const std::string& word, const std::vector<std::string>& choices)
{
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 4) + 1;
  for(const std::string& candidate : choices)
  {
    const std::size_t d = edit_distance(word, candidate);
    if(d < best_distance || (best.empty() && word.size() >= 3 && candidate.compare(0, word.size(), word) == 0))
    {
      best = candidate;
      best_distance = (std::min)(d, best_distance);
    }
  }
  return best;
}

[[noreturn]] void usage_error(const std::string& message, const std::string& hint = std::string())
{
  std::cerr << "error: " << message << "\n";
  if(!hint.empty())
    std::cerr << "       " << hint << "\n";
  std::cerr << synopsis << "Try 'spherical_parameterize --help' for the options.\n";
  std::exit(EXIT_USAGE);
}

struct Option
{
  const char* short_name; // "" if none
  const char* long_name;
  const char* value; // what the value is, nullptr for a flag
};

const Option options[] = {
    {"-o", "--output", "a file name: .off, .ply, .gii, or a FreeSurfer surface name"},
    {"", "--radius", "a positive number"},
    {"", "--float64", nullptr},
    {"", "--overwrite", nullptr},
    {"-w", "--weights", "uniform, cotangent or mean_value"},
    {"-t", "--tolerance", "a positive number such as 1e-6"},
    {"", "--criterion", "imbalance or paper"},
    {"", "--gauss-seidel-sweeps", "a number of sweeps, 0 or more"},
    {"-s", "--solver", "global or local"},
    {"", "--disk-solver", "amg or sparse_lu"},
    {"", "--max-seconds", "a positive number of seconds"},
    {"", "--seed", "an integer"},
    {"", "--no-backtracking", nullptr},
    {"", "--start", "multilevel or two_disks"},
    {"", "--verbose", nullptr},
    {"", "--admissible-weights", nullptr},
    {"", "--hold-weights", nullptr},
    {"", "--least-distortion", nullptr},
    {"", "--no-least-distortion", nullptr},
    {"-q", "--quiet", nullptr},
    {"", "--json", nullptr},
    {"-h", "--help", nullptr},
};

const Option* find_option(const std::string& name)
{
  for(const Option& o : options)
    if(name == o.long_name || (o.short_name[0] != '\0' && name == o.short_name))
      return &o;
  return nullptr;
}

// A named value out of a fixed set (weights, solvers); the suggestion names the closest one.
std::string choice(const std::string& option, const std::string& value, const std::vector<std::string>& names,
                   const std::vector<std::string>& aliases = {})
{
  for(const std::string& n : names)
    if(value == n)
      return n;
  for(std::size_t i = 0; i + 1 < aliases.size(); i += 2)
    if(value == aliases[i])
      return aliases[i + 1];
  std::string list;
  for(const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  const std::string guess = closest(value, names);
  usage_error("unknown value '" + value + "' for " + option + " (one of: " + list + ")",
              guess.empty() ? std::string() : "did you mean '" + guess + "'?");
}

double positive_number(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size())
    usage_error(option + " expects a number, got '" + text + "'");
  if(!std::isfinite(x) || !(x > 0.))
    usage_error(option + " must be a positive finite number, got '" + text + "'");
  return x;
}

int integer(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(text.c_str(), &end, 10);
  if(text.empty() || end != text.c_str() + text.size())
    usage_error(option + " expects an integer, got '" + text + "'");
  if(errno == ERANGE || x < std::numeric_limits<int>::min() || x > std::numeric_limits<int>::max())
    usage_error(option + " is out of range: '" + text + "'");
  return static_cast<int>(x);
}

bool ends_with(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

struct Settings
{
  std::string input, output;
  std::string weights_name = "uniform";
  SP::Weighting weighting = SP::Weighting::UNIFORM;
  double tolerance = 1e-6, max_seconds = -1.;
  std::string criterion = "imbalance";
  long gauss_seidel_sweeps = -1; // -1: the library's default
  int seed = 0;
  bool quiet = false, json = false, backtracking = true, sparse_lu = false, admissible = false, float64 = false;
  bool hold = false; // --hold-weights
  // --least-distortion, --no-least-distortion; otherwise the library's default: on for cotangent and mean_value
  // weights (not made admissible), off for the others.
  int least_distortion_flag = -1;
  bool least_distortion = false; // the setting in effect
  bool overwrite = false; // map again even when the output is already a certified answer to the same request
  bool multilevel = true, verbose = false;
  double radius = 1.;
  SP::Nonlinear_solver solver = SP::Nonlinear_solver::GLOBAL_NEWTON;
};

Settings parse_arguments(int argc, char** argv)
{
  Settings settings;
  std::vector<std::string> given;
  bool only_files = false; // after "--"
  for(int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    if(only_files || arg.empty() || arg[0] != '-' || arg == "-")
    {
      if(settings.input.empty())
        settings.input = arg;
      else
        usage_error("more than one input file ('" + settings.input + "', '" + arg + "')",
                    "one mesh per run; the output is set with -o FILE");
      continue;
    }
    if(arg == "--")
    {
      only_files = true;
      continue;
    }

    // --name=value
    std::string name = arg, attached;
    bool has_attached = false;
    const std::size_t equal = arg.find('=');
    if(arg.compare(0, 2, "--") == 0 && equal != std::string::npos)
    {
      name = arg.substr(0, equal);
      attached = arg.substr(equal + 1);
      has_attached = true;
    }
    const Option* option = find_option(name);
    if(option == nullptr)
    {
      std::vector<std::string> names;
      for(const Option& o : options)
        names.push_back(o.long_name);
      // "-tolerance" for "--tolerance", or a typo
      std::string guess =
          (name.size() > 2 && name[1] != '-' && find_option("-" + name)) ? "-" + name : closest(name, names);
      usage_error("unknown option '" + name + "'", guess.empty() ? std::string() : "did you mean '" + guess + "'?");
    }
    const std::string canonical = option->long_name;
    if(std::find(given.begin(), given.end(), canonical) != given.end() && canonical != "--quiet"
       && canonical != "--json")
      std::cerr << "warning: " << canonical << " is given more than once; the last one counts\n";
    given.push_back(canonical);

    std::string value;
    if(option->value == nullptr)
    {
      if(has_attached)
        usage_error(canonical + " takes no value, got '" + attached + "'");
    }
    else if(has_attached)
    {
      value = attached;
    }
    else
    {
      if(a + 1 >= argc)
        usage_error(name + " needs a value: " + option->value);
      value = argv[++a];
      // "-o -q": the value is missing, not a file named "-q".
      if(value.size() > 1 && value[0] == '-' && find_option(value.substr(0, value.find('='))) != nullptr)
        usage_error(name + " needs a value (" + option->value + "), got the option '" + value + "'");
    }
    if(option->value != nullptr && value.empty())
      usage_error(name + " needs a value: " + option->value);

    if(canonical == "--help")
    {
      print_usage(std::cout);
      std::exit(EXIT_OK);
    }
    else if(canonical == "--output")
    {
      if(ends_with(value, ".obj") || ends_with(value, ".stl") || ends_with(value, ".gz"))
        usage_error("cannot write '" + value + "': the output is .off, .ply, .gii or a FreeSurfer surface");
#ifndef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
      if(ends_with(value, ".gii"))
        usage_error("cannot write '" + value + "': this program was built without the GIFTI library (libgiftiio-dev)");
#endif
      settings.output = value;
    }
    else if(canonical == "--weights")
    {
      settings.weights_name =
          choice(canonical, value, {"uniform", "cotangent", "mean_value"},
                 {"tutte", "uniform", "conformal", "cotangent", "mean-value", "mean_value", "mvc", "mean_value"});
      settings.weighting = settings.weights_name == "uniform"     ? SP::Weighting::UNIFORM
                           : settings.weights_name == "cotangent" ? SP::Weighting::COTANGENT
                                                                  : SP::Weighting::MEAN_VALUE;
    }
    else if(canonical == "--tolerance")
      settings.tolerance = positive_number(name, value);
    else if(canonical == "--gauss-seidel-sweeps")
    {
      settings.gauss_seidel_sweeps = integer(name, value);
      if(settings.gauss_seidel_sweeps < 0)
        usage_error(name + " needs a number of sweeps, 0 or more");
    }
    else if(canonical == "--criterion")
      settings.criterion = choice(canonical, value, {"imbalance", "paper"});
    else if(canonical == "--max-seconds")
      settings.max_seconds = positive_number(name, value);
    else if(canonical == "--seed")
      settings.seed = integer(name, value);
    else if(canonical == "--solver")
      settings.solver = choice(canonical, value, {"global", "local"}) == "local" ? SP::Nonlinear_solver::LOCAL_NEWTON
                                                                                 : SP::Nonlinear_solver::GLOBAL_NEWTON;
    else if(canonical == "--disk-solver")
      settings.sparse_lu = choice(canonical, value, {"amg", "sparse_lu"}) == "sparse_lu";
    else if(canonical == "--no-backtracking")
      settings.backtracking = false;
    else if(canonical == "--start")
      settings.multilevel = choice(canonical, value, {"multilevel", "two_disks"}) == "multilevel";
    else if(canonical == "--verbose")
      settings.verbose = true;
    else if(canonical == "--radius")
      settings.radius = positive_number(name, value);
    else if(canonical == "--float64")
      settings.float64 = true;
    else if(canonical == "--overwrite")
      settings.overwrite = true;
    else if(canonical == "--admissible-weights")
      settings.admissible = true;
    else if(canonical == "--hold-weights")
      settings.hold = true;
    else if(canonical == "--least-distortion")
      settings.least_distortion_flag = 1;
    else if(canonical == "--no-least-distortion")
      settings.least_distortion_flag = 0;
    else if(canonical == "--quiet")
      settings.quiet = true;
    else if(canonical == "--json")
      settings.json = true;
  }
  if(settings.input.empty())
    usage_error("no input mesh given");
  settings.least_distortion = settings.least_distortion_flag >= 0
                                  ? settings.least_distortion_flag == 1
                                  : SP::least_distortion_by_default(settings.weighting, settings.admissible);
  return settings;
}

// An input that does not exist, or is a folder: say so, and name a file of that folder the user may have meant.
void explain_missing_input(const std::string& input)
{
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path path(input);
  if(fs::is_directory(path, error))
  {
    std::cerr << "error: '" << input << "' is a folder, not a mesh file [CANNOT_OPEN]\n";
    std::exit(EXIT_IO);
  }
  if(fs::exists(path, error))
    return;
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::vector<std::string> names;
  for(fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
    if(it->is_regular_file(error))
      names.push_back(it->path().filename().string());
  const std::string guess = closest(path.filename().string(), names);
  std::cerr << "error: no such file: '" << input << "' [CANNOT_OPEN]\n";
  if(!guess.empty())
    std::cerr << "       did you mean '" << (path.has_parent_path() ? (folder / guess).string() : guess) << "'?\n";
  std::exit(EXIT_IO);
}

// FreeSurfer surfaces have no extension of their own (lh.white, lh.pial): they are recognized by their first bytes.
bool is_FreeSurfer_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char magic[3] = {0, 0, 0};
  in.read(magic, 3);
  return in.gcount() == 3 && SP::IO::internal::has_FreeSurfer_magic(magic, magic + 3);
}

std::string output_format(const std::string& path)
{
  if(ends_with(path, ".off"))
    return "off";
  if(ends_with(path, ".ply"))
    return "ply";
  if(ends_with(path, ".gii"))
    return "gifti";
  return "freesurfer";
}

std::string default_output(std::string input)
{
  if(is_FreeSurfer_file(input))
    return input + ".sphere"; // lh.white -> lh.white.sphere, in FreeSurfer's format
  if(ends_with(input, ".surf.gii"))
    return input.substr(0, input.size() - 9) + "_sphere.surf.gii";
  if(ends_with(input, ".gii"))
    return input.substr(0, input.size() - 4) + "_sphere.surf.gii";
  if(input.size() > 3 && input.compare(input.size() - 3, 3, ".gz") == 0)
    input.resize(input.size() - 3); // mesh.off.gz
  const std::size_t slash = input.find_last_of('/');
  const std::size_t dot = input.find_last_of('.');
  const std::string stem =
      (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ? input.substr(0, dot) : input;
  return stem + "_sphere.off";
}

// The output's folder must exist and take a new file, and the output itself must not be a folder.
bool can_write_next_to(const std::string& path, std::string& error)
{
  const std::size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  struct stat info;
  if(::stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
  {
    error = "cannot write '" + path + "': the folder '" + folder + "' does not exist";
    return false;
  }
  if(::access(folder.c_str(), W_OK) != 0)
  {
    error = "cannot write '" + path + "': the folder '" + folder + "' is not writable";
    return false;
  }
  if(::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
  {
    error = "cannot write '" + path + "': it is a folder";
    return false;
  }
  return true;
}

// The certificate of the coordinates as the file holds them, when they differ from the certified map: rounded to
// float32 (FreeSurfer, GIfTI without --float64) or scaled by a radius other than 1. Rounding can fold triangles whose
// edges are below float32's resolution (about 6e-8 of the radius).
Written_figures certify_as_written(const Mesh& mesh, const std::vector<Point>& sphere, const std::string& format,
                                   const Settings& settings)
{
  Written_figures written;
  written.format = format;
  written.radius = settings.radius;
  const bool float32 = format == "freesurfer" || (format == "gifti" && !settings.float64);
  written.precision = float32 ? "float32" : "float64";
  if(!float32 && settings.radius == 1.)
    return written; // exactly the certified coordinates
  auto as_written = [&](double c) {
    return float32 ? double(static_cast<float>(settings.radius * c)) : settings.radius * c;
  };
  std::vector<Point> stored(sphere.size());
  for(std::size_t i = 0; i < sphere.size(); ++i)
    stored[i] = Point(as_written(sphere[i].x()), as_written(sphere[i].y()), as_written(sphere[i].z()));
  const SP::Sphere_map_certificate certificate =
      SP::certify_sphere_map(mesh, boost::make_iterator_property_map(stored.begin(), get(CGAL::vertex_index, mesh)));
  written.certified = true;
  written.flipped_faces = certificate.flipped_faces;
  written.bijective = certificate.bijective;
  return written;
}

// A polygon soup from any of the formats: FreeSurfer surfaces by their first bytes, GIfTI by the name .gii.
SP::IO::File_read read_input(const std::string& path, std::vector<Point>& points,
                             std::vector<std::vector<std::size_t>>& faces,
                             SP::IO::FreeSurfer_surface_info& freesurfer_info)
{
  if(ends_with(path, ".gii"))
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
    return SP::IO::read_GIfTI_surface(path, points, faces);
#else
    return SP::IO::internal::file_error(SP::IO::File_status::UNKNOWN_FORMAT,
                                        path + ": this program was built without the GIFTI library (libgiftiio-dev)");
#endif
  }
  if(is_FreeSurfer_file(path))
    return SP::IO::read_FreeSurfer_surface(path, points, faces, &freesurfer_info);
  return SP::IO::read_polygon_soup(path, points, faces);
}

// --- Re-runs: an output that already answers the same request, and passes the certificate as stored, is kept. ---
// Every output records the run that made it in one line its format keeps: a comment of OFF and PLY, the "created
// by" line of a FreeSurfer surface, a metadata entry of a GIfTI file. A cohort re-run after a killed job then redoes
// only what is missing or unfinished (a stopped run writes its best map with a status other than OK).
const std::string stamp_tag = "spherical_parameterize/1";
constexpr int least_distortion_version = 2;

struct Run_stamp
{
  std::string status, weights, criterion, precision, input;
  bool admissible = false;
  bool hold = false; // --hold-weights (absent from the stamps written before it: no)
  // --least-distortion: 0 off (absent), else the version of its rule that made the map: 1, written "yes", before
  // 2026-12-05, when balanced cotangent maps below distortion 1.1 were kept; 2 since, when the minimization follows
  // every balanced map (outputs of version 1 are mapped again).
  int least_distortion = 0;
  double tolerance = 0., radius = 1.;
};

// FNV-1a (64 bits) of the coordinates' bits and the faces: an output is kept only for the very input it was made from.
std::string input_fingerprint(const std::vector<Point>& points, const std::vector<std::vector<std::size_t>>& faces)
{
  std::uint64_t hash = 14695981039346656037ull;
  auto add = [&hash](std::uint64_t value) {
    for(int byte = 0; byte < 8; ++byte)
    {
      hash ^= (value >> (8 * byte)) & 0xFF;
      hash *= 1099511628211ull;
    }
  };
  add(points.size());
  for(const Point& p : points)
    for(int k = 0; k < 3; ++k)
    {
      const double c = p[k];
      std::uint64_t bits;
      std::memcpy(&bits, &c, 8);
      add(bits);
    }
  add(faces.size());
  for(const auto& f : faces)
  {
    add(f.size());
    for(std::size_t i : f)
      add(i);
  }
  std::ostringstream text;
  text << std::hex << std::setw(16) << std::setfill('0') << hash;
  return text.str();
}

// The shortest decimal form that reads back as the same double (1e-06, not 9.9999999999999995e-07).
std::string round_trip(double x)
{
  for(int digits = 6;; ++digits)
  { // from 6: 100, not 1e+02
    std::ostringstream text;
    text << std::setprecision(digits) << x;
    if(digits >= 17 || std::strtod(text.str().c_str(), nullptr) == x)
      return text.str();
  }
}

std::string format_stamp(const Run_stamp& stamp)
{
  std::ostringstream line;
  line << stamp_tag << " status=" << stamp.status << " weights=" << stamp.weights
       << " admissible=" << (stamp.admissible ? "yes" : "no") << " hold=" << (stamp.hold ? "yes" : "no")
       << (stamp.least_distortion > 0 ? " least_distortion=" + std::to_string(stamp.least_distortion) : std::string())
       << " criterion=" << stamp.criterion
       << " tolerance=" << round_trip(stamp.tolerance) << " precision=" << stamp.precision
       << " radius=" << round_trip(stamp.radius) << " input=" << stamp.input;
  return line.str();
}

// Finds the stamp in `text` (a comment line, a "created by" line, a metadata value); false if there is none.
bool parse_stamp(const std::string& text, Run_stamp& stamp)
{
  const std::size_t at = text.find(stamp_tag + " ");
  if(at == std::string::npos)
    return false;
  std::istringstream fields(text.substr(at + stamp_tag.size()));
  std::string field;
  int found = 0;
  while(fields >> field)
  {
    const std::size_t equal = field.find('=');
    if(equal == std::string::npos)
      continue;
    const std::string key = field.substr(0, equal), value = field.substr(equal + 1);
    char* end = nullptr;
    if(key == "status")
      stamp.status = value;
    else if(key == "weights")
      stamp.weights = value;
    else if(key == "criterion")
      stamp.criterion = value;
    else if(key == "precision")
      stamp.precision = value;
    else if(key == "input")
      stamp.input = value;
    else if(key == "admissible")
      stamp.admissible = value == "yes";
    else if(key == "least_distortion")
    {
      stamp.least_distortion = value == "yes" ? 1 : std::atoi(value.c_str());
      continue; // optional: written only when asked
    }
    else if(key == "hold")
    {
      stamp.hold = value == "yes";
      continue; // optional: stamps written before --hold-weights existed lack it
    }
    else if(key == "tolerance")
      stamp.tolerance = std::strtod(value.c_str(), &end);
    else if(key == "radius")
      stamp.radius = std::strtod(value.c_str(), &end);
    else
      continue;
    ++found;
  }
  return found == 8;
}

std::string output_precision(const std::string& format, const Settings& settings)
{
  return format == "freesurfer" || (format == "gifti" && !settings.float64) ? "float32" : "float64";
}

// An existing output as stored: its points, its faces and its stamp line ("" if it has none).
SP::IO::File_read read_existing_output(const std::string& path, std::vector<Point>& points,
                                       std::vector<std::vector<std::size_t>>& faces, std::string& stamp_line)
{
  stamp_line.clear();
  const std::string format = output_format(path);
  if(format == "gifti")
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
    std::vector<std::pair<std::string, std::string>> metadata;
    const SP::IO::File_read read = SP::IO::read_GIfTI_surface(path, points, faces, &metadata);
    for(const auto& entry : metadata)
      if(entry.first == "spherical_parameterize")
        stamp_line = entry.second;
    return read;
#else
    return SP::IO::internal::file_error(SP::IO::File_status::UNKNOWN_FORMAT, "built without the GIFTI library");
#endif
  }
  if(format == "freesurfer")
  {
    if(!is_FreeSurfer_file(path))
      return SP::IO::internal::file_error(SP::IO::File_status::INVALID_DATA, "not a FreeSurfer surface");
    SP::IO::FreeSurfer_surface_info info;
    const SP::IO::File_read read = SP::IO::read_FreeSurfer_surface(path, points, faces, &info);
    stamp_line = info.created_by;
    return read;
  }
  // OFF and PLY: the stamp is a comment line of the header.
  std::ifstream in(path);
  std::string line;
  for(int k = 0; k < 16 && std::getline(in, line); ++k)
  {
    if(line.find(stamp_tag) != std::string::npos)
    {
      stamp_line = line;
      break;
    }
    if(line == "end_header")
      break;
  }
  return SP::IO::read_polygon_soup(path, points, faces);
}

// Why the existing `output` is not kept; empty when it is: it holds the stamp of a successful run with the same
// weights, criterion, precision and radius and a tolerance at least as tight, made from this very input, the input's
// vertices and faces, and coordinates that pass the certificate (exact orientations, degree 1) as they are stored.
std::string reason_not_to_keep(const std::string& output, const Mesh& mesh,
                               const std::vector<std::vector<std::size_t>>& faces, const std::string& fingerprint,
                               const Settings& settings, Written_figures& kept)
{
  std::vector<Point> stored;
  std::vector<std::vector<std::size_t>> stored_faces;
  std::string stamp_line;
  if(!read_existing_output(output, stored, stored_faces, stamp_line))
    return "it cannot be read as a mesh";
  Run_stamp stamp;
  if(!parse_stamp(stamp_line, stamp))
    return "it was not written by this program";
  if(stamp.status != "OK")
    return "the run that wrote it ended with " + stamp.status;
  const std::string format = output_format(output);
  if(stamp.weights != settings.weights_name || stamp.admissible != settings.admissible || stamp.hold != settings.hold
     || stamp.least_distortion != (settings.least_distortion ? least_distortion_version : 0)
     || stamp.criterion != settings.criterion || !(stamp.tolerance <= settings.tolerance)
     || stamp.radius != settings.radius || stamp.precision != output_precision(format, settings))
    return "it was made with other settings (" + stamp_line.substr(stamp_line.find(stamp_tag) + stamp_tag.size() + 1)
           + ")";
  if(stamp.input != fingerprint)
    return "it was made from another input (or the input changed)";
  if(stored.size() != num_vertices(mesh) || stored_faces != faces)
    return "its vertices or faces are not the input's";
  const SP::Sphere_map_certificate certificate =
      SP::certify_sphere_map(mesh, boost::make_iterator_property_map(stored.begin(), get(CGAL::vertex_index, mesh)));
  if(!certificate.bijective)
    return "its coordinates fail the certificate (" + plural(certificate.flipped_faces, "flipped face") + ")";
  kept.format = format;
  kept.precision = stamp.precision;
  kept.radius = stamp.radius;
  kept.certified = true;
  kept.flipped_faces = certificate.flipped_faces;
  kept.bijective = true;
  kept.total_signed_area = certificate.total_signed_area;
  return std::string();
}

// Writes to a temporary file next to `path`, then renames it: a failure never leaves a half-written file.
bool write_sphere(const std::string& path, const std::vector<Point>& sphere,
                  const std::vector<std::vector<std::size_t>>& faces,
                  const SP::IO::FreeSurfer_surface_info& freesurfer_info, const Settings& settings,
                  const std::string& stamp, std::string& error)
{
  const std::string temporary = path + ".partial." + std::to_string(::getpid());
  {
    std::lock_guard<std::mutex> lock(temporary_file_mutex);
    temporary_file = temporary;
  }
  struct Forget_temporary
  {
    ~Forget_temporary()
    {
      std::lock_guard<std::mutex> lock(temporary_file_mutex);
      temporary_file.clear();
    }
  } forget_temporary;
  const std::string format = output_format(path);
  if(format == "gifti")
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_GIFTI
    if(!SP::IO::write_GIfTI_surface(temporary, sphere, faces, settings.float64, settings.radius, error,
                                    {{"spherical_parameterize", stamp}}))
    {
      std::remove(temporary.c_str());
      return false;
    }
#else
    error = "this program was built without the GIFTI library";
    return false;
#endif
  }
  else if(format == "freesurfer")
  {
    std::ofstream out(temporary, std::ios::binary);
    if(!out)
    {
      error = "cannot open '" + temporary + "' for writing";
      return false;
    }
    SP::IO::FreeSurfer_surface_info info = freesurfer_info; // the input's tags (volume geometry) go on
    info.created_by = "created by " + stamp;
    const bool written = SP::IO::write_FreeSurfer_surface(out, sphere, faces, info, settings.radius);
    out.flush();
    if(!written || !out)
    {
      error = "writing '" + temporary + "' failed";
      std::remove(temporary.c_str());
      return false;
    }
  }
  else
  {
    std::ofstream out(temporary);
    if(!out)
    {
      error = "cannot open '" + temporary + "' for writing";
      return false;
    }
    out << std::setprecision(17);
    if(format == "ply")
    {
      out << "ply\nformat ascii 1.0\ncomment " << stamp << "\nelement vertex " << sphere.size()
          << "\nproperty double x\nproperty double y\n"
          << "property double z\nelement face " << faces.size()
          << "\nproperty list uchar int vertex_indices\nend_header\n";
    }
    else
    {
      out << "OFF\n# " << stamp << "\n" << sphere.size() << ' ' << faces.size() << " 0\n";
    }
    // std::to_chars writes what `out << std::setprecision(17)` writes (%.17g), several times faster (a third of
    // bunny00's 0.045 s of writing went to iostream's formatting).
    const double r = settings.radius;
    std::string text;
    text.reserve(64 * sphere.size() + 32 * faces.size());
    char buffer[40];
    auto append_number = [&](auto value, auto... format) {
      const std::to_chars_result written = std::to_chars(buffer, buffer + sizeof(buffer), value, format...);
      text.append(buffer, written.ptr);
    };
    for(const Point& p : sphere)
    {
      append_number(r * p.x(), std::chars_format::general, 17);
      text += ' ';
      append_number(r * p.y(), std::chars_format::general, 17);
      text += ' ';
      append_number(r * p.z(), std::chars_format::general, 17);
      text += '\n';
    }
    for(const auto& f : faces)
    {
      append_number(f.size());
      for(std::size_t i : f)
      {
        text += ' ';
        append_number(i);
      }
      text += '\n';
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if(!out)
    {
      error = "writing '" + temporary + "' failed";
      std::remove(temporary.c_str());
      return false;
    }
  }
  if(std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    error = "cannot move '" + temporary + "' to '" + path + "'";
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

} // namespace

int main(int argc, char** argv)
{
  const Clock::time_point start = Clock::now();
  start_signal_watcher(); // first: before any other thread exists
  const Settings settings = parse_arguments(argc, argv);
  const std::string& input = settings.input;
  const std::string output = settings.output.empty() ? default_output(input) : settings.output;
  explain_missing_input(input);
  {
    std::error_code error;
    if(std::filesystem::exists(output, error) && std::filesystem::equivalent(input, output, error))
      usage_error("the output '" + output + "' is the input file", "choose another name with -o FILE");
  }
  Run_figures run;
  run.input = input;
  run.weights = settings.weights_name;
  run.tolerance = settings.tolerance;
  run.criterion = settings.criterion;
  Progress_line progress(!settings.quiet, start);

  // An output that cannot be written is found before the work, not after it.
  std::string output_error;
  if(!can_write_next_to(output, output_error))
  {
    std::cerr << "error: " << output_error << "\n";
    return EXIT_IO;
  }

  // Read as a polygon soup first: a soup can hold what a halfedge structure refuses, so the error is precise.
  progress.phase("reading " + input);
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  SP::IO::FreeSurfer_surface_info freesurfer_info; // kept for a FreeSurfer output (its volume geometry)
  const SP::IO::File_read read = read_input(input, points, faces, freesurfer_info);
  if(!read)
  {
    progress.clear();
    std::cerr << "error: " << read.message << " [" << SP::IO::get_file_status_name(read.status) << "]\n";
    return EXIT_IO;
  }
  progress.phase("checking " + std::to_string(points.size()) + " vertices, " + std::to_string(faces.size()) + " faces");
  const SP::Input_check check = SP::check_polygon_soup(points, faces);
  run.read_seconds = seconds_since(start);
  if(!check)
  {
    progress.clear();
    std::cerr << "error: " << input << ": " << check.message << " [" << SP::get_error_name(check.status) << "]\n";
    if(settings.json)
    {
      SP::Result rejected;
      rejected.status = check.status;
      rejected.message = check.message;
      rejected.number_of_vertices = points.size();
      rejected.number_of_faces = faces.size();
      run.total_seconds = seconds_since(start);
      print_json(std::cout, rejected, run);
    }
    return EXIT_BAD_INPUT;
  }
  progress.phase("building the halfedge mesh");
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);

  const std::string fingerprint = input_fingerprint(points, faces);
  if(!settings.overwrite && std::filesystem::exists(output))
  {
    progress.phase("certifying the existing " + output);
    Written_figures kept;
    const std::string reason = reason_not_to_keep(output, mesh, faces, fingerprint, settings, kept);
    if(reason.empty())
    {
      SP::Result done;
      done.status = SP::Error_code::OK;
      done.message = "Kept: the output already answers this request (a successful run with these settings, from this "
                     "input) and passes the certificate as stored; --overwrite maps again";
      done.number_of_vertices = points.size();
      done.number_of_faces = faces.size();
      done.bijective = true;
      done.flipped_faces = 0;
      done.total_signed_area = kept.total_signed_area;
      done.admissible_weights = settings.admissible;
      run.output = output;
      run.skipped = true;
      run.written = kept;
      run.total_seconds = seconds_since(start);
      progress.clear();
      if(settings.json)
        print_json(std::cout, done, run);
      else if(!settings.quiet)
        print_text(std::cout, done, run);
      return EXIT_OK;
    }
    progress.clear();
    if(!settings.quiet)
      std::cerr << "note: mapping again: the existing '" << output << "' is not kept: " << reason << "\n";
  }

  auto sphere_map = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", Point(0, 0, 0)).first;
  // The first report comes after stage 1: from then on a stop signal keeps the best map.
  auto report = [&progress](const SP::Progress& p) {
    int expected = SETTING_UP;
    run_phase.compare_exchange_strong(expected, ITERATING);
    return progress(p) && stop_signal.load() == 0;
  };
  const auto parameters = SP::parameters::combine(
      SP::parameters::weighting(settings.weighting), SP::parameters::tolerance(settings.tolerance),
      SP::parameters::max_seconds(settings.max_seconds), SP::parameters::metis_seed(settings.seed),
      SP::parameters::max_gauss_seidel_sweeps(settings.gauss_seidel_sweeps >= 0
                                                  ? std::size_t(settings.gauss_seidel_sweeps)
                                                  : SP::default_max_gauss_seidel_sweeps),
      SP::parameters::preserve_bijectivity(settings.backtracking), SP::parameters::nonlinear_solver(settings.solver),
      SP::parameters::progress_callback(report), SP::parameters::admissible_weights(settings.admissible),
      SP::parameters::hold_weights(settings.hold),
      SP::parameters::least_distortion(settings.least_distortion),
      SP::parameters::multilevel(settings.multilevel), CGAL::parameters::verbose(settings.verbose),
      SP::parameters::convergence_test(settings.criterion == "paper" ? SP::Convergence_test::PAPER_RESIDUAL
                                                                     : SP::Convergence_test::IMBALANCE));
  progress.phase("input checks, then stage 1/3, initial guess");
  const Clock::time_point map_start = Clock::now();
  // The two disks of stage 1 at the same time where TBB is linked (twice as fast on large meshes); the map does not
  // depend on it.
  using Concurrency = CGAL::Parallel_if_available_tag;
  const SP::Result result =
      settings.sparse_lu ? SP::spherical_parameterize<Concurrency>(
          mesh, sphere_map,
          SP::parameters::combine(parameters,
                                  CGAL::parameters::sparse_linear_solver(SP::Sparse_LU_disk_solver_traits())))
                         : SP::spherical_parameterize<Concurrency>(mesh, sphere_map, parameters);
  run.map_seconds = seconds_since(map_start);
  start_writing_phase();

  const bool has_map = result.number_of_vertices > 0 && result.residual >= 0.;
  if(has_map)
  {
    progress.phase("writing " + output);
    const Clock::time_point write_start = Clock::now();
    // What users compare tools by: the corners' angle error and the spread of the area ratios, only where it is
    // printed. Measured on a thread of its own while the map is written and certified as written (both only read the
    // mesh and the map): about 2% of the whole process on 3.3M faces.
    std::future<SP::Spherical_distortion> distortion;
    if(settings.json || !settings.quiet)
      distortion = std::async(std::launch::async, [&mesh, &sphere_map]() {
        return SP::measure_spherical_distortion(mesh, sphere_map);
      });
    std::vector<Point> sphere(points.size());
    for(Mesh::Vertex_index v : mesh.vertices())
      sphere[static_cast<std::size_t>(v)] = sphere_map[v];
    std::string error;
    Run_stamp stamp;
    stamp.status = SP::get_error_name(result.status);
    stamp.weights = settings.weights_name;
    stamp.admissible = settings.admissible;
    stamp.hold = settings.hold;
    stamp.least_distortion = settings.least_distortion ? least_distortion_version : 0;
    stamp.criterion = settings.criterion;
    stamp.tolerance = settings.tolerance;
    stamp.precision = output_precision(output_format(output), settings);
    stamp.radius = settings.radius;
    stamp.input = fingerprint;
    if(!write_sphere(output, sphere, faces, freesurfer_info, settings, format_stamp(stamp), error))
    {
      if(distortion.valid())
        distortion.wait();
      progress.clear();
      std::cerr << "error: " << error << "\n";
      return EXIT_IO;
    }
    run.output = output;
    run.written = certify_as_written(mesh, sphere, output_format(output), settings);
    run.write_seconds = seconds_since(write_start);
    if(distortion.valid())
    {
      run.distortion = distortion.get();
      run.has_distortion = true;
    }
  }
  run.total_seconds = seconds_since(start);
  progress.clear();
  if(settings.json)
    print_json(std::cout, result, run);
  else if(!settings.quiet)
    print_text(std::cout, result, run);
  std::cout << std::flush;

  if(!has_map)
  {
    std::cerr << "error: " << result.message << " [" << SP::get_error_name(result.status) << "]\n";
    return result.status == SP::Error_code::OK ? EXIT_NOT_SOLVED : EXIT_BAD_INPUT;
  }
  if(result.status == SP::Error_code::OK && run.written.certified && !run.written.bijective)
  {
    std::cerr << "error: the map is certified in double precision, but the coordinates as written ("
              << run.written.precision << ", radius " << run.written.radius << ") fold "
              << plural(run.written.flipped_faces, "triangle")
              << ": write .off or .ply (17 digits), or .gii with --float64\n";
    return EXIT_NOT_SOLVED;
  }
  if(result.status != SP::Error_code::OK)
  {
    if(result.status == SP::Error_code::CANCELLED && stop_signal.load() != 0)
      std::cerr << "error: interrupted (" << signal_name(stop_signal.load()) << ") [CANCELLED]\n";
    else
      std::cerr << "error: " << result.message << " [" << SP::get_error_name(result.status) << "]\n";
    std::cerr << "       the best map found is written to '" << output << "'\n";
    return EXIT_NOT_SOLVED;
  }
  return EXIT_OK;
}
