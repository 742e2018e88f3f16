#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# The main job: set up, build the command-line tool, map the bundled bunny onto the sphere and print the figures.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh spherical_parameterize
build="${BUILD_DIR:-build}"
input="${1:-examples/Spherical_parameterization/data/bunny.off}"
output="${2:-$build/bunny_sphere.off}"
# --overwrite: map and print the figures on every run, not only the first.
"$build/examples/Spherical_parameterization/spherical_parameterize" "$input" -o "$output" --overwrite
