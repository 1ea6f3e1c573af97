#!/usr/bin/env python3
"""
A quality mesh of a plate with holes
====================================

Delaunay refinement of a 2D domain (``gpugeom.mesh2d``, Triangle's ``-q -a``): the outline of a
bracket plate with a row of bolt holes and a slot, meshed so that every angle is at least 30
degrees and triangles grow from fine near the holes to coarse away from them (a sizing
function). The mesh is checked exactly (``gpugeom.verify.check_mesh2d``); the picture shows it
beside the histogram of its smallest angles.

  python3 mesh_domain.py [--min-angle 30] [--size 0.002] [-o mesh_domain.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import gpugeom


def circle(cx, cy, r, k):
    t = np.linspace(0, 2 * np.pi, k, endpoint=False)
    return np.column_stack([cx + r * np.cos(t), cy + r * np.sin(t)])


def plate():
    """Points, segments (closed loops) and a point in each hole of the plate."""
    outline = np.array([[0, 0], [2, 0], [2, 0.6], [1.3, 1.0], [0.7, 1.0], [0, 0.6]], float)
    slot = np.array([[0.8, 0.55], [1.2, 0.55], [1.2, 0.7], [0.8, 0.7]], float)
    loops = [outline, slot] + [circle(x, 0.25, 0.09, 48) for x in (0.3, 0.75, 1.25, 1.7)]
    holes = [[1.0, 0.62]] + [[x, 0.25] for x in (0.3, 0.75, 1.25, 1.7)]
    pts, segs, first = [], [], 0
    for loop in loops:
        k = len(loop)
        pts.append(loop)
        segs.append(np.column_stack([np.arange(k), (np.arange(k) + 1) % k]) + first)
        first += k
    return np.concatenate(pts), np.concatenate(segs), np.array(holes, float)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--min-angle", type=float, default=30.0)
    ap.add_argument("--size", type=float, default=0.002, help="area bound at the holes")
    ap.add_argument("-o", default="mesh_domain.png")
    a = ap.parse_args()
    pts, segs, holes = plate()
    centres = np.array([[x, 0.25] for x in (0.3, 0.75, 1.25, 1.7)])

    def area_bound(x, y):  # fine at the bolt holes, 20 times coarser far from them
        d = float(np.min(np.hypot(x - centres[:, 0], y - centres[:, 1])))
        return a.size * (1 + 19 * min(max((d - 0.09) / 0.4, 0.0), 1.0))

    t0 = time.perf_counter()
    m = gpugeom.mesh2d(pts, segs, holes=holes, min_angle=a.min_angle, max_area=area_bound)
    ms = 1e3 * (time.perf_counter() - t0)
    ok, msg = gpugeom.verify.check_mesh2d(m, segs, min_angle=a.min_angle)
    v, t = m["vertices"], m["triangles"]
    e = v[t[:, [1, 2, 0]]] - v[t]  # edge vectors
    ln = np.linalg.norm(e, axis=2)
    cosines = [-(e[:, i] * e[:, (i + 2) % 3]).sum(1) / (ln[:, i] * ln[:, (i + 2) % 3])
               for i in range(3)]
    smallest = np.degrees(np.arccos(np.clip(np.max(cosines, axis=0), -1, 1)))
    print(f"{len(pts)} input points, {len(segs)} segments: {len(v)} vertices, {len(t)} triangles "
          f"in {ms:.1f} ms; smallest angle {smallest.min():.2f} degrees "
          f"({len(m.small_angles)} forced by the input); exact check: {ok} {msg}")

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [2.2, 1]})
    ax.triplot(v[:, 0], v[:, 1], t, lw=0.25, color="k")
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"{len(t)} triangles, every angle >= {a.min_angle:g} degrees")
    bx.hist(smallest, bins=60, color="tab:blue")
    bx.axvline(a.min_angle, color="tab:red", lw=1)
    bx.set_xlabel("smallest angle of a triangle (degrees)")
    bx.set_ylabel("triangles")
    fig.tight_layout()
    fig.savefig(a.o, dpi=120)
    print("->", a.o)


if __name__ == "__main__":
    main()
