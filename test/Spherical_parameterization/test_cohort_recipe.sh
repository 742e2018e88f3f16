#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# The cohort recipe of the manual: GNU parallel over a folder of surfaces, one job killed midway (SIGTERM, as a
# scheduler sends it), then the same recipe run again. Every output must be certified, nothing half-written, and
# nothing redone that was done. Also: the Slurm array script on one task, and gather_runs.py over the logs.
# Usage: test_cohort_recipe.sh TOOL SHARED_MESHES BUNNY COHORT_SCRIPTS_DIR SCRATCH
tool=$1 shared=$2 bunny=$3 scripts=$4 scratch=$5
command -v parallel > /dev/null || { echo "GNU parallel is not installed (Debian package 'parallel'): not tested"; exit 77; }
rm -rf "$scratch" && mkdir -p "$scratch/surfaces" "$scratch/spheres" && cd "$scratch" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

cp "$bunny" surfaces/bunny.off
cp "$shared/npm_bunny.off" "$shared/trimesh_fuze.off" "$shared/c3d_fandisk.off" surfaces/
cp "$shared/formats/lh.fsavg5.pial" surfaces/lh.fsavg5.pial      # a FreeSurfer surface among OFF files
cp "$shared/c3d_igea.off" surfaces/big_igea.off                 # about 6 s: the job that gets killed
recipe() {  # the manual's GNU parallel line, with the tool's path
  parallel --jobs 2 "'$tool' {} -o spheres/{/.}_sphere.off --max-seconds 600 --json -q" ::: surfaces/* >> runs.jsonl
}

# 1. The recipe, with the long job killed once it has run for 2 s.
recipe 2> run1.err &
recipe_pid=$!
for _ in $(seq 200); do pgrep -f "big_igea.off -o" > /dev/null && break; sleep 0.05; done
sleep 2
pkill -TERM -f "big_igea.off -o" || fail "the long job was not running after 2 s"
wait $recipe_pid
first=$?
[ "$first" = 1 ] || fail "first run: GNU parallel should report exactly one failed job, got exit $first"
ls spheres/*.partial.* 2> /dev/null && fail "half-written files after the kill"
stamp_of() { head -c 400 "$1" | grep -a -o 'status=[A-Z_]*' | head -1; }
if [ -e spheres/big_igea_sphere.off ]; then
  [ "$(stamp_of spheres/big_igea_sphere.off)" = "status=CANCELLED" ] || fail "the killed job's map is not marked CANCELLED"
fi
done_files="spheres/bunny_sphere.off spheres/npm_bunny_sphere.off spheres/trimesh_fuze_sphere.off spheres/c3d_fandisk_sphere.off spheres/lh.fsavg5_sphere.off"
for f in $done_files; do [ "$(stamp_of "$f")" = "status=OK" ] || fail "$f: not written by a successful run"; done
before=$(stat -c '%n %i %Y.%y' $done_files)

# 2. The same recipe again: only the killed surface is mapped; the others are certified again and kept.
recipe 2> run2.err || fail "second run: exit $? ($(cat run2.err))"
after=$(stat -c '%n %i %Y.%y' $done_files)
[ "$before" = "$after" ] || fail "a finished output was rewritten by the re-run"
[ "$(stamp_of spheres/big_igea_sphere.off)" = "status=OK" ] || fail "the killed surface was not mapped again"
ls spheres/*.partial.* 2> /dev/null && fail "half-written files after the re-run"

# 3. The Slurm array script on one task (no Slurm needed), then a third pass: everything kept, nothing mapped.
mkdir -p slurm && cp "$bunny" slurm/bunny.off && printf '%s\n' slurm/bunny.off > list.txt
SLURM_ARRAY_TASK_ID=1 SPHERICAL_PARAMETERIZE="$tool" bash "$scripts/slurm_array.sh" list.txt > slurm.jsonl 2> slurm.err
[ $? = 0 ] && [ -s slurm/bunny_sphere.off ] || fail "slurm_array.sh: $(cat slurm.err)"
recipe 2> run3.err || fail "third run: exit $?"
/usr/bin/python3 - runs.jsonl slurm.jsonl <<'PY' || failures=$((failures + 1))
import json, sys
runs = [json.loads(line) for line in open(sys.argv[1])]
names = ["bunny", "npm_bunny", "trimesh_fuze", "c3d_fandisk", "lh.fsavg5", "big_igea"]
for name in names:
    mine = [r for r in runs if r["output"] == "spheres/%s_sphere.off" % name]
    made = [r for r in mine if not r["skipped"]]
    kept = [r for r in mine if r["skipped"]]
    if name == "big_igea":
        # mapped at most twice (the killed run prints its line only if it was stopped during the iterations)
        assert 1 <= len(made) <= 2 and made[-1]["status"] == "OK" and len(kept) == 1, (name, mine)
        assert all(r["status"] == "CANCELLED" for r in made[:-1]), (name, mine)
    else:
        assert len(made) == 1 and made[0]["status"] == "OK" and len(kept) == 2, (name, mine)
    assert all(r["status"] == "OK" and r["bijective"] and r["flipped_faces"] == 0 for r in kept), (name, kept)
slurm = [json.loads(line) for line in open(sys.argv[2])]
assert len(slurm) == 1 and slurm[0]["status"] == "OK", slurm
print("ok: cohort recipe: %d runs logged, every output certified, nothing redone after the kill" % len(runs))
PY
# gather_runs.py: one row per surface, every one OK, the figures of the run that made it.
/usr/bin/python3 "$scripts/gather_runs.py" runs.jsonl > table.tsv 2> gather.err || fail "gather_runs.py: $(cat gather.err)"
[ "$(wc -l < table.tsv)" = 7 ] || fail "gather_runs.py: expected a header and 6 rows: $(cat table.tsv)"
grep -q "6 surface(s): OK 6" gather.err || fail "gather_runs.py summary: $(cat gather.err)"
awk -F'\t' 'NR > 1 && ($3 != "OK" || $7 == "" || $11 != "True") { exit 1 }' table.tsv || fail "gather_runs.py rows: $(cat table.tsv)"
# A map certified in double precision whose float32 output folds a triangle (exit 1, JSON "written": {"bijective":
# false}, as man.off to FreeSurfer does) is not counted as OK.
printf '%s\n' '{"format": "spherical_parameterize/1", "input": "man.off", "output": "man.sphere", "status": "OK", "success": false, "skipped": false, "vertices": 17495, "faces": 34986, "weights": "uniform", "max_imbalance": 1e-9, "flipped_faces": 0, "written": {"format": "freesurfer", "precision": "float32", "radius": 1, "flipped_faces": 1, "bijective": false}, "seconds": {"read": 0.1, "map": 1.0, "write": 0.1, "total": 1.2}}' > folded.jsonl
/usr/bin/python3 "$scripts/gather_runs.py" folded.jsonl > folded.tsv 2> folded.err && fail "gather_runs.py: a folded float32 output counted as OK"
grep -q "OK_FOLDED_AS_WRITTEN" folded.tsv || fail "gather_runs.py: the folded output's status: $(cat folded.tsv)"
[ $failures = 0 ] && echo "ok: cohort recipe (GNU parallel, a killed job, re-runs), Slurm array script, gather_runs.py"
exit $((failures > 0))
