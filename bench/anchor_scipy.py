#!/usr/bin/env python3
"""SciPy / Qhull anchors on the same points gpugeom generates (read back from .npy files
written by `gpugeom gen`): 2D/3D Delaunay and the 3D convex hull. Appends CSV rows."""
import argparse, os, subprocess, sys, tempfile, time

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
                t0 = time.perf_counter()
                out = len(ConvexHull(p).simplices) if a.problem == "hull3d" else len(Delaunay(p).simplices)
                ms = 1e3 * (time.perf_counter() - t0)
                print(f"{a.problem:11s} {d:12s} {n:10d} scipy {ms:10.1f} ms  ({out} simplices)")
                if a.csv:
                    with open(a.csv, "a") as c:
                        c.write(f"{a.problem},{d}{dim},{n},scipy-qhull,cpu-1core,0,{ms},0,{ms},{ms},0\n")
    return 0

if __name__ == "__main__":
    sys.exit(main())
