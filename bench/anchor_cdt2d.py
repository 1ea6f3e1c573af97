#!/usr/bin/env python3
"""CPU anchor for the 2D constrained Delaunay benchmark: Shewchuk's Triangle (the `triangle`
package) with -p (the planar straight-line graph: points and segments; Q: quiet), one core, on
the very inputs gpugeom_bench_cdt2d used (its --save DIR: NAME_points.npy, NAME_segments.npy).
Triangle's -p also removes the triangles outside the segments (gpugeom's Domain::Enclosed);
the times include that. Prints a table and appends CSV rows.
"""
import argparse, glob, os, sys

from anchor_common import append_row, timed_ms

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True, help="folder of inputs (gpugeom_bench_cdt2d --save)")
    ap.add_argument("--max-n", type=float, default=1e8, help="skip inputs with more points")
    ap.add_argument("--csv")
    a = ap.parse_args()
    import numpy as np
    try:
        import triangle
    except ImportError as e:
        print(f"note: Triangle anchor skipped ({e})")
        return 0
    print(f"{'input':16s} {'n':>10s} {'segments':>9s} {'tool':12s} {'ms':>10s} {'triangles':>10s}")
    for f in sorted(glob.glob(os.path.join(a.dir, "*_points.npy"))):
        name = os.path.basename(f)[: -len("_points.npy")]
        p = np.ascontiguousarray(np.load(f), dtype=np.float64)
        s = np.ascontiguousarray(np.load(f.replace("_points.npy", "_segments.npy")), dtype=np.int32)
        if len(p) > a.max_n:
            continue
        out, ms = timed_ms(lambda: triangle.triangulate({"vertices": p, "segments": s}, "pQ"))
        print(f"{name:16s} {len(p):10d} {len(s):9d} {'triangle -p':12s} {ms:10.1f} "
              f"{len(out['triangles']):10d}", flush=True)
        append_row(a.csv, "cdt2d", name, len(p), "triangle-p", ms)
    return 0

if __name__ == "__main__":
    sys.exit(main())
