#!/usr/bin/env python3
"""
Stippling a photograph with a centroidal Voronoi diagram
========================================================

A stipple drawing of a photograph: dots at the sites of the weighted centroidal Voronoi
diagram of its darkness (Lloyd's iteration on the GPU), each dot as large as its cell is dark.
A tqdm bar follows the iterations when tqdm is installed.

  python3 stipple_photo.py [-n 20000] [-o stipple.png]
"""
import argparse
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.cbook as cbook
import matplotlib.image as mpimg
import matplotlib.pyplot as plt

import gpugeom


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=20000)
    ap.add_argument("-o", default="stipple.png")
    ap.add_argument("--iterations", type=int, default=200)
    a = ap.parse_args()
    img = mpimg.imread(cbook.get_sample_data("grace_hopper.jpg", asfileobj=False))
    try:
        from tqdm import tqdm

        bar = tqdm(total=a.iterations, desc="Lloyd iterations")
    except ImportError:
        bar = None
    t0 = time.perf_counter()
    s = gpugeom.stipple(img, a.n, progress=bar, gamma=1.2, max_iterations=a.iterations)
    if bar is not None:
        bar.close()
    print(f"{a.n} dots, {s.iterations} iterations (converged: {s.converged}) in "
          f"{time.perf_counter() - t0:.2f} s on {s.stats['backend']}")
    fig, ax = plt.subplots(figsize=(6, 6 * s.shape[0] / s.shape[1]))
    s.plot(ax)
    ax.axis("off")
    fig.tight_layout()
    fig.savefig(a.o, dpi=150)
    print("->", a.o)


if __name__ == "__main__":
    main()
