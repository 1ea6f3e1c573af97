#!/usr/bin/env python3
"""The I/O table (issue 24): gpugeom's readers and writers (gpugeom_bench_io, in-process) beside
NumPy's loadtxt / savetxt / load / save and meshio's VTU in the same run, MB/s per format.

  python3 bench/io_table.py --driver BUILD/bench/gpugeom_bench_io [--sizes 1e6,1e7]
                            [--anchor-max 1e6] [--reps 3] [--dir /tmp]

NumPy's text functions take seconds per 10^6 points, so the anchors stop at --anchor-max.
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

import numpy as np


def timed(f, reps):
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        ts.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(ts)


def row(fmt, op, n, mb, ms, tool):
    print(f"{fmt:14s} {op:5s} {n:10d} {mb:9.1f} MB {ms:9.1f} ms {mb / (ms / 1e3):8.0f} MB/s  {tool}",
          flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--driver", required=True)
    ap.add_argument("--sizes", default="1e6")
    ap.add_argument("--anchor-max", type=float, default=1e6)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--dir", default="/tmp")
    a = ap.parse_args()
    print(f"# {os.cpu_count()} CPUs; numpy {np.__version__}", flush=True)
    subprocess.run([a.driver, "--sizes", a.sizes, "--reps", str(a.reps), "--dir", a.dir],
                   check=True)
    try:
        import meshio
    except ImportError:
        meshio = None
        print("# meshio not installed: its VTU rows are left out")
    for n in [int(float(s)) for s in a.sizes.split(",")]:
        if n > a.anchor_max:
            continue
        rng = np.random.default_rng(1)
        p = rng.random((n, 3))
        f = os.path.join(a.dir, "io_anchor.xyz")
        reps = max(1, min(a.reps, 2))
        w = timed(lambda: np.savetxt(f, p, fmt="%.17g"), reps)
        mb = os.path.getsize(f) / 1e6
        row("xyz", "write", n, mb, w, "numpy.savetxt %.17g")
        row("xyz", "read", n, mb, timed(lambda: np.loadtxt(f), reps), "numpy.loadtxt")
        g = os.path.join(a.dir, "io_anchor.npy")
        w = timed(lambda: np.save(g, p), a.reps)
        mb = os.path.getsize(g) / 1e6
        row("npy", "write", n, mb, w, "numpy.save")
        row("npy", "read", n, mb, timed(lambda: np.load(g), a.reps), "numpy.load")
        os.remove(f)
        os.remove(g)
        if meshio is not None:
            from scipy.spatial import Delaunay

            q = rng.random((n, 2))
            tri = Delaunay(q).simplices.astype(np.int32)
            m = meshio.Mesh(np.column_stack([q, np.zeros(n)]), [("triangle", tri)])
            h = os.path.join(a.dir, "io_anchor.vtu")
            for name, kw in (("vtu", {"binary": True, "compression": None}),
                             ("vtu-zlib", {"binary": True, "compression": "zlib"}),
                             ("vtu-ascii", {"binary": False})):
                w = timed(lambda: meshio.vtu.write(h, m, **kw), reps)
                mb = os.path.getsize(h) / 1e6
                row(name, "write", n, mb, w, "meshio")
                row(name, "read", n, mb, timed(lambda: meshio.read(h), reps), "meshio")
            os.remove(h)
    return 0


if __name__ == "__main__":
    sys.exit(main())
