#!/usr/bin/env python3
"""SciPy / Qhull anchors on the same points gpugeom generates (read back from .npy files
written by `gpugeom gen`): 2D/3D Delaunay and the 3D convex hull. Appends CSV rows."""
import argparse, os, subprocess, sys, tempfile

from anchor_common import append_row, timed_ms

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gpugeom", required=True)
    ap.add_argument("--problem", default="delaunay2d")
    ap.add_argument("--dist", default="uniform")
    ap.add_argument("--sizes", default="100000")
    ap.add_argument("--seed", default="1")
    ap.add_argument("--csv")
    a = ap.parse_args()
    try:
        import numpy as np
        from scipy.spatial import ConvexHull, Delaunay
    except ImportError as e:
        print(f"note: SciPy anchor skipped ({e})")
        return 0
    dim = "2d" if a.problem == "delaunay2d" else "3d"
    with tempfile.TemporaryDirectory() as tmp:
        for d in a.dist.split(","):
            for s in a.sizes.split(","):
                n = int(float(s))
                f = os.path.join(tmp, "p.npy")
                subprocess.run([a.gpugeom, "--quiet", "gen", d + dim, "-n", str(n), "--seed", a.seed, "-o", f], check=True)
                p = np.load(f)
                build = ConvexHull if a.problem == "hull3d" else Delaunay
                out, ms = timed_ms(lambda q: len(build(q).simplices), p)
                print(f"{a.problem:11s} {d:12s} {n:10d} scipy {ms:10.1f} ms  ({out} simplices)")
                append_row(a.csv, a.problem, d + dim, n, "scipy-qhull", ms, resident_ms=ms)
    return 0

if __name__ == "__main__":
    sys.exit(main())
