#!/usr/bin/env python3
"""
The convex hull of a terrain scan
=================================

The exact convex hull of a scanned point cloud.

A LiDAR-like scan of terrain: matplotlib's sample elevation model of the Jacksboro fault,
sampled at a few hundred thousand random positions with bilinear interpolation and scanner
noise (x, y, elevation in metres). gpugeom.ConvexHull gives its hull exactly (only extreme
points as vertices); the picture shows the cloud and the hull's facets.

  python3 hull_scan.py [-n 400000] [-o hull_scan.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.cbook as cbook
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import gpugeom


def scan(n, rng):
    dem = cbook.get_sample_data("jacksboro_fault_dem.npz")
    z = dem["elevation"].astype(np.float64)
    # The grid is in degrees (3 arc-seconds); metres at the tile's latitude.
    lat = np.radians(0.5 * (float(dem["ymin"]) + float(dem["ymax"])))
    dy = float(dem["dy"]) * 111320.0
    dx = float(dem["dx"]) * 111320.0 * np.cos(lat)
    u = rng.random(n) * (z.shape[1] - 1)
    v = rng.random(n) * (z.shape[0] - 1)
    i, j = np.floor(v).astype(int), np.floor(u).astype(int)
    fu, fv = u - j, v - i
    i1, j1 = np.minimum(i + 1, z.shape[0] - 1), np.minimum(j + 1, z.shape[1] - 1)
    h = (z[i, j] * (1 - fu) * (1 - fv) + z[i, j1] * fu * (1 - fv) + z[i1, j] * (1 - fu) * fv +
         z[i1, j1] * fu * fv)
    return np.column_stack([u * dx, v * dy, h + rng.normal(0, 0.5, n)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=400000)
    ap.add_argument("-o", default="hull_scan.png")
    a = ap.parse_args()
    p = scan(a.n, np.random.default_rng(1))
    t0 = time.perf_counter()
    hull = gpugeom.ConvexHull(p)
    ms = 1e3 * (time.perf_counter() - t0)
    ok, msg = gpugeom.verify.check_convex_hull(p, hull.simplices)
    print(f"{len(p)} scanned points: hull of {len(hull.vertices)} vertices, {hull.nsimplex} "
          f"facets, volume {hull.volume:.4g} m^3, area {hull.area:.4g} m^2, in {ms:.1f} ms on "
          f"{hull.stats['backend']}; exact check: {ok} {msg}")
    fig = plt.figure(figsize=(9, 7))
    ax = fig.add_subplot(projection="3d")
    sub = p[:: max(1, len(p) // 20000)]
    ax.scatter(sub[:, 0], sub[:, 1], sub[:, 2], s=0.3, c=sub[:, 2], cmap="terrain")
    ax.add_collection3d(Poly3DCollection(p[hull.simplices], alpha=0.15, facecolor="tab:orange",
                                         edgecolor="k", linewidths=0.2))
    ax.set_box_aspect((np.ptp(p[:, 0]), np.ptp(p[:, 1]), 8 * np.ptp(p[:, 2])))
    ax.set_title(f"convex hull of a {len(p)}-point terrain scan (elevation x8)")
    fig.tight_layout()
    fig.savefig(a.o, dpi=120)
    print("->", a.o)


if __name__ == "__main__":
    main()
