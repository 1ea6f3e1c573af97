"""Distributed Delaunay (gpugeom.dask.delaunay) on one host's GPUs, one Dask worker per GPU,
against the single-GPU gpugeom.Delaunay of the same points, in one run.

    python bench/dask_delaunay.py --gpus 1,2,4 --dims 3 --n 1e7 --dist uniform,clustered

Each worker is a process that sees one GPU (CUDA_VISIBLE_DEVICES; what dask-cuda's
LocalCUDACluster does, without needing it). The points are made on the workers, chunk by chunk,
so the client never holds them. Timed: the whole distributed call until the simplices and their
neighbours are in the workers' memory (wall clock), the single-GPU call inside one worker on all
points (from host arrays, as the blocks are; with --cpu, the single call in the client process
on all cores), the bytes the workers sent each other, the rounds
and the local points per own point. --cpu runs CPU workers instead (--gpus: worker counts).

Past what one call holds (3D: 1.4·10^8 points; --single-max skips the single call above it),
--verify judges the result without it: the tetrahedra's (triangles') volumes sum to the convex
hull's, and the faces without a neighbour are as many as the hull's facets (points in general
position), so the simplices cover the hull once; every face between blocks was matched by the
call itself (a face matched other than twice raises).

    python bench/dask_delaunay.py --gpus 1 --blocks-per-worker 4 --n 2e8 --dist uniform \
        --single-max 1e8 --verify
"""
import argparse
import os
import re
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from anchor_common import append_row  # noqa: E402
from dask_cluster import cluster, moved, usable_cores  # noqa: E402


def make_chunk(seed, i, m, d, dist):
    rng = np.random.default_rng([seed, i])
    if dist == "uniform":
        return rng.random((m, d))
    if dist == "clustered":  # 64 gaussian clusters, the same centres in every chunk
        centres = np.random.default_rng(seed).random((64, d))
        return centres[rng.integers(0, 64, m)] + 0.01 * rng.normal(size=(m, d))
    if dist == "sphere":  # on the unit circle or sphere: one block takes them all
        v = rng.normal(size=(m, d))
        return v / np.linalg.norm(v, axis=1)[:, None]
    raise ValueError(dist)


