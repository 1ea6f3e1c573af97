#!/usr/bin/env python3
"""
Contour lines as breaklines: constrained Delaunay
=================================================

Terrain contour lines as breaklines: the exact constrained Delaunay triangulation.

A TIN from contour points alone (the Delaunay triangulation) cuts across the contour lines
wherever two points of one line are closer to a point of the next line than to each other, so
the surface crosses its own contours. With every contour edge a segment
(``gpugeom.ConstrainedDelaunay``), each contour line is a chain of triangle edges; the other edges
stay as Delaunay as the lines allow. The picture shows a window of both.

  python3 terrain_breaklines.py [-o breaklines.png] [--levels 60]
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


def contour_segments(levels):
    """Points of every contour line and the index pairs of its consecutive points."""
    pts, elev, segs, first = [], [], [], 0
    for s, lev in contour_lines(levels):
        closed = len(s) > 2 and np.array_equal(s[0], s[-1])
        s = s[:-1] if closed else s
        k = len(s)
        i = np.arange(first, first + k - 1)
        e = np.stack([i, i + 1], axis=1)
        if closed:
            e = np.concatenate([e, [[first + k - 1, first]]])
        pts.append(s)
        elev.append(np.full(k, lev))
        segs.append(e)
        first += k
    return np.concatenate(pts), np.concatenate(elev), np.concatenate(segs).astype(np.int32)


def edge_set(simplices):
    e = np.concatenate([simplices[:, [0, 1]], simplices[:, [1, 2]], simplices[:, [2, 0]]])
    return set(map(tuple, np.sort(e, axis=1).tolist()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", default="terrain_breaklines.png")
    ap.add_argument("--levels", type=int, default=60)
    a = ap.parse_args()
    p, z, segs = contour_segments(a.levels)
    t0 = time.perf_counter()
    # (traced contour lines can cross where they pass a saddle: such crossings get a vertex)
    cdt = gpugeom.ConstrainedDelaunay(p, segs, crossings="split")
    ms = 1e3 * (time.perf_counter() - t0)
    tin = gpugeom.Delaunay(p)
    # the exact check, with the pieces the split made as the segments
    marked = np.stack([cdt.simplices[:, [1, 2, 0]], cdt.simplices[:, [2, 0, 1]]], axis=2)
    marked = marked[cdt.segment_of >= 0].astype(np.int32)
    ok, msg = gpugeom.verify.check_constrained_delaunay(cdt.points, cdt.simplices, marked,
                                                        cdt.duplicate_of)
    dup = np.asarray(tin.duplicate_of)  # (traced lines repeat points: take the first of each)
    ends = np.where(dup[segs] >= 0, dup[segs], segs)
    want = {e for e in map(tuple, np.sort(ends, axis=1).tolist()) if e[0] != e[1]}
    lost = len(want - edge_set(tin.simplices))
    c = cdt.stats["counters"]
    print(f"{len(p)} contour points, {len(want)} contour edges: the Delaunay TIN misses {lost} of "
          f"them; the constrained one has all ({c['segments_recovered']} segments recovered, "
          f"{c['recovery_rounds']} rounds, {c['crossings']} crossings split) in {ms:.1f} ms on "
          f"{cdt.stats['backend']}; exact check: {ok} {msg}")

    cx, cy = np.median(p, axis=0)
    w = 0.012 * (p[:, 0].max() - p[:, 0].min())
    fig, axes = plt.subplots(1, 2, figsize=(14, 7))
    q = cdt.points  # (the input points, then the crossings' vertices: at their segments' level)
    zq = np.concatenate([z, z[segs[cdt.new_point_segments[:, 0], 0]]])
    for ax, pp, zz, s, title in ((axes[0], p, z, tin.simplices, "Delaunay TIN (crosses contours)"),
                                 (axes[1], q, zq, cdt.simplices, "constrained: contours are edges")):
        ax.tripcolor(pp[:, 0], pp[:, 1], s, zz, shading="gouraud", cmap="terrain")
        ax.triplot(pp[:, 0], pp[:, 1], s, lw=0.3, color="k", alpha=0.5)
        ax.add_collection(LineCollection(p[segs], lw=1.2, color="tab:red"))
        ax.set_xlim(cx - w, cx + w)
        ax.set_ylim(cy - w, cy + w)
        ax.set_aspect("equal")
        ax.set_title(title)
    fig.tight_layout()
    fig.savefig(a.o, dpi=130)
    print("->", a.o)


if __name__ == "__main__":
    main()
