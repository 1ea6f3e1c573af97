#!/usr/bin/env python3
"""CPU anchor for the 3D convex hull benchmark: Qhull through SciPy's ConvexHull, one core, on
the very points gpugeom_bench_hull3d used (the .npy files its --save DIR wrote). Prints a table
and appends CSV rows. Each input runs --reps times (the same median as gpugeom's rows; the
fastest run is printed too, since Qhull's time on a shared machine varies by up to 2x between
runs).
"""
import argparse, glob, os, sys

from anchor_common import append_row, timed_ms

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True, help="folder of .npy inputs (gpugeom_bench_hull3d --save)")
    ap.add_argument("--max-n", type=float, default=1e8, help="skip inputs larger than this")
    ap.add_argument("--reps", type=int, default=3, help="runs per input (median recorded)")
    ap.add_argument("--csv")
    a = ap.parse_args()
    import numpy as np
    try:
        from scipy.spatial import ConvexHull
    except ImportError as e:
        print(f"note: Qhull anchor skipped ({e})")
        return 0
    print(f"{'input':26s} {'n':>10s} {'tool':12s} {'median ms':>10s} {'fastest':>10s} {'vertices':>9s}")
    for f in sorted(glob.glob(os.path.join(a.dir, "*.npy"))):
        p = np.ascontiguousarray(np.load(f), dtype=np.float64)
        if len(p) > a.max_n:
            continue
        name = os.path.basename(f)[:-4].rsplit("_", 1)[0].replace("scal_", "scal:")
        runs = [timed_ms(lambda q: len(ConvexHull(q).vertices), p) for _ in range(max(1, a.reps))]
        nv = runs[0][0]
        times = sorted(t for _, t in runs)
        ms = times[len(times) // 2]
        print(f"{name:26s} {len(p):10d} {'qhull':12s} {ms:10.1f} {times[0]:10.1f} {nv:9d}", flush=True)
        append_row(a.csv, "hull3d", name, len(p), "qhull", ms)
    return 0

if __name__ == "__main__":
    sys.exit(main())
