"""The CLI's convex hull against Qhull (SciPy's ConvexHull): the same extreme points, and every
facet's plane through three of them with every input point on its inner side."""
import os
import subprocess
import sys
import tempfile

import numpy as np

try:
    from scipy.spatial import ConvexHull
except ImportError:  # the oracle is optional: say so and skip (CTest's skip code)
    print("SKIPPED: scipy is not installed")
    sys.exit(77)

cli = sys.argv[1]
fail = 0
with tempfile.TemporaryDirectory() as w:
    cases = [("ball3d", 20000), ("sphere3d", 5000), ("thin_box3d", 20000), ("uniform3d", 50000),
             ("gaussian3d", 20000), ("grid3d", 4000), ("thin_sphere3d", 20000)]
    for dist, n in cases:
        pts = os.path.join(w, dist + ".npy")
        out = os.path.join(w, dist + "_hull.npy")
        subprocess.run([cli, "gen", dist, "-n", str(n), "-o", pts, "--seed", "5"], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run([cli, "hull3d", pts, "-o", out], check=True, stdout=subprocess.DEVNULL)
        p = np.load(pts)
        tris = np.load(out)
        ours = set(np.unique(tris).tolist())
        want = set(ConvexHull(p).vertices.tolist())
        if ours != want:
            print(f"FAIL {dist}: {len(ours)} vertices, Qhull {len(want)};"
                  f" only ours {sorted(ours - want)[:5]}, only Qhull {sorted(want - ours)[:5]}")
            fail = 1
            continue
        a, b, c = p[tris[:, 0]], p[tris[:, 1]], p[tris[:, 2]]
        nrm = np.cross(b - a, c - a)
        side = np.einsum("ij,kj->ik", nrm, p) - np.einsum("ij,ij->i", nrm, a)[:, None]
        scale = np.abs(p).max() ** 3
        if side.max() > 1e-12 * scale:
            print(f"FAIL {dist}: a point lies outside a facet by {side.max()}")
            fail = 1
        print(f"ok {dist} n={n}: {len(ours)} extreme points, {len(tris)} facets, as Qhull")
sys.exit(fail)
