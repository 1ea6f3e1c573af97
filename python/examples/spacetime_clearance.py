#!/usr/bin/env python3
"""
Clearance in space and time: a 4D distance transform
====================================================

Clearance in space and time: the exact distance transform of a 4D grid (time, z, y, x).

Spheres drift through a box over a number of frames. Every cell of the 4D grid gets its
distance to the nearest occupied cell in space *and* time, with one frame weighted as `--dt`
cells of space (`sampling`): a planner reads off how far it is, at any moment, from anything
that was or will be there. `slices=` computes a few frames alone, exactly as the whole grid
would have them. The figure shows the middle z plane at four times.

  python3 spacetime_clearance.py [-n 48] [--frames 32] [-o spacetime_clearance.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import gpugeom


def occupancy(n, frames, rng, spheres=6):
    """True where a sphere is: centres move on straight lines through the box."""
    start = rng.random((spheres, 3)) * n
    velocity = (rng.random((spheres, 3)) - 0.5) * n / frames
    radius = rng.uniform(0.05, 0.12, spheres) * n
    z, y, x = np.meshgrid(*(np.arange(n),) * 3, indexing="ij")
    occ = np.zeros((frames, n, n, n), dtype=bool)
    for t in range(frames):
        c = (start + velocity * t) % n
        for (cz, cy, cx), r in zip(c, radius):
            occ[t] |= (z - cz) ** 2 + (y - cy) ** 2 + (x - cx) ** 2 <= r * r
    return occ


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=48, help="cells along each space axis")
    ap.add_argument("--frames", type=int, default=32)
    ap.add_argument("--dt", type=float, default=2.0, help="one frame, in cells of space")
    ap.add_argument("-o", default="spacetime_clearance.png")
    a = ap.parse_args()
    occ = occupancy(a.n, a.frames, np.random.default_rng(3))
    free = ~occ  # non-zero: distance to the nearest occupied (zero) cell
    sampling = (a.dt, 1.0, 1.0, 1.0)
    t0 = time.perf_counter()
    dist = gpugeom.distance_transform_edt(free, sampling=sampling)
    t1 = time.perf_counter()
    frames = [0, a.frames // 3, 2 * a.frames // 3, a.frames - 1]
    some = gpugeom.distance_transform_edt(free, sampling=sampling, slices=frames)
    print(f"4D grid {free.shape}: {free.size / 1e6:.1f}M cells in {1e3 * (t1 - t0):.1f} ms; "
          f"largest clearance {dist.max():.2f} cells")
    print(f"slices equal the whole grid's: {np.array_equal(some, dist[frames])}")
    try:
        import scipy.ndimage as ndi

        small = free[:, ::2, ::2, ::2]
        same = np.array_equal(gpugeom.distance_transform_edt(small, sampling=sampling),
                              ndi.distance_transform_edt(small, sampling=sampling))
        print(f"exact check: {same} (against scipy.ndimage, {small.shape})")
    except ImportError:
        pass
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.6))
    for ax, t in zip(axes, frames):
        im = ax.imshow(dist[t, a.n // 2], cmap="magma", vmin=0, vmax=float(dist.max()))
        ax.contour(occ[t, a.n // 2], levels=[0.5], colors="cyan", linewidths=0.8)
        ax.set_title(f"frame {t}")
        ax.set_axis_off()
    fig.colorbar(im, ax=axes, shrink=0.8, label="clearance in space-time (cells)")
    fig.suptitle("Distance to the nearest occupied cell in (t, z, y, x), middle z plane")
    fig.savefig(a.o, dpi=110)
    print(f"wrote {a.o}")


if __name__ == "__main__":
    main()
