#!/usr/bin/env python3
"""The exact distance transform of grids of 4 and more axes (issue 54) as SciPy and CuPy users
call it, in one run: gpugeom.distance_transform_edt end to end (NumPy in, NumPy out) and
device-resident (CuPy in and out, timed with a synchronise), beside
cupyx.scipy.ndimage.distance_transform_edt (on its own CuPy arrays, and from NumPy) and
scipy.ndimage.distance_transform_edt (once, up to --scipy-max elements). Zeros are the sites
(SciPy's convention), a fraction --density of the elements.

  python3 bench/edt_nd.py [--shapes 128x128x128x128,48x48x48x48x48] [--density 0.01]
                          [--reps 3] [--indices]

Prints the GPU's name and a line per shape and tool (median of --reps after a warm-up), and
whether each result equals gpugeom's (distances; ties aside for indices).
"""
import argparse
import time

import numpy as np

import gpugeom
from anchor_common import med


def timed(fn):
    t0 = time.perf_counter()
    r = fn()
    return r, (time.perf_counter() - t0) * 1e3


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shapes", default="128x128x128x128,48x48x48x48x48")
    ap.add_argument("--density", type=float, default=0.01)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--indices", action="store_true", help="also return_indices=True")
    ap.add_argument("--scipy-max", type=float, default=3e8)
    a = ap.parse_args()
    import cupy as cp
    import cupyx.scipy.ndimage as cndi
    import scipy.ndimage as ndi

    sync = cp.cuda.runtime.deviceSynchronize
    print(f"GPU: {gpugeom.device_info().get('name')}; CuPy {cp.__version__}")
    rng = np.random.default_rng(5)
    for text in a.shapes.split(","):
        shape = tuple(int(e) for e in text.split("x"))
        n = int(np.prod(shape))
        img = rng.random(shape, dtype=np.float32) >= a.density
        img.flat[0] = False
        d_img = cp.asarray(img)
        for ind in ([False, True] if a.indices else [False]):
            kw = dict(return_indices=ind)
            tag = f"{text} ({n / 1e6:.0f}M elements{', indices' if ind else ''})"
            ours = gpugeom.distance_transform_edt(d_img, backend="cuda", **kw)  # warm-up
            dev = med(lambda: gpugeom.distance_transform_edt(d_img, backend="cuda", **kw),
                      a.reps, sync)
            e2e = med(lambda: gpugeom.distance_transform_edt(img, backend="cuda", **kw),
                      a.reps, sync)
            ref = cp.asnumpy(ours[0] if ind else ours)
            del ours
            print(f"edt {tag}: gpugeom device-resident {dev:.1f} ms, end to end {e2e:.1f} ms",
                  flush=True)
            try:
                c = cndi.distance_transform_edt(d_img, **kw)  # warm-up (and the check)
                same = np.array_equal(cp.asnumpy(c[0] if ind else c), ref)
                del c
                cdev = med(lambda: cndi.distance_transform_edt(d_img, **kw), a.reps, sync)
                def cupy_from_numpy():
                    r = cndi.distance_transform_edt(cp.asarray(img), **kw)
                    return [cp.asnumpy(x) for x in r] if ind else cp.asnumpy(r)

                ce2e = med(cupy_from_numpy, a.reps, sync)
                print(f"edt {tag}: CuPy device-resident {cdev:.1f} ms ({cdev / dev:.1f}x ours), "
                      f"from NumPy {ce2e:.1f} ms ({ce2e / e2e:.1f}x ours); equal distances: "
                      f"{same}", flush=True)
            except Exception as e:  # CuPy's transform takes 2D and 3D only
                print(f"edt {tag}: CuPy refused: {type(e).__name__}: {str(e)[:100]}", flush=True)
            if n <= a.scipy_max and not ind:  # (once a shape: SciPy takes a minute at 128^4)
                s, sms = timed(lambda: ndi.distance_transform_edt(img, **kw))
                same = np.array_equal(s[0] if ind else s, ref)
                print(f"edt {tag}: SciPy {sms:.0f} ms ({sms / e2e:.1f}x ours end to end); "
                      f"equal distances: {same}", flush=True)
                del s
        del d_img
        cp.get_default_memory_pool().free_all_blocks()


if __name__ == "__main__":
    main()
