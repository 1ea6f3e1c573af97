#!/usr/bin/env python3
"""SciPy's distance_transform_edt as the oracle for `gpugeom edt`: distances (isotropic and
anisotropic, 2D, 3D, 4D and 5D) must match, and every reported index must be a site at the reported
distance (ties may pick a different site: gpugeom takes the first in raster order)."""
import os, subprocess, sys, tempfile

def main(gpugeom):
    try:
        import numpy as np
        import scipy.ndimage as ndi
    except ImportError as e:
        print(f"SKIP: SciPy not installed ({e})")
        return 0
    rng = np.random.default_rng(7)
    cases = [((1, 97), None, 0.3), ((83, 1), None, 0.3), ((301, 211), None, 0.05), ((256, 256), None, 0.5),
             ((200, 150), (1.5, 0.7), 0.02), ((40, 50, 60), None, 0.01), ((30, 20, 25), (2.0, 1.0, 0.5), 0.1),
             ((64, 64), None, 0.9), ((7, 9, 8, 10), None, 0.05), ((6, 5, 7, 4), (2.0, 1.0, 0.5, 1.5), 0.1),
             ((4, 3, 5, 4, 3), None, 0.05)]
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for shape, samp, zeros in cases:
            a = (rng.random(shape) >= zeros).astype(np.uint8)
            a.flat[rng.integers(a.size)] = 0
            f = lambda n: os.path.join(tmp, n)
            np.save(f("in.npy"), a)
            cmd = [gpugeom, "--quiet", "--backend", os.environ.get("GPUGEOM_BACKEND", "cpu"), "edt", f("in.npy"),
                   "-o", f("d.npy"), "--sites", "zero", "--float64", "--indices", f("i.npy")]
            if samp:
                cmd += ["--sampling", ",".join(map(str, samp))]
            subprocess.run(cmd, check=True)
            d, ind = np.load(f("d.npy")), np.load(f("i.npy"))
            ref = ndi.distance_transform_edt(a, sampling=samp)
            s = np.array(samp or [1.0] * a.ndim).reshape((-1,) + (1,) * a.ndim)
            at = np.sqrt((((ind - np.indices(shape)) * s) ** 2).sum(0))
            ok = (np.allclose(d, ref, rtol=1e-14, atol=0) and np.allclose(at, ref, rtol=1e-14, atol=0)
                  and (a[tuple(ind)] == 0).all())
            print(f"{'ok  ' if ok else 'FAIL'} shape {shape} sampling {samp} zeros {zeros}: "
                  f"max |d - scipy| {np.abs(d - ref).max():.3g}")
            bad += not ok
    print(f"{len(cases) - bad} passed, {bad} failed")
    return 1 if bad else 0

if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
