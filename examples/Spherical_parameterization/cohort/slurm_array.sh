#!/bin/bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# One surface per Slurm array task: the cohort recipe of the manual on a cluster.
#
#   find subjects -path '*/surf/?h.white' > surfaces.txt
#   mkdir -p logs && sbatch --array=1-$(wc -l < surfaces.txt)%100 slurm_array.sh surfaces.txt
#   cat logs/*.jsonl | python3 gather_runs.py > table.tsv
#
# Re-submitting the same array after a failure or a time-out redoes only what is missing or unfinished: an output
# that is a certified answer to the same request is kept (exit 0 at once).
#SBATCH --job-name=spherical_parameterize
#SBATCH --time=00:30:00
#SBATCH --cpus-per-task=1
#SBATCH --mem=4G
#SBATCH --output=logs/%A_%a.jsonl
#SBATCH --error=logs/%A_%a.err
# Slurm sends SIGTERM at the time limit: the iterations stop and the best map so far is written (exit 1). The time
# budget below ends the run first, with its figures, leaving Slurm's limit as the safety net.
surface=$(sed -n "${SLURM_ARRAY_TASK_ID:?run under sbatch --array, or set it}p" "${1:?a file listing one surface per line}")
[ -n "$surface" ] || { echo "no line ${SLURM_ARRAY_TASK_ID} in $1" >&2; exit 4; }
# FreeSurfer inputs are written next to them as lh.white.sphere; pass -o for other names and formats.
"${SPHERICAL_PARAMETERIZE:-spherical_parameterize}" "$surface" --max-seconds 1500 --json -q
status=$?
# 0 certified (or kept), 1 not converged or not bijective (the best map is written), 2 invalid mesh, 3 file error,
# 4 usage error, 128 + signal: stopped before the iterations (nothing written).
case $status in
  0) ;;
  2) echo "$surface: not a closed genus-0 triangle mesh (see the JSON line)" >&2 ;;
  *) echo "$surface: exit $status (see the JSON line and logs)" >&2 ;;
esac
exit $status
