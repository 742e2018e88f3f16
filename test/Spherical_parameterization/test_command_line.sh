#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# The command-line tool as a user meets it: exit codes, messages, and an output with the input's vertex order
# and face list. Usage: test_command_line.sh TOOL SHARED_MESHES BUNDLED_MESH SCRATCH_DIR CGAL_SAMPLE_MESHES
set -u
tool=$1; shared=$2; bunny=$3; scratch=$4; cgal_data=$5 # CGAL's sample meshes
rm -rf "$scratch"; mkdir -p "$scratch"
failures=0
check() { # description, expected exit code, actual exit code
  if [ "$2" -ne "$3" ]; then echo "FAIL: $1 (exit $3, expected $2)"; failures=$((failures + 1)); else echo "ok: $1"; fi
}
check_json() { # description, JSON file, a Python condition on its object o
  python3 -c "import json,sys; o=json.load(open(sys.argv[1])); assert $3, o" "$2" || { echo "FAIL: $1"; failures=$((failures + 1)); }
}

"$tool" --help > "$scratch/help.txt"; check "--help" 0 $?
grep -q "Usage: spherical_parameterize" "$scratch/help.txt" || { echo "FAIL: --help text"; failures=$((failures + 1)); }

"$tool" "$bunny" -o "$scratch/bunny_sphere.off" -q; check "bundled bunny to OFF" 0 $?
"$tool" "$bunny" -o "$scratch/bunny_sphere.ply" -q; check "bundled bunny to PLY" 0 $?
# Same face list, same number of vertices, every vertex on the unit sphere, 17 significant digits.
python3 - "$bunny" "$scratch/bunny_sphere.off" <<'PY' || failures=$((failures + 1))
import sys
def read(path):  # OFF, '#' comments allowed (the output's first comment records the run)
    tokens = " ".join(line.split("#")[0] for line in open(path)).split()
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    coords = tokens[4:4 + 3 * nv]
    rest = tokens[4 + 3 * nv:]
    faces, k = [], 0
    for _ in range(nf):
        d = int(rest[k]); faces.append(tuple(rest[k + 1:k + 1 + d])); k += 1 + d
    return nv, coords, faces
