#!/usr/bin/env python3
"""Every capability once on small CuPy arrays, compared with the CPU backend: a short run for
compute-sanitizer over the Python package's device paths (used by the GPU sessions)."""
import numpy as np

import cupy as cp
import gpugeom

rng = np.random.default_rng(3)
p2, p3 = rng.random((3000, 2)), rng.random((2000, 3))
for p in (p2, p3):
    a = gpugeom.Delaunay(cp.asarray(p))
    b = gpugeom.Delaunay(p, backend="cpu")
    assert {tuple(sorted(t)) for t in cp.asnumpy(a.simplices).tolist()} == \
        {tuple(sorted(t)) for t in b.simplices.tolist()}
v = gpugeom.Voronoi(cp.asarray(p2))
assert np.array_equal(cp.asnumpy(v.vertices), gpugeom.Voronoi(p2, backend="cpu").vertices)
h = gpugeom.ConvexHull(cp.asarray(p3))
assert np.array_equal(cp.asnumpy(h.vertices), gpugeom.ConvexHull(p3, backend="cpu").vertices)
img = rng.random((97, 61)) > 0.2
img[0, 0] = False
d, i = gpugeom.distance_transform_edt(cp.asarray(img), return_indices=True)
rd, ri = gpugeom.distance_transform_edt(img, return_indices=True, backend="cpu")
assert np.array_equal(cp.asnumpy(d), rd) and np.array_equal(cp.asnumpy(i), ri)
dens = rng.random((40, 50)) + 0.1
c = gpugeom.centroidal_voronoi(cp.asarray(dens), 50, max_iterations=5)
assert np.array_equal(cp.asnumpy(c.sites),
                      gpugeom.centroidal_voronoi(dens, 50, max_iterations=5, backend="cpu").sites)
print("python device smoke: all capabilities equal to the CPU backend")
