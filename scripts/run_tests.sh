#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# The tests: set up, build everything, run ctest (without the cases labelled "slow"), the sanitized unit tests and
# the fuzzer, print the known failures.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-build}"
status=0
(cd "$build" && ctest --output-on-failure -j2 -LE slow --timeout 600) || status=$?
# The small unit tests under ASan + UBSan, and the fuzzer for FUZZ_SECONDS (60 by default), both built with clang.
if [ "${SANITIZERS:-1}" != 0 ]; then
  echo
  echo "== Sanitizers and fuzzing (scripts/run_sanitizers.sh; SANITIZERS=0 leaves them out)"
  bash scripts/run_sanitizers.sh "${FUZZ_SECONDS:-60}" || status=1
fi
echo
echo "== Known failures (kept in the tests, see test/Spherical_parameterization/known_failures.txt):"
grep -v '^#' test/Spherical_parameterization/known_failures.txt | grep . || echo "   none"
exit $status
