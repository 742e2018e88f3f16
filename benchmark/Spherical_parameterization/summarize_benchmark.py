#!/usr/bin/env python3
"""Summarizes the CSV of benchmark_spherical_parameterization: a Markdown table, the speed-up of the default
(global) solver over the paper's local Newton, and the exponent of time against faces (least squares in log-log)."""
import csv
import math
import sys

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
