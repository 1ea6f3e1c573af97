#!/usr/bin/env python3
"""The Python package against SciPy and CuPy in one run, as a Python user calls each: NumPy in /
NumPy out (gpugeom's host path, cupyx with its copies both ways) and CuPy in / CuPy out
(device-resident, timed with a synchronise). Also the Python layer's overhead over the
extension call (the C++ entry point plus zero-copy array hand-off), per call at 10^3 points and
as a fraction at 10^6.

  python3 bench/python_api.py [--quick] [--reps 3] [--csv out.csv]

Prints a table (median of --reps; SciPy once where it takes seconds) with the GPU's name.
"""
import argparse
import statistics
import sys
import time

import numpy as np

import gpugeom
from anchor_common import med
from gpugeom import _core


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--csv", default="")
    ap.add_argument("--scipy-max", type=float, default=1e6)
    ap.add_argument("--only-overhead", action="store_true")
    a = ap.parse_args()
    reps = a.reps
    rng = np.random.default_rng(7)
    info = gpugeom.device_info()
    gpu = info["name"] if info["available"] else "none (" + info["reason"] + ")"
    print(f"# gpugeom {gpugeom.__version__}, GPU: {gpu}, numpy {np.__version__}", flush=True)
    try:
        import cupy as cp
        from cupyx.scipy import ndimage as cnd
        sync = cp.cuda.get_current_stream().synchronize
    except Exception:  # no CuPy / no GPU
        cp = None
    import scipy
    import scipy.ndimage as ndi
    import scipy.spatial as ss
    print(f"# scipy {scipy.__version__}" + (f", cupy {cp.__version__}" if cp else ""), flush=True)
    rows = []

    def row(problem, n, tool, ms, note=""):
        rows.append((problem, n, tool, ms, note))
        print(f"{problem:28s} {n:>11} {tool:26s} {ms:12.3f} ms  {note}", flush=True)

    gpugeom.Delaunay(rng.random((1000, 2)))  # context, pools, threads warm

    # --- Python overhead per call (10^3) and at 10^6: the package's call and the extension's
    # call alternate, and the overhead is the median of the pairwise differences (the machine's
    # drift between separate series is larger than the overhead itself) ---
    for n in ([1000, 100000] if a.quick else [1000, 1000000]):
        p = rng.random((n, 2))
        k = 400 if n <= 1000 else 20
        py, core, diff = [], [], []
        for _ in range(k):
            t0 = time.perf_counter()
            gpugeom.Delaunay(p)
            t1 = time.perf_counter()
            _core.delaunay2d(p)
            t2 = time.perf_counter()
            py.append(1e3 * (t1 - t0))
            core.append(1e3 * (t2 - t1))
            diff.append(1e3 * ((t1 - t0) - (t2 - t1)))
        t_core = statistics.median(core)
        d = statistics.median(diff)
        row("delaunay2d overhead", n, "gpugeom.Delaunay", statistics.median(py))
        row("delaunay2d overhead", n, "_core.delaunay2d (C++ call)", t_core,
            f"python layer {1e3 * d:.1f} us = {100 * d / t_core:.1f} % (median of {k} pairs)")

    if a.only_overhead:
        return 0
    # --- 2D Delaunay ---
    for n in ([10**5] if a.quick else [10**6, 10**7]):
        p = rng.random((n, 2))
        row("Delaunay 2D uniform", n, "gpugeom numpy", med(lambda: gpugeom.Delaunay(p), reps))
        if cp is not None:
            g = cp.asarray(p)
            row("Delaunay 2D uniform", n, "gpugeom cupy (resident)",
                med(lambda: gpugeom.Delaunay(g), reps, sync))
        if n <= a.scipy_max:
            row("Delaunay 2D uniform", n, "scipy.spatial.Delaunay", med(lambda: ss.Delaunay(p), 1))
    # --- Voronoi 2D ---
    for n in ([10**5] if a.quick else [10**6]):
        p = rng.random((n, 2))
        row("Voronoi 2D uniform", n, "gpugeom numpy",
            med(lambda: gpugeom.Voronoi(p), reps))
        if cp is not None:
            g = cp.asarray(p)
            row("Voronoi 2D uniform", n, "gpugeom cupy (resident)",
                med(lambda: gpugeom.Voronoi(g), reps, sync))
        if n <= a.scipy_max:
            row("Voronoi 2D uniform", n, "scipy.spatial.Voronoi", med(lambda: ss.Voronoi(p), 1))
    # --- 3D hull ---
    for n in ([10**5] if a.quick else [10**6, 10**7]):
        p = rng.normal(size=(n, 3))
        p /= np.linalg.norm(p, axis=1)[:, None] ** 0.7  # a ball
        row("ConvexHull 3D ball", n, "gpugeom numpy", med(lambda: gpugeom.ConvexHull(p), reps))
        if cp is not None:
            g = cp.asarray(p)
            row("ConvexHull 3D ball", n, "gpugeom cupy (resident)",
                med(lambda: gpugeom.ConvexHull(g), reps, sync))
        if n <= a.scipy_max:
            row("ConvexHull 3D ball", n, "scipy.spatial.ConvexHull",
                med(lambda: ss.ConvexHull(p), 1))
    # --- 3D Delaunay ---
    for n in ([10**4] if a.quick else [10**5, 10**6]):
        p = rng.random((n, 3))
        row("Delaunay 3D uniform", n, "gpugeom numpy", med(lambda: gpugeom.Delaunay(p), reps))
        if cp is not None:
            g = cp.asarray(p)
            row("Delaunay 3D uniform", n, "gpugeom cupy (resident)",
                med(lambda: gpugeom.Delaunay(g), reps, sync))
        if n <= min(a.scipy_max, 10**5):
            row("Delaunay 3D uniform", n, "scipy.spatial.Delaunay", med(lambda: ss.Delaunay(p), 1))
    # --- EDT (10 % sites = zeros) ---
    for side in ([1024] if a.quick else [4096, 8192]):
        img = rng.random((side, side)) > 0.1
        n = side * side
        row(f"EDT {side}^2", n, "gpugeom numpy",
            med(lambda: gpugeom.distance_transform_edt(img), reps))
        if cp is not None:
            row(f"EDT {side}^2", n, "cupyx numpy in/out",
                med(lambda: cp.asnumpy(cnd.distance_transform_edt(cp.asarray(img))), reps))
            g = cp.asarray(img)
            row(f"EDT {side}^2", n, "gpugeom cupy (resident)",
                med(lambda: gpugeom.distance_transform_edt(g), reps, sync))
            row(f"EDT {side}^2", n, "cupyx cupy (resident)",
                med(lambda: cnd.distance_transform_edt(g), reps, sync))
        if side <= 4096:
            row(f"EDT {side}^2", n, "scipy.ndimage", med(lambda: ndi.distance_transform_edt(img), 1))
    # --- CVD ---
    side = 512 if a.quick else 2048
    y, x = np.mgrid[0:side, 0:side]
    dens = np.exp(-((x - side / 2) ** 2 + (y - side / 3) ** 2) / (side * side / 10)) + 0.02
    row(f"CVD {side}^2 20 iterations", 20000, "gpugeom numpy",
        med(lambda: gpugeom.centroidal_voronoi(dens, 20000, max_iterations=20, tol=0), reps))
    if a.csv:
        with open(a.csv, "w") as f:
            f.write("problem,n,tool,ms,note\n")
            for r in rows:
                f.write(",".join(str(v) for v in r) + "\n")


if __name__ == "__main__":
    sys.exit(main())
