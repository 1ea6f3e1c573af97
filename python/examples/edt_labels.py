#!/usr/bin/env python3
"""
Distance transform and Voronoi labels of a photograph
=====================================================

The exact Euclidean distance transform of an image and its digital Voronoi labels.

Dark regions of a photograph (matplotlib's sample portrait of Grace Hopper) are the sites;
every pixel gets its distance to the nearest dark pixel (scipy.ndimage's
distance_transform_edt, computed exactly on the GPU when there is one), and a few hundred
labelled seeds grow into their digital Voronoi regions (voronoi_labels).

  python3 edt_labels.py [-o edt_labels.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.cbook as cbook
import matplotlib.image as mpimg
import matplotlib.pyplot as plt
import numpy as np

import gpugeom


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", default="edt_labels.png")
    a = ap.parse_args()
    img = mpimg.imread(cbook.get_sample_data("grace_hopper.jpg", asfileobj=False))
    grey = img[..., :3].astype(np.float64).mean(axis=2) / 255.0
    background = grey > 0.25  # non-zero: distance to the nearest dark (zero) pixel
    t0 = time.perf_counter()
    dist, ind = gpugeom.distance_transform_edt(background, return_indices=True)
    t1 = time.perf_counter()
    rng = np.random.default_rng(0)
    seeds = np.zeros(grey.shape, dtype=np.int32)
    r, c = rng.integers(0, grey.shape[0], 300), rng.integers(0, grey.shape[1], 300)
    seeds[r, c] = np.arange(1, 301)
    labels, ldist = gpugeom.voronoi_labels(seeds, return_distances=True)
    t2 = time.perf_counter()
    print(f"{grey.shape} image: EDT + feature transform {1e3 * (t1 - t0):.1f} ms, "
          f"Voronoi labels {1e3 * (t2 - t1):.1f} ms")

    fig, ax = plt.subplots(1, 3, figsize=(15, 5.6))
    ax[0].imshow(grey, cmap="gray")
    ax[0].set_title("photograph (sites: dark pixels)")
    ax[1].imshow(dist, cmap="magma")
    ax[1].set_title("exact distance to the nearest dark pixel")
    perm = rng.permutation(301)
    ax[2].imshow(perm[labels], cmap="tab20", interpolation="nearest")
    ax[2].contour(ldist, levels=8, colors="k", linewidths=0.3)
    ax[2].plot(c, r, "k.", ms=2)
    ax[2].set_title("digital Voronoi regions of 300 seeds")
    for x in ax:
        x.axis("off")
    fig.tight_layout()
    fig.savefig(a.o, dpi=110)
    print("->", a.o)


if __name__ == "__main__":
    main()
