#!/usr/bin/env python3
"""Anchors for the 2D Delaunay benchmark, on the very points gpugeom_bench_del2d uses
(`gpugeom gen` with the same seed, or the same .npy files): Triangle (the `triangle` package,
Shewchuk's code) and SciPy's Delaunay (Qhull), one core each; CuPy's `cupyx.scipy.spatial.Delaunay`
(a GPU code) with the points already on the device (`cupy`: simplices left there) and as a
NumPy caller calls it (`cupy_host`: host points in, host simplices out). Median of 3 after a
warm-up for the CuPy tools. Prints a table, appends CSV rows.
"""
import argparse, os, statistics, subprocess, sys, tempfile, time

from anchor_common import append_row, timed_ms

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gpugeom", required=True)
    ap.add_argument("--dists", default="uniform")
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--files", default="")
    ap.add_argument("--scipy-max", type=float, default=1e6, help="skip Qhull above this size")
    ap.add_argument("--tools", default="triangle,scipy-qhull")
    ap.add_argument("--csv")
    a = ap.parse_args()
    import numpy as np
    tools = {}
    try:
        import triangle
        tools["triangle"] = lambda p: len(triangle.triangulate({"vertices": p}, "Q")["triangles"])
    except ImportError as e:
        print(f"note: Triangle anchor skipped ({e})")
    try:
        from scipy.spatial import Delaunay
        tools["scipy-qhull"] = lambda p: len(Delaunay(p).simplices)
    except ImportError as e:
        print(f"note: SciPy anchor skipped ({e})")
    if "cupy" in a.tools or "cupy_host" in a.tools:
        try:
            import cupy as cp
            from cupyx.scipy.spatial import Delaunay as CuDelaunay

            def median3(f, setup=lambda p: p):
                def run(p):
                    x = setup(p)  # (not timed: e.g. the upload of a device-resident run)
                    f(x)  # warm-up
                    ts = []
                    for _ in range(3):
                        t0 = time.perf_counter()
                        nt = f(x)
                        ts.append(1e3 * (time.perf_counter() - t0))
                    return nt, statistics.median(ts)
                return run

            def on_device(d):
                t = CuDelaunay(d).simplices
                cp.cuda.Device().synchronize()
                return int(t.shape[0])

            def host(p):
                return int(cp.asnumpy(CuDelaunay(cp.asarray(p)).simplices).shape[0])

            tools["cupy"] = median3(on_device, cp.asarray)
            tools["cupy_host"] = median3(host)
        except Exception as e:  # ImportError, or a CuPy without spatial.Delaunay
            print(f"note: CuPy anchor skipped ({e})")
    tools = {k: v for k, v in tools.items() if k in a.tools.split(",")}
    inputs = []
    with tempfile.TemporaryDirectory() as tmp:
        for d in filter(None, a.dists.split(",")):
            for s in filter(None, a.sizes.split(",")):
                n = int(float(s))
                f = os.path.join(tmp, f"{d}_{n}.npy")
                subprocess.run([a.gpugeom, "--quiet", "gen", d + "2d", "-n", str(n), "--seed", "1",
                                "-o", f], check=True)
                inputs.append((d, np.load(f)))
        for f in filter(None, a.files.split(",")):
            inputs.append((os.path.basename(f), np.load(f)))
        print(f"{'distribution':22s} {'n':>10s} {'tool':12s} {'ms':>10s} {'triangles':>10s}")
        for name, p in inputs:
            p = np.ascontiguousarray(p[:, :2], dtype=np.float64)
            for tool, run in tools.items():
                if tool == "scipy-qhull" and len(p) > a.scipy_max:
                    continue
                if tool.startswith("cupy"):
                    nt, ms = run(p)
                else:
                    nt, ms = timed_ms(run, p)
                print(f"{name:22s} {len(p):10d} {tool:12s} {ms:10.1f} {nt:10d}", flush=True)
                append_row(a.csv, "delaunay2d", name, len(p), tool, ms)
    return 0

if __name__ == "__main__":
    sys.exit(main())
