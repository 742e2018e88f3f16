#!/usr/bin/env bash
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

# Brain-surface formats through the command line, checked with an independent reader and writer (nibabel): FreeSurfer
# and GIfTI in and out on cortices written by nibabel, other GIfTI encodings and byte orders written here by nibabel,
# the vertex order and triangles kept, and the float32 certificate of the coordinates as written.
# Usage: test_brain_formats.sh TOOL SHARED_MESHES CGAL_MESHES SCRATCH_DIR
set -u
tool=$1; shared=$2; cgal=$3; scratch=$4
rm -rf "$scratch"; mkdir -p "$scratch"
python=/usr/bin/python3  # Debian's, with python3-nibabel
"$python" -c "import nibabel" || { echo "FAIL: nibabel is missing (scripts/setup.sh installs python3-nibabel)"; exit 1; }
"$python" - "$tool" "$shared/formats" "$cgal" "$scratch" <<'PY'
import json, os, subprocess, sys
import numpy as np
import nibabel as nib
tool, formats, cgal, scratch = sys.argv[1:5]
failures = 0

def run(arguments, expected):
    global failures
    done = subprocess.run([tool] + arguments + ["--json"], capture_output=True, text=True)
    figures = json.loads(done.stdout) if done.stdout.strip() else None
    if done.returncode != expected:
        print("FAIL: %s: exit %d, expected %d\n%s" % (" ".join(arguments), done.returncode, expected, done.stderr[-500:]))
        failures += 1
    return figures

def check(condition, what):
    global failures
    print(("ok: " if condition else "FAIL: ") + what)
    failures += 0 if condition else 1

def gifti_surface(path):
    image = nib.load(path)
    points = image.get_arrays_from_intent("NIFTI_INTENT_POINTSET")[0]
    triangles = image.get_arrays_from_intent("NIFTI_INTENT_TRIANGLE")[0]
    return points.data, triangles.data, points

def on_sphere(points, radius, precision):
    r = np.linalg.norm(points.astype(np.float64), axis=1)
    return np.abs(r - radius).max() <= precision * radius

# FreeSurfer in, FreeSurfer out with FreeSurfer's radius 100.
source = os.path.join(formats, "lh.fsavg5.pial")
out = os.path.join(scratch, "lh.sphere")
f = run([source, "-o", out, "--radius", "100"], 0)
v_in, t_in = nib.freesurfer.read_geometry(source)
v_out, t_out = nib.freesurfer.read_geometry(out)
check(f is not None and f["written"] == {"format": "freesurfer", "precision": "float32", "radius": 100, "flipped_faces": 0, "bijective": True},
      "FreeSurfer -> FreeSurfer, radius 100, certified as written: %s" % (f and f["written"]))
check(v_out.shape == v_in.shape and (t_out == t_in).all(), "FreeSurfer output keeps the vertex count and the triangles")
check(on_sphere(v_out, 100., 1e-6), "FreeSurfer output on the sphere of radius 100 (float32)")
_, _, _, created_by = nib.freesurfer.read_geometry(out, read_metadata=True, read_stamp=True)
check(created_by.startswith("created by spherical_parameterize/1 status=OK") and "radius=100 " in created_by,
      "FreeSurfer output records the run in its created-by line: %s" % created_by)
again = run([source, "-o", out, "--radius", "100"], 0)
check(again is not None and again["skipped"] is True, "FreeSurfer output kept by a re-run")
again = run([source, "-o", out], 0)
check(again is not None and again["skipped"] is False, "FreeSurfer output mapped again for another radius")
f = run([source, "-o", out, "--radius", "100"], 0)

