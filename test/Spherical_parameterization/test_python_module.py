# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

"""The Python module as a user meets it: map, figures, certificate, distortion, readers, errors, progress,
cancellation, Ctrl-C and the GIL. Usage: python3 test_python_module.py MODULE_DIR SHARED_MESHES BUNDLED_BUNNY"""
import os
import signal
import sys
import threading
import time

import numpy as np

sys.path.insert(0, sys.argv[1])
import cgal_spherical_parameterization as sp  # noqa: E402

shared, bunny = sys.argv[2], sys.argv[3]
failures = 0


def check(condition, what):
    global failures
    print(("ok: " if condition else "FAIL: ") + what)
    failures += 0 if condition else 1


# Map the bundled bunny: X on the unit sphere, in V's order, certified; the figures of the command line's JSON.
V, F = sp.read_surface(bunny)
check(V.shape == (1839, 3) and F.shape == (3674, 3) and V.dtype == np.float64, "read_surface: %s %s" % (V.shape, F.shape))
X, info = sp.map_to_sphere(V, F)
check(info["status"] == "OK" and info["success"] and info["bijective"] and info["flipped_faces"] == 0, "map_to_sphere: %s" % info["message"])
check(X.shape == V.shape and X.dtype == np.float64 and np.abs(np.linalg.norm(X, axis=1) - 1).max() < 1e-14, "X on the unit sphere")
check(info["max_imbalance"] <= 1e-6 and set(info["stages"]) == {"initial_guess", "gauss_seidel", "newton"}, "figures")
# What does not apply is None, as the JSON's null: stationarity (symmetric weights), the least-distortion figures.
check(all(info[k] is None for k in ("max_stationarity", "unstationary_vertices", "distortion_energy", "max_distortion_stationarity",
                                    "least_distortion_steps", "distortion_vertices_at_rounding_floor"))
      and info["least_distortion_map"] is False and info["balanced_map_folded"] is False and info["least_distortion_from_balanced_map"] is False and info["replaced_balanced_map_distortion"] is None and info["replaced_balanced_map_angle_error"] is None, "figures that do not apply: %s" % {k: info[k] for k in info if "distortion" in k or "stationar" in k})
certificate = sp.certify(X, F)
check(certificate["bijective"] and certificate["flipped_faces"] == 0 and abs(certificate["total_signed_area"] - 4 * np.pi) < 1e-9,
      "certify: %s" % certificate)
# The certificate can fail: swap two vertices' images.
Y = X.copy()
Y[[0, 100]] = Y[[100, 0]]
check(not sp.certify(Y, F)["bijective"], "certify rejects a map with two vertices swapped")
distortion = sp.measure_distortion(V, X, F)
check(0 < distortion["mean_angle_error_degrees"] < 30 and distortion["log_area_ratio_stddev"] > 0, "distortion: %s" % distortion)
check(info["distortion"] == distortion, "map_to_sphere's distortion is measure_distortion's: %s" % info["distortion"])
# Cotangent and mean-value weights: by default, where their own map is not balanced, the bijective map of least
# conformal distortion (stationary: OK); least_distortion=False keeps the weights' own map. The bunny's balanced
# cotangent map is replaced by that minimum, started from it (3.36 degrees against 3.16, 2026-12-05).
X2, info2 = sp.map_to_sphere(V, F, weights="cotangent")
check(info2["weights"] == "cotangent" and info2["status"] == "OK" and info2["bijective"], "cotangent weights: %s" % info2["status"])
check(info2["least_distortion_map"] is True and info2["least_distortion_from_balanced_map"] is True
      and isinstance(info2["replaced_balanced_map_distortion"], float)
      and info2["replaced_balanced_map_angle_error"] > info2["distortion"]["mean_angle_error_degrees"],
      "cotangent weights, the balanced map replaced: %s" % {k: info2[k] for k in info2 if "distortion" in k})
Xmv, infomv = sp.map_to_sphere(V, F, weights="mean_value")
check(infomv["status"] == "OK" and infomv["least_distortion_map"] is True and infomv["bijective"],
      "mean-value weights, the default: %s, least distortion map %s" % (infomv["status"], infomv["least_distortion_map"]))
# FreeSurfer surfaces through the same reader.
V3, F3 = sp.read_surface(os.path.join(shared, "formats", "lh.fsavg5.pial"))
check(V3.shape == (10242, 3), "read_surface FreeSurfer: %s" % (V3.shape,))

