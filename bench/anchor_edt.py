#!/usr/bin/env python3
"""Distance-transform anchors on random site grids: CuPy's cupyx.scipy.ndimage
distance_transform_edt on the GPU (float32 distances, device-resident, CUDA-event timing, and
host array in / host array out as a NumPy caller sees it: cupy_host),
SciPy and OpenCV (DIST_L2, precise mask) on the CPU, and the `edt` package where installed.
Appends CSV rows in the bench format; prints a line per measurement."""
import argparse, statistics, sys, time

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--sides", default="1024")
    ap.add_argument("--density", default="0.1")
    ap.add_argument("--tools", default="cupy,cupy_host,scipy,opencv,edt")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--csv")
    a = ap.parse_args()
    import numpy as np
    rng = np.random.default_rng(12345)
    rows = []
    for side in map(int, a.sides.split(",")):
        for dens in map(float, a.density.split(",")):
            shape = (side,) * a.dim
            img = (rng.random(shape, dtype=np.float32) >= dens).astype(np.uint8)  # zeros are the sites
            n = img.size
            for tool in a.tools.split(","):
                t = None
                try:
                    if tool == "cupy":
                        import cupy as cp
                        from cupyx.scipy import ndimage as cnd
                        g = cp.asarray(img)
                        def run():
                            try:
                                return cnd.distance_transform_edt(g, float64_distances=False)
                            except TypeError:
                                return cnd.distance_transform_edt(g)
                        run(); cp.cuda.Device().synchronize()
                        ts = []
                        for _ in range(a.reps):
                            s, e = cp.cuda.Event(), cp.cuda.Event()
                            s.record(); run(); e.record(); e.synchronize()
                            ts.append(cp.cuda.get_elapsed_time(s, e))
                        t = statistics.median(ts); dev = cp.cuda.runtime.getDeviceProperties(0)["name"].decode()
                    elif tool == "cupy_host":  # as a NumPy user calls it: host array in, host array out
                        import cupy as cp
                        from cupyx.scipy import ndimage as cnd
                        def run():
                            g = cp.asarray(img)
                            try:
                                d = cnd.distance_transform_edt(g, float64_distances=False)
                            except TypeError:
                                d = cnd.distance_transform_edt(g)
                            return cp.asnumpy(d)
                        run()
                        ts = []
                        for _ in range(a.reps):
                            t0 = time.perf_counter(); run(); ts.append(1e3 * (time.perf_counter() - t0))
                        t = statistics.median(ts); dev = cp.cuda.runtime.getDeviceProperties(0)["name"].decode()
                    elif tool == "scipy":
                        if n > 4096 * 4096 or (a.dim == 3 and side > 256): continue
                        from scipy import ndimage
                        t0 = time.perf_counter(); ndimage.distance_transform_edt(img); t = 1e3 * (time.perf_counter() - t0)
                        dev = "cpu-1core"
                    elif tool == "opencv":
                        if a.dim != 2: continue
                        import cv2
                        cv2.setNumThreads(1)
                        cv2.distanceTransform(img, cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
                        t0 = time.perf_counter(); cv2.distanceTransform(img, cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
                        t = 1e3 * (time.perf_counter() - t0); dev = "cpu-1core"
                    elif tool == "edt":
                        import edt as edtpkg
                        t0 = time.perf_counter(); edtpkg.edt(img, parallel=1); t = 1e3 * (time.perf_counter() - t0)
                        dev = "cpu-1core"
                except ImportError as ex:
                    print(f"note: {tool} anchor skipped ({ex})")
                    continue
                if t is None: continue
                print(f"anchor {tool:7s} {side}^{a.dim} density {dens}: {t:10.3f} ms")
                rows.append(f"edt{a.dim}d,density{dens},{n},{tool},{dev},0,{t},0,{t},{t},0\n")
    if a.csv:
        with open(a.csv, "a") as f:
            f.writelines(rows)
    return 0

if __name__ == "__main__":
    sys.exit(main())