# GIfTI in, GIfTI out, float32 and float64.
source = os.path.join(formats, "lh.conte69.surf.gii")
p_in, t_in, _ = gifti_surface(source)
for extra, dtype in (([], np.float32), (["--float64"], np.float64)):
    out = os.path.join(scratch, "conte69_sphere%s.surf.gii" % ("64" if extra else ""))
    f = run([source, "-o", out] + extra, 0)
    p_out, t_out, array = gifti_surface(out)
    check(f is not None and f["status"] == "OK" and f["written"]["precision"] == ("float64" if extra else "float32"),
          "GIfTI -> GIfTI %s: %s" % (dtype.__name__, f and f["written"]))
    check(p_out.dtype == dtype and p_out.shape == p_in.shape and (t_out == t_in).all(), "GIfTI output: dtype, vertex count, triangles")
    check(on_sphere(p_out, 1., 1e-6 if dtype == np.float32 else 1e-14), "GIfTI output on the unit sphere")
    stamp = nib.load(out).meta.get("spherical_parameterize", "")
    check(stamp.startswith("spherical_parameterize/1 status=OK") and ("precision=%s" % dtype.__name__) in stamp,
          "GIfTI output records the run in its metadata: %s" % stamp)
    again = run([source, "-o", out] + extra, 0)
    check(again is not None and again["skipped"] is True and again["written"]["bijective"] is True,
          "GIfTI %s output kept by a re-run, certified as stored" % dtype.__name__)

# GIfTI encodings and byte orders the package did not write: ASCII, base64, gzip-base64, big-endian.
points, triangles = p_in.astype(np.float32), t_in.astype(np.int32)
for encoding in ("ASCII", "GIFTI_ENCODING_B64BIN", "GIFTI_ENCODING_B64GZ"):
    for endian in ("little", "big"):
        if encoding == "ASCII" and endian == "big":
            continue
        image = nib.gifti.GiftiImage(darrays=[
            nib.gifti.GiftiDataArray(points, intent="NIFTI_INTENT_POINTSET", encoding=encoding, endian=endian),
            nib.gifti.GiftiDataArray(triangles, intent="NIFTI_INTENT_TRIANGLE", encoding=encoding, endian=endian)])
        variant = os.path.join(scratch, "conte69_%s_%s.surf.gii" % (encoding.split("_")[-1], endian))
        nib.save(image, variant)
        f = run([variant, "-o", os.path.join(scratch, "variant_sphere.off")], 0)
        check(f is not None and f["vertices"] == len(points) and f["faces"] == len(triangles),
              "GIfTI %s %s-endian read" % (encoding, endian))

# An OFF mesh to FreeSurfer: nibabel reads what we write.
out = os.path.join(scratch, "bunny.sphere")
f = run([os.path.join(cgal, "triceratops.off"), "-o", out], 0)
v_out, t_out = nib.freesurfer.read_geometry(out)
check(f is not None and len(v_out) == f["vertices"] and len(t_out) == f["faces"], "OFF -> FreeSurfer, read back by nibabel")

# Rounding to float32 can fold what double precision keeps positive (man.off's limbs: spherical edges of 1e-10):
# the run says so and exits 1; the .off output of the same map is certified.
f = run([os.path.join(cgal, "man.off"), "-o", os.path.join(scratch, "man.sphere")], 1)
check(f is not None and f["status"] == "OK" and f["written"]["precision"] == "float32" and f["written"]["flipped_faces"] > 0
      and f["written"]["bijective"] is False and f["success"] is False, "man.off: float32 folds reported (%s)" % (f and f["written"]))
f = run([os.path.join(cgal, "man.off"), "-o", os.path.join(scratch, "man_sphere.off")], 0)
check(f is not None and f["written"]["flipped_faces"] is None, "man.off to .off: the certified coordinates themselves")

# Malformed FreeSurfer files get a file error (exit 3) that names the defect, never a crash.
with open(os.path.join(formats, "lh.fsavg5.pial"), "rb") as stream:
    data = stream.read()
bad_index = bytearray(data)
bad_index[-12:-8] = b"\x7f\xff\xff\xff"  # the last triangle's first vertex (this file has no trailing tags)
for name, broken, status in (("truncated", data[: len(data) // 2], "TRUNCATED"), ("bad_index", bytes(bad_index), "INVALID_DATA"),
                             ("no_counts", data[:40], "TRUNCATED")):
    path = os.path.join(scratch, "lh." + name)
    open(path, "wb").write(broken)
    done = subprocess.run([tool, path, "-o", os.path.join(scratch, "broken.off")], capture_output=True, text=True)
    check(done.returncode == 3 and status in done.stderr, "FreeSurfer %s: exit %d, %s" % (name, done.returncode, done.stderr.strip()[-90:]))
print("%d failed" % failures)
sys.exit(1 if failures else 0)
PY
