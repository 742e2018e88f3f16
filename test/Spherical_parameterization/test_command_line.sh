#!/usr/bin/env bash
# The command-line tool as a user meets it: exit codes, messages, and an output with the input's vertex order
# and face list. Usage: test_command_line.sh TOOL SHARED_MESHES BUNDLED_MESH SCRATCH_DIR
set -u
tool=$1; shared=$2; bunny=$3; scratch=$4
rm -rf "$scratch"; mkdir -p "$scratch"
failures=0
check() { # description, expected exit code, actual exit code
  if [ "$2" -ne "$3" ]; then echo "FAIL: $1 (exit $3, expected $2)"; failures=$((failures + 1)); else echo "ok: $1"; fi
}

"$tool" --help > "$scratch/help.txt"; check "--help" 0 $?
grep -q "Usage: spherical_parameterize" "$scratch/help.txt" || { echo "FAIL: --help text"; failures=$((failures + 1)); }

"$tool" "$bunny" -o "$scratch/bunny_sphere.off" -q; check "bundled bunny to OFF" 0 $?
"$tool" "$bunny" -o "$scratch/bunny_sphere.ply" -q; check "bundled bunny to PLY" 0 $?
# Same face list, same number of vertices, every vertex on the unit sphere, 17 significant digits.
python3 - "$bunny" "$scratch/bunny_sphere.off" <<'PY' || failures=$((failures + 1))
import sys
def read(path):
    tokens = open(path).read().split()
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
"$tool" "$scratch/does_not_exist.off" 2> /dev/null; check "missing input" 3 $?
"$tool" "$shared/bad_input/garbage.off" -o "$scratch/x.off" 2> /dev/null; check "garbage input" 3 $?
"$tool" "$shared/bad_input/empty.off" -o "$scratch/x.off" 2> /dev/null; check "empty input" 3 $?
"$tool" "$bunny" --weights nonsense 2> /dev/null; check "unknown weights" 4 $?
"$tool" "$bunny" --frobnicate 2> /dev/null; check "unknown option" 4 $?
"$tool" "$bunny" -q -o "$scratch/no/such/folder/out.off" 2> /dev/null; check "unwritable output" 3 $?
ls "$scratch/no/such/folder" > /dev/null 2>&1 && { echo "FAIL: half-written output"; failures=$((failures + 1)); }

echo "$failures failed"
[ "$failures" -eq 0 ]
