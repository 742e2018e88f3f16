#!/usr/bin/env python3
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

"""Gathers the JSON lines of many spherical_parameterize runs (--json) into one table, one row per output.

  python3 gather_runs.py runs.jsonl [more.jsonl ...] > table.tsv      (or the lines on stdin)

A surface mapped several times (a re-run after a killed job) keeps its last run; a run that kept an existing output
("skipped": true) keeps the figures of the run that made it, when the logs hold that run. Lines that are not JSON
(a job killed before it printed) are counted and left out. Prints tab-separated values and a summary on stderr.
"""
import json
import sys

COLUMNS = ["input", "output", "status", "vertices", "faces", "weights", "max_imbalance", "flipped_faces", "map_seconds",
           "total_seconds", "kept"]


def records(streams):
    bad = 0
    for stream in streams:
        for line in stream:
            line = line.strip()
            if not line:
                continue
            try:
                record = json.loads(line)
            except ValueError:
                bad += 1
                continue
            if isinstance(record, dict) and record.get("format", "").startswith("spherical_parameterize/"):
                yield record
            else:
                bad += 1
    if bad:
        print("gather_runs: %d line(s) that are not a run's JSON were left out" % bad, file=sys.stderr)


def main(paths):
    streams = [open(path) for path in paths] if paths else [sys.stdin]
    rows = {}  # key: the output (or the input when nothing was written), in the order first seen
    for record in records(streams):
        key = record.get("output") or record["input"]
        made = rows.get(key, {}).get("made")
        if record.get("skipped"):
            rows[key] = {"last": record, "made": made}
        else:
            rows[key] = {"last": record, "made": record if record.get("output") else None}
    print("\t".join(COLUMNS))
    statuses = {}
    for key, row in rows.items():
        last, made = row["last"], row["made"] or row["last"]
        kept = bool(last.get("skipped"))
        status = last["status"]
        if (last.get("written") or {}).get("bijective") is False:
            status += "_FOLDED_AS_WRITTEN"  # certified in double precision, but float32 rounding folded a triangle
        values = {
            "input": last["input"], "output": last.get("output"), "status": status,
            "vertices": last["vertices"], "faces": last["faces"], "weights": last["weights"],
            "max_imbalance": made.get("max_imbalance"), "flipped_faces": last.get("flipped_faces"),
            "map_seconds": made["seconds"]["map"], "total_seconds": made["seconds"]["total"], "kept": kept,
        }
        print("\t".join("" if values[c] is None else str(values[c]) for c in COLUMNS))
        statuses[status] = statuses.get(status, 0) + 1
    summary = ", ".join("%s %d" % item for item in sorted(statuses.items()))
    print("gather_runs: %d surface(s): %s" % (len(rows), summary or "none"), file=sys.stderr)
    return 0 if set(statuses) <= {"OK"} else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
