#!/usr/bin/env python3
"""
The digital methods: a Delaunay triangulation from a digital Voronoi diagram
============================================================================

The thesis' digital methods start from the digital Voronoi diagram of the points on a grid
(the exact distance transform's labels, ``gpugeom.voronoi_labels``): its dual is almost the
Delaunay triangulation already, and exact flips finish it. ``method="digital"`` gives exactly
the triangles (2D Delaunay), tetrahedra (3D Delaunay) or facets (3D hull) of the default
method, with fewer flips on well-spread points. The picture shows the digital diagram of a few
hundred points and their exact triangulation; the text compares both methods on more points.

  python3 digital_methods.py [-n 20000] [--grid 160] [-o digital_methods.png]
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import gpugeom


def triangle_set(simplices):
    """The triangles as sets of vertices: the methods may list them in another order."""
    return {tuple(sorted(t)) for t in simplices.tolist()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=20000)
    ap.add_argument("--grid", type=int, default=160)
    ap.add_argument("-o", default="digital_methods.png")
    a = ap.parse_args()
    rng = np.random.default_rng(7)

    # Both methods on n gaussian points: the same triangles.
    p = rng.normal(size=(a.n, 2))
    inc = gpugeom.Delaunay(p)
    dig = gpugeom.Delaunay(p, method="digital")
    same = triangle_set(inc.simplices) == triangle_set(dig.simplices)
    fi, fd = inc.stats["counters"]["flips"], dig.stats["counters"]["flips"]
    p3 = rng.random((a.n, 3))
    h_same = triangle_set(gpugeom.ConvexHull(p3).simplices) == \
        triangle_set(gpugeom.ConvexHull(p3, method="digital").simplices)
    print(f"{a.n} gaussian points: the same triangles by both methods: {same}; flips: "
          f"incremental {fi}, digital {fd}; 3D hull of {a.n} points, the same facets: {h_same}")

    # A few hundred points on a grid: their digital Voronoi diagram, and the exact triangulation.
    g = a.grid
    q = rng.random((300, 2)) * (g - 1)
    seeds = np.zeros((g, g), np.int32)
    ij = np.round(q).astype(int)
    seeds[ij[:, 1], ij[:, 0]] = np.arange(1, len(q) + 1)
    labels = gpugeom.voronoi_labels(seeds)
    tri = gpugeom.Delaunay(q, method="digital")
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.4))
    colours = rng.random((len(q) + 1, 3)) * 0.5 + 0.5
    for ax in axes:
        ax.imshow(colours[labels], origin="lower", interpolation="nearest")
        ax.plot(q[:, 0], q[:, 1], "k.", ms=3)
        ax.set_axis_off()
    axes[0].set_title(f"digital Voronoi diagram on a {g}x{g} grid")
    axes[1].triplot(q[:, 0], q[:, 1], tri.simplices, lw=0.6, color="k")
    axes[1].set_xlim(-0.5, g - 0.5)
    axes[1].set_ylim(-0.5, g - 0.5)
    axes[1].set_title("its exact Delaunay triangulation (method=\"digital\")")
    fig.tight_layout()
    fig.savefig(a.o, dpi=110)
    print("->", a.o)


if __name__ == "__main__":
    main()
