#!/usr/bin/env python3
"""The Voronoi diagram of `gpugeom delaunay2d --voronoi` against SciPy's (Qhull), on points in
general position: for every input point the same finite cell vertices (to rounding) and the
same boundedness, and the same ridges (pairs of points). Skips when SciPy is missing."""
import json, os, subprocess, sys, tempfile

def main():
    cli = sys.argv[1]
    try:
        import numpy as np
        from scipy.spatial import Voronoi
    except ImportError as e:
        print(f"SKIPPED: SciPy not available ({e})")
        return 0
    fails = 0
    with tempfile.TemporaryDirectory() as tmp:
        for dist, n, seed in [("uniform", 2000, 3), ("gaussian", 5000, 4), ("thin_circle", 3000, 5)]:
            pts = os.path.join(tmp, "p.npy")
            vor = os.path.join(tmp, "v.json")
            subprocess.run([cli, "--quiet", "gen", dist + "2d", "-n", str(n), "--seed", str(seed), "-o", pts], check=True)
            subprocess.run([cli, "--quiet", "delaunay2d", pts, "--voronoi", vor], check=True)
            p = np.load(pts)
            ours = json.load(open(vor))
            ref = Voronoi(p)
            verts = np.array(ours["vertices"])
            scale = np.abs(p).max()
            for i in range(n):
                mine = ours["regions"][i]
                theirs = ref.regions[ref.point_region[i]]
                if (-1 in mine) != (-1 in theirs):
                    print(f"{dist}: point {i} bounded differently"); fails += 1; break
                a = np.unique(np.round(verts[[v for v in mine if v >= 0]] / scale, 9), axis=0)
                b = np.unique(np.round(ref.vertices[[v for v in theirs if v >= 0]] / scale, 9), axis=0)
                if a.shape != b.shape or not np.allclose(a, b, atol=1e-8):
                    print(f"{dist}: point {i} has other cell vertices"); fails += 1; break
            mine_r = {tuple(sorted(r)) for r in ours["ridge_points"]}
            their_r = {tuple(sorted(map(int, r))) for r in ref.ridge_points}
            if mine_r != their_r:
                print(f"{dist}: ridges differ ({len(mine_r ^ their_r)} not shared)"); fails += 1
            else:
                print(f"ok: {dist} {n}: {len(mine_r)} ridges, every cell as SciPy's")
    return 1 if fails else 0

if __name__ == "__main__":
    sys.exit(main())
