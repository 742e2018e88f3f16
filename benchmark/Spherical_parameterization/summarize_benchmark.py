#!/usr/bin/env python3
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

"""Summarizes the CSV of benchmark_spherical_parameterization: a Markdown table, the speed-up of the default
(global) solver over the paper's local Newton, the exponent of time against faces (least squares in log-log), and
the time to reach each tolerance.

Usage: summarize_benchmark.py CSV [--plot FILE.svg]   (--plot: the time-to-tolerance chart as an SVG file, the
manual's fig/time_to_tolerance.svg; written by hand, no plotting library needed)"""
import csv
import math
import sys

plot_path = sys.argv[sys.argv.index("--plot") + 1] if "--plot" in sys.argv else None
rows = list(csv.DictReader(open(sys.argv[1])))
if not rows:
    sys.exit("no results in " + sys.argv[1])

print("| mesh | faces | weights | solver | tolerance | status | stage 1 (s) | stage 2 (s) | stage 3 (s) | total (s) | Res | max imbalance | flips | peak MB | KB/face | levels (vertices:Newton steps) |")
print("|---|---:|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for r in rows:
    faces = int(r["faces"])
    print("| %s | %d | %s | %s | %s | %s | %.3f | %.3f | %.3f | %.3f | %.2e | %.2e | %s | %.0f | %.2f | %s |" % (
        r["mesh"], faces, r["weights"], r["solver"], r.get("tolerance", "1e-06"), r["status"], float(r["initial_s"]), float(r["gauss_seidel_s"]),
        float(r["newton_s"]), float(r["total_s"]), float(r["res"]), float(r.get("max_imbalance", "nan")), r["flips"],
        float(r["peak_mb"]), float(r["peak_mb"]) * 1024. / faces, r.get("levels", "").replace(";", ", ")))

key = lambda r: (r["mesh"], r["weights"], r.get("tolerance", "1e-06"))
glob = {key(r): r for r in rows if r["solver"] == "global"}
local = [r for r in rows if r["solver"] in ("local", "paper")]
if local:
    print("\nSpeed-up of the default solver (global Newton, multilevel start, stopping on the imbalance) over the paper's "
          "local Newton (local: stopping on the imbalance; paper: the paper's setting, two-disk start and its Res "
          "test), same run. A speed-up against 'paper' compares different stopping tests: see its max imbalance.\n")
    print("| mesh | faces | tolerance | solver | its time (s) | its status, Res, max imbalance | global (s) | global status, max imbalance | speed-up |")
    print("|---|---:|---:|---|---:|---|---:|---|---:|")
    for r in local:
        g = glob.get(key(r))
        if g is None:
            continue
        ratio = float(r["total_s"]) / float(g["total_s"])
        if g["status"] != "OK":
            speed_up = "none: the default solver did not converge"
        else:
            # The local Newton did not reach the tolerance (budget or stall): the ratio is a lower bound.
            speed_up = ("%s%.1f" % (">= " if r["status"] != "OK" else "", ratio))
        print("| %s | %s | %s | %s | %.3f | %s, %.1e, %.1e | %.3f | %s, %.1e | %s |" % (
            r["mesh"], r["faces"], r.get("tolerance", "1e-06"), r["solver"], float(r["total_s"]), r["status"], float(r["res"]),
            float(r.get("max_imbalance", "nan")), float(g["total_s"]), g["status"], float(g.get("max_imbalance", "nan")), speed_up))

# From 5k faces up: below, fixed costs (reading the options, METIS' set-up) blur the slope.
ok = [r for r in rows if r["solver"] == "global" and r["weights"] == "uniform" and r["status"] == "OK"
      and float(r.get("tolerance", "1e-06")) == 1e-6 and int(r["faces"]) >= 5000]
def slope(rows):
    """Least-squares slope of log(total seconds) against log(faces)."""
    xs = [math.log(int(r["faces"])) for r in rows]
    ys = [math.log(float(r["total_s"])) for r in rows]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


if len(ok) >= 2:
    print("\nTime against faces (uniform weights, default solver, %d meshes from %d to %d faces): "
          "total seconds ~ faces^%.2f" % (len(ok), min(int(r["faces"]) for r in ok), max(int(r["faces"]) for r in ok),
                                          slope(ok)))
    big = [r for r in ok if int(r["faces"]) >= 100000]
    if len(big) >= 2:
        print("The same on the %d meshes of 100k faces or more: faces^%.2f" % (len(big), slope(big)))

def write_plot(path, ladders):
    """Seconds (log scale) against the tolerance (log scale, tighter to the right), one line per mesh."""
    width, height, left, right, top, bottom = 640, 400, 70, 190, 30, 50
    points = {m: sorted((t, float(r["total_s"])) for t, r in ts.items() if r["status"] == "OK") for m, ts in ladders.items()}
    tolerances = [t for p in points.values() for t, _ in p]
    seconds = [v for p in points.values() for _, v in p]
    if not tolerances:
        return
    lt0, lt1 = math.floor(math.log10(min(tolerances))), math.ceil(math.log10(max(tolerances)))
    ls0, ls1 = math.floor(math.log10(min(seconds))), math.ceil(math.log10(max(seconds)))
    lt1 = max(lt1, lt0 + 1)
    ls1 = max(ls1, ls0 + 1)
    x = lambda t: left + (lt1 - math.log10(t)) / (lt1 - lt0) * (width - left - right)
    y = lambda v: top + (ls1 - math.log10(v)) / (ls1 - ls0) * (height - top - bottom)
    colours = ["#1f5fa8", "#c0392b", "#27864a", "#8e44ad", "#d68910"]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>']
    for e in range(lt0, lt1 + 1):
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (x(10 ** e), top, x(10 ** e), height - bottom))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">1e%d</text>' % (x(10 ** e), height - bottom + 16, e))
    for e in range(ls0, ls1 + 1):
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (left, y(10 ** e), width - right, y(10 ** e)))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%g s</text>' % (left - 6, y(10 ** e) + 4, 10 ** e))
    out.append('<text x="%d" y="%d" text-anchor="middle">tolerance on the largest imbalance (tighter to the right)</text>'
               % ((left + width - right) // 2, height - 12))
    for k, (m, p) in enumerate(sorted(points.items())):
        c = colours[k % len(colours)]
        out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' % (c, " ".join("%.1f,%.1f" % (x(t), y(v)) for t, v in p)))
        for t, v in p:
            out.append('<circle cx="%.1f" cy="%.1f" r="3.5" fill="%s"/>' % (x(t), y(v), c))
        faces = next(iter(ladders[m].values()))["faces"]
        out.append('<text x="%d" y="%d" fill="%s">%s (%s faces)</text>' % (width - right + 10, top + 16 + 18 * k, c, m, faces))
    out.append('<text x="%d" y="%d">whole map call, seconds (log scale)</text>' % (left, top - 10))
    out.append("</svg>")
    open(path, "w").write("\n".join(out) + "\n")


# Time to a tolerance: the default solver on the same mesh at several tolerances of the imbalance test.
by_mesh = {}
for r in rows:
    if r["solver"] == "global" and r["weights"] == "uniform":
        by_mesh.setdefault(r["mesh"], {})[float(r.get("tolerance", "1e-06"))] = r
ladders = {m: t for m, t in by_mesh.items() if len(t) >= 3}
if ladders:
    print("\nTime to reach a tolerance (default solver, uniform weights, whole map call; the status and the max imbalance "
          "reached):\n")
    tolerances = sorted({t for ts in ladders.values() for t in ts}, reverse=True)
    print("| mesh | faces | " + " | ".join("%.0e" % t for t in tolerances) + " |")
    print("|---|---:|" + "---:|" * len(tolerances))
    for m, ts in sorted(ladders.items(), key=lambda item: int(next(iter(item[1].values()))["faces"])):
        cells = []
        for t in tolerances:
            r = ts.get(t)
            cells.append("-" if r is None else "%.2f s (%s, %.0e)" % (float(r["total_s"]), r["status"], float(r.get("max_imbalance", "nan"))))
        print("| %s | %s | %s |" % (m, next(iter(ts.values()))["faces"], " | ".join(cells)))

    if plot_path:
        write_plot(plot_path, ladders)