def points(n, d, dist, chunks, seed=1):
    import dask
    import dask.array as da
    m = [n // chunks + (i < n % chunks) for i in range(chunks)]
    parts = [da.from_delayed(dask.delayed(make_chunk)(seed, i, mi, d, dist), shape=(mi, d),
                             dtype=np.float64) for i, mi in enumerate(m)]
    return da.concatenate(parts)


def single(pts, backend):
    import gpugeom
    t0 = time.perf_counter()
    tri = gpugeom.Delaunay(pts, backend=backend)
    ms = 1e3 * (time.perf_counter() - t0)
    if backend == "cpu":
        return ms, tri.nsimplex, f"cpu ({usable_cores()} cores)"
    return ms, tri.nsimplex, gpugeom.device_info().get("name", "cpu")


def _block_measure(r, d):
    """The sum of a block's owned simplices' volumes (areas), on the worker's GPU (CuPy) where
    it has one, in parts of 10^7 simplices."""
    try:
        import cupy as xp
        xp.cuda.runtime.getDeviceCount()
    except Exception:  # (no CuPy or no GPU: NumPy)
        xp = np
    s, ids, at = r["simplices"], r["vertices"], r["vertex_points"]
    order = np.argsort(ids, kind="stable")
    sorted_ids, pts = xp.asarray(ids[order]), xp.asarray(at[order])
    total = 0.0
    step = 10**7
    for a in range(0, len(s), step):
        v = xp.searchsorted(sorted_ids, xp.asarray(s[a:a + step]))
        p = pts[v]  # (k, d + 1, d)
        e = p[:, 1:, :] - p[:, :1, :]
        total += float(xp.abs(xp.linalg.det(e)).sum()) / (2.0 if d == 2 else 6.0)
    return total


def _hull_measure(pts):
    """The convex hull's volume (area) and facet count (gpugeom.ConvexHull on the worker)."""
    import gpugeom
    h = gpugeom.ConvexHull(np.ascontiguousarray(pts))
    return float(h.volume), int(len(h.simplices))


def verify(dt, pts, d):
    """(volumes' sum, hull's volume, faces without a neighbour, hull facets)."""
    import dask
    import dask.array as da
    vols = dask.compute(*[dask.delayed(_block_measure)(r, d) for r in dt._results])
    hull_vol, facets = dask.delayed(_hull_measure)(pts).compute()
    open_faces = int(da.count_nonzero(dt.neighbors == -1).compute())
    return float(np.sum(vols)), hull_vol, open_faces, facets


def print_tasks(records):
    """Per kind of task (its function's name), how many ran and their compute and transfer
    time summed over the workers, and when the last ended (ms from the first start)."""
    kinds = {}
    first = min(ss["start"] for r in records for ss in r["startstops"])
    for r in records:
        key = r["key"][0] if isinstance(r["key"], tuple) else r["key"]
        name = "triangulate_block" if key.startswith("gpugeom-delaunay-block") else \
            re.sub(r"(-[0-9a-f]{4,})+$", "", key)
        for ss in r["startstops"]:
            k = kinds.setdefault((name, ss["action"]), [0, 0.0, 0.0])
            k[0] += 1
            k[1] += ss["stop"] - ss["start"]
            k[2] = max(k[2], ss["stop"] - first)
    for (name, action), (count, total, last) in sorted(kinds.items(), key=lambda kv: -kv[1][1]):
        if total > 1e-3:
            print(f"    {name[:36]:36s} {action:9s} {count:5d} tasks {1e3 * total:9.1f} ms, "
                  f"last ends at {1e3 * last:8.1f} ms")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--gpus", default="1,2,4")
    p.add_argument("--dims", default="3")
    p.add_argument("--n", default="1e7")
    p.add_argument("--dist", default="uniform,clustered")
    p.add_argument("--blocks-per-worker", type=int, default=2)
    p.add_argument("--chunks", type=int, default=16,
                   help="chunks the points are made in (the same points for every worker count)")
    p.add_argument("--cpu", action="store_true")
    p.add_argument("--check", action="store_true", help="compare with the single run")
    p.add_argument("--single-max", type=float, default=float("inf"),
                   help="no single call above this many points (past what one call holds)")
    p.add_argument("--verify", action="store_true",
                   help="volumes and hull faces against the convex hull's (no single call)")
    p.add_argument("--csv", default="")
    p.add_argument("--tasks", action="store_true",
                   help="per kind of task: its count, compute and transfer time (Dask's task "
                        "stream), to see where a distributed call spends its time")
    a = p.parse_args()
    import dask
    from contextlib import nullcontext
    from distributed import Client, get_task_stream, wait
    import gpugeom.dask as gd
    backend = "cpu" if a.cpu else "cuda"
    for d in [int(x) for x in a.dims.split(",")]:
        for n in [int(float(x)) for x in a.n.split(",")]:
            for dist in a.dist.split(","):
                base = None
                for w in [int(x) for x in a.gpus.split(",")]:
                    with cluster(w, a.cpu) as cl, Client(cl) as client:
                        pts = points(n, d, dist, chunks=a.chunks)
                        # the workers import gpugeom before the clock starts, as a long-lived
                        # cluster has
                        client.run(lambda: __import__("gpugeom.dask"))
                        if base is None and n > a.single_max:
                            base = (float("nan"), -1, "none (past --single-max)")
                            ref_ms, ref_m, name = base
                            print(f"{d}D {dist} n={n}: no single call", flush=True)
                        if base is None:
                            # a GPU: on one worker's GPU; the CPU: in this process on all of
                            # the host's cores, as a user without Dask runs it
                            base = single(pts.compute(), backend) if a.cpu else \
                                dask.delayed(single)(pts, backend).compute()
                            ref_ms, ref_m, name = base
                            print(f"{d}D {dist} n={n}: single {name}: {ref_ms:.0f} ms, "
                                  f"{ref_m} simplices", flush=True)
                            append_row(a.csv, f"dask-delaunay{d}d", dist, n, "gpugeom-single",
                                       ref_ms, machine=name)
                        pts = pts.persist()  # the caller's points, in the workers' memory
                        wait(pts)
                        before = moved(client)
                        with get_task_stream() if a.tasks else nullcontext() as stream:
                            t0 = time.perf_counter()
                            dt = gd.delaunay(pts, blocks=w * a.blocks_per_worker,
                                             backend=backend)
                            s, nb = dask.persist(dt.simplices, dt.neighbors)
                            wait([s, nb])  # every block's arrays in the workers' memory
                            ms = 1e3 * (time.perf_counter() - t0)
                        sent = moved(client) - before
                        local = sum(st["nlocal"] for st in dt.block_stats) / n
                        rounds = max(st["rounds"] for st in dt.block_stats)
                        # (which blocks took a second round, and how many simplices each tested)
                        per_block = " ".join(f"{st['rounds']}/{st.get('tested', 0)}"
                                             for st in dt.block_stats)
                        ok = ""
                        if a.verify:
                            t1 = time.perf_counter()
                            vol, hull_vol, open_faces, facets = verify(dt, pts, d)
                            ok += (f", volumes {vol:.12g} against the hull's {hull_vol:.12g} "
                                   f"(relative {abs(vol - hull_vol) / hull_vol:.1e}), "
                                   f"{open_faces} faces on the hull against {facets} facets "
                                   f"({1e3 * (time.perf_counter() - t1):.0f} ms to verify)")
                        if a.check and ref_m >= 0:
                            ok += f", {'same' if dt.nsimplex == ref_m else 'DIFFERENT'} count"
                        ratio = (f"{ref_ms / ms:.2f}x the single run; efficiency "
                                 f"{ref_ms / ms / w:.2f}" if ref_m >= 0 else "no single run")
                        print(f"  {w} workers, {len(dt.block_stats)} blocks: {ms:.0f} ms "
                              f"({ratio}), {sent / 2**20:.0f} MiB between workers, "
                              f"{rounds} rounds (per block, rounds/tested: {per_block}), "
                              f"{local:.2f} local points per point, "
                              f"{dt.nsimplex} simplices{ok}; phases "
                              + " ".join(f"{k} {v:.0f}" for k, v in dt.timings.items()),
                              flush=True)
                        append_row(a.csv, f"dask-delaunay{d}d", dist, n,
                                   f"gpugeom-dask-{w}", ms, machine=f"{name} x{w}")
                        for st in dt.block_stats:
                            if st.get("why"):
                                print(f"    block {st['block']}: {st['why']}", flush=True)
                        if a.tasks:
                            print_tasks(stream.data)


if __name__ == "__main__":
    main()
