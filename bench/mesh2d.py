#!/usr/bin/env python3
"""Quality meshing: gpugeom.mesh2d (end to end from NumPy arrays, and device-resident from CuPy
arrays) against Shewchuk's Triangle (the `triangle` package, one core) and CGAL's Delaunay
mesher (bench/anchor_cgal_mesh2d, one core, when --cgal names it) on the same domains and bounds,
in one run. Prints the machine, a table (time, triangles, rounds, gpugeom's phases) and appends
CSV rows.

    python3 bench/mesh2d.py [--csv out.csv] [--quick] [--cgal PATH [--cgal-max-area-inv N]]

CGAL bounds edge lengths, not areas: its anchor uses the side of the equilateral triangle of the
area bound (so its meshes meet the area bound too, with more triangles).
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from anchor_common import append_row  # noqa: E402


def square_with_hole():
    v = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [.3, .3], [.7, .3], [.7, .7], [.3, .7]], float)
    s = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]], np.int32)
    return v, s, np.array([[.5, .5]])


def coastline(m=5000, seed=3):
    rng = np.random.default_rng(seed)
    t = 2 * np.pi * np.arange(m) / m
    r = 1 + 0.25 * np.sin(7 * t) + 0.1 * np.sin(53 * t + 1) + 0.03 * np.sin(911 * t + 2) \
        + 0.004 * rng.uniform(-1, 1, m)
    v = np.column_stack([r * np.cos(t), r * np.sin(t)])
    s = np.column_stack([np.arange(m), (np.arange(m) + 1) % m]).astype(np.int32)
    return v, s, None


def write_poly(path, v, s, holes):
    """The domain as a Triangle .poly file (indices from 0)."""
    with open(path, "w") as f:
        f.write(f"{len(v)} 2 0 0\n")
        for i, (x, y) in enumerate(v):
            f.write(f"{i} {float(x)!r} {float(y)!r}\n")
        f.write(f"{len(s)} 0\n")
        for j, (a, b) in enumerate(s):
            f.write(f"{j} {a} {b}\n")
        h = [] if holes is None else holes
        f.write(f"{len(h)}\n")
        for k, (x, y) in enumerate(h):
            f.write(f"{k} {float(x)!r} {float(y)!r}\n")


def best_ms(f, repeat):
    out, best = None, float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        best = min(best, (time.perf_counter() - t0) * 1e3)
    return out, best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv")
    ap.add_argument("--quick", action="store_true", help="the smaller sizes only")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cgal", help="path of anchor_cgal_mesh2d (CGAL's mesher), if built")
    ap.add_argument("--cgal-min-area", type=float, default=1e-6,
                    help="smallest area bound CGAL is run for (it is slow below)")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    import gpugeom
    try:
        import triangle
    except ImportError:
        triangle = None
    try:
        import cupy
    except ImportError:
        cupy = None
    info = gpugeom.device_info()
    gpu = info["name"] if info["available"] else "none"
    print(f"machine: GPU {gpu}; gpugeom CUDA build: {gpugeom.built_with_cuda()}")
    backend = "cuda" if info["available"] else "cpu"
    cases = [("square-hole", square_with_hole, 30, area) for area in (1e-4, 1e-5, 1e-6, 1e-7)]
    cases += [("coastline", coastline, angle, area) for angle in (20, 30)
              for area in (1e-4, 1e-5, 1e-6)]
    if a.quick:
        cases = [c for c in cases if c[3] >= 1e-5]
    print(f"{'domain':12s} {'q':>4s} {'a':>7s} {'tool':22s} {'ms':>9s} {'triangles':>10s} "
          f"{'rounds':>6s}")
    for name, make, angle, area in cases:
        v, s, holes = make()
        kw = dict(holes=holes, min_angle=angle, max_area=area, backend=backend)
        m, ms = best_ms(lambda: gpugeom.mesh2d(v, s, **kw), a.repeat)
        c = m.stats["counters"]
        phases = " ".join(f"{k} {v:.1f}" for k, v in m.stats["phase_ms"].items())
        print(f"{name:12s} {angle:4.0f} {area:7.0e} {'gpugeom ' + backend + ' e2e':22s} "
              f"{ms:9.1f} {len(m['triangles']):10d} {c['rounds']:6d}  "
              f"[{phases}; flips {c.get('flips', 0)} in {c.get('flip_passes', 0)} passes]",
              flush=True)
        append_row(a.csv, "mesh2d", f"{name}-q{angle}-a{area:g}", len(m["triangles"]),
                   f"gpugeom-{backend}-e2e", ms, machine=gpu if backend == "cuda" else "cpu")
        if cupy is not None and backend == "cuda":
            dv, ds = cupy.asarray(v), cupy.asarray(s)
            h = np.zeros((0, 2)) if holes is None else holes

            def dev():
                r = gpugeom._core.refine2d_device(dv, ds, h, np.zeros((0, 4)), min_angle=angle,
                                                   max_area=area)
                cupy.cuda.runtime.deviceSynchronize()
                return r
            r, ms = best_ms(dev, a.repeat)
            nt = r["stats"]["counters"]["triangles"]
            print(f"{name:12s} {angle:4.0f} {area:7.0e} {'gpugeom device':22s} {ms:9.1f} "
                  f"{nt:10d}", flush=True)
            append_row(a.csv, "mesh2d", f"{name}-q{angle}-a{area:g}", nt, "gpugeom-device", ms,
                       machine=gpu)
        if triangle is not None:
            d = dict(vertices=v, segments=s)
            if holes is not None:
                d["holes"] = holes
            opts = f"pq{angle}a{area:.10f}Q"
            t, ms = best_ms(lambda: triangle.triangulate(d, opts), 1 if area < 1e-6 else a.repeat)
            print(f"{name:12s} {angle:4.0f} {area:7.0e} {'triangle (1 core)':22s} {ms:9.1f} "
                  f"{len(t['triangles']):10d}", flush=True)
            append_row(a.csv, "mesh2d", f"{name}-q{angle}-a{area:g}", len(t["triangles"]),
                       "triangle", ms)
        if a.cgal and area >= a.cgal_min_area:
            poly = os.path.join(tmp, f"{name}.poly")
            write_poly(poly, v, s, holes)
            rep = "1" if area < 1e-5 else str(a.repeat)
            out = subprocess.run([a.cgal, poly, str(angle), repr(area), rep], check=True,
                                 capture_output=True, text=True).stdout.split()
            ms, nt = float(out[0]), int(out[1])
            print(f"{name:12s} {angle:4.0f} {area:7.0e} {'cgal mesher (1 core)':22s} {ms:9.1f} "
                  f"{nt:10d}", flush=True)
            append_row(a.csv, "mesh2d", f"{name}-q{angle}-a{area:g}", nt, "cgal-mesher", ms)
    return 0


if __name__ == "__main__":
    sys.exit(main())