nv_in, _, faces_in = read(sys.argv[1])
nv_out, coords, faces_out = read(sys.argv[2])
assert nv_in == nv_out, "vertex count differs"
assert faces_in == faces_out, "face list differs"
values = [float(c) for c in coords]
for i in range(0, len(values), 3):
    r = (values[i] ** 2 + values[i + 1] ** 2 + values[i + 2] ** 2) ** 0.5
    assert abs(r - 1) < 1e-14, "vertex %d off the sphere" % (i // 3)
assert max(len(c.lstrip('-').replace('.', '').split('e')[0].lstrip('0')) for c in coords) >= 15, "too few digits"
print("ok: output keeps the vertex order and faces, on the unit sphere")
PY

"$tool" "$shared/bad_input/genus1_rocker-arm.off" -o "$scratch/x.off" 2> "$scratch/err.txt"; check "genus 1 rejected" 2 $?
grep -q "GENUS_NOT_ZERO" "$scratch/err.txt" || { echo "FAIL: genus message"; cat "$scratch/err.txt"; failures=$((failures + 1)); }
"$tool" "$shared/bad_input/nonmanifold_edges_simplify_brain.off" -o "$scratch/x.off" 2> "$scratch/err.txt"; check "non-manifold edges rejected" 2 $?
grep -q "NON_MANIFOLD_EDGE" "$scratch/err.txt" || { echo "FAIL: non-manifold message"; failures=$((failures + 1)); }
[ ! -e "$scratch/x.off" ] || { echo "FAIL: an output was written for a rejected mesh"; failures=$((failures + 1)); }
# Files that are not meshes: exit 3, the reader's status in the message, no output.
expect_file_error() { # description, input, status name
  "$tool" "$2" -q -o "$scratch/x.off" 2> "$scratch/err.txt"; check "$1" 3 $?
  grep -q "\[$3\]" "$scratch/err.txt" || { echo "FAIL: $1: no [$3] in: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
  [ ! -e "$scratch/x.off" ] || { echo "FAIL: $1: an output was written"; failures=$((failures + 1)); rm -f "$scratch/x.off"; }
}
expect_file_error "missing input" "$scratch/does_not_exist.off" CANNOT_OPEN
expect_file_error "a folder as input" "$scratch" CANNOT_OPEN
expect_file_error "garbage input" "$shared/bad_input/garbage.off" UNKNOWN_FORMAT
expect_file_error "empty input" "$shared/bad_input/empty.off" EMPTY_FILE
expect_file_error "truncated input" "$shared/bad_input/truncated_horse.off" TRUNCATED
printf 'ply\nformat ascii 1.0\nelement vertex 3\n' > "$scratch/ply_named.off"
expect_file_error "PLY text named .off" "$scratch/ply_named.off" UNKNOWN_FORMAT
printf 'solid nothing\nendsolid\n' > "$scratch/garbage.stl"
expect_file_error "an STL without facets" "$scratch/garbage.stl" EMPTY_FILE
printf 'this is not a mesh\n' > "$scratch/garbage.obj"
expect_file_error "OBJ garbage" "$scratch/garbage.obj" UNKNOWN_FORMAT
head -c 100000 "$shared/bad_input/large_holes_handles_dragon_vrip.off.gz" > "$scratch/cut.off.gz"
expect_file_error "truncated gzip" "$scratch/cut.off.gz" TRUNCATED
sed '5,$d' "$bunny" > "$scratch/cut_bunny.off"
expect_file_error "OFF cut after 2 vertices" "$scratch/cut_bunny.off" TRUNCATED

# Gzip input gives the same sphere as the plain file.
gzip -c "$bunny" > "$scratch/bunny.off.gz"
"$tool" "$scratch/bunny.off.gz" -q -o "$scratch/bunny_gz_sphere.off"; check "gzip input" 0 $?
cmp -s "$scratch/bunny_gz_sphere.off" "$scratch/bunny_sphere.off" || { echo "FAIL: gzip input gives another sphere"; failures=$((failures + 1)); }

# The 871k-face dragon (gzip) is refused within 2 s of CPU time (bash's time: wall, user, system seconds).
TIMEFORMAT='%R %U %S'
{ time "$tool" "$shared/bad_input/large_holes_handles_dragon_vrip.off.gz" -q -o "$scratch/x.off" 2> "$scratch/err.txt"; } 2> "$scratch/time.txt"
check "dragon (871k faces, gzip) refused" 2 $?
grep -q "\[HAS_BORDER\]" "$scratch/err.txt" || { echo "FAIL: dragon status: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
grep -q "407 boundary loop" "$scratch/err.txt" || { echo "FAIL: dragon message: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
read -r wall user system < "$scratch/time.txt"
echo "   dragon: $wall s wall, $user + $system s CPU"
awk "BEGIN { exit !($user + $system < 2.0) }" || { echo "FAIL: refusing the dragon took $user + $system s of CPU time"; failures=$((failures + 1)); }
[ ! -e "$scratch/x.off" ] || { echo "FAIL: an output was written for the dragon"; failures=$((failures + 1)); }

# The triakis tetrahedron has no balanced solution: exit 1, the status said, and the certified fallback written.
cat > "$scratch/triakis.off" <<'MESH'
OFF
8 12 0
1 1 1
1 -1 -1
-1 1 -1
-1 -1 1
0.5 0.5 -0.5
-0.5 0.5 0.5
0.5 -0.5 0.5
-0.5 -0.5 -0.5
3 0 1 4
3 1 2 4
3 2 0 4
3 0 2 5
3 2 3 5
3 3 0 5
3 0 3 6
3 3 1 6
3 1 0 6
3 1 3 7
3 3 2 7
3 2 1 7
MESH
"$tool" "$scratch/triakis.off" -o "$scratch/triakis_sphere.off" > "$scratch/out.txt" 2> "$scratch/err.txt"; check "triakis tetrahedron" 1 $?
grep -q "NO_BALANCED_SOLUTION" "$scratch/err.txt" || { echo "FAIL: triakis status: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
grep -q "certified bijective" "$scratch/err.txt" || { echo "FAIL: triakis fallback not certified: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
grep -q "flipped faces:   0" "$scratch/out.txt" || { echo "FAIL: triakis flips: $(cat "$scratch/out.txt")"; failures=$((failures + 1)); }
[ -s "$scratch/triakis_sphere.off" ] || { echo "FAIL: no fallback map written for the triakis tetrahedron"; failures=$((failures + 1)); }

"$tool" "$bunny" --weights nonsense 2> /dev/null; check "unknown weights" 4 $?
"$tool" "$bunny" --frobnicate 2> /dev/null; check "unknown option" 4 $?

# Outputs that cannot be written: exit 3 before any work, nothing left behind.
expect_output_error() { # description, output path
  "$tool" "$bunny" -q -o "$2" 2> "$scratch/err.txt"; check "$1" 3 $?
  grep -q "cannot write\|cannot open\|cannot move" "$scratch/err.txt" || { echo "FAIL: $1: message: $(cat "$scratch/err.txt")"; failures=$((failures + 1)); }
}
expect_output_error "output folder missing" "$scratch/no/such/folder/out.off"
ls "$scratch/no/such/folder" > /dev/null 2>&1 && { echo "FAIL: half-written output"; failures=$((failures + 1)); }
touch "$scratch/a_file"
expect_output_error "output folder is a file" "$scratch/a_file/out.off"
mkdir -p "$scratch/a_folder.off"
expect_output_error "output is a folder" "$scratch/a_folder.off"
expect_output_error "output in /proc (no file can be created)" "/proc/spherical_parameterize_test.off"
# A failed run leaves an existing output as it was, and no temporary file anywhere.
cp "$scratch/bunny_sphere.off" "$scratch/keep.off"
"$tool" "$shared/bad_input/genus1_rocker-arm.off" -q -o "$scratch/keep.off" 2> /dev/null; check "rejected mesh, existing output" 2 $?
cmp -s "$scratch/keep.off" "$scratch/bunny_sphere.off" || { echo "FAIL: a rejected run changed an existing output"; failures=$((failures + 1)); }
leftovers=$(find "$scratch" -name '*.partial*' | wc -l)
[ "$leftovers" -eq 0 ] || { echo "FAIL: $leftovers temporary files left"; failures=$((failures + 1)); }

# --- The user's side: help, JSON, progress, quiet, and a helpful message for each mistake. ---
expect_error() { # description, expected exit code, text stderr must contain, arguments...
  local what=$1 code=$2 text=$3; shift 3
  "$tool" "$@" > "$scratch/out.txt" 2> "$scratch/err.txt"
  local status=$?
  if [ "$status" -ne "$code" ]; then echo "FAIL: $what (exit $status, expected $code)"; failures=$((failures + 1)); return; fi
  if ! grep -qF -- "$text" "$scratch/err.txt"; then
    echo "FAIL: $what: stderr lacks '$text':"; cat "$scratch/err.txt"; failures=$((failures + 1)); return
  fi
  echo "ok: $what"
}

# --help names every option, shows examples, the JSON keys and the exit codes.
for text in --output --weights --tolerance --criterion --gauss-seidel-sweeps --solver --disk-solver --max-seconds --seed --no-backtracking --admissible-weights --hold-weights --least-distortion --quiet --json \
            --help Examples: "Exit status" max_tangential_residual mean_value cotangent; do
  grep -qF -- "$text" "$scratch/help.txt" || { echo "FAIL: --help does not mention $text"; failures=$((failures + 1)); }
done
"$tool" -h | cmp -s - "$scratch/help.txt" || { echo "FAIL: -h differs from --help"; failures=$((failures + 1)); }

expect_error "no input" 4 "no input mesh given"
expect_error "unknown option with a suggestion" 4 "did you mean '--tolerance'?" "$bunny" --tolerence 1e-7
expect_error "single-dash long option" 4 "did you mean '--seed'?" "$bunny" -seed 3
expect_error "missing value" 4 "-o needs a value" "$bunny" -o
expect_error "option instead of a value" 4 "got the option '-q'" "$bunny" -o -q
expect_error "not a number" 4 "expects a number, got 'abc'" "$bunny" -t abc
expect_error "negative tolerance" 4 "must be a positive finite number" "$bunny" --tolerance=-1
expect_error "infinite time budget" 4 "must be a positive finite number" "$bunny" --max-seconds inf
expect_error "seed not an integer" 4 "expects an integer, got '1.5'" "$bunny" --seed 1.5
expect_error "misspelled weights" 4 "did you mean 'cotangent'?" "$bunny" -w cotangnet
expect_error "unknown solver" 4 "one of: global, local" "$bunny" --solver newton
expect_error "flag with a value" 4 "--quiet takes no value" "$bunny" --quiet=yes
expect_error "unsupported output format" 4 "the output is .off, .ply, .gii or a FreeSurfer surface" "$bunny" -o "$scratch/sphere.obj"
expect_error "two inputs" 4 "more than one input file" "$bunny" "$bunny"
cp "$bunny" "$scratch/mine.off"
expect_error "output overwrites the input" 4 "is the input file" "$scratch/mine.off" -o "$scratch/mine.off"
cmp -s "$bunny" "$scratch/mine.off" || { echo "FAIL: the input was overwritten"; failures=$((failures + 1)); }
expect_error "misspelled input" 3 "did you mean '$scratch/mine.off'?" "$scratch/mine.of"
expect_error "folder as input" 3 "is a folder, not a mesh file" "$scratch"
expect_error "repeated option" 0 "--tolerance is given more than once" "$bunny" -q -t 1e-3 -t 1e-6 -o "$scratch/twice.off"

# --quiet: nothing on stdout or stderr on success.
"$tool" "$bunny" --quiet -o "$scratch/quiet.off" > "$scratch/out.txt" 2> "$scratch/err.txt"; check "--quiet run" 0 $?
if [ -s "$scratch/out.txt" ] || [ -s "$scratch/err.txt" ]; then echo "FAIL: --quiet printed something"; failures=$((failures + 1)); fi

# The text summary names the status, the flip count and the output.
"$tool" "$bunny" -o "$scratch/text.off" > "$scratch/out.txt" 2> /dev/null; check "text summary run" 0 $?
for text in "status:          OK" "flipped faces:   0" "written:         $scratch/text.off"; do
  grep -qF -- "$text" "$scratch/out.txt" || { echo "FAIL: summary lacks '$text'"; cat "$scratch/out.txt"; failures=$((failures + 1)); }
done

# --json on success (with --option=value): one object, every documented key, figures that agree.
"$tool" "$bunny" --json --tolerance=1e-6 --weights=uniform -o "$scratch/json.off" > "$scratch/good.json" 2> /dev/null
check "--json run" 0 $?
# --admissible-weights: cotangent weights made symmetric and positive, reported in the JSON.
"$tool" "$bunny" --json -w cotangent --admissible-weights -o "$scratch/admissible.off" > "$scratch/admissible.json" 2> /dev/null
check "--admissible-weights run" 0 $?
check_json "--admissible-weights figures" "$scratch/admissible.json" "o['admissible_weights'] is True and o['raised_weights'] > 0 and o['status'] == 'OK'"
# --hold-weights: on a mesh whose cotangent map is balanced nothing is held; the option is part of the request that
# an existing output must answer (a run without it maps again).
"$tool" "$bunny" --json -w cotangent --hold-weights -o "$scratch/held.off" > "$scratch/held.json" 2> /dev/null
check "--hold-weights run" 0 $?
check_json "--hold-weights figures" "$scratch/held.json" "o['status'] == 'OK' and o['held_weight_vertices'] == 0 and o['held_weight_parameter'] == 1 and o['requested_weights_max_imbalance'] is None"
"$tool" "$bunny" --json -w cotangent -o "$scratch/held.off" > "$scratch/held_again.json" 2> /dev/null
check "a run without --hold-weights on its output" 0 $?
check_json "an output of --hold-weights kept for a run without it" "$scratch/held_again.json" "o['skipped'] is False"
# --least-distortion (the default with cotangent weights): pcbvicebar's cotangent map does not converge
# (known_failures.txt, cotangent_balanced); with the option, the bijective map of least conformal distortion,
# stationary (exit 0); the option is part of the request an output answers.
"$tool" "$shared/oscad_pcbvicebar.off" --json -w cotangent -o "$scratch/least.off" > "$scratch/least.json" 2> /dev/null
check "--least-distortion run" 0 $?
check_json "--least-distortion figures" "$scratch/least.json" "o['status'] == 'OK' and o['least_distortion_map'] is True and o['balanced_map_folded'] is True and o['distortion_energy'] >= 1 and 0 <= o['max_distortion_stationarity'] <= 1e-6 and o['least_distortion_steps'] > 0 and o['distortion_vertices_at_rounding_floor'] >= 0 and o['max_imbalance'] > 1e-6 and o['bijective'] is True"
"$tool" "$shared/oscad_pcbvicebar.off" --json -w cotangent --least-distortion -o "$scratch/least.off" > "$scratch/least_again.json" 2> /dev/null
check "--least-distortion given again on its output" 0 $?
check_json "an output of the default kept for --least-distortion given" "$scratch/least_again.json" "o['skipped'] is True"
"$tool" "$shared/oscad_pcbvicebar.off" --json -w cotangent --no-least-distortion -o "$scratch/least.off" > "$scratch/least_without.json" 2> /dev/null
check "a run with --no-least-distortion on its output" 1 $?
check_json "an output of --least-distortion not kept for --no-least-distortion" "$scratch/least_without.json" "o['skipped'] is False and o['least_distortion_map'] is False and o['balanced_map_folded'] is False and o['distortion_energy'] is None"
# A balanced map of more angle error than the minimum (CGAL's dragknob, cotangent weights: 59.9 degrees against 3.0) is
# replaced, and says so.
"$tool" "$cgal_data/dragknob.off" --json -w cotangent -o "$scratch/dragknob.off" > "$scratch/dragknob.json" 2> /dev/null
check "a replaced balanced map" 0 $?
check_json "its figures" "$scratch/dragknob.json" "o['status'] == 'OK' and o['least_distortion_map'] is True and o['replaced_balanced_map_distortion'] > 1.1 and o['distortion_energy'] < o['replaced_balanced_map_distortion'] and o['replaced_balanced_map_angle_error'] > 4 * o['distortion']['mean_angle_error_degrees'] and o['bijective'] is True"
check_json "and no figure of it otherwise" "$scratch/least_without.json" "o['replaced_balanced_map_distortion'] is None and o['replaced_balanced_map_angle_error'] is None"
# A balanced map of less angle error than the minimum stays (CGAL's cube-meshed: 1.65 degrees against 1.67).
"$tool" "$cgal_data/cube-meshed.off" --json -w cotangent -o "$scratch/cube_meshed.off" > "$scratch/cube_meshed.json" 2> /dev/null
check "a balanced map kept" 0 $?
check_json "its figures" "$scratch/cube_meshed.json" "o['status'] == 'OK' and o['least_distortion_map'] is False and o['max_imbalance'] <= 1e-6 and o['replaced_balanced_map_distortion'] is None and o['replaced_balanced_map_angle_error'] is None and o['least_distortion_from_balanced_map'] is False"
# --json on an invalid mesh: the same keys, the error status, no output, figures null.
"$tool" "$shared/bad_input/genus1_rocker-arm.off" --json -o "$scratch/bad.off" > "$scratch/bad.json" 2> /dev/null
check "--json on an invalid mesh" 2 $?
python3 - "$scratch/good.json" "$scratch/bad.json" "$scratch/json.off" "$bunny" <<'JSON_CHECK' || failures=$((failures + 1))
import json, math, os, sys
keys = {"format", "input", "output", "status", "success", "skipped", "message", "vertices", "faces", "weights", "criterion", "tolerance",
        "max_imbalance", "imbalance_percentile_99", "unbalanced_vertices", "vertices_at_rounding_floor", "vertices_below_precision", "regularized_tip_vertices",
        "held_weight_vertices", "held_weight_parameter", "requested_weights_max_imbalance",
        "least_distortion_map", "balanced_map_folded", "least_distortion_from_balanced_map", "replaced_balanced_map_distortion", "replaced_balanced_map_angle_error", "distortion_energy", "max_distortion_stationarity", "least_distortion_steps",
        "distortion_vertices_at_rounding_floor", "max_stationarity", "unstationary_vertices", "residual", "max_tangential_residual", "flipped_faces", "total_signed_area", "bijective",
        "distortion", "initial_flipped_faces", "uniform_initial_guess_fallback", "multilevel_fallback", "partition_retries", "partition_seed", "admissible_weights", "raised_weights", "clamped_weights",
        "rejected_moves", "separator_size",
        "cut_loop_length", "levels", "stages", "written", "seconds"}
good = json.load(open(sys.argv[1]))
bad = json.load(open(sys.argv[2]))
for name, o in (("good", good), ("bad", bad)):
    assert set(o) == keys, "%s: keys differ: %s" % (name, set(o) ^ keys)
    assert set(o["stages"]) == {"initial_guess", "gauss_seidel", "newton"}, name
    for s in o["stages"].values():
        assert set(s) == {"seconds", "iterations", "linear_iterations", "residual"}, name
    assert set(o["seconds"]) == {"read", "map", "write", "total"}, name
    assert o["format"] == "spherical_parameterize/1", name
assert good["status"] == "OK" and good["success"] is True and good["bijective"] is True, good
assert good["vertices"] == 1839 and good["faces"] == 3674, good
assert good["flipped_faces"] == 0 and good["criterion"] == "imbalance" and good["tolerance"] == 1e-6, good
assert 0 <= good["max_imbalance"] and good["unbalanced_vertices"] == 0, good
assert good["max_stationarity"] is None and good["unstationary_vertices"] is None, good  # uniform weights: symmetric
assert good["imbalance_percentile_99"] <= good["max_imbalance"], good
assert abs(good["total_signed_area"] - 4 * math.pi) < 1e-6, good
d = good["distortion"]
assert set(d) == {"mean_angle_error_degrees", "max_angle_error_degrees", "log_area_ratio_stddev"}, d
assert 0 < d["mean_angle_error_degrees"] <= d["max_angle_error_degrees"] < 180 and d["log_area_ratio_stddev"] > 0, d
assert bad["distortion"] is None, bad
# The angle error again, independently, from the input and the written output.
def read_off(path):
    words = [w for line in open(path) for w in line.split("#")[0].split()]
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    numbers = words[4:]
    points = [tuple(map(float, numbers[3 * i:3 * i + 3])) for i in range(nv)]
    rest = numbers[3 * nv:]
    faces = [tuple(map(int, rest[4 * k + 1:4 * k + 4])) for k in range(nf)]
    return points, faces
def corner_angles(p, f):
    out = []
    for t in f:
        for k in range(3):
            a, b, c = p[t[k]], p[t[(k + 1) % 3]], p[t[(k + 2) % 3]]
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            out.append(math.atan2(math.sqrt(sum(x * x for x in cross)), sum(u[i] * v[i] for i in range(3))))
    return out
mesh_points, mesh_faces = read_off(sys.argv[4])
sphere_points, sphere_faces = read_off(sys.argv[3])
assert sphere_faces == mesh_faces
errors = [abs(x - y) * 180 / math.pi for x, y in zip(corner_angles(mesh_points, mesh_faces), corner_angles(sphere_points, mesh_faces))]
assert abs(sum(errors) / len(errors) - d["mean_angle_error_degrees"]) < 1e-6 * d["mean_angle_error_degrees"], (sum(errors) / len(errors), d)
assert abs(max(errors) - d["max_angle_error_degrees"]) < 1e-6 * d["max_angle_error_degrees"], (max(errors), d)
assert good["output"] == sys.argv[3] and os.path.exists(good["output"]), good
assert abs(good["stages"]["newton"]["residual"] - good["residual"]) <= 1e-9 * good["residual"], good
assert good["seconds"]["total"] >= good["seconds"]["map"] > 0, good
assert bad["status"] == "GENUS_NOT_ZERO" and bad["success"] is False and bad["output"] is None, bad
assert bad["residual"] is None and bad["max_imbalance"] is None and bad["flipped_faces"] is None and "genus 1" in bad["message"], bad
assert not os.path.exists(os.path.join(os.path.dirname(sys.argv[3]), "bad.off"))
print("ok: --json objects (success and invalid mesh)")
JSON_CHECK

# Progress on a run longer than a second, stderr not a terminal: "[   t s] stage ..." lines, at most one a second.
# A tolerance no double-precision map reaches keeps the iterations going until the time budget (the paper's Res:
# the imbalance test holds every vertex to at most its rounding floor, which is reached), on a mesh large enough
# (50k vertices) that the stagnation rules do not end the run first.
"$tool" "$shared/oded_koala.off" -o "$scratch/progress.off" --criterion paper -t 1e-300 --max-seconds 4 > /dev/null 2> "$scratch/progress.txt"
python3 - "$scratch/progress.txt" <<'PROGRESS_CHECK' || failures=$((failures + 1))
import re, sys
text = open(sys.argv[1]).read()
lines = [l for l in text.splitlines() if l.startswith("[")]
times = [float(re.match(r"\[\s*([0-9.]+) s\] ", l).group(1)) for l in lines]
assert len(lines) >= 2, "too few progress lines: %r" % text
assert any(re.search(r"stage 3/3, \w+ newton: iteration \d+, Res [0-9.e+-]+, \d+ non-positive faces", l) for l in lines), lines
assert all(b - a >= 0.99 for a, b in zip(times, times[1:])), "more than one line a second: %r" % times
assert "\r" not in text, "carriage returns outside a terminal"
print("ok: progress, %d lines at least a second apart" % len(lines))
PROGRESS_CHECK

# Ctrl-C during the iterations: the best map so far is written, exit 1, status CANCELLED. A 100k-face mesh, whose
# iterations last well beyond the 2 s (the small bunny's end by stagnation after about 2 s).
"$tool" "$shared/oded_koala.off" -o "$scratch/interrupted.off" --criterion paper -t 1e-300 --max-seconds 60 --json > "$scratch/interrupted.json" 2> "$scratch/err.txt" &
pid=$!
sleep 2
kill -INT $pid
wait $pid; check "Ctrl-C" 1 $?
grep -qF "interrupted (Ctrl-C)" "$scratch/err.txt" || { echo "FAIL: no interruption message"; cat "$scratch/err.txt"; failures=$((failures + 1)); }
python3 -c 'import json, sys; o = json.load(open(sys.argv[1])); assert o["status"] == "CANCELLED" and o["output"], o' \
    "$scratch/interrupted.json" && [ -s "$scratch/interrupted.off" ] || { echo "FAIL: interrupted run"; failures=$((failures + 1)); }

# SIGTERM, as job schedulers and `timeout` send it, at random moments (reading, stage 1, the iterations, writing) of
# runs on meshes of several sizes, uniform and mean-value weights: every run ends within 2 s, with either a complete
# map written (exit 1, CANCELLED; or exit 0 when it had just finished) or nothing at all (exit 143), and never a
# partial file left behind. Mean-value weights also with the default criterion (the minimization of the conformal
# distortion) and with --no-least-distortion, whose least-squares iterations send no progress report of their own (a
# SIGTERM there was once ignored until the end of the run); koala's go on for more than 30 s, so its signals, sent up
# to 4 s, fall in stage 1 or in those iterations.
python3 - "$tool" "$shared" "$scratch" <<'SIGTERM_CHECK' || failures=$((failures + 1))
import os, random, signal, subprocess, sys, time
tool, shared, scratch = sys.argv[1:4]
random.seed(int(os.environ.get("SIGTERM_SEED", "1")))
paper = ["--criterion", "paper", "-t", "1e-300"]
cases = [("trimesh_fuze", "uniform", paper, 2.5), ("npm_bunny", "mean_value", paper, 2.5),
         ("oded_springer", "mean_value", paper, 2.5), ("oded_springer", "uniform", paper, 2.5),
         ("c3d_horse", "uniform", paper, 2.5), ("oded_koala", "mean_value", paper, 2.5), ("oded_koala", "mean_value", [], 4.0),
         ("oded_koala", "mean_value", ["--no-least-distortion"], 4.0)]
problems = 0
outcomes = {}
for case, (mesh, weights, criterion, latest) in enumerate(cases):
    for attempt in range(4):
        out = os.path.join(scratch, "sigterm_%d_%s_%s_%d.off" % (case, mesh, weights, attempt))
        arguments = [tool, os.path.join(shared, mesh + ".off"), "-o", out, "-w", weights] + criterion + ["--max-seconds", "60", "-q"]
        process = subprocess.Popen(arguments, stderr=subprocess.PIPE)
        delay = random.uniform(0.0, latest)
        time.sleep(delay)
        sent = time.monotonic()
        process.send_signal(signal.SIGTERM)
        try:
            _, err = process.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill(); process.communicate()
            print("FAIL: %s %s: still running 10 s after SIGTERM (sent at %.2f s)" % (mesh, weights, delay)); problems += 1
            continue
        took = time.monotonic() - sent
        code = process.returncode
        leftovers = [f for f in os.listdir(scratch) if f.startswith(os.path.basename(out) + ".partial")]
        written = os.path.exists(out)
        complete = False
        if written:
            tokens = " ".join(line.split("#")[0] for line in open(out)).split()
            nv, nf = int(tokens[1]), int(tokens[2])
            complete = tokens[0] == "OFF" and len(tokens) == 4 + 3 * nv + 4 * nf
        # A signal in the first milliseconds, before main() has blocked it, takes its default action (killed by
        # SIGTERM, nothing written): that is a stop too.
        startup = code == -signal.SIGTERM and delay < 0.1 and not written
        good = took <= 2.0 and not leftovers and ((code in (0, 1) and complete) or (code == 128 + signal.SIGTERM and not written) or startup)
        outcomes[code] = outcomes.get(code, 0) + 1
        if not good:
            problems += 1
            print("FAIL: %s %s: SIGTERM at %.2f s: exit %d after %.2f s, written %s complete %s leftovers %s\n%s"
                  % (mesh, weights, delay, code, took, written, complete, leftovers, err.decode()[-400:]))
print("%s: SIGTERM at random moments, %d runs, exit codes %s" % ("ok" if problems == 0 else "FAIL", sum(outcomes.values()), outcomes))
sys.exit(1 if problems else 0)
SIGTERM_CHECK

# SIGTERM inside a long MINRES solve: bigbrain's first Newton step on its own mesh with cotangent weights is one MINRES
# solve of 99 iterations, about 5.5 s on the development machine, which starts about 0.4 s after --verbose reports its
# level of 40,960 vertices solved. MINRES asks after every iteration whether to stop: the run ends within 2 s with the
# best map written (exit 1, CANCELLED), where it once ended with nothing (exit 143: the solve outlasted the 1.2 s the
# command line waits).
python3 - "$tool" "$shared" "$scratch" <<'MINRES_STOP' || failures=$((failures + 1))
import json, os, signal, subprocess, sys, time
tool, shared, scratch = sys.argv[1:4]
out = os.path.join(scratch, "bigbrain_stopped.off")
process = subprocess.Popen([tool, os.path.join(shared, "bbw_tpl-bigbrain_hemi-L_desc-white.off"), "-o", out,
                            "-w", "cotangent", "--json", "--verbose"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
seen = []
for line in process.stderr:
    seen.append(line.decode())
    if line.startswith(b"multilevel: 163842 vertices") or line.startswith(b"multilevel: 40960 vertices"):
        break
time.sleep(2.0)
sent = time.monotonic()
process.send_signal(signal.SIGTERM)
stdout, err = process.communicate(timeout=60)
took = time.monotonic() - sent
report = json.loads(stdout.decode()) if stdout.strip() else {}
good = (seen[-1].startswith("multilevel: 40960") and process.returncode == 1 and took <= 2.0
        and report.get("status") == "CANCELLED" and os.path.exists(out) and os.path.getsize(out) > 0)
print("%s: SIGTERM 2 s into bigbrain's first Newton step (cotangent weights): exit %d after %.2f s, status %s"
      % ("ok" if good else "FAIL", process.returncode, took, report.get("status")))
if not good:
    print("".join(seen[-3:]) + err.decode()[-400:])
sys.exit(0 if good else 1)
MINRES_STOP

# Re-runs keep an output that is a certified answer to the same request, and map again otherwise.
kept="$scratch/kept.off"
"$tool" "$bunny" -o "$kept" -q; check "re-runs: first run" 0 $?
before=$(stat -c '%i %Y.%y' "$kept")
"$tool" "$bunny" -o "$kept" --json > "$scratch/kept.json" 2> "$scratch/kept.err"; check "re-runs: same request kept" 0 $?
[ "$before" = "$(stat -c '%i %Y.%y' "$kept")" ] || { echo "FAIL: a kept output was rewritten"; failures=$((failures + 1)); }
python3 -c 'import json, sys; o = json.load(open(sys.argv[1])); assert o["skipped"] is True and o["status"] == "OK" and o["bijective"] and o["flipped_faces"] == 0, o' \
  "$scratch/kept.json" || { echo "FAIL: JSON of a kept output"; failures=$((failures + 1)); }
"$tool" "$bunny" -o "$kept" -t 1e-3 --json | grep -q '"skipped": true' || { echo "FAIL: a looser tolerance keeps the output"; failures=$((failures + 1)); }
remapped() {  # description, then the tool's arguments: the run must map again (skipped false) and say why
  local what=$1; shift
  "$tool" "$@" --json > "$scratch/remap.json" 2> "$scratch/remap.err"
  if grep -q '"skipped": false' "$scratch/remap.json" && { [[ " $* " == *" --overwrite "* ]] || grep -q "is not kept: $what" "$scratch/remap.err"; }; then
    echo "ok: re-runs: mapped again ($what)"
  else
    echo "FAIL: re-runs: not mapped again ($what): $(cat "$scratch/remap.err")"; failures=$((failures + 1))
  fi
}
remapped "--overwrite" "$bunny" -o "$kept" --overwrite
remapped "it was made with other settings" "$bunny" -o "$kept" -t 1e-9
remapped "it was made from another input" "$shared/trimesh_fuze.off" -o "$kept"
remapped "it was made with other settings" "$bunny" -o "$kept" -w cotangent
# An output of the least-distortion rule before 2026-12-05 (stamp "least_distortion=yes", where balanced cotangent
# maps were kept that the minimization now replaces) is mapped again.
grep -q "least_distortion=2 " "$kept" && sed -i 's/least_distortion=2 /least_distortion=yes /' "$kept"
remapped "it was made with other settings" "$bunny" -o "$kept" -w cotangent
# A fold in the stored coordinates (two vertices swapped, faces and stamp untouched) fails the certificate.
"$tool" "$bunny" -o "$kept" -q --overwrite
python3 - "$kept" <<'SWAP'
import sys
lines = open(sys.argv[1]).read().split("\n")
lines[3], lines[4] = lines[4], lines[3]  # the first two vertices (after "OFF", the stamp, the counts)
open(sys.argv[1], "w").write("\n".join(lines))
SWAP
remapped "its coordinates fail the certificate" "$bunny" -o "$kept"
sed -i '2d' "$kept"  # the stamp removed: a file this program did not write (or wrote before stamps)
remapped "it was not written by this program" "$bunny" -o "$kept"

echo "$failures failed"
[ "$failures" -eq 0 ]
