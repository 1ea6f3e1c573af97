import sys, time, traceback, numpy as np, dask, gpugeom, gpugeom.dask as gd
sys.path.insert(0, "python/tests")
from test_dask import _relation
for d, n in ((2, 2_000_000), (3, 1_000_000), (2, 2_000_000), (3, 1_000_000)):
    pts = np.random.default_rng(d).random((n, d))
    t = time.perf_counter(); ref = gpugeom.Delaunay(pts); t1 = time.perf_counter() - t
    try:
        with dask.config.set(scheduler="threads"):
            t = time.perf_counter(); dt = gd.delaunay(pts, blocks=4); s, nb = dask.compute(dt.simplices, dt.neighbors); t2 = time.perf_counter() - t
        same = np.array_equal(_relation(s, nb), _relation(ref.simplices, ref.neighbors))
        print(f"{d}D n={n}: single {t1*1e3:.0f} ms, dask(threads, 4 blocks) {t2*1e3:.0f} ms, same {same}", {k: round(v) for k, v in dt.timings.items()}, [(b['rounds'], b['nlocal']) for b in dt.block_stats], flush=True)
    except Exception:
        traceback.print_exc(); sys.stdout.flush()
