#!/usr/bin/env python3
"""
Voronoi cells of particles in a periodic box
============================================

Voronoi cells of particles in a periodic box, as a molecular-dynamics or granular-matter
analysis uses them.

Two particle sets in the unit box: an ideal gas (uniform points) and a jittered crystal (a
simple cubic lattice whose sites are shaken a little). gpugeom.VoronoiCells gives every
particle's cell (volume, surface area, neighbours, faces) in the periodic box; the cells fill
the box exactly. The picture shows the distribution of cell volumes and of neighbour counts for
both sets, and a few cells of the crystal drawn from their faces.

  python3 particle_cells.py [-n 20000] [-o particle_cells.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import gpugeom


def crystal(n, rng, shake=0.08):
    m = max(2, round(n ** (1 / 3)))
    sites = (np.indices((m, m, m)).reshape(3, -1).T + 0.5) / m
    return (sites + rng.normal(0, shake / m, sites.shape)) % 1.0


def padded(faces):
    """The faces (ragged: 3 to a dozen vertices each) as one masked array, each padded with its
    last vertex. Given the ragged list, matplotlib (3.11) pads it with uninitialised rows, and
    its autoscaling reads them: limits of whatever the memory held."""
    k = max(len(f) for f in faces)
    out = np.ma.masked_all((len(faces), k, 3))
    for j, f in enumerate(faces):
        out[j] = np.concatenate([f, np.repeat(f[-1:], k - len(f), axis=0)])
        out[j, len(f):] = np.ma.masked
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=20000)
    ap.add_argument("-o", default="particle_cells.png")
    a = ap.parse_args()
    rng = np.random.default_rng(3)
    sets = {"ideal gas": rng.random((a.n, 3)), "jittered crystal": crystal(a.n, rng)}
    fig = plt.figure(figsize=(13, 4.2))
    ax_v, ax_k = fig.add_subplot(1, 3, 1), fig.add_subplot(1, 3, 2)
    ok = True
    for name, p in sets.items():
        t0 = time.perf_counter()
        c = gpugeom.VoronoiCells(p, box=[0, 1], periodic=True)
        ms = 1e3 * (time.perf_counter() - t0)
        vol = np.asarray(c.volumes)
        k = np.diff(np.asarray(c.face_offsets))
        fills = abs(vol.sum() - 1) < 1e-9
        ok &= fills
        print(f"{name}: {len(p)} cells in {ms:.1f} ms on {c.stats['backend']}, mean "
              f"{k.mean():.2f} neighbours, volume sum {vol.sum():.15f}")
        ax_v.hist(vol * len(p), bins=60, histtype="step", density=True, label=name)
        ax_k.hist(k, bins=np.arange(k.min(), k.max() + 2) - 0.5, histtype="step", density=True,
                  label=name)
        cells = c
    print(f"exact check: {ok} (the cells fill the box)")
    ax_v.set_xlabel("cell volume / mean volume")
    ax_v.legend()
    ax_k.set_xlabel("neighbours (faces) per cell")
    ax3 = fig.add_subplot(1, 3, 3, projection="3d")
    centre = np.argsort(np.linalg.norm(np.asarray(cells.centroids) - 0.5, axis=1))[:6]
    for i, colour in zip(centre, plt.cm.tab10.colors):
        ax3.add_collection3d(Poly3DCollection(padded(cells.cell_faces(int(i))), alpha=0.35,
                                              facecolor=colour, edgecolor="k", linewidths=0.3),
                             autolim=False)
    pts = np.concatenate([np.concatenate(cells.cell_faces(int(i))) for i in centre])
    for set_lim, d in ((ax3.set_xlim, 0), (ax3.set_ylim, 1), (ax3.set_zlim, 2)):
        set_lim(pts[:, d].min(), pts[:, d].max())
    ax3.set_title("six cells of the crystal")
    fig.tight_layout()
    fig.savefig(a.o, dpi=120)
    print(f"wrote {a.o}")


if __name__ == "__main__":
    main()
