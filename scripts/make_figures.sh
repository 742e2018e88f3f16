#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# Regenerates the manual's pictures, doc/Spherical_parameterization/fig/*.png, from real meshes:
#   stages_triceratops.png   the paper's Figure 1 (two halves, planar disks, initial sphere, final sphere)
#   weights_triceratops.png  the paper's Figure 2 (uniform, mean-value and cotangent weights)
#   weights_brain.png        the same on a brain hemisphere (the paper's Figure 3 uses a human)
# Installs what is missing (POV-Ray, the DejaVu font, pngquant; Debian packages), builds the target
# make_figure_meshes (not part of `all`), writes the meshes of each stage into ${BUILD_DIR:-build}/figures/,
# and renders them with POV-Ray.
# Usage: scripts/make_figures.sh [--render-only]   (--render-only: keep the meshes already written, render again)
set -euo pipefail
cd "$(dirname "$0")/.."

render_only=0
[ "${1:-}" = "--render-only" ] && render_only=1

bash scripts/install_missing.sh povray fonts-dejavu-core pngquant

build="${BUILD_DIR:-build}"
shared_meshes="${SHARED_MESHES:-../shared/meshes}"
scenes=doc/Spherical_parameterization/figure_sources
out=doc/Spherical_parameterization/fig
work="$build/figures"
mkdir -p "$work" "$out"

# Writes the POV-Ray include files of one mesh into $work/NAME; prints the figures of each weighting.
generate() {
  local name=$1 mesh=$2
  shift 2
  if [ $render_only -eq 1 ] && [ -f "$work/$name/final_cotangent.inc" ]; then return; fi
  [ -f "$mesh" ] || { echo "missing mesh: $mesh" >&2; exit 1; }
  echo "== $name: $mesh"
  mkdir -p "$work/$name"
  "$build/doc/Spherical_parameterization/figure_sources/make_figure_meshes" "$mesh" "$work/$name" "$@"
}

# Renders SCENE with the include files of NAME into $out/OUTPUT; 256 colours keep each PNG near 250 KB.
render() {
  local scene=$1 name=$2 output=$3
  local start=$SECONDS
  # The layout is 9.2 x 6 units (layout.inc): 1440 x 939 pixels.
  if ! povray +I"$scenes/$scene" +L"$scenes" +L"$work/$name" +O"$work/$output" +W1440 +H939 +A0.1 +FN -D -V \
       >"$work/$output.log" 2>&1; then
    cat "$work/$output.log" >&2
    exit 1
  fi
  pngquant 256 --speed 1 --strip --force --output "$out/$output" "$work/$output"
  echo "== $out/$output: $(( $(stat -c %s "$out/$output") / 1024 )) KB, rendered in $(( SECONDS - start )) s"
}

if [ $render_only -eq 0 ] || [ ! -x "$build/doc/Spherical_parameterization/figure_sources/make_figure_meshes" ]; then
  bash scripts/setup.sh make_figure_meshes
fi
# Triceratops: x runs from tail to head, y up; a brain's left hemisphere (RAS): seen from the left, z up.
generate triceratops "$build/cgal_data/data/meshes/triceratops.off" --stages --view-from 0,0,1 --up 0,1,0
generate brain "$shared_meshes/nilearn_fsavg5_pial_left.off" --view-from -1,0,0 --up 0,0,1

render stages.pov triceratops stages_triceratops.png
render weights.pov triceratops weights_triceratops.png
render weights.pov brain weights_brain.png