# Invalid input raises ValueError whose message starts with the error code.
def raises(call, code, what):
    try:
        call()
    except ValueError as error:
        check(str(error).startswith(code), "%s: ValueError %s" % (what, str(error)[:90]))
        return
    check(False, "%s: no ValueError" % what)

raises(lambda: sp.map_to_sphere(V, F[:-1]), "HAS_BORDER", "a face removed")
raises(lambda: sp.map_to_sphere(V, np.array([[0, 1, 5000]])), "INVALID_ARGUMENT", "an index out of range")
raises(lambda: sp.map_to_sphere(V[:, :2], F), "INVALID_ARGUMENT", "V with two columns")
raises(lambda: sp.map_to_sphere(V, F, weights="conformal"), "INVALID_ARGUMENT", "unknown weights")
raises(lambda: sp.read_surface(os.path.join(shared, "PROVENANCE.md")), "UNKNOWN_FORMAT", "not a mesh file")

# Progress: the callable sees the stages; returning False cancels with the best map so far.
Vk, Fk = sp.read_surface(os.path.join(shared, "oded_koala.off"))
stages = []
def follow(stage, iteration, residual, non_positive, seconds):
    stages.append((stage, seconds))
    return seconds < 1.0
Xk, infok = sp.map_to_sphere(Vk, Fk, criterion="paper", tolerance=1e-300, max_seconds=30, progress=follow)
check(infok["status"] == "CANCELLED" and len(stages) >= 2 and Xk.shape == Vk.shape and stages[-1][1] < 10,
      "progress and cancel: %s after %d reports, %.2f s" % (infok["status"], len(stages), stages[-1][1] if stages else -1))

# Mean-value weights (default criterion): the callable is asked during their least-squares iterations too, and its
# False ends them (koala's iterations go on past 30 s).
asked = []
def stop_after_stage_1(stage, iteration, residual, non_positive, seconds):
    asked.append(seconds)
    return len(asked) == 1
start = time.monotonic()
Xm, infom = sp.map_to_sphere(Vk, Fk, weights="mean_value", max_seconds=30, progress=stop_after_stage_1)
check(infom["status"] == "CANCELLED" and len(asked) >= 2 and time.monotonic() - start < asked[0] + 15 and Xm.shape == Vk.shape,
      "mean-value weights cancelled after stage 1: %s after %d reports, %.2f s" % (infom["status"], len(asked), time.monotonic() - start))

# The GIL is released during the work: another Python thread keeps running. Its ticks are counted in the middle of the
# call, not against a rate, so that a loaded machine does not fail the test (a held GIL gives none there).
ticks = []
stop = threading.Event()
def tick():
    while not stop.is_set():
        ticks.append(time.monotonic())
        time.sleep(0.001)
ticker = threading.Thread(target=tick)
ticker.start()
start = time.monotonic()
sp.map_to_sphere(Vk, Fk, criterion="paper", tolerance=1e-300, max_seconds=1.5)
elapsed = time.monotonic() - start
stop.set()
ticker.join()
inside = sum(1 for t in ticks if start + 0.25 * elapsed < t < start + 0.75 * elapsed)
check(inside >= 5, "GIL released: %d ticks of another thread in the middle half of a %.2f s call" % (inside, elapsed))

# Ctrl-C (SIGINT) during the work raises KeyboardInterrupt promptly.
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
start = time.monotonic()
try:
    sp.map_to_sphere(Vk, Fk, criterion="paper", tolerance=1e-300, max_seconds=60)
    check(False, "Ctrl-C: no KeyboardInterrupt")
except KeyboardInterrupt:
    check(time.monotonic() - start < 10.0, "Ctrl-C: KeyboardInterrupt after %.2f s" % (time.monotonic() - start))

# least_distortion=False keeps mean value's least-squares map. After the Ctrl-C check: on 2026-12-02 a Ctrl-C in a
# later call of the same process reached it only at that call's end in 2 of 3 runs on a loaded machine. Probably the
# cause found later that day (the Ctrl-C check itself failed so in 2 of 10 runs): the multilevel smoothing sweeps
# dropped a refusal, and the module accepted the next reports; a refusal is final since (spherical_parameterize.h).
Xmv0, infomv0 = sp.map_to_sphere(V, F, weights="mean_value", least_distortion=False)
check(infomv0["least_distortion_map"] is False and infomv0["max_stationarity"] is not None,
      "mean-value weights, least_distortion=False: %s" % infomv0["status"])

print("%d failed" % failures)
sys.exit(1 if failures else 0)
