"""Where a gpugeom.dask.delaunay call spends its time, step by step, in one process (Dask's
synchronous scheduler): each step of the blocks (the local points, the triangulation, what a round
requires, the finality test, the output) and of the call around them, summed over the blocks, in
milliseconds. For the blocks' own costs; the distributed costs (transfers, scheduling) are what
bench/dask_delaunay.py --tasks shows.

    python bench/dask_block_steps.py --dims 3 --n 1e7 --blocks 2 --backend cuda
"""
import argparse
import time
from collections import defaultdict

import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--dims", type=int, default=3)
    p.add_argument("--n", type=float, default=1e6)
    p.add_argument("--blocks", type=int, default=2)
    p.add_argument("--backend", default="cpu")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--repeat", type=int, default=2, help="runs; the last is reported")
    a = p.parse_args()
    import dask
    import gpugeom
    from gpugeom import _core
    from gpugeom.dask import _delaunay, _ghost
    dask.config.set(scheduler="synchronous")
    spent = defaultdict(float)

    def timed(owner, name, label=None):
        f = getattr(owner, name)

        def run(*args, **kwargs):
            t = time.perf_counter()
            try:
                return f(*args, **kwargs)
            finally:
                spent[label or name] += time.perf_counter() - t
        setattr(owner, name, run)

    for name in ("_local_points", "_held", "_curve_order", "_triangulated", "Delaunay", "_judge",
                 "_borders", "_border_parts", "_emit", "_copies", "_Outside", "final_simplices"):
        timed(_ghost, name)
    for name in ("_split", "_survey", "_frontiers", "_summary", "_global_hull", "_total",
                 "_whole", "_on_convex_surface", "_faces_to", "_match", "_neighbors_of"):
        timed(_delaunay, name)
    # the C++ passes, as the modules call them
    for name in ("block_required", "block_output", "circumballs_inside_region", "block_borders",
                 "split_to_blocks", "match_faces", "block_neighbors", "cell_counts",
                 "hull_candidates2d", "balls_in_bins", "empty_frontiers", "hilbert_order"):
        timed(_core, name, "_core." + name)
    n = int(a.n)
    pts = np.random.default_rng(1).random((n, a.dims))
    for _ in range(a.repeat):
        spent.clear()
        t = time.perf_counter()
        tri = gpugeom.dask.delaunay(pts, blocks=a.blocks, backend=a.backend, threads=a.threads)
        t_call = time.perf_counter()
        dask.compute(tri.simplices, tri.neighbors)  # (the neighbours' passes, the gathers)
        spent["(the arrays computed and gathered)"] = time.perf_counter() - t_call
        total = 1e3 * (time.perf_counter() - t)
    t = time.perf_counter()
    gpugeom.Delaunay(pts, backend=a.backend, threads=a.threads)
    single = 1e3 * (time.perf_counter() - t)
    info = gpugeom.device_info().get("name", "cpu") if a.backend != "cpu" else "cpu"
    print(f"{a.dims}D n={n} in {a.blocks} blocks on {info} ({a.backend}): {total:.0f} ms in all "
          f"(the single call: {single:.0f} ms); phases "
          + " ".join(f"{k} {v:.0f}" for k, v in tri.timings.items()), flush=True)
    for k, v in sorted(spent.items(), key=lambda kv: -kv[1]):
        print(f"  {k:36s} {1e3 * v:9.1f} ms")


if __name__ == "__main__":
    main()
