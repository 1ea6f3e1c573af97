#!/usr/bin/env python3
"""The caller's allocator against the library's own pool (issue 48), in one run: each problem
called from PyTorch tensors and from CuPy arrays on the GPU, once with the framework's caching
allocator lent to the library (what the package does) and once with the library's pool (the
allocator not lent), alternating, median of --reps. Also how many blocks a call takes, which is
what lending costs: each one is a Python call into the framework.

  python3 bench/python_memory.py [--reps 5] [--quick]

Prints a table with the GPU's name.
"""
import argparse
import statistics
import time

import numpy as np

import gpugeom
from gpugeom import _arrays, _memory


class Counted:
    def __init__(self, inner):
        self.inner, self.n = inner, 0

    def allocate(self, nbytes, stream):
        self.n += 1
        return self.inner.allocate(nbytes, stream)

    def deallocate(self, ptr, nbytes, stream):
        self.inner.deallocate(ptr, nbytes, stream)

    def cached_bytes(self, device):
        return self.inner.cached_bytes(device)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    info = gpugeom.device_info()
    if not info["available"]:
        print("# no usable GPU:", info["reason"])
        return
    print(f"# gpugeom {gpugeom.__version__}, GPU: {info['name']}", flush=True)
    rng = np.random.default_rng(3)
    n3, n2, side = (10**5, 10**5, 128) if a.quick else (10**6, 10**6, 256)
    problems = [
        ("delaunay3d uniform", n3, lambda x: gpugeom.Delaunay(x), rng.random((n3, 3))),
        ("delaunay2d uniform", n2, lambda x: gpugeom.Delaunay(x), rng.random((n2, 2))),
        ("convex hull ball", n3, lambda x: gpugeom.ConvexHull(x), rng.random((n3, 3)) - 0.5),
        ("edt+indices", side**3, lambda x: gpugeom.distance_transform_edt(x, return_indices=True),
         rng.random((side, side, side)) > 0.001),
    ]
    frameworks = []
    try:
        import torch

        frameworks.append(("torch", lambda h: torch.from_numpy(h).cuda(), torch.cuda.synchronize))
    except ImportError:
        pass
    try:
        import cupy

        frameworks.append(("cupy", cupy.asarray, cupy.cuda.Device().synchronize))
    except ImportError:
        pass
    plain = lambda name, stream: stream  # noqa: E731  (the allocator not lent)
    lent = _arrays.call_stream
    print(f"{'problem':22s} {'n':>10} {'arrays':6s} {'lent ms':>9} {'pool ms':>9} {'ratio':>6} "
          f"{'blocks/call':>11}")
    for name, to_dev, sync in frameworks:
        for problem, n, call, host in problems:
            x = to_dev(host)
            counted = Counted(_memory.allocator(name))
            times = {"lent": [], "pool": []}
            for r in range(a.reps + 1):
                for mode in ("lent", "pool"):
                    _arrays.call_stream = (
                        (lambda nm, s: (s if s else 1, counted)) if mode == "lent" else plain)
                    sync()
                    t = time.perf_counter()
                    res = call(x)
                    sync()
                    if r:  # (the first round warms both)
                        times[mode].append(1e3 * (time.perf_counter() - t))
                    del res
            _arrays.call_stream = lent
            ml, mp = statistics.median(times["lent"]), statistics.median(times["pool"])
            blocks = counted.n / (a.reps + 1)
            print(f"{problem:22s} {n:>10} {name:6s} {ml:9.2f} {mp:9.2f} {ml / mp:6.3f} "
                  f"{blocks:11.0f}", flush=True)


if __name__ == "__main__":
    main()
