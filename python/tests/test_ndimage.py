"""distance_transform_edt against scipy.ndimage (exact: equal values and indices, ties aside),
voronoi_labels against a brute-force nearest site."""
import numpy as np
import pytest
import scipy.ndimage as ndi

import gpugeom


def tie_free_indices_equal(mine, ref, dist, shape, sampling=None):
    """SciPy may break ties differently: where the indices differ, both must be at the same
    distance."""
    if np.array_equal(mine, ref):
        return True
    s = np.ones(len(shape)) if sampling is None else np.asarray(sampling, float)
    grid = np.indices(shape)
    dm = np.sqrt(sum(((mine[k] - grid[k]) * s[k]) ** 2 for k in range(len(shape))))
    dr = np.sqrt(sum(((ref[k] - grid[k]) * s[k]) ** 2 for k in range(len(shape))))
    return np.allclose(dm, dr, rtol=1e-12, atol=0)


@pytest.mark.parametrize("shape", [(1,), (37,), (64, 48), (17, 23, 29), (9, 8, 7, 6),
                                   (11, 1, 12, 10), (5, 6, 4, 5, 3), (3, 2, 3, 2, 3, 2, 2, 3)])
@pytest.mark.parametrize("sampling", [None, "aniso"])
def test_edt_equals_scipy(shape, sampling, backend, rng):
    a = rng.random(shape) > (0.1 if len(shape) < 4 else 0.02)
    a.flat[0] = False
    samp = None if sampling is None else [0.5 + 0.7 * k for k in range(len(shape))]
    d, i = gpugeom.distance_transform_edt(a, sampling=samp, return_indices=True, backend=backend)
    rd, ri = ndi.distance_transform_edt(a, sampling=samp, return_indices=True)
    assert d.dtype == np.float64 and d.shape == a.shape
    assert i.dtype == np.int32 and i.shape == (len(shape),) + a.shape
    np.testing.assert_allclose(d, rd, rtol=1e-13, atol=0)
    assert tie_free_indices_equal(i, ri, d, shape, samp)


@pytest.mark.parametrize("dtype", [np.uint8, np.int16, np.float32, np.float64, np.int64])
def test_edt_dtypes(dtype, backend, rng):
    a = (rng.random((40, 30)) > 0.2).astype(dtype) * 3
    np.testing.assert_allclose(gpugeom.distance_transform_edt(a, backend=backend),
                               ndi.distance_transform_edt(a), rtol=1e-13)


def test_edt_output_arrays(backend, rng):
    a = rng.random((50, 40)) > 0.05
    a[0, 0] = False
    dist = np.empty(a.shape)
    ind = np.empty((2,) + a.shape, dtype=np.int32)
    r = gpugeom.distance_transform_edt(a, return_indices=True, distances=dist, indices=ind,
                                       backend=backend)
    assert r is None
    np.testing.assert_allclose(dist, ndi.distance_transform_edt(a), rtol=1e-13)
    only_d = gpugeom.distance_transform_edt(a, return_indices=True, distances=dist,
                                            backend=backend)
    assert only_d.shape == (2,) + a.shape  # the indices, as SciPy returns them
    # output arrays that are views with strides get the result too
    big = np.zeros((2, 50, 80))
    bigi = np.zeros((2, 2, 50, 40), dtype=np.int32)
    gpugeom.distance_transform_edt(a, return_indices=True, distances=big[1, :, ::2],
                                   indices=bigi[:, 1], backend=backend)
    np.testing.assert_array_equal(big[1, :, ::2], dist)
    np.testing.assert_array_equal(bigi[:, 1], ind)
    assert not big[0].any() and not big[1, :, 1::2].any()
    f32 = np.empty(a.shape, dtype=np.float32)
    gpugeom.distance_transform_edt(a, distances=f32, backend=backend)
    np.testing.assert_allclose(f32, dist, rtol=1e-6)
    with pytest.raises(RuntimeError, match="int32"):  # SciPy's exception type for this
        gpugeom.distance_transform_edt(a, return_indices=True,
                                       indices=np.empty((2,) + a.shape, dtype=np.int64),
                                       backend=backend)


