#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# Every closed genus-0 mesh of CGAL's sample data (data/meshes of libcgal-dev's data.tar.gz: the 48 that pass the
# input checks) and of ../shared/meshes, mapped by the command line, one process each, default settings unless
# options are given (they are passed on, e.g. `-w cotangent` or `--start two_disks`). Meshes the input checks
# refuse (open, genus > 0, ...) are counted and left out. Prints a Markdown table (time is the whole process).
# Usage: scripts/run_corpus_table.sh [command-line options...]     Never run by the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh spherical_parameterize >/dev/null
build="${BUILD_DIR:-build}"
tool="$build/examples/Spherical_parameterization/spherical_parameterize"
data="$build/cgal_data_all"
if [ ! -d "$data/data/meshes" ]; then
  mkdir -p "$data"
  tar xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$data" data/meshes
fi
out="$build/corpus_table"
mkdir -p "$out"
runs="$out/runs.jsonl"
: > "$runs"
for mesh in "$data"/data/meshes/*.off ../shared/meshes/*.off; do
  start=$(date +%s.%N)
  status=0
  "$tool" "$mesh" -o "$out/sphere.off" --overwrite --json -q "$@" > "$out/run.json" 2>/dev/null || status=$?
  end=$(date +%s.%N)
  [ "$status" = 2 ] && continue  # refused by the input checks: not a closed genus-0 mesh
  if [ -s "$out/run.json" ]; then
    python3 -c 'import json,sys; o=json.load(open(sys.argv[1])); o["process_seconds"]=float(sys.argv[3])-float(sys.argv[2]); print(json.dumps(o))' \
      "$out/run.json" "$start" "$end" >> "$runs"
  else
    echo "{\"input\": \"$mesh\", \"status\": \"EXIT_$status\"}" >> "$runs"
  fi
done
python3 - "$runs" <<'TABLE'
import json, os, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
print("| mesh | vertices | faces | status | max imbalance | Newton steps | levels | seconds |")
print("|---|---:|---:|---|---:|---:|---|---:|")
for o in rows:
    levels = " -> ".join("%d:%d" % (l["vertices"], l["newton_steps"]) for l in o.get("levels", []))
    newton = o.get("stages", {}).get("newton", {}).get("iterations", "")
    print("| %s | %s | %s | %s | %s | %s | %s | %.2f |" % (os.path.basename(o["input"]), o.get("vertices", ""), o.get("faces", ""),
          o["status"], "%.1e" % o["max_imbalance"] if o.get("max_imbalance") is not None else "-", newton, levels,
          o.get("process_seconds", float("nan"))))
ok = sum(o["status"] == "OK" for o in rows)
times = sorted(o.get("process_seconds", 1e9) for o in rows)
print("\n%d meshes, %d OK; slowest %.2f s; %d under 1 s" % (len(rows), ok, times[-1] if times else 0, sum(t < 1 for t in times)))
TABLE
