#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# Installs what is missing (Debian 12, as root or with sudo), configures and builds into ${BUILD_DIR:-build}.
# Usage: scripts/setup.sh [cmake build targets...]   (no target: everything)
set -euo pipefail
cd "$(dirname "$0")/.."

# TBB is optional for users; the tests check that CGAL::Parallel_tag gives the same map as Sequential_tag.
# Doxygen builds the manual's reference pages; ctest checks them for warnings (doc.manual, about a second).
bash scripts/install_missing.sh cmake g++ libcgal-dev libcgal-demo libeigen3-dev libmetis-dev libboost-dev libgtest-dev ccache zlib1g-dev libtbb-dev doxygen \
  libgiftiio-dev python3-nibabel pybind11-dev python3-dev python3-numpy parallel

build="${BUILD_DIR:-build}"

# CGAL's sample meshes (the paper's triceratops, bunny00, man...) ship in libcgal-demo's data.tar.gz: the 48 closed
# genus-0 ones of the test corpus, and nefertiti (an open mesh for the tests of bad input).
data=/usr/share/doc/libcgal-dev/data.tar.gz
list=test/Spherical_parameterization/cgal_sample_meshes.txt
if [ -f "$data" ] && [ ! -f "$build/cgal_data/data/meshes/tripod.off" ]; then
  mkdir -p "$build/cgal_data"
  tar xzf "$data" -C "$build/cgal_data" data/meshes/nefertiti.off $(grep -v '^#' "$list" | sed 's|^|data/meshes/|')
fi

# Configured after the extraction: the corpus cases are made from the meshes present at configure time.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null

# Two jobs at most: one CGAL + Eigen translation unit needs up to 3 GB and a minute or more.
start=$(date +%s)
if [ $# -gt 0 ]; then
  cmake --build "$build" -j2 --target "$@"
else
  cmake --build "$build" -j2
fi
echo "== build: $(( $(date +%s) - start )) s"
