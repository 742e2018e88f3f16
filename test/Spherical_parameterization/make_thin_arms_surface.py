#!/usr/bin/python3
# Copyright (c) 2026 CGAL Spherical Parameterization contributors.
# This file is part of CGAL Spherical Parameterization, a package in CGAL's style (www.cgal.org).
#
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Author(s)     : CGAL Spherical Parameterization contributors

"""A marching-tetrahedra surface of a ball with many thin arms, written as OFF: closed, genus 0, with the slivers
that marching cubes makes, and arms long enough (length over radius 10 to 40) that the balanced maps squeeze their
tips to spherical edges of 1e-10 to below 1e-16.

Usage: make_thin_arms_surface.py SEED ARMS RESOLUTION OUTPUT.off

The same arguments give the same file (no random generator of a library: a linear congruential one of our own). The
arms point along a Fibonacci spiral of directions (well apart, so they do not touch: genus 0, one component).
"""
import sys

import numpy as np


def lcg(seed):
    state = (seed * 2654435761 + 12345) % (1 << 32)
    while True:
        state = (1664525 * state + 1013904223) % (1 << 32)
        yield state / float(1 << 32)


def field(points, arms):
    """Smooth union of a ball of radius 0.3 and capsules from its centre: negative inside."""
    f = np.linalg.norm(points, axis=-1) - 0.3
    width = 0.03
    for direction, length, radius in arms:
        t = np.clip(points @ direction, 0., length)
        distance = np.linalg.norm(points - t[..., None] * direction, axis=-1) - radius
        h = np.clip(0.5 + 0.5 * (distance - f) / width, 0., 1.)
        f = distance * (1. - h) + f * h - width * h * (1. - h)
    return f


def make(seed, number_of_arms, resolution):
    uniform = lcg(seed)
    golden = np.pi * (3. - np.sqrt(5.))
    offset = next(uniform) * 2. * np.pi
    arms = []
    for k in range(number_of_arms):
        z = 1. - 2. * (k + 0.5) / number_of_arms
        r = np.sqrt(1. - z * z)
        angle = golden * k + offset
        direction = np.array([r * np.cos(angle), r * np.sin(angle), z])
        arms.append((direction, 0.5 + 0.45 * next(uniform), 0.025 + 0.045 * next(uniform)))
    axis = np.linspace(-1.05, 1.05, resolution)
    grid = np.stack(np.meshgrid(axis, axis, axis, indexing='ij'), -1)
    f = field(grid, arms) + 1e-7  # no grid value exactly on the surface
    n = resolution
    # Six tetrahedra per cube around its diagonal 0-6: neighbouring cubes split their common faces alike.
    corner = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]])
    tetrahedra = [(0, 5, 1, 6), (0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6)]
    shifted = [f[i:n - 1 + i, j:n - 1 + j, k:n - 1 + k] for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    crossed = np.argwhere((np.minimum.reduce(shifted) < 0) & (np.maximum.reduce(shifted) > 0))
    index_of_edge, points, faces = {}, [], []

    def position(a):
        return np.array([axis[a[0]], axis[a[1]], axis[a[2]]])

    def vertex_on(a, b):
        key = (min(a, b), max(a, b))
        if key not in index_of_edge:
            s = f[a] / (f[a] - f[b])
            index_of_edge[key] = len(points)
            points.append(position(a) + s * (position(b) - position(a)))
        return index_of_edge[key]

    def outward(triangle, inside_point):
        a, b, c = (points[i] for i in triangle)
        if np.dot(np.cross(b - a, c - a), inside_point - a) > 0:
            return (triangle[0], triangle[2], triangle[1])
        return triangle

    for cell in crossed:
        cube = [tuple(cell + corner[k]) for k in range(8)]
        for tetrahedron in tetrahedra:
            v = [cube[i] for i in tetrahedron]
            inside = [p for p in v if f[p] < 0]
            outside = [p for p in v if f[p] >= 0]
            if not inside or not outside:
                continue
            inside_point = np.mean([position(p) for p in inside], axis=0)
            if len(inside) != 2:
                lone = inside[0] if len(inside) == 1 else outside[0]
                others = outside if len(inside) == 1 else inside
                faces.append(outward(tuple(vertex_on(lone, o) for o in others), inside_point))
            else:
                (a, b), (c, d) = inside, outside
                quad = [vertex_on(a, c), vertex_on(a, d), vertex_on(b, d), vertex_on(b, c)]
                faces.append(outward((quad[0], quad[1], quad[2]), inside_point))
                faces.append(outward((quad[0], quad[2], quad[3]), inside_point))
    return points, faces


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    points, faces = make(int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]))
    with open(sys.argv[4], 'w') as out:
        out.write('OFF\n%d %d 0\n' % (len(points), len(faces)))
        for p in points:
            out.write('%.17g %.17g %.17g\n' % tuple(p))
        for t in faces:
            out.write('3 %d %d %d\n' % t)


if __name__ == '__main__':
    main()
