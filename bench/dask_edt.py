"""Distributed exact distance transform (gpugeom.dask.distance_transform_edt) on one host's GPUs,
one Dask worker per GPU, against the single-GPU gpugeom.ndimage.distance_transform_edt of the
same volume, in one run.

    python bench/dask_edt.py --gpus 1,2 --n 1024,2048 --zeros 0.01

The volume (n^3 uint8, a fraction --zeros of its voxels zero at random) is made on the workers
in --slabs-per-worker slabs along axis 0 for each worker, and kept there; those are the slabs. Timed:
the distributed call until every slab's float32 distances are in the workers' memory (wall
clock), and the single-GPU call inside one worker on the whole volume (host array in, host array
out; by slices where the volume has 2^32 voxels or more, as the library requires); the bytes
the workers sent each other. --check compares the two results element for element (small n).
First, unless --no-devices, the same volume in the bench's own process: one call, then
distance_transform_edt(devices=[0..w-1]) (several GPUs of the host without Dask).
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from anchor_common import append_row  # noqa: E402
from dask_cluster import cluster, moved  # noqa: E402


def make_slab(seed, first, rows, n, zeros):
    """The slab of `rows` planes from plane `first`: ones, with zeros at random voxels (about
    `zeros` of them), each plane from its own seed, so that the volume is the same whatever its
    slabs."""
    a = np.ones((rows, n, n), np.uint8)
    for z in range(rows):
        rng = np.random.default_rng([seed, first + z])
        a[z].reshape(-1)[rng.integers(0, n * n, int(zeros * n * n) + 1)] = 0
    return a


def make_slab_gpu(seed, first, rows, n, zeros):
    """make_slab's slab on the worker's GPU (a CuPy array)."""
    import cupy
    return cupy.asarray(make_slab(seed, first, rows, n, zeros))


def starts(rows):
    return np.concatenate([[0], np.cumsum(rows)[:-1]]).astype(int).tolist()


def volume(client, n, zeros, chunks, device=False, seed=1):
    """The volume made on the workers, slab i on worker i * workers // chunks: each worker holds
    consecutive slabs, as many as the others (left to itself Dask placed them all on one
    worker once, and the slabs then ran there one after the other)."""
    import dask
    import dask.array as da
    workers = sorted(client.scheduler_info()["workers"])
    rows = [n // chunks + (i < n % chunks) for i in range(chunks)]
    parts = []
    for i, (s, r) in enumerate(zip(starts(rows), rows)):
        f = client.submit(make_slab_gpu if device else make_slab, seed, s, r, n, zeros,
                          pure=False, workers=[workers[i * len(workers) // chunks]])
        meta = __import__("cupy").empty((0, 0, 0), np.uint8) if device else None
        parts.append(da.from_delayed(dask.delayed(f), shape=(r, n, n), dtype=np.uint8,
                                     meta=meta))
    return da.concatenate(parts)


def warm(backend):
    """A worker's device context and its pinned staging buffers made before the clock starts
    (the single run does it for the first worker; the others would pay it in the timed call),
    and gpugeom.dask imported (Dask's array module with it: about a second on the GPU host the
    first time a worker unpickles a slab's task)."""
    import gpugeom.dask  # noqa: F401
    import gpugeom.ndimage as gn
    a = np.ones((64, 64, 64), np.uint8)
    a[0, 0, 0] = 0
    gn.distance_transform_edt(a, float64_distances=False, backend=backend)
    return True


def single(vol, backend, keep):
    import gpugeom
    import gpugeom.ndimage as gn
    n = vol.shape[0]
    slices = list(range(n)) if vol.size >= 2**32 - 1 else None
    t0 = time.perf_counter()
    d = gn.distance_transform_edt(vol, float64_distances=False, slices=slices, backend=backend)
    ms = 1e3 * (time.perf_counter() - t0)
    name = (gpugeom.device_info().get("name") or "cpu")
    return ms, name, (d if keep else None)


def phase_line(vol, devices, backend):
    """The library's phases (ms) of one more such call."""
    from gpugeom import _core
    slices = list(range(vol.shape[0])) if devices is None and vol.size >= 2**32 - 1 else []
    r = _core.distance_transform(vol, zero_sites=True, sampling=[], distance=32, squared=False,
                                 features=False, labels=False, backend=backend, devices=devices,
                                 slices=slices)
    return " ".join(f"{k} {v:.0f}" for k, v in r["stats"]["phase_ms"].items())


def in_process(n, zeros, chunks, gpus, csv, cpu, phases=False):
    """The same volume in this process: one call on one device, then distance_transform_edt's
    devices= over 1, 2, ... of them (no Dask: one host thread and slab per device)."""
    import gpugeom
    import gpugeom.ndimage as gn
    backend = "cpu" if cpu else "cuda"
    rows = [n // chunks + (i < n % chunks) for i in range(chunks)]
    vol = np.concatenate([make_slab(1, s, r, n, zeros) for s, r in zip(starts(rows), rows)])
    name = (gpugeom.device_info().get("name") or "cpu")
    tiny = np.ones((64, 64, 64), np.uint8)
    tiny[0, 0, 0] = 0
    for w in gpus:  # each device's context and staging buffers made before the clock starts
        gn.distance_transform_edt(tiny, devices=list(range(w)), backend=backend)
    slices = list(range(n)) if vol.size >= 2**32 - 1 else None
    t0 = time.perf_counter()
    gn.distance_transform_edt(vol, float64_distances=False, slices=slices, backend=backend)
    one = 1e3 * (time.perf_counter() - t0)
    print(f"EDT {n}^3 in one process, {name}: one call {one:.0f} ms", flush=True)
    if phases:
        print("    phases: " + phase_line(vol, None, backend), flush=True)
    append_row(csv, "devices-edt3d", f"zeros{zeros:g}", n**3, "gpugeom-single", one, machine=name)
    for w in gpus:
        t0 = time.perf_counter()
        gn.distance_transform_edt(vol, float64_distances=False, devices=list(range(w)),
                                  backend=backend)
        ms = 1e3 * (time.perf_counter() - t0)
        print(f"  devices={list(range(w))}: {ms:.0f} ms ({one / ms:.2f}x one call; efficiency "
              f"{one / ms / w:.2f})", flush=True)
        if phases:
            print("    phases: " + phase_line(vol, list(range(w)), backend), flush=True)
        append_row(csv, "devices-edt3d", f"zeros{zeros:g}", n**3, f"gpugeom-devices-{w}", ms,
                   machine=f"{name} x{w}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--gpus", default="1,2")
    p.add_argument("--n", default="1024,2048")
    p.add_argument("--zeros", type=float, default=0.01)
    p.add_argument("--chunks", type=int, default=16,
                   help="slabs the in-process volume is made in (the same volume as Dask's)")
    p.add_argument("--slabs-per-worker", type=int, default=2)
    p.add_argument("--cpu", action="store_true")
    p.add_argument("--check", action="store_true", help="compare with the single run (small n)")
    p.add_argument("--csv", default="")
    p.add_argument("--phases", action="store_true",
                   help="print the library's phases of each in-process configuration")
    p.add_argument("--tasks", action="store_true", help="print the Dask tasks' timeline")
    p.add_argument("--device", action="store_true",
                   help="device-resident: the slabs made on the workers' GPUs (CuPy chunks), the "
                        "results left there; the single run on a CuPy volume (no in-process runs)")
    p.add_argument("--no-devices", action="store_true",
                   help="skip the in-process runs over several devices (devices=)")
    a = p.parse_args()
    import dask
    from distributed import Client, get_task_stream, wait
    import gpugeom.dask as gd
    backend = "cpu" if a.cpu else "cuda"
    problem = "dask-edt3d-device" if a.device else "dask-edt3d"
    for n in [int(float(x)) for x in a.n.split(",")]:
        if not a.no_devices and not a.device:
            in_process(n, a.zeros, a.chunks, [int(x) for x in a.gpus.split(",")], a.csv, a.cpu,
                       a.phases)
        base = None
        for w in [int(x) for x in a.gpus.split(",")]:
            with cluster(w, a.cpu) as cl, Client(cl) as client:
                # the slabs: the volume's chunks, --slabs-per-worker for each worker
                vol = volume(client, n, a.zeros, w * a.slabs_per_worker, a.device).persist()
                wait(vol)
                if base is None:
                    base = dask.delayed(single)(vol, backend, a.check).compute()
                    ref_ms, name, ref = base
                    print(f"EDT {n}^3 ({a.zeros:g} zeros): single {name}: {ref_ms:.0f} ms",
                          flush=True)
                    append_row(a.csv, problem, f"zeros{a.zeros:g}", n**3, "gpugeom-single",
                               ref_ms, machine=name)
                client.run(warm, backend)
                before = moved(client)
                t0, t0_wall = time.perf_counter(), time.time()
                with get_task_stream() as ts:
                    d = gd.distance_transform_edt(vol, float64_distances=False, backend=backend)
                    d = d.persist()
                    wait(d)  # every slab's distances in the workers' memory
                ms = 1e3 * (time.perf_counter() - t0)
                if a.tasks:  # where each task ran and when (ms from the call), by key prefix
                    for t in sorted(ts.data, key=lambda t: t["startstops"][0]["start"]):
                        for ss in t["startstops"]:
                            print(f"    {str(t['key'])[:40]:40s} {t['worker'][-5:]} {ss['action']:9s}"
                                  f" {1e3 * (ss['start'] - t0_wall):8.0f} "
                                  f"{1e3 * (ss['stop'] - t0_wall):8.0f}")
                sent = moved(client) - before
                ok = ""
                if a.check:
                    ok = ", same as the single run" if np.array_equal(d.compute(), ref) \
                        else ", DIFFERENT from the single run"
                print(f"  {w} workers, {len(d.chunks[0])} slabs: {ms:.0f} ms ({ref_ms / ms:.2f}x "
                      f"the single run; efficiency {ref_ms / ms / w:.2f}), "
                      f"{sent / 2**20:.0f} MiB between workers{ok}", flush=True)
                append_row(a.csv, problem, f"zeros{a.zeros:g}", n**3, f"gpugeom-dask-{w}",
                           ms, machine=f"{name} x{w}")
                del d


if __name__ == "__main__":
    main()
