#!/usr/bin/env python3
"""Voronoi cells (issue 49) as a particle code calls them, in one run: gpugeom.VoronoiCells end to
end (NumPy points in, host arrays out) and device-resident (CuPy in and out, timed with a
synchronise), on uniform points in a box (bounded and periodic) and a clustered,
cosmology-like set (periodic). Anchors, where installed: freud.locality.Voronoi (periodic, all
host cores); SciPy's Voronoi diagram of the points (the diagram only: a SciPy user would still
have to cut and measure the cells, so its ratio is a lower bound), up to --scipy-max points.

  python3 bench/voronoi_cells.py [--sizes 1e5,1e6,1e7] [--reps 3] [--scipy-max 1e5]

Prints the GPU's name and a line per case (median of --reps after a warm-up), with the phases of
the last device-resident run.
"""
import argparse
import multiprocessing
import os
import time

import numpy as np

import gpugeom
from anchor_common import med


def clustered(rng, n):
    """Half the points in Gaussian clusters whose widths and weights follow power laws (as
    haloes), half uniform, all taken into the unit box."""
    k = max(n // 2000, 1)
    centres = rng.random((k, 3))
    widths = 0.002 * (1 + rng.pareto(1.5, k))
    weights = rng.pareto(1.2, k) + 1
    m = n // 2
    which = rng.choice(k, size=m, p=weights / weights.sum())
    p = np.concatenate([centres[which] + rng.normal(size=(m, 3)) * widths[which, None],
                        rng.random((n - m, 3))])
    return p - np.floor(p)


def freud_run(p, vols, reps, out):
    """In a child process, as Voro++ (under freud) exits the process on points closer than its
    tolerance: freud's median time and its largest relative volume difference to ours."""
    import freud

    box = freud.box.Box.cube(1)
    fv = freud.locality.Voronoi()
    q = p - 0.5
    if len(p) <= 1e6:
        fv.compute((box, q))  # (warm-up: freud's first call starts its threads)
    fr = med(lambda: fv.compute((box, q)), reps)
    out.put((fr, float(np.max(np.abs(np.asarray(fv.volumes) - vols) / np.asarray(fv.volumes)))))


def freud_line(p, vols, reps, e2e_np, dev_np):
    ctx = multiprocessing.get_context("fork")  # (the child touches no GPU)
    out = ctx.Queue()
    child = ctx.Process(target=freud_run, args=(p, vols, reps, out))
    child.start()
    child.join()
    if child.exitcode != 0:
        return f"freud failed (exit code {child.exitcode}: Voro++ refused the points)"
    fr, err = out.get()
    return (f"freud {fr:.0f} ms ({fr / e2e_np:.1f}x end to end, {fr / dev_np:.1f}x device, "
            f"without polygons as freud; volumes agree to {err:.1e})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="1e5,1e6,1e7")
    ap.add_argument("--cases", default="uniform-bounded,uniform-periodic,clustered-periodic")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--scipy-max", type=float, default=1e5)
    a = ap.parse_args()
    import cupy as cp

    try:
        import freud
    except ImportError:
        freud = None
    info = gpugeom.device_info()
    print(f"GPU: {info.get('name')}; host cores: {os.cpu_count()}; freud: "
          f"{freud.__version__ if freud else 'not installed'}")
    rng = np.random.default_rng(1)

    sync = cp.cuda.runtime.deviceSynchronize

    for n in (int(float(s)) for s in a.sizes.split(",")):
        reps = a.reps if n <= 1e6 else 1
        for name in a.cases.split(","):
            case, periodic = name.split("-")[0], name.endswith("periodic")
            p = rng.random((n, 3)) if case == "uniform" else clustered(rng, n)
            d = cp.asarray(p)
            run = dict(box=[0, 1], periodic=periodic, backend="cuda")
            c = gpugeom.VoronoiCells(d, **run)  # (warm-up)
            e2e = med(lambda: gpugeom.VoronoiCells(p, **run), reps, sync)
            dev = med(lambda: gpugeom.VoronoiCells(d, **run), reps, sync)
            nop = dict(run, polygons=False)
            e2e_np = med(lambda: gpugeom.VoronoiCells(p, **nop), reps, sync)
            dev_np = med(lambda: gpugeom.VoronoiCells(d, **nop), reps, sync)
            c = gpugeom.VoronoiCells(d, **run)
            vsum = float(c.volumes.sum())
            st = c.stats
            ph = ", ".join(f"{k} {v:.0f}" for k, v in st.get("phase_ms", {}).items())
            cnt = st.get("counters", {})
            line = (f"cells {case} {'periodic' if periodic else 'bounded'} {n}: gpugeom end to "
                    f"end {e2e:.1f} ms, device-resident {dev:.1f} ms; without polygons "
                    f"{e2e_np:.1f} / {dev_np:.1f} ms (volume sum {vsum:.12f}; "
                    f"images {cnt.get('images')}, attempts {cnt.get('attempts')}; {ph})")
            if freud and periodic:
                line += "; " + freud_line(p, cp.asnumpy(c.volumes), reps, e2e_np, dev_np)
            if n <= a.scipy_max and case == "uniform" and not periodic:
                import scipy.spatial as ss

                t0 = time.perf_counter()
                ss.Voronoi(p)
                sc = (time.perf_counter() - t0) * 1e3
                line += f"; SciPy's diagram alone {sc:.0f} ms ({sc / e2e:.0f}x end to end)"
            print(line, flush=True)
            del c, d


if __name__ == "__main__":
    main()
