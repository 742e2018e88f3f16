# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

"""Maps a FreeSurfer surface (lh.white, lh.pial, ...) onto the sphere and saves it as a FreeSurfer sphere of radius
100, in the input's vertex order (so curvature, thickness and labels stay attached).

    python3 map_freesurfer_surface.py lh.white lh.sphere

Reads and writes with nibabel when it is installed (python3-nibabel), with the module's own reader otherwise (the
command line `spherical_parameterize lh.white -o lh.sphere --radius 100` does the same in one step)."""
import sys

import cgal_spherical_parameterization as sp

source, target = sys.argv[1], sys.argv[2]
try:
    import nibabel
    V, F = nibabel.freesurfer.read_geometry(source)
except ImportError:
    nibabel = None
    V, F = sp.read_surface(source)

def show(stage, iteration, residual, non_positive_faces, seconds):
    print("  %-14s iteration %4d  Res %.2e  %5.1f s" % (stage, iteration, residual, seconds), file=sys.stderr)

X, info = sp.map_to_sphere(V, F, weights="uniform", progress=show)
print("%s: %s, max imbalance %.1e, %d flipped faces, %.2f s"
      % (source, info["status"], info["max_imbalance"], info["flipped_faces"], info["seconds"]))
if nibabel is not None:
    nibabel.freesurfer.write_geometry(target, 100.0 * X, F)
    # FreeSurfer stores float32: certify the sphere as it was written.
    W, _ = nibabel.freesurfer.read_geometry(target)
    written = sp.certify(W, F)
    print("written %s (float32, radius 100): %s" % (target, "certified bijective" if written["bijective"]
                                                     else "%d triangles folded by rounding" % written["flipped_faces"]))
else:
    print("nibabel is not installed: use the command line to write FreeSurfer files")
sys.exit(0 if info["success"] else 1)
