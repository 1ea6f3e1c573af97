#!/usr/bin/env python3
"""
Density of a clustered point cloud from its Delaunay tetrahedralisation (DTFE)
==============================================================================

The Delaunay Tessellation Field Estimator, as cosmology uses it on simulation snapshots: each
point's density is 4 over the volume of the tetrahedra around it, and the density field is
linear inside every tetrahedron. The points are a toy snapshot (haloes of many sizes on a
uniform background in a unit box); ``gpugeom.Delaunay`` tetrahedralises them exactly, and
``find_simplex`` with the barycentric ``transform`` interpolates the field on a slice.

  python3 dtfe_density.py [-n 200000] [--pixels 300] [-o dtfe_density.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import gpugeom


def snapshot(n, rng):
    """Haloes (gaussian blobs with a power-law spread of masses) on a uniform background."""
    k = 60
    centres = rng.random((k, 3))
    mass = rng.pareto(1.2, k) + 1
    sizes = 0.012 * mass ** (1 / 3)
    share = (mass / mass.sum() * 0.8 * n).astype(int)
    pts = [rng.random((n - share.sum(), 3))]
    for c, s, m in zip(centres, sizes, share):
        pts.append(c + rng.normal(0, s, (m, 3)))
    p = np.concatenate(pts)
    return p[np.all((p > 0) & (p < 1), axis=1)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=200000)
    ap.add_argument("--pixels", type=int, default=300)
    ap.add_argument("-o", default="dtfe_density.png")
    a = ap.parse_args()
    p = snapshot(a.n, np.random.default_rng(3))
    t0 = time.perf_counter()
    tri = gpugeom.Delaunay(p)
    ms = 1e3 * (time.perf_counter() - t0)
    s = tri.simplices
    ok, msg = gpugeom.verify.check_delaunay(p, s)
    # every tetrahedron's volume, summed over its four vertices: the contiguous Voronoi cell
    d = p[s[:, 1:]] - p[s[:, :1]]
    vol = np.abs(np.linalg.det(d)) / 6
    star = np.zeros(len(p))
    for k in range(4):
        np.add.at(star, s[:, k], vol)
    rho = 4.0 / star  # points per unit volume (the mean is len(p))
    # the field on the slice z = 0.5, linear inside each tetrahedron
    g = (np.arange(a.pixels) + 0.5) / a.pixels
    xs, ys = np.meshgrid(g, g)
    q = np.column_stack([xs.ravel(), ys.ravel(), np.full(xs.size, 0.5)])
    t = tri.find_simplex(q)
    inside = t >= 0
    T = tri.transform[t[inside]]
    b = np.einsum("ijk,ik->ij", T[:, :3], q[inside] - T[:, 3])
    bary = np.column_stack([b, 1 - b.sum(1)])
    field = np.full(len(q), np.nan)
    field[inside] = (bary * rho[s[t[inside]]]).sum(1)
    print(f"{len(p)} points: {len(s)} tetrahedra in {ms:.0f} ms on {tri.stats['backend']}; "
          f"exact check: {ok} {msg}; density from {rho.min():.3g} to {rho.max():.3g} "
          f"(mean {len(p)})")

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5.4))
    im = ax.imshow(np.log10(field.reshape(xs.shape) / len(p)), origin="lower",
                   extent=(0, 1, 0, 1), cmap="magma")
    fig.colorbar(im, ax=ax, label="log10 density / mean")
    ax.set_title("DTFE density on the slice z = 0.5")
    near = np.abs(p[:, 2] - 0.5) < 0.01
    bx.scatter(p[near, 0], p[near, 1], s=0.5, c="k")
    bx.set_aspect("equal")
    bx.set_xlim(0, 1)
    bx.set_ylim(0, 1)
    bx.set_title("the points within 0.01 of the slice")
    fig.tight_layout()
    fig.savefig(a.o, dpi=110)
    print("->", a.o)


if __name__ == "__main__":
    main()
