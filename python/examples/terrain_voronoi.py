#!/usr/bin/env python3
"""
A terrain TIN and its Voronoi cells
===================================

Terrain contour points, their exact Delaunay triangulation (a TIN) and Voronoi cells.

Contour lines of matplotlib's sample elevation model (the Jacksboro fault, 3 arc-second samples) give a
point set typical of terrain modelling: long runs of nearly collinear points along each line.
gpugeom triangulates it exactly; the picture shows the TIN coloured by elevation and the
Voronoi cells of a window of it.

  python3 terrain_voronoi.py [-o terrain.png] [--levels 25]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection

import gpugeom
from _terrain import contour_lines


def contour_points(levels):
    lines = contour_lines(levels)
    return (np.concatenate([s for s, _ in lines]),
            np.concatenate([np.full(len(s), lev) for s, lev in lines]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", default="terrain_voronoi.png")
    ap.add_argument("--levels", type=int, default=25)
    a = ap.parse_args()
    p, z = contour_points(a.levels)
    t0 = time.perf_counter()
    tri = gpugeom.Delaunay(p)
    vor = gpugeom.Voronoi(p)
    ms = 1e3 * (time.perf_counter() - t0)
    ok, msg = gpugeom.verify.check_delaunay(p, tri.simplices, tri.duplicate_of)
    print(f"{len(p)} contour points: {tri.nsimplex} triangles, {len(vor.vertices)} Voronoi "
          f"vertices in {ms:.1f} ms on {tri.stats['backend']}; exact check: {ok} {msg}")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(14, 6.5))
    ax1.tripcolor(p[:, 0], p[:, 1], tri.simplices, z, shading="gouraud", cmap="terrain")
    ax1.triplot(p[:, 0], p[:, 1], tri.simplices, lw=0.1, color="k", alpha=0.4)
    ax1.set_title(f"TIN of {len(p)} contour points ({tri.nsimplex} triangles)")
    ax1.set_aspect("equal")
    # Voronoi cells in a window: finite ridges as segments
    cx, cy = np.median(p, axis=0)
    w = 0.12 * (p[:, 0].max() - p[:, 0].min())
    rv = np.asarray(vor.ridge_vertices_array)
    fin = (rv >= 0).all(axis=1)
    seg = vor.vertices[rv[fin]]
    inwin = (np.abs(seg[:, :, 0] - cx) < w).all(1) & (np.abs(seg[:, :, 1] - cy) < w).all(1)
    ax2.add_collection(LineCollection(seg[inwin], lw=0.4, color="tab:blue"))
    sel = (np.abs(p[:, 0] - cx) < w) & (np.abs(p[:, 1] - cy) < w)
    ax2.scatter(p[sel, 0], p[sel, 1], s=1.5, c=z[sel], cmap="terrain")
    ax2.set_xlim(cx - w, cx + w)
    ax2.set_ylim(cy - w, cy + w)
    ax2.set_aspect("equal")
    ax2.set_title("Voronoi cells of the contour points (window)")
    fig.tight_layout()
    fig.savefig(a.o, dpi=130)
    print("->", a.o)


if __name__ == "__main__":
    main()