@pytest.mark.parametrize("sampling", [None, (2.0, 1.0, 0.5)])
def test_edt_slices_equal_whole_volume(sampling, backend, rng):
    a = rng.random((23, 31, 19)) > 0.03
    a[0, 0, 0] = False
    zs = [22, 0, 11, 11, -1]
    d, i = gpugeom.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                          backend=backend)
    ds, is_ = gpugeom.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                             slices=zs, backend=backend)
    assert ds.shape == (5, 31, 19) and is_.shape == (3, 5, 31, 19)
    np.testing.assert_array_equal(ds, d[zs])
    np.testing.assert_array_equal(is_, i[:, zs])
    dist = np.empty((2, 31, 19), dtype=np.float32)
    assert gpugeom.distance_transform_edt(a, sampling=sampling, distances=dist, slices=[3, 4],
                                          backend=backend) is None
    np.testing.assert_array_equal(dist, d[3:5].astype(np.float32))
    with pytest.raises(ValueError, match="3 or more dimensions"):
        gpugeom.distance_transform_edt(a[0], slices=[0], backend=backend)
    with pytest.raises(IndexError, match="out of bounds"):
        gpugeom.distance_transform_edt(a, slices=[23], backend=backend)
    with pytest.raises(RuntimeError, match="needs"):
        gpugeom.distance_transform_edt(a, distances=np.empty(a.shape), slices=[1],
                                       backend=backend)


@pytest.mark.parametrize("shape", [(60,), (40, 33), (23, 31, 19), (7, 6, 9, 8)])
def test_edt_several_devices_equal_one(shape, backend, rng):
    """devices=: one slab per device (on the CPU backend, per entry), the same arrays, into the
    caller's arrays too."""
    a = rng.random(shape) > 0.03
    a.flat[-1] = False
    sampling = [1.0 + 0.5 * j for j in range(len(shape))]
    d, i = gpugeom.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                          backend=backend)
    for devices in ([0, 0, 0], [0], "all"):
        d2, i2 = gpugeom.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                                devices=devices, backend=backend)
        np.testing.assert_array_equal(d2, d)
        np.testing.assert_array_equal(i2, i)
    dist, ind = np.empty(shape, np.float32), np.empty((len(shape),) + shape, np.int32)
    assert gpugeom.distance_transform_edt(a, sampling=sampling, return_indices=True,
                                          distances=dist, indices=ind, devices=[0, 0],
                                          backend=backend) is None
    np.testing.assert_array_equal(dist, d.astype(np.float32))
    np.testing.assert_array_equal(ind, i)
    with pytest.raises(ValueError, match="slices"):
        gpugeom.distance_transform_edt(a, devices=[0, 0], slices=[0], backend=backend)
    with pytest.raises(ValueError, match="ordinals"):
        gpugeom.distance_transform_edt(a, devices="first", backend=backend)


def test_edt_only_indices_and_float32(backend, rng):
    a = rng.random((33, 21)) > 0.3
    a[5, 5] = False
    i = gpugeom.distance_transform_edt(a, return_distances=False, return_indices=True,
                                       backend=backend)
    assert i.shape == (2, 33, 21)
    d32 = gpugeom.distance_transform_edt(a, float64_distances=False, backend=backend)
    assert d32.dtype == np.float32


