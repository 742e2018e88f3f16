#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# The unit tests under AddressSanitizer + UndefinedBehaviorSanitizer on the small meshes, then the libFuzzer
# target for a bounded time. Both built with clang into ${SANITIZE_BUILD_DIR:-build-sanitize}; clang and its
# runtime are installed when missing (Debian 12: clang-14, libclang-rt-14-dev). Run scripts/setup.sh first (as
# scripts/run_tests.sh does): it installs the other packages and extracts CGAL's sample meshes.
# Usage: scripts/run_sanitizers.sh [fuzz seconds, default 60]
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds=${1:-60}
build="${SANITIZE_BUILD_DIR:-build-sanitize}"

bash scripts/install_missing.sh clang-14 libclang-rt-14-dev zlib1g-dev

start=$(date +%s)
# -O1 keeps the sanitizers' reports readable and the build and run fast; assertions stay on (no NDEBUG). Line tables
# only: the reports keep their files and lines, and the unit tests' translation unit compiles in 272 s instead of 336 s
# (3.7 GB instead of 4.8 GB, an object of 43 MB instead of 144 MB): it is the sanitizer build's longest step.
flags="-O1 -gline-tables-only -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined"
CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DSPHERICAL_PARAMETERIZATION_BUILD_FUZZER=ON \
  -DSPHERICAL_PARAMETERIZATION_BUILD_EXAMPLES=OFF -DSPHERICAL_PARAMETERIZATION_BUILD_BENCHMARKS=OFF \
  -DSPHERICAL_PARAMETERIZATION_CGAL_DATA="$PWD/${BUILD_DIR:-build}/cgal_data/data/meshes" >/dev/null
# One unit-test binary and the fuzzer only: each sanitized CGAL + Eigen translation unit costs minutes. Their common
# target builds both at once.
cmake --build "$build" -j2 --target unit_tests_and_fuzzer
echo "== sanitizer build: $(( $(date +%s) - start )) s"

# The small cases: everything but the tests that map meshes of thousands of vertices several times over.
status=0
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
start=$(date +%s)
"$build/test/Spherical_parameterization/test_spherical_parameterization" \
  --gtest_filter="${SANITIZE_TEST_FILTER:-CheckInput.*:ImbalanceLeastSquares.*:ConstrainedBalance.*:ReadPolygonSoup.*:TwoDiskPartition.TinyMeshes:InitialSphere.*:Certificate.*:SphericalParameterize.TinyMeshes:SphericalParameterize.ReportsInputErrorsAndWritesNothing:Inscribability.ProofOnlyWhereItHolds:SphericalParameterize.DegenerateGeometryZeroAreaCoincidentNeedleValence50:AssignWeights.ClampedWeightsAreFiniteAndCounted:SphericalParameterize.FuzzerFindings:SphericalParameterize.CadSlivers:SphericalParameterize.TinyCapsGiveTheBestIterateAndItsFigures:SphericalParameterize.InputUntouchedAfterSuccessAndAfterEveryKindOfFailure}" \
  || status=$?
echo "== sanitized unit tests: exit $status, $(( $(date +%s) - start )) s"

# Fuzzing: a corpus seeded with the small meshes of ../shared/meshes, every bad input under 64 KiB and what the
# fuzzer found before (test/Spherical_parameterization/fuzz_regressions).
# A fresh corpus each run, as on CI's fresh clone: a corpus kept from earlier runs grows until loading it takes
# the whole time budget.
corpus="$build/fuzz_corpus"
rm -rf "$corpus"
mkdir -p "$corpus"
for f in ../shared/meshes/*.off ../shared/meshes/bad_input/*.off test/Spherical_parameterization/fuzz_regressions/*.off; do
  [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && cp -f "$f" "$corpus/"
done
start=$(date +%s)
fuzz_status=0
"$build/test/Spherical_parameterization/fuzz_spherical_parameterization" "$corpus" -max_total_time="$fuzz_seconds" \
  -max_len=65536 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/" 2> "$build/fuzz.log" \
  || fuzz_status=$?
grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|stat::new_units_added)|Done [0-9]+ runs|ERROR|broken promise|SUMMARY" "$build/fuzz.log" || true
echo "== fuzzing: exit $fuzz_status, $(( $(date +%s) - start )) s (log: $build/fuzz.log; crashes as $build/crash-*)"
[ "$fuzz_status" -eq 0 ] || { tail -40 "$build/fuzz.log"; status=1; }
exit $status
