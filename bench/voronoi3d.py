#!/usr/bin/env python3
"""The 3D Voronoi diagram (issue 49) as a Python user calls it, against SciPy in one run:
gpugeom end to end (NumPy points in, host arrays out) and device-resident (CuPy in and out, timed
with a synchronise), SciPy's `scipy.spatial.Voronoi` on the host (once; only up to --scipy-max
points, as it takes seconds). Uniform points in the unit cube, and an integer grid for the
merged (cospherical) vertices.

  python3 bench/voronoi3d.py [--sizes 1e5,1e6] [--reps 3] [--scipy-max 1e5]

Prints the GPU's name and a line per size (median of --reps after a warm-up).
"""
import argparse
import time

import numpy as np

import gpugeom
from anchor_common import med


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--scipy-max", type=float, default=1e5)
    a = ap.parse_args()
    import cupy as cp
    import scipy.spatial as ss

    info = gpugeom.device_info()
    print(f"GPU: {info.get('name')}")
    rng = np.random.default_rng(1)

    sync = cp.cuda.runtime.deviceSynchronize

    for n in (int(float(s)) for s in a.sizes.split(",")):
        p = rng.random((n, 3))
        d = cp.asarray(p)
        gpugeom.Voronoi(d, backend="cuda")  # (warm-up)
        e2e = med(lambda: gpugeom.Voronoi(p, backend="cuda"), a.reps, sync)
        dev = med(lambda: gpugeom.Voronoi(d, backend="cuda"), a.reps, sync)
        v = gpugeom.Voronoi(d, backend="cuda")
        line = (f"3D Voronoi uniform {n}: gpugeom end to end {e2e:.1f} ms, device-resident "
                f"{dev:.1f} ms, {len(v.vertices)} vertices")
        if n <= a.scipy_max:
            t0 = time.perf_counter()
            s = ss.Voronoi(p)
            sc = (time.perf_counter() - t0) * 1e3
            assert len(s.vertices) == len(v.vertices)
            line += f"; SciPy {sc:.0f} ms ({sc / e2e:.0f}x end to end, {sc / dev:.0f}x device)"
        print(line, flush=True)
    g = np.array(np.meshgrid(*[np.arange(40.0)] * 3, indexing="ij")).reshape(3, -1).T
    v = gpugeom.Voronoi(cp.asarray(g), backend="cuda")
    print(f"3D Voronoi grid 40^3: {len(v.vertices)} vertices (one per cube: {39 ** 3})")


if __name__ == "__main__":
    main()