def test_voronoi_labels(backend, rng):
    lab = np.zeros((40, 50), dtype=np.int32)
    pts = rng.integers(0, [40, 50], size=(30, 2))
    lab[pts[:, 0], pts[:, 1]] = np.arange(1, 31)
    out, dist, site = gpugeom.voronoi_labels(lab, return_distances=True, return_sites=True,
                                             backend=backend)
    assert out.dtype == lab.dtype and out.shape == lab.shape
    nz = np.flatnonzero(lab)
    coords = np.column_stack(np.unravel_index(nz, lab.shape))
    grid = np.indices(lab.shape).reshape(2, -1).T
    d2 = ((grid[:, None, :] - coords[None, :, :]) ** 2).sum(-1)
    best = d2.argmin(axis=1)  # the first of equally near sites in C order, as gpugeom's rule
    np.testing.assert_array_equal(site.reshape(-1), nz[best])
    np.testing.assert_array_equal(out.reshape(-1), lab.reshape(-1)[nz[best]])
    np.testing.assert_allclose(dist.reshape(-1), np.sqrt(d2.min(axis=1)))


@pytest.mark.parametrize("shape", [(6, 7, 5, 8), (4, 3, 5, 4, 3)])
def test_edt_nd_output_arrays_and_sites(shape, backend, rng):
    """N-D grids: the caller's arrays, float32, a single site, all sites."""
    a = rng.random(shape) > 0.05
    a.flat[3] = False
    d = np.empty(shape)
    i = np.empty((len(shape),) + shape, dtype=np.int32)
    assert gpugeom.distance_transform_edt(a, return_indices=True, distances=d, indices=i,
                                          backend=backend) is None
    rd, ri = ndi.distance_transform_edt(a, return_indices=True)
    np.testing.assert_allclose(d, rd, rtol=1e-13, atol=0)
    assert tie_free_indices_equal(i, ri, d, shape)
    d32 = gpugeom.distance_transform_edt(a, float64_distances=False, backend=backend)
    assert d32.dtype == np.float32 and d32.shape == shape
    np.testing.assert_allclose(d32, rd, rtol=1e-6)
    one = np.ones(shape, dtype=bool)
    one.flat[one.size // 2] = False
    np.testing.assert_allclose(gpugeom.distance_transform_edt(one, backend=backend),
                               ndi.distance_transform_edt(one), rtol=1e-13, atol=0)
    zeros = np.zeros(shape, dtype=np.uint8)
    assert not gpugeom.distance_transform_edt(zeros, backend=backend).any()


def test_voronoi_labels_4d(backend, rng):
    shape = (7, 6, 8, 5)
    lab = np.zeros(shape, dtype=np.int64)
    pts = rng.integers(0, shape, size=(25, 4))
    lab[tuple(pts.T)] = np.arange(1, 26)
    out, dist, site = gpugeom.voronoi_labels(lab, return_distances=True, return_sites=True,
                                             backend=backend)
    nz = np.flatnonzero(lab)
    coords = np.column_stack(np.unravel_index(nz, shape))
    grid = np.indices(shape).reshape(4, -1).T
    d2 = ((grid[:, None, :] - coords[None, :, :]) ** 2).sum(-1)
    best = d2.argmin(axis=1)
    np.testing.assert_array_equal(site.reshape(-1), nz[best])
    np.testing.assert_array_equal(out.reshape(-1), lab.reshape(-1)[nz[best]])
    np.testing.assert_allclose(dist.reshape(-1), np.sqrt(d2.min(axis=1)))


@pytest.mark.parametrize("shape", [(9, 6, 5, 7), (6, 4, 3, 5, 3)])
def test_edt_nd_slices_equal_whole(shape, backend, rng):
    a = rng.random(shape) > 0.03
    a.flat[-1] = False
    samp = [1.0 + 0.5 * k for k in range(len(shape))]
    d, i = gpugeom.distance_transform_edt(a, sampling=samp, return_indices=True, backend=backend)
    zs = [shape[0] - 1, 0, 3, 3]
    ds, js = gpugeom.distance_transform_edt(a, sampling=samp, return_indices=True, slices=zs,
                                            backend=backend)
    np.testing.assert_array_equal(ds, d[zs])
    np.testing.assert_array_equal(js, i[:, zs])
